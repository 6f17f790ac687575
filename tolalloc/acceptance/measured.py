"""ISO 9283 statistics from measurements: where a data set repeats a commanded pose, its pose accuracy and
repeatability as the standard computes them, beside a design's prediction.

A laser-tracker file (:mod:`tolalloc.diagnose.measurements`) holds target positions in the tracker's frame. Rows
with the same joint values (:meth:`Measurements.pose_groups`) are the cycles of one command pose; a group needs at
least two. For ``AP_P`` the command positions must be expressed where the attained ones are: the tracker frame
and the target offset on the flange are fitted (:func:`tolalloc.diagnose.calibrate.fit_model`, nominal kinematics,
no geometric parameter) on the *other* rows -- those of poses measured once -- as ISO 9283 6.4 asks (the transform
established at poses other than the test poses). A file that repeats every pose has no other rows: the frame is
then fitted on the groups' barycentres themselves, which absorbs the rigid-body part of the robot's errors (said in
:attr:`MeasuredAcceptance.note`). ``RP_l`` does not depend on the frame.

Where the file logs the approach directions (``dir1..dirN``) and a pose was approached in more than one way, each
way at least twice, the pose's multi-directional accuracy variation ``vAP_P`` (ISO 9283 7.2.3) is the largest
distance between the barycentres of its approach groups (the joints' directions, which set the flanks the gears
rest on; the standard's three Cartesian approaches are one instance), and ``AP_P`` and ``RP_l`` use the cycles of the
pose's first approach only (the standard's same-direction cycles).

Only positions are read (the measurement format has no orientation), so only ``AP_P``, ``RP_l`` and ``vAP_P`` are
computed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError, check_vector
from tolalloc.acceptance.statistics import MIN_CYCLES, pose_accuracy, pose_repeatability

__all__ = ["MeasuredAcceptance", "measured_acceptance", "compare_with_prediction", "MIN_REGISTRATION_POSES"]

#: distinct once-measured poses needed to fit the frame on them (else the groups' barycentres are used)
MIN_REGISTRATION_POSES = 6


@dataclass(frozen=True, eq=False)
class MeasuredAcceptance:
    """``AP_P`` and ``RP_l`` of the repeated poses of a measurement set.

    Attributes
    ----------
    q : array, shape (G, n) [rad, mm]
        The repeated command poses.
    cycles : array of int, shape (G,)
        Cycles ``AP_P`` and ``RP_l`` use (those of the pose's first approach).
    ap_mm, rp_mm : arrays, shape (G,)
    rows : tuple of arrays
        File rows of each pose's cycles.
    registration_rows : array of int
        File rows the frame was fitted on.
    rms_registration_mm : float
        RMS residual of that fit.
    note : str
    robot : Robot
    vap_mm : array, shape (G,)
        ``vAP_P`` of each pose, NaN where it was approached one way only.
    approaches : array of int, shape (G,)
        Approach groups of each pose with at least two cycles.
    """

    q: np.ndarray
    cycles: np.ndarray
    ap_mm: np.ndarray
    rp_mm: np.ndarray
    rows: tuple
    registration_rows: np.ndarray
    rms_registration_mm: float
    note: str
    robot: object
    vap_mm: np.ndarray = None
    approaches: np.ndarray = None

    def to_frame(self) -> pd.DataFrame:
        """One row per repeated pose: ``pose``, ``cycles``, ``AP_P_mm``, ``RP_l_mm``, ``approaches``, ``vAP_P_mm``
        (NaN for a pose approached one way), ``q<k>_deg`` / ``q<k>_mm``."""
        df = pd.DataFrame({"pose": np.arange(1, len(self.q) + 1), "cycles": self.cycles, "AP_P_mm": self.ap_mm,
                           "RP_l_mm": self.rp_mm, "approaches": self.approaches, "vAP_P_mm": self.vap_mm})
        qi = self.robot.q_to_interface(self.q)
        for j, jt in enumerate(self.robot.joints):
            df[f"q{j + 1}_{'deg' if jt.is_revolute else 'mm'}"] = qi[:, j]
        return df


def measured_acceptance(meas, robot, *, target_offset_mm=None) -> MeasuredAcceptance:
    """``AP_P`` and ``RP_l`` (ISO 9283 7.2.1, 7.2.2) of every pose a measurement set repeats (module docstring).

    Parameters
    ----------
    meas : Measurements
    robot : Robot
    target_offset_mm : array, shape (3,), optional
        The target's offset in the flange frame [mm] when it is known (calibrated): only the frame's rotation and
        translation are fitted then (Kabsch); default: fitted with them.

    Raises
    ------
    TolallocError
        No pose is measured at least twice.
    """
    from dataclasses import replace

    from tolalloc.diagnose.calibrate import fit_model, initial_fit, kabsch
    from tolalloc.errormodel import build_error_model

    groups = meas.pose_groups()
    counts = np.bincount(groups)
    rep = np.flatnonzero(counts >= MIN_CYCLES)
    if not len(rep):
        raise TolallocError(f"measurements {meas.source}: no command pose is measured at least {MIN_CYCLES} times "
                            f"({meas.n_poses} rows, {len(counts)} distinct poses, each once); the pose accuracy and "
                            f"repeatability of ISO 9283 need {MIN_CYCLES} or more attained positions of one command "
                            "pose (the standard uses 30 cycles) -- measure the test poses repeatedly, with the same "
                            "joint values.")
    once = np.flatnonzero(counts[groups] == 1)
    if len(once) >= MIN_REGISTRATION_POSES:
        q_reg, x_reg, reg_rows = meas.q[once], meas.xyz_mm[once], meas.rows[once] if len(meas.rows) else once + 1
        note = f"frame fitted on the {len(once)} poses measured once (not the test poses, ISO 9283 6.4)"
    else:
        q_reg = np.stack([meas.q[groups == g][0] for g in range(len(counts))])
        x_reg = np.stack([meas.xyz_mm[groups == g].mean(axis=0) for g in range(len(counts))])
        reg_rows = np.arange(1, meas.n_poses + 1) if not len(meas.rows) else meas.rows
        note = (f"frame fitted on the barycentres of the {len(counts)} poses themselves (fewer than "
                f"{MIN_REGISTRATION_POSES} poses measured once): the rigid-body part of the robot's errors is "
                "absorbed, so AP_P is smaller than a test registered elsewhere would find (ISO 9283 6.4)")
    if len(q_reg) < 3:
        raise TolallocError(f"measurements {meas.source}: {len(q_reg)} distinct poses cannot fix the tracker frame "
                            "and the target offset; measure at least 3 (ISO 9283 6.4: other poses than the test "
                            "poses).")
    model = build_error_model(robot, exclude=())
    if target_offset_mm is None:
        fit = fit_model(initial_fit(model, q_reg, x_reg), q_reg, x_reg, geo_index=np.zeros(0, int), prior=False,
                        robust=False)
    else:
        t = check_vector(target_offset_mm, "target_offset_mm", 3)
        fit0 = replace(initial_fit(model, q_reg, x_reg), t_mm=t)
        R, p = kabsch(fit0.base_points(q_reg), x_reg)
        fit = replace(fit0, R=R, p_mm=p)
        fit = replace(fit, residual_mm=x_reg - fit.predict(q_reg))
    ap, rp, rows, qs, vap, ways, n = [], [], [], [], [], [], []
    for g in rep:
        idx = np.flatnonzero(groups == g)
        base = (meas.xyz_mm[idx] - fit.p_mm) @ fit.R  # tracker -> base frame
        cmd = fit.base_points(meas.q[idx[:1]])[0]
        bary, first = _approach_groups(meas.direction, idx, base)
        ap.append(float(pose_accuracy(base[first], cmd)))
        rp.append(float(pose_repeatability(base[first])))
        vap.append(max((float(np.linalg.norm(a - b)) for i, a in enumerate(bary) for b in bary[i + 1:]),
                       default=np.nan))
        ways.append(len(bary))
        n.append(int(first.sum()))
        rows.append(meas.rows[idx] if len(meas.rows) else idx + 1)
        qs.append(meas.q[idx[0]])
    if any(w > 1 for w in ways):
        note += ("; poses approached in more than one way: AP_P and RP_l from the cycles of each pose's first "
                 "approach, vAP_P between the approaches' barycentres (ISO 9283 7.2.1-7.2.3)")
    return MeasuredAcceptance(np.array(qs), np.array(n), np.array(ap), np.array(rp), tuple(rows),
                              np.asarray(reg_rows), fit.rms_mm, note, robot, np.array(vap), np.array(ways))


def _approach_groups(direction, idx, base) -> tuple:
    """The barycentres (base frame) of one pose's approach groups with at least two cycles -- rows of ``idx`` with
    the same joint directions, in order of first appearance (one group without direction columns) -- and the mask
    of the first group's rows in ``idx``."""
    if direction is None:
        return [base.mean(axis=0)], np.ones(len(idx), bool)
    _, first_at, inverse = np.unique(direction[idx], axis=0, return_index=True, return_inverse=True)
    inverse = np.ravel(inverse)
    kept = [k for k in np.argsort(first_at) if np.sum(inverse == k) >= MIN_CYCLES]
    if not kept:                      # every approach once: the pose's cycles together, as without the columns
        return [base.mean(axis=0)], np.ones(len(idx), bool)
    return [base[inverse == k].mean(axis=0) for k in kept], inverse == kept[0]


def compare_with_prediction(measured: MeasuredAcceptance, prediction) -> pd.DataFrame:
    """The measured statistics beside a design's prediction at the same poses (a
    :func:`tolalloc.acceptance.predict.predict_acceptance` of a :func:`tolalloc.acceptance.layout.acceptance_test_at`
    test): per pose and statistic the measured value, the predicted measured median and value at the share, and the
    share of the design's robots whose test reports no more than the measured value (where the measured robot sits
    in the design's fleet)."""
    from tolalloc.acceptance.measures import measure_cdf

    rows = []
    for s in prediction.statistics:
        if s.model.name not in ("AP_P", "RP_l"):
            continue
        vals = measured.ap_mm if s.model.name == "AP_P" else measured.rp_mm
        if len(vals) != s.model.n_rows:
            raise TolallocError(f"prediction: expected a prediction at the {len(vals)} measured poses, got "
                                f"{s.model.n_rows} rows; predict at acceptance_test_at(robot, measured.q, ...).")
        if np.any(measured.cycles != s.model.cycles):
            raise TolallocError(f"prediction: made for {s.model.cycles} cycles per pose, but the measured poses have "
                                f"{', '.join(map(str, np.unique(measured.cycles)))}; the laws of AP_P and RP_l depend "
                                "on the count: predict at acceptance_test_at(robot, measured.q, ..., cycles=n) with "
                                "the measured count (poses measured a different number of times: one prediction each).")
        C = s.cov_robot + s.cov_instrument
        pct = measure_cdf(s.model.measure, C, vals, s.model.cycles, s.mean)
        for i, v in enumerate(vals):
            rows.append({"statistic": s.model.name, "pose": i + 1, "measured_mm": v,
                         "predicted_median_mm": s.median_measured[i], "predicted_at_share_mm": s.measured[i],
                         "share": s.model.requirement.share, "fleet_share_at_or_below": float(pct[i])})
    return pd.DataFrame(rows)
