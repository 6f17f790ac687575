"""When to show progress, and a bar over the stages of a long job.

A foundation module: the Monte Carlo engine, the diagnosis and the workflows all ask :func:`show_progress` whether
``progress=None`` means on -- when a person is watching: stderr is a terminal, or the code runs in a Jupyter
kernel (where stderr is not a terminal but the notebook shows what is written to it).
"""

from __future__ import annotations

import sys

__all__ = ["show_progress", "StageBar"]


def show_progress(progress: bool | None) -> bool:
    """``progress`` itself when given; for None, whether a person is watching (terminal or notebook)."""
    if progress is not None:
        return bool(progress)
    return bool(sys.stderr.isatty()) or "ipykernel" in sys.modules


class StageBar:
    """A status line on stderr naming the stage one job is in, with the time since it started (``with
    StageBar(show, "allocate") as bar: bar.stage("region search")``); a no-op when ``show`` is false."""

    def __init__(self, show: bool, job: str):
        self.job, self._bar, self._started = job, None, False
        if show:
            from tqdm import tqdm

            self._bar = tqdm(desc=job, unit="stage", file=sys.stderr, leave=False, dynamic_ncols=True,
                             bar_format="{desc} ({elapsed} so far)")

    def stage(self, name: str) -> None:
        """Start stage ``name`` (the previous one is done)."""
        if self._bar is None:
            return
        if self._started:
            self._bar.update(1)
        self._started = True
        self._bar.set_description_str(f"{self.job}: {name}")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self._bar is not None:
            self._bar.close()
        return False
