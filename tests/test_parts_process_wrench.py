"""A process wrench in the design with bought parts (``Conditions.process_force_n`` / ``process_torque_nm``): the same
loads the diagnosis reads from a logged wrench, through the joints, the beams and the mount.

Known answer: at one pose, a tool-frame force that points down with ``m g`` (and the moment that moves it to the
payload's centre of mass) loads the design exactly as ``m`` kg of payload does.
"""

import numpy as np
import pytest

import tolalloc
from tolalloc.errormodel.parts import Conditions, PartEffects, with_parts
from tolalloc.physics.loads import G

from parts_robot import arm

CHOICE = {("j1", "reducer"): "HD-CSG-17-100", ("j1", "bearing"): "ISO492-P0", ("j2", "reducer"): "HD-CSG-14-100-SA"}


@pytest.fixture(scope="module")
def robot(tmp_path_factory):
    return with_parts(arm(tmp_path_factory.mktemp("arm")), CHOICE)


@pytest.mark.parametrize("q", [[0.3, -0.5, 0.7], [-0.6, 1.1, -2.0]])
def test_a_process_force_of_m_g_down_loads_the_design_as_m_kg_of_payload(robot, q):
    q = np.array([q])
    m = 0.8
    empty = PartEffects(robot, q, 0.0, 20.0)
    R = robot.fk_internal(q)[0, :3, :3]
    down = np.array([0.0, 0.0, -m * G])
    lever_m = 1e-3 * (empty.payload_point[0] - empty.tool[0])
    cond = Conditions(process_force_n=tuple(R.T @ down), process_torque_nm=tuple(R.T @ np.cross(lever_m, down)))
    pushed, held = PartEffects(robot, q, 0.0, 20.0, cond.check(robot)), PartEffects(robot, q, m, 20.0)
    assert not np.allclose(held.tau, empty.tau)
    np.testing.assert_allclose(pushed.tau, held.tau, rtol=1e-12, atol=1e-12)
    a, b = pushed.body_terms(), held.body_terms()
    for name in ("beam", "mount"):
        k = list(a.names).index(name)
        np.testing.assert_allclose(a.columns[:, :, k], b.columns[:, :, k], rtol=1e-12, atol=1e-15)
    # the Monte Carlo's physical draws too (same random numbers)
    from tolalloc.errormodel.parts_sample import sample_effects

    (va, da), (vb, db) = (sample_effects(fx, 0, 64, np.random.default_rng(5)) for fx in (pushed, held))
    np.testing.assert_allclose(va, vb, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(da, db, rtol=1e-12, atol=1e-15)
    assert np.abs(db).max() > 0


def test_a_process_force_reaches_the_allocation_from_the_options_and_the_command_line():
    from tolalloc.cli import build_parser
    from tolalloc.cli.allocate import settings

    args = build_parser().parse_args(["allocate", "arm3", "--parts", "--process-force-n", "0", "0", "-50",
                                      "--process-torque-nm", "0", "1.5", "0"])
    parts = settings(args)["parts"]
    assert parts["process_force_n"] == (0.0, 0.0, -50.0) and parts["process_torque_nm"] == (0.0, 1.5, 0.0)
    with pytest.raises(tolalloc.TolallocError, match="needs `parts`"):
        settings(build_parser().parse_args(["allocate", "arm3", "--process-force-n", "0", "0", "-50"]))


@pytest.mark.parametrize("bad", [(1.0, 2.0), (0.0, float("nan"), 0.0), (True, 0.0, 0.0), "x"])
def test_a_process_force_that_is_not_three_finite_numbers_is_refused(robot, bad):
    with pytest.raises(tolalloc.TolallocError, match=r"process_force_n: expected three finite numbers"):
        Conditions(process_force_n=bad).check(robot)


def test_a_process_force_that_overloads_a_reducer_option_is_refused_naming_it(tmp_path):
    """arm3's j2 options include a size 14 gear rated 10 N m: a 25 N push down in the tool frame (beside 1 kg of
    payload) overloads it somewhere in the region, and the refusal names the process wrench."""
    robot = arm(tmp_path)
    with pytest.raises(tolalloc.TolallocError, match=r"joint j2: HD-CSG-14-100 is rated 10 N m, but the load "
                                                     r"\(gravity and the process wrench\) reaches .* or the process "
                                                     r"wrench"):
        tolalloc.allocate_tolerances(robot, region="work", parts={"payload_kg": (0.0, 1.0),
                                                                  "process_force_n": (0.0, 0.0, -25.0)},
                                     requirement=tolalloc.PositionRequirement(1.5, 0.95), verification=False)


def test_a_process_load_makes_the_design_with_parts_no_cheaper_and_is_named(tmp_path):
    """The same requirement at the same pose (the nominal one: the region's search evaluates the same terms at more
    points) with a 3 N push and a 0.2 N m moment at the tool: the joints and beams carry more, so the cheapest
    design costs at least as much (the programme's relative gap 1e-3), and the headline names the process wrench."""
    robot = arm(tmp_path)
    kw = dict(region="nominal", requirement=tolalloc.PositionRequirement(1.5, 0.95), verification=False)
    free = tolalloc.allocate_tolerances(robot, parts={"payload_kg": (0.0, 1.0)}, **kw)
    pushed = tolalloc.allocate_tolerances(robot, parts={"payload_kg": (0.0, 1.0), "process_force_n": (0.0, 0.0, -3.0),
                                                        "process_torque_nm": (0.0, 0.2, 0.0)}, **kw)
    assert pushed.cost >= free.cost * (1 - 1e-3)
    assert "process force (0, 0, -3) N and moment (0, 0.2, 0) N m at the tool, tool frame" in pushed.headline()[0]
    assert "process force" not in free.headline()[0]
