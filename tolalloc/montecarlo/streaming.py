"""Streaming Monte Carlo statistics: merge-able moments, extrema, counts and fixed-range 2-D histograms.

Every statistic is accumulated chunk by chunk, so memory does not grow with the number of samples:

* moments (count, mean, co-moment matrix) merge with Chan et al.'s parallel update; merging is done in
  a fixed order (sub-blocks within a block, blocks in block order), so results do not depend on how the
  blocks were grouped into chunks, threads or cluster tasks;
* extrema, threshold counts and histogram counts are exact (max/min and integer sums), hence
  associative.

Histograms are fixed-range (the range is chosen before sampling, e.g. from the linear prediction), with
one overflow cell on every side so that nothing is silently dropped.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError

__all__ = ["Moments", "Extras", "HistSpec", "McHistogram", "proportion_ci", "PLANES"]

#: Projection planes of the 2-D histograms: (axis i, axis j, name).
PLANES = ((0, 1, "xy"), (0, 2, "xz"), (1, 2, "yz"))


class Moments:
    """Running count, mean and co-moment matrix ``sum (x - mean)(x - mean)^T`` of feature vectors."""

    __slots__ = ("n", "mean", "M2")

    def __init__(self, n: int = 0, mean: np.ndarray | None = None, M2: np.ndarray | None = None):
        self.n, self.mean, self.M2 = n, mean, M2

    @classmethod
    def of(cls, F: np.ndarray) -> "Moments":
        """Moments of the columns of ``F`` (d, N); ``F`` is centred in place (its values are destroyed)."""
        N = F.shape[1]
        mean = F.mean(axis=1)
        F -= mean[:, None]
        return cls(N, mean, F @ F.T)

    def merge(self, other: "Moments") -> "Moments":
        """Add ``other`` in place (Chan et al.); returns self."""
        if other.n == 0:
            return self
        if self.n == 0:
            self.n, self.mean, self.M2 = other.n, other.mean.copy(), other.M2.copy()
            return self
        tot = self.n + other.n
        d = other.mean - self.mean
        self.mean = self.mean + d * (other.n / tot)
        self.M2 = self.M2 + other.M2 + np.outer(d, d) * (self.n * other.n / tot)
        self.n = tot
        return self

    def cov(self, ddof: int = 1) -> np.ndarray:
        return self.M2 / max(self.n - ddof, 1)


class Extras:
    """Exact, associative statistics: extrema (d,), threshold counts (R,), histogram counts."""

    __slots__ = ("mx", "mn", "counts", "hist")

    def __init__(self, mx, mn, counts, hist=None):
        self.mx, self.mn, self.counts, self.hist = mx, mn, counts, hist

    def merge(self, other: "Extras") -> "Extras":
        np.maximum(self.mx, other.mx, out=self.mx)
        np.minimum(self.mn, other.mn, out=self.mn)
        self.counts += other.counts
        if self.hist is not None:
            self.hist += other.hist
        return self


@dataclass(frozen=True)
class HistSpec:
    """Fixed-range histogram layout: ``bins`` per axis on ``[lo, lo + bins * width)`` per axis and pose.

    Attributes
    ----------
    lo_mm, width_mm : array, shape (P, 3)
    bins : int
    """

    lo_mm: np.ndarray
    width_mm: np.ndarray
    bins: int

    @classmethod
    def symmetric(cls, half_width_mm: np.ndarray, bins: int) -> "HistSpec":
        """Windows ``[-h, h]`` per pose and axis; ``half_width_mm`` (P, 3) [mm] > 0."""
        h = np.asarray(half_width_mm, float)
        if h.ndim != 2 or h.shape[1] != 3 or not np.all(np.isfinite(h)) or np.any(h <= 0):
            raise TolallocError(f"hist_range_mm: expected finite half-widths > 0 [mm] of shape (P, 3), got {h!r}.")
        if int(bins) != bins or bins < 2 or bins > 2000:
            raise TolallocError(f"hist_bins: expected an integer number of bins in [2, 2000], got {bins!r}.")
        return cls(-h, 2 * h / int(bins), int(bins))

    @property
    def cells(self) -> int:
        return (self.bins + 2) ** 2

    def cell_index(self, dp: np.ndarray, pose: int, out: np.ndarray, tmp: np.ndarray) -> None:
        """Flat cell indices of the three planes for position errors ``dp`` (3, N) into ``out`` (3, N) int.

        Cells include one overflow row/column on each side (index 0 and ``bins + 1``).
        """
        b = self.bins
        N = dp.shape[1]
        idx = np.empty((3, N), dtype=np.intp)
        for a in range(3):
            t = tmp[:N]
            np.subtract(dp[a], self.lo_mm[pose, a], out=t)
            t *= 1.0 / self.width_mm[pose, a]
            np.floor(t, out=t)
            np.clip(t, -1.0, float(b), out=t)
            t += 1.0
            idx[a] = t
        for k, (i, j, _) in enumerate(PLANES):
            np.multiply(idx[i], b + 2, out=out[k])
            out[k] += idx[j]

    def count(self, cells: np.ndarray) -> np.ndarray:
        """Histogram counts (3, bins + 2, bins + 2) of flat cell indices (3, N)."""
        c = self.cells
        return np.stack([np.bincount(cells[k], minlength=c) for k in range(3)]).reshape(3, self.bins + 2, self.bins + 2)


@dataclass(frozen=True)
class McHistogram:
    """Fixed-range 2-D histograms of the position error ``p' - p`` projected on the x-y, x-z, y-z planes.

    Attributes
    ----------
    n : int
        Samples counted (all of them; those outside the window are in ``outside``).
    edges_mm : array, shape (P, 3, bins + 1)
        Bin edges per pose and axis (x, y, z) [mm].
    counts : array of int, shape (P, 3, bins, bins)
        ``counts[p, k, i, j]``: samples of pose ``p`` in cell ``(i, j)`` of plane ``k`` (x-y, x-z, y-z),
        first index along the plane's first axis.
    outside : array of int, shape (P, 3)
        Samples of the plane outside its window.
    """

    n: int
    edges_mm: np.ndarray
    counts: np.ndarray
    outside: np.ndarray
    planes: tuple = ("xy", "xz", "yz")

    def density(self, pose: int = 0, plane: str = "xy") -> np.ndarray:
        """Probability density [1/mm^2] on the cells of one plane, shape (bins, bins)."""
        if plane not in self.planes:
            raise TolallocError(f"plane: expected one of {self.planes}, got {plane!r}.")
        k = self.planes.index(plane)
        i, j, _ = PLANES[k]
        wi = np.diff(self.edges_mm[pose, i])[0]
        wj = np.diff(self.edges_mm[pose, j])[0]
        return self.counts[pose, k] / (self.n * wi * wj)

    def to_frame(self) -> pd.DataFrame:
        """One row per pose and plane with the window and the fraction outside it."""
        rows = []
        for p in range(self.counts.shape[0]):
            for k, (i, j, name) in enumerate(PLANES):
                rows.append({"pose": p, "plane": name, "bins": self.counts.shape[-1],
                             "lo_i_mm": self.edges_mm[p, i, 0], "hi_i_mm": self.edges_mm[p, i, -1],
                             "lo_j_mm": self.edges_mm[p, j, 0], "hi_j_mm": self.edges_mm[p, j, -1],
                             "fraction_outside": self.outside[p, k] / self.n})
        return pd.DataFrame(rows)


def proportion_ci(k, n, ci: str = "wilson", level: float = 0.95) -> np.ndarray:
    """Point estimate and two-sided confidence interval of a binomial proportion.

    Parameters
    ----------
    k : array of int
        Successes.
    n : int or array of int (broadcast with ``k``)
        Trials.
    ci : {"wilson", "exact"}
        Wilson score interval or Clopper-Pearson.

    Returns
    -------
    array, shape (..., 3): ``p, low, high``.
    """
    from scipy import stats

    k, nn = np.asarray(k, dtype=float), np.asarray(n, dtype=float)
    if not (np.all(np.isfinite(nn)) and np.all(nn >= 1) and np.all(np.isfinite(k)) and np.all((k >= 0) & (k <= nn))):
        raise TolallocError(f"k, n: expected 0 <= k <= n successes of n >= 1 trials, got k = "
                            f"{np.array2string(k, threshold=6)}, n = {np.array2string(nn, threshold=6)}.")
    if not 0.0 < level < 1.0:
        raise TolallocError(f"level: expected a confidence level strictly between 0 and 1, got {level!r}.")
    p = k / n
    if ci == "wilson":
        z = stats.norm.ppf(0.5 + level / 2)
        den = 1 + z**2 / n
        centre = (p + z**2 / (2 * n)) / den
        half = z * np.sqrt(p * (1 - p) / n + z**2 / (4 * n**2)) / den
        lo, hi = np.clip(centre - half, 0, 1), np.clip(centre + half, 0, 1)
    elif ci in ("exact", "clopper-pearson"):
        a = (1 - level) / 2
        lo = np.where(k > 0, stats.beta.ppf(a, np.maximum(k, 1e-300), n - k + 1), 0.0)
        hi = np.where(k < n, stats.beta.ppf(1 - a, k + 1, np.maximum(n - k, 1e-300)), 1.0)
    else:
        raise TolallocError(f"ci: expected 'wilson' or 'exact' (Clopper-Pearson), got {ci!r}.")
    return np.stack([p, lo, hi], axis=-1)
