"""``robosuite_rs.utils.camera_utils`` gives robosuite 1.5.2's results.

The fixture python/tests/fixtures/robosuite_utils/camera_utils.json (scripts/record_utils.py)
holds, from robosuite's Lift env (Panda) after reset, the simulator values the functions read
and robosuite's outputs for six cameras at two image sizes. The tests rebuild a minimal
robosuite-style sim from those values (``camera_name2id``, ``cam_fovy``, ``cam_xpos``,
``cam_xmat``, ``stat.extent``, ``vis.map.znear/zfar``), so they do not need an env.

Tolerance 1e-12 (absolute and relative): the camera functions compute in float64 (a float32
depth map stays float32, compared to 1e-6). ``CameraMover`` goes through robosuite's float32
``mat2quat``; its poses compare to 1e-6.
"""

from __future__ import annotations

import json
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

from robosuite_rs.utils import camera_utils as CU
from robosuite_rs.utils import transform_utils as T

from . import recorded
from .recorded import decode

FIXTURE = Path(__file__).parent / "fixtures" / "robosuite_utils" / "camera_utils.json"
DATA = json.loads(FIXTURE.read_text())

TOL = 1e-12
F32_TOL = 1e-6
MOVER_TOL = 1e-6

# robosuite names that need robosuite's env machinery (h5py demo files, XML resets,
# DomainRandomizationWrapper); robosuite_rs does not provide them.
NOT_PROVIDED = {"DemoPlaybackCameraMover"}

def assert_array(ours: Any, ref: dict, tol: float = TOL, where: str = "") -> None:
    recorded.assert_array(ours, ref, tol, where)


def mujoco_quat2mat(q: np.ndarray) -> np.ndarray:
    """Row-major 3x3 of a unit (w, x, y, z) quaternion, as MuJoCo's mju_quat2Mat."""
    w, x, y, z = q
    return np.array(
        [
            w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y),
            2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x),
            2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z,
        ]
    )


def make_sim() -> SimpleNamespace:
    """A robosuite-style sim holding the recorded values; ``forward()`` recomputes the world
    pose of cameras in the world body from ``model.cam_pos`` / ``model.cam_quat``."""
    rec = DATA["sim"]
    names = tuple(rec["camera_names"])
    ids = rec["camera_ids"]

    def camera_name2id(name: str) -> int:
        # robosuite's binding_utils.MjModel.camera_name2id
        if name == "free":
            return -1
        if name not in ids:
            raise ValueError('No "camera" with name %s exists. Available "camera" names = %s.' % (name, names))
        return ids[name]

    model = SimpleNamespace(
        camera_name2id=camera_name2id,
        cam_fovy=decode(rec["cam_fovy"]),
        cam_pos=decode(rec["cam_pos"]),
        cam_quat=decode(rec["cam_quat"]),
        cam_bodyid=decode(rec["cam_bodyid"]),
        stat=SimpleNamespace(extent=decode(rec["stat_extent"])),
        vis=SimpleNamespace(map=SimpleNamespace(znear=rec["vis_map_znear"], zfar=rec["vis_map_zfar"])),
    )
    data = SimpleNamespace(cam_xpos=decode(rec["cam_xpos"]), cam_xmat=decode(rec["cam_xmat"]))
    sim = SimpleNamespace(model=model, data=data, forward_calls=0)

    def forward() -> None:
        sim.forward_calls += 1
        for i in np.flatnonzero(model.cam_bodyid == 0):
            data.cam_xpos[i] = model.cam_pos[i]
            data.cam_xmat[i] = mujoco_quat2mat(model.cam_quat[i])

    sim.forward = forward
    return sim


CAMERA_CASES = [pytest.param(e, id=f"{e['camera_name']}-{e['height']}x{e['width']}") for e in DATA["cameras"]]


def test_fixture_covers_the_cameras() -> None:
    assert {e["camera_name"] for e in DATA["cameras"]} == {
        "frontview", "birdview", "agentview", "sideview", "robot0_robotview", "robot0_eye_in_hand"
    }
    assert len({(e["height"], e["width"]) for e in DATA["cameras"]}) == 2


@pytest.mark.parametrize("entry", CAMERA_CASES)
def test_camera_matrices(entry: dict) -> None:
    sim = make_sim()
    name, h, w = entry["camera_name"], entry["height"], entry["width"]
    assert sim.model.camera_name2id(name) == entry["camera_id"]
    assert_array(CU.get_camera_intrinsic_matrix(sim, name, h, w), entry["intrinsic"], where="intrinsic")
    assert_array(CU.get_camera_extrinsic_matrix(sim, name), entry["extrinsic"], where="extrinsic")
    assert_array(CU.get_camera_transform_matrix(sim, name, h, w), entry["transform"], where="transform")
    # keyword arguments, as robosuite's own callers pass them
    assert_array(
        CU.get_camera_transform_matrix(sim=sim, camera_name=name, camera_height=h, camera_width=w),
        entry["transform"],
        where="transform (keywords)",
    )


@pytest.mark.parametrize("entry", CAMERA_CASES)
def test_project_points(entry: dict) -> None:
    transform = decode(entry["transform"])
    for i, case in enumerate(entry["project"]):
        pixels = CU.project_points_from_world_to_camera(
            decode(case["points"]), transform, entry["height"], entry["width"]
        )
        assert_array(pixels, case["pixels"], where=f"project[{i}]")


@pytest.mark.parametrize("entry", CAMERA_CASES)
def test_pixels_to_world(entry: dict) -> None:
    camera_to_world = decode(entry["camera_to_world"])
    for i, case in enumerate(entry["unproject"]):
        pixels, depth = decode(case["pixels"]), decode(case["depth_map"])
        if "raises" in case:
            # robosuite's bilinear sampling mis-shapes batched (..., H, W, 1) depth maps.
            with pytest.raises(ValueError) as excinfo:
                CU.transform_from_pixels_to_world(pixels, depth, camera_to_world)
            assert str(excinfo.value) == case["message"]
        else:
            points = CU.transform_from_pixels_to_world(pixels, depth, camera_to_world)
            assert_array(points, case["points"], where=f"unproject[{i}]")


def test_real_depth_map() -> None:
    sim = make_sim()
    assert DATA["real_depth"]
    for i, case in enumerate(DATA["real_depth"]):
        depth = decode(case["depth_map"])
        tol = F32_TOL if depth.dtype == np.float32 else TOL
        assert_array(CU.get_real_depth_map(sim, depth), case["real"], tol, where=f"real_depth[{i}]")


def test_real_depth_map_bounds() -> None:
    """0 maps to the near plane and 1 to the far plane (``znear``/``zfar`` times extent)."""
    sim = make_sim()
    extent = sim.model.stat.extent
    real = CU.get_real_depth_map(sim, np.array([0.0, 1.0]))
    # 1 - d (1 - near / far) cancels at d = 1: a few 1e-13 of relative rounding.
    np.testing.assert_allclose(real, [sim.model.vis.map.znear * extent, sim.model.vis.map.zfar * extent], rtol=1e-10)


def test_free_camera_reads_the_last_camera() -> None:
    """robosuite's ``camera_name2id("free")`` is -1, which indexes the last camera."""
    sim = make_sim()
    assert_array(CU.get_camera_intrinsic_matrix(sim, "free", 84, 84), DATA["free_camera"]["intrinsic"])
    assert_array(CU.get_camera_extrinsic_matrix(sim, "free"), DATA["free_camera"]["extrinsic"])


def test_bilinear_interpolate() -> None:
    assert DATA["bilinear_interpolate"]
    for i, case in enumerate(DATA["bilinear_interpolate"]):
        out = CU.bilinear_interpolate(decode(case["im"]), decode(case["x"]), decode(case["y"]))
        if "scalar" in case["result"]:  # scalar x and y give a NumPy scalar
            expected = decode(case["result"])
            assert isinstance(out, np.generic) and out.dtype == expected.dtype, f"bilinear[{i}]"
            assert abs(out - expected) <= TOL * max(1.0, abs(expected)), f"bilinear[{i}]"
        else:
            assert_array(out, case["result"], where=f"bilinear[{i}]")


# The calls scripts/record_utils.py made on robosuite (sim, agentview's 84x84 transform t).
# The unknown-camera errors come from the sim's camera_name2id (the fake copies robosuite's);
# the camera functions must let them through unchanged.
ERROR_CALLS = {
    "intrinsic_unknown_camera": lambda sim, t: CU.get_camera_intrinsic_matrix(sim, "no_such_camera", 84, 84),
    "extrinsic_unknown_camera": lambda sim, t: CU.get_camera_extrinsic_matrix(sim, "no_such_camera"),
    "depth_above_one": lambda sim, t: CU.get_real_depth_map(sim, np.array([0.5, 1.5])),
    "depth_below_zero": lambda sim, t: CU.get_real_depth_map(sim, np.array([[-0.1, 0.5]])),
    "project_points_not_3d": lambda sim, t: CU.project_points_from_world_to_camera(np.zeros((4, 2)), t, 84, 84),
    "project_transform_not_4x4": lambda sim, t: CU.project_points_from_world_to_camera(
        np.zeros((4, 3)), t[:3], 84, 84
    ),
    "project_transform_not_2d": lambda sim, t: CU.project_points_from_world_to_camera(
        np.zeros((4, 3)), t[None], 84, 84
    ),
    "unproject_leading_shape_mismatch": lambda sim, t: CU.transform_from_pixels_to_world(
        np.zeros((2, 2)), np.ones((3, 6, 8, 1)), np.linalg.inv(t)
    ),
}


@pytest.mark.parametrize("key", sorted(ERROR_CALLS))
def test_bad_input_fails_like_robosuite(key: str) -> None:
    sim = make_sim()
    t = CU.get_camera_transform_matrix(sim, "agentview", 84, 84)
    expected = DATA["errors"][key]
    with pytest.raises(Exception) as excinfo:
        ERROR_CALLS[key](sim, t)
    assert type(excinfo.value).__name__ == expected["raises"]
    assert str(excinfo.value) == expected["message"]


def test_error_fixture_is_covered() -> None:
    assert set(DATA["errors"]) == set(ERROR_CALLS)


def test_camera_segmentation_flips_the_render() -> None:
    """robosuite renders with ``segmentation=True`` and flips rows to image order."""
    calls = []
    frame = np.arange(4 * 3 * 2).reshape(4, 3, 2)

    def render(**kwargs: Any) -> np.ndarray:
        calls.append(kwargs)
        return frame

    sim = SimpleNamespace(render=render)
    out = CU.get_camera_segmentation(sim, "agentview", 4, 3)
    assert calls == [{"camera_name": "agentview", "height": 4, "width": 3, "segmentation": True}]
    np.testing.assert_array_equal(out, frame[::-1])


def check_snapshot(mover: CU.CameraMover, snap: dict, where: str) -> None:
    sim = mover.env.sim
    cam_id = sim.model.camera_name2id(mover.camera)
    pos, quat = mover.get_camera_pose()
    ref_pos, ref_quat = decode(snap["pose"])
    np.testing.assert_allclose(pos, ref_pos, atol=MOVER_TOL, err_msg=f"{where}: pose position")
    np.testing.assert_allclose(quat, ref_quat, atol=MOVER_TOL, err_msg=f"{where}: pose quaternion")
    np.testing.assert_allclose(sim.data.cam_xpos[cam_id], decode(snap["cam_xpos"]), atol=MOVER_TOL, err_msg=where)
    np.testing.assert_allclose(sim.data.cam_xmat[cam_id], decode(snap["cam_xmat"]), atol=MOVER_TOL, err_msg=where)


@pytest.mark.parametrize("session", DATA["camera_mover"]["sessions"], ids=lambda s: s["camera"])
def test_camera_mover(session: dict) -> None:
    sim = make_sim()
    env = SimpleNamespace(sim=sim)
    camera = session["camera"]
    cam_id = sim.model.camera_name2id(camera)
    np.testing.assert_array_equal(sim.model.cam_pos[cam_id], decode(session["model_cam_pos"]))
    np.testing.assert_array_equal(sim.model.cam_quat[cam_id], decode(session["model_cam_quat"]))
    # robosuite's CameraMover rebuilds the env from its XML, whose numbers have 6 digits; the
    # camera starts from that rounded pose. Start the same way.
    reloaded_pos, reloaded_quat = decode(session["reloaded_mocap_pos"]), decode(session["reloaded_mocap_quat"])
    np.testing.assert_allclose(reloaded_pos, sim.model.cam_pos[cam_id], atol=1e-6)
    np.testing.assert_allclose(reloaded_quat, sim.model.cam_quat[cam_id], atol=1e-6)
    sim.model.cam_pos[cam_id] = reloaded_pos
    sim.model.cam_quat[cam_id] = reloaded_quat

    mover = CU.CameraMover(env, camera=camera, **decode(session["init_kwargs"]))
    assert mover.mover_body_name == session["mover_body_name"]
    assert sim.forward_calls == 1
    check_snapshot(mover, session["after_init"], "after init")

    for i, step in enumerate(session["steps"]):
        result = getattr(mover, step["method"])(**decode(step["kwargs"]))
        where = f"step {i} {step['method']}"
        if step["result"] is None:
            assert result is None, where
        else:
            ref = decode(step["result"])
            assert isinstance(result, tuple) and len(result) == len(ref), where
            for ours, expected in zip(result, ref):
                np.testing.assert_allclose(ours, expected, atol=MOVER_TOL, err_msg=where)
                assert np.asarray(ours).dtype == expected.dtype, where
        check_snapshot(mover, step, where)


def test_camera_mover_writes_the_model_pose() -> None:
    sim = make_sim()
    mover = CU.CameraMover(SimpleNamespace(sim=sim), camera="birdview")
    cam_id = sim.model.camera_name2id("birdview")
    quat = T.axisangle2quat(np.array([0.0, 0.0, 0.5]))
    mover.set_camera_pose(pos=[0.1, 0.2, 3.0], quat=2.0 * quat)
    np.testing.assert_array_equal(sim.model.cam_pos[cam_id], [0.1, 0.2, 3.0])
    np.testing.assert_allclose(sim.model.cam_quat[cam_id], T.convert_quat(quat, to="wxyz"), atol=1e-15)
    pos, got_quat = mover.get_camera_pose()
    np.testing.assert_array_equal(pos, [0.1, 0.2, 3.0])
    np.testing.assert_array_equal(got_quat, 2.0 * quat)  # kept as given, like a mocap quaternion


@pytest.mark.parametrize("camera", sorted(DATA["camera_mover"]["errors"]))
def test_camera_mover_refuses_cameras_robosuite_refuses(camera: str) -> None:
    expected = DATA["camera_mover"]["errors"][camera]
    with pytest.raises(Exception) as excinfo:
        CU.CameraMover(SimpleNamespace(sim=make_sim()), camera=camera)
    assert type(excinfo.value).__name__ == expected["raises"]


def test_every_public_name_of_robosuite() -> None:
    wanted = set(DATA["public_names"]) - NOT_PROVIDED
    assert {n for n in wanted if not hasattr(CU, n)} == set()
    assert wanted <= set(CU.__all__)
