"""Stable-Baselines3's env checker and a short PPO run on robosuite_rs (not part of CI:
SB3 pulls in torch, several GB).

    .venv/bin/pip install stable-baselines3
    .venv/bin/python python/scripts/sb3_check.py [--timesteps 2048]

robosuite's GymWrapper example 3 with only the imports changed (and the task: robosuite's
example uses "Door", which robosuite_rs does not provide yet, so Lift).
"""

from __future__ import annotations

import argparse

from stable_baselines3 import PPO
from stable_baselines3.common.env_checker import check_env

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper


def main() -> None:
    """Checks the env with SB3's checker, trains PPO briefly and evaluates it."""
    parser = argparse.ArgumentParser()
    parser.add_argument("--timesteps", type=int, default=2048)
    args = parser.parse_args()

    env = suite.make(
        env_name="Door" if "Door" in suite.ALL_ENVIRONMENTS else "Lift",
        robots="Panda",
        has_renderer=False,
        has_offscreen_renderer=False,
        use_camera_obs=False,
    )
    gym_env = GymWrapper(env)

    # Verify Gymnasium compatibility
    check_env(gym_env)

    # Train PPO agent
    model = PPO("MlpPolicy", gym_env, verbose=1)
    model.learn(total_timesteps=args.timesteps)

    # Evaluate trained agent
    obs, info = gym_env.reset()
    for _ in range(1000):
        action, _states = model.predict(obs, deterministic=True)
        obs, reward, terminated, truncated, info = gym_env.step(action)
        if terminated or truncated:
            obs, info = gym_env.reset()

    gym_env.close()
    print("SB3 check_env and PPO run: OK")


if __name__ == "__main__":
    main()
