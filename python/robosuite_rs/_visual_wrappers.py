"""robosuite's ``VisualizationWrapper`` and ``DomainRandomizationWrapper`` over the Rust
env's own model (``env.sim.model``); see :mod:`robosuite_rs.wrappers`."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from copy import deepcopy
from typing import Any

import numpy as np

from ._demo_wrappers import Wrapper
from .utils.mjmod import CameraModder, DynamicsModder, LightingModder, ModderError, TextureModder

__all__ = [
    "VisualizationWrapper",
    "DomainRandomizationWrapper",
    "DEFAULT_INDICATOR_SITE_CONFIG",
    "DEFAULT_COLOR_ARGS",
    "DEFAULT_CAMERA_ARGS",
    "DEFAULT_LIGHTING_ARGS",
    "DEFAULT_DYNAMICS_ARGS",
]

#: robosuite's default indicator: a red, half-transparent sphere of radius 3 cm.
DEFAULT_INDICATOR_SITE_CONFIG = {
    "type": "sphere",
    "size": [0.03],
    "rgba": [1, 0, 0, 0.5],
}

# MJCF's <site> attributes (MuJoCo's XML reference), besides the body's `pos`.
_SITE_ATTRIBUTES = {
    "name", "class", "type", "group", "pos", "quat", "axisangle", "xyaxes", "zaxis", "euler", "size",
    "fromto", "material", "rgba", "user",
}
_SITE_TYPES = {"sphere", "capsule", "ellipsoid", "cylinder", "box"}


def _to_string(v: Any) -> str:
    """robosuite's ``convert_to_string``."""
    if isinstance(v, (bool, np.bool_)):
        return str(v).lower()
    if isinstance(v, (int, float, np.integer, np.floating, str)):
        return str(v)
    return " ".join(str(x) for x in np.asarray(v).ravel())


def _check_indicator(i: int, config: Any) -> dict[str, Any]:
    """One indicator config (``"default"`` or a dict of site attributes), checked."""
    if isinstance(config, str):
        if config != "default":
            raise ModderError(f"indicator_configs[{i}]: a string must be 'default', got {config!r}")
        out = deepcopy(DEFAULT_INDICATOR_SITE_CONFIG)
        out["name"] = f"indicator{i}"
        return out
    if not isinstance(config, dict):
        raise ModderError(f"indicator_configs[{i}] must be 'default' or a dict of site attributes, got {config!r}")
    if not isinstance(config.get("name"), str) or not config["name"]:
        raise ModderError("Name must be specified for all indicator object configurations!")
    unknown = sorted(set(config) - _SITE_ATTRIBUTES)
    if unknown:
        raise ModderError(
            f"indicator {config['name']!r}: unknown site attribute(s) {unknown}; valid: {sorted(_SITE_ATTRIBUTES)}"
        )
    if "type" in config and config["type"] not in _SITE_TYPES:
        raise ModderError(
            f"indicator {config['name']!r}: type must be one of {sorted(_SITE_TYPES)}, got {config['type']!r}"
        )
    for key in ("pos", "size", "rgba", "quat", "euler", "axisangle", "xyaxes", "zaxis", "fromto"):
        if key in config:
            try:
                values = np.asarray(config[key], dtype=np.float64).ravel()
            except (TypeError, ValueError):
                raise ModderError(f"indicator {config['name']!r}: {key} must be numbers, got {config[key]!r}") from None
            if values.size == 0 or not np.all(np.isfinite(values)):
                raise ModderError(f"indicator {config['name']!r}: {key} must be finite numbers, got {config[key]!r}")
            if key == "pos" and values.size != 3:
                raise ModderError(f"indicator {config['name']!r}: pos must have 3 values, got {config[key]!r}")
            if key == "size" and np.any(values < 0):
                raise ModderError(f"indicator {config['name']!r}: size must not be negative, got {config[key]!r}")
    return dict(config)


class VisualizationWrapper(Wrapper):
    """robosuite's ``VisualizationWrapper``: shows the robots', grippers' and objects' sites
    (each setting of :meth:`get_visualization_settings`, all on at first; the grip site
    coloured red to green by its distance to the task's target), and adds indicator sites
    (``indicator_configs``: ``None``, ``"default"`` (a red sphere), a dict of site
    attributes with a ``name`` (``pos`` places its body), or a list of these) moved with
    :meth:`set_indicator_pos`. Indicators are added to the scene (the env is rebuilt
    from its scene with them, then reset).

    Raises:
        ModderError: (a ``ValueError`` that is also robosuite's ``AssertionError``) for an
            env with camera segmentations, an indicator config that is not ``"default"``
            or a dict with a ``name``, an unknown site attribute or type, non-finite or
            negative sizes, or an indicator name the scene already uses; the env is then
            unchanged.
    """

    def __init__(self, env: Any, indicator_configs: Any = None) -> None:
        super().__init__(env)
        base = env.unwrapped if hasattr(env, "unwrapped") else env
        make_args = getattr(base, "_make_args", None)
        segs = (make_args[1] if make_args else {}).get("camera_segmentations")
        if segs is not None and not (isinstance(segs, (list, tuple)) and all(s is None for s in segs)):
            raise ModderError("Cannot use camera segmentations with visualization wrapper!")
        self.indicator_configs: list[dict[str, Any]] | None = None
        if indicator_configs is not None:
            configs = [indicator_configs] if isinstance(indicator_configs, (str, dict)) else list(indicator_configs)
            self.indicator_configs = [_check_indicator(i, c) for i, c in enumerate(configs)]
            names = [c["name"] for c in self.indicator_configs]
            if len(set(names)) != len(names):
                raise ModderError(f"indicator names must be distinct, got {names}")
        self._vis_settings = {vis: True for vis in sorted(self.env._visualizations)}
        if self.indicator_configs:
            # robosuite adds an XML processor and hard-resets: the env is rebuilt from its
            # scene with the indicators (and any processor given before).
            self.env.set_xml_processor(self._add_indicators_to_model)
            try:
                self.env.reset_from_xml_string(self.env.model.get_xml())
            except Exception as e:
                base._xml_processors.remove(self._add_indicators_to_model)
                raise ModderError(f"cannot add the indicators to the scene: {e}") from e
            m = self.env.sim.model
            for name in self.get_indicator_names():
                rgba = m.site_rgba[m.site_name2id(name)]
                rgba[3] = abs(rgba[3])  # indicators are always drawn (robosuite's are)
        self.reset()

    def get_indicator_names(self) -> list[str]:
        """The indicators' names."""
        return [c["name"] for c in self.indicator_configs] if self.indicator_configs is not None else []

    def set_indicator_pos(self, indicator: str, pos: Any) -> None:
        """Moves ``indicator`` to world position ``pos`` (shown from the next
        ``sim.forward()`` or step on).

        Raises:
            ModderError: for an unknown indicator or a position that is not 3 finite numbers.
        """
        names = self.get_indicator_names()
        if indicator not in names:
            raise ModderError(f"Invalid indicator name specified. Valid options are {names}, got {indicator}")
        p = np.asarray(pos, dtype=np.float64)
        if p.shape != (3,) or not np.all(np.isfinite(p)):
            raise ModderError(f"pos must be 3 finite numbers, got {pos!r}")
        m = self.env.sim.model
        m.body_pos[m.body_name2id(indicator + "_body")] = p

    def get_visualization_settings(self) -> Any:
        """The visualization settings (``"env"``, ``"grippers"``, ``"robots"``)."""
        return self._vis_settings.keys()

    def set_visualization_setting(self, setting: str, visible: bool) -> None:
        """Shows (``visible``) or hides the sites of ``setting`` from the next step or reset.

        Raises:
            ModderError: for an unknown setting.
        """
        if setting not in self._vis_settings:
            raise ModderError(
                f"Invalid visualization setting specified. Valid options are {list(self._vis_settings)}, got {setting}"
            )
        self._vis_settings[setting] = bool(visible)

    def reset(self, **kwargs: Any) -> Any:
        """Resets the env, then applies the visualization settings. With the env's
        ``hard_reset`` (the default), the indicators go back to their configured positions,
        as robosuite's reload of the scene puts them."""
        ret = self.env.reset(**kwargs)
        base = self.env.unwrapped if hasattr(self.env, "unwrapped") else self.env
        if self.indicator_configs and getattr(getattr(base, "_obsv", None), "hard_reset", True):
            m = self.env.sim.model
            for config in self.indicator_configs:
                m.body_pos[m.body_name2id(config["name"] + "_body")] = np.asarray(
                    config.get("pos", (0, 0, 0)), dtype=np.float64
                )
            self.env.sim.forward()
        self.env.visualize(vis_settings=self._vis_settings)
        return ret

    def step(self, action: Any) -> Any:
        """Steps the env, then applies the visualization settings."""
        ret = self.env.step(action)
        self.env.visualize(vis_settings=self._vis_settings)
        return ret

    def _add_indicators_to_model(self, xml: str) -> str:
        """Adds each indicator (a body holding its site) to the scene's worldbody (those
        the scene has already are left as they are)."""
        if not self.indicator_configs:
            return xml
        root = ET.fromstring(xml)
        worldbody = root.find("worldbody")
        if worldbody is None:
            raise ModderError("the scene has no worldbody")
        bodies = {b.get("name") for b in root.iter("body")}
        sites = {s.get("name") for s in root.iter("site")}
        for config in self.indicator_configs:
            config = deepcopy(config)
            name = config["name"]
            if name + "_body" in bodies:
                continue
            if name in sites:
                raise ModderError(f"indicator {name!r}: the scene has a site of that name")
            pos = _to_string(config.pop("pos", (0, 0, 0)))
            body = ET.SubElement(worldbody, "body", {"name": name + "_body", "pos": pos})
            attrs = {"pos": (0, 0, 0), "size": (0.005,), "rgba": (1, 0, 0, 1)}  # robosuite's new_site defaults
            attrs.update(config)
            ET.SubElement(body, "site", {k: _to_string(v) for k, v in attrs.items() if v is not None})
        return ET.tostring(root, encoding="utf8").decode("utf8")


#: robosuite's color randomization arguments (:class:`~robosuite_rs.utils.mjmod.TextureModder`).
DEFAULT_COLOR_ARGS = {
    "geom_names": None,
    "randomize_local": True,
    "randomize_material": True,
    "local_rgb_interpolation": 0.2,
    "local_material_interpolation": 0.3,
    "texture_variations": ["rgb", "checker", "noise", "gradient"],
    "randomize_skybox": True,
}

#: robosuite's camera randomization arguments (:class:`~robosuite_rs.utils.mjmod.CameraModder`).
DEFAULT_CAMERA_ARGS = {
    "camera_names": None,
    "randomize_position": True,
    "randomize_rotation": True,
    "randomize_fovy": True,
    "position_perturbation_size": 0.01,
    "rotation_perturbation_size": 0.087,
    "fovy_perturbation_size": 5.0,
}

#: robosuite's lighting randomization arguments (:class:`~robosuite_rs.utils.mjmod.LightingModder`).
DEFAULT_LIGHTING_ARGS = {
    "light_names": None,
    "randomize_position": True,
    "randomize_direction": True,
    "randomize_specular": True,
    "randomize_ambient": True,
    "randomize_diffuse": True,
    "randomize_active": True,
    "position_perturbation_size": 0.1,
    "direction_perturbation_size": 0.35,
    "specular_perturbation_size": 0.1,
    "ambient_perturbation_size": 0.1,
    "diffuse_perturbation_size": 0.1,
}

#: robosuite's dynamics randomization arguments (:class:`~robosuite_rs.utils.mjmod.DynamicsModder`).
DEFAULT_DYNAMICS_ARGS = {
    "randomize_density": True,
    "randomize_viscosity": True,
    "density_perturbation_ratio": 0.1,
    "viscosity_perturbation_ratio": 0.1,
    "body_names": None,
    "randomize_position": True,
    "randomize_quaternion": True,
    "randomize_inertia": True,
    "randomize_mass": True,
    "position_perturbation_size": 0.0015,
    "quaternion_perturbation_size": 0.003,
    "inertia_perturbation_ratio": 0.02,
    "mass_perturbation_ratio": 0.02,
    "geom_names": None,
    "randomize_friction": True,
    "randomize_solref": True,
    "randomize_solimp": True,
    "friction_perturbation_ratio": 0.1,
    "solref_perturbation_ratio": 0.1,
    "solimp_perturbation_ratio": 0.1,
    "joint_names": None,
    "randomize_stiffness": True,
    "randomize_frictionloss": True,
    "randomize_damping": True,
    "randomize_armature": True,
    "stiffness_perturbation_ratio": 0.1,
    "frictionloss_perturbation_size": 0.05,
    "damping_perturbation_size": 0.01,
    "armature_perturbation_size": 0.01,
}


def _modder(cls: Any, key: str, args: Any, sim: Any, random_state: Any) -> Any:
    import inspect

    if not isinstance(args, dict):
        raise ModderError(f"{key} must be a dict, got {args!r}")
    valid = [p for p in inspect.signature(cls.__init__).parameters if p not in ("self", "sim", "random_state")]
    unknown = sorted(set(args) - set(valid))
    if unknown:
        raise ModderError(f"{key}: unknown argument(s) {unknown}; valid: {valid}")
    return cls(sim=sim, random_state=random_state, **args)


class DomainRandomizationWrapper(Wrapper):
    """robosuite's ``DomainRandomizationWrapper``: randomizes the env's colours and textures,
    cameras, lights and dynamics (robosuite's modders of :mod:`robosuite_rs.utils.mjmod`
    with their ``*_randomization_args``) on each reset (``randomize_on_reset``) and every
    ``randomize_every_n_steps`` steps (0: only :meth:`randomize_domain`), starting from the
    defaults saved at each reset. Draws come from ``np.random.RandomState(seed)``; without
    a ``seed``, from the env's ``seed`` given to ``make``, else NumPy's global RNG (as
    robosuite). Only this env's model changes.

    Raises:
        ModderError: (a ``ValueError`` that is also robosuite's ``AssertionError``) for a
            seed that is not a non-negative int, a flag that is not a bool, a negative or
            non-integer ``randomize_every_n_steps``, an argument dict with an unknown key,
            an unknown element name, or a perturbation that is negative or not finite; the
            env is then unchanged.
    """

    def __init__(
        self,
        env: Any,
        seed: int | None = None,
        randomize_color: bool = True,
        randomize_camera: bool = True,
        randomize_lighting: bool = True,
        randomize_dynamics: bool = True,
        color_randomization_args: dict[str, Any] = DEFAULT_COLOR_ARGS,
        camera_randomization_args: dict[str, Any] = DEFAULT_CAMERA_ARGS,
        lighting_randomization_args: dict[str, Any] = DEFAULT_LIGHTING_ARGS,
        dynamics_randomization_args: dict[str, Any] = DEFAULT_DYNAMICS_ARGS,
        randomize_on_reset: bool = True,
        randomize_every_n_steps: int = 1,
    ) -> None:
        super().__init__(env)
        for key, value in [
            ("randomize_color", randomize_color),
            ("randomize_camera", randomize_camera),
            ("randomize_lighting", randomize_lighting),
            ("randomize_dynamics", randomize_dynamics),
            ("randomize_on_reset", randomize_on_reset),
        ]:
            if not isinstance(value, (bool, np.bool_)):
                raise ModderError(f"{key} must be a bool, got {value!r}")
        if (
            isinstance(randomize_every_n_steps, (bool, np.bool_))
            or not isinstance(randomize_every_n_steps, (int, np.integer))
            or randomize_every_n_steps < 0
        ):
            raise ModderError(f"randomize_every_n_steps must be an int >= 0, got {randomize_every_n_steps!r}")
        if seed is None:
            base = env.unwrapped if hasattr(env, "unwrapped") else env
            make_args = getattr(base, "_make_args", None)
            env_seed = (make_args[1] if make_args else {}).get("seed")
            random_state = np.random.RandomState(int(env_seed)) if env_seed is not None else None
        else:
            if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)) or seed < 0:
                raise ModderError(f"seed must be an int >= 0 or None, got {seed!r}")
            random_state = np.random.RandomState(int(seed))
        self.seed = seed
        self.random_state = random_state
        self.randomize_color = bool(randomize_color)
        self.randomize_camera = bool(randomize_camera)
        self.randomize_lighting = bool(randomize_lighting)
        self.randomize_dynamics = bool(randomize_dynamics)
        self.color_randomization_args = color_randomization_args
        self.camera_randomization_args = camera_randomization_args
        self.lighting_randomization_args = lighting_randomization_args
        self.dynamics_randomization_args = dynamics_randomization_args
        self.randomize_on_reset = bool(randomize_on_reset)
        self.randomize_every_n_steps = int(randomize_every_n_steps)
        self.step_counter = 0
        self.modders: list[Any] = []
        sim = self.env.sim
        # Every modder is made (and its arguments checked) before anything changes.
        if self.randomize_color:
            self.tex_modder = _modder(
                TextureModder, "color_randomization_args", color_randomization_args, sim, random_state
            )
            self.modders.append(self.tex_modder)
        if self.randomize_camera:
            self.camera_modder = _modder(
                CameraModder, "camera_randomization_args", camera_randomization_args, sim, random_state
            )
            self.modders.append(self.camera_modder)
        if self.randomize_lighting:
            self.light_modder = _modder(
                LightingModder, "lighting_randomization_args", lighting_randomization_args, sim, random_state
            )
            self.modders.append(self.light_modder)
        if self.randomize_dynamics:
            self.dynamics_modder = _modder(
                DynamicsModder, "dynamics_randomization_args", dynamics_randomization_args, sim, random_state
            )
            self.modders.append(self.dynamics_modder)
        self.save_default_domain()

    def reset(self, **kwargs: Any) -> Any:
        """Restores the defaults, resets the env, saves its values as the new defaults and
        (``randomize_on_reset``) randomizes; returns the reset's observations."""
        self.restore_default_domain()
        ret = self.env.reset(**kwargs)
        self.save_default_domain()
        self.step_counter = 0
        for modder in self.modders:
            modder.update_sim(self.env.sim)
        if self.randomize_on_reset:
            self.randomize_domain()
            ret = self.env._get_observations()
        return ret

    def step(self, action: Any) -> Any:
        """Randomizes (every ``randomize_every_n_steps`` steps), then steps the env."""
        self.step_randomization()
        return self.env.step(action)

    def step_randomization(self) -> None:
        """Counts a step and randomizes on every ``randomize_every_n_steps``-th."""
        if self.randomize_every_n_steps > 0 and self.step_counter % self.randomize_every_n_steps == 0:
            self.randomize_domain()
        self.step_counter += 1

    def randomize_domain(self) -> None:
        """Runs every modder's ``randomize()``."""
        for modder in self.modders:
            modder.randomize()

    def save_default_domain(self) -> None:
        """Saves the current values as the defaults."""
        for modder in self.modders:
            modder.save_defaults()

    def restore_default_domain(self) -> None:
        """Writes the saved defaults back."""
        for modder in self.modders:
            modder.restore_defaults()

