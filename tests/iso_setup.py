"""Shared set-up of the ISO 9283 acceptance tests: the UR10's test laid out once per test process."""

from functools import cache


@cache
def ur10_test():
    """The UR10 and its acceptance test in the box of its working pose set (two candidate centres: a cube of
    about 38 mm with the tool orientation held)."""
    from tolalloc.acceptance import acceptance_test
    from tolalloc.robot.io import load_robot

    robot = load_robot("ur10")
    return robot, acceptance_test(robot, candidates=2)
