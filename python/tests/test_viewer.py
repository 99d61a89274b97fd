"""robosuite's on-screen viewers (``has_renderer=True``): MuJoCo's viewer and the OpenCV
window on a virtual display (Xvfb), screenshots compared with the offscreen frame of the
same camera and state; Gymnasium's ``render_mode="human"``; and the errors without a
display, with a bad renderer, camera or EGL device."""

from __future__ import annotations

import time

import gymnasium
import numpy as np
import pytest

import robosuite_rs as suite
from robosuite_rs.renderers import MjviewerRenderer, OpenCVViewer

from .xdisplay import screenshot, start_xvfb, wait_for, windows


@pytest.fixture(scope="session")
def display() -> str:
    return start_xvfb()


@pytest.fixture
def on_display(display: str, monkeypatch: pytest.MonkeyPatch) -> str:
    monkeypatch.setenv("DISPLAY", display)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    return display


def _scripted_steps(env: suite.RobosuiteEnv, n: int) -> None:
    """``n`` steps of a fixed action that moves the arm (so the frames are not the reset's)."""
    action = np.zeros(env.action_dim)
    action[:3] = [0.3, -0.2, -0.4]
    for _ in range(n):
        env.step(action)


def _correlation(a: np.ndarray, b: np.ndarray) -> float:
    ga, gb = a.astype(np.float64).mean(axis=2).ravel(), b.astype(np.float64).mean(axis=2).ravel()
    ga, gb = ga - ga.mean(), gb - gb.mean()
    return float(ga @ gb / np.sqrt((ga @ ga) * (gb @ gb) + 1e-12))


def _largest_window(display: str) -> tuple[int, int, int, int] | None:
    found = windows(display)
    return max(found, key=lambda w: w[2] * w[3]) if found else None


def test_mjviewer_window_shows_the_scene(on_display: str) -> None:
    env = suite.make("Lift", robots="Panda", has_renderer=True, renderer="mjviewer",
                     render_camera="frontview", seed=0, horizon=50)
    try:
        assert isinstance(env.viewer, MjviewerRenderer)
        assert env.has_renderer and env.renderer == "mjviewer"
        env.reset()
        _scripted_steps(env, 10)  # robosuite's mjviewer opens and syncs in step
        env.render()
        box = wait_for(lambda: _largest_window(on_display))
        assert box is not None, "no window opened"
        _, _, w, h = box
        expected = np.flip(env.sim.render(camera_name="frontview", width=w, height=h), axis=0)

        def matches() -> float:
            env.render()
            c = _correlation(screenshot(on_display, box), expected)
            return c if c > 0.9 else 0.0

        corr = wait_for(matches)
        assert corr > 0.9, f"the window does not show frontview (correlation {corr:.3f})"
        # another camera: the picture changes to that camera's
        env.viewer.set_camera(env.sim.model.camera_name2id("agentview"))
        agent = np.flip(env.sim.render(camera_name="agentview", width=w, height=h), axis=0)

        def shows_agentview() -> bool:
            env.render()
            shot = screenshot(on_display, box)
            return _correlation(shot, agent) > 0.9 > _correlation(shot, expected)

        assert wait_for(shows_agentview), "set_camera did not change the view"
        with pytest.raises(ValueError, match="out of range"):
            env.viewer.set_camera(99)
    finally:
        env.close()
    assert wait_for(lambda: not windows(on_display)), "env.close() left the window open"
    with pytest.raises(RuntimeError, match="has_renderer=True"):
        env.render()


def test_opencv_window_shows_the_offscreen_frame(on_display: str) -> None:
    pytest.importorskip("cv2", reason="renderer='mujoco' needs opencv-python (test.sh installs it)")
    env = suite.make("Lift", robots="Panda", has_renderer=True, renderer="mujoco",
                     has_offscreen_renderer=False, render_camera=["frontview", "agentview"], seed=0)
    try:
        assert isinstance(env.viewer, OpenCVViewer)
        assert env.has_offscreen_renderer, "robosuite's OpenCV viewer draws offscreen"
        assert env.viewer.camera_names == ["frontview", "agentview"]
        env.viewer.set_camera(camera_name=["frontview", "agentview"], width=200, height=150)
        keys: list[int] = []
        env.viewer.add_keypress_callback(keys.append)
        env.reset()
        _scripted_steps(env, 5)
        frame = env.viewer.frame()
        assert frame.shape == (150, 400, 3)
        # the frame is the two cameras side by side, top row first
        front = np.flip(env.sim.render(camera_name="frontview", width=200, height=150), axis=0)
        np.testing.assert_array_equal(frame[:, :200], front)

        import cv2

        env.render()

        def found() -> bool:
            cv2.waitKey(1)  # Qt paints the window while it handles its events
            box = _largest_window(on_display)
            if box is None:
                return False
            shot = screenshot(on_display, box).astype(np.int16)
            # the image lies inside the window (below any toolbar): the best offset
            h, w = frame.shape[:2]
            if shot.shape[0] < h or shot.shape[1] < w:
                return False
            best = min(
                np.abs(shot[dy:dy + h, dx:dx + w] - frame).mean()
                for dy in range(shot.shape[0] - h + 1)
                for dx in range(shot.shape[1] - w + 1)
            )
            return bool(best < 2.0)  # (an exact match is 0.0: falsy, so not returned as is)

        assert wait_for(found), "the OpenCV window does not show the frame"
        assert keys and all(k == -1 for k in keys), keys  # waitKey(1) with no key pressed
    finally:
        env.close()
    assert wait_for(lambda: not windows(on_display)), "env.close() left the window open"


def test_gymnasium_human_mode_paces_at_render_fps(on_display: str) -> None:
    env = gymnasium.make("robosuite_rs/Lift-v0", render_mode="human", horizon=20)
    try:
        assert env.render_mode == "human"
        assert "human" in env.metadata["render_modes"]
        fps = env.metadata["render_fps"]
        start = time.perf_counter()
        env.reset(seed=0)  # a frame, then one per step, at most render_fps a second
        for _ in range(4):
            env.step(env.action_space.sample())
        elapsed = time.perf_counter() - start
        assert elapsed >= 4 / fps, f"5 frames at {fps} fps took {elapsed:.3f} s"
        assert env.render() is None
        assert wait_for(lambda: _largest_window(on_display)) is not None
    finally:
        env.close()
    assert wait_for(lambda: not windows(on_display))


def test_no_display_is_one_clear_error(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    monkeypatch.setenv("MUJOCO_GL", "egl")
    for kwargs in ({"has_renderer": True}, {"render_mode": "human"}):
        with pytest.raises(RuntimeError, match=r"DISPLAY.*MUJOCO_GL=egl"):
            suite.make("Lift", robots="Panda", **kwargs)
    with pytest.raises(RuntimeError, match="DISPLAY"):
        gymnasium.make("robosuite_rs/Lift-v0", render_mode="human")


def test_a_display_that_is_not_there_is_a_clear_error(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("DISPLAY", ":987")
    with pytest.raises(RuntimeError, match=r"no window opens on DISPLAY=':987'"):
        suite.make("Lift", robots="Panda", has_renderer=True)


def test_bad_viewer_arguments(monkeypatch: pytest.MonkeyPatch) -> None:
    # checked before the display: these need none
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    with pytest.raises(ValueError, match="renderer.*pygame.*mjviewer.*mujoco"):
        suite.make("Lift", has_renderer=True, renderer="pygame")
    with pytest.raises(ValueError, match="nope.*frontview"):
        suite.make("Lift", has_renderer=True, render_camera="nope")
    with pytest.raises(ValueError, match="render_camera"):
        suite.make("Lift", has_renderer=True, render_camera=["frontview", "agentview"])  # mjviewer: one
    with pytest.raises(ValueError, match="renderer_config.*cam_id"):
        suite.make("Lift", has_renderer=True, renderer_config={"cam_id": 0})
    with pytest.raises(suite.VectorizeError, match="has_renderer"):
        suite.make_vec("Lift", num_envs=2, has_renderer=True)
    env = suite.make("Lift", has_renderer=False, has_offscreen_renderer=False)
    try:
        assert env.viewer is None
        with pytest.raises(RuntimeError, match="has_renderer=True"):
            env.render()
    finally:
        env.close()


def test_an_egl_device_that_does_not_exist_lists_the_devices(monkeypatch: pytest.MonkeyPatch) -> None:
    missing = r"render_gpu_device_id.*EGL device 99 does not exist; EGL lists \d+ device\(s\): \[0: "
    with pytest.raises(ValueError, match=missing):  # camera observations open the renderer at make
        suite.make("Lift", use_camera_obs=True, camera_heights=32, camera_widths=32, render_gpu_device_id=99)
    env = suite.make("Lift", render_gpu_device_id=99)  # sim.render opens it at the first frame
    try:
        with pytest.raises(ValueError, match=missing):
            env.sim.render(camera_name="frontview", width=32, height=32)
    finally:
        env.close()
    monkeypatch.setenv("MUJOCO_EGL_DEVICE_ID", "99")
    with pytest.raises(ValueError, match=r"MUJOCO_EGL_DEVICE_ID.*EGL device 99 does not exist"):
        suite.make("Lift", use_camera_obs=True, camera_heights=32, camera_widths=32)
    # device 0 exists wherever rendering works: the same frames as the default choice
    monkeypatch.delenv("MUJOCO_EGL_DEVICE_ID")
    frames = []
    for device in (-1, 0):
        env = suite.make("Lift", use_camera_obs=True, camera_heights=32, camera_widths=32,
                         render_gpu_device_id=device, seed=0)
        frames.append(env.reset()["agentview_image"])
        env.close()
    np.testing.assert_array_equal(frames[0], frames[1])
