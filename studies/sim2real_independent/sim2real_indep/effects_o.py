"""Set O: the registry of its new effect kinds, their families, the session options they need and the hooks that put
the target on a milling spindle's nose or a C-frame's die and the tool's weight where it hangs.

Physics in :mod:`effects_o_joint`, :mod:`effects_o_body`, :mod:`effects_o_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-O kind (and the probe and payload hooks none at
all), so sets A-N regenerate unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_o_body as ob
from sim2real_indep import effects_o_joint as oj
from sim2real_indep import effects_o_thermal as ot
from sim2real_indep.hardware import PAYLOAD_MAX_KG, pick_place

Z = np.array([0.0, 0.0, 1.0])

#: kind -> (draw, apply, true-structure features)
EFFECTS_O = {
    "milling_force": (oj.milling_draw, oj.milling_apply, oj.milling_features),
    "bolt_torque": (oj.bolt_draw, oj.bolt_apply, oj.bolt_features),
    "cut_flank": (oj.flank_draw, oj.flank_apply, oj.flank_features),
    "enc_hysteresis": (oj.hyst_draw, oj.hyst_apply, oj.hyst_features),
    "lsb_stop": (oj.lsb_draw, oj.lsb_apply, oj.lsb_features),
    "mesh_te": (oj.mesh_draw, oj.mesh_apply, oj.mesh_features),
    "pontoon": (ob.pontoon_draw, ob.pontoon_apply, ob.pontoon_features),
    "guyed_mast": (ob.mast_draw, ob.mast_apply, ob.mast_features),
    "weld_gun": (ob.cframe_draw, ob.cframe_apply, ob.cframe_features),
    "spindle_bracket": (ob.bracket_draw, ob.bracket_apply, ob.bracket_features),
    "purge_air": (ot.purge_draw, ot.purge_apply, ot.purge_features),
    "ir_dryer": (ot.ir_draw, ot.ir_apply, ot.ir_features),
}
#: families (context.FAMILY takes them over). milling_force, the gears twisted by a milling spindle's cutting force and
#: torque, and bolt_torque, by a nutrunner's reaction moment, joint compliance; cut_flank, the lost motion of axes 1, 4
#: and 6 whose flank the cutting load chooses, and enc_hysteresis, the hysteresis band of the output encoders closing
#: the position loop (a lost motion following the last motion), backlash; lsb_stop, the output encoders' counts and
#: stopping dead band, and mesh_te, a ring-gear axis's tooth-mesh transmission error, transmission (a joint's error as
#: a function of its own angle); pontoon, the arm's floating support, and guyed_mast, its guyed mast, mount compliance
#: (the robot's support); weld_gun, a C-frame tool opened by its squeeze force, and spindle_bracket, the spindle's
#: bracket bent by the cut, link deflection (the end-of-arm structure carrying the target, as sets K's RCC and N's ring
#: frame); purge_air, the hollow arm cooled by its purge air, and ir_dryer, the links warmed by an infrared panel,
#: thermal
FAMILY_O = {"milling_force": "joint_compliance", "bolt_torque": "joint_compliance", "cut_flank": "backlash",
            "enc_hysteresis": "backlash", "lsb_stop": "transmission", "mesh_te": "transmission",
            "pontoon": "mount_compliance", "guyed_mast": "mount_compliance", "weld_gun": "link_deflection",
            "spindle_bracket": "link_deflection", "purge_air": "thermal", "ir_dryer": "thermal"}
#: measurement effects that need the tracker's frame (none in set O)
AFTER_TRACKER: set = set()
#: kinds whose sessions have several blocks: what happens between them, the pauses' length [min] and the blocks
BLOCKS = {"purge_air": ("pause", (15.0, 40.0), (2, 4)), "bolt_torque": ("pause", (2.0, 6.0), (4, 8))}
#: kinds whose sessions change the payload between blocks (pick and place, one load none)
PICK_PLACE = {"pontoon", "guyed_mast"}
#: kinds whose tool is the session's one payload: its share of the arm's largest payload
TOOL_LOAD = {"weld_gun": (0.6, 0.9), "milling_force": (0.2, 0.5), "cut_flank": (0.2, 0.5),
             "spindle_bracket": (0.2, 0.5)}
SPINDLE_KINDS = {"milling_force", "cut_flank", "spindle_bracket"}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-O case: 2-3 blocks separated by pauses of 15-40 min (the booth opened, the purge stopped) or
    4-7 blocks by pauses of 2-6 min (the fasteners' parts changed); pick and place with 2-4 loads changed between 6-10
    blocks, the first block empty if the draw left none; the tool (spindle, C-frame) carried throughout as the one
    payload."""
    kinds = set(physics) & set(EFFECTS_O)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(BLOCKS)):
        gap, pause, (lo, hi) = BLOCKS[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind=gap, pause_min=pause)
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
        steps = list(opts["payload_steps"])
        if min(steps) > 0:                                   # held and empty blocks (no draws)
            steps[0] = 0.0
        opts["payload_steps"] = tuple(steps)
    for k in sorted(kinds & set(TOOL_LOAD)):
        opts["payload_steps"] = (float(np.round(rng.uniform(*TOOL_LOAD[k]) * PAYLOAD_MAX_KG[robot_key], 1)),)
    return opts


def _mapped(probe_mm, lo_hi):
    """The drawn offset's direction across the tool axis (3,) and its length (5-100 mm) mapped onto ``lo_hi``."""
    probe_mm = np.asarray(probe_mm, float)
    d = ob._unit_xy(probe_mm)
    share = (np.linalg.norm(probe_mm) - 5.0) / 95.0
    return d, lo_hi[0] + (lo_hi[1] - lo_hi[0]) * share


def probe_hook(physics, probe_mm, robot_key):
    """The target offset (3,) [mm] (no random numbers): for the C-frame, on its die -- the drawn offset's direction
    across the tool axis the throat's, its length (5-100 mm) mapped onto the arm's throat depth, at the die's height;
    for a milling spindle, on its nose -- the direction the bracket's, the length mapped onto the bracket's, the target
    on the housing's radius outside the spindle's axis; unchanged otherwise."""
    if "weld_gun" in physics and robot_key in ob.CFRAME:
        d, a = _mapped(probe_mm, ob.CFRAME[robot_key][0])
        return a * d + ob.CFRAME[robot_key][1] * Z
    if set(physics) & SPINDLE_KINDS and robot_key in ob.SPINDLE:
        d, a = _mapped(probe_mm, ob.SPINDLE[robot_key][0])
        return (a + ob.SPINDLE_HOUSING_MM) * d + ob.SPINDLE[robot_key][1] * Z
    return probe_mm


def payload_hook(physics, com_mm, probe_mm, robot_key):
    """The payload's centre of mass (3,) [mm], tool frame (no random numbers): the C-frame's half way to its die, the
    spindle's half way down its axis; unchanged otherwise."""
    if "weld_gun" in physics and robot_key in ob.CFRAME:
        return 0.5 * np.asarray(probe_mm, float)
    if set(physics) & SPINDLE_KINDS and robot_key in ob.SPINDLE:
        d, a, z = ob.spindle_axis(probe_mm)
        return a * d + 0.5 * z * Z
    return com_mm
