"""Monte Carlo figures: error clouds with projection densities, sensitivity curves, errors over time.

Every function draws from a result object (:class:`~tolalloc.montecarlo.run.McResult`,
:class:`~tolalloc.montecarlo.sensitivity.SensitivityResult`, :class:`~tolalloc.montecarlo.sensitivity.TrajectoryResult`)
and returns the matplotlib figure; ``path`` saves it (PNG, modest dpi).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.report.plots import fit_layout

__all__ = ["scatter_density", "hist_density", "sensitivity_curves", "trajectory_plot"]

_DIRS = {"dx": (0, "Δx [mm]"), "dy": (1, "Δy [mm]"), "dz": (2, "Δz [mm]")}


def _save(fig, path, dpi):
    if path is not None:
        fig.savefig(path, dpi=dpi, bbox_inches="tight")
    return fig


def scatter_density(result, path=None, *, title: str = "", max_points: int = 20000, cloud_points: int = 5000,
                    dpi: int = 90, axes=None):
    """3-D scatter of ``p' - p`` and x-y, x-z, y-z projection densities (the paper's Figs. 6 and 12).

    Needs ``result.samples`` (run :func:`run_mc` with ``keep_samples > 0``). The densities use the first
    ``max_points`` kept samples, the 3-D cloud the first ``cloud_points`` of them (more only overplot it, and a 3-D
    scatter costs its drawing time per point). ``axes``: draw into these four Axes (the first with
    ``projection="3d"``); default a new figure.
    """
    if not result.samples:
        raise TolallocError("scatter_density: the result has no samples; run the Monte Carlo with keep_samples > 0.")
    dp = result.samples["dp_mm"][:max_points]
    if axes is None:
        fig = plt.figure(figsize=(13, 3.6))
        axes = [fig.add_subplot(1, 4, 1, projection="3d")] + [fig.add_subplot(1, 4, k) for k in (2, 3, 4)]
    else:
        fig = axes[0].figure
    ax = axes[0]
    cloud = dp[:cloud_points]
    ax.scatter(cloud[:, 0], cloud[:, 1], cloud[:, 2], s=0.5, alpha=0.3)
    ax.set_xlabel("Δx [mm]")
    ax.set_ylabel("Δy [mm]")
    ax.set_zlabel("Δz [mm]")
    ax.set_title("error cloud")
    for k, (i, j, name) in enumerate([(0, 1, "x-y"), (0, 2, "x-z"), (1, 2, "y-z")]):
        a = axes[k + 1]
        h = a.hist2d(dp[:, i], dp[:, j], bins=60, density=True, cmap="viridis")
        fig.colorbar(h[3], ax=a, fraction=0.046)
        a.set_xlabel(f"Δ{'xyz'[i]} [mm]")
        a.set_ylabel(f"Δ{'xyz'[j]} [mm]")
        a.set_title(f"{name} projection density")
    lab = result.labels
    fig.suptitle(title or f"n={result.n}, {lab.get('sigma_set')}, links {lab.get('link_mode')}, "
                 f"deflection {lab.get('deflection_mode')}, clearance {lab.get('clearance')}", fontsize=9)
    fit_layout(fig)
    return _save(fig, path, dpi)


def sensitivity_curves(result, quantities=("dx", "dy", "dz", "norm"), path=None, *, title: str = "", dpi: int = 90):
    """One panel per quantity, one curve per parameter (the paper's Figs. 7-9, 13-16).

    ``quantities``: ``dx``, ``dy``, ``dz``, ``norm`` (mm), ``alpha``, ``beta``, ``gamma``, ``rot`` (rad).
    The x axis is the parameter value in mm or deg.
    """
    fig, axes = plt.subplots(1, len(quantities), figsize=(3.4 * len(quantities), 3.2), squeeze=False)
    for ax, qn in zip(axes[0], quantities):
        for i, name in enumerate(result.params):
            f = 1.0 if result.units[i] == "mm" else 180 / np.pi
            x = result.grid[i] * f
            if qn in _DIRS:
                y, lab = result.dp_mm[i, :, _DIRS[qn][0]], _DIRS[qn][1]
            elif qn == "norm":
                y, lab = result.norm_mm[i], "|Δp| [mm]"
            elif qn in ("alpha", "beta", "gamma"):
                y, lab = result.euler_rad[i, :, ("alpha", "beta", "gamma").index(qn)], f"Δ{qn} [rad]"
            elif qn == "rot":
                y, lab = result.rot_rad[i], "attitude error |Δφ| [rad]"
            else:
                raise TolallocError(f"sensitivity_curves: unknown quantity {qn!r}; use dx, dy, dz, norm, alpha, beta, gamma, rot.")
            ax.plot(x, y, marker="o", ms=3, label=name)
        unit = "mm" if all(u == "mm" for u in result.units) else "deg" if all(u == "rad" for u in result.units) else "mm / deg"
        ax.set_xlabel(f"parameter error [{unit}]")
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
    axes[0][-1].legend(fontsize=7)
    if title:
        fig.suptitle(title, fontsize=9)
    fit_layout(fig)
    return _save(fig, path, dpi)


def trajectory_plot(result, path=None, *, title: str = "", dpi: int = 90):
    """Error of each direction over time, one curve per parameter, plus the Monte Carlo ±1 std band
    if the result carries one (the paper's Fig. 18, as curves instead of surfaces)."""
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.3))
    for d, ax in enumerate(axes):
        for i, name in enumerate(result.params):
            ax.plot(result.t_s, result.dp_mm[:, i, d], label=name)
        if result.mc is not None:
            sd = result.mc.std_mm[:, d]
            ax.fill_between(result.t_s, -sd, sd, color="grey", alpha=0.2, label="MC ±1 std (all errors)")
        ax.set_xlabel("time [s]")
        ax.set_ylabel(f"Δ{'xyz'[d]} [mm]")
        ax.grid(alpha=0.3)
    axes[-1].legend(fontsize=7)
    if title:
        fig.suptitle(title, fontsize=9)
    fit_layout(fig)
    return _save(fig, path, dpi)


def hist_density(result, path=None, *, pose: int = 0, title: str = "", dpi: int = 90):
    """x-y, x-z, y-z projection densities of ``p' - p`` from streamed histograms (all samples, Figs. 6/12).

    Needs ``result.hist`` (run :func:`run_mc` with ``hist_bins > 0``).
    """
    h = getattr(result, "hist", None)
    if h is None:
        raise TolallocError("hist_density: the result has no histograms; run the Monte Carlo with hist_bins > 0.")
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.4))
    for k, (ax, plane) in enumerate(zip(axes, h.planes)):
        i, j = "xyz".index(plane[0]), "xyz".index(plane[1])
        ei, ej = h.edges_mm[pose, i], h.edges_mm[pose, j]
        m = ax.pcolormesh(ei, ej, h.density(pose, plane).T, cmap="viridis", shading="flat")
        fig.colorbar(m, ax=ax, fraction=0.046)
        ax.set_xlabel(f"Δ{plane[0]} [mm]")
        ax.set_ylabel(f"Δ{plane[1]} [mm]")
        ax.set_title(f"{plane[0]}-{plane[1]} density ({h.outside[pose, k] / h.n:.1e} outside)", fontsize=9)
    fig.suptitle(title or f"n={h.n}, pose {pose}", fontsize=9)
    fit_layout(fig)
    return _save(fig, path, dpi)
