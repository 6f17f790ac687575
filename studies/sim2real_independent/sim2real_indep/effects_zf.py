"""Set ZF: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zf_joint`, :mod:`effects_zf_body`, :mod:`effects_zf_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-ZF kind, so sets A-ZE regenerate unchanged; the probe
hook draws none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zf_body as zfb
from sim2real_indep import effects_zf_joint as zfj
from sim2real_indep import effects_zf_thermal as zft

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZF = {
    "bungee_cord": (zfj.bungee_draw, zfj.bungee_apply, zfj.bungee_features),
    "warm_preload": (zfj.preload_draw, zfj.preload_apply, zfj.preload_features),
    "viscous_crossing": (zfj.crossing_draw, zfj.crossing_apply, zfj.crossing_features),
    "centring_spring": (zfj.centring_draw, zfj.centring_apply, zfj.centring_features),
    "repaired_sector": (zfj.sector_draw, zfj.sector_apply, zfj.sector_features),
    "sagging_disc": (zfj.sagdisc_draw, zfj.sagdisc_apply, zfj.sagdisc_features),
    "shelf_bracket": (zfb.shelf_draw, zfb.shelf_apply, zfb.shelf_features),
    "shim_friction": (zfb.shim_draw, zfb.shim_apply, zfb.shim_features),
    "polymer_boom": (zfb.polymer_draw, zfb.polymer_apply, zfb.polymer_features),
    "flange_gapping": (zfb.gap_draw, zfb.gap_apply, zfb.gap_features),
    "peltier_loop": (zft.peltier_draw, zft.peltier_apply, zft.peltier_features),
    "marking_pulses": (zft.pulse_draw, zft.pulse_apply, zft.pulse_features),
}
#: families (context.FAMILY takes them over). bungee_cord, the gears twisted by an elastic cord's stretch towards an
#: overhead eye, and warm_preload, the joints stiffening as their preload grows with warming, joint compliance;
#: viscous_crossing, the output crossing its lash during the dwell against an oil film, and centring_spring, the output
#: held inside its clearance by a centring spring, backlash; repaired_sector, a welded and re-cut sector of axis 1's gear,
#: and sagging_disc, a wrist encoder disc sinking on its hub, transmission (the joints' reading and drive); shelf_bracket,
#: the base on a cantilevered shelf bracket, and shim_friction, the base slipping on its shims with the moment's change,
#: mount compliance; polymer_boom, a printed boom softening with the air's warmth, and flange_gapping, a tool flange
#: opening past its preload, link deflection; peltier_loop, a bracket on a PID-controlled Peltier cooler, and
#: marking_pulses, a bracket warmed by a marking laser at each dwell, thermal
FAMILY_ZF = {"bungee_cord": "joint_compliance", "warm_preload": "joint_compliance", "viscous_crossing": "backlash",
             "centring_spring": "backlash", "repaired_sector": "transmission", "sagging_disc": "transmission",
             "shelf_bracket": "mount_compliance", "shim_friction": "mount_compliance",
             "polymer_boom": "link_deflection", "flange_gapping": "link_deflection", "peltier_loop": "thermal",
             "marking_pulses": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZF)
AFTER_TRACKER: set = set()
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"shelf_bracket": {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 100.0)}}
#: kinds whose sessions span the shop's air drift: blocks, pauses [min] and the drift [K]
AIR_DRIFT = {"polymer_boom": ((4, 7), (20.0, 60.0), (3.0, 6.0))}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZF case: for :data:`PART_KG`, 3-5 blocks at least, each with a new part; for
    :data:`AIR_DRIFT`, blocks with pauses over which the air drifts. No draws without a set-ZF kind."""
    kinds = set(physics) & set(EFFECTS_ZF)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(PART_KG)):
        opts["blocks"] = max(opts["blocks"], int(rng.integers(3, 6)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    for k in sorted(kinds & set(AIR_DRIFT)):
        (lo, hi), pause, (d0, d1) = AIR_DRIFT[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="pause", pause_min=pause,
                    air={"drift_K": float(rng.choice([-1.0, 1.0]) * rng.uniform(d0, d1)), "cycle_K": 0.2,
                         "period_min": 120.0})
    return opts


def probe_hook(physics, probe):
    """The target at the tip of the case's tool boom or bracket (no draws)."""
    for k in physics:
        if k in ("polymer_boom", "flange_gapping"):
            probe = probe + np.array([zfb.BOOM_MM, 0.0, 0.0])
        elif k in ("peltier_loop", "marking_pulses"):
            probe = probe + np.array([0.0, 0.0, zft.BRACKET_MM])
    return probe
