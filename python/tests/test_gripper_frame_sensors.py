"""robosuite 1.5.2's sensors that read (or write) other observables' ``obs_cache`` entries,
when those inputs are modified: the gripper-frame poses of PickPlace, NutAssembly and
ToolHang (``world_pose_in_gripper``, enabled and inactive; ``{obj}_to_robot0_eef_pos`` /
``_quat`` from the cached object pose and world pose), Wipe's centroid and
TwoArmPegInHole's ``peg_to_hole``, ``t`` and ``d``. The expected values are robosuite's
sensor code (``robosuite/environments/manipulation/manipulation_env.py``) applied to the
modified values the env observed."""

from __future__ import annotations

import numpy as np
import pytest

import robosuite_rs as suite
from robosuite_rs import observables as O
from robosuite_rs.utils import transform_utils as T

KW = dict(robots="Panda", has_renderer=False, has_offscreen_renderer=False, use_camera_obs=False, ignore_done=True)
GRIPPER_FRAME_TASKS = ["PickPlaceCan", "PickPlace", "NutAssemblySquare", "NutAssembly", "ToolHang"]


def make(task: str, **kw) -> suite.RobosuiteEnv:
    return suite.make(task, seed=3, **{**KW, **kw})


def actions(env, n: int, seed: int = 1) -> list[np.ndarray]:
    rng = np.random.default_rng(seed)
    return [0.5 * rng.uniform(-1, 1, env.action_dim) for _ in range(n)]


def same(a, b) -> bool:
    """Bitwise equal values (dtype and shape included)."""
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and bool(np.array_equal(a, b))


def identity(x):
    return x


def world_pose(obs) -> np.ndarray:
    """robosuite's ``_get_world_pose_in_gripper_sensor`` on observed eef values."""
    return T.pose_inv(T.pose2mat((obs["robot0_eef_pos"], obs["robot0_eef_quat"])))


def relative(pos, quat, pose_in_gripper) -> tuple[np.ndarray, np.ndarray]:
    """robosuite's ``_get_rel_obj_eef_sensor``: (relative position, relative quaternion)."""
    return T.mat2pose(T.pose_in_A_to_pose_in_B(T.pose2mat((pos, quat)), pose_in_gripper))


@pytest.mark.parametrize("task", GRIPPER_FRAME_TASKS)
def test_world_pose_in_gripper_is_enabled_inactive_and_first_of_the_task(task):
    env = make(task)
    names = list(env._observables)
    assert "world_pose_in_gripper" in env.observation_names
    assert "world_pose_in_gripper" in env.enabled_observables
    assert "world_pose_in_gripper" not in env.active_observables
    # robosuite's order: right after the robot's observables, before the objects'
    first_task = next(i for i, n in enumerate(names) if not n.startswith("robot0_"))
    assert names[first_task] == "world_pose_in_gripper"
    assert env._observables["world_pose_in_gripper"].modality == "object"
    obs = env.reset()
    assert "world_pose_in_gripper" not in obs and "world_pose_in_gripper" not in env.observation_keys()
    parts = [obs[k] for k in names if k in obs and env._observables[k].modality == "object"]
    assert obs["object-state"].shape == np.concatenate([np.ravel(p) for p in parts]).shape
    for a in [None] + actions(env, 3):
        if a is not None:
            obs = env.step(a)[0]
        value = env._obs_cache["world_pose_in_gripper"]
        assert value.shape == (4, 4) and value.dtype == np.float64
        np.testing.assert_allclose(value, world_pose(obs), rtol=0, atol=1e-12)
    # activated, it is served like any observable
    env.modify_observable("world_pose_in_gripper", "active", True)
    obs = env.step(actions(env, 1)[0])[0]
    np.testing.assert_allclose(obs["world_pose_in_gripper"], world_pose(obs), rtol=0, atol=1e-12)


@pytest.mark.parametrize("task", ["Lift", "Stack", "Door", "Wipe"])
def test_tasks_without_gripper_frame_poses_have_no_world_pose(task):
    assert not any(n.startswith("world_pose") for n in make(task).observation_names)


def test_no_world_pose_without_object_observations():
    assert "world_pose_in_gripper" not in make("PickPlaceCan", use_object_obs=False).observation_names


@pytest.mark.parametrize("task, obj", [("PickPlaceCan", "Can"), ("NutAssemblySquare", "SquareNut"), ("ToolHang", "tool")])
def test_corrupted_object_position_feeds_robosuites_relative_pose(task, obj):
    env, twin = make(task), make(task)
    env.modify_observable(f"{obj}_pos", "corrupter", O.create_deterministic_corrupter(0.05))
    obs, ref = env.reset(), twin.reset()
    # no cached object pose at the reset's observation: robosuite's zeros
    assert same(obs[f"{obj}_to_robot0_eef_pos"], np.zeros(3)) and same(obs[f"{obj}_to_robot0_eef_quat"], np.zeros(4))
    for a in actions(env, 6):
        prev = obs
        obs, ref = env.step(a)[0], twin.step(a)[0]
        assert np.array_equal(obs[f"{obj}_pos"], ref[f"{obj}_pos"] + 0.05)
        pose = env._obs_cache["world_pose_in_gripper"]
        np.testing.assert_allclose(pose, world_pose(obs), rtol=0, atol=1e-12)
        pos, quat = relative(prev[f"{obj}_pos"], prev[f"{obj}_quat"], pose)
        assert same(obs[f"{obj}_to_robot0_eef_pos"], pos)
        assert same(obs[f"{obj}_to_robot0_eef_quat"], quat)  # float32, as robosuite's mat2quat
        # the offset seen from the gripper: the world offset rotated into the gripper frame
        shift = pose[:3, :3] @ np.full(3, 0.05)
        np.testing.assert_allclose(obs[f"{obj}_to_robot0_eef_pos"] - ref[f"{obj}_to_robot0_eef_pos"], shift, atol=1e-5)
        np.testing.assert_allclose(obs[f"{obj}_to_robot0_eef_quat"], ref[f"{obj}_to_robot0_eef_quat"], atol=1e-5)
        for k in ref:
            if not k.startswith(obj) and k != "object-state":
                assert same(obs[k], ref[k]), k


def test_corrupted_eef_position_moves_the_world_pose_and_the_relative_poses():
    env, twin = make("PickPlaceCan"), make("PickPlaceCan")
    env.modify_observable("robot0_eef_pos", "corrupter", O.create_deterministic_corrupter(-0.02))
    obs, ref = env.reset(), twin.reset()
    for a in actions(env, 5):
        prev = obs
        obs, ref = env.step(a)[0], twin.step(a)[0]
        assert np.array_equal(obs["robot0_eef_pos"], ref["robot0_eef_pos"] - 0.02)
        pose = env._obs_cache["world_pose_in_gripper"]
        assert same(pose, world_pose(obs))  # computed from the cached, corrupted eef position
        pos, quat = relative(prev["Can_pos"], prev["Can_quat"], pose)
        assert same(obs["Can_to_robot0_eef_pos"], pos) and same(obs["Can_to_robot0_eef_quat"], quat)
        np.testing.assert_allclose(obs["Can_to_robot0_eef_pos"] - ref["Can_to_robot0_eef_pos"],
                                   pose[:3, :3] @ np.full(3, 0.02), atol=1e-5)


def test_disabled_world_pose_leaves_robosuites_relative_pose_on_its_stale_cache_entry():
    env = make("PickPlaceCan")
    env.reset()
    obs = env.step(actions(env, 1)[0])[0]
    stale = np.array(env._obs_cache["world_pose_in_gripper"])
    env.modify_observable("world_pose_in_gripper", "enabled", False)
    assert not env._obsv.fast
    for a in actions(env, 3, seed=3):
        prev, obs = obs, env.step(a)[0]
        pos, quat = relative(prev["Can_pos"], prev["Can_quat"], stale)
        assert same(obs["Can_to_robot0_eef_pos"], pos) and same(obs["Can_to_robot0_eef_quat"], quat)


@pytest.mark.parametrize("task", GRIPPER_FRAME_TASKS + ["Wipe", "TwoArmPegInHole"])
def test_unmodified_inputs_give_the_native_values_bit_for_bit(task):
    kw = {"robots": ["Panda", "Panda"]} if task.startswith("TwoArm") else {}
    fast, slow = make(task, **kw), make(task, **kw)
    other = "robot0_joint_vel"
    slow.modify_observable(other, "filter", identity)
    assert fast._obsv.fast and not slow._obsv.fast
    f, s = fast.reset(), slow.reset()
    assert list(f) == list(s) and all(same(f[k], s[k]) for k in f)
    for a in actions(fast, 8):
        f, s = fast.step(a)[0], slow.step(a)[0]
        assert list(f) == list(s) and all(same(f[k], s[k]) for k in f)
        for name in fast.observation_names:
            assert same(fast._observables[name]._current_observed_value, slow._observables[name]._current_observed_value), name


def test_corrupted_wipe_centroid_does_not_feed_back_into_itself():
    # robosuite's wipe_radius writes the raw centroid into obs_cache before wipe_centroid
    # reads it: the corruption is added once per sample, not accumulated
    env, twin = make("Wipe"), make("Wipe")
    env.modify_observable("wipe_centroid", "corrupter", O.create_deterministic_corrupter(0.1))
    obs, ref = env.reset(), twin.reset()
    for a in actions(env, 5):
        obs, ref = env.step(a)[0], twin.step(a)[0]
        assert np.array_equal(obs["wipe_centroid"], ref["wipe_centroid"] + 0.1)
        assert same(obs["gripper_to_wipe_centroid"], obs["wipe_centroid"] - obs["robot0_eef_pos"])


def test_disabled_wipe_radius_freezes_robosuites_wipe_centroid():
    env = make("Wipe")
    env.reset()
    obs = env.step(actions(env, 1)[0])[0]
    env.modify_observable("wipe_radius", "enabled", False)
    env.modify_observable("wipe_centroid", "corrupter", O.create_deterministic_corrupter(0.1))
    start = obs["wipe_centroid"]
    for k, a in enumerate(actions(env, 3, seed=4), start=1):
        obs = env.step(a)[0]
        # nothing writes the raw centroid any more: each sample corrupts the cached value again
        np.testing.assert_allclose(obs["wipe_centroid"], start + 0.1 * k, rtol=0, atol=1e-12)


def test_peg_in_hole_sensors_read_robosuites_cache_entries():
    env, twin = make("TwoArmPegInHole", robots=["Panda", "Panda"]), make("TwoArmPegInHole", robots=["Panda", "Panda"])
    env.modify_observable("hole_pos", "corrupter", O.create_deterministic_corrupter(0.05))
    env.modify_observable("angle", "corrupter", O.create_deterministic_corrupter(1.0))
    obs, ref = env.reset(), twin.reset()
    for a in actions(env, 4):
        obs, ref = env.step(a)[0], twin.step(a)[0]
        assert np.array_equal(obs["angle"], ref["angle"] + 1.0)
        # angle writes the raw t and d before t and d read them
        assert same(obs["t"], ref["t"]) and same(obs["d"], ref["d"])
        # peg_to_hole: the cached (corrupted) hole position minus the peg's body position
        peg = ref["hole_pos"] - ref["peg_to_hole"]
        np.testing.assert_allclose(obs["peg_to_hole"], obs["hole_pos"] - peg, rtol=0, atol=1e-12)
        assert not np.allclose(obs["peg_to_hole"], ref["peg_to_hole"])
