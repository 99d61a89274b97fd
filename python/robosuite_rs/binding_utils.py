"""robosuite's ``robosuite.utils.binding_utils``: ``MjSim``, ``MjModel``, ``MjData`` and
``MjSimState`` over MuJoCo's own Python objects.

``env.sim.model._model`` and ``env.sim.data._data`` are a ``mujoco.MjModel`` and a
``mujoco.MjData`` that share their memory with the Rust environment: what ``mujoco.mj_*``,
``mujoco.Renderer`` or ``mujoco.viewer`` read and write is what the environment steps. The
memory belongs to those Python objects, so a NumPy view of ``data.qpos`` stays valid after
``env.close()`` or after ``env.reset_from_xml_string`` gave the env a new model (it then
shows the old simulation, no longer stepped; a scene differing only in box sizes is loaded
into the same memory instead).

``MjSim.forward`` / ``step`` / ``reset`` run through the environment (MuJoCo errors become
``RuntimeError``, the environment then needs a reset); writes through ``set_state`` /
``set_state_from_flattened`` are checked (length, finite values) before anything changes.
"""

from __future__ import annotations

from typing import Any

import mujoco
import numpy as np

__all__ = ["MjSim", "MjModel", "MjData", "MjSimState"]

_OBJECTS = (
    ("body", "nbody", mujoco.mjtObj.mjOBJ_BODY),
    ("joint", "njnt", mujoco.mjtObj.mjOBJ_JOINT),
    ("geom", "ngeom", mujoco.mjtObj.mjOBJ_GEOM),
    ("site", "nsite", mujoco.mjtObj.mjOBJ_SITE),
    ("light", "nlight", mujoco.mjtObj.mjOBJ_LIGHT),
    ("camera", "ncam", mujoco.mjtObj.mjOBJ_CAMERA),
    ("actuator", "nu", mujoco.mjtObj.mjOBJ_ACTUATOR),
    ("sensor", "nsensor", mujoco.mjtObj.mjOBJ_SENSOR),
    ("tendon", "ntendon", mujoco.mjtObj.mjOBJ_TENDON),
    ("mesh", "nmesh", mujoco.mjtObj.mjOBJ_MESH),
)


class MjSimState:
    """A simulation state ``(time, qpos, qvel)`` (robosuite's ``MjSimState``)."""

    def __init__(self, time: float, qpos: np.ndarray, qvel: np.ndarray) -> None:
        self.time = time
        self.qpos = qpos
        self.qvel = qvel

    @classmethod
    def from_flattened(cls, array: Any, sim: "MjSim") -> "MjSimState":
        """The state of a flat ``[time, qpos, qvel]`` array for ``sim``'s model."""
        array = np.asarray(array, dtype=np.float64)
        nq, nv = sim.model.nq, sim.model.nv
        return cls(time=array[0], qpos=array[1 : 1 + nq], qvel=array[1 + nq : 1 + nq + nv])

    def flatten(self) -> np.ndarray:
        """``[time, qpos, qvel]`` as one float64 array."""
        return np.concatenate([[self.time], self.qpos, self.qvel], axis=0)


def _names(model: mujoco.MjModel, count: str, obj: Any) -> tuple[tuple[Any, ...], dict[Any, int], dict[int, Any]]:
    id2name = {i: mujoco.mj_id2name(model, obj, i) for i in range(getattr(model, count))}
    name2id = {name: i for i, name in id2name.items()}
    return tuple(id2name[i] for i in sorted(name2id.values())), name2id, id2name


def _lookups(kind: str) -> tuple[Any, Any]:
    """``{kind}_name2id`` and ``{kind}_id2name`` with robosuite's errors (``ValueError``
    listing the names); the camera's also map ``"free"`` and -1 to each other."""
    free = kind == "camera"
    by_name, by_id, names_key = f"_{kind}_name2id", f"_{kind}_id2name", f"{kind}_names"

    def name2id(self: "MjModel", name: str) -> int:
        if free and name == "free":
            return -1
        try:
            return getattr(self, by_name)[name]
        except KeyError:
            names = getattr(self, names_key)
            raise ValueError(f'No "{kind}" with name {name} exists. Available "{kind}" names = {names}.') from None

    def id2name(self: "MjModel", id: int) -> Any:
        if free and id == -1:
            return "free"
        try:
            return getattr(self, by_id)[id]
        except KeyError:
            raise ValueError(f"No {kind} with id {id} exists.") from None

    name2id.__name__, id2name.__name__ = f"{kind}_name2id", f"{kind}_id2name"
    name2id.__doc__ = f"The id of {kind} ``name`` (``ValueError`` listing the names if there is none)."
    id2name.__doc__ = f"The name of {kind} ``id``."
    return name2id, id2name


class MjModel:
    """robosuite's ``MjModel``: a ``mujoco.MjModel`` (``_model``) with mujoco-py's name
    lookups (``body_name2id``, ``site_id2name``, ``camera_names``, ...), ``get_xml`` and the
    joint address helpers; every other attribute is the ``mujoco.MjModel``'s."""

    def __init__(self, model: mujoco.MjModel, get_xml: Any = None) -> None:
        object.__setattr__(self, "_model", model)
        object.__setattr__(self, "_get_xml", get_xml)
        for kind, count, obj in _OBJECTS:
            names, name2id, id2name = _names(model, count, obj)
            object.__setattr__(self, f"{kind}_names", names)
            object.__setattr__(self, f"_{kind}_name2id", name2id)
            object.__setattr__(self, f"_{kind}_id2name", id2name)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._model, name)

    def __setattr__(self, name: str, value: Any) -> None:
        setattr(self._model, name, value)

    def __dir__(self) -> list[str]:
        return sorted(set(super().__dir__()) | set(dir(self._model)))

    def get_xml(self) -> str:
        """The scene as MJCF with the model's current values (what robomimic stores per
        demonstration and ``env.reset_from_xml_string`` loads back)."""
        if self._get_xml is None:
            raise RuntimeError("this model has no scene text (it was not made by an env)")
        return self._get_xml()

    def _joint_addr(self, name: str, adr: Any, free: int, ball: int) -> Any:
        joint_id = self.joint_name2id(name)
        kind = int(self._model.jnt_type[joint_id])
        addr = int(adr[joint_id])
        ndim = {int(mujoco.mjtJoint.mjJNT_FREE): free, int(mujoco.mjtJoint.mjJNT_BALL): ball}.get(kind, 1)
        return addr if ndim == 1 else (addr, addr + ndim)

    def get_joint_qpos_addr(self, name: str) -> Any:
        """The ``qpos`` address of joint ``name``: an int for a 1-dof joint, else
        ``(start, end)``."""
        return self._joint_addr(name, self._model.jnt_qposadr, 7, 4)

    def get_joint_qvel_addr(self, name: str) -> Any:
        """The ``qvel`` address of joint ``name``: an int for a 1-dof joint, else
        ``(start, end)``."""
        return self._joint_addr(name, self._model.jnt_dofadr, 6, 3)


for _kind, _count, _obj in _OBJECTS:
    _n2i, _i2n = _lookups(_kind)
    setattr(MjModel, _n2i.__name__, _n2i)
    setattr(MjModel, _i2n.__name__, _i2n)


class MjData:
    """robosuite's ``MjData``: a ``mujoco.MjData`` (``_data``) with mujoco-py's named
    getters and setters; every other attribute is the ``mujoco.MjData``'s."""

    def __init__(self, data: mujoco.MjData, model: MjModel) -> None:
        object.__setattr__(self, "_data", data)
        object.__setattr__(self, "_model", model)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._data, name)

    def __setattr__(self, name: str, value: Any) -> None:
        setattr(self._data, name, value)

    def __dir__(self) -> list[str]:
        return sorted(set(super().__dir__()) | set(dir(self._data)))

    @property
    def model(self) -> MjModel:
        """The model (robosuite's ``MjModel``)."""
        return self._model

    @property
    def body_xpos(self) -> np.ndarray:
        """``xpos`` (mujoco-py's name)."""
        return self._data.xpos

    @property
    def body_xquat(self) -> np.ndarray:
        """``xquat`` (mujoco-py's name)."""
        return self._data.xquat

    @property
    def body_xmat(self) -> np.ndarray:
        """``xmat`` (mujoco-py's name)."""
        return self._data.xmat

    def _jac(self, fn: Any, oid: int, rot: bool) -> np.ndarray:
        jac = np.zeros((3, self._model.nv))
        if rot:
            fn(self._model._model, self._data, None, jac, oid)
        else:
            fn(self._model._model, self._data, jac, None, oid)
        return jac

    def get_body_xpos(self, name: str) -> np.ndarray:
        """Position of body ``name``."""
        return self._data.xpos[self._model.body_name2id(name)]

    def get_body_xquat(self, name: str) -> np.ndarray:
        """Orientation of body ``name`` (w, x, y, z)."""
        return self._data.xquat[self._model.body_name2id(name)]

    def get_body_xmat(self, name: str) -> np.ndarray:
        """Orientation of body ``name`` as a 3×3 matrix."""
        return self._data.xmat[self._model.body_name2id(name)].reshape((3, 3))

    def get_body_jacp(self, name: str) -> np.ndarray:
        """Translational Jacobian (3×nv) of body ``name``."""
        return self._jac(mujoco.mj_jacBody, self._model.body_name2id(name), False)

    def get_body_jacr(self, name: str) -> np.ndarray:
        """Rotational Jacobian (3×nv) of body ``name``."""
        return self._jac(mujoco.mj_jacBody, self._model.body_name2id(name), True)

    def get_body_xvelp(self, name: str) -> np.ndarray:
        """Linear velocity of body ``name`` (Jacobian × qvel)."""
        return self.get_body_jacp(name) @ self._data.qvel

    def get_body_xvelr(self, name: str) -> np.ndarray:
        """Angular velocity of body ``name``."""
        return self.get_body_jacr(name) @ self._data.qvel

    def get_geom_xpos(self, name: str) -> np.ndarray:
        """Position of geom ``name``."""
        return self._data.geom_xpos[self._model.geom_name2id(name)]

    def get_geom_xmat(self, name: str) -> np.ndarray:
        """Orientation of geom ``name`` as a 3×3 matrix."""
        return self._data.geom_xmat[self._model.geom_name2id(name)].reshape((3, 3))

    def get_geom_jacp(self, name: str) -> np.ndarray:
        """Translational Jacobian of geom ``name``."""
        return self._jac(mujoco.mj_jacGeom, self._model.geom_name2id(name), False)

    def get_geom_jacr(self, name: str) -> np.ndarray:
        """Rotational Jacobian of geom ``name``."""
        return self._jac(mujoco.mj_jacGeom, self._model.geom_name2id(name), True)

    def get_geom_xvelp(self, name: str) -> np.ndarray:
        """Linear velocity of geom ``name``."""
        return self.get_geom_jacp(name) @ self._data.qvel

    def get_geom_xvelr(self, name: str) -> np.ndarray:
        """Angular velocity of geom ``name``."""
        return self.get_geom_jacr(name) @ self._data.qvel

    def get_site_xpos(self, name: str) -> np.ndarray:
        """Position of site ``name``."""
        return self._data.site_xpos[self._model.site_name2id(name)]

    def get_site_xmat(self, name: str) -> np.ndarray:
        """Orientation of site ``name`` as a 3×3 matrix."""
        return self._data.site_xmat[self._model.site_name2id(name)].reshape((3, 3))

    def get_site_jacp(self, name: str) -> np.ndarray:
        """Translational Jacobian of site ``name``."""
        return self._jac(mujoco.mj_jacSite, self._model.site_name2id(name), False)

    def get_site_jacr(self, name: str) -> np.ndarray:
        """Rotational Jacobian of site ``name``."""
        return self._jac(mujoco.mj_jacSite, self._model.site_name2id(name), True)

    def get_site_xvelp(self, name: str) -> np.ndarray:
        """Linear velocity of site ``name``."""
        return self.get_site_jacp(name) @ self._data.qvel

    def get_site_xvelr(self, name: str) -> np.ndarray:
        """Angular velocity of site ``name``."""
        return self.get_site_jacr(name) @ self._data.qvel

    def get_camera_xpos(self, name: str) -> np.ndarray:
        """Position of camera ``name``."""
        return self._data.cam_xpos[self._model.camera_name2id(name)]

    def get_camera_xmat(self, name: str) -> np.ndarray:
        """Orientation of camera ``name`` as a 3×3 matrix."""
        return self._data.cam_xmat[self._model.camera_name2id(name)].reshape((3, 3))

    def get_light_xpos(self, name: str) -> np.ndarray:
        """Position of light ``name``."""
        return self._data.light_xpos[self._model.light_name2id(name)]

    def get_light_xdir(self, name: str) -> np.ndarray:
        """Direction of light ``name``."""
        return self._data.light_xdir[self._model.light_name2id(name)]

    def get_sensor(self, name: str) -> Any:
        """``sensordata[sensor id]`` — robosuite's (and mujoco-py's) indexing by sensor id,
        not by the sensor's address: the first value of a 1-dimensional sensor."""
        return self._data.sensordata[self._model.sensor_name2id(name)]

    def _mocap_id(self, name: str) -> int:
        return int(self._model.body_mocapid[self._model.body_name2id(name)])

    def get_mocap_pos(self, name: str) -> np.ndarray:
        """Position of mocap body ``name``."""
        return self._data.mocap_pos[self._mocap_id(name)]

    def set_mocap_pos(self, name: str, value: Any) -> None:
        """Sets the position of mocap body ``name``."""
        self._data.mocap_pos[self._mocap_id(name)] = value

    def get_mocap_quat(self, name: str) -> np.ndarray:
        """Orientation of mocap body ``name``."""
        return self._data.mocap_quat[self._mocap_id(name)]

    def set_mocap_quat(self, name: str, value: Any) -> None:
        """Sets the orientation of mocap body ``name``."""
        self._data.mocap_quat[self._mocap_id(name)] = value

    def _get(self, array: np.ndarray, addr: Any) -> Any:
        return array[addr] if isinstance(addr, (int, np.integer)) else array[addr[0] : addr[1]]

    def _set(self, array: np.ndarray, addr: Any, name: str, value: Any) -> None:
        if isinstance(addr, (int, np.integer)):
            array[addr] = value
            return
        value = np.array(value)
        if value.shape != (addr[1] - addr[0],):
            raise ValueError(f"Value has incorrect shape {name}: {value}")
        array[addr[0] : addr[1]] = value

    def get_joint_qpos(self, name: str) -> Any:
        """Position of joint ``name`` (a float, or an array for free and ball joints)."""
        return self._get(self._data.qpos, self._model.get_joint_qpos_addr(name))

    def set_joint_qpos(self, name: str, value: Any) -> None:
        """Sets the position of joint ``name``."""
        self._set(self._data.qpos, self._model.get_joint_qpos_addr(name), name, value)

    def get_joint_qvel(self, name: str) -> Any:
        """Velocity of joint ``name``."""
        return self._get(self._data.qvel, self._model.get_joint_qvel_addr(name))

    def set_joint_qvel(self, name: str, value: Any) -> None:
        """Sets the velocity of joint ``name``."""
        self._set(self._data.qvel, self._model.get_joint_qvel_addr(name), name, value)


class MjRenderContextOffscreen:
    """robosuite's offscreen render context (``sim._render_context_offscreen``) for what
    users set on it: ``cam``, a ``mujoco.MjvCamera`` that starts on fixed camera 0 and that
    :meth:`MjSim.render` updates as robosuite's does (a camera name makes it that fixed
    camera, ``"free"`` MuJoCo's free camera, whose ``lookat``, ``distance``, ``azimuth``
    and ``elevation`` are then drawn). Frames are drawn by the environment's own renderer."""

    def __init__(self, device_id: int = -1) -> None:
        self.device_id = device_id
        self.cam = mujoco.MjvCamera()
        self.cam.fixedcamid = 0
        self.cam.type = mujoco.mjtCamera.mjCAMERA_FIXED


class MjSim:
    """robosuite's ``MjSim`` for one environment: ``model`` and ``data`` over the
    environment's own memory; ``forward``, ``step``, ``reset`` and ``render`` run in the
    environment."""

    def __init__(self, native: Any) -> None:
        """Wraps the simulator of ``native`` (a ``robosuite_rs._native.RobosuiteEnv``)."""
        self._native = native
        model, data = native.sim_objects()
        self.model = MjModel(model, native.get_xml)
        self.data = MjData(data, self.model)
        self._render_context_offscreen = MjRenderContextOffscreen()

    def reset(self) -> None:
        """``mj_resetData``."""
        self._native.sim_reset()

    def forward(self) -> None:
        """``mj_forward`` (``RuntimeError`` for a MuJoCo error)."""
        self._native.sim_forward()

    def step(self, with_udd: bool = True) -> None:
        """``mj_step``."""
        self._native.sim_step()

    def step1(self) -> None:
        """``mj_step1``."""
        self._native.sim_step1()

    def step2(self) -> None:
        """``mj_step2``."""
        self._native.sim_step2()

    def get_state(self) -> MjSimState:
        """The current ``(time, qpos, qvel)`` (copies)."""
        return MjSimState(time=self.data.time, qpos=np.copy(self.data.qpos), qvel=np.copy(self.data.qvel))

    def set_state(self, value: MjSimState) -> None:
        """Writes a state; call :meth:`forward` afterwards.

        Raises:
            ValueError: for a state of the wrong size or with a non-finite value (nothing
                is written).
        """
        self.set_state_from_flattened(np.concatenate([[value.time], np.ravel(value.qpos), np.ravel(value.qvel)]))

    def set_state_from_flattened(self, value: Any) -> None:
        """Writes a flat ``[time, qpos, qvel]`` state; call :meth:`forward` afterwards.

        Raises:
            ValueError: for a state that is not flat, of the wrong length, or with a
                non-finite value or a position or velocity beyond 1e6 (nothing is written).
        """
        flat = np.asarray(value, dtype=np.float64)
        nq, nv = self.model.nq, self.model.nv
        if flat.ndim != 1 or flat.shape[0] != 1 + nq + nv:
            raise ValueError(
                f"invalid argument `state`: expected a flat array of {1 + nq + nv} values "
                f"[time, qpos, qvel], got shape {flat.shape}"
            )
        if not np.all(np.isfinite(flat)) or np.any(np.abs(flat[1:]) > 1e6):
            flat = np.asarray(self._native.check_flat_state(flat))  # raises, naming the value
        self.data.time = float(flat[0])
        self.data.qpos[:] = flat[1 : 1 + nq]
        self.data.qvel[:] = flat[1 + nq :]

    def render(
        self,
        width: int | None = None,
        height: int | None = None,
        *,
        camera_name: str | None = None,
        depth: bool = False,
        mode: str = "offscreen",
        device_id: int = -1,
        segmentation: bool = False,
    ) -> Any:
        """A frame of ``camera_name`` at ``width × height``, rows bottom first (OpenGL's
        order, as robosuite): uint8 H×W×3, or ``(rgb, depth)`` with ``depth``; with
        ``segmentation`` an int32 H×W×2 image of ``(object type, object id)``.
        ``camera_name="free"`` draws MuJoCo's free camera as set on
        ``sim._render_context_offscreen.cam``. Without ``camera_name``, as robosuite: the
        render context's camera (the previous call's; fixed camera 0 at first).

        Raises:
            ValueError: for an unknown camera, a missing or bad size, a free camera with
                non-finite values or a distance <= 0, or a mode other than ``"offscreen"``.
        """
        if mode != "offscreen":
            raise ValueError(f"only mode='offscreen' is supported, got {mode!r}")
        if width is None or height is None:
            raise ValueError("render needs width and height")
        cam = self._render_context_offscreen.cam
        if camera_name is not None:
            camera_id = self.model.camera_name2id(camera_name)
            free = camera_id == -1
            cam.type = mujoco.mjtCamera.mjCAMERA_FREE if free else mujoco.mjtCamera.mjCAMERA_FIXED
            cam.fixedcamid = camera_id
        if cam.type == mujoco.mjtCamera.mjCAMERA_FREE:
            view = (tuple(float(v) for v in cam.lookat), float(cam.distance), float(cam.azimuth), float(cam.elevation))
            return self._native.render_camera(0, int(width), int(height), bool(depth), bool(segmentation), view)
        if cam.type != mujoco.mjtCamera.mjCAMERA_FIXED or cam.fixedcamid < 0:
            raise ValueError(
                f"render draws fixed cameras ({self.model.camera_names}) or the free camera; the render "
                f"context's camera is of type {cam.type} with id {cam.fixedcamid}"
            )
        return self._native.render_camera(int(cam.fixedcamid), int(width), int(height), bool(depth), bool(segmentation))

    def free(self) -> None:
        """Nothing to free: the environment owns the simulation."""
