"""Transmission error: the kinematic error of a joint's gear and encoder, periodic in the joint angle.

A revolute joint's output lags or leads its commanded angle ``q`` by ``dq(q) = sum_k a_k sin(k q) + b_k cos(k q)``
[rad], ``k`` the *order* (cycles per output turn):

* ``1``, ``2``, ``3`` ...: once per output turn and its low harmonics -- the output bearing's and the circular
  spline's runout, the output-side encoder's eccentricity (once per turn: an encoder disc mounted off centre by
  ``e`` on a radius ``r`` reads ``e / r sin(q + phi)``), cumulative pitch errors;
* ``N`` and ``2N`` (``N`` the gear ratio): a strain-wave gear's wave generator turns ``N`` times per output turn and
  deforms the flexspline twice per turn of its own, so its tooth-meshing error repeats at ``N`` and ``2N`` cycles per
  output turn (its catalogue figure, the *transmission accuracy*, is the peak-to-peak of the whole error over one
  output turn); a motor-side encoder's eccentricity repeats at ``N`` too. A stage before the output -- a pinion on a
  ring gear, a spur or belt stage of ratio ``N`` -- repeats its runout and its damaged teeth at ``N`` and ``2N``
  in the same way.

:func:`transmission_columns` is the basis the diagnosis fits (one Gaussian prior scale per joint: a ridge). Where the
robot file gives no ratio, :data:`PLAUSIBLE_RATIOS` (reducers) and then :data:`STAGE_RATIOS` (a stage before the
output) are the candidates of a frequency search (:func:`ratio_columns`), which the diagnosis runs on its training
residual and claims only when the poses resolve the frequency. :func:`transmission_error` is the forward model the
design samples.
"""

from __future__ import annotations

import numpy as np

from tolalloc.robot.model import Robot

__all__ = ["HARMONICS", "SERIES_ORDERS", "PLAUSIBLE_RATIOS", "STAGE_RATIOS", "gear_orders", "variant_orders",
           "coupling_columns", "transmission_columns", "ratio_columns", "transmission_error"]

HARMONICS = {"1x": (1,), "1x2x": (1, 2), "2x3x": (2, 3)}
#: Highest orders of the ``series<K>`` variants (all orders 1..K).
SERIES_ORDERS = (6, 12, 24, 36)
#: Gear ratios a frequency search tries where the robot file gives none: strain-wave and cycloid reducers of robot
#: joints are built from 30:1 to 200:1 (integer ratios: tooth counts).
PLAUSIBLE_RATIOS = tuple(range(30, 201))
#: Orders of a stage before the output tried where no reducer ratio stands out: a pinion on a ring gear, a spur or a
#: belt stage turning 7 to 29 times per output turn (below 7 the low-order ``series`` variants cover it).
STAGE_RATIOS = tuple(range(7, 30))


def gear_orders(ratio: float) -> tuple:
    """Orders of a strain-wave gear of ratio ``N``: once per output turn, ``N`` and ``2N``."""
    return (1.0, float(ratio), 2.0 * float(ratio))


def variant_orders(variant: str, ratio: float | None = None) -> tuple:
    """Orders of a transmission variant (``1x``, ``1x2x``, ``2x3x``, ``series<K>``; ``gear``: :func:`gear_orders`
    of ``ratio``, or once per turn where it is unknown; ``motor``: the low orders plus ``N``)."""
    if variant.startswith("series"):
        return tuple(float(k) for k in range(1, int(variant[6:]) + 1))
    if variant == "gear":
        return gear_orders(ratio) if ratio is not None and np.isfinite(ratio) else (1.0,)
    base = tuple(float(k) for k in HARMONICS.get("2x3x" if variant == "motor" else (variant or "2x3x"), (1,)))
    if variant == "motor" and ratio is not None and np.isfinite(ratio):
        return base + (float(ratio),)
    return base


def _order_label(k: float, ratio: float | None) -> str:
    if ratio is not None and np.isfinite(ratio) and k in (ratio, 2 * ratio) and k > 3:
        return "N" if k == ratio else "2N"
    return f"{k:g}x"


def transmission_columns(robot: Robot, q: np.ndarray, variant: str, ratios: np.ndarray | None = None) -> tuple:
    """Joint-offset basis ``A`` (P, n, M) [rad per unit amplitude], column names and the joint of each column (M,)
    (one prior scale per joint). ``ratios`` (n,): gear ratios (NaN where unknown)."""
    P, n = q.shape
    if variant == "coupling":
        return coupling_columns(robot, q)
    cols, names, groups = [], [], []
    for j in range(n):
        if not robot.joints[j].is_revolute:
            continue
        N = None if ratios is None else float(ratios[j])
        for k in variant_orders(variant, N):
            lab = _order_label(k, N)
            for fn, f in (("s", np.sin), ("c", np.cos)):
                a = np.zeros((P, n))
                a[:, j] = f(k * q[:, j])
                cols.append(a)
                names.append(f"{fn}{lab}_{robot.joints[j].name} [rad]")
                groups.append(j)
    A = np.stack(cols, axis=-1) if cols else np.zeros((P, n, 0))
    return A, names, np.array(groups, int)


def coupling_columns(robot: Robot, q: np.ndarray) -> tuple:
    """Joint-offset basis of ratio and coupling errors (:func:`transmission_columns`' layout): every revolute joint
    ``j`` turns by ``k_jj q_j`` (its own ratio off) and ``k_jk q_k`` (a coupling to joint ``k``: a coupled wrist's
    coupling factor, a shaft or spline running through another axis) [rad per rad, or per m of a prismatic joint's
    stroke]; one prior scale per joint."""
    P, n = q.shape
    cols, names, groups = [], [], []
    for j in range(n):
        if not robot.joints[j].is_revolute:
            continue
        for k in range(n):
            a = np.zeros((P, n))
            rev = robot.joints[k].is_revolute
            a[:, j] = q[:, k] if rev else q[:, k] / 1000.0
            cols.append(a)
            names.append(f"k_{robot.joints[j].name}_{robot.joints[k].name} [rad/{'rad' if rev else 'm'}]")
            groups.append(j)
    A = np.stack(cols, axis=-1) if cols else np.zeros((P, n, 0))  # no revolute joint: no column
    return A, names, np.array(groups, int)


def ratio_columns(qj: np.ndarray, ratio: float) -> np.ndarray:
    """The ``N`` and ``2N`` columns of one joint's angles ``qj`` (P,) for a candidate ratio, shape (P, 4)."""
    return np.stack([np.sin(ratio * qj), np.cos(ratio * qj), np.sin(2 * ratio * qj), np.cos(2 * ratio * qj)], axis=1)


def transmission_error(q: np.ndarray, orders, amplitudes, phases) -> np.ndarray:
    """Kinematic error [rad] of one joint at angles ``q`` (P,): ``sum_k A_k sin(k q + phi_k)`` over ``orders``,
    ``amplitudes`` [rad] and ``phases`` [rad] (each shape (K,)), shape (P,)."""
    q = np.asarray(q, float)[:, None]
    return np.sum(np.asarray(amplitudes, float) * np.sin(np.asarray(orders, float) * q + np.asarray(phases, float)),
                  axis=1)


#: How the catalogue's peak-to-peak transmission accuracy is shared among the orders 1, N and 2N of a gear (an
#: ASSUMPTION: most of the error once per output turn, as the periodograms of the UR10 in reports/sim2real_ur10 find
#: little at N and 2N). The amplitudes sum to half the peak-to-peak, so the sum of sines never exceeds the figure.
GEAR_SHARES = (0.7, 0.15, 0.15)


def catalogue_amplitudes(ptp: float, ratio: float | None) -> tuple:
    """Orders and amplitudes [rad or mm] of a gear whose catalogue transmission accuracy is ``ptp`` (peak-to-peak
    over one output turn): :data:`GEAR_SHARES` of ``ptp / 2`` at orders 1, N and 2N (all at order 1 without a
    ratio). Returns ``(orders (K,), amplitudes (K,))``; the variance over a random phase is ``sum(a^2) / 2``."""
    if ratio is None or not np.isfinite(ratio):
        return np.array([1.0]), np.array([ptp / 2.0])
    return np.array(gear_orders(ratio)), ptp / 2.0 * np.array(GEAR_SHARES)
