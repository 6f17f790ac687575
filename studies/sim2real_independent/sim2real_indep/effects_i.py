"""Set I: the registry of its new effect kinds, their families, the session options they need and the boom's target.

Physics in :mod:`effects_i_joint`, :mod:`effects_i_body`, :mod:`effects_i_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-I kind (and the probe hook none at all), so
sets A-H regenerate unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_i_body as ib
from sim2real_indep import effects_i_joint as ij
from sim2real_indep import effects_i_thermal as it
from sim2real_indep.hardware import pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_I = {
    "tilted_base": (ij.tilt_draw, ij.tilt_apply, ij.tilt_features),
    "balancer_relax": (ij.bal_draw, ij.bal_apply, ij.bal_features),
    "floor_beams": (ib.floor_draw, ib.floor_apply, ib.floor_features),
    "portal": (ib.portal_draw, ib.portal_apply, ib.portal_features),
    "lap_splice": (ib.splice_draw, ib.splice_apply, ib.splice_features),
    "fork_arm": (ib.fork_draw, ib.fork_apply, ib.fork_features),
    "overrun_lash": (ij.overrun_draw, ij.overrun_apply, ij.overrun_features),
    "nut_play": (ij.nut_draw, ij.nut_apply, ij.nut_features),
    "idler_runout": (ij.idler_draw, ij.idler_apply, ij.idler_features),
    "para_gear": (ij.para_draw, ij.para_apply, ij.para_features),
    "rail_boom": (it.boom_draw, it.boom_apply, it.boom_features),
    "housing_growth": (it.housing_draw, it.housing_apply, it.housing_features),
}
#: families (context.FAMILY takes them over); tilted_base is the gear torsion under gravity acting obliquely in the
#: base frame (an installation, not a compliant mount): scored as joint compliance; rail_boom, a tool-side boom
#: bowing with the air temperature, as thermal (its generic physics: expansion following the air); nut_play, the
#: lost motion of a prismatic stage's nut, as backlash
FAMILY_I = {"tilted_base": "joint_compliance", "balancer_relax": "joint_compliance", "floor_beams": "mount_compliance",
            "portal": "mount_compliance", "lap_splice": "link_deflection", "fork_arm": "link_deflection",
            "overrun_lash": "backlash", "nut_play": "backlash", "idler_runout": "transmission",
            "para_gear": "transmission", "rail_boom": "thermal", "housing_growth": "thermal"}
#: measurement effects that need the tracker's frame: none in set I
AFTER_TRACKER: set = set()
#: a hall whose air drifts over the session (pauses between the blocks)
AIR = {"rail_boom"}
#: drive-heated kinds: a cold start, production periods (exercise) between the blocks
WARM = {"housing_growth"}
#: kinds whose sessions change the payload between blocks (pick and place with several loads)
PICK_PLACE = {"tilted_base", "balancer_relax", "floor_beams", "portal", "lap_splice", "fork_arm", "overrun_lash",
              "nut_play"}
#: the target at the end of the bimetal boom, 400-900 mm from the flange (the drawn offset of 5-100 mm mapped onto it)
BOOM_MM = (400.0, 900.0)


def session_options(robot_key, physics, rng, opts):
    """The session of a set-I case: a hall whose air drifts by 3-6 K (cycling by up to 0.5 K) over 5-8 blocks with
    pauses of 20-60 min for the boom; 5-8 blocks with production periods of 10-30 min for the housings; pick and
    place with 2-4 loads changed between 6-10 blocks for the load-driven kinds."""
    kinds = set(physics)
    if not kinds & set(EFFECTS_I):
        return opts
    opts = dict(opts)
    if kinds & AIR:
        opts.update(blocks=int(rng.integers(5, 9)), gap_kind="pause", pause_min=(20.0, 60.0),
                    air={"drift_K": rng.choice([-1, 1]) * rng.uniform(3.0, 6.0), "cycle_K": rng.uniform(0.0, 0.5),
                         "period_min": rng.uniform(60, 180)})
    if kinds & WARM:
        opts.update(blocks=max(opts["blocks"], int(rng.integers(5, 9))), gap_kind="exercise")
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
    return opts


def probe_hook(physics, probe_mm):
    """The target offset (3,) [mm]: for the bimetal boom, the drawn offset's direction with its length 5-100 mm mapped
    linearly onto the boom's 400-900 mm (no random numbers); unchanged otherwise."""
    if "rail_boom" not in physics:
        return probe_mm
    n = np.linalg.norm(probe_mm)
    return probe_mm / n * (BOOM_MM[0] + (BOOM_MM[1] - BOOM_MM[0]) * (n - 5.0) / 95.0)
