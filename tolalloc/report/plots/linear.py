"""Figures of the linear variance map: error-budget bars and the linear-vs-Monte-Carlo comparison."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from tolalloc.linear.covariance import ErrorBudget
from tolalloc.report.plots import fit_layout

__all__ = ["budget_bars", "linearisation_figure"]

_COLORS = {"x": "#4c72b0", "y": "#55a868", "z": "#c44e52", "norm": "#333333"}


def budget_bars(b: ErrorBudget, path=None, *, pose="worst", by: str = "parameter", top: int = 12, dpi: int = 110,
                ax=None):
    """Grouped horizontal bars: each contributor's share [%] of the variance of x, y, z and of the norm.

    Parameters
    ----------
    b : ErrorBudget
    path : str or Path, optional
        Save the figure there (PNG).
    pose : int or "worst"
    by : {"parameter", "kind"}
    top : int
        Number of dominant contributors shown (by share of the norm).
    ax : matplotlib Axes, optional
        Draw into it (default: a new figure).

    Returns
    -------
    matplotlib.figure.Figure
    """
    df = b.to_frame(pose=pose, by=by).head(top)
    label = df[by].tolist()
    if by == "parameter":
        label = [f"{p} ({k.replace('_', ' ')})" for p, k in zip(df["parameter"], df["kind"])]
    n = len(df)
    if ax is None:
        fig, ax = plt.subplots(figsize=(7.5, 0.42 * n + 1.4))
    else:
        fig = ax.figure
    y = np.arange(n)[::-1]
    h = 0.2
    for i, axn in enumerate(("x", "y", "z", "norm")):
        ax.barh(y + (1.5 - i) * h, df[f"share_{axn}_pct"], height=h, color=_COLORS[axn],
                label=f"{axn} (var {b.total[int(df['pose'].iloc[0]) - 1, i]:.3g} {b.unit.replace('2', '²')})")
    ax.set_yticks(y)
    ax.set_yticklabels(label, fontsize=8)
    ax.set_xlabel("share of variance [%]")
    pose_i = int(df["pose"].iloc[0])
    qtxt = ", ".join(f"{v:g}" for v in np.round(b.q_interface[pose_i - 1], 2))  # pose_i is 1-based
    ax.set_title(f"{b.quantity} error budget, pose {pose_i} (q = {qtxt} deg/mm)", fontsize=9)
    ax.legend(fontsize=7, loc="lower right")
    ax.grid(axis="x", alpha=0.3)
    fit_layout(fig)
    if path is not None:
        fig.savefig(path, dpi=dpi)
    return fig


def linearisation_figure(table, path=None, *, dpi: int = 110):
    """Linear vs Monte Carlo across error scales (a table from ``studies/linearisation``).

    Parameters
    ----------
    table : pandas.DataFrame
        Columns ``case, scale, pose, quantity, linear, mc, mc_se`` with quantities ``std_x_mm``,
        ``std_y_mm``, ``std_z_mm``, ``rms_mm``, ``p_within`` (at the radius ``r_mm``) and
        ``corr_xy`` .. ``corr_yz``.
    path : str or Path, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.8))
    cases = list(dict.fromkeys(table["case"]))
    markers = dict(zip(cases, "osD^v"))
    ax = axes[0]
    for case in cases:
        sub = table[(table["case"] == case) & table["quantity"].isin(["std_x_mm", "std_y_mm", "std_z_mm", "rms_mm"])]
        g = sub.groupby("scale")
        rel = g.apply(lambda d: np.max(np.abs(d["linear"] / d["mc"] - 1)), include_groups=False)
        ax.plot(rel.index, 100 * rel.values, marker=markers[case], label=case)
    ax.axhline(2, color="grey", ls=":", lw=1)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("sigma scale (x Table 2)")
    ax.set_ylabel("max |linear/MC - 1| of std, rms [%]")
    ax.set_title("standard deviations", fontsize=9)
    ax.legend(fontsize=7)
    ax = axes[1]
    for case in cases:
        sub = table[(table["case"] == case) & table["quantity"].str.startswith("corr_")]
        g = sub.groupby("scale")
        dif = g.apply(lambda d: np.max(np.abs(d["linear"] - d["mc"])), include_groups=False)
        ax.plot(dif.index, dif.values, marker=markers[case], label=case)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("sigma scale (x Table 2)")
    ax.set_ylabel("max |corr linear - corr MC|")
    ax.set_title("correlations", fontsize=9)
    ax = axes[2]
    for case in cases:
        sub = table[(table["case"] == case) & (table["quantity"] == "p_within")]
        ax.errorbar(sub["mc"], sub["linear"] - sub["mc"], yerr=2 * sub["mc_se"], fmt=markers[case], ms=4,
                    label=case, alpha=0.8)
    ax.axhline(0, color="grey", lw=1)
    ax.set_xlabel("P(|dp| < r), Monte Carlo")
    ax.set_ylabel("linear-Gaussian P - MC P (bars: 2 s.e.)")
    ax.set_title("probabilities (r = radius of MC p = 0.5, 0.9, 0.99)", fontsize=9)
    fit_layout(fig)
    if path is not None:
        fig.savefig(path, dpi=dpi)
    return fig
