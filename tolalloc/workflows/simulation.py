"""Nonlinear Monte Carlo in one call: :func:`simulate_errors`."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError
from tolalloc.outputs import write_json
from tolalloc.workflows import defaults as D
from tolalloc.workflows import inputs
from tolalloc.workflows.base import JobResult, format_labels
from tolalloc.workflows.settings import ErrorModelOptions, MonteCarlo, as_settings, named_fields

__all__ = ["simulate_errors", "ErrorSimulation"]

#: the rotation-error radius when none is given [rad] (0.1146 deg)
ANGLE_RADIUS_RAD = 0.002
#: below this, every ``P(|dP| < r)`` of a simulation is "about zero": the printout says why
P_ABOUT_ZERO = 1e-3


@inputs.job_entry
def simulate_errors(robot="tool_changer", n_mc: int | None = None, *, seed: int | None = None, q_deg_mm=None,
                    poses: str | None = None, radius_mm=D.SIMULATION_RADII_MM, angle_radius_deg=None,
                    error_model=None, monte_carlo=None, progress: bool | None = None, tool: str | None = None,
                    trust_units: bool = False) -> "ErrorSimulation":
    """Sample ``n_mc`` robots with random errors and evaluate their exact tool poses (streamed, bounded memory).

    The errors are those of the error model (``error_model``: by default the robot file's first sigma set, e.g. the
    seed paper's Table 2 for ``tool_changer``: manufacturing errors of millimetres at the tool, not an allocated
    design; the printout names the sigma set). To simulate a design, pass its sigmas
    (``error_model=allocation.error_model_options()``).

    Parameters
    ----------
    robot : Robot, str or path
    n_mc : int, optional
        Number of sampled robots (>= 1; default 100 000); the same robots are evaluated at every pose. Short form
        of ``monte_carlo=MonteCarlo(n_mc=...)``.
    seed : int, optional
        Same seed, same numbers (default 0; short form of ``MonteCarlo(seed=...)``).
    q_deg_mm : array, shape (n_joints,) or (P, n_joints), optional
        Joint values [deg / mm]; default the pose set ``poses`` (or the nominal pose).
    poses : str, optional
        A pose set of the robot (not with ``q_deg_mm``).
    radius_mm : float or sequence
        Radii for ``P(|dP| < r)`` [mm] (95 % intervals: ``MonteCarlo.ci``; default 0.15 and 0.25).
    angle_radius_deg : float or sequence, optional
        Radii for ``P(|rotation error| < r)`` [deg]; default 0.002 rad (0.1146 deg).
    error_model : ErrorModelOptions, optional
        Sigma set, sigma overrides (mm or deg), link / deflection model, clearance, exclusions.
    monte_carlo : MonteCarlo, optional
        Samples, seed, interval, estimator, kept samples, histograms, and where the samples run
        (:class:`~tolalloc.workflows.MonteCarlo`).
    progress : bool, optional
        Progress bar on stderr (default: for runs of 10^7 samples or more in a terminal); never changes a number.

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
    mc = _monte_carlo(monte_carlo, n_mc, seed)
    model_options = as_settings(error_model, ErrorModelOptions, "error_model")
    radii, arad = _radii(radius_mm, angle_radius_deg)
    inputs.check_optional_flag(progress, "progress")
    inputs.check_name(poses, "poses", "the name of a pose set of the robot")
    inputs.check_one_pose_source(q_deg_mm, poses)
    rob = inputs.as_robot(robot, tool=tool, trust_units=trust_units)
    model = inputs.error_model(rob, **model_options.keywords())
    _, q = inputs.resolve_poses(rob, q_deg_mm, poses)
    from tolalloc.errormodel.model import CLEARANCE_SIGMA, CLEARANCE_TILT_LITERAL_RAD
    from tolalloc.montecarlo.run import run_mc

    with named_fields("", {"n": "n_mc"}):  # the sampler's count is this job's n_mc
        res = run_mc(model, q, mc.n_mc, mc.seed, radii_mm=radii, angle_radii_rad=arad or [ANGLE_RADIUS_RAD],
                     keep_samples=mc.kept, ci=mc.ci, n_jobs=mc.jobs, scheduler=mc.scheduler,
                     chunk_size=mc.chunk_size, progress=progress, hist_bins=mc.hist_bins,
                     hist_range_mm=mc.hist_range_mm, estimator=mc.estimator)
    tilt = ((CLEARANCE_TILT_LITERAL_RAD if model_options.clearance_tilt_literal else CLEARANCE_SIGMA["tilt_rad"])
            if model_options.clearance else None)
    return ErrorSimulation(res, rob, tilt, {"sigma_overrides": sorted(model_options.sigma or {})})


def _monte_carlo(monte_carlo, n_mc, seed) -> MonteCarlo:
    """The :class:`MonteCarlo` of the call: the object, or the short forms ``n_mc`` / ``seed`` (not both)."""
    given = {k: v for k, v in (("n_mc", n_mc), ("seed", seed)) if v is not None}
    if monte_carlo is not None and given:
        name = next(iter(given))
        raise ArgumentError(name, f"{inputs.shown(given[name])} and `monte_carlo` both set it; give one of them "
                            f"(MonteCarlo({name}=...)).")
    if monte_carlo is not None:
        return as_settings(monte_carlo, MonteCarlo, "monte_carlo")
    with named_fields("", {"n_mc": "n_mc", "seed": "seed"}):
        return MonteCarlo(**given)


def _radii(radius_mm, angle_radius_deg) -> tuple[list, list]:
    """``(radii [mm], angle radii [rad])`` checked by their argument names."""
    radii = inputs.check_values(radius_mm, "radius_mm", inputs.check_positive, "mm", "0.25")
    arad = [np.deg2rad(a) for a in inputs.check_values([] if angle_radius_deg is None else angle_radius_deg,
                                                       "angle_radius_deg", inputs.check_positive, "deg", "0.1")]
    return radii, arad


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

    def sigma_line(self) -> str:
        """Which errors were sampled: the sigma set (with its description from the robot file) and any overrides."""
        name = self.mc.labels.get("sigma_set")
        desc = (self.robot.sigma_sets.get(name) or {}).get("description") if name else None
        over = self.inputs.get("sigma_overrides") or []
        return (f"errors sampled: sigma set {name!r} of {self.robot.name}" + (f" ({desc})" if desc else "")
                + (f", sigma overridden for {', '.join(over) if len(over) <= 6 else f'{len(over)} parameters'}"
                   if over else "")
                + ("" if over else "; the sigma set's manufacturing errors, not an allocated design"))

    def scale_note(self) -> str | None:
        """Why every ``P(|dP| < r)`` is about zero, when it is: the errors are far larger than the radii."""
        r = self.mc
        best = max(float(np.max(v[:, 0])) for v in r.p_within.values()) if r.p_within else 1.0
        if best >= P_ABOUT_ZERO:
            return None
        mean = float(np.max(np.asarray(r.norm_mm)[:, 0]))
        return (f"note: every P(|dP| < r) is below {P_ABOUT_ZERO:g}: the sampled errors (mean |dP| up to {mean:.3g} mm) "
                "are far larger than the radii asked for. Give larger radius_mm, or simulate a design's tolerances "
                "(error_model=allocation.error_model_options() of an allocate_tolerances result).")

    def headline(self) -> list[str]:
        r = self.mc
        lines = [f"robot: {self.robot.name}   n_mc = {r.n}, seed = {r.seed}, {r.q.shape[0]} pose(s)", self.sigma_line()]
        for rad, v in r.p_within.items():
            lines.append(f"P(|dP| < {rad:g} mm) = " + ", ".join(f"{a:.4f} [{b:.4f}, {c:.4f}]" for a, b, c in v[:4]))
        lines += _angle_lines(r, 4)
        note = self.scale_note()
        return lines + ([note] if note else [])

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
        out = [self.sigma_line(), f"robot {self.robot.name}, n_mc={res.n}, seed={res.seed}, {format_labels(res.labels)}",
               res.to_frame().to_string(index=False, na_rep="", float_format=lambda x: f"{x:.6g}")]
        for r, v in res.p_within.items():
            out.append(f"P(|dp| < {r:g} mm) = " + ", ".join(f"{a:.4f} [{b:.4f}, {c:.4f}]" for a, b, c in v))
        out += _angle_lines(res)
        for r, e in (res.p_estimates or {}).items():
            out.append(f"P(|dp| < {r:g} mm), {e.message()}: " + ", ".join(
                f"{a:.6f} [{b:.6f}, {c:.6f}]" for a, b, c in zip(e.p_hat, e.ci_low, e.ci_high)))
        note = self.scale_note()
        return "\n".join(out + ([note] if note else []))

    def plot_scatter(self, ax=None):
        """Kept samples' position errors: a 3-D cloud and the x-y, x-z, y-z densities; draws into ``ax`` (four Axes,
        the first a 3-D one) or a new figure and returns the four."""
        import matplotlib.pyplot as plt

        from tolalloc.report.plots.mc import scatter_density
        from tolalloc.workflows.base import axes_of
        from tolalloc.workflows.checks import check_axes

        check_axes(ax, "ax", 4)
        if ax is None:  # the four panels (their colorbars are axes of the figure too, not panels)
            fig = plt.figure(figsize=(13, 3.6))
            ax = [fig.add_subplot(1, 4, 1, projection="3d")] + [fig.add_subplot(1, 4, k) for k in (2, 3, 4)]
        ax = list(np.ravel(np.asarray(ax, dtype=object)))
        if ax[0].name != "3d":
            raise ArgumentError("ax", "expected its first Axes with projection='3d' (the error cloud), got a 2-D one: "
                                "fig.add_subplot(1, 4, 1, projection='3d') and three more.")
        scatter_density(self.mc, None, axes=ax)
        return axes_of(ax)

    def write_files(self, folder, *, report: bool = False) -> list[str]:
        """Write ``mc_table.csv``, ``mc_summary.json``, ``mc_scatter.png`` (and the histograms) into an existing
        ``folder`` (not atomic; :meth:`save` stages through this); returns the file names."""
        from pathlib import Path

        import matplotlib.pyplot as plt

        from tolalloc.report.plots.mc import hist_density, scatter_density

        folder, res = Path(folder), self.mc
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
