"""robosuite's on-screen viewers (``robosuite.renderers``), opened by
``make(..., has_renderer=True)`` and shown by ``env.render()``:

* ``renderer="mjviewer"`` (the default): MuJoCo's interactive viewer
  (``mujoco.viewer.launch_passive`` on ``env.sim.model._model`` / ``env.sim.data._data``),
  synced after every ``env.step`` and by ``env.render()``;
* ``renderer="mujoco"``: an OpenCV window showing the offscreen frame of ``render_camera``
  (several cameras side by side), drawn by ``env.render()``; needs ``opencv-python``
  (``pip install robosuite-rs[viewer]``).

Both need a display (``DISPLAY`` or ``WAYLAND_DISPLAY``, e.g. a desktop session or
``xvfb-run``); :func:`check_display` says so with one clear error before anything tries to
open a window.
"""

from __future__ import annotations

import os

from .viewer import MjviewerRenderer, OpenCVViewer

__all__ = ["MjviewerRenderer", "OpenCVViewer", "check_display", "load_renderer_config", "RENDERERS"]

#: robosuite's renderer names (``make``'s ``renderer``).
RENDERERS: tuple[str, ...] = ("mjviewer", "mujoco")

_NO_DISPLAY = (
    "has_renderer=True / render_mode='human' opens a window and needs a display: {why}. Run it in a "
    "desktop session, over `ssh -X`, or under a virtual display (`xvfb-run -a python ...`); on a "
    "headless machine use offscreen frames instead (has_renderer=False with render_mode='rgb_array' "
    "or camera observations, MUJOCO_GL=egl)"
)


# A window of 16 × 16 pixels, hidden, in a child process: GLFW (MuJoCo's window library)
# connects to the display and makes an OpenGL context there; nothing in this process
# changes, and a display that never answers cannot hang it (the probe has a timeout).
_PROBE = """
import sys, glfw
glfw.ERROR_REPORTING = False
if not glfw.init():
    sys.exit("GLFW cannot connect to the display")
glfw.window_hint(glfw.VISIBLE, glfw.FALSE)
window = glfw.create_window(16, 16, "probe", None, None)
if not window:
    sys.exit("GLFW connects but cannot open an OpenGL window (no GLX/EGL on this display)")
glfw.destroy_window(window)
glfw.terminate()
"""

_PROBE_TIMEOUT_S = 30.0
_probed: set[tuple[str, str]] = set()


def check_display() -> None:
    """Checks that a window can open: ``DISPLAY`` or ``WAYLAND_DISPLAY`` is set and GLFW
    (the window library MuJoCo's viewer uses) opens an OpenGL window there (tried once per
    display in a child process, at most 30 s).

    Raises:
        RuntimeError: naming ``DISPLAY`` / ``MUJOCO_GL`` and the way out, when there is no
            display or no window opens on it.
    """
    display = os.environ.get("DISPLAY", "")
    wayland = os.environ.get("WAYLAND_DISPLAY", "")
    if not display and not wayland:
        why = "neither DISPLAY nor WAYLAND_DISPLAY is set"
        if os.environ.get("MUJOCO_GL", "").lower() in ("egl", "osmesa"):
            why += f" (MUJOCO_GL={os.environ['MUJOCO_GL']} selects headless rendering)"
        raise RuntimeError(_NO_DISPLAY.format(why=why))
    key = (display, wayland)
    if key in _probed:
        return
    import subprocess
    import sys

    shown = f"DISPLAY={display!r}" if display else f"WAYLAND_DISPLAY={wayland!r}"
    try:
        run = subprocess.run(
            [sys.executable, "-c", _PROBE], capture_output=True, text=True, timeout=_PROBE_TIMEOUT_S
        )
    except subprocess.TimeoutExpired:
        raise RuntimeError(
            _NO_DISPLAY.format(why=f"the display {shown} did not answer within {_PROBE_TIMEOUT_S:.0f} s")
        ) from None
    if run.returncode != 0:
        detail = (run.stderr.strip().splitlines() or ["the window probe failed"])[-1]
        raise RuntimeError(_NO_DISPLAY.format(why=f"no window opens on {shown}: {detail}"))
    _probed.add(key)


def load_renderer_config(renderer: str) -> dict:
    """robosuite's ``load_renderer_config``: the default settings of ``renderer`` (none:
    an empty dict, so the mjviewer's free camera is robosuite's ``DEFAULT_FREE_CAM``)."""
    return {}
