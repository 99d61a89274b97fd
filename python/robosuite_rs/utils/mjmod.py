"""robosuite's modders (``robosuite.utils.mjmod``): :class:`LightingModder`,
:class:`CameraModder`, :class:`TextureModder` and :class:`DynamicsModder` change an env's
own model (``env.sim.model``, the ``mujoco.MjModel`` whose memory is the Rust env's) with
robosuite's defaults, ranges and draws: the same ``np.random.RandomState`` gives the
values robosuite's modders give.

Differences from robosuite, where robosuite cannot be followed:

* arguments are checked when a modder is made (unknown names, negative or non-finite
  perturbation sizes, unknown texture variations): :class:`ModderError` (a ``ValueError``
  that is also the ``AssertionError`` robosuite raises), and nothing is changed;
* :class:`DynamicsModder` draws from its ``random_state`` (robosuite's draws from NumPy's
  global RNG whatever ``random_state`` is), so a seed fixes the dynamics too;
* :class:`TextureModder` works on MuJoCo 3.17's ``tex_data`` (robosuite's needs MuJoCo
  3.1.1) and uploads each changed texture to the env's renderers, so frames show it.
"""

from __future__ import annotations

import copy
import math
from typing import Any, Iterable

import numpy as np

from . import transform_utils as trans

__all__ = [
    "ModderError",
    "BaseModder",
    "LightingModder",
    "CameraModder",
    "TextureModder",
    "Texture",
    "DynamicsModder",
    "MJT_TEXTURE_ENUM",
]


class ModderError(ValueError, AssertionError):
    """A modder argument robosuite rejects (or would fail on later): a ``ValueError`` that
    is also the ``AssertionError`` robosuite raises."""


def _check_state(random_state: Any) -> Any:
    if random_state is None:
        return np.random.mtrand._rand
    if not isinstance(random_state, np.random.RandomState):
        raise ModderError(f"random_state must be a numpy.random.RandomState or None, got {type(random_state).__name__}")
    return random_state


def _check_flag(key: str, value: Any) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise ModderError(f"{key} must be a bool, got {value!r}")
    return bool(value)


def _check_size(key: str, value: Any, upper: float | None = None) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ModderError(f"{key} must be a number, got {value!r}") from None
    if isinstance(value, (bool, np.bool_)) or not math.isfinite(v) or v < 0:
        raise ModderError(f"{key} must be a finite number >= 0, got {value!r}")
    if upper is not None and v > upper:
        raise ModderError(f"{key} must be at most {upper}, got {value!r}")
    return v


def _check_names(key: str, given: Any, valid: Iterable[Any], kind: str) -> list[Any]:
    """``given`` (a list of names, or ``None``: every element) checked against ``valid``."""
    valid = list(valid)
    if given is None:
        return valid
    if isinstance(given, str):
        raise ModderError(f"{key} must be a list of {kind} names, got the string {given!r}")
    try:
        names = list(given)
    except TypeError:
        raise ModderError(f"{key} must be a list of {kind} names or None, got {given!r}") from None
    known = set(valid)
    unknown = [n for n in names if n not in known]
    if unknown:
        shown = [n for n in valid if n is not None]
        raise ModderError(f"{key}: unknown {kind} name(s) {unknown}; valid: {shown}")
    return names


class BaseModder:
    """robosuite's ``BaseModder``: a modder of ``sim`` (``env.sim``) drawing from
    ``random_state`` (``None``: NumPy's global RNG, as robosuite).

    Raises:
        ModderError: for a ``random_state`` that is not a ``RandomState``.
    """

    def __init__(self, sim: Any, random_state: Any = None) -> None:
        self.sim = sim
        self.random_state = _check_state(random_state)

    def update_sim(self, sim: Any) -> None:
        """Points the modder at ``sim``."""
        self.sim = sim

    @property
    def model(self) -> Any:
        """The simulator's model."""
        return self.sim.model


class LightingModder(BaseModder):
    """robosuite's ``LightingModder``: each ``randomize()`` sets every light's position
    (default ± ``position_perturbation_size`` per axis), direction (rotated by a random
    axis-angle of at most ``direction_perturbation_size`` radians), specular, ambient and
    diffuse colours (default ± their perturbation sizes) and ``active`` (on or off, even
    odds), each when its ``randomize_*`` flag is set.

    Raises:
        ModderError: for an unknown light name, a flag that is not a bool, or a
            perturbation size that is negative or not finite.
    """

    def __init__(
        self,
        sim: Any,
        random_state: Any = None,
        light_names: Any = None,
        randomize_position: bool = True,
        randomize_direction: bool = True,
        randomize_specular: bool = True,
        randomize_ambient: bool = True,
        randomize_diffuse: bool = True,
        randomize_active: bool = True,
        position_perturbation_size: float = 0.1,
        direction_perturbation_size: float = 0.35,  # 20 degrees
        specular_perturbation_size: float = 0.1,
        ambient_perturbation_size: float = 0.1,
        diffuse_perturbation_size: float = 0.1,
    ) -> None:
        super().__init__(sim, random_state=random_state)
        self.light_names = _check_names("light_names", light_names, sim.model.light_names, "light")
        self.randomize_position = _check_flag("randomize_position", randomize_position)
        self.randomize_direction = _check_flag("randomize_direction", randomize_direction)
        self.randomize_specular = _check_flag("randomize_specular", randomize_specular)
        self.randomize_ambient = _check_flag("randomize_ambient", randomize_ambient)
        self.randomize_diffuse = _check_flag("randomize_diffuse", randomize_diffuse)
        self.randomize_active = _check_flag("randomize_active", randomize_active)
        self.position_perturbation_size = _check_size("position_perturbation_size", position_perturbation_size)
        self.direction_perturbation_size = _check_size("direction_perturbation_size", direction_perturbation_size)
        self.specular_perturbation_size = _check_size("specular_perturbation_size", specular_perturbation_size)
        self.ambient_perturbation_size = _check_size("ambient_perturbation_size", ambient_perturbation_size)
        self.diffuse_perturbation_size = _check_size("diffuse_perturbation_size", diffuse_perturbation_size)
        self.save_defaults()

    def save_defaults(self) -> None:
        """Saves the current values as the defaults perturbations start from."""
        self._defaults: dict[Any, dict[str, Any]] = {k: {} for k in self.light_names}
        for name in self.light_names:
            self._defaults[name]["pos"] = np.array(self.get_pos(name))
            self._defaults[name]["dir"] = np.array(self.get_dir(name))
            self._defaults[name]["specular"] = np.array(self.get_specular(name))
            self._defaults[name]["ambient"] = np.array(self.get_ambient(name))
            self._defaults[name]["diffuse"] = np.array(self.get_diffuse(name))
            self._defaults[name]["active"] = self.get_active(name)

    def restore_defaults(self) -> None:
        """Writes the saved defaults back."""
        for name in self.light_names:
            d = self._defaults[name]
            self.set_pos(name, d["pos"])
            self.set_dir(name, d["dir"])
            self.set_specular(name, d["specular"])
            self.set_ambient(name, d["ambient"])
            self.set_diffuse(name, d["diffuse"])
            self.set_active(name, d["active"])

    def randomize(self) -> None:
        """Randomizes every selected light (robosuite's order of draws)."""
        for name in self.light_names:
            if self.randomize_position:
                self._randomize_position(name)
            if self.randomize_direction:
                self._randomize_direction(name)
            if self.randomize_specular:
                self._randomize_specular(name)
            if self.randomize_ambient:
                self._randomize_ambient(name)
            if self.randomize_diffuse:
                self._randomize_diffuse(name)
            if self.randomize_active:
                self._randomize_active(name)

    def _delta(self, size: float) -> np.ndarray:
        return self.random_state.uniform(low=-size, high=size, size=3)

    def _randomize_position(self, name: Any) -> None:
        self.set_pos(name, self._defaults[name]["pos"] + self._delta(self.position_perturbation_size))

    def _randomize_direction(self, name: Any) -> None:
        axis, angle = trans.random_axis_angle(
            angle_limit=self.direction_perturbation_size, random_state=self.random_state
        )
        rot = trans.quat2mat(trans.axisangle2quat(axis * angle))
        self.set_dir(name, rot.dot(self._defaults[name]["dir"]))

    def _randomize_specular(self, name: Any) -> None:
        self.set_specular(name, self._defaults[name]["specular"] + self._delta(self.specular_perturbation_size))

    def _randomize_ambient(self, name: Any) -> None:
        self.set_ambient(name, self._defaults[name]["ambient"] + self._delta(self.ambient_perturbation_size))

    def _randomize_diffuse(self, name: Any) -> None:
        self.set_diffuse(name, self._defaults[name]["diffuse"] + self._delta(self.diffuse_perturbation_size))

    def _randomize_active(self, name: Any) -> None:
        self.set_active(name, int(self.random_state.uniform() > 0.5))

    def get_lightid(self, name: Any) -> int:
        """The id of light ``name`` (-1 if there is none)."""
        try:
            return self.model.light_name2id(name)
        except ValueError:
            return -1

    def _id(self, name: Any) -> int:
        i = self.get_lightid(name)
        if i < 0:
            raise ModderError(f"Unknown light {name}")
        return i

    @staticmethod
    def _vec3(value: Any) -> list[float]:
        value = list(value)
        if len(value) != 3:
            raise ModderError(f"Expected 3-dim value, got {value}")
        return value

    def get_pos(self, name: Any) -> np.ndarray:
        """The light's position."""
        return self.model.light_pos[self._id(name)]

    def set_pos(self, name: Any, value: Any) -> None:
        """Sets the light's position."""
        self.model.light_pos[self._id(name)] = self._vec3(value)

    def get_dir(self, name: Any) -> np.ndarray:
        """The light's direction."""
        return self.model.light_dir[self._id(name)]

    def set_dir(self, name: Any, value: Any) -> None:
        """Sets the light's direction."""
        self.model.light_dir[self._id(name)] = self._vec3(value)

    def get_active(self, name: Any) -> Any:
        """Whether the light is on (1) or off (0)."""
        return self.model.light_active[self._id(name)]

    def set_active(self, name: Any, value: Any) -> None:
        """Turns the light on (1) or off (0)."""
        self.model.light_active[self._id(name)] = value

    def get_specular(self, name: Any) -> np.ndarray:
        """The light's specular colour."""
        return self.model.light_specular[self._id(name)]

    def set_specular(self, name: Any, value: Any) -> None:
        """Sets the light's specular colour."""
        self.model.light_specular[self._id(name)] = self._vec3(value)

    def get_ambient(self, name: Any) -> np.ndarray:
        """The light's ambient colour."""
        return self.model.light_ambient[self._id(name)]

    def set_ambient(self, name: Any, value: Any) -> None:
        """Sets the light's ambient colour."""
        self.model.light_ambient[self._id(name)] = self._vec3(value)

    def get_diffuse(self, name: Any) -> np.ndarray:
        """The light's diffuse colour."""
        return self.model.light_diffuse[self._id(name)]

    def set_diffuse(self, name: Any, value: Any) -> None:
        """Sets the light's diffuse colour."""
        self.model.light_diffuse[self._id(name)] = self._vec3(value)


class CameraModder(BaseModder):
    """robosuite's ``CameraModder``: each ``randomize()`` sets every camera's position
    (default ± ``position_perturbation_size`` per axis), orientation (the default rotated by
    a random axis-angle of at most ``rotation_perturbation_size`` radians) and ``fovy``
    (default ± ``fovy_perturbation_size`` degrees), each when its flag is set.

    Raises:
        ModderError: for an unknown camera name, no ``randomize_*`` flag set, a flag that
            is not a bool, a perturbation size that is negative or not finite, or a
            ``fovy_perturbation_size`` that could take a camera's ``fovy`` out of
            ``(0, 180)`` degrees.
    """

    def __init__(
        self,
        sim: Any,
        random_state: Any = None,
        camera_names: Any = None,
        randomize_position: bool = True,
        randomize_rotation: bool = True,
        randomize_fovy: bool = True,
        position_perturbation_size: float = 0.01,
        rotation_perturbation_size: float = 0.087,
        fovy_perturbation_size: float = 5.0,
    ) -> None:
        super().__init__(sim, random_state=random_state)
        self.randomize_position = _check_flag("randomize_position", randomize_position)
        self.randomize_rotation = _check_flag("randomize_rotation", randomize_rotation)
        self.randomize_fovy = _check_flag("randomize_fovy", randomize_fovy)
        if not (self.randomize_position or self.randomize_rotation or self.randomize_fovy):
            raise ModderError("CameraModder needs one of randomize_position, randomize_rotation, randomize_fovy")
        self.camera_names = _check_names("camera_names", camera_names, sim.model.camera_names, "camera")
        self.position_perturbation_size = _check_size("position_perturbation_size", position_perturbation_size)
        self.rotation_perturbation_size = _check_size("rotation_perturbation_size", rotation_perturbation_size)
        self.fovy_perturbation_size = _check_size("fovy_perturbation_size", fovy_perturbation_size)
        if self.randomize_fovy:
            size = self.fovy_perturbation_size
            for name in self.camera_names:
                fovy = float(self.model.cam_fovy[self._id(name)])
                if fovy - size <= 0 or fovy + size >= 180:
                    raise ModderError(
                        f"fovy_perturbation_size {size} could take camera {name} (fovy {fovy})"
                        " out of (0, 180) degrees"
                    )
        self.save_defaults()

    def save_defaults(self) -> None:
        """Saves the current values as the defaults perturbations start from."""
        self._defaults: dict[Any, dict[str, Any]] = {k: {} for k in self.camera_names}
        for name in self.camera_names:
            self._defaults[name]["pos"] = np.array(self.get_pos(name))
            self._defaults[name]["quat"] = np.array(self.get_quat(name))
            self._defaults[name]["fovy"] = self.get_fovy(name)

    def restore_defaults(self) -> None:
        """Writes the saved defaults back."""
        for name in self.camera_names:
            self.set_pos(name, self._defaults[name]["pos"])
            self.set_quat(name, self._defaults[name]["quat"])
            self.set_fovy(name, self._defaults[name]["fovy"])

    def randomize(self) -> None:
        """Randomizes every selected camera (robosuite's order of draws)."""
        for name in self.camera_names:
            if self.randomize_position:
                delta = self.random_state.uniform(
                    low=-self.position_perturbation_size, high=self.position_perturbation_size, size=3
                )
                self.set_pos(name, self._defaults[name]["pos"] + delta)
            if self.randomize_rotation:
                axis, angle = trans.random_axis_angle(
                    angle_limit=self.rotation_perturbation_size, random_state=self.random_state
                )
                delta_rot = trans.quat2mat(trans.axisangle2quat(axis * angle))
                base = trans.quat2mat(trans.convert_quat(self._defaults[name]["quat"], to="xyzw"))
                self.set_quat(name, trans.convert_quat(trans.mat2quat(delta_rot.T.dot(base)), to="wxyz"))
            if self.randomize_fovy:
                delta_fovy = self.random_state.uniform(
                    low=-self.fovy_perturbation_size, high=self.fovy_perturbation_size
                )
                self.set_fovy(name, self._defaults[name]["fovy"] + delta_fovy)

    def get_camid(self, name: Any) -> int:
        """The id of camera ``name`` (-1 if there is none)."""
        try:
            return self.model.camera_name2id(name)
        except ValueError:
            return -1

    def _id(self, name: Any) -> int:
        i = self.get_camid(name)
        if i < 0:
            raise ModderError(f"Unknown camera {name}")
        return i

    def get_fovy(self, name: Any) -> float:
        """The camera's vertical field of view (degrees)."""
        return self.model.cam_fovy[self._id(name)]

    def set_fovy(self, name: Any, value: float) -> None:
        """Sets the camera's vertical field of view (degrees, in ``(0, 180)``)."""
        i = self._id(name)
        if not 0 < value < 180:
            raise ModderError(f"fovy must be in (0, 180) degrees, got {value}")
        self.model.cam_fovy[i] = value

    def get_quat(self, name: Any) -> np.ndarray:
        """The camera's orientation ``(w, x, y, z)``."""
        return self.model.cam_quat[self._id(name)]

    def set_quat(self, name: Any, value: Any) -> None:
        """Sets the camera's orientation ``(w, x, y, z)``."""
        value = list(value)
        if len(value) != 4:
            raise ModderError(f"Expected value of length 4, instead got {value}")
        self.model.cam_quat[self._id(name)] = value

    def get_pos(self, name: Any) -> np.ndarray:
        """The camera's position."""
        return self.model.cam_pos[self._id(name)]

    def set_pos(self, name: Any, value: Any) -> None:
        """Sets the camera's position."""
        value = list(value)
        if len(value) != 3:
            raise ModderError(f"Expected value of length 3, instead got {value}")
        self.model.cam_pos[self._id(name)] = value


#: MuJoCo's ``mjtTexture`` names by value.
MJT_TEXTURE_ENUM = ["2d", "cube", "skybox"]


class Texture:
    """One texture of the model (robosuite's ``Texture``): ``id``, ``type``, ``height``,
    ``width`` and ``bitmap``, an H×W×3 uint8 view of its colour channels in the model's
    ``tex_data``."""

    __slots__ = ["id", "type", "height", "width", "tex_adr", "nchannel", "tex_data"]

    def __init__(self, model: Any, tex_id: int) -> None:
        self.id = tex_id
        self.type = MJT_TEXTURE_ENUM[int(model.tex_type[tex_id])]
        self.height = int(model.tex_height[tex_id])
        self.width = int(model.tex_width[tex_id])
        self.tex_adr = int(model.tex_adr[tex_id])
        self.nchannel = int(model.tex_nchannel[tex_id])
        self.tex_data = model.tex_data

    @property
    def bitmap(self) -> np.ndarray:
        """The RGB channels (a view: writing it writes the model)."""
        size = self.height * self.width * self.nchannel
        data = self.tex_data[self.tex_adr : self.tex_adr + size].reshape((self.height, self.width, self.nchannel))
        return data[..., :3]


_TEXTURE_VARIATIONS = ("rgb", "checker", "noise", "gradient")


class TextureModder(BaseModder):
    """robosuite's ``TextureModder``: each ``randomize()`` whitens the materials, then gives
    each geom with a textured material a random texture (one of ``texture_variations``:
    a plain colour, a checker, noise or a gradient; near the default with
    ``randomize_local``), and its material random reflectance, shininess and specular
    (``randomize_material``), each other geom a random colour, and the skybox a random
    texture (``randomize_skybox``). Changed textures are uploaded to the env's renderers.

    Raises:
        ModderError: for an unknown geom name, an unknown or empty ``texture_variations``,
            an interpolation outside ``[0, 1]``, a flag that is not a bool, or
            ``randomize_skybox`` in a model without a skybox texture.
    """

    def __init__(
        self,
        sim: Any,
        random_state: Any = None,
        geom_names: Any = None,
        randomize_local: bool = False,
        randomize_material: bool = False,
        local_rgb_interpolation: float = 0.1,
        local_material_interpolation: float = 0.2,
        texture_variations: Any = ("rgb", "checker", "noise", "gradient"),
        randomize_skybox: bool = True,
    ) -> None:
        super().__init__(sim, random_state=random_state)
        self.geom_names = _check_names("geom_names", geom_names, sim.model.geom_names, "geom")
        self.randomize_local = _check_flag("randomize_local", randomize_local)
        self.randomize_material = _check_flag("randomize_material", randomize_material)
        self.local_rgb_interpolation = _check_size("local_rgb_interpolation", local_rgb_interpolation, 1.0)
        self.local_material_interpolation = _check_size(
            "local_material_interpolation", local_material_interpolation, 1.0
        )
        if isinstance(texture_variations, str):
            texture_variations = [texture_variations]
        variations = list(texture_variations)
        bad = [v for v in variations if v not in _TEXTURE_VARIATIONS]
        if bad or not variations:
            raise ModderError(
                f"texture_variations must be a non-empty list of {list(_TEXTURE_VARIATIONS)}, got {variations}"
            )
        self.texture_variations = variations
        self.randomize_skybox = _check_flag("randomize_skybox", randomize_skybox)
        if self.randomize_skybox and self._skybox_id() < 0:
            raise ModderError("randomize_skybox: the model has no skybox texture")
        callbacks = {"rgb": self.rand_rgb, "checker": self.rand_checker, "noise": self.rand_noise,
                     "gradient": self.rand_gradient}
        self._texture_variation_callbacks = {k: callbacks[k] for k in self.texture_variations}
        # Textures changed during randomize() / restore_defaults(), uploaded once at the end
        # (geoms share textures); None outside those calls (set_texture uploads at once).
        self._pending: set[int] | None = None
        self.save_defaults()

    def save_defaults(self) -> None:
        """Saves the current textures, materials and colours as the defaults."""
        self.textures = [Texture(self.model, i) for i in range(self.model.ntex)]
        self._default_texture_bitmaps = [np.array(t.bitmap) for t in self.textures]
        # Each texture's checker masks, made when first used (robosuite makes them all here).
        self._texture_checker_mats: list[Any] = [None] * len(self.textures)
        self._defaults: dict[Any, dict[str, Any]] = {k: {} for k in self.geom_names}
        if self.randomize_skybox:
            self._defaults["skybox"] = {}
        for name in self.geom_names:
            if self._check_geom_for_texture(name):
                self._defaults[name]["texture"] = self._default_texture_bitmaps[self._name_to_tex_id(name)]
                self._defaults[name]["material"] = self.get_material(name)
            else:
                self._defaults[name]["rgb"] = np.array(self.get_geom_rgb(name))
        if self.randomize_skybox:
            self._defaults["skybox"]["texture"] = self._default_texture_bitmaps[self._name_to_tex_id("skybox")]

    def restore_defaults(self) -> None:
        """Writes the saved defaults back (and uploads the textures)."""
        with self._uploads():
            self._restore_defaults()

    def _uploads(self) -> Any:
        """A context in which changed textures are uploaded once, at its end."""
        import contextlib

        @contextlib.contextmanager
        def batch() -> Any:
            self._pending = set()
            try:
                yield
            finally:
                pending, self._pending = self._pending, None
                native = getattr(self.sim, "_native", None)
                if native is not None:
                    for tex_id in sorted(pending):
                        native.upload_texture(tex_id)

        return batch()

    def _restore_defaults(self) -> None:
        for name in self.geom_names:
            if self._check_geom_for_texture(name):
                self.set_texture(name, self._defaults[name]["texture"], perturb=False)
                self.set_material(name, self._defaults[name]["material"], perturb=False)
            else:
                self.set_geom_rgb(name, self._defaults[name]["rgb"])
        if self.randomize_skybox:
            self.set_texture("skybox", self._defaults["skybox"]["texture"], perturb=False)

    def randomize(self) -> None:
        """Randomizes every selected geom's texture or colour, and the skybox."""
        with self._uploads():
            self._randomize()

    def _randomize(self) -> None:
        self.whiten_materials()
        for name in self.geom_names:
            if self._check_geom_for_texture(name):
                self._randomize_texture(name)
                if self.randomize_material:
                    self._randomize_material(name)
            else:
                self._randomize_geom_color(name)
        if self.randomize_skybox:
            self._randomize_texture("skybox")

    def _randomize_geom_color(self, name: Any) -> None:
        if self.randomize_local:
            random_color = self.random_state.uniform(0, 1, size=3)
            rgb = (1.0 - self.local_rgb_interpolation) * self._defaults[name][
                "rgb"
            ] + self.local_rgb_interpolation * random_color
        else:
            rgb = self.random_state.uniform(0, 1, size=3)
        self.set_geom_rgb(name, rgb)

    def _randomize_texture(self, name: Any) -> None:
        keys = list(self._texture_variation_callbacks.keys())
        choice = keys[self.random_state.randint(len(keys))]
        self._texture_variation_callbacks[choice](name)

    def _randomize_material(self, name: Any) -> None:
        if name == "skybox":
            return
        material = self.random_state.uniform(0, 1, size=3)  # (reflectance, shininess, specular)
        self.set_material(name, material, perturb=self.randomize_local)

    def rand_checker(self, name: Any) -> None:
        """A random checker pattern for ``name``."""
        rgb1, rgb2 = self.get_rand_rgb(2)
        self.set_checker(name, rgb1, rgb2, perturb=self.randomize_local)

    def rand_gradient(self, name: Any) -> None:
        """A random gradient for ``name``."""
        rgb1, rgb2 = self.get_rand_rgb(2)
        vertical = bool(self.random_state.uniform() > 0.5)
        self.set_gradient(name, rgb1, rgb2, vertical=vertical, perturb=self.randomize_local)

    def rand_rgb(self, name: Any) -> None:
        """A random plain colour for ``name``."""
        self.set_rgb(name, self.get_rand_rgb(), perturb=self.randomize_local)

    def rand_noise(self, name: Any) -> None:
        """A random noise pattern for ``name``."""
        fraction = 0.1 + self.random_state.uniform() * 0.8
        rgb1, rgb2 = self.get_rand_rgb(2)
        self.set_noise(name, rgb1, rgb2, fraction, perturb=self.randomize_local)

    def whiten_materials(self) -> None:
        """Sets the selected geoms' colours, and their materials', to white."""
        for name in self.geom_names:
            geom_id = self.model.geom_name2id(name)
            self.model.geom_rgba[geom_id, :] = 1.0
            if self._check_geom_for_texture(name):
                self.model.mat_rgba[self.model.geom_matid[geom_id], :] = 1.0

    def get_geom_rgb(self, name: Any) -> np.ndarray:
        """The geom's colour."""
        return self.model.geom_rgba[self.model.geom_name2id(name), :3]

    def set_geom_rgb(self, name: Any, rgb: Any) -> None:
        """Sets the geom's colour."""
        self.model.geom_rgba[self.model.geom_name2id(name), :3] = rgb

    def get_rand_rgb(self, n: int = 1) -> Any:
        """One random uint8 colour, or a tuple of ``n``."""

        def _rand_rgb() -> np.ndarray:
            return np.array(self.random_state.uniform(size=3) * 255, dtype=np.uint8)

        if n == 1:
            return _rand_rgb()
        return tuple(_rand_rgb() for _ in range(n))

    def get_texture(self, name: Any) -> Texture:
        """The texture of geom ``name`` (or ``"skybox"``)."""
        return self.textures[self._name_to_tex_id(name)]

    def set_texture(self, name: Any, bitmap: Any, perturb: bool = False) -> None:
        """Writes ``bitmap`` (H×W×3) into the texture of ``name`` (with ``perturb``, blended
        into the default by ``local_rgb_interpolation``) and uploads it."""
        bitmap_to_set = self.get_texture(name).bitmap
        if perturb:
            bitmap = (1.0 - self.local_rgb_interpolation) * self._defaults[name][
                "texture"
            ] + self.local_rgb_interpolation * bitmap
        bitmap_to_set[:] = bitmap
        self.upload_texture(name)

    def get_material(self, name: Any) -> np.ndarray:
        """``(reflectance, shininess, specular)`` of the geom's material."""
        mat_id = self._name_to_mat_id(name)
        m = self.model
        return np.array((m.mat_reflectance[mat_id], m.mat_shininess[mat_id], m.mat_specular[mat_id]))

    def set_material(self, name: Any, material: Any, perturb: bool = False) -> None:
        """Sets ``(reflectance, shininess, specular)`` of the geom's material (with
        ``perturb``, blended into the default by ``local_material_interpolation``)."""
        mat_id = self._name_to_mat_id(name)
        if perturb:
            material = (1.0 - self.local_material_interpolation) * self._defaults[name][
                "material"
            ] + self.local_material_interpolation * material
        self.model.mat_reflectance[mat_id] = material[0]
        self.model.mat_shininess[mat_id] = material[1]
        self.model.mat_specular[mat_id] = material[2]

    def get_checker_matrices(self, name: Any) -> Any:
        """The two checker masks of the texture of ``name``."""
        tex_id = self._name_to_tex_id(name)
        if self._texture_checker_mats[tex_id] is None:
            t = self.textures[tex_id]
            self._texture_checker_mats[tex_id] = self._make_checker_matrices(t.height, t.width)
        return self._texture_checker_mats[tex_id]

    def set_checker(self, name: Any, rgb1: Any, rgb2: Any, perturb: bool = False) -> None:
        """A checker pattern of ``rgb1`` and ``rgb2``."""
        cbd1, cbd2 = self.get_checker_matrices(name)
        rgb1 = np.asarray(rgb1).reshape([1, 1, -1])
        rgb2 = np.asarray(rgb2).reshape([1, 1, -1])
        self.set_texture(name, rgb1 * cbd1 + rgb2 * cbd2, perturb=perturb)

    def set_gradient(self, name: Any, rgb1: Any, rgb2: Any, vertical: bool = True, perturb: bool = False) -> None:
        """A linear gradient from ``rgb1`` to ``rgb2`` (along y with ``vertical``, else x)."""
        bitmap = self.get_texture(name).bitmap
        h, w = bitmap.shape[:2]
        p = np.tile(np.linspace(0, 1, h)[:, None], (1, w)) if vertical else np.tile(np.linspace(0, 1, w), (h, 1))
        new_bitmap = np.zeros_like(bitmap)
        for i in range(3):
            new_bitmap[..., i] = rgb2[i] * p + rgb1[i] * (1.0 - p)
        self.set_texture(name, new_bitmap, perturb=perturb)

    def set_rgb(self, name: Any, rgb: Any, perturb: bool = False) -> None:
        """A plain colour."""
        new_bitmap = np.zeros_like(self.get_texture(name).bitmap)
        new_bitmap[..., :] = np.asarray(rgb)
        self.set_texture(name, new_bitmap, perturb=perturb)

    def set_noise(self, name: Any, rgb1: Any, rgb2: Any, fraction: float = 0.9, perturb: bool = False) -> None:
        """``rgb1`` with a ``fraction`` of the pixels ``rgb2``."""
        bitmap = self.get_texture(name).bitmap
        h, w = bitmap.shape[:2]
        mask = self.random_state.uniform(size=(h, w)) < fraction
        new_bitmap = np.zeros_like(bitmap)
        new_bitmap[..., :] = np.asarray(rgb1)
        new_bitmap[mask, :] = np.asarray(rgb2)
        self.set_texture(name, new_bitmap, perturb=perturb)

    def upload_texture(self, name: Any, device_id: int = 0) -> None:
        """Uploads the texture of ``name`` to the env's renderers (MuJoCo's
        ``mjr_uploadTexture``), so that frames show it."""
        tex_id = self.get_texture(name).id
        if self._pending is not None:
            self._pending.add(tex_id)
            return
        native = getattr(self.sim, "_native", None)
        if native is not None:
            native.upload_texture(tex_id)

    def _check_geom_for_texture(self, name: Any) -> bool:
        geom_id = self.model.geom_name2id(name)
        mat_id = self.model.geom_matid[geom_id]
        return bool(mat_id >= 0 and self.model.mat_texid[mat_id].max() >= 0)

    def _skybox_id(self) -> int:
        found = -1
        for tex_id in range(self.model.ntex):
            if self.model.tex_type[tex_id] == 2:  # mjTEXTURE_SKYBOX
                found = tex_id
        return found

    def _name_to_tex_id(self, name: Any) -> int:
        if name == "skybox":
            return self._skybox_id()
        if not self._check_geom_for_texture(name):
            raise ModderError(f"geom {name} has no textured material")
        mat_id = self.model.geom_matid[self.model.geom_name2id(name)]
        return int(_mat_texid(self.model, mat_id))

    def _name_to_mat_id(self, name: Any) -> int:
        if name == "skybox":
            raise ValueError("Error: skybox has no material!")
        if not self._check_geom_for_texture(name):
            raise ModderError(f"geom {name} has no textured material")
        return int(self.model.geom_matid[self.model.geom_name2id(name)])

    @staticmethod
    def _make_checker_matrices(h: int, w: int) -> tuple[np.ndarray, np.ndarray]:
        re = np.r_[((w + 1) // 2) * [0, 1]]
        ro = np.r_[((w + 1) // 2) * [1, 0]]
        cbd1 = np.expand_dims(np.vstack(((h + 1) // 2) * [re, ro]), -1)[:h, :w]
        cbd2 = np.expand_dims(np.vstack(((h + 1) // 2) * [ro, re]), -1)[:h, :w]
        return cbd1, cbd2


def _mat_texid(model: Any, mat_id: int) -> int:
    """The texture of material ``mat_id``: MuJoCo 3's ``mat_texid`` has one slot per texture
    role; the first one set (the RGB role first) is the one robosuite's modder changes."""
    ids = np.atleast_1d(model.mat_texid[mat_id])
    for t in ids:
        if t >= 0:
            return int(t)
    return -1


class DynamicsModder(BaseModder):
    """robosuite's ``DynamicsModder``: each ``randomize()`` perturbs, from the defaults,
    the medium's density and viscosity, every selected body's position, orientation,
    inertia and mass, every selected geom's friction, solref and solimp, and every selected
    joint's stiffness, frictionloss, damping and armature (sizes are added, ratios scale;
    robosuite's clips), then runs ``mj_forward``. Bodies without mass keep mass and
    inertia; free joints keep frictionloss, damping and armature; joints without stiffness
    keep it (as robosuite). Draws come from ``random_state``.

    Raises:
        ModderError: for an unknown body, geom or joint name, a flag that is not a bool,
            or a perturbation size or ratio that is negative or not finite.
    """

    def __init__(
        self,
        sim: Any,
        random_state: Any = None,
        # Opt parameters
        randomize_density: bool = True,
        randomize_viscosity: bool = True,
        density_perturbation_ratio: float = 0.1,
        viscosity_perturbation_ratio: float = 0.1,
        # Body parameters
        body_names: Any = None,
        randomize_position: bool = True,
        randomize_quaternion: bool = True,
        randomize_inertia: bool = True,
        randomize_mass: bool = True,
        position_perturbation_size: float = 0.02,
        quaternion_perturbation_size: float = 0.02,
        inertia_perturbation_ratio: float = 0.02,
        mass_perturbation_ratio: float = 0.02,
        # Geom parameters
        geom_names: Any = None,
        randomize_friction: bool = True,
        randomize_solref: bool = True,
        randomize_solimp: bool = True,
        friction_perturbation_ratio: float = 0.1,
        solref_perturbation_ratio: float = 0.1,
        solimp_perturbation_ratio: float = 0.1,
        # Joint parameters
        joint_names: Any = None,
        randomize_stiffness: bool = True,
        randomize_frictionloss: bool = True,
        randomize_damping: bool = True,
        randomize_armature: bool = True,
        stiffness_perturbation_ratio: float = 0.1,
        frictionloss_perturbation_size: float = 0.05,
        damping_perturbation_size: float = 0.01,
        armature_perturbation_size: float = 0.01,
    ) -> None:
        super().__init__(sim=sim, random_state=random_state)
        m = sim.model
        self.body_names = _check_names("body_names", body_names, m.body_names, "body")
        self.geom_names = _check_names("geom_names", geom_names, m.geom_names, "geom")
        self.joint_names = _check_names("joint_names", joint_names, m.joint_names, "joint")
        f, s = _check_flag, _check_size
        inf = np.inf

        def spec(flag: str, fv: Any, key: str, kv: Any, kind: str, clip: tuple[float, float]) -> dict[str, Any]:
            return {"randomize": f(flag, fv), "perturbation": s(key, kv), "type": kind, "clip": clip}

        self.opt_randomizations = {
            "density": spec("randomize_density", randomize_density, "density_perturbation_ratio",
                            density_perturbation_ratio, "ratio", (0.0, inf)),
            "viscosity": spec("randomize_viscosity", randomize_viscosity, "viscosity_perturbation_ratio",
                              viscosity_perturbation_ratio, "ratio", (0.0, inf)),
        }
        self.body_randomizations = {
            "position": spec("randomize_position", randomize_position, "position_perturbation_size",
                             position_perturbation_size, "size", (-inf, inf)),
            "quaternion": spec("randomize_quaternion", randomize_quaternion, "quaternion_perturbation_size",
                               quaternion_perturbation_size, "size", (-inf, inf)),
            "inertia": spec("randomize_inertia", randomize_inertia, "inertia_perturbation_ratio",
                            inertia_perturbation_ratio, "ratio", (0.0, inf)),
            "mass": spec("randomize_mass", randomize_mass, "mass_perturbation_ratio", mass_perturbation_ratio,
                         "ratio", (0.0, inf)),
        }
        self.geom_randomizations = {
            "friction": spec("randomize_friction", randomize_friction, "friction_perturbation_ratio",
                             friction_perturbation_ratio, "ratio", (0.0, inf)),
            "solref": spec("randomize_solref", randomize_solref, "solref_perturbation_ratio",
                           solref_perturbation_ratio, "ratio", (0.0, 1.0)),
            "solimp": spec("randomize_solimp", randomize_solimp, "solimp_perturbation_ratio",
                           solimp_perturbation_ratio, "ratio", (0.0, inf)),
        }
        self.joint_randomizations = {
            "stiffness": spec("randomize_stiffness", randomize_stiffness, "stiffness_perturbation_ratio",
                              stiffness_perturbation_ratio, "ratio", (0.0, inf)),
            "frictionloss": spec("randomize_frictionloss", randomize_frictionloss, "frictionloss_perturbation_size",
                                 frictionloss_perturbation_size, "size", (0.0, inf)),
            "damping": spec("randomize_damping", randomize_damping, "damping_perturbation_size",
                            damping_perturbation_size, "size", (0.0, inf)),
            "armature": spec("randomize_armature", randomize_armature, "armature_perturbation_size",
                             armature_perturbation_size, "size", (0.0, inf)),
        }
        self.dummy_bodies = {n for n in m.body_names if m.body_mass[m.body_name2id(n)] == 0}
        self.save_defaults()

    def _dofs(self, joint_id: int) -> list[int]:
        return [i for i, v in enumerate(self.model.dof_jntid) if v == joint_id]

    def save_defaults(self) -> None:
        """Saves the current values as the defaults perturbations start from."""
        m = self.model
        self.opt_defaults = {None: {"density": m.opt.density, "viscosity": m.opt.viscosity}}
        self.body_defaults = {}
        for name in m.body_names:
            i = m.body_name2id(name)
            self.body_defaults[name] = {
                "position": np.array(m.body_pos[i]),
                "quaternion": np.array(m.body_quat[i]),
                "inertia": np.array(m.body_inertia[i]),
                "mass": m.body_mass[i],
            }
        self.geom_defaults = {}
        for name in m.geom_names:
            i = m.geom_name2id(name)
            self.geom_defaults[name] = {
                "friction": np.array(m.geom_friction[i]),
                "solref": np.array(m.geom_solref[i]),
                "solimp": np.array(m.geom_solimp[i]),
            }
        self.joint_defaults = {}
        for name in m.joint_names:
            i = m.joint_name2id(name)
            dofs = self._dofs(i)
            self.joint_defaults[name] = {
                "stiffness": m.jnt_stiffness[i],
                "frictionloss": np.array(m.dof_frictionloss[dofs]),
                "damping": np.array(m.dof_damping[dofs]),
                "armature": np.array(m.dof_armature[dofs]),
            }

    def restore_defaults(self) -> None:
        """Writes the saved defaults back and runs ``mj_forward``."""
        for group in (self.opt_defaults, self.body_defaults, self.geom_defaults, self.joint_defaults):
            for name, defaults in group.items():
                for attr, default_val in defaults.items():
                    self.mod(name=name, attr=attr, val=default_val)
        self.update()

    def randomize(self) -> None:
        """Randomizes every enabled parameter of the selected elements (robosuite's order
        of draws) and runs ``mj_forward``."""
        for group_defaults, group_randomizations, names in zip(
            (self.opt_defaults, self.body_defaults, self.geom_defaults, self.joint_defaults),
            (self.opt_randomizations, self.body_randomizations, self.geom_randomizations, self.joint_randomizations),
            ([None], self.body_names, self.geom_names, self.joint_names),
        ):
            for name in names:
                for attr, default_val in group_defaults[name].items():
                    val = copy.copy(default_val)
                    settings = group_randomizations[attr]
                    if settings["randomize"]:
                        rs = self.random_state
                        perturbation = rs.rand() if np.ndim(val) == 0 else rs.rand(*np.shape(val))
                        perturbation = settings["perturbation"] * (-1 + 2 * perturbation)
                        val = val + perturbation if settings["type"] == "size" else val * (1.0 + perturbation)
                        val = np.clip(val, *settings["clip"])
                    self.mod(name=name, attr=attr, val=val)
        self.update()

    def update_sim(self, sim: Any) -> None:
        """Points the modder at ``sim`` and saves its values as the defaults."""
        super().update_sim(sim=sim)
        self.save_defaults()

    def update(self) -> None:
        """Runs ``mj_forward`` so the changes take effect."""
        self.sim.forward()

    @property
    def dynamics_parameters(self) -> set[str]:
        """Every parameter :meth:`mod` changes."""
        return {"density", "viscosity", "position", "quaternion", "inertia", "mass", "friction", "solref",
                "solimp", "stiffness", "frictionloss", "damping", "armature"}

    def mod(self, name: Any, attr: str, val: Any) -> None:
        """Sets parameter ``attr`` of element ``name`` (``None`` for density and viscosity).

        Raises:
            ModderError: for an unknown parameter.
        """
        if attr not in self.dynamics_parameters:
            raise ModderError(
                f"Invalid dynamics parameter specified! Supported parameters are: {sorted(self.dynamics_parameters)};"
                f" requested: {attr}"
            )
        getattr(self, f"mod_{attr}")(name, val)

    def mod_density(self, name: Any = None, val: float = 0.0) -> None:
        """The medium's density."""
        if name is not None:
            raise ModderError("No name should be specified if modding density!")
        self.model.opt.density = val

    def mod_viscosity(self, name: Any = None, val: float = 0.0) -> None:
        """The medium's viscosity."""
        if name is not None:
            raise ModderError("No name should be specified if modding viscosity!")
        self.model.opt.viscosity = val

    def mod_position(self, name: Any, val: Any = (0, 0, 0)) -> None:
        """The body's position in its parent."""
        self.model.body_pos[self.model.body_name2id(name)] = np.array(val)

    def mod_quaternion(self, name: Any, val: Any = (1, 0, 0, 0)) -> None:
        """The body's orientation in its parent (normalized)."""
        val = np.array(val) / np.linalg.norm(val)
        self.model.body_quat[self.model.body_name2id(name)] = val

    def mod_inertia(self, name: Any, val: Any) -> None:
        """The body's diagonal inertia (not for bodies without mass)."""
        if name not in self.dummy_bodies:
            self.model.body_inertia[self.model.body_name2id(name)] = np.array(val)

    def mod_mass(self, name: Any, val: float) -> None:
        """The body's mass (not for bodies without mass)."""
        if name not in self.dummy_bodies:
            self.model.body_mass[self.model.body_name2id(name)] = val

    def mod_friction(self, name: Any, val: Any) -> None:
        """The geom's (sliding, torsional, rolling) friction."""
        self.model.geom_friction[self.model.geom_name2id(name)] = np.array(val)

    def mod_solref(self, name: Any, val: Any) -> None:
        """The geom's solref."""
        self.model.geom_solref[self.model.geom_name2id(name)] = np.array(val)

    def mod_solimp(self, name: Any, val: Any) -> None:
        """The geom's solimp."""
        self.model.geom_solimp[self.model.geom_name2id(name)] = np.array(val)

    def mod_stiffness(self, name: Any, val: float) -> None:
        """The joint's stiffness (only a joint with stiffness)."""
        i = self.model.joint_name2id(name)
        if self.model.jnt_stiffness[i] != 0:
            self.model.jnt_stiffness[i] = val

    def _mod_dof(self, array: str, name: Any, val: Any) -> None:
        i = self.model.joint_name2id(name)
        if self.model.jnt_type[i] != 0:  # not a free joint
            getattr(self.model, array)[self._dofs(i)] = val

    def mod_frictionloss(self, name: Any, val: Any) -> None:
        """The joint's frictionloss (not a free joint's)."""
        self._mod_dof("dof_frictionloss", name, val)

    def mod_damping(self, name: Any, val: Any) -> None:
        """The joint's damping (not a free joint's)."""
        self._mod_dof("dof_damping", name, val)

    def mod_armature(self, name: Any, val: Any) -> None:
        """The joint's armature (not a free joint's)."""
        self._mod_dof("dof_armature", name, val)

    @property
    def opt(self) -> Any:
        """The model's options."""
        return self.model.opt
