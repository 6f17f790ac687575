"""Set ZM: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zm_joint`, :mod:`effects_zm_body`, :mod:`effects_zm_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-ZM kind, so sets A-ZL regenerate unchanged; the
probe and payload hooks draw none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zm_body as zmb
from sim2real_indep import effects_zm_joint as zmj
from sim2real_indep import effects_zm_thermal as zmt

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZM = {
    "moment_softening": (zmj.softening_draw, zmj.softening_apply, zmj.softening_features),
    "mesh_ripple": (zmj.ripple_draw, zmj.ripple_apply, zmj.ripple_features),
    "upstream_toss": (zmj.toss_draw, zmj.toss_apply, zmj.toss_features),
    "limiter_play": (zmj.limiter_draw, zmj.limiter_apply, zmj.limiter_features),
    "microstep_error": (zmj.microstep_draw, zmj.microstep_apply, zmj.microstep_features),
    "step_accuracy": (zmj.accuracy_draw, zmj.accuracy_apply, zmj.accuracy_features),
    "conical_mounts": (zmb.conical_draw, zmb.conical_apply, zmb.conical_features),
    "rail_blocks": (zmb.rail_draw, zmb.rail_apply, zmb.rail_features),
    "mandrel_rock": (zmb.mandrel_draw, zmb.mandrel_apply, zmb.mandrel_features),
    "jaw_guide_tilt": (zmb.jaw_draw, zmb.jaw_apply, zmb.jaw_features),
    "mean_radiant": (zmt.radiant_draw, zmt.radiant_apply, zmt.radiant_features),
    "enclosure_door": (zmt.door_draw, zmt.door_apply, zmt.door_features),
}
#: families (context.FAMILY takes them over). moment_softening, wrist gears softened by the tilting moment on their
#: output bearing, and mesh_ripple, wrist strain-wave gears whose mesh stiffness ripples with the wave generator's
#: angle, joint compliance; upstream_toss, a wrist bend's lost motion tossed onto a flank by the main axes'
#: deceleration, and limiter_play, a ball-detent torque limiter's seat play flanked by the off-axis tool's weight,
#: backlash; microstep_error, stepper wrists short of their microsteps, and step_accuracy, their full steps off by the
#: motors' tooth-pitch errors, transmission (the joints' drive); conical_mounts, the base on hardening cone mounts, and
#: rail_blocks, the base on a parked track carriage's rail blocks, softer pulled than pressed, mount compliance; mandrel_rock, a
#: part rocking on an expanding mandrel's sleeve, and jaw_guide_tilt, a gripper's jaws tilting in their rail guides,
#: link deflection (the end-of-arm structure carrying the target); mean_radiant, links at the operative temperature of
#: the air and the lagging envelope, and enclosure_door, a conditioned cell opened at each loading, thermal
FAMILY_ZM = {"moment_softening": "joint_compliance", "mesh_ripple": "joint_compliance",
             "upstream_toss": "backlash", "limiter_play": "backlash", "microstep_error": "transmission",
             "step_accuracy": "transmission", "conical_mounts": "mount_compliance",
             "rail_blocks": "mount_compliance", "mandrel_rock": "link_deflection",
             "jaw_guide_tilt": "link_deflection", "mean_radiant": "thermal", "enclosure_door": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZM)
AFTER_TRACKER: set = set()
_PART = {"ur10": (1.0, 8.0), "kr16_like": (2.0, 14.0), "tool_changer": (10.0, 60.0)}
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"moment_softening": _PART, "mandrel_rock": _PART, "jaw_guide_tilt": _PART, "enclosure_door": _PART,
           "conical_mounts": {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 80.0)},
           "rail_blocks": {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 80.0)}}
#: kinds whose effect follows the time: blocks, what lies between them, the pauses' length [min]
LONG = {"mean_radiant": ((5, 9), "pause", (30.0, 90.0)), "enclosure_door": ((4, 8), "pause", (5.0, 15.0))}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZM case: for :data:`LONG`, blocks with pauses between them (the radiant envelope's: a hall
    whose air drifts by 3-8 K over the session, logged); for :data:`PART_KG`, 3-5 blocks at least, each with a new part
    (the enclosure's: one per block, each loading a pause). No draws without a set-ZM kind."""
    kinds = set(physics) & set(EFFECTS_ZM)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(LONG)):
        (lo, hi), gap, pause = LONG[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind=gap, pause_min=pause)
    if "mean_radiant" in kinds:
        opts["air"] = {"drift_K": float(rng.choice([-1, 1]) * rng.uniform(3.0, 8.0)),
                       "cycle_K": float(rng.uniform(0.0, 0.5)), "period_min": float(rng.uniform(60, 180))}
    for k in sorted(kinds & set(PART_KG)):
        opts["blocks"] = max(opts["blocks"], int(rng.integers(3, 6)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    return opts


def probe_hook(physics, probe):
    """The target on the part on the mandrel or between the jaws (no draws)."""
    for k in physics:
        if k == "mandrel_rock":
            probe = probe + np.array([0.0, 0.0, zmb.MANDREL_TARGET_MM])
        elif k == "jaw_guide_tilt":
            probe = probe + np.array([0.0, 0.0, zmb.JAW_TARGET_MM])
    return probe


def payload_hook(physics, payload_com):
    """The part's centre of mass (tool frame) [mm]: 30-80 mm past the sleeve's centre, or 40-100 mm below the jaw
    guides (the drawn offset's length mapped onto that range, its direction kept across the tool axis at a fifth) (no
    draws)."""
    for k in physics:
        r = float(np.linalg.norm(payload_com))
        if k == "mandrel_rock":
            payload_com = np.array([0.2 * payload_com[0], 0.2 * payload_com[1], zmb.MANDREL_MM + 30.0 + 50.0 * r / 80])
        elif k == "jaw_guide_tilt":
            payload_com = np.array([0.2 * payload_com[0], 0.2 * payload_com[1], zmb.JAW_MM + 40.0 + 60.0 * r / 80])
    return payload_com
