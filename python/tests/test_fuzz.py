"""The Python half of the fuzz suite (issue #17): Hypothesis over the Python API as a user
calls it (actions of any dtype, shape and value; states; make arguments; vector batches).
Every call returns or raises a typed exception (``ValueError``, ``TypeError``,
``RuntimeError`` for a diverged simulation), a rejected call changes nothing, and no step
reports a success it did not have. Scene files that could end the process run in a child
process each. ``FUZZ_EXAMPLES`` sets the examples per property (20 by default; ``make fuzz``
runs 300)."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import robosuite_rs as suite

from .conftest import QUIET

EXAMPLES = int(os.environ.get("FUZZ_EXAMPLES", "20"))
SETTINGS = settings(
    max_examples=EXAMPLES,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
TYPED = (ValueError, TypeError, RuntimeError)
DTYPES = st.sampled_from(
    [np.float64, np.float32, np.float16, np.int8, np.int16, np.int64, np.uint8, np.uint16, np.uint64, np.bool_]
)
NASTY = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(-2, 2),
    st.sampled_from([1e10, -1e300, 2**63, 2**64 - 1, 0.0]),
)


@pytest.fixture(scope="module")
def lift() -> suite.RobosuiteEnv:
    env = suite.make("Lift", horizon=1000, **QUIET)
    env.reset(seed=0)
    return env


@SETTINGS
@given(data=st.data())
def test_actions_of_any_dtype_shape_and_value(lift: suite.RobosuiteEnv, data: st.DataObject) -> None:
    dtype = data.draw(DTYPES)
    shape = data.draw(hnp.array_shapes(min_dims=0, max_dims=2, max_side=9))
    action = data.draw(hnp.arrays(dtype, shape, elements=st.just(0) | hnp.from_dtype(np.dtype(dtype))))
    before = lift.get_state()
    try:
        _, reward, _, info = lift.step(action)
    except TYPED:
        np.testing.assert_array_equal(lift.get_state(), before)
        return
    assert np.isfinite(reward) and isinstance(info["success"], bool)
    if lift.timestep > 500:
        lift.reset(seed=0)


@SETTINGS
@given(edits=st.lists(st.tuples(st.integers(0, 40), NASTY), max_size=4), extra=st.integers(-1, 1))
def test_states(lift: suite.RobosuiteEnv, edits: list[tuple[int, float]], extra: int) -> None:
    lift.reset(seed=1)
    state = lift.get_state().tolist()
    for i, v in edits:
        if i < len(state):
            state[i] = v
    state = state[: len(state) + extra] if extra < 0 else state + [0.0] * extra
    before = lift.get_state()
    try:
        lift.set_state(np.array(state))
    except TYPED:
        np.testing.assert_array_equal(lift.get_state(), before)
        return
    try:
        _, reward, _, _ = lift.step(np.zeros(7))
        assert np.isfinite(reward)
    except RuntimeError as e:
        assert "diverged" in str(e) or "MuJoCo" in str(e)
        lift.reset(seed=1)


@SETTINGS
@given(
    control_freq=st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.floats(0.1, 600)),
    horizon=st.integers(-5, 3000),
    magnitude=NASTY,
)
def test_make_arguments(control_freq: float, horizon: int, magnitude: float) -> None:
    try:
        env = suite.make(
            "Lift",
            control_freq=control_freq,
            horizon=horizon,
            initialization_noise={"magnitude": magnitude, "type": "uniform"},
            **QUIET,
        )
    except TYPED:
        return
    env.reset(seed=0)
    env.step(np.zeros(7))
    env.close()


@pytest.fixture(scope="module")
def vec():
    v = suite.make_vec("Lift", 2, **QUIET)
    v.reset(seed=0)
    yield v
    v.close()


@SETTINGS
@given(data=st.data())
def test_vector_batches(vec, data: st.DataObject) -> None:
    shape = data.draw(st.tuples(st.integers(0, 3), st.integers(5, 8)))
    batch = data.draw(hnp.arrays(np.float32, shape, elements=st.floats(-1, 1, width=32) | st.just(np.nan)))
    before = np.copy(vec.step(np.zeros((2, 7), np.float32))[0])
    try:
        vec.step(batch)
    except TYPED:
        after = vec.step(np.zeros((2, 7), np.float32))[0]
        assert after.shape == before.shape
        return
    assert batch.shape == (2, 7) and np.isfinite(batch).all()


@pytest.mark.parametrize("memory,timestep", [("1K", "0.002"), ("32K", "0.002"), ("16M", "1e-9")])
def test_scene_files_in_a_child_process(tmp_path, memory: str, timestep: str) -> None:
    xml = suite.scene_xml("Lift")
    end = xml.rfind("</mujoco>")
    path = tmp_path / "scene.xml"
    path.write_text(xml[:end] + f'<size memory="{memory}"/><option timestep="{timestep}"/>' + xml[end:])
    code = f"""
        import numpy as np, robosuite_rs as suite
        try:
            env = suite.make("Lift", model_xml={str(path)!r})
            env.reset(seed=0)
            env.step(np.zeros(7))
        except (ValueError, RuntimeError) as e:
            print("typed:", type(e).__name__)
        else:
            print("ran")
        """
    child = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, timeout=120)
    assert child.returncode == 0, child.stdout + child.stderr
    assert "typed:" in child.stdout or "ran" in child.stdout
