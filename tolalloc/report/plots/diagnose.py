"""Figures of the sim-to-real diagnosis; each draws from a :class:`~tolalloc.diagnose.Diagnosis` (or its parts)."""

from __future__ import annotations

import sys

import matplotlib

if "ipykernel" not in sys.modules:  # files only; a notebook keeps its inline backend and shows the figures
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from tolalloc.report.plots import fit_layout  # noqa: E402

__all__ = ["plot_where", "plot_ranking", "plot_before_after", "plot_confusion", "draw_where", "where_figure",
           "where_panels", "plot_corrections"]


def where_panels(where, n_features: int = 6) -> int:
    """Panels of the "where" figure: the strongest features, the per-axis RMS and the regions."""
    return len(where.trends.head(n_features)) + 2


def draw_where(where, axes, n_features: int = 6, max_points: int = 600) -> None:
    """The panels of :func:`plot_where` into ``axes`` (a sequence of at least :func:`where_panels` Axes; the rest
    are switched off)."""
    trends = where.trends.head(n_features)
    k = len(trends)
    flat = list(np.ravel(np.asarray(axes, dtype=object)))
    norm = where.norm_mm
    for ax, (_, row) in zip(flat, trends.iterrows()):
        v = where.features[row["feature"]].to_numpy()
        show = np.linspace(0, len(v) - 1, min(len(v), max_points)).astype(int)
        ax.scatter(v[show], norm[show], s=5, alpha=0.5, rasterized=True)
        order = np.argsort(v)
        chunks = np.array_split(order, 8)
        ax.plot([v[c].mean() for c in chunks], [np.sqrt(np.mean(norm[c] ** 2)) for c in chunks], "r-o", ms=3,
                label="RMS in bins")
        ax.set_xlabel(row["feature"])
        ax.set_ylabel("|residual| [mm]")
        ax.set_title(f"rho={row['spearman_norm']:+.2f}, max|r| comp={row['max_abs_corr_component']:.2f}", fontsize=9)
    ax = flat[k]
    pa = where.per_axis
    ax.bar(pa["axis"], pa["rms_mm"])
    ax.set_ylabel("RMS [mm]")
    ax.set_title("per axis (robot base frame)", fontsize=9)
    ax = flat[k + 1]
    reg = where.regions
    ax.barh([f"r {a} / z {b}" for a, b in zip(reg["reach_mm"], reg["elevation_mm"])], reg["rms_mm"])
    ax.invert_yaxis()
    ax.set_xlabel("RMS [mm]")
    ax.set_title("regions (reach / elevation mm)", fontsize=9)
    ax.tick_params(axis="y", labelsize=7)
    for ax in flat[k + 2:]:
        ax.axis("off")


def where_figure(where, n_features: int = 6):
    """A new figure with the panels of :func:`plot_where`: ``(fig, axes (rows, 3))``."""
    ncol = 3
    nrow = int(np.ceil(where_panels(where, n_features) / ncol))
    return plt.subplots(nrow, ncol, figsize=(4.2 * ncol, 3.2 * nrow), squeeze=False)


def plot_where(where, path, n_features: int = 6, dpi: int = 72, max_points: int = 600) -> None:
    """Residual norm against the strongest features, per-axis RMS and the worst (reach, elevation) cells.

    At most ``max_points`` poses are drawn as dots (an even subsample, to keep the file small); the binned
    RMS line uses all poses.
    """
    fig, axes = where_figure(where, n_features)
    draw_where(where, axes, n_features, max_points)
    fig.suptitle("Residual after geometric calibration: where")
    fit_layout(fig)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)


def plot_ranking(diagnosis, path=None, dpi: int = 90, ax=None):
    """Clipped held-out RMS (the selection's score) of every candidate effect against the geometric model (first
    selection step). ``path``: saved there and closed; else drawn into ``ax`` (or a new figure), which is returned."""
    ranking = [c for c in diagnosis.ranking if c.applicable]
    fig, ax = plt.subplots(figsize=(6.5, 3.2)) if ax is None else (ax.figure, ax)
    names = ["geometric only"] + [c.effect for c in ranking]
    base = next((c.robust_rms_mm * 100.0 / (100.0 - c.gain_pct) for c in ranking if c.gain_pct < 100.0),
                diagnosis.stages[0].base_rms_mm)  # the geometric model's clipped RMS, from any candidate's gain
    vals = [base] + [c.robust_rms_mm for c in ranking]
    colors = ["grey"] + ["tab:green" if c.significant else "tab:blue" for c in ranking]
    ax.barh(names, vals, color=colors)
    for i, c in enumerate(ranking, start=1):
        ax.text(vals[i], i, f"  p={c.p_value:.1e}", va="center", fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel("clipped out-of-fold RMS of the training file [mm]")
    ax.set_title("Candidate effects on top of the geometric calibration (green: significant)", fontsize=9)
    return _done(fig, ax, path, dpi)


def plot_before_after(table, path=None, dpi: int = 90, ax=None):
    """Bars of RMS / p95 / max held-out error for nominal, geometric and final models (``before_after()`` table).
    ``path``: saved there and closed; else drawn into ``ax`` (or a new figure), which is returned."""
    fig, ax = plt.subplots(figsize=(6, 3.2)) if ax is None else (ax.figure, ax)
    x = np.arange(len(table))
    for i, col in enumerate(("rms_mm", "p95_mm", "max_mm")):
        ax.bar(x + (i - 1) * 0.27, table[col], width=0.27, label=col.replace("_mm", ""))
    ax.set_xticks(x, table["model"])
    ax.set_yscale("log")
    ax.set_ylabel("held-out error [mm]")
    ax.legend(fontsize=8)
    return _done(fig, ax, path, dpi)


def _done(fig, ax, path, dpi):
    """Save and close the figure (``path``), or return the Axes drawn on."""
    fit_layout(fig)
    if path is None:
        return ax
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return None


def plot_confusion(matrix, labels, path, title: str = "", dpi: int = 90) -> None:
    """Confusion matrix (rows: true label, columns: diagnosed), counts annotated."""
    m = np.asarray(matrix)
    fig, ax = plt.subplots(figsize=(6, 5))
    ax.imshow(m, cmap="Blues")
    ax.set_xticks(range(len(labels)), labels, rotation=45, ha="right")
    ax.set_yticks(range(len(labels)), labels)
    for i in range(m.shape[0]):
        for j in range(m.shape[1]):
            ax.text(j, i, str(m[i, j]), ha="center", va="center", color="black")
    ax.set_xlabel("diagnosed")
    ax.set_ylabel("true (withheld)")
    ax.set_title(title, fontsize=9)
    fit_layout(fig)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)


def plot_corrections(compensation, ax=None):
    """The joint corrections of a compensation (:class:`~tolalloc.diagnose.compensate.Compensation`) per target row,
    one line per joint [deg / mm]; refused rows marked on the axis. Draws into ``ax`` or a new figure and returns
    the Axes."""
    c = compensation
    fig, ax = plt.subplots(figsize=(7, 3.4)) if ax is None else (ax.figure, ax)
    rows = np.arange(1, len(c.q) + 1)
    dq = c.robot.q_to_interface(c.q - c.q_seed)
    ok = c.ok
    for j, jt in enumerate(c.robot.joints):
        ax.plot(rows[ok], dq[ok, j], ".-", ms=3, lw=0.8, label=f"{jt.name} [{'deg' if jt.is_revolute else 'mm'}]")
    if (~ok).any():
        ax.plot(rows[~ok], np.zeros(int((~ok).sum())), "rx", label="refused")
    ax.axhline(0.0, color="grey", lw=0.5)
    ax.set_xlabel("program row")
    ax.set_ylabel("correction (deg / mm)")
    ax.set_title("Compensated minus programmed joint values", fontsize=9)
    ax.legend(fontsize=7, ncol=2)
    return ax
