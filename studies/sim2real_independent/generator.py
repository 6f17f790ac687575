"""Independent generator of laser-tracker measurement cases (issue 40, part 7).

Physics written from the literature (see :mod:`physics`, :mod:`hardware`, :mod:`session`), kinematics and mass
model of its own (:mod:`kinematics`, parsing the robot files with tomllib). **Imports nothing of tolalloc.**

A case: one robot, one measurement session (poses in visiting order with time stamps, approach directions,
payload and air temperature), a true robot that differs from its file by

* geometric errors on every kinematic parameter: link-vector components N(0, s_L), s_L ~ U(0.1, 0.5) mm;
  joint-axis tilts and joint zero offsets N(0, s_A), s_A ~ U(0.01, 0.05) deg (typical of calibrated-before
  industrial arms: Mooring, Roth & Driels, *Fundamentals of Manipulator Calibration*, 1991; Nubiola & Bonev,
  RCIM 29, 2013, ABB IRB 1600: link-length errors of tenths of a mm);
* a mass model off the file's by U(0.85, 1.15) per mass and N(0, 20 mm) per centre-of-mass coordinate (the files'
  centres of mass are approximations);
* the physical effects of the case (``physics``: a tuple of kinds, see :data:`EFFECTS`);

measured by a laser tracker in its own frame (yaw U(0, 360) deg, tilt U(-3, 3) deg about two axes -- a levelled
tracker -- at 1.5-5 m), on a target at an unknown offset of 5-100 mm from the tool point, with Gaussian noise of
s_T ~ U(0.01, 0.05) mm per coordinate (Leica AT960 MPE +-(15 um + 6 um/m): 0.01-0.05 mm at these distances).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import pandas as pd

from sim2real_indep import effects_body as eb
from sim2real_indep import effects_c as ec
from sim2real_indep import effects_d as ed
from sim2real_indep import effects_e as ee
from sim2real_indep import effects_f as ef
from sim2real_indep import effects_g as eg
from sim2real_indep import effects_h as eh
from sim2real_indep import effects_i as ei
from sim2real_indep import effects_j as ejs  # set J (ej is effects_joint)
from sim2real_indep import effects_k as ek
from sim2real_indep import effects_l as el
from sim2real_indep import effects_m as em
from sim2real_indep import effects_n as en
from sim2real_indep import effects_o as eo
from sim2real_indep import effects_p as ep
from sim2real_indep import effects_q as eq
from sim2real_indep import effects_r as er
from sim2real_indep import effects_s as es
from sim2real_indep import effects_t as et
from sim2real_indep import effects_u as eu
from sim2real_indep import effects_v as ev
from sim2real_indep import effects_w as ew
from sim2real_indep import effects_x as ex
from sim2real_indep import effects_y as ey
from sim2real_indep import effects_z as ez
from sim2real_indep import effects_za as eza
from sim2real_indep import effects_zb as ezb
from sim2real_indep import effects_zc as ezc
from sim2real_indep import effects_zd as ezd
from sim2real_indep import effects_ze as eze
from sim2real_indep import effects_zf as ezf
from sim2real_indep import effects_zg as ezg
from sim2real_indep import effects_zh as ezh
from sim2real_indep import effects_zi as ezi
from sim2real_indep import effects_zj as ezj
from sim2real_indep import effects_zk as ezk
from sim2real_indep import effects_zl as ezl
from sim2real_indep import effects_zm as ezm
from sim2real_indep import effects_zn as ezn
from sim2real_indep import effects_zo as ezo
from sim2real_indep import effects_zp as ezp
from sim2real_indep import effects_joint as ej
from sim2real_indep import hardware as hwm
from sim2real_indep import kinematics as kin
from sim2real_indep.context import FAMILY, Ctx
from sim2real_indep.session import RATED_SPEED_DEG_S, make_session

HERE = Path(__file__).resolve().parent
ROBOT_FILES = {"ur10": "ur10", "tool_changer": "tool_changer", "kr16_like": str(HERE / "kr16_like.toml")}
#: kind -> (draw, apply, true-structure features)
EFFECTS = {
    "gear": (ej.gear_draw, ej.gear_apply, ej.gear_features),
    "encoder": (ej.encoder_draw, ej.encoder_apply, ej.encoder_features),
    "compliance": (ej.stiffness_draw, ej.stiffness_apply(False), ej.compliance_features),
    "hardening": (ej.stiffness_draw, ej.stiffness_apply(True), ej.hardening_features),
    "backlash": (ej.backlash_draw, ej.backlash_apply, ej.backlash_features),
    "heat": (eb.heat_draw, eb.heat_apply, eb.heat_features),
    "ambient": (eb.ambient_draw, eb.ambient_apply, eb.ambient_features),
    "sag": (eb.sag_draw, eb.sag_apply, eb.sag_features),
    "mount": (eb.mount_draw, eb.mount_apply, eb.mount_features),
    **ec.EFFECTS_C,  # set C's new kinds
    **ed.EFFECTS_D,  # set D's new kinds
    **ee.EFFECTS_E,  # set E's new kinds
    **ef.EFFECTS_F,  # set F's new kinds
    **eg.EFFECTS_G,  # set G's new kinds
    **eh.EFFECTS_H,  # set H's new kinds
    **ei.EFFECTS_I,  # set I's new kinds
    **ejs.EFFECTS_J,  # set J's new kinds
    **ek.EFFECTS_K,  # set K's new kinds
    **el.EFFECTS_L,  # set L's new kinds
    **em.EFFECTS_M,  # set M's new kinds
    **en.EFFECTS_N,  # set N's new kinds
    **eo.EFFECTS_O,  # set O's new kinds
    **ep.EFFECTS_P,  # set P's new kinds
    **eq.EFFECTS_Q,  # set Q's new kinds
    **er.EFFECTS_R,  # set R's new kinds
    **es.EFFECTS_S,  # set S's new kinds
    **et.EFFECTS_T,  # set T's new kinds
    **eu.EFFECTS_U,  # set U's new kinds
    **ev.EFFECTS_V,  # set V's new kinds
    **ew.EFFECTS_W,  # set W's new kinds
    **ex.EFFECTS_X,  # set X's new kinds
    **ey.EFFECTS_Y,  # set Y's new kinds
    **ez.EFFECTS_Z,  # set Z's new kinds
    **eza.EFFECTS_ZA,  # set ZA's new kinds
    **ezb.EFFECTS_ZB,  # set ZB's new kinds
    **ezc.EFFECTS_ZC,  # set ZC's new kinds
    **ezd.EFFECTS_ZD,  # set ZD's new kinds
    **eze.EFFECTS_ZE,  # set ZE's new kinds
    **ezf.EFFECTS_ZF,  # set ZF's new kinds
    **ezg.EFFECTS_ZG,  # set ZG's new kinds
    **ezh.EFFECTS_ZH,  # set ZH's new kinds
    **ezi.EFFECTS_ZI,  # set ZI's new kinds
    **ezj.EFFECTS_ZJ,  # set ZJ's new kinds
    **ezk.EFFECTS_ZK,  # set ZK's new kinds
    **ezl.EFFECTS_ZL,  # set ZL's new kinds
    **ezm.EFFECTS_ZM,  # set ZM's new kinds
    **ezn.EFFECTS_ZN,  # set ZN's new kinds
    **ezo.EFFECTS_ZO,  # set ZO's new kinds
    **ezp.EFFECTS_ZP,  # set ZP's new kinds
}
AFTER_TRACKER = (ec.AFTER_TRACKER | ed.AFTER_TRACKER | eh.AFTER_TRACKER  # measurement effects: need the tracker
                 | ei.AFTER_TRACKER | ejs.AFTER_TRACKER | ek.AFTER_TRACKER | el.AFTER_TRACKER
                 | em.AFTER_TRACKER | en.AFTER_TRACKER | eo.AFTER_TRACKER | ep.AFTER_TRACKER
                 | eq.AFTER_TRACKER | er.AFTER_TRACKER | es.AFTER_TRACKER | et.AFTER_TRACKER | eu.AFTER_TRACKER
                 | ev.AFTER_TRACKER | ew.AFTER_TRACKER | ex.AFTER_TRACKER | ey.AFTER_TRACKER
                 | ez.AFTER_TRACKER | eza.AFTER_TRACKER | ezb.AFTER_TRACKER | ezc.AFTER_TRACKER
                 | ezd.AFTER_TRACKER | eze.AFTER_TRACKER | ezf.AFTER_TRACKER
                 | ezg.AFTER_TRACKER | ezh.AFTER_TRACKER | ezi.AFTER_TRACKER | ezj.AFTER_TRACKER
                 | ezk.AFTER_TRACKER | ezl.AFTER_TRACKER | ezm.AFTER_TRACKER | ezn.AFTER_TRACKER
                 | ezo.AFTER_TRACKER | ezp.AFTER_TRACKER)
GRAVITY_KINDS = {"compliance", "hardening", "sag", "mount", "backlash"}


@dataclass(frozen=True)
class Case:
    """A generated case: the measurement table, its split and the truth (for the oracle only)."""

    case_id: str
    robot_key: str
    physics: tuple
    frame: pd.DataFrame
    train: np.ndarray      # row indices
    test: np.ndarray
    split: str
    nominal: kin.Chain     # the robot file
    truth: dict            # true chain, masses, probe, frame, noise, hardware, effect parameters

    @property
    def label_truth(self) -> str:
        fams = sorted({FAMILY[k] for k in self.physics}) or ["none"]
        return "+".join(fams)

    def model_ctx(self, probe_mm, true_masses: bool = True) -> Ctx:
        """The nominal robot at this session's poses with the true (or the file's) mass model and payload placement."""
        ch, t = self.nominal, self.truth
        return Ctx(ch, t["session"], t["masses"] if true_masses else ch.masses,
                   t["com"] if true_masses else ch.mass_com, ch.mass_link,
                   t["payload_com_mm"] if true_masses else np.zeros(3), np.asarray(probe_mm, float))

    def true_features_of(self, kind, probe_mm) -> np.ndarray:
        """The true structure of effect ``kind`` as feature columns (m, P, 3) at the nominal geometry (shape
        parameters known, amplitudes free)."""
        return EFFECTS[kind][2](self.truth["params"][kind], self.model_ctx(probe_mm), self.truth["hw"])

    def true_features(self, probe_mm) -> np.ndarray:
        """All true structures of the case, (m, P, 3)."""
        cols = [self.true_features_of(k, probe_mm) for k in self.physics]
        return np.concatenate(cols) if cols else np.zeros((0, len(self.frame), 3))


def _perturb(chain: kin.Chain, rng):
    """The true geometry: every link vector, joint axis, joint zero and the tool point off the file's."""
    s_L, s_A = rng.uniform(0.1, 0.5), np.deg2rad(rng.uniform(0.01, 0.05))
    axes = []
    for w in chain.axes:
        u = np.cross(w, [1.0, 0, 0] if abs(w[0]) < 0.9 else [0, 1.0, 0])
        u /= np.linalg.norm(u)
        tilt = rng.normal(0, s_A, 2) @ np.array([u, np.cross(w, u)])
        axes.append(kin._rot(tilt / max(np.linalg.norm(tilt), 1e-15), np.linalg.norm(tilt)) @ w)
    off = np.where(chain.revolute, rng.normal(0, s_A, chain.n), rng.normal(0, s_L, chain.n))
    return replace(chain, links=chain.links + rng.normal(0, s_L, chain.links.shape), axes=np.array(axes),
                   tool=chain.tool + rng.normal(0, s_L, 3), q_offset=off), {"s_L_mm": s_L, "s_A_deg": np.rad2deg(s_A)}


def _session_options(robot_key, physics, rng):
    kinds = set(physics)
    opts = {"blocks": int(rng.integers(1, 4)), "gap_kind": str(rng.choice(["none", "pause"]))}
    if "heat" in kinds:
        opts.update(blocks=int(rng.integers(4, 7)), gap_kind="mixed")
    if "ambient" in kinds:
        drift = rng.choice([-1, 1]) * rng.uniform(2.0, 6.0)
        # a working day: blocks with pauses of 30-90 min, the shop's air drifting by 2-6 K
        opts.update(blocks=int(rng.integers(5, 9)), gap_kind="pause", pause_min=(30.0, 90.0),
                    air={"drift_K": drift, "cycle_K": rng.uniform(0.0, 1.0), "period_min": rng.uniform(60, 180)})
    pmax = hwm.PAYLOAD_MAX_KG[robot_key]
    if "sag" in kinds or (kinds & GRAVITY_KINDS and rng.random() < 0.5):
        steps = np.round(rng.uniform(0, pmax, int(rng.integers(2, 4))), 1)
        opts.update(blocks=max(opts["blocks"], len(steps)), payload_steps=tuple(steps))
    else:
        opts["payload_steps"] = (float(np.round(rng.uniform(0, pmax) * (rng.random() < 0.5), 1)),)
    opts = ec.session_options(robot_key, physics, rng, opts)
    opts = ed.session_options(robot_key, physics, rng, opts)  # set D (no draws without a set-D kind)
    opts = ee.session_options(robot_key, physics, rng, opts)  # set E (no draws without a set-E kind)
    opts = ef.session_options(robot_key, physics, rng, opts)  # set F (no draws without a set-F kind)
    opts = eg.session_options(robot_key, physics, rng, opts)  # set G (no draws without a set-G kind)
    opts = eh.session_options(robot_key, physics, rng, opts)  # set H (no draws without a set-H kind)
    opts = ei.session_options(robot_key, physics, rng, opts)  # set I (no draws without a set-I kind)
    opts = ejs.session_options(robot_key, physics, rng, opts)  # set J (no draws without a set-J kind)
    opts = ek.session_options(robot_key, physics, rng, opts)  # set K (no draws without a set-K kind)
    opts = el.session_options(robot_key, physics, rng, opts)  # set L (no draws without a set-L kind)
    opts = em.session_options(robot_key, physics, rng, opts)  # set M (no draws without a set-M kind)
    opts = en.session_options(robot_key, physics, rng, opts)  # set N (no draws without a set-N kind)
    opts = eo.session_options(robot_key, physics, rng, opts)  # set O (no draws without a set-O kind)
    opts = ep.session_options(robot_key, physics, rng, opts)  # set P (no draws without a set-P kind)
    opts = eq.session_options(robot_key, physics, rng, opts)  # set Q (no draws without a set-Q kind)
    opts = er.session_options(robot_key, physics, rng, opts)  # set R (no draws without a set-R kind)
    opts = es.session_options(robot_key, physics, rng, opts)  # set S (no draws without a set-S kind)
    opts = et.session_options(robot_key, physics, rng, opts)  # set T (no draws without a set-T kind)
    opts = eu.session_options(robot_key, physics, rng, opts)  # set U (no draws without a set-U kind)
    opts = ev.session_options(robot_key, physics, rng, opts)  # set V (no draws without a set-V kind)
    opts = ew.session_options(robot_key, physics, rng, opts)  # set W (no draws without a set-W kind)
    opts = ex.session_options(robot_key, physics, rng, opts)  # set X (no draws without a set-X kind)
    opts = ey.session_options(robot_key, physics, rng, opts)  # set Y (no draws without a set-Y kind)
    opts = ez.session_options(robot_key, physics, rng, opts)  # set Z (no draws without a set-Z kind)
    opts = eza.session_options(robot_key, physics, rng, opts)  # set ZA (no draws without a set-ZA kind)
    opts = ezb.session_options(robot_key, physics, rng, opts)  # set ZB (no draws without a set-ZB kind)
    opts = ezc.session_options(robot_key, physics, rng, opts)  # set ZC (no draws without a set-ZC kind)
    opts = ezd.session_options(robot_key, physics, rng, opts)  # set ZD (no draws without a set-ZD kind)
    opts = eze.session_options(robot_key, physics, rng, opts)  # set ZE (no draws without a set-ZE kind)
    opts = ezf.session_options(robot_key, physics, rng, opts)  # set ZF (no draws without a set-ZF kind)
    opts = ezg.session_options(robot_key, physics, rng, opts)  # set ZG (no draws without a set-ZG kind)
    opts = ezh.session_options(robot_key, physics, rng, opts)  # set ZH (no draws without a set-ZH kind)
    opts = ezi.session_options(robot_key, physics, rng, opts)  # set ZI (no draws without a set-ZI kind)
    opts = ezj.session_options(robot_key, physics, rng, opts)  # set ZJ (no draws without a set-ZJ kind)
    opts = ezk.session_options(robot_key, physics, rng, opts)  # set ZK (no draws without a set-ZK kind)
    opts = ezl.session_options(robot_key, physics, rng, opts)  # set ZL (no draws without a set-ZL kind)
    opts = ezm.session_options(robot_key, physics, rng, opts)  # set ZM (no draws without a set-ZM kind)
    opts = ezn.session_options(robot_key, physics, rng, opts)  # set ZN (no draws without a set-ZN kind)
    opts = ezo.session_options(robot_key, physics, rng, opts)  # set ZO (no draws without a set-ZO kind)
    return ezp.session_options(robot_key, physics, rng, opts)  # set ZP (no draws without a set-ZP kind)


def _tracker(rng):
    yaw, a, b = rng.uniform(0, 2 * np.pi), *np.deg2rad(rng.uniform(-3, 3, 2))
    R = kin._rot([0, 0, 1.0], yaw) @ kin._rot([1.0, 0, 0], a) @ kin._rot([0, 1.0, 0], b)
    d = rng.uniform(1500, 5000)
    phi = rng.uniform(0, 2 * np.pi)
    return R, np.array([d * np.cos(phi), d * np.sin(phi), rng.uniform(-500, 500)])


def _unit(rng):
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def generate(case_id, robot_key, physics, n_poses, seed, split="random") -> Case:
    """One measurement case of ``n_poses`` poses of ``robot_key`` with the effects ``physics`` (kinds of
    :data:`EFFECTS`; empty for geometry and noise only)."""
    rng = np.random.default_rng(seed)
    nominal = kin.load_chain(ROBOT_FILES[robot_key])
    true_chain, geo = _perturb(nominal, rng)
    masses = nominal.masses * rng.uniform(0.85, 1.15, len(nominal.masses))
    com = nominal.mass_com + rng.normal(0, 20.0, nominal.mass_com.shape)
    session = make_session(nominal, robot_key, n_poses, rng, **_session_options(robot_key, physics, rng))
    session = ec.session_hook(physics, session, rng)
    probe = eg.probe_hook(physics, _unit(rng) * rng.uniform(5, 100))  # set G's target rod (no draws)
    probe = ei.probe_hook(physics, probe)  # set I's bimetal boom (no draws)
    probe = ejs.probe_hook(physics, probe)  # set J's tool plate (no draws)
    probe = ek.probe_hook(physics, probe)  # set K's gripper on the RCC (no draws)
    probe = el.probe_hook(physics, probe, robot_key)  # set L's gripper finger (no draws)
    probe = em.probe_hook(physics, probe, robot_key)  # set M's gimbal tool, gripper bar, finger (no draws)
    probe = en.probe_hook(physics, probe, robot_key)  # set N's lattice boom (no draws)
    probe = eo.probe_hook(physics, probe, robot_key)  # set O's spindle nose, C-frame die (no draws)
    probe = ep.probe_hook(physics, probe, robot_key)  # set P's changed tool (no draws)
    probe = eq.probe_hook(physics, probe)  # set Q's holder, gooseneck, gripper boom (no draws)
    probe = er.probe_hook(physics, probe)  # set R's bracket, swing-away tool (no draws)
    probe = es.probe_hook(physics, probe)  # set S's profile frame (no draws)
    probe = eu.probe_hook(physics, probe)  # set U's sandwich boom, sleeve extension (no draws)
    probe = ev.probe_hook(physics, probe)  # set V's bolted boom, printed boom, crossbar (no draws)
    probe = ew.probe_hook(physics, probe)  # set W's hot part (no draws)
    probe = ex.probe_hook(physics, probe)  # set X's printed fingers, suction cup (no draws)
    probe = ey.probe_hook(physics, probe)  # set Y's foam pad, panel (no draws)
    probe = ez.probe_hook(physics, probe)  # set Z's gripper boom, welded frame (no draws)
    probe = eza.probe_hook(physics, probe)  # set ZA's gripper bar, soft fingers (no draws)
    probe = ezb.probe_hook(physics, probe)  # set ZB's torch, stay-cable boom, welding horn (no draws)
    probe = ezc.probe_hook(physics, probe)  # set ZC's bayonet tool, bush boom, bonded part (no draws)
    probe = ezd.probe_hook(physics, probe)  # set ZD's bonded boom, hot-melt nozzle (no draws)
    probe = eze.probe_hook(physics, probe, robot_key)  # set ZE's shuttle boom, ringing boom, PCM bracket (no draws)
    probe = ezf.probe_hook(physics, probe)  # set ZF's polymer boom, gapping tool, brackets (no draws)
    probe = ezg.probe_hook(physics, probe)  # set ZG's beam-column and leaf booms, PA6 bracket (no draws)
    probe = ezh.probe_hook(physics, probe)  # set ZH's inflated boom, collet boom, swinging bracket (no draws)
    probe = ezi.probe_hook(physics, probe)  # set ZI's parts on the Bernoulli and jamming grippers (no draws)
    probe = ezj.probe_hook(physics, probe)  # set ZJ's gecko part, warm panel, plume bracket (no draws)
    probe = ezk.probe_hook(physics, probe)  # set ZK's buckling bracket, dashpot slide (no draws)
    probe = ezl.probe_hook(physics, probe)  # set ZL's F/T sensor's tool, part between the pads (no draws)
    probe = ezm.probe_hook(physics, probe)  # set ZM's part on the mandrel, between the jaws (no draws)
    probe = ezn.probe_hook(physics, probe)  # set ZN's part on the dovetail slide, below the bellows (no draws)
    probe = ezo.probe_hook(physics, probe)  # set ZO's tool beyond the cross-spring pivot, dry-ice nozzle (no draws)
    probe = ezp.probe_hook(physics, probe)  # set ZP's boom tip, spindle nose (no draws)
    payload_com = ec.payload_com(physics, _unit(rng) * rng.uniform(0, 80), rng)
    payload_com = ejs.payload_hook(physics, payload_com, probe)  # set J's tool plate (no draws)
    payload_com = ek.payload_hook(physics, payload_com, probe)  # set K's gripper and offset cutter (no draws)
    payload_com = el.payload_hook(physics, payload_com, probe)  # set L's part between the fingers (no draws)
    payload_com = em.payload_hook(physics, payload_com, probe)  # set M's part on the tool, bar, fingers (no draws)
    payload_com = en.payload_hook(physics, payload_com, probe)  # set N's part at the boom's tip (no draws)
    payload_com = eo.payload_hook(physics, payload_com, probe, robot_key)  # set O's spindle, C-frame (no draws)
    payload_com = es.payload_hook(physics, payload_com, probe)  # set S's profile frame's module (no draws)
    payload_com = ezb.payload_hook(physics, payload_com)  # set ZB's torch, part at the boom's tip (no draws)
    payload_com = ezc.payload_hook(physics, payload_com)  # set ZC's off-axis part, boom tip, bonded part (no draws)
    payload_com = ezd.payload_hook(physics, payload_com)  # set ZD's off-axis part (no draws)
    payload_com = ezl.payload_hook(physics, payload_com)  # set ZL's sensor's tool, pads (no draws)
    payload_com = ezm.payload_hook(physics, payload_com)  # set ZM's mandrel, jaws (no draws)
    payload_com = ezn.payload_hook(physics, payload_com)  # set ZN's slide, bellows (no draws)
    payload_com = ezo.payload_hook(physics, payload_com)  # set ZO's part below the cross-spring pivot (no draws)
    payload_com = ezp.payload_hook(physics, payload_com)  # set ZP's part at the boom's tip (no draws)
    ctx = Ctx(true_chain, session, masses, com, nominal.mass_link, payload_com, probe)
    scale = np.where(nominal.revolute, np.pi / 180, 1.0)
    rated = np.array(RATED_SPEED_DEG_S[robot_key]) * scale
    hw = {"drives": hwm.size_drives(robot_key, np.abs(ctx.loads).max(axis=0) * 1.0, rated, rng),
          "tubes": hwm.draw_tubes(robot_key, rng), "mount": hwm.draw_mount(robot_key, rng),
          "material": hwm.ROBOTS[robot_key]["material"]}
    params, dq = {}, np.zeros_like(session.q)
    strain, disp = np.zeros((n_poses, len(nominal.links))), np.zeros((n_poses, 3))
    for kind in physics:
        draw, apply, _ = EFFECTS[kind]
        params[kind] = draw(ctx, hw, rng)
        if kind in AFTER_TRACKER:
            continue
        c = apply(params[kind], ctx, hw)
        dq += 0 if c.dq is None else c.dq
        strain += 0 if c.strain is None else c.strain
        disp += 0 if c.displace is None else c.displace
    links = true_chain.links[None] * (1 + strain[..., None])
    pos = kin.target(true_chain, session.q + dq, probe, links=links) + disp
    R_f, t_f = _tracker(rng)
    hw["tracker"] = {"R": R_f, "t": t_f}
    for kind in physics:
        if kind in AFTER_TRACKER:  # a measurement effect: needs the tracker's frame
            pos = pos + EFFECTS[kind][1](params[kind], ctx, hw).displace
    noise = rng.uniform(0.01, 0.05)
    meas = pos @ R_f.T + t_f + rng.normal(0, noise, pos.shape)
    frame = _frame(nominal, session, meas)
    if split == "time":
        train, test = np.arange(int(round(0.75 * n_poses))), np.arange(int(round(0.75 * n_poses)), n_poses)
    else:
        perm = rng.permutation(n_poses)
        train, test = np.sort(perm[:int(round(0.75 * n_poses))]), np.sort(perm[int(round(0.75 * n_poses)):])
    truth = {"chain": true_chain, "geometry": geo, "masses": masses, "com": com, "payload_com_mm": payload_com,
             "probe_mm": probe, "R_frame": R_f, "t_frame": t_f, "noise_mm": noise, "hw": hw, "params": params,
             "session": session, "effect_mm": pos - kin.target(true_chain, session.q, probe)}
    return Case(case_id, robot_key, tuple(physics), frame, train, test, split, nominal, truth)


def _frame(chain, session, meas) -> pd.DataFrame:
    cols = {}
    for j in range(chain.n):
        if chain.revolute[j]:
            cols[f"q{j + 1}_deg"] = np.rad2deg(session.q[:, j])
        else:
            cols[f"q{j + 1}_mm"] = session.q[:, j]
    cols.update(x_mm=meas[:, 0], y_mm=meas[:, 1], z_mm=meas[:, 2], temperature_c=np.round(session.air_c, 3))
    cols.update({f"dir{j + 1}": session.direction[:, j].astype(int) for j in range(chain.n)})
    cols.update(payload_kg=session.payload_kg, time_s=np.round(session.time_s, 1))
    return pd.DataFrame(cols)
