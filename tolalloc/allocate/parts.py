"""Joint allocation of machining tolerances and bought parts over poses, payload and ambient temperature.

:func:`allocate_parts` finds the cheapest combination of standard machining values (ISO 286 grades, steps, classes)
and catalogue parts (a reducer grade, a bearing class, an encoder per slot of the robot file) that meets
``P(|dP| < r) >= p`` -- certified by the trace or the eigenvalue rule -- at every point of the active set, and grows
the active set by cutting planes until the search of the region (joints x payload x ambient,
:mod:`tolalloc.allocate.parts_region`) finds no point where the design's ratio exceeds ``1 + tol``:

1. the conditions are checked (a payload above the rating, a reducer option whose rated torque the gravity load
   exceeds anywhere in the region: one error naming the joint, the part and by how much);
2. every combination of the slots' signatures (:func:`~tolalloc.allocate.parts_problem.signature_combos`) and both
   rules are solved by the joint mixed-integer program (:mod:`tolalloc.allocate.parts_discrete`); the cheapest wins;
3. the region is searched for the winner's worst point, which joins the active set (step 2 again) while the ratio
   there exceeds ``1 + tol``;
4. with the parts fixed, the machining allocation of :func:`tolalloc.allocate.solve.allocate` (continuous certified
   and exact designs, and the exact standard design) runs on the final points.

``after="compensation"`` states the requirement after the compensation models (stiffness given the payload,
temperature, error tables): their residual share of every systematic part remains (the split of
:mod:`tolalloc.errormodel.parts`). The result's :meth:`PartsAllocation.parts_table` says per joint which part to buy
and how much of the variance it carries at the worst point.
"""

from __future__ import annotations

import time
import numpy as np

from tolalloc.allocate.catalogue import build_catalogue
from tolalloc.allocate.costs import CostSet, cost_set
from tolalloc.allocate.parts_discrete import PartsOutcome, parts_ratio, solve_parts_rule
from tolalloc.allocate.parts_problem import (Points, compensation_advice, option_blocks, parts_problem,
                                             signature_combos)
from tolalloc.allocate.parts_region import PointRatio, WorstPoint, worst_point
from tolalloc.allocate.parts_result import PartsAllocation, check_rated_options
from tolalloc.allocate.problem import Solver, make_design
from tolalloc.errormodel.parts import COMPENSATION_RESIDUAL, Conditions, residual_factors, with_parts
from tolalloc.exceptions import TolallocError

__all__ = ["allocate_parts", "PartsAllocation"]


def _solve_points(model, robot, points, cond, kw, first: int = 0) -> tuple:
    """The cheapest certified design over every signature combination and rule at ``points`` (combination ``first``
    first: the last round's winner gives the others a cost to beat, and their relaxations prune them)."""
    best, notes, tried = None, [], 0
    combos = signature_combos(robot)
    for c in [first] + [c for c in range(len(combos)) if c != first]:
        ob = option_blocks(robot, model, points, combos[c], cond, kw["after"], kw["residual"])
        try:
            pr = parts_problem(model, points, ob.fixed_cov, ob.bias_mm, radius_mm=kw["radius_mm"], prob=kw["prob"],
                               costs=kw["costs"], after=kw["after"])
        except TolallocError as exc:  # this combination's mean alone reaches the radius
            notes.append(str(exc))
            continue
        cat = build_catalogue(pr)
        for rule in kw["rules"]:
            out = solve_parts_rule(pr, cat, ob, rule, time_limit=kw["time_limit_s"],
                                   cutoff=None if best is None else best[0].cost)
            tried += 1
            if out.opt is not None and (best is None or out.cost < best[0].cost):
                best = (out, ob, pr, cat, c)
    return best, notes, tried


def _best_reachable(model, robot, points, cond, kw) -> str:
    """Why no design exists: the smallest certified ratio with every machining tolerance at its lower limit and the
    finest part of every slot, and the share of the variance the parts carry there."""
    from tolalloc.allocate.parts_discrete import _finest_parts, _scaled

    best = None
    for combo in signature_combos(robot):
        ob = option_blocks(robot, model, points, combo, cond, kw["after"], kw["residual"])
        pr = parts_problem(model, points, ob.fixed_cov, ob.bias_mm, radius_mm=kw["radius_mm"], prob=kw["prob"],
                           costs=kw["costs"], after=kw["after"])
        part = _finest_parts(ob, _scaled(pr, ob))
        for rule in kw["rules"]:
            r = float(parts_ratio(pr, ob, rule, pr.u_min, part)[0])
            if best is None or r < best[0]:
                best = (r, rule, ob, pr, part)
    r, rule, ob, pr, part = best
    parts_cov = ob.fixed_cov + ob.cov[part].sum(axis=0)
    total = pr.covariances(pr.t_from_u(pr.u_min)) / pr.scale[:, None, None] - ob.fixed_cov + parts_cov
    i = int(np.argmax(np.einsum("pii->p", total)))
    share = 100 * np.trace(parts_cov[i]) / np.trace(total[i])
    return (f"with every machining tolerance at its lower limit and the finest part of every slot the {rule} rule is "
            f"exceeded by a factor {r:.4g}; at point {i + 1} (payload {points.payload_kg[i]:g} kg, ambient "
            f"{points.ambient_c[i]:g} degC) the bought parts carry {share:.0f} % of the variance and their mean error is "
            f"{np.linalg.norm(ob.bias_mm[i]):.3g} mm: relax the radius, "
            + compensation_advice(kw["after"]) + ", or offer finer parts in the slots")


def _checked(model, region, q, conditions, costs, after, residual, rules, seed) -> tuple:
    """The checked conditions, the cost set and the first poses; refuses parts the load exceeds."""
    robot = model.robot
    cond = conditions.check(robot)
    residual_factors(after, residual)  # checks both
    bad = [r for r in rules if r not in ("trace", "lmi")]
    if bad or not rules:
        raise TolallocError(f"rules: expected 'trace' and/or 'lmi', got {rules!r}")
    cs = costs if isinstance(costs, CostSet) else cost_set(model, costs)
    if q is None:
        q = (0.5 * (region.q_min + region.q_max))[None] if region is not None else robot.poses(
            "working" if "working" in robot.pose_sets else None)
    q = np.atleast_2d(robot.check_q(q, "q"))
    check_rated_options(robot, model, region, q, cond, seed)
    return cond, cs, q


def allocate_parts(model, region=None, q=None, *, conditions: Conditions = Conditions(), radius_mm: float = 0.25,
                   prob: float = 0.95, costs: CostSet | dict | None = None, after: str = "none",
                   residual=COMPENSATION_RESIDUAL, rules=("trace", "lmi"), tol: float = 1e-3,
                   max_rounds: int = 12, seed: int = 0, n_seed: int = 256, n_starts: int = 3,
                   time_limit_s: float = 60.0, exact: bool = True) -> PartsAllocation:
    """Cheapest machining standard values and catalogue parts meeting the requirement (module docstring).

    Parameters
    ----------
    model : ErrorModel
        The machining error model; its robot's ``[components]`` slots are the part choices.
    region : Region, optional
        A joint box (:func:`tolalloc.allocate.region.box_region`) searched together with payload and ambient.
    q : array, shape (A, n) [rad, mm], optional
        Poses (without ``region``: the requirement holds at these and the condition corners; with it: the first
        active poses; default the box centre, or the robot's working pose set).
    conditions : Conditions
        Payload range [kg], ambient range [degC], reference temperature and duty cycle.
    radius_mm, prob : float
    costs : CostSet or dict, optional
        Machining costs (the costs file); parts are priced by the catalogue.
    after : {"none", "compensation"}
    residual : float or dict
        Share of every systematic part the compensation models leave (``after="compensation"``); a dict gives it
        per effect, 1 for the effects it omits (:func:`tolalloc.errormodel.parts.residual_factors`).
    rules : tuple of {"trace", "lmi"}
    tol : float
        Stop when the worst ratio found is at most ``1 + tol``.
    max_rounds : int
    seed, n_seed, n_starts : int
        Region search (:func:`tolalloc.allocate.parts_region.worst_point`).
    time_limit_s : float
        HiGHS time limit per program [s].
    exact : bool
        Step 4: the machining allocation with the parts fixed.
    """
    t0 = time.perf_counter(), time.process_time()
    robot = model.robot
    cond, cs, q = _checked(model, region, q, conditions, costs, after, residual, rules, seed)
    kw = dict(radius_mm=float(radius_mm), prob=float(prob), costs=cs, after=after, residual=residual,
              rules=tuple(rules), time_limit_s=time_limit_s)
    points = Points.grid(q, cond.corners())
    rounds, worst, tried, history, first = 0, None, 0, [], 0
    for rounds in range(1, max_rounds + 1):
        best, notes, n_tried = _solve_points(model, robot, points, cond, kw, first)
        tried += n_tried
        if best is None:
            why = "; ".join(notes) or _best_reachable(model, robot, points, cond, kw)
            raise TolallocError(f"no design meets P(|dP| < {radius_mm:g} mm) >= {prob:g} with these parts and "
                                f"process limits: {why}")
        out, ob, pr, cat, first = best
        ratio = PointRatio(with_parts(robot, ob.choice(out.part)),
                           pr.model_for(pr.t_from_u(cat.u_of(out.opt, out.n))), cond, kw["radius_mm"], kw["prob"],
                           out.rule, after, kw["residual"])
        if region is None:  # the poses only: the worst of the active points
            worst = _worst_active(ratio, points)
            break
        worst = worst_point(ratio, region.q_min, region.q_max, n_seed=n_seed, n_starts=n_starts, seed=seed + rounds,
                            static=None if worst is None else worst.static)
        history.append((rounds, out.cost, worst.ratio))
        if worst.ratio <= 1.0 + tol or rounds == max_rounds:
            break
        points = points.stack(worst.point)
    converged = worst.ratio <= 1.0 + tol
    return _finish(robot, model, out, ob, pr, cat, points, worst, cond, kw, rounds, converged, tried, history,
                   exact, region, seed, t0)


def _worst_active(ratio: PointRatio, points: Points) -> WorstPoint:
    """The active point of the largest ratio."""
    r = ratio(points)
    i = int(np.argmax(r))
    return WorstPoint(Points(points.q[i:i + 1], points.payload_kg[i:i + 1], points.ambient_c[i:i + 1]), float(r[i]),
                      len(points), np.zeros(points.q.shape[1] + 2, bool))


def _finish(robot, model, out: PartsOutcome, ob, pr, cat, points, worst: WorstPoint | None, cond, kw, rounds,
            converged, tried, history, exact, region, seed, t0) -> PartsAllocation:
    """Fold the chosen parts into the final problem; the machining allocation with them fixed."""
    from tolalloc.allocate.solve import allocate

    choice = ob.choice(out.part)
    extra = ob.fixed_cov + ob.cov[out.part].sum(axis=0)
    final = parts_problem(model, points, extra, ob.bias_mm, radius_mm=kw["radius_mm"], prob=kw["prob"],
                          costs=kw["costs"], after=kw["after"])
    t = final.t_from_u(cat.u_of(out.opt, out.n))
    solver = Solver.DISCRETE_TRACE if out.rule == "trace" else Solver.DISCRETE_LMI
    design = make_design(final, solver, t, time_s=out.time_s, message=out.message,
                         status="optimal" if out.status == "optimal" else out.status)
    labels = tuple(cat.label[o] for o in out.opt)
    machining = allocate(final, solver="exact", time_limit_s=kw["time_limit_s"]) if exact else None
    worst_pt = worst.point if worst is not None else Points(points.q[:1], points.payload_kg[:1],
                                                             points.ambient_c[:1])
    shares = option_blocks(robot, model, worst_pt, {k: (v,) for k, v in choice.items()}, cond, kw["after"],
                           kw["residual"])
    return PartsAllocation(final, design, out, choice, labels, shares, points, worst, cond, kw["after"],
                           kw["residual"], rounds, converged, tried, tuple(history), machining, region,
                           time.perf_counter() - t0[0], time.process_time() - t0[1])
