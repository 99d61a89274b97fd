"""robosuite's `make` arguments beyond the RL loop: the tasks' own constructor arguments,
`lite_physics`, `render_gpu_device_id`, `camera_depths=None`, controller configs with keys
robosuite ignores, and the bimanual set-up name."""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest

import robosuite_rs as suite

from .conftest import QUIET


def test_task_arguments_are_robosuites_with_their_defaults() -> None:
    # The recorded robosuite 1.5.2 constructor arguments of every task (see
    # scripts/record_task_args.py) are this package's, with the same defaults.
    from pathlib import Path

    fixture = Path(__file__).resolve().parents[2] / "robosuite-env/tests/fixtures/task_args.json"
    recorded = json.loads(fixture.read_text())["tasks"]
    for name in suite.ALL_ENVIRONMENTS:
        ours = suite.task_arguments(name)
        for arg, default in recorded[name].items():
            if arg == "task_config":
                continue
            assert arg in ours, (name, arg)
            if isinstance(default, list):
                assert np.array_equal(np.asarray(ours[arg], float), np.asarray(default, float)), (name, arg)
            else:
                assert ours[arg] == default, (name, arg, ours[arg], default)


def test_task_arguments_reach_the_scene() -> None:
    env = suite.make("Lift", table_full_size=(1.0, 0.6, 0.05), table_friction=np.array([0.5, 0.005, 0.0001]), **QUIET)
    env.reset(seed=0)
    m = env.sim.model
    assert np.array_equal(m.geom_size[m.geom_name2id("table_collision")], [0.5, 0.3, 0.025])
    assert np.array_equal(m.geom_friction[m.geom_name2id("table_collision")], [0.5, 0.005, 0.0001])
    door = suite.make("Door", use_latch=False, **QUIET)
    assert "handle_qpos" not in door.observation_names
    assert "handle_qpos" in suite.make("Door", **QUIET).observation_names
    milk = suite.make("PickPlace", single_object_mode=2, object_type="milk", **QUIET)
    assert list(milk.reset(seed=0)) == list(suite.make("PickPlaceMilk", **QUIET).reset(seed=0))
    wipe = suite.make("Wipe", task_config={"num_markers": 40}, **QUIET)
    assert len([n for n in wipe.sim.model.body_names if n.startswith("contact")]) == 40
    # A copy made by pickling keeps the task's arguments.
    import pickle

    again = pickle.loads(pickle.dumps(env))
    assert np.array_equal(again.sim.model.geom_size[m.geom_name2id("table_collision")], [0.5, 0.3, 0.025])


@pytest.mark.parametrize(
    ("env_name", "kwargs", "error", "match"),
    [
        ("Door", {"table_full_size": (1, 1, 1)}, TypeError, "Door's own: use_latch"),
        ("Door", {"use_latch": "yes"}, ValueError, "use_latch"),
        ("Lift", {"table_full_size": (1.0, 1.0)}, ValueError, "table_full_size"),
        ("Lift", {"table_full_size": (1.0, float("nan"), 0.05)}, ValueError, "finite"),
        ("PickPlaceMilk", {"single_object_mode": 0}, TypeError, "single_object_mode"),
        ("PickPlace", {"object_type": "pizza"}, ValueError, "milk"),
        ("PickPlace", {"single_object_mode": 2}, ValueError, "object_type"),
        ("NutAssembly", {"single_object_mode": 5}, ValueError, "single_object_mode"),
        ("Wipe", {"task_config": {"num_markers": 0}}, ValueError, "num_markers"),
        ("Wipe", {"task_config": {"print_results": True}}, NotImplementedError, "print_results"),
        ("TwoArmHandover", {"prehensile": False}, NotImplementedError, "prehensile"),
        ("Lift", {"render_gpu_device_id": -2}, ValueError, "render_gpu_device_id"),
        ("Lift", {"lite_physics": "no"}, ValueError, "lite_physics"),
    ],
)
def test_bad_arguments_are_clear_errors(env_name: str, kwargs: dict, error: type, match: str) -> None:
    with pytest.raises(error, match=match):
        suite.make(env_name, **kwargs, **QUIET)


def test_lite_physics_off_gives_robosuites_same_trajectory() -> None:
    # robosuite 1.5.2's two substep orders give bit-identical Lift trajectories.
    a = suite.make("Lift", seed=3, **QUIET)
    b = suite.make("Lift", seed=3, lite_physics=False, **QUIET)
    a.reset()
    b.reset()
    rng = np.random.default_rng(1)
    for _ in range(10):
        act = rng.uniform(-1, 1, 7)
        a.step(act)
        b.step(act)
    assert np.array_equal(a.get_state(), b.get_state())


def test_robomimics_arguments_are_taken() -> None:
    # What robomimic's EnvRobosuite passes: a GPU id, camera_depths=None, and its v1.5
    # datasets' controller configs with keys robosuite 1.5 ignores (a warning names them).
    config = suite.load_composite_controller_config(robot="Panda")
    config["body_parts"]["right"].update(damping=1, damping_limits=[0, 10], control_delta=True)
    with pytest.warns(UserWarning, match=r"body_parts\.right\.damping, body_parts\.right\.damping_limits"):
        env = suite.make("Lift", render_gpu_device_id=0, camera_depths=None, controller_configs=config, **QUIET)
    plain = suite.make("Lift", **QUIET)
    env.reset(seed=0)
    plain.reset(seed=0)
    act = np.full(7, 0.3)
    assert np.array_equal(env.step(act)[0]["robot0_eef_pos"], plain.step(act)[0]["robot0_eef_pos"])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        suite.make("Lift", controller_configs=suite.load_composite_controller_config(robot="Panda"), **QUIET)


def test_bimanual_is_robosuites_single_robot_set_up() -> None:
    env = suite.make("TwoArmLift", robots="Baxter", env_configuration="bimanual", **QUIET)
    assert env.action_dim == 14
    with pytest.raises(ValueError, match="env_configuration"):
        suite.make("TwoArmLift", robots=["Panda", "Panda"], env_configuration="bimanual", **QUIET)


def test_wipe_goes_on_after_its_early_termination_with_ignore_done() -> None:
    env = suite.make("Wipe", ignore_done=True, **QUIET)
    env.reset(seed=0)
    s = env.get_state()
    s[1] = 2.85  # joint 1 near its limit: Wipe terminates
    env.set_state(s)
    assert env.step(np.zeros(6))[2]
    assert env.step(np.zeros(6))[2]  # robosuite keeps stepping


def test_placement_initializer_is_robosuites_uniform_sampler() -> None:
    from robosuite_rs.utils.placement_samplers import UniformRandomSampler

    sampler = UniformRandomSampler(
        name="ObjectSampler", x_range=[0.1, 0.1], y_range=[-0.2, -0.2], rotation=0.0,
        ensure_object_boundary_in_range=False, reference_pos=(0, 0, 0.8), z_offset=0.01,
    )
    env = suite.make("Lift", placement_initializer=sampler, **QUIET)
    for seed in range(3):
        obs = env.reset(seed=seed)
        np.testing.assert_allclose(obs["cube_pos"][:2], [0.1, -0.2], atol=1e-12)
    with pytest.raises(TypeError, match="placement_initializer"):
        suite.make("ToolHang", placement_initializer=sampler, **QUIET)  # robosuite's takes none
    with pytest.raises(TypeError, match="UniformRandomSampler"):
        suite.make("Lift", placement_initializer=object(), **QUIET)
    with pytest.raises(ValueError, match="x_range"):
        UniformRandomSampler(name="s", y_range=[0, 1])
    with pytest.raises(ValueError, match="rotation_axis"):
        UniformRandomSampler(name="s", x_range=[0, 1], y_range=[0, 1], rotation_axis="w")
    with pytest.raises(TypeError, match="mujoco_objects"):
        UniformRandomSampler(name="s", mujoco_objects=["cube"], x_range=[0, 1], y_range=[0, 1])


def test_base_types_choose_the_robots_mount() -> None:
    env = suite.make("Stack", base_types="NullMount", **QUIET)
    env.reset(seed=0)
    assert env.sim.data.get_body_xpos("robot0_base")[2] == 0.0  # no pedestal: on the floor
    assert "fixed_mount0_pedestal" not in env.sim.model.body_names
    two = suite.make("TwoArmLift", robots=["Panda", "Sawyer"], base_types=["default", "NullMount"], **QUIET)
    assert "fixed_mount0_pedestal" in two.sim.model.body_names
    assert "fixed_mount1_pedestal" not in two.sim.model.body_names
    with pytest.raises(ValueError, match="NullMount"):
        suite.make("Lift", base_types="Pedestal", **QUIET)
    with pytest.raises(ValueError, match="one per robot"):
        suite.make("TwoArmLift", base_types=["NullMount"] * 3, **QUIET)


def test_one_schema_declared_in_rust_takes_robosuites_values() -> None:
    # The argument list is exported from the Rust schema; values cross as they are.
    from robosuite_rs import _native

    assert set(suite.SUPPORTED_KWARGS) == set(_native.supported_kwargs())
    for name in ("robots", "camera_segmentations", "initialization_noise", "has_renderer", "render_gpu_device_id"):
        assert name in suite.SUPPORTED_KWARGS
    env = suite.make(
        "Lift", robots=np.array(["Panda"]), horizon=np.int64(5), reward_scale=None,
        initialization_noise={"magnitude": np.float32(0.0), "type": "uniform"}, **QUIET,
    )
    assert (env.horizon, env.reward_scale) == (5, None)
    a, b = env.reset(seed=0), suite.make("Lift", initialization_noise=None, **QUIET).reset(seed=0)
    assert np.array_equal(a["robot0_joint_pos"], b["robot0_joint_pos"])  # no noise either way
    # The registry path (gymnasium ids of other Rust envs, Rust's registry) reads lists too.
    native = _native.make_registered("Lift", {"robots": ["Panda"], "horizon": 3, **QUIET})
    native.reset(0, None)
    # Ill-typed values name the argument and the item; nothing is made.
    with pytest.raises(ValueError, match=r"camera_heights.*\[1\]"):
        suite.make("Lift", camera_heights=[84, "a"], **QUIET)
    with pytest.raises(ValueError, match="horizon"):
        suite.make("Lift", horizon=2.5, **QUIET)
    with pytest.raises(ValueError, match="reward_scale"):
        suite.make("Lift", reward_scale=float("inf"), **QUIET)
    with pytest.raises(TypeError, match="Lift's own: table_full_size"):
        suite.make("Lift", horizn=5, **QUIET)


def test_placement_samplers_sample_as_robosuites() -> None:
    # robosuite's samplers in Python, over the env's own objects: cubeA in a square, cubeB
    # on top of it (SequentialCompositeSampler with a reference), set by hand.
    from robosuite_rs.utils.placement_samplers import (
        RandomizationError,
        SequentialCompositeSampler,
        UniformRandomSampler,
    )

    env = suite.make("Stack", **QUIET)
    env.reset(seed=0)
    cube_a, cube_b = env.model.mujoco_objects

    def composite(seed: int) -> SequentialCompositeSampler:
        rng = np.random.default_rng(seed)
        sampler = SequentialCompositeSampler("Stack")
        sampler.append_sampler(UniformRandomSampler(
            "A", mujoco_objects=cube_a, x_range=[-0.1, 0.1], y_range=[-0.1, 0.1], rotation=None,
            ensure_object_boundary_in_range=False, reference_pos=(0, 0, 0.8), z_offset=0.01, rng=rng,
        ))
        sampler.append_sampler(UniformRandomSampler(
            "B", x_range=[0, 0], y_range=[0, 0], rotation=[0.5, 0.5],
            ensure_object_boundary_in_range=False, ensure_valid_placement=False, rng=rng,
        ), sample_args={"reference": "cubeA"})
        sampler.add_objects_to_sampler("B", cube_b)
        return sampler

    placed = composite(7).sample()
    (xa, ya, za), quat_a, _ = placed["cubeA"]
    (xb, yb, zb), quat_b, _ = placed["cubeB"]
    assert -0.1 <= xa <= 0.1 and -0.1 <= ya <= 0.1
    assert za == pytest.approx(0.81 - cube_a.bottom_offset[2])
    assert (xb, yb) == (xa, ya)
    assert zb == pytest.approx(za + cube_a.top_offset[2] - cube_b.bottom_offset[2])
    assert np.allclose(quat_b, [np.cos(0.25), 0, 0, np.sin(0.25)]) and np.isclose(np.linalg.norm(quat_a), 1)
    assert composite(7).sample()["cubeA"][0] == (xa, ya, za)  # same rng seed, same draw
    for name, (pos, quat, obj) in placed.items():
        env.sim.data.set_joint_qpos(obj.joints[0], np.concatenate([pos, quat]))
    env.sim.forward()
    assert np.allclose(env._get_observations(force_update=True)["cubeB_pos"], [xb, yb, zb])
    # robosuite's refusals: add_objects on a composite, an object placed twice, no room.
    with pytest.raises(AttributeError, match="add_objects"):
        composite(0).add_objects(cube_a)
    with pytest.raises(AttributeError, match="add_objects"):
        suite.make("Lift", placement_initializer=SequentialCompositeSampler("s"), **QUIET)
    with pytest.raises(AssertionError, match="cubeA"):
        composite(0).add_objects_to_sampler("B", cube_a)
    crowded = UniformRandomSampler(
        "c", mujoco_objects=[cube_a, cube_b], x_range=[0, 0], y_range=[0, 0], ensure_object_boundary_in_range=False,
    )
    with pytest.raises(RandomizationError):
        crowded.sample()
    with pytest.raises(TypeError, match="placement_initializer"):
        suite.make("Lift", placement_initializer=crowded, **QUIET)  # the task adds its own objects
