"""The main job in one call: :func:`allocate_tolerances`.

Region -> allocation (certified and exact) -> standard grades -> coverage of the region -> nonlinear Monte Carlo
verification -> correction loop; with ``calibration=PLAN`` the calibration-aware allocation instead
(:mod:`tolalloc.workflows.calibrated`: certified stage -> exact stage -> standard grades -> end-to-end Monte Carlo,
no correction loop). The result (:class:`ToleranceAllocation`) holds every stage's object.
"""

from __future__ import annotations


import numpy as np

from tolalloc.exceptions import ArgumentError
from tolalloc.progress import StageBar, show_progress
from tolalloc.verify.cost import check_allocation_budgets
from tolalloc.workflows import inputs
from tolalloc.workflows.allocation_result import ToleranceAllocation
from tolalloc.workflows.allocation_settings import allocation_settings
from tolalloc.workflows.calibrated import PLAN_IN_MEMORY, calibrated_allocation
from tolalloc.workflows.calplan import CalibrationPlanDesign
from tolalloc.workflows.defaults import CORRECTION_ROUNDS as DEFAULT_CORRECTION_ROUNDS
from tolalloc.workflows.requirements import CALIBRATED_ESTIMATORS, ESTIMATORS

__all__ = ["allocate_tolerances", "ESTIMATORS", "CALIBRATED_ESTIMATORS", "DEFAULT_CORRECTION_ROUNDS"]


@inputs.job_entry
def allocate_tolerances(robot="tool_changer", requirement=None, *, radius_mm: float | None = None,
                        prob: float | None = None, region=None, costs=None, error_model=None, solver=None,
                        verification=None, n_mc: int | None = None, calibration=None, progress: bool | None = None,
                        tool: str | None = None, trust_units: bool = False,
                        parts=None):
    """Cheapest tolerances meeting ``P(|dP| < radius_mm) >= prob`` wherever the robot must work, verified.

    Parameters
    ----------
    robot : Robot, str or path
        A :class:`~tolalloc.robot.Robot`, a built-in name (``"tool_changer"``, ``"ur10"``) or a robot file.
    requirement : Requirement or list of Requirement, optional
        What must hold: a :class:`~tolalloc.workflows.PositionRequirement` and optionally an
        :class:`~tolalloc.workflows.OrientationRequirement` (one of each kind). Default: ``P(|dP| < 0.25 mm) >=
        0.95``.
    radius_mm, prob : float, optional
        Short form of ``requirement=PositionRequirement(radius_mm, prob)`` (not with ``requirement``).
    region : str, path, array or Region, optional
        Where the requirement holds (:class:`~tolalloc.workflows.Region`, or its ``where``: a pose set,
        ``"limits"``, a box of the robot file, a trajectory CSV or an array / DataFrame of poses in deg / mm).
        Default: the robot's ``working`` box, else its ``working`` pose set, else the nominal pose.
    costs : str, path or Costs, optional
        Cost laws and process limits: a costs file (TOML) or :class:`~tolalloc.workflows.Costs` (with ``z`` of
        sigma = t / z, or uniform errors); default the built-in assumptions.
    error_model : ErrorModelOptions, optional
        Sigma set of the fixed parameters, link and deflection model, clearance, excluded parameters
        (:class:`~tolalloc.workflows.ErrorModelOptions`).
    solver : {"exact", "certified"} or Solver, optional
        The design reported and its standard values (:class:`~tolalloc.workflows.Solver`).
    verification : Verification or bool, optional
        The nonlinear Monte Carlo verification and the correction loop (:class:`~tolalloc.workflows.Verification`:
        samples, seed, estimator, correction, scheduler); ``False``: none (linear prediction and coverage only).
    n_mc : int, optional
        Short form of ``verification=Verification(n_mc=...)``: samples per verified pose (default 1 000 000).
    calibration : str, path or CalibrationPlanDesign, optional
        A :func:`plan_calibration` result or the plan CSV it saved: allocate for the accuracy after calibration (what
        runs, options refused: :mod:`tolalloc.workflows.calibrated`); returns a :class:`CalibratedToleranceAllocation`.
    progress : bool, optional
        The job's stages on stderr (:mod:`tolalloc.progress`: a status line on a terminal, a line per stage in a log).
    tool, trust_units
        URDF tool link; accept inputs that look like a unit slip (radians for degrees ...).
    parts : bool or dict, optional
        Design with the bought parts too: the robot file's catalogue slots are chosen with the machining standard
        values over the region, a payload and an ambient range (:func:`tolalloc.verify.parts.verified_parts`: True,
        or its options ``payload_kg``, ``ambient_c``, ``duty``, ``after`` ...); returns a
        :class:`~tolalloc.workflows.parts.PartsToleranceAllocation` (its ``verification``: the nonlinear Monte Carlo
        at the worst point, ``n_mc`` draws). Default: the machining tolerances alone.

    Returns
    -------
    ToleranceAllocation or CalibratedToleranceAllocation (with ``calibration``); ``.ok``: the requirement is met.

    Notes
    -----
    Every default is the command line's (:mod:`tolalloc.workflows.defaults`): the same call and ``tolalloc allocate``
    with the same inputs write the same files. The keywords this call took before its settings objects (``seed``,
    ``poses``, ``sigma_set``, ``snap``, ``verify`` ...) still work for one release, with a ``DeprecationWarning``
    naming the object that holds each now.

    Examples
    --------
    >>> import tolalloc
    >>> res = tolalloc.allocate_tolerances("tool_changer", region="nominal", n_mc=2000)
    >>> res.verdict, round(res.cost, 2)
    ('demonstrated', 44.26)
    """
    s = allocation_settings(requirement, radius_mm=radius_mm, prob=prob, region=region, costs=costs,
                            error_model=error_model, solver=solver, verification=verification, n_mc=n_mc,
                            calibration=calibration)
    inputs.check_optional_flag(progress, "progress")
    rob = inputs.as_robot(robot, tool=tool, trust_units=trust_units)
    model = inputs.error_model(rob, **s.error_model.keywords())
    cost_set = _costs(s.costs, model)
    label, box, q = inputs.resolve_region(rob, s.region.where, s.region.poses)
    kw = dict(**s.problem_arguments(), costs=cost_set)
    ver, sol = s.verification, s.solver
    inputs_record = _record(rob, label, cost_set, s, box is not None, tool=tool, trust_units=trust_units)
    run = dict(snap=sol.snap, angle_step_deg=sol.angle_step_deg, verify=ver.monte_carlo, n_mc=ver.n_mc, seed=ver.seed,
               estimator=ver.estimator, coverage_n=s.region.coverage_n, inputs_record=inputs_record)
    if parts is not None and parts is not False:  # True, or a dict of options (empty: the defaults)
        return _allocate_parts(model, label, box, q, parts, s, cost_set, inputs_record)
    with StageBar(show_progress(progress), f"allocate {rob.name}") as bar:
        if s.calibration is not None:
            bar.stage("calibration-aware allocation")
            return calibrated_allocation(model, label, box, q, *_calibration_plan(s.calibration, rob),
                                         costs_path=s.costs.file, exact=sol.method == "exact", **run, **kw)
        return _allocate(model, label, box, q, kw, solver=sol.method, correction=s.correction,
                         correction_rounds=s.correction_rounds, scheduler=ver.scheduler, bar=bar, **run)


def _allocate_parts(model, label, box, q, parts, s, cost_set, inputs_record):
    """The joint allocation with the robot file's catalogue parts (:func:`tolalloc.verify.parts.verified_parts`)."""
    if s.calibration is not None or len(s.requirements) > 1:
        raise ArgumentError("parts", "the design with bought parts takes the position requirement alone, without a "
                            "calibration plan; drop `calibration` / the orientation requirement, or `parts`")
    from tolalloc.verify.parts import verified_parts

    from tolalloc.workflows.parts import PartsToleranceAllocation

    req, ver = s.position, s.verification
    res = verified_parts(model, box, q, parts, radius_mm=float(req.radius_mm), prob=float(req.prob), costs=cost_set,
                         verify=ver.monte_carlo, n_mc=ver.n_mc or 20000, seed=ver.seed)
    return PartsToleranceAllocation(res, float(req.radius_mm), float(req.prob), label, inputs_record)


def _allocate(model, label, box, q, kw, *, solver, snap, angle_step_deg, verify, n_mc, seed, estimator, correction,
              correction_rounds, coverage_n, scheduler, inputs_record, bar) -> ToleranceAllocation:
    from tolalloc.allocate import allocate, build_problem

    check_allocation_budgets(model, box is not None, q, n_mc=n_mc if verify else None, estimator=estimator,
                             coverage_n=coverage_n, rounds=correction_rounds if correction and verify else 0)
    reg_info = None
    if box is not None and _box_is_one_pose(model, box, kw, seed):
        box, q = None, 0.5 * (box.q_min + box.q_max)[None, :]
    if box is not None:
        reg_info = _region_search(model, box, kw, solver=solver, snap=snap, angle_step_deg=angle_step_deg, bar=bar)
        q = reg_info.active_q
    if reg_info is not None and snap and reg_info.result.status == "optimal":
        res = reg_info.result  # the standard design's loop solved it on the final active set
    else:
        bar.stage(f"{solver} design" + (" and standard grades" if snap else ""))
        res = allocate(build_problem(model, q, **kw), solver=solver, snap=snap, angle_step_deg=angle_step_deg)
    if box is not None and res.status == "infeasible":
        return ToleranceAllocation(res, label, box, reg_info, None, None, None, inputs_record,
                                   infeasible=_region_infeasible(res, box, reg_info, seed), built=res.design)
    cov, ver, corr = None, None, None
    if res.status == "optimal":
        res, cov, ver, corr = _verify_and_correct(model, kw, res, box, verify=verify, n_mc=n_mc, seed=seed,
                                                  estimator=estimator, correction=correction, rounds=correction_rounds,
                                                  solver=solver, snap=snap, angle_step_deg=angle_step_deg,
                                                  coverage_n=coverage_n, scheduler=scheduler, bar=bar)
    return ToleranceAllocation(res, label, box, reg_info, cov, ver, corr, inputs_record, built=res.built)


def _region_search(model, box, kw, *, solver, snap, angle_step_deg, bar):
    """Cutting planes over the box for the continuous design, continued for the standard design (``snap``)."""
    from tolalloc.allocate.region import allocate_region
    from tolalloc.allocate.region_standard import allocate_region_standard

    rob = model.robot
    q0 = rob.poses("working") if "working" in rob.pose_sets else None
    if q0 is not None and not np.all((q0 >= box.q_min - 1e-12) & (q0 <= box.q_max + 1e-12)):
        q0 = None
    bar.stage(f"region search ({solver} design)")
    reg_info = allocate_region(model, box, q0, solver=solver, **kw)
    if not snap or reg_info.result.status != "optimal":
        return reg_info
    bar.stage("region search (standard grades)")
    return allocate_region_standard(model, box, solver=solver, angle_step_deg=angle_step_deg, continuous=reg_info,
                                    **kw)


def _box_is_one_pose(model, box, kw, seed) -> bool:
    """True if no joint of the box moves the position-error covariance (a single prismatic joint, say): the
    requirement is then the same at every pose of the box, and its centre stands for all of them."""
    from tolalloc.allocate import build_problem
    from tolalloc.allocate.region import static_joints

    centre = 0.5 * (box.q_min + box.q_max)
    return bool(static_joints(build_problem(model, centre[None, :], **kw), box, seed=seed).all())


def _verify_and_correct(model, kw, res, box, *, verify, n_mc, seed, estimator, correction, rounds, solver, snap,
                        angle_step_deg, coverage_n, scheduler, bar):
    """Coverage of a box region, Monte Carlo verification and the correction loop.

    Returns ``(result, coverage, verification, correction)``: the final (corrected) allocation and its checks.
    """
    from tolalloc.allocate.problem import build_problem, make_design
    from tolalloc.allocate.region import coverage

    design = res.built
    standard = design is not res.design
    cov, vproblem, vdesign = None, res.problem, design
    if box is not None:
        bar.stage(f"coverage ({coverage_n:,} fresh poses)")
        cov = coverage(res.problem, design.t, box, n=coverage_n, seed=seed + 12345)
        vproblem = build_problem(model, np.vstack([res.problem.q, cov.worst_q]), **kw)
        vdesign = make_design(vproblem, design.solver, design.t, fallback_from=design.fallback_from)
    if not verify:
        return res, cov, None, None
    from tolalloc.verify.designs import verify_design

    bar.stage(f"Monte Carlo verification ({n_mc:,} samples per pose)")
    ver = verify_design(vproblem, vdesign, n_mc=n_mc, seed=seed, scheduler=scheduler, estimator=estimator)
    if ver.verdict == "demonstrated" or not correction:
        return res, cov, ver, None
    from tolalloc.verify.correct import correct_design

    bar.stage("correction (re-solve and verify)")
    corr = correct_design(model, vproblem.q, solver=solver, n_mc=n_mc, seed=seed, max_rounds=rounds, result=res,
                          verification=ver, snap=snap, angle_step_deg=angle_step_deg, scheduler=scheduler,
                          keep_samples=4000, estimator=estimator, standard=standard, **kw)
    if corr.rounds and box is not None:  # the corrected design, checked over the region again
        cov = coverage(corr.result.problem, corr.result.built.t, box, n=coverage_n, seed=seed + 12345)
    return corr.result, cov, corr.verification, corr


def _record(rob, label, cost_set, s, is_box: bool, *, tool, trust_units) -> dict:
    """The inputs that decide the numbers (for the report's reproduce command; the requirement's angle part, the
    costs' z and distribution and the error-model options are read back from the problem). ``n_mc`` None: no
    verification; ``correction`` / ``correction_rounds`` None: no correction loop (calibration-aware);
    ``coverage_n`` None: no box region, so no coverage sample. ``scheduler`` is left out: it never changes a
    number."""
    ver, sol, exclude = s.verification, s.solver, s.error_model.exclude
    return {"robot": rob.name, "radius_mm": float(s.position.radius_mm), "prob": float(s.position.prob),
            "region": label, "costs": cost_set.source, "seed": int(ver.seed), "n_mc": ver.n_mc,
            "estimator": ver.estimator, "solver": sol.method, "snap": bool(sol.snap), "exclude": list(exclude),
            "correction": None if s.correction is None else bool(s.correction),
            "correction_rounds": s.correction_rounds, "coverage_n": s.region.coverage_n if is_box else None,
            "angle_step_deg": sol.angle_step_deg, "tool": tool, "trust_units": bool(trust_units),
            "calibration": None if s.calibration is None else _plan_source(s.calibration),
            "requirements": [r.to_dict() for r in s.requirements]}


def _region_infeasible(res, box, reg_info, seed) -> str:
    """Why a region is infeasible even at the tightest process limits: each requirement that cannot be met (position
    in mm, orientation in deg), at the worst pose found for it, with the limits that bind there; what would work."""
    from tolalloc.allocate.region import worst_pose

    pr = res.problem
    found = [_requirement_at_worst(res, b, worst_pose(pr, res.design.t, box, seed=seed, fixed=reg_info.static,
                                                       requirement=b["name"])[:2]) for b in pr.blocks]
    unmet = [f for f in found if f[0]] or found
    relax = " and ".join(f[2] for f in unmet)
    return (f"`region` {box.name}: even with every tolerance at its tightest process limit, " + "; ".join(
        f[1] for f in unmet) + f". Lower these t_min in a costs file (`costs`), relax {relax}, or use a smaller "
        "region; nothing written.")


def _requirement_at_worst(res, block, searched) -> tuple:
    """``(unmet, text, arguments to relax)`` of one requirement (a block of the problem) at its worst pose: the
    search's ``(q, p)`` or an active pose of the allocation when that one is worse."""
    from tolalloc.linear.covariance import variance_share
    from tolalloc.linear.probability import radius_for_prob

    pr, name = res.problem, block["name"]
    robot = pr.model.robot
    q, p_best = searched
    p_set = res.diagnosis.p_best[name]
    if float(p_set.min()) < p_best:  # an active pose is worse than what the search found
        q, p_best = pr.q[int(np.argmin(p_set))], float(p_set.min())
    J, var = pr.model.jacobian(q)[block["rows"]], pr.sigma(res.design.t) ** 2
    share = variance_share(J, var)
    names = pr.costs.names
    binding = ", ".join(f"{names[k]} ({share[k]:.0%})" for k in np.argsort(share)[::-1][:4] if share[k] >= 0.02)
    angle = name == "orientation"
    unit, f, sym = ("deg", 180.0 / np.pi, "dw") if angle else ("mm", 1.0, "dP")
    reach = float(radius_for_prob(J @ (var[:, None] * J.T), block["prob"])) * f
    joints = ", ".join(f"{j.name} = {v:.4g} {j.unit}" for j, v in zip(robot.joints, robot.q_to_interface(q)))
    text = (f"the {name} requirement P(|{sym}| < {block['radius'] * f:g} {unit}) >= {block['prob']:g} cannot be met "
            f"(at the worst pose found for it, {joints}, the best achievable P is {p_best:.4f} and P = "
            f"{block['prob']:g} holds only within {reach:.4g} {unit}" + (f"; limits that bind: {binding}" if binding
                                                                          else "") + ")")
    return (p_best < block["prob"], text, "`angle_radius_deg` / `angle_prob`" if angle else "`radius_mm` / `prob`")


def _costs(costs, model):
    """The cost set of a :class:`~tolalloc.workflows.Costs` for ``model``."""
    from tolalloc.allocate.costs import cost_set, load_costs

    if costs.file is None:
        return cost_set(model, None, z=costs.z, distribution=costs.distribution)
    return load_costs(costs.file, model, z=costs.z, distribution=costs.distribution)


def _plan_source(calibration) -> str:
    """Where a calibration plan comes from: its file, or :data:`PLAN_IN_MEMORY` for a plan_calibration result."""
    return PLAN_IN_MEMORY if isinstance(calibration, CalibrationPlanDesign) else str(calibration)


def _calibration_plan(calibration, robot) -> tuple:
    """``(plan, source)``: the plan of a :class:`CalibrationPlanDesign` (checked against ``robot``) or the plan read
    from a plan CSV, and where it comes from (:func:`_plan_source`)."""
    from tolalloc.calibration.plan import read_plan

    if isinstance(calibration, CalibrationPlanDesign):
        try:
            return calibration.plan_for(robot), PLAN_IN_MEMORY
        except ArgumentError as exc:  # the plan's robot is the allocation's argument `calibration` here
            raise ArgumentError("calibration", exc.detail) from None
    return read_plan(calibration, robot), _plan_source(calibration)
