"""Figures. Every function draws from a result object and never recomputes.

One module per pipeline stage (``mc``, ``linear``, ``allocate``, ``diagnose``).
The non-interactive Agg backend is selected so figures are produced without a display.
"""

import sys

import matplotlib

if "ipykernel" not in sys.modules:  # files only; a notebook keeps its inline backend and shows the figures
    matplotlib.use("Agg")
