"""Set ZB: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zb_joint`, :mod:`effects_zb_body`, :mod:`effects_zb_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-ZB kind, so sets A-ZA regenerate unchanged; the probe
and payload hooks draw none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zb_body as zbb
from sim2real_indep import effects_zb_joint as zbj
from sim2real_indep import effects_zb_thermal as zbt

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZB = {
    "impedance_preset": (zbj.impedance_draw, zbj.impedance_apply, zbj.impedance_features),
    "hose_wrap": (zbj.hose_draw, zbj.hose_apply, zbj.hose_features),
    "pawl_notch": (zbj.pawl_draw, zbj.pawl_apply, zbj.pawl_features),
    "reversal_pulse": (zbj.pulse_draw, zbj.pulse_apply, zbj.pulse_features),
    "nonius_slip": (zbj.nonius_draw, zbj.nonius_apply, zbj.nonius_features),
    "fieldbus_rounding": (zbj.fieldbus_draw, zbj.fieldbus_apply, zbj.fieldbus_features),
    "mecanum_base": (zbb.mecanum_draw, zbb.mecanum_apply, zbb.mecanum_features),
    "grout_void": (zbb.void_draw, zbb.void_apply, zbb.void_features),
    "insulating_flange": (zbb.flange_draw, zbb.flange_apply, zbb.flange_features),
    "stay_cable": (zbb.stay_draw, zbb.stay_apply, zbb.stay_features),
    "air_knife": (zbt.knife_draw, zbt.knife_apply, zbt.knife_features),
    "sonotrode": (zbt.horn_draw, zbt.horn_apply, zbt.horn_features),
}
#: families (context.FAMILY takes them over). impedance_preset, a torque-controlled arm's joint-impedance stiffness set
#: per block, and hose_wrap, the joints yielding to a hose wrapped round the wrist by axis 6, joint compliance;
#: pawl_notch, gravity-loaded axes settling onto the next notch of a positive-locking brake, and reversal_pulse, a
#: friction-compensation pulse left over after a reversal, backlash (lost motion in a clearance, errors that follow
#: the last motion); nonius_slip, a two-track absolute encoder decoding the wrong fine period in a window, and
#: fieldbus_rounding, joint targets sent as integers of 0.01 deg, transmission (the joints' reading and command);
#: mecanum_base, an AMR's mecanum wheels' stiffness changing at each docking, and grout_void, a base plate over a grout
#: void under one edge, mount compliance (the robot's support); insulating_flange, a torch turning on its insulating
#: flange, and stay_cable, a tool boom on a sagging stay cable, link deflection (the end-of-arm structure carrying the
#: target); air_knife, the forearm heated when axis 1 turns it into a hot air curtain, and sonotrode, an ultrasonic
#: welding stack warming in the production, thermal
FAMILY_ZB = {"impedance_preset": "joint_compliance", "hose_wrap": "joint_compliance", "pawl_notch": "backlash",
             "reversal_pulse": "backlash", "nonius_slip": "transmission", "fieldbus_rounding": "transmission",
             "mecanum_base": "mount_compliance", "grout_void": "mount_compliance",
             "insulating_flange": "link_deflection", "stay_cable": "link_deflection", "air_knife": "thermal",
             "sonotrode": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZB)
AFTER_TRACKER: set = set()
#: kinds whose sessions have pauses between their blocks (the AMR leaves and re-docks): blocks' and pauses' ranges
PAUSES = {"mecanum_base": ((3, 6), (5.0, 15.0))}
#: kinds whose sessions have production (exercise) between their blocks: the blocks' range
PRODUCTION = {"sonotrode": (3, 6)}
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"impedance_preset": {"ur10": (2.0, 9.0), "kr16_like": (3.0, 14.0), "tool_changer": (20.0, 70.0)},
           "stay_cable": {"ur10": (0.5, 3.0), "kr16_like": (1.0, 5.0), "tool_changer": (2.0, 10.0)}}
#: kinds whose tool is the logged payload, one mass for the session [kg] (the torch)
TOOL_KG = {"insulating_flange": (3.0, 8.0)}
#: the target's offset added by the end-of-arm structure of a kind (tool frame) [mm]
PROBE_OFFSET = {"insulating_flange": zbb.TORCH_MM, "stay_cable": np.array([zbb.BOOM_MM, 0.0, -40.0]),
                "sonotrode": np.array([0.0, 0.0, zbt.HORN_MM])}
#: the payload's centre of mass a kind puts (tool frame) [mm]: the torch's, the part at the boom's tip
PAYLOAD_COM = {"insulating_flange": zbb.TORCH_COM_MM, "stay_cable": np.array([zbb.BOOM_MM, 0.0, -60.0])}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZB case: for :data:`PAUSES`, blocks of its range with pauses between them; for
    :data:`PRODUCTION`, blocks with production between them; for :data:`PART_KG`, 3-5 blocks at least, each with a new
    part; for :data:`TOOL_KG`, the tool's mass as the payload. No draws without a set-ZB kind."""
    kinds = set(physics) & set(EFFECTS_ZB)
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
        opts["blocks"] = max(opts["blocks"], int(rng.integers(3, 6)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    for k in sorted(kinds & set(TOOL_KG)):
        opts["payload_steps"] = (float(np.round(rng.uniform(*TOOL_KG[k]), 2)),)
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
