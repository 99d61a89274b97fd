"""Gymnasium environments backed by Rust: :class:`RustEnv` (any env exported from Rust)
and :class:`GymWrapper` (robosuite's ``GymWrapper``, served by the Rust core).

Import swap for robosuite users::

    from robosuite_rs.wrappers import GymWrapper   # was: from robosuite.wrappers import GymWrapper

robosuite's demonstration wrappers are here too: :class:`DataCollectionWrapper` and
:class:`DemoSamplerWrapper` (see :mod:`robosuite_rs.datasets`), and its visual ones:
:class:`VisualizationWrapper` and :class:`DomainRandomizationWrapper`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, SupportsFloat

import gymnasium as gym
import numpy as np

from ._demo_wrappers import DataCollectionWrapper, DemoSamplerWrapper, Wrapper
from ._visual_wrappers import DomainRandomizationWrapper, VisualizationWrapper
from .spaces import from_spec

if TYPE_CHECKING:
    from . import RobosuiteEnv

__all__ = [
    "RustEnv",
    "GymWrapper",
    "Wrapper",
    "DataCollectionWrapper",
    "DemoSamplerWrapper",
    "VisualizationWrapper",
    "DomainRandomizationWrapper",
]


class RustEnv(gym.Env):  # type: ignore[type-arg]
    """A ``gymnasium.Env`` delegating to a Rust environment (a ``_native.NativeEnv``).

    A pyo3 class cannot subclass ``gymnasium.Env``, so this thin class does: ``reset``
    calls ``super().reset(seed=seed)`` (so ``np_random`` is seeded as Gymnasium expects)
    and forwards the seed to Rust, which seeds the environment's own generator. Every
    call returns fresh NumPy arrays of the space's dtype, a Python ``float`` reward and
    Python ``bool`` flags. Errors raised in Rust arrive as exceptions carrying the Rust
    message (``ValueError`` for a bad action or argument); the env stays usable.
    """

    def __init__(self, native: Any) -> None:
        """Wraps ``native``, an object with the ``NativeEnv`` methods."""
        self._native = native
        self.observation_space = from_spec(native.observation_space_spec())
        self.action_space = from_spec(native.action_space_spec())
        metadata = dict(native.metadata())
        if metadata.get("render_fps") is None:
            metadata.pop("render_fps", None)
        self.metadata = metadata
        render_mode = getattr(native, "render_mode", None)
        self.render_mode = render_mode() if callable(render_mode) else None

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[Any, dict[str, Any]]:
        """Starts an episode; ``seed`` re-seeds both ``np_random`` and the Rust env.

        Raises:
            ValueError: for a negative seed or unknown options.
        """
        super().reset(seed=seed)
        return self._native.reset(seed, options)

    def step(self, action: Any) -> tuple[Any, SupportsFloat, bool, bool, dict[str, Any]]:
        """Applies ``action``.

        Raises:
            ValueError: for an action of the wrong shape or with NaN/inf, or when the
                episode has ended.
        """
        return self._native.step(action)

    def render(self) -> Any:
        """The frame of :attr:`render_mode`: an ``H×W×3`` uint8 array for ``"rgb_array"``,
        an ``H×W`` float32 array (raw depth in ``[0, 1]``) for ``"depth_array"``, ``None``
        without a render mode. Drawn in Rust with the GIL released.

        Raises:
            RuntimeError: when the offscreen renderer fails (the message names the cause).
        """
        render = getattr(self._native, "render", None)
        return render() if callable(render) else None

    def close(self) -> None:
        """Closes the Rust env; calling it again does nothing."""
        self._native.close()

    def __repr__(self) -> str:
        return f"<{type(self).__name__}{'<' + self.spec.id + '>' if self.spec else ''} {self._native!r}>"


class GymWrapper(RustEnv):
    """robosuite's ``GymWrapper(env, keys=None, flatten_obs=True)``, backed by Rust.

    ``env`` is a :class:`robosuite_rs.RobosuiteEnv` (from :func:`robosuite_rs.make`); the
    wrapper and ``env`` share the same simulation and observables, as in robosuite: an
    observable modified or added on ``env`` (``modify_observable`` / ``add_observable``,
    before or after wrapping) shows in the wrapper's observations.

    * ``keys``: observation keys to use; default robosuite's ``object-state`` (with
      ``use_object_obs``), each camera's ``{camera}_image`` (with ``use_camera_obs``), then
      each ``robot{i}_proprio-state``, keeping those observed at construction (robosuite's
      flat observations skip the others). A key the env does not observe (at construction,
      or at a later ``step`` / ``reset``, e.g. after ``modify_observable(key, "active",
      False)``) raises ``ValueError`` and nothing is stepped.
    * ``flatten_obs=True``: observations are one ``float32`` vector and
      ``observation_space`` is a ``float32`` Box; otherwise a Dict of the chosen keys (a
      Box of each observation's dtype: camera images ``uint8``). As in robosuite the space
      is made from the observation at construction; later observations follow the env's
      observables (a modality group that loses members shrinks).
    * Stepping: while every observable of ``env`` is as made, ``step`` / ``reset`` are one
      call into Rust; otherwise they run ``env.step`` / ``env.reset`` (robosuite's
      observables, substep by substep), with the same results on an unmodified env.
    * ``render()`` draws the env's ``render_mode`` (``make(..., render_mode="rgb_array")``);
      an env made with ``has_renderer=True`` (or ``render_mode="human"``) gives Gymnasium's
      ``render_mode="human"``: its window shows every step and reset at
      ``metadata["render_fps"]``.
    * ``action_space`` is a ``float32`` Box (robosuite's ``action_spec`` bounds); actions
      are taken as ``float32``.
    * Unlike robosuite's wrapper, ``reset(seed=...)`` really seeds the episode, the
      horizon is reported as ``truncated`` and ``info["success"]`` is set on every step.
      (On the ``env.step`` path an early termination on the horizon step itself, e.g.
      Wipe's, is reported as ``truncated`` only.)
    * ``unwrapped`` is this wrapper; it offers ``get_state()`` / ``set_state(flat)`` and
      ``check_success()`` of the robosuite env.
    """

    def __init__(self, env: RobosuiteEnv, keys: list[str] | None = None, flatten_obs: bool = True) -> None:
        """Wraps ``env``.

        Raises:
            ValueError: for a key the env does not observe (the message lists those it
                does), a duplicate key, or no key at all.
            TypeError: when ``env`` is not a ``robosuite_rs`` environment.
        """
        native_env = getattr(env, "_native", None)
        if native_env is None or not hasattr(native_env, "gym_env") or not hasattr(env, "_obsv"):
            raise TypeError(f"GymWrapper needs an env made by robosuite_rs.make, got {type(env).__name__}")
        if keys is not None and (isinstance(keys, str) or not all(isinstance(k, str) for k in keys)):
            raise ValueError(f"keys must be a list of observation names, got {keys!r}")
        obs = env.observation_spec()
        if keys is None:
            keys = [k for k in _default_keys(env) if k in obs]
        keys = list(keys)
        _check_keys(keys, obs)
        flatten_obs = bool(flatten_obs)
        # A native gym env over the same simulation: stepped while env's observables are
        # as made, and the source of the action space, metadata and render().
        native = _native_gym(env, keys, flatten_obs)
        # the key shapes `native` was made for (None: made for other keys)
        shapes = None if native is None else _native_shapes(env, keys)
        if native is None:
            native = _native_gym(env, None, flatten_obs) or _native_gym(env, list(native_env.observation_keys())[:1], True)
        if native is None:
            raise ValueError("GymWrapper: the env observes nothing the Rust core can serve")
        super().__init__(native)
        self.env = env
        self.keys = keys
        self.flatten_obs = flatten_obs
        self.name = env.name
        self.observation_space = _observation_space(obs, keys, flatten_obs)
        self._native_shapes = shapes
        self._route_key: tuple[int, bool] | None = None
        self._route: Any = None
        self._missing: list[str] = []
        self._next_frame = 0.0
        if getattr(env, "has_renderer", False) and self.render_mode is None:
            # Gymnasium's on-screen mode: the env's viewer, shown at every step and reset.
            self.metadata = dict(self.metadata, render_modes=[*self.metadata.get("render_modes", []), "human"])
            self.render_mode = "human"

    def _replan(self) -> None:
        """After a change of ``env``'s observables: which keys are missing, and whether the
        native gym env (rebuilt for the keys' current shapes) can step for ``env``."""
        obsv = self.env._obsv
        self._route_key = (obsv.version, obsv.fast)
        self._route = None
        observed = set(self.env.observation_keys())
        self._missing = [k for k in self.keys if k not in observed]
        if self._missing or not obsv.fast:
            return
        shapes = _native_shapes(self.env, self.keys)
        if shapes != self._native_shapes:
            native = _native_gym(self.env, self.keys, self.flatten_obs)
            if native is None:
                return
            self._native, self._native_shapes = native, shapes
        self._route = self._native

    def _observe(self, obs_dict: Any) -> Any:
        """robosuite's ``_flatten_obs`` (as ``float32``) / ``_filter_obs`` of ``obs_dict``."""
        if self.flatten_obs:
            return np.concatenate([np.asarray(obs_dict[k]).ravel() for k in self.keys]).astype(np.float32)
        return {k: np.array(obs_dict[k]) for k in self.keys}

    def _check_observed(self) -> Any:
        """The native gym env to step, or ``None`` for ``env``'s own step / reset.

        Raises:
            ValueError: when a key is not observed now (nothing is stepped).
        """
        obsv = self.env._obsv
        if (obsv.version, obsv.fast) != self._route_key:
            self._replan()
        if self._missing:
            raise ValueError(
                f"GymWrapper: observation key(s) {self._missing} are not observed by the env any more "
                f"(disabled or deactivated); observed: {self.env.observation_keys()}"
            )
        return self._route

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[Any, dict[str, Any]]:
        """Starts an episode; ``seed`` re-seeds both ``np_random`` and the env.

        Raises:
            ValueError: for a negative seed, unknown options, or a key not observed.
        """
        native = self._check_observed()
        if native is not None:
            out = super().reset(seed=seed, options=options)
        else:
            if options:
                raise ValueError(f"unknown key `{next(iter(options))}`; available: ")
            gym.Env.reset(self, seed=seed)
            obs = self.env.reset(seed)
            out = self._observe(obs), {"success": bool(self.env.check_success())}
        if self.render_mode == "human":
            self.render()
        return out

    def step(self, action: Any) -> tuple[Any, SupportsFloat, bool, bool, dict[str, Any]]:
        """Applies ``action``.

        Raises:
            ValueError: for an action of the wrong shape or with NaN/inf, when the episode
                has ended, or for a key not observed (nothing is stepped); as ``env.step``
                when an observable fails.
        """
        obsv = self.env._obsv
        if (obsv.version, obsv.fast) == self._route_key and self._route is not None:
            out = self._route.step(action)
        elif self._check_observed() is not None:
            out = self._route.step(action)
        else:
            obs, reward, done, info = self.env.step(_f32(action))
            env = self.env
            truncated = env.timestep >= env.horizon and not env.ignore_done
            out = self._observe(obs), float(reward), bool(done and not truncated), bool(truncated), info
        if self.render_mode == "human":
            self.render()
        return out

    def render(self) -> Any:
        """The frame of ``render_mode`` (``"rgb_array"`` / ``"depth_array"``, see
        :meth:`RustEnv.render`); with ``"human"`` (an env made with ``has_renderer=True`` or
        ``render_mode="human"``) shows the env's viewer window, at most
        ``metadata["render_fps"]`` times a second (``step`` and ``reset`` call it), and
        returns ``None``.

        Raises:
            RuntimeError: as ``env.render()`` (no display, a closed env).
        """
        if self.render_mode != "human":
            return super().render()
        import time

        fps = self.metadata.get("render_fps")
        if fps:
            now = time.perf_counter()
            if self._next_frame > now:
                time.sleep(self._next_frame - now)
            self._next_frame = max(now, self._next_frame) + 1.0 / float(fps)
        self.env.render()
        return None

    def close(self) -> None:
        """Closes the env and its viewer window; calling it again does nothing."""
        self.env.close()
        super().close()

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickling and ``copy.deepcopy``: a GymWrapper over a copy of the wrapped env (see
        :meth:`robosuite_rs.RobosuiteEnv.__reduce__`)."""
        return (type(self), (self.env, self.keys, self.flatten_obs))

    def get_state(self) -> np.ndarray:
        """The flat simulator state ``[time, qpos, qvel]``."""
        return self.env.get_state()

    def set_state(self, state: Any) -> None:
        """Sets the flat simulator state ``[time, qpos, qvel]``.

        Raises:
            ValueError: for a wrong length or a non-finite value.
        """
        self.env.set_state(state)

    def check_success(self) -> bool:
        """Whether the task is solved in the current state."""
        return self.env.check_success()

    def __getattr__(self, name: str) -> Any:
        """robosuite's ``Wrapper`` forwarding: attributes this wrapper lacks are the wrapped
        env's (``gym_env.sim``, ``gym_env.robots``, ``gym_env.reward()``, ...)."""
        env = self.__dict__.get("env")
        if env is None or name.startswith("__"):
            raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")
        return getattr(env, name)


def _default_keys(env: Any) -> list[str]:
    """robosuite 1.5's default GymWrapper keys for ``env``."""
    keys = ["object-state"] if env.use_object_obs else []
    if env.use_camera_obs:
        keys += [f"{cam}_image" for cam in env.camera_names]
    return keys + [f"robot{i}_proprio-state" for i in range(len(env._native.robots_info()))]


def _check_keys(keys: list[str], obs: Any) -> None:
    if not keys:
        raise ValueError(f"GymWrapper: no observation keys selected (observed: {list(obs)})")
    missing = [k for k in keys if k not in obs]
    if missing:
        raise ValueError(f"GymWrapper: observation key(s) {missing} are not observed by the env; observed: {list(obs)}")
    dup = sorted({k for k in keys if keys.count(k) > 1})
    if dup:
        raise ValueError(f"GymWrapper: duplicate key(s) {dup}")


def _box_spec(sample: Any) -> tuple[Any, ...]:
    """robosuite's ``get_box_space`` as a space description: integer dtypes span their
    range, floats ``(-inf, inf)``."""
    a = np.asarray(sample)
    if a.dtype.kind not in "biuf":
        raise ValueError(f"GymWrapper: observation of dtype {a.dtype} has no Box space")
    inf = np.full(a.shape, np.inf)
    return ("Box", -inf, inf, a.dtype.name)


def _observation_space(obs: Any, keys: list[str], flatten_obs: bool) -> Any:
    """robosuite's ``observation_space`` from the observation ``obs``."""
    if flatten_obs:
        n = sum(np.asarray(obs[k]).size for k in keys)
        return from_spec(("Box", np.full(n, -np.inf), np.full(n, np.inf), "float32"))
    return from_spec(("Dict", [(k, _box_spec(obs[k])) for k in keys]))


def _native_gym(env: Any, keys: list[str] | None, flatten_obs: bool) -> Any:
    """A native gym env over ``env`` for ``keys`` (``None``: when the Rust core cannot
    serve them, e.g. an added observable)."""
    try:
        return env._native.gym_env(keys, flatten_obs)
    except (ValueError, KeyError, RuntimeError):
        return None


def _native_shapes(env: Any, keys: list[str]) -> dict[str, tuple[int, ...]] | None:
    """The shapes of ``keys`` in the Rust core's observation space now."""
    spaces_ = dict(env._native.observation_space_spec()[1])
    if not all(k in spaces_ for k in keys):
        return None
    return {k: np.shape(spaces_[k][1]) for k in keys}


def _f32(action: Any) -> Any:
    """A numeric action as the native gym env takes it (``float32``); anything else as is
    (``env.step`` says what is wrong with it)."""
    try:
        a = np.asarray(action)
    except Exception:
        return action
    return a.astype(np.float32) if a.dtype.kind in "biuf" else action
