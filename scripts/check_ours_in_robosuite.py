#!/usr/bin/env python3
"""Ours written, robosuite's read: an episode recorded with robosuite_rs's
``DataCollectionWrapper`` and ``gather_demonstrations_as_hdf5``, played back by robosuite
1.5.2 with the logic of its own ``scripts/playback_demonstrations_from_hdf5.py`` (headless:
no viewer), from the states and from the actions.

Run from the repository root with the virtualenv that has robosuite_rs (and h5py); the
playback half runs in a second Python that has robosuite 1.5.2, mujoco 3.3.7 and h5py (the
recording script's scratch virtualenv):

    .venv/bin/python scripts/check_ours_in_robosuite.py \\
        --robosuite-python .bench-venv/robosuite/bin/python

Writes python/tests/fixtures/demonstrations/ours_in_robosuite.json (see the README there):
per demo, robosuite's playback from the states (every state set, the state read back, the
observations robosuite computes compared with ours on the same states) and from the actions
(robosuite's per-step divergence ``‖states[j+1] − state after action j‖``, its largest
component, the largest joint-position difference of the arm, the fingers and the cube, over
the first 10 steps and over the whole demo, and whether robosuite finds the task solved at
the end).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "python", "tests", "fixtures", "demonstrations", "ours_in_robosuite.json")
OBS_KEYS = ("robot0_eef_pos", "robot0_joint_pos", "robot0_gripper_qpos", "cube_pos", "cube_quat")
SEEDS = (11, 12)


def make_kwargs():
    return dict(has_renderer=False, has_offscreen_renderer=False, ignore_done=True, use_camera_obs=False,
                reward_shaping=True, control_freq=20)


def scripted_lift(env, max_steps: int = 60) -> int:
    """The recording script's Lift policy: above the cube, down, close, lift (two steps past
    success)."""
    obs = env.reset()
    start = obs["cube_pos"].copy()
    phase, hold, t, after = 0, 0, 0, None
    while t < max_steps:
        eef, obj = obs["robot0_eef_pos"], obs["cube_pos"]
        g = -1.0
        if phase == 0:
            target = obj + [0, 0, 0.06]
            if np.linalg.norm(target - eef) < 0.015:
                phase = 1
        if phase == 1:
            target = obj + [0, 0, -0.005]
            hold += 1
            if np.linalg.norm(target - eef) < 0.01 or (eef[2] < obj[2] + 0.012 and hold > 8):
                phase, hold = 2, 0
        if phase == 2:
            target, g = obj + [0, 0, -0.005], 1.0
            hold += 1
            if hold >= 5:
                phase = 3
        if phase == 3:
            target, g = start + [0, 0, 0.2], 1.0
        a = np.zeros(7)
        a[:3] = np.clip((target - eef) * 20.0, -1, 1)
        a[6] = g
        obs, _, _, _ = env.step(a)
        t += 1
        if env._check_success():
            after = t if after is None else after
            if t >= after + 2:
                break
    return t


def record(folder: str) -> str:
    """Scripted Lift episodes through our DataCollectionWrapper, gathered by our
    gather_demonstrations_as_hdf5; returns the demo.hdf5 path."""
    import robosuite_rs as suite
    from robosuite_rs import datasets as D
    from robosuite_rs.wrappers import DataCollectionWrapper

    env_info = {"env_name": "Lift", "robots": ["Panda"],
                "controller_configs": suite.load_composite_controller_config(robot="Panda")}
    raw = os.path.join(folder, "raw")
    for seed in SEEDS:
        env = suite.make("Lift", robots=["Panda"], controller_configs=env_info["controller_configs"], seed=seed,
                         **make_kwargs())
        env = DataCollectionWrapper(env, raw)
        steps = scripted_lift(env)
        print(f"ours: Lift seed {seed}: {steps} steps, success {env.env._check_success()}", file=sys.stderr)
        env.close()
    return D.gather_demonstrations_as_hdf5(raw, folder, json.dumps(env_info))


def our_observations(path: str) -> dict[str, dict[str, np.ndarray]]:
    """Our observations on every stored state (robosuite's playback sequence)."""
    from robosuite_rs import datasets as D

    seen: dict[str, dict[str, list]] = {}

    def cb(env, demo, t):
        o = env._get_observations(force_update=True)
        for k in OBS_KEYS:
            seen.setdefault(demo, {}).setdefault(k, []).append(np.array(o[k]))

    D.playback(path, callback=cb)
    return {d: {k: np.array(v) for k, v in kv.items()} for d, kv in seen.items()}


def robosuite_playback(path: str, obs_out: str) -> None:
    """In robosuite 1.5.2: playback_demonstrations_from_hdf5.py's loop without the viewer;
    prints a JSON report, saves robosuite's observations per state to ``obs_out``."""
    import robosuite

    report: dict = {"robosuite": robosuite.__version__, "demos": {}}
    saved = {}
    with h5py.File(path, "r") as f:
        env_info = json.loads(f["data"].attrs["env_info"])
        env = robosuite.make(**env_info, **make_kwargs())
        for ep in f["data"]:
            model_xml = f[f"data/{ep}"].attrs["model_file"]
            states = f[f"data/{ep}/states"][()]
            actions = np.array(f[f"data/{ep}/actions"][()])
            # from the states
            env.reset()
            env.reset_from_xml_string(env.edit_model_xml(model_xml))
            env.sim.reset()
            readback = 0.0
            for t, state in enumerate(states):
                env.sim.set_state_from_flattened(state)
                env.sim.forward()
                readback = max(readback, float(np.abs(env.sim.get_state().flatten() - state).max()))
                o = env._get_observations(force_update=True)
                for k in OBS_KEYS:
                    saved.setdefault(f"{ep}/{k}", []).append(np.array(o[k]))
            # from the actions
            env.reset()
            env.reset_from_xml_string(env.edit_model_xml(model_xml))
            env.sim.reset()
            env.sim.set_state_from_flattened(states[0])
            env.sim.forward()
            m = env.sim.model
            groups = {
                "arm": [f"robot0_joint{i}" for i in range(1, 8)],
                "fingers": ["gripper0_right_finger_joint1", "gripper0_right_finger_joint2"],
                "cube": ["cube_joint0"],
            }
            qpos_idx = {}
            for g, joints in groups.items():
                idx = []
                for jn in joints:
                    jid = m.joint_name2id(jn)
                    adr = m.jnt_qposadr[jid]
                    width = 7 if m.jnt_type[jid] == 0 else 1
                    idx += list(range(1 + adr, 1 + adr + width))
                qpos_idx[g] = idx
            norms, maxabs = [], []
            per_group = {g: [] for g in groups}
            for j, action in enumerate(actions):
                env.step(action)
                if j < len(actions) - 1:
                    d = states[j + 1] - env.sim.get_state().flatten()
                    norms.append(float(np.linalg.norm(d)))
                    maxabs.append(float(np.abs(d).max()))
                    for g, idx in qpos_idx.items():
                        per_group[g].append(float(np.abs(d[idx]).max()))
            report["demos"][ep] = {
                "states": int(len(states)),
                "actions": int(len(actions)),
                "from_states_max_abs_state_readback": readback,
                "from_actions_max_divergence_norm": max(norms),
                "from_actions_max_abs_first_10_steps": max(maxabs[:10]),
                "from_actions_max_abs": max(maxabs),
                "from_actions_max_abs_qpos_first_10_steps": {g: max(v[:10]) for g, v in per_group.items()},
                "from_actions_max_abs_qpos": {g: max(v) for g, v in per_group.items()},
                "from_actions_success_at_end": bool(env._check_success()),
            }
    np.savez(obs_out, **{k: np.array(v) for k, v in saved.items()})
    print(json.dumps(report))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--robosuite-python", default=os.path.join(ROOT, ".bench-venv", "robosuite", "bin", "python"))
    ap.add_argument("--playback", help=argparse.SUPPRESS)  # the robosuite half
    ap.add_argument("--obs-out", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.playback:
        robosuite_playback(args.playback, args.obs_out)
        return
    with tempfile.TemporaryDirectory() as tmp:
        path = record(tmp)
        obs_out = os.path.join(tmp, "robosuite_obs.npz")
        p = subprocess.run([args.robosuite_python, os.path.abspath(__file__), "--playback", path, "--obs-out", obs_out],
                           capture_output=True, text=True, check=False)
        if p.returncode != 0:
            sys.exit(f"robosuite's playback failed:\n{p.stderr}")
        report = json.loads(p.stdout.strip().splitlines()[-1])
        theirs = np.load(obs_out)
        ours = our_observations(path)
        for ep, r in report["demos"].items():
            r["from_states_max_abs_obs_difference"] = {
                k: float(np.abs(theirs[f"{ep}/{k}"] - ours[ep][k]).max()) for k in OBS_KEYS
            }
    report["recorded_by"] = "robosuite_rs DataCollectionWrapper + gather_demonstrations_as_hdf5 (Lift, Panda, seeds 11 and 12)"
    with open(OUT, "w") as f:
        json.dump(report, f, indent=2)
        f.write("\n")
    print(json.dumps(report, indent=2))


if __name__ == "__main__":
    main()
