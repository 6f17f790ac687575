"""Bulk sampling of error-parameter values: the one sampler of the error model and the Monte Carlo engines.

The stream is part of the definition of the numbers: all normal parameters with non-zero sigma are drawn in
one call, then the other distributions in parameter order.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from tolalloc.errormodel.model import ErrorModel

__all__ = ["sample_values", "draw_rows"]


def draw_rows(model: ErrorModel, m: int, rng: np.random.Generator, out: np.ndarray, fill_normal=None) -> np.ndarray:
    """Fill ``out`` (K, m) with parameter draws; returns the row multipliers ``mult`` (K,).

    Normal rows hold standard normals (value = ``mult * row``, ``mult = sigma``); other rows hold the
    values (``mult = 1``); zero-sigma rows are 0 (``mult = 0``). All normal rows are drawn in one call,
    then the others in parameter order (the stream of :func:`sample_values`). ``fill_normal(rng, out)``:
    an alternative filler of standard normals for the normal rows that draws the same numbers (the numba
    engine passes its port of numpy's generator, :func:`tolalloc.montecarlo.run.engines.numba_engine.fill_standard_normal`).
    """
    params = model.params
    sig = model.sigma
    mult = np.zeros(len(params))
    normal = [k for k, p in enumerate(params) if p.distribution == "normal" and sig[k] > 0]
    if normal:
        a = normal[0]
        if fill_normal is not None:
            tmp = out[a:a + len(normal)] if normal == list(range(a, a + len(normal))) else np.empty((len(normal), m))
            fill_normal(rng, tmp)
            out[normal] = tmp
        elif normal == list(range(a, a + len(normal))):
            rng.standard_normal(out=out[a:a + len(normal)])
        else:
            out[normal] = rng.standard_normal((len(normal), m))
        mult[normal] = sig[normal]
    done = set(normal)
    for k, p in enumerate(params):
        if k in done:
            continue
        if sig[k] == 0:
            out[k] = 0.0
            continue
        mult[k] = 1.0
        if p.distribution == "ring":
            k2 = next((i for i, o in enumerate(params) if o.group == p.group and i != k), None)
            s = rng.standard_normal(m) * (np.sqrt(2.0) * p.sigma)
            t = rng.uniform(0.0, 2 * np.pi, m)
            out[k] = s * np.cos(t)
            done.add(k)
            if k2 is not None:
                out[k2] = s * np.sin(t)
                mult[k2] = 1.0
                done.add(k2)
        elif p.distribution == "uniform":
            out[k] = rng.uniform(-np.sqrt(3.0) * p.sigma, np.sqrt(3.0) * p.sigma, m)
        elif p.distribution == "truncnormal":
            from scipy.stats import truncnorm

            out[k] = truncnorm.rvs(-3, 3, scale=p.sigma, size=m, random_state=rng)
    return mult


def sample_values(model: ErrorModel, m: int, rng: np.random.Generator) -> np.ndarray:
    """Draw ``m`` samples of the parameter values, transposed: shape (K, m) [mm, rad].

    The distributions of :class:`~tolalloc.errormodel.model.ErrorParameter` (normal, uniform over ``±sqrt(3) sigma``,
    normal truncated at ``±3 sigma``, ring pairs ``s (cos t, sin t)``), drawn in bulk: all normal
    parameters with non-zero sigma in one call; zero-sigma parameters are exactly 0 and draw nothing.
    :meth:`ErrorModel.sample` is this, transposed.
    """
    out = np.empty((len(model.params), m))
    mult = draw_rows(model, m, rng, out)
    scaled = [k for k, p in enumerate(model.params) if p.distribution == "normal" and mult[k] > 0]
    out[scaled] *= mult[scaled, None]
    return out
