"""Steps per second of robosuite_rs from Python (GymWrapper, robosuite-style env, make_vec,
make_pool).

    .venv/bin/python python/scripts/bench.py [--task Lift] [--seconds 3] [--only gym] [--json]

Random actions, Panda with OSC_POSE, horizon 1000 (resets included), as robosuite's own
GymWrapper is measured by scripts/bench_robosuite.py; scripts/bench_vs_robosuite.sh runs
both, interleaved, and prints the ratios.
"""

from __future__ import annotations

import argparse
import json
import os
import time
from typing import Callable

import numpy as np

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper

QUIET = {"has_renderer": False, "has_offscreen_renderer": False, "use_camera_obs": False}


def timed(seconds: float, step: Callable[[], int]) -> float:
    """Calls ``step`` (which returns how many env steps it made) for ``seconds``; steps/s."""
    n = 0
    start = time.perf_counter()
    while time.perf_counter() - start < seconds:
        n += step()
    return n / (time.perf_counter() - start)


def bench_gym(task: str, seconds: float) -> float:
    """GymWrapper (a gymnasium.Env) steps per wall-clock second, resets included."""
    env = GymWrapper(suite.make(task, horizon=1000, **QUIET))
    env.reset(seed=0)
    env.action_space.seed(0)
    actions = [env.action_space.sample() for _ in range(1000)]

    def step() -> int:
        for a in actions:
            _, _, terminated, truncated, _ = env.step(a)
            if terminated or truncated:
                env.reset()
        return len(actions)

    return timed(seconds, step)


def bench_robosuite_api(task: str, seconds: float) -> float:
    """robosuite-style ``env.step`` (dict observations) steps per second, resets included."""
    env = suite.make(task, horizon=1000, **QUIET)
    env.reset()
    actions = np.random.default_rng(0).uniform(-1, 1, size=(1000, env.action_dim))

    def step() -> int:
        for a in actions:
            _, _, done, _ = env.step(a)
            if done:
                env.reset()
        return len(actions)

    return timed(seconds, step)


def bench_vec(task: str, num_envs: int, seconds: float) -> float:
    """make_vec env steps per second (all envs summed; autoreset included)."""
    vec = suite.make_vec(task, num_envs, horizon=1000, **QUIET)
    vec.reset(seed=0)
    vec.action_space.seed(0)
    actions = [vec.action_space.sample() for _ in range(100)]

    def step() -> int:
        for a in actions:
            vec.step(a)
        return len(actions) * num_envs

    rate = timed(seconds, step)
    vec.close()
    return rate


def bench_pool(task: str, seconds: float) -> float:
    """make_pool env steps per second: 2 envs per CPU, batches of one per CPU."""
    cpus = os.cpu_count() or 1
    pool = suite.make_pool(task, 2 * cpus, cpus, horizon=1000, **QUIET)
    pool.reset(seed=0)
    pool.action_space.seed(0)
    actions = [pool.action_space.sample() for _ in range(100)]

    def step() -> int:
        for a in actions:
            pool.step(a)
        return len(actions) * cpus

    rate = timed(seconds, step)
    pool.close()
    return rate


def main() -> None:
    """Prints the figures (or JSON with ``--json``)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--task", default="Lift")
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--only", choices=["gym"], help="measure only the GymWrapper")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args()
    figures = {"task": args.task, "gym_wrapper_steps_per_s": bench_gym(args.task, args.seconds)}
    if args.only is None:
        figures["robosuite_api_steps_per_s"] = bench_robosuite_api(args.task, args.seconds)
        for n in (1, 2, 4):
            figures[f"make_vec_{n}_steps_per_s"] = bench_vec(args.task, n, args.seconds)
        figures["make_pool_steps_per_s"] = bench_pool(args.task, args.seconds)
    if args.json:
        print(json.dumps(figures))
        return
    print(f"CPUs: {os.cpu_count()}, load average: {os.getloadavg()[0]:.2f}, task {args.task}")
    for key, value in figures.items():
        if key != "task":
            print(f"{key:<28} {value:8.0f}")


if __name__ == "__main__":
    main()
