#!/usr/bin/env python3
"""Record robosuite 1.5.2's WHOLE_BODY_IK composite controller (its `WholeBodyIK` class and
the `IKSolver` it builds) on a synthetic model, as a test fixture for robosuite-rs.

Run it with a Python that has robosuite 1.5.2 (and mujoco 3.3.7), for example

    .bench-venv/robosuite/bin/python scripts/record_whole_body_ik.py

It writes robosuite-env/tests/fixtures/whole_body_ik/whole_body_ik.json, figures only.

Env rollouts (`env_cases`): robosuite's WHOLE_BODY_IK configs on Lift (`whole_body_ik.json`
driving a Panda, in its world frame and in the base frame; `default_tiago_whole_body_ik.json`
on Tiago, on TwoArmLift; `default_pandaomron_whole_body_ik.json` on PandaOmron, whose frame is its mobile
base), 60 steps of absolute grip-site targets in free motion (the recorder checks that the robot touches nothing), with the
state after reset, the actions and after each step the joints, grip sites and fingers (the
observation keys named by `eef_keys` and `gripper_keys`, in that order), as
scripts/record_controllers.py records the arm controllers.

The model is robosuite-rs's own (robosuite-env/tests/fixtures/whole_body_ik/torso_two_arms.xml:
a torso, a head and two 7-joint arms with grip sites named as robosuite names them), so the
fixture pins the IK's math without robosuite's robots. robosuite's own `WholeBodyIK` runs on
it: its constructor, config validation, action layout, `action_limits` and `set_goal`, with
the body-part controllers replaced by stubs that record the action each receives (the
grippers' `format_action` is the identity here), and `controller_factory` returning those
stubs. Each case is a `composite_controller_specific_configs` dict as robosuite's JSON files
write it, the body parts (joints, action size, limits), and a sequence of states and actions:
the robot's joints are set, `mj_forward` runs, then `set_goal(action)`. Each step records the
joint positions, the action, the IK's joint targets (`q_des`) and every part's action. The
next state follows the targets (a kinematic robot), with a jump to a random posture every few
steps.

Cases that set `input_action_repr` set that IKSolver attribute after construction:
robosuite's WholeBodyIK always leaves it `"absolute"` (it passes `ik_input_type` to the
solver's teleoperation `input_type`), so the relative modes are the solver's own.

Infinite action limits are written as null.
"""
import copy
import json
import os
import sys
from collections import OrderedDict

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fixture_json  # noqa: E402

os.environ.setdefault("MUJOCO_GL", "disable")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import robosuite  # noqa: E402
from robosuite.controllers.composite import composite_controller as cc_module  # noqa: E402
from scipy.spatial.transform import Rotation  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DIR = os.path.join(ROOT, "robosuite-env", "tests", "fixtures", "whole_body_ik")
MODEL = os.path.join(DIR, "torso_two_arms.xml")
OUT = os.path.join(DIR, "whole_body_ik.json")

ARM_JOINTS = ["shoulder_pitch", "shoulder_roll", "shoulder_yaw", "elbow_pitch", "wrist_yaw", "wrist_roll", "wrist_pitch"]
PARTS = OrderedDict(
    [
        ("right", {"joints": [f"robot0_r_{j}" for j in ARM_JOINTS], "arm": True}),
        ("left", {"joints": [f"robot0_l_{j}" for j in ARM_JOINTS], "arm": True}),
        ("torso", {"joints": ["robot0_torso_waist_yaw", "robot0_torso_waist_pitch", "robot0_torso_waist_roll"]}),
        ("head", {"joints": ["robot0_head_yaw", "robot0_head_pitch"]}),
        ("right_gripper", {"gripper_dof": 6}),
        ("left_gripper", {"gripper_dof": 1}),
    ]
)

# robosuite's default_gr1.json settings.
GR1_WEIGHTS = {
    "robot0_torso_waist_yaw": 100.0,
    "robot0_torso_waist_pitch": 100.0,
    "robot0_torso_waist_roll": 500.0,
    "robot0_l_shoulder_pitch": 4.0,
    "robot0_r_shoulder_pitch": 4.0,
    "robot0_l_shoulder_roll": 3.0,
    "robot0_r_shoulder_roll": 3.0,
    "robot0_l_shoulder_yaw": 2.0,
    "robot0_r_shoulder_yaw": 2.0,
}
GR1 = {
    "ref_name": ["gripper0_right_grip_site", "gripper0_left_grip_site"],
    "interpolation": None,
    "actuation_part_names": ["torso", "head", "right", "left", "base", "legs"],
    "max_dq": 4,
    "nullspace_joint_weights": GR1_WEIGHTS,
    "ik_pseudo_inverse_damping": 5e-2,
    "ik_integration_dt": 1e-1,
    "ik_max_dq": 4.0,
    "ik_max_dq_torso": 0.2,
    "ik_input_type": "absolute",
    "ik_input_ref_frame": "base",
    "ik_input_rotation_repr": "axis_angle",
    "ik_verbose": True,
}


def case(name, steps, parts=None, repr_=None, seed=0, far=(), **overrides):
    config = copy.deepcopy(GR1)
    for k, v in overrides.items():
        if v is None:
            config.pop(k, None)
        else:
            config[k] = v
    return {
        "name": name,
        "config": config,
        "parts": list(parts or PARTS.keys()),
        "input_action_repr": repr_,
        "steps": steps,
        "seed": seed,
        "far": list(far),
    }


CASES = [
    # GR1's default settings, in the world frame and in robosuite's default base frame.
    case("gr1_world", 14, ik_input_ref_frame="world", far=(9, 10)),
    case("gr1_base", 14, seed=1, far=(11,)),
    # robosuite's default when ik_input_ref_frame is left out: world; quaternion inputs; only
    # the arms through IK, the torso and head as parts of their own.
    case(
        "arms_quat",
        10,
        seed=2,
        actuation_part_names=["right", "left"],
        ik_input_ref_frame=None,
        ik_input_rotation_repr="quat_wxyz",
    ),
    # The torso after the arms (robosuite limits the entries of its IK step at the torso
    # joints' model ids), tight step limits, a frame that is a body other than the base.
    case(
        "torso_last",
        10,
        seed=3,
        actuation_part_names=["right", "left", "torso"],
        ik_max_dq=0.5,
        ik_max_dq_torso=0.05,
        ik_input_ref_frame="robot0_torso_link0",
        far=(4,),
    ),
    # A ref site and a part the model lacks (robosuite drops both), defaults for the rest.
    case(
        "one_site",
        8,
        seed=4,
        ref_name=["gripper0_right_grip_site", "gripper0_missing_grip_site"],
        actuation_part_names=["right", "torso", "base"],
        ik_pseudo_inverse_damping=None,
        ik_integration_dt=None,
        ik_max_dq=None,
        ik_max_dq_torso=None,
        ik_input_ref_frame=None,
        ik_input_rotation_repr=None,
        nullspace_joint_weights={"robot0_r_elbow_pitch": 7.5, "robot0_not_a_joint": 3.0},
        parts=["right", "torso", "right_gripper"],
    ),
    # IKSolver's relative modes.
    case("relative", 10, seed=5, repr_="relative", ik_input_ref_frame="world"),
    case("relative_pose", 10, seed=6, repr_="relative_pose"),
    # skip_wbc_action: the parts' own actions, IK unused.
    case("skip_wbc_action", 4, seed=7, skip_wbc_action=True),
]


class StubController:
    def __init__(self, part_name, params):
        self.part_name = part_name
        self.joint_names = list(params.get("joints", []))
        self.control_dim = params.get("control_dim", len(self.joint_names))
        self.control_limits = (np.array(params["low"], dtype=float), np.array(params["high"], dtype=float))
        self.goals = []

    def set_goal(self, action):
        self.goals.append(np.array(action, dtype=float).copy())

    def reset_goal(self):
        pass


class StubGripper:
    def __init__(self, dof):
        self.dof = dof

    def format_action(self, action):
        return action


class StubRobotModel:
    def __init__(self, arms):
        self.arms = arms


class StubSim:
    def __init__(self, model, data):
        class M:
            pass

        class D:
            pass

        self.model = M()
        self.model._model = model
        self.model.site_names = [model.site(i).name for i in range(model.nsite)]
        self.data = D()
        self.data._data = data


def part_params(name):
    spec = PARTS[name]
    if "gripper_dof" in spec:
        dof = spec["gripper_dof"]
        return {"type": "GRIP", "control_dim": dof, "low": [-1.0] * dof, "high": [1.0] * dof}
    n = len(spec["joints"])
    # JOINT_POSITION's control_limits are its input_min / input_max (GR1's: -1, 1); the
    # arms get distinct bounds here so the fixture tells them from the default [-1, 1].
    lo, hi = (-0.5, 0.75) if spec.get("arm") else (-1.0, 1.0)
    return {"type": "JOINT_POSITION", "joints": spec["joints"], "low": [lo] * n, "high": [hi] * n}


def limits_json(v):
    return [None if not np.isfinite(x) else float(x) for x in v]


def record_case(c, model):
    data = mujoco.MjData(model)
    rng = np.random.default_rng(1000 + c["seed"])
    parts = c["parts"]
    part_config = OrderedDict((p, part_params(p)) for p in parts)
    grippers = {p: StubGripper(PARTS[p]["gripper_dof"]) for p in parts if "gripper_dof" in PARTS[p]}
    arms = [p for p in parts if PARTS[p].get("arm")]
    stubs = {}

    def factory(part_name, controller_type, controller_params):
        stubs[part_name] = StubController(part_name, controller_params)
        return stubs[part_name]

    original = cc_module.controller_factory
    cc_module.controller_factory = factory
    sim = StubSim(model, data)
    cc = cc_module.WholeBodyIK(sim, StubRobotModel(arms), grippers)
    specific = copy.deepcopy(c["config"])
    cc.load_controller_config(part_config, specific)
    cc_module.controller_factory = original
    ik = cc.joint_action_policy
    if c["input_action_repr"]:
        ik.input_action_repr = c["input_action_repr"]

    robot_joints = [model.joint(i).name for i in range(model.njnt) if model.joint(i).name.startswith("robot0_")]
    jid = [model.joint(n).id for n in robot_joints]
    lo = model.jnt_range[jid, 0]
    hi = model.jnt_range[jid, 1]
    limited = model.jnt_limited[jid].astype(bool)

    def random_posture():
        q = np.zeros(len(jid))
        q[limited] = rng.uniform(0.8 * lo[limited] + 0.2 * hi[limited], 0.2 * lo[limited] + 0.8 * hi[limited])
        q[~limited] = rng.uniform(-1.0, 1.0, size=(~limited).sum())
        return q

    qpos = model.qpos0.copy()
    qpos[[model.jnt_qposadr[j] for j in jid]] = random_posture()
    ref = ik.input_ref_frame
    frame = None
    if ref != "world":
        body = "robot0_base" if ref == "base" else ref
        frame = (model.body(body).pos.copy(), model.body(body).quat.copy())

    steps = []
    for t in range(c["steps"]):
        if t > 0 and t % 5 == 0:
            qpos[[model.jnt_qposadr[j] for j in jid]] = random_posture()
        data.qpos[:] = qpos
        data.qvel[:] = 0
        mujoco.mj_forward(model, data)
        action = []
        for i, site in enumerate(ik.site_names):
            sid = model.site(site).id
            p = data.site_xpos[sid].copy()
            r = data.site_xmat[sid].reshape(3, 3).copy()
            far = t in c["far"]
            dp = rng.normal(0.0, 0.04, 3) if not far else np.array([3.0, -2.0, 1.5])
            dr = Rotation.from_rotvec(rng.normal(0.0, 0.15, 3))
            zero_rot = t == 2 and i == 0
            if ik.input_action_repr == "absolute":
                pt, rt = p + dp, (dr * Rotation.from_matrix(r)).as_matrix()
                if frame is not None:
                    fr = Rotation.from_quat(np.roll(frame[1], -1)).as_matrix()
                    pt, rt = fr.T @ (pt - frame[0]), fr.T @ rt
                if zero_rot:
                    rt = np.eye(3)
                pos, rot = pt, Rotation.from_matrix(rt)
            else:
                pos, rot = dp, dr
                if zero_rot:
                    rot = Rotation.identity()
            if ik.input_rotation_repr == "axis_angle":
                ori = rot.as_rotvec() if not zero_rot else np.zeros(3)
            else:
                ori = np.roll(rot.as_quat(), 1) * (1.0 if t != 3 else 1.7)  # one unnormalised
            action += list(np.round(pos, 6)) + list(np.round(ori, 6))
        # The parts outside the IK: fixed pseudo-random values.
        n_total = cc.action_limits[0].shape[0]
        extra = list(np.round(rng.uniform(-1.0, 1.0, n_total - len(action)), 6))
        action = action + extra
        if c["config"].get("skip_wbc_action"):
            action = list(np.round(rng.uniform(-0.3, 0.3, n_total), 6))
        for s in stubs.values():
            s.goals.clear()
        q_before = data.qpos.copy()
        cc.set_goal(np.array(action, dtype=float))
        assert np.array_equal(q_before, data.qpos), "set_goal changed qpos"
        step = {
            "qpos": [float(v) for v in data.qpos],
            "action": [float(v) for v in action],
            "parts": {p: [float(v) for v in stubs[p].goals[-1]] for p in cc.part_controllers},
        }
        if not c["config"].get("skip_wbc_action"):
            step["q_des"] = [float(v) for v in ik.q_des]
            # The kinematic robot follows the IK's targets.
            for k, name in enumerate(ik.joint_names):
                qpos[model.jnt_qposadr[model.joint(name).id]] = ik.q_des[k]
        steps.append(step)

    low, high = cc.action_limits
    return {
        "name": c["name"],
        "config": c["config"],
        "input_action_repr": c["input_action_repr"],
        "parts": [
            {
                "name": p,
                "joints": PARTS[p].get("joints", []),
                "action_dim": int(stubs[p].control_dim),
                "gripper": p in grippers,
                "arm": p in arms,
                "low": [float(v) for v in stubs[p].control_limits[0]],
                "high": [float(v) for v in stubs[p].control_limits[1]],
            }
            for p in parts
        ],
        "expected": {
            "joint_names": list(ik.joint_names),
            "nullspace_gains": [float(v) for v in ik.Kn],
            "ref_names": list(ik.site_names),
            "actuation_part_names": list(cc.composite_controller_specific_config["actuation_part_names"]),
            "ik_split": [[k, int(a), int(b)] for k, (a, b) in ik.action_split_indexes().items()],
            "action_split": [[k, int(a), int(b)] for k, (a, b) in cc._whole_body_controller_action_split_indexes.items()],
            "part_split": [[k, int(a), int(b)] for k, (a, b) in cc._action_split_indexes.items()],
            "action_low": limits_json(low),
            "action_high": limits_json(high),
        },
        "steps": steps,
    }


ENV_STEPS = 60


def short(x):
    """A per-step figure to 10 significant digits (far below the 1e-5 tolerance)."""
    return float(f"{x:.10g}")


def robot_touches(env):
    m, d = env.sim.model._model, env.sim.data._data
    robot_geoms = set()
    for r in env.robots:
        for g in list(r.robot_model.contact_geoms) + [g for gr in r.gripper.values() for g in gr.contact_geoms]:
            robot_geoms.add(mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, g))
    # A mobile base stands on the floor.
    floor = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "floor")
    for c in d.contact[: d.ncon]:
        if floor in (int(c.geom1), int(c.geom2)):
            continue
        if (int(c.geom1) in robot_geoms) != (int(c.geom2) in robot_geoms):
            return True
    return False


def env_case(robot, task, name, config_file, overrides, seed, toggle=True):
    """A rollout of `robot` on `task` under robosuite's WHOLE_BODY_IK (the config file
    `config_file` of robosuite's `controllers/config/`, with `overrides` in its specific
    configs): absolute grip-site targets circling each site's reset pose, the grippers
    opening and closing (held open unless `toggle`), zero for the other parts (a mobile
    base's velocity)."""
    from robosuite import load_composite_controller_config

    path = os.path.join(os.path.dirname(robosuite.__file__), "controllers", "config", config_file)
    cfg = load_composite_controller_config(controller=path, robot=robot)
    cfg["composite_controller_specific_configs"].update(overrides)
    given = copy.deepcopy(cfg)
    env = robosuite.make(
        task,
        robots=robot,
        controller_configs=cfg,
        has_renderer=False,
        has_offscreen_renderer=False,
        use_camera_obs=False,
        seed=seed,
    )
    obs = env.reset()
    cc = env.robots[0].composite_controller
    ik = cc.joint_action_policy
    m, d = env.sim.model._model, env.sim.data._data
    start = {}
    for site in ik.site_names:
        sid = m.site(site).id
        start[site] = (d.site_xpos[sid].copy(), Rotation.from_matrix(d.site_xmat[sid].reshape(3, 3)))
    frame = ik.input_ref_frame
    ik_split = ik.action_split_indexes()
    low, high = env.action_spec
    record = {
        "name": name,
        "robot": robot,
        "task": task,
        "config": given,
        "action_low": limits_json(low),
        "action_high": limits_json(high),
        "task_state": [float(x) for x in env.cube.size] if task == "Lift" else [],
        "init_state": [float(x) for x in env.sim.get_state().flatten()],
        "actions": [],
        "steps": [],
    }
    for t in range(ENV_STEPS):
        w = 2 * np.pi * t / 30.0
        action = np.zeros(env.action_dim)
        for i, site in enumerate(ik.site_names):
            p0, r0 = start[site]
            sign = 1.0 if i == 0 else -1.0
            p = p0 + np.array([0.08 * np.sin(w), sign * 0.06 * np.sin(2 * w), 0.05 * (1 - np.cos(w))])
            r = Rotation.from_rotvec([0.15 * np.sin(w), sign * 0.1 * np.sin(w), 0.2 * np.sin(w)]) * r0
            if frame != "world":
                body = "robot0_base" if frame == "base" else frame
                fp, fq = m.body(body).pos, m.body(body).quat
                fr = Rotation.from_quat(np.roll(fq, -1))
                p, r = fr.inv().apply(p - fp), fr.inv() * r
            k = 6 * i
            action[k : k + 6] = np.concatenate([p, r.as_rotvec()])
        for part, (a, b) in cc._whole_body_controller_action_split_indexes.items():
            if part.endswith("_gripper"):
                action[a:b] = 1.0 if toggle and (t // 10) % 2 else -1.0
        action = np.round(action, 6)
        record["actions"].append([float(x) for x in action])
        obs, _, _, _ = env.step(action.copy())
        if robot_touches(env):
            sys.exit(f"record_whole_body_ik: {robot} {name} touched something at step {t}")
        record["eef_keys"] = sorted(k for k in obs if k.endswith("eef_pos") and "base_to" not in k)
        record["gripper_keys"] = sorted(k for k in obs if k.endswith("gripper_qpos"))
        record["steps"].append(
            {
                "joint_pos": [short(x) for x in obs["robot0_joint_pos"]],
                "eef_pos": [short(x) for k in record["eef_keys"] for x in obs[k]],
                "gripper_qpos": [short(x) for k in record["gripper_keys"] for x in obs[k]],
            }
        )
    env.close()
    return record


ENV_CASES = [
    ("Panda", "Lift", "WHOLE_BODY_IK", "default/composite/whole_body_ik.json", {}),
    ("Panda", "Lift", "WHOLE_BODY_IK base frame", "default/composite/whole_body_ik.json", {"ik_input_ref_frame": "base"}),
    # Tiago's Robotiq85 fingers (a closed linkage) differ between MuJoCo 3.3.7 and 3.17 by
    # up to 0.1 when they reverse (as the UR5e's in record_controllers.py): held open here.
    ("Tiago", "TwoArmLift", "Tiago WHOLE_BODY_IK", "robots/default_tiago_whole_body_ik.json", {"toggle": False}),
    ("PandaOmron", "Lift", "PandaOmron WHOLE_BODY_IK", "robots/default_pandaomron_whole_body_ik.json", {}),
]


def main():
    model = mujoco.MjModel.from_xml_path(MODEL)
    out = {
        "robosuite": robosuite.__version__,
        "mujoco": mujoco.__version__,
        "model": os.path.basename(MODEL),
        "cases": [record_case(c, model) for c in CASES],
        "env_cases": [
            env_case(r, t, name, f, {k: v for k, v in o.items() if k != "toggle"}, 300 + i, o.get("toggle", True))
            for i, (r, t, name, f, o) in enumerate(ENV_CASES)
        ],
    }
    fixture_json.dump(out, OUT)
    print(f"wrote {OUT}: {len(out['cases'])} cases, {len(out['env_cases'])} env rollouts")


if __name__ == "__main__":
    main()
