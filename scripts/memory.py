"""Memory per environment from Python: the resident memory (RSS) and proportional set size
(PSS) of this process after one env of a task and after N more, made by one
``gymnasium.make_vec`` (Rust threads) or one by one with ``robosuite_rs.make``.

    python scripts/memory.py [--task Lift] [--envs 128] [--one-by-one] [--textures]

Envs have no cameras; the first env and those made one by one have no offscreen renderer,
so their scene is compiled without texture images, unless ``--textures`` gives them
``has_offscreen_renderer=True`` (the images kept). ``make_vec``'s envs keep the Python
default (``has_offscreen_renderer=True``). Prints the first env's RSS and make time and the RSS / PSS per further env in MiB.
Linux only (reads /proc/self).
"""

from __future__ import annotations

import argparse
import gc
import time

import gymnasium as gym
import numpy as np

import robosuite_rs as suite


def mib(file: str, key: str) -> float:
    with open(f"/proc/self/{file}") as f:
        for line in f:
            if line.startswith(key):
                return int(line.split()[1]) / 1024
    return float("nan")


def memory() -> tuple[float, float]:
    return mib("status", "VmRSS:"), mib("smaps_rollup", "Pss:")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--task", default="Lift")
    p.add_argument("--envs", type=int, default=128)
    p.add_argument("--one-by-one", action="store_true")
    p.add_argument("--textures", action="store_true")
    args = p.parse_args()
    robots = ["Panda", "Panda"] if args.task.startswith("TwoArm") else "Panda"
    kwargs = dict(robots=robots, has_renderer=False, has_offscreen_renderer=args.textures,
                  use_camera_obs=False)
    start = memory()
    made = time.perf_counter()
    first = suite.make(args.task, **kwargs)
    made = time.perf_counter() - made
    first.reset(seed=0)
    first.step(np.zeros(first.action_dim))
    one = memory()
    if args.one_by_one:
        envs = []
        for i in range(args.envs):
            env = suite.make(args.task, **kwargs)
            env.reset(seed=i + 1)
            env.step(np.zeros(env.action_dim))
            envs.append(env)
    else:
        vec = gym.make_vec(f"robosuite_rs/{args.task}-v0", args.envs)
        vec.reset(seed=1)
        vec.step(np.zeros(vec.action_space.shape, dtype=vec.action_space.dtype))
    gc.collect()
    last = memory()
    how = "one by one" if args.one_by_one else "one make_vec"
    print(f"{args.task}: {args.envs} further envs ({how})")
    print(f"  first env RSS      {one[0] - start[0]:8.1f} MiB   made in {made * 1e3:.0f} ms")
    print(f"  per further env    RSS {(last[0] - one[0]) / args.envs:6.2f} MiB"
          f"   PSS {(last[1] - one[1]) / args.envs:6.2f} MiB")


if __name__ == "__main__":
    main()
