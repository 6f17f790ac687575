"""The seed-paper study's unit-mix hypothesis robot (studies/seed_paper/run.py `metre_robot`).

The paper's literal reading puts the link lengths in metres beside error values in mm; the study builds that robot
on purpose, so it must pass the unit guard that refuses such a robot from a user (the guard's own refusal is
tested in tests/test_robot.py).
"""

import importlib.util
from pathlib import Path

import numpy as np

import tolalloc
from tolalloc.robot.model import Link

RUN = Path(__file__).resolve().parents[1] / "studies" / "seed_paper" / "run.py"


def test_metre_robot_is_the_tool_changer_with_links_in_metres():
    spec = importlib.util.spec_from_file_location("seed_paper_run", RUN)
    run = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(run)
    robot = tolalloc.load_robot("tool_changer")
    metres = run.metre_robot(robot)
    links = [(a.vector_mm, b.vector_mm) for a, b in zip(robot.chain, metres.chain) if isinstance(a, Link)]
    assert links and all(np.allclose(m * 1000.0, mm) for mm, m in links)
    assert metres.n_joints == robot.n_joints and not metres.pose_sets
