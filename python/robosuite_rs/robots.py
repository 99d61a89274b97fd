"""robosuite's robot objects (``env.robots``): read-only views of the Rust env's robots
with robosuite's attribute names (``name``, ``dof``, ``action_dim``, ``action_limits``,
``robot_model.naming_prefix``, ``gripper``, ``part_controllers``, ``composite_controller``,
``init_qpos``, ...)."""

from __future__ import annotations

import weakref
from collections import OrderedDict
from typing import Any

import numpy as np

from . import _native
from .models.robots import RobotModel, create_robot

__all__ = ["Robot", "RobotModel", "GripperModel", "PartController", "CompositeController", "ROBOT_CLASS_MAPPING"]

#: robosuite's robot classes by robot name (the robots this build provides).
ROBOT_CLASS_MAPPING: dict[str, str] = dict(sorted(_native.robot_classes()))

# robosuite's part controller class names by type.
_CONTROLLER_CLASSES = {
    "OSC_POSE": "OperationalSpaceController",
    "OSC_POSITION": "OperationalSpaceController",
    "IK_POSE": "InverseKinematicsController",
    "JOINT_POSITION": "JointPositionController",
    "JOINT_VELOCITY": "JointVelocityController",
    "JOINT_TORQUE": "JointTorqueController",
}


def _names(model: Any, kind: str, ids: list[int]) -> list[str]:
    return [getattr(model, f"{kind}_id2name")(i) for i in ids]


class GripperModel:
    """robosuite's ``robot.gripper[arm]``: a gripper's names in the compiled scene, with
    ``sites`` (its sites, which ``env.visualize``'s ``"grippers"`` setting shows) and
    ``important_sites`` (``grip_site``, ``grip_cylinder``, ``ee``, ``ee_x``, ``ee_y``,
    ``ee_z``)."""

    def __init__(
        self,
        name: str,
        prefix: str,
        joints: list[str],
        actuators: list[str],
        dof: int,
        sites: list[str] | None = None,
        site_prefix: str = "",
    ) -> None:
        self.name = name
        self.naming_prefix = prefix
        self.joints = joints
        self.actuators = actuators
        self.dof = dof
        self.sites: list[str] = list(sites or [])
        self.important_sites: dict[str, str] = {
            key: site_prefix + suffix
            for key, suffix in [
                ("grip_site", "grip_site"),
                ("grip_cylinder", "grip_site_cylinder"),
                ("ee", "ee"),
                ("ee_x", "ee_x"),
                ("ee_y", "ee_y"),
                ("ee_z", "ee_z"),
            ]
        }

    def __repr__(self) -> str:
        return f"<GripperModel {self.name} prefix={self.naming_prefix!r}>"


class PartController:
    """One part controller (``composite_controller.part_controllers[arm]``) with robosuite's
    fields: ``name`` (its type, e.g. ``"OSC_POSE"``), ``ref_name`` (the end-effector site),
    ``part_name``, ``control_dim``, ``input_type``, ``control_delta``, and its config."""

    def __init__(self, kind: str, part_name: str, ref_name: str, control_dim: int, config: dict[str, Any]) -> None:
        self.name = kind
        self.part_name = part_name
        self.ref_name = ref_name
        self.control_dim = control_dim
        self.config = config
        self.input_type = config.get("input_type", "delta")
        self.control_delta = self.input_type == "delta"
        self.input_ref_frame = config.get("input_ref_frame", "base")

    def __repr__(self) -> str:
        return f"<{_CONTROLLER_CLASSES.get(self.name, self.name)} {self.part_name} ref={self.ref_name}>"


class CompositeController:
    """robosuite's ``robot.composite_controller``: its parts in robosuite's action order
    (the body parts in the config's order, then each arm's gripper; ``HYBRID_MOBILE_BASE``
    adds the base mode as the last entry)."""

    def __init__(
        self,
        name: str,
        part_controllers: "OrderedDict[str, Any]",
        action_split: "OrderedDict[str, tuple[int, int]]",
        limits: tuple[np.ndarray, np.ndarray],
    ) -> None:
        self.name = name
        self.part_controllers = part_controllers
        self._action_split_indexes = action_split
        self._limits = limits

    @property
    def action_limits(self) -> tuple[np.ndarray, np.ndarray]:
        """``(low, high)`` of the robot's action."""
        return self._limits[0].copy(), self._limits[1].copy()


class Robot:
    """A robot of the env (robosuite's ``env.robots[i]``)."""

    @property
    def _env(self) -> Any:
        env = self._env_ref()
        if env is None:
            raise ReferenceError(f"robot {self.name!r}: its env was freed (keep a reference to the env)")
        return env

    def __init__(self, env: Any, info: dict[str, Any], model: Any, controller_config: dict[str, Any] | None) -> None:
        # The env holds its robots; a weak reference back lets the env be freed as soon as
        # its last user reference goes (no reference cycle for the GC to find).
        self._env_ref = weakref.ref(env)
        index = info["index"]
        self.name = info["name"]
        self.robot_type = self.name
        self.idn = index
        self.init_qpos = np.array(info["init_qpos"])
        self._joint_qpos = list(info["joint_qpos"])
        self._joint_dofs = list(info["joint_dofs"])
        self._action_low = np.array(info["action_low"])
        self._action_high = np.array(info["action_high"])
        jnt_qposadr = list(model.jnt_qposadr)
        joints = [model.joint_id2name(jnt_qposadr.index(a)) for a in self._joint_qpos]
        arm_actuators = [i for a in info["arms"] for i in a["actuators"]]
        #: robosuite's ``robot_model`` (a :mod:`robosuite_rs.models.robots` model), with the
        #: env's compiled names.
        self.robot_model: RobotModel = create_robot(self.name, idn=index)
        self.robot_model.joints = joints
        self.robot_model.actuators = _names(model, "actuator", arm_actuators)
        #: robosuite's joint bookkeeping: the robot's (arm) joint names, ids, qpos and dof
        #: addresses.
        self.robot_joints = list(joints)
        self._ref_joint_indexes = [model.joint_name2id(j) for j in joints]
        self._ref_joint_pos_indexes = list(self._joint_qpos)
        self._ref_joint_vel_indexes = list(self._joint_dofs)
        self.arms = [a["side"] for a in info["arms"]]
        parts_cfg = (controller_config or {}).get("body_parts", {})
        self.gripper: dict[str, GripperModel | None] = {}
        #: robosuite's ``gripper_joints``: per arm with a gripper, its joint names.
        self.gripper_joints: dict[str, list[str]] = {}
        part_controllers: OrderedDict[str, Any] = OrderedDict()
        split: OrderedDict[str, tuple[int, int]] = OrderedDict()
        #: robosuite's robot class (``FixedBaseRobot``, ``WheeledRobot``, ``LeggedRobot``).
        self.robot_class = info.get("robot_class", "FixedBaseRobot")
        layout = {name: (start, end) for name, start, end in info.get("layout", [])}
        for a in info["arms"]:
            side = a["side"]
            cfg = parts_cfg.get(side, {}) if isinstance(parts_cfg, dict) else {}
            ref = model.site_id2name(a["eef_site"])
            part_controllers[side] = PartController(a["controller"], side, ref, a["controller_dim"], dict(cfg))
        #: The body parts other than arms (torso, head, base, legs) and their joints.
        self.body_parts: dict[str, list[str]] = {}
        for b in info.get("body_parts", []):
            cfg = parts_cfg.get(b["name"], {}) if isinstance(parts_cfg, dict) else {}
            part_controllers[b["name"]] = PartController(b["controller"], b["name"], "", b["controller_dim"], dict(cfg))
            self.body_parts[b["name"]] = list(b["joints"])
        for a in info["arms"]:
            side = a["side"]
            if a["gripper"] is None:
                self.gripper[side] = None
                continue
            ref = model.site_id2name(a["eef_site"])
            g_joints = [model.joint_id2name(jnt_qposadr.index(q)) for q in a["gripper_qpos"]]
            g_acts = _names(model, "actuator", a["gripper_actuators"])
            # robosuite names a gripper's elements `gripper{robot}_{arm}_...`.
            site_prefix = f"gripper{index}_{side}_"
            prefix = site_prefix
            sites = [n for n in model.site_names if isinstance(n, str) and n.startswith(site_prefix)]
            self.gripper[side] = GripperModel(
                a["gripper"], prefix, g_joints, g_acts, a["gripper_dim"], sites, site_prefix
            )
            self.gripper_joints[side] = list(g_joints)
            part_controllers[f"{side}_gripper"] = PartController("GRIP", f"{side}_gripper", ref, a["gripper_dim"], {})
        # robosuite's `_action_split_indexes`, in action order.
        for name, (start, end) in sorted(layout.items(), key=lambda kv: kv[1]):
            split[name] = (start, end)
        part_controllers = OrderedDict((k, part_controllers[k]) for k in split if k in part_controllers)
        if info.get("action_split") is not None:
            # WHOLE_BODY_IK: the end-effector poses, then the parts outside the IK.
            split = OrderedDict((name, (start, end)) for name, start, end in info["action_split"])
        self.part_controllers = part_controllers
        self.composite_controller = CompositeController(
            (controller_config or {}).get("type", "BASIC"),
            part_controllers,
            split,
            (self._action_low, self._action_high),
        )

    @property
    def is_mobile(self) -> bool:
        """Whether the robot has a mobile base (robosuite's ``is_mobile``)."""
        return self.robot_class != "FixedBaseRobot"

    @property
    def dof(self) -> int:
        """robosuite's ``dof``: the number of the robot model's own joints (``robot{i}_``;
        not its gripper's or its base's)."""
        prefix = f"robot{self.idn}_"
        return sum(1 for j in self.robot_model.joints if j.startswith(prefix))

    @property
    def _joint_positions(self) -> np.ndarray:
        """The robot's joint positions (robosuite's ``_joint_positions``)."""
        return self._env.sim.data.qpos[self._ref_joint_pos_indexes].copy()

    @property
    def _joint_velocities(self) -> np.ndarray:
        """The robot's joint velocities (robosuite's ``_joint_velocities``)."""
        return self._env.sim.data.qvel[self._ref_joint_vel_indexes].copy()

    @property
    def action_dim(self) -> int:
        """The robot's action dimension."""
        return len(self._action_low)

    @property
    def action_limits(self) -> tuple[np.ndarray, np.ndarray]:
        """``(low, high)`` of the robot's action."""
        return self.composite_controller.action_limits

    def create_action_vector(self, action_dict: dict[str, Any]) -> np.ndarray:
        """robosuite's ``create_action_vector``: the flat action from per-part values
        (``{"right": ..., "right_gripper": ...}``); parts not given are zero.

        Raises:
            ValueError: for an unknown part or a value of the wrong length.
        """
        out = np.zeros(self.action_dim)
        split = self.composite_controller._action_split_indexes
        hybrid = self.composite_controller.name == "HYBRID_MOBILE_BASE"
        if hybrid:
            # robosuite's HYBRID_MOBILE_BASE: the last entry is the base mode (-1: arm mode).
            out[-1] = float(action_dict.get("base_mode", -1.0))
        for part, value in action_dict.items():
            if hybrid and part == "base_mode":
                continue
            if part not in split:
                raise ValueError(f"unknown part {part!r}; parts: {list(split)}")
            start, end = split[part]
            value = np.asarray(value, dtype=np.float64).ravel()
            if value.shape != (end - start,):
                raise ValueError(f"part {part!r} takes {end - start} values, got {value.shape[0]}")
            out[start:end] = value
        return out

    def print_action_info(self) -> None:
        """Prints the action layout (robosuite's ``print_action_info``)."""
        for part, (start, end) in self.composite_controller._action_split_indexes.items():
            print(f"Action Dim for {part}: {start}:{end} ({end - start} dims)")

    def print_action_info_dict(self) -> None:
        """Prints the action layout as a dict."""
        print({p: (s, e) for p, (s, e) in self.composite_controller._action_split_indexes.items()})

    def set_robot_joint_positions(self, jpos: Any) -> None:
        """robosuite's ``set_robot_joint_positions``: writes the arm joints' positions and
        runs a forward pass.

        Raises:
            ValueError: for a wrong number of positions or a non-finite value.
        """
        jpos = np.asarray(jpos, dtype=np.float64).ravel()
        if jpos.shape != (len(self._joint_qpos),):
            raise ValueError(f"expected {len(self._joint_qpos)} joint positions, got {jpos.shape[0]}")
        if not np.all(np.isfinite(jpos)):
            raise ValueError("joint positions must be finite")
        self._env.sim.data.qpos[self._joint_qpos] = jpos
        self._env.sim.forward()

    def __repr__(self) -> str:
        return f"<Robot {self.name} idn={self.idn} action_dim={self.action_dim}>"
