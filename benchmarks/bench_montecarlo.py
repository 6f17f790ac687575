"""Monte Carlo throughput and memory (not part of the test suite).

    python benchmarks/bench_montecarlo.py [--n 10000000]

Measures, in one run on this machine: run_mc (sampling + exact chains + statistics) samples/s and peak RSS,
the fast exact chain alone, the generic perturbed_chain + fk_poe path, Pinocchio's forwardKinematics in a
Python loop and modern_robotics' FKinSpace in a Python loop (per perturbed sample), and prints ratios.
Goal of issue 3 on 2 cores: >= 3 M samples/s, >= 10x Pinocchio-in-a-loop, 10^7 samples under 1 GB.
"""

from __future__ import annotations

import argparse
import os
import resource
import time

import numpy as np

from tolalloc import load_robot
from tolalloc.errors import build_error_model
from tolalloc.montecarlo import FastChain, generic_pose_errors, run_mc, sample_values


def rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def timeit(f, reps=3):
    best = np.inf
    for _ in range(reps):
        t = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - t)
    return best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=10**7)
    ap.add_argument("--loop-n", type=int, default=20000, help="samples for the Python-loop peers")
    a = ap.parse_args()
    robot = load_robot("tool_changer")
    model = build_error_model(robot, "table2")
    q = robot.q_nominal
    print(f"tool_changer, {len(model.params)} error parameters, cpus={os.cpu_count()}")

    rss0 = rss_mb()
    t = time.perf_counter()
    res = run_mc(model, q, a.n, seed=0, radii_mm=(0.25,))
    dt = time.perf_counter() - t
    mc_rate = a.n / dt
    print(f"run_mc n={a.n}: {dt:.2f} s, {mc_rate / 1e6:.2f} M samples/s; peak RSS {rss_mb():.0f} MB "
          f"(before {rss0:.0f} MB); std_mm={np.round(res.std_mm[0], 4)}")

    m = 2**16
    V = sample_values(model, m, np.random.default_rng(0))
    chain = FastChain(model)
    chain_rate = m / timeit(lambda: chain.pose(q, V, transposed=True))
    samp_rate = m / timeit(lambda: sample_values(model, m, np.random.default_rng(0)))
    Vn = np.ascontiguousarray(V[:, :4096].T)
    gen_rate = 4096 / timeit(lambda: generic_pose_errors(model, q, Vn), 1)
    print(f"fast chain only (1 thread): {chain_rate / 1e6:.2f} M/s; sampling only: {samp_rate / 1e6:.2f} M/s; "
          f"generic perturbed_chain+fk_poe: {gen_rate / 1e6:.3f} M/s")

    L = a.loop_n
    Vl = np.ascontiguousarray(V[:, :L].T)
    peers = {}
    try:
        import modern_robotics as mr

        screws, home, dq = model.perturbed_chain(Vl)  # built outside the timed loop (favours the peer)
        Sl = np.ascontiguousarray(np.swapaxes(screws, 1, 2))
        qq = q + dq
        t = time.perf_counter()
        for i in range(L):
            mr.FKinSpace(home[i], Sl[i], qq[i])
        peers["modern_robotics FKinSpace loop"] = L / (time.perf_counter() - t)
    except ImportError as exc:
        print(f"modern_robotics not available: {exc}")
    try:
        import pinocchio as pin

        pm = pin.Model()
        spec = [((0, 0, 315), pin.JointModelRZ()), ((0, 0, 210), pin.JointModelRX()), ((0, 796, 0), pin.JointModelRX()),
                ((0, 560, 0), pin.JointModelPY()), ((0, 240, 0), pin.JointModelRX()), ((0, 165, 0), pin.JointModelRZ())]
        parent = 0
        for j, (t_, jm) in enumerate(spec):
            parent = pm.addJoint(parent, jm, pin.SE3(np.eye(3), np.array(t_, float)), f"j{j + 1}")
        pdata = pm.createData()
        pin.forwardKinematics(pm, pdata, q)
        assert np.allclose(pdata.oMi[6].translation, robot.fk(q)[:3, 3]), "pinocchio model mismatch"
        base = [pm.jointPlacements[i + 1].translation.copy() for i in range(6)]
        dirs = [b / np.linalg.norm(b) for b in base]
        il = [model.index(f"dl{i}") for i in range(1, 7)]
        idq = [model.index(nm) for nm in ("dth1", "dth2", "dth3", "dd4", "dth5", "dth6")]
        t = time.perf_counter()
        for i in range(L):  # links and drives only (deflections omitted: a lower bound on the peer's cost)
            for j in range(6):
                pm.jointPlacements[j + 1].translation = base[j] + Vl[i, il[j]] * dirs[j]
            pin.forwardKinematics(pm, pdata, q + Vl[i, idq])
            pdata.oMi[6].translation
        peers["pinocchio forwardKinematics loop (links+drives)"] = L / (time.perf_counter() - t)
    except ImportError as exc:
        print(f"pinocchio not available: {exc}")
    for name, rate in peers.items():
        print(f"{name}: {rate / 1e3:.1f} k samples/s; run_mc is {mc_rate / rate:.0f}x faster")
    print(f"goals: >= 3 M/s -> {'met' if mc_rate >= 3e6 else 'NOT met'} ({mc_rate / 1e6:.2f} M/s); "
          f"peak RSS < 1 GB -> {'met' if rss_mb() < 1024 else 'NOT met'}")


if __name__ == "__main__":
    main()
