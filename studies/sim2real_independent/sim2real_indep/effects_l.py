"""Set L: the registry of its new effect kinds, their families, the session options they need and the hooks that put
the target on a gripper finger's tip and the part between the fingers.

Physics in :mod:`effects_l_joint`, :mod:`effects_l_body`, :mod:`effects_l_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-L kind (and the probe and payload hooks none at
all), so sets A-K regenerate unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_l_body as lb
from sim2real_indep import effects_l_joint as lj
from sim2real_indep import effects_l_thermal as lt
from sim2real_indep.hardware import pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_L = {
    "polymer_heat": (lj.soft_draw, lj.soft_apply, lj.soft_features),
    "dispense_drain": (lj.drain_draw, lj.drain_apply, lj.drain_features),
    "gauge_pinion": (lj.gauge_draw, lj.gauge_apply, lj.gauge_features),
    "valve_lap": (lj.valve_draw, lj.valve_apply, lj.valve_features),
    "pin_ring": (lj.pin_draw, lj.pin_apply, lj.pin_features),
    "pallet_load": (lb.pallet_draw, lb.pallet_apply, lb.pallet_features),
    "anchor_loose": (lb.loose_draw, lb.loose_apply, lb.loose_features),
    "grip_spread": (lb.grip_draw, lb.grip_apply, lb.grip_features),
    "float_holder": (lb.float_draw, lb.float_apply, lb.float_features),
    "guide_errors": (lb.guide_draw, lb.guide_apply, lb.guide_features),
    "hot_part": (lt.hot_draw, lt.hot_apply, lt.hot_features),
    "wet_arm": (lt.wet_draw, lt.wet_apply, lt.wet_features),
}
#: families (context.FAMILY takes them over). polymer_heat, the gears' twist growing as they warm, is joint compliance
#: (the family whose model holds its shape, as set K's thermal backlash is backlash); dispense_drain, the gears twisted
#: by an unlogged cartridge's weight, joint compliance; gauge_pinion, the lost motion of the pinion driving axis 1's
#: secondary encoder (the joint leads its reading), and valve_lap, a hydraulic axis stopping anywhere in its valve's
#: dead band, backlash; pin_ring, the pins' pitch errors, and guide_errors, the telescopic stage's straightness and
#: angular error motions along its stroke (the joint's motion errors as a function of its own position, as set C's
#: bearing runout), transmission; pallet_load, the base frame tilted by the robot and the growing pallet, and
#: anchor_loose, the base plate opening as its anchors loosen, mount compliance; grip_spread, the fingers carrying the
#: target spread by the grip force and the part, and float_holder, the tool on a preloaded radially compliant holder,
#: link deflection (the end-of-arm structure carrying the target, as sets D's bracket, G's rod, J's plate and K's RCC);
#: hot_part, the gripper heated by the parts it holds, and wet_arm, the forearm cooled by evaporating coolant, thermal
FAMILY_L = {"polymer_heat": "joint_compliance", "dispense_drain": "joint_compliance", "gauge_pinion": "backlash",
            "valve_lap": "backlash", "pin_ring": "transmission", "guide_errors": "transmission",
            "pallet_load": "mount_compliance", "anchor_loose": "mount_compliance", "grip_spread": "link_deflection",
            "float_holder": "link_deflection", "hot_part": "thermal", "wet_arm": "thermal"}
#: measurement effects that need the tracker's frame: none in set L
AFTER_TRACKER: set = set()
#: kinds driven by the production between the blocks: production periods and pauses (servo off)
PRODUCTION = {"polymer_heat", "dispense_drain", "pallet_load", "anchor_loose", "hot_part", "wet_arm"}
#: kinds consuming or stacking during production: production periods between all blocks
EXERCISE = {"dispense_drain", "pallet_load"}
#: kinds whose sessions change the payload between blocks (pick and place with several loads, one of them none)
PICK_PLACE = {"pallet_load", "grip_spread", "hot_part", "valve_lap"}
#: the gripper's half opening at the target's finger [mm] per arm (assumed); tip heights in :mod:`effects_l_body`
HALF_OPEN_MM = {"ur10": (15.0, 45.0), "kr16_like": (25.0, 70.0), "tool_changer": (100.0, 200.0)}
FINGER_KINDS = {"grip_spread", "hot_part"}
#: the part's contact height as a share of the tip height
CONTACT_SHARE = 0.85


def session_options(robot_key, physics, rng, opts):
    """The session of a set-L case: 5-8 blocks with production periods and pauses of 10-40 min (servo off) for the
    production-driven kinds (production between all blocks for the consuming and stacking ones); pick and place with
    2-4 loads (one of them none: no part held; a gripper case's first block empty if the draw left none) changed between
    6-10 blocks for the load-driven kinds."""
    kinds = set(physics)
    if not kinds & set(EFFECTS_L):
        return opts
    opts = dict(opts)
    if kinds & PRODUCTION:
        opts.update(blocks=max(opts["blocks"], int(rng.integers(5, 9))), gap_kind="mixed", pause_min=(10.0, 40.0))
    if kinds & EXERCISE:
        opts.update(gap_kind="exercise")
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
        steps = list(opts["payload_steps"])
        if kinds & FINGER_KINDS and min(steps) > 0:      # the gripper both holding and empty (no draws)
            steps[0] = 0.0
        opts["payload_steps"] = tuple(steps)
    return opts


def probe_hook(physics, probe_mm, robot_key):
    """The target offset (3,) [mm]: for the gripper kinds, on the tip of the finger the drawn offset points to -- its
    part across the tool axis the closing axis, the length 5-100 mm mapped onto the arm's half opening, the part along
    the axis onto its tip height (no random numbers); unchanged otherwise."""
    if not set(physics) & FINGER_KINDS:
        return probe_mm
    (w0, w1), (z0, z1) = HALF_OPEN_MM[robot_key], lb.FINGER_TIP_MM[robot_key]
    n = np.linalg.norm(probe_mm)
    u = probe_mm / n
    d = np.array([u[0], u[1], 0.0])
    d = d / np.linalg.norm(d) if np.linalg.norm(d) > 1e-9 else np.array([1.0, 0.0, 0.0])
    return (w0 + (w1 - w0) * (n - 5.0) / 95.0) * d + (z0 + (z1 - z0) * abs(u[2])) * np.array([0.0, 0.0, 1.0])


def payload_hook(physics, com_mm, probe_mm):
    """The payload's centre of mass (3,) [mm], tool frame: for the gripper kinds, between the fingers at the contact
    height (85 % of the tip height) plus a quarter of the drawn offset; unchanged otherwise (no random numbers)."""
    if not set(physics) & FINGER_KINDS:
        return com_mm
    return np.array([0.0, 0.0, CONTACT_SHARE * probe_mm[2]]) + 0.25 * np.asarray(com_mm, float)
