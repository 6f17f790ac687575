"""Monte Carlo figures are produced without a display."""

import matplotlib
import numpy as np
import matplotlib.pyplot as plt
import pytest

from tolalloc import TolallocError, load_robot
from tolalloc.errormodel import build_error_model
from tolalloc.montecarlo.run import run_mc
from tolalloc.report.plots import mc as mcplots
from tolalloc.montecarlo.sensitivity import PAPER_LINK_GRID_MM, quintic_trajectory, sensitivity, trajectory_errors


@pytest.fixture(scope="module")
def model():
    return build_error_model(load_robot("tool_changer"), "table2", clearance=True)


def test_backend_is_headless():
    assert matplotlib.get_backend().lower() == "agg"


def test_figures_written(tmp_path, model):
    q = model.robot.q_nominal
    res = run_mc(model, q, 3000, seed=0, keep_samples=3000)
    fig = mcplots.scatter_density(res, tmp_path / "scatter.png")
    assert len(fig.axes) >= 4
    plt.close(fig)
    sens = sensitivity(model, q, ["dl3", "dl4"], PAPER_LINK_GRID_MM)
    fig = mcplots.sensitivity_curves(sens, ("dx", "norm", "beta", "rot"), tmp_path / "sens.png")
    assert len(fig.axes[0].lines) == 2
    plt.close(fig)
    P = model.robot.poses("working")
    t, Q = quintic_trajectory(P[0], P[5], 5.0, 11)
    tr = trajectory_errors(model, t, Q, ["dth2"], mc=run_mc(model, Q, 500, seed=0))
    plt.close(mcplots.trajectory_plot(tr, tmp_path / "traj.png"))
    for name in ("scatter.png", "sens.png", "traj.png"):
        data = (tmp_path / name).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 5000


def test_scatter_needs_samples(model):
    res = run_mc(model, model.robot.q_nominal, 100, seed=0)
    with pytest.raises(TolallocError):
        mcplots.scatter_density(res)
    sens = sensitivity(model, model.robot.q_nominal, ["dl3"], [0.1])
    with pytest.raises(TolallocError):
        mcplots.sensitivity_curves(sens, ("speed",))
    plt.close("all")


def test_pose_probabilities_with_an_estimate_of_one_and_a_rounded_interval_end(tmp_path):
    """An estimate of exactly 1 whose interval's upper end is 1 - 2.2e-16 (floating point) still plots."""
    from types import SimpleNamespace

    from tolalloc.report.plots.allocate import plot_pose_probabilities

    one_below = 1.0 - np.finfo(float).eps
    v = SimpleNamespace(p_mc=np.array([1.0, 0.97]), ci_low=np.array([0.998, 0.96]),
                        ci_high=np.array([one_below, 0.98]), p_linear=np.array([0.9999, 0.97]), prob=0.95,
                        radius_mm=0.25)
    path = tmp_path / "p.png"
    plot_pose_probabilities(v, path)
    assert path.stat().st_size > 0


def test_cloud_draws_its_points_and_the_densities_all_kept(model):
    res = run_mc(model, model.robot.q_nominal, 3000, seed=0, keep_samples=3000)
    fig = mcplots.scatter_density(res, max_points=2000, cloud_points=300)
    cloud = fig.axes[0].collections[0]
    assert len(cloud.get_offsets()) == 300
    dp = res.samples["dp_mm"][:2000]
    xy = fig.axes[1].collections[0].get_coordinates()  # the x-y density's cell corners span the first 2000 samples
    assert xy[..., 0].min() == pytest.approx(dp[:, 0].min()) and xy[..., 0].max() == pytest.approx(dp[:, 0].max())
    assert xy[..., 1].min() == pytest.approx(dp[:, 1].min()) and xy[..., 1].max() == pytest.approx(dp[:, 1].max())
    plt.close(fig)


def test_fit_layout_leaves_no_engine_and_the_same_pixels(tmp_path):
    """tight_layout leaves a placeholder layout engine, which makes savefig draw the figure once more; fit_layout
    removes it, and the file is the same to the byte."""
    from tolalloc.report.plots import fit_layout

    def figure():
        fig, axes = plt.subplots(2, 2, figsize=(6, 4))
        for ax in axes.flat:
            ax.scatter(np.arange(50), np.arange(50) ** 0.5, s=3)
            ax.set_title("panel")
            ax.set_xlabel("x [mm]")
        fig.suptitle("title")
        return fig

    plain, fitted = figure(), figure()
    plain.tight_layout()
    assert plain.get_layout_engine() is not None
    fit_layout(fitted)
    assert fitted.get_layout_engine() is None
    plain.savefig(tmp_path / "plain.png", dpi=60)
    fitted.savefig(tmp_path / "fitted.png", dpi=60)
    assert (tmp_path / "plain.png").read_bytes() == (tmp_path / "fitted.png").read_bytes()
    plt.close("all")
