"""Decoding of the recorded robosuite values in ``fixtures/robosuite_utils`` (format:
``scripts/record_utils.py``)."""

from __future__ import annotations

from typing import Any

import numpy as np


def decode(x: Any) -> Any:
    """The Python/NumPy value of a fixture entry."""
    if isinstance(x, list):
        return [decode(v) for v in x]
    if isinstance(x, dict):
        if "array" in x:
            return np.array(x["array"], dtype=x["dtype"]).reshape(x["shape"])
        if "scalar" in x:
            return np.dtype(x["dtype"]).type(x["scalar"])
        if "tuple" in x:
            return tuple(decode(v) for v in x["tuple"])
        if "RandomState" in x:
            return np.random.RandomState(x["RandomState"])
        if "Generator" in x:
            return np.random.default_rng(x["Generator"])
        return {k: decode(v) for k, v in x.items()}
    return x
