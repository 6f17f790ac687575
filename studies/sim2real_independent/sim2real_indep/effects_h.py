"""Set H: the registry of its new effect kinds, their families and the session options they need.

Physics in :mod:`effects_h_joint`, :mod:`effects_h_body`, :mod:`effects_h_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-H kind, so sets A-G regenerate unchanged.
Imports nothing of tolalloc.
"""

from __future__ import annotations

from sim2real_indep import effects_h_body as hb
from sim2real_indep import effects_h_joint as hj
from sim2real_indep import effects_h_thermal as ht
from sim2real_indep.hardware import pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_H = {
    "load_data": (hj.load_draw, hj.load_apply, hj.load_features),
    "gear_creep": (hj.gcreep_draw, hj.gcreep_apply, hj.gcreep_features),
    "agv_wheels": (hb.agv_draw, hb.agv_apply, hb.agv_features),
    "skid": (hb.skid_draw, hb.skid_apply, hb.skid_features),
    "curved_link": (hb.curve_draw, hb.curve_apply, hb.curve_features),
    "bond_creep": (hb.bond_draw, hb.bond_apply, hb.bond_features),
    "wrist_lash": (hj.wlash_draw, hj.wlash_apply, hj.wlash_features),
    "cold_grease": (ht.grease_draw, ht.grease_apply, ht.grease_features),
    "stale_table": (hj.table_draw, hj.table_apply, hj.table_features),
    "wrist_coupling": (hj.couple_draw, hj.couple_apply, hj.couple_features),
    "tracker_warmup": (ht.warm_draw, ht.warm_apply, ht.warm_features),
    "helix_shift": (ht.helix_draw, ht.helix_apply, ht.helix_features),
}
#: families (context.FAMILY takes them over); skid moves the arm's base and the tracker's stand with the arm's
#: gravity load: scored as mount compliance; tracker_warmup, a drift of the measurement as the instrument warms,
#: as thermal (as set C's tracker_scale); cold_grease, friction lost motion against the last motion that fades as
#: the joints warm, as backlash (as set E's friction wind-up)
FAMILY_H = {"load_data": "joint_compliance", "gear_creep": "joint_compliance", "agv_wheels": "mount_compliance",
            "skid": "mount_compliance", "curved_link": "link_deflection", "bond_creep": "link_deflection",
            "wrist_lash": "backlash", "cold_grease": "backlash", "stale_table": "transmission",
            "wrist_coupling": "transmission", "tracker_warmup": "thermal", "helix_shift": "thermal"}
#: measurement effects: need the tracker's frame
AFTER_TRACKER = {"tracker_warmup", "skid"}
#: kinds whose sessions change the payload between blocks (pick and place with several loads)
PICK_PLACE = {"load_data", "gear_creep", "agv_wheels", "skid", "curved_link", "bond_creep", "wrist_lash"}
#: creeping kinds: pauses (the load held) and production periods between the blocks
CREEP = {"gear_creep", "bond_creep"}
#: warm-up kinds: a cold start, production periods (exercise) between the blocks
WARM = {"cold_grease", "helix_shift"}
#: the tracker switched on just before the session, pauses between the blocks
TRACKER = {"tracker_warmup"}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-H case: 5-8 blocks with production periods of 10-30 min for the warm-up kinds; 4-7
    blocks with pauses of 10-30 min for the tracker's warm-up; 5-8 blocks with pauses (20-60 min, the load held) or
    production periods for the creeping kinds; pick and place with 2-4 loads changed between 6-10 blocks for the
    gravity kinds."""
    kinds = set(physics)
    if not kinds & set(EFFECTS_H):
        return opts
    opts = dict(opts)
    if kinds & TRACKER:
        opts.update(blocks=int(rng.integers(4, 8)), gap_kind="pause", pause_min=(10.0, 30.0))
    if kinds & CREEP:
        opts.update(blocks=int(rng.integers(5, 9)), gap_kind="mixed", pause_min=(20.0, 60.0))
    if kinds & WARM:
        opts.update(blocks=max(opts["blocks"], int(rng.integers(5, 9))), gap_kind="exercise")
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
    return opts
