"""Set W: the registry of its new effect kinds, their families, the session options and the probe they need.

Physics in :mod:`effects_w_joint`, :mod:`effects_w_body`, :mod:`effects_w_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-W kind, so sets A-V regenerate unchanged; the probe hook
draws none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_w_body as wb
from sim2real_indep import effects_w_joint as wj
from sim2real_indep import effects_w_thermal as wt

#: kind -> (draw, apply, true-structure features)
EFFECTS_W = {
    "swarf_shroud": (wj.swarf_draw, wj.swarf_apply, wj.swarf_features),
    "rail_trolley": (wj.trolley_draw, wj.trolley_apply, wj.trolley_features),
    "stable_probe": (wj.stable_draw, wj.stable_apply, wj.stable_features),
    "part_slide": (wj.slide_draw, wj.slide_apply, wj.slide_features),
    "hub_slip": (wj.hub_draw, wj.hub_apply, wj.hub_features),
    "emi_counts": (wj.emi_draw, wj.emi_apply, wj.emi_features),
    "cracked_plinth": (wb.plinth_draw, wb.plinth_apply, wb.plinth_features),
    "young_grout": (wb.grout_draw, wb.grout_apply, wb.grout_features),
    "air_bellows": (wb.bellows_draw, wb.bellows_apply, wb.bellows_features),
    "bent_bracket": (wb.bracket_draw, wb.bracket_apply, wb.bracket_features),
    "cooling_part": (wt.part_draw, wt.part_apply, wt.part_features),
    "air_stratification": (wt.strat_draw, wt.strat_apply, wt.strat_features),
}
#: families (context.FAMILY takes them over). swarf_shroud, the gears twisted by the chips a spindle's shroud collects,
#: and rail_trolley, by a balancer on a free-running rail trolley, joint compliance; stable_probe, the tracker's
#: stable-probe trigger firing before the servo's creep ends (behind the pose along the last approach), and part_slide,
#: a part sliding in its nest to the stop the last move or its weight chose, backlash (errors that follow the last
#: motion); hub_slip, an output hub slipping on its shaft at an emergency stop, and emi_counts, welding noise
#: miscounting the output encoders, transmission (the joints' reading and drive); cracked_plinth, a plinth cracked at
#: its root, and young_grout, a pedestal on a grout bed still stiffening, mount compliance (the robot's support);
#: air_bellows, a bellows compliance unit following the shop air's pressure, and bent_bracket, the target's bracket
#: bent in a collision, link deflection (the end-of-arm structure carrying the target); cooling_part, a hot part
#: cooling in the gripper, and air_stratification, the links at the temperatures of stratified air, thermal
FAMILY_W = {"swarf_shroud": "joint_compliance", "rail_trolley": "joint_compliance", "stable_probe": "backlash",
            "part_slide": "backlash", "hub_slip": "transmission", "emi_counts": "transmission",
            "cracked_plinth": "mount_compliance", "young_grout": "mount_compliance", "air_bellows": "link_deflection",
            "bent_bracket": "link_deflection", "cooling_part": "thermal", "air_stratification": "thermal"}
#: measurement effects that need the tracker's frame (none in set W: the stable-probe lag is along the target's path)
AFTER_TRACKER: set = set()
#: kinds whose sessions have production (exercise) between their blocks: the blocks' range
PRODUCTION = {"swarf_shroud": (4, 8), "hub_slip": (4, 7), "emi_counts": (4, 7), "bent_bracket": (4, 7),
              "cooling_part": (4, 9)}
#: kinds whose sessions are a long day of blocks (set A's pauses)
LONG_DAY = {"young_grout", "air_stratification"}
#: the target's offset added by the end-of-arm structure of a kind (tool frame) [mm]
PROBE_OFFSET = {"cooling_part": np.array([wt.PART_MM, 0.0, 0.0])}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-W case: for :data:`LONG_DAY`, 5-8 blocks with pauses of 30-90 min; for :data:`PRODUCTION`,
    the blocks of its range with production (exercise) between them. No draws without a set-W kind."""
    kinds = set(physics) & set(EFFECTS_W)
    if not kinds:
        return opts
    opts = dict(opts)
    if kinds & LONG_DAY:
        opts.update(blocks=max(opts["blocks"], int(rng.integers(5, 9))), gap_kind="pause", pause_min=(30.0, 90.0))
    for k in sorted(kinds & set(PRODUCTION)):
        lo, hi = PRODUCTION[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="exercise")
    return opts


def probe_hook(physics, probe):
    """The target at the end of the case's end-of-arm structure (no draws)."""
    for k in physics:
        if k in PROBE_OFFSET:
            probe = probe + PROBE_OFFSET[k]
    return probe
