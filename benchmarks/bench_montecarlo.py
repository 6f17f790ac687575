"""Monte Carlo throughput and memory against peers (not part of the test suite).

    python benchmarks/bench_montecarlo.py [--n 4194304] [--loop-n 20000]

Measures, in one run on this machine: the numba kernels' first-compile and cached-load times, run_mc (sampling + exact chains + statistics) samples/s (wall clock
and per CPU-second) with the compiled kernel (numba, when installed) and the numpy path, and per perturbed
sample: Pinocchio's forwardKinematics in a Python loop,
modern_robotics' FKinSpace in a Python loop and roboticstoolbox-python's batched ETS.fkine, and prints
ratios. The functions are reused by ``benchmarks/run_all.py``.
"""

from __future__ import annotations

import argparse
import os
import resource
import time

import numpy as np

from tolalloc import load_robot
from tolalloc.errormodel import build_error_model
from tolalloc.montecarlo.run import run_mc, sample_values


def rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def timeit(f, reps=3):
    best = np.inf
    for _ in range(reps):
        t = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - t)
    return best


def measure_run_mc(model, q, n, n_jobs=None, reps=2, **kw) -> dict:
    """Best of ``reps`` runs (after a small warm-up run): wall-clock samples/s and samples per CPU-second."""
    run_mc(model, q, 1000, seed=0, n_jobs=n_jobs, **kw)  # JIT cache load / thread pools outside the timing
    best = None
    for _ in range(reps):
        c0, t0 = time.process_time(), time.perf_counter()
        run_mc(model, q, n, seed=0, n_jobs=n_jobs, **kw)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        if best is None or wall < best[0]:
            best = (wall, cpu)
    return {"wall_rate": n / best[0], "cpu_rate": n / best[1], "wall_s": best[0]}


def numba_compile_times() -> dict:
    """First-compile and cached-load time [s] of all numba kernels (Monte Carlo and Jacobians).

    Each is measured in a fresh Python subprocess running
    :func:`tolalloc.montecarlo.engines.warmup.warm_numba_kernels` with ``NUMBA_CACHE_DIR`` set to a new empty
    temporary directory (first compile), then again with the directory that run filled (cached load). Times are
    the wall clock of the warm-up call alone (imports excluded).
    """
    import subprocess
    import sys
    import tempfile

    code = ("import time; import tolalloc.montecarlo.run, tolalloc.robot.kinematics; "
            "from tolalloc.montecarlo.engines.warmup import warm_numba_kernels as w; "
            "t = time.perf_counter(); ok = w(); print(ok, time.perf_counter() - t)")
    out = {}
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        for key in ("first_compile_s", "cached_load_s"):
            res = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
            ok, sec = res.stdout.split()[-2:]
            if ok != "True":
                return {}
            out[key] = float(sec)
    return out


def pinocchio_model(robot):
    """A Pinocchio model of the tool_changer (checked against ``robot.fk_internal``)."""
    import pinocchio as pin

    pm = pin.Model()
    spec = [((0, 0, 315), pin.JointModelRZ()), ((0, 0, 210), pin.JointModelRX()), ((0, 796, 0), pin.JointModelRX()),
            ((0, 560, 0), pin.JointModelPY()), ((0, 240, 0), pin.JointModelRX()), ((0, 165, 0), pin.JointModelRZ())]
    parent = 0
    for j, (t_, jm) in enumerate(spec):
        parent = pm.addJoint(parent, jm, pin.SE3(np.eye(3), np.array(t_, float)), f"j{j + 1}")
    pdata = pm.createData()
    q = robot.q_nominal
    pin.forwardKinematics(pm, pdata, q)
    assert np.allclose(pdata.oMi[6].translation, robot.fk_internal(q)[:3, 3]), "pinocchio model mismatch"
    return pm, pdata


def peer_pinocchio_loop(model, q, Vl) -> float:
    """Samples/s of Pinocchio forwardKinematics per perturbed robot (links + drives: a lower bound on its cost)."""
    import pinocchio as pin

    pm, pdata = pinocchio_model(model.robot)
    base = [pm.jointPlacements[i + 1].translation.copy() for i in range(6)]
    dirs = [b / np.linalg.norm(b) for b in base]
    il = [model.index(f"dl{i}") for i in range(1, 7)]
    idq = [model.index(nm) for nm in ("dth1", "dth2", "dth3", "dd4", "dth5", "dth6")]
    L = len(Vl)
    t = time.perf_counter()
    for i in range(L):
        for j in range(6):
            pm.jointPlacements[j + 1].translation = base[j] + Vl[i, il[j]] * dirs[j]
        pin.forwardKinematics(pm, pdata, q + Vl[i, idq])
        pdata.oMi[6].translation
    return L / (time.perf_counter() - t)


def peer_modern_robotics_loop(model, q, Vl) -> float:
    """Samples/s of modern_robotics FKinSpace per perturbed chain (chains built outside the timed loop)."""
    import modern_robotics as mr

    screws, home, dq = model.perturbed_chain(Vl)
    Sl = np.ascontiguousarray(np.swapaxes(screws, 1, 2))
    qq = q + dq
    L = len(Vl)
    t = time.perf_counter()
    for i in range(L):
        mr.FKinSpace(home[i], Sl[i], qq[i])
    return L / (time.perf_counter() - t)


def peer_rtb_batched(model, q, Vl) -> float:
    """Samples/s of roboticstoolbox-python's batched ETS.fkine over the perturbed joint values.

    Nominal geometry (joint drive errors only): the toolbox evaluates a batch of joint vectors for one
    geometry, so this is a lower bound on its cost for perturbed robots.
    """
    from roboticstoolbox import ET

    ets = (ET.tz(315) * ET.Rz() * ET.tz(210) * ET.Rx() * ET.ty(796) * ET.Rx() * ET.ty(560) * ET.ty() * ET.ty(240)
           * ET.Rx() * ET.ty(165) * ET.Rz())
    assert np.allclose(np.asarray(ets.fkine(q).A)[:3, 3], model.robot.fk_internal(q)[:3, 3]), "rtb model mismatch"
    idq = [model.index(nm) for nm in ("dth1", "dth2", "dth3", "dd4", "dth5", "dth6")]
    Q = q + Vl[:, idq]
    t = time.perf_counter()
    ets.fkine(Q)
    return len(Vl) / (time.perf_counter() - t)


def peers(model, q, L=20000) -> dict:
    """name -> samples/s (or an error string when the peer is not available)."""
    Vl = np.ascontiguousarray(sample_values(model, L, np.random.default_rng(0)).T)
    out = {}
    for name, fn in [("pinocchio forwardKinematics, Python loop (links+drives only)", peer_pinocchio_loop),
                     ("modern_robotics FKinSpace, Python loop", peer_modern_robotics_loop),
                     ("roboticstoolbox ETS.fkine batched (drives only)", peer_rtb_batched)]:
        try:
            out[name] = fn(model, q, Vl)
        except Exception as exc:  # a peer that does not import or run is reported, not fatal
            out[name] = f"skipped: {type(exc).__name__}: {exc}"[:160]
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=2**22)
    ap.add_argument("--loop-n", type=int, default=20000, help="samples for the Python-loop peers")
    a = ap.parse_args()
    robot = load_robot("tool_changer")
    model = build_error_model(robot, "table2")
    q = robot.q_nominal
    print(f"tool_changer, {len(model.params)} error parameters, cpus={os.cpu_count()}, load={os.getloadavg()}")
    from tolalloc.engine import NUMBA_AVAILABLE

    ct = numba_compile_times()
    if ct:
        print(f"numba kernels (fresh subprocess, empty NUMBA_CACHE_DIR): first compile {ct['first_compile_s']:.1f} s, "
              f"cached load {ct['cached_load_s']:.2f} s")
    for engine in (["numba"] if NUMBA_AVAILABLE else []) + ["numpy"]:
        for jobs in (2, 1):
            r0 = measure_run_mc(model, q, a.n, n_jobs=jobs, radii_mm=(0.25,), engine=engine)
            print(f"run_mc engine={engine} n={a.n} threads={jobs}: {r0['wall_rate'] / 1e6:.2f} M samples/s wall, "
                  f"{r0['cpu_rate'] / 1e6:.2f} M per CPU-second; peak RSS {rss_mb():.0f} MB")
    r = measure_run_mc(model, q, a.n, radii_mm=(0.25,))
    for name, rate in peers(model, q, a.loop_n).items():
        if isinstance(rate, str):
            print(f"{name}: {rate}")
        else:
            print(f"{name}: {rate / 1e3:.1f} k samples/s; run_mc is {r['wall_rate'] / rate:.0f}x faster")


if __name__ == "__main__":
    main()
