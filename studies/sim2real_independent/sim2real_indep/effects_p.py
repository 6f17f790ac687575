"""Set P: the registry of its new effect kinds, their families, the session options they need and the hook that puts
the target on a changed tool.

Physics in :mod:`effects_p_joint`, :mod:`effects_p_body`, :mod:`effects_p_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-P kind (and the probe hook none at all), so sets
A-O regenerate unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_p_body as pb
from sim2real_indep import effects_p_joint as pj
from sim2real_indep import effects_p_thermal as pt
from sim2real_indep.hardware import PAYLOAD_MAX_KG, pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_P = {
    "mag_coupling": (pj.coupling_draw, pj.coupling_apply, pj.coupling_features),
    "belt_slack": (pj.belt_draw, pj.belt_apply, pj.belt_features),
    "seal_relax": (pj.seal_draw, pj.seal_apply, pj.seal_features),
    "quick_change": (pb.qc_draw, pb.qc_apply, pb.qc_features),
    "pole_pitch": (pj.pole_draw, pj.pole_apply, pj.pole_features),
    "stray_field": (pj.stray_draw, pj.stray_apply, pj.stray_features),
    "vacuum_feet": (pb.vac_draw, pb.vac_apply, pb.vac_features),
    "platen_clamp": (pb.platen_draw, pb.platen_apply, pb.platen_features),
    "vacuum_plate": (pb.vplate_draw, pb.vplate_apply, pb.vplate_features),
    "hose_lance": (pb.lance_draw, pb.lance_apply, pb.lance_features),
    "jacket_cycle": (pt.jacket_draw, pt.jacket_apply, pt.jacket_features),
    "charging_heat": (pt.charge_draw, pt.charge_apply, pt.charge_features),
}
#: families (context.FAMILY takes them over). mag_coupling, the main axes' gear inputs lagging their motors across
#: magnetic couplings, and belt_slack, a wrist axis' belt stage softening as its slack span goes slack, joint
#: compliance (twist under the joints' loads); seal_relax, the seals' relaxing wind-up against the last motion, and
#: quick_change, the tool re-seated in its locating pins' clearance at each change, backlash (lost motion in a
#: clearance or a friction-held wind-up); pole_pitch, a magnetised ring's accumulated pitch errors, and stray_field, a
#: magnetic encoder's reading turned by the next axis' brake magnet, transmission (a joint's error as a function of the
#: joints' angles); vacuum_feet, the portable arm's vacuum-held pads, and platen_clamp, the machine platen it sits on,
#: mount compliance (the robot's support); vacuum_plate, a vacuum gripper's face plate bowed in while it holds a part,
#: and hose_lance, a dispensing lance bent by its supply hose, link deflection (the end-of-arm structure carrying the
#: target); jacket_cycle, the links following a jacket cooler's on-off cycle, and
#: charging_heat, an AMR's deck bowed by its charging battery, thermal
FAMILY_P = {"mag_coupling": "joint_compliance", "belt_slack": "joint_compliance", "seal_relax": "backlash",
            "quick_change": "backlash", "pole_pitch": "transmission", "stray_field": "transmission",
            "vacuum_feet": "mount_compliance", "platen_clamp": "mount_compliance", "vacuum_plate": "link_deflection",
            "hose_lance": "link_deflection", "jacket_cycle": "thermal",
            "charging_heat": "thermal"}
#: measurement effects that need the tracker's frame (none in set P)
AFTER_TRACKER: set = set()
#: kinds whose sessions have several blocks: what happens between them, the pauses' length [min] and the blocks
BLOCKS = {"quick_change": ("pause", (1.0, 3.0), (4, 8)), "charging_heat": ("pause", (10.0, 25.0), (3, 6))}
#: kinds whose sessions change the payload between blocks (pick and place, one load none)
PICK_PLACE = {"mag_coupling", "belt_slack", "vacuum_feet", "vacuum_plate"}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-P case: 4-7 blocks separated by pauses of 1-3 min (the tool changed, each tool its own
    weight) or 3-5 blocks by pauses of 10-25 min (the AMR charging); pick and place with 2-4 loads changed between 6-10
    blocks, the first block empty if the draw left none."""
    kinds = set(physics) & set(EFFECTS_P)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(BLOCKS)):
        gap, pause, (lo, hi) = BLOCKS[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind=gap, pause_min=pause)
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
        steps = list(opts["payload_steps"])
        if min(steps) > 0:                                   # held and empty blocks (no draws)
            steps[0] = 0.0
        opts["payload_steps"] = tuple(steps)
    if "quick_change" in kinds:                              # a tool of its own weight in every block
        opts["payload_steps"] = tuple(np.round(rng.uniform(0.1, 0.6, opts["blocks"]) * PAYLOAD_MAX_KG[robot_key], 1))
    return opts


def _share(probe_mm):
    return (np.linalg.norm(probe_mm) - 5.0) / 95.0


def probe_hook(physics, probe_mm, robot_key):
    """The target offset (3,) [mm] (no random numbers): at a lance's nozzle, on the tool axis at the lance's length (the
    drawn offset's length, 5-100 mm, mapped onto 250-400 mm); on a vacuum plate's face, the drawn offset's direction
    across the tool axis within half the plate's smallest radius, the face 60-120 mm out by the same length; on a
    changed tool, the drawn offset's direction with its length mapped onto the tool's 120-250 mm; unchanged
    otherwise."""
    probe_mm = np.asarray(probe_mm, float)
    if "hose_lance" in physics and robot_key in pb.LANCE_ARMS:
        lo, hi = pb.LANCE_MM
        return np.array([0.0, 0.0, lo + (hi - lo) * _share(probe_mm)])
    if "vacuum_plate" in physics:
        lo, hi = pb.VPLATE_FACE_MM
        across = probe_mm[:2] / np.linalg.norm(probe_mm) * 0.5 * pb.VPLATE_R_MM[0]
        return np.r_[across, lo + (hi - lo) * _share(probe_mm)]
    if "quick_change" in physics:
        lo, hi = pb.QC_TOOL_MM
        return probe_mm / np.linalg.norm(probe_mm) * (lo + (hi - lo) * _share(probe_mm))
    return probe_mm
