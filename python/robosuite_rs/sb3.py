"""A Stable-Baselines3 ``VecEnv`` stepping Rust environments in Rust threads: :class:`RustVecEnv`.

SB3 trains on ``num_envs`` envs at once through its ``VecEnv`` API; ``SubprocVecEnv`` runs
each env in its own Python process. :class:`RustVecEnv` runs them on the Rust worker
threads of :func:`robosuite_rs.make_vec` (one process, GIL released while the envs step)::

    from stable_baselines3 import PPO
    from robosuite_rs.sb3 import make_sb3_vec_env

    venv = make_sb3_vec_env("Lift", 8, seed=0, horizon=200)
    PPO("MlpPolicy", venv).learn(100_000)

It follows SB3's ``VecEnv`` contract exactly: ``reset()`` returns only observations and
uses the seeds given to ``seed()`` once; an env whose episode ends is reset at once (the
returned row is the new episode's first observation, the last one is in
``infos[i]["terminal_observation"]``; ``infos[i]["TimeLimit.truncated"]``, on every step as in
``DummyVecEnv``, says whether the episode was cut by a time limit); rewards are ``float32``, dones ``bool``. ``VecNormalize``,
``VecMonitor``, ``EvalCallback`` and ``model.learn`` work on it. Importing this module
needs ``stable-baselines3``; ``robosuite_rs`` itself does not.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from stable_baselines3.common.vec_env.base_vec_env import VecEnv, VecEnvIndices, VecEnvObs, VecEnvStepReturn

from .vector import RustVectorEnv

__all__ = ["RustVecEnv", "make_sb3_vec_env"]


def _row(obs: Any, i: int) -> Any:
    """Env ``i``'s observation of a batch (a copy: the batch may be reused)."""
    if isinstance(obs, dict):
        return {k: _row(v, i) for k, v in obs.items()}
    if isinstance(obs, tuple):
        return tuple(_row(v, i) for v in obs)
    return np.array(obs[i], copy=True)


def _scalar(value: Any) -> Any:
    """A NumPy scalar as a Python one (what SB3's per-env infos hold)."""
    return value.item() if isinstance(value, np.generic) else value


def _split_info(info: dict[str, Any], n: int) -> list[dict[str, Any]]:
    """Gymnasium's vector infos (arrays with ``_key`` masks) as one dict per env."""
    out: list[dict[str, Any]] = [{} for _ in range(n)]
    for key, value in info.items():
        if key.startswith("_"):
            continue
        mask = info.get("_" + key)
        rows = _split_info(value, n) if isinstance(value, dict) else [_scalar(value[i]) for i in range(n)]
        for i in range(n):
            if mask is None or mask[i]:
                out[i][key] = rows[i]
    for row in out:
        # SB3's success convention (Monitor, EvalCallback): `is_success`.
        if "success" in row and "is_success" not in row:
            row["is_success"] = bool(row["success"])
    return out


class RustVecEnv(VecEnv):
    """SB3's ``VecEnv`` over a :class:`~robosuite_rs.vector.RustVectorEnv`.

    There are no Python sub-envs: ``get_attr`` answers ``render_mode``, ``metadata``,
    ``observation_space``, ``action_space`` and ``spec`` (the same for every env) and
    raises ``AttributeError`` for anything else, as ``SubprocVecEnv`` does for an attribute
    its envs lack; ``set_attr`` and ``env_method`` raise ``AttributeError`` (nothing can be
    set or called on a Rust env from here); ``env_is_wrapped`` is ``False`` for every
    wrapper (use ``VecMonitor`` rather than ``Monitor``). ``render`` is SB3's, with
    ``render_mode=None``: it draws nothing (``get_images`` gives ``None`` per env).
    """

    _ATTRS = ("render_mode", "metadata", "observation_space", "action_space", "spec")

    def __init__(self, venv: RustVectorEnv) -> None:
        """Wraps ``venv`` (from :func:`robosuite_rs.make_vec` in its default Rust mode).

        Raises:
            TypeError: when ``venv`` is not a ``RustVectorEnv``.
        """
        if not isinstance(venv, RustVectorEnv):
            raise TypeError(f"RustVecEnv wraps a robosuite_rs RustVectorEnv, got {type(venv).__name__}")
        #: The wrapped Rust vector env (not ``venv``: SB3 reads that name on its wrappers).
        self.vector_env = venv
        self._actions: np.ndarray | None = None
        super().__init__(venv.num_envs, venv.single_observation_space, venv.single_action_space)

    # --- the VecEnv API ------------------------------------------------------------------
    def reset(self) -> VecEnvObs:
        """Resets every env with the seeds and options given since the last reset (then
        forgets them, as SB3 does); returns the batched observations.

        Raises:
            ValueError: for per-env options that differ (the Rust vector takes one set).
        """
        seeds = list(self._seeds)
        options = [dict(o or {}) for o in self._options]
        if any(o != options[0] for o in options):
            raise ValueError("RustVecEnv.reset: per-env options must be the same for every env")
        seed: Any = None if all(s is None for s in seeds) else seeds
        obs, info = self.vector_env.reset(seed=seed, options=options[0] or None)
        self.reset_infos = _split_info(info, self.num_envs)
        self._reset_seeds()
        self._reset_options()
        self._actions = None
        return obs

    def step_async(self, actions: np.ndarray) -> None:
        """Keeps ``actions`` for :meth:`step_wait`."""
        self._actions = actions

    def step_wait(self) -> VecEnvStepReturn:
        """Steps every env in Rust threads; ends and resets finished episodes as SB3 does.

        Raises:
            RuntimeError: without a preceding :meth:`step_async`.
            ValueError: for a malformed action (nothing is stepped).
        """
        if self._actions is None:
            raise RuntimeError("RustVecEnv.step_wait called without step_async")
        actions, self._actions = self._actions, None
        obs, rewards, terminated, truncated, info = self.vector_env.step(actions)
        dones = np.logical_or(terminated, truncated)
        infos = _split_info(info, self.num_envs)
        for i, row in enumerate(infos):
            row["TimeLimit.truncated"] = bool(truncated[i] and not terminated[i])
        if dones.any():
            for i in np.flatnonzero(dones):
                infos[i]["terminal_observation"] = _row(obs, i)
            obs, reset_info = self.vector_env.reset(options={"reset_mask": dones})
            for i, row in enumerate(_split_info(reset_info, self.num_envs)):
                if dones[i]:
                    self.reset_infos[i] = row
        return obs, np.asarray(rewards, dtype=np.float32), dones, infos

    def close(self) -> None:
        """Closes the Rust envs."""
        self.vector_env.close()

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        """``attr_name`` of each env in ``indices`` (see the class doc for what exists).

        Raises:
            AttributeError: for any other attribute.
        """
        values = {
            "render_mode": getattr(self.vector_env, "render_mode", None),
            "metadata": self.vector_env.metadata,
            "observation_space": self.vector_env.single_observation_space,
            "action_space": self.vector_env.single_action_space,
            "spec": None,
        }
        if attr_name not in values:
            raise AttributeError(f"robosuite_rs RustVecEnv envs have no attribute {attr_name!r} (only {', '.join(self._ATTRS)})")
        return [values[attr_name] for _ in self._get_indices(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        """Nothing can be set on the Rust envs.

        Raises:
            AttributeError: always.
        """
        raise AttributeError(f"robosuite_rs RustVecEnv cannot set {attr_name!r} on its Rust envs")

    def env_method(self, method_name: str, *method_args: Any, indices: VecEnvIndices = None, **method_kwargs: Any) -> list[Any]:
        """No Python method can be called on the Rust envs.

        Raises:
            AttributeError: always.
        """
        raise AttributeError(f"robosuite_rs RustVecEnv envs have no method {method_name!r}")

    def get_images(self) -> Sequence[np.ndarray | None]:
        """``None`` for each env: the Rust vector env has no render mode."""
        return [None for _ in range(self.num_envs)]

    def env_is_wrapped(self, wrapper_class: type, indices: VecEnvIndices = None) -> list[bool]:
        """``False`` for each env: the Rust envs carry no Python wrapper."""
        return [False for _ in self._get_indices(indices)]


def make_sb3_vec_env(
    env_name: str,
    num_envs: int,
    robots: str | Sequence[str] | None = None,
    *,
    seed: int | None = None,
    **kwargs: Any,
) -> RustVecEnv:
    """``RustVecEnv(robosuite_rs.make_vec(env_name, num_envs, robots, **kwargs))``, seeded
    with ``seed`` (env ``i`` gets ``seed + i`` at the first reset) when given.

    Takes :func:`robosuite_rs.make_vec`'s arguments of its Rust mode (``max_episode_steps``,
    ``threads``, ``keys``, ``flatten_obs`` and robosuite's keyword arguments).

    Raises:
        ValueError, TypeError: as :func:`robosuite_rs.make_vec`.
    """
    from . import make_vec

    venv = RustVecEnv(make_vec(env_name, num_envs, robots, **kwargs))
    if seed is not None:
        venv.seed(seed)
    return venv
