"""The IPA UR10 reader (tolalloc.diagnose.read_ipa_ur10): units, derived columns, bad files, the real data."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import tolalloc
from tolalloc.diagnose import read_ipa_ur10
from tolalloc.diagnose.ipa_ur10 import IPA_JOINTS, IPA_POSITION

ROOT = Path(__file__).resolve().parents[1]


def _write_ipa(path: Path, q_rad: np.ndarray, p_mm: np.ndarray, temperature=None) -> Path:
    """A file in the IPA layout: ';'-separated, decimal commas."""
    cols = list(IPA_JOINTS + IPA_POSITION) + ([] if temperature is None else ["measurement_temperature"])
    rows = [";".join(cols)]
    for i in range(len(q_rad)):
        vals = [*q_rad[i], *p_mm[i]] + ([] if temperature is None else [temperature[i]])
        rows.append(";".join(f"{v:.9f}".replace(".", ",") for v in vals))
    path.write_text("\n".join(rows) + "\n")
    return path


def test_units_and_derived_columns(tmp_path):
    q = np.array([[0.1, -1.0, 1.5, 0.0, 0.5, 3.0], [0.2, -1.0, 1.4, 0.0, 0.5, 3.0], [0.1, -0.9, 1.4, 0.0, 0.5, 3.0]])
    p = np.array([[1000.5, -20.25, 300.0], [1001.0, -20.0, 301.0], [999.0, -19.0, 299.5]])
    df = read_ipa_ur10(_write_ipa(tmp_path / "m.csv", q, p, temperature=[22.5, 22.6, 22.7]))
    assert list(df.columns) == [*(f"q{j}" for j in range(1, 7)), "x_mm", "y_mm", "z_mm", "temperature_c",
                                *(f"dir{j}" for j in range(1, 7)), "time_s"]
    np.testing.assert_allclose(df[[f"q{j}" for j in range(1, 7)]].to_numpy(), np.degrees(q), atol=1e-6)
    np.testing.assert_allclose(df[["x_mm", "y_mm", "z_mm"]].to_numpy(), p)
    np.testing.assert_allclose(df["temperature_c"], [22.5, 22.6, 22.7])
    # sign of each joint's change from the previous row, +1 when unchanged or first
    np.testing.assert_array_equal(df["dir1"], [1, 1, -1])
    np.testing.assert_array_equal(df["dir2"], [1, 1, 1])
    np.testing.assert_array_equal(df["dir3"], [1, -1, 1])
    np.testing.assert_array_equal(df["time_s"], [0.0, 1.0, 2.0])
    # the table is what the diagnosis reads (no temperature column is fine too)
    robot = tolalloc.load_robot("ur10")
    # a probe position per pose, tracker frame shifted
    p_robot = robot.fk(robot.q_to_interface(q))[:, :3, 3] + [500.0, -200.0, 50.0]
    no_temp = read_ipa_ur10(_write_ipa(tmp_path / "n.csv", q, p_robot))
    assert "temperature_c" not in no_temp.columns
    m = tolalloc.diagnose.measurements_from_frame(no_temp, robot, "n.csv")
    np.testing.assert_allclose(m.q, q, atol=1e-8)


@pytest.mark.parametrize("content, match", [
    ("a;b;c\n1;2;3\n", r"missing shoulder_pan_joint, .*Is this an IPA UR10 measurement file\?$"),
    ("", r"cannot be read as an IPA UR10 file"),
])
def test_bad_files_get_one_line(tmp_path, content, match):
    path = tmp_path / "bad.csv"
    path.write_text(content)
    with pytest.raises(tolalloc.TolallocError, match=match) as info:
        read_ipa_ur10(path)
    assert "\n" not in str(info.value)
    with pytest.raises(tolalloc.TolallocError, match="cannot be read as an IPA UR10 file"):
        read_ipa_ur10(tmp_path / "absent.csv")


def test_a_semicolon_file_given_to_the_diagnosis_names_the_reader(tmp_path):
    path = _write_ipa(tmp_path / "m.csv", np.zeros((2, 6)), np.ones((2, 3)))
    with pytest.raises(tolalloc.TolallocError, match=r"read_ipa_ur10"):
        tolalloc.diagnose.read_measurements(path, tolalloc.load_robot("ur10"))


def _data():
    for up in ROOT.parents:
        if (up / "shared" / "data" / "ipa-ur10").is_dir():
            return up / "shared" / "data" / "ipa-ur10"
    return None


@pytest.mark.skipif(_data() is None,
                    reason="the UR10 data folder shared/data/ipa-ur10 is absent (read-only shared data)")
def test_real_series_c_reads_inside_the_ur10_limits():
    df = read_ipa_ur10(_data() / "Series_C" / "measurements_random_poses.csv")
    assert len(df) == 2773 and not df.isna().any().any()
    robot = tolalloc.load_robot("ur10")
    q = robot.q_from_interface(df[[f"q{j}" for j in range(1, 7)]].to_numpy())
    assert np.all(q >= robot.lower - 1e-9) and np.all(q <= robot.upper + 1e-9)
    # probe positions within the reach of a UR10 (1.3 m) of the tracker origin's neighbourhood: mm, not m
    assert 100.0 < np.ptp(df["x_mm"]) < 3000.0
