"""The linear model of the ISO 9283 statistics: systematic and random parts, each with its own map.

Every error of the tool pose at a pose ``m`` of the test is, to first order, ``J_m e`` plus the effects of bought
parts: ``e`` the error parameters, each split (:mod:`tolalloc.calibration.split`) into a **systematic** part, fixed
for a built robot (its manufacturing error, after an optional calibration), and a **random** part, new at every
move (clearance, encoder and transmission repeatability). A statistic's *vector* ``x_i`` (per test pose or path
point ``i``) is a linear map of the errors at the *evaluation poses* ``m`` (the test poses, the registration
poses, the path points)::

    x_i = sum_m L_im (J_m s + s_m^eff)  +  sum over cycles of sum_m L_im (J_m r + r_m^eff + eps_m) / (its count)

so that, with ``S`` the covariance of the systematic parts (diagonal, or the posterior of a calibration) and ``V``
the variances of the random parts, its covariance over the built robots is::

    C_i = L_i (J S J^T + E_sys) L_i^T  +  sum_m W_im L_im (J_m V J_m^T + E_rand,m + T_m) L_im^T

``W_im`` the weight of pose ``m``'s independent random draw in ``x_i`` (``1/n`` for the mean of ``n`` cycles, ``1``
for one cycle), ``E`` the bought-part effects (:class:`ErrorEffects`, the seam where they enter: systematic
covariance joint over the evaluation poses, random covariance per pose) and ``T_m`` the tracker's (only in the
*measured* statistic).

* ``AP_P`` (ISO 9283 7.2.1), measure *ball*: the barycentre minus the command position, registered; random
  weight ``1/n``;
* ``AP_a, AP_b, AP_c`` (7.2.1), *ball* (one row each): the mean angle minus the command angle, registered; ``1/n``;
* ``RP_l`` (7.2.2), *rp*: the attained position of one cycle; weight 1;
* ``RP_a, RP_b, RP_c`` (7.2.2), *sd3* (one row each): the attained angle of one cycle; weight 1;
* ``vAP_P`` (7.2.3), *ball* (one row per pose and pair of approach directions): the barycentre from one direction
  minus that from another, each pose evaluated once per direction (the approach known, :attr:`EvaluationPoses.
  approach`); ``1/n`` each. Whatever a robot keeps at the pose cancels (``L J = 0``); the flank lost motion rests
  on, which the direction sets, and the random parts remain. The largest of a pose's three pairs is ``vAP_P``:
  each pair is held at ``1 - (1 - share) / 3`` (Bonferroni, as the path points); ``vAP_a, vAP_b, vAP_c``
  likewise per angle (one row each), from the mean rotations;
* ``AD_P`` (7.3), *ball* (one row): ``u . (Pb - Pa)`` of the mean positions, ``u`` the command direction; ``1/n``;
* ``AT_P`` (8.2), *ball*: the barycentre minus the command point across the path, registered; ``1/n`` (path
  cycles).

*ball*: the statistic is ``|x_i|`` (``P(|x| < r)``, :mod:`tolalloc.linear.probability`); *rp* and *sd3*: the
repeatability of ``n`` cycles of that per-cycle covariance (:mod:`tolalloc.linear.repeatability`). Repeatabilities
and distances do not depend on the registration (a rigid motion of every measured point).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from tolalloc.exceptions import TolallocError
from tolalloc.acceptance.evaluation import EvaluationPoses, evaluation_poses, requirement_poses
from tolalloc.acceptance.instrument import registration_map, _skew
from tolalloc.acceptance.requirements import IsoRequirement
from tolalloc.acceptance.statistics import PAIRS
from tolalloc.linear.repeatability import RP_LAW_MIN_CYCLES

__all__ = ["StatisticModel", "ErrorEffects", "EffectCovariance", "EvaluationPoses", "evaluation_poses",
           "statistic_models", "design_variances", "effects_at", "requirement_poses",
           "multidirectional_labels", "MEASURES", "ANGLES"]

MEASURES = ("ball", "rp", "sd3")
ANGLES = ("a", "b", "c")


@dataclass(frozen=True, eq=False)
class EffectCovariance:
    """Covariance of bought-part effects on the tool pose error at the evaluation poses.

    Attributes
    ----------
    systematic : array, shape (M * 6, M * 6)
        Joint covariance over the poses of the part each built robot keeps (compliance under the test load, thermal
        offset ...); rows per pose: position [mm], rotation [rad].
    random : array, shape (M, 6, 6)
        Covariance per pose of the part new at every move (a gear's repeatability, encoder noise, drift within the
        test), independent between moves.
    mean : array, shape (M * 6,), optional
        The part every built robot shares at the poses (the wind-up under the test load, the sag of the links, the
        thermal growth at the test's temperature); ``None``: zero.
    """

    systematic: np.ndarray
    random: np.ndarray
    mean: np.ndarray | None = None


class ErrorEffects(Protocol):
    """The seam for bought-part effects: ``effects(robot, q, conditions) -> EffectCovariance or None``.

    ``q`` (M, n) [rad, mm] are the evaluation poses, ``conditions`` the requirement's
    :class:`~tolalloc.acceptance.requirements.Conditions` (load, velocity). ``None``: no effect beyond the error
    model (the default). Where the test knows how poses are approached (a multi-directional accuracy), it passes
    ``approach=`` (M, n): each joint's direction of motion into the pose (+1 / -1, 0 unknown); an effect that
    depends on it (lost motion) takes that keyword.
    """

    def __call__(self, robot, q: np.ndarray, conditions, **approach) -> EffectCovariance | None: ...


def effects_at(effects, robot, ev: EvaluationPoses, conditions) -> EffectCovariance | None:
    """``effects`` at the evaluation poses ``ev`` (with ``approach=`` where some poses' approach is known)."""
    if effects is None:
        return None
    if ev.approach is None or not np.any(ev.approach):
        return effects(robot, ev.q, conditions)
    if not _takes_approach(effects):
        raise TolallocError("effects: a multi-directional accuracy needs the bought-part effects with the approach "
                            "directions (effects(robot, q, conditions, approach=...)); this effects callable does "
                            "not take the keyword. Use tolalloc.acceptance.parts_effects(), or add it.")
    return effects(robot, ev.q, conditions, approach=ev.approach)


def _takes_approach(fn) -> bool:
    """Whether ``fn`` accepts the keyword ``approach`` (a callable whose signature cannot be read is trusted)."""
    import inspect

    try:
        params = inspect.signature(fn).parameters.values()
    except (TypeError, ValueError):
        return True
    return any(p.name == "approach" or p.kind is p.VAR_KEYWORD for p in params)


@dataclass(frozen=True, eq=False)
class StatisticModel:
    """The linear model of one statistic at its rows (test poses or path points).

    Attributes
    ----------
    name : str
        ``AP_P``, ``AP_a`` ..., ``RP_l``, ``RP_a`` ..., ``AD_P``, ``AT_P``.
    requirement : IsoRequirement
    measure : {"ball", "rp", "sd3"}
    cycles : int
        Cycles of the test (the ``n`` of a repeatability).
    limit : float
        The requirement's limit [mm or rad].
    target : array, shape (P,)
        Probability each row must reach: the requirement's share (path accuracy: ``1 - (1 - share) / P`` per
        point, so that the largest over the points, ``AT_P``, meets the limit with the share).
    labels : tuple of str
        ``P1`` ... or ``path point 1`` ...
    L : array, shape (P, 3, M, 6)
        Map from the pose errors at the evaluation poses to the statistic's vector (a scalar statistic in row 0).
    W : array, shape (P, M)
        Weight of each pose's independent random draw (module docstring).
    unit : {"mm", "deg"}
        Unit shown to users.
    systematic : bool
        Whether the systematic parts enter the statistic (accuracies); a repeatability sees the scatter of the cycles
        about their barycentre only, in which every part a robot keeps cancels.
    """

    name: str
    requirement: IsoRequirement
    measure: str
    cycles: int
    limit: float
    target: np.ndarray
    labels: tuple
    L: np.ndarray
    W: np.ndarray
    unit: str = "mm"
    systematic: bool = True

    @property
    def n_rows(self) -> int:
        return self.L.shape[0]

    def systematic_map(self, J: np.ndarray) -> np.ndarray:
        """``G = L J``, shape (P, 3, K): systematic parameters -> statistic vector; ``J`` (M, 6, K) (zero for a
        repeatability)."""
        G = np.einsum("pams,msk->pak", self.L, J)
        return G if self.systematic else np.zeros_like(G)

    def random_units(self, J: np.ndarray) -> np.ndarray:
        """Covariance of the statistic vector per unit variance of each parameter's random part, (P, K, 3, 3)."""
        LJ = np.einsum("pams,msk->pmak", self.L, J)  # (P, M, 3, K)
        return np.einsum("pm,pmak,pmbk->pkab", self.W, LJ, LJ)

    def pose_covariance(self, cov6: np.ndarray) -> np.ndarray:
        """Contribution of per-pose independent covariances ``cov6`` (M, 6, 6) [mm^2, rad^2], shape (P, 3, 3)."""
        return np.einsum("pm,pams,mst,pbmt->pab", self.W, self.L, cov6, self.L)

    def joint_covariance(self, cov: np.ndarray) -> np.ndarray:
        """Contribution of a systematic covariance joint over the evaluation poses ``cov`` (M*6, M*6), shape
        (P, 3, 3) (zero for a repeatability)."""
        Lf = self.L.reshape(self.n_rows, 3, -1)
        return np.einsum("pai,ij,pbj->pab", Lf, cov, Lf) * float(self.systematic)

    def effect_mean(self, effects: EffectCovariance | None) -> np.ndarray | None:
        """The statistic vector's mean over the built robots from the effects' mean, shape (P, 3) (``None`` without
        one, and for a repeatability: the cycles' scatter about their barycentre does not see it)."""
        if effects is None or effects.mean is None or not self.systematic:
            return None
        return np.einsum("pai,i->pa", self.L.reshape(self.n_rows, 3, -1), effects.mean)

    def covariance(self, J, sys_cov, rand_var, *, effects: EffectCovariance | None = None, tracker=None):
        """The statistic vector's covariance over the built robots, shape (P, 3, 3).

        Parameters
        ----------
        J : array, shape (M, 6, K)
            Error Jacobian at the evaluation poses.
        sys_cov : array, shape (K,) or (K, K)
            Variances (or covariance) of the systematic parts [mm^2, rad^2].
        rand_var : array, shape (K,)
            Variances of the random parts.
        effects : EffectCovariance, optional
        tracker : Tracker, optional
            Adds the instrument (the *measured* statistic).
        """
        G = self.systematic_map(J)
        S = np.asarray(sys_cov, float)
        C = np.einsum("pak,k,pbk->pab", G, S, G) if S.ndim == 1 else np.einsum("pak,kl,pbl->pab", G, S, G)
        C = C + np.einsum("pkab,k->pab", self.random_units(J), np.asarray(rand_var, float))
        if effects is not None:
            C = C + self.joint_covariance(effects.systematic) + self.pose_covariance(effects.random)
        if tracker is not None:
            C = C + self.instrument_covariance(tracker)
        return C

    def instrument_covariance(self, tracker) -> np.ndarray:
        """The tracker's contribution to the statistic vector's covariance, shape (P, 3, 3)."""
        M = self.L.shape[2]
        return self.pose_covariance(np.broadcast_to(tracker.covariance(), (M, 6, 6)))


def design_variances(split, posterior=None) -> tuple[np.ndarray, np.ndarray]:
    """``(systematic variances (K,) or posterior covariance (K, K), random variances (K,))`` of a design's split
    (:class:`~tolalloc.calibration.split.ErrorSplit`), or after a calibration (its
    :class:`~tolalloc.calibration.posterior.Posterior`)."""
    if posterior is not None:
        return posterior.cov_sys, posterior.random_var
    return split.prior_var_of(np.arange(len(split.model.params))), split.random_variance()


def _registered(ev: EvaluationPoses, rows_idx, visits: int, n: int, project=None, rotation: bool = False):
    """L and W of the registered barycentre (position, or rotation with ``rotation``) at evaluation rows
    ``rows_idx``."""
    M, P = len(ev.q), len(rows_idx)
    L = np.zeros((P, 3, M, 6))
    W = np.zeros((P, M))
    reg = ev.registration
    H = registration_map(ev.points_mm[reg]) if len(reg) else np.zeros((6, 0))
    for i, m in enumerate(rows_idx):
        if rotation:
            L[i, :, m, 3:] = np.eye(3)
            B = np.hstack([np.eye(3), np.zeros((3, 3))])  # the registration's rotation theta
        else:
            L[i, :, m, :3] = np.eye(3)
            B = np.hstack([-_skew(ev.points_mm[m]), np.eye(3)])  # delta + theta x p
        for r_i, r in enumerate(reg):
            L[i, :, r, :3] -= B @ H[:, 3 * r_i:3 * r_i + 3]
        W[i, m] = 1.0 / n
        W[i, reg] = 1.0 / visits
        if project is not None:
            L[i] = np.einsum("ab,bms->ams", project[i], L[i])
    return L, W


def _one_row(L, axis: int):
    """Keep row ``axis`` of L (P, 3, M, 6), moved to row 0 (a scalar statistic)."""
    out = np.zeros_like(L)
    out[:, 0] = L[:, axis]
    return out


def statistic_models(requirements, test, ev: EvaluationPoses | None = None) -> list[StatisticModel]:
    """The statistic models of ISO 9283 requirements in a test (one per statistic and angle).

    Parameters
    ----------
    requirements : sequence of IsoRequirement
    test : AcceptanceTest
    ev : EvaluationPoses, optional
        Default :func:`evaluation_poses` of the test (with the path of a path accuracy requirement).
    """
    reqs = list(requirements)
    if ev is None:
        ev = requirement_poses(test, reqs)
    n, visits = test.cycles, test.registration_visits
    nt = len(ev.test)
    P1_5 = tuple(f"P{i}" for i in range(1, nt + 1))
    out = []
    for req in reqs:
        if not isinstance(req, IsoRequirement):
            raise TolallocError(f"requirements: expected ISO 9283 requirements, got {req!r}.")
        tgt = np.full(nt, req.share)
        k = req.kind
        if k == "pose_accuracy":
            L, W = _registered(ev, ev.test, visits, n)
            out.append(StatisticModel("AP_P", req, "ball", n, req.limit, tgt, P1_5, L, W))
        elif k == "orientation_accuracy":
            L, W = _registered(ev, ev.test, visits, n, rotation=True)
            out += [StatisticModel(f"AP_{a}", req, "ball", n, req.limit, tgt, P1_5, _one_row(L, j), W, "deg")
                    for j, a in enumerate(ANGLES)]
        elif k in ("pose_repeatability", "orientation_repeatability"):
            M = len(ev.q)
            L, W = np.zeros((nt, 3, M, 6)), np.zeros((nt, M))
            off = 0 if k == "pose_repeatability" else 3
            for i, m in enumerate(ev.test):
                L[i, :, m, off:off + 3] = np.eye(3)
                W[i, m] = 1.0
            if k == "pose_repeatability":
                if n < RP_LAW_MIN_CYCLES:
                    raise TolallocError(f"cycles: RP_l is predicted for tests of at least {RP_LAW_MIN_CYCLES} "
                                        f"cycles (its law's range; ISO 9283 uses 30), the test has {n}; lay the test "
                                        f"out with cycles >= {RP_LAW_MIN_CYCLES}.")
                out.append(StatisticModel("RP_l", req, "rp", n, req.limit, tgt, P1_5, L, W, systematic=False))
            else:
                out += [StatisticModel(f"RP_{a}", req, "sd3", n, req.limit, tgt, P1_5, _one_row(L, j), W, "deg",
                                       systematic=False) for j, a in enumerate(ANGLES)]
        elif k == "multidirectional_accuracy":
            L, W = _multidirectional_map(req, ev, n)
            out.append(StatisticModel("vAP_P", req, "ball", n, req.limit, _pair_target(req),
                                      multidirectional_labels(req), L, W))
        elif k == "multidirectional_orientation":
            L, W = _multidirectional_map(req, ev, n, rotation=True)
            out += [StatisticModel(f"vAP_{a}", req, "ball", n, req.limit, _pair_target(req),
                                   multidirectional_labels(req), _one_row(L, j), W, "deg")
                    for j, a in enumerate(ANGLES)]
        elif k == "distance_accuracy":
            out.append(_distance_model(req, ev, n))
        elif k == "path_accuracy":
            m = len(ev.path)
            proj = np.eye(3)[None] - np.einsum("pa,pb->pab", ev.tangents, ev.tangents)
            L, W = _registered(ev, ev.path, visits, test.path_cycles, project=proj)
            out.append(StatisticModel("AT_P", req, "ball", test.path_cycles, req.limit,
                                      np.full(m, 1 - (1 - req.share) / m),
                                      tuple(f"path point {i + 1}" for i in range(m)), L, W))
        else:  # pragma: no cover - every IsoRequirement kind is handled above
            raise TolallocError(f"requirements: no statistic model for kind {k!r}.")
    return out


def _multidirectional_map(req, ev: EvaluationPoses, n: int, rotation: bool = False):
    """L and W of a multi-directional statistic: per pose and pair of directions, the barycentre (position, or mean
    rotation with ``rotation``) of one direction's cycles minus the other's."""
    if len(ev.directional) != len(req.poses):
        raise TolallocError(f"{req.kind}: the evaluation poses lack its directional visits; build them with "
                            "evaluation_poses(test, multidirectional=requirement).")
    M, off = len(ev.q), 3 if rotation else 0
    rows = len(req.poses) * len(PAIRS)
    L, W = np.zeros((rows, 3, M, 6)), np.zeros((rows, M))
    for v, visits in enumerate(ev.directional):
        for k, (a, b) in enumerate(PAIRS):
            i = v * len(PAIRS) + k
            L[i, :, visits[a], off:off + 3], L[i, :, visits[b], off:off + 3] = np.eye(3), -np.eye(3)
            W[i, visits[[a, b]]] = 1.0 / n
    return L, W


def _pair_target(req) -> np.ndarray:
    """Each pair of directions at ``1 - (1 - share) / 3``: the largest of a pose's pairs then meets the share."""
    return np.full(len(req.poses) * len(PAIRS), 1 - (1 - req.share) / len(PAIRS))


def multidirectional_labels(req) -> tuple:
    """Row labels of ``vAP_P``: pose and pair of approach directions (``P1 -x/-y``), pose by pose."""
    return tuple(f"P{pose} {req.approach[a]}/{req.approach[b]}" for pose in req.poses for a, b in PAIRS)


def _distance_model(req, ev: EvaluationPoses, n: int) -> StatisticModel:
    """``AD_P``: the mean attained distance minus the command distance, ``u . (mean P_b - mean P_a)``."""
    if max(req.poses) > len(ev.test):
        raise TolallocError(f"{req.kind}: poses {list(req.poses)} but the test has {len(ev.test)} test poses; name "
                            f"poses 1-{len(ev.test)}.")
    a, b = (ev.test[i - 1] for i in req.poses)
    u = ev.points_mm[b] - ev.points_mm[a]
    if not np.linalg.norm(u) > 1e-9:
        raise TolallocError(f"{req.kind}: the command positions of P{req.poses[0]} and P{req.poses[1]} coincide, "
                            "so the distance between them has no direction; name two distinct test poses.")
    u = u / np.linalg.norm(u)
    M = len(ev.q)
    L, W = np.zeros((1, 3, M, 6)), np.zeros((1, M))
    L[0, 0, b, :3], L[0, 0, a, :3] = u, -u
    W[0, [a, b]] = 1.0 / n
    lab = (f"P{req.poses[0]}-P{req.poses[1]}",)
    return StatisticModel("AD_P", req, "ball", n, req.limit, np.array([req.share]), lab, L, W)
