"""What differs between the two UR10 sessions: measured, for the study's report (section "Across sessions").

Four measurements, all computed here (no number typed by hand):

* **Joint-angle coverage** (:func:`coverage`): per joint, the share of one session's poses whose angle (mod 360 deg)
  lies within :data:`COVER_DEG` of an angle the other session visited. Every joint-angle-periodic effect (the
  transmission's harmonic series, joint offsets seen through the chain) is known only where a session went.
* **One robot, two sessions** (:func:`one_robot`): the same model (geometry; geometry + transmission ``series36``
  + joint compliance ``masses``) fitted to each session alone and to both sessions together with one shared
  geometry and effect set and only the tracker frame and probe offset per session (9 parameters each); and with
  the joint offsets per session as well. When the joint fit reaches the RMS of the single-session fits, one robot
  explains both sessions: nothing in the robot changed between them (no re-mounted base, no changed joint zero,
  no other tool), only the tracker frame and probe offset.
* **Registration** (:func:`registration_rows`): the across-session diagnoses' geometric and final models scored on
  the same poses after registering the tracker frame and probe offset on 30 test poses (as scored) and on every
  test pose (in-sample: the most better registration could give).
* **Temperature** (:func:`thermal_estimate`): the length change of the arm between the sessions' mean
  temperatures, for aluminium links (:data:`ALPHA_AL`).

The joint fit (:func:`joint_fit`) is a Gauss-Newton MAP fit of the library's measurement model (``Fit.base_points``)
with the geometric prior of :mod:`tolalloc.diagnose.geometry` and the transmission's prior scales by marginal
likelihood (:func:`tolalloc.diagnose.evidence.ard_evidence`); poses beyond :data:`TRIM` x the median 3-D residual
are dropped after the first pass (gross errors), as the library's robust fits do.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pandas as pd
from scipy.spatial.transform import Rotation

from tolalloc.diagnose import calibrate
from tolalloc.diagnose.effects import effect_basis, effect_reference
from tolalloc.diagnose.evidence import ard_evidence
from tolalloc.diagnose.guards import parameter_checks
from tolalloc.diagnose.register import REGISTER_N, RegistrationSplit, register_and_score, registration_split
from tolalloc.diagnose.scores import rms
from tolalloc.diagnose.select import align_basis

#: A pose counts as covered when the other session visited an angle within this of it [deg].
COVER_DEG = 2.0
#: Linear expansion coefficient of aluminium [1/K] (the UR10's links).
ALPHA_AL = 23e-6
#: Poses beyond this factor x the median 3-D residual are dropped after the first pass.
TRIM = 5.0
EFFECTS = (("transmission", "series36"), ("joint_compliance", "masses"))



def coverage(A: pd.DataFrame, C: pd.DataFrame, n_joints: int) -> pd.DataFrame:
    """Share [%] of each session's poses per joint whose angle mod 360 the other session visited (+-COVER_DEG)."""
    rows = []
    for test, train, name in ((C, A, "C poses covered by A"), (A, C, "A poses covered by C")):
        row = {"poses": name}
        for j in range(n_joints):
            seen = np.zeros(360, bool)
            seen[np.floor(np.mod(train[f"q{j + 1}"].to_numpy(), 360.0)).astype(int) % 360] = True
            w = int(COVER_DEG)
            near = np.any([np.roll(seen, s) for s in range(-w, w + 1)], axis=0)
            row[f"q{j + 1}_pct"] = 100 * near[np.floor(np.mod(test[f"q{j + 1}"].to_numpy(), 360.0)).astype(int) % 360].mean()
        rows.append(row)
    return pd.DataFrame(rows)


def _basis(robot, m, t_mm, names=None):
    """Transmission series36 + compliance masses on the poses of ``m`` (base frame), its column names and groups."""
    ref = effect_reference(m)
    parts = [effect_basis(e, robot, m, t_mm, ref, v) for e, v in EFFECTS]
    if names is not None:
        parts = [align_basis(b, nm) for b, nm in zip(parts, names)]
    groups = np.concatenate([parts[0].groups, np.full(parts[1].B.shape[2], robot.n_joints)])
    return np.concatenate([b.B for b in parts], axis=2), [b.names for b in parts], groups


class _Joint:
    """Shared geometry ``geo`` (+ per-session ``specific``) and effects ``beta``; per session ``R, p, t``."""

    def __init__(self, fits, ms, Bs, geo, specific):
        self.fits, self.ms, self.Bs, self.S = fits, ms, Bs, len(fits)
        self.geo, self.spec = np.asarray(geo, int), np.asarray(specific, int)
        self.M, self.R0 = Bs[0].shape[2], [f.R.copy() for f in fits]
        self.nl = 9 * self.S + len(self.geo) + len(self.spec) * (self.S - 1)
        self.x = np.concatenate([np.r_[np.zeros(3), f.p_mm, f.t_mm] for f in fits] + [fits[0].delta[self.geo]]
                                + [np.zeros(len(self.spec) * (self.S - 1) + self.M)])
        self.keep = [np.ones(m.n_poses, bool) for m in ms]
        self.w_geo = 0.05 / fits[0].model.sigma[self.geo]  # prior rows: noise / prior sd (noise ~0.05 mm)
        self.w_beta = np.ones(self.M)

    def fit_of(self, x, s):
        """Session ``s``'s :class:`Fit` (geometry, frame) and effect coefficients at ``x``."""
        r, k, ns = x[9 * s:9 * s + 9], 9 * self.S, len(self.spec)
        delta = np.zeros_like(self.fits[s].delta)
        delta[self.geo] = x[k:k + len(self.geo)]
        if s > 0 and ns:
            delta[self.spec] += x[k + len(self.geo) + (s - 1) * ns:k + len(self.geo) + s * ns]
        R = self.R0[s] @ Rotation.from_rotvec(r[:3]).as_matrix()
        return replace(self.fits[s], R=R, p_mm=r[3:6], t_mm=r[6:9], delta=delta), x[self.nl:]

    def residual(self, x, s):
        f, beta = self.fit_of(x, s)
        return ((f.base_points(self.ms[s].q) + self.Bs[s] @ beta) @ f.R.T + f.p_mm - self.ms[s].xyz_mm)[self.keep[s]]

    def system(self, x):
        """Stacked residual and Jacobian (numeric for frame and geometry, analytic for the linear effects)."""
        res = [self.residual(x, s).ravel() for s in range(self.S)]
        rows = np.cumsum([0] + [len(r) for r in res])
        J = np.zeros((rows[-1], len(x)))
        for i in range(self.nl):
            xx = x.copy()
            xx[i] += 1e-6
            for s in range(self.S):
                if i < 9 * self.S and i // 9 != s:
                    continue  # another session's frame
                J[rows[s]:rows[s + 1], i] = (self.residual(xx, s).ravel() - res[s]) / 1e-6
        for s in range(self.S):
            R = self.fit_of(x, s)[0].R
            J[rows[s]:rows[s + 1], self.nl:] = np.einsum("ij,pjm->pim", R, self.Bs[s][self.keep[s]]).reshape(
                rows[s + 1] - rows[s], self.M)
        k = 9 * self.S
        P = np.zeros((len(self.geo) + self.M, len(x)))
        P[np.arange(len(self.geo)), k + np.arange(len(self.geo))] = self.w_geo
        P[len(self.geo) + np.arange(self.M), self.nl + np.arange(self.M)] = self.w_beta
        r = np.concatenate(res + [P @ x])
        return r, np.vstack([J, P])

    def solve(self, iters):
        for _ in range(iters):
            r, J = self.system(self.x)
            dx = np.linalg.lstsq(J, -r, rcond=None)[0]
            self.x = self.x + dx
            if np.abs(dx[:self.nl]).max() < 1e-7:
                break


def joint_fit(fits, ms, Bs, groups, geo, specific=()):
    """MAP fit of sessions ``ms`` with shared geometry/effects (module docstring); returns the fitted :class:`_Joint`."""
    J = _Joint(fits, ms, Bs, geo, specific)
    J.solve(3)
    for s in range(J.S):
        e = np.linalg.norm(J.residual(J.x, s), axis=1)  # all poses are kept before the first trim
        J.keep[s] = e < TRIM * np.median(e)
    if J.M:  # prior scales per group by marginal likelihood on the current residual, bases in each tracker frame
        Phi = np.vstack([np.einsum("ij,pjm->pim", J.fit_of(J.x, s)[0].R, Bs[s][J.keep[s]]).reshape(-1, J.M)
                         for s in range(J.S)])
        y = -np.concatenate([J.residual(J.x, s).ravel() for s in range(J.S)]) + Phi @ J.x[J.nl:]
        ev = ard_evidence(Phi, y, groups)
        J.w_beta = ev.noise_sd / ev.sd
    J.solve(6)
    return J


def one_robot(robot, ms: dict) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Single-session vs joint fits (module docstring): RMS table, and the geometric-only parameters of the two
    single-session calibrations side by side with their posterior sd and the difference in sigmas."""
    cals = {s: calibrate(robot, m) for s, m in ms.items()}
    (a, ca), (c, cc) = cals.items()
    geo = np.union1d(ca.geometric.geo_index, cc.geometric.geo_index)
    model = ca.geometric.model
    offsets = [g for g in geo if model.params[g].name.endswith("_offset")]
    fits = [cals[s].geometric for s in ms]
    BA, names, groups = _basis(robot, ms[a], ca.geometric.t_mm)
    BC = _basis(robot, ms[c], cc.geometric.t_mm, names)[0]
    rows = []
    for label, Bs in (("geometric", [BA[:, :, :0], BC[:, :, :0]]),
                      ("geometric+transmission+joint_compliance", [BA, BC])):
        g = groups[:Bs[0].shape[2]]
        alone = [joint_fit([f], [m], [B], g, geo) for f, m, B in zip(fits, ms.values(), Bs)]
        both = joint_fit(fits, list(ms.values()), Bs, g, geo)
        offs = joint_fit(fits, list(ms.values()), Bs, g, geo, offsets)
        for i, s in enumerate(ms):
            rows.append({"model": label, "session": s, "alone_rms_mm": rms(alone[i].residual(alone[i].x, 0)),
                         "joint_rms_mm": rms(both.residual(both.x, i)),
                         "joint_with_own_offsets_rms_mm": rms(offs.residual(offs.x, i)),
                         "joint_model_reg30_rms_mm": _reg30(both, i, robot.revolute_mask)})
    pa, pc = (parameter_checks(cals[s].geometric, ms[s].q).to_frame() for s in ms)
    par = pa.merge(pc, on=["parameter", "unit"], suffixes=(f"_{a}", f"_{c}"))
    par["difference_sigmas"] = (par[f"value_{a}"] - par[f"value_{c}"]) / np.hypot(par[f"posterior_sd_{a}"],
                                                                                  par[f"posterior_sd_{c}"])
    par = par[["parameter", "unit", f"value_{a}", f"posterior_sd_{a}", f"value_{c}", f"posterior_sd_{c}",
               "difference_sigmas"]]
    return pd.DataFrame(rows), par.reindex(par["difference_sigmas"].abs().sort_values(ascending=False).index)


def _reg30(J, s, revolute, n=REGISTER_N) -> float:
    """The joint model on session ``s`` re-registered (frame + probe offset) on ``n`` of its poses, RMS of the rest."""
    f, beta = J.fit_of(J.x, s)
    m = J.ms[s]
    split = registration_split(m.q, revolute, n)
    return rms(register_and_score(f, m.q, m.xyz_mm, J.Bs[s] @ beta, split).residual_mm)


def registration_rows(name: str, d) -> list:
    """The across run ``d``'s geometric and final models: registered on its 30 poses (scored) vs on every test pose."""
    test, sc = d.test, d.scored_index
    every = RegistrationSplit(np.arange(test.n_poses), sc, float(test.n_poses))
    reg = d.registered
    extra_final = (d.final.test_pred_mm - reg.p_mm) @ reg.R - reg.base_points(test.q)
    rows = []
    for label, ev, extra in (("geometric", d.geometric, np.zeros((test.n_poses, 3))), ("final", d.final, extra_final)):
        all_reg = register_and_score(ev.fit, test.q, test.xyz_mm, extra, every, t_prior=None)
        rows.append({"run": name, "model": label, "registered_on_30_rms_mm": rms(ev.test_mm),
                     "registered_on_all_test_poses_rms_mm": rms(all_reg.residual_mm)})
    return rows


def thermal_estimate(robot_size_mm: float, A: pd.DataFrame, C: pd.DataFrame) -> dict:
    """Length change of an aluminium arm of ``robot_size_mm`` between the sessions' mean temperatures [mm]."""
    dT = float(A["temperature_c"].mean() - C["temperature_c"].mean())
    return {"delta_T_K": dT, "length_change_mm": ALPHA_AL * abs(dT) * robot_size_mm}


def section(robot, A_all, C_all, ms: dict, reg_rows: list, out) -> list:
    """The report section "What differs between the sessions" (tables written to ``out`` as CSV too)."""
    from tolalloc.diagnose.geometry import robot_size_mm
    cov = coverage(A_all, C_all, robot.n_joints)
    fits, par = one_robot(robot, ms)
    reg = pd.DataFrame(reg_rows)
    th = thermal_estimate(robot_size_mm(robot), A_all, C_all)
    for df, name in ((cov, "sessions_coverage"), (fits, "sessions_one_robot"), (par, "sessions_geometry"),
                     (reg, "sessions_registration")):
        df.to_csv(out / f"{name}.csv", index=False, float_format="%.5g")
    full = fits[fits["model"] != "geometric"].set_index("session")
    geo = fits[fits["model"] == "geometric"].set_index("session")
    fin = reg[reg["model"] == "final"].set_index("run")
    big = par[par["difference_sigmas"].abs() > 3]
    q1 = cov.set_index("poses")["q1_pct"]
    return ["## What differs between the sessions (measured, `sessions.py`)", "",
            f"Joint-angle coverage: share [%] of one session's poses whose angle (mod 360 deg) lies within "
            f"{COVER_DEG:.0f} deg of an angle the other session visited (sessions_coverage.csv):", "",
            cov.to_markdown(index=False, floatfmt=".1f"), "",
            "One robot, two sessions: the same model fitted to each session alone and to both together with one shared "
            "geometry and effect set and only the tracker frame + probe offset per session (9 parameters each), and with "
            "the joint offsets per session as well; `joint_model_reg30_rms_mm`: the joint model re-registered on 30 "
            "poses of the session, RMS of its other poses (sessions_one_robot.csv):", "",
            fits.to_markdown(index=False, floatfmt=".3f"), "",
            "Registration: the across runs' models scored on the same poses, registered on 30 test poses (as scored) "
            "and on every test pose (in-sample; sessions_registration.csv):", "",
            reg.to_markdown(index=False, floatfmt=".3f"), "",
            "Geometric parameters of the geometry-only calibration of each session that differ by more than 3 "
            "posterior sd (all in sessions_geometry.csv):", "",
            big.to_markdown(index=False, floatfmt=".3g"), "",
            "Reading:", "",
            "* Nothing in the robot changed between the sessions: one shared geometry + transmission + compliance "
            "model with only the tracker frame and probe offset per session fits A at "
            f"{full.loc['A', 'joint_rms_mm']:.3f} mm and C at {full.loc['C', 'joint_rms_mm']:.3f} mm against "
            f"{full.loc['A', 'alone_rms_mm']:.3f} and {full.loc['C', 'alone_rms_mm']:.3f} mm fitted alone; joint "
            f"offsets per session change that to {full.loc['A', 'joint_with_own_offsets_rms_mm']:.3f} / "
            f"{full.loc['C', 'joint_with_own_offsets_rms_mm']:.3f} mm. The geometry-only parameters differ by up to "
            f"{par['difference_sigmas'].abs().max():.1f} sd between the sessions, yet one shared geometry costs only "
            f"{geo.loc['A', 'joint_rms_mm'] - geo.loc['A', 'alone_rms_mm']:.3f} / "
            f"{geo.loc['C', 'joint_rms_mm'] - geo.loc['C', 'alone_rms_mm']:.3f} mm RMS: the geometry-only fits absorb "
            "the unmodelled joint-angle errors of their own pose set differently, the geometry itself is the same.",
            f"* Not the registration: a model that has seen both sessions, re-registered on 30 poses, scores "
            f"{full.loc['A', 'joint_model_reg30_rms_mm']:.3f} / {full.loc['C', 'joint_model_reg30_rms_mm']:.3f} mm; the "
            "across runs' final models registered on every test pose (in-sample) still score "
            + ", ".join(f"{r} {v:.3f} mm (30 poses: {fin.loc[r, 'registered_on_30_rms_mm']:.3f})"
                        for r, v in fin["registered_on_all_test_poses_rms_mm"].items()) + ".",
            f"* Not temperature: {abs(th['delta_T_K']):.2f} K between the sessions' mean temperatures lengthens a "
            f"{robot_size_mm(robot):.0f} mm aluminium arm by {th['length_change_mm']:.3f} mm.",
            f"* The joint-angle coverage: {q1.iloc[0]:.1f} % of C's poses have a shoulder-pan angle A visited and "
            f"{q1.iloc[1]:.1f} % of A's one C visited (the q1 ranges do not overlap mod 360 deg), and shoulder-lift and "
            "elbow angles of A lie mostly outside C's. The joint-angle-dependent error (the transmission's harmonics, "
            "the geometric fit's compensation of them) at those angles is in neither training session, so no model "
            "trained on one session can predict it with the frame and probe offset alone: the registration poses "
            "of the new session must also correct the trained parameters (the `calibration` update, section "
            "\"Registration poses a new session needs\").", ""]
