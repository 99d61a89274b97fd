"""Ray RLlib PPO on Lift with several env runners on a Ray cluster.

    python python/examples/rllib_ppo_lift.py --iterations 5 --env-runners 2

``ray.init()`` starts a local cluster (or joins one: run the same script with
``RAY_ADDRESS=<head>:6379`` on a multi-node cluster, every node having robosuite_rs
installed). The env is named ``"robosuite_rs:robosuite_rs/Lift-v0"``: the env-runner
processes import robosuite_rs because the id says so (the plain ``"robosuite_rs/Lift-v0"``
fails there with ``NamespaceNotFound``: Gymnasium 1.x has no plugin entry points).
``--vector-entry-point`` steps each runner's envs in Rust threads (Gymnasium's
``vectorization_mode="vector_entry_point"``) instead of a ``SyncVectorEnv``.
"""

from __future__ import annotations

import argparse
import time

import ray
from ray.rllib.algorithms.ppo import PPOConfig

ENV_ID = "robosuite_rs:robosuite_rs/Lift-v0"


def main(argv: list[str] | None = None) -> list[dict]:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--iterations", type=int, default=5)
    p.add_argument("--env-runners", type=int, default=2)
    p.add_argument("--envs-per-runner", type=int, default=1)
    p.add_argument("--horizon", type=int, default=200)
    p.add_argument("--batch", type=int, default=2000, help="train_batch_size_per_learner")
    p.add_argument("--vector-entry-point", action="store_true")
    args = p.parse_args(argv)

    ray.init(include_dashboard=False)
    config = (
        PPOConfig()
        .environment(
            ENV_ID,
            env_config={"horizon": args.horizon, "reward_shaping": True, "has_offscreen_renderer": False, "use_camera_obs": False},
        )
        .env_runners(
            num_env_runners=args.env_runners,
            num_envs_per_env_runner=args.envs_per_runner,
            gym_env_vectorize_mode="vector_entry_point" if args.vector_entry_point else "sync",
        )
        .training(train_batch_size_per_learner=args.batch, minibatch_size=min(250, args.batch), num_epochs=5, lr=3e-4)
    )
    algo = config.build_algo()
    results = []
    start = time.perf_counter()
    try:
        for i in range(args.iterations):
            result = algo.train()
            runners = result["env_runners"]
            steps = runners["num_env_steps_sampled_lifetime"]
            print(
                f"iteration {i + 1}: env steps {steps}, episodes {runners.get('num_episodes_lifetime')}, "
                f"episode_return_mean {runners.get('episode_return_mean', float('nan')):.2f}, "
                f"{steps / (time.perf_counter() - start):.0f} env steps/s",
                flush=True,
            )
            results.append(result)
    finally:
        algo.stop()
        ray.shutdown()
    return results


if __name__ == "__main__":
    main()
