#!/usr/bin/env python3
"""Record robosuite 1.5.2's segmentation observations on Lift as a test fixture for
robosuite-rs (run as scripts/record_robosuite_cameras.py, with MUJOCO_GL=egl):

    MUJOCO_GL=egl .bench-venv/robosuite/bin/python scripts/record_robosuite_segmentation.py

It writes robosuite-env/tests/fixtures/robosuite/lift_segmentation.json: Lift (Panda,
seed 0) with `agentview` and `robot0_eye_in_hand` at 64x64 and the `element`, `instance`
and `class` segmentations of each; the cube size and the state [time, qpos, qvel] after
reset; robosuite's instance and class names in id order; and each segmentation frame as
the hex of its little-endian int16 values (OpenGL row order, as robosuite returns them).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fixture_json  # noqa: E402  (scripts/fixture_json.py: the fixtures' layout)

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np  # noqa: E402
import robosuite as suite  # noqa: E402

CAMERAS = ["agentview", "robot0_eye_in_hand"]
LEVELS = ["element", "instance", "class"]
SIZE = 64


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "robosuite-env/tests/fixtures/robosuite/lift_segmentation.json"
    env = suite.make(
        "Lift",
        robots="Panda",
        has_renderer=False,
        has_offscreen_renderer=True,
        use_camera_obs=True,
        camera_names=CAMERAS,
        camera_heights=SIZE,
        camera_widths=SIZE,
        camera_segmentations=[LEVELS, LEVELS],
        seed=0,
    )
    obs = env.reset()
    frames = {
        cam: {
            level: np.ascontiguousarray(obs[f"{cam}_segmentation_{level}"], dtype="<i2").tobytes().hex()
            for level in LEVELS
        }
        for cam in CAMERAS
    }
    record = {
        "robosuite": suite.__version__,
        "task": "Lift",
        "size": SIZE,
        "cameras": CAMERAS,
        "levels": LEVELS,
        "cube_size": [float(x) for x in env.cube.size],
        "state": [float(x) for x in env.sim.get_state().flatten()],
        "instances": list(env.model.instances_to_ids),
        "classes": list(env.model.classes_to_ids),
        "frames": frames,
    }
    fixture_json.dump(record, out)
    print(f"wrote {out} ({os.path.getsize(out) // 1024} KiB)")


if __name__ == "__main__":
    main()
