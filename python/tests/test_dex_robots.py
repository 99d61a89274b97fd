"""robosuite 1.5's Panda with an Inspire hand from Python (PandaDexRH, PandaDexLH), with
robosuite's robot objects."""

from __future__ import annotations

import numpy as np

import robosuite_rs as suite
from robosuite_rs.robots import ROBOT_CLASS_MAPPING

from .conftest import QUIET


def test_panda_dex_rh_on_lift() -> None:
    assert ROBOT_CLASS_MAPPING["PandaDexRH"] == ROBOT_CLASS_MAPPING["PandaDexLH"] == "FixedBaseRobot"
    env = suite.make("Lift", robots="PandaDexRH", **QUIET)
    robot = env.robots[0]
    assert robot.composite_controller.name == "BASIC"
    assert list(robot.composite_controller._action_split_indexes) == ["right", "right_gripper"]
    # robosuite 1.5.2: action_dim 12, dof 7 (the arm's joints), a hand of six actions.
    assert env.action_dim == robot.action_dim == 12 and robot.dof == 7
    hand = robot.gripper["right"]
    assert hand.name == "InspireRightHand" and hand.dof == 6 and hand.naming_prefix == "gripper0_right_"
    assert robot.gripper_joints["right"][:2] == [
        "gripper0_right_joint_r_thumb_proximal_1",
        "gripper0_right_joint_r_thumb_proximal_2",
    ]
    assert len(robot.gripper_joints["right"]) == 12 and len(hand.actuators) == 12
    obs = env.reset()
    assert obs["robot0_gripper_qpos"].shape == (12,) and obs["robot0_gripper_qvel"].shape == (12,)
    # Closing the hand bends its fingers.
    action = robot.create_action_vector({"right": np.zeros(6), "right_gripper": np.ones(6)})
    assert action.shape == (12,) and np.all(action[6:] == 1.0)
    for _ in range(10):
        obs, *_ = env.step(action)
    assert obs["robot0_gripper_qpos"].max() > 0.3


def test_panda_dex_pair_on_two_arm_lift() -> None:
    env = suite.make("TwoArmLift", robots=["PandaDexRH", "PandaDexLH"], **QUIET)
    assert env.action_dim == 24
    assert [r.gripper["right"].name for r in env.robots] == ["InspireRightHand", "InspireLeftHand"]
