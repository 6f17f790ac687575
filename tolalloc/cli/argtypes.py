"""Argument types of the CLI: each refuses a bad value by its flag with one clear line, before any work.

Used as argparse ``type=``; a refused value raises :class:`argparse.ArgumentTypeError`, which the
parser of :mod:`tolalloc.cli` prints as one ``error:`` line naming the flag (exit 2).
"""

from __future__ import annotations

import argparse
import math

__all__ = ["count", "seed", "positive_float", "finite_float", "nonnegative_int", "row_ranges", "MAX_RANGE_ROWS"]

#: Most rows one ``row_ranges`` range may span (a slip such as ``1-10000000000`` is refused, not expanded).
MAX_RANGE_ROWS = 10_000_000


def _number(text: str) -> float:
    try:
        return float(str(text).replace("_", ""))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None


def count(text: str) -> int:
    """A whole number >= 1; ``1e6``, ``1_000_000`` and ``10**6``-style ``1e20`` are accepted."""
    s = str(text).strip().replace("_", "")
    try:
        value = int(s)
    except ValueError:
        x = _number(s)
        if not math.isfinite(x) or x != math.floor(x):
            raise argparse.ArgumentTypeError(f"expected a whole number >= 1 (e.g. 1000000 or 1e6), got {text!r}") from None
        value = int(x)
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 1 (e.g. 1000000 or 1e6), got {text!r}")
    return value


def nonnegative_int(text: str) -> int:
    """A whole number >= 0."""
    try:
        value = int(str(text).strip())
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 0, got {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 0, got {text!r}")
    return value


def seed(text: str) -> int:
    """A random seed: a whole number >= 0 (numpy's seeds are non-negative)."""
    try:
        value = int(str(text).strip())
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 0 as seed (e.g. 0 or 42), got {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 0 as seed (e.g. 0 or 42), got {text!r}")
    return value


def finite_float(text: str) -> float:
    """A finite number (no nan / inf)."""
    x = _number(text)
    if not math.isfinite(x):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return x


def positive_float(text: str) -> float:
    """A finite number > 0."""
    x = _number(text)
    if not (math.isfinite(x) and x > 0):
        raise argparse.ArgumentTypeError(f"expected a finite number > 0, got {text!r}")
    return x


def row_ranges(text: str) -> list:
    """Row numbers from 1 as comma-separated numbers and inclusive ranges, ``1-60,75,80-90`` -> [1, ..., 60, 75,
    80, ..., 90], in the order written (a row written twice is kept twice: the command refuses it by name)."""
    want = ("expected data rows of the test file from 1 as numbers and inclusive ranges separated by commas, "
            f"e.g. 1-60,75,80-90, got {text!r}")
    rows = []
    for part in str(text).split(","):
        ends = [e.strip() for e in part.split("-")]
        if not 1 <= len(ends) <= 2 or not all(e.isascii() and e.isdigit() for e in ends):
            raise argparse.ArgumentTypeError(want)
        lo, hi = int(ends[0]), int(ends[-1])
        if lo < 1 or hi < lo:
            raise argparse.ArgumentTypeError(want + ("; rows count from 1" if lo < 1 else
                                                     f"; a range runs upwards ({hi}-{lo}, not {lo}-{hi})"))
        if hi - lo + 1 > MAX_RANGE_ROWS:
            raise argparse.ArgumentTypeError(want + f"; a range spans at most {MAX_RANGE_ROWS:,} rows")
        rows.extend(range(lo, hi + 1))
    return rows
