"""Gymnasium's own entry points on our ids: ``gymnasium.make`` / ``make_vec`` with the
arguments Gymnasium passes (``render_mode=None``, ``max_episode_steps``, ``vector_kwargs``,
``wrappers``, ``vectorization_mode``) and the ``"robosuite_rs:robosuite_rs/Lift-v0"`` id
form in processes started by spawn and forkserver."""

from __future__ import annotations

import functools
import multiprocessing
import tomllib
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import robosuite_rs as suite
from robosuite_rs.vector import RustVectorEnv

from .conftest import QUIET

ID = "robosuite_rs/Lift-v0"
MODULE_ID = "robosuite_rs:robosuite_rs/Lift-v0"


def test_make_accepts_render_mode_none() -> None:
    env = gym.make(ID, render_mode=None, horizon=10, **QUIET)
    assert env.render_mode is None and env.unwrapped.render_mode is None
    obs, _ = env.reset(seed=0)
    assert obs.shape == (60,)
    assert env.step(env.action_space.sample())[0].shape == (60,)
    assert env.render() is None
    env.close()


def test_make_vec_accepts_render_mode_none() -> None:
    vec = gym.make_vec(ID, 2, render_mode=None, horizon=10, **QUIET)
    assert isinstance(vec, RustVectorEnv)
    assert vec.reset(seed=0)[0].shape == (2, 60)
    vec.close()
    sync = gym.make_vec(ID, 2, vectorization_mode="sync", render_mode=None, horizon=10, **QUIET)
    assert isinstance(sync, gym.vector.SyncVectorEnv) and sync.render_mode is None
    sync.close()


def test_rust_vector_refuses_a_render_mode() -> None:
    with pytest.raises(suite.VectorizeError, match="does not render"):
        gym.make_vec(ID, 2, render_mode="rgb_array", horizon=10, **QUIET)


def _rollout(vec: gym.vector.VectorEnv, steps: int) -> list[tuple[np.ndarray, ...]]:
    obs, _ = vec.reset(seed=7)
    rng = np.random.default_rng(3)
    out = [(np.array(obs),)]
    for _ in range(steps):
        actions = rng.uniform(-1, 1, size=vec.action_space.shape).astype(np.float32)
        obs, rew, term, trunc, _ = vec.step(actions)
        out.append((np.array(obs), np.array(rew, dtype=np.float64), np.array(term), np.array(trunc)))
    return out


def test_make_vec_max_episode_steps_truncates_in_rust_as_gymnasium_does() -> None:
    limit = 20
    vec = gym.make_vec(ID, 2, max_episode_steps=limit, horizon=500, **QUIET)
    assert isinstance(vec, RustVectorEnv)
    assert vec.spec is not None and vec.spec.kwargs["max_episode_steps"] == limit
    rust = _rollout(vec, 2 * limit + 3)
    vec.close()
    truncated_at = [t for t, step in enumerate(rust[1:], start=1) if step[3].any()]
    # Steps limit and 2*limit+1 (the step after a truncation is the NEXT_STEP autoreset).
    assert truncated_at == [limit, 2 * limit + 1]
    assert all(step[3].all() for step in rust[1:] if step[3].any())
    # Gymnasium's own TimeLimit around each env (SyncVectorEnv): the same trajectory, bit for bit.
    sync = gym.make_vec(ID, 2, vectorization_mode="sync", max_episode_steps=limit, horizon=500, **QUIET)
    assert isinstance(sync, gym.vector.SyncVectorEnv)
    reference = _rollout(sync, 2 * limit + 3)
    sync.close()
    for t, (a, b) in enumerate(zip(rust, reference)):
        for x, y in zip(a, b):
            np.testing.assert_array_equal(x, y, err_msg=f"step {t}")


def test_make_vec_entry_point_takes_gymnasium_arguments_directly() -> None:
    # `robosuite_rs.make_vec` (the vector entry point) with Gymnasium's arguments.
    sync = suite.make_vec(
        "Lift",
        3,
        vectorization_mode="sync",
        vector_kwargs={"copy": False},
        wrappers=[gym.wrappers.ClipAction],
        max_episode_steps=5,
        horizon=10,
        **QUIET,
    )
    assert isinstance(sync, gym.vector.SyncVectorEnv) and sync.num_envs == 3 and sync.copy is False
    assert all(isinstance(e, gym.wrappers.ClipAction) for e in sync.envs)
    assert all(e.spec is not None and e.spec.max_episode_steps == 5 for e in sync.envs)
    sync.reset(seed=0)
    flags = [bool(sync.step(np.zeros((3, 7), dtype=np.float32))[3].all()) for _ in range(5)]
    assert flags == [False, False, False, False, True]
    sync.close()
    rust = suite.make_vec("Lift", 2, vectorization_mode="vector_entry_point", max_episode_steps=3, **QUIET)
    assert isinstance(rust, RustVectorEnv)
    rust.reset(seed=0)
    flags = [bool(rust.step(np.zeros((2, 7), dtype=np.float32))[3].all()) for _ in range(3)]
    assert flags == [False, False, True]
    rust.close()


def test_make_vec_refuses_what_the_rust_vector_cannot_honour() -> None:
    with pytest.raises(suite.VectorizeError, match="wrappers"):
        suite.make_vec("Lift", 2, wrappers=[gym.wrappers.ClipAction], **QUIET)
    with pytest.raises(gym.error.Error, match="vector_kwargs"):
        suite.make_vec("Lift", 2, vector_kwargs={"copy": False}, **QUIET)
    with pytest.raises(suite.VectorizeError, match="threads"):
        suite.make_vec("Lift", 2, vectorization_mode="sync", threads=2, **QUIET)
    with pytest.raises(suite.VectorizeError, match="pin_threads"):
        suite.make_vec("Lift", 2, vectorization_mode="async", pin_threads=True, **QUIET)
    with pytest.raises(ValueError, match="vectorization_mode"):
        suite.make_vec("Lift", 2, vectorization_mode="processes", **QUIET)
    with pytest.raises(ValueError, match="max_episode_steps"):
        suite.make_vec("Lift", 2, max_episode_steps=0, **QUIET)
    with pytest.raises(TypeError, match="max_episode_steps"):
        suite.make_vec("Lift", 2, max_episode_steps=2.5, **QUIET)
    with pytest.raises(ValueError, match="max_episode_steps"):
        suite.make_pool("Lift", 2, 1, max_episode_steps=-1, **QUIET)
    # Gymnasium's make_vec keeps its own rule: no wrappers with the vector entry point.
    with pytest.raises(gym.error.Error, match="wrappers"):
        gym.make_vec(ID, 2, wrappers=[gym.wrappers.ClipAction], **QUIET)


def test_make_pool_max_episode_steps() -> None:
    pool = suite.make_pool("Lift", 2, 2, max_episode_steps=4, **QUIET)
    obs, *_, info = pool.reset(seed=0)
    ids = info["env_id"]
    truncs = []
    for _ in range(4):
        _, _, _, trunc, info = pool.step(np.zeros((2, 7), dtype=np.float32), ids)
        ids = info["env_id"]
        truncs.append(bool(trunc.all()))
    assert truncs == [False, False, False, True]
    pool.close()


@pytest.mark.parametrize("context", ["spawn", "forkserver"])
def test_module_id_form_works_in_fresh_processes(context: str) -> None:
    # The env factory is `gymnasium.make` itself (pickled by reference): the worker never
    # imports robosuite_rs unless the id tells Gymnasium to.
    make = functools.partial(gym.make, MODULE_ID, horizon=10, **QUIET)
    vec = gym.vector.AsyncVectorEnv([make, make], context=context)
    obs, _ = vec.reset(seed=1)
    reference = [gym.make(ID, horizon=10, **QUIET).reset(seed=1 + i)[0] for i in range(2)]
    np.testing.assert_array_equal(obs, np.stack(reference))
    assert vec.step(np.zeros((2, 7), dtype=np.float32))[0].shape == (2, 60)
    vec.close()
    # Through gymnasium.make_vec's async mode as well.
    via_make_vec = gym.make_vec(MODULE_ID, 2, vectorization_mode="async", vector_kwargs={"context": context}, horizon=10, **QUIET)
    np.testing.assert_array_equal(via_make_vec.reset(seed=1)[0], obs)
    via_make_vec.close()


def test_plain_id_fails_in_a_spawned_process() -> None:
    # Why the id form matters: a spawned worker that never imports robosuite_rs does not
    # know the plain id.
    make = functools.partial(gym.make, ID, horizon=10, **QUIET)
    ctx = multiprocessing.get_context("spawn")
    with ctx.Pool(1) as pool:
        with pytest.raises(gym.error.NamespaceNotFound):
            pool.apply(make)


def test_extension_is_built_for_the_stable_abi_and_declares_its_gymnasium() -> None:
    # maturin names an abi3 build `_native.abi3.so` (a version-specific one
    # `_native.cpython-3XX-...so`); `make test-wheel` checks the wheel's cp310-abi3 tag.
    assert Path(suite._native.__file__).name == "_native.abi3.so"
    pyproject = tomllib.loads((Path(__file__).resolve().parents[2] / "pyproject.toml").read_text())
    assert "pyo3/abi3-py310" in pyproject["tool"]["maturin"]["features"]
    assert pyproject["project"]["requires-python"] == ">=3.10"
    assert "gymnasium>=1.1" in pyproject["project"]["dependencies"]
    assert hasattr(gym.vector, "AutoresetMode")  # what >=1.1 is for
