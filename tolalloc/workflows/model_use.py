"""Using an identified model: predictions in interface units, compensation of a program, the exported robot files.

* :func:`predict_frame` -- the identified model's target points at joint values given in deg / mm (with the
  covariates its effects read), with their predicted uncertainty;
* :func:`compensate_program` (job; ``tolalloc compensate``) -- a program's joint values compensated so that the target
  point lands where the nominal robot would have put it (or on given targets), from a diagnosis
  (:class:`~tolalloc.workflows.MeasurementDiagnosis`) or from an exported model file (``identified.toml``);
  :class:`CompensationResult` is its result;
* :func:`export_files` -- ``identified.toml`` (chain layout with the ``[identified]`` section) and
  ``identified.urdf`` (:mod:`tolalloc.diagnose.model_export`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError, InputFileError, TolallocError
from tolalloc.outputs import check_distinct_outputs, json_native, output_group, write_json
from tolalloc.workflows import inputs
from tolalloc.workflows.base import JobResult

__all__ = ["predict_frame", "read_program", "compensate_program", "CompensationResult", "export_files",
           "load_identified", "save_result", "COVARIATES"]

#: Covariate columns a program or a prediction may carry (besides dir1..dirN).
COVARIATES = ("payload_kg", "temperature_c", "time_s")


def save_result(result, directory, json=None) -> list[Path]:
    """``result.write_files`` into ``directory`` (created; all files published together or none) and / or its JSON
    summary to ``json`` (``"-"``: standard output); the paths written."""
    if directory is None and json is None:
        raise ArgumentError("directory", "nothing to save: expected a directory to write into (a str or "
                            "pathlib.Path), and / or json=FILE ('-' for standard output).")
    directory = result.check_out(directory, "directory")
    to_stdout = isinstance(json, str) and json == "-"
    json_path = None if to_stdout else result.check_out(json, "json", directory=False)
    check_distinct_outputs([("directory", directory), ("json", json_path)])
    written = []
    with output_group() as group:
        if directory is not None:
            written += [directory / nm for nm in result.write_files(group.directory(directory))]
        if json_path is not None:
            write_json(result.summary(), group.file(json_path))
            written.append(json_path)
    if to_stdout:
        write_json(result.summary(), "-")
    return written


def _frame_of(program, argument: str) -> pd.DataFrame | None:
    """A DataFrame of a CSV path or a DataFrame; None for an array-like."""
    return inputs.read_table(program, argument, "a CSV with one row per pose: a column per joint (q1_deg ...), "
                             "optional x_mm, y_mm, z_mm targets and the covariates (payload_kg, temperature_c, "
                             "time_s, dir1..dirN)")


def _numeric(frame: pd.DataFrame, col: str, argument: str) -> np.ndarray:
    v = pd.to_numeric(frame[col], errors="coerce").to_numpy(dtype=float)
    if not np.all(np.isfinite(v)):
        row = int(np.flatnonzero(~np.isfinite(v))[0]) + 1
        raise ArgumentError(argument, f"column {col!r}, row {row}: expected a finite number, got "
                            f"{frame[col].iloc[row - 1]!r}.")
    return v


def read_program(robot, program, argument: str = "program") -> dict:
    """Joint values, optional targets and covariates of a program.

    ``program``: a CSV path or DataFrame (a column per joint in deg / mm, optional ``x_mm, y_mm, z_mm`` targets,
    ``payload_kg``, ``temperature_c``, ``time_s``, ``dir1..dirN``, a process wrench ``force_x_n`` ... ``torque_z_nm``;
    a table of ``x_mm, y_mm, z_mm`` alone: targets without joint values), or joint values (P, n) [deg / mm]. Returns
    ``{"q": (P, n) [rad, mm] or None, "targets_mm": (P, 3) or None, "covariates": {name: (P,)}, "direction": (P, n) or None,
    "columns": joint column names or None, "wrench": (P, 6) or None}``.
    """
    frame = _frame_of(program, argument)
    if frame is None:
        return {"q": inputs.joint_values(robot, program, argument), "targets_mm": None, "covariates": {},
                "direction": None, "columns": None}
    if not len(frame):
        raise ArgumentError(argument, "expected at least one row (pose), got none.")
    from tolalloc.robot.columns import find_joint_columns

    xyz = [c for c in ("x_mm", "y_mm", "z_mm") if c in frame.columns]
    if xyz and len(xyz) < 3:
        raise ArgumentError(argument, f"targets need all of x_mm, y_mm, z_mm; got only {', '.join(xyz)}.")
    try:
        cols = find_joint_columns(robot, frame.columns, argument)
    except TolallocError:
        if len(xyz) < 3 or any(str(c).startswith("q") for c in frame.columns):
            raise
        cols = None  # targets only: the seeds come from the nominal robot's inverse kinematics
    q = None if cols is None else inputs.joint_values(robot, frame, argument)
    targets = np.column_stack([_numeric(frame, c, argument) for c in xyz]) if xyz else None
    cov = {c: _numeric(frame, c, argument) for c in COVARIATES if c in frame.columns}
    dirs = [f"dir{j + 1}" for j in range(robot.n_joints)]
    present = [c for c in dirs if c in frame.columns]
    if present and len(present) < len(dirs):
        raise ArgumentError(argument, f"approach directions need all of dir1..dir{robot.n_joints}; got "
                            f"{', '.join(present)}.")
    direction = np.column_stack([_numeric(frame, c, argument) for c in dirs]) if present else None
    from tolalloc.diagnose.measurements import read_wrench

    wrench = read_wrench(list(frame.columns), lambda c: _numeric(frame, c, argument), argument)
    return {"q": q, "targets_mm": targets, "covariates": cov, "direction": direction, "columns": cols,
            "wrench": wrench}


def _meas(model, prog: dict, q=None):
    """The model's measurement set of a program's poses (or ``q``) and covariates."""
    c = prog["covariates"]
    return model.measurements(prog["q"] if q is None else q, payload_kg=c.get("payload_kg"), temperature_c=c.get("temperature_c"),
                              time_s=c.get("time_s"), direction=prog["direction"], wrench=prog.get("wrench"))


def predict_frame(model, q, *, frame: str = "base", robot=None, without=(), **covariates) -> pd.DataFrame:
    """Predicted target points of ``model`` (a diagnosis, its :class:`~tolalloc.diagnose.model_use.IdentifiedModel`
    or an exported ``identified.toml``, whose nominal robot ``robot`` defaults to the built-in one it names) at ``q``
    (a program as :func:`read_program` takes it; ``covariates``: ``payload_kg``, ``temperature_c``, ``time_s``,
    ``dir`` arrays and ``wrench`` (P, 6) [N, N m], beside or instead of the program's columns): ``row``,
    ``x_mm, y_mm, z_mm`` in ``frame``, and where the model holds its parameter covariance (a diagnosis's, or one read
    from a file exported with it) ``sigma_mm`` (1-sigma of the 3-D prediction error) and ``radius95_mm`` (the radius
    holding a measurement with 95 % probability, measurement noise included); ``without``: effects of a file left out
    (as :func:`compensate_program`)."""
    from tolalloc.linear.probability import radius_for_prob

    model = _identified(model, robot, without)[0]
    prog = read_program(model.robot, q, "q")
    for k, v in covariates.items():
        if v is None:
            continue
        if k == "dir":
            prog["direction"] = v
        elif k == "wrench":
            prog["wrench"] = v
        elif k in COVARIATES:
            prog["covariates"][k] = v
        else:
            raise ArgumentError(k, f"expected one of the covariates {', '.join(COVARIATES)}, dir, wrench; got {k!r}.")
    meas = _meas(model, prog)
    x = model.points(meas, frame)
    out = pd.DataFrame({"row": np.arange(1, len(x) + 1), "x_mm": x[:, 0], "y_mm": x[:, 1], "z_mm": x[:, 2]})
    if model.cov is not None:
        C = model.point_covariance(meas, frame)
        out["sigma_mm"] = np.sqrt(np.trace(C, axis1=1, axis2=2))
        out["radius95_mm"] = radius_for_prob(C + model.noise_mm ** 2 * np.eye(3), 0.95)
    return out


@dataclass(frozen=True, eq=False, repr=False)
class CompensationResult(JobResult):
    """A compensated program (:func:`compensate_program`).

    Attributes
    ----------
    compensation : Compensation   (:class:`tolalloc.diagnose.compensate.Compensation`)
    columns : list of str or None  the program's joint column names (the output keeps them)
    inputs : dict
    """

    compensation: object
    columns: list | None = None
    inputs: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return bool(self.compensation.ok.all())

    def headline(self) -> list[str]:
        c = self.compensation
        n, bad = len(c.q), int((~c.ok).sum())
        dq = np.abs(self.compensation.robot.q_to_interface(c.q - c.q_seed))[c.ok]
        lines = [f"robot: {c.robot.name}   {n} targets, frame {c.frame}",
                 f"compensated: {n - bad}   refused: {bad}"
                 + ("" if not len(dq) else f"   largest joint correction {dq.max():.4g} (deg / mm)")]
        lines += [f"left out of the model: {e} ({v}): its part of the error is not compensated"
                  for e, v in self.inputs.get("left_out", {}).items()]
        return lines

    def to_frame(self) -> pd.DataFrame:
        """One row per target: compensated joint values, corrections, target, model point, error, status, reason."""
        return self.compensation.to_frame(self.columns)

    def refused_lines(self) -> list[str]:
        """One line per refused row: its number (from 1), status and reason."""
        c = self.compensation
        return [f"row {i + 1}: {c.status[i]}: {c.reason[i]}" for i in np.flatnonzero(~c.ok)]

    def summary(self) -> dict:
        c = self.compensation
        return json_native({"robot": c.robot.name, "frame": c.frame, "targets": len(c.q),
                            "compensated": int(c.ok.sum()),
                            "refused": [{"row": int(i + 1), "status": c.status[i], "reason": c.reason[i]}
                                        for i in np.flatnonzero(~c.ok)],
                            "max_error_mm": float(c.error_mm[c.ok].max()) if c.ok.any() else None,
                            "tol_mm": c.tol_mm, "inputs": self.inputs})

    def text(self) -> str:
        return "\n".join(self.headline() + self.refused_lines())

    def write_files(self, folder, *, report: bool = False) -> list[str]:
        """``compensated.csv`` (:meth:`to_frame`) into an existing ``folder``; the names written. Thirteen significant
        digits: a joint value in degrees read back from the file lands within 1e-9 mm of the solution at 2 m reach,
        below the solver's 1e-6 mm tolerance."""
        self.to_frame().to_csv(Path(folder) / "compensated.csv", index=False, float_format="%.13g")
        return ["compensated.csv"]

    def save(self, directory=None, *, json=None) -> list[Path]:
        """Write ``compensated.csv`` into ``directory`` and / or the JSON summary to ``json``; the paths written."""
        return save_result(self, directory, json)

    def plot_corrections(self, ax=None):
        """The joint corrections of every compensated row (deg / mm), one line per joint; draws into ``ax`` or a new
        figure and returns the Axes."""
        from tolalloc.report.plots.diagnose import plot_corrections

        return plot_corrections(self.compensation, ax=ax)


def _identified(model, robot, without=()) -> tuple:
    """``(IdentifiedModel, what it came from)`` of a diagnosis, an identified model or an exported file's path (less
    the effects ``without``, for a file)."""
    from tolalloc.diagnose.model_use import IdentifiedModel

    without = _without(without)
    if without and not isinstance(model, (str, os.PathLike)):
        raise ArgumentError("without", "leaves effects out of an exported identified.toml; a diagnosis or an "
                            "IdentifiedModel holds its training session and is used whole.")
    if isinstance(model, IdentifiedModel):
        return model, "IdentifiedModel"
    if hasattr(model, "identified_model"):
        return model.identified_model(), "MeasurementDiagnosis"
    if isinstance(model, (str, os.PathLike)):
        return load_identified(model, robot, without=without), str(model)
    raise ArgumentError("model", f"expected a MeasurementDiagnosis, an IdentifiedModel or the path of an exported "
                        f"identified.toml, got {inputs.shown(model)}.")


def _without(without) -> tuple:
    """``without`` (an effect name or several) as a tuple of names."""
    if isinstance(without, str):
        return (without,)
    if without is None:
        return ()
    try:
        names = tuple(without)
    except TypeError:
        names = None
    if names is None or not all(isinstance(w, str) for w in names):
        raise ArgumentError("without", f"expected an effect name or a sequence of them (e.g. 'thermal'), got "
                            f"{inputs.shown(without)}.")
    return names


def load_identified(path, robot=None, *, without=()):
    """The identified model of an exported ``identified.toml`` (:mod:`tolalloc.diagnose.model_export`); ``robot``: the
    nominal robot (default: the built-in robot the file names); ``without``: effects of the file left out (one
    bound to the training session, such as a thermal history variant, can only be read so)."""
    import tomllib

    from tolalloc.diagnose.model_export import model_from_identified

    p = Path(path)
    if not p.is_file():
        raise InputFileError(f"identified model file {str(path)!r} does not exist; expected the identified.toml a "
                             "diagnosis exported (MeasurementDiagnosis.export_model, tolalloc diagnose "
                             "--export-model).")
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise InputFileError(f"identified model file {str(path)!r}: not valid TOML ({exc}).") from None
    section = data.get("identified")
    if section is None:
        raise InputFileError(f"identified model file {str(path)!r} has no [identified] section; expected the "
                             "identified.toml a diagnosis exported, not a plain robot file.")
    rob = inputs.as_robot(section.get("nominal_robot") if robot is None else robot)
    model = model_from_identified(section, rob, _without(without))
    _check_chain(data, model, path)
    return model


def _check_chain(data: dict, model, path) -> None:
    """The file's ``[[chain]]`` (what ``load_robot`` reads) must be the geometry its ``[identified]`` section gives
    (the compensation uses the section): the two forward kinematics agree to 1e-6 mm at the zero pose and at random
    poses within the limits, else the file was altered."""
    from tolalloc.diagnose.model_export import identified_robot_dict
    from tolalloc.robot.io.load import robot_from_dict

    try:
        chain = robot_from_dict(data, str(path))
    except TolallocError as exc:
        raise InputFileError(f"identified model file {str(path)!r}: its [[chain]] cannot be read ({exc}).") from None
    ident = robot_from_dict(identified_robot_dict(model), "rebuilt")
    if chain.n_joints != ident.n_joints:
        raise InputFileError(f"identified model file {str(path)!r}: its [[chain]] has {chain.n_joints} joints, its "
                             f"[identified] section {ident.n_joints}; the file was altered -- export the model again.")
    q = np.vstack([np.zeros(ident.n_joints), ident.random_q(np.random.default_rng(0), 8)])
    gap = float(np.abs(chain.fk_internal(q)[:, :3, 3] - ident.fk_internal(q)[:, :3, 3]).max())
    if gap > 1e-6:
        raise InputFileError(f"identified model file {str(path)!r}: its [[chain]] and its [identified] section give "
                             f"forward kinematics {gap:.3g} mm apart (the compensation uses the section); the file was "
                             "altered -- export the model again.")


@inputs.job_entry
def compensate_program(model, program, *, robot=None, frame: str = "base", tol_mm: float = 1e-6,
                       without=(), trust_units: bool = False) -> CompensationResult:
    """Compensate a program with an identified model.

    Parameters
    ----------
    model : MeasurementDiagnosis, IdentifiedModel, or str / path
        The diagnosis, its identified model, or an exported ``identified.toml``.
    program : str, path, DataFrame or array
        One row per pose: the program's joint values (deg / mm; the seeds), optional ``x_mm, y_mm, z_mm`` targets
        (default: where the nominal robot puts the target point at those joint values) and the covariates the model's
        effects read (``payload_kg``, ``temperature_c``, ``time_s``, ``dir1..dirN``, a process wrench ``force_x_n`` ...
        ``torque_z_nm``). Targets without joint values
        are seeded by the nominal robot's inverse kinematics (a position has many joint solutions: give the
        program's joint values where there are some).
    robot : str, path or Robot, optional
        The nominal robot of an exported model file (default: the built-in robot it names).
    frame : {"base", "tracker"}
        The frame of the targets: the robot's base frame, or the training file's measurement frame.
    tol_mm : float
        Distance below which a target counts as reached.
    without : str or sequence of str
        Effects of an exported model file left out (an effect bound to the training session -- a thermal history
        variant, a creeping mount -- can only be read so): the identified geometry and the other effects are used,
        the left-out effect's part of the error is not compensated (the result says so).

    Returns
    -------
    CompensationResult
        Rows outside the reachable space or whose correction leaves the joint limits are refused (status, reason).
    """
    from tolalloc.diagnose.compensate import compensate
    from tolalloc.diagnose.model_use import FRAMES

    inputs.check_choice(frame, "frame", FRAMES)
    tol_mm = inputs.check_positive(tol_mm, "tol_mm", "mm", "1e-6")
    ident, source = _identified(model, robot, without)
    prog = read_program(ident.robot, program)
    try:
        q0 = prog["q"] if prog["q"] is not None else np.zeros((len(prog["targets_mm"]), ident.robot.n_joints))
        comp = compensate(ident, prog["q"], prog["targets_mm"], _meas(ident, prog, q0), frame=frame, tol_mm=tol_mm)
    except TolallocError as exc:
        raise ArgumentError("program", str(exc)) from None
    shown = program if isinstance(program, (str, os.PathLike)) else type(program).__name__
    record = {"model": source, "program": shown,
              "frame": frame, "tol_mm": tol_mm, "targets": "given" if prog["targets_mm"] is not None else
              "nominal robot at the program's joint values",
              **({"left_out": dict(ident.ref["left_out"])} if (ident.ref or {}).get("left_out") else {})}
    return CompensationResult(comp, prog["columns"], json_native({k: str(v) if isinstance(v, os.PathLike) else v
                                                                   for k, v in record.items()}))


def export_files(model, folder, name: str | None = None) -> list[str]:
    """``identified.toml`` and ``identified.urdf`` of ``model`` into an existing ``folder``; the names written."""
    import tomli_w

    from tolalloc.diagnose.model_export import identified_robot_dict, identified_urdf

    folder = Path(folder)
    (folder / "identified.toml").write_text(tomli_w.dumps(identified_robot_dict(model, name)), encoding="utf-8")
    (folder / "identified.urdf").write_text(identified_urdf(model, name), encoding="utf-8")
    return ["identified.toml", "identified.urdf"]
