"""Reliability under bad input, misuse, fork and faults (issue #17): every reproducer gives
a typed exception and leaves the env usable and unchanged. Trials that could end the
process (a MuJoCo fatal error, a fork) run in a child process with a time limit, so a crash
or a hang fails the test instead of ending the run."""

from __future__ import annotations

import copy
import pickle
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import robosuite_rs as suite

from .conftest import QUIET


def run_child(code: str, timeout: float = 120.0) -> subprocess.CompletedProcess[str]:
    """Runs ``code`` in a fresh interpreter; a hang raises ``TimeoutExpired``."""
    return subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def lift_scene_with(extra: str) -> str:
    xml = suite.scene_xml("Lift")
    end = xml.rfind("</mujoco>")
    return xml[:end] + extra + xml[end:]


def test_a_mujoco_fatal_error_is_an_exception_at_make_not_an_exit(tmp_path) -> None:
    path = tmp_path / "tiny_arena.xml"
    path.write_text(lift_scene_with('<size memory="16K"/>'))
    child = run_child(
        f"""
        import numpy as np, robosuite_rs as suite
        try:
            suite.make("Lift", model_xml={str(path)!r})
        except RuntimeError as e:
            assert "memory" in str(e), e
            env = suite.make("Lift")
            env.reset(seed=0)
            env.step(np.zeros(7))
            print("typed error, still alive")
        """
    )
    assert child.returncode == 0, child.stdout + child.stderr
    assert "typed error, still alive" in child.stdout


def test_work_per_step_is_bounded_at_make(tmp_path) -> None:
    with pytest.raises(ValueError, match="control_freq"):
        suite.make("Lift", control_freq=1e-6, **QUIET)
    path = tmp_path / "tiny_timestep.xml"
    path.write_text(lift_scene_with('<option timestep="1e-9"/>'))
    with pytest.raises(ValueError, match="control_freq"):
        suite.make("Lift", model_xml=str(path), **QUIET)


def test_divergence_is_never_a_success() -> None:
    with pytest.raises(ValueError, match="initialization_noise"):
        suite.make("Lift", initialization_noise={"magnitude": 1e10, "type": "gaussian"}, **QUIET)
    env = suite.make("Lift", **QUIET)
    env.reset(seed=0)
    before = env.get_state()
    for bad in (before * 0 + 1e10, np.where(np.arange(before.size) == 3, np.nan, before)):
        with pytest.raises(ValueError, match="state"):
            env.set_state(bad)
        np.testing.assert_array_equal(env.get_state(), before)
    state = before.copy()
    nq = (before.size - 1) // 2 + 1  # Lift: 16 positions, 15 velocities
    state[1 + nq :] = 1e6
    env.set_state(state)
    with pytest.raises(RuntimeError, match="diverged"):
        env.step(np.zeros(7))
    env.reset(seed=0)
    _, reward, _, info = env.step(np.zeros(7))
    assert np.isfinite(reward) and info["success"] is False


def test_a_one_dimensional_force_sensor_is_rejected(tmp_path) -> None:
    xml = suite.scene_xml("Wipe")
    at = xml.find("<force ")
    sensor = xml[at : xml.find("/>", at) + 2]
    assert "force_ee" in sensor
    path = tmp_path / "wipe_touch.xml"
    path.write_text(xml.replace(sensor, sensor.replace("<force ", "<touch ", 1), 1))
    with pytest.raises(RuntimeError, match="force_ee"):
        suite.make("Wipe", model_xml=str(path), **QUIET)


def test_unsigned_actions_are_taken_by_value_or_rejected() -> None:
    a, b = suite.make("Lift", **QUIET), suite.make("Lift", **QUIET)
    a.reset(seed=1)
    b.reset(seed=1)
    with pytest.raises(ValueError, match="int64"):
        a.step(np.full(7, 2**64 - 1, np.uint64))
    obs_a, *_ = a.step(np.ones(7, np.uint16))
    obs_b, *_ = b.step(np.ones(7))
    for key in obs_a:
        np.testing.assert_array_equal(obs_a[key], obs_b[key])


def test_strict_conversions() -> None:
    env = suite.make("Lift", **QUIET)
    env.reset(seed=0)
    state = env.get_state()
    for shape in [(1, state.size), (state.size, 1)]:
        with pytest.raises(ValueError, match="1-D"):
            env.set_state(state.reshape(shape))
    with pytest.raises(TypeError, match="num_envs"):
        suite.make_vec("Lift", 2.7, **QUIET)
    with pytest.raises(TypeError, match="batch_size"):
        suite.make_pool("Lift", 2, 1.5, **QUIET)
    with suite.make_pool("Lift", 2, 2, **QUIET) as pool:
        pool.reset(seed=0)
        with pytest.raises(TypeError, match="env_id"):
            pool.send(np.zeros((2, 7), np.float32), [0.5, 1.5])


def test_vector_batches_must_match_exactly_and_change_nothing_when_rejected() -> None:
    good = np.full((2, 7), 0.25, np.float32)
    bad_batches = [np.zeros((3, 7), np.float32), np.zeros((1, 7), np.float32), good.copy()]
    bad_batches[2][1, 3] = np.nan
    vec, reference = suite.make_vec("Lift", 2, **QUIET), suite.make_vec("Lift", 2, **QUIET)
    try:
        vec.reset(seed=3)
        reference.reset(seed=3)
        for bad in bad_batches:
            with pytest.raises(ValueError):
                vec.step(bad)
            got, want = vec.step(good), reference.step(good)
            np.testing.assert_array_equal(got[0], want[0])
            np.testing.assert_array_equal(got[1], want[1])
    finally:
        vec.close()
        reference.close()
    with suite.make_pool("Lift", 2, 2, **QUIET) as pool:
        _, info = pool.reset(seed=0)
        ids = info["env_id"]
        for bad in bad_batches:
            with pytest.raises(ValueError):
                pool.send(bad, ids)
        pool.send(good, ids)
        obs, *_ = pool.recv()
        assert obs.shape == (2, 60)


def test_vector_envs_after_fork_raise_instead_of_hanging() -> None:
    child = run_child(
        """
        import os, threading, time
        import numpy as np, robosuite_rs as suite
        vec = suite.make_vec("Lift", 2, horizon=1000)
        pool = suite.make_pool("Lift", 2, 1, horizon=1000)
        vec.reset(seed=0)
        pool.reset(seed=0)
        stop = False
        def stepper():
            while not stop:
                vec.step(np.zeros((2, 7), np.float32))
        t = threading.Thread(target=stepper)
        t.start()
        time.sleep(0.2)
        pid = os.fork()  # very likely while the other thread is inside a step
        if pid == 0:
            code = 0
            for call in (lambda: vec.step(np.zeros((2, 7), np.float32)),
                         lambda: pool.recv()):
                try:
                    call()
                    code = 1
                except NotImplementedError as e:
                    assert "fork" in str(e), e
            vec.close()
            pool.close()
            os._exit(code)
        _, status = os.waitpid(pid, 0)
        stop = True
        t.join()
        vec.step(np.zeros((2, 7), np.float32))  # the parent keeps working
        vec.close()
        pool.close()
        print("child exit", os.waitstatus_to_exitcode(status))
        """,
        timeout=120,
    )
    assert child.returncode == 0, child.stdout + child.stderr
    assert "child exit 0" in child.stdout, child.stdout + child.stderr


def test_single_envs_after_fork_raise_instead_of_hanging() -> None:
    # A step of 500 substeps (control_freq=1) holds the env's lock almost all the time, so
    # the fork lands inside a step; the child's calls must return (an error naming the
    # fork, or a result if the fork fell between steps), never wait on the dead thread.
    child = run_child(
        """
        import os, threading, time
        import numpy as np, robosuite_rs as suite
        from robosuite_rs.wrappers import GymWrapper
        env = suite.make("Lift", control_freq=1, horizon=10**6, has_offscreen_renderer=False)
        env.reset(seed=0)
        gym_env = GymWrapper(suite.make("Lift", control_freq=1, horizon=10**6, has_offscreen_renderer=False))
        gym_env.reset(seed=0)
        stop = False
        def stepper(step):
            while not stop:
                step(np.zeros(7))
        threads = [threading.Thread(target=stepper, args=(f,)) for f in (env.step, gym_env.step)]
        for t in threads:
            t.start()
        time.sleep(0.5)
        pid = os.fork()
        if pid == 0:
            raised = 0
            for call in (lambda: env.step(np.zeros(7)), lambda: gym_env.step(np.zeros(7))):
                try:
                    call()
                except NotImplementedError as e:
                    assert "fork" in str(e), e
                    raised += 1
            os._exit(10 + raised)
        _, status = os.waitpid(pid, 0)
        stop = True
        for t in threads:
            t.join()
        env.step(np.zeros(7))  # the parent keeps working
        print("child exit", os.waitstatus_to_exitcode(status))
        """,
        timeout=120,
    )
    assert child.returncode == 0, child.stdout + child.stderr
    # 10 + the number of calls that raised (each raise named the fork).
    assert any(f"child exit {code}" in child.stdout for code in (10, 11, 12)), child.stdout + child.stderr


def test_a_call_from_inside_a_call_on_the_same_env_raises_instead_of_deadlocking() -> None:
    # An action whose __array__ steps the env it is an action for (the fuzz harness's
    # reproducer): an error naming the re-entry, and the env usable afterwards.
    child = run_child(
        """
        import numpy as np, robosuite_rs as suite
        from robosuite_rs.wrappers import GymWrapper

        class Sneaky:
            def __init__(self, target, shape):
                self.target, self.shape = target, shape
            def __array__(self, dtype=None, copy=None):
                self.target(np.zeros(self.shape, np.float32))
                return np.zeros(self.shape, dtype or np.float32)

        vec = suite.make_vec("Lift", 2, horizon=100)
        vec.reset(seed=0)
        gym_env = GymWrapper(suite.make("Lift", horizon=100, has_offscreen_renderer=False))
        gym_env.reset(seed=0)
        env = suite.make("Lift", horizon=100, has_offscreen_renderer=False)
        env.reset(seed=0)
        for name, step, shape in (("vec", vec.step, (2, 7)), ("gym", gym_env.step, (7,)), ("env", env.step, (7,))):
            try:
                step(Sneaky(step, shape))
                # robosuite's env object converts the action before it takes the env, so
                # there the inner step simply runs first.
                assert name == "env", name
            except NotImplementedError as e:
                assert "re-entrant" in str(e), (name, e)
            step(np.zeros(shape, np.float32))  # still usable
        print("ok")
        """,
        timeout=120,
    )
    assert child.returncode == 0, child.stdout + child.stderr
    assert "ok" in child.stdout


def test_deepcopy_and_pickle_continue_bit_identically() -> None:
    env = suite.make("Lift", horizon=50, **QUIET)
    env.reset(seed=4)
    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, size=(12, 7))
    for a in actions[:3]:
        env.step(a)
    copies = [copy.deepcopy(env), pickle.loads(pickle.dumps(env))]
    for a in actions[3:]:
        want = env.step(a)
        for c in copies:
            got = c.step(a)
            assert got[1:] == want[1:]
            for key in want[0]:
                np.testing.assert_array_equal(got[0][key], want[0][key])
    # The RNG is copied too: unseeded resets start the same episode.
    want = env.reset()
    for c in copies:
        got = c.reset()
        for key in want:
            np.testing.assert_array_equal(got[key], want[key])


def test_gym_wrapper_deepcopy() -> None:
    from robosuite_rs.wrappers import GymWrapper

    g = GymWrapper(suite.make("Lift", **QUIET))
    g.reset(seed=9)
    g.step(np.zeros(7, np.float32))
    c = copy.deepcopy(g)
    a = np.full(7, 0.3, np.float32)
    x, y = g.step(a), c.step(a)
    np.testing.assert_array_equal(x[0], y[0])
    assert x[1:4] == y[1:4]
