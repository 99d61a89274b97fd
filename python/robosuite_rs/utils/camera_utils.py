"""Camera matrices, depth maps and pixel <-> world projections: robosuite 1.5.2's
``camera_utils`` in NumPy, plus ``CameraMover``.

The functions take a robosuite-style simulator ``sim`` and read only what robosuite's read:
``sim.model.camera_name2id(name)``, ``sim.model.cam_fovy`` (degrees, one per camera),
``sim.data.cam_xpos`` (ncam x 3), ``sim.data.cam_xmat`` (ncam x 9, row-major),
``sim.model.stat.extent``, ``sim.model.vis.map.znear`` / ``zfar`` and, for segmentation,
``sim.render(...)``. Any object with those attributes works.

Conventions: camera frames follow OpenCV (x right, y down, z along the view; robosuite flips
MuJoCo's camera y and z axes), pixels are (row, column), quaternions are (x, y, z, w).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from . import transform_utils as T

__all__ = [
    "get_camera_intrinsic_matrix",
    "get_camera_extrinsic_matrix",
    "get_camera_transform_matrix",
    "get_camera_segmentation",
    "get_real_depth_map",
    "project_points_from_world_to_camera",
    "transform_from_pixels_to_world",
    "bilinear_interpolate",
    "CameraMover",
]

# MuJoCo cameras look along -z with y up; this flips y and z so z looks along the view.
_CAMERA_AXIS_CORRECTION = np.array(
    [[1.0, 0.0, 0.0, 0.0], [0.0, -1.0, 0.0, 0.0], [0.0, 0.0, -1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]
)


def get_camera_intrinsic_matrix(sim: Any, camera_name: str, camera_height: int, camera_width: int) -> np.ndarray:
    """3x3 pinhole intrinsics ``[[f, 0, w/2], [0, f, h/2], [0, 0, 1]]`` of a camera for
    ``camera_height`` x ``camera_width`` images, with ``f = (h / 2) / tan(fovy / 2)``."""
    cam_id = sim.model.camera_name2id(camera_name)
    fovy = sim.model.cam_fovy[cam_id]
    f = 0.5 * camera_height / np.tan(fovy * np.pi / 360)
    return np.array([[f, 0, camera_width / 2], [0, f, camera_height / 2], [0, 0, 1]])


def get_camera_extrinsic_matrix(sim: Any, camera_name: str) -> np.ndarray:
    """4x4 pose of the camera in the world frame, axes in the OpenCV convention (z along the
    view, y down): MuJoCo's camera pose with its y and z axes flipped."""
    cam_id = sim.model.camera_name2id(camera_name)
    camera_pos = sim.data.cam_xpos[cam_id]
    camera_rot = sim.data.cam_xmat[cam_id].reshape(3, 3)
    return T.make_pose(camera_pos, camera_rot) @ _CAMERA_AXIS_CORRECTION


def get_camera_transform_matrix(sim: Any, camera_name: str, camera_height: int, camera_width: int) -> np.ndarray:
    """4x4 matrix taking homogeneous world points to homogeneous pixels:
    ``[[K, 0], [0, 1]] @ inverse(extrinsic)``; divide by the third component to get
    (column, row) pixel coordinates."""
    extrinsic = get_camera_extrinsic_matrix(sim=sim, camera_name=camera_name)
    intrinsic = get_camera_intrinsic_matrix(
        sim=sim, camera_name=camera_name, camera_height=camera_height, camera_width=camera_width
    )
    k_exp = np.eye(4)
    k_exp[:3, :3] = intrinsic
    return k_exp @ T.pose_inv(extrinsic)


def get_camera_segmentation(sim: Any, camera_name: str, camera_height: int, camera_width: int) -> np.ndarray:
    """Segmentation image from ``sim.render(..., segmentation=True)`` flipped upside down to
    image row order: (H, W, 2) with the object types in channel 0 and the ids in channel 1."""
    return sim.render(camera_name=camera_name, height=camera_height, width=camera_width, segmentation=True)[::-1]


def get_real_depth_map(sim: Any, depth_map: np.ndarray) -> np.ndarray:
    """Distances (in meters) from MuJoCo's normalized depth buffer values in [0, 1]:
    ``near / (1 - d (1 - near / far))`` with ``near = znear * extent``, ``far = zfar * extent``.

    Raises:
        AssertionError: a value is outside [0, 1].
    """
    assert np.all(depth_map >= 0.0) and np.all(depth_map <= 1.0)
    extent = float(sim.model.stat.extent)
    far = float(sim.model.vis.map.zfar) * extent
    near = float(sim.model.vis.map.znear) * extent
    return near / (1.0 - depth_map * (1.0 - near / far))


def project_points_from_world_to_camera(
    points: np.ndarray, world_to_camera_transform: np.ndarray, camera_height: int, camera_width: int
) -> np.ndarray:
    """Pixel (row, column) indices, integer, shape ``(..., 2)``, of world points of shape
    ``(..., 3)`` under a 4x4 world-to-pixel transform (``get_camera_transform_matrix``).

    Coordinates are rounded half to even and clipped to the image.

    Raises:
        AssertionError: ``points`` do not end in 3 or the transform is not 4x4.
    """
    assert points.shape[-1] == 3
    assert len(world_to_camera_transform.shape) == 2
    assert world_to_camera_transform.shape[0] == 4 and world_to_camera_transform.shape[1] == 4

    lead = points.shape[:-1]
    homogeneous = np.concatenate((points, np.ones(lead + (1,))), axis=-1)  # (..., 4)
    transform = world_to_camera_transform.reshape([1] * len(lead) + [4, 4])
    pixels = np.matmul(transform, homogeneous[..., None])[..., 0]  # (..., 4)
    pixels = pixels / pixels[..., 2:3]
    pixels = pixels[..., :2].round().astype(int)  # (..., 2) as (column, row)
    return np.concatenate(
        (
            pixels[..., 1:2].clip(0, camera_height - 1),
            pixels[..., 0:1].clip(0, camera_width - 1),
        ),
        axis=-1,
    )


def transform_from_pixels_to_world(
    pixels: np.ndarray, depth_map: np.ndarray, camera_to_world_transform: np.ndarray
) -> np.ndarray:
    """World points, shape ``(..., 3)``, of pixels (row, column) of shape ``(..., 2)`` given
    depth images of shape ``(..., H, W, 1)`` and a 4x4 pixel-to-world transform (the inverse
    of ``get_camera_transform_matrix``).

    The depth at each (fractional) pixel is read by bilinear interpolation, exactly as
    robosuite does: robosuite takes the image size from ``depth_map.shape[-2:]``, i.e.
    (W, 1), so the maps are viewed as a ``(-1, W, 1, 1)`` stack and rows index into that
    stack; this reproduces it.

    Raises:
        AssertionError: the leading shapes of ``pixels`` and ``depth_map`` differ.
    """
    pixels_lead = pixels.shape[:-1]
    depth_lead = depth_map.shape[:-3]
    assert depth_lead == pixels_lead

    pixels = pixels.astype(float)
    im_h, im_w = depth_map.shape[-2:]
    stacked = depth_map.reshape(-1, im_h, im_w, 1)
    z = bilinear_interpolate(im=stacked, x=pixels[..., 1:2], y=pixels[..., 0:1])
    z = z.reshape(*depth_lead, 1)

    # Homogeneous camera vector [column * z, row * z, z, 1].
    cam_pts = np.concatenate([pixels[..., 1:2] * z, pixels[..., 0:1] * z, z, np.ones_like(z)], axis=-1)
    transform = camera_to_world_transform.reshape([1] * len(cam_pts.shape[:-1]) + [4, 4])
    points = np.matmul(transform, cam_pts[..., None])[..., 0]
    return points[..., :3]


def bilinear_interpolate(im: np.ndarray, x: ArrayLike, y: ArrayLike) -> np.ndarray:
    """Bilinear samples of ``im`` (indexed ``im[row, column]``) at columns ``x`` and rows
    ``y``; neighbours outside the image are clamped to its border."""
    x = np.asarray(x)
    y = np.asarray(y)

    x0 = np.floor(x).astype(int)
    y0 = np.floor(y).astype(int)
    x1 = np.clip(x0 + 1, 0, im.shape[1] - 1)
    y1 = np.clip(y0 + 1, 0, im.shape[0] - 1)
    x0 = np.clip(x0, 0, im.shape[1] - 1)
    y0 = np.clip(y0, 0, im.shape[0] - 1)

    top_left = im[y0, x0]
    bottom_left = im[y1, x0]
    top_right = im[y0, x1]
    bottom_right = im[y1, x1]

    w_top_left = (x1 - x) * (y1 - y)
    w_bottom_left = (x1 - x) * (y - y0)
    w_top_right = (x - x0) * (y1 - y)
    w_bottom_right = (x - x0) * (y - y0)

    return (
        w_top_left * top_left
        + w_bottom_left * bottom_left
        + w_top_right * top_right
        + w_bottom_right * bottom_right
    )


class CameraMover:
    """Moves one of the world's fixed cameras.

    robosuite attaches the camera to a new mocap body (rebuilding the env from its XML) and
    moves that body; here the camera's own model pose ``sim.model.cam_pos`` /
    ``sim.model.cam_quat`` (w, x, y, z) is written instead, then ``sim.forward()`` is called.
    For a camera in the world body the two are the same pose, and the env is not rebuilt.

    The mover keeps the pose as set (like robosuite's mocap pose: the quaternion as given,
    not normalized) and writes the normalized quaternion to the model, as MuJoCo normalizes
    mocap quaternions.

    Needs ``env.sim`` with ``model.camera_name2id``, ``model.cam_pos``, ``model.cam_quat``,
    ``forward()`` and, when present, ``model.cam_bodyid`` (to refuse cameras not in the
    world body, as robosuite does).

    Args:
        env: environment with a robosuite-style ``sim``.
        camera: name of the camera to move, e.g. "frontview", "agentview".
        init_camera_pos: (x, y, z) world position to start from, if given.
        init_camera_quat: (x, y, z, w) world orientation to start from, if given.

    Raises:
        AssertionError: no camera of that name directly in the world body.
    """

    def __init__(
        self,
        env: Any,
        camera: str = "frontview",
        init_camera_pos: ArrayLike | None = None,
        init_camera_quat: ArrayLike | None = None,
    ) -> None:
        self.env = env
        self.camera = camera
        self.mover_body_name = f"{self.camera}_cameramover"

        model = self.env.sim.model
        try:
            self.camera_id = int(model.camera_name2id(camera))
        except (ValueError, KeyError) as err:
            raise AssertionError(f"no camera named {camera!r}") from err
        assert self.camera_id >= 0, f"no camera named {camera!r}"
        body_ids = getattr(model, "cam_bodyid", None)
        if body_ids is not None:
            assert int(body_ids[self.camera_id]) == 0, f"camera {camera!r} is not in the world body"

        self._pos = np.array(model.cam_pos[self.camera_id], dtype=np.float64)
        self._quat_wxyz = np.array(model.cam_quat[self.camera_id], dtype=np.float64)

        self.set_camera_pose(pos=init_camera_pos, quat=init_camera_quat)

    def set_camera_pose(self, pos: ArrayLike | None = None, quat: ArrayLike | None = None) -> None:
        """Set the camera's world position (x, y, z) and/or orientation (x, y, z, w), then
        ``sim.forward()``."""
        model = self.env.sim.model
        if pos is not None:
            self._pos[:] = pos
            model.cam_pos[self.camera_id] = self._pos
        if quat is not None:
            self._quat_wxyz[:] = T.convert_quat(np.asarray(quat), to="wxyz")
            model.cam_quat[self.camera_id] = self._quat_wxyz / np.linalg.norm(self._quat_wxyz)
        self.env.sim.forward()

    def get_camera_pose(self) -> tuple[np.ndarray, np.ndarray]:
        """The camera's world pose as set: ``(position (3,), (x, y, z, w) quaternion)``."""
        return self._pos.copy(), T.convert_quat(self._quat_wxyz, to="xyzw")

    def rotate_camera(self, point: ArrayLike | None, axis: ArrayLike, angle: float) -> tuple[np.ndarray, np.ndarray]:
        """Rotate the camera by ``angle`` degrees about ``axis`` through ``point`` (both in the
        camera frame; ``point=None`` rotates about the camera's position).

        Returns the new ``(position, float32 (x, y, z, w) quaternion)``.
        """
        camera_pos = self._pos.copy()
        camera_rot = T.quat2mat(T.convert_quat(self._quat_wxyz, to="xyzw"))

        rotation = T.rotation_matrix(np.pi * angle / 180.0, axis, point=point)
        camera_pose = np.zeros((4, 4))
        camera_pose[:3, :3] = camera_rot
        camera_pose[:3, 3] = camera_pos
        camera_pose = camera_pose @ rotation

        pos, quat = camera_pose[:3, 3], T.mat2quat(camera_pose[:3, :3])
        self.set_camera_pose(pos=pos, quat=quat)
        return pos, quat

    def move_camera(self, direction: ArrayLike, scale: float) -> tuple[np.ndarray, np.ndarray]:
        """Move the camera by ``scale`` along ``direction`` (in the camera frame).

        Returns ``(new position, orientation)``; like robosuite, the orientation is returned
        in MuJoCo's (w, x, y, z) order.
        """
        camera_pos = self._pos.copy()
        camera_quat = self._quat_wxyz.copy()
        camera_rot = T.quat2mat(T.convert_quat(camera_quat, to="xyzw"))

        camera_pos += scale * camera_rot.dot(direction)
        self.set_camera_pose(pos=camera_pos)
        return camera_pos, camera_quat
