"""robosuite_rs.datasets and the demonstration wrappers against demonstrations recorded with
robosuite 1.5.2 itself (``fixtures/demonstrations``, recorded by
``scripts/record_demonstrations.py``: robosuite's own DataCollectionWrapper and
gather_demonstrations_as_hdf5, plus robomimic's dataset_states_to_obs output computed in
robosuite).

Tolerances (robosuite ran MuJoCo 3.3.7, we run 3.17.0):

* observations of a state set with ``set_state_from_flattened`` + ``forward``: 1e-9 for
  float64 keys; float32 keys (``robot0_eef_quat_site``) 3 ulps (5e-7); ``joint_acc`` (a
  forward pass's accelerations: contact solver) 0.1 while the gripper squeezes the object,
  as the scene tests allow more for it; PickPlaceCan's ``Can_pos`` / ``Can_quat`` 1e-6
  (its mesh body compiles ~3e-7 apart in the two MuJoCo versions; everything else of that
  scene is within 1e-9).
* the last ``next_obs`` of a demo (robomimic steps the last action there): the action
  replay tolerances below.
* replay from actions: arm joints 1e-5 in free space (the first 10 steps; as the recorded
  free-arm replay in test_observables.py) and 2e-3 over the whole demo (grasp and carry),
  fingers 2e-3 (their coupling constraint), the object in play 2e-2 once grasped (contact
  dynamics of the two MuJoCo versions). PickPlaceCan's three other objects sit outside the
  scene and tumble onto each other; they are not compared.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

h5py = pytest.importorskip("h5py")

import robosuite_rs as suite  # noqa: E402
from robosuite_rs import datasets as D  # noqa: E402
from robosuite_rs.wrappers import DataCollectionWrapper, DemoSamplerWrapper  # noqa: E402

FIXTURES = Path(__file__).resolve().parent / "fixtures" / "demonstrations"


def _sha(path: Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def _walk(g, out=None, prefix=""):
    out = {} if out is None else out
    for k in g:
        if isinstance(g[k], h5py.Dataset):
            out[prefix + k] = g[k][()]
        else:
            _walk(g[k], out, prefix + k + "/")
    return out


@pytest.fixture(scope="module")
def converted(tmp_path_factory):
    """states_to_obs (done_mode 2, one worker) of both fixtures, and of lift with --shaped."""
    d = tmp_path_factory.mktemp("s2o")
    out = {}
    for name in ("lift", "can"):
        shutil.copy(FIXTURES / f"{name}.hdf5", d)
        out[name] = D.states_to_obs(d / f"{name}.hdf5", done_mode=2, num_workers=1)
    out["lift_shaped"] = D.states_to_obs(d / "lift.hdf5", output_name="shaped.hdf5", shaped=True, done_mode=1, num_workers=1)
    return d, out


def _obs_tolerance(name: str, key: str, dtype) -> float:
    if key.endswith("joint_acc"):
        return 0.1
    if dtype == np.float32:
        return 5e-7
    if name == "can" and key == "object":
        return 1e-6
    return 1e-9


@pytest.mark.parametrize("name", ["lift", "can"])
def test_states_to_obs_gives_robomimics_output(converted, name):
    _, out = converted
    with h5py.File(FIXTURES / f"{name}_low_dim.hdf5") as exp, h5py.File(out[name].output) as got:
        assert got["data"].attrs["env_args"] == exp["data"].attrs["env_args"]
        assert got["data"].attrs["total"] == exp["data"].attrs["total"]
        assert sorted(got["data"]) == sorted(exp["data"])
        for ep in exp["data"]:
            e, g = exp[f"data/{ep}"], got[f"data/{ep}"]
            assert g.attrs["model_file"] == e.attrs["model_file"]
            assert g.attrs["num_samples"] == e.attrs["num_samples"]
            np.testing.assert_array_equal(g["states"][()], e["states"][()])
            np.testing.assert_array_equal(g["actions"][()], e["actions"][()])
            np.testing.assert_array_equal(g["rewards"][()], e["rewards"][()])
            np.testing.assert_array_equal(g["dones"][()], e["dones"][()])
            assert g["dones"].dtype == e["dones"].dtype and g["rewards"].dtype == e["rewards"].dtype
            assert set(g["obs"]) == set(e["obs"]) and set(g["next_obs"]) == set(e["next_obs"])
            for grp in ("obs", "next_obs"):
                for k in e[grp]:
                    a, b = e[f"{grp}/{k}"][()], g[f"{grp}/{k}"][()]
                    assert b.dtype == a.dtype and b.shape == a.shape, (ep, grp, k)
                    tol = _obs_tolerance(name, k, a.dtype)
                    if grp == "next_obs":  # the last one comes from stepping the last action
                        np.testing.assert_allclose(b[-1], a[-1], rtol=0, atol=max(tol, 2e-3), err_msg=f"{ep} {grp} {k} last")
                        a, b = a[:-1], b[:-1]
                    np.testing.assert_allclose(b, a, rtol=0, atol=tol, err_msg=f"{ep} {grp} {k}")


def test_shaped_rewards_and_done_mode_1(converted):
    _, out = converted
    with h5py.File(FIXTURES / "lift_low_dim.hdf5") as exp, h5py.File(out["lift_shaped"].output) as got:
        for ep in exp["data"]:
            shaped = exp[f"data/{ep}/rewards_shaped"][()]
            np.testing.assert_allclose(got[f"data/{ep}/rewards"][()][:-1], shaped[:-1], rtol=0, atol=1e-9)
            np.testing.assert_allclose(got[f"data/{ep}/rewards"][()][-1], shaped[-1], rtol=0, atol=1e-3)
            dones = got[f"data/{ep}/dones"][()]
            assert dones[-1] == 1 and not dones[:-1].any()  # done_mode 1: the end only
            assert exp[f"data/{ep}/successes"][()].any()
        assert json.loads(got["data"].attrs["env_args"])["env_kwargs"]["reward_shaping"] is True


def test_states_to_obs_workers_identical_and_options(converted):
    d, out = converted
    r2 = D.states_to_obs(d / "lift.hdf5", output_name="two.hdf5", done_mode=2, num_workers=2)
    assert r2.num_workers == 2
    with h5py.File(out["lift"].output) as a, h5py.File(r2.output) as b:
        A, B = _walk(a), _walk(b)
        assert A.keys() == B.keys()
        for k in A:
            np.testing.assert_array_equal(A[k], B[k], err_msg=k)
        assert dict(a["data"].attrs) == dict(b["data"].attrs)
    # done_mode 0, copies, no next_obs, gzip, first demo only
    with h5py.File(d / "lift_ld.hdf5") as src, h5py.File(d / "with_rewards.hdf5", "w") as dst:
        for key in src:
            src.copy(key, dst)
        for k, v in src["data"].attrs.items():
            dst["data"].attrs[k] = v
        del dst["data/demo_1/rewards"]
        dst["data/demo_1/rewards"] = np.arange(len(src["data/demo_1/actions"]), dtype=np.float64)
    r = D.states_to_obs(d / "with_rewards.hdf5", output_name="opts.hdf5", n=1, done_mode=0, copy_rewards=True,
                        copy_dones=True, exclude_next_obs=True, compress=True, num_workers=1)
    with h5py.File(r.output) as g, h5py.File(d / "with_rewards.hdf5") as src:
        assert list(g["data"]) == ["demo_1"] and g["data"].attrs["total"] == 27
        np.testing.assert_array_equal(g["data/demo_1/rewards"][()], np.arange(27.0))
        np.testing.assert_array_equal(g["data/demo_1/dones"][()], src["data/demo_1/dones"][()])
        assert "next_obs" not in g["data/demo_1"]
        assert g["data/demo_1/obs/object"].compression == "gzip"
    # done_mode 0 on its own: done exactly where the next state succeeds
    r0 = D.states_to_obs(d / "lift.hdf5", output_name="dm0.hdf5", done_mode=0, num_workers=1)
    with h5py.File(r0.output) as g, h5py.File(FIXTURES / "lift_low_dim.hdf5") as exp:
        for ep in exp["data"]:
            np.testing.assert_array_equal(g[f"data/{ep}/dones"][()], exp[f"data/{ep}/successes"][()].astype(int))


def _model_fields(path):
    """Every array and scalar of a saved model (MuJoCo's Python bindings), by name."""
    import mujoco

    m = mujoco.MjModel.from_binary_path(str(path))
    out = {}
    for name in dir(m):
        if name.startswith("_"):
            continue
        v = getattr(m, name)
        if isinstance(v, np.ndarray):
            out[name] = v
        elif isinstance(v, (int, float)):
            out[name] = np.array(v)
    for struct in ("opt", "stat", "vis"):
        obj = getattr(m, struct)
        for name in dir(obj):
            if name.startswith("_"):
                continue
            v = getattr(obj, name)
            if isinstance(v, (np.ndarray, int, float)):
                out[f"{struct}.{name}"] = np.asarray(v)
            elif struct == "vis" and hasattr(v, "__dir__"):
                for sub in dir(v):
                    w = getattr(v, sub)
                    if not sub.startswith("_") and isinstance(w, (np.ndarray, int, float)):
                        out[f"vis.{name}.{sub}"] = np.asarray(w)
    return out


def test_scene_patching_matches_a_full_compile(tmp_path):
    """A demo scene that differs from one compiled before only in the cube's size is made by
    resizing a copy (no compile): every model field equals a full compile's to 1e-12."""
    pytest.importorskip("mujoco")
    from robosuite_rs import _native

    env = suite.make("Lift", robots="Panda", has_renderer=False, has_offscreen_renderer=False, use_camera_obs=False)
    with h5py.File(FIXTURES / "lift.hdf5") as f:
        xmls = [env.edit_model_xml(D._model_file(f, ep)) for ep in ("demo_1", "demo_2")]
    assert xmls[0] != xmls[1]
    try:
        _native.set_scene_patching(True)
        before = _native.scenes_patched()
        _native.save_scene_model(xmls[0], tmp_path / "first.mjb")
        _native.save_scene_model(xmls[1], tmp_path / "patched.mjb")
        assert _native.scenes_patched() == before + 1
        # something else than box sizes differs: compiled in full
        _native.save_scene_model(xmls[1].replace('impratio="20"', 'impratio="19"'), tmp_path / "other.mjb")
        assert _native.scenes_patched() == before + 1
        _native.set_scene_patching(False)
        _native.save_scene_model(xmls[1], tmp_path / "full.mjb")
        assert _native.scenes_patched() == before + 1
    finally:
        _native.set_scene_patching(True)
    patched, full = _model_fields(tmp_path / "patched.mjb"), _model_fields(tmp_path / "full.mjb")
    assert patched.keys() == full.keys() and len(full) > 300
    first = _model_fields(tmp_path / "first.mjb")
    for k in full:
        a, b = full[k], patched[k]
        assert a.shape == b.shape and a.dtype == b.dtype, k
        if a.dtype.kind == "f":
            np.testing.assert_allclose(b, a, rtol=0, atol=1e-12, err_msg=k)
        else:
            np.testing.assert_array_equal(b, a, err_msg=k)
    for k in ("geom_size", "body_mass", "body_inertia", "geom_rbound"):  # the demos' cubes do differ
        assert not np.array_equal(first[k], full[k]), k


def test_patched_scenes_give_bit_identical_observations(converted):
    """states_to_obs with scene patching gives exactly what full compiles give."""
    from robosuite_rs import _native

    d, _ = converted
    try:
        _native.set_scene_patching(True)  # empties the cache: demo_1 compiled, demo_2 patched
        before = _native.scenes_patched()
        patched = D.states_to_obs(d / "lift.hdf5", output_name="patched.hdf5", done_mode=2, num_workers=1)
        assert _native.scenes_patched() == before + 1
        _native.set_scene_patching(False)
        full = D.states_to_obs(d / "lift.hdf5", output_name="full_compile.hdf5", done_mode=2, num_workers=1)
        assert _native.scenes_patched() == before + 1
    finally:
        _native.set_scene_patching(True)
    with h5py.File(patched.output) as a, h5py.File(full.output) as b:
        A, B = _walk(a), _walk(b)
        assert A.keys() == B.keys() and any(k.endswith("obs/object") for k in A)
        for k in A:
            np.testing.assert_array_equal(A[k], B[k], err_msg=k)


@pytest.mark.parametrize("cameras", [False, True])
def test_native_loop_equals_robomimics_python_loop(converted, cameras, monkeypatch):
    """Each trajectory observed in one native call (the default) gives exactly what
    robomimic's per-state loop through the env gives: low-dim, and images and depth."""
    d, out = converted
    kw = dict(camera_names=["agentview"], camera_height=32, camera_width=40, depth=True, n=1) if cameras else {}
    native = out["lift"] if not cameras else D.states_to_obs(d / "lift.hdf5", output_name="cam_native.hdf5",
                                                           done_mode=2, num_workers=1, **kw)
    monkeypatch.setattr(D, "NATIVE_LOOP", False)
    looped = D.states_to_obs(d / "lift.hdf5", output_name=f"loop{int(cameras)}.hdf5", done_mode=2, num_workers=1, **kw)
    with h5py.File(native.output) as a, h5py.File(looped.output) as b:
        A, B = _walk(a), _walk(b)
        assert A.keys() == B.keys()
        if cameras:
            assert A["data/demo_1/obs/agentview_image"].shape[1:] == (32, 40, 3)
            assert A["data/demo_1/obs/agentview_depth"].shape[1:] == (32, 40, 1)
            assert A["data/demo_1/obs/agentview_image"].std() > 10  # a scene, not a blank frame
            assert a["data/demo_1"].attrs["camera_info"] == b["data/demo_1"].attrs["camera_info"]
        for k in A:
            assert A[k].dtype == B[k].dtype, k
            np.testing.assert_array_equal(A[k], B[k], err_msg=k)


def test_scene_of_another_demo_loads_in_place():
    """Demos of one task differ in the cube's size: the env keeps its model and data (env.sim
    and views of its arrays stay valid and show the new scene)."""
    with h5py.File(FIXTURES / "lift.hdf5") as f:
        xmls = [str(f[f"data/{ep}"].attrs["model_file"]) for ep in sorted(f["data"])]
        info = json.loads(f["data"].attrs["env_info"])
    info.pop("env_name", None)
    env = suite.make("Lift", **info, has_offscreen_renderer=False, use_camera_obs=False, ignore_done=True)
    env.reset_from_xml_string(xmls[0])
    sim, size = env.sim, env.sim.model.geom_size
    cube = env.sim.model.geom_name2id("cube_g0")
    first = size[cube].copy()
    env.reset_from_xml_string(xmls[1])
    assert env.sim is sim
    assert not np.array_equal(size[cube], first)  # the same view shows scene 2's cube
    fresh = suite.make("Lift", **info, has_offscreen_renderer=False, use_camera_obs=False, ignore_done=True)
    fresh.reset_from_xml_string(xmls[1])
    np.testing.assert_allclose(size[cube], fresh.sim.model.geom_size[cube], rtol=1e-12)
    np.testing.assert_allclose(env.sim.model.body_mass, fresh.sim.model.body_mass, rtol=1e-12)
    with pytest.raises((ValueError, RuntimeError)):
        env.reset_from_xml_string("<mujoco><worldbody>")
    assert env.sim is sim and np.array_equal(size[cube], fresh.sim.model.geom_size[cube])


def test_playback_from_states_gives_robosuites_observations():
    seen = {}

    def record(env, demo, t):
        seen.setdefault(demo, []).append(env._get_observations(force_update=True))

    res = D.playback(FIXTURES / "lift.hdf5", callback=record)
    with h5py.File(FIXTURES / "lift_low_dim.hdf5") as exp:
        for ep in exp["data"]:
            assert res[ep].steps == len(exp[f"data/{ep}/states"])
            for key in ("robot0_eef_pos", "robot0_joint_pos_cos", "robot0_gripper_qpos"):
                got = np.array([o[key] for o in seen[ep]])
                np.testing.assert_allclose(got, exp[f"data/{ep}/obs/{key}"][()], rtol=0, atol=1e-9, err_msg=key)
            got = np.array([o["object-state"] for o in seen[ep]])
            np.testing.assert_allclose(got, exp[f"data/{ep}/obs/object"][()], rtol=0, atol=1e-9)


@pytest.mark.parametrize("name,obj", [("lift", "cube_joint0"), ("can", "Can_joint0")])
def test_playback_from_actions_within_replay_tolerances(name, obj):
    with h5py.File(FIXTURES / f"{name}.hdf5") as f:
        stored = {ep: f[f"data/{ep}/states"][()] for ep in f["data"]}
    diffs = {}

    def record(env, demo, j):
        states = stored[demo]
        if j + 1 < len(states):
            m = env.sim.model
            adr = m.jnt_qposadr[m.joint_name2id(obj)]
            d = np.abs(states[j + 1] - env.sim.get_state().flatten())[1:]
            diffs.setdefault(demo, []).append((d[:7].max(), d[7:9].max(), d[adr : adr + 3].max()))

    res = D.playback(FIXTURES / f"{name}.hdf5", use_actions=True, callback=record)
    for ep, rows in diffs.items():
        rows = np.array(rows)
        assert res[ep].steps == len(stored[ep]) and len(res[ep].divergence) == len(stored[ep]) - 1
        assert rows[:10, 0].max() < 1e-5, rows[:10, 0]
        assert rows[:, 0].max() < 2e-3 and rows[:, 1].max() < 2e-3, rows[:, :2].max(axis=0)
        assert rows[:, 2].max() < 2e-2, rows[:, 2].max()


def _scripted_lift(env, steps=60):
    """The recording script's Lift policy: above the cube, down, close, lift."""
    obs = env.reset()
    start = obs["cube_pos"].copy()
    phase, hold = 0, 0
    for _ in range(steps):
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
        if env._check_success():
            break


def test_data_collection_wrapper_round_trip(tmp_path, capsys):
    env_info = {"env_name": "Lift", "robots": ["Panda"], "controller_configs": suite.load_composite_controller_config(robot="Panda")}
    kwargs = {k: v for k, v in env_info.items() if k != "env_name"}
    env = suite.make("Lift", **kwargs, has_renderer=False, has_offscreen_renderer=False, ignore_done=True,
                     use_camera_obs=False, reward_shaping=True, control_freq=20, seed=5)
    env = DataCollectionWrapper(env, tmp_path / "raw", flush_freq=10)
    _scripted_lift(env)
    steps = env.t
    assert env.env._check_success()
    env.reset()  # flushes the episode, starts another (never stepped: not written)
    env.close()
    (ep_dir,) = [p for p in (tmp_path / "raw").iterdir()]
    assert ep_dir.name.startswith("ep_") and (ep_dir / "model.xml").read_text() and json.loads((ep_dir / "ep_meta.json").read_text()) == {}
    npz = sorted(ep_dir.glob("state_*.npz"))
    assert len(npz) == (steps + 9) // 10
    first = np.load(npz[0], allow_pickle=True)
    assert set(first.files) == {"states", "action_infos", "successful", "env"} and str(first["env"]) == "Lift"
    assert first["states"].shape == (11, 1 + env.sim.model.nq + env.sim.model.nv)  # reset state + 10 steps
    assert set(first["action_infos"][0]) == {"actions"} and first["action_infos"][0]["actions"].shape == (7,)
    path = D.gather_demonstrations_as_hdf5(tmp_path / "raw", tmp_path, json.dumps(env_info))
    with h5py.File(path) as f:
        data = f["data"]
        assert set(data.attrs) == {"date", "time", "repository_version", "env", "env_info"}
        assert data.attrs["env"] == "Lift" and json.loads(data.attrs["env_info"])["env_name"] == "Lift"
        assert list(data) == ["demo_1"]
        g = data["demo_1"]
        assert g["states"].shape[0] == g["actions"].shape[0] == steps
        assert g.attrs["model_file"] == (ep_dir / "model.xml").read_text()
        assert json.loads(g.attrs["ep_meta"]) == {}
    # ours replays itself exactly, from its actions (the point of DataCollectionWrapper's reset)
    res = D.playback(path, use_actions=True)
    assert res["demo_1"].divergence.max() == 0.0
    assert D.playback(path)["demo_1"].steps == steps


def test_demo_sampler_wrapper(tmp_path):
    import random

    env = suite.make("Lift", robots="Panda", has_renderer=False, has_offscreen_renderer=False, use_camera_obs=False)
    with h5py.File(FIXTURES / "lift.hdf5") as f:
        all_states = np.concatenate([f[f"data/{ep}/states"][()] for ep in f["data"]])
        ends = {ep: f[f"data/{ep}/states"][()][-3:] for ep in f["data"]}
    shutil.copy(FIXTURES / "lift.hdf5", tmp_path / "demo.hdf5")
    w = DemoSamplerWrapper(env, tmp_path, need_xml=True, sampling_schemes=["uniform"], scheme_ratios=[1.0])
    random.seed(0)
    for _ in range(2):
        obs = w.reset()
        state = w.sim.get_state().flatten()
        assert np.abs(all_states - state).max(axis=1).min() == 0.0
        assert "cube_pos" in obs
    w2 = DemoSamplerWrapper(env, tmp_path / "demo.hdf5", sampling_schemes=["reverse", "random"], scheme_ratios=[0.5, 0.5],
                            open_loop_initial_window_width=3, open_loop_increment_freq=1000)
    random.seed(1)
    np.random.seed(1)
    kinds = set()
    for _ in range(6):
        w2.reset()
        state = w2.sim.get_state().flatten()
        hit = any(np.abs(e - state).max(axis=1).min() == 0.0 for e in ends.values())
        kinds.add(hit)
    assert kinds == {True, False}  # both schemes drawn; demo states from the last 3 only
    with pytest.raises(ValueError, match="unknown sampling scheme"):
        DemoSamplerWrapper(env, tmp_path, sampling_schemes=["bogus"], scheme_ratios=[1.0])
    with pytest.raises(ValueError, match="sum to 1"):
        DemoSamplerWrapper(env, tmp_path, scheme_ratios=[0.5, 0.2])
    other = suite.make("Stack", robots="Panda", has_renderer=False, has_offscreen_renderer=False, use_camera_obs=False)
    with pytest.raises(ValueError, match="does not match"):
        DemoSamplerWrapper(other, tmp_path)


def test_convert_to_robomimic(tmp_path):
    shutil.copy(FIXTURES / "lift.hdf5", tmp_path)
    before = _sha(tmp_path / "lift.hdf5")
    np.random.seed(0)
    out = D.convert_to_robomimic(tmp_path / "lift.hdf5", val_ratio=0.5)
    assert _sha(tmp_path / "lift.hdf5") == before
    with h5py.File(out) as f:
        meta = json.loads(f["data"].attrs["env_args"])
        assert list(meta) == ["type", "env_name", "env_version", "env_kwargs"] and meta["type"] == 1
        assert meta["env_name"] == "Lift" and meta["env_version"] == "1.5.2" and meta["env_kwargs"]["robots"] == ["Panda"]
        assert f["data"].attrs["total"] == 56 and f["data/demo_1"].attrs["num_samples"] == 27
        train = [k.decode() for k in f["mask/train"][()]]
        valid = [k.decode() for k in f["mask/valid"][()]]
        assert sorted(train + valid) == ["demo_1", "demo_2"] and len(valid) == 1
    with pytest.raises(FileExistsError):
        D.convert_to_robomimic(tmp_path / "lift.hdf5")


# ----------------------------------------------------------------------------- bad input


@pytest.fixture()
def lift_copy(tmp_path):
    shutil.copy(FIXTURES / "lift.hdf5", tmp_path / "demo.hdf5")
    return tmp_path / "demo.hdf5"


def _edit(path, fn):
    with h5py.File(path, "a") as f:
        fn(f)


def _no_leftovers(folder):
    return [p.name for p in Path(folder).iterdir() if ".tmp-" in p.name] == []


def test_bad_input_missing_and_truncated(tmp_path, lift_copy):
    with pytest.raises(FileNotFoundError, match="no such dataset"):
        D.states_to_obs(tmp_path / "nope.hdf5")
    data = lift_copy.read_bytes()
    (tmp_path / "cut.hdf5").write_bytes(data[: len(data) // 3])
    with pytest.raises(D.DatasetError, match="cut.hdf5: not a readable HDF5"):
        D.states_to_obs(tmp_path / "cut.hdf5")
    with pytest.raises(D.DatasetError, match="not a readable HDF5"):
        D.playback(tmp_path / "cut.hdf5")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cut.hdf5", "demo.hdf5"]


def test_bad_input_states_and_scene(lift_copy):
    def short_states(f):
        s = f["data/demo_2/states"][()]
        del f["data/demo_2/states"]
        f["data/demo_2/states"] = s[:, :-1]

    _edit(lift_copy, short_states)
    before = _sha(lift_copy)
    with pytest.raises(D.DatasetError, match=r"data/demo_2/states: shape \(29, 31\) does not fit"):
        D.states_to_obs(lift_copy, num_workers=1)
    with pytest.raises(D.DatasetError, match=r"data/demo_2/states"):
        D.playback(lift_copy)
    assert _sha(lift_copy) == before and not (lift_copy.parent / "demo_ld.hdf5").exists()
    assert _no_leftovers(lift_copy.parent)

    def bad_xml(f):
        f["data/demo_1"].attrs["model_file"] = "<mujoco><worldbody><body></mujoco>"

    _edit(lift_copy, bad_xml)
    with pytest.raises(D.DatasetError, match="data/demo_1 attribute model_file"):
        D.states_to_obs(lift_copy, num_workers=1)
    with pytest.raises(D.DatasetError, match="data/demo_1 attribute model_file"):
        D.playback(lift_copy, demos=["demo_1"])


def test_bad_input_env_args(lift_copy):
    _edit(lift_copy, lambda f: f["data"].attrs.__setitem__("env", "NoSuchTask"))
    with pytest.raises(D.DatasetError, match="unknown env 'NoSuchTask'"):
        D.states_to_obs(lift_copy)
    info = json.loads(h5py.File(FIXTURES / "lift.hdf5")["data"].attrs["env_info"])
    info["no_such_argument"] = 1

    def bad_arg(f):
        f["data"].attrs["env"] = "Lift"
        f["data"].attrs["env_info"] = json.dumps(info)

    _edit(lift_copy, bad_arg)
    with pytest.raises(D.DatasetError, match="no_such_argument"):
        D.states_to_obs(lift_copy)
    with pytest.raises(D.DatasetError, match="env_args"):
        D.states_to_obs(lift_copy, camera_names=["no_such_camera"])


def test_bad_output(tmp_path, lift_copy):
    r = D.states_to_obs(lift_copy, n=1, num_workers=1)
    with pytest.raises(FileExistsError, match="overwrite"):
        D.states_to_obs(lift_copy, n=1, num_workers=1)
    mtime = os.path.getmtime(r.output)
    D.states_to_obs(lift_copy, n=1, num_workers=1, overwrite=True)
    assert os.path.getmtime(r.output) >= mtime
    with pytest.raises(D.DatasetError, match="replace the input"):
        D.states_to_obs(lift_copy, output_name="demo.hdf5", overwrite=True)
    with pytest.raises(FileNotFoundError, match="output folder"):
        D.states_to_obs(lift_copy, output_name=str(tmp_path / "missing" / "out.hdf5"))
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        if os.access(ro, os.W_OK):  # root ignores the mode: a path under a file instead
            bad = str(lift_copy) + "/out.hdf5"
            with pytest.raises((FileNotFoundError, NotADirectoryError)):
                D.states_to_obs(lift_copy, output_name=bad)
        else:
            with pytest.raises(PermissionError, match="not writable"):
                D.states_to_obs(lift_copy, output_name=str(ro / "out.hdf5"))
    finally:
        ro.chmod(0o700)
    assert _no_leftovers(tmp_path)


def test_worker_error_stops_the_run(lift_copy):
    _edit(lift_copy, lambda f: f["data/demo_2"].attrs.__setitem__("model_file", "<mujoco><bad/></mujoco>"))
    with pytest.raises(D.DatasetError, match="data/demo_2 attribute model_file"):
        D.states_to_obs(lift_copy, num_workers=2)
    assert not (lift_copy.parent / "demo_ld.hdf5").exists() and _no_leftovers(lift_copy.parent)


def test_cli_states_to_obs(lift_copy, capsys):
    cmd = [sys.executable, "-m", "robosuite_rs.datasets", "states-to-obs", "--dataset", str(lift_copy),
           "--output_name", "cli.hdf5", "--done_mode", "2", "--n", "1", "--num_workers", "1"]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert "Wrote 1 trajectories" in p.stdout and "states/s" in p.stdout
    assert "1/1" in p.stderr  # the progress bar
    with h5py.File(lift_copy.parent / "cli.hdf5") as f:
        assert list(f["data"]) == ["demo_1"] and f["data/demo_1/dones"][-1] == 1
    # the refusal of an existing output, through the same entry point in this process
    from robosuite_rs.datasets.__main__ import main

    assert main(cmd[3:]) == 1
    assert "exists" in capsys.readouterr().err
