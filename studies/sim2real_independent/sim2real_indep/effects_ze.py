"""Set ZE: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_ze_joint`, :mod:`effects_ze_body`, :mod:`effects_ze_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-ZE kind, so sets A-ZD regenerate unchanged; the probe
hook draws none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_ze_body as zeb
from sim2real_indep import effects_ze_joint as zej
from sim2real_indep import effects_ze_thermal as zet

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZE = {
    "tether_reel": (zej.tether_draw, zej.tether_apply, zej.tether_features),
    "ball_reducer": (zej.ball_draw, zej.ball_apply, zej.ball_features),
    "rotary_clamp": (zej.clamp_draw, zej.clamp_apply, zej.clamp_features),
    "noback_brake": (zej.noback_draw, zej.noback_apply, zej.noback_features),
    "disc_shift": (zej.disc_draw, zej.disc_apply, zej.disc_features),
    "reversal_counts": (zej.counts_draw, zej.counts_apply, zej.counts_features),
    "slender_pedestal": (zeb.pedestal_draw, zeb.pedestal_apply, zeb.pedestal_features),
    "slewing_rock": (zeb.rock_draw, zeb.rock_apply, zeb.rock_features),
    "shuttle_boom": (zeb.shuttle_draw, zeb.shuttle_apply, zeb.shuttle_features),
    "ringing_boom": (zeb.ring_draw, zeb.ring_apply, zeb.ring_features),
    "holding_heat": (zet.holding_draw, zet.holding_apply, zet.holding_features),
    "pcm_tool": (zet.pcm_draw, zet.pcm_apply, zet.pcm_features),
}
#: families (context.FAMILY takes them over). tether_reel, the gears twisted by a constant-force tether pulling the tool
#: towards a fixed anchor, and ball_reducer, the Hertzian 2/3-power twist of ball reducers, joint compliance;
#: rotary_clamp, axis 1's flank chosen by a clamp used in some blocks, and noback_brake, a no-back's release travel when
#: the motor drives with the load, backlash (lost motion in a clearance, errors that follow the last motion); disc_shift,
#: axis 1's encoder disc carried under its head by the bearing's tilt, and reversal_counts, a decoder gaining a count at
#: each reversal, transmission (the joints' reading); slender_pedestal, a riser column's tilt amplified by the weight
#: (P-delta), and slewing_rock, a slewing ring's tilting clearance taken up towards the moment, mount compliance (the
#: robot's support); shuttle_boom, a tool boom bent by a carriage parked at a new station each block, and ringing_boom,
#: a tool boom's residual vibration after the stop, link deflection (the end-of-arm structure carrying the target);
#: holding_heat, the links warmed by the motors' copper loss holding the gravity torque, and pcm_tool, a tool bracket on
#: a melting phase-change heat sink, thermal
FAMILY_ZE = {"tether_reel": "joint_compliance", "ball_reducer": "joint_compliance", "rotary_clamp": "backlash",
             "noback_brake": "backlash", "disc_shift": "transmission", "reversal_counts": "transmission",
             "slender_pedestal": "mount_compliance", "slewing_rock": "mount_compliance",
             "shuttle_boom": "link_deflection", "ringing_boom": "link_deflection", "holding_heat": "thermal",
             "pcm_tool": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZE)
AFTER_TRACKER: set = set()
#: kinds whose sessions have pauses between their blocks: blocks' and pauses' ranges [min] (the clamp used or not, the
#: shuttle moved to a new station, the motors' brakes holding while the links cool)
PAUSES = {"rotary_clamp": ((3, 6), (2.0, 8.0)), "shuttle_boom": ((3, 6), (1.0, 5.0)),
          "holding_heat": ((3, 6), (5.0, 20.0))}
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"slender_pedestal": {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 100.0)}}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZE case: for :data:`PAUSES`, blocks of its range with pauses between them; for
    :data:`PART_KG`, 3-5 blocks at least, each with a new part. No draws without a set-ZE kind."""
    kinds = set(physics) & set(EFFECTS_ZE)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(PAUSES)):
        (lo, hi), pause = PAUSES[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="pause", pause_min=pause)
    for k in sorted(kinds & set(PART_KG)):
        opts["blocks"] = max(opts["blocks"], int(rng.integers(3, 6)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    return opts


def probe_hook(physics, probe, robot_key):
    """The target at the tip of the case's tool boom or bracket (no draws)."""
    for k in physics:
        if k == "shuttle_boom":
            probe = probe + np.array([zeb.SHUTTLE_L_MM[robot_key], 0.0, 0.0])
        elif k == "ringing_boom":
            probe = probe + np.array([0.0, 0.0, zeb.RING_MM])
        elif k == "pcm_tool":
            probe = probe + np.array([0.0, 0.0, zet.PCM_MM])
    return probe
