"""Ray RLlib on robosuite_rs (``make test-rl``): PPO with two env runners on a local Ray
cluster, the env named by the ``"robosuite_rs:robosuite_rs/Lift-v0"`` id (the runner
processes import robosuite_rs because the id says so), in Gymnasium's ``sync`` mode and
with our Rust-threaded vector entry point inside each runner."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

import ray
from ray.rllib.algorithms.ppo import PPOConfig
from ray.rllib.utils.metrics import (
    ENV_RUNNER_RESULTS,
    NUM_ENV_STEPS_SAMPLED_LIFETIME,
    NUM_EPISODES_LIFETIME,
)

pytestmark = pytest.mark.rl

MODULE_ID = "robosuite_rs:robosuite_rs/Lift-v0"
ENV_CONFIG = {"horizon": 25, "has_offscreen_renderer": False, "use_camera_obs": False}


@pytest.fixture(scope="module")
def local_ray() -> Iterator[None]:
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    yield
    ray.shutdown()


@pytest.mark.parametrize("mode,envs_per_runner", [("sync", 1), ("vector_entry_point", 2)])
def test_ppo_trains_with_two_env_runners(local_ray: None, mode: str, envs_per_runner: int) -> None:
    config = (
        PPOConfig()
        .environment(MODULE_ID, env_config=ENV_CONFIG)
        .env_runners(num_env_runners=2, num_envs_per_env_runner=envs_per_runner, gym_env_vectorize_mode=mode)
        .training(train_batch_size_per_learner=200, minibatch_size=100, num_epochs=1)
    )
    algo = config.build_algo()
    try:
        result = algo.train()
        runners = result[ENV_RUNNER_RESULTS]
        assert runners[NUM_ENV_STEPS_SAMPLED_LIFETIME] >= 200
        # Episodes of 25 steps ended (truncated by the horizon) in the runner processes.
        assert runners[NUM_EPISODES_LIFETIME] >= 200 // 25 - 2 * envs_per_runner
        assert runners["episode_len_mean"] == 25
    finally:
        algo.stop()
