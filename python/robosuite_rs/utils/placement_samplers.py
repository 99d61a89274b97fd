"""robosuite's placement samplers (``robosuite.utils.placement_samplers``).

As ``make``'s ``placement_initializer``, a :class:`UniformRandomSampler`'s settings travel
to the Rust task, which places its own objects with them from the env's RNG (so the same
seed gives the same placement)::

    from robosuite_rs.utils.placement_samplers import UniformRandomSampler
    sampler = UniformRandomSampler(name="ObjectSampler", x_range=[-0.1, 0.1], y_range=[-0.1, 0.1],
                                   rotation=None, reference_pos=(0, 0, 0.8), z_offset=0.01)
    env = robosuite_rs.make("Lift", placement_initializer=sampler)

The tasks that take one (robosuite's: Lift, Stack, Door, NutAssembly, TwoArmLift,
TwoArmHandover) give it all their objects, as robosuite's ``add_objects`` does; a
:class:`SequentialCompositeSampler` is refused there as robosuite refuses it (its
``add_objects`` raises).

In Python, the samplers also sample as robosuite's do, over objects such as
``env.model.mujoco_objects`` (``sample(fixtures, reference, on_top)`` returns
``{name: (pos, quat_wxyz, obj)}``, drawn from the sampler's ``rng``), for placing objects
by hand with ``env.sim.data.set_joint_qpos``.
"""

from __future__ import annotations

import collections
import math
from copy import copy
from typing import Any

import numpy as np

__all__ = ["ObjectPositionSampler", "UniformRandomSampler", "SequentialCompositeSampler", "RandomizationError"]


class RandomizationError(Exception):
    """robosuite's ``RandomizationError``: a sampler found no valid placement."""


_OBJECT_ATTRS = ("name", "horizontal_radius", "bottom_offset", "top_offset")


def _objects(mujoco_objects: Any) -> list[Any]:
    """An object or a list of them as a list.

    Raises:
        TypeError: for anything that is not an object robosuite's samplers can place.
    """
    if mujoco_objects is None:
        return []
    if hasattr(mujoco_objects, "horizontal_radius"):
        return [mujoco_objects]
    items = [mujoco_objects] if isinstance(mujoco_objects, str) else list(mujoco_objects)
    for obj in items:
        if not all(hasattr(obj, attr) for attr in _OBJECT_ATTRS):
            raise TypeError(
                "mujoco_objects: expected objects with name, horizontal_radius, bottom_offset and "
                f"top_offset (such as env.model.mujoco_objects' items), got {obj!r}"
            )
    return items


class ObjectPositionSampler:
    """robosuite's ``ObjectPositionSampler``: a named sampler over ``mujoco_objects``
    (objects with robosuite's ``name``, ``horizontal_radius``, ``bottom_offset`` and
    ``top_offset``, such as ``env.model.mujoco_objects``' items)."""

    def __init__(
        self,
        name: str,
        mujoco_objects: Any = None,
        ensure_object_boundary_in_range: bool = True,
        ensure_valid_placement: bool = True,
        reference_pos: Any = (0, 0, 0),
        z_offset: float = 0.0,
        rng: Any = None,
    ) -> None:
        self.name = name
        self.mujoco_objects: list[Any] = _objects(mujoco_objects)
        self.ensure_object_boundary_in_range = bool(ensure_object_boundary_in_range)
        self.ensure_valid_placement = bool(ensure_valid_placement)
        self.reference_pos = reference_pos
        self.z_offset = z_offset
        self.rng = np.random.default_rng() if rng is None else rng

    def add_objects(self, mujoco_objects: Any) -> None:
        """Adds objects to sample.

        Raises:
            AssertionError: for an object already in the sampler (as robosuite).
        """
        for obj in _objects(mujoco_objects):
            assert obj not in self.mujoco_objects, f"Object '{obj.name}' already in sampler!"
            self.mujoco_objects.append(obj)

    def reset(self) -> None:
        """Forgets the objects (robosuite's ``reset``)."""
        self.mujoco_objects = []

    def sample(self, fixtures: Any = None, reference: Any = None, on_top: bool = True) -> dict[str, Any]:
        raise NotImplementedError


def _pair(name: str, value: Any) -> list[float]:
    if value is None:
        raise ValueError(f"UniformRandomSampler: {name} is required (a [low, high] pair)")
    pair = [float(v) for v in np.asarray(value, dtype=float).ravel()]
    if len(pair) != 2 or not all(math.isfinite(v) for v in pair):
        raise ValueError(f"UniformRandomSampler: {name} must be two finite numbers, got {value!r}")
    return pair


class UniformRandomSampler(ObjectPositionSampler):
    """robosuite's ``UniformRandomSampler``: each object at a uniform x in ``x_range`` and y
    in ``y_range`` around ``reference_pos``, its bottom ``z_offset`` above it, rotated about
    ``rotation_axis`` by ``rotation`` (``None``: uniform in [0, 2π); an angle; or a
    ``[low, high]`` range), kept inside the ranges by its radius
    (``ensure_object_boundary_in_range``) and clear of the others
    (``ensure_valid_placement``). Arguments as robosuite's. As ``make``'s
    ``placement_initializer`` it must hold no objects (the task adds its own) and the env's
    RNG draws instead of ``rng``.

    Raises:
        ValueError: for a missing or non-finite range, an unknown axis, or a bad rotation.
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
        super().__init__(name, mujoco_objects, ensure_object_boundary_in_range, ensure_valid_placement, reference, float(z_offset), rng)
        self.x_range = _pair("x_range", x_range)
        self.y_range = _pair("y_range", y_range)
        self.rotation = rotation
        self.rotation_axis = rotation_axis

    def _sample_in(self, bounds: list[float], radius: float) -> float:
        """A uniform draw in ``bounds``, shrunk by ``radius`` at each end when the object's
        boundary must stay in range (robosuite's ``_sample_x`` / ``_sample_y``)."""
        low, high = bounds
        if self.ensure_object_boundary_in_range:
            low, high = low + radius, high - radius
        return float(self.rng.uniform(high=high, low=low))

    def _sample_x(self, radius: float) -> float:
        return self._sample_in(self.x_range, radius)

    def _sample_y(self, radius: float) -> float:
        return self._sample_in(self.y_range, radius)

    def _sample_quat(self) -> np.ndarray:
        if self.rotation is None:
            angle = self.rng.uniform(high=2 * np.pi, low=0)
        elif isinstance(self.rotation, list):
            angle = self.rng.uniform(high=max(self.rotation), low=min(self.rotation))
        else:
            angle = self.rotation
        axis = "xyz".index(self.rotation_axis)
        quat = np.array([np.cos(angle / 2), 0.0, 0.0, 0.0])
        quat[1 + axis] = np.sin(angle / 2)
        return quat

    def sample(self, fixtures: Any = None, reference: Any = None, on_top: bool = True) -> dict[str, Any]:
        """robosuite's ``UniformRandomSampler.sample``: a placement for each of this
        sampler's objects, clear of ``fixtures`` (``{name: (pos, quat, obj)}``) and of each
        other, relative to ``reference`` (an object name in ``fixtures``, an ``(x, y, z)``,
        or ``None``: ``reference_pos``), resting on top of it when ``on_top``.

        Returns:
            ``fixtures`` and the new placements, ``{name: (pos, quat_wxyz, obj)}``.

        Raises:
            RandomizationError: when an object finds no valid placement in 5000 tries.
            AssertionError: for an unknown reference or an object placed already (as robosuite).
        """
        placed = {} if fixtures is None else copy(fixtures)
        if reference is None:
            base = np.array(self.reference_pos, dtype=float)
        elif isinstance(reference, str):
            assert reference in placed, f"Invalid reference received. Current options are: {placed.keys()}, requested: {reference}"
            ref_pos, _, ref_obj = placed[reference]
            base = np.array(ref_pos, dtype=float)
            if on_top:
                base += np.array((0, 0, ref_obj.top_offset[-1]))
        else:
            base = np.array(reference, dtype=float)
            assert base.shape[0] == 3, f"Invalid reference received. Should be (x,y,z) 3-tuple, but got: {base}"
        for obj in self.mujoco_objects:
            assert obj.name not in placed, f"Object '{obj.name}' has already been sampled!"
            radius, bottom = obj.horizontal_radius, obj.bottom_offset
            for _ in range(5000):
                x = self._sample_x(radius) + base[0]
                y = self._sample_y(radius) + base[1]
                z = self.z_offset + base[2] - (bottom[-1] if on_top else 0.0)
                valid = not self.ensure_valid_placement or all(
                    not (
                        np.linalg.norm((x - ox, y - oy)) <= other.horizontal_radius + radius
                        and z - oz <= other.top_offset[-1] - bottom[-1]
                    )
                    for (ox, oy, oz), _, other in placed.values()
                )
                if valid:
                    quat = self._sample_quat()
                    if hasattr(obj, "init_quat"):
                        from .transform_utils import quat_multiply

                        quat = quat_multiply(quat, obj.init_quat)
                    placed[obj.name] = ((x, y, z), quat, obj)
                    break
            else:
                raise RandomizationError("Cannot place all objects ):")
        return placed

    def _task_option(self) -> dict[str, Any]:
        """The sampler as the Rust task's ``placement_initializer`` option.

        Raises:
            TypeError: when the sampler holds objects (the task adds its own).
        """
        if self.mujoco_objects:
            raise TypeError(
                "placement_initializer: leave mujoco_objects out; the task adds its own objects "
                "(robosuite asserts the same when they are the task's)"
            )
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


class SequentialCompositeSampler(ObjectPositionSampler):
    """robosuite's ``SequentialCompositeSampler``: samplers run in the order appended, each
    clear of what the earlier ones placed (and able to place on top of it with
    ``sample_args={"reference": name}``)."""

    def __init__(self, name: str) -> None:
        self.samplers: collections.OrderedDict[str, ObjectPositionSampler] = collections.OrderedDict()
        self.sample_args: collections.OrderedDict[str, dict[str, Any] | None] = collections.OrderedDict()
        super().__init__(name=name)

    def append_sampler(self, sampler: ObjectPositionSampler, sample_args: dict[str, Any] | None = None) -> None:
        """Adds ``sampler`` (run with ``sample_args``: ``reference``, ``on_top``)."""
        for obj in sampler.mujoco_objects:
            assert obj not in self.mujoco_objects, f"Object '{obj.name}' already has sampler associated with it!"
            self.mujoco_objects.append(obj)
        self.samplers[sampler.name] = sampler
        self.sample_args[sampler.name] = sample_args

    def hide(self, mujoco_objects: Any) -> None:
        """Puts ``mujoco_objects`` far out of the workspace (robosuite's hiding sampler)."""
        self.append_sampler(
            UniformRandomSampler(
                name="HideSampler", mujoco_objects=mujoco_objects, x_range=[-10, -20], y_range=[-10, -20],
                rotation=[0, 0], rotation_axis="z", z_offset=10, ensure_object_boundary_in_range=False,
                ensure_valid_placement=False, rng=self.rng,
            )
        )

    def add_objects(self, mujoco_objects: Any) -> None:
        """Refused, as robosuite refuses it (objects belong to the sub-samplers)."""
        raise AttributeError("add_objects() should not be called for SequentialCompsiteSamplers!")

    def add_objects_to_sampler(self, sampler_name: str, mujoco_objects: Any) -> None:
        """Adds ``mujoco_objects`` to the sub-sampler ``sampler_name``."""
        objects = _objects(mujoco_objects)
        for obj in objects:
            assert obj not in self.mujoco_objects, f"Object '{obj.name}' already has sampler associated with it!"
            self.mujoco_objects.append(obj)
        assert sampler_name in self.samplers, (
            f"Invalid sub-sampler specified, valid options are: {self.samplers.keys()}, requested: {sampler_name}"
        )
        self.samplers[sampler_name].add_objects(objects)

    def reset(self) -> None:
        """Forgets the objects of this sampler and of every sub-sampler."""
        super().reset()
        for sampler in self.samplers.values():
            sampler.reset()

    def sample(self, fixtures: Any = None, reference: Any = None, on_top: bool = True) -> dict[str, Any]:
        """Each sub-sampler's placements in turn (``reference`` / ``on_top`` apply where its
        ``sample_args`` do not set them)."""
        placed = {} if fixtures is None else copy(fixtures)
        for sampler, args in zip(self.samplers.values(), self.sample_args.values()):
            args = dict(args or {})
            args.setdefault("reference", reference)
            args.setdefault("on_top", on_top)
            placed.update(sampler.sample(fixtures=placed, **args))
        return placed
