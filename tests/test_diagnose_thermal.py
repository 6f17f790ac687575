"""Time-driven thermal variants (diagnose/thermal.py) and the telescopic-guide deflection (effects.py).

Known answers: the lagged joint activity at constant speed is the closed-form step response; per-link warm-up
growth is recovered from a chain whose links are scaled one by one (independent of the error model's Jacobian);
the guide tilt of the tool_changer's stage on horizontal poses equals the rigid rotation of the target about the
guide point by the hand-computed gravity moment of the masses beyond it."""

import json

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tolalloc
from tolalloc.diagnose.effects import effect_basis, effect_reference, target_points, variants
from tolalloc.physics.loads import G
from tolalloc.diagnose.measurements import Measurements
from tolalloc.physics.thermal import is_air_variant
from tolalloc.physics.thermal_history import activity, time_problem
from tolalloc.robot.model import Link, Robot


def test_time_problems_are_named():
    t = 30.0 * np.arange(20)
    assert time_problem(t) is None
    assert time_problem(None) == "no time_s column"
    assert "not increasing" in time_problem(np.r_[t[:5], t[3:8]])
    assert "another unit" in time_problem(1000.0 * t)  # 30 s steps written in ms
    assert "another unit" in time_problem(3600.0 * 24 * np.arange(5.0))  # one pose a day for 4 days


def test_activity_at_constant_speed_is_the_step_response():
    t = 20.0 * np.arange(200)
    q = np.column_stack([0.01 * t, np.zeros_like(t)])  # joint 1 at 0.01 rad/s, joint 2 still
    tau = 600.0
    act = activity(t, q, tau)
    np.testing.assert_allclose(act[:, 0], 0.01 * (1 - np.exp(-t / tau)), atol=1e-12)
    assert np.all(act[:, 1] == 0)
    perm = np.random.default_rng(0).permutation(len(t))  # row order does not matter, time does
    np.testing.assert_allclose(activity(t[perm], q[perm], tau), act[perm], atol=1e-12)


def _scaled_point(robot, q1, t, eps: dict):
    chain = tuple(Link(el.name, np.asarray(el.vector_mm) * (1 + eps.get(el.name, 0.0))) if hasattr(el, "vector_mm")
                  else el for el in robot.chain)
    grown = Robot(robot.name, chain, tool_offset_mm=robot.tool_offset_mm, tool_rotation=robot.tool_rotation)
    return target_points(grown, q1[None], t)[0]


def test_per_link_warmup_growth_recovered():
    robot = tolalloc.load_robot("tool_changer")
    P = 90
    rng = np.random.default_rng(4)
    q = rng.uniform(np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi), (P, robot.n_joints))
    ts = 30.0 * np.arange(P)
    t = np.array([0.0, 40.0, 60.0])
    g = {"l3": 30.0, "l6": 50.0}  # per-link growth at full warm-up [1e-6] (l1/l2 and l4/l5 are collinear pairs)
    w = 1 - np.exp(-ts / 1800.0)
    d = np.stack([_scaled_point(robot, q[i], t, {k: 1e-6 * v * w[i] for k, v in g.items()}) for i in range(P)]) \
        - target_points(robot, q, t)
    meas = Measurements(q, np.zeros((P, 3)), None, None, None, ts)
    assert "links_warmup_30min" in variants("thermal", meas) and "activity_30min" in variants("thermal", meas)
    basis = effect_basis("thermal", robot, meas, t, effect_reference(meas), "links_warmup_30min")
    beta = np.linalg.lstsq(basis.B.reshape(-1, basis.B.shape[-1]), d.ravel(), rcond=None)[0]
    got = {nm.split(" ")[0][6:]: b for nm, b in zip(basis.names, beta)}
    for k, v in g.items():
        assert got[k] == pytest.approx(v, rel=2e-3)
    assert all(abs(got[k]) < 0.05 for k in got if k not in g)


def test_guide_tilt_is_the_rigid_rotation_by_the_gravity_moment():
    robot = tolalloc.load_robot("tool_changer")
    strokes = np.array([0.0, 150.0, 300.0, 450.0])
    q = np.zeros((4, robot.n_joints))
    q[:, 3] = strokes  # the arm horizontal along +y, the stage extending
    t = np.array([0.0, 0.0, 0.0])
    meas = Measurements(q, np.zeros((4, 3)), payload_kg=np.full(4, 2.0))
    assert "guide" in variants("link_deflection", meas, {}, robot)
    basis = effect_basis("link_deflection", robot, meas, t, {}, "guide")
    pg = robot.joint_points_mm[3]
    c = 2e-8  # rad per N m (tilts of ~3e-5 rad: the first-order basis holds to ~1e-5 of the displacement)
    for i, s in enumerate(strokes):
        # moment about the guide of the masses beyond the stage (bodies 4, 5 move with it) and 2 kg at the target
        p_t = target_points(robot, q[i:i + 1], t)[0]
        arms = [(m.com_mm + [0.0, s, 0.0], m.mass_kg) for m in robot.masses if m.body > 3] + [(p_t, 2.0)]
        M = sum(np.cross((a - pg) / 1000.0, [0.0, 0.0, -kg * G]) for a, kg in arms)
        exact = Rotation.from_rotvec(c * M).apply(p_t - pg) - (p_t - pg)
        got = basis.B[i, :, basis.names.index("g_j4 [rad/(N m)]")] * c
        np.testing.assert_allclose(got, exact, atol=1e-4 * np.linalg.norm(exact))  # first order: angle ~1e-4
        assert exact[2] < 0  # the stage tips down


@pytest.mark.parametrize("warmup", [80e-6, 0.0])
def test_air_drift_and_drive_warmup_together_are_one_combined_variant(warmup):
    """The whole arm grows with the logged air temperature (steel, 11.5e-6 / K) while link l3 warms up with its
    drives (30 min time constant; displacement from scaled chains, not from the effect's columns): neither kind
    alone describes it; the combined variant is chosen and named. With the air alone, no combination is chosen
    (the BIC charges its extra columns)."""
    from tolalloc.diagnose import diagnose

    robot = tolalloc.load_robot("tool_changer")
    P = 120
    rng = np.random.default_rng(7)
    q = rng.uniform(np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi), (P, robot.n_joints))
    ts = 30.0 * np.arange(P)
    temp = 20.0 + 3.0 * np.sin(2 * np.pi * ts / ts[-1])  # one slow swing of the air over the session
    t = np.array([0.0, 40.0, 60.0])
    links = [el.name for el in robot.links if el.length_mm > 0]
    warm = 1 - np.exp(-ts / 1800.0)
    eps = [{nm: 11.5e-6 * (temp[i] - temp.mean()) + (warmup * warm[i] if nm == "l3" else 0.0) for nm in links}
           for i in range(P)]
    xyz = np.stack([_scaled_point(robot, q[i], t, eps[i]) for i in range(P)])
    xyz += rng.normal(0.0, 0.005, xyz.shape)
    meas = Measurements(q, xyz, temp, None, None, ts)
    d = diagnose(robot, meas, folds=3, max_effects=1)
    variant = next(c.variant for c in d.ranking if c.effect == "thermal")
    if not warmup:
        assert variant in ("temperature", "lag_5min")
    else:
        air, work = variant.split("+")
        assert air in ("temperature", "lag_5min") and not is_air_variant(work), variant
    assert d.effect == "thermal"
    assert d.final.heldout_rms_mm < 0.5 * d.geometric.heldout_rms_mm


def _bowed_chain(robot, name: str, axis_home: np.ndarray, theta: float, pieces: int = 400) -> Robot:
    """``robot`` with link ``name`` bent into an arc: ``pieces`` short links, each turned about ``axis_home`` (across
    the link, at home) by the curvature up to its middle, and everything after the link turned by the whole angle
    ``theta`` about its end (the joint axes, later links and the tool): the bowed robot built from its elements,
    independent of :func:`link_bow`."""
    turn = lambda a: Rotation.from_rotvec(axis_home * a).as_matrix()  # noqa: E731
    chain, after = [], False
    for el in robot.chain:
        if isinstance(el, Link) and el.name == name:
            v = np.asarray(el.vector_mm, float)
            chain += [Link(f"{name}_{i}", turn(theta * (i + 0.5) / pieces) @ v / pieces) for i in range(pieces)]
            after = True
        elif after and isinstance(el, Link):
            chain.append(Link(el.name, turn(theta) @ np.asarray(el.vector_mm, float)))
        elif after:
            chain.append(type(el)(el.name, el.kind, turn(theta) @ np.asarray(el.axis, float), el.lower, el.upper,
                                  el.nominal))
        else:
            chain.append(el)
    return Robot(robot.name, tuple(chain), tool_offset_mm=turn(theta) @ robot.tool_offset_mm,
                 tool_rotation=turn(theta) @ robot.tool_rotation, trust_units=True)


def _across(e: np.ndarray) -> tuple:
    """The two unit axes across a link of direction ``e`` (at home) about which :func:`link_bow` orders its bows."""
    a1 = np.cross(e, [1.0, 0.0, 0.0] if abs(e[0]) < 0.9 else [0.0, 1.0, 0.0])
    a1 /= np.linalg.norm(a1)
    return a1, np.cross(e, a1)


@pytest.mark.parametrize("robot_name", ["ur10", "tool_changer"])
def test_link_bow_is_the_tool_shift_of_an_arc_bent_link(robot_name):
    """A uniform curvature along a link (a temperature difference across its section) moves the tool point as the
    robot rebuilt with that link bent into an arc does (first order in the angle; 400 pieces)."""
    from tolalloc.physics.thermal import BOW_MIN_MM, link_bow

    robot = tolalloc.load_robot(robot_name)
    rng = np.random.default_rng(3)
    q = rng.uniform(np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi), (5, robot.n_joints))
    B, names = link_bow(robot, q)
    long_links = [lk.name for lk in robot.links if lk.length_mm >= BOW_MIN_MM]
    assert names == tuple(long_links) and B.shape == (5, 3, 2 * len(names)) and len(names) >= 2
    theta = 2e-4  # 200 urad: the second-order term is ~theta^2 L ~ 1e-5 mm
    for i, name in enumerate(names):
        v = np.asarray(next(lk for lk in robot.links if lk.name == name).vector_mm, float)
        for k, axis in enumerate(_across(v / np.linalg.norm(v))):
            bent = _bowed_chain(robot, name, axis, theta)
            exact = bent.fk_internal(q)[:, :3, 3] - robot.fk_internal(q)[:, :3, 3]
            np.testing.assert_allclose(B[:, :, 2 * i + k] * theta / 1e-6, exact, atol=2e-3 * np.abs(exact).max())
            assert np.abs(exact).max() > 0.01  # a measurable bow: 200 urad over a long link


def test_a_link_bowing_as_it_warms_up_is_diagnosed_as_thermal_bow():
    """The UR10's upper arm bows across its section as its drive warms it (400 urad at full warm-up, 30 min time
    constant; the poses from the robot rebuilt with the arc-bent link, not from the effect's columns): the diagnosis
    names thermal in a bow variant and recovers the bow about the right axis (its size within 25 %: the variant's time
    constant is chosen on a grid, here 45 min), which no growth-only variant describes."""
    from tolalloc.diagnose import diagnose

    robot = tolalloc.load_robot("ur10")
    P = 120
    rng = np.random.default_rng(11)
    q = rng.uniform(np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi), (P, robot.n_joints))
    ts = 30.0 * np.arange(P)
    t = np.array([0.0, 30.0, 50.0])
    link = max(robot.links, key=lambda lk: lk.length_mm)
    axis = _across(np.asarray(link.vector_mm, float) / link.length_mm)[0]
    theta = 400e-6 * (1 - np.exp(-ts / 1800.0))
    xyz = np.stack([target_points(_bowed_chain(robot, link.name, axis, theta[i], pieces=40), q[i:i + 1], t)[0]
                    for i in range(P)])
    xyz += rng.normal(0.0, 0.005, xyz.shape)
    d = diagnose(robot, Measurements(q, xyz, None, None, None, ts), folds=3, max_effects=1)
    assert d.effect == "thermal", d.verdict
    variant = next(c.variant for c in d.ranking if c.effect == "thermal")
    assert variant.startswith("bow_"), variant
    # no temperature column drives a bow: the reasons say the time alone does, and what else could
    assert any("time since the session's start alone" in r and "creep, a leak" in r and "a step at a pause" in r
               for r in d.verdict.reasons)
    params = d.final.fit.parameters_frame().set_index("parameter")["value"]
    bow = params[[n for n in params.index if n.startswith(f"thermal:bow_{link.name}_")]]
    assert len(bow) == 2 and 300 < bow.iloc[0] < 500 and abs(bow.iloc[1]) < 30, bow  # the bow about the true axis
    assert d.final.heldout_rms_mm < 0.25 * d.geometric.heldout_rms_mm
    # the identified model written to its file and read back predicts the bowed arm at new poses and times alike
    from tolalloc.diagnose.model_export import identified_section, model_from_identified
    from tolalloc.diagnose.model_use import identified_model

    m = identified_model(d)
    back = model_from_identified(json.loads(json.dumps(identified_section(m))), robot)
    q_new, t_new = q[::7] + 0.1, ts[::7] + 15.0
    a, b = (x.points(x.measurements(q_new, time_s=t_new), "tracker") for x in (m, back))
    np.testing.assert_allclose(b, a, atol=1e-9)
    later = m.points(m.measurements(q_new, time_s=t_new + 7200.0), "tracker")
    assert np.abs(later - a).max() > 0.05  # the bow is in the prediction: two hours later the arm is warmer


def _tilted_chain(robot: Robot, joint: str, axis_home: np.ndarray, theta: float) -> Robot:
    """``robot`` with joint ``joint``'s axis and everything it carries (later links and joints, the tool) turned by
    ``theta`` about ``axis_home`` (at home) through the joint's point: a tilted bearing seat, built from the chain's
    elements, independent of :func:`axis_tilt`."""
    R = Rotation.from_rotvec(axis_home * theta).as_matrix()
    chain, after = [], False
    for el in robot.chain:
        after = after or (not isinstance(el, Link) and el.name == joint)
        if after and isinstance(el, Link):
            chain.append(Link(el.name, R @ np.asarray(el.vector_mm, float)))
        elif after:
            chain.append(type(el)(el.name, el.kind, R @ np.asarray(el.axis, float), el.lower, el.upper, el.nominal))
        else:
            chain.append(el)
    return Robot(robot.name, tuple(chain), tool_offset_mm=R @ robot.tool_offset_mm,
                 tool_rotation=R @ robot.tool_rotation, trust_units=True)


@pytest.mark.parametrize("robot_name", ["ur10", "tool_changer"])
def test_axis_tilt_is_the_tool_shift_of_a_tilted_bearing_seat(robot_name):
    """A joint axis tilted about an axis across it (a housing grown more on one side) moves the tool point as the robot
    rebuilt with that axis and everything after it turned does (first order in the angle); prismatic joints have no
    tilt column."""
    from tolalloc.physics.thermal import axis_tilt

    robot = tolalloc.load_robot(robot_name)
    rng = np.random.default_rng(4)
    q = rng.uniform(np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi), (5, robot.n_joints))
    B, names = axis_tilt(robot, q)
    revolute = [jt for jt in robot.joints if jt.is_revolute]
    assert B.shape == (5, 3, 2 * len(revolute)) and len(names) == B.shape[2]
    theta = 1e-4
    for i, jt in enumerate(revolute):
        assert names[2 * i] == f"tilt_{jt.name}_u [urad]"
        for k, axis in enumerate(_across(np.asarray(jt.axis, float) / np.linalg.norm(jt.axis))):
            exact = _tilted_chain(robot, jt.name, axis, theta).fk_internal(q)[:, :3, 3] - robot.fk_internal(q)[:, :3, 3]
            # (a wrist axis through the tool point: no shift, to round-off)
            np.testing.assert_allclose(B[:, :, 2 * i + k] * theta / 1e-6, exact,
                                       atol=max(2e-3 * np.abs(exact).max(), 1e-9))


def test_duty_warmup_heats_while_working_and_cools_in_a_pause():
    """The warm-up of a heat source that is on while the robot works: the step response 1 - exp(-t / tau) over
    uninterrupted work, then, over a gap of 65 median intervals, 5 intervals more of heating and a cooling by
    exp(-60 / tau) (in intervals); the poses' order does not matter."""
    from tolalloc.physics.thermal_history import PAUSE_STEPS, duty_warmup

    tau = 600.0
    t = np.concatenate([10.0 * np.arange(50), 490.0 + 650.0 + 10.0 * np.arange(10)])
    y = duty_warmup(t, tau)
    np.testing.assert_allclose(y[:50], 1 - np.exp(-t[:50] / tau), rtol=1e-12)
    hot = 1 - np.exp(-(490.0 + PAUSE_STEPS * 10.0) / tau)
    np.testing.assert_allclose(y[50], hot * np.exp(-(650.0 - PAUSE_STEPS * 10.0) / tau), rtol=1e-12)
    assert y[50] < y[49] and np.all(np.diff(y[50:]) > 0)
    perm = np.random.default_rng(0).permutation(len(t))
    np.testing.assert_allclose(duty_warmup(t[perm], tau), y[perm], rtol=1e-12)


def test_an_axis_tilting_as_the_robot_works_is_diagnosed_as_thermal_tilt():
    """The UR10's shoulder axis tilts by up to 300 urad as its housing warms while the robot works (20 min time
    constant) and back in two pauses of 40 min (the poses from the robot rebuilt with the tilted axis, not from the
    effect's columns): the diagnosis names thermal in a tilt variant and recovers the tilt about the right axis; the
    identified model refuses to be written without the session's history."""
    from tolalloc.diagnose import diagnose
    from tolalloc.diagnose.model_export import identified_section
    from tolalloc.diagnose.model_use import identified_model
    from tolalloc.physics.thermal_history import duty_warmup

    robot = tolalloc.load_robot("ur10")
    P = 120
    rng = np.random.default_rng(12)
    q = rng.uniform(np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi), (P, robot.n_joints))
    ts = 20.0 * np.arange(P) + 2400.0 * (np.arange(P) >= 40) + 2400.0 * (np.arange(P) >= 80)
    joint = robot.joints[1]
    axis = _across(np.asarray(joint.axis, float))[0]
    theta = 300e-6 * duty_warmup(ts, 1200.0)
    t = np.array([0.0, 30.0, 50.0])
    xyz = np.stack([target_points(_tilted_chain(robot, joint.name, axis, theta[i]), q[i:i + 1], t)[0]
                    for i in range(P)])
    xyz += rng.normal(0.0, 0.005, xyz.shape)
    d = diagnose(robot, Measurements(q, xyz, None, None, None, ts), folds=3, max_effects=1)
    assert d.effect == "thermal", d.verdict
    variant = next(c.variant for c in d.ranking if c.effect == "thermal")
    assert variant.startswith("tilt_"), variant
    params = d.final.fit.parameters_frame().set_index("parameter")["value"]
    tilt = params[[n for n in params.index if n.startswith(f"thermal:tilt_{joint.name}_")]]
    assert len(tilt) == 2 and 200 < tilt.iloc[0] < 400 and abs(tilt.iloc[1]) < 40, tilt
    assert d.final.heldout_rms_mm < 0.4 * d.geometric.heldout_rms_mm  # to 1.1x the noise floor (0.0087 mm)
    with pytest.raises(tolalloc.TolallocError, match="history"):
        from tolalloc.diagnose.model_export import model_from_identified
        model_from_identified(json.loads(json.dumps(identified_section(identified_model(d)))), robot)


def test_frame_drift_columns_are_a_translation_of_the_measuring_frame():
    """frame_drift: three translations of 1 um, the same at every pose, named as the measuring frame's columns."""
    from tolalloc.physics.thermal import MEASUREMENT_PREFIX, frame_drift, is_measurement_column

    B, names = frame_drift(4)
    assert B.shape == (4, 3, 3) and all(is_measurement_column(n) for n in names)
    assert names == tuple(f"{MEASUREMENT_PREFIX}{a} [um]" for a in "xyz")
    np.testing.assert_array_equal(B, np.broadcast_to(1e-3 * np.eye(3), (4, 3, 3)))
    assert not is_measurement_column("alpha [1e-6/K] (warmup_30min)")


def test_a_tracker_warming_up_is_named_as_a_drift_of_the_frames_and_left_out_of_the_robot():
    """The measuring frame drifts by 0.12 mm over a 40 min warm-up (the robot itself unchanged): the diagnosis names
    thermal in a drift variant, says what it means, and the identified model's base-frame points do not move with
    time while its tracker-frame points do."""
    from tolalloc.diagnose import diagnose
    from tolalloc.diagnose.model_use import identified_model

    robot = tolalloc.load_robot("ur10")
    P = 120
    rng = np.random.default_rng(13)
    q = rng.uniform(np.maximum(robot.lower, -np.pi), np.minimum(robot.upper, np.pi), (P, robot.n_joints))
    ts = 30.0 * np.arange(P)
    x = target_points(robot, q, np.array([0.0, 30.0, 50.0]))
    s = 1 - np.exp(-ts / 2400.0)
    xyz = x + np.outer(s, [0.08, -0.06, 0.07]) + rng.normal(0.0, 0.005, (P, 3))
    d = diagnose(robot, Measurements(q, xyz, None, None, None, ts), folds=3, max_effects=1)
    assert d.effect == "thermal", d.verdict
    variant = next(c.variant for c in d.ranking if c.effect == "thermal")
    assert variant.startswith("drift_"), variant
    assert any("the measuring frame and the robot's base drift apart" in r for r in d.verdict.reasons)
    m = identified_model(d)
    early, late = (m.measurements(q[:10], time_s=t + 10.0 * np.arange(10)) for t in (0.0, 7200.0))
    np.testing.assert_allclose(m.points(late, "base"), m.points(early, "base"), atol=1e-12)
    assert np.abs(m.points(late, "tracker") - m.points(early, "tracker")).max() > 0.05


def test_clock_variants_are_the_time_driven_ones():
    from tolalloc.physics.thermal import is_clock_variant

    assert all(is_clock_variant(v) for v in ("warmup_45min", "links_warmup_30min", "bow_120min",
                                             "warmup_10min+bow_60min"))
    assert not any(is_clock_variant(v) for v in ("temperature", "drift_240min", "activity_5min", "ambient_lag_30min",
                                                 "temperature+warmup_10min", "held_15min"))
