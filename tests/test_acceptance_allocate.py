"""ISO 9283 requirements as allocation constraints (tolalloc.acceptance.terms, tolalloc.allocate with acceptance=):
the blocks are the prediction's model, the designs meet them (and the guard band demonstrates them), bad input is
refused."""

import numpy as np
import pytest

from iso_setup import ur10_test
from tolalloc.exceptions import TolallocError
from tolalloc.acceptance import PoseAccuracy, PoseRepeatability, Tracker, predict_acceptance
from tolalloc.acceptance.layout import AcceptanceTest
from tolalloc.acceptance.terms import AcceptanceSpec
from tolalloc.allocate import allocate, build_problem
from tolalloc.calibration.split import split_errors
from tolalloc.errormodel import build_error_model
from tolalloc.linear.repeatability import p_rp_within

REQS = (PoseAccuracy(limit_mm=0.05), PoseRepeatability(limit_mm=0.05))


@pytest.fixture(scope="module")
def case():
    robot, test = ur10_test()
    names = [p.name for p in build_error_model(robot).params if p.kind != "joint_drive"]
    model = build_error_model(robot, exclude=tuple(names))
    pr = build_problem(model, radius_mm=None, acceptance=AcceptanceSpec(REQS, test))
    return robot, test, model, pr, allocate(pr, solver="exact", snap=False)


def test_exact_design_meets_the_requirements_the_prediction_states(case):
    robot, test, model, pr, res = case
    assert res.status == "optimal" and res.design.solver == "exact" and res.certified.ok
    assert res.design.cost <= res.certified.cost + 1e-9
    pred = predict_acceptance(test, REQS, pr.model_for(res.design.t))
    for s in pred.statistics:  # the blocks are the prediction's covariance, term for term
        b = next(b for b in pr.blocks if b["name"] == s.model.name)
        np.testing.assert_allclose(b["C0"] + np.einsum("pkij,k->pij", b["A"], pr.u_from_t(res.design.t)),
                                   s.cov_robot, rtol=1e-9, atol=1e-15)
        np.testing.assert_allclose(res.design.p_linear[s.model.name], s.p_robot, rtol=1e-9)
        assert np.all(s.p_robot >= 0.95 - 1e-5)
    assert pred.statistics[0].robot.max() == pytest.approx(0.05, rel=1e-3)  # AP binds at its worst pose


def test_certified_rp_rule_is_sufficient(case):
    robot, test, model, pr, res = case
    rp = next(b for b in pr.blocks if b["name"] == "RP_l")
    C = rp["C0"] + np.einsum("pkij,k->pij", rp["A"], pr.u_from_t(res.certified.t))
    if res.certified.solver == "certified-lmi":
        assert np.all(np.linalg.eigvalsh(C)[:, -1] <= rp["eig_bound"] * (1 + 1e-9))
    else:
        assert np.all(np.einsum("pii->p", C) <= rp["trace_bound"] * (1 + 1e-9))
    assert np.all(p_rp_within(C, 0.05, 30) >= 0.95)


def test_guard_band_allocates_a_demonstrated_conformance(case):
    robot, test, model, _, _ = case
    near = AcceptanceTest(robot, test.placement, tracker=Tracker(mpe_a_mm=0.005, mpe_b_mm_per_m=0.0, distance_m=1.0))
    reqs = (PoseAccuracy(limit_mm=0.05, guard_band=True),)
    pr = build_problem(model, radius_mm=None, acceptance=AcceptanceSpec(reqs, near))
    res = allocate(pr, solver="certified", snap=False)
    pred = predict_acceptance(near, reqs, pr.model_for(res.design.t))
    assert pred.demonstrated, pred.text()


def test_bad_acceptance_input(case):
    robot, test, model, _, _ = case
    random_only = {"kinds": {"joint_drive": {"systematic": False}}}
    with pytest.raises(TolallocError, match=r"pose_accuracy: no systematic part is left to allocate for AP_P .* State "
                                            r"a repeatability requirement instead"):
        build_problem(model, radius_mm=None, acceptance=AcceptanceSpec(REQS, test, split=random_only))
    with pytest.raises(TolallocError, match=r"pose_repeatability: with guard_band the limit 0.05 mm less the expanded "
                                            r"uncertainty of the measurement, U = .* nothing is left for the robot"):
        build_problem(model, radius_mm=None, acceptance=AcceptanceSpec(
            (PoseRepeatability(limit_mm=0.05, guard_band=True),),
            AcceptanceTest(robot, test.placement, tracker=Tracker(mpe_a_mm=0.2))))
    with pytest.raises(TolallocError, match=r"the measured RP_l of a robot without errors of its own is already "
                                            r"0\.0638\d* mm at the share 0\.95, above that .* conformance can never be "
                                            r"demonstrated"):
        build_problem(model, radius_mm=None, acceptance=AcceptanceSpec(
            (PoseRepeatability(limit_mm=0.05, guard_band=True),), test))
    with pytest.raises(TolallocError, match=r"radius_mm: without a position requirement the problem needs ISO 9283"):
        build_problem(model, radius_mm=None)
    assert split_errors(model).systematic.all()  # the defaults: every parameter here has a systematic part
