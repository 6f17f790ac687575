"""The printed summary of a diagnosis: test-file figures first, then cross-validation, worst test poses, guards,
the ranking, and the gap split."""

from __future__ import annotations

import numpy as np

__all__ = ["summary_lines"]

COLUMNS = ["model", "rms_mm", "p95_mm", "max_mm", "rms_shrink_pct"]


def summary_lines(d, folds: int, gap=None) -> list[str]:
    """Lines of the summary of :class:`~tolalloc.diagnose.Diagnosis` ``d`` (and its :class:`GapSplit`)."""
    from tolalloc.report.diagnosis import worst_test_poses

    out = [f"effect: {d.effect}" + (f" (sequence: {' -> '.join(d.effects)})" if len(d.effects) > 1 else "")]
    if d.subsample is not None:
        s = d.subsample
        out.append(f"subsample: cross-validation and effect selection on {s['cv_rows']:,} of {s['rows']:,} training "
                   f"rows (seed {s['seed']}), identifiability on {s['identifiability_rows']:,}; final fits on all rows")
    if d.test is not None:
        reg = d.registration
        how = (f"{len(reg.score_index)} scored poses; {len(reg.register_index)} other test poses registered the "
               "tracker frame and probe offset and are not scored" if reg is not None
               else f"{d.test.n_poses} poses, training tracker frame")
        out.append(f"test file {d.test.source} ({how}) [mm]:")
        out.append(d.before_after("test")[COLUMNS].to_string(index=False, float_format="%.4f"))
    out.append(f"cross-validation on the training file ({d.train.n_poses} poses, {folds} folds, out-of-fold) [mm]:")
    out.append(d.before_after("cv")[COLUMNS].to_string(index=False, float_format="%.4f"))
    if d.test is not None:
        out.append("worst test poses (final model; joints in deg / mm; extrapolation 1: outside the training data):")
        out.append(worst_test_poses(d).to_string(index=False, float_format="%.3f"))
        u = d.uncertainty
        out.append(f"predicted uncertainty: median 1-sigma {np.median(u.sigma_mm):.4f} mm (noise {u.noise_mm:.4f} mm "
                   f"per coordinate); {100 * u.coverage:.0f} % of {len(u.inside)} scored test residuals within the "
                   "predicted 95 % radius (95 % expected when the model's uncertainty is right)")
    out += [f"GUARD: {g}" for g in d.guards] or ["guards: none fired"]
    out += [f"note: {f}" for f in d.findings]
    out.append("ranking (held-out RMS: cross-validation + scored test poses):")
    for c in d.ranking:
        if c.applicable:
            out.append(f"  {c.effect:17s} held-out RMS {c.heldout_rms_mm:.4f} mm  p={c.p_value:.2e}  "
                       f"gain {c.gain_pct:+.1f} %")
        else:
            out.append(f"  {c.effect:17s} not testable: {c.reason}")
    if gap is not None:
        out.append("where the test error lies (mean squares of the 3-D error, adding up to the nominal model's):")
        out.append(gap.to_frame().to_string(index=False, float_format="%.4f"))
        out.append(f"  systematic_unnamed: what a Gaussian process on the joint values, trained on the training "
                   f"residual, predicts on the test poses ({100 * gap.gp_test_explained:.0f} % of the final model's "
                   f"test error); noise floor from the {gap.noise_source}")
    return out
