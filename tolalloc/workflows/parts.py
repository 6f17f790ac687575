"""The job's result of ``allocate_tolerances(..., parts=...)``: machining tolerances and catalogue parts chosen
together (:func:`tolalloc.verify.parts.verified_parts`), on the shared result protocol (:mod:`tolalloc.workflows.base`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from tolalloc.exceptions import ArgumentError
from tolalloc.outputs import json_native, write_json
from tolalloc.workflows import inputs
from tolalloc.workflows.base import JobResult

__all__ = ["PartsToleranceAllocation", "read_parts_choice"]

#: The columns of a parts table that name a choice (``parts.csv`` of a design with bought parts).
CHOICE_COLUMNS = ("joint", "kind", "part")
_PARTS_CSV = ("the parts.csv of a design with bought parts (tolalloc allocate ROBOT --parts --out DIR writes "
              "DIR/parts.csv)")


@dataclass(frozen=True, eq=False, repr=False)
class PartsToleranceAllocation(JobResult):
    """Machining tolerances and bought parts allocated together, with the nonlinear Monte Carlo at the worst point.

    Attributes
    ----------
    result : PartsAllocation
        The joint allocation (:class:`tolalloc.allocate.parts_result.PartsAllocation`: choice, design, proof,
        worst point, ``verification``).
    radius_mm, prob : float
        The requirement ``P(|dP| < radius_mm) >= prob`` at every point of the region x payload x ambient.
    label : str
        The region's name.
    inputs : dict
        The call's arguments, for the record.
    """

    result: object
    radius_mm: float
    prob: float
    label: str
    inputs: dict = field(default_factory=dict)

    @property
    def verification(self):
        """The nonlinear Monte Carlo (:class:`tolalloc.verify.parts.PartsVerification`), None without one."""
        return self.result.verification

    @property
    def verdict(self) -> str:
        v = self.verification
        return "not verified" if v is None else v.verdict

    @property
    def ok(self) -> bool:
        return self.result.ok and self.verdict == "demonstrated"

    @property
    def cost(self) -> float:
        return self.result.cost

    @property
    def choice(self) -> dict:
        """``{(joint, kind): part name}`` of every catalogue slot."""
        return self.result.choice

    def headline(self) -> list[str]:
        r, c = self.result, self.result.conditions
        w = r.worst_point
        q = ", ".join(f"{v:.4g}" for v in r.problem.model.robot.q_to_interface(w.q[0]))
        return [f"robot: {r.problem.model.robot.name}   requirement: P(|dP| < {self.radius_mm:g} mm) >= {self.prob:g} "
                f"over {self.label!r} x payload {c.payload_kg[0]:g}-{c.payload_kg[1]:g} kg x ambient "
                f"{c.ambient_c[0]:g}-{c.ambient_c[1]:g} degC{_process(c)} (after: {r.after})",
                f"cost {r.cost:.4g} = machining {r.machining_cost:.4g} + bought parts {r.parts_cost:.4g}   "
                f"(program {r.outcome.status}, relative gap {r.outcome.gap:g})",
                f"worst point: q = {q} deg / mm, payload {w.payload_kg[0]:g} kg, ambient {w.ambient_c[0]:g} degC",
                f"verdict: {self.verdict}"]

    def to_frame(self) -> pd.DataFrame:
        """The parts to buy, one row per slot (:meth:`PartsAllocation.parts_table`)."""
        return self.result.parts_table()

    def tolerances(self) -> pd.DataFrame:
        """The machining tolerances (``tol_mm`` / ``tol_deg``, standard value, cost)."""
        return self.result.tolerances()

    def variance_shares(self) -> pd.DataFrame:
        """Each source's share of the tool-error variance at the worst point."""
        return self.result.variance_shares()

    def verification_frame(self) -> pd.DataFrame:
        """One row per verified point (empty without a verification)."""
        return pd.DataFrame() if self.verification is None else self.verification.to_frame()

    def summary(self) -> dict:
        v = self.verification
        return json_native({"inputs": self.inputs, "requirement": {"radius_mm": self.radius_mm, "prob": self.prob},
                            **self.result.summary(), "verdict": self.verdict,
                            "verification": None if v is None else self.verification_frame().to_dict("records")})

    def text(self) -> str:
        return "\n".join(self.headline() + ["", self.to_frame()[["joint", "kind", "part", "grade", "cost"]]
                                            .to_string(index=False)])

    def plot_shares(self, ax=None):
        """Each source's share of the variance at the worst point (bars, largest first); returns the axes."""
        from tolalloc.report.plots.acceptance import plot_source_shares

        return plot_source_shares(self.variance_shares(), ax=ax)

    def write_files(self, folder, *, report: bool = False) -> list[str]:
        """``parts.csv``, ``tolerances.csv``, ``variance.csv``, ``verification.csv`` and ``summary.json`` into an
        existing ``folder`` (not atomic: :meth:`save` publishes them together)."""
        folder = Path(folder)
        files = {"parts.csv": self.to_frame(), "tolerances.csv": self.tolerances(), "variance.csv": self.variance_shares(),
                 "verification.csv": self.verification_frame()}
        for name, frame in files.items():
            frame.to_csv(folder / name, index=False, float_format="%.8g")
        write_json(self.summary(), folder / "summary.json")
        return [*files, "summary.json"]


def read_parts_choice(source, argument: str = "parts") -> dict:
    """``{(joint, kind): part name}`` from the parts table of a design with bought parts.

    Parameters
    ----------
    source : str, os.PathLike or pandas.DataFrame
        The ``parts.csv`` that ``allocate_tolerances(..., parts=...)`` saves (``tolalloc allocate ROBOT --parts --out
        DIR``), or its ``to_frame()``: one row per catalogue slot, columns ``joint``, ``kind``, ``part`` (others are
        ignored).
    argument : str
        The argument's name in the errors.
    """
    frame = inputs.read_table(source, argument, _PARTS_CSV, text=True)
    if frame is None:
        raise ArgumentError(argument, f"expected a parts table: a path to a parts.csv or a DataFrame, got "
                            f"{type(source).__name__}.")
    where = "the table" if isinstance(source, pd.DataFrame) else repr(str(source))
    missing = [c for c in CHOICE_COLUMNS if c not in frame.columns]
    if missing:
        raise ArgumentError(argument, f"{where}: expected the columns {', '.join(CHOICE_COLUMNS)} (the parts.csv of a "
                            f"design with bought parts); missing {', '.join(missing)}.")
    choice = {}
    for i, row in enumerate(frame[list(CHOICE_COLUMNS)].astype(str).itertuples(index=False), start=1):
        joint, kind, part = (v.strip() for v in row)
        if not (joint and kind and part):
            raise ArgumentError(argument, f"{where}, row {i}: expected a joint, a kind and a part, got "
                                f"{joint!r}, {kind!r}, {part!r}.")
        if choice.setdefault((joint, kind), part) != part:
            raise ArgumentError(argument, f"{where}, row {i}: slot {joint}.{kind} is chosen twice "
                                f"({choice[(joint, kind)]} and {part}); keep one row per slot.")
    if not choice:
        raise ArgumentError(argument, f"{where}: no rows; expected one row per catalogue slot.")
    return choice


def _process(c) -> str:
    """The conditions' process wrench in words (empty without one)."""
    if not c.has_process_wrench:
        return ""
    f, m = (", ".join(f"{v:g}" for v in x) for x in (c.process_force_n, c.process_torque_nm))
    return f" x process force ({f}) N and moment ({m}) N m at the tool, tool frame"
