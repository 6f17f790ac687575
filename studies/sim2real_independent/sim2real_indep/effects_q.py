"""Set Q: the registry of its new effect kinds, their families, the session options they need and the hook that puts
the target on a holder, a nozzle or a gripper boom.

Physics in :mod:`effects_q_joint`, :mod:`effects_q_body`, :mod:`effects_q_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-Q kind (and the probe hook none at all), so sets
A-P regenerate unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_q_body as qb
from sim2real_indep import effects_q_joint as qj
from sim2real_indep import effects_q_thermal as qt
from sim2real_indep.hardware import pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_Q = {
    "sensor_stops": (qj.sensor_draw, qj.sensor_apply, qj.sensor_features),
    "fluid_tank": (qj.tank_draw, qj.tank_apply, qj.tank_features),
    "lash_comp": (qj.comp_draw, qj.comp_apply, qj.comp_features),
    "servo_tail": (qj.tail_draw, qj.tail_apply, qj.tail_features),
    "ball_pass": (qj.pass_draw, qj.pass_apply, qj.pass_features),
    "draw_wire": (qj.wire_draw, qj.wire_apply, qj.wire_features),
    "disc_springs": (qb.disc_draw, qb.disc_apply, qb.disc_features),
    "kinematic_mount": (qb.kc_draw, qb.kc_apply, qb.kc_features),
    "ball_holder": (qb.holder_draw, qb.holder_apply, qb.holder_features),
    "gooseneck": (qb.neck_draw, qb.neck_apply, qb.neck_features),
    "ejector_chill": (qt.chill_draw, qt.chill_apply, qt.chill_features),
    "door_draught": (qt.door_draw, qt.door_apply, qt.door_features),
}
#: families (context.FAMILY takes them over). sensor_stops, the main axes' torque-sensor flexures locking on their
#: overload stops, and fluid_tank, the gears twisted by a tool tank's liquid settling to its low side, joint compliance;
#: lash_comp, the controller's backlash compensation against the worn gears' lost motion, and servo_tail, a
#: PI-controlled axis' overshoot in the motion direction decaying through the dwell, backlash (errors that follow the
#: last motion); ball_pass, strain-wave gears' error at their wave-generator bearing's ball-pass rate, and draw_wire,
#: the telescopic stage's draw-wire sensor's stretch and drum eccentricity, transmission (a joint's error as a function
#: of its own position); disc_springs, the arm's feet on stacks of disc springs, and kinematic_mount, its base on a
#: clamped three-ball coupling, mount compliance (the robot's support); ball_holder, the reflector's articulated holder
#: giving in its ball joints, and gooseneck, the nozzle's supply tube straightening under its pressure, link deflection
#: (the end-of-arm structure carrying the target); ejector_chill, a gripper boom chilled by its ejector, and
#: door_draught, the arm chilled by the draught of a hall door, thermal
FAMILY_Q = {"sensor_stops": "joint_compliance", "fluid_tank": "joint_compliance", "lash_comp": "backlash",
            "servo_tail": "backlash", "ball_pass": "transmission", "draw_wire": "transmission",
            "disc_springs": "mount_compliance", "kinematic_mount": "mount_compliance", "ball_holder": "link_deflection",
            "gooseneck": "link_deflection", "ejector_chill": "thermal", "door_draught": "thermal"}
#: measurement effects that need the tracker's frame (none in set Q)
AFTER_TRACKER: set = set()
#: kinds whose sessions have several blocks: what happens between them, the pauses' length [min] and the blocks
BLOCKS = {"door_draught": ("pause", (5.0, 15.0), (4, 8))}
#: kinds whose sessions change the payload between blocks (pick and place, one load none)
PICK_PLACE = {"ejector_chill"}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-Q case: 4-7 blocks separated by pauses of 5-15 min (the hall's traffic through the door);
    pick and place with 2-4 loads changed between 6-10 blocks, the first block empty if the draw left none."""
    kinds = set(physics) & set(EFFECTS_Q)
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
    return opts


def _share(probe_mm):
    return (np.linalg.norm(probe_mm) - 5.0) / 95.0


def probe_hook(physics, probe_mm):
    """The target offset (3,) [mm] (no random numbers): at a gripper boom's tip, on the tool axis at the boom's length
    (the drawn offset's length, 5-100 mm, mapped onto 400-700 mm); at a gooseneck's nozzle, bent towards the drawn
    offset's direction across the tool axis on a radius mapped onto 60-120 mm; on an articulated holder, the drawn
    offset's direction with its length mapped onto 150-250 mm; unchanged otherwise."""
    probe_mm = np.asarray(probe_mm, float)
    if "ejector_chill" in physics:
        lo, hi = qt.BOOM_MM
        return np.array([0.0, 0.0, lo + (hi - lo) * _share(probe_mm)])
    if "gooseneck" in physics:
        lo, hi = qb.NECK_R_MM
        R = lo + (hi - lo) * _share(probe_mm)
        e = probe_mm[:2] / np.linalg.norm(probe_mm[:2])
        return np.r_[R * e, qb.NECK_L0_MM + R]
    if "ball_holder" in physics:
        lo, hi = qb.HOLDER_MM
        return probe_mm / np.linalg.norm(probe_mm) * (lo + (hi - lo) * _share(probe_mm))
    return probe_mm
