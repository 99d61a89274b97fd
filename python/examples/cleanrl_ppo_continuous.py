"""CleanRL-style PPO (continuous actions) on robosuite_rs with Gymnasium 1.x.

CleanRL's ``ppo_continuous_action.py`` pins gymnasium 0.29; its Gymnasium 1.x port builds
the envs exactly as :func:`make_env` below (the 1.x wrappers ``FlattenObservation``,
``RecordEpisodeStatistics``, ``ClipAction``, ``NormalizeObservation``,
``TransformObservation``, ``NormalizeReward``, ``TransformReward`` in a ``SyncVectorEnv``)
and runs unchanged on our ids. This file is our own, compact PPO in the same shape (one
file, the same hyper-parameters' names), so the env pipeline can be seen working end to
end::

    python python/examples/cleanrl_ppo_continuous.py --total-timesteps 20000

``--env-id`` takes any robosuite_rs id; ``"robosuite_rs:robosuite_rs/Lift-v0"`` (the
default) also works in processes that never imported robosuite_rs (``--async-envs``
builds an ``AsyncVectorEnv`` with spawned workers). Needs torch (``make test-rl``'s venv
has it); :func:`make_envs` and :func:`run_random` need only Gymnasium.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np

ENV_ID = "robosuite_rs:robosuite_rs/Lift-v0"
# Small, fast Lift episodes without any renderer.
ENV_KWARGS: dict[str, Any] = {"horizon": 100, "reward_shaping": True, "has_offscreen_renderer": False, "use_camera_obs": False}


def _clip_obs(obs: np.ndarray) -> np.ndarray:
    return np.clip(obs, -10, 10)


def _clip_reward(reward: float) -> float:
    return float(np.clip(reward, -10, 10))


def make_env(env_id: str, gamma: float, env_kwargs: dict[str, Any]) -> Callable[[], gym.Env]:
    """CleanRL's ``make_env`` thunk, Gymnasium 1.x form (module-level clip functions so the
    thunk pickles into spawned workers)."""

    def thunk() -> gym.Env:
        env = gym.make(env_id, **env_kwargs)
        env = gym.wrappers.FlattenObservation(env)
        env = gym.wrappers.RecordEpisodeStatistics(env)
        env = gym.wrappers.ClipAction(env)
        env = gym.wrappers.NormalizeObservation(env)
        env = gym.wrappers.TransformObservation(env, _clip_obs, env.observation_space)
        env = gym.wrappers.NormalizeReward(env, gamma=gamma)
        env = gym.wrappers.TransformReward(env, _clip_reward)
        return env

    return thunk


def make_envs(
    env_id: str = ENV_ID, num_envs: int = 2, gamma: float = 0.99, asynchronous: bool = False, env_kwargs: dict[str, Any] | None = None
) -> gym.vector.VectorEnv:
    """``num_envs`` CleanRL-wrapped envs in a ``SyncVectorEnv`` (or an ``AsyncVectorEnv``
    with spawned workers)."""
    fns = [make_env(env_id, gamma, ENV_KWARGS if env_kwargs is None else env_kwargs) for _ in range(num_envs)]
    if asynchronous:
        return gym.vector.AsyncVectorEnv(fns, context="spawn")
    return gym.vector.SyncVectorEnv(fns)


def episode_returns(infos: dict[str, Any]) -> list[tuple[float, int]]:
    """``(return, length)`` of each episode that ended this step (Gymnasium 1.x's
    ``RecordEpisodeStatistics`` in a vector env: ``infos["episode"]`` with mask ``_episode``)."""
    if "episode" not in infos:
        return []
    mask = infos["_episode"]
    return [(float(infos["episode"]["r"][i]), int(infos["episode"]["l"][i])) for i in np.flatnonzero(mask)]


def run_random(steps: int, num_envs: int = 2, seed: int = 0, env_kwargs: dict[str, Any] | None = None) -> list[tuple[float, int]]:
    """Steps the CleanRL pipeline with random actions; returns the finished episodes."""
    envs = make_envs(num_envs=num_envs, env_kwargs=env_kwargs)
    envs.reset(seed=seed)
    envs.action_space.seed(seed)
    done: list[tuple[float, int]] = []
    for _ in range(steps):
        *_, infos = envs.step(envs.action_space.sample())
        done += episode_returns(infos)
    envs.close()
    return done


def train(args: argparse.Namespace) -> list[tuple[int, float]]:
    """PPO as in CleanRL's ``ppo_continuous_action.py``; returns ``(global_step, return)``
    of each finished episode."""
    import torch
    from torch import nn
    from torch.distributions.normal import Normal

    torch.manual_seed(args.seed)
    torch.set_num_threads(1)  # a small MLP trains fastest on one thread
    envs = make_envs(args.env_id, args.num_envs, args.gamma, args.async_envs)
    obs_dim = int(np.prod(envs.single_observation_space.shape))
    act_dim = int(np.prod(envs.single_action_space.shape))

    def layer(i: int, o: int, std: float = np.sqrt(2)) -> nn.Linear:
        lin = nn.Linear(i, o)
        nn.init.orthogonal_(lin.weight, std)
        nn.init.constant_(lin.bias, 0.0)
        return lin

    critic = nn.Sequential(layer(obs_dim, 64), nn.Tanh(), layer(64, 64), nn.Tanh(), layer(64, 1, 1.0))
    actor_mean = nn.Sequential(layer(obs_dim, 64), nn.Tanh(), layer(64, 64), nn.Tanh(), layer(64, act_dim, 0.01))
    actor_logstd = nn.Parameter(torch.zeros(1, act_dim))
    params = list(critic.parameters()) + list(actor_mean.parameters()) + [actor_logstd]
    optimizer = torch.optim.Adam(params, lr=args.learning_rate, eps=1e-5)

    def policy(x: torch.Tensor) -> Normal:
        mean = actor_mean(x)
        return Normal(mean, actor_logstd.expand_as(mean).exp())

    n, t_max = args.num_envs, args.num_steps
    obs_buf = torch.zeros((t_max, n, obs_dim))
    act_buf = torch.zeros((t_max, n, act_dim))
    logp_buf = torch.zeros((t_max, n))
    rew_buf = torch.zeros((t_max, n))
    done_buf = torch.zeros((t_max, n))
    val_buf = torch.zeros((t_max, n))
    valid = torch.ones((t_max, n))  # 0 for Gymnasium 1.x's autoreset steps (NEXT_STEP)

    next_obs = torch.as_tensor(envs.reset(seed=args.seed)[0], dtype=torch.float32)
    next_done = torch.zeros(n)
    autoreset = np.zeros(n, dtype=bool)
    global_step, history = 0, []
    batch = n * t_max
    start = time.time()
    for _ in range(max(1, args.total_timesteps // batch)):
        for t in range(t_max):
            global_step += n
            obs_buf[t], done_buf[t] = next_obs, next_done
            valid[t] = torch.as_tensor(~autoreset, dtype=torch.float32)
            with torch.no_grad():
                dist = policy(next_obs)
                action = dist.sample()
                logp_buf[t] = dist.log_prob(action).sum(1)
                val_buf[t] = critic(next_obs).flatten()
            act_buf[t] = action
            obs, reward, term, trunc, infos = envs.step(action.numpy())
            autoreset = np.logical_or(term, trunc)
            rew_buf[t] = torch.as_tensor(reward, dtype=torch.float32)
            next_obs = torch.as_tensor(obs, dtype=torch.float32)
            next_done = torch.as_tensor(autoreset, dtype=torch.float32)
            for ret, _ in episode_returns(infos):
                history.append((global_step, ret))
        with torch.no_grad():
            next_value = critic(next_obs).flatten()
            adv = torch.zeros_like(rew_buf)
            last = torch.zeros(n)
            for t in reversed(range(t_max)):
                nonterminal = 1.0 - (next_done if t == t_max - 1 else done_buf[t + 1])
                value_next = next_value if t == t_max - 1 else val_buf[t + 1]
                delta = rew_buf[t] + args.gamma * value_next * nonterminal - val_buf[t]
                last = delta + args.gamma * args.gae_lambda * nonterminal * last
                adv[t] = last
            returns = adv + val_buf
        b_obs, b_act = obs_buf.reshape(batch, obs_dim), act_buf.reshape(batch, act_dim)
        b_logp, b_adv, b_ret = logp_buf.reshape(-1), adv.reshape(-1), returns.reshape(-1)
        b_valid = valid.reshape(-1).bool()
        idx_all = torch.nonzero(b_valid).flatten()
        mb = max(1, len(idx_all) // args.num_minibatches)
        for _ in range(args.update_epochs):
            perm = idx_all[torch.randperm(len(idx_all))]
            for s in range(0, len(perm), mb):
                idx = perm[s : s + mb]
                dist = policy(b_obs[idx])
                ratio = (dist.log_prob(b_act[idx]).sum(1) - b_logp[idx]).exp()
                a = b_adv[idx]
                a = (a - a.mean()) / (a.std() + 1e-8)
                pg = torch.max(-a * ratio, -a * ratio.clamp(1 - args.clip_coef, 1 + args.clip_coef)).mean()
                v_loss = 0.5 * ((critic(b_obs[idx]).flatten() - b_ret[idx]) ** 2).mean()
                loss = pg - args.ent_coef * dist.entropy().sum(1).mean() + args.vf_coef * v_loss
                optimizer.zero_grad()
                loss.backward()
                nn.utils.clip_grad_norm_(params, args.max_grad_norm)
                optimizer.step()
        recent = [r for _, r in history[-10:]]
        print(
            f"global_step={global_step} episodes={len(history)} "
            f"mean_return(last 10)={np.mean(recent) if recent else float('nan'):.3f} "
            f"SPS={int(global_step / (time.time() - start))}",
            flush=True,
        )
    envs.close()
    return history


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    """CleanRL's argument names (a subset)."""
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--env-id", default=ENV_ID)
    p.add_argument("--total-timesteps", type=int, default=20_000)
    p.add_argument("--learning-rate", type=float, default=3e-4)
    p.add_argument("--num-envs", type=int, default=2)
    p.add_argument("--num-steps", type=int, default=1024)
    p.add_argument("--gamma", type=float, default=0.99)
    p.add_argument("--gae-lambda", type=float, default=0.95)
    p.add_argument("--num-minibatches", type=int, default=32)
    p.add_argument("--update-epochs", type=int, default=10)
    p.add_argument("--clip-coef", type=float, default=0.2)
    p.add_argument("--ent-coef", type=float, default=0.0)
    p.add_argument("--vf-coef", type=float, default=0.5)
    p.add_argument("--max-grad-norm", type=float, default=0.5)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--async-envs", action="store_true", help="AsyncVectorEnv with spawned workers")
    return p.parse_args(argv)


if __name__ == "__main__":
    train(parse_args())
