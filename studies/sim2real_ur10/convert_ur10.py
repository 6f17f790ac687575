"""Convert the IPA UR10 laser-tracker files (';'-separated, decimal commas, joints in rad) to the
measurement CSV of `tolalloc diagnose` (q1..q6 in deg, x_mm, y_mm, z_mm, temperature_c, dir1..dir6, time_s).

Usage: python studies/sim2real_ur10/convert_ur10.py IN.csv OUT.csv [--max-rows N]

The data stays in ../shared/data (never copied into the repository); converted files go wherever OUT says. The
conversion is :func:`tolalloc.diagnose.read_ipa_ur10` (which says how ``time_s`` and ``dir1..dir6`` are derived);
this script adds where the shared data lives and a command line.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pandas as pd

from tolalloc.diagnose import read_ipa_ur10


def _data_dir() -> Path:
    """``shared/data/ipa-ur10`` beside the nearest ancestor folder that has one (repository or git worktree)."""
    for up in Path(__file__).resolve().parents:
        if (up / "shared" / "data" / "ipa-ur10").is_dir():
            return up / "shared" / "data" / "ipa-ur10"
    return Path(__file__).resolve().parents[3] / "shared" / "data" / "ipa-ur10"


DATA = _data_dir()
SERIES = {"A": "Series_A/measurements_grid.csv", "C": "Series_C/measurements_random_poses.csv"}


def series(name: str) -> pd.DataFrame:
    """Series 'A' (grid) or 'C' (random poses) from ../shared/data/ipa-ur10, converted."""
    return read_ipa_ur10(DATA / SERIES[name])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("input")
    ap.add_argument("output")
    ap.add_argument("--max-rows", type=int, default=None)
    a = ap.parse_args(argv)
    df = read_ipa_ur10(a.input)
    if a.max_rows:
        df = df.iloc[: a.max_rows]
    df.to_csv(a.output, index=False, float_format="%.8g")
    print(f"{len(df)} rows -> {a.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
