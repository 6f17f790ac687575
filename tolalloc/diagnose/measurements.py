"""Laser-tracker measurement sets: reading and validating the measurement CSV.

Columns (other columns are ignored):

``q1_deg ...``      joint values in interface units (deg for revolute, mm for prismatic joints), see below
``x_mm,y_mm,z_mm``  measured target position in the tracker's fixed frame [mm]
``temperature_c``   optional, ambient temperature [degC]
``dir1..dirN``      optional, sign (+1/-1) of each joint's last motion before the point
``payload_kg``      optional, the mass held [kg] (above 10 x the rated payload or below 0: refused)
``time_s``          optional, time stamp [s]
``force_x_n ...``   optional, ``force_x_n, force_y_n, force_z_n``: process force on the tool at the target [N]
``torque_x_nm ...`` optional, ``torque_x_nm, torque_y_nm, torque_z_nm``: the process moment [N m]

The force and moment (:data:`WRENCH_COLUMNS`) are in the robot's base frame, each set all three or none.

The joint columns are named by the rule of :mod:`tolalloc.robot.columns`: ``q<k>_deg`` / ``q<k>_mm``, the
calibration plan's ``<joint name>_deg`` / ``_mm``, or plain ``q1..qN``.
Lines starting with ``#`` before the header are skipped (a calibration plan filled in with tracker readings is
a measurement file).

NaN policy: a row with an empty / NaN cell in a required column (joints, ``x_mm..z_mm``) is
**skipped and counted** (``Measurements.n_skipped``); a cell holding text that is not a number is an
**error** naming the row and column. Optional covariates with NaN are an error (fill or drop them).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError
from tolalloc.units import radians_fix
from tolalloc.robot.columns import JOINT_COLUMNS_TEXT, find_joint_columns
from tolalloc.robot.model import Robot
from tolalloc.diagnose.scale import point_kinematics

__all__ = ["Measurements", "read_measurements", "measurements_from_frame", "check_train_test", "comment_lines",
           "WRENCH_COLUMNS", "read_wrench",
           "file_rows", "POSITION_COLUMNS"]

#: fewer distinct poses than this cannot fix the tracker registration and target offset (9 unknowns, 3 per pose)
MIN_DISTINCT_POSES = 3

POSITION_COLUMNS = ("x_mm", "y_mm", "z_mm")
#: The logged process wrench at the target, robot base frame: force [N] and moment [N m] (each all three or none).
WRENCH_COLUMNS = (("force_x_n", "force_y_n", "force_z_n"), ("torque_x_nm", "torque_y_nm", "torque_z_nm"))


#: The optional covariates and their one accepted unit: a column of the same quantity in another unit is refused.
COVARIATE_UNITS = {"payload": "payload_kg", "time": "time_s", "temperature": "temperature_c"}


def _check_covariate_units(cols, source: str) -> None:
    """Refuse a covariate column in another unit (``payload_g``, ``time_ms``, ``temperature_k``): it would be ignored
    silently, and an effect fitted without it."""
    for c in cols:
        base, _, unit = str(c).partition("_")
        want = COVARIATE_UNITS.get(base)
        if want is not None and unit and c != want:
            raise TolallocError(f"{source}: column {c!r}: expected {want!r} (the one unit the diagnosis reads); "
                                f"convert the column to {want.split('_')[1]} and rename it {want}.")
        axis = re.fullmatch(r"(force|torque)_([xyz])_(\w+)", str(c))
        if axis and c not in WRENCH_COLUMNS[axis[1] == "torque"]:
            want = f"{axis[1]}_{axis[2]}_{'n' if axis[1] == 'force' else 'nm'}"
            raise TolallocError(f"{source}: column {c!r}: expected {want!r} (the process {axis[1]} in "
                                f"{'N' if axis[1] == 'force' else 'N m'}, the one unit the diagnosis reads); convert "
                                f"the column and rename it {want}.")


def file_rows(rows: np.ndarray | None, n: int) -> np.ndarray:
    """1-based file rows of ``n`` poses, shape (n,): ``rows`` (:attr:`Measurements.rows`) when given, else the
    positions + 1 (a set built without rows)."""
    return np.arange(1, n + 1) if rows is None or not len(rows) else np.asarray(rows, dtype=np.int64)


@dataclass(frozen=True, eq=False)
class Measurements:
    """A validated measurement set.

    Attributes
    ----------
    q : array, shape (P, n) [rad, mm]
        Joint values (internal units).
    xyz_mm : array, shape (P, 3) [mm]
        Measured target positions in the tracker frame.
    temperature_c, payload_kg, time_s : array, shape (P,) or None
    direction : array, shape (P, n) of +1/-1, or None
    rows : array of int, shape (P,)
        Row number (1-based, header excluded) in the source file of every kept pose.
    n_skipped : int
        Rows skipped because a required cell was empty / NaN.
    source : str
    wrench : array, shape (P, 6) or None
        The logged process wrench at the target, robot base frame: force [N], moment [N m].
    """

    q: np.ndarray
    xyz_mm: np.ndarray
    temperature_c: np.ndarray | None = None
    direction: np.ndarray | None = None
    payload_kg: np.ndarray | None = None
    time_s: np.ndarray | None = None
    rows: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    n_skipped: int = 0
    source: str = "<frame>"
    wrench: np.ndarray | None = None

    @property
    def n_poses(self) -> int:
        return int(self.q.shape[0])

    def subset(self, idx) -> "Measurements":
        """The poses ``idx`` (integer index array or boolean mask) as a new set."""
        idx = np.asarray(idx)
        pick = (lambda a: None if a is None else a[idx])
        return Measurements(self.q[idx], self.xyz_mm[idx], pick(self.temperature_c), pick(self.direction),
                            pick(self.payload_kg), pick(self.time_s), self.rows[idx], 0, self.source,
                            pick(self.wrench))

    def pose_groups(self) -> np.ndarray:
        """Group number per row, equal for rows with the same joint values (repeated measurements of one pose),
        shape (P,) of int, numbered in order of first appearance. Cross-validation folds that keep each group
        together do not score a pose against its own repeat."""
        h = _row_hash(self.q)
        _, first, inverse = np.unique(h, return_index=True, return_inverse=True)
        order = np.argsort(np.argsort(first))  # renumber by first appearance
        return order[np.ravel(inverse)]

    def covariates(self) -> dict:
        """Available scalar covariates by column name, each shape (P,)."""
        out = {}
        for key in ("temperature_c", "payload_kg", "time_s"):
            v = getattr(self, key)
            if v is not None:
                out[key] = v
        return out


def _numeric(df: pd.DataFrame, col: str, source: str) -> np.ndarray:
    """Column as floats; text that is not a number -> error naming the first bad cell."""
    raw = df[col]
    num = pd.to_numeric(raw, errors="coerce")
    cand = np.flatnonzero((num.isna() & raw.notna()).to_numpy())  # strip only these cells (large files)
    bad = cand[(raw.iloc[cand].astype(str).str.strip() != "").to_numpy()]
    if bad.size:
        i = int(bad[0])
        raise TolallocError(
            f"{source}: column {col!r}, row {i + 1}: expected a number, got {raw.iloc[i]!r}; "
            "use '.' as decimal separator and numbers only (convert the file first if it uses decimal commas).")
    return num.to_numpy(dtype=float)


def _scale_check(robot: Robot, q: np.ndarray, xyz: np.ndarray, source: str) -> None:
    """Compare the spread of the measured points with the spread of the nominal model's points."""
    if len(q) < 3:
        return
    p_nom, _ = point_kinematics(robot.screws, robot.home, q, np.zeros(3))  # chunked, no (P, n, 4, 4) temporaries
    s_nom = np.sqrt(np.mean(np.sum((p_nom - p_nom.mean(0)) ** 2, axis=1)))
    s_meas = np.sqrt(np.mean(np.sum((xyz - xyz.mean(0)) ** 2, axis=1)))
    if s_nom < 20.0:  # poses too close together to judge the scale
        return
    ratio = s_meas / s_nom
    if 2e-4 < ratio < 5e-3:
        raise TolallocError(
            f"{source}: the measured positions look like metres, not mm: they spread over {s_meas:.4g} "
            f"while the robot model's points spread over {s_nom:.4g} mm at the same joint values; "
            "multiply x_mm, y_mm, z_mm by 1000.")
    if ratio < 0.3 or ratio > 3.0:
        raise TolallocError(
            f"{source}: the measured positions spread over {s_meas:.4g} mm but the robot model's points spread "
            f"over {s_nom:.4g} mm at the same joint values (ratio {ratio:.3g}); expected comparable spreads. "
            "Check the units (mm expected), the robot (wrong robot?) and the joint columns (deg / mm expected).")


def _row_hash(A: np.ndarray) -> np.ndarray:
    """One 64-bit hash per row of ``A`` (equal rows, equal hashes), shape (rows,)."""
    return pd.util.hash_pandas_object(pd.DataFrame(A), index=False).to_numpy()


def _duplicated(A: np.ndarray) -> np.ndarray:
    """True for every row equal to an earlier row of ``A``, shape (rows,): rows of equal hash are compared
    exactly with the first row of that hash (O(rows log rows))."""
    h = _row_hash(A)
    _, first, inverse = np.unique(h, return_index=True, return_inverse=True)
    earlier = first[np.ravel(inverse)]
    return (earlier != np.arange(len(A))) & (A[earlier] == A).all(axis=1)


def _first_duplicate(A: np.ndarray):
    """Indices ``(i, j)``, i < j, of the first row ``j`` equal to an earlier row ``i``, or None."""
    dup = np.flatnonzero(_duplicated(A))
    if dup.size == 0:
        return None
    j = int(dup[0])
    i = int(np.flatnonzero((A[:j] == A[j]).all(axis=1))[0])
    return i, j


def _check_poses(Q: np.ndarray, X: np.ndarray, rows: np.ndarray, source: str) -> None:
    """Refuse duplicated rows (they would leak across cross-validation folds) and too few distinct poses."""
    QX = np.concatenate([Q, X], axis=1)
    d = _first_duplicate(QX)
    if d is not None:
        n_dup = int(_duplicated(QX).sum())
        raise TolallocError(f"{source}: row {rows[d[1]]} repeats row {rows[d[0]]} exactly ({n_dup} duplicated row(s)); "
                            "expected each measurement once (a copy would be scored as held out against itself); "
                            "remove the duplicates.")
    n_distinct = len(np.unique(_row_hash(Q)))
    if n_distinct < MIN_DISTINCT_POSES:
        raise TolallocError(f"{source}: only {n_distinct} distinct pose(s) in {len(Q)} rows; expected at least "
                            f"{MIN_DISTINCT_POSES} different joint configurations (the registration alone has 9 "
                            "unknowns); measure more poses.")


def check_train_test(train: Measurements, test: Measurements, train_name: str, test_name: str) -> None:
    """Refuse a test set that shares poses with the training set (its error would not be held out)."""
    if Path(train_name).resolve() == Path(test_name).resolve():
        raise TolallocError(f"`test` {test_name!r} is the training file; expected held-out measurements in another "
                            "file (or leave out `test`: cross-validation still scores held-out rows).")
    keys, first = np.unique(_row_hash(train.q), return_index=True)
    h_test = _row_hash(test.q)
    at = np.minimum(np.searchsorted(keys, h_test), len(keys) - 1)
    # same hash and the same joint values (a hash collision of different poses is not sharing)
    shared = (keys[at] == h_test) & (train.q[first[at]] == test.q).all(axis=1)
    if shared.any():
        j = int(np.flatnonzero(shared)[0])
        i = int(np.flatnonzero((train.q == test.q[j]).all(axis=1))[0])
        raise TolallocError(f"`test` {test_name!r}: {int(shared.sum())} of its {test.n_poses} poses are also in `train` "
                            f"{train_name!r} (e.g. test row {test.rows[j]} = train row {train.rows[i]}); expected "
                            "held-out poses; remove them from one of the files.")


def measurements_from_frame(df: pd.DataFrame, robot: Robot, source: str = "<frame>") -> Measurements:
    """Validate a measurement table (see the module docstring) and return :class:`Measurements`."""
    n = robot.n_joints
    cols = [str(c).strip() for c in df.columns]
    df = df.copy()
    df.columns = cols
    qcols = find_joint_columns(robot, cols, source)
    missing = [c for c in POSITION_COLUMNS if c not in cols]
    if missing:
        lower = {c.lower(): c for c in cols}
        hints = [f"{lower[m.lower()]!r} -> {m!r}" for m in missing if m.lower() in lower]
        hint = f" Rename: {', '.join(hints)}." if hints else ""
        raise TolallocError(
            f"{source}: missing column(s) {missing}; expected the joint columns ({', '.join(qcols)}) and "
            f"{', '.join(POSITION_COLUMNS)}, got columns {cols}.{hint}")
    if len(df) == 0:
        raise TolallocError(f"{source}: no data rows; expected one row per measured pose.")
    Q = np.column_stack([_numeric(df, c, source) for c in qcols])
    X = np.column_stack([_numeric(df, c, source) for c in POSITION_COLUMNS])
    bad_inf = np.isinf(np.concatenate([Q, X], axis=1))
    if bad_inf.any():
        raise TolallocError(f"{source}: row {int(np.argwhere(bad_inf)[0, 0]) + 1}: infinite value; expected finite numbers.")
    keep = ~(np.isnan(Q).any(1) | np.isnan(X).any(1))
    n_skipped = int((~keep).sum())
    if not keep.any():
        raise TolallocError(f"{source}: every row has an empty or NaN cell in {qcols[0]}..{qcols[-1]} / x_mm,y_mm,z_mm; "
                            "no pose left.")
    rows = np.flatnonzero(keep) + 1
    Q, X = Q[keep], X[keep]
    qi = robot.q_from_interface(Q)
    lo, hi = robot.lower, robot.upper
    bad = (qi < lo - 1e-9) | (qi > hi + 1e-9)
    if bad.any():
        i, k = np.argwhere(bad)[0]
        j = robot.joints[k]
        lim = robot.q_to_interface(np.array([lo, hi]))[:, k]
        rad_like = all(np.abs(Q[:, c]).max() <= 2 * np.pi for c, jt in enumerate(robot.joints) if jt.kind == "revolute")
        advice = (f"these look like radians; expected {radians_fix(robot.revolute_mask)}" if rad_like else
                  f"the values do not fit robot {robot.name!r} -- wrong robot? (or check the robot file's limits)")
        raise TolallocError(
            f"{source}: row {rows[i]}: {qcols[k]} ({j.name}) = {Q[i, k]:g} {j.unit} is outside the joint limits "
            f"[{lim[0]:g}, {lim[1]:g}] {j.unit} ({int(bad.any(1).sum())} row(s) affected); {advice}.")

    def optional(col):
        if col not in cols:
            return None
        v = _numeric(df, col, source)[keep]
        if np.isnan(v).any():
            raise TolallocError(f"{source}: column {col!r} has empty / NaN cells (row {rows[np.isnan(v)][0]}); "
                                "fill them or drop the column.")
        return v

    _check_covariate_units(cols, source)
    dcols = [f"dir{j + 1}" for j in range(n)]
    direction = None
    present = [c for c in dcols if c in cols]
    if present:
        if len(present) != n:
            raise TolallocError(f"{source}: direction columns {present} given, expected all of {dcols} or none.")
        direction = np.column_stack([optional(c) for c in dcols])
        if not np.all(np.isin(direction, (-1.0, 1.0))):
            bad_v = direction[~np.isin(direction, (-1.0, 1.0))][0]
            raise TolallocError(f"{source}: dir columns must hold +1 or -1 (sign of the last motion), got {bad_v:g}.")
    _check_poses(Q, X, rows, source)
    _scale_check(robot, qi, X, source)
    payload = optional("payload_kg")
    _check_payload(robot, payload, rows, source)
    return Measurements(qi, X, optional("temperature_c"), direction, payload, optional("time_s"),
                        rows, n_skipped, source, read_wrench(cols, optional, source))


#: A logged payload above this many times the robot's rated payload is taken for another unit (grams).
PAYLOAD_RATED_FACTOR = 10.0
#: Without a rated payload in the robot file: no serial robot carries this much [kg] (the largest, about 2.3 t).
PAYLOAD_MAX_KG = 5000.0


def _check_payload(robot, payload, rows: np.ndarray, source: str) -> None:
    """Refuse a negative payload, and one too heavy for the robot to be in kilograms (a column in grams)."""
    if payload is None:
        return
    if (payload < 0).any():
        i = int(np.flatnonzero(payload < 0)[0])
        raise TolallocError(f"{source}: row {rows[i]}: payload_kg = {payload[i]:g} is negative; expected the mass the "
                            "robot holds at each pose, in kg (0 for none).")
    rated_kg = robot.components.payload.rated_kg
    limit = PAYLOAD_RATED_FACTOR * rated_kg if rated_kg else PAYLOAD_MAX_KG
    if payload.max() > limit:
        i = int(np.argmax(payload))
        what = (f"{payload[i] / rated_kg:.0f} times the rated payload of robot {robot.name!r}, {rated_kg:g} kg "
                "(components.payload.rated_kg)" if rated_kg else
                f"more than any serial robot carries ({PAYLOAD_MAX_KG:g} kg)")
        raise TolallocError(f"{source}: row {rows[i]}: payload_kg = {payload[i]:g} is {what}; a column in grams? "
                            "Expected kilograms: divide the column by 1000.")


def read_wrench(cols, column, source: str) -> np.ndarray | None:
    """The logged process wrench (P, 6) from the columns of :data:`WRENCH_COLUMNS` among ``cols``, each read by
    ``column(name)`` (P,), or None without any; a force or moment needs all three of its columns (the other one is
    zero when absent)."""
    parts = []
    for names in WRENCH_COLUMNS:
        present = [c for c in names if c in cols]
        if present and len(present) != 3:
            raise TolallocError(f"{source}: column(s) {present} given, expected all of {list(names)} (base frame) or "
                                "none; add the missing axes (0 where the process has no component).")
        parts.append(np.column_stack([column(c) for c in names]) if present else None)
    if parts[0] is None and parts[1] is None:
        return None
    n = len(next(p for p in parts if p is not None))
    wrench = np.column_stack([p if p is not None else np.zeros((n, 3)) for p in parts])
    if not np.all(np.isfinite(wrench)):
        raise TolallocError(f"{source}: the force / torque columns hold an infinite value; expected finite numbers.")
    return wrench


def read_measurements(path, robot: Robot) -> Measurements:
    """Read and validate a measurement CSV (comma-separated, '.' decimals); see the module docstring."""
    path = Path(path)
    if path.is_dir():
        raise TolallocError(f"measurement file {str(path)!r} is a directory; expected a CSV file with "
                            f"{JOINT_COLUMNS_TEXT} and x_mm, y_mm, z_mm.")
    if not path.is_file():
        raise TolallocError(f"measurement file {str(path)!r} does not exist; expected a CSV with {JOINT_COLUMNS_TEXT} "
                            "and x_mm, y_mm, z_mm.")
    try:
        # numbers straight to float64 (8 bytes a cell); any column that is not all numbers: read as text
        # again, so every cell gets the usual checks and messages
        opts = dict(skipinitialspace=True, encoding="utf-8-sig", skiprows=comment_lines(path))
        df = pd.read_csv(path, **opts)
        if not all(pd.api.types.is_float_dtype(t) or pd.api.types.is_integer_dtype(t) for t in df.dtypes):
            df = pd.read_csv(path, dtype=str, **opts)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise TolallocError(f"{path}: cannot be read as CSV ({exc}); expected comma-separated columns: "
                            f"{JOINT_COLUMNS_TEXT} and x_mm, y_mm, z_mm.") from None
    if df.shape[1] == 1 and ";" in str(df.columns[0]):
        raise TolallocError(f"{path}: looks ';'-separated; expected a comma-separated CSV with '.' decimals "
                            "(convert it; for the IPA UR10 files: "
                            "tolalloc.diagnose.read_ipa_ur10(path).to_csv(out, index=False)).")
    return measurements_from_frame(df, robot, str(path))


def comment_lines(path) -> int:
    """The number of ``#`` lines before the header (a calibration plan's settings), skipped by the reader."""
    k = 0
    try:
        with open(path, encoding="utf-8-sig") as f:
            for line in f:
                if not line.lstrip().startswith("#"):
                    break
                k += 1
    except (OSError, UnicodeDecodeError):
        return 0  # the reader says what is wrong with the file
    return k
