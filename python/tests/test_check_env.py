"""Gymnasium's own checker on every registered env, and gymnasium.make for every id."""

from __future__ import annotations

import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import robosuite_rs  # registers the ids
from robosuite_rs.registration import register_envs
from robosuite_rs.wrappers import GymWrapper

from .conftest import UNBOUNDED_OBS_WARNINGS, unexpected

IDS = register_envs()


def test_every_rust_env_is_registered() -> None:
    assert "robosuite_rs/Lift-v0" in IDS
    for env_id in IDS:
        assert env_id in gym.registry


@pytest.mark.parametrize("env_id", IDS)
def test_check_env_on_registered_env(env_id: str) -> None:
    env = gym.make(env_id, horizon=30)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped)
    assert unexpected(caught) == []
    env.close()


ROBOTS = ["Sawyer", "IIWA", "Jaco", "Kinova3", "UR5e", "XArm7"]


# One case per robot and task (not one per robot), so parallel test runs spread them.
@pytest.mark.parametrize("robot", ROBOTS)
@pytest.mark.parametrize("env_id", IDS)
def test_check_env_on_every_task_with_every_robot(env_id: str, robot: str) -> None:
    # The Panda is covered above; every other single-arm robot on every task, with its
    # default gripper (Wipe: the wiping tool) and default controller; the two-arm tasks
    # with two of it.
    name = env_id.split("/")[1].rsplit("-v", 1)[0]
    count = robosuite_rs._native.task_robot_count(name)
    env = gym.make(env_id, horizon=30, robots=[robot] * count)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped)
    assert unexpected(caught) == [], (env_id, robot)
    joints = env.unwrapped.env.observation_spec()["robot0_joint_pos"].shape
    assert joints == ((6,) if robot == "UR5e" else (7,)), (env_id, robot)
    env.close()


# robosuite 1.5's whole-body robots and robots with hands: a bimanual robot alone on the
# two-arm tasks, a wheeled robot with a Panda partner there (two wheeled robots cannot share
# a scene, in robosuite either), two of any other.
WHOLE_BODY_ROBOTS = ["PandaOmron", "Tiago", "SpotWithArm", "SpotWithArmFloating", "PandaDexRH", "PandaDexLH", "Baxter",
                     "GR1", "GR1ArmsOnly", "GR1FloatingBody", "GR1FixedLowerBody"]
BIMANUAL = {"Tiago", "Baxter", "GR1", "GR1ArmsOnly", "GR1FloatingBody", "GR1FixedLowerBody"}
WHEELED = {"PandaOmron", "Tiago"}
WHOLE_BODY_IK = {"GR1", "GR1ArmsOnly", "GR1FixedLowerBody"}
UNBOUNDED_ACTION_WARNINGS = (
    "A Box action space minimum value is -infinity",
    "A Box action space maximum value is infinity",
    "we recommend using a symmetric and normalized space",
)


@pytest.mark.parametrize("robot", WHOLE_BODY_ROBOTS)
@pytest.mark.parametrize("env_id", IDS)
def test_check_env_on_every_task_with_every_whole_body_robot(env_id: str, robot: str) -> None:
    # The render check is the same code for every robot and runs on every task above; here
    # the spaces, seeding and step results of each robot's action and observation layout.
    name = env_id.split("/")[1].rsplit("-v", 1)[0]
    count = 1 if robot in BIMANUAL else robosuite_rs._native.task_robot_count(name)
    robots = [robot] + [("Panda" if robot in WHEELED else robot)] * (count - 1)
    # GR1FixedLowerBody's default WHOLE_BODY_MINK_IK needs `mink`: robosuite's WHOLE_BODY_IK.
    extra = {"controller_configs": robosuite_rs.load_composite_controller_config(
        controller="WHOLE_BODY_IK", robot=robot)} if robot == "GR1FixedLowerBody" else {}
    env = gym.make(env_id, horizon=30, robots=robots, **extra)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped, skip_render_check=True)
    # WHOLE_BODY_IK takes absolute targets: robosuite's action space is unbounded there too.
    allowed = UNBOUNDED_OBS_WARNINGS + (UNBOUNDED_ACTION_WARNINGS if robot in WHOLE_BODY_IK else ())
    assert unexpected(caught, allowed) == [], (env_id, robot)
    spec = env.unwrapped.env.observation_spec()
    prefixes = ["robot0_right_", "robot0_left_"] if robot in BIMANUAL else ["robot0_"]
    for prefix in prefixes:
        assert spec[prefix + "eef_pos"].shape == (3,), (env_id, robot, prefix)
    env.close()


@pytest.mark.parametrize("env_id", IDS)
def test_gymnasium_make_and_run(env_id: str) -> None:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        env = gym.make(env_id, horizon=5, reward_shaping=True)
        obs, info = env.reset(seed=3)
        assert obs in env.observation_space
        assert isinstance(info, dict)
        steps = 0
        while True:
            obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
            steps += 1
            assert type(reward) is float and type(terminated) is bool and type(truncated) is bool
            assert obs.dtype == np.float32 and obs in env.observation_space
            assert "success" in info
            if terminated or truncated:
                break
        assert steps == 5 and truncated
        env.close()
        env.close()
    assert unexpected(caught) == []


def test_check_env_on_wrapper_built_directly(gym_env: GymWrapper) -> None:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(gym_env, skip_render_check=True)
    assert unexpected(caught) == []
    assert isinstance(gym_env, gym.Env)
    assert gym_env.unwrapped is gym_env
    assert gym_env.metadata == {"render_modes": ["rgb_array", "depth_array"], "render_fps": 20}
    assert gym_env.render_mode is None and gym_env.render() is None


def test_check_env_dict_observations(env) -> None:  # type: ignore[no-untyped-def]
    g = GymWrapper(env, keys=["robot0_eef_pos", "robot0_eef_quat_site", "cube_pos"], flatten_obs=False)
    assert list(g.observation_space.spaces) == ["robot0_eef_pos", "robot0_eef_quat_site", "cube_pos"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(g, skip_render_check=True)
    assert unexpected(caught) == []
    obs, _ = g.reset(seed=0)
    assert list(obs) == ["robot0_eef_pos", "robot0_eef_quat_site", "cube_pos"]
    assert obs["robot0_eef_quat_site"].dtype == np.float32
    assert obs["robot0_eef_pos"].dtype == np.float64


def test_gymnasium_make_kwargs_reach_the_env() -> None:
    env = gym.make("robosuite_rs/Lift-v0", horizon=7, keys=["object-state"], reward_scale=None)
    assert env.observation_space.shape == (10,)
    assert env.unwrapped.env.horizon == 7
    assert env.unwrapped.env.reward_scale is None
    with pytest.raises(ValueError, match="renderer"):
        gym.make("robosuite_rs/Lift-v0", has_renderer=True, renderer="pygame")
