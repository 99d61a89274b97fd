"""The two-arm tasks through robosuite's Python API: robot set-ups, observation layouts,
GymWrapper keys, Gymnasium's check_env and bad input."""
from __future__ import annotations

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper

# (task, action dim, object-state dim, proprio dim) as robosuite 1.5.2 reports them.
TWO_ARM = [
    ("TwoArmLift", 14, 19, 50),
    ("TwoArmPegInHole", 12, 17, 46),
    ("TwoArmHandover", 14, 16, 50),
    ("TwoArmTransport", 14, 41, 50),
]


def test_two_arm_tasks_are_listed() -> None:
    for task, *_ in TWO_ARM:
        assert task in suite.ALL_ENVIRONMENTS


@pytest.mark.parametrize("configuration", ["opposed", "parallel", "default"])
@pytest.mark.parametrize("task,dim,obj,proprio", TWO_ARM)
def test_make_with_two_pandas(task: str, dim: int, obj: int, proprio: int, configuration: str) -> None:
    env = suite.make(task, robots=["Panda", "Panda"], env_configuration=configuration, horizon=20)
    low, high = env.action_spec
    assert low.shape == (dim,) and np.all(low == -1.0) and np.all(high == 1.0)
    obs = env.reset()
    assert obs["object-state"].shape == (obj,)
    assert obs["robot0_proprio-state"].shape == (proprio,)
    assert obs["robot1_proprio-state"].shape == (proprio,)
    assert obs["robot1_eef_quat_site"].dtype == np.float32
    obs, reward, done, info = env.step(np.zeros(dim))
    assert reward == 0.0 and not done and info["success"] is False


def test_opposed_robots_act_in_their_own_base_frames() -> None:
    # robosuite: action +x moves robot 0's grip site along world +y and robot 1's along -y.
    env = suite.make("TwoArmLift", robots=["Panda", "Panda"], env_configuration="opposed", initialization_noise=None)
    obs = env.reset()
    start = [obs["robot0_eef_pos"].copy(), obs["robot1_eef_pos"].copy()]
    action = np.zeros(14)
    action[0] = action[7] = 1.0
    for _ in range(5):
        obs, *_ = env.step(action)
    assert obs["robot0_eef_pos"][1] - start[0][1] > 0.02
    assert obs["robot1_eef_pos"][1] - start[1][1] < -0.02


def test_gym_wrapper_default_keys_follow_robosuites_order() -> None:
    env = GymWrapper(suite.make("TwoArmLift", robots=["Panda", "Sawyer"]))
    assert env.keys == ["object-state", "robot0_proprio-state", "robot1_proprio-state"]
    obs, _ = env.reset(seed=0)
    assert obs.shape == (19 + 50 + 50,)
    assert env.action_space.shape == (14,)


@pytest.mark.parametrize("task", [t for t, *_ in TWO_ARM])
def test_check_env_on_two_arm_tasks(task: str) -> None:
    check_env(GymWrapper(suite.make(task, robots=["Panda", "Panda"], horizon=10)), skip_render_check=True)


def test_gymnasium_make_takes_two_arm_kwargs() -> None:
    env = gymnasium.make("robosuite_rs/TwoArmHandover-v0", robots=["Panda", "Sawyer"], env_configuration="parallel", horizon=5)
    obs, _ = env.reset(seed=1)
    assert obs.shape == (16 + 50 + 50,)
    env.close()


@pytest.mark.parametrize("task,dim,obj,proprio", TWO_ARM)
def test_one_baxter_is_the_single_robot_set_up(task: str, dim: int, obj: int, proprio: int) -> None:
    env = suite.make(task, robots="Baxter", horizon=5)
    obs = env.reset()
    assert env.action_dim == dim
    assert obs["object-state"].shape == (obj,)
    assert "robot0_right_eef_pos" in obs and "robot0_left_eef_pos" in obs
    assert "robot1_proprio-state" not in obs
    assert GymWrapper(env).keys == ["object-state", "robot0_proprio-state"]


def test_bad_two_arm_set_ups_raise_value_errors_listing_what_is_valid() -> None:
    with pytest.raises(ValueError, match="bimanual"):
        suite.make("TwoArmLift", robots="Panda")
    with pytest.raises(ValueError, match="got 3 robots"):
        suite.make("TwoArmLift", robots=["Panda"] * 3)
    with pytest.raises(ValueError, match="opposed.*parallel"):
        suite.make("TwoArmLift", robots=["Panda", "Panda"], env_configuration="diagonal")
    with pytest.raises(ValueError, match="only `default`"):
        suite.make("Lift", robots="Panda", env_configuration="opposed")
    with pytest.raises(ValueError, match="needs 1 robot"):
        suite.make("Lift", robots=["Baxter", "Panda"])
    with pytest.raises(ValueError, match="gripper_types"):
        suite.make("TwoArmPegInHole", robots=["Panda", "Panda"], gripper_types="PandaGripper")
