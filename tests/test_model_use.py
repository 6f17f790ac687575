"""Using an identified model (issue 45, part 1): predictions, compensation, export, and their bad input.

Known answers: the identified model rebuilt from a diagnosis reproduces the diagnosis's own test predictions and
predicted uncertainties; the compensation, on a synthetic robot without effects, puts the *true* robot (the
generator's perturbed chain) on its targets to the noise level while the programmed joint values miss them by
millimetres; the exported TOML and URDF files, read back by the robot loaders, reproduce the identified forward
kinematics to 1e-9 mm, and the ``[identified]`` section rebuilds the model exactly.
"""

import contextlib
import dataclasses
import io
import tomllib

import numpy as np
import pandas as pd
import pytest

import tolalloc
from tolalloc.cli import main
from tolalloc.diagnose import diagnose, generate, measurements_from_frame
from tolalloc.diagnose.compensate import compensate, solve_targets
from tolalloc.diagnose.model_export import identified_robot_dict, identified_section, model_from_identified
from tolalloc.diagnose.model_use import identified_model
from tolalloc.diagnose.synth import split_frame
from tolalloc.errormodel import build_error_model
from tolalloc.exceptions import TolallocError
from tolalloc.robot.io.urdf import load_urdf
from tolalloc.robot.kinematics import fk_poe
from tolalloc.workflows.diagnosis import MeasurementDiagnosis
from tolalloc.workflows.model_use import compensate_program, load_identified, predict_frame

ROBOT = tolalloc.load_robot("ur10")


def _diagnosis(effect, n, seed, **kw):
    case = generate(ROBOT, effect, n, np.random.default_rng(seed), **kw)
    tr, te = split_frame(case.frame, 0.25, np.random.default_rng(1))
    return case, te, diagnose(ROBOT, measurements_from_frame(tr, ROBOT), measurements_from_frame(te, ROBOT), folds=2,
                              max_effects=1)


@pytest.fixture(scope="module")
def backlash():
    case, te, d = _diagnosis("backlash", 64, 8)
    assert d.effects == ("backlash",)
    return d, identified_model(d)


@pytest.fixture(scope="module")
def geometric():
    """A robot without effects measured with 1 um noise: the identified geometry is the true one."""
    case, te, d = _diagnosis("none", 60, 3, noise_mm=0.001)
    return case, d, identified_model(d)


def _kw(m):
    return dict(temperature_c=m.temperature_c, time_s=m.time_s, direction=m.direction, payload_kg=m.payload_kg)


def test_rebuilt_model_reproduces_the_diagnosis(backlash):
    d, m = backlash
    meas = m.measurements(d.test.q, **_kw(d.test))
    np.testing.assert_allclose(m.points(meas, "tracker"), d.final.test_pred_mm, atol=1e-9)
    sigma = np.sqrt(np.trace(m.point_covariance(meas, "tracker"), axis1=1, axis2=2))
    np.testing.assert_allclose(sigma, d.uncertainty.sigma_mm, rtol=1e-9)
    base = m.point_covariance(meas, "base")  # the registration's share left out: never larger
    assert np.all(np.trace(base, axis1=1, axis2=2) <= sigma ** 2 + 1e-15)
    assert m.covariates() == {"dir": ["backlash (approach)"]}


def test_joint_jacobian_matches_finite_differences(backlash):
    _, m = backlash
    q = ROBOT.random_q(np.random.default_rng(2), 3)
    J, h = m.joint_jacobian(q), 1e-6
    for j in range(ROBOT.n_joints):
        dq = np.zeros(ROBOT.n_joints)
        dq[j] = h
        fd = (m.geometric_points(q + dq) - m.geometric_points(q - dq)) / (2 * h)
        np.testing.assert_allclose(J[:, :, j], fd, atol=1e-5)


def _true_tracker_points(case, q):
    """The generator's robot (tolerance model's perturbed chain, probe offset, tracker frame) at ``q``."""
    tr = case.truth
    screws, home, dq = build_error_model(ROBOT).perturbed_chain(tr["geometric"][None, :])
    T = fk_poe(screws[0], home[0], q + dq[0])
    return (T[:, :3, 3] + T[:, :3, :3] @ tr["t_mm"]) @ tr["R"].T + tr["p_mm"]


def test_compensation_puts_the_true_robot_on_its_targets(geometric):
    case, d, m = geometric
    rng = np.random.default_rng(4)
    q_goal = ROBOT.random_q(rng, 12) * 0.8
    targets = _true_tracker_points(case, q_goal)  # reachable positions, in the tracker frame
    seed = q_goal + np.deg2rad(rng.normal(0, 0.3, q_goal.shape))  # a program taught near them
    res = solve_targets(m, targets, seed, frame="tracker", tol_mm=1e-10)
    assert res.status == ("ok",) * 12 and res.error_mm.max() < 1e-9
    before = np.linalg.norm(_true_tracker_points(case, seed) - targets, axis=1)
    after = np.linalg.norm(_true_tracker_points(case, res.q) - targets, axis=1)
    assert before.min() > 0.5 and after.max() < 0.02


def test_compensation_of_nominal_targets_and_nominal_ik(backlash):
    d, m = backlash
    q = d.test.q[:6]
    meas = m.measurements(q, **_kw(d.test.subset(np.arange(6))))
    res = compensate(m, q, meas=meas, tol_mm=1e-9)
    assert res.ok.all() and res.error_mm.max() < 1e-9
    from tolalloc.diagnose.compensate import nominal_targets

    np.testing.assert_allclose(res.targets_mm, nominal_targets(m, q), atol=0)
    # without joint values: seeds from the nominal robot's inverse kinematics, then the same targets reached
    free = compensate(m, targets_mm=res.targets_mm, meas=meas, tol_mm=1e-9)
    assert free.ok.all() and free.error_mm.max() < 1e-9
    # the tool chose these joint values, so they stay inside the limits: one row's nominal solution lies on
    # wrist_1's +360 deg limit, which the unclamped compensation left by 0.004 deg
    robot = m.robot
    assert np.isclose(free.q_seed, robot.upper).any()
    assert ((free.q >= robot.lower) & (free.q <= robot.upper)).all()


def test_unreachable_and_joint_limit_rows_are_refused(backlash):
    d, m = backlash
    q = d.test.q[:3]
    meas = m.measurements(q, **_kw(d.test.subset(np.arange(3))))
    x = m.points(meas)
    x[1] *= 5000.0 / np.linalg.norm(x[1])  # far outside the reach
    res = solve_targets(m, x, q, meas)
    assert res.status[0] == res.status[2] == "ok" and res.status[1] == "unreachable"
    assert "mm away at the closest joint values found" in res.reason[1]
    assert res.error_mm[1] > 100
    rob = ROBOT
    lo = rob.q_to_interface(rob.lower)
    assert np.all(lo <= -359)  # the UR10's +-360 deg: move a seed to its limit and ask for a step beyond it
    q_edge = q[:1].copy()
    q_edge[0, 0] = rob.lower[0]
    x_edge = m.points(m.measurements(q_edge + np.array([[-0.01, 0, 0, 0, 0, 0]]), direction=meas.direction[:1]))
    edge = solve_targets(m, x_edge, q_edge, m.measurements(q_edge, direction=meas.direction[:1]))
    assert edge.status == ("joint_limits",)
    assert "shoulder_pan_joint by 0.57" in edge.reason[0]


def test_missing_covariates_are_named(backlash):
    _, m = backlash
    with pytest.raises(TolallocError, match=r"backlash effect \(variant approach\) cannot be evaluated at these poses: "
                                            r"the program has no dir1..dirN"):
        m.measurements(ROBOT.random_q(np.random.default_rng(0), 2))


def test_export_reproduces_the_identified_kinematics(backlash, tmp_path):
    d, m = backlash
    md = MeasurementDiagnosis(d)
    paths = md.export_model(tmp_path / "exp")
    assert [p.name for p in paths] == ["identified.toml", "identified.urdf"]
    q = ROBOT.random_q(np.random.default_rng(5), 50)
    x = m.geometric_points(q)
    exp = tmp_path / "exp"
    for rob in (tolalloc.load_robot(exp / "identified.toml"), load_urdf(exp / "identified.urdf")):
        assert np.abs(rob.fk_internal(q)[:, :3, 3] - x).max() < 1e-9
    section = tomllib.loads((tmp_path / "exp" / "identified.toml").read_text())["identified"]
    assert section["effects"][0]["effect"] == "backlash" and section["effects"][0]["variant"] == "approach"
    back = load_identified(tmp_path / "exp" / "identified.toml")
    meas = m.measurements(d.test.q, **_kw(d.test))
    np.testing.assert_allclose(back.points(meas), m.points(meas), atol=1e-9)
    # the exported file's path predicts the points the model itself does (the nominal robot named in the file), with
    # their uncertainty: the file holds the parameter covariance
    np.testing.assert_allclose(back.cov, m.cov, rtol=1e-12, atol=0)
    assert section["covariance"]["parameters"][:9][-1] == "target_offset:z [mm]"
    assert len(section["covariance"]["parameters"]) == 9 + len(m.fit.geo_index) + len(m.fit.beta)
    q_deg = ROBOT.q_to_interface(d.test.q)
    from_file = predict_frame(exp / "identified.toml", q_deg, dir=d.test.direction)
    assert list(from_file.columns) == ["row", "x_mm", "y_mm", "z_mm", "sigma_mm", "radius95_mm"]
    pd.testing.assert_frame_equal(from_file, predict_frame(m, q_deg, dir=d.test.direction),
                                  check_exact=False, atol=1e-9)
    # a model without its covariance exports none and predicts without the sigma columns
    bare = dataclasses.replace(m, cov=None)
    assert "covariance" not in identified_section(bare)
    nocov = predict_frame(model_from_identified(identified_section(bare), ROBOT), q_deg, dir=d.test.direction)
    assert list(nocov.columns) == ["row", "x_mm", "y_mm", "z_mm"]


def test_an_identified_chain_keeps_its_sub_millimetre_links():
    """Two joint points a calibration pulled a fraction of a millimetre apart are a real link of the identified
    chain, not a length in metres: a file with an ``[identified]`` section loads with it (a plain robot file with the
    same link is still refused as a likely unit slip)."""
    from tolalloc.robot.io.load import robot_from_dict

    data = identified_robot_dict(identified_model(_diagnosis("none", 40, 3, noise_mm=0.001)[2]))
    data["chain"].insert(len(data["chain"]) - 1, {"link": "to_tcp_shift", "vector_mm": [0.0, 0.4, 0.3]})
    robot = robot_from_dict(data, "identified.toml")
    assert any(e.name == "to_tcp_shift" for e in robot.links)
    plain = {k: v for k, v in data.items() if k != "identified"}
    with pytest.raises(TolallocError, match="link to_tcp_shift is 0.5 mm long .* looks like a length in metres"):
        robot_from_dict(plain, "plain.toml")


def test_identified_section_refusals(backlash):
    _, m = backlash
    sec = identified_section(m)
    with pytest.raises(TolallocError, match="it was identified on robot 'ur10', the nominal robot given is "
                                            "'tool_changer'"):
        model_from_identified(sec, tolalloc.load_robot("tool_changer"))
    with pytest.raises(TolallocError, match="expected an \\[identified\\] section with format"):
        model_from_identified({"format": "other"}, ROBOT)
    lag = {**sec, "effects": [{**sec["effects"][0], "effect": "thermal", "variant": "lag_60min"}]}
    with pytest.raises(TolallocError, match=r"thermal effect \(variant lag_60min\) is driven by the training file's "
                                            "history"):
        model_from_identified(lag, ROBOT)
    creep = {**sec, "effects": [{**sec["effects"][0], "effect": "mount_compliance", "variant": "flow"}]}
    with pytest.raises(TolallocError, match=r"mount_compliance effect \(variant flow\) creeps under the load history "
                                            "of the training file"):
        model_from_identified(creep, ROBOT)
    assert identified_robot_dict(m)["identified"]["format"] == sec["format"]


def _cut(text: str, before: str) -> str:
    """``text`` cut at the start of the first line that begins with ``before`` (a file cut short at a line)."""
    lines = text.splitlines(keepends=True)
    return "".join(lines[:next(i for i, ln in enumerate(lines) if ln.startswith(before))])


def test_a_damaged_model_file_is_refused_naming_what_is_wrong(backlash, tmp_path):
    """A file cut short at an entry (still valid TOML: read before as a smaller model, every row "compensated"), a
    missing key, a value that is text or NaN, a rotation that is not one, a unit changed, a robot changed under the
    same name, and a [[chain]] edited apart from the [identified] section: each a clear error, never a model."""
    import tomli_w

    from tolalloc.robot.model import Link

    d, m = backlash
    MeasurementDiagnosis(d).export_model(tmp_path / "exp")
    path = tmp_path / "exp" / "identified.toml"
    text = path.read_text()
    data = tomllib.loads(text)
    assert data["identified"]["n_geometry"] == len(data["identified"]["geometry"]) > 0
    assert "x_tracker = registration_rotation x_base" in data["identified"]["frames"]

    def refused(doc, match, robot=None):
        bad = tmp_path / "bad.toml"
        bad.write_text(doc if isinstance(doc, str) else tomli_w.dumps(doc))
        with pytest.raises(TolallocError, match=match):
            load_identified(bad, robot)

    refused(_cut(text, "geometry = ["), r"0 geometry entries where the section says n_geometry = \d+")
    sec = data["identified"]

    def altered(**changes):
        return {**data, "identified": {k: v for k, v in {**sec, **changes}.items() if v is not None}}

    refused(altered(registration_translation_mm=None), "has no registration_translation_mm; the file is incomplete")
    refused(altered(target_offset_mm=[0.0, 1.0, 2.0, 3.0]),
            r"target_offset_mm: expected an array of shape \(3\), got shape \(4,\)")
    refused(altered(registration_rotation=[[5.0, 0, 0], [0, 1, 0], [0, 0, 1]]), "is not a rotation")
    geo = [dict(g) for g in sec["geometry"]]
    geo[0]["value"] = "abc"
    refused(altered(geometry=geo), r"geometry\[0\].value: expected numbers, got 'abc'")
    geo[0]["value"], geo[0]["unit"] = float("nan"), geo[0]["unit"]
    refused(altered(geometry=geo), r"geometry\[0\].value: expected finite numbers, got nan")
    geo = [dict(g) for g in sec["geometry"]]
    geo[0]["unit"] = "deg" if geo[0]["unit"] == "rad" else "um"
    refused(altered(geometry=geo), r"geometry\[0\] .* is in '(deg|um)'; the parameter's unit is")
    chain = list(ROBOT.chain)
    i = next(k for k, e in enumerate(chain) if isinstance(e, Link) and np.linalg.norm(e.vector_mm) > 300)
    chain[i] = dataclasses.replace(chain[i], vector_mm=np.asarray(chain[i].vector_mm) * 1.01)
    other = dataclasses.replace(ROBOT, chain=tuple(chain))
    refused(text, r"the nominal robot given \('ur10'\) differs from the one the model was identified on", other)
    moved = {**data, "chain": [dict(c) for c in data["chain"]]}
    link = next(c for c in moved["chain"] if "vector_mm" in c and np.linalg.norm(c["vector_mm"]) > 300)
    link["vector_mm"] = [v + 1.0 for v in link["vector_mm"]]
    refused(moved, r"its \[\[chain\]\] and its \[identified\] section give forward kinematics .* mm apart")
    cov = dict(sec["covariance"])
    refused(altered(covariance={**cov, "parameters": cov["parameters"][::-1]}),
            "the covariance's parameters are not the model's")
    matrix = [list(r) for r in cov["matrix"]]
    matrix[0][1] += 1.0
    refused(altered(covariance={**cov, "matrix": matrix}), "covariance.matrix is not a covariance")
    refused(altered(covariance={**cov, "matrix": matrix[:-1]}), r"covariance.matrix: expected an array of shape")


def test_non_finite_or_misshapen_rows_are_input_errors_not_compensated_rows(backlash):
    _, m = backlash
    q = ROBOT.random_q(np.random.default_rng(1), 2) * 0.7
    with pytest.raises(TolallocError, match=r"targets_mm: row 0 is not finite .* 2 such row\(s\)"):
        solve_targets(m, np.array([[np.nan, 0.0, 0.0], [np.inf, 0.0, 0.0]]), q)
    with pytest.raises(TolallocError, match=r"q_program: row 0 is not finite"):
        compensate(m, np.full((1, 6), np.nan))
    with pytest.raises(TolallocError, match=r"q_program: expected rows of 6 joint values \[rad, mm\], got shape"):
        compensate(m, np.zeros((1, 5)))


def test_workflow_predict_compensate_and_plots(backlash, tmp_path):
    d, m = backlash
    md = MeasurementDiagnosis(d)
    q_deg = ROBOT.q_to_interface(d.test.q)
    pred = md.predict(q_deg, dir=d.test.direction, frame="tracker")
    assert list(pred.columns) == ["row", "x_mm", "y_mm", "z_mm", "sigma_mm", "radius95_mm"]
    np.testing.assert_allclose(pred[["x_mm", "y_mm", "z_mm"]].to_numpy(), d.final.test_pred_mm, atol=1e-9)
    assert (pred["radius95_mm"] > pred["sigma_mm"]).all()
    prog = pd.DataFrame(q_deg[:4], columns=[f"q{j}_deg" for j in range(1, 7)])
    for j in range(6):
        prog[f"dir{j + 1}"] = d.test.direction[:4, j]
    res = md.compensate(prog)
    assert res.ok and list(res.to_frame().columns[:7]) == ["row", *prog.columns[:6]]
    assert res.save(tmp_path / "c") == [tmp_path / "c" / "compensated.csv"]
    only = pd.DataFrame(res.compensation.targets_mm, columns=["x_mm", "y_mm", "z_mm"])  # targets without joints
    only[[f"dir{j}" for j in range(1, 7)]] = d.test.direction[:4]
    free = md.compensate(only)
    assert free.ok and free.compensation.error_mm.max() < 1e-6
    assert len(md.plot_where()) >= 3 and res.plot_corrections() is not None
    with pytest.raises(TolallocError, match="frame: expected one of 'base', 'tracker', got 'world'"):
        md.predict(q_deg, dir=d.test.direction, frame="world")
    with pytest.raises(TolallocError, match="targets need all of x_mm, y_mm, z_mm; got only x_mm"):
        md.compensate(prog.assign(x_mm=1.0))
    with pytest.raises(TolallocError, match="expected a MeasurementDiagnosis, an IdentifiedModel or the path"):
        compensate_program(42, prog)


def test_cli_compensate(backlash, tmp_path):
    d, m = backlash
    train = pd.DataFrame(ROBOT.q_to_interface(d.train.q), columns=[f"q{j}_deg" for j in range(1, 7)])
    train[["x_mm", "y_mm", "z_mm"]] = d.train.xyz_mm
    train[[f"dir{j}" for j in range(1, 7)]] = d.train.direction
    train.to_csv(tmp_path / "train.csv", index=False)
    with contextlib.redirect_stdout(io.StringIO()):  # the same diagnosis from the command line, its model exported
        assert main(["diagnose", "ur10", "--train", str(tmp_path / "train.csv"), "--folds", "2", "--export-model",
                     str(tmp_path / "exp")]) == 0
    section = tomllib.loads((tmp_path / "exp" / "identified.toml").read_text())["identified"]
    assert section["nominal_robot"] == "ur10" and section["geometry"]
    q_deg = ROBOT.q_to_interface(d.test.q[:5])
    prog = pd.DataFrame(q_deg, columns=[f"q{j}_deg" for j in range(1, 7)])
    for j in range(6):
        prog[f"dir{j + 1}"] = d.test.direction[:5, j]
    prog[["x_mm", "y_mm", "z_mm"]] = m.points(m.measurements(d.test.q[:5], direction=d.test.direction[:5]))
    prog.loc[2, "x_mm"] += 5000.0
    prog.to_csv(tmp_path / "prog.csv", index=False)
    with contextlib.redirect_stdout(io.StringIO()) as out:
        rc = main(["compensate", str(tmp_path / "exp" / "identified.toml"), str(tmp_path / "prog.csv"), "--out",
                   str(tmp_path / "out")])
    assert rc == 1 and "row 3: unreachable: target not reached" in out.getvalue()
    table = pd.read_csv(tmp_path / "out" / "compensated.csv")
    assert list(table["status"]) == ["ok", "ok", "unreachable", "ok", "ok"] and np.isnan(table["q1_deg"][2])
    np.testing.assert_allclose(table[[f"q{j}_deg" for j in range(1, 7)]].drop(index=2).to_numpy(),
                               np.delete(q_deg, 2, axis=0), atol=1e-6)  # the targets were the model's own points
    with contextlib.redirect_stderr(io.StringIO()) as err:
        rc = main(["compensate", str(tmp_path / "prog.csv"), str(tmp_path / "prog.csv"), "--out", str(tmp_path / "o2")])
    assert rc == 2 and "not valid TOML" in err.getvalue() and not (tmp_path / "o2").exists()


def _with_lag(section: dict) -> dict:
    """``section`` with a thermal history effect appended (two parameters, correlated with the others in the
    covariance): an effect an exported file records but cannot rebuild."""
    lag = {"effect": "thermal", "variant": "lag_60min", "columns": ["lag_a", "lag_b"],
           "fitted_columns": ["lag_a", "lag_b"], "values": [0.01, -0.02]}
    cov = section["covariance"]
    n = len(cov["parameters"])
    C = np.zeros((n + 2, n + 2))
    C[:n, :n] = cov["matrix"]
    C[n:, n:] = [[4e-4, 1e-4], [1e-4, 9e-4]]
    C[n:, :n] = 1e-6 * np.sqrt(np.diag(C)[:n])
    C[:n, n:] = C[n:, :n].T
    return {**section, "effects": [*section["effects"], lag], "n_effects": section["n_effects"] + 1,
            "covariance": {"parameters": [*cov["parameters"], "thermal:lag_a", "thermal:lag_b"],
                           "matrix": C.tolist()}}


def test_a_session_bound_effect_is_left_out_on_request_or_refused(backlash, tmp_path):
    import types

    import tomli_w

    d, m = backlash
    sec = identified_section(m)
    lag = _with_lag(sec)
    with pytest.raises(TolallocError, match=r"thermal effect \(variant lag_60min\) is driven by the training file's "
                                            r"history.*leave the effect out \(without=\('thermal',\); tolalloc "
                                            "compensate --without thermal\\)"):
        model_from_identified(lag, ROBOT)
    whole, left = model_from_identified(sec, ROBOT), model_from_identified(lag, ROBOT, ("thermal",))
    meas = m.measurements(d.test.q, **_kw(d.test))
    np.testing.assert_array_equal(left.points(meas), whole.points(meas))
    np.testing.assert_array_equal(left.cov, whole.cov)  # the kept parameters' block
    assert left.ref["left_out"] == {"thermal": "lag_60min"} and not whole.ref["left_out"]
    with pytest.raises(TolallocError, match="cannot leave out 'mount_compliance': the file's effects are backlash, "
                                            "thermal"):
        model_from_identified(lag, ROBOT, ("thermal", "mount_compliance"))

    data = identified_robot_dict(m)
    path = tmp_path / "identified.toml"
    path.write_text(tomli_w.dumps({**data, "identified": lag}))
    prog = pd.DataFrame(ROBOT.q_to_interface(d.test.q[:3]), columns=[f"q{j}_deg" for j in range(1, 7)])
    prog[[f"dir{j}" for j in range(1, 7)]] = d.test.direction[:3]
    with pytest.raises(TolallocError, match="tolalloc compensate --without thermal"):
        compensate_program(path, prog)
    res = compensate_program(path, prog, without="thermal")
    assert res.ok and res.summary()["inputs"]["left_out"] == {"thermal": "lag_60min"}
    assert "left out of the model: thermal (lag_60min): its part of the error is not compensated" in res.text()
    np.testing.assert_allclose(res.to_frame()[prog.columns[:6]].to_numpy(),
                               compensate_program(m, prog).to_frame()[prog.columns[:6]].to_numpy(), atol=1e-9)
    prog.to_csv(tmp_path / "prog.csv", index=False)
    with contextlib.redirect_stdout(io.StringIO()) as out:
        rc = main(["compensate", str(path), str(tmp_path / "prog.csv"), "--out", str(tmp_path / "out"),
                   "--without", "thermal"])
    assert rc == 0 and "left out of the model: thermal (lag_60min)" in out.getvalue()
    with pytest.raises(TolallocError, match="without: leaves effects out of an exported identified.toml"):
        compensate_program(m, prog, without="thermal")
    with pytest.raises(TolallocError, match="without: expected an effect name or a sequence of them"):
        predict_frame(path, d.test.q[:2], without=3)

    # the diagnosis says which of its final model's effects an exported file cannot carry
    assert MeasurementDiagnosis(d).export_notes() == []
    bound = dataclasses.replace(m, effects=("thermal", "mount_compliance"),
                                variants={"thermal": "lag_60min", "mount_compliance": "creep_30min"})
    notes = MeasurementDiagnosis.export_notes(types.SimpleNamespace(identified_model=lambda: bound))
    assert len(notes) == 2 and "compensate --without mount_compliance" in notes[1]
    assert notes[0].startswith("identified.toml: its thermal effect (variant lag_60min) is driven by the training "
                               "file's history")
