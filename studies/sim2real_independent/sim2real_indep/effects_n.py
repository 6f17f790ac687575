"""Set N: the registry of its new effect kinds, their families, the session options they need and the hooks that put
the target on a lattice boom's tip or a ring frame and the part where the boom or the ring's fingers hold it.

Physics in :mod:`effects_n_joint`, :mod:`effects_n_body`, :mod:`effects_n_thermal` (sources in their docstrings).
The session hook consumes random numbers only when a case has a set-N kind (and the probe and payload hooks none at
all), so sets A-M regenerate unchanged. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_n_body as nb
from sim2real_indep import effects_n_joint as nj
from sim2real_indep import effects_n_thermal as nt
from sim2real_indep.hardware import PAYLOAD_MAX_KG, pick_place

Z = np.array([0.0, 0.0, 1.0])

#: kind -> (draw, apply, true-structure features)
EFFECTS_N = {
    "wind_panel": (nj.wind_draw, nj.wind_apply, nj.wind_features),
    "jet_reaction": (nj.jet_draw, nj.jet_apply, nj.jet_features),
    "harness_lash": (nj.harness_draw, nj.harness_apply, nj.harness_features),
    "balanced_lash": (nj.balanced_draw, nj.balanced_apply, nj.balanced_features),
    "rope_creep": (nj.rope_draw, nj.rope_apply, nj.rope_features),
    "crawler_sink": (nb.crawler_draw, nb.crawler_apply, nb.crawler_features),
    "leaf_springs": (nb.leaf_draw, nb.leaf_apply, nb.leaf_features),
    "truss_slack": (nj.truss_draw, nj.truss_apply, nj.truss_features),
    "ring_frame": (nb.ring_draw, nb.ring_apply, nb.ring_features),
    "tripod_tilt": (nt.tripod_draw, nt.tripod_apply, nt.tripod_features),
    "pad_heat": (nt.pad_draw, nt.pad_apply, nt.pad_features),
    "mag_drift": (nt.mag_draw, nt.mag_apply, nt.mag_features),
}
#: families (context.FAMILY takes them over). wind_panel, the gears twisted by the wind's normal force on a carried
#: panel, and jet_reaction, by a water jet's reaction, joint compliance; harness_lash, axis 1's lost motion whose flank
#: the base harness's torsion chooses, and balanced_lash, axis 2's under gravity, a counterbalance and its seal
#: friction, backlash; rope_creep, a telescopic stage's rope creeping on its traction sheave, and mag_drift, magnetic
#: encoders' errors growing as they warm (the family whose model holds the shape, as set K's thermal backlash is
#: backlash), transmission; crawler_sink, a tracked carrier sinking plastically into soft ground, and leaf_springs, a
#: vehicle's leaf springs with inter-leaf friction, mount compliance (the robot's support); truss_slack, a lattice
#: gripper boom's pin slack, and ring_frame, a ring gripper frame the held part stiffens, link deflection (the
#: end-of-arm structure carrying the target, as sets K's RCC and M's tie-rod bar); tripod_tilt, the tracker's head
#: tilted by its unequally heated tripod legs (a measurement effect following a temperature, as set G's tripod growth),
#: and pad_heat, the base lifted and tilted by unequally heated elastomer pads, thermal
FAMILY_N = {"wind_panel": "joint_compliance", "jet_reaction": "joint_compliance", "harness_lash": "backlash",
            "balanced_lash": "backlash", "rope_creep": "transmission", "mag_drift": "transmission",
            "crawler_sink": "mount_compliance", "leaf_springs": "mount_compliance", "truss_slack": "link_deflection",
            "ring_frame": "link_deflection", "tripod_tilt": "thermal", "pad_heat": "thermal"}
#: measurement effects that need the tracker's frame
AFTER_TRACKER = {"tripod_tilt"}
#: kinds whose sessions have 5-8 blocks (4-7 for the rope): what happens between them, and the pauses' length [min]
BLOCKS = {"jet_reaction": ("pause", (10.0, 40.0)), "tripod_tilt": ("pause", (10.0, 40.0)),
          "pad_heat": ("pause", (10.0, 40.0)), "mag_drift": ("mixed", (10.0, 40.0)),
          "rope_creep": ("pause", (2.0, 10.0))}
#: kinds whose sessions change the payload between blocks (pick and place, one load none)
PICK_PLACE = {"crawler_sink", "balanced_lash", "truss_slack", "ring_frame"}
#: kinds that carry one load throughout (the panel)
PANEL = {"wind_panel"}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-N case: 5-8 blocks separated by pauses of 10-40 min (the jet's pump, the heaters) or by
    production periods and pauses (the encoders' warming), 4-7 blocks with short pauses for the rope's re-referencing;
    pick and place with 2-4 loads changed between 6-10 blocks, the first block empty if the draw left none; the panel
    held throughout (50-90 % of the arm's largest payload)."""
    kinds = set(physics) & set(EFFECTS_N)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(BLOCKS)):
        gap, pause = BLOCKS[k]
        lo = 4 if k == "rope_creep" else 5
        gap = "mixed" if opts.get("gap_kind") == "mixed" else gap
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, lo + 4))), gap_kind=gap, pause_min=pause)
    if kinds & PICK_PLACE:
        opts.update(pick_place(robot_key, rng, opts["blocks"]))
        steps = list(opts["payload_steps"])
        if min(steps) > 0:                                   # held and empty blocks (no draws)
            steps[0] = 0.0
        opts["payload_steps"] = tuple(steps)
    if kinds & PANEL:
        opts["payload_steps"] = (float(np.round(rng.uniform(0.5, 0.9) * PAYLOAD_MAX_KG[robot_key], 1)),)
    return opts


def probe_hook(physics, probe_mm, robot_key):
    """The target offset (3,) [mm] (no random numbers): for the lattice boom, its tip's lower node -- the drawn offset's
    direction across the tool axis the boom's, its length (5-100 mm) mapped onto the arm's boom length, at the lower
    chord's height; for the ring frame, on the ring in that direction, the length mapped onto the ring's radius, at the
    hub's height; unchanged otherwise."""
    probe_mm = np.asarray(probe_mm, float)
    d = np.array([probe_mm[0], probe_mm[1], 0.0])
    d = d / np.linalg.norm(d) if np.linalg.norm(d) > 1e-9 else np.array([1.0, 0.0, 0.0])
    share = (np.linalg.norm(probe_mm) - 5.0) / 95.0
    if "truss_slack" in physics and robot_key in nj.TRUSS:
        L0, L1 = nj.TRUSS[robot_key][0]
        return (L0 + (L1 - L0) * share) * d + nj.CHORD_Z_MM * Z
    if "ring_frame" in physics and robot_key in nb.RING:
        R0, R1 = nb.RING[robot_key][0]
        return (R0 + (R1 - R0) * share) * d + nb.HUB_Z_MM * Z
    return probe_mm


def payload_hook(physics, com_mm, probe_mm):
    """The payload's centre of mass (3,) [mm], tool frame: for the lattice boom, at its tip (the part hangs from the
    tip's gripper); for the ring frame, on the tool axis 30-100 mm below the fingers' grip (the drawn offset's length,
    0-80 mm, mapped onto that range); unchanged otherwise (no random numbers)."""
    if "truss_slack" in physics:
        return np.asarray(probe_mm, float).copy()
    if "ring_frame" in physics:
        below = 30.0 + 70.0 * min(np.linalg.norm(com_mm) / 80.0, 1.0)
        return (nb.HUB_Z_MM + nb.FINGER_MM + below) * Z
    return com_mm
