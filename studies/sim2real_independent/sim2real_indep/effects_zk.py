"""Set ZK: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zk_joint`, :mod:`effects_zk_body`, :mod:`effects_zk_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-ZK kind, so sets A-ZJ regenerate unchanged; the probe
hook draws none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zk_body as zkb
from sim2real_indep import effects_zk_joint as zkj
from sim2real_indep import effects_zk_thermal as zkt

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZK = {
    "kt_magnet_drift": (zkj.kt_draw, zkj.kt_apply, zkj.kt_features),
    "capstan_spans": (zkj.capstan_draw, zkj.capstan_apply, zkj.capstan_features),
    "sensor_hysteresis": (zkj.hyst_draw, zkj.hyst_apply, zkj.hyst_features),
    "housing_spread": (zkj.spread_draw, zkj.spread_apply, zkj.spread_features),
    "quench_ovality": (zkj.ovality_draw, zkj.ovality_apply, zkj.ovality_features),
    "ride_height": (zkj.ride_draw, zkj.ride_apply, zkj.ride_features),
    "beam_torsion": (zkb.beam_draw, zkb.beam_apply, zkb.beam_features),
    "asphalt_creep": (zkb.asphalt_draw, zkb.asphalt_apply, zkb.asphalt_features),
    "flange_buckling": (zkb.buckle_draw, zkb.buckle_apply, zkb.buckle_features),
    "dashpot_slide": (zkb.dashpot_draw, zkb.dashpot_apply, zkb.dashpot_features),
    "drive_board_heat": (zkt.board_draw, zkt.board_apply, zkt.board_features),
    "ram_wiper_heat": (zkt.ram_draw, zkt.ram_apply, zkt.ram_features),
}
#: families (context.FAMILY takes them over). kt_magnet_drift, the gravity feed-forward of current-based compliant
#: control falling short as the magnets warm, and capstan_spans, a cable-capstan stage whose free spans change length
#: with the angle, joint compliance; sensor_hysteresis, joint torque sensors' hysteresis read by a joint-impedance
#: controller (an error following the load's last change), and housing_spread, axis 1's lost motion widened by its
#: housing spreading under the tilting moment, backlash; quench_ovality, axis 1's ring gear distorted by its
#: hardening, and ride_height, axis 1's magnetic ring encoder read across an air gap set by the axial load,
#: transmission; beam_torsion, the base on a single I-beam twisting about its axis, and asphalt_creep, the base's pads
#: creeping into a sun-warmed asphalt yard, mount compliance; flange_buckling, a sheet-metal bracket whose free flange
#: buckles one way, and dashpot_slide, a tool on a spring-and-dashpot compliance slide, link deflection (the end-of-arm
#: structure carrying the target); drive_board_heat, the link tubes warmed by the joint-integrated drives, and
#: ram_wiper_heat, the telescopic ram warmed by its wipers' friction, thermal
FAMILY_ZK = {"kt_magnet_drift": "joint_compliance", "capstan_spans": "joint_compliance",
             "sensor_hysteresis": "backlash", "housing_spread": "backlash", "quench_ovality": "transmission",
             "ride_height": "transmission", "beam_torsion": "mount_compliance", "asphalt_creep": "mount_compliance",
             "flange_buckling": "link_deflection", "dashpot_slide": "link_deflection",
             "drive_board_heat": "thermal", "ram_wiper_heat": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZK)
AFTER_TRACKER: set = set()
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"flange_buckling": {"ur10": (0.5, 3.0), "kr16_like": (1.0, 5.0), "tool_changer": (5.0, 30.0)},
           "dashpot_slide": {"ur10": (0.5, 3.0), "kr16_like": (1.0, 5.0), "tool_changer": (5.0, 30.0)},
           "ride_height": {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 80.0)},
           "beam_torsion": {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 80.0)}}
#: kinds whose effect follows the time, the production and the pauses: blocks, what lies between them, the pauses'
#: length [min]
LONG = {"kt_magnet_drift": ((4, 7), "mixed", (20.0, 60.0)), "drive_board_heat": ((4, 7), "mixed", (20.0, 60.0)),
        "asphalt_creep": ((4, 7), "pause", (20.0, 60.0)), "ram_wiper_heat": ((4, 7), "mixed", (10.0, 30.0))}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZK case: for :data:`LONG`, blocks with production or pauses between them that spread the
    session over hours; for :data:`PART_KG`, 3-5 blocks at least, each with a new part. No draws without a set-ZK
    kind."""
    kinds = set(physics) & set(EFFECTS_ZK)
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
    """The target at the buckling bracket's end and on the dashpot slide's carriage (no draws)."""
    for k in physics:
        if k == "flange_buckling":
            probe = probe + np.array([0.0, 0.0, zkb.BRACKET_MM])
        elif k == "dashpot_slide":
            probe = probe + np.array([0.0, 0.0, zkb.SLIDE_MM])
    return probe
