"""Figures of a pooled fleet; each draws from the fleet table (:meth:`tolalloc.workflows.FleetAnalysis.to_frame`)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from tolalloc.report.plots import fit_layout  # noqa: E402

__all__ = ["plot_spread", "plot_cpk"]


def plot_spread(table, ax=None):
    """Between-robot spread of the geometric parameters with its interval: divided by the allocated sd where the
    table has one (1 = as allocated), else in mm / deg. Returns the Axes."""
    tab = table[table["kind"] == "geometric"]
    fig, ax = plt.subplots(figsize=(7, 0.28 * len(tab) + 1.4)) if ax is None else (ax.figure, ax)
    y = np.arange(len(tab))
    if "allocated_sd" in tab.columns:
        s = tab["allocated_sd"].to_numpy()
        f, label = 1.0 / s, "spread / allocated sd"
        ax.axvline(1.0, color="grey", lw=0.8)
    else:
        f = np.where(tab["unit"] == "rad", np.rad2deg(1.0), 1.0)
        label = "spread (mm, deg)"
    mid, lo, hi = tab["spread"] * f, tab["spread_lo"] * f, tab["spread_hi"] * f
    ax.errorbar(mid, y, xerr=[mid - lo, hi - mid], fmt="o", ms=3, capsize=2)
    ax.set_yticks(y, tab["parameter"], fontsize=7)
    ax.invert_yaxis()
    ax.set_xscale("log")
    ax.set_xlabel(label)
    ax.set_title("Robot-to-robot spread of the identifiable parameters (interval)", fontsize=9)
    fit_layout(fig)
    return ax


def plot_cpk(table, ax=None):
    """Cpk of every geometric combination (bar) and its lower end (dot) against the allocation; lines at 1 and 1.33.
    Returns the Axes."""
    tab = table[table["kind"] == "geometric"]
    fig, ax = plt.subplots(figsize=(7, 0.28 * len(tab) + 1.4)) if ax is None else (ax.figure, ax)
    y = np.arange(len(tab))
    ax.barh(y, np.minimum(tab["cpk"], 10.0), color="tab:blue", alpha=0.6, label="Cpk")
    ax.plot(np.clip(tab["cpk_lo"], -1.0, 10.0), y, "k.", label="lower end")
    for v in (1.0, 1.33):
        ax.axvline(v, color="grey", lw=0.8, ls="--")
    ax.set_yticks(y, tab["parameter"], fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("Cpk against the allocated tolerance (clipped at 10)")
    ax.legend(fontsize=7)
    fit_layout(fig)
    return ax
