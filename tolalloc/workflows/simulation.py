"""Nonlinear Monte Carlo in one call: :func:`simulate_errors`."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError, check_memory
from tolalloc.outputs import output_group, write_json
from tolalloc.workflows import inputs
from tolalloc.workflows.base import JobResult, format_labels

__all__ = ["simulate_errors", "ErrorSimulation"]

#: samples kept for the scatter figure
KEEP_SAMPLES = 20_000
#: memory of one kept sample [bytes]: its errors at the first pose (11 float64 values, 88 bytes), held twice while the
#: blocks are joined, with room to spare
KEPT_BYTES = 256
#: histogram bins per axis at most (the streaming accumulator's limit)
MAX_HIST_BINS = 2000
#: local threads at most
MAX_JOBS = 1024


@inputs.job_entry
def simulate_errors(robot="tool_changer", n: int = 100_000, *, seed: int = 0, q_deg_mm=None, poses: str | None = None,
                    radius_mm=(0.15, 0.25), angle_radius_rad=None, angle_radius_deg=None, ci: str = "wilson",
                    sigma_set: str | None = None, link_mode: str = "consistent", deflection_mode: str = "screw",
                    clearance: bool = False, clearance_tilt_literal: bool = False, sigma: dict | None = None,
                    exclude=(), scheduler=None, jobs: int | None = None, chunk_size: int = 2**20,
                    progress: bool | None = None, hist_bins: int = 0, hist_range_mm: float | None = None,
                    keep_samples: int | None = None, estimator: str | None = None, tool: str | None = None,
                    trust_units: bool = False) -> "ErrorSimulation":
    """Sample ``n`` robots with random errors and evaluate their exact tool poses (streamed, bounded memory).

    Parameters
    ----------
    robot : Robot, str or path
    n : int
        Number of sampled robots (>= 1); the same robots are evaluated at every pose.
    seed : int
        Same seed, same numbers (whatever ``scheduler``, ``jobs`` and ``chunk_size``).
    q_deg_mm : array, shape (n_joints,) or (P, n_joints), optional
        Joint values [deg / mm]; default the pose set ``poses`` (or the nominal pose).
    radius_mm : float or sequence
        Radii for ``P(|dP| < r)`` [mm] (95 % intervals by ``ci``: ``wilson`` or ``exact``).
    angle_radius_rad, angle_radius_deg : float or sequence, optional
        Radii for ``P(|rotation error| < r)``, in rad or in deg (one of the two); default 0.002 rad.
    sigma_set, link_mode, deflection_mode, clearance, clearance_tilt_literal, sigma, exclude
        Error-model options (``sigma``: overrides in mm or deg).
    scheduler, jobs, chunk_size, progress
        Where and how the samples run; never change the numbers.
    hist_bins, hist_range_mm
        x-y, x-z, y-z histograms of the position error over all samples.
    keep_samples : int, optional
        Per-sample errors kept at the first pose for figures (default ``min(n, 20000)``).
    estimator : {None, "auto", "plain", "paired", "importance"}
        Also estimate each ``P(|dP| < r)`` with this estimator (``paired``: exact linear P plus the mean
        difference of nonlinear and linear indicators on the same draws), with its interval, discordant samples
        and variance reduction against plain Monte Carlo.

    Returns
    -------
    ErrorSimulation

    Examples
    --------
    >>> import tolalloc
    >>> sim = tolalloc.simulate_errors("tool_changer", 2000, seed=1)
    >>> sim.mc.n
    2000
    """
    n, seed, radii, arad, hist_bins, keep, scheduler = _checked(
        n, seed, ci, estimator, radius_mm, angle_radius_rad, angle_radius_deg, hist_bins, hist_range_mm, keep_samples,
        jobs, chunk_size, progress, q_deg_mm, poses, scheduler, dict(sigma_set=sigma_set, link_mode=link_mode,
                                                           deflection_mode=deflection_mode, clearance=clearance,
                                                           exclude=exclude, sigma=sigma,
                                                           clearance_tilt_literal=clearance_tilt_literal))
    rob = inputs.as_robot(robot, tool=tool, trust_units=trust_units)
    model = inputs.error_model(rob, sigma_set=sigma_set, link_mode=link_mode, deflection_mode=deflection_mode,
                               clearance=clearance, exclude=exclude, sigma=sigma,
                               clearance_tilt_literal=clearance_tilt_literal)
    _, q = inputs.resolve_poses(rob, q_deg_mm, poses)
    from tolalloc.errormodel.model import CLEARANCE_SIGMA, CLEARANCE_TILT_LITERAL_RAD
    from tolalloc.montecarlo.run import run_mc

    res = run_mc(model, q, n, seed, radii_mm=radii, angle_radii_rad=arad or [0.002], keep_samples=keep, ci=ci,
                 n_jobs=jobs, scheduler=scheduler, chunk_size=chunk_size, progress=progress, hist_bins=hist_bins,
                 hist_range_mm=hist_range_mm, estimator=estimator)
    tilt = ((CLEARANCE_TILT_LITERAL_RAD if clearance_tilt_literal else CLEARANCE_SIGMA["tilt_rad"])
            if clearance else None)
    return ErrorSimulation(res, rob, tilt)


def _checked(n, seed, ci, estimator, radius_mm, angle_radius_rad, angle_radius_deg, hist_bins, hist_range_mm,
             keep_samples, jobs, chunk_size, progress, q_deg_mm, poses, scheduler, model_options) -> tuple:
    """Every argument of :func:`simulate_errors` but the robot, checked by name; returns
    ``(n, seed, radii_mm, angle_radii_rad, hist_bins, keep_samples, scheduler)``."""
    n = inputs.check_count(n, "n", example="100000")
    seed = inputs.check_seed(seed)
    inputs.check_choice(ci, "ci", ("wilson", "exact"))
    if estimator is not None:
        inputs.check_choice(estimator, "estimator", ("auto", "plain", "paired", "importance"))
    radii = inputs.check_values(radius_mm, "radius_mm", inputs.check_positive, "mm", "0.25")
    inputs.check_not_both(angle_radius_deg, "angle_radius_deg", angle_radius_rad, "angle_radius_rad",
                          "give the radii of the rotation error", " (a list gives several radii)")
    arad = inputs.check_values([] if angle_radius_rad is None else angle_radius_rad, "angle_radius_rad",
                               inputs.check_positive, "rad", "0.002")
    arad += [np.deg2rad(a) for a in inputs.check_values([] if angle_radius_deg is None else angle_radius_deg,
                                                        "angle_radius_deg", inputs.check_positive, "deg", "0.1")]
    hist_bins = inputs.check_count(hist_bins, "hist_bins", minimum=0, example="100")
    if hist_bins == 1 or hist_bins > MAX_HIST_BINS:
        raise ArgumentError("hist_bins", f"expected 0 (no histogram) or a whole number of bins from 2 to "
                            f"{MAX_HIST_BINS} (e.g. 100), got {hist_bins}.")
    if hist_range_mm is not None:
        inputs.check_positive(hist_range_mm, "hist_range_mm", "mm", "1.0")
        if not hist_bins:
            raise ArgumentError("hist_range_mm", f"{hist_range_mm:g} sets the histogram window, but no histogram is made; "
                                "give hist_bins (e.g. 100) or leave out hist_range_mm.")
    if keep_samples is None:
        keep = min(n, KEEP_SAMPLES)
    else:
        keep = inputs.check_count(keep_samples, "keep_samples", minimum=0, example="20000")
        check_memory(min(keep, n), KEPT_BYTES, "keep_samples", "kept samples", "20000")
    if jobs is not None:
        inputs.check_count(jobs, "jobs", example="4", maximum=MAX_JOBS)
    inputs.check_count(chunk_size, "chunk_size", example="1048576")
    inputs.check_optional_flag(progress, "progress")
    inputs.check_model_options(**model_options)
    inputs.check_name(poses, "poses", "the name of a pose set of the robot")
    inputs.check_one_pose_source(q_deg_mm, poses)
    scheduler = inputs.check_scheduler(scheduler)
    return n, seed, radii, arad, hist_bins, keep, scheduler


def _angle_lines(res, max_poses: int | None = None) -> list[str]:
    """``P(|rotation error| < r)`` per pose with its 95 % interval, the radius in deg (as the user gives it)."""
    return [f"P(|dw| < {np.rad2deg(r):.4g} deg) = " + ", ".join(f"{a:.4f} [{b:.4f}, {c:.4f}]" for a, b, c in v[:max_poses])
            for r, v in res.p_within_angle.items()]


@dataclass(frozen=True, eq=False, repr=False)
class ErrorSimulation(JobResult):
    """Nonlinear Monte Carlo of the tool-pose error.

    Attributes
    ----------
    mc : McResult
        Mean, standard deviation, extremes of dx, dy, dz [mm], ``|dP|``, reach change, Euler-angle errors [rad],
        ``P(|dP| < r)`` with 95 % intervals (``mc.p_within[r]``, ``r`` one of the simulated radii [mm]; all of them:
        :meth:`probability_frame`); kept samples and histograms.
    robot : Robot
    clearance_tilt_rad : float or None
    """

    mc: object
    robot: object
    clearance_tilt_rad: float | None = None
    inputs: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return True

    def headline(self) -> list[str]:
        r = self.mc
        lines = [f"robot: {self.robot.name}   n = {r.n}, seed = {r.seed}, {r.q.shape[0]} pose(s)"]
        for rad, v in r.p_within.items():
            lines.append(f"P(|dP| < {rad:g} mm) = " + ", ".join(f"{a:.4f} [{b:.4f}, {c:.4f}]" for a, b, c in v[:4]))
        lines += _angle_lines(r, 4)
        return lines

    def to_frame(self) -> pd.DataFrame:
        """Table-3-style table: one row per pose and quantity with mean, std, max, min."""
        return self.mc.to_frame()

    def probability_frame(self) -> pd.DataFrame:
        """``P(|dP| < r)`` and ``P(|rotation error| < r)`` with their 95 % intervals, one row per pose and radius:
        ``pose`` (from 1), ``error``, ``radius_mm`` / ``radius_deg``, ``p``, ``ci_low``, ``ci_high``
        (:func:`tolalloc.montecarlo.radii.probability_frame`). Other radii: ``simulate_errors(radius_mm=[...])``."""
        from tolalloc.montecarlo.radii import probability_frame

        return probability_frame(self.mc)

    def summary(self) -> dict:
        """The content of ``mc_summary.json``; per-pose arrays are flattened when there is one pose."""
        res, robot = self.mc, self.robot
        one = res.q.shape[0] == 1

        def f(a):
            a = np.asarray(a)
            return a[0].tolist() if one else a.tolist()

        def pw(d, key):
            return {f"{r:g}": {"p": f(v[:, 0]), "ci_low": f(v[:, 1]), "ci_high": f(v[:, 2]), key: r} for r, v in d.items()}

        out = {
            "robot": robot.name, "n": res.n, "seed": res.seed, "labels": res.labels, "ci": res.ci,
            "q_deg_mm": f(robot.q_to_interface(res.q)),
            "mean_mm": f(res.mean_mm), "std_mm": f(res.std_mm), "cov_mm2": f(res.cov_mm2),
            "max_mm": f(res.dp_max_mm), "min_mm": f(res.dp_min_mm),
            "norm_mm": f(res.norm_mm), "reach_mm": f(res.reach_mm),
            "angle_mean_rad": f(res.angle_mean_rad), "angle_std_rad": f(res.angle_std_rad),
            "rotvec_std_rad": f(res.rotvec_std_rad),
            "p_within": pw(res.p_within, "radius_mm"),
            "p_within_angle": {k: {**v, "radius_deg": float(np.rad2deg(v["radius_rad"]))}
                               for k, v in pw(res.p_within_angle, "radius_rad").items()},
            "stats_order": "norm_mm and reach_mm are [mean, std, max, min]; angles are X-Y-Z fixed [alpha, beta, gamma]",
        }
        if res.hist is not None:
            out["hist_fraction_outside"] = (res.hist.outside / res.n).tolist()
        if res.p_estimates:
            out["p_estimates"] = {f"{r:g}": e.summary() for r, e in res.p_estimates.items()}
        out["labels"] = {**out["labels"], "clearance_tilt_rad": self.clearance_tilt_rad}
        return out

    def text(self) -> str:
        """What the command line prints."""
        res = self.mc
        out = [f"robot {self.robot.name}, n={res.n}, seed={res.seed}, {format_labels(res.labels)}",
               res.to_frame().to_string(index=False, na_rep="", float_format=lambda x: f"{x:.6g}")]
        for r, v in res.p_within.items():
            out.append(f"P(|dp| < {r:g} mm) = " + ", ".join(f"{a:.4f} [{b:.4f}, {c:.4f}]" for a, b, c in v))
        out += _angle_lines(res)
        for r, e in (res.p_estimates or {}).items():
            out.append(f"P(|dp| < {r:g} mm), {e.message()}: " + ", ".join(
                f"{a:.6f} [{b:.6f}, {c:.6f}]" for a, b, c in zip(e.p_hat, e.ci_low, e.ci_high)))
        return "\n".join(out)

    def plot_scatter(self):
        """Kept samples' position errors with density contours; returns the figure."""
        from tolalloc.report.plots.mc import scatter_density

        return scatter_density(self.mc, None)

    def save(self, out=None, *, json=None) -> list[str]:
        """Write ``mc_table.csv``, ``mc_summary.json``, ``mc_scatter.png`` (and histograms) into directory ``out``,
        and/or the JSON summary to file ``json``; all published together. Returns the file names in ``out``."""
        self.check_out(out, "out")
        self.check_out(json, "json", directory=False)
        names = []
        with output_group() as group:
            if out is not None:
                names = self.write_files(group.directory(out))
            if json is not None:
                write_json(self.summary(), group.file(json))
        return names

    def write_files(self, folder) -> list[str]:
        """Write the output files into an existing ``folder`` (not atomic; :meth:`save` stages through this)."""
        import matplotlib.pyplot as plt

        from tolalloc.report.plots.mc import hist_density, scatter_density

        res = self.mc
        res.to_frame().to_csv(folder / "mc_table.csv", index=False)
        write_json(self.summary(), folder / "mc_summary.json")
        plt.close(scatter_density(res, folder / "mc_scatter.png"))
        names = ["mc_table.csv", "mc_summary.json", "mc_scatter.png"]
        if res.hist is not None:
            plt.close(hist_density(res, folder / "mc_density.png"))
            np.savez_compressed(folder / "mc_hist.npz", counts=res.hist.counts, edges_mm=res.hist.edges_mm,
                                outside=res.hist.outside, n=res.hist.n, planes=np.array(res.hist.planes))
            names += ["mc_density.png", "mc_hist.npz"]
        return names
