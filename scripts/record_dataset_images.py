#!/usr/bin/env python3
"""Records what robomimic's ``dataset_states_to_obs.py --camera_names agentview
robot0_eye_in_hand --camera_height 84 --camera_width 84 --depth`` gives on robosuite 1.5.2
for the first recorded Lift demonstration, at a few of its states, as the fixture
``python/tests/fixtures/demonstrations/lift_images.npz``.

Run in a scratch virtualenv with robosuite 1.5.2 (``mujoco==3.3.7``), h5py and numpy:

    .bench-venv/robosuite/bin/python scripts/record_dataset_images.py

robomimic itself is not installed (not on PyPI at 0.5); its steps are ported line for line
(as in ``scripts/record_demonstrations.py``): ``EnvRobosuite`` made for data processing with
cameras (``has_offscreen_renderer``, ``use_camera_obs``, ``camera_depths``), ``reset_to``
(ep_meta, reset, ``reset_from_xml_string(edit_model_xml(model))``, ``sim.reset()``, then each
state set and forwarded) and ``get_observation`` (images flipped upright, depth flipped,
given a channel axis and turned into metres with ``get_real_depth_map``).
"""
from __future__ import annotations

import json
import os

import h5py
import numpy as np
import robosuite
from robosuite.utils.camera_utils import get_real_depth_map

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIX = os.path.join(ROOT, "python", "tests", "fixtures", "demonstrations")
CAMERAS = ["agentview", "robot0_eye_in_hand"]
SIZE = 84
INDICES = [0, 9, 18, 26]


def main() -> None:
    with h5py.File(os.path.join(FIX, "lift.hdf5")) as f:
        env_info = json.loads(f["data"].attrs["env_info"])
        env_name = f["data"].attrs["env"]
        demo = sorted(f["data"])[0]
        states = f[f"data/{demo}/states"][()]
        xml = str(f[f"data/{demo}"].attrs["model_file"])
        ep_meta = f[f"data/{demo}"].attrs.get("ep_meta")
    env_info.pop("env_name", None)
    env = robosuite.make(
        env_name, **env_info, has_renderer=False, has_offscreen_renderer=True, ignore_done=True,
        use_object_obs=True, use_camera_obs=True, camera_names=CAMERAS, camera_heights=SIZE,
        camera_widths=SIZE, camera_depths=True, reward_shaping=False,
    )
    for name in env.observation_names:
        if "joint_pos" in name or "eef_vel" in name:
            env.modify_observable(observable_name=name, attribute="active", modifier=True)
    env.set_ep_meta(json.loads(ep_meta) if ep_meta is not None else {})
    env.reset()
    env.reset_from_xml_string(env.edit_model_xml(xml))
    env.sim.reset()
    out = {"indices": np.array(INDICES), "demo": np.array(demo)}
    for i in INDICES:
        env.sim.set_state_from_flattened(states[i])
        env.sim.forward()
        di = env._get_observations(force_update=True)
        for cam in CAMERAS:
            out.setdefault(f"{cam}_image", []).append(di[f"{cam}_image"][::-1].copy())
            d = di[f"{cam}_depth"][::-1].copy()
            out.setdefault(f"{cam}_depth", []).append(get_real_depth_map(env.sim, d).astype(np.float32))
    arrays = {k: np.array(v) for k, v in out.items()}
    path = os.path.join(FIX, "lift_images.npz")
    np.savez_compressed(path, **arrays)
    print(f"wrote {path} ({os.path.getsize(path)} bytes), robosuite {robosuite.__version__}")


if __name__ == "__main__":
    main()
