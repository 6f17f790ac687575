"""Error-screw model: named geometric error parameters of a serial chain.

Every error parameter ``k`` is a small rigid displacement ``exp([xi_k] e_k)``
inserted into the POE chain at a *site* ``s`` (the number of joints before
it; ``xi_k`` is a unit twist in the base frame at home, ``(omega, v)``)::

    T = G_0 e^{[S1]q1} G_1 e^{[S2]q2} ... G_{n-1} e^{[Sn]qn} G_n M

Kinds (internal units mm / rad)::

    link_length       translation along the link vector, at the link's site
                      (consistent: moves every downstream axis *and* the tool;
                      axes_only: the paper's Eq. 24, the tool point stays -- an
                      inverse translation is inserted before M).
    joint_drive       joint value offset q_j + dq_j (twist S_j at site j).
    axis_deflection   rotation about a base axis perpendicular to the joint axis,
                      through the joint point (screw: Eqs. 20-22, before the
                      joint's exponential; tilt: Eqs. 32/37, the axis direction
                      itself tilts -- an inverse rotation follows the joint).
    clearance_axial   slip along the revolute joint axis (Table 4).
    clearance_radial  two components of a radial clearance rod s of uniform
                      random direction (Eq. 42): not Gaussian (a ring).
    clearance_tilt    clearance deflection angles about the perpendicular axes.

The insertion table is built once, as the plain-array :class:`~tolalloc.errormodel.chain.ChainProgram`
(:attr:`ErrorModel.program`); the exact perturbed chain (per-sample screws, home pose and joint offsets),
the first-order error Jacobian and both Monte Carlo engines read it.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
import pandas as pd

from tolalloc.engine import resolve_engine
from tolalloc.exceptions import TolallocError
from tolalloc.errormodel.chain import JOINT, ChainProgram, chain_program, check_joint_values, check_parameter_values
from tolalloc.robot.lie import adjoint, cross, exp_se3
from tolalloc.robot.kinematics import jacobian_kernel, prefix_lists
from tolalloc.robot.model import Robot
from tolalloc.units import unit_columns
from tolalloc.errormodel.sampling import sample_values  # the one sampler, shared with the Monte Carlo engine

__all__ = ["ErrorParameter", "ErrorModel", "KINDS", "perpendicular_axes"]

KINDS = ("link_length", "joint_drive", "axis_deflection", "clearance_axial", "clearance_radial", "clearance_tilt")

#: Defaults for robots without sigma sets (assumed typical values, see docs/howto/own-robot.md) [mm or rad].
GENERIC_SIGMA = {
    "link_length": 0.02,
    "joint_drive_revolute": np.deg2rad(0.005),
    "joint_drive_prismatic": 0.01,
    "axis_deflection": np.deg2rad(0.005),
}
#: Joint clearance of the seed paper's Table 4 [mm, rad]; tilt 0.0087 rad corrects Table 4's literal 0.087.
CLEARANCE_SIGMA = {"axial_mm": 0.2, "radial_mm": 0.5, "tilt_rad": 0.0087}
CLEARANCE_TILT_LITERAL_RAD = 0.087


@dataclass(frozen=True, eq=False)
class ErrorParameter:
    """One error parameter.

    Attributes
    ----------
    name : str
    kind : str, one of :data:`KINDS`
    element : str
        Link or joint it belongs to.
    unit : {"mm", "rad"}
        Internal unit of the value and of ``sigma``.
    site : int
        Insertion site (joints before it), ``0..n``.
    twist : array, shape (6,)
        Unit twist in the base frame at home.
    undo_site : int or None
        Site where the inverse displacement is inserted (``axes_only`` links, ``tilt`` deflections).
    sigma : float
        Standard deviation of the value [unit].
    distribution : {"normal", "uniform", "truncnormal", "ring"}
        ``ring``: the pair with the same ``group`` is ``s (cos t, sin t)`` with ``s ~ N(0, sqrt(2) sigma)``
        and ``t`` uniform, so each component has standard deviation ``sigma``.
    group : str
        Name shared by the two components of a radial clearance.
    joint_index : int or None
        For joint drives: the index of the joint (0-based).
    """

    name: str
    kind: str
    element: str
    unit: str
    site: int
    twist: np.ndarray
    undo_site: int | None = None
    sigma: float = 0.0
    distribution: str = "normal"
    group: str = ""
    joint_index: int | None = None

    @property
    def interface_unit(self) -> str:
        """Unit shown to users: ``mm`` or ``deg``."""
        return "mm" if self.unit == "mm" else "deg"

    @property
    def to_interface(self) -> float:
        """Factor converting internal values to ``interface_unit``."""
        return 1.0 if self.unit == "mm" else 180.0 / np.pi


def perpendicular_axes(axis: np.ndarray):
    """The two base axes most perpendicular to ``axis`` (Gram-Schmidt against it), with their letters."""
    order = [i for i in range(3) if i != int(np.argmax(np.abs(axis)))]
    out = []
    for i in order:
        e = np.eye(3)[i]
        e = e - axis * (axis @ e)
        out.append(("xyz"[i], e / np.linalg.norm(e)))
    return out


@dataclass(frozen=True, eq=False)
class ErrorModel:
    """The error parameters of a robot with their standard deviations and modelling options.

    Attributes
    ----------
    robot : Robot
    params : tuple of ErrorParameter
    link_mode : {"consistent", "axes_only"}
    deflection_mode : {"screw", "tilt"}
    sigma_set : str
    """

    robot: Robot
    params: tuple
    link_mode: str = "consistent"
    deflection_mode: str = "screw"
    sigma_set: str = "generic"

    # ---------------------------------------------------------------- views
    @property
    def names(self) -> list[str]:
        return [p.name for p in self.params]

    @property
    def kinds(self) -> np.ndarray:
        return np.array([p.kind for p in self.params])

    @property
    def sigma(self) -> np.ndarray:
        """Standard deviations [mm or rad], shape (K,)."""
        return np.array([p.sigma for p in self.params])

    @property
    def labels(self) -> dict:
        """Options as shown in outputs."""
        return {"sigma_set": self.sigma_set, "link_mode": self.link_mode, "deflection_mode": self.deflection_mode}

    def index(self, name: str) -> int:
        try:
            return self.names.index(name)
        except ValueError:
            raise TolallocError(f"unknown error parameter {name!r}; known: {', '.join(self.names)}") from None

    def with_sigma(self, sigma) -> "ErrorModel":
        """A copy with new standard deviations, shape (K,) [mm or rad]."""
        sigma = np.asarray(sigma, dtype=float)
        if sigma.shape != (len(self.params),) or np.any(~np.isfinite(sigma)) or np.any(sigma < 0):
            raise TolallocError(f"sigma: expected {len(self.params)} finite values >= 0, got {np.array2string(sigma, threshold=8)}")
        return replace(self, params=tuple(replace(p, sigma=float(s)) for p, s in zip(self.params, sigma)))

    def interface_columns(self, name: str, values, names=None) -> dict:
        """Per-parameter values in internal units (mm, rad) as a ``<name>_mm`` / ``<name>_deg`` column pair in the
        interface units (:func:`tolalloc.units.unit_columns`).

        Parameters
        ----------
        name : str
            Column stem (``tol``, ``sigma``).
        values : array, shape (K,) [mm or rad]
            One value per parameter of ``names`` (default: every parameter, in model order).
        names : sequence of str, optional
        """
        params = self.params if names is None else [self.params[self.index(nm)] for nm in names]
        f = np.array([p.to_interface for p in params])
        return unit_columns(name, np.asarray(values, float) * f, np.array([p.interface_unit == "mm" for p in params]))

    def to_frame(self) -> pd.DataFrame:
        """One row per parameter: ``parameter, kind, element, unit, sigma_mm, sigma_deg, distribution``; the sigma
        in ``sigma_mm`` on length rows, in ``sigma_deg`` on angle rows, the other one NaN."""
        return pd.DataFrame({
            "parameter": self.names,
            "kind": self.kinds,
            "element": [p.element for p in self.params],
            "unit": [p.interface_unit for p in self.params],
            **self.interface_columns("sigma", self.sigma),
            "distribution": [p.distribution for p in self.params],
        })

    # ------------------------------------------------------------- sampling
    def sample(self, n: int, rng: np.random.Generator) -> np.ndarray:
        """Draw ``n`` samples of all parameter values, shape (n, K) [mm or rad]."""
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
            raise TolallocError(f"n: expected a whole number of samples >= 0, got {n!r}")

        return sample_values(self, n, rng).T

    # ------------------------------------------------------- exact chains
    @cached_property
    def program(self) -> ChainProgram:
        """The perturbed chain as the plain-array program every evaluator reads (:mod:`tolalloc.errormodel.chain`)."""
        return chain_program(self)

    def perturbed_chain(self, values: np.ndarray, *, engine: str | None = None):
        """Exact perturbed chains for sampled parameter values (the generic path, from :attr:`program`).

        Parameters
        ----------
        values : array, shape (N, K) [mm or rad]
            One column per parameter, in the order of :attr:`names`; another width is refused.
        engine : {None, "auto", "numba", "numpy"}
            As :func:`tolalloc.engine.resolve_engine`: the compiled walk over the program
            (:mod:`tolalloc.errormodel._chain_nb`) or the numpy one; equal to rounding.

        Returns
        -------
        screws : array, shape (N, n, 6)
        home : array, shape (N, 4, 4)
        dq : array, shape (N, n)
            Joint offsets; evaluate ``fk_poe(screws, home, q + dq)``.
        """
        values = np.atleast_2d(np.asarray(values, dtype=float))
        check_parameter_values(self, values)
        N = values.shape[0]
        prog = self.program
        n = self.robot.n_joints
        dq = np.zeros((N, n))
        screws = np.empty((N, n, 6))
        amounts = prog.amounts(values)  # (N, F)
        if resolve_engine(engine) == "numba":
            from tolalloc.errormodel import _chain_nb

            home = np.empty((N, 4, 4))
            _chain_nb.perturbed_chain(*prog.kernel_arrays, amounts, screws, home, dq)
            return screws, home, dq
        C = np.broadcast_to(np.eye(4), (N, 4, 4)).copy()
        err = [f for f in range(prog.n_factors) if prog.kind[f] != JOINT]
        E = (exp_se3(amounts[:, err, None] * prog.twist[err]) if err else None)  # (N, len(err), 4, 4): one call
        pos = {f: i for i, f in enumerate(err)}
        for f in range(prog.n_factors):
            if prog.kind[f] == JOINT:  # E_j = exp([S'_j](q_j + dq_j)) with S'_j = Ad_C S_j
                j = int(prog.joint[f])
                dq[:, j] += amounts[:, f]
                screws[:, j, :] = adjoint(C) @ prog.twist[f]
            else:
                C = C @ E[:, pos[f]]
        home = C @ prog.home
        return screws, home, dq

    # ----------------------------------------------------- first order
    def jacobian(self, q: np.ndarray, *, engine: str | None = None) -> np.ndarray:
        """First-order error Jacobian of the tool pose at ``q`` (from :attr:`program`).

        Parameters
        ----------
        q : array, shape (..., n) [rad, mm]
        engine : {None, "auto", "numba", "numpy"}
            As :func:`tolalloc.robot.kinematics.space_jacobian` (compiled kernel for many poses (P, n)).

        Returns
        -------
        J : array, shape (..., 6, K)
            Rows: tool-point position error ``dp`` [mm] (3), then the rotation
            error ``dw`` (space frame) [rad] (3), per unit of each parameter: the sum over the parameter's
            factors ``f`` of ``coef_f Ad_{P_site(f)} twist_f`` (``P_s`` the nominal prefix product).
        """
        q = np.asarray(q, dtype=float)
        check_joint_values(self, q)
        nb = jacobian_kernel(self.robot.screws, q, engine)
        if nb is not None:
            return nb.error_jacobian(self.robot.screws, self.robot.home[:3, 3], q, *self.program.param_entries())
        R, p = prefix_lists(self.robot.screws, q)  # lists over sites 0..n of (..., 3, 3), (..., 3)
        batch = q.shape[:-1]
        K = len(self.params)
        # spatial twist Ad_{P_site} xi = (R w, R v + p x R w) per entry, grouped by insertion site and coefficient
        Rw = np.zeros(batch + (3, K))
        Vv = np.zeros(batch + (3, K))
        for site, idx, cf, W in self.program.site_groups():
            Rs = np.ascontiguousarray(np.broadcast_to(R[site], batch + (3, 3)))
            rw = (Rs.reshape(-1, 3) @ W[:3]).reshape(batch + (3, len(idx)))  # one BLAS product per site
            vv = (Rs.reshape(-1, 3) @ W[3:]).reshape(batch + (3, len(idx))) + cross(p[site][..., :, None], rw, axis=-2)
            if cf == 1.0:
                Rw[..., idx] += rw
                Vv[..., idx] += vv
            elif cf == -1.0:
                Rw[..., idx] -= rw
                Vv[..., idx] -= vv
            else:
                Rw[..., idx] += cf * rw
                Vv[..., idx] += cf * vv
        p_tool = (R[-1] @ self.robot.home[:3, 3]) + p[-1]  # (..., 3)
        dp = Vv - cross(p_tool[..., :, None], Rw, axis=-2)  # (..., 3, K): p_tool x every column
        return np.concatenate([dp, Rw], axis=-2)
