"""Set Z: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_z_joint`, :mod:`effects_z_body`, :mod:`effects_z_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-Z kind, so sets A-Y regenerate unchanged. Imports
nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_z_body as zb
from sim2real_indep import effects_z_joint as zj
from sim2real_indep import effects_z_thermal as zt

#: kind -> (draw, apply, true-structure features)
EFFECTS_Z = {
    "water_slug": (zj.slug_draw, zj.slug_apply, zj.slug_features),
    "balancer_gas": (zj.gas_draw, zj.gas_apply, zj.gas_features),
    "balancer_seal": (zj.seal_draw, zj.seal_apply, zj.seal_features),
    "tripod_windup": (zj.windup_draw, zj.windup_apply, zj.windup_features),
    "band_spiral": (zj.band_draw, zj.band_apply, zj.band_features),
    "head_tilt": (zj.head_draw, zj.head_apply, zj.head_features),
    "warm_isolators": (zb.iso_draw, zb.iso_apply, zb.iso_features),
    "oil_canning": (zb.can_draw, zb.can_apply, zb.can_features),
    "bowstring": (zb.bow_draw, zb.bow_apply, zb.bow_features),
    "stress_relief": (zb.relief_draw, zb.relief_apply, zb.relief_features),
    "floor_heating": (zt.floor_draw, zt.floor_apply, zt.floor_features),
    "duct_lag": (zt.duct_draw, zt.duct_apply, zt.duct_features),
}
#: families (context.FAMILY takes them over). water_slug, the gears twisted by water running to the lower end of a
#: hollow gripper boom, and balancer_gas, axis 2's gear loaded by its gas balancer's force following the air by the gas
#: law, joint compliance; balancer_seal, axis 2 held back against its last motion by the balancer's seal friction, and
#: tripod_windup, the tracker's frame turned by its tripod's friction-held windup after each slew, backlash (errors
#: that follow the last motion); band_spiral, the telescopic stage's spiral band drive, and head_tilt, axis 1's
#: encoder misread as its bearing tilts under the arm's moment, transmission (the joints' reading and drive);
#: warm_isolators, the base's isolators softening as they warm, and oil_canning, the table's top plate snapping between
#: its two dished shapes, mount compliance (the robot's support); bowstring, the upper arm bent by a taut harness, and
#: stress_relief, a welded gripper frame distorting as its residual stresses relax, link deflection (the arm's and the
#: end-of-arm structure carrying the target); floor_heating, the base plate curled by a cooling floor heating loop, and
#: duct_lag, the upper arm bowed by a duct that slows one side's following of the air, thermal
FAMILY_Z = {"water_slug": "joint_compliance", "balancer_gas": "joint_compliance", "balancer_seal": "backlash",
            "tripod_windup": "backlash", "band_spiral": "transmission", "head_tilt": "transmission",
            "warm_isolators": "mount_compliance", "oil_canning": "mount_compliance", "bowstring": "link_deflection",
            "stress_relief": "link_deflection", "floor_heating": "thermal", "duct_lag": "thermal"}
#: measurement effects that need the tracker's frame
AFTER_TRACKER = {"tripod_windup"}
#: kinds whose sessions are a working morning in a drifting hall (balancer_gas: an outdoor site, a larger drift): the
#: blocks' range, the pauses [min], the drift's range [K]
AIR = {"balancer_gas": ((5, 9), (20.0, 50.0), (15.0, 25.0)), "warm_isolators": ((5, 9), (20.0, 50.0), (8.0, 14.0)),
       "duct_lag": ((5, 9), (20.0, 50.0), (8.0, 14.0))}
#: kinds whose sessions have pauses between their blocks: the blocks' range and the pauses' range [min]
PAUSES = {"floor_heating": ((5, 9), (30.0, 80.0))}
#: kinds whose sessions have production (exercise) between their blocks: the blocks' range
PRODUCTION = {"stress_relief": (4, 7)}
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
#: the target's offset added by the end-of-arm structure of a kind (tool frame) [mm]
PROBE_OFFSET = {"water_slug": np.array([zj.BOOM_MM, 0.0, 0.0]), "stress_relief": np.array([zb.FRAME_MM, 0.0, 0.0])}
PART_KG = {"head_tilt": {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 80.0)}}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-Z case: for :data:`AIR`, the blocks of its range with pauses between them and the hall's air
    drifting by the drawn change over the session (with a small HVAC cycle); for :data:`PAUSES`, blocks with pauses;
    for :data:`PRODUCTION`, blocks with production between them; for :data:`PART_KG`, 3-5 blocks at least, each with a
    new part. No draws without a set-Z kind."""
    kinds = set(physics) & set(EFFECTS_Z)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(AIR)):
        (lo, hi), pause, (d_lo, d_hi) = AIR[k]
        drift = float(rng.choice([-1.0, 1.0]) * rng.uniform(d_lo, d_hi))
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind="pause", pause_min=pause,
                    air={"drift_K": drift, "cycle_K": rng.uniform(0.2, 0.6), "period_min": rng.uniform(60.0, 150.0)})
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
    return opts


def probe_hook(physics, probe):
    """The target at the end of the case's end-of-arm structure (no draws)."""
    for k in physics:
        if k in PROBE_OFFSET:
            probe = probe + PROBE_OFFSET[k]
    return probe
