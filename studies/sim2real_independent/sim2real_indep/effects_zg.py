"""Set ZG: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zg_joint`, :mod:`effects_zg_body`, :mod:`effects_zg_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-ZG kind, so sets A-ZF regenerate unchanged; the probe
hook draws none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zg_body as zgb
from sim2real_indep import effects_zg_joint as zgj
from sim2real_indep import effects_zg_thermal as zgt

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZG = {
    "gravcomp_payload": (zgj.gravcomp_draw, zgj.gravcomp_apply, zgj.gravcomp_features),
    "taut_harness": (zgj.harness_draw, zgj.harness_apply, zgj.harness_features),
    "tilt_flank": (zgj.tilt_draw, zgj.tilt_apply, zgj.tilt_features),
    "coast_flank": (zgj.coast_draw, zgj.coast_apply, zgj.coast_features),
    "chipped_pinion": (zgj.chip_draw, zgj.chip_apply, zgj.chip_features),
    "missing_pin": (zgj.pin_draw, zgj.pin_apply, zgj.pin_features),
    "settlement_tilt": (zgb.settle_draw, zgb.settle_apply, zgb.settle_features),
    "bolt_relaxation": (zgb.relax_draw, zgb.relax_apply, zgb.relax_features),
    "beam_column": (zgb.column_draw, zgb.column_apply, zgb.column_features),
    "leaf_boom": (zgb.leaf_draw, zgb.leaf_apply, zgb.leaf_features),
    "drying_film": (zgt.film_draw, zgt.film_apply, zgt.film_features),
    "rotary_union": (zgt.union_draw, zgt.union_apply, zgt.union_features),
}
#: families (context.FAMILY takes them over). gravcomp_payload, an impedance-controlled arm yielding to the part's
#: weight beyond its declared load, and taut_harness, axis 1 twisted by its supply bundle past the bundle's slack,
#: joint compliance; tilt_flank, axis 1's lost motion flanked by an inclined installation's gravity torque, and
#: coast_flank, the loaded axes' lost motion crossed by the link's inertia at a fast move's end, backlash;
#: chipped_pinion, axis 1's pinion with a chipped tooth, and missing_pin, axis 2's RV reducer with a broken ring pin,
#: transmission; settlement_tilt, the foundation settling unevenly in time, and bolt_relaxation, the base's anchor
#: bolts relaxing so that it tilts more under the moment, mount compliance; beam_column, a slender boom whose bending
#: the axial load amplifies, and leaf_boom, a flat-bar boom bending towards its weak axis, link deflection;
#: drying_film, the links held below the air by an evaporating film, and rotary_union, a bracket warmed by the seals of
#: a rotary union that axis 6 turns, thermal
FAMILY_ZG = {"gravcomp_payload": "joint_compliance", "taut_harness": "joint_compliance", "tilt_flank": "backlash",
             "coast_flank": "backlash", "chipped_pinion": "transmission", "missing_pin": "transmission",
             "settlement_tilt": "mount_compliance", "bolt_relaxation": "mount_compliance",
             "beam_column": "link_deflection", "leaf_boom": "link_deflection", "drying_film": "thermal",
             "rotary_union": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZG)
AFTER_TRACKER: set = set()
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"gravcomp_payload": {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 80.0)},
           "beam_column": {"ur10": (0.0, 8.0), "kr16_like": (0.0, 10.0), "tool_changer": (0.0, 10.0)}}
#: kinds whose effect follows the time: their sessions span hours, blocks with pauses [min]
LONG = {"settlement_tilt": ((4, 7), (20.0, 50.0)), "drying_film": ((4, 7), (10.0, 30.0)),
        "rotary_union": ((4, 7), (20.0, 50.0))}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZG case: for :data:`PART_KG`, 3-5 blocks at least, each with a new part; for :data:`LONG`,
    blocks with pauses that spread the session over hours. No draws without a set-ZG kind."""
    kinds = set(physics) & set(EFFECTS_ZG)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(PART_KG)):
        opts["blocks"] = max(opts["blocks"], int(rng.integers(3, 6)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    for k in sorted(kinds & set(LONG)):
        (lo, hi), pause = LONG[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="pause", pause_min=pause)
    return opts


def probe_hook(physics, probe):
    """The target at the tip of the case's tool boom or bracket (no draws)."""
    for k in physics:
        if k in ("beam_column", "leaf_boom"):
            probe = probe + np.array([zgb.BOOM_MM, 0.0, 0.0])
        elif k == "rotary_union":
            probe = probe + np.array([0.0, 0.0, zgt.BRACKET_MM])
    return probe
