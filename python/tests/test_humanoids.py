"""robosuite 1.5's GR1 humanoids from Python: GR1 (legs, torso, head, WHOLE_BODY_IK),
GR1ArmsOnly, GR1FloatingBody (HYBRID_MOBILE_BASE) and GR1FixedLowerBody (whose default
WHOLE_BODY_MINK_IK is refused), with robosuite's robot objects."""

from __future__ import annotations

import numpy as np
import pytest

import robosuite_rs as suite
from robosuite_rs.robots import ROBOT_CLASS_MAPPING

from .conftest import QUIET


def test_gr1_on_lift_holds_its_hands_under_whole_body_ik() -> None:
    assert ROBOT_CLASS_MAPPING["GR1"] == "LeggedRobot"
    env = suite.make("Lift", robots="GR1", **QUIET)
    robot = env.robots[0]
    assert robot.composite_controller.name == "WHOLE_BODY_IK"
    assert robot.action_dim == 24
    obs = env.reset()
    for key in ("robot0_right_eef_pos", "robot0_left_eef_pos", "right_gripper_to_cube_pos"):
        assert key in obs, key
    split = robot.composite_controller._action_split_indexes
    assert {"right", "left", "right_gripper", "left_gripper"} <= set(split)
    assert split["right"][1] - split["right"][0] == 6
    # WHOLE_BODY_IK takes absolute hand poses: an all-zero action asks for targets the arms
    # cannot reach; the IK's step limits keep the motion bounded and the state finite.
    start = obs["robot0_right_eef_pos"].copy()
    for _ in range(5):
        obs, reward, done, info = env.step(np.zeros(robot.action_dim))
    assert np.all(np.isfinite(obs["robot0_right_eef_pos"]))
    assert np.linalg.norm(obs["robot0_right_eef_pos"] - start) < 0.5


def test_gr1_arms_only_and_floating_body_layouts() -> None:
    arms_only = suite.make("Lift", robots="GR1ArmsOnly", **QUIET)
    assert arms_only.action_dim == 24 and list(arms_only.robots[0].body_parts) == []
    floating = suite.make("Lift", robots="GR1FloatingBody", **QUIET)
    robot = floating.robots[0]
    assert robot.composite_controller.name == "HYBRID_MOBILE_BASE"
    assert floating.action_dim == 34 and "base" in robot.body_parts
    obs = floating.reset()
    start = obs["robot0_base_pos"].copy()
    action = robot.create_action_vector({"base": [1.0, 0.0, 0.0], "base_mode": 1.0})
    for _ in range(10):
        obs, *_ = floating.step(action)
    assert np.linalg.norm(obs["robot0_base_pos"][:2] - start[:2]) > 0.02


def test_gr1_fixed_lower_body_default_controller_is_refused() -> None:
    with pytest.raises(NotImplementedError, match="mink"):
        suite.make("Lift", robots="GR1FixedLowerBody", **QUIET)
