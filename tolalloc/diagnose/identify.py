"""Identifiability of the geometric calibration parameters at the measured poses.

The geometric columns of the identification Jacobian, normalised to unit norm (the scaled Jacobian), are
projected off the registration and probe-offset columns; a column-pivoted QR (``scipy.linalg.qr(pivoting=True)``)
keeps a column while the part of it not explained by the columns kept before is at least ``tol`` (default
1e-3) of its norm. The rest, and the SVD null-space combinations of the projected columns, are reported as
unidentifiable and not fitted, each with the reason (absorbed by the registration / probe offset, or redundant
with named identifiable parameters).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd
import scipy.linalg

from tolalloc.robot.lie import hat

__all__ = ["Identifiability", "identifiability", "select_columns", "DEFAULT_TOL"]

DEFAULT_TOL = 1e-3

def select_columns(J_fixed: np.ndarray, J_cand: np.ndarray, tol: float = DEFAULT_TOL):
    """Which candidate columns are identifiable on top of the always-fitted ones.

    Parameters
    ----------
    J_fixed : array, shape (m, f)
    J_cand : array, shape (m, k)

    Returns
    -------
    keep : array of int (sorted), independent candidate columns
    share : array, shape (k,), the fraction of each candidate column not explained by ``J_fixed``
        and the candidates picked before it (0 for dropped columns)
    sing : array, singular values of the projected, normalised candidate columns (descending)
    Vt : array, shape (k, k), right singular vectors (rows)
    """
    k = J_cand.shape[1]
    if k == 0:
        return np.zeros(0, int), np.zeros(0), np.zeros(0), np.zeros((0, 0))
    norms = np.linalg.norm(J_cand, axis=0)
    Jn = J_cand / np.where(norms > 0, norms, 1.0)
    if J_fixed.shape[1]:
        Qf, _ = np.linalg.qr(J_fixed / np.linalg.norm(J_fixed, axis=0))
        Jn = Jn - Qf @ (Qf.T @ Jn)
    Jn[:, norms == 0] = 0.0
    _, Rq, piv = scipy.linalg.qr(Jn, mode="economic", pivoting=True)
    diag = np.abs(np.diag(Rq))
    share = np.zeros(k)
    share[piv[: len(diag)]] = diag
    ok = np.cumprod(diag >= tol).astype(bool)
    keep = np.sort(piv[: len(diag)][ok])
    _, sing, Vt = np.linalg.svd(Jn, full_matrices=False)
    return keep, share, sing, Vt


@dataclass(frozen=True, eq=False)
class Identifiability:
    """What the poses can and cannot separate.

    Attributes
    ----------
    names : tuple of str            all geometric parameters of the error model
    identifiable : tuple of str     fitted
    unidentifiable : tuple of str   not fitted (absorbed by the registration / offset or by other parameters)
    share : array, shape (K,)       independent share of each parameter's column (see :func:`select_columns`)
    rank : int                      rank of the full problem (9 + identifiable)
    condition_number : float        of the column-normalised Jacobian of the fitted parameters
    observability_index : float     Borm-Menq O1 = (prod sigma_i)^(1/L) / sqrt(P) (normalised columns)
    null_combinations : tuple of str  parameter combinations the data cannot separate
    min_poses : int                 poses needed for the fitted parameters (3 coordinates per pose, 2 spare)
    reasons : dict                  why each unidentifiable parameter was dropped (name -> text)
    aliases : dict                  fitted parameter -> ((dropped parameter, c), ...): the dropped parameters it also
                                    stands for (its fitted value carries ``c`` x theirs, each in its own unit,
                                    :data:`ALIAS_MIN` or more in normalised columns)
    """

    names: tuple
    identifiable: tuple
    unidentifiable: tuple
    share: np.ndarray
    rank: int
    condition_number: float
    observability_index: float
    null_combinations: tuple
    min_poses: int
    reasons: dict = field(default_factory=dict)
    aliases: dict = field(default_factory=dict)

    def to_frame(self) -> pd.DataFrame:
        return pd.DataFrame({"parameter": self.names, "identifiable": [n in self.identifiable for n in self.names],
                             "independent_share": self.share, "reason": [self.reasons.get(n, "") for n in self.names]})

    def to_dict(self) -> dict:
        return {"rank": self.rank, "condition_number": self.condition_number,
                "observability_index": self.observability_index, "identifiable": list(self.identifiable),
                "unidentifiable": list(self.unidentifiable), "null_combinations": list(self.null_combinations),
                "min_poses": self.min_poses, "dropped": dict(self.reasons),
                "aliases": {k: [{"parameter": n, "coefficient": c} for n, c in v] for k, v in self.aliases.items()}}


def identifiability(fit, q: np.ndarray, tol: float = DEFAULT_TOL) -> Identifiability:
    """Identifiability of the geometric parameters on the poses ``q`` at the registration/offset of ``fit``.

    Parameters
    ----------
    fit : :class:`tolalloc.diagnose.calibrate.Fit`   model, registration and probe offset
    q : array, shape (P, n) [rad, mm]
    tol : float   independent share below which a column is dropped
    """
    model = fit.model
    P = len(q)
    J = model.jacobian(q)
    Jp, Jw = J[:, :3, :], J[:, 3:, :]
    T = model.robot.fk_internal(q)
    arm = T[:, :3, :3] @ fit.t_mm
    y = T[:, :3, 3] + arm
    Jg = (Jp + np.cross(Jw, arm[:, :, None], axis=1)).reshape(3 * P, -1)
    Jf = np.concatenate([-hat(y), np.broadcast_to(np.eye(3), (P, 3, 3)), T[:, :3, :3]], axis=2).reshape(3 * P, 9)
    keep, share, sing, Vt = select_columns(Jf, Jg, tol)
    names = tuple(model.names)
    null = []
    smax = sing.max() if len(sing) else 1.0
    for i in range(Vt.shape[0]):
        s = sing[i] if i < len(sing) else 0.0
        if s >= tol * max(smax, 1e-300) and s >= tol:
            continue
        v = Vt[i]
        order = np.argsort(-np.abs(v))[:4]
        terms = [f"{v[k]:+.2f} {names[k]}" for k in order if abs(v[k]) > 0.05]
        null.append(" ".join(terms) if terms else "(none)")
    Jall = np.concatenate([Jf, Jg[:, keep]], axis=1)
    Jn = Jall / np.maximum(np.linalg.norm(Jall, axis=0), 1e-300)
    sv = np.linalg.svd(Jn, compute_uv=False)
    rank = int(np.sum(sv > sv[0] * 1e-10))
    cond = float(sv[0] / sv[-1]) if sv[-1] > 0 else float("inf")
    o1 = float(np.exp(np.mean(np.log(np.maximum(sv, 1e-300)))) / np.sqrt(P))
    L = 9 + len(keep)
    min_poses = int(np.ceil(L / 3)) + 2
    return Identifiability(names, tuple(names[k] for k in keep), tuple(n for k, n in enumerate(names) if k not in set(keep)),
                           share, rank, cond, o1, tuple(null), min_poses, *_drop_reasons(Jf, Jg, keep, names, tol))


#: A dropped parameter whose normalised column takes at least this share of a fitted one's is that one's alias.
ALIAS_MIN = 0.3


def _drop_reasons(Jf: np.ndarray, Jg: np.ndarray, keep: np.ndarray, names: tuple, tol: float) -> tuple:
    """Why each geometric column not in ``keep`` was dropped (absorbed by registration/offset, or redundant), and the
    aliases: per fitted parameter, the redundant dropped ones its value also carries (``Identifiability.aliases``;
    a dropped ``delta_k`` moves the points as ``c x delta_k`` of the fitted one, ``c = c_normalised x |J_k| / |J_i|``
    in the parameters' own units)."""
    norms = np.linalg.norm(Jg, axis=0)
    Jn = Jg / np.where(norms > 0, norms, 1.0)
    Qf, _ = np.linalg.qr(Jf / np.linalg.norm(Jf, axis=0))
    proj = Jn - Qf @ (Qf.T @ Jn)
    free = np.linalg.norm(proj, axis=0)
    out, aliases = {}, {}
    for k in sorted(set(range(Jg.shape[1])) - set(keep.tolist())):
        if norms[k] == 0:
            out[names[k]] = "no effect on the measured points at these poses"
        elif free[k] < tol:
            out[names[k]] = f"absorbed by the registration / probe offset (independent share {free[k]:.1e} < {tol:g})"
        else:
            c, *_ = np.linalg.lstsq(proj[:, keep], proj[:, k], rcond=None)
            left = np.linalg.norm(proj[:, k] - proj[:, keep] @ c)
            top = np.argsort(-np.abs(c))[:3]
            combo = " ".join(f"{c[i] / free[k]:+.2f} {names[keep[i]]}" for i in top if abs(c[i]) > 1e-3 * free[k])
            out[names[k]] = (f"redundant with the identifiable parameters (independent share {left / free[k]:.1e} "
                             f"of what registration/offset leave; ~ {combo})")
            for i in top:
                if abs(c[i]) >= ALIAS_MIN * free[k]:
                    coef = float(norms[k] / norms[keep[i]] * c[i])
                    aliases.setdefault(names[keep[i]], []).append((names[k], coef))
    return out, {a: tuple(v) for a, v in aliases.items()}
