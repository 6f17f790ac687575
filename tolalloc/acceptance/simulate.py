"""The acceptance test simulated robot by robot: exact kinematics, every cycle, the tracker and the registration.

:func:`simulate_acceptance` builds ``n_robots`` robots (each a draw of the systematic parts of the error parameters,
or of a calibration's posterior) and runs the ISO 9283 test on each as a laboratory would:

1. the registration poses (the cube's corners) measured ``visits`` times each, the rigid transform of least
   squares between the measured and the command positions fitted (Kabsch), every later measurement expressed
   through it;
2. P1-P5, ``cycles`` cycles each, every move a new draw of the random parts (and of the bought parts' random
   effects); the attained pose from the exact perturbed chain (the chain program of the error model,
   :class:`tolalloc.errormodel.chain.FastChain`), the tracker's error a normal draw of its standard uncertainty
   (:class:`~tolalloc.acceptance.instrument.Tracker`) per coordinate and angle;
3. the test path (with a path accuracy requirement), ``path_cycles`` cycles; the attained point at a command point
   is the attained position moved along the path's tangent into the normal plane;
4. the statistics of :mod:`tolalloc.acceptance.statistics`, once from the measurements (what the test reports)
   and once from the exact attained poses registered without the tracker's error (what the robot does).

It checks the linear prediction (:func:`tolalloc.acceptance.predict.predict_acceptance`) without its
approximations (first order, Gaussian laws, the approximate law of ``RP_l``); quantiles come with distribution-free
confidence intervals (:func:`quantile_interval`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.stats import binom

from tolalloc.exceptions import TolallocError, whole_number
from tolalloc.acceptance.model import (ANGLES, effects_at, multidirectional_labels, requirement_poses,
                                      statistic_models)
from tolalloc.acceptance.requirements import IsoRequirement, check_requirements
from tolalloc.acceptance import statistics as st
from tolalloc.errormodel.chain import FastChain
from tolalloc.errormodel.sampling import sample_values
from tolalloc.robot.lie import exp_so3

__all__ = ["SimulatedAcceptance", "simulate_acceptance", "quantile_interval", "kabsch_batch"]


def quantile_interval(x, p: float, level: float = 0.95) -> tuple[float, float, float]:
    """The ``p``-quantile of a sample and a distribution-free ``level`` confidence interval for it (order
    statistics whose ranks the binomial law brackets); ``(estimate, low, high)``."""
    x = np.sort(np.asarray(x, float).ravel())
    n = len(x)
    a = (1 - level) / 2
    lo = int(binom.ppf(a, n, p))
    hi = int(binom.ppf(1 - a, n, p)) + 1
    return float(np.quantile(x, p)), float(x[max(lo - 1, 0)]), float(x[min(hi - 1, n - 1)])


def kabsch_batch(a: np.ndarray, b: np.ndarray):
    """Rotations ``R`` (N, 3, 3) and translations ``t`` (N, 3) minimising ``sum_i |R a_i + t - b_i|^2`` for each of
    ``N`` point sets ``a``, ``b`` (N, R, 3)."""
    ca, cb = a.mean(axis=1, keepdims=True), b.mean(axis=1, keepdims=True)
    Hm = np.einsum("nri,nrj->nij", a - ca, b - cb)
    U, _, Vt = np.linalg.svd(Hm)
    d = np.sign(np.linalg.det(np.einsum("nij,njk->nik", np.swapaxes(Vt, 1, 2), np.swapaxes(U, 1, 2))))
    D = np.tile(np.eye(3), (len(a), 1, 1))
    D[:, 2, 2] = d
    R = np.swapaxes(Vt, 1, 2) @ D @ np.swapaxes(U, 1, 2)
    t = cb[:, 0] - np.einsum("nij,nj->ni", R, ca[:, 0])
    return R, t


@dataclass(frozen=True, eq=False)
class SimulatedAcceptance:
    """Results of :func:`simulate_acceptance`.

    Attributes
    ----------
    test : AcceptanceTest
    robot, measured : dict name -> array, shape (N, P)
        Each statistic (``AP_P``, ``RP_l``, ``AP_a`` ... as absolute values) per robot and row, without and with
        the tracker's error [mm or rad].
    labels : dict name -> tuple of str
    requirements : dict name -> IsoRequirement
    n_robots, seed : int
    targets : dict name -> array
        The share each row is judged at: the requirement's, and for the path points of ``AT_P`` the prediction's
        ``1 - (1 - share) / m`` (the largest over the points is then held at the share); for ``vAP_P``, per pair of
        directions, ``1 - (1 - share) / 3``.
    """

    test: object
    robot: dict
    measured: dict
    labels: dict
    requirements: dict
    n_robots: int
    seed: int
    targets: dict = None

    def to_frame(self, level: float = 0.95) -> pd.DataFrame:
        """Per statistic and row: the quantile at the row's share (:attr:`targets`; robot and measured) with its
        ``level`` interval, the measured median, and the share of simulated robots meeting the limit. Values in mm or
        deg (``unit``)."""
        rows = []
        for name, meas in self.measured.items():
            req = self.requirements[name]
            f, unit = (180 / np.pi, "deg") if req.unit == "deg" else (1.0, "mm")
            for i, lab in enumerate(self.labels[name]):
                share = float(self.targets[name][i])
                r = quantile_interval(self.robot[name][:, i], share, level)
                m = quantile_interval(meas[:, i], share, level)
                rows.append({"statistic": name, "where": lab, "unit": unit, "share": share,
                             "robot": r[0] * f, "robot_low": r[1] * f, "robot_high": r[2] * f,
                             "measured": m[0] * f, "measured_low": m[1] * f, "measured_high": m[2] * f,
                             "median_measured": float(np.median(meas[:, i])) * f,
                             "p_meets": float(np.mean(self.robot[name][:, i] <= req.limit))})
        return pd.DataFrame(rows)


def _draw(model, sigma, n, rng):
    """Values (K, n) of parameters with standard deviations ``sigma`` (their distributions)."""
    return sample_values(model.with_sigma(sigma), n, rng)


def _rotvec(E: np.ndarray) -> np.ndarray:
    """Rotation vectors (n, 3) of rotations ``E`` (n, 3, 3) by less than 90 deg (the skew part, arcsine-scaled)."""
    v = 0.5 * np.stack([E[:, 2, 1] - E[:, 1, 2], E[:, 0, 2] - E[:, 2, 0], E[:, 1, 0] - E[:, 0, 1]], axis=1)
    s = np.linalg.norm(v, axis=1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        f = np.where(s > 1e-12, np.arcsin(np.minimum(s, 1.0)) / np.where(s > 1e-12, s, 1.0), 1.0)
    return v * f


def simulate_acceptance(test, requirements, model, split=None, *, posterior=None, effects=None, n_robots: int = 2000,
                        seed: int = 0) -> SimulatedAcceptance:
    """Simulate the ISO 9283 acceptance test on ``n_robots`` built robots (module docstring).

    Parameters
    ----------
    test : AcceptanceTest
    requirements : IsoRequirement or sequence
    model : ErrorModel
        The design's error model.
    split : ErrorSplit, optional
        Default :func:`tolalloc.calibration.split.split_errors`.
    posterior : Posterior, optional
        After a calibration: the systematic parts are drawn from its remaining covariance (normal), the random
        parts with its variances.
    effects : ErrorEffects, optional
        Bought-part effects, drawn as normal errors of their means and covariances (the conditions of the first
        requirement).
    n_robots : int
    seed : int
    """
    from tolalloc.acceptance.predict import _split_for

    if whole_number(n_robots) is None or whole_number(n_robots) < 2:
        raise TolallocError(f"n_robots: expected a whole number of robots >= 2 (e.g. 2000), got {n_robots!r}.")
    n_robots = whole_number(n_robots)
    reqs = [r for r in check_requirements(requirements) if isinstance(r, IsoRequirement)]
    if not reqs:
        raise TolallocError("requirements: expected at least one ISO 9283 requirement to simulate.")
    split = _split_for(model, split)
    rng = np.random.default_rng(seed)
    ev = requirement_poses(test, reqs)
    sim = _Lab(test, model, split, posterior, effects, ev, reqs[0].conditions, n_robots, rng)
    robot, measured, labels, byname = {}, {}, {}, {}
    for req in reqs:
        for name, (r_vals, m_vals, lab) in sim.statistics(req).items():
            robot[name], measured[name], labels[name], byname[name] = r_vals, m_vals, lab, req
    targets = {sm.name: sm.target for sm in statistic_models(reqs, test, ev)}  # the prediction's shares per row
    return SimulatedAcceptance(test, robot, measured, labels, byname, n_robots, seed, targets)


class _Lab:
    """One batch of robots run through the test (positions and orientations kept per pose and cycle)."""

    def __init__(self, test, model, split, posterior, effects, ev, conditions, n, rng):
        self.test, self.model, self.ev, self.n, self.rng = test, model, ev, n, rng
        if posterior is not None:
            lam, vec = np.linalg.eigh(0.5 * (posterior.cov_sys + posterior.cov_sys.T))
            self.s = (vec * np.sqrt(np.maximum(lam, 0))) @ rng.standard_normal((len(lam), n))
            self.rand_sigma = np.sqrt(posterior.random_var)
        else:
            sys_sigma = np.where(split.systematic, model.sigma, 0.0)
            self.s = _draw(model, sys_sigma, n, rng)
            self.rand_sigma = split.random_sigma
        self.chain = FastChain(model)
        self.programs = [self.chain.program(q) for q in ev.q]
        self.work = FastChain.workspace(n)
        self.eff = effects_at(effects, test.robot, ev, conditions)
        M = len(ev.q)
        self.eff_sys = np.zeros((n, M, 6))
        if self.eff is not None:
            lam, vec = np.linalg.eigh(self.eff.systematic)
            self.eff_sys = (rng.standard_normal((n, len(lam))) @ (vec * np.sqrt(np.maximum(lam, 0))).T).reshape(n, M, 6)
            if self.eff.mean is not None:
                self.eff_sys += self.eff.mean.reshape(M, 6)
        tr = test.tracker
        self.noise_mm, self.noise_rad = tr.sigma_mm, tr.sigma_rad
        self.R_true, self.t_true, self.R_meas, self.t_meas = self._register()
        self.cmd = test.robot.fk_internal(ev.q)

    def _visit(self, m: int):
        """One move to evaluation pose ``m`` for every robot: attained position (n, 3) and rotation (n, 3, 3)."""
        V = self.s + _draw(self.model, self.rand_sigma, self.n, self.rng)
        X = self.chain.run(self.programs[m], V, np.empty((3, 4, self.n)), self.work)
        p, R = np.ascontiguousarray(X[:, 3].T), np.moveaxis(X[:, :3], -1, 0)
        if self.eff is not None:
            e = self.rng.multivariate_normal(np.zeros(6), self.eff.random[m], self.n) + self.eff_sys[:, m]
            R = exp_so3(e[:, 3:]) @ R
            p = p + e[:, :3]
        return p, R

    def _noise(self, shape, sigma):
        return sigma * self.rng.standard_normal(shape)

    def _register(self):
        reg = self.ev.registration
        if not len(reg):
            eye = np.tile(np.eye(3), (self.n, 1, 1))
            return eye, np.zeros((self.n, 3)), eye, np.zeros((self.n, 3))
        visits = self.test.registration_visits
        true = np.zeros((self.n, len(reg), 3))
        meas = np.zeros_like(true)
        for r_i, m in enumerate(reg):
            for _ in range(visits):
                p, _ = self._visit(m)
                true[:, r_i] += p / visits
                meas[:, r_i] += (p + self._noise(p.shape, self.noise_mm)) / visits
        cmd = np.broadcast_to(self.ev.points_mm[reg], true.shape)
        return (*kabsch_batch(true, cmd), *kabsch_batch(meas, cmd))

    def cycles(self, rows, n_cycles: int):
        """Registered positions and rotation errors, robot and measured: 4 arrays (n, len(rows), n_cycles, 3)."""
        shape = (self.n, len(rows), n_cycles, 3)
        pt, pm, wt, wm = (np.zeros(shape) for _ in range(4))
        for j in range(n_cycles):
            for i, m in enumerate(rows):
                p, R = self._visit(m)
                Rc = self.cmd[m, :3, :3]
                pn = p + self._noise(p.shape, self.noise_mm)
                pt[:, i, j] = np.einsum("nab,nb->na", self.R_true, p) + self.t_true
                pm[:, i, j] = np.einsum("nab,nb->na", self.R_meas, pn) + self.t_meas
                wt[:, i, j] = _rotvec(self.R_true @ R @ Rc.T)
                wm[:, i, j] = _rotvec(self.R_meas @ R @ Rc.T) + self._noise(p.shape, self.noise_rad)
        return pt, pm, wt, wm

    def _multidirectional(self, req) -> dict:
        """vAP_P or vAP_a, vAP_b, vAP_c per pose and pair of directions (the directional visits run once for both)."""
        ev, n_c, V = self.ev, self.test.cycles, len(self.ev.directional)
        if not hasattr(self, "_directional_cycles"):
            self._directional_cycles = [x.reshape(self.n, V, 3, n_c, 3)
                                        for x in self.cycles(ev.directional.ravel(), n_c)]
        pt, pm, wt, wm = self._directional_cycles
        lab = multidirectional_labels(req)
        if req.kind == "multidirectional_accuracy":
            d = [st.barycentre_distances(x).reshape(self.n, -1) for x in (pt, pm)]
            return {"vAP_P": (d[0], d[1], lab)}
        a = [st.angle_differences(x).reshape(self.n, -1, 3) for x in (wt, wm)]
        return {f"vAP_{c}": (a[0][..., j], a[1][..., j], lab) for j, c in enumerate(ANGLES)}

    def statistics(self, req) -> dict:
        """name -> (robot (n, P), measured (n, P), labels) of one requirement."""
        ev, n_c = self.ev, self.test.cycles
        P1_5 = tuple(f"P{i}" for i in range(1, len(ev.test) + 1))
        if req.kind in ("pose_accuracy", "pose_repeatability", "orientation_accuracy",
                        "orientation_repeatability", "distance_accuracy"):
            if not hasattr(self, "_test_cycles"):
                self._test_cycles = self.cycles(ev.test, n_c)
            pt, pm, wt, wm = self._test_cycles
            cmd = ev.points_mm[ev.test]
        if req.kind == "pose_accuracy":
            return {"AP_P": (st.pose_accuracy(pt, cmd), st.pose_accuracy(pm, cmd), P1_5)}
        if req.kind == "pose_repeatability":
            return {"RP_l": (st.pose_repeatability(pt), st.pose_repeatability(pm), P1_5)}
        if req.kind == "orientation_accuracy":
            a_t, a_m = (np.abs(st.orientation_accuracy(w, np.zeros(3))) for w in (wt, wm))  # deviations: command 0
            return {f"AP_{a}": (a_t[..., j], a_m[..., j], P1_5) for j, a in enumerate(ANGLES)}
        if req.kind == "orientation_repeatability":
            r_t, r_m = st.orientation_repeatability(wt), st.orientation_repeatability(wm)
            return {f"RP_{a}": (r_t[..., j], r_m[..., j], P1_5) for j, a in enumerate(ANGLES)}
        if req.kind == "distance_accuracy":
            a, b = (i - 1 for i in req.poses)
            lab = (f"P{req.poses[0]}-P{req.poses[1]}",)
            ad = [np.abs(st.distance_accuracy(x[:, a], x[:, b], cmd[a], cmd[b]))[:, None] for x in (pt, pm)]
            return {"AD_P": (ad[0], ad[1], lab)}
        if req.kind.startswith("multidirectional"):
            return self._multidirectional(req)
        pt, pm, _, _ = self.cycles(ev.path, self.test.path_cycles)
        cmd = ev.points_mm[ev.path]
        t = ev.tangents
        out = []
        for x in (pt, pm):
            d = x - cmd[None, :, None, :]
            d = d - np.einsum("ncjk,ck,cl->ncjl", d, t, t)  # across the path only
            out.append(st.pose_accuracy(d, np.zeros(3)))
        return {"AT_P": (out[0], out[1], tuple(f"path point {i + 1}" for i in range(len(ev.path))))}
