"""The command that reproduces a result, as a ``tolalloc`` command line and as the Python call.

Built from the result's ``inputs`` record and, for options the record does not hold, from what the result itself
shows (the problem's requirement and cost model, the error model's options, the checks that ran). Options that
neither holds are named in the notes, so the reader knows the command takes their defaults.
"""

from __future__ import annotations

import shlex

from tolalloc.report.html_diagnosis import row_ranges_text

__all__ = ["allocation_command", "diagnosis_command"]

#: keyword argument -> command-line flag, for the options whose names differ only in spelling
_FLAG = {"radius_mm": "--radius-mm", "prob": "--prob", "region": "--region", "poses": "--poses", "costs": "--costs",
         "z": "--z", "uniform": "--uniform", "sigma_set": "--sigma-set", "link_mode": "--link-mode",
         "deflection_mode": "--deflection-mode", "clearance": "--clearance", "angle_radius_deg": "--angle-radius-deg",
         "angle_prob": "--angle-prob", "solver": "--solver", "calibration": "--calibration", "n_mc": "--n-mc",
         "seed": "--seed", "estimator": "--estimator", "coverage_n": "--coverage-n",
         "correction_rounds": "--correction-rounds",
         "angle_step_deg": "--angle-step-deg", "tool": "--tool", "trust_units": "--trust-units",
         "exclude": "--exclude", "test": "--test", "test_frame": "--test-frame", "register_n": "--register-n",
         "register_rows": "--register-rows",
         "register_update": "--register-update", "folds": "--folds", "alpha": "--alpha", "cv_rows": "--cv-rows", "gap_split": "--gap-split",
         "train": "--train", "robust_loss": "--robust-loss", "instrument_noise_mm": "--instrument-noise-mm"}
#: boolean keyword arguments whose command-line flag switches them off
_NEGATED = {"verify": "--no-verify", "correction": "--no-correction", "snap": "--no-snap"}


def _robot_argument(name: str, notes: list) -> str:
    from tolalloc.robot.io.load import builtin_robots

    if name in builtin_robots():
        return name
    notes.append(f"Robot {name!r} was given as a robot file or a Robot object: put its path in place of ROBOT_FILE.")
    return "ROBOT_FILE"


def _cli_value(v) -> str:
    if isinstance(v, float):
        short = f"{v:g}"
        return short if float(short) == v else repr(v)
    return str(v)


def _cli_args(kw: dict) -> list[str]:
    args = []
    for k, v in kw.items():
        if k in _NEGATED:
            args += [] if v else [_NEGATED[k]]
        elif isinstance(v, bool):
            args += [_FLAG[k]] if v else []
        elif isinstance(v, (list, tuple)):
            for item in v:
                args += [_FLAG[k], _cli_value(item)]
        else:
            args += [_FLAG[k], _cli_value(v)]
    return args


def _py(v) -> str:
    return repr(float(v)) if isinstance(v, float) else repr(v)


def _render(command: str, function: str, robot: str, kw: dict, out_flags: list[str], save: str) -> tuple[str, str]:
    from tolalloc.workflows.keywords import grouped_call

    cli = shlex.join(["tolalloc", command, robot, *_cli_args(kw), *out_flags])
    return cli, f"import tolalloc\n\nresult = {grouped_call(function, [robot], kw)}\n{save}"


def _where(job, notes: list) -> dict:
    """``region`` / ``poses`` keyword giving the same poses."""
    robot, label = job.robot, job.label
    if getattr(job, "region", None) is not None:
        return {"region": label}
    if label == "nominal" or label in robot.pose_sets:
        return {"poses": label}
    if label.lower().endswith(".csv"):
        return {"region": label}
    notes.append("The poses were given as an array: write them to a CSV file (q1..qN per row, deg / mm) and put "
                 "its path in place of POSES.csv.")
    return {"region": "POSES.csv"}


def allocation_command(job) -> tuple[str, str, list[str]]:
    """``(command line, Python call, notes)`` reproducing a :class:`ToleranceAllocation` or
    :class:`CalibratedToleranceAllocation` (with ``report.html`` into ``DIR``)."""
    inp, pr = job.inputs, job.problem
    notes = []
    robot = _robot_argument(inp.get("robot", job.robot.name), notes)
    kw = {**_where(job, notes), "radius_mm": float(pr.radius_mm), "prob": float(pr.prob)}
    if pr.angle_radius_rad is not None:
        import numpy as np

        kw |= {"angle_radius_deg": float(np.rad2deg(pr.angle_radius_rad)), "angle_prob": float(pr.angle_prob)}
    if inp.get("costs") not in (None, "defaults"):
        kw["costs"] = str(inp["costs"])
    if pr.costs.distribution == "uniform":
        kw["uniform"] = True
    elif kw.get("costs") is not None or abs(pr.costs.z - 3.0) > 1e-12:
        kw["z"] = float(pr.costs.z)
    labels = pr.model.labels
    kw["sigma_set"] = labels["sigma_set"]
    kw |= {k: labels[k] for k, d in (("link_mode", "consistent"), ("deflection_mode", "screw")) if labels[k] != d}
    if any(str(k).startswith("clearance") for k in pr.model.kinds):
        kw["clearance"] = True
    kw |= _allocation_checks(job, inp, notes)
    for key in ("exclude", "tool", "trust_units"):
        if inp.get(key):
            kw[key] = inp[key]
    if "exclude" not in inp:
        notes.append("Parameters left out of the error model (exclude) are not recorded in the result: add "
                     "--exclude NAME for each one that was left out.")
    cli, python = _render("allocate", "allocate_tolerances", robot, kw, ["--report", "DIR"],
                          "result.save('DIR', report=True)")
    return cli, python, notes


def _allocation_checks(job, inp: dict, notes: list) -> dict:
    """Solver, snapping, calibration plan, verification, estimator, correction and coverage options (from the inputs
    record; what the result shows where a record lacks one)."""
    kw = {}
    if inp.get("solver", "exact") != "exact":
        kw["solver"] = inp["solver"]
    calibration = inp.get("calibration")
    if calibration is not None and getattr(job, "plan_file", "") is None:  # a plan_calibration result, not a file
        kw["calibration"] = "PLAN.csv"
        notes.append("The calibration plan was given as a plan_calibration result, not a file: save it "
                     "(plan.save_plan('PLAN.csv')) and put its path in place of PLAN.csv.")
    elif calibration is not None:
        kw["calibration"] = str(calibration)
    snap = inp.get("snap", getattr(job.result, "standard", "n/a") is not None)
    if not snap:
        kw["snap"] = False
    verified = inp.get("n_mc") is not None
    if not verified:
        kw["verify"] = False
    else:
        kw["n_mc"] = int(inp["n_mc"])
        kw["estimator"] = str(inp.get("estimator", "auto"))
    kw["seed"] = int(inp.get("seed", 0))
    _correction(job, inp, verified, kw, notes)
    if inp.get("coverage_n") is not None:
        kw["coverage_n"] = int(inp["coverage_n"])
    elif "coverage_n" not in inp and getattr(job, "coverage", None) is not None:
        kw["coverage_n"] = int(job.coverage.n)
    if inp.get("angle_step_deg") is not None:
        kw["angle_step_deg"] = float(inp["angle_step_deg"])
    return kw


def _correction(job, inp: dict, verified: bool, kw: dict, notes: list) -> None:
    """``correction`` / ``correction_rounds`` into ``kw``: none for a calibration-aware allocation (no loop), the
    round limit whenever a verification with the loop on could use it."""
    ver, corr = getattr(job, "verification", None), getattr(job, "correction", None)
    if "correction" in inp:
        on = inp["correction"]
        if on is False:
            kw["correction"] = False
    else:  # a record without it: the loop was off if a pose was not demonstrated and nothing was corrected
        on = not (ver is not None and corr is None and ver.verdict != "demonstrated")
        if not on:
            kw["correction"] = False
    if on and verified and inp.get("correction_rounds") is not None:
        kw["correction_rounds"] = int(inp["correction_rounds"])
    elif on and corr is not None and "correction_rounds" not in inp:
        notes.append(f"The round limit of the correction loop is not recorded; {corr.rounds} round(s) ran "
                     "(the default limit is 2).")


def diagnosis_command(job) -> tuple[str, str, list[str]]:
    """``(command line, Python call, notes)`` reproducing a :class:`MeasurementDiagnosis` (report into ``DIR``)."""
    d, inp = job.diagnosis, job.inputs
    notes = []
    robot = _robot_argument(inp.get("robot", d.robot.name), notes)
    kw = {"train": _measurement_path(d.train.source, "TRAIN.csv", notes)}
    if d.test is not None:
        kw["test"] = _measurement_path(d.test.source, "TEST.csv", notes)
    if d.test_frame != "same":
        kw["test_frame"] = d.test_frame
        if inp.get("register_n") is not None:
            kw["register_n"] = inp["register_n"]
        if inp.get("register_rows") is not None:
            kw["register_rows"] = [int(r) for r in inp["register_rows"]]
        if inp.get("register_update") is not None:
            kw["register_update"] = inp["register_update"]
    kw["folds"] = int(inp.get("folds", job.folds))
    for key, default in (("alpha", 0.01), ("seed", 0)):
        if key in inp:
            kw[key] = inp[key]
        else:
            notes.append(f"{key} is not recorded in the result; the command uses the default {default}.")
    for key in ("cv_rows", "tool"):
        if inp.get(key) is not None:
            kw[key] = inp[key]
    if job.gap is not None:
        kw["gap_split"] = True
    if inp.get("trust_units"):
        kw["trust_units"] = True
    if inp.get("robust_loss", "auto") != "auto":
        kw["robust_loss"] = inp["robust_loss"]
    if inp.get("instrument_noise_mm") is not None:
        kw["instrument_noise_mm"] = inp["instrument_noise_mm"]
    offset = {k: inp[k] for k in ("target_offset_mm", "target_offset_sd_mm") if inp.get(k) is not None}
    train = kw.pop("train")
    extra = ([] if "target_offset_mm" not in offset else
             ["--target-offset-mm", *(_cli_value(float(v)) for v in offset["target_offset_mm"])])
    extra += [] if "target_offset_sd_mm" not in offset else [
        "--target-offset-sd-mm", *(_cli_value(float(v)) for v in _as_list(offset["target_offset_sd_mm"]))]
    kw.update(offset)
    cli_kw = {k: v for k, v in kw.items() if k not in offset}
    if "register_rows" in cli_kw:
        cli_kw["register_rows"] = row_ranges_text(cli_kw["register_rows"])
    cli = shlex.join(["tolalloc", "diagnose", robot, "--train", train, *_cli_args(cli_kw), *extra, "--report", "DIR"])
    from tolalloc.workflows.keywords import grouped_call

    python = (f"import tolalloc\n\nresult = {grouped_call('diagnose_measurements', [robot, train], kw)}\n"
              "result.save('DIR', report=True)")
    return cli, python, notes


def _measurement_path(source: str, placeholder: str, notes: list) -> str:
    if str(source).endswith("(DataFrame)"):
        notes.append(f"The measurements {source} were given as a DataFrame: save it as CSV and put its path in place "
                     f"of {placeholder}.")
        return placeholder
    return str(source)


def _as_list(value) -> list:
    """A recorded number or list of numbers as a list."""
    return [value] if isinstance(value, (int, float)) else list(value)
