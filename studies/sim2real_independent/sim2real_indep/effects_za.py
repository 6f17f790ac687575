"""Set ZA: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_za_joint`, :mod:`effects_za_body`, :mod:`effects_za_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-ZA kind, so sets A-Z regenerate unchanged. Imports
nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_za_body as zab
from sim2real_indep import effects_za_joint as zaj
from sim2real_indep import effects_za_thermal as zat

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZA = {
    "flank_stiffness": (zaj.flank_draw, zaj.flank_apply, zaj.flank_features),
    "luff_rope": (zaj.luff_draw, zaj.luff_apply, zaj.luff_features),
    "guide_drag": (zaj.guide_draw, zaj.guide_apply, zaj.guide_features),
    "tool_recoil": (zaj.recoil_draw, zaj.recoil_apply, zaj.recoil_features),
    "scratch_count": (zaj.scratch_draw, zaj.scratch_apply, zaj.scratch_features),
    "tooth_skip": (zaj.skip_draw, zaj.skip_apply, zaj.skip_features),
    "slide_overhang": (zab.slide_draw, zab.slide_apply, zab.slide_features),
    "ground_thaw": (zab.thaw_draw, zab.thaw_apply, zab.thaw_features),
    "offcentre_pick": (zab.pick_draw, zab.pick_apply, zab.pick_features),
    "soft_fingers": (zab.finger_draw, zab.finger_apply, zab.finger_features),
    "ac_jet": (zat.jet_draw, zat.jet_apply, zat.jet_features),
    "oven_door": (zat.door_draw, zat.door_apply, zat.door_features),
}
#: families (context.FAMILY takes them over). flank_stiffness, gears stiffer on one tooth flank than on the other, and
#: luff_rope, tool_changer's boom luffed by a rope tackle whose compliance follows the luff angle, joint compliance;
#: guide_drag, the telescopic stage held back against its last stroke by its guides' friction, and tool_recoil, a tool
#: on viscoelastic mounts still creeping back from the last stop's deceleration, backlash (errors that follow the last
#: motion); scratch_count, a ring scale losing counts at a scratch, and tooth_skip, a wrist belt that jumped a tooth
#: between two blocks, transmission (the joints' reading and drive); slide_overhang, the arm on a slide table pulled
#: out to another length for each block, and ground_thaw, outrigger pads on thawing ground, mount compliance (the
#: robot's support); offcentre_pick, a gripper bar twisted by parts picked off its centre line, and soft_fingers, an
#: inflatable gripper's fingers bent by the part, link deflection (the end-of-arm structure carrying the target);
#: ac_jet, the upper arm bowed by an air conditioner's cycling cold jet, and oven_door, the forearm heated by an oven
#: door's pulses, thermal
FAMILY_ZA = {"flank_stiffness": "joint_compliance", "luff_rope": "joint_compliance", "guide_drag": "backlash",
             "tool_recoil": "backlash", "scratch_count": "transmission", "tooth_skip": "transmission",
             "slide_overhang": "mount_compliance", "ground_thaw": "mount_compliance",
             "offcentre_pick": "link_deflection", "soft_fingers": "link_deflection", "ac_jet": "thermal",
             "oven_door": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZA)
AFTER_TRACKER: set = set()
#: kinds whose sessions have pauses between their blocks: the blocks' range and the pauses' range [min]
PAUSES = {"slide_overhang": ((3, 6), (10.0, 30.0)), "ground_thaw": ((4, 8), (20.0, 50.0)),
          "ac_jet": ((3, 6), (5.0, 15.0)), "oven_door": ((3, 6), (5.0, 15.0))}
#: kinds whose sessions have production (exercise) between their blocks: the blocks' range
PRODUCTION = {"tooth_skip": (3, 6)}
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"offcentre_pick": {"ur10": (2.0, 8.0), "kr16_like": (4.0, 14.0), "tool_changer": (20.0, 70.0)},
           "soft_fingers": {"ur10": (0.1, 0.8), "kr16_like": (0.2, 1.5), "tool_changer": (0.5, 3.0)}}
#: the target's offset added by the end-of-arm structure of a kind (tool frame) [mm]
PROBE_OFFSET = {"offcentre_pick": np.array([zab.BAR_MM, 0.0, zab.POST_MM]),
                "soft_fingers": np.array([0.0, 0.0, zab.FINGER_MM])}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZA case: for :data:`PAUSES`, blocks of its range with pauses between them; for
    :data:`PRODUCTION`, blocks with production between them; for :data:`PART_KG`, 3-5 blocks at least, each with a new
    part. No draws without a set-ZA kind."""
    kinds = set(physics) & set(EFFECTS_ZA)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(PAUSES)):
        (lo, hi), pause = PAUSES[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="pause", pause_min=pause)
    for k in sorted(kinds & set(PRODUCTION)):
        lo, hi = PRODUCTION[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="exercise")
    for k in sorted(kinds & set(PART_KG)):
        opts["blocks"] = max(opts["blocks"], int(rng.integers(3, 6)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    return opts


def probe_hook(physics, probe):
    """The target at the end of the case's end-of-arm structure (no draws)."""
    for k in physics:
        if k in PROBE_OFFSET:
            probe = probe + PROBE_OFFSET[k]
    return probe
