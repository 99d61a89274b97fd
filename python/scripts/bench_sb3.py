"""SB3 PPO training throughput: robosuite_rs's Rust-threaded VecEnv against SubprocVecEnv.

    python python/scripts/bench_sb3.py --num-envs 2 4 --timesteps 16384 --json bench-sb3.json

For each ``n`` in ``--num-envs`` and each VecEnv (``RustVecEnv``: ``make_sb3_vec_env``,
one process, Rust threads; ``SubprocVecEnv``: one Python process per env, started by
``--start-method``, each making ``"robosuite_rs:robosuite_rs/Lift-v0"``; optionally
``DummyVecEnv``) it runs the same PPO (``MlpPolicy`` on CPU, ``VecMonitor``) for
``--timesteps`` env steps and reports env steps per second of ``model.learn`` (rollouts
and gradient updates: the training throughput), plus the rate of stepping the VecEnv alone
with random actions. One warm-up PPO iteration per VecEnv is not counted; ``--repeats`` runs
alternate between the VecEnvs and the medians are reported (on a shared machine the load
moves: compare only runs made together). Lift: Panda,
OSC_POSE, horizon ``--horizon``, no renderer. Needs stable-baselines3.
"""

from __future__ import annotations

import argparse
import functools
import json
import os
import platform
import time
from typing import Any

import gymnasium as gym
import numpy as np

ENV_KWARGS: dict[str, Any] = {"has_offscreen_renderer": False, "use_camera_obs": False}
MODULE_ID = "robosuite_rs:robosuite_rs/Lift-v0"


def make_venv(kind: str, n: int, horizon: int, start_method: str, rust_threads: int | None = None) -> Any:
    """A fresh SB3 VecEnv of ``kind`` with ``n`` Lift envs."""
    from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv

    from robosuite_rs.sb3 import make_sb3_vec_env

    kwargs = dict(ENV_KWARGS, horizon=horizon)
    if kind == "rust":
        return make_sb3_vec_env("Lift", n, threads=rust_threads, **kwargs)
    fns = [functools.partial(gym.make, MODULE_ID, **kwargs)] * n
    if kind == "subproc":
        return SubprocVecEnv(fns, start_method=start_method)
    if kind == "dummy":
        return DummyVecEnv(fns)
    raise ValueError(f"unknown VecEnv kind {kind!r}")


def stepping_rate(venv: Any, steps: int) -> float:
    """Env steps per second of ``venv.step`` with random actions (no learning)."""
    venv.seed(0)
    venv.reset()
    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, size=(steps, venv.num_envs) + venv.action_space.shape).astype(np.float32)
    start = time.perf_counter()
    for a in actions:
        venv.step(a)
    return steps * venv.num_envs / (time.perf_counter() - start)


def training_rate(venv: Any, timesteps: int, args: argparse.Namespace) -> float:
    """Env steps per second of ``PPO.learn`` (after one uncounted warm-up iteration)."""
    from stable_baselines3 import PPO
    from stable_baselines3.common.vec_env import VecMonitor

    venv = VecMonitor(venv)
    model = PPO(
        "MlpPolicy", venv, n_steps=args.n_steps, batch_size=args.batch_size, n_epochs=args.n_epochs,
        seed=0, device="cpu", verbose=0,
    )
    per_iteration = args.n_steps * venv.num_envs
    model.learn(total_timesteps=per_iteration)  # warm-up
    start = time.perf_counter()
    model.learn(total_timesteps=max(per_iteration, timesteps), reset_num_timesteps=False)
    elapsed = time.perf_counter() - start
    return (model.num_timesteps - per_iteration) / elapsed


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--num-envs", type=int, nargs="+", default=[os.cpu_count() or 2])
    p.add_argument("--timesteps", type=int, default=16_384)
    p.add_argument("--horizon", type=int, default=500)
    p.add_argument("--n-steps", type=int, default=256, help="PPO rollout length per env")
    p.add_argument("--batch-size", type=int, default=256)
    p.add_argument("--n-epochs", type=int, default=4)
    p.add_argument("--step-only", type=int, default=500, help="vector steps of the stepping-only rate")
    p.add_argument("--kinds", nargs="+", default=["rust", "subproc"], choices=["rust", "subproc", "dummy"])
    p.add_argument("--start-method", default="forkserver", choices=["fork", "forkserver", "spawn"])
    p.add_argument("--repeats", type=int, default=3, help="interleaved runs per VecEnv; medians reported")
    p.add_argument("--rust-threads", type=int, help="Rust worker threads (default: CPUs, at most num_envs)")
    p.add_argument("--torch-threads", type=int, default=1, help="torch.set_num_threads (small MLPs: 1 is fastest)")
    p.add_argument("--json", help="also write the results to this file")
    args = p.parse_args()

    import stable_baselines3
    import torch

    torch.set_num_threads(args.torch_threads)
    results = []
    print(
        f"machine: {platform.machine()}, {os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.1f}; "
        f"torch threads {torch.get_num_threads()}; SB3 {stable_baselines3.__version__}"
    )
    print(f"PPO MlpPolicy n_steps={args.n_steps} batch_size={args.batch_size} n_epochs={args.n_epochs}; Lift horizon {args.horizon}")
    for n in args.num_envs:
        runs: dict[str, list[tuple[float, float]]] = {kind: [] for kind in args.kinds}
        for r in range(args.repeats):
            for kind in args.kinds:  # interleaved, so load changes hit every kind alike
                venv = make_venv(kind, n, args.horizon, args.start_method, args.rust_threads)
                step_rate = stepping_rate(venv, args.step_only)
                venv.close()
                venv = make_venv(kind, n, args.horizon, args.start_method, args.rust_threads)
                train_rate = training_rate(venv, args.timesteps, args)
                venv.close()
                runs[kind].append((train_rate, step_rate))
                print(
                    f"run {r + 1}: {kind:>8} n={n:<3} PPO training {train_rate:8.0f} env steps/s   "
                    f"stepping only {step_rate:8.0f} env steps/s   (load average {os.getloadavg()[0]:.1f})",
                    flush=True,
                )
        for kind in args.kinds:
            train = [t for t, _ in runs[kind]]
            step = [s for _, s in runs[kind]]
            row = {
                "vec_env": kind,
                "num_envs": n,
                "train_steps_per_s_median": round(float(np.median(train)), 1),
                "train_steps_per_s_runs": [round(t, 1) for t in train],
                "step_only_steps_per_s_median": round(float(np.median(step)), 1),
            }
            results.append(row)
            print(
                f"median: {kind:>8} n={n:<3} PPO training {row['train_steps_per_s_median']:8.0f} env steps/s   "
                f"stepping only {row['step_only_steps_per_s_median']:8.0f} env steps/s"
            )
        by_kind = {r["vec_env"]: r for r in results if r["num_envs"] == n}
        if "rust" in by_kind and "subproc" in by_kind:
            ratio = by_kind["rust"]["train_steps_per_s_median"] / by_kind["subproc"]["train_steps_per_s_median"]
            print(f"n={n}: RustVecEnv / SubprocVecEnv training throughput (medians) = {ratio:.2f}x", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"config": vars(args), "cpus": os.cpu_count(), "results": results}, f, indent=2)


if __name__ == "__main__":
    main()
