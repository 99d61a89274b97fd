"""robosuite's robot model classes (``robosuite.models.robots``): ``Panda(idn=0)`` and the
other robots of this build describe the robot's model on its own as robosuite's do
(robosuite's file prepared with its joint settings, before a task adds a mount and
grippers): prefixed element names, ``init_qpos``, default gripper and base, base offsets,
``get_xml()``. ``env.robots[i].robot_model`` is one of these for the env's robot.

Scenes are composed in Rust, so the MJCF-editing methods of robosuite's models
(``add_gripper``, ``add_base``, ``set_base_xpos``, ``set_joint_attribute``, ...) are not
served; a custom scene is a Rust task (``robosuite_env::tasks::TaskSpec``) or a scene file
passed as ``make(..., model_xml=path)``.
"""

from __future__ import annotations

import json
from collections import OrderedDict
from typing import Any, Callable

import numpy as np

from .. import _native

__all__ = ["RobotModel", "ManipulatorModel", "REGISTERED_ROBOTS", "create_robot"]


def save_xml(text: str, fname: str, pretty: bool = False) -> None:
    """Writes the MJCF ``text`` to ``fname`` (``pretty``: indented), as robosuite's
    ``save_model``."""
    if pretty:
        import xml.dom.minidom

        text = xml.dom.minidom.parseString(text).toprettyxml(indent="  ")
    with open(fname, "w", encoding="utf8") as f:
        f.write(text)


class RobotModel:
    """robosuite's ``RobotModel`` for one robot of this build (see the module docs).

    Raises:
        ValueError: for an ``idn`` that is not a non-negative int.
    """

    #: robosuite's robot name (set on each robot's class).
    robot_name: str = ""

    def __init__(self, idn: int = 0) -> None:
        if isinstance(idn, bool) or not isinstance(idn, (int, np.integer)) or idn < 0:
            raise ValueError(f"idn must be a non-negative int, got {idn!r}")
        d = json.loads(_native.describe_robot(self.robot_name, int(idn)))
        self.name = d["name"]
        self.idn = d["idn"]
        self.naming_prefix: str = d["naming_prefix"]
        self.arm_type: str = d["arm_type"]
        self.arms: list[str] = list(d["arms"])
        self.root_body: str = d["root_body"]
        self.bodies: list[str] = d["bodies"]
        self.joints: list[str] = d["joints"]
        self.actuators: list[str] = d["actuators"]
        self.sites: list[str] = d["sites"]
        self.contact_geoms: list[str] = d["contact_geoms"]
        self.visual_geoms: list[str] = d["visual_geoms"]
        self.top_offset = np.array(d["top_offset"])
        self._horizontal_radius = float(d["horizontal_radius"])
        self._base_offset = np.array(d["base_offset"])
        self._init_qpos = np.array(d["init_qpos"])
        self._default_grippers = dict(zip(self.arms, d["default_grippers"]))
        self._default_base = d["default_base"]
        bins, empty, table_x, table_z = d["base_xpos_offset"]
        self._base_xpos_offset: dict[str, Any] = {
            "bins": np.array(bins),
            "empty": np.array(empty),
            "table": lambda table_length: np.array((table_x - table_length / 2, 0, table_z)),
        }
        self._eef_name = dict(zip(self.arms, d["eef_name"]))
        self._xml: str = d["xml"]

    @property
    def dof(self) -> int:
        """The number of joints."""
        return len(self.joints)

    @property
    def init_qpos(self) -> np.ndarray:
        """The joints' rest positions (radians)."""
        return self._init_qpos.copy()

    @property
    def default_gripper(self) -> dict[str, str]:
        """The default gripper per arm (robosuite's class names)."""
        return dict(self._default_grippers)

    @property
    def default_base(self) -> str:
        """The default base (mount) class name."""
        return self._default_base

    @property
    def base_xpos_offset(self) -> dict[str, Any]:
        """Where the robot stands per arena: ``"bins"``, ``"empty"`` (arrays) and
        ``"table"`` (a function of the table's length), as robosuite's."""
        return dict(self._base_xpos_offset)

    @property
    def horizontal_radius(self) -> float:
        """The robot's horizontal radius (metres)."""
        return self._horizontal_radius

    @property
    def bottom_offset(self) -> np.ndarray:
        """From the root body to the robot's bottom, without a mount."""
        return self._base_offset.copy()

    @property
    def eef_name(self) -> dict[str, str]:
        """The body each arm's gripper attaches to, per arm (prefixed)."""
        return dict(self._eef_name)

    def get_xml(self) -> str:
        """The robot's prepared MJCF."""
        return self._xml

    def save_model(self, fname: str, pretty: bool = False) -> None:
        """Writes :meth:`get_xml` to ``fname`` (``pretty``: indented)."""
        save_xml(self._xml, fname, pretty)

    def __repr__(self) -> str:
        return f"<{type(self).__name__} idn={self.idn} prefix={self.naming_prefix!r}>"


class ManipulatorModel(RobotModel):
    """robosuite's ``ManipulatorModel``: a robot model with arms (every robot here)."""


def _robot_class(name: str) -> type[ManipulatorModel]:
    cls = type(name, (ManipulatorModel,), {"robot_name": name, "__doc__": f"robosuite's ``{name}`` robot model."})
    cls.__module__ = __name__
    return cls


#: robosuite's robot model classes by name (the robots this build provides).
REGISTERED_ROBOTS: "OrderedDict[str, type[ManipulatorModel]]" = OrderedDict(
    (name, _robot_class(name)) for name in _native.robot_names()
)
globals().update(REGISTERED_ROBOTS)
__all__ += list(REGISTERED_ROBOTS)


def create_robot(robot_name: str, *args: Any, **kwargs: Any) -> ManipulatorModel:
    """robosuite's ``create_robot``: the model of ``robot_name``.

    Raises:
        Exception: for an unknown robot, as robosuite (naming the robots this build has).
    """
    if robot_name not in REGISTERED_ROBOTS:
        raise Exception(
            f"Robot {robot_name} not found. Make sure it is a registered robot among: {', '.join(REGISTERED_ROBOTS)}"
        )
    factory: Callable[..., ManipulatorModel] = REGISTERED_ROBOTS[robot_name]
    return factory(*args, **kwargs)
