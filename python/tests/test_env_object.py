"""robosuite's env object beyond the RL loop: ``env.sim`` on MuJoCo's own objects, the XML
round trip, episode metadata, observables, ``env.robots`` and ``install_as_robosuite``."""

from __future__ import annotations

import gc
import json
import subprocess
import sys
import textwrap

import mujoco
import numpy as np
import pytest

import robosuite_rs as suite
from robosuite_rs.wrappers import GymWrapper


def lift(**kwargs):
    kwargs.setdefault("seed", 3)
    return suite.make("Lift", robots="Panda", has_renderer=False, use_camera_obs=False, **kwargs)


def actions(n, dim=7, seed=0):
    return np.random.default_rng(seed).uniform(-1, 1, size=(n, dim))


# --- env.sim shares memory with the env ------------------------------------------------
def test_sim_model_and_data_are_mujocos_own_objects():
    env = lift()
    env.reset()
    assert isinstance(env.sim.model._model, mujoco.MjModel)
    assert isinstance(env.sim.data._data, mujoco.MjData)
    assert env.sim.data._data.model is env.sim.model._model
    assert env.sim is env.sim  # the same object until the model changes
    # mujoco's own functions work on them
    mujoco.mj_forward(env.sim.model._model, env.sim.data._data)


def test_a_sim_model_write_is_seen_by_no_other_env():
    # Envs of one configuration share one compiled model copy-on-write; env.sim.model is
    # always the env's own.
    a, b = lift(), lift()
    a.reset(seed=1)
    b.reset(seed=1)
    before = b.sim.model.geom_rgba.copy()
    a.sim.model.geom_rgba[:] = 0.25
    a.sim.model.opt.timestep = 0.001
    assert (a.sim.model.geom_rgba == 0.25).all()
    np.testing.assert_array_equal(b.sim.model.geom_rgba, before)
    assert b.sim.model.opt.timestep == 0.002
    c = lift()  # a new env starts from the compiled model
    np.testing.assert_array_equal(c.sim.model.geom_rgba, before)
    # Both step on, each with its own model.
    for env in (a, b, c):
        env.reset(seed=2)
        env.step(actions(1)[0])


def test_an_env_that_never_renders_steps_draws_and_reads_textures_as_a_textured_one():
    # has_offscreen_renderer=False: the scene is simulated without texture images; the
    # frames, env.sim.model's tex_* arrays and the trajectory are the textured env's.
    bare, full = lift(has_offscreen_renderer=False), lift(has_offscreen_renderer=True)
    obs = [env.reset(seed=4) for env in (bare, full)]
    for a in actions(6):
        obs = [env.step(a)[0] for env in (bare, full)]
        assert obs[0].keys() == obs[1].keys()
        for k in obs[0]:
            np.testing.assert_array_equal(obs[0][k], obs[1][k], err_msg=k)
    np.testing.assert_array_equal(
        bare.sim.render(64, 64, camera_name="agentview"), full.sim.render(64, 64, camera_name="agentview")
    )
    for field in ("tex_width", "tex_height", "tex_adr", "tex_data"):
        np.testing.assert_array_equal(getattr(bare.sim.model, field), getattr(full.sim.model, field), err_msg=field)
    assert bare.sim.model.tex_data.size > 1_000_000
    a = actions(1, seed=5)[0]
    np.testing.assert_array_equal(bare.step(a)[0]["cube_pos"], full.step(a)[0]["cube_pos"])


def test_data_arrays_are_what_the_env_steps():
    env = lift()
    env.reset()
    qpos = env.sim.data.qpos  # a view, kept across steps
    nq = env.sim.model.nq
    for a in actions(5):
        env.step(a)
        np.testing.assert_array_equal(qpos, env.get_state()[1 : 1 + nq])
    # a write is what the next step starts from
    state = env.get_state()
    env.sim.data.qpos[env.sim.model.get_joint_qpos_addr("robot0_joint1")] += 0.1
    env.sim.forward()
    assert env.get_state()[1] == pytest.approx(state[1] + 0.1)


def test_touching_sim_keeps_trajectories_bit_identical():
    plain, touched = lift(), lift()
    plain.reset(seed=11)
    touched.reset(seed=11)
    _ = touched.sim.data.qpos  # hands the memory to MuJoCo's Python objects mid-episode
    for a in actions(20, seed=4):
        o1, r1, _, _ = plain.step(a)
        o2, r2, _, _ = touched.step(a)
        assert r1 == r2
        for k in o1:
            np.testing.assert_array_equal(o1[k], o2[k])
    np.testing.assert_array_equal(plain.get_state(), touched.get_state())


def test_views_outlive_close_and_model_replacement():
    env = lift()
    env.reset()
    env.step(actions(1)[0])
    qpos = env.sim.data.qpos
    model = env.sim.model._model
    expected = qpos.copy()
    xml = env.sim.model.get_xml()
    env.reset_from_xml_string(xml)
    assert env.sim.data.qpos is not qpos
    np.testing.assert_array_equal(qpos, expected)  # the old data, still readable
    env.close()
    del env
    gc.collect()
    np.testing.assert_array_equal(qpos, expected)
    assert model.nq == len(expected)


def test_name_maps_and_named_getters():
    env = lift()
    env.reset()
    m, d = env.sim.model, env.sim.data
    assert m.body_names[m.body_name2id("cube_main")] == "cube_main"
    assert m.camera_name2id("free") == -1 and m.camera_id2name(-1) == "free"
    assert "agentview" in m.camera_names
    with pytest.raises(ValueError, match='No "body" with name nope exists'):
        m.body_name2id("nope")
    with pytest.raises(ValueError, match="No site with id"):
        m.site_id2name(10_000)
    site = "gripper0_right_grip_site"
    np.testing.assert_array_equal(d.get_site_xpos(site), d.site_xpos[m.site_name2id(site)])
    assert d.get_site_xmat(site).shape == (3, 3)
    assert d.get_body_jacp("robot0_right_hand").shape == (3, m.nv)
    np.testing.assert_allclose(
        d.get_site_xvelp(site), d.get_site_jacp(site) @ d.qvel, rtol=0, atol=0
    )
    free = m.get_joint_qpos_addr("cube_joint0")
    assert free[1] - free[0] == 7 and m.get_joint_qvel_addr("cube_joint0")[1] - m.get_joint_qvel_addr("cube_joint0")[0] == 6
    assert isinstance(m.get_joint_qpos_addr("robot0_joint1"), int)
    cube = d.get_joint_qpos("cube_joint0").copy()
    d.set_joint_qpos("cube_joint0", cube + np.r_[0.01, 0, 0, 0, 0, 0, 0])
    assert d.get_joint_qpos("cube_joint0")[0] == pytest.approx(cube[0] + 0.01)
    with pytest.raises(ValueError, match="incorrect shape"):
        d.set_joint_qpos("cube_joint0", [0.0, 1.0])
    # raw fields pass through
    assert m.stat.extent > 0 and m.vis.map.znear > 0
    assert m.cam_fovy.shape == (m.ncam,) and d.cam_xmat.shape == (m.ncam, 9)


def test_get_state_set_state_and_bad_writes():
    env = lift()
    env.reset()
    for a in actions(3):
        env.step(a)
    state = env.sim.get_state()
    flat = state.flatten()
    np.testing.assert_array_equal(flat, env.get_state())
    for a in actions(3, seed=1):
        env.step(a)
    env.sim.set_state_from_flattened(flat)
    env.sim.forward()
    np.testing.assert_array_equal(env.get_state(), flat)
    before = env.get_state()
    for bad in (flat[:-1], np.r_[flat, 0.0], np.where(np.arange(flat.size) == 3, np.nan, flat), flat.reshape(1, -1)):
        with pytest.raises(ValueError):
            env.sim.set_state_from_flattened(bad)
        np.testing.assert_array_equal(env.get_state(), before)


def test_non_finite_write_is_reported_by_the_step():
    env = lift()
    env.reset()
    env.sim.data.qvel[0] = np.inf
    with pytest.raises(RuntimeError, match="diverged"):
        env.step(np.zeros(7))
    env.reset()  # usable again
    env.step(np.zeros(7))


def test_sim_render_camera_depth_and_segmentation():
    env = lift()
    env.reset()
    rgb = env.sim.render(width=64, height=48, camera_name="agentview")
    assert rgb.shape == (48, 64, 3) and rgb.dtype == np.uint8 and rgb.std() > 0
    rgb2, depth = env.sim.render(64, 48, camera_name="agentview", depth=True)
    np.testing.assert_array_equal(rgb, rgb2)
    assert depth.shape == (48, 64) and depth.dtype == np.float32 and 0 < depth.min() <= depth.max() <= 1
    seg = env.sim.render(64, 48, camera_name="agentview", segmentation=True)
    assert seg.shape == (48, 64, 2) and seg.dtype == np.int32
    geoms = seg[..., 1][seg[..., 0] == int(mujoco.mjtObj.mjOBJ_GEOM)]
    assert env.sim.model.geom_name2id("cube_g0_vis") in set(geoms.tolist())
    with pytest.raises(ValueError, match="camera"):
        env.sim.render(64, 48, camera_name="nope")
    before = env.get_state()
    for w, h in ((0, 48), (64, 5000)):
        with pytest.raises(ValueError):
            env.sim.render(w, h, camera_name="agentview")
    np.testing.assert_array_equal(env.get_state(), before)
    np.testing.assert_array_equal(env.sim.render(64, 48, camera_name="agentview"), rgb)
    # Without a name, as robosuite's render context: the previous call's camera ...
    np.testing.assert_array_equal(env.sim.render(64, 48), rgb)
    # ... and camera 0 in a sim that has not rendered yet.
    other = lift()
    other.reset()
    first = other.sim.model.camera_id2name(0)
    np.testing.assert_array_equal(other.sim.render(40, 30), other.sim.render(40, 30, camera_name=first))

    # MuJoCo's free camera ("free", id -1): robosuite's render context camera, as set on it.
    cam = env.sim._render_context_offscreen.cam
    assert cam.type == mujoco.mjtCamera.mjCAMERA_FIXED
    free = env.sim.render(64, 48, camera_name="free")
    assert cam.type == mujoco.mjtCamera.mjCAMERA_FREE and free.std() > 0
    assert not np.array_equal(free, rgb)
    np.testing.assert_array_equal(env.sim.render(64, 48), free)  # the context keeps the free camera
    cam.distance = 4.0  # further away: the scene covers fewer pixels
    far = env.sim.render(64, 48)
    assert not np.array_equal(far, free)
    cam.distance = 2.0
    np.testing.assert_array_equal(env.sim.render(64, 48), free)
    cam.distance = 0.0
    with pytest.raises(ValueError, match="free camera"):
        env.sim.render(64, 48)
    np.testing.assert_array_equal(env.get_state(), before)
    np.testing.assert_array_equal(env.sim.render(64, 48, camera_name="agentview"), rgb)  # back to fixed


# --- the XML round trip ------------------------------------------------------------------
def test_xml_round_trip_reproduces_observations():
    env = lift()
    env.reset(seed=5)  # Lift re-draws the cube size at reset: the XML must carry it
    size = env.sim.model.geom_size[env.sim.model.geom_name2id("cube_g0")].copy()
    states = []
    for a in actions(8, seed=2):
        env.step(a)
        states.append(env.sim.get_state().flatten())
    xml = env.sim.model.get_xml()

    def replay(e):
        # robomimic's reset_to: sim.reset (controls zeroed), then each state + forward
        e.sim.reset()
        out = []
        for s in states:
            e.sim.set_state_from_flattened(s)
            e.sim.forward()
            out.append(e._get_observations(force_update=True))
        return out

    observations = replay(env)
    other = lift(seed=99)
    other.reset()
    other.reset_from_xml_string(xml)
    # MuJoCo writes 6 significant digits (robosuite's saved scenes too)
    np.testing.assert_allclose(other.sim.model.geom_size[other.sim.model.geom_name2id("cube_g0")], size, rtol=1e-6)
    for got, expected in zip(replay(other), observations):
        assert list(got) == list(expected)
        for k in expected:
            # MuJoCo saves 6 significant digits (robosuite's get_xml too): sizes, body
            # frames, masses and inertias move by up to 1e-6 relative, which poses show
            # (1e-7) and joint accelerations from the forward pass (1e-6)
            atol = 1e-5 if k.endswith(("joint_acc", "proprio-state")) else 1e-6
            np.testing.assert_allclose(got[k], expected[k], rtol=0, atol=atol, err_msg=k)


def test_reset_from_xml_string_is_deterministic_and_refuses_bad_scenes():
    env = lift()
    env.reset()
    xml = env.sim.model.get_xml()
    env.reset_from_xml_string(xml)
    a = env.get_state()
    env.reset_from_xml_string(xml)
    np.testing.assert_array_equal(a, env.get_state())  # no noise, no placement
    before = env.get_state()
    with pytest.raises((ValueError, RuntimeError)):
        env.reset_from_xml_string("<mujoco><worldbody/></mujoco>")
    with pytest.raises((ValueError, RuntimeError)):
        env.reset_from_xml_string("not xml at all")
    np.testing.assert_array_equal(env.get_state(), before)
    env.step(np.zeros(7))


def test_edit_model_xml_points_assets_at_the_local_files_and_processors_run():
    env = lift()
    env.reset()
    xml = env.sim.model.get_xml()
    moved = xml.replace(suite._native.robosuite_package_dir(), "/elsewhere/site-packages/robosuite")
    assert "/elsewhere/" in moved
    edited = env.edit_model_xml(moved)
    assert "/elsewhere/" not in edited
    seen = []
    env.set_xml_processor(lambda x: seen.append(len(x)) or x)
    env.reset_from_xml_string(moved)
    assert len(seen) == 1
    with pytest.raises(TypeError):
        env.set_xml_processor(3)


def test_ep_meta():
    env = lift()
    assert env.get_ep_meta() == {}
    meta = {"lang": "lift the cube", "n": [1, 2]}
    env.set_ep_meta(meta)
    got = env.get_ep_meta()
    assert got == meta and got is not meta
    env.unset_ep_meta()
    assert env.get_ep_meta() == {}


# --- observables ---------------------------------------------------------------------
def test_observables_api():
    env = lift()
    obs = env.reset()
    assert "robot0_joint_pos" in env.observation_names
    assert {"robot0_proprio", "object"} <= env.observation_modalities
    assert env.active_observables == env.enabled_observables == env.observation_names
    env.modify_observable("robot0_joint_pos", "active", False)
    obs2 = env._get_observations(force_update=True)
    assert "robot0_joint_pos" not in obs2
    assert obs2["robot0_proprio-state"].shape[0] == obs["robot0_proprio-state"].shape[0] - 7
    assert "robot0_joint_pos" not in env.active_observables
    assert "robot0_joint_pos" not in env.observation_keys()
    assert "robot0_joint_pos" not in env.step(np.zeros(7))[0]
    env.modify_observable("robot0_joint_pos", "active", True)
    assert env._get_observations()["robot0_proprio-state"].shape == obs["robot0_proprio-state"].shape
    with pytest.raises(ValueError, match="robot0_joint_vel"):
        env.modify_observable("nope", "active", True)
    with pytest.raises(ValueError):
        env.modify_observable("robot0_joint_pos", "active", "yes")
    with pytest.raises(ValueError, match="valid options"):
        env.modify_observable("robot0_joint_pos", "colour", lambda x: x)  # the rest: test_observables.py


def test_get_observations_force_update_reads_the_current_state():
    env = lift()
    env.reset()
    env.step(np.ones(7))
    cube = env.sim.model.get_joint_qpos_addr("cube_joint0")
    env.sim.data.qpos[cube[0] : cube[0] + 3] += np.array([0.05, 0.0, 0.0])
    env.sim.forward()
    stale = env._get_observations()
    fresh = env._get_observations(force_update=True)
    assert fresh["cube_pos"][0] == pytest.approx(stale["cube_pos"][0] + 0.05)
    np.testing.assert_array_equal(fresh["cube_pos"], env.sim.data.get_body_xpos("cube_main"))


# --- robots --------------------------------------------------------------------------
def test_robots():
    env = lift()
    env.reset()
    (robot,) = env.robots
    assert robot.name == "Panda" and robot.robot_model.naming_prefix == "robot0_"
    assert robot.robot_model.joints == [f"robot0_joint{i}" for i in range(1, 8)]
    assert robot.action_dim == 7 and robot.dof == 7  # robosuite: the robot model's joints, not the gripper's
    low, high = robot.action_limits
    np.testing.assert_array_equal(low, -np.ones(7))
    right = robot.part_controllers["right"]
    assert right.name == "OSC_POSE" and right.ref_name == "gripper0_right_grip_site"
    assert right.control_delta and right.input_type == "delta"
    assert robot.composite_controller.part_controllers is robot.part_controllers
    assert robot.gripper["right"].name == "PandaGripper"
    np.testing.assert_array_equal(robot.create_action_vector({"right_gripper": [1.0]}), np.r_[np.zeros(6), 1.0])
    with pytest.raises(ValueError):
        robot.create_action_vector({"left": [1.0]})
    np.testing.assert_allclose(robot.init_qpos, [0, np.pi / 16, 0, -np.pi / 2 - np.pi / 3, 0, np.pi - 0.2, np.pi / 4])
    robot.set_robot_joint_positions(robot.init_qpos)
    np.testing.assert_array_equal(env.sim.data.qpos[:7], robot.init_qpos)
    two = suite.make("TwoArmLift", robots=["Panda", "Sawyer"], seed=1)
    assert [r.robot_model.naming_prefix for r in two.robots] == ["robot0_", "robot1_"]
    assert two.robots[1].name == "Sawyer"


def test_gym_wrapper_forwards_env_attributes():
    env = lift()
    gym_env = GymWrapper(env)
    gym_env.reset(seed=0)
    assert gym_env.sim.model.nq == env.sim.model.nq
    assert gym_env.robots[0].name == "Panda"
    with pytest.raises(AttributeError):
        gym_env.no_such_attribute


# --- install_as_robosuite ---------------------------------------------------------------
ROBOMIMIC_STYLE = textwrap.dedent(
    """
    import json, sys
    import numpy as np
    import robosuite_rs
    robosuite_rs.install_as_robosuite()
    import robosuite
    import robosuite.utils.transform_utils as T
    from robosuite.wrappers import GymWrapper
    from robosuite.controllers import load_composite_controller_config
    from robosuite.wrappers import DomainRandomizationWrapper, VisualizationWrapper
    from robosuite.utils.mjmod import CameraModder, DynamicsModder, LightingModder, TextureModder
    assert robosuite.__version__ == "1.5.2" and robosuite_rs.__version__ != "1.5.2"
    assert robosuite.__version__.split(".")[0] == "1" and int(robosuite.__version__.split(".")[1]) >= 5
    # the calls robomimic's EnvRobosuite makes, in its order
    env_meta = json.loads(sys.argv[1])
    kwargs = dict(env_meta["env_kwargs"])
    kwargs.update(has_renderer=False, has_offscreen_renderer=True, ignore_done=True, use_object_obs=True,
                  use_camera_obs=False, camera_depths=False)
    env = robosuite.make(env_meta["env_name"], **kwargs)
    for ob_name in env.observation_names:
        if ("joint_pos" in ob_name) or ("eef_vel" in ob_name):
            env.modify_observable(observable_name=ob_name, attribute="active", modifier=True)
    env.reset()
    xml = env.sim.model.get_xml()
    state = dict(model=xml, states=np.array(env.sim.get_state().flatten()), ep_meta=json.dumps(env.get_ep_meta()))
    obs0 = env._get_observations(force_update=True)
    for a in np.random.default_rng(0).uniform(-1, 1, (5, env.action_spec[0].shape[0])):
        env.step(a)
    # reset_to({"model", "states", "ep_meta"})
    env.set_ep_meta(json.loads(state["ep_meta"]))
    env.unset_ep_meta(); env.set_ep_meta({})
    env.reset()
    env.reset_from_xml_string(env.edit_model_xml(state["model"]))
    env.sim.reset()
    env.sim.set_state_from_flattened(state["states"])
    env.sim.forward()
    if hasattr(env, "update_state"):
        env.update_state()
    obs = env._get_observations(force_update=True)
    for k in obs0:
        atol = 1e-5 if k.endswith(("joint_acc", "proprio-state")) else 1e-6  # 6-digit XML
        assert np.allclose(obs[k], obs0[k], rtol=0, atol=atol), k
    pf = env.robots[0].robot_model.naming_prefix
    assert any(k.startswith(pf) for k in obs)
    r, s = env.reward(), env._check_success()
    im = env.sim.render(height=32, width=40, camera_name="agentview")[::-1]
    assert im.shape == (32, 40, 3)
    cam_id = env.sim.model.camera_name2id("agentview")
    fovy = env.sim.model.cam_fovy[cam_id]; pos = env.sim.data.cam_xpos[cam_id]; mat = env.sim.data.cam_xmat[cam_id]
    extent, znear, zfar = env.sim.model.stat.extent, env.sim.model.vis.map.znear, env.sim.model.vis.map.zfar
    ref = env.robots[0].composite_controller.part_controllers["right"].ref_name
    eef = env.sim.data.site_xpos[env.sim.model.site_name2id(ref)]
    q = T.mat2quat(env.sim.data.site_xmat[env.sim.model.site_name2id(ref)].reshape(3, 3))
    assert q.shape == (4,)
    g = GymWrapper(env)
    g.reset(seed=0)
    assert g.sim is env.sim
    print("OK", float(r), bool(s))
    """
)


@pytest.mark.parametrize("controller", [None, "OSC_POSE"])
def test_install_as_robosuite_serves_robomimics_calls(controller):
    import robosuite_rs

    env_kwargs = {"robots": ["Panda"], "control_freq": 20, "reward_shaping": False}
    if controller is not None:
        env_kwargs["controller_configs"] = robosuite_rs.load_composite_controller_config(robot="Panda")
    meta = {"env_name": "Lift", "type": 1, "env_kwargs": env_kwargs}
    out = subprocess.run(
        [sys.executable, "-c", ROBOMIMIC_STYLE, json.dumps(meta)], capture_output=True, text=True, timeout=300
    )
    assert out.returncode == 0, out.stderr[-3000:]
    assert out.stdout.startswith("OK")


def test_install_as_robosuite_refuses_the_real_one_and_is_idempotent():
    code = textwrap.dedent(
        """
        import sys, types
        import robosuite_rs
        a = robosuite_rs.install_as_robosuite()
        assert robosuite_rs.install_as_robosuite() is a
        import robosuite.utils.camera_utils, robosuite.macros, robosuite.robots
        assert robosuite.macros.IMAGE_CONVENTION == "opengl"
        assert "Panda" in robosuite.ALL_ROBOTS and "BASIC" in robosuite.ALL_COMPOSITE_CONTROLLERS
        del sys.modules["robosuite"]
        sys.modules["robosuite"] = types.ModuleType("robosuite")
        try:
            robosuite_rs.install_as_robosuite()
        except RuntimeError as e:
            print("refused", e)
        """
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-3000:]
    assert "refused" in out.stdout


def test_env_model_and_timesteps(tmp_path):
    import mujoco

    env = suite.make("Lift", control_freq=25, has_offscreen_renderer=False)
    env.reset(seed=0)
    assert env.model_timestep == env.sim.model.opt.timestep == 0.002
    assert env.control_timestep == pytest.approx(0.04)
    # env.model's XML compiles to the env's own model (same bodies, same names).
    model = mujoco.MjModel.from_xml_string(env.model.get_xml())
    assert model.nbody == env.sim.model._model.nbody
    assert [model.body(i).name for i in range(model.nbody)] == list(env.sim.model.body_names)
    assert env.model.worldbody.find(".//body[@name='cube_main']") is not None
    env.model.save_model(str(tmp_path / "scene.xml"), pretty=True)
    assert mujoco.MjModel.from_xml_path(str(tmp_path / "scene.xml")).nbody == model.nbody


def test_robosuites_image_convention_macro_flips_camera_images():
    code = textwrap.dedent(
        """
        import numpy as np, robosuite_rs
        robosuite_rs.install_as_robosuite()
        import robosuite, robosuite.macros as macros
        kw = dict(use_camera_obs=True, camera_names="agentview", camera_heights=32, camera_widths=32)
        a = robosuite.make("Lift", **kw)
        macros.IMAGE_CONVENTION = "opencv"   # as robosuite's users set it, before making the env
        b = robosuite.make("Lift", **kw)
        ia, ib = a.reset(seed=0)["agentview_image"], b.reset(seed=0)["agentview_image"]
        assert not np.array_equal(ia, ib)
        assert np.array_equal(ia[::-1], ib)
        print("OK")
        """
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    assert "OK" in out.stdout


def test_model_mujoco_objects_are_the_tasks_objects() -> None:
    # robosuite's env.model.mujoco_objects: the task's objects in its order, with names
    # that exist in the compiled model and the extent placement uses.
    env = lift()
    env.reset(seed=0)  # a reset draws the cube's size anew (robosuite: a new model, new objects)
    (cube,) = env.model.mujoco_objects
    assert (cube.name, cube.naming_prefix, cube.root_body, cube.joints) == ("cube", "cube_", "cube_main", ["cube_joint0"])
    m = env.sim.model
    assert m.body_name2id(cube.root_body) >= 0
    assert all(m.geom_name2id(g) >= 0 for g in cube.contact_geoms + cube.visual_geoms)
    assert all(m.site_name2id(s) >= 0 for s in cube.sites)
    # Placed with its bottom z_offset (0.01) above the table top (0.8), before any step.
    z = env.sim.data.body_xpos[m.body_name2id(cube.root_body)][2] + cube.bottom_offset[2]
    assert abs(z - 0.81) < 1e-9
    half = m.geom_size[m.geom_name2id(cube.contact_geoms[0])]
    assert np.allclose(cube.top_offset, [0, 0, half[2]]) and np.allclose(cube.bottom_offset, [0, 0, -half[2]])
    # PickPlace: robosuite's visual objects, then the physical ones.
    pick = suite.make("PickPlace", robots="Panda", has_renderer=False, use_camera_obs=False)
    names = [o.name for o in pick.model.mujoco_objects]
    assert names == ["VisualMilk", "VisualBread", "VisualCereal", "VisualCan", "Milk", "Bread", "Cereal", "Can"]
    assert all(pick.sim.model.body_name2id(o.root_body) >= 0 for o in pick.model.mujoco_objects)


def test_an_env_is_freed_with_its_last_reference() -> None:
    # No reference cycles through env.sim, env.robots, env.model, rendering, observables
    # or the GymWrapper: the env (and its simulation's memory) goes with its last
    # reference, without waiting for Python's cycle collector.
    import weakref

    from robosuite_rs.observables import create_gaussian_noise_corrupter

    gc.collect()
    gc.disable()
    try:
        env = lift()
        env.reset(seed=0)
        _ = (env.sim.data.qpos, env.robots[0].dof, env.model.mujoco_objects, env.sim.render(16, 16, camera_name="agentview"))
        env.modify_observable("cube_pos", "corrupter", create_gaussian_noise_corrupter(0.0, 0.01))
        gym_env = GymWrapper(env)
        gym_env.reset(seed=0)
        robot = env.robots[0]
        ref = weakref.ref(env)
        del env, gym_env, _
        assert ref() is None
        with pytest.raises(ReferenceError, match="env was freed"):
            robot._joint_positions  # noqa: B018 (reads the env)
    finally:
        gc.enable()
