#!/usr/bin/env python3
"""Run robomimic's own robosuite wrapper (`robomimic.envs.env_robosuite.EnvRobosuite`, and
the parts of `robomimic/scripts/dataset_states_to_obs.py` and `playback_dataset.py` that
drive it) UNCHANGED on robosuite-rs, through `robosuite_rs.install_as_robosuite()`.

Nothing of robomimic is copied here: robomimic is imported from a scratch virtualenv (not
part of CI) in which the real robosuite is NOT installed:

    python3.11 -m venv .bench-venv/robomimic
    .bench-venv/robomimic/bin/pip install numpy gymnasium mujoco==3.17.0 h5py torch torchvision \
        tqdm termcolor psutil imageio imageio-ffmpeg matplotlib six \
        huggingface_hub==0.23.4 diffusers==0.11.1 cmake
    CMAKE_POLICY_VERSION_MINIMUM=3.5 .bench-venv/robomimic/bin/pip install --no-build-isolation egl_probe
    .bench-venv/robomimic/bin/pip install --no-deps -e <robomimic checkout>
    echo "$PWD/python" > .bench-venv/robomimic/lib/python3.11/site-packages/robosuite_rs_path.pth
    .bench-venv/robomimic/bin/python scripts/check_robomimic.py [--case Lift-Panda] [--no-images]

Every call prints one line `PASS|FAIL|INFO <call>: <detail>`; the exit status is the number
of FAILs (capped at 100). The recorded values come from robosuite 1.5.2 itself
(robosuite-env/tests/fixtures/scenes/<case>.json, a scene XML saved on another machine with
`env.sim.model.get_xml()` plus the states, observations, shaped rewards and successes
robosuite computed on it), so the comparisons say whether robomimic sees robosuite's numbers.
"""
from __future__ import annotations

import argparse
import copy
import gzip
import json
import sys
import tempfile
import traceback
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
SCENES = ROOT / "robosuite-env" / "tests" / "fixtures" / "scenes"

FAILS: list[str] = []


def report(status: str, name: str, detail: str = "") -> None:
    if status == "FAIL":
        FAILS.append(name)
    print(f"{status} {name}{': ' + detail if detail else ''}", flush=True)


def call(name: str, fn, *args, verbose: bool = False, **kwargs):
    """Runs fn; PASS with a short description of the result, FAIL with the exception."""
    try:
        out = fn(*args, **kwargs)
    except Exception as e:  # noqa: BLE001 - every failure is the finding
        tb = traceback.extract_tb(e.__traceback__)
        where = f" [{Path(tb[-1].filename).name}:{tb[-1].lineno}]" if tb else ""
        report("FAIL", name, f"{type(e).__name__}: {e}{where}")
        if verbose:
            traceback.print_exc()
        return None
    report("PASS", name, describe(out))
    return out


def describe(x) -> str:
    if x is None:
        return "None"
    if isinstance(x, np.ndarray):
        return f"ndarray{x.shape} {x.dtype}"
    if isinstance(x, dict):
        keys = list(x)
        return f"dict({len(keys)} keys: {', '.join(map(str, keys[:8]))}{', ...' if len(keys) > 8 else ''})"
    if isinstance(x, tuple):
        return "(" + ", ".join(describe(v) for v in x) + ")"
    s = repr(x)
    return s if len(s) < 100 else s[:97] + "..."


def expect(name: str, ok: bool, detail: str) -> None:
    report("PASS" if ok else "FAIL", name, detail)


# --------------------------------------------------------------------------------------
# env_meta as robomimic's robosuite-1.5 datasets store it (data.attrs["env_args"])
# --------------------------------------------------------------------------------------
def legacy_keyed(cfg: dict) -> dict:
    """The composite config as robomimic's converted v1.5 datasets (HF `v1.5/*`) store it:
    the OSC arm config still under robosuite <=1.4 key names (`damping`, `damping_limits`,
    `control_delta`) and `input_ref_frame="world"`. robosuite 1.5's OSC takes **kwargs and
    silently ignores the old names (its defaults are the same values)."""
    cfg = copy.deepcopy(cfg)
    right = cfg["body_parts"]["right"]
    right["damping"] = right.pop("damping_ratio", 1)
    right["damping_limits"] = right.pop("damping_ratio_limits", [0, 10])
    right.pop("input_type", None)
    right["control_delta"] = True
    right["input_ref_frame"] = "world"
    return cfg


def env_meta_for(robosuite, case: dict, cameras: list[str], style: str) -> dict:
    """`style`: "serialize" = what `EnvRobosuite.serialize()` writes with robosuite 1.5.2
    (dataset_states_to_obs.py stores that as env_args; robomimic adds render_gpu_device_id
    on a machine where egl_probe finds an EGL device); "hf_v15" = the shape of robomimic's
    released robosuite-1.5 datasets (hard_reset, lite_physics, legacy controller keys)."""
    robots = case["robots"]
    cfg = robosuite.load_composite_controller_config(robot=robots[0])
    kwargs = dict(
        has_renderer=False,
        has_offscreen_renderer=bool(cameras),
        ignore_done=True,
        use_object_obs=True,
        use_camera_obs=bool(cameras),
        control_freq=20,
        controller_configs=cfg,
        robots=list(robots),
        camera_depths=False,
        camera_heights=84,
        camera_widths=84,
        reward_shaping=case.get("reward_shaping", True),
    )
    if cameras:
        kwargs["camera_names"] = list(cameras)
    if case.get("env_configuration", "default") != "default":
        kwargs["env_configuration"] = case["env_configuration"]
    if style == "hf_v15":
        kwargs["controller_configs"] = legacy_keyed(cfg)
        kwargs["hard_reset"] = False
        kwargs["lite_physics"] = False
        if len(robots) == 2:
            kwargs["env_configuration"] = "single-arm-opposed"
    return dict(env_name=case["task"], env_version="1.5.2", type=1, env_kwargs=kwargs)


# --------------------------------------------------------------------------------------
def max_obs_diff(obs: dict, recorded: dict, with_object: bool = True) -> tuple[float, str, list[str]]:
    """Largest |diff| between robomimic's observation dict and robosuite's recorded raw
    observations, over what robomimic keeps: `object` (robosuite's `object-state`) and the
    robot-prefixed keys but `*proprio-state`. `*joint_acc` is left out: it is `data.qacc`,
    which depends on `data.ctrl`, and robomimic's `reset_to` restores no ctrl (in robosuite
    neither).

    The recording holds robosuite's SECOND observation pass on each state: PickPlace,
    NutAssembly and ToolHang's `{obj}_to_robot0_eef_*` (part of `object`) read `{obj}_pos`
    from robosuite's observable cache, i.e. from the previous pass. robomimic's `reset_to`
    makes one pass, so its `object` carries that staleness (in robosuite too: robosuite-rs
    reproduces it, see the INFO lines); `with_object=False` leaves `object` out for it."""
    worst, worst_key, missing = 0.0, "", []
    for k, v in recorded.items():
        if k == "object-state":
            if not with_object:
                continue
            k_obs = "object"
        elif k.startswith("robot") and not k.endswith(("proprio-state", "joint_acc")):
            k_obs = k
        else:
            continue
        if k_obs not in obs:
            missing.append(k_obs)
            continue
        a, b = np.asarray(obs[k_obs], dtype=np.float64).ravel(), np.asarray(v, dtype=np.float64).ravel()
        if a.shape != b.shape:
            missing.append(f"{k_obs}(shape {a.shape} vs {b.shape})")
            continue
        d = float(np.max(np.abs(a - b))) if a.size else 0.0
        if d > worst:
            worst, worst_key = d, k_obs
    return worst, worst_key, missing


def check_env(EnvUtils, ObsUtils, robosuite, case, xml, label, env_meta, use_images, cameras, tol):
    print(f"\n=== {label} ===", flush=True)
    meta = copy.deepcopy(env_meta)
    env = call(
        f"[{label}] EnvUtils.create_env_from_metadata",
        EnvUtils.create_env_from_metadata,
        env_meta=meta,
        render=False,
        render_offscreen=use_images,
        use_image_obs=use_images,
        verbose=True,
    )
    if env is None:
        return None
    call(f"[{label}] env.action_dimension", lambda: env.action_dimension)
    call(f"[{label}] env.name / type / version", lambda: (env.name, env.type, env.version))
    call(f"[{label}] repr(env)", lambda: len(repr(env)))
    obs = call(f"[{label}] env.reset()", env.reset)
    if obs is not None and use_images:
        for cam in cameras:
            k = f"{cam}_image"
            expect(f"[{label}] reset obs {k}", k in obs and obs[k].shape == (84, 84, 3) and obs[k].dtype == np.uint8,
                   describe(obs.get(k)))
    st = call(f"[{label}] env.get_state()", env.get_state)
    if st is not None:
        expect(f"[{label}] get_state() keys", set(st) >= {"model", "states", "ep_meta"}, str(sorted(st)))
        call(f"[{label}] env.reset_to({{'states': s}}) (own state)", env.reset_to, {"states": st["states"]})
        call(f"[{label}] env.reset_to(get_state()) (own xml round trip)", env.reset_to, copy.deepcopy(st))

    # scene saved by robosuite 1.5.2 on another machine + robosuite's states
    states = np.asarray(case["states"], dtype=np.float64)
    initial = {"model": xml, "states": states[0], "ep_meta": json.dumps(case.get("ep_meta", {}))}
    obs0 = call(f"[{label}] env.reset_to({{model: robosuite xml, states, ep_meta}})", env.reset_to, initial, verbose=True)
    if obs0 is not None:
        d, k, missing = max_obs_diff(obs0, case["observations"][0], with_object=False)
        expect(f"[{label}] robot obs after reset_to(model) == robosuite's", d <= tol and not missing,
               f"max |diff| {d:.2e} ({k}); missing {missing}")
        d, k, missing = max_obs_diff(env.get_observation(), case["observations"][0])
        expect(f"[{label}] get_observation() after reset_to(model) == robosuite's (object incl.)",
               d <= tol and not missing, f"max |diff| {d:.2e} ({k}); missing {missing}")
        call(f"[{label}] env.get_ep_meta() after reset_to", env.env.get_ep_meta)
        s_now = env.get_state()["states"]
        expect(f"[{label}] get_state()['states'] == loaded state", np.allclose(s_now, states[0], atol=1e-12),
               f"max |diff| {np.max(np.abs(s_now - states[0])):.2e}")

    # every recorded state: observation, reward (shaped, robosuite's), success
    worst, worst_r, bad_succ, fails = 0.0, 0.0, 0, []
    for t, s in enumerate(states):
        try:
            o = env.reset_to({"states": s})
            d1 = max_obs_diff(o, case["observations"][t], with_object=False)[0]
            d, k, missing = max_obs_diff(env.get_observation(), case["observations"][t])
            worst = max(worst, d, d1)
            if missing:
                fails.append(f"t={t} missing {missing}")
            r = env.get_reward()
            if env_meta["env_kwargs"].get("reward_shaping"):
                worst_r = max(worst_r, abs(r - case["rewards"][t]))
            succ = env.is_success()
            if bool(succ["task"]) != bool(case["successes"][t]):
                bad_succ += 1
        except Exception as e:  # noqa: BLE001
            fails.append(f"t={t} {type(e).__name__}: {e}")
            break
    expect(f"[{label}] reset_to(states[t]) + get_observation() x{len(states)}: obs/reward/success == robosuite's",
           not fails and worst <= tol and worst_r <= tol and bad_succ == 0,
           f"obs max {worst:.2e}, reward max {worst_r:.2e}, success mismatches {bad_succ}; {fails[:2]}")
    call(f"[{label}] env.get_reward()", env.get_reward)
    call(f"[{label}] env.is_success()", env.is_success)
    call(f"[{label}] env.is_done()", env.is_done)
    call(f"[{label}] env.get_observation()", env.get_observation)

    # step from a recorded state with robosuite's recorded action
    actions = np.asarray(case["actions"], dtype=np.float64)
    env.reset_to({"states": states[0]})
    out = call(f"[{label}] env.step(action)", env.step, actions[0])
    if out is not None:
        o, r, done, info = out
        expect(f"[{label}] step() returns (obs, r, done, info['is_success'])",
               isinstance(o, dict) and "is_success" in info and done is False, f"r={r:.4f} info={info}")
        dev = float(np.max(np.abs(env.get_state()["states"] - states[1])))
        report("INFO", f"[{label}] state after step vs robosuite's recorded", f"max |diff| {dev:.2e}")

    # rendering (robomimic flips rows: sim.render is OpenGL bottom-first)
    img = call(f"[{label}] env.render(mode='rgb_array', 84, 84, 'agentview')", env.render,
               mode="rgb_array", height=84, width=84, camera_name="agentview")
    if img is not None:
        expect(f"[{label}] render image", img.shape == (84, 84, 3) and img.dtype == np.uint8 and img.std() > 0,
               f"{img.shape} {img.dtype} std={img.std():.1f}")
    call(f"[{label}] env.render(mode='rgb_array', 512, 512) default camera", env.render, mode="rgb_array", height=512, width=512)

    # camera matrices (robomimic's own + robosuite.utils.camera_utils)
    import robosuite.utils.camera_utils as CU

    for cam in ["agentview", "robot0_eye_in_hand"]:
        K = call(f"[{label}] env.get_camera_intrinsic_matrix({cam})", env.get_camera_intrinsic_matrix, cam, 84, 84)
        R = call(f"[{label}] env.get_camera_extrinsic_matrix({cam})", env.get_camera_extrinsic_matrix, cam)
        P = call(f"[{label}] env.get_camera_transform_matrix({cam})", env.get_camera_transform_matrix, cam, 84, 84)
        try:
            sim = env.env.sim
            K2 = CU.get_camera_intrinsic_matrix(sim, cam, 84, 84)
            R2 = CU.get_camera_extrinsic_matrix(sim, cam)
            P2 = CU.get_camera_transform_matrix(sim, cam, 84, 84)
            ok = K is not None and R is not None and P is not None and np.allclose(K, K2) and np.allclose(R, R2) and np.allclose(P, P2)
            expect(f"[{label}] robosuite.utils.camera_utils({cam}) == robomimic's matrices", ok, "")
        except Exception as e:  # noqa: BLE001
            report("FAIL", f"[{label}] robosuite.utils.camera_utils({cam})", f"{type(e).__name__}: {e}")

    ser = call(f"[{label}] env.serialize()", env.serialize)
    if ser is not None:
        try:
            json.dumps(ser)
            report("PASS", f"[{label}] json.dumps(serialize())")
        except Exception as e:  # noqa: BLE001
            report("FAIL", f"[{label}] json.dumps(serialize())", f"{type(e).__name__}: {e}")
        # a checkpoint's env_meta is serialize(): robomimic re-creates envs from it
        env2 = call(f"[{label}] create_env_from_metadata(env.serialize()) (checkpoint round trip)",
                    EnvUtils.create_env_from_metadata, env_meta=json.loads(json.dumps(ser)), render=False,
                    render_offscreen=use_images, use_image_obs=use_images)
        if env2 is not None:
            call(f"[{label}] round-trip env.reset()", env2.reset)
    return env


def write_dataset(path: Path, case: dict, xml: str, env_meta: dict) -> None:
    """A one-demo hdf5 in robomimic's layout (data/demo_0/{states,actions}, model_file,
    ep_meta, env_args) from the robosuite recording."""
    import h5py

    states = np.asarray(case["states"], dtype=np.float64)
    actions = np.asarray(case["actions"], dtype=np.float64)
    n = len(actions)
    with h5py.File(path, "w") as f:
        data = f.create_group("data")
        data.attrs["env_args"] = json.dumps(env_meta, indent=4)
        data.attrs["total"] = n
        demo = data.create_group("demo_0")
        demo.create_dataset("states", data=states[:n])
        demo.create_dataset("actions", data=actions)
        demo.attrs["model_file"] = xml
        demo.attrs["ep_meta"] = json.dumps(case.get("ep_meta", {}))
        demo.attrs["num_samples"] = n


def check_scripts(case, xml, env_meta, cameras, tol, workdir: Path):
    import h5py
    import robomimic.scripts.dataset_states_to_obs as DS
    import robomimic.scripts.playback_dataset as PB

    label = "scripts"
    print(f"\n=== {label}: dataset_states_to_obs / playback_dataset on a 1-demo dataset ===", flush=True)
    src = workdir / "demo.hdf5"
    write_dataset(src, case, xml, env_meta)
    args = argparse.Namespace(
        dataset=str(src), output_name="demo_obs.hdf5", n=None, shaped=True, camera_names=list(cameras),
        camera_height=84, camera_width=84, depth=False, done_mode=2, copy_rewards=False, copy_dones=False,
        exclude_next_obs=False, compress=False,
    )
    if call("dataset_states_to_obs.dataset_states_to_obs(args)", DS.dataset_states_to_obs, args, verbose=True) is not None or (
        workdir / "demo_obs.hdf5"
    ).exists():
        try:
            with h5py.File(workdir / "demo_obs.hdf5", "r") as f:
                g = f["data/demo_0"]
                rewards = g["rewards"][()]
                n = len(rewards)
                dr = float(np.max(np.abs(rewards[: n - 1] - np.asarray(case["rewards"][1:n]))))
                expect("dataset_states_to_obs rewards == robosuite's (shaped)", dr <= tol, f"max |diff| {dr:.2e} over {n - 1} steps")
                worst, worst_obj = 0.0, 0.0
                for t in range(n):
                    o = {k: g[f"obs/{k}"][t] for k in g["obs"]}
                    worst = max(worst, max_obs_diff(o, case["observations"][t], with_object=False)[0])
                    if "object" in o:
                        worst_obj = max(worst_obj, float(np.max(np.abs(o["object"] - np.asarray(case["observations"][t]["object-state"])))))
                expect("dataset_states_to_obs robot obs == robosuite's", worst <= tol, f"max |diff| {worst:.2e}")
                report("PASS" if worst_obj <= tol else "INFO", "dataset_states_to_obs obs/object vs robosuite's 2nd pass",
                       f"max |diff| {worst_obj:.2e}" + ("" if worst_obj <= tol else
                       " (one pass per state: {obj}_to_robot0_eef_* read the previous state's cache, as in robosuite)"))
                for cam in cameras:
                    k = f"obs/{cam}_image"
                    expect(f"dataset_states_to_obs {k}", k in g and g[k].shape == (n, 84, 84, 3), describe(g[k][()]) if k in g else "missing")
                if cameras:
                    info = json.loads(g.attrs["camera_info"]) if "camera_info" in g.attrs else None
                    expect("dataset_states_to_obs camera_info attr", info is not None and set(info) == set(cameras),
                           str(sorted(info)) if info else "missing")
                ea = json.loads(f["data"].attrs["env_args"])
                report("INFO", "dataset_states_to_obs env_args (serialize())", json.dumps(sorted(ea["env_kwargs"])))
        except Exception as e:  # noqa: BLE001
            report("FAIL", "reading dataset_states_to_obs output", f"{type(e).__name__}: {e}")

    for use_actions, video in ((False, None), (True, None), (False, str(workdir / "playback.mp4"))):
        args = argparse.Namespace(
            dataset=str(src), filter_key=None, n=None, use_obs=False, use_actions=use_actions, render=False,
            video_path=video, video_skip=5, render_image_names=None, render_depth_names=None, first=False,
        )
        call(f"playback_dataset(use_actions={use_actions}, video={'mp4' if video else None})",
             PB.playback_dataset, args, verbose=True)
    if (workdir / "playback.mp4").exists():
        report("INFO", "playback video", f"{(workdir / 'playback.mp4').stat().st_size} bytes")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--case", default="Lift-Panda", help="fixture stem in robosuite-env/tests/fixtures/scenes")
    ap.add_argument("--no-images", action="store_true", help="skip the camera-observation envs")
    ap.add_argument("--tol", type=float, default=1e-6, help="max |diff| to robosuite's recorded values")
    ap.add_argument("--keep", action="store_true", help="keep the temporary datasets")
    args = ap.parse_args()

    import robosuite_rs

    robosuite = call("robosuite_rs.install_as_robosuite()", robosuite_rs.install_as_robosuite)
    if robosuite is None:
        return 1
    import robosuite as imported

    expect("import robosuite is robosuite_rs", imported is robosuite and robosuite.__version__ == "1.5.2", robosuite.__version__)
    try:
        import robomimic
        import robomimic.envs.env_robosuite  # noqa: F401  (EnvRobosuite, through EnvUtils)
        import robomimic.utils.env_utils as EnvUtils
        import robomimic.utils.obs_utils as ObsUtils
        # robomimic's scripts import these at the top, before any env renders: on a machine
        # whose EGL is Mesa's llvmpipe, importing triton (torch._dynamo, pulled in by this
        # chain) after a GL context exists crashes the process (two LLVMs; plain
        # mujoco.Renderer does the same), so import them first, as robomimic does
        import robomimic.utils.file_utils  # noqa: F401
        import robomimic.scripts.dataset_states_to_obs  # noqa: F401
        import robomimic.scripts.playback_dataset  # noqa: F401
    except Exception as e:  # noqa: BLE001
        report("FAIL", "import robomimic.envs.env_robosuite", f"{type(e).__name__}: {e}")
        traceback.print_exc()
        return 1
    report("PASS", "import robomimic.envs.env_robosuite", f"robomimic {robomimic.__version__} at {Path(robomimic.__file__).parent}")
    for mod in ("robosuite.utils.transform_utils", "robosuite.utils.camera_utils", "robosuite.controllers", "robosuite.wrappers"):
        call(f"import {mod}", __import__, mod)
    call("robosuite.load_composite_controller_config(robot='Panda')", robosuite.load_composite_controller_config, robot="Panda")

    case = json.loads((SCENES / f"{args.case}.json").read_text())
    xml = gzip.decompress((SCENES / f"{args.case}.xml.gz").read_bytes()).decode()
    n_robots = len(case["robots"])
    cameras = ["agentview"] + [f"robot{i}_eye_in_hand" for i in range(n_robots)]

    # robomimic's get_observation needs ObsUtils initialised (train / scripts do this)
    ObsUtils.initialize_obs_utils_with_obs_specs(
        {"obs": {"low_dim": ["robot0_eef_pos"], "rgb": [f"{c}_image" for c in cameras]}}
    )
    call("robomimic egl_probe.get_available_devices()", lambda: __import__("egl_probe").get_available_devices())

    check_env(EnvUtils, ObsUtils, robosuite, case, xml, "low-dim serialize-style",
              env_meta_for(robosuite, case, [], "serialize"), False, [], args.tol)
    check_env(EnvUtils, ObsUtils, robosuite, case, xml, "low-dim hf_v15-style",
              env_meta_for(robosuite, case, [], "hf_v15"), False, [], args.tol)
    if not args.no_images:
        check_env(EnvUtils, ObsUtils, robosuite, case, xml, "images hf_v15-style",
                  env_meta_for(robosuite, case, cameras, "hf_v15"), True, cameras, args.tol)
        meta = env_meta_for(robosuite, case, cameras, "serialize")
        meta["env_kwargs"]["render_gpu_device_id"] = 0  # what EnvRobosuite stores when egl_probe finds a GPU
        check_env(EnvUtils, ObsUtils, robosuite, case, xml, "images serialize-style render_gpu_device_id=0",
                  meta, True, cameras, args.tol)

    # robomimic's data-processing constructor (dataset_states_to_obs.py)
    print("\n=== create_env_for_data_processing ===", flush=True)
    meta = env_meta_for(robosuite, case, [], "hf_v15")
    env = call("EnvUtils.create_env_for_data_processing(cameras)", EnvUtils.create_env_for_data_processing,
               env_meta=meta, camera_names=[] if args.no_images else cameras, camera_height=84, camera_width=84,
               reward_shaping=True, verbose=True)
    if env is not None:
        import robomimic.scripts.dataset_states_to_obs as DS

        env.reset_to({"model": xml, "states": np.asarray(case["states"][0]), "ep_meta": "{}"})
        info = call("dataset_states_to_obs.get_camera_info(env, cameras)", DS.get_camera_info, env=env,
                    camera_names=cameras, camera_height=84, camera_width=84, verbose=True)
        if info is not None:
            expect("camera_info intrinsics/extrinsics shapes",
                   all(np.shape(v["intrinsics"]) == (3, 3) and np.shape(v["extrinsics"]) == (4, 4) for v in info.values()),
                   str(sorted(info)))

    with tempfile.TemporaryDirectory(prefix="check_robomimic_") as tmp:
        work = Path(tmp)
        check_scripts(case, xml, env_meta_for(robosuite, case, [], "hf_v15"), [] if args.no_images else cameras,
                      args.tol, work)
        if args.keep:
            keep = ROOT / "target" / "check_robomimic"
            keep.mkdir(parents=True, exist_ok=True)
            for p in work.iterdir():
                (keep / p.name).write_bytes(p.read_bytes())

    print(f"\n{len(FAILS)} FAIL(s)" + (": " + "; ".join(FAILS) if FAILS else ""))
    return min(len(FAILS), 100)


if __name__ == "__main__":
    sys.exit(main())
