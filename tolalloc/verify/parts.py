"""Nonlinear Monte Carlo verification of a design with bought parts, at its worst points.

Every sample is one built robot making one move: its machining errors (the design's half-widths, drawn by the error
model) and the bought parts' effects drawn physically (:func:`tolalloc.errormodel.parts_sample.sample_effects`: the
catalogue's torque-torsion curve at the drawn stiffness, gear and encoder errors at the joint angle, the bearings'
rotating eccentricities, lost motion by approach direction) go through the exact perturbed chain of
:func:`~tolalloc.errormodel.parts.parts_error_model` (:func:`tolalloc.montecarlo.run.pose_errors`), plus the beam and
mount displacements. The point (pose, payload, ambient) is the region's worst one found by the allocation's search
and, optionally, its active points.

**Paired estimator with the linear model as its control.** On the same draws the linear map ``J v + d`` gives a
second indicator. The linear draws are not Gaussian (sines, flanks), so the mean of the linear indicator is itself
estimated, from ``n_control`` further draws of the (cheap) linear map alone::

    P = mu_L + (b - c) / n         b, c: draws inside by the nonlinear chain only / by the linear map only

and the interval adds Tango's interval of the paired difference and Wilson's interval of ``mu_L``, each at level
``1 - (1 - level) / 2`` (Bonferroni), so the sum holds at ``level``. The plain estimate of the same draws is carried
alongside. A point is ``demonstrated`` when the interval's lower end reaches ``p``, ``violated`` when its upper end is
below, else ``inconclusive``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.errormodel.chain import FastChain
from tolalloc.errormodel.parts import PartEffects, parts_error_model, with_parts
from tolalloc.errormodel.parts_sample import sample_effects
from tolalloc.exceptions import TolallocError
from tolalloc.linear.probability import p_within_radius
from tolalloc.montecarlo.intervals import paired_difference_ci
from tolalloc.montecarlo.run import pose_errors
from tolalloc.montecarlo.streaming import proportion_ci

__all__ = ["PartsVerification", "verify_parts", "draw_errors", "verified_parts", "BLOCK"]


@dataclass(frozen=True, eq=False)
class PartsVerification:
    """Result of :func:`verify_parts`: one row per point (:meth:`to_frame`), the overall ``verdict``.

    Attributes
    ----------
    q : array (M, n) [rad, mm];  payload_kg, ambient_c : arrays (M,)
    p_hat, low, high : arrays (M,)      paired estimate and its interval at ``level``
    p_plain, plain_low, plain_high : arrays (M,)   plain Monte Carlo of the same draws (Wilson)
    p_control : array (M,)              mean of the linear indicator (``n_control`` draws)
    p_certified : array (M,)            the design's certified bound ``P(|y| < r - |m|)`` (Gaussian linear)
    p_linear : array (M,)               Gaussian linear ``P(|m + y| < r)`` with the mean
    verdicts : tuple of str             demonstrated / violated / inconclusive
    n, n_control : int;  level, prob, radius_mm : float;  seed : int;  time_s : float
    """

    robot: str
    q: np.ndarray
    payload_kg: np.ndarray
    ambient_c: np.ndarray
    p_hat: np.ndarray
    low: np.ndarray
    high: np.ndarray
    p_plain: np.ndarray
    plain_low: np.ndarray
    plain_high: np.ndarray
    p_control: np.ndarray
    p_certified: np.ndarray
    p_linear: np.ndarray
    verdicts: tuple
    n: int
    n_control: int
    level: float
    prob: float
    radius_mm: float
    seed: int
    time_s: float = 0.0
    q_interface: np.ndarray | None = None

    @property
    def verdict(self) -> str:
        """``demonstrated`` when every point is, ``violated`` when one is, else ``inconclusive``."""
        if "violated" in self.verdicts:
            return "violated"
        return "demonstrated" if all(v == "demonstrated" for v in self.verdicts) else "inconclusive"

    def to_frame(self) -> pd.DataFrame:
        """One row per point: pose (interface units), payload, ambient, the estimates and the verdict."""
        cols = {f"q{j + 1}": self.q_interface[:, j] for j in range(self.q.shape[1])}
        return pd.DataFrame({"point": np.arange(1, len(self.q) + 1), **cols, "payload_kg": self.payload_kg,
                             "ambient_c": self.ambient_c, "p_mc": self.p_hat, "ci_low": self.low, "ci_high": self.high,
                             "p_plain": self.p_plain, "p_linear_control": self.p_control,
                             "p_linear_gaussian": self.p_linear, "p_certified_bound": self.p_certified,
                             "verdict": list(self.verdicts)})


def _values(fx: PartEffects, i: int, mm, n: int, rng, kw) -> tuple:
    """Parameter values (n, K) of ``fx.pm.model`` (machining draws, then the effects') and the direct displacement."""
    values, direct = sample_effects(fx, i, n, rng, **kw)
    values[:, :len(mm.params)] += mm.sample(n, rng)
    return values, direct


def draw_errors(fx: PartEffects, i: int, mm, chain: FastChain, n: int, rng, *, after: str, residual) -> tuple:
    """``n`` draws at point ``i``: the nonlinear tool-position errors (n, 3) [mm] and the linear ones on the same
    draws. ``mm``: the machining error model at the design's sigmas (its parameters lead ``fx.pm.model``'s)."""
    values, direct = _values(fx, i, mm, n, rng, dict(after=after, residual=residual))
    nl = pose_errors(fx.pm.model, fx.q[i], values, chain=chain)["dp_mm"] + direct
    return nl, values @ fx.J[i].T + direct


#: Draws evaluated at once (memory: about 60 parameter values each).
BLOCK = 50_000


def _point(fx, i, mm, chain, n, n_control, rng, r, level, kw) -> tuple:
    """Paired estimate, its interval, the plain estimate and the control's mean at point ``i``."""
    b = c = inside = kc = 0
    for start in range(0, n, BLOCK):
        nl, lin = draw_errors(fx, i, mm, chain, min(BLOCK, n - start), rng, **kw)
        a, b_ = np.linalg.norm(nl, axis=1) < r, np.linalg.norm(lin, axis=1) < r
        b, c, inside = b + int(np.sum(a & ~b_)), c + int(np.sum(~a & b_)), inside + int(a.sum())
    for start in range(0, n_control, BLOCK):  # the control's mean from the linear map alone
        values, direct = _values(fx, i, mm, min(BLOCK, n_control - start), rng, kw)
        kc += int(np.sum(np.linalg.norm(values @ fx.J[i].T + direct, axis=1) < r))
    half = 1 - (1 - level) / 2
    d = paired_difference_ci(b, c, n, half)
    mu = proportion_ci(kc, n_control, "wilson", half)
    plain = proportion_ci(inside, n, "wilson", level)
    return mu[0] + d[0], max(mu[1] + d[1], 0.0), min(mu[2] + d[2], 1.0), plain, mu[0]


def verify_parts(res, *, which: str = "certified", points: str = "worst", n_mc: int = 20000,
                 n_control: int | None = None, seed: int = 0, level: float = 0.95,
                 machining: bool = True) -> PartsVerification:
    """Verify a :class:`~tolalloc.allocate.parts_result.PartsAllocation` by the nonlinear Monte Carlo.

    Parameters
    ----------
    res : PartsAllocation
    which : {"certified", "standard"}
        The joint certified design (``res.design``), or the exact standard machining design with the same parts
        (``res.machining.standard``).
    points : {"worst", "active"}
        The region's worst point found (default), or it and every active point.
    n_mc, n_control : int
        Paired draws per point, and draws of the linear control (default ``10 n_mc``).
    seed : int
    level : float
        Confidence level of each point's interval.
    machining : bool
        Draw the machining errors (default); False: the bought parts' effects alone (to compare with a simulation of
        the parts only).
    """
    import time

    t0 = time.perf_counter()
    if which not in ("certified", "standard"):
        raise TolallocError(f"which: expected 'certified' or 'standard', got {which!r}")
    if points not in ("worst", "active"):
        raise TolallocError(f"points: expected 'worst' or 'active', got {points!r}")
    if isinstance(n_mc, bool) or not isinstance(n_mc, (int, np.integer)) or n_mc < 100:
        raise TolallocError(f"n_mc: expected a whole number of draws >= 100, got {n_mc!r}")
    design = res.design if which == "certified" else getattr(res.machining, "standard", None)
    if design is None or design.t is None:
        raise TolallocError("which='standard': the allocation has no standard machining design (run it with "
                            "exact=True)")
    n_control = 10 * int(n_mc) if n_control is None else int(n_control)
    pr = res.problem
    mm = pr.model_for(design.t if machining else np.zeros_like(design.t))
    robot = with_parts(mm.robot, res.choice)
    pts = res.worst_point if points == "worst" else res.worst_point.stack(res.points)
    fx = PartEffects(robot, pts.q, pts.payload_kg, pts.ambient_c, res.conditions, pm=parts_error_model(mm, robot))
    chain = FastChain(fx.pm.model)
    rng = np.random.default_rng(seed)
    kw = dict(after=res.after, residual=res.residual)
    rows = [_point(fx, i, mm, chain, int(n_mc), n_control, rng, pr.radius_mm, level, kw) for i in range(len(pts))]
    p_hat, low, high, plain, control = (np.array(x) for x in zip(*rows))
    plain = np.array(plain)
    m, C = fx.terms().moments(res.after, res.residual)
    J = fx.J[:, :, :len(mm.params)]
    C = C + np.einsum("pik,k,pjk->pij", J, mm.sigma ** 2, J)
    p_lin = np.array([float(p_within_radius(C[i], pr.radius_mm, m[i])) for i in range(len(pts))])
    room = np.maximum(pr.radius_mm - np.linalg.norm(m, axis=1), 0.0)
    p_cert = np.asarray(p_within_radius(C, room))
    verdicts = tuple("demonstrated" if lo >= pr.prob else "violated" if hi < pr.prob else "inconclusive"
                     for lo, hi in zip(low, high))
    return PartsVerification(robot.name, pts.q, pts.payload_kg, pts.ambient_c, p_hat, low, high, plain[:, 0],
                             plain[:, 1], plain[:, 2], control, p_cert, p_lin, verdicts, int(n_mc), n_control, level,
                             pr.prob, pr.radius_mm, seed, time.perf_counter() - t0, robot.q_to_interface(pts.q))


_OPTIONS = ("payload_kg", "ambient_c", "duty", "reference_c", "process_force_n", "process_torque_nm", "after",
            "residual", "rules")


def verified_parts(model, region, q, options, *, radius_mm: float, prob: float, costs=None, verify: bool = True,
                   n_mc: int = 20000, seed: int = 0):
    """The joint allocation with the bought parts (:func:`tolalloc.allocate.parts.allocate_parts`) and, with
    ``verify``, its nonlinear Monte Carlo at the worst point (:func:`verify_parts`), in the result's
    ``verification``.

    ``options``: True, or a dict of ``payload_kg`` (low, high) [kg] (default 0 to the robot's rated payload),
    ``ambient_c`` (low, high) [degC] (default the reference), ``duty``, ``reference_c`` (default 20),
    ``process_force_n`` and ``process_torque_nm`` (x, y, z) [N, N m] at the tool point in the tool frame (default none),
    ``after``, ``residual`` and ``rules``.
    """
    from dataclasses import replace

    from tolalloc.allocate.parts import allocate_parts
    from tolalloc.errormodel.parts import Conditions

    opts = {} if options is True else options
    if not isinstance(opts, dict):
        raise TolallocError(f"parts: expected True or a dict of options ({', '.join(_OPTIONS)}), got {options!r}")
    bad = [k for k in opts if k not in _OPTIONS]
    if bad:
        raise TolallocError(f"parts: unknown option {bad[0]!r}; expected {', '.join(_OPTIONS)}")
    robot = model.robot
    if not robot.components.slots:
        raise TolallocError(f"parts: robot {robot.name!r} names no catalogue slots; give its joints parts in the "
                            "robot file's [components] section (reducer = { family = ... }, see "
                            "tolalloc.robot.part_catalogue)")
    ref = float(opts.get("reference_c", 20.0))
    rated = robot.components.payload.rated_kg or 0.0
    cond = Conditions(tuple(opts.get("payload_kg", (0.0, rated))), tuple(opts.get("ambient_c", (ref, ref))), ref,
                      float(opts.get("duty", 0.5)), tuple(opts.get("process_force_n", (0.0, 0.0, 0.0))),
                      tuple(opts.get("process_torque_nm", (0.0, 0.0, 0.0))))
    kw = {k: opts[k] for k in ("after", "residual", "rules") if k in opts}
    res = allocate_parts(model, region, q, conditions=cond, radius_mm=radius_mm, prob=prob, costs=costs, seed=seed,
                         **kw)
    if verify and res.design.ok:
        res = replace(res, verification=verify_parts(res, n_mc=n_mc, seed=seed))
    return res
