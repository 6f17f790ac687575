"""One joint-column rule for every reader: measurement files, calibration plans, trajectories, DataFrames."""

import numpy as np
import pandas as pd
import pytest

import tolalloc
from tolalloc import TolallocError
from tolalloc.calibration import make_plan, read_plan, write_plan
from tolalloc.diagnose import generate, measurements_from_frame, read_measurements
from tolalloc.robot.columns import find_joint_columns, joint_column_names
from tolalloc.workflows.inputs import joint_values, trajectory


@pytest.fixture(scope="module")
def tc():
    return tolalloc.load_robot("tool_changer")


@pytest.fixture(scope="module")
def frame(tc):
    return generate(tc, "none", 30, np.random.default_rng(0)).frame  # columns q1..q6 (the plain alias)


def test_the_rule_accepts_unit_names_plan_names_and_the_plain_alias(tc):
    assert joint_column_names(tc) == ["q1_deg", "q2_deg", "q3_deg", "q4_mm", "q5_deg", "q6_deg"]
    assert find_joint_columns(tc, joint_column_names(tc), "f") == joint_column_names(tc)
    plan = ["j1_deg", "j2_deg", "j3_deg", "j4_mm", "j5_deg", "j6_deg"]
    assert find_joint_columns(tc, ["x_mm", *plan[::-1]], "f") == plan
    mixed = [" q1", "q2_deg_mm", "j3_deg", "q4_mm", "q5", "q6_deg", "dir1", "q1_std"]
    assert find_joint_columns(tc, mixed, "f") == ["q1", "q2_deg_mm", "j3_deg", "q4_mm", "q5", "q6_deg"]


@pytest.mark.parametrize("rename, match", [
    ({"q1": "q1_mm"}, r"^f: column 'q1_mm': joint 1 \(j1\) is revolute, its values are read in deg, not mm: name the "
                      r"column q1_deg \(with its values in deg\)\.$"),
    ({"q1": "q1_rad"}, r"column 'q1_rad': .* read in deg: convert the column to degrees \(numpy.degrees\) and name "
                       r"it q1_deg\."),
    ({"q4": "q4_m"}, r"column 'q4_m': joint 4 \(j4\) is prismatic, .* read in mm: multiply the column by 1000 and "
                     r"name it q4_mm\."),
    ({"q4": "j4_deg"}, r"column 'j4_deg': joint 4 \(j4\) is prismatic, its values are read in mm, not deg: name the "
                       r"column q4_mm"),
    ({"x": "q1_deg"}, r"joint 1 \(j1\) is given in 2 columns, 'q1', 'q1_deg'; expected one column per joint: keep one\."),
    ({"q6": "Q6"}, r"missing column\(s\) for joint\(s\) q6_deg \(j6\); .* Rename: 'Q6' -> 'q6'\."),
    ({"x": "q7"}, r"^f: the file has joint columns q1..q7 but robot 'tool_changer' has 6 joints: is it a file of "
                  r"another robot\? \(expected q1..q6\)$"),
    ({"q6": "other"}, r"missing column\(s\) for joint\(s\) q6_deg \(j6\);.* The file has joint columns q1..q5 but robot "
                      r"'tool_changer' has 6 joints: is it a file of another robot\?"),
])
def test_the_rule_refuses_with_a_hint(tc, rename, match):
    cols = [rename.get(c, c) for c in ["q1", "q2", "q3", "q4", "q5", "q6", "x"]]
    with pytest.raises(TolallocError, match=match):
        find_joint_columns(tc, cols, "f")


def test_measurement_reader_takes_the_plan_names_and_refuses_a_seventh_joint(tc, frame, tmp_path):
    ur10 = tolalloc.load_robot("ur10")
    extra = pd.DataFrame({**{f"q{k}": [0.0] * 3 for k in range(1, 8)}, "x_mm": 0.0, "y_mm": 0.0, "z_mm": 0.0})
    with pytest.raises(TolallocError, match=r"the file has joint columns q1..q7 but robot 'ur10' has 6 joints: is it a "
                                            r"file of another robot\?"):
        measurements_from_frame(extra, ur10)
    # a calibration plan filled in with tracker readings is a measurement file
    q = tc.q_from_interface(frame[[f"q{k}" for k in range(1, 7)]].to_numpy())
    path = tmp_path / "plan.csv"
    write_plan(make_plan(tc, q), tc, path)
    filled = pd.read_csv(path, comment="#").assign(x_mm=frame["x_mm"], y_mm=frame["y_mm"], z_mm=frame["z_mm"])
    head = "".join(line + "\n" for line in path.read_text().splitlines() if line.startswith("#"))
    path.write_text(head + filled.to_csv(index=False))
    m = read_measurements(path, tc)
    np.testing.assert_allclose(m.q, q, atol=1e-9)
    np.testing.assert_allclose(read_plan(path, tc).q, q, atol=1e-9)  # and still a plan
    wrong = frame.rename(columns={"q2": "q2_rad"})
    with pytest.raises(TolallocError, match="column 'q2_rad': .* convert the column to degrees"):
        measurements_from_frame(wrong, tc)


def test_plan_and_trajectory_readers_take_every_form(tc, tmp_path):
    q_deg = np.array([[10.0, 20.0, -5.0, 100.0, -10.0, 3.0], [0.0, 30.0, -10.0, 50.0, -20.0, 0.0],
                      [5.0, 10.0, -15.0, 200.0, -5.0, 1.0]])
    body = "\n".join(",".join(f"{v:g}" for v in row) for row in q_deg) + "\n"
    for header in ("q1_deg,q2_deg,q3_deg,q4_mm,q5_deg,q6_deg\n", "q1,q2,q3,q4,q5,q6\n",
                   "j1_deg,j2_deg,j3_deg,j4_mm,j5_deg,j6_deg\n", ""):
        path = tmp_path / "traj.csv"
        path.write_text(header + body)
        np.testing.assert_allclose(tc.q_to_interface(trajectory(tc, path)), q_deg, atol=1e-9)
        if header:
            path.write_text(f"# robot = tool_changer\n# n_poses = 3\n{header}{body}")
            np.testing.assert_allclose(tc.q_to_interface(read_plan(path, tc).q), q_deg, atol=1e-9)
    path.write_text("q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg\n" + body)
    with pytest.raises(tolalloc.ArgumentError, match=r"^region: '.*traj.csv': column 'q4_deg': joint 4 \(j4\) is "
                                                      r"prismatic"):
        trajectory(tc, path)
    path.write_text("# robot = tool_changer\nq1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg\n" + body)
    with pytest.raises(TolallocError, match=r"^calibration plan traj.csv: column 'q4_deg': joint 4 \(j4\) is prismatic"):
        read_plan(path, tc)
    df = pd.DataFrame(q_deg, columns=joint_column_names(tc))
    np.testing.assert_allclose(tc.q_to_interface(joint_values(tc, df)), q_deg, atol=1e-9)
    with pytest.raises(tolalloc.ArgumentError, match=r"^q_deg_mm: DataFrame: joint 1 \(j1\) is given in 2 columns"):
        joint_values(tc, df.assign(q1=0.0))
