"""The handover of a design: drawing callouts with their process and cost source, a purchase list, the assumptions.

:func:`handover` turns an :class:`~tolalloc.allocate.result.AllocationResult` (its design to build by default) into
a :class:`Handover`: the callouts and bought parts of :func:`tolalloc.allocate.drawing.feature_map`, each callout
with the process that holds it -- the optimiser's where the costs file has ``[processes.*]``, else the cheapest
process of the built-in (assumed) table (:mod:`tolalloc.allocate.process_table`) -- its cost, and where the cost
comes from (the cost law's published form and paper; ``assumed`` for the built-in coefficients). The assumptions
behind the design's verdict are listed once, in :attr:`Handover.assumptions`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from tolalloc.allocate.datums import datum_letters
from tolalloc.allocate.drawing import FeatureMap, HandoverSettings, diameter_factor, feature_map
from tolalloc.allocate.fits import parse_fit
from tolalloc.allocate.process_table import (COST_LAW_SURVEYS, PROCESS_TABLE_SOURCE, PROCESSES, choose_process,
                                             cost_law_text)
from tolalloc.exceptions import TolallocError

__all__ = ["Handover", "handover", "callout_process", "callout_text", "QIF_TYPES"]

_ARCSEC = np.pi / 648000.0
#: The QIF 3 characteristic type each callout maps to (the export's ``qif_characteristic`` column).
QIF_TYPES = {"perpendicularity": "PerpendicularityCharacteristic", "parallelism": "ParallelismCharacteristic",
             "angularity": "AngularityCharacteristic", "coaxiality": "CoaxialityCharacteristic",
             "position": "PositionCharacteristic", "size": "LinearCharacteristic",
             "fit": "DiameterCharacteristic"}


def callout_process(c, table=PROCESSES):
    """``(label, holds)``: the cheapest process of ``table`` that holds callout ``c`` (a fit: hole / shaft)."""
    if c.characteristic == "fit":
        fit = parse_fit(c.grade, c.length_mm, where=c.feature)
        hole = choose_process(table, grade=fit.hole.grade)
        shaft = choose_process(table, grade=fit.shaft.grade)
        return f"{hole.label} / {shaft.label}", hole.holds and shaft.holds
    if c.grade.startswith("IT"):
        ch = choose_process(table, grade=int(c.grade[2:]))
    else:
        ch = choose_process(table, zone_mm=c.zone_mm, length_mm=c.length_mm)
    return ch.label, ch.holds


def _mm(x: float) -> str:
    """A zone as the drawing shows it, rounded down (never looser): 0.001 mm from 0.1 mm up, else 0.0001 mm."""
    d = 3 if x >= 0.1 else 4
    return f"{np.floor(x * 10**d * (1 + 1e-9)) / 10**d:.{d}f}"


def callout_text(c) -> str:
    """The callout as a drawing shows it: ``⊥ Ø0.0078 | A over 100``, ``315 ±0.105 (IT10)``, ``Ø50 H7/g6``."""
    if c.characteristic == "fit":
        return f"Ø{c.length_mm:g} {c.grade}"
    if c.characteristic == "size":
        return f"{c.length_mm:g} ±{_mm(c.zone_mm / 2)}" + (f" ({c.grade})" if c.grade else "")
    head = f"{c.symbol} {'Ø' if c.diameter else ''}{_mm(c.zone_mm)}"
    head += "".join(f" | {d}" for d in datum_letters(c.datum))
    if c.characteristic == "position":
        return f"{head} (TED {c.length_mm:g}" + (f", {c.grade}" if c.grade else "") + ")"
    return f"{head} over {c.length_mm:g}" + (f", tilt about {c.direction}" if c.direction else "")


@dataclass(frozen=True, eq=False)
class Handover:
    """Drawing callouts, purchase list and assumptions of one design.

    Attributes
    ----------
    features : FeatureMap
    process : tuple of str
        Process per callout.
    process_source : tuple of str
        ``"optimiser (costs file)"`` or ``"built-in table (assumed)"`` per callout.
    holds : tuple of bool
        Whether a process holds the callout (False: finer than the table's finest, which is named).
    cost : tuple of float
        Cost per callout and per part (the cost laws' relative units), callouts first.
    cost_source : tuple of str
        Per callout, then per part: the cost law, its source and whether its coefficients are assumed.
    assumptions : tuple of str
    """

    features: FeatureMap
    process: tuple
    process_source: tuple
    holds: tuple
    cost: tuple
    cost_source: tuple
    assumptions: tuple

    @property
    def callouts(self) -> tuple:
        return self.features.callouts

    @property
    def parts(self) -> tuple:
        return self.features.parts

    def process_of(self) -> dict:
        """Error parameter -> process (callouts) or ``"purchased part"`` (joint drives)."""
        out = {p: "purchased part" for part in self.parts for p in part.parameters}
        for c, proc in zip(self.callouts, self.process):
            out.update({p: proc for p in c.parameters})
        return out

    def cost_source_of(self) -> dict:
        """Error parameter -> where its cost comes from (the cost law, its source, assumed or the costs file)."""
        groups = [c.parameters for c in self.callouts] + [p.parameters for p in self.parts]
        return {p: src for g, src in zip(groups, self.cost_source) for p in g}

    def callout_of(self) -> dict:
        """Error parameter -> its callout as the drawing shows it, or ``purchased part: <grade>`` (joint drives)."""
        out = {}
        for part in self.parts:
            tol = (f"±{part.required / _ARCSEC:.4g} arcsec" if part.unit == "rad" else
                   f"±{part.required * 1000:.4g} um")
            out.update({p: f"purchased part, {tol}" for p in part.parameters})
        for c in self.callouts:
            out.update({p: callout_text(c) for p in c.parameters})
        return out

    def drawing_frame(self) -> pd.DataFrame:
        """One row per callout: ``feature, callout`` (as on the drawing), ``characteristic, symbol, zone_mm,
        zone_um, diameter_zone, direction, datum, length_mm, grade, process, process_source, cost, cost_source,
        parameters, span_source``."""
        cs = self.callouts
        return pd.DataFrame({
            "feature": [c.feature for c in cs], "callout": [callout_text(c) for c in cs],
            "characteristic": [c.characteristic for c in cs],
            "symbol": [c.symbol for c in cs], "zone_mm": [c.zone_mm for c in cs],
            "zone_um": [c.zone_mm * 1000.0 for c in cs], "diameter_zone": [c.diameter for c in cs],
            "direction": [c.direction for c in cs], "datum": [c.datum for c in cs],
            "length_mm": [c.length_mm for c in cs], "grade": [c.grade for c in cs], "process": list(self.process),
            "process_source": list(self.process_source), "cost": list(self.cost[:len(cs)]),
            "cost_source": list(self.cost_source[:len(cs)]), "parameters": [" ".join(c.parameters) for c in cs],
            "span_source": [c.span_source for c in cs]})

    def purchase_frame(self) -> pd.DataFrame:
        """One row per bought part: ``part, joint, grade, required_arcsec, required_um, catalogue_source,
        part_arcsec, part_um, meets, cost, cost_source, parameters`` (half-widths; the unit not of the row empty)."""
        ps, n = self.parts, len(self.callouts)

        def col(unit, f):
            return [(getattr(p, "required" if f == "req" else "part_halfwidth") / (_ARCSEC if unit == "rad" else
                     1e-3)) if p.unit == unit else np.nan for p in ps]
        return pd.DataFrame({
            "part": [p.part for p in ps], "joint": [p.joint for p in ps], "grade": [p.grade for p in ps],
            "required_arcsec": col("rad", "req"), "required_um": col("mm", "req"),
            "catalogue_source": [p.source or "none given: to be chosen" for p in ps],
            "part_arcsec": col("rad", "part"), "part_um": col("mm", "part"), "meets": [p.meets for p in ps],
            "cost": list(self.cost[n:]), "cost_source": list(self.cost_source[n:]),
            "parameters": [" ".join(p.parameters) for p in ps]})

    def rows_without_handover(self, names) -> list:
        """Error parameters of ``names`` that no callout and no part covers (empty when the handover is complete)."""
        covered = set(self.process_of())
        return [n for n in names if n not in covered]


def _sources(costs, names_all) -> dict:
    """Parameter -> cost-source text."""
    out = {}
    for nm, cm in zip(costs.names, costs.models):
        who = ("assumed: built-in coefficients (relative cost units)" if costs.source == "defaults" else
               f"costs file {costs.source}")
        out[nm] = f"{who}; {cm.model} law {cost_law_text(cm.model)}"
    return {nm: out.get(nm, "not allocated (fixed or excluded)") for nm in names_all}


def handover(result, design=None, *, settings: HandoverSettings | None = None) -> Handover:
    """The handover tables of ``design`` (default: the design to build, ``result.built``) of an allocation.

    Parameters
    ----------
    result : AllocationResult
    design : Design, optional
    settings : HandoverSettings, optional
        Defaults for spans, datums and seat diameters; tilt zones; fits; the bought-part chooser.
    """
    d = design or result.built
    if d is None or d.t is None:
        raise TolallocError("handover: the allocation has no design to hand over (infeasible or failed).")
    pr = result.problem
    model, costs = pr.model, pr.costs
    is_std = result.standard is not None and d is result.standard
    labels = list(result.grade) if is_std else [""] * len(d.t)
    fm = feature_map(model, d.t, labels, z=costs.z, distribution=costs.distribution, settings=settings, strict=False)
    names = list(model.names)
    idx = {nm: i for i, nm in enumerate(names)}
    pcost = result.to_frame(d)["cost"].to_numpy(float)
    opt_proc = dict(zip(names, result.process)) if is_std else {}
    src = _sources(costs, names)
    process, psrc, holds = [], [], []
    for c in fm.callouts:
        chosen = {opt_proc.get(p, "") for p in c.parameters} - {""}
        if chosen:
            process.append(" / ".join(sorted(chosen)))
            psrc.append(f"optimiser (costs file {costs.source} [processes.*])")
            holds.append(True)
        else:
            label, ok = callout_process(c)
            process.append(label)
            psrc.append("built-in table (assumed): the cheapest process that holds it")
            holds.append(ok)
    groups = [c.parameters for c in fm.callouts] + [p.parameters for p in fm.parts]
    cost = tuple(float(sum(pcost[idx[p]] for p in g)) for g in groups)
    csrc = tuple(" | ".join(sorted({src[p] for p in g})) for g in groups)
    return Handover(fm, tuple(process), tuple(psrc), tuple(holds), cost, csrc,
                    tuple(assumptions(result, d, fm, any(not h for h in holds))))


def assumptions(result, design, fm: FeatureMap, unheld: bool) -> list:
    """The assumptions behind the design's verdict and its tables, one sentence each."""
    pr = result.problem
    costs = pr.costs
    dist = ("normal (Gaussian), independent, zero mean" if costs.distribution == "normal" else
            "uniform over ±t, independent, zero mean")
    out = [
        f"Requirement: P(|dP| < {pr.radius_mm:g} mm) >= {pr.prob:g} at each of the {pr.n_poses} pose(s) the "
        "allocation was solved for (a region: its worst poses; the coverage check samples the rest).",
        "Rigid links and joints: no deflection under load or gravity, no dynamics (the error model is geometric).",
        "No temperature effects: every part at the reference temperature 20 °C (ISO 1).",
        f"Every error parameter {dist}; sigma = t / z with z = {costs.z:.4g} (a tolerance ±t covers "
        f"{'±' + format(costs.z, '.3g') + ' sigma' if costs.distribution == 'normal' else 'the whole range'}).",
        "The allocation uses the first-order (linear) map of the errors to the tool; the nonlinear Monte Carlo "
        "verification, where run, checks it.",
        f"Two tilts bounded by one diameter zone: the zone is set at the two-dimensional coverage of the tolerance "
        "(Rayleigh-distributed tilt magnitude for normal tilts): "
        f"Ø = L x {diameter_factor(fm.z, fm.distribution):.4f} "
        "x t, not z per component; a coaxiality zone is centred on the datum axis, so its diameter is twice the "
        "second seat's radial offset: Ø = 2 L x f x t.",
        "A radial clearance becomes the loosest preferred ISO 286 clearance fit whose largest radial play is at most "
        "sqrt(2) t (the ring's magnitude at the tolerance's coverage); back from a fit, sigma = c_max / (2 sqrt(2) z).",
        "Joint drives are bought parts: the order names the allowed transmission + encoder error as a half-width "
        "(catalogues state peak-to-peak figures: half of them is compared).",
    ]
    if costs.source == "defaults":
        out.append("Costs: the built-in cost laws and coefficients are ASSUMED (relative cost units, not measured "
                   "prices); each row names its law's published form and source (" + COST_LAW_SURVEYS + ").")
    else:
        out.append(f"Costs: from the costs file {costs.source}; each row names its law's published form and source.")
    out.append("Processes: " + PROCESS_TABLE_SOURCE + ".")
    out += [f"{u[0].upper()}{u[1:]}." for u in fm.defaults_used]
    out += [f"LOOSER THAN THE DESIGN: {w}." for w in fm.warnings]
    if fm.datum_features:
        out.append("Datum features: " + "; ".join(f"{k} {what} ({src})" for k, what, src in fm.datum_features)
                   + ". A zone per direction names the base axis its tilt is about at the home pose (column "
                   "direction): its two planes lie across the direction that tilt moves the axis, in the frame its "
                   "datum system fixes -- the second datum (a locating pin hole or keyway) fixes the turn of the "
                   "base axes about the first. The drawer adds the ISO 1101 orientation plane indicator that shows "
                   "it (the callouts here give it as the column direction only). A datum system is read in order of "
                   "precedence: the datum the zone is oriented or located from, then the feature that fixes the "
                   "rotation about it (a locating pin hole or keyway) or the face across it (a seat shoulder). The "
                   "datum features are taken as perfect relative to their axes and faces: their own tolerances are "
                   "not in the budget.")
    out += [f"DATUM NEEDED: {w}." for w in fm.datum_gaps]
    if unheld:
        out.append("Some callouts are finer than any process of the table holds: their process names the finest "
                   "one (see the drawing table).")
    return out
