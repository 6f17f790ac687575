"""Robot files (TOML): built-ins, units, and every bad-input case with its message."""

from __future__ import annotations

import re
import textwrap

import numpy as np
import pytest

from tolalloc import TolallocError, builtin_robots, load_robot
from tolalloc.robot.lie import rot_x, rot_y, rot_z
from tolalloc.robot.io import robot_from_dict

BASE = textwrap.dedent("""\
    name = "two"
    description = "a two-joint test arm"
    [[chain]]
    link = "l1"
    vector_mm = [0, 0, 100]
    [[chain]]
    joint = "j1"
    type = "revolute"
    axis = [0, 0, 1]
    limits_deg = [-90, 90]
    nominal_deg = 10
    [[chain]]
    link = "l2"
    vector_mm = [100, 0, 0]
    [[chain]]
    joint = "j2"
    type = "prismatic"
    axis = [1, 0, 0]
    limits_mm = [0, 200]
    [tool]
    offset_mm = [0, 0, -20]
    rpy_deg = [10, 20, 30]
    """)


def write(tmp_path, text, name="robot.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_builtin_robots_listed_and_loadable():
    robots = builtin_robots()
    assert {"tool_changer", "ur10"} <= set(robots)
    assert all(isinstance(d, str) and d for d in robots.values())
    for name in robots:
        r = load_robot(name)
        assert r.name == name
        assert r.n_joints == 6


def test_tool_changer_file_content():
    r = load_robot("tool_changer")
    assert set(r.sigma_sets) == {"table1", "table2"}
    assert [m.name for m in r.masses] == ["l3", "l4", "l5", "l6"]
    assert [m.body for m in r.masses] == [2, 3, 4, 5]
    np.testing.assert_allclose(r.gravity, [0, 0, -1])
    assert "working" in r.pose_sets


def test_chain_file_units_and_tool(tmp_path):
    r = load_robot(write(tmp_path, BASE))
    assert r.name == "two" and r.description == "a two-joint test arm"
    assert r.joints[0].nominal == pytest.approx(np.deg2rad(10))
    assert (r.joints[0].lower, r.joints[0].upper) == pytest.approx((-np.pi / 2, np.pi / 2))
    assert (r.joints[1].lower, r.joints[1].upper) == (0.0, 200.0)
    np.testing.assert_allclose(r.home[:3, 3], [100, 0, 80])
    d = np.deg2rad
    np.testing.assert_allclose(r.home[:3, :3], rot_z(d(30)) @ rot_y(d(20)) @ rot_x(d(10)), atol=1e-15)
    # metres and radians give the same robot
    alt = (BASE.replace("vector_mm = [100, 0, 0]", "vector_m = [0.1, 0, 0]")
           .replace("limits_deg = [-90, 90]", f"limits_rad = [{-np.pi / 2!r}, {np.pi / 2!r}]")
           .replace("offset_mm = [0, 0, -20]", "offset_m = [0, 0, -0.02]"))
    r2 = load_robot(write(tmp_path, alt, "alt.toml"))
    np.testing.assert_allclose(r2.home, r.home, atol=1e-12)
    np.testing.assert_allclose(r2.screws, r.screws, atol=1e-12)
    np.testing.assert_allclose(r2.lower, r.lower)


def test_masses_gravity_pose_sets(tmp_path):
    # gravity is a top-level key: it must come before the tables; it is normalised on load
    text = BASE.replace('description = "a two-joint test arm"\n', 'description = "a two-joint test arm"\ngravity = [0, -2, 0]\n')
    text += textwrap.dedent("""\
        [[masses]]
        link = "l2"
        mass_kg = 3.5
        com_m = [0.05, 0, 0.1]
        [pose_sets.work]
        q_deg_mm = [[0, 0], [45, 150]]
        """)
    r = load_robot(write(tmp_path, text))
    np.testing.assert_allclose(r.gravity, [0, -1, 0])
    (m,) = r.masses
    assert (m.name, m.body, m.mass_kg) == ("l2", 1, 3.5)
    np.testing.assert_allclose(m.com_mm, [50, 0, 100])
    np.testing.assert_allclose(r.poses("work"), [[0, 0], [np.pi / 4, 150]])


def test_robot_from_dict_matches_file(tmp_path):
    import tomllib

    r1 = load_robot(write(tmp_path, BASE))
    r2 = robot_from_dict(tomllib.loads(BASE))
    np.testing.assert_allclose(r1.home, r2.home)


BAD_CASES = [
    # (substitution old -> new, regex the message must match)
    ("axis = [0, 0, 1]", "axis = [0, 0, 0]", r"chain\[1\]\.axis: axis is the zero vector; expected a unit vector"),
    ("axis = [0, 0, 1]", "axis = [0, nan, 1]", r"chain\[1\]\.axis: axis must be finite"),
    ("axis = [0, 0, 1]", "axis = [0, inf, 1]", r"chain\[1\]\.axis: axis must be finite"),
    ("axis = [0, 0, 1]", "axis = [0, 1, 1]", r"chain\[1\]\.axis: .*norm 1\.41421; expected a unit vector"),
    ("axis = [0, 0, 1]", "axis = [0, 1]", r"chain\[1\]\.axis"),
    ("vector_mm = [0, 0, 100]", "vector_in = [0, 0, 100]", r"chain\[0\]: unknown unit 'in' in key 'vector_in'; expected vector_mm or vector_m"),
    ("limits_mm = [0, 200]", "limits_deg = [0, 200]", r"chain\[3\] \(j2\): key 'limits_deg' has unit 'deg'; expected limits_mm or limits_m"),
    ("offset_mm = [0, 0, -20]", "offset_ft = [0, 0, -20]", r"tool: unknown unit 'ft' in key 'offset_ft'; expected offset_mm or offset_m"),
    ('axis = [0, 0, 1]\n', "", r"chain\[1\]\.axis: Field required"),
    ('type = "prismatic"\n', "", r"chain\[3\]\.type: Field required"),
    ('name = "two"\n', "", r"name: Field required"),
    ("vector_mm = [100, 0, 0]\n", "", r"chain\[2\] \(l2\): missing vector_mm"),
    ('type = "revolute"', 'type = "spherical"', r"chain\[1\]\.type: Input should be 'revolute', 'prismatic' or 'continuous'"),
    ("nominal_deg = 10", "nominal_deg = 100", r"chain\[1\] \(j1\): nominal value 100(\.0)? deg lies outside the joint limits \[-90(\.0)?, 90(\.0)?\] deg"),
    ("limits_deg = [-90, 90]", "limits_deg = [90, -90]", r"chain\[1\] \(j1\): limits must be \[lower, upper\] with lower < upper"),
    ('link = "l2"', 'link = "l1"', r"duplicate element names \['l1'\]"),
    ('link = "l2"', 'link = "l2"\njoint = "x"', r"chain\[2\]: expected either a 'link' or a 'joint' key"),
    ('name = "two"', 'name = "two"\ncolour = "red"', r"colour: Extra inputs are not permitted"),
    ("vector_mm = [100, 0, 0]", "vector_mm = [100, 0]", r"chain\[2\] \(l2\): vector must be 3 finite numbers"),
    ('name = "two"', 'name = "two', r"not valid TOML \(.*line 1.*\); see docs/howto/own-robot.md for the robot file format"),
    ('name = "two"', 'name = "two"\ngravity = [0, 0, 0]', r"gravity: expected a non-zero direction"),
]


@pytest.mark.parametrize("old,new,match", BAD_CASES, ids=[c[2][:40] for c in BAD_CASES])
def test_bad_robot_file(tmp_path, old, new, match):
    assert old in BASE
    path = write(tmp_path, BASE.replace(old, new, 1), "bad_robot.toml")
    with pytest.raises(TolallocError, match=match) as info:
        load_robot(path)
    # the message names the file
    assert str(info.value).startswith(f"robot file {str(path)!r}: ")


@pytest.mark.parametrize("extra,match", [
    ('[[masses]]\nlink = "l9"\nmass_kg = 1\ncom_mm = [0, 0, 0]\n', r"masses\[0\]\.link: 'l9' is not a link of the chain"),
    ('[[masses]]\nlink = "l1"\nmass_kg = -1\ncom_mm = [0, 0, 0]\n', r"masses\[0\]: expected mass_kg >= 0 and com_mm"),
    ('[[masses]]\nlink = "l1"\nmass_kg = 1\n', r"masses\[0\]: expected mass_kg >= 0 and com_mm"),
    ('[[masses]]\nlink = "l1"\nmass_kg = 1\ncom_in = [0, 0, 0]\n', r"masses\[0\]: unknown unit 'in' in key 'com_in'"),
    ("[pose_sets.w]\nq_deg_mm = [[0, 300]]\n", r"pose_sets\.w\.q_deg_mm \(pose 1\): joint j2 = 300 mm is outside its limits \[0, 200\] mm"),
    ("[pose_sets.w]\nq_deg_mm = [[0, 1, 2]]\n", r"pose_sets\.w\.q_deg_mm: robot 'two' has 2 joints \(j1, j2\); expected 2 values \(deg, mm\), got 3"),
    ("[pose_sets.w]\nq_deg = [[0, 1]]\n", r"pose_sets\.w: expected one key 'q_deg_mm'"),
])
def test_bad_masses_and_pose_sets(tmp_path, extra, match):
    path = write(tmp_path, BASE + extra, "bad_extra.toml")
    with pytest.raises(TolallocError, match=match) as info:
        load_robot(path)
    assert "bad_extra.toml" in str(info.value)


def test_unknown_robot_and_missing_file(tmp_path):
    with pytest.raises(TolallocError, match=r"robot 'nonsense': not a built-in robot \(.*tool_changer.*\) and no such file"):
        load_robot("nonsense")
    with pytest.raises(TolallocError, match=re.escape(str(tmp_path / "none.toml")) + ".*no such file"):
        load_robot(tmp_path / "none.toml")


def test_unreadable_file(tmp_path):
    path = tmp_path / "binary.toml"
    path.write_bytes(b"\x00\xff\xfe")
    with pytest.raises(TolallocError, match=r"binary\.toml': cannot be read as text .*expected a TOML robot file"):
        load_robot(path)


def test_tool_option_only_for_urdf(tmp_path):
    with pytest.raises(TolallocError, match=r"^`tool` 'x': the tool link can only be chosen for a URDF robot file"):
        load_robot("tool_changer", tool="x")
    with pytest.raises(TolallocError, match=r"got robot 'tool_changer'"):
        load_robot(load_robot("tool_changer"), tool="x")


@pytest.mark.parametrize("rows", ["[[0, 1], [2]]", "[['a', 1]]"])
def test_ragged_or_non_numeric_pose_set_is_a_clear_error(tmp_path, rows):
    # regression: a ragged or non-numeric q_deg_mm gave a numpy ValueError traceback
    path = write(tmp_path, BASE + f"[pose_sets.w]\nq_deg_mm = {rows}\n", "ragged.toml")
    with pytest.raises(TolallocError, match=r"ragged\.toml.*pose_sets\.w\.q_deg_mm: expected rows of 2 numbers"):
        load_robot(path)
