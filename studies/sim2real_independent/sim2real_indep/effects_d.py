"""Set D: the registry of its new effect kinds, and the session options they need.

Physics in :mod:`effects_d_joint`, :mod:`effects_d_body`, :mod:`effects_d_thermal` (sources in their
docstrings). The hook consumes random numbers only when a case has a set-D kind, so sets A, B and C regenerate
unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

from sim2real_indep import effects_d_body as db
from sim2real_indep import effects_d_joint as dj
from sim2real_indep import effects_d_thermal as dt
from sim2real_indep.hardware import pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_D = {
    "gas_spring": (dj.gas_spring_draw, dj.gas_spring_apply, dj.gas_spring_features),
    "dresspack": (dj.dresspack_draw, dj.dresspack_apply, dj.dresspack_features),
    "varlash": (dj.varlash_draw, dj.varlash_apply, dj.varlash_features),
    "belt": (dj.belt_draw, dj.belt_apply, dj.belt_features),
    "ball_screw": (dj.screw_draw, dj.screw_apply, dj.screw_features),
    "loose_anchor": (db.anchor_draw, db.anchor_apply, db.anchor_features),
    "pad_creep": (db.settle_draw, db.settle_apply, db.settle_features),
    "tapered": (db.taper_draw, db.taper_apply, db.taper_features),
    "bracket": (db.bracket_draw, db.bracket_apply, db.bracket_features),
    "thermal_bend": (dt.bend_draw, dt.bend_apply, dt.bend_features),
    "tool_heat": (dt.toolheat_draw, dt.toolheat_apply, dt.toolheat_features),
    "refraction": (dt.refraction_draw, dt.refraction_apply, dt.refraction_features),
}
#: families (context.FAMILY takes them over); refraction is a measurement error following the air: scored as
#: thermal like set C's tracker_scale (it is expected to be absorbed: a few um)
FAMILY_D = {"gas_spring": "joint_compliance", "dresspack": "joint_compliance", "varlash": "backlash",
            "belt": "transmission", "ball_screw": "transmission", "loose_anchor": "mount_compliance",
            "pad_creep": "mount_compliance", "tapered": "link_deflection", "bracket": "link_deflection",
            "thermal_bend": "thermal", "tool_heat": "thermal", "refraction": "thermal"}
#: kinds applied after the tracker is placed (they need its frame)
AFTER_TRACKER = {"refraction"}
DRIVE_HEAT = {"thermal_bend"}
TOOL_WORK = {"tool_heat"}
AIR = {"refraction"}
CREEP = {"pad_creep"}
#: kinds whose sessions change the payload between blocks (pick and place with several loads)
PICK_PLACE = {"gas_spring", "loose_anchor", "pad_creep", "tapered", "bracket", "dresspack"}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-D case: duty cycles with pauses for drive heat; production periods (exercise) between
    blocks for the process tool; a drifting, stratifying air for refraction; pauses of 5-40 min (brakes on) for
    the creeping pads; pick and place with 2-4 loads changed between 6-10 blocks for the gravity kinds."""
    kinds = set(physics)
    if not kinds & set(EFFECTS_D):
        return opts
    opts = dict(opts)
    if kinds & DRIVE_HEAT:
        opts.update(blocks=int(rng.integers(5, 9)), gap_kind="mixed", pause_min=(5.0, 60.0))
    if kinds & TOOL_WORK:
        opts.update(blocks=int(rng.integers(5, 9)), gap_kind="exercise")
    if kinds & CREEP:
        opts.update(blocks=max(opts["blocks"], int(rng.integers(4, 8))),
                    gap_kind="mixed" if opts["gap_kind"] in ("mixed", "exercise") else "pause", pause_min=(5.0, 40.0))
    if kinds & AIR:
        opts.update(blocks=int(rng.integers(5, 9)), gap_kind="pause", pause_min=(10.0, 60.0),
                    air={"drift_K": rng.choice([-1, 1]) * rng.uniform(2.0, 5.0), "cycle_K": rng.uniform(0.0, 0.8),
                         "period_min": rng.uniform(60, 180)})
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
    return opts
