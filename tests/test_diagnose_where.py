"""Residual breakdown finds the feature that drives a planted residual."""

import numpy as np

import tolalloc
from tolalloc.diagnose import calibrate, generate, measurements_from_frame
from tolalloc.diagnose.where import where_breakdown


def test_thermal_residual_points_at_temperature():
    robot = tolalloc.load_robot("ur10")
    case = generate(robot, "thermal", 150, np.random.default_rng(11), magnitude_mm=0.5)
    m = measurements_from_frame(case.frame, robot)
    cal = calibrate(robot, m)
    w = where_breakdown(robot, m, cal.geometric)
    top3 = list(w.trends["feature"].head(3))
    assert "temperature_c" in top3 or "time_s" in top3
    np.testing.assert_allclose(w.per_axis["rms_mm"].iloc[3], cal.geometric.rms_mm, rtol=1e-12)
    assert len(w.worst) == 10 and w.worst["error_mm"].is_monotonic_decreasing
    assert w.regions["poses"].sum() == m.n_poses
