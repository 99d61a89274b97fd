"""Gymnasium environments backed by Rust: :class:`RustEnv` (any env exported from Rust)
and :class:`GymWrapper` (robosuite's ``GymWrapper``, served by the Rust core).

Import swap for robosuite users::

    from robosuite_rs.wrappers import GymWrapper   # was: from robosuite.wrappers import GymWrapper
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, SupportsFloat

import gymnasium as gym
import numpy as np

from .spaces import from_spec

if TYPE_CHECKING:
    from . import RobosuiteEnv

__all__ = ["RustEnv", "GymWrapper"]


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
    wrapper and ``env`` share the same simulation, as in robosuite.

    * ``keys``: observation keys to use; default ``object-state``, each camera's
      ``{camera}_image`` (with ``use_camera_obs=True``), then ``robot{i}_proprio-state``
      (robosuite's default order, computed by the Rust core).
    * ``flatten_obs=True``: observations are one ``float32`` vector and
      ``observation_space`` is a ``float32`` Box; otherwise a Dict of the chosen keys
      (camera images as ``uint8`` Boxes ``(H, W, 3)``).
    * ``render()`` draws the env's ``render_mode`` (``make(..., render_mode="rgb_array")``).
    * ``action_space`` is a ``float32`` Box (robosuite's ``action_spec`` bounds).
    * Unlike robosuite's wrapper, ``reset(seed=...)`` really seeds the episode, the
      horizon is reported as ``truncated`` and ``info["success"]`` is set on every step.
    * ``unwrapped`` is this wrapper; it offers ``get_state()`` / ``set_state(flat)`` and
      ``check_success()`` of the robosuite env.
    """

    def __init__(self, env: RobosuiteEnv, keys: list[str] | None = None, flatten_obs: bool = True) -> None:
        """Wraps ``env``.

        Raises:
            ValueError: for an unknown key.
            TypeError: when ``env`` is not a ``robosuite_rs`` environment.
        """
        native_env = getattr(env, "_native", None)
        if native_env is None or not hasattr(native_env, "gym_env"):
            raise TypeError(f"GymWrapper needs an env made by robosuite_rs.make, got {type(env).__name__}")
        super().__init__(native_env.gym_env(None if keys is None else list(keys), bool(flatten_obs)))
        self.env = env
        self.keys = list(keys) if keys is not None else list(native_env.default_gym_keys())
        self.flatten_obs = bool(flatten_obs)
        self.name = env.name

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
