"""Checks of single workflow arguments, each refusing a bad value by its keyword argument.

Every refusal is an :class:`~tolalloc.exceptions.ArgumentError` that names the argument, shows what arrived (on
one line, :func:`~tolalloc.exceptions.describe`) and says what would work; the command line prints it with the
argument's flag. Values are strict: numbers are numbers (not strings or bools), flags are ``True`` / ``False``,
names are strings, paths are ``str`` or ``os.PathLike``.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.units import RANGES, check_positive, check_probability, number  # noqa: F401 (re-exported)
from tolalloc.exceptions import ArgumentError, TolallocError, describe, known_names, whole_number

__all__ = ["shown", "check_values", "check_probability", "RANGES", "check_positive", "check_count", "check_seed",
           "check_choice", "check_flag", "check_optional_flag", "check_name", "check_names", "check_path", "Z_RANGE",
           "check_z", "check_costs_file", "check_scheduler", "check_model_options", "check_not_both", "number",
           "check_axes", "check_text"]


def shown(value, limit: int = 60) -> str:
    """What arrived, for a message (see :func:`tolalloc.exceptions.describe`)."""
    return describe(value, limit)


def check_not_both(first, first_argument: str, second, second_argument: str, what: str, hint: str = "") -> None:
    """Refuse two arguments given together (not None) when one would silently override the other.

    The message reads ``"<first>: <value> and `<second>` <value> both <what>; give one of them<hint>."``.
    """
    if first is not None and second is not None:
        raise ArgumentError(first_argument, f"{shown(first)} and `{second_argument}` {shown(second)} both {what}; "
                            f"give one of them{hint}.")


def check_values(value, argument: str, check, *args, **kwargs) -> list:
    """A number or a flat sequence of numbers, each checked by ``check(x, argument, *args, **kwargs)``."""
    if isinstance(value, (list, tuple, np.ndarray, pd.Series)):
        items = list(np.ravel(np.asarray(value, dtype=object))) if not isinstance(value, (list, tuple)) else list(value)
        if any(isinstance(v, (list, tuple, np.ndarray, pd.Series, dict)) for v in items):
            raise ArgumentError(argument, f"expected a number or a flat list of numbers, got {shown(value)}.")
        return [check(v, argument, *args, **kwargs) for v in items]
    return [check(value, argument, *args, **kwargs)]


def check_count(value, argument: str, *, minimum: int = 1, example: str = "1000000", maximum: int | None = None) -> int:
    """A whole number >= ``minimum`` (and <= ``maximum``); ``1e6`` as a float is accepted when it is whole."""
    want = f"a whole number >= {minimum}" + ("" if maximum is None else f" and <= {maximum}")
    n = whole_number(value)
    if n is None or n < minimum or (maximum is not None and n > maximum):
        raise ArgumentError(argument, f"expected {want} (e.g. {example}), got {shown(value)}.")
    return n


def check_seed(value, argument: str = "seed") -> int:
    """A random seed: a whole number >= 0 (numpy takes seeds below 2**128)."""
    return check_count(value, argument, minimum=0, example="0 or 42", maximum=2**128 - 1)


def check_choice(value, argument: str, choices) -> str:
    """One of ``choices`` (strings)."""
    if not isinstance(value, str) or value not in choices:
        raise ArgumentError(argument, f"expected one of {', '.join(repr(c) for c in choices)}, got {shown(value)}.")
    return str(value)


def check_flag(value, argument: str) -> bool:
    """``True`` or ``False`` (a numpy bool too); anything else is refused rather than read by its truth value."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise ArgumentError(argument, f"expected True or False, got {shown(value)}.")


def check_optional_flag(value, argument: str) -> bool | None:
    """``None`` (automatic), ``True`` or ``False``."""
    return None if value is None else check_flag(value, argument)


def check_name(value, argument: str, what: str, known=None) -> str | None:
    """``None`` or a non-empty string (one of ``known`` if given: a list of names offered in the message)."""
    if value is None:
        return None
    if not isinstance(value, str) or not value.strip():
        extra = f" ({known_names(known)})" if known else ""
        raise ArgumentError(argument, f"expected {what}{extra} as a string, got {shown(value)}.")
    if known is not None and value not in known:
        raise ArgumentError(argument, f"unknown {what} {value!r}; known: {known_names(known)}.")
    return str(value)


def check_names(value, argument: str, what: str) -> tuple:
    """A name or a list / tuple of names (strings) -> tuple of str."""
    if isinstance(value, str):
        value = (value,)
    if not isinstance(value, (list, tuple, set, frozenset)) or not all(isinstance(v, str) and v.strip() for v in value):
        raise ArgumentError(argument, f"expected {what}: a name or a list of names, e.g. ('dl1', 'axis_deflection'), "
                            f"got {shown(value)}.")
    return tuple(dict.fromkeys(value))


def check_path(value, argument: str, what: str) -> Path | None:
    """``None`` or a path (str or os.PathLike) to an input file."""
    if value is None:
        return None
    if not isinstance(value, (str, os.PathLike)) or not str(value).strip() or "\0" in str(value):
        raise ArgumentError(argument, f"expected a path to {what} (a str or pathlib.Path), got {shown(value)}.")
    return Path(value)


#: sigma = t / z: smallest and largest z (a tolerance of 1/100 .. 100 standard deviations)
Z_RANGE = (1e-2, 1e2)


def check_z(value, argument: str = "z") -> float:
    """``z`` of sigma = t / z, a number within :data:`Z_RANGE`."""
    x = np.nan if isinstance(value, (bool, np.bool_)) else number(value, argument)
    if not (np.isfinite(x) and Z_RANGE[0] <= x <= Z_RANGE[1]):
        raise ArgumentError(argument, f"expected a number > 0 (sigma = t / z, e.g. 3) between {Z_RANGE[0]:g} and "
                            f"{Z_RANGE[1]:g}, got {shown(value)}.")
    return x


def check_costs_file(path, argument: str = "costs") -> Path | None:
    """``None`` or the path of a readable TOML costs file whose ``z`` (if any) lies within :data:`Z_RANGE`; its
    other keys are checked by :func:`tolalloc.allocate.costs.load_costs`."""
    import tomllib

    path = check_path(path, argument, "a costs file (TOML)")
    if path is None or not path.is_file():
        return path  # a missing file or a directory: the costs loader says which
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8-sig"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError, OSError) as exc:
        raise ArgumentError(argument, f"{path}: not valid TOML ({exc}); expected a costs file with tables such as "
                            "[kinds.link_length] holding a, b, t_ref_mm, t_min_mm, t_max_mm (see tolalloc.allocate.costs)."
                            ) from None
    z = data.get("z")
    if isinstance(z, (int, float)) and not isinstance(z, bool) and not Z_RANGE[0] <= z <= Z_RANGE[1]:
        raise ArgumentError(argument, f"{str(path)!r}: z = {z!r} (sigma = t / z) is outside {Z_RANGE[0]:g} .. "
                            f"{Z_RANGE[1]:g}; expected a number such as z = 3.")
    return path


def check_scheduler(value, argument: str = "scheduler"):
    """Where Monte Carlo samples run (see :func:`tolalloc.montecarlo.parallel.check_scheduler`)."""
    if value is not None and not isinstance(value, str) and not hasattr(value, "submit"):
        raise ArgumentError(argument, f"expected None (local threads), 'threads', 'processes', a Dask scheduler "
                            f"address such as 'tcp://10.0.0.5:8786' or a distributed.Client, got {shown(value)}.")
    from tolalloc.montecarlo.parallel import check_scheduler as check

    try:
        return check(value)
    except ArgumentError:
        raise
    except TolallocError as exc:
        text = str(exc)
        raise ArgumentError(argument, text[len(argument) + 2:] if text.startswith(argument + ": ") else text) from None


def check_model_options(*, sigma_set=None, link_mode="consistent", deflection_mode="screw", clearance=False,
                        exclude=(), sigma=None, clearance_tilt_literal=False) -> tuple:
    """Check the error-model options that need no robot; returns ``exclude`` as a tuple of names."""
    check_name(sigma_set, "sigma_set", "the name of a sigma set of the robot file (or 'generic')")
    check_choice(link_mode, "link_mode", ("consistent", "axes_only"))
    check_choice(deflection_mode, "deflection_mode", ("screw", "tilt"))
    check_flag(clearance, "clearance")
    check_flag(clearance_tilt_literal, "clearance_tilt_literal")
    if clearance_tilt_literal and not clearance:
        raise ArgumentError("clearance_tilt_literal", "changes the clearance tilt sigma, but clearance is off; add "
                            "`clearance` (or leave out `clearance_tilt_literal`).")
    if sigma is not None and not isinstance(sigma, dict):
        raise ArgumentError("sigma", f"expected a dict {{parameter or kind: sigma in mm or deg}}, got {shown(sigma)}.")
    return check_names(exclude, "exclude", "parameters or kinds to leave out")


def check_axes(value, argument: str, count: int = 1):
    """``None`` (a new figure) or where a plot draws: a matplotlib ``Axes`` (``count`` 1) or a sequence of ``count``
    of them (a figure's ``axes`` array); returns it unchanged."""
    if value is None:
        return None
    from matplotlib.axes import Axes

    items = [value] if count == 1 else (list(np.ravel(np.asarray(value, dtype=object)))
                                        if isinstance(value, (list, tuple, np.ndarray)) else None)
    if items is None or len(items) != count or not all(isinstance(a, Axes) for a in items):
        want = "a matplotlib Axes (e.g. fig, ax = plt.subplots())" if count == 1 else \
            f"{count} matplotlib Axes side by side (e.g. fig, axes = plt.subplots(1, {count}))"
        raise ArgumentError(argument, f"expected None (a new figure) or {want}, got {shown(value)}.")
    return value


def check_text(value, argument: str, what: str) -> str | None:
    """``None`` or a string (a title, a label)."""
    if value is not None and not isinstance(value, str):
        raise ArgumentError(argument, f"expected {what} as a string (or None), got {shown(value)}.")
    return value
