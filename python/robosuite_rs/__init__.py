"""robosuite's Python API served by the Rust core of robosuite-rs.

A robosuite user changes imports only::

    import robosuite_rs as suite                    # was: import robosuite as suite
    from robosuite_rs.wrappers import GymWrapper    # was: from robosuite.wrappers import GymWrapper

    env = suite.make("Lift", robots="Panda", has_renderer=False,
                     has_offscreen_renderer=False, use_camera_obs=False)
    gym_env = GymWrapper(env)

Importing the package also registers every env with Gymnasium
(``gymnasium.make("robosuite_rs/Lift-v0")``).
"""

from __future__ import annotations

# The extension links MuJoCo 3.17.0 dynamically; the `mujoco` wheel ships the library and
# loads it (by its SONAME) when imported, so it must be imported before `_native`.
import mujoco as _mujoco  # noqa: F401  (imported for its side effect)

import json
import operator
from collections import OrderedDict
from os import PathLike
from typing import Any

import numpy as np
from gymnasium import error as gymnasium_error

from . import _native
from ._env_observables import EnvObservables
from .compat import served_macro
from .renderers import MjviewerRenderer, OpenCVViewer, load_renderer_config

__all__ = [
    "make",
    "make_vec",
    "make_pool",
    "VectorizeError",
    "scene_xml",
    "load_composite_controller_config",
    "load_part_controller_config",
    "ALL_PART_CONTROLLERS",
    "RobosuiteEnv",
    "ALL_ENVIRONMENTS",
    "SUPPORTED_KWARGS",
    "task_arguments",
    "install_as_robosuite",
    "__version__",
]

__version__: str = _native.__version__

#: robosuite's arm part controllers (``robosuite.controllers.ALL_PART_CONTROLLERS``).
ALL_PART_CONTROLLERS: tuple[str, ...] = tuple(_native.part_controller_types())

#: The robosuite tasks this build provides.
ALL_ENVIRONMENTS: list[str] = list(_native.robosuite_env_names())

#: Every keyword argument :func:`make` takes besides ``model_xml`` and each task's own
#: (:func:`task_arguments`): the configuration schema, declared once in the Rust core
#: (``robosuite_env::config::kwarg_names``), which checks every name, type and value.
SUPPORTED_KWARGS: tuple[str, ...] = tuple(_native.supported_kwargs())


def load_composite_controller_config(controller: str | None = None, robot: str | None = None) -> dict[str, Any]:
    """robosuite's ``load_composite_controller_config``: the composite controller config
    (a dict) robosuite hands out for ``robot`` (its ``default_{robot}.json``, else
    ``basic.json``) or for the composite controller ``controller`` (``"BASIC"`` or a
    ``.json`` path), read from robosuite's own files."""
    return json.loads(_native.load_composite_controller_config(controller, robot))


def load_part_controller_config(custom_fpath: str | PathLike[str] | None = None, default_controller: str | None = None) -> dict[str, Any]:
    """robosuite's ``load_part_controller_config``: the part controller config of
    ``default_controller`` (one of :data:`ALL_PART_CONTROLLERS`) or of the JSON file
    ``custom_fpath``."""
    path = None if custom_fpath is None else str(custom_fpath)
    return json.loads(_native.load_part_controller_config(path, default_controller))


def _native_kwargs(robots: Any, kwargs: dict[str, Any]) -> dict[str, Any]:
    """:func:`make`'s keyword arguments as the Rust core reads them: ``robots`` folded in
    and a ``placement_initializer`` object as its settings; every other value as given
    (lists as lists, dicts as dicts, NumPy values included). Warns about controller config
    keys robosuite's controllers ignore."""
    out = dict(kwargs)
    if robots is not None:
        out["robots"] = robots
    if "placement_initializer" in out:
        out["placement_initializer"] = _placement_option(out["placement_initializer"])
    configs = out.get("controller_configs")
    ignored = [] if configs is None else _native.controller_ignored_keys(configs)
    if ignored:
        import warnings

        warnings.warn(
            f"controller_configs: robosuite's controllers ignore {', '.join(ignored)} (not settings "
            "of their controller type); so does robosuite_rs",
            stacklevel=3,
        )
    return out


def _placement_option(value: Any) -> dict[str, Any] | None:
    """``placement_initializer`` as the task's option."""
    from .utils.placement_samplers import SequentialCompositeSampler, UniformRandomSampler

    if isinstance(value, SequentialCompositeSampler):
        # robosuite's tasks call the sampler's add_objects, which a composite sampler refuses.
        value.add_objects([])
    if value is not None and not isinstance(value, UniformRandomSampler):
        raise TypeError(
            "placement_initializer must be None or a robosuite_rs.utils.placement_samplers."
            f"UniformRandomSampler, got {type(value).__name__}"
        )
    return None if value is None else value._task_option()


def task_arguments(env_name: str) -> dict[str, Any]:
    """The task ``env_name``'s own constructor arguments with robosuite's defaults (e.g.
    ``{"use_latch": True}`` for Door; lists for robosuite's tuples, ``None`` for ``None``),
    passed to :func:`make` as keyword arguments like robosuite's.

    Raises:
        ValueError: for an unknown task.
    """
    return json.loads(_native.task_options(env_name))


class RobosuiteEnv:
    """A robosuite environment (robosuite's ``MujocoEnv`` API) run by the Rust core.

    ``reset()`` returns an ``OrderedDict`` of NumPy arrays (``float64``, except
    ``robotN_eef_quat_site`` which is ``float32`` as in robosuite); ``step(action)``
    returns robosuite's ``(obs, reward, done, info)``.
    """

    def __init__(self, native: Any) -> None:
        """Wraps ``native`` (a ``_native.RobosuiteEnv``); use :func:`make` instead."""
        self._native = native
        self._make_args: tuple[str, dict[str, Any], str | None] | None = None
        self._sim: Any = None
        self._robots: Any = None
        self._ep_meta: dict[str, Any] = {}
        # The user's processors, run after edit_model_xml (a list without the bound method,
        # so an env is freed when its last reference goes, without waiting for the GC).
        self._xml_processors: list[Any] = []
        self._controller_configs: list[dict[str, Any] | None] = []
        self._obsv = EnvObservables(native)
        self._viewer: Any = None
        self._closed = False
        self.has_renderer = False
        self.renderer = "mjviewer"
        self.renderer_config: dict[str, Any] | None = None
        self.render_camera: list[str] | None = ["frontview"]

    # --- robosuite's env object: env.sim, env.robots, the XML round trip ----------------
    @property
    def sim(self) -> Any:
        """robosuite's ``MjSim`` over this env's own memory: ``sim.model._model`` and
        ``sim.data._data`` are a ``mujoco.MjModel`` and ``mujoco.MjData`` shared with the
        Rust env (see :mod:`robosuite_rs.binding_utils`)."""
        if self._sim is None:  # made on first use; made anew when a scene gets a new model
            from .binding_utils import MjSim

            self._sim = MjSim(self._native)
        return self._sim

    @property
    def robots(self) -> list[Any]:
        """The robots (robosuite's ``env.robots``), see :mod:`robosuite_rs.robots`."""
        if self._robots is None:
            from .robots import Robot

            model = self.sim.model
            infos = self._native.robots_info()
            configs = self._controller_configs or [None] * len(infos)
            self._robots = [
                Robot(self, info, model, configs[i] if i < len(configs) else None) for i, info in enumerate(infos)
            ]
        return self._robots

    def edit_model_xml(self, xml_str: str) -> str:
        """robosuite's ``edit_model_xml``: points the mesh and texture files of a scene
        saved anywhere (paths through a ``robosuite/`` folder) at this machine's copy of
        robosuite's model files."""
        import xml.etree.ElementTree as ET

        try:
            root = ET.fromstring(xml_str)
        except ET.ParseError as e:
            raise ValueError(f"not an MJCF scene: {e}") from None
        asset = root.find("asset")
        if asset is None:
            return xml_str
        local = _native.robosuite_package_dir()
        for elem in asset.findall("mesh") + asset.findall("texture"):
            old = elem.get("file")
            if old is None:
                continue
            parts = old.split("/")
            hits = [i for i, p in enumerate(parts) if p == "robosuite"]
            if hits:
                elem.set("file", "/".join([local.rstrip("/")] + parts[max(hits) + 1 :]))
        return ET.tostring(root, encoding="utf8").decode("utf8")

    def set_xml_processor(self, processor: Any) -> None:
        """robosuite's ``set_xml_processor``: ``processor(xml) -> xml`` is applied (after
        :meth:`edit_model_xml`) to every scene :meth:`reset_from_xml_string` loads."""
        if not callable(processor):
            raise TypeError(f"processor must be callable, got {processor!r}")
        self._xml_processors.append(processor)

    def reset_from_xml_string(self, xml_string: str) -> None:
        """robosuite's ``reset_from_xml_string``: reloads the env from a scene's MJCF (such
        as ``env.sim.model.get_xml()`` saved by robosuite or by this package, on any
        machine), then resets deterministically (robots at ``init_qpos``, objects as the
        scene places them). A scene that differs from the current one only in the sizes of
        generated boxes (the demonstrations of one task) is loaded into the current model
        in place: ``env.sim`` and views of its arrays stay valid and show the new scene;
        any other scene gets a new model and data (``env.sim`` is then a new object).

        Raises:
            ValueError / RuntimeError: for text that is not a scene of this task (the
                message names what is missing); the env is then unchanged.
        """
        if not isinstance(xml_string, str):
            raise TypeError(f"xml_string must be a str, got {type(xml_string).__name__}")
        # the native load points asset paths through a `robosuite/` folder at the local
        # model files (what edit_model_xml does), so the text goes as given
        xml = xml_string
        for processor in self._xml_processors:
            xml = processor(xml)
            if not isinstance(xml, str):
                raise TypeError(f"an xml processor returned {type(xml).__name__}, not str")
        _, in_place = self._native.reset_from_xml_string(xml)
        self._obsv.native_replaced()
        if not in_place:  # a new model and data: env.sim and env.robots are made anew
            self._sim = None
            self._robots = None
        if isinstance(self._viewer, OpenCVViewer):
            self._viewer.sim = self.sim
        elif self._viewer is not None:
            self._viewer.update()  # a window on the new model

    def get_ep_meta(self) -> dict[str, Any]:
        """Episode metadata (a copy), ``{}`` unless set."""
        import copy

        return copy.deepcopy(self._ep_meta)

    def set_ep_meta(self, meta: dict[str, Any]) -> None:
        """Sets the episode metadata."""
        self._ep_meta = meta

    def unset_ep_meta(self) -> None:
        """Clears the episode metadata."""
        self._ep_meta = {}

    def update_state(self) -> None:
        """robosuite's hook after setting a state: nothing to update here."""

    # --- robosuite's visualization: env.visualize and the sites it toggles ---------------
    @property
    def _visualizations(self) -> set[str]:
        """robosuite's visualization keywords: ``{"env", "robots", "grippers"}``."""
        return {"env", "robots", "grippers"}

    def visualize(self, vis_settings: dict[str, Any]) -> None:
        """robosuite's ``visualize``: shows (``True``) or hides each setting's sites (the
        task objects' for ``"env"``, the robots' for ``"robots"``, the grippers' for
        ``"grippers"``) by the sign of their alpha, and with ``"grippers"`` on colours the
        grip site red to green by its distance to the task's target (Lift's cube, Stack's
        cube A, the closest nut handle or object, the door handle, the tool, the pot
        handles), as robosuite's tasks do. A reset hides them all again (robosuite's reset
        calls ``visualize`` with every setting off).

        Raises:
            ValueError: (also robosuite's ``KeyError``) for settings without one of
                ``"env"``, ``"robots"``, ``"grippers"``; nothing is changed.
        """
        if not isinstance(vis_settings, dict):
            raise TypeError(f"vis_settings must be a dict, got {type(vis_settings).__name__}")
        missing = sorted(self._visualizations - set(vis_settings))
        if missing:
            raise _VisualizationError(f"vis_settings needs the keys {sorted(self._visualizations)}; missing {missing}")
        self._native.visualize(
            bool(vis_settings["env"]), bool(vis_settings["robots"]), bool(vis_settings["grippers"])
        )

    def _gripper_to_target(
        self, gripper: Any, target: Any, target_type: str = "body", return_distance: bool = False
    ) -> Any:
        """robosuite's ``_gripper_to_target``: the vector (or with ``return_distance`` the
        distance) from the gripper's grip site to ``target`` (a body, geom or site name, or
        a task object, whose root body is used)."""
        data = self.sim.data
        gripper_pos = data.get_site_xpos(gripper.important_sites["grip_site"])
        if isinstance(target, MujocoObject):
            target_pos = data.get_body_xpos(target.root_body)
        elif target_type == "body":
            target_pos = data.get_body_xpos(target)
        elif target_type == "site":
            target_pos = data.get_site_xpos(target)
        else:
            target_pos = data.get_geom_xpos(target)
        diff = target_pos - gripper_pos
        return np.linalg.norm(diff) if return_distance else diff

    def _visualize_gripper_to_target(self, gripper: Any, target: Any, target_type: str = "body") -> None:
        """robosuite's ``_visualize_gripper_to_target``: colours the grip site of ``gripper``
        (or of each gripper of a dict) from red (far) to green (at ``target``)."""
        if isinstance(gripper, dict):
            for g in gripper.values():
                if g is not None:
                    self._visualize_gripper_to_target(g, target, target_type)
            return
        dist = float(np.sum(np.square(self._gripper_to_target(gripper, target, target_type))))
        max_dist = 0.1
        scaled = (1.0 - min(dist / max_dist, 1.0)) ** 15
        model = self.sim.model
        rgba = model.site_rgba[model.site_name2id(gripper.important_sites["grip_site"])]
        rgba[:3] = (1 - scaled, scaled, 0.0)

    # --- observables --------------------------------------------------------------------
    # robosuite's observables API (see robosuite_rs.observables and _env_observables): while
    # every observable is as made, step/reset are single native calls; otherwise the
    # step runs substep by substep and the observables sample on robosuite's schedule.
    @property
    def _observables(self) -> OrderedDict[str, Any]:
        """robosuite's ``env._observables``: observable name -> :class:`~robosuite_rs.observables.Observable`
        (the env's own first, in robosuite's order, then those added)."""
        self._obsv.materialize()
        return self._obsv.map

    @property
    def _obs_cache(self) -> dict[str, Any]:
        """robosuite's ``env._obs_cache``: the last sampled value of every enabled
        observable (and what sensors put there)."""
        self._obsv.materialize()
        return self._obsv.cache

    @property
    def observation_names(self) -> set[str]:
        """Every observable's name."""
        return set(self._obsv.map)

    @property
    def observation_modalities(self) -> set[str]:
        """Every observable's modality."""
        return {o.modality for o in self._obsv.map.values()}

    @property
    def enabled_observables(self) -> set[str]:
        """The enabled observables (sampled as the simulation runs)."""
        return {n for n, o in self._obsv.map.items() if o.is_enabled()}

    @property
    def active_observables(self) -> set[str]:
        """The active observables (returned in observations when enabled)."""
        return {n for n, o in self._obsv.map.items() if o.is_active()}

    def modify_observable(self, observable_name: str, attribute: str, modifier: Any) -> None:
        """robosuite's ``modify_observable``: sets ``attribute`` of the observable
        ``observable_name`` to ``modifier``: ``"sensor"`` (a :func:`~robosuite_rs.observables.sensor`
        function), ``"corrupter"``, ``"filter"``, ``"delayer"`` (a function or ``None``),
        ``"sampling_rate"`` (Hz), ``"enabled"``, ``"active"`` (bools; an observable that
        is not both is left out of the observations). A new corrupter or filter is tried
        once on the observable's current reading (NumPy's global RNG is left as it was).

        Raises:
            ValueError: for an unknown observable or attribute (the message lists the valid
                ones), a modifier of the wrong kind, a sampling rate that is not a positive
                finite number, a sensor that fails on an empty ``obs_cache``, a corrupter or
                filter that raises or turns the current reading into NaN/inf, a delayer not
                giving a non-negative number; the env is then unchanged.
        """
        self._obsv.modify(observable_name, attribute, modifier)

    def add_observable(self, observable: Any) -> None:
        """robosuite's ``add_observable``: adds ``observable`` (an
        :class:`~robosuite_rs.observables.Observable`) after the others; it is sampled
        from the next step on (env steps then run substep by substep in Python).

        Raises:
            ValueError: (also an ``AssertionError``, as robosuite raises) when an
                observable of that name exists.
            TypeError: for anything but an ``Observable``.
        """
        self._obsv.add(observable)

    def _get_observations(self, force_update: bool = False) -> OrderedDict[str, np.ndarray]:
        """robosuite's ``_get_observations``: the enabled and active observables' current
        values, then the ``{modality}-state`` concatenations; with ``force_update`` every
        enabled observable samples now (after ``sim.set_state_from_flattened`` and
        ``sim.forward()``: the current state). As in robosuite a forced update also moves
        the observables' clocks by one model timestep, so later env steps sample one
        substep earlier (those steps then run substep by substep) until the next reset."""
        return self._obsv.get_observations(force_update)

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickling and ``copy.deepcopy``: the configuration plus the whole run-time state
        (simulator, controllers, task, episode counter, RNG), so that the copy continues
        bit-identically. A ``model_xml`` scene is re-read from its path. Observables
        changed by ``modify_observable`` / ``add_observable`` are carried over with their
        clocks, values and ``obs_cache`` (their callables pickled as Python pickles them;
        ``copy.deepcopy`` keeps functions as they are).

        Raises:
            TypeError: for an env not made by :func:`make`.
            pickle.PicklingError: (when pickling) for an observable's callable that cannot
                be pickled; the message names the observable.
        """
        if self._make_args is None:
            raise TypeError("only envs made by robosuite_rs.make can be pickled or copied")
        return (_restore_env, (self._make_args, self._native.save_env_state(), self._obsv.save()))

    # --- robosuite's API -------------------------------------------------------------
    def reset(self, seed: int | None = None) -> OrderedDict[str, np.ndarray]:
        """Starts an episode; ``seed`` (an extension of robosuite's API) re-seeds the env.
        Sites shown by :meth:`visualize` are hidden again, as robosuite's reset does. An
        open mjviewer window stays open and shows the new episode."""
        obs = self._obsv.after_reset(self._native.reset(seed))
        if self._viewer is not None and self.renderer != "mujoco" and self._viewer.viewer is not None:
            self._viewer.update()
        return obs

    def step(self, action: Any) -> tuple[OrderedDict[str, np.ndarray], float, bool, dict[str, Any]]:
        """Applies ``action``; returns ``(obs, reward, done, info)``.

        Raises:
            ValueError: for an action of the wrong length or with NaN/inf (the env is
                unchanged), or when stepping an episode that is done (as robosuite); when
                an observable's sensor, corrupter, filter or delayer fails (the step is
                then taken all the same, and the message says so).
        """
        out = self._native.step(action) if self._obsv.fast else self._obsv.step(action)
        if self._viewer is not None and self.renderer != "mujoco":
            self._viewer.update()  # robosuite's mjviewer shows every step
        return out

    # --- robosuite's on-screen viewer --------------------------------------------------
    @property
    def viewer(self) -> Any:
        """robosuite's ``env.viewer``: the on-screen viewer of ``has_renderer=True`` (a
        :class:`~robosuite_rs.renderers.MjviewerRenderer` or
        :class:`~robosuite_rs.renderers.OpenCVViewer`, with ``set_camera`` and
        ``add_keypress_callback``), ``None`` without one."""
        return self._viewer

    def render(self) -> None:
        """robosuite's ``env.render()``: shows the current state in the on-screen window
        (opened at the first call or step): MuJoCo's viewer is synced, the OpenCV window
        draws the offscreen frame of ``render_camera``.

        Raises:
            RuntimeError: for an env made without ``has_renderer=True`` (frames come from
                ``env.sim.render`` or Gymnasium's ``render_mode="rgb_array"``), a closed env,
                or no display (the message names ``DISPLAY`` / ``MUJOCO_GL``).
        """
        if self._viewer is None:
            raise RuntimeError(
                "render() shows the on-screen viewer: make the env with has_renderer=True (renderer="
                "'mjviewer' or 'mujoco'); for frames use env.sim.render(...) or render_mode='rgb_array'"
                + (" (this env is closed)" if self._closed else "")
            )
        self._viewer.render()

    def close_renderer(self) -> None:
        """robosuite's ``close_renderer``: closes the window (the next ``render()`` opens it again)."""
        if self._viewer is not None:
            self._viewer.close_window()

    def _init_viewer(self, kwargs: dict[str, Any]) -> None:
        """robosuite's ``initialize_renderer`` for ``make``'s (already checked) arguments."""
        self.has_renderer = bool(kwargs.get("has_renderer", False))
        self.renderer = str(kwargs.get("renderer") or "mjviewer").lower()
        camera = kwargs.get("render_camera", "frontview")
        self.render_camera = None if camera is None else [camera] if isinstance(camera, str) else list(camera)
        config = kwargs.get("renderer_config")
        self.renderer_config = dict(config) if config is not None else (
            None if self.renderer == "mujoco" else load_renderer_config(self.renderer)
        )
        if not self.has_renderer:
            return
        from .renderers import check_display

        model = self.sim.model
        # ValueError listing the model's cameras for an unknown one
        camera_ids = None if self.render_camera is None else [model.camera_name2id(c) for c in self.render_camera]
        if self.renderer == "mujoco":
            viewer: Any = OpenCVViewer(self.sim)  # ImportError without opencv-python
            if camera_ids is not None:
                viewer.set_camera(camera_id=camera_ids)
        else:
            viewer = MjviewerRenderer(self, camera_id=None if camera_ids is None else camera_ids[0], **(self.renderer_config or {}))
        check_display()
        self._viewer = viewer

    @property
    def action_spec(self) -> tuple[np.ndarray, np.ndarray]:
        """``(low, high)`` action bounds."""
        return self._native.action_spec

    @property
    def action_dim(self) -> int:
        """The action dimension."""
        return self._native.action_dim

    def observation_spec(self) -> OrderedDict[str, np.ndarray]:
        """The current observations (as robosuite's ``observation_spec()``)."""
        return self._obsv.get_observations(False)

    def observation_keys(self) -> list[str]:
        """The observation keys, in order."""
        if self._obsv.fast:
            return list(self._native.observation_keys())
        return list(self._obsv.build())

    @property
    def horizon(self) -> int:
        """Episode length in env steps."""
        return self._native.horizon

    @property
    def control_freq(self) -> float:
        """Control frequency in Hz."""
        return self._native.control_freq

    @property
    def reward_scale(self) -> float | None:
        """The reward scale (``None``: unnormalised)."""
        return self._native.reward_scale

    @property
    def reward_shaping(self) -> bool:
        """Whether rewards are shaped."""
        return self._native.reward_shaping

    @property
    def ignore_done(self) -> bool:
        """Whether the horizon is ignored."""
        return self._native.ignore_done

    @property
    def use_object_obs(self) -> bool:
        """Whether object observations are included."""
        return self._native.use_object_obs

    @property
    def use_camera_obs(self) -> bool:
        """Whether camera observations (``{camera}_image``, ...) are included."""
        return self._native.use_camera_obs

    @property
    def has_offscreen_renderer(self) -> bool:
        """Whether the env has an offscreen renderer (camera observations or a render mode)."""
        return self._native.has_offscreen_renderer

    @property
    def camera_names(self) -> list[str]:
        """The observed cameras (empty without camera observations)."""
        return list(self._native.camera_names)

    @property
    def model_timestep(self) -> float:
        """MuJoCo's timestep in seconds (robosuite's ``model_timestep``, 0.002)."""
        return self._native.model_timestep

    @property
    def control_timestep(self) -> float:
        """Seconds of simulation per env step (robosuite's ``control_timestep``,
        ``1 / control_freq``)."""
        return 1.0 / self._native.control_freq

    @property
    def model(self) -> "_TaskModel":
        """robosuite's ``env.model`` (the task's MJCF model) as far as its XML: ``get_xml()``,
        ``root`` / ``worldbody`` (ElementTree elements) and ``save_model(fname)``."""
        return _TaskModel(self._native.source_xml(), self._native.mujoco_objects)

    @property
    def timestep(self) -> int:
        """Env steps taken in the current episode."""
        return self._native.timestep

    @property
    def name(self) -> str:
        """The task name."""
        return self._native.name

    def check_success(self) -> bool:
        """Whether the task is solved in the current state."""
        return self._native.check_success()

    _check_success = check_success

    def reward(self, action: Any = None) -> float:
        """The reward of the current state."""
        return self._native.reward()

    def get_state(self) -> np.ndarray:
        """The flat simulator state ``[time, qpos, qvel]``."""
        return self._native.get_state()

    def set_state(self, state: Any) -> None:
        """Sets the flat simulator state ``[time, qpos, qvel]`` (runs ``mj_forward``).

        Raises:
            ValueError: for a state that is not a flat array of the right length, or with a
                non-finite value or a position or velocity beyond 1e6 in magnitude.
        """
        self._native.set_state(state)

    def close(self) -> None:
        """Closes the env and its viewer window; calling it again does nothing.
        ``env.sim``'s arrays stay readable (they belong to Python)."""
        if self._viewer is not None:
            self._viewer.close()
            self._viewer = None
        self._closed = True
        self._native.close()

    def __repr__(self) -> str:
        return f"<robosuite_rs.RobosuiteEnv {self.name} horizon={self.horizon}>"


class _VisualizationError(ValueError, KeyError):
    """Settings ``visualize`` cannot apply: a ``ValueError`` that is also the ``KeyError``
    robosuite raises."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


class MujocoObject:
    """One of the task's objects as robosuite's ``MujocoObject`` describes it (an item of
    ``env.model.mujoco_objects``): ``name``, ``naming_prefix``, ``root_body``, ``joints``,
    ``contact_geoms``, ``visual_geoms``, ``sites`` (names in the compiled model),
    ``bottom_offset`` / ``top_offset`` (from the root body, NumPy arrays) and
    ``horizontal_radius`` (metres)."""

    def __init__(self, info: dict[str, Any]) -> None:
        self.name: str = info["name"]
        self.naming_prefix: str = info["naming_prefix"]
        self.root_body: str = info["root_body"]
        self.joints: list[str] = list(info["joints"])
        self.contact_geoms: list[str] = list(info["contact_geoms"])
        self.visual_geoms: list[str] = list(info["visual_geoms"])
        self.sites: list[str] = list(info["sites"])
        self.bottom_offset = np.array(info["bottom_offset"])
        self.top_offset = np.array(info["top_offset"])
        self.horizontal_radius: float = float(info["horizontal_radius"])

    def __repr__(self) -> str:
        return f"<MujocoObject {self.name}>"


class _TaskModel:
    """robosuite's ``env.model`` (a ``ManipulationTask``) for what is read from its XML: the
    scene's MJCF as compiled (robosuite's names; assets by absolute path), and its
    ``mujoco_objects`` (:class:`MujocoObject`)."""

    def __init__(self, xml: str, objects_json: str = "[]") -> None:
        import xml.etree.ElementTree as ET

        self._xml = xml
        self.mujoco_objects: list[MujocoObject] = [MujocoObject(o) for o in json.loads(objects_json)]
        self.root = ET.fromstring(xml)
        self.worldbody = self.root.find("worldbody")
        self.asset = self.root.find("asset")
        self.actuator = self.root.find("actuator")

    def get_xml(self) -> str:
        """The scene's MJCF text."""
        return self._xml

    def save_model(self, fname: str, pretty: bool = False) -> None:
        """Writes the MJCF to ``fname`` (``pretty``: indented)."""
        from .models.robots import save_xml

        save_xml(self._xml, fname, pretty)


def make(
    env_name: str,
    robots: str | list[str] | None = None,
    *,
    model_xml: str | PathLike[str] | None = None,
    **kwargs: Any,
) -> RobosuiteEnv:
    """robosuite's ``suite.make``: the task ``env_name`` with robosuite's keyword arguments.

    ``robots``: a robot name or one per robot (``None``: a Panda for each robot the task
    takes; two for the two-arm tasks); ``env_configuration``: ``"default"``, or for the
    two-arm tasks ``"opposed"`` / ``"parallel"`` (robosuite's set-ups).

    The arguments are :data:`SUPPORTED_KWARGS` (the schema declared in the Rust core) and the
    task's own (:func:`task_arguments`), with robosuite's names, value types (a name or a
    list of names, dicts, ``None``, NumPy values) and defaults, among them ``horizon``,
    ``control_freq``, ``reward_scale`` (``None`` allowed), ``reward_shaping``,
    ``ignore_done``, ``use_object_obs``, ``seed``, ``lite_physics``,
    ``initialization_noise`` (``"default"``, ``None`` or ``{"magnitude", "type"}``),
    ``controller_configs`` (robosuite's composite or part configs, as
    :func:`load_composite_controller_config` / :func:`load_part_controller_config` return
    them, one or one per robot), ``gripper_types``, ``base_types``, robosuite's camera
    arguments (camera observations are off by default here; ``has_offscreen_renderer``
    defaults to ``True`` as in robosuite), Gymnasium's ``render_mode`` (``"rgb_array"``,
    ``"depth_array"`` or ``None``) drawn from ``render_camera`` at ``render_width`` ×
    ``render_height``, and robosuite's on-screen viewer: ``has_renderer=True`` with
    ``renderer="mjviewer"`` (MuJoCo's viewer, the default; ``renderer_config={"cam_config":
    ...}`` places its free camera) or ``renderer="mujoco"`` (an OpenCV window; needs
    opencv-python), showing ``render_camera`` (``None``: the free camera; a list: side by
    side in the OpenCV window), see ``env.render()`` / ``env.viewer``;
    ``render_mode="human"`` is ``has_renderer=True``. ``model_xml``: a robosuite-style scene file to run the task
    on, e.g. one saved from robosuite with ``env.sim.model.get_xml()``.

    Raises:
        ValueError: for an unknown task, an unsupported value, or an ill-typed or invalid
            argument (the message names the argument and the item; an unknown camera's
            lists the model's cameras).
        TypeError: for an unknown keyword argument (the message lists robosuite's and the
            task's own).
        RuntimeError: for ``has_renderer=True`` without a display (the message names
            ``DISPLAY`` / ``MUJOCO_GL``).
        ImportError: for ``renderer="mujoco"`` without opencv-python.
    """
    if kwargs.get("render_mode") == "human":
        # Gymnasium's on-screen mode is robosuite's viewer.
        kwargs = dict(kwargs, render_mode=None, has_renderer=True)
    config = _native_kwargs(robots, kwargs)
    convention = served_macro("IMAGE_CONVENTION", "opengl")
    if convention != "opengl":
        config.setdefault("image_convention", convention)
    model = None if model_xml is None else str(model_xml)
    native = _native.make_robosuite(env_name, config, model)
    env = RobosuiteEnv(native)
    env._make_args = (env_name, config, model)
    env._obsv.hard_reset = bool(kwargs.get("hard_reset", True))
    env._controller_configs = _controller_config_dicts(kwargs.get("controller_configs"), robots, env)
    try:
        env._init_viewer(kwargs)
    except BaseException:
        env.close()
        raise
    return env


def _controller_config_dicts(given: Any, robots: Any, env: RobosuiteEnv) -> list[dict[str, Any] | None]:
    """Each robot's composite controller config as robosuite hands it out (the one given,
    else the robot's default), for ``env.robots[i].part_controllers``."""
    names = [i["name"] for i in env._native.robots_info()]
    if given is None:
        out: list[dict[str, Any] | None] = []
        for name in names:
            try:
                out.append(load_composite_controller_config(robot=name))
            except (ValueError, RuntimeError):
                out.append(None)
        return out
    items = list(given) if isinstance(given, (list, tuple)) else [given] * len(names)
    return [c if isinstance(c, dict) else None for c in items]


def _restore_env(make_args: tuple[str, dict[str, Any], str | None], state: str, observables: Any = None) -> "RobosuiteEnv":
    """An env made with ``make_args`` and given the run-time ``state`` and the
    ``observables`` (``EnvObservables.save()``; ``None`` in older pickles) (for ``pickle``)."""
    native = _native.make_robosuite(*make_args)
    native.load_env_state(state)
    env = RobosuiteEnv(native)
    env._make_args = make_args
    if observables is not None:
        env._obsv.load(observables)
    return env


def scene_xml(env_name: str, robots: str | list[str] | None = None, **kwargs: Any) -> str:
    """The MJCF text of the scene :func:`make` builds for ``env_name`` (robosuite's names);
    save it and pass the path as ``make(..., model_xml=path)``.

    Raises:
        ValueError: as :func:`make`.
    """
    return _native.scene_xml(env_name, _native_kwargs(robots, kwargs))


def _count(name: str, value: Any) -> int:
    """``value`` as an int if it is an integer (Python or NumPy), else ``TypeError``: a
    float such as ``2.7`` is never truncated."""
    if isinstance(value, bool):
        raise TypeError(f"{name} must be an integer, got {value!r}")
    try:
        return operator.index(value)
    except TypeError:
        raise TypeError(f"{name} must be an integer, got {value!r}") from None


def _max_steps(value: Any) -> int | None:
    """Gymnasium's ``max_episode_steps`` (``None``: no limit beyond the horizon)."""
    if value is None:
        return None
    steps = _count("max_episode_steps", value)
    if steps < 1:
        raise ValueError(f"max_episode_steps must be at least 1, got {steps}")
    return steps


class VectorizeError(gymnasium_error.Error, ValueError):
    """A vectorization argument that the chosen mode cannot honour (e.g. ``wrappers`` for
    the Rust-threaded vector env). A ``gymnasium.error.Error`` (as Gymnasium's own
    ``make_vec`` raises for these) and a ``ValueError``."""


def _make_single_env(env_id: str, wrappers: tuple[Any, ...], kwargs: dict[str, Any]) -> Any:
    """One env of a ``"sync"`` / ``"async"`` vector: ``gymnasium.make`` then ``wrappers``
    (module level, so ``AsyncVectorEnv`` can pickle it into spawn/forkserver workers)."""
    import gymnasium

    from . import registration as _registration  # noqa: F401  (registers the ids in a fresh process)

    env = gymnasium.make(env_id, **kwargs)
    for wrapper in wrappers:
        env = wrapper(env)
    return env


def make_vec(
    env_name: str,
    num_envs: int = 1,
    robots: str | list[str] | None = None,
    *,
    keys: list[str] | None = None,
    flatten_obs: bool = True,
    model_xml: str | PathLike[str] | None = None,
    threads: int | None = None,
    pin_threads: bool = False,
    max_episode_steps: int | None = None,
    vectorization_mode: str | None = None,
    vector_kwargs: dict[str, Any] | None = None,
    wrappers: Any = None,
    copy: bool = True,
    **kwargs: Any,
) -> Any:
    """``num_envs`` GymWrapper'd envs as one ``gymnasium.vector.VectorEnv``; the vector
    entry point of the ``robosuite_rs/<Task>-v0`` ids (``gymnasium.make_vec``).

    Takes :func:`make`'s keyword arguments (``render_mode=None`` included) plus
    GymWrapper's ``keys`` / ``flatten_obs`` and Gymnasium's ``make_vec`` arguments:

    * ``vectorization_mode``: ``None`` or ``"vector_entry_point"`` (default) steps the envs
      in Rust threads with the GIL released (a :class:`~robosuite_rs.vector.RustVectorEnv`;
      ``threads``: default the number of CPUs, at most ``num_envs``; ``pin_threads=True``
      pins each worker thread to its own CPU; ``reset(seed=s)`` seeds env ``i`` with
      ``s + i``). ``"sync"`` / ``"async"`` build Gymnasium's
      ``SyncVectorEnv`` / ``AsyncVectorEnv`` over ``gymnasium.make`` of the same id, as
      ``gymnasium.make_vec`` does.
    * ``max_episode_steps``: Gymnasium's ``TimeLimit`` (``truncated`` after that many
      steps); in the Rust mode the limit runs in Rust, inside each env.
    * ``vector_kwargs``: keyword arguments of ``SyncVectorEnv`` / ``AsyncVectorEnv``
      (``"sync"`` / ``"async"`` only).
    * ``wrappers``: callables applied to each sub-env (``"sync"`` / ``"async"`` only: the
      Rust envs have no Python sub-env to wrap).
    * ``copy``: Gymnasium's vector env argument. ``True``: ``step`` / ``reset`` return
      fresh arrays. ``False`` (Rust mode): read-only views of the batch each env writes its
      observation into (no copy; camera images included), overwritten by the next ``step``
      or ``reset``; copy what must outlive it. With ``"sync"`` / ``"async"`` it is passed
      to ``SyncVectorEnv`` / ``AsyncVectorEnv``.

    Raises:
        ValueError: as :func:`make`, for ``num_envs < 1`` or ``max_episode_steps < 1``, or
            an unknown ``vectorization_mode``.
        VectorizeError: for ``wrappers``, ``vector_kwargs`` or a render mode with the Rust
            mode, or ``threads`` / ``pin_threads`` with ``"sync"`` / ``"async"`` (nothing
            is built).
        TypeError: for a ``num_envs`` or ``max_episode_steps`` that is not an integer.
    """
    num_envs = _count("num_envs", num_envs)
    if num_envs < 1:
        raise ValueError(f"num_envs must be at least 1, got {num_envs}")
    steps = _max_steps(max_episode_steps)
    mode = getattr(vectorization_mode, "value", vectorization_mode)
    wrappers = tuple(wrappers or ())
    vector_kwargs = dict(vector_kwargs or {})
    if mode in ("sync", "async"):
        if threads is not None or pin_threads:
            name = "threads" if threads is not None else "pin_threads"
            raise VectorizeError(f"{name} is for the Rust vector env, not vectorization_mode={mode!r}")
        import gymnasium
        from functools import partial

        single_kwargs = dict(kwargs, keys=keys, flatten_obs=flatten_obs, max_episode_steps=steps)
        if robots is not None:
            single_kwargs["robots"] = robots
        if model_xml is not None:
            single_kwargs["model_xml"] = model_xml
        from .registration import gym_id

        env_id = gym_id(env_name)
        make_one = partial(_make_single_env, env_id, wrappers, single_kwargs)
        vector_cls = gymnasium.vector.SyncVectorEnv if mode == "sync" else gymnasium.vector.AsyncVectorEnv
        if not copy:
            vector_kwargs.setdefault("copy", False)
        return vector_cls([make_one] * num_envs, **vector_kwargs)
    if mode not in (None, "vector_entry_point"):
        raise ValueError(
            f"vectorization_mode must be None, 'vector_entry_point', 'sync' or 'async', got {vectorization_mode!r}"
        )
    if wrappers:
        raise VectorizeError(
            "wrappers apply to Python sub-envs; the Rust vector env has none: use "
            "vectorization_mode='sync' or 'async', or wrap the vector env with gymnasium.wrappers.vector"
        )
    if vector_kwargs:
        raise VectorizeError(f"vector_kwargs are for vectorization_mode='sync' or 'async', got {vector_kwargs}")
    if kwargs.get("has_renderer"):
        raise VectorizeError(
            "has_renderer=True: the Rust vector env shows no window; use vectorization_mode='sync' "
            "(a window per sub-env) or has_renderer=False"
        )
    if kwargs.get("render_mode") is not None:
        raise VectorizeError(
            f"render_mode={kwargs['render_mode']!r}: the Rust vector env does not render; "
            "use vectorization_mode='sync' (or render_mode=None)"
        )
    from .vector import RustVectorEnv

    config = _native_kwargs(robots, kwargs)
    native = _native.make_robosuite_vec(
        env_name,
        num_envs,
        config,
        None if keys is None else list(keys),
        bool(flatten_obs),
        None if model_xml is None else str(model_xml),
        threads,
        steps,
        bool(pin_threads),
    )
    return RustVectorEnv(native, copy=bool(copy))


def make_pool(
    env_name: str,
    num_envs: int,
    batch_size: int,
    robots: str | list[str] | None = None,
    *,
    keys: list[str] | None = None,
    flatten_obs: bool = True,
    model_xml: str | PathLike[str] | None = None,
    threads: int | None = None,
    pin_threads: bool = False,
    max_episode_steps: int | None = None,
    copy: bool = True,
    **kwargs: Any,
) -> "EnvPool":
    """``num_envs`` GymWrapper'd envs in an asynchronous :class:`~robosuite_rs.pool.EnvPool`
    (EnvPool's ``send`` / ``recv`` mode) whose ``recv`` returns ``batch_size`` of them.

    Takes :func:`make_vec`'s arguments of its Rust mode (``threads``, ``pin_threads`` and
    ``max_episode_steps`` included); ``batch_size`` must be in ``1..num_envs``
    (EnvPool's advice: ``num_envs`` about 2-3 x ``batch_size``). ``copy=False``: ``recv``
    returns read-only views of the pool's batch (no copy), overwritten by the next ``recv``.

    Raises:
        ValueError: as :func:`make`, and for ``num_envs < 1`` or a bad ``batch_size``.
        TypeError: for a ``num_envs`` or ``batch_size`` that is not an integer.
    """
    from .pool import EnvPool

    num_envs = _count("num_envs", num_envs)
    batch_size = _count("batch_size", batch_size)
    if num_envs < 1:
        raise ValueError(f"num_envs must be at least 1, got {num_envs}")
    if not 1 <= batch_size <= num_envs:
        raise ValueError(f"batch_size must be in 1..{num_envs}, got {batch_size}")
    steps = _max_steps(max_episode_steps)
    config = _native_kwargs(robots, kwargs)
    native = _native.make_robosuite_pool(
        env_name,
        num_envs,
        batch_size,
        config,
        None if keys is None else list(keys),
        bool(flatten_obs),
        None if model_xml is None else str(model_xml),
        threads,
        steps,
        bool(pin_threads),
    )
    return EnvPool(native, copy=bool(copy))


from .vector import RustVectorEnv  # noqa: E402
from .pool import EnvPool  # noqa: E402
from .registration import register_envs as _register_envs  # noqa: E402
from .compat import install_as_robosuite  # noqa: E402

_register_envs()


def __getattr__(name: str) -> Any:
    """``robosuite_rs.sb3`` on first use (it imports Stable-Baselines3, which this package
    does not require)."""
    if name == "sb3":
        import importlib

        return importlib.import_module(".sb3", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
