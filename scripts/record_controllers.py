#!/usr/bin/env python3
"""Record robosuite 1.5.2's arm controllers as test fixtures for robosuite-rs.

Run it with a Python that has robosuite 1.5.2 (and mujoco 3.3.7), for example through
scripts/record_robosuite.sh's virtualenv:

    .bench-venv/robosuite/bin/python scripts/record_controllers.py [ROBOT ...]

It writes robosuite-env/tests/fixtures/robosuite/controllers/ROBOT.json, figures only. For
each case (a controller config, as robosuite users write it, on Lift):

* the config robosuite-rs is given, and the config robosuite ran (they differ only where
  robosuite 1.5.2 is broken, see below);
* the action bounds robosuite's env reports (`action_spec`);
* the drawn cube size and the state right after a seeded reset, 60 actions, and after every
  step the arm's joint positions, the grip site's position and the gripper's joint positions
  (10 significant digits; actions are rounded to 6 decimals before robosuite runs them). The arm moves freely: the recorder checks that the robot touches
  nothing.

Two controllers cannot run as robosuite 1.5.2 ships them, so robosuite runs them as its
documentation describes, with the smallest change:
* JOINT_VELOCITY: its constructor assigns to the read-only `torque_compensation` property
  (AttributeError) and later tests that array's truth value; both uses are renamed to the
  `use_torque_compensation` flag its other controllers have (patched in memory here).
* IK_POSE: its joint-position target is absolute but goes to a delta-mode joint-position
  controller; robosuite's own `"input_type": "absolute"` key (passed through to that
  controller) fixes it. On robots outside IK's list (UR5e, ...) the robot is added to the
  list and the nullspace gains are sized to the arm: 10 on all but the last three joints, 5
  on those (robosuite's [10, 10, 10, 10, 5, 5, 5] for 7 joints).

It also records, as figures for the documentation, how far robosuite's broken set-ups move
the hand under zero actions over 20 steps: IK_POSE as shipped, and OSC_POSE with linear
interpolation in its default base frame.

With --floor (run with robosuite on MuJoCo 3.17.0, as scripts/record_robosuite.sh's second
virtualenv has it) it replays every recorded case and writes into the fixture how far
robosuite itself then is from its 3.3.7 recording: the part of any difference that MuJoCo's
version causes.
"""
import argparse
import copy
import inspect
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fixture_json  # noqa: E402  (scripts/fixture_json.py: the fixtures' layout)

os.environ.setdefault("MUJOCO_GL", "disable")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import robosuite  # noqa: E402
import robosuite as suite  # noqa: E402
from robosuite import load_composite_controller_config  # noqa: E402
from robosuite.controllers.parts import generic  # noqa: E402
from robosuite.controllers.parts.arm import ik as ik_module  # noqa: E402
from robosuite.controllers.parts.generic import joint_vel  # noqa: E402

STEPS = 60


def fix_joint_velocity():
    """robosuite's JointVelocityController with `use_torque_compensation` as its flag."""
    source = inspect.getsource(joint_vel)
    source = source.replace(
        'self.torque_compensation = kwargs.get("use_torque_compensation", True)',
        'self.use_torque_compensation = kwargs.get("use_torque_compensation", True)',
    )
    source = source.replace("if self.torque_compensation:", "if self.use_torque_compensation:")
    namespace = {}
    exec(compile(source, joint_vel.__file__, "exec"), namespace)
    generic.JointVelocityController = namespace["JointVelocityController"]


def size_ik_gains(robot, n):
    """Lets IK_POSE run on `robot` with nullspace gains for `n` joints."""
    ik_module.SUPPORTED_IK_ROBOTS.add(robot)
    func = ik_module.InverseKinematicsController.__dict__["compute_joint_positions"].__func__
    defaults = list(func.__defaults__)
    names = func.__code__.co_varnames[: func.__code__.co_argcount]
    first_default = len(names) - len(defaults)
    defaults[names.index("Kn") - first_default] = np.array([10.0] * (n - 3) + [5.0] * 3)
    func.__defaults__ = tuple(defaults)


def part(kind, **overrides):
    """robosuite's default part config file for `kind`, with `overrides`."""
    path = os.path.join(os.path.dirname(robosuite.__file__), "controllers", "config", "default", "parts", f"{kind.lower()}.json")
    with open(path) as f:
        cfg = json.load(f)
    cfg.update(overrides)
    return cfg


def composite(robot, arm_cfg):
    cfg = load_composite_controller_config(robot=robot)
    arm = copy.deepcopy(arm_cfg)
    arm["gripper"] = cfg["body_parts"]["right"].get("gripper", {"type": "GRIP"})
    cfg["body_parts"]["right"] = arm
    return cfg


def make(robot, cfg, seed):
    return suite.make(
        "Lift",
        robots=robot,
        controller_configs=cfg,
        has_renderer=False,
        has_offscreen_renderer=False,
        use_camera_obs=False,
        seed=seed,
    )


def same_collisions_as_mujoco_3_3(env):
    """On MuJoCo 3.17 (when measuring what MuJoCo's version changes), turns off the multi-
    contact convex collisions that 3.17 turns on by default and 3.3.7 lacks, as robosuite-rs
    does."""
    if hasattr(mujoco.mjtDisableBit, "mjDSBL_MULTICCD"):
        env.sim.model._model.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_MULTICCD


def short(x):
    """A per-step figure to 10 significant digits (far below the 1e-5 tolerance)."""
    return float(f"{x:.10g}")


def robot_touches(env):
    m, d = env.sim.model._model, env.sim.data._data
    robot_geoms = set()
    for r in env.robots:
        for g in list(r.robot_model.contact_geoms) + [g for gr in r.gripper.values() for g in gr.contact_geoms]:
            robot_geoms.add(mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, g))
    for c in d.contact[: d.ncon]:
        if (int(c.geom1) in robot_geoms) != (int(c.geom2) in robot_geoms):
            return True
    return False


def base_frame_pose(env):
    """The grip site's pose in the arm's base frame (the `robot0_right_center` site):
    position and rotation vector."""
    from scipy.spatial.transform import Rotation

    d, m = env.sim.data, env.sim.model
    b = m.site_name2id("robot0_right_center")
    s = m.site_name2id("gripper0_right_grip_site")
    pb, rb = d.site_xpos[b], d.site_xmat[b].reshape(3, 3)
    p, r = d.site_xpos[s], d.site_xmat[s].reshape(3, 3)
    return rb.T @ (p - pb), Rotation.from_matrix(rb.T @ r).as_rotvec(), p.copy(), Rotation.from_matrix(r).as_rotvec()


# Action generators: (env, rng, step) -> arm action (the gripper's is appended).
def uniform(scale=0.5):
    return lambda env, ctx, rng, t: rng.uniform(-scale, scale, ctx["arm_dim"])


def with_gains(inner, kp=(30.0, 300.0), damping=None):
    def act(env, ctx, rng, t):
        parts = []
        if damping is not None:
            parts.append(rng.uniform(damping[0], damping[1], ctx["gain_dim"]))
        parts.append(rng.uniform(kp[0], kp[1], ctx["gain_dim"]))
        parts.append(inner(env, ctx, rng, t))
        return np.concatenate(parts)

    return act


def absolute_pose(frame):
    """Targets around the reset pose, in the input frame: position, rotation vector."""

    def act(env, ctx, rng, t):
        p0, r0 = ctx["base_pose"] if frame == "base" else ctx["world_pose"]
        w = 2 * np.pi * t / 30.0
        pos = p0 + np.array([0.08 * np.sin(w), 0.06 * np.sin(2 * w), 0.05 * (1 - np.cos(w))])
        rot = r0 + np.array([0.15 * np.sin(w), 0.1 * np.sin(w), 0.2 * np.sin(w)])
        return np.concatenate([pos, rot])

    return act


def absolute_joints(env, ctx, rng, t):
    w = 2 * np.pi * t / 30.0
    n = ctx["joints"]
    return ctx["q0"] + 0.15 * np.sin(w + np.arange(n))


def cases_for(robot, n):
    """(name, arm config, robosuite's config if different, action generator)."""
    osc = part("OSC_POSE")
    osc["damping_ratio_limits"] = [0, 10]
    c = [
        ("OSC_POSE", osc, None, uniform()),
        ("OSC_POSITION", part("OSC_POSITION"), None, uniform()),
        ("IK_POSE", part("IK_POSE"), part("IK_POSE", input_type="absolute"), uniform(0.05)),
        ("JOINT_POSITION", part("JOINT_POSITION"), None, uniform()),
        ("JOINT_VELOCITY", part("JOINT_VELOCITY"), None, uniform()),
        ("JOINT_TORQUE", part("JOINT_TORQUE"), None, uniform()),
        ("JOINT_TORQUE output 5", part("JOINT_TORQUE", output_max=5.0, output_min=-5.0), None, uniform()),
    ]
    if robot != "Panda":
        return c
    return c + [
        ("OSC_POSE world", dict(osc, input_ref_frame="world"), None, uniform()),
        ("OSC_POSE absolute base", dict(osc, input_type="absolute"), None, absolute_pose("base")),
        ("OSC_POSE absolute world", dict(osc, input_type="absolute", input_ref_frame="world"), None, absolute_pose("world")),
        ("OSC_POSE variable", dict(osc, impedance_mode="variable"), None, with_gains(uniform(), damping=(0.5, 2.0))),
        ("OSC_POSE variable_kp", dict(osc, impedance_mode="variable_kp"), None, with_gains(uniform())),
        ("OSC_POSE coupled", dict(osc, uncouple_pos_ori=False), None, uniform()),
        ("OSC_POSE linear world", dict(osc, interpolation="linear", input_ref_frame="world"), None, uniform()),
        ("OSC_POSE kp list", dict(osc, kp=[100, 150, 200, 250, 300, 120], damping_ratio=[1, 0.8, 1.2, 1, 0.9, 1.1]), None, uniform()),
        ("OSC_POSITION variable_kp", dict(part("OSC_POSITION"), impedance_mode="variable_kp"), None, with_gains(uniform())),
        ("OSC_POSITION world", dict(part("OSC_POSITION"), input_ref_frame="world"), None, uniform()),
        ("JOINT_POSITION absolute", part("JOINT_POSITION", input_type="absolute"), None, absolute_joints),
        ("JOINT_POSITION variable", part("JOINT_POSITION", impedance_mode="variable"), None, with_gains(uniform(), damping=(0.5, 2.0))),
        ("JOINT_POSITION variable_kp", part("JOINT_POSITION", impedance_mode="variable_kp"), None, with_gains(uniform())),
        ("JOINT_POSITION linear", part("JOINT_POSITION", interpolation="linear"), None, uniform()),
        ("JOINT_VELOCITY linear", part("JOINT_VELOCITY", interpolation="linear"), None, uniform()),
        ("JOINT_VELOCITY kp list", part("JOINT_VELOCITY", kp=[20.0] * n), None, uniform()),
        ("JOINT_TORQUE linear", part("JOINT_TORQUE", output_max=5.0, output_min=-5.0, interpolation="linear"), None, uniform()),
    ]


def gripper_action(rng, t):
    return 1.0 if (t // 10) % 2 else -1.0


def run_case(robot, name, cfg, rs_cfg, policy, seed, actions=None):
    env = make(robot, composite(robot, rs_cfg or cfg), seed)
    obs = env.reset()
    same_collisions_as_mujoco_3_3(env)
    ctrl = env.robots[0].part_controllers["right"]
    n = len(env.robots[0].arm_joints) if hasattr(env.robots[0], "arm_joints") else len(ctrl.qpos_index)
    base_p, base_r, world_p, world_r = base_frame_pose(env)
    gain_dim = 6 if name.startswith("OSC") else n
    arm_dim = (6 if name.startswith(("OSC_POSE", "IK")) else 3 if name.startswith("OSC_POSITION") else n)
    ctx = {
        "joints": n,
        "arm_dim": arm_dim,
        "gain_dim": gain_dim,
        "q0": np.array(env.sim.data.qpos[ctrl.qpos_index]),
        "base_pose": (base_p, base_r),
        "world_pose": (world_p, world_r),
    }
    low, high = env.action_spec
    record = {
        "name": name,
        "config": cfg,
        "robosuite_config": rs_cfg,
        "action_low": [float(x) for x in low],
        "action_high": [float(x) for x in high],
        "task_state": [float(x) for x in env.cube.size],
        "init_state": [float(x) for x in env.sim.get_state().flatten()],
        "actions": [],
        "steps": [],
    }
    rng = np.random.default_rng(seed)
    for t in range(STEPS):
        if actions is None:
            arm = policy(env, ctx, rng, t)
            # Rounded before robosuite sees them, so the fixture holds the exact actions.
            action = np.round(np.concatenate([np.asarray(arm, dtype=np.float64), [gripper_action(rng, t)]]), 6)
        else:
            action = np.asarray(actions[t], dtype=np.float64)
        obs, _, _, _ = env.step(action)
        if robot_touches(env):
            sys.exit(f"record_controllers: {robot} {name} touched something at step {t}; free motion is required")
        record["actions"].append([float(x) for x in action])
        record["steps"].append(
            {
                "joint_pos": [short(x) for x in obs["robot0_joint_pos"]],
                "eef_pos": [short(x) for x in obs["robot0_eef_pos"]],
                "gripper_qpos": [short(x) for x in obs["robot0_gripper_qpos"]],
            }
        )
    env.close()
    return record


def zero_action_drift(robot, arm_cfg):
    """How far the grip site moves in 20 zero-action steps."""
    env = make(robot, composite(robot, arm_cfg), 5)
    obs = env.reset()
    p0 = np.array(obs["robot0_eef_pos"])
    for _ in range(20):
        obs, _, _, _ = env.step(np.zeros(env.action_dim))
    env.close()
    return float(np.linalg.norm(np.array(obs["robot0_eef_pos"]) - p0))


def record(robot, out):
    probe = make(robot, None, 0)
    n = len(probe.robots[0].part_controllers["right"].qpos_index)
    probe.close()
    size_ik_gains(robot, n)
    data = {
        "robot": robot,
        "robosuite": robosuite.__version__,
        "mujoco": mujoco.__version__,
        "joints": n,
        "cases": [],
    }
    for i, (name, cfg, rs_cfg, policy) in enumerate(cases_for(robot, n)):
        data["cases"].append(run_case(robot, name, cfg, rs_cfg, policy, 200 + i))
    if robot == "Panda":
        osc_linear = dict(part("OSC_POSE"), interpolation="linear")
        data["robosuite_zero_action_drift"] = {
            "IK_POSE": zero_action_drift(robot, part("IK_POSE")),
            "OSC_POSE linear base": zero_action_drift(robot, osc_linear),
        }
    path = os.path.join(out, f"{robot}.json")
    fixture_json.dump(data, path)
    print(f"{robot}: {len(data['cases'])} cases -> {path} ({os.path.getsize(path) // 1024} KiB)")


def floor(robot, out):
    """What MuJoCo's version alone changes: robosuite on this MuJoCo (3.17.0, with 3.3.7's
    collision set) replaying each recorded case, against the recording; written into the
    fixture as each case's `floor`."""
    path = os.path.join(out, f"{robot}.json")
    with open(path) as f:
        data = json.load(f)
    probe = make(robot, None, 0)
    n = len(probe.robots[0].part_controllers["right"].qpos_index)
    probe.close()
    size_ik_gains(robot, n)
    cases = {name: (cfg, rs_cfg, seed) for seed, (name, cfg, rs_cfg, _) in enumerate(cases_for(robot, n), start=200)}
    for case in data["cases"]:
        cfg, rs_cfg, seed = cases[case["name"]]
        again = run_case(robot, case["name"], cfg, rs_cfg, None, seed, actions=case["actions"])
        case["floor"] = {
            k: max(max(abs(x - y) for x, y in zip(a[k], b[k])) for a, b in zip(case["steps"], again["steps"]))
            for k in ("joint_pos", "eef_pos", "gripper_qpos")
        }
        case["floor_mujoco"] = mujoco.__version__
    fixture_json.dump(data, path)
    worst = max(max(c["floor"].values()) for c in data["cases"])
    print(f"{robot}: floors written (largest {worst:.2e}) -> {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "..", "robosuite-env", "tests", "fixtures", "robosuite", "controllers"))
    parser.add_argument("--floor", action="store_true", help="measure MuJoCo-version floors into existing fixtures (run on MuJoCo 3.17)")
    parser.add_argument("robots", nargs="*", default=["Panda", "Sawyer", "UR5e"])
    args = parser.parse_args()
    if robosuite.__version__ != "1.5.2":
        sys.exit(f"record_controllers: robosuite {robosuite.__version__} is installed, 1.5.2 is needed")
    fix_joint_velocity()
    os.makedirs(args.out, exist_ok=True)
    for robot in args.robots:
        (floor if args.floor else record)(robot, args.out)


if __name__ == "__main__":
    main()
