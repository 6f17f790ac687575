"""The UR10-class design's joint compliance against what the diagnosis measured on the real UR10.

The measured figure: the ``joint_compliance`` effect the sim-to-real diagnosis selected and fitted on the IPA laser-
tracker data (``reports/sim2real_ur10/random_{C,A}_parameters.csv``: ``c_<joint> [rad/(N m)]`` of the ``masses``
variant, i.e. the wind-up ``c_j tau_j`` under the gravity load of the robot's own masses, probe included in the
fit). Its displacement of the tool point on the session's poses is ``sum_j J_j c_j tau_j``.

The prediction: the catalogue reducers of the UR10-class design (``tolalloc/data/robots/ur10.toml``) wound up by the
same loads along the catalogue's three-band curve (every joint's loop on its motor, as on the real UR10, whose
wind-up the diagnosis sees), through the same point Jacobian. Both use the project's one gravity-load model
(:func:`tolalloc.physics.loads.gravity_torques`). Compared: the RMS displacement over all poses and over the
*loaded* poses (the top quarter of the shoulder-lift load), the ratio predicted / measured. The design at its
rated payload (10 kg) on the same poses is listed beside it; the data hold no payload, so that row has no measured
counterpart.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

import tolalloc
from tolalloc.diagnose.ipa_ur10 import read_ipa_ur10
from tolalloc.physics.loads import gravity_torques, point_jacobian, target_points, tip_load

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "studies" / "sim2real_ur10"))
from convert_ur10 import DATA  # noqa: E402  (the sim-to-real study's data folder: ../shared/data/ipa-ur10)
SESSIONS = {"C": "Series_C/measurements_random_poses.csv", "A": "Series_A/measurements_grid.csv"}
LOADED_QUANTILE = 0.75


def fitted_compliance(robot, session: str) -> np.ndarray:
    """The diagnosis's fitted ``c_j`` [rad/(N m)] per joint (0 where it fitted none)."""
    par = pd.read_csv(ROOT / "reports" / "sim2real_ur10" / f"random_{session}_parameters.csv")
    c = np.zeros(robot.n_joints)
    for j, jt in enumerate(robot.joints):
        row = par[par["parameter"] == f"joint_compliance:c_{jt.name} [rad/(N m)]"]
        c[j] = float(row["value"].iloc[0]) if len(row) else 0.0
    return c


def fitted_variant(session: str) -> str:
    """The joint-compliance variant the diagnosis chose on the session's random split (``masses``: linear)."""
    summ = pd.read_csv(ROOT / "reports" / "sim2real_ur10" / "summary.csv").set_index("run")
    variants = str(summ.loc[f"random_{session}", "variants"])
    return next((v.split(":", 1)[1].strip() for v in variants.split(";") if v.strip().startswith("joint_compliance")),
                "none")


def compare(choice: dict, every: int = 4) -> pd.DataFrame:
    """One row per session: RMS wind-up displacement measured and predicted, all poses and loaded poses [mm]."""
    robot = tolalloc.load_robot("ur10")
    reducers = [robot.components.slots[(jt.name, "reducer")].resolve(choice[(jt.name, "reducer")])
                for jt in robot.joints]
    rows = []
    for s, f in SESSIONS.items():
        variant = fitted_variant(s)
        if variant != "masses":  # a hardening fit's linear term alone is not its wind-up: no figure to compare with
            rows.append({"session": s, "fitted_variant": variant})
            continue
        df = read_ipa_ur10(DATA / f)
        q = robot.q_from_interface(df[[f"q{j + 1}" for j in range(6)]].to_numpy()[::every])
        tau = gravity_torques(robot, q)
        p = target_points(robot, q, np.zeros(3))
        J = point_jacobian(robot, q, p)
        measured = np.linalg.norm(np.einsum("pij,pj->pi", J, fitted_compliance(robot, s) * tau), axis=1)
        wind = np.stack([red.deflection(tau[:, j]) for j, red in enumerate(reducers)], axis=1)
        predicted = np.linalg.norm(np.einsum("pij,pj->pi", J, wind), axis=1)
        pay = robot.components.payload
        p_pay = p + robot.fk_internal(q)[:, :3, :3] @ pay.com_mm
        tau_rated = tau + pay.rated_kg * tip_load(robot, q, p_pay)
        wind_r = np.stack([red.deflection(tau_rated[:, j]) for j, red in enumerate(reducers)], axis=1)
        rated = np.linalg.norm(np.einsum("pij,pj->pi", J, wind_r), axis=1)
        loaded = np.abs(tau[:, 1]) >= np.quantile(np.abs(tau[:, 1]), LOADED_QUANTILE)

        def rms(x):
            return float(np.sqrt(np.mean(x ** 2)))

        rows.append({"session": s, "fitted_variant": variant, "poses": len(q), "loaded_poses": int(loaded.sum()),
                     "measured_rms_mm": rms(measured), "predicted_rms_mm": rms(predicted),
                     "ratio": rms(predicted) / rms(measured),
                     "measured_loaded_rms_mm": rms(measured[loaded]), "predicted_loaded_rms_mm": rms(predicted[loaded]),
                     "ratio_loaded": rms(predicted[loaded]) / rms(measured[loaded]),
                     "predicted_rated_payload_loaded_rms_mm": rms(rated[loaded]),
                     "c_shoulder_lift_fitted_rad_per_Nm": fitted_compliance(robot, s)[1],
                     "c_elbow_fitted_rad_per_Nm": fitted_compliance(robot, s)[2]})
    return pd.DataFrame(rows)
