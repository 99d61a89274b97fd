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

    * ``reset(seed=s)`` seeds env ``i`` with ``s + i`` (as ``SyncVectorEnv``); a list seeds
      each env; ``options={"reset_mask": mask}`` resets only some envs.
    * Autoreset is Gymnasium's ``NEXT_STEP``: an env whose episode ended is reset on the
      next ``step`` (its action is ignored; reward 0, flags False).
    * Observations are batched in Rust: each env writes its observation (camera images
      included) straight into its row of one batch, which ``step`` and ``reset`` copy into
      fresh arrays; with ``copy=False`` (Gymnasium's ``AsyncVectorEnv`` argument) they
      return read-only views of the batch instead (no copy), overwritten by the next
      ``step`` or ``reset``. Infos come with Gymnasium's ``_key`` masks.
    """

    def __init__(self, native: Any, copy: bool = True) -> None:
        """Wraps ``native``, an object with the ``NativeVecEnv`` methods."""
        self._native = native
        self.copy = bool(copy)
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
        self,
        *,
        seed: int | list[int | None] | None = None,
        options: dict[str, Any] | None = None,
    ) -> tuple[Any, dict[str, Any]]:
        """Resets the envs, as Gymnasium's vector envs do.

        * ``seed``: an integer (env ``i`` gets ``seed + i``), a list with one optional
          seed per env, or ``None`` (each env continues its own stream).
        * ``options["reset_mask"]``: a bool array of shape ``(num_envs,)``; only those envs
          are reset, the others keep their observation and state. Other options go to
          every env that is reset.

        Raises:
            ValueError: for a seed list of the wrong length, a negative seed, a malformed
                mask or an option the envs do not know.
        """
        if isinstance(seed, (int, np.integer)):
            super().reset(seed=int(seed))
            native_seed: Any = int(seed)
        elif seed is None:
            super().reset(seed=None)
            native_seed = None
        else:
            native_seed = [None if s is None else int(s) for s in seed]
        return self._native.reset(native_seed, dict(options) if options else None, self.copy)

    def step(self, actions: Any) -> tuple[Any, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        """Steps every env with its row of ``actions`` (batched as ``action_space``).

        Raises:
            ValueError: for a malformed action.
        """
        return self._native.step(actions, self.copy)

    def close_extras(self, **kwargs: Any) -> None:
        """Closes the Rust envs."""
        self._native.close()
