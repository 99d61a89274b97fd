#!/usr/bin/env python3
"""Record robosuite 1.5.2's ``transform_utils`` and ``camera_utils`` as test fixtures.

Run it with a Python that has robosuite 1.5.2 and mujoco 3.3.7 (nothing is rendered, so no
OpenGL is needed), from the repository root:

    python3 -m venv .bench-venv/robosuite            # git-ignored; reuse it if it exists
    .bench-venv/robosuite/bin/pip install robosuite==1.5.2 mujoco==3.3.7
    .bench-venv/robosuite/bin/python scripts/record_utils.py

It writes two pretty-printed JSON files (indent 1, floats in ``repr`` precision) that
python/tests/test_transform_utils.py and python/tests/test_camera_utils.py replay against
``robosuite_rs.utils``:

* python/tests/fixtures/robosuite_utils/transform_utils.json: robosuite's constants and, per
  public function, fixed seeded calls (identity, 180-degree rotations, near-zero angles,
  negative w, non-unit and float32 inputs, batched inputs where robosuite takes them, bad
  input) with their arguments, results (or the exception raised) and any argument the call
  changed in place.
* python/tests/fixtures/robosuite_utils/camera_utils.json: from a Lift env (Panda, seed 0, no
  renderer, no camera observations) after ``reset()``, the simulator values the functions
  read (camera names and ids, ``cam_fovy``, ``cam_xpos``, ``cam_xmat``, ``stat.extent``,
  ``vis.map.znear`` / ``zfar``, and ``cam_pos`` / ``cam_quat`` / ``cam_bodyid`` for
  ``CameraMover``) and, per camera and image size, the intrinsic, extrinsic and transform
  matrices, projected pixels of world points, pixels back to world points, real depth maps;
  plus ``bilinear_interpolate`` calls, bad input and a ``CameraMover`` session.

Arrays are stored as ``{"array": nested lists, "dtype": ..., "shape": ...}``, NumPy scalars
as ``{"scalar": value, "dtype": ...}``, tuples as ``{"tuple": [...]}``,
``np.random.RandomState(s)`` as ``{"RandomState": s}``, ``np.random.default_rng(s)`` as
``{"Generator": s}`` and "the first positional argument itself" as ``{"ref_arg": 0}``.
A case with ``"np_random_seed": s`` calls ``np.random.seed(s)`` first.
"""

from __future__ import annotations

import copy
import inspect
import json
import math
import os
import platform
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT_DIR = os.path.join(ROOT, "python", "tests", "fixtures", "robosuite_utils")

CAMERAS = ["frontview", "birdview", "agentview", "sideview", "robot0_robotview", "robot0_eye_in_hand"]
SIZES = [(84, 84), (120, 160)]  # (height, width)


# ----------------------------------------------------------------------------- encoding


def enc(x):
    """JSON-able form of an argument or result (see the module docstring)."""
    if isinstance(x, np.ndarray):
        return {"array": x.tolist(), "dtype": str(x.dtype), "shape": list(x.shape)}
    if isinstance(x, np.generic):
        return {"scalar": x.item(), "dtype": str(x.dtype)}
    if isinstance(x, tuple):
        return {"tuple": [enc(v) for v in x]}
    if isinstance(x, list):
        return [enc(v) for v in x]
    if isinstance(x, dict):
        return {str(k): enc(v) for k, v in x.items()}
    if isinstance(x, np.random.RandomState):
        return {"RandomState": _SEEDS[id(x)]}
    if isinstance(x, np.random.Generator):
        return {"Generator": _SEEDS[id(x)]}
    if isinstance(x, Ref):
        return {"ref_arg": x.index}
    if x is None or isinstance(x, (bool, int, float, str)):
        return x
    raise TypeError(f"cannot encode {type(x)}")


class Ref:
    """Stands for positional argument ``index`` itself (``unit_vector(v, out=v)``)."""

    def __init__(self, index: int) -> None:
        self.index = index


_SEEDS: dict[int, int] = {}  # id(random state or generator) -> the seed it was made with


def seeded_random_state(seed: int) -> np.random.RandomState:
    state = np.random.RandomState(seed)
    _SEEDS[id(state)] = seed
    return state


def seeded_generator(seed: int) -> np.random.Generator:
    gen = np.random.default_rng(seed)
    _SEEDS[id(gen)] = seed
    return gen


def changed(before, after) -> bool:
    if isinstance(before, np.ndarray):
        return before.dtype != after.dtype or before.shape != after.shape or not np.array_equal(before, after)
    if isinstance(before, (list, tuple)):
        return len(before) != len(after) or any(changed(b, a) for b, a in zip(before, after))
    return False


# ----------------------------------------------------------------------------- recording


class Recorder:
    def __init__(self, module) -> None:
        self.module = module
        self.cases: dict[str, list] = {}

    def call(self, name: str, *args, np_random_seed: int | None = None, note: str | None = None, **kwargs):
        fn = getattr(self.module, name)
        case = {"args": enc(list(args)), "kwargs": {k: enc(v) for k, v in kwargs.items()}}
        if np_random_seed is not None:
            case["np_random_seed"] = np_random_seed
            np.random.seed(np_random_seed)
        if note:
            case["note"] = note
        call_args = list(args)
        call_kwargs = {k: (call_args[v.index] if isinstance(v, Ref) else v) for k, v in kwargs.items()}
        before_args = copy.deepcopy(call_args)
        before_kwargs = {k: copy.deepcopy(v) for k, v in call_kwargs.items()}
        try:
            result = fn(*call_args, **call_kwargs)
        except Exception as err:  # noqa: BLE001 - recording robosuite's exception
            case["raises"] = type(err).__name__
            case["message"] = str(err)
        else:
            case["result"] = enc(result)
        if any(changed(b, a) for b, a in zip(before_args, call_args)):
            case["args_after"] = enc(call_args)
        kw_changed = {k: enc(call_kwargs[k]) for k in call_kwargs if changed(before_kwargs[k], call_kwargs[k])}
        if kw_changed:
            case["kwargs_after"] = kw_changed
        self.cases.setdefault(name, []).append(case)
        return None if "raises" in case else result


def public_names(module) -> list[str]:
    """Names the module defines itself (functions, classes) or as module-level constants."""
    names = []
    for name, value in vars(module).items():
        if name.startswith("_") or inspect.ismodule(value):
            continue
        if inspect.isfunction(value) or inspect.isclass(value) or hasattr(value, "py_func"):
            if getattr(value, "__module__", None) == module.__name__:
                names.append(name)
        elif isinstance(value, (int, float)):
            names.append(name)
    return sorted(names)


def meta() -> dict:
    import mujoco
    import numba
    import robosuite
    import robosuite.macros as macros

    return {
        "robosuite": robosuite.__version__,
        "mujoco": mujoco.__version__,
        "numpy": np.__version__,
        "numba": numba.__version__,
        "robosuite_macros_ENABLE_NUMBA": macros.ENABLE_NUMBA,
        "python": platform.python_version(),
        "machine": platform.machine(),
        "recorded_by": "scripts/record_utils.py",
    }


# ----------------------------------------------------------------------------- transform_utils


def unit(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v)


def record_transform_utils() -> dict:
    import robosuite.utils.transform_utils as T

    rng = np.random.default_rng(20250152)
    r = Recorder(T)
    s2 = math.sqrt(0.5)

    # Quaternions (x, y, z, w).
    named_quats = {
        "identity": np.array([0.0, 0.0, 0.0, 1.0]),
        "negative identity": np.array([0.0, 0.0, 0.0, -1.0]),
        "180 about x": np.array([1.0, 0.0, 0.0, 0.0]),
        "180 about y": np.array([0.0, 1.0, 0.0, 0.0]),
        "180 about z": np.array([0.0, 0.0, 1.0, 0.0]),
        "180 about x+y": np.array([s2, s2, 0.0, 0.0]),
        "90 about z": np.array([0.0, 0.0, s2, s2]),
        "near-zero angle": np.array([5e-10, 0.0, 0.0, 1.0]),
        "1e-4 rad about y": np.array([0.0, math.sin(5e-5), 0.0, math.cos(5e-5)]),
        "negative w": unit([0.3, -0.2, 0.5, -0.7]),
        "non-unit": np.array([0.5, -1.0, 0.25, 2.0]),
    }
    random_quats = [unit(rng.normal(size=4)) for _ in range(6)]
    all_quats = list(named_quats.values()) + random_quats
    f32_quats = [q.astype(np.float32) for q in random_quats[:3]] + [named_quats["negative w"].astype(np.float32)]

    # Rotation matrices.
    rotations = [np.eye(3), np.diag([1.0, -1.0, -1.0]), np.diag([-1.0, 1.0, -1.0]), np.diag([-1.0, -1.0, 1.0])]
    rotations += [T.euler2mat(rng.uniform(-math.pi, math.pi, 3)) for _ in range(6)]
    rotations += [T.euler2mat([0.3, math.pi / 2, 0.2]), T.euler2mat([-0.4, -math.pi / 2, 1.1])]  # gimbal lock
    rotations += [T.euler2mat([0.0, 0.0, 1e-7])]  # near-identity

    def random_pose():
        return T.make_pose(rng.uniform(-1.0, 1.0, 3), T.euler2mat(rng.uniform(-math.pi, math.pi, 3)))

    poses = [np.eye(4)] + [random_pose() for _ in range(5)]

    # convert_quat
    for q in all_quats[:4] + random_quats[:2] + f32_quats[:1]:
        r.call("convert_quat", q)
        r.call("convert_quat", q, to="wxyz")
        r.call("convert_quat", q, to="xyzw")
    r.call("convert_quat", random_quats[0], to="abc", note="bad convention")

    # quat_multiply / quat_distance
    pairs = [(random_quats[i], random_quats[i + 1]) for i in range(5)]
    pairs += [
        (named_quats["identity"], random_quats[0]),
        (named_quats["180 about x"], named_quats["180 about y"]),
        (named_quats["negative w"], named_quats["non-unit"]),
    ]
    r.call("quat_multiply", [1, -2, 3, 4], [-5, 6, 7, 8], note="robosuite's docstring example, lists of ints")
    r.call("quat_multiply", [0.1, 0.2, 0.3, 0.9], (0.5, -0.5, 0.5, 0.5), note="list and tuple")
    for a, b in pairs:
        r.call("quat_multiply", a, b)
        r.call("quat_distance", a, b)
    for a, b in [(f32_quats[0], f32_quats[1]), (f32_quats[2], f32_quats[3]), (f32_quats[0], random_quats[3])]:
        r.call("quat_multiply", a, b)
        r.call("quat_distance", a, b)

    # quat_conjugate / quat_inverse
    for q in all_quats + f32_quats:
        r.call("quat_conjugate", q)
        r.call("quat_inverse", q)
    r.call("quat_inverse", [0.1, 0.2, 0.3, 0.4], note="list")
    r.call("quat_inverse", np.array([0, 0, 2, 0]), note="int array")

    # quat_slerp
    for a, b in pairs[:5] + [(f32_quats[0], f32_quats[1])]:
        for frac in (0.0, 1.0, 0.25, 0.5, 0.9):
            r.call("quat_slerp", a, b, frac)
    neg_pair = (random_quats[0], -random_quats[1] if np.dot(random_quats[0], random_quats[1]) > 0 else random_quats[1])
    r.call("quat_slerp", neg_pair[0], neg_pair[1], 0.3, note="dot < 0: shortest path negates")
    r.call("quat_slerp", neg_pair[0], neg_pair[1], 0.3, shortestpath=False, note="dot < 0, long way")
    r.call("quat_slerp", random_quats[2], random_quats[2], 0.4, note="same quaternion")
    r.call("quat_slerp", random_quats[2], -random_quats[2], 0.4, note="opposite quaternion")
    r.call("quat_slerp", named_quats["non-unit"], random_quats[3], 0.6, note="non-unit input")
    r.call("quat_slerp", [0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 0.0], 0.5, note="lists")

    # random_quat
    for rand in [np.array([0.0, 0.0, 0.0]), np.array([1.0, 0.5, 0.25]), rng.random(3), rng.random(3)]:
        r.call("random_quat", rand)
    r.call("random_quat", [0.3, 0.6, 0.9], note="list")
    r.call("random_quat", rng.random(3).astype(np.float32), note="float32 input")
    r.call("random_quat", np_random_seed=7, note="global np.random")
    r.call("random_quat", None, np_random_seed=8, note="global np.random")
    r.call("random_quat", np.array([0.1, 0.2]), note="wrong length")

    # random_axis_angle
    r.call("random_axis_angle", np_random_seed=3, note="global np.random")
    r.call("random_axis_angle", 0.5, np_random_seed=4, note="global np.random")
    r.call("random_axis_angle", random_state=seeded_random_state(11))
    r.call("random_axis_angle", angle_limit=0.25, random_state=seeded_random_state(12))
    r.call("random_axis_angle", None, seeded_random_state(13))
    r.call("random_axis_angle", random_state=seeded_generator(5), note="not a RandomState")

    # vec / mat4
    r.call("vec", [1.0, 2.5, -3.25])
    r.call("vec", (0.1, 0.2, 0.3, 0.4))
    r.call("vec", rng.normal(size=5))
    r.call("vec", np.array([1, 2, 3]))
    r.call("mat4", list(range(16)))
    r.call("mat4", poses[1])
    r.call("mat4", rng.normal(size=16))

    # mat2pose / pose2mat / make_pose
    for p in poses:
        r.call("mat2pose", p)
    r.call("mat2pose", poses[2].astype(np.float32))
    for q in random_quats[:3] + [named_quats["identity"], named_quats["non-unit"], named_quats["negative w"]]:
        r.call("pose2mat", (rng.uniform(-1, 1, 3), q))
    r.call("pose2mat", ([0.1, 0.2, 0.3], named_quats["180 about z"]), note="list position")
    r.call("pose2mat", (np.zeros(3), f32_quats[0]))
    for _ in range(3):
        r.call("make_pose", rng.uniform(-1, 1, 3), T.euler2mat(rng.uniform(-3, 3, 3)))
    r.call("make_pose", [0.0, 1.0, 2.0], np.eye(3))
    r.call("make_pose", np.float32([0.5, 0.25, 0.125]), np.eye(3, dtype=np.float32))

    # mat2quat
    for m in rotations:
        r.call("mat2quat", m)
    r.call("mat2quat", poses[3], note="4x4 pose: top-left 3x3")
    r.call("mat2quat", rotations[5].astype(np.float32))

    # euler2mat
    for e in [np.zeros(3), np.array([math.pi, 0.0, 0.0]), np.array([0.0, math.pi / 2, 0.0])]:
        r.call("euler2mat", e)
    for _ in range(4):
        r.call("euler2mat", rng.uniform(-math.pi, math.pi, 3))
    r.call("euler2mat", [0.1, -0.2, 0.3], note="list")
    r.call("euler2mat", rng.uniform(-3, 3, (5, 3)), note="batched (5, 3)")
    r.call("euler2mat", rng.uniform(-3, 3, (2, 2, 3)), note="batched (2, 2, 3)")
    r.call("euler2mat", rng.uniform(-3, 3, 3).astype(np.float32), note="float32 input")
    r.call("euler2mat", np.array([0.1, 0.2]), note="wrong shape")

    # mat2euler
    for m in rotations:
        r.call("mat2euler", m)
    for axes in T._AXES2TUPLE:
        r.call("mat2euler", rotations[4], axes)
    for axes in ["rzyz", "sxyx", "szxz", "rxyz"]:
        r.call("mat2euler", np.eye(3), axes=axes, note="identity, repeated/rotating axes")
        r.call("mat2euler", rotations[10], axes=axes, note="gimbal lock")
    r.call("mat2euler", rotations[6], axes=(2, 1, 1, 1), note="tuple axes")
    r.call("mat2euler", rotations[7], axes="SXYZ", note="upper case")
    r.call("mat2euler", poses[4], note="4x4 pose")

    # quat2mat
    for q in all_quats + f32_quats:
        r.call("quat2mat", q)
    r.call("quat2mat", np.zeros(4), note="zero quaternion: identity")
    r.call("quat2mat", np.array([1e-9, 0.0, 0.0, 1e-9]), note="norm^2 < EPS: identity")

    # quat2axisangle (modifies w in place when |w| > 1)
    for q in all_quats + f32_quats:
        r.call("quat2axisangle", q.copy())
    r.call("quat2axisangle", np.array([0.0, 0.0, 0.0, 1.0 + 1e-9]), note="w > 1 clipped in place")
    r.call("quat2axisangle", np.array([1e-5, 0.0, 0.0, 1.0 + 1e-7]), note="w > 1 clipped in place")
    r.call("quat2axisangle", np.array([0.0, 1e-5, 0.0, -1.0 - 1e-7]), note="w < -1 clipped in place")
    r.call("quat2axisangle", np.array([0.0, 0.0, 1e-9, 1.0 - 1e-17]), note="w rounds to 1")
    r.call("quat2axisangle", np.array([0.0, 0.0, 3e-8, 1.0 - 4.5e-16]), note="tiny angle, den > 0")
    r.call("quat2axisangle", np.array([0, 0, 0, 1]), note="int array")

    # axisangle2quat
    for v in [
        np.zeros(3),
        np.array([1e-9, 0.0, 0.0]),
        np.array([1e-300, 0.0, 0.0]),
        np.array([math.pi, 0.0, 0.0]),
        np.array([0.0, -math.pi, 0.0]),
        np.array([0.0, 0.0, 2 * math.pi]),
        np.array([3.0, 4.0, 12.0]),
    ] + [rng.normal(size=3) for _ in range(4)]:
        r.call("axisangle2quat", v)
    r.call("axisangle2quat", [0.1, 0.2, -0.3], note="list")
    r.call("axisangle2quat", rng.normal(size=3).astype(np.float32), note="float32 input")
    r.call("axisangle2quat", np.array([0, 0, 2]), note="int array")

    # poses between frames
    for i in range(4):
        r.call("pose_in_A_to_pose_in_B", poses[i + 1], poses[i])
        r.call("pose_inv", poses[i + 1])
        r.call("vel_in_A_to_vel_in_B", rng.normal(size=3), rng.normal(size=3), poses[i + 1])
        r.call("force_in_A_to_force_in_B", rng.normal(size=3), rng.normal(size=3), poses[i + 1])
        r.call("_skew_symmetric_translation", rng.normal(size=3))
    r.call("pose_inv", np.eye(4))
    r.call("pose_inv", poses[2].astype(np.float32), note="float32 pose")
    r.call("vel_in_A_to_vel_in_B", [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], poses[3], note="lists")

    # rotation_matrix
    for angle, direction, point in [
        (0.0, [0.0, 0.0, 1.0], None),
        (math.pi, [1.0, 0.0, 0.0], None),
        (2 * math.pi, [0.3, -0.2, 0.9], None),
        (math.pi / 2, [0.0, 0.0, 2.0], [1.0, 0.0, 0.0]),
        (-0.7, np.array([1.0, 2.0, 3.0]), np.array([0.5, -0.5, 0.25])),
        (1e-8, [0.0, 1.0, 0.0], None),
        (2.5, rng.normal(size=3), rng.normal(size=3)),
        (-3.0, rng.normal(size=4), rng.normal(size=4)),
    ]:
        r.call("rotation_matrix", angle, direction, point)
    r.call("rotation_matrix", 0.4, (1, 1, 0))

    # clip_translation
    r.call("clip_translation", np.array([0.1, 0.2, 0.3]), 1.0)
    r.call("clip_translation", np.array([1.0, 2.0, 2.0]), 1.5)
    r.call("clip_translation", np.array([3.0, 4.0]), 5.0, note="norm == limit")
    r.call("clip_translation", np.zeros(3), 0.1)
    r.call("clip_translation", rng.normal(size=6), 0.2)
    r.call("clip_translation", np.array([0.3, -0.4, 1.2], dtype=np.float32), 0.5, note="float32")
    r.call("clip_translation", [0.01, 0.02, 0.0], 0.5, note="list within limit")

    # clip_rotation
    for q, lim in [
        (named_quats["identity"], 0.1),
        (named_quats["negative identity"], 0.1),
        (named_quats["90 about z"], 0.5),
        (named_quats["90 about z"], 2.0),
        (named_quats["180 about x"], 1.0),
        (named_quats["negative w"], 1.0),
        (named_quats["non-unit"], 0.2),
        (named_quats["1e-4 rad about y"], 0.01),
        (random_quats[4], 0.3),
        (random_quats[5], 3.0),
        (f32_quats[0], 0.2),
        (f32_quats[1], 6.0),
    ]:
        r.call("clip_rotation", q, lim)
    r.call("clip_rotation", [0.0, 0.0, 0.5, 0.5], 0.1, note="list")

    # unit_vector
    r.call("unit_vector", [3.0, 4.0])
    r.call("unit_vector", [1.0])
    r.call("unit_vector", [], note="empty")
    r.call("unit_vector", rng.normal(size=7))
    r.call("unit_vector", rng.normal(size=4).astype(np.float32))
    m54 = rng.random((5, 4, 3))
    r.call("unit_vector", m54, axis=-1)
    r.call("unit_vector", m54, axis=1)
    r.call("unit_vector", m54[0], axis=0)
    r.call("unit_vector", m54[1], note="2-D, axis=None: whole array")
    r.call("unit_vector", m54, axis=1, out=np.empty((5, 4, 3), dtype=np.float32), note="out float32")
    r.call("unit_vector", m54[2], axis=1, out=np.empty((4, 3)), note="out float64")
    r.call("unit_vector", rng.random(5), out=np.empty(5), note="1-D with out")
    r.call("unit_vector", rng.random((3, 3)), axis=0, out=Ref(0), note="out is data (in place)")

    # orientation / pose errors
    for i in range(4):
        r.call("get_orientation_error", random_quats[i], random_quats[i + 1])
        r.call("get_pose_error", poses[i + 1], poses[i])
    r.call("get_orientation_error", named_quats["identity"], named_quats["identity"])
    r.call("get_orientation_error", [0.0, 0.0, s2, s2], [0.0, 0.0, 0.0, 1.0], note="lists")
    r.call("get_orientation_error", f32_quats[0], f32_quats[1], note="float32")
    r.call("get_pose_error", poses[0], poses[0])

    # matrix_inverse
    for n in (3, 4, 6):
        a = rng.normal(size=(n, n)) + n * np.eye(n)
        r.call("matrix_inverse", a)
    r.call("matrix_inverse", poses[2])
    r.call("matrix_inverse", np.array([[1.0, 2.0], [2.0, 4.0]]), note="singular")

    # rotate_2d_point
    for p, rot in [
        (np.array([1.0, 0.0]), math.pi / 2),
        (np.array([0.3, -0.7]), -1.2),
        ([2.0, 1.0], 0.0),
        (np.array([0.5, 0.5], dtype=np.float32), 0.3),
        (np.array([1.0, 2.0]), np.float32(0.7)),
        (rng.normal(size=2), rng.uniform(-4, 4)),
    ]:
        r.call("rotate_2d_point", p, rot)

    return {
        "meta": meta(),
        "public_names": public_names(T),
        "constants": {
            "PI": T.PI,
            "EPS": T.EPS,
            "_NEXT_AXIS": T._NEXT_AXIS,
            "_AXES2TUPLE": {k: list(v) for k, v in T._AXES2TUPLE.items()},
            "_TUPLE2AXES": [[list(k), v] for k, v in T._TUPLE2AXES.items()],
        },
        "cases": r.cases,
    }


# ----------------------------------------------------------------------------- camera_utils


def record_camera_utils() -> dict:
    import robosuite as suite
    import robosuite.utils.camera_utils as CU

    np.random.seed(0)
    env = suite.make(
        "Lift",
        robots="Panda",
        has_renderer=False,
        has_offscreen_renderer=False,
        use_camera_obs=False,
        seed=0,
    )
    env.reset()
    sim = env.sim
    model, data = sim.model, sim.data
    ncam = model.ncam

    znear, zfar = model.vis.map.znear, model.vis.map.zfar
    sim_record = {
        "camera_names": list(model.camera_names),
        "camera_ids": {name: model.camera_name2id(name) for name in model.camera_names},
        "cam_fovy": enc(np.array(model.cam_fovy)),
        "cam_xpos": enc(np.array(data.cam_xpos)),
        "cam_xmat": enc(np.array(data.cam_xmat)),
        "cam_pos": enc(np.array(model.cam_pos)),
        "cam_quat": enc(np.array(model.cam_quat)),
        "cam_bodyid": enc(np.array(model.cam_bodyid)),
        "stat_extent": enc(model.stat.extent),
        "vis_map_znear": enc(znear),
        "vis_map_zfar": enc(zfar),
        "ncam": ncam,
    }

    rng = np.random.default_rng(7)
    cube_pos = np.array(data.body_xpos[model.body_name2id("cube_main")])
    world_points = np.array([cube_pos, [0.0, 0.0, 0.8], [0.1, -0.2, 0.85], [-0.3, 0.25, 1.0], [0.5, 0.0, 1.2]])

    per_camera = []
    for name in CAMERAS:
        for height, width in SIZES:
            entry = {"camera_name": name, "camera_id": model.camera_name2id(name), "height": height, "width": width}
            entry["intrinsic"] = enc(CU.get_camera_intrinsic_matrix(sim, name, height, width))
            entry["extrinsic"] = enc(CU.get_camera_extrinsic_matrix(sim, name))
            transform = CU.get_camera_transform_matrix(sim, name, height, width)
            entry["transform"] = enc(transform)

            batch = rng.uniform([-0.4, -0.4, 0.8], [0.4, 0.4, 1.2], size=(2, 3, 3))
            entry["project"] = []
            for pts in (world_points, world_points[0], batch):
                pixels = CU.project_points_from_world_to_camera(pts, transform, height, width)
                entry["project"].append({"points": enc(pts), "pixels": enc(pixels)})

            camera_to_world = np.linalg.inv(transform)
            entry["camera_to_world"] = enc(camera_to_world)
            depth_small = rng.uniform(0.5, 2.0, size=(6, 8, 1))
            depth_batch = rng.uniform(0.5, 2.0, size=(3, 6, 8, 1))
            entry["unproject"] = []
            for pix, depth in (
                (np.array([2, 5]), depth_small),
                (np.array([2.25, 4.5]), depth_small),
                (np.array([4.5, 6.75]), depth_small[..., 0]),  # (H, W): robosuite reads it as intended
                (np.array([[1, 2], [3.5, 4.25], [5, 7]]), depth_batch),  # robosuite raises ValueError
            ):
                case = {"pixels": enc(pix), "depth_map": enc(depth)}
                try:
                    case["points"] = enc(CU.transform_from_pixels_to_world(pix, depth, camera_to_world))
                except ValueError as err:
                    case["raises"] = type(err).__name__
                    case["message"] = str(err)
                entry["unproject"].append(case)
            per_camera.append(entry)

    depth_cases = []
    for depth in (
        np.array([[0.0, 0.25, 0.5], [0.75, 0.99, 1.0]], dtype=np.float32)[..., None],
        rng.uniform(0.9, 0.999, size=(4, 5, 1)).astype(np.float32),
        rng.uniform(0.0, 1.0, size=(3, 4)),
    ):
        depth_cases.append({"depth_map": enc(depth), "real": enc(CU.get_real_depth_map(sim, depth))})

    errors = {}

    def record_error(key, fn, *args):
        try:
            fn(*args)
        except Exception as err:  # noqa: BLE001
            errors[key] = {"raises": type(err).__name__, "message": str(err)}
        else:
            raise RuntimeError(f"{key}: robosuite did not raise")

    record_error("intrinsic_unknown_camera", CU.get_camera_intrinsic_matrix, sim, "no_such_camera", 84, 84)
    record_error("extrinsic_unknown_camera", CU.get_camera_extrinsic_matrix, sim, "no_such_camera")
    record_error("depth_above_one", CU.get_real_depth_map, sim, np.array([0.5, 1.5]))
    record_error("depth_below_zero", CU.get_real_depth_map, sim, np.array([[-0.1, 0.5]]))
    t = CU.get_camera_transform_matrix(sim, "agentview", 84, 84)
    record_error("project_points_not_3d", CU.project_points_from_world_to_camera, np.zeros((4, 2)), t, 84, 84)
    record_error("project_transform_not_4x4", CU.project_points_from_world_to_camera, np.zeros((4, 3)), t[:3], 84, 84)
    record_error(
        "project_transform_not_2d", CU.project_points_from_world_to_camera, np.zeros((4, 3)), t[None], 84, 84
    )
    record_error(
        "unproject_leading_shape_mismatch",
        CU.transform_from_pixels_to_world,
        np.zeros((2, 2)),
        np.ones((3, 6, 8, 1)),
        np.linalg.inv(t),
    )

    # robosuite's camera_name2id maps "free" to -1, so these read the last camera's values.
    free = {
        "intrinsic": enc(CU.get_camera_intrinsic_matrix(sim, "free", 84, 84)),
        "extrinsic": enc(CU.get_camera_extrinsic_matrix(sim, "free")),
    }

    bilinear = []
    im = rng.uniform(0.0, 1.0, size=(5, 6))
    im3 = rng.uniform(0.0, 1.0, size=(5, 6, 1))
    for image, x, y in (
        (im, np.array([0.0, 1.5, 5.0, 2.25]), np.array([0.0, 2.5, 4.0, 3.75])),
        (im, np.array([-1.0, 7.5]), np.array([6.0, -0.5])),
        (im3, np.array([[0.5], [4.75]]), np.array([[1.25], [3.0]])),
        (im, 2.5, 1.5),
    ):
        out = CU.bilinear_interpolate(image, x, y)
        bilinear.append({"im": enc(image), "x": enc(x), "y": enc(y), "result": enc(out)})

    mover = record_camera_mover(suite, CU)

    return {
        "meta": meta(),
        "public_names": public_names(CU),
        "sim": sim_record,
        "cameras": per_camera,
        "real_depth": depth_cases,
        "errors": errors,
        "free_camera": free,
        "bilinear_interpolate": bilinear,
        "camera_mover": mover,
    }


def record_camera_mover(suite, CU) -> dict:
    """A CameraMover session per camera: the camera's model pose before, then after each
    call its return value, get_camera_pose() and the camera's world pose in MuJoCo."""

    def make_env():
        np.random.seed(1)
        e = suite.make(
            "Lift", robots="Panda", has_renderer=False, has_offscreen_renderer=False, use_camera_obs=False, seed=1
        )
        e.reset()
        return e

    sessions = []
    plans = {
        "frontview": (
            {},
            [
                ("set_camera_pose", {"pos": [1.5, 0.1, 1.4]}),
                ("set_camera_pose", {"quat": np.array([0.4, 0.5, 0.5, 0.58])}),
                ("rotate_camera", {"point": None, "axis": [0.0, 1.0, 0.0], "angle": 10.0}),
                ("rotate_camera", {"point": [0.0, 0.0, 0.5], "axis": [1.0, 0.0, 0.0], "angle": -25.0}),
                ("move_camera", {"direction": [0.0, 0.0, 1.0], "scale": 0.1}),
                ("move_camera", {"direction": [1.0, -1.0, 0.0], "scale": -0.05}),
                ("set_camera_pose", {"pos": [1.0, 0.0, 1.5], "quat": np.array([0.5, 0.5, 0.5, 0.5])}),
                ("set_camera_pose", {}),
            ],
        ),
        "agentview": (
            {"init_camera_pos": [0.6, 0.2, 1.6], "init_camera_quat": np.array([0.3, 0.6, 0.6, 0.4])},
            [
                ("rotate_camera", {"point": [0.1, 0.0, 0.0], "axis": [0.0, 0.0, 1.0], "angle": 45.0}),
                ("move_camera", {"direction": [0.0, 1.0, 0.0], "scale": 0.3}),
            ],
        ),
    }
    for camera, (init_kwargs, steps) in plans.items():
        env = make_env()
        cam_id = env.sim.model.camera_name2id(camera)
        session = {
            "camera": camera,
            "init_kwargs": enc(init_kwargs),
            "model_cam_pos": enc(np.array(env.sim.model.cam_pos[cam_id])),
            "model_cam_quat": enc(np.array(env.sim.model.cam_quat[cam_id])),
        }
        mover = CU.CameraMover(env, camera=camera, **init_kwargs)
        session["mover_body_name"] = mover.mover_body_name
        # robosuite rebuilt the env from its XML (numbers printed to 6 digits): the mocap
        # body's pose in that model is where the camera starts before init_camera_pos/quat.
        body_id = mover.env.sim.model.body_name2id(mover.mover_body_name)
        session["reloaded_mocap_pos"] = enc(np.array(mover.env.sim.model.body_pos[body_id]))
        session["reloaded_mocap_quat"] = enc(np.array(mover.env.sim.model.body_quat[body_id]))

        def snapshot():
            sim = mover.env.sim
            cid = sim.model.camera_name2id(camera)
            pos, quat = mover.get_camera_pose()
            return {
                "pose": enc((np.array(pos), np.array(quat))),
                "cam_xpos": enc(np.array(sim.data.cam_xpos[cid])),
                "cam_xmat": enc(np.array(sim.data.cam_xmat[cid])),
            }

        session["after_init"] = snapshot()
        session["steps"] = []
        for method, kwargs in steps:
            result = getattr(mover, method)(**kwargs)
            if isinstance(result, tuple):
                result = tuple(np.array(v) for v in result)
            session["steps"].append({"method": method, "kwargs": enc(kwargs), "result": enc(result), **snapshot()})
        sessions.append(session)
        env.close()

    errors = {}
    for camera in ("robot0_eye_in_hand", "no_such_camera"):
        env = make_env()
        try:
            CU.CameraMover(env, camera=camera)
        except Exception as err:  # noqa: BLE001
            errors[camera] = {"raises": type(err).__name__, "message": str(err)}
        else:
            raise RuntimeError(f"CameraMover({camera!r}) did not raise")
        env.close()
    return {"sessions": sessions, "errors": errors}


# ----------------------------------------------------------------------------- main


def write(name: str, payload: dict) -> str:
    os.makedirs(OUT_DIR, exist_ok=True)
    path = os.path.join(OUT_DIR, name)
    with open(path, "w") as f:
        json.dump(payload, f, indent=1, allow_nan=False)
        f.write("\n")
    return path


def main() -> int:
    import robosuite

    if robosuite.__version__ != "1.5.2":
        print(f"expected robosuite 1.5.2, found {robosuite.__version__}", file=sys.stderr)
        return 1
    for name, payload in (
        ("transform_utils.json", record_transform_utils()),
        ("camera_utils.json", record_camera_utils()),
    ):
        path = write(name, payload)
        print(f"wrote {os.path.relpath(path, ROOT)} ({os.path.getsize(path)} bytes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
