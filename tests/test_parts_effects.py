"""The bought parts' effects in the error model: closed forms, the physical draws against the linear terms' moments,
the systematic / random split, and the conditions' checks."""

import numpy as np
import pytest

import tolalloc
from tolalloc.errormodel.parts import Conditions, PartEffects, with_parts
from tolalloc.errormodel.parts_sample import sample_effects
from tolalloc.physics.bearings import runout_sd, runout_values
from tolalloc.physics.transmission import catalogue_amplitudes, transmission_error
from tolalloc.robot.components import ARCMIN, Bearing

from parts_robot import arm


CHOICE = {("j1", "reducer"): "HD-CSG-17-100", ("j1", "bearing"): "ISO492-P0", ("j2", "reducer"): "HD-CSG-14-100-SA"}


@pytest.fixture(scope="module")
def loaded(tmp_path_factory):
    return arm(tmp_path_factory.mktemp("arm"))


@pytest.fixture(scope="module")
def robot(loaded):
    return with_parts(loaded, CHOICE)


def test_bearing_runout_draws_have_the_closed_form_moments():
    b = Bearing("P0", span_mm=40.0, bore_mm=60.0, radial_runout=0.020)
    v = runout_values(b, np.random.default_rng(0).uniform(0, 2 * np.pi, (40000, 2)))
    sd = runout_sd(b)
    np.testing.assert_allclose(sd, [0.005, 0.005, 0.00025, 0.00025])  # eps / 2 and eps / span, eps = Kia / 2
    np.testing.assert_allclose(v.std(axis=0), sd, rtol=0.02)
    assert np.abs(np.corrcoef(v.T) - np.eye(4)).max() < 0.02  # uncorrelated


def test_gear_amplitudes_keep_the_catalogue_peak_to_peak():
    orders, amps = catalogue_amplitudes(1.0 * ARCMIN, 100)
    assert tuple(orders) == (1.0, 100.0, 200.0) and amps.sum() == pytest.approx(0.5 * ARCMIN)
    q = np.linspace(0, 2 * np.pi, 200001)
    e = transmission_error(q, orders, amps, np.array([0.3, 1.1, 2.0]))
    assert np.ptp(e) <= 1.0 * ARCMIN * (1 + 1e-9)


def test_terms_closed_forms_and_output_side_loop(robot):
    q = np.deg2rad([[0.0, 0.0, 0.0]])
    cond = Conditions((0.0, 1.0), (20.0, 30.0), reference_c=20.0, duty=0.0)
    fx = PartEffects(robot, q, [1.0], [30.0], cond)
    T = fx.terms()
    red = robot.components.joint("j2").reducer
    w = T.mean[0, T.names.index("windup_j2")]
    assert w == pytest.approx(red.deflection(fx.tau[0, 1]))  # the catalogue curve at the gravity load
    # j2's load: fore arm 1.5 kg at 125 mm and 1 kg at the tool, 250 mm out, about -y (gravity -z)
    assert abs(fx.tau[0, 1]) == pytest.approx(9.81 * (1.5 * 0.125 + 1.0 * 0.25), rel=1e-9)
    g = T.mean[0, T.names.index("thermal_upper")]  # aluminium, 10 K above the reference, duty 0: alpha dT L
    assert g == pytest.approx(23.1e-6 * 10 * 300)
    assert T.of_effect("lost_motion").rnd_sd[0, 0] == pytest.approx(red.lost_motion / 2)
    # a motor-side encoder's error reaches the output divided by the ratio, once per motor turn (order N)
    enc = robot.components.joint("j2").encoder
    e = fx.encoder_terms(1, enc, red.ratio)
    assert e.sys_sd[0, 0] == pytest.approx(enc.accuracy / 2 / red.ratio / np.sqrt(2))
    # an output-side encoder closes the loop on the output: the gear's terms vanish
    assert not fx.reducer_terms(1, red, loop_on_motor=False).names


def test_physical_draws_match_the_linear_moments(robot):
    q = np.deg2rad([[10.0, -40.0, 30.0]])
    fx = PartEffects(robot, q, [1.0], [28.0], Conditions((0.0, 1.0), (15.0, 30.0)))
    T = fx.terms()
    for after in ("none", "compensation"):
        m, C = T.moments(after)
        v, d = sample_effects(fx, 0, 30000, np.random.default_rng(2), after=after)
        x = v @ fx.J[0].T + d
        se = np.sqrt(np.diag(C[0]) / len(x))
        assert np.all(np.abs(x.mean(0) - m[0]) <= 4 * se + 0.02 * np.abs(m[0]))  # 1/k of the drawn stiffness: ~1 %
        np.testing.assert_allclose(np.cov(x.T), C[0], rtol=0.06, atol=0.03 * np.abs(C[0]).max())
    sys_, rnd = T.systematic_covariance(), T.random_covariance()
    np.testing.assert_allclose(T.moments("none")[1], sys_ + rnd)
    assert np.trace(rnd[0]) > 0 and set(T.of_effect("lost_motion").names) <= set(T.names)


def test_conditions_are_checked(robot, loaded):
    with pytest.raises(tolalloc.TolallocError, match=r"payload_kg: 5 kg is above the rated payload of robot 'arm3' "
                                                     r"\(1 kg, \[components.payload\] rated_kg\); give a range up "
                                                     r"to 1 kg"):
        Conditions((0, 5)).check(robot)
    with pytest.raises(tolalloc.TolallocError, match=r"ambient_c: expected a range low <= high"):
        Conditions((0, 1), (30, 20)).check(robot)
    with pytest.raises(tolalloc.TolallocError, match=r"j1.bearing: no part chosen; options: ISO492-P0, ISO492-P5"):
        with_parts(loaded, {("j1", "reducer"): "HD-CSG-17-100"})


def test_beam_sag_equals_an_independent_quadrature_on_folded_and_loaded_arms():
    """The closed-form cantilever integrals against the study's independent simulation (its own DH kinematics, masses
    read from the file, numerical quadrature along each tube): every carried mass and the payload at its centre of
    mass, bending, torsion and shear; poses where the folded wrist hangs back over the forearm included."""
    import sys
    from pathlib import Path

    from tolalloc.physics.beams import beam_sag
    from tolalloc.physics.loads import target_points

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies" / "bought_components"))
    from independent import UR10Sim

    robot = tolalloc.load_robot("ur10")
    q = np.vstack([np.deg2rad([[10, -135, -35, -55, 65, 0], [0, -60, 150, -170, 90, 0]]),
                   robot.random_q(np.random.default_rng(3), 6)])
    tool = target_points(robot, q, np.zeros(3))
    sim = UR10Sim({}, Conditions((0.0, 10.0), (15.0, 30.0), 20.0, 0.5))
    for kg in (0.0, 7.5):
        at = tool + robot.fk_internal(q)[:, :3, :3] @ robot.components.payload.com_mm
        lib = beam_sag(robot, q, tool, np.full(len(q), kg), at)
        np.testing.assert_allclose(lib, sim.bending(q, kg), atol=2e-5 * np.abs(lib).max())


def test_a_screw_errs_over_its_stroke_not_over_2_pi_mm():
    """A ball screw's catalogue travel deviation is one half-wave over the joint's stroke (order pi / stroke in
    rad/mm, amplitude half the peak-to-peak), so two poses a few mm apart on the stroke keep nearly the same error in
    the acceptance test's kernel; a missing stroke is refused."""
    from tolalloc.acceptance.parts import _periodic_kernel
    from tolalloc.errormodel.parts import gear_harmonics, stroke_of, with_parts
    from tolalloc.exceptions import TolallocError
    from tolalloc.robot.io import load_robot

    robot = load_robot("tool_changer")
    robot = with_parts(robot, {k: s.options[0].name for k, s in robot.components.slots.items()})
    j = next(i for i, jt in enumerate(robot.joints) if not jt.is_revolute)
    red = robot.components.joint(robot.joints[j].name).reducer
    S = stroke_of(robot, j)
    assert S == pytest.approx(robot.upper[j] - robot.lower[j]) and S > 100
    orders, amps = gear_harmonics(red, False, S)
    np.testing.assert_allclose(orders, [np.pi / S])
    np.testing.assert_allclose(amps, [red.transmission_accuracy / 2])
    q = np.tile(0.5 * (robot.lower + robot.upper), (3, 1))
    q[:, j] += np.array([0.0, 5.0, S / 2])                                   # 5 mm and half the stroke apart
    K = _periodic_kernel(robot, j, "transmission", q)
    a2 = amps[0] ** 2 / 2
    np.testing.assert_allclose(K[0], a2 * np.cos(np.pi / S * (q[0, j] - q[:, j])), rtol=1e-12)
    assert K[0, 1] > 0.99 * a2 and abs(K[0, 2]) < 1e-9 * a2
    with pytest.raises(TolallocError, match="stroke"):
        gear_harmonics(red, False, None)
