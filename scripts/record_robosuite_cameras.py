#!/usr/bin/env python3
"""Record robosuite 1.5.2's camera observations on Lift as a test fixture for robosuite-rs.

Run it with a Python that has robosuite 1.5.2 (and mujoco 3.3.7), for example the
virtualenv scripts/record_robosuite.sh makes, with Mesa's EGL installed:

    MUJOCO_GL=egl .bench-venv/robosuite/bin/python scripts/record_robosuite_cameras.py [--size N] [OUT]

It writes robosuite-env/tests/fixtures/robosuite/lift_cameras.json: Lift (Panda, seed 0)
with `agentview` and `robot0_eye_in_hand` at 64x64 (or `--size N`, written to OUT), depth and element segmentation on; the
cube size and the state [time, qpos, qvel] after reset; every observation key with its
shape and dtype; GymWrapper's default keys; and both cameras' RGB frames (hex of the uint8
bytes) and depth frames (hex of the little-endian float32 bytes), as robosuite returns them
(OpenGL row order, raw depth in [0, 1]).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fixture_json  # noqa: E402  (scripts/fixture_json.py: the fixtures' layout)

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np  # noqa: E402
import robosuite as suite  # noqa: E402
from robosuite.wrappers import GymWrapper  # noqa: E402

CAMERAS = ["agentview", "robot0_eye_in_hand"]
SIZE = 64


def main():
    args = sys.argv[1:]
    size = SIZE
    if "--size" in args:
        i = args.index("--size")
        size = int(args[i + 1])
        del args[i : i + 2]
    out = args[0] if args else "robosuite-env/tests/fixtures/robosuite/lift_cameras.json"
    env = suite.make(
        "Lift",
        robots="Panda",
        has_renderer=False,
        has_offscreen_renderer=True,
        use_camera_obs=True,
        camera_names=CAMERAS,
        camera_heights=size,
        camera_widths=size,
        camera_depths=True,
        camera_segmentations="element",
        seed=0,
    )
    obs = env.reset()
    keys = [{"key": k, "shape": list(np.asarray(v).shape), "dtype": str(np.asarray(v).dtype)} for k, v in obs.items()]
    frames = {}
    for cam in CAMERAS:
        frames[cam] = {
            "image": np.ascontiguousarray(obs[f"{cam}_image"], dtype=np.uint8).tobytes().hex(),
            "depth": np.ascontiguousarray(obs[f"{cam}_depth"], dtype="<f4").tobytes().hex(),
        }
    gym = GymWrapper(env)
    record = {
        "robosuite": suite.__version__,
        "task": "Lift",
        "size": size,
        "cameras": CAMERAS,
        "cube_size": [float(x) for x in env.cube.size],
        "state": [float(x) for x in env.sim.get_state().flatten()],
        "keys": keys,
        "gym_default_keys": list(gym.keys),
        "frames": frames,
    }
    fixture_json.dump(record, out)
    print(f"wrote {out} ({os.path.getsize(out) // 1024} KiB)")


if __name__ == "__main__":
    main()
