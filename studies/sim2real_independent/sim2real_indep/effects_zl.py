"""Set ZL: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zl_joint`, :mod:`effects_zl_body`, :mod:`effects_zl_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-ZL kind, so sets A-ZK regenerate unchanged; the probe
and payload hooks draw none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zl_body as zlb
from sim2real_indep import effects_zl_joint as zlj
from sim2real_indep import effects_zl_thermal as zlt

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZL = {
    "idle_current": (zlj.idle_draw, zlj.idle_apply, zlj.idle_features),
    "kt_saturation": (zlj.saturation_draw, zlj.saturation_apply, zlj.saturation_features),
    "current_remanence": (zlj.remanence_draw, zlj.remanence_apply, zlj.remanence_features),
    "hose_bourdon": (zlj.bourdon_draw, zlj.bourdon_apply, zlj.bourdon_features),
    "stator_leakage": (zlj.leakage_draw, zlj.leakage_apply, zlj.leakage_features),
    "step_truncation": (zlj.truncation_draw, zlj.truncation_apply, zlj.truncation_features),
    "raised_floor": (zlb.floor_draw, zlb.floor_apply, zlb.floor_features),
    "load_cells": (zlb.cells_draw, zlb.cells_apply, zlb.cells_features),
    "ft_sensor": (zlb.ft_draw, zlb.ft_apply, zlb.ft_features),
    "pad_pivot": (zlb.pad_draw, zlb.pad_apply, zlb.pad_features),
    "thermal_ratchet": (zlt.ratchet_draw, zlt.ratchet_apply, zlt.ratchet_features),
    "arc_radiation": (zlt.arc_draw, zlt.arc_apply, zlt.arc_features),
}
#: families (context.FAMILY takes them over). idle_current, stepper wrists sagging as their drivers cut the holding
#: current at standstill, and kt_saturation, current-based wrist control whose motors' torque constant saturates,
#: joint compliance; current_remanence, Hall current sensors magnetised by the last large current under current-based
#: control (an error following the last moves, reset at each enable), and hose_bourdon, a wrist roll's lash flank
#: chosen by a pressurised gripper hose while a part is held, backlash; stator_leakage, output magnetic encoders
#: misread by the motor's current-borne leakage field, and step_truncation, stepper wrists short by the running sum of
#: truncated step counts, transmission (the joints' reading and drive); raised_floor, the base on an access floor's
#: panels, and load_cells, the base on a weighing platform's load cells, mount
#: compliance; ft_sensor, a force/torque sensor's flexure, and pad_pivot, a part pivoting between soft finger pads,
#: link deflection (the end-of-arm structure carrying the target); thermal_ratchet, tubes growing through their
#: fits' friction, and arc_radiation, the forearm heated by the welding arc's radiation, thermal
FAMILY_ZL = {"idle_current": "joint_compliance", "kt_saturation": "joint_compliance",
             "current_remanence": "backlash", "hose_bourdon": "backlash", "stator_leakage": "transmission",
             "step_truncation": "transmission", "raised_floor": "mount_compliance",
             "load_cells": "mount_compliance", "ft_sensor": "link_deflection", "pad_pivot": "link_deflection",
             "thermal_ratchet": "thermal", "arc_radiation": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZL)
AFTER_TRACKER: set = set()
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"idle_current": {"ur10": (1.0, 8.0), "kr16_like": (2.0, 14.0), "tool_changer": (10.0, 60.0)},
           "kt_saturation": {"ur10": (1.0, 8.0), "kr16_like": (2.0, 14.0), "tool_changer": (10.0, 60.0)},
           "raised_floor": {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 80.0)},
           "ft_sensor": {"ur10": (1.0, 8.0), "kr16_like": (2.0, 14.0), "tool_changer": (10.0, 60.0)},
           "pad_pivot": {"ur10": (1.0, 8.0), "kr16_like": (2.0, 14.0), "tool_changer": (10.0, 60.0)},
           "hose_bourdon": {"ur10": (1.0, 8.0), "kr16_like": (2.0, 14.0), "tool_changer": (10.0, 60.0)}}
#: kinds whose part is held in some blocks only (the gripper's line pressurised while it holds one)
SOME_EMPTY = {"hose_bourdon"}
#: kinds whose effect follows the time, the production and the pauses: blocks, what lies between them, the pauses'
#: length [min]
LONG = {"thermal_ratchet": ((4, 7), "mixed", (20.0, 60.0)), "arc_radiation": ((4, 7), "exercise", (10.0, 30.0))}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZL case: for :data:`LONG`, blocks with production or pauses between them that spread the
    session over hours; for :data:`PART_KG`, 3-5 blocks at least, each with a new part (:data:`SOME_EMPTY`: every
    other block empty). No draws without a set-ZL kind."""
    kinds = set(physics) & set(EFFECTS_ZL)
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
    if kinds & SOME_EMPTY:  # after every part kind's schedule: the gripper holds nothing in every other block
        steps = np.array(opts["payload_steps"])
        steps[int(rng.integers(0, 2))::2] = 0.0
        opts["payload_steps"] = tuple(steps)
    return opts


def probe_hook(physics, probe):
    """The target on the tool past the force/torque sensor, or on the part below the finger pads (no draws)."""
    for k in physics:
        if k == "ft_sensor":
            probe = probe + np.array([0.0, 0.0, zlb.FT_TARGET_MM])
        elif k == "pad_pivot":
            probe = probe + np.array([0.0, 0.0, zlb.PART_TARGET_MM])
    return probe


def payload_hook(physics, payload_com):
    """The part's centre of mass (tool frame) [mm]: on the tool past the sensor, or 40-90 mm below the pads (the
    drawn offset's length mapped onto that range, its direction kept across the tool axis at a fifth) (no draws)."""
    for k in physics:
        if k == "ft_sensor":
            payload_com = payload_com + np.array([0.0, 0.0, zlb.SENSOR_MM + 100.0])
        elif k == "pad_pivot":
            r = float(np.linalg.norm(payload_com))
            payload_com = np.array([0.2 * payload_com[0], 0.2 * payload_com[1], zlb.PAD_MM + 40.0 + 50.0 * r / 80.0])
    return payload_com
