"""Compile (or load from numba's on-disk cache) every numba kernel once: Monte Carlo and Jacobian stacks.

Used by the test session (``tests/conftest.py``) so the first compile of a fresh environment is not charged to
whichever test runs first, and by ``benchmarks/bench_montecarlo.py`` to time the first compile and the cached load.
"""

from __future__ import annotations

import numpy as np

__all__ = ["warm_numba_kernels"]


def warm_numba_kernels() -> bool:
    """Run each numba kernel once on tiny inputs; return ``False`` (doing nothing) when numba is unavailable.

    Runs ``run_mc`` with ``engine="numba"`` on the ``tool_changer`` ``table2`` model at 2 poses and 200 samples,
    once plain and once with radii, angle radii, a histogram and kept samples (the specialisations in use), then
    :func:`tolalloc.robot.kinematics.space_jacobian` and :meth:`ErrorModel.jacobian` on 64 poses with
    ``engine="numba"``.
    """
    from tolalloc.engine import NUMBA_AVAILABLE

    if not NUMBA_AVAILABLE:
        return False
    from tolalloc.errormodel import build_error_model
    from tolalloc.montecarlo.run import run_mc
    from tolalloc.robot.io.load import load_robot
    from tolalloc.robot.kinematics import space_jacobian

    robot = load_robot("tool_changer")
    model = build_error_model(robot, "table2")
    q = robot.poses("working")[:2]
    run_mc(model, q, 200, seed=0, engine="numba", progress=False)
    run_mc(model, q, 200, seed=0, engine="numba", radii_mm=(0.1,), angle_radii_rad=(0.01,), hist_bins=4,
           keep_samples=10, progress=False)
    Q = np.random.default_rng(0).uniform(-1.0, 1.0, (64, robot.n_joints))
    space_jacobian(robot.screws, Q, engine="numba")
    model.jacobian(Q, engine="numba")
    return True
