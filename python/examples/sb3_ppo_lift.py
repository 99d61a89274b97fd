"""Stable-Baselines3 PPO on Lift with the Rust-threaded VecEnv, writing a learning curve.

    python python/examples/sb3_ppo_lift.py --timesteps 50000 --num-envs 4 --out docs/sb3_ppo_lift.png

The envs are stepped on Rust threads (``robosuite_rs.sb3.make_sb3_vec_env``), wrapped in
SB3's ``VecMonitor`` (episode returns) and ``VecNormalize``. A callback records each
finished episode's return and whether Lift was solved at any step of it (robosuite's
``_check_success``, ``info["is_success"]``); the PNG plots both against env steps, and the
same numbers are written next to it as CSV. Needs stable-baselines3 and matplotlib.
"""

from __future__ import annotations

import argparse
import csv
import time
from pathlib import Path

import numpy as np
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.vec_env import VecMonitor, VecNormalize

from robosuite_rs.sb3 import make_sb3_vec_env


class EpisodeLog(BaseCallback):
    """Collects ``(env steps, return, solved)`` for every finished episode."""

    def __init__(self) -> None:
        super().__init__()
        self.rows: list[tuple[int, float, bool]] = []
        self._solved: np.ndarray | None = None

    def _on_step(self) -> bool:
        infos, dones = self.locals["infos"], self.locals["dones"]
        if self._solved is None:
            self._solved = np.zeros(len(infos), dtype=bool)
        for i, info in enumerate(infos):
            self._solved[i] |= bool(info.get("is_success", False))
            if dones[i]:
                self.rows.append((self.num_timesteps, float(info["episode"]["r"]), bool(self._solved[i])))
                self._solved[i] = False
        return True


def smooth(values: np.ndarray, window: int) -> np.ndarray:
    """Trailing mean over ``window`` episodes."""
    out = np.empty(len(values))
    for i in range(len(values)):
        out[i] = values[max(0, i - window + 1) : i + 1].mean()
    return out


def plot(rows: list[tuple[int, float, bool]], out: Path, title: str) -> None:
    """Episode return and success rate against env steps."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    steps = np.array([r[0] for r in rows])
    returns = np.array([r[1] for r in rows])
    solved = np.array([r[2] for r in rows], dtype=float)
    window = max(1, len(rows) // 20)
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    ax1.plot(steps, returns, ".", alpha=0.3, label="episode")
    ax1.plot(steps, smooth(returns, window), "-", label=f"mean of last {window}")
    ax1.set_ylabel("episode return (shaped)")
    ax1.legend()
    ax2.plot(steps, smooth(solved, window), "-")
    ax2.set_ylabel(f"success rate (last {window} episodes)")
    ax2.set_xlabel("env steps")
    ax2.set_ylim(-0.02, 1.02)
    fig.suptitle(title)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=100)


def main(argv: list[str] | None = None) -> list[tuple[int, float, bool]]:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--timesteps", type=int, default=50_000)
    p.add_argument("--num-envs", type=int, default=4)
    p.add_argument("--horizon", type=int, default=200)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--out", type=Path, default=Path("sb3_ppo_lift.png"))
    args = p.parse_args(argv)
    import torch

    torch.set_num_threads(1)  # a small MLP trains fastest on one thread; the cores step envs

    venv = make_sb3_vec_env(
        "Lift", args.num_envs, seed=args.seed, horizon=args.horizon, reward_shaping=True,
        has_offscreen_renderer=False, use_camera_obs=False,
    )
    venv = VecNormalize(VecMonitor(venv), gamma=0.99)
    model = PPO(
        "MlpPolicy", venv, n_steps=512, batch_size=128, n_epochs=10, gamma=0.99, gae_lambda=0.95,
        learning_rate=3e-4, seed=args.seed, device="cpu", verbose=0,
    )
    log = EpisodeLog()
    start = time.perf_counter()
    model.learn(total_timesteps=args.timesteps, callback=log)
    elapsed = time.perf_counter() - start
    venv.close()
    rows = log.rows
    print(f"{model.num_timesteps} env steps in {elapsed:.1f} s ({model.num_timesteps / elapsed:.0f} steps/s), {len(rows)} episodes")
    if rows:
        tail = rows[-max(1, len(rows) // 10) :]
        head = rows[: max(1, len(rows) // 10)]
        print(f"mean return: first 10% of episodes {np.mean([r[1] for r in head]):.2f}, last 10% {np.mean([r[1] for r in tail]):.2f}")
        print(f"success rate: first 10% {np.mean([r[2] for r in head]):.2f}, last 10% {np.mean([r[2] for r in tail]):.2f}")
        plot(rows, args.out, f"SB3 PPO on robosuite_rs Lift (Panda, OSC_POSE), {args.num_envs} Rust-threaded envs")
        with open(args.out.with_suffix(".csv"), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["env_steps", "episode_return", "solved"])
            w.writerows(rows)
        print(f"wrote {args.out} and {args.out.with_suffix('.csv')}")
    return rows


if __name__ == "__main__":
    main()
