"""All-or-nothing output: early path checks, staged writes, one-step publication, a writer lock.

Every output is written into a temporary sibling of its target (``.tmp-*`` in the target's parent)
and published only when the whole command succeeded:

* a file by one :func:`os.replace`;
* a new directory by one :func:`os.rename` of the staged folder;
* an existing directory by replacing its files of the same name, with SIGINT / SIGTERM held back until the
  last file is in place; files an earlier publication wrote there and this one does not are removed (the
  directory's :data:`MANIFEST` lists them), other files are kept.

A directory output is locked (``.NAME.lock`` next to it, see :mod:`tolalloc.output_lock`) from staging to
publication; a second run writing the same directory at the same time gets ``DIR is being written by another run``.
The command line takes the lock of its output directories before it computes (:func:`reserve_directory` inside
:func:`reservations`), so the conflict is reported at the start.

An error or an interrupt removes the staged folder, the lock and the parent folders the output created, so nothing
half-written stays on disk. An :class:`OSError` while staging or publishing (no space left, a quota, permission
denied, a path too long) becomes one :class:`~tolalloc.exceptions.TolallocError` naming the path and the cause.
Outside the command line (whose handlers turn SIGTERM into an exception), a SIGTERM while an output is staged is
held as an exception until the staged output is removed, then ends the process as SIGTERM does.
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import tempfile
from pathlib import Path

import numpy as np

from tolalloc.exceptions import (ArgumentError, TolallocError, interrupts_as_exceptions, raise_if_interrupted,
                                 signals_deferred)
from tolalloc.output_lock import (ADVICE, cannot_write, directory_lock, in_reservations, is_reserved, make_parents,
                                  remove_empty, reservations, reserve)

__all__ = ["atomic_output", "output_group", "check_output", "check_distinct_outputs", "write_json", "json_default",
           "json_native", "directory_lock", "reservations", "reserve_directory", "published"]

#: paths published by this process since the last :func:`published` reset (read by the interrupt message)
_PUBLISHED: list = []


def json_default(obj):
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, (np.floating, np.integer)):
        return obj.item()
    if isinstance(obj, np.bool_):
        return bool(obj)
    if isinstance(obj, np.str_):
        return str(obj)
    raise TypeError(f"not JSON serialisable: {type(obj)}")


def json_native(obj):
    """``obj`` with numpy arrays and scalars turned into lists and Python numbers, recursively (what ``json.dumps``
    takes as it is); dict keys and other values unchanged."""
    if isinstance(obj, dict):
        return {k: json_native(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [json_native(v) for v in obj]
    if isinstance(obj, (np.ndarray, np.generic)):
        return json_native(json_default(obj))
    return obj



#: staging path -> the output it stands for, while staged (error messages name the output, not the staging path)
_STAGED: dict = {}


def _shown(name: str) -> str:
    """``name`` with a staging path replaced by the output it stands for (innermost staging first)."""
    for _ in range(8):  # staged outputs nest (a JSON file staged inside a staged directory)
        for tmp, target in _STAGED.items():
            if name == tmp or name.startswith(tmp + os.sep):
                name = target + name[len(tmp):]
                break
        else:
            return name
    return name


def _write_failed(exc: OSError, targets: list) -> TolallocError:
    """An :class:`OSError` raised while staged outputs ``targets`` were written, as one line: the file it names
    (where it was going, not its staging path), or the outputs, the cause and what to do."""
    if isinstance(exc.filename, (str, os.PathLike)):
        where = repr(_shown(os.fspath(exc.filename)))
    else:
        where = " and ".join(repr(_shown(str(t))) for t in targets)
    why = exc.strerror or str(exc) or type(exc).__name__
    return TolallocError(f"cannot write {where} ({why}); nothing was written; "
                         f"{ADVICE.get(exc.errno or 0, 'choose another path')}.")


def _cannot_write(path: Path, directory: bool, exc: OSError) -> TolallocError:
    return cannot_write(path, directory, exc, shown=_shown)


def _path_text(path, name: str) -> str:
    """``path`` (a str or :class:`os.PathLike`) as its text; anything else is refused naming ``name``."""
    value = os.fspath(path) if isinstance(path, os.PathLike) else path
    if not isinstance(value, str) or "\0" in value:
        shown = " ".join(repr(path).split())[:60]
        raise ArgumentError(name, f"expected a path (a str or os.PathLike such as pathlib.Path), got "
                            f"{type(path).__name__} {shown}; give a file or directory path.")
    return value


def check_output(path, flag: str, *, directory: bool = False) -> None:
    """Fail early (before any computation) if ``path`` cannot be written as an output file / directory.

    ``None`` and ``'-'`` (stdout, files only) pass; an empty path is refused. Nothing is created.

    Raises
    ------
    TolallocError
        Naming ``flag`` and the path: empty, a directory where a file is expected (or the reverse),
        below a file, or in a place that is not writable.
    """
    if path is None:
        return
    path = _path_text(path, flag)
    if path == "-" and not directory:
        return
    if not path.strip():
        want = "a directory" if directory else "a file"
        raise TolallocError(f"{flag}: expected {want} path, got an empty string; give a path or leave out {flag}.")
    try:
        _check_place(Path(path), flag, directory)
    except OSError as exc:  # a name too long, a loop of symbolic links ...
        why = exc.strerror or type(exc).__name__
        raise TolallocError(f"{flag} {_short(path)!r}: cannot be used as an output path ({why}); "
                            f"{ADVICE.get(exc.errno or 0, 'choose another path')}.") from None


def _short(text: str, n: int = 120) -> str:
    """``text`` shortened in the middle to about ``n`` characters."""
    return text if len(text) <= n else f"{text[:n // 2]}...{text[-n // 2:]}"


def _check_place(p: Path, flag: str, directory: bool) -> None:
    if directory and p.resolve().parent == p.resolve():
        raise TolallocError(f"{flag} {str(p)!r}: refusing to write results into the filesystem root; give a "
                            f"directory of their own, e.g. {flag} results.")
    if p.exists() and p.is_dir() != directory:
        want = "a directory" if directory else "a file"
        raise TolallocError(f"{flag} {str(p)!r}: expected {want} path, but {str(p)!r} is "
                            f"{'a directory' if p.is_dir() else 'a file'}; choose another path.")
    parent = p if directory and p.exists() else p.parent
    while not parent.exists() and parent != parent.parent:
        parent = parent.parent
    if not parent.is_dir():
        raise TolallocError(f"{flag} {str(p)!r}: expected a path below a directory, but {str(parent)!r} is a file; "
                            "choose another path.")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise TolallocError(f"{flag} {str(p)!r}: expected a writable place, but {str(parent)!r} is not writable; "
                            "choose another path.")


def check_distinct_outputs(outputs, inputs=(), *, files=()) -> None:
    """Refuse two output flags naming the same path, an output that would overwrite an input, or an output below
    one that is a file (the flags in ``files``).

    ``outputs`` and ``inputs`` are ``(flag, path or None)`` pairs; ``None`` and ``'-'`` are skipped.
    """
    given = [(flag, str(path), Path(os.path.realpath(str(path)))) for flag, path in outputs
             if path is not None and str(path) != "-"]
    real = {flag: r for flag, _, r in given}
    for flag, text, path in given:
        for outer in files:
            if outer in real and outer != flag and real[outer] in path.parents:
                raise TolallocError(f"{flag} {text!r}: lies below the file that {outer} writes "
                                    f"({str(real[outer])!r}); give {flag} a path outside it.")
    seen = {}
    for flag, path in inputs:
        if path is not None:
            seen.setdefault(os.path.realpath(str(path)), ("input", flag))
    for flag, text, path in given:
        key = str(path)
        if key in seen:
            role, other = seen[key]
            what = f"the input {other}; an output would overwrite it" if role == "input" else f"the same path as {other}"
            raise TolallocError(f"{flag} {text!r}: {what}; give each output its own path.")
        seen[key] = ("output", flag)


def reserve_directory(path, flag: str) -> None:
    """Check output directory ``path`` (:func:`check_output`) and, inside :func:`reservations`, take its lock now,
    until that block ends; the staging of that directory later in the block uses this lock. ``None`` passes;
    outside :func:`reservations` only the check is made (the staging takes the lock)."""
    check_output(path, flag, directory=True)
    if path is not None and in_reservations():
        reserve(Path(path))


def published(reset: bool = False) -> list:
    """Paths published by :func:`atomic_output` so far (a copy); ``reset`` empties the record first."""
    if reset:
        _PUBLISHED.clear()
    return list(_PUBLISHED)


#: List of the files the last publication wrote into a directory (one name per line), kept in that directory.
MANIFEST = ".tolalloc-files"


def _publish_dir(tmp: Path, path: Path) -> None:
    """Move staged folder ``tmp`` to ``path`` (the caller holds the signals back).

    The directory keeps a list of the files published into it (:data:`MANIFEST`); a later publication removes the
    files of that list it does not write again (another job's report, say), so the folder never hands over one
    job's files beside another's. Files the list does not name (the user's own) are kept."""
    new = sorted(item.name for item in tmp.iterdir())
    (tmp / MANIFEST).write_text("".join(f"{name}\n" for name in new))
    if path.is_dir() and (path / MANIFEST).is_file():
        for name in set((path / MANIFEST).read_text().splitlines()) - set(new) - {"", MANIFEST}:
            old = path / Path(name).name  # a bare name: never a path outside the folder
            if old.is_dir() and not old.is_symlink():
                shutil.rmtree(old, ignore_errors=True)
            elif old.exists() or old.is_symlink():
                old.unlink()
    if not path.exists():
        try:
            os.rename(tmp, path)  # one step: the directory appears complete
            return
        except OSError:
            if not path.is_dir():
                raise
    for item in tmp.iterdir():
        target = path / item.name
        if target.is_dir() and not target.is_symlink():
            shutil.rmtree(target)
        os.replace(item, target)


def _special(path: Path) -> bool:
    """A symlink, device or pipe (``/dev/stdout``, ``/dev/null``): written through, never replaced."""
    return path.is_symlink() or (path.exists() and not path.is_file() and not path.is_dir())


@contextlib.contextmanager
def _direct_output(path: Path):
    """Stage in a private temporary folder, then copy the bytes into ``path`` (which stays what it is)."""
    folder = Path(tempfile.mkdtemp(prefix="tolalloc-"))
    try:
        tmp = folder / (path.name or "out")
        yield tmp
        raise_if_interrupted()
        try:
            with signals_deferred(), open(path, "wb") as dst:
                dst.write(tmp.read_bytes() if tmp.exists() else b"")
        except OSError as exc:
            raise _cannot_write(path, False, exc) from None
        _PUBLISHED.append(str(path))
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def _load_plotting() -> None:
    """Import matplotlib's pyplot before anything is staged: an interrupt inside that import (a second or more on a
    cold start) must not land among staged files, where a library can turn it into an error of its own."""
    with contextlib.suppress(ImportError):
        import matplotlib.pyplot  # noqa: F401


@contextlib.contextmanager
def _stage(path: Path, directory: bool):
    """Yield the staging path of output ``path``; publish it if the block finishes without error. Whatever
    happens, the staging path, the lock and the parent folders made for it (when left empty) are removed."""
    if not directory and _special(path):
        with _direct_output(path) as tmp:
            yield tmp
        return
    tmp = None
    with contextlib.ExitStack() as stack:
        try:
            stack.callback(remove_empty, make_parents(path.parent))
            if directory:
                if not is_reserved(path):
                    stack.enter_context(directory_lock(path))
                tmp = Path(tempfile.mkdtemp(prefix=".tmp-", dir=path.parent))
            else:
                fd, tmp_name = tempfile.mkstemp(prefix=".tmp-", dir=path.parent)
                os.close(fd)
                tmp = Path(tmp_name)
                os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes 0o600
        except OSError as exc:
            raise _cannot_write(path, directory, exc) from None
        _STAGED[str(tmp)] = str(path)
        try:
            yield tmp
            raise_if_interrupted()
            try:
                with signals_deferred():  # an interrupt is delivered after the record below, never between
                    if directory:
                        os.chmod(tmp, 0o777 & ~_umask())  # mkdtemp makes 0o700
                        _publish_dir(tmp, path)
                    else:
                        os.replace(tmp, path)
                    if _shown(str(path)) == str(path):  # not a write into a staging path
                        _PUBLISHED.append(str(path))
            except OSError as exc:
                raise _cannot_write(path, directory, exc) from None
        finally:
            with signals_deferred():  # the clean-up is not cut short by a second signal
                _STAGED.pop(str(tmp), None)
                if directory:
                    shutil.rmtree(tmp, ignore_errors=True)
                elif tmp.exists():
                    tmp.unlink()


@contextlib.contextmanager
def atomic_output(path: str | os.PathLike, *, directory: bool = False, name: str = "path"):
    """Yield a temporary path; publish it at ``path`` only if the block finishes without error.

    For ``directory=True`` the temporary path is a fresh directory; a new ``path`` is created from it
    by one rename, an existing one gets its files of the same name replaced (other files are kept).
    The directory is locked against other runs meanwhile (see the module docstring). A file gets the
    usual permissions (``0o666`` less the umask).

    Raises
    ------
    TolallocError
        ``path`` neither a str nor an :class:`os.PathLike` (naming argument ``name``), or an operating-system
        error while staging, writing or publishing (an unwritable place, no space left, a quota, a path too long):
        one line naming the path and the cause. An error or interrupt in the block removes the temporary path,
        the lock and the parent folders made for it; nothing is published.
    """
    path = Path(_path_text(path, name))
    if directory:
        _load_plotting()
    with interrupts_as_exceptions(), _stage(path, directory) as tmp:
        try:
            yield tmp
        except OSError as exc:
            raise _write_failed(exc, [path]) from None


class _Group:
    def __init__(self, stack: contextlib.ExitStack):
        self._stack = stack
        self.targets: list = []

    def file(self, path) -> Path:
        """Staging path of output file ``path``."""
        path = Path(_path_text(path, "path"))
        self.targets.append(path)
        return self._stack.enter_context(_stage(path, False))

    def directory(self, path) -> Path:
        """Staging folder of output directory ``path``."""
        path = Path(_path_text(path, "path"))
        _load_plotting()
        self.targets.append(path)
        return self._stack.enter_context(_stage(path, True))


@contextlib.contextmanager
def output_group():
    """Several outputs staged together and published together (SIGINT / SIGTERM held back meanwhile).

    Yields an object with ``file(path)`` and ``directory(path)``, each returning a staging path
    (see :func:`atomic_output`). An error or interrupt in the block removes every staged output; an
    operating-system error raises one :class:`TolallocError` naming the file and the cause.
    """
    with interrupts_as_exceptions(), contextlib.ExitStack() as stack:
        group = _Group(stack)
        try:
            yield group
        except OSError as exc:
            raise _write_failed(exc, group.targets) from None
        raise_if_interrupted()
        with signals_deferred():
            stack.close()


def _umask() -> int:
    umask = os.umask(0)
    os.umask(umask)
    return umask


def write_json(obj, path) -> None:
    """Write ``obj`` as indented JSON to ``path`` atomically ('-' prints to stdout)."""
    text = json.dumps(obj, indent=2, default=json_default)
    if str(path) == "-":
        print(text)
        return
    with atomic_output(path) as tmp:
        tmp.write_text(text + "\n")
