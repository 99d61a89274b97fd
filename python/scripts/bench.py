"""Steps per second of robosuite_rs from Python (single env and make_vec).

    .venv/bin/python python/scripts/bench.py [--steps 3000]

Random actions, Lift with a Panda and OSC_POSE, horizon 1000 (resets included), as the
robosuite 1.5.2 figure it is compared with (247.7 env steps/s for robosuite's own Lift on
the same kind of 2-vCPU machine; see shared/reference/robosuite-1.5.2-facts.md §10).
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper

QUIET = {"has_renderer": False, "has_offscreen_renderer": False, "use_camera_obs": False}


def bench_gym(steps: int) -> float:
    """GymWrapper steps per wall-clock second (resets included)."""
    env = GymWrapper(suite.make("Lift", horizon=1000, **QUIET))
    env.reset(seed=0)
    env.action_space.seed(0)
    actions = [env.action_space.sample() for _ in range(steps)]
    start = time.perf_counter()
    for a in actions:
        _, _, terminated, truncated, _ = env.step(a)
        if terminated or truncated:
            env.reset()
    return steps / (time.perf_counter() - start)


def bench_robosuite_api(steps: int) -> float:
    """robosuite-style ``env.step`` steps per second (resets included)."""
    env = suite.make("Lift", horizon=1000, **QUIET)
    env.reset()
    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, size=(steps, env.action_dim))
    start = time.perf_counter()
    for a in actions:
        _, _, done, _ = env.step(a)
        if done:
            env.reset()
    return steps / (time.perf_counter() - start)


def bench_vec(num_envs: int, steps: int) -> float:
    """make_vec env steps per second (all envs summed; autoreset included)."""
    vec = suite.make_vec("Lift", num_envs, horizon=1000, **QUIET)
    vec.reset(seed=0)
    vec.action_space.seed(0)
    actions = [vec.action_space.sample() for _ in range(steps // num_envs)]
    start = time.perf_counter()
    for a in actions:
        vec.step(a)
    rate = len(actions) * num_envs / (time.perf_counter() - start)
    vec.close()
    return rate


def main() -> None:
    """Prints the figures."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=3000)
    args = parser.parse_args()
    print(f"CPUs: {os.cpu_count()}, load average: {os.getloadavg()[0]:.2f}")
    print(f"GymWrapper (gymnasium.Env) single env: {bench_gym(args.steps):8.0f} steps/s")
    print(f"robosuite API env.step single env:     {bench_robosuite_api(args.steps):8.0f} steps/s")
    for n in (1, 2, 4):
        print(f"make_vec num_envs={n}:                   {bench_vec(n, args.steps):8.0f} env steps/s")


if __name__ == "__main__":
    main()
