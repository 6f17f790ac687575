"""Set U: the registry of its new effect kinds, their families, the session options and the probe they need.

Physics in :mod:`effects_u_joint`, :mod:`effects_u_body`, :mod:`effects_u_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-U kind, so sets A-T regenerate unchanged; the probe hook
draws none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_u_body as ub
from sim2real_indep import effects_u_joint as uj
from sim2real_indep import effects_u_thermal as ut
from sim2real_indep.hardware import PAYLOAD_MAX_KG

#: kind -> (draw, apply, true-structure features)
EFFECTS_U = {
    "integral_clamp": (uj.clamp_draw, uj.clamp_apply, uj.clamp_features),
    "parked_tool": (uj.parked_draw, uj.parked_apply, uj.parked_features),
    "chain_slack": (uj.chain_draw, uj.chain_apply, uj.chain_features),
    "bowden_lash": (uj.bowden_draw, uj.bowden_apply, uj.bowden_features),
    "dropped_counts": (uj.count_draw, uj.count_apply, uj.count_features),
    "soiled_disc": (uj.soil_draw, uj.soil_apply, uj.soil_features),
    "trunnion": (ub.trunnion_draw, ub.trunnion_apply, ub.trunnion_features),
    "slab_joint": (ub.slab_draw, ub.slab_apply, ub.slab_features),
    "sandwich_boom": (ub.boom_draw, ub.boom_apply, ub.boom_features),
    "sleeve_rock": (ub.sleeve_draw, ub.sleeve_apply, ub.sleeve_features),
    "platform_growth": (ut.platform_draw, ut.platform_apply, ut.platform_features),
    "magnet_coil": (ut.coil_draw, ut.coil_apply, ut.coil_features),
}
#: families (context.FAMILY takes them over). integral_clamp, the main axes sagging by the load their clamped integrator
#: leaves to the proportional term, and parked_tool, the gears twisted by a spare tool parked on the forearm in some
#: blocks, joint compliance; chain_slack, axis 3's lost motion across a chain's slack strand, and bowden_lash, axis 5's
#: across a Bowden cable's sheath friction, backlash (errors that follow the last motion); dropped_counts, the main
#: axes' encoders dropping counts in fast moves, and soiled_disc, axis 2's encoder misreading a soiled sector,
#: transmission (the joints' reading); trunnion, the arm on a tilting positioner's worm drive, and slab_joint, its base
#: straddling a slab's joint, mount compliance (the robot's support); sandwich_boom, a sandwich gripper boom carrying
#: the target, and sleeve_rock, the target's telescopic extension rocking in its sleeve's clearance, link deflection
#: (the end-of-arm structure carrying the target); platform_growth, the arm's platform following the air, and
#: magnet_coil, a magnetic gripper warmed by its coil while it holds a part, thermal
FAMILY_U = {"integral_clamp": "joint_compliance", "parked_tool": "joint_compliance", "chain_slack": "backlash",
            "bowden_lash": "backlash", "dropped_counts": "transmission", "soiled_disc": "transmission",
            "trunnion": "mount_compliance", "slab_joint": "mount_compliance", "sandwich_boom": "link_deflection",
            "sleeve_rock": "link_deflection", "platform_growth": "thermal", "magnet_coil": "thermal"}
#: measurement effects that need the tracker's frame (none in set U)
AFTER_TRACKER: set = set()
#: kinds whose sessions have several blocks: what happens between them, the pauses' length [min] and the blocks
BLOCKS = {"parked_tool": ("pause", (5.0, 20.0), (4, 9)), "magnet_coil": ("pause", (10.0, 30.0), (6, 11))}
#: kinds whose sessions alternate an empty gripper and one holding a part between blocks
PICK_PLACE = {"magnet_coil", "sandwich_boom"}
#: the target's offset added by the end-of-arm structure of a kind (tool frame) [mm]
PROBE_OFFSET = {"sandwich_boom": np.array([ub.BOOM_MM, 0.0, 0.0]), "sleeve_rock": np.array([0.0, 0.0, ub.SLEEVE_MM])}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-U case: the platform's a working day (set A's ambient: 5-8 blocks, pauses of 30-90 min, the
    hall's air drifting by 2-6 K); the blocks of :data:`BLOCKS`; and for :data:`PICK_PLACE`, 6-10 blocks that alternate
    an empty gripper and one holding a part of 30-100 % of the arm's largest payload."""
    kinds = set(physics) & set(EFFECTS_U)
    if not kinds:
        return opts
    opts = dict(opts)
    if "platform_growth" in kinds:
        drift = rng.choice([-1, 1]) * rng.uniform(2.0, 6.0)
        opts.update(blocks=max(opts["blocks"], int(rng.integers(5, 9))), gap_kind="pause", pause_min=(30.0, 90.0),
                    air={"drift_K": drift, "cycle_K": rng.uniform(0.0, 1.0), "period_min": rng.uniform(60, 180)})
    for k in sorted(kinds & set(BLOCKS)):
        gap, pause, (lo, hi) = BLOCKS[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind=gap)
        opts.setdefault("pause_min", pause)
    if kinds & PICK_PLACE:
        blocks = max(opts["blocks"], int(rng.integers(6, 11)))
        parts = np.round(rng.uniform(0.3, 1.0, blocks) * PAYLOAD_MAX_KG[robot_key], 1)
        opts.update(blocks=blocks, gap_kind="pause", payload_steps=tuple(np.where(np.arange(blocks) % 2, parts, 0.0)))
        opts.setdefault("pause_min", (10.0, 30.0))
    return opts


def probe_hook(physics, probe):
    """The target at the end of the case's end-of-arm structure (no draws)."""
    for k in physics:
        if k in PROBE_OFFSET:
            probe = probe + PROBE_OFFSET[k]
    return probe
