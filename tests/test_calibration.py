"""Post-calibration covariance: limits (perfect and empty plans), a closed-form planar 2R case, bad input."""

import numpy as np
import pytest

from tolalloc.calibration import make_plan, posterior, read_plan, split_errors, write_plan
from tolalloc.errormodel import build_error_model
from tolalloc.exceptions import TolallocError
from tolalloc.linear.covariance import linear_map
from tolalloc.robot.io import load_robot

PLANAR = """name = "planar2r"
[[chain]]
joint = "j1"
type = "revolute"
axis = [0, 0, 1]
limits_deg = [-180, 180]
[[chain]]
link = "l1"
vector_mm = [400, 0, 0]
[[chain]]
joint = "j2"
type = "revolute"
axis = [0, 0, 1]
limits_deg = [-180, 180]
[[chain]]
link = "l2"
vector_mm = [300, 0, 0]
"""


@pytest.fixture(scope="module")
def tc():
    return load_robot("tool_changer")


@pytest.fixture(scope="module")
def planar(tmp_path_factory):
    path = tmp_path_factory.mktemp("robot") / "planar2r.toml"
    path.write_text(PLANAR, encoding="utf-8")
    return load_robot(str(path))


def random_poses(robot, n, seed):
    rng = np.random.default_rng(seed)
    return robot.lower + (robot.upper - robot.lower) * rng.random((n, robot.n_joints))


def test_empty_plan_equals_todays_covariance(tc):
    model = build_error_model(tc, clearance=True)
    split = split_errors(model, {"kinds": {"joint_drive": {"repeatability_deg": 0.0},
                                           "joint_drive_prismatic": {"repeatability_mm": 0.0}}})
    post = posterior(split, make_plan(tc, np.zeros((0, tc.n_joints))))
    q = random_poses(tc, 20, 1)
    np.testing.assert_allclose(post.tool_covariance(q), linear_map(model, q).cov_mm2, rtol=1e-12, atol=1e-15)


def test_perfect_plan_leaves_the_random_part(tc):
    """Noise -> 0, full-pose measurements at many poses, only identifiable parameters estimated."""
    small = {"axial_mm": 0.002, "radial_mm": 0.003, "tilt_rad": 1e-5}  # random parts well below the systematic
    model = build_error_model(tc, clearance=True, clearance_sigma=small)
    split = split_errors(model)
    q = random_poses(tc, 40, 2)
    probe = posterior(split, make_plan(tc, q, measurement="pose", registration=False), random_noise=False)
    ident = [model.names[k] for k in probe.estimated if model.names[k] not in probe.unidentifiable]
    # parameters left out: zero prior, so "all systematic identifiable" holds for the rest
    zero = {nm: 0.0 for nm in model.names if split.systematic[model.index(nm)] and nm not in ident}
    model0 = build_error_model(tc, clearance=True, clearance_sigma=small, sigma=zero)
    split0 = split_errors(model0)
    plan = make_plan(tc, q, measurement="pose", noise_mm=1e-9, noise_deg=1e-11, registration=False, estimate=ident)
    post = posterior(split0, plan, random_noise=False)
    qe = random_poses(tc, 30, 3)
    J = model0.jacobian(qe)[:, :3, :]
    random_only = J @ np.diag(split0.random_variance()) @ np.swapaxes(J, 1, 2)
    prior = linear_map(model0, qe).cov_mm2
    assert np.all(np.trace(prior, axis1=1, axis2=2) > 10 * np.trace(random_only, axis1=1, axis2=2))
    np.testing.assert_allclose(post.tool_covariance(qe), random_only, rtol=1e-6, atol=1e-9)


def test_planar_2r_posterior_closed_form(planar):
    """Link lengths only: per pose the information is [[1, cos t2], [cos t2, 1]] / s^2 (unit link directions)."""
    model = build_error_model(planar, sigma={"dl1": 0.05, "dl2": 0.03}, exclude=("joint_drive", "axis_deflection"))
    assert model.names == ["dl1", "dl2"]
    split = split_errors(model)
    t2 = np.deg2rad([25.0, 140.0])
    q = np.column_stack([np.deg2rad([10.0, -70.0]), t2])
    s = 0.01
    post = posterior(split, make_plan(planar, q, noise_mm=s, registration=False))
    c = np.cos(t2).sum()
    lam = np.diag([1 / 0.05**2, 1 / 0.03**2]) + np.array([[2, c], [c, 2]]) / s**2
    np.testing.assert_allclose(post.cov_sys, np.linalg.inv(lam), rtol=1e-10)
    assert post.unidentifiable == ()


def test_planar_2r_a_optimal_two_pose_plan(planar):
    """trace S_post over (t2a, t2b) is smallest where cos t2a + cos t2b = 0 (equal priors): closed form."""
    model = build_error_model(planar, sigma={"dl1": 0.04, "dl2": 0.04}, exclude=("joint_drive", "axis_deflection"))
    split = split_errors(model)
    grid = np.deg2rad(np.arange(0.0, 181.0, 15.0))
    best, best_c = np.inf, None
    for a in grid:
        for b in grid:
            q = np.array([[0.0, a], [0.3, b]])
            tr = np.trace(posterior(split, make_plan(planar, q, noise_mm=0.01, registration=False)).cov_sys)
            if tr < best - 1e-15:
                best, best_c = tr, np.cos(a) + np.cos(b)
    assert abs(best_c) < 1e-12
    lam = 1 / 0.04**2 + 2 / 0.01**2
    assert best == pytest.approx(2 / lam, rel=1e-10)


def test_registration_hides_base_rotation(tc):
    model = build_error_model(tc)
    post = posterior(split_errors(model), make_plan(tc, random_poses(tc, 30, 4)))
    assert "dth1" in post.unidentifiable  # a base-joint offset is a rotation of the tracker frame
    k = model.index("dth1")
    assert post.sigma_post[k] == pytest.approx(model.sigma[k], rel=1e-9)  # keeps its prior
    assert post.sigma_post[model.index("dth2")] < 0.01 * model.sigma[model.index("dth2")]


def test_few_measurements_name_the_unidentifiable(tc):
    model = build_error_model(tc)
    post = posterior(split_errors(model), make_plan(tc, random_poses(tc, 3, 5)))  # 9 rows for 22 + 9 unknowns
    assert len(post.unidentifiable) >= 22 - 9
    assert np.all(post.sigma_post <= model.sigma * (1 + 1e-12))


def test_split_and_posterior_frames_give_each_sigma_in_its_rows_unit(tc):
    model = build_error_model(tc, clearance=True)
    split = split_errors(model)
    post = posterior(split, make_plan(tc, random_poses(tc, 12, 6)))
    for frame, names in ((split.to_frame(), ("sigma_sys", "sigma_random")),
                         (post.to_frame(), ("sigma_prior", "sigma_post", "sigma_random"))):
        mm = frame["unit"] == "mm"
        for name in names:
            assert name not in frame and frame[f"{name}_mm"][~mm].isna().all() and frame[f"{name}_deg"][mm].isna().all()
        row = frame.set_index("parameter")
        # a length (link, mm) and an angle (joint drive, deg; repeatability 0.0003 deg by default)
        assert row.loc["dl3", "sigma_random_mm"] == 0.0 and row.loc["dth2", "sigma_random_deg"] == pytest.approx(0.0003)
        assert row.loc["ca1", "sigma_random_mm"] == pytest.approx(model.sigma[model.index("ca1")])  # random only
    s, p = split.to_frame().set_index("parameter"), post.to_frame().set_index("parameter")
    assert s.loc["dl3", "sigma_sys_mm"] == pytest.approx(model.sigma[model.index("dl3")])
    assert s.loc["dth2", "sigma_sys_deg"] == pytest.approx(np.rad2deg(model.sigma[model.index("dth2")]))
    k, j = model.index("dl3"), model.index("dth2")
    assert p.loc["dl3", "sigma_post_mm"] == pytest.approx(post.sigma_post[k])
    assert p.loc["dth2", "sigma_post_deg"] == pytest.approx(np.rad2deg(post.sigma_post[j]))
    assert p.loc["dth2", "sigma_prior_deg"] == pytest.approx(np.rad2deg(np.sqrt(post.prior_var[j])))


def test_bad_input(tc, tmp_path):
    model = build_error_model(tc, clearance=True)
    q = random_poses(tc, 5, 6)
    for bad in (np.nan, -0.1, 0.0, "x"):
        with pytest.raises(TolallocError, match="noise_mm"):
            make_plan(tc, q, noise_mm=bad)
    with pytest.raises(TolallocError, match="outside its limits"):
        make_plan(tc, q + 10.0)
    with pytest.raises(TolallocError, match="unknown parameter 'nope'"):
        posterior(split_errors(model), make_plan(tc, q, estimate=["nope"]))
    with pytest.raises(TolallocError, match="no systematic part"):
        posterior(split_errors(model), make_plan(tc, q, estimate=["ca1"]))
    with pytest.raises(TolallocError, match="unknown error parameter 'zz'"):
        split_errors(model, {"parameters": {"zz": {"systematic": True}}})
    with pytest.raises(TolallocError, match="repeatability_deg"):
        split_errors(model, {"parameters": {"dth1": {"repeatability_mm": 0.1}}})
    path = tmp_path / "plan.csv"
    write_plan(make_plan(tc, q, noise_mm=0.03), tc, path)
    back = read_plan(path, tc)
    np.testing.assert_allclose(back.q, q, atol=1e-9)
    assert back.noise_mm == 0.03
    path.write_text(path.read_text().replace("# noise_mm = 0.03", "# noise_mm = -1"))
    with pytest.raises(TolallocError, match="noise_mm"):
        read_plan(path, tc)


def test_planar_2r_designed_plan_is_the_closed_form_optimum(planar):
    """With a task weight W = I (evaluation poses at t2 = +-90 deg) the A-optimal 2-pose plan has
    cos t2a + cos t2b = 0 and trace S_post = 2 / (1/s0^2 + 2/s^2); the designer must find one among the candidates."""
    from tolalloc.calibration.design import design_plan

    model = build_error_model(planar, sigma={"dl1": 0.04, "dl2": 0.04}, exclude=("joint_drive", "axis_deflection"))
    split = split_errors(model, {"kinds": {"joint_drive": {"repeatability_deg": 0.0}}})
    t2 = np.deg2rad(np.arange(0.0, 181.0, 15.0))
    cand = np.column_stack([np.deg2rad(np.linspace(-60, 60, len(t2))), t2])
    q_eval = np.deg2rad([[0.0, 90.0], [30.0, -90.0]])
    d = design_plan(split, 2, cand, q_eval, noise_mm=0.01, registration=False)
    assert abs(np.cos(d.plan.q[:, 1]).sum()) < 1e-12
    post = posterior(split, d.plan)
    assert np.trace(post.cov_sys) == pytest.approx(2 / (1 / 0.04**2 + 2 / 0.01**2), rel=1e-10)
    assert d.relaxation_bound_mm2 <= d.score_mm2 * (1 + 1e-9)


def test_floor_splits_into_the_unidentifiable_part_and_noise(planar):
    """Candidates all at t2 = 0: dl1 and dl2 push the tool along the same line, so only dl1 + dl2 is identifiable.
    With equal priors s0 the part of the floor no candidate identifies is ``s0^2 mean |J n|^2`` over the evaluation
    poses, n = (1, -1) / sqrt(2); it does not depend on the noise, and the floor falls to it as the noise goes."""
    from tolalloc.calibration.design import design_plan

    s0 = 0.04
    model = build_error_model(planar, sigma={"dl1": s0, "dl2": s0}, exclude=("joint_drive", "axis_deflection"))
    split = split_errors(model, {"kinds": {"joint_drive": {"repeatability_deg": 0.0}}})
    cand = np.column_stack([np.deg2rad(np.linspace(-60, 60, 9)), np.zeros(9)])
    q_eval = np.deg2rad([[0.0, 90.0], [30.0, -45.0]])
    n = np.array([1.0, -1.0]) / np.sqrt(2)
    J = model.jacobian(q_eval)[:, :3, :]
    null_floor = s0**2 * np.mean(np.sum((J @ n) ** 2, axis=1))
    no_cal = s0**2 * np.mean(np.sum(J**2, axis=(1, 2)))
    floors = []
    for noise in (0.01, 1e-3):
        d = design_plan(split, 2, cand, q_eval, noise_mm=noise, registration=False)
        assert d.floor_unidentifiable_mm2 == pytest.approx(null_floor, rel=1e-9)
        assert d.no_calibration_mm2 == pytest.approx(no_cal, rel=1e-12)
        assert null_floor < d.floor_mm2 <= d.score_mm2 < no_cal
        floors.append(d.floor_mm2 - null_floor)
    assert floors[1] < 0.02 * floors[0]  # the noise part shrinks with the noise variance (x 0.01)


def test_plan_poses_of_another_width_and_plans_of_another_robot_are_refused():
    """make_plan names the joint count (it was a numpy reshape error); posterior refuses a plan made for another
    robot (it computed a posterior at that robot's poses without a word)."""
    ur10, tc = load_robot("ur10"), load_robot("tool_changer")
    with pytest.raises(TolallocError, match=r"calibration poses: robot 'ur10' has 6 joints .*\(rad, rad, rad, rad, "
                                            r"rad, rad\), got 5"):
        make_plan(ur10, np.zeros((4, 5)))
    assert make_plan(ur10, np.zeros(6)).q.shape == (1, 6) and make_plan(ur10, []).q.shape == (0, 6)
    split = split_errors(build_error_model(ur10))
    with pytest.raises(TolallocError, match=r"plan: made for the robot 'tool_changer' \(6 joints\), but the error "
                                            r"split is of 'ur10'"):
        posterior(split, make_plan(tc, tc.poses("working")))
    assert posterior(split, make_plan(ur10, ur10.poses("working"))).cov_sys.shape[0] == len(split.model.params)
