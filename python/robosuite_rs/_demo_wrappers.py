"""robosuite's demonstration wrappers: ``Wrapper`` (robosuite's base class),
``DataCollectionWrapper`` and ``DemoSamplerWrapper`` (robosuite 1.5.2's
``robosuite/wrappers/``), exported by :mod:`robosuite_rs.wrappers`."""

from __future__ import annotations

import json
import os
import re
import random
import time
from typing import Any, Sequence

import numpy as np


def env_name_of(env: Any) -> str:
    """The task name robosuite writes for ``env`` (its class name there: ``Lift``,
    ``PickPlaceCan``, ...); here the env's ``name``."""
    base = env.unwrapped if hasattr(env, "unwrapped") else env
    name = getattr(base, "name", None)
    return name if isinstance(name, str) else base.__class__.__name__


class Wrapper:
    """robosuite's ``Wrapper``: forwards everything it does not override to ``env``
    (methods returning the wrapped env return the wrapper instead)."""

    def __init__(self, env: Any) -> None:
        self.env = env

    @classmethod
    def class_name(cls) -> str:
        return cls.__name__

    def _warn_double_wrap(self) -> None:
        env = self.env
        while isinstance(env, Wrapper):
            if env.class_name() == self.class_name():
                raise Exception(f"Attempted to double wrap with Wrapper: {self.__class__.__name__}")
            env = env.env

    def step(self, action: Any) -> Any:
        return self.env.step(action)

    def reset(self) -> Any:
        return self.env.reset()

    def render(self, **kwargs: Any) -> Any:
        return self.env.render(**kwargs)

    def observation_spec(self) -> Any:
        return self.env.observation_spec()

    @property
    def action_spec(self) -> Any:
        return self.env.action_spec

    @property
    def action_dim(self) -> int:
        return self.env.action_dim

    @property
    def unwrapped(self) -> Any:
        return self.env.unwrapped if hasattr(self.env, "unwrapped") else self.env

    def __getattr__(self, attr: str) -> Any:
        if attr == "env":  # not set yet (during unpickling): no recursion
            raise AttributeError(attr)
        orig_attr = getattr(self.env, attr)
        if callable(orig_attr):

            def hooked(*args: Any, **kwargs: Any) -> Any:
                result = orig_attr(*args, **kwargs)
                return self if result is self.env else result

            return hooked
        return orig_attr


_ACTUATOR_INPUT = re.compile(
    r"(<(?:general|motor|position|velocity|intvelocity|damper|cylinder|muscle|adhesion)\b[^>]*?)\s+input=\"[^\"]*\""
)


def _robosuite_readable_xml(xml: str) -> str:
    """``xml`` as robosuite 1.5.2's MuJoCo (3.3.7) reads it: without the actuators'
    ``input`` attribute that MuJoCo 3.17 writes (3.3.7 rejects the file with it; without it
    only ``actuator_ctrlspec`` changes, which robosuite's own scenes leave at 0 as well)."""
    return _ACTUATOR_INPUT.sub(r"\1", xml)


class DataCollectionWrapper(Wrapper):
    """robosuite's ``DataCollectionWrapper``: saves the simulator states and actions of
    every episode to disk, in robosuite's format, so that robosuite's
    ``gather_demonstrations_as_hdf5`` (and :func:`robosuite_rs.datasets.gather_demonstrations_as_hdf5`)
    read it.

    Per episode (from its first ``step``), a folder ``<directory>/ep_<t1>_<t2>`` (the
    ``time.time()`` of the first step) holding ``model.xml`` (``env.sim.model.get_xml()``
    at the reset, without what robosuite 1.5.2's MuJoCo 3.3.7 cannot read: the actuators'
    ``input`` attribute), ``ep_meta.json`` (``env.get_ep_meta()``) and ``state_<t1>_<t2>.npz``
    files, each with ``states`` (flat ``[time, qpos, qvel]`` rows: the reset state, then the
    state after every ``collect_freq``-th step), ``action_infos`` (per collected step a dict
    ``{"actions": action}``, plus ``"actions_abs"`` when the step's info has
    ``action_abs``), ``successful`` (whether ``_check_success()`` held after any step since
    the last flush) and ``env`` (the task name). A file is written every ``flush_freq``
    steps, at the next ``reset()`` and at ``close()``.

    As in robosuite, ``reset()`` reloads the scene it just made from its own XML and
    state (``reset_from_xml_string`` + ``set_state_from_flattened``), so that the recorded
    actions replay the episode deterministically from its first state.

    Args:
        env: the environment (a :class:`robosuite_rs.RobosuiteEnv` or a wrapper of one).
        directory: where episodes are written (made if missing).
        collect_freq: save the state every this many env steps.
        flush_freq: write the states collected so far every this many env steps.
    """

    def __init__(self, env: Any, directory: str | os.PathLike[str], collect_freq: int = 1, flush_freq: int = 100) -> None:
        super().__init__(env)
        if int(collect_freq) < 1 or int(flush_freq) < 1:
            raise ValueError(f"collect_freq and flush_freq must be >= 1, got {collect_freq}, {flush_freq}")
        self.directory = os.fspath(directory)
        self.states: list[np.ndarray] = []
        self.action_infos: list[dict[str, np.ndarray]] = []
        self.successful = False
        self.collect_freq = int(collect_freq)
        self.flush_freq = int(flush_freq)
        if not os.path.exists(self.directory):
            print(f"DataCollectionWrapper: making new directory at {self.directory}")
            os.makedirs(self.directory)
        self.ep_directory: str | None = None
        self.has_interaction = False
        self.t = 0
        self._current_task_instance_state: np.ndarray | None = None
        self._current_task_instance_xml: str | None = None

    def _start_new_episode(self) -> None:
        if self.has_interaction:
            self._flush()
        self.t = 0
        self.has_interaction = False
        self._current_task_instance_xml = _robosuite_readable_xml(self.env.sim.model.get_xml())
        self._current_task_instance_state = np.array(self.env.sim.get_state().flatten())
        # robosuite's trick for deterministic open-loop playback of the recorded actions
        self.env.set_ep_meta(self.env.get_ep_meta())
        self.env.reset_from_xml_string(self._current_task_instance_xml)
        self.env.sim.reset()
        self.env.sim.set_state_from_flattened(self._current_task_instance_state)
        self.env.sim.forward()

    def _on_first_interaction(self) -> None:
        self.has_interaction = True
        t1, t2 = str(time.time()).split(".")
        self.ep_directory = os.path.join(self.directory, f"ep_{t1}_{t2}")
        if os.path.exists(self.ep_directory):
            raise FileExistsError(f"DataCollectionWrapper: episode folder {self.ep_directory} exists")
        print(f"DataCollectionWrapper: making folder at {self.ep_directory}")
        os.makedirs(self.ep_directory)
        with open(os.path.join(self.ep_directory, "model.xml"), "w") as f:
            f.write(self._current_task_instance_xml or "")
        with open(os.path.join(self.ep_directory, "ep_meta.json"), "w") as f:
            json.dump(self.env.get_ep_meta(), f)
        assert len(self.states) == 0
        self.states.append(self._current_task_instance_state)

    def _flush(self) -> None:
        t1, t2 = str(time.time()).split(".")
        state_path = os.path.join(self.ep_directory or self.directory, f"state_{t1}_{t2}.npz")
        np.savez(
            state_path,
            states=np.array(self.states),
            action_infos=np.array(self.action_infos, dtype=object),
            successful=self.successful,
            env=env_name_of(self.env),
        )
        self.states = []
        self.action_infos = []
        self.successful = False

    def reset(self) -> Any:
        self.env.unset_ep_meta()
        ret = super().reset()
        self._start_new_episode()
        return ret

    def step(self, action: Any) -> Any:
        ret = super().step(action)
        self.t += 1
        if not self.has_interaction:
            self._on_first_interaction()
        if self.t % self.collect_freq == 0:
            self.states.append(self.env.sim.get_state().flatten())
            info = {"actions": np.array(action)}
            step_info = ret[3]
            if "action_abs" in step_info:
                info["actions_abs"] = np.array(step_info["action_abs"])
            self.action_infos.append(info)
        if self.env._check_success():
            self.successful = True
        if self.t % self.flush_freq == 0:
            self._flush()
        return ret

    def close(self) -> None:
        if self.has_interaction:
            self._flush()
            self.has_interaction = False
        self.env.close()


class DemoSamplerWrapper(Wrapper):
    """robosuite's ``DemoSamplerWrapper``: on every ``reset()``, starts the episode from a
    state of a demonstration or from the env's own reset, by a mix of sampling schemes (a
    reset-from-demonstration curriculum).

    Args:
        env: the environment (of the task the demonstrations were recorded on).
        demo_path: a folder holding ``demo.hdf5`` (robosuite's argument) or the path of an
            hdf5 file in robosuite's or robomimic's layout.
        need_xml: reload each demonstration's scene (its ``model_file``: the XML itself, as
            robosuite 1.5.2 writes it, or a file name under ``<demo_path>/models/``) before
            setting its state.
        num_traj: use this many demonstrations (sampled with ``random.seed(3141)``, as
            robosuite) instead of all (``-1``).
        sampling_schemes: from ``"random"`` (the env's own reset), ``"uniform"`` (any state
            of a random demo), ``"forward"`` (a state in a window from a demo's start that
            grows by ``open_loop_window_increment`` every ``open_loop_increment_freq``
            samples), ``"reverse"`` (the same window from a demo's end).
        scheme_ratios: the probability of each scheme (positive, summing to 1).
        open_loop_increment_freq, open_loop_initial_window_width, open_loop_window_increment:
            the open-loop window's schedule (demo steps).

    Schemes are drawn with Python's ``random`` and open-loop indices with NumPy's global
    generator, as robosuite does, so the same seeds give robosuite's samples. After setting
    a demo state (``set_state_from_flattened`` + ``forward``), ``reset()`` returns
    ``env._get_observations(force_update=True)`` (robosuite 1.5.2 calls the
    ``_get_observation`` of older robosuite versions there, which its envs lack).

    Raises:
        ValueError: for an unknown scheme, ratios that do not fit, a file of another task.
        FileNotFoundError / OSError: for a missing or unreadable demo file.
    """

    _METHODS = {
        "random": "_random_sample",
        "uniform": "_uniform_sample",
        "forward": "_forward_sample_open_loop",
        "reverse": "_reverse_sample_open_loop",
    }

    def __init__(
        self,
        env: Any,
        demo_path: str | os.PathLike[str],
        need_xml: bool = False,
        num_traj: int = -1,
        sampling_schemes: Sequence[str] = ("uniform", "random"),
        scheme_ratios: Sequence[float] = (0.9, 0.1),
        open_loop_increment_freq: int = 100,
        open_loop_initial_window_width: int = 25,
        open_loop_window_increment: int = 25,
    ) -> None:
        super().__init__(env)
        from .datasets import _open_input

        self.demo_path = os.fspath(demo_path)
        hdf5_path = self.demo_path if os.path.isfile(self.demo_path) else os.path.join(self.demo_path, "demo.hdf5")
        self.demo_file = _open_input(hdf5_path)
        data = self.demo_file["data"]
        env_name = data.attrs.get("env")
        if env_name is None and "env_args" in data.attrs:
            env_name = json.loads(data.attrs["env_args"]).get("env_name")
        if env_name != env_name_of(env):
            raise ValueError(
                f"Wrapped env {env_name_of(env)} does not match env on which demos were collected ({env_name})"
            )
        self.demo_list = list(data.keys())
        if not self.demo_list:
            raise ValueError(f"{hdf5_path}: no demonstrations under data/")
        if num_traj > 0:
            random.seed(3141)
            self.demo_list = random.sample(self.demo_list, num_traj)
        self.need_xml = need_xml
        self.demo_sampled = 0
        self.sample_method_dict = dict(self._METHODS)
        self.sampling_schemes = list(sampling_schemes)
        self.scheme_ratios = np.asarray(scheme_ratios, dtype=np.float64)
        bad = [s for s in self.sampling_schemes if s not in self._METHODS]
        if bad:
            raise ValueError(f"unknown sampling scheme(s) {bad}; valid: {list(self._METHODS)}")
        if len(self.sampling_schemes) != len(self.scheme_ratios):
            raise ValueError("sampling_schemes and scheme_ratios differ in length")
        if not (np.all(self.scheme_ratios > 0.0) and np.isclose(self.scheme_ratios.sum(), 1.0, rtol=0, atol=1e-9)):
            raise ValueError(f"scheme_ratios must be positive and sum to 1, got {list(scheme_ratios)}")
        self.open_loop_increment_freq = open_loop_increment_freq
        self.open_loop_window_increment = open_loop_window_increment
        self.open_loop_window_size = open_loop_initial_window_width

    def reset(self) -> Any:
        state = self.sample()
        if state is None:
            return self.env.reset()
        if self.need_xml:
            state, xml = state
            self.env.reset_from_xml_string(xml)
        if isinstance(state, tuple):
            state = state[0]
        self.env.sim.set_state_from_flattened(state)
        self.env.sim.forward()
        return self.env._get_observations(force_update=True)

    def sample(self) -> Any:
        """A state of a demo (with its XML when ``need_xml``), or ``None`` for the env's
        own reset."""
        seed = random.uniform(0, 1)
        ratio = np.cumsum(self.scheme_ratios) > seed
        i = int(np.argmax(ratio)) if ratio.any() else len(ratio) - 1
        return getattr(self, self.sample_method_dict[self.sampling_schemes[i]])()

    def _random_sample(self) -> None:
        return None

    def _states(self, ep_ind: str) -> np.ndarray:
        return self.demo_file[f"data/{ep_ind}/states"][()]

    def _with_xml(self, state: np.ndarray, ep_ind: str) -> Any:
        if self.need_xml:
            return state, self.env.edit_model_xml(self._xml_for_episode_index(ep_ind))
        return state

    def _uniform_sample(self) -> Any:
        ep_ind = random.choice(self.demo_list)
        state = random.choice(self._states(ep_ind))
        return self._with_xml(state, ep_ind)

    def _open_loop_step(self, eps_len: int) -> None:
        self.demo_sampled += 1
        if self.demo_sampled >= self.open_loop_increment_freq:
            if self.open_loop_window_size < eps_len:
                self.open_loop_window_size += self.open_loop_window_increment
            self.demo_sampled = 0

    def _reverse_sample_open_loop(self) -> Any:
        ep_ind = random.choice(self.demo_list)
        states = self._states(ep_ind)
        eps_len = states.shape[0]
        index = np.random.randint(max(eps_len - self.open_loop_window_size, 0), eps_len)
        self._open_loop_step(eps_len)
        return self._with_xml(states[index], ep_ind)

    def _forward_sample_open_loop(self) -> Any:
        ep_ind = random.choice(self.demo_list)
        states = self._states(ep_ind)
        eps_len = states.shape[0]
        index = np.random.randint(0, min(self.open_loop_window_size, eps_len))
        self._open_loop_step(eps_len)
        return self._with_xml(states[index], ep_ind)

    def _xml_for_episode_index(self, ep_ind: str) -> str:
        model_file = self.demo_file[f"data/{ep_ind}"].attrs["model_file"]
        if isinstance(model_file, bytes):
            model_file = model_file.decode()
        if model_file.lstrip().startswith("<"):
            return model_file
        with open(os.path.join(self.demo_path, "models", model_file)) as f:
            return f.read()

    def close(self) -> None:
        try:
            self.demo_file.close()
        finally:
            self.env.close()
