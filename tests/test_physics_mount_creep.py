"""A creeping mount: the held load's lag and integral against closed forms and an ODE solver, the basis through the
diagnosis's effect layer, held-out poses continuing the training history, and the refusals without ``time_s``."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import tolalloc
from tolalloc.diagnose.effects import effect_basis, effect_reference, variants
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.select import carry_problem
from tolalloc.physics.compliance import mount_moment
from tolalloc.physics.loads import target_points
from tolalloc.physics.mount_creep import CREEP_MIN, creep_signal, creep_variants, dwell_times

UR10 = tolalloc.load_robot("ur10")
T_MM = np.array([0.0, 0.0, 80.0])


def _session(P=40, seed=3, pause_at=None):
    rng = np.random.default_rng(seed)
    q = rng.uniform(-2.5, 2.5, (P, 6))
    t = np.cumsum(rng.uniform(20.0, 40.0, P))
    if pause_at is not None:
        t[pause_at:] += 3600.0
    return q, t


def test_dwell_times_split_the_working_time_and_give_a_pause_to_the_previous_pose():
    t = np.array([0.0, 30.0, 60.0, 90.0, 90.0 + 3600.0, 90.0 + 3630.0])
    prev, new = dwell_times(t)
    np.testing.assert_allclose(new, [0, 15, 15, 15, 75, 15])  # a pause: 5 median intervals of work, then idle
    np.testing.assert_allclose(prev + new, np.r_[0.0, np.diff(t)])


def test_flow_integrates_the_held_load_and_creep_lags_it():
    t = np.array([0.0, 1800.0, 3600.0, 5400.0])
    load = np.array([[2.0], [2.0], [4.0], [4.0]])
    # each interval: half at the previous pose's load, half at the new one's [unit h]
    np.testing.assert_allclose(creep_signal(t, load, "flow")[:, 0], [0.0, 1.0, 2.5, 4.5])
    tau = 60.0 * CREEP_MIN[0]
    y = creep_signal(t, load, f"creep_{CREEP_MIN[0]:g}min")[:, 0]
    e = np.exp(-900.0 / tau)  # half an interval
    assert y[0] == 3.0  # the mean load: what the robot held before is not known
    assert y[1] == pytest.approx(2.0 + (3.0 - 2.0) * e ** 2)
    assert y[2] == pytest.approx((y[1] * e + 2.0 * (1 - e)) * e + 4.0 * (1 - e))
    assert y[3] == pytest.approx(4.0 + (y[2] - 4.0) * e ** 2)


def test_creep_lag_matches_an_ode_solver_over_a_session_with_a_pause():
    q, t = _session(pause_at=25)
    load = np.sin(q[:, :2])  # any (P, 2) load
    tau = 60.0 * 30.0
    prev, new = dwell_times(t)
    y = [load.mean(0)]
    for i in range(1, len(t)):  # the held load: the previous pose's until the switch, then the new one's
        t_switch = t[i - 1] + prev[i]

        def rhs(s, yy, i=i, t_switch=t_switch):
            return (np.where(s < t_switch, load[i - 1], load[i]) - yy) / tau
        sol = solve_ivp(rhs, (t[i - 1], t[i]), y[-1], rtol=1e-10, atol=1e-12, max_step=5.0)
        y.append(sol.y[:, -1])
    np.testing.assert_allclose(creep_signal(t, load, "creep_30min"), np.array(y), atol=1e-7)


@pytest.mark.parametrize("variant", ["flow", "creep_30min"])
def test_held_out_poses_continue_the_training_history(variant):
    """A random split: the held-out poses' signal, run through with the training file's poses in time order, is the
    signal of the whole session at those poses (for the lag, up to its start at the training poses' mean)."""
    q, t = _session(P=50)
    load = np.cos(q[:, :3])
    test = np.arange(3, 50, 4)
    train = np.setdiff1d(np.arange(50), test)
    whole = creep_signal(t, load, variant)
    part = creep_signal(t[test], load[test], variant, history=(t[train], load[train]))
    if variant == "flow":
        np.testing.assert_allclose(part, whole[test], atol=1e-12)
    else:  # the lag starts at the training poses' mean load, the whole session's at its own: linear, so the
        # difference decays from the start with tau
        decay = np.exp(-(t[test] - t[0]) / (60.0 * 30.0))[:, None]
        np.testing.assert_allclose(part - whole[test], (load[train].mean(0) - load.mean(0)) * decay, atol=1e-12)
    same = creep_signal(t, load, variant, history=(t, load))  # the training file itself
    np.testing.assert_array_equal(same, whole)


def test_the_flow_basis_holds_a_flowing_mount_exactly():
    """A support flowing under the held moment, its tilt computed with an ODE solver from the mass model and a payload
    picked up during the session, lies in the ``flow`` basis with its true compliances."""
    q, t = _session(P=30, pause_at=18)
    kg = np.where(np.arange(30) < 12, 0.0, 5.0)
    meas = Measurements(q, np.zeros((30, 3)), payload_kg=kg, time_s=t)
    p = target_points(UR10, q, T_MM)
    Mh = mount_moment(UR10, q, p, kg)
    prev, _ = dwell_times(t)
    held = [np.zeros(3)]
    for i in range(1, 30):
        t_switch = t[i - 1] + prev[i]
        sol = solve_ivp(lambda s, yy, i=i, ts=t_switch: np.where(s < ts, Mh[i - 1], Mh[i]) / 3600.0,
                        (t[i - 1], t[i]), held[-1], rtol=1e-10, atol=1e-10, max_step=10.0)
        held.append(sol.y[:, -1])
    c, f = 2e-7, 5e-8  # [rad/(N m)], [rad/(N m h)]
    truth = np.cross(c * Mh + f * np.array(held), p)
    basis = effect_basis("mount_compliance", UR10, meas, T_MM, effect_reference(meas, robot=UR10), "flow")
    assert basis.names == ("c_mount [rad/(N m)]", "f_mount [rad/(N m h)]")
    np.testing.assert_allclose(basis.B @ np.array([c, f]), truth, atol=1e-6)
    # a held-out file's basis continues the training file's history: the rows of the whole session's
    test = np.arange(2, 30, 5)
    train = np.setdiff1d(np.arange(30), test)
    part = Measurements(q[train], np.zeros((len(train), 3)), payload_kg=kg[train], time_s=t[train])
    held_out = Measurements(q[test], np.zeros((len(test), 3)), payload_kg=kg[test], time_s=t[test])
    B = effect_basis("mount_compliance", UR10, held_out, T_MM, effect_reference(part, robot=UR10), "flow").B
    np.testing.assert_allclose(B, basis.B[test], rtol=1e-12, atol=1e-12)


def test_creep_variants_need_time_in_every_file():
    q, t = _session(P=20)
    timed = Measurements(q, np.zeros((20, 3)), time_s=t)
    untimed = Measurements(q, np.zeros((20, 3)))
    assert set(creep_variants(t)) <= set(variants("mount_compliance", timed))
    assert "flow" in variants("mount_compliance", timed)
    assert not any(v.startswith(("creep", "flow")) for v in variants("mount_compliance", untimed))
    assert carry_problem("mount_compliance", "flow", untimed) == "the test file has no time_s column"
    assert carry_problem("mount_compliance", "tensor", untimed) is None
    back = Measurements(q, np.zeros((20, 3)), time_s=np.r_[t[:-1], t[0]])
    assert carry_problem("mount_compliance", "flow", back, "the program").startswith(
        "the program: time_s is not increasing within the session (pose 20: ")
    with pytest.raises(ValueError, match=r"mount's creep \(variant flow\) needs time_s in every file"):
        effect_basis("mount_compliance", UR10, untimed, T_MM, effect_reference(timed, robot=UR10), "flow")
