"""robosuite's GymWrapper example 1 (random actions), unchanged except for the imports."""

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper

# Create robosuite environment
env = suite.make(
    env_name="Lift",
    robots="Panda",
    has_renderer=False,
    has_offscreen_renderer=False,
    use_camera_obs=False,
)

# Wrap with GymWrapper
gym_env = GymWrapper(env)

# Print space information
print(f"Observation space: {gym_env.observation_space}")
print(f"Action space: {gym_env.action_space}")

# Run episode with random actions
obs, info = gym_env.reset(seed=42)
print(f"Initial observation shape: {obs.shape}")

for step in range(100):
    # Sample random action
    action = gym_env.action_space.sample()

    # Execute action
    obs, reward, terminated, truncated, info = gym_env.step(action)

    # Check if episode ended
    if terminated or truncated:
        print(f"Episode ended at step {step}")
        obs, info = gym_env.reset()

gym_env.close()
