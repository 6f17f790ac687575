"""Set ZC: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zc_joint`, :mod:`effects_zc_body`, :mod:`effects_zc_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-ZC kind, so sets A-ZB regenerate unchanged; the probe
and payload hooks draw none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zc_body as zcb
from sim2real_indep import effects_zc_joint as zcj
from sim2real_indep import effects_zc_thermal as zct

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZC = {
    "spool_tension": (zcj.spool_draw, zcj.spool_apply, zcj.spool_features),
    "coupled_wrist": (zcj.coupled_draw, zcj.coupled_apply, zcj.coupled_features),
    "bayonet_play": (zcj.bayonet_draw, zcj.bayonet_apply, zcj.bayonet_features),
    "air_preload": (zcj.preload_draw, zcj.preload_apply, zcj.preload_features),
    "swapped_bits": (zcj.swap_draw, zcj.swap_apply, zcj.swap_features),
    "multistart_worm": (zcj.worm_draw, zcj.worm_apply, zcj.worm_features),
    "hexapod_mount": (zcb.hexapod_draw, zcb.hexapod_apply, zcb.hexapod_features),
    "counterweight_base": (zcb.counterweight_draw, zcb.counterweight_apply, zcb.counterweight_features),
    "rubber_bush": (zcb.bush_draw, zcb.bush_apply, zcb.bush_features),
    "floor_hose": (zcb.floor_hose_draw, zcb.floor_hose_apply, zcb.floor_hose_features),
    "cure_exotherm": (zct.cure_draw, zct.cure_apply, zct.cure_features),
    "link_convection": (zct.convection_draw, zct.convection_apply, zct.convection_features),
}
#: families (context.FAMILY takes them over). spool_tension, the joints yielding to a dancer-tensioned wire pulled
#: towards its guide eye, and coupled_wrist, a wrist whose drive trains' compliances act in motor coordinates, joint
#: compliance; bayonet_play, a tool turned across its bayonet's play by its hose's drag, and air_preload, axis 1's gear
#: play preloaded by a cylinder only while the air is on, backlash (lost motion in a clearance, errors that follow the
#: last motion); swapped_bits, output encoders' words logged with two data lines crossed, and multistart_worm, a worm
#: stage's start-to-start index error, transmission (the joints' reading and drive); hexapod_mount, the arm on a
#: six-strut pedestal whose struts are softer in tension, and counterweight_base, a carrier whose counterweight cancels
#: the moment only within its stroke, mount compliance (the robot's support); rubber_bush, a tool boom hinged on a
#: progressive rubber bush, and floor_hose, a tool boom bent by the hose it lifts off the floor, link deflection (the
#: end-of-arm structure carrying the target); cure_exotherm, a bonded part warmed by its adhesive's cure, and
#: link_convection, the forearm bowed by the air its motors stratify in it, thermal
FAMILY_ZC = {"spool_tension": "joint_compliance", "coupled_wrist": "joint_compliance", "bayonet_play": "backlash",
             "air_preload": "backlash", "swapped_bits": "transmission", "multistart_worm": "transmission",
             "hexapod_mount": "mount_compliance", "counterweight_base": "mount_compliance",
             "rubber_bush": "link_deflection", "floor_hose": "link_deflection", "cure_exotherm": "thermal",
             "link_convection": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZC)
AFTER_TRACKER: set = set()
#: kinds whose sessions have pauses between their blocks: blocks' and pauses' ranges [min] (a new roll, the air
#: switched, a new bonded part)
PAUSES = {"spool_tension": ((3, 6), (3.0, 10.0)), "air_preload": ((3, 6), (5.0, 15.0)),
          "cure_exotherm": ((3, 6), (2.0, 6.0))}
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"coupled_wrist": {"ur10": (3.0, 9.0), "kr16_like": (5.0, 15.0), "tool_changer": (20.0, 70.0)},
           "counterweight_base": {"ur10": (2.0, 10.0), "kr16_like": (3.0, 16.0), "tool_changer": (20.0, 80.0)},
           "rubber_bush": {"ur10": (0.5, 3.0), "kr16_like": (1.0, 5.0), "tool_changer": (2.0, 10.0)},
           "cure_exotherm": {"ur10": (1.0, 4.0), "kr16_like": (1.0, 6.0), "tool_changer": (2.0, 10.0)}}
#: the target's offset added by the end-of-arm structure of a kind (tool frame) [mm]
PROBE_OFFSET = {"bayonet_play": np.array([80.0, 0.0, 150.0]), "floor_hose": np.array([zcb.HOSE_BOOM_MM, 0.0, 0.0]),
                "rubber_bush": np.array([zcb.BUSH_BOOM_MM, 0.0, 40.0]),
                "cure_exotherm": np.array([0.0, 0.0, zct.PART_MM])}
#: the payload's centre of mass a kind puts (tool frame) [mm]: the part held off the wrist's axis, at the boom's tip,
#: the bonded part
PAYLOAD_COM = {"coupled_wrist": np.array([80.0, 0.0, 120.0]), "rubber_bush": np.array([zcb.BUSH_BOOM_MM, 0.0, 20.0]),
               "cure_exotherm": np.array([0.0, 30.0, 150.0])}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZC case: for :data:`PAUSES`, blocks of its range with pauses between them; for
    :data:`PART_KG`, 3-5 blocks at least, each with a new part. No draws without a set-ZC kind."""
    kinds = set(physics) & set(EFFECTS_ZC)
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
