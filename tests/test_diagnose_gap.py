"""Residual split of the held-out error (tolalloc.diagnose.gap): a smooth or a local systematic residual is found,
pure noise is not, repeated poses give the noise floor, and the parts add up to the nominal mean square."""

import numpy as np
import pytest

from tolalloc.diagnose.gap import gap_split

REV = np.array([True, True, True])


def _data(rng, P, sys_mm, noise_mm, repeats=0):
    q = rng.uniform(-np.pi, np.pi, (P, 3))
    if repeats:
        q[-repeats:] = q[:repeats]
    s = sys_mm * np.column_stack([np.sin(q[:, 0]) * np.cos(q[:, 1]), np.cos(2 * q[:, 2]), np.sin(q[:, 1] + q[:, 2])])
    return q, s + rng.normal(0, noise_mm, (P, 3))


def _split(rng, sys_mm, noise_mm, repeats=0):
    q, e = _data(rng, 300, sys_mm, noise_mm, repeats)
    qt, et = _data(rng, 100, sys_mm, noise_mm)
    tests = {"nominal": 3 * et, "geometric": 1.5 * et, "final": et}
    return gap_split(q, e, qt, tests, REV), tests


def test_smooth_systematic_residual_is_found_and_parts_add_up():
    g, tests = _split(np.random.default_rng(0), sys_mm=0.2, noise_mm=0.02)
    ms_final = np.mean(np.sum(tests["final"] ** 2, axis=1))
    assert g.systematic_unnamed > 0.8 * (ms_final - 3 * 0.02 ** 2)
    assert g.gp_test_explained > 0.8 and g.gp_loo_explained > 0.8
    total = g.removed_by_geometry + g.removed_by_effect + g.systematic_unnamed + g.noise_floor + g.rest
    assert total == pytest.approx(g.ms_nominal, rel=1e-12)
    assert g.removed_by_geometry == pytest.approx(g.ms_nominal * (1 - 1.5 ** 2 / 9))


def test_pure_noise_has_no_systematic_part():
    g, tests = _split(np.random.default_rng(1), sys_mm=0.0, noise_mm=0.03)
    ms_final = np.mean(np.sum(tests["final"] ** 2, axis=1))
    assert g.systematic_unnamed < 0.1 * ms_final
    assert g.noise_floor == pytest.approx(3 * 0.03 ** 2, rel=0.25)  # the GP noise variance
    assert g.noise_source.startswith("GP noise")


def test_repeated_poses_give_the_noise_floor():
    g, _ = _split(np.random.default_rng(2), sys_mm=0.2, noise_mm=0.02, repeats=60)
    assert g.noise_source.startswith("repeated poses")
    assert g.noise_floor == pytest.approx(3 * 0.02 ** 2, rel=0.35)


def test_local_residual_in_two_of_six_joints_is_found():
    """A residual varying on ~0.15 rad in q1, q2 only (the shape found on the UR10 data): the per-joint length
    scales find it (short in q1, q2, long in the other four) and the GP's noise variance is the noise."""
    rng = np.random.default_rng(0)

    def data(P):
        q = rng.uniform(-1.0, 1.0, (P, 6))
        s = 0.2 * np.column_stack([np.sin(8 * q[:, 0]) * np.cos(6 * q[:, 1]), np.cos(8 * q[:, 0] + 6 * q[:, 1]),
                                   np.sin(6 * q[:, 1])])
        return q, s + rng.normal(0, 0.03, (P, 3))

    (q, e), (qt, et) = data(400), data(150)
    g = gap_split(q, e, qt, {"nominal": 2 * et, "geometric": et, "final": et}, np.ones(6, bool), restarts=2)
    assert g.gp_test_explained > 0.8  # at most ~0.95: MS(systematic) ~0.051, noise 3 * 0.03^2
    assert g.gp_noise_sd_mm == pytest.approx(0.03, rel=0.15)
    assert g.noise_floor == pytest.approx(3 * g.gp_noise_sd_mm ** 2)
    assert max(g.gp_length_scales[:2]) < 0.5 < 5.0 < min(g.gp_length_scales[2:])
