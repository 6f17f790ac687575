"""Set F: the registry of its new effect kinds, their families, and the session options they need.

Physics in :mod:`effects_f_joint`, :mod:`effects_f_body`, :mod:`effects_f_thermal` (sources in their docstrings).
The hook consumes random numbers only when a case has a set-F kind, so sets A-E regenerate unchanged. Imports
nothing of tolalloc.
"""

from __future__ import annotations

from sim2real_indep import effects_f_body as fb
from sim2real_indep import effects_f_joint as fj
from sim2real_indep import effects_f_thermal as ft
from sim2real_indep.hardware import pick_place

#: kind -> (draw, apply, true-structure features)
EFFECTS_F = {
    "cable_balancer": (fj.balancer_draw, fj.balancer_apply, fj.balancer_features),
    "lever_stiffness": (fj.leverstiff_draw, fj.leverstiff_apply, fj.leverstiff_features),
    "plate_yield": (fb.yield_draw, fb.yield_apply, fb.yield_features),
    "uplift": (fb.uplift_draw, fb.uplift_apply, fb.uplift_features),
    "eccentric_axis": (fb.ecc_draw, fb.ecc_apply, fb.ecc_features),
    "weld_crack": (fb.crack_draw, fb.crack_apply, fb.crack_features),
    "wear_zones": (fj.wear_draw, fj.wear_apply, fj.wear_features),
    "brake_hub": (fj.brake_draw, fj.brake_apply, fj.brake_features),
    "tape_scale": (fj.tape_draw, fj.tape_apply, fj.tape_features),
    "lever_drive": (fj.leverpin_draw, fj.leverpin_apply, fj.leverpin_features),
    "day_night": (ft.daynight_draw, ft.daynight_apply, ft.daynight_features),
    "screw_growth": (ft.screw_draw, ft.screw_apply, ft.screw_features),
}
#: a day and a night: long pauses between the blocks, the hall's air cycling over 24 h
DAY = {"day_night"}
#: screw friction heat: production periods (exercise) between the blocks
DUTY = {"screw_growth"}
#: kinds whose sessions change the payload between blocks (pick and place with several loads)
PICK_PLACE = {"cable_balancer", "lever_stiffness", "plate_yield", "uplift", "eccentric_axis", "weld_crack",
              "wear_zones", "brake_hub"}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-F case: a day and a night of 6-10 blocks with pauses of 60-150 min, the air cycling by
    +-1.5-3.5 K over 24 h (drift +-0.5 K) for the slab; 5-9 blocks with production periods (exercise, 10-30 min)
    between them for the screws; pick and place with 2-4 loads changed between 6-10 blocks for the gravity kinds."""
    kinds = set(physics)
    if not kinds & set(EFFECTS_F):
        return opts
    opts = dict(opts)
    if kinds & DAY:
        opts.update(blocks=int(rng.integers(6, 11)), gap_kind="pause", pause_min=(60.0, 150.0),
                    air={"drift_K": rng.uniform(-0.5, 0.5), "cycle_K": rng.uniform(1.5, 3.5), "period_min": 1440.0})
    if kinds & DUTY:
        opts.update(blocks=int(rng.integers(5, 10)), gap_kind="exercise")
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
    return opts
