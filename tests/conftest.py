"""Shared test fixtures: random serial chains, an independent Pinocchio model, finite differences.

``random_chain(rng, n_joints)`` is importable by any test module (``from conftest import random_chain``)
and also exposed as the fixture ``make_chain``.
"""

from __future__ import annotations

import os
import sys

# One BLAS thread per test process: the suite runs one pytest-xdist worker per core (pyproject's addopts), and
# BLAS threads on top of the workers only contend for the same cores. Set before numpy is imported (it reads them
# when it loads OpenBLAS); subprocesses of the tests inherit them.
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

# Compiled modules are cached inside the suite even where the environment forbids it (PYTHONDONTWRITEBYTECODE): both
# workers, the command-line subprocesses and the documentation's notebook kernels then compile the package and the
# rewritten test modules once instead of at every start.
sys.dont_write_bytecode = False
os.environ.pop("PYTHONDONTWRITEBYTECODE", None)

import numpy as np  # noqa: E402
import pytest
from hypothesis import HealthCheck, settings

from tolalloc.robot.lie import exp_so3, inv_transform, rotvec
from tolalloc.robot.model import Joint, Link, Robot


# Hypothesis profiles: "ci" (the default: derandomised, so every run of the suite tries the same examples) and
# "long" (TOLALLOC_HYPOTHESIS_PROFILE=long: fresh random examples, 10^4 per public call in the property tests, see
# tests/property_strategies.py). Tests that set their own max_examples keep them in both.
_QUIET = [HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much,
          HealthCheck.function_scoped_fixture]
settings.register_profile("ci", derandomize=True, deadline=None, database=None, suppress_health_check=_QUIET,
                          print_blob=True)
settings.register_profile("long", max_examples=10_000, deadline=None, suppress_health_check=_QUIET, print_blob=True)
# "deep" (TOLALLOC_HYPOTHESIS_PROFILE=deep): fresh random examples, the deep counts of the method tests (issue 46)
settings.register_profile("deep", deadline=None, suppress_health_check=_QUIET, print_blob=True, database=None)
settings.load_profile(os.environ.get("TOLALLOC_HYPOTHESIS_PROFILE", "ci"))


def random_unit(rng: np.random.Generator) -> np.ndarray:
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    return exp_so3(random_unit(rng) * rng.uniform(0, np.pi))


def random_chain(rng: np.random.Generator, n_joints: int, *, p_prismatic: float = 0.3, name: str = "random") -> Robot:
    """A random serial chain of ``n_joints`` joints (mixed revolute / prismatic, random axes and offsets).

    Between joints there are 0-2 links of random direction and length 0-600 mm (a zero link count
    makes two joints share a point); the tool has a random offset and orientation. Limits are wide
    (revolute +-2 pi, prismatic +-1000 mm) so random configurations are valid.
    """
    chain = []
    k_link = 0
    for j in range(n_joints):
        for _ in range(int(rng.integers(0, 3)) if j else 1):
            k_link += 1
            chain.append(Link(f"l{k_link}", random_unit(rng) * rng.uniform(10.0, 600.0)))
        prismatic = rng.uniform() < p_prismatic
        if prismatic:
            chain.append(Joint(f"j{j + 1}", "prismatic", random_unit(rng), -1000.0, 1000.0, 0.0))
        else:
            chain.append(Joint(f"j{j + 1}", "revolute", random_unit(rng), -2 * np.pi, 2 * np.pi, 0.0))
    if rng.uniform() < 0.7:
        k_link += 1
        chain.append(Link(f"l{k_link}", random_unit(rng) * rng.uniform(10.0, 300.0)))
    return Robot(name, tuple(chain), tool_offset_mm=rng.normal(scale=50.0, size=3),
                 tool_rotation=random_rotation(rng))


def random_q(rng: np.random.Generator, robot: Robot, size=None) -> np.ndarray:
    """Random joint values [rad, mm] inside the limits (revolute +-pi, prismatic +-300 mm)."""
    shape = (robot.n_joints,) if size is None else (size, robot.n_joints)
    rev = rng.uniform(-np.pi, np.pi, shape)
    pri = rng.uniform(-300.0, 300.0, shape)
    return np.where(robot.revolute_mask, rev, pri)


def pinocchio_model(robot: Robot, rng: np.random.Generator | None = None):
    """Build an independent Pinocchio model of ``robot`` (metres), with a frame ``tool``.

    Joint frames are placed at the joint points with (optionally random) orientations, so the joint
    axes are expressed in rotated local frames (JointModelRevoluteUnaligned / PrismaticUnaligned).
    Returns ``(model, tool_frame_id)``. Pinocchio joint values: rad and m (prismatic mm / 1000).
    """
    import pinocchio as pin

    model = pin.Model()
    parent = 0
    R_prev, p_prev = np.eye(3), np.zeros(3)
    for j, joint in enumerate(robot.joints):
        R_j = random_rotation(rng) if rng is not None else np.eye(3)
        p_j = robot.joint_points_mm[j] / 1000.0
        placement = pin.SE3(R_prev.T @ R_j, R_prev.T @ (p_j - p_prev))
        axis_local = R_j.T @ joint.axis
        jm = (pin.JointModelRevoluteUnaligned(*axis_local) if joint.is_revolute
              else pin.JointModelPrismaticUnaligned(*axis_local))
        parent = model.addJoint(parent, jm, placement, joint.name)
        R_prev, p_prev = R_j, p_j
    M = robot.home
    tool = pin.SE3(R_prev.T @ M[:3, :3], R_prev.T @ (M[:3, 3] / 1000.0 - p_prev))
    fid = model.addFrame(pin.Frame("tool", parent, tool, pin.FrameType.OP_FRAME))
    return model, fid


def to_pin_q(robot: Robot, q: np.ndarray) -> np.ndarray:
    """Joint values [rad, mm] -> Pinocchio's [rad, m]."""
    return np.where(robot.revolute_mask, q, q / 1000.0)


def pin_jacobian_to_ours(robot: Robot, J_pin: np.ndarray) -> np.ndarray:
    """Pinocchio frame Jacobian (rows (v [m], w), columns per rad or per m) -> ours (rows (w, v [mm]), per rad or mm)."""
    col = np.where(robot.revolute_mask, 1.0, 1e-3)
    return np.vstack([J_pin[3:], 1000.0 * J_pin[:3]]) * col


def twist_fd(fk, q: np.ndarray, h: float = 1e-6, frame: str = "space") -> np.ndarray:
    """Central finite-difference Jacobian of ``fk`` (q -> 4x4), columns ``(omega, v)``.

    ``space``: the twist ``[V] = dT T^-1``; ``body``: ``T^-1 dT``.
    """
    n = q.shape[-1]
    J = np.zeros((6, n))
    for k in range(n):
        e = np.zeros(n)
        e[k] = h
        Tp, Tm = fk(q + e), fk(q - e)
        T = fk(q)
        dT = (Tp - Tm) / (2 * h)
        X = dT @ inv_transform(T) if frame == "space" else inv_transform(T) @ dT
        J[:3, k] = [X[2, 1], X[0, 2], X[1, 0]]
        J[3:, k] = X[:3, 3]
    return J


def pose_error(T1: np.ndarray, T2: np.ndarray) -> tuple[float, float]:
    """(position difference [same unit], rotation angle [rad]) between two poses."""
    dp = float(np.linalg.norm(T1[:3, 3] - T2[:3, 3]))
    dr = float(np.linalg.norm(rotvec(T1[:3, :3].T @ T2[:3, :3])))
    return dp, dr


@pytest.fixture
def make_chain():
    """Fixture returning :func:`random_chain`."""
    return random_chain


@pytest.fixture
def rng():
    return np.random.default_rng(20240611)


def skew_robot():
    """A robot with non-axis-aligned joints (exercises the generic rotation branch of the fast paths)."""
    from tolalloc.robot.model import Joint, Link, Robot

    a = np.array([0.0, 0.6, 0.8])
    b = np.array([1.0, 1.0, 1.0]) / np.sqrt(3)
    chain = (Link("l1", np.array([0.0, 0.0, 300.0])), Joint("j1", "revolute", a),
             Link("l2", np.array([100.0, 400.0, 50.0])), Joint("j2", "revolute", b),
             Link("l3", np.array([0.0, 200.0, 0.0])), Joint("j3", "prismatic", b, -100.0, 100.0),
             Link("l4", np.array([50.0, 100.0, 0.0])))
    return Robot("skew", chain)


_FIRST_TEST_SEEN = []


@pytest.fixture(autouse=True)
def warm_numba_kernels(request, tmp_path_factory):
    """Compile (or load from numba's on-disk cache) the numba kernels once per test run.

    See :func:`tolalloc.montecarlo.engines.warmup.warm_numba_kernels` (Monte Carlo kernel via a tiny ``run_mc``,
    Jacobian kernels on 64 poses). The first compile of a fresh environment (about 7 s) is paid here instead of
    inside whichever test happens to run first; ``benchmarks/bench_montecarlo.py`` reports first-compile and
    cached-load times. Under pytest-xdist one worker compiles: the first to create a marker file in the run's shared
    temporary folder, skipping the worker whose first file is the documentation build (it runs Sphinx, no kernel,
    for longer than the compile takes). The others go on with their tests and load the kernels from numba's on-disk
    cache when they first need one.
    Decided at a process's first test (a function-scoped fixture, to see which test that is); a no-op after it.
    """
    if _FIRST_TEST_SEEN:
        return
    _FIRST_TEST_SEEN.append(request.node.nodeid)
    if request.node.path.name == FIRST_FILE:
        return
    if "PYTEST_XDIST_WORKER" in os.environ:
        marker = tmp_path_factory.getbasetemp().parent / "numba_warm_up"
        try:
            os.close(os.open(marker, os.O_CREAT | os.O_EXCL))
        except FileExistsError:
            return
    from tolalloc.montecarlo.engines.warmup import warm_numba_kernels as warm

    if warm():
        _warm_other_kernels()


def _warm_other_kernels() -> None:
    """The numba kernels outside the Monte Carlo warm-up, compiled here once for the run rather than by both workers
    at once: the error model's perturbed-chain walk and the diagnosis's point kinematics."""
    import tolalloc
    from tolalloc.diagnose.scale import point_kinematics
    from tolalloc.errormodel import build_error_model

    robot = tolalloc.load_robot("tool_changer")
    model = build_error_model(robot, "table2")
    model.perturbed_chain(np.zeros((2, len(model.names))), engine="numba")
    ur10 = tolalloc.load_robot("ur10")  # unit screws: the compiled path
    point_kinematics(ur10.screws, ur10.home, np.zeros((2, ur10.n_joints)), np.zeros(3))


# The documentation build: the longest single test, and one that needs no numba kernel (see warm_numba_kernels).
FIRST_FILE = "test_docs.py"


def pytest_collection(session):
    """On odd-numbered pytest-xdist workers, import the test modules in reverse order before collecting.

    Every worker imports every test module at collection, and on a fresh checkout each import first rewrites the
    module's assertions (about 4 s for the whole suite). Walking the list from the other end, the second worker
    rewrites the half the first has not reached and loads the rest from the rewritten modules the first has cached
    (written atomically), so the rewriting is shared instead of done twice. A module that fails to import here is
    left to pytest's own collection, which reports it.
    """
    worker = os.environ.get("PYTEST_XDIST_WORKER", "")
    if not worker.startswith("gw") or int(worker[2:] or 0) % 2 == 0:
        return None
    import importlib
    from pathlib import Path

    for path in sorted(Path(__file__).parent.glob("test_*.py"), reverse=True):
        try:
            importlib.import_module(path.stem)
        except (Exception, pytest.skip.Exception):
            sys.modules.pop(path.stem, None)
    return None


def pytest_collection_modifyitems(config, items):
    """The documentation build's file first, then files with a test marked ``slow`` (stable otherwise):
    pytest-xdist hands out whole files in this order, alternating between workers, so the long files start early
    and the workers finish together instead of one running the last long file alone. The order holds because
    pyproject's addopts pass ``--no-loadscope-reorder``: without it pytest-xdist (>= 3.5) hands out the files with
    the most tests first and this order is lost."""
    slow = {item.path for item in items if item.get_closest_marker("slow")}
    items.sort(key=lambda item: (item.path.name != FIRST_FILE, item.path not in slow))


@pytest.fixture(scope="module")
def plan_path(tmp_path_factory):
    """A 12-pose calibration plan of the tool_changer at seeded random poses within its limits (a CSV path)."""
    import tolalloc
    from tolalloc.calibration import make_plan, write_plan

    tc = tolalloc.load_robot("tool_changer")
    rng = np.random.default_rng(0)
    path = tmp_path_factory.mktemp("plan") / "plan.csv"
    write_plan(make_plan(tc, tc.lower + (tc.upper - tc.lower) * rng.random((12, 6))), tc, path)
    return path


# ---- no test writes into the checkout: new top-level entries after the run fail it (xdist: the controller checks) ----
_CHECKOUT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_MAY_APPEAR = {".pytest_cache", ".hypothesis", "build", "__pycache__", ".venv", "tolalloc.egg-info", "dist", ".coverage"}


def pytest_sessionstart(session):
    if not hasattr(session.config, "workerinput"):
        session.config._entries_before = set(os.listdir(_CHECKOUT))


def pytest_sessionfinish(session, exitstatus):
    before = getattr(session.config, "_entries_before", None)
    if before is None:
        return
    new = sorted(set(os.listdir(_CHECKOUT)) - before - _MAY_APPEAR)
    if new:
        print(f"\nerror: the tests wrote into the checkout {_CHECKOUT}: {', '.join(new)} (write into tmp_path)")
        session.exitstatus = pytest.ExitCode.TESTS_FAILED
