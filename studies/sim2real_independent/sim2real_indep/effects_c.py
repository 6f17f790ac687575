"""Set C: the registry of its new effect kinds, and the session and payload options they need.

Physics in :mod:`effects_c_thermal`, :mod:`effects_c_joint`, :mod:`effects_c_body` (sources in their docstrings).
The hooks here consume random numbers only when a case has a set-C kind, so sets A and B regenerate unchanged.
Imports nothing of tolalloc.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from sim2real_indep import effects_c_body as cb
from sim2real_indep import effects_c_joint as cj
from sim2real_indep import effects_c_thermal as ct
from sim2real_indep.hardware import pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_C = {
    "twonode": (ct.twonode_draw, ct.twonode_apply, ct.twonode_features),
    "workcell": (ct.workcell_draw, ct.workcell_apply, ct.workcell_features),
    "column_bow": (ct.column_draw, ct.column_apply, ct.column_features),
    "tracker_scale": (ct.scale_draw, ct.scale_apply, ct.scale_features),
    "rv_error": (cj.rv_draw, cj.rv_apply, cj.rv_features),
    "dual_encoder": (cj.dual_encoder_draw, cj.dual_encoder_apply, cj.dual_encoder_features),
    "runout": (cj.runout_draw, cj.runout_apply, cj.runout_features),
    "hyst_stiffness": (cj.hyst_draw, cj.hyst_apply, cj.hyst_features),
    "bearing_tilt": (cj.tilt_draw, cj.tilt_apply, cj.tilt_features),
    "dahl": (cj.dahl_draw, cj.dahl_apply, cj.dahl_features),
    "track": (cb.track_draw, cb.track_apply, cb.track_features),
    "box_torsion": (cb.box_draw, cb.box_apply, cb.box_features),
    "bolted_tube": (cb.bolted_draw, cb.bolted_apply, cb.bolted_features),
}
#: kinds applied after the tracker is placed (they need its frame, ``hw["tracker"]``)
AFTER_TRACKER = {"tracker_scale"}
DRIVE_HEAT = {"twonode", "workcell", "column_bow"}
AIR = {"workcell", "tracker_scale"}
#: kinds whose sessions change the payload between blocks (pick and place with several loads)
PICK_PLACE = {"hyst_stiffness", "bearing_tilt", "box_torsion", "bolted_tube", "track"}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-C case: duty cycles with pauses of varied length for drive heat; a drifting workcell
    air for air-driven kinds; pick and place with 2-4 loads changed between 6-10 blocks."""
    kinds = set(physics)
    if not kinds & set(EFFECTS_C):
        return opts
    opts = dict(opts)
    if kinds & DRIVE_HEAT:
        opts.update(blocks=int(rng.integers(5, 9)), gap_kind="mixed", pause_min=(5.0, 60.0))
    if kinds & AIR:
        opts.update(blocks=int(rng.integers(5, 9)), gap_kind="mixed" if kinds & DRIVE_HEAT else "pause",
                    pause_min=(10.0, 60.0), air={"drift_K": rng.choice([-1, 1]) * rng.uniform(2.0, 5.0),
                                                 "cycle_K": rng.uniform(0.0, 0.8), "period_min": rng.uniform(60, 180)})
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
    return opts


def payload_com(physics, com, rng):
    """Payload centre of mass in the tool frame: an offset gripper (120-250 mm, mostly across the tool axis) for
    the link-torsion kind; unchanged otherwise."""
    if "box_torsion" not in physics:
        return com
    a = rng.uniform(0, 2 * np.pi)
    v = np.array([np.cos(a), np.sin(a), rng.uniform(-0.3, 0.3)])
    return v / np.linalg.norm(v) * rng.uniform(120, 250)


def session_hook(physics, session, rng):
    """An approach plan for the lost-motion kind: each joint's final approach from a random side (logged as its
    direction), over a travel log-U(0.005, 0.5) deg at a speed log-U(0.2, 20) deg/s."""
    if "dahl" not in physics:
        return session
    P, n = session.q.shape
    d = rng.choice([-1.0, 1.0], (P, n))
    travel = np.deg2rad(np.exp(rng.uniform(np.log(0.005), np.log(0.5), (P, n))))
    speed = np.deg2rad(np.exp(rng.uniform(np.log(0.2), np.log(20.0), (P, n))))
    return replace(session, direction=d, approach={"travel": travel, "speed": speed})
