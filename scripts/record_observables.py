#!/usr/bin/env python3
"""Record robosuite 1.5.2's observations with modified observables, as a test fixture
(python/tests/fixtures/observables/lift_observables.json, replayed by
python/tests/test_observables.py).

The run, on Lift with the Panda, is a list of operations (stored in the fixture, so that the
replay performs the same ones):

* ``modify``: ``env.modify_observable(name, attribute, value)`` where a corrupter, filter or
  delayer is described as data (``{"deterministic_corrupter": [c, low, high]}``,
  ``{"scale_filter": k}``, ``{"deterministic_delayer": d}``);
* ``reset_from_xml``: ``env.reset_from_xml_string`` of the scene robosuite saved in
  robosuite-env/tests/fixtures/scenes/Lift-Panda.xml.gz (so both sides start from the same
  cube), then the flat state ``env.sim.get_state().flatten()`` is recorded;
* ``step``: ``env.step(action)`` with a fixed action;
* ``force_update``: ``env._get_observations(force_update=True)`` (robosuite then samples one
  substep earlier on later steps).

After ``reset_from_xml``, ``step`` and ``force_update`` the observation dict is recorded
(every key: dtype, shape, values) with the number of robosuite's "sampling rate ... too low"
warnings printed during the operation, and after every step the flat state.

It runs robosuite (and MuJoCo 3.3.7) from the scratch virtualenv and is not part of CI:

    .bench-venv/robosuite/bin/python scripts/record_observables.py [--out FILE]
"""

import argparse
import contextlib
import gzip
import io
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fixture_json  # noqa: E402  (scripts/fixture_json.py: the fixtures' layout)

os.environ.setdefault("MUJOCO_GL", "disable")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import robosuite  # noqa: E402
from robosuite.controllers import load_composite_controller_config  # noqa: E402
from robosuite.utils import observables as O  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join("robosuite-env", "tests", "fixtures", "scenes", "Lift-Panda.xml.gz")
OUT = os.path.join(ROOT, "python", "tests", "fixtures", "observables", "lift_observables.json")


def actions(n):
    """Small arm moves in free space (OSC deltas), gripper input 0 (its fingers stay put: their
    contact with the joint limits is where MuJoCo versions differ most)."""
    rng = np.random.default_rng(7)
    return [[round(float(v), 6) for v in 0.3 * rng.uniform(-1.0, 1.0, 6)] + [0.0] for _ in range(n)]


def operations():
    acts = iter(actions(16))
    ops = [
        # robosuite's example settings: a fast, delayed joint sensor ...
        {"op": "modify", "name": "robot0_joint_pos", "attribute": "sampling_rate", "value": 100},
        {"op": "modify", "name": "robot0_joint_pos", "attribute": "delayer", "value": {"deterministic_delayer": 0.01}},
        # ... a corrupted (and clipped), then filtered end-effector position ...
        {"op": "modify", "name": "robot0_eef_pos", "attribute": "corrupter",
         "value": {"deterministic_corrupter": [0.01, -math.inf, 1.0]}},
        {"op": "modify", "name": "robot0_eef_pos", "attribute": "filter", "value": {"scale_filter": 2.0}},
        # ... a slow one, and one sampled at 50 Hz with a delay it can keep
        {"op": "modify", "name": "robot0_joint_vel", "attribute": "sampling_rate", "value": 10},
        {"op": "modify", "name": "robot0_gripper_qpos", "attribute": "sampling_rate", "value": 50},
        {"op": "modify", "name": "robot0_gripper_qpos", "attribute": "delayer", "value": {"deterministic_delayer": 0.006}},
        {"op": "reset_from_xml"},
    ]
    ops += [{"op": "step", "action": next(acts)} for _ in range(6)]
    ops += [{"op": "force_update"}]
    ops += [{"op": "step", "action": next(acts)} for _ in range(4)]
    ops += [
        {"op": "modify", "name": "robot0_eef_quat", "attribute": "enabled", "value": False},
        {"op": "modify", "name": "cube_quat", "attribute": "active", "value": False},
        {"op": "step", "action": next(acts)},
        {"op": "modify", "name": "robot0_eef_quat", "attribute": "enabled", "value": True},
    ]
    ops += [{"op": "step", "action": next(acts)} for _ in range(3)]
    return ops


def function(value):
    """A corrupter / filter / delayer described as data (the replay builds the same)."""
    if not isinstance(value, dict):
        return value
    (kind, arg), = value.items()
    if kind == "deterministic_corrupter":
        return O.create_deterministic_corrupter(arg[0], low=arg[1], high=arg[2])
    if kind == "deterministic_delayer":
        return O.create_deterministic_delayer(arg)
    if kind == "scale_filter":
        return lambda x: arg * np.asarray(x)
    raise ValueError(kind)


def encode(obs):
    out = {}
    for key, value in obs.items():
        a = np.asarray(value)
        vals = [float(v) if a.dtype.kind == "f" else v.item() for v in a.ravel()]
        out[key] = {"dtype": str(a.dtype), "shape": list(a.shape), "values": vals}
    return out


def jsonable(ops):
    """inf as a string (JSON has none)."""
    def fix(x):
        if isinstance(x, float) and math.isinf(x):
            return "inf" if x > 0 else "-inf"
        if isinstance(x, list):
            return [fix(v) for v in x]
        if isinstance(x, dict):
            return {k: fix(v) for k, v in x.items()}
        return x
    return fix(ops)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--out", default=OUT)
    args = p.parse_args()
    scene = json.load(open(os.path.join(ROOT, SCENE.replace(".xml.gz", ".json"))))
    kwargs = dict(scene["env_kwargs"])
    kwargs["controller_configs"] = load_composite_controller_config(robot="Panda")
    np.random.seed(0)
    env = robosuite.make("Lift", **kwargs)
    env.reset()
    xml = gzip.decompress(open(os.path.join(ROOT, SCENE), "rb").read()).decode()
    records = []
    for op in operations():
        buf = io.StringIO()
        rec = {}
        with contextlib.redirect_stdout(buf):
            if op["op"] == "modify":
                env.modify_observable(op["name"], op["attribute"], function(op["value"]))
            elif op["op"] == "reset_from_xml":
                env.reset_from_xml_string(xml)
                rec["state"] = [float(v) for v in env.sim.get_state().flatten()]
                rec["obs"] = encode(env._get_observations())
            elif op["op"] == "step":
                obs, reward, done, info = env.step(np.array(op["action"]))
                rec["obs"] = encode(obs)
                rec["reward"] = float(reward)
                rec["state"] = [float(v) for v in env.sim.get_state().flatten()]
            elif op["op"] == "force_update":
                rec["obs"] = encode(env._get_observations(force_update=True))
        rec["warnings"] = buf.getvalue().count("Warning: sampling rate")
        records.append(rec)
    fixture = {
        "about": "robosuite 1.5.2 observations with modified observables; see scripts/record_observables.py",
        "versions": {"robosuite": robosuite.__version__, "mujoco": mujoco.__version__, "numpy": np.__version__},
        "task": "Lift",
        "env_kwargs": {k: v for k, v in scene["env_kwargs"].items() if k != "controller_configs"},
        "scene": SCENE,
        "operations": jsonable(operations()),
        "records": records,
    }
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    fixture_json.dump(fixture, args.out)
    print(f"wrote {args.out}: {len(records)} operations, warnings {sum(r['warnings'] for r in records)}")


if __name__ == "__main__":
    main()
