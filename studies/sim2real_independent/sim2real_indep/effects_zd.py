"""Set ZD: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zd_joint`, :mod:`effects_zd_body`, :mod:`effects_zd_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-ZD kind, so sets A-ZC regenerate unchanged; the probe
and payload hooks draw none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zd_body as zdb
from sim2real_indep import effects_zd_joint as zdj
from sim2real_indep import effects_zd_thermal as zdt

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZD = {
    "soft_float": (zdj.soft_float_draw, zdj.soft_float_apply, zdj.soft_float_features),
    "torque_crosstalk": (zdj.crosstalk_draw, zdj.crosstalk_apply, zdj.crosstalk_features),
    "floating_sun": (zdj.sun_draw, zdj.sun_apply, zdj.sun_features),
    "spline_drag": (zdj.spline_draw, zdj.spline_apply, zdj.spline_features),
    "readhead_dropout": (zdj.dropout_draw, zdj.dropout_apply, zdj.dropout_features),
    "range_shift": (zdj.range_draw, zdj.range_apply, zdj.range_features),
    "levelling_valves": (zdb.valves_draw, zdb.valves_apply, zdb.valves_features),
    "scissor_lift": (zdb.scissor_draw, zdb.scissor_apply, zdb.scissor_features),
    "curing_bond": (zdb.bond_draw, zdb.bond_apply, zdb.bond_features),
    "drive_tendons": (zdb.tendon_draw, zdb.tendon_apply, zdb.tendon_features),
    "bake_booth": (zdt.booth_draw, zdt.booth_apply, zdt.booth_features),
    "gun_warmup": (zdt.gun_draw, zdt.gun_apply, zdt.gun_features),
}
#: families (context.FAMILY takes them over). soft_float, a Cartesian soft-float compliance yielding to the tool's and
#: part's weight in the tool frame, and torque_crosstalk, joint torque sensors' bending-moment crosstalk in a
#: torque-controlled arm, joint compliance; floating_sun, a planetary stage's floating-sun play taken up by the load, and
#: spline_drag, tool_changer's wrist play whose flank the telescope's stroke chooses, backlash (lost motion in a
#: clearance, errors that follow the last motion); readhead_dropout, a diametric read-head pair whose averaging lapses
#: in some blocks, and range_shift, a range-change gearbox's rounded low-range ratio, transmission (the joints' reading
#: and drive); levelling_valves, air mounts re-levelled by valves with a dead band, and scissor_lift, a scissor lift
#: table heaved by its cylinder's oil column, mount compliance (the robot's support); curing_bond, a tool boom whose root
#: bond stiffens as it cures, and drive_tendons, the forearm bent by the wrist's drive tendons, link deflection (the
#: arm's and the end-of-arm structure carrying the target); bake_booth, the arm in a booth whose unlogged air follows its
#: flash-off schedule, and gun_warmup, a tool bracket warmed by a hot-melt gun's warm-up, thermal
FAMILY_ZD = {"soft_float": "joint_compliance", "torque_crosstalk": "joint_compliance", "floating_sun": "backlash",
             "spline_drag": "backlash", "readhead_dropout": "transmission", "range_shift": "transmission",
             "levelling_valves": "mount_compliance", "scissor_lift": "mount_compliance",
             "curing_bond": "link_deflection", "drive_tendons": "link_deflection", "bake_booth": "thermal",
             "gun_warmup": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZD)
AFTER_TRACKER: set = set()
#: kinds whose sessions have pauses between their blocks: blocks' and pauses' ranges [min] (a head's window misted, the
#: gearbox's range shifted, the booth's mode switched)
PAUSES = {"readhead_dropout": ((3, 6), (2.0, 10.0)), "range_shift": ((3, 6), (3.0, 10.0)),
          "bake_booth": ((3, 6), (5.0, 15.0))}
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"soft_float": {"ur10": (1.0, 8.0), "kr16_like": (2.0, 14.0), "tool_changer": (10.0, 70.0)},
           "torque_crosstalk": {"ur10": (1.0, 8.0), "kr16_like": (2.0, 14.0), "tool_changer": (10.0, 60.0)},
           "scissor_lift": {"ur10": (1.0, 10.0), "kr16_like": (2.0, 16.0), "tool_changer": (10.0, 80.0)},
           "drive_tendons": {"ur10": (1.0, 8.0), "kr16_like": (2.0, 14.0), "tool_changer": (10.0, 60.0)}}
#: the target's offset added by the end-of-arm structure of a kind (tool frame) [mm]: the bonded boom's tip, the nozzle
PROBE_OFFSET = {"curing_bond": np.array([zdb.BOND_BOOM_MM, 0.0, 0.0]), "gun_warmup": np.array([0.0, 0.0, zdt.GUN_MM])}
#: the payload's centre of mass a kind puts (tool frame) [mm]: the part held off the wrist's axis
PAYLOAD_COM = {"drive_tendons": np.array([60.0, 0.0, 150.0])}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZD case: for :data:`PAUSES`, blocks of its range with pauses between them; for
    :data:`PART_KG`, 3-5 blocks at least, each with a new part. No draws without a set-ZD kind."""
    kinds = set(physics) & set(EFFECTS_ZD)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(PAUSES)):
        (lo, hi), pause = PAUSES[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="pause", pause_min=pause)
    for k in sorted(kinds & set(PART_KG)):
        opts["blocks"] = max(opts["blocks"], int(rng.integers(3, 6)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    return opts


def probe_hook(physics, probe):
    """The target at the end of the case's end-of-arm structure (no draws)."""
    for k in physics:
        if k in PROBE_OFFSET:
            probe = probe + PROBE_OFFSET[k]
    return probe


def payload_hook(physics, payload_com):
    """The payload's centre of mass where the case's tool or part puts it (no draws)."""
    for k in physics:
        if k in PAYLOAD_COM:
            payload_com = np.array(PAYLOAD_COM[k], float)
    return payload_com
