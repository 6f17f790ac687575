"""The ISO 9283 statistics of a test, computed from attained poses exactly as the standard defines them.

ISO 9283:1998 (Manipulating industrial robots -- Performance criteria and related test methods):

* **pose accuracy** (7.2.1): the distance from the command position to the *barycentre* of the attained
  positions of ``n`` cycles approaching the command pose from the same direction::

      AP_P = sqrt((xb - xc)^2 + (yb - yc)^2 + (zb - zc)^2),   xb = (1/n) sum_j x_j  (likewise y, z)

  and per orientation angle ``AP_a = ab - ac`` (likewise ``b``, ``c``);
* **pose repeatability** (7.2.2)::

      RP_l = lb + 3 S_l,   l_j = |P_j - barycentre|,   lb = (1/n) sum_j l_j,
      S_l = sqrt(sum_j (l_j - lb)^2 / (n - 1))

  and per angle ``RP_a = +-3 S_a``, ``S_a = sqrt(sum_j (a_j - ab)^2 / (n - 1))`` (likewise ``b``, ``c``);
* **multi-directional pose accuracy variation** (7.2.3): the pose approached ``n`` times from each of three
  orthogonal directions ``h``, the largest distance between the barycentres of the directions::

      vAP_P = max_{h, k} sqrt((xb_h - xb_k)^2 + (yb_h - yb_k)^2 + (zb_h - zb_k)^2)

  and per orientation angle ``vAP_a = max_{h, k} |ab_h - ab_k|`` (likewise ``b``, ``c``);

* **distance accuracy** (7.3): with ``D_j = |P1_j - P2_j|`` the attained and ``D_c = |P1c - P2c|`` the command
  distance of two poses, ``AD_P = Db - D_c`` (``Db`` the mean of the ``D_j``); **distance repeatability**
  ``RD = +-3 S_D``;
* **path accuracy** (8.2): the largest distance, over the points of the command path, from the command point to
  the barycentre of the attained points of ``n`` cycles, ``AT_P = max_i |Pb_i - P_ci|``; **path repeatability**
  (8.3) ``RT_P = max_i (lb_i + 3 S_li)``.

Orientation angles: the standard states them as rotations ``a, b, c`` about the base axes x, y, z. For the small
deviations of a test they are, to first order, the components of the rotation vector of ``R_attained R_command^T``
(base frame); that is how the simulations of this package give them.

Every function takes plain arrays [mm, rad] and needs at least two cycles (``S`` divides by ``n - 1``).
"""

from __future__ import annotations

import numpy as np

from tolalloc.exceptions import TolallocError

__all__ = ["pose_accuracy", "pose_repeatability", "orientation_accuracy", "orientation_repeatability",
           "multidirectional_accuracy", "barycentre_distances", "multidirectional_orientation", "angle_differences",
           "distance_accuracy", "distance_repeatability", "path_accuracy", "path_repeatability", "check_cycles",
           "MIN_CYCLES", "PAIRS"]

#: the pairs of the three approach directions of a multi-directional test, in the order of :func:`barycentre_distances`
PAIRS = ((0, 1), (0, 2), (1, 2))

#: the fewest cycles a repeatability needs (its standard deviation divides by n - 1)
MIN_CYCLES = 2


def check_cycles(n, name: str = "cycles") -> int:
    """A whole number of cycles of at least :data:`MIN_CYCLES`, as int."""
    ok = isinstance(n, (int, np.integer)) and not isinstance(n, bool) and int(n) >= MIN_CYCLES
    if not ok:
        raise TolallocError(f"{name}: expected a whole number of cycles of at least {MIN_CYCLES} (ISO 9283 uses 30 "
                            f"for pose and distance characteristics, 10 for path characteristics), got {n!r}; a "
                            "repeatability needs at least two attained poses of one command pose.")
    return int(n)


def _cycles(x, width: int, name: str) -> np.ndarray:
    """``x`` as an array (..., n, width) of finite values with n >= 2 cycles."""
    a = np.asarray(x, dtype=float)
    if a.ndim < 2 or a.shape[-1] != width:
        raise TolallocError(f"{name}: expected the attained values of the cycles as an array of shape (n, {width}) "
                            f"(n cycles), got shape {a.shape}.")
    check_cycles(a.shape[-2], f"{name} (number of cycles)")
    if not np.all(np.isfinite(a)):
        raise TolallocError(f"{name}: every attained value must be a finite number; got NaN or inf.")
    return a


def _commanded(x, attained: np.ndarray, name: str) -> np.ndarray:
    """``x`` as finite values of one command per cycle group: shape ``attained.shape[:-2] + (3,)`` or broadcasting
    to it."""
    try:
        c = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise TolallocError(f"{name}: expected the command as numbers [mm or rad], got {x!r}.") from None
    want = attained.shape[:-2] + (3,)
    try:
        if np.broadcast_shapes(c.shape, want) != want:
            raise ValueError
    except ValueError:
        raise TolallocError(f"{name}: expected the command as shape {want} (one per group of cycles), got shape "
                            f"{c.shape}.") from None
    if c.ndim == 0 or c.shape[-1] != 3:
        raise TolallocError(f"{name}: expected three values per command (x, y, z or a, b, c), got shape {c.shape}.")
    if not np.all(np.isfinite(c)):
        raise TolallocError(f"{name}: every commanded value must be a finite number; got NaN or inf.")
    return c


def _wrapped(angles: np.ndarray, reference) -> np.ndarray:
    """``angles - reference`` [rad] wrapped into [-pi, pi): a tool pointing down reads +-180 deg, and the cycles on
    either side of that seam are a few thousandths apart, not 2 pi."""
    return (angles - reference + np.pi) % (2 * np.pi) - np.pi


def pose_accuracy(attained_mm, commanded_mm) -> np.ndarray:
    """ISO 9283 7.2.1 position accuracy ``AP_P``: distance from the command position to the barycentre.

    Parameters
    ----------
    attained_mm : array, shape (..., n, 3) [mm]
        Attained positions of ``n`` cycles.
    commanded_mm : array, shape (..., 3) [mm]

    Returns
    -------
    array, shape (...) [mm]
    """
    a = _cycles(attained_mm, 3, "attained_mm")
    return np.linalg.norm(a.mean(axis=-2) - _commanded(commanded_mm, a, "commanded_mm"), axis=-1)


def pose_repeatability(attained_mm) -> np.ndarray:
    """ISO 9283 7.2.2 position repeatability ``RP_l = lb + 3 S_l`` of the attained positions.

    Parameters
    ----------
    attained_mm : array, shape (..., n, 3) [mm]

    Returns
    -------
    array, shape (...) [mm]
    """
    a = _cycles(attained_mm, 3, "attained_mm")
    l_ = np.linalg.norm(a - a.mean(axis=-2, keepdims=True), axis=-1)
    return l_.mean(axis=-1) + 3.0 * l_.std(axis=-1, ddof=1)


def orientation_accuracy(attained_rad, commanded_rad) -> np.ndarray:
    """ISO 9283 7.2.1 orientation accuracy ``(AP_a, AP_b, AP_c)``: mean attained angle minus command angle (each
    cycle's difference wrapped into [-pi, pi) first, so angles across the +-180 deg seam average correctly).

    Parameters
    ----------
    attained_rad : array, shape (..., n, 3) [rad]
        Attained angles ``a, b, c`` of ``n`` cycles.
    commanded_rad : array, shape (..., 3) [rad]

    Returns
    -------
    array, shape (..., 3) [rad], signed
    """
    a = _cycles(attained_rad, 3, "attained_rad")
    c = _commanded(commanded_rad, a, "commanded_rad")
    return _wrapped(a, c[..., None, :]).mean(axis=-2)


def orientation_repeatability(attained_rad) -> np.ndarray:
    """ISO 9283 7.2.2 orientation repeatability ``(RP_a, RP_b, RP_c) = 3 S`` of each angle (the standard writes
    ``+-3 S_a``; the half-width is returned).

    Parameters
    ----------
    attained_rad : array, shape (..., n, 3) [rad]

    Returns
    -------
    array, shape (..., 3) [rad]
    """
    a = _cycles(attained_rad, 3, "attained_rad")
    return 3.0 * _wrapped(a, a[..., :1, :]).std(axis=-2, ddof=1)


def barycentre_distances(attained_mm) -> np.ndarray:
    """Distances between the barycentres of the three approach directions, per pair of :data:`PAIRS`.

    Parameters
    ----------
    attained_mm : array, shape (..., 3, n, 3) [mm]
        Attained positions: per direction, cycle by cycle.

    Returns
    -------
    array, shape (..., 3) [mm]
    """
    return np.linalg.norm(_pair_differences(attained_mm, "attained_mm"), axis=-1)


def _pair_differences(x, name: str) -> np.ndarray:
    """Barycentre of one direction's cycles minus another's, per pair of :data:`PAIRS`: (..., 3, n, 3) ->
    (..., 3 pairs, 3)."""
    a = _cycles(x, 3, name)
    if a.ndim < 3 or a.shape[-3] != 3:
        raise TolallocError(f"{name}: expected the cycles of three approach directions, shape (..., 3, n, 3), "
                            f"got shape {a.shape}.")
    b = a.mean(axis=-2)
    return np.stack([b[..., h, :] - b[..., k, :] for h, k in PAIRS], axis=-2)


def multidirectional_accuracy(attained_mm) -> np.ndarray:
    """ISO 9283 7.2.3 multi-directional pose accuracy variation ``vAP_P``: the largest distance between the
    barycentres of the cycles approached from each of three directions.

    Parameters
    ----------
    attained_mm : array, shape (..., 3, n, 3) [mm]

    Returns
    -------
    array, shape (...) [mm]
    """
    return barycentre_distances(attained_mm).max(axis=-1)


def angle_differences(attained_rad) -> np.ndarray:
    """Absolute differences between the mean angles ``a, b, c`` of the three approach directions, per pair of
    :data:`PAIRS`.

    Parameters
    ----------
    attained_rad : array, shape (..., 3, n, 3) [rad]
        Attained angles: per direction, cycle by cycle.

    Returns
    -------
    array, shape (..., 3 pairs, 3 angles) [rad]
    """
    a = _cycles(attained_rad, 3, "attained_rad")
    return np.abs(_pair_differences(_wrapped(a, a[..., :1, :1, :]), "attained_rad"))


def multidirectional_orientation(attained_rad) -> np.ndarray:
    """ISO 9283 7.2.3 ``vAP_a, vAP_b, vAP_c``: per angle, the largest difference between the mean angles of the three
    approach directions.

    Parameters
    ----------
    attained_rad : array, shape (..., 3, n, 3) [rad]

    Returns
    -------
    array, shape (..., 3) [rad]
    """
    return angle_differences(attained_rad).max(axis=-2)


def _distances(p1, p2):
    a1 = _cycles(p1, 3, "attained_1_mm")
    a2 = _cycles(p2, 3, "attained_2_mm")
    if a1.shape != a2.shape:
        raise TolallocError(f"attained_1_mm, attained_2_mm: expected the same cycles at both poses, got shapes "
                            f"{a1.shape} and {a2.shape}.")
    return np.linalg.norm(a1 - a2, axis=-1)


def distance_accuracy(attained_1_mm, attained_2_mm, commanded_1_mm, commanded_2_mm) -> np.ndarray:
    """ISO 9283 7.3 distance accuracy ``AD_P = Db - D_c`` between two poses (signed).

    Parameters
    ----------
    attained_1_mm, attained_2_mm : array, shape (..., n, 3) [mm]
        Attained positions at the two poses, cycle by cycle.
    commanded_1_mm, commanded_2_mm : array, shape (..., 3) [mm]

    Returns
    -------
    array, shape (...) [mm]
    """
    d = _distances(attained_1_mm, attained_2_mm)
    a1 = _cycles(attained_1_mm, 3, "attained_1_mm")
    dc = np.linalg.norm(_commanded(commanded_1_mm, a1, "commanded_1_mm") - _commanded(commanded_2_mm, a1,
                                                                                      "commanded_2_mm"), axis=-1)
    return d.mean(axis=-1) - dc


def distance_repeatability(attained_1_mm, attained_2_mm) -> np.ndarray:
    """ISO 9283 7.3 distance repeatability ``RD = 3 S_D`` (the standard writes ``+-3 S_D``).

    Returns
    -------
    array, shape (...) [mm]
    """
    return 3.0 * _distances(attained_1_mm, attained_2_mm).std(axis=-1, ddof=1)


def _path(attained, commanded):
    a = np.asarray(attained, dtype=float)
    c = np.asarray(commanded, dtype=float)
    if a.ndim != 3 or a.shape[-1] != 3 or c.shape != a.shape[1:]:
        raise TolallocError(f"attained_mm, commanded_mm: expected the attained path points of n cycles as shape "
                            f"(n, m, 3) and the m command points as (m, 3), got {a.shape} and {c.shape}.")
    return _cycles(np.swapaxes(a, 0, 1), 3, "attained_mm"), c  # (m, n, 3)


def path_accuracy(attained_mm, commanded_mm) -> float:
    """ISO 9283 8.2 path accuracy ``AT_P = max_i |barycentre_i - P_ci|`` over the command points.

    Parameters
    ----------
    attained_mm : array, shape (n, m, 3) [mm]
        Attained path points of ``n`` cycles at the ``m`` command points (each where the attained path crosses
        the plane normal to the command path at that point).
    commanded_mm : array, shape (m, 3) [mm]

    Returns
    -------
    float [mm]
    """
    a, c = _path(attained_mm, commanded_mm)
    return float(pose_accuracy(a, c).max())


def path_repeatability(attained_mm) -> float:
    """ISO 9283 8.3 path repeatability ``RT_P = max_i (lb_i + 3 S_li)``; ``attained_mm`` as :func:`path_accuracy`."""
    a = np.asarray(attained_mm, dtype=float)
    a, _ = _path(a, np.zeros(a.shape[1:]) if a.ndim == 3 else a)
    return float(pose_repeatability(a).max())
