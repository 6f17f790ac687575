"""What if the process force were logged: set O's milling cases diagnosed with and without the cutting wrench as
columns (``force_x_n`` ... ``torque_z_nm``, at the target, robot base frame).

Set O was judged without the columns (its data carry no force: a process force nobody logs). This script takes the
same generated sessions and adds the wrench the generator applied -- the cut's mean force at the cutter's tip and the
spindle's reaction torque (``sim2real_indep.effects_o_joint``), moved to the measured target -- then runs the
diagnosis on both. It is a what-if on independently written physics, not a judged result:

    python studies/sim2real_independent/logged_wrench.py O01 O17
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import generator as gen  # noqa: E402
import tolalloc  # noqa: E402
from sim2real_indep import cases as cs, kinematics as kin  # noqa: E402
from sim2real_indep.context import Ctx  # noqa: E402
from sim2real_indep.effects_o_joint import cut_loads_tool, spindle_tip  # noqa: E402

WRENCH = ["force_x_n", "force_y_n", "force_z_n", "torque_x_nm", "torque_y_nm", "torque_z_nm"]


def case_with_wrench(case_id: str):
    """The generated case and its frame with the applied cutting wrench at the target (base frame) as columns."""
    set_name = case_id.rstrip("0123456789")  # O01 -> O, ZA01 -> ZA
    cases = cs.SETS[set_name][0]
    i = [c[0] for c in cases].index(case_id)
    cid, robot, physics, n, split = cases[i][:5]
    case = gen.generate(cid, robot, physics, n, cs.case_seed(set_name, i), split)
    t = case.truth
    ctx = Ctx(t["chain"], t["session"], t["masses"], t["com"], case.nominal.mass_link, t["payload_com_mm"],
              t["probe_mm"])
    p_f, R = kin.flange(ctx.chain, ctx.q)
    F_tool, M_tool = cut_loads_tool(t["params"]["milling_force"])
    tip = p_f + R @ spindle_tip(ctx.probe_mm)
    F, M = np.einsum("pij,pj->pi", R, F_tool), np.einsum("pij,pj->pi", R, M_tool)
    at_target = M + np.cross((tip - kin.target(ctx.chain, ctx.q, ctx.probe_mm)) / 1000.0, F)
    frame = case.frame.copy()
    frame[WRENCH] = np.hstack([F, at_target])
    return case, frame


def main(ids) -> None:
    rms = lambda a: float(np.sqrt(np.mean(np.sum(a ** 2, axis=1))))  # noqa: E731
    for case_id in ids:
        case, logged = case_with_wrench(case_id)
        print(f"{case_id} ({'+'.join(case.physics)}, {case.robot_key}):")
        for label, frame in (("without the wrench", case.frame), ("with the wrench", logged)):
            d = tolalloc.diagnose_measurements(gen.ROBOT_FILES[case.robot_key], frame.iloc[case.train],
                                               frame.iloc[case.test], progress=False).diagnosis
            print(f"  {label:18s} {d.verdict.headline()[:80]:80s} geometric {rms(d.geometric.test_mm):.3f} mm, "
                  f"final {rms(d.final.test_mm):.3f} mm (test RMS)")


if __name__ == "__main__":
    main(sys.argv[1:] or ["O01", "O17"])
