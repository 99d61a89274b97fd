"""robosuite's two viewers (``robosuite.renderers.viewer``): :class:`MjviewerRenderer` and
:class:`OpenCVViewer`, with robosuite's methods (``set_camera``, ``add_keypress_callback``,
``update``, ``render``, ``reset``, ``close``)."""

from __future__ import annotations

import platform
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["MjviewerRenderer", "OpenCVViewer", "DEFAULT_FREE_CAM"]

#: robosuite's free camera of the mjviewer, used when ``render_camera=None``.
DEFAULT_FREE_CAM: dict[str, Any] = {"lookat": [0, 0, 1], "distance": 2, "azimuth": 180, "elevation": -20}


class MjviewerRenderer:
    """MuJoCo's interactive viewer (``mujoco.viewer.launch_passive``) on the env's own
    ``MjModel`` / ``MjData``: the window opens at the first :meth:`update` (``env.step``
    or ``env.render()``), and each :meth:`update` shows the current state (``sync``).

    ``camera_id``: a fixed camera, ``-1`` / ``None`` MuJoCo's free camera placed by
    ``cam_config`` (robosuite's ``DEFAULT_FREE_CAM`` when ``None``). As in robosuite the
    collision geoms (group 0) are hidden and MuJoCo's side panels are closed.
    """

    def __init__(self, env: Any, camera_id: int | None = None, cam_config: dict[str, Any] | None = None) -> None:
        self.env = env
        self.camera_id = camera_id
        self.camera_config = DEFAULT_FREE_CAM if cam_config is None else cam_config
        self.viewer: Any = None
        self.keypress_callback: Callable[[int], Any] | None = None
        self._sim: Any = None

    def render(self) -> None:
        """Shows the current state (robosuite's mjviewer draws in ``update``; here
        ``env.render()`` syncs too)."""
        self.update()

    def set_camera(self, camera_id: int | None) -> None:
        """Shows fixed camera ``camera_id`` (``-1`` / ``None``: the free camera), now if the
        window is open, else when it opens.

        Raises:
            ValueError: for an id the model does not have.
        """
        if camera_id is not None:
            ncam = self.env.sim.model._model.ncam
            if not isinstance(camera_id, (int, np.integer)) or not -1 <= int(camera_id) < ncam:
                raise ValueError(
                    f"camera_id {camera_id!r} out of range: -1 (free) or a fixed camera 0..{ncam - 1} "
                    f"({list(self.env.sim.model.camera_names)})"
                )
            camera_id = int(camera_id)
        self.camera_id = camera_id
        if self.viewer is not None:
            with self.viewer.lock():
                self._apply_camera()

    def _apply_camera(self) -> None:
        import mujoco

        cam = self.viewer.cam
        if self.camera_id is not None and self.camera_id >= 0:
            cam.type = mujoco.mjtCamera.mjCAMERA_FIXED
            cam.fixedcamid = self.camera_id
        else:
            cam.type = mujoco.mjtCamera.mjCAMERA_FREE
            cfg = self.camera_config
            cam.lookat[:] = cfg["lookat"]
            cam.distance = cfg["distance"]
            cam.azimuth = cfg["azimuth"]
            cam.elevation = cfg["elevation"]

    def update(self) -> None:
        """Opens the window if it is not open (or was closed by the user, or the env's
        simulation was replaced), then shows the current state.

        Raises:
            RuntimeError: when there is no display (see :func:`~robosuite_rs.renderers.check_display`).
        """
        sim = self.env.sim
        if self.viewer is not None and (self._sim is not sim or not self.viewer.is_running()):
            self.close_window()
        if self.viewer is None:
            from mujoco import viewer

            from . import check_display

            check_display()
            self.viewer = viewer.launch_passive(
                sim.model._model,
                sim.data._data,
                key_callback=self._on_key,
                show_left_ui=False,
                show_right_ui=False,
            )
            self._sim = sim
            with self.viewer.lock():
                self.viewer.opt.geomgroup[0] = 0
                self._apply_camera()
        self.viewer.sync()

    def _on_key(self, key: int) -> None:
        if self.keypress_callback is not None:
            self.keypress_callback(key)

    def reset(self) -> None:
        """Nothing to do: the window stays open across resets (the model does not change)."""

    def add_keypress_callback(self, keypress_callback: Callable[[int], Any]) -> None:
        """Calls ``keypress_callback(keycode)`` (GLFW's key code) on each key pressed in the window."""
        self.keypress_callback = keypress_callback

    def close_window(self) -> None:
        """Closes the window (a later :meth:`update` opens a new one)."""
        if self.viewer is not None:
            self.viewer.close()
            self.viewer = None
            self._sim = None

    def close(self) -> None:
        """Closes the window."""
        self.close_window()


def _cv2() -> Any:
    try:
        import cv2
    except ImportError as e:
        raise ImportError(
            "renderer='mujoco' shows frames in an OpenCV window and needs opencv-python "
            "(pip install opencv-python, or robosuite-rs[viewer]); renderer='mjviewer' needs nothing more"
        ) from e
    return cv2


class OpenCVViewer:
    """robosuite's OpenCV window (``renderer="mujoco"``): :meth:`render` draws each camera
    of :meth:`set_camera` offscreen at ``width × height`` (1280 × 800 as robosuite), side by
    side, shows the image in the window ``"offscreen render"`` (top left of the screen)
    and passes the key read by ``cv2.waitKey(1)`` to the keypress callback.

    Raises:
        ImportError: (when made) without opencv-python.
    """

    def __init__(self, sim: Any) -> None:
        self._cv2 = _cv2()
        self.width = 1280
        self.height = 800
        self.sim = sim
        self.camera_names: list[str] = []
        self.set_camera(camera_id=0)
        self._window_name = "offscreen render"
        self._has_window = False
        self.keypress_callback: Callable[[int], Any] | None = None

    def set_camera(
        self,
        camera_id: int | list[int] | None = None,
        camera_name: str | list[str] | None = None,
        width: int | None = None,
        height: int | None = None,
    ) -> None:
        """Shows the camera(s) ``camera_id`` or ``camera_name`` (exactly one of them; a list
        shows them side by side), optionally at a new ``width`` / ``height``.

        Raises:
            ValueError: for none or both of ``camera_id`` / ``camera_name``, an unknown camera
                (listing the model's), or a size that is not a positive int.
        """
        if (camera_id is None) == (camera_name is None):
            raise ValueError("set_camera takes exactly one of camera_id and camera_name")
        for name, value in (("width", width), ("height", height)):
            if value is not None and (not isinstance(value, (int, np.integer)) or value <= 0):
                raise ValueError(f"{name} must be a positive int, got {value!r}")
        model = self.sim.model
        if camera_id is not None:
            ids = [camera_id] if isinstance(camera_id, (int, np.integer)) else list(camera_id)
            ncam = model._model.ncam
            for i in ids:
                if not isinstance(i, (int, np.integer)) or not 0 <= int(i) < ncam:
                    raise ValueError(
                        f"camera_id {i!r} out of range: the model has {ncam} cameras ({list(model.camera_names)})"
                    )
            names = [model.camera_id2name(int(i)) for i in ids]
        else:
            names = [camera_name] if isinstance(camera_name, str) else list(camera_name)  # type: ignore[arg-type]
            for name in names:
                model.camera_name2id(name)  # ValueError listing the cameras
        if not names:
            raise ValueError("set_camera needs at least one camera")
        self.camera_names = names
        if width is not None:
            self.width = int(width)
        if height is not None:
            self.height = int(height)

    def frame(self) -> np.ndarray:
        """The image :meth:`render` shows: the cameras side by side, RGB, top row first."""
        images = [self.sim.render(camera_name=c, height=self.height, width=self.width) for c in self.camera_names]
        return np.flip(np.concatenate(images, axis=1), axis=0)

    def render(self) -> None:
        """Draws the frame and shows it in the window (opened at the first call)."""
        cv2 = self._cv2
        image = np.ascontiguousarray(self.frame()[..., ::-1])  # BGR for OpenCV
        cv2.imshow(self._window_name, image)
        if platform.system() != "Darwin" and not self._has_window:
            cv2.moveWindow(self._window_name, 0, 0)
        key = cv2.waitKey(1)
        self._has_window = True
        if self.keypress_callback is not None:
            self.keypress_callback(key)

    def update(self) -> None:
        """Nothing: robosuite's OpenCV window is drawn by ``env.render()`` only."""

    def reset(self) -> None:
        """Nothing to do on reset."""

    def add_keypress_callback(self, keypress_callback: Callable[[int], Any]) -> None:
        """Calls ``keypress_callback(key)`` after each :meth:`render` with ``cv2.waitKey(1)``'s
        result (-1 when no key was pressed)."""
        self.keypress_callback = keypress_callback

    def close_window(self) -> None:
        """Closes the window."""
        if self._has_window:
            self._cv2.destroyWindow(self._window_name)
            self._cv2.waitKey(1)
        self._has_window = False

    def close(self) -> None:
        """Closes the window and drops the simulation."""
        self.close_window()
        self.sim = None
