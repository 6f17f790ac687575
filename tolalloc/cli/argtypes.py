"""Argument types of the CLI: each refuses a bad value by its flag with one clear line, before any work.

Used as argparse ``type=``; a refused value raises :class:`argparse.ArgumentTypeError`, which the
parser of :mod:`tolalloc.cli` prints as one ``error:`` line naming the flag (exit 2).
"""

from __future__ import annotations

import argparse
import math

__all__ = ["count", "seed", "positive_float", "finite_float", "nonnegative_int"]


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
