"""Robot files (TOML) and the built-in robots.

Two TOML layouts are read, both with the unit in every key name:

* the **chain** layout (``[[chain]]`` entries of links and joints, see
  docs/howto/own-robot.md for a complete example), and
* the **DH** layout (``convention = "standard" | "modified"`` and
  ``[[dh]]`` rows), converted to a chain by :mod:`tolalloc.robot.io.dh`.

Lengths may be given in ``_mm`` or ``_m``, angles in ``_deg`` or ``_rad``;
everything is converted to mm and rad on load. Validation is done by
pydantic models; errors are re-raised as :class:`TolallocError` naming the
file, the field and what was expected.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, ValidationError, field_validator, model_validator

from tolalloc.exceptions import TolallocError
from tolalloc.robot.lie import exp_so3
from tolalloc.robot.checks import check_reserved_names
from tolalloc.robot.components_file import parse_components
from tolalloc.robot.model import Joint, Link, Mass, Robot
from tolalloc.robot.dh_rows import check_limits
from tolalloc.units import ALL_UNITS, ANGLE_UNITS, LENGTH_UNITS, check_reach, unit_value

__all__ = ["robot_from_chain_dict", "parse_tool", "check_limits", "LENGTH_UNITS", "ANGLE_UNITS"]

_ALL_UNITS = ALL_UNITS
#: base key -> allowed unit suffixes
_UNIT_KEYS = {
    "vector": LENGTH_UNITS,
    "offset": LENGTH_UNITS,
    "com": LENGTH_UNITS,
    "rpy": ANGLE_UNITS,
    "limits": _ALL_UNITS,
    "nominal": _ALL_UNITS,
    "d": LENGTH_UNITS,
    "a": LENGTH_UNITS,
    "alpha": ANGLE_UNITS,
    "theta_offset": ANGLE_UNITS,
    "d_offset": LENGTH_UNITS,
}

Vec3 = tuple[float, float, float]


def _unit_value(data: dict, base: str, allowed: dict, default=None, check: bool = True):
    """Return (value in internal units, unit) for ``base_<unit>`` in ``data`` (:func:`tolalloc.units.unit_value`)."""
    return unit_value(data, base, allowed, default, exclude=("d_offset",) if base == "d" else (), check=check)


class _Strict(BaseModel):
    model_config = ConfigDict(extra="allow", frozen=True)

    @model_validator(mode="before")
    @classmethod
    def _check_unit_suffixes(cls, data):
        if isinstance(data, dict):
            for key in data:
                for base, allowed in _UNIT_KEYS.items():
                    if key.startswith(base + "_") and key not in cls.model_fields:
                        unit = key[len(base) + 1 :]
                        if unit in ("offset",):
                            continue
                        if unit not in allowed:
                            want = " or ".join(f"{base}_{u}" for u in allowed)
                            raise ValueError(f"unknown unit {unit!r} in key {key!r}; expected {want}")
            extra = [k for k in data if k not in cls.model_fields and not _is_unit_key(k)]
            if extra:
                raise ValueError(f"unknown key(s) {extra}; expected keys among {sorted(cls.model_fields) + cls._unit_bases()}")
        return data

    @classmethod
    def _unit_bases(cls) -> list:
        return []


def _is_unit_key(key: str) -> bool:
    return any(key.startswith(b + "_") and key[len(b) + 1 :] in allowed for b, allowed in _UNIT_KEYS.items())


def _check_axis(v):
    a = np.asarray(v, dtype=float)
    if not np.all(np.isfinite(a)):
        raise ValueError(f"axis must be finite, got {list(v)}")
    n = np.linalg.norm(a)
    if n == 0:
        raise ValueError("axis is the zero vector; expected a unit vector such as [0, 0, 1]")
    if abs(n - 1.0) > 1e-6:
        raise ValueError(f"axis {list(v)} has norm {n:.6g}; expected a unit vector (norm 1 within 1e-6)")
    return tuple(a / n)


class LinkEntry(_Strict):
    link: str

    @classmethod
    def _unit_bases(cls):
        return ["vector_mm|vector_m"]

    def build(self) -> Link:
        extra = self.model_extra or {}
        vec, _ = _unit_value(extra, "vector", LENGTH_UNITS)
        if vec is None:
            raise ValueError("missing vector_mm (the link's translation at home, base axes)")
        if vec.shape != (3,) or not np.all(np.isfinite(vec)):
            raise ValueError(f"vector must be 3 finite numbers, got {extra}")
        if not np.any(vec):
            raise ValueError("the vector is zero; a link needs a length > 0 (its tolerance has a direction); "
                             "leave the entry out")
        return Link(self.link, vec)


class JointEntry(_Strict):
    joint: str
    type: Literal["revolute", "prismatic", "continuous"]
    axis: Vec3

    _check = field_validator("axis")(classmethod(lambda cls, v: _check_axis(v)))

    @classmethod
    def _unit_bases(cls):
        return ["limits_deg|limits_rad|limits_mm|limits_m", "nominal_deg|nominal_rad|nominal_mm|nominal_m"]

    def build(self) -> Joint:
        extra = self.model_extra or {}
        revolute = self.type != "prismatic"
        allowed = ANGLE_UNITS if revolute else LENGTH_UNITS
        kind = "revolute" if revolute else "prismatic"
        default_lim = np.array([-np.pi, np.pi]) if revolute else np.array([-1000.0, 1000.0])
        if self.type == "continuous":
            default_lim = np.array([-4 * np.pi, 4 * np.pi])
        # a continuous joint may turn more than once each way
        lim, _ = _unit_value(extra, "limits", allowed, default_lim, check=self.type != "continuous")
        nom, _ = _unit_value(extra, "nominal", allowed, 0.0, check=self.type != "continuous")
        check_limits(lim, nom, revolute)
        return Joint(self.joint, kind, np.array(self.axis), float(lim[0]), float(lim[1]), float(nom))


class MassEntry(_Strict):
    link: str
    mass_kg: float

    @classmethod
    def _unit_bases(cls):
        return ["com_mm|com_m"]


class ToolEntry(_Strict):
    pass


class ChainFile(BaseModel):
    model_config = ConfigDict(extra="forbid")
    name: str
    description: str = ""
    chain: list[dict]
    tool: dict = {}
    gravity: Vec3 = (0.0, 0.0, -1.0)
    masses: list[dict] = []
    pose_sets: dict[str, dict] = {}
    sigma_sets: dict[str, dict] = {}
    regions: dict[str, dict] = {}
    components: dict = {}
    #: the record of an identified model (tolalloc.diagnose.model_export); not read by the kinematics
    identified: dict = {}


def _loc(err) -> str:
    out = ""
    for part in err["loc"]:
        out += f"[{part}]" if isinstance(part, int) else (("." if out else "") + str(part))
    return out or "(top level)"


def _format(exc: ValidationError, prefix: str) -> str:
    lines = []
    for err in exc.errors():
        msg = err["msg"].removeprefix("Value error, ")
        loc = prefix + ("." if prefix and err["loc"] else "") + _loc(err) if err["loc"] else prefix or "(top level)"
        lines.append(f"{loc}: {msg}")
    return "; ".join(lines)


def _validate(model, data, where: str):
    try:
        return model.model_validate(data)
    except ValidationError as exc:
        raise TolallocError(_format(exc, where)) from None


def robot_from_chain_dict(data: dict, source: str = "<dict>") -> Robot:
    """Build a :class:`Robot` from the parsed TOML of a chain-layout robot file."""
    spec = _validate(ChainFile, data, "")
    chain = []
    for i, entry in enumerate(spec.chain):
        where = f"chain[{i}]"
        if "link" in entry and "joint" not in entry:
            model = LinkEntry
        elif "joint" in entry and "link" not in entry:
            model = JointEntry
        else:
            raise TolallocError(f"{where}: expected either a 'link' or a 'joint' key, got keys {sorted(entry)}")
        item = _validate(model, entry, where)
        try:
            chain.append(item.build())
        except ValueError as exc:
            raise TolallocError(f"{where} ({item.link if model is LinkEntry else item.joint}): {exc}") from None
    offset, R_tool = parse_tool(spec.tool)
    # an identified model's chain holds its calibrated offsets: a sub-millimetre link there is real, not metres
    return _finish_robot(spec.name, chain, offset, R_tool, spec.gravity, spec.masses, spec.pose_sets, spec.description,
                         spec.sigma_sets, regions=spec.regions, components=spec.components,
                         base_dir=source_dir(source), tiny_links_suspect=not spec.identified)


def source_dir(source: str):
    """The folder of the robot file ``source`` names (``robot file '<path>'``, a built-in robot, or a path; None for a
    dict): where the file's ``[components] catalogue_file`` is read from."""
    import ast
    from pathlib import Path

    if source.startswith("built-in robot"):
        return Path(__file__).resolve().parents[2] / "data" / "robots"
    if source.startswith("robot file "):
        try:
            source = ast.literal_eval(source[len("robot file "):])
        except (ValueError, SyntaxError):
            return None
    p = Path(source)
    return p.parent if p.is_file() else None


def parse_tool(tool: dict):
    """Return (offset [mm] (3,), rotation (3, 3)) of a ``[tool]`` table (``offset_mm``, ``rpy_deg`` X-Y-Z fixed)."""
    extra = _validate(ToolEntry, tool, "tool").model_extra or {}
    try:
        offset, _ = _unit_value(extra, "offset", LENGTH_UNITS, np.zeros(3))
        rpy, _ = _unit_value(extra, "rpy", ANGLE_UNITS, np.zeros(3))
    except ValueError as exc:
        raise TolallocError(f"tool: {exc}") from None
    if np.shape(offset) != (3,) or np.shape(rpy) != (3,) or not np.all(np.isfinite(offset)) or not np.all(np.isfinite(rpy)):
        raise TolallocError(f"tool: expected offset_mm and rpy_deg of 3 finite numbers each, got {tool}")
    R = exp_so3([0, 0, rpy[2]]) @ exp_so3([0, rpy[1], 0]) @ exp_so3([rpy[0], 0, 0])
    return np.asarray(offset, float), R


def _finish_robot(name, chain, offset, R_tool, gravity, masses, pose_sets, description, sigma_sets=None, *,
                  regions=None, tiny_links_suspect: bool = True, components=None, base_dir=None) -> Robot:
    """Shared tail of the chain and DH loaders: gravity, masses, pose sets.

    ``tiny_links_suspect``: a sub-millimetre link among long ones is taken for a length in metres (chain
    layout, where every link is a part); a DH table legitimately holds small calibrated offsets, so the DH
    loader only checks the total reach.
    """
    g = np.asarray(gravity, dtype=float)
    if not np.all(np.isfinite(g)) or np.linalg.norm(g) == 0:
        raise TolallocError(f"gravity: expected a non-zero direction such as [0, 0, -1], got {list(gravity)}")
    check_reach({e.name: float(np.linalg.norm(e.vector_mm)) for e in chain if isinstance(e, Link)}, "lengths",
                tiny_links=tiny_links_suspect)
    # the file's unit rules above (unit keys, reach) replace the guards of a chain built from objects
    robot = Robot(name, tuple(chain), tool_offset_mm=np.asarray(offset, float), tool_rotation=np.asarray(R_tool),
                  gravity=g / np.linalg.norm(g), description=description, trust_units=True)
    body_of = {}
    for e in chain:
        if isinstance(e, Link):
            body_of[e.name] = int(sum(isinstance(x, Joint) for x in chain[: chain.index(e)]))
    mass_list = []
    for i, m in enumerate(masses):
        entry = _validate(MassEntry, m, f"masses[{i}]")
        if entry.link not in body_of:
            raise TolallocError(f"masses[{i}].link: {entry.link!r} is not a link of the chain; links: {sorted(body_of)}")
        try:
            com, _ = _unit_value(entry.model_extra or {}, "com", LENGTH_UNITS)
        except ValueError as exc:
            raise TolallocError(f"masses[{i}]: {exc}") from None
        if com is None or entry.mass_kg < 0:
            raise TolallocError(f"masses[{i}]: expected mass_kg >= 0 and com_mm (3 numbers), got {m}")
        mass_list.append(Mass(entry.link, body_of[entry.link], float(entry.mass_kg), com))
    check_reserved_names("", pose_sets=pose_sets, regions=regions or {}, sigma_sets=sigma_sets or {})
    sets = {}
    for set_name, entry in pose_sets.items():
        if set(entry) != {"q_deg_mm"}:
            raise TolallocError(f"pose_sets.{set_name}: expected one key 'q_deg_mm' (rows of joint values in deg / mm), got keys {sorted(entry)}")
        where = f"pose_sets.{set_name}.q_deg_mm"
        try:
            rows = np.atleast_2d(np.asarray(entry["q_deg_mm"], dtype=float))
        except (TypeError, ValueError):
            raise TolallocError(f"{where}: expected rows of {robot.n_joints} numbers (deg / mm), one row per pose, "
                                f"got {entry['q_deg_mm']!r}.") from None
        sets[set_name] = robot.check_q(rows, where, interface=True)
    object.__setattr__(robot, "masses", tuple(mass_list))
    object.__setattr__(robot, "pose_sets", sets)
    object.__setattr__(robot, "sigma_sets", dict(sigma_sets or {}))
    object.__setattr__(robot, "regions", _parse_regions(robot, regions or {}))
    try:
        parts = parse_components(components, {j.name: j.is_revolute for j in robot.joints},
                                 [lk.name for lk in robot.links], base_dir=base_dir,
                                 link_vectors={lk.name: lk.vector_mm for lk in robot.links})
    except ValueError as exc:
        raise TolallocError(str(exc)) from None
    object.__setattr__(robot, "components", parts)
    return robot


def _parse_regions(robot: Robot, regions: dict) -> dict:
    """``[regions.NAME]`` boxes -> ``{NAME: (q_min, q_max)}`` in internal units [rad, mm], each shape (n,)."""
    out = {}
    for name, entry in regions.items():
        where = f"regions.{name}"
        if not isinstance(entry, dict) or set(entry) != {"q_min_deg_mm", "q_max_deg_mm"}:
            got = sorted(entry) if isinstance(entry, dict) else entry
            raise TolallocError(f"{where}: expected keys 'q_min_deg_mm' and 'q_max_deg_mm' ({robot.n_joints} numbers "
                                f"each, deg / mm), got {got!r}.")
        try:
            lo = np.asarray(entry["q_min_deg_mm"], dtype=float).ravel()
            hi = np.asarray(entry["q_max_deg_mm"], dtype=float).ravel()
        except (TypeError, ValueError):
            raise TolallocError(f"{where}: expected numbers (deg / mm), got {entry!r}.") from None
        if lo.shape != (robot.n_joints,) or hi.shape != (robot.n_joints,):
            raise TolallocError(f"{where}: expected {robot.n_joints} values in q_min_deg_mm and q_max_deg_mm, "
                                f"got {lo.size} and {hi.size}.")
        if np.any(hi < lo):
            bad = [int(j) + 1 for j in np.flatnonzero(hi < lo)]
            raise TolallocError(f"{where}: q_max_deg_mm < q_min_deg_mm at joint(s) {bad}: the box is inverted; "
                                "give q_min <= q_max for every joint.")
        q = robot.check_q(np.stack([lo, hi]), where, interface=True)
        out[name] = (q[0], q[1])
    return out
