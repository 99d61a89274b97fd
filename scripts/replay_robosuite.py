#!/usr/bin/env python3
"""Replay a recorded rollout in robosuite 1.5.2 itself, on whichever MuJoCo is importable.

Separates MuJoCo-version effects from porting errors: the fixtures of
robosuite-env/tests/fixtures/robosuite were recorded with robosuite 1.5.2 on MuJoCo 3.3.7,
robosuite-rs runs MuJoCo 3.17.0. Replaying a rollout's actions in robosuite on MuJoCo
3.17.0 shows how far robosuite itself moves from its recording; with --compare, how far
robosuite-rs (`cargo run -p robosuite-env --example replay_fixture -- TASK INDEX`) is from
that run.

robosuite 1.5.2 predates two MuJoCo API changes; this script patches them in robosuite's
binding helpers (joint types compare as integers; `mj_fullM(m, d, dst)` without `qM`), so
that it runs with any robosuite 1.5.2 (scripts/record_robosuite.sh's MuJoCo-3.17.0 one has
them patched already). Where MuJoCo has multi-point convex collisions, they are turned off,
as robosuite-rs turns them off.

Usage (a Python with robosuite 1.5.2; MuJoCo 3.17.0 can come from another environment):
  PYTHONPATH=DIR_WITH_MUJOCO_3_17 python scripts/replay_robosuite.py Door 0 [--compare ours.json]
"""
import argparse
import json
import os
import sys

os.environ.setdefault("MUJOCO_GL", "disable")
if os.environ.get("PYTHONHASHSEED") != "0":
    # As record_robosuite.py: robosuite's single-object mode 1 draws from a set of names.
    os.environ["PYTHONHASHSEED"] = "0"
    os.execv(sys.executable, [sys.executable] + sys.argv)

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import robosuite as suite  # noqa: E402
import robosuite.utils.binding_utils as binding  # noqa: E402
from record_robosuite import our_key  # noqa: E402
from robosuite.controllers.parts import controller as controller_module  # noqa: E402


def _joint_addr(model, name, field, nfree, nball):
    j = model.joint_name2id(name)
    kind = int(model.jnt_type[j])
    adr = getattr(model, field)[j]
    n = nfree if kind == int(mujoco.mjtJoint.mjJNT_FREE) else nball if kind == int(mujoco.mjtJoint.mjJNT_BALL) else 1
    return adr if n == 1 else (adr, adr + n)


def _controller_update(self, force=False):
    """robosuite's Controller.update with either mj_fullM signature."""
    if self.new_update or force:
        if not (self.lite_physics and not force):
            self.sim.forward()
        if self.ref_name is not None:
            self.update_reference_data()
        self.joint_pos = np.array(self.sim.data.qpos[self.qpos_index])
        self.joint_vel = np.array(self.sim.data.qvel[self.qvel_index])
        nv = self.sim.model.nv
        mass_matrix = np.ndarray(shape=(nv, nv), dtype=np.float64, order="C")
        if hasattr(self.sim.data._data, "qM"):
            mujoco.mj_fullM(self.sim.model._model, mass_matrix, self.sim.data.qM)
        else:
            mujoco.mj_fullM(self.sim.model._model, self.sim.data._data, mass_matrix)
        self.mass_matrix = mass_matrix[self.qvel_index, :][:, self.qvel_index]
        self.new_update = False


binding.MjModel.get_joint_qpos_addr = lambda self, name: _joint_addr(self, name, "jnt_qposadr", 7, 4)
binding.MjModel.get_joint_qvel_addr = lambda self, name: _joint_addr(self, name, "jnt_dofadr", 6, 3)
controller_module.Controller.update = _controller_update


def no_multiccd(env):
    """MuJoCo 3.17's multi-point convex collisions off, as in robosuite's MuJoCo and in
    robosuite-rs (scripts/mujoco_floor.py does the same)."""
    if hasattr(mujoco.mjtDisableBit, "mjDSBL_MULTICCD"):
        env.sim.model._model.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_MULTICCD


def largest(steps_a, steps_b, first_contact):
    """Largest differences: arm (joints, grip site) before / after the first touch, reward."""
    free = contact = reward = 0.0
    for i, (a, b) in enumerate(zip(steps_a, steps_b)):
        for key in ("robot0_joint_pos", "robot0_eef_pos"):
            d = float(np.max(np.abs(np.array(a["obs"][key]) - np.array(b["obs"][key]))))
            if first_contact is not None and i >= first_contact:
                contact = max(contact, d)
            else:
                free = max(free, d)
        reward = max(reward, abs(a["reward"] - b["reward"]))
    return free, contact, reward


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("task")
    parser.add_argument("rollout", type=int, help="index of the rollout in the fixture (0: scripted)")
    default_dir = os.path.join(os.path.dirname(__file__), "..", "robosuite-env", "tests", "fixtures", "robosuite")
    parser.add_argument("--fixtures", default=default_dir)
    parser.add_argument("--compare", help="robosuite-rs's steps of the same rollout (JSON from the replay_fixture example)")
    args = parser.parse_args()
    with open(os.path.join(args.fixtures, f"{args.task}.json")) as f:
        fixture = json.load(f)
    rollout = fixture["rollouts"][args.rollout]
    # record_robosuite.py seeds rollout i with 100 + i; the reset then repeats the recorded one.
    env = suite.make(
        args.task,
        robots=fixture["robot"],
        has_renderer=False,
        has_offscreen_renderer=False,
        use_camera_obs=False,
        seed=100 + args.rollout,
    )
    no_multiccd(env)
    env.reset()
    no_multiccd(env)
    start = np.max(np.abs(env.sim.get_state().flatten() - np.array(rollout["init_state"])))
    keys = list(rollout["steps"][0]["obs"])
    ours = []
    for action in rollout["actions"]:
        obs, reward, done, _ = env.step(np.array(action))
        obs = {our_key(args.task, env, k): v for k, v in obs.items()}
        ours.append(
            {
                "obs": {k: np.asarray(obs[k], dtype=np.float64).reshape(-1).tolist() for k in keys},
                "reward": float(reward),
                "success": bool(env._check_success()),
            }
        )
        if done:
            break
    first = next((i for i, s in enumerate(rollout["steps"]) if s["robot_contact"]), None)
    print(f"robosuite {suite.__version__} on MuJoCo {mujoco.__version__}: {args.task} rollout {args.rollout}")
    print(f"  reset state vs recording: {start:.2e}; steps {len(ours)} (recorded {len(rollout['steps'])})")
    free, contact, reward = largest(ours, rollout["steps"], first)
    print(f"  vs its recording (MuJoCo {fixture['mujoco']}): arm free {free:.2e}, after touch {contact:.2e}, reward {reward:.3e}")
    if args.compare:
        with open(args.compare) as f:
            rs = json.load(f)
        free, contact, reward = largest(rs, ours, first)
        mismatches = sum(a["success"] != b["success"] for a, b in zip(rs, ours))
        print(f"  robosuite-rs vs this run: arm free {free:.2e}, after touch {contact:.2e}, reward {reward:.3e}, success mismatches {mismatches}")
        for key in keys:
            d = max(
                (float(np.max(np.abs(np.array(a["obs"][key]) - np.array(b["obs"][key])))) for a, b in zip(rs, ours) if b["obs"][key]),
                default=0.0,
            )
            print(f"    {key:28s} {d:.2e}")


if __name__ == "__main__":
    main()
