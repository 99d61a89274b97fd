#!/usr/bin/env python3
"""Record robosuite 1.5.2's own behaviour as test fixtures for robosuite-rs.

Run it with a Python that has robosuite 1.5.2 (and mujoco 3.3.7) installed, for example
through scripts/record_robosuite.sh, which makes such a virtualenv. It writes, per task, one
JSON file to robosuite-env/tests/fixtures/robosuite/ holding figures only:

* the compiled scene's counts (nq, nv, nu, nbody, ...) and the names of every body, joint,
  geom, site, actuator, sensor, camera and mesh, in model order;
* rollouts: the task parameters robosuite drew (Lift's cube size, Wipe's markers, ...), the
  state [time, qpos, qvel] right after reset, a fixed action sequence (a scripted reach,
  grasp and lift, or seeded random actions), and after every step chosen observations (to
  12 significant digits), the reward, success and whether the robot touched anything;
* placement: over many resets, the smallest and largest initial position of every object.

Mobile robots (PandaOmron, Tiago) add a rollout that moves the base and torso; legged
robots (SpotWithArm, SpotWithArmFloating) one that moves the legs or the floating base.

Usage: record_robosuite.py [--out DIR] [--resets N] [--robot NAME] [TASK ...]
(default: every task, with the Panda; another robot's fixtures are named TASK-ROBOT.json)
       record_robosuite.py --layouts [--every-task] --robot NAME
(the robot's observation layouts on every single-arm task, or with --every-task on all 19
tasks with the robot alone, as `TASK-ROBOT` entries of observations.json; GR1FixedLowerBody,
whose default WHOLE_BODY_MINK_IK needs mink, with robosuite's WHOLE_BODY_IK config)
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fixture_json  # noqa: E402  (scripts/fixture_json.py: the fixtures' layout)

os.environ.setdefault("MUJOCO_GL", "disable")
if os.environ.get("PYTHONHASHSEED") != "0":
    # robosuite's single-object mode 1 draws the object from a set of names, whose order
    # follows string hashing: fix it so that recordings repeat.
    os.environ["PYTHONHASHSEED"] = "0"
    os.execv(sys.executable, [sys.executable] + sys.argv)

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import robosuite  # noqa: E402
import robosuite as suite  # noqa: E402

OBJ = {
    "body": mujoco.mjtObj.mjOBJ_BODY,
    "joint": mujoco.mjtObj.mjOBJ_JOINT,
    "geom": mujoco.mjtObj.mjOBJ_GEOM,
    "site": mujoco.mjtObj.mjOBJ_SITE,
    "actuator": mujoco.mjtObj.mjOBJ_ACTUATOR,
    "sensor": mujoco.mjtObj.mjOBJ_SENSOR,
    "camera": mujoco.mjtObj.mjOBJ_CAMERA,
    "mesh": mujoco.mjtObj.mjOBJ_MESH,
}
COUNTS = {
    "body": "nbody",
    "joint": "njnt",
    "geom": "ngeom",
    "site": "nsite",
    "actuator": "nu",
    "sensor": "nsensor",
    "camera": "ncam",
    "mesh": "nmesh",
}


def make_kwargs(robots, kwargs):
    """A fixture's recorded `make` arguments as robosuite takes them: `composite_controller`
    (a name) becomes robosuite's `controller_configs` for the robot
    (`load_composite_controller_config(controller=..., robot=...)`)."""
    kwargs = dict(kwargs)
    name = kwargs.pop("composite_controller", None)
    if name is not None:
        from robosuite.controllers import load_composite_controller_config

        robot = robots if isinstance(robots, str) else robots[0]
        kwargs["controller_configs"] = load_composite_controller_config(controller=name, robot=robot)
    return kwargs


def make(task, seed, **kwargs):
    robots = kwargs.pop("robots", "Panda")
    return suite.make(
        task,
        robots=robots,
        has_renderer=False,
        has_offscreen_renderer=False,
        use_camera_obs=False,
        seed=seed,
        **make_kwargs(robots, kwargs),
    )


def scene(env):
    m = env.sim.model._model
    names = {k: [mujoco.mj_id2name(m, t, i) or "" for i in range(getattr(m, COUNTS[k]))] for k, t in OBJ.items()}
    counts = {c: int(getattr(m, c)) for c in ["nq", "nv", "nu", "nbody", "njnt", "ngeom", "nsite", "nmesh", "nsensor", "ncam"]}
    return counts, names


def short(x):
    """A per-step figure to 12 significant digits (far below every tolerance)."""
    return float(f"{x:.12g}")


def flat_state(env):
    return [float(x) for x in env.sim.get_state().flatten()]


def robot_touches(env):
    """Whether any contact pairs a robot or gripper geom with a geom outside the robot."""
    m, d = env.sim.model._model, env.sim.data._data
    robot_geoms = set()
    for r in env.robots:
        for g in r.robot_model.contact_geoms:
            robot_geoms.add(mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, g))
        for gripper in r.gripper.values():
            for g in gripper.contact_geoms:
                robot_geoms.add(mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, g))
    for c in d.contact[: d.ncon]:
        a, b = int(c.geom1), int(c.geom2)
        if (a in robot_geoms) != (b in robot_geoms):
            return True
    return False


# ---------------------------------------------------------------------------------------
# Task parameters: what robosuite drew at its hard reset that the state does not hold, in
# the layout robosuite-rs's Task::save_state uses.


PICK_PLACE = ["PickPlace", "PickPlaceSingle", "PickPlaceMilk", "PickPlaceBread", "PickPlaceCereal", "PickPlaceCan"]
NUT_ASSEMBLY = ["NutAssembly", "NutAssemblySingle", "NutAssemblySquare", "NutAssemblyRound"]


def active_object(task, env):
    """The object in play of a single-object mode (PickPlace's `object_id`, NutAssembly's
    `nut_id`), or None in mode 0."""
    if task in PICK_PLACE and env.single_object_mode != 0:
        return env.object_id
    if task in NUT_ASSEMBLY and env.single_object_mode != 0:
        return env.nut_id
    return None


def task_state(task, env):
    if task == "Lift":
        return [float(x) for x in env.cube.size]
    if task == "TwoArmPegInHole":
        # The peg radius drawn at the hard reset.
        return [float(env.peg.size[0])]
    if task in ("TwoArmHandover", "TwoArmTransport"):
        # The hammer's figures drawn at the hard reset.
        h = env.hammer if task == "TwoArmHandover" else env.transport.payload
        return [float(x) for x in (h.handle_radius, h.handle_length, h.handle_density, h.handle_friction, h.head_halfsize)]
    if task == "ToolHang":
        # No drawn model parameters; the state is ToolHang's observation cache, which a
        # replay restarts from the recorded reset state.
        return []
    if task == "Door":
        # The door's root pose, placed through the model: position, then quaternion (wxyz).
        body = env.sim.model.body_name2id(env.door.root_body)
        return [float(x) for x in env.sim.model.body_pos[body]] + [float(x) for x in env.sim.model.body_quat[body]]
    if task == "Wipe":
        # Marker positions (model body_pos), wiped flags, then per arm the force bias, the
        # step's force and the force sensor now.
        markers = env.model.mujoco_arena.markers
        pos = [float(x) for m in markers for x in env.sim.model.body_pos[env.sim.model.body_name2id(m.root_body)]]
        arms = env.robots[0].arms
        force = [float(x) for arm in arms for x in env.robots[0].ee_force[arm]]
        return pos + [float(m in env.wiped_markers) for m in markers] + [0.0] * (6 * len(arms)) + force
    active = active_object(task, env)
    if active is not None:
        # The object in play.
        return [float(active)]
    return []


def our_key(task, env, key):
    """robosuite-rs's name for an observation key. In single-object mode 1 robosuite names
    the object keys after each reset's object (`Cereal_pos`); a fixed observation space
    cannot, so robosuite-rs names them `obj_*` (PickPlaceSingle) / `nut_*`
    (NutAssemblySingle)."""
    prefix = {"PickPlaceSingle": ("obj", lambda: env.objects[env.object_id].name),
              "NutAssemblySingle": ("nut", lambda: env.nuts[env.nut_id].name)}.get(task)
    if prefix is not None:
        name = prefix[1]() + "_"
        if key.startswith(name):
            return prefix[0] + "_" + key[len(name):]
    return key


# Observation keys recorded per step (beside the full state).
def obs_keys(task, obs):
    skip = ("-state", "_cos", "_sin", "joint_acc", "eef_quat_site", "gripper_qvel")
    return [k for k in obs if not k.endswith(skip) and not any(s in k for s in skip)]


# ---------------------------------------------------------------------------------------
# Scripted policies: reach a point above a target, descend, close, lift. Targets come from
# robosuite's own observations, so the recorded actions are robosuite's closed loop.


def toward(eef, target, gain=10.0):
    return np.clip((np.asarray(target) - np.asarray(eef)) * gain, -1.0, 1.0)


def pick_policy(obj_key, lift_height=0.15, grasp_depth=-0.005):
    state = {"phase": 0, "t": 0, "start": None}

    def act(obs):
        eef = obs["robot0_eef_pos"]
        obj = obs[obj_key]
        if state["start"] is None:
            state["start"] = np.array(obj)
        state["t"] += 1
        grip = -1.0
        if state["phase"] == 0:
            target = obj + np.array([0, 0, 0.08])
            if np.linalg.norm(target - eef) < 0.01 or state["t"] > 30:
                state["phase"], state["t"] = 1, 0
        elif state["phase"] == 1:
            target = obj + np.array([0, 0, grasp_depth])
            if np.linalg.norm(target - eef) < 0.008 or state["t"] > 20:
                state["phase"], state["t"] = 2, 0
        elif state["phase"] == 2:
            target, grip = eef, 1.0
            if state["t"] > 8:
                state["phase"], state["t"] = 3, 0
        else:
            target, grip = state["start"] + np.array([0, 0, lift_height]), 1.0
        a = np.zeros(7)
        a[:3] = toward(eef, target)
        a[6] = grip
        return a

    return act


def wrap_angle(a):
    return (a + np.pi) % (2 * np.pi) - np.pi


def bar_grasp_policy(obj_name, lift_height=0.1):
    """Grasp a bar lying along its object's x axis (ToolHang's tool grip): reach 20 cm above
    it while yawing the hand so the fingers close across the bar, descend, close, lift."""
    import robosuite.utils.transform_utils as T

    state = {"phase": 0, "t": 0, "start": None}

    def act(obs):
        eef = obs["robot0_eef_pos"]
        obj = np.asarray(obs[f"{obj_name}_pos"])
        if state["start"] is None:
            state["start"] = obj.copy()
        state["t"] += 1
        finger = T.quat2mat(obs["robot0_eef_quat"])[:, 1]
        bar = T.quat2mat(obs[f"{obj_name}_quat"])[:, 0]
        err = wrap_angle(np.arctan2(bar[1], bar[0]) + np.pi / 2 - np.arctan2(finger[1], finger[0]))
        if abs(err) > np.pi / 2:
            err = wrap_angle(err + np.pi)
        grip = -1.0
        if state["phase"] == 0:
            # high enough to pass over ToolHang's stand
            target = obj + np.array([0, 0, 0.2])
            if (np.linalg.norm(target - eef) < 0.01 and abs(err) < 0.03) or state["t"] > 40:
                state["phase"], state["t"] = 1, 0
        elif state["phase"] == 1:
            target = obj
            if np.linalg.norm(target - eef) < 0.006 or state["t"] > 30:
                state["phase"], state["t"] = 2, 0
        elif state["phase"] == 2:
            target, grip = eef, 1.0
            if state["t"] > 10:
                state["phase"], state["t"] = 3, 0
        else:
            target, grip = state["start"] + np.array([0, 0, lift_height]), 1.0
        a = np.zeros(7)
        a[:3] = toward(eef, target)
        a[5] = np.clip(err * 4.0, -1.0, 1.0) if state["phase"] < 2 else 0.0
        a[6] = grip
        return a

    return act


def yaw_of(q):
    """The yaw of an xyzw quaternion."""
    x, y, z, w = q
    return np.arctan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def finger_yaw(obs):
    """The yaw of the Panda's finger axis (the hand's y axis) from robot0_eef_quat."""
    x, y, z, w = obs["robot0_eef_quat"]
    return np.arctan2(1.0 - 2.0 * (x * x + z * z), 2.0 * (x * y - w * z))


def wrap(a, period):
    """An angle wrapped to [-period/2, period/2)."""
    return (a + period / 2) % period - period / 2


def osc_action(eef, target, yaw, grip):
    """A Panda action: toward `target`, turning by `yaw` about z, with the gripper command."""
    out = np.zeros(7)
    out[:3] = toward(eef, target)
    out[5] = np.clip(yaw / 0.5, -1.0, 1.0)
    out[6] = grip
    return out


def stack_policy():
    """Grasp cube A (fingers aligned with its faces), lift it, carry it over cube B, lower
    it onto B, release and retreat."""
    state = {"phase": 0, "t": 0}

    def act(obs):
        eef, a, b = obs["robot0_eef_pos"], obs["cubeA_pos"], obs["cubeB_pos"]
        state["t"] += 1
        phase, t = state["phase"], state["t"]
        grip, yaw, done = -1.0, 0.0, False
        if phase == 0:
            target = a + np.array([0, 0, 0.08])
            yaw = wrap(yaw_of(obs["cubeA_quat"]) - finger_yaw(obs), np.pi / 2)
            done = (np.linalg.norm(target - eef) < 0.01 and abs(yaw) < 0.05) or t > 45
        elif phase == 1:
            target = a + np.array([0, 0, -0.005])
            yaw = wrap(yaw_of(obs["cubeA_quat"]) - finger_yaw(obs), np.pi / 2)
            done = np.linalg.norm(target - eef) < 0.008 or t > 25
        elif phase == 2:
            target, grip, done = eef, 1.0, t > 8
        elif phase == 3:
            target, grip = np.array([eef[0], eef[1], 0.95]), 1.0
            done = eef[2] > 0.93 or t > 30
        elif phase == 4:
            target, grip = np.array([b[0] + eef[0] - a[0], b[1] + eef[1] - a[1], 0.95]), 1.0
            done = np.linalg.norm((a - b)[:2]) < 0.004 or t > 50
        elif phase == 5:
            target, grip = np.array([b[0] + eef[0] - a[0], b[1] + eef[1] - a[1], eef[2] + b[2] + 0.047 - a[2]]), 1.0
            done = a[2] - b[2] < 0.05 or t > 30
        elif phase == 6:
            target, done = eef, t > 10
        else:
            target = np.array([eef[0], eef[1], 1.0])
        if done:
            state["phase"], state["t"] = phase + 1, 0
        return osc_action(eef, target, yaw, grip)

    return act


def door_policy(env):
    """Fingers across the door's normal above the handle, descend onto the lever, close,
    press the lever down (turning the latch), then pull along the door's normal."""
    door = env.sim.model.body_name2id(env.door.door_body)
    state = {"phase": 0, "t": 0, "anchor": None}

    def act(obs):
        eef, handle = obs["robot0_eef_pos"], obs["handle_pos"]
        w, _, _, z = env.sim.data.body_xquat[door]
        yaw = 2.0 * np.arctan2(z, w)
        normal = np.array([np.sin(yaw), -np.cos(yaw), 0.0])
        state["t"] += 1
        phase, t = state["phase"], state["t"]
        grip, done = -1.0, False
        if phase == 0:
            target = handle + np.array([0, 0, 0.06])
            done = np.linalg.norm(target - eef) < 0.01 or t > 40
        elif phase == 1:
            target = handle + np.array([0, 0, -0.005])
            done = np.linalg.norm(target - eef) < 0.008 or t > 25
        elif phase == 2:
            target, grip, done = eef, 1.0, t > 8
        elif phase == 3:
            target, grip = state["anchor"] + np.array([0, 0, -0.1]), 1.0
            done = float(obs["handle_qpos"]) > 0.6 or t > 40
        else:
            target, grip = state["anchor"] + 0.2 * normal, 1.0
        yaw_err = wrap(np.arctan2(normal[1], normal[0]) - finger_yaw(obs), np.pi) if phase < 3 else 0.0
        if done:
            state["phase"], state["t"], state["anchor"] = phase + 1, 0, np.array(eef)
        return osc_action(eef, target, yaw_err, grip)

    return act


def wipe_policy(env):
    """Above the first marker, press the tool 2 cm into the table and follow the markers'
    path, one marker per step."""
    ids = [env.sim.model.body_name2id(m.root_body) for m in env.model.mujoco_arena.markers]
    points = np.array([env.sim.data.body_xpos[i] for i in ids])
    state = {"t": 0, "k": 0, "down": False}

    def act(obs):
        eef = obs["robot0_eef_pos"]
        p = points[min(state["k"], len(points) - 1)]
        state["t"] += 1
        if not state["down"] and (np.hypot(*(eef - p)[:2]) < 0.01 or state["t"] > 60):
            state["down"] = True
        if state["down"]:
            state["k"] += 1
        out = np.zeros(6)
        out[:3] = toward(eef, [p[0], p[1], p[2] - 0.02 if state["down"] else p[2] + 0.05])
        return out

    return act


def place_policy(grab, goal, carry_z, release_z):
    """Pick an object and put it down: above the grasp point `grab(obs)` (returning the
    point and the yaw error of the fingers, or None not to align), descend, close, lift to
    `carry_z`, carry the object over `goal` (xy), lower it until the object is at
    `release_z`, open and rise."""
    state = {"phase": 0, "t": 0}

    def act(obs, obj_pos):
        eef = np.asarray(obs["robot0_eef_pos"])
        point, yaw_err = grab(obs)
        grip, align = -1.0, False
        ph = state["phase"]
        if ph == 0:
            target, align = point + np.array([0, 0, 0.08]), True
        elif ph == 1:
            target, align = point, True
        elif ph == 2:
            target, grip = eef, 1.0
        elif ph == 3:
            target, grip = np.array([eef[0], eef[1], carry_z]), 1.0
        elif ph == 4:
            target, grip = np.array([goal[0] + eef[0] - obj_pos[0], goal[1] + eef[1] - obj_pos[1], carry_z]), 1.0
        elif ph == 5:
            target = np.array([goal[0] + eef[0] - obj_pos[0], goal[1] + eef[1] - obj_pos[1], eef[2] - obj_pos[2] + release_z])
            grip = 1.0
        elif ph == 6:
            target = eef
        else:
            target = np.array([eef[0], eef[1], carry_z])
        yaw = yaw_err if (align and yaw_err is not None) else 0.0
        d = np.linalg.norm(target - eef)
        state["t"] += 1
        t = state["t"]
        done = {
            0: (d < 0.01 and abs(yaw) < 0.05) or t > 60,
            1: d < 0.005 or t > 40,
            2: t >= 12,
            3: d < 0.02 or t > 40,
            4: d < 0.005 or t > 80,
            5: d < 0.01 or t > 50,
            6: t >= 12,
        }.get(ph, False)
        if done:
            state["phase"], state["t"] = ph + 1, 0
        return osc_action(eef, target, yaw, grip)

    return act


# Grasp heights above the objects' origins (below their tops), the heights of their origins
# above the bin floor when they rest (measured in robosuite), and the drop at release.
GROCERY_GRASP = {"Milk": 0.03, "Bread": 0.0, "Cereal": 0.0, "Can": 0.0}
GROCERY_REST = {"Milk": 0.061, "Bread": 0.022, "Cereal": 0.075, "Can": 0.040}
RELEASE_DROP = 0.005


def pick_place_policy(env, name):
    """Put grocery `name` into its quadrant of the goal bin."""
    i = env.object_to_id[name.lower()]
    # The corner of the object's quadrant nearest the robot, 6 cm inside (the centres of the
    # far quadrants stretch the arm to the end of its reach, where its posture is chaotic).
    centre = env.target_bin_placements[i]
    x_low, y_low = centre[0] - env.bin_size[0] / 4.0, centre[1] - env.bin_size[1] / 4.0
    goal = np.array([x_low + 0.06, y_low + 0.06])
    key = f"{name}_pos"
    act = place_policy(
        lambda obs: (np.asarray(obs[key]) + np.array([0, 0, GROCERY_GRASP[name]]), None),
        goal,
        carry_z=1.1,
        release_z=env.bin2_pos[2] + 0.02 + GROCERY_REST[name] + RELEASE_DROP,
    )
    return lambda obs: act(obs, np.asarray(obs[key]))


def nut_policy(env, name):
    """Grasp nut `name` by its handle with the fingers across it, carry its ring over its
    peg, lower it and let go."""
    i = env.nut_to_id[name.lower().replace("nut", "")]
    peg = env.sim.data.body_xpos[[env.peg1_body_id, env.peg2_body_id][i]]
    # Grasp point along the nut's x axis (the handles' centres are at 0.054 and 0.06).
    handle = 0.062 if i == 0 else 0.06
    key, quat_key = f"{name}_pos", f"{name}_quat"

    def grab(obs):
        nut = np.asarray(obs[key])
        yaw = yaw_of(obs[quat_key])
        point = nut + np.array([handle * np.cos(yaw), handle * np.sin(yaw), 0.002])
        return point, wrap(yaw + np.pi / 2 - finger_yaw(obs), np.pi)

    act = place_policy(grab, peg[:2].copy(), carry_z=1.02, release_z=0.84)
    return lambda obs: act(obs, np.asarray(obs[key]))


def base_frame(env, robot):
    """The rotation of robot `robot`'s base (OSC actions are in that frame)."""
    body = env.sim.model.body_name2id(env.robots[robot].robot_model.root_body)
    return np.array(env.sim.data.body_xmat[body]).reshape(3, 3)


def two_arm_lift_policy(env, lift_height=0.15):
    """Each arm (robot i's, or a bimanual robot's right then left) reaches 8 cm above handle
    i with its fingers across the handle's bar, descends onto it and closes; once both have
    closed, both lift. Deltas are turned into each robot's base frame."""
    import robosuite.utils.transform_utils as T

    bimanual = len(env.robots) == 1
    prefixes = ["robot0_right_", "robot0_left_"] if bimanual else ["robot0_", "robot1_"]
    frames = [base_frame(env, 0)] * 2 if bimanual else [base_frame(env, 0), base_frame(env, 1)]
    state = {"phase": [0, 0], "t": [0, 0], "start": None, "lift_t": 0}

    def arm(obs, i):
        eef = obs[f"{prefixes[i]}eef_pos"]
        handle = np.asarray(obs[f"handle{i}_xpos"])
        if state["start"] is None:
            state["start"] = [np.asarray(obs["handle0_xpos"]).copy(), np.asarray(obs["handle1_xpos"]).copy()]
        state["t"][i] += 1
        finger = T.quat2mat(obs[f"{prefixes[i]}eef_quat"])[:, 1]
        bar = T.quat2mat(obs["pot_quat"])[:, 0]
        err = wrap_angle(np.arctan2(bar[1], bar[0]) + np.pi / 2 - np.arctan2(finger[1], finger[0]))
        if abs(err) > np.pi / 2:
            err = wrap_angle(err + np.pi)
        phase, t = state["phase"][i], state["t"][i]
        grip, done = -1.0, False
        if phase == 0:
            target = handle + np.array([0, 0, 0.08])
            done = (np.linalg.norm(target - eef) < 0.01 and abs(err) < 0.05) or t > 40
        elif phase == 1:
            target = handle
            done = np.linalg.norm(target - eef) < 0.006 or t > 30
        elif phase == 2:
            target, grip, done = eef, 1.0, t > 10
        else:
            grip = 1.0
            target = eef if min(state["phase"]) < 3 else state["start"][i] + np.array([0, 0, lift_height])
        if done:
            state["phase"][i], state["t"][i] = phase + 1, 0
        a = np.zeros(7)
        a[:3] = frames[i].T @ toward(eef, target)
        a[5] = np.clip(err * 4.0, -1.0, 1.0) if phase < 2 else 0.0
        a[6] = grip
        return a

    def act(obs):
        a0, a1 = arm(obs, 0), arm(obs, 1)
        if bimanual:
            # robosuite's bimanual layout: right arm, left arm, right gripper, left gripper.
            return np.concatenate([a0[:6], a1[:6], a0[6:], a1[6:]])
        return np.concatenate([a0, a1])

    return act


def peg_approach_policy(env):
    """Robot 0 carries the peg's body toward the hole's centre (10 cm along the plate's x
    axis) while robot 1 holds still; deltas in robot 0's base frame."""
    import robosuite.utils.transform_utils as T

    frame = base_frame(env, 0)

    def act(obs):
        hole_x = T.quat2mat(obs["hole_quat"])[:, 0]
        goal = np.asarray(obs["peg_to_hole"]) + 0.1 * hole_x
        a = np.zeros(env.action_dim)
        a[:3] = frame.T @ np.clip(goal * 5.0, -1.0, 1.0)
        return a

    return act


def handover_policy(env):
    """Gripper 0 grasps the handle next to the head, lifts the hammer to the middle turning
    its head towards robot 0, gripper 1 grasps the handle's far end, gripper 0 lets go and
    rises. Deltas in each robot's base frame."""
    import robosuite.utils.transform_utils as T

    bimanual = len(env.robots) == 1
    pf = ["robot0_right_", "robot0_left_"] if bimanual else ["robot0_", "robot1_"]
    frames = [base_frame(env, 0)] * 2 if bimanual else [base_frame(env, 0), base_frame(env, 1)]
    st = {"phase": 0, "t": 0}
    def yaw_err(obs, i, axis):
        finger = T.quat2mat(obs[f"{pf[i]}eef_quat"])[:, 1]
        e = wrap_angle(np.arctan2(axis[1], axis[0]) + np.pi / 2 - np.arctan2(finger[1], finger[0]))
        if abs(e) > np.pi / 2:
            e = wrap_angle(e + np.pi)
        return e
    def act(obs):
        st["t"] += 1
        ph, t = st["phase"], st["t"]
        axis = T.quat2mat(obs["hammer_quat"])[:, 2]
        handle = np.asarray(obs["handle_xpos"])
        L = env.hammer.handle_length
        e0, e1 = obs[f"{pf[0]}eef_pos"], obs[f"{pf[1]}eef_pos"]
        g0 = handle + axis * (L / 2 - 0.02)   # arm 0 holds next to the head
        g1 = handle - axis * (L / 2 - 0.03)   # arm 1 takes the far end
        t0, t1 = e0, e1
        grip0, grip1, y0, y1, done = -1.0, -1.0, 0.0, 0.0, False
        meet = np.array([0.0, 0.0, 1.1])
        turn = wrap_angle(-np.pi / 2 - np.arctan2(axis[1], axis[0]))
        if ph == 0:
            t0 = g0 + np.array([0, 0, 0.08]); y0 = yaw_err(obs, 0, axis)
            done = (np.linalg.norm(t0 - e0) < 0.01 and abs(y0) < 0.05) or t > 40
        elif ph == 1:
            t0 = g0; y0 = yaw_err(obs, 0, axis); done = np.linalg.norm(t0 - e0) < 0.006 or t > 30
        elif ph == 2:
            grip0, done = 1.0, t > 10
        elif ph == 3:
            grip0 = 1.0; t0 = e0 + (meet - handle); y0 = turn
            done = (np.linalg.norm(meet - handle) < 0.01 and abs(turn) < 0.05) or t > 60
        elif ph == 4:
            grip0 = 1.0; t0 = e0 + (meet - handle)
            t1 = g1 + np.array([0, 0, 0.08]); y1 = yaw_err(obs, 1, axis)
            done = (np.linalg.norm(t1 - e1) < 0.01 and abs(y1) < 0.05) or t > 60
        elif ph == 5:
            grip0 = 1.0; t0 = e0 + (meet - handle)
            t1 = g1; y1 = yaw_err(obs, 1, axis); done = np.linalg.norm(t1 - e1) < 0.006 or t > 30
        elif ph == 6:
            grip0 = grip1 = 1.0; t0 = e0 + (meet - handle); done = t > 10
        elif ph == 7:
            grip1 = 1.0; done = t > 10
        else:
            grip1 = 1.0; t0 = e0 + np.array([0, 0, 0.1])
        if done:
            st["phase"], st["t"] = ph + 1, 0
        def one(i, tgt, yaw, grip):
            a = np.zeros(7); a[:3] = frames[i].T @ toward(obs[f"{pf[i]}eef_pos"], tgt); a[5] = np.clip(yaw * 4.0, -1, 1); a[6] = grip
            return a
        a0, a1 = one(0, t0, y0, grip0), one(1, t1, y1, grip1)
        return np.concatenate([a0, a1])
    return act


def transport_policy(env):
    """Gripper 0 grasps the lid's handle and lifts the lid; gripper 1 grasps the trash and
    lifts it (no yaw alignment). Deltas in each robot's base frame."""
    bimanual = len(env.robots) == 1
    pf = ["robot0_right_", "robot0_left_"] if bimanual else ["robot0_", "robot1_"]
    frames = [base_frame(env, 0)] * 2 if bimanual else [base_frame(env, 0), base_frame(env, 1)]
    keys = ["lid_handle_pos", "trash_pos"]
    state = {"phase": [0, 0], "t": [0, 0]}

    def arm(obs, i):
        eef, obj = obs[f"{pf[i]}eef_pos"], np.asarray(obs[keys[i]])
        state["t"][i] += 1
        phase, t = state["phase"][i], state["t"][i]
        grip, done = -1.0, False
        if phase == 0:
            target = obj + np.array([0, 0, 0.08])
            done = np.linalg.norm(target - eef) < 0.01 or t > 40
        elif phase == 1:
            target = obj
            done = np.linalg.norm(target - eef) < 0.006 or t > 30
        elif phase == 2:
            target, grip, done = eef, 1.0, t > 10
        else:
            target, grip = eef + np.array([0, 0, 0.05]), 1.0
        if done:
            state["phase"][i], state["t"][i] = phase + 1, 0
        a = np.zeros(7)
        a[:3] = frames[i].T @ toward(eef, target)
        a[6] = grip
        return a

    def act(obs):
        a0, a1 = arm(obs, 0), arm(obs, 1)
        if bimanual:
            return np.concatenate([a0[:6], a1[:6], a0[6:], a1[6:]])
        return np.concatenate([a0, a1])

    return act


def random_policy(seed, dim):
    rng = np.random.default_rng(seed)
    return lambda obs: rng.uniform(-1.0, 1.0, dim)


POLICIES = {
    "Lift": [("scripted", lambda env: pick_policy("cube_pos"), 80), ("random", lambda env: random_policy(7, env.action_dim), 60)],
    "Stack": [("scripted", lambda env: stack_policy(), 140), ("random", lambda env: random_policy(7, env.action_dim), 60)],
    "Door": [("scripted", door_policy, 130), ("random", lambda env: random_policy(7, env.action_dim), 60)],
    "Wipe": [("scripted", wipe_policy, 150), ("random", lambda env: random_policy(7, env.action_dim), 60)],
    "ToolHang": [("scripted", lambda env: bar_grasp_policy("tool"), 120), ("random", lambda env: random_policy(3, env.action_dim), 60)],
}


# Fixtures of other set-ups than robosuite's default: fixture name -> (task, robots, make
# keyword arguments). Every other fixture is the task with the --robot robot.
SETUPS = {
    "TwoArmLift": ("TwoArmLift", ["Panda", "Panda"], {"env_configuration": "opposed"}),
    "TwoArmLift-parallel": ("TwoArmLift", ["Panda", "Panda"], {"env_configuration": "parallel"}),
}
POLICIES["TwoArmLift"] = [("scripted", two_arm_lift_policy, 110), ("random", lambda env: random_policy(5, env.action_dim), 60)]
POLICIES["TwoArmLift-parallel"] = POLICIES["TwoArmLift"]
SETUPS["TwoArmPegInHole"] = ("TwoArmPegInHole", ["Panda", "Panda"], {"env_configuration": "opposed"})
SETUPS["TwoArmPegInHole-parallel"] = ("TwoArmPegInHole", ["Panda", "Panda"], {"env_configuration": "parallel"})
POLICIES["TwoArmPegInHole"] = [("scripted", peg_approach_policy, 80), ("random", lambda env: random_policy(9, env.action_dim), 60)]
POLICIES["TwoArmPegInHole-parallel"] = POLICIES["TwoArmPegInHole"]
SETUPS["TwoArmHandover"] = ("TwoArmHandover", ["Panda", "Panda"], {"env_configuration": "opposed"})
SETUPS["TwoArmHandover-parallel"] = ("TwoArmHandover", ["Panda", "Panda"], {"env_configuration": "parallel"})
POLICIES["TwoArmHandover"] = [("scripted", handover_policy, 215), ("random", lambda env: random_policy(3, env.action_dim), 60)]
POLICIES["TwoArmHandover-parallel"] = POLICIES["TwoArmHandover"]
SETUPS["TwoArmTransport"] = ("TwoArmTransport", ["Panda", "Panda"], {"env_configuration": "opposed"})
SETUPS["TwoArmTransport-parallel"] = ("TwoArmTransport", ["Panda", "Panda"], {"env_configuration": "parallel"})
POLICIES["TwoArmTransport"] = [("scripted", transport_policy, 120), ("random", lambda env: random_policy(17, env.action_dim), 60)]
POLICIES["TwoArmTransport-parallel"] = POLICIES["TwoArmTransport"]
# One bimanual Baxter (robosuite's "single-robot" set-up).
for _task in ["TwoArmLift", "TwoArmPegInHole", "TwoArmHandover", "TwoArmTransport"]:
    SETUPS[f"{_task}-Baxter"] = (_task, ["Baxter"], {})
    POLICIES[f"{_task}-Baxter"] = POLICIES[_task]


# Robots with a mobile base: their fixtures add a base-moving rollout.
MOBILE_ROBOTS = ["PandaOmron", "Tiago"]
# Tiago, one bimanual robot (robosuite's "single-robot" set-up).
for _task in ["TwoArmLift"]:
    SETUPS[f"{_task}-Tiago"] = (_task, ["Tiago"], {})
    POLICIES[f"{_task}-Tiago"] = [POLICIES[_task][1]]

# The Panda with Inspire hands: a right-hand and a left-hand Panda facing each other.
SETUPS["TwoArmLift-PandaDex"] = ("TwoArmLift", ["PandaDexRH", "PandaDexLH"], {"env_configuration": "opposed"})
POLICIES["TwoArmLift-PandaDex"] = [POLICIES["TwoArmLift"][1]]

# Two Spots facing each other (their leg bases are prefixed per robot, robosuite composes
# both); a PandaOmron with a Panda partner (two wheeled robots cannot share a scene in
# robosuite). Each adds its legs or base rollout (`record`).
SETUPS["TwoArmLift-SpotWithArm"] = ("TwoArmLift", ["SpotWithArm", "SpotWithArm"], {"env_configuration": "opposed"})
POLICIES["TwoArmLift-SpotWithArm"] = [POLICIES["TwoArmLift"][1]]
SETUPS["TwoArmLift-PandaOmron"] = ("TwoArmLift", ["PandaOmron", "Panda"], {"env_configuration": "opposed"})
POLICIES["TwoArmLift-PandaOmron"] = [POLICIES["TwoArmLift"][1]]
SETUPS["TwoArmLift-SpotWithArmFloating"] = ("TwoArmLift", ["SpotWithArmFloating", "SpotWithArmFloating"], {"env_configuration": "opposed"})
POLICIES["TwoArmLift-SpotWithArmFloating"] = [POLICIES["TwoArmLift"][1]]


# robosuite's GR1 humanoids, each with its default composite controller (GR1 and GR1ArmsOnly:
# WHOLE_BODY_IK, GR1FloatingBody: HYBRID_MOBILE_BASE), as one bimanual robot on TwoArmLift
# ("single-robot") and on Lift. The WHOLE_BODY_IK rollouts move the grip sites around their
# reset poses (`ik_policy`): random absolute targets send the IK anywhere.
GR1_ROBOTS = ["GR1", "GR1ArmsOnly", "GR1FloatingBody"]
MOBILE_ROBOTS.append("GR1FloatingBody")


def ik_policy(env, toggle=True):
    """Absolute grip-site targets (WHOLE_BODY_IK, in its input frame) circling each site's
    reset pose, the hands opening and closing, the other parts at rest."""
    from scipy.spatial.transform import Rotation

    robot = env.robots[0]
    cc = robot.composite_controller
    ik = cc.joint_action_policy
    m, d = env.sim.model._model, env.sim.data._data
    start = {}
    for site in ik.site_names:
        sid = m.site(site).id
        start[site] = (d.site_xpos[sid].copy(), Rotation.from_matrix(d.site_xmat[sid].reshape(3, 3)))
    frame = ik.input_ref_frame
    if frame != "world":
        bid = m.body("robot0_base" if frame == "base" else frame).id
        fp, fr = d.xpos[bid].copy(), Rotation.from_matrix(d.xmat[bid].reshape(3, 3))
    state = {"t": 0}

    def act(obs):
        t = state["t"]
        state["t"] += 1
        w = 2 * np.pi * t / 30.0
        action = np.zeros(env.action_dim)
        for i, site in enumerate(ik.site_names):
            p0, r0 = start[site]
            sign = 1.0 if i == 0 else -1.0
            p = p0 + np.array([0.08 * np.sin(w), sign * 0.06 * np.sin(2 * w), 0.05 * (1 - np.cos(w))])
            r = Rotation.from_rotvec([0.15 * np.sin(w), sign * 0.1 * np.sin(w), 0.2 * np.sin(w)]) * r0
            if frame != "world":
                p, r = fr.inv().apply(p - fp), fr.inv() * r
            action[6 * i : 6 * i + 6] = np.concatenate([p, r.as_rotvec()])
        for part, (a, b) in cc._whole_body_controller_action_split_indexes.items():
            if part.endswith("_gripper"):
                action[a:b] = 1.0 if toggle and (t // 10) % 2 else -1.0
        return np.round(action, 6)

    return act


def default_policy(env, seed):
    """WHOLE_BODY_IK robots: `ik_policy`; the others: seeded random actions."""
    if type(env.robots[0].composite_controller).__name__ == "WholeBodyIK":
        return ik_policy(env)
    return random_policy(seed, env.action_dim)


for _robot in GR1_ROBOTS:
    SETUPS[f"TwoArmLift-{_robot}"] = ("TwoArmLift", [_robot], {})
    POLICIES[f"TwoArmLift-{_robot}"] = [("random", lambda env: default_policy(env, 5), 60)]
for _robot in GR1_ROBOTS:
    SETUPS[f"Lift-{_robot}"] = ("Lift", _robot, {})
    POLICIES[f"Lift-{_robot}"] = [("random", lambda env: default_policy(env, 7), 60)]
# GR1FloatingBody's random rollout on Lift meets a knife-edge event at its 22nd step: robosuite
# on MuJoCo 3.3.7 and on 3.17 part there by 8.8e-3 rad in the left wrist from 1e-8 before,
# and by 3 rad later. Its first 20 steps are recorded (the base rollout runs 60).
POLICIES["Lift-GR1FloatingBody"] = [("random", lambda env: default_policy(env, 7), 20)]

# GR1FixedLowerBody: its default WHOLE_BODY_MINK_IK needs the `mink` library (robosuite-rs
# refuses it with a typed error), so its fixture drives it with robosuite's WHOLE_BODY_IK.
SETUPS["Lift-GR1FixedLowerBody"] = ("Lift", "GR1FixedLowerBody", {"composite_controller": "WHOLE_BODY_IK"})
POLICIES["Lift-GR1FixedLowerBody"] = [("random", lambda env: default_policy(env, 7), 60)]


# Baxter on Wipe: its scripted rollout stops before the arm's contact ends the episode
# (robosuite on MuJoCo 3.3.7 and 3.17 end it a few steps apart).
SETUPS["Wipe-Baxter"] = ("Wipe", "Baxter", {})
POLICIES["Wipe-Baxter"] = [("scripted", wipe_policy, 110), POLICIES["Wipe"][1]]


def scripted_and_random(scripted, steps, seed):
    """A task's rollouts: the scripted policy for `steps` steps, then 60 random actions."""
    return [("scripted", scripted, steps), ("random", lambda env: random_policy(seed, env.action_dim), 60)]


for _task, _obj in [("PickPlace", "Milk"), ("PickPlaceMilk", "Milk"), ("PickPlaceBread", "Bread"),
                    ("PickPlaceCereal", "Cereal"), ("PickPlaceCan", "Can")]:
    POLICIES[_task] = scripted_and_random(lambda env, o=_obj: pick_place_policy(env, o), 240, 11)
POLICIES["PickPlaceSingle"] = scripted_and_random(
    lambda env: pick_place_policy(env, env.objects[env.object_id].name), 240, 11)
for _task, _nut in [("NutAssembly", "RoundNut"), ("NutAssemblySquare", "SquareNut"), ("NutAssemblyRound", "RoundNut")]:
    POLICIES[_task] = scripted_and_random(lambda env, n=_nut: nut_policy(env, n), 200, 13)
POLICIES["NutAssemblySingle"] = scripted_and_random(lambda env: nut_policy(env, env.nuts[env.nut_id].name), 200, 13)


def for_robot(env, policy):
    """A single-arm policy's [arm (6), gripper (1)] actions in the layout of the robot's
    composite controller (robosuite's `create_action_vector`; other parts at rest, a
    HYBRID_MOBILE_BASE robot in arm mode, the grip command on every action of a dexterous
    hand), for robots whose action is not that layout. A bimanual robot's right arm follows
    the policy (which reads `robot0_eef_*` from the right arm's `robot0_right_eef_*`); its
    left arm holds still, its gripper open."""
    robot = env.robots[0]
    if env.action_dim == 7 and len(robot.arms) == 1:
        return policy
    bimanual = len(robot.arms) == 2

    def act(obs):
        if bimanual:
            obs = dict(obs)
            for k in ("eef_pos", "eef_quat"):
                obs[f"robot0_{k}"] = obs[f"robot0_right_{k}"]
        a = np.asarray(policy(obs), dtype=np.float64)
        parts = {"right": a[:6]}
        # A hand of several actions (the Inspire hands) gets the grip command on each.
        if bimanual:
            parts["left"] = np.zeros(6)
        for arm in robot.arms:
            dof = robot.gripper[arm].dof
            if dof > 0:
                parts[f"{arm}_gripper"] = np.repeat(a[6:7], dof) if arm == "right" else -np.ones(dof)
        return robot.create_action_vector(parts)

    return act


def base_policy(env, steps=60):
    """A mobile robot's base rollout: the base drives forward, sideways and turns while the
    torso rises, first in arm mode, then in base mode (HYBRID_MOBILE_BASE's last entry), and
    the arms hold still (every robot of the scene; a robot without a base holds still)."""
    state = {"t": 0}

    def robot_action(robot, t):
        torso = robot.part_controllers["torso"].control_dim if "torso" in robot.part_controllers else 0
        parts = {"base": np.array([0.6 * np.sin(t / 9.0), 0.3, 0.4 * np.cos(t / 7.0)])}
        if torso == 1:
            parts["torso"] = np.array([0.5])
        elif torso:
            parts["torso"] = np.full(torso, 0.2 * np.sin(t / 11.0))
        parts["base_mode"] = 1.0 if t > steps // 2 else -1.0
        return robot.create_action_vector(parts)

    def act(obs):
        state["t"] += 1
        return np.concatenate([robot_action(r, state["t"]) for r in env.robots])

    return act


# Legged robots: their fixtures add a rollout that moves the legs or the floating base.
LEGGED_ROBOTS = ["SpotWithArm", "SpotWithArmFloating"]


def legs_policy(env):
    """A legged robot's legs rollout: the leg joints sway about their rest positions
    (SpotWithArm's JOINT_POSITION legs), or the floating base drives forward, sideways and
    turns (SpotWithArmFloating's base); the arm holds still (every robot of the scene)."""
    state = {"t": 0}

    def act(obs):
        state["t"] += 1
        t = state["t"]
        parts = {
            "legs": 0.2 * np.sin(t / 6.0 + np.arange(12)),
            "base": np.array([0.6 * np.sin(t / 9.0), 0.3, 0.4 * np.cos(t / 7.0)]),
        }
        return np.concatenate([r.create_action_vector(parts) for r in env.robots])

    return act


def rollout(task, robot, seed, make_policy, steps, kwargs, kind=""):
    env = make(task, seed, robots=robot, **kwargs)
    obs = env.reset()
    record = {
        "task_state": task_state(task, env),
        "init_state": flat_state(env),
        "actions": [],
        "steps": [],
    }
    keys = obs_keys(task, obs)
    policy = make_policy(env)
    if kind == "scripted":
        policy = for_robot(env, policy)
    for _ in range(steps):
        action = np.asarray(policy(obs), dtype=np.float64)
        # Kept before the step: robosuite's mobile-base controller rotates its slice of the
        # action in place.
        record["actions"].append([float(x) for x in action])
        obs, reward, done, _ = env.step(action)
        record["steps"].append(
            {
                "obs": {
                    our_key(task, env, k): [short(x) for x in np.asarray(obs[k], dtype=np.float64).reshape(-1)]
                    for k in keys
                },
                "reward": float(reward),
                "success": bool(env._check_success()),
                "robot_contact": robot_touches(env),
            }
        )
        if done:
            break
    env.close()
    return record


def placement(task, robot, resets, kwargs):
    """Smallest and largest initial position of every object's root body over resets."""
    env = make(task, 1234, robots=robot, **kwargs)
    m = env.sim.model._model
    lo, hi = {}, {}
    for _ in range(resets):
        env.reset()
        d = env.sim.data._data
        objects = list(env.model.mujoco_objects)
        if task == "Wipe":
            # The markers' path starts uniformly in the covered area and ends a walk away.
            objects += [env.model.mujoco_arena.markers[0], env.model.mujoco_arena.markers[-1]]
        for obj in objects:
            bid = mujoco.mj_name2id(env.sim.model._model, mujoco.mjtObj.mjOBJ_BODY, obj.root_body)
            p = np.array(d.xpos[bid])
            name = obj.root_body
            lo[name] = np.minimum(lo.get(name, p), p)
            hi[name] = np.maximum(hi.get(name, p), p)
    env.close()
    del m
    return {"resets": resets, "bodies": {k: {"min": lo[k].tolist(), "max": hi[k].tolist()} for k in lo}}


def record(fixture, robot, out, resets):
    task, robot, kwargs = SETUPS.get(fixture, (fixture, robot, {}))
    env = make(task, 0, robots=robot, **kwargs)
    env.reset()
    counts, names = scene(env)
    env.close()
    data = {
        "task": task,
        "robot": robot if isinstance(robot, str) else robot[0],
        **({} if isinstance(robot, str) else {"robots": robot}),
        **({"kwargs": kwargs} if kwargs else {}),
        "robosuite": robosuite.__version__,
        "mujoco": mujoco.__version__,
        "counts": counts,
        "names": names,
        "rollouts": [],
        "placement": placement(task, robot, resets, kwargs),
    }
    policies = list(POLICIES[fixture])
    if (robot if isinstance(robot, str) else robot[0]) in MOBILE_ROBOTS:
        policies.append(("base", base_policy, 60))
    if (robot if isinstance(robot, str) else robot[0]) in LEGGED_ROBOTS:
        policies.append(("legs", legs_policy, 60))
    for i, (kind, make_policy, steps) in enumerate(policies):
        r = rollout(task, robot, 100 + i, make_policy, steps, kwargs, kind)
        r["kind"] = kind
        data["rollouts"].append(r)
    stem = fixture if fixture in SETUPS or robot == "Panda" else f"{task}-{robot}"
    path = os.path.join(out, f"{stem}.json")
    fixture_json.dump(data, path)
    n = sum(len(r["steps"]) for r in data["rollouts"])
    print(f"{stem}: {n} steps, {resets} resets -> {path} ({os.path.getsize(path) // 1024} KiB)")


# robosuite's single-arm tasks (every one takes a bimanual robot too).
SINGLE_ARM_TASKS = ["Lift", "Stack", "Door", "Wipe", "ToolHang"] + PICK_PLACE + NUT_ASSEMBLY


def observation_layouts(robot, out, every_task=False):
    """Adds `TASK-ROBOT` entries to observations.json: robosuite's action dimension and
    observation keys in order (with shapes and dtypes) for `robot` on every single-arm task
    (with `every_task`, on every registered task with `robot` alone), made with its defaults
    and reset (as the file's per-task entries)."""
    path = os.path.join(out, "observations.json")
    with open(path) as f:
        data = json.load(f)
    kwargs = {}
    if robot == "GR1FixedLowerBody":
        from robosuite.controllers import load_composite_controller_config

        kwargs["controller_configs"] = load_composite_controller_config(controller="WHOLE_BODY_IK", robot=robot)
    tasks = sorted(suite.ALL_ENVIRONMENTS) if every_task else SINGLE_ARM_TASKS
    for task in tasks:
        env = make(task, 0, robots=robot, **kwargs)
        obs = env.reset()
        data[f"{task}-{robot}"] = {
            "action_dim": int(env.action_dim),
            "env_configuration": env.env_configuration,
            "obs": [[k, list(np.asarray(v).shape), str(np.asarray(v).dtype)] for k, v in obs.items()],
        }
        env.close()
        print(f"{task}-{robot}: action_dim {env.action_dim}, {len(obs)} keys")
    # The file's layout: one observation key per line.
    entries = []
    for name, entry in data.items():
        keys = ",\n".join(f"      {json.dumps(k, separators=(', ', ': '))}" for k in entry["obs"])
        entries.append(
            f'  {json.dumps(name)}: {{\n    "action_dim": {entry["action_dim"]},\n'
            f'    "env_configuration": {json.dumps(entry["env_configuration"])},\n'
            f'    "obs": [\n{keys}\n    ]\n  }}'
        )
    with open(path, "w") as f:
        f.write("{\n" + ",\n".join(entries) + "\n}\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "..", "robosuite-env", "tests", "fixtures", "robosuite"))
    parser.add_argument("--resets", type=int, default=200)
    parser.add_argument("--robot", default="Panda")
    parser.add_argument("--layouts", action="store_true",
                        help="record the --robot robot's observation layouts on every single-arm task into observations.json")
    parser.add_argument("--every-task", action="store_true",
                        help="with --layouts: on all 19 registered tasks, the robot alone")
    parser.add_argument("tasks", nargs="*", default=list(POLICIES))
    args = parser.parse_args()
    if robosuite.__version__ != "1.5.2":
        sys.exit(f"record_robosuite: robosuite {robosuite.__version__} is installed, 1.5.2 is needed")
    os.makedirs(args.out, exist_ok=True)
    if args.layouts:
        observation_layouts(args.robot, args.out, args.every_task)
        return
    for task in args.tasks:
        if task not in POLICIES:
            sys.exit(f"record_robosuite: unknown task {task}; known: {', '.join(POLICIES)}")
        record(task, args.robot, args.out, args.resets)


if __name__ == "__main__":
    main()
