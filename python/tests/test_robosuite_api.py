"""robosuite's env API: suite.make, reset/step, specs, state, errors."""

from __future__ import annotations

from collections import OrderedDict

import numpy as np
import pytest

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper

from .conftest import QUIET


def test_reset_returns_ordered_numpy_dict(env: suite.RobosuiteEnv) -> None:
    obs = env.reset()
    assert isinstance(obs, OrderedDict)
    keys = list(obs)
    assert keys[0] == "robot0_joint_pos"
    assert keys[-2:] == ["robot0_proprio-state", "object-state"]
    assert obs["robot0_proprio-state"].shape == (50,)
    assert obs["object-state"].shape == (10,)
    for k, v in obs.items():
        assert isinstance(v, np.ndarray)
        assert v.dtype == (np.float32 if k.endswith("eef_quat_site") else np.float64), k
    assert env.observation_spec().keys() == obs.keys()


def test_step_is_robosuite_four_tuple(env: suite.RobosuiteEnv) -> None:
    env.reset()
    low, high = env.action_spec
    assert env.action_dim == 7 and low.shape == (7,) and np.all(low == -1) and np.all(high == 1)
    for t in range(env.horizon):
        obs, reward, done, info = env.step(np.zeros(env.action_dim))
        assert isinstance(obs, OrderedDict) and type(reward) is float and type(done) is bool
        assert isinstance(info, dict)
        assert done == (t == env.horizon - 1)
    with pytest.raises(ValueError):
        env.step(np.zeros(7))
    assert isinstance(env.check_success(), bool)
    assert env._check_success() == env.check_success()


def test_attributes() -> None:
    env = suite.make("Lift", robots=["Panda"], horizon=123, reward_scale=None, reward_shaping=True, control_freq=10, **QUIET)
    assert env.horizon == 123 and env.reward_scale is None and env.reward_shaping and env.control_freq == 10
    env2 = suite.make("Lift", reward_scale=2.5, **QUIET)
    assert env2.reward_scale == 2.5 and env2.horizon == 1000


def test_get_set_state_round_trip(gym_env: GymWrapper) -> None:
    gym_env.reset(seed=5)
    for _ in range(3):
        gym_env.step(gym_env.action_space.sample())
    state = gym_env.unwrapped.get_state()
    assert state.dtype == np.float64 and state.ndim == 1
    inner = gym_env.unwrapped.env
    before = inner.observation_spec()
    for _ in range(3):
        gym_env.step(gym_env.action_space.sample())
    assert not np.array_equal(gym_env.unwrapped.get_state(), state)
    gym_env.unwrapped.set_state(state)
    np.testing.assert_array_equal(gym_env.unwrapped.get_state(), state)
    after = inner.observation_spec()
    np.testing.assert_allclose(after["robot0_joint_pos"], before["robot0_joint_pos"])
    with pytest.raises(ValueError):
        gym_env.unwrapped.set_state(state[:-1])


def test_seeded_episodes_repeat(env: suite.RobosuiteEnv) -> None:
    a = env.reset(seed=11)["object-state"]
    b = env.reset(seed=11)["object-state"]
    c = env.reset(seed=12)["object-state"]
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)


def test_controller_configs() -> None:
    cfg = {"type": "BASIC", "body_parts": {"right": {"type": "OSC_POSE", "kp": 100, "damping_ratio": 1.0,
                                                    "output_max": [0.05, 0.05, 0.05, 0.5, 0.5, 0.5],
                                                    "output_min": [-0.05, -0.05, -0.05, -0.5, -0.5, -0.5],
                                                    "input_ref_frame": "base", "gripper": {"type": "GRIP"}}}}
    env = suite.make("Lift", controller_configs=cfg, **QUIET)
    env.reset(seed=0)
    env.step(np.zeros(7))
    bad = {"type": "BASIC", "body_parts": {"right": {"type": "OSC_POSE", "input_ref_frame": "moon"}}}
    with pytest.raises(ValueError, match="input_ref_frame"):
        suite.make("Lift", controller_configs=bad, **QUIET)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"render_collision_mesh": True},
        {"render_visual_mesh": False},
    ],
)
def test_unsupported_arguments_raise(kwargs: dict[str, object]) -> None:
    with pytest.raises(ValueError, match="not supported"):
        suite.make("Lift", **kwargs)


def test_gripper_types() -> None:
    env = suite.make("Lift", gripper_types="Robotiq85Gripper", **QUIET)
    obs = env.reset(seed=0)
    assert obs["robot0_gripper_qpos"].shape == (6,)
    with pytest.raises(ValueError, match="FooGripper"):
        suite.make("Lift", gripper_types="FooGripper", **QUIET)


def test_invalid_arguments_raise() -> None:
    with pytest.raises(TypeError, match="unexpected keyword argument 'no_such_arg'"):
        suite.make("Lift", no_such_arg=1, **QUIET)
    with pytest.raises(ValueError, match="unknown environment"):
        suite.make("NoSuchTask", **QUIET)
    with pytest.raises(ValueError, match="horizon"):
        suite.make("Lift", horizon=0, **QUIET)
    with pytest.raises(ValueError, match="robot"):
        suite.make("Lift", robots="Sawyerr", **QUIET)
    with pytest.raises(ValueError, match="control_freq"):
        suite.make("Lift", control_freq=-1, **QUIET)


def test_model_xml_missing_file_raises(tmp_path) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(RuntimeError, match="cannot read the scene file"):
        suite.make("Lift", model_xml=tmp_path / "missing.xml", **QUIET)


def test_model_xml_runs_the_task_on_a_scene_file(tmp_path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "lift_scene.xml"
    path.write_text(suite.scene_xml("Lift"))
    env = suite.make("Lift", model_xml=path, horizon=5, **QUIET)
    ref = suite.make("Lift", horizon=5, **QUIET)
    obs, ref_obs = env.reset(seed=3), ref.reset(seed=3)
    assert obs.keys() == ref_obs.keys()
    # Same initial posture up to the reset noise (a supplied scene keeps its cube size, so
    # the RNG streams differ).
    np.testing.assert_allclose(obs["robot0_joint_pos"], ref_obs["robot0_joint_pos"], atol=0.2)
    assert env.get_state().shape == ref.get_state().shape
    g = GymWrapper(env)
    g.reset(seed=0)
    for _ in range(5):
        _, _, _, truncated, info = g.step(g.action_space.sample())
    assert truncated and "success" in info
