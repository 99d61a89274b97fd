"""A Rust user's own pyo3 module (python/examples/own_module, built by scripts/test.sh)
exports its envs as gymnasium.Env with one call each: a small non-robosuite env and a
custom wrapper stack over Lift."""

from __future__ import annotations

import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from .conftest import unexpected

my_envs = pytest.importorskip("my_envs", reason="build python/examples/own_module first (python/scripts/test.sh does)")


def test_corridor_is_a_gymnasium_env() -> None:
    env = my_envs.make_corridor(6)
    assert isinstance(env, gym.Env)
    assert isinstance(env.observation_space, gym.spaces.Dict)
    assert list(env.observation_space.spaces) == ["position", "distance"]
    assert env.observation_space["position"] == gym.spaces.Discrete(6)
    assert env.action_space == gym.spaces.Discrete(2)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env, skip_render_check=True)
    assert unexpected(caught, allowed=()) == []
    obs, info = env.reset(seed=0)
    assert type(obs["position"]) is int and obs["distance"].dtype == np.float32
    done, total = False, 0.0
    while not done:
        obs, reward, terminated, truncated, info = env.step(1)
        total += reward
        done = terminated or truncated
    assert terminated and obs["position"] == 5 and info["steps"] >= 1
    with pytest.raises(ValueError, match="invalid action"):
        env.reset()
        env.step(5)
    env.step(np.int64(0))


def test_custom_stack_over_lift() -> None:
    env = my_envs.make_lift_stack(horizon=10, repeat=2)
    assert env.observation_space.shape == (60,) and env.observation_space.dtype == np.float32
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env, skip_render_check=True)
    assert unexpected(caught) == []
    env.reset(seed=1)
    steps = 0
    while True:
        _, _, terminated, truncated, info = env.step(env.action_space.sample())
        steps += 1
        if terminated or truncated:
            break
    assert steps == 5 and "success" in info  # horizon 10, each action repeated twice
