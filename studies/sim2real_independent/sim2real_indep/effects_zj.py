"""Set ZJ: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zj_joint`, :mod:`effects_zj_body`, :mod:`effects_zj_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-ZJ kind, so sets A-ZI regenerate unchanged; the probe
hook draws none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zj_body as zjb
from sim2real_indep import effects_zj_joint as zjj
from sim2real_indep import effects_zj_thermal as zjt

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZJ = {
    "gauge_zero_drift": (zjj.zero_draw, zjj.zero_apply, zjj.zero_features),
    "traction_microslip": (zjj.traction_draw, zjj.traction_apply, zjj.traction_features),
    "gyro_filter": (zjj.gyro_draw, zjj.gyro_apply, zjj.gyro_features),
    "stepper_stall": (zjj.stall_draw, zjj.stall_apply, zjj.stall_features),
    "ghost_order": (zjj.ghost_draw, zjj.ghost_apply, zjj.ghost_features),
    "hydrostatic_rail": (zjb.hydro_draw, zjb.hydro_apply, zjb.hydro_features),
    "clay_pier": (zjb.pier_draw, zjb.pier_apply, zjb.pier_features),
    "gecko_pad": (zjb.gecko_draw, zjb.gecko_apply, zjb.gecko_features),
    "warm_sag": (zjb.sag_draw, zjb.sag_apply, zjb.sag_features),
    "wind_flank": (zjb.wind_draw, zjb.wind_apply, zjb.wind_features),
    "stray_weld_current": (zjt.weld_draw, zjt.weld_apply, zjt.weld_features),
    "plume_bracket": (zjt.plume_draw, zjt.plume_apply, zjt.plume_features),
}
#: families (context.FAMILY takes them over). gauge_zero_drift, joint torque sensors' thermal zero drift that a
#: joint-impedance controller turns into joint offsets, and traction_microslip, traction-roller wrist reducers
#: yielding by Mindlin micro-slip with Masing memory, joint compliance; gyro_filter, link angles from gyro-aided
#: inclination sensors whose complementary filter still carries the last moves' gyro scale error, and wind_flank,
#: axis 1's lost motion whose flank a steady wind's torque chooses, backlash (errors that follow the last motion);
#: stepper_stall, open-loop stepper wrists losing steps in loaded, fast moves, and ghost_order, axis 1's wheel
#: carrying its hobbing machine's index order, transmission (the joints' drive); hydrostatic_rail, the base on a
#: carriage held by opposed constant-flow hydrostatic pads, and clay_pier, the base on a pair of short piers in soft
#: clay, mount compliance; gecko_pad, a part on a directional dry adhesive stiffened by its shear, and warm_sag, a
#: warm moulding creeping under its weight's history, link deflection (the end-of-arm structure carrying the target);
#: stray_weld_current, the main bearings heated by a welding current returning through the arm, and plume_bracket, a
#: bracket heated by a hot part's plume while the tool points down, thermal
FAMILY_ZJ = {"gauge_zero_drift": "joint_compliance", "traction_microslip": "joint_compliance",
             "gyro_filter": "backlash", "wind_flank": "backlash", "stepper_stall": "transmission",
             "ghost_order": "transmission", "hydrostatic_rail": "mount_compliance", "clay_pier": "mount_compliance",
             "gecko_pad": "link_deflection", "warm_sag": "link_deflection", "stray_weld_current": "thermal",
             "plume_bracket": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZJ)
AFTER_TRACKER: set = set()
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"gecko_pad": {"ur10": (0.2, 2.0), "kr16_like": (0.3, 3.0), "tool_changer": (1.0, 8.0)},
           "warm_sag": {"ur10": (0.3, 2.5), "kr16_like": (0.5, 4.0), "tool_changer": (1.0, 8.0)},
           "plume_bracket": {"ur10": (0.5, 4.0), "kr16_like": (1.0, 8.0), "tool_changer": (2.0, 20.0)}}
#: kinds whose effect follows the time, the production and the pauses: blocks, what lies between them, the pauses'
#: length [min]
LONG = {"gauge_zero_drift": ((4, 7), "mixed", (20.0, 60.0)), "stray_weld_current": ((4, 7), "mixed", (20.0, 60.0)),
        "plume_bracket": ((4, 7), "pause", (5.0, 20.0))}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZJ case: for :data:`LONG`, blocks with production or pauses between them that spread the
    session over hours; for :data:`PART_KG`, 3-5 blocks at least, each with a new part. No draws without a set-ZJ
    kind."""
    kinds = set(physics) & set(EFFECTS_ZJ)
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
    """The target on the part of the gecko pad, at the warm panel's tip, at the plume bracket's end (no draws)."""
    for k in physics:
        if k == "gecko_pad":
            probe = probe + np.array([0.0, 0.0, zjb.PART_MM])
        elif k == "warm_sag":
            probe = probe + np.array([zjb.PANEL_MM, 0.0, 0.0])
        elif k == "plume_bracket":
            probe = probe + np.array([0.0, 0.0, zjt.BRACKET_MM])
    return probe
