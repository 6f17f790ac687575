"""The protocol every workflow result follows (the docs page "Results" describes it):

* ``save(directory, *, report=False, json=None) -> list[Path]``: the files written into ``directory`` (created or
  updated, all files together or none), ``report=True`` adding ``report.html`` where the result has one;
  ``json=FILE`` the JSON summary to a file, ``json="-"`` to standard output (as ``--json -`` on the command line);
* ``write_files(folder, *, report=False) -> list[str]``: the same files into an existing folder, not atomic;
* ``to_frame()`` (the key table), ``summary()`` (the JSON), ``text()`` (what the command prints), ``ok``;
* ``plot_*(ax=None)``: draw into ``ax`` (an Axes, or a sequence of them for a figure of several panels) or a new
  figure, and return the axes drawn on;
* ``repr()`` a few lines, and ``_repr_html_()`` a compact card for notebooks (the headline and the key table, without
  empty columns).

Paths may be ``str`` or any ``os.PathLike`` wherever a path goes.
"""

from __future__ import annotations

import html
import os
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.exceptions import ArgumentError, TolallocError
from tolalloc.outputs import check_distinct_outputs, check_output, output_group, write_json
from tolalloc.workflows.checks import check_flag

__all__ = ["JobResult", "AllocationJobResult", "html_card", "format_labels", "compact_frame", "axes_of", "CARD_ROWS"]

#: rows of the key table in the HTML card at most (the rest: ``to_frame()``)
CARD_ROWS = 25


def compact_frame(frame: pd.DataFrame | None) -> pd.DataFrame | None:
    """``frame`` for a card: each ``X_mm`` / ``X_deg`` pair of a frame with a ``unit`` column as one column ``X``
    in the row's unit, and the columns empty in every row dropped."""
    if frame is None:
        return None
    frame = frame.copy()
    if "unit" in frame.columns:
        for col in [c for c in frame.columns if c.endswith("_mm") and c[:-3] + "_deg" in frame.columns]:
            base = col[:-3]
            merged = frame[col].where(frame["unit"] == "mm", frame[base + "_deg"])
            frame.insert(list(frame.columns).index(col), base, merged)
            frame = frame.drop(columns=[col, base + "_deg"])
    empty = [c for c in frame.columns if frame[c].isna().all() or (frame[c].astype(str) == "").all()]
    return frame.drop(columns=empty)


def html_card(title: str, lines: list[str], frame: pd.DataFrame | None = None, *, max_rows: int = CARD_ROWS) -> str:
    """A small HTML block: a title, a few ``key: value`` lines and an optional table (no external resources; empty
    cells blank, never ``NaN``)."""
    head = f"<strong>{html.escape(title)}</strong>"
    body = "".join(f"<div>{html.escape(s)}</div>" for s in lines)
    table = ""
    if frame is not None and len(frame.columns):
        table = frame.head(max_rows).to_html(index=False, border=0, na_rep="", float_format=lambda x: f"{x:.5g}")
        if len(frame) > max_rows:
            table += f"<div>… {len(frame) - max_rows} more rows (to_frame())</div>"
    return f'<div class="tolalloc-result">{head}{body}{table}</div>'


def axes_of(drawn):
    """What a ``plot_*`` method returns: the Axes drawn on (one Axes, or an array for a figure of several panels)
    of a figure or of the axes a plotting function was given."""
    import matplotlib.figure

    if isinstance(drawn, matplotlib.figure.Figure):
        axes = drawn.axes
        return axes[0] if len(axes) == 1 else np.array(axes, dtype=object)
    if isinstance(drawn, (list, tuple)):
        return np.array(drawn, dtype=object)
    return drawn


def _old_axes(method: str, ax, axes):
    """``axes=`` of a plot method before the protocol: the same as ``ax=``, with a DeprecationWarning."""
    if axes is None:
        return ax
    warnings.warn(f"{method}(axes=...) is deprecated: use {method}(ax=...) (every plot_* method takes ax).",
                  DeprecationWarning, stacklevel=3)
    if ax is not None:
        raise ArgumentError("axes", "and `ax` both given; give ax only.")
    return axes


class JobResult:
    """Base of the workflow results: the :mod:`save protocol <tolalloc.workflows.base>`, ``__repr__`` and
    ``_repr_html_`` from :meth:`headline`.

    Subclasses define ``headline() -> list[str]`` (a few lines: robot, requirement, cost, verdict), ``to_frame()``,
    ``summary()``, ``text()`` and ``write_files(folder, *, report=False) -> list[str]``; ``has_report`` says
    whether ``report=True`` writes a ``report.html``.
    """

    #: whether :meth:`save` can write a self-contained ``report.html`` (``report=True``)
    has_report: bool = False

    def headline(self) -> list[str]:  # pragma: no cover - every subclass overrides it
        raise NotImplementedError

    def write_files(self, folder, *, report: bool = False) -> list[str]:  # pragma: no cover
        raise NotImplementedError

    def __repr__(self) -> str:
        lines = self.headline()
        return f"<{type(self).__name__}\n  " + "\n  ".join(lines) + ">"

    def card_frame(self) -> pd.DataFrame | None:
        """The key table of the HTML card (default :meth:`to_frame`)."""
        return self.to_frame()

    def card_lines(self) -> list[str]:
        """The lines above the card's table (default :meth:`headline`)."""
        return self.headline()

    def _repr_html_(self) -> str:
        try:
            frame = compact_frame(self.card_frame())
        except TolallocError:  # a result without a table still shows its headline
            frame = None
        return html_card(type(self).__name__, self.card_lines(), frame)

    # ------------------------------------------------------------------ saving
    def check_savable(self) -> None:
        """Refuse to save a result with nothing to write (an infeasible allocation); a no-op by default."""

    def save(self, directory=None, *, report: bool = False, json=None, **old) -> list[Path]:
        """Write the result's files into ``directory`` (``str`` or ``os.PathLike``; created if missing, files of the
        same name replaced; all files appear together or none) and / or its JSON summary to ``json`` (a file, or
        ``"-"`` for standard output). ``report=True`` adds the self-contained ``report.html`` (results with
        ``has_report``). Returns the paths of the files written (not standard output)."""
        directory, report = self._old_save_keywords(directory, report, old)
        return self._save(directory, report=report, json=json)

    def _old_save_keywords(self, directory, report, old: dict):
        """``out=`` (the directory's former name), with a DeprecationWarning."""
        if "out" in old:
            warnings.warn(f"{type(self).__name__}.save(out=...) is deprecated: use save(directory) (every result "
                          "saves as save(directory, *, report=False, json=None)).", DeprecationWarning, stacklevel=3)
            if directory is not None:
                raise ArgumentError("out", "and `directory` both given; give directory only.")
            directory = old.pop("out")
        if old:
            name = next(iter(old))
            raise ArgumentError(name, f"save() has no argument {name!r}; it takes directory, report and json.")
        return directory, report

    def _save(self, directory, *, report, json, extra=()) -> list[Path]:
        """:meth:`save`, with ``extra`` more files ``[(argument, path, writer(staging path))]`` published with the
        others."""
        self.check_savable()
        directory = self.check_out(directory, "directory")
        report = check_flag(report, "report")
        if report and not self.has_report:
            raise ArgumentError("report", f"{type(self).__name__} has no HTML report (the allocations and the "
                                "diagnosis have one); leave out report.")
        if report and directory is None:
            raise ArgumentError("report", "needs `directory`: report.html is written into it.")
        to_stdout = isinstance(json, str) and json == "-"
        json_path = None if to_stdout else self.check_out(json, "json", directory=False)
        extra = [(a, Path(p), w) for a, p, w in extra if p is not None]
        if directory is None and json is None and not extra:
            raise ArgumentError("directory", "nothing to save: expected a directory to write into (a str or "
                                "pathlib.Path), and / or json=FILE ('-' for standard output).")
        check_distinct_outputs([("directory", directory), ("json", json_path), *[(a, p) for a, p, _ in extra]],
                               files=("json", *[a for a, _, _ in extra]))
        written = []
        with output_group() as group:
            if directory is not None:
                written += [directory / name for name in self.write_files(group.directory(directory), report=report)]
            if json_path is not None:
                write_json(self.summary(), group.file(json_path))
                written.append(json_path)
            for _, path, writer in extra:
                writer(group.file(path))
                written.append(path)
        if to_stdout:
            write_json(self.summary(), "-")
        return written

    @staticmethod
    def check_out(path, argument: str, *, directory: bool = True, required: bool = False) -> Path | None:
        """Refuse an output path that cannot be written, before anything is written (None passes unless
        ``required``)."""
        want = "a directory" if directory else "a file"
        if path is None and required:
            raise ArgumentError(argument, f"expected {want} path to write to (a str or pathlib.Path), got None.")
        if path is not None and (not isinstance(path, (str, os.PathLike)) or "\0" in str(path) or not str(path)):
            raise ArgumentError(argument, f"expected {want} path (a str or pathlib.Path), got "
                                f"{type(path).__name__} {' '.join(repr(path).split())[:60]}.")
        check_output(path, argument, directory=directory)
        return None if path is None else Path(path)


def format_labels(labels: dict) -> str:
    """Model options for a one-line header: ``sigma_set=table2, link_mode=consistent, ...``."""
    return ", ".join(f"{k}={v}" for k, v in labels.items() if v is not None)


class AllocationJobResult(JobResult):
    """Base of the two allocation results (:class:`~.allocation_result.ToleranceAllocation`,
    :class:`~.calibrated.CalibratedToleranceAllocation`): both hold the allocation's ``result`` (its ``problem``)."""

    def reproduce_command(self) -> tuple:
        """``(command line, Python call, notes)`` that reproduce this result (:mod:`tolalloc.workflows.reproduce`)."""
        from tolalloc.workflows.reproduce import allocation_command

        return allocation_command(self)

    @property
    def robot(self):
        return self.result.problem.model.robot

    @property
    def problem(self):
        return self.result.problem
