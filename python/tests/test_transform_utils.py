"""``robosuite_rs.utils.transform_utils`` gives robosuite 1.5.2's results.

The fixture python/tests/fixtures/robosuite_utils/transform_utils.json holds robosuite's own
calls (scripts/record_utils.py, robosuite 1.5.2 with its default numba JIT on NumPy 1.26):
arguments, results or the exception raised, and the arguments a call changed in place.
Each case is replayed here and must give the same types, dtypes, shapes and values.

Tolerance: 1e-12 (absolute and relative) where robosuite computes in float64. robosuite
computes some functions in float32 (``FLOAT32_FUNCTIONS`` and any call with a float32
argument); their last bits depend on the BLAS/LAPACK build (float32 dot products,
``mat2quat``'s eigen-solver), so those compare to 1e-6, a few float32 roundings.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from robosuite_rs.utils import transform_utils as T

from .recorded import assert_array, decode

FIXTURE = Path(__file__).parent / "fixtures" / "robosuite_utils" / "transform_utils.json"
DATA = json.loads(FIXTURE.read_text())

F64_TOL = 1e-12
F32_TOL = 1e-6

# robosuite computes these in float32 (whatever the input dtype).
FLOAT32_FUNCTIONS = {
    "quat_multiply",
    "quat_conjugate",
    "quat_inverse",
    "quat_distance",
    "quat_slerp",
    "random_quat",
    "vec",
    "mat4",
    "mat2pose",
    "mat2quat",
    "mat2euler",
    "pose2mat",
    "quat2mat",
    "rotation_matrix",
    "unit_vector",
}

# numba's np.linalg.inv (robosuite) and NumPy's word "singular" differently.
MESSAGE_DIFFERS = {"matrix_inverse"}

def has_float32(x: Any) -> bool:
    if isinstance(x, list):
        return any(has_float32(v) for v in x)
    if isinstance(x, dict):
        if x.get("dtype") == "float32":
            return True
        return any(has_float32(v) for v in x.values())
    return False


def assert_matches(ours: Any, ref: Any, tol: float, where: str = "result") -> None:
    """``ours`` has the type, dtype, shape and (within ``tol``) the values of fixture ``ref``."""
    if isinstance(ref, dict) and "array" in ref:
        assert_array(ours, ref, tol, where)
    elif isinstance(ref, dict) and "scalar" in ref:
        expected = decode(ref)
        assert isinstance(ours, np.generic), f"{where}: {type(ours)} is not a NumPy scalar"
        assert ours.dtype == expected.dtype, f"{where}: dtype {ours.dtype} != {expected.dtype}"
        assert math.isclose(float(ours), float(expected), rel_tol=tol, abs_tol=tol), where
    elif isinstance(ref, dict) and "tuple" in ref:
        assert isinstance(ours, tuple), f"{where}: {type(ours)} is not a tuple"
        assert len(ours) == len(ref["tuple"]), where
        for i, (o, r) in enumerate(zip(ours, ref["tuple"])):
            assert_matches(o, r, tol, f"{where}[{i}]")
    elif isinstance(ref, list):
        assert isinstance(ours, list) and len(ours) == len(ref), where
        for i, (o, r) in enumerate(zip(ours, ref)):
            assert_matches(o, r, tol, f"{where}[{i}]")
    elif isinstance(ref, dict) and ("RandomState" in ref or "Generator" in ref):
        kind = np.random.RandomState if "RandomState" in ref else np.random.Generator
        assert isinstance(ours, kind), where
    elif isinstance(ref, bool) or ref is None:
        assert ours is ref, f"{where}: {ours!r} is not {ref!r}"
    elif isinstance(ref, float):
        assert type(ours) is float, f"{where}: {type(ours)} is not a Python float"
        assert math.isclose(ours, ref, rel_tol=tol, abs_tol=tol), f"{where}: {ours!r} != {ref!r}"
    else:
        assert type(ours) is type(ref) and ours == ref, f"{where}: {ours!r} != {ref!r}"


CASES = [
    pytest.param(name, case, id=f"{name}-{i}" + (f"-{case['note']}" if "note" in case else ""))
    for name, cases in DATA["cases"].items()
    for i, case in enumerate(cases)
]


@pytest.mark.parametrize(("name", "case"), CASES)
def test_matches_robosuite(name: str, case: dict) -> None:
    fn = getattr(T, name)
    args = decode(case["args"])
    kwargs = {k: (args[v["ref_arg"]] if isinstance(v, dict) and "ref_arg" in v else decode(v))
              for k, v in case["kwargs"].items()}
    tol = F32_TOL if (name in FLOAT32_FUNCTIONS or has_float32(case)) else F64_TOL
    if "np_random_seed" in case:
        np.random.seed(case["np_random_seed"])

    if "raises" in case:
        with pytest.raises(Exception) as excinfo:
            fn(*args, **kwargs)
        assert type(excinfo.value).__name__ == case["raises"]
        if name not in MESSAGE_DIFFERS:
            assert str(excinfo.value) == case["message"]
        return

    result = fn(*args, **kwargs)
    assert_matches(result, case["result"], tol)

    # Arguments change in place exactly where robosuite changes them.
    if "args_after" in case:
        assert_matches(args, case["args_after"], tol, "args after the call")
    else:
        assert_matches(args, case["args"], 0.0, "args after the call")
    if "kwargs_after" in case:
        for k, ref in case["kwargs_after"].items():
            assert_matches(kwargs[k], ref, tol, f"{k} after the call")


def test_constants() -> None:
    c = DATA["constants"]
    assert T.PI == c["PI"]
    assert T.EPS == c["EPS"]
    assert T._NEXT_AXIS == c["_NEXT_AXIS"]
    assert T._AXES2TUPLE == {k: tuple(v) for k, v in c["_AXES2TUPLE"].items()}
    assert list(T._AXES2TUPLE) == list(c["_AXES2TUPLE"])
    assert T._TUPLE2AXES == {tuple(k): v for k, v in c["_TUPLE2AXES"]}


def test_every_public_name_of_robosuite() -> None:
    missing = [n for n in DATA["public_names"] if not hasattr(T, n)]
    assert missing == []
    assert set(DATA["public_names"]) <= set(T.__all__)


def test_every_function_has_cases() -> None:
    functions = {n for n in DATA["public_names"] if callable(getattr(T, n))}
    assert functions <= set(DATA["cases"])


def test_quat2axisangle_round_trip() -> None:
    """axisangle2quat inverts quat2axisangle (angles in [0, pi))."""
    rng = np.random.default_rng(3)
    for _ in range(20):
        v = rng.normal(size=3)
        v *= rng.uniform(0.01, 3.0) / np.linalg.norm(v)
        np.testing.assert_allclose(T.quat2axisangle(T.axisangle2quat(v)), v, rtol=1e-12, atol=1e-12)


def test_quat_mat_round_trip() -> None:
    """mat2quat inverts quat2mat up to sign and float32 rounding; w >= 0."""
    rng = np.random.default_rng(4)
    for _ in range(20):
        q = rng.normal(size=4)
        q /= np.linalg.norm(q)
        back = T.mat2quat(T.quat2mat(q))
        assert back[3] >= 0.0
        np.testing.assert_allclose(back, q * np.sign(q[3]), atol=1e-6)
