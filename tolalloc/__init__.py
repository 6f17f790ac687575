"""tolalloc: tolerance allocation, verification and sim-to-real diagnosis for serial robots.

Units inside the library: lengths in mm, angles in rad. Joint values at the
interface (robot files, CLI, CSV) are in degrees (revolute) and mm (prismatic).

The names below are loaded on first use (PEP 562), so ``import tolalloc`` stays cheap and the command line can
take over SIGINT / SIGTERM before numpy and the solvers are imported (see :mod:`tolalloc.__main__`).
"""

from __future__ import annotations

import importlib

__version__ = "0.1.0"

_HOME = {
    "TolallocError": "tolalloc.exceptions",
    **{name: "tolalloc.robot" for name in ("Joint", "Link", "Mass", "Robot", "load_robot", "builtin_robots",
                                           "fk_poe", "space_jacobian", "body_jacobian")},
}

__all__ = list(_HOME)


def __getattr__(name: str):
    if name in _HOME:
        value = getattr(importlib.import_module(_HOME[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'tolalloc' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + __all__)
