"""Set L thermal effects (new physics, not in sets A-K): hot die-cast parts heating the gripper's fingers and body by
conduction while they are held; a machine-tending arm splashed with coolant, whose wetted side evaporative cooling
drives towards the wet-bulb temperature until the film has dried. Same protocol as :mod:`effects_joint` (``draw``,
``apply``, ``features``).

Sources:

* hot parts: a part held between the fingers heats them through the contact conductance h_c A_c (h_c of dry metal
  contacts under clamping pressure 10^3-10^4 W/m^2 K: Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*,
  6th ed., 2007, sec. 3.2 and its table of contact resistances; Madhusudana, *Thermal Contact Conductance*, 1996); a
  finger is one lumped node (tau = rho c V / (h_c A_c + G_loss): 2-8 min), the gripper's body a second one fed by the
  fingers (15-40 min; Incropera & DeWitt, ch. 5), their steady rises under continuous holding 35-65 % of the part's
  excess temperature and 20-50 % of the finger's (assumed). The heat flows while a part is held -- the blocks with a
  payload logged, and during production the parts handled for a duty of 30-70 % (the session starting from production,
  at its steady state) -- and the finger (steel) and the body (the arm's metal) grow along the tool axis, carrying the
  target at the finger's tip (:func:`effects_l.probe_hook`; the gripper of :mod:`effects_l_body`). Die-cast aluminium
  parts taken out at 250-380 K above the air (die-casting extraction, kr16_like; assumed). Set D's process-tool heat
  follows the production periods; this heat follows the held parts, logged. First drawn also for disc cutters on
  tool_changer (40-150 K after boring) and moulded parts on ur10 (30-60 K), with castings at 150-280 K, the finger's
  rise 20-50 % of the part's and fingers of 80-150 mm on kr16_like: the growth stayed within some 0.05 mm, absorbed or
  with the joint model within 1.2x in trial draws; the long fingers of extraction grippers (150-250 mm) and hotter parts
  are kept on kr16_like only.
* wet arm: a film of water-based coolant evaporates at the wet-bulb temperature, 5-10 K below the air at 20-25 degC and
  30-60 % relative humidity (psychrometrics: ASHRAE Handbook -- Fundamentals, ch. 1; the heat and mass transfer
  analogy, Incropera & DeWitt, ch. 6), and a machine-tending arm reaching into a machine tool with flood coolant is
  splashed on the side facing the machine while it works. The wetted side of the forearm tube cools towards the
  wet-bulb temperature, its mean by 40-80 % and the difference across it by 40-70 % of the depression (the tube's
  circumferential conduction), through a lumped lag of 3-8 min; the evaporation, and so the cooling, grows with the air
  flow over the tube (forced convection, h ~ v^0.5: Incropera & DeWitt, ch. 7): full while the robot works, 50-80 % of
  it in the measurement's slow moves and dwells, 20-40 % in the pauses; the thin film left after drip-off (a few um)
  dries 2-6 min after the last splash; the session starts from production, the last splash 0-10 min before it
  (assumed). The cooler side shortens: the tube bows towards it with curvature alpha dT / D (Timoshenko & Goodier,
  *Theory of Elasticity*, thermal stresses; Roark's *Formulas for Stress and Strain*, beams with a temperature
  difference: tip kappa L^2 / 2, rotation kappa L) and contracts by alpha dT_mean. The forearm tubes of ur10 and
  kr16_like (the tubes of :mod:`hardware`, their diameters from the section), the wetted side at random about the tube;
  none on tool_changer. First drawn with a depression of 4-8 K, an across share of 30-60 %, a lag of 5-15 min and
  drying in 5-25 min at one rate: a session whose production periods follow each other without pauses kept the arm wet
  throughout (absorbed in trial draws), and gains of 10-20 % in others.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import effects_c_thermal as ct
from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_l_body import finger_geometry, finger_length

STEEL_CTE = 11.7e-6


# ------------------------------------------------------------------------------------------------ hot parts
#: per arm: the part's excess temperature [K] (assumed)
HOT_PART_K = {"kr16_like": (250.0, 380.0)}


def hot_draw(ctx, hw, rng):
    if ctx.chain.name not in HOT_PART_K:
        return {}
    _, _, z_tip = finger_geometry(ctx.probe_mm)
    L = finger_length(ctx.chain.name, z_tip)
    dT = rng.uniform(*HOT_PART_K[ctx.chain.name])
    f_finger = rng.uniform(0.35, 0.65)
    return {"L_finger_mm": L, "L_body_mm": z_tip - L, "rise_finger_K": f_finger * dT,
            "rise_body_K": rng.uniform(0.2, 0.5) * f_finger * dT, "tau_finger_s": rng.uniform(2, 8) * 60,
            "tau_body_s": rng.uniform(15, 40) * 60, "duty": rng.uniform(0.3, 0.7), "cte_body": hw["material"]["cte"]}


def two_lags(dur, u, tau1, tau2, x1, x2):
    """Exact end-of-segment states of tau1 x1' = u - x1, tau2 x2' = x1 - x2 from the states ``x1``, ``x2`` for an input
    held at u[k] over segments of dur[k] [s] (tau1 != tau2; :func:`effects_d_thermal.series_lags` from a cold start)."""
    o1, o2 = np.zeros(len(dur)), np.zeros(len(dur))
    for k, (dt, uk) in enumerate(zip(dur, u)):
        e1, e2 = np.exp(-dt / tau1), np.exp(-dt / tau2)
        c = (x1 - uk) * tau1 / (tau1 - tau2)
        x1, x2 = uk + (x1 - uk) * e1, uk + c * e1 + (x2 - uk - c) * e2
        o1[k], o2[k] = x1, x2
    return o1, o2


def hot_temperatures(p, ctx):
    """Finger and body rises (2, P) [K] at the measurements: heated while a part is held (a payload logged in the
    move and the dwell, the duty of the production periods); the session starting from production, at its steady
    state."""
    s = ctx.session
    held = (s.payload_kg > 0).astype(float)
    on = np.stack([np.where(s.gap_s > 0, p["duty"], 0.0), held, held], axis=1).ravel()
    finger, body = two_lags(ct._segment_times(s), on, p["tau_finger_s"], p["tau_body_s"], p["duty"], p["duty"])
    return np.array([p["rise_finger_K"] * finger[2::3], p["rise_body_K"] * body[2::3]])


def hot_parts(p, ctx):
    """Target displacement (2, P, 3) [mm]: the finger's and the body's growth along the tool axis."""
    T = hot_temperatures(p, ctx)
    _, Rt = kin.flange(ctx.chain, ctx.q)
    ax = Rt[:, :, 2]
    return np.array([ax * (STEEL_CTE * p["L_finger_mm"] * T[0])[:, None],
                     ax * (p["cte_body"] * p["L_body_mm"] * T[1])[:, None]])


def hot_apply(p, ctx, hw):
    return Contribution(displace=hot_parts(p, ctx).sum(axis=0) if p else None)


def hot_features(p, ctx, hw):
    return hot_parts(p, ctx) if p else np.zeros((0, len(ctx.q), 3))


# ------------------------------------------------------------------------------------------------- wet arm
#: per arm: the forearm tubes a machine-tending arm wets
WET_TUBES = {"ur10": ("a3",), "kr16_like": ("d4",)}


def tube_diameter(tb):
    """Outer diameter [m] of a round tube from its area and second moment (D^2 + d^2 = 16 I / A, D^2 - d^2 = 4 A /
    pi)."""
    return float(np.sqrt((16 * tb["I"] / tb["A"] + 4 * tb["A"] / np.pi) / 2))


def wet_draw(ctx, hw, rng):
    if ctx.chain.name not in WET_TUBES:
        return {}
    tubes = {}
    for name in WET_TUBES[ctx.chain.name]:
        v = ctx.chain.links[ctx.chain.link_names.index(name)]
        e = v / np.linalg.norm(v)
        u = np.cross(e, [1.0, 0, 0] if abs(e[0]) < 0.9 else [0, 1.0, 0])
        u /= np.linalg.norm(u)
        a = rng.uniform(0, 2 * np.pi)
        tubes[name] = {"side_home": np.cos(a) * u + np.sin(a) * np.cross(e, u),
                       "D_m": tube_diameter(hw["tubes"][name])}
    dT = rng.uniform(5, 10)
    return {"tubes": tubes, "cte": hw["material"]["cte"], "dT_mean_K": rng.uniform(0.4, 0.8) * dT,
            "dT_across_K": rng.uniform(0.4, 0.7) * dT, "tau_s": rng.uniform(3, 8) * 60,
            "dry_s": rng.uniform(2, 6) * 60, "pre_s": rng.uniform(0, 10) * 60, "s_block": rng.uniform(0.5, 0.8),
            "s_still": rng.uniform(0.2, 0.4)}


def wet_state(p, session, step_s=10.0):
    """The share (P,) of the wet-bulb depression reached at the measurements: a wet tube cools at a rate that grows with
    the air flow over it -- fully while the robot works (production, coolant splashing), ``s_block`` of it in the slow
    moves and dwells of the measurement, ``s_still`` in the pauses --, and not at all once the film has dried, ``dry_s``
    after the last splash; the tube follows through its lag (exact per step of ``step_s``). The session starts from
    production: the last splash ``pre_s`` before it, the tube at the wet state then."""
    dur = ct._segment_times(session).reshape(-1, 3)
    wet_until, t, out = p["dry_s"] - p["pre_s"], 0.0, np.zeros(len(dur))
    x = 1.0 if wet_until >= 0 else np.exp(wet_until / p["tau_s"])
    for i, (gap, move, dwell) in enumerate(dur):
        segs = [(gap, 1.0 if session.gap_s[i] > 0 else p["s_still"]), (move, p["s_block"]), (dwell, p["s_block"])]
        for k, (T, rate) in enumerate(segs):
            if k == 0 and session.gap_s[i] > 0:          # production: wetted throughout
                x = 1.0 + (x - 1.0) * np.exp(-T / p["tau_s"])
                t, wet_until = t + T, t + T + p["dry_s"]
                continue
            end = t + T
            while t < end - 1e-9:
                dt = min(step_s, end - t)
                u = rate if t + 0.5 * dt < wet_until else 0.0
                x = u + (x - u) * np.exp(-dt / p["tau_s"])
                t += dt
        out[i] = x
    return out


def wet_parts(p, ctx):
    """Target displacement (2 tubes, P, 3) [mm]: per tube its bow towards the wetted side and its contraction."""
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    w = wet_state(p, ctx.session)
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    cols = []
    for name, tb in p["tubes"].items():
        li = ctx.chain.link_names.index(name)
        e, tip, L = eb._beam_state(ctx, li)
        n = np.einsum("pij,j->pi", R[:, ctx.chain.link_body[li]], tb["side_home"])
        kappa = p["cte"] * p["dT_across_K"] / tb["D_m"] * w                    # [1/m], towards the wet side
        bow = (1000.0 * (kappa * L * L / 2)[:, None] * n
               + np.cross((kappa * L)[:, None] * np.cross(e, n), ctx.target - tip))
        strain = -p["cte"] * p["dT_mean_K"] * w
        shrink = ctx.link_scale_feature(np.arange(len(ctx.chain.links)) == li) * strain[:, None]
        cols += [bow, shrink]
    return np.array(cols)


def wet_apply(p, ctx, hw):
    return Contribution(displace=wet_parts(p, ctx).sum(axis=0) if p else None)


def wet_features(p, ctx, hw):
    return wet_parts(p, ctx)
