"""Rotations, quaternions and homogeneous poses: robosuite 1.5.2's ``transform_utils`` in NumPy.

Every public name of ``robosuite.utils.transform_utils`` is here with the same signature,
defaults, return shapes and dtypes, and the same numbers.

Conventions:

* Quaternions are (x, y, z, w) unless a function says otherwise (``convert_quat`` converts
  to and from MuJoCo's (w, x, y, z)).
* Rotation matrices are 3x3, poses are 4x4 homogeneous matrices ``[[R, p], [0, 1]]``.
* Axis-angle vectors are the rotation axis scaled by the angle in radians.

robosuite compiles ``mat2quat``, ``quat2mat`` and ``matrix_inverse`` with numba and always
runs on NumPy 1.x (its dependency ``mink`` pins ``numpy<2``). Several functions compute in
float32 (``quat_multiply``, ``mat2quat``, ``mat2euler``, ``unit_vector``, ...). The code
below spells out the precision of each step (which values are rounded to float32, which are
computed in float64), so the results match robosuite's whichever NumPy version runs it.
Where robosuite's float32 result depends on the BLAS or LAPACK build (float32 dot products,
``mat2quat``'s eigen-solver), ours agrees to float32 rounding: dot products of float32
vectors here round each product to float32 and add them in float64, as the BLAS kernels
numba calls do.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "PI",
    "EPS",
    "convert_quat",
    "quat_multiply",
    "quat_conjugate",
    "quat_inverse",
    "quat_distance",
    "quat_slerp",
    "random_quat",
    "random_axis_angle",
    "vec",
    "mat4",
    "mat2pose",
    "mat2quat",
    "euler2mat",
    "mat2euler",
    "pose2mat",
    "quat2mat",
    "quat2axisangle",
    "axisangle2quat",
    "pose_in_A_to_pose_in_B",
    "pose_inv",
    "vel_in_A_to_vel_in_B",
    "force_in_A_to_force_in_B",
    "rotation_matrix",
    "clip_translation",
    "clip_rotation",
    "make_pose",
    "unit_vector",
    "get_orientation_error",
    "get_pose_error",
    "matrix_inverse",
    "rotate_2d_point",
]

PI = np.pi
EPS = np.finfo(float).eps * 4.0

# The axis that follows axis i (i + 1 modulo 3, with one extra entry for parity offsets).
_NEXT_AXIS = [1, 2, 0, 1]

# Euler axis sequences: name -> (first axis, parity, repetition, frame).
# "s" = static (extrinsic) frame, "r" = rotating (intrinsic) frame.
_AXES2TUPLE = {
    "sxyz": (0, 0, 0, 0),
    "sxyx": (0, 0, 1, 0),
    "sxzy": (0, 1, 0, 0),
    "sxzx": (0, 1, 1, 0),
    "syzx": (1, 0, 0, 0),
    "syzy": (1, 0, 1, 0),
    "syxz": (1, 1, 0, 0),
    "syxy": (1, 1, 1, 0),
    "szxy": (2, 0, 0, 0),
    "szxz": (2, 0, 1, 0),
    "szyx": (2, 1, 0, 0),
    "szyz": (2, 1, 1, 0),
    "rzyx": (0, 0, 0, 1),
    "rxyx": (0, 0, 1, 1),
    "ryzx": (0, 1, 0, 1),
    "rxzx": (0, 1, 1, 1),
    "rxzy": (1, 0, 0, 1),
    "ryzy": (1, 0, 1, 1),
    "rzxy": (1, 1, 0, 1),
    "ryxy": (1, 1, 1, 1),
    "ryxz": (2, 0, 0, 1),
    "rzxz": (2, 0, 1, 1),
    "rxyz": (2, 1, 0, 1),
    "rzyz": (2, 1, 1, 1),
}

_TUPLE2AXES = {code: name for name, code in _AXES2TUPLE.items()}

_F32 = np.float32
_F64 = np.float64


def _dot32(a: np.ndarray, b: np.ndarray) -> np.float32:
    """Dot product of two float32 vectors: products rounded to float32, summed in float64,
    rounded to float32 (what the float32 BLAS dot behind robosuite's numba code does)."""
    prods = (np.asarray(a, dtype=_F32).ravel() * np.asarray(b, dtype=_F32).ravel()).astype(_F64)
    return _F32(math.fsum(prods.tolist()))


def convert_quat(q: ArrayLike, to: str = "xyzw") -> np.ndarray:
    """Reorder a quaternion: ``to="xyzw"`` reads (w, x, y, z) and returns (x, y, z, w);
    ``to="wxyz"`` does the reverse. The first axis is reordered; dtype is kept.

    Raises:
        Exception: ``to`` is neither "xyzw" nor "wxyz".
    """
    if to == "xyzw":
        return np.asarray(q)[[1, 2, 3, 0]]
    if to == "wxyz":
        return np.asarray(q)[[3, 0, 1, 2]]
    raise Exception("convert_quat: choose a valid `to` argument (xyzw or wxyz)")


def quat_multiply(quaternion1: ArrayLike, quaternion0: ArrayLike) -> np.ndarray:
    """Hamilton product ``quaternion1 * quaternion0`` of two (x, y, z, w) quaternions.

    Returns a float32 (x, y, z, w) array, e.g. ``quat_multiply([1, -2, 3, 4], [-5, 6, 7, 8])``
    is ``[-44, -14, 48, 28]``. The arithmetic is float32 when both inputs are float32 arrays,
    float64 otherwise.
    """
    a1 = np.asarray(quaternion1)
    a0 = np.asarray(quaternion0)
    dt = _F32 if (a1.dtype == _F32 and a0.dtype == _F32) else _F64
    x1, y1, z1, w1 = a1.astype(dt)[:4]
    x0, y0, z0, w0 = a0.astype(dt)[:4]
    return np.array(
        (
            x1 * w0 + y1 * z0 - z1 * y0 + w1 * x0,
            -x1 * z0 + y1 * w0 + z1 * x0 + w1 * y0,
            x1 * y0 - y1 * x0 + z1 * w0 + w1 * z0,
            -x1 * x0 - y1 * y0 - z1 * z0 + w1 * w0,
        ),
        dtype=_F32,
    )


def quat_conjugate(quaternion: ArrayLike) -> np.ndarray:
    """Conjugate (-x, -y, -z, w) of an (x, y, z, w) quaternion, as float32."""
    q = np.asarray(quaternion)
    return np.array((-q[0], -q[1], -q[2], q[3]), dtype=_F32)


def quat_inverse(quaternion: ArrayLike) -> np.ndarray:
    """Inverse ``conjugate / |q|^2`` of an (x, y, z, w) quaternion, as float32."""
    q = np.asarray(quaternion)
    norm2 = _dot32(q, q) if q.dtype == _F32 else np.dot(q.astype(_F64), q.astype(_F64))
    return quat_conjugate(q) / _F32(norm2)


def quat_distance(quaternion1: ArrayLike, quaternion0: ArrayLike) -> np.ndarray:
    """The (x, y, z, w) quaternion ``d`` with ``d * quaternion0 = quaternion1``, as float32."""
    return quat_multiply(quaternion1, quat_inverse(quaternion0))


def quat_slerp(quat0: ArrayLike, quat1: ArrayLike, fraction: float, shortestpath: bool = True) -> np.ndarray:
    """Spherical linear interpolation between two (x, y, z, w) quaternions.

    Returns the float32 unit quaternion at ``fraction`` (0 gives ``quat0``, 1 gives
    ``quat1``, both normalized). With ``shortestpath`` the endpoint is negated when needed to
    take the shorter arc. Nearly equal or opposite endpoints return normalized ``quat0``.
    """
    q0 = unit_vector(quat0[:4])
    q1 = unit_vector(quat1[:4])
    if fraction == 0.0:
        return q0
    if fraction == 1.0:
        return q1
    d = float(_dot32(q0, q1))
    if abs(abs(d) - 1.0) < EPS:
        return q0
    if shortestpath and d < 0.0:
        d = -d
        q1 *= -1.0
    angle = math.acos(min(max(d, -1.0), 1.0))
    if abs(angle) < EPS:
        return q0
    fraction = float(fraction)
    inv_sin = 1.0 / math.sin(angle)
    q0 *= math.sin((1.0 - fraction) * angle) * inv_sin
    q1 *= math.sin(fraction * angle) * inv_sin
    q0 += q1
    return q0


def random_quat(rand: ArrayLike | None = None) -> np.ndarray:
    """Uniformly random unit (x, y, z, w) quaternion, as float32.

    ``rand``: three independent samples of U[0, 1); by default ``np.random.rand(3)`` (the
    global NumPy generator).
    """
    if rand is None:
        rand = np.random.rand(3)
    else:
        assert len(rand) == 3
    u0, u1, u2 = (float(u) for u in rand)
    r1 = np.sqrt(1.0 - u0)
    r2 = np.sqrt(u0)
    t1 = 2.0 * math.pi * u1
    t2 = 2.0 * math.pi * u2
    return np.array((np.sin(t1) * r1, np.cos(t1) * r1, np.sin(t2) * r2, np.cos(t2) * r2), dtype=_F32)


def random_axis_angle(
    angle_limit: float | None = None, random_state: np.random.RandomState | None = None
) -> tuple[np.ndarray, float]:
    """Random rotation as ``(unit axis (3,), angle)``.

    The axis is a normalized 3-D standard normal sample, the angle is uniform in
    ``[0, angle_limit)`` (default 2*pi). Draws from ``random_state`` (a
    ``np.random.RandomState``) or else from the global NumPy generator.

    Raises:
        AssertionError: ``random_state`` is not a ``np.random.RandomState``.
    """
    if angle_limit is None:
        angle_limit = 2.0 * np.pi
    if random_state is not None:
        assert isinstance(random_state, np.random.RandomState)
        rng = random_state
    else:
        rng = np.random
    axis = rng.randn(3)
    axis /= np.linalg.norm(axis)
    angle = rng.uniform(low=0.0, high=angle_limit)
    return axis, angle


def vec(values: ArrayLike) -> np.ndarray:
    """``values`` as a float32 array."""
    return np.array(values, dtype=_F32)


def mat4(array: ArrayLike) -> np.ndarray:
    """``array`` (16 numbers) as a float32 4x4 matrix."""
    return np.array(array, dtype=_F32).reshape((4, 4))


def mat2pose(hmat: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Split a 4x4 pose into ``(position (3,), float32 (x, y, z, w) quaternion)``.

    The position is a view of ``hmat[:3, 3]``.
    """
    hmat = np.asarray(hmat)
    return hmat[:3, 3], mat2quat(hmat[:3, :3])


def mat2quat(rmat: ArrayLike) -> np.ndarray:
    """Rotation matrix (the top-left 3x3 of ``rmat``) to a float32 (x, y, z, w) quaternion
    with w >= 0.

    The quaternion is the eigenvector of the largest eigenvalue of the symmetric 4x4 matrix
    built from the rotation (computed in float32, as robosuite does).
    """
    m = np.asarray(rmat).astype(_F32)[:3, :3]
    (m00, m01, m02), (m10, m11, m12), (m20, m21, m22) = m
    zero = _F32(0.0)
    k = np.array(
        [
            [m00 - m11 - m22, zero, zero, zero],
            [m01 + m10, m11 - m00 - m22, zero, zero],
            [m02 + m20, m12 + m21, m22 - m00 - m11, zero],
            [m21 - m12, m02 - m20, m10 - m01, m00 + m11 + m22],
        ],
        dtype=_F32,
    )
    k /= _F32(3.0)
    # eigh reads the lower triangle, the only one filled in.
    eigenvalues, eigenvectors = np.linalg.eigh(k)
    wxyz = eigenvectors[[3, 0, 1, 2], np.argmax(eigenvalues)]
    if wxyz[0] < 0.0:
        np.negative(wxyz, wxyz)
    return wxyz[[1, 2, 3, 0]]


def euler2mat(euler: ArrayLike) -> np.ndarray:
    """(roll, pitch, yaw) angles in radians (static x, y, z axes) to a float64 rotation
    matrix; batched: shape ``(..., 3)`` gives ``(..., 3, 3)``.

    Raises:
        AssertionError: the last dimension is not 3.
    """
    euler = np.asarray(euler, dtype=_F64)
    assert euler.shape[-1] == 3, "Invalid shaped euler {}".format(euler)

    ai, aj, ak = -euler[..., 2], -euler[..., 1], -euler[..., 0]
    si, sj, sk = np.sin(ai), np.sin(aj), np.sin(ak)
    ci, cj, ck = np.cos(ai), np.cos(aj), np.cos(ak)
    cc, cs = ci * ck, ci * sk
    sc, ss = si * ck, si * sk

    mat = np.empty(euler.shape[:-1] + (3, 3), dtype=_F64)
    mat[..., 0, 0] = cj * ci
    mat[..., 0, 1] = cj * si
    mat[..., 0, 2] = -sj
    mat[..., 1, 0] = sj * cs - sc
    mat[..., 1, 1] = sj * ss + cc
    mat[..., 1, 2] = cj * sk
    mat[..., 2, 0] = sj * cc + ss
    mat[..., 2, 1] = sj * sc - cs
    mat[..., 2, 2] = cj * ck
    return mat


def mat2euler(rmat: ArrayLike, axes: str | tuple[int, int, int, int] = "sxyz") -> np.ndarray:
    """Rotation matrix (top-left 3x3 of ``rmat``) to float32 Euler angles in radians.

    ``axes``: one of the 24 sequences of ``_AXES2TUPLE`` ("sxyz" = roll, pitch, yaw about
    static x, y, z) or its (first axis, parity, repetition, frame) tuple. The matrix is read
    as float32; the angles are computed in float64 from those values.
    """
    try:
        first, parity, repetition, frame = _AXES2TUPLE[axes.lower()]  # type: ignore[union-attr]
    except (AttributeError, KeyError):
        first, parity, repetition, frame = axes

    i = first
    j = _NEXT_AXIS[i + parity]
    k = _NEXT_AXIS[i - parity + 1]

    m = np.asarray(rmat, dtype=_F32)[:3, :3]
    if repetition:
        sy = math.sqrt(m[i, j] * m[i, j] + m[i, k] * m[i, k])
        if sy > EPS:
            ax = math.atan2(m[i, j], m[i, k])
            ay = math.atan2(sy, m[i, i])
            az = math.atan2(m[j, i], -m[k, i])
        else:
            ax = math.atan2(-m[j, k], m[j, j])
            ay = math.atan2(sy, m[i, i])
            az = 0.0
    else:
        cy = math.sqrt(m[i, i] * m[i, i] + m[j, i] * m[j, i])
        if cy > EPS:
            ax = math.atan2(m[k, j], m[k, k])
            ay = math.atan2(-m[k, i], cy)
            az = math.atan2(m[j, i], m[i, i])
        else:
            ax = math.atan2(-m[j, k], m[j, j])
            ay = math.atan2(-m[k, i], cy)
            az = 0.0

    if parity:
        ax, ay, az = -ax, -ay, -az
    if frame:
        ax, az = az, ax
    return vec((ax, ay, az))


def pose2mat(pose: tuple[ArrayLike, ArrayLike]) -> np.ndarray:
    """``(position (3,), (x, y, z, w) quaternion)`` to a float32 4x4 homogeneous matrix."""
    mat = np.zeros((4, 4), dtype=_F32)
    mat[:3, :3] = quat2mat(pose[1])
    mat[:3, 3] = np.array(pose[0], dtype=_F32)
    mat[3, 3] = 1.0
    return mat


def quat2mat(quaternion: ArrayLike) -> np.ndarray:
    """(x, y, z, w) quaternion (need not be unit) to a float64 3x3 rotation matrix.

    The quaternion is read as float32, as in robosuite; a quaternion with squared norm below
    ``EPS`` gives the identity.
    """
    q = np.asarray(quaternion).astype(_F32)[[3, 0, 1, 2]]  # (w, x, y, z)
    n = _dot32(q, q)
    if n < EPS:
        return np.identity(3)
    # Scale by sqrt(2 / n) in float64, keep float32 (numba's in-place float32 multiply).
    q = (q.astype(_F64) * math.sqrt(2.0 / float(n))).astype(_F32)
    q2 = np.outer(q, q)  # float32 products
    d = q2.astype(_F64)
    return np.array(
        [
            [1.0 - d[2, 2] - d[3, 3], q2[1, 2] - q2[3, 0], q2[1, 3] + q2[2, 0]],
            [q2[1, 2] + q2[3, 0], 1.0 - d[1, 1] - d[3, 3], q2[2, 3] - q2[1, 0]],
            [q2[1, 3] - q2[2, 0], q2[2, 3] + q2[1, 0], 1.0 - d[1, 1] - d[2, 2]],
        ],
        dtype=_F64,
    )


def quat2axisangle(quat: np.ndarray) -> np.ndarray:
    """(x, y, z, w) quaternion to axis-angle: the rotation axis scaled by the angle in radians.

    Like robosuite, ``quat[3]`` is clipped to [-1, 1] in place when ``quat`` is an array.
    Returns ``zeros(3)`` (float64) for an exactly zero rotation (``1 - w^2 == 0``); otherwise
    float32 for a float32 quaternion, float64 else. Not batched.
    """
    if not isinstance(quat, np.ndarray):
        quat = np.asarray(quat, dtype=_F64)
    if quat[3] > 1.0:
        quat[3] = 1.0
    elif quat[3] < -1.0:
        quat[3] = -1.0

    dt = _F32 if quat.dtype == _F32 else _F64
    w = quat[3]
    den = math.sqrt(1.0 - float(w * w))  # w * w rounds in the quaternion's precision
    if den == 0.0:
        return np.zeros(3)
    return (quat[:3].astype(dt) * dt(2.0) * dt(math.acos(float(w)))) / dt(den)


def axisangle2quat(vec: ArrayLike) -> np.ndarray:
    """Axis-angle (axis scaled by the angle in radians) to a float64 (x, y, z, w) quaternion.

    A zero vector gives the identity ``[0, 0, 0, 1]``. Not batched.
    """
    v = np.asarray(vec)
    if v.dtype == _F32:
        angle = np.sqrt(_dot32(v, v))
        dt = _F32
    else:
        v = v.astype(_F64)
        angle = np.linalg.norm(v)
        dt = _F64
    if angle == 0.0:
        return np.array([0.0, 0.0, 0.0, 1.0])
    axis = v / angle
    half = float(angle) / 2.0
    q = np.zeros(4)
    q[3] = np.cos(half)
    q[:3] = axis * dt(np.sin(half))
    return q


def pose_in_A_to_pose_in_B(pose_A: ArrayLike, pose_A_in_B: ArrayLike) -> np.ndarray:
    """Pose of C in frame B, ``pose_A_in_B @ pose_A``, from the pose of C in frame A
    (``pose_A``) and the pose of A in B (all 4x4)."""
    return np.asarray(pose_A_in_B).dot(pose_A)


def pose_inv(pose: ArrayLike) -> np.ndarray:
    """Inverse ``[[R^T, -R^T p], [0, 1]]`` of a 4x4 pose ``[[R, p], [0, 1]]``, as float64."""
    pose = np.asarray(pose)
    inv = np.zeros((4, 4))
    inv[:3, :3] = pose[:3, :3].T
    inv[:3, 3] = -inv[:3, :3].dot(pose[:3, 3])
    inv[3, 3] = 1.0
    return inv


def _skew_symmetric_translation(pos_A_in_B: ArrayLike) -> np.ndarray:
    """3x3 cross-product matrix ``[p]x`` of the position of A in B (``[p]x v = p x v``)."""
    px, py, pz = pos_A_in_B[0], pos_A_in_B[1], pos_A_in_B[2]
    return np.array([0.0, -pz, py, pz, 0.0, -px, -py, px, 0.0]).reshape((3, 3))


def vel_in_A_to_vel_in_B(
    vel_A: ArrayLike, ang_vel_A: ArrayLike, pose_A_in_B: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Linear and angular velocity of a point given in frame A, expressed in frame B.

    Returns ``(R v + [p]x R w, R w)`` where ``[[R, p], [0, 1]] = pose_A_in_B``.
    """
    pose_A_in_B = np.asarray(pose_A_in_B)
    rot = pose_A_in_B[:3, :3]
    skew = _skew_symmetric_translation(pose_A_in_B[:3, 3])
    vel_B = rot.dot(vel_A) + skew.dot(rot.dot(ang_vel_A))
    ang_vel_B = rot.dot(ang_vel_A)
    return vel_B, ang_vel_B


def force_in_A_to_force_in_B(
    force_A: ArrayLike, torque_A: ArrayLike, pose_A_in_B: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Force and torque at a point given in frame A, expressed in frame B.

    Returns ``(R^T f, -R^T [p]x f + R^T t)`` where ``[[R, p], [0, 1]] = pose_A_in_B``
    (robosuite's formula).
    """
    pose_A_in_B = np.asarray(pose_A_in_B)
    rot = pose_A_in_B[:3, :3]
    skew = _skew_symmetric_translation(pose_A_in_B[:3, 3])
    force_B = rot.T.dot(force_A)
    torque_B = -rot.T.dot(skew.dot(force_A)) + rot.T.dot(torque_A)
    return force_B, torque_B


def rotation_matrix(angle: float, direction: ArrayLike, point: ArrayLike | None = None) -> np.ndarray:
    """4x4 float64 pose rotating by ``angle`` radians about ``direction`` (need not be unit),
    through ``point`` if given (else through the origin).

    The rotation block and the translation are computed in float32, as in robosuite.
    """
    sina = math.sin(angle)
    cosa = math.cos(angle)
    axis = unit_vector(direction[:3])
    rot = np.array(((cosa, 0.0, 0.0), (0.0, cosa, 0.0), (0.0, 0.0, cosa)), dtype=_F32)
    rot += np.outer(axis, axis) * _F32(1.0 - cosa)
    axis *= _F32(sina)
    rot += np.array(
        ((0.0, -axis[2], axis[1]), (axis[2], 0.0, -axis[0]), (-axis[1], axis[0], 0.0)),
        dtype=_F32,
    )
    mat = np.identity(4)
    mat[:3, :3] = rot
    if point is not None:
        p = np.asarray(point[:3], dtype=_F32)
        rotated = np.array([_dot32(rot[r], p) for r in range(3)], dtype=_F32)
        mat[:3, 3] = p - rotated
    return mat


def clip_translation(dpos: ArrayLike, limit: float) -> tuple[Any, bool]:
    """Scale ``dpos`` (any length) down to norm ``limit`` if its norm exceeds it.

    Returns ``(clipped dpos, True)``, or ``(dpos itself, False)`` when within the limit.
    """
    arr = np.asarray(dpos)
    if arr.dtype == _F32:
        norm = np.sqrt(_dot32(arr, arr))
        if norm > limit:
            return (arr * _F32(limit)) / norm, True
        return dpos, False
    norm = np.linalg.norm(arr)
    if norm > limit:
        return arr * limit / norm, True
    return dpos, False


def clip_rotation(quat: ArrayLike, limit: float) -> tuple[np.ndarray, bool]:
    """Limit the angle of an (x, y, z, w) rotation to ``limit`` radians.

    Returns ``(quaternion, clipped)``: the normalized input and False when its angle is within
    the limit (or zero), else the float64 quaternion about the same axis with angle ``limit``
    and True.
    """
    q = np.asarray(quat)
    if q.dtype == _F32:
        q = q / np.sqrt(_dot32(q, q))
    else:
        q = q.astype(_F64)
        q = q / np.linalg.norm(q)

    den = math.sqrt(max(1.0 - float(q[3] * q[3]), 0.0))
    if den == 0:
        return q, False
    x = float(q[0]) / den
    y = float(q[1]) / den
    z = float(q[2]) / den
    a = 2 * math.acos(float(q[3]))

    if abs(a) > limit:
        a = float(limit) * float(np.sign(a)) / 2
        sa = math.sin(a)
        ca = math.cos(a)
        return np.array([x * sa, y * sa, z * sa, ca]), True
    return q, False


def make_pose(translation: ArrayLike, rotation: ArrayLike) -> np.ndarray:
    """float64 4x4 pose ``[[rotation, translation], [0, 1]]``."""
    pose = np.zeros((4, 4))
    pose[:3, :3] = rotation
    pose[:3, 3] = translation
    pose[3, 3] = 1.0
    return pose


def unit_vector(data: ArrayLike, axis: int | None = None, out: np.ndarray | None = None) -> np.ndarray | None:
    """``data`` divided by its Euclidean norm (along ``axis`` if given, else over the whole
    array).

    Without ``out`` returns a new float32 array; with ``out`` writes the result into ``out``
    (in its dtype) and returns None.
    """
    if out is None:
        data = np.array(data, dtype=_F32, copy=True)
        if data.ndim == 1:
            data /= math.sqrt(float(_dot32(data, data)))
            return data
    else:
        if out is not data:
            out[:] = np.asarray(data)
        data = out
    length = np.atleast_1d(np.sum(data * data, axis))
    np.sqrt(length, length)
    if axis is not None:
        length = np.expand_dims(length, axis)
    data /= length
    if out is None:
        return data
    return None


def get_orientation_error(target_orn: ArrayLike, current_orn: ArrayLike) -> np.ndarray:
    """3-vector orientation error (target - current) between two (x, y, z, w) quaternions,
    as used by robosuite's operational-space controllers: ``2 * E(current) @ target`` in
    (w, x, y, z) order."""
    c = np.array([current_orn[3], current_orn[0], current_orn[1], current_orn[2]])
    t = np.array([target_orn[3], target_orn[0], target_orn[1], target_orn[2]])
    e = np.zeros((3, 4))
    e[0, :] = [-c[1], c[0], -c[3], c[2]]
    e[1, :] = [-c[2], c[3], c[0], -c[1]]
    e[2, :] = [-c[3], -c[2], c[1], c[0]]
    return 2.0 * e.dot(t)


def get_pose_error(target_pose: ArrayLike, current_pose: ArrayLike) -> np.ndarray:
    """6-vector error between two 4x4 poses: position difference (target - current), then
    the rotation error ``0.5 * sum_i current_col_i x target_col_i``."""
    target_pose = np.asarray(target_pose)
    current_pose = np.asarray(current_pose)
    error = np.zeros(6)
    error[:3] = target_pose[:3, 3] - current_pose[:3, 3]
    error[3:] = 0.5 * (
        np.cross(current_pose[:3, 0], target_pose[:3, 0])
        + np.cross(current_pose[:3, 1], target_pose[:3, 1])
        + np.cross(current_pose[:3, 2], target_pose[:3, 2])
    )
    return error


def matrix_inverse(matrix: ArrayLike) -> np.ndarray:
    """Inverse of a square matrix (``np.linalg.inv``)."""
    return np.linalg.inv(matrix)


def rotate_2d_point(input: ArrayLike, rot: float) -> np.ndarray:
    """The 2-D vector ``input`` rotated counterclockwise by ``rot`` radians."""
    input_x, input_y = input
    x = input_x * np.cos(rot) - input_y * np.sin(rot)
    y = input_x * np.sin(rot) + input_y * np.cos(rot)
    return np.array([x, y])
