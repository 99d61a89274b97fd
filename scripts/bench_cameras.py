"""Camera env steps per second of Lift from Python, in one process: robosuite 1.5.2's
GymWrapper (``--lib robosuite``, run with its virtualenv and ``MUJOCO_GL=egl``) or
robosuite-rs's (``--lib rs``, run with the project's .venv), one camera (agentview) and two
(agentview + robot0_eye_in_hand) at each ``--sizes``; robosuite-rs at each render quality.
``--vec N[,N]``: robosuite-rs's ``make_vec`` of N envs (Rust threads) instead, with
``copy=True`` and ``copy=False`` (``--copies``; env steps per second: vector steps x N);
``--one-camera``: agentview only.

Prints one JSON object per line: lib, cameras, size, quality, num_envs, copy, steps_per_s.
``scripts/bench_cameras_vs_robosuite.sh`` runs both libraries and prints a table.
"""

from __future__ import annotations

import argparse
import json
import time
from typing import Any

import numpy as np

CAMERA_SETS = (["agentview"], ["agentview", "robot0_eye_in_hand"])


def camera_kwargs(cameras: list[str], size: int) -> dict[str, Any]:
    return dict(
        has_renderer=False,
        has_offscreen_renderer=True,
        use_camera_obs=True,
        camera_names=cameras,
        camera_heights=size,
        camera_widths=size,
    )


def time_single(suite: Any, wrapper: Any, kwargs: dict[str, Any], seconds: float, warmup: int) -> float:
    env = wrapper(suite.make("Lift", robots="Panda", **kwargs))
    rng = np.random.default_rng(0)
    low, high = env.action_space.low, env.action_space.high
    env.reset(seed=0)
    for _ in range(warmup):
        env.step(rng.uniform(low, high))
    steps = 0
    start = time.perf_counter()
    while time.perf_counter() - start < seconds:
        _, _, terminated, truncated, _ = env.step(rng.uniform(low, high))
        steps += 1
        if terminated or truncated:
            env.reset()
    rate = steps / (time.perf_counter() - start)
    env.close()
    return rate


def time_vec(suite: Any, n: int, copy: bool, kwargs: dict[str, Any], seconds: float, warmup: int) -> float:
    extra = {} if copy else {"copy": False}
    vec = suite.make_vec("Lift", n, robots="Panda", **extra, **kwargs)
    vec.action_space.seed(0)
    vec.reset(seed=0)
    for _ in range(warmup):
        vec.step(vec.action_space.sample())
    steps = 0
    start = time.perf_counter()
    while time.perf_counter() - start < seconds:
        obs, *_ = vec.step(vec.action_space.sample())
        steps += 1
    rate = steps * n / (time.perf_counter() - start)
    vec.close()
    return rate


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--lib", choices=["robosuite", "rs"], required=True)
    parser.add_argument("--seconds", type=float, default=8.0)
    parser.add_argument("--warmup", type=int, default=5)
    parser.add_argument("--sizes", default="84,256")
    parser.add_argument("--qualities", default="fast,robosuite", help="robosuite-rs render qualities")
    parser.add_argument("--vec", default="", help="comma-separated num_envs for make_vec (robosuite-rs)")
    parser.add_argument("--copies", default="true,false", help="with --vec: the copy values to time")
    parser.add_argument("--one-camera", action="store_true", help="agentview only")
    args = parser.parse_args()
    sizes = [int(s) for s in args.sizes.split(",") if s]
    if args.lib == "robosuite":
        import robosuite as suite
        from robosuite.wrappers import GymWrapper
    else:
        import robosuite_rs as suite
        from robosuite_rs.wrappers import GymWrapper
    for cameras in CAMERA_SETS[:1] if args.one_camera else CAMERA_SETS:
        for size in sizes:
            kwargs = camera_kwargs(cameras, size)
            row = {"lib": args.lib, "cameras": "+".join(cameras), "size": size}
            if args.vec:
                vec_cameras = dict(kwargs, flatten_obs=False, keys=[f"{c}_image" for c in cameras] + ["robot0_proprio-state"])
                copies = [c.strip().lower() == "true" for c in args.copies.split(",") if c]
                for n in [int(v) for v in args.vec.split(",") if v]:
                    for copy in copies:
                        rate = time_vec(suite, n, copy, vec_cameras, args.seconds, args.warmup)
                        print(json.dumps(row | {"num_envs": n, "copy": copy, "steps_per_s": rate}), flush=True)
                continue
            qualities = [None] if args.lib == "robosuite" else args.qualities.split(",")
            for quality in qualities:
                extra = {} if quality is None else {"render_quality": quality}
                rate = time_single(suite, GymWrapper, kwargs | extra, args.seconds, args.warmup)
                print(json.dumps(row | {"quality": quality or "robosuite", "steps_per_s": rate}), flush=True)


if __name__ == "__main__":
    main()
