"""Command-line interface: ``tolalloc <command> ...``.

Each command lives in its own module exposing ``register(subparsers)``; the
module list below is the whole command set. Every :class:`TolallocError` and every
malformed argument is printed as one ``error:`` line with exit status 2; nothing
half-written stays on disk (outputs go through :func:`tolalloc.outputs.atomic_output`).
Ctrl-C (SIGINT) and SIGTERM print ``interrupted; nothing written`` and exit with
130 / 143; staged output is removed, no traceback.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import signal
import sys
import threading

from tolalloc.exceptions import Interrupted, TolallocError, clear_interrupt, note_interrupt, raise_if_interrupted

#: command modules, in the order shown by --help
COMMAND_MODULES = ["robot_cmds", "diagnose", "compensate", "fleet", "mc", "analyze", "allocate", "calplan", "review"]


class _UsageError(TolallocError):
    """A malformed command line (printed like any other error)."""


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors: ``error: tolalloc mc: argument --n: ... (see tolalloc mc --help)``.

    Flags are never abbreviated (``allow_abbrev=False``, for the subcommands too): a unit-less ``--radius`` must not
    stand for ``--radius-mm``; an unknown flag is refused with the full flags it may mean.
    """

    def __init__(self, *args, **kwargs):
        kwargs["allow_abbrev"] = False
        super().__init__(*args, **kwargs)

    def error(self, message):  # noqa: D102 - argparse API
        raise _UsageError(f"{self.prog}: {message} (see '{self.prog} --help').")

    def parse_args(self, args=None, namespace=None):  # noqa: D102 - argparse API
        namespace, extras = self.parse_known_args(args, namespace)
        if extras:
            command = self._command_parser(namespace)
            command.error(_unrecognized(command, extras))
        return namespace

    def _command_parser(self, namespace) -> argparse.ArgumentParser:
        """The subcommand's parser that collected the unrecognized arguments (this one if none)."""
        for action in self._actions:
            if isinstance(action, argparse._SubParsersAction):
                return action.choices.get(getattr(namespace, action.dest, None), self)
        return self


def _unrecognized(parser: argparse.ArgumentParser, extras: list) -> str:
    """argparse's message for unrecognized arguments, naming the full flags an unknown ``--flag`` may mean."""
    import difflib

    text = f"unrecognized arguments: {' '.join(extras)}"
    known = sorted(o for o in parser._option_string_actions if o.startswith("--"))
    for arg in extras:
        flag = arg.split("=", 1)[0]
        if not flag.startswith("--"):
            continue
        near = [o for o in known if o.startswith(flag)] or difflib.get_close_matches(flag, known, n=3, cutoff=0.6)
        if near:
            return f"{text}; did you mean {' or '.join(near)}? Flags are written in full, with their unit"
    return text


def _version_text() -> str:
    """What ``tolalloc --version`` prints."""
    from tolalloc.version import package_version

    return f"tolalloc {package_version()}"


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="tolalloc",
        description="Tolerance allocation, verification and sim-to-real diagnosis for serial robots. "
        "Units: lengths in mm, joint values in deg (revolute) and mm (prismatic).",
    )
    parser.add_argument("--version", action="version", version=_version_text(),
                        help="print the installed version and exit")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for name in COMMAND_MODULES:
        importlib.import_module(f"{__name__}.{name}").register(sub)
    from tolalloc.cli.common import flag_map

    for command in sub.choices.values():
        command.set_defaults(flags=flag_map(command))
    return parser


def _on_signal(signum, frame):
    # the first signal wins; later ones are ignored while the staged output is cleaned up
    for s in (signal.SIGINT, signal.SIGTERM):
        signal.signal(s, signal.SIG_IGN)
    note_interrupt(signum)  # re-raised at the next checkpoint if a library swallows the exception below
    raise Interrupted(signum)


def _quiet_unraisable(previous):
    """An ``sys.unraisablehook`` that drops the :class:`Interrupted` our handler raised where Python cannot propagate
    it -- inside a ctypes callback (numba's object cache notifying llvmlite, say), where Python would print
    "Exception ignored ..." and a traceback; the interrupt is recorded and re-raised at the next checkpoint. Anything
    else goes to ``previous``."""
    def hook(unraisable):
        if isinstance(unraisable.exc_value, Interrupted):
            return
        previous(unraisable)

    return hook


def _quiet_excepthook(previous):
    """An ``sys.excepthook`` that drops the :class:`Interrupted` our handler raised inside a Cython function that
    cannot propagate it (scipy's Sobol sampler, say): Cython prints its traceback through ``sys.excepthook`` before it
    reports it as unraisable (:func:`_quiet_unraisable`); the interrupt is recorded and re-raised at the next
    checkpoint. Anything else goes to ``previous``."""
    def hook(exc_type, exc_value, tb):
        if isinstance(exc_value, Interrupted):
            return
        previous(exc_type, exc_value, tb)

    return hook


def _not_after_an_interrupt(record) -> bool:
    """Logging filter: drop what a library logs about the exception our interrupt raised inside it (cvxpy logs
    ``Encountered unexpected exception importing solver ...: ImportError('initialization failed')``)."""
    from tolalloc.exceptions import interrupt_pending

    return not interrupt_pending()


@contextlib.contextmanager
def _interrupt_handlers():
    """Turn SIGINT / SIGTERM into :class:`Interrupted` for the block (main thread only), then restore."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    import logging

    clear_interrupt()
    solver_log = logging.getLogger("__cvxpy__")
    solver_log.addFilter(_not_after_an_interrupt)
    old = {s: signal.signal(s, _on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
    hook, sys.unraisablehook = sys.unraisablehook, _quiet_unraisable(sys.unraisablehook)
    excepthook, sys.excepthook = sys.excepthook, _quiet_excepthook(sys.excepthook)
    try:
        yield
    finally:
        for s, h in old.items():
            signal.signal(s, h)
        sys.unraisablehook, sys.excepthook = hook, excepthook
        solver_log.removeFilter(_not_after_an_interrupt)
        clear_interrupt()


@contextlib.contextmanager
def _warnings_as_lines():
    """The library's own warnings as one ``warning: ...`` line each on stderr (other warnings as Python shows them)."""
    import os
    import warnings

    package = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    with warnings.catch_warnings():
        python_show = warnings.showwarning

        def show(message, category, filename, lineno, file=None, line=None):
            if os.path.abspath(str(filename)).startswith(package + os.sep):
                print(f"warning: {message}", file=sys.stderr)
            else:
                python_show(message, category, filename, lineno, file, line)

        warnings.showwarning = show
        yield


def _run(args) -> int:
    """The command's exit status; an error raised while a signal is pending is the interrupt."""
    try:
        return int(args.func(args) or 0)
    except Exception:
        # a library can turn the handler's exception into an error of its own (numba, interrupted while it
        # compiles a kernel, raises "no compiled object yet"): the run was interrupted all the same
        raise_if_interrupted()
        raise


def main(argv: list[str] | None = None) -> int:
    """Run one command; returns the exit status (0 ok, 1 a requirement not met, 2 bad input, 130/143 interrupted)."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["--version"]:  # answered before the commands' modules (and their numerical stack) are imported
        print(_version_text())
        return 0
    from tolalloc.outputs import published, reservations

    published(reset=True)
    args = None
    with _interrupt_handlers(), _warnings_as_lines():
        try:
            args = build_parser().parse_args(argv)
            with reservations():  # output directories are locked before the command computes, until it ends
                code = _run(args)
            raise_if_interrupted()  # a signal whose exception a library swallowed (nothing was published since)
            return code
        except TolallocError as exc:
            from tolalloc.cli.common import error_line

            print(f"error: {error_line(exc, args)}", file=sys.stderr)
            return 2
        except KeyboardInterrupt as exc:
            signum = getattr(exc, "signum", signal.SIGINT)
            done = published()
            print("interrupted; nothing written" if not done else
                  f"interrupted after writing {', '.join(done)} (complete); nothing else written", file=sys.stderr)
            return 128 + int(signum)
        except BrokenPipeError:  # output piped into `head` and closed early: not an error of ours
            import os

            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
            return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
