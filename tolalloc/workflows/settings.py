"""Settings objects of the jobs: small frozen dataclasses, built once, checked once, reused across calls.

======================================  ==================================================  ======================
object                                  what it holds                                       taken by
======================================  ==================================================  ======================
:class:`ErrorModelOptions`              sigma set, link / deflection model, clearance ...   every job
:class:`Costs`                          costs file, ``z`` of sigma = t / z, uniform errors  allocation, plan
:class:`MonteCarlo`                     samples, seed, interval, estimator, histograms ...  ``simulate_errors``
:class:`Measurement`                    what the tracker measures and its noise             ``plan_calibration``
======================================  ==================================================  ======================

The allocation's own (:class:`~tolalloc.workflows.allocation_settings.Region`, ``Solver``, ``Verification``) and
the diagnosis's (``Refit``, ``FitOptions``) follow the same rules. A bad field is refused at construction with an
:class:`~tolalloc.exceptions.ArgumentError` naming it as ``ClassName.field`` (``Verification.n_mc: expected at
least 100 samples ...``); the command line shows the flag instead. Defaults come from
:mod:`tolalloc.workflows.defaults`, which the command line reads too.
"""

from __future__ import annotations

import contextlib
import os
from dataclasses import dataclass, fields, replace

from tolalloc.exceptions import ArgumentError, check_memory
from tolalloc.workflows import defaults as D
from tolalloc.workflows.checks import (check_choice, check_costs_file, check_count, check_flag, check_model_options,
                                       check_optional_flag, check_positive, check_scheduler, check_seed, check_z,
                                       shown)

__all__ = ["Settings", "ErrorModelOptions", "Costs", "MonteCarlo", "Measurement", "named_fields", "as_settings",
           "KEEP_SAMPLES", "KEPT_BYTES", "MAX_HIST_BINS", "MAX_JOBS"]

#: samples kept for the scatter figure of a simulation
KEEP_SAMPLES = 20_000
#: memory of one kept sample [bytes]: its errors at the first pose (11 float64 values, 88 bytes), held twice while the
#: blocks are joined, with room to spare
KEPT_BYTES = 256
#: histogram bins per axis at most (the streaming accumulator's limit)
MAX_HIST_BINS = 2000
#: local threads at most
MAX_JOBS = 1024


@contextlib.contextmanager
def named_fields(owner: str, rename: dict | None = None):
    """Within the block, an :class:`ArgumentError` of a bare argument ``x`` names ``owner.x`` (``owner``: a class
    name); without an owner, one of ``x`` or of a field ``Class.x`` names ``rename[x]`` where ``rename`` maps ``x``
    (the job keyword the value came from). Other errors pass unchanged."""
    try:
        yield
    except ArgumentError as exc:
        arg = exc.argument
        field = arg.rsplit(".", 1)[-1]
        if owner and "." not in arg:
            name = f"{owner}.{arg}"
        elif rename is not None and field in rename:
            name = rename[field]
        else:
            raise
        raise ArgumentError(name, exc.detail) from None


class Settings:
    """Base of the settings objects: a frozen dataclass whose :meth:`check` runs at construction (and on
    :meth:`replace`), its errors naming ``ClassName.field``."""

    #: fields that never change a number (where the work runs): left out of :meth:`to_dict`
    _unrecorded: tuple = ()

    def __post_init__(self):
        with named_fields(type(self).__name__):
            self.check()

    def check(self) -> None:
        """Refuse a bad field; normalise the others (``1e6`` samples to ``1000000``)."""

    def _set(self, **values) -> None:
        for name, value in values.items():
            object.__setattr__(self, name, value)

    def replace(self, **changes):
        """A copy with ``changes`` (checked again)."""
        return replace(self, **changes)

    def to_dict(self) -> dict:
        """The fields that decide the numbers, for JSON records (paths as strings)."""
        out = {}
        for f in fields(self):
            if f.name in self._unrecorded:
                continue
            v = getattr(self, f.name)
            out[f.name] = str(v) if isinstance(v, os.PathLike) else (list(v) if isinstance(v, tuple) else v)
        return out


def as_settings(value, cls, argument: str, short=None):
    """``value`` as a ``cls`` object: None -> ``cls()``, a ``cls`` as it is, else ``short(value)`` (a callable
    building the object from the job's short keyword ``argument``, whose errors then name ``argument``)."""
    if value is None:
        return cls()
    if isinstance(value, cls):
        return value
    if short is None:
        raise ArgumentError(argument, f"expected a tolalloc.{cls.__name__}(...), got {shown(value)}.")
    with named_fields("", {f.name: argument for f in fields(cls)}):
        return short(value)


@dataclass(frozen=True)
class ErrorModelOptions(Settings):
    """Which errors the model has and how large (:func:`tolalloc.errormodel.build_error_model`).

    Parameters
    ----------
    sigma_set : str, optional
        A sigma set of the robot file (``tool_changer``: ``table2``, the default, or ``table1``) or ``"generic"``;
        default: the robot file's first. In an allocation it sets only the fixed parameters (the others are
        allocated).
    link_mode : {"consistent", "axes_only"}
        Link errors move axes and tool (default) or the axes only (the seed paper's Eq. 24).
    deflection_mode : {"screw", "tilt"}
        Axis deflections as error screws (default) or as a tilt of the axis.
    clearance : bool
        Add joint clearance (axial slip, radial ring, tilt) to every revolute joint.
    clearance_tilt_literal : bool
        The seed paper's literal clearance tilt sigma (not in an allocation).
    sigma : dict, optional
        Sigma overrides ``{parameter or kind: sigma}`` in mm (lengths) or deg (angles) (not in an allocation).
    exclude : str or sequence of str
        Parameters or kinds left out.
    """

    sigma_set: str | None = None
    link_mode: str = D.LINK_MODE
    deflection_mode: str = D.DEFLECTION_MODE
    clearance: bool = False
    clearance_tilt_literal: bool = False
    sigma: dict | None = None
    exclude: tuple = ()

    def check(self) -> None:
        exclude = check_model_options(**self.keywords())
        self._set(exclude=exclude, sigma=None if self.sigma is None else dict(self.sigma))

    def keywords(self) -> dict:
        """Keyword arguments of :func:`tolalloc.workflows.inputs.error_model`."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def changed(self) -> list[str]:
        """The fields set away from their defaults."""
        return [f.name for f in fields(self) if getattr(self, f.name) not in (f.default, None, ())]


@dataclass(frozen=True)
class Costs(Settings):
    """What tolerances cost: a costs file (TOML: cost laws, process limits, fixed / excluded parameters, the
    ``[calibration]`` split) and how a tolerance t maps to a standard deviation.

    Parameters
    ----------
    file : str or path, optional
        The costs file (default: the built-in assumed laws and limits).
    z : float, optional
        sigma = t / z (default 3, or the costs file's ``z``).
    uniform : bool
        Errors uniform over ±t (sigma = t / sqrt(3)); not with ``z``.
    """

    file: str | os.PathLike | None = None
    z: float | None = None
    uniform: bool = False

    def check(self) -> None:
        path = check_costs_file(self.file, "file")
        check_flag(self.uniform, "uniform")
        if self.uniform and self.z is not None:
            raise ArgumentError("uniform", "and `z` both set sigma = t / z; give one of them.")
        self._set(file=path, z=None if self.z is None else check_z(self.z))

    @property
    def distribution(self) -> str | None:
        return "uniform" if self.uniform else None


@dataclass(frozen=True)
class MonteCarlo(Settings):
    """How :func:`~tolalloc.workflows.simulate_errors` samples: how many robots, which seed, which intervals and
    estimators, what it keeps, and where the samples run (the last three never change a number).

    Parameters
    ----------
    n_mc : int
        Sampled robots (>= 1; default 100 000); the same robots at every pose.
    seed : int
        Same seed, same numbers (whatever ``scheduler``, ``jobs`` and ``chunk_size``).
    ci : {"wilson", "exact"}
        95 % intervals of ``P(|dP| < r)``: Wilson or Clopper-Pearson.
    estimator : {None, "auto", "plain", "paired", "importance"}
        Also estimate each ``P(|dP| < r)`` with this estimator, with its interval and variance reduction.
    keep_samples : int, optional
        Per-sample errors kept at the first pose for figures (default ``min(n_mc, 20000)``).
    hist_bins : int
        x-y, x-z, y-z histograms of the position error over all samples (0: none; 2 .. 2000 bins per axis).
    hist_range_mm : float, optional
        Half-width of the histogram window [mm] (default: 6 linear standard deviations per axis).
    scheduler, jobs, chunk_size
        Where the samples run (local threads by default, a Dask scheduler), local threads, samples per Dask task.
    """

    n_mc: int = D.SIMULATION_N_MC
    seed: int = D.SEED
    ci: str = D.CI
    estimator: str | None = None
    keep_samples: int | None = None
    hist_bins: int = 0
    hist_range_mm: float | None = None
    scheduler: object = None
    jobs: int | None = None
    chunk_size: int = D.CHUNK_SIZE

    _unrecorded = ("scheduler", "jobs", "chunk_size")

    def check(self) -> None:
        n = check_count(self.n_mc, "n_mc", example="100000")
        check_choice(self.ci, "ci", ("wilson", "exact"))
        if self.estimator is not None:
            check_choice(self.estimator, "estimator", ("auto", "plain", "paired", "importance"))
        bins = check_count(self.hist_bins, "hist_bins", minimum=0, example="100")
        if bins == 1 or bins > MAX_HIST_BINS:
            raise ArgumentError("hist_bins", f"expected 0 (no histogram) or a whole number of bins from 2 to "
                                f"{MAX_HIST_BINS} (e.g. 100), got {bins}.")
        if self.hist_range_mm is not None:
            check_positive(self.hist_range_mm, "hist_range_mm", "mm", "1.0")
            if not bins:
                raise ArgumentError("hist_range_mm", f"{self.hist_range_mm:g} sets the histogram window, but no "
                                    "histogram is made; give hist_bins (e.g. 100) or leave out hist_range_mm.")
        keep = self.keep_samples
        if keep is not None:
            keep = check_count(keep, "keep_samples", minimum=0, example="20000")
            check_memory(min(keep, n), KEPT_BYTES, "keep_samples", "kept samples", "20000")
        if self.jobs is not None:
            check_count(self.jobs, "jobs", example="4", maximum=MAX_JOBS)
        check_count(self.chunk_size, "chunk_size", example="1048576")
        self._set(n_mc=n, seed=check_seed(self.seed), hist_bins=bins, keep_samples=keep,
                  scheduler=check_scheduler(self.scheduler))

    @property
    def kept(self) -> int:
        """Samples kept for figures: ``keep_samples``, default ``min(n_mc, 20000)``."""
        return min(self.n_mc, KEEP_SAMPLES) if self.keep_samples is None else self.keep_samples


@dataclass(frozen=True)
class Measurement(Settings):
    """What a laser tracker measures in a calibration plan, and how well.

    Parameters
    ----------
    kind : {"position", "pose"}
        Tool positions, or positions and orientations.
    noise_mm : float
        Tracker noise sigma per coordinate [mm] (0.1 um .. 1 m; default 0.02).
    noise_deg : float
        Orientation noise sigma per axis [deg] (pose measurements only; default 0.001).
    registration : bool
        Estimate the tracker frame and the tool offset too (False: both are known).
    """

    kind: str = "position"
    noise_mm: float = D.NOISE_MM
    noise_deg: float = D.NOISE_DEG
    registration: bool = True

    #: tracker noise sigma: 0.1 um .. 1 m and 1e-6 .. 10 deg (see :mod:`tolalloc.workflows.calplan`)
    NOISE_MM_RANGE = (1e-4, 1e3)
    NOISE_DEG_RANGE = (1e-6, 10.0)

    def check(self) -> None:
        check_choice(self.kind, "kind", ("position", "pose"))
        check_positive(self.noise_mm, "noise_mm", "mm", "0.02", self.NOISE_MM_RANGE)
        check_positive(self.noise_deg, "noise_deg", "deg", "0.001", self.NOISE_DEG_RANGE)
        check_flag(self.registration, "registration")
        if self.kind == "position" and self.noise_deg != D.NOISE_DEG:
            raise ArgumentError("noise_deg", f"{shown(self.noise_deg)} is the orientation noise of pose "
                                "measurements, but `kind` is position; add kind='pose' (or leave out `noise_deg`).")


def check_progress(value) -> bool | None:
    """``progress``: None (automatic), True or False."""
    return check_optional_flag(value, "progress")
