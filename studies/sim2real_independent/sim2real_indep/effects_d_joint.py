"""Set D joint effects (new physics, not in sets A-C): a gas-spring counterbalance on joint 2 that changes the net
torque loading the compliant gear; a dress pack (hose package) twisting the wrist joints through their compliant
gears; lost motion that varies along the gear (centre-distance eccentricity); a timing-belt stage of non-integer
ratio with pulley eccentricities; ball-screw lead deviation of a prismatic stage. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* gas spring: polytropic compression of the charge, F = F1 (V1 / V)^n, n = 1.0-1.3 (isothermal to near
  adiabatic for slow robot motion); catalogue progression F2 / F1 of 1.2-1.6 over the stroke (Stabilus /
  Suspa gas-spring catalogues, as recalled). Counterbalance geometry of a link-mounted cylinder (pivot on the
  base body at r1 from the joint axis, rod eye on the arm at r2): length L = sqrt(r1^2 + r2^2 - 2 r1 r2 cos psi),
  moment arm r1 r2 sin(psi) / L (statics of a two-force member; e.g. Craig, *Introduction to Robotics*, ch. 5;
  counterbalanced axis 2 of heavy KUKA / FANUC arms). Spring sized to carry 40-90 % of the largest gravity torque
  (assumed). The joint's gear deflects under the net torque with the linear stiffness of :mod:`hardware`.
* dress pack: a hose package twisted by a wrist roll joint behaves as a torsion spring with friction in its
  guides (manufacturers' dress-pack guidelines limit the twist to about +-180 deg; torques of a few N m for a
  16 kg-class arm, assumed 2-30 N m at 180 deg by arm size, friction 10-25 % of that); the reaction loads the
  compliant wrist gear (K3 of :mod:`hardware`). The gravity torsion of every joint acts as well.
* lost motion varying along the gear: the backlash of a gear pair grows with the centre distance, which an
  eccentricity e of the wheel modulates once per output turn: b(theta) = b0 (1 + eps cos(theta + phi))
  (ISO 1328-1 radial runout / ISO 21771 backlash from centre-distance deviation; AGMA 2002 tooth thickness and
  backlash); flank selection by gravity above a friction preload as in :func:`physics.backlash_offset`.
* timing belt: driver Z1 and driven Z2 teeth (non-integer ratio Z2 / Z1), pulley eccentricities 5-25 um on the
  pitch radii (ISO 5294 / ISO 13050 pulley tolerances, radial runout of the order of 10-25 um for small
  pulleys), and a tooth-meshing (polygon) ripple at Z2 cycles per output turn of 0.5-2 um on the pitch circle
  (assumed). The output angle error is the belt-line error divided by the driven pitch radius.
* ball screw: ISO 3408-3 / JIS B 1192 lead accuracy: mean travel deviation e_p over the useful travel (class C5:
  about 20-30 um, C7: +-50 um per 300 mm, C10 rolled transport screws: +-210 um per 300 mm), the travel
  variation v_u (bow of the deviation curve) and the wobble within one revolution v_2pi (C5: about 8 um); values
  as recalled from THK / NSK catalogues. Here e_p over the measured travel log-U(0.03, 0.25) mm (classes C5-C10),
  bow 5-30 um, wobble 2-8 um.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import hardware as hwm
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution

# ---------------------------------------------------------------------------------------- gas-spring counterbalance
#: per arm: pivot radius r1, rod-eye radius r2 [m] (assumed from the arm's size)
SPRING_GEOM = {"ur10": ((0.06, 0.10), (0.15, 0.25)), "tool_changer": ((0.15, 0.25), (0.35, 0.55)),
               "kr16_like": ((0.10, 0.16), (0.25, 0.40))}
SPRING_JOINT = 1  # joint 2 (index 1) on all three arms


def _spring_geometry(p, q2):
    psi = p["psi0"] + p["s"] * q2
    L = np.sqrt(p["r1"] ** 2 + p["r2"] ** 2 - 2 * p["r1"] * p["r2"] * np.cos(psi))
    return psi, L


def spring_torque_shape(p, q2):
    """Counterbalance torque (P,) [N m] on joint 2 per unit extended force F1 [N]."""
    psi, L = _spring_geometry(p, q2)
    V = 1.0 - p["dV"] * (p["L_ext"] - L) / p["stroke"]     # gas volume, 1 at full extension
    F = V ** -p["n"]
    return p["s"] * F * p["r1"] * p["r2"] * np.sin(psi) / L


def gas_spring_draw(ctx, hw, rng):
    r1, r2 = (rng.uniform(*v) for v in SPRING_GEOM[ctx.chain.name])
    q2 = ctx.q[:, SPRING_JOINT]
    tau_g = ctx.loads[:, SPRING_JOINT]
    mid = 0.5 * (q2.min() + q2.max())
    p = {"r1": r1, "r2": r2, "n": rng.uniform(1.0, 1.3), "s": 1.0, "psi0": 0.0, "dV": 0.0, "stroke": 1.0, "L_ext": 1.0}
    # psi at mid-range 60-120 deg (a cylinder working across the arm); the side chosen to oppose gravity
    psi_mid = np.deg2rad(rng.uniform(60, 120))
    p["s"] = -float(np.sign(np.mean(tau_g) or 1.0)) * float(np.sign(np.sin(psi_mid)))
    p["psi0"] = psi_mid - p["s"] * mid
    psi_range = p["psi0"] + p["s"] * np.array([q2.min(), q2.max()])
    psi_all = np.linspace(psi_range.min() - 0.1, psi_range.max() + 0.1, 200)
    L = np.sqrt(r1 ** 2 + r2 ** 2 - 2 * r1 * r2 * np.cos(psi_all))
    p["L_ext"], p["stroke"] = L.max(), L.max() - L.min()
    prog = rng.uniform(1.2, 1.6)                             # F2 / F1 at full compression
    p["dV"] = 1 - prog ** (-1 / p["n"])
    shape = spring_torque_shape(p, q2)
    p["F1_N"] = rng.uniform(0.4, 0.9) * np.abs(tau_g).max() / max(np.abs(shape).max(), 1e-12)
    return p


def _net_load(p, ctx):
    loads = ctx.loads.copy()
    loads[:, SPRING_JOINT] += p["F1_N"] * spring_torque_shape(p, ctx.q[:, SPRING_JOINT])
    return loads


def gas_spring_apply(p, ctx, hw):
    loads = _net_load(p, ctx)
    dq = np.array([hwm.torsion(d, loads[:, j], False) for j, d in enumerate(hw["drives"])]).T
    return Contribution(dq=dq)


def gas_spring_features(p, ctx, hw):
    cols = [ctx.joint_feature(j, ctx.loads[:, j]) for j in range(ctx.chain.n)]
    cols.append(ctx.joint_feature(SPRING_JOINT, spring_torque_shape(p, ctx.q[:, SPRING_JOINT])))
    return np.array(cols)


# ------------------------------------------------------------------------------------------------- dress pack
HOSE_TORQUE_180 = {"ur10": (2.0, 6.0), "tool_changer": (10.0, 30.0), "kr16_like": (5.0, 15.0)}  # [N m] at 180 deg


def dresspack_draw(ctx, hw, rng):
    """The last three revolute joints (the wrist) carry the hose package; its neutral twist within +-30 deg of
    the middle of the measured range."""
    rev = np.flatnonzero(ctx.chain.revolute)[-3:]
    out = []
    for j in rev:
        k = rng.uniform(*HOSE_TORQUE_180[ctx.chain.name]) / np.pi
        q = ctx.q[:, j]
        q0 = 0.5 * (q.min() + q.max()) + np.deg2rad(rng.uniform(-30, 30))
        out.append({"joint": int(j), "k_Nm_per_rad": k, "q0": q0, "friction_Nm": rng.uniform(0.10, 0.25) * k * np.pi})
    return out


def _hose_torque(h, ctx):
    j = h["joint"]
    return -h["k_Nm_per_rad"] * (ctx.q[:, j] - h["q0"]) - h["friction_Nm"] * ctx.session.direction[:, j]


def dresspack_apply(p, ctx, hw):
    loads = ctx.loads.copy()
    for h in p:
        loads[:, h["joint"]] += _hose_torque(h, ctx)
    dq = np.array([hwm.torsion(d, loads[:, j], False) for j, d in enumerate(hw["drives"])]).T
    return Contribution(dq=dq)


def dresspack_features(p, ctx, hw):
    cols = [ctx.joint_feature(j, ctx.loads[:, j]) for j in range(ctx.chain.n)]
    for h in p:
        j = h["joint"]
        cols += [ctx.joint_feature(j, ctx.q[:, j] - h["q0"]), ctx.joint_feature(j, ctx.session.direction[:, j])]
    return np.array(cols)


# --------------------------------------------------------------------------------- position-dependent lost motion
def varlash_draw(ctx, hw, rng):
    return [{"joint": int(j), "b0": rng.uniform(1.0, 3.0) * ph.ARCMIN, "eps": rng.uniform(0.3, 0.7),
             "phi": rng.uniform(0, 2 * np.pi), "h": rng.uniform(0.1, 0.5) * ph.ARCMIN,
             "preload": rng.uniform(0.02, 0.08) * hw["drives"][j]["T_rated"]}
            for j in np.flatnonzero(ctx.chain.revolute)]


def _flank(b, ctx):
    j = b["joint"]
    return ph.backlash_offset(ctx.session.direction[:, j], ctx.loads[:, j], b["preload"], 2.0, 0.0)


def varlash_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for b in p:
        j, th = b["joint"], ctx.q[:, b["joint"]]
        width = b["b0"] * (1 + b["eps"] * np.cos(th + b["phi"]))
        dq[:, j] = _flank(b, ctx) * width / 2 - ctx.session.direction[:, j] * b["h"] / 2
    return Contribution(dq=dq)


def varlash_features(p, ctx, hw):
    cols = []
    for b in p:
        j, th, f = b["joint"], ctx.q[:, b["joint"]], _flank(b, ctx)
        cols += [ctx.joint_feature(j, f), ctx.joint_feature(j, f * np.cos(th)), ctx.joint_feature(j, f * np.sin(th)),
                 ctx.joint_feature(j, ctx.session.direction[:, j])]
    return np.array(cols)


# ------------------------------------------------------------------------------------------------ timing belt
def belt_draw(ctx, hw, rng):
    """One or two wrist joints (revolute, index >= 3) driven through a timing belt (pitch 3 or 5 mm)."""
    wrist = [int(j) for j in np.flatnonzero(ctx.chain.revolute) if j >= 3]
    k = int(rng.integers(1, 3))
    out = []
    for j in sorted(rng.permutation(wrist)[:k]):
        z1 = int(rng.choice([18, 20, 22, 24]))
        z2 = int(rng.integers(30, 49))
        if z2 % z1 == 0:
            z2 += 1
        pitch = float(rng.choice([3.0, 5.0]))
        R1, R2 = z1 * pitch / (2 * np.pi), z2 * pitch / (2 * np.pi)          # pitch radii [mm]
        e1, e2, m = rng.uniform(5, 25) * 1e-3, rng.uniform(5, 25) * 1e-3, rng.uniform(0.5, 2.0) * 1e-3
        out.append({"joint": int(j), "z1": z1, "z2": z2, "pitch_mm": pitch, "R1_mm": R1, "R2_mm": R2,
                    "orders": np.array([1.0, z2 / z1, float(z2)]), "amp": np.array([e2, e1, m]) / R2,
                    "phase": rng.uniform(0, 2 * np.pi, 3)})
    return out


def belt_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        th = ctx.q[:, g["joint"]]
        dq[:, g["joint"]] += (g["amp"] * np.sin(np.multiply.outer(th, g["orders"]) + g["phase"])).sum(axis=1)
    return Contribution(dq=dq)


def belt_features(p, ctx, hw):
    cols = []
    for g in p:
        th = ctx.q[:, g["joint"]]
        for f in g["orders"]:
            cols += [ctx.joint_feature(g["joint"], np.sin(f * th)), ctx.joint_feature(g["joint"], np.cos(f * th))]
    return np.array(cols)


# ------------------------------------------------------------------------------------------------- ball screw
def screw_draw(ctx, hw, rng):
    """Every prismatic joint driven by a ball screw of lead 5, 10 or 20 mm, accuracy class C5-C7 (none on an arm
    without a prismatic joint)."""
    out = []
    for j in np.flatnonzero(~ctx.chain.revolute):
        s = ctx.q[:, j]
        out.append({"joint": int(j), "lead_mm": float(rng.choice([5.0, 10.0, 20.0])),
                    "e_p_mm": rng.choice([-1, 1]) * np.exp(rng.uniform(np.log(0.03), np.log(0.25))),  # travel
                    "bow_mm": rng.uniform(-1, 1) * rng.uniform(0.005, 0.03),     # travel variation (bow)
                    "wobble_mm": rng.uniform(0.002, 0.008), "phase": rng.uniform(0, 2 * np.pi),
                    "travel": (float(s.min()), float(s.max()))})
    return out


def _screw_signals(g, ctx):
    s = ctx.q[:, g["joint"]]
    lo, hi = g["travel"]
    u = 2 * (s - lo) / max(hi - lo, 1e-9) - 1                 # -1..1 over the travel
    w = 2 * np.pi * s / g["lead_mm"]
    return np.array([(u + 1) / 2, (3 * u ** 2 - 1) / 2, np.sin(w), np.cos(w)])


def screw_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for g in p:
        sig = _screw_signals(g, ctx)
        amp = [g["e_p_mm"], g["bow_mm"], g["wobble_mm"] * np.cos(g["phase"]), g["wobble_mm"] * np.sin(g["phase"])]
        dq[:, g["joint"]] += np.asarray(amp) @ sig
    return Contribution(dq=dq)


def screw_features(p, ctx, hw):
    return np.array([ctx.joint_feature(g["joint"], s) for g in p for s in _screw_signals(g, ctx)])

