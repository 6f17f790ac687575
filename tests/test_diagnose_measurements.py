"""Reading and validating measurement CSVs: every bad input gives a TolallocError saying what to do."""

import numpy as np
import pandas as pd
import pytest

import tolalloc
from tolalloc import TolallocError
from tolalloc.diagnose import calibrate, generate, measurements_from_frame, read_measurements


@pytest.fixture(scope="module")
def robot():
    return tolalloc.load_robot("tool_changer")


@pytest.fixture(scope="module")
def frame(robot):
    return generate(robot, "none", 80, np.random.default_rng(0)).frame


def test_reads_all_columns(tmp_path, robot, frame):
    path = tmp_path / "m.csv"
    frame.assign(extra_column="ignored").to_csv(path, index=False)
    m = read_measurements(path, robot)
    assert m.n_poses == 80 and m.n_skipped == 0
    np.testing.assert_allclose(robot.q_to_interface(m.q), frame[[f"q{j}" for j in range(1, 7)]].to_numpy())
    assert m.direction.shape == (80, 6) and m.temperature_c.shape == (80,)


def test_missing_and_misnamed_columns(robot, frame):
    with pytest.raises(TolallocError, match=r"missing column\(s\) \['z_mm'\]"):
        measurements_from_frame(frame.drop(columns="z_mm"), robot)
    with pytest.raises(TolallocError, match="'X_MM' -> 'x_mm'"):
        measurements_from_frame(frame.rename(columns={"x_mm": "X_MM"}), robot)


def test_non_numeric_cell(robot, frame):
    bad = frame.astype(object)
    bad.loc[5, "q3"] = "abc"
    with pytest.raises(TolallocError, match=r"column 'q3', row 6: expected a number, got 'abc'"):
        measurements_from_frame(bad, robot)


def test_nan_rows_are_skipped_and_counted(robot, frame):
    bad = frame.copy()
    bad.loc[[3, 10], "y_mm"] = np.nan
    m = measurements_from_frame(bad, robot)
    assert m.n_skipped == 2 and m.n_poses == 78
    assert 4 not in m.rows and 11 not in m.rows and 5 in m.rows


def test_metres_detected(robot, frame):
    bad = frame.copy()
    bad[["x_mm", "y_mm", "z_mm"]] /= 1000.0
    with pytest.raises(TolallocError, match="look like metres"):
        measurements_from_frame(bad, robot)


def test_joint_limits(robot, frame):
    bad = frame.copy()
    bad.loc[7, "q2"] = 75.0  # j2 limits [-10, 60] deg
    with pytest.raises(TolallocError, match=r"row 8: q2 \(j2\) = 75 deg is outside the joint limits \[-10, 60\]"):
        measurements_from_frame(bad, robot)


def test_radians_instead_of_degrees_is_rejected(robot, frame):
    bad = frame.copy()
    for j in (1, 2, 3, 5, 6):
        bad[f"q{j}"] = np.deg2rad(bad[f"q{j}"])
    with pytest.raises(TolallocError, match="spread"):
        measurements_from_frame(bad, robot)


def test_direction_values(robot, frame):
    bad = frame.copy()
    bad.loc[0, "dir2"] = 0.5
    with pytest.raises(TolallocError, match=r"\+1 or -1"):
        measurements_from_frame(bad, robot)


def test_too_few_poses_names_the_minimum(robot, frame):
    m = measurements_from_frame(frame.iloc[:8], robot)
    with pytest.raises(TolallocError, match=r"need at least \d+ poses"):
        calibrate(robot, m)


def test_semicolon_file(tmp_path, robot, frame):
    path = tmp_path / "semi.csv"
    frame.to_csv(path, index=False, sep=";")
    with pytest.raises(TolallocError, match="';'-separated"):
        read_measurements(path, robot)
    with pytest.raises(TolallocError, match="does not exist"):
        read_measurements(tmp_path / "nope.csv", robot)


@pytest.mark.parametrize("col, want", [("payload_g", "payload_kg"), ("time_ms", "time_s"),
                                       ("temperature_k", "temperature_c")])
def test_a_covariate_in_another_unit_is_refused_not_ignored(col, want):
    robot = tolalloc.load_robot("ur10")
    df = pd.DataFrame(np.zeros((5, 6)), columns=[f"q{i}_deg" for i in range(1, 7)])
    df[["x_mm", "y_mm", "z_mm"]] = np.arange(15.0).reshape(5, 3)
    df[col] = 1.0
    with pytest.raises(TolallocError, match=f"column '{col}': expected '{want}' .* rename it {want}"):
        measurements_from_frame(df, robot)


def test_a_payload_in_grams_or_negative_is_refused(robot, frame):
    """tool_changer's rated payload is 20 kg: 10x that is taken for grams; a robot file without a rated payload is
    held to the heaviest any serial robot carries; a negative mass is refused."""
    from dataclasses import replace

    from tolalloc.diagnose.measurements import PAYLOAD_MAX_KG

    ok = frame.assign(payload_kg=np.linspace(0.0, 190.0, len(frame)))
    assert measurements_from_frame(ok, robot).payload_kg.max() == 190.0
    grams = frame.assign(payload_kg=np.linspace(0.0, 8000.0, len(frame)))
    with pytest.raises(TolallocError, match=rf"row {len(frame)}: payload_kg = 8000 is 400 times the rated payload of "
                                            r"robot 'tool_changer', 20 kg \(components.payload.rated_kg\); a column in "
                                            "grams\\? Expected kilograms: divide the column by 1000"):
        measurements_from_frame(grams, robot)
    bare = replace(robot, components=replace(robot.components, payload=replace(robot.components.payload,
                                                                                 rated_kg=None)))
    assert measurements_from_frame(ok.assign(payload_kg=3000.0), bare).payload_kg.max() == 3000.0
    with pytest.raises(TolallocError, match=rf"is more than any serial robot carries \({PAYLOAD_MAX_KG:g} kg\)"):
        measurements_from_frame(grams, bare)
    with pytest.raises(TolallocError, match="row 3: payload_kg = -2 is negative; expected the mass the robot holds"):
        measurements_from_frame(ok.assign(payload_kg=np.r_[0.0, 0.0, -2.0, np.zeros(len(frame) - 3)]), robot)
