"""Set Y: the registry of its new effect kinds, their families, the session options and the probe they need.

Physics in :mod:`effects_y_joint`, :mod:`effects_y_body`, :mod:`effects_y_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-Y kind, so sets A-X regenerate unchanged; the probe hook
draws none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_y_body as yb
from sim2real_indep import effects_y_joint as yj
from sim2real_indep import effects_y_thermal as yt

#: kind -> (draw, apply, true-structure features)
EFFECTS_Y = {
    "frost_load": (yj.frost_draw, yj.frost_apply, yj.frost_features),
    "output_brake": (yj.brake_draw, yj.brake_apply, yj.brake_features),
    "coupling_play": (yj.play_draw, yj.play_apply, yj.play_features),
    "squeeze_film": (yj.film_draw, yj.film_apply, yj.film_features),
    "pinion_runout": (yj.pinion_draw, yj.pinion_apply, yj.pinion_features),
    "torque_arm": (yj.arm_draw, yj.arm_apply, yj.arm_features),
    "press_walk": (yb.walk_draw, yb.walk_apply, yb.walk_features),
    "tyre_leak": (yb.leak_draw, yb.leak_apply, yb.leak_features),
    "foam_gripper": (yb.foam_draw, yb.foam_apply, yb.foam_features),
    "sheet_part": (yb.sheet_draw, yb.sheet_apply, yb.sheet_features),
    "vision_lamp": (yt.lamp_draw, yt.lamp_apply, yt.lamp_features),
    "cabinet_exhaust": (yt.exhaust_draw, yt.exhaust_apply, yt.exhaust_features),
}
#: families (context.FAMILY takes them over). frost_load, the gears twisted by the frost a cold-store arm gathers, and
#: output_brake, the outputs held in some blocks by safety brakes whose armatures give under the load, joint compliance;
#: coupling_play, the output encoders dragged across their couplings' play, and squeeze_film, the lost motion of axes 2
#: and 3 crossed slowly through stiff grease, backlash (errors that follow the last motion); pinion_runout, axis 1's
#: gauge pinion running eccentrically, and torque_arm, the output encoders turned by their own weight on their torque
#: arms, transmission (the joints' reading); press_walk, the base plate walking under a press's shocks, and tyre_leak,
#: the cart's leaking tyre, mount compliance (the robot's support); foam_gripper, a part on a foam vacuum pad, and
#: sheet_part, a thin panel bending under its own weight, link deflection (the end-of-arm structure carrying the
#: target); vision_lamp, the upper arm bowed by its lamps, and cabinet_exhaust, the pedestal bowed by the cabinet's
#: exhaust, thermal
FAMILY_Y = {"frost_load": "joint_compliance", "output_brake": "joint_compliance", "coupling_play": "backlash",
            "squeeze_film": "backlash", "pinion_runout": "transmission", "torque_arm": "transmission",
            "press_walk": "mount_compliance", "tyre_leak": "mount_compliance", "foam_gripper": "link_deflection",
            "sheet_part": "link_deflection", "vision_lamp": "thermal", "cabinet_exhaust": "thermal"}
#: measurement effects that need the tracker's frame (none in set Y)
AFTER_TRACKER: set = set()
#: kinds whose sessions have production (exercise) between their blocks: the blocks' range
PRODUCTION = {"press_walk": (4, 7), "cabinet_exhaust": (4, 8), "vision_lamp": (4, 7)}
#: kinds whose sessions have pauses between their blocks: the blocks' range and the pauses' range [min]
PAUSES = {"frost_load": ((4, 7), (40.0, 90.0)), "tyre_leak": ((4, 7), (20.0, 50.0)),
          "output_brake": ((3, 6), (5.0, 15.0))}
#: kinds that hold a part: a new part (the logged payload) for each block, its mass range per arm [kg]
PART_KG = {"foam_gripper": {"ur10": (1.5, 6.0), "kr16_like": (3.0, 12.0), "tool_changer": (10.0, 40.0)},
           "sheet_part": {"ur10": (1.0, 4.0), "kr16_like": (2.0, 8.0), "tool_changer": (5.0, 20.0)}}
#: the target's offset added by the end-of-arm structure of a kind (tool frame) [mm]
PROBE_OFFSET = {"foam_gripper": np.array([0.0, 0.0, yb.FOAM_MM]),
                "sheet_part": np.array([yb.SHEET_MM, 0.0, 0.0])}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-Y case: for :data:`PAUSES`, the blocks of its range with pauses between them; for
    :data:`PRODUCTION`, the blocks of its range with production (exercise) between them; for :data:`PART_KG`, 2-4
    blocks at least, each with a new part. No draws without a set-Y kind."""
    kinds = set(physics) & set(EFFECTS_Y)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(PAUSES)):
        (lo, hi), pause = PAUSES[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="pause", pause_min=pause)
    for k in sorted(kinds & set(PRODUCTION)):
        lo, hi = PRODUCTION[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="exercise")
    for k in sorted(kinds & set(PART_KG)):
        opts["blocks"] = max(opts["blocks"], int(rng.integers(2, 5)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    return opts


def probe_hook(physics, probe):
    """The target at the end of the case's end-of-arm structure (no draws)."""
    for k in physics:
        if k in PROBE_OFFSET:
            probe = probe + PROBE_OFFSET[k]
    return probe
