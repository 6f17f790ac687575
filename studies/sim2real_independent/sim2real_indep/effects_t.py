"""Set T: the registry of its new effect kinds, their families and the session options they need.

Physics in :mod:`effects_t_joint`, :mod:`effects_t_body`, :mod:`effects_t_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-T kind, so sets A-S regenerate unchanged; set T needs no
probe or payload hook. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_t_body as tb
from sim2real_indep import effects_t_joint as tj
from sim2real_indep import effects_t_thermal as tt
from sim2real_indep.hardware import PAYLOAD_MAX_KG

#: kind -> (draw, apply, true-structure features)
EFFECTS_T = {
    "charge_cable": (tj.cable_draw, tj.cable_apply, tj.cable_features),
    "balancer_leak": (tj.leak_draw, tj.leak_apply, tj.leak_features),
    "hose_capstan": (tj.capstan_draw, tj.capstan_apply, tj.capstan_features),
    "via_approach": (tj.approach_draw, tj.approach_apply, tj.approach_features),
    "inclinometer": (tj.incl_draw, tj.incl_apply, tj.incl_features),
    "rangefinder": (tj.range_draw, tj.range_apply, tj.range_features),
    "crane_runway": (tb.crane_draw, tb.crane_apply, tb.crane_features),
    "shield_squeeze": (tb.squeeze_draw, tb.squeeze_apply, tb.squeeze_features),
    "lockable_float": (tb.float_draw, tb.float_apply, tb.float_features),
    "plunger_stiction": (tb.plunger_draw, tb.plunger_apply, tb.plunger_features),
    "dew_warming": (tt.dew_draw, tt.dew_apply, tt.dew_features),
    "main_drive": (tt.drive_draw, tt.drive_apply, tt.drive_features),
}
#: families (context.FAMILY takes them over). charge_cable, the joints twisted by a floor-lying charging cable's hanging
#: weight, and balancer_leak, axis 2's gear loaded by its balancer's gas leaking away, joint compliance; hose_capstan,
#: the joints twisted by a retracted hose's pull that the ring's capstan friction raises or lowers by the hose's last
#: sliding, and via_approach, the lost motion's flank set by a hidden approach move, backlash (errors that follow the
#: last motion); inclinometer, the boom joints read from MEMS inclinometers, and rangefinder, the telescopic stage
#: read by a laser rangefinder with cyclic errors, transmission (the joints' reading); crane_runway, the base on a
#: column bent by a crane's wheel loads, and shield_squeeze, the console on a shield ovalised by squeezing rock, mount
#: compliance (the robot's support); lockable_float, a tool floating under its weight on a compliance unit locked while
#: a part is held, and plunger_stiction, a tool on a frictional axial compliance plunger, link deflection (the
#: end-of-arm structure carrying the target); dew_warming, an arm brought in cold and warmed by the air and the dew
#: condensing on it, and main_drive, the console bowed back as a tunnelling machine's main drive cools, thermal
FAMILY_T = {"charge_cable": "joint_compliance", "balancer_leak": "joint_compliance", "hose_capstan": "backlash",
            "via_approach": "backlash", "inclinometer": "transmission", "rangefinder": "transmission",
            "crane_runway": "mount_compliance", "shield_squeeze": "mount_compliance",
            "lockable_float": "link_deflection", "plunger_stiction": "link_deflection",
            "dew_warming": "thermal", "main_drive": "thermal"}
#: measurement effects that need the tracker's frame (none in set T)
AFTER_TRACKER: set = set()
#: kinds whose sessions have several blocks: what happens between them, the pauses' length [min] and the blocks
BLOCKS = {"balancer_leak": ("pause", (20.0, 60.0), (4, 8)), "shield_squeeze": ("pause", (15.0, 45.0), (4, 8)),
          "main_drive": ("pause", (15.0, 45.0), (4, 8)), "crane_runway": ("pause", (5.0, 20.0), (3, 6)),
          "dew_warming": ("pause", (10.0, 40.0), (4, 8))}
#: kinds whose sessions change the payload between blocks (pick and place)
PICK_PLACE = {"lockable_float"}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-T case: the blocks of :data:`BLOCKS` (hours of an intervention or of a working session;
    several such kinds: mixed gaps) and, for the lockable float, 6-10 blocks that alternate an empty gripper and one
    holding a part of 30-100 % of the arm's largest payload."""
    kinds = set(physics) & set(EFFECTS_T)
    if not kinds:
        return opts
    opts = dict(opts)
    blocked = sorted(kinds & set(BLOCKS))
    for k in blocked:
        gap, pause, (lo, hi) = BLOCKS[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind=gap, pause_min=pause)
    if len(blocked) > 1:
        opts["gap_kind"] = "mixed"
    if kinds & PICK_PLACE:  # the gripper alternately empty and holding a part
        blocks = max(opts["blocks"], int(rng.integers(6, 11)))
        parts = np.round(rng.uniform(0.3, 1.0, blocks) * PAYLOAD_MAX_KG[robot_key], 1)
        opts.update(blocks=blocks, payload_steps=tuple(np.where(np.arange(blocks) % 2, parts, 0.0)))
    return opts
