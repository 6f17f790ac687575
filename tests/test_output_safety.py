"""Output safety: a full disk, a quota, a refused permission or a path too long is one clear error and leaves nothing;
SIGTERM / SIGINT while a Python ``save()`` stages; the output lock taken before the command computes; the lock
without ``fcntl`` (as on Windows)."""

from __future__ import annotations

import errno
import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import tolalloc
from tolalloc.cli import main
from tolalloc.exceptions import ArgumentError, TolallocError
from tolalloc.outputs import atomic_output, check_output, directory_lock, output_group, write_json

ROOT = Path(__file__).resolve().parents[1]


def _no_space(*args, **kwargs):
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))  # as PIL's PNG writer raises it: no file name


@pytest.fixture(scope="module")
def sim():
    return tolalloc.simulate_errors("tool_changer", n_mc=200, seed=1, progress=False)


def test_full_disk_on_the_command_line_is_one_error_line(tmp_path, monkeypatch, capsys):
    from matplotlib.figure import Figure

    monkeypatch.setattr(Figure, "savefig", _no_space)
    target = tmp_path / "new" / "out"
    code = main(["mc", "tool_changer", "--n", "100", "--out", str(target)])
    err = capsys.readouterr().err
    assert code == 2
    assert err.strip().splitlines() == [f"error: cannot write {str(target)!r} (No space left on device); nothing was "
                                        "written; free some space or choose another place."]
    assert list(tmp_path.iterdir()) == []  # no out/, no new/ made for it, no .tmp-*, no lock


def test_full_disk_in_python_save_is_a_tolalloc_error(sim, tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    monkeypatch.setattr(Figure, "savefig", _no_space)
    with pytest.raises(TolallocError, match=r"cannot write '.*out' \(No space left on device\); nothing was written"):
        sim.save(tmp_path / "out", json=tmp_path / "s.json")
    assert list(tmp_path.iterdir()) == []


def test_an_error_naming_a_staged_file_names_where_it_was_going(sim, tmp_path, monkeypatch):
    import pandas as pd

    def quota(self, path, *args, **kwargs):
        raise OSError(errno.EDQUOT, os.strerror(errno.EDQUOT), str(path))

    monkeypatch.setattr(pd.DataFrame, "to_csv", quota)
    with pytest.raises(TolallocError, match=r"cannot write '.*/out/mc_table\.csv' \(Disk quota exceeded\); nothing "
                                            r"was written; free some of the quota or choose another place\."):
        sim.save(tmp_path / "out")
    assert list(tmp_path.iterdir()) == []


def test_permission_refused_while_publishing(tmp_path, monkeypatch):
    def refuse(src, dst):
        raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(dst))

    monkeypatch.setattr(os, "replace", refuse)
    with pytest.raises(TolallocError, match=r"cannot write an output file at '.*a\.json' \(Permission denied: "
                                            r".*a\.json\); .*choose a writable place\."):
        write_json({"x": 1}, tmp_path / "sub" / "a.json")
    assert list(tmp_path.iterdir()) == []  # neither the staged file nor the folder made for it


def test_a_path_too_long_is_refused_before_anything_runs(tmp_path):
    with pytest.raises(TolallocError, match=r"--out '.*\.\.\..*': cannot be used as an output path \(File name too "
                                            r"long\); choose a shorter path\."):
        check_output(tmp_path / ("a" * 300), "--out", directory=True)


@pytest.mark.parametrize("bad", [3, 2.5, b"out", ["out"], None])
def test_a_path_that_is_no_path_is_refused_naming_the_argument(tmp_path, bad):
    with pytest.raises(ArgumentError, match=rf"^path: expected a path \(a str or os.PathLike such as pathlib.Path\), "
                                            rf"got {type(bad).__name__} "):
        with atomic_output(bad):
            pass
    with pytest.raises(ArgumentError, match=r"^path: expected a path"):
        write_json({}, bad)
    if bad is not None:
        with pytest.raises(ArgumentError, match=r"^--out: expected a path"):
            check_output(bad, "--out", directory=True)
        with pytest.raises(ArgumentError, match=r"^path: expected a path"), output_group() as group:
            group.directory(bad)


def test_the_lock_is_taken_before_the_command_computes(tmp_path, monkeypatch, capsys):
    import tolalloc.workflows

    def computed(*args, **kwargs):
        raise AssertionError("the allocation ran although its output directory was locked")

    tolalloc.allocate_tolerances  # noqa: B018  (resolved before its home is patched: tolalloc keeps what it loads)
    monkeypatch.setattr(tolalloc.workflows, "allocate_tolerances", computed)
    target = tmp_path / "out"
    with directory_lock(target):  # another run is writing out/
        code = main(["allocate", "tool_changer", "--out", str(target)])
    assert code == 2
    assert "is being written by another run" in capsys.readouterr().err
    # a run refused after its reservation (here: an unknown robot) leaves neither the lock nor the folders made for it
    assert main(["mc", "no_such_robot", "--n", "10", "--out", str(tmp_path / "a" / "b" / "out")]) == 2
    assert list(tmp_path.iterdir()) == []


def _default_signals() -> None:
    # a background or nohup shell starts the suite with SIGINT ignored, which a child inherits; Python then never
    # installs its KeyboardInterrupt handler
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _python(script: str, cwd: Path, **kw) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    if sys.platform != "win32":
        kw.setdefault("preexec_fn", _default_signals)
    return subprocess.run([sys.executable, "-c", textwrap.dedent(script)], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=120, **kw)


@pytest.mark.skipif(sys.platform == "win32", reason="SIGTERM is not a catchable signal on Windows")
def test_sigterm_while_python_stages_removes_the_staging_folder_and_the_lock(tmp_path):
    run = _python("""
        import os, signal, time
        from tolalloc.outputs import output_group
        with output_group() as group:
            (group.directory("D") / "a.txt").write_text("half")
            group.file("s.json").write_text("{}")
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(30)
        print("not reached")
    """, tmp_path)
    assert run.returncode == -signal.SIGTERM, run.stderr  # ended by SIGTERM as before, after the clean-up
    assert run.stdout == "" and "Traceback" not in run.stderr
    assert list(tmp_path.iterdir()) == []  # no D, no .tmp-*, no .D.lock


def test_sigint_turned_into_a_library_error_stays_an_interrupt(tmp_path):
    # an interrupt inside an import or a native call can come out as another error (matplotlib: a RuntimeError)
    run = _python("""
        import os, signal, time, sys
        from tolalloc.outputs import atomic_output
        assert "matplotlib.pyplot" not in sys.modules
        try:
            with atomic_output("D", directory=True) as tmp:
                assert "matplotlib.pyplot" in sys.modules  # imported before anything was staged
                (tmp / "a.txt").write_text("half")
                try:
                    os.kill(os.getpid(), signal.SIGINT)
                    time.sleep(30)
                except KeyboardInterrupt:
                    raise RuntimeError("a library's own error")
        except KeyboardInterrupt as exc:
            print(type(exc).__name__, type(exc.__cause__).__name__)
        print(sorted(os.listdir(".")))
    """, tmp_path)
    assert run.stdout.split("\n")[:2] == ["Interrupted RuntimeError", "[]"], run.stderr


def test_the_lock_works_without_fcntl(tmp_path):
    """filelock's portable lock: the output layer with ``fcntl`` missing (as on Windows) stages, locks, publishes."""
    run = _python("""
        import sys
        sys.modules["fcntl"] = None  # import fcntl now fails
        import os
        from tolalloc.exceptions import TolallocError
        from tolalloc.outputs import atomic_output, directory_lock, reservations, reserve_directory
        with atomic_output("D", directory=True) as tmp:
            (tmp / "a.txt").write_text("1")
        print(sorted(os.listdir(".")), sorted(os.listdir("D")))
        with directory_lock("D"):
            try:
                with atomic_output("D", directory=True):
                    pass
            except TolallocError as exc:
                print("refused:", str(exc).split(" (")[0])
        with reservations():
            reserve_directory("E", "--out")
            print(sorted(os.listdir(".")))
            with atomic_output("E", directory=True) as tmp:  # the reservation's own lock, not a second one
                (tmp / "b.txt").write_text("2")
        print(sorted(os.listdir(".")))
    """, tmp_path)
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines() == ["['D'] ['.tolalloc-files', 'a.txt']", "refused: 'D' is being written by "
                                       "another run", "['.E.lock', 'D']", "['D', 'E']"]


@pytest.mark.skipif(not sys.platform.startswith("linux") or os.geteuid() != 0, reason="mounts a tmpfs (Linux, root)")
def test_a_real_full_disk(tmp_path, capsys):
    disk = tmp_path / "disk"
    disk.mkdir()
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", str(disk)], capture_output=True).returncode:
        pytest.skip("cannot mount a tmpfs here")
    try:
        code = main(["mc", "tool_changer", "--n", "100", "--out", str(disk / "out")])
        err = capsys.readouterr().err
        assert code == 2 and err.count("\n") == 1 and "(No space left on device); nothing was written" in err, err
        assert list(disk.iterdir()) == []
    finally:
        subprocess.run(["umount", str(disk)], check=True)
