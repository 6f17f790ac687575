"""Set F joint effects (new physics, not in sets A-E): a spring balancer pulling the forearm up through a cable
from a fixed hook; axes 2 and 3 of the heavy arms driven by electric cylinders through a lever, seen as a joint
stiffness that follows the lever's moment arm; gear backlash grown in two worn zones of the gear; a holding brake
that closes at standstill with a clearance in its hub; an output-side tape-scale encoder with a gap at its butt
joint; the lever linkage's pin positions off their drawing values. Same protocol as :mod:`effects_joint`
(``draw``, ``apply``, ``features``).

Sources:

* balancer: a spring balancer (tool / hose balancer) keeps a nearly constant pull over its stroke through a
  conical drum, with a residual rate of a few % to ~20 % of the pull over the stroke (balancer catalogues, e.g.
  Tecna / Carl Stahl, as recalled); the pull acts along the cable from the clamp on the forearm to the hook.
  Joint loads of an external force: tau = J(p)^T F (statics: Craig, *Introduction to Robotics*, ch. 5). Pull by
  arm 20-60 / 50-150 / 150-500 N (hose packages or tools of 2-50 kg), hook 0.6-1.5 m above the clamp's highest
  position and N(0, 0.3 m) off its mean plan position, clamp at 30-70 % of the forearm, rate 5-20 % of the pull
  over the session's cable-length range
  (assumptions). Every joint deflects with the linear stiffness of :mod:`hardware` under gravity plus pull.
* cylinder-driven axes: a linear actuator (ball-screw electric cylinder) between a pivot on the proximal body at
  r1 from the joint axis and a rod eye on the distal body at r2: L^2 = r1^2 + r2^2 - 2 r1 r2 cos psi, moment arm
  a = r1 r2 sin(psi) / L, dL = a dpsi (law of cosines; cylinder-lever kinematics of excavator and palletiser arms,
  e.g. Koivo et al., J. Aerosp. Eng. 9(1), 1996; Hartenberg & Denavit, *Kinematic Synthesis of Linkages*, 1964).
  A cylinder of axial rigidity k_a seen at the joint: K = k_a a^2 (virtual work). Long cylinder, short crank:
  r1 / r2 >= 3 keeps L_max / L_min < 1.8 (a stroke a real cylinder has); r1 0.8-1.2 / 0.5-0.8 m, r2 0.25-0.4 /
  0.15-0.25 m for tool_changer / kr16_like, psi 80-100 deg at mid-range (all assumed). k_a 80-200 / 50-150 N/um:
  screw E A / L in series with the nut, the support bearings and the clevis pins (a 40 mm screw of 0.8 m alone is
  ~330 N/um; assumed; first drawn at 200-600 / 100-300, which made the joints stiffer than their cycloid gears).
  The kinds replace the reducers of axes 2 and 3 of those two arms (none on ur10: the kinds do nothing there).
* lever pin positions: the controller turns the cylinder stroke (motor encoder x lead) into the joint angle with
  the drawing's r1, r2 and closed length; line-bored pin holes off by 0.03-0.1 / 0.01-0.04 mm, the cylinder's
  mounting length by 0.05-0.2 / 0.02-0.08 mm on the welded tool_changer / the machined kr16_like (assumed
  tolerances; kr16_like's first drawn as tool_changer's gave up to 2.5 mm) give the angle error dpsi = psi_r1 dr1 +
  psi_r2 dr2 + dL / a (first order; the second order, (0.1 mm / 0.2 m)^2, is negligible).
* worn zones: the backlash of a gear grows where its teeth have worn (wear modes: ISO 10825 / AGMA 1010 gear-tooth
  wear terminology); the teeth that mesh most -- the sectors where the joint works most -- wear most (assumed), so
  b(theta) = b0 + sum_k w_k exp(-(theta - theta_k)^2 / 2 s_k^2), two zones inside the used range of each main
  axis, b0 0.3-1 arcmin, w 0.5-2.5 arcmin, s 5-20 deg (assumed); the wrist gears keep b0; flank selection by the
  gravity load above a friction preload as :func:`physics.backlash_offset` (Nordin & Gutman, Automatica 38, 2002).
* brake at standstill: controllers can close the holding brakes and switch the servo off after a standstill time
  (energy saving; e.g. KUKA's brake delay / brake mode machine data, as recalled). A spring-applied brake's friction
  disc sits on a splined / hexagonal hub with rotational play c (0.5-2 deg at the motor, assumed); while moving the
  disc rides on the hub's flank, and the deceleration throws it to the leading flank; when the brake closes and the
  servo drops, a gravity torque above the motor-side drag (0.5-2 % of the rated torque, assumed) turns the motor
  through the play to the flank it pushes: the output moves by (sign(tau) + d) c / 2N (gear ratio N: strain-wave
  80-160, cycloid 101-161). Standstill time 3.5-7 s against the dwells of 3-8 s: some poses are braked, some not.
* tape-scale encoder: an output-side angle encoder with a steel scale tape on a drum, full-circle version with a
  butt joint (HEIDENHAIN "Angle encoders without integral bearing", ERA 7000 / 8000 series, as recalled): a gap g
  at the joint leaves the lines spread over 2 pi - g / R, so the reading runs fast by eps = g / (2 pi R) and drops by
  g / R at the joint (a sawtooth in the output angle). g 0.01-0.05 mm, R by arm (assumed); on the main axes 1-3 (an
  accuracy retrofit with secondary encoders, assumed). Oracle check: over tool_changer's short joint ranges
  (70-120 deg) the butt joint is mostly outside the range and the remaining ramp is absorbed by the zero offsets;
  the set uses it on ur10 and kr16_like.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution

TWO_PI = 2 * np.pi


def gravity_torsion(ctx, hw, skip=()):
    """Joint offsets (P, n) of the linear gear stiffness under gravity (joints in ``skip`` left at zero)."""
    dq = np.zeros_like(ctx.q)
    for j, d in enumerate(hw["drives"]):
        if j not in skip:
            dq[:, j] = hwm.torsion(d, ctx.loads[:, j], False)
    return dq


# ------------------------------------------------------------------------------------------------ balancer
#: per arm: clamped link (the forearm) and pull range [N] (assumed)
BALANCER = {"ur10": ("a3", (20.0, 60.0)), "kr16_like": ("d4", (50.0, 150.0)), "tool_changer": ("l4", (150.0, 500.0))}


def _clamp_point(p, ctx):
    """Clamp positions (P, 3) [mm] on the forearm's body."""
    R, t = kin.body_transforms(ctx.chain, ctx.q)
    return np.einsum("pij,j->pi", R[:, p["body"]], p["clamp_home"]) + t[:, p["body"]]


def point_loads(ctx, body, point, force):
    """Joint loads (P, n) [N m / N] of forces (P, 3) [N] acting at points (P, 3) [mm] of ``body``."""
    J = kin.position_jacobian(ctx.chain, ctx.q, point)
    out = np.einsum("pin,pi->pn", J, force) * np.where(ctx.chain.revolute, 1e-3, 1.0)
    out[:, body:] = 0.0                                # the joints past the body do not carry it
    return out


def balancer_draw(ctx, hw, rng):
    name, pull = BALANCER[ctx.chain.name]
    ch = ctx.chain
    li = ch.link_names.index(name)
    root = np.cumsum(ch.links, axis=0)[li] - ch.links[li]
    p = {"body": int(ch.link_body[li]), "clamp_home": root + rng.uniform(0.3, 0.7) * ch.links[li]}
    c = _clamp_point(p, ctx)
    p["hook_mm"] = np.r_[c[:, :2].mean(axis=0) + rng.normal(0, 300.0, 2), c[:, 2].max() + rng.uniform(600, 1500)]
    L = np.linalg.norm(p["hook_mm"] - c, axis=1)
    p["L_ref_mm"], p["F0_N"] = float(L.mean()), rng.uniform(*pull)
    p["k_N_per_mm"] = p["F0_N"] * rng.uniform(0.05, 0.2) / max(np.ptp(L), 1.0)
    return p


def balancer_loads(p, ctx):
    """Joint loads (2, P, n) [N m / N] of the pull per N of F0 and per N/mm of the rate."""
    c = _clamp_point(p, ctx)
    v = p["hook_mm"] - c
    L = np.linalg.norm(v, axis=1, keepdims=True)
    u = v / L
    return np.array([point_loads(ctx, p["body"], c, u), point_loads(ctx, p["body"], c, u * (L - p["L_ref_mm"]))])


def balancer_apply(p, ctx, hw):
    unit = balancer_loads(p, ctx)
    loads = ctx.loads + p["F0_N"] * unit[0] + p["k_N_per_mm"] * unit[1]
    return Contribution(dq=np.array([hwm.torsion(d, loads[:, j], False) for j, d in enumerate(hw["drives"])]).T)


def balancer_features(p, ctx, hw):
    unit = balancer_loads(p, ctx)
    cols = [ctx.joint_feature(j, ctx.loads[:, j]) for j in range(ctx.chain.n)]
    cols += [ctx.joint_feature(j, unit[k][:, j]) for k in range(2) for j in range(p["body"])]
    return np.array(cols)


# ---------------------------------------------------------------------------------------- cylinder lever
#: per arm: cylinder-driven joints, pivot radius r1, crank radius r2 [m], axial rigidity [N/um], pin-position and
#: mounting-length errors [mm] (assumed)
LEVER = {"tool_changer": ((1, 2), (0.8, 1.2), (0.25, 0.40), (80, 200), (0.03, 0.1), (0.05, 0.2)),
         "kr16_like": ((1, 2), (0.5, 0.8), (0.15, 0.25), (50, 150), (0.01, 0.04), (0.02, 0.08))}


def lever_geometry(ctx, hw, rng):
    """Lever of each cylinder-driven joint (none on an arm without them): psi = psi0 + s q, psi 80-100 deg at
    the middle of the session's range. Drawn once per robot (kept in ``hw``: the lever kinds of a case share it);
    each kind gets its own copies."""
    spec = LEVER.get(ctx.chain.name)
    if spec is None:
        return []
    if "lever" not in hw:
        hw["lever"] = _draw_levers(ctx, spec, rng)
    return [dict(lv) for lv in hw["lever"]]


def _draw_levers(ctx, spec, rng):
    out = []
    for j in spec[0]:
        q = ctx.q[:, j]
        s = float(rng.choice([-1.0, 1.0]))
        mid = np.deg2rad(rng.uniform(80, 100))
        out.append({"joint": int(j), "r1": rng.uniform(*spec[1]), "r2": rng.uniform(*spec[2]), "s": s,
                    "psi0": mid - s * 0.5 * (q.min() + q.max())})
    return out


def lever_state(lv, q):
    """Included angle psi [rad], cylinder length L [m] and moment arm a [m] at joint angles ``q``."""
    psi = lv["psi0"] + lv["s"] * np.asarray(q)
    r1, r2 = lv["r1"], lv["r2"]
    L = np.sqrt(r1 * r1 + r2 * r2 - 2 * r1 * r2 * np.cos(psi))
    return psi, L, r1 * r2 * np.sin(psi) / L


def lever_partials(lv, q):
    """d psi / d r1, d psi / d r2, d psi / d L at fixed stroke (3, P) [rad/m]."""
    psi, L, a = lever_state(lv, q)
    r1, r2 = lv["r1"], lv["r2"]
    rs = r1 * r2 * np.sin(psi)
    return np.array([-(r1 * r1 - r2 * r2 + L * L) / (2 * r1 * rs), -(r2 * r2 - r1 * r1 + L * L) / (2 * r2 * rs), 1 / a])


def leverstiff_draw(ctx, hw, rng):
    spec = LEVER.get(ctx.chain.name)
    geo = lever_geometry(ctx, hw, rng)
    for lv in geo:
        lv["k_a_N_per_m"] = rng.uniform(*spec[3]) * 1e6
    return geo


def _lever_signal(lv, ctx):
    """Joint load over the squared moment arm (P,) [N m / m^2 = N/m]: the joint offset per unit 1/k_a."""
    _, _, a = lever_state(lv, ctx.q[:, lv["joint"]])
    return ctx.loads[:, lv["joint"]] / (a * a)


def leverstiff_apply(p, ctx, hw):
    dq = gravity_torsion(ctx, hw, skip={lv["joint"] for lv in p})
    for lv in p:
        dq[:, lv["joint"]] = _lever_signal(lv, ctx) / lv["k_a_N_per_m"]
    return Contribution(dq=dq)


def leverstiff_features(p, ctx, hw):
    lev = {lv["joint"]: lv for lv in p}
    return np.array([ctx.joint_feature(j, _lever_signal(lev[j], ctx) if j in lev else ctx.loads[:, j])
                     for j in range(ctx.chain.n)])


def leverpin_draw(ctx, hw, rng):
    geo = lever_geometry(ctx, hw, rng)
    for lv in geo:
        pin, length = LEVER[ctx.chain.name][4:]
        lv["d_m"] = np.r_[rng.choice([-1, 1], 2) * rng.uniform(*pin, 2),
                          rng.choice([-1, 1]) * rng.uniform(*length)] * 1e-3   # dr1, dr2, dL [m]
    return geo


def leverpin_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for lv in p:
        dq[:, lv["joint"]] = lv["d_m"] @ lever_partials(lv, ctx.q[:, lv["joint"]]) / lv["s"]
    return Contribution(dq=dq)


def leverpin_features(p, ctx, hw):
    if not p:
        return np.zeros((0, len(ctx.q), 3))
    return np.array([ctx.joint_feature(lv["joint"], d / lv["s"]) for lv in p
                     for d in lever_partials(lv, ctx.q[:, lv["joint"]])])


# ------------------------------------------------------------------------------------------ worn zones
def wear_draw(ctx, hw, rng):
    out = []
    for j in np.flatnonzero(ctx.chain.revolute):
        z = {"joint": int(j), "b0": rng.uniform(0.3, 1.0) * ph.ARCMIN, "h": rng.uniform(0.1, 0.4) * ph.ARCMIN,
             "preload": rng.uniform(0.02, 0.08) * hw["drives"][j]["T_rated"], "centre": np.zeros(0)}
        if j < 3:  # the main axes: two worn sectors inside the used range
            z.update(centre=rng.uniform(*np.quantile(ctx.q[:, j], [0.1, 0.9]), 2),
                     width=np.deg2rad(rng.uniform(5, 20, 2)), w=rng.uniform(0.5, 2.5, 2) * ph.ARCMIN)
        out.append(z)
    return out


def _wear_signals(z, ctx):
    """Flank (P,), flank x each zone's shape (k, P), direction (P,)."""
    j = z["joint"]
    d = ctx.session.direction[:, j]
    flank = ph.backlash_offset(d, ctx.loads[:, j], z["preload"], 2.0, 0.0)
    zones = [flank * np.exp(-0.5 * ((ctx.q[:, j] - c) / s) ** 2) for c, s in zip(z["centre"], z.get("width", []))]
    return flank, zones, d


def wear_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for z in p:
        flank, zones, d = _wear_signals(z, ctx)
        dq[:, z["joint"]] = flank * z["b0"] / 2 + sum(w / 2 * g for w, g in zip(z.get("w", []), zones)) - d * z["h"] / 2
    return Contribution(dq=dq)


def wear_features(p, ctx, hw):
    cols = []
    for z in p:
        flank, zones, d = _wear_signals(z, ctx)
        cols += [ctx.joint_feature(z["joint"], s) for s in [flank, *zones, d]]
    return np.array(cols)


# ---------------------------------------------------------------------------------------- brake at standstill
def brake_draw(ctx, hw, rng):
    out = []
    for j in np.flatnonzero(ctx.chain.revolute):
        d = hw["drives"][j]
        N = int(rng.choice([80, 100, 120, 160] if d["kind"] == "HD" else [101, 121, 141, 161]))
        out.append({"joint": int(j), "ratio": N, "c_motor": np.deg2rad(rng.uniform(0.5, 2.0)),
                    "drag": rng.uniform(0.005, 0.02) * d["T_rated"]})
    return {"t_brake_s": rng.uniform(3.5, 7.0), "joints": out}


def brake_signal(p, b, ctx):
    """(sign(tau) + d) on braked poses whose load beats the drag, else 0 (P,): output offset per c / 2N."""
    s, j = ctx.session, b["joint"]
    tau = ctx.loads[:, j]
    on = (s.dwell_s > p["t_brake_s"]) & (np.abs(tau) > b["drag"])
    return np.where(on, np.sign(tau) + s.direction[:, j], 0.0)


def brake_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    for b in p["joints"]:
        dq[:, b["joint"]] = b["c_motor"] / (2 * b["ratio"]) * brake_signal(p, b, ctx)
    return Contribution(dq=dq)


def brake_features(p, ctx, hw):
    return np.array([ctx.joint_feature(b["joint"], brake_signal(p, b, ctx)) for b in p["joints"]])


# ----------------------------------------------------------------------------------------- tape-scale encoder
TAPE_R_MM = {"ur10": (50.0, 90.0), "kr16_like": (80.0, 150.0), "tool_changer": (120.0, 250.0)}  # drum radius


def tape_draw(ctx, hw, rng):
    out = []
    for j in np.flatnonzero(ctx.chain.revolute[:3]):
        R, g = rng.uniform(*TAPE_R_MM[ctx.chain.name]), rng.uniform(0.01, 0.05)
        out.append({"joint": int(j), "R_mm": R, "gap_mm": g, "eps": g / (TWO_PI * R),
                    "theta_g": rng.uniform(0, TWO_PI)})
    return out


def tape_signal(t, ctx):
    """Angle past the butt joint (P,) [rad] in [0, 2 pi): the reading runs fast by eps times it."""
    return np.mod(ctx.q[:, t["joint"]] - t["theta_g"], TWO_PI)


def tape_apply(p, ctx, hw):  # the controller servoes the reading: the true angle is off by minus its error
    dq = np.zeros_like(ctx.q)
    for t in p:
        dq[:, t["joint"]] = -t["eps"] * tape_signal(t, ctx)
    return Contribution(dq=dq)


def tape_features(p, ctx, hw):
    return np.array([ctx.joint_feature(t["joint"], tape_signal(t, ctx)) for t in p])
