"""Progress bars of the diagnosis: on or off for a block of work (:func:`progress_scope`), one bar
(:func:`progress_bar`, a silent stand-in when progress is off) and one bar counting the fits of a block
(:func:`fit_counter`, :func:`count_fit`).

The fits and the pipeline's stages draw them (:mod:`.scale`, :mod:`.calibrate`, :mod:`.pipeline`); when progress
is on is :func:`tolalloc.progress.show_progress`'s business.
"""

from __future__ import annotations

import contextlib
import contextvars
import sys

from tolalloc.progress import show_progress

__all__ = ["progress_scope", "progress_bar", "fit_counter", "count_fit"]

_PROGRESS = contextvars.ContextVar("tolalloc_diagnose_progress", default=False)


@contextlib.contextmanager
def progress_scope(enabled: bool | None):
    """Turn progress bars on (True), off (False) or on when a person is watching (None: a terminal or a notebook,
    :func:`tolalloc.progress.show_progress`) inside the block."""
    token = _PROGRESS.set(show_progress(enabled))
    try:
        yield
    finally:
        _PROGRESS.reset(token)


def progress_bar(desc: str, total: int | None = None, unit: str = "it"):
    """A tqdm bar on stderr when progress is on (see :func:`progress_scope`), else a silent stand-in."""
    if not _PROGRESS.get():
        return _NoBar()
    from tqdm import tqdm

    return tqdm(total=total, desc=desc, unit=unit, file=sys.stderr, leave=False, dynamic_ncols=True)


_FITS = contextvars.ContextVar("tolalloc_diagnose_fit_bar", default=None)


@contextlib.contextmanager
def fit_counter(desc: str, total: int | None = None):
    """Count the fits (:func:`count_fit`) done inside the block on one progress bar."""
    bar = progress_bar(desc, total, unit="fit")
    token = _FITS.set(bar)
    try:
        yield bar
    finally:
        _FITS.reset(token)
        bar.close()


def count_fit() -> None:
    """One fit done (advances the bar of the enclosing :func:`fit_counter`, if any)."""
    bar = _FITS.get()
    if bar is not None:
        bar.update()


class _NoBar:
    def update(self, n=1):
        pass

    def set_postfix_str(self, s):
        pass

    def close(self):
        pass
