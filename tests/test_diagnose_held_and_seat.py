"""Two effects read from the logged payload's history: heat exchanged with a held part (thermal ``held_<tau>min``)
and a tool re-seated within its coupling's clearance at every tool change (backlash ``reseat``).

Known answers: the first-order step response of a held payload; the re-seat columns reproduce the target of a robot
rebuilt with the shifted tool offset; block placement of a test file among the training poses. End to end: sessions
rebuilt from the physics (not from the effect's columns) are named with the right family and variant, and the
held-out error falls to the noise where the test poses share the training blocks.
"""

from __future__ import annotations

import numpy as np
import pytest

import tolalloc
from tolalloc.diagnose.effects import effect_basis, effect_reference, target_points, variants
from tolalloc.diagnose.measurements import Measurements
from tolalloc.physics.blocks import MAX_BLOCKS, MIN_BLOCK_POSES, contrasts
from tolalloc.physics.seating import seat_blocks, seat_columns, seat_problem
from tolalloc.physics.thermal_history import held_heat
from tolalloc.robot.model import Link, Robot

TOOL = np.array([0.0, 30.0, 120.0])


def _poses(robot, P: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return rng.uniform(np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi), (P, robot.n_joints))


# ------------------------------------------------------------------------------------------------ held heat
def test_held_heat_is_the_first_order_response_to_the_payload_held_before_each_pose():
    """A 4 kg part picked at pose 10 and put down at pose 30 (poses 60 s apart, tau 10 min): 4 (1 - exp(-dt / tau))
    from the interval after the pick, then the decay exp(-dt / tau) from the value at the release; the poses' order
    does not matter."""
    tau = 600.0
    t = 60.0 * np.arange(50)
    m = np.where((np.arange(50) >= 10) & (np.arange(50) < 30), 4.0, 0.0)
    y = held_heat(t, m, tau)
    assert np.all(y[:11] == 0.0)  # the part is held over the interval before pose 11 first
    np.testing.assert_allclose(y[11:31], 4.0 * (1 - np.exp(-(t[11:31] - t[10]) / tau)), rtol=1e-12)
    np.testing.assert_allclose(y[31:], y[30] * np.exp(-(t[31:] - t[30]) / tau), rtol=1e-12)
    perm = np.random.default_rng(0).permutation(50)
    np.testing.assert_allclose(held_heat(t[perm], m[perm], tau), y[perm], rtol=1e-12)


def test_held_variants_need_a_payload_that_varies():
    t = 60.0 * np.arange(40)
    q = np.zeros((40, 6))
    with_part = Measurements(q, np.zeros((40, 3)), None, None, np.repeat([0.0, 3.0], 20), t)
    constant = Measurements(q, np.zeros((40, 3)), None, None, np.full(40, 3.0), t)
    assert "held_30min" in variants("thermal", with_part)
    assert not any(v.startswith("held") for v in variants("thermal", constant))


def _grown_point(robot, q1, eps: dict):
    chain = tuple(Link(el.name, np.asarray(el.vector_mm) * (1 + eps.get(el.name, 0.0))) if hasattr(el, "vector_mm")
                  else el for el in robot.chain)
    grown = Robot(robot.name, chain, tool_offset_mm=robot.tool_offset_mm, tool_rotation=robot.tool_rotation)
    return target_points(grown, q1[None], TOOL)[0]


def _held_session(robot, P: int, seed: int):
    """A session in which a chilled part (5 kg) is held in four spells; the forearm shrinks by 60e-6 per held kg at
    full soak (tau 15 min), the upper arm by 20e-6: rebuilt from the shrunk links."""
    q = _poses(robot, P, seed)
    t = 40.0 * np.arange(P)
    m = np.where((np.arange(P) // 25) % 2 == 1, 5.0, 0.0)
    s = held_heat(t, m, 900.0)
    links = [lk.name for lk in robot.links if lk.length_mm > 300]
    k = {links[0]: -20e-6, links[1]: -60e-6}
    xyz = np.stack([_grown_point(robot, q[i], {n: v * s[i] for n, v in k.items()}) for i in range(P)])
    return q, t, m, xyz, k


def test_held_columns_reproduce_links_growing_with_the_held_payload():
    robot = tolalloc.load_robot("ur10")
    q, t, m, xyz, k = _held_session(robot, 100, 3)
    meas = Measurements(q, xyz, None, None, m, t)
    basis = effect_basis("thermal", robot, meas, TOOL, effect_reference(meas), "held_15min")
    d = xyz - target_points(robot, q, TOOL)
    beta = np.linalg.lstsq(basis.B.reshape(-1, basis.B.shape[-1]), d.ravel(), rcond=None)[0]
    got = {nm.split(" ")[0][6:]: b for nm, b in zip(basis.names, beta)}
    for name, v in k.items():
        assert got[name] == pytest.approx(v * 1e6, rel=5e-3)


def test_a_part_chilling_the_arm_while_held_is_diagnosed_as_held_heat():
    """Thermal in a held variant, with a lag near the true 15 min, and the held-out error near the noise."""
    from tolalloc.diagnose import diagnose

    robot = tolalloc.load_robot("ur10")
    q, t, m, xyz, _ = _held_session(robot, 150, 5)
    xyz = xyz + np.random.default_rng(6).normal(0.0, 0.008, xyz.shape)
    d = diagnose(robot, Measurements(q, xyz, None, None, m, t), folds=3, max_effects=1)
    assert d.effect == "thermal", d.verdict
    variant = next(c.variant for c in d.ranking if c.effect == "thermal")
    assert variant.startswith("held_") and 7.5 <= float(variant[5:-3]) <= 30, variant
    assert d.final.heldout_rms_mm < 0.5 * d.geometric.heldout_rms_mm
    _export_refused(d, robot, "held_")


# ------------------------------------------------------------------------------------------------ tool re-seat
def test_seat_blocks_are_runs_of_the_payload_placed_among_the_training_poses():
    t = 60.0 * np.arange(30)
    m = np.repeat([1.0, 2.0, 1.0], 10)
    np.testing.assert_array_equal(seat_blocks(t, m, t, m), np.repeat([0, 1, 2], 10))
    # other poses: within a training block's time and payload -> its block; another payload, or after the training
    # poses' last change with a new tool -> no block; poses of another payload between training poses of one block
    # split its run but not its block
    tt = np.array([30.0, 90.0, 610.0, 1500.0, 2000.0, 3000.0])
    mm = np.array([1.0, 3.0, 2.0, 1.0, 5.0, 1.0])
    np.testing.assert_array_equal(seat_blocks(tt, mm, t, m), [0, -1, 1, 2, -1, -1])
    # a gripper picking and releasing parts (the payload drops to zero) is not a tool change
    grip = Measurements(np.zeros((40, 6)), np.zeros((40, 3)), None, None, np.repeat([0.0, 3.0, 0.0, 3.0], 10), t[:40]
                        if len(t) >= 40 else 60.0 * np.arange(40))
    assert "reseat" not in variants("backlash", grip)


def test_seat_problems_are_named():
    t = 60.0 * np.arange(40)
    assert seat_problem(None, np.zeros(40)).startswith("needs time_s")
    assert seat_problem(t, np.full(40, 2.0)) == "the payload never changes"
    assert seat_problem(t[::-1], np.repeat([1.0, 2.0], 20)) is not None  # a time that runs backwards
    assert seat_problem(t, np.repeat([0.0, 2.0], 20)).startswith("the payload drops to zero")
    assert "at most" in seat_problem(t, 1.0 + np.arange(40.0) % 2)
    assert f"at least {MIN_BLOCK_POSES}" in seat_problem(t, np.repeat([1.0, 2.0], [37, 3]))
    t = 60.0 * np.arange(MAX_BLOCKS * MIN_BLOCK_POSES)
    assert seat_problem(t, np.repeat(np.arange(1.0, MAX_BLOCKS + 1), MIN_BLOCK_POSES)) is None


def test_block_contrasts_are_orthonormal_in_the_pose_counts():
    n = np.array([12.0, 7.0, 30.0, 9.0])
    C = contrasts(n)
    assert C.shape == (4, 3)
    np.testing.assert_allclose(n @ C, 0.0, atol=1e-12)
    np.testing.assert_allclose(C.T @ (n[:, None] * C), n.sum() * np.eye(3), atol=1e-10)


def test_seat_columns_are_the_target_of_the_tool_shifted_on_the_flange():
    """Each block's seat d_b on the flange is the tool offset at the mean seat plus the contrasts' columns; a pose in
    a block the training poses do not hold is predicted at the mean seat."""
    robot = tolalloc.load_robot("ur10")
    q = _poses(robot, 30, 1)
    t = 60.0 * np.arange(30)
    m = np.repeat([2.0, 4.0, 3.0], [8, 10, 12])
    blocks = seat_blocks(t, m, t, m)
    n = np.bincount(blocks).astype(float)
    B, names = seat_columns(robot, q, blocks, n)
    assert B.shape == (30, 3, 6) and names[3] == "seat_x_contrast2 [mm]"
    d = np.array([[0.02, 0.0, -0.01], [0.05, -0.03, 0.02], [-0.04, 0.06, 0.01]])  # the blocks' seats on the flange
    mean = n @ d / n.sum()
    C = contrasts(n)
    c = C.T @ (n[:, None] * (d - mean)) / n.sum()  # (2, 3): the contrasts' coefficients per flange axis
    want = np.stack([target_points(robot, q[i:i + 1], TOOL + d[blocks[i]])[0] for i in range(30)]) \
        - target_points(robot, q, TOOL + mean)
    np.testing.assert_allclose(B @ c.ravel(), want, atol=1e-12)
    unseen, _ = seat_columns(robot, q[:4], np.full(4, -1), n)
    assert not unseen.any()


def _reseat_session(robot, P: int, seed: int, split: int | None = None):
    """Four tools changed in turn (1.5, 3, 2, 4 kg), each seated anew within a 0.15 mm clearance; rebuilt from the
    shifted tool offset."""
    rng = np.random.default_rng(seed)
    q = _poses(robot, P, seed)
    t = 30.0 * np.arange(P)
    block = np.minimum(np.arange(P) // (P // 4), 3)
    m = np.array([1.5, 3.0, 2.0, 4.0])[block]
    seat = rng.uniform(-0.15, 0.15, (4, 3))
    xyz = np.stack([target_points(robot, q[i:i + 1], TOOL + seat[block[i]])[0] for i in range(P)])
    return q, t, m, xyz + rng.normal(0.0, 0.01, xyz.shape)


def test_a_tool_reseated_at_every_change_is_diagnosed_as_backlash_reseat():
    """Every fourth pose held out: the test poses share the training poses' tool changes, so the model predicts them
    to the noise (0.017 mm in 3-D) where the geometric model, one tool offset for all, misses by the seats' scatter.
    The interpolation check reads the joint-space blocks (a time block holds out whole tool changes)."""
    from tolalloc.diagnose import diagnose
    from tolalloc.diagnose.scores import rms

    robot = tolalloc.load_robot("tool_changer")
    q, t, m, xyz = _reseat_session(robot, 160, 8)
    test = np.arange(160) % 4 == 3
    train, held = (Measurements(q[k], xyz[k], None, None, m[k], t[k]) for k in (~test, test))
    assert "reseat" in variants("backlash", train)
    d = diagnose(robot, train, held, folds=3, max_effects=1)
    assert d.effect == "backlash", d.verdict
    assert next(c.variant for c in d.ranking if c.effect == "backlash") == "reseat"
    assert rms(d.final.test_mm) < 0.025 < 0.1 < rms(d.geometric.test_mm)
    # the identified model predicts the session's poses with their payload and time; its file refuses the seats
    from tolalloc.diagnose.model_use import identified_model

    model = identified_model(d)
    pred = model.points(model.measurements(q[test], payload_kg=m[test], time_s=t[test]), "base")
    assert rms(pred - xyz[test]) < 0.025
    _export_refused(d, robot, "reseat")


def _export_refused(d, robot, variant: str):
    """The identified model's file records the effect but refuses to rebuild it (it needs the training session)."""
    import json

    from tolalloc.diagnose.model_export import identified_section, model_from_identified
    from tolalloc.diagnose.model_use import identified_model

    section = json.loads(json.dumps(identified_section(identified_model(d))))
    with pytest.raises(tolalloc.TolallocError, match=variant):
        model_from_identified(section, robot)


# ------------------------------------------------------------------------------------------------ joint zeros homed
def _cycles():
    """Four power cycles of 30 poses (30 s apart) separated by 40 min pauses."""
    return 30.0 * np.arange(120) + 2400.0 * (np.arange(120) // 30)


def test_power_cycles_are_cut_at_the_pauses_and_placed_by_time():
    from tolalloc.physics.rehoming import cycle_blocks, cycle_gap_s

    t = _cycles()
    assert cycle_gap_s(t) == pytest.approx(150.0)  # 5 median intervals
    np.testing.assert_array_equal(cycle_blocks(t, t), np.repeat(np.arange(4), 30))
    # between two training poses of a cycle: that cycle; after a pause beyond the last training pose: none
    other = np.array([45.0, t[35] + 10.0, t[-1] + 20.0, t[-1] + 3600.0])
    np.testing.assert_array_equal(cycle_blocks(other, t), [0, 1, 3, -1])


def test_rehome_problems_are_named():
    from tolalloc.physics.rehoming import rehome_problem

    assert rehome_problem(None).startswith("needs time_s")
    assert rehome_problem(30.0 * np.arange(60)) == "no power cycle in the training poses"
    assert rehome_problem(_cycles()) is None
    short = np.concatenate([30.0 * np.arange(40), 5000.0 + 30.0 * np.arange(3)])
    assert f"at least {MIN_BLOCK_POSES}" in rehome_problem(short)


def _incremental_tool_changer(tmp_path):
    """The tool_changer with incremental encoders (homed at each power-up) on its first three joints: the first three
    of its robot file's encoder entries (j1, j2, j3) replaced."""
    from importlib.resources import files

    text = (files("tolalloc") / "data" / "robots" / "tool_changer.toml").read_text()
    part = 'encoder = { part = "MOTOR-ENC-STD" }'
    assert text.index("[components.joints.j4]") > [i for i in range(len(text)) if text.startswith(part, i)][2]
    text = text.replace(part, 'encoder = { side = "motor", accuracy_arcmin = 4, homing = "incremental" }', 3)
    path = tmp_path / "tool_changer_incremental.toml"
    path.write_text(text)
    return tolalloc.load_robot(path)


def test_an_encoder_homing_other_than_absolute_or_incremental_is_refused(tmp_path):
    from importlib.resources import files

    text = (files("tolalloc") / "data" / "robots" / "tool_changer.toml").read_text()
    path = tmp_path / "bad.toml"
    bad = 'encoder = { side = "motor", homing = "relative" }'
    path.write_text(text.replace('encoder = { part = "MOTOR-ENC-STD" }', bad, 1))
    with pytest.raises(tolalloc.TolallocError, match="homing: expected one of absolute, incremental, got 'relative'"):
        tolalloc.load_robot(path)


def test_rehome_is_offered_only_for_joints_homed_at_power_up(tmp_path):
    from tolalloc.physics.rehoming import homed_joints, rehome_problem

    t = _cycles()
    plain = tolalloc.load_robot("tool_changer")
    assert not len(homed_joints(plain)) and "homing = incremental" in rehome_problem(t, plain)
    meas = Measurements(np.zeros((120, 6)), np.zeros((120, 3)), None, None, None, t)
    assert "rehome" not in variants("transmission", meas, robot=plain)
    robot = _incremental_tool_changer(tmp_path)
    np.testing.assert_array_equal(homed_joints(robot), [0, 1, 2])
    assert "rehome" in variants("transmission", meas, robot=robot)


def _rehomed(robot, q, t, zeros: np.ndarray, blocks: np.ndarray) -> np.ndarray:
    """The target of the robot whose joint zeros are ``zeros[b]`` (B, n) [rad / mm] in power cycle b."""
    return np.stack([target_points(robot, q[i:i + 1] + zeros[blocks[i]], TOOL)[0] for i in range(len(q))])


def test_rehome_columns_are_the_target_of_the_joints_homed_anew():
    """First order in the zeros: a joint's zero in each cycle is the mean zero plus the contrasts' columns."""
    from tolalloc.physics.blocks import contrasts
    from tolalloc.physics.loads import point_jacobian
    from tolalloc.physics.rehoming import cycle_blocks, rehome_columns

    robot = tolalloc.load_robot("tool_changer")
    t = _cycles()
    q = _poses(robot, 120, 2)
    blocks = cycle_blocks(t, t)
    n = np.bincount(blocks).astype(float)
    zeros = np.random.default_rng(3).normal(0.0, 1e-6, (4, robot.n_joints))
    mean = n @ zeros / n.sum()
    B, names, groups = rehome_columns(point_jacobian(robot, q + mean, target_points(robot, q + mean, TOOL)), blocks,
                                      n, [j.name for j in robot.joints], ["rad"] * robot.n_joints)
    assert B.shape == (120, 3, 3 * robot.n_joints) and names[0].endswith("_contrast1 [rad]")
    np.testing.assert_array_equal(groups, np.repeat(np.arange(robot.n_joints), 3))
    c = contrasts(n).T @ (n[:, None] * (zeros - mean)) / n.sum()  # (3, n): the contrasts' coefficients per joint
    want = _rehomed(robot, q, t, zeros, blocks) - _rehomed(robot, q, t, np.broadcast_to(mean, zeros.shape), blocks)
    np.testing.assert_allclose(B @ c.T.ravel(), want, atol=1e-5 * np.abs(want).max())  # second order: ~1e-6


def test_joints_homed_anew_at_each_power_up_are_diagnosed_as_transmission_rehome(tmp_path):
    """A tool_changer whose first three axes home on proximity switches (zeros scattered by 2e-4 rad) in four power
    cycles; every fourth pose held out: named transmission in the rehome variant, the test poses predicted to the
    noise; the identified model's file refuses the zeros."""
    from tolalloc.diagnose import diagnose
    from tolalloc.diagnose.scores import rms
    from tolalloc.physics.rehoming import cycle_blocks

    robot = _incremental_tool_changer(tmp_path)
    rng = np.random.default_rng(21)
    t = _cycles()
    q = _poses(robot, 120, 4)
    zeros = np.zeros((4, robot.n_joints))
    zeros[:, :3] = rng.normal(0.0, 2e-4, (4, 3))
    xyz = _rehomed(robot, q, t, zeros, cycle_blocks(t, t)) + rng.normal(0.0, 0.01, (120, 3))
    test = np.arange(120) % 4 == 3
    train, held = (Measurements(q[k], xyz[k], None, None, None, t[k]) for k in (~test, test))
    assert "rehome" in variants("transmission", train, robot=robot)
    d = diagnose(robot, train, held, folds=3, max_effects=1)
    assert d.effect == "transmission", d.verdict
    assert next(c.variant for c in d.ranking if c.effect == "transmission") == "rehome"
    assert rms(d.final.test_mm) < 0.025 < 0.1 < rms(d.geometric.test_mm)
    _export_refused(d, robot, "rehome")


def test_a_test_file_without_the_history_leaves_the_effect_judged_on_the_training_file():
    """Trained with the tool changes logged, tested on a file without its payload column: no traceback; the reason
    says the test file cannot carry the seats."""
    from tolalloc.diagnose import diagnose

    robot = tolalloc.load_robot("tool_changer")
    q, t, m, xyz = _reseat_session(robot, 160, 8)
    test = np.arange(160) % 4 == 3
    train = Measurements(q[~test], xyz[~test], None, None, m[~test], t[~test])
    d = diagnose(robot, train, Measurements(q[test], xyz[test], None, None, None, t[test]), folds=3, max_effects=1)
    assert any("backlash (reseat) was judged on the training file only: the test file has no payload_kg column" in r
               for r in d.verdict.reasons), d.verdict.reasons
