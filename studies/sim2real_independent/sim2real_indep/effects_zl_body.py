"""Set ZL body effects (new physics, not in sets A-ZK): the arm's base on a raised access floor's panels and
pedestals; its base on a weighing platform's load cells; a six-axis
force/torque sensor's flexure between the flange and the tool; and a part pivoting between a gripper's soft finger
pads. Same protocol as :mod:`effects_joint`.

Sources:

* raised floor (``raised_floor``): an arm set on a raised access floor (removable panels of 600 mm on adjustable
  pedestals, with stringers along one grid direction: EN 12825:2001, panel deflection under a concentrated load of
  up to 2.5 mm at the working load; CISCA, *Recommended Test Procedures for Access Floors*, 2007) tilts with the
  panels' bending and the pedestals' shortening; the stringers make the floor stiffer along one grid axis, the tilt
  compliance about the other being 1.5-3 times the first (assumed); the base sinks with the weight by c L_v^2 W, L_v
  0.15-0.3 m (a plate's vertical and rotational compliances, assumed), the grid's heading at random, its pivot at the
  panels' top 0-40 mm below the base frame. Parts of up to the rated payload changed between blocks; sized to
  0.25-0.6 mm. Unlike set I's floor beams (two beams under the feet), set E's table frame or set ZF's shelf bracket,
  the support is a panel-and-pedestal floor, stiffer along its stringers. Driven by the pose and the payload
  (logged). The true structure: two columns (tilt about each grid axis, the first with the sink), amplitudes c, c
  times the ratio.
* weighing platform (``load_cells``): the arm stands on a platform scale (a stiff plate on four shear-beam load cells
  at the corners of a pallet-sized rectangle, half sides a_l 0.5-0.6 m and a_s 0.3-0.4 m, its long side at a heading
  at random -- palletising and
  dispensing cells weigh what the arm handles); a load cell is a strain-gauged flexure that deflects by its rated
  deflection, 0.2-0.5 mm at its rated capacity (OIML R 60, 2017; makers' data sheets, as recalled), chosen at 1.5-3
  times the arm's and part's weight over four cells. Each cell's load is W / 4 plus its share of the moment, so the
  plate sinks by W / (4 k) and tilts by M_l / (4 k a_s^2) about its long axis and M_s / (4 k a_l^2) about its short
  one, about the cells' top 60-120 mm below the base frame (first on a square, a 0.25-0.4 m: ur10's ZL06 with the
  link model at 1.09x; then a pallet scale's rectangle, still with a new part of up to the rated payload in each
  block: 1.19x -- the platform's sink under the part's weight is the upper arm's and forearm's bending under it; now
  the arm keeps its session's one part: the scale weighs the pallet beside it). Sized to 0.25-0.6 mm. (The set's first mount kind here was
  ``chevron_mounts``, the base on inclined elastomer mounts turning about an elastic centre above them: at 30-45 deg
  ambiguous with the joint model at 1.01-1.02x on tool_changer (ZL13), ur10 (ZL06) and kr16_like (ZL21), at 10-20
  deg on ur10 (ZL06) 1.24x -- a tilt about a point up near the shoulder is axis 2's own compliance; replaced.) Unlike
  set Q's disc springs or set G's air isolators (isolating feet), set S's Mullins mounts or set ZK's asphalt, the
  support is a weighing instrument's measuring flexures. Driven by the pose and the payload (logged). The true
  structure: one column (tilt and sink in their physical ratio), amplitude 1 / k.
* force/torque sensor (``ft_sensor``): a strain-gauge six-axis sensor between the flange and the tool is a flexure of
  finite stiffness (makers' data: tilt 2e4-2e5 N m/rad, torsion 1.2-1.8 times stiffer, forces 1e8-3e8 N/m: ATI
  Industrial Automation F/T catalogue, as recalled); the tool's weight (1-4 / 2-8 / 10-30 kg, its centre 60-150 mm
  past the sensor) and the part's load it; the sensor turns by M / K_t about its own x and y, by M_z / K_z about its
  axis and gives F / K_F, carrying the target (250 mm along the tool axis: :func:`effects_zl.probe_hook`). Parts of
  1-8 / 2-14 / 10-60 kg changed between blocks; sized to 0.25-0.6 mm. Unlike set K's remote-centre compliance, set
  ZD's soft float (a controller) or set ZF's flange gapping (a bolted joint past its preload), the compliance is the
  sensor's measuring flexure, linear in six axes. Driven by the attitude and the payload (logged). The true
  structure: one column (the six compliances in the catalogue's ratios), amplitude 1 / K_t.
* finger pads (``pad_pivot``): a parallel gripper holds the part between two elastomer pads by friction; the part's
  weight about the closing axis (the tool's y) twists the pads, each a disc of radius a and thickness t in torsion,
  k = G pi a^4 / (2 t) (Roark's *Formulas for Stress and Strain*, 7th ed., torsion of circular sections; soft-finger
  contacts: Xydas & Kao, IJRR 18, 1999), so the part pivots about the pads' centre by M_y / (2 k). The pads 150 mm
  down the tool axis, the part's centre 40-90 mm below them, the target on the part 100 mm below the pads
  (:func:`effects_zl.probe_hook`, :func:`effects_zl.payload_hook`). Parts of 1-8 / 2-14 / 10-60 kg changed between
  blocks; sized to 0.25-0.6 mm. Unlike set ZI's jamming grip (locked at each block's start), set Y's foam pad
  (compression and shear of a vacuum pad) or set ZA's off-centre pick (a bar twisted about its own axis), the part
  turns between the fingers about the closing axis. Driven by the attitude and the payload (logged). The true
  structure: one column, amplitude 1 / (2 k).
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
Z = np.array([0.0, 0.0, 1.0])
SENSOR_MM = 50.0    # the F/T sensor's height; its compliance centre at half of it
FT_TARGET_MM = 250.0  # the target on the tool past the sensor, along the tool axis
PAD_MM = 150.0      # the finger pads' centre down the tool axis
PART_TARGET_MM = 250.0  # the target on the part, 100 mm below the pads
TOOL_KG = {"ur10": (1.0, 4.0), "kr16_like": (2.0, 8.0), "tool_changer": (10.0, 30.0)}


def _amp_apply(amp, F):
    return Contribution(displace=np.einsum("k,kpi->pi", np.asarray(amp, float), F))


def total_weight(ctx):
    m, _, _ = ctx.mass_state
    return m.sum(axis=1) * G


def _tilt(ctx, axis_moment, pivot):
    """(P, 3) the target's displacement [mm] for a rotation axis_moment (P, 3) [rad per unit] about ``pivot``."""
    return np.cross(axis_moment, ctx.target - pivot)


# ---------------------------------------------------------------------------------------------------- raised floor
def grid_axes(p):
    e1 = np.array([np.cos(p["psi"]), np.sin(p["psi"]), 0.0])
    return e1, np.cross(Z, e1)


def floor_draw(ctx, hw, rng):
    p = {"psi": rng.uniform(0, np.pi), "ratio": rng.uniform(1.5, 3.0), "pivot_mm": rng.uniform(0.0, 40.0),
         "Lv_m": rng.uniform(0.15, 0.3)}
    p["c"] = _size(floor_features(p, ctx, hw), [1.0, p["ratio"]], rng)
    return p


def floor_features(p, ctx, hw):
    M = mount_moment(ctx)
    e1, e2 = grid_axes(p)
    pivot = np.array([0.0, 0.0, -p["pivot_mm"]])
    sink = -1000.0 * p["Lv_m"] ** 2 * total_weight(ctx)[:, None] * Z
    return np.array([_tilt(ctx, (M @ e1)[:, None] * e1, pivot) + sink, _tilt(ctx, (M @ e2)[:, None] * e2, pivot)])


def floor_apply(p, ctx, hw):
    return _amp_apply(p["c"], floor_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- load cells
def cells_draw(ctx, hw, rng):
    p = {"psi": rng.uniform(0, np.pi), "a_l": rng.uniform(0.5, 0.6), "a_s": rng.uniform(0.3, 0.4),
         "pivot_mm": rng.uniform(60.0, 120.0)}
    p["c"] = float(_size(cells_features(p, ctx, hw), [1.0], rng)[0])
    return p


def cells_features(p, ctx, hw):
    """(1, P, 3) per unit 1 / k [m/N]: the tilts M_l / (4 a_s^2), M_s / (4 a_l^2) about the cells' top and the sink
    W / 4."""
    M = mount_moment(ctx)
    el, es = grid_axes(p)
    rot = (M @ el)[:, None] * el / (4 * p["a_s"] ** 2) + (M @ es)[:, None] * es / (4 * p["a_l"] ** 2)
    tilt = _tilt(ctx, rot, np.array([0.0, 0.0, -p["pivot_mm"]]))
    sink = -1000.0 * (total_weight(ctx) / 4)[:, None] * Z
    return (tilt + sink)[None]


def cells_apply(p, ctx, hw):
    return _amp_apply([p["c"]], cells_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- F/T sensor
def sensor_loads(p, ctx):
    """Force (P, 3) [N] and moment (P, 3) [N m] on the sensor's compliance centre, tool frame: the tool's and the
    part's weight."""
    g = gravity_in_tool(tool_frame(ctx)) * G
    c = np.array([0.0, 0.0, SENSOR_MM / 2])
    rt = (np.array([0.0, 0.0, SENSOR_MM + p["tool_cm_mm"]]) - c) / 1000.0
    rp = (np.asarray(ctx.payload_com_mm, float) - c) / 1000.0
    mp = ctx.session.payload_kg[:, None]
    F = (p["tool_kg"] + mp) * g
    M = np.cross(rt, p["tool_kg"] * g) + np.cross(rp, mp * g)
    return F, M


def ft_draw(ctx, hw, rng):
    robot = ctx.chain.name if ctx.chain.name in TOOL_KG else "ur10"
    p = {"tool_kg": rng.uniform(*TOOL_KG[robot]), "tool_cm_mm": rng.uniform(60.0, 150.0),
         "torsion": rng.uniform(1.2, 1.8), "force_m2": rng.uniform(2e4, 2e5) / rng.uniform(1e8, 3e8)}
    p["inv_Kt"] = float(_size(ft_features(p, ctx, hw), [1.0], rng)[0])
    return p


def ft_features(p, ctx, hw):
    F, M = sensor_loads(p, ctx)
    theta = M * np.array([1.0, 1.0, 1.0 / p["torsion"]])            # [rad per unit 1 / K_t]
    d = 1000.0 * p["force_m2"] * F                                   # [mm per unit 1 / K_t]
    arm = ctx.probe_mm - np.array([0.0, 0.0, SENSOR_MM / 2])
    local = d + np.cross(theta, arm)
    return np.einsum("pij,pj->pi", tool_frame(ctx), local)[None]


def ft_apply(p, ctx, hw):
    return _amp_apply([p["inv_Kt"]], ft_features(p, ctx, hw))


# ---------------------------------------------------------------------------------------------------- finger pads
def pad_moment(ctx):
    """(P,) the part's weight moment about the closing axis (the tool's y) through the pads' centre [N m]."""
    g = gravity_in_tool(tool_frame(ctx)) * G
    r = (np.asarray(ctx.payload_com_mm, float) - np.array([0.0, 0.0, PAD_MM])) / 1000.0
    return np.cross(r, ctx.session.payload_kg[:, None] * g)[:, 1]


def pad_draw(ctx, hw, rng):
    p = {}
    p["inv_k"] = float(_size(pad_features(p, ctx, hw), [1.0], rng)[0])
    return p


def pad_features(p, ctx, hw):
    arm = ctx.probe_mm - np.array([0.0, 0.0, PAD_MM])
    local = np.cross(pad_moment(ctx)[:, None] * np.array([0.0, 1.0, 0.0]), arm)
    return np.einsum("pij,pj->pi", tool_frame(ctx), local)[None]


def pad_apply(p, ctx, hw):
    return _amp_apply([p["inv_k"]], pad_features(p, ctx, hw))
