"""Set K: the registry of its new effect kinds, their families, the session options they need and the hooks that
place the target and the payload at a gripper.

Physics in :mod:`effects_k_joint`, :mod:`effects_k_body`, :mod:`effects_k_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-K kind (and the probe and payload hooks none at
all), so sets A-J regenerate unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_k_body as kb
from sim2real_indep import effects_k_joint as kj
from sim2real_indep import effects_k_thermal as kt
from sim2real_indep.hardware import pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_K = {
    "vacuum_hose": (kj.vac_draw, kj.vac_apply, kj.vac_features),
    "rcc": (kb.rcc_draw, kb.rcc_apply, kb.rcc_features),
    "outrigger_soil": (kb.outrig_draw, kb.outrig_apply, kb.outrig_features),
    "bulkhead": (kb.bulk_draw, kb.bulk_apply, kb.bulk_features),
    "side_cylinder": (kb.cyl_draw, kb.cyl_apply, kb.cyl_features),
    "tele_rope": (kj.rope_draw, kj.rope_apply, kj.rope_features),
    "thermal_lash": (kt.lash_draw, kt.lash_apply, kt.lash_features),
    "ram_roll": (kj.roll_draw, kj.roll_apply, kj.roll_features),
    "cardan": (kj.cardan_draw, kj.cardan_apply, kj.cardan_features),
    "spline_twist": (kj.spline_draw, kj.spline_apply, kj.spline_features),
    "read_head": (kt.head_draw, kt.head_apply, kt.head_features),
    "comp_mismatch": (kt.comp_draw, kt.comp_apply, kt.comp_features),
}
#: families (context.FAMILY takes them over). vacuum_hose, a pull on the tool that twists the gears, and tele_rope, the
#: ropes holding the telescopic stage (its drive train), are joint compliance; rcc, the compliant device between flange
#: and gripper, is scored as link deflection (the end-of-arm structure carrying the target, as sets D's bracket, G's
#: target rod and J's tool plate); bulkhead, the arm's support bowed by the chamber's pressure, as mount compliance;
#: thermal_lash, lost motion whose width follows a housing's temperature, as backlash (the family whose model holds its
#: flank); ram_roll, the telescopic ram turning inside its key's clearance, as backlash; spline_twist, a wrist angle
#: off with the extension through its drive shaft's spline, as transmission; comp_mismatch, the residual of the
#: controller's thermal correction, as thermal
FAMILY_K = {"vacuum_hose": "joint_compliance", "tele_rope": "joint_compliance", "rcc": "link_deflection",
            "outrigger_soil": "mount_compliance", "bulkhead": "mount_compliance", "side_cylinder": "link_deflection",
            "thermal_lash": "backlash", "ram_roll": "backlash", "cardan": "transmission",
            "spline_twist": "transmission", "read_head": "thermal", "comp_mismatch": "thermal"}
#: measurement effects that need the tracker's frame: none in set K
AFTER_TRACKER: set = set()
#: drive-heated kinds: a cold start, production periods and pauses (servo off) between the blocks
WARM = {"thermal_lash", "read_head", "comp_mismatch"}
#: drive-heated kinds whose sessions have production periods between all blocks (no pauses: the housings warm)
EXERCISE = {"read_head"}
#: consolidating ground: pauses (the load held) and production periods between the blocks
CREEP = {"outrigger_soil"}
#: kinds whose sessions change the payload between blocks (pick and place with several loads)
PICK_PLACE = {"vacuum_hose", "rcc", "outrigger_soil", "tele_rope", "ram_roll", "side_cylinder"}
#: the gripper's reach along the tool axis [mm] for the RCC (the drawn offset's axial part mapped onto it)
GRIP_MM = (150.0, 250.0)
#: the cutter's centre off the wrist axis [mm] for the ram's roll (the drawn centre of mass mapped onto it)
CUTTER_MM = (250.0, 450.0)


def session_options(robot_key, physics, rng, opts):
    """The session of a set-K case: 5-8 blocks with production periods and pauses of 10-40 min (servo off) for the
    drive-heated kinds, from a cold start (production periods only for the read heads); 5-8 blocks with pauses of
    20-60 min (the load held) and production periods for the consolidating ground; pick and place with 2-4 loads
    (one of them none: the vacuum off) changed between 6-10 blocks for the load-driven kinds."""
    kinds = set(physics)
    if not kinds & set(EFFECTS_K):
        return opts
    opts = dict(opts)
    if kinds & WARM:
        opts.update(blocks=max(opts["blocks"], int(rng.integers(5, 9))), gap_kind="mixed", pause_min=(10.0, 40.0))
    if kinds & EXERCISE:
        opts.update(gap_kind="exercise")
    if kinds & CREEP:
        opts.update(blocks=max(opts["blocks"], int(rng.integers(5, 9))), gap_kind="mixed", pause_min=(20.0, 60.0))
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
    return opts


def probe_hook(physics, probe_mm):
    """The target offset (3,) [mm]: for the RCC, at the gripper's tip -- the drawn offset's part across the tool axis
    kept, its axial part (5-100 mm) mapped onto 150-250 mm beyond the flange (no random numbers); unchanged
    otherwise."""
    if "rcc" not in physics:
        return probe_mm
    n = np.linalg.norm(probe_mm)
    return np.array([probe_mm[0], probe_mm[1], GRIP_MM[0] + (GRIP_MM[1] - GRIP_MM[0]) * abs(probe_mm[2]) / n])


def payload_hook(physics, com_mm, probe_mm):
    """The payload's centre of mass (3,) [mm], tool frame: for the RCC, in the gripper's jaws (80 % of the way to the
    target plus a quarter of the drawn offset); for the ram's roll, a disc cutter gripped at its rim, its centre
    250-450 mm off the wrist axis (the drawn offset's direction across the tool axis, its length 0-80 mm mapped onto
    that range; first 150-300 mm: the roll torque of the set's case kept one sign, the bias of the wrist's centre of
    mass winning); unchanged otherwise (no random numbers)."""
    com = np.asarray(com_mm, float)
    if "rcc" in physics:
        return 0.8 * np.asarray(probe_mm, float) + 0.25 * com
    if "ram_roll" in physics:
        d = np.array([com[0], com[1], 0.0])
        d = d / np.linalg.norm(d) if np.linalg.norm(d) > 1e-9 else np.array([1.0, 0.0, 0.0])
        r = CUTTER_MM[0] + (CUTTER_MM[1] - CUTTER_MM[0]) * min(np.linalg.norm(com) / 80.0, 1.0)
        return r * d + [0.0, 0.0, com[2]]
    return com_mm
