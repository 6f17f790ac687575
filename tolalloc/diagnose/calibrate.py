"""Geometric calibration: tracker registration, target offset and identifiable geometric errors.

Model of a measured point (tracker frame)::

    x_i = R ( T(q_i + dq; delta) [t; 1] + B_i beta ) + p

``R, p`` the registration (tracker <- robot base, 6), ``t`` the target offset on the flange (3, flange
frame), ``delta`` the identifiable geometric error parameters (exact perturbed chain) of the calibration model
-- by default the complete, minimal model of :mod:`tolalloc.diagnose.geometry` (4 line errors per revolute
joint, 2 per prismatic joint, joint offsets; the paper's tolerance model of :mod:`tolalloc.errormodel.model`
can still be passed as ``model``) -- and ``B_i beta`` an optional linear effect correction
(:mod:`tolalloc.diagnose.effects`).

The fit starts from a point-set alignment (Kabsch, via ``Rotation.align_vectors``) of the nominal flange
points to the measured points -- any tracker orientation works -- then solves robust nonlinear least
squares (Levenberg-Marquardt on normal equations accumulated chunk by chunk, :mod:`.scale`; first a plain fit,
then ``soft_l1`` loss with a scale of 3 robust standard deviations, applied to the measurement rows only). MAP: the second pass adds a Gaussian
prior ``N(0, model.sigma)`` on the fitted geometric parameters (see :func:`fit_model`). The Jacobian is analytic: the first-order error Jacobian of the nominal model
for ``delta`` (exact up to second order), exact for ``R, p, t, beta``.

Identifiability: the geometric columns, normalised to unit norm, are projected off the registration
and offset columns; a pivoted QR keeps a column while the part of it not explained by the columns kept
before is at least ``tol`` (default 1e-3) of its norm. The rest, and the SVD null-space combinations of
the projected columns, are reported as unidentifiable and not fitted, each with the reason
(``Identifiability.reasons``: absorbed by the registration / probe offset, or redundant with named
identifiable parameters).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field, replace

import numpy as np
import pandas as pd
from scipy.spatial.transform import Rotation

from tolalloc.exceptions import ArgumentError, TolallocError, describe
from tolalloc.errormodel.model import ErrorModel
from tolalloc.robot.model import Robot
from tolalloc.diagnose.measurements import Measurements, file_rows
from tolalloc.diagnose.geometry import build_geometry_model
from tolalloc.diagnose.identify import DEFAULT_TOL, Identifiability, identifiability, select_columns  # re-exported
from tolalloc.progress import count_fit
from tolalloc.diagnose.scale import (CHUNK_ROWS, LOSSES, Problem, norm_scale, point_kinematics, robust_scale, solve,
                                     subsample_index)

__all__ = ["Fit", "Identifiability", "Calibration", "calibrate", "fit_model", "identifiability", "initial_fit",
           "fixed_jacobian", "is_collinear", "kabsch", "select_columns", "DEFAULT_TOL", "DEFAULT_LOSS", "HUBER_C",
           "TUKEY_C", "OUTLIER_C", "outlier_rows", "offset_prior"]

#: Robust loss of the diagnosis's fits (see :func:`fit_model`).
DEFAULT_LOSS = "tukey"
#: Huber threshold in units of the median 3-D residual norm (~3.1 sd per coordinate for Gaussian noise).
HUBER_C = 2.0
#: Tukey threshold in units of the median 3-D residual norm (~6.2 sd per coordinate: a Gaussian 3-D error
#: exceeds it with probability ~1e-7, so only gross errors lose all weight).
TUKEY_C = 4.0
#: A pose whose 3-D residual exceeds this many median residual norms is listed as an outlier (any loss).
OUTLIER_C = TUKEY_C
#: A pose whose robust weight falls below this is listed as down-weighted.
DOWN_WEIGHT = 0.5


def is_collinear(points: np.ndarray, rtol: float = 1e-9) -> bool:
    """Whether points (P, 3) lie on one line (or coincide): second singular value of the centred points at most
    ``rtol`` times the first (always for fewer than 3 points)."""
    if len(points) < 3:
        return True
    s = np.linalg.svd(points - points.mean(axis=0), compute_uv=False)
    return bool(s[1] <= rtol * max(s[0], 1e-300))


def kabsch(a: np.ndarray, b: np.ndarray):
    """Rotation ``R`` and translation ``p`` minimising ``sum |R a_i + p - b_i|^2``; a, b shape (P, 3).

    For points ``a`` on one line the rotation about the line is free: SciPy then returns the smallest rotation, and
    its warning about that is not passed on (the diagnosis reports it as a guard, :func:`.pipeline.diagnose`).
    """
    ca, cb = a.mean(0), b.mean(0)
    with warnings.catch_warnings():
        if is_collinear(a):
            warnings.filterwarnings("ignore", message="Optimal rotation is not uniquely", category=UserWarning)
        rot, _ = Rotation.align_vectors(b - cb, a - ca)
    R = rot.as_matrix()
    return R, cb - R @ ca


@dataclass(frozen=True, eq=False)
class Fit:
    """A fitted measurement model (see the module docstring).

    Attributes
    ----------
    model : ErrorModel
    R : array, shape (3, 3)      tracker <- base rotation
    p_mm : array, shape (3,)     tracker <- base translation [mm]
    t_mm : array, shape (3,)     target offset in the flange frame [mm]
    delta : array, shape (K,)    geometric parameter values [mm, rad] (0 where not fitted)
    geo_index : array of int     fitted geometric parameters
    beta : array, shape (M,)     effect parameters (0 where not identifiable)
    beta_index : array of int    fitted effect parameters
    effect_names : tuple of str
    residual_mm : array, shape (P, 3)  measured - predicted, tracker frame
    f_scale_mm : float           robust loss scale used (Huber / Tukey: the threshold on the 3-D residual norm)
    loss : str                   robust loss of the last pass (``none``, ``soft_l1``, ``huber``, ``tukey``; ``fixed``:
                                 another fit's pose weights)
    weights : array, shape (P,)  final IRLS weight of every pose (0: rejected by Tukey's biweight)
    t_prior_mm : (mean (3,), sd (3,)) or None   the prior on the target offset the fit used [mm]
    beta_prior_w : array, shape (M,) or None     ridge weights of the effect parameters the fit used
    """

    model: ErrorModel
    R: np.ndarray
    p_mm: np.ndarray
    t_mm: np.ndarray
    delta: np.ndarray
    geo_index: np.ndarray
    beta: np.ndarray = field(default_factory=lambda: np.zeros(0))
    beta_index: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    effect_names: tuple = ()
    residual_mm: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    f_scale_mm: float = 0.0
    loss: str = "none"
    weights: np.ndarray | None = None
    t_prior_mm: tuple | None = None
    beta_prior_w: np.ndarray | None = None

    @property
    def rms_mm(self) -> float:
        return float(np.sqrt(np.mean(np.sum(self.residual_mm ** 2, axis=1))))

    def base_points(self, q: np.ndarray, B: np.ndarray | None = None) -> np.ndarray:
        """Predicted target points in the robot base frame [mm], shape (P, 3)."""
        screws, home, dq = self.model.perturbed_chain(self.delta[None, :])
        x, _ = point_kinematics(screws[0], home[0], q + dq[0], self.t_mm)
        if B is not None and B.shape[-1]:
            x = x + B @ self.beta
        return x

    def predict(self, q: np.ndarray, B: np.ndarray | None = None) -> np.ndarray:
        """Predicted target points in the tracker frame [mm], shape (P, 3)."""
        return self.base_points(q, B) @ self.R.T + self.p_mm

    def parameters_frame(self) -> pd.DataFrame:
        """Fitted geometric and effect parameters in interface units."""
        rows = [{"parameter": self.model.params[k].name, "value": self.delta[k] * self.model.params[k].to_interface,
                 "unit": self.model.params[k].interface_unit} for k in self.geo_index]
        rows += [{"parameter": nm, "value": b, "unit": ""} for nm, b in zip(self.effect_names, self.beta)]
        return pd.DataFrame(rows, columns=["parameter", "value", "unit"])


def _Problem(fit0: Fit, q, xyz, geo_index, B=None, extra=None, *, n_effects=None, chunk_rows=None) -> Problem:
    """The measurement model's :class:`~tolalloc.diagnose.scale.Problem` for the fitted columns, starting at ``fit0``."""
    return Problem(fit0.model, fit0.R, fit0.p_mm, fit0.t_mm, fit0.delta, q, xyz, geo_index, B, extra,
                   n_effects=n_effects, chunk_rows=chunk_rows or CHUNK_ROWS)


def fit_model(start: Fit, q: np.ndarray, xyz: np.ndarray, *, geo_index=None, B=None, effect_names=(),
              robust: bool = True, extra: np.ndarray | None = None, prior: bool = True, n_effects: int | None = None,
              label: str = "fit", chunk_rows: int | None = None, loss: str | None = None, t_prior=None,
              beta_prior_w=None, sd_tol: float = 0.01, weights: np.ndarray | None = None) -> Fit:
    """Fit registration, offset, the geometric parameters ``geo_index`` and effect columns ``B``.

    Parameters
    ----------
    start : Fit
        Starting point (registration, offset, geometric values); see :func:`initial_fit`.
    q : array, shape (P, n) [rad, mm]
    xyz : array, shape (P, 3) [mm], tracker frame
    geo_index : array of int, optional (default: ``start.geo_index``)
    B : array, shape (P, 3, M), or callable ``B(slice) -> (rows, 3, M)`` with ``n_effects = M``, optional
        Effect basis [mm per unit]; a callable is evaluated chunk by chunk (large files).
    extra : array, shape (P, 3), optional
        A fixed displacement of the target in the base frame [mm] (a frozen effect, for re-registration).
    prior : bool
        MAP: after a plain least-squares pass, add a Gaussian prior ``N(0, model.sigma)`` on every fitted
        geometric parameter (parameters with sigma 0 get none), weighted with the robust noise estimate
        of the plain pass (``1.4826 MAD`` per coordinate). Registration and effects have no prior unless given.
    loss : {"soft_l1", "huber", "tukey"}, optional
        Robust loss of the measurement rows after the plain pass (default :data:`DEFAULT_LOSS`; see
        :mod:`.scale`). ``huber``: threshold :data:`HUBER_C` x the median 3-D residual of the plain pass;
        ``tukey``: Tukey's biweight with threshold :data:`TUKEY_C` x the median 3-D residual of the plain pass (the
        median is not moved by a few gross errors; they start far beyond the threshold and keep no weight).
    t_prior : (mean (3,), sd (3,)) [mm], optional
        Gaussian prior on the target offset (flange frame), weighted like the geometric prior (noise / sd).
    beta_prior_w : array, shape (M,), optional
        Fixed ridge weights of the effect parameters (rows ``w_i beta_i``; ``w = noise / prior sd`` from the
        effect's own hyper-parameter fit, :mod:`.evidence`).
    label : str   name of the fit on its progress bar (large files)
    chunk_rows : int, optional   poses per chunk of the normal equations (default :data:`~.scale.CHUNK_ROWS`)
    sd_tol : float
        Both passes stop once a step is worth less than ``sd_tol`` standard errors of the parameters
        (:func:`~.scale.solve`); 0 iterates to the solver's own tolerances.
    weights : array, shape (P,), optional
        Pose weights held fixed in the second pass instead of the robust loss (weighted least squares): the
        weights another model's robust fit gave these poses (:func:`calibrate` fits the nominal model with the
        geometric fit's weights, so that a pose counts as an outlier by its misfit under the model that can
        explain smooth errors, not under the misfit of the nominal one).
    """
    loss = DEFAULT_LOSS if loss is None else loss
    if loss not in LOSSES[1:]:
        raise ValueError(f"loss: expected one of {', '.join(LOSSES[1:])}, got {loss!r}")
    geo_index = start.geo_index if geo_index is None else np.asarray(geo_index, int)
    prob = _Problem(start, q, xyz, geo_index, B, extra, n_effects=n_effects, chunk_rows=chunk_rows)
    t_sd = None if t_prior is None else np.broadcast_to(np.asarray(t_prior[1], float), (3,))
    noise0 = robust_scale(start.residual_mm.ravel()) / 3.0 if len(start.residual_mm) else 0.05
    prob.set_priors(None if t_sd is None else (t_prior[0], noise0 / t_sd), beta_prior_w)
    x, raw = solve(prob, prob.x0(), max_iter=60, sd_tol=sd_tol, label=label)
    sig = start.model.sigma[geo_index]
    noise = robust_scale(raw.ravel()) / 3.0
    if prior and len(geo_index) and np.any(sig > 0):
        prob.prior_w = np.where(sig > 0, noise / np.where(sig > 0, sig, 1.0), 0.0)
    if t_sd is not None:
        prob.set_priors((t_prior[0], noise / t_sd), beta_prior_w)
    if weights is not None:
        prob.loss, prob.fixed_w = "fixed", np.asarray(weights, float)
    elif robust and loss == "soft_l1":
        prob.f_scale = robust_scale(raw.ravel())
    elif robust:
        prob.loss = loss
        prob.f_scale = (HUBER_C if loss == "huber" else TUKEY_C) * norm_scale(raw)
    if robust or weights is not None or prob.prior_w.any() or t_sd is not None:
        x, raw = solve(prob, x, max_iter=30, sd_tol=sd_tol, label=label + " (robust)")
    R, p, t, delta, beta = prob.unpack(x)
    count_fit()
    return Fit(start.model, R, p, t, delta, geo_index, beta, np.arange(len(beta)), tuple(effect_names), -raw,
               prob.f_scale, prob.loss if (robust or weights is not None) else "none", prob.pose_weights(raw),
               None if t_sd is None else (np.asarray(t_prior[0], float), t_sd),
               None if beta_prior_w is None else np.asarray(beta_prior_w, float))


def outlier_rows(fit: Fit, rows: np.ndarray | None = None, factor: float = OUTLIER_C, stage: str | None = None,
                 below: float = DOWN_WEIGHT) -> list:
    """Poses ``fit`` down-weighted (IRLS weight below ``below``) or whose 3-D residual exceeds ``factor`` x its median
    residual norm: dicts with the file ``row`` (``rows``: 1-based file rows of the poses; default pose number + 1),
    ``error_mm`` and the ``weight`` of the fit (and ``stage`` when given), largest error first."""
    e = np.linalg.norm(fit.residual_mm, axis=1)
    if not len(e):
        return []
    w = fit.weights if fit.weights is not None else np.ones(len(e))
    idx = np.flatnonzero((e > factor * norm_scale(fit.residual_mm)) | (w < below))
    idx = idx[np.argsort(-e[idx])]
    rows = file_rows(rows, len(e))
    extra = {} if stage is None else {"stage": stage}
    return [{**extra, "row": int(rows[i]), "error_mm": float(e[i]), "weight": float(w[i])} for i in idx]


def fixed_jacobian(fit: Fit, q: np.ndarray, xyz: np.ndarray) -> np.ndarray:
    """Jacobian (3P, 9 + len(geo_index)) of the registration, offset and fitted geometric columns at ``fit``."""
    prob = _Problem(fit, q, xyz, fit.geo_index, None)
    return prob.jac(prob.x0())


def offset_prior(target_offset_mm, target_offset_sd_mm) -> tuple | None:
    """The prior of the probe / target offset, ``(mean (3,), sd (3,))`` [mm], or None without a standard deviation;
    refuses a mean without its standard deviation, a standard deviation that is not positive (one or three values)
    and a mean that is not three finite numbers (x, y, z in the flange frame, relative to the tool point)."""
    if target_offset_sd_mm is None:
        if target_offset_mm is not None:
            raise ArgumentError("target_offset_mm", "a prior mean needs its standard deviation: give "
                                "`target_offset_sd_mm` too (e.g. 5 for a tool drawing good to a few mm).")
        return None
    try:
        sd = np.broadcast_to(np.asarray(target_offset_sd_mm, dtype=float), (3,))
    except (TypeError, ValueError):
        sd = np.full(3, np.nan)
    if not np.all(np.isfinite(sd)) or np.any(sd <= 0):
        raise ArgumentError("target_offset_sd_mm", "expected a positive standard deviation in mm (one or three "
                            f"values), got {describe(target_offset_sd_mm)}.")
    try:
        mean = np.zeros(3) if target_offset_mm is None else np.asarray(target_offset_mm, dtype=float)
    except (TypeError, ValueError):
        mean = None
    if mean is None or mean.shape != (3,) or not np.all(np.isfinite(mean)):
        raise ArgumentError("target_offset_mm", "expected three finite numbers (x, y, z in the flange frame, "
                            f"relative to the robot's tool point) [mm], got {describe(target_offset_mm)}.")
    return mean, sd.copy()


def initial_fit(model: ErrorModel, q: np.ndarray, xyz: np.ndarray) -> Fit:
    """Kabsch alignment of the nominal flange points to the measured points (target offset 0)."""
    flange, _ = point_kinematics(model.robot.screws, model.robot.home, q, np.zeros(3))
    R, p = kabsch(flange, xyz)
    K = len(model.params)
    return Fit(model, R, p, np.zeros(3), np.zeros(K), np.zeros(0, int))


@dataclass(frozen=True, eq=False)
class Calibration:
    """Result of :func:`calibrate`: nominal (registration + offset only) and geometric fits on the training poses.

    ``identifiability_rows``: the poses the identifiability analysis used (all, or a seeded subsample of
    :data:`~tolalloc.diagnose.scale.SUBSAMPLE_ROWS` for larger files; the fits always use every pose).
    ``loss``: the robust loss the fits used (Tukey falls back to Huber on a small file, :func:`calibrate`);
    ``loss_note``: why it differs from the one asked for (empty when it does not).
    """

    nominal: Fit
    geometric: Fit
    identifiability: Identifiability
    identifiability_rows: int = 0
    loss: str = DEFAULT_LOSS
    loss_note: str = ""


def calibrate(robot: Robot, meas: Measurements, *, model: ErrorModel | None = None, tol: float = DEFAULT_TOL,
              robust: bool = True, loss: str | None = None, t_prior=None) -> Calibration:
    """Register the tracker frame, the target offset and the identifiable geometric parameters.

    ``loss``, ``t_prior``: robust loss and target-offset prior of the fits (:func:`fit_model`).

    Robust fits keep the corners of the data: a pose is down-weighted for being inconsistent with the others under
    the geometric model, not for the misfit of the nominal one -- the nominal model is refitted with the geometric
    fit's pose weights. On a small file (fewer than :data:`POSES_PER_PARAMETER` poses per fitted parameter) Tukey's
    biweight, which gives a pose no weight at all, falls back to Huber's bounded-influence loss, whose weights never
    reach zero, with ``loss="auto"`` (the diagnosis's default; ``Calibration.loss_note`` says so). The nominal fit
    before the identifiability analysis uses Tukey's biweight for ``auto``.

    Raises :class:`TolallocError` when the file has fewer poses than the identifiable parameters need.
    Files of more than :data:`~tolalloc.diagnose.scale.SUBSAMPLE_ROWS` poses: the identifiability analysis
    runs on a seeded random subsample of that many poses, whose fits also start the fits on all poses.
    """
    model = model or build_geometry_model(robot)
    q, xyz = meas.q, meas.xyz_mm
    if len(q) < 5:
        raise TolallocError(f"{meas.source}: {len(q)} pose(s) after skipping NaN rows; registration and target offset "
                            "alone (9 parameters) need at least 5 poses, geometric calibration many more -- measure more poses.")
    sub = subsample_index(len(q))
    qs, xyzs = (q, xyz) if sub is None else (q[sub], xyz[sub])
    start = initial_fit(model, qs, xyzs)
    kw = dict(robust=robust, loss="tukey" if loss == "auto" else loss, t_prior=t_prior)
    if sub is not None:
        start = fit_model(start, qs, xyzs, **kw)
    nominal = fit_model(start, q, xyz, label="nominal calibration", **kw)
    ident = identifiability(nominal, qs, tol)
    # structural count: the same robot on a rich pose set; tells how many poses a full calibration needs
    rng = np.random.default_rng(0)
    rev = robot.revolute_mask  # revolute joints clipped to one turn; prismatic joints over their whole stroke
    lo = np.where(rev, np.maximum(robot.lower, -np.pi), robot.lower)
    hi = np.where(rev, np.minimum(robot.upper, np.pi), robot.upper)
    rich = identifiability(nominal, rng.uniform(lo, hi, (60, robot.n_joints)), tol)
    if len(q) < rich.min_poses:
        raise TolallocError(
            f"{meas.source}: {len(q)} poses for {9 + len(rich.identifiable)} identifiable parameters "
            f"(registration 6, target offset 3, geometric {len(rich.identifiable)}); need at least {rich.min_poses} poses "
            "(3 coordinates each, 2 spare) -- measure more poses spread over the workspace.")
    geo = np.array([model.index(n) for n in ident.identifiable], int)
    used, note = _loss_for_size(len(q), 9 + len(geo)) if robust and loss == "auto" else (loss, "")
    kw["loss"] = used
    start = replace(nominal, geo_index=geo)
    if sub is not None:
        start = fit_model(start, qs, xyzs, geo_index=geo, **kw)
    geometric = fit_model(start, q, xyz, geo_index=geo, label="geometric calibration", **kw)
    if robust and geometric.weights is not None:  # outliers by the geometric model's judgement (docstring)
        nominal = fit_model(nominal, q, xyz, label="nominal calibration", t_prior=t_prior,
                            weights=geometric.weights)
    return Calibration(nominal, geometric, ident, len(qs), used or DEFAULT_LOSS, note)


#: Fewer poses than this per fitted parameter (registration, offset, geometry) make a training file small.
POSES_PER_PARAMETER = 10


def is_small_file(n_poses: int, n_params: int) -> bool:
    """Whether a training file is small: fewer than POSES_PER_PARAMETER poses per fitted parameter (registration,
    offset, geometry). The robust loss (:func:`_loss_for_size`) and the selection's minimum gain
    (:func:`small_file_min_gain`) both change there."""
    return n_poses < POSES_PER_PARAMETER * n_params


def small_file_min_gain(n_poses: int, n_params: int, min_gain: float) -> tuple[float, str]:
    """(minimum gain, note) of the effect selection on a training file of ``n_poses`` poses for ``n_params`` fitted
    parameters.

    On a small file (fewer than POSES_PER_PARAMETER poses per parameter) an out-of-fold RMS over its ``3 n_poses``
    coordinates is uncertain by about ``1 / sqrt(2 * 3 n_poses)`` of itself (the relative sd of an RMS of Gaussian
    errors); a gain within that spread is not a finding, however consistent its sign. The minimum gain is raised to
    that spread there; elsewhere ``min_gain`` is returned with an empty note.
    """
    if not is_small_file(n_poses, n_params):
        return min_gain, ""
    spread = 1.0 / np.sqrt(6.0 * n_poses)
    if spread <= min_gain:
        return min_gain, ""
    return float(spread), (f"minimum gain of a selected effect raised from {100 * min_gain:g} % to {100 * spread:.2f} %: "
                           f"{n_poses} training poses for {n_params} parameters (fewer than {POSES_PER_PARAMETER} per "
                           f"parameter), where an out-of-fold RMS over {3 * n_poses} coordinates is itself uncertain by "
                           f"about 1/sqrt(2 x {3 * n_poses}) = {100 * spread:.2f} % and a smaller gain is not told from "
                           "that spread")


def _loss_for_size(n_poses: int, n_params: int) -> tuple:
    """(loss, note) of ``loss="auto"``: Tukey's biweight, or Huber on a small file (fewer than POSES_PER_PARAMETER
    poses per parameter)."""
    if not is_small_file(n_poses, n_params):
        return "tukey", ""
    return "huber", (f"robust loss: Huber in place of Tukey's biweight: {n_poses} training poses for {n_params} "
                     f"parameters (fewer than {POSES_PER_PARAMETER} per parameter), where a zero weight would drop "
                     "poses that carry the calibration (the ends of the joint ranges); Huber bounds their influence "
                     "without dropping them")
