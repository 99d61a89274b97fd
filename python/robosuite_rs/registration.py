"""Registration of the Rust environments with Gymnasium (``robosuite_rs/<Name>-v0``)."""

from __future__ import annotations

from typing import Any

import gymnasium

from . import _native

__all__ = ["register_envs", "make_gym_env", "make_registered_env", "gym_id", "NAMESPACE"]

NAMESPACE = "robosuite_rs"


def gym_id(name: str) -> str:
    """The Gymnasium id of the Rust env ``name`` (``robosuite_rs/<name>-v0``)."""
    return f"{NAMESPACE}/{name}-v0"


def make_gym_env(env_name: str, keys: list[str] | None = None, flatten_obs: bool = True, **kwargs: Any) -> gymnasium.Env:  # type: ignore[type-arg]
    """``GymWrapper(make(env_name, **kwargs), keys, flatten_obs)``: the entry point of the
    robosuite ids."""
    from . import make
    from .wrappers import GymWrapper

    return GymWrapper(make(env_name, **kwargs), keys=keys, flatten_obs=flatten_obs)


# Read by ``gymnasium.make`` before it calls the entry point: with these render modes it
# maps ``render_mode="rgb_array_list"`` to ``RenderCollection`` over ``"rgb_array"`` (the
# env's own ``metadata`` also has ``render_fps``, its control frequency) and passes
# ``render_mode="human"`` on (robosuite's viewer, see ``make``).
make_gym_env.metadata = {"render_modes": ["rgb_array", "depth_array", "human"]}  # type: ignore[attr-defined]


def make_registered_env(env_id: str, **kwargs: Any) -> gymnasium.Env:  # type: ignore[type-arg]
    """Any env of the Rust registry (``gym_core::registry``) as a ``gymnasium.Env``."""
    from .wrappers import RustEnv

    return RustEnv(_native.make_registered(env_id, kwargs))


def register_envs() -> list[str]:
    """Registers every Rust env with Gymnasium (idempotent); returns the Gymnasium ids.

    robosuite tasks (``robosuite_rs/Lift-v0``) make the GymWrapper'd env and accept
    robosuite's keyword arguments plus ``keys`` and ``flatten_obs``; they also have a
    vector entry point (``gymnasium.make_vec`` steps them in Rust threads). Other ids of
    the Rust registry make a :class:`~robosuite_rs.wrappers.RustEnv`.
    """
    ids = []
    robosuite_names = set(_native.robosuite_env_names())
    for name in _native.registered_ids():
        env_id = gym_id(name)
        ids.append(env_id)
        if env_id in gymnasium.registry:
            continue
        if name in robosuite_names:
            gymnasium.register(
                id=env_id,
                entry_point="robosuite_rs.registration:make_gym_env",
                vector_entry_point="robosuite_rs:make_vec",
                kwargs={"env_name": name},
            )
        else:
            gymnasium.register(
                id=env_id,
                entry_point="robosuite_rs.registration:make_registered_env",
                kwargs={"env_id": name},
            )
    return ids
