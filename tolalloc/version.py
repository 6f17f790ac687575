"""The version of tolalloc: stated once, in ``pyproject.toml``, and read here from the installed package's metadata.

``tolalloc.__version__`` and ``tolalloc --version`` show :func:`package_version`; a source tree that was never
installed (no metadata) reports :data:`FALLBACK`.
"""

from __future__ import annotations

import functools

__all__ = ["package_version", "FALLBACK"]

#: the version shown when tolalloc runs from a source tree without being installed (PEP 440 local version)
FALLBACK = "0+unknown"


@functools.cache
def package_version() -> str:
    """The installed distribution's version (``0.1.0``), or :data:`FALLBACK` when it is not installed."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("tolalloc")
    except PackageNotFoundError:
        return FALLBACK
