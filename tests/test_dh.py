"""DH tables (standard and modified) -> POE chain, checked against direct composition of the DH transforms."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import twist_fd

from tolalloc import TolallocError, load_robot
from tolalloc.robot.io.dh import chain_from_dh
from tolalloc.robot.lie import rot_x, rot_z, transform
from tolalloc.robot.model import Robot
from tolalloc.robot.io import robot_from_dict

UR10_DH = dict(  # ../shared/data/ipa-ur10/README.md, metres and rad
    d=[0.1273, 0, 0, 0.163941, 0.1157, 0.0922],
    a=[0, -0.612, -0.5723, 0, 0, 0],
    alpha=[np.pi / 2, 0, 0, np.pi / 2, -np.pi / 2, 0],
)


def Tz(d):
    return transform(None, [0, 0, d])


def Tx(a):
    return transform(None, [a, 0, 0])


def Rz(t):
    return transform(rot_z(t))


def Rx(t):
    return transform(rot_x(t))


def standard_dh_fk(q, d, a, alpha, theta0, prismatic=None):
    prismatic = prismatic or [False] * len(q)
    T = np.eye(4)
    for qi, di, ai, al, th, pr in zip(q, d, a, alpha, theta0, prismatic):
        T = T @ Rz(th + (0 if pr else qi)) @ Tz(di + (qi if pr else 0)) @ Tx(ai) @ Rx(al)
    return T


def modified_dh_fk(q, d, a, alpha, theta0, prismatic=None):
    """Craig: T_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i); row i holds alpha_{i-1}, a_{i-1}."""
    prismatic = prismatic or [False] * len(q)
    T = np.eye(4)
    for qi, di, ai, al, th, pr in zip(q, d, a, alpha, theta0, prismatic):
        T = T @ Rx(al) @ Tx(ai) @ Rz(th + (0 if pr else qi)) @ Tz(di + (qi if pr else 0))
    return T


def test_ur10_matches_standard_dh_table():
    robot = load_robot("ur10")
    assert [lk.name for lk in robot.links] == ["d1", "a2", "a3", "d4", "d5", "d6"]
    rng = np.random.default_rng(7)
    d = 1000 * np.array(UR10_DH["d"])
    a = 1000 * np.array(UR10_DH["a"])
    for q in rng.uniform(-np.pi, np.pi, (20, 6)):
        T_dh = standard_dh_fk(q, d, a, UR10_DH["alpha"], np.zeros(6))
        T = robot.fk_internal(q)
        np.testing.assert_allclose(T[:3, 3], T_dh[:3, 3], atol=1e-9)
        np.testing.assert_allclose(T[:3, :3], T_dh[:3, :3], atol=1e-12)
    # batched evaluation agrees too
    Q = rng.uniform(-np.pi, np.pi, (5, 6))
    np.testing.assert_allclose(robot.fk_internal(Q), [standard_dh_fk(q, d, a, UR10_DH["alpha"], np.zeros(6)) for q in Q], atol=1e-9)


def test_ur10_home_and_nominal():
    robot = load_robot("ur10")
    # zero configuration: the arm stretched along -x; flange at (a2+a3, -(d4+d6), d1-d5)
    np.testing.assert_allclose(robot.home[:3, 3], [-1184.3, -256.141, 11.6], atol=1e-9)
    np.testing.assert_allclose(robot.q_to_interface(robot.q_nominal), [0, -90, 0, -90, 0, 0], atol=1e-12)


@pytest.mark.parametrize("seed", range(3))
def test_ur10_jacobians_match_finite_differences(seed):
    robot = load_robot("ur10")
    q = np.random.default_rng(seed).uniform(-np.pi, np.pi, 6)
    for frame, J in (("space", robot.space_jacobian_internal(q)), ("body", robot.body_jacobian_internal(q))):
        np.testing.assert_allclose(J, twist_fd(robot.fk_internal, q, h=1e-6, frame=frame), atol=2e-5 * np.abs(J).max())


def random_dh_rows(rng, n, prismatic_every=0):
    rows = []
    for i in range(n):
        pr = prismatic_every and i % prismatic_every == prismatic_every - 1
        rows.append(dict(name=f"j{i + 1}", type="prismatic" if pr else "revolute",
                         d=float(rng.uniform(-300, 300)), a=float(rng.uniform(-300, 300)),
                         alpha=float(rng.uniform(-np.pi, np.pi)), theta_offset=float(rng.uniform(-np.pi, np.pi)),
                         lower=-np.inf, upper=np.inf, nominal=0.0))  # no limits
    return rows


@pytest.mark.parametrize("convention,reference", [("standard", standard_dh_fk), ("modified", modified_dh_fk)])
@pytest.mark.parametrize("seed", range(4))
def test_random_dh_tables(convention, reference, seed):
    rng = np.random.default_rng(seed)
    n = 6
    rows = random_dh_rows(rng, n, prismatic_every=3 if seed % 2 else 0)
    chain, R_last = chain_from_dh(rows, convention)
    robot = Robot("dh", tuple(chain), tool_rotation=R_last)
    cols = [np.array([r[k] for r in rows]) for k in ("d", "a", "alpha", "theta_offset")]
    pr = [r["type"] == "prismatic" for r in rows]
    for q in rng.uniform(-np.pi, np.pi, (5, n)) * np.where(pr, 100, 1):
        np.testing.assert_allclose(robot.fk_internal(q), reference(q, *cols, prismatic=pr), atol=1e-9)


def _dh_file(convention, rows_toml, tool=""):
    return f'name = "dh_arm"\nconvention = "{convention}"\n{rows_toml}{tool}'


ROWS_TOML = """
[[dh]]
name = "q1"
d_mm = 400
a_mm = 25
alpha_deg = -90
[[dh]]
name = "q2"
a_m = 0.455
theta_offset_deg = -90
[[dh]]
name = "q3"
type = "prismatic"
d_mm = 35
limits_mm = [0, 300]
nominal_mm = 50
"""


@pytest.mark.parametrize("convention,reference", [("standard", standard_dh_fk), ("modified", modified_dh_fk)])
def test_dh_toml_file_with_tool(tmp_path, convention, reference):
    tool = "\n[tool]\noffset_mm = [10, 20, 30]\nrpy_deg = [0, 0, 90]\n"
    path = tmp_path / "arm.toml"
    path.write_text(_dh_file(convention, ROWS_TOML, tool))
    robot = load_robot(path)
    assert [j.kind for j in robot.joints] == ["revolute", "revolute", "prismatic"]
    assert robot.q_nominal[2] == 50.0 and robot.upper[2] == 300.0
    d, a = [400, 0, 35], [25, 455, 0]
    alpha, th0 = np.deg2rad([-90, 0, 0]), np.deg2rad([0, -90, 0])
    T_tool = transform(rot_z(np.pi / 2), [10, 20, 30])  # the tool is given in the last DH frame
    rng = np.random.default_rng(1)
    for q in np.c_[rng.uniform(-3, 3, (4, 2)), rng.uniform(0, 300, 4)]:
        np.testing.assert_allclose(robot.fk_internal(q), reference(q, d, a, alpha, th0, prismatic=[0, 0, 1]) @ T_tool, atol=1e-9)
    names = [lk.name for lk in robot.links]
    assert names == (["d1", "a1", "a2", "d3_offset"] if convention == "standard" else ["a0", "d1", "a1", "d3_offset"])
    # the prismatic offset's length error does not clash with the drive error dd3
    from tolalloc.errormodel import build_error_model

    model = build_error_model(robot)
    assert "dd3" in model.names and "dd3_offset" in model.names


UR10_CSV = """# convention: standard
# name: ur10_csv
# description: the UR10 of the shared README as a CSV DH table
name, d_m, a_m, alpha_rad, lower_deg_mm, upper_deg_mm, nominal_deg_mm
shoulder_pan_joint, 0.1273, 0, 1.5707963267948966, -360, 360,
shoulder_lift_joint, 0, -0.612, 0, -360, 360, -90
elbow_joint, 0, -0.5723, 0, -360, 360,
wrist_1_joint, 0.163941, 0, 1.5707963267948966, -360, 360, -90
wrist_2_joint, 0.1157, 0, -1.5707963267948966, -360, 360,
wrist_3_joint, 0.0922, 0, 0, -360, 360,
"""


def test_dh_csv_equals_toml(tmp_path):
    path = tmp_path / "ur10.csv"
    path.write_text(UR10_CSV)
    csv_robot = load_robot(path)
    ref = load_robot("ur10")
    assert csv_robot.name == "ur10_csv" and "CSV DH" in csv_robot.description
    np.testing.assert_allclose(csv_robot.screws, ref.screws, atol=1e-12)
    np.testing.assert_allclose(csv_robot.home, ref.home, atol=1e-12)
    np.testing.assert_allclose(csv_robot.q_nominal, ref.q_nominal)
    np.testing.assert_allclose(csv_robot.lower, ref.lower)


def test_dh_csv_modified_prismatic(tmp_path):
    path = tmp_path / "scara.csv"
    path.write_text("# convention: modified\nname,type,d_mm,a_mm,alpha_deg,lower_deg_mm,upper_deg_mm\n"
                    "q1,,400,0,0,-170,170\nq2,revolute,0,325,0,,\nq3,prismatic,20,275,180,0,200\n")
    robot = load_robot(path)
    assert robot.name == "scara" and [j.kind for j in robot.joints] == ["revolute", "revolute", "prismatic"]
    assert robot.upper[2] == 200.0 and robot.upper[0] == pytest.approx(np.deg2rad(170))
    q = np.array([0.3, -0.5, 50.0])
    ref = modified_dh_fk(q, [400, 0, 20], [0, 325, 275], np.deg2rad([0, 0, 180]), np.zeros(3), prismatic=[0, 0, 1])
    np.testing.assert_allclose(robot.fk_internal(q), ref, atol=1e-9)


@pytest.mark.parametrize("text,match", [
    ("name,d_mm\nq1,100\n", r"expected a comment line '# convention: standard'"),
    ("# convention: craig\nname,d_mm\nq1,100\n", r"got convention 'craig'"),
    ("# convention: standard\nname,d_in\nq1,100\n", r"header \['name', 'd_in'\].*unknown: \['d_in'\]"),
    ("# convention: standard\nname,d_mm,alpha_deg\nq1,abc,0\n", r"dh\[0\] \(q1\): d_mm: expected a number, got 'abc'; expected numbers in the unit of the column name"),
    ("# convention: standard\nname,d_mm,lower_deg_mm,alpha_deg\nq1,1,5,0\n", r"dh\[0\] \(q1\): give both lower_deg_mm and upper_deg_mm"),
    ("# convention: standard\nname,type,alpha_deg\nq1,ball,0\n", r"dh\[0\]: type must be 'revolute', 'prismatic' or 'continuous'"),
])
def test_bad_dh_csv(tmp_path, text, match):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(TolallocError, match=match) as info:
        load_robot(path)
    assert str(info.value).startswith(f"DH CSV file {str(path)!r}")


@pytest.mark.parametrize("row,match", [
    ('[[dh]]\nname = "q1"\nd_in = 3\n', r"dh\[0\]: unknown key 'd_in'"),
    ('[[dh]]\nname = "q1"\nalpha_grad = 3\n', r"dh\[0\]: unknown key 'alpha_grad'"),
    ('[[dh]]\nname = "q1"\nalpha_mm = 3\n', r"dh\[0\]: key 'alpha_mm' has unit 'mm'; expected alpha_deg or alpha_rad"),
    ('[[dh]]\nname = "q1"\ntype = "ball"\n', r"dh\[0\]: type must be 'revolute', 'prismatic' or 'continuous'"),
    ('[[dh]]\nname = "q1"\nd_mm = 3\nd_m = 0.003\n', r"dh\[0\]: give d once"),
])
def test_bad_dh_rows(tmp_path, row, match):
    path = tmp_path / "bad_dh.toml"
    path.write_text(_dh_file("standard", row))
    with pytest.raises(TolallocError, match=match) as info:
        load_robot(path)
    assert "bad_dh.toml" in str(info.value)


def test_bad_dh_convention():
    with pytest.raises(TolallocError, match=r"convention: Input should be 'standard' or 'modified'"):
        robot_from_dict({"name": "x", "convention": "craig", "dh": [{"name": "a"}]})


@pytest.mark.parametrize("row, match", [
    # regressions: these were accepted (a NaN link, inverted limits, a nominal pose outside the limits)
    ("q1,nan,0,-10,10,0", r"dh\[0\]: d must be one finite number, got nan"),
    ("q1,100,0,10,-10,0", r"dh\[0\]: limits must be \[lower, upper\] with lower < upper, got \[10\.0, -10\.0\] deg"),
    ("q1,100,0,-10,10,50", r"dh\[0\]: nominal value 50\.0 deg lies outside the joint limits \[-10\.0, 10\.0\] deg"),
])
def test_dh_csv_values_are_checked(tmp_path, row, match):
    path = tmp_path / "bad.csv"
    path.write_text(f"# convention: standard\nname,d_mm,a_mm,lower_deg_mm,upper_deg_mm,nominal_deg_mm,alpha_deg\n{row},0\n")
    with pytest.raises(TolallocError, match=match):
        load_robot(path)


def test_dh_csv_that_is_not_text(tmp_path):
    # regression: a binary file gave a UnicodeDecodeError traceback
    path = tmp_path / "bin.csv"
    path.write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(TolallocError, match=r"DH CSV file .*bin\.csv.*cannot be read as text"):
        load_robot(path)
