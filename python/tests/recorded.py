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


def assert_array(ours: Any, ref: dict, tol: float, where: str = "result") -> None:
    """``ours`` is an ndarray with the dtype, shape and (within ``tol``; exactly for
    integers) the values of the fixture array ``ref``."""
    expected = decode(ref)
    assert isinstance(ours, np.ndarray), f"{where}: {type(ours)} is not an ndarray"
    assert ours.dtype == expected.dtype, f"{where}: dtype {ours.dtype} != {expected.dtype}"
    assert ours.shape == expected.shape, f"{where}: shape {ours.shape} != {expected.shape}"
    if np.issubdtype(expected.dtype, np.floating):
        np.testing.assert_allclose(ours, expected, rtol=tol, atol=tol, err_msg=where)
    else:
        np.testing.assert_array_equal(ours, expected, err_msg=where)
