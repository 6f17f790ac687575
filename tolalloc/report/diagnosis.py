"""Markdown report of a diagnosis with CSV tables and figures."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

from tolalloc.diagnose.pipeline import Diagnosis

__all__ = ["write_report", "markdown_table"]


def markdown_table(df: pd.DataFrame, floatfmt: str = ".4g") -> str:
    """A DataFrame as a Markdown table."""
    return df.to_markdown(index=False, floatfmt=floatfmt)


def write_report(d: Diagnosis, out: Path, title: str = "Sim-to-real diagnosis", prefix: str = "") -> Path:
    """Write ``{prefix}report.md``, CSV tables and PNG figures of ``d`` into directory ``out``; returns the report path."""
    from tolalloc.report.plots.diagnose import plot_before_after, plot_ranking, plot_where

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    ba = d.before_after()
    ba.to_csv(out / f"{prefix}before_after.csv", index=False)
    d.sequence_frame().to_csv(out / f"{prefix}ranking.csv", index=False)
    d.where.trends.to_csv(out / f"{prefix}where_trends.csv", index=False)
    d.where.worst.to_csv(out / f"{prefix}worst_poses.csv", index=False)
    d.calibration.identifiability.to_frame().to_csv(out / f"{prefix}identifiability.csv", index=False)
    d.final.fit.parameters_frame().to_csv(out / f"{prefix}parameters.csv", index=False)
    plot_where(d.where, out / f"{prefix}where.png")
    plot_ranking(d, out / f"{prefix}ranking.png")
    plot_before_after(ba, out / f"{prefix}before_after.png")
    ident = d.calibration.identifiability
    lines = [f"# {title}", "",
             f"Robot `{d.robot.name}`; training file `{d.train.source}` ({d.train.n_poses} poses, "
             f"{d.train.n_skipped} rows with empty cells skipped)"
             + (f"; test file `{d.test.source}` ({d.test.n_poses} poses, frame: {d.test_frame})" if d.test is not None else "")
             + ".", "",
             f"**Diagnosed effect: `{d.effect}`**" + (f" (sequence: {' -> '.join(d.effects)})" if len(d.effects) > 1 else ""),
             "", "Calibration model: the complete, minimal geometric model (4 line errors per revolute joint, 2 per "
             "prismatic joint, joint offsets, tracker registration, probe offset; `tolalloc.diagnose.geometry`), MAP "
             "with priors 10x the robot's sigma set. The paper's error-screw model is the tolerance model "
             "(allocation, Monte Carlo), not used here.", ""]
    lines += (["## Guards", "", *[f"- {g}" for g in d.guards], ""] if d.guards else ["Guards: none fired.", ""])
    lines += ["## How far: held-out error (cross-validation" + (" + test file" if d.test is not None else "") + ")", "",
             markdown_table(ba[["model", "label", "rms_mm", "p95_mm", "max_mm", "rms_shrink_pct",
                                "rms_shrink_vs_geometric_pct"]]), "",
             f"![before/after]({prefix}before_after.png)", ""]
    if d.test is not None:
        bt = d.before_after("test")
        lines += ["Test file alone:", "", markdown_table(bt[["model", "rms_mm", "p95_mm", "max_mm", "rms_shrink_pct"]]), ""]
    lines += ["## Which: candidate effects", "",
              "Each candidate is fitted on training poses only and scored on held-out poses; p: one-sided Wilcoxon "
              "signed-rank test of the per-pose squared-error reduction (Bonferroni over the candidates of a step).", ""]
    seq = d.sequence_frame()
    cols = ["step", "base", "effect", "heldout_rms_mm", "gain_pct", "p_value", "n_params", "significant", "selected", "reason"]
    lines += [markdown_table(seq[cols]), "", f"![ranking]({prefix}ranking.png)", ""]
    lines += ["## Where: residual after geometric calibration (training poses, robot base frame)", "",
              markdown_table(d.where.per_axis), "", "Strongest trends (Spearman of |e|, largest |Pearson| of a component, "
              "RMS per quartile bin of the feature):", "",
              markdown_table(d.where.trends.head(10)[["feature", "spearman_norm", "max_abs_corr_component",
                                                     "axis_of_max_corr", "bin_rms_mm", "bin_ratio"]]), "",
              "Worst regions:", "", markdown_table(d.where.regions.head(4)), "",
              "Worst poses:", "", markdown_table(d.where.worst.head(5)), "", f"![where]({prefix}where.png)", ""]
    lines += ["## Identifiability of the geometric parameters", "",
              f"rank {ident.rank} (9 registration/offset + {len(ident.identifiable)} geometric), condition number "
              f"{ident.condition_number:.3g}, observability index O1 {ident.observability_index:.3g}; minimum poses "
              f"{ident.min_poses}.", "",
              f"Not identifiable (not fitted): {', '.join(ident.unidentifiable) or 'none'}.", "",
              *[f"- `{k}`: {v}" for k, v in ident.reasons.items()], "",
              "Combinations the data cannot separate (normalised columns): "
              + ("; ".join(f"`{c}`" for c in ident.null_combinations) or "none") + ".", ""]
    path = out / f"{prefix}report.md"
    path.write_text("\n".join(lines) + "\n")
    (out / f"{prefix}diagnosis.json").write_text(json.dumps(d.to_dict(), indent=2, default=_default) + "\n")
    return path


def _default(o):
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, (np.floating, np.integer, np.bool_)):
        return o.item()
    raise TypeError(type(o))
