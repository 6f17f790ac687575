"""The writer lock of an output directory, and the folders an output makes on its way.

A directory output is locked by ``.NAME.lock`` next to it, a :class:`filelock.FileLock` (``flock`` on Linux and
macOS, ``msvcrt.locking`` on Windows; where neither exists, filelock's soft lock), released by the operating system
if the process dies. The lock is taken without waiting: a second run writing the same directory at the same time
gets ``DIR is being written by another run``. :func:`tolalloc.outputs.atomic_output` holds it from staging to
publication; a command line reserves its output directories before it computes (:func:`reservations`,
:func:`reserve`), so the conflict is reported at the start, and the later staging in the same thread uses the
reservation instead of locking again.

The parent folders an output creates (``--out new/deeper/dir``) are removed again when nothing was published into
them (:func:`make_parents`, :func:`remove_empty`).
"""

from __future__ import annotations

import contextlib
import errno
import os
import threading
from pathlib import Path

from tolalloc.exceptions import TolallocError

__all__ = ["directory_lock", "reservations", "in_reservations", "reserve", "is_reserved", "lock_path", "make_parents",
           "remove_empty", "cannot_write", "ADVICE"]

#: what to do about an operating-system error, by errno (otherwise: choose another path)
ADVICE = {errno.ENOSPC: "free some space or choose another place",
          errno.EDQUOT: "free some of the quota or choose another place",
          errno.ENAMETOOLONG: "choose a shorter path", errno.EACCES: "choose a writable place",
          errno.EPERM: "choose a writable place", errno.EROFS: "choose a writable place"}


def cannot_write(path, directory: bool, exc: OSError, shown=str) -> TolallocError:
    """An :class:`OSError` while preparing or publishing output ``path`` as one line: the path, the cause, what to
    do. ``shown`` turns a path into the text shown (a staging path into its target)."""
    what = "an output directory" if directory else "an output file"
    why = exc.strerror or type(exc).__name__
    where = shown(os.fspath(exc.filename)) if isinstance(exc.filename, (str, os.PathLike)) else shown(str(path))
    return TolallocError(f"cannot write {what} at {shown(str(path))!r} ({why}: {where}); expected {what} path in "
                         f"a writable place; {ADVICE.get(exc.errno or 0, 'choose another path')}.")


def make_parents(folder: Path) -> list[Path]:
    """Create ``folder`` and its missing parents; returns the folders this call created, outermost first."""
    missing = []
    while not folder.exists() and folder != folder.parent:
        missing.append(folder)
        folder = folder.parent
    made = []
    for d in reversed(missing):
        try:
            d.mkdir()
        except FileExistsError:
            continue  # made meanwhile by another run: not ours to remove
        made.append(d)
    return made


def remove_empty(made: list[Path]) -> None:
    """Remove the folders of :func:`make_parents` again, innermost first, as long as they are empty."""
    for d in reversed(made):
        try:
            d.rmdir()
        except OSError:
            return


def lock_path(path) -> Path:
    """The lock file of output directory ``path``: ``.NAME.lock`` beside it."""
    path = Path(os.path.abspath(path))
    return path.parent / f".{path.name}.lock"


@contextlib.contextmanager
def directory_lock(path):
    """Hold the lock of output directory ``path`` (see the module docstring) for the block; the lock file and the
    parent folders made for it are removed afterwards."""
    from filelock import FileLock, Timeout

    lock_file = lock_path(path)
    try:
        made = make_parents(lock_file.parent)
    except OSError as exc:
        raise cannot_write(path, True, exc) from None
    try:
        lock = FileLock(str(lock_file), timeout=0)
        try:
            lock.acquire()
        except Timeout:
            raise TolallocError(f"{str(path)!r} is being written by another run (lock {str(lock_file)!r}); wait "
                                "for it to finish or choose another output directory.") from None
        except OSError as exc:
            raise cannot_write(path, True, exc) from None
        try:
            yield
        finally:
            lock.release()
            with contextlib.suppress(OSError):  # Windows: already removed by the release
                os.unlink(lock_file)
    finally:
        remove_empty(made)


_LOCAL = threading.local()


def _scopes() -> list:
    if not hasattr(_LOCAL, "scopes"):
        _LOCAL.scopes = []
    return _LOCAL.scopes


@contextlib.contextmanager
def reservations():
    """The directory locks :func:`reserve` takes inside the block are held until its end (this thread)."""
    with contextlib.ExitStack() as stack:
        scope = (stack, set())
        _scopes().append(scope)
        try:
            yield
        finally:
            _scopes().remove(scope)


def in_reservations() -> bool:
    """True inside a :func:`reservations` block (this thread)."""
    return bool(_scopes())


def is_reserved(path) -> bool:
    """True when this thread holds the lock of output directory ``path`` through :func:`reserve`."""
    key = str(lock_path(path))
    return any(key in keys for _, keys in _scopes())


def reserve(path) -> None:
    """Take the lock of output directory ``path`` now and hold it until the enclosing :func:`reservations` ends.

    Raises
    ------
    TolallocError
        When another run holds it (see :func:`directory_lock`), or the place is not writable.
    RuntimeError
        Outside :func:`reservations`.
    """
    if not _scopes():
        raise RuntimeError("reserve() needs an enclosing reservations() block")
    if is_reserved(path):
        return
    stack, keys = _scopes()[-1]
    stack.enter_context(directory_lock(path))
    keys.add(str(lock_path(path)))
