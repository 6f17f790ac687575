"""Set J thermal effects (new physics, not in sets A-I): a joint housing warmed on one side by its motor and the
motor's holding-brake coil, so that the joint's axis tilts; and carbon-fibre tube links wound with an unbalanced
layup, which twist about their own axes as the hall's air warms them. Same protocol as :mod:`effects_joint`
(``draw``, ``apply``, ``features``).

Sources:

* brake-heated housing: a spring-applied holding brake is released by a coil that dissipates its rated power while
  the servo is on and nothing while it is off (10-20 / 15-35 / 30-60 W on ur10 / kr16_like / tool_changer: the coil
  data of servo-motor brakes in manufacturers' catalogues, as recalled); with a share of 30-70 % of the motor's
  losses (:func:`effects_c_thermal.drive_heat`) it warms the housing's wall on the motor's side more than the
  opposite one. The bearing seats, s apart along the axis, stand on walls of height h: the warmer wall grows alpha h
  dT more, and the axis tilts by alpha h dT / s about the normal to the axis and the walls (differential thermal
  growth of a structure: Bryan, "International status of thermal error research", CIRP Annals 39(2), 1990; ISO 230-3
  on thermal tilts of axes; Mayr et al., "Thermal issues in machine tools", CIRP Annals 61(2), 2012). dT is one
  lumped node (Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, ch. 5) of 15-45 min, 5-15 K at the
  steady state of continuous production (a motor flanged to one side runs at 40-80 degC), from a cold start; the
  brake's heat on in moves, dwells and production, off in the pauses (servo off). h 60-120 / 100-200 / 150-300 mm,
  s 50-90 / 80-150 / 120-220 mm, the walls' direction at random about the axis (assumed); axes 1-3 (first drawn on
  axes 2-3 at 3-10 K with walls lower than the seats' spacing: absorbed in most draws). The housing's axial growth
  is set I's and left out.
* laminate twist: an off-axis ply at theta to the tube's axis has the shear expansion coefficient alpha_xs =
  (alpha_1 - alpha_2) sin(2 theta) (the transformation of the expansion tensor: Jones, *Mechanics of Composite
  Materials*, 2nd ed., 1999, ch. 2; Daniel & Ishai, *Engineering Mechanics of Composite Materials*, 2006: carbon /
  epoxy alpha_1 -0.3..-0.7e-6 /K, alpha_2 25-35e-6 /K). A balanced +-theta winding cancels it; an unbalanced one (a
  share f of the helical plies one-handed, after the balanced rest's restraint, 20-50 %; the layup of set G's
  bend-twist tubes, assumed; first drawn at 10-30 %: gains below 20 % in some draws) leaves f alpha_xs, and a
  thin-walled closed tube whose wall shears by gamma twists by gamma / r per length (Bredt's kinematics). theta 20-45
  deg; the tubes follow the air through a lumped lag of 10-30 min (rho c t / h of 3-6 mm CFRP walls), in a hall whose
  air drifts by 3-6 K. The tube links of 400 mm or more past joint 2. The laminate's axial expansion (near zero) is
  left out: the case isolates the twist.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import effects_body as eb
from sim2real_indep import effects_c_thermal as ct
from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution

ALPHA_HOUSING = {"ur10": 23e-6, "kr16_like": 23e-6, "tool_changer": 11.7e-6}  # the arms' materials (hardware)
#: wall height h, seat spacing s [m]; brake coil power [W] (assumed)
BRAKE = {"ur10": ((0.06, 0.12), (0.05, 0.09), (10.0, 20.0)), "kr16_like": ((0.10, 0.20), (0.08, 0.15), (15.0, 35.0)),
         "tool_changer": ((0.15, 0.30), (0.12, 0.22), (30.0, 60.0))}


# ----------------------------------------------------------------------------------------- brake-heated housing
def brake_draw(ctx, hw, rng):
    ch = ctx.chain
    joints = [int(j) for j in np.flatnonzero(ch.revolute) if j < 3]
    n, m = ch.n, len(joints)
    accel, duty = rng.uniform(0.2, 0.6, n), rng.uniform(0.2, 0.5, n)
    ex_w = ct.drive_heat(ctx, hw, accel, duty, exercise_only=True)
    (h0, h1), (s0, s1), (b0, b1) = BRAKE[ch.name]
    coil, share = rng.uniform(b0, b1, m), rng.uniform(0.3, 0.7, m)
    normals = []
    for j in joints:
        w = ch.axes[j]
        u = np.cross(w, [1.0, 0, 0] if abs(w[0]) < 0.9 else [0, 1.0, 0])
        u /= np.linalg.norm(u)
        a = rng.uniform(0, 2 * np.pi)
        wall = np.cos(a) * u + np.sin(a) * np.cross(w, u)          # the walls' direction, normal to the axis
        normals.append(np.cross(w, wall))
    return {"joints": joints, "accel_s": accel, "duty": duty, "coil_W": coil, "share": share,
            "R_K_per_W": rng.uniform(5.0, 15.0, m) / (coil + share * ex_w[joints]),
            "tau_s": rng.uniform(15, 45, m) * 60,
            "normal_home": np.array(normals),
            "k_rad_per_K": ALPHA_HOUSING[ch.name] * rng.uniform(h0, h1, m) / rng.uniform(s0, s1, m)}


def brake_heat(p, ctx, hw):
    """Heat (P, 3, m) [W] into the motor's side of each housing per segment (gap, move, dwell): the brake coil while
    the servo is on (moves, dwells, production; not in pauses) plus a share of the motor's losses."""
    s = ctx.session
    pw = ct.drive_heat(ctx, hw, p["accel_s"], p["duty"])[:, :, p["joints"]]
    on = np.stack([(s.gap_s > 0).astype(float), np.ones(len(s.q)), np.ones(len(s.q))], axis=1)
    return on[:, :, None] * p["coil_W"] + p["share"] * pw


def brake_rise(p, ctx, hw):
    """Temperature difference (P, m) [K] across each housing at the measurements (cold start, exact for heat held
    over each segment)."""
    dur = ct._segment_times(ctx.session)
    u = (brake_heat(p, ctx, hw) * p["R_K_per_W"]).reshape(-1, len(p["joints"]))
    x, out = np.zeros(len(p["joints"])), np.zeros(u.shape)
    for i, (dt, ui) in enumerate(zip(dur, u)):
        x = ui + (x - ui) * np.exp(-dt / p["tau_s"])
        out[i] = x
    return out[2::3]


def brake_parts(p, ctx, hw):
    """Target displacement (m, P, 3) [mm] per unit tilt per K: the distal chain turned about each housing's tilt axis
    (fixed in the proximal body) through the joint's axis point, times its temperature difference."""
    R, _ = kin.body_transforms(ctx.chain, ctx.q)
    _, c = kin.joint_frames(ctx.chain, ctx.q)
    dT = brake_rise(p, ctx, hw)
    cols = []
    for k, j in enumerate(p["joints"]):
        n = R[:, j] @ p["normal_home"][k]
        cols.append(np.cross(n, ctx.target - c[:, j]) * dT[:, k:k + 1])
    return np.array(cols)


def brake_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", p["k_rad_per_K"], brake_parts(p, ctx, hw)))


def brake_features(p, ctx, hw):
    return brake_parts(p, ctx, hw)


# ------------------------------------------------------------------------------------------------ laminate twist
def _cfrp_tubes(ctx, hw):
    ch = ctx.chain
    return [n for n in hw["tubes"] if ch.link_body[ch.link_names.index(n)] >= 2
            and np.linalg.norm(ch.links[ch.link_names.index(n)]) >= 400.0]


def shear_cte(alpha_1, alpha_2, theta):
    """Shear expansion coefficient [1/K] (engineering shear strain per K) of a ply at ``theta`` [rad] to the axis."""
    return (alpha_1 - alpha_2) * np.sin(2 * theta)


def laminate_draw(ctx, hw, rng):
    links = {}
    for name in _cfrp_tubes(ctx, hw):
        tb = hw["tubes"][name]
        D = np.sqrt((16 * tb["I"] / tb["A"] + 4 * tb["A"] / np.pi) / 2)      # the tube's outer diameter [m]
        d = np.sqrt(max(D * D - 4 * tb["A"] / np.pi, 0.0))
        g = shear_cte(rng.uniform(-0.7e-6, -0.3e-6), rng.uniform(25e-6, 35e-6), np.deg2rad(rng.uniform(20, 45)))
        links[name] = rng.uniform(0.2, 0.5) * g / ((D + d) / 4) * rng.choice([-1, 1])   # twist [rad / (m K)]
    return {"links": links, "tau_s": rng.uniform(10, 30) * 60}


def laminate_parts(p, ctx):
    """Target displacement (links, P, 3) [mm] per unit twist rate [rad / (m K)]: the chain beyond each tube turned
    about the tube's axis by its length times the tube's temperature change since the session start."""
    dT = eb.structure_temperature(p, ctx)[:, None]
    cols = []
    for name in p["links"]:
        e, tip, L = eb._beam_state(ctx, ctx.chain.link_names.index(name))
        cols.append(np.cross(e * L, ctx.target - tip) * dT)
    return np.array(cols) if cols else np.zeros((0, len(ctx.q), 3))


def laminate_apply(p, ctx, hw):
    return Contribution(displace=np.einsum("k,kpi->pi", list(p["links"].values()), laminate_parts(p, ctx)))


def laminate_features(p, ctx, hw):
    return laminate_parts(p, ctx)
