"""Set M: the registry of its new effect kinds, their families, the session options they need and the hooks that put
the target on a gripper bar's end or a gripper finger's tip, and the part where it is held.

Physics in :mod:`effects_m_joint`, :mod:`effects_m_body`, :mod:`effects_m_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-M kind (and the probe and payload hooks none at
all), so sets A-L regenerate unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_m_body as mb
from sim2real_indep import effects_m_joint as mj
from sim2real_indep import effects_m_thermal as mt
from sim2real_indep.hardware import pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_M = {
    "slurry_lift": (mj.slurry_draw, mj.slurry_apply, mj.slurry_features),
    "oil_column": (mj.oil_draw, mj.oil_apply, mj.oil_features),
    "spindle_dither": (mj.dither_draw, mj.dither_apply, mj.dither_features),
    "chain_stage": (mj.chain_draw, mj.chain_apply, mj.chain_features),
    "friction_wheel": (mj.wheel_draw, mj.wheel_apply, mj.wheel_features),
    "cart_dock": (mb.dock_draw, mb.dock_apply, mb.dock_features),
    "carriage_play": (mb.carriage_draw, mb.carriage_apply, mb.carriage_features),
    "rope_mount": (mb.rope_draw, mb.rope_apply, mb.rope_features),
    "tie_rod_bar": (mb.bar_draw, mb.bar_apply, mb.bar_features),
    "jaw_play": (mb.jaw_draw, mb.jaw_apply, mb.jaw_features),
    "hot_plume": (mt.plume_draw, mt.plume_apply, mt.plume_features),
    "oil_growth": (mt.growth_draw, mt.growth_apply, mt.growth_features),
}
#: families (context.FAMILY takes them over). slurry_lift, the gears twisted by the slurry's lift on what dips into it,
#: and oil_column, the hydraulic axes' oil springs, joint compliance; spindle_dither, the main axes' lost motion whose
#: flank a running spindle's vibration chooses, and jaw_play, the target's jaw rocking in its guide's clearance,
#: backlash; chain_stage, the telescopic stage's chain travel, and friction_wheel, axis 1's reading through a measuring
#: wheel, transmission; cart_dock, the cart docked anew between the blocks, and carriage_play, the track carriage
#: rocking across its rollers' clearance, mount compliance (the robot's support); rope_mount, the tool on wire-rope
#: isolators, and tie_rod_bar, the gripper bar bending at two rates, link deflection (the end-of-arm structure
#: carrying the target, as sets K's RCC and L's holder); hot_plume, a measurement error following a hot air column's
#: temperature, and oil_growth, the cylinders growing with the oil's temperature, thermal
FAMILY_M = {"slurry_lift": "joint_compliance", "oil_column": "joint_compliance", "spindle_dither": "backlash",
            "jaw_play": "backlash", "chain_stage": "transmission", "friction_wheel": "transmission",
            "cart_dock": "mount_compliance", "carriage_play": "mount_compliance", "rope_mount": "link_deflection",
            "tie_rod_bar": "link_deflection", "hot_plume": "thermal", "oil_growth": "thermal"}
#: measurement effects that need the tracker's frame
AFTER_TRACKER = {"hot_plume"}
#: kinds whose sessions have blocks separated by production periods (and pauses): the dock, the oil, the spindle
BLOCKS = {"cart_dock": "exercise", "oil_growth": "mixed", "spindle_dither": "mixed"}
#: kinds whose sessions change the payload between blocks (pick and place, one load none)
PICK_PLACE = {"slurry_lift", "jaw_play", "tie_rod_bar", "rope_mount"}
#: the target's carrier: the bar's end, a finger's tip
TIP_KINDS = ("tie_rod_bar", "jaw_play")


def session_options(robot_key, physics, rng, opts):
    """The session of a set-M case: 5-8 blocks separated by production periods (the cart leaving and docking again) or
    by production periods and pauses of 10-40 min (the oil, the spindle switched between blocks); pick and place with
    2-4 loads changed between 6-10 blocks, the first block empty if the draw left none."""
    kinds = set(physics) & set(EFFECTS_M)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(BLOCKS)):
        opts.update(blocks=max(opts["blocks"], int(rng.integers(5, 9))), gap_kind=BLOCKS[k], pause_min=(10.0, 40.0))
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
        steps = list(opts["payload_steps"])
        if min(steps) > 0:                                   # held and empty blocks (no draws)
            steps[0] = 0.0
        opts["payload_steps"] = tuple(steps)
    return opts


def _share(probe_mm):
    return (np.linalg.norm(probe_mm) - 5.0) / 95.0


def probe_hook(physics, probe_mm, robot_key):
    """The target offset (3,) [mm] (no random numbers): a gripper bar's end, across the tool
    axis in the drawn direction, at the arm's bar length; a finger's tip at the gripper's half opening and tip height;
    unchanged otherwise."""
    kinds = set(physics)
    probe_mm = np.asarray(probe_mm, float)
    xy = np.array([probe_mm[0], probe_mm[1], 0.0])
    d = xy / np.linalg.norm(xy) if np.linalg.norm(xy) > 1e-9 else np.array([1.0, 0.0, 0.0])
    z = np.array([0.0, 0.0, 1.0])
    if "tie_rod_bar" in kinds and robot_key in mb.BAR:
        L0, L1 = mb.BAR[robot_key][0]
        return (L0 + (L1 - L0) * _share(probe_mm)) * d + (60.0 + 0.4 * abs(probe_mm[2])) * z
    if "jaw_play" in kinds and robot_key in mb.JAW:
        (w0, w1), (z0, z1) = mb.JAW[robot_key]
        return (w0 + (w1 - w0) * _share(probe_mm)) * d + (z0 + (z1 - z0) * abs(probe_mm[2]) / np.linalg.norm(
            probe_mm)) * z
    return probe_mm


def payload_hook(physics, com_mm, probe_mm):
    """The payload's centre of mass (3,) [mm], tool frame (no random numbers): the part at the bar's middle, between
    the fingers at 85 % of the tip's height plus a quarter of the drawn offset; unchanged otherwise."""
    kinds = set(physics)
    if "tie_rod_bar" in kinds:
        return 0.5 * np.asarray(probe_mm, float)
    if "jaw_play" in kinds:
        return np.array([0.0, 0.0, 0.85 * probe_mm[2]]) + 0.25 * np.asarray(com_mm, float)
    return com_mm
