"""The hidden hardware of a simulated robot: gears, drives, tubes, mount -- drawn from stated ranges.

Sources of the ranges (the study's README / report repeats them):

* strain-wave gears (ur10 all joints, wrists of the others): Harmonic Drive CSF-type, sizes 14-65. The size-32
  catalogue example (T1 = 29 N m, T2 = 108 N m, K1 = 6.7e4, K2 = 1.1e5, K3 = 1.2e5 N m/rad) is scaled by
  (size / 32)^3 for other sizes (torque capacity and stiffness of geometrically similar gears grow with the cube of
  the pitch diameter -- an approximation of the catalogue table, not the table itself); rated torque ~1.27 T2.
  The size is the smallest whose rated torque covers 1.3x the largest static load of the session.
* cycloid gears (main axes of kr16_like and tool_changer): Nabtesco RV-E-like sizes, rated torque 167-3136 N m,
  torsional rigidity 49-980 N m/arcmin, lost motion 1 arcmin at +-3 % rated torque (values as recalled from the
  RV-E catalogue table: 20E 167 / 49, 40E 412 / 108, 80E 784 / 196, 110E 1078 / 294, 160E 1568 / 392,
  320E 3136 / 980); a load past the largest gets a size rated for it with the table's rigidity per rated torque.
  The size covers 1.3x the session's largest static load (the base axis: half the largest load of the arm).
* joint stiffness of the assembled joint: the gear's in series with bearings, shafts and housing: compliance x
  U(1, 2) (assumption; assembled robot joints are softer than their gears, e.g. Dumas et al., "Joint stiffness
  identification of six-revolute industrial serial robots", RCIM 27, 2011).
* prismatic stage (tool_changer j4): ball-screw drive axial stiffness 200-800 N/um (THK / Hiwin ball-screw
  catalogues, preloaded nut + support bearings).
* drive losses: copper loss at rated torque 8-20 % of rated mechanical power T_rated * omega_rated (servo motors
  of 85-92 % efficiency), friction loss 5-15 % of T_rated * |omega| (strain-wave efficiency 70-85 %).
* links: round-tube equivalents; aluminium E = 70 GPa, nu = 0.33, CTE 23e-6 /K; steel E = 210 GPa, nu = 0.30,
  CTE 11.7e-6 /K (handbook values, e.g. ASM Handbook).
* mount: a steel pedestal column (E = 210 GPa) on an anchored base plate of rotational stiffness in the stated
  range (assumption: the semi-rigid range of small column bases, cf. EN 1993-1-8 5.2.2.5).
Imports nothing of tolalloc.
"""

from __future__ import annotations

import numpy as np

from sim2real_indep import physics as ph

HD_SIZES = np.array([14, 17, 20, 25, 32, 40, 45, 50, 58, 65])
RV_RATED = np.array([167, 412, 784, 1078, 1568, 3136.0])
RV_RIGIDITY_NM_ARCMIN = np.array([49, 108, 196, 294, 392, 980.0])
ALUMINIUM = {"E": 70e9, "nu": 0.33, "cte": 23e-6, "rho": 2700.0}
STEEL = {"E": 210e9, "nu": 0.30, "cte": 11.7e-6, "rho": 7850.0}

#: per robot: gear kind per joint, link tube sections {link: (D range [mm], wall range [mm])}, material,
#: pedestal (height range [mm], D [mm], wall [mm]), base-plate rotational stiffness range [N m/rad],
#: copper-loss / rated-speed data
#: The largest payload each arm is given in a session [kg].
PAYLOAD_MAX_KG = {"ur10": 10.0, "tool_changer": 80.0, "kr16_like": 16.0}


def pick_place(robot_key, rng, blocks_now: int) -> dict:
    """Session options of pick and place: 2-4 loads (empty and up to the arm's largest payload) changed between
    6-10 blocks (at least ``blocks_now``)."""
    loads = np.round(np.r_[0.0, rng.uniform(0.2, 1.0, int(rng.integers(1, 4))) * PAYLOAD_MAX_KG[robot_key]], 1)
    blocks = int(rng.integers(6, 11))
    return {"blocks": max(blocks_now, blocks), "payload_steps": tuple(rng.choice(loads, blocks))}

ROBOTS = {
    "ur10": {"gears": ["HD"] * 6, "material": ALUMINIUM,
             "tubes": {"a2": ((85, 110), (3, 5)), "a3": ((75, 95), (3, 5))},
             "pedestal": ((300, 800), (180, 250), (6, 10)), "plate": (0.5e6, 5e6)},
    "tool_changer": {"gears": ["RV", "RV", "RV", "screw", "HD", "HD"], "material": STEEL,
                     "tubes": {"l1": ((250, 320), (10, 16)), "l2": ((200, 260), (8, 14)),
                               "l3": ((160, 220), (6, 12)), "l4": ((140, 190), (6, 10)),
                               "l5": ((120, 160), (5, 9))},
                     "pedestal": ((0, 300), (350, 450), (12, 20)), "plate": (2e6, 20e6)},
    "kr16_like": {"gears": ["RV", "RV", "RV", "HD", "HD", "HD"], "material": ALUMINIUM,
                  "tubes": {"d1": ((300, 380), (10, 20)), "a1": ((300, 380), (10, 20)),
                            "a2": ((160, 220), (8, 14)), "d4": ((120, 160), (6, 10))},
                  "pedestal": ((0, 500), (350, 450), (12, 20)), "plate": (2e6, 20e6)},
}


def hd_gear(size):
    s = (size / 32.0) ** 3
    return {"kind": "HD", "size": int(size), "T1": 29 * s, "T2": 108 * s, "K1": 6.7e4 * s, "K2": 1.1e5 * s,
            "K3": 1.2e5 * s, "T_rated": 1.27 * 108 * s}


def rv_gear(i, need=None):
    """RV size ``i``; past the largest listed size (``need`` above its rating): a size rated for ``need`` with the
    table's rigidity per rated torque (0.25-0.31 arcmin^-1 across the table; 0.27 taken)."""
    if need is not None:
        return {"kind": "RV", "size": -1, "T_rated": need, "K": 0.27 * need / ph.ARCMIN, "lost_motion": 1.0 * ph.ARCMIN}
    return {"kind": "RV", "size": int(i), "T_rated": RV_RATED[i], "K": RV_RIGIDITY_NM_ARCMIN[i] / ph.ARCMIN,
            "lost_motion": 1.0 * ph.ARCMIN}


def size_drives(robot_key, max_load, rated_speed, rng):
    """Gear, stiffness and loss data per joint, sized for ``max_load`` (n,) [N m or N]."""
    drives = []
    for j, kind in enumerate(ROBOTS[robot_key]["gears"]):
        # the base axis carries no gravity load: sized for half the largest load (its inertial torque)
        need = 1.3 * max(max_load[j], 5.0, 0.5 * max(max_load) if j == 0 else 0.0)
        if kind == "HD":
            ok = [s for s in HD_SIZES if hd_gear(s)["T_rated"] >= need]
            d = hd_gear(ok[0] if ok else HD_SIZES[-1])
        elif kind == "RV":
            ok = np.flatnonzero(RV_RATED >= need)
            d = rv_gear(ok[0]) if len(ok) else rv_gear(-1, need)
        else:
            d = {"kind": "screw", "T_rated": 5 * need, "K_axial_N_per_mm": rng.uniform(200, 800) * 1e3}
        d["soften"] = rng.uniform(1.0, 2.0)  # assembled joint softer than the gear
        omega = rated_speed[j] * (1e-3 if kind == "screw" else 1.0)  # [rad/s] or [m/s]
        d["P_cu_rated_W"] = rng.uniform(0.08, 0.20) * d["T_rated"] * omega
        d["friction_frac"] = rng.uniform(0.05, 0.15)
        drives.append(d)
    return drives


def torsion(drive, load, hardening: bool):
    """Joint deflection [rad or mm] under static load [N m or N]: the catalogue curve (hardening) or its
    high-torque slope alone (linear)."""
    s = drive["soften"]
    if drive["kind"] == "screw":
        return s * load / drive["K_axial_N_per_mm"]
    if drive["kind"] == "HD":
        if hardening:
            return s * ph.harmonic_drive_torsion(load, drive["T1"], drive["T2"], drive["K1"], drive["K2"], drive["K3"])
        return s * load / drive["K3"]
    if hardening:
        return s * ph.cycloid_torsion(load, drive["T_rated"], drive["lost_motion"], drive["K"])
    return s * load / drive["K"]


def torsion_knots(drive):
    """Torque knots [N m] of the piecewise-linear torsion curve (the true shape parameters)."""
    if drive["kind"] == "HD":
        return drive["T1"], drive["T2"]
    if drive["kind"] == "RV":
        return 0.03 * drive["T_rated"], 0.03 * drive["T_rated"]
    return None


def draw_tubes(robot_key, rng):
    """Link tube sections: {link: dict(A, I, J [m^2, m^4], E, G, k, rho)}."""
    spec = ROBOTS[robot_key]
    mat = spec["material"]
    out = {}
    for name, (D, t) in spec["tubes"].items():
        Dm, tm = rng.uniform(*D) / 1000, rng.uniform(*t) / 1000
        A, I, J = ph.tube_section(Dm, tm)
        out[name] = {"A": A, "I": I, "J": J, "E": mat["E"], "G": mat["E"] / (2 * (1 + mat["nu"])),
                     "k": ph.cowper_k_thin_tube(mat["nu"]), "rho": mat["rho"]}
    return out


def draw_mount(robot_key, rng):
    """Pedestal and base plate: height [mm], column EI [N m^2], plate stiffness about two axes [N m/rad]."""
    h, D, t = ROBOTS[robot_key]["pedestal"]
    _, I, _ = ph.tube_section(rng.uniform(*D) / 1000, rng.uniform(*t) / 1000)
    lo, hi = ROBOTS[robot_key]["plate"]
    kx = np.exp(rng.uniform(np.log(lo), np.log(hi)))
    return {"height_mm": rng.uniform(*h), "EI": STEEL["E"] * I, "k_plate": (kx, kx * rng.uniform(1.0, 2.0)),
            "plate_axis_rad": rng.uniform(0, np.pi)}
