"""GymWrapper over an env whose observables are modified or added (robosuite's
``modify_observable`` / ``add_observable``), and pickling of those customisations."""

from __future__ import annotations

import copy
import pickle

import numpy as np
import pytest

import robosuite_rs as suite
from robosuite_rs.observables import Observable, sensor
from robosuite_rs.wrappers import GymWrapper

QUIET = {"has_renderer": False, "has_offscreen_renderer": False, "use_camera_obs": False}


def make(**kw: object) -> suite.RobosuiteEnv:
    return suite.make("Lift", robots="Panda", horizon=kw.pop("horizon", 30), **QUIET, **kw)


def actions(n: int, dim: int = 7, seed: int = 3) -> list[np.ndarray]:
    rng = np.random.default_rng(seed)
    return [rng.uniform(-1, 1, dim) for _ in range(n)]


def run(g: GymWrapper, seed: int, acts: list[np.ndarray]) -> list[tuple]:
    out: list[tuple] = [g.reset(seed=seed)]
    for a in acts:
        out.append(g.step(a))
        if out[-1][2] or out[-1][3]:
            out.append(g.reset())
    return out


def assert_same_runs(a: list[tuple], b: list[tuple]) -> None:
    assert len(a) == len(b)
    for x, y in zip(a, b):
        assert len(x) == len(y)
        for u, v in zip(x, y):
            if isinstance(u, dict) and any(isinstance(w, np.ndarray) for w in u.values()):
                assert list(u) == list(v)
                for k in u:
                    assert u[k].dtype == v[k].dtype and np.array_equal(u[k], v[k]), k
            elif isinstance(u, np.ndarray):
                assert u.dtype == v.dtype and u.shape == v.shape and np.array_equal(u, v)
            else:
                assert type(u) is type(v) and u == v


@sensor("extra")
def unused_sensor(obs_cache: dict) -> np.ndarray:
    return np.zeros(1)


@sensor("extra")
def eef_height(obs_cache: dict) -> np.ndarray:
    """robosuite-style sensor reading another observable from the cache."""
    return np.array([obs_cache.get("robot0_eef_pos", np.zeros(3))[2]])


def python_path(g: GymWrapper) -> GymWrapper:
    """Forces ``g`` onto env.step / env.reset: an added observable that nobody selects
    makes every step run robosuite's observables in Python."""
    g.env.add_observable(Observable("_unused", unused_sensor, sampling_rate=20))
    return g


# --- the two paths agree ----------------------------------------------------------------
@pytest.mark.parametrize("flatten", [True, False])
def test_python_path_equals_the_native_path_step_for_step(flatten: bool) -> None:
    acts = actions(40)  # float64 actions: both paths take them as float32
    fast = GymWrapper(make(horizon=15), flatten_obs=flatten)
    slow = python_path(GymWrapper(make(horizon=15), flatten_obs=flatten))
    a = run(fast, 7, acts)
    b = run(slow, 7, acts)
    assert fast._route is not None and slow._route is None
    assert_same_runs(a, b)
    assert any(s[3] for s in b if len(s) == 5)  # the horizon was reached: truncated
    assert all("success" in s[-1] for s in b)


def test_python_space_equals_the_native_space() -> None:
    env = make()
    for flatten in (True, False):
        g = GymWrapper(env, flatten_obs=flatten)
        native = GymWrapper.__mro__[1](env._native.gym_env(None, flatten))
        assert g.observation_space == native.observation_space
        assert g.action_space == native.action_space
        assert g.keys == list(env._native.default_gym_keys())


def test_python_path_errors_and_episode_end() -> None:
    g = python_path(GymWrapper(make(horizon=2)))
    with pytest.raises(RuntimeError, match="before calling reset"):
        g.step(np.zeros(7))  # as the native path
    g.reset(seed=0)
    with pytest.raises(ValueError, match="shape"):
        g.step(np.zeros(6))
    with pytest.raises(ValueError, match="unknown key"):
        g.reset(options={"x": 1})
    assert g.step(np.zeros(7))[2:4] == (False, False)
    assert g.step(np.zeros(7))[2:4] == (False, True)
    with pytest.raises(ValueError):
        g.step(np.zeros(7))


# --- observables modified before / after wrapping ------------------------------------
def test_modified_before_wrapping_changes_keys_and_space() -> None:
    env = make()
    env.modify_observable("cube_pos", "active", False)
    g = GymWrapper(env)
    assert g.observation_space.shape == (57,)  # object-state lost cube_pos (3)
    obs, _ = g.reset(seed=1)
    assert obs.shape == (57,)
    full = env._native.all_observations()
    assert np.array_equal(obs[:7], np.concatenate([full["cube_quat"], full["gripper_to_cube_pos"]]).astype(np.float32))
    # every object observable off: robosuite's default keys skip object-state
    for k in ("cube_quat", "gripper_to_cube_pos"):
        env.modify_observable(k, "enabled", False)
    g2 = GymWrapper(env, flatten_obs=False)
    assert g2.keys == ["robot0_proprio-state"]


def test_corrupter_after_wrapping_shows_in_the_observations() -> None:
    env = make()
    g = GymWrapper(env, keys=["cube_pos", "robot0_eef_pos"], flatten_obs=False)
    g.reset(seed=2)
    obs0 = g.step(np.zeros(7))[0]
    assert g._route is not None
    env.modify_observable("cube_pos", "corrupter", lambda x: x + 100.0)
    obs1 = g.step(np.zeros(7))[0]
    assert g._route is None
    truth = env._native.all_observations()
    assert np.allclose(obs1["cube_pos"], truth["cube_pos"] + 100.0)
    assert np.array_equal(obs1["robot0_eef_pos"], truth["robot0_eef_pos"])
    assert obs1["cube_pos"].dtype == obs0["cube_pos"].dtype
    # back to as made: the native path again (at the next reset, with robosuite's clocks)
    env.modify_observable("cube_pos", "corrupter", None)
    g.reset(seed=2)
    g.step(np.zeros(7))
    assert g._route is not None


def test_corrupted_member_changes_the_flat_modality_group() -> None:
    env = make()
    g = GymWrapper(env)
    g.reset(seed=4)
    clean = g.step(np.zeros(7))[0]
    env.modify_observable("cube_pos", "corrupter", lambda x: x + 1.0)
    g.reset(seed=4)
    noisy = g.step(np.zeros(7))[0]
    # object-state: cube_pos, cube_quat, gripper_to_cube_pos (robosuite computes the last
    # from the cached, corrupted cube_pos), then the proprio-state
    assert np.allclose(noisy[:3], clean[:3] + 1.0, atol=1e-5)
    assert np.array_equal(noisy[3:7], clean[3:7])
    assert np.allclose(noisy[7:10], clean[7:10] + 1.0, atol=1e-5)
    assert np.array_equal(noisy[10:], clean[10:])


def test_delayer_filter_and_sampling_rate_follow_robosuite() -> None:
    acts = [a.astype(np.float32) for a in actions(12)]
    env = make()
    env.modify_observable("cube_pos", "sampling_rate", 5)
    env.modify_observable("robot0_eef_pos", "delayer", lambda: 0.01)
    env.modify_observable("gripper_to_cube_pos", "filter", lambda x: x * 0.5)
    g = GymWrapper(env, keys=["cube_pos", "robot0_eef_pos", "gripper_to_cube_pos"], flatten_obs=False)
    ref = make()
    for name, attr, mod in (
        ("cube_pos", "sampling_rate", 5),
        ("robot0_eef_pos", "delayer", lambda: 0.01),
        ("gripper_to_cube_pos", "filter", lambda x: x * 0.5),
    ):
        ref.modify_observable(name, attr, mod)
    g.reset(seed=5)
    ref.reset(seed=5)
    seen = []
    for a in acts:
        o = g.step(a)[0]
        r = ref.step(a)[0]
        for k in g.keys:
            assert np.array_equal(o[k], r[k]), k
        seen.append(o["cube_pos"].copy())
    held = sum(np.array_equal(x, y) for x, y in zip(seen, seen[1:]))
    assert 0 < held < len(seen) - 1  # 5 Hz at 20 Hz control: the value is held between samples


def test_added_observable_can_be_selected_before_or_after_wrapping() -> None:
    env = make()
    with pytest.raises(ValueError, match="not observed.*observed:"):
        GymWrapper(env, keys=["object-state", "eef_height"])
    env.add_observable(Observable("eef_height", eef_height, sampling_rate=20))
    g = GymWrapper(env, keys=["object-state", "eef_height"])
    assert g.observation_space.shape == (11,)
    obs, _ = g.reset(seed=0)
    obs = g.step(np.zeros(7))[0]
    assert obs.shape == (11,)
    assert obs[-1] == np.float32(env._native.all_observations()["robot0_eef_pos"][2])


def test_deactivated_key_after_wrapping_is_a_clear_error_and_nothing_steps() -> None:
    env = make()
    g = GymWrapper(env, keys=["cube_pos", "robot0_proprio-state"])
    g.reset(seed=0)
    g.step(np.zeros(7))
    env.modify_observable("cube_pos", "active", False)
    t = env.timestep
    with pytest.raises(ValueError, match=r"\['cube_pos'\].*not observed"):
        g.step(np.zeros(7))
    with pytest.raises(ValueError, match="not observed"):
        g.reset()
    assert env.timestep == t
    env.modify_observable("cube_pos", "active", True)
    assert g.step(np.zeros(7))[0].shape == g.observation_space.shape


def test_bad_keys() -> None:
    env = make()
    with pytest.raises(ValueError, match="duplicate"):
        GymWrapper(env, keys=["cube_pos", "cube_pos"])
    with pytest.raises(ValueError, match="no observation keys"):
        GymWrapper(env, keys=[])
    with pytest.raises(ValueError, match="list of observation names"):
        GymWrapper(env, keys="cube_pos")
    with pytest.raises(TypeError):
        GymWrapper(object())  # type: ignore[arg-type]


# --- pickling / deepcopy keeps the customisations ---------------------------------------
def shift(x: np.ndarray) -> np.ndarray:
    return np.asarray(x) + 0.25


def halve(x: np.ndarray) -> np.ndarray:
    return np.asarray(x) * 0.5


def fixed_delay() -> float:
    return 0.012


def customise(env: suite.RobosuiteEnv) -> None:
    env.modify_observable("cube_pos", "corrupter", shift)
    env.modify_observable("gripper_to_cube_pos", "filter", halve)
    env.modify_observable("robot0_eef_pos", "delayer", fixed_delay)
    env.modify_observable("cube_quat", "sampling_rate", 7)
    env.modify_observable("robot0_joint_vel", "active", False)
    env.modify_observable("robot0_joint_acc", "enabled", False)
    env.add_observable(Observable("eef_height", eef_height, sampling_rate=10))


@pytest.mark.parametrize("how", ["pickle", "deepcopy"])
def test_copies_keep_observable_customisations_and_continue_identically(how: str) -> None:
    env = make(horizon=50)
    customise(env)
    env.reset(seed=9)
    acts = [a.astype(np.float32) for a in actions(12, seed=5)]
    for a in acts[:5]:
        env.step(a)
    twin = pickle.loads(pickle.dumps(env)) if how == "pickle" else copy.deepcopy(env)
    assert twin.observation_keys() == env.observation_keys()
    assert "eef_height" in twin.observation_keys() and "robot0_joint_vel" not in twin.observation_keys()
    assert twin.enabled_observables == env.enabled_observables
    o, t = env._observables, twin._observables
    assert t["cube_pos"]._corrupter(np.zeros(3))[0] == 0.25
    assert 1 / t["cube_quat"]._sampling_timestep == pytest.approx(7)
    assert t["robot0_eef_pos"]._delayer() == 0.012
    assert t["cube_pos"]._sensor is twin._obsv.sensors["cube_pos"]  # the copy's own sensor
    assert not twin._obsv.fast
    for a in acts[5:]:
        x, y = env.step(a)[0], twin.step(a)[0]
        assert list(x) == list(y)
        for k in x:
            assert np.array_equal(x[k], y[k]), k
    assert o["cube_pos"] is not t["cube_pos"]


def test_pickling_an_unpicklable_callable_names_the_observable() -> None:
    env = make()
    env.modify_observable("cube_pos", "corrupter", lambda x: x + 1.0)
    env.reset(seed=0)
    with pytest.raises(pickle.PicklingError, match="observable 'cube_pos': its corrupter"):
        pickle.dumps(env)
    twin = copy.deepcopy(env)  # deepcopy keeps the lambda
    a = np.zeros(7)
    assert np.array_equal(env.step(a)[0]["cube_pos"], twin.step(a)[0]["cube_pos"])
    with pytest.raises(pickle.PicklingError, match="cube_pos"):
        pickle.dumps(GymWrapper(env))


def test_flags_alone_keep_the_fast_path_in_the_copy() -> None:
    env = make()
    env.modify_observable("cube_pos", "active", False)
    env.reset(seed=1)
    env.step(np.zeros(7))
    assert env._obsv.fast
    twin = pickle.loads(pickle.dumps(env))
    assert twin._obsv.fast and "cube_pos" not in twin.observation_keys()
    x, y = env.step(np.zeros(7))[0], twin.step(np.zeros(7))[0]
    assert list(x) == list(y) and all(np.array_equal(x[k], y[k]) for k in x)


def test_a_sensor_swapped_for_another_own_sensor_is_the_copys_own() -> None:
    env = make(hard_reset=False)  # robosuite's reset puts the own sensors back otherwise
    env.modify_observable("cube_pos", "sensor", env._observables["robot0_eef_pos"]._sensor)
    env.reset(seed=2)
    twin = copy.deepcopy(env)
    assert twin._observables["cube_pos"]._sensor is twin._obsv.sensors["robot0_eef_pos"]
    y = twin.step(np.zeros(7))[0]
    assert np.array_equal(y["cube_pos"], twin._native.all_observations()["robot0_eef_pos"])


def test_gym_wrapper_copies_keep_keys_and_observables() -> None:
    env = make()
    customise(env)
    g = GymWrapper(env, keys=["cube_pos", "eef_height", "robot0_proprio-state"])
    g.reset(seed=3)
    g.step(np.zeros(7))
    for copier in (lambda w: pickle.loads(pickle.dumps(w)), copy.deepcopy):
        twin = copier(g)
        assert twin.keys == g.keys and twin.observation_space == g.observation_space
        a = np.full(7, 0.1, np.float32)
        assert np.array_equal(g.step(a)[0], twin.step(a)[0])
        g = twin
