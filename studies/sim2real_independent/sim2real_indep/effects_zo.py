"""Set ZO: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zo_joint`, :mod:`effects_zo_body`, :mod:`effects_zo_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-ZO kind, so sets A-ZN regenerate unchanged; the
probe and payload hooks draw none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zo_body as zob
from sim2real_indep import effects_zo_joint as zoj
from sim2real_indep import effects_zo_thermal as zot

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZO = {
    "gravity_table": (zoj.table_draw, zoj.table_apply, zoj.table_features),
    "entrained_air": (zoj.air_draw, zoj.air_apply, zoj.air_features),
    "differential_lash": (zoj.diff_draw, zoj.diff_apply, zoj.diff_features),
    "tensioner_stop": (zoj.tensioner_draw, zoj.tensioner_apply, zoj.tensioner_features),
    "race_waviness": (zoj.wave_draw, zoj.wave_apply, zoj.wave_features),
    "lever_cam_fit": (zoj.cam_draw, zoj.cam_apply, zoj.cam_features),
    "deck_cupping": (zob.cup_draw, zob.cup_apply, zob.cup_features),
    "closed_cell_pads": (zob.pads_draw, zob.pads_apply, zob.pads_features),
    "cross_spring_pivot": (zob.cross_draw, zob.cross_apply, zob.cross_features),
    "qzs_mount": (zob.qzs_draw, zob.qzs_apply, zob.qzs_features),
    "ultrasonic_ram": (zot.ultra_draw, zot.ultra_apply, zot.ultra_features),
    "dry_ice_nozzle": (zot.ice_draw, zot.ice_apply, zot.ice_features),
}
#: families (context.FAMILY takes them over). gravity_table, a soft servo's gravity feed-forward read from a coarse
#: table, and entrained_air, the telescopic ram's cylinder softened by the air in its loaded chamber, joint compliance;
#: differential_lash, a differential wrist's two side-gear trains' lost motions, and tensioner_stop, a wrist belt's
#: tensioner arm pushed to its stop, backlash (errors that follow the load's side and the last motion across a play);
#: race_waviness, axis 1's encoder read on a wavy bearing raceway, and lever_cam_fit, hydraulic axes driven through a
#: fitted cam polynomial, transmission (the joints' reading and drive); deck_cupping, a cart deck cupping as it takes up
#: moisture, and closed_cell_pads, the stand on gas-stiffened foam pads, mount compliance (the robot's support);
#: cross_spring_pivot, a tool on a load-stiffened flexure pivot, and qzs_mount, a sensor on a quasi-zero-stiffness
#: isolator, link deflection (the end-of-arm structure carrying the target); ultrasonic_ram, the telescopic stage read
#: by an ultrasonic sensor whose compensation lags the air (a reading following the air, as set C's tracker scale),
#: and dry_ice_nozzle, a tool bracket chilled by dry-ice blasting, thermal
FAMILY_ZO = {"gravity_table": "joint_compliance", "entrained_air": "joint_compliance",
             "differential_lash": "backlash", "tensioner_stop": "backlash", "race_waviness": "transmission",
             "lever_cam_fit": "transmission", "deck_cupping": "mount_compliance",
             "closed_cell_pads": "mount_compliance", "cross_spring_pivot": "link_deflection",
             "qzs_mount": "link_deflection", "ultrasonic_ram": "thermal", "dry_ice_nozzle": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZO)
AFTER_TRACKER: set = set()
_PART = {"ur10": (1.0, 8.0), "kr16_like": (2.0, 14.0), "tool_changer": (10.0, 60.0)}
_RATED = {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 80.0)}
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"differential_lash": _PART, "tensioner_stop": _PART, "cross_spring_pivot": _PART,
           "closed_cell_pads": _RATED, "entrained_air": _RATED}
#: kinds whose effect follows the time: blocks, what lies between them, the pauses' length [min]
LONG = {"deck_cupping": ((4, 7), "pause", (20.0, 60.0)), "ultrasonic_ram": ((5, 9), "pause", (20.0, 60.0)),
        "dry_ice_nozzle": ((4, 7), "exercise", (10.0, 30.0))}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZO case: for :data:`LONG`, blocks with pauses (or production) between them (the
    ultrasonic sensor's: a hall air drifting by 2-5 K and cycling by 0.3-1 K over 40-120 min, logged); for
    :data:`PART_KG`, 3-5 blocks at least, each with a new part. No draws without a set-ZO kind."""
    kinds = set(physics) & set(EFFECTS_ZO)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(LONG)):
        (lo, hi), gap, pause = LONG[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind=gap, pause_min=pause)
    if "ultrasonic_ram" in kinds:
        opts["air"] = {"drift_K": float(rng.choice([-1.0, 1.0]) * rng.uniform(2.0, 5.0)),
                       "cycle_K": float(rng.uniform(0.3, 1.0)), "period_min": float(rng.uniform(40.0, 120.0))}
    for k in sorted(kinds & set(PART_KG)):
        opts["blocks"] = max(opts["blocks"], int(rng.integers(3, 6)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    return opts


def probe_hook(physics, probe):
    """The target on the tool beyond the cross-spring pivot, or at the dry-ice nozzle (no draws)."""
    for k in physics:
        if k == "cross_spring_pivot":
            probe = probe + np.array([0.0, 0.0, zob.CS_TARGET_MM])
        elif k == "dry_ice_nozzle":
            probe = probe + np.array([0.0, 0.0, zot.NOZZLE_MM])
    return probe


def payload_hook(physics, payload_com):
    """The part's centre of mass (tool frame) [mm]: 40-100 mm below the cross-spring pivot (the drawn offset's length
    mapped onto that range, its direction kept across the tool axis at half its size) (no draws)."""
    for k in physics:
        if k == "cross_spring_pivot":
            r = float(np.linalg.norm(payload_com))
            payload_com = np.array([0.5 * payload_com[0], 0.5 * payload_com[1], zob.CS_MM + 40.0 + 60.0 * r / 80])
    return payload_com
