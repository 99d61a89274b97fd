"""robosuite's placement samplers (``robosuite.utils.placement_samplers``) as ``make``'s
``placement_initializer``: the sampler's settings travel to the Rust task, which places
its own objects with them from the env's RNG (so the same seed gives the same placement).

    from robosuite_rs.utils.placement_samplers import UniformRandomSampler
    sampler = UniformRandomSampler(name="ObjectSampler", x_range=[-0.1, 0.1], y_range=[-0.1, 0.1],
                                   rotation=None, reference_pos=(0, 0, 0.8), z_offset=0.01)
    env = robosuite_rs.make("Lift", placement_initializer=sampler)

The tasks that take one (robosuite's: Lift, Stack, Door, NutAssembly, TwoArmLift,
TwoArmHandover) give it all their objects, as robosuite's ``add_objects`` does.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["UniformRandomSampler"]


def _pair(name: str, value: Any) -> list[float]:
    if value is None:
        raise ValueError(f"UniformRandomSampler: {name} is required (a [low, high] pair)")
    pair = [float(v) for v in np.asarray(value, dtype=float).ravel()]
    if len(pair) != 2 or not all(math.isfinite(v) for v in pair):
        raise ValueError(f"UniformRandomSampler: {name} must be two finite numbers, got {value!r}")
    return pair


class UniformRandomSampler:
    """robosuite's ``UniformRandomSampler``: each object at a uniform x in ``x_range`` and y
    in ``y_range`` around ``reference_pos``, its bottom ``z_offset`` above it, rotated about
    ``rotation_axis`` by ``rotation`` (``None``: uniform in [0, 2π); an angle; or a
    ``[low, high]`` range), kept inside the ranges by its radius
    (``ensure_object_boundary_in_range``) and clear of the others
    (``ensure_valid_placement``). Arguments as robosuite's; ``mujoco_objects`` and ``rng``
    must be left out (the task adds its objects, the env's RNG draws).

    Raises:
        ValueError: for a missing or non-finite range, an unknown axis, or a bad rotation.
        TypeError: for ``mujoco_objects`` or ``rng``.
    """

    def __init__(
        self,
        name: str,
        mujoco_objects: Any = None,
        x_range: Any = None,
        y_range: Any = None,
        rotation: Any = None,
        rotation_axis: str = "z",
        ensure_object_boundary_in_range: bool = True,
        ensure_valid_placement: bool = True,
        reference_pos: Any = (0, 0, 0),
        z_offset: float = 0.0,
        rng: Any = None,
    ) -> None:
        if mujoco_objects is not None:
            raise TypeError("UniformRandomSampler: leave mujoco_objects out; the task adds its own objects")
        if rng is not None:
            raise TypeError("UniformRandomSampler: leave rng out; the env's RNG draws (seed the env instead)")
        if rotation_axis not in ("x", "y", "z"):
            raise ValueError(f"UniformRandomSampler: rotation_axis must be 'x', 'y' or 'z', got {rotation_axis!r}")
        if rotation is not None and not isinstance(rotation, (int, float, np.number)):
            rotation = _pair("rotation", rotation)
        elif rotation is not None:
            rotation = float(rotation)
            if not math.isfinite(rotation):
                raise ValueError(f"UniformRandomSampler: rotation must be finite, got {rotation}")
        reference = [float(v) for v in np.asarray(reference_pos, dtype=float).ravel()]
        if len(reference) != 3 or not all(math.isfinite(v) for v in reference):
            raise ValueError(f"UniformRandomSampler: reference_pos must be three finite numbers, got {reference_pos!r}")
        if not math.isfinite(float(z_offset)):
            raise ValueError(f"UniformRandomSampler: z_offset must be finite, got {z_offset}")
        self.name = name
        self.x_range = _pair("x_range", x_range)
        self.y_range = _pair("y_range", y_range)
        self.rotation = rotation
        self.rotation_axis = rotation_axis
        self.ensure_object_boundary_in_range = bool(ensure_object_boundary_in_range)
        self.ensure_valid_placement = bool(ensure_valid_placement)
        self.reference_pos = reference
        self.z_offset = float(z_offset)

    def _task_option(self) -> dict[str, Any]:
        """The sampler as the Rust task's ``placement_initializer`` option."""
        return {
            "x_range": self.x_range,
            "y_range": self.y_range,
            "rotation": self.rotation,
            "rotation_axis": self.rotation_axis,
            "ensure_object_boundary_in_range": self.ensure_object_boundary_in_range,
            "ensure_valid_placement": self.ensure_valid_placement,
            "reference_pos": self.reference_pos,
            "z_offset": self.z_offset,
        }

    def __repr__(self) -> str:
        return f"UniformRandomSampler(name={self.name!r}, x_range={self.x_range}, y_range={self.y_range})"
