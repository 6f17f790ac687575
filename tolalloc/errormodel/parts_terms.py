"""The terms of the bought parts' effects (:class:`EffectTerms`: per term a tool column, a mean, a systematic and a
random standard deviation at every point) and the share of them a compensation model leaves
(:func:`residual_factors`); built by :class:`tolalloc.errormodel.parts.PartEffects` (its module docstring says
which effect carries which part)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError

__all__ = ["EFFECTS", "THERMAL_SD", "BEAM_SD", "MOUNT_SD", "TILT_SD", "COMPENSATION_RESIDUAL", "residual_factors",
           "EffectTerms"]

EFFECTS = ("compliance", "lost_motion", "transmission", "encoder", "homing", "bearing", "thermal", "beam", "mount")
#: Relative spread (one sd) of a link's thermal growth between robots (CTE and temperature field; ASSUMED).
THERMAL_SD = 0.1
#: Relative spread of the links' bending (modulus, wall thickness; ASSUMED).
BEAM_SD = 0.1
#: Relative spread of the mount's tilt (its stiffness is an estimate; ASSUMED).
MOUNT_SD = 0.2
#: Relative spread of a bearing's tilt under its moment (the catalogue's moment stiffness is nominal, the preload
#: and the housing's stiffness vary; ASSUMED).
TILT_SD = 0.2
#: Share of a mean and of a systematic part a compensation model leaves (``after="compensation"``; ASSUMED).
COMPENSATION_RESIDUAL = 0.1


def residual_factors(after: str, residual=COMPENSATION_RESIDUAL) -> dict:
    """Per effect, the share of its mean and systematic part left: 1 everywhere for ``after="none"``; for
    ``"compensation"`` the number ``residual``, or ``residual[effect]`` (1 where a dict omits the effect: no model
    for it)."""
    if after not in ("none", "compensation"):
        raise TolallocError(f"after: expected 'none' or 'compensation', got {after!r}")
    if after == "none":
        return dict.fromkeys(EFFECTS, 1.0)
    if isinstance(residual, dict):
        bad = [k for k in residual if k not in EFFECTS]
        if bad:
            raise TolallocError(f"residual: unknown effect {bad[0]!r}; effects: {', '.join(EFFECTS)}")
        out = {e: float(residual.get(e, 1.0)) for e in EFFECTS}
    else:
        out = dict.fromkeys(EFFECTS, float(residual))
    if not all(0.0 <= v <= 1.0 for v in out.values()):
        raise TolallocError(f"residual: expected shares in [0, 1], got {residual!r}")
    return out


@dataclass(frozen=True, eq=False)
class EffectTerms:
    """Terms of the bought parts' effects at P points (module docstring).

    Attributes
    ----------
    names, effect : tuple of str, (T,)
    joint : array of int, shape (T,)          joint of the term (-1: none)
    columns : array, shape (P, 3, T)          tool displacement per unit value [mm per mm or rad, or per unit]
    mean, sys_sd, rnd_sd : arrays, shape (P, T)
    rotation : array, shape (P, 3, T)         tool rotation per unit value [rad per mm or rad, or per unit]; a
                                              beam's, a bearing's tilt or the mount's only with
                                              PartEffects(rotations=True)
    """

    names: tuple
    effect: tuple
    joint: np.ndarray
    columns: np.ndarray
    mean: np.ndarray
    sys_sd: np.ndarray
    rnd_sd: np.ndarray
    rotation: np.ndarray

    @staticmethod
    def empty(P: int) -> "EffectTerms":
        return EffectTerms((), (), np.zeros(0, int), np.zeros((P, 3, 0)), np.zeros((P, 0)), np.zeros((P, 0)),
                           np.zeros((P, 0)), np.zeros((P, 3, 0)))

    def __add__(self, other: "EffectTerms") -> "EffectTerms":
        return EffectTerms(self.names + other.names, self.effect + other.effect,
                           np.concatenate([self.joint, other.joint]),
                           *(np.concatenate([getattr(self, a), getattr(other, a)], axis=-1)
                             for a in ("columns", "mean", "sys_sd", "rnd_sd", "rotation")))

    def select(self, mask) -> "EffectTerms":
        """The terms where ``mask`` (T,) is true."""
        idx = np.flatnonzero(np.asarray(mask, bool))
        return EffectTerms(tuple(self.names[i] for i in idx), tuple(self.effect[i] for i in idx), self.joint[idx],
                           self.columns[:, :, idx], self.mean[:, idx], self.sys_sd[:, idx], self.rnd_sd[:, idx],
                           self.rotation[:, :, idx])

    def of_effect(self, effect: str) -> "EffectTerms":
        """The terms of one effect (:data:`EFFECTS`)."""
        return self.select([e == effect for e in self.effect])

    def mean_mm(self) -> np.ndarray:
        """Mean tool displacement [mm], shape (P, 3): the compensable part."""
        return np.einsum("pit,pt->pi", self.columns, self.mean)

    def _cov(self, sd) -> np.ndarray:
        return np.einsum("pit,pt,pjt->pij", self.columns, sd ** 2, self.columns)

    def systematic_covariance(self) -> np.ndarray:
        """Covariance [mm^2] (P, 3, 3) of the systematic parts: between robots, fixed for one."""
        return self._cov(self.sys_sd)

    def random_covariance(self) -> np.ndarray:
        """Covariance [mm^2] (P, 3, 3) of the random parts: move to move (what repeatability sees)."""
        return self._cov(self.rnd_sd)

    def moments(self, after: str = "none", residual=COMPENSATION_RESIDUAL) -> tuple:
        """``(mean (P, 3), covariance (P, 3, 3))`` of the tool error the effects add: ``after="none"`` all parts;
        ``"compensation"``: the compensation models leave ``residual`` of every mean and systematic sd (a number, or
        ``{effect: share}`` with 1 for the effects it omits: :func:`residual_factors`)."""
        f = residual_factors(after, residual)
        ft = np.array([f[e] for e in self.effect])
        return (np.einsum("pit,pt->pi", self.columns, self.mean * ft),
                self._cov(self.sys_sd * ft) + self.random_covariance())

    def to_frame(self, point: int = 0) -> pd.DataFrame:
        """One row per term at one point: effect, term, joint, mean displacement and the two standard deviations of
        the tool displacement it adds [mm] (along its column)."""
        n = np.linalg.norm(self.columns[point], axis=0)
        return pd.DataFrame({"effect": self.effect, "term": self.names, "joint": self.joint + 1,
                             "mean_mm": np.abs(self.mean[point]) * n, "systematic_sd_mm": self.sys_sd[point] * n,
                             "random_sd_mm": self.rnd_sd[point] * n})
