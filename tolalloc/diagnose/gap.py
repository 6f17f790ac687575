"""How far the held-out error could still shrink: split it into geometry, effect, unnamed-systematic and noise.

On the held-out (test) poses, in mean squares (3-D error, mm^2), so that the parts add up::

    MS(nominal) = removed_by_geometry + removed_by_effect + systematic_unnamed + noise_floor + rest

* ``removed_by_geometry = MS(nominal) - MS(geometric)``, ``removed_by_effect = MS(geometric) - MS(final)``
  (negative when a model made the held-out error worse -- reported as is);
* ``systematic_unnamed``: the part of the final residual a Gaussian process on the joint values predicts on
  the held-out poses, ``MS(final) - MS(final - prediction)`` (clipped at 0). The GP
  (:mod:`tolalloc.diagnose.gp`) has one length scale per joint (inputs: the joint values themselves [rad, mm],
  standardised) and a noise variance, shared by the three coordinates, all fitted by maximum marginal
  likelihood on the **training** poses' out-of-fold final residuals only (on at most ``max_fit`` of them, a
  seeded random subset; the posterior is conditioned on all training poses);
* ``noise_floor``: from repeated poses when the data has them (pairs closer than ``repeat_tol`` in
  :func:`joint_features`: half the mean squared difference of their residuals), else the GP's fitted noise
  variance, ``3 s_n^2`` (a likelihood estimate of the non-systematic part; it also holds any systematic error
  that varies faster than the training poses resolve);
* ``rest``: what is left (``MS(final)`` minus the two above; negative when the noise estimate is too high).

Also reported: the share of the held-out final residual the GP removes and the share of the training residual
its leave-one-out predictions explain (a random-fold CV; on a time-ordered session a local residual can be
predictable from neighbours in joint space yet not from a contiguous block of time).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.diagnose.gp import GPFit, fit_gp

__all__ = ["GapSplit", "gap_split", "diagnosis_gap_split", "joint_features", "fit_residual_gp"]

#: At most this many training poses fit the GP's hyper-parameters (seeded random subset).
MAX_FIT = 1000
#: L-BFGS-B starts of the hyper-parameter fit.
RESTARTS = 3


def joint_features(q: np.ndarray, revolute: np.ndarray, stroke_mm: np.ndarray | None = None) -> np.ndarray:
    """Features of joint values ``q`` (P, n) [rad, mm]: ``cos, sin`` per revolute joint, ``q / stroke`` per prismatic."""
    cols = []
    for j in range(q.shape[1]):
        if revolute[j]:
            cols += [np.cos(q[:, j]), np.sin(q[:, j])]
        else:
            s = 1.0 if stroke_mm is None else max(float(stroke_mm[j]), 1e-9)
            cols.append(q[:, j] / s)
    return np.column_stack(cols)


def _ms(e):
    return float(np.mean(np.sum(e ** 2, axis=1)))


def fit_residual_gp(q_train: np.ndarray, e_train: np.ndarray, *, max_fit: int = MAX_FIT, restarts: int = RESTARTS,
                    seed: int = 0) -> GPFit:
    """The GP of the module docstring: residuals ``e_train`` (P, 3) [mm] on joint values ``q_train`` (P, n) [rad, mm].

    Its ``length_scales`` (n,) are per joint [rad, mm]; ``noise_sd`` and ``signal_sd`` per coordinate [mm].
    """
    return fit_gp(np.asarray(q_train, float), np.asarray(e_train, float), restarts=restarts, max_fit=max_fit,
                  seed=seed)


@dataclass(frozen=True)
class GapSplit:
    """Held-out mean-square error split (see the module docstring); all values [mm^2] unless noted.

    Attributes
    ----------
    ms_nominal, removed_by_geometry, removed_by_effect, systematic_unnamed, noise_floor, rest : float
    noise_source : str              ``repeated poses (...)`` or ``GP noise variance (...)``
    gp_test_explained : float       ``systematic_unnamed / MS(final)``: share of the held-out final residual the
        GP removes (0-1)
    gp_loo_explained : float        share of the training residual's MS (about its mean) the GP's
        leave-one-out predictions explain (0-1; negative when they make it worse)
    gp_noise_sd_mm, gp_signal_sd_mm : float   the GP's fitted noise and signal sd per coordinate [mm]
    gp_length_scales : tuple of float          the GP's length scale per joint [rad, mm]
    gp_fit_poses : int              training poses the GP's hyper-parameters were fitted on
    """

    ms_nominal: float
    removed_by_geometry: float
    removed_by_effect: float
    systematic_unnamed: float
    noise_floor: float
    rest: float
    noise_source: str
    gp_test_explained: float
    gp_loo_explained: float
    gp_noise_sd_mm: float
    gp_signal_sd_mm: float
    gp_length_scales: tuple
    gp_fit_poses: int

    def to_frame(self):
        import pandas as pd

        parts = ["removed_by_geometry", "removed_by_effect", "systematic_unnamed", "noise_floor", "rest"]
        vals = [getattr(self, p) for p in parts]
        return pd.DataFrame({"part": parts, "ms_mm2": vals, "rms_equiv_mm": np.sign(vals) * np.sqrt(np.abs(vals)),
                             "share_of_nominal_pct": [100 * v / self.ms_nominal for v in vals]})

    def to_dict(self) -> dict:
        conv = {str: str, tuple: list, int: int}
        return {k: conv.get(type(v), float)(v) for k, v in self.__dict__.items()}


def _repeat_pairs(X: np.ndarray, tol: float):
    """Index pairs (i < j) of rows of ``X`` closer than ``tol``."""
    from scipy.spatial import cKDTree

    pairs = np.array(sorted(cKDTree(X).query_pairs(tol)), dtype=int).reshape(-1, 2)
    return pairs[:, 0], pairs[:, 1]


def gap_split(q_train, e_train_final, q_test, e_test: dict, revolute, *, stroke_mm=None, repeat_tol: float = 1e-3,
              seed: int = 0, max_fit: int = MAX_FIT, restarts: int = RESTARTS) -> GapSplit:
    """Split the held-out error (see the module docstring).

    Parameters
    ----------
    q_train : array, shape (P, n) [rad, mm]
    e_train_final : array, shape (P, 3) [mm]   out-of-fold residuals of the final model on the training poses
    q_test : array, shape (T, n)
    e_test : dict with ``nominal``, ``geometric``, ``final`` residual arrays, shape (T, 3) [mm], in the same
        frame as ``e_train_final``
    revolute : array of bool, shape (n,)
    stroke_mm : array, shape (n,), optional   range of each prismatic joint (repeat detection scaling)
    repeat_tol : float                        repeat distance in :func:`joint_features` units
    seed, max_fit, restarts :                 of the GP fit (:func:`fit_residual_gp`)
    """
    e_train_final = np.asarray(e_train_final, float)
    gp = fit_residual_gp(q_train, e_train_final, max_fit=max_fit, restarts=restarts, seed=seed)
    ms_f = _ms(e_test["final"])
    systematic = max(ms_f - _ms(e_test["final"] - gp.predict(q_test)), 0.0)
    loo_explained = 1.0 - _ms(gp.loo_residual) / max(_ms(e_train_final - e_train_final.mean(0)), 1e-300)
    i, j = _repeat_pairs(joint_features(np.asarray(q_train, float), revolute, stroke_mm), repeat_tol)
    if len(i) >= 3:
        noise = 0.5 * _ms(e_train_final[i] - e_train_final[j])
        source = f"repeated poses ({len(i)} pairs)"
    else:
        noise = 3 * gp.noise_sd ** 2
        source = f"GP noise variance (no repeated poses; s_n = {gp.noise_sd:.3f} mm per coordinate)"
    ms_n, ms_g = _ms(e_test["nominal"]), _ms(e_test["geometric"])
    return GapSplit(ms_n, ms_n - ms_g, ms_g - ms_f, systematic, noise, ms_f - systematic - noise, source,
                    systematic / max(ms_f, 1e-300), float(loo_explained), gp.noise_sd, gp.signal_sd,
                    tuple(float(v) for v in gp.length_scales), gp.n_fit)


def diagnosis_gap_split(d, **kw) -> GapSplit:
    """:func:`gap_split` of a diagnosis's scored test poses (a :class:`tolalloc.diagnose.pipeline.Diagnosis` with a
    test file). Residuals are rotated into the robot's base frame, since a re-registered test file has its own
    tracker frame; the GP is trained on the training poses' out-of-fold final residuals. ``kw`` go to
    :func:`gap_split`.
    """
    if d.test is None:
        raise ValueError("the gap split needs a test file: it splits the held-out test error")
    R_test = d.registered.R if d.registered is not None else d.final.fit.R
    e_test = {"nominal": d.nominal.test_mm, "geometric": d.geometric.test_mm, "final": d.final.test_mm @ R_test}
    return gap_split(d.train.q, d.final.oof_mm @ d.final.fit.R, d.test.q[d.scored_index], e_test,
                     d.robot.revolute_mask, **kw)
