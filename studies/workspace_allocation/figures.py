"""Figure of the workspace-allocation study: linear P on a 2-D slice through the worst sampled pose."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import TwoSlopeNorm  # noqa: E402


def _axis(robot, j, values):
    """Joint values for an axis in the interface unit (deg revolute, mm prismatic) and the label."""
    joint = robot.joints[j]
    if robot.revolute_mask[j]:
        return np.rad2deg(values), f"q{j + 1} {joint.name} [deg]"
    return np.asarray(values), f"q{j + 1} {joint.name} [mm]"


def plot_slices(robot, slices, titles, prob, path, dpi=90):
    """One panel per design: P over two joints (others at the slice's centre), contour at ``prob``.

    Parameters
    ----------
    robot : Robot
    slices : list of dict
        From ``compute.p_slice`` (``x``, ``y``, ``P``, ``joints``, ``q_centre``).
    titles : list of str
    prob : float
    """
    lo = min(float(s["P"].min()) for s in slices)
    hi = max(float(s["P"].max()) for s in slices)
    norm = TwoSlopeNorm(vcenter=prob, vmin=min(lo, prob - 1e-4), vmax=max(hi, prob + 1e-4))
    fig, axes = plt.subplots(1, len(slices), figsize=(5.6 * len(slices), 4.8), squeeze=False)
    for ax, s, title in zip(axes[0], slices, titles):
        a, b = s["joints"]
        x, xl = _axis(robot, a, s["x"])
        y, yl = _axis(robot, b, s["y"])
        im = ax.pcolormesh(x, y, s["P"], cmap="RdYlGn", norm=norm, shading="auto")
        if s["P"].min() < prob < s["P"].max():
            cs = ax.contour(x, y, s["P"], levels=[prob], colors="k", linewidths=1.2)
            ax.clabel(cs, fmt=f"P = {prob:g}", fontsize=7)
        cx, _ = _axis(robot, a, s["q_centre"][a])
        cy, _ = _axis(robot, b, s["q_centre"][b])
        ax.plot([cx], [cy], marker="*", color="k", ms=13, ls="none", clip_on=False, zorder=5)
        ax.set_xlabel(xl)
        ax.set_ylabel(yl)
        ax.set_title(title, fontsize=9)
    fig.colorbar(im, ax=axes[0].tolist(), label="linear P(|dP| < r)", shrink=0.9)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
