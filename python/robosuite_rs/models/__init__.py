"""robosuite's models (``robosuite.models``): the robot model classes
(:mod:`robosuite_rs.models.robots`). Scenes are composed by the Rust core from robosuite's
own model files."""

from . import robots

__all__ = ["robots"]
