"""`tolalloc robots`, `tolalloc show ROBOT`, `tolalloc fk ROBOT --q ...`."""

from __future__ import annotations

from tolalloc.cli.common import add_robot_arg, check_output, parse_q, robot_from_args, trusting, write_json


def register(sub) -> None:
    p = sub.add_parser("robots", help="list the built-in robots", description="List the built-in robots, one line each.")
    p.set_defaults(func=cmd_robots)

    p = sub.add_parser("show", help="joints, links and nominal pose of a robot",
                       description="Show a robot's joints (limits and nominal values in deg / mm), links [mm], "
                       "pose sets and its nominal end-effector pose.")
    add_robot_arg(p)
    p.set_defaults(func=cmd_show)

    p = sub.add_parser("fk", help="forward kinematics at given joint values",
                       description="End-effector pose T(q) by the product of exponentials.")
    add_robot_arg(p)
    p.add_argument("--q", "--pose", dest="q", required=True, metavar="Q_DEG_MM",
                   help='joint values, comma-separated, deg (revolute) / mm (prismatic), e.g. "15,30,-10,0,-20,-5" '
                   "(--pose is the same flag, as in analyze and mc)")
    p.add_argument("--json", nargs="?", const="-", default=None, metavar="OUT",
                   help="write JSON with position_mm and rotation (3x3) to OUT ('-', or no OUT: standard output) "
                   "instead of the text")
    p.set_defaults(func=cmd_fk)


def cmd_robots(args) -> int:
    from tolalloc.workflows.robot_info import robots_text

    print(robots_text())
    return 0


def cmd_show(args) -> int:
    from tolalloc.workflows.robot_info import robot_text

    with trusting(args):
        print(robot_text(robot_from_args(args)))
    return 0


def cmd_fk(args) -> int:
    from tolalloc.workflows.robot_info import pose_dict, pose_text

    check_output(args.json, "--json")
    robot = robot_from_args(args)
    with trusting(args):
        pose = pose_dict(robot, parse_q(args.q))
    if args.json is not None:
        write_json(pose, args.json)
    else:
        print(pose_text(pose))
    return 0
