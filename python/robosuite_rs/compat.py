"""``robosuite_rs.install_as_robosuite()``: serve ``import robosuite`` (and the submodules
robosuite's users import) from this package, so that code written for robosuite 1.5.2 —
robomimic's ``EnvRobosuite``, research scripts — runs unchanged (the pattern of
``pymysql.install_as_MySQLdb()``).

Afterwards ``robosuite.__version__`` is ``"1.5.2"`` (the API served);
``robosuite_rs.__version__`` stays this package's own.
"""

from __future__ import annotations

import sys
import types
from typing import Any

def served_macro(name: str, default: Any) -> Any:
    """``robosuite.macros.<name>`` as a user set it after :func:`install_as_robosuite`,
    else ``default`` (robosuite's value)."""
    macros = sys.modules.get("robosuite.macros")
    if macros is None or not getattr(sys.modules.get("robosuite"), "__robosuite_rs__", False):
        return default
    return getattr(macros, name, default)


#: The robosuite release whose API is served.
ROBOSUITE_API_VERSION = "1.5.2"

#: robosuite's composite controllers (``robosuite.controllers.ALL_COMPOSITE_CONTROLLERS``).
ALL_COMPOSITE_CONTROLLERS: tuple[str, ...] = ("BASIC", "HYBRID_MOBILE_BASE", "WHOLE_BODY_IK", "WHOLE_BODY_MINK_IK")

#: robosuite's grippers this build provides (``robosuite.ALL_GRIPPERS``).
ALL_GRIPPERS: tuple[str, ...] = (
    "PandaGripper",
    "RethinkGripper",
    "Robotiq85Gripper",
    "Robotiq140Gripper",
    "JacoThreeFingerGripper",
    "JacoThreeFingerDexterousGripper",
    "RobotiqThreeFingerGripper",
    "RobotiqThreeFingerDexterousGripper",
    "XArm7Gripper",
    "WipingGripper",
    "BDGripper",
)


def _module(name: str, doc: str, attrs: dict[str, Any], package: bool = False) -> types.ModuleType:
    module = types.ModuleType(name, doc)
    module.__dict__.update(attrs)
    if package:
        module.__path__ = []  # type: ignore[attr-defined]
    return module


def install_as_robosuite() -> types.ModuleType:
    """Registers this package as ``robosuite`` in ``sys.modules``: ``import robosuite``,
    ``robosuite.make``, ``robosuite.utils.transform_utils``, ``robosuite.utils.camera_utils``,
    ``robosuite.utils.binding_utils``, ``robosuite.utils.mjmod``, ``robosuite.wrappers``
    (``GymWrapper``, ``DataCollectionWrapper``, ``DemoSamplerWrapper``,
    ``VisualizationWrapper``, ``DomainRandomizationWrapper``),
    ``robosuite.controllers``, ``robosuite.robots``, ``robosuite.models.robots``,
    ``robosuite.macros`` then give ours.
    Returns the ``robosuite`` module. Calling it again changes nothing.

    Raises:
        RuntimeError: when the real robosuite is imported already in this process.
    """
    existing = sys.modules.get("robosuite")
    if existing is not None:
        if getattr(existing, "__robosuite_rs__", False):
            return existing
        raise RuntimeError("robosuite is imported already; call install_as_robosuite() before importing it")

    import robosuite_rs as rs
    from . import binding_utils, models, robots, wrappers
    from .utils import camera_utils, placement_samplers, transform_utils

    macros = _module(
        "robosuite.macros",
        "robosuite's macros (the values robosuite-rs uses).",
        {
            "SIMULATION_TIMESTEP": 0.002,
            "USING_INSTANCE_RANDOMIZATION": False,
            "ENABLE_NUMBA": False,
            "CACHE_NUMBA": False,
            "IMAGE_CONVENTION": "opengl",
            "CONCATENATE_IMAGES": False,
            "MUJOCO_GPU_RENDERING": True,
            "SPACEMOUSE_VENDOR_ID": 9583,
            "SPACEMOUSE_PRODUCT_ID": 50734,
            "CONSOLE_LOGGING_LEVEL": "WARN",
            "FILE_LOGGING_LEVEL": None,
        },
    )
    controllers = _module(
        "robosuite.controllers",
        "robosuite's controller configs.",
        {
            "load_composite_controller_config": rs.load_composite_controller_config,
            "load_part_controller_config": rs.load_part_controller_config,
            "ALL_PART_CONTROLLERS": rs.ALL_PART_CONTROLLERS,
            "ALL_COMPOSITE_CONTROLLERS": ALL_COMPOSITE_CONTROLLERS,
        },
        package=True,
    )
    robots_mod = _module(
        "robosuite.robots",
        "robosuite's robot classes.",
        {"ROBOT_CLASS_MAPPING": robots.ROBOT_CLASS_MAPPING, "Robot": robots.Robot},
        package=True,
    )
    utils = _module(
        "robosuite.utils",
        "robosuite's utilities.",
        {
            "transform_utils": transform_utils,
            "camera_utils": camera_utils,
            "binding_utils": binding_utils,
            "placement_samplers": placement_samplers,
        },
        package=True,
    )
    wrappers_mod = _module(
        "robosuite.wrappers",
        "robosuite's wrappers.",
        {
            "GymWrapper": wrappers.GymWrapper,
            "Wrapper": wrappers.Wrapper,
            "DataCollectionWrapper": wrappers.DataCollectionWrapper,
            "DemoSamplerWrapper": wrappers.DemoSamplerWrapper,
            "VisualizationWrapper": wrappers.VisualizationWrapper,
            "DomainRandomizationWrapper": wrappers.DomainRandomizationWrapper,
        },
        package=True,
    )
    environments = _module(
        "robosuite.environments",
        "robosuite's environments.",
        {"ALL_ENVIRONMENTS": rs.ALL_ENVIRONMENTS},
        package=True,
    )
    models_mod = _module(
        "robosuite.models",
        "robosuite's models (the robot model classes).",
        {"robots": models.robots},
        package=True,
    )
    robosuite = _module(
        "robosuite",
        "robosuite 1.5.2's API served by robosuite-rs (robosuite_rs.install_as_robosuite()).",
        {
            "__version__": ROBOSUITE_API_VERSION,
            "__robosuite_rs__": True,
            "make": rs.make,
            "ALL_ENVIRONMENTS": rs.ALL_ENVIRONMENTS,
            "ALL_ROBOTS": list(robots.ROBOT_CLASS_MAPPING),
            "ALL_GRIPPERS": list(ALL_GRIPPERS),
            "ALL_PART_CONTROLLERS": rs.ALL_PART_CONTROLLERS,
            "ALL_COMPOSITE_CONTROLLERS": ALL_COMPOSITE_CONTROLLERS,
            "load_composite_controller_config": rs.load_composite_controller_config,
            "load_part_controller_config": rs.load_part_controller_config,
            "macros": macros,
            "controllers": controllers,
            "robots": robots_mod,
            "utils": utils,
            "wrappers": wrappers_mod,
            "environments": environments,
            "models": models_mod,
        },
        package=True,
    )
    for module in (robosuite, macros, controllers, robots_mod, utils, wrappers_mod, environments, models_mod):
        sys.modules[module.__name__] = module
    sys.modules["robosuite.models.robots"] = models.robots
    sys.modules["robosuite.utils.transform_utils"] = transform_utils
    sys.modules["robosuite.utils.placement_samplers"] = placement_samplers
    sys.modules["robosuite.utils.camera_utils"] = camera_utils
    sys.modules["robosuite.utils.binding_utils"] = binding_utils
    from .utils import mjmod

    utils.mjmod = mjmod  # type: ignore[attr-defined]
    sys.modules["robosuite.utils.mjmod"] = mjmod
    from . import observables  # robosuite.utils.observables: Observable, sensor, corrupters, delayers

    utils.observables = observables  # type: ignore[attr-defined]
    sys.modules["robosuite.utils.observables"] = observables
    return robosuite
