"""Blocked cross-validation folds (issue 15 item 3) and the clipped statistic of the selection."""

import numpy as np
import pytest

from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.select import clip_level, make_folds, robust_rms


def _meas(P=53, n=4, seed=0, repeats=()):
    q = np.random.default_rng(seed).uniform(-2, 2, (P, n))
    for a, b in repeats:  # row b repeats the pose of row a
        q[b] = q[a]
    return Measurements(q, np.zeros((P, 3)))


def _is_partition(folds, P):
    allidx = np.sort(np.concatenate(folds))
    return np.array_equal(allidx, np.arange(P))


@pytest.mark.parametrize("k", [2, 3, 5, 7])
def test_time_blocks_are_contiguous_and_partition(k):
    folds = make_folds(_meas(), k, "time")
    assert len(folds) == k and _is_partition(folds, 53)
    for f in folds:
        assert np.array_equal(f, np.arange(f[0], f[-1] + 1))  # one contiguous run of rows
    sizes = [len(f) for f in folds]
    assert max(sizes) - min(sizes) <= 1
    default = make_folds(_meas(), k)  # "blocked": the time blocks (the joint-space blocks are added by the context)
    assert all(np.array_equal(a, b) for a, b in zip(default, folds))


def test_joint_blocks_are_regions_of_joint_space():
    m = _meas(P=80)
    folds = make_folds(m, 4, "joint", seed=1)
    assert _is_partition(folds, 80)
    z = (m.q - m.q.min(0)) / np.ptp(m.q, axis=0)
    cent = np.array([z[f].mean(0) for f in folds])
    for i, f in enumerate(folds):  # every pose is nearest to its own block's centre (Voronoi cells: contiguous)
        assert np.all(np.argmin(((z[f][:, None] - cent[None]) ** 2).sum(-1), axis=1) == i)


@pytest.mark.parametrize("scheme", ["time", "joint", "random"])
def test_repeated_poses_stay_in_one_fold(scheme):
    m = _meas(repeats=[(3, 4), (10, 30), (11, 50)])
    folds = make_folds(m, 5, scheme, seed=2)
    where = np.zeros(53, int)
    for i, f in enumerate(folds):
        where[f] = i
    assert where[3] == where[4] and where[10] == where[30] and where[11] == where[50]


def test_random_only_on_request_and_bad_scheme():
    folds = make_folds(_meas(), 5, "random", seed=0)
    assert _is_partition(folds, 53)
    assert not all(np.array_equal(f, np.arange(f[0], f[-1] + 1)) for f in folds)
    with pytest.raises(ValueError, match="cv: expected one of"):
        make_folds(_meas(), 5, "shuffled")


def test_clipped_rms_outliers_neither_hide_nor_fake():
    rng = np.random.default_rng(0)
    base = rng.normal(0, 0.05, (200, 3))
    clip = clip_level(base)
    assert clip == pytest.approx(2.5 * np.median(np.linalg.norm(base, axis=1)))
    # three gross outliers change the plain RMS by > 2x but the clipped one by < 10 %
    bad = base.copy()
    bad[[5, 50, 150]] += 3.0
    plain = lambda r: np.sqrt(np.mean(np.sum(r ** 2, 1)))  # noqa: E731
    assert plain(bad) > 2 * plain(base)
    assert robust_rms(bad, clip) < 1.1 * robust_rms(base, clip)
    # a real 30 % reduction of the error still shows as ~30 % on the clipped statistic
    assert 1 - robust_rms(0.7 * bad, clip) / robust_rms(bad, clip) == pytest.approx(0.3, abs=0.03)


def test_test_file_basis_keeps_the_training_columns():
    """A column the test poses do not excite (e.g. gravity-held backlash of a joint whose torque keeps its sign on
    the test file) is kept as zeros, so the fitted parameters line up with the test basis column by column."""
    from tolalloc.diagnose.effects import EffectBasis
    from tolalloc.diagnose.select import align_basis

    b = EffectBasis("backlash", ("b_j1 [rad]", "b_j3 [rad]"), np.arange(12.0).reshape(2, 3, 2), "gravity")
    a = align_basis(b, ("b_j1 [rad]", "b_j2 [rad]", "b_j3 [rad]"))
    assert a.names == ("b_j1 [rad]", "b_j2 [rad]", "b_j3 [rad]") and a.B.shape == (2, 3, 3)
    assert np.all(a.B[:, :, 1] == 0)
    assert np.array_equal(a.B[:, :, 0], b.B[:, :, 0]) and np.array_equal(a.B[:, :, 2], b.B[:, :, 1])
