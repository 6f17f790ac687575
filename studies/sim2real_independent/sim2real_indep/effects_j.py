"""Set J: the registry of its new effect kinds, their families, the session options they need and the tool plate's
target and payload.

Physics in :mod:`effects_j_joint`, :mod:`effects_j_body`, :mod:`effects_j_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-J kind (and the probe and payload hooks none at
all), so sets A-I regenerate unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_j_body as jb
from sim2real_indep import effects_j_joint as jj
from sim2real_indep import effects_j_thermal as jt
from sim2real_indep.hardware import pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_J = {
    "planet_stage": (jj.planet_draw, jj.planet_apply, jj.planet_features),
    "diff_wrist": (jj.diff_draw, jj.diff_apply, jj.diff_features),
    "flange_slip": (jj.slip_draw, jj.slip_apply, jj.slip_features),
    "bar_pins": (jj.pin_draw, jj.pin_apply, jj.pin_features),
    "hose_retract": (jj.retract_draw, jj.retract_apply, jj.retract_features),
    "wrist_shafts": (jj.shaft_draw, jj.shaft_apply, jj.shaft_features),
    "grout_creep": (jb.grout_draw, jb.grout_apply, jb.grout_features),
    "wall_console": (jb.console_draw, jb.console_apply, jb.console_features),
    "skew_casting": (jb.skew_draw, jb.skew_apply, jb.skew_features),
    "tool_plate": (jb.plate_draw, jb.plate_apply, jb.plate_features),
    "brake_tilt": (jt.brake_draw, jt.brake_apply, jt.brake_features),
    "laminate_twist": (jt.laminate_draw, jt.laminate_apply, jt.laminate_features),
}
#: families (context.FAMILY takes them over); flange_slip, a link turned across its bolt-hole clearance by the load's
#: history, and bar_pins, the play of the parallelogram bar's pins, are lost motion: scored as backlash; hose_retract
#: and wrist_shafts twist the drive trains under loads: joint compliance; tool_plate, the end-of-arm structure
#: carrying the target, as link deflection (as set D's bracket and set G's target rod)
FAMILY_J = {"planet_stage": "transmission", "diff_wrist": "transmission", "flange_slip": "backlash",
            "bar_pins": "backlash", "hose_retract": "joint_compliance", "wrist_shafts": "joint_compliance",
            "grout_creep": "mount_compliance", "wall_console": "mount_compliance", "skew_casting": "link_deflection",
            "tool_plate": "link_deflection", "brake_tilt": "thermal", "laminate_twist": "thermal"}
#: measurement effects that need the tracker's frame: none in set J
AFTER_TRACKER: set = set()
#: a hall whose air drifts over the session (pauses between the blocks)
AIR = {"laminate_twist"}
#: servo on and off: production periods and pauses (servo off, brakes closed) between the blocks, a cold start
BRAKE = {"brake_tilt"}
#: creeping mount: pauses (the moment held) and production periods between the blocks
CREEP = {"grout_creep"}
#: kinds whose sessions change the payload between blocks (pick and place with several loads)
PICK_PLACE = {"flange_slip", "bar_pins", "hose_retract", "wrist_shafts", "grout_creep", "wall_console",
              "skew_casting", "tool_plate"}
#: the tool plate's reach and the gripper's drop [mm] (the drawn target offset of 5-100 mm mapped onto them)
PLATE_MM, DROP_MM = (100.0, 200.0), (150.0, 300.0)


def session_options(robot_key, physics, rng, opts):
    """The session of a set-J case: a hall whose air drifts by 3-6 K (cycling by up to 0.5 K) over 5-8 blocks with
    pauses of 20-60 min for the laminate; 5-8 blocks with production periods and pauses of 10-40 min for the brake;
    5-8 blocks with pauses of 20-60 min and production periods for the grout; pick and place with 2-4 loads changed
    between 6-10 blocks for the load-driven kinds."""
    kinds = set(physics)
    if not kinds & set(EFFECTS_J):
        return opts
    opts = dict(opts)
    if kinds & AIR:
        opts.update(blocks=int(rng.integers(5, 9)), gap_kind="pause", pause_min=(20.0, 60.0),
                    air={"drift_K": rng.choice([-1, 1]) * rng.uniform(3.0, 6.0), "cycle_K": rng.uniform(0.0, 0.5),
                         "period_min": rng.uniform(60, 180)})
    if kinds & BRAKE:
        opts.update(blocks=max(opts["blocks"], int(rng.integers(5, 9))), gap_kind="mixed", pause_min=(10.0, 40.0))
    if kinds & CREEP:
        opts.update(blocks=max(opts["blocks"], int(rng.integers(5, 9))), gap_kind="mixed", pause_min=(20.0, 60.0))
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
    return opts


def probe_hook(physics, probe_mm):
    """The target offset (3,) [mm]: for the tool plate, the gripper's tip -- the plate's reach (the drawn offset's
    length 5-100 mm mapped onto 100-200 mm) along the drawn direction's part in the flange plane, then the gripper's
    drop (150-300 mm by the direction's part along the tool axis) down the tool axis (no random numbers); unchanged
    otherwise."""
    if "tool_plate" not in physics:
        return probe_mm
    n = np.linalg.norm(probe_mm)
    u = probe_mm / n
    d = np.array([u[0], u[1], 0.0])
    d = d / np.linalg.norm(d) if np.linalg.norm(d) > 1e-9 else np.array([1.0, 0.0, 0.0])
    reach = PLATE_MM[0] + (PLATE_MM[1] - PLATE_MM[0]) * (n - 5.0) / 95.0
    drop = DROP_MM[0] + (DROP_MM[1] - DROP_MM[0]) * abs(u[2])
    return reach * d + drop * np.array([0.0, 0.0, 1.0])


def payload_hook(physics, com_mm, probe_mm):
    """The payload's centre of mass (3,) [mm], tool frame: for the tool plate, between the gripper's jaws (three
    quarters down the gripper, plus a quarter of the drawn offset); unchanged otherwise (no random numbers)."""
    if "tool_plate" not in physics:
        return com_mm
    d, reach, drop = jb.plate_geometry(probe_mm)
    return reach * d + 0.75 * drop * np.array([0.0, 0.0, 1.0]) + 0.25 * np.asarray(com_mm, float)
