"""Set ZN: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zn_joint`, :mod:`effects_zn_body`, :mod:`effects_zn_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-ZN kind, so sets A-ZM regenerate unchanged; the
probe and payload hooks draw none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zn_body as znb
from sim2real_indep import effects_zn_joint as znj
from sim2real_indep import effects_zn_thermal as znt

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZN = {
    "hygro_gear": (znj.hygro_draw, znj.hygro_apply, znj.hygro_features),
    "payload_estimator": (znj.estimator_draw, znj.estimator_apply, znj.estimator_features),
    "load_holding_valve": (znj.valve_draw, znj.valve_apply, znj.valve_features),
    "roll_endplay": (znj.endplay_draw, znj.endplay_apply, znj.endplay_features),
    "rope_lay": (znj.rope_draw, znj.rope_apply, znj.rope_features),
    "magnetostrictive_rod": (znj.rod_draw, znj.rod_apply, znj.rod_features),
    "wire_rope_isolators": (znb.wire_draw, znb.wire_apply, znb.wire_features),
    "focalised_mounts": (znb.focal_draw, znb.focal_apply, znb.focal_features),
    "dovetail_gib": (znb.dovetail_draw, znb.dovetail_apply, znb.dovetail_features),
    "bellows_coupling": (znb.bellows_draw, znb.bellows_apply, znb.bellows_features),
    "radiant_tube_heater": (znt.radiant_draw, znt.radiant_apply, znt.radiant_features),
    "dragging_brake": (znt.brake_draw, znt.brake_apply, znt.brake_features),
}
#: families (context.FAMILY takes them over). hygro_gear, polymer wrist gears softened by the water they take up after
#: a washdown, and payload_estimator, a cobot's on-line payload identification lagging each part change, joint
#: compliance; load_holding_valve, a hydraulic boom dropping as its holding valves close after a lowering move, and
#: roll_endplay, a roll bearing's end play crossed by the axial weight, backlash (errors that follow the last motion or
#: the load's side across a clearance); rope_lay, a capstan stage's rope-lay waviness, and magnetostrictive_rod, the
#: telescopic stage's magnetostrictive sensor, transmission (the joints' drive and reading); wire_rope_isolators and
#: focalised_mounts, mount compliance; dovetail_gib, a tool-side dovetail slide, and bellows_coupling, a tool on a
#: bellows coupling, link deflection (the end-of-arm structure carrying the target); radiant_tube_heater, tubes bowed by
#: the roof's radiant heaters, and dragging_brake, axis 2 warmed by its dragging brake, thermal
FAMILY_ZN = {"hygro_gear": "joint_compliance", "payload_estimator": "joint_compliance",
             "load_holding_valve": "backlash", "roll_endplay": "backlash", "rope_lay": "transmission",
             "magnetostrictive_rod": "transmission", "wire_rope_isolators": "mount_compliance",
             "focalised_mounts": "mount_compliance", "dovetail_gib": "link_deflection",
             "bellows_coupling": "link_deflection", "radiant_tube_heater": "thermal", "dragging_brake": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZN)
AFTER_TRACKER: set = set()
_PART = {"ur10": (1.0, 8.0), "kr16_like": (2.0, 14.0), "tool_changer": (10.0, 60.0)}
_RATED = {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 80.0)}
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"payload_estimator": _PART, "dovetail_gib": _PART, "bellows_coupling": _PART,
           "wire_rope_isolators": _RATED, "focalised_mounts": _RATED}
#: kinds whose effect follows the time: blocks, what lies between them, the pauses' length [min]
LONG = {"hygro_gear": ((4, 7), "pause", (15.0, 45.0)), "radiant_tube_heater": ((5, 9), "pause", (10.0, 30.0)),
        "dragging_brake": ((4, 7), "exercise", (10.0, 40.0))}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZN case: for :data:`LONG`, blocks with pauses (or production) between them (the radiant
    heaters': a hall air cycling by 0.3-0.8 K over 20-40 min, logged); for :data:`PART_KG`, 3-5 blocks at least, each
    with a new part. No draws without a set-ZN kind."""
    kinds = set(physics) & set(EFFECTS_ZN)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(LONG)):
        (lo, hi), gap, pause = LONG[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind=gap, pause_min=pause)
    if "radiant_tube_heater" in kinds:
        opts["air"] = {"drift_K": 0.0, "cycle_K": float(rng.uniform(0.3, 0.8)),
                       "period_min": float(rng.uniform(20.0, 40.0))}
    for k in sorted(kinds & set(PART_KG)):
        opts["blocks"] = max(opts["blocks"], int(rng.integers(3, 6)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    return opts


def probe_hook(physics, probe):
    """The target on the part on the dovetail slide or below the bellows (no draws)."""
    for k in physics:
        if k == "dovetail_gib":
            probe = probe + np.array([0.0, 0.0, znb.SLIDE_TARGET_MM])
        elif k == "bellows_coupling":
            probe = probe + np.array([0.0, 0.0, znb.BELLOWS_TARGET_MM])
    return probe


def payload_hook(physics, payload_com):
    """The part's centre of mass (tool frame) [mm]: 40-100 mm below the slide or the bellows (the drawn offset's
    length mapped onto that range, its direction kept across the tool axis at a fifth) (no draws)."""
    for k in physics:
        r = float(np.linalg.norm(payload_com))
        if k == "dovetail_gib":
            payload_com = np.array([0.2 * payload_com[0], 0.2 * payload_com[1], znb.SLIDE_MM + 40.0 + 60.0 * r / 80])
        elif k == "bellows_coupling":
            payload_com = np.array([0.2 * payload_com[0], 0.2 * payload_com[1],
                                    znb.BELLOWS_MM + 40.0 + 60.0 * r / 80])
    return payload_com
