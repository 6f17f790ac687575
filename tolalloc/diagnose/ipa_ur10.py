"""Reader of the IPA UR10 laser-tracker files (a public measurement set of a UR10 arm).

The files are ``;``-separated with decimal commas: the six joint values in rad (``shoulder_pan_joint`` ...
``wrist_3_joint``), the probe position in the tracker frame in mm (``measurement_x/y/z``) and, where recorded, the
air temperature (``measurement_temperature``, degC). :func:`read_ipa_ur10` returns the measurement table of
:func:`tolalloc.diagnose.diagnose`: ``q1..q6`` [deg], ``x_mm, y_mm, z_mm``, ``temperature_c``, ``dir1..dir6`` and
``time_s``. Two columns are derived, not measured:

* ``time_s`` is the row order times 1 s (series C's time stamps were mangled by a spreadsheet);
* ``dir1..dir6`` are the signs of each joint's change from the previous row (+1 when unchanged or first): an
  assumption, as the robot's path between the points is not recorded.

The reader is also a template for other trackers: write the same columns.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError

#: Joint columns of the IPA files, base to flange (values in rad).
IPA_JOINTS = ("shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint",
              "wrist_3_joint")
#: Probe position columns of the IPA files (tracker frame, mm).
IPA_POSITION = ("measurement_x", "measurement_y", "measurement_z")


def read_ipa_ur10(path) -> pd.DataFrame:
    """Read one IPA UR10 measurement file into the measurement table of the diagnosis (interface units).

    Parameters
    ----------
    path : str or Path
        An IPA file, e.g. ``Series_C/measurements_random_poses.csv`` of the data set.

    Returns
    -------
    pandas.DataFrame
        One row per measured pose: ``q1..q6`` [deg], ``x_mm, y_mm, z_mm``, ``temperature_c`` (when the file has
        a temperature column), ``dir1..dir6`` (+1 / -1), ``time_s`` (row order, 1 s apart).
    """
    path = Path(path)
    try:
        raw = pd.read_csv(path, sep=";", decimal=",", dtype=str)
    except (OSError, pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise TolallocError(f"{path}: cannot be read as an IPA UR10 file ({exc}); expected a ';'-separated file "
                            f"with the columns {', '.join(IPA_JOINTS + IPA_POSITION)}.") from None
    missing = [c for c in IPA_JOINTS + IPA_POSITION if c not in raw.columns]
    if missing:
        raise TolallocError(f"{path}: expected the IPA UR10 columns {', '.join(IPA_JOINTS + IPA_POSITION)}; "
                            f"missing {', '.join(missing)}. Is this an IPA UR10 measurement file?")

    def number(column: str) -> np.ndarray:
        return pd.to_numeric(raw[column].str.replace(",", ".", regex=False), errors="coerce").to_numpy(float)

    out = {f"q{j + 1}": np.rad2deg(number(c)) for j, c in enumerate(IPA_JOINTS)}
    out.update({"x_mm": number(IPA_POSITION[0]), "y_mm": number(IPA_POSITION[1]), "z_mm": number(IPA_POSITION[2])})
    if "measurement_temperature" in raw.columns:
        out["temperature_c"] = number("measurement_temperature")
    q = np.column_stack([out[f"q{j + 1}"] for j in range(len(IPA_JOINTS))])
    direction = np.sign(np.diff(q, axis=0, prepend=q[:1]))
    direction[direction == 0] = 1.0
    out.update({f"dir{j + 1}": direction[:, j] for j in range(len(IPA_JOINTS))})
    out["time_s"] = np.arange(len(raw), dtype=float)
    return pd.DataFrame(out)
