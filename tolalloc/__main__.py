"""Entry point of ``tolalloc`` and ``python -m tolalloc``.

SIGINT / SIGTERM are taken over before the heavy imports: an interrupt while the program is still starting
ends it like any later one (one line on stderr, exit 130 / 143, nothing written), not with a traceback from
inside an import. :func:`tolalloc.cli.main` installs its own handlers for the run itself.
"""

import os
import signal
import sys


def _starting(signum, frame):
    sys.stderr.write("interrupted; nothing written\n")
    sys.stderr.flush()
    os._exit(128 + signum)  # nothing to clean up yet: no output has been staged


def run() -> None:
    """Console-script entry point."""
    for s in (signal.SIGINT, signal.SIGTERM):
        signal.signal(s, _starting)
    from tolalloc.cli import main

    code = main()
    for s in (signal.SIGINT, signal.SIGTERM):  # the run is over; its output is published
        signal.signal(s, signal.SIG_IGN)
    if code in (128 + signal.SIGINT, 128 + signal.SIGTERM):
        # interrupted: a solver thread may still be inside C++ (IPOPT, Clarabel), and finalising the interpreter
        # under it aborts the process ("terminate called without an active exception", status -6); everything
        # was already cleaned up and the one line printed, so leave without finalising
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    sys.exit(code)


if __name__ == "__main__":
    run()
