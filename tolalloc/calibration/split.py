"""Systematic and random parts of the error parameters.

Every error parameter ``e_k`` is split into a *systematic* part ``s_k`` (fixed for a built robot, what a
calibration can estimate and the controller compensate) and a *random* part ``r_k`` (new at every move or
every day, what no calibration removes): ``e_k = s_k + r_k``, independent.

Defaults per kind -- ASSUMPTIONS of this project, overridable per kind or parameter::

    link_length, axis_deflection   systematic only (machined / assembled geometry).
    joint_drive                    systematic zero offset (sigma of the error model) plus a random
                                   repeatability term (encoder / transmission repeatability, default
                                   sigma 0.0003 deg for revolute, 0.001 mm for prismatic drives).
    clearance_*                    random only (clearance and backlash take a new value each move).

Overrides (the costs file's ``[calibration]`` table, or a dict of the same shape)::

    [calibration.kinds.joint_drive]
    repeatability_deg = 0.0005
    [calibration.parameters.e2y]
    systematic = false               # treat as random (e.g. thermally drifting)
    [calibration.parameters.dth6]
    repeatability_deg = 0.001

``repeatability_*`` is a standard deviation; the random part of a non-systematic parameter is its whole
error-model sigma.

The random part of a systematic parameter can also be *chosen* by the calibration-aware allocation, like a
tolerance, with its own cost law and process limits (e.g. encoder / transmission grades)::

    [calibration.kinds.joint_drive.grade]
    model = "reciprocal"             # any cost law of the costs file (a, b, k, t_ref_*, t_min_*, t_max_*)
    a = 0.2
    b = 0.3
    t_ref_deg = 0.001                # a grade is a repeatability band +-t, sigma = t / z (z of the costs file)
    t_min_deg = 0.0003
    t_max_deg = 0.003

A ``grade`` replaces ``repeatability_*`` for that parameter (a parameter-level entry overrides the kind's); it is
allowed only for parameters with a systematic part (a random-only parameter's tolerance is allocated already).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError
from tolalloc.errormodel.model import ErrorModel

__all__ = ["ErrorSplit", "split_errors", "DEFAULT_SPLIT"]

#: Default split per kind (see module docstring); repeatability in the interface unit (deg or mm).
DEFAULT_SPLIT = {
    "link_length": {"systematic": True},
    "axis_deflection": {"systematic": True},
    "joint_drive": {"systematic": True, "repeatability_deg": 0.0003},
    "joint_drive_prismatic": {"systematic": True, "repeatability_mm": 0.001},
    "clearance_axial": {"systematic": False},
    "clearance_radial": {"systematic": False},
    "clearance_tilt": {"systematic": False},
}
_KEYS = {"systematic", "grade", "repeatability_deg", "repeatability_rad", "repeatability_mm", "repeatability_m"}
_FACTOR = {"deg": ("rad", np.pi / 180), "rad": ("rad", 1.0), "mm": ("mm", 1.0), "m": ("mm", 1000.0)}


@dataclass(frozen=True, eq=False)
class ErrorSplit:
    """Systematic / random split of an error model's parameters.

    Attributes
    ----------
    model : ErrorModel
    systematic : array of bool, shape (K,)
        Whether the parameter has a systematic part (prior sigma = the model's sigma).
    random_sigma : array, shape (K,) [mm or rad]
        Standard deviation of the random part.
    grade : tuple of (dict or None), length K, optional
        Per parameter, the raw cost-law table of an allocatable repeatability grade (``None``: the random part is
        fixed at ``random_sigma``); resolved into a cost model by :mod:`tolalloc.allocate.calibrated.certified`.
    """

    model: ErrorModel
    systematic: np.ndarray
    random_sigma: np.ndarray
    grade: tuple | None = None

    @property
    def graded(self) -> np.ndarray:
        """Indices of the parameters whose random part is an allocatable grade, shape (G,)."""
        if self.grade is None:
            return np.zeros(0, int)
        return np.array([k for k, g in enumerate(self.grade) if g is not None], int)

    @property
    def sys_index(self) -> np.ndarray:
        """Indices of the parameters with a systematic part, shape (Ks,)."""
        return np.flatnonzero(self.systematic)

    @property
    def prior_sigma(self) -> np.ndarray:
        """Prior (manufacturing) sigma of the systematic parts, shape (Ks,) [mm or rad]."""
        return self.model.sigma[self.systematic]

    def prior_var_of(self, idx) -> np.ndarray:
        """Prior variance of the systematic parts of parameters ``idx`` [mm^2 or rad^2]."""
        from tolalloc.linear.covariance import VARIANCE_FACTOR

        idx = np.asarray(idx, int)
        fac = np.array([VARIANCE_FACTOR[self.model.params[k].distribution] for k in idx])
        return np.where(self.systematic[idx], fac * self.model.sigma[idx] ** 2, 0.0)

    def random_variance(self) -> np.ndarray:
        """Second moment of the random part per parameter, shape (K,) [mm^2 or rad^2]."""
        from tolalloc.linear.covariance import VARIANCE_FACTOR

        fac = np.array([VARIANCE_FACTOR[p.distribution] for p in self.model.params])
        return fac * self.random_sigma**2

    def with_model(self, model: ErrorModel) -> "ErrorSplit":
        """The same split on a model with new sigmas (same parameters); random-only parts follow the new sigma."""
        rnd = np.where(self.systematic, self.random_sigma, model.sigma)
        return ErrorSplit(model, self.systematic.copy(), rnd, self.grade)

    def with_random_sigma(self, random_sigma) -> "ErrorSplit":
        """A copy with new random-part sigmas, shape (K,) [mm or rad]."""
        return ErrorSplit(self.model, self.systematic.copy(), np.asarray(random_sigma, float).copy(), self.grade)

    def to_frame(self) -> pd.DataFrame:
        """One row per parameter: kind, systematic?, prior sigma of the systematic part and random sigma, each as a
        ``<name>_mm`` / ``<name>_deg`` pair in the row's interface unit (:func:`tolalloc.units.unit_columns`)."""
        m = self.model
        units = [p.interface_unit for p in m.params]
        return pd.DataFrame({"parameter": m.names, "kind": m.kinds, "unit": units, "systematic": self.systematic,
                             **m.interface_columns("sigma_sys", np.where(self.systematic, m.sigma, 0)),
                             **m.interface_columns("sigma_random", self.random_sigma)})


def _kind_key(p) -> str:
    return "joint_drive_prismatic" if p.kind == "joint_drive" and p.unit == "mm" else p.kind


def _entry(p, entry: dict, where: str, out: dict) -> None:
    """Merge one override table into ``out`` (keys ``systematic`` and ``repeatability`` [internal unit])."""
    if not isinstance(entry, dict):
        raise TolallocError(f"{where}: expected a table such as {{ systematic = true }}, got {entry!r}.")
    bad = set(entry) - _KEYS
    if bad:
        raise TolallocError(f"{where}: unknown key(s) {', '.join(sorted(bad))}; expected {', '.join(sorted(_KEYS))}.")
    if "systematic" in entry:
        if not isinstance(entry["systematic"], bool):
            raise TolallocError(f"{where}.systematic: expected true or false, got {entry['systematic']!r}.")
        out["systematic"] = entry["systematic"]
    if "grade" in entry:
        if any(key.startswith("repeatability_") for key in entry):
            raise TolallocError(f"{where}: give either a fixed repeatability_* or an allocatable grade, not both.")
        if not isinstance(entry["grade"], dict):
            raise TolallocError(f"{where}.grade: expected a cost-law table such as {{ model = \"reciprocal\", a = 0.2, "
                                f"b = 0.3, t_ref_{p.interface_unit} = ..., t_min_{p.interface_unit} = ..., "
                                f"t_max_{p.interface_unit} = ... }}, got {entry['grade']!r}.")
        out["grade"], out["grade_where"] = entry["grade"], f"{where}.grade"
    for key, value in entry.items():
        if not key.startswith("repeatability_"):
            continue
        unit, fac = _FACTOR[key.split("_", 1)[1]]
        if unit != p.unit:
            raise TolallocError(f"{where}: {p.name} is in {p.interface_unit}, but {key} was given; "
                                f"use repeatability_{p.interface_unit}.")
        try:
            v = float(value)
        except (TypeError, ValueError):
            v = np.nan
        if isinstance(value, bool) or not np.isfinite(v) or v < 0:
            raise TolallocError(f"{where}.{key}: expected a finite standard deviation >= 0, got {value!r}.")
        out["repeatability"] = v * fac
        out["grade"] = None


def split_errors(model: ErrorModel, overrides: dict | None = None) -> ErrorSplit:
    """Split an error model's parameters into systematic and random parts.

    Parameters
    ----------
    model : ErrorModel
    overrides : dict, optional
        ``{"kinds": {kind: {...}}, "parameters": {name: {...}}}`` (the costs file's ``[calibration]`` table).

    Returns
    -------
    ErrorSplit
    """
    overrides = overrides or {}
    bad = set(overrides) - {"kinds", "parameters"}
    if bad:
        raise TolallocError(f"calibration: unknown section(s) {', '.join(sorted(bad))}; expected kinds, parameters.")
    kinds = overrides.get("kinds", {}) or {}
    pars = overrides.get("parameters", {}) or {}
    for kd in kinds:
        if kd not in DEFAULT_SPLIT:
            raise TolallocError(f"calibration.kinds: unknown kind {kd!r}; known: {', '.join(DEFAULT_SPLIT)}.")
    for nm in pars:
        if nm not in model.names:
            raise TolallocError(f"calibration.parameters: unknown error parameter {nm!r}; known: {', '.join(model.names)}.")
    sys_ = np.zeros(len(model.params), bool)
    rnd = np.zeros(len(model.params))
    grades: list = []
    for k, p in enumerate(model.params):
        key = _kind_key(p)
        spec: dict = {"repeatability": 0.0, "grade": None}
        _entry(p, DEFAULT_SPLIT[key], f"default split of {key}", spec)
        if key in kinds:
            _entry(p, kinds[key], f"calibration.kinds.{key}", spec)
        if p.name in pars:
            _entry(p, pars[p.name], f"calibration.parameters.{p.name}", spec)
        sys_[k] = spec["systematic"]
        rnd[k] = spec["repeatability"] if sys_[k] else p.sigma
        if spec["grade"] is not None and not sys_[k]:
            raise TolallocError(f"{spec['grade_where']}: {p.name} has no systematic part (systematic = false), so its "
                                "whole error is random and its tolerance is allocated by the costs file already; "
                                "drop the grade or set systematic = true.")
        grades.append(spec["grade"])
    return ErrorSplit(model, sys_, rnd, tuple(grades) if any(g is not None for g in grades) else None)
