"""Set R: the registry of its new effect kinds, their families, the session options they need and the hook that puts
the target on a bracket or a swing-away tool.

Physics in :mod:`effects_r_joint`, :mod:`effects_r_body`, :mod:`effects_r_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-R kind (and the probe hook none at all), so sets
A-Q regenerate unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_r_body as rb
from sim2real_indep import effects_r_joint as rj
from sim2real_indep import effects_r_thermal as rt

#: kind -> (draw, apply, true-structure features)
EFFECTS_R = {
    "line_pressure": (rj.line_draw, rj.line_apply, rj.line_features),
    "slide_shift": (rj.slide_draw, rj.slide_apply, rj.slide_features),
    "stick_band": (rj.band_draw, rj.band_apply, rj.band_features),
    "floor_cable": (rj.cable_draw, rj.cable_apply, rj.cable_features),
    "rehoming": (rj.home_draw, rj.home_apply, rj.home_features),
    "belt_splice": (rj.splice_draw, rj.splice_apply, rj.splice_features),
    "forklift_slab": (rb.slab_draw, rb.slab_apply, rb.slab_features),
    "sprayer_tank": (rb.tank_draw, rb.tank_apply, rb.tank_features),
    "web_buckling": (rb.web_draw, rb.web_apply, rb.web_features),
    "swing_mount": (rb.swing_draw, rb.swing_apply, rb.swing_features),
    "heated_hose": (rt.hose_draw, rt.hose_apply, rt.hose_features),
    "welding_cable": (rt.weld_draw, rt.weld_apply, rt.weld_features),
}
#: families (context.FAMILY takes them over). line_pressure, axis 2's gear twisted by a line-fed pneumatic balancer's
#: force swinging with the compressor's cycle, and slide_shift, the gears twisted by a tool slide's carriage standing
#: out
#: or in, joint compliance; stick_band, axes held by a proportional loop short of their target by their friction on the
#: approach's side, and floor_cable, the joints twisted by a floor-dragged cable's friction only when it was last pulled
#: out, backlash (errors that follow the last motion); rehoming, the incremental encoders' zero set anew at each homing,
#: and belt_splice, a belt splice's pitch error as a function of axis 5's angle, transmission (the joints' reading and
#: drive); forklift_slab, the base on a slab dished by a parked truck, and sprayer_tank, the base on a sprung chassis
#: under its draining tank, mount compliance (the robot's support); web_buckling, the target's bracket buckling in
#: shear,
#: and swing_mount, the target's tool swung off its stop by its weight, link deflection (the end-of-arm structure
#: carrying the target); heated_hose and welding_cable, links bowed by a heated hose and a welding cable, thermal
FAMILY_R = {"line_pressure": "joint_compliance", "slide_shift": "joint_compliance", "stick_band": "backlash",
            "floor_cable": "backlash", "rehoming": "transmission", "belt_splice": "transmission",
            "forklift_slab": "mount_compliance", "sprayer_tank": "mount_compliance", "web_buckling": "link_deflection",
            "swing_mount": "link_deflection", "heated_hose": "thermal", "welding_cable": "thermal"}
#: measurement effects that need the tracker's frame (none in set R)
AFTER_TRACKER: set = set()
#: kinds whose sessions have several blocks: what happens between them, the pauses' length [min] and the blocks
BLOCKS = {"rehoming": ("pause", (5.0, 20.0), (3, 6)), "sprayer_tank": ("pause", (5.0, 15.0), (3, 6)),
          "welding_cable": ("exercise", (10.0, 30.0), (4, 8)), "heated_hose": ("pause", (10.0, 30.0), (2, 4))}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-R case: the blocks of :data:`BLOCKS` (the first kind in sorted order sets the gap's
    kind)."""
    kinds = set(physics) & set(EFFECTS_R)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(BLOCKS), reverse=True):
        gap, pause, (lo, hi) = BLOCKS[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind=gap, pause_min=pause)
    return opts


def _share(probe_mm):
    return (np.linalg.norm(probe_mm) - 5.0) / 95.0


def probe_hook(physics, probe_mm):
    """The target offset (3,) [mm] (no random numbers): at a sheet-metal bracket's tip, 30 mm out on the tool axis and
    across it towards the drawn offset's direction, the length mapped onto 120-220 mm; on a swing-away tool, the drawn
    offset's direction with its length mapped onto 150-250 mm; unchanged otherwise."""
    probe_mm = np.asarray(probe_mm, float)
    if "web_buckling" in physics:
        lo, hi = rb.BRACKET_MM
        e = probe_mm[:2] / np.linalg.norm(probe_mm[:2])
        return np.r_[(lo + (hi - lo) * _share(probe_mm)) * e, 30.0]
    if "swing_mount" in physics:
        lo, hi = rb.SWING_MM
        return probe_mm / np.linalg.norm(probe_mm) * (lo + (hi - lo) * _share(probe_mm))
    return probe_mm
