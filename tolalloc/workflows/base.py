"""What every workflow result shares: a compact repr, an HTML view for notebooks, atomic saving."""

from __future__ import annotations

import html
from pathlib import Path

import pandas as pd

from tolalloc.outputs import check_output

__all__ = ["JobResult", "html_card", "format_labels"]


def html_card(title: str, lines: list[str], frame: pd.DataFrame | None = None, *, max_rows: int = 40) -> str:
    """A small HTML block: a title, a few ``key: value`` lines and an optional table (no external resources)."""
    head = f"<strong>{html.escape(title)}</strong>"
    body = "".join(f"<div>{html.escape(s)}</div>" for s in lines)
    table = ""
    if frame is not None:
        table = frame.head(max_rows).to_html(index=False, border=0, float_format=lambda x: f"{x:.5g}")
        if len(frame) > max_rows:
            table += f"<div>… {len(frame) - max_rows} more rows (to_frame())</div>"
    return f'<div class="tolalloc-result">{head}{body}{table}</div>'


class JobResult:
    """Mixin of the workflow results: ``__repr__`` and ``_repr_html_`` from :meth:`headline`, and
    :meth:`check_out` for the paths a :meth:`save` is about to write.

    Subclasses define ``headline() -> list[str]`` (a few lines: robot, requirement, cost, verdict),
    ``to_frame()``, ``summary()``, ``text()`` and ``save(...)``.
    """

    def headline(self) -> list[str]:  # pragma: no cover - every subclass overrides it
        raise NotImplementedError

    def __repr__(self) -> str:
        lines = self.headline()
        return f"<{type(self).__name__}\n  " + "\n  ".join(lines) + ">"

    def _repr_html_(self) -> str:
        try:
            frame = self.to_frame()
        except Exception:  # a result without a table still shows its headline
            frame = None
        return html_card(type(self).__name__, self.headline(), frame)

    @staticmethod
    def check_out(path, argument: str, *, directory: bool = True, required: bool = False) -> Path | None:
        """Refuse an output path that cannot be written, before anything is written (None passes unless
        ``required``)."""
        import os

        from tolalloc.exceptions import ArgumentError

        want = "a directory" if directory else "a file"
        if path is None and required:
            raise ArgumentError(argument, f"expected {want} path to write to (a str or pathlib.Path), got None.")
        if path is not None and (not isinstance(path, (str, os.PathLike)) or "\0" in str(path)):
            raise ArgumentError(argument, f"expected {want} path (a str or pathlib.Path), got "
                                f"{type(path).__name__} {' '.join(repr(path).split())[:60]}.")
        check_output(path, argument, directory=directory)
        return None if path is None else Path(path)


def format_labels(labels: dict) -> str:
    """Model options for a one-line header: ``sigma_set=table2, link_mode=consistent, ...``."""
    return ", ".join(f"{k}={v}" for k, v in labels.items() if v is not None)
