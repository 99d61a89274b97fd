//! robosuite's camera observations (`RobotEnv._create_camera_sensors`), in three parts:
//! * this module: the camera arguments ([`CameraConfig`]) with their validation and the
//!   observables they add (`{camera}_image`, `{camera}_depth`,
//!   `{camera}_segmentation_{level}`);
//! * [`rig`]: one environment's cameras resolved against its model, their frames, and the
//!   renderer that draws them (MuJoCo's, [`crate::render`], feature `render`);
//! * [`segmentation`]: which model part each geom belongs to, for the segmentation frames.
//!
//! Shapes and dtypes are robosuite's: images `(H, W, 3)` uint8, depth `(H, W, 1)` float32
//! (raw z-buffer in `[0, 1]`; metres through [`crate::render::real_depth`], robosuite's
//! `get_real_depth_map`), segmentation `(H, W, 1)` int32. Rows run bottom first under
//! robosuite's default `IMAGE_CONVENTION = "opengl"`, top first under `"opencv"`.

pub mod rig;
pub mod segmentation;

use crate::observables::{Modality, ObsSpec};
use gym_core::{ArrayValue, DType, Error, RenderMode, Result};
use ndarray::{ArrayD, IxDyn};

/// The largest camera or frame width or height accepted (robosuite sets no limit; MuJoCo's
/// offscreen buffer must fit one OpenGL renderbuffer, and 4096 fits every implementation,
/// Mesa's included).
pub const MAX_CAMERA_SIZE: usize = 4096;

/// robosuite's segmentation levels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Segmentation {
    /// Per object instance (robot, gripper, each object), ids from 1, 0 for the rest.
    Instance,
    /// Per object class, ids from 1, 0 for the rest.
    Class,
    /// Per geom: the geom id, -1 for the background.
    Element,
}

impl Segmentation {
    /// robosuite's name (`"instance"`, `"class"`, `"element"`).
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Instance => "instance",
            Self::Class => "class",
            Self::Element => "element",
        }
    }

    pub(crate) fn parse(s: &str) -> Result<Self> {
        match s {
            "instance" => Ok(Self::Instance),
            "class" => Ok(Self::Class),
            "element" => Ok(Self::Element),
            other => Err(Error::invalid_argument(
                "camera_segmentations",
                format!("unknown segmentation `{other}`; valid: instance, class, element, None"),
            )),
        }
    }
}

/// robosuite's `macros.IMAGE_CONVENTION`: the row order of camera observations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ImageConvention {
    /// Bottom row first, as OpenGL reads pixels (robosuite's default).
    #[default]
    OpenGl,
    /// Top row first.
    OpenCv,
}

/// How MuJoCo's renderer draws camera frames and `render()` frames: cost against closeness to
/// robosuite's frames (the figures are in the repository's `docs/benchmarks.md` and
/// `docs/fidelity.md`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RenderQuality {
    /// No multisampling and no reflections. Frames smaller than
    /// [`FAST_FULL_SIZE_FROM`] pixels on both sides are antialiased by supersampling (drawn at
    /// 2× their size, each 2×2 block averaged); larger ones are drawn at their size, where
    /// aliased edges weigh less. Depth is read where robosuite's multisampled depth buffer
    /// resolves it (sample 0 of the 4× pattern, the view moved by a fraction of a pixel;
    /// see [`crate::render::Supersampling`]). On a CPU (Mesa's llvmpipe) about 4–7× cheaper
    /// per env step than `Robosuite` (one or two cameras, 84×84 or 256×256, with or without
    /// depth); mean absolute difference to robosuite 1.5.2's frames 3.1–4.1 of 255
    /// (`Robosuite`: 2.9–3.5), depth equal to `Robosuite`'s.
    #[default]
    Fast,
    /// The model's own settings, as robosuite draws: 4× multisampling and reflections.
    Robosuite,
}

/// [`RenderQuality::Fast`] draws frames whose width or height is at least this many pixels
/// at their own size, smaller ones at twice their size.
pub const FAST_FULL_SIZE_FROM: usize = 128;

impl RenderQuality {
    /// How frames are supersampled: `Fast` at 2× below [`FAST_FULL_SIZE_FROM`] pixels,
    /// `Robosuite` not at all (it multisamples).
    #[cfg(feature = "render")]
    pub fn supersampling(self) -> crate::render::Supersampling {
        match self {
            Self::Fast => crate::render::Supersampling {
                factor: 2,
                full_size_from: FAST_FULL_SIZE_FROM,
            },
            Self::Robosuite => crate::render::Supersampling::NONE,
        }
    }

    /// The name `render_quality` takes: `"fast"` or `"robosuite"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Fast => "fast",
            Self::Robosuite => "robosuite",
        }
    }

    pub(crate) fn parse(s: &str) -> Result<Self> {
        match s {
            "fast" => Ok(Self::Fast),
            "robosuite" => Ok(Self::Robosuite),
            other => Err(Error::invalid_argument(
                "render_quality",
                format!("unknown render quality `{other}`; valid: fast, robosuite"),
            )),
        }
    }
}

/// robosuite's camera arguments, and the camera and size of Gymnasium's render modes.
///
/// Each per-camera list holds one value for every camera, or one per camera (as robosuite's
/// `_input2list` broadcasts a single value).
#[derive(Debug, Clone, PartialEq)]
pub struct CameraConfig {
    /// Add camera observations (default false: this crate is headless by default).
    pub use_camera_obs: bool,
    /// Create the offscreen renderer (needed by camera observations and render modes).
    pub has_offscreen_renderer: bool,
    /// Cameras to observe (default `["agentview"]`).
    pub camera_names: Vec<String>,
    /// Heights in pixels (default `[256]`).
    pub camera_heights: Vec<usize>,
    /// Widths in pixels (default `[256]`).
    pub camera_widths: Vec<usize>,
    /// Whether each camera also gives `{camera}_depth` (default `[false]`).
    pub camera_depths: Vec<bool>,
    /// Segmentations per camera: empty for none, one list for every camera, or one per camera.
    pub camera_segmentations: Vec<Vec<Segmentation>>,
    /// Gymnasium's render mode (`rgb_array` or `depth_array`; `None`: no rendering).
    pub render_mode: Option<RenderMode>,
    /// The camera `render()` draws (robosuite's `render_camera`, default `"frontview"`).
    pub render_camera: String,
    /// Height of rendered frames (default 256).
    pub render_height: usize,
    /// Width of rendered frames (default 256).
    pub render_width: usize,
    /// Row order of camera observations.
    pub image_convention: ImageConvention,
    /// How frames are drawn (default [`RenderQuality::Fast`]).
    pub render_quality: RenderQuality,
    /// The EGL device frames are drawn on (robosuite's `render_gpu_device_id`, an index in
    /// EGL's device order); `None`: `MUJOCO_EGL_DEVICE_ID` if set, else the first device
    /// that opens.
    pub render_gpu_device_id: Option<usize>,
}

impl Default for CameraConfig {
    fn default() -> Self {
        Self {
            use_camera_obs: false,
            has_offscreen_renderer: false,
            camera_names: vec!["agentview".to_owned()],
            camera_heights: vec![256],
            camera_widths: vec![256],
            camera_depths: vec![false],
            camera_segmentations: Vec::new(),
            render_mode: None,
            render_camera: "frontview".to_owned(),
            render_height: 256,
            render_width: 256,
            image_convention: ImageConvention::OpenGl,
            render_quality: RenderQuality::Fast,
            render_gpu_device_id: None,
        }
    }
}

/// One observed camera, resolved: its name, size and outputs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CameraObs {
    /// The camera's name in the model.
    pub name: String,
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Whether `{name}_depth` is observed.
    pub depth: bool,
    /// The segmentation observables, in order.
    pub segmentations: Vec<Segmentation>,
}

impl CameraConfig {
    /// Camera observations of `width × height` from `names`, with an offscreen renderer.
    pub fn observe<S: Into<String>>(
        names: impl IntoIterator<Item = S>,
        width: usize,
        height: usize,
    ) -> Self {
        Self {
            use_camera_obs: true,
            has_offscreen_renderer: true,
            camera_names: names.into_iter().map(Into::into).collect(),
            camera_heights: vec![height],
            camera_widths: vec![width],
            ..Self::default()
        }
    }

    /// Whether an offscreen renderer is needed (camera observations or a render mode).
    pub fn needs_renderer(&self) -> bool {
        self.use_camera_obs || self.render_mode.is_some()
    }

    /// Whether an env of this configuration may render on its own: with an offscreen
    /// renderer (robosuite's `has_offscreen_renderer`), camera observations or a render
    /// mode. An env that may not is built on its scene without texture images (it can
    /// still draw frames when asked, see `RobosuiteEnv::textures_loaded`).
    pub fn may_render(&self) -> bool {
        self.has_offscreen_renderer || self.needs_renderer()
    }

    /// The observed cameras, each list broadcast or matched to the camera names.
    pub fn cameras(&self) -> Vec<CameraObs> {
        if !self.use_camera_obs {
            return Vec::new();
        }
        let pick = |i: usize, n: usize| if n == 1 { 0 } else { i };
        self.camera_names
            .iter()
            .enumerate()
            .map(|(i, name)| CameraObs {
                name: name.clone(),
                width: self.camera_widths[pick(i, self.camera_widths.len())],
                height: self.camera_heights[pick(i, self.camera_heights.len())],
                depth: self.camera_depths[pick(i, self.camera_depths.len())],
                segmentations: match self.camera_segmentations.len() {
                    0 => Vec::new(),
                    n => self.camera_segmentations[pick(i, n)].clone(),
                },
            })
            .collect()
    }

    /// Checks the arguments (camera names are checked against the model when the
    /// environment is made).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for camera options without the offscreen renderer, an
    /// empty camera list, a list whose length is neither 1 nor the number of cameras, a
    /// size of 0 or above [`MAX_CAMERA_SIZE`], or an unsupported render mode.
    pub fn validate(&self) -> Result<()> {
        if self.use_camera_obs && !self.has_offscreen_renderer {
            return Err(Error::invalid_argument(
                "use_camera_obs",
                "camera observations require an offscreen renderer (has_offscreen_renderer=True)",
            ));
        }
        if let Some(mode) = self.render_mode {
            match mode {
                RenderMode::RgbArray | RenderMode::DepthArray => {}
                RenderMode::Human => {
                    return Err(Error::unsupported(
                        "render_mode=\"human\" needs a viewer window, which the Rust env does \
                         not open (Python's robosuite_rs opens one for it, Rust programs see the \
                         `view` example): use \"rgb_array\" or \"depth_array\"",
                    ));
                }
                other => {
                    return Err(Error::invalid_argument(
                        "render_mode",
                        format!(
                            "`{}` is not supported; valid: rgb_array, depth_array, None",
                            other.as_str()
                        ),
                    ));
                }
            }
            check_size("render_width", self.render_width)?;
            check_size("render_height", self.render_height)?;
        }
        if !self.use_camera_obs {
            return Ok(());
        }
        let n = self.camera_names.len();
        if n == 0 {
            return Err(Error::invalid_argument(
                "camera_names",
                "give at least one camera name when using camera observations",
            ));
        }
        let lens = [
            ("camera_heights", self.camera_heights.len()),
            ("camera_widths", self.camera_widths.len()),
            ("camera_depths", self.camera_depths.len()),
        ];
        for (name, len) in lens {
            if len != 1 && len != n {
                return Err(Error::invalid_argument(
                    name,
                    format!("give one value for every camera or one per camera ({n}), got {len}"),
                ));
            }
        }
        let segs = self.camera_segmentations.len();
        if segs > 1 && segs != n {
            return Err(Error::invalid_argument(
                "camera_segmentations",
                format!("give one list for every camera or one per camera ({n}), got {segs}"),
            ));
        }
        for (name, sizes) in [
            ("camera_heights", &self.camera_heights),
            ("camera_widths", &self.camera_widths),
        ] {
            for &v in sizes {
                check_size(name, v)?;
            }
        }
        Ok(())
    }
}

/// `v` as a camera or frame size named `name`: in `1..=MAX_CAMERA_SIZE`.
pub(crate) fn check_size(name: &str, v: usize) -> Result<()> {
    if v == 0 || v > MAX_CAMERA_SIZE {
        return Err(Error::invalid_argument(
            name,
            format!("must be in 1..={MAX_CAMERA_SIZE} pixels, got {v}"),
        ));
    }
    Ok(())
}

/// The observable specs of `cameras`, in robosuite's order (per camera: image, depth,
/// segmentations), modality `image`.
pub fn camera_specs(cameras: &[CameraObs]) -> Vec<ObsSpec> {
    let mut out = Vec::new();
    for c in cameras {
        let spec = |key: String, channels: usize, dtype: DType| ObsSpec {
            key,
            shape: vec![c.height, c.width, channels],
            dtype,
            modality: Modality::Image,
            needs_object_obs: false,
            active: true,
        };
        out.push(spec(format!("{}_image", c.name), 3, DType::U8));
        if c.depth {
            out.push(spec(format!("{}_depth", c.name), 1, DType::F32));
        }
        for s in &c.segmentations {
            out.push(spec(
                format!("{}_segmentation_{}", c.name, s.as_str()),
                1,
                DType::I32,
            ));
        }
    }
    out
}

/// Zeroed arrays for `specs` (the frames' storage).
pub fn blank_frames(specs: &[ObsSpec]) -> Vec<ArrayValue> {
    specs
        .iter()
        .map(|s| match s.dtype {
            DType::U8 => ArrayValue::U8(ArrayD::zeros(IxDyn(&s.shape))),
            DType::F32 => ArrayValue::F32(ArrayD::zeros(IxDyn(&s.shape))),
            _ => ArrayValue::I32(ArrayD::zeros(IxDyn(&s.shape))),
        })
        .collect()
}
