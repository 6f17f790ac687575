"""Synthetic measurement sets: same columns whatever the effect; stated noise and magnitude."""

import numpy as np
import pytest

import tolalloc
from tolalloc import TolallocError
from tolalloc.diagnose import LABELS, generate, measurements_from_frame
from tolalloc.diagnose.synth import split_frame


@pytest.mark.parametrize("name", ["tool_changer", "ur10"])
def test_same_columns_for_every_label(name):
    robot = tolalloc.load_robot(name)
    cols = {tuple(generate(robot, lab, 20, np.random.default_rng(1)).frame.columns) for lab in LABELS}
    assert len(cols) == 1
    (c,) = cols
    assert c[:9] == ("q1", "q2", "q3", "q4", "q5", "q6", "x_mm", "y_mm", "z_mm")
    assert "temperature_c" in c and "dir6" in c and "payload_kg" in c and "time_s" in c


def test_noise_and_effect_size():
    robot = tolalloc.load_robot("ur10")
    base = generate(robot, "none", 60, np.random.default_rng(2), noise_mm=0.0, magnitude_mm=0.4)
    noisy = generate(robot, "none", 60, np.random.default_rng(2), noise_mm=0.02, magnitude_mm=0.4)
    d = (noisy.frame[["x_mm", "y_mm", "z_mm"]] - base.frame[["x_mm", "y_mm", "z_mm"]]).to_numpy()
    assert d.std() == pytest.approx(0.02, rel=0.15)
    eff = generate(robot, "backlash", 60, np.random.default_rng(2), noise_mm=0.0, magnitude_mm=0.4)
    # same seed: identical poses, frame, geometry; the difference is the effect (exact FK vs its first-order size)
    d = (eff.frame[["x_mm", "y_mm", "z_mm"]] - base.frame[["x_mm", "y_mm", "z_mm"]]).to_numpy()
    assert np.sqrt(np.mean(np.sum(d ** 2, axis=1))) == pytest.approx(0.4, rel=0.02)
    m = measurements_from_frame(eff.frame, robot)
    assert m.n_poses == 60
    tr, te = split_frame(eff.frame, 0.25, np.random.default_rng(0))
    assert len(tr) == 45 and len(te) == 15
    with pytest.raises(TolallocError, match="one of"):
        generate(robot, "gravity", 10)


def test_an_effect_the_robot_cannot_show_is_refused_not_nan():
    """A single prismatic joint has no revolute joint for a transmission error and no link a load can bend: the
    generator says so (it used to scale by 1/0 and write NaN into the table)."""
    import warnings

    robot = tolalloc.Robot.from_dh([{"name": "q1", "type": "prismatic", "d_mm": 300, "a_mm": 200, "alpha_deg": 90}],
                                   convention="standard")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for effect in ("transmission", "link_deflection"):
            with pytest.raises(TolallocError, match=f"'{effect}' moves no target point of robot 'dh_robot'"):
                generate(robot, effect, 20, np.random.default_rng(0))
        frame = generate(robot, "backlash", 20, np.random.default_rng(0)).frame
    assert np.isfinite(frame.select_dtypes("number").to_numpy()).all()


@pytest.mark.parametrize("n_poses", [0, 1, -5, 2.5, True])
def test_a_pose_count_that_is_not_a_whole_number_of_at_least_two_is_refused(n_poses):
    # regression: 0 ended in a numpy IndexError, -5 in "negative dimensions are not allowed"
    with pytest.raises(TolallocError, match=r"n_poses: expected a whole number of poses >= 2"):
        generate(tolalloc.load_robot("tool_changer"), "backlash", n_poses, np.random.default_rng(0))
