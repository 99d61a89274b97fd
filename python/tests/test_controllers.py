"""robosuite's controllers and controller configs from Python, as robosuite users write them."""

from __future__ import annotations

import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper

import warnings

from .conftest import QUIET, unexpected


def test_robosuites_default_config_is_accepted_verbatim() -> None:
    cfg = suite.load_composite_controller_config(controller="BASIC", robot="Panda")
    assert cfg["type"] == "BASIC"
    assert set(cfg["body_parts"]) == {"right", "left", "torso", "head", "base", "legs"}
    env = suite.make("Lift", robots="Panda", controller_configs=cfg, **QUIET)
    low, high = env.action_spec
    assert low.shape == (7,)
    env.reset(seed=0)
    env.step(np.zeros(7))
    own = suite.load_composite_controller_config(robot="Panda")
    assert list(own["body_parts"]) == ["right"]
    assert own["body_parts"]["right"]["type"] == "OSC_POSE"


@pytest.mark.parametrize("controller", suite.ALL_PART_CONTROLLERS)
@pytest.mark.parametrize("robot", ["Panda", "UR5e"])
def test_every_part_controller_on_a_7_and_a_6_joint_arm(controller: str, robot: str) -> None:
    part = suite.load_part_controller_config(default_controller=controller)
    assert part["type"] == controller
    env = suite.make("Lift", robots=robot, controller_configs=part, horizon=10, **QUIET)
    joints = 7 if robot == "Panda" else 6
    arm = {"OSC_POSE": 6, "IK_POSE": 6, "OSC_POSITION": 3}.get(controller, joints)
    low, high = env.action_spec
    assert low.shape == (arm + 1,)
    if controller == "IK_POSE":
        np.testing.assert_array_equal(high[:6], [0.02, 0.02, 0.02, 0.05, 0.05, 0.05])
    env.reset(seed=1)
    rng = np.random.default_rng(0)
    for _ in range(5):
        obs, _, _, _ = env.step(rng.uniform(low, high))
    assert np.all(np.isfinite(obs["robot0_joint_pos"]))


def test_variable_impedance_and_numpy_values() -> None:
    part = suite.load_part_controller_config(default_controller="OSC_POSE")
    part.update(impedance_mode="variable_kp", kp=np.array([100.0, 120, 140, 160, 180, 200]), kp_limits=np.array([10, 250]))
    env = suite.make("Lift", controller_configs=part, **QUIET)
    low, high = env.action_spec
    assert low.shape == (13,)
    np.testing.assert_array_equal(low[:6], 10.0)
    np.testing.assert_array_equal(high[:6], 250.0)


def test_bad_configs_raise_naming_the_key() -> None:
    part = suite.load_part_controller_config(default_controller="OSC_POSE")
    with pytest.raises(ValueError, match=r"controller_configs\.kp"):
        suite.make("Lift", controller_configs=dict(part, kp=float("nan")), **QUIET)
    with pytest.raises(ValueError, match=r"controller_configs\.body_parts\.right\.kp"):
        suite.make("Lift", controller_configs={"type": "BASIC", "body_parts": {"right": dict(part, kp=-3)}}, **QUIET)
    with pytest.raises(ValueError, match="JOINT_VELOCITY"):
        suite.make("Lift", controller_configs=dict(part, type="JOINT_SPEED"), **QUIET)
    with pytest.warns(UserWarning, match="kpp"):  # robosuite ignores it too
        suite.make("Lift", controller_configs=dict(part, kpp=1), **QUIET)
    with pytest.raises(ValueError, match="list of 6"):
        jp = suite.load_part_controller_config(default_controller="JOINT_POSITION")
        suite.make("Lift", robots="UR5e", controller_configs=dict(jp, kp=[50] * 7), **QUIET)
    with pytest.raises(NotImplementedError, match="mink"):
        suite.make("Lift", controller_configs=suite.load_composite_controller_config(controller="WHOLE_BODY_MINK_IK"), **QUIET)
    with pytest.raises(ValueError, match="default_controller"):
        suite.load_part_controller_config(default_controller="OSC")


def test_custom_config_file(tmp_path) -> None:
    path = tmp_path / "mine.json"
    path.write_text('{"type": "JOINT_VELOCITY", "kp": 3.0, "output_max": 0.5, "output_min": -0.5}')
    part = suite.load_part_controller_config(custom_fpath=path)
    env = suite.make("Lift", controller_configs=part, **QUIET)
    assert env.action_spec[0].shape == (8,)


def test_gymnasium_check_env_with_joint_velocity() -> None:
    part = suite.load_part_controller_config(default_controller="JOINT_VELOCITY")
    env = GymWrapper(suite.make("Lift", controller_configs=part, horizon=20, **QUIET))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env, skip_render_check=True)
    assert unexpected(caught) == []
    env.close()


def test_whole_body_ik_on_a_panda() -> None:
    # robosuite's whole_body_ik.json on a one-armed robot: the parts and the left site it
    # lacks are dropped (as robosuite drops them); the action is the grip site's absolute
    # pose (unbounded), then the gripper.
    cfg = suite.load_composite_controller_config(controller="WHOLE_BODY_IK")
    env = suite.make("Lift", controller_configs=cfg, **QUIET)
    low, high = env.action_spec
    assert low.shape == (7,)
    assert np.all(np.isneginf(low[:6])) and np.all(np.isposinf(high[:6]))
    obs = env.reset()
    target = obs["robot0_eef_pos"] + np.array([0.0, 0.0, 0.05])
    quat = obs["robot0_eef_quat_site"]
    angle = 2 * np.arccos(np.clip(quat[3], -1, 1))
    axis = quat[:3] / max(np.linalg.norm(quat[:3]), 1e-12)
    action = np.concatenate([target, axis * angle, [-1.0]])
    for _ in range(30):
        obs, _, _, _ = env.step(action)
    assert np.linalg.norm(obs["robot0_eef_pos"] - target) < 0.01
    robot = env.robots[0]
    assert list(robot.composite_controller._action_split_indexes.items()) == [
        ("right", (0, 6)),
        ("right_gripper", (6, 7)),
    ]
    np.testing.assert_array_equal(robot.create_action_vector({"right": action[:6], "right_gripper": [-1.0]}), action)
    with pytest.raises(ValueError):
        env.step(np.concatenate([[np.nan], action[1:]]))
