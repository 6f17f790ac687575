"""Interrupts, concurrent writers, staged output and bounded Monte Carlo task generation (issue 12)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tolalloc.cli import main
from tolalloc.outputs import MANIFEST, atomic_output, directory_lock
from tolalloc.progress import PROGRESS_LINE

ROOT = Path(__file__).resolve().parents[1]


def _start(argv, cwd):
    # runs that would go on for days: no time budget refuses them, and no estimate is announced before they start
    env = {**os.environ, "PYTHONPATH": str(ROOT), "TOLALLOC_TIME_BUDGET_S": "inf", "TOLALLOC_ANNOUNCE_S": "inf"}
    return subprocess.Popen([sys.executable, "-m", "tolalloc", *argv], cwd=cwd, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


def _wait_handlers(proc, timeout=60.0):
    """Wait until the process catches SIGINT and SIGTERM (Linux: the SigCgt mask of /proc/PID/status)."""
    want = (1 << (signal.SIGINT - 1)) | (1 << (signal.SIGTERM - 1))
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        for line in Path(f"/proc/{proc.pid}/status").read_text().splitlines():
            if line.startswith("SigCgt:") and int(line.split()[1], 16) & want == want:
                return
        time.sleep(0.002)
    raise AssertionError("the process never installed its signal handlers")


def _cpu_s(pid) -> float:
    """CPU time [s] a process has used (Linux: utime + stime of /proc/PID/stat)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _wait_running(proc, cpu_s, timeout=60.0):
    """Let the process take the signals over, then run until it has used ``cpu_s`` of CPU (past its imports, into
    the computation, however loaded the machine; without /proc: that long on the clock). It must still be running."""
    if Path("/proc/self/status").exists():
        _wait_handlers(proc)
        t0 = time.monotonic()
        while _cpu_s(proc.pid) < cpu_s and time.monotonic() - t0 < timeout and proc.poll() is None:
            time.sleep(0.02)
    else:
        time.sleep(cpu_s)
    assert proc.poll() is None, proc.communicate()


@pytest.mark.parametrize("argv, sig, code", [
    (["mc", "tool_changer", "--n", "1e20", "--out", "out", "--json", "s.json"], signal.SIGINT, 130),
    (["allocate", "tool_changer", "--n-mc", "1e10", "--out", "out"], signal.SIGTERM, 143),
])
def test_interrupt_prints_one_line_and_leaves_nothing(tmp_path, argv, sig, code):
    proc = _start(argv, tmp_path)
    _wait_running(proc, 1.5)  # imports take about 1 s of CPU: the job is running (a signal during them: below)
    proc.send_signal(sig)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == code, err
    # stderr is a pipe: the stages finished before the signal have their progress line
    lines = [line for line in err.strip().splitlines() if not PROGRESS_LINE.match(line)]
    assert lines == ["interrupted; nothing written"]
    assert "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == []  # no out/, no .tmp-*, no lock file


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs /proc to see when the handlers are in place")
@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_interrupt_while_starting_up_is_just_as_quiet(tmp_path, sig, code):
    # regression: a signal during the imports (before the run's own handlers) gave a KeyboardInterrupt
    # traceback from inside an import (SIGINT) or a bare kill status -15 (SIGTERM). Sent as soon as the entry
    # point has taken the signals over, i.e. while numpy and the solvers are still being imported.
    proc = _start(["mc", "tool_changer", "--n", "1e20", "--out", "out"], tmp_path)
    _wait_handlers(proc)
    proc.send_signal(sig)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == code, err
    assert err.strip() == "interrupted; nothing written"
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def test_interrupt_while_staging_removes_the_temporary_folder(tmp_path):
    target = tmp_path / "out"
    with pytest.raises(KeyboardInterrupt):
        with atomic_output(target, directory=True) as tmp:
            (tmp / "half.csv").write_text("1,2\n")
            raise KeyboardInterrupt
    assert list(tmp_path.iterdir()) == []


def test_new_directory_is_published_whole_and_existing_one_keeps_other_files(tmp_path):
    target = tmp_path / "out"
    with atomic_output(target, directory=True) as tmp:
        (tmp / "a.txt").write_text("1")
        (tmp / "sub").mkdir()
        assert not target.exists()  # nothing visible before the end of the block
    assert sorted(p.name for p in target.iterdir()) == [MANIFEST, "a.txt", "sub"]
    (target / "mine.txt").write_text("keep")
    with atomic_output(target, directory=True) as tmp:
        (tmp / "a.txt").write_text("2")
    assert (target / "a.txt").read_text() == "2" and (target / "mine.txt").read_text() == "keep"
    assert not (target / "sub").exists()  # the earlier publication's, not written again: another job's leftover
    assert (target / MANIFEST).read_text() == "a.txt\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]  # no staging folder, no lock left
    umask = os.umask(0)
    os.umask(umask)
    assert (target.stat().st_mode & 0o777) == 0o777 & ~umask  # not mkdtemp's 0o700


def test_second_writer_of_the_same_directory_is_refused(tmp_path, capsys):
    target = tmp_path / "out"
    with directory_lock(target):  # another run is publishing into out/
        code = main(["mc", "tool_changer", "--n", "100", "--out", str(target)])
    err = capsys.readouterr().err
    assert code == 2
    assert err.strip().splitlines() == [f"error: {str(target)!r} is being written by another run (lock "
                                        f"{str(tmp_path / '.out.lock')!r}); wait for it to finish or choose another "
                                        "output directory."]
    assert sorted(p.name for p in tmp_path.iterdir()) == []
    assert main(["mc", "tool_changer", "--n", "100", "--out", str(target)]) == 0  # the lock is gone with the run
    assert (target / "mc_summary.json").is_file()


def test_mc_tasks_are_generated_lazily(monkeypatch):
    # regression: one task per block was built up front, so n = 1e20 ran out of memory
    import tolalloc.montecarlo.run as run_mod
    from tolalloc import load_robot
    from tolalloc.errormodel import build_error_model

    seen = {}

    def fake_map(fn, tasks, shared, **kw):
        seen["type"] = type(tasks)
        first = next(iter(tasks))
        seen["first"] = first
        raise KeyboardInterrupt  # stop at once: the caller must not have built the task list

    monkeypatch.setattr(run_mod, "ordered_map", fake_map)
    monkeypatch.setenv("TOLALLOC_TIME_BUDGET_S", "inf")  # a run that would never end: not refused here
    monkeypatch.setenv("TOLALLOC_ANNOUNCE_S", "inf")
    model = build_error_model(load_robot("tool_changer"))
    t0 = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        run_mod.run_mc(model, model.robot.q_nominal, 10**20, 0)
    assert time.perf_counter() - t0 < 30  # a list of 1e20 / BLOCK_SIZE tuples would never finish
    assert seen["type"] is not list and seen["first"] == (0, 1)


def test_counts_accept_scientific_notation_as_the_help_says(capsys, tmp_path):
    assert main(["mc", "tool_changer", "--n", "1e3", "--json", str(tmp_path / "s.json")]) == 0
    import json

    assert json.loads((tmp_path / "s.json").read_text())["n"] == 1000
    from tolalloc.cli.argtypes import count

    assert count("1e6") == 10**6 and count("1_000_000") == 10**6 and count("1e20") == 10**20


def test_interrupt_handler_is_restored_after_main():
    before = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)
    main(["robots"])
    assert (signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)) == before


def test_output_group_publishes_all_or_nothing(tmp_path):
    from tolalloc.outputs import output_group, published

    with pytest.raises(RuntimeError):
        with output_group() as out:
            out.file(tmp_path / "a.json").write_text("x")
            (out.directory(tmp_path / "rep") / "r.md").write_text("y")
            raise RuntimeError("the second output failed")
    assert list(tmp_path.iterdir()) == []
    published(reset=True)
    with output_group() as out:
        out.file(tmp_path / "a.json").write_text("x")
        (out.directory(tmp_path / "rep") / "r.md").write_text("y")
        assert sorted(p.name for p in tmp_path.iterdir() if not p.name.startswith(".")) == []
    assert (tmp_path / "a.json").read_text() == "x" and (tmp_path / "rep" / "r.md").read_text() == "y"
    assert sorted(published()) == sorted([str(tmp_path / "a.json"), str(tmp_path / "rep")])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.json", "rep"]


@pytest.fixture
def python_sigint():
    """Python's default SIGINT handler for the test, whatever the parent shell set (a background or nohup shell
    starts the suite with SIGINT ignored, which a child inherits)."""
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, old)


def test_interruptible_returns_raises_and_lets_a_signal_stop_the_wait(python_sigint):
    # regression: Clarabel releases the GIL but the main thread only runs Python's signal handlers when the solve
    # returns, so Ctrl-C during a long solve waited for it (18 s on a loaded machine). A sleep stands in for it.
    import threading

    from tolalloc.exceptions import interruptible

    assert interruptible(divmod, 7, 3) == (2, 1)
    with pytest.raises(ZeroDivisionError):
        interruptible(divmod, 1, 0)
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    t0 = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        interruptible(time.sleep, 30.0)
    assert time.monotonic() - t0 < 15.0  # the interrupt ends the wait, not the 30 s call


def _calplan_is_interrupted(tmp_path, capsys, code):
    """Run ``calplan`` (its relaxation patched to meet a signal) and check: exit ``code``, the one line, no file."""
    out = tmp_path / "plan.csv"
    assert main(["calplan", "tool_changer", "--n-poses", "8", "--n-candidates", "200", "--out", str(out)]) == code
    assert capsys.readouterr().err.strip().splitlines()[-1] == "interrupted; nothing written"
    assert list(tmp_path.iterdir()) == []


def test_an_interrupt_a_library_swallows_still_stops_the_run(tmp_path, monkeypatch, capsys, python_sigint):
    # regression: SIGINT while cvxpy imported its solver interfaces became ImportError('initialization failed')
    # inside a C extension, cvxpy logged and ignored it, and calplan finished and wrote its plan (exit 0) with
    # signals ignored from then on
    import tolalloc.calibration.design as design

    orig = design.relax

    def swallowing(*args, **kwargs):
        try:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(5.0)  # the handler raises in here
        except KeyboardInterrupt:
            pass  # what the library did with it
        return orig(*args, **kwargs)

    monkeypatch.setattr(design, "relax", swallowing)
    _calplan_is_interrupted(tmp_path, capsys, 130)


def test_an_interrupt_a_library_turns_into_its_own_error_is_still_an_interrupt(tmp_path, monkeypatch, capsys,
                                                                              python_sigint):
    # regression: SIGTERM while numba compiled a kernel (a fresh environment) ended the run with numba's
    # RuntimeError("no compiled object yet ...") and a traceback instead of the one line and exit 143
    import tolalloc.calibration.design as design

    def converting(*args, **kwargs):
        try:
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(5.0)  # the handler raises in here
        except KeyboardInterrupt:
            raise RuntimeError("no compiled object yet for <Library '_prefix'>") from None  # what the library did

    monkeypatch.setattr(design, "relax", converting)
    _calplan_is_interrupted(tmp_path, capsys, 143)


def test_signals_deferred_holds_a_signal_another_thread_receives(python_sigint):
    # regression: a thread signal mask held SIGINT back only in the main thread; the kernel delivered it to
    # another thread (BLAS, solver, here a timer) and Python ran the handler in the main thread inside the
    # block anyway -- CasADi then printed a KeyboardInterruptException warning from inside IPOPT
    import threading

    from tolalloc.exceptions import signals_deferred

    seen = []
    with pytest.raises(KeyboardInterrupt):
        with signals_deferred():
            timer = threading.Timer(0.05, os.kill, (os.getpid(), signal.SIGINT))
            timer.start()
            for _ in range(100):  # Python code running in the block, as a solver's callbacks do
                time.sleep(0.01)
            seen.append("block finished")
    assert seen == ["block finished"]  # delivered after the block, not inside it
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_an_interrupt_inside_a_native_callback_prints_nothing(monkeypatch):
    """The handler's exception raised inside a ctypes callback (numba's object cache notifying llvmlite while a
    kernel compiles) cannot propagate; Python would hand it to ``sys.unraisablehook``, which prints "Exception
    ignored ..." with a traceback. Inside the command line's handlers it is dropped (the interrupt stays recorded for
    the next checkpoint); other unraisable errors still reach the hook, and after the block the hook is back."""
    import ctypes

    from tolalloc.cli import _interrupt_handlers
    from tolalloc.exceptions import Interrupted

    seen = []
    monkeypatch.setattr(sys, "unraisablehook", lambda u: seen.append(type(u.exc_value).__name__))

    def interrupted():
        raise Interrupted(signal.SIGTERM)

    def broken():
        raise ValueError("a real error")

    hook = sys.unraisablehook
    with _interrupt_handlers():
        ctypes.CFUNCTYPE(None)(interrupted)()
        ctypes.CFUNCTYPE(None)(broken)()
    assert seen == ["ValueError"]
    assert sys.unraisablehook is hook


def test_an_interrupt_inside_a_cython_function_prints_no_traceback(monkeypatch):
    """A Cython function that cannot propagate the handler's exception (scipy's Sobol sampler while the Monte Carlo
    draws its points) prints it with ``PyErr_PrintEx``, which calls ``sys.excepthook``, before reporting it as
    unraisable: inside the command line's handlers the hook drops it (the interrupt stays recorded for the next
    checkpoint); other exceptions still reach the hook, and after the block the hook is back."""
    from tolalloc.cli import _interrupt_handlers
    from tolalloc.exceptions import Interrupted

    seen = []
    monkeypatch.setattr(sys, "excepthook", lambda t, v, tb: seen.append(t.__name__))
    hook = sys.excepthook
    with _interrupt_handlers():
        sys.excepthook(Interrupted, Interrupted(signal.SIGTERM), None)
        sys.excepthook(ValueError, ValueError("a real error"), None)
    assert seen == ["ValueError"]
    assert sys.excepthook is hook
