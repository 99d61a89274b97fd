#!/usr/bin/env python3
"""Record short scripted demonstrations with robosuite 1.5.2's own ``DataCollectionWrapper``
and ``gather_demonstrations_as_hdf5``, plus what robomimic's ``dataset_states_to_obs.py``
gives on them, as test fixtures for ``robosuite_rs.datasets``.

Run it with a Python that has robosuite 1.5.2, mujoco 3.3.7 and h5py (nothing is rendered),
from the repository root:

    python3 -m venv .bench-venv/robosuite            # git-ignored; reuse it if it exists
    .bench-venv/robosuite/bin/pip install robosuite==1.5.2 mujoco==3.3.7 h5py
    .bench-venv/robosuite/bin/python scripts/record_demonstrations.py

It writes into python/tests/fixtures/demonstrations/ (see the README there):

* ``demo.hdf5``: robosuite's ``demo.hdf5`` as ``gather_demonstrations_as_hdf5`` writes it
  (``data`` attrs date, time, repository_version, env, env_info; ``demo_N`` with attr
  ``model_file`` and datasets ``states``, ``actions``) for three scripted, successful
  episodes: two of Lift and one of PickPlaceCan are gathered into one file each
  (``lift.hdf5``, ``can.hdf5``), since a demo.hdf5 holds one env.
* ``lift_low_dim.hdf5``, ``can_low_dim.hdf5``: robomimic's ``dataset_states_to_obs.py``
  output on those files (``--done_mode 2``; rewards sparse, ``--shaped`` rewards stored as
  ``rewards_shaped``), computed by a line-for-line port of robomimic's ``extract_trajectory``
  and ``EnvRobosuite.reset_to`` / ``get_observation`` (robomimic itself is not installed in
  this virtualenv; the port is ``RobomimicEnv`` below).

The episodes are scripted with a proportional controller on the end effector (OSC_POSE,
robosuite's default Panda controller): reach above the object, descend, close, lift (Lift);
then carry over the object's bin, lower, open, rise (PickPlaceCan).
"""

from __future__ import annotations

import json
import os
import shutil
import sys
import tempfile
from copy import deepcopy

import h5py
import numpy as np

import robosuite
from robosuite.controllers import load_composite_controller_config
from robosuite.scripts.collect_human_demonstrations import gather_demonstrations_as_hdf5
from robosuite.wrappers import DataCollectionWrapper

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "python", "tests", "fixtures", "demonstrations")


def make_env(task: str, seed: int):
    config = {
        "env_name": task,
        "robots": ["Panda"],
        "controller_configs": load_composite_controller_config(robot="Panda"),
    }
    # collect_human_demonstrations.py's make call, without the on-screen renderer
    env = robosuite.make(
        **config,
        has_renderer=False,
        has_offscreen_renderer=False,
        ignore_done=True,
        use_camera_obs=False,
        reward_shaping=True,
        control_freq=20,
        seed=seed,
    )
    return env, json.dumps(config)


def move(eef, target, gripper, gain=20.0):
    a = np.zeros(7)
    a[:3] = np.clip((target - eef) * gain, -1, 1)
    a[6] = gripper
    return a


def scripted_episode(env, task: str, max_steps: int) -> int:
    """Runs the scripted policy until success (plus two steps) or max_steps; returns steps."""
    obs = env.reset()
    key = "cube_pos" if task == "Lift" else "Can_pos"
    start = obs[key].copy()
    phase, t, hold, after = 0, 0, 0, None
    if task != "Lift":
        base = env.unwrapped if hasattr(env, "unwrapped") else env
        bin_target = np.array(base.target_bin_placements[base.object_to_id["can"]])
    while t < max_steps:
        eef = obs["robot0_eef_pos"]
        obj = obs[key]
        if phase == 0:  # above the object
            target, g = obj + [0, 0, 0.06], -1
            if np.linalg.norm(target - eef) < 0.015:
                phase, hold = 1, 0
        if phase == 1:  # down to it
            target, g = obj + [0, 0, -0.005], -1
            hold += 1
            if np.linalg.norm(target - eef) < 0.01 or (eef[2] < obj[2] + 0.012 and hold > 8):
                phase, hold = 2, 0
        if phase == 2:  # close
            target, g = obj + [0, 0, -0.005], 1
            hold += 1
            if hold >= 5:
                phase = 3
        if phase == 3:  # lift
            target, g = start + [0, 0, 0.2], 1
            if task != "Lift" and eef[2] > start[2] + 0.12:
                phase = 4
        if phase == 4:  # over the bin
            target, g = np.array([bin_target[0], bin_target[1], start[2] + 0.2]), 1
            if np.linalg.norm(target[:2] - eef[:2]) < 0.02:
                phase = 5
        if phase == 5:  # lower into it
            target, g = np.array([bin_target[0], bin_target[1], bin_target[2] + 0.12]), 1
            if eef[2] < bin_target[2] + 0.14:
                phase, hold = 6, 0
        if phase == 6:  # open, rise
            hold += 1
            target, g = np.array([bin_target[0], bin_target[1], bin_target[2] + (0.12 if hold < 5 else 0.3)]), -1
        obs, _, _, _ = env.step(move(eef, target, g))
        t += 1
        if env._check_success():
            after = t if after is None else after
            if t >= after + 2:
                break
    return t


class RobomimicEnv:
    """robomimic's ``EnvRobosuite`` as far as ``dataset_states_to_obs.py`` uses it (robomimic
    HEAD: ``create_for_data_processing``, ``reset``, ``reset_to``, ``step``,
    ``get_observation``, ``get_reward``, ``is_success``, ``serialize``), for low-dim
    observations."""

    def __init__(self, env_meta: dict, reward_shaping: bool):
        env_kwargs = deepcopy(env_meta["env_kwargs"])
        for k in ("env_name", "camera_names", "camera_height", "camera_width", "reward_shaping",
                  "render", "render_offscreen", "use_image_obs", "use_depth_obs"):
            env_kwargs.pop(k, None)
        env_kwargs.update({"reward_shaping": reward_shaping})
        env_kwargs.update(dict(
            has_renderer=False,
            has_offscreen_renderer=False,
            ignore_done=True,
            use_object_obs=True,
            use_camera_obs=False,
            camera_depths=False,
        ))
        self._env_name = env_meta["env_name"]
        self._init_kwargs = deepcopy(env_kwargs)
        self.env = robosuite.make(self._env_name, **env_kwargs)
        for ob_name in self.env.observation_names:
            if ("joint_pos" in ob_name) or ("eef_vel" in ob_name):
                self.env.modify_observable(observable_name=ob_name, attribute="active", modifier=True)

    def serialize(self):
        return dict(env_name=self._env_name, env_version=robosuite.__version__, type=1,
                    env_kwargs=deepcopy(self._init_kwargs))

    def step(self, action):
        obs, r, done, info = self.env.step(action)
        return self.get_observation(obs), r, False, info

    def reset(self, unset_ep_meta=True):
        if unset_ep_meta:
            self.env.unset_ep_meta()
        return self.get_observation(self.env.reset())

    def reset_to(self, state):
        should_ret = False
        if "model" in state:
            ep_meta = json.loads(state["ep_meta"]) if state.get("ep_meta", None) is not None else {}
            self.env.set_ep_meta(ep_meta)
            self.reset(unset_ep_meta=False)
            xml = self.env.edit_model_xml(state["model"])
            self.env.reset_from_xml_string(xml)
            self.env.sim.reset()
        if "states" in state:
            self.env.sim.set_state_from_flattened(state["states"])
            self.env.sim.forward()
            should_ret = True
        if should_ret:
            return self.get_observation()
        return None

    def get_observation(self, di=None):
        if di is None:
            di = self.env._get_observations(force_update=True)
        ret = {}
        if "object-state" in di:
            ret["object"] = np.array(di["object-state"])
        for robot in self.env.robots:
            pf = robot.robot_model.naming_prefix
            for k in di:
                if k.startswith(pf) and (k not in ret) and (not k.endswith("proprio-state")):
                    ret[k] = np.array(di[k])
        return ret

    def get_reward(self):
        return self.env.reward()

    def is_success(self):
        return {"task": self.env._check_success()}


def extract_trajectory(env, initial_state, states, actions, done_mode):
    """robomimic's ``extract_trajectory`` (low-dim: no camera info)."""
    assert states.shape[0] == actions.shape[0]
    obs = env.reset_to(initial_state)
    traj = dict(obs=[], next_obs=[], rewards=[], dones=[], successes=[],
                actions=np.array(actions), states=np.array(states))
    traj_len = states.shape[0]
    for t in range(1, traj_len + 1):
        if t == traj_len:
            next_obs, _, _, _ = env.step(actions[t - 1])
        else:
            next_obs = env.reset_to({"states": states[t]})
        r = env.get_reward()
        done = False
        if (done_mode == 1) or (done_mode == 2):
            done = done or (t == traj_len)
        success = env.is_success()["task"]
        if (done_mode == 0) or (done_mode == 2):
            done = done or success
        traj["obs"].append(obs)
        traj["next_obs"].append(next_obs)
        traj["rewards"].append(r)
        traj["dones"].append(int(done))
        traj["successes"].append(success)
        obs = deepcopy(next_obs)
    for k in ("obs", "next_obs"):
        traj[k] = {kk: np.array([o[kk] for o in traj[k]]) for kk in traj[k][0]}
    for k in ("rewards", "dones", "successes"):
        traj[k] = np.array(traj[k])
    return traj


def states_to_obs(src: str, dst: str) -> None:
    """robomimic's ``dataset_states_to_obs`` on ``src`` (after robomimic's
    ``convert_robosuite.py``'s env_args), done_mode 2, sparse rewards, plus the shaped ones
    (a second pass with ``--shaped``) as ``rewards_shaped``."""
    with h5py.File(src, "r") as f:
        env_meta = dict(type=1, env_name=f["data"].attrs["env"],
                        env_version=f["data"].attrs["repository_version"],
                        env_kwargs=json.loads(f["data"].attrs["env_info"]))
        envs = {False: RobomimicEnv(env_meta, False), True: RobomimicEnv(env_meta, True)}
        demos = sorted(f["data"].keys(), key=lambda d: int(d[5:]))
        with h5py.File(dst, "w") as out:
            data = out.create_group("data")
            total = 0
            for ep in demos:
                states = f[f"data/{ep}/states"][()]
                actions = f[f"data/{ep}/actions"][()]
                initial = dict(states=states[0], model=f[f"data/{ep}"].attrs["model_file"],
                               ep_meta=f[f"data/{ep}"].attrs.get("ep_meta", None))
                trajs = {s: extract_trajectory(envs[s], initial, states, actions, 2) for s in (False, True)}
                traj = trajs[False]
                g = data.create_group(ep)
                g.create_dataset("actions", data=traj["actions"])
                g.create_dataset("states", data=traj["states"])
                g.create_dataset("rewards", data=traj["rewards"])
                g.create_dataset("dones", data=traj["dones"])
                g.create_dataset("rewards_shaped", data=trajs[True]["rewards"])
                g.create_dataset("successes", data=traj["successes"])
                for k in traj["obs"]:
                    g.create_dataset(f"obs/{k}", data=traj["obs"][k])
                    g.create_dataset(f"next_obs/{k}", data=traj["next_obs"][k])
                g.attrs["model_file"] = initial["model"]
                g.attrs["num_samples"] = traj["actions"].shape[0]
                total += traj["actions"].shape[0]
            data.attrs["total"] = total
            data.attrs["env_args"] = json.dumps(envs[False].serialize(), indent=4)


def action_replay(path: str) -> dict:
    """robosuite's playback_demonstrations_from_hdf5.py --use-actions, without the viewer:
    the largest |state difference| per demo (robosuite against its own recording)."""
    out = {}
    with h5py.File(path, "r") as f:
        env_info = json.loads(f["data"].attrs["env_info"])
        env = robosuite.make(**env_info, has_renderer=False, has_offscreen_renderer=False,
                             ignore_done=True, use_camera_obs=False, reward_shaping=True, control_freq=20)
        for ep in f["data"]:
            env.reset()
            env.reset_from_xml_string(env.edit_model_xml(f[f"data/{ep}"].attrs["model_file"]))
            env.sim.reset()
            states = f[f"data/{ep}/states"][()]
            env.sim.set_state_from_flattened(states[0])
            env.sim.forward()
            worst = 0.0
            for j, action in enumerate(f[f"data/{ep}/actions"][()]):
                env.step(action)
                if j < len(states) - 1:
                    worst = max(worst, float(np.abs(states[j + 1] - env.sim.get_state().flatten()).max()))
            out[ep] = worst
    return out


def record(task: str, seeds: list[int], max_steps: int, name: str) -> None:
    tmp = tempfile.mkdtemp()
    try:
        raw = os.path.join(tmp, "raw")
        for seed in seeds:
            np.random.seed(seed)
            env, env_info = make_env(task, seed)
            env = DataCollectionWrapper(env, raw)
            steps = scripted_episode(env, task, max_steps)
            print(f"{task} seed {seed}: {steps} steps, success {env.env._check_success()}", file=sys.stderr)
            env.close()
        gather_demonstrations_as_hdf5(raw, tmp, env_info)
        shutil.copy(os.path.join(tmp, "demo.hdf5"), os.path.join(OUT, f"{name}.hdf5"))
    finally:
        shutil.rmtree(tmp)
    states_to_obs(os.path.join(OUT, f"{name}.hdf5"), os.path.join(OUT, f"{name}_low_dim.hdf5"))
    print(f"{name}: robosuite's own action replay, max |state diff| per demo: "
          f"{action_replay(os.path.join(OUT, f'{name}.hdf5'))}", file=sys.stderr)


def main() -> None:
    os.makedirs(OUT, exist_ok=True)
    record("Lift", [1, 2], 60, "lift")
    record("PickPlaceCan", [3], 150, "can")


if __name__ == "__main__":
    main()
