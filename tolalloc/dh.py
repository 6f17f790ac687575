"""Denavit-Hartenberg tables (standard or modified) converted to a POE chain.

Each non-zero DH length becomes a named :class:`~tolalloc.robot.Link`
(``d1``, ``a2`` ...), so it carries a length tolerance like any other link.

Standard DH (``T_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i)``): joint ``i``
turns about ``z_{i-1}`` through the origin of frame ``i-1``.
Modified DH (Craig, ``T_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i)``):
joint ``i`` turns about ``z_i`` through the origin of frame ``i``; the row of
joint ``i`` holds ``alpha_{i-1}`` and ``a_{i-1}``.
The tool frame is the last DH frame, optionally followed by ``[tool]``.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from pydantic import BaseModel, ConfigDict

from ._validate import TolallocError
from .lie import rot_x, rot_z
from .robot import Joint, Link

__all__ = ["robot_from_dh_dict", "chain_from_dh"]


class DHFile(BaseModel):
    model_config = ConfigDict(extra="forbid")
    name: str
    description: str = ""
    convention: Literal["standard", "modified"]
    dh: list[dict]
    tool: dict = {}
    gravity: tuple[float, float, float] = (0.0, 0.0, -1.0)
    masses: list[dict] = []
    pose_sets: dict[str, dict] = {}
    sigma_sets: dict[str, dict] = {}


def chain_from_dh(rows: list[dict], convention: str):
    """Build chain elements and the final frame rotation from DH rows in internal units.

    Parameters
    ----------
    rows : list of dict
        Keys ``name``, ``type`` (``revolute`` / ``prismatic``), ``d``, ``a`` [mm],
        ``alpha``, ``theta_offset`` [rad], ``lower``, ``upper``, ``nominal``.
    convention : {"standard", "modified"}

    Returns
    -------
    chain : list of Link and Joint
    R_tool : array, shape (3, 3)
        Orientation of the last DH frame at the zero configuration.
    """
    R = np.eye(3)
    chain = []
    for i, r in enumerate(rows, start=1):
        if convention == "modified":
            R = R @ rot_x(r["alpha"])
            if r["a"] != 0:
                chain.append(Link(f"a{i - 1}", r["a"] * R[:, 0]))
            R = R @ rot_z(r["theta_offset"])
            axis = R[:, 2].copy()
            chain.append(Joint(r["name"], r["type"], axis, r["lower"], r["upper"], r["nominal"]))
            if r["d"] != 0:
                chain.append(Link(f"d{i}", r["d"] * R[:, 2]))
        else:
            axis = R[:, 2].copy()
            chain.append(Joint(r["name"], r["type"], axis, r["lower"], r["upper"], r["nominal"]))
            if r["d"] != 0:
                chain.append(Link(f"d{i}", r["d"] * R[:, 2]))
            R = R @ rot_z(r["theta_offset"])
            if r["a"] != 0:
                chain.append(Link(f"a{i}", r["a"] * R[:, 0]))
            R = R @ rot_x(r["alpha"])
    return chain, R


def robot_from_dh_dict(data: dict, source: str = "<dict>"):
    """Build a robot from a parsed DH TOML file (see the README)."""
    from .robotfile import ANGLE_UNITS, LENGTH_UNITS, _finish_robot, _unit_value, _validate, parse_tool

    spec = _validate(DHFile, data, "")
    rows = []
    for i, row in enumerate(spec.dh):
        where = f"dh[{i}]"
        known = {"name", "type"}
        try:
            kind = row.get("type", "revolute")
            if kind not in ("revolute", "prismatic", "continuous"):
                raise ValueError(f"type must be 'revolute', 'prismatic' or 'continuous', got {kind!r}")
            for key in row:
                if key not in known and not any(key.startswith(b + "_") for b in ("d", "a", "alpha", "theta_offset", "limits", "nominal")):
                    raise ValueError(f"unknown key {key!r}; expected name, type, d_mm|d_m, a_mm|a_m, alpha_deg|alpha_rad, theta_offset_deg|theta_offset_rad, limits_*, nominal_*")
            d, _ = _unit_value(row, "d", LENGTH_UNITS, 0.0)
            a, _ = _unit_value(row, "a", LENGTH_UNITS, 0.0)
            alpha, _ = _unit_value(row, "alpha", ANGLE_UNITS, 0.0)
            th0, _ = _unit_value(row, "theta_offset", ANGLE_UNITS, 0.0)
            rev = kind != "prismatic"
            units = ANGLE_UNITS if rev else LENGTH_UNITS
            lim, _ = _unit_value(row, "limits", units, np.array([-2 * np.pi, 2 * np.pi]) if rev else np.array([-1000.0, 1000.0]))
            nom, _ = _unit_value(row, "nominal", units, 0.0)
        except ValueError as exc:
            raise TolallocError(f"{where}: {exc}") from None
        rows.append(dict(name=str(row.get("name", f"j{i + 1}")), type="revolute" if rev else "prismatic",
                         d=float(d), a=float(a), alpha=float(alpha), theta_offset=float(th0),
                         lower=float(lim[0]), upper=float(lim[1]), nominal=float(nom)))
    chain, R_last = chain_from_dh(rows, spec.convention)
    offset, R_tool = parse_tool(spec.tool)
    # the tool of a DH robot is given in the last DH frame
    return _finish_robot(spec.name, chain, R_last @ offset, R_last @ R_tool, spec.gravity, spec.masses,
                         spec.pose_sets, spec.description, spec.sigma_sets)
