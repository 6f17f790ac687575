"""A joint bearing's tilt under the moment across its axis (tolalloc.physics.compliance.bearing_tilt) against a closed
form, in the parts' terms and in their physical draws."""

import numpy as np
import pytest

from tolalloc.errormodel.parts import TILT_SD, PartEffects
from tolalloc.exceptions import TolallocError
from tolalloc.errormodel.parts_sample import sample_effects
from tolalloc.physics.compliance import bearing_tilt
from tolalloc.physics.loads import G, gravity_torques, joint_wrenches
from tolalloc.robot import Joint, Link, Mass, Robot
from tolalloc.robot.components import Bearing, Components, JointComponents
from tolalloc.robot.components_file import parse_components

K = 1.0e6  # [N m/rad]
KG = 20.0


def _arm() -> Robot:
    """j1 about the vertical at the origin, a 1 m link along x, j2 about x, 20 kg at (1000, 300, 0) mm on the last
    body; j1's bearing tilts by K, j2's is rigid."""
    chain = (Joint("j1", "revolute", np.array([0.0, 0.0, 1.0])), Link("l1", np.array([1000.0, 0.0, 0.0])),
             Joint("j2", "revolute", np.array([1.0, 0.0, 0.0])), Link("l2", np.array([0.0, 300.0, 0.0])))
    robot = Robot("arm", chain)
    object.__setattr__(robot, "masses", (Mass("m", 2, KG, np.array([1000.0, 300.0, 0.0])),))
    bearing = Bearing("P5", 100.0, None, K, "", 60.0, 0.005)
    object.__setattr__(robot, "components", Components(joints={"j1": JointComponents(bearing=bearing)}))
    return robot


def test_a_vertical_joints_bearing_tilts_the_arm_down_by_m_g_r2_over_k():
    """The 20 kg at horizontal reach r from j1's vertical axis: moment m g r across the axis, tilt m g r / K, the
    point at reach r drops by m g r^2 / K; j2's axis carries the same load as a torque only."""
    robot, q = _arm(), np.zeros((1, 2))
    p = np.array([[1000.0, 300.0, 0.0]])
    M = joint_wrenches(robot, q)[1]
    np.testing.assert_allclose(M[0, 0], np.cross([1.0, 0.3, 0.0], [0.0, 0.0, -KG * G]), rtol=1e-12)
    np.testing.assert_allclose(M[0, 1], [-KG * G * 0.3, 0.0, 0.0], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(M[0, 1, 0], gravity_torques(robot, q)[0, 1], rtol=1e-12)  # the axis part: the torque
    d = bearing_tilt(robot, q, p)
    drop = KG * G * (1000.0**2 + 300.0**2) / 1000.0 / K
    np.testing.assert_allclose(d[0, :, 0], [0.0, 0.0, -drop], atol=1e-12)
    np.testing.assert_allclose(d[0, :, 1], 0.0, atol=0.0)  # no stiffness given: rigid


def test_a_payload_and_a_process_wrench_add_their_moments():
    """5 kg at the tool and a 10 N m moment about base x there: j1's moment grows by r x m g and by the couple."""
    robot, q = _arm(), np.zeros((1, 2))
    tip = np.array([[1000.0, 300.0, 0.0]])
    wrench = np.array([[0.0, 0.0, 0.0, 10.0, 0.0, 0.0]])
    M0, M = joint_wrenches(robot, q)[1][0, 0], joint_wrenches(robot, q, tip, 5.0, wrench)[1][0, 0]
    np.testing.assert_allclose(M - M0, np.cross([1.0, 0.3, 0.0], [0.0, 0.0, -5.0 * G]) + [10.0, 0.0, 0.0],
                               rtol=1e-12)


def test_the_tilt_is_a_compliance_term_and_its_draws_have_its_mean_and_spread():
    robot = _arm()
    pm_robot = robot  # its parts are given, not chosen from slots
    fx = PartEffects(pm_robot, np.array([[0.3, 0.2]]), 0.0, 20.0)
    terms = fx.terms()
    k = terms.names.index("tilt_j1")
    assert terms.effect[k] == "compliance"
    expect = bearing_tilt(pm_robot, fx.q, fx.tool)[0, :, 0]
    np.testing.assert_allclose(terms.columns[0, :, k] * terms.mean[0, k], expect, rtol=1e-12)
    assert terms.sys_sd[0, k] == pytest.approx(TILT_SD)
    n = 40_000
    _, direct = sample_effects(fx, 0, n, np.random.default_rng(5))
    np.testing.assert_allclose(direct.mean(axis=0), expect, atol=5 * TILT_SD * np.abs(expect).max() / np.sqrt(n))
    assert direct[:, 2].std() == pytest.approx(TILT_SD * abs(expect[2]), rel=0.03)


def test_a_bearing_with_a_tilt_stiffness_and_no_runout_budgets_its_tilt_only():
    """A table that gives the pair's stiffness and no runout: the tilt term as with a runout, no runout parameters or
    terms, and draws that are the tilt alone; the arm with the runout too has the same tilt and four runout terms."""
    from dataclasses import replace

    with_runout = _arm()
    stiff_only = _arm()
    b = with_runout.components.joint("j1").bearing
    object.__setattr__(stiff_only, "components", Components(joints={"j1": JointComponents(
        bearing=replace(b, precision_class=None, radial_runout=None, span_mm=None))}))
    q = np.array([[0.3, 0.2]])
    fx, fx_r = PartEffects(stiff_only, q, 0.0, 20.0), PartEffects(with_runout, q, 0.0, 20.0)
    terms, terms_r = fx.terms(), fx_r.terms()
    assert fx.pm.bearing == {} and list(fx_r.pm.bearing) == [0]
    assert [n for n in terms.names if n.startswith("bearing_")] == []
    assert len([n for n in terms_r.names if n.startswith("bearing_")]) == 4
    k, k_r = terms.names.index("tilt_j1"), terms_r.names.index("tilt_j1")
    np.testing.assert_allclose(terms.columns[0, :, k] * terms.mean[0, k],
                               terms_r.columns[0, :, k_r] * terms_r.mean[0, k_r], rtol=1e-12)
    values, direct = sample_effects(fx, 0, 2_000, np.random.default_rng(1))
    assert values.shape[1] == len(fx.pm.model.params) and np.abs(direct).max() > 0
    classed = _arm()   # an ISO 492 class without its runout: the runout is asked for, tilt stiffness or not
    object.__setattr__(classed, "components", Components(joints={"j1": JointComponents(
        bearing=replace(b, radial_runout=None))}))
    with pytest.raises(TolallocError, match="joint 'j1'.*bearing.radial_runout_um"):
        PartEffects(classed, q, 0.0, 20.0).terms()


def test_a_bearing_on_a_prismatic_joint_is_refused_naming_the_joint():
    with pytest.raises(ValueError, match=r"joints.slide.bearing: slide is a prismatic joint"):
        parse_components({"joints": {"slide": {"bearing": {"tilt_stiffness_Nm_per_rad": 1e6}}}}, {"slide": False},
                         ["l1"])


def test_a_slotted_bearings_tilt_is_in_the_allocations_mean_not_in_its_options(tmp_path):
    """The UR10's bearing slots with a tilt stiffness: the tilt is the slot's geometry, the same for every option, so
    the allocation's fixed terms carry its mean (bias_mm equals the whole design's mean) and no option carries it."""
    import re
    from importlib.resources import files

    from tolalloc.allocate.parts_problem import Points, option_blocks, signature_combos
    from tolalloc.errormodel.build import build_error_model
    from tolalloc.errormodel.parts import Conditions, with_parts
    from tolalloc.robot import load_robot

    src = (files("tolalloc") / "data" / "robots" / "ur10.toml").read_text()
    path = tmp_path / "ur10_tilt.toml"
    path.write_text(re.sub(r'(bearing = \{ family = "ISO492", [^}]*?)( \})', r'\1, tilt_stiffness_Nm_per_rad = 2.0e5\2',
                           src))
    robot = load_robot(path)
    model = build_error_model(robot, "generic")
    q = robot.random_q(np.random.default_rng(0), 3)
    cond = Conditions(payload_kg=(10.0, 10.0)).check(robot)
    combo = signature_combos(robot)[0]
    blocks = option_blocks(robot, model, Points(q, np.full(3, 10.0), np.full(3, 20.0)), combo, cond)
    terms = PartEffects(with_parts(robot, {k: v[0] for k, v in combo.items()}), q, 10.0, 20.0, cond, model).terms()
    tilt = terms.select([n.startswith("tilt_") for n in terms.names])
    assert len(tilt.names) == 6 and np.abs(tilt.mean_mm()).max() > 0.1   # six bearing slots, a tenth of a mm
    np.testing.assert_allclose(blocks.bias_mm, terms.mean_mm(), atol=1e-12)
    assert not any(n.startswith("tilt_") for t in blocks.terms for n in t.names)


def test_a_payload_or_a_wrench_without_its_point_is_refused():
    from tolalloc.physics.compliance import mount_columns

    robot, q = _arm(), np.zeros((1, 2))
    wrench = np.array([[0.0, 0.0, 0.0, 10.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match="needs tip_mm"):
        joint_wrenches(robot, q, None, 0.0, wrench)
    with pytest.raises(ValueError, match="needs tip_mm"):
        joint_wrenches(robot, q, None, 5.0)
    with pytest.raises(ValueError, match="needs tip_mm"):
        mount_columns(robot, q, np.zeros((1, 3)), None, None, wrench=wrench)


def test_the_tilt_turns_about_the_pairs_centre_wherever_the_joint_point_sits_on_the_axis():
    """j1's point moved 500 mm up its own axis (the same arm) with the bearing's centre left where it was: the tilt
    under load and the runout's tilt columns do not change; with the centre moved along too, they do."""
    from tolalloc.errormodel.build import build_error_model
    from tolalloc.errormodel.parts import parts_error_model

    def arm(first, centre):
        chain = (*first, Joint("j1", "revolute", np.array([0.0, 0.0, 1.0])),
                 Link("l1", np.array([1000.0, 0.0, -sum(lk.vector_mm[2] for lk in first)])),
                 Joint("j2", "revolute", np.array([1.0, 0.0, 0.0])), Link("l2", np.array([0.0, 300.0, 0.0])))
        robot = Robot("arm", chain)
        object.__setattr__(robot, "masses", (Mass("m", 2, KG, np.array([1000.0, 300.0, 0.0])),))
        bearing = Bearing("P5", 100.0, None, K, "", 60.0, 0.005, centre_mm=centre)
        object.__setattr__(robot, "components", Components(joints={"j1": JointComponents(bearing=bearing)}))
        return robot

    low, high, moved = arm((), 500.0), arm((Link("l0", np.array([0.0, 0.0, 500.0])),), 0.0), arm((), 0.0)
    q = np.array([[0.3, 0.2], [-1.0, 0.7]])
    p = low.fk_internal(q)[:, :3, 3]
    np.testing.assert_allclose(high.fk_internal(q)[:, :3, 3], p, atol=1e-9)   # the same arm
    tip, kg = p, np.array([5.0, 5.0])
    a, b = bearing_tilt(low, q, p, tip, kg), bearing_tilt(high, q, p, tip, kg)
    np.testing.assert_allclose(a, b, atol=1e-12)
    assert np.abs(a - bearing_tilt(moved, q, p, tip, kg)).max() > 1e-3
    cols = [parts_error_model(build_error_model(r, "generic"), r) for r in (low, high)]
    J = [pm.model.jacobian(q)[:, :, pm.bearing[0]] for pm in cols]
    np.testing.assert_allclose(J[0], J[1], atol=1e-9)


def test_the_centre_is_read_from_a_bearing_table_and_a_catalogue_slot():
    inline = parse_components({"joints": {"j1": {"bearing": {"span_mm": 80, "radial_runout_um": 5,
                                                             "centre_mm": -40}}}}, {"j1": True}, ["l1"])
    assert inline.joints["j1"].bearing.centre_mm == -40.0
    slot = parse_components({"joints": {"j1": {"bearing": {"family": "ISO492", "bore_mm": 90, "span_mm": 60,
                                                           "centre_mm": 25}}}}, {"j1": True}, ["l1"])
    assert all(slot.slots[("j1", "bearing")].resolve(n).centre_mm == 25.0 for n in slot.slots[("j1", "bearing")].names)
    plain = parse_components({"joints": {"j1": {"bearing": {"span_mm": 80}}}}, {"j1": True}, ["l1"])
    assert plain.joints["j1"].bearing.centre_mm == 0.0
