"""Which compiled engine runs: numba (default, a core dependency) or the numpy reference path.

A foundation module (like :mod:`tolalloc.exceptions`): the robot's Jacobian kernels and the Monte Carlo
engines both ask :func:`resolve_engine`, so it sits below every pipeline stage.
"""

from __future__ import annotations

import importlib.util
import os

from tolalloc.exceptions import TolallocError

__all__ = ["NUMBA_AVAILABLE", "ENGINES", "resolve_engine"]

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
