"""Figures. Every function draws from a result object and never recomputes.

One module per pipeline stage (``mc``, ``linear``, ``allocate``, ``diagnose``).
The non-interactive Agg backend is selected so figures are produced without a display.
"""

import sys

import matplotlib

if "ipykernel" not in sys.modules:  # files only; a notebook keeps its inline backend and shows the figures
    matplotlib.use("Agg")


def fit_layout(fig) -> None:
    """``fig.tight_layout()``, leaving no layout engine on the figure.

    ``tight_layout`` leaves a placeholder engine behind, and ``savefig`` draws a figure that has any engine once more
    (without rendering) before it renders it: about a third of the save, for the same pixels.
    """
    fig.tight_layout()
    fig.set_layout_engine(None)
