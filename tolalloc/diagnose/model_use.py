"""The identified model of a diagnosis, for use: target points at new joint values and covariates, their
uncertainty, and the model's Jacobian in the joints (for the compensation's inverse kinematics, :mod:`.compensate`).

This module is the one place that reads how a :class:`~tolalloc.diagnose.diagnosis.Diagnosis` holds its final
model: the final :class:`~tolalloc.diagnose.calibrate.Fit` (geometric parameters, probe offset, effect parameters,
registration), the effects and their variants (the selection's candidates), and the effect bases, which it rebuilds
with :func:`~tolalloc.diagnose.effects.effect_basis` and :func:`~tolalloc.diagnose.select.align_basis` the way the
selection built them. Everything that uses a diagnosis's model (prediction, compensation, export, fleets) goes
through :class:`IdentifiedModel`, so that a change in the diagnosis's internals is followed here only.
:func:`identified_model` checks its reconstruction: the rebuilt model must reproduce the final fit's residuals on
the training poses (to :data:`REBUILD_TOL_MM`), else it refuses.

Frames: ``base`` is the robot's base frame as the identified model defines it (the registration absorbs base
errors: the identified geometry's first joint sits where the nominal one does, up to the unidentifiable
parameters); ``tracker`` is the training file's measurement frame (``R x + p``). The point is the measured target
(the nominal robot's tool point plus the fitted probe offset ``t_mm``, flange frame).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.robot.kinematics import fk_poe, space_jacobian
from tolalloc.robot.model import Robot
from tolalloc.physics.thermal import is_measurement_column
from tolalloc.diagnose.calibrate import Fit
from tolalloc.diagnose.effects import effect_basis, effect_reference
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.select import align_basis, carry_problem
from tolalloc.diagnose.uncertainty import information_parts, parameter_covariance, point_jacobian

__all__ = ["IdentifiedModel", "identified_model", "calibrated_model", "FRAMES", "REBUILD_TOL_MM", "LOAD_EFFECTS"]

#: Frames of predictions and targets.
FRAMES = ("base", "tracker")
#: Largest difference [mm] between the rebuilt model's training predictions and the final fit's.
REBUILD_TOL_MM = 1e-6
#: Effects whose basis depends on the payload (gravity and payload loads).
LOAD_EFFECTS = ("joint_compliance", "mount_compliance", "link_deflection", "backlash")


@dataclass(frozen=True, eq=False)
class IdentifiedModel:
    """A diagnosis's final model, ready to evaluate at new poses.

    Attributes
    ----------
    robot : Robot                 the nominal robot
    fit : Fit                     the final fit (geometry ``delta``, probe offset ``t_mm``, effect ``beta``, ``R``,
                                  ``p_mm``)
    effects : tuple of str        selected effects, in the order of the fit's effect columns
    variants : dict               effect -> variant
    columns : dict                effect -> names of its training basis columns (before ``keep``)
    keep : array of int           kept columns of the concatenated bases
    ref : dict                    the training file's effect reference (:func:`~.effects.effect_reference`)
    basis_t_mm : array, shape (3,)   probe offset the effect bases are built with [mm]
    cov : array, shape (N, N) or None   parameter covariance (columns of :func:`~.uncertainty.point_jacobian`)
    noise_mm : float              measurement noise per coordinate of the training fit [mm]
    payload_in_training : bool    the training file logged a non-zero payload
    train : Measurements or None  the training poses (None for a model rebuilt from a file)
    unidentifiable : dict         geometric parameters the training poses could not separate -> why
    verdict : str or None         the diagnosis's verdict (``effect``, ``none``, ``ambiguous``, ``inconclusive``)
    """

    robot: Robot
    fit: Fit
    effects: tuple = ()
    variants: dict | None = None
    columns: dict | None = None
    keep: np.ndarray | None = None
    ref: dict | None = None
    basis_t_mm: np.ndarray | None = None
    cov: np.ndarray | None = None
    noise_mm: float = float("nan")
    payload_in_training: bool = False
    train: Measurements | None = None
    unidentifiable: dict | None = None
    verdict: str | None = None

    @property
    def param_names(self) -> tuple:
        """The fitted effect parameters, ``effect:column [unit]``."""
        return tuple(self.fit.effect_names)

    def covariates(self) -> dict:
        """Covariate columns the model needs at new poses -> why (the effects and variants that read them)."""
        need = {}
        probe = Measurements(np.zeros((1, self.robot.n_joints)), np.zeros((1, 3)))
        for e in self.effects:
            v = self.variants[e]
            why = carry_problem(e, v, probe)
            if why is not None:
                for col in ("temperature_c", "time_s", "dir"):
                    if col.split("_")[0] in why:
                        need.setdefault(col, []).append(f"{e} ({v})")
            if e in LOAD_EFFECTS and self.payload_in_training:
                need.setdefault("payload_kg", []).append(f"{e} ({v})")
        return need

    def measurements(self, q, *, payload_kg=None, temperature_c=None, time_s=None, direction=None,
                     wrench=None) -> Measurements:
        """Poses ``q`` (P, n) [rad, mm] with their covariates as a measurement set (no positions), checked against what
        the model's effects need (:meth:`covariates`); ``wrench`` (P, 6) a process wrench at the target [N, N m], base
        frame (none: no process force)."""
        q = np.atleast_2d(np.asarray(q, dtype=float))
        P = len(q)

        def col(v, name):
            if v is None:
                return None
            shape = {"dir": q.shape, "wrench": (P, 6)}.get(name, (P,))
            a = np.broadcast_to(np.asarray(v, dtype=float), shape).copy()
            if not np.all(np.isfinite(a)):
                raise TolallocError(f"{name}: expected finite values, one per pose, got NaN or infinite ones.")
            return a

        meas = Measurements(q, np.zeros((P, 3)), col(temperature_c, "temperature_c"), col(direction, "dir"),
                            col(payload_kg, "payload_kg"), col(time_s, "time_s"), wrench=col(wrench, "wrench"))
        for e in self.effects:
            why = carry_problem(e, self.variants[e], meas, "the program")
            if why is not None:
                raise TolallocError(f"the identified model's {e} effect (variant {self.variants[e]}) cannot be "
                                    f"evaluated at these poses: {why}; "
                                    + ("pass the column (the training file had it)." if " has no " in why else
                                       "give values it can use, as the training file's were."))
        if meas.payload_kg is None and self.payload_in_training and set(self.effects) & set(LOAD_EFFECTS):
            raise TolallocError("payload_kg: the identified model's load effects ("
                                + ", ".join(e for e in self.effects if e in LOAD_EFFECTS)
                                + ") were fitted with a logged payload; pass payload_kg for these poses too.")
        return meas

    def basis(self, meas: Measurements) -> np.ndarray | None:
        """The kept effect columns at the poses of ``meas``, shape (P, 3, m) [mm per unit], base frame; None without
        effects."""
        if not self.effects:
            return None
        parts = [align_basis(effect_basis(e, self.robot, meas, self.basis_t_mm, self.ref), self.columns[e]).B
                 for e in self.effects]
        return np.concatenate(parts, axis=2)[:, :, self.keep]

    def points(self, meas: Measurements, frame: str = "base") -> np.ndarray:
        """Predicted target points at the poses of ``meas`` [mm], shape (P, 3), in ``frame``: ``tracker`` what the
        instrument measures, ``base`` where the robot puts the target relative to its base -- without a drift between
        the two frames (:func:`~tolalloc.physics.thermal.is_measurement_column`)."""
        B = self.basis(meas)
        if _frame(frame) == "base":
            return self.fit.base_points(meas.q, self.robot_only(B))
        return self.fit.base_points(meas.q, B) @ self.fit.R.T + self.fit.p_mm

    def robot_only(self, B: np.ndarray | None) -> np.ndarray | None:
        """``B`` (P, 3, m) (:meth:`basis`) with the columns of a drift between the measuring frame and the base set to
        zero."""
        inst = [is_measurement_column(nm.split(":", 1)[1]) for nm in self.fit.effect_names]
        if B is None or not any(inst):
            return B
        B = B.copy()
        B[:, :, np.array(inst)] = 0.0
        return B

    def chain(self) -> tuple:
        """The identified geometry as a POE chain: ``screws (n, 6)``, ``home (4, 4)``, joint offsets ``dq (n,)``;
        ``fk_poe(screws, home, q + dq)`` is the flange-with-tool pose, the target point ``T [t_mm; 1]``."""
        screws, home, dq = self.fit.model.perturbed_chain(self.fit.delta[None, :])
        return screws[0], home[0], dq[0]

    def geometric_points(self, q) -> np.ndarray:
        """Target points of the identified geometry alone (no effects) [mm], base frame, shape (P, 3)."""
        screws, home, dq = self.chain()
        T = fk_poe(screws, home, np.atleast_2d(q) + dq)
        return T[:, :3, 3] + T[:, :3, :3] @ self.fit.t_mm

    def joint_jacobian(self, q, frame: str = "base") -> np.ndarray:
        """d(target point) / d(joint values) of the identified geometry, shape (P, 3, n) [mm per rad or mm]
        (the effects' own slope in the joints, a small fraction of it, is left out)."""
        screws, _, dq = self.chain()
        q = np.atleast_2d(q)
        Js = space_jacobian(screws, q + dq)
        p = self.geometric_points(q)
        J = Js[:, 3:, :] + np.cross(Js[:, :3, :], p[:, :, None], axis=1)
        return J if _frame(frame) == "base" else np.einsum("ij,pjn->pin", self.fit.R, J)

    def point_covariance(self, meas: Measurements, frame: str = "base") -> np.ndarray:
        """Covariance of the predicted points from the parameter covariance [mm^2], shape (P, 3, 3).

        ``base``: the probe offset, geometric and effect parameters (the registration defines the base frame and
        leaves it); ``tracker``: all parameters, the registration's included."""
        if self.cov is None:
            raise TolallocError("this identified model has no parameter covariance (built with covariance=False, or "
                                "read from a file exported without one); rebuild it from the diagnosis.")
        J = point_jacobian(self.fit, meas.q, self.basis(meas))
        if _frame(frame) == "base":
            J, C = np.einsum("ji,pjk->pik", self.fit.R, J[:, :, 6:]), self.cov[6:, 6:]
        else:
            C = self.cov
        S = np.einsum("pik,kl,pjl->pij", J, C, J)
        return 0.5 * (S + np.swapaxes(S, 1, 2))

    def information(self) -> tuple:
        """The training data's information about the fitted parameters and the fit's prior precisions
        (:func:`~tolalloc.diagnose.uncertainty.information_parts`: ``data (N, N)``, ``prior (N,)``, ``noise2``),
        columns of :func:`~tolalloc.diagnose.uncertainty.point_jacobian`: registration (6), probe offset (3),
        geometric parameters ``fit.geo_index``, effect columns."""
        if self.train is None:
            raise TolallocError("this identified model has no training poses (it was rebuilt from a file); use the "
                                "diagnosis itself.")
        return information_parts(self.fit, self.train.q, self.basis(self.train))

    def nominal(self) -> "IdentifiedModel":
        """The nominal robot with this model's probe offset and registration (no geometric errors, no effects)."""
        fit = replace(self.fit, delta=np.zeros_like(self.fit.delta), geo_index=np.zeros(0, int), beta=np.zeros(0),
                      beta_index=np.zeros(0, int), effect_names=())
        return replace(self, fit=fit, effects=(), keep=np.zeros(0, int), cov=None)


def _frame(frame: str) -> str:
    if frame not in FRAMES:
        raise TolallocError(f"frame: expected one of {', '.join(FRAMES)}, got {frame!r}.")
    return frame


def _variants(diagnosis, effects) -> dict:
    """Each selected effect's variant, from the selection's candidates (every stage scores the same variant)."""
    found = {}
    for st in diagnosis.stages:
        for c in st.candidates:
            if c.effect in effects and getattr(c, "variant", ""):
                found.setdefault(c.effect, c.variant)
    missing = [e for e in effects if e not in found]
    if missing:
        raise TolallocError(f"the diagnosis records no variant for the effect(s) {', '.join(missing)}; the identified "
                            "model cannot be rebuilt from it.")
    return found


def identified_model(diagnosis, *, covariance: bool = True) -> IdentifiedModel:
    """The final model of ``diagnosis`` (:class:`~tolalloc.diagnose.diagnosis.Diagnosis`) as an
    :class:`IdentifiedModel`, checked against the final fit's training residuals (module docstring).

    ``covariance``: also the parameter covariance (for :meth:`IdentifiedModel.point_covariance`).
    """
    d = diagnosis
    fit, train, robot = d.final.fit, d.train, d.robot
    effects = tuple(d.final.effects)
    t = d.calibration.geometric.t_mm
    variants = _variants(d, effects) if effects else {}
    if getattr(d, "effect_ref", None) is not None:  # the diagnosis's own reference: its searched gear ratios too
        ref = dict(d.effect_ref, variants=dict(variants))
    else:
        ref = effect_reference(train, robot.components.gear_ratios([jt.name for jt in robot.joints]), robot)
        ref["variants"] = dict(variants)
    columns, names = {}, []
    for e in effects:
        b = effect_basis(e, robot, train, t, ref)
        columns[e] = tuple(b.names)
        names += [f"{e}:{nm}" for nm in b.names]
    keep = np.asarray(d.final.keep, int) if effects else np.zeros(0, int)
    pay = train.payload_kg is not None and bool(np.any(train.payload_kg != 0))
    v = d.verdict.verdict if d.verdict is not None else None
    model = IdentifiedModel(robot, fit, effects, variants, columns, keep, ref, np.asarray(t, float),
                            payload_in_training=pay, train=train, verdict=v,
                            unidentifiable=dict(d.calibration.identifiability.reasons))
    if effects and tuple(names[k] for k in keep) != tuple(fit.effect_names):
        raise TolallocError("the identified model's effect columns could not be rebuilt from the diagnosis (the "
                            "rebuilt names differ from the final fit's); this is a defect -- please report it.")
    B = model.basis(train)
    gap = np.abs((train.xyz_mm - fit.predict(train.q, B)) - fit.residual_mm).max() if len(train.q) else 0.0
    if not gap <= REBUILD_TOL_MM:
        raise TolallocError(f"the identified model rebuilt from the diagnosis misses the final fit's training "
                            f"predictions by up to {gap:.3g} mm (expected below {REBUILD_TOL_MM:g} mm); this is a "
                            "defect -- please report it.")
    if covariance:
        cov, noise = parameter_covariance(fit, train.q, B)
        model = replace(model, cov=cov, noise_mm=noise)
    return model


def calibrated_model(calibration, train: Measurements, *, covariance: bool = True) -> IdentifiedModel:
    """The geometric model of a calibration (:func:`~tolalloc.diagnose.calibrate.calibrate` on ``train``) as an
    :class:`IdentifiedModel`: no effects, no verdict (a calibrated robot, not a diagnosed one)."""
    fit = calibration.geometric
    if len(fit.residual_mm) != train.n_poses:
        raise TolallocError(f"calibrated_model: the calibration was fitted on {len(fit.residual_mm)} poses, the "
                            f"measurements given hold {train.n_poses}; give the set it was calibrated on.")
    model = IdentifiedModel(fit.model.robot, fit, (), {}, {}, np.zeros(0, int), {}, np.asarray(fit.t_mm, float),
                            train=train, unidentifiable=dict(calibration.identifiability.reasons))
    if covariance:
        cov, noise = parameter_covariance(fit, train.q)
        model = replace(model, cov=cov, noise_mm=noise)
    return model
