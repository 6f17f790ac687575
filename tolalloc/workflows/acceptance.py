"""Tolerances for the requirements robot makers state (ISO 9283), with their acceptance test simulated:
:func:`allocate_acceptance` and its result.

What runs: the acceptance test laid out in the working region (:func:`tolalloc.acceptance.acceptance_test`); one
allocation problem with a block per ISO 9283 statistic at the test's poses (and the error balls, if given, at the
working poses; :func:`tolalloc.allocate.build_problem`) solved certified, exact and on standard grades
(:func:`tolalloc.allocate.allocate`); the test predicted for the design to build
(:func:`tolalloc.acceptance.predict_acceptance`, with the ISO 14253-1 verdicts) and simulated robot by robot
(:func:`tolalloc.acceptance.simulate.simulate_acceptance`) as the check of the prediction. The logic lives in those
stages; this module wires them.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from tolalloc.exceptions import ArgumentError
from tolalloc.outputs import json_native, write_json
from tolalloc.workflows import inputs
from tolalloc.workflows.base import JobResult

__all__ = ["allocate_acceptance", "AcceptanceAllocation"]


@inputs.job_entry
def allocate_acceptance(robot="tool_changer", requirement=None, *, region=None, costs=None, error_model=None,
                        solver=None, test=None, verification=None, n_robots: int = 2000, parts=None,
                        tool: str | None = None, trust_units: bool = False) -> "AcceptanceAllocation":
    """Cheapest tolerances meeting ISO 9283 requirements (``AP``, ``RP``, ...), with the acceptance test simulated.

    Parameters
    ----------
    robot : Robot, str or path
    requirement : Requirement, sequence of them, or path
        :mod:`tolalloc.acceptance.requirements` objects (at least one ISO 9283 one; the error balls may join them),
        or a requirement file (TOML, :mod:`tolalloc.acceptance.requirement_file`), whose ``[test]`` table sets the
        test unless ``test`` is given.
    region : str, (q_min, q_max) or Region, optional
        The working region the test cube is placed in: a box of the robot file, ``"limits"``, a pose set (its
        spanning box) or a box [rad, mm]; default :func:`tolalloc.acceptance.layout.default_region`. A
        :class:`~tolalloc.workflows.Region`'s ``poses`` names the pose set where the error balls hold (default
        ``working``, else nominal).
    costs, error_model, solver
        As :func:`tolalloc.allocate_tolerances` (:class:`~tolalloc.workflows.Costs`,
        :class:`~tolalloc.workflows.ErrorModelOptions`, :class:`~tolalloc.workflows.Solver`); the costs file's
        ``[calibration]`` table sets the systematic / random split (:mod:`tolalloc.calibration.split`).
    test : dict or AcceptanceTest, optional
        Keywords of :func:`tolalloc.acceptance.acceptance_test` (``cycles``, ``cube_edge_mm``, ``tracker`` ...), or
        a test laid out already.
    verification : Verification or bool, optional
        ``False``: no simulated test; else the test is simulated on ``n_robots`` robots as the check of the prediction
        (the :class:`~tolalloc.workflows.Verification`'s ``seed``).
    n_robots : int
        Robots of the simulated acceptance test (default 2000).
    parts : dict, True, PartsToleranceAllocation, str, path or pandas.DataFrame, optional
        The bought parts in the test (:mod:`tolalloc.acceptance.parts`): a choice ``{(joint, kind): part}`` of the
        robot's catalogue slots; ``True`` for the parts its file names (every slot one part); or the parts a design
        with bought parts chose -- its result (``allocate_tolerances(..., parts=...)``), the ``parts.csv`` it saved or
        that table read into a DataFrame (:func:`~tolalloc.workflows.parts.read_parts_choice`). This job does not
        choose parts itself. Their effects under the test load enter the allocation (their mean as a shorter limit),
        the predicted and the simulated test. Default: the error model alone.

    Returns
    -------
    AcceptanceAllocation
    """
    region, poses, cost, em, sol, verify, seed = _settings(region, costs, error_model, solver, verification)
    costs = cost.file
    solver, snap, angle_step_deg = sol.method, sol.snap, sol.angle_step_deg
    from tolalloc.acceptance import acceptance_test
    from tolalloc.acceptance.layout import AcceptanceTest
    from tolalloc.acceptance.terms import AcceptanceSpec
    from tolalloc.allocate import allocate, build_problem
    from tolalloc.workflows.allocation import _costs
    from tolalloc.workflows.calibrated import split_from_costs

    reqs, test_kw, source = _requirements(requirement)
    n_robots = inputs.check_count(n_robots, "n_robots", minimum=2, example="2000")
    seed = inputs.check_seed(seed)
    if solver not in ("exact", "certified"):
        raise ArgumentError("solver", f"expected 'exact' or 'certified', got {solver!r}.")
    rob = inputs.as_robot(robot, tool=tool, trust_units=trust_units)
    parts = _choice(parts)
    rob, effects = _parts(rob, parts)
    model = inputs.error_model(rob, sigma_set=em.sigma_set, link_mode=em.link_mode, deflection_mode=em.deflection_mode,
                               clearance=em.clearance, exclude=em.exclude)
    cost_set = _costs(cost, model)
    split = split_from_costs(model, costs)
    times = {}
    t0 = time.perf_counter()
    if isinstance(test, AcceptanceTest):
        lay = test if effects is None else replace(test, robot=rob)
    else:
        kw = dict(test_kw if test is None else _test_options(test))
        lay = acceptance_test(rob, _region(rob, region), **kw)
    times["test_layout_s"] = time.perf_counter() - t0
    pos = next((r for r in reqs if r.kind == "position"), None)
    ori = next((r for r in reqs if r.kind == "orientation"), None)
    iso = tuple(r for r in reqs if r.kind not in ("position", "orientation"))
    spec = AcceptanceSpec(iso, lay, split=split, effects=effects)
    q = None if pos is None else inputs.resolve_poses(rob, None, poses)[1]
    t0 = time.perf_counter()
    problem = build_problem(model, q, radius_mm=None if pos is None else pos.radius_mm,
                            prob=0.95 if pos is None else pos.prob, costs=cost_set,
                            angle_radius_deg=None if ori is None else ori.radius_deg,
                            angle_prob=None if ori is None else ori.prob, acceptance=spec)
    res = allocate(problem, solver=solver, snap=snap, angle_step_deg=angle_step_deg)
    times["allocation_s"] = time.perf_counter() - t0
    pred, sim = _predicted(res, problem, spec, verify, n_robots, seed, times)
    record = {"robot": rob.name, "requirements": [r.to_dict() for r in reqs], "requirement_source": source,
              "parts": None if effects is None else _part_names(rob, parts),
              "test": lay.summary(), "solver": solver, "snap": snap, "n_robots": n_robots if verify else None,
              "seed": seed, "costs_source": cost_set.source}
    return AcceptanceAllocation(res, lay, reqs, pred, sim, record, times, _stiffness(rob, lay, effects))


def _stiffness(robot, test, effects):
    """With the bought parts: the static compliance at P1, the cube's centre (ISO 9283 10); else None."""
    if effects is None or robot.components.payload.rated_kg is None:
        return None
    from tolalloc.acceptance import static_compliance

    return static_compliance(robot, test.q_test[0])


def _choice(parts):
    """``parts`` as the job uses it: None, True or a ``{(joint, kind): part}`` choice (a design with bought parts,
    its result or its parts table, read into one)."""
    import pandas as pd

    from tolalloc.workflows.parts import PartsToleranceAllocation, read_parts_choice

    if parts is None or parts is False or parts is True or isinstance(parts, dict):
        return parts
    if isinstance(parts, PartsToleranceAllocation):
        return dict(parts.choice)
    if isinstance(parts, (str, os.PathLike, pd.DataFrame)):
        return read_parts_choice(parts)
    raise ArgumentError("parts", f"expected a choice {{(joint, kind): part name}} of the robot's catalogue slots, True "
                        "(the parts its file names), a design with bought parts, the parts.csv it saved or that table "
                        f"as a DataFrame, got {inputs.shown(parts)}.")


def _parts(robot, parts) -> tuple:
    """``(robot, effects)``: the robot with the chosen parts and their :func:`~tolalloc.acceptance.parts.
    parts_effects`, or ``(robot, None)`` without ``parts``."""
    if parts is None or parts is False:
        return robot, None
    from tolalloc.acceptance.parts import parts_effects
    from tolalloc.errormodel.parts import with_parts

    choice = {} if parts is True else parts
    open_slots = [f"{j}.{kind} ({' | '.join(o.name for o in slot.options)})"
                  for (j, kind), slot in sorted(robot.components.slots.items())
                  if len(slot.options) > 1 and (j, kind) not in choice]
    if open_slots:
        raise ArgumentError("parts", f"robot {robot.name!r} offers a choice in {len(open_slots)} catalogue slot(s) "
                            f"no part is named for: {'; '.join(open_slots)}. The ISO 9283 job does not choose parts: "
                            "name one per slot ({(joint, kind): part} in Python, --part JOINT.KIND=NAME on the command "
                            "line), or pass the parts a design with bought parts chose (allocate_tolerances(robot, "
                            "parts=True), tolalloc allocate ROBOT --parts --out DIR): its result or its parts.csv "
                            "(--parts-file DIR/parts.csv).")
    return with_parts(robot, choice), parts_effects()


def _part_names(robot, parts) -> dict:
    """``{"joint.kind": part name}`` of the robot's catalogue slots as chosen (a slot of one part: that part)."""
    choice = parts if isinstance(parts, dict) else {}
    return {f"{j}.{kind}": choice.get((j, kind), slot.options[0].name)
            for (j, kind), slot in sorted(robot.components.slots.items())}


def _predicted(res, problem, spec, verify: bool, n_robots: int, seed: int, times: dict) -> tuple:
    """The acceptance test predicted for the design of ``res`` and, with ``verify``, simulated on ``n_robots``
    robots: ``(prediction, simulation)`` (None where not made); their durations into ``times``."""
    from tolalloc.acceptance.predict import predict_acceptance
    from tolalloc.acceptance.simulate import simulate_acceptance

    if res.status != "optimal":
        return None, None
    t0 = time.perf_counter()
    design_model = problem.model_for(res.built.t)
    lay, iso, split = spec.test, spec.requirements, spec.split
    pred = predict_acceptance(lay, iso, design_model, spec_split(split, problem.model), effects=spec.effects)
    times["prediction_s"] = time.perf_counter() - t0
    if not verify:
        return pred, None
    t0 = time.perf_counter()
    sim = simulate_acceptance(lay, iso, design_model, spec_split(split, problem.model), effects=spec.effects,
                              n_robots=n_robots, seed=seed)
    times["simulation_s"] = time.perf_counter() - t0
    return pred, sim


def _settings(region, costs, error_model, solver, verification) -> tuple:
    """The settings objects of :func:`allocate_acceptance` (or their short forms): ``(region, poses, Costs,
    ErrorModelOptions, Solver, verify, seed)``."""
    from tolalloc.workflows.allocation_settings import Region, Solver, Verification
    from tolalloc.workflows.settings import Costs, ErrorModelOptions, as_settings

    poses = region.poses if isinstance(region, Region) else None
    region = region.where if isinstance(region, Region) else region
    cost = as_settings(costs, Costs, "costs", lambda v: Costs(file=v))
    em = as_settings(error_model, ErrorModelOptions, "error_model")
    sol = as_settings(solver, Solver, "solver", lambda v: Solver(method=v))
    ver = as_settings(None if verification in (True, False) else verification, Verification, "verification")
    return region, poses, cost, em, sol, verification is not False, ver.seed


def spec_split(split, model):
    """``split`` restricted to the parameters of ``model`` (the problem's, without excluded ones)."""
    from tolalloc.calibration.split import ErrorSplit

    idx = [split.model.index(nm) for nm in model.names]
    return ErrorSplit(model, split.systematic[idx], split.random_sigma[idx])


def _requirements(requirement):
    from tolalloc.acceptance.requirement_file import read_requirement_file
    from tolalloc.acceptance.requirements import IsoRequirement, check_requirements

    if requirement is None:
        raise ArgumentError("requirement", "expected ISO 9283 requirements (e.g. [tolalloc.acceptance.PoseAccuracy("
                            "limit_mm=0.5), tolalloc.acceptance.PoseRepeatability(limit_mm=0.05)]) or a requirement "
                            "file (examples/requirements_iso9283.toml), got None.")
    if isinstance(requirement, (str, Path)):
        f = read_requirement_file(requirement)
        reqs, test_kw, source = f.requirements, f.test, f.source
    else:
        reqs, test_kw, source = check_requirements(requirement), {}, "<objects>"
    if not any(isinstance(r, IsoRequirement) for r in reqs):
        raise ArgumentError("requirement", "needs at least one ISO 9283 requirement (pose_accuracy, "
                            "pose_repeatability, ...); for the error balls alone use tolalloc.allocate_tolerances.")
    return reqs, test_kw, source


def _test_options(test) -> dict:
    if not isinstance(test, dict):
        raise ArgumentError("test", f"expected a dict of acceptance_test keywords or an AcceptanceTest, got {test!r}.")
    return dict(test)


def _region(robot, region):
    """A joint box (q_min, q_max) [rad, mm] for the cube, or None (the default region)."""
    if region is None or isinstance(region, (tuple, list)):
        return region
    label, box, q = inputs.resolve_region(robot, region, None)
    if box is not None:
        return box.q_min, box.q_max
    return q.min(axis=0), q.max(axis=0)


@dataclass(frozen=True, eq=False, repr=False)
class AcceptanceAllocation(JobResult):
    """Tolerances for ISO 9283 requirements and their acceptance test, predicted and simulated.

    Attributes
    ----------
    result : AllocationResult
        Certified, exact and standard designs (``result.built``: the one to build).
    test : AcceptanceTest
    requirements : tuple of Requirement
    prediction : AcceptancePrediction or None
        The predicted test of the design to build (None when no design was found).
    simulation : SimulatedAcceptance or None
    inputs : dict
    times_s : dict
    compliance : StaticCompliance or None
        With the bought parts: the static compliance at P1 predicted from them (ISO 9283 10).
    """

    result: object
    test: object
    requirements: tuple
    prediction: object
    simulation: object
    inputs: dict = field(default_factory=dict)
    times_s: dict = field(default_factory=dict)
    compliance: object = None

    @property
    def ok(self) -> bool:
        """A design was found and its robots meet every ISO 9283 requirement at its share (the prediction)."""
        return self.result.status == "optimal" and self.prediction is not None and self.prediction.met

    @property
    def cost(self) -> float:
        """Cost of the machining design to build (``result.built``); bought parts, given to this job, are not priced
        in it (a design with bought parts prices them: ``PartsToleranceAllocation.cost``)."""
        return float(self.result.built.cost)

    @property
    def demonstrated(self) -> bool:
        """The acceptance test demonstrates conformance (ISO 14253-1) at every statistic and test pose."""
        return self.ok and self.prediction.demonstrated

    def headline(self) -> list[str]:
        d = self.result.built
        return [f"robot {self.test.robot.name}: " + "; ".join(r.text() for r in self.requirements),
                f"design {d.label}, cost {d.cost:.4g}" if d.t is not None else f"status {self.result.status}",
                "conformance demonstrated by the test" if self.demonstrated else
                ("met, not demonstrated by the test" if self.ok else "not met")]

    def to_frame(self):
        """The tolerance table of the design to build (:meth:`AllocationResult.to_frame`)."""
        return self.result.to_frame()

    def datasheet(self):
        """The predicted test as a datasheet (:meth:`AcceptancePrediction.to_frame`)."""
        return None if self.prediction is None else self.prediction.to_frame()

    def text(self) -> str:
        out = ["\n".join(self.headline()), self.result.message or ""]
        if self.inputs.get("parts"):
            out.append("bought parts in the test, their effects under the test load included: "
                       + ", ".join(dict.fromkeys(self.inputs["parts"].values())))
        if self.prediction is not None:
            out.append(self.prediction.text())
        if self.simulation is not None:
            out.append(f"simulated test ({self.simulation.n_robots} robots, seed {self.simulation.seed}): share of "
                       "robots meeting each limit (worst test pose) " + ", ".join(
                           f"{k} {v.min():.3f}" for k, v in self._sim_share().items()))
        if self.compliance is not None:
            from tolalloc.acceptance.static_load import LOAD_DIRECTIONS

            c = self.compliance
            out.append(f"static compliance at P1 (ISO 9283 10; predicted from the parts, loads up to "
                       f"{c.loads_n[-1]:.4g} N): " + ", ".join(
                           f"{d} {1000 * v:.3g}" for d, v in zip(LOAD_DIRECTIONS, c.compliance_mm_per_n)) + " um/N")
        return "\n".join(x for x in out if x)

    def _sim_share(self) -> dict:
        s = self.simulation
        return {k: np.mean(s.robot[k] <= s.requirements[k].limit, axis=0) for k in s.robot}

    def summary(self) -> dict:
        d = self.result.built
        out = {"inputs": self.inputs, "status": self.result.status, "design": d.label, "cost": d.cost,
               "met": self.ok, "demonstrated": self.demonstrated, "times_s": self.times_s,
               "allocation": self.result.summary()}
        if self.prediction is not None:
            out["datasheet"] = self.datasheet().to_dict(orient="records")
            out["notes"] = list(self.prediction.notes)
        if self.simulation is not None:
            out["simulated_share_meeting"] = {k: v.tolist() for k, v in self._sim_share().items()}
        if self.compliance is not None:
            from tolalloc.acceptance.static_load import LOAD_DIRECTIONS

            out["static_compliance_mm_per_N"] = dict(zip(LOAD_DIRECTIONS, self.compliance.compliance_mm_per_n))
        return json_native(out)

    def plot_acceptance(self, ax=None):
        """The predicted statistics beside the simulated robots, per test pose (one panel per statistic); returns the
        axes (:func:`tolalloc.report.plots.acceptance.plot_acceptance`)."""
        from tolalloc.report.plots.acceptance import plot_acceptance

        if self.prediction is None:
            raise ArgumentError("prediction", f"no design was found ({self.result.message}): nothing to plot.")
        return plot_acceptance(self.prediction, self.simulation, ax=ax)

    def check_savable(self) -> None:
        if self.prediction is None:
            raise ArgumentError("directory", f"nothing to save: no design was found ({self.result.message}).")

    def write_files(self, folder, *, report: bool = False) -> list[str]:
        """``tolerances.csv/.md/.tex``, ``datasheet.csv/.md``, ``simulation.csv``, ``static_compliance.csv`` (with the
        parts), ``summary.json`` and ``acceptance.png`` into an existing ``folder`` (not atomic: :meth:`save`
        publishes them together)."""
        import matplotlib.pyplot as plt

        from tolalloc.report.plots import fit_layout
        from tolalloc.report.plots.acceptance import plot_acceptance
        from tolalloc.report.tables import write_tables

        tmp = Path(folder)
        write_tables(self.to_frame(), tmp, caption=f"Tolerances of {self.test.robot.name}: " + "; ".join(
            r.text() for r in self.requirements), note=f"design: {self.result.built.label}")
        ds = self.datasheet()
        ds.to_csv(tmp / "datasheet.csv", index=False, float_format="%.6g")
        (tmp / "datasheet.md").write_text(self.prediction.text() + "\n\n" + ds.to_markdown(index=False) + "\n")
        names = ["tolerances.csv", "tolerances.md", "tolerances.tex", "datasheet.csv", "datasheet.md"]
        if self.simulation is not None:
            self.simulation.to_frame().to_csv(tmp / "simulation.csv", index=False, float_format="%.6g")
            names.append("simulation.csv")
        if self.compliance is not None:
            self.compliance.to_frame().to_csv(tmp / "static_compliance.csv", index=False, float_format="%.6g")
            names.append("static_compliance.csv")
        write_json(self.summary(), tmp / "summary.json")
        axes = plot_acceptance(self.prediction, self.simulation)
        fig = np.atleast_1d(axes)[0].figure
        fit_layout(fig)
        fig.savefig(tmp / "acceptance.png", dpi=100)
        plt.close(fig)
        return names + ["summary.json", "acceptance.png"]
