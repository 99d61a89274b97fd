"""robosuite 1.5's legged robots from Python: SpotWithArm (legs, BASIC) and
SpotWithArmFloating (floating base, BASIC), with robosuite's robot objects."""

from __future__ import annotations

import numpy as np

import robosuite_rs as suite
from robosuite_rs.robots import ROBOT_CLASS_MAPPING

from .conftest import QUIET


def test_spot_with_arm_on_lift() -> None:
    assert ROBOT_CLASS_MAPPING["SpotWithArm"] == "LeggedRobot"
    env = suite.make("Lift", robots="SpotWithArm", **QUIET)
    robot = env.robots[0]
    assert robot.is_mobile and robot.composite_controller.name == "BASIC"
    assert list(robot.composite_controller._action_split_indexes) == ["right", "legs", "right_gripper"]
    assert robot.action_dim == 19 and list(robot.body_parts) == ["legs"]
    obs = env.reset()
    assert obs["robot0_base_pos"].shape == (3,) and "robot0_base_to_eef_pos" in obs
    # Bend the front right knee.
    legs = np.zeros(12)
    legs[2] = 1.0
    action = robot.create_action_vector({"legs": legs})
    assert action[8] == 1.0 and action.shape == (19,)
    for _ in range(3):
        obs, *_ = env.step(action)
    assert np.all(np.isfinite(obs["robot0_base_pos"]))


def test_spot_with_arm_floating_drives_its_base() -> None:
    assert ROBOT_CLASS_MAPPING["SpotWithArmFloating"] == "LeggedRobot"
    env = suite.make("Lift", robots="SpotWithArmFloating", **QUIET)
    robot = env.robots[0]
    assert list(robot.body_parts) == ["base"] and robot.action_dim == 10
    obs = env.reset()
    start = obs["robot0_base_pos"].copy()
    action = robot.create_action_vector({"base": [1.0, 0.0, 0.0]})
    for _ in range(10):
        obs, *_ = env.step(action)
    assert np.linalg.norm(obs["robot0_base_pos"][:2] - start[:2]) > 0.05
