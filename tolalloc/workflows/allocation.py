"""The main job in one call: :func:`allocate_tolerances`.

Region -> allocation (certified and exact) -> standard grades -> coverage of the region -> nonlinear Monte Carlo
verification -> correction loop; with ``calibration=PLAN`` the calibration-aware allocation instead
(:mod:`tolalloc.workflows.calibrated`: certified stage -> exact stage -> standard grades -> end-to-end Monte Carlo,
no correction loop). The result (:class:`ToleranceAllocation`) holds every stage's object.
"""

from __future__ import annotations

import os

import numpy as np

from tolalloc.exceptions import ArgumentError
from tolalloc.progress import StageBar, show_progress
from tolalloc.workflows import inputs
from tolalloc.workflows.allocation_result import ToleranceAllocation
from tolalloc.workflows.calibrated import PLAN_IN_MEMORY, calibrated_allocation
from tolalloc.workflows.calplan import CalibrationPlanDesign

__all__ = ["allocate_tolerances", "ESTIMATORS", "CALIBRATED_ESTIMATORS", "DEFAULT_CORRECTION_ROUNDS"]

#: probability estimators of the verification (see :func:`tolalloc.verify.verify_design`)
ESTIMATORS = ("auto", "plain", "paired", "importance")
#: those of the calibration-aware allocation's end-to-end Monte Carlo (it has no importance sampler)
CALIBRATED_ESTIMATORS = ("auto", "plain", "paired")
#: correction rounds at most when ``correction_rounds`` is not given
DEFAULT_CORRECTION_ROUNDS = 2


@inputs.job_entry
def allocate_tolerances(robot="tool_changer", *, radius_mm: float = 0.25, prob: float = 0.95, region=None,
                        poses: str | None = None, costs=None, z: float | None = None, uniform: bool = False,
                        sigma_set: str | None = None, link_mode: str = "consistent", deflection_mode: str = "screw",
                        clearance: bool = False, exclude=(), angle_radius_deg: float | None = None,
                        angle_prob: float | None = None, solver: str = "exact", snap: bool = True,
                        angle_step_deg: float | None = None, calibration=None, verify: bool = True,
                        n_mc: int = 10**6, seed: int = 0, estimator: str = "auto", correction: bool | None = None,
                        correction_rounds: int | None = None, coverage_n: int = 100_000, scheduler=None,
                        tool: str | None = None, trust_units: bool = False, progress: bool | None = None,
                        parts=None):
    """Cheapest tolerances meeting ``P(|dP| < radius_mm) >= prob`` wherever the robot must work, verified.

    Parameters
    ----------
    robot : Robot, str or path
        A :class:`~tolalloc.robot.Robot`, a built-in name (``"tool_changer"``, ``"ur10"``) or a robot file.
    radius_mm, prob : float
        Required radius r of the tool-position error [mm] and probability p, in (0, 1).
    region : str, path or array, optional
        Where the requirement holds: a pose set, ``"limits"``, a box of the robot file, a trajectory CSV or an array /
        DataFrame of poses (deg / mm). Boxes are searched for their worst pose (cutting planes) and checked on a
        fresh sample of ``coverage_n`` poses. Default: the robot's ``working`` box, else the pose set ``poses``.
    poses : str, optional
        Pose set used without ``region`` (not with it; default ``working`` if defined, else ``nominal``).
    costs : str or path, optional
        Costs file (TOML): cost laws, process limits, fixed / excluded parameters (default: built-in assumptions).
    z : float, optional
        sigma = t / z (default 3, or the costs file's ``z``). ``uniform=True``: errors uniform over +-t.
    sigma_set, link_mode, deflection_mode, clearance, exclude
        Error-model options (see :func:`tolalloc.errormodel.build_error_model`).
    angle_radius_deg, angle_prob : float, optional
        Orientation requirement ``P(|rotation error| < angle_radius_deg) >= angle_prob`` [deg].
    solver : {"exact", "certified"}
        Design reported: exact probability (CasADi + IPOPT) or certified (cvxpy + Clarabel; with ``calibration``: no
        exact stage).
    snap : bool
        Standard grades (ISO 286 for link lengths, ``angle_step_deg`` for angles, default 1 arcsec).
    calibration : str, path or CalibrationPlanDesign, optional
        A :func:`plan_calibration` result or the plan CSV it saved: allocate for the accuracy after calibration (what
        runs, options refused: :mod:`tolalloc.workflows.calibrated`); returns a :class:`CalibratedToleranceAllocation`.
    verify, correction : bool
        Nonlinear Monte Carlo verification (``n_mc`` samples per pose, ``seed``); ``correction`` (default on)
        re-solves with raised targets where a pose is not demonstrated (at most ``correction_rounds``, default 2).
    estimator : {"auto", "plain", "paired", "importance"}
        How the verification estimates ``P(|dP| < r)``: ``paired`` = exact linear P + mean difference of nonlinear and
        linear indicators on shared draws; ``importance`` = that difference by importance sampling (rare events);
        ``auto`` = paired for Gaussian parameters, else plain, importance where the tail is too thin for ``n_mc``.
    scheduler : str or dask.distributed.Client, optional
        Where the Monte Carlo runs (threads by default); never changes the numbers.
    tool, trust_units
        URDF tool link; accept inputs that look like a unit slip (radians for degrees ...).
    progress : bool, optional
        The job's stage on stderr (region search, coverage, verification ...); default: in a terminal or notebook.
    parts : bool or dict, optional
        Design with the bought parts too: the robot file's catalogue slots are chosen with the machining standard
        values over the region, a payload and an ambient range (:func:`tolalloc.verify.parts.verified_parts`: True,
        or its options ``payload_kg``, ``ambient_c``, ``duty``, ``after`` ...); returns a
        :class:`~tolalloc.allocate.parts_result.PartsAllocation` (its ``verification``: the nonlinear Monte Carlo at
        the worst point, ``n_mc`` draws). Default: the machining tolerances alone.

    Returns
    -------
    ToleranceAllocation or CalibratedToleranceAllocation (with ``calibration``); ``.ok``: the requirement is met.

    Examples
    --------
    >>> import tolalloc
    >>> res = tolalloc.allocate_tolerances("tool_changer", region="nominal", n_mc=2000)
    >>> res.verdict, round(res.cost, 2)
    ('demonstrated', 44.52)
    """
    seed, n_mc, coverage_n = _check(radius_mm, prob, angle_radius_deg, angle_prob, angle_step_deg, z, uniform, solver,
                                    estimator, n_mc, verify, seed, correction_rounds, coverage_n, progress)
    options = dict(sigma_set=sigma_set, link_mode=link_mode, deflection_mode=deflection_mode, clearance=clearance,
                   exclude=exclude)
    costs, calibration, scheduler, correction, correction_rounds = _check_more(
        snap, correction, correction_rounds, poses, costs, calibration, scheduler, estimator, angle_radius_deg, options)
    rob = inputs.as_robot(robot, tool=tool, trust_units=trust_units)
    model = inputs.error_model(rob, **options)
    cost_set = _costs(costs, model, z, uniform)
    label, box, q = inputs.resolve_region(rob, region, poses)
    kw = dict(radius_mm=float(radius_mm), prob=float(prob), costs=cost_set, angle_radius_deg=angle_radius_deg,
              angle_prob=angle_prob)
    inputs_record = _record(rob, label, cost_set, radius_mm=radius_mm, prob=prob, seed=seed, estimator=estimator,
                            n_mc=n_mc if verify else None, solver=solver, snap=snap, exclude=exclude, tool=tool,
                            correction=correction, correction_rounds=correction_rounds, trust_units=trust_units,
                            coverage_n=coverage_n if box is not None else None, angle_step_deg=angle_step_deg,
                            calibration=calibration)
    run = dict(snap=snap, angle_step_deg=angle_step_deg, verify=verify, n_mc=n_mc, seed=seed, estimator=estimator,
               coverage_n=coverage_n, inputs_record=inputs_record)
    if parts:
        if calibration is not None or angle_radius_deg is not None:
            raise ArgumentError("parts", "the design with bought parts has the position requirement without a "
                                "calibration plan; drop `calibration` / `angle_radius_deg`, or `parts`")
        from tolalloc.verify.parts import verified_parts

        return verified_parts(model, box, q, parts, radius_mm=float(radius_mm), prob=float(prob), costs=cost_set,
                              verify=verify, n_mc=n_mc, seed=seed)
    with StageBar(show_progress(progress), f"allocate {rob.name}") as bar:
        if calibration is not None:
            bar.stage("calibration-aware allocation")
            return calibrated_allocation(model, label, box, q, *_calibration_plan(calibration, rob), costs_path=costs,
                                         exact=solver == "exact", **run, **kw)
        return _allocate(model, label, box, q, kw, solver=solver, correction=correction,
                         correction_rounds=correction_rounds, scheduler=scheduler, bar=bar, **run)


def _allocate(model, label, box, q, kw, *, solver, snap, angle_step_deg, verify, n_mc, seed, estimator, correction,
              correction_rounds, coverage_n, scheduler, inputs_record, bar) -> ToleranceAllocation:
    from tolalloc.allocate import allocate, build_problem

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


def _record(rob, label, cost_set, *, radius_mm, prob, seed, estimator, n_mc, solver, snap, exclude, correction,
            correction_rounds, coverage_n, angle_step_deg, tool, trust_units, calibration) -> dict:
    """The inputs that decide the numbers (for the report's reproduce command; the requirement's angle part, the
    costs' z and distribution and the error-model options are read back from the problem). ``n_mc`` None: no
    verification; ``correction`` / ``correction_rounds`` None: no correction loop (calibration-aware);
    ``coverage_n`` None: no box region, so no coverage sample. ``scheduler`` is left out: it never changes a
    number."""
    return {"robot": rob.name, "radius_mm": float(radius_mm), "prob": float(prob), "region": label,
            "costs": cost_set.source, "seed": int(seed), "n_mc": None if n_mc is None else int(n_mc),
            "estimator": estimator, "solver": solver, "snap": bool(snap),
            "exclude": [exclude] if isinstance(exclude, str) else list(exclude),
            "correction": None if correction is None else bool(correction),
            "correction_rounds": None if correction_rounds is None else int(correction_rounds),
            "coverage_n": None if coverage_n is None else int(coverage_n), "angle_step_deg": angle_step_deg,
            "tool": tool, "trust_units": bool(trust_units),
            "calibration": None if calibration is None else _plan_source(calibration)}


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


def _costs(costs, model, z, uniform):
    from tolalloc.allocate.costs import cost_set, load_costs

    dist = "uniform" if uniform else None
    if costs is None:
        return cost_set(model, None, z=z, distribution=dist)
    return load_costs(costs, model, z=z, distribution=dist)


def _plan_source(calibration) -> str:
    """Where a calibration plan comes from: its file, or :data:`PLAN_IN_MEMORY` for a plan_calibration result."""
    return PLAN_IN_MEMORY if isinstance(calibration, CalibrationPlanDesign) else str(calibration)


def _calibration_plan(calibration, robot) -> tuple:
    """``(plan, source)``: the plan of a :class:`CalibrationPlanDesign` (checked against ``robot``) or the plan read
    from a plan CSV, and where it comes from (:func:`_plan_source`)."""
    from tolalloc.calibration.plan import read_plan

    if isinstance(calibration, CalibrationPlanDesign):
        return calibration.plan_for(robot), PLAN_IN_MEMORY
    return read_plan(calibration, robot), _plan_source(calibration)


#: correction rounds at most (each re-solves the allocation and re-runs the verification)
MAX_CORRECTION_ROUNDS = 50


def _check_more(snap, correction, correction_rounds, poses, costs, calibration, scheduler, estimator,
                angle_radius_deg, model_options) -> tuple:
    """Refuse bad flags, names, paths, error-model options and options the calibration-aware allocation cannot
    honour, by their argument names; returns ``(costs, calibration, scheduler, correction, correction_rounds)``
    checked, with their defaults."""
    inputs.check_flag(snap, "snap")
    inputs.check_optional_flag(correction, "correction")
    inputs.check_model_options(**model_options)
    inputs.check_name(poses, "poses", "the name of a pose set of the robot")
    costs = inputs.check_costs_file(costs)
    if not isinstance(calibration, (CalibrationPlanDesign, str, os.PathLike, type(None))):
        raise ArgumentError("calibration", "expected the CalibrationPlanDesign plan_calibration returns, or the path "
                            f"of a calibration plan CSV (a str or pathlib.Path), got {inputs.shown(calibration)}.")
    if not isinstance(calibration, CalibrationPlanDesign):
        calibration = inputs.check_path(calibration, "calibration", "a calibration plan CSV (from plan_calibration)")
    scheduler = inputs.check_scheduler(scheduler)
    return (costs, calibration, scheduler,
            *_correction_options(calibration, correction, correction_rounds, scheduler, estimator, angle_radius_deg))


def _check(radius_mm, prob, angle_radius_deg, angle_prob, angle_step_deg, z, uniform, solver, estimator, n_mc, verify,
           seed, correction_rounds, coverage_n, progress) -> tuple:
    """Refuse bad numbers by their argument names before any computation; returns ``(seed, n_mc, coverage_n)`` as
    ints (``n_mc`` as given when there is no verification)."""
    inputs.check_optional_flag(progress, "progress")
    inputs.check_positive(radius_mm, "radius_mm", "mm", "0.25")
    inputs.check_probability(prob, "prob")
    if angle_radius_deg is not None:
        inputs.check_positive(angle_radius_deg, "angle_radius_deg", "deg", "0.02")
    if angle_prob is not None:
        inputs.check_probability(angle_prob, "angle_prob")
        if angle_radius_deg is None:
            raise ArgumentError("angle_prob", f"{angle_prob:g} needs an orientation requirement: add "
                                "`angle_radius_deg` A.")
    if angle_step_deg is not None:
        inputs.check_positive(angle_step_deg, "angle_step_deg", "deg", "0.001")
    inputs.check_flag(uniform, "uniform")
    inputs.check_flag(verify, "verify")
    if uniform and z is not None:
        raise ArgumentError("uniform", "and `z` both set sigma = t / z; give one of them.")
    if z is not None:
        inputs.check_z(z)
    inputs.check_choice(solver, "solver", ("exact", "certified"))
    inputs.check_choice(estimator, "estimator", ESTIMATORS)
    if correction_rounds is not None and (
            isinstance(correction_rounds, (bool, np.bool_)) or not isinstance(correction_rounds, (int, np.integer))
            or not 0 <= correction_rounds <= MAX_CORRECTION_ROUNDS):
        raise ArgumentError("correction_rounds", f"expected a whole number from 0 to {MAX_CORRECTION_ROUNDS} (rounds of "
                            f"the correction loop, e.g. 2), got {inputs.shown(correction_rounds)}; or switch the "
                            "correction off.")
    if verify:
        try:
            inputs.check_count(n_mc, "n_mc", minimum=100)
        except ArgumentError:
            raise ArgumentError("n_mc", f"expected at least 100 samples per pose (a whole number, e.g. 1000000), got "
                                f"{inputs.shown(n_mc)}; or switch the verification off.") from None
    return (inputs.check_seed(seed), int(n_mc) if verify else n_mc,
            inputs.check_count(coverage_n, "coverage_n", example="100000"))


def _correction_options(calibration, correction, correction_rounds, scheduler, estimator, angle_radius_deg) -> tuple:
    """``(correction, correction_rounds)`` with their defaults (after calibration: no loop, so ``correction`` None or
    False as given and no round limit); refuses, by their argument names, the options the calibration-aware
    allocation cannot honour."""
    if calibration is None:
        return (True if correction is None else correction,
                DEFAULT_CORRECTION_ROUNDS if correction_rounds is None else correction_rounds)
    no_loop = ("the calibration-aware allocation (`calibration`) has no correction loop: its end-to-end Monte Carlo "
               "states per pose whether the design to build passed, and nothing is re-solved")
    if correction:
        raise ArgumentError("correction", f"expected False or nothing with `calibration` ({no_loop}), got True; "
                            "leave out `correction`.")
    if correction_rounds is not None:
        raise ArgumentError("correction_rounds", f"expected nothing with `calibration` ({no_loop}), got "
                            f"{inputs.shown(correction_rounds)}; leave out `correction_rounds`.")
    if scheduler is not None:
        raise ArgumentError("scheduler", "expected nothing with `calibration` (the end-to-end Monte Carlo of the "
                            "calibration-aware allocation runs in this process, vectorised over the simulated robots, "
                            f"and takes no scheduler), got {inputs.shown(scheduler)}; leave out `scheduler`.")
    if estimator not in CALIBRATED_ESTIMATORS:
        raise ArgumentError("estimator", f"expected one of {', '.join(map(repr, CALIBRATED_ESTIMATORS))} with "
                            "`calibration` (the end-to-end Monte Carlo of the calibration-aware allocation has no "
                            f"importance sampler), got {estimator!r}; use 'paired' for a rare-event requirement.")
    if angle_radius_deg is not None:
        raise ArgumentError("angle_radius_deg", f"expected nothing with `calibration` (the calibration-aware "
                            f"allocation handles the position requirement only), got {angle_radius_deg!r}; leave "
                            "out `angle_radius_deg` and `angle_prob`, or allocate without `calibration`.")
    return correction, None
