"""Command-line interface: ``tolalloc <command> ...``.

Each command lives in its own module exposing ``register(subparsers)``; the
module list below is the whole command set. Every :class:`TolallocError` is
printed as one ``error:`` line with exit status 2; nothing half-written stays
on disk (outputs are written through :func:`tolalloc.cli.common.atomic_output`).
"""

from __future__ import annotations

import argparse
import importlib
import sys

from tolalloc.exceptions import TolallocError

#: command modules, in the order shown by --help
COMMAND_MODULES = ["robot_cmds", "diagnose", "mc", "analyze", "allocate", "calplan"]


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="tolalloc",
        description="Tolerance allocation, verification and sim-to-real diagnosis for serial robots. "
        "Units: lengths in mm, joint values in deg (revolute) and mm (prismatic).",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for name in COMMAND_MODULES:
        importlib.import_module(f"{__name__}.{name}").register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except TolallocError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # output piped into `head` and closed early: not an error of ours
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
