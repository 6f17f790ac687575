"""Input guards of issue 12 that accept what is right: byte-order marks, --trust-units, an explicit --tool,
random poses within limits, and the unit-plausibility rules on their boundaries."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from tolalloc import TolallocError, load_robot
from tolalloc.cli import main
from tolalloc.diagnose.measurements import check_train_test, measurements_from_frame, read_measurements
from tolalloc.robot.model import Joint, Link, Robot
from tolalloc.units import MAX_PLAUSIBLE_M, check_plausible, trusting_units, unit_value

BOM = "\ufeff"
ROBOT = """name = "t"
[[chain]]
joint = "j1"
type = "revolute"
axis = [0, 0, 1]
limits_deg = [-170, 170]
[[chain]]
link = "l1"
vector_VEC
"""


def test_byte_order_mark_is_accepted_in_toml_dh_csv_and_measurements(tmp_path, capsys):
    (tmp_path / "r.toml").write_text(BOM + ROBOT.replace("VEC", "mm = [0, 0, 400]"), encoding="utf-8")
    plain = load_robot(str(tmp_path / "r.toml"))
    assert plain.home[:3, 3].tolist() == [0.0, 0.0, 400.0]
    (tmp_path / "d.csv").write_text(BOM + "# convention: standard\nname,d_mm,a_mm,alpha_deg\nq1,400,0,90\nq2,0,300,0\n",
                                    encoding="utf-8")
    dh = load_robot(str(tmp_path / "d.csv"))
    assert np.allclose(dh.home[:3, 3], [300.0, 0.0, 400.0])
    robot = load_robot("tool_changer")
    from tolalloc.diagnose import generate

    frame = generate(robot, "none", 20, np.random.default_rng(1)).frame
    (tmp_path / "m.csv").write_text(BOM + frame.to_csv(index=False), encoding="utf-8")
    m = read_measurements(tmp_path / "m.csv", robot)
    assert m.n_poses == 20 and np.allclose(m.xyz_mm, frame[["x_mm", "y_mm", "z_mm"]].to_numpy())
    (tmp_path / "c.toml").write_text(BOM + "z = 3\n", encoding="utf-8")
    assert main(["allocate", "tool_changer", "--no-verify", "--costs", str(tmp_path / "c.toml"), "--solver",
                 "certified"]) == 0


def test_trust_units_accepts_what_the_guard_refuses(tmp_path, capsys):
    path = tmp_path / "big.toml"
    path.write_text(ROBOT.replace("VEC", "m = [0, 0, 25]"))  # a 25 m link
    assert main(["show", str(path)]) == 2
    assert "looks like millimetres" in capsys.readouterr().err
    assert main(["show", str(path), "--trust-units"]) == 0
    assert "25000" in capsys.readouterr().out


@pytest.mark.parametrize("raw, unit, bad", [
    (MAX_PLAUSIBLE_M, "m", False), (MAX_PLAUSIBLE_M + 0.1, "m", True),
    ([-360, 360], "deg", False), ([-360.5, 0], "deg", True),
    (2 * np.pi, "rad", False), (6.3, "rad", True), (1e6, "mm", False),
])
def test_plausibility_boundaries(raw, unit, bad):
    if bad:
        with pytest.raises(ValueError, match="--trust-units"):
            check_plausible(raw, f"x_{unit}", unit)
        with trusting_units():
            check_plausible(raw, f"x_{unit}", unit)
    else:
        check_plausible(raw, f"x_{unit}", unit)


def test_unit_value_converts_and_refuses_doubles():
    assert unit_value({"vector_m": [0.5, 0, 0]}, "vector", {"mm": 1.0, "m": 1000.0}) == (pytest.approx([500, 0, 0]), "m")
    with pytest.raises(ValueError, match="give vector once"):
        unit_value({"vector_m": [1, 0, 0], "vector_mm": [1, 0, 0]}, "vector", {"mm": 1.0, "m": 1000.0})
    with pytest.raises(ValueError, match="expected numbers, got"):
        unit_value({"vector_mm": [1, "x", 0]}, "vector", {"mm": 1.0, "m": 1000.0})


def test_urdf_finger_is_taken_when_named(tmp_path):
    from test_bad_input_table import URDF_BRANCH

    path = tmp_path / "b.urdf"
    path.write_text(URDF_BRANCH)
    tool0 = load_robot(str(path), tool="tool0")
    finger = load_robot(str(path), tool="finger")
    assert tool0.n_joints == 2 and finger.n_joints == 3
    assert np.allclose(tool0.home[:3, 3], [300.0, 0.0, 700.0])
    assert np.allclose(finger.home[:3, 3], [300.0, 0.0, 720.0])


def test_robot_refuses_nan_tool_and_nominal():
    chain = (Joint("j1", "revolute", np.array([0.0, 0, 1])), Link("l1", np.array([100.0, 0, 0])))
    with pytest.raises(TolallocError, match="tool offset .* expected 3 finite numbers"):
        Robot("r", chain, tool_offset_mm=np.array([np.nan, 0, 0]))
    with pytest.raises(TolallocError, match=r"^joint j1: expected a finite nominal value inside the limits \[rad\], "
                                            r"got nan\.$"):
        Joint("j1", "revolute", np.array([0.0, 0, 1]), nominal=np.nan)  # refused by the joint itself


def test_random_q_stays_within_limits_per_joint_type():
    robot = load_robot("tool_changer")
    q = robot.random_q(np.random.default_rng(0), 20000)
    assert q.shape == (20000, 6)
    assert np.all(q >= robot.lower) and np.all(q <= robot.upper)
    # uniform: each joint's sample mean within 4 standard errors of the interval's midpoint
    mid, half = (robot.lower + robot.upper) / 2, (robot.upper - robot.lower) / 2
    se = half / np.sqrt(3) / np.sqrt(len(q))
    assert np.all(np.abs(q.mean(axis=0) - mid) < 4 * se)
    j4 = robot.joints.index(next(j for j in robot.joints if j.kind == "prismatic"))
    assert q[:, j4].max() > 400.0  # the prismatic stroke (0-500 mm) is not clipped to +-pi


def test_train_and_test_sharing_poses_is_refused(tmp_path):
    robot = load_robot("tool_changer")
    from tolalloc.diagnose import generate

    frame = generate(robot, "none", 30, np.random.default_rng(2)).frame
    train = measurements_from_frame(frame.iloc[:20], robot, "train")
    test = measurements_from_frame(frame.iloc[20:], robot, "test")
    check_train_test(train, test, str(tmp_path / "a.csv"), str(tmp_path / "b.csv"))  # disjoint: fine
    shared = measurements_from_frame(pd.concat([frame.iloc[20:], frame.iloc[[4, 7]]]), robot, "test")
    with pytest.raises(TolallocError, match=r"^`test` '.*b.csv': 2 of its 12 poses are also in `train`"):
        check_train_test(train, shared, str(tmp_path / "a.csv"), str(tmp_path / "b.csv"))


def test_repeated_pose_with_another_reading_is_kept_but_an_exact_copy_is_not():
    robot = load_robot("tool_changer")
    from tolalloc.diagnose import generate

    frame = generate(robot, "none", 20, np.random.default_rng(4)).frame
    again = frame.iloc[[3]].copy()
    again["x_mm"] += 0.01  # the same pose measured twice: a legitimate repeat
    assert measurements_from_frame(pd.concat([frame, again]), robot).n_poses == 21
    with pytest.raises(TolallocError, match="row 21 repeats row 4 exactly"):
        measurements_from_frame(pd.concat([frame, frame.iloc[[3]]]), robot)


def test_duplicate_rows_found_by_hash_match_a_direct_comparison():
    from tolalloc.diagnose.measurements import _duplicated

    rng = np.random.default_rng(7)
    A = rng.integers(0, 3, size=(400, 3)).astype(float)  # many repeats
    direct = np.array([any((A[i] == A[j]).all() for i in range(j)) for j in range(len(A))])
    assert np.array_equal(_duplicated(A), direct)
    assert _duplicated(A).sum() == len(A) - len(np.unique(A, axis=0))


def test_pose_groups_join_repeats_of_one_pose():
    robot = load_robot("tool_changer")
    from tolalloc.diagnose import generate

    frame = generate(robot, "none", 6, np.random.default_rng(5)).frame
    again = frame.iloc[[4, 1]].copy()
    again["z_mm"] += 0.02
    m = measurements_from_frame(pd.concat([frame, again]), robot)
    assert m.pose_groups().tolist() == [0, 1, 2, 3, 4, 5, 4, 1]


def test_random_q_of_a_multi_turn_joint_stays_within_one_turn():
    chain = (Joint("j1", "revolute", np.array([0.0, 0, 1]), -4 * np.pi, 4 * np.pi), Link("l1", np.array([100.0, 0, 0])),
             Joint("j2", "prismatic", np.array([1.0, 0, 0]), 0.0, 800.0))
    q = Robot("r", chain).random_q(np.random.default_rng(1), 5000)
    assert q[:, 0].min() >= -np.pi and q[:, 0].max() <= np.pi and q[:, 0].min() < -3.0 and q[:, 0].max() > 3.0
    assert q[:, 1].min() >= 0.0 and q[:, 1].max() > 790.0


def test_dh_table_with_small_calibrated_offset_is_accepted_but_chain_link_is_not():
    """A calibrated DH table holds sub-mm offsets (a1 = 0.3 mm on a UR10); a 0.3 mm chain link among metre-long
    ones is a unit slip."""
    import tomllib
    from importlib.resources import files

    from tolalloc.robot.io import robot_from_dict

    data = tomllib.loads((files("tolalloc") / "data/robots/ur10.toml").read_text())
    data["dh"][0]["a_m"] = 0.0003
    robot = robot_from_dict(data)
    assert any(link.name == "a1" for link in robot.links)
    chain = {"name": "x", "chain": [{"link": "base", "vector_mm": [0, 0, 400]},
                                    {"joint": "j1", "type": "revolute", "axis": [0, 0, 1], "limits_deg": [-90, 90]},
                                    {"link": "tiny", "vector_mm": [0.3, 0, 0]},
                                    {"link": "arm", "vector_mm": [600, 0, 0]}]}
    with pytest.raises(TolallocError, match="looks like a length in metres"):
        robot_from_dict(chain)
