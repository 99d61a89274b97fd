"""robosuite 1.5's mobile robots from Python: PandaOmron (wheeled, HYBRID_MOBILE_BASE) and
Tiago (bimanual, wheeled, BASIC), with robosuite's robot objects."""

from __future__ import annotations

import numpy as np

import robosuite_rs as suite
from robosuite_rs.robots import ROBOT_CLASS_MAPPING

from .conftest import QUIET


def test_panda_omron_on_lift() -> None:
    assert ROBOT_CLASS_MAPPING["PandaOmron"] == "WheeledRobot"
    env = suite.make("Lift", robots="PandaOmron", **QUIET)
    robot = env.robots[0]
    assert robot.is_mobile and robot.composite_controller.name == "HYBRID_MOBILE_BASE"
    assert list(robot.composite_controller._action_split_indexes) == ["right", "torso", "base", "right_gripper"]
    assert robot.action_dim == 12 and list(robot.body_parts) == ["base", "torso"]
    obs = env.reset()
    assert obs["robot0_base_pos"].shape == (3,)
    start = obs["robot0_base_pos"].copy()
    # Drive the base forward in base mode.
    action = robot.create_action_vector({"base": [1.0, 0.0, 0.0], "base_mode": 1.0})
    assert action[-1] == 1.0 and action[7] == 1.0
    for _ in range(10):
        obs, *_ = env.step(action)
    assert obs["robot0_base_pos"][0] - start[0] > 0.05


def test_tiago_alone_on_two_arm_lift() -> None:
    assert ROBOT_CLASS_MAPPING["Tiago"] == "WheeledRobot"
    env = suite.make("TwoArmLift", robots="Tiago", **QUIET)
    robot = env.robots[0]
    assert robot.arms == ["right", "left"]
    assert list(robot.composite_controller._action_split_indexes) == [
        "right", "left", "torso", "head", "base", "right_gripper", "left_gripper"
    ]
    obs = env.reset()
    assert "robot0_base_to_right_eef_pos" in obs and "robot0_base_to_left_eef_pos" in obs
    obs, *_ = env.step(np.zeros(env.action_dim))
    assert np.all(np.isfinite(obs["robot0_joint_pos"]))
