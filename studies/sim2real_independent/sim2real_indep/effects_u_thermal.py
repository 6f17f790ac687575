"""Set U thermal effects (new physics, not in sets A-T): the arm on a steel mezzanine platform whose beams and columns
follow the hall's air, carrying the base away from the platform's fixed bearing and up, while the tracker stands on the
ground floor; and a magnetic gripper whose coil, energised while it holds a part, warms its body, which grows along the
tool axis. Same protocol as :mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* platform growth: a steel platform is fixed at one bearing and slides on the others (expansion bearings: the
  structure grows freely from its fixed point, e.g. EN 1993-1-1 / AISC Design Guide on expansion joints), so a point at
  distance L from the fixed bearing moves by alpha L dT along that direction, and the columns lift the deck by alpha H
  dT. The steel's lumped temperature follows the air (logged) through its time constant rho c t / h (Incropera &
  DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5; 4-12 mm steel sections and h 5-10 W/m^2 K: 20-60 min);
  alpha 12e-6 /K (structural steel) under the heavy arms, an aluminium-profile platform (23e-6 /K, thin walls: 15-40
  min) under ur10, the robot 3-8 m from the fixed bearing, columns 2.5-4.5 m (assumed). The session is set A's
  ambient one (a working day's blocks, the hall drifting by 2-6 K). Unlike set G's tripod growth (the instrument's
  legs) and set A's ambient kind (the arm's own links), the arm's support carries the whole arm. The true structure:
  one column (the lagged air times the growth's direction), amplitude alpha.
* magnet coil: electro-magnetic grippers hold a part with their coil energised (holding power of 30-150 W for the
  sizes of these arms, as recalled from electro-magnet catalogues, e.g. Schramberg / Walker Magnetics) and release it
  with the coil off. The gripper's body is one lumped node (Incropera & DeWitt, ch. 5) of time constant 5-15 min
  heated by the coil's power over its loss conductance, 25-60 K above the air when held on for long (magnets rated for
  continuous duty run their surfaces up to 80-100 degC); the body (the flange to the target, 200-400 mm along the tool
  axis, aluminium 23e-6 /K) grows by alpha L dT along the tool axis.
  The coil is on exactly while the payload column logs a part (a gripper alternately empty and holding a part between
  blocks, :func:`effects_u.session_options`). The true structure: one column (L times the node), amplitude alpha dT_max.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.session import air_temperature


# ------------------------------------------------------------------------------------------ platform growth
#: per arm: the platform's expansion coefficient [1/K] and time constant range [min]: aluminium-profile platforms
#: (thin walls) under the light arm, steel ones under the heavy arms
PLATFORM = {"ur10": (23e-6, (15.0, 40.0)), "kr16_like": (12e-6, (20.0, 60.0)), "tool_changer": (12e-6, (20.0, 60.0))}

def platform_draw(ctx, hw, rng):
    az = rng.uniform(0, 2 * np.pi)
    L, H = rng.uniform(3000.0, 8000.0), rng.uniform(2500.0, 4500.0)
    alpha, tau = PLATFORM[ctx.chain.name]
    return {"alpha": alpha, "tau_s": rng.uniform(*tau) * 60, "dir_mm": np.array(
        [L * np.cos(az), L * np.sin(az), H])}


def platform_temperature(p, session):
    """(P,) the steel's temperature rise over the session's first pose [K], the air (true, fine-grained) lagged."""
    t = session.time_s
    grid = np.unique(np.r_[np.linspace(t[0], t[-1], 2000), t])
    T = ph.first_order_foh(grid, air_temperature(session, grid), p["tau_s"])
    T = np.interp(t, grid, T)
    return T - T[0]


def platform_shape(p, ctx):
    return platform_temperature(p, ctx.session)[:, None] * p["dir_mm"][None]


def platform_apply(p, ctx, hw):
    return Contribution(displace=p["alpha"] * platform_shape(p, ctx))


def platform_features(p, ctx, hw):
    return platform_shape(p, ctx)[None]


# --------------------------------------------------------------------------------------------- magnet coil
def coil_draw(ctx, hw, rng):
    return {"tau_s": rng.uniform(5.0, 15.0) * 60, "dT_max": rng.uniform(25.0, 60.0),
            "L_mm": rng.uniform(200.0, 400.0), "alpha": 23e-6}


def coil_node(p, session):
    """(P,) the body's rise over the air per unit of its held-on rise: the coil's on signal (a part logged) through the
    node's lag, held on from each pose to the next."""
    on = (session.payload_kg > 0).astype(float)
    return ph.first_order_zoh(session.time_s, on, p["tau_s"], x0=0.0)


def coil_shape(p, ctx):
    _, Rt = kin.flange(ctx.chain, ctx.q)
    return Rt[:, :, 2] * (p["L_mm"] * coil_node(p, ctx.session))[:, None]


def coil_apply(p, ctx, hw):
    return Contribution(displace=p["alpha"] * p["dT_max"] * coil_shape(p, ctx))


def coil_features(p, ctx, hw):
    return coil_shape(p, ctx)[None]
