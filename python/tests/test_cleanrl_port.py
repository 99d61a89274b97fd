"""CleanRL's Gymnasium 1.x env pipeline (python/examples/cleanrl_ppo_continuous.py) on our
ids: the wrappers CleanRL stacks do what they say on a few hundred steps."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np

from .conftest import QUIET

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "cleanrl_ppo_continuous.py"
HORIZON = 50


def _example():
    spec = importlib.util.spec_from_file_location("cleanrl_ppo_continuous", EXAMPLE)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def test_cleanrl_wrappers_on_robosuite_rs() -> None:
    ex = _example()
    kwargs = dict(QUIET, horizon=HORIZON, reward_shaping=True)
    envs = ex.make_envs(num_envs=2, env_kwargs=kwargs)
    assert isinstance(envs, gym.vector.SyncVectorEnv)
    wrappers = []
    env = envs.envs[0]
    while isinstance(env, gym.Wrapper):
        wrappers.append(type(env).__name__)
        env = env.env
    for name in ("TransformReward", "NormalizeReward", "TransformObservation", "NormalizeObservation", "ClipAction", "RecordEpisodeStatistics", "FlattenObservation"):
        assert name in wrappers
    # The same envs without CleanRL's wrappers, stepped with the same actions.
    plain = gym.vector.SyncVectorEnv([lambda: gym.make(ex.ENV_ID, **kwargs)] * 2)
    obs, _ = envs.reset(seed=3)
    plain.reset(seed=3)
    rng = np.random.default_rng(0)
    raw_returns = np.zeros(2)
    expected: list[tuple[float, int]] = []
    got: list[tuple[float, int]] = []
    all_obs, scaled, raw = [obs], [], []
    for _ in range(3 * (HORIZON + 1)):
        actions = rng.uniform(-1, 1, size=(2, 7)).astype(np.float32)
        obs, rew, term, trunc, infos = envs.step(actions)
        _, p_rew, p_term, p_trunc, _ = plain.step(actions)
        np.testing.assert_array_equal(term | trunc, p_term | p_trunc)
        raw_returns += p_rew
        for i in np.flatnonzero(p_term | p_trunc):
            expected.append((raw_returns[i], HORIZON))
            raw_returns[i] = 0.0
        got += ex.episode_returns(infos)
        all_obs.append(obs)
        scaled.append(rew)
        raw.append(p_rew)
    envs.close()
    plain.close()
    # RecordEpisodeStatistics: every episode, its raw return and length.
    assert len(got) == len(expected) == 6
    for (r, length), (r_exp, l_exp) in zip(sorted(got), sorted(expected)):
        assert length == l_exp and np.isclose(r, r_exp, rtol=1e-5)
    # NormalizeObservation saw every observation (reset, 153 steps); clipping bounds them.
    norm = envs.envs[0]
    while not isinstance(norm, gym.wrappers.NormalizeObservation):
        norm = norm.env
    assert round(norm.obs_rms.count) == 1 + 3 * (HORIZON + 1)
    stacked = np.concatenate(all_obs)
    assert np.abs(stacked).max() <= 10.0 and stacked.std() < 5.0
    # NormalizeReward rescales the rewards the agent sees (the raw ones are unchanged above).
    scaled_arr, raw_arr = np.concatenate(scaled), np.concatenate(raw)
    moving = raw_arr != 0
    assert moving.any() and not np.allclose(scaled_arr[moving], raw_arr[moving])
    assert np.abs(scaled_arr).max() <= 10.0


def test_cleanrl_random_run_reports_episodes() -> None:
    episodes = _example().run_random(steps=2 * (HORIZON + 1), num_envs=2, env_kwargs=dict(QUIET, horizon=HORIZON))
    assert [length for _, length in episodes] == [HORIZON] * 4
    assert all(np.isfinite(r) for r, _ in episodes)
