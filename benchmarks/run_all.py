"""All benchmarks in one run, with ratios against peers measured in the same run.

    python benchmarks/run_all.py [--quick] [--big-n 100000000]

Rows: Monte Carlo throughput with the compiled kernel (numba) and the numpy path, and the verification
workload (12 poses) in a fresh process per engine (run_mc vs Pinocchio / modern_robotics loops and roboticstoolbox-python's
batched fkine), a streamed 10^8-sample run (time, peak RSS), the error-Jacobian stack for 1,000 poses,
allocation for 1, 20 and 200 poses with each solver (and SciPy SLSQP as a peer), and P(|x| < r) against
SciPy-integrated Imhof and a Monte Carlo estimate. Prints a table and writes reports/benchmarks/
benchmarks.md and benchmarks.csv with the machine it ran on. The machine may be shared: ratios measured
in the same run are the comparable numbers; the load average is recorded.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_linear import timeit as median_time  # noqa: E402
from bench_montecarlo import measure_run_mc, peers, pinocchio_model  # noqa: E402

from tolalloc import load_robot  # noqa: E402
from tolalloc.errormodel import build_error_model  # noqa: E402
from tolalloc.linear.covariance import linear_map  # noqa: E402
from tolalloc.linear.probability import p_within_radius  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
ROWS: list[dict] = []


def row(section, case, ours, unit, peer="", peer_value=np.nan, note=""):
    """``ratio`` is always 'how many times better ours is' (rates: ours/peer; times: peer/ours)."""
    ratio = np.nan
    if np.isfinite(peer_value) and peer_value > 0:
        ratio = ours / peer_value if unit.endswith("/s") else peer_value / ours
    ROWS.append({"section": section, "case": case, "ours": ours, "unit": unit, "peer": peer,
                 "peer_value": peer_value, "ratio_ours_better": ratio, "note": note})
    r = f"{ratio:9.1f}x" if np.isfinite(ratio) else "          "
    pv = f"{peer_value:12.4g}" if np.isfinite(peer_value) else " " * 12
    print(f"{section:12s} {case:44s} {ours:12.4g} {unit:10s} {pv} {r}  {peer} {note}", flush=True)


def machine() -> dict:
    cpu = platform.processor()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    import scipy

    try:
        import numba

        nb = numba.__version__
    except ImportError:
        nb = "not installed (numpy path only)"
    return {"numba": nb, "date": datetime.datetime.now().isoformat(timespec="seconds"), "cpu": cpu,
            "cores_usable": len(os.sched_getaffinity(0)), "cores_total": os.cpu_count(),
            "load_avg_1_5_15": " ".join(f"{x:.2f}" for x in os.getloadavg()),
            "python": platform.python_version(), "numpy": np.__version__, "scipy": scipy.__version__,
            "platform": platform.platform()}


# ----------------------------------------------------------------- Monte Carlo
def bench_mc(model, q, n, loop_n):
    from tolalloc.engine import NUMBA_AVAILABLE

    kw = dict(radii_mm=(0.15, 0.25), angle_radii_rad=(0.002,))
    engines = (["numba"] if NUMBA_AVAILABLE else []) + ["numpy"]
    rates = {}
    for engine in engines:
        r2 = measure_run_mc(model, q, n, n_jobs=2, engine=engine, **kw)
        r1 = measure_run_mc(model, q, n // 2, n_jobs=1, reps=1, engine=engine, **kw)
        rates[engine] = r2
        row("monte_carlo", f"run_mc {engine}, 2 threads (wall clock)", r2["wall_rate"], "samples/s",
            note=f"22 params, n={n}; goal >= 3e6")
        row("monte_carlo", f"run_mc {engine}, per CPU-second (2 threads)", r2["cpu_rate"], "samples/s",
            note=f"x2 cores = {2 * r2['cpu_rate']:.3g}/s if both cores were free")
        row("monte_carlo", f"run_mc {engine}, 1 thread (wall clock)", r1["wall_rate"], "samples/s")
    if len(engines) == 2:
        row("monte_carlo", "run_mc numba vs numpy path, 2 threads", rates["numba"]["wall_rate"], "samples/s",
            "numpy path (same draws, same statistics)", rates["numpy"]["wall_rate"])
    best = rates[engines[0]]
    for name, rate in peers(model, q, loop_n).items():
        if isinstance(rate, str):
            row("monte_carlo", "peer unavailable", np.nan, "samples/s", name, note=rate)
        else:
            row("monte_carlo", f"run_mc {engines[0]} 2 threads vs peer (per sample)", best["wall_rate"], "samples/s",
                name, rate)


def bench_verify_workload(n, engines):
    """The allocation's verification workload (12 poses x n samples) in a fresh process per engine:
    wall time including imports and loading the compiled kernel from numba's on-disk cache."""
    times = {}
    for engine in engines:
        code = ("import time; t0 = time.perf_counter()\n"
                "from tolalloc import load_robot\nfrom tolalloc.errormodel import build_error_model\n"
                "from tolalloc.montecarlo.run import run_mc\n"
                "r = load_robot('tool_changer'); m = build_error_model(r, 'table2')\n"
                "q = r.poses('working')[:12]\n"
                f"res = run_mc(m, q, {n}, seed=0, radii_mm=(0.25,), engine='{engine}')\n"
                "print(time.perf_counter() - t0)\n")
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
        times[engine] = float(out.stdout.strip().splitlines()[-1])
    for engine in engines:
        peer = ("numpy path, same workload", times["numpy"]) if engine != "numpy" else ("", np.nan)
        row("monte_carlo", f"12 poses x {n:.0e} samples, {engine} (fresh process)", times[engine], "s", *peer,
            note="imports + cached kernel load + run")


def bench_big(n):
    """A streamed run in a fresh process: wall time and peak RSS."""
    code = (
        "import json, resource, time, numpy as np\n"
        "from tolalloc import load_robot\nfrom tolalloc.errormodel import build_error_model\n"
        "from tolalloc.montecarlo.run import run_mc\n"
        "r = load_robot('tool_changer'); m = build_error_model(r, 'table2')\n"
        "t = time.perf_counter()\n"
        f"res = run_mc(m, r.q_nominal, {n}, seed=0, radii_mm=(0.15, 0.25), angle_radii_rad=(0.002,), hist_bins=100, "
        "keep_samples=20000)\n"
        "print(json.dumps({'s': time.perf_counter() - t, 'rss_mb': resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,"
        " 'std_mm': res.std_mm[0].tolist(), 'outside': res.hist.outside[0].tolist()}))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    d = json.loads(out.stdout.strip().splitlines()[-1])
    row("streaming", f"run_mc n={n:.0e} + 3 histograms 100x100", n / d["s"], "samples/s",
        note=f"{d['s']:.0f} s, peak RSS {d['rss_mb']:.0f} MB (goal < 1024 MB); std_mm {np.round(d['std_mm'], 4).tolist()}")
    return d


# ----------------------------------------------------------------- Jacobians
def _pin_error_jacobian(pm, pdata, robot, model, q):
    """The same 6xK error Jacobian with Pinocchio, pose by pose: forward kinematics, then each error screw
    moved to the current configuration by the SE3 action of ``P_site = oMi[site] oMi_home[site]^-1``."""
    import pinocchio as pin

    pin.forwardKinematics(pm, pdata, np.zeros(robot.n_joints))
    home_inv = [pdata.oMi[i].inverse() for i in range(robot.n_joints + 1)]
    twists = [pin.Motion(p.twist[3:], p.twist[:3]) for p in model.params]
    sites = [p.site for p in model.params]
    undo = [p.undo_site for p in model.params]
    out = np.empty((len(q), 6, len(twists)))
    tool = robot.home[:3, 3]
    for i, qi in enumerate(q):
        pin.forwardKinematics(pm, pdata, qi)
        P = [pdata.oMi[j] * home_inv[j] for j in range(robot.n_joints + 1)]
        p_tool = P[-1].act(tool)
        for k, tw in enumerate(twists):
            m = P[sites[k]].act(tw)
            w, v = m.angular.copy(), m.linear.copy()
            if undo[k] is not None:
                mu = P[undo[k]].act(tw)
                w, v = w - mu.angular, v - mu.linear
            out[i, :3, k] = v - np.cross(p_tool, w)
            out[i, 3:, k] = w
    return out


def bench_jacobian(robot, model):
    """Jacobian stacks for 1,000 poses: default engine (numba when installed), the numpy path, Pinocchio loops."""
    from tolalloc.engine import resolve_engine

    q = np.random.default_rng(0).uniform(robot.lower, robot.upper, (1000, robot.n_joints))
    eng = resolve_engine(None)
    robot.space_jacobian_internal(q), model.jacobian(q)  # first call: numba import / compile or disk-cache load
    t_jac = median_time(lambda: model.jacobian(q))
    t_jac_np = median_time(lambda: model.jacobian(q, engine="numpy"))
    t_lin = median_time(lambda: linear_map(model, q), repeat=5)
    t_loop = median_time(lambda: [model.jacobian(qi) for qi in q[:100]], repeat=3) * 10
    K = len(model.params)
    row("jacobian", f"ErrorModel.jacobian, 1000 poses (6x{K}) [{eng}]", t_jac, "s", "per-pose Python loop of the same", t_loop)
    if eng == "numba":
        err = float(np.max(np.abs(model.jacobian(q) - model.jacobian(q, engine="numpy"))))
        row("jacobian", f"ErrorModel.jacobian, 1000 poses (6x{K}) [numba]", t_jac, "s", "ours, numpy path", t_jac_np,
            note=f"max |difference| {err:.1e}")
    t_sj = median_time(lambda: robot.space_jacobian_internal(q))
    t_sj_np = median_time(lambda: robot.space_jacobian_internal(q, engine="numpy"))
    try:
        import pinocchio as pin

        pm, pdata = pinocchio_model(robot)

        def pin_loop():
            for qi in q:
                pin.computeJointJacobians(pm, pdata, qi)
                pin.getJointJacobian(pm, pdata, robot.n_joints, pin.ReferenceFrame.WORLD)

        t_pin = median_time(pin_loop, repeat=3)
        row("jacobian", f"space Jacobian stack, 1000 poses (6x6) [{eng}]", t_sj, "s",
            "pinocchio computeJointJacobians loop (C++ per pose)", t_pin)
        row("jacobian", "space Jacobian stack, 1000 poses (6x6) [numpy]", t_sj_np, "s",
            "pinocchio computeJointJacobians loop (C++ per pose)", t_pin)
        J_pin = _pin_error_jacobian(pm, pdata, robot, model, q[:50])
        err = float(np.max(np.abs(J_pin - model.jacobian(q[:50]))))
        t_pin_err = median_time(lambda: _pin_error_jacobian(pm, pdata, robot, model, q[:100]), repeat=3) * 10
        row("jacobian", f"ErrorModel.jacobian, 1000 poses (6x{K}) [{eng}]", t_jac, "s",
            "pinocchio forwardKinematics + SE3 action of each error screw, loop", t_pin_err,
            note=f"same quantity: max |difference| {err:.1e}")
        row("jacobian", f"ErrorModel.jacobian, 1000 poses (6x{K}) [numpy]", t_jac_np, "s",
            "pinocchio forwardKinematics + SE3 action of each error screw, loop", t_pin_err)
    except ImportError as exc:
        row("jacobian", f"space Jacobian stack, 1000 poses (6x6) [{eng}]", t_sj, "s", "ours, numpy path", t_sj_np)
        row("jacobian", "peer unavailable", np.nan, "s", "pinocchio", note=str(exc))
    row("jacobian", "linear_map (Jacobian + covariances), 1000", t_lin, "s")


# ----------------------------------------------------------------- allocation
def _slsqp(problem):
    """SciPy SLSQP on the exact problem (finite-difference gradients), from the tightest limits."""
    from scipy.optimize import minimize

    a = problem.alloc
    b = problem.blocks[0]
    models = [problem.costs.models[k] for k in a]
    t_ref = problem.t_ref[a]

    def cost(u):
        t = t_ref * np.sqrt(np.maximum(u, 1e-300))
        return float(sum(m.cost(ti) for m, ti in zip(models, t)))

    def cons(u):
        cov = np.einsum("pkij,k->pij", b["A"], u) + b["C0"]
        return p_within_radius(cov, b["radius"]) - b["prob"]

    lo, hi = problem.u_min, problem.u_max
    res = minimize(cost, lo.copy(), method="SLSQP", bounds=list(zip(lo, hi)),
                   constraints=[{"type": "ineq", "fun": cons}], options={"maxiter": 300, "ftol": 1e-10})
    return res, cost(res.x), bool(np.all(cons(res.x) > -1e-5))


def bench_allocation(robot, model, sizes):
    from tolalloc.allocate import allocate, build_problem

    rng = np.random.default_rng(0)
    for P in sizes:
        q = robot.q_nominal[None] if P == 1 else rng.uniform(robot.lower, robot.upper, (P, robot.n_joints))
        problem = build_problem(model, q, radius_mm=0.25, prob=0.95)
        t0 = time.perf_counter()
        allocate(problem, solver="exact", snap=False)  # first call: builds the CasADi/IPOPT solver for this size
        t_first = time.perf_counter() - t0
        times, costs = {}, {}
        for solver in ("certified", "exact"):
            t0 = time.perf_counter()
            res = allocate(problem, solver=solver, snap=False)
            times[solver] = time.perf_counter() - t0
            costs[solver] = getattr(res.design, "cost", np.nan)
        t0 = time.perf_counter()
        sres, scost, sfeas = _slsqp(problem)
        t_s = time.perf_counter() - t0
        for solver in ("certified", "exact"):
            row("allocation", f"{P} poses, solver={solver}", times[solver], "s", "scipy SLSQP (exact constraint)", t_s,
                note=f"cost {costs[solver]:.4g} vs SLSQP {scost:.4g} ({'feasible' if sfeas else 'infeasible'}, "
                     f"{sres.message[:40]})" + (f"; first call incl. solver build {t_first:.2f} s" if solver == "exact" else ""))


# ----------------------------------------------------------------- probability
def _imhof(lam, r):
    """P(sum lam_j chi2_1 < r^2) by Imhof's integral (scipy.integrate.quad)."""
    from scipy.integrate import quad

    x = r * r

    def f(u):
        th = 0.5 * np.sum(np.arctan(lam * u)) - 0.5 * x * u
        rho = np.prod((1 + (lam * u) ** 2) ** 0.25)
        return np.sin(th) / (u * rho)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # quad's subdivision warnings on the oscillating tail
        v, _ = quad(f, 0, np.inf, limit=500, epsabs=1e-12)
    return 0.5 - v / np.pi


def bench_probability(robot, model, mc_n=100000):
    q = np.random.default_rng(1).uniform(robot.lower, robot.upper, (1000, robot.n_joints))
    cov = linear_map(model, q).cov_mm2
    r = 30.0
    t_ours = median_time(lambda: p_within_radius(cov, r), repeat=7)
    ours = p_within_radius(cov, r)
    m = 40
    lams = np.linalg.eigvalsh(cov[:m])
    t0 = time.perf_counter()
    imh = np.array([_imhof(l, r) for l in lams])
    t_imh = (time.perf_counter() - t0) / m * 1000
    rng = np.random.default_rng(2)
    t0 = time.perf_counter()
    mcp = np.array([np.mean(np.einsum("ij,nj->ni", np.linalg.cholesky(c), rng.standard_normal((mc_n, 3))) ** 2 @ np.ones(3)
                            < r * r) for c in cov[:m]])
    t_mc = (time.perf_counter() - t0) / m * 1000
    row("probability", "p_within_radius, 1000 covariances", t_ours, "s", "scipy quad Imhof (loop)", t_imh,
        note=f"max |ours - Imhof| = {np.max(np.abs(ours[:m] - imh)):.1e} on {m}")
    row("probability", "p_within_radius, 1000 covariances", t_ours, "s", f"Monte Carlo {mc_n:.0e} samples each", t_mc,
        note=f"max |ours - MC| = {np.max(np.abs(ours[:m] - mcp)):.1e} (MC std ~ {np.sqrt(0.25 / mc_n):.0e})")


def write(info, out_dir):
    out_dir.mkdir(parents=True, exist_ok=True)
    df = pd.DataFrame(ROWS)
    df.to_csv(out_dir / "benchmarks.csv", index=False)
    pd.DataFrame([info]).to_csv(out_dir / "machine.csv", index=False)
    lines = ["# Benchmarks", "", "Generated by `python benchmarks/run_all.py`; every ratio is measured in the same run.",
             "`ratio_ours_better` = ours/peer for rates (samples/s), peer/ours for times (s).", "", "## Machine", ""]
    lines += [f"- {k}: {v}" for k, v in info.items()]
    lines += ["", "The machine may be shared with other jobs (see the load average): absolute rates vary, ratios "
              "measured in the same run are the comparable numbers.", "", "## Results", "",
              df.to_markdown(index=False, floatfmt=".4g"), ""]
    (out_dir / "benchmarks.md").write_text("\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes (a smoke run)")
    ap.add_argument("--big-n", type=float, default=1e8, help="samples of the streamed run (0 to skip)")
    ap.add_argument("--out", default=str(ROOT / "reports" / "benchmarks"))
    a = ap.parse_args()
    info = machine()
    print(json.dumps(info, indent=1))
    robot = load_robot("tool_changer")
    model = build_error_model(robot, "table2")
    print(f"{'section':12s} {'case':44s} {'ours':>12s} {'unit':10s} {'peer value':>12s} {'ratio':>10s}  peer")
    bench_mc(model, robot.q_nominal, 2**18 if a.quick else 2**23, 2000 if a.quick else 20000)
    from tolalloc.engine import NUMBA_AVAILABLE

    bench_verify_workload(10**5 if a.quick else 10**6, (["numba"] if NUMBA_AVAILABLE else []) + ["numpy"])
    bench_jacobian(robot, model)
    bench_probability(robot, model, 20000 if a.quick else 100000)
    bench_allocation(robot, model, (1, 20) if a.quick else (1, 20, 200))
    if a.big_n > 0:
        bench_big(int(2**20 if a.quick else a.big_n))
    info["load_avg_at_end"] = " ".join(f"{x:.2f}" for x in os.getloadavg())
    write(info, Path(a.out))
    print(f"wrote {a.out}/benchmarks.md, benchmarks.csv, machine.csv")


if __name__ == "__main__":
    main()
