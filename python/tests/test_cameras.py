"""Camera observations and Gymnasium rendering from Python (robosuite's camera arguments,
``render_mode``), checked against the robosuite fixture the Rust tests use."""

from __future__ import annotations

import json
import sys
import threading
import time
import warnings
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from gymnasium.wrappers import RecordVideo

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper

from .conftest import unexpected

FIXTURE = json.loads(
    (Path(__file__).parents[2] / "robosuite-env/tests/fixtures/robosuite/lift_cameras.json").read_text()
)
SIZE = FIXTURE["size"]
CAMERAS = dict(
    use_camera_obs=True,
    has_offscreen_renderer=True,
    camera_names=FIXTURE["cameras"],
    camera_heights=SIZE,
    camera_widths=SIZE,
    camera_depths=True,
    camera_segmentations="element",
)


def lift(**kwargs: Any) -> suite.RobosuiteEnv:
    return suite.make("Lift", robots="Panda", horizon=20, **kwargs)


def test_keys_shapes_and_dtypes_are_robosuites() -> None:
    env = lift(**CAMERAS)
    obs = env.reset(seed=0)
    ours = [{"key": k, "shape": list(v.shape), "dtype": str(v.dtype)} for k, v in obs.items()]
    assert ours == FIXTURE["keys"]
    assert env.use_camera_obs and env.has_offscreen_renderer
    assert env.camera_names == FIXTURE["cameras"]
    image = obs["agentview_image"]
    assert image.dtype == np.uint8 and image.flags.c_contiguous and image.std() > 0
    depth = obs["agentview_depth"]
    assert depth.dtype == np.float32 and 0.0 < depth.min() and depth.max() <= 1.0
    env.close()


def test_use_camera_obs_alone_works_as_in_robosuite() -> None:
    # robosuite's has_offscreen_renderer defaults to True, camera_names to agentview.
    env = lift(use_camera_obs=True, camera_heights=16, camera_widths=16)
    assert env.has_offscreen_renderer and env.camera_names == ["agentview"]
    assert env.reset(seed=0)["agentview_image"].shape == (16, 16, 3)
    env.close()


def test_gym_wrapper_default_keys_and_uint8_dict_spaces() -> None:
    env = lift(**CAMERAS)
    g = GymWrapper(env)
    assert g.keys == FIXTURE["gym_default_keys"]
    flat_len = 10 + 2 * SIZE * SIZE * 3 + env.reset(seed=0)["robot0_proprio-state"].size
    assert g.observation_space.shape == (flat_len,)
    d = GymWrapper(env, flatten_obs=False)
    assert list(d.observation_space.spaces) == FIXTURE["gym_default_keys"]
    box = d.observation_space["agentview_image"]
    assert box.dtype == np.uint8 and box.shape == (SIZE, SIZE, 3)
    assert box.low.min() == 0 and box.high.max() == 255
    obs, _ = d.reset(seed=1)
    assert obs["robot0_eye_in_hand_image"].dtype == np.uint8
    assert obs in d.observation_space
    env.close()


@pytest.mark.parametrize("flatten_obs", [True, False])
def test_check_env_with_image_observations(flatten_obs: bool) -> None:
    g = GymWrapper(lift(**CAMERAS), flatten_obs=flatten_obs)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(g, skip_render_check=True)
    assert unexpected(caught) == []
    g.close()


def test_check_env_with_render_mode_rgb_array() -> None:
    env = gym.make("robosuite_rs/Lift-v0", horizon=10, render_mode="rgb_array", render_width=48, render_height=32)
    assert env.render_mode == "rgb_array"
    assert env.metadata["render_modes"] == ["rgb_array", "depth_array"]
    assert env.metadata["render_fps"] == 20
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        # Also makes the env with each declared render mode and checks its frames.
        check_env(env.unwrapped)
    assert unexpected(caught) == []
    env.reset(seed=0)
    frame = env.render()
    assert isinstance(frame, np.ndarray) and frame.dtype == np.uint8 and frame.shape == (32, 48, 3)
    assert frame.std() > 0
    env.close()


def test_render_modes_and_sizes() -> None:
    none = gym.make("robosuite_rs/Lift-v0", render_mode=None)
    none.reset(seed=0)
    assert none.render_mode is None and none.render() is None
    depth = gym.make("robosuite_rs/Lift-v0", render_mode="depth_array", render_camera="agentview")
    depth.reset(seed=0)
    d = depth.render()
    assert d.dtype == np.float32 and d.shape == (256, 256) and 0.0 < d.min() < d.max() <= 1.0
    # robosuite's API env takes render_mode too; the GymWrapper draws it.
    g = GymWrapper(lift(render_mode="rgb_array", render_camera="birdview", render_width=20, render_height=10))
    g.reset(seed=0)
    assert g.render_mode == "rgb_array" and g.render().shape == (10, 20, 3)


def test_same_seed_same_pixels() -> None:
    def run() -> list[np.ndarray]:
        env = gym.make(
            "robosuite_rs/Lift-v0", flatten_obs=False, render_mode="rgb_array", render_width=32, render_height=32, **CAMERAS
        )
        obs, _ = env.reset(seed=7)
        env.action_space.seed(7)
        frames = [obs["agentview_image"], env.render()]
        for _ in range(3):
            obs, *_ = env.step(env.action_space.sample())
            frames += [obs["agentview_image"], obs["robot0_eye_in_hand_image"], env.render()]
        env.close()
        return frames

    a, b = run(), run()
    assert all(np.array_equal(x, y) for x, y in zip(a, b, strict=True))
    # The robot moves: the eye-in-hand view changes between steps.
    assert not np.array_equal(a[3], a[6])


def test_render_collection_and_record_video(tmp_path: Path) -> None:
    env = gym.make("robosuite_rs/Lift-v0", horizon=4, render_mode="rgb_array_list", render_width=32, render_height=32)
    env.reset(seed=0)
    for _ in range(3):
        env.step(env.action_space.sample())
    frames = env.render()
    assert len(frames) == 4 and all(f.shape == (32, 32, 3) and f.dtype == np.uint8 for f in frames)
    env.close()

    video = RecordVideo(
        gym.make("robosuite_rs/Lift-v0", horizon=4, render_mode="rgb_array", render_width=32, render_height=32),
        str(tmp_path / "videos"),
        episode_trigger=lambda _: True,
    )
    video.reset(seed=0)
    done = False
    while not done:
        _, _, terminated, truncated, _ = video.step(video.action_space.sample())
        done = terminated or truncated
    video.close()
    files = list((tmp_path / "videos").glob("*.mp4"))
    assert len(files) == 1 and files[0].stat().st_size > 0


def test_vector_env_with_images() -> None:
    vec = suite.make_vec("Lift", 2, flatten_obs=False, keys=["agentview_image", "cube_pos"], **CAMERAS)
    obs, _ = vec.reset(seed=0)
    assert obs["agentview_image"].dtype == np.uint8 and obs["agentview_image"].shape == (2, SIZE, SIZE, 3)
    obs, *_ = vec.step(vec.action_space.sample())
    assert obs["agentview_image"].shape == (2, SIZE, SIZE, 3) and obs in vec.observation_space
    vec.close()


def test_gil_is_released_while_rendering_and_stepping() -> None:
    env = gym.make(
        "robosuite_rs/Lift-v0", render_mode="rgb_array", render_width=64, render_height=64, flatten_obs=False, **CAMERAS
    )
    env.reset(seed=0)
    count = 0
    stop = False

    def spin() -> None:
        nonlocal count
        while not stop:
            count += 1

    # With a long switch interval the spinning thread only runs while the main thread has
    # released the GIL: here, only inside the Rust calls.
    old = sys.getswitchinterval()
    sys.setswitchinterval(0.5)
    thread = threading.Thread(target=spin)
    thread.start()
    try:
        time.sleep(0.01)
        before = count
        env.render()
        during_render = count - before
        before = count
        env.step(env.action_space.sample())
        during_step = count - before
    finally:
        stop = True
        thread.join()
        sys.setswitchinterval(old)
        env.close()
    assert during_render > 0 and during_step > 0


def test_segmentation_levels_per_camera() -> None:
    env = lift(
        use_camera_obs=True,
        has_offscreen_renderer=True,
        camera_names=["agentview", "frontview"],
        camera_heights=48,
        camera_widths=48,
        camera_segmentations=[["instance", "class"], None],
    )
    obs = env.reset(seed=0)
    seg_keys = [k for k in obs if "_segmentation_" in k]
    assert seg_keys == ["agentview_segmentation_instance", "agentview_segmentation_class"]
    inst = obs["agentview_segmentation_instance"]
    assert inst.dtype == np.int32 and inst.shape == (48, 48, 1)
    # robosuite's instances on Lift: cube, Panda0, RethinkMount0, PandaGripper0_right.
    assert set(np.unique(inst).tolist()) <= {0, 1, 2, 3, 4} and (inst == 1).any()
    # One instance per class on Lift: the same ids.
    assert np.array_equal(inst, obs["agentview_segmentation_class"])
    env.close()


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"camera_names": "nocam"}, r"unknown camera `nocam`; valid: .*agentview.*robot0_eye_in_hand"),
        ({"render_mode": "rgb_array", "render_camera": "nocam"}, r"render_camera.*valid: .*frontview"),
        ({"camera_heights": 0}, "camera_heights"),
        ({"camera_widths": 100_000}, "camera_widths"),
        ({"camera_names": ["agentview", "frontview"], "camera_heights": [64, 64, 64]}, "camera_heights"),
        ({"camera_heights": "big"}, "camera_heights"),
        ({"camera_depths": "yes"}, "camera_depths"),
        ({"camera_segmentations": "everything"}, "segmentation"),
        ({"has_offscreen_renderer": False}, "has_offscreen_renderer"),
        ({"render_mode": "movie"}, "render mode"),
        ({"render_width": -3}, "render_width"),
    ],
)
def test_bad_camera_options_raise_value_error(kwargs: dict[str, Any], match: str) -> None:
    args = {"use_camera_obs": True, "has_offscreen_renderer": True} | kwargs
    with pytest.raises(ValueError, match=match):
        lift(**args)


def test_render_quality_fast_is_close_to_robosuite_quality_and_deterministic() -> None:
    def frames(quality: str) -> list[np.ndarray]:
        env = lift(
            use_camera_obs=True,
            camera_names=["agentview", "robot0_eye_in_hand"],
            camera_heights=64,
            camera_widths=64,
            render_quality=quality,
        )
        obs = env.reset(seed=0)
        env.close()
        return [obs["agentview_image"].astype(float), obs["robot0_eye_in_hand_image"].astype(float)]

    fast, model = frames("fast"), frames("robosuite")
    assert all(np.array_equal(a, b) for a, b in zip(fast, frames("fast"), strict=True))
    for a, b in zip(fast, model, strict=True):
        # Measured from robosuite's state: 1.56 (agentview) and 1.04 (eye in hand).
        assert 0.0 < np.abs(a - b).mean() < 2.0
    with pytest.raises(ValueError, match="render_quality"):
        lift(use_camera_obs=True, render_quality="ultra")


def test_fast_depth_is_robosuite_qualitys_and_a_closed_envs_context_draws_the_same() -> None:
    def frames(quality: str, size: int) -> tuple[np.ndarray, np.ndarray]:
        env = lift(
            use_camera_obs=True,
            camera_names="agentview",
            camera_heights=size,
            camera_widths=size,
            camera_depths=True,
            render_quality=quality,
        )
        obs = env.reset(seed=0)
        env.close()
        return obs["agentview_image"], obs["agentview_depth"]

    for size in (48, 128):
        # The second env of a configuration gets the first one's render context back.
        (rgb, depth), again = frames("fast", size), frames("fast", size)
        assert np.array_equal(rgb, again[0]) and np.array_equal(depth, again[1])
        # Depth is read where multisampling reads it (measured: below 1e-9).
        assert np.abs(depth - frames("robosuite", size)[1]).mean() < 1e-6


def test_an_unknown_viewer_is_refused() -> None:
    with pytest.raises(ValueError, match="renderer"):
        lift(has_renderer=True, renderer="pygame")


def _camera_keys() -> list[str]:
    keys = ["cube_pos"]
    for c in FIXTURE["cameras"]:
        keys += [f"{c}_image", f"{c}_depth", f"{c}_segmentation_element"]
    return keys


class _Lone:
    """A single env stepped as a NEXT_STEP vector env steps its sub-env."""

    def __init__(self, seed: int) -> None:
        self.env = GymWrapper(suite.make("Lift", robots="Panda", horizon=3, **CAMERAS), keys=_camera_keys(), flatten_obs=False)
        self.obs, _ = self.env.reset(seed=seed)
        self.ended = False

    def step(self, action: np.ndarray) -> dict[str, np.ndarray]:
        if self.ended:
            self.obs, _ = self.env.reset()
            self.ended = False
        else:
            self.obs, _, terminated, truncated, _ = self.env.step(action)
            self.ended = terminated or truncated
        return self.obs


def _assert_rows(obs: dict[str, np.ndarray], row: int, expected: dict[str, np.ndarray], what: str) -> None:
    assert list(obs) == list(expected)
    for k, v in expected.items():
        assert obs[k].dtype == v.dtype
        np.testing.assert_array_equal(obs[k][row], v, err_msg=f"{what}: {k}")


def test_vector_env_and_pool_views_are_the_batch_and_equal_single_envs() -> None:
    import gc

    keys = _camera_keys()
    vec = suite.make_vec("Lift", 2, flatten_obs=False, keys=keys, horizon=3, copy=False, **CAMERAS)
    copied = suite.make_vec("Lift", 2, flatten_obs=False, keys=keys, horizon=3, **CAMERAS)
    lone = [_Lone(5 + i) for i in range(2)]
    obs, _ = vec.reset(seed=5)
    fresh, _ = copied.reset(seed=5)
    addresses = {k: v.ctypes.data for k, v in obs.items()}
    for i, single in enumerate(lone):
        _assert_rows(obs, i, single.obs, f"reset {i}")
    vec.action_space.seed(1)
    for t in range(7):  # horizon 3: autoresets included
        actions = vec.action_space.sample()
        obs, *_ = vec.step(actions)
        previous = fresh
        fresh, *_ = copied.step(actions)
        for i, single in enumerate(lone):
            _assert_rows(obs, i, single.step(actions[i]), f"step {t}, env {i}")
            _assert_rows(fresh, i, single.obs, f"copied step {t}, env {i}")
        # Views: the same memory every step, read-only; copies: new arrays every step.
        assert {k: v.ctypes.data for k, v in obs.items()} == addresses
        assert not any(v.flags.writeable for v in obs.values())
        assert all(fresh[k].ctypes.data != previous[k].ctypes.data for k in keys)
    # A view keeps the vector env's memory alive after the env is closed and dropped.
    image = obs[keys[1]]
    expected = image.copy()
    vec.close()
    del vec, obs
    gc.collect()
    np.testing.assert_array_equal(image, expected)
    copied.close()

    pool = suite.make_pool("Lift", 3, 2, flatten_obs=False, keys=keys, horizon=3, copy=False, **CAMERAS)
    lone = [_Lone(9 + i) for i in range(3)]
    expected_obs = [single.obs for single in lone]
    obs, info = pool.reset(seed=9)
    pool.action_space.seed(2)
    for t in range(6):
        for k, env_id in enumerate(info["env_id"]):
            _assert_rows(obs, k, expected_obs[env_id], f"pool round {t}, env {env_id}")
        actions = pool.action_space.sample()
        for k, env_id in enumerate(info["env_id"]):
            expected_obs[env_id] = {key: v.copy() for key, v in lone[env_id].step(actions[k]).items()}
        obs, _, _, _, info = pool.step(actions)
        assert not any(v.flags.writeable for v in obs.values())
    pool.close()
