"""Bad input raises a Python exception with the Rust message; the env stays usable."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper


@pytest.mark.parametrize(
    "action",
    [
        np.zeros(6, dtype=np.float32),
        np.zeros(8, dtype=np.float32),
        np.zeros((7, 1), dtype=np.float32),
        np.array([np.nan, 0, 0, 0, 0, 0, 0], dtype=np.float32),
        np.array([0, 0, np.inf, 0, 0, 0, 0]),
        [0.0] * 3,
        "not an action",
    ],
)
def test_bad_action_raises_value_error_and_env_stays_usable(gym_env: GymWrapper, action: object) -> None:
    gym_env.reset(seed=0)
    gym_env.step(gym_env.action_space.sample())
    state = gym_env.get_state()
    with pytest.raises(ValueError, match="action"):
        gym_env.step(action)
    np.testing.assert_array_equal(gym_env.get_state(), state)
    obs, reward, terminated, truncated, info = gym_env.step(gym_env.action_space.sample())
    assert obs in gym_env.observation_space


def test_bad_action_on_robosuite_env(env: suite.RobosuiteEnv) -> None:
    env.reset()
    with pytest.raises(ValueError, match="not finite"):
        env.step(np.full(7, np.nan))
    with pytest.raises(ValueError, match="shape"):
        env.step(np.zeros(3))
    env.step(np.zeros(7))


def test_actions_of_other_dtypes_and_lists_are_accepted(gym_env: GymWrapper) -> None:
    gym_env.reset(seed=0)
    gym_env.step(np.zeros(7, dtype=np.float64))
    gym_env.step([0.0] * 7)
    gym_env.step(np.zeros(7, dtype=np.int64))


def test_step_before_reset_and_after_end(env: suite.RobosuiteEnv) -> None:
    g = GymWrapper(env)
    with pytest.raises(RuntimeError, match="reset"):
        g.step(g.action_space.sample())
    g.reset(seed=0)
    truncated = False
    while not truncated:
        _, _, _, truncated, _ = g.step(g.action_space.sample())
    with pytest.raises(ValueError, match="episode ended"):
        g.step(g.action_space.sample())
    g.reset()
    g.step(g.action_space.sample())


def test_bad_seed_and_options(gym_env: GymWrapper) -> None:
    with pytest.raises(gym.error.Error, match="Seed must be greater or equal to zero"):
        gym_env.reset(seed=-1)  # Gymnasium's own check, in super().reset
    with pytest.raises(ValueError, match="seed must be a non-negative integer"):
        gym_env.env.reset(seed=-1)
    with pytest.raises(ValueError, match="unknown key"):
        gym_env.reset(options={"nope": 1})
    gym_env.reset(options={})
    gym_env.reset(seed=2**63)


def test_unknown_gym_wrapper_key(env: suite.RobosuiteEnv) -> None:
    with pytest.raises(ValueError, match="no_such_key"):
        GymWrapper(env, keys=["no_such_key"])
    with pytest.raises(TypeError):
        GymWrapper(object())  # type: ignore[arg-type]
