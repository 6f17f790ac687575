"""Convert the IPA UR10 laser-tracker files (';'-separated, decimal commas, joints in rad) to the
measurement CSV of `tolalloc diagnose` (q1..q6 in deg, x_mm, y_mm, z_mm, temperature_c, dir1..dir6, time_s).

Usage: python studies/sim2real_ur10/convert_ur10.py IN.csv OUT.csv [--max-rows N]

The data stays in ../shared/data (never copied into the repository); converted files go wherever OUT says.
``time_s`` is the row order times 1 s: Series C's time stamps were mangled by a spreadsheet (see its README).
``dir1..dir6`` are the signs of each joint's change from the previous row (+1 when unchanged or first): an
assumption -- the robot's actual path between the points is not recorded.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import pandas as pd

JOINTS = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"]


def _data_dir() -> Path:
    """``shared/data/ipa-ur10`` beside the nearest ancestor folder that has one (repository or git worktree)."""
    for up in Path(__file__).resolve().parents:
        if (up / "shared" / "data" / "ipa-ur10").is_dir():
            return up / "shared" / "data" / "ipa-ur10"
    return Path(__file__).resolve().parents[3] / "shared" / "data" / "ipa-ur10"


DATA = _data_dir()
SERIES = {"A": "Series_A/measurements_grid.csv", "C": "Series_C/measurements_random_poses.csv"}


def read_ur10(path) -> pd.DataFrame:
    """Read one IPA UR10 file into the measurement table (interface units)."""
    raw = pd.read_csv(path, sep=";", decimal=",", dtype=str)
    missing = [c for c in (*JOINTS, "measurement_x", "measurement_y", "measurement_z") if c not in raw.columns]
    if missing:
        raise ValueError(f"{path}: missing columns {missing}; is this an IPA UR10 measurement file?")

    def num(c):
        return pd.to_numeric(raw[c].str.replace(",", ".", regex=False), errors="coerce").to_numpy(float)

    out = {f"q{j + 1}": np.rad2deg(num(c)) for j, c in enumerate(JOINTS)}
    out.update({"x_mm": num("measurement_x"), "y_mm": num("measurement_y"), "z_mm": num("measurement_z")})
    if "measurement_temperature" in raw.columns:
        out["temperature_c"] = num("measurement_temperature")
    q = np.column_stack([out[f"q{j + 1}"] for j in range(6)])
    d = np.sign(np.diff(q, axis=0, prepend=q[:1]))
    d[d == 0] = 1.0
    out.update({f"dir{j + 1}": d[:, j] for j in range(6)})
    out["time_s"] = np.arange(len(raw), dtype=float)
    return pd.DataFrame(out)


def series(name: str) -> pd.DataFrame:
    """Series 'A' (grid) or 'C' (random poses) from ../shared/data/ipa-ur10, converted."""
    return read_ur10(DATA / SERIES[name])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("input")
    ap.add_argument("output")
    ap.add_argument("--max-rows", type=int, default=None)
    a = ap.parse_args(argv)
    df = read_ur10(a.input)
    if a.max_rows:
        df = df.iloc[: a.max_rows]
    df.to_csv(a.output, index=False, float_format="%.8g")
    print(f"{len(df)} rows -> {a.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
