"""The observables of one :class:`robosuite_rs.RobosuiteEnv` (robosuite's
``env._observables`` and the env methods around it), run as robosuite 1.5.2 runs them.

Two ways to step:

* Fast: while every observable is as the env made it (its own sensor, the control
  frequency as sampling rate, no corrupter, filter or delayer, none added) and its clock
  is where robosuite's would be, an env step samples every observable on its last
  substep, so ``env.step`` / ``env.reset`` are single calls into Rust and the Python
  ``Observable`` objects are brought up to date only when looked at. (At a control
  frequency whose period is not a whole number of model timesteps, e.g. 30 Hz,
  robosuite's observables do not sample on the last substep: such envs always take the
  slow way.)
* Slow: otherwise the step runs one substep at a time (``step_begin`` / ``step_substep`` /
  ``step_end`` of the native env, bit-identical to its ``step``) and updates every
  observable after every substep, in robosuite's order; the env's own sensors read the
  value of their key from one native observation pass at that substep.

robosuite's sensors that read other observables' values from ``obs_cache`` (joint
cos/sin, gripper-to-object vectors, the world pose in the gripper frame and the object
poses relative to it, Wipe's centroid, TwoArmPegInHole's ``peg_to_hole``, ``t`` and ``d``)
are computed from ``obs_cache`` here too, with robosuite's code, whenever those inputs
differ from the values the native sensor read (corrupted, delayed, sampled at another
substep or disabled); robosuite's sensors that write other entries of ``obs_cache``
(``{obj}_to_{pf}eef_pos`` its relative quaternion, ``wipe_radius`` the centroid,
``angle`` ``t`` and ``d``) write them here too.
"""

from __future__ import annotations

import copy
import math
import numbers
import pickle
import re
import weakref
from collections import OrderedDict
from typing import Any, Callable

import numpy as np

from .compat import served_macro
from .utils import transform_utils as T
from .observables import NO_CORRUPTION, NO_DELAY, NO_FILTER, Observable, ObservableError

ATTRIBUTES = ("sensor", "corrupter", "filter", "delayer", "sampling_rate", "enabled", "active")

# robosuite's clock of an observable as made (no delay), k env steps after a reset: kept
# every _CHECKPOINT steps per (period, timestep, substeps), the rest recomputed.
_CHECKPOINT = 256
_STEADY: dict[tuple[float, float, int], list[tuple[float, bool]]] = {}


def _clock_step(t: float, sampled: bool, period: float, dt: float, substeps: int) -> tuple[float, bool]:
    """robosuite's clock after one env step (``substeps`` updates, no delay)."""
    for _ in range(substeps):
        t += dt
        if not sampled and period >= t:
            sampled = True
        if t >= period:
            t %= period
            sampled = False
    return t, sampled


def steady_clock(period: float, dt: float, substeps: int, k: int) -> tuple[float, bool]:
    """``(time since last sample, sampled)`` of an observable as made, ``k`` env steps after
    ``reset()`` (its forced sample included)."""
    marks = _STEADY.setdefault((period, dt, substeps), [])
    if not marks:
        t, sampled = 0.0 + dt, True
        if t >= period:
            t, sampled = t % period, False
        marks.append((t, sampled))
    while (len(marks) - 1) * _CHECKPOINT < k - k % _CHECKPOINT:
        t, sampled = marks[-1]
        for _ in range(_CHECKPOINT):
            t, sampled = _clock_step(t, sampled, period, dt, substeps)
        marks.append((t, sampled))
    t, sampled = marks[k // _CHECKPOINT]
    for _ in range(k % _CHECKPOINT):
        t, sampled = _clock_step(t, sampled, period, dt, substeps)
    return t, sampled


_ALIGNED: dict[tuple[float, float, int], bool] = {}


def samples_at_step_ends(period: float, dt: float, substeps: int, steps: int = 256) -> bool:
    """Whether an observable as made (sampling period = the control period) samples exactly
    once per env step, on its last substep (checked over the first ``steps`` steps after a
    reset; its clock drifts by ~1e-17 s per step). It does for control frequencies whose
    period is a whole number of model timesteps (20 Hz: 25 substeps), not for others
    (30 Hz: a 1/30 s period over steps of 16 substeps, some steps then sample twice or not
    at all)."""
    key = (period, dt, substeps)
    if key not in _ALIGNED:
        t, sampled = steady_clock(period, dt, substeps, 0)
        ok = True
        for _ in range(steps):
            for i in range(substeps):
                t += dt
                sample = False
                if not sampled and period >= t:
                    sampled = sample = True
                if t >= period:
                    if not sampled:
                        ok = False  # robosuite's late sample (with its warning)
                    t %= period
                    sampled = False
                if sample != (i == substeps - 1):
                    ok = False
            if not ok:
                break
        _ALIGNED[key] = ok
    return _ALIGNED[key]


def _same(a: Any, b: Any) -> bool:
    """Bitwise the same value (dtype and shape included)."""
    if b is None:
        return False
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and bool(np.array_equal(a, b))


# --- robosuite's sensors that read other observables from obs_cache --------------------
class CacheRule:
    """How robosuite computes one of the env's observables from ``obs_cache``.

    ``keys``: the cache entries it reads; the native value is served when each holds the
    value the native sensor read (those in ``before``: the previous native observation
    pass's, as robosuite's relative-pose sensors run before the object poses they read are
    sampled again; the others: the current pass's), else ``compute(obs_cache)``, robosuite's
    sensor, which also writes what robosuite's writes into the cache. ``writes``: the cache
    entries robosuite's sensor writes besides its own, set to the native pass's values when
    the native value is served. ``feeders``: the observables whose sensors write entries
    this one reads (the native value assumes they ran just before, in the same pass).
    ``exact``: ``compute`` gives the native value from the native inputs (robosuite's
    gripper-frame poses, computed in float32 as robosuite does, do not).
    """

    __slots__ = ("keys", "before", "compute", "writes", "feeders", "exact")

    def __init__(
        self,
        keys: tuple[str, ...],
        compute: Callable[[dict[str, Any]], Any] | None,
        before: tuple[str, ...] = (),
        writes: tuple[str, ...] = (),
        feeders: tuple[str, ...] = (),
        exact: bool = True,
    ) -> None:
        self.keys, self.compute, self.before = keys, compute, before
        self.writes, self.feeders, self.exact = writes, feeders, exact


def _difference(a: str, b: str) -> Callable[[dict[str, Any]], np.ndarray]:
    def value(cache: dict[str, Any]) -> np.ndarray:
        return cache[a] - cache[b] if a in cache and b in cache else np.zeros(3)

    return value


def _elementwise(fn: Callable[[Any], Any], key: str, size: int) -> Callable[[dict[str, Any]], np.ndarray]:
    def value(cache: dict[str, Any]) -> np.ndarray:
        return fn(cache[key]) if key in cache else np.zeros(size)

    return value


def _cached(key: str, default: Callable[[], Any]) -> Callable[[dict[str, Any]], Any]:
    """robosuite's sensors that return another sensor's cache entry."""

    def value(cache: dict[str, Any]) -> Any:
        return cache[key] if key in cache else default()

    return value


def _world_pose_in_gripper(pos: str, quat: str) -> Callable[[dict[str, Any]], np.ndarray]:
    """robosuite's ``_get_world_pose_in_gripper_sensor``."""

    def value(cache: dict[str, Any]) -> np.ndarray:
        if pos in cache and quat in cache:
            return T.pose_inv(T.pose2mat((cache[pos], cache[quat])))
        return np.eye(4)

    return value


def _rel_obj_eef(obj: str, world_pose: str, quat_key: str) -> Callable[[dict[str, Any]], np.ndarray]:
    """robosuite's ``_get_rel_obj_eef_sensor``: the object's position in the gripper frame;
    writes the relative quaternion into the cache."""

    def value(cache: dict[str, Any]) -> np.ndarray:
        if any(name not in cache for name in (f"{obj}_pos", f"{obj}_quat", world_pose)):
            return np.zeros(3)
        obj_pose = T.pose2mat((cache[f"{obj}_pos"], cache[f"{obj}_quat"]))
        rel_pose = T.pose_in_A_to_pose_in_B(obj_pose, cache[world_pose])
        rel_pos, rel_quat = T.mat2pose(rel_pose)
        cache[quat_key] = rel_quat
        return rel_pos

    return value


def _peg_to_hole(body_xpos: Callable[[str], np.ndarray]) -> Callable[[dict[str, Any]], np.ndarray]:
    """TwoArmPegInHole's ``peg_to_hole``: the cached hole position minus the peg body's."""

    def value(cache: dict[str, Any]) -> np.ndarray:
        return cache["hole_pos"] - body_xpos("peg_main") if "hole_pos" in cache else np.zeros(3)

    return value


# `_get_obj_eef_sensor` observables: name pattern -> (object key, gripper number or None).
_OBJ_EEF = (
    (re.compile(r"^(?P<arm>.*)gripper_to_cube_pos$"), "cube_pos", None),
    (re.compile(r"^(?P<arm>.*)gripper_to_(?P<obj>cube[AB])$"), "{obj}_pos", None),
    (re.compile(r"^door_to_(?P<arm>.*)eef_pos$"), "door_pos", None),
    (re.compile(r"^handle_to_(?P<arm>.*)eef_pos$"), "handle_pos", None),
    (re.compile(r"^(?P<arm>.*)gripper_to_wipe_centroid$"), "wipe_centroid", None),
    (re.compile(r"^(?P<arm>.*)gripper(?P<i>[01])_to_handle(?P=i)$"), "handle{i}_xpos", "i"),
    (re.compile(r"^(?P<arm>.*)gripper(?P<i>[01])_to_handle$"), "handle_xpos", "i"),
    (re.compile(r"^(?P<arm>.*)gripper(?P<i>[01])_to_payload$"), "payload_pos", "i"),
    (re.compile(r"^(?P<arm>.*)gripper(?P<i>0)_to_lid_handle$"), "lid_handle_pos", "i"),
    (re.compile(r"^(?P<arm>.*)gripper(?P<i>1)_to_trash$"), "trash_pos", "i"),
)


_WORLD_POSE = re.compile(r"^world_pose_in_(?P<arm>(right_|left_)?)gripper$")
_REL_POS = re.compile(r"^(?P<obj>.+)_to_robot0_(?P<arm>(right_|left_)?)eef_pos$")


def cache_rules(
    specs: list[tuple[str, tuple[int, ...]]], body_xpos: Callable[[str], np.ndarray] | None = None
) -> dict[str, CacheRule]:
    """For each of the env's observables that robosuite computes from ``obs_cache`` (or
    whose sensor writes other cache entries): its :class:`CacheRule`. ``body_xpos(object)``
    gives a body's position now (TwoArmPegInHole's peg, ``peg_main``)."""
    names = {name for name, _ in specs}
    rules: dict[str, CacheRule] = {}
    for name, shape in specs:
        size = int(np.prod(shape)) if shape else 1
        for suffix, fn in (("_joint_pos_cos", np.cos), ("_joint_pos_sin", np.sin)):
            if name.endswith(suffix):
                key = name[: -len(suffix)] + "_joint_pos"
                if key in names:
                    rules[name] = CacheRule((key,), _elementwise(fn, key, size))
        if name == "cubeA_to_cubeB" and {"cubeA_pos", "cubeB_pos"} <= names:
            rules[name] = CacheRule(("cubeB_pos", "cubeA_pos"), _difference("cubeB_pos", "cubeA_pos"))
        m = _WORLD_POSE.match(name)
        if m is not None:
            pos, quat = f"robot0_{m['arm']}eef_pos", f"robot0_{m['arm']}eef_quat"
            if {pos, quat} <= names:
                rules[name] = CacheRule((pos, quat), _world_pose_in_gripper(pos, quat), exact=False)
        m = _REL_POS.match(name)
        world_pose = f"world_pose_in_{m['arm']}gripper" if m is not None else ""
        if m is not None and world_pose in names:
            obj, quat_key = m["obj"], name[: -len("pos")] + "quat"
            inputs = (f"{obj}_pos", f"{obj}_quat")
            if set(inputs) <= names and quat_key in names:
                compute = _rel_obj_eef(obj, world_pose, quat_key)
                rules[name] = CacheRule((*inputs, world_pose), compute, before=inputs, writes=(quat_key,), exact=False)
                rules[quat_key] = CacheRule((quat_key,), _cached(quat_key, lambda: np.zeros(4)), feeders=(name,))
        if name == "wipe_radius" and "wipe_centroid" in names:
            rules[name] = CacheRule((), None, writes=("wipe_centroid",), exact=False)
            rules["wipe_centroid"] = CacheRule(
                ("wipe_centroid",), _cached("wipe_centroid", lambda: np.zeros(3)), feeders=(name,)
            )
        if name == "angle" and {"t", "d"} <= names and "hole_pos" in names:
            rules[name] = CacheRule((), None, writes=("t", "d"), exact=False)
            for key in ("t", "d"):
                rules[key] = CacheRule((key,), _cached(key, lambda: 0.0), feeders=(name,))
        if name == "peg_to_hole" and "hole_pos" in names and body_xpos is not None:
            rules[name] = CacheRule(("hole_pos",), _peg_to_hole(body_xpos))
        for pattern, obj_key, robot_group in _OBJ_EEF:
            m = pattern.match(name)
            if m is None:
                continue
            groups = m.groupdict()
            obj = obj_key.format(**groups)
            arm = groups["arm"]
            if robot_group is None:
                eefs = [f"robot0_{arm}eef_pos"]
            else:
                i = int(groups[robot_group])
                # two robots: robot i's arm; one two-armed robot: gripper 0 right, 1 left
                eefs = [f"robot{i}_{arm}eef_pos"] + ([f"robot0_{('right_', 'left_')[i]}eef_pos"] if not arm else [])
            eef = next((e for e in eefs if e in names), None)
            if eef is not None and obj in names:
                rules[name] = CacheRule((obj, eef), _difference(obj, eef))
            break
    return rules


class BuiltinSensor:
    """The sensor of one of the env's own observables: the value of its key in the native
    observation pass of the current substep (outside a step: the last observation).
    Called with robosuite's ``obs_cache`` like any sensor."""

    __slots__ = ("_owner", "__name__", "__modality__", "__weakref__")

    def __init__(self, owner: "EnvObservables", name: str, modality: str) -> None:
        self._owner = weakref.ref(owner)
        self.__name__ = name
        self.__modality__ = modality

    def __call__(self, obs_cache: dict[str, Any]) -> Any:
        owner = self._owner()
        if owner is None:
            raise RuntimeError(f"the env of observable {self.__name__!r} is gone")
        return owner.builtin_value(self.__name__, obs_cache)

    def __repr__(self) -> str:
        return f"<robosuite_rs sensor {self.__name__!r} ({self.__modality__})>"


class EnvObservable(Observable):
    """One of the env's own observables: an :class:`Observable` whose value, while the env
    runs the fast way, is brought up to date when read."""

    _owner: "weakref.ref[EnvObservables]"

    @property
    def obs(self) -> Any:
        owner = self._owner()
        if owner is not None and owner.fast:
            owner.materialize()
        return super().obs


class EnvObservables:
    """robosuite's ``env._observables`` with ``_obs_cache`` and the env methods that use
    them, over a native env."""

    def __init__(self, native: Any, hard_reset: bool = True) -> None:
        self.native = native
        self.hard_reset = bool(hard_reset)
        self.dt = float(native.model_timestep)
        self.substeps = int(native.substeps)
        self.rate = native.control_freq
        self.period = 1.0 / self.rate
        specs = list(native.observables())
        self.sensors: dict[str, BuiltinSensor] = {}
        self.map: OrderedDict[str, Observable] = OrderedDict()
        self.shapes: dict[str, tuple[int, ...]] = {}
        for name, modality, shape, _dtype, enabled, active in specs:
            s = BuiltinSensor(self, name, modality)
            self.sensors[name] = s
            self.shapes[name] = tuple(shape)
            o = EnvObservable._prebuilt(name, s, self.rate, tuple(shape), bool(enabled), bool(active))
            o._owner = weakref.ref(self)
            self.map[name] = o
        me = weakref.ref(self)  # no reference cycle through the rules
        self.cache_rules = cache_rules(
            [(name, self.shapes[name]) for name in self.sensors], lambda obj: me()._body_xpos(obj)
        )
        # (keys, compute) of the rules whose computation gives the native value from the
        # native inputs
        self.rules = {n: (r.keys, r.compute) for n, r in self.cache_rules.items() if r.exact}
        # Rules reading values of the previous native pass (relative poses): that pass's
        # values are kept (``_prev``) when the next one is made.
        self._needs_prev = any(rule.before for rule in self.cache_rules.values())
        self._prev: Any = None
        self.cache: dict[str, Any] = {}
        self.added: set[str] = set()
        # fast: see the module docstring; while it holds the Observable objects' clocks and
        # values are brought up to date only by materialize().
        self.aligned = samples_at_step_ends(self.period, self.dt, self.substeps)
        self.fast = self.aligned
        self._in_step = False
        self._pass: dict[str, Any] | None = None
        # Bumped by every change of the observables' settings (modify, add, a new model),
        # for those that cache what they derive from them (GymWrapper's key plan).
        self.version = 0

    # --- native values ------------------------------------------------------------------
    def _complete(self, values: Any, wanted: list[str]) -> Any:
        """``values`` plus those of ``wanted`` the native dict leaves out (from the same
        observation pass: the native buffer holds every observable)."""
        missing = [n for n in wanted if n not in values]
        if missing:
            extra = self.native.all_observations()
            values = dict(values)
            for n in missing:
                values[n] = extra[n]
        return values

    def _enabled_builtins(self) -> list[str]:
        return [n for n, o in self.map.items() if o._enabled and n in self.sensors]

    def pass_values(self) -> Any:
        """The native values of the current observation pass: inside a step or a forced
        update one pass per substep (made on first use), else the last observation."""
        if self._in_step:
            if self._pass is None:
                self._prev = self.native.all_observations() if self._needs_prev else None
                self._pass = self._complete(self.native.update_observations(), self._enabled_builtins())
            return self._pass
        return self.native.observation_spec()

    def builtin_value(self, name: str, obs_cache: dict[str, Any]) -> Any:
        values = self.pass_values()
        rule = self.cache_rules.get(name)
        if rule is not None:
            if not self._reads_native_inputs(rule, obs_cache, values):
                return rule.compute(obs_cache)
            if rule.writes:
                values = self._complete(values, list(rule.writes))
                for k in rule.writes:
                    obs_cache[k] = np.array(values[k])
        if name not in values:
            values = self._complete(values, [name])
        return np.array(values[name])

    def _reads_native_inputs(self, rule: CacheRule, obs_cache: dict[str, Any], values: Any) -> bool:
        """Whether ``obs_cache`` holds the inputs the native sensor read (see
        :class:`CacheRule`)."""
        for k in rule.keys:
            ref = self._prev if k in rule.before else values
            if k not in obs_cache or ref is None or not _same(obs_cache[k], ref.get(k)):
                return False
        return True

    def _body_xpos(self, body: str) -> np.ndarray:
        """The current position of body ``body`` (as the simulator has it now)."""
        import mujoco

        model, data = self.native.sim_objects()
        return np.array(data.xpos[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, body)])

    # --- clocks -------------------------------------------------------------------------
    def _steady(self) -> tuple[float, bool]:
        return steady_clock(self.period, self.dt, self.substeps, int(self.native.timestep))

    def materialize(self) -> None:
        """In the fast mode: sets every enabled observable's clock, value and cache entry to
        what robosuite's would be now (sampled on the last substep of the last step)."""
        if not self.fast:
            return
        enabled = [n for n, o in self.map.items() if o._enabled]
        if not enabled:
            return
        t, sampled = self._steady()
        values = self._complete(self.native.observation_spec(), enabled)
        cache: dict[str, Any] = {}
        for n in enabled:
            o = self.map[n]
            o._time_since_last_sample, o._sampled = t, sampled
            o._current_delay = 0.0
            o._current_observed_value = np.array(values[n])
            cache[n] = np.array(values[n])
        self.cache.clear()
        self.cache.update(cache)

    def as_made(self) -> bool:
        """Whether every observable is as the env made it (settings only: flags may
        differ) and the clocks are aligned with the steps, so that a forced update's values
        are the native observation's."""
        return self.aligned and self._as_made()

    def skip_forced_updates(self, k: int) -> None:
        """The observables' clocks as ``k`` forced updates (``get_observations(True)``)
        leave them, without reading anything: for a caller that read those updates' values
        natively (``observe_states``) and makes a real forced update next, which samples
        every enabled observable (value and cache) anew. Only for observables
        :meth:`as_made` (no delay is drawn)."""
        if k <= 0:
            return
        self.materialize()
        self.fast = False
        for o in self.map.values():
            if not o._enabled:
                continue
            t, period = o._time_since_last_sample, o._sampling_timestep
            sampled = o._sampled
            for _ in range(k):
                t += self.dt
                sampled = True
                if t >= period:
                    t %= period
                    sampled = False
            o._time_since_last_sample, o._sampled = t, sampled
            o._current_delay = 0.0

    def _as_made(self) -> bool:
        """Every observable as the env made it (settings only)."""
        if self.added:
            return False
        for n, o in self.map.items():
            if (
                o._sensor is not self.sensors[n]
                or o._corrupter is not NO_CORRUPTION
                or o._filter is not NO_FILTER
                or o._delayer is not NO_DELAY
                or o._sampling_timestep != self.period
                or o._current_delay != 0.0
            ):
                return False
            if o._enabled:
                rule = self.cache_rules.get(n)
                if rule is not None and not all(self.map[k]._enabled for k in (*rule.keys, *rule.feeders)):
                    return False
        return True

    def refresh(self) -> None:
        """Chooses the fast mode when it gives robosuite's results (the Observable objects
        must be up to date)."""
        if self.fast:
            return
        self.fast = self._can_be_fast()

    def _can_be_fast(self) -> bool:
        if not self.aligned or not self._as_made():
            return False
        steady = None
        shown = None
        for n, o in self.map.items():
            if not o._enabled:
                continue
            if steady is None:
                steady = self._steady()
            if (o._time_since_last_sample, o._sampled) != steady:
                return False
            if o._active:
                if shown is None:
                    shown = self.native.observation_spec()
                if not _same(o._current_observed_value, shown.get(n)):
                    return False
        return True

    # --- updates ------------------------------------------------------------------------
    def force_update(self, values: Any = None) -> None:
        """robosuite's ``_update_observables(force=True)``: every enabled observable
        samples now (``values``: the native observation pass to read, if one was just
        made)."""
        self._in_step, self._pass, self._prev = True, None, None
        if values is not None:
            self._pass = self._complete(values, self._enabled_builtins())
        try:
            for o in self.map.values():
                o.update(timestep=self.dt, obs_cache=self.cache, force=True)
        finally:
            self._in_step, self._pass = False, None

    def build(self) -> OrderedDict[str, Any]:
        """robosuite's ``_get_observations()`` from the observables' current values."""
        observations: OrderedDict[str, Any] = OrderedDict()
        groups: OrderedDict[str, list[np.ndarray]] = OrderedDict()
        for n, o in self.map.items():
            if o._enabled and o._active:
                value = o._current_observed_value
                observations[n] = value
                key = o.modality + "-state"
                part = [value] if type(value) in (int, float) or not value.shape else value
                groups.setdefault(key, []).append(np.array(part))
        for key, parts in groups.items():
            if key == "image-state" and not served_macro("CONCATENATE_IMAGES", False):
                continue
            observations[key] = np.concatenate(parts, axis=-1)
        return observations

    def get_observations(self, force_update: bool = False) -> OrderedDict[str, Any]:
        if force_update:
            self.materialize()
            self.fast = False
            try:
                self.force_update()
            finally:
                self.refresh()
            return self.build()
        if self.fast:
            return self.native.observation_spec()
        return self.build()

    def after_reset(self, values: Any) -> Any:
        """robosuite's observable handling in ``reset()`` after the native reset that gave
        ``values``: clocks reset (delays drawn), the env's own sensors put back (with
        ``hard_reset``), cache emptied, a forced update."""
        if self.fast:
            return values
        self.cache = {}
        for o in self.map.values():
            o.reset()
        if self.hard_reset:
            for n, s in self.sensors.items():
                o = self.map[n]
                if o._sensor is not s:
                    o._sensor = s
                    o._set_shape(self.shapes[n])
        try:
            self.force_update(values)
        finally:
            self.refresh()
        return values if self.fast else self.build()

    def step(self, action: Any) -> tuple[Any, float, bool, dict[str, Any]]:
        """robosuite's ``step`` with the observables updated after every substep.

        Raises:
            ValueError: when an observable's sensor, corrupter, filter or delayer fails: the
                native step is finished first (the simulation and the episode move on by
                one step), then the error is raised, saying so.
        """
        native = self.native
        native.step_begin(action)
        observables = list(self.map.values())
        dt, substeps = self.dt, self.substeps
        cache = self.cache
        last = substeps - 1
        # Observables whose clocks are equal advance together on the substeps where none
        # samples (then update() only moves the clock); where one does, every observable
        # is updated in order, as robosuite does.
        groups = _clock_groups(observables)
        for i in range(substeps):
            due = False
            for g in groups:
                if not g[1]:
                    t = g[0] + dt
                    if g[2] - g[3] >= t or t >= g[2]:
                        due = True
                        break
            if not due:
                native.step_substep(i == last)
                for g in groups:
                    t = g[0] + dt
                    if t >= g[2]:
                        t %= g[2]
                        g[1] = False
                    g[0] = t
                continue
            native.step_substep(True)
            _write_back(groups)
            self._in_step, self._pass = True, None
            try:
                for o in observables:
                    o.update(timestep=dt, obs_cache=cache)
            except BaseException as e:
                self._in_step, self._pass = False, None
                self._finish_step(i + 1)
                if not isinstance(e, Exception):
                    raise
                raise ValueError(
                    f"{e} -- raised while updating the observables during env.step(): the step was "
                    f"still taken (the simulation and the episode moved on by one step, now timestep "
                    f"{native.timestep}); its observations, reward and done were not returned"
                ) from e
            self._in_step, self._pass = False, None
            groups = _clock_groups(observables)
        _write_back(groups)
        _obs, reward, done, info = native.step_end()
        return self.build(), reward, done, info

    def _finish_step(self, done_substeps: int) -> None:
        """Runs the rest of the native step after an observable failed at a substep."""
        native = self.native
        while done_substeps < self.substeps:
            native.step_substep(done_substeps == self.substeps - 1)
            done_substeps += 1
        native.step_end()

    # --- robosuite's modify_observable / add_observable ---------------------------------
    def _trial_input(self, o: Observable) -> Any:
        """The observable's sensor reading now (for checking a new corrupter or filter)."""
        cache = dict(self.cache)
        return o._sensor(cache)

    def modify(self, name: str, attribute: str, modifier: Any) -> None:
        if name not in self.map:
            raise ObservableError(f"No valid observable with name {name} found. Options are: {sorted(self.map)}")
        if attribute not in ATTRIBUTES:
            raise ValueError(
                f"Invalid observable attribute specified. Requested: {attribute!r}, valid options are {list(ATTRIBUTES)}"
            )
        o = self.map[name]
        if attribute in ("enabled", "active"):
            if not isinstance(modifier, (bool, np.bool_)):
                raise ValueError(f"modify_observable: {attribute} of {name!r} takes a bool, got {modifier!r}")
            self.materialize()
            if name in self.sensors:
                self.native.modify_observable(name, attribute, bool(modifier))
            if attribute == "enabled":
                o.set_enabled(bool(modifier))
            else:
                o.set_active(bool(modifier))
            self.version += 1
            self.fast = False
            self.refresh()
            return
        if attribute == "sampling_rate":
            rate = modifier
            if isinstance(rate, (bool, np.bool_)) or not isinstance(rate, numbers.Real) or not (
                math.isfinite(rate) and rate > 0
            ):
                raise ValueError(
                    f"modify_observable: sampling_rate of {name!r} must be a positive finite number (Hz), got {rate!r}"
                )
        elif modifier is not None and not callable(modifier):
            raise ValueError(f"modify_observable: {attribute} of {name!r} must be callable or None, got {modifier!r}")
        self.materialize()
        if attribute == "sensor":
            if modifier is None:
                raise ValueError(f"modify_observable: the sensor of {name!r} must be a sensor function, got None")
            o.set_sensor(modifier)
        elif attribute in ("corrupter", "filter"):
            self._check_processing(o, attribute, modifier)
            (o.set_corrupter if attribute == "corrupter" else o.set_filter)(modifier)
        elif attribute == "delayer":
            if modifier is not None:
                self._check_delayer(o, modifier)
            o.set_delayer(modifier)
        else:
            o.set_sampling_rate(modifier)
        self.version += 1
        self.fast = False
        self.refresh()

    def _check_processing(self, o: Observable, attribute: str, fn: Any) -> None:
        """Runs the observable's current reading through the new corrupter or filter (NumPy's
        global RNG left as it was): refuses one that raises or turns finite values into
        NaN/inf."""
        if fn is None:
            return
        state = np.random.get_state()
        try:
            raw = self._trial_input(o)
            raw_array = np.asarray(raw)
            corrupter = fn if attribute == "corrupter" else o._corrupter
            filt = fn if attribute == "filter" else o._filter
            try:
                value = np.array(filt(corrupter(raw)))
            except Exception as e:
                raise ValueError(
                    f"modify_observable: the new {attribute} of {o.name!r} raised {type(e).__name__}: {e} "
                    f"on the current reading (nothing changed)"
                ) from e
        except ValueError:
            raise
        except Exception as e:
            raise ValueError(
                f"modify_observable: the sensor of {o.name!r} raised {type(e).__name__}: {e} (nothing changed)"
            ) from e
        finally:
            np.random.set_state(state)
        if value.dtype.kind in "fc" and not np.isfinite(value).all() and not (
            raw_array.dtype.kind in "fc" and not np.isfinite(raw_array).all()
        ):
            raise ValueError(
                f"modify_observable: the new {attribute} of {o.name!r} turns the current reading into NaN/inf "
                f"({value!r}); nothing changed"
            )

    def _check_delayer(self, o: Observable, delayer: Any) -> None:
        state = np.random.get_state()
        try:
            delay = delayer()
        except Exception as e:
            raise ValueError(f"modify_observable: the delayer of {o.name!r} raised {type(e).__name__}: {e}") from e
        finally:
            np.random.set_state(state)
        if isinstance(delay, (bool, np.bool_)) or not isinstance(delay, numbers.Real) or not (
            math.isfinite(delay) and delay >= 0
        ):
            raise ValueError(
                f"modify_observable: the delayer of {o.name!r} must return a non-negative finite number of "
                f"seconds, got {delay!r}"
            )

    def add(self, observable: Any) -> None:
        if not isinstance(observable, Observable):
            raise TypeError(f"add_observable takes an Observable, got {type(observable).__name__}")
        if observable.name in self.map:
            raise ObservableError(
                f"Observable name {observable.name} is already associated with an existing observable! "
                f"Use modify_observable(...) to modify a pre-existing observable."
            )
        self.materialize()
        self.map[observable.name] = observable
        self.added.add(observable.name)
        self.version += 1
        self.fast = False

    def native_replaced(self) -> None:
        """After ``reset_from_xml_string`` (a new native env with its default flags): the
        flags pushed again, then robosuite's reset handling."""
        self.dt = float(self.native.model_timestep)
        self.substeps = int(self.native.substeps)
        self.aligned = samples_at_step_ends(self.period, self.dt, self.substeps)
        self.version += 1
        if not self.aligned:
            self.materialize()
            self.fast = False
        for n, enabled, active in [(o[0], o[4], o[5]) for o in self.native.observables()]:
            ob = self.map[n]
            if ob._enabled != enabled:
                self.native.modify_observable(n, "enabled", ob._enabled)
            if ob._active != active:
                self.native.modify_observable(n, "active", ob._active)
        if not self.fast:
            self.after_reset(self.native.observation_spec())


    # --- pickling -------------------------------------------------------------------------
    def save(self) -> "SavedObservables":
        """What a copy of the env needs to continue with these observables: each own
        observable's flags; unless the env runs the fast way, also every setting, clock,
        value and ``obs_cache`` entry, and the added observables."""
        flags = [(n, self.map[n]._enabled, self.map[n]._active) for n in self.sensors]
        state: dict[str, Any] = {"hard_reset": self.hard_reset, "flags": flags, "slow": None}
        if not self.fast:
            own = []
            for n in self.sensors:
                o = self.map[n]
                own.append((n, {
                    "sensor": None if o._sensor is self.sensors[n] else _BuiltinRef.of(o._sensor),
                    "shape": o._data_shape,
                    "corrupter": o._corrupter,
                    "filter": o._filter,
                    "delayer": o._delayer,
                    "sampling_timestep": o._sampling_timestep,
                    "clock": (o._time_since_last_sample, o._sampled, o._current_delay),
                    "value": o._current_observed_value,
                }))
            added = []
            for n in self.added:
                o = self.map[n]
                fields = {k: _BuiltinRef.of(v) for k, v in vars(o).items()}
                added.append((n, type(o), fields))
            added.sort(key=lambda item: list(self.map).index(item[0]))
            state["slow"] = {"own": own, "added": added, "cache": dict(self.cache)}
        return SavedObservables(state)

    def load(self, saved: "SavedObservables") -> None:
        """Applies :meth:`save`'s state to the observables of a fresh env of the same
        configuration (its native state already loaded)."""
        state = saved.state
        self.hard_reset = bool(state["hard_reset"])
        for n, enabled, active in state["flags"]:
            o = self.map[n]
            for attribute, value, current in (("enabled", enabled, o._enabled), ("active", active, o._active)):
                if value != current:
                    self.native.modify_observable(n, attribute, bool(value))
            o._enabled, o._active = bool(enabled), bool(active)
        slow = state["slow"]
        if slow is not None:
            for n, a in slow["own"]:
                o = self.map[n]
                o._sensor = self.sensors[n] if a["sensor"] is None else a["sensor"].resolve(self)
                o._set_shape(a["shape"])
                o._corrupter, o._filter, o._delayer = a["corrupter"], a["filter"], a["delayer"]
                o._sampling_timestep = a["sampling_timestep"]
                o._time_since_last_sample, o._sampled, o._current_delay = a["clock"]
                o._current_observed_value = a["value"]
            for n, cls, fields in slow["added"]:
                o = cls.__new__(cls)
                o.__dict__.update({k: v.resolve(self) if isinstance(v, _BuiltinRef) else v for k, v in fields.items()})
                self.map[n] = o
                self.added.add(n)
            self.cache = dict(slow["cache"])
            self.fast = False
        self.version += 1


class _BuiltinRef:
    """An env's own sensor (``BuiltinSensor``) in a saved state, by name: the copy's own
    sensor of that name."""

    __slots__ = ("name",)

    def __init__(self, name: str) -> None:
        self.name = name

    @staticmethod
    def of(value: Any) -> Any:
        return _BuiltinRef(value.__name__) if isinstance(value, BuiltinSensor) else value

    def resolve(self, owner: EnvObservables) -> BuiltinSensor:
        return owner.sensors[self.name]

    def __reduce__(self) -> tuple[Any, ...]:
        return (_BuiltinRef, (self.name,))


class SavedObservables:
    """:meth:`EnvObservables.save`'s state. ``copy.deepcopy`` copies it as usual (functions
    are kept as they are); ``pickle`` first checks each setting and names the observable
    whose callable (or value) cannot be pickled."""

    __slots__ = ("state",)

    def __init__(self, state: dict[str, Any]) -> None:
        self.state = state

    def __deepcopy__(self, memo: dict[int, Any]) -> "SavedObservables":
        return SavedObservables(copy.deepcopy(self.state, memo))

    def _items(self) -> Any:
        """``(observable, attribute, value)`` of everything saved beyond plain flags."""
        slow = self.state["slow"]
        if slow is None:
            return
        for n, a in slow["own"]:
            for k, v in a.items():
                yield n, k, v
        for n, _cls, fields in slow["added"]:
            for k, v in fields.items():
                yield n, k.lstrip("_"), v
        for n, v in slow["cache"].items():
            yield n, "obs_cache value", v

    def __reduce__(self) -> tuple[Any, ...]:
        for name, attribute, value in self._items():
            try:
                pickle.dumps(value)
            except Exception as e:
                raise pickle.PicklingError(
                    f"cannot pickle the env: observable {name!r}: its {attribute} {value!r} cannot be "
                    f"pickled ({type(e).__name__}: {e}); use a module-level function, or copy.deepcopy"
                ) from e
        return (SavedObservables, (self.state,))


def _clock_groups(observables: list[Observable]) -> list[list[Any]]:
    """The enabled observables grouped by clock: ``[time since last sample, sampled,
    sampling period, current delay, members]``."""
    groups: dict[tuple[float, bool, float, float], list[Any]] = {}
    for o in observables:
        if o._enabled:
            key = (o._time_since_last_sample, o._sampled, o._sampling_timestep, o._current_delay)
            g = groups.get(key)
            if g is None:
                groups[key] = [key[0], key[1], key[2], key[3], [o]]
            else:
                g[4].append(o)
    return list(groups.values())


def _write_back(groups: list[list[Any]]) -> None:
    for t, sampled, _period, _delay, members in groups:
        for o in members:
            o._time_since_last_sample = t
            o._sampled = sampled
