"""robosuite's GymWrapper example 2 (the training-loop pattern), unchanged except for the
imports and one fallback: it runs "Stack" as robosuite's example does, or "Lift" in a
build of robosuite_rs that does not provide Stack."""

import numpy as np
import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper

ENV_NAME = "Stack" if "Stack" in suite.ALL_ENVIRONMENTS else "Lift"

# Create and wrap environment
env = suite.make(
    env_name=ENV_NAME,
    robots="Panda",
    has_renderer=False,
    has_offscreen_renderer=False,
    use_camera_obs=False,
    horizon=200,
)

gym_env = GymWrapper(
    env,
    keys=["robot0_proprio-state", "object-state"],
    flatten_obs=True
)

# Training loop compatible with any Gymnasium-based RL library
num_episodes = 10
for episode in range(num_episodes):
    obs, info = gym_env.reset(seed=episode)
    episode_reward = 0
    episode_length = 0

    done = False
    while not done:
        # In practice, replace with policy network
        action = gym_env.action_space.sample()

        # Standard Gymnasium step
        obs, reward, terminated, truncated, info = gym_env.step(action)

        episode_reward += reward
        episode_length += 1

        # Episode ends if terminated OR truncated
        done = terminated or truncated

        # Check for success (if provided in info)
        if done and info.get("success", False):
            print(f"Episode {episode}: SUCCESS!")

    print(f"Episode {episode}: reward={episode_reward:.2f}, length={episode_length}")

gym_env.close()
