"""The result of the joint allocation with bought parts, and the check of the parts' ratings.

:class:`PartsAllocation` holds the design (machining standard values and one part per slot), the proof of the
mixed-integer program, the active points and the region's worst point; :meth:`PartsAllocation.parts_table` is the
per-joint *part to buy* (name, family, grade, cost and its source, the figures, the share of the variance it carries
at the worst point), :meth:`PartsAllocation.variance_shares` the whole budget there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.stats import qmc

from tolalloc.errormodel.parts import EFFECTS, PartEffects
from tolalloc.exceptions import TolallocError
from tolalloc.robot.components import ARCMIN, ARCSEC
from tolalloc.robot.part_catalogue import builtin_catalogue

__all__ = ["PartsAllocation", "check_rated_options", "part_figures"]


def part_figures(kind: str, spec, motion: str = "rotary") -> str:
    """The figures of a part that matter for accuracy, as one line; ``motion``: ``"linear"`` for a prismatic joint's
    part (a ball screw, a linear scale: mm, N/um, N), else rotary (arcmin, arcsec, N m/rad, N m)."""
    linear = motion == "linear"
    ang = (lambda x: f"{x * 1000:.3g} um") if linear else (lambda x: f"{x / ARCMIN:.3g} arcmin")
    if kind == "reducer":
        out = [spec.type]
        if spec.transmission_accuracy is not None:
            out.append(f"transmission accuracy {ang(spec.transmission_accuracy)}")
        if spec.lost_motion is not None:
            out.append(f"lost motion {ang(spec.lost_motion)}")
        if spec.stiffness:
            out.append(f"stiffness {spec.stiffness[-1] / 1000:.3g} N/um" if linear else
                       f"stiffness {spec.stiffness[-1]:.3g} N m/rad")
        if spec.rated_torque is not None:
            out.append(f"rated {spec.rated_torque:.4g} {'N' if linear else 'N m'}")
        return ", ".join(out)
    if kind == "encoder":
        acc = (spec.accuracy or 0)
        figure = f"{acc * 1000:.3g} um" if linear else f"{acc / ARCSEC:.3g} arcsec"
        return f"{spec.side}-side, accuracy {figure} peak-to-peak"
    if kind == "bearing":
        return (f"ISO 492 {spec.precision_class}: Kia {spec.radial_runout * 1000:.3g} um at bore {spec.bore_mm:g} mm, "
                f"span {spec.span_mm:g} mm")
    return f"R {spec.winding_resistance_ohm} ohm, k_t {spec.torque_constant_Nm_per_A} N m/A"


def check_rated_options(robot, model, region, q, cond, seed: int = 0) -> None:
    """Refuse every reducer (a slot's option, or the figures of the file) whose rated torque the gravity load (with the
    conditions' process wrench) exceeds at the top of the payload range, at ``q`` or anywhere in a 256-point Sobol
    sample of ``region``."""
    if region is not None:
        lo, hi = region.q_min, region.q_max
        q = np.vstack([q, lo + qmc.Sobol(len(lo), scramble=True, seed=seed).random(256) * (hi - lo)])
    fx = PartEffects(robot, q, cond.payload_kg[1], cond.ambient_c[1], cond, model)
    load = np.abs(fx.tau).max(axis=0)
    where = "the region" if region is not None else "the poses"
    for j, jt in enumerate(robot.joints):
        slot = robot.components.slots.get((jt.name, "reducer"))
        opts = [(p.name, p.spec) for p in slot.options] if slot is not None else (
            [("its reducer", robot.components.joint(jt.name).reducer)] if robot.components.joint(jt.name).reducer
            else [])
        for name, red in opts:
            if red.rated_torque is None or load[j] <= red.rated_torque:
                continue
            unit = "N m" if jt.is_revolute else "N"
            ok = sorted((p.spec.rated_torque, p.family) for p in builtin_catalogue().parts["reducer"].values()
                        if p.motion == ("rotary" if jt.is_revolute else "linear") and p.spec.rated_torque
                        and p.spec.rated_torque >= load[j])
            fams = list(dict.fromkeys(f"{f} ({r:.4g} {unit})" for r, f in ok))[:3]
            what = "the load (gravity and the process wrench)" if cond.has_process_wrench else "the gravity load"
            raise TolallocError(
                f"joint {jt.name}: {name} is rated {red.rated_torque:.4g} {unit}, but {what} reaches "
                f"{load[j]:.4g} {unit} in {where} at the payload of {cond.payload_kg[1]:g} kg, "
                f"{load[j] - red.rated_torque:.4g} {unit} ({100 * (load[j] / red.rated_torque - 1):.0f} %) above; "
                f"drop it, or choose a reducer rated for at least {load[j]:.4g} {unit}"
                + (f" (in the built-in catalogue: {', '.join(fams)})" if fams else "")
                + ", or lower the payload range" + (" or the process wrench" if cond.has_process_wrench else ""))


@dataclass(frozen=True, eq=False)
class PartsAllocation:
    """Result of :func:`tolalloc.allocate.parts.allocate_parts`.

    Attributes
    ----------
    problem : PartsProblem           the final active points with the chosen parts folded in
    design : Design                  machining half-widths of the joint certified design (``discrete-trace`` or
                                     ``discrete-lmi``)
    outcome : PartsOutcome           the mixed-integer program's proof (``status``, ``gap``, ``bound``)
    choice : dict                    ``{(joint, kind): part name}`` (every slot)
    labels : tuple of str            machining standard value per allocatable parameter (``IT7``, a class, "")
    shares : OptionBlocks            the chosen parts' terms at the worst point
    points : Points                  active points
    worst : WorstPoint               the worst point found for the design (the region's; without a region, the worst
                                     active point)
    conditions : Conditions
    after : str
    residual : float or dict
    rounds, programs : int
    converged : bool                 the worst ratio found is within ``1 + tol``
    history : tuple of (round, cost, worst ratio)
    machining : AllocationResult or None   step 4: the machining allocation with these parts
    region : Region or None
    time_s, cpu_s : float            wall time and the process's CPU time (all threads) [s]
    verification : PartsVerification or None    the nonlinear Monte Carlo, when a job ran it
    """

    problem: object
    design: object
    outcome: object
    choice: dict
    labels: tuple
    shares: object
    points: object
    worst: object
    conditions: object
    after: str
    residual: object
    rounds: int
    converged: bool
    programs: int
    history: tuple
    machining: object
    region: object
    time_s: float
    cpu_s: float = float("nan")
    verification: object = None

    @property
    def ok(self) -> bool:
        return self.design.ok and self.converged

    @property
    def parts_cost(self) -> float:
        return float(self.outcome.parts_cost)

    @property
    def machining_cost(self) -> float:
        return float(self.design.cost)

    @property
    def cost(self) -> float:
        return self.parts_cost + self.machining_cost

    def _slots(self):
        return self.problem.model.robot.components.slots

    def variance_shares(self) -> pd.DataFrame:
        """The budget at the worst point: one row per source -- the machining tolerances, each bought part, each
        effect that belongs to no part -- with the trace of its covariance [mm^2] and its share [%]."""
        sh, pr = self.shares, self.problem
        m = pr.model_for(self.design.t)
        J = m.jacobian(self.worst_point.q)[0, :3, :]
        rows = [("machining", "tolerances", float(np.sum(J ** 2 * m.sigma ** 2)))]
        for z, key in enumerate(sh.keys):
            rows.append((self.choice[key], f"{key[0]} {key[1]}", float(np.trace(sh.cov[z, 0]))))
        for e in EFFECTS:
            t = sh.fixed.of_effect(e)
            if t.names:
                rows.append((e, "effect", float(np.trace(t.moments(self.after, self.residual)[1][0]))))
        df = pd.DataFrame(rows, columns=["source", "what", "trace_mm2"])
        df["share_pct"] = 100 * df["trace_mm2"] / df["trace_mm2"].sum()
        return df

    @property
    def worst_point(self):
        """The worst point found (:attr:`worst`'s point)."""
        from tolalloc.allocate.parts_problem import Points

        if self.worst is not None:
            return self.worst.point
        return Points(self.points.q[:1], self.points.payload_kg[:1], self.points.ambient_c[:1])

    def parts_table(self) -> pd.DataFrame:
        """Per slot, the part to buy: ``joint, kind, part, family, grade, options, cost, cost_source, figures, source,
        variance_share_pct`` (share of the tool-error variance at the worst point)."""
        shares = self.variance_shares().set_index("what")["share_pct"]
        rows = []
        for key, slot in self._slots().items():
            p = slot.part(self.choice[key])
            rows.append({"joint": key[0], "kind": key[1], "part": p.name, "family": p.family, "grade": p.grade,
                         "options": " | ".join(slot.names), "cost": p.cost, "cost_source": p.cost_source,
                         "figures": part_figures(key[1], slot.resolve(p.name), p.motion), "source": p.source,
                         "variance_share_pct": float(shares.get(f"{key[0]} {key[1]}", np.nan))})
        return pd.DataFrame(rows)

    def to_frame(self) -> pd.DataFrame:
        """:meth:`parts_table`."""
        return self.parts_table()

    def tolerances(self) -> pd.DataFrame:
        """The machining tolerances of the design: ``parameter, unit, tol_mm, tol_deg, standard, cost``."""
        pr = self.problem
        m = pr.model
        std = [""] * len(m.params)
        for a, k in enumerate(pr.alloc):
            std[k] = self.labels[a]
        return pd.DataFrame({"parameter": m.names, "unit": [p.interface_unit for p in m.params],
                             **m.interface_columns("tol", self.design.t), "standard": std,
                             "cost": pr.param_costs(self.design.t)})

    def summary(self) -> dict:
        """Costs, the program's proof, the points, the worst point and the run's time (JSON-ready)."""
        w = self.worst_point
        robot = self.problem.model.robot
        out = self.outcome
        return {"robot": robot.name, "status": self.design.status, "converged": self.converged,
                "rule": out.rule, "cost": self.cost, "machining_cost": self.machining_cost,
                "parts_cost": self.parts_cost, "mip_status": out.status, "mip_gap": out.gap,
                "mip_bound": out.bound, "programs": self.programs, "rounds": self.rounds,
                "active_points": len(self.points), "after": self.after,
                "worst_q_deg_mm": robot.q_to_interface(w.q[0]).tolist(),
                "worst_payload_kg": float(w.payload_kg[0]), "worst_ambient_c": float(w.ambient_c[0]),
                "worst_ratio": None if self.worst is None else float(self.worst.ratio),
                "time_s": self.time_s, "cpu_s": self.cpu_s}
