"""Set ZI: the registry of its new effect kinds, their families, the session options they need.

Physics in :mod:`effects_zi_joint`, :mod:`effects_zi_body`, :mod:`effects_zi_thermal` (sources in their docstrings). The
session hook consumes random numbers only when a case has a set-ZI kind, so sets A-ZH regenerate unchanged; the probe
hook draws none. Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_zi_body as zib
from sim2real_indep import effects_zi_joint as zij
from sim2real_indep import effects_zi_thermal as zit

#: kind -> (draw, apply, true-structure features)
EFFECTS_ZI = {
    "pi_load_step": (zij.step_draw, zij.step_apply, zij.step_features),
    "helix_tilt": (zij.helix_draw, zij.helix_apply, zij.helix_features),
    "dog_play": (zij.dog_draw, zij.dog_apply, zij.dog_features),
    "flank_profile": (zij.flank_draw, zij.flank_apply, zij.flank_features),
    "cage_runout": (zij.cage_draw, zij.cage_apply, zij.cage_features),
    "free_swivel": (zib.swivel_draw, zib.swivel_apply, zib.swivel_features),
    "gravel_ratchet": (zib.ratchet_draw, zib.ratchet_apply, zib.ratchet_features),
    "crowned_sole": (zib.sole_draw, zib.sole_apply, zib.sole_features),
    "bernoulli_grip": (zib.bernoulli_draw, zib.bernoulli_apply, zib.bernoulli_features),
    "jamming_grip": (zib.jamming_draw, zib.jamming_apply, zib.jamming_features),
    "thermosyphon": (zit.syphon_draw, zit.syphon_apply, zit.syphon_features),
    "motion_cooling": (zit.cooling_draw, zit.cooling_apply, zit.cooling_features),
}
#: families (context.FAMILY takes them over). pi_load_step, the loaded axes' PI loops recovering from each pose's load
#: step, and helix_tilt, the outputs tilted by their helical stages' thrust, joint compliance; dog_play, axis 1 twisted
#: by its dress pack inside the wide play of its guide's dog, and free_swivel, the target on a friction-held swivel that
#: hangs downhill, backlash; flank_profile, axis 2's mesh error switching with the loaded flank, and cage_runout, axis
#: 1's encoder misread by its bearing's cage-borne runout, transmission; gravel_ratchet, the base on a densifying
#: granular bed, and crowned_sole, an unanchored base rocking on its bowed sole, mount compliance; bernoulli_grip, a
#: part floating on a Bernoulli gripper's air film, and jamming_grip, a part in a jamming gripper locked at the block's
#: start, link deflection; thermosyphon, the forearm cooled by a heat pipe that works with the wrist end down, and
#: motion_cooling, the upper arm and forearm cooled by the air they move through, thermal
FAMILY_ZI = {"pi_load_step": "joint_compliance", "helix_tilt": "joint_compliance", "dog_play": "backlash",
             "free_swivel": "backlash", "flank_profile": "transmission", "cage_runout": "transmission",
             "gravel_ratchet": "mount_compliance", "crowned_sole": "mount_compliance",
             "bernoulli_grip": "link_deflection", "jamming_grip": "link_deflection", "thermosyphon": "thermal",
             "motion_cooling": "thermal"}
#: measurement effects that need the tracker's frame (none in set ZI)
AFTER_TRACKER: set = set()
#: kinds that change the part between blocks (the logged payload): its mass range per arm [kg]
PART_KG = {"crowned_sole": {"ur10": (0.0, 10.0), "kr16_like": (0.0, 16.0), "tool_changer": (0.0, 80.0)},
           "bernoulli_grip": {"ur10": (0.2, 2.0), "kr16_like": (0.2, 3.0), "tool_changer": (1.0, 8.0)},
           "jamming_grip": {"ur10": (0.2, 3.0), "kr16_like": (0.3, 5.0), "tool_changer": (1.0, 10.0)}}
#: kinds whose effect follows the time, the pauses and the production between blocks: their sessions span hours, in
#: blocks with production or pauses between them; the pauses' length [min]
LONG = {"thermosyphon": ((4, 7), "mixed", (20.0, 60.0)), "motion_cooling": ((4, 7), "mixed", (20.0, 60.0))}


def session_options(robot_key, physics, rng, opts):
    """The session of a set-ZI case: for :data:`PART_KG`, 3-5 blocks at least, each with a new part; for :data:`LONG`,
    blocks with production or pauses between them that spread the session over hours. No draws without a set-ZI
    kind."""
    kinds = set(physics) & set(EFFECTS_ZI)
    if not kinds:
        return opts
    opts = dict(opts)
    for k in sorted(kinds & set(PART_KG)):
        opts["blocks"] = max(opts["blocks"], int(rng.integers(3, 6)))
        lo, hi = PART_KG[k][robot_key]
        opts["payload_steps"] = tuple(np.round(rng.uniform(lo, hi, opts["blocks"]), 2))
    for k in sorted(kinds & set(LONG)):
        (lo, hi), gap, pause = LONG[k]
        opts.update(blocks=max(opts["blocks"], int(rng.integers(lo, hi))), gap_kind=gap, pause_min=pause)
    return opts


def probe_hook(physics, probe):
    """The target on the held part, beyond the gripper's face (no draws)."""
    for k in physics:
        if k in ("bernoulli_grip", "jamming_grip"):
            probe = probe + np.array([0.0, 0.0, zib.PART_MM])
    return probe
