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
squares (``scipy.optimize.least_squares``, TRF; first a plain fit, then ``soft_l1`` loss with a scale of 3
robust standard deviations, applied to the measurement rows only). MAP: the second pass adds a Gaussian
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

from dataclasses import dataclass, field, replace

import numpy as np
import pandas as pd
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from tolalloc.exceptions import TolallocError
from tolalloc.errormodel.model import ErrorModel
from tolalloc.robot.lie import hat
from tolalloc.robot.kinematics import fk_poe
from tolalloc.robot.model import Robot
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.geometry import build_geometry_model
from tolalloc.diagnose.identify import DEFAULT_TOL, Identifiability, identifiability, select_columns  # re-exported

__all__ = ["Fit", "Identifiability", "Calibration", "calibrate", "fit_model", "identifiability", "initial_fit",
           "fixed_jacobian", "kabsch", "select_columns", "DEFAULT_TOL"]


def kabsch(a: np.ndarray, b: np.ndarray):
    """Rotation ``R`` and translation ``p`` minimising ``sum |R a_i + p - b_i|^2``; a, b shape (P, 3)."""
    ca, cb = a.mean(0), b.mean(0)
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
    f_scale_mm : float           robust loss scale used
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

    @property
    def rms_mm(self) -> float:
        return float(np.sqrt(np.mean(np.sum(self.residual_mm ** 2, axis=1))))

    def base_points(self, q: np.ndarray, B: np.ndarray | None = None) -> np.ndarray:
        """Predicted target points in the robot base frame [mm], shape (P, 3)."""
        screws, home, dq = self.model.perturbed_chain(self.delta[None, :])
        T = fk_poe(screws[0], home[0], q + dq[0])
        x = T[:, :3, 3] + T[:, :3, :3] @ self.t_mm
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


def _geo_point_jacobian(model: ErrorModel, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Error Jacobian rows of the flange: dp (P,3,K) and dw (P,3,K), and flange rotations (P,3,3)."""
    J = model.jacobian(q)
    return J[:, :3, :], J[:, 3:, :]


class _Problem:
    """Residual and analytic Jacobian for a fixed set of fitted columns.

    With ``prior_w`` (shape (len(geo_index),), set by :func:`fit_model`) the residual vector ends with the
    MAP prior rows ``prior_w * delta[geo_index]`` (``prior_w = noise / prior sigma``, mm). With ``f_scale > 0``
    the data rows ``r`` are replaced by ``sign(r) f sqrt(2 (sqrt(1 + (r/f)^2) - 1))``, whose squares sum to the
    ``soft_l1`` loss, so the robust loss acts on the measurements only and never weakens the prior.
    """

    def __init__(self, fit0: Fit, q, xyz, geo_index, B, extra=None):
        self.model, self.q, self.xyz = fit0.model, q, xyz
        self.extra = np.zeros((len(q), 3)) if extra is None else extra
        self.R0 = fit0.R
        self.geo = np.asarray(geo_index, int)
        self.B = B if B is not None else np.zeros((len(q), 3, 0))
        self.Jp, self.Jw = _geo_point_jacobian(self.model, q)
        self.Rfl = self.model.robot.fk(q)[:, :3, :3]
        self.fit0 = fit0
        self.prior_w = np.zeros(len(self.geo))
        self.f_scale = 0.0
        self._cache = (None, None)

    def unpack(self, x):
        k = len(self.geo)
        R = self.R0 @ Rotation.from_rotvec(x[:3]).as_matrix()
        delta = self.fit0.delta.copy()
        delta[self.geo] = x[9:9 + k]
        return R, x[3:6], x[6:9], delta, x[9 + k:]

    def x0(self):
        return np.concatenate([np.zeros(3), self.fit0.p_mm, self.fit0.t_mm, self.fit0.delta[self.geo],
                               np.zeros(self.B.shape[-1])])

    def base(self, x):
        if self._cache[0] is not None and np.array_equal(self._cache[0], x):
            return self._cache[1]
        out = self._base(x)
        self._cache = (np.array(x, copy=True), out)
        return out

    def _base(self, x):
        R, p, t, delta, beta = self.unpack(x)
        screws, home, dq = self.model.perturbed_chain(delta[None, :])
        T = fk_poe(screws[0], home[0], self.q + dq[0])
        y = T[:, :3, 3] + T[:, :3, :3] @ t + self.B @ beta + self.extra
        return y, R, p

    def raw(self, x):
        """Data residual predicted - measured, shape (3P,) [mm], without robust transform or prior rows."""
        y, R, p = self.base(x)
        return (y @ R.T + p - self.xyz).ravel()

    def _robust(self, r):
        """Transformed residual and its derivative d r' / d r (soft_l1), identity when ``f_scale`` is 0."""
        if self.f_scale <= 0:
            return r, np.ones_like(r)
        f = self.f_scale
        root = np.sqrt(1.0 + (r / f) ** 2)
        rt = np.sign(r) * f * np.sqrt(2.0 * (root - 1.0))
        ratio = np.divide(r, rt, out=np.ones_like(r), where=np.abs(rt) > 1e-12 * f)
        return rt, ratio / root

    def fun(self, x):
        res = self._robust(self.raw(x))[0]
        if not self.prior_w.any():
            return res
        return np.concatenate([res, self.prior_w * x[9:9 + len(self.geo)]])

    def jac(self, x):
        y, R, p = self.base(x)
        t = x[6:9]
        arm = self.Rfl @ t  # (P, 3)
        Jg = self.Jp[:, :, self.geo] + np.cross(self.Jw[:, :, self.geo], arm[:, :, None], axis=1)
        P = len(self.q)
        cols = [
            -np.einsum("ij,pjk->pik", R, hat(y)),
            np.broadcast_to(np.eye(3), (P, 3, 3)),
            np.einsum("ij,pjk->pik", R, self.Rfl),
            np.einsum("ij,pjk->pik", R, Jg),
            np.einsum("ij,pjk->pik", R, self.B),
        ]
        J = np.concatenate(cols, axis=2).reshape(3 * P, -1)
        if self.f_scale > 0:
            J = J * self._robust(self.raw(x))[1][:, None]
        if not self.prior_w.any():
            return J
        k = len(self.geo)
        Jp = np.zeros((k, J.shape[1]))
        Jp[:, 9:9 + k] = np.diag(self.prior_w)
        return np.concatenate([J, Jp])


def _robust_scale(res: np.ndarray) -> float:
    return float(max(3.0 * 1.4826 * np.median(np.abs(res - np.median(res))), 1e-4))


def fit_model(start: Fit, q: np.ndarray, xyz: np.ndarray, *, geo_index=None, B=None, effect_names=(),
              robust: bool = True, extra: np.ndarray | None = None, prior: bool = True) -> Fit:
    """Fit registration, offset, the geometric parameters ``geo_index`` and effect columns ``B``.

    Parameters
    ----------
    start : Fit
        Starting point (registration, offset, geometric values); see :func:`initial_fit`.
    q : array, shape (P, n) [rad, mm]
    xyz : array, shape (P, 3) [mm], tracker frame
    geo_index : array of int, optional (default: ``start.geo_index``)
    B : array, shape (P, 3, M), optional, effect basis [mm per unit]
    extra : array, shape (P, 3), optional
        A fixed displacement of the target in the base frame [mm] (a frozen effect, for re-registration).
    prior : bool
        MAP: after a plain least-squares pass, add a Gaussian prior ``N(0, model.sigma)`` on every fitted
        geometric parameter (parameters with sigma 0 get none), weighted with the robust noise estimate
        of the plain pass (``1.4826 MAD`` per coordinate). Registration, offset and effects have no prior.
    """
    geo_index = start.geo_index if geo_index is None else np.asarray(geo_index, int)
    prob = _Problem(start, q, xyz, geo_index, B, extra)
    opts = dict(jac=prob.jac, method="trf", x_scale="jac", xtol=1e-10, ftol=1e-10, gtol=1e-10)
    sol = least_squares(prob.fun, prob.x0(), max_nfev=60, **opts)
    f_scale = 0.0
    sig = start.model.sigma[geo_index]
    if prior and len(geo_index) and np.any(sig > 0):
        noise = _robust_scale(sol.fun) / 3.0
        prob.prior_w = np.where(sig > 0, noise / np.where(sig > 0, sig, 1.0), 0.0)
    if robust:
        f_scale = prob.f_scale = _robust_scale(prob.raw(sol.x))
    if robust or prob.prior_w.any():
        sol = least_squares(prob.fun, sol.x, max_nfev=30, **opts)
    R, p, t, delta, beta = prob.unpack(sol.x)
    res = -prob.raw(sol.x).reshape(-1, 3)
    return Fit(start.model, R, p, t, delta, geo_index, beta, np.arange(len(beta)), tuple(effect_names), res, f_scale)


def fixed_jacobian(fit: Fit, q: np.ndarray, xyz: np.ndarray) -> np.ndarray:
    """Jacobian (3P, 9 + len(geo_index)) of the registration, offset and fitted geometric columns at ``fit``."""
    prob = _Problem(fit, q, xyz, fit.geo_index, None)
    return prob.jac(prob.x0())


def initial_fit(model: ErrorModel, q: np.ndarray, xyz: np.ndarray) -> Fit:
    """Kabsch alignment of the nominal flange points to the measured points (target offset 0)."""
    flange = model.robot.fk(q)[:, :3, 3]
    R, p = kabsch(flange, xyz)
    K = len(model.params)
    return Fit(model, R, p, np.zeros(3), np.zeros(K), np.zeros(0, int))


@dataclass(frozen=True, eq=False)
class Calibration:
    """Result of :func:`calibrate`: nominal (registration + offset only) and geometric fits on the training poses."""

    nominal: Fit
    geometric: Fit
    identifiability: Identifiability


def calibrate(robot: Robot, meas: Measurements, *, model: ErrorModel | None = None, tol: float = DEFAULT_TOL,
              robust: bool = True) -> Calibration:
    """Register the tracker frame, the target offset and the identifiable geometric parameters.

    Raises :class:`TolallocError` when the file has fewer poses than the identifiable parameters need.
    """
    model = model or build_geometry_model(robot)
    q, xyz = meas.q, meas.xyz_mm
    if len(q) < 5:
        raise TolallocError(f"{meas.source}: {len(q)} pose(s) after skipping NaN rows; registration and target offset "
                            "alone (9 parameters) need at least 5 poses, geometric calibration many more -- measure more poses.")
    nominal = fit_model(initial_fit(model, q, xyz), q, xyz, robust=robust)
    ident = identifiability(nominal, q, tol)
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
    geometric = fit_model(replace(nominal, geo_index=geo), q, xyz, geo_index=geo, robust=robust)
    return Calibration(nominal, geometric, ident)
