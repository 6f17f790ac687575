"""Export of an identified model (:class:`~tolalloc.diagnose.model_use.IdentifiedModel`) as robot files, and its
rebuild from the exported TOML.

* **TOML chain layout** (:func:`identified_robot_dict`): the identified geometry as ``[[chain]]`` links and joints --
  every joint axis where the diagnosis put it, the joint offsets folded into the geometry (``exp(S (q + d))`` is
  ``exp(S q) exp(S d)``, and ``exp(S d)`` is carried to the right through the rest of the chain, turning every later
  screw by its adjoint), the tool point at the measured target (the fitted probe offset). Its forward kinematics is
  the identified geometry's (without effects); ``tolalloc.load_robot`` reads it.
* **URDF** (:func:`identified_urdf`): the same chain, one link frame per joint (base-aligned at the zero
  configuration, at the joint's point), a fixed ``tool`` link at the target point.
* The **[identified] section** of the TOML (ignored by the kinematics; :data:`FORMAT`): the nominal robot's name, the
  probe offset, the training file's registration, the diagnosis's geometric parameters, and the non-geometric
  effects as their fitted parameters -- per effect the variant, the column names (with their units) and values --
  with the training file's reference values (mean temperature, time origin, load scale per joint, gear ratios)
  the effects' columns are computed from, and the parameters' covariance (``[identified.covariance]``: the
  parameters' names and the matrix, registration and probe offset first) where the model has one.
  :func:`model_from_identified` rebuilds the identified model from it and the nominal robot, so a program can be
  compensated -- and its predictions given their uncertainty -- from the file alone; thermal variants driven by the
  training file's history (``lag``, ``activity``, ``motor``, ``tilt``, ``held``), a mount creeping under the history
  of its load (``creep_<tau>min``, ``flow``), the seats of its tool changes
  (backlash ``reseat``) and the zeros of its power cycles (transmission ``rehome``) are recorded but cannot be rebuilt
  from the file (:func:`session_bound`): such a file is read with the effect left out (``without``) or not at all.

The joint points are the points of the identified axes nearest the nominal joint points; where two nominal joint
points coincide and the identified axes are skew, the link between them is the axes' small distance (the robot-file
loader keeps such a sub-millimetre link in a file with an ``[identified]`` section; in a plain robot file it takes it
for a unit slip unless ``trust_units``).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from tolalloc.exceptions import TolallocError, check_finite_array
from tolalloc.robot.lie import adjoint, exp_se3
from tolalloc.robot.model import Robot
from tolalloc.physics.mount_creep import is_creep_variant
from tolalloc.diagnose.calibrate import Fit
from tolalloc.diagnose.geometry import build_geometry_model
from tolalloc.diagnose.model_use import IdentifiedModel

__all__ = ["FORMAT", "FRAMES", "check_section", "identified_geometry", "identified_robot_dict", "identified_urdf",
           "model_from_identified", "HISTORY_VARIANTS", "FIXED_PARAMETERS", "session_bound", "leave_out_advice"]

#: The ``format`` key of the ``[identified]`` section.
FORMAT = "tolalloc identified model 1"
#: The frames of the ``[identified]`` section's figures (written into it).
FRAMES = ("x_tracker = registration_rotation x_base + registration_translation_mm (base frame: the nominal robot's); "
          "target_offset_mm and basis_target_offset_mm in the flange frame; nominal_screws (unit axis, moment [mm]) and "
          "nominal_home_mm in the base frame at the zero configuration")
#: Thermal variants whose columns need the training file's history (not rebuilt from a file).
HISTORY_VARIANTS = ("lag", "activity", "motor", "tilt", "held", "scale_lag")


def identified_geometry(model: IdentifiedModel) -> tuple:
    """The identified chain without joint offsets and with the tool at the target point.

    Returns
    -------
    screws : array, shape (n, 6)   space screws at the zero configuration (offsets folded in)
    points : array, shape (n, 3) [mm]   a point on each joint axis (nearest the nominal joint point)
    home : array, shape (4, 4)     the target frame at the zero configuration (rotation: the flange's)
    """
    screws, home, dq = model.chain()
    E = np.eye(4)
    out = np.empty_like(screws)
    for j in range(len(screws)):
        out[j] = adjoint(E) @ screws[j]
        E = E @ exp_se3(screws[j] * dq[j])
    home = E @ home
    home[:3, 3] = home[:3, 3] + home[:3, :3] @ model.fit.t_mm
    points = np.empty((len(out), 3))
    nominal = model.robot.joint_points_mm
    for j, (s, jt) in enumerate(zip(out, model.robot.joints)):
        if jt.is_revolute:
            w = s[:3] / np.linalg.norm(s[:3])
            foot = np.cross(w, s[3:])
            points[j] = foot + np.dot(nominal[j] - foot, w) * w
        else:
            points[j] = nominal[j]
    return out, points, home


def _axis(s, revolute: bool) -> list:
    a = s[:3] if revolute else s[3:]
    return [float(v) for v in a / np.linalg.norm(a)]


def _limits(robot: Robot, j: int) -> dict:
    jt = robot.joints[j]
    if jt.is_revolute:
        return {"limits_rad": [float(jt.lower), float(jt.upper)], "nominal_rad": float(jt.nominal)}
    return {"limits_mm": [float(jt.lower), float(jt.upper)], "nominal_mm": float(jt.nominal)}


def identified_robot_dict(model: IdentifiedModel, name: str | None = None) -> dict:
    """The identified model as a chain-layout robot file (a dict for ``tomli_w``; module docstring)."""
    robot = model.robot
    screws, points, home = identified_geometry(model)
    chain, prev = [], np.zeros(3)
    for j, jt in enumerate(robot.joints):
        vec = points[j] - prev
        if np.any(vec):
            chain.append({"link": f"to_{jt.name}", "vector_mm": [float(v) for v in vec]})
        chain.append({"joint": jt.name, "type": "revolute" if jt.is_revolute else "prismatic",
                      "axis": _axis(screws[j], jt.is_revolute), **_limits(robot, j)})
        prev = points[j]
    chain.append({"link": "to_target", "vector_mm": [float(v) for v in home[:3, 3] - prev]})
    rpy = Rotation.from_matrix(home[:3, :3]).as_euler("xyz")
    return {"name": name or f"{robot.name}_identified",
            "description": f"Identified model of robot {robot.name!r} from a tolalloc diagnosis: the identified "
                           "geometry (joint offsets folded in), tool point at the measured target; the [identified] "
                           "section holds the fitted parameters and the non-geometric effects.",
            "gravity": [float(v) for v in robot.gravity], "chain": chain,
            "tool": {"offset_mm": [0.0, 0.0, 0.0], "rpy_rad": [float(v) for v in rpy]},
            "identified": identified_section(model)}


def identified_section(model: IdentifiedModel) -> dict:
    """The ``[identified]`` section (module docstring)."""
    fit = model.fit
    geo = [{"name": fit.model.params[k].name, "value": float(fit.delta[k]), "unit": fit.model.params[k].unit}
           for k in fit.geo_index]
    effects, a = [], 0
    for e in model.effects:
        names = [nm for nm in fit.effect_names if nm.startswith(f"{e}:")]
        effects.append({"effect": e, "variant": model.variants[e], "columns": list(model.columns[e]),
                        "fitted_columns": [nm.split(":", 1)[1] for nm in names],
                        "values": [float(v) for v in fit.beta[a:a + len(names)]]})
        a += len(names)
    ref = model.ref or {}
    reference = {k: v for k, v in (("temperature_c", ref.get("temperature_c")), ("time0_s", ref.get("time0_s")))
                 if v is not None}
    if ref.get("load_scale") is not None:
        reference["load_scale_per_joint"] = [float(v) for v in ref["load_scale"]]
    if ref.get("gear_ratio") is not None:
        reference["gear_ratio"] = [float(v) for v in ref["gear_ratio"]]
    return {"format": FORMAT, "nominal_robot": model.robot.name, "n_geometry": len(geo), "n_effects": len(effects),
            "frames": FRAMES,
            "nominal_screws": [[float(v) for v in row] for row in model.robot.screws],
            "nominal_home_mm": [[float(v) for v in row] for row in model.robot.home],
            "target_offset_mm": [float(v) for v in fit.t_mm],
            "basis_target_offset_mm": [float(v) for v in model.basis_t_mm],
            "registration_rotation": [[float(v) for v in row] for row in fit.R],
            "registration_translation_mm": [float(v) for v in fit.p_mm],
            "payload_in_training": bool(model.payload_in_training), "noise_mm": float(model.noise_mm),
            "geometry": geo, "effects": effects, "reference": reference,
            **({} if model.cov is None else {"covariance": _covariance_table(model)})}


#: Names of the parameter covariance's first nine rows (:func:`~.uncertainty.point_jacobian`'s columns).
FIXED_PARAMETERS = ("registration:rotation_x [rad]", "registration:rotation_y [rad]", "registration:rotation_z [rad]",
                    "registration:translation_x [mm]", "registration:translation_y [mm]",
                    "registration:translation_z [mm]", "target_offset:x [mm]", "target_offset:y [mm]",
                    "target_offset:z [mm]")


def _parameter_names(fit) -> list:
    """The covariance's parameters in its order: registration, probe offset, geometry (``fit.geo_index``), effects."""
    geo = [f"geometry:{fit.model.params[k].name} [{fit.model.params[k].unit}]" for k in fit.geo_index]
    return [*FIXED_PARAMETERS, *geo, *fit.effect_names]


def _covariance_table(model: IdentifiedModel) -> dict:
    """The parameter covariance with its parameters' names (rows and columns in that order)."""
    return {"parameters": _parameter_names(model.fit),
            "matrix": [[float(v) for v in row] for row in np.asarray(model.cov, float)]}


def _covariance(section: dict, fit, kept: np.ndarray) -> np.ndarray | None:
    """The parameter covariance of the section (None in a file written without one), checked against the file's
    parameters (the rebuilt fit's, with the left-out effects' parameters where ``kept`` is False): the same names in
    the same order, a symmetric matrix with a non-negative diagonal. Returns the kept parameters' block."""
    table = section.get("covariance")
    if table is None:
        return None
    names = _parameter_names(fit)
    n_fixed = len(names) - len(fit.effect_names)
    listed = table.get("parameters") if isinstance(table, dict) else None
    if not isinstance(listed, list) or len(listed) != n_fixed + len(kept) or \
            [nm for nm, k in zip(listed, [True] * n_fixed + list(kept)) if k] != names:
        raise TolallocError("identified model: the covariance's parameters are not the model's (registration, target "
                            "offset, geometry and effect parameters, in that order); the file was altered -- export "
                            "the model again.")
    n = len(listed)
    C = check_finite_array(table.get("matrix"), "identified model: covariance.matrix", (n, n))
    if np.abs(C - C.T).max() > 1e-9 * max(np.abs(C).max(), 1e-300) or np.any(np.diag(C) < 0):
        raise TolallocError("identified model: covariance.matrix is not a covariance (symmetric, non-negative "
                            "variances); the file was altered -- export the model again.")
    rows = np.flatnonzero(np.r_[np.ones(n_fixed, bool), kept])
    return C[np.ix_(rows, rows)]


def identified_urdf(model: IdentifiedModel, name: str | None = None) -> str:
    """The identified geometry as URDF text (metres, radians; module docstring)."""
    robot = model.robot
    screws, points, home = identified_geometry(model)
    nm = name or f"{robot.name}_identified"
    f = (lambda v: " ".join(repr(float(x)) for x in v))
    lines = ['<?xml version="1.0"?>', f'<robot name="{nm}">',
             "  <!-- identified geometry of a tolalloc diagnosis (joint offsets folded in; tool link at the measured "
             "target); the non-geometric effects are in the TOML export's [identified] section; joint limits: "
             "position from the robot file, effort and velocity 0 as placeholders (tolalloc does not know them: set "
             "them before a controller or planner reads them) -->",
             '  <link name="base_link"/>']
    parent, prev = "base_link", np.zeros(3)
    for j, jt in enumerate(robot.joints):
        child = f"{jt.name}_link"
        kind = "revolute" if jt.is_revolute else "prismatic"
        lo, hi = (jt.lower, jt.upper) if jt.is_revolute else (jt.lower / 1000.0, jt.upper / 1000.0)
        lines += [f'  <link name="{child}"/>', f'  <joint name="{jt.name}" type="{kind}">',
                  f'    <parent link="{parent}"/>', f'    <child link="{child}"/>',
                  f'    <origin xyz="{f((points[j] - prev) / 1000.0)}" rpy="0 0 0"/>',
                  f'    <axis xyz="{f(_axis(screws[j], jt.is_revolute))}"/>',
                  f'    <limit lower="{lo!r}" upper="{hi!r}" effort="0" velocity="0"/>', "  </joint>"]
        parent, prev = child, points[j]
    rpy = Rotation.from_matrix(home[:3, :3]).as_euler("xyz")
    lines += ['  <link name="tool"/>', '  <joint name="tool_fixed" type="fixed">', f'    <parent link="{parent}"/>',
              '    <child link="tool"/>', f'    <origin xyz="{f((home[:3, 3] - prev) / 1000.0)}" rpy="{f(rpy)}"/>',
              "  </joint>", "</robot>", ""]
    return "\n".join(lines)


def model_from_identified(section: dict, robot: Robot, without: tuple = ()) -> IdentifiedModel:
    """The identified model rebuilt from an ``[identified]`` section and the nominal ``robot``, with the parameter
    covariance where the file holds one (:meth:`~.model_use.IdentifiedModel.point_covariance`).

    ``without``: effects of the file left out of the model (their names; ``ref["left_out"]`` maps them to their
    variants). An effect bound to the training session (:func:`session_bound`) can only be rebuilt this way; the
    identified geometry and the other effects keep the values fitted beside it, and the covariance is the kept
    parameters' block (the left-out effect's part of the error is neither compensated nor in the uncertainty)."""
    if not isinstance(section, dict) or section.get("format") != FORMAT:
        raise TolallocError(f"identified model: expected an [identified] section with format = {FORMAT!r} (written "
                            "by a tolalloc export), got " + (repr(section.get("format")) if isinstance(section, dict)
                                                             else type(section).__name__) + ".")
    if section.get("nominal_robot") != robot.name:
        raise TolallocError(f"identified model: it was identified on robot {section.get('nominal_robot')!r}, the "
                            f"nominal robot given is {robot.name!r}; give the robot the diagnosis used.")
    check_section(section, robot)
    geo_model = build_geometry_model(robot)
    delta, idx = np.zeros(len(geo_model.params)), []
    for i, g in enumerate(section.get("geometry", [])):
        try:
            k = geo_model.index(g["name"])
        except Exception:
            raise TolallocError(f"identified model: geometric parameter {g.get('name')!r} is not one of robot "
                                f"{robot.name!r}'s; was the file written for another robot?") from None
        unit = geo_model.params[k].unit
        if g.get("unit", unit) != unit:
            raise TolallocError(f"identified model: geometry[{i}] ({g['name']}) is in {g['unit']!r}; the parameter's "
                                f"unit is {unit!r} (the file's values are not converted).")
        delta[k] = _number(g.get("value"), f"geometry[{i}].value")
        idx.append(k)
    effects, variants, columns, keep, names, beta, kept = _effects(section, without)
    ref_in = section.get("reference", {})
    ref = {"temperature_c": ref_in.get("temperature_c"), "time0_s": ref_in.get("time0_s"), "history": None,
           "motion": None, "variants": dict(variants),
           "left_out": {e["effect"]: e["variant"] for e in section.get("effects", []) if e["effect"] in without},
           "gear_ratio": None if "gear_ratio" not in ref_in else np.asarray(ref_in["gear_ratio"], float),
           "load_scale": None if "load_scale_per_joint" not in ref_in else
           np.asarray(ref_in["load_scale_per_joint"], float)}
    fit = Fit(geo_model, np.asarray(section["registration_rotation"], float),
              np.asarray(section["registration_translation_mm"], float), np.asarray(section["target_offset_mm"], float),
              delta, np.asarray(idx, int), np.asarray(beta, float), np.arange(len(beta)), tuple(names))
    return IdentifiedModel(robot, fit, tuple(effects), variants, columns, np.asarray(keep, int), ref,
                           np.asarray(section["basis_target_offset_mm"], float), _covariance(section, fit, kept),
                           float(section.get("noise_mm", np.nan)), bool(section.get("payload_in_training", False)))


def session_bound(effect: str, variant: str) -> str | None:
    """Why an effect of an exported model cannot be rebuilt from the file (what it needs of the training session),
    or None where it can."""
    if effect == "thermal" and variant.startswith(HISTORY_VARIANTS):
        return "is driven by the training file's history, which the file does not hold"
    if effect == "mount_compliance" and is_creep_variant(variant):
        return "creeps under the load history of the training file, which the file does not hold"
    if effect == "transmission" and variant == "rehome":
        return ("holds the joints' zeros in the training session's power cycles, which the next homing does not "
                "keep (or calibrate the zeros after each power-up)")
    if effect == "backlash" and variant == "reseat":
        return ("holds the tool's seats in the training session's tool changes, which a new tool change does not "
                "keep (or diagnose without the tool changes' payload blocks for a model of the mean seat)")
    return None


def leave_out_advice(effect: str) -> str:
    """How to read an exported model without ``effect`` (one :func:`session_bound` names), and what that costs."""
    return (f"leave the effect out (without=('{effect}',); tolalloc compensate --without {effect}): the identified "
            "geometry and the other effects are kept, the effect's part of the error is then not compensated")


def _effects(section: dict, without: tuple) -> tuple:
    """The section's effects less ``without``: names, variants, columns, fitted-column index, parameter names and
    values, and the mask of the covariance's effect parameters kept."""
    listed = [e["effect"] for e in section.get("effects", [])]
    unknown = [w for w in without if w not in listed]
    if unknown:
        raise TolallocError(f"identified model: cannot leave out {', '.join(map(repr, unknown))}: the file's effects "
                            f"are {', '.join(listed) or 'none'}.")
    effects, variants, columns, keep, names, beta, kept, a = [], {}, {}, [], [], [], [], 0
    for e in section.get("effects", []):
        v, n_fit = e["variant"], len(e["fitted_columns"])
        if e["effect"] in without:
            kept += [False] * n_fit
            continue
        reason = session_bound(e["effect"], v)
        if reason is not None:
            raise TolallocError(f"identified model: its {e['effect']} effect (variant {v}) {reason}; use the "
                                "diagnosis itself (MeasurementDiagnosis.compensate) for that session, or "
                                f"{leave_out_advice(e['effect'])}.")
        effects.append(e["effect"])
        variants[e["effect"]] = v
        columns[e["effect"]] = tuple(e["columns"])
        keep += [a + e["columns"].index(c) for c in e["fitted_columns"]]
        names += [f"{e['effect']}:{c}" for c in e["fitted_columns"]]
        beta += list(e["values"])
        kept += [True] * n_fit
        a += len(e["columns"])
    return effects, variants, columns, keep, names, beta, np.asarray(kept, bool)


def _number(value, key: str) -> float:
    """``value`` as a finite float, or a TolallocError naming ``key``."""
    return float(check_finite_array(value, f"identified model: {key}", ()))


def _array(section: dict, key: str, shape: tuple) -> np.ndarray:
    """``section[key]`` as a finite array of ``shape``, or a TolallocError naming the key (also where it is absent)."""
    if key not in section:
        raise TolallocError(f"identified model: the [identified] section has no {key}; the file is incomplete "
                            "(cut short?) -- export the model again.")
    return check_finite_array(section[key], f"identified model: {key}", shape)


def check_section(section: dict, robot: Robot) -> None:
    """The ``[identified]`` section whole and consistent (raises TolallocError naming what is wrong).

    Its figures have their shapes and are finite, the registration rotation is a rotation, the geometry and effect
    entries are as many as the section says (a file cut short at an entry is refused, not read as a smaller model),
    each effect's fitted columns are among its columns with one value each, and the nominal robot given has the
    screws and home pose the model was identified on (files written before these were recorded skip the checks)."""
    R = _array(section, "registration_rotation", (3, 3))
    if np.abs(R.T @ R - np.eye(3)).max() > 1e-6 or np.linalg.det(R) < 0:
        raise TolallocError("identified model: registration_rotation is not a rotation (R^T R = I, det R = 1); "
                            "the file was altered -- export the model again.")
    for key in ("registration_translation_mm", "target_offset_mm", "basis_target_offset_mm"):
        _array(section, key, (3,))
    for key, count in (("geometry", "n_geometry"), ("effects", "n_effects")):
        entries = section.get(key, [])
        if not isinstance(entries, list) or not all(isinstance(e, dict) for e in entries):
            raise TolallocError(f"identified model: {key} must be a list of tables, got {type(entries).__name__}.")
        if count in section and len(entries) != section[count]:
            raise TolallocError(f"identified model: {len(entries)} {key} entries where the section says "
                                f"{count} = {section[count]!r}; the file is incomplete (cut short?) -- export the "
                                "model again.")
    for i, e in enumerate(section.get("effects", [])):
        cols, fitted, values = e.get("columns"), e.get("fitted_columns"), e.get("values")
        if not (isinstance(cols, list) and isinstance(fitted, list) and isinstance(values, list)
                and set(fitted) <= set(cols) and len(values) == len(fitted) and isinstance(e.get("variant"), str)
                and isinstance(e.get("effect"), str)):
            raise TolallocError(f"identified model: effects[{i}] needs effect, variant, columns, fitted_columns (among "
                                "the columns) and one value per fitted column; the entry is incomplete or altered.")
        for k, v in enumerate(values):
            _number(v, f"effects[{i}].values[{k}]")
    if "nominal_screws" in section:
        screws = _array(section, "nominal_screws", robot.screws.shape)
        home = _array(section, "nominal_home_mm", (4, 4))
        gap = max(np.abs(screws - robot.screws).max(), np.abs(home - robot.home).max())
        if gap > 1e-6:
            raise TolallocError(f"identified model: the nominal robot given ({robot.name!r}) differs from the one the "
                                f"model was identified on by {gap:.3g} (mm or unit-axis components) in its screws or "
                                "home pose (a changed robot or tool file under the same name); give the robot the "
                                "diagnosis used.")
