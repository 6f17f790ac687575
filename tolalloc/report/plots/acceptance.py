"""Figures of the ISO 9283 acceptance test: the predicted statistics beside the simulated robots, with the limit and
the guard band of the measurement uncertainty. Drawn from result objects; nothing is recomputed."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

__all__ = ["plot_acceptance", "plot_feature_shares"]


def plot_acceptance(prediction, simulation=None, *, names=None, ax=None):
    """One panel per statistic: for each test pose, the measured statistic of the simulated robots (box: quartiles,
    whiskers 2.5 % - 97.5 %), the predicted measured value at the share (dot) and the robot's (cross), the limit
    (solid) and the limit less ``U`` (dashed: the measured value must lie below it for conformance demonstrated,
    ISO 14253-1).

    Parameters
    ----------
    prediction : AcceptancePrediction
    simulation : SimulatedAcceptance, optional
    names : sequence of str, optional
        Statistics to draw (default all).
    ax : array of Axes, optional
        One per statistic.

    Returns
    -------
    array of Axes
    """
    stats = [s for s in prediction.statistics if names is None or s.model.name in names]
    if ax is None:
        fig, ax = plt.subplots(1, len(stats), figsize=(4.2 * len(stats), 3.6), squeeze=False)
        ax = ax[0]
    for a, s in zip(np.atleast_1d(ax), stats):
        m = s.model
        f, unit = (180 / np.pi, "deg") if m.unit == "deg" else (1000.0, "um")
        x = np.arange(m.n_rows)
        if simulation is not None and m.name in simulation.measured:
            data = [simulation.measured[m.name][:, i] * f for i in x]
            a.boxplot(data, positions=x, widths=0.5, whis=(2.5, 97.5), showfliers=False)
        a.plot(x, s.measured * f, "o", color="C1", label=f"predicted, measured ({100 * m.requirement.share:g} %)")
        a.plot(x, s.robot * f, "x", color="C2", label="predicted, robot")
        a.axhline(m.limit * f, color="C3", label="limit")
        a.plot(x, (m.limit - s.U) * f, "--", color="C3", label="limit - U")
        if m.n_rows <= 6:
            a.set_xticks(x, m.labels, fontsize=8)
        elif m.n_rows <= 12:                          # a multi-directional test's pairs: "P1 -x/-y" ...
            a.set_xticks(x, m.labels, fontsize=7, rotation=60, ha="right")
        else:
            a.set_xticks(x, [str(i + 1) for i in x], fontsize=8)
        a.set_title(f"{m.name} ({m.requirement.who()})", fontsize=9)
        a.set_ylabel(f"{m.name} [{unit}]")
        a.set_ylim(bottom=0)
    np.atleast_1d(ax)[0].legend(fontsize=7, loc="lower right")
    return ax


def plot_feature_shares(frame, *, top: int = 12, ax=None):
    """Horizontal bars of the drawing features' share of the position-error variance at the worst pose, largest
    first (``frame``: :meth:`~tolalloc.allocate.tolerance_analysis.DrawingAnalysis.feature_frame`). Returns the axes."""
    rows = frame.head(top).iloc[::-1]
    return _share_bars([f"{f} ({c})" for f, c in zip(rows["feature"], rows["characteristic"])],
                       rows["variance_share_pct"], "share of the variance at the worst pose [%]", ax)


def plot_source_shares(frame, *, top: int = 12, ax=None):
    """Horizontal bars of each source's share of the tool-error variance at the worst point, largest first
    (``frame``: :meth:`~tolalloc.allocate.parts_result.PartsAllocation.variance_shares`). Returns the axes."""
    rows = frame.sort_values("share_pct").tail(top)
    return _share_bars([f"{s} ({w})" for s, w in zip(rows["source"], rows["what"])], rows["share_pct"],
                       "share of the variance at the worst point [%]", ax)


def _share_bars(labels, shares, xlabel: str, ax):
    """Horizontal bars of variance shares [%], the largest at the top (``labels`` and ``shares`` bottom to top)."""
    if ax is None:
        _, ax = plt.subplots(figsize=(6.0, 0.3 * len(labels) + 1.2))
    ax.barh(labels, shares, color="C0")
    ax.set_xlabel(xlabel)
    ax.tick_params(axis="y", labelsize=7)
    return ax
