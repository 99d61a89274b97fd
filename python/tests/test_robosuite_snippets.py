"""robosuite 1.5.2's documented usage, run with only the imports swapped
(`robosuite_rs.install_as_robosuite()`, then robosuite's own code): basic usage
(robosuite.ai/docs/basicusage.html, with `has_renderer=False`), controllers
(modules/controllers.html), offscreen rendering (modules/renderers.html) and the
observables of robosuite's `demo_sensor_corruption.py` (corrupters, delayers, sampling
rates, `add_observable`). Each runs in a fresh interpreter, as a user's script would."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

PRELUDE = """
import robosuite_rs
robosuite_rs.install_as_robosuite()
"""

SNIPPETS = {
    "basic usage": """
        import numpy as np
        import robosuite as suite

        # create environment instance
        env = suite.make(
            env_name="Lift", # try with other tasks like "Stack" and "Door"
            robots="Panda",  # try with other robots like "Sawyer" and "Jaco"
            has_renderer=False,
            has_offscreen_renderer=False,
            use_camera_obs=False,
        )

        # reset the environment
        env.reset()

        for i in range(50):
            action = np.random.randn(*env.action_spec[0].shape) * 0.1
            obs, reward, done, info = env.step(action)  # take action in the environment
        assert obs["robot0_eef_pos"].shape == (3,) and isinstance(reward, float)
        print("OK")
    """,
    "controllers": """
        import numpy as np
        import robosuite as suite
        from robosuite import load_composite_controller_config, load_part_controller_config

        # BASIC controller: arms controlled using OSC, mobile base (if present) using JOINT_VELOCITY, other parts controlled using JOINT_POSITION
        controller_config = load_composite_controller_config(controller="BASIC")

        # create an environment to visualize on-screen
        env = suite.make(
            "TwoArmLift",
            robots=["Sawyer", "Panda"],             # load a Sawyer robot and a Panda robot
            gripper_types="default",                # use default grippers per robot arm
            controller_configs=controller_config,   # arms controlled via OSC, other parts via JOINT_POSITION/JOINT_VELOCITY
            env_configuration="opposed",            # (two-arm envs only) arms face each other
            has_renderer=False,                     # no on-screen rendering
            has_offscreen_renderer=False,           # no off-screen rendering
            control_freq=20,                        # 20 hz control for applied actions
            horizon=200,                            # each episode terminates after 200 steps
            use_object_obs=False,                   # no observations needed
            use_camera_obs=False,                   # no observations needed
        )
        env.reset()
        low, high = env.action_spec
        for _ in range(10):
            env.step(np.random.uniform(low, high))
        part = load_part_controller_config(default_controller="JOINT_VELOCITY")
        env = suite.make("Lift", robots="Panda", controller_configs=part, has_renderer=False,
                         has_offscreen_renderer=False, use_camera_obs=False)
        env.reset()
        assert env.robots[0].part_controllers["right"].name == "JOINT_VELOCITY"
        assert env.action_dim == 8
        print("OK")
    """,
    "offscreen rendering": """
        import numpy as np
        import robosuite as suite

        env = suite.make(
            "Lift",
            robots="Panda",
            has_renderer=False,
            has_offscreen_renderer=True,
            use_camera_obs=True,
            camera_names="agentview",
            camera_heights=84,
            camera_widths=84,
        )
        obs = env.reset()
        assert obs["agentview_image"].shape == (84, 84, 3)
        frame = env.sim.render(width=64, height=48, camera_name="frontview")
        assert frame.shape == (48, 64, 3) and frame.dtype == np.uint8 and frame.any()
        print("OK")
    """,
    "sensor corruption demo": """
        import numpy as np
        import robosuite as suite
        from robosuite.utils.observables import Observable, create_gaussian_noise_corrupter, create_uniform_sampled_delayer

        np.random.seed(0)
        env = suite.make(
            "Lift",
            robots="Panda",
            has_renderer=False,
            has_offscreen_renderer=True,
            ignore_done=True,
            camera_names="agentview",
            camera_heights=48,
            camera_widths=48,
            use_camera_obs=True,
            use_object_obs=True,
            hard_reset=False,
        )
        attributes = ["corrupter", "delayer", "sampling_rate"]

        def modify_obs(obs_name, attrs, mods):
            for attr, mod in zip(attrs, mods):
                env.modify_observable(
                    observable_name=obs_name,
                    attribute=attr,
                    modifier=mod,
                )

        image_obs_name = "agentview_image"
        image_corrupter = create_gaussian_noise_corrupter(mean=0.0, std=10.0, low=0, high=255)
        image_delayer = create_uniform_sampled_delayer(min_delay=0.0, max_delay=0.05)
        modify_obs(obs_name=image_obs_name, attrs=attributes, mods=[image_corrupter, image_delayer, 10.0])

        proprio_obs_name = f"{env.robots[0].robot_model.naming_prefix}joint_pos"
        joint_limits = env.sim.model.jnt_range[env.robots[0]._ref_joint_indexes]
        joint_range = joint_limits[:, 1] - joint_limits[:, 0]
        proprio_corrupter = create_gaussian_noise_corrupter(mean=0.0, std=joint_range / 50.0)
        curr_proprio_delay = 0.0
        tmp_delayer = create_uniform_sampled_delayer(min_delay=0.0, max_delay=0.02)

        def proprio_delayer():
            global curr_proprio_delay
            curr_proprio_delay = tmp_delayer()
            return curr_proprio_delay

        proprio_sensor = env._observables[proprio_obs_name]._sensor
        proprio_ground_truth_obs_name = f"{proprio_obs_name}_ground_truth"
        observable = Observable(
            name=proprio_ground_truth_obs_name,
            sensor=proprio_sensor,
            delayer=lambda: curr_proprio_delay,
            sampling_rate=20.0,
        )
        env.add_observable(observable)
        env.modify_observable(observable_name=proprio_obs_name, attribute="active", modifier=True)
        modify_obs(obs_name=proprio_obs_name, attrs=attributes, mods=[proprio_corrupter, proprio_delayer, 20.0])

        obs = env.reset()
        errors = []
        for _ in range(20):
            obs, _, _, _ = env.step(np.zeros(env.action_dim))
            errors.append(np.abs(obs[proprio_obs_name] - obs[proprio_ground_truth_obs_name]).max())
            assert obs[image_obs_name].shape == (48, 48, 3)
        # The corrupted joint positions differ from the ground truth by the noise only.
        assert 0 < np.mean(errors) < 0.5, errors
        print("OK")
    """,
}


@pytest.mark.parametrize("name", list(SNIPPETS))
def test_robosuites_documented_usage_runs_with_only_the_imports_swapped(name: str) -> None:
    code = PRELUDE + textwrap.dedent(SNIPPETS[name])
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-4000:]
    assert out.stdout.strip().endswith("OK"), out.stdout[-2000:]
