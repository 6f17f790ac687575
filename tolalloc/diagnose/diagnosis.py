"""The result of a diagnosis (:class:`Diagnosis`): models, held-out scores, guards, verdict."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.exceptions import TolallocError
from tolalloc.robot.model import Robot
from tolalloc.diagnose.calibrate import Calibration, Fit
from tolalloc.diagnose.guards import Extrapolation, ParameterCheck
from tolalloc.diagnose.uncertainty import PoseUncertainty
from tolalloc.diagnose.measurements import Measurements
from tolalloc.diagnose.recalibrate import UNCERTAINTY_SCOPE, CalibrationUpdate
from tolalloc.diagnose.register import RegistrationSplit
from tolalloc.diagnose.scores import Evaluation, error_stats
from tolalloc.diagnose.verdict import Verdict
from tolalloc.diagnose.where import WhereBreakdown

__all__ = ["Diagnosis"]


@dataclass(frozen=True, eq=False)
class Diagnosis:
    """Result of :func:`diagnose`.

    Attributes
    ----------
    robot : Robot
    train, test : Measurements (test may be None)
    calibration : Calibration      registration + offset (+ identifiable geometry) on all training poses
    stages : tuple of Stage        sequential selection; ``stages[0].candidates`` is the ranking
    effects : tuple of str         selected effects in order (empty: ``none``)
    nominal, geometric, final : Evaluation   held-out evaluations of the three models
    where : WhereBreakdown         residual breakdown after geometric calibration (training poses)
    test_frame : {"same", "refit"}
    guards : tuple of str          guards that fired (implausible or weakly identified parameters, extrapolating
                                   test poses, fallback)
    extrapolation : Extrapolation or None   per test pose flags (None without a test file)
    fallback : str or None         ``nominal`` / ``geometric`` when the fitted model lost on cross-validation
    registration : RegistrationSplit or None   ``refit``: test poses used to register the frame (never scored)
    uncertainty : PoseUncertainty or None      per test pose predicted 1-sigma and 95 % radius, coverage check
    registered : Fit or None       ``refit``: the final fit with the test frame's registration and probe offset
    subsample : dict or None       large training files: what ran on a seeded subsample (cross-validation,
                                   effect selection, identifiability) and what on all rows (the final fits)
    parameter_check : ParameterCheck or None   geometric parameters and probe offset vs the plausibility level
    findings : tuple of str        well-identified deviations from nominal (informational, not guards)
    verdict : Verdict or None      ``effect`` / ``none`` / ``ambiguous`` / ``inconclusive``, candidates, reasons,
                                   the model safe to use, suggested poses (:mod:`.verdict`)
    outliers : tuple of dict       training rows each stage's fit (nominal, geometric, final) down-weighted or left
                                   far out (``stage``, ``row``, ``error_mm``, ``weight``;
                                   :func:`~tolalloc.diagnose.calibrate.outlier_rows`)
    settings : dict                robust loss and target-offset prior of the fits
    effect_ref : dict or None      the effect reference the bases were built with (:func:`~.effects.effect_reference`:
                                   the training file's temperature and time origin, the gear ratios -- given or found
                                   by the search -- and the chosen variants), so a model rebuilt from the diagnosis
                                   predicts with the very same columns
    calibration_update : CalibrationUpdate or None   ``register_update="calibration"``: the k of each updated
                                   model (its training data count 1/k in the prior), its floor, the registration
                                   poses set aside as gross errors and the update's robust loss (:mod:`.recalibrate`)
    """

    robot: Robot
    train: Measurements
    test: Measurements | None
    calibration: Calibration
    stages: tuple
    effects: tuple
    nominal: Evaluation
    geometric: Evaluation
    final: Evaluation
    where: WhereBreakdown
    test_frame: str = "same"
    guards: tuple = ()
    extrapolation: Extrapolation | None = None
    fallback: str | None = None
    registration: RegistrationSplit | None = None
    uncertainty: PoseUncertainty | None = None
    registered: Fit | None = None
    subsample: dict | None = None
    parameter_check: ParameterCheck | None = None
    findings: tuple = ()
    verdict: Verdict | None = None
    outliers: tuple = ()
    settings: dict | None = None
    calibration_update: CalibrationUpdate | None = None
    effect_ref: dict | None = None

    @property
    def scored_index(self) -> np.ndarray:
        """Test poses (0-based) the test figures are computed on: all, or the non-registration ones."""
        return self.registration.score_index if self.registration is not None else np.arange(self.test.n_poses)

    def registration_fitted(self) -> str:
        """What the registration poses of a ``refit`` test file fitted, in words."""
        u = self.calibration_update
        return "the tracker frame and probe offset" if u is None else u.fitted()

    def uncertainty_scope(self) -> str:
        """Empty, or (calibration update) that the predicted uncertainty is the update's posterior; said beside every
        coverage figure."""
        return UNCERTAINTY_SCOPE if self.final.test_cov is not None else ""

    @property
    def effect(self) -> str:
        """The effect claimed: the first selected one, or ``none`` (also when the verdict is ``inconclusive``:
        the final model's effects are then not claimed; ``effects`` still lists them)."""
        if self.verdict is not None and self.verdict.verdict in ("none", "inconclusive"):
            return "none"
        return self.effects[0] if self.effects else "none"

    @property
    def family_probability_none(self) -> float | None:
        """Posterior probability of no effect beside the ranked families (:mod:`.families`); None when not stated."""
        p = [c.probability for c in self.ranking if np.isfinite(c.probability)]
        return None if not p else max(0.0, 1.0 - float(sum(p)))

    @property
    def ranking(self) -> tuple:
        return self.stages[0].candidates

    def before_after(self, which: str = "heldout") -> pd.DataFrame:
        """RMS / p95 / max / mean error [mm] of nominal, geometric and final models with the shrink in percent.

        ``which``: ``heldout`` (CV + test), ``cv`` (out-of-fold training poses) or ``test``.
        """
        rows = []
        for name, ev in (("nominal", self.nominal), ("geometric", self.geometric), ("final", self.final)):
            res = {"heldout": ev.heldout_mm, "cv": ev.oof_mm, "test": ev.test_mm}[which]
            if res is None:
                raise TolallocError("no test file was given; use which='heldout' or 'cv'.")
            rows.append({"model": name, "label": ev.label, **error_stats(res)})
        df = pd.DataFrame(rows)
        for col in ("rms_mm", "p95_mm", "max_mm"):
            base = df[col].iloc[0]
            df[col.replace("_mm", "_shrink_pct")] = 100.0 * (1.0 - df[col] / base)
        df["rms_shrink_vs_geometric_pct"] = 100.0 * (1.0 - df["rms_mm"] / df["rms_mm"].iloc[1])
        return df

    def outliers_frame(self) -> pd.DataFrame:
        """Training poses treated as gross errors: file row, 3-D residual [mm], IRLS weight."""
        return pd.DataFrame(list(self.outliers), columns=["stage", "row", "error_mm", "weight"])

    def ranking_frame(self) -> pd.DataFrame:
        return pd.DataFrame([c.to_dict() for c in self.ranking])

    def sequence_frame(self) -> pd.DataFrame:
        rows = []
        for i, st in enumerate(self.stages):
            for c in st.candidates:
                rows.append({"step": i + 1, "base": "+".join(("geometric", *st.base)), "base_rms_mm": st.base_rms_mm,
                             **c.to_dict(), "selected": c.effect == st.selected, "removed": c.effect == st.removed})
        return pd.DataFrame(rows)

    def to_dict(self) -> dict:
        """JSON-ready result. The error figures of each set of poses under their own key: ``cv_rms_mm`` and the
        ``cv`` block (out-of-fold predictions of the training file), ``test_rms_mm`` and the ``test`` block (the
        test file's scored poses, with a test file) -- the figures the summary prints."""
        cv, test = self._block("cv"), None if self.test is None else self._block("test")
        out = {
            "robot": self.robot.name,
            **(self.verdict.to_dict() if self.verdict is not None else {}),
            "effect": self.effect,
            "effects": list(self.effects),
            "ranking": [c.to_dict() for c in self.ranking],
            "probability_no_effect": self.family_probability_none,
            "sequence": [{"base": list(st.base), "base_rms_mm": st.base_rms_mm, "selected": st.selected or "none", "removed": st.removed,
                          "candidates": [c.to_dict() for c in st.candidates]} for st in self.stages],
            "cv_rms_mm": cv["rms_mm"],
            **({} if test is None else {"test_rms_mm": test["rms_mm"]}),
            "heldout": {"cv_poses": len(self.nominal.oof_mm), "test_poses": 0 if self.test is None else len(self.scored_index),
                        "test_frame": self.test_frame,
                        "sealed_test": "the test file was scored once, after the model was chosen on the training "
                                       "file alone (variants, folds, thresholds, selection)"
                                       + ("" if self.calibration_update is None or self.registration is None else
                                          "; its registration poses (never scored) also fitted a correction of the "
                                          "trained parameters (register_update='calibration')")},
            "train": {"poses": self.train.n_poses, "skipped_rows": self.train.n_skipped, "source": self.train.source,
                      "rms_mm": {"nominal": self.calibration.nominal.rms_mm, "geometric": self.calibration.geometric.rms_mm,
                                 "final": self.final.fit.rms_mm}},
            "identifiability": self.calibration.identifiability.to_dict(),
            "registration": {"rotation": self.calibration.geometric.R, "translation_mm": self.calibration.geometric.p_mm,
                             "target_offset_mm": self.calibration.geometric.t_mm},
            "parameters": self.final.fit.parameters_frame().to_dict(orient="records"),
            "guards": list(self.guards),
            "findings": list(self.findings),
            "outliers": list(self.outliers),
            "settings": self.settings,
            "fallback": self.fallback,
            "subsample": self.subsample,
            "models": {"calibration": "complete minimal geometric model (diagnose.geometry): 4 line errors per "
                                      "revolute joint, 2 per prismatic joint, joint offsets, registration, probe offset",
                       "tolerance": "the paper's error-screw model (errormodel.model), not used by the diagnosis"},
        }
        out["cv"] = cv | {"poses": self.train.n_poses}
        if self.extrapolation is not None:
            out["extrapolation"] = self.extrapolation.to_dict()
        if self.test is not None:
            fitted = {} if self.calibration_update is None else {"fitted": self.registration_fitted()}
            out["test"] = {"poses": self.test.n_poses, "skipped_rows": self.test.n_skipped, "source": self.test.source,
                           "scored_poses": len(self.scored_index), **test,
                           "registration": None if self.registration is None else
                           self.registration.to_dict(self.test.rows, **fitted)}
            if self.registered is not None:
                out["test"]["registration"] |= {"rotation": self.registered.R, "translation_mm": self.registered.p_mm,
                                                "target_offset_mm": self.registered.t_mm}
            if self.calibration_update is not None and self.registration is not None:
                out["test"]["registration"] |= self.calibration_update.to_dict(self.test.rows)
        if self.uncertainty is not None:
            out["uncertainty"] = self.uncertainty.to_dict()
        if self.parameter_check is not None:
            out["parameter_check"] = self.parameter_check.to_frame().to_dict(orient="records")
        return out

    def _block(self, which: str) -> dict:
        """RMS, p95 and max error [mm] of the nominal, geometric and final models on the poses ``which`` and the
        RMS shrink in percent."""
        b = self.before_after(which)
        return {**{k: dict(zip(b["model"], b[k])) for k in ("rms_mm", "p95_mm", "max_mm")},
                "shrink_pct": {"final_vs_nominal": float(b["rms_shrink_pct"].iloc[2]),
                               "final_vs_geometric": float(b["rms_shrink_vs_geometric_pct"].iloc[2]),
                               "geometric_vs_nominal": float(b["rms_shrink_pct"].iloc[1])}}
