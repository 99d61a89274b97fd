"""A ``gymnasium.vector.VectorEnv`` stepping Rust environments in Rust threads."""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from .spaces import from_spec

__all__ = ["RustVectorEnv"]


class RustVectorEnv(VectorEnv):  # type: ignore[type-arg]
    """A vector of Rust environments (a ``_native.NativeVecEnv``: adapters'
    ``ThreadVectorEnv``) stepped in parallel on Rust worker threads with the GIL released.

    * ``reset(seed=s)`` seeds env ``i`` with ``s + i`` (as ``SyncVectorEnv``).
    * Autoreset is Gymnasium's ``NEXT_STEP``: an env whose episode ended is reset on the
      next ``step`` (its action is ignored; reward 0, flags False).
    * Observations are batched in Rust into fresh arrays; infos come with Gymnasium's
      ``_key`` masks.
    """

    def __init__(self, native: Any) -> None:
        """Wraps ``native``, an object with the ``NativeVecEnv`` methods."""
        self._native = native
        self.num_envs = int(native.num_envs)
        self.single_observation_space = from_spec(native.observation_space_spec())
        self.single_action_space = from_spec(native.action_space_spec())
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        metadata = dict(native.metadata())
        if metadata.get("render_fps") is None:
            metadata.pop("render_fps", None)
        metadata["autoreset_mode"] = AutoresetMode.NEXT_STEP
        self.metadata = metadata
        self.render_mode = None

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[Any, dict[str, Any]]:
        """Resets every env; env ``i`` gets ``seed + i``.

        Raises:
            ValueError: for a list of seeds or for options (not supported).
        """
        if seed is not None and not isinstance(seed, (int, np.integer)):
            raise ValueError("RustVectorEnv.reset takes one integer seed (env i gets seed + i) or None")
        if options:
            raise ValueError(f"RustVectorEnv.reset does not support options, got {sorted(options)}")
        super().reset(seed=seed)
        return self._native.reset(None if seed is None else int(seed))

    def step(self, actions: Any) -> tuple[Any, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        """Steps every env with its row of ``actions`` (batched as ``action_space``).

        Raises:
            ValueError: for a malformed action.
        """
        return self._native.step(actions)

    def close_extras(self, **kwargs: Any) -> None:
        """Closes the Rust envs."""
        self._native.close()
