"""Which compiled engine runs: numba (default, a core dependency) or the numpy reference path.

A foundation module (like :mod:`tolalloc.exceptions`): the robot's Jacobian kernels and the Monte Carlo
engines both ask :func:`resolve_engine`, so it sits below every pipeline stage.
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib.util
import os
import tempfile

from tolalloc.exceptions import TolallocError

__all__ = ["NUMBA_AVAILABLE", "ENGINES", "resolve_engine", "first_compile"]

#: True when numba can be imported (checked without importing it).
NUMBA_AVAILABLE = importlib.util.find_spec("numba") is not None
ENGINES = (None, "auto", "numba", "numpy")


def resolve_engine(engine: str | None = None) -> str:
    """``"numba"`` or ``"numpy"``: ``engine`` if given, else numba when importable and ``TOLALLOC_NUMBA`` != 0."""
    if not (engine is None or (isinstance(engine, str) and engine in ENGINES)):
        from tolalloc.exceptions import describe

        raise TolallocError(f"engine: expected None, 'auto', 'numba' or 'numpy', got {describe(engine)}.")
    if engine == "numpy":
        return "numpy"
    if engine == "numba":
        if not NUMBA_AVAILABLE:
            raise TolallocError("engine='numba' needs the numba package: pip install numba "
                                "(or use engine='numpy').")
        return "numba"
    if os.environ.get("TOLALLOC_NUMBA", "1").strip().lower() in ("0", "false", "no", "off"):
        return "numpy"
    return "numba" if NUMBA_AVAILABLE else "numpy"


#: How long a process waits for another one's compilation before compiling itself [s].
COMPILE_WAIT_S = 300.0


@contextlib.contextmanager
def first_compile(module_file: str):
    """Hold a file lock, shared by every process of this installation, around the first call of the numba kernels
    of ``module_file`` (their compilation, or the load of the on-disk cache).

    Processes that start together on an empty cache (test workers, notebook kernels, command-line runs) would each
    compile the same kernels (the Monte Carlo kernel takes about 12 s); with the lock one compiles and writes the
    cache and the others wait and load it. After ``COMPILE_WAIT_S`` a waiting process compiles on its own; where no
    lock can be made (a read-only temporary folder) it compiles at once.
    """
    from filelock import FileLock, Timeout

    key = hashlib.sha1(os.path.abspath(module_file).encode()).hexdigest()[:16]
    lock = FileLock(os.path.join(tempfile.gettempdir(), f"tolalloc-numba-{key}.lock"))
    try:
        lock.acquire(timeout=COMPILE_WAIT_S)
    except (Timeout, OSError):
        yield
        return
    try:
        yield
    finally:
        lock.release()
