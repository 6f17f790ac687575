"""Bought parts in the ISO 9283 acceptance test (tolalloc.acceptance.parts): the covariance over the test poses
against physical draws through the robot's own forward kinematics, the means against the kinematics of the deflected
joints, lost motion seen by the accuracy and not by the repeatability, and the refusals."""

import copy
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tolalloc.acceptance import PoseAccuracy, PoseRepeatability, predict_acceptance
from tolalloc.acceptance.parts import effect_covariance, parts_effects
from tolalloc.acceptance.simulate import simulate_acceptance
from tolalloc.calibration.split import split_errors
from tolalloc.errormodel import build_error_model
from tolalloc.errormodel.parts import PartEffects, with_parts
from tolalloc.exceptions import TolallocError
from tolalloc.physics.compliance import mount_tilt
from tolalloc.physics.transmission import catalogue_amplitudes, transmission_error
from tolalloc.robot.components import JointComponents, Mount, Reducer
from iso_setup import ur10_test

ARCMIN = np.deg2rad(1 / 60)


def _resolved():
    robot, test = ur10_test()
    return with_parts(robot, {k: s.options[0].name for k, s in robot.components.slots.items()}), test


def _only(robot, joints=None, mount=None, links=False):
    """``robot`` whose components are only ``joints`` ({name: JointComponents}), ``mount`` and, with ``links``, its
    link sections (the payload rating kept)."""
    comps = replace(robot.components, joints=dict(joints or {}), mount=mount or Mount(), slots={},
                    links=robot.components.links if links else {})
    out = copy.copy(robot)
    object.__setattr__(out, "components", comps)
    return out


def _pose_error(robot, q, dq):
    """Position [mm] and rotation [rad] error (..., 6) of joint offsets ``dq`` (n, P, J) from the forward
    kinematics: the tool point's move and the rotation vector of ``R(q + dq) R(q)^T``."""
    T0 = robot.fk_internal(q)
    n, P = dq.shape[:2]
    T = robot.fk_internal((q[None] + dq).reshape(n * P, -1)).reshape(n, P, 4, 4)
    dp = T[..., :3, 3] - T0[None, :, :3, 3]
    R = np.einsum("npab,pcb->npac", T[..., :3, :3], T0[:, :3, :3])
    return np.concatenate([dp, Rotation.from_matrix(R.reshape(-1, 3, 3)).as_rotvec().reshape(n, P, 3)], axis=-1)


def test_gear_error_covariance_over_the_poses_is_that_of_physical_draws():
    """A strain-wave gear's kinematic error (orders 1, N, 2N at random phases) on the shoulder and elbow: the joint
    covariance over the test's poses equals that of 12 000 robots drawn physically and moved through the forward
    kinematics (including the pairs of poses, which a per-pose model does not give)."""
    robot, test = _resolved()
    red = Reducer(ratio=100.0, transmission_accuracy=1.0 * ARCMIN)
    names = ("shoulder_lift_joint", "elbow_joint")
    r = _only(robot, {nm: JointComponents(reducer=red) for nm in names})
    q = np.vstack([test.q_test, test.q_registration[:3]])
    eff = effect_covariance(r, q, 0.0)
    rng = np.random.default_rng(3)
    n = 12_000
    dq = np.zeros((n, len(q), r.n_joints))
    orders, amps = catalogue_amplitudes(red.transmission_accuracy, red.ratio)
    for nm in names:
        j = [jt.name for jt in r.joints].index(nm)
        phases = rng.uniform(0, 2 * np.pi, (n, len(orders)))
        dq[:, :, j] = np.stack([transmission_error(np.full(n, qm), orders, amps, phases) for qm in q[:, j]], axis=1)
    x = _pose_error(r, q, dq).reshape(n, -1)
    emp = np.cov(x, rowvar=False)
    sd = np.sqrt(np.diag(eff.systematic)) + 1e-6 * np.sqrt(np.max(np.diag(eff.systematic)))
    err = np.abs(eff.systematic - emp) / np.outer(sd, sd)       # in units of the correlation
    assert np.max(err) < 0.07, np.unravel_index(np.argmax(err), err.shape)
    assert np.allclose(eff.mean, 0.0) and np.allclose(eff.random, 0.0)
    # poses apart in the elbow angle are correlated as the cosine of their phase difference, not independently
    off_diag = eff.systematic[:6, 6:12]
    assert np.linalg.norm(off_diag) > 0.05 * np.linalg.norm(eff.systematic[:6, :6])


def test_means_are_the_kinematics_of_the_wound_up_joints_and_the_tilted_mount():
    """Linear reducer stiffness at 100 % of the rated load: the mean pose error is the forward kinematics with every
    joint wound up by its torque over its stiffness (position and rotation); a mount's tilt turns the tool by the
    same rotation that moves every point ``theta x d``."""
    robot, test = _resolved()
    red = Reducer(ratio=100.0, stiffness=(2.0e5,))
    r = _only(robot, {jt.name: JointComponents(reducer=red) for jt in robot.joints})
    q = test.q_test
    eff = effect_covariance(r, q, 100.0)
    fx = PartEffects(r, q, robot.components.payload.rated_kg, 20.0)
    w = fx.tau / 2.0e5                                                 # (P, J) wind-up [rad]
    want = _pose_error(r, q, w[None])[0]
    np.testing.assert_allclose(eff.mean.reshape(-1, 6), want, rtol=2e-3, atol=1e-7)
    assert np.max(np.abs(want[:, :3])) > 0.05                           # a visible mean: > 50 um
    # the arm's own weight winds the joints up at no load; the payload adds in proportion (linear stiffness)
    half, none = (effect_covariance(r, q, pct).mean for pct in (50.0, 0.0))
    np.testing.assert_allclose(half, (none + eff.mean) / 2, atol=1e-9)
    assert np.linalg.norm(eff.mean - none) > 0.1 * np.linalg.norm(eff.mean)

    m = _only(robot, mount=Mount((1.0e6, 1.0e6)))
    mean = effect_covariance(m, q, 100.0).mean.reshape(-1, 6)
    fxm = PartEffects(m, q, robot.components.payload.rated_kg, 20.0, rotations=True)
    other = fxm.tool + np.array([150.0, -80.0, 40.0])
    moved = mount_tilt(m, q, other, fxm.payload_point, fxm.payload)
    np.testing.assert_allclose(moved - mean[:, :3], np.cross(mean[:, 3:], other - fxm.tool), rtol=1e-6, atol=1e-9)
    assert np.all(np.linalg.norm(mean[:, 3:], axis=1) > 0)


def _design(robot):
    names = [p.name for p in build_error_model(robot).params if p.kind != "joint_drive"]
    model = build_error_model(robot, exclude=tuple(names)).with_sigma(np.full(robot.n_joints, np.deg2rad(1e-5)))
    return model, split_errors(model)


def test_lost_motion_is_seen_by_the_accuracy_and_not_by_the_repeatability():
    """The test approaches each pose the same way every cycle: a gear's lost motion is an offset of the pose (the
    accuracy grows with it) and the cycles repeat it (the repeatability does not move); a gear's repeatability is
    new at every move (the repeatability grows)."""
    robot, test = _resolved()
    reqs = [PoseAccuracy(limit_mm=1.0), PoseRepeatability(limit_mm=1.0)]
    out = {}
    for name, red in (("none", None), ("lost", Reducer(ratio=100.0, lost_motion=2 * ARCMIN)),
                      ("repeat", Reducer(ratio=100.0, repeatability=0.2 * ARCMIN))):
        r = _only(robot, {jt.name: JointComponents(reducer=red) for jt in robot.joints} if red else {})
        model, split = _design(r)
        t = replace(test, robot=r)
        frame = predict_acceptance(t, reqs, model, split, effects=parts_effects()).to_frame().set_index(
            ["statistic", "where"])["robot_mm"]
        out[name] = frame
    ap, rp = ("AP_P", "P1"), ("RP_l", "P1")
    assert out["lost"][ap] > 5 * out["none"][ap] and out["lost"][rp] == pytest.approx(out["none"][rp], rel=1e-6)
    assert out["repeat"][rp] > 5 * out["none"][rp]


def test_simulated_test_with_parts_agrees_with_the_prediction():
    """The catalogue parts of the UR10 (means, gears, bearings, links, mount): the test simulated on 2000 robots
    agrees with the prediction within its confidence interval (AP and RP at every pose)."""
    robot, test = _resolved()
    model, split = _design(robot)
    t = replace(test, robot=robot)
    reqs = [PoseAccuracy(limit_mm=0.5), PoseRepeatability(limit_mm=0.1)]
    pred = predict_acceptance(t, reqs, model, split, effects=parts_effects()).to_frame().set_index(
        ["statistic", "where"])
    sim = simulate_acceptance(t, reqs, model, split, effects=parts_effects(), n_robots=2000, seed=4).to_frame(
        ).set_index(["statistic", "where"])
    inside = (sim["robot_low"] * 0.98 <= pred["robot_mm"]) & (pred["robot_mm"] <= sim["robot_high"] * 1.02)
    assert inside.all(), pd_text(pred, sim)
    assert pred.loc[("AP_P", "P1"), "robot_mm"] > 0.1          # the parts are visible: 0.47 mm at P1


def pd_text(pred, sim):
    return f"{pred['robot_mm'].to_dict()} vs {sim[['robot_low', 'robot_high']].to_dict()}"


def test_refusals_name_what_to_do():
    robot, test = ur10_test()
    with pytest.raises(TolallocError, match="hold no chosen part.*with_parts"):
        effect_covariance(robot, test.q_test, 100.0)
    r, _ = _resolved()
    unrated = copy.copy(r)
    object.__setattr__(unrated, "components", replace(r.components, payload=replace(r.components.payload,
                                                                                      rated_kg=None)))
    with pytest.raises(TolallocError, match="rated_kg, or test at load_pct = 0"):
        effect_covariance(unrated, test.q_test, 100.0)
    assert effect_covariance(unrated, test.q_test, 0.0).systematic.shape == (30, 30)
    with pytest.raises(TolallocError, match="duty"):
        parts_effects(duty=1.5)
    with pytest.raises(TolallocError, match="ambient_c"):
        parts_effects(ambient_c=float("nan"))


def test_an_incremental_encoders_homing_is_kept_through_the_test_and_random_to_the_design(tmp_path):
    """``homing_repeatability_arcsec`` (incremental encoders only): the zero falls in +-h at each power-up. The parts
    model counts it as random (no calibration removes it; the Monte Carlo draws it uniform), the acceptance test,
    run in one power cycle, as a zero every pose of a robot shares: AP in the robot's base frame sees it, RP does
    not."""
    from parts_robot import arm
    from tolalloc.errormodel.parts_sample import sample_effects

    enc = 'encoder = { side = "motor", homing = "incremental", homing_repeatability_arcsec = 3 }'
    r = arm(tmp_path, f"[components.joints.j3]\n{enc}\n")
    h = np.deg2rad(3 / 3600)
    assert r.components.joint("j3").encoder.homing_repeatability == pytest.approx(h)
    with pytest.raises(ValueError, match='homing_repeatability: an absolute encoder.*homing = "incremental"'):
        arm(tmp_path, "[components.joints.j3]\n" + enc.replace('"incremental"', '"absolute"') + "\n", "bad.toml")
    r = with_parts(r, {k: slot.options[0].name for k, slot in r.components.slots.items()})
    fx = PartEffects(r, np.array([[0.1, -0.2, 0.3]]), 0.0, 20.0)
    row = fx.terms().to_frame().set_index("term").loc["homing_j3"]
    col = np.linalg.norm(fx.J[0, :, fx.pm.drive[2]])
    assert row["effect"] == "homing" and row["random_sd_mm"] == pytest.approx(h / np.sqrt(3) * col)
    assert row["systematic_sd_mm"] == 0 and row["mean_mm"] == 0
    values, _ = sample_effects(fx, 0, 40_000, np.random.default_rng(5))
    j3 = values[:, fx.pm.drive[2]]                              # j3 has no reducer: its zero only
    assert np.max(np.abs(j3)) <= h and np.std(j3) == pytest.approx(h / np.sqrt(3), rel=0.02)

    robot, test = _resolved()
    homed = Reducer(ratio=100.0)
    incremental = replace(robot.components.joint("wrist_1_joint").encoder, homing="incremental",
                          homing_repeatability=20 * np.deg2rad(1 / 3600), accuracy=None)
    reqs = [PoseAccuracy(limit_mm=1.0), PoseRepeatability(limit_mm=1.0)]
    out = {}
    for name, joints in (("none", {}), ("homed", {"wrist_1_joint": JointComponents(reducer=homed,
                                                                                   encoder=incremental)})):
        rr = _only(robot, joints)
        model, split = _design(rr)
        for reg in ("corners", "none"):
            t = replace(test, robot=rr, registration=reg)
            out[name, reg] = predict_acceptance(t, reqs, model, split, effects=parts_effects()).to_frame(
                ).set_index(["statistic", "where"])["robot_mm"]
        if joints:
            eff = effect_covariance(rr, test.q_test, 100.0)
            assert np.allclose(eff.random, 0) and np.linalg.norm(eff.systematic[:6, 6:12]) > 0   # shared by the poses
    ap, rp = ("AP_P", "P1"), ("RP_l", "P1")
    # measured in the robot's base frame (no registration) the zero shows in AP; registered on the cube's corners,
    # the same zero at every pose of a small cube is nearly a rigid shift, which the registration takes out
    assert out["homed", "none"][ap] > 3 * out["none", "none"][ap]
    assert out["homed", "corners"][ap] == pytest.approx(out["none", "corners"][ap], rel=0.05)
    for reg in ("corners", "none"):
        assert out["homed", reg][rp] == pytest.approx(out["none", reg][rp], rel=1e-6)


@pytest.fixture(scope="module")
def ur10_drives():
    robot, test = ur10_test()
    others = tuple(p.name for p in build_error_model(robot).params if p.kind != "joint_drive")
    choice = {k: s.options[0].name for k, s in robot.components.slots.items()}
    return robot, test, others, choice


def _allocate(ur10_drives, ap_mm, parts, n_robots=300):
    import tolalloc

    robot, test, others, _ = ur10_drives
    return tolalloc.allocate_acceptance(robot, [PoseAccuracy(limit_mm=ap_mm), PoseRepeatability(limit_mm=0.12)],
                                        error_model=tolalloc.ErrorModelOptions(exclude=others), test=test,
                                        solver=tolalloc.Solver(snap=False), n_robots=n_robots, parts=parts)


def test_the_acceptance_allocation_budgets_the_bought_parts(ur10_drives):
    """``allocate_acceptance(parts=...)``: the parts' covariances enter the constraints and their mean shortens the
    limit, so the design the allocation returns meets the requirement under the exact law with the mean (the
    prediction) and in the simulated test; the parts show in RP; too coarse parts are named as the cause."""
    choice = ur10_drives[3]
    without, with_parts_ = _allocate(ur10_drives, 0.6, None), _allocate(ur10_drives, 0.6, choice)
    assert without.ok and with_parts_.ok
    pred = with_parts_.prediction.to_frame().set_index(["statistic", "where"])
    assert (pred["p_meets"] >= 0.95 - 1e-6).all()
    assert with_parts_.simulation.to_frame()["p_meets"].min() >= 0.93          # 300 robots
    rp = ("RP_l", "P1")
    assert pred.loc[rp, "robot_mm"] > 2 * without.prediction.to_frame().set_index(["statistic", "where"]).loc[
        rp, "robot_mm"]
    assert with_parts_.inputs["parts"]["elbow_joint.reducer"] == "HD-CSG-32-100" and without.inputs["parts"] is None
    assert "bought parts in the test" in with_parts_.text() and "HD-CSG-32-100" in with_parts_.text()
    assert "bought parts" not in without.text()
    tight = _allocate(ur10_drives, 0.52, choice, n_robots=2)
    assert not tight.ok and _allocate(ur10_drives, 0.52, None, n_robots=2).ok
    assert "bought parts' mean error" in tight.text() and "choose finer parts" in tight.text()
    with pytest.raises(TolallocError, match="mean error alone .* reaches the limit 0.05 mm"):
        _allocate(ur10_drives, 0.05, choice, n_robots=2)
    with pytest.raises(TolallocError, match="parts: expected a choice"):
        _allocate(ur10_drives, 0.6, 32, n_robots=2)


def test_the_parts_a_design_chose_carry_over_to_the_acceptance_job(ur10_drives, tmp_path):
    """The parts of a design with bought parts -- its result, the parts.csv it saved or that table -- are the
    acceptance job's choice, the same as the dict; ``parts=True`` where the robot file offers options, and a parts
    table that names no choice, are refused with what to do."""
    import pandas as pd

    import tolalloc
    from tolalloc.workflows.parts import PartsToleranceAllocation

    choice = ur10_drives[3]
    table = pd.DataFrame([{"joint": j, "kind": k, "part": p, "family": "x", "cost": 1.0} for (j, k), p in
                          choice.items()])
    table.to_csv(tmp_path / "parts.csv", index=False)
    design = PartsToleranceAllocation(result=SimpleNamespace(choice=choice), radius_mm=0.75, prob=0.95, label="box")
    ref = _allocate(ur10_drives, 0.6, choice, n_robots=2)
    for source in (tmp_path / "parts.csv", str(tmp_path / "parts.csv"), design, table):
        res = _allocate(ur10_drives, 0.6, source, n_robots=2)
        assert res.cost == pytest.approx(ref.cost, rel=1e-9) and res.inputs["parts"] == ref.inputs["parts"]
    with pytest.raises(tolalloc.ArgumentError, match=r"^parts: robot 'ur10' offers a choice in \d+ catalogue slot\(s\) "
                                                     r"no part is named for: .*The ISO 9283 job does not choose parts"):
        _allocate(ur10_drives, 0.6, True, n_robots=2)
    table.iloc[:1].assign(part="other").pipe(lambda t: pd.concat([table, t])).to_csv(tmp_path / "twice.csv",
                                                                                     index=False)
    table.drop(columns="part").to_csv(tmp_path / "nopart.csv", index=False)
    for name, message in (("twice.csv", "is chosen twice"), ("nopart.csv", "missing part")):
        with pytest.raises(tolalloc.ArgumentError, match=f"^parts: .*{message}"):
            _allocate(ur10_drives, 0.6, tmp_path / name, n_robots=2)
    with pytest.raises(tolalloc.InputFileError, match=r"^parts: '.*absent.csv' does not exist; expected the parts.csv"):
        _allocate(ur10_drives, 0.6, tmp_path / "absent.csv", n_robots=2)


def test_the_command_line_passes_the_parts_to_the_acceptance_job(monkeypatch, capsys, tmp_path):
    """``allocate --requirement FILE``: ``--part JOINT.KIND=NAME`` (repeated) is the choice, ``--parts`` alone the
    robot file's parts; malformed parts, the design's conditions and ``--part`` without a requirement file are
    refused (exit 2)."""
    from pathlib import Path

    import tolalloc.workflows.acceptance as job
    from tolalloc.cli import main

    seen = []

    class Result:
        ok, prediction = True, None

        def text(self):
            return "stub"

    monkeypatch.setattr(job, "allocate_acceptance", lambda *a, **kw: seen.append(kw) or Result())
    req = str(Path(__file__).resolve().parents[1] / "examples" / "requirements_iso9283.toml")
    base = ["allocate", "ur10", "--requirement", req]
    assert main(base + ["--part", "elbow_joint.encoder=RING-100-STD", "--part",
                        "shoulder_lift_joint.encoder=RING-100-PREC"]) == 0
    assert seen[-1]["parts"] == {("elbow_joint", "encoder"): "RING-100-STD",
                                 ("shoulder_lift_joint", "encoder"): "RING-100-PREC"}
    assert main(base + ["--parts"]) == 0 and seen[-1]["parts"] is True
    assert main(base) == 0 and seen[-1]["parts"] is None
    capsys.readouterr()
    for extra, message in ((["--part", "elbow_joint=RING"], "JOINT.KIND=NAME"),
                           (["--parts", "--payload-kg", "0", "5"], "does not apply to --requirement")):
        assert main(base + extra) == 2 and message in capsys.readouterr().err
    assert main(["allocate", "ur10", "--part", "elbow_joint.encoder=RING-100-STD"]) == 2
    assert "applies to --requirement" in capsys.readouterr().err
    assert len(seen) == 3
    # --parts-file: a design's parts.csv, --part overriding one of its slots
    (tmp_path / "parts.csv").write_text("joint,kind,part,cost\nelbow_joint,encoder,RING-100-STD,3\n"
                                        "elbow_joint,bearing,ISO492-P5,2\n")
    assert main(base + ["--parts-file", str(tmp_path / "parts.csv"), "--part", "elbow_joint.bearing=ISO492-P4"]) == 0
    assert seen[-1]["parts"] == {("elbow_joint", "encoder"): "RING-100-STD", ("elbow_joint", "bearing"): "ISO492-P4"}
    capsys.readouterr()
    assert main(["allocate", "ur10", "--parts-file", str(tmp_path / "parts.csv")]) == 2
    assert "error: --parts-file: applies to --requirement" in capsys.readouterr().err
    assert main(base + ["--parts-file", str(tmp_path / "none.csv")]) == 2
    assert "error: --parts-file: " in capsys.readouterr().err and len(seen) == 4
