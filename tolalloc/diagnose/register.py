"""Cross-session scoring: register the test file's tracker frame on a held-out part of it, score only the rest.

A test file from another session (``--test-frame refit``) is in another tracker frame with another probe
offset. Its registration (rotation, translation, 6) and target offset (3) are re-estimated with the trained
model frozen -- on a small **registration subset** of the test poses (default :data:`REGISTER_N` = 30, or a
fraction of the test file), and the model is scored on the **other** test poses only. Registering on the
scored poses would let the 9 registration parameters absorb part of the error being scored.

The registration subset is chosen to be **representative** of the test series, not its extremes: the test
poses are clustered into ``r`` groups by k-means in joint space (features ``cos q, sin q`` of revolute joints
and the standardised stroke of prismatic joints, see :func:`tolalloc.diagnose.gap.joint_features`; seeded
k-means++ start) and the pose nearest each cluster centre is taken (a k-medoids-like stratified sample).
The poses cover every region of the series (a well-conditioned registration) with the density of the
series. Why not its extremes: the 9 registration parameters are a least-squares fit to the trained model's
error at the registration poses. The error of a model trained on another session is largest where it
extrapolates most -- at the extremes of the test series -- so registering there tilts the frame towards
the worst poses and adds that error to every scored pose (on the real UR10 across sessions, farthest-point
sampling made the re-registered geometric model score worse than the nominal one).

A session that starts by measuring a designed registration set names those rows instead (``register_rows``,
:func:`split_from_rows`): they register the frame and every other test row is scored. Rows are numbered as
:attr:`~tolalloc.diagnose.measurements.Measurements.rows` numbers them -- the 1-based data rows of the test file
(header and ``#`` lines excluded, rows skipped for empty cells keep their numbers; a DataFrame's rows by position),
the numbers the JSON key ``registration_rows`` reports -- and 1-based positions for a set built without ``rows``.
"""

from __future__ import annotations

import warnings
from collections import Counter
from dataclasses import dataclass, replace

import numpy as np
from scipy.cluster.vq import kmeans2

from tolalloc.exceptions import ArgumentError, TolallocError, describe, whole_number
from tolalloc.diagnose.calibrate import Fit, fit_model, kabsch
from tolalloc.diagnose.gap import joint_features
from tolalloc.diagnose.measurements import file_rows

__all__ = ["REGISTER_N", "MIN_REGISTER", "MIN_SCORED", "CHOSEN_BY", "RegistrationSplit", "registration_split",
           "register_count", "register_row_numbers", "check_register_rows", "split_from_rows", "Registered",
           "register_and_score"]

#: Default number of test poses the registration is estimated on.
REGISTER_N = 30
#: Registration + probe offset are 9 unknowns, 3 coordinates per pose: at least 5 poses (15 rows, 6 spare).
MIN_REGISTER = 5
#: Fewer scored poses than this give no usable test figure.
MIN_SCORED = 5
#: How the registration poses were chosen: k-means in joint space (``register_n``), or named (``register_rows``).
CHOSEN_BY = ("kmeans", "given rows")


@dataclass(frozen=True, eq=False)
class RegistrationSplit:
    """Which test poses register the tracker frame and which are scored.

    Attributes
    ----------
    register_index : array of int, shape (r,)   test poses (0-based, sorted) the registration is fitted on
    score_index : array of int, shape (T - r,)  the other test poses, the only ones scored
    requested : float or None                   ``--register-n`` as given (count >= 1 or fraction < 1); None when
                                                the rows were given (``register_rows``)
    chosen_by : str                             one of :data:`CHOSEN_BY`: ``kmeans`` (nearest each k-means
                                                centre, :func:`registration_split`) or ``given rows``
                                                (:func:`split_from_rows`)
    """

    register_index: np.ndarray
    score_index: np.ndarray
    requested: float | None
    chosen_by: str = "kmeans"

    @property
    def n_poses(self) -> int:
        return len(self.register_index) + len(self.score_index)

    def to_dict(self, rows: np.ndarray | None = None, fitted: str = "tracker frame (6) and probe offset (3)") -> dict:
        """JSON block; ``rows``: 1-based file rows of the test poses (``Measurements.rows``); ``fitted``: what the
        registration poses fitted."""
        numbers = file_rows(rows, self.n_poses)
        pick = (lambda idx: numbers[idx].tolist())  # noqa: E731
        how = ("pose nearest each k-means centre in joint space (seeded), representative of the test series"
               if self.chosen_by == "kmeans" else "the rows given as registration rows (register_rows)")
        return {"register_n_requested": self.requested, "registration_poses": len(self.register_index),
                "scored_poses": len(self.score_index), "registration_rows": pick(self.register_index),
                "method": f"{how}; {fitted} re-fitted on these rows only, the other rows scored"}

    def chosen_text(self) -> str:
        """How the registration poses were chosen, for a sentence about them (``... test poses <text> fitted``)."""
        return "spread in joint space" if self.chosen_by == "kmeans" else "given as registration rows"


def register_count(n_test: int, register_n: float) -> int:
    """Number of registration poses: ``register_n`` itself when >= 1, else that fraction of ``n_test`` (rounded).

    Raises :class:`ArgumentError` (``register_n``) when it leaves fewer than :data:`MIN_REGISTER` registration or
    :data:`MIN_SCORED` scored poses.
    """
    if not np.isfinite(register_n) or register_n <= 0:
        raise ArgumentError("register_n", f"expected a pose count >= {MIN_REGISTER} or a fraction in (0, 1), "
                            f"got {register_n!r}.")
    n = int(register_n) if register_n >= 1 else int(round(register_n * n_test))
    if register_n >= 1 and n != register_n:
        raise ArgumentError("register_n", f"a count must be a whole number, got {register_n!r}; use a value below 1 "
                            "for a fraction.")
    if n > n_test:  # more registration poses than the test file has
        raise ArgumentError("register_n", f"{register_n:g} asks for {n:,} registration poses, but the {n_test} test "
                            f"poses leave at most {max(0, n_test - MIN_SCORED)} after the {MIN_SCORED} scored ones; expected "
                            f"a count from {MIN_REGISTER} to {max(MIN_REGISTER, n_test - MIN_SCORED)} or a fraction "
                            "below 1 -- choose another count or fraction, or a larger test file.")
    if n < MIN_REGISTER or n_test - n < MIN_SCORED:
        raise ArgumentError(
            "register_n", f"{register_n:g} gives {n} registration and {n_test - n} scored poses of the {n_test} test poses; "
            f"re-registering needs at least {MIN_REGISTER} registration and {MIN_SCORED} scored poses -- "
            "choose another count or fraction, or a larger test file.")
    return n


def registration_split(q: np.ndarray, revolute: np.ndarray, register_n: float = REGISTER_N,
                       seed: int = 0) -> RegistrationSplit:
    """Choose the registration poses: the pose nearest each of ``r`` k-means centres (see the module docstring).

    Parameters
    ----------
    q : array, shape (T, n) [rad, mm]   test joint values
    revolute : array of bool, shape (n,)
    register_n : float   count (>= 1) or fraction (< 1) of the test poses
    seed : int           seed of the k-means++ start (and of the fill-up when clusters share a nearest pose)
    """
    T = len(q)
    n = register_count(T, register_n)
    X = joint_features(q, revolute)
    X = X / np.maximum(X.std(0), 1e-9)
    rng = np.random.default_rng(seed)
    with warnings.catch_warnings():  # empty clusters (duplicate poses) are handled below
        warnings.simplefilter("ignore")
        centres, label = kmeans2(X, n, minit="++", seed=rng)
    chosen = []
    for k in range(n):
        members = np.flatnonzero(label == k)
        if len(members):
            chosen.append(int(members[np.argmin(np.linalg.norm(X[members] - centres[k], axis=1))]))
    chosen = np.unique(chosen)
    if len(chosen) < n:  # empty clusters (duplicate poses): fill up with seeded random poses
        rest = np.setdiff1d(np.arange(T), chosen)
        chosen = np.concatenate([chosen, rng.choice(rest, n - len(chosen), replace=False)])
    reg = np.sort(chosen.astype(int))
    return RegistrationSplit(reg, np.setdiff1d(np.arange(T), reg), float(register_n))


#: What a ``register_rows`` value is, for the messages that refuse one.
_ROWS_WANTED = "data rows of the test file, numbered from 1 as in its error messages and the JSON's registration_rows"
#: ... and as a Python value.
_ROWS_VALUE = f"{_ROWS_WANTED}: whole numbers (e.g. list(range(1, 61)) for its first 60 rows)"


def check_register_rows(register_rows, register_n=None, *, test_given: bool, test_frame: str):
    """The rules of ``register_rows`` that need no test file's content; returns its row numbers (a list of int in
    the order given) or None when it is None.

    ``register_rows`` and ``register_n`` are exclusive; the rows need a test file and ``test_frame='refit'``; they
    must be whole numbers from 1, each given once (:func:`register_row_numbers`). Raises :class:`ArgumentError`.
    """
    if register_rows is None:
        return None
    if register_n is not None:
        number = isinstance(register_n, (int, float, np.number)) and not isinstance(register_n, (bool, np.bool_))
        n = f"{register_n:g}" if number else describe(register_n)
        raise ArgumentError("register_rows", f"and `register_n` are exclusive: expected either the rows that register "
                            f"the frame or how many test poses to choose in joint space, got both (`register_n` {n}); "
                            "leave one of them out.")
    if test_frame != "refit":
        raise ArgumentError("register_rows", "needs `test_frame` refit: only a test file in another frame is "
                            "re-registered.")
    if not test_given:
        raise ArgumentError("register_rows", "needs `test`: only a test file in another frame is re-registered, and "
                            "none was given; pass the test file or leave this option out.")
    return register_row_numbers(register_rows)


def register_row_numbers(register_rows) -> list:
    """``register_rows`` as a list of int (the order given): whole numbers >= 1, each once; else
    :class:`ArgumentError`. Needs no test file."""
    if isinstance(register_rows, (str, bytes, dict)) or not np.iterable(register_rows):
        raise ArgumentError("register_rows", f"expected a list of {_ROWS_VALUE}, got {describe(register_rows)}.")
    items = list(register_rows)
    nums = [whole_number(v) for v in items]
    bad = [v for v, n in zip(items, nums) if n is None or n < 1]
    if bad:
        raise ArgumentError("register_rows", f"expected {_ROWS_VALUE}, got {describe(bad[0])} among the "
                            f"{len(items)} rows given; give the row numbers of the test file.")
    counts = Counter(nums)
    twice = sorted(n for n, c in counts.items() if c > 1)
    if twice:
        more = f" ({len(twice)} rows repeated: {_listed(twice)})" if len(twice) > 1 else ""
        raise ArgumentError("register_rows", f"expected each registration row once, got row {twice[0]} "
                            f"{counts[twice[0]]} times{more}; remove the repeats.")
    return nums


def _listed(values, limit: int = 8) -> str:
    """``values`` (ints) for a message: the first ``limit`` of them, then how many more."""
    values = list(values)
    text = ", ".join(str(v) for v in values[:limit])
    return text + (f" and {len(values) - limit} more" if len(values) > limit else "")


def split_from_rows(register_rows, n_test: int, rows: np.ndarray | None = None,
                    source: str = "the test file") -> RegistrationSplit:
    """The split that registers the frame on the given test rows and scores every other test pose.

    Parameters
    ----------
    register_rows : sequence of int   test rows of the registration, numbered as ``rows`` numbers the poses
    n_test : int                      test poses
    rows : array of int, shape (n_test,), optional  file row of every test pose (``Measurements.rows``); empty or
                                      None: 1-based positions
    source : str                      the test file, for the messages

    Raises :class:`ArgumentError` for a row that is not a whole number >= 1, a row given twice, a row that is not
    among ``rows``, or fewer than :data:`MIN_REGISTER` registration or :data:`MIN_SCORED` scored poses. A split's
    ``to_dict(rows)["registration_rows"]`` given back as ``register_rows`` gives the same split.
    """
    nums = register_row_numbers(register_rows)
    numbers = file_rows(rows, n_test)
    index = {int(r): i for i, r in enumerate(numbers)}  # file row -> test pose
    lost = [n for n in nums if n not in index]
    if lost:
        have = np.sort(numbers)
        top = int(have[-1]) if len(have) else 0
        gaps = np.setdiff1d(np.arange(int(have[0]), top + 1), have) if len(have) else np.zeros(0, int)
        within = f"{have[0] if len(have) else 0}..{top}" + (f" without {_listed(gaps.tolist())}" if len(gaps) else "")
        more = f" ({len(lost)} of the rows given are not: {_listed(lost)})" if len(lost) > 1 else ""
        raise ArgumentError("register_rows", f"row {lost[0]} is not among the test poses of {source}{more}: its "
                            f"{n_test} poses are rows {within} (rows with empty cells are skipped); expected "
                            f"{_ROWS_WANTED}; check the row numbers or the test file.")
    r = len(nums)
    if r < MIN_REGISTER or n_test - r < MIN_SCORED:
        advice = "give more rows" if r < MIN_REGISTER else "give fewer rows or use a larger test file"
        raise ArgumentError("register_rows", f"the {r} rows given leave {n_test - r} of the {n_test} test poses "
                            f"to score; re-registering needs at least {MIN_REGISTER} registration and {MIN_SCORED} "
                            f"scored poses -- {advice}.")
    reg = np.sort([index[n] for n in nums])
    return RegistrationSplit(reg, np.setdiff1d(np.arange(n_test), reg), None, "given rows")


@dataclass(frozen=True, eq=False)
class Registered:
    """A trained model re-registered to the test file's frame.

    Attributes
    ----------
    fit : Fit                      the trained fit with the test frame's ``R, p_mm, t_mm``
    pred_mm : array, shape (T, 3)  predictions of every test pose in the test frame [mm]
    residual_mm : array, shape (T - r, 3)  measured - predicted on the scored poses only [mm]
    posterior_cov : array, shape (9 + k + m, 9 + k + m) or None   with the calibration update
                                   (:mod:`.recalibrate`): covariance of the frame, probe offset and updated
                                   parameters (columns of :func:`tolalloc.diagnose.uncertainty.point_jacobian`) given
                                   the registration poses and the prior [parameter units squared]; None for a
                                   frame-only re-registration
    prior : CalibrationPrior or None   with the calibration update: the prior it used
                                   (:class:`tolalloc.diagnose.power_prior.CalibrationPrior`: its ``inflation`` k
                                   and floor)
    """

    fit: Fit
    pred_mm: np.ndarray
    residual_mm: np.ndarray
    posterior_cov: np.ndarray | None = None
    prior: object | None = None


def register_and_score(fit: Fit, q: np.ndarray, xyz: np.ndarray, extra: np.ndarray,
                       split: RegistrationSplit, *, t_prior=None, loss: str | None = None) -> Registered:
    """Re-estimate registration and target offset on ``split.register_index`` (model frozen), score the rest.

    Parameters
    ----------
    fit : Fit                       trained model (geometry, effects)
    q : array, shape (T, n) [rad, mm]
    xyz : array, shape (T, 3) [mm]  measured, test tracker frame
    extra : array, shape (T, 3) [mm]  the trained effects' displacement in the base frame (frozen)
    split : RegistrationSplit
    t_prior : (mean (3,), sd (3,)) [mm], optional   prior of the target offset (the caller's, as in training)
    loss : str, optional            robust loss (:func:`tolalloc.diagnose.calibrate.fit_model`)
    """
    r = split.register_index
    R, p = kabsch(fit.base_points(q[r]) + extra[r], xyz[r])
    f = fit_model(replace(fit, R=R, p_mm=p), q[r], xyz[r], geo_index=np.zeros(0, int), extra=extra[r],
                  t_prior=t_prior, loss=loss)
    f = replace(fit, R=f.R, p_mm=f.p_mm, t_mm=f.t_mm)
    pred = (f.base_points(q) + extra) @ f.R.T + f.p_mm
    s = split.score_index
    return Registered(f, pred, xyz[s] - pred[s])
