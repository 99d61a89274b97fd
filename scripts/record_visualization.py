"""Records what robosuite 1.5.2's VisualizationWrapper, ``env.visualize`` and modders do,
for ``python/tests/test_visual_wrappers.py``:

* per task (Lift, TwoArmLift, Stack, Door, NutAssemblySquare, PickPlaceCan): the
  visualization settings, the sites each setting toggles (objects', robots',
  grippers'), the state after the wrapper's reset, each site's rgba after a sequence of
  ``env.visualize`` calls at that state (the grip site coloured by its distance to the
  target), the indicator sites the wrapper adds;
* Lift: 64x64 ``frontview`` / ``agentview`` frames (bottom row first) with every site
  hidden, with the default indicator at a known position, and with every site shown;
* the camera and lighting modders' draws for a seed, and the dynamics modder's
  perturbations (robosuite's ``DynamicsModder.randomize`` draws from NumPy's global RNG,
  seeded here with the same seed).

Run with robosuite's virtualenv (EGL for the frames):

    MUJOCO_GL=egl .bench-venv/robosuite/bin/python scripts/record_visualization.py

Output: ``python/tests/fixtures/robosuite_utils/visualization.json``.
"""

from __future__ import annotations

import base64
import json
import zlib
from pathlib import Path

import numpy as np
import robosuite as suite
from robosuite.utils.mjmod import CameraModder, DynamicsModder, LightingModder
from robosuite.wrappers import VisualizationWrapper

OUT = Path(__file__).resolve().parents[1] / "python/tests/fixtures/robosuite_utils/visualization.json"
SIZE = 64
CAMERAS = ["frontview", "agentview"]
FAR = [0.0, 0.0, -5.0]  # an indicator position out of every camera's view
INDICATOR_POS = [-0.05, 0.1, 1.0]
INDICATORS = [
    "default",
    {"name": "marker", "type": "box", "size": [0.02, 0.02, 0.02], "rgba": [0, 0, 1, 1], "pos": [0.1, -0.1, 1.0]},
]
SEQUENCE = [
    {"env": True, "robots": True, "grippers": True},
    {"env": True, "robots": False, "grippers": True},
    {"env": False, "robots": False, "grippers": False},
    {"env": False, "robots": True, "grippers": True},
]
SEED = 3


def lst(a) -> list:
    return np.asarray(a, dtype=np.float64).tolist()


def frame(env, camera: str) -> str:
    img = np.ascontiguousarray(env.sim.render(SIZE, SIZE, camera_name=camera), dtype=np.uint8)
    return base64.b64encode(zlib.compress(img.tobytes(), 9)).decode()


def site_rgba(env) -> dict[str, list]:
    m = env.sim.model
    return {m.site_id2name(i): lst(m.site_rgba[i]) for i in range(m.nsite)}


def record_task(name: str, **kwargs) -> dict:
    env = suite.make(
        name,
        has_renderer=False,
        has_offscreen_renderer=True,
        use_camera_obs=False,
        seed=0,
        **kwargs,
    )
    env = VisualizationWrapper(env, indicator_configs=INDICATORS)
    env.reset()
    m = env.sim.model
    out: dict = {
        "settings": sorted(env.get_visualization_settings()),
        "object_sites": [list(o.sites) for o in env.model.mujoco_objects],
        "robot_sites": [list(r.robot_model.sites) for r in env.robots],
        "gripper_sites": [{arm: list(r.gripper[arm].sites) for arm in r.arms} for r in env.robots],
        "indicator_names": env.get_indicator_names(),
        "indicators": {
            n: {
                "body_pos": lst(m.body_pos[m.body_name2id(n + "_body")]),
                "site_type": int(m.site_type[m.site_name2id(n)]),
                "site_size": lst(m.site_size[m.site_name2id(n)]),
                "site_rgba": lst(m.site_rgba[m.site_name2id(n)]),
            }
            for n in env.get_indicator_names()
        },
        "state": lst(env.sim.get_state().flatten()),
        "after_reset": site_rgba(env),
        "sequence": [],
    }
    for settings in SEQUENCE:
        env.env.visualize(vis_settings=settings)
        out["sequence"].append(site_rgba(env))
    if name == "Lift":
        frames = {}
        env.set_indicator_pos("marker", FAR)
        for label, settings, pos in [
            ("hidden", {"env": False, "robots": False, "grippers": False}, FAR),
            ("indicator", {"env": False, "robots": False, "grippers": False}, INDICATOR_POS),
            ("shown", {"env": True, "robots": True, "grippers": True}, FAR),
        ]:
            env.env.visualize(vis_settings=settings)
            env.set_indicator_pos("indicator0", pos)
            env.sim.forward()
            frames[label] = {c: frame(env, c) for c in CAMERAS}
        out["frames"] = frames
        out["far"] = FAR
        out["indicator_pos"] = INDICATOR_POS
    env.close()
    return out


def record_modders() -> dict:
    env = suite.make("Lift", robots="Panda", has_renderer=False, has_offscreen_renderer=False, use_camera_obs=False)
    env.reset()
    sim, m = env.sim, env.sim.model
    cams = CameraModder(sim, random_state=np.random.RandomState(SEED))
    cams.randomize()
    lights = LightingModder(sim, random_state=np.random.RandomState(SEED))
    lights.randomize()
    out = {
        "seed": SEED,
        "camera": {n: {"pos": lst(cams.get_pos(n)), "quat": lst(cams.get_quat(n)), "fovy": float(cams.get_fovy(n))}
                   for n in cams.camera_names},
        "camera_defaults": {n: {k: lst(v) for k, v in d.items()} for n, d in cams._defaults.items()},
        "light": {
            n: {
                "pos": lst(lights.get_pos(n)),
                "dir": lst(lights.get_dir(n)),
                "specular": lst(lights.get_specular(n)),
                "ambient": lst(lights.get_ambient(n)),
                "diffuse": lst(lights.get_diffuse(n)),
                "active": int(lights.get_active(n)),
            }
            for n in lights.light_names
        },
        "light_defaults": {n: {k: lst(v) for k, v in d.items()} for n, d in lights._defaults.items()},
    }
    cams.restore_defaults()
    lights.restore_defaults()
    # DynamicsModder.randomize draws from NumPy's global RNG (not its random_state).
    dyn = DynamicsModder(sim, random_state=np.random.RandomState(SEED))
    np.random.seed(SEED)
    dyn.randomize()
    groups = {"body": [], "geom": [], "joint": []}
    for n in dyn.body_names:
        i = m.body_name2id(n)
        groups["body"].append(
            [n, lst(m.body_pos[i]), lst(m.body_quat[i]), lst(m.body_inertia[i]), float(m.body_mass[i])]
        )
    for n in dyn.geom_names:
        i = m.geom_name2id(n)
        groups["geom"].append([n, lst(m.geom_friction[i]), lst(m.geom_solref[i]), lst(m.geom_solimp[i])])
    for n in dyn.joint_names:
        i = m.joint_name2id(n)
        dofs = [k for k, v in enumerate(m.dof_jntid) if v == i]
        groups["joint"].append(
            [n, float(m.jnt_stiffness[i]), lst(m.dof_frictionloss[dofs]), lst(m.dof_damping[dofs]),
             lst(m.dof_armature[dofs])]
        )
    defaults = {
        "body": {n: [lst(d["position"]), lst(d["quaternion"]), lst(d["inertia"]), float(d["mass"])]
                 for n, d in dyn.body_defaults.items()},
        "geom": {n: [lst(d["friction"]), lst(d["solref"]), lst(d["solimp"])] for n, d in dyn.geom_defaults.items()},
        "joint": {n: [float(d["stiffness"]), lst(d["frictionloss"]), lst(d["damping"]), lst(d["armature"])]
                  for n, d in dyn.joint_defaults.items()},
    }
    out["dynamics"] = {
        "density": float(m.opt.density),
        "viscosity": float(m.opt.viscosity),
        "after": groups,
        "defaults": defaults,
    }
    env.close()
    return out


def main() -> None:
    data = {
        "robosuite": suite.__version__,
        "size": SIZE,
        "cameras": CAMERAS,
        "tasks": {
            "Lift": record_task("Lift", robots="Panda"),
            "TwoArmLift": record_task("TwoArmLift", robots=["Panda", "Panda"]),
            "Stack": record_task("Stack", robots="Panda"),
            "Door": record_task("Door", robots="Panda"),
            "NutAssemblySquare": record_task("NutAssemblySquare", robots="Panda"),
            "PickPlaceCan": record_task("PickPlaceCan", robots="Panda"),
        },
        "modders": record_modders(),
    }
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(json.dumps(data, separators=(",", ":")))
    print(f"wrote {OUT} ({OUT.stat().st_size} bytes)")


if __name__ == "__main__":
    main()
