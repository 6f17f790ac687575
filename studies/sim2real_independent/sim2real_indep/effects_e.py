"""Set E: the registry of its new effect kinds, and the session options they need.

Physics in :mod:`effects_e_joint`, :mod:`effects_e_body`, :mod:`effects_e_thermal` (sources in their
docstrings). The hook consumes random numbers only when a case has a set-E kind, so sets A, B, C and D regenerate
unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

from sim2real_indep import effects_e_body as xb
from sim2real_indep import effects_e_joint as xj
from sim2real_indep import effects_e_thermal as xt
from sim2real_indep.hardware import pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_E = {
    "parallelogram": (xj.para_draw, xj.para_apply, xj.para_features),
    "varstiff": (xj.varstiff_draw, xj.varstiff_apply, xj.varstiff_features),
    "friction_windup": (xj.windup_draw, xj.windup_apply, xj.windup_features),
    "scissor_gear": (xj.scissor_draw, xj.scissor_apply, xj.scissor_features),
    "magnetic_ring": (xj.magring_draw, xj.magring_apply, xj.magring_features),
    "ring_gear": (xj.ring_draw, xj.ring_apply, xj.ring_features),
    "table_frame": (xb.frame_draw, xb.frame_apply, xb.frame_features),
    "soft_foot": (xb.softfoot_draw, xb.softfoot_apply, xb.softfoot_features),
    "channel": (xb.channel_draw, xb.channel_apply, xb.channel_features),
    "ram": (xb.ram_draw, xb.ram_apply, xb.ram_features),
    "sunlight": (xt.sun_draw, xt.sun_apply, xt.sun_features),
    "fan_thermostat": (xt.fan_draw, xt.fan_apply, xt.fan_features),
}
#: families (context.FAMILY takes them over)
FAMILY_E = {"parallelogram": "joint_compliance", "varstiff": "joint_compliance", "friction_windup": "backlash",
            "scissor_gear": "backlash", "magnetic_ring": "transmission", "ring_gear": "transmission",
            "table_frame": "mount_compliance", "soft_foot": "mount_compliance", "channel": "link_deflection",
            "ram": "link_deflection", "sunlight": "thermal", "fan_thermostat": "thermal"}
#: a working day in the sun: long pauses between the blocks
SUN = {"sunlight"}
DRIVE_HEAT = {"fan_thermostat"}
#: kinds whose sessions change the payload between blocks (pick and place with several loads)
PICK_PLACE = {"parallelogram", "varstiff", "friction_windup", "scissor_gear", "table_frame", "soft_foot",
              "channel", "ram"}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-E case: a half-day of 5-8 blocks with pauses of 20-60 min (servo off) for the sun;
    a power-on duty cycle of 5-9 blocks, exercise and pauses of 5-40 min, for the thermostat fan; pick and place
    with 2-4 loads changed between 6-10 blocks for the gravity kinds."""
    kinds = set(physics)
    if not kinds & set(EFFECTS_E):
        return opts
    opts = dict(opts)
    if kinds & SUN:
        opts.update(blocks=int(rng.integers(5, 9)), gap_kind="pause", pause_min=(20.0, 60.0))
    if kinds & DRIVE_HEAT:
        opts.update(blocks=int(rng.integers(5, 10)), gap_kind="mixed", pause_min=(5.0, 40.0))
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
    return opts
