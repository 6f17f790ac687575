"""Nonlinear Monte Carlo of a design with bought parts: the paired estimator against plain Monte Carlo of the same
draws, the draws' consistency with the linear map, and the verdicts."""

import numpy as np
import pytest

from tolalloc.allocate.parts import allocate_parts
from tolalloc.errormodel import build_error_model
from tolalloc.errormodel.parts import Conditions
from tolalloc.verify.parts import verify_parts

from parts_robot import arm
from parts_robot import CLASSES


@pytest.fixture(scope="module")
def res(tmp_path_factory):
    robot = arm(tmp_path_factory.mktemp("arm"))
    return allocate_parts(build_error_model(robot), q=np.deg2rad([[10.0, -30.0, 0.0]]),
                          conditions=Conditions((0.0, 1.0), (15.0, 30.0)), radius_mm=0.3, rules=("trace",),
                          costs=CLASSES, exact=False, after="compensation")


def test_paired_estimate_agrees_with_plain_and_demonstrates(res):
    v = verify_parts(res, n_mc=4000, n_control=20000, seed=3, points="active")
    df = v.to_frame()
    assert len(df) == 1 + len(res.points) and v.verdict == "demonstrated"
    # the paired and the plain estimates of the same draws agree (their intervals overlap)
    assert np.all((v.low <= v.plain_high) & (v.plain_low <= v.high))
    assert df["p_mc"].iloc[0] == pytest.approx(df["p_mc"].iloc[1:].min(), abs=0.003)  # the worst active point
    # the certified bound (Gaussian, radius reduced by the mean) is below the Gaussian probability with the mean
    assert np.all(v.p_certified <= v.p_linear + 1e-9) and np.all(v.p_certified >= res.problem.prob - 1e-6)
    with pytest.raises(Exception, match=r"which='standard': the allocation has no standard machining design"):
        verify_parts(res, which="standard")


def test_job_options_are_checked(tmp_path):
    import tolalloc
    from parts_robot import ARM

    with pytest.raises(tolalloc.TolallocError, match=r"parts: unknown option 'payload'; expected payload_kg, ambient_c"):
        tolalloc.allocate_tolerances("ur10", parts={"payload": 3})
    with pytest.raises(tolalloc.TolallocError, match=r"parts: the design with bought parts takes the position "
                                                     r"requirement alone, without a calibration plan"):
        tolalloc.allocate_tolerances("ur10", [tolalloc.PositionRequirement(),
                                              tolalloc.OrientationRequirement(radius_deg=0.1)], parts=True)
    with pytest.raises(tolalloc.TolallocError, match=r"parts: the design with bought parts takes the position"):
        tolalloc.allocate_tolerances("ur10", [tolalloc.PositionRequirement(),  # no options: the defaults, not ignored
                                              tolalloc.OrientationRequirement(radius_deg=0.1)], parts={})
    bare = tmp_path / "bare.toml"
    bare.write_text(ARM.split("[components.payload]")[0])  # the arm without its [components] section
    with pytest.raises(tolalloc.TolallocError, match=r"parts: robot 'arm3' names no catalogue slots"):
        tolalloc.allocate_tolerances(str(bare), region="limits", parts=True)
