"""EnvPool's asynchronous mode for Rust environments: :class:`EnvPool`.

``recv()`` returns the first ``batch_size`` environments to finish a step, with their ids in
``info["env_id"]``; ``send(actions, env_id)`` gives exactly those their next actions. The
Rust threads never wait for the slowest environment of a batch, so a pool of ``2-3 x
batch_size`` envs keeps every core busy (EnvPool's usage, as in CleanRL's async PPO).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium.vector.utils import batch_space

from .spaces import from_spec

__all__ = ["EnvPool"]


class EnvPool:
    """A pool of Rust environments (a ``_native.NativeEnvPool``: adapters'
    ``ThreadEnvPool``) stepped on Rust threads with the GIL released.

    * ``async_reset(seed=s)`` queues a reset of every env (env ``i`` gets ``s + i``);
      ``reset(seed=s)`` is ``async_reset`` then ``recv``.
    * ``recv() -> (obs, reward, terminated, truncated, info)``: ``batch_size`` rows, in the
      order the envs finished; ``info["env_id"]`` says which env each row is.
    * ``send(actions, env_id)``: one action row per id of the last ``recv``. An env whose
      episode ended is reset instead (its action ignored; reward 0, flags False), as
      EnvPool and Gymnasium's ``NEXT_STEP`` autoreset do.
    * ``step(actions, env_id=None)`` is ``send`` then ``recv`` (default ids: the last
      ``recv``'s).

    Each env's trajectory depends only on its seed and the actions sent to it. Each env
    writes its observation (camera images included) straight into its row of the batch,
    which ``recv`` copies into fresh arrays; with ``copy=False`` it returns read-only views
    of the batch instead (no copy), overwritten by the next ``recv``.
    """

    def __init__(self, native: Any, copy: bool = True) -> None:
        """Wraps ``native``, an object with the ``NativeEnvPool`` methods."""
        self._native = native
        self.copy = bool(copy)
        self.num_envs = int(native.num_envs)
        self.batch_size = int(native.batch_size)
        self.single_observation_space = from_spec(native.observation_space_spec())
        self.single_action_space = from_spec(native.action_space_spec())
        self.observation_space = batch_space(self.single_observation_space, self.batch_size)
        self.action_space = batch_space(self.single_action_space, self.batch_size)
        self.metadata = dict(native.metadata())
        self._last_ids: np.ndarray | None = None
        self.closed = False

    def async_reset(self, seed: int | list[int | None] | None = None) -> None:
        """Queues a reset of every env: an integer gives env ``i`` ``seed + i``, a list one
        optional seed per env.

        Raises:
            ValueError: for a negative seed or a list of the wrong length.
        """
        if seed is None or isinstance(seed, (int, np.integer)):
            self._native.async_reset(None if seed is None else int(seed))
        else:
            self._native.async_reset([None if s is None else int(s) for s in seed])

    def recv(self) -> tuple[Any, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        """The first ``batch_size`` envs to finish.

        Raises:
            ValueError: when fewer than ``batch_size`` envs are pending, or for an env's error.
        """
        out = self._native.recv(self.copy)
        self._last_ids = out[4]["env_id"]
        return out

    def send(self, actions: Any, env_id: Any) -> None:
        """Gives the envs ``env_id`` (one per row of ``actions``) their next actions.

        Raises:
            ValueError: for an id that is unknown, repeated or still pending, or actions
                that are not exactly one finite row per id; nothing is sent then.
            TypeError: for ids that are not integers (``0.5`` is never truncated).
        """
        ids = np.asarray(env_id)
        if ids.ndim > 1 or (ids.size and ids.dtype.kind not in "iu"):
            raise TypeError(
                f"env_id must be an integer id or a 1-D sequence of integer ids, got {env_id!r}"
            )
        self._native.send(actions, [int(i) for i in ids.reshape(-1)])

    def reset(self, *, seed: int | list[int | None] | None = None) -> tuple[Any, dict[str, Any]]:
        """``async_reset`` then ``recv``: the first ``batch_size`` reset observations."""
        self.async_reset(seed)
        obs, _, _, _, info = self.recv()
        return obs, info

    def step(
        self, actions: Any, env_id: Any = None
    ) -> tuple[Any, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        """``send`` then ``recv``; ``env_id`` defaults to the last ``recv``'s ids."""
        if env_id is None:
            if self._last_ids is None:
                raise ValueError("step needs env_id before the first recv (call reset first)")
            env_id = self._last_ids
        self.send(actions, env_id)
        return self.recv()

    def close(self) -> None:
        """Closes the envs and joins the Rust threads; calling it again does nothing."""
        if not self.closed:
            self._native.close()
            self.closed = True

    def __enter__(self) -> "EnvPool":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"<EnvPool num_envs={self.num_envs} batch_size={self.batch_size}>"
