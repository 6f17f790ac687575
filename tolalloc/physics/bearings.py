"""Bearing runout: a joint's two bearings turn its body about an axis that wobbles with their radial runout.

A rotating inner ring whose raceway runs out by ``Kia`` (ISO 492: the full indicator reading) carries its shaft
``eps = Kia / 2`` off the housing's axis, in a direction fixed *in the turning body* (its phase ``phi``). With two
bearings ``span`` apart (independent phases), the body -- in its own frame, so the error is a constant of the built
robot, not a function of the joint angle -- is displaced at the joint point by the mean of the two eccentricities
and tilted by their difference over the span::

    t = (e1 + e2) / 2                    e_b = eps (cos phi_b, sin phi_b)  in the plane normal to the axis
    w = R90 (e2 - e1) / span             (rotation about the normal-plane axes)

Over uniform phases each of the four components ``(t_a, t_b, w_a, w_b)`` (``a``, ``b`` the two axes normal to the
joint axis) has mean zero, standard deviation ``eps / 2`` (translation) and ``eps / span`` (tilt), and they are
uncorrelated (:func:`runout_sd`); :func:`runout_values` is the exact draw. The error model inserts them after the
joint (in the body's frame): :mod:`tolalloc.errormodel.parts`.
"""

from __future__ import annotations

import numpy as np

from tolalloc.robot.components import Bearing

__all__ = ["budgets_runout", "runout_sd", "runout_values"]


def budgets_runout(bearing: Bearing) -> bool:
    """Whether ``bearing``'s runout is part of the errors: it gives one, an ISO 492 class, or no tilt stiffness (in
    the last two cases a missing runout is asked for). A table with a tilt stiffness and neither a runout nor a class
    describes the pair's stiffness only."""
    return bearing.radial_runout is not None or bool(bearing.precision_class) or not bearing.tilt_stiffness


def _check(bearing: Bearing) -> tuple:
    if bearing.radial_runout is None or bearing.span_mm is None:
        raise ValueError("the bearing needs radial_runout and span_mm (a catalogue class at a bore, and the span)")
    return bearing.radial_runout / 2.0, bearing.span_mm


def runout_sd(bearing: Bearing) -> np.ndarray:
    """Standard deviations of ``(t_a, t_b, w_a, w_b)`` over the phases, shape (4,) [mm, mm, rad, rad]."""
    eps, span = _check(bearing)
    return np.array([eps / 2.0, eps / 2.0, eps / span, eps / span])


def runout_values(bearing: Bearing, phases: np.ndarray) -> np.ndarray:
    """The body's displacement ``(t_a, t_b, w_a, w_b)`` for the bearings' phases ``phases`` (N, 2) [rad], shape (N, 4)
    [mm, mm, rad, rad] (module docstring)."""
    eps, span = _check(bearing)
    ph = np.asarray(phases, float)
    e1 = eps * np.stack([np.cos(ph[:, 0]), np.sin(ph[:, 0])], axis=1)
    e2 = eps * np.stack([np.cos(ph[:, 1]), np.sin(ph[:, 1])], axis=1)
    t = (e1 + e2) / 2.0
    d = (e2 - e1) / span
    return np.concatenate([t, np.stack([-d[:, 1], d[:, 0]], axis=1)], axis=1)
