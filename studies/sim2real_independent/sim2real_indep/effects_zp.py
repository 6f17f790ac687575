"""Set ZP: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zp_joint`, :mod:`effects_zp_body`, :mod:`effects_zp_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-ZP kind, so sets A-ZO regenerate unchanged; the
probe and payload hooks draw none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zp_body as zpb
from sim2real_indep import effects_zp_joint as zpj
from sim2real_indep import effects_zp_thermal as zpt

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZP = {
    "soaked_jacket": (zpj.jacket_draw, zpj.jacket_apply, zpj.jacket_features),
    "vessel_list": (zpj.list_draw, zpj.list_apply, zpj.list_features),
    "clevis_clearance": (zpj.clevis_draw, zpj.clevis_apply, zpj.clevis_features),
    "clock_spring_flank": (zpj.spring_draw, zpj.spring_apply, zpj.spring_features),
    "mylar_strip": (zpj.strip_draw, zpj.strip_apply, zpj.strip_features),
    "tacho_integration": (zpj.tacho_draw, zpj.tacho_apply, zpj.tacho_features),
    "magnet_base": (zpb.magnet_draw, zpb.magnet_apply, zpb.magnet_features),
    "ballast_stand": (zpb.stand_draw, zpb.stand_apply, zpb.stand_features),
    "needle_gripper": (zpb.needle_draw, zpb.needle_apply, zpb.needle_features),
    "ltb_boom": (zpb.ltb_draw, zpb.ltb_apply, zpb.ltb_features),
    "heated_bed": (zpt.bed_draw, zpt.bed_apply, zpt.bed_features),
    "air_motor_heat": (zpt.air_draw, zpt.air_apply, zpt.air_features),
}
#: families (context.FAMILY takes them over). soaked_jacket, a drying jacket's water weighing on the links, and
#: vessel_list, gravity turning in the base frame as the vessel lists, joint compliance (the gears twisted);
#: clevis_clearance, the boom cylinders' eye-pin clearances, and clock_spring_flank, the wrist rolls' lost motion whose
#: flank a spiral spring's wind-up chooses, backlash; mylar_strip, axis 1's code strip swelling with the humidity, and
#: tacho_integration, boom axes read by integrating tachogenerators, transmission (the joints' reading); magnet_base, a
#: magnetically clamped base's rough interface, and ballast_stand, an unanchored stand lifting a foot, mount compliance;
#: needle_gripper, a part on a needle gripper, and ltb_boom, a gripper boom near lateral-torsional buckling, link
#: deflection (the end-of-arm structure carrying the target); heated_bed, the forearm warmed by a heated bed by where
#: the arm has worked, and air_motor_heat, a spindle's extension following the compressor-cycled supply air, thermal
FAMILY_ZP = {"soaked_jacket": "joint_compliance", "vessel_list": "joint_compliance",
             "clevis_clearance": "backlash", "clock_spring_flank": "backlash", "mylar_strip": "transmission",
             "tacho_integration": "transmission", "magnet_base": "mount_compliance",
             "ballast_stand": "mount_compliance", "needle_gripper": "link_deflection", "ltb_boom": "link_deflection",
             "heated_bed": "thermal", "air_motor_heat": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZP)
AFTER_TRACKER: set = set()
_PART = {"ur10": (1.0, 8.0), "kr16_like": (2.0, 14.0), "tool_changer": (10.0, 60.0)}
_RATED = {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 80.0)}
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"needle_gripper": _PART, "ltb_boom": _PART, "magnet_base": _RATED, "ballast_stand": _RATED,
           "clevis_clearance": _RATED, "clock_spring_flank": _RATED}
#: kinds whose effect follows the time: blocks, what lies between them, the pauses' length [min]
LONG = {"soaked_jacket": ((4, 7), "pause", (15.0, 45.0)), "vessel_list": ((3, 6), "pause", (10.0, 40.0)),
        "mylar_strip": ((4, 7), "pause", (20.0, 60.0)), "tacho_integration": ((3, 6), "pause", (30.0, 90.0)),
        "heated_bed": ((3, 6), "pause", (5.0, 20.0))}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZP case: for :data:`LONG`, blocks with pauses between them; for :data:`PART_KG`, 3-5
    blocks at least, each with a new part. No draws without a set-ZP kind."""
    kinds = set(physics) & set(EFFECTS_ZP)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(LONG)):
        (lo, hi), gap, pause = LONG[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind=gap, pause_min=pause)
    for k in sorted(kinds & set(PART_KG)):
        opts["blocks"] = max(opts["blocks"], int(rng.integers(3, 6)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    return opts


def probe_hook(physics, probe):
    """The target at the boom's tip or at the spindle's nose (no draws)."""
    for k in physics:
        if k == "ltb_boom":
            probe = probe + np.array([0.0, 0.0, zpb.LTB_MM])
        elif k == "air_motor_heat":
            probe = probe + np.array([0.0, 0.0, zpt.SPINDLE_MM])
    return probe


def payload_hook(physics, payload_com):
    """The part's centre of mass (tool frame) [mm] at the boom's tip (the drawn offset's cross-axis part kept at 30 %)
    (no draws)."""
    for k in physics:
        if k == "ltb_boom":
            payload_com = np.array([0.3 * payload_com[0], 0.3 * payload_com[1], zpb.LTB_MM])
    return payload_com
