"""URDF import: Pinocchio on the UR5 and Panda of example-robot-data and on random URDFs; bad input."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from tolalloc import TolallocError, load_robot
from tolalloc.cli import main
from tolalloc.robot.io.urdf import load_urdf

pin = pytest.importorskip("pinocchio")  # a test dependency (`pin`); skip reason: Pinocchio not installed


def _erd_dir() -> Path | None:
    """The robots/ folder of the example-robot-data package (installed as a cmeel package)."""
    import site
    import sys

    for base in [*site.getsitepackages(), *sys.path]:
        cand = Path(base) / "cmeel.prefix" / "share" / "example-robot-data" / "robots"
        if cand.is_dir():
            return cand
    return None


ERD = _erd_dir()
needs_erd = pytest.mark.skipif(ERD is None, reason="example-robot-data (test extra) is not installed")
UR5 = "ur_description/urdf/ur5_robot.urdf"
PANDA = "panda_description/urdf/panda.urdf"


def compare_with_pinocchio(robot, urdf_path, tool, rng, n_q=5):
    """FK and space/body Jacobians of ``robot`` against Pinocchio's URDF model, to 1e-9."""
    model = pin.buildModelFromUrdf(str(urdf_path))
    data = model.createData()
    fid = model.getFrameId(tool)
    assert fid < model.nframes, tool
    jids = [model.getJointId(j.name) for j in robot.joints]
    assert all(j < model.njoints for j in jids)
    worst = 0.0
    for _ in range(n_q):
        q = rng.uniform(robot.lower, robot.upper) if np.all(np.isfinite(robot.upper)) else None
        q = np.where(robot.revolute_mask, np.clip(q, -2 * np.pi, 2 * np.pi), q)
        qp = pin.neutral(model)
        cols = []
        for jid, joint, value in zip(jids, robot.joints, q):
            jm = model.joints[jid]
            if jm.nq == 2:  # continuous joint: (cos, sin)
                qp[jm.idx_q:jm.idx_q + 2] = np.cos(value), np.sin(value)
            else:
                qp[jm.idx_q] = value if joint.is_revolute else value / 1000.0
            cols.append(jm.idx_v)
        pin.computeJointJacobians(model, data, qp)
        pin.updateFramePlacements(model, data)
        oMf = data.oMf[fid]
        T = robot.fk_internal(q)
        np.testing.assert_allclose(T[:3, 3], 1000.0 * oMf.translation, atol=1e-9 * max(1.0, np.linalg.norm(T[:3, 3])))
        np.testing.assert_allclose(T[:3, :3], oMf.rotation, atol=1e-9)
        colscale = np.where(robot.revolute_mask, 1.0, 1e-3)
        for ref, J in ((pin.ReferenceFrame.WORLD, robot.space_jacobian_internal(q)), (pin.ReferenceFrame.LOCAL, robot.body_jacobian_internal(q))):
            Jp = pin.getFrameJacobian(model, data, fid, ref)[:, cols]
            Jp = np.vstack([Jp[3:], 1000.0 * Jp[:3]]) * colscale
            np.testing.assert_allclose(J, Jp, atol=1e-9 * max(1.0, np.abs(J).max()))
            worst = max(worst, float(np.abs(J - Jp).max()))
    return worst


@needs_erd
@pytest.mark.parametrize("tool", ["tool0", "ee_link", "wrist_3_link"])
def test_ur5_matches_pinocchio(tool):
    robot = load_urdf(ERD / UR5, tool=tool)
    assert robot.name == "ur5" and robot.n_joints == 6
    assert [j.name for j in robot.joints] == ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                             "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"]
    np.testing.assert_allclose(robot.upper, [2 * np.pi] * 2 + [np.pi] + [2 * np.pi] * 3, atol=1e-10)
    compare_with_pinocchio(robot, ERD / UR5, tool, np.random.default_rng(5))


@needs_erd
def test_ur5_geometry_and_masses():
    robot = load_urdf(ERD / UR5, tool="tool0")
    names = [lk.name for lk in robot.links]
    assert names == ["base_link", "shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link", "wrist_2_link", "wrist_3_link"]
    # URDF metres -> mm: shoulder height 0.089159 m, forearm 0.39225 m
    np.testing.assert_allclose(robot.links[0].vector_mm, [0, 0, 89.159], atol=1e-9)
    assert robot.links[3].length_mm == pytest.approx(392.25)
    masses = {m.name: m for m in robot.masses}
    assert masses["upper_arm_link"].mass_kg == 8.393 and masses["upper_arm_link"].body == 2
    assert masses["base_link"].body == 0 and masses["wrist_3_link"].body == 6
    # com of the upper arm: 0.28 m along its link z axis, which at home points along base +x (rpy 0, pi/2, 0)
    np.testing.assert_allclose(masses["upper_arm_link"].com_mm, [280.0, 135.85, 89.159], atol=1e-6)


@needs_erd
@pytest.mark.parametrize("tool", ["panda_hand_tcp", "panda_link8", "panda_link7"])
def test_panda_matches_pinocchio(tool):
    robot = load_urdf(ERD / PANDA, tool=tool)
    assert robot.n_joints == 7
    # joint 4 cannot reach 0: the nominal value is the middle of its limits
    assert robot.q_nominal[3] == pytest.approx(0.5 * (-3.0718 - 0.0698))
    assert np.all(robot.q_nominal >= robot.lower) and np.all(robot.q_nominal <= robot.upper)
    compare_with_pinocchio(robot, ERD / PANDA, tool, np.random.default_rng(7))


@needs_erd
def test_branch_without_tool_is_refused():
    with pytest.raises(TolallocError, match=r"branches at link 'wrist_3_link'.*\['ee_link', 'tool0'\].*choose the tool link with `tool` \(e\.g\. "):
        load_urdf(ERD / UR5)
    with pytest.raises(TolallocError, match=r"branches at link 'panda_hand'.*panda_leftfinger.*with `tool` \(e\.g\. panda_hand or"):
        load_urdf(ERD / PANDA)


# ---------------------------------------------------------------- synthetic URDFs
def urdf_text(joints, links=None, name="synth", extra=""):
    """joints: list of dicts (name, type, parent, child, xyz, rpy, axis or None, limit (lo, hi) or None, mimic)."""
    link_names = links or sorted({j["parent"] for j in joints} | {j["child"] for j in joints})
    out = [f'<robot name="{name}">']
    for ln in link_names:
        out.append(f'<link name="{ln}"><inertial><origin xyz="0.01 0.02 0.03" rpy="0 0 0"/><mass value="1.5"/>'
                   f'<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>')
    for j in joints:
        s = f'<joint name="{j["name"]}" type="{j["type"]}"><parent link="{j["parent"]}"/><child link="{j["child"]}"/>'
        s += '<origin xyz="{} {} {}" rpy="{} {} {}"/>'.format(*j.get("xyz", (0, 0, 0)), *j.get("rpy", (0, 0, 0)))
        if j.get("axis") is not None:
            s += '<axis xyz="{} {} {}"/>'.format(*j["axis"])
        if j.get("limit") is not None:
            s += '<limit lower="{}" upper="{}" effort="1" velocity="1"/>'.format(*j["limit"])
        if j.get("mimic"):
            s += f'<mimic joint="{j["mimic"]}"/>'
        out.append(s + "</joint>")
    return "\n".join(out) + extra + "\n</robot>\n"


def random_urdf_joints(rng, n):
    """A chain of n movable joints (revolute / continuous / prismatic) with fixed joints between some of them."""
    joints, k = [], 0
    parent = "base"
    for i in range(n):
        if rng.uniform() < 0.4:
            k += 1
            joints.append(dict(name=f"fix{k}", type="fixed", parent=parent, child=f"f{k}",
                               xyz=rng.uniform(-0.3, 0.3, 3), rpy=rng.uniform(-3, 3, 3)))
            parent = f"f{k}"
        kind = rng.choice(["revolute", "continuous", "prismatic"], p=[0.5, 0.2, 0.3])
        axis = rng.normal(size=3)
        axis *= rng.uniform(0.5, 2.0) / np.linalg.norm(axis)  # not normalised: the importer normalises
        limit = (-2.5, 2.5) if kind == "revolute" else (-0.3, 0.4) if kind == "prismatic" else None
        joints.append(dict(name=f"j{i + 1}", type=str(kind), parent=parent, child=f"b{i + 1}",
                           xyz=rng.uniform(-0.4, 0.4, 3), rpy=rng.uniform(-3, 3, 3), axis=axis, limit=limit))
        parent = f"b{i + 1}"
    joints.append(dict(name="tool_joint", type="fixed", parent=parent, child="tool",
                       xyz=rng.uniform(-0.1, 0.1, 3), rpy=rng.uniform(-3, 3, 3)))
    return joints


@pytest.mark.parametrize("seed", range(20))
def test_random_urdfs_match_pinocchio(tmp_path, seed):
    rng = np.random.default_rng(seed)
    joints = random_urdf_joints(rng, int(rng.integers(2, 8)))
    path = tmp_path / "random.urdf"
    path.write_text(urdf_text(joints))
    robot = load_urdf(path)  # a single chain: the default tool is its last link
    assert robot.n_joints == sum(j["type"] != "fixed" for j in joints)
    for j, spec in zip(robot.joints, [s for s in joints if s["type"] != "fixed"]):
        if spec["type"] == "continuous":
            assert j.kind == "revolute" and j.upper == pytest.approx(4 * np.pi)
        if spec["type"] == "prismatic":
            assert (j.lower, j.upper) == pytest.approx((-300.0, 400.0))
    compare_with_pinocchio(robot, path, "tool", rng, n_q=3)
    assert len(robot.masses) == len({s["child"] for s in joints} | {"base"})


def test_fixed_joints_folded_and_masses(tmp_path):
    joints = [
        dict(name="j1", type="revolute", parent="base", child="l1", xyz=(0, 0, 0.3), axis=(0, 0, 1), limit=(-3, 3)),
        dict(name="mount", type="fixed", parent="l1", child="bracket", xyz=(0.1, 0, 0), rpy=(0, 0, np.pi / 2)),
        dict(name="j2", type="prismatic", parent="bracket", child="l2", xyz=(0.2, 0, 0), axis=(1, 0, 0), limit=(0, 0.5)),
        dict(name="flange", type="fixed", parent="l2", child="tcp", xyz=(0, 0, 0.05)),
    ]
    path = tmp_path / "folded.urdf"
    path.write_text(urdf_text(joints))
    robot = load_urdf(path)
    assert [e.name for e in robot.chain] == ["base", "j1", "l1", "bracket", "j2", "l2"]
    np.testing.assert_allclose([lk.vector_mm for lk in robot.links], [[0, 0, 300], [100, 0, 0], [0, 200, 0], [0, 0, 50]], atol=1e-12)
    np.testing.assert_allclose(robot.joints[1].axis, [0, 1, 0], atol=1e-15)  # x of the bracket, turned 90 deg about z
    assert (robot.joints[1].lower, robot.joints[1].upper) == (0.0, 500.0)
    np.testing.assert_allclose(robot.home[:3, 3], [100, 200, 350], atol=1e-12)
    bodies = {m.name: m.body for m in robot.masses}
    assert bodies == {"base": 0, "l1": 1, "bracket": 1, "l2": 2, "tcp": 2}
    coms = {m.name: m.com_mm for m in robot.masses}
    np.testing.assert_allclose(coms["bracket"], [100 - 20, 10, 330], atol=1e-9)  # (10, 20, 30) mm turned 90 deg about z
    assert all(m.mass_kg == 1.5 for m in robot.masses)


CHAIN = [
    dict(name="j1", type="revolute", parent="base", child="l1", xyz=(0, 0, 0.3), axis=(0, 0, 1), limit=(-3, 3)),
    dict(name="j2", type="revolute", parent="l1", child="l2", xyz=(0.4, 0, 0), axis=(0, 1, 0), limit=(-3, 3)),
]


def _bad(tmp_path, joints, name="bad.urdf", **kw):
    path = tmp_path / name
    path.write_text(urdf_text(joints, **kw))
    return path


@pytest.mark.parametrize("joints,tool,match", [
    ([*CHAIN, dict(name="j3", type="revolute", parent="base", child="l2", axis=(0, 0, 1), limit=(-1, 1))], None,
     r"link 'l2' is the child of joints 'j2' and 'j3': the URDF has a closed loop"),
    ([*CHAIN, dict(name="j3", type="revolute", parent="l1", child="l3", axis=(0, 0, 1), limit=(-1, 1))], None,
     r"branches at link 'l1'.*\['l2', 'l3'\].*choose the tool link with `tool` \(e\.g\. l1 or l2\)\.$"),
    ([CHAIN[0], {**CHAIN[1], "axis": None}], None,
     r"joint 'j2' \(revolute\) has no <axis>; the URDF default \(1, 0, 0\) is not assumed"),
    ([CHAIN[0], {**CHAIN[1], "axis": (0, 0, 0)}], None, r"joint 'j2' has axis \[0.0, 0.0, 0.0\]; expected a non-zero"),
    ([CHAIN[0], {**CHAIN[1], "xyz": (400, 0, 0)}], None,
     r"joint 'j2' has its origin 400 m from its parent link; URDF lengths are metres and this does not look like metres"),
    ([CHAIN[0], {**CHAIN[1], "type": "prismatic", "limit": (0, 50)}], None, r"50 m of prismatic stroke.*does not look like metres"),
    ([CHAIN[0], {**CHAIN[1], "mimic": "j1"}], None, r"joint 'j2' mimics joint 'j1'; mimic joints on the tool chain are not supported"),
    ([dict(name="free", type="floating", parent="world", child="base"), *CHAIN], None, r"joint 'free' is floating"),
    ([CHAIN[0], {**CHAIN[1], "type": "planar"}], None, r"joint 'j2' is planar"),
    ([CHAIN[0], {**CHAIN[1], "limit": (1, -1)}], None, r"joint 'j2' has <limit lower=1.0 upper=-1.0> \[rad\]; expected finite lower < upper"),
    (CHAIN, "nowhere", r"the tool link 'nowhere' \(`tool`\) is not a link of the URDF; links: base, l1, l2\.$"),
    (CHAIN, "base", r"no movable joint between the root link 'base' and the tool link 'base'"),
])
def test_bad_urdf(tmp_path, joints, tool, match):
    path = _bad(tmp_path, joints)
    with pytest.raises(TolallocError, match=match) as info:
        load_urdf(path, tool=tool)
    assert str(info.value).startswith(f"URDF file {str(path)!r}: ")


def test_mimic_off_the_chain_is_ignored(tmp_path):
    fingers = [dict(name="f1", type="prismatic", parent="l2", child="fa", axis=(0, 1, 0), limit=(0, 0.04)),
               dict(name="f2", type="prismatic", parent="l2", child="fb", axis=(0, -1, 0), limit=(0, 0.04), mimic="f1")]
    robot = load_urdf(_bad(tmp_path, [*CHAIN, *fingers]), tool="l2")
    assert [j.name for j in robot.joints] == ["j1", "j2"]
    assert {m.name: m.body for m in robot.masses}["fa"] == 2


@pytest.mark.parametrize("text,match", [
    ("<robot name='x'><link name='a'/>", r"not valid XML .*expand a \.xacro file first"),
    ("<sdf version='1.6'><model name='x'/></sdf>", r"the root element is <sdf>; expected <robot>"),
    ("<robot name='x'><link name='a'/><link name='b'/></robot>", r"several root links \['a', 'b'\]"),
    ("<robot name='x'><link name='a'/><joint name='j' type='revolute'><parent link='a'/><child link='zz'/>"
     "<axis xyz='0 0 1'/><limit lower='-1' upper='1' effort='1' velocity='1'/></joint></robot>", r"joint 'j' refers to link 'zz', which is not defined"),
    ("<robot name='x'><link name='a'/><link name='b'/><link name='c'/>"
     "<joint name='j1' type='continuous'><parent link='b'/><child link='c'/><axis xyz='0 0 1'/></joint>"
     "<joint name='j2' type='continuous'><parent link='c'/><child link='b'/><axis xyz='0 0 1'/></joint></robot>",
     r"links \['b', 'c'\] are not reachable from the root link 'a': they form a closed loop"),
    ("<robot name='x'><link name='a'/><link name='b'/><joint name='j1' type='continuous'><child link='b'/></joint></robot>",
     r"yourdfpy could not read the URDF"),
    ("<robot name='x'><link name='a'/><link name='b'/><joint name='j1' type='revolute'><parent link='a'/>"
     "<child link='b'/><axis xyz='0 0 1'/></joint></robot>", r"joint 'j1' \(revolute\) has no <limit>; URDF requires"),
])
def test_malformed_urdf(tmp_path, text, match):
    path = tmp_path / "m.urdf"
    path.write_text(text)
    with pytest.raises(TolallocError, match=match):
        load_robot(path)


def test_cli_with_urdf_and_tool(tmp_path, capsys):
    import json

    path = _bad(tmp_path, [*CHAIN, dict(name="j3", type="revolute", parent="l1", child="l3", axis=(0, 0, 1), limit=(-1, 1))],
                name="branchy.urdf")
    assert main(["show", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and "choose the tool link with --tool (e.g. l1 or l2)." in err, err
    assert main(["fk", str(path), "--tool", "l2", "--q", "90,0", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    np.testing.assert_allclose(data["position_mm"], [0, 400, 300], atol=1e-9)
    assert main(["show", str(path), "--tool", "l3"]) == 0
    assert "robot: synth" in capsys.readouterr().out
    assert main(["show", "tool_changer", "--tool", "l3"]) == 2
    assert re.search(r"--tool 'l3': the tool link can only be chosen for a URDF", capsys.readouterr().err)


def test_single_jaw_gripper_is_not_taken_as_an_arm_joint(tmp_path):
    # regression (z1, so100): a one-jaw gripper does not branch the tree, so the longest chain ran through the
    # jaw joint and the import returned a 3-joint arm whose last "arm joint" was the gripper
    jaw = dict(name="jointGripper", type="revolute", parent="l2", child="gripperMover", axis=(0, 1, 0), limit=(-1, 0))
    path = _bad(tmp_path, [*CHAIN, jaw])
    with pytest.raises(TolallocError, match=r"ends with joint 'jointGripper'.*with `tool` \(e.g. l2 for the arm without the gripper"):
        load_urdf(path)
    assert [j.name for j in load_urdf(path, tool="l2").joints] == ["j1", "j2"]
    assert [j.name for j in load_urdf(path, tool="gripperMover").joints] == ["j1", "j2", "jointGripper"]
    plain = _bad(tmp_path, [*CHAIN, {**jaw, "name": "j3", "child": "l3"}], name="plain.urdf")
    assert load_urdf(plain).n_joints == 3  # an ordinary third joint is still taken without --tool
