"""Bimanual robots (Baxter, Tiago) on robosuite's single-arm tasks through robosuite's Python
API: observation layouts equal robosuite 1.5.2's (recorded in
robosuite-env/tests/fixtures/robosuite/observations.json), GymWrapper's flat keys and
Gymnasium's check_env."""
from __future__ import annotations

import json
import pathlib

import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper

LAYOUTS = pathlib.Path(__file__).resolve().parents[2] / "robosuite-env" / "tests" / "fixtures" / "robosuite" / "observations.json"


@pytest.mark.parametrize("task,robot", [("Lift", "Baxter"), ("Lift", "Tiago"), ("Door", "Baxter"), ("Wipe", "Baxter")])
def test_layout_equals_robosuites(task: str, robot: str) -> None:
    want = json.loads(LAYOUTS.read_text())[f"{task}-{robot}"]
    env = suite.make(task, robots=robot, horizon=5)
    obs = env.reset()
    assert env.action_dim == want["action_dim"]
    assert [[k, list(np.asarray(v).shape), str(np.asarray(v).dtype)] for k, v in obs.items()] == want["obs"]
    obs, reward, done, info = env.step(np.zeros(env.action_dim))
    assert info["success"] is False and not done


def test_gym_wrapper_flattens_robosuites_keys() -> None:
    env = suite.make("Lift", robots="Baxter", horizon=5)
    wrapped = GymWrapper(env)
    assert wrapped.keys == ["object-state", "robot0_proprio-state"]
    raw = env.reset()
    flat, _ = wrapped.reset(seed=3)
    assert flat.shape == (raw["object-state"].size + raw["robot0_proprio-state"].size,)
    # Both grippers' offsets to the cube are in the object state, right arm first.
    assert raw["object-state"].shape == (3 + 4 + 3 + 3,)
    check_env(GymWrapper(suite.make("Lift", robots="Baxter", horizon=10)), skip_render_check=True)


def test_two_robots_on_a_single_arm_task_raise_listing_the_robots() -> None:
    with pytest.raises(ValueError, match="needs 1 robot.*Baxter"):
        suite.make("Lift", robots=["Baxter", "Panda"])
