"""Set V: the registry of its new effect kinds, their families, the session options and the probe they need.

Physics in :mod:`effects_v_joint`, :mod:`effects_v_body`, :mod:`effects_v_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-V kind, so sets A-U regenerate unchanged; the probe hook
draws none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_v_body as vb
from sim2real_indep import effects_v_joint as vj
from sim2real_indep import effects_v_thermal as vt

#: kind -> (draw, apply, true-structure features)
EFFECTS_V = {
    "coiled_cord": (vj.cord_draw, vj.cord_apply, vj.cord_features),
    "overhead_festoon": (vj.festoon_draw, vj.festoon_apply, vj.festoon_features),
    "coupled_flank": (vj.coupled_draw, vj.coupled_apply, vj.coupled_features),
    "journal_climb": (vj.climb_draw, vj.climb_apply, vj.climb_features),
    "interpolation_error": (vj.interp_draw, vj.interp_apply, vj.interp_features),
    "rack_segments": (vj.rack_draw, vj.rack_apply, vj.rack_features),
    "stabilizer_jacks": (vb.jacks_draw, vb.jacks_apply, vb.jacks_features),
    "self_leveling": (vb.level_draw, vb.level_apply, vb.level_features),
    "bolt_loosening": (vb.bolt_draw, vb.bolt_apply, vb.bolt_features),
    "moisture_swell": (vb.moist_draw, vb.moist_apply, vb.moist_features),
    "restrained_bar": (vt.bar_draw, vt.bar_apply, vt.bar_features),
    "slab_curl": (vt.curl_draw, vt.curl_apply, vt.curl_features),
}
#: families (context.FAMILY takes them over). coiled_cord, the joints twisted by a coiled cord's spring pull, and
#: overhead_festoon, by a catenary hose's pull, joint compliance; coupled_flank, a wrist axis' lost motion whose flank
#: its motor's net motion (with the coupling compensation) chooses, and journal_climb, the pinned boom joints' pins
#: climbing their worn bushes against the last rotation, backlash (errors that follow the last motion);
#: interpolation_error, the output encoders' sub-divisional error, and rack_segments, the telescopic stage's butted rack,
#: transmission (the joints' reading and drive); stabilizer_jacks, a mobile carrier on its suspension or its jacks by
#: block, and self_leveling, a carrier levelled on locked jacks at each block's start, mount compliance (the robot's
#: support); bolt_loosening, a boom's root bolts loosening with the moves, and moisture_swell, a printed polyamide boom
#: taking up humidity, link deflection (the end-of-arm structure carrying the target); restrained_bar, a restrained
#: crossbar bowing as the air warms it, and slab_curl, the floor slab curling between the arm and the tracker, thermal
FAMILY_V = {"coiled_cord": "joint_compliance", "overhead_festoon": "joint_compliance",
            "coupled_flank": "backlash", "journal_climb": "backlash", "interpolation_error": "transmission",
            "rack_segments": "transmission", "stabilizer_jacks": "mount_compliance", "self_leveling": "mount_compliance",
            "bolt_loosening": "link_deflection", "moisture_swell": "link_deflection", "restrained_bar": "thermal",
            "slab_curl": "thermal"}
#: measurement effects that need the tracker's frame (none in set V)
AFTER_TRACKER: set = set()
#: kinds whose sessions are a working day with the hall's air drifting (set A's ambient session)
AIR_DAY = {"restrained_bar", "slab_curl"}
#: kinds whose sessions are a long day of blocks (set A's pauses) in still air
LONG_DAY = {"moisture_swell"}
#: kinds whose sessions have several blocks: the pauses' length [min] and the blocks
BLOCKS = {"stabilizer_jacks": ((5.0, 20.0), (4, 9)), "self_leveling": ((5.0, 20.0), (4, 9))}
#: the target's offset added by the end-of-arm structure of a kind (tool frame) [mm]
PROBE_OFFSET = {"bolt_loosening": np.array([vb.BOLT_BOOM_MM, 0.0, 0.0]),
                "moisture_swell": np.array([vb.MOIST_BOOM_MM, 0.0, 0.0]),
                "restrained_bar": np.array([0.0, 0.0, vt.BAR_MM])}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-V case: for :data:`AIR_DAY`, a working day (set A's ambient: 5-8 blocks, pauses of 30-90
    min, the hall's air drifting by 2-6 K); for :data:`LONG_DAY`, 5-8 blocks with pauses of 30-90 min; the blocks of
    :data:`BLOCKS`. No draws without a set-V kind."""
    kinds = set(physics) & set(EFFECTS_V)
    if not kinds:
        return opts
    opts = dict(opts)
    if kinds & AIR_DAY:
        drift = rng.choice([-1, 1]) * rng.uniform(2.0, 6.0)
        opts.update(blocks=max(opts["blocks"], int(rng.integers(5, 9))), gap_kind="pause", pause_min=(30.0, 90.0),
                    air={"drift_K": drift, "cycle_K": rng.uniform(0.0, 1.0), "period_min": rng.uniform(60, 180)})
    if kinds & LONG_DAY:
        opts.update(blocks=max(opts["blocks"], int(rng.integers(5, 9))), gap_kind="pause", pause_min=(30.0, 90.0))
    for k in sorted(kinds & set(BLOCKS)):
        pause, (lo, hi) = BLOCKS[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="pause")
        opts.setdefault("pause_min", pause)
    return opts


def probe_hook(physics, probe):
    """The target at the end of the case's end-of-arm structure (no draws)."""
    for k in physics:
        if k in PROBE_OFFSET:
            probe = probe + PROBE_OFFSET[k]
    return probe
