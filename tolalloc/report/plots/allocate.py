"""Figures of the tolerance allocation; each draws from an :class:`AllocationResult` / :class:`Verification`
(or a study's result frame) and never recomputes."""

from __future__ import annotations

import sys

import matplotlib

if "ipykernel" not in sys.modules:  # files only; a notebook keeps its inline backend and shows the figures
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from tolalloc.report.plots import fit_layout  # noqa: E402
from tolalloc.units import in_row_unit  # noqa: E402

__all__ = ["plot_budget", "plot_cloud", "plot_pareto", "plot_pose_probabilities"]

_KIND_COLORS = {"link_length": "#4c72b0", "joint_drive": "#55a868", "axis_deflection": "#c44e52",
                "clearance_axial": "#8172b2", "clearance_radial": "#937860", "clearance_tilt": "#da8bc3"}


def plot_budget(table, path=None, *, title: str = "", dpi: int = 100, axes=None):
    """Error budget of a design: tolerance per parameter and its variance share at the design's worst pose.

    Parameters
    ----------
    table : DataFrame
        :meth:`AllocationResult.to_frame` of the design (columns parameter, kind, unit, tol_mm, tol_deg,
        variance_share_pct, at_limit): the figure shows that table's design and nothing else.
    axes : pair of matplotlib Axes, optional
        Draw into these (tolerances, shares); default a new figure.
    """
    if axes is None:
        fig, axes = plt.subplots(1, 2, figsize=(10, 0.28 * len(table) + 1.6), sharey=True)
    else:
        fig = axes[0].figure
    y = np.arange(len(table))[::-1]
    colors = [_KIND_COLORS.get(k, "#777777") for k in table["kind"]]
    tol = in_row_unit(table, "tol").to_numpy(float)
    ax = axes[0]
    ax.barh(y, tol, color=colors)
    ax.set_xscale("log")
    ax.set_yticks(y, [f"{p} [{u}]" for p, u in zip(table["parameter"], table["unit"])], fontsize=8)
    ax.set_xlabel("tolerance ± [mm for lengths, deg for angles] (log scale)")
    for yi, (t, lim) in enumerate(zip(tol, table["at_limit"])):
        if lim:
            ax.text(t, y[yi], f" {lim}", va="center", fontsize=7)
    ax = axes[1]
    ax.barh(y, table["variance_share_pct"], color=colors)
    ax.set_xlabel("share of tr Σ at the worst pose [%]")
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for k, c in _KIND_COLORS.items() if k in set(table["kind"])]
    ax.legend(handles, [k for k in _KIND_COLORS if k in set(table["kind"])], fontsize=7, loc="lower right")
    if title:
        fig.suptitle(title, fontsize=10)
    fit_layout(fig)
    return _finish(fig, path, dpi)


def plot_cloud(verification, path=None, *, title: str = "", dpi: int = 100, axes=None):
    """Position errors of the kept Monte Carlo samples at one pose, three projections, with the r-circle.

    Parameters
    ----------
    verification : Verification
        With ``samples_mm`` (kept at ``samples_pose``).
    axes : three matplotlib Axes, optional
        Draw into these (x-y, x-z, y-z); default a new figure.
    """
    s = verification.samples_mm
    if s is None or len(s) == 0:
        raise ValueError("the verification kept no samples (keep_samples=0)")
    r = verification.radius_mm
    inside = np.linalg.norm(s, axis=1) < r
    if axes is None:
        fig, axes = plt.subplots(1, 3, figsize=(11, 3.8))
    else:
        fig = axes[0].figure
    th = np.linspace(0, 2 * np.pi, 200)
    for ax, (i, j) in zip(axes, [(0, 1), (0, 2), (1, 2)]):
        ax.scatter(s[inside, i], s[inside, j], s=2, alpha=0.4, color="#4c72b0", label="|dP| < r")
        ax.scatter(s[~inside, i], s[~inside, j], s=3, alpha=0.7, color="#c44e52", label="|dP| >= r")
        ax.plot(r * np.cos(th), r * np.sin(th), "k-", lw=1, label=f"r = {r:g} mm")
        ax.set_xlabel(f"d{'xyz'[i]} [mm]")
        ax.set_ylabel(f"d{'xyz'[j]} [mm]")
        ax.set_aspect("equal")
    axes[0].legend(fontsize=7, loc="upper right")
    k = verification.samples_pose
    fig.suptitle(title or f"pose {k + 1}: {len(s)} of the Monte Carlo samples, "
                 f"P_hat = {verification.p_mc[k]:.4f} (linear {verification.p_linear[k]:.4f})", fontsize=10)
    fit_layout(fig)
    return _finish(fig, path, dpi)


def plot_pose_probabilities(verification, path=None, *, dpi: int = 100, ax=None, interval: str | None = None):
    """Per pose: linear prediction, Monte Carlo estimate with its interval, and the required p.

    ``ax``: draw into this matplotlib Axes (default a new figure). ``interval``: what the intervals are, for the
    legend (default the verification's ``interval_label()``, e.g. ``simultaneous 95% interval``; else
    ``95% interval``).
    """
    v = verification
    if interval is None:
        interval = v.interval_label() if hasattr(v, "interval_label") else "95% interval"
    x = np.arange(1, len(v.p_mc) + 1)
    if ax is None:
        fig, ax = plt.subplots(figsize=(7, 3.5))
    else:
        fig = ax.figure
    ax.plot(x, v.p_linear, "o", mfc="none", label="linear (Gaussian)")
    # an interval end computed a rounding error inside the estimate (an estimate of exactly 1 whose upper end
    # comes out as 1 - 2e-16) is drawn as a zero-length bar: matplotlib refuses negative lengths
    below = np.maximum(np.asarray(v.p_mc) - v.ci_low, 0.0)
    above = np.maximum(np.asarray(v.ci_high) - v.p_mc, 0.0)
    ax.errorbar(x, v.p_mc, yerr=[below, above], fmt="s", ms=3, capsize=3,
                label=f"Monte Carlo, {interval}")
    ax.axhline(v.prob, color="k", lw=0.8, ls="--", label=f"p = {v.prob:g}")
    ax.set_xlabel("pose")
    ax.set_ylabel(f"P(|dP| < {v.radius_mm:g} mm)")
    ax.set_xticks(x)
    ax.legend(fontsize=8)
    fit_layout(fig)
    return _finish(fig, path, dpi)


def plot_pareto(frame, x: str, path=None, *, xlabel: str = "", logx: bool = False, dpi: int = 100, title: str = ""):
    """Cost against a requirement parameter for the certified and exact solvers.

    Parameters
    ----------
    frame : DataFrame
        Columns ``x``, ``cost_certified``, ``cost_exact`` (NaN where infeasible), optionally ``cost_trace``,
        ``cost_lmi``.
    """
    fig, ax = plt.subplots(figsize=(6, 4))
    for col, style, lab in [("cost_trace", ":", "certified, trace rule"), ("cost_lmi", "-.", "certified, eigenvalue rule"),
                            ("cost_certified", "--o", "certified (cheaper rule)"), ("cost_exact", "-s", "exact (IPOPT)")]:
        if col in frame:
            ax.plot(frame[x], frame[col], style, ms=4, label=lab)
    if "feasible" in frame and (~frame["feasible"]).any():
        bad = frame.loc[~frame["feasible"], x]
        for b in bad:
            ax.axvline(b, color="#c44e52", alpha=0.2, lw=6)
        ax.plot([], [], color="#c44e52", alpha=0.3, lw=6, label="infeasible within limits")
    if logx:
        ax.set_xscale("log")
    ax.set_xlabel(xlabel or x)
    ax.set_ylabel("total cost [relative units]")
    if title:
        ax.set_title(title, fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fit_layout(fig)
    return _finish(fig, path, dpi)


def _finish(fig, path, dpi):
    if path is not None:
        fig.savefig(path, dpi=dpi)
        plt.close(fig)
        return None
    return fig
