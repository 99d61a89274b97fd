"""make_vec: a VectorEnv stepping in Rust threads that matches single envs step for step."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper

from .conftest import QUIET


@pytest.mark.parametrize("pin_threads", [False, True])
def test_vector_env_matches_single_envs(pin_threads: bool) -> None:
    n, horizon, seed = 3, 4, 100
    vec = suite.make_vec("Lift", n, horizon=horizon, pin_threads=pin_threads, **QUIET)
    assert isinstance(vec, gym.vector.VectorEnv)
    assert vec.num_envs == n
    assert vec.observation_space.shape == (n, 60) and vec.observation_space.dtype == np.float32
    assert vec.action_space.shape == (n, 7)
    singles = [GymWrapper(suite.make("Lift", horizon=horizon, **QUIET)) for _ in range(n)]

    obs, info = vec.reset(seed=seed)
    expected = [s.reset(seed=seed + i)[0] for i, s in enumerate(singles)]
    np.testing.assert_array_equal(obs, np.stack(expected))
    assert info["success"].shape == (n,) and info["_success"].all()

    vec.action_space.seed(0)
    pending_reset = [False] * n
    for t in range(2 * horizon + 3):
        actions = vec.action_space.sample()
        obs, rewards, terms, truncs, infos = vec.step(actions)
        assert obs.dtype == np.float32 and rewards.dtype == np.float64 and truncs.dtype == np.bool_
        for i, s in enumerate(singles):
            if pending_reset[i]:  # NEXT_STEP autoreset: no seed, action ignored
                o, _ = s.reset()
                r, te, tr = 0.0, False, False
            else:
                o, r, te, tr, _ = s.step(actions[i])
            pending_reset[i] = te or tr
            np.testing.assert_array_equal(obs[i], o, err_msg=f"env {i} step {t}")
            assert rewards[i] == r and terms[i] == te and truncs[i] == tr
        assert truncs.any() == ((t + 1) % (horizon + 1) == horizon)
    vec.close()
    vec.close()


def test_vector_env_bad_actions() -> None:
    vec = suite.make_vec("Lift", 2, horizon=5, **QUIET)
    vec.reset(seed=0)
    with pytest.raises(ValueError):
        vec.step(np.zeros((2, 6), dtype=np.float32))
    bad = np.zeros((2, 7), dtype=np.float32)
    bad[1, 0] = np.nan
    with pytest.raises(ValueError, match="not finite"):
        vec.step(bad)
    vec.reset(seed=0)
    vec.step(np.zeros((2, 7), dtype=np.float32))
    with pytest.raises(ValueError):
        suite.make_vec("Lift", 0, **QUIET)


def test_gymnasium_make_vec_uses_rust_threads() -> None:
    vec = gym.make_vec("robosuite_rs/Lift-v0", num_envs=2, horizon=3)
    assert type(vec).__name__ == "RustVectorEnv"
    obs, _ = vec.reset(seed=1)
    assert obs.shape == (2, 60)
    vec.step(vec.action_space.sample())
    vec.close()


def test_vector_reset_takes_seed_lists_and_a_reset_mask() -> None:
    n = 3
    vec = suite.make_vec("Lift", n, horizon=10, **QUIET)
    singles = [GymWrapper(suite.make("Lift", horizon=10, **QUIET)) for _ in range(n)]
    seeds = [7, None, 9]
    obs, _ = vec.reset(seed=seeds)
    for i in (0, 2):
        np.testing.assert_array_equal(obs[i], singles[i].reset(seed=seeds[i])[0])
    # Step once, then reset only env 1 with a mask: envs 0 and 2 keep their observations.
    stepped, *_ = vec.step(np.zeros((n, 7), dtype=np.float32))
    mask = np.array([False, True, False])
    again, info = vec.reset(seed=[None, 5, None], options={"reset_mask": mask})
    np.testing.assert_array_equal(again[[0, 2]], stepped[[0, 2]])
    np.testing.assert_array_equal(again[1], singles[1].reset(seed=5)[0])
    assert info["_success"].tolist() == [False, True, False]
    with pytest.raises(ValueError):
        vec.reset(seed=[1, 2])
    with pytest.raises(gym.error.Error, match="greater or equal to zero"):  # Gymnasium's own check
        vec.reset(seed=-1)
    with pytest.raises(ValueError, match="non-negative"):
        vec.reset(seed=[0, -1, 2])
    with pytest.raises(ValueError):
        vec.reset(options={"reset_mask": np.array([True, False])})
    vec.close()
