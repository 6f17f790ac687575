"""Set S: the registry of its new effect kinds, their families, the session options they need and the hooks that put
the target (and the part) on a profile frame's gripper module.

Physics in :mod:`effects_s_joint`, :mod:`effects_s_body`, :mod:`effects_s_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-S kind (the probe and payload hooks none at all), so
sets A-R regenerate unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_s_body as sb
from sim2real_indep import effects_s_joint as sj
from sim2real_indep import effects_s_thermal as st
from sim2real_indep.hardware import pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_S = {
    "float_pinion": (sj.pinion_draw, sj.pinion_apply, sj.pinion_features),
    "wall_boot": (sj.boot_draw, sj.boot_apply, sj.boot_features),
    "overshoot_lash": (sj.lash_draw, sj.lash_apply, sj.lash_features),
    "cogging": (sj.cog_draw, sj.cog_apply, sj.cog_features),
    "pot_loading": (sj.pot_draw, sj.pot_apply, sj.pot_features),
    "dowel_yaw": (sb.dowel_draw, sb.dowel_apply, sb.dowel_features),
    "twin_robot": (sb.twin_draw, sb.twin_apply, sb.twin_features),
    "mullins_mounts": (sb.mullins_draw, sb.mullins_apply, sb.mullins_features),
    "profile_frame": (sb.frame_draw, sb.frame_apply, sb.frame_features),
    "diaphragm": (sb.diaphragm_draw, sb.diaphragm_apply, sb.diaphragm_features),
    "oil_shrink": (st.oil_draw, st.oil_apply, st.oil_features),
    "wheel_growth": (st.wheel_draw, st.wheel_apply, st.wheel_features),
}
#: families (context.FAMILY takes them over). float_pinion, axis 2's gear let go by a sprung pinion that its teeth wedge
#: out of mesh, and wall_boot, the joints twisted by a wall bellows' spring rates, joint compliance; overshoot_lash, the
#: lost motion crossed back by the position loop's overshoot, and dowel_yaw, the base yawed across its dowels' clearance
#: by axis 1's reaction torque, backlash (errors that follow the last motion); cogging, the drives' cogging against a
#: proportional loop at standstill, and pot_loading, the boom cylinders' loaded potentiometric transducers, transmission
#: (a joint's error as a function of its own position); twin_robot, the shared table tilted by a twin's production
#: cycle, and mullins_mounts, the base on isolators softening past their largest load, mount compliance (the robot's
#: support); profile_frame, the target's profile-frame joint turning by its semi-rigid curve, and diaphragm, a tool on a
#: stiffening double-diaphragm flexure, link deflection (the end-of-arm structure carrying the target); oil_shrink, the
#: boom sinking as its trapped oil cools in the dwell, and wheel_growth, axis 1's measuring wheel and ring growing
#: apart with the hall's air, thermal
FAMILY_S = {"float_pinion": "joint_compliance", "wall_boot": "joint_compliance", "overshoot_lash": "backlash",
            "dowel_yaw": "backlash", "cogging": "transmission", "pot_loading": "transmission",
            "twin_robot": "mount_compliance", "mullins_mounts": "mount_compliance", "profile_frame": "link_deflection",
            "diaphragm": "link_deflection", "oil_shrink": "thermal", "wheel_growth": "thermal"}
#: measurement effects that need the tracker's frame (none in set S)
AFTER_TRACKER: set = set()
#: kinds whose sessions have several blocks: what happens between them, the pauses' length [min] and the blocks
BLOCKS = {"oil_shrink": ("exercise", (10.0, 30.0), (4, 8)), "wheel_growth": ("pause", (30.0, 90.0), (5, 9))}
#: kinds whose sessions change the payload between blocks (pick and place)
PICK_PLACE = {"mullins_mounts", "float_pinion"}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-S case: the blocks of :data:`BLOCKS` (production between the blocks for the trapped oil, a
    working day's pauses for the wheel, both mixed), a drifting hall air for the wheel (2-6 K over the session, an HVAC
    cycle of 0-1 K over 60-180 min) and pick and place for the isolators and the pinion."""
    kinds = set(physics) & set(EFFECTS_S)
    if not kinds:
        return opts
    opts = dict(opts)
    blocked = sorted(kinds & set(BLOCKS))
    for k in blocked:
        gap, pause, (lo, hi) = BLOCKS[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind=gap, pause_min=pause)
    if len(blocked) > 1:
        opts["gap_kind"] = "mixed"
    if "wheel_growth" in kinds:
        opts["air"] = {"drift_K": rng.choice([-1, 1]) * rng.uniform(2.0, 6.0), "cycle_K": rng.uniform(0.0, 1.0),
                       "period_min": rng.uniform(60, 180)}
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
    return opts


def _share(probe_mm):
    return (np.linalg.norm(probe_mm) - 5.0) / 95.0


def probe_hook(physics, probe_mm):
    """The target offset (3,) [mm] (no random numbers): on a profile frame's gripper module, 30 mm out on the tool axis
    and across it towards the drawn offset's direction, the length mapped onto 150-300 mm; unchanged otherwise."""
    probe_mm = np.asarray(probe_mm, float)
    if "profile_frame" in physics:
        lo, hi = sb.FRAME_MM
        e = probe_mm[:2] / np.linalg.norm(probe_mm[:2])
        return np.r_[(lo + (hi - lo) * _share(probe_mm)) * e, sb.PLATE_MM]
    return probe_mm


def payload_hook(physics, payload_com, probe_mm):
    """The part's centre of mass in the tool frame (no random numbers): in the profile frame's gripper module, at the
    target; unchanged otherwise."""
    return np.asarray(probe_mm, float).copy() if "profile_frame" in physics else payload_com
