"""Set ZK body effects (new physics, not in sets A-ZJ): the arm's base on the top flange of a single open-section
steel beam that twists about its own axis; the base's pads creeping into an asphalt yard whose binder softens as the
sun warms the pavement; a folded sheet-metal bracket carrying the gripper whose free flange buckles when bending puts
it in compression; and a tool on an axial compliance slide damped by a hydraulic dashpot. Same protocol as
:mod:`effects_joint`.

Sources:

* beam torsion (``beam_torsion``): the arm's base plate bolted at mid-span to the top flange of a single rolled I-beam
  (a mezzanine edge beam or a platform girder, span 3-6 m along a heading e, its ends held against twist); the
  component of the arm's gravity moment about e is a concentrated torque at mid-span, which an open section carries
  by St Venant and warping torsion, theta = M_e / k_t (Trahair, *Flexural-Torsional Buckling of Structures*, 1993,
  ch. 10; SCI P385, *Design of steel beams in torsion*, 2011; the deck's bracing counted into k_t), about the beam's
  shear centre 120-300 mm below the base; the beam also sinks under the weight, W L^3 / (48 EI) (HEA 200-300, I of
  3.7e-5-1.8e-4 m^4; its bending slope under the moment's other component is negligible). The twist sized to
  0.25-0.6 mm, the sink in its physical ratio to it. The arm moves parts of up to its rated payload, changed between
  blocks. (First with the session's own payload schedule: ZK11 on tool_changer 7.8 % with the link model at 1.08x and
  kr16_like's ZK21 19.8 % with the transmission model at 1.22x -- the base's fixed tilt absorbs the moment's mean, and
  over a +-60 or +-90 deg turn of axis 1 little else is left; now with a part per block, on tool_changer and on ur10,
  whose axis 1 turns the moment through +-170 deg.) Unlike set I's floor beams (two beams bending under the feet) or
  the base kind's plate (a tilt about two axes), the support twists about one fixed line. Driven by the pose and the
  payload (logged). The true structure: one column (twist plus sink), amplitude 1 / k_t.
* asphalt creep (``asphalt_creep``): an arm on a mobile or temporary base standing on four steel pads on an asphalt
  yard; asphalt creeps under sustained pad pressure (static indentation of asphalt: EN 12697-20 / -21; Read &
  Whiteoak, *The Shell Bitumen Handbook*, 5th ed., 2003, ch. 8), at a rate following its binder's viscosity, which
  falls about e-fold per 4-8 K (Arrhenius / WLF: Ferry, *Viscoelastic Properties of Polymers*, 1980, ch. 11); the sun
  warms the pavement by 5-15 K with tau 1-3 h from the session's start (unlogged). Each pad sinks at a rate
  proportional to its load, W / 4 plus the moment's share (pads at +-a, a 0.25-0.4 m; a linear viscous Winkler bed,
  assumed), so the base sinks by W / 4 and tilts about the moment's axis by M / (4 a^2), both integrated over the
  history with the fluidity exp((T - T0) / T_e); in the pauses the arm stands at its last pose. Sized to 0.25-0.6 mm.
  Unlike set D's pad creep (an elastomer's bounded Zener creep), set J's grout creep (concrete's power law) or set
  ZI's gravel ratchet (densification per move), the pavement flows without bound at a rate set by its temperature.
  Driven by the pose, the payload and the time (logged) and the pavement's temperature (not logged). The true
  structure: one column, amplitude the creep per unit load and fluidity.
* flange buckling (``flange_buckling``): a folded sheet-metal bracket (an angle of 1-1.5 mm steel, 220 mm along the
  tool's z) carries the gripper, the part and the target at its end; bending by the part's weight across it (along the
  tool's x) puts its free flange in compression one way, and beyond the flange's local buckling stress it loses
  stiffness (post-buckling stiffness of a plate with a free edge some 0.4-0.5 of the pre-buckling one: Koiter, 1945;
  Bulson, *The Stability of Flat Plates*, 1970; effective widths: Winter, 1947, EN 1993-1-5), while the other way the
  flange is in tension and the bracket stays stiff: delta = c0 (F + (1 / rho - 1) (F - F_cr)_+), rho 0.5-0.8 for the
  bracket's bending, F_cr 20-50 % of the session's largest compressive load. Parts of 0.5-3 / 1-5 / 5-30 kg (ur10 /
  kr16_like / tool_changer) changed between blocks; sized to 0.25-0.6 mm. Unlike set R's web buckling (shear, the
  same either way) or set ZG's beam-column (amplification by an axial load), the stiffness changes with the sign of the
  bending. Driven by the attitude and the payload (logged). The true structure: one column, amplitude c0.
* dashpot slide (``dashpot_slide``): a tool on an axial compliance slide (spring rate k) with a hydraulic dashpot in
  parallel -- a Kelvin-Voigt element, delay time tau = c / k of 5-30 s (compliance units with dampers for deburring
  and insertion: Whitney, *Mechanical Assemblies*, 2004, ch. 10; Kelvin-Voigt model: Findley, Lai & Onaran, *Creep
  and Relaxation of Nonlinear Viscoelastic Materials*, 1976, ch. 5); the carriage, the part and the target (120 mm
  along the tool's z) are pushed along the slide by their weight's component along it, x = F / k lagged by tau: over
  each move and dwell the slide relaxes towards the new pose's load, over a pause towards the parked one's. Parts of
  0.5-3 / 1-5 / 5-30 kg changed between blocks (and a carriage of 0.3-1 kg); sized to 0.25-0.6 mm. Unlike set T's
  plunger stiction (a friction play operator), set ZD's soft float (an instantaneous spring) or set ZA's tool recoil
  (viscoelastic mounts thrown by the deceleration), the slide lags its weight's history. Driven by the attitude, the
  payload and the time (logged). The true structure: one column, amplitude 1 / k.
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import kinematics as kin
from sim2real_indep.context import Contribution
from sim2real_indep.effects_body import mount_moment
from sim2real_indep.effects_ze_joint import _size
from sim2real_indep.effects_zi_body import gravity_in_tool, tool_frame

G = kin.G
BRACKET_MM = 220.0   # the buckling bracket: the target at its end, along the tool's z
SLIDE_MM = 120.0     # the dashpot slide: the target on its carriage, along the tool's z
Z = np.array([0.0, 0.0, 1.0])


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def total_weight(ctx):
    """(P,) the arm's and the payload's weight [N]."""
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * G


# ---------------------------------------------------------------------------------------------------- beam torsion
def beam_axis(p):
    return np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])


def beam_draw(ctx, hw, rng):
    L = rng.uniform(3.0, 6.0)
    I = np.exp(rng.uniform(np.log(3.7e-5), np.log(1.8e-4)))
    p = {"psi": rng.uniform(0, np.pi), "depth_mm": rng.uniform(120.0, 300.0)}
    # the sink per N over the twist per N m: (L^3 / 48 EI) / (1 / k_t), k_t of the braced beam 0.5-3e6 N m/rad
    p["sink_ratio_m2"] = L ** 3 / (48 * 210e9 * I) * np.exp(rng.uniform(np.log(5e5), np.log(3e6)))
    p["c"] = float(_size(beam_features(p, ctx, hw), [1.0], rng)[0])
    return p


def beam_features(p, ctx, hw):
    e = beam_axis(p)
    Me = mount_moment(ctx) @ e
    twist = np.cross(Me[:, None] * e, ctx.target - np.array([0.0, 0.0, -p["depth_mm"]]))
    sink = -1000.0 * p["sink_ratio_m2"] * total_weight(ctx)[:, None] * Z
    return (twist + sink)[None]


def beam_apply(p, ctx, hw):
    return _amp_apply([p["c"]], beam_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- asphalt creep
def fluidity(p, session):
    """(P,) the binder's fluidity at each pose's time: exp((T(t) - T0) / T_e), T rising by dT with tau_sun."""
    t = session.time_s - session.time_s[0]
    return np.exp(p["dT_K"] * (1 - np.exp(-t / p["tau_sun_s"])) / p["Te_K"])


def creep_integrals(p, ctx):
    """(P, 3) the moment and (P,) the weight integrated with the fluidity [N m s, N s] over the history: over a gap the
    arm stands at the previous pose, over the move and dwell at the new one."""
    s = ctx.session
    M, W, phi = mount_moment(ctx), total_weight(ctx), fluidity(p, s)
    IM, IW = np.zeros_like(M), np.zeros(len(W))
    for k in range(1, len(W)):
        g = abs(s.gap_s[k])
        dt = s.time_s[k] - s.time_s[k - 1] - g
        f = 0.5 * (phi[k] + phi[k - 1])
        IM[k] = IM[k - 1] + f * (g * M[k - 1] + dt * M[k])
        IW[k] = IW[k - 1] + f * (g * W[k - 1] + dt * W[k])
    return IM, IW


def asphalt_draw(ctx, hw, rng):
    p = {"a_m": rng.uniform(0.25, 0.4), "pad_mm": rng.uniform(50.0, 200.0), "dT_K": rng.uniform(5.0, 15.0),
         "Te_K": rng.uniform(4.0, 8.0), "tau_sun_s": 3600 * rng.uniform(1.0, 3.0)}
    p["c"] = float(_size(asphalt_features(p, ctx, hw), [1.0], rng)[0])
    return p


def asphalt_features(p, ctx, hw):
    IM, IW = creep_integrals(p, ctx)
    IM = IM * np.array([1.0, 1.0, 0.0])  # the pads resist the moment's horizontal part
    pivot = np.array([0.0, 0.0, -p["pad_mm"]])
    tilt = np.cross(IM / (4 * p["a_m"] ** 2), ctx.target - pivot)  # [rad per unit c] x [mm]
    sink = -1000.0 * (IW / 4)[:, None] * Z                         # [m per unit c] -> mm
    return (tilt + sink)[None]


def asphalt_apply(p, ctx, hw):
    return _amp_apply([p["c"]], asphalt_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- flange buckling
def cross_load(ctx):
    """(P,) the part's weight across the bracket, along the tool's x [N] (positive: the free flange in
    compression)."""
    return ctx.session.payload_kg * G * gravity_in_tool(tool_frame(ctx))[:, 0]


def buckle_draw(ctx, hw, rng):
    F = cross_load(ctx)
    p = {"rho": rng.uniform(0.5, 0.8), "F_cr": float(max(F.max(), 1e-6) * rng.uniform(0.2, 0.5))}
    p["c0"] = float(_size(buckle_features(p, ctx, hw), [1.0], rng)[0])
    return p


def buckle_law(p, F):
    """The tip's deflection per unit c0: F + (1 / rho - 1) (F - F_cr)_+."""
    return F + (1 / p["rho"] - 1) * np.maximum(F - p["F_cr"], 0.0)


def buckle_features(p, ctx, hw):
    Rt = tool_frame(ctx)
    return (Rt[:, :, 0] * buckle_law(p, cross_load(ctx))[:, None])[None]


def buckle_apply(p, ctx, hw):
    return _amp_apply([p["c0"]], buckle_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- dashpot slide
def axial_load(p, ctx):
    """(P,) the carriage's and the part's weight along the slide (the tool's z) [N]."""
    m = ctx.session.payload_kg + p["carriage_kg"]
    return m * G * gravity_in_tool(tool_frame(ctx))[:, 2]


def kelvin_voigt(p, session, F):
    """(P,) the slide's position per unit 1 / k: settled at the first pose, then relaxing towards the held pose's load
    with tau over each gap (the previous pose) and each move and dwell (the new pose)."""
    x = np.empty(len(F))
    x[0] = F[0]
    for k in range(1, len(F)):
        g = abs(session.gap_s[k])
        dt = session.time_s[k] - session.time_s[k - 1] - g
        y = F[k - 1] + (x[k - 1] - F[k - 1]) * np.exp(-g / p["tau_s"])
        x[k] = F[k] + (y - F[k]) * np.exp(-dt / p["tau_s"])
    return x


def dashpot_draw(ctx, hw, rng):
    p = {"tau_s": rng.uniform(5.0, 30.0), "carriage_kg": rng.uniform(0.3, 1.0)}
    p["inv_k"] = float(_size(dashpot_features(p, ctx, hw), [1.0], rng)[0])
    return p


def dashpot_features(p, ctx, hw):
    x = kelvin_voigt(p, ctx.session, axial_load(p, ctx))
    return (tool_frame(ctx)[:, :, 2] * x[:, None])[None]


def dashpot_apply(p, ctx, hw):
    return _amp_apply([p["inv_k"]], dashpot_features(p, ctx, hw))
