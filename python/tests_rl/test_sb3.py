"""Stable-Baselines3 on robosuite_rs (``make test-rl``): the Rust-threaded ``RustVecEnv``
against SB3's own ``DummyVecEnv``, with VecNormalize, VecMonitor, EvalCallback and
``model.learn``, and ``SubprocVecEnv`` workers started by spawn and forkserver with the
``"robosuite_rs:robosuite_rs/Lift-v0"`` id."""

from __future__ import annotations

import functools

import gymnasium as gym
import numpy as np
import pytest
from stable_baselines3 import PPO, SAC
from stable_baselines3.common.callbacks import EvalCallback
from stable_baselines3.common.env_checker import check_env
from stable_baselines3.common.monitor import Monitor
from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv, VecMonitor, VecNormalize

from robosuite_rs.sb3 import RustVecEnv, make_sb3_vec_env

pytestmark = pytest.mark.rl

QUIET = {"has_renderer": False, "has_offscreen_renderer": False, "use_camera_obs": False}
ID = "robosuite_rs/Lift-v0"
MODULE_ID = "robosuite_rs:robosuite_rs/Lift-v0"


def test_rust_vec_env_matches_dummy_vec_env_step_for_step() -> None:
    n, seed = 3, 11
    rust = make_sb3_vec_env("Lift", n, horizon=500, max_episode_steps=6, **QUIET)
    dummy = DummyVecEnv([functools.partial(gym.make, ID, horizon=500, max_episode_steps=6, **QUIET)] * n)
    assert rust.observation_space == dummy.observation_space and rust.action_space == dummy.action_space
    rust.seed(seed)
    dummy.seed(seed)
    np.testing.assert_array_equal(rust.reset(), dummy.reset())
    rng = np.random.default_rng(0)
    dones_seen = 0
    for t in range(20):
        actions = rng.uniform(-1, 1, size=(n, 7)).astype(np.float32)
        r_obs, r_rew, r_done, r_info = rust.step(actions)
        d_obs, d_rew, d_done, d_info = dummy.step(actions)
        np.testing.assert_array_equal(r_obs, d_obs, err_msg=f"step {t}")
        np.testing.assert_array_equal(r_rew, d_rew)
        assert r_rew.dtype == d_rew.dtype == np.float32
        np.testing.assert_array_equal(r_done, d_done)
        for a, b in zip(r_info, d_info):
            assert a["TimeLimit.truncated"] == b["TimeLimit.truncated"]
            assert ("terminal_observation" in a) == ("terminal_observation" in b)
            if "terminal_observation" in b:
                np.testing.assert_array_equal(a["terminal_observation"], b["terminal_observation"])
                assert a["TimeLimit.truncated"] is True
                dones_seen += 1
            assert a["success"] == b["success"] and a["is_success"] == bool(b["success"])
    assert dones_seen == 3 * n  # steps 6, 12 and 18
    # seed() applies to the next reset only, as in SB3.
    rust.seed(seed)
    dummy.seed(seed)
    np.testing.assert_array_equal(rust.reset(), dummy.reset())
    assert rust._seeds == [None] * n
    rust.close()
    dummy.close()


def test_sb3_stays_optional() -> None:
    import subprocess
    import sys

    code = "import sys, robosuite_rs; assert 'stable_baselines3' not in sys.modules; print(robosuite_rs.sb3.RustVecEnv.__name__)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0 and out.stdout.strip() == "RustVecEnv", out.stderr


def test_rust_vec_env_attribute_api() -> None:
    venv = make_sb3_vec_env("Lift", 2, horizon=10, **QUIET)
    assert venv.render_mode is None and venv.get_attr("render_mode") == [None, None]
    assert venv.get_attr("action_space", indices=1) == [venv.action_space]
    assert venv.env_is_wrapped(Monitor) == [False, False]
    with pytest.raises(AttributeError, match="no attribute 'foo'"):
        venv.get_attr("foo")
    with pytest.raises(AttributeError):
        venv.set_attr("horizon", 5)
    with pytest.raises(AttributeError):
        venv.env_method("check_success")
    venv.reset()
    assert venv.get_images() == [None, None]
    with pytest.raises(RuntimeError, match="step_async"):
        venv.step_wait()
    with pytest.raises(ValueError):
        venv.step(np.zeros((2, 6), dtype=np.float32))
    with pytest.raises(TypeError):
        RustVecEnv(DummyVecEnv([lambda: gym.make(ID, **QUIET)]))  # type: ignore[arg-type]
    venv.close()


def test_sb3_check_env_on_the_registered_id() -> None:
    check_env(gym.make(ID, horizon=10, **QUIET).unwrapped)


def test_ppo_learns_with_vec_normalize_vec_monitor_and_eval_callback(tmp_path) -> None:
    train = VecNormalize(VecMonitor(make_sb3_vec_env("Lift", 4, seed=0, max_episode_steps=32, **QUIET)))
    evaluation = VecNormalize(VecMonitor(make_sb3_vec_env("Lift", 2, seed=100, max_episode_steps=32, **QUIET)), training=False)
    callback = EvalCallback(evaluation, n_eval_episodes=2, eval_freq=64, log_path=str(tmp_path), verbose=0)
    model = PPO("MlpPolicy", train, n_steps=64, batch_size=64, n_epochs=1, seed=0, device="cpu")
    model.learn(total_timesteps=512, callback=callback)
    assert model.num_timesteps == 512
    assert len(model.ep_info_buffer) == 512 // 32  # VecMonitor's episodes: 4 envs x 128 steps / 32
    assert all(info["l"] == 32 for info in model.ep_info_buffer)
    assert train.obs_rms.count > 512  # VecNormalize saw every observation
    evals = np.load(tmp_path / "evaluations.npz")
    assert evals["results"].shape == (2, 2) and np.isfinite(evals["results"]).all()
    assert (evals["ep_lengths"] == 32).all()
    np.testing.assert_array_equal(evaluation.obs_rms.mean, train.obs_rms.mean)  # synced by EvalCallback
    train.close()
    evaluation.close()


def test_sac_runs_on_rust_vec_env() -> None:
    venv = make_sb3_vec_env("Lift", 2, seed=0, max_episode_steps=16, **QUIET)
    model = SAC("MlpPolicy", venv, learning_starts=32, batch_size=32, seed=0, device="cpu")
    model.learn(total_timesteps=96)
    assert model.num_timesteps == 96 and model.replay_buffer.size() == 48
    venv.close()


@pytest.mark.parametrize("start_method", ["spawn", "forkserver"])
def test_subproc_vec_env_with_module_id(start_method: str) -> None:
    # gymnasium.make pickles by reference: the workers import robosuite_rs only because
    # the id names it.
    make = functools.partial(gym.make, MODULE_ID, horizon=10, **QUIET)
    venv = SubprocVecEnv([make, make], start_method=start_method)
    venv.seed(5)
    obs = venv.reset()
    expected = [gym.make(ID, horizon=10, **QUIET).reset(seed=5 + i)[0] for i in range(2)]
    np.testing.assert_array_equal(obs, np.stack(expected))
    for _ in range(10):
        _, _, dones, infos = venv.step(np.zeros((2, 7), dtype=np.float32))
    assert dones.all() and all(i["TimeLimit.truncated"] for i in infos)
    venv.close()
