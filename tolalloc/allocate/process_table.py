"""Which manufacturing process holds which tolerance, and where each cost law comes from.

The built-in process table (:data:`PROCESSES`) says, per process, the ISO 286 grades it holds on a size or a
distance and the finest orientation, coaxiality or position zone it holds on an axis of a given length (a zone
per 100 mm of length, never below a floor), with a relative cost (turning = 1). Its figures are ASSUMED typical
workshop values (grade ranges as in the usual process-capability charts: turning IT7-IT13, boring IT8-IT13,
reaming IT6-IT10, cylindrical grinding IT5-IT7, honing and lapping IT4-IT5), labelled so in every table; a costs
file's ``[processes.*]`` replaces them for the optimiser (:mod:`tolalloc.allocate.processes`).

:func:`choose_process` names the cheapest process of a table that holds a callout; a callout finer than every
process is answered with the finest one and flagged (:class:`ProcessChoice` ``holds = False``), or refused by
:func:`require_process` with an error naming the feature, the finest process and its relative cost.

:data:`COST_LAW_SOURCES`: the published form of each cost-tolerance law of :mod:`tolalloc.allocate.costs` and the
paper it comes from (as tabulated in the surveys of Chase et al. 1990 and Dong et al. 1994).
"""

from __future__ import annotations

from dataclasses import dataclass

from tolalloc.exceptions import TolallocError

__all__ = ["Process", "ProcessChoice", "PROCESSES", "PROCESS_TABLE_SOURCE", "COST_LAW_SOURCES", "choose_process",
           "require_process", "cost_law_text", "COST_LAW_SURVEYS"]

#: Where the built-in process table comes from.
PROCESS_TABLE_SOURCE = ("assumed: typical process capabilities (ISO 286 grade ranges of the usual process-capability "
                        "charts; orientation zones per 100 mm and relative costs are this project's assumptions)")


@dataclass(frozen=True)
class Process:
    """One manufacturing process.

    Attributes
    ----------
    name : str
    grades : (int, int)
        ISO 286 grades it holds on a size or a distance (inclusive).
    zone_um_per_100mm : float
        Finest orientation / coaxiality / position zone on an axis, per 100 mm of its length [um].
    zone_min_um : float
        Finest zone on a short axis [um].
    relative_cost : float
        Cost of the process relative to turning (1.0).
    source : str
    """

    name: str
    grades: tuple
    zone_um_per_100mm: float
    zone_min_um: float
    relative_cost: float
    source: str = "assumed"

    def finest_zone_mm(self, length_mm: float) -> float:
        """Finest zone it holds on an axis of length ``length_mm`` [mm]."""
        return max(self.zone_um_per_100mm * length_mm / 100.0, self.zone_min_um) / 1000.0

    def holds(self, *, grade: int | None = None, zone_mm: float | None = None, length_mm: float | None = None) -> bool:
        """Whether it holds IT ``grade`` (a size, a distance) or a zone ``zone_mm`` over ``length_mm``."""
        if grade is not None:
            return self.grades[0] <= grade <= self.grades[1] or grade > self.grades[1]
        return zone_mm >= self.finest_zone_mm(length_mm) * (1 - 1e-9)


#: The built-in (assumed) process table, cheapest first.
PROCESSES = (
    Process("turning", (7, 13), 20.0, 10.0, 1.0),
    Process("milling", (8, 13), 25.0, 12.0, 1.1),
    Process("boring", (8, 13), 12.0, 8.0, 1.4),
    Process("reaming", (6, 10), 12.0, 8.0, 1.6),
    Process("cylindrical grinding", (5, 7), 5.0, 3.0, 2.5),
    Process("honing", (4, 5), 4.0, 2.0, 3.5),
    Process("lapping", (4, 5), 2.0, 1.0, 5.0),
)

#: Published form and source of each cost law (``tau = t / t_ref``; ``A, B, k`` the papers' coefficients).
COST_LAW_SOURCES = {
    "reciprocal": ("c = a + b/tau (A + B/t)", "Chase & Greenwood (1988), Design issues in mechanical tolerance "
                   "analysis, Manufacturing Review 1(1):50-59"),
    "reciprocal_power": ("c = a + b/tau^k (A + B/t^k)", "Sutherland & Roth (1975), J. Eng. Ind. 97(1):283-286; "
                         "k = 2: Spotts (1973), J. Eng. Ind. 95(3):762-764"),
    "exponential": ("c = a + b exp(-tau) (A e^(-Bt))", "Speckhart (1972), Calculation of tolerance based on a "
                    "minimum cost approach, J. Eng. Ind. 94(2):447-453"),
    "michael_siddall": ("c = a + b tau^-k exp(-tau) (A t^-k e^(-Bt))", "Michael & Siddall (1981), The optimization "
                        "problem with optimal tolerance assignment and full acceptance, J. Mech. Des. "
                        "103(4):842-848"),
}
COST_LAW_SURVEYS = ("forms as tabulated by Chase, Greenwood, Loosli & Hauglund (1990), Manufacturing Review "
                    "3(1):49-59, and Dong, Hu & Xue (1994), J. Eng. Ind. 116(2):199-206")


def cost_law_text(model: str) -> str:
    """``"<form>; <source>"`` of cost law ``model``."""
    form, src = COST_LAW_SOURCES[model]
    return f"{form}; {src}"


@dataclass(frozen=True)
class ProcessChoice:
    """The process named for one callout.

    Attributes
    ----------
    process : Process
        The cheapest process that holds the callout, or the finest of the table when none does.
    holds : bool
        False: no process of the table holds the callout (``process`` is the finest one).
    """

    process: Process
    holds: bool

    @property
    def label(self) -> str:
        return self.process.name if self.holds else f"none holds it (finest: {self.process.name})"


def choose_process(table=PROCESSES, *, grade: int | None = None, zone_mm: float | None = None,
                   length_mm: float | None = None) -> ProcessChoice:
    """The cheapest process of ``table`` that holds IT ``grade`` or a zone ``zone_mm`` [mm] over ``length_mm``.

    Where none holds it, the process with the finest capability (ties: the cheaper), ``holds = False``.
    """
    if (grade is None) == (zone_mm is None):
        raise TolallocError("choose_process: give a grade or a zone (with its length), not both and not neither.")
    able = [p for p in table if p.holds(grade=grade, zone_mm=zone_mm, length_mm=length_mm)]
    if able:
        return ProcessChoice(min(able, key=lambda p: p.relative_cost), True)
    if grade is not None:
        best = min(table, key=lambda p: (p.grades[0], p.relative_cost))
    else:
        best = min(table, key=lambda p: (p.finest_zone_mm(length_mm), p.relative_cost))
    return ProcessChoice(best, False)


def require_process(feature: str, table=PROCESSES, **kw) -> ProcessChoice:
    """:func:`choose_process`, refusing a callout no process of ``table`` holds with one error naming ``feature``,
    the finest process, what it holds and its relative cost."""
    ch = choose_process(table, **kw)
    if ch.holds:
        return ch
    p = ch.process
    if kw.get("grade") is not None:
        what, best = f"IT{kw['grade']}", f"IT{p.grades[0]}"
    else:
        what = f"a zone of {kw['zone_mm']:.4g} mm over {kw['length_mm']:g} mm"
        best = f"{p.finest_zone_mm(kw['length_mm']):.4g} mm"
    raise TolallocError(f"{feature}: {what} is finer than any process of the table holds; the finest is {p.name} "
                        f"({best}, relative cost {p.relative_cost:g}); widen the tolerance or add a finer process.")
