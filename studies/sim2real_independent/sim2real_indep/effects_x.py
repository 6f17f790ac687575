"""Set X: the registry of its new effect kinds, their families, the session options and the probe they need.

Physics in :mod:`effects_x_joint`, :mod:`effects_x_body`, :mod:`effects_x_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-X kind, so sets A-W regenerate unchanged; the probe hook
draws none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_x_body as xb
from sim2real_indep import effects_x_joint as xj
from sim2real_indep import effects_x_thermal as xt

#: kind -> (draw, apply, true-structure features)
EFFECTS_X = {
    "magnet_fanner": (xj.fanner_draw, xj.fanner_apply, xj.fanner_features),
    "support_arm": (xj.support_draw, xj.support_apply, xj.support_features),
    "track_lash": (xj.track_draw, xj.track_apply, xj.track_features),
    "run_in_wear": (xj.wear_draw, xj.wear_apply, xj.wear_features),
    "ring_lobing": (xj.lobing_draw, xj.lobing_apply, xj.lobing_features),
    "cosine_error": (xj.cosine_draw, xj.cosine_apply, xj.cosine_features),
    "collision_shift": (xb.collision_draw, xb.collision_apply, xb.collision_features),
    "levelling_foot": (xb.foot_draw, xb.foot_apply, xb.foot_features),
    "printed_fingers": (xb.finger_draw, xb.finger_apply, xb.finger_features),
    "suction_cup": (xb.cup_draw, xb.cup_apply, xb.cup_features),
    "washdown": (xt.wash_draw, xt.wash_apply, xt.wash_features),
    "induction_stray": (xt.stray_draw, xt.stray_apply, xt.stray_features),
}
#: families (context.FAMILY takes them over). magnet_fanner, the gears twisted by a sheet fanner's pull on the blank in
#: the gripper, and support_arm, by a spring-balanced tool-support arm's height-dependent lift, joint compliance;
#: track_lash, the arm's linear track left on the flank of its carriage's last approach, and run_in_wear, a replaced
#: gear set's lost motion opening as it runs in, backlash (errors that follow the last motion); ring_lobing, axis 1's
#: ring scale pulled into three lobes by its clamping screws, and cosine_error, the telescopic stage's length sensor
#: mounted at an angle to its travel, transmission (the joints' reading); collision_shift, the base plate slipped on its
#: bolted joint in a collision, and levelling_foot, the stand's foot unscrewing in the production, mount compliance (the
#: robot's support); printed_fingers, 3D-printed fingers creeping under the held part, and suction_cup, a part tilting
#: on its suction cup, link deflection (the end-of-arm structure carrying the target); washdown, the arm cooling after a
#: hot sanitation rinse, and induction_stray, the forearm heated by an induction heater's stray field, thermal
FAMILY_X = {"magnet_fanner": "joint_compliance", "support_arm": "joint_compliance", "track_lash": "backlash",
            "run_in_wear": "backlash", "ring_lobing": "transmission", "cosine_error": "transmission",
            "collision_shift": "mount_compliance", "levelling_foot": "mount_compliance",
            "printed_fingers": "link_deflection", "suction_cup": "link_deflection", "washdown": "thermal",
            "induction_stray": "thermal"}
#: measurement effects that need the tracker's frame (none in set X)
AFTER_TRACKER: set = set()
#: kinds whose sessions have production (exercise) between their blocks: the blocks' range
PRODUCTION = {"track_lash": (4, 7), "run_in_wear": (4, 8), "collision_shift": (4, 7), "induction_stray": (4, 8),
              "levelling_foot": (4, 8)}
#: kinds whose sessions have a sanitation (a pause of 15-40 min) between their blocks: the blocks' range
SANITATION = {"washdown": (4, 7)}
#: kinds that hold a part: a new part (the logged payload) for each block, its mass range per arm [kg]
PART_KG = {"printed_fingers": {"ur10": (0.5, 2.0), "kr16_like": (1.0, 3.0), "tool_changer": (2.0, 5.0)},
           "suction_cup": {"ur10": (1.0, 4.0), "kr16_like": (3.0, 10.0), "tool_changer": (8.0, 25.0)}}
#: the target's offset added by the end-of-arm structure of a kind (tool frame) [mm]
PROBE_OFFSET = {"printed_fingers": np.array([0.0, 0.0, xb.FINGER_MM]),
                "suction_cup": np.array([0.0, 0.0, xb.CUP_MM])}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-X case: for :data:`SANITATION`, pauses of 15-40 min between its blocks; for
    :data:`PRODUCTION`, the blocks of its range with production (exercise) between them; for :data:`PART_KG`, 2-4
    blocks at least, each with a new part. No draws without a set-X
    kind."""
    kinds = set(physics) & set(EFFECTS_X)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(SANITATION)):
        lo, hi = SANITATION[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="pause", pause_min=(15.0, 40.0))
    for k in sorted(kinds & set(PRODUCTION)):
        lo, hi = PRODUCTION[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="exercise")
    for k in sorted(kinds & set(PART_KG)):
        opts["blocks"] = max(opts["blocks"], int(rng.integers(2, 5)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    return opts


def probe_hook(physics, probe):
    """The target at the end of the case's end-of-arm structure (no draws)."""
    for k in physics:
        if k in PROBE_OFFSET:
            probe = probe + PROBE_OFFSET[k]
    return probe
