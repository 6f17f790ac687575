"""Scoring of one diagnosis against the oracle's label (rules of issue 40, part 7).

* label ``none`` / ``absorbed``: right = verdict ``none`` or ``inconclusive``; any other verdict is a false claim.
* a clear label (a family, or a mixture ``a+b``): right = verdict ``effect`` naming it (a mixture: at least one of
  the two; ``both`` says whether it named both). An ``effect`` verdict names its ``candidates``: the final model's
  ``effects`` may also hold a further effect whose family the diagnosis does not claim (a tie on a later or a minor
  effect), which does not count as named.
* label ``ambiguous:{...}``: right = verdict ``ambiguous`` with at most two candidates including the truth
  (``right3``: at most three); a verdict ``effect`` there is a *confident claim where the data cannot decide*.
* lenient (reported beside): also a confident ``effect`` naming the truth on an ambiguous label, and an
  ``ambiguous`` verdict with at most three candidates including the truth on a clear label.
"""

from __future__ import annotations


def _names(text):
    return set(filter(None, str(text or "").split("+")))


def score(row) -> dict:
    label, verdict = row["label"], row["verdict"]
    named = _names(row["named"])
    cands = _names(row["candidates"])
    effects = cands if verdict == "effect" else _names(row["effects"])  # what an `effect` verdict claims
    out = {"right": False, "right3": False, "right_lenient": False, "false_claim": False,
           "confident_undecidable": False, "both": False}
    if label in ("none", "absorbed"):
        ok = verdict in ("none", "inconclusive")
        out.update(right=ok, right3=ok, right_lenient=ok, false_claim=not ok and verdict != "error")
        return out
    hit = bool(named & effects)
    in_cands = bool(named & cands)
    out["both"] = verdict == "effect" and named <= effects and len(named) > 1
    if label.startswith("ambiguous"):
        out["right"] = verdict == "ambiguous" and in_cands and len(cands) <= 2
        out["right3"] = verdict == "ambiguous" and in_cands and len(cands) <= 3
        out["confident_undecidable"] = verdict == "effect"
        out["right_lenient"] = out["right3"] or (verdict == "effect" and hit)
    else:
        out["right"] = out["right3"] = verdict == "effect" and hit
        out["right_lenient"] = out["right"] or (verdict == "ambiguous" and in_cands and len(cands) <= 3)
    return out
