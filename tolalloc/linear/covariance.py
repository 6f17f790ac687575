"""Linear variance map and error budget.

To first order the tool-pose error is ``[dp; dw] = J(q) e`` with the analytic error
Jacobian ``J = ErrorModel.jacobian(q)`` (6 x K: position rows [mm], space-frame rotation
rows [rad]; built from the error screws and adjoint maps, no finite differences). For
input covariance ``S_e`` (K x K) the output covariance is ``S = J S_e J^T``.

Second moments only
-------------------
The map propagates means and covariances exactly for the linearised model whatever the
input distributions, so every input enters through its own second moment: ``sigma^2`` for
normal and uniform (``+-sqrt(3) sigma``) inputs, ``0.9733 sigma^2`` for the normal truncated
at ``+-3 sigma`` (what :meth:`ErrorModel.sample` draws), and ``sigma^2`` per component for the
two components of a radial joint clearance ``s (cos t, sin t)`` (uncorrelated, but *not*
Gaussian and not independent: the pair is ring-shaped). Probabilities computed from ``S``
(:mod:`tolalloc.linear.probability`) treat the output as Gaussian; that is exact for Gaussian inputs
to first order and an approximation otherwise -- ``studies/linearisation`` measures how good.

Error budget
------------
For independent inputs parameter ``k`` contributes ``J_ik^2 var_k`` to the variance of
direction ``i`` (x, y, z) and ``sum_i J_ik^2 var_k`` to the trace (``E|dp|^2``, "norm"). For
correlated inputs the contributions are the Euler allocation ``J_ik (S_e J^T)_ki``; they still
sum to the variance but can be negative. Kinds (link length, joint drive, ...) sum their
parameters.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError, describe, whole_number
from tolalloc.errormodel.model import ErrorModel
from tolalloc.linear.probability import p_within_radius, radius_for_prob
from tolalloc.units import unit_columns

__all__ = ["LinearResult", "ErrorBudget", "linear_map", "input_covariance", "budget", "variance_contributions",
           "variance_share", "VARIANCE_FACTOR"]

#: Second moment of each sampling distribution per unit sigma^2.
VARIANCE_FACTOR = {"normal": 1.0, "uniform": 1.0, "ring": 1.0, "truncnormal": 0.9733369246625415}
_AXES = ("x", "y", "z", "norm")


def input_covariance(model: ErrorModel, cov=None, correlation=None) -> np.ndarray:
    """Input covariance ``S_e`` (K, K) [mm^2, mm rad, rad^2].

    Parameters
    ----------
    model : ErrorModel
    cov : array, shape (K, K), optional
        Full input covariance; used as is (must be symmetric PSD).
    correlation : array, shape (K, K), optional
        Correlation matrix; combined with the model's standard deviations.

    Default: independent inputs, ``diag(VARIANCE_FACTOR[distribution] * sigma^2)``.
    """
    K = len(model.params)
    var = np.array([VARIANCE_FACTOR[p.distribution] * p.sigma**2 for p in model.params])
    if cov is not None and correlation is not None:
        raise TolallocError("input covariance: give either cov or correlation, not both.")
    if cov is None and correlation is None:
        return np.diag(var)
    mat = np.asarray(cov if cov is not None else correlation, dtype=float)
    name = "cov" if cov is not None else "correlation"
    if mat.shape != (K, K) or not np.all(np.isfinite(mat)):
        raise TolallocError(f"{name}: expected a finite ({K}, {K}) matrix for the parameters {', '.join(model.names)}; got shape {mat.shape}.")
    if not np.allclose(mat, mat.T, rtol=1e-10, atol=1e-14 * np.abs(mat).max(initial=1.0)):
        raise TolallocError(f"{name}: expected a symmetric matrix; symmetrise it with (C + C.T) / 2.")
    if correlation is not None:
        if not np.allclose(np.diag(mat), 1.0):
            raise TolallocError("correlation: expected ones on the diagonal.")
        sd = np.sqrt(var)
        mat = mat * np.outer(sd, sd)
    lam = np.linalg.eigvalsh(mat)
    if lam.min() < -1e-10 * max(lam.max(), 1e-300):
        raise TolallocError(f"{name}: expected a positive semi-definite matrix, smallest eigenvalue {lam.min():.3g}.")
    return 0.5 * (mat + mat.T)


@dataclass(frozen=True, eq=False)
class LinearResult:
    """First-order pose-error statistics at ``P`` poses.

    Attributes
    ----------
    model : ErrorModel
    q : array, shape (P, n) [rad, mm]
    J : array, shape (P, 6, K)
        Error Jacobian (rows dp [mm], dw [rad]).
    cov_eps : array, shape (K, K)
        Input covariance [mm^2, rad^2].
    cov_mm2 : array, shape (P, 3, 3)
        Position-error covariance.
    cov_rot_rad2 : array, shape (P, 3, 3)
        Rotation-error covariance (space frame).
    std_mm : array, shape (P, 3)
    std_rot_rad : array, shape (P, 3)
    correlated : bool
        Whether ``cov_eps`` has off-diagonal terms.
    """

    model: ErrorModel
    q: np.ndarray
    J: np.ndarray
    cov_eps: np.ndarray
    cov_mm2: np.ndarray
    cov_rot_rad2: np.ndarray
    std_mm: np.ndarray
    std_rot_rad: np.ndarray
    correlated: bool = False

    @property
    def n_poses(self) -> int:
        return self.q.shape[0]

    @property
    def rms_mm(self) -> np.ndarray:
        """``sqrt(E|dp|^2) = sqrt(trace cov)``, shape (P,) [mm]."""
        return np.sqrt(np.trace(self.cov_mm2, axis1=-2, axis2=-1))

    @property
    def corr(self) -> np.ndarray:
        """Position-error correlation matrices, shape (P, 3, 3) (0 where a std is 0)."""
        s = self.std_mm
        den = s[:, :, None] * s[:, None, :]
        return np.divide(self.cov_mm2, den, out=np.zeros_like(self.cov_mm2), where=den > 0)

    def p_within(self, radius_mm) -> np.ndarray:
        """``P(|dp| < r)`` under the Gaussian approximation, shape (P,)."""
        return p_within_radius(self.cov_mm2, radius_mm)

    def radius_for(self, p) -> np.ndarray:
        """Radius [mm] with ``P(|dp| < r) = p``, shape (P,)."""
        return radius_for_prob(self.cov_mm2, p)

    def p_within_angle(self, angle_rad) -> np.ndarray:
        """``P(|dw| < angle)`` under the Gaussian approximation, shape (P,)."""
        return p_within_radius(self.cov_rot_rad2, angle_rad)

    def to_frame(self) -> pd.DataFrame:
        """One row per pose: joint values (deg / mm), position std [mm], rms [mm], rotation std [deg]."""
        robot = self.model.robot
        qi = robot.q_to_interface(self.q)
        cols = {f"{j.name}_{j.unit}": qi[:, k] for k, j in enumerate(robot.joints)}
        df = pd.DataFrame({"pose": np.arange(1, self.n_poses + 1), **cols})
        for a, ax in enumerate("xyz"):
            df[f"std_{ax}_mm"] = self.std_mm[:, a]
        df["rms_mm"] = self.rms_mm
        for a, ax in enumerate("xyz"):
            df[f"std_rot_{ax}_deg"] = np.rad2deg(self.std_rot_rad[:, a])
        return df


def linear_map(model: ErrorModel, q, *, cov=None, correlation=None) -> LinearResult:
    """Covariance of the tool-pose error by the linear map ``J S_e J^T`` at one or many poses.

    Parameters
    ----------
    model : ErrorModel
    q : array, shape (n,) or (P, n) [rad, mm]
    cov, correlation : array, shape (K, K), optional
        Correlated inputs (see :func:`input_covariance`); default independent.

    Returns
    -------
    LinearResult
    """
    q = np.atleast_2d(model.robot.check_q(q, "q"))
    S = input_covariance(model, cov, correlation)
    J = model.jacobian(q)  # (P, 6, K)
    correlated = bool(np.any(S - np.diag(np.diag(S))))
    if correlated:
        C = J @ S @ np.swapaxes(J, -1, -2)
    else:
        Jv = J * np.diag(S)
        C = Jv @ np.swapaxes(J, -1, -2)
    C = 0.5 * (C + np.swapaxes(C, -1, -2))
    cp, cr = C[:, :3, :3].copy(), C[:, 3:, 3:].copy()
    std = np.sqrt(np.maximum(np.diagonal(cp, axis1=1, axis2=2), 0))
    stdr = np.sqrt(np.maximum(np.diagonal(cr, axis1=1, axis2=2), 0))
    return LinearResult(model, q, J, S, cp, cr, std, stdr, correlated)


# ---------------------------------------------------------------------- budget
@dataclass(frozen=True, eq=False)
class ErrorBudget:
    """Each parameter's contribution to the error variance at each pose.

    Attributes
    ----------
    quantity : {"position", "rotation"}
    unit : str
        Unit of the variances: ``mm2`` or ``rad2``.
    names, kinds : tuple of str, length K
    sigma_interface : array, shape (K,)
        Standard deviations in interface units (mm / deg).
    units : tuple of str
        Interface units of the parameters.
    var : array, shape (P, K, 4)
        Contribution to the variance of x, y, z and to the trace ("norm").
    total : array, shape (P, 4)
        Variances of x, y, z and the trace.
    q_interface : array, shape (P, n)
    """

    quantity: str
    unit: str
    names: tuple
    kinds: tuple
    sigma_interface: np.ndarray
    units: tuple
    var: np.ndarray
    total: np.ndarray
    q_interface: np.ndarray

    @property
    def share(self) -> np.ndarray:
        """Fraction of each variance, shape (P, K, 4) (0 where the total is 0)."""
        t = self.total[:, None, :]
        return np.divide(self.var, t, out=np.zeros_like(self.var), where=t > 0)

    @property
    def worst_pose(self) -> int:
        """Pose with the largest trace (mean squared error)."""
        return int(np.argmax(self.total[:, 3]))

    def _pose_index(self, pose):
        P = self.total.shape[0]
        if pose is None:
            return list(range(P))
        if isinstance(pose, str) and pose == "worst":
            return [self.worst_pose]
        items = list(np.ravel(np.asarray(pose, dtype=object))) if not isinstance(pose, (str, bytes, dict)) else None
        idx = None if items is None or not items else [whole_number(p) for p in items]
        if idx is None or any(i is None or i < 0 or i >= P for i in idx):
            raise TolallocError(f"pose: expected a pose index 0..{P - 1} (whole numbers, 0-based), 'worst' or None, "
                                f"got {describe(pose)}.")
        return idx

    def to_frame(self, pose=None, by: str = "parameter") -> pd.DataFrame:
        """Long table, per pose the dominant contributors first (by their share of the norm).

        Parameters
        ----------
        pose : int, sequence of int, "worst" or None (all poses)
        by : {"parameter", "kind"}

        Columns: ``pose, parameter|kind, [kind, unit, sigma_mm, sigma_deg,] var_x_<u> .. var_norm_<u>,
        share_x_pct .. share_norm_pct`` (``<u>`` is ``mm2`` or ``rad2``; shares in percent). A parameter's sigma is in
        ``sigma_mm`` (lengths) or ``sigma_deg`` (angles), the other one NaN (:func:`tolalloc.units.unit_columns`).
        """
        if by not in ("parameter", "kind"):
            raise TolallocError(f"by: expected 'parameter' or 'kind', got {by!r}.")
        u = self.unit
        frames = []
        for i in self._pose_index(pose):
            var, share = self.var[i], self.share[i]
            if by == "kind":
                kinds = list(dict.fromkeys(self.kinds))
                mask = np.array([[k == kd for k in self.kinds] for kd in kinds], dtype=float)
                var, share = mask @ var, mask @ share
                df = pd.DataFrame({"pose": i + 1, "kind": kinds})
            else:
                is_mm = np.array([un == "mm" for un in self.units], bool)
                df = pd.DataFrame({"pose": i + 1, "parameter": list(self.names), "kind": list(self.kinds),
                                   "unit": list(self.units), **unit_columns("sigma", self.sigma_interface, is_mm)})
            for a, ax in enumerate(_AXES):
                df[f"var_{ax}_{u}"] = var[:, a]
            for a, ax in enumerate(_AXES):
                df[f"share_{ax}_pct"] = 100.0 * share[:, a]
            frames.append(df.sort_values("share_norm_pct", ascending=False, kind="stable"))
        return pd.concat(frames, ignore_index=True)

    def to_markdown(self, pose="worst", by: str = "parameter", top: int | None = None, digits: int = 4) -> str:
        """Markdown table of :meth:`to_frame` (the empty one of each unit pair blank),
        optionally the ``top`` rows per pose."""
        df = self.to_frame(pose, by)
        if top is not None:
            df = df.groupby("pose", sort=False).head(top)
        df = df.astype(object).where(df.notna(), None)
        return df.to_markdown(index=False, floatfmt=f".{digits}g", missingval="")

    def write_csv(self, path, pose=None, by: str = "parameter") -> None:
        """Write :meth:`to_frame` to ``path`` (CSV)."""
        self.to_frame(pose, by).to_csv(path, index=False, float_format="%.6g")

    def write_markdown(self, path, pose="worst", by: str = "parameter", top: int | None = None) -> None:
        """Write :meth:`to_markdown` to ``path``."""
        with open(path, "w") as fh:
            fh.write(self.to_markdown(pose, by, top) + "\n")


def variance_contributions(J, cov) -> np.ndarray:
    """Contribution of each parameter to the variance of each error row: ``J_ik (S J^T)_ki``.

    Parameters
    ----------
    J : array, shape (..., R, K)
        Error Jacobian rows (e.g. the position rows, R = 3).
    cov : array, shape (K,) or (K, K)
        Parameter variances (independent parameters: ``sigma**2``) or their covariance ``S``.

    Returns
    -------
    array, shape (..., R, K)
        Summed over K: the diagonal of ``J S J^T``; summed over R and K: its trace.
    """
    J = np.asarray(J, float)
    cov = np.asarray(cov, float)
    if cov.ndim == 1:
        return J**2 * cov
    return J * np.einsum("kl,...il->...ik", cov, J)


def variance_share(J, cov) -> np.ndarray:
    """Share of each parameter in the trace of ``J S J^T`` (the mean squared error), shape (..., K).

    ``J`` (..., R, K) and ``cov`` (K,) or (K, K) as :func:`variance_contributions`; zero where the trace is 0.
    The one implementation behind every "variance share" of the package (error budget, tolerance tables,
    binding process limits, the verification's non-Gaussian attribution).
    """
    v = variance_contributions(J, cov).sum(-2)
    tot = v.sum(-1, keepdims=True)
    return np.divide(v, tot, out=np.zeros_like(v), where=tot > 0)


def budget(result: LinearResult, quantity: str = "position") -> ErrorBudget:
    """Error budget of a :class:`LinearResult`.

    Parameters
    ----------
    result : LinearResult
    quantity : {"position", "rotation"}

    Returns
    -------
    ErrorBudget
    """
    if not isinstance(result, LinearResult):
        raise TolallocError(f"result: expected a LinearResult (from linear_map(model, q)), got "
                            f"{type(result).__name__}.")
    if quantity not in ("position", "rotation"):
        raise TolallocError(f"quantity: expected 'position' or 'rotation', got {quantity!r}.")
    rows = slice(0, 3) if quantity == "position" else slice(3, 6)
    Jq = result.J[:, rows, :]  # (P, 3, K)
    contrib = variance_contributions(Jq, result.cov_eps)  # (P, 3, K): J_ik (S J^T)_ki
    var = np.concatenate([np.swapaxes(contrib, 1, 2), contrib.sum(1)[:, :, None]], axis=2)  # (P, K, 4)
    total = var.sum(axis=1)
    model = result.model
    return ErrorBudget(
        quantity=quantity,
        unit="mm2" if quantity == "position" else "rad2",
        names=tuple(model.names),
        kinds=tuple(model.kinds),
        sigma_interface=np.array([p.sigma * p.to_interface for p in model.params]),
        units=tuple(p.interface_unit for p in model.params),
        var=var,
        total=total,
        q_interface=model.robot.q_to_interface(result.q),
    )
