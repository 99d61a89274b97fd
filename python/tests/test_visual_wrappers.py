"""robosuite's VisualizationWrapper, ``env.visualize`` and DomainRandomizationWrapper with
its modders, against robosuite 1.5.2 (``fixtures/robosuite_utils/visualization.json``,
recorded by ``scripts/record_visualization.py``)."""

from __future__ import annotations

import base64
import json
import math
import zlib
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import robosuite_rs as suite
from robosuite_rs.utils.mjmod import CameraModder, DynamicsModder, LightingModder, ModderError
from robosuite_rs.wrappers import DomainRandomizationWrapper, VisualizationWrapper
from robosuite_rs._visual_wrappers import DEFAULT_COLOR_ARGS

FIXTURE = Path(__file__).parent / "fixtures" / "robosuite_utils" / "visualization.json"
DATA = json.loads(FIXTURE.read_text())
SIZE = DATA["size"]
INDICATORS = [
    "default",
    {"name": "marker", "type": "box", "size": [0.02, 0.02, 0.02], "rgba": [0, 0, 1, 1], "pos": [0.1, -0.1, 1.0]},
]
ALL_OFF = {"env": False, "robots": False, "grippers": False}
ALL_ON = {"env": True, "robots": True, "grippers": True}


def make(task: str = "Lift", **kwargs: Any) -> Any:
    robots = ["Panda", "Panda"] if task.startswith("TwoArm") else "Panda"
    args = dict(has_renderer=False, has_offscreen_renderer=True, use_camera_obs=False, seed=0)
    args.update(kwargs)
    return suite.make(task, robots=robots, **args)


def decode_frame(text: str) -> np.ndarray:
    return np.frombuffer(zlib.decompress(base64.b64decode(text)), dtype=np.uint8).reshape(SIZE, SIZE, 3)


def site_rgba(env: Any) -> dict[str, np.ndarray]:
    m = env.sim.model
    return {m.site_id2name(i): np.array(m.site_rgba[i]) for i in range(m.nsite)}


def mask_figures(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, float, np.ndarray]:
    """Pixels where two frames differ: the mask, its area and its centroid (row, col)."""
    mask = np.abs(a.astype(int) - b.astype(int)).max(axis=2) > 40
    rows, cols = np.nonzero(mask)
    return mask, float(mask.sum()), np.array([rows.mean(), cols.mean()])


# --- VisualizationWrapper ------------------------------------------------------------


@pytest.fixture(scope="module", params=["Lift", "TwoArmLift", "Stack", "Door", "NutAssemblySquare", "PickPlaceCan"])
def wrapped(request: Any) -> Any:
    env = VisualizationWrapper(make(request.param), indicator_configs=INDICATORS)
    yield request.param, env
    env.close()


def test_sites_and_indicators_as_robosuite(wrapped: Any) -> None:
    task, env = wrapped
    ref = DATA["tasks"][task]
    assert sorted(env.get_visualization_settings()) == ref["settings"]
    assert [list(o.sites) for o in env.model.mujoco_objects] == ref["object_sites"]
    assert [list(r.robot_model.sites) for r in env.robots] == ref["robot_sites"]
    assert [{arm: r.gripper[arm].sites for arm in r.arms} for r in env.robots] == ref["gripper_sites"]
    assert env.get_indicator_names() == ref["indicator_names"]
    m = env.sim.model
    for name, want in ref["indicators"].items():
        np.testing.assert_allclose(m.body_pos[m.body_name2id(name + "_body")], want["body_pos"], atol=1e-12)
        site = m.site_name2id(name)
        assert int(m.site_type[site]) == want["site_type"]
        np.testing.assert_allclose(m.site_size[site], want["site_size"], atol=1e-7)
        np.testing.assert_allclose(m.site_rgba[site], want["site_rgba"], atol=1e-7)


def test_visualize_toggles_and_colours_as_robosuite(wrapped: Any) -> None:
    task, env = wrapped
    ref = DATA["tasks"][task]
    env.reset()
    ours = site_rgba(env)
    assert set(ours) == set(ref["after_reset"])
    for name, rgba in ref["after_reset"].items():
        assert np.sign(ours[name][3]) == np.sign(rgba[3]), name
    env.sim.set_state_from_flattened(np.array(ref["state"]))
    env.sim.forward()
    for settings, want in zip(
        [
            ALL_ON,
            {"env": True, "robots": False, "grippers": True},
            ALL_OFF,
            {"env": False, "robots": True, "grippers": True},
        ],
        ref["sequence"],
    ):
        env.env.visualize(vis_settings=settings)
        ours = site_rgba(env)
        for name, rgba in want.items():
            np.testing.assert_allclose(ours[name], rgba, atol=2e-6, err_msg=f"{task} {settings} {name}")


def test_frames_show_indicators_and_sites_where_robosuites_do() -> None:
    ref = DATA["tasks"]["Lift"]
    env = VisualizationWrapper(make("Lift"), indicator_configs=INDICATORS)
    env.sim.set_state_from_flattened(np.array(ref["state"]))
    env.set_indicator_pos("marker", ref["far"])
    frames: dict[str, dict[str, np.ndarray]] = {}
    for label, settings, pos in [
        ("hidden", ALL_OFF, ref["far"]),
        ("indicator", ALL_OFF, ref["indicator_pos"]),
        ("shown", ALL_ON, ref["far"]),
    ]:
        env.env.visualize(vis_settings=settings)
        env.set_indicator_pos("indicator0", pos)
        env.sim.forward()
        frames[label] = {c: env.sim.render(SIZE, SIZE, camera_name=c) for c in DATA["cameras"]}
    for camera in DATA["cameras"]:
        theirs = {k: decode_frame(v[camera]) for k, v in ref["frames"].items()}
        for label in ("indicator", "shown"):
            m_ours, area_ours, c_ours = mask_figures(frames[label][camera], frames["hidden"][camera])
            m_theirs, area_theirs, c_theirs = mask_figures(theirs[label], theirs["hidden"])
            where = (
                f"{camera} {label}: ours {area_ours:.0f} px at {c_ours}, "
                f"robosuite {area_theirs:.0f} px at {c_theirs}"
            )
            assert area_theirs >= 3 and area_ours >= 3, where
            assert 0.6 <= area_ours / area_theirs <= 1.6, where
            assert np.linalg.norm(c_ours - c_theirs) <= 1.5, where
            iou = (m_ours & m_theirs).sum() / (m_ours | m_theirs).sum()
            assert iou >= 0.5, f"{where}, IoU {iou:.2f}"
    env.close()


def test_settings_follow_steps_and_resets() -> None:
    env = VisualizationWrapper(make("Lift"))
    assert env.get_indicator_names() == []
    robot_site = env.robots[0].robot_model.sites[0]
    grip_site = env.robots[0].gripper["right"].important_sites["grip_site"]
    m = env.sim.model
    assert m.site_rgba[m.site_name2id(robot_site)][3] > 0
    env.set_visualization_setting("robots", False)
    env.step(np.zeros(env.action_dim))
    assert m.site_rgba[m.site_name2id(robot_site)][3] < 0
    assert m.site_rgba[m.site_name2id(grip_site)][3] > 0
    # A plain reset hides every site again, as robosuite's reset does.
    env.env.reset()
    for name in [robot_site, grip_site] + env.model.mujoco_objects[0].sites:
        assert m.site_rgba[m.site_name2id(name)][3] < 0, name
    env.reset()
    assert m.site_rgba[m.site_name2id(grip_site)][3] > 0
    with pytest.raises(ValueError, match="Invalid visualization setting"):
        env.set_visualization_setting("walls", True)
    with pytest.raises(KeyError):
        env.env.visualize({"env": True})
    env.close()


@pytest.mark.parametrize(
    "configs, match",
    [
        ({"type": "sphere"}, "Name must be specified"),
        ("big", "must be 'default'"),
        ({"name": "a", "colour": [1, 0, 0, 1]}, "unknown site attribute"),
        ({"name": "a", "size": [float("nan")]}, "finite"),
        ({"name": "a", "size": [-0.1]}, "negative"),
        ({"name": "a", "type": "cone"}, "type must be one of"),
        ({"name": "a", "pos": [0, 1]}, "3 values"),
        (["default", {"name": "indicator0"}], "distinct"),
        ({"name": "table_top"}, "site of that name"),
    ],
)
def test_bad_indicator_configs_leave_the_env_unchanged(configs: Any, match: str) -> None:
    env = make("Lift")
    env.reset()
    nsite, xml, processors = env.sim.model.nsite, env.model.get_xml(), list(env._xml_processors)
    with pytest.raises(ValueError, match=match) as info:
        VisualizationWrapper(env, indicator_configs=configs)
    assert isinstance(info.value, AssertionError)
    assert env.sim.model.nsite == nsite and env.model.get_xml() == xml and env._xml_processors == processors
    env.step(np.zeros(env.action_dim))
    wrapped = VisualizationWrapper(env, indicator_configs="default")
    m = env.sim.model
    wrapped.set_indicator_pos("indicator0", [0.1, 0.2, 1.3])
    wrapped.step(np.zeros(env.action_dim))
    np.testing.assert_allclose(env.sim.data.get_site_xpos("indicator0"), [0.1, 0.2, 1.3])
    wrapped.reset()  # a hard reset (the default) puts it back, as robosuite's reload does
    np.testing.assert_array_equal(m.body_pos[m.body_name2id("indicator0_body")], [0, 0, 0])
    with pytest.raises(ValueError, match="Invalid indicator name"):
        wrapped.set_indicator_pos("nope", [0, 0, 1])
    with pytest.raises(ValueError, match="3 finite numbers"):
        wrapped.set_indicator_pos("indicator0", [0, float("inf"), 1])
    env.close()


def test_segmentation_envs_are_refused() -> None:
    env = make("Lift", use_camera_obs=True, camera_names="agentview", camera_heights=16, camera_widths=16,
               camera_segmentations="element")
    with pytest.raises(ValueError, match="segmentations"):
        VisualizationWrapper(env)
    env.close()


# --- the modders against robosuite's -------------------------------------------------


@pytest.fixture(scope="module")
def lift() -> Any:
    env = make("Lift", has_offscreen_renderer=False)
    env.reset()
    yield env
    env.close()


def test_camera_and_lighting_modders_draw_robosuites_values(lift: Any) -> None:
    ref = DATA["modders"]
    cams = CameraModder(lift.sim, random_state=np.random.RandomState(ref["seed"]))
    assert list(cams.camera_names) == list(ref["camera"])
    for name, d in ref["camera_defaults"].items():
        for key, value in d.items():
            np.testing.assert_allclose(cams._defaults[name][key], value, atol=1e-12, err_msg=f"{name} {key}")
    cams.randomize()
    for name, want in ref["camera"].items():
        np.testing.assert_allclose(cams.get_pos(name), want["pos"], atol=1e-12)
        # robosuite's mat2quat works in float32.
        np.testing.assert_allclose(cams.get_quat(name), want["quat"], atol=1e-6)
        assert math.isclose(cams.get_fovy(name), want["fovy"], abs_tol=1e-12)
    cams.restore_defaults()
    lights = LightingModder(lift.sim, random_state=np.random.RandomState(ref["seed"]))
    assert len(lights.light_names) == len(ref["light"])
    lights.randomize()
    for name, want in zip(lights.light_names, ref["light"].values()):
        for key in ("pos", "dir", "specular", "ambient", "diffuse"):
            np.testing.assert_allclose(getattr(lights, f"get_{key}")(name), want[key], atol=1e-6, err_msg=key)
        assert int(lights.get_active(name)) == want["active"]
    lights.restore_defaults()


def test_dynamics_modder_draws_robosuites_perturbations(lift: Any) -> None:
    ref = DATA["modders"]["dynamics"]
    dyn = DynamicsModder(lift.sim, random_state=np.random.RandomState(DATA["modders"]["seed"]))
    m = lift.sim.model
    names = {"body": list(dyn.body_names), "geom": list(dyn.geom_names), "joint": list(dyn.joint_names)}
    for group in ("body", "geom", "joint"):
        assert names[group] == [row[0] for row in ref["after"][group]], group
    defaults = {
        "body": {n: [d["position"], d["quaternion"], d["inertia"], d["mass"]] for n, d in dyn.body_defaults.items()},
        "geom": {n: [d["friction"], d["solref"], d["solimp"]] for n, d in dyn.geom_defaults.items()},
        "joint": {
            n: [d["stiffness"], d["frictionloss"], d["damping"], d["armature"]] for n, d in dyn.joint_defaults.items()
        },
    }
    dyn.randomize()
    compared = 0
    for group, rows in ref["after"].items():
        for row in rows:
            name = row[0]
            if name is None:
                continue
            if group == "body":
                i = m.body_name2id(name)
                ours = [m.body_pos[i], m.body_quat[i], m.body_inertia[i], m.body_mass[i]]
            elif group == "geom":
                i = m.geom_name2id(name)
                ours = [m.geom_friction[i], m.geom_solref[i], m.geom_solimp[i]]
            else:
                i = m.joint_name2id(name)
                dofs = [k for k, v in enumerate(m.dof_jntid) if v == i]
                ours = [m.jnt_stiffness[i], m.dof_frictionloss[dofs], m.dof_damping[dofs], m.dof_armature[dofs]]
            for k, (value, want) in enumerate(zip(ours, row[1:])):
                theirs_default = ref["defaults"][group][name][k]
                # Same defaults (Lift's cube size is drawn at reset, so not its mass): same values.
                if np.allclose(defaults[group][name][k], theirs_default, rtol=0, atol=1e-12):
                    np.testing.assert_allclose(value, want, rtol=1e-12, atol=1e-12, err_msg=f"{group} {name} {k}")
                    compared += 1
    assert compared > 0.9 * sum(len(r) * (len(r[0]) - 1) for r in ref["after"].values())
    assert math.isclose(m.opt.density, ref["density"], abs_tol=1e-12)
    assert math.isclose(m.opt.viscosity, ref["viscosity"], abs_tol=1e-12)
    dyn.restore_defaults()
    for name, d in dyn.geom_defaults.items():
        np.testing.assert_array_equal(m.geom_friction[m.geom_name2id(name)], d["friction"])


# --- DomainRandomizationWrapper --------------------------------------------------------


def camera_env(**kwargs: Any) -> Any:
    return make(
        "Lift", use_camera_obs=True, camera_names="agentview", camera_heights=SIZE, camera_widths=SIZE, **kwargs
    )


def model_params(env: Any) -> dict[str, np.ndarray]:
    m = env.sim.model
    keys = ["cam_pos", "cam_quat", "cam_fovy", "light_pos", "light_dir", "light_diffuse", "light_active",
            "geom_rgba", "geom_friction", "geom_solref", "body_mass", "body_pos", "dof_damping", "tex_data",
            "mat_shininess"]
    out = {k: np.array(getattr(m, k)) for k in keys}
    out["density"] = np.array(m.opt.density)
    return out


def textured(m: Any, name: Any) -> bool:
    mat = m.geom_matid[m.geom_name2id(name)]
    return bool(mat >= 0 and m.mat_texid[mat].max() >= 0)


def test_same_seed_same_domain_other_seed_other_domain() -> None:
    base = [camera_env(), camera_env()]
    first, obs, params = [], [], []
    # Two envs with seed 5, then the first again with seed 6 (each reset restores the
    # wrapper's defaults first).
    for env, seed in [(base[0], 5), (base[1], 5), (base[0], 6)]:
        m = env.sim.model
        # Every geom but the large textures (walls, table, cube: their draws take a while).
        small = [n for n in m.geom_names if n is not None and (n == "floor" or not textured(m, n))]
        color = dict(DEFAULT_COLOR_ARGS, geom_names=small)
        e = DomainRandomizationWrapper(env, seed=seed, randomize_every_n_steps=0, color_randomization_args=color)
        first.append(e.reset()["agentview_image"])
        for _ in range(2):
            o, *_ = e.step(np.zeros(e.action_dim))
        obs.append(o)
        params.append(model_params(e))
        e.restore_default_domain()
    np.testing.assert_array_equal(first[0], first[1])
    np.testing.assert_array_equal(obs[0]["agentview_image"], obs[1]["agentview_image"])
    np.testing.assert_array_equal(obs[0]["robot0_eef_pos"], obs[1]["robot0_eef_pos"])
    for k in params[0]:
        np.testing.assert_array_equal(params[0][k], params[1][k], err_msg=k)
    assert not np.array_equal(obs[0]["agentview_image"], obs[2]["agentview_image"])
    for k in ("cam_pos", "light_pos", "geom_friction", "body_mass", "tex_data"):
        assert not np.array_equal(params[0][k], params[2][k]), k
    for e in base:
        e.close()


def test_draws_stay_in_robosuites_ranges_and_other_envs_are_untouched() -> None:
    env = make("Lift", has_offscreen_renderer=False)
    other = make("Lift", has_offscreen_renderer=False)
    env.reset()
    other.reset()
    before = model_params(env)
    other_before = model_params(other)
    dr = DomainRandomizationWrapper(env, seed=1, randomize_on_reset=False)
    dr.randomize_domain()
    after = model_params(env)
    m = env.sim.model
    # Cameras: position +-0.01 per axis, fovy +-5 degrees, rotation at most 0.087 rad.
    assert np.all(np.abs(after["cam_pos"] - before["cam_pos"]) <= 0.01 + 1e-12)
    assert np.all(np.abs(after["cam_fovy"] - before["cam_fovy"]) <= 5.0 + 1e-12)
    dots = np.abs(np.sum(after["cam_quat"] * before["cam_quat"], axis=1)).clip(max=1.0)
    assert np.all(2 * np.arccos(dots) <= 0.087 + 1e-9)
    # Lights: position +-0.1, colours +-0.1, direction turned at most 0.35 rad.
    assert np.all(np.abs(after["light_pos"] - before["light_pos"]) <= 0.1 + 1e-6)
    assert np.all(np.abs(after["light_diffuse"] - before["light_diffuse"]) <= 0.1 + 1e-6)
    cos = np.sum(after["light_dir"] * before["light_dir"], axis=1) / (
        np.linalg.norm(after["light_dir"], axis=1) * np.linalg.norm(before["light_dir"], axis=1)
    )
    assert np.all(np.arccos(cos.clip(-1, 1)) <= 0.35 + 1e-6)
    # Dynamics (the wrapper's defaults): friction +-10 %, mass +-2 %, body position +-1.5 mm,
    # damping +-0.01 (not below 0), solref clipped to [0, 1], density +-10 %.
    ratio = after["geom_friction"] / np.where(before["geom_friction"] == 0, 1, before["geom_friction"])
    assert np.all((ratio >= 0.9 - 1e-12) & (ratio <= 1.1 + 1e-12))
    massive = before["body_mass"] > 0
    assert np.all(np.abs(after["body_mass"][massive] / before["body_mass"][massive] - 1) <= 0.02 + 1e-12)
    assert np.all(np.abs(after["body_pos"] - before["body_pos"]) <= 0.0015 + 1e-12)
    assert np.all(np.abs(after["dof_damping"] - before["dof_damping"]) <= 0.01 + 1e-12)
    assert np.all(after["dof_damping"] >= 0) and np.all((after["geom_solref"] >= 0) & (after["geom_solref"] <= 1))
    assert abs(float(after["density"]) / float(before["density"]) - 1) <= 0.1 + 1e-12
    # Colours (local): untextured geoms 0.8 * default + 0.2 * uniform.
    untextured = [i for i in range(m.ngeom) if m.geom_matid[i] < 0 and m.geom_id2name(i) in dr.tex_modder.geom_names]
    assert untextured
    for i in untextured:
        low = 0.8 * before["geom_rgba"][i, :3]
        assert np.all((after["geom_rgba"][i, :3] >= low - 1e-6) & (after["geom_rgba"][i, :3] <= low + 0.2 + 1e-6))
    assert not np.array_equal(after["tex_data"], before["tex_data"])
    # The other env of the same configuration keeps its model.
    for k, v in model_params(other).items():
        np.testing.assert_array_equal(v, other_before[k], err_msg=k)
    dr.restore_default_domain()
    restored = model_params(env)
    # As robosuite's, the textured geoms stay whitened; everything else is restored.
    textured = [
        i
        for i in range(m.ngeom)
        if m.geom_id2name(i) in dr.tex_modder.geom_names and dr.tex_modder._check_geom_for_texture(m.geom_id2name(i))
    ]
    assert textured
    np.testing.assert_array_equal(restored["geom_rgba"][textured], 1.0)
    restored["geom_rgba"][textured] = before["geom_rgba"][textured]
    # robosuite's whitening sets every geom's alpha to 1; the colours come back.
    restored["geom_rgba"][:, 3] = before["geom_rgba"][:, 3]
    for k, v in restored.items():
        np.testing.assert_array_equal(v, before[k], err_msg=k)
    env.close()
    other.close()


def test_texture_changes_reach_the_frames() -> None:
    env = camera_env()
    frame0 = env.reset()["agentview_image"].copy()
    assert textured(env.sim.model, "table_visual")
    dr = DomainRandomizationWrapper(
        env,
        seed=2,
        randomize_camera=False,
        randomize_lighting=False,
        randomize_dynamics=False,
        color_randomization_args={"geom_names": ["table_visual"], "texture_variations": ["checker"],
                                  "randomize_skybox": False},
        randomize_on_reset=False,
        randomize_every_n_steps=0,
    )
    dr.randomize_domain()
    # Only textures changed (materials whitened, bitmaps replaced): the frame shows them.
    frame1 = env._get_observations(force_update=True)["agentview_image"]
    assert np.abs(frame1.astype(int) - frame0.astype(int)).mean() > 5
    dr.restore_default_domain()
    frame2 = env._get_observations(force_update=True)["agentview_image"]
    assert np.abs(frame2.astype(int) - frame0.astype(int)).max() <= 2
    env.close()


def test_randomize_every_n_steps() -> None:
    env = make("Lift", has_offscreen_renderer=False)
    dr = DomainRandomizationWrapper(env, seed=0, randomize_color=False, randomize_lighting=False,
                                    randomize_dynamics=False, randomize_every_n_steps=2)
    dr.reset()
    seen = [np.array(env.sim.model.cam_pos)]
    for _ in range(4):
        dr.step(np.zeros(env.action_dim))
        seen.append(np.array(env.sim.model.cam_pos))
    changed = [not np.array_equal(a, b) for a, b in zip(seen, seen[1:])]
    assert changed == [True, False, True, False]
    env.close()


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"camera_randomization_args": {"position_perturbation_size": -0.1}}, "finite number >= 0"),
        ({"lighting_randomization_args": {"diffuse_perturbation_size": float("nan")}}, "finite number >= 0"),
        ({"dynamics_randomization_args": {"mass_perturbation_ratio": float("inf")}}, "finite number >= 0"),
        ({"camera_randomization_args": {"camera_names": ["nowhere"]}}, "unknown camera"),
        ({"camera_randomization_args": {"fovy_perturbation_size": 90.0}}, "out of \\(0, 180\\)"),
        ({"dynamics_randomization_args": {"joint_names": ["robot0_joint99"]}}, "unknown joint"),
        ({"color_randomization_args": {"texture_variations": ["stripes"]}}, "texture_variations"),
        ({"color_randomization_args": {"local_rgb_interpolation": 1.5}}, "at most 1"),
        ({"lighting_randomization_args": {"randomise_position": True}}, "unknown argument"),
        ({"camera_randomization_args": {"randomize_position": False, "randomize_rotation": False,
                                        "randomize_fovy": False}}, "needs one of"),
        ({"seed": -1}, "seed"),
        ({"seed": 1.5}, "seed"),
        ({"randomize_every_n_steps": -2}, "randomize_every_n_steps"),
        ({"randomize_color": "yes"}, "randomize_color"),
    ],
)
def test_bad_randomization_arguments_leave_the_env_unchanged(lift: Any, kwargs: dict[str, Any], match: str) -> None:
    before = model_params(lift)
    with pytest.raises(ValueError, match=match) as info:
        DomainRandomizationWrapper(lift, **kwargs)
    assert isinstance(info.value, AssertionError)
    for k, v in model_params(lift).items():
        np.testing.assert_array_equal(v, before[k], err_msg=k)


def test_robosuite_import_paths() -> None:
    import robosuite_rs.utils.mjmod as mjmod
    from robosuite_rs import wrappers

    assert {"TextureModder", "LightingModder", "CameraModder", "DynamicsModder"} <= set(mjmod.__all__)
    assert wrappers.VisualizationWrapper is VisualizationWrapper
    assert wrappers.DomainRandomizationWrapper is DomainRandomizationWrapper
    with pytest.raises(ModderError):
        CameraModder(object(), random_state=np.random.default_rng(0))


def test_without_a_seed_the_envs_seed_decides() -> None:
    params = []
    for seed in (7, 7, 8):
        env = make("Lift", has_offscreen_renderer=False, seed=seed)
        dr = DomainRandomizationWrapper(env, randomize_color=False, randomize_every_n_steps=0)
        dr.reset()
        params.append(model_params(env))
        env.close()
    for k in ("cam_pos", "light_pos", "geom_friction"):
        np.testing.assert_array_equal(params[0][k], params[1][k], err_msg=k)
        assert not np.array_equal(params[0][k], params[2][k]), k
