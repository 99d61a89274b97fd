"""Throughput of robosuite 1.5.2's GymWrapper with random actions (one process, one env).

Prints JSON: task, steps_per_s (including resets at the horizon), reset_ms.
With --cameras NAME[,NAME] (and --size N) the env observes those cameras at N x N
(use_camera_obs=True; run with MUJOCO_GL=egl for headless rendering).
Run through scripts/bench_vs_robosuite.sh, which installs robosuite in a scratch venv.
"""
import argparse
import json
import time

import numpy as np
import robosuite as suite
from robosuite.wrappers import GymWrapper


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--task", default="Lift")
    parser.add_argument("--seconds", type=float, default=15.0)
    parser.add_argument("--cameras", default="", help="comma-separated camera names")
    parser.add_argument("--size", type=int, default=84)
    args = parser.parse_args()
    cameras = [c for c in args.cameras.split(",") if c]
    camera_kwargs = (
        dict(has_offscreen_renderer=True, use_camera_obs=True, camera_names=cameras,
             camera_heights=args.size, camera_widths=args.size)
        if cameras else dict(has_offscreen_renderer=False, use_camera_obs=False)
    )
    env = GymWrapper(suite.make(args.task, robots="Panda", has_renderer=False, **camera_kwargs))
    rng = np.random.default_rng(0)
    low, high = env.action_space.low, env.action_space.high
    env.reset(seed=0)
    # Warm up: robosuite compiles its numba helpers on first use.
    for _ in range(100):
        env.step(rng.uniform(low, high))
    env.reset()
    steps, resets, reset_time = 0, 0, 0.0
    start = time.perf_counter()
    while time.perf_counter() - start < args.seconds:
        _, _, terminated, truncated, _ = env.step(rng.uniform(low, high))
        steps += 1
        if terminated or truncated:
            t = time.perf_counter()
            env.reset()
            reset_time += time.perf_counter() - t
            resets += 1
    elapsed = time.perf_counter() - start
    t = time.perf_counter()
    for _ in range(5):
        env.reset()
    reset_ms = (time.perf_counter() - t) / 5 * 1000
    print(json.dumps({"task": args.task, "cameras": cameras, "size": args.size, "steps_per_s": steps / elapsed, "steps": steps,
                      "resets": resets, "reset_ms": reset_ms}))


if __name__ == "__main__":
    main()
