"""Set ZH: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zh_joint`, :mod:`effects_zh_body`, :mod:`effects_zh_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-ZH kind, so sets A-ZG regenerate unchanged; the probe
hook draws none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zh_body as zhb
from sim2real_indep import effects_zh_joint as zhj
from sim2real_indep import effects_zh_thermal as zht

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZH = {
    "worn_mesh": (zhj.worn_draw, zhj.worn_apply, zhj.worn_features),
    "tooth_crack": (zhj.crack_draw, zhj.crack_apply, zhj.crack_features),
    "grease_gel": (zhj.gel_draw, zhj.gel_apply, zhj.gel_features),
    "pinion_handover": (zhj.handover_draw, zhj.handover_apply, zhj.handover_features),
    "running_in_te": (zhj.runin_draw, zhj.runin_apply, zhj.runin_features),
    "brazier_pedestal": (zhb.brazier_draw, zhb.brazier_apply, zhb.brazier_features),
    "dished_plate": (zhb.plate_draw, zhb.plate_apply, zhb.plate_features),
    "inflated_boom": (zhb.inflated_draw, zhb.inflated_apply, zhb.inflated_features),
    "collet_root": (zhb.collet_draw, zhb.collet_apply, zhb.collet_features),
    "loose_pivot": (zhb.pivot_draw, zhb.pivot_apply, zhb.pivot_features),
    "wrist_conduction": (zht.conduction_draw, zht.conduction_apply, zht.conduction_features),
    "regen_resistor": (zht.resistor_draw, zht.resistor_apply, zht.resistor_features),
}
#: families (context.FAMILY takes them over). worn_mesh, axis 2's mesh softened in its worn production zone, and
#: tooth_crack, axis 3's ring softened while a cracked tooth meshes, joint compliance; grease_gel, the loaded axes'
#: lost motion held centred by grease gelled in each pause, and loose_pivot, a target bracket between the stops of a
#: loose pin, backlash; pinion_handover, axis 1's runout switching between two torque-biased pinions, and
#: running_in_te, axis 2's tooth-mesh error fading as the gears run in, transmission; brazier_pedestal, a thin tube
#: pedestal softened by ovalisation, and dished_plate, the base on a rim-clamped plate, mount compliance;
#: inflated_boom, an air-inflated boom wrinkling past a moment, and collet_root, a boom giving in its clamp bush, link
#: deflection; wrist_conduction, a hot tool's heat diffusing into the forearm, and regen_resistor, a braking resistor
#: on the pedestal heated by the lowering moves, thermal
FAMILY_ZH = {"worn_mesh": "joint_compliance", "tooth_crack": "joint_compliance", "grease_gel": "backlash",
             "loose_pivot": "backlash", "pinion_handover": "transmission", "running_in_te": "transmission",
             "brazier_pedestal": "mount_compliance", "dished_plate": "mount_compliance",
             "inflated_boom": "link_deflection", "collet_root": "link_deflection", "wrist_conduction": "thermal",
             "regen_resistor": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZH)
AFTER_TRACKER: set = set()
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"dished_plate": {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 80.0)},
           "inflated_boom": {"ur10": (0.0, 3.0), "kr16_like": (0.0, 3.0), "tool_changer": (0.0, 3.0)}}
#: kinds whose effect follows the time or the pauses: their sessions span hours, blocks with pauses [min]
LONG = {"grease_gel": ((4, 7), (20.0, 60.0)), "wrist_conduction": ((4, 7), (5.0, 20.0)),
        "regen_resistor": ((4, 7), (10.0, 30.0))}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZH case: for :data:`PART_KG`, 3-5 blocks at least, each with a new part; for :data:`LONG`,
    blocks with pauses that spread the session over hours. No draws without a set-ZH kind."""
    kinds = set(physics) & set(EFFECTS_ZH)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(PART_KG)):
        opts["blocks"] = max(opts["blocks"], int(rng.integers(3, 6)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    for k in sorted(kinds & set(LONG)):
        (lo, hi), pause = LONG[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="pause", pause_min=pause)
    return opts


def probe_hook(physics, probe):
    """The target at the tip of the case's boom or swinging bracket (no draws)."""
    for k in physics:
        if k in ("inflated_boom", "collet_root"):
            probe = probe + np.array([zhb.BOOM_MM, 0.0, 0.0])
        elif k == "loose_pivot":
            probe = probe + np.array([0.0, 0.0, zhb.PIVOT_MM])
    return probe
