"""The verdict rule of the Monte Carlo verification, applied to every stated requirement.

Each requirement -- the position one and, when stated, the orientation one -- is judged at each pose from the
interval of its own ``P_hat`` against its own ``p``. The intervals of all poses and requirements judged together
are simultaneous: with ``m`` = poses x requirements (plus the possible second looks, :func:`verification_family`),
each is at level ``1 - (1 - level) / m`` (Bonferroni,
:func:`tolalloc.montecarlo.intervals.simultaneous_level`), so that all of them cover their true probabilities with
probability at least ``level`` (0.95) -- a design exactly at ``p`` everywhere is called *failed* (or a design
below ``p`` somewhere *demonstrated*) with probability at most ``1 - level``, however many poses are verified.
Where a pose may be judged twice -- the certified criterion re-runs a straddling position interval with more
samples -- each possible second look is one more interval of the family (:func:`verification_family`): ``m`` =
poses x requirements + poses.

* **demonstrated** when the lower bound is ``>= p``;
* **consistent** when the upper bound is ``>= p`` but the lower bound is below;
* **failed** when the upper bound is below ``p``.

A pose's verdict is its weakest requirement's (:func:`weakest`): *demonstrated* only when every requirement is,
*failed* when any requirement is. :class:`RequirementCheck` holds one requirement's intervals and says how far its
deciding bound lies from ``p``; :func:`limiting` names the requirement that sets the overall verdict;
:func:`failure_reasons` says why a pose did not pass its design's criterion.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.linear.covariance import variance_share

__all__ = ["RequirementCheck", "pose_verdicts", "overall_verdict", "weakest", "limiting", "shortfall_text",
           "orientation_check", "failure_reasons", "interval_words", "family_text", "verification_family"]

#: verdicts from the weakest to the strongest
ORDER = ("failed", "consistent", "demonstrated")


def interval_words(family_level: float, m: int) -> str:
    """What an interval is, for printed lines: ``95%`` for a single interval, ``simultaneous 95%`` for one of ``m > 1``
    intervals judged together (each at the Bonferroni level, :func:`family_text`)."""
    lvl = f"{100 * family_level:.4g}%"
    return lvl if m <= 1 else f"simultaneous {lvl}"


def verification_family(n_poses: int, n_requirements: int, criterion: str, n_mc: int, n_max: int,
                        importance_look: bool = False) -> tuple:
    """``(n_intervals, second_looks)``: the Bonferroni family of a verification and its possible second looks.

    Every pose has one interval per requirement. A pose whose position interval straddles ``p`` is re-run with
    ``n_max`` samples and judged on that second look when ``n_max > n_mc`` and either the criterion is certified or
    ``importance_look`` (``estimator="auto"`` on a Gaussian model: the second look is importance sampling, which
    resolves a thin tail that the paired estimator's few discordant draws cannot); every position interval then
    has a possible second look (one per pose, counted whether or not it runs: which poses get one depends on the
    data). ``n_max = n_mc`` means no second look (:func:`~tolalloc.verify.designs.verify_design` refuses
    ``n_max < n_mc``). All the family's intervals, first and second looks alike, are at
    ``simultaneous_level(level, n_intervals)`` (Bonferroni: the family's alpha spent equally on every look).

    >>> verification_family(18, 1, "certified", 10**6, 4 * 10**6)
    (36, 18)
    >>> verification_family(18, 2, "certified", 10**6, 10**6), verification_family(18, 2, "exact", 10**6, 4 * 10**6)
    ((36, 0), (36, 0))
    >>> verification_family(18, 2, "exact", 10**6, 4 * 10**6, importance_look=True)
    (54, 18)
    """
    from tolalloc.montecarlo.intervals import family_size

    again = criterion == "certified" or bool(importance_look)
    looks = int(n_poses) if again and n_max > n_mc else 0
    return family_size(int(n_poses) * int(n_requirements), looks), looks


def family_text(family_level: float, m: int, n_poses: int, n_requirements: int = 1, second_looks: int = 0) -> str:
    """The intervals' family in words, e.g. ``95% simultaneous over the 18 poses (Bonferroni: 18 intervals at 99.72%
    each)`` (with two requirements ``over the 18 poses and 2 requirements (... 36 intervals ...)``; with a possible
    second look at each position interval ``(Bonferroni: 36 intervals at 99.86% each, a possible second look at
    each position interval counted)``, ``m`` counting them)."""
    from tolalloc.montecarlo.intervals import simultaneous_level

    if m <= 1:
        return f"{100 * family_level:.4g}% (a single interval)"
    what = ("1 pose" if n_poses == 1 else f"the {n_poses} poses") + (
        "" if n_requirements == 1 else f" and {n_requirements} requirements")
    looks = ", a possible second look at each position interval counted" if second_looks else ""
    return (f"{100 * family_level:.4g}% simultaneous over {what} (Bonferroni: {m} intervals at "
            f"{100 * simultaneous_level(family_level, m):.4g}% each{looks})")


def pose_verdicts(ci_low, ci_high, prob) -> np.ndarray:
    """Per-pose verdict of one requirement from the interval of its ``P_hat`` (simultaneous over the poses when the
    intervals are: the rule is the same).

    Parameters
    ----------
    ci_low, ci_high : array, shape (P,)
    prob : float

    Returns
    -------
    array of str, shape (P,)
        ``"demonstrated"`` (lower bound >= p), ``"consistent"`` (upper bound >= p) or ``"failed"``.
    """
    lo, hi = np.asarray(ci_low, float), np.asarray(ci_high, float)
    return np.where(lo >= prob, "demonstrated", np.where(hi >= prob, "consistent", "failed"))


def overall_verdict(verdicts) -> str:
    """The weakest per-pose verdict: ``failed`` < ``consistent`` < ``demonstrated``."""
    v = set(np.asarray(verdicts).tolist())
    return "failed" if "failed" in v else ("consistent" if "consistent" in v else "demonstrated")


def weakest(*verdicts) -> np.ndarray:
    """Pose by pose, the weakest of several requirements' verdicts (arrays of the same shape (P,))."""
    stack = np.stack([np.asarray(v) for v in verdicts])
    return np.where((stack == "failed").any(axis=0), "failed",
                    np.where((stack == "consistent").any(axis=0), "consistent", "demonstrated"))


def fmt_prob(x: float, prob: float) -> str:
    """A probability with enough decimals to tell it from ``prob`` (4, more for a rare-event ``prob``)."""
    return f"{x:.{max(4, int(np.ceil(-np.log10(max(1.0 - prob, 1e-15)))) + 2)}f}"


def fmt_margin(m: float) -> str:
    """A distance between probabilities to two significant digits, positional (``0.0010``, ``0.00000041``)."""
    return np.format_float_positional(float(m), precision=2, unique=False, fractional=False, trim="k")


@dataclass(frozen=True, eq=False)
class RequirementCheck:
    """One requirement's Monte Carlo intervals at every pose.

    Attributes
    ----------
    name : {"position", "orientation"}
    prob : float
        The required probability ``p`` of this requirement.
    p_linear, p_mc, ci_low, ci_high : arrays, shape (P,)
        Linear (Gaussian) prediction (NaN where unknown), Monte Carlo estimate and its interval.
    family_level : float
        Level at which all ``n_intervals`` intervals of the verification hold together (0.95).
    n_intervals : int
        Intervals in the Bonferroni family (poses x requirements, plus the possible second looks:
        :func:`verification_family`); each is at :attr:`level`. 1: a single 95 % interval.
    """

    name: str
    prob: float
    p_linear: np.ndarray
    p_mc: np.ndarray
    ci_low: np.ndarray
    ci_high: np.ndarray
    family_level: float = 0.95
    n_intervals: int = 1

    @property
    def level(self) -> float:
        """Level of each interval: ``1 - (1 - family_level) / n_intervals``."""
        from tolalloc.montecarlo.intervals import simultaneous_level

        return simultaneous_level(self.family_level, self.n_intervals)

    @property
    def _words(self) -> str:
        return interval_words(self.family_level, self.n_intervals)

    @property
    def verdicts(self) -> np.ndarray:
        """Per-pose verdict of this requirement alone, shape (P,)."""
        return pose_verdicts(self.ci_low, self.ci_high, self.prob)

    @property
    def verdict(self) -> str:
        return overall_verdict(self.verdicts)

    def worst(self) -> tuple[int, str, float]:
        """``(pose index, bound, margin)`` of the bound that decides the verdict, at the pose where it is weakest.

        For a *failed* requirement the upper bound (the failed pose whose upper bound lies furthest below ``p``),
        else the lower bound (the pose with the lowest lower bound); ``margin`` = bound - ``p`` (negative: short).
        """
        if self.verdict == "failed":
            m = np.where(self.verdicts == "failed", self.ci_high - self.prob, np.inf)
            i = int(np.argmin(m))
            return i, "upper", float(m[i])
        m = self.ci_low - self.prob
        i = int(np.argmin(m))
        return i, "lower", float(m[i])

    def margin_text(self) -> str:
        """How far the deciding bound lies from ``p`` at the weakest pose, e.g.
        ``orientation lower simultaneous 95% bound 0.9511 at pose 3, 0.0011 above p = 0.95``."""
        i, bound, m = self.worst()
        value = fmt_prob((self.ci_high if bound == "upper" else self.ci_low)[i], self.prob)
        return (f"{self.name} {bound} {self._words} bound {value} at pose {i + 1}, {fmt_margin(abs(m))} "
                f"{'above' if m >= 0 else 'below'} p = {self.prob:g}")

    def clause(self) -> str:
        """One clause: what this requirement's intervals show and by how much."""
        i, bound, m = self.worst()
        value = fmt_prob((self.ci_high if bound == "upper" else self.ci_low)[i], self.prob)
        if m >= 0:
            return (f"{self.name}: lower {self._words} bound >= p = {self.prob:g} at every pose (least: {value} at "
                    f"pose {i + 1})")
        n = int(np.sum(self.verdicts == "failed")) if bound == "upper" else int(np.sum(self.ci_low < self.prob))
        return (f"{self.name}: {bound} {self._words} bound below p = {self.prob:g} at {n} pose(s), by up to "
                f"{fmt_margin(-m)} at pose {i + 1} ({value})")

    def to_dict(self) -> dict:
        """JSON-ready: verdict, the poses (1-based) not demonstrated / failed, the deciding bound and its margin."""
        i, bound, m = self.worst()
        v = self.verdicts
        return {"requirement": self.name, "prob": float(self.prob), "verdict": self.verdict,
                "poses_not_demonstrated": [int(k) + 1 for k in np.flatnonzero(v != "demonstrated")],
                "poses_failed": [int(k) + 1 for k in np.flatnonzero(v == "failed")],
                "worst_pose": i + 1, "bound": bound, "ci_low": float(self.ci_low[i]), "ci_high": float(self.ci_high[i]),
                "family_level": float(self.family_level), "level_per_interval": self.level, "margin": m,
                "message": self.clause()}


def orientation_check(angle: dict, n_poses: int, family_level: float = 0.95, n_intervals: int = 1) -> RequirementCheck:
    """The orientation requirement's :class:`RequirementCheck` from a verification's ``angle`` dict (``prob``,
    ``p_linear`` (None: unknown), ``p_mc``, ``ci_low``, ``ci_high``), its intervals one of ``n_intervals`` that
    hold together at ``family_level``."""
    lin = np.full(n_poses, np.nan) if angle.get("p_linear") is None else np.asarray(angle["p_linear"], float)
    return RequirementCheck("orientation", float(angle["prob"]), lin, np.asarray(angle["p_mc"], float),
                            np.asarray(angle["ci_low"], float), np.asarray(angle["ci_high"], float), family_level,
                            n_intervals)


def limiting(checks) -> RequirementCheck:
    """The requirement that sets the overall verdict: the weakest verdict, then the smallest deciding margin."""
    return min(checks, key=lambda c: (ORDER.index(c.verdict), c.worst()[2]))


def shortfall_text(checks) -> str:
    """The clauses of the requirements that are not demonstrated ("" when all are)."""
    return "; ".join(c.clause() for c in checks if c.verdict != "demonstrated")


def failure_reasons(problem, model, p_lin: np.ndarray, est: np.ndarray, n: np.ndarray, ok: np.ndarray,
                    a_ok: np.ndarray, angle: RequirementCheck | None, a_n, nongauss_share: float) -> tuple:
    """Per pose, why it did not pass ("" when it passed): under-specified, non-Gaussian, inconclusive or nonlinear
    (position), under-specified, inconclusive or below (orientation).

    ``p_lin`` (P,): linear position probabilities; ``est`` (P, 3): position estimate and interval; ``n`` (P,)
    position samples; ``ok`` / ``a_ok`` (P,): position / orientation passed; ``angle``: the orientation
    requirement's intervals (None without one) from ``a_n`` (P,) samples.
    """
    p = problem.prob
    nongauss = np.array([prm.distribution != "normal" for prm in model.params])
    reasons = []
    for i in range(len(est)):
        if ok[i] and a_ok[i]:
            reasons.append("")
            continue
        share = float(variance_share(problem.J[i, :3, :], model.sigma**2)[nongauss].sum())
        bits = []
        if not ok[i]:
            if p_lin[i] < p - 1e-6:
                bits.append(f"under-specified: even the linear prediction P = {p_lin[i]:.4f} < {p:g}")
            elif share >= nongauss_share:
                kinds = sorted({prm.distribution for prm, g in zip(model.params, nongauss) if g})
                bits.append(f"non-Gaussian parameters ({', '.join(kinds)}) carry {share:.0%} of the variance: "
                            f"P_hat = {est[i, 0]:.4f} vs linear-Gaussian {p_lin[i]:.4f}")
            elif est[i, 1] < p <= est[i, 2]:  # the interval contains p: too few samples to tell, whatever P_hat
                bits.append(f"inconclusive: interval [{est[i, 1]:.4f}, {est[i, 2]:.4f}] contains {p:g} "
                            f"at n = {n[i]}; raise n_mc (or use estimator='importance')")
            else:
                bits.append(f"nonlinearity: exact kinematics give P_hat = {est[i, 0]:.4f} "
                            f"[{est[i, 1]:.4f}, {est[i, 2]:.4f}] vs linear {p_lin[i]:.4f}")
        if not a_ok[i]:
            bits.append(angle_reason(angle, i, int(a_n[i])))
        reasons.append("; ".join(bits))
    return tuple(reasons)


def angle_reason(angle: RequirementCheck, i: int, n: int) -> str:
    """Why the orientation requirement did not pass at pose ``i`` (0-based), estimated from ``n`` samples."""
    p, p_hat, lo, hi, lin = angle.prob, angle.p_mc[i], angle.ci_low[i], angle.ci_high[i], angle.p_linear[i]
    interval = f"P_hat = {p_hat:.4f} [{lo:.4f}, {hi:.4f}]"
    if lin < p - 1e-6:
        return f"orientation under-specified: even the linear prediction P = {lin:.4f} < {p:g} ({interval})"
    if lo < p <= hi:
        return (f"orientation inconclusive: {interval} contains {p:g} at n = {n}, lower bound "
                f"{fmt_margin(p - lo)} below; raise n_mc")
    return f"orientation {interval} below {p:g}: upper bound {fmt_margin(p - hi)} below"
