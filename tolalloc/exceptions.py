"""Input checks used at public entry points.

Every failure raises :class:`TolallocError` whose message says what was
expected, what arrived and what to do; the CLI turns it into one line on
stderr and a non-zero exit.
"""

from __future__ import annotations

import contextlib
import os
import re
import signal
import threading
from typing import Any

import numpy as np

__all__ = ["TolallocError", "ArgumentError", "UnknownArgumentError", "InputFileError", "Interrupted",
           "signals_deferred", "interrupts_as_exceptions", "interruptible", "note_interrupt", "interrupt_pending",
           "clear_interrupt",
           "raise_if_interrupted", "check_vector", "check_finite_array", "check_positive", "known_names",
           "memory_budget_bytes", "check_memory", "describe", "whole_number"]


class TolallocError(ValueError):
    """A user-facing input error (bad robot file, bad joint values, bad sigma ...)."""

    def __str__(self) -> str:
        if not self.args:
            return ""
        return _text(self.args[0]) if len(self.args) == 1 else "; ".join(_text(a) for a in self.args)


def _text(value) -> str:
    """``value`` as message text: a string as it is, bytes decoded, anything else by its ``str`` (or ``repr`` when that
    fails): formatting a message never raises."""
    if isinstance(value, str):
        return value
    if isinstance(value, (bytes, bytearray)):
        return bytes(value).decode("utf-8", "replace")
    try:
        return str(value)
    except Exception:  # a value whose __str__ fails still leaves a message
        return object.__repr__(value)


class ArgumentError(TolallocError):
    """A bad value of one named argument of a public call.

    ``str(exc)`` is ``"<argument>: <detail>"`` (``"<argument> <detail>"`` when the detail goes on a sentence:
    ``"angle_prob 0.9 needs ..."``); the command line prints the same text with the argument's flag in place of
    its Python name (``radius_mm`` -> ``--radius-mm``), and other arguments named in backticks by their flags.
    Any values are taken (as text), so that raising one never fails.

    Attributes
    ----------
    argument : str
        The keyword argument of the public call (``radius_mm``, ``q_deg_mm`` ...).
    detail : str
        What was expected, what arrived and what to do.
    """

    def __init__(self, argument="", detail="", *more):
        argument, detail = _text(argument), " ".join(_text(d) for d in (detail, *more))
        self.sep = " " if detail.startswith(("needs ", "and ")) or detail[:1].isdigit() else ": "
        super().__init__(f"{argument}{self.sep}{detail}" if argument else detail)
        self.argument = argument
        self.detail = detail

    def __reduce__(self):  # pickled across processes (Dask workers) with its two parts
        return type(self), (self.argument, self.detail)


class UnknownArgumentError(ArgumentError, TypeError):
    """A keyword argument a public call does not have: a :class:`TypeError` as Python's own, whose text names the
    call's arguments closest to the one given (``radius`` -> ``radius_mm``) and where the full list is."""


class InputFileError(TolallocError, FileNotFoundError):
    """An input file that does not exist (a robot file, a measurement or plan file, a trajectory).

    ``argument``: the keyword argument that named the file, when the message starts with it (``"parts: ..."``); the
    command line prints its flag there instead, as for an :class:`ArgumentError`.
    """

    def __new__(cls, *args, **kwargs):  # OSError's layout, whoever asks (pickling helpers call cls.__new__ bare)
        return OSError.__new__(cls, *args)

    def __init__(self, message="", *more, argument: str = ""):
        TolallocError.__init__(self, message, *more)
        self.argument = argument

    def __str__(self) -> str:
        return TolallocError.__str__(self)


@contextlib.contextmanager
def signals_deferred():
    """Hold SIGINT / SIGTERM back during the block; they are delivered right after it.

    Used around a native call that would trap the Python handler's exception, and around publishing outputs
    (an interrupt never lands between a rename and its record). CasADi turns an exception raised by a signal
    handler during IPOPT (its callbacks run Python code) into a solver stop with a warning on stderr and carries
    on; held back, the signal interrupts as usual right after the call.

    The Python-level handlers are swapped for one that only records the signal, and the recorded signal is then
    handed to the previous handler (re-sent to the process if that was the default action). A thread signal
    mask would not do: the kernel delivers a process signal to any thread that does not block it (BLAS and
    solver threads), and Python then runs the handler in the main thread inside the call anyway.
    Main thread only (elsewhere a no-op, as Python runs handlers only there).
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    got: list = []

    def hold(signum, frame):
        got.append(signum)

    old = {s: signal.signal(s, hold) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for s, h in old.items():
            signal.signal(s, h)
        if got:
            _deliver(got[0], old[got[0]])


_GUARD_DEPTH = [0]


@contextlib.contextmanager
def interrupts_as_exceptions():
    """SIGINT and SIGTERM, where Python's defaults are in place, raise :class:`Interrupted` inside the block.

    So the block's clean-up (``finally``, ``with``) runs on SIGTERM too, whose default ends the process on the spot;
    after the block, SIGTERM then ends the process as it would have. An error a library raises while a signal is
    pending (an interrupt inside an import can come out as an ``ImportError`` or a ``RuntimeError``) becomes the
    :class:`Interrupted` it stands for. Handlers a program installed itself (the command line's) are left alone.
    Main thread only (elsewhere a no-op); a nested block is a no-op.
    """
    if threading.current_thread() is not threading.main_thread() or _GUARD_DEPTH[0]:
        yield
        return
    got: list = []

    def on_signal(signum, frame):
        got.append(signum)
        raise Interrupted(signum)

    swapped = {s: signal.signal(s, on_signal) for s, default in ((signal.SIGINT, signal.default_int_handler),
                                                                 (signal.SIGTERM, signal.SIG_DFL))
               if signal.getsignal(s) is default}
    _GUARD_DEPTH[0] += 1
    try:
        yield
        if got:  # the handler's exception was swallowed and the block finished
            raise Interrupted(got[0])
    except BaseException as exc:
        if got and not isinstance(exc, Interrupted):
            raise Interrupted(got[0]) from exc
        raise
    finally:
        _GUARD_DEPTH[0] -= 1
        for s, h in swapped.items():
            signal.signal(s, h)
        if got and got[0] == signal.SIGTERM:
            os.kill(os.getpid(), signal.SIGTERM)  # the default action, now that the block has cleaned up


def _deliver(signum: int, handler) -> None:
    """Hand a held signal to ``handler`` as the process would have."""
    if callable(handler):
        handler(signum, None)
    elif handler == signal.SIG_DFL:
        os.kill(os.getpid(), signum)


def interruptible(fn, *args, **kwargs):
    """Return ``fn(*args, **kwargs)``, run in a worker thread so that SIGINT / SIGTERM stop the wait at once.

    For native solvers that release the GIL but never return to the interpreter until they finish (Clarabel):
    Python runs signal handlers only in the main thread between bytecodes, so an interrupt during a long solve
    waited for the solve (18 s on a loaded machine). The main thread now waits in short joins, the handler's
    exception propagates from there, and the daemon worker dies with the process. Outside the main thread
    ``fn`` is called directly. Exceptions of ``fn`` are re-raised in the caller.
    """
    if threading.current_thread() is not threading.main_thread():
        return fn(*args, **kwargs)
    box: dict = {}

    def work():
        try:
            box["value"] = fn(*args, **kwargs)
        except BaseException as exc:  # handed to the caller below
            box["error"] = exc

    worker = threading.Thread(target=work, name="tolalloc-solver", daemon=True)
    raise_if_interrupted()
    worker.start()
    while worker.is_alive():
        worker.join(0.05)
    raise_if_interrupted()
    if "error" in box:
        raise box["error"]
    return box["value"]


class Interrupted(KeyboardInterrupt):
    """SIGINT or SIGTERM arrived; ``signum`` says which (SIGINT when not given)."""

    def __init__(self, signum: int = signal.SIGINT):
        super().__init__(signum)
        self.signum = signum


#: Signals the CLI's handler has seen (see :func:`raise_if_interrupted`).
_PENDING: list = []


def note_interrupt(signum: int) -> None:
    """Record that signal ``signum`` arrived (the CLI's handler, before it raises :class:`Interrupted`)."""
    _PENDING.append(signum)


def interrupt_pending() -> bool:
    """True when a signal was recorded by :func:`note_interrupt` and not cleared."""
    return bool(_PENDING)


def clear_interrupt() -> None:
    """Forget recorded signals (a CLI run starts or ends)."""
    _PENDING.clear()


def raise_if_interrupted() -> None:
    """Checkpoint: raise :class:`Interrupted` again if a signal arrived whose exception a library swallowed.

    The handler's exception can be lost: a signal while cvxpy imports its solver interfaces turns into an
    ``ImportError('initialization failed')`` of a C extension, which cvxpy logs and ignores, and the run then
    finished and wrote its output with signals ignored. Called before each solve and before anything is
    published, so such a run still stops, with nothing written.
    """
    if _PENDING:
        raise Interrupted(_PENDING[0])


def check_finite_array(value: Any, name: str, shape: tuple | None = None) -> np.ndarray:
    """Return ``value`` as a float array; raise if non-numeric, non-finite or of the wrong shape.

    ``shape`` may contain ``None`` for a free dimension.
    """
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise TolallocError(f"{name}: expected numbers, got {describe(value)}.") from None
    if shape is not None:
        ok = arr.ndim == len(shape) and all(s is None or s == a for s, a in zip(shape, arr.shape))
        if not ok:
            want = "(" + ", ".join("N" if s is None else str(s) for s in shape) + ")"
            raise TolallocError(f"{name}: expected an array of shape {want}, got shape {arr.shape}.")
    if not np.all(np.isfinite(arr)):
        shown = " ".join(np.array2string(arr, threshold=12).split())
        raise TolallocError(f"{name}: expected finite numbers, got {shown}.")
    return arr


def check_vector(value: Any, name: str, size: int) -> np.ndarray:
    """Return a finite float vector of length ``size``."""
    return check_finite_array(value, name, (size,))


def check_positive(value: Any, name: str, *, allow_zero: bool = False) -> float:
    """Return ``value`` as a float, raising unless it is finite and > 0 (or >= 0)."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise TolallocError(f"{name}: expected a number, got {describe(value)}.") from None
    if not np.isfinite(x) or x < 0 or (x == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise TolallocError(f"{name}: expected a finite number {bound}, got {describe(value)}.")
    return x


def known_names(*groups) -> str:
    """The names a message offers after ``known:``, each once, in the order given (``", "``-joined).

    Pass the groups in the order the user meets them: built-in names first (``limits``, ``nominal``,
    ``generic``), then the robot file's regions, pose sets or sigma sets; a name in two groups is listed where it
    first appears (a box region and a pose set both called ``working`` are one name to type).
    """
    return ", ".join(dict.fromkeys(str(name) for group in groups for name in group))


def memory_budget_bytes() -> int:
    """Bytes one array of a call may take: half the machine's physical memory (4 GiB where it cannot be read)."""
    try:
        total = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):
        total = 8 * 2**30
    return int(total) // 2


def _bytes_text(n: float) -> str:
    for unit, size in (("TiB", 2**40), ("GiB", 2**30), ("MiB", 2**20)):
        if n >= size:
            return f"{n / size:,.0f} {unit}" if n >= 1000 * size else f"{n / size:.3g} {unit}"
    return f"{n:.0f} bytes"


def check_memory(count: int, bytes_each: float, argument: str, what: str, example: str) -> int:
    """Refuse a count whose arrays would not fit in memory (:func:`memory_budget_bytes`); returns ``count``.

    ``bytes_each`` is the memory one item (a sample kept, a candidate pose ...) holds at once; the message names
    ``argument``, the memory the count would need and the largest count that fits.
    """
    budget = memory_budget_bytes()
    need = float(count) * float(bytes_each)
    if need > budget:
        largest = int(budget // max(float(bytes_each), 1.0))
        raise ArgumentError(argument, f"{count:g} {what} would hold about {_bytes_text(need)} in memory at once, more "
                            f"than the {_bytes_text(budget)} a call may use on this machine; expected at most "
                            f"{largest:,} (e.g. {example}).")
    return count


def describe(value, limit: int = 60) -> str:
    """What arrived, for a message, on one line: a number or string as its repr, anything else with its type."""
    if type(value).__repr__ is object.__repr__:  # a default repr shows only a memory address
        return f"a {type(value).__name__} object"
    text = re.sub(r" at 0x[0-9a-fA-F]+", "", " ".join(repr(value).split()))  # no memory addresses
    if len(text) > limit:
        text = text[:limit - 3] + "..."
    plain = isinstance(value, (str, int, float)) and not isinstance(value, bool)
    return text if plain else f"{type(value).__name__} {text}"


def whole_number(value) -> int | None:
    """``value`` as an int if it is a whole number (int, numpy integer, or a float such as 1e6), else None."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        return None
    try:
        return int(value) if float(value) == int(value) else None
    except (ValueError, OverflowError):
        return None
