"""End-to-end nonlinear check of the calibration story: manufacture, measure, calibrate, compensate, use.

For each of ``n_robots`` simulated robots:

1. the systematic parts ``s`` are drawn from the manufacturing prior (:meth:`ErrorModel.sample`), plus a tracker
   registration (rotation ``N(0, 1e-3 rad)``, translation ``N(0, 1 mm)``) and a target offset on the flange
   (``N(0, 1 mm)``);
2. the plan's measurements are simulated with the exact perturbed kinematics (the model's chain program evaluated
   by :class:`~tolalloc.errormodel.chain.FastChain`, vectorised over the robots, one pose program per plan pose)
   with fresh random parts at every measurement and tracker noise ``sigma_m``;
3. a nonlinear least-squares calibration (Gauss-Newton on the exact residuals with the nominal Jacobian, MAP with
   the manufacturing prior on the estimated parameters, registration and target offset free; all robots solved
   together, each started at the nominal model and iterated to convergence; a fit whose step grows restarts with
   the Jacobian at the estimate; see :func:`~tolalloc.verify.calibrated_fit._fit`; iteration counts and
   non-converged fits are in the result and its message) estimates ``s_E``;
4. the controller compensates with ``s_E_hat``; at every working pose a fresh random part is drawn and
   ``dP = p_true(q) - p_model(s_E_hat, q)`` is evaluated exactly.

``P_hat(|dP| < r)`` per pose (one draw per robot and pose, so robots are independent trials) with a Wilson
interval is reported beside the linear post-calibration prediction of :mod:`tolalloc.calibration.posterior`.
The intervals are simultaneous over the poses (Bonferroni, level ``1 - (1 - level) / P`` each:
:func:`tolalloc.montecarlo.intervals.simultaneous_level`). The diagnosis's
calibrator (:mod:`tolalloc.diagnose.calibrate`) is not used: it fits one robot at a time with its own parameter
selection, and it is being rewritten; the fit here is the plan's Bayesian estimator itself.

This module holds the result, :class:`CalibrationCheck`, the driver, :func:`verify_calibration`, and the linearised
pipeline that is the paired estimator's control; the simulated measurements and the fits of steps 2 and 3 are in
:mod:`tolalloc.verify.calibrated_fit`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.calibration.plan import CalibrationPlan
from tolalloc.calibration.posterior import nuisance_columns, posterior
from tolalloc.calibration.split import ErrorSplit
from tolalloc.exceptions import ArgumentError, TolallocError
from tolalloc.linear.probability import p_within_radius
from tolalloc.montecarlo.estimate import ProbabilityEstimate
from tolalloc.montecarlo.intervals import simultaneous_level
from tolalloc.montecarlo.paired import PairedCounts, check_estimator, control_fallback_reason, estimate_from_counts
from tolalloc.montecarlo.streaming import proportion_ci
from tolalloc.verify.calibrated_fit import _STEP_TOL, _PlanChains, _fit, _measure

__all__ = ["CalibrationCheck", "verify_calibration", "REGISTRATION_SIGMA"]

#: Sigmas of the simulated registration rotation [rad], translation [mm] and target offset [mm].
REGISTRATION_SIGMA = (1e-3, 1.0, 1.0)


@dataclass(frozen=True, eq=False)
class CalibrationCheck:
    """Result of :func:`verify_calibration`.

    Attributes
    ----------
    q : array, shape (P, n) [rad, mm]
    radius_mm : float
    p_linear : array, shape (P,)
        Linear post-calibration prediction of ``P(|dP| < r)``.
    p_mc, ci_low, ci_high : arrays, shape (P,)
        Monte Carlo estimate and simultaneous interval.
    n_robots : int
    rms_step : float
        Largest normalised size of the last Gauss-Newton step over the robots (convergence indicator).
    fits_per_s : float
        Simulated calibrations per second of wall time (sampling, simulated measurements and the fits).
    iterations : array of int, shape (n_robots,)
        Gauss-Newton iterations of each robot's fit (the maximum where it did not converge).
    fit_cpu_s : float
        CPU time of the same part [s] (all threads of the process).
    n_exact : int
        Fits that left the fixed (nominal) Jacobian for the Jacobian at the estimate (see
        :func:`~tolalloc.verify.calibrated_fit._fit`).
    n_converged : int
        Fits whose last normalised step is below the step tolerance.
    estimate : ProbabilityEstimate or None
        With ``estimator`` ``paired`` / ``auto``: the paired estimate, whose control is the *linearised pipeline*
        (linear measurements, the linear MAP fit, linear use; exact Gaussian P in ``estimate.p_linear``), its
        discordant counts and variance reduction; ``p_mc``/``ci_*`` are then its estimate and interval.
    family_level : float
        Level at which the intervals of all ``P`` poses hold together (each at ``1 - (1 - family_level) / P``).
    """

    q: np.ndarray
    radius_mm: float
    p_linear: np.ndarray
    p_mc: np.ndarray
    ci_low: np.ndarray
    ci_high: np.ndarray
    n_robots: int
    rms_step: float
    fits_per_s: float
    iterations: np.ndarray
    fit_cpu_s: float
    n_exact: int = 0
    n_converged: int = 0
    estimate: ProbabilityEstimate | None = None
    family_level: float = 0.95

    @property
    def n_intervals(self) -> int:
        """Intervals judged together: one per pose (the position requirement only)."""
        return len(self.q)

    @property
    def level_per_interval(self) -> float:
        """Level of each interval (Bonferroni): ``1 - (1 - family_level) / n_intervals``."""
        return simultaneous_level(self.family_level, self.n_intervals)

    @property
    def estimator(self) -> np.ndarray:
        """Estimator that ran at each pose (``plain`` or ``paired``), shape (P,)."""
        return np.full(len(self.q), "plain") if self.estimate is None else self.estimate.estimator

    @property
    def converged(self) -> bool:
        """Whether every fit met its step tolerance."""
        return bool(self.rms_step < _STEP_TOL)

    @property
    def converged_share(self) -> float:
        """Share of the simulated calibrations whose fit met its step tolerance."""
        return self.n_converged / self.n_robots

    @property
    def agree(self) -> np.ndarray:
        """Whether the linear prediction lies in the Monte Carlo interval, per pose."""
        return (self.p_linear >= self.ci_low) & (self.p_linear <= self.ci_high)

    def to_frame(self) -> pd.DataFrame:
        """One row per pose: p_linear, p_mc, ci_low, ci_high, ``level_per_interval`` (the level of each interval),
        ``family_level`` (the level at which all of them hold together), agree, estimator (and the paired
        estimate's columns)."""
        cols = {"pose": np.arange(1, len(self.q) + 1), "p_linear": self.p_linear, "p_mc": self.p_mc,
                "ci_low": self.ci_low, "ci_high": self.ci_high, "level_per_interval": self.level_per_interval,
                "family_level": self.family_level, "agree": self.agree, "estimator": self.estimator}
        if self.estimate is not None:
            cols.update({"p_linear_pipeline": self.estimate.p_linear, "n_discordant": self.estimate.n_discordant,
                         "variance_reduction": self.estimate.variance_reduction})
        return pd.DataFrame(cols)

    def fits_note(self) -> str:
        """Convergence of the fits: iteration counts, and how many robots did not converge."""
        it = self.iterations
        bad = self.n_robots - self.n_converged
        note = f"Gauss-Newton iterations per fit: median {np.median(it):g}, max {it.max()}"
        if self.n_exact:
            note += f"; {self.n_exact} fits with the Jacobian at the estimate"
        return note + (f"; {bad} of {self.n_robots} fits NOT converged (last step {self.rms_step:.2e})" if bad else "")

    def message(self) -> str:
        bad = np.flatnonzero(~self.agree)
        if not len(bad):
            return (f"the linear post-calibration prediction lies in the Monte Carlo interval at all {len(self.q)} "
                    f"poses ({self.n_robots} simulated calibrations; {self.fits_note()})")
        worst = bad[np.argmax(np.abs(self.p_linear[bad] - self.p_mc[bad]))]
        return (f"the linear prediction is outside the interval at {len(bad)} of {len(self.q)} poses; worst pose "
                f"{worst + 1}: linear {self.p_linear[worst]:.4f}, Monte Carlo {self.p_mc[worst]:.4f} "
                f"[{self.ci_low[worst]:.4f}, {self.ci_high[worst]:.4f}] ({self.fits_note()})")


def _linear_pipeline(model, E, prior_sd, plan: CalibrationPlan, q_eval, var_sys, var_rnd):
    """The linearised calibration story, the paired estimator's control.

    Linear readings ``y = J0 truth + sum_m J_m extra_m + noise`` (``J0`` the fit's nominal Jacobian: error
    columns ``E`` and, with registration, the nuisance columns), the linear MAP ``x_hat = H y`` (the fixed point
    of :func:`~tolalloc.verify.calibrated_fit._fit` on linear residuals, reached in one step), and the linear
    compensated error at the working poses ``err = J_p (s + fresh_p) - J_p,E x_hat_E``. Every input is an
    independent Gaussian block, so ``err`` is Gaussian with the covariance returned here (systematic parts,
    registration, random parts at the measurements, tracker noise, fresh random parts).

    Returns
    -------
    H : array, shape (D, 3M)
    J0 : array, shape (3M, D)
    Jm : array, shape (M, 3, K)
    Jp : array, shape (P, 3, K)
    cov : array, shape (P, 3, 3) [mm^2]
    """
    nN = 9 if plan.registration else 0
    D = len(E) + nN
    scale = np.r_[prior_sd, np.full(3, 1e-3), np.full(6, 1.0)][:D]
    Jm = model.jacobian(plan.q)[:, :3, :]
    J0 = Jm[:, :, E]
    if nN:
        J0 = np.concatenate([J0, nuisance_columns(model, plan.q, 3)], axis=2)
    J0 = J0.reshape(-1, D)
    Jn = J0 * scale / plan.noise_mm
    A = Jn.T @ Jn + np.diag(np.r_[np.ones(len(E)), np.zeros(nN)])
    A += 1e-12 * np.trace(A) / D * np.eye(D)  # as in calibrated_fit._fit
    H = (scale[:, None] * np.linalg.solve(A, Jn.T)) / plan.noise_mm
    Jp = model.jacobian(np.atleast_2d(q_eval))[:, :3, :]
    G = Jp[:, :, E] @ H[: len(E)]  # (P, 3, 3M)
    M = len(plan.q)
    cs = Jp - G @ Jm.reshape(3 * M, -1)
    cov = np.einsum("pik,k,pjk->pij", cs, var_sys, cs)
    if nN:
        sr, st, so = REGISTRATION_SIGMA
        cr = -G @ J0[:, len(E):]
        cov += np.einsum("pik,k,pjk->pij", cr, np.repeat([sr**2, st**2, so**2], 3), cr)
    ce = np.einsum("pimj,mjk->pimk", G.reshape(len(Jp), 3, M, 3), Jm)
    cov += np.einsum("pimk,k,pjmk->pij", ce, var_rnd, ce)
    cov += plan.noise_mm**2 * G @ np.swapaxes(G, 1, 2)
    cov += np.einsum("pik,k,pjk->pij", Jp, var_rnd, Jp)
    return H, J0, Jm, Jp, 0.5 * (cov + np.swapaxes(cov, 1, 2))


def _paired(err, draws, lin, E, radius_mm, level, seed, estimator, reason):
    """Paired estimate of ``P(|err| < r)`` per pose with the linearised pipeline on the same draws as control."""
    s, truth, extra, noise, fresh = draws
    H, J0, Jm, Jp, cov = lin
    B = len(s)
    y = truth @ J0.T + np.einsum("mik,bmk->bmi", Jm, extra).reshape(B, -1) + noise.reshape(B, -1)
    x_hat = y @ H.T
    e_lin = (np.einsum("pik,bk->bpi", Jp, s) + np.einsum("pik,bpk->bpi", Jp, fresh)
             - np.einsum("pie,be->bpi", Jp[:, :, E], x_hat[:, : len(E)]))
    nl, li = err < radius_mm, np.linalg.norm(e_lin, axis=-1) < radius_mm
    counts = np.stack([nl.sum(0), li.sum(0), (nl & li).sum(0)], axis=1)[:, None, :].astype(np.int64)
    dev = np.abs(err - np.linalg.norm(e_lin, axis=-1)).max(axis=0)
    pc = PairedCounts(B, int(seed), counts, dev)
    return estimate_from_counts(pc, 0, radius_mm, p_within_radius(cov, radius_mm), estimator=estimator,
                                model_reason=reason, level=level)


def verify_calibration(split: ErrorSplit, plan: CalibrationPlan, q_eval, radius_mm: float, *, n_robots: int = 400,
                       seed: int = 0, level: float = 0.95, estimator: str = "plain") -> CalibrationCheck:
    """End-to-end Monte Carlo of manufacture -> calibration -> compensated use (see the module docstring).

    Parameters
    ----------
    split : ErrorSplit
    plan : CalibrationPlan
        Position measurements; estimates every systematic parameter with a non-zero prior (and the registration and
        target offset if ``plan.registration``; else they are known and zero).
    q_eval : array, shape (P, n) [rad, mm]
    radius_mm : float
    n_robots : int
        Simulated robots (= trials per pose).
    estimator : {"plain", "auto", "paired"}
        ``plain``: Wilson intervals of the nonlinear hits. ``paired``: the linearised pipeline on the same draws
        as control (:func:`_linear_pipeline`; its exact Gaussian P plus the mean difference of the two indicators,
        Tango's interval); ``auto``: paired for Gaussian parameters, plain elsewhere or where the control is poor.
        The control's P is the linearised *simulated* pipeline's, which differs from ``p_linear`` (the posterior's
        prediction) where the random parts make the simulated MAP fit differ from the posterior's weighting.
    """
    check_estimator(estimator, ("auto", "plain", "paired"))
    model = split.model
    reason = control_fallback_reason(model)
    if estimator == "paired" and reason:
        raise ArgumentError("estimator", f"'paired' needs Gaussian parameters; {reason.split(':')[0]}. Use "
                            "estimator='auto' or 'plain'.")
    if plan.measurement != "position" or plan.estimate is not None:
        raise TolallocError("verify_calibration: expected a position plan estimating all systematic parameters "
                            "(measurement = position, estimate = all).")
    if plan.n_poses == 0:
        raise TolallocError("verify_calibration: the plan has no poses; nothing to calibrate.")
    q_eval = np.atleast_2d(model.robot.check_q(q_eval, "q_eval"))
    rng = np.random.default_rng(seed)
    K = len(model.params)
    E = np.array([k for k in split.sys_index if model.sigma[k] > 0], dtype=int)
    sys_model = model.with_sigma(np.where(split.systematic, model.sigma, 0.0))
    rnd_model = model.with_sigma(split.random_sigma)
    M, P = plan.n_poses, len(q_eval)
    t0, c0 = time.perf_counter(), time.process_time()
    s = sys_model.sample(n_robots, rng)  # (B, K)
    sr, st, so = REGISTRATION_SIGMA
    truth = s[:, E]
    if plan.registration:  # without registration the tracker frame and target offset are known exactly
        truth = np.concatenate([truth, rng.normal(0, sr, (n_robots, 3)), rng.normal(0, st, (n_robots, 3)),
                                rng.normal(0, so, (n_robots, 3))], axis=1)
    extra = rnd_model.sample(n_robots * M, rng).reshape(n_robots, M, K)
    not_est = np.setdiff1d(np.arange(K), E)
    extra = extra + s[:, None, :] * np.isin(np.arange(K), not_est)  # systematic parts not estimated stay in
    chains = _PlanChains(model, plan.q)
    noise = rng.normal(0, plan.noise_mm, (n_robots, M, 3))
    y = _measure(chains, truth, E, extra) + noise
    prior_sd = np.sqrt(split.prior_var_of(E))
    est, steps, iters, exact = _fit(chains, model, E, prior_sd, plan, y)
    fit_time, fit_cpu = time.perf_counter() - t0, time.process_time() - c0
    # use: fresh random parts at every working pose; the model predicts with the estimated systematic parts
    hat = np.zeros((n_robots, K))
    hat[:, E] = est[:, : len(E)]
    fresh = rnd_model.sample(n_robots * P, rng).reshape(n_robots, P, K)
    use = _PlanChains(model, q_eval)
    p_true, _ = use.tool(s, fresh)
    p_hat, _ = use.tool(hat)
    err = np.linalg.norm(p_true - p_hat, axis=-1)  # (B, P)
    lvl = simultaneous_level(level, P)
    p_lin = p_within_radius(posterior(split, plan).tool_covariance(q_eval), radius_mm)
    pe = None
    if estimator == "plain":
        ci = proportion_ci(np.sum(err < radius_mm, axis=0), n_robots, "wilson", lvl)
    else:
        lin = _linear_pipeline(model, E, prior_sd, plan, q_eval, sys_model.sigma**2, split.random_sigma**2)
        pe = _paired(err, (s, truth, extra, noise, fresh), lin, E, radius_mm, lvl, seed, estimator, reason)
        ci = np.stack([pe.p_hat, pe.ci_low, pe.ci_high], axis=1)
    return CalibrationCheck(q_eval, float(radius_mm), p_lin, ci[:, 0], ci[:, 1], ci[:, 2], n_robots,
                            float(steps.max()), n_robots / fit_time, iters, fit_cpu, int(exact.sum()),
                            int(np.sum(steps < _STEP_TOL)), pe, float(level))
