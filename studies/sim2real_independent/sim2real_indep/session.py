"""A measurement session: poses in the order the robot visits them, their time stamps, approach directions, the
payload schedule, the air temperature and the drive activity that heats the links.

Timing follows a laser-tracker protocol: each move at a programmed fraction of the rated joint speed, then a
settle-and-measure dwell of a few seconds (a tracker's stable-probe measurement takes 2-5 s); thermal sessions
interleave measurement blocks with exercise periods (the robot runs a production-like cycle, as in thermal drift
tests such as ISO 9283 section 7.2.6 "drift of pose characteristics") and pauses (servo off, brakes on, cooling).
Imports nothing of tolalloc.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from sim2real_indep import kinematics as kin

#: Joint sampling boxes of the measured workspace [deg / mm]; poses whose target or any joint point from joint 3 on
#: lies below FLOOR_MM (base frame z) are redrawn.
BOXES = {
    "ur10": ([-170, -170, -150, -250, -160, -180], [170, -10, 150, 70, 160, 180]),
    "tool_changer": ([-60, -10, -45, 0, -90, -180], [60, 60, 30, 500, 90, 180]),
    "kr16_like": ([-90, -50, -70, -170, -115, -180], [90, 60, 60, 170, 115, 180]),
}
FLOOR_MM = {"ur10": -100.0, "tool_changer": 200.0, "kr16_like": 250.0}
RATED_SPEED_DEG_S = {"ur10": [120, 120, 180, 180, 180, 180], "tool_changer": [30, 30, 30, 100, 60, 90],
                     "kr16_like": [156, 156, 156, 330, 330, 615]}  # UR10 / KR 16 data sheets; tool_changer assumed


@dataclass(frozen=True)
class Session:
    """Poses in visiting order and everything logged or needed about them (P poses, n joints).

    q : (P, n) [rad, mm]; time_s : (P,); direction : (P, n) +-1; payload_kg : (P,); air_c : (P,) logged air
    temperature; air : the air temperature law (see :func:`air_temperature`); speed : (P, n) [rad/s or mm/s] mean
    joint speed of the move into each pose; move_s, dwell_s :
    (P,) durations of that move and of the dwell; gap_s : (P,) exercise (>0) or pause (<0) time before the pose
    [s]; exercise_speed : (n,) mean |speed| of the exercise cycle; approach : set C's approach plan (or None).
    """

    q: np.ndarray
    time_s: np.ndarray
    direction: np.ndarray
    payload_kg: np.ndarray
    air_c: np.ndarray
    speed: np.ndarray
    move_s: np.ndarray
    dwell_s: np.ndarray
    gap_s: np.ndarray
    exercise_speed: np.ndarray
    air: dict
    approach: dict | None = None  # set C: final approach travel / speed per pose and joint (P, n) [rad, rad/s]


def sample_poses(chain: kin.Chain, robot_key: str, n: int, rng) -> np.ndarray:
    """``n`` random poses (n, dof) [rad, mm] in the robot's measurement box, above its floor."""
    lo, hi = (np.array(v, float) for v in BOXES[robot_key])
    scale = np.where(chain.revolute, np.pi / 180, 1.0)
    out = []
    for _ in range(50):
        if len(out) >= n:
            break
        q = (lo + (hi - lo) * rng.random((4 * n, chain.n))) * scale
        p, _ = kin.flange(chain, q)
        _, c = kin.joint_frames(chain, q)
        ok = (p[:, 2] > FLOOR_MM[robot_key]) & (c[:, 2:, 2].min(axis=1) > FLOOR_MM[robot_key])
        out.extend(q[ok])
    if len(out) < n:
        raise RuntimeError(f"{robot_key}: too few poses above the floor in the sampling box")
    return np.array(out[:n])


def make_session(chain: kin.Chain, robot_key: str, n: int, rng, *, blocks: int = 1, gap_kind: str = "none",
                 payload_steps=(0.0,), air: dict | None = None, speed_frac=(0.2, 0.4),
                 pause_min=(10.0, 40.0)) -> Session:
    """A session of ``n`` poses in ``blocks`` measurement blocks.

    gap_kind : "none" | "exercise" | "pause" | "mixed" -- what happens between blocks (exercise 10-30 min,
    pause ``pause_min`` [min], default 10-40). payload_steps : payload masses [kg], one per equal share of the
    blocks (the payload is changed between blocks and logged). air : {"drift_K": total change, "cycle_K":
    amplitude of an HVAC cycle, "period_min": its period} -- the air temperature (logged) follows it; None: a still
    shop (+-0.05 K).
    """
    q = sample_poses(chain, robot_key, n, rng)
    scale = np.where(chain.revolute, np.pi / 180, 1.0)
    rated = np.array(RATED_SPEED_DEG_S[robot_key], float) * scale
    v = rated * rng.uniform(*speed_frac)
    dq = np.diff(np.vstack([q[:1], q]), axis=0)
    move = np.abs(dq / v).max(axis=1) + 1.0  # 0.5 s acceleration at each end
    move[0] = 0.0
    dwell = rng.uniform(3.0, 8.0, n)
    block_of = np.minimum((np.arange(n) * blocks) // n, blocks - 1)
    gap = np.zeros(n)
    starts = np.flatnonzero(np.diff(block_of)) + 1
    for s in starts:
        kind = gap_kind if gap_kind != "mixed" else rng.choice(["exercise", "pause"])
        if kind == "exercise":
            gap[s] = rng.uniform(600, 1800)
        elif kind == "pause":
            gap[s] = -60 * rng.uniform(*pause_min)
    time = np.cumsum(np.abs(gap) + move + dwell)  # measured at the end of each dwell
    direction = np.sign(dq)
    direction[0] = rng.choice([-1.0, 1.0], chain.n)
    for i in range(1, n):  # a joint that did not move keeps its last direction
        direction[i] = np.where(direction[i] == 0, direction[i - 1], direction[i])
    share = np.minimum((block_of * len(payload_steps)) // blocks, len(payload_steps) - 1)
    payload = np.asarray(payload_steps, float)[share]
    # a still shop: the air wanders by +-0.05 K over a 3 h cycle
    air = dict(air) if air else {"drift_K": 0.0, "cycle_K": 0.05, "period_min": 180.0}
    air = {"T0": rng.uniform(19.5, 22.5), "drift_K": 0.0, "cycle_K": 0.0, "period_min": 90.0,
           "phase": rng.uniform(0, 2 * np.pi)} | air
    speed = np.where(move[:, None] > 0, np.abs(dq) / np.maximum(move[:, None], 1e-9), 0.0)
    sess = Session(q=q, time_s=time, direction=direction, payload_kg=payload, air_c=np.zeros(n), speed=speed,
                   move_s=move, dwell_s=dwell, gap_s=gap, exercise_speed=rated * rng.uniform(0.3, 0.6, chain.n),
                   air=air)
    # the logged air temperature: a sensor of 0.02 K noise
    return replace(sess, air_c=air_temperature(sess, time) + rng.normal(0, 0.02, n))



def air_temperature(session: Session, t_s) -> np.ndarray:
    """True (noise-free) air temperature [degC] at times ``t_s`` [s] of the session."""
    a = session.air
    t_h = (np.asarray(t_s, float) - session.time_s[0]) / 3600
    span = max((session.time_s[-1] - session.time_s[0]) / 3600, 1e-9)
    cycle = a["cycle_K"] * np.sin(2 * np.pi * t_h * 60 / a["period_min"] + a["phase"])
    return a["T0"] + a["drift_K"] * t_h / span + cycle
