"""simulate_errors shows every probability it was asked for, each radius in the unit the user gave."""

import numpy as np

import tolalloc


def test_orientation_probability_is_printed_with_its_radius_in_deg():
    sim = tolalloc.simulate_errors("tool_changer", 500, seed=2, angle_radius_deg=1.0)
    line = next(ln for ln in sim.text().splitlines() if ln.startswith("P(|dw| < 1 deg) = "))
    p, lo, hi = sim.mc.p_within_angle[np.deg2rad(1.0)][0]
    assert line == f"P(|dw| < 1 deg) = {p:.4f} [{lo:.4f}, {hi:.4f}]"
    assert "P(|dw| < 1 deg)" in repr(sim)
    block = sim.summary()["p_within_angle"]
    assert [v["radius_deg"] for v in block.values()] == [1.0]


def test_a_radius_not_simulated_is_refused_naming_the_simulated_ones():
    import pickle

    import pytest

    from tolalloc.montecarlo import RadiusNotSimulated

    sim = tolalloc.simulate_errors("tool_changer", radius_mm=[0.25, 25.0],
                                   monte_carlo=tolalloc.MonteCarlo(n_mc=300, seed=1, estimator="paired"))
    with pytest.raises(RadiusNotSimulated, match=r"^radius 0.3 mm was not simulated; simulated radii: 0.25 mm, 25 mm\. "
                                                 r"Simulate it with radius_mm=\[0.25, 25, 0.3\] \(simulate_errors; "
                                                 r"--radius-mm\): the same seed gives the same samples\.$") as info:
        sim.mc.p_within[0.3]
    assert isinstance(info.value, tolalloc.TolallocError) and isinstance(info.value, KeyError)
    with pytest.raises(KeyError, match=r"simulated radii: 0.002 rad \(0.1146 deg\).*angle_radius_rad=\[0.002, 0.01\]"):
        sim.mc.p_within_angle[0.01]
    with pytest.raises(RadiusNotSimulated, match=r"radius '0.25' \(expected a number in mm\)"):
        sim.mc.p_within["0.25"]
    with pytest.raises(RadiusNotSimulated, match="simulated radii: 0.25 mm, 25 mm"):
        sim.mc.p_estimates[1.0]
    assert sim.mc.p_within[0.1 + 0.15] is sim.mc.p_within[0.25]  # equal up to rounding: the simulated radius
    with pytest.raises(RadiusNotSimulated):
        pickle.loads(pickle.dumps(sim.mc)).p_within_angle[0.01]
    more = tolalloc.simulate_errors("tool_changer", 300, seed=1, radius_mm=[0.25, 25.0, 0.3])
    np.testing.assert_array_equal(more.mc.p_within[25.0], sim.mc.p_within[25.0])  # as the message says


def test_probability_frame_reads_every_probability_of_the_result():
    sim = tolalloc.simulate_errors("tool_changer", 300, seed=3, poses="working", radius_mm=[20.0, 30.0],
                                   angle_radius_deg=[0.1, 0.5])
    frame = sim.probability_frame()
    P = sim.mc.q.shape[0]
    assert list(frame.columns) == ["pose", "error", "radius_mm", "radius_deg", "p", "ci_low", "ci_high"]
    assert len(frame) == P * 4 and frame["pose"].tolist()[:P] == list(range(1, P + 1))
    for r in (20.0, 30.0):
        rows = frame[frame["radius_mm"] == r]
        assert (rows["error"] == "position").all() and rows["radius_deg"].isna().all()
        np.testing.assert_array_equal(rows[["p", "ci_low", "ci_high"]].to_numpy(), sim.mc.p_within[r])
    for d in (0.1, 0.5):
        rows = frame[np.isclose(frame["radius_deg"], d)]
        assert (rows["error"] == "rotation").all() and rows["radius_mm"].isna().all()
        np.testing.assert_array_equal(rows[["p", "ci_low", "ci_high"]].to_numpy(), sim.mc.p_within_angle[np.deg2rad(d)])
