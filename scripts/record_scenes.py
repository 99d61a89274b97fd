#!/usr/bin/env python3
"""Record robosuite 1.5.2 scenes the way robomimic saves them, as test fixtures.

robomimic's `EnvRobosuite.get_state()` stores, per demonstration, the compiled scene as
`env.sim.model.get_xml()` (MuJoCo's `mj_saveLastXML`) next to the flattened sim states; a
replay calls `env.reset_from_xml_string(xml)` and `env.sim.set_state_from_flattened(s)`.
This script records such scenes from robosuite itself so that robosuite-rs's tests can load
them and compare observations. Per case (each of robosuite's 19 tasks with the Panda, two
Pandas in the default, i.e. opposed, configuration for the two-arm tasks, and Lift with each
of Sawyer, IIWA, Jaco, Kinova3, UR5e, XArm7 and PandaDexRH) it:

* seeds `np.random.seed(k)` and robosuite's own generator (`seed=k`; robosuite 1.5.2 draws
  placements and model parameters from `env.rng`, so without it no recording repeats), makes
  the env with robosuite's default composite controller for the robot, and calls `reset()`;
* saves `env.sim.model.get_xml()` and `env.get_ep_meta()`;
* takes 10 steps of seeded uniform random actions in [-1, 1] (`np.random.default_rng(k)`)
  and records, at reset and after every step, after an `env.sim.forward()` (robosuite's step
  leaves the kinematics one substep stale, which no replay from the state reproduces): the
  flattened state [time, qpos, qvel], `data.ctrl`, `env.reward(action)` (and the reward
  `step` returned), `_check_success()` and every numeric observation of
  `env._get_observations(force_update=True)` (its second pass on the state: see
  `numeric_obs`);
* writes robosuite-env/tests/fixtures/scenes/<Task>-<Robot>.xml.gz (the XML exactly as
  robosuite returned it, gzip level 9, mtime 0) and <Task>-<Robot>.json (schema in that
  folder's README.md). Two-arm tasks are named <Task>-Panda.

A second pass checks the recording against robosuite itself: a fresh env of the same case
is reset from the XML as robomimic's `reset_to` does (`reset()`, `edit_model_xml`,
`reset_from_xml_string`, `sim.reset()`), every recorded state (and ctrl) is set and
forwarded, and the largest absolute differences to the recorded observations and rewards,
success mismatches, and the bodies whose inertia the reloaded XML changed (mj_saveLastXML
drops the compiler's `inertiagrouprange`) are printed in a summary table. A case that
fails inside robosuite is reported there and no file is written for it.

It runs robosuite (and MuJoCo 3.3.7) from a scratch virtualenv and is not part of CI:

    python3 -m venv .bench-venv/robosuite
    .bench-venv/robosuite/bin/pip install robosuite==1.5.2 mujoco==3.3.7 h5py
    .bench-venv/robosuite/bin/python scripts/record_scenes.py [--out DIR] [--no-check] [CASE ...]

CASE is a file stem such as Lift-Panda or TwoArmLift-Panda (default: all 26). Reruns write
byte-identical files (the XML holds the virtualenv's absolute asset paths, so use the same
virtualenv path).
"""
import argparse
import gzip
import hashlib
import json
import math
import os
import sys

os.environ.setdefault("MUJOCO_GL", "disable")
if os.environ.get("PYTHONHASHSEED") != "0":
    # robosuite's single-object mode 1 (PickPlaceSingle, NutAssemblySingle) draws the object
    # from a set of names, whose order follows string hashing: fix it so that runs repeat.
    os.environ["PYTHONHASHSEED"] = "0"
    os.execv(sys.executable, [sys.executable] + sys.argv)

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import robosuite  # noqa: E402
from robosuite.controllers import load_composite_controller_config  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "robosuite-env", "tests", "fixtures", "scenes")
STEPS = 10

SINGLE_ARM = [
    "Lift", "Stack", "NutAssembly", "NutAssemblySingle", "NutAssemblySquare", "NutAssemblyRound",
    "PickPlace", "PickPlaceSingle", "PickPlaceMilk", "PickPlaceBread", "PickPlaceCereal",
    "PickPlaceCan", "Door", "Wipe", "ToolHang",
]
TWO_ARM = ["TwoArmLift", "TwoArmPegInHole", "TwoArmHandover", "TwoArmTransport"]
OTHER_ROBOTS = ["Sawyer", "IIWA", "Jaco", "Kinova3", "UR5e", "XArm7", "PandaDexRH"]

# (task, robot, seed): the seed is fixed per case (not its position in a run).
CASES = (
    [(t, "Panda", 100 + i) for i, t in enumerate(SINGLE_ARM)]
    + [(t, "Panda", 200 + i) for i, t in enumerate(TWO_ARM)]
    + [("Lift", r, 300 + i) for i, r in enumerate(OTHER_ROBOTS)]
)

COUNTS = ["nq", "nv", "nu", "nbody", "njnt", "ngeom", "nsite", "ncam", "nsensor"]
NAMES = {  # kind -> its count
    "body": "nbody",
    "joint": "njnt",
    "geom": "ngeom",
    "site": "nsite",
    "camera": "ncam",
    "actuator": "nu",
    "sensor": "nsensor",
}


def stem(task, robot):
    return f"{task}-{robot}"


def env_kwargs(task, robot, seed):
    """robosuite.make's arguments for a case (JSON-serialisable)."""
    two_arm = task in TWO_ARM
    kwargs = dict(
        robots=[robot, robot] if two_arm else robot,
        has_renderer=False,
        has_offscreen_renderer=False,
        use_camera_obs=False,
        ignore_done=True,
        use_object_obs=True,
        controller_configs=load_composite_controller_config(robot=robot),
        reward_shaping=True,
        seed=seed,
    )
    if two_arm:
        kwargs["env_configuration"] = "default"
    return kwargs


def make(task, robot, seed):
    np.random.seed(seed)
    kwargs = env_kwargs(task, robot, seed)
    return robosuite.make(task, **kwargs), kwargs


def floats(x):
    out = [float(v) for v in np.asarray(x, dtype=np.float64).ravel()]
    if not all(math.isfinite(v) for v in out):
        raise ValueError("non-finite value")
    return out


def numeric_obs(env):
    """Every numeric observation: {key: (dtype, shape, flat floats)} in robosuite's order.

    Two forced passes on the same state: robosuite's object-to-eef observables (PickPlace,
    NutAssembly, ToolHang: `{obj}_to_robot0_eef_pos/_quat`) are computed before `{obj}_pos`
    and `{obj}_quat` in a pass and read those from the observation cache, i.e. from the
    previous pass. After a first pass on the state, the second gives values that depend on
    the state alone."""
    env._get_observations(force_update=True)
    out = {}
    for k, v in env._get_observations(force_update=True).items():
        a = np.asarray(v)
        if a.dtype.kind not in "biuf":
            continue
        out[k] = (str(a.dtype), list(a.shape), floats(a))
    return out


def single_object(env):
    """PickPlace's / NutAssembly's object in play in single-object mode, else None. Neither
    the XML nor the state names it (the others are only moved out of the scene), and a
    reset from the XML draws it again."""
    mode = getattr(env, "single_object_mode", 0)
    if not mode:
        return None
    index = env.object_id if hasattr(env, "object_id") else env.nut_id
    return {"mode": int(mode), "name": str(env.obj_to_use), "id": int(index)}


def record(task, robot, seed):
    env, kwargs = make(task, robot, seed)
    env.reset()
    xml = env.sim.model.get_xml()
    ep_meta = env.get_ep_meta()
    m = env.sim.model
    counts = {c: int(getattr(m._model, c)) for c in COUNTS}
    # robosuite's id -> name maps (None for unnamed objects), in id order. (robosuite's
    # `body_names` etc. tuples are built from a name -> id dict, so all unnamed objects
    # collapse into one entry: they are neither complete nor in id order when a model has
    # several unnamed geoms, as PickPlace and NutAssembly do.)
    names = {k: [getattr(m, f"_{k}_id2name")[i] for i in range(counts[c])] for k, c in NAMES.items()}
    assert all(getattr(m, f"{k}_names") == tuple(n for n in names[k]) for k in names
               if None not in names[k]), "robosuite's name tuples disagree with its id maps"

    rng = np.random.default_rng(seed)
    states, ctrls, actions, rewards, step_rewards, successes, observations = [], [], [], [], [], [], []
    spec = {}

    def snapshot(action, step_reward):
        # robosuite's step ends on mj_step, which leaves the position-derived quantities
        # (xpos, site_xpos, sensors) one substep behind qpos: bring them up to date, as
        # robomimic's reset_to(state) does, so that the state alone reproduces what follows.
        # (An extra mj_forward does not change the trajectory: every substep starts with one.)
        env.sim.forward()
        states.append(floats(env.sim.get_state().flatten()))
        ctrls.append(floats(env.sim.data.ctrl))
        step_rewards.append(None if step_reward is None else float(step_reward))
        # In the order of robosuite's step: reward (Wipe's marks markers wiped), then
        # success, then observations.
        rewards.append(float(env.reward(action)))
        successes.append(bool(env._check_success()))
        obs = numeric_obs(env)
        for k, (dtype, shape, _) in obs.items():
            if k in spec and spec[k] != {"dtype": dtype, "shape": shape}:
                raise ValueError(f"observation {k} changed dtype/shape")
            spec.setdefault(k, {"dtype": dtype, "shape": shape})
        observations.append({k: v for k, (_, _, v) in obs.items()})

    snapshot(None, None)
    for _ in range(STEPS):
        action = rng.uniform(-1.0, 1.0, size=env.action_dim)
        actions.append(floats(action))
        _, reward, _, _ = env.step(action)
        snapshot(action, reward)

    name = stem(task, robot)
    xml_bytes = xml.encode("utf-8")
    doc = {
        "case": name,
        "task": task,
        "robots": kwargs["robots"] if isinstance(kwargs["robots"], list) else [kwargs["robots"]],
        "seed": seed,
        "env_kwargs": kwargs,
        "env_configuration": env.env_configuration,
        # TwoArmTransport has no shaped reward: robosuite turns reward_shaping off.
        "reward_shaping": bool(env.reward_shaping),
        "single_object": single_object(env),
        "versions": {"robosuite": robosuite.__version__, "mujoco": mujoco.__version__, "numpy": np.__version__},
        "xml": {"file": name + ".xml.gz", "sha256": hashlib.sha256(xml_bytes).hexdigest(), "bytes": len(xml_bytes)},
        "ep_meta": ep_meta,
        "counts": counts,
        "names": names,
        "action_dim": int(env.action_dim),
        "obs_spec": spec,
        "states": states,
        "ctrls": ctrls,
        "actions": actions,
        "rewards": rewards,
        "step_rewards": step_rewards,
        "successes": successes,
        "observations": observations,
    }
    # The compiled model's inertias, to compare with the model reloaded from the XML.
    inertia = np.concatenate([m.body_mass[:, None], m.body_inertia], axis=1).copy()
    env.close()
    return doc, xml_bytes, inertia


def write(out, doc, xml_bytes):
    os.makedirs(out, exist_ok=True)
    name = doc["case"]
    with open(os.path.join(out, name + ".xml.gz"), "wb") as f:
        f.write(gzip.compress(xml_bytes, compresslevel=9, mtime=0))
    with open(os.path.join(out, name + ".json"), "w") as f:
        json.dump(doc, f, indent=1, allow_nan=False)
        f.write("\n")


def check(doc, xml, inertia):
    """robosuite replaying its own recording, as robomimic's reset_to does. Returns the
    largest observation difference, its key, that without joint_acc, keys missing in the
    replay, the largest reward difference, the number of success mismatches, and the names of
    the bodies whose mass or inertia the reloaded model changed."""
    task, robot, seed = doc["task"], doc["robots"][0], doc["seed"]
    env, _ = make(task, robot, seed)
    env.reset()
    env.reset_from_xml_string(env.edit_model_xml(xml))
    env.sim.reset()
    m = env.sim.model
    reloaded = np.concatenate([m.body_mass[:, None], m.body_inertia], axis=1)
    changed = [m._body_id2name[i] or f"#{i}" for i in range(m.nbody)
               if not np.allclose(inertia[i], reloaded[i], rtol=1e-4, atol=1e-9)]
    worst, worst_key, missing = 0.0, "", set()
    # joint_acc is qacc, which also depends on the constraint solver's warm start (not in
    # the state): keep it (and the concatenations holding it) apart.
    worst_pos = 0.0
    d_reward, bad_success = 0.0, 0
    for i, s in enumerate(doc["states"]):
        env.sim.set_state_from_flattened(np.array(s))
        env.sim.data.ctrl[:] = doc["ctrls"][i]
        env.sim.forward()
        action = np.array(doc["actions"][i - 1]) if i > 0 else None
        d_reward = max(d_reward, abs(float(env.reward(action)) - doc["rewards"][i]))
        bad_success += bool(env._check_success()) != doc["successes"][i]
        obs = numeric_obs(env)
        for k, rec in doc["observations"][i].items():
            if k not in obs or len(obs[k][2]) != len(rec):
                missing.add(k)
                continue
            d = max((abs(a - b) for a, b in zip(obs[k][2], rec)), default=0.0)
            if d > worst:
                worst, worst_key = d, k
            if not (k.endswith("joint_acc") or k.endswith("-state")):
                worst_pos = max(worst_pos, d)
    env.close()
    return worst, worst_key, worst_pos, sorted(missing), d_reward, bad_success, changed


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--out", default=OUT)
    p.add_argument("--no-check", action="store_true", help="skip the replay check")
    p.add_argument("cases", nargs="*", help="file stems such as Lift-Panda (default: all)")
    args = p.parse_args()
    known = {stem(t, r): (t, r, s) for t, r, s in CASES}
    unknown = [c for c in args.cases if c not in known]
    if unknown:
        p.error(f"unknown case(s) {unknown}; known: {sorted(known)}")
    todo = [known[c] for c in args.cases] if args.cases else CASES

    rows = []
    for task, robot, seed in todo:
        name = stem(task, robot)
        try:
            doc, xml_bytes, inertia = record(task, robot, seed)
            write(args.out, doc, xml_bytes)
        except Exception as e:  # a failure inside robosuite: report it, write nothing
            rows.append((name, seed, None, f"recording failed: {type(e).__name__}: {e}"))
            print(f"{name}: recording failed: {type(e).__name__}: {e}", flush=True)
            continue
        size = (os.path.getsize(os.path.join(args.out, name + ".xml.gz")),
                os.path.getsize(os.path.join(args.out, name + ".json")))
        result = None
        if not args.no_check:
            try:
                result = check(doc, xml_bytes.decode("utf-8"), inertia)
            except Exception as e:
                rows.append((name, seed, size, f"check failed: {type(e).__name__}: {e}", doc))
                print(f"{name}: check failed: {type(e).__name__}: {e}", flush=True)
                continue
        rows.append((name, seed, size, result, doc))
        print(f"{name}: written" + (f", max |dobs| {result[0]:.3g} ({result[1]})" if result else ""), flush=True)

    print()
    print(f"{'case':28} {'seed':>4} {'nq':>4} {'nv':>4} {'nu':>3} {'obs keys':>8} {'xml.gz KB':>9} {'json KB':>8}"
          f" {'max|dobs|':>10} {'worst key':26} {'w/o acc':>9} {'max|drew|':>9} {'succ!=':>6}  notes")
    failed = 0
    for row in rows:
        name, seed, size = row[:3]
        if size is None:
            failed += 1
            print(f"{name:28} {seed:>4}  SKIPPED: {row[3]}")
            continue
        doc, result = row[4], row[3]
        c = doc["counts"]
        head = (f"{name:28} {seed:>4} {c['nq']:>4} {c['nv']:>4} {c['nu']:>3} {len(doc['obs_spec']):>8}"
                f" {size[0] / 1024:>9.1f} {size[1] / 1024:>8.1f}")
        if result is None:
            print(head + "  (not checked)")
        elif isinstance(result, str):
            failed += 1
            print(head + f"  {result}")
        else:
            worst, key, worst_pos, missing, d_rew, bad, changed = result
            note = f"keys not in replay: {missing}; " if missing else ""
            if changed:
                note += f"reload changes inertia of: {' '.join(changed)}"
            print(head + f" {worst:>10.3g} {key:26} {worst_pos:>9.3g} {d_rew:>9.3g} {bad:>6}  {note}")
    total = sum(os.path.getsize(os.path.join(args.out, f)) for f in os.listdir(args.out)) if os.path.isdir(args.out) else 0
    print(f"\n{len(rows) - failed}/{len(rows)} cases ok; {args.out}: {total / 1e6:.2f} MB")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
