"""What the process limits allow: every allocatable tolerance at its lower limit ``t_min`` (the fixed ones at their
values), the best probability and radius per requirement block, and the limits that bind where no design can meet
a requirement (:func:`check_process_limits`, run by :func:`tolalloc.allocate.allocate` before the solvers)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tolalloc.allocate.blocks import block_covariances, block_probability, block_radius
from tolalloc.allocate.problem import AllocationProblem
from tolalloc.linear.covariance import variance_share

__all__ = ["LimitReport", "check_process_limits"]


@dataclass(frozen=True, eq=False)
class LimitReport:
    """What the process limits allow: every allocatable tolerance at ``t_min``.

    Attributes
    ----------
    feasible : bool
        Whether that tightest design meets every requirement (exact Gaussian probability).
    p_best : dict name -> array (P,)
        Best achievable probability at the required radius, per pose.
    radius_best : dict name -> array (P,)
        Radius achievable at the required probability [mm or rad], per pose.
    worst_pose : dict name -> int
    binding : list of (parameter, variance share at the worst pose)
        Limits that bind, largest share first (``t_min`` of allocatable parameters, fixed values).
    message : str
    """

    feasible: bool
    p_best: dict
    radius_best: dict
    worst_pose: dict
    binding: list
    message: str


def _binding(problem: AllocationProblem, b: dict, i: int, t) -> list:
    """The parameters whose variance shares at pose ``i`` of block ``b`` reach 2 %, largest first (at most 8)."""
    names = problem.costs.names
    if b.get("measure") is None:
        share = variance_share(problem.J[i, b["rows"], :], problem.sigma(t) ** 2)
    else:
        share = np.zeros(len(names))  # allocatable parameters only: the fixed ones are held in C0 together
        share[problem.alloc] = np.einsum("kii->k", b["A"][i]) * problem.u_from_t(t)
        share /= max(np.trace(b["C0"][i]) + share.sum(), 1e-300)
    order = np.argsort(share)[::-1]
    return [(names[k], float(share[k])) for k in order if share[k] >= 0.02][:8]


def _fixed_text(b: dict, i: int, C, f: float, unit: str) -> str:
    """An ISO block's fixed part at row ``i`` (its share of the variance) and the bought parts' mean, as text."""
    if b.get("measure") is None:
        return ""
    out = (f" The fixed part (bought parts' effects, repeatabilities, fixed tolerances) carries "
           f"{np.trace(b['C0'][i]) / max(np.trace(C[i]), 1e-300):.0%} of the variance there")
    bias = b.get("bias")
    if bias is not None and bias[i] > 0:
        out += (f"; the bought parts' mean error ({bias[i] * f:.4g} {unit}) leaves "
                f"{(b['radius'] - bias[i]) * f:.4g} {unit} of the limit")
    return out + "."


def check_process_limits(problem: AllocationProblem) -> LimitReport:
    """Best achievable probability and radius within the process limits, and the limits that bind."""
    t = problem.t_min.copy()
    t[problem.fixed] = np.array(problem.costs.fixed_tol)[problem.fixed]
    names = problem.costs.names
    feasible, p_best, r_best, worst, binding, lines = True, {}, {}, {}, [], []
    for b in problem.blocks:
        C = block_covariances(problem, b, t)
        p = block_probability(b, C)
        r = block_radius(b, C, b["prob"])
        i = int(np.argmin(p - b["target"]))
        p_best[b["name"]], r_best[b["name"]], worst[b["name"]] = p, r, i
        if p[i] < b["target"][i]:
            feasible = False
            top = _binding(problem, b, i, t)
            binding += top
            angle = b["name"] == "orientation" or (b.get("requirement") is not None and b["requirement"].unit == "deg")
            unit, f = ("deg", 180 / np.pi) if angle else ("mm", 1.0)
            stat = {"position": "|dP|", "orientation": "|dw|"}.get(b["name"], b["name"])
            lim = ", ".join(
                f"{nm} {'fixed at' if problem.costs.role[names.index(nm)] == 'fixed' else 't_min ='} "
                f"{t[names.index(nm)] * problem.model.params[names.index(nm)].to_interface:.4g} "
                f"{problem.model.params[names.index(nm)].interface_unit} ({s:.0%})" for nm, s in top)
            lines.append(
                f"infeasible within the process limits: with every tolerance at its lower limit the worst pose "
                f"({_where(problem, b, i)}) reaches P({stat} {'<' if b.get('measure') is None else '<='} "
                f"{b['radius'] * f:g} {unit}) = {p[i]:.4f} "
                f"< {b['target'][i]:g}; the {b['name']} {'radius' if b.get('measure') is None else 'value'} achievable "
                f"at p = {b['prob']:g} is {r.max() * f:.4g} {unit}.{_fixed_text(b, i, C, f, unit)} "
                + (f"Limits that bind (variance share at that pose): {lim}. Lower these t_min (or the fixed "
                   "tolerances) in a costs file (--costs) or relax the requirement." if lim else
                   "No tolerance binds: choose finer parts (a better reducer or encoder grade) or relax the "
                   "requirement."))
    return LimitReport(feasible, p_best, r_best, worst, binding,
                       " ".join(lines) if lines else "feasible within the process limits")


def _where(problem: AllocationProblem, b: dict, i: int) -> str:
    """Pose ``i`` of block ``b`` as the user reads it."""
    return f"pose {i + 1} of {problem.n_poses}" if b.get("labels") is None else b["labels"][i]
