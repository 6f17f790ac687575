"""CLI: calplan writes a plan that allocate --calibration reads; bad input -> exit 2, one error line, nothing written."""

import re

import numpy as np
import pytest

from tolalloc.calibration import make_plan, write_plan
from tolalloc.cli import main
from tolalloc.robot.io import load_robot


@pytest.fixture(scope="module")
def tc():
    return load_robot("tool_changer")


@pytest.mark.slow
def test_calplan_then_allocate(tmp_path, capsys):
    plan = tmp_path / "plan.csv"
    assert main(["calplan", "tool_changer", "--n-poses", "8", "--n-candidates", "256", "--out", str(plan)]) == 0
    out = capsys.readouterr().out
    assert "designed" in out and plan.is_file()
    over = re.search(r"relaxation: SciPy trust-constr \(\d round\(s\) over (\d+) of 256 candidates", out)
    assert over and int(over.group(1)) < 256  # the column generation runs
    rc = main(["allocate", "tool_changer", "--calibration", str(plan), "--n-mc", "500", "--coverage-n", "5000",
               "--no-snap", "--out", str(tmp_path / "res")])  # standard grades: tests/test_calibrated_standard.py
    out = capsys.readouterr().out
    assert rc == 0 and "certified calibrated design: cost" in out and "calibrated away" in out
    assert "coverage (post-calibration P)" in out and "end-to-end Monte Carlo" in out
    assert (tmp_path / "res" / "tolerances.csv").is_file() and (tmp_path / "res" / "verification.csv").is_file()


@pytest.mark.parametrize("edit, msg", [
    (("# noise_mm = 0.02", "# noise_mm = -1"), "noise_mm"),
    (("# noise_mm = 0.02", "# noise_mm = nan"), "noise_mm"),
    (("# estimate = all", "# estimate = dl1 nope"), "needs a plan that estimates every systematic parameter"),
    (("# registration = true", "# registration = maybe"), "registration"),
])
def test_bad_plan_exit_2_nothing_written(tc, tmp_path, capsys, edit, msg):
    path = tmp_path / "plan.csv"
    write_plan(make_plan(tc, tc.poses("working")[:5]), tc, path)
    path.write_text(path.read_text().replace(*edit))
    out = tmp_path / "res"
    rc = main(["allocate", "tool_changer", "--calibration", str(path), "--out", str(out)])
    err = capsys.readouterr().err
    assert rc == 2 and err.startswith("error:") and msg in err and err.count("\n") == 1
    assert not out.exists()


def test_pose_outside_limits_and_bad_flags(tc, tmp_path, capsys):
    path = tmp_path / "plan.csv"
    write_plan(make_plan(tc, tc.poses("working")[:3]), tc, path)
    lines = path.read_text().splitlines()
    lines[-1] = "170," + lines[-1].split(",", 1)[1]  # j1 beyond its +-90 deg limits
    path.write_text("\n".join(lines) + "\n")
    assert main(["allocate", "tool_changer", "--calibration", str(path), "--no-verify"]) == 2
    assert "outside its limits" in capsys.readouterr().err
    out = tmp_path / "p.csv"
    assert main(["calplan", "tool_changer", "--n-poses", "5", "--noise-mm", "-0.1", "--out", str(out)]) == 2
    assert "--noise-mm" in capsys.readouterr().err and not out.exists()
    assert main(["calplan", "tool_changer", "--n-poses", "0", "--n-candidates", "64", "--out", str(out)]) == 2
    assert "--n-poses" in capsys.readouterr().err and not out.exists()


def test_few_poses_name_unidentifiable(tmp_path, capsys):
    out = tmp_path / "p.csv"
    assert main(["calplan", "tool_changer", "--n-poses", "2", "--n-candidates", "64", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "not identifiable individually by the plan" in text and "dth1 (1.00)" in text


def test_allocate_with_repeatability_grades_from_the_costs_file(tc, tmp_path, capsys):
    """A `grade` table in the costs file's [calibration] section makes the repeatability a priced decision."""
    import json

    plan = tmp_path / "plan.csv"
    rng = np.random.default_rng(0)
    write_plan(make_plan(tc, tc.lower + (tc.upper - tc.lower) * rng.random((12, 6))), tc, plan)
    costs = tmp_path / "costs.toml"
    costs.write_text('[calibration.kinds.joint_drive.grade]\nmodel = "reciprocal"\na = 0.2\nb = 0.3\n'
                     't_ref_deg = 0.001\nt_min_deg = 0.0003\nt_max_deg = 0.01\n', encoding="utf-8")
    out = tmp_path / "res"
    # at the working pose set: the box search over the working region (run by test_calplan_then_allocate) ends on
    # these poses here, with the same costs, and takes about 10 s more
    rc = main(["allocate", "tool_changer", "--calibration", str(plan), "--costs", str(costs), "--no-verify",
               "--poses", "working", "--out", str(out)])
    text = capsys.readouterr().out
    assert rc == 0 and "repeatability grades" in text
    summary = json.loads((out / "summary.json").read_text())
    assert summary["cost_certified"] == pytest.approx(summary["cost_parts"] + summary["cost_repeatability_grades"])
    assert summary["cost_repeatability_grades"] > 0
    assert "repeatability_grade" in (out / "tolerances.csv").read_text().splitlines()[0]
