"""Monte Carlo engines: the numpy reference path lives in :mod:`tolalloc.montecarlo.run.blocks`; the compiled numba engine here."""

