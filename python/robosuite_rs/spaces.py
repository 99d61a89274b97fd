"""Gymnasium spaces from the descriptions the Rust core gives (``NativeEnv.*_space_spec()``)."""

from __future__ import annotations

import inspect
from collections import OrderedDict
from typing import Any

import numpy as np
from gymnasium import spaces

__all__ = ["from_spec"]

_DICT_HAS_SORT_KEYS = "sort_keys" in inspect.signature(spaces.Dict.__init__).parameters


def _bounds(values: np.ndarray, dtype: np.dtype) -> np.ndarray:
    """Bounds as an array of ``dtype``; for integer dtypes ±inf becomes the dtype's limits
    (set directly: ``float(iinfo(int64).max)`` does not cast back to int64)."""
    values = np.asarray(values, dtype=np.float64)
    if not np.issubdtype(dtype, np.integer):
        return values.astype(dtype)
    info = np.iinfo(dtype)
    out = np.zeros(values.shape, dtype=dtype)
    finite = np.isfinite(values)
    out[finite] = values[finite].astype(dtype)
    out[np.isneginf(values)] = info.min
    out[np.isposinf(values)] = info.max
    return out


def from_spec(spec: tuple[Any, ...]) -> spaces.Space[Any]:
    """Builds the ``gymnasium.spaces`` object a Rust space description stands for.

    Descriptions: ``("Box", low, high, dtype)``, ``("Discrete", n, start)``,
    ``("MultiDiscrete", nvec, start)``, ``("MultiBinary", shape)``,
    ``("Dict", [(key, spec), ...])`` (order kept, never sorted) and
    ``("Tuple", [spec, ...])``.

    Raises:
        ValueError: for an unknown kind of space.
    """
    kind = spec[0]
    if kind == "Box":
        _, low, high, dtype_name = spec
        dtype = np.dtype(dtype_name)
        return spaces.Box(low=_bounds(low, dtype), high=_bounds(high, dtype), dtype=dtype)
    if kind == "Discrete":
        _, n, start = spec
        return spaces.Discrete(int(n), start=int(start))
    if kind == "MultiDiscrete":
        _, nvec, start = spec
        return spaces.MultiDiscrete(np.asarray(nvec, dtype=np.int64), start=np.asarray(start, dtype=np.int64))
    if kind == "MultiBinary":
        _, shape = spec
        shape = list(shape)
        return spaces.MultiBinary(shape[0] if len(shape) == 1 else shape)
    if kind == "Dict":
        items = [(key, from_spec(sub)) for key, sub in spec[1]]
        if _DICT_HAS_SORT_KEYS:
            return spaces.Dict(items, sort_keys=False)
        return spaces.Dict(OrderedDict(items))
    if kind == "Tuple":
        return spaces.Tuple([from_spec(sub) for sub in spec[1]])
    raise ValueError(f"unknown space kind {kind!r}")
