"""ISO 9283 static compliance (clause 10) predicted from the bought parts: the mechanical interface's displacement
per unit load.

The standard loads the mechanical interface in steps up to the rated load, along and against each axis of the base
frame, with the robot holding its pose, and states the largest displacement per unit load [mm/N] per direction. The
prediction loads and reads the mechanical interface too -- the end of the robot file's chain, its tool offset left out
(a tool point away from the flange would add the tool's lever to every load) -- and applies the loads to the parts'
elastic physics (:class:`tolalloc.errormodel.parts.PartEffects`, one implementation with the design and the
diagnosis): the gears' wind-up on their catalogue torque-torsion curves (a hardening gear is stiffer once the arm's
own weight has taken up its soft band, so the preload matters), the joint bearings' tilt (both filed under
``compliance``), the links' bending and the mount's tilt. The displacement of a load is the elastic deflection with
it less the deflection under the arm's own weight alone (the test zeroes its indicator at the unloaded pose). The
robot carries no payload (the load is the test's); thermal growth, gear and encoder errors do not change with the
load and are left out.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import pandas as pd

from tolalloc.errormodel.build import build_error_model
from tolalloc.errormodel.parts import Conditions, PartEffects, parts_error_model
from tolalloc.exceptions import ArgumentError, TolallocError

__all__ = ["StaticCompliance", "static_compliance", "ELASTIC", "LOAD_DIRECTIONS", "GRAVITY"]

#: the effects whose mean changes with a load at the tool
ELASTIC = ("compliance", "beam", "mount")
#: the six load directions of the test: along and against the base frame's axes
LOAD_DIRECTIONS = ("+x", "-x", "+y", "-y", "+z", "-z")
#: standard gravity [m/s^2] (the rated payload's weight as the full test load)
GRAVITY = 9.80665


@dataclass(frozen=True, eq=False)
class StaticCompliance:
    """The predicted static compliance test at one pose.

    Attributes
    ----------
    robot : str
    q : array, shape (n,) [rad, mm]
    loads_n : array, shape (S,) [N]
        The load steps.
    displacement_mm : array, shape (6, S, 3) [mm]
        The mechanical interface's displacement per load direction (:data:`LOAD_DIRECTIONS`) and step, base frame.
    by_effect_mm : dict effect -> array, shape (6, S, 3)
        Each elastic effect's part of it (:data:`ELASTIC`).
    """

    robot: str
    q: np.ndarray
    loads_n: np.ndarray
    displacement_mm: np.ndarray
    by_effect_mm: dict

    @property
    def compliance_mm_per_n(self) -> np.ndarray:
        """The largest displacement per unit load over the steps, per direction, shape (6,) [mm/N]."""
        return (np.linalg.norm(self.displacement_mm, axis=-1) / self.loads_n[None, :]).max(axis=1)

    def to_frame(self) -> pd.DataFrame:
        """One row per direction and load step: the displacement (components and length), the displacement per unit
        load and each effect's share of the length."""
        rows = []
        for d, name in enumerate(LOAD_DIRECTIONS):
            for s, load in enumerate(self.loads_n):
                v = self.displacement_mm[d, s]
                n = float(np.linalg.norm(v))
                row = {"direction": name, "load_N": float(load), "dx_mm": v[0], "dy_mm": v[1], "dz_mm": v[2],
                       "displacement_mm": n, "compliance_mm_per_N": n / float(load)}
                for e, part in self.by_effect_mm.items():       # the share along the total displacement
                    row[f"{e}_pct"] = 100.0 * float(part[d, s] @ v) / n ** 2 if n > 0 else 0.0
                rows.append(row)
        return pd.DataFrame(rows)

    def text(self) -> str:
        """One line per direction: the compliance and the effect that gives most of it at the full load."""
        c = self.compliance_mm_per_n
        lines = [f"ISO 9283 static compliance (predicted from the parts) of {self.robot}, loads up to "
                 f"{self.loads_n[-1]:.4g} N at the mechanical interface:"]
        for d, name in enumerate(LOAD_DIRECTIONS):
            v = self.displacement_mm[d, -1]
            shares = {e: float(p[d, -1] @ v) for e, p in self.by_effect_mm.items()}
            top = max(shares, key=shares.get) if np.any(v) else "-"
            lines.append(f"  {name}: {1000 * c[d]:.4g} um/N ({np.linalg.norm(v):.4g} mm at full load; mostly {top})")
        return "\n".join(lines)


def static_compliance(robot, q, *, load_n: float | None = None, steps: int = 10) -> StaticCompliance:
    """Predict the ISO 9283 static compliance test at the pose ``q`` (module docstring).

    Parameters
    ----------
    robot : Robot
        With its parts resolved (:func:`tolalloc.errormodel.parts.with_parts`).
    q : array, shape (n,) [rad, mm]
        The pose (the standard: the test cube's centre, P1).
    load_n : float, optional
        The full load [N]; default the rated payload's weight (``[components.payload] rated_kg`` x g).
    steps : int
        Load steps up to the full load (the standard: 10 %, 20 % ... 100 %).

    Returns
    -------
    StaticCompliance
    """
    from tolalloc.acceptance.parts import _check_resolved

    _check_resolved(robot)
    q = np.asarray(robot.check_q(np.atleast_2d(q), "q"), float)
    if len(q) != 1:
        raise ArgumentError("q", f"expected one pose of {robot.n_joints} joint values, got {len(q)} poses.")
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 1:
        raise ArgumentError("steps", f"expected a whole number of load steps >= 1 (the standard: 10), got {steps!r}.")
    if load_n is None:
        rated = robot.components.payload.rated_kg
        if rated is None or not rated > 0:
            raise TolallocError(f"robot {robot.name!r}: no load_n given and no rated payload > 0 ([components.payload] "
                                f"rated_kg, here {rated!r}) to take the full load from; give load_n [N].")
        load_n = rated * GRAVITY
    if isinstance(load_n, bool) or not (isinstance(load_n, (int, float, np.integer, np.floating))
                                        and np.isfinite(load_n) and load_n > 0):
        raise ArgumentError("load_n", f"expected a load > 0 [N], e.g. 100, got {load_n!r}.")
    loads = float(load_n) * np.arange(1, steps + 1) / steps
    if np.any(robot.tool_offset_mm):  # the mechanical interface: the chain's end
        robot = replace(robot, tool_offset_mm=np.zeros(3), trust_units=True)
    R = robot.fk_internal(q)[0, :3, :3]
    pm = parts_error_model(build_error_model(robot, "generic"), robot)   # built once for every load
    base = _elastic(robot, q, np.zeros(3), pm)
    disp = np.zeros((len(LOAD_DIRECTIONS), steps, 3))
    parts = {e: np.zeros_like(disp) for e in base}
    for d, name in enumerate(LOAD_DIRECTIONS):
        axis = np.zeros(3)
        axis["xyz".index(name[1])] = 1.0 if name[0] == "+" else -1.0
        for s, load in enumerate(loads):
            loaded = _elastic(robot, q, R.T @ (load * axis), pm)   # the process force is given in the tool frame
            for e in base:
                parts[e][d, s] = loaded[e] - base[e]
            disp[d, s] = sum(parts[e][d, s] for e in base)
    return StaticCompliance(robot.name, q[0], loads, disp, parts)


def _elastic(robot, q, force_tool, pm) -> dict:
    """The elastic effects' mean displacement of ``robot``'s tool point [mm] under a force at it (tool frame), per
    effect (``pm``: the robot's parts error model); the caller passes the robot without its tool offset."""
    fx = PartEffects(robot, q, 0.0, 20.0, Conditions(process_force_n=tuple(force_tool)), pm=pm)
    t = fx.terms()
    return {e: t.of_effect(e).mean_mm()[0] for e in ELASTIC}
