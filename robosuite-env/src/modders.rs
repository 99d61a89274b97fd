//! robosuite's modders (`robosuite.utils.mjmod`): [`LightingModder`], [`CameraModder`],
//! [`TextureModder`] and [`DynamicsModder`] change one env's own model with robosuite's
//! defaults, ranges and order of draws. [`DomainRandomizationWrapper`](crate::wrappers::DomainRandomizationWrapper)
//! runs them on an env; they can also be used alone on a [`Sim`].
//!
//! Each modder is made from its arguments (robosuite's defaults are the [`Default`]s; the
//! wrapper's, which differ from the modders' own for colour and dynamics), checks them
//! against the model (unknown names, negative or non-finite perturbations: a typed error,
//! nothing changed) and saves the model's current values as the defaults its
//! perturbations start from. Draws come from the [`EnvRng`] passed to `randomize`, so the
//! same RNG state gives the same domain. Writes go to the simulator's own model (the
//! private, copy-on-write path of [`Sim`]): another env made from the same configuration
//! never sees them.

use crate::sim::Sim;
use gym_core::{EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::{MjModel, MjtObjBase as mjtObj, MjtTexture};
use nalgebra::{Matrix3, Quaternion, Rotation3, Unit, UnitQuaternion, Vector3};
use rand::RngExt;
use rand_distr::StandardNormal;

/// `u` in `[lo, hi)` (NumPy's `uniform(lo, hi)`).
fn uniform(rng: &mut EnvRng, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * rng.random::<f64>()
}

/// Three draws in `[-size, size)`.
fn delta3(rng: &mut EnvRng, size: f64) -> [f64; 3] {
    std::array::from_fn(|_| uniform(rng, -size, size))
}

/// robosuite's `random_axis_angle(angle_limit)`: an axis uniform on the sphere, an angle
/// in `[0, angle_limit)`, as a rotation matrix.
fn random_rotation(rng: &mut EnvRng, angle_limit: f64) -> Matrix3<f64> {
    let axis = Vector3::from_fn(|_, _| rng.sample::<f64, _>(StandardNormal));
    let angle = uniform(rng, 0.0, angle_limit);
    match Unit::try_new(axis, 1e-12) {
        Some(axis) => *Rotation3::from_axis_angle(&axis, angle).matrix(),
        None => Matrix3::identity(),
    }
}

/// A perturbation size or ratio: finite and `>= 0`.
fn check_size(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid_argument(
            key,
            format!("must be a finite number >= 0, got {value}"),
        ))
    }
}

/// The ids of `given` names of `kind` (every element, named or not, for `None`).
fn check_names(
    model: &MjModel,
    key: &str,
    kind: mjtObj,
    what: &str,
    count: usize,
    given: Option<&[String]>,
) -> Result<Vec<usize>> {
    let Some(given) = given else {
        return Ok((0..count).collect());
    };
    let unknown: Vec<&str> = given
        .iter()
        .filter(|n| n.contains('\0') || model.name_to_id(kind, n).is_none())
        .map(String::as_str)
        .collect();
    if !unknown.is_empty() {
        let valid: Vec<&str> = (0..count)
            .filter_map(|i| model.id_to_name(kind, i))
            .collect();
        return Err(Error::invalid_argument(
            key,
            format!(
                "unknown {what} name(s) {unknown:?}; valid: {}",
                valid.join(", ")
            ),
        ));
    }
    Ok(given
        .iter()
        .filter_map(|n| model.name_to_id(kind, n))
        .collect())
}

// --- LightingModder -------------------------------------------------------------------

/// robosuite's `LightingModder` arguments (its defaults).
#[derive(Debug, Clone, PartialEq)]
pub struct LightingArgs {
    /// The lights to randomize (`None`: every light).
    pub light_names: Option<Vec<String>>,
    /// Perturb each light's position.
    pub randomize_position: bool,
    /// Rotate each light's direction.
    pub randomize_direction: bool,
    /// Perturb the specular colour.
    pub randomize_specular: bool,
    /// Perturb the ambient colour.
    pub randomize_ambient: bool,
    /// Perturb the diffuse colour.
    pub randomize_diffuse: bool,
    /// Turn each light on or off (even odds).
    pub randomize_active: bool,
    /// Position: default ± this per axis (0.1).
    pub position_perturbation_size: f64,
    /// Direction: rotated by at most this angle in radians (0.35, 20°).
    pub direction_perturbation_size: f64,
    /// Specular colour: default ± this per channel (0.1).
    pub specular_perturbation_size: f64,
    /// Ambient colour: default ± this per channel (0.1).
    pub ambient_perturbation_size: f64,
    /// Diffuse colour: default ± this per channel (0.1).
    pub diffuse_perturbation_size: f64,
}

impl Default for LightingArgs {
    fn default() -> Self {
        Self {
            light_names: None,
            randomize_position: true,
            randomize_direction: true,
            randomize_specular: true,
            randomize_ambient: true,
            randomize_diffuse: true,
            randomize_active: true,
            position_perturbation_size: 0.1,
            direction_perturbation_size: 0.35,
            specular_perturbation_size: 0.1,
            ambient_perturbation_size: 0.1,
            diffuse_perturbation_size: 0.1,
        }
    }
}

#[derive(Debug, Clone)]
struct LightDefaults {
    pos: [f64; 3],
    dir: [f64; 3],
    specular: [f32; 3],
    ambient: [f32; 3],
    diffuse: [f32; 3],
    active: bool,
}

/// robosuite's `LightingModder`: each [`LightingModder::randomize`] sets every selected
/// light's position, direction, specular / ambient / diffuse colours and `active` from its
/// defaults (see [`LightingArgs`]).
#[derive(Debug, Clone)]
pub struct LightingModder {
    args: LightingArgs,
    lights: Vec<usize>,
    defaults: Vec<LightDefaults>,
}

impl LightingModder {
    /// A modder of `model`'s lights, its current values saved as the defaults.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an unknown light name or a perturbation size that is
    /// negative or not finite.
    pub fn new(model: &MjModel, args: LightingArgs) -> Result<Self> {
        for (key, v) in [
            (
                "position_perturbation_size",
                args.position_perturbation_size,
            ),
            (
                "direction_perturbation_size",
                args.direction_perturbation_size,
            ),
            (
                "specular_perturbation_size",
                args.specular_perturbation_size,
            ),
            ("ambient_perturbation_size", args.ambient_perturbation_size),
            ("diffuse_perturbation_size", args.diffuse_perturbation_size),
        ] {
            check_size(key, v)?;
        }
        let n = model.ffi().nlight.max(0) as usize;
        let lights = check_names(
            model,
            "light_names",
            mjtObj::mjOBJ_LIGHT,
            "light",
            n,
            args.light_names.as_deref(),
        )?;
        let mut modder = Self {
            args,
            lights,
            defaults: Vec::new(),
        };
        modder.save_defaults(model);
        Ok(modder)
    }

    /// The arguments.
    pub fn args(&self) -> &LightingArgs {
        &self.args
    }

    /// The ids of the lights it randomizes.
    pub fn lights(&self) -> &[usize] {
        &self.lights
    }

    /// Saves `model`'s current values as the defaults.
    pub fn save_defaults(&mut self, model: &MjModel) {
        self.defaults = self
            .lights
            .iter()
            .map(|&i| LightDefaults {
                pos: model.light_pos()[i],
                dir: model.light_dir()[i],
                specular: model.light_specular()[i],
                ambient: model.light_ambient()[i],
                diffuse: model.light_diffuse()[i],
                active: model.light_active()[i],
            })
            .collect();
    }

    /// Writes the saved defaults back.
    pub fn restore_defaults(&self, sim: &mut Sim) {
        let m = sim.model_mut();
        for (&i, d) in self.lights.iter().zip(&self.defaults) {
            m.light_pos_mut()[i] = d.pos;
            m.light_dir_mut()[i] = d.dir;
            m.light_specular_mut()[i] = d.specular;
            m.light_ambient_mut()[i] = d.ambient;
            m.light_diffuse_mut()[i] = d.diffuse;
            m.light_active_mut()[i] = d.active;
        }
    }

    /// Randomizes every selected light (robosuite's order of draws).
    pub fn randomize(&self, sim: &mut Sim, rng: &mut EnvRng) {
        let a = &self.args;
        let m = sim.model_mut();
        let colour = |rng: &mut EnvRng, base: [f32; 3], size: f64| -> [f32; 3] {
            let d = delta3(rng, size);
            std::array::from_fn(|k| (f64::from(base[k]) + d[k]) as f32)
        };
        for (&i, d) in self.lights.iter().zip(&self.defaults) {
            if a.randomize_position {
                let delta = delta3(rng, a.position_perturbation_size);
                m.light_pos_mut()[i] = std::array::from_fn(|k| d.pos[k] + delta[k]);
            }
            if a.randomize_direction {
                let rot = random_rotation(rng, a.direction_perturbation_size);
                let dir = rot * Vector3::from(d.dir);
                m.light_dir_mut()[i] = [dir.x, dir.y, dir.z];
            }
            if a.randomize_specular {
                m.light_specular_mut()[i] = colour(rng, d.specular, a.specular_perturbation_size);
            }
            if a.randomize_ambient {
                m.light_ambient_mut()[i] = colour(rng, d.ambient, a.ambient_perturbation_size);
            }
            if a.randomize_diffuse {
                m.light_diffuse_mut()[i] = colour(rng, d.diffuse, a.diffuse_perturbation_size);
            }
            if a.randomize_active {
                m.light_active_mut()[i] = rng.random::<f64>() > 0.5;
            }
        }
    }
}

// --- CameraModder ---------------------------------------------------------------------

/// robosuite's camera randomization arguments (`DEFAULT_CAMERA_ARGS`).
#[derive(Debug, Clone, PartialEq)]
pub struct CameraArgs {
    /// The cameras to randomize (`None`: every camera).
    pub camera_names: Option<Vec<String>>,
    /// Perturb each camera's position.
    pub randomize_position: bool,
    /// Rotate each camera.
    pub randomize_rotation: bool,
    /// Perturb each camera's vertical field of view.
    pub randomize_fovy: bool,
    /// Position: default ± this per axis (0.01).
    pub position_perturbation_size: f64,
    /// Orientation: rotated by at most this angle in radians (0.087, 5°).
    pub rotation_perturbation_size: f64,
    /// `fovy`: default ± this many degrees (5).
    pub fovy_perturbation_size: f64,
}

impl Default for CameraArgs {
    fn default() -> Self {
        Self {
            camera_names: None,
            randomize_position: true,
            randomize_rotation: true,
            randomize_fovy: true,
            position_perturbation_size: 0.01,
            rotation_perturbation_size: 0.087,
            fovy_perturbation_size: 5.0,
        }
    }
}

/// robosuite's `CameraModder`: each [`CameraModder::randomize`] sets every selected
/// camera's position, orientation and `fovy` from its defaults (see [`CameraArgs`]).
#[derive(Debug, Clone)]
pub struct CameraModder {
    args: CameraArgs,
    cameras: Vec<usize>,
    defaults: Vec<([f64; 3], [f64; 4], f64)>,
}

impl CameraModder {
    /// A modder of `model`'s cameras, its current values saved as the defaults.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an unknown camera name, no `randomize_*` flag set, a
    /// perturbation size that is negative or not finite, or a `fovy_perturbation_size`
    /// that could take a selected camera's `fovy` out of `(0, 180)` degrees.
    pub fn new(model: &MjModel, args: CameraArgs) -> Result<Self> {
        if !(args.randomize_position || args.randomize_rotation || args.randomize_fovy) {
            return Err(Error::invalid_argument(
                "camera_randomization_args",
                "CameraModder needs one of randomize_position, randomize_rotation, randomize_fovy",
            ));
        }
        check_size(
            "position_perturbation_size",
            args.position_perturbation_size,
        )?;
        check_size(
            "rotation_perturbation_size",
            args.rotation_perturbation_size,
        )?;
        check_size("fovy_perturbation_size", args.fovy_perturbation_size)?;
        let n = model.ffi().ncam.max(0) as usize;
        let cameras = check_names(
            model,
            "camera_names",
            mjtObj::mjOBJ_CAMERA,
            "camera",
            n,
            args.camera_names.as_deref(),
        )?;
        if args.randomize_fovy {
            let s = args.fovy_perturbation_size;
            if let Some(&bad) = cameras.iter().find(|&&c| {
                let f = model.cam_fovy()[c];
                f - s <= 0.0 || f + s >= 180.0
            }) {
                return Err(Error::invalid_argument(
                    "fovy_perturbation_size",
                    format!(
                        "{s} could take camera `{}` (fovy {}) out of (0, 180) degrees",
                        model.id_to_name(mjtObj::mjOBJ_CAMERA, bad).unwrap_or("?"),
                        model.cam_fovy()[bad]
                    ),
                ));
            }
        }
        let mut modder = Self {
            args,
            cameras,
            defaults: Vec::new(),
        };
        modder.save_defaults(model);
        Ok(modder)
    }

    /// The arguments.
    pub fn args(&self) -> &CameraArgs {
        &self.args
    }

    /// The ids of the cameras it randomizes.
    pub fn cameras(&self) -> &[usize] {
        &self.cameras
    }

    /// Saves `model`'s current values as the defaults.
    pub fn save_defaults(&mut self, model: &MjModel) {
        self.defaults = self
            .cameras
            .iter()
            .map(|&i| (model.cam_pos()[i], model.cam_quat()[i], model.cam_fovy()[i]))
            .collect();
    }

    /// Writes the saved defaults back.
    pub fn restore_defaults(&self, sim: &mut Sim) {
        let m = sim.model_mut();
        for (&i, &(pos, quat, fovy)) in self.cameras.iter().zip(&self.defaults) {
            m.cam_pos_mut()[i] = pos;
            m.cam_quat_mut()[i] = quat;
            m.cam_fovy_mut()[i] = fovy;
        }
    }

    /// Randomizes every selected camera (robosuite's order of draws).
    pub fn randomize(&self, sim: &mut Sim, rng: &mut EnvRng) {
        let a = &self.args;
        let m = sim.model_mut();
        for (&i, &(pos, quat, fovy)) in self.cameras.iter().zip(&self.defaults) {
            if a.randomize_position {
                let d = delta3(rng, a.position_perturbation_size);
                m.cam_pos_mut()[i] = std::array::from_fn(|k| pos[k] + d[k]);
            }
            if a.randomize_rotation {
                let delta = random_rotation(rng, a.rotation_perturbation_size);
                let base = UnitQuaternion::from_quaternion(Quaternion::new(
                    quat[0], quat[1], quat[2], quat[3],
                ));
                let rot = delta.transpose() * base.to_rotation_matrix().matrix();
                let q = UnitQuaternion::from_matrix(&rot);
                m.cam_quat_mut()[i] = [q.w, q.i, q.j, q.k];
            }
            if a.randomize_fovy {
                let s = a.fovy_perturbation_size;
                m.cam_fovy_mut()[i] = fovy + uniform(rng, -s, s);
            }
        }
    }
}

// --- TextureModder --------------------------------------------------------------------

/// One of robosuite's texture patterns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureVariation {
    /// A plain colour (`"rgb"`).
    Rgb,
    /// A checker of two colours (`"checker"`).
    Checker,
    /// One colour with a random fraction of the pixels another (`"noise"`).
    Noise,
    /// A linear gradient between two colours, vertical or horizontal (`"gradient"`).
    Gradient,
}

impl TextureVariation {
    /// robosuite's name.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Rgb => "rgb",
            Self::Checker => "checker",
            Self::Noise => "noise",
            Self::Gradient => "gradient",
        }
    }
}

impl std::str::FromStr for TextureVariation {
    type Err = Error;

    fn from_str(s: &str) -> Result<Self> {
        match s {
            "rgb" => Ok(Self::Rgb),
            "checker" => Ok(Self::Checker),
            "noise" => Ok(Self::Noise),
            "gradient" => Ok(Self::Gradient),
            _ => Err(Error::invalid_argument(
                "texture_variations",
                format!("unknown texture variation `{s}`; valid: rgb, checker, noise, gradient"),
            )),
        }
    }
}

/// robosuite's color randomization arguments (`DEFAULT_COLOR_ARGS`).
#[derive(Debug, Clone, PartialEq)]
pub struct ColorArgs {
    /// The geoms to randomize (`None`: every geom).
    pub geom_names: Option<Vec<String>>,
    /// Blend the random colours and materials into the defaults (by the interpolations).
    pub randomize_local: bool,
    /// Randomize the textured geoms' materials (reflectance, shininess, specular).
    pub randomize_material: bool,
    /// With `randomize_local`: the weight of the random colour, in `[0, 1]` (0.2).
    pub local_rgb_interpolation: f64,
    /// With `randomize_local`: the weight of the random material, in `[0, 1]` (0.3).
    pub local_material_interpolation: f64,
    /// The patterns a texture is drawn from (all four).
    pub texture_variations: Vec<TextureVariation>,
    /// Randomize the skybox texture too.
    pub randomize_skybox: bool,
}

impl Default for ColorArgs {
    fn default() -> Self {
        Self {
            geom_names: None,
            randomize_local: true,
            randomize_material: true,
            local_rgb_interpolation: 0.2,
            local_material_interpolation: 0.3,
            texture_variations: vec![
                TextureVariation::Rgb,
                TextureVariation::Checker,
                TextureVariation::Noise,
                TextureVariation::Gradient,
            ],
            randomize_skybox: true,
        }
    }
}

/// A texture's place in `tex_data`.
#[derive(Debug, Clone, Copy)]
struct Tex {
    adr: usize,
    height: usize,
    width: usize,
    nchannel: usize,
}

/// A selected geom: its id and, when its material has a texture, (texture, material).
#[derive(Debug, Clone, Copy)]
struct ColorGeom {
    geom: usize,
    textured: Option<(usize, usize)>,
}

/// robosuite's `TextureModder`: each [`TextureModder::randomize`] whitens the selected
/// geoms and their materials, then gives each geom with a textured material a random
/// texture (one of `texture_variations`; blended into the default with
/// `randomize_local`) and, with `randomize_material`, a random reflectance / shininess /
/// specular; each other geom a random colour; and the skybox a random texture. It returns
/// the textures it changed, which must be uploaded to the render contexts
/// (`RobosuiteEnv::upload_texture`, feature `render`) for frames to
/// show them (the wrapper does). An env that never renders on its own is built without
/// texture images (`RobosuiteEnv::textures_loaded`): call `RobosuiteEnv::load_textures`
/// before making a modder of its model (the wrapper does), else it sees 1×1 placeholders.
#[derive(Debug, Clone)]
pub struct TextureModder {
    args: ColorArgs,
    geoms: Vec<ColorGeom>,
    skybox: Option<usize>,
    textures: Vec<Option<Tex>>,
    default_bitmaps: Vec<Option<Vec<u8>>>,
    /// Per selected geom: its rgba, and its material's rgba (textured geoms).
    default_rgba: Vec<([f32; 4], [f32; 4])>,
    default_material: Vec<[f32; 3]>,
}

impl TextureModder {
    /// A modder of `model`'s colours and textures, its current values saved as the
    /// defaults.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an unknown geom name, an interpolation outside
    /// `[0, 1]` or not finite, no texture variation, or `randomize_skybox` in a model
    /// without a skybox texture.
    pub fn new(model: &MjModel, args: ColorArgs) -> Result<Self> {
        for (key, v) in [
            ("local_rgb_interpolation", args.local_rgb_interpolation),
            (
                "local_material_interpolation",
                args.local_material_interpolation,
            ),
        ] {
            if !(v.is_finite() && (0.0..=1.0).contains(&v)) {
                return Err(Error::invalid_argument(
                    key,
                    format!("must be a number in [0, 1], got {v}"),
                ));
            }
        }
        if args.texture_variations.is_empty() {
            return Err(Error::invalid_argument(
                "texture_variations",
                "must name at least one of rgb, checker, noise, gradient",
            ));
        }
        let ngeom = model.ffi().ngeom.max(0) as usize;
        let ids = check_names(
            model,
            "geom_names",
            mjtObj::mjOBJ_GEOM,
            "geom",
            ngeom,
            args.geom_names.as_deref(),
        )?;
        let ntexdata = model.ffi().ntexdata.max(0) as usize;
        let textures: Vec<Option<Tex>> = (0..model.ffi().ntex.max(0) as usize)
            .map(|t| {
                let adr = model.tex_adr()[t];
                let tex = Tex {
                    adr: usize::try_from(adr).ok()?,
                    height: model.tex_height()[t].max(0) as usize,
                    width: model.tex_width()[t].max(0) as usize,
                    nchannel: model.tex_nchannel()[t].max(0) as usize,
                };
                (tex.nchannel >= 3 && tex.adr + tex.height * tex.width * tex.nchannel <= ntexdata)
                    .then_some(tex)
            })
            .collect();
        let geoms = ids
            .into_iter()
            .map(|geom| {
                let mat = model.geom_matid()[geom];
                let textured = usize::try_from(mat).ok().and_then(|mat| {
                    let tex = model.mat_texid()[mat]
                        .iter()
                        .find_map(|&t| usize::try_from(t).ok())?;
                    textures[tex].is_some().then_some((tex, mat))
                });
                ColorGeom { geom, textured }
            })
            .collect();
        let skybox = (0..textures.len()).rev().find(|&t| {
            model.tex_type()[t] == MjtTexture::mjTEXTURE_SKYBOX && textures[t].is_some()
        });
        if args.randomize_skybox && skybox.is_none() {
            return Err(Error::invalid_argument(
                "randomize_skybox",
                "the model has no skybox texture",
            ));
        }
        let mut modder = Self {
            args,
            geoms,
            skybox,
            textures,
            default_bitmaps: Vec::new(),
            default_rgba: Vec::new(),
            default_material: Vec::new(),
        };
        modder.save_defaults(model);
        Ok(modder)
    }

    /// The arguments.
    pub fn args(&self) -> &ColorArgs {
        &self.args
    }

    /// The ids of the geoms it randomizes.
    pub fn geoms(&self) -> Vec<usize> {
        self.geoms.iter().map(|g| g.geom).collect()
    }

    fn bitmap<'m>(&self, model: &'m MjModel, tex: usize) -> Option<&'m [u8]> {
        let t = self.textures[tex]?;
        model
            .tex_data()
            .get(t.adr..t.adr + t.height * t.width * t.nchannel)
    }

    /// The textures it writes: the selected geoms' and the skybox.
    fn used_textures(&self) -> Vec<usize> {
        let mut used: Vec<usize> = self
            .geoms
            .iter()
            .filter_map(|g| g.textured.map(|(t, _)| t))
            .chain(self.skybox.filter(|_| self.args.randomize_skybox))
            .collect();
        used.sort_unstable();
        used.dedup();
        used
    }

    /// Saves `model`'s current values as the defaults.
    pub fn save_defaults(&mut self, model: &MjModel) {
        let mut bitmaps = vec![None; self.textures.len()];
        for t in self.used_textures() {
            bitmaps[t] = self.bitmap(model, t).map(<[u8]>::to_vec);
        }
        self.default_bitmaps = bitmaps;
        self.default_rgba = self
            .geoms
            .iter()
            .map(|g| {
                let mat = g
                    .textured
                    .map_or([1.0; 4], |(_, mat)| model.mat_rgba()[mat]);
                (model.geom_rgba()[g.geom], mat)
            })
            .collect();
        self.default_material = self
            .geoms
            .iter()
            .map(|g| match g.textured {
                Some((_, mat)) => [
                    model.mat_reflectance()[mat],
                    model.mat_shininess()[mat],
                    model.mat_specular()[mat],
                ],
                None => [0.0; 3],
            })
            .collect();
    }

    /// Writes the saved defaults back (textures, materials and every colour the
    /// randomization whitened); returns the textures changed (to upload).
    pub fn restore_defaults(&self, sim: &mut Sim) -> Vec<usize> {
        let m = sim.model_mut();
        for (i, g) in self.geoms.iter().enumerate() {
            let (geom_rgba, mat_rgba) = self.default_rgba[i];
            m.geom_rgba_mut()[g.geom] = geom_rgba;
            if let Some((_, mat)) = g.textured {
                let [r, s, p] = self.default_material[i];
                m.mat_reflectance_mut()[mat] = r;
                m.mat_shininess_mut()[mat] = s;
                m.mat_specular_mut()[mat] = p;
                m.mat_rgba_mut()[mat] = mat_rgba;
            }
        }
        let used = self.used_textures();
        for &t in &used {
            if let (Some(tex), Some(default)) = (self.textures[t], &self.default_bitmaps[t]) {
                m.tex_data_mut()[tex.adr..tex.adr + default.len()].copy_from_slice(default);
            }
        }
        used
    }

    /// Randomizes the selected geoms, their textures and materials, and the skybox
    /// (robosuite's order of draws); returns the textures changed (to upload).
    pub fn randomize(&self, sim: &mut Sim, rng: &mut EnvRng) -> Vec<usize> {
        let a = &self.args;
        let m = sim.model_mut();
        // whiten_materials
        for g in &self.geoms {
            m.geom_rgba_mut()[g.geom] = [1.0; 4];
            if let Some((_, mat)) = g.textured {
                m.mat_rgba_mut()[mat] = [1.0; 4];
            }
        }
        for (i, g) in self.geoms.iter().enumerate() {
            match g.textured {
                Some((tex, mat)) => {
                    self.randomize_texture(m, tex, rng);
                    if a.randomize_material {
                        let draw: [f64; 3] = std::array::from_fn(|_| rng.random::<f64>());
                        let w = if a.randomize_local {
                            a.local_material_interpolation
                        } else {
                            1.0
                        };
                        let d = self.default_material[i];
                        let v: [f32; 3] = std::array::from_fn(|k| {
                            ((1.0 - w) * f64::from(d[k]) + w * draw[k]) as f32
                        });
                        m.mat_reflectance_mut()[mat] = v[0];
                        m.mat_shininess_mut()[mat] = v[1];
                        m.mat_specular_mut()[mat] = v[2];
                    }
                }
                None => {
                    let draw: [f64; 3] = std::array::from_fn(|_| rng.random::<f64>());
                    let w = if a.randomize_local {
                        a.local_rgb_interpolation
                    } else {
                        1.0
                    };
                    let d = self.default_rgba[i].0;
                    let c: [f32; 3] =
                        std::array::from_fn(|k| ((1.0 - w) * f64::from(d[k]) + w * draw[k]) as f32);
                    m.geom_rgba_mut()[g.geom][..3].copy_from_slice(&c);
                }
            }
        }
        if a.randomize_skybox
            && let Some(sky) = self.skybox
        {
            self.randomize_texture(m, sky, rng);
        }
        self.used_textures()
    }

    /// A random uint8 colour (robosuite's `get_rand_rgb`).
    fn rand_rgb(rng: &mut EnvRng) -> [f64; 3] {
        std::array::from_fn(|_| (rng.random::<f64>() * 255.0).floor())
    }

    /// One random pattern written into texture `tex`.
    fn randomize_texture(&self, m: &mut MjModel, tex: usize, rng: &mut EnvRng) {
        let Some(t) = self.textures[tex] else {
            return;
        };
        let variations = &self.args.texture_variations;
        let choice = variations[rng.random_range(0..variations.len())];
        let (h, w) = (t.height, t.width);
        // The pattern: per pixel, the weight of `c2` against `c1`.
        let (c1, c2, weight): (_, _, Box<dyn Fn(usize, usize) -> f64>) = match choice {
            TextureVariation::Rgb => {
                let c = Self::rand_rgb(rng);
                (c, c, Box::new(|_, _| 0.0))
            }
            TextureVariation::Checker => {
                let (c1, c2) = (Self::rand_rgb(rng), Self::rand_rgb(rng));
                // robosuite's checker: c1 where (row + col) is odd, c2 where it is even.
                (c1, c2, Box::new(|r, c| ((r + c + 1) % 2) as f64))
            }
            TextureVariation::Gradient => {
                let (c1, c2) = (Self::rand_rgb(rng), Self::rand_rgb(rng));
                let vertical = rng.random::<f64>() > 0.5;
                let span = |n: usize| if n > 1 { (n - 1) as f64 } else { 1.0 };
                let (sh, sw) = (span(h), span(w));
                (
                    c1,
                    c2,
                    Box::new(move |r, c| {
                        if vertical {
                            r as f64 / sh
                        } else {
                            c as f64 / sw
                        }
                    }),
                )
            }
            TextureVariation::Noise => {
                let fraction = 0.1 + rng.random::<f64>() * 0.8;
                let (c1, c2) = (Self::rand_rgb(rng), Self::rand_rgb(rng));
                let mask: Vec<bool> = (0..h * w).map(|_| rng.random::<f64>() < fraction).collect();
                (
                    c1,
                    c2,
                    Box::new(move |r, c| if mask[r * w + c] { 1.0 } else { 0.0 }),
                )
            }
        };
        let blend = if self.args.randomize_local {
            Some(self.args.local_rgb_interpolation)
        } else {
            None
        };
        let default = self.default_bitmaps[tex].as_deref();
        let data = &mut m.tex_data_mut()[t.adr..t.adr + h * w * t.nchannel];
        for r in 0..h {
            for c in 0..w {
                let p = weight(r, c);
                let px = (r * w + c) * t.nchannel;
                for k in 0..3 {
                    // The pattern is made in uint8, as robosuite's bitmap.
                    let mut v = (c2[k] * p + c1[k] * (1.0 - p)).floor();
                    if let (Some(a), Some(d)) = (blend, default) {
                        v = (1.0 - a) * f64::from(d[px + k]) + a * v;
                    }
                    data[px + k] = v.clamp(0.0, 255.0) as u8;
                }
            }
        }
    }
}

// --- DynamicsModder -------------------------------------------------------------------

/// robosuite's dynamics randomization arguments (`DEFAULT_DYNAMICS_ARGS`).
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsArgs {
    /// Scale the medium's density.
    pub randomize_density: bool,
    /// Scale the medium's viscosity.
    pub randomize_viscosity: bool,
    /// Density: default × (1 ± this) (0.1).
    pub density_perturbation_ratio: f64,
    /// Viscosity: default × (1 ± this) (0.1).
    pub viscosity_perturbation_ratio: f64,
    /// The bodies to randomize (`None`: every body).
    pub body_names: Option<Vec<String>>,
    /// Perturb each body's position in its parent.
    pub randomize_position: bool,
    /// Perturb each body's orientation (normalized after).
    pub randomize_quaternion: bool,
    /// Scale each body's inertia (bodies with mass only).
    pub randomize_inertia: bool,
    /// Scale each body's mass (bodies with mass only).
    pub randomize_mass: bool,
    /// Position: default ± this per axis (0.0015).
    pub position_perturbation_size: f64,
    /// Quaternion: default ± this per component (0.003).
    pub quaternion_perturbation_size: f64,
    /// Inertia: default × (1 ± this) (0.02).
    pub inertia_perturbation_ratio: f64,
    /// Mass: default × (1 ± this) (0.02).
    pub mass_perturbation_ratio: f64,
    /// The geoms to randomize (`None`: every geom).
    pub geom_names: Option<Vec<String>>,
    /// Scale each geom's friction.
    pub randomize_friction: bool,
    /// Scale each geom's solref (clipped to `[0, 1]`).
    pub randomize_solref: bool,
    /// Scale each geom's solimp.
    pub randomize_solimp: bool,
    /// Friction: default × (1 ± this) (0.1).
    pub friction_perturbation_ratio: f64,
    /// solref: default × (1 ± this) (0.1).
    pub solref_perturbation_ratio: f64,
    /// solimp: default × (1 ± this) (0.1).
    pub solimp_perturbation_ratio: f64,
    /// The joints to randomize (`None`: every joint).
    pub joint_names: Option<Vec<String>>,
    /// Scale each joint's stiffness (joints with stiffness only).
    pub randomize_stiffness: bool,
    /// Perturb each joint's frictionloss (not free joints').
    pub randomize_frictionloss: bool,
    /// Perturb each joint's damping (not free joints').
    pub randomize_damping: bool,
    /// Perturb each joint's armature (not free joints').
    pub randomize_armature: bool,
    /// Stiffness: default × (1 ± this) (0.1).
    pub stiffness_perturbation_ratio: f64,
    /// frictionloss: default ± this, clipped at 0 (0.05).
    pub frictionloss_perturbation_size: f64,
    /// Damping: default ± this, clipped at 0 (0.01).
    pub damping_perturbation_size: f64,
    /// Armature: default ± this, clipped at 0 (0.01).
    pub armature_perturbation_size: f64,
}

impl Default for DynamicsArgs {
    fn default() -> Self {
        Self {
            randomize_density: true,
            randomize_viscosity: true,
            density_perturbation_ratio: 0.1,
            viscosity_perturbation_ratio: 0.1,
            body_names: None,
            randomize_position: true,
            randomize_quaternion: true,
            randomize_inertia: true,
            randomize_mass: true,
            position_perturbation_size: 0.0015,
            quaternion_perturbation_size: 0.003,
            inertia_perturbation_ratio: 0.02,
            mass_perturbation_ratio: 0.02,
            geom_names: None,
            randomize_friction: true,
            randomize_solref: true,
            randomize_solimp: true,
            friction_perturbation_ratio: 0.1,
            solref_perturbation_ratio: 0.1,
            solimp_perturbation_ratio: 0.1,
            joint_names: None,
            randomize_stiffness: true,
            randomize_frictionloss: true,
            randomize_damping: true,
            randomize_armature: true,
            stiffness_perturbation_ratio: 0.1,
            frictionloss_perturbation_size: 0.05,
            damping_perturbation_size: 0.01,
            armature_perturbation_size: 0.01,
        }
    }
}

/// One randomized parameter: whether, how much, added (`size`) or scaling (`ratio`), clip.
#[derive(Debug, Clone, Copy)]
struct Perturb {
    on: bool,
    amount: f64,
    ratio: bool,
    clip: (f64, f64),
}

impl Perturb {
    /// robosuite's draw for one value: `rand()` per element, always drawn.
    fn apply<const N: usize>(&self, rng: &mut EnvRng, default: [f64; N]) -> [f64; N] {
        if !self.on {
            return default;
        }
        std::array::from_fn(|k| {
            let p = self.amount * (-1.0 + 2.0 * rng.random::<f64>());
            let v = if self.ratio {
                default[k] * (1.0 + p)
            } else {
                default[k] + p
            };
            v.clamp(self.clip.0, self.clip.1)
        })
    }

    fn apply_slice(&self, rng: &mut EnvRng, default: &[f64], out: &mut [f64]) {
        for (o, &d) in out.iter_mut().zip(default) {
            *o = self.apply(rng, [d])[0];
        }
    }
}

/// A body's position, quaternion, inertia and mass.
type BodyValues = ([f64; 3], [f64; 4], [f64; 3], f64);
/// A joint's stiffness, and its dofs' frictionloss, damping and armature.
type JointValues = (f64, Vec<f64>, Vec<f64>, Vec<f64>);

#[derive(Debug, Clone, Default)]
struct DynamicsDefaults {
    density: f64,
    viscosity: f64,
    body: Vec<BodyValues>,
    geom: Vec<([f64; 3], [f64; 2], [f64; 5])>,
    joint: Vec<JointValues>,
}

/// robosuite's `DynamicsModder`: each [`DynamicsModder::randomize`] perturbs, from the
/// defaults, the medium's density and viscosity, every selected body's position,
/// orientation, inertia and mass, every selected geom's friction, solref and solimp, and
/// every selected joint's stiffness, frictionloss, damping and armature (see
/// [`DynamicsArgs`]), then runs `mj_forward`. Bodies without mass keep mass and inertia;
/// free joints keep frictionloss, damping and armature; joints without stiffness keep it
/// (as robosuite).
#[derive(Debug, Clone)]
pub struct DynamicsModder {
    args: DynamicsArgs,
    bodies: Vec<usize>,
    geoms: Vec<usize>,
    joints: Vec<usize>,
    /// Per joint of the model: its dofs.
    dofs: Vec<Vec<usize>>,
    defaults: DynamicsDefaults,
}

impl DynamicsModder {
    /// A modder of `model`'s dynamics, its current values saved as the defaults.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an unknown body, geom or joint name, or a
    /// perturbation size or ratio that is negative or not finite.
    pub fn new(model: &MjModel, args: DynamicsArgs) -> Result<Self> {
        for (key, v) in [
            (
                "density_perturbation_ratio",
                args.density_perturbation_ratio,
            ),
            (
                "viscosity_perturbation_ratio",
                args.viscosity_perturbation_ratio,
            ),
            (
                "position_perturbation_size",
                args.position_perturbation_size,
            ),
            (
                "quaternion_perturbation_size",
                args.quaternion_perturbation_size,
            ),
            (
                "inertia_perturbation_ratio",
                args.inertia_perturbation_ratio,
            ),
            ("mass_perturbation_ratio", args.mass_perturbation_ratio),
            (
                "friction_perturbation_ratio",
                args.friction_perturbation_ratio,
            ),
            ("solref_perturbation_ratio", args.solref_perturbation_ratio),
            ("solimp_perturbation_ratio", args.solimp_perturbation_ratio),
            (
                "stiffness_perturbation_ratio",
                args.stiffness_perturbation_ratio,
            ),
            (
                "frictionloss_perturbation_size",
                args.frictionloss_perturbation_size,
            ),
            ("damping_perturbation_size", args.damping_perturbation_size),
            (
                "armature_perturbation_size",
                args.armature_perturbation_size,
            ),
        ] {
            check_size(key, v)?;
        }
        let f = model.ffi();
        let (nbody, ngeom, njnt) = (
            f.nbody.max(0) as usize,
            f.ngeom.max(0) as usize,
            f.njnt.max(0) as usize,
        );
        let bodies = check_names(
            model,
            "body_names",
            mjtObj::mjOBJ_BODY,
            "body",
            nbody,
            args.body_names.as_deref(),
        )?;
        let geoms = check_names(
            model,
            "geom_names",
            mjtObj::mjOBJ_GEOM,
            "geom",
            ngeom,
            args.geom_names.as_deref(),
        )?;
        let joints = check_names(
            model,
            "joint_names",
            mjtObj::mjOBJ_JOINT,
            "joint",
            njnt,
            args.joint_names.as_deref(),
        )?;
        let mut dofs = vec![Vec::new(); njnt];
        for (dof, &j) in model.dof_jntid().iter().enumerate() {
            if let Some(list) = usize::try_from(j).ok().and_then(|j| dofs.get_mut(j)) {
                list.push(dof);
            }
        }
        let mut modder = Self {
            args,
            bodies,
            geoms,
            joints,
            dofs,
            defaults: DynamicsDefaults::default(),
        };
        modder.save_defaults(model);
        Ok(modder)
    }

    /// The arguments.
    pub fn args(&self) -> &DynamicsArgs {
        &self.args
    }

    /// Saves `model`'s current values as the defaults.
    pub fn save_defaults(&mut self, model: &MjModel) {
        let dof = |a: &[f64], j: usize| self.dofs[j].iter().map(|&d| a[d]).collect::<Vec<_>>();
        self.defaults = DynamicsDefaults {
            density: model.opt().density,
            viscosity: model.opt().viscosity,
            body: self
                .bodies
                .iter()
                .map(|&b| {
                    (
                        model.body_pos()[b],
                        model.body_quat()[b],
                        model.body_inertia()[b],
                        model.body_mass()[b],
                    )
                })
                .collect(),
            geom: self
                .geoms
                .iter()
                .map(|&g| {
                    (
                        model.geom_friction()[g],
                        model.geom_solref()[g],
                        model.geom_solimp()[g],
                    )
                })
                .collect(),
            joint: self
                .joints
                .iter()
                .map(|&j| {
                    (
                        model.jnt_stiffness()[j],
                        dof(model.dof_frictionloss(), j),
                        dof(model.dof_damping(), j),
                        dof(model.dof_armature(), j),
                    )
                })
                .collect(),
        };
    }

    /// Writes the saved defaults back and runs `mj_forward`.
    ///
    /// # Errors
    /// [`Error::Simulation`] when MuJoCo raises an error in `mj_forward`.
    pub fn restore_defaults(&self, sim: &mut Sim) -> Result<()> {
        self.write(sim, None)
    }

    /// Randomizes every enabled parameter of the selected elements (robosuite's order of
    /// draws) and runs `mj_forward`.
    ///
    /// # Errors
    /// [`Error::Simulation`] when MuJoCo raises an error in `mj_forward`.
    pub fn randomize(&self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        self.write(sim, Some(rng))
    }

    /// Writes the defaults, perturbed when `rng` is given, then `mj_forward`.
    fn write(&self, sim: &mut Sim, rng: Option<&mut EnvRng>) -> Result<()> {
        let a = &self.args;
        let inf = f64::INFINITY;
        let randomizing = rng.is_some();
        // Without an RNG every perturbation is off and nothing is drawn.
        let p = |on: bool, amount: f64, ratio: bool, clip: (f64, f64)| Perturb {
            on: on && randomizing,
            amount,
            ratio,
            clip,
        };
        let (size, ratio) = (false, true);
        let density = p(
            a.randomize_density,
            a.density_perturbation_ratio,
            ratio,
            (0.0, inf),
        );
        let viscosity = p(
            a.randomize_viscosity,
            a.viscosity_perturbation_ratio,
            ratio,
            (0.0, inf),
        );
        let position = p(
            a.randomize_position,
            a.position_perturbation_size,
            size,
            (-inf, inf),
        );
        let quaternion = p(
            a.randomize_quaternion,
            a.quaternion_perturbation_size,
            size,
            (-inf, inf),
        );
        let inertia = p(
            a.randomize_inertia,
            a.inertia_perturbation_ratio,
            ratio,
            (0.0, inf),
        );
        let mass = p(
            a.randomize_mass,
            a.mass_perturbation_ratio,
            ratio,
            (0.0, inf),
        );
        let friction = p(
            a.randomize_friction,
            a.friction_perturbation_ratio,
            ratio,
            (0.0, inf),
        );
        let solref = p(
            a.randomize_solref,
            a.solref_perturbation_ratio,
            ratio,
            (0.0, 1.0),
        );
        let solimp = p(
            a.randomize_solimp,
            a.solimp_perturbation_ratio,
            ratio,
            (0.0, inf),
        );
        let stiffness = p(
            a.randomize_stiffness,
            a.stiffness_perturbation_ratio,
            ratio,
            (0.0, inf),
        );
        let frictionloss = p(
            a.randomize_frictionloss,
            a.frictionloss_perturbation_size,
            size,
            (0.0, inf),
        );
        let damping = p(
            a.randomize_damping,
            a.damping_perturbation_size,
            size,
            (0.0, inf),
        );
        let armature = p(
            a.randomize_armature,
            a.armature_perturbation_size,
            size,
            (0.0, inf),
        );
        let mut spare = gym_core::rng_from_seed(0);
        let rng: &mut EnvRng = match rng {
            Some(rng) => rng,
            None => &mut spare,
        };
        let d = &self.defaults;
        let m = sim.model_mut();
        m.opt_mut().density = density.apply(rng, [d.density])[0];
        m.opt_mut().viscosity = viscosity.apply(rng, [d.viscosity])[0];
        for (&b, &(pos, quat, inert, ms)) in self.bodies.iter().zip(&d.body) {
            m.body_pos_mut()[b] = position.apply(rng, pos);
            let q = quaternion.apply(rng, quat);
            let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
            m.body_quat_mut()[b] = if norm > 0.0 {
                q.map(|v| v / norm)
            } else {
                quat
            };
            let new_inertia = inertia.apply(rng, inert);
            let new_mass = mass.apply(rng, [ms])[0];
            // Bodies without mass keep both (robosuite's dummy bodies).
            if ms != 0.0 {
                m.body_inertia_mut()[b] = new_inertia;
                m.body_mass_mut()[b] = new_mass;
            }
        }
        for (&g, &(fr, sr, si)) in self.geoms.iter().zip(&d.geom) {
            m.geom_friction_mut()[g] = friction.apply(rng, fr);
            m.geom_solref_mut()[g] = solref.apply(rng, sr);
            m.geom_solimp_mut()[g] = solimp.apply(rng, si);
        }
        let free = mujoco_rs::wrappers::mj_model::MjtJoint::mjJNT_FREE;
        let mut buf = Vec::new();
        for (&j, (st, fl, dm, ar)) in self.joints.iter().zip(&d.joint) {
            let new_stiffness = stiffness.apply(rng, [*st])[0];
            if *st != 0.0 {
                m.jnt_stiffness_mut()[j] = new_stiffness;
            }
            let is_free = m.jnt_type()[j] == free;
            let dofs = &self.dofs[j];
            for (perturb, default, which) in
                [(frictionloss, fl, 0), (damping, dm, 1), (armature, ar, 2)]
            {
                buf.clear();
                buf.resize(default.len(), 0.0);
                perturb.apply_slice(rng, default, &mut buf);
                if is_free {
                    continue;
                }
                let arr = match which {
                    0 => m.dof_frictionloss_mut(),
                    1 => m.dof_damping_mut(),
                    _ => m.dof_armature_mut(),
                };
                for (&dof, &v) in dofs.iter().zip(&buf) {
                    arr[dof] = v;
                }
            }
        }
        sim.forward()
    }
}
