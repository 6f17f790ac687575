"""The printed summary of a diagnosis: test-file figures first, then cross-validation, worst test poses, guards,
the ranking, and the gap split."""

from __future__ import annotations

__all__ = ["summary_lines"]

def summary_lines(d, folds: int, gap=None) -> list[str]:
    """Lines of the summary of :class:`~tolalloc.diagnose.Diagnosis` ``d`` (the verdict first, see
    :func:`tolalloc.report.diagnosis.summary_lines`) and of its :class:`GapSplit`."""
    from tolalloc.report.diagnosis import summary_lines as diagnosis_lines

    out = list(diagnosis_lines(d))
    if gap is not None:
        out.append("where the test error lies (mean squares of the 3-D error, adding up to the nominal model's):")
        out.append(gap.to_frame().to_string(index=False, float_format="%.4f"))
        out.append(f"  systematic_unnamed: what a Gaussian process on the joint values, trained on the training "
                   f"residual, predicts on the test poses ({100 * gap.gp_test_explained:.0f} % of the final model's "
                   f"test error); noise floor from the {gap.noise_source}")
    return out
