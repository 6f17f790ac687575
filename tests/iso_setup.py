"""Shared set-up of the ISO 9283 acceptance tests: the UR10's test laid out once per test process."""

from functools import cache


@cache
def ur10_test():
    """The UR10 and its acceptance test in the box of its working pose set: a given cube of 20 mm edge (the tool
    orientation of the box's middle pose held; a larger one, 38 mm, is found by a search of 3 candidate centres in
    1 s, this one is checked in 0.05 s)."""
    from tolalloc.acceptance import acceptance_test
    from tolalloc.robot.io import load_robot

    robot = load_robot("ur10")
    return robot, acceptance_test(robot, cube_centre_mm=[-59.276, -676.644, 1244.494], cube_edge_mm=20.0,
                                  orientation="fixed")
