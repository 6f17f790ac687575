"""Denavit-Hartenberg tables (standard or modified) converted to a POE chain.

Each non-zero DH length becomes a named :class:`~tolalloc.robot.model.Link`
(``d1``, ``a2`` ...), so it carries a length tolerance like any other link.

Standard DH (``T_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i)``): joint ``i``
turns about ``z_{i-1}`` through the origin of frame ``i-1``.
Modified DH (Craig, ``T_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i)``):
joint ``i`` turns about ``z_i`` through the origin of frame ``i``; the row of
joint ``i`` holds ``alpha_{i-1}`` and ``a_{i-1}``.
The tool frame is the last DH frame, optionally followed by ``[tool]``.
For a prismatic joint ``i`` the constant part of ``d_i`` is the link ``d<i>_offset`` (so that its
length error ``dd<i>_offset`` does not clash with the drive error ``dd<i>``).

CSV form (``load_dh_csv``): ``#`` comment lines ``# key: value`` give ``convention`` (required:
``standard`` or ``modified``), ``name`` and ``description``; then a header row and one row per
joint with the columns ``name``, ``type`` (optional, default revolute), ``d_mm`` | ``d_m``,
``a_mm`` | ``a_m``, ``alpha_deg`` | ``alpha_rad``, ``theta_offset_deg`` | ``theta_offset_rad`` and
optionally ``lower_deg_mm``, ``upper_deg_mm``, ``nominal_deg_mm`` (deg for revolute, mm for
prismatic rows); empty cells take the defaults. Example::

    # convention: standard
    # name: ur10_csv
    name,d_m,a_m,alpha_rad
    shoulder_pan_joint,0.1273,0,1.5707963267948966
    shoulder_lift_joint,0,-0.612,0
    ...
"""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict

from tolalloc.exceptions import TolallocError
from tolalloc.robot.dh_rows import CSV_COLUMNS, parse_dh_rows, row_from_cells
from tolalloc.robot.io.robotfile import source_dir, _finish_robot, _validate, parse_tool
from tolalloc.robot.elements import chain_from_dh

__all__ = ["robot_from_dh_dict", "chain_from_dh", "load_dh_csv"]


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
    regions: dict[str, dict] = {}
    components: dict = {}


def robot_from_dh_dict(data: dict, source: str = "<dict>"):
    """Build a robot from a parsed DH TOML file (see docs/howto/own-robot.md)."""

    spec = _validate(DHFile, data, "")
    rows = parse_dh_rows(spec.dh)
    chain, R_last = chain_from_dh(rows, spec.convention)
    offset, R_tool = parse_tool(spec.tool)
    # the tool of a DH robot is given in the last DH frame
    return _finish_robot(spec.name, chain, R_last @ offset, R_last @ R_tool, spec.gravity, spec.masses,
                         spec.pose_sets, spec.description, spec.sigma_sets, tiny_links_suspect=False, regions=spec.regions,
                         components=spec.components, base_dir=source_dir(source))


def load_dh_csv(path):
    """Load a robot from a DH table in CSV form (see the module docstring).

    Raises
    ------
    TolallocError
        Naming the file, the row (``dh[i]`` = data row ``i``, 0-based) and the column.
    """
    import csv
    from pathlib import Path

    path = Path(path)
    source = f"DH CSV file {str(path)!r}"
    meta, lines = {}, []
    try:
        text = path.read_text(encoding="utf-8-sig")  # a byte-order mark (Windows editors) is fine
    except (OSError, UnicodeDecodeError) as exc:
        raise TolallocError(f"{source}: cannot be read as text ({exc}); expected a DH table in CSV.") from None
    for line in text.splitlines():
        if line.lstrip().startswith("#"):
            key, sep, value = line.lstrip()[1:].partition(":")
            if sep:
                meta[key.strip().lower()] = value.strip()
        elif line.strip():
            lines.append(line)
    if meta.get("convention") not in ("standard", "modified"):
        raise TolallocError(f"{source}: expected a comment line '# convention: standard' or '# convention: modified' "
                            f"before the header, got convention {meta.get('convention')!r}.")
    reader = csv.DictReader(lines, skipinitialspace=True)
    header = [h.strip() for h in (reader.fieldnames or [])]
    unknown = [h for h in header if h not in CSV_COLUMNS]
    if "name" not in header or unknown:
        raise TolallocError(f"{source}: header {header}: expected a 'name' column and columns among {', '.join(CSV_COLUMNS)}"
                            + (f"; unknown: {unknown}" if unknown else "") + ".")
    if "alpha_deg" not in header and "alpha_rad" not in header:  # alpha = 0 everywhere would be another robot
        raise TolallocError(f"{source}: header {header}: no alpha_deg or alpha_rad column; a DH table needs the link "
                            "twists alpha (write 0 where a twist is zero).")
    rows = []
    for i, raw in enumerate(reader):
        cells = {k.strip(): (v or "").strip() for k, v in raw.items() if k is not None}
        if None in raw:
            raise TolallocError(f"{source}: dh[{i}]: more cells than header columns ({len(header)}).")
        row = row_from_cells(cells, i, source)
        rows.append(row)
    data = {"name": meta.get("name", path.stem), "description": meta.get("description", ""),
            "convention": meta["convention"], "dh": rows}
    try:
        return robot_from_dh_dict(data, source)
    except TolallocError as exc:
        raise TolallocError(f"{source}: {exc}") from None
