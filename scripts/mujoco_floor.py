#!/usr/bin/env python3
"""Measure how far robosuite 1.5.2 itself moves from its own recordings when it runs on
MuJoCo 3.17.0 (robosuite-rs's MuJoCo) instead of 3.3.7 (robosuite's), and write that floor
into each fixture of robosuite-env/tests/fixtures/robosuite/.

Run with a Python that has robosuite 1.5.2 and mujoco 3.17.0 (scripts/record_robosuite.sh
makes one and adapts robosuite's three calls to MuJoCo's changed Python API). Every
recorded rollout is run again from the same seed with the same actions, in closed loop, with
MuJoCo 3.17's multi-point convex collisions turned off as robosuite-rs turns them off, and
compared with the recording as tests/robosuite_replay.rs compares robosuite-rs: the largest
difference of robot joints and grip site before the first touch (`free_arm`), after it
(`contact_arm`), of object positions (`objects`), of rewards, and the success mismatches.
The replay test then allows, on top of its tolerances, what MuJoCo's version alone causes.

Usage: mujoco_floor.py [FIXTURE ...]  (default: every fixture)
"""
import glob
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fixture_json  # noqa: E402  (scripts/fixture_json.py: the fixtures' layout)

os.environ.setdefault("MUJOCO_GL", "disable")
if os.environ.get("PYTHONHASHSEED") != "0":
    # As record_robosuite.py: robosuite's single-object mode 1 draws from a set of names.
    os.environ["PYTHONHASHSEED"] = "0"
    os.execv(sys.executable, [sys.executable] + sys.argv)

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import robosuite as suite  # noqa: E402
from record_robosuite import make_kwargs, our_key  # noqa: E402

FIXTURES = os.path.join(os.path.dirname(__file__), "..", "robosuite-env", "tests", "fixtures", "robosuite")


def is_arm_key(key):
    return key.startswith("robot") and (key.endswith("joint_pos") or key.endswith("eef_pos"))


def is_object_pos_key(key):
    return (not key.startswith("robot") and key.endswith("_pos") and "_to_" not in key
            and not key.startswith("gripper"))


def floor(fixture, index):
    r = fixture["rollouts"][index]
    env = suite.make(
        fixture["task"],
        robots=fixture.get("robots", fixture["robot"]),
        has_renderer=False,
        has_offscreen_renderer=False,
        use_camera_obs=False,
        seed=100 + index,
        **make_kwargs(fixture.get("robots", fixture["robot"]), fixture.get("kwargs", {})),
    )

    def no_multiccd():
        env.sim.model._model.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_MULTICCD

    no_multiccd()
    env.reset()
    no_multiccd()
    start = env.sim.get_state().flatten()
    if np.abs(start - np.array(r["init_state"])).max() != 0.0:
        sys.exit(f"mujoco_floor: {fixture['task']} rollout {index} does not start where it was recorded")
    first = next((i for i, s in enumerate(r["steps"]) if s["robot_contact"]), None)
    out = {"free_arm": 0.0, "contact_arm": 0.0, "objects": 0.0, "reward": 0.0, "success_mismatches": 0}
    for i, (action, rec) in enumerate(zip(r["actions"], r["steps"])):
        obs, reward, done, _ = env.step(np.array(action))
        obs = {our_key(fixture["task"], env, k): v for k, v in obs.items()}
        touched = first is not None and i >= first
        for key, want in rec["obs"].items():
            d = float(np.abs(np.asarray(obs[key], dtype=np.float64).reshape(-1) - np.array(want)).max(initial=0.0))
            if is_arm_key(key):
                k = "contact_arm" if touched else "free_arm"
                out[k] = max(out[k], d)
            elif is_object_pos_key(key):
                out["objects"] = max(out["objects"], d)
        out["reward"] = max(out["reward"], abs(float(reward) - rec["reward"]))
        out["success_mismatches"] += int(bool(env._check_success()) != rec["success"])
        if done:
            break
    env.close()
    return out


def main():
    if mujoco.__version__ != "3.17.0":
        sys.exit(f"mujoco_floor: needs mujoco 3.17.0, found {mujoco.__version__}")
    paths = [os.path.join(FIXTURES, f"{n}.json") for n in sys.argv[1:]] or sorted(glob.glob(os.path.join(FIXTURES, "*.json")))
    for path in paths:
        with open(path) as f:
            fixture = json.load(f)
        for i, r in enumerate(fixture["rollouts"]):
            r["floor"] = floor(fixture, i)
            print(f"{os.path.basename(path)} {r['kind']}: {r['floor']}")
        fixture_json.dump(fixture, path)


if __name__ == "__main__":
    main()
