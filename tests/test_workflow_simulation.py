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
