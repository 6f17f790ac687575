"""Progress of the long jobs, for all of them: whether it is shown, where, and the bars themselves.

Progress goes to stderr, never stdout, in the form its reader can use (:func:`progress_mode`):

* ``"bars"``: stderr is a terminal -- tqdm bars redrawn in place and cleared when done;
* ``"notebook"``: a Jupyter kernel with ipywidgets -- ``tqdm.auto``'s widget bars, which close when done, so a cell
  keeps no progress lines;
* ``"lines"``: anything else (a pipe, a CI log, a notebook without ipywidgets) -- no bars, but one line per stage,
  written when the stage ends, with its duration (``allocate tool_changer: region search (certified design): 12.3 s``).

``progress=False`` turns it off, ``True`` and ``None`` (the default) on; ``None`` leaves out a lone Monte Carlo run
below :data:`tolalloc.montecarlo.run.PROGRESS_MIN_N` samples. A job names its stages with :class:`StageBar`; work
inside a job draws its bars through :func:`progress_bar` within a :func:`progress_scope`, and fits count themselves on
the bar of the enclosing :func:`fit_counter` (:func:`count_fit`).
"""

from __future__ import annotations

import contextlib
import contextvars
import re
import sys
import time

__all__ = ["show_progress", "progress_mode", "StageBar", "progress_scope", "progress_bar", "new_bar", "fit_counter",
           "count_fit", "NoBar", "duration_text", "PROGRESS_LINE"]

#: A line written in ``"lines"`` mode: ``<stage>: [<count> <unit>s, ]<duration>`` (to tell progress from messages in a
#: log; an ``error:`` or ``warning:`` line never matches).
PROGRESS_LINE = re.compile(r"^(?!error: |warning: ).+: (?:[\d,]+ \S+, )?(?:\d+\.\d+ s|\d+ min \d\d s|\d+ h \d\d min)$")


def show_progress(progress: bool | None) -> bool:
    """Whether progress is shown: ``progress`` itself when given, on for None."""
    return True if progress is None else bool(progress)


def _notebook_widgets() -> bool:
    """True inside a Jupyter kernel whose front end can show ipywidgets' bars."""
    if "ipykernel" not in sys.modules:
        return False
    try:
        import ipywidgets  # noqa: F401
    except ImportError:
        return False
    return True


def progress_mode(progress: bool | None = None, stream=None) -> str | None:
    """How progress is shown on ``stream`` (default ``sys.stderr``): ``"bars"``, ``"notebook"``, ``"lines"`` or None
    (off); see the module docstring."""
    if not show_progress(progress):
        return None
    stream = sys.stderr if stream is None else stream
    try:
        if stream.isatty():
            return "bars"
    except (AttributeError, ValueError):  # no isatty, or a closed stream
        pass
    return "notebook" if _notebook_widgets() else "lines"


def duration_text(seconds: float) -> str:
    """``0.42 s``, ``12.3 s``, ``2 min 05 s``, ``1 h 02 min``."""
    if seconds < 10:
        return f"{seconds:.2f} s"
    if seconds < 60:
        return f"{seconds:.1f} s"
    if seconds < 3600:
        return f"{int(seconds // 60)} min {int(seconds % 60):02d} s"
    return f"{int(seconds // 3600)} h {int(seconds % 3600 // 60):02d} min"


def _write_line(text: str) -> None:
    sys.stderr.write(text + "\n")
    sys.stderr.flush()


class NoBar:
    """A silent stand-in for a bar (progress off). Bars are context managers: ``with progress_bar(...) as bar:``
    closes the bar at the end of the block (in a log: no line for a block cut short by an error)."""

    def __enter__(self):
        return self

    def __exit__(self, exc_type, *exc):
        if exc_type is not None:
            self._cut_short()
        self.close()
        return False

    def _cut_short(self):
        pass

    def update(self, n=1):
        pass

    def set_postfix_str(self, s):
        pass

    def set_description_str(self, s):
        pass

    def close(self):
        pass


class _LineBar(NoBar):
    """A bar for a log: counts quietly and writes one line when it closes -- what it did and how long it took."""

    def __init__(self, desc: str, unit: str):
        self.desc, self.unit, self.n, self._t0, self._closed = desc, unit, 0, time.perf_counter(), False

    def update(self, n=1):
        self.n += n

    def set_description_str(self, s):
        self.desc = s

    def _cut_short(self):
        self._closed = True

    def close(self):
        if self._closed:
            return
        self._closed = True
        count = f"{self.n:,} {self.unit}{'' if self.n == 1 else 's'}, " if self.unit != "it" and self.n else ""
        _write_line(f"{self.desc}: {count}{duration_text(time.perf_counter() - self._t0)}")


def new_bar(desc: str, total: int | None = None, unit: str = "it", *, mode: str | None = None, unit_scale: bool = False,
            detail: bool = False):
    """A bar on stderr in ``mode`` (default: :func:`progress_mode` of stderr): tqdm (``"bars"``), a notebook widget
    (``"notebook"``) or one line when it closes (``"lines"``; none for a ``detail`` bar, which is part of a stage
    that writes its own line); :class:`NoBar` when ``mode`` is off."""
    mode = progress_mode(True) if mode is None else mode
    if mode == "lines":
        return NoBar() if detail else _LineBar(desc, unit)
    if mode == "bars":
        from tqdm import tqdm
    elif mode == "notebook":
        from tqdm.auto import tqdm
    else:
        return NoBar()
    return tqdm(total=total, desc=desc, unit=unit, unit_scale=unit_scale, file=sys.stderr, leave=False,
                dynamic_ncols=True)


class StageBar:
    """The stages of one job on stderr (``with StageBar(show, "allocate") as bar: bar.stage("region search")``):
    a status line naming the stage and the time so far (terminal, notebook), or one line per finished stage with its
    duration (a log); a no-op when ``show`` is false."""

    def __init__(self, show: bool, job: str):
        self.job, self._bar, self._t0 = job, None, 0.0
        self._name: str | None = None
        self._mode = progress_mode(True) if show else None
        if self._mode in ("bars", "notebook"):
            self._bar = new_bar(job, unit="stage", mode=self._mode)
            self._bar.bar_format = "{desc} ({elapsed} so far)"

    def _finish(self) -> None:
        if self._mode == "lines" and self._name is not None:
            _write_line(f"{self.job}: {self._name}: {duration_text(time.perf_counter() - self._t0)}")
        elif self._bar is not None and self._name is not None:
            self._bar.update(1)

    def stage(self, name: str) -> None:
        """Start stage ``name`` (the previous one is done)."""
        if self._mode is None:
            return
        self._finish()
        self._name, self._t0 = name, time.perf_counter()
        if self._bar is not None:
            self._bar.set_description_str(f"{self.job}: {name}")

    def __enter__(self):
        return self

    def __exit__(self, exc_type, *exc):
        if exc_type is None:
            self._finish()  # the last stage (a stage cut short by an error or an interrupt writes no line)
        if self._bar is not None:
            self._bar.close()
        return False


_MODE: contextvars.ContextVar[str | None] = contextvars.ContextVar("tolalloc_progress_mode", default=None)


@contextlib.contextmanager
def progress_scope(progress: bool | None):
    """Bars of :func:`progress_bar` on (True, None: in the :func:`progress_mode` of stderr) or off (False) inside
    the block."""
    token = _MODE.set(progress_mode(progress))
    try:
        yield
    finally:
        _MODE.reset(token)


def progress_bar(desc: str, total: int | None = None, unit: str = "it", *, detail: bool = False):
    """A bar (:func:`new_bar`) when the enclosing :func:`progress_scope` has progress on, else a :class:`NoBar`;
    use it as a context manager (``with progress_bar("reading") as bar:``)."""
    mode = _MODE.get()
    return NoBar() if mode is None else new_bar(desc, total, unit, mode=mode, detail=detail)


_FITS = contextvars.ContextVar("tolalloc_fit_bar", default=None)


@contextlib.contextmanager
def fit_counter(desc: str, total: int | None = None):
    """Count the fits (:func:`count_fit`) done inside the block on one bar."""
    bar = progress_bar(desc, total, unit="fit")
    token = _FITS.set(bar)
    try:
        with bar:
            yield bar
    finally:
        _FITS.reset(token)


def count_fit() -> None:
    """One fit done (advances the bar of the enclosing :func:`fit_counter`, if any)."""
    bar = _FITS.get()
    if bar is not None:
        bar.update()
