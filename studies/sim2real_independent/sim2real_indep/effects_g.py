"""Set G: the registry of its new effect kinds, their families, the session options they need and the target rod.

Physics in :mod:`effects_g_joint`, :mod:`effects_g_body`, :mod:`effects_g_thermal` (sources in their docstrings).
The hooks consume random numbers only when a case has a set-G kind (and the probe hook none at all), so sets A-F
regenerate unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_g_body as gb
from sim2real_indep import effects_g_joint as gj
from sim2real_indep import effects_g_thermal as gt
from sim2real_indep.hardware import pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_G = {
    "twin_pinion": (gj.dual_draw, gj.dual_apply, gj.dual_features),
    "hose_catenary": (gj.hose_draw, gj.hose_apply, gj.hose_features),
    "jack_leak": (gb.leak_draw, gb.leak_apply, gb.leak_features),
    "air_isolator": (gb.air_draw, gb.air_apply, gb.air_features),
    "cfrp_twist": (gb.cfrp_draw, gb.cfrp_apply, gb.cfrp_features),
    "target_rod": (gb.rod_draw, gb.rod_apply, gb.rod_features),
    "axial_float": (gj.float_draw, gj.float_apply, gj.float_features),
    "bearing_clearance": (gb.clear_draw, gb.clear_apply, gb.clear_features),
    "ratio_rounding": (gj.ratio_draw, gj.ratio_apply, gj.ratio_features),
    "ring_shift": (gj.ring_draw, gj.ring_apply, gj.ring_features),
    "tripod_growth": (gt.tripod_draw, gt.tripod_apply, gt.tripod_features),
    "bar_expansion": (gt.bar_draw, gt.bar_apply, gt.bar_features),
}
#: families (context.FAMILY takes them over); target_rod is the target's own support bending under gravity: scored
#: as link deflection; tripod_growth is a drift of the measurement frame following the air: scored as thermal (as
#: set C's tracker_scale)
FAMILY_G = {"twin_pinion": "joint_compliance", "hose_catenary": "joint_compliance", "jack_leak": "mount_compliance",
            "air_isolator": "mount_compliance", "cfrp_twist": "link_deflection", "target_rod": "link_deflection",
            "axial_float": "backlash", "bearing_clearance": "backlash", "ratio_rounding": "transmission",
            "ring_shift": "transmission", "tripod_growth": "thermal", "bar_expansion": "thermal"}
#: a hall whose air drifts over the session (pauses between the blocks)
AIR = {"tripod_growth", "bar_expansion"}
#: jacks leaking through a long session with pauses (the load held)
LEAK = {"jack_leak"}
#: kinds whose sessions change the payload between blocks (pick and place with several loads)
PICK_PLACE = {"twin_pinion", "hose_catenary", "jack_leak", "air_isolator", "cfrp_twist", "axial_float",
              "bearing_clearance", "ring_shift"}
#: the target at the end of a carbon rod 250-600 mm long (the drawn offset of 5-100 mm mapped onto it)
ROD_MM = (250.0, 600.0)


def session_options(robot_key, physics, rng, opts):
    """The session of a set-G case: a hall whose air drifts by 2-5 K (cycling by up to 0.8 K) over 5-8 blocks with
    pauses of 20-60 min for the air-driven kinds; 5-8 blocks with pauses of 20-60 min (the load held) for the leaking
    jacks; pick and place with 2-4 loads changed between 6-10 blocks for the gravity kinds."""
    kinds = set(physics)
    if not kinds & set(EFFECTS_G):
        return opts
    opts = dict(opts)
    if kinds & AIR:
        opts.update(blocks=int(rng.integers(5, 9)), gap_kind="pause", pause_min=(20.0, 60.0),
                    air={"drift_K": rng.choice([-1, 1]) * rng.uniform(2.0, 5.0), "cycle_K": rng.uniform(0.0, 0.8),
                         "period_min": rng.uniform(60, 180)})
    if kinds & LEAK:
        opts.update(blocks=max(opts["blocks"], int(rng.integers(5, 9))), gap_kind="pause", pause_min=(20.0, 60.0))
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
    return opts


def probe_hook(physics, probe_mm):
    """The target offset (3,) [mm]: for the extension rod, the drawn offset's direction with its length 5-100 mm
    mapped linearly onto the rod's 250-600 mm (no random numbers); unchanged otherwise."""
    if "target_rod" not in physics:
        return probe_mm
    n = np.linalg.norm(probe_mm)
    length = ROD_MM[0] + (ROD_MM[1] - ROD_MM[0]) * (n - 5.0) / 95.0
    return probe_mm / n * length
