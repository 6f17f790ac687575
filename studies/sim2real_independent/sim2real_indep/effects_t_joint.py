"""Set T joint effects (new physics, not in sets A-S): a heavy charging cable lying on the floor and rising to a clamp
on the tool, whose hanging length, and so its weight on the tool, grows with the clamp's height; axis 2's hydropneumatic
balancer losing its gas through a worn seal during the session; a dress-pack hose pulled back by a retract unit through
a guide ring on the turret, whose capstan friction on the ring raises or lowers the pull by the hose's last sliding
direction; the lost motion of the joints whose flank a hidden Cartesian approach move chooses (each pose reached by a
short linear move along a direction fixed in the tool); tool_changer's boom joints read by gravity-referenced MEMS
inclinometers on the links; and its telescopic stage read by a phase-comparison laser rangefinder. Same protocol as
:mod:`effects_joint` (``draw``, ``apply``, ``features``).

Sources:

* charging cable: an inextensible cable of weight w per length lying on a floor with a horizontal back-tension H (the
  spring retractor of a charger's cable management) leaves the floor at its touchdown point and hangs as a catenary up
  to the clamp at height h above the floor; its suspended length is s = sqrt(h^2 + 2 a h), a = H / w, its horizontal
  reach a acosh(1 + h / a), and it pulls the clamp down by w s and towards the touchdown point by H (the catenary with
  a touchdown point: Irvine, *Cable Structures*, 1981, ch. 1; the same relation serves mooring lines, e.g. Faltinsen,
  *Sea Loads on Ships and Offshore Structures*, 1990, ch. 8). Unlike set G's hose hung between two fixed points, the
  weight carried grows with the clamp's height. Liquid-cooled DC charging cables of 1.5-3 / 2.5-4.5 kg/m on the ur10 /
  kr16_like charging robots (as recalled from high-power charging cable data), back-tension 5-20 / 10-40 N, the floor
  0.4-0.9 / 0-0.4 m below the base (a table / a low pedestal), the charger 1.5-3 m aside, the clamp 30-80 mm off the
  tool axis and 20-80 mm along it (assumed). Joint loads tau = J^T F (Craig, *Introduction to Robotics*, ch. 5), every
  joint twisting with the linear gear stiffness of :mod:`hardware`; the gravity twist is set A's and left out. The true
  structure: one column, amplitude w.
* balancer gas leak: a hydropneumatic balancer (a cylinder between the turret and a lug on the upper arm, its gas in an
  accumulator) pushes with F = p A, its gas polytropic in the stroke, p ~ m (V0 / V)^n; a worn rod seal lets the gas
  escape at a mass rate proportional to the pressure (laminar leakage: Merritt, *Hydraulic Control Systems*, 1967,
  ch. 4), so m(t) = m0 exp(-t / tau) and the balancing torque F dL/dq2 (virtual work; the lever by the law of cosines)
  falls by the same factor; the gear of axis 2 twists by the lost share. Pivot 150-300 / 250-400 mm from axis 2, lug
  300-500 / 500-800 mm out (kr16_like / tool_changer), 70-110 deg between them at mid-range, a gas column 1.5-3 times
  the stroke's compression plus 50 mm, n 1.0-1.3, the push at the session's most loaded pose 60-90 % of the gravity
  torque there, a seal that loses 20-45 % of the gas over the session (a failing seal; assumed; first a column of
  0.3-0.8 m, a share of 40-70 % and 5-20 % lost: 0.03 mm on kr16_like, absorbed). The balancer's torque at the
  session's start is set D's gas spring and left out. The true structure: one column, amplitude F_ref (the push at
  mid-stroke).
* hose capstan: the dress-pack hose runs from a retract unit on the turret up through a guide ring and down to a clamp
  on the tool; the unit pulls with F0. A hose sliding round the ring's lip with wrap angle theta carries F0 exp(mu
  theta) on the clamp's side while it is pulled out and F0 exp(-mu theta) while the unit draws it in (Euler-Eytelwein
  belt friction: Johnson, *Contact Mechanics*, 1985, ch. 7; Shigley's *Mechanical Engineering Design*, band brakes);
  after a stop static friction keeps the tension of the last sliding direction. The pull acts between the turret and
  the tool, on joints 2-6. F0 40-100 / 80-200 / 150-400 N (ur10 / kr16_like / tool_changer; first 30-80 N on ur10), the
  ring 300-600 / 400-700 / 500-900 mm above axis 2's point, mu 0.15-0.35 (a polyurethane hose on a polished ring), the
  hose rising vertically from the unit to the ring (assumed). The frictionless pull is set J's retraction and left out.
  The last sliding direction (the clamp's distance from the ring grown or shrunk by more than 1 mm in the last move) is
  computed once from the true poses (a shape parameter). The true structure: one column, amplitude F0.
* hidden approach: robot programs reach a taught point by a short linear move from an approach point set back along a
  direction fixed in the tool (the pick-and-place idiom: approach from above, then descend); a measurement program
  built on such points makes every joint's last motion the approach's, sign(J^-1 v) with v the approach velocity and no
  rotation (resolved rates: Whitney, "Resolved motion rate control of manipulators and human prostheses", IEEE Trans.
  Man-Mach. Syst. 10(2), 1969), while the controller's log records the pose-to-pose direction. The lost motion's flank
  then follows :func:`physics.backlash_offset` with the approach's direction: the gravity flank where the load beats the
  output-side drag, else the approach's trailing flank (Nordin & Gutman, Automatica 38, 2002). Worn gears of 0.8-2
  arcmin (strain-wave) or 0.6-1.5 arcmin (cycloid), drag 1-3 % of the rated torque, approaches of 20-60 mm within 35 deg
  of the tool axis from either side (assumed). The flank is computed once from the true loads (a shape parameter). The
  true structure: a column per revolute joint, amplitude its lost motion.
* inclinometers: hydraulic booms and tool changers read their boom angles with gravity-referenced MEMS inclinometers on
  the links, each giving the link's absolute pitch a = atan2(a_x, a_z) of two accelerometer channels; channel offsets
  b_x, b_z, a gain mismatch kappa and a non-orthogonality nu leave an error b_x cos a - b_z sin a - (nu / 2) cos 2a -
  (kappa / 2) sin 2a (+ const) (Fisher, "Using an accelerometer for inclination sensing", Analog Devices AN-1057, 2010;
  Luczak, Oleksiuk & Bodnicki, "Sensing tilt with MEMS accelerometers", IEEE Sensors J. 6(6), 2006). The controller
  takes the joint angles as differences of neighbouring links' readings (q2 = r2, q3 = r3 - r2, q5 = r5 - r3 on the
  boom, forearm and wrist of tool_changer, whose axes 2, 3 and 5 are parallel) and servoes them, so joint 3 is off by
  the difference of two sensors' errors at two absolute angles. Residuals after the makers' calibration: offsets
  0.5-2e-4 (50-200 ug), gain 0.5-2e-3, non-orthogonality 0.5-3e-4 rad, each N(0, that) per sensor (assumed; the gain
  mismatch tried at 2e-4 - 1e-3 left the offsets' once-per-turn term, which the link model copies as a gravity sag
  cos a, dominant: 1.20x in a trial draw). tool_changer only. The true structure: four columns per sensor, amplitudes
  its four coefficients.
* rangefinder: the telescopic stage of tool_changer read by a phase-comparison laser distance sensor on the outer
  section aimed at a reflector on the inner one; the phase measurement's electrical cross-talk leaves cyclic errors with
  the fine measuring unit U (half the fine modulation wavelength) and U / 2 (Ruger, *Electronic Distance Measurement*,
  4th ed., 1996, on cyclic errors; Kahmen & Faig, *Surveying*, 1988). The stage servoes the reading, so it stands off by
  -e(d0 + q4). U 0.5-1 m (fine modulation 150-300 MHz), amplitudes 0.2-0.6 and 0.05-0.2 mm (industrial sensors'
  linearity of +-1-2 mm), d0 0.3-0.9 m (assumed). The true structure: four columns (sine and cosine of both orders).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep import physics as ph
from sim2real_indep.context import Contribution
from sim2real_indep.effects_s_joint import compliance
from sim2real_indep.session import BOXES


def _empty(ctx):
    return np.zeros((0, len(ctx.q), 3))


def force_loads(ctx, point, F, first=0):
    """Joint loads (P, n) [N m / N] of forces F (P, 3) [N] at ``point`` (P, 3) [mm]; zero on the joints before
    ``first`` (an internal force between body ``first`` and the tool)."""
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    out = np.zeros(ctx.q.shape)
    for j in range(first, ctx.chain.n):
        arm = np.cross((point - c[:, j]) / 1000.0, F) if ctx.chain.revolute[j] else F
        out[:, j] = np.einsum("pi,pi->p", arm, w[:, j])
    return out


def twist_displacement(ctx, hw, loads):
    """(P, 3): the target's displacement [mm] when every joint twists with its linear compliance under ``loads``."""
    return np.einsum("pij,pj->pi", ctx.jac, loads * compliance(hw))


def _tool_point(ctx, offset):
    fl, Rt = kin.flange(ctx.chain, ctx.q)
    return fl + Rt @ offset


# ---------------------------------------------------------------------------------------------- charging cable
CABLE = {"ur10": ((1.5, 3.0), (5.0, 20.0), (400.0, 900.0)), "kr16_like": ((2.5, 4.5), (10.0, 40.0), (0.0, 400.0))}


def cable_draw(ctx, hw, rng):
    if ctx.chain.name not in CABLE:
        return {}
    w, H, floor = CABLE[ctx.chain.name]
    az, b = rng.uniform(0, 2 * np.pi, 2)
    off = rng.uniform(30.0, 80.0)
    p = {"w_N_m": rng.uniform(*w) * kin.G, "H0_N": rng.uniform(*H), "z_floor": -rng.uniform(*floor),
         "charger": rng.uniform(1500.0, 3000.0) * np.array([np.cos(az), np.sin(az)]),
         "clamp": np.array([off * np.cos(b), off * np.sin(b), rng.uniform(20.0, 80.0)])}
    p["a_m"] = p["H0_N"] / p["w_N_m"]                                  # catenary parameter [m]
    return p


def cable_force(p, ctx):
    """(P, 3) the cable's pull on the clamp per unit weight per length [N per N/m = m], and the clamp (P, 3) [mm]."""
    A = _tool_point(ctx, p["clamp"])
    h = np.maximum(A[:, 2] - p["z_floor"], 1.0) / 1000.0                # height above the floor [m]
    s = np.sqrt(h ** 2 + 2 * p["a_m"] * h)                               # suspended length [m]
    d = p["charger"] - A[:, :2]
    u = d / np.linalg.norm(d, axis=1, keepdims=True)
    return np.c_[p["a_m"] * u, -s], A


def cable_shape(p, ctx, hw):
    F, A = cable_force(p, ctx)
    return twist_displacement(ctx, hw, force_loads(ctx, A, F))


def cable_apply(p, ctx, hw):
    if not p:
        return Contribution(dq=np.zeros_like(ctx.q))
    F, A = cable_force(p, ctx)
    return Contribution(dq=p["w_N_m"] * force_loads(ctx, A, F) * compliance(hw))


def cable_features(p, ctx, hw):
    return cable_shape(p, ctx, hw)[None] if p else _empty(ctx)


# ------------------------------------------------------------------------------------------- balancer gas leak
BALANCER = {"kr16_like": ((150.0, 300.0), (300.0, 500.0)), "tool_changer": ((250.0, 400.0), (500.0, 800.0))}


def balancer_length(p, q2):
    """The balancer's pin-to-pin length [mm] and dL/dq2 [mm/rad] (law of cosines)."""
    psi = p["psi_mid"] + p["sense"] * (np.asarray(q2, float) - p["q_mid"])
    L = np.sqrt(p["r1"] ** 2 + p["r2"] ** 2 - 2 * p["r1"] * p["r2"] * np.cos(psi))
    return L, p["sense"] * p["r1"] * p["r2"] * np.sin(psi) / L


def balancer_torque(p, q2):
    """(P,): the balancer's torque on axis 2 per unit push at mid-stroke [N m per N]: (V0 / V)^n dL/dq2, signed."""
    L, dL = balancer_length(p, q2)
    V = p["column_mm"] - (p["L_mid"] - L)                              # gas column [mm]
    return p["sign"] * (p["column_mm"] / V) ** p["n"] * dL / 1000.0


def leak_signal(p, session):
    """(P,): the gas lost since the session's first pose, exp(-t / tau) - 1 (<= 0)."""
    return np.exp(-(session.time_s - session.time_s[0]) / p["tau_s"]) - 1.0


def leak_draw(ctx, hw, rng):
    if ctx.chain.name not in BALANCER:
        return {}
    (r1, r2), box = BALANCER[ctx.chain.name], BOXES[ctx.chain.name]
    lo, hi = np.deg2rad(box[0][1]), np.deg2rad(box[1][1])
    p = {"r1": rng.uniform(*r1), "r2": rng.uniform(*r2), "psi_mid": np.deg2rad(rng.uniform(70.0, 110.0)),
         "q_mid": 0.5 * (lo + hi), "sense": float(rng.choice([-1.0, 1.0])), "n": rng.uniform(1.0, 1.3),
         "sign": 1.0}
    L = balancer_length(p, np.linspace(lo, hi, 101))[0]
    p["L_mid"] = balancer_length(p, p["q_mid"])[0]
    p["column_mm"] = (p["L_mid"] - L.min()) * rng.uniform(1.5, 3.0) + 50.0   # the gas never fully compressed
    tau, shape = ctx.loads[:, 1], balancer_torque(p, ctx.q[:, 1])
    k = int(np.argmax(np.abs(tau)))
    p["sign"] = -np.sign(tau[k]) * np.sign(shape[k])                   # it holds the arm up where gravity pulls most
    p["F_ref"] = rng.uniform(0.6, 0.9) * abs(tau[k]) / abs(shape[k])
    span = ctx.session.time_s[-1] - ctx.session.time_s[0]
    p["tau_s"] = span / -np.log(1 - rng.uniform(0.2, 0.45))
    return p


def leak_twist(p, ctx, hw):
    """(P,): axis 2's twist per unit push [rad per N]."""
    return compliance(hw)[1] * balancer_torque(p, ctx.q[:, 1]) * leak_signal(p, ctx.session)


def leak_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, 1] = p["F_ref"] * leak_twist(p, ctx, hw)
    return Contribution(dq=dq)


def leak_features(p, ctx, hw):
    return ctx.joint_feature(1, leak_twist(p, ctx, hw))[None] if p else _empty(ctx)


# ------------------------------------------------------------------------------------------------ hose capstan
CAPSTAN = {"ur10": ((40.0, 100.0), (300.0, 600.0)), "kr16_like": ((80.0, 200.0), (400.0, 700.0)),
           "tool_changer": ((150.0, 400.0), (500.0, 900.0))}
RING_BODY = 1  # the turret carries the retract unit and its ring


def capstan_points(p, ctx):
    """Ring (on the turret) and clamp (on the tool) (P, 3) [mm]; the hose's rising direction at the ring (P, 3)."""
    R, t = kin.body_transforms(ctx.chain, ctx.q)
    ring = np.einsum("pij,j->pi", R[:, RING_BODY], p["ring_home"]) + t[:, RING_BODY]
    return ring, _tool_point(ctx, p["clamp"]), R[:, RING_BODY, :, 2]


def capstan_wrap(p, ctx):
    """(P,) the wrap angle on the ring's lip [rad] and the unit pull on the clamp towards the ring (P, 3)."""
    ring, clamp, up = capstan_points(p, ctx)
    d = ring - clamp
    u = d / np.linalg.norm(d, axis=1, keepdims=True)
    return np.arccos(np.clip(np.einsum("pi,pi->p", up, -u), -1.0, 1.0)), u


def capstan_state(p, ctx):
    """(P,) +1 where the hose was last pulled out (the clamp moved away from the ring), -1 where drawn in."""
    ring, clamp, _ = capstan_points(p, ctx)
    ell = np.linalg.norm(clamp - ring, axis=1)
    s, prev = np.empty(len(ell)), p["s0"]
    for i in range(len(ell)):
        if i and abs(ell[i] - ell[i - 1]) > 1.0:
            prev = np.sign(ell[i] - ell[i - 1])
        s[i] = prev
    return s


def capstan_draw(ctx, hw, rng):
    F0, height = CAPSTAN[ctx.chain.name]
    ch = ctx.chain
    off = rng.normal(0.0, 50.0, 2)
    a, o = rng.uniform(0, 2 * np.pi), rng.uniform(50.0, 120.0)
    p = {"ring_home": ch.points()[1] + np.r_[off, rng.uniform(*height)], "F0_N": rng.uniform(*F0),
         "mu": rng.uniform(0.15, 0.35), "s0": float(rng.choice([-1.0, 1.0])),
         "clamp": np.array([o * np.cos(a), o * np.sin(a), rng.uniform(30.0, 100.0)])}
    p["s"] = capstan_state(p, ctx)
    return p


def capstan_loads(p, ctx):
    """(P, n): joint loads per unit retract force [N m per N] of the capstan's share, F0 (exp(s mu theta) - 1)."""
    theta, u = capstan_wrap(p, ctx)
    _, clamp, _ = capstan_points(p, ctx)
    F = (np.exp(p["s"] * p["mu"] * theta) - 1.0)[:, None] * u
    return force_loads(ctx, clamp, F, first=RING_BODY)


def capstan_apply(p, ctx, hw):
    return Contribution(dq=p["F0_N"] * capstan_loads(p, ctx) * compliance(hw))


def capstan_features(p, ctx, hw):
    return twist_displacement(ctx, hw, capstan_loads(p, ctx))[None]


# ---------------------------------------------------------------------------------------------- hidden approach
def approach_rates(p, ctx):
    """(P, n): joint rates of the final approach, a unit tool velocity along the approach direction, no rotation."""
    fl, Rt = kin.flange(ctx.chain, ctx.q)
    w, c = kin.joint_frames(ctx.chain, ctx.q)
    rev = ctx.chain.revolute[None, :, None]
    Jv = np.where(rev, np.cross(w, fl[:, None, :] - c), w)             # (P, n, 3)
    Jw = np.where(rev, w, 0.0)
    J = np.concatenate([Jv, Jw], axis=2).transpose(0, 2, 1)             # (P, 6, n)
    v = np.c_[Rt @ p["a_tool"], np.zeros((len(ctx.q), 3))]
    return np.array([np.linalg.lstsq(Ji, vi, rcond=1e-9)[0] for Ji, vi in zip(J, v)])


def approach_flank(p, tau, ctx):
    """(P, m): the output's place in the lost motion, in its units: the gravity flank +-1/2 where the load beats the
    drag, else the approach's trailing flank -d/2 (d the approach's direction; the logged one where the joint hardly
    moves in the approach)."""
    js = p["joints"]
    rates = approach_rates(p, ctx)[:, js] * p["d_mm"]
    d = np.where(np.abs(rates) > p["b"], np.sign(rates), ctx.session.direction[:, js])
    return np.where(np.abs(tau) > p["drag"], 0.5 * np.sign(tau), -0.5 * d)


def approach_draw(ctx, hw, rng):
    js = [j for j in range(ctx.chain.n) if ctx.chain.revolute[j]]
    hd = np.array([hw["drives"][j]["kind"] == "HD" for j in js])
    b = np.where(hd, rng.uniform(0.8, 2.0, len(js)), rng.uniform(0.6, 1.5, len(js))) * ph.ARCMIN
    tilt, az = np.deg2rad(rng.uniform(0.0, 35.0)), rng.uniform(0, 2 * np.pi)
    a = np.array([np.sin(tilt) * np.cos(az), np.sin(tilt) * np.sin(az), np.cos(tilt) * rng.choice([-1.0, 1.0])])
    p = {"joints": js, "b": b, "a_tool": a, "d_mm": rng.uniform(20.0, 60.0),
         "drag": rng.uniform(0.01, 0.03, len(js)) * np.array([hw["drives"][j]["T_rated"] for j in js])}
    p["flank"] = approach_flank(p, ctx.loads[:, js], ctx)
    return p


def approach_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    dq[:, p["joints"]] = p["b"] * p["flank"]
    return Contribution(dq=dq)


def approach_features(p, ctx, hw):
    return np.array([ctx.joint_feature(j, p["flank"][:, k]) for k, j in enumerate(p["joints"])])


# ---------------------------------------------------------------------------------------------- inclinometers
#: per arm: the joints whose sum is each sensor's absolute pitch (boom, forearm, wrist of tool_changer)
INCLINO = {"tool_changer": ((1,), (1, 2), (1, 2, 4))}


def incl_draw(ctx, hw, rng):
    if ctx.chain.name not in INCLINO:
        return {}
    sensors = INCLINO[ctx.chain.name]
    c = []
    for _ in sensors:
        bx, bz = rng.normal(0.0, rng.uniform(0.5e-4, 2e-4), 2)
        kappa, nu = rng.normal(0.0, rng.uniform(0.5e-3, 2e-3)), rng.normal(0.0, rng.uniform(0.5e-4, 3e-4))
        c.append([bx, -bz, -nu / 2, -kappa / 2])
    return {"sensors": sensors, "c": np.array(c)}


def incl_harmonics(a):
    """(4, P): cos a, sin a, cos 2a, sin 2a."""
    return np.array([np.cos(a), np.sin(a), np.cos(2 * a), np.sin(2 * a)])


def incl_signals(p, q):
    """(m, 4, P, n): each joint's error per unit coefficient of each sensor's error law: the reading r_k = a_k + e_k,
    the joints the readings' differences, servoed (dq = -e_k on the first joint of sensor k, +e_k on the next)."""
    q = np.asarray(q, float)
    S = len(p["sensors"])
    out = np.zeros((S, 4, len(q), q.shape[1]))
    firsts = [s[-1] for s in p["sensors"]]                             # the joint each reading adds
    for k, js in enumerate(p["sensors"]):
        h = incl_harmonics(q[:, list(js)].sum(axis=1))
        out[k, :, :, firsts[k]] -= h
        if k + 1 < S:
            out[k, :, :, firsts[k + 1]] += h
    return out


def incl_apply(p, ctx, hw):
    if not p:
        return Contribution(dq=np.zeros_like(ctx.q))
    return Contribution(dq=np.einsum("kh,khpn->pn", p["c"], incl_signals(p, ctx.q)))


def incl_features(p, ctx, hw):
    if not p:
        return _empty(ctx)
    s = incl_signals(p, ctx.q).reshape(-1, len(ctx.q), ctx.chain.n)
    return np.einsum("pij,mpj->mpi", ctx.jac, s)


# ----------------------------------------------------------------------------------------------- rangefinder
def range_draw(ctx, hw, rng):
    if ctx.chain.name != "tool_changer":
        return {}
    A, phi = np.r_[rng.uniform(0.2, 0.6), rng.uniform(0.05, 0.2)], rng.uniform(0, 2 * np.pi, 2)
    return {"joint": 3, "d0": rng.uniform(300.0, 900.0), "U": rng.uniform(500.0, 1000.0),
            "amp": np.r_[A * np.cos(phi), A * np.sin(phi)]}


def range_signals(p, q):
    """(4, P): the stage's error per unit amplitude [mm/mm]: -(sin, sin 2x, cos, cos 2x) of the reading's phase."""
    x = 2 * np.pi * (p["d0"] + np.asarray(q)[:, p["joint"]]) / p["U"]
    return -np.array([np.sin(x), np.sin(2 * x), np.cos(x), np.cos(2 * x)])


def range_apply(p, ctx, hw):
    dq = np.zeros_like(ctx.q)
    if p:
        dq[:, p["joint"]] = p["amp"] @ range_signals(p, ctx.q)
    return Contribution(dq=dq)


def range_features(p, ctx, hw):
    return np.array([ctx.joint_feature(p["joint"], s) for s in range_signals(p, ctx.q)]) if p else _empty(ctx)
