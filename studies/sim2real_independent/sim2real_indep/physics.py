"""Physical laws of the independent benchmark, each from the literature (units: rad, N m, N, m or mm as named).

Written from textbooks, catalogues and papers, not from tolalloc's effect code (which this study never reads):

* strain-wave (harmonic drive) kinematic error -- Tuttle & Seering, "A nonlinear model of a harmonic drive gear
  transmission", IEEE Trans. Robot. Autom. 12(3), 1996; Ghorbel, Gandhi & Alpeter, "On the kinematic error in
  harmonic drive gears", J. Mech. Des. 123(1), 2001: the error repeats twice per wave-generator turn (2N cycles per
  output turn for a ratio N), with smaller components once per wave-generator turn (N per output turn) and once
  per output turn (assembly eccentricity). Harmonic Drive catalogues give the transmission accuracy as the
  peak-to-peak deviation over one output turn: 0.5-1.5 arcmin for the CSF / CSG series.
* encoder eccentricity -- an eccentricity e of a graduated disc of diameter D reads the angle with the error
  (2 e / D) sin(phi - phi0) (HEIDENHAIN, "Angle Encoders" brochure: +-412 e / D arcsec, e in um, D in mm).
* torsion of strain-wave gears -- Harmonic Drive AG catalogue / engineering data ("torsional stiffness K1, K2,
  K3 over the torque regions 0-T1, T1-T2, > T2"; worked example for size 32: T1 = 29 N m, K1 = 6.7e4 N m/rad,
  T2 = 108 N m, K2 = 1.1e5 N m/rad, K3 = 1.2e5 N m/rad, T = 60 N m -> 7.15e-4 rad).
* torsion of cycloid (RV) gears -- Nabtesco RV catalogues: lost motion (about 1 arcmin) measured at +-3 % of the
  rated torque, then a single torsional rigidity.
* beams -- Timoshenko & Gere, *Mechanics of Materials*; Roark's *Formulas for Stress and Strain* (cantilever tip
  deflection F L^3 / 3EI, slope F L^2 / 2EI; end moment M L^2 / 2EI, M L / EI; uniform load w L^4 / 8EI,
  w L^3 / 6EI; shear deflection F L / (k G A), Cowper's k = 2 (1 + nu) / (4 + 3 nu) for a thin-walled tube).
* first-order heating -- lumped-capacitance model (Incropera & DeWitt, *Fundamentals of Heat and Mass
  Transfer*, ch. 5): tau dT/dt = R_th P - T, solved exactly for piecewise-constant or piecewise-linear inputs.
* motor losses -- copper loss R I^2 = P_cu,rated (T / T_rated)^2 with I proportional to torque; friction loss
  T_f |omega| (e.g. Mohan, *Electric Drives*, ch. on losses and thermal rating).
* backlash / lost motion -- dead zone of width b between the two tooth flanks (Nordin & Gutman, "Controlling
  mechanical systems with backlash -- a survey", Automatica 38, 2002), plus the hysteresis loss of the torsion
  curve (Harmonic Drive and Nabtesco catalogues).

Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

ARCMIN = np.pi / (180 * 60)  # [rad]


# ------------------------------------------------------------------------------------------- transmission
def harmonic_drive_error(theta, ratio, amp_rad, phase_rad):
    """Kinematic error of a strain-wave gear [rad] at output angles ``theta`` (P,) [rad].

    ``amp_rad`` / ``phase_rad`` (3,): components at 2N, N and 1 cycles per output turn (N = ``ratio``).
    """
    freqs = np.array([2 * ratio, ratio, 1.0])
    return (np.asarray(amp_rad) * np.sin(np.multiply.outer(theta, freqs) + phase_rad)).sum(axis=-1)


def encoder_eccentricity_error(theta, ecc_um, diameter_mm, phase_rad, cycles_per_output_turn=1.0):
    """Angle reading error [rad] of an eccentric disc (2 e / D) sin(k theta + phase); k = 1 on the output side,
    k = N (and the error divided by N) for a motor-side encoder."""
    return 2e-3 * ecc_um / diameter_mm * np.sin(cycles_per_output_turn * np.asarray(theta) + phase_rad)


# --------------------------------------------------------------------------------------------- stiffness
def harmonic_drive_torsion(torque, T1, T2, K1, K2, K3):
    """Torsion angle [rad] of a strain-wave gear under output torque [N m] (odd, piecewise linear, hardening)."""
    a = np.abs(torque)
    phi = np.minimum(a, T1) / K1 + np.clip(a - T1, 0, T2 - T1) / K2 + np.maximum(a - T2, 0) / K3
    return np.sign(torque) * phi


def cycloid_torsion(torque, T_rated, lost_motion_rad, K):
    """Torsion angle [rad] of a cycloid (RV) gear: half the lost motion reached at 3 % of the rated torque,
    then the catalogue rigidity K [N m/rad]."""
    T0 = 0.03 * T_rated
    return harmonic_drive_torsion(torque, T0, T0 * (1 + 1e-9), T0 / (lost_motion_rad / 2), K, K)


# ------------------------------------------------------------------------------------------------ beams
def tube_section(D_m, t_m):
    """Area [m^2], second moment I [m^4] and polar moment J [m^4] of a round tube (outer diameter, wall)."""
    d = D_m - 2 * t_m
    return np.pi / 4 * (D_m ** 2 - d ** 2), np.pi / 64 * (D_m ** 4 - d ** 4), np.pi / 32 * (D_m ** 4 - d ** 4)


def cowper_k_thin_tube(nu):
    return 2 * (1 + nu) / (4 + 3 * nu)


def cantilever_tip(e, L_m, force_N, moment_Nm, w_N_per_m, EI, kGA, GJ):
    """Tip displacement [m] and rotation vector [rad] of a cantilever (root clamped) along unit ``e``.

    force_N (..., 3): resultant at the tip; moment_Nm (..., 3): moment about the tip of everything beyond it;
    w_N_per_m (..., 3): uniform load along the span. Euler-Bernoulli bending + shear + free torsion.
    """
    e = np.asarray(e, float)

    def perp(v):
        return v - np.sum(v * e, axis=-1, keepdims=True) * e

    F, M, w = perp(force_N), moment_Nm, perp(w_N_per_m)
    Mb = perp(M)
    Mt = np.sum(M * e, axis=-1, keepdims=True) * e
    delta = (F * L_m ** 3 / (3 * EI) + F * L_m / kGA + w * L_m ** 4 / (8 * EI) + w * L_m ** 2 / (2 * kGA)
             + np.cross(Mb, e) * L_m ** 2 / (2 * EI))
    rot = (np.cross(e, F) * L_m ** 2 / (2 * EI) + np.cross(e, w) * L_m ** 3 / (6 * EI) + Mb * L_m / EI
           + Mt * L_m / GJ)
    return delta, rot


# ----------------------------------------------------------------------------------------------- thermal
def first_order_zoh(t_s, u, tau_s, x0=0.0):
    """Exact response x(t_k) of tau dx/dt = u - x to an input held at u[k] on [t_k, t_k+1) (u: (K,) or (K, m))."""
    t = np.asarray(t_s, float)
    u = np.asarray(u, float)
    x = np.zeros_like(u)
    x[0] = x0
    decay = np.exp(-np.diff(t) / tau_s)
    for k in range(len(t) - 1):
        x[k + 1] = u[k] + (x[k] - u[k]) * decay[k]
    return x


def first_order_foh(t_s, u, tau_s, x0=None):
    """Exact response of tau dx/dt = u - x to a piecewise-linear input through the samples (t_k, u_k)."""
    t = np.asarray(t_s, float)
    u = np.asarray(u, float)
    x = np.zeros_like(u)
    x[0] = u[0] if x0 is None else x0
    dt = np.diff(t)
    decay = np.exp(-dt / tau_s)
    for k in range(len(t) - 1):
        x[k + 1] = decay[k] * x[k] + (1 - decay[k]) * u[k] + (u[k + 1] - u[k]) * (1 - tau_s * (1 - decay[k]) / dt[k])
    return x


def motor_losses(speed_rad_s, torque_Nm, T_rated, P_cu_rated_W, friction_frac):
    """Heat [W] of a joint drive: copper loss P_cu,rated (T / T_rated)^2 + friction friction_frac T_rated |omega|."""
    return P_cu_rated_W * (np.asarray(torque_Nm) / T_rated) ** 2 + friction_frac * T_rated * np.abs(speed_rad_s)


# ------------------------------------------------------------------------------------------------ backlash
def backlash_offset(direction, torque_Nm, preload_Nm, backlash_rad, hysteresis_rad):
    """Output angle minus motor-side reading [rad] of a gear with lost motion.

    A joint whose static load exceeds ``preload_Nm`` (friction that holds the output) rests on the flank the load
    pushes it to, +b/2 sign(T); otherwise on the flank of its last motion: moving in +, the output trails by b/2.
    The hysteresis loss of the torsion curve always trails the motion: -h/2 direction.
    """
    direction = np.asarray(direction, float)
    loaded = np.abs(torque_Nm) > preload_Nm
    side = np.where(loaded, np.sign(torque_Nm), -direction)
    return side * backlash_rad / 2 - direction * hysteresis_rad / 2
