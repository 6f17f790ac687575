"""`tolalloc allocate`: solver status honesty (not converged), the correction loop's flags, an infeasible region."""

import json

from solver_patches import clarabel_inaccurate as _clarabel_inaccurate
from solver_patches import ipopt_not_converged as _ipopt_not_converged
from tolalloc.cli import main
from tolalloc.progress import PROGRESS_LINE


def test_certified_not_converged_is_labelled_and_exits_1(monkeypatch, tmp_path, capsys):
    _clarabel_inaccurate(monkeypatch)
    out = tmp_path / "nc"
    rc = main(["allocate", "tool_changer", "--poses", "nominal", "--solver", "certified", "--out", str(out)])
    text = capsys.readouterr().out
    assert rc == 1, text
    assert "status: NOT CONVERGED" in text and "(NOT CONVERGED)" in text and "optimal_inaccurate" in text
    assert "status: optimal" not in text and "verified:" not in text and "not verified" in text
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "not_converged" and s["design_status"] == "not_converged"
    assert s["design_label"].startswith("certified-") and s["design_label"].endswith("(NOT CONVERGED)")
    assert s["costs"]["certified"] is None and "verification" not in s
    first = (out / "tolerances.md").read_text().splitlines()[0]
    assert first == (f"design: {s['design_label']}: for reference only, it does not meet the requirement (status "
                     "not_converged); not a design to build") and first == f"design: {s['tables_design']}"


def test_exact_not_converged_without_a_certified_start(monkeypatch, tmp_path, capsys):
    _clarabel_inaccurate(monkeypatch)
    _ipopt_not_converged(monkeypatch)
    out = tmp_path / "nc"
    rc = main(["allocate", "tool_changer", "--poses", "nominal", "--out", str(out)])
    text = capsys.readouterr().out
    assert rc == 1, text
    assert "design: exact (NOT CONVERGED)" in text and "Maximum_Iterations_Exceeded" in text
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "not_converged" and s["solver"] == "exact" and s["costs"]["exact"] is None


def test_exact_not_converged_falls_back_to_the_certified_design(monkeypatch, capsys):
    _ipopt_not_converged(monkeypatch)
    rc = main(["allocate", "tool_changer", "--poses", "nominal", "--no-verify"])
    text = capsys.readouterr().out
    assert rc == 0, text
    assert "design: certified-" in text and "(fallback from exact)" in text
    assert "guard: IPOPT did not converge (Maximum_Iterations_Exceeded)" in text
    assert "exact n/a" in text  # a fallback is not reported as an exact cost


def test_no_correction_flag(tmp_path, capsys):
    out = tmp_path / "nocorr"
    rc = main(["allocate", "tool_changer", "--poses", "nominal", "--n-mc", "20000", "--no-correction", "--out", str(out)])
    text = capsys.readouterr().out
    s = json.loads((out / "summary.json").read_text())
    assert s["correction"] is None and "correction:" not in text
    assert s["verification"]["verdict"] in ("demonstrated", "consistent") and rc == 0
    assert (out / "tolerances.md").read_text().splitlines()[0].startswith("design: standard grades (discrete-exact)")


def test_bad_correction_rounds_exits_2(capsys):
    assert main(["allocate", "tool_changer", "--poses", "nominal", "--correction-rounds", "-1"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: --correction-rounds") and len(err.strip().splitlines()) == 1


def test_infeasible_region_is_one_error_line_exit_1_nothing_written(tmp_path, capsys):
    costs = tmp_path / "c.toml"
    costs.write_text("[kinds.joint_drive]\nt_min_deg = 0.05\n")
    out = tmp_path / "o"
    rc = main(["allocate", "tool_changer", "--region", "working", "--costs", str(costs), "--out", str(out)])
    cap = capsys.readouterr()
    assert rc == 1
    lines = [line for line in cap.err.strip().splitlines() if not PROGRESS_LINE.match(line)]  # the stages done
    assert len(lines) == 1 and lines[0].startswith("error: --region working: ")
    msg = lines[0]
    assert "best achievable P is 0." in msg and "deg" in msg and "j1 = " in msg and "--costs" in msg
    p_best = float(msg.split("best achievable P is ")[1][:6])
    assert p_best < 0.95
    assert not out.exists()


def test_correction_round_limit_is_said(tmp_path, capsys):
    # the exact design sits on P = p at its one pose: consistent; with no correction round allowed the loop stops and
    # says so, the tables hold the uncorrected design, and a consistent exact design still passes (exit 0)
    out = tmp_path / "lim"
    rc = main(["allocate", "tool_changer", "--poses", "nominal", "--n-mc", "20000", "--seed", "3",
               "--correction-rounds", "0", "--out", str(out)])
    text = capsys.readouterr().out
    s = json.loads((out / "summary.json").read_text())
    corr = s["correction"]
    assert corr["rounds"] == 0 and corr["stopped"]
    # one pose with its possible second look (importance sampling under auto): 2 intervals, simultaneous
    assert corr["reason"].startswith("round limit (0) reached; still short: position: lower simultaneous 95% bound "
                                     "below p = 0.95 at 1 pose(s), by up to ")
    assert corr["verdict"] == corr["verdict_before"] == "consistent" and corr["premium_pct"] == 0
    assert "stopped, not demonstrated: round limit (0) reached" in text and "verdict per pose: 1 consistent" in text
    assert (out / "tolerances.md").read_text().splitlines()[0].startswith("design: standard grades") and rc == 0
