//! The cameras of one environment: its observed cameras resolved against the model, their
//! frames, and the offscreen renderer that draws them and Gymnasium's `render()` frames.
//! Without the `render` feature, asking for any of it is an [`Error::Unsupported`].

use super::segmentation::{SegmentGroup, segment_ids};
use super::{CameraConfig, CameraObs, ImageConvention, Segmentation, blank_frames, camera_specs};
use crate::observables::ObsSpec;
use crate::sim::Data;
use gym_core::{ArrayValue, Error, Frame, RenderMode, Result};
use mujoco_rs::prelude::{MjModel, MjtObjBase};

/// Observed cameras with their frames, and the render-mode camera.
#[derive(Debug)]
#[cfg_attr(not(feature = "render"), allow(dead_code))]
pub struct CameraRig {
    cameras: Vec<(CameraObs, usize)>,
    specs: Vec<ObsSpec>,
    frames: Vec<ArrayValue>,
    convention: ImageConvention,
    render_mode: Option<RenderMode>,
    render_camera: (usize, usize, usize),
    /// Per geom id: its instance and its class id (robosuite's segmentation ids, 0 for a
    /// geom of no group).
    instance_ids: Vec<i32>,
    class_ids: Vec<i32>,
    /// `None` once released ([`CameraRig::release_renderer`]).
    #[cfg(feature = "render")]
    renderer: Option<crate::render::OffscreenRenderer>,
}

/// The id of camera `name`, or an error listing the model's cameras.
fn camera_id(model: &MjModel, key: &str, name: &str) -> Result<usize> {
    model
        .name_to_id(MjtObjBase::mjOBJ_CAMERA, name)
        .ok_or_else(|| {
            let valid: Vec<&str> = (0..model.ffi().ncam as usize)
                .filter_map(|i| model.id_to_name(MjtObjBase::mjOBJ_CAMERA, i))
                .collect();
            Error::invalid_argument(
                key,
                format!("unknown camera `{name}`; valid: {}", valid.join(", ")),
            )
        })
}

/// Gives `model` the look robosuite renders, when `config` needs a renderer: every site
/// hidden (robosuite's reset calls `visualize` with every setting off, which negates the
/// alpha of the robots', grippers' and objects' sites; the arenas' are transparent), and,
/// when a camera observes a segmentation, every site shrunk to `1e-8` (as
/// `RobotEnv._setup_observables` does); with [`RenderQuality::Fast`](super::RenderQuality),
/// no multisampling (`vis.quality.offsamples = 0`). Only rendering values change, not the
/// physics.
pub fn prepare_model(config: &CameraConfig, model: &mut MjModel) {
    if !config.needs_renderer() {
        return;
    }
    if config.render_quality == super::RenderQuality::Fast {
        // SAFETY: one visual setting the render context reads when it is made changes.
        unsafe { model.ffi_mut() }.vis.quality.offsamples = 0;
    }
    for rgba in model.site_rgba_mut() {
        rgba[3] = -rgba[3].abs();
    }
    if config.use_camera_obs && !config.camera_segmentations.iter().all(Vec::is_empty) {
        for size in model.site_size_mut() {
            *size = [1e-8; 3];
        }
    }
}

impl CameraRig {
    /// The rig `config` asks for on `model` (`None` when it needs no renderer).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an invalid configuration or an unknown camera (the
    /// message lists the model's cameras); [`Error::Unsupported`] in a build without the
    /// `render` feature; [`Error::Render`] when no OpenGL context can be opened (the message
    /// names the missing library).
    pub fn new(
        config: &CameraConfig,
        model: &MjModel,
        groups: &[SegmentGroup],
    ) -> Result<Option<Self>> {
        config.validate()?;
        if !config.needs_renderer() {
            return Ok(None);
        }
        let cameras = config
            .cameras()
            .into_iter()
            .map(|c| camera_id(model, "camera_names", &c.name).map(|id| (c, id)))
            .collect::<Result<Vec<_>>>()?;
        let render_camera = (
            camera_id(model, "render_camera", &config.render_camera)?,
            config.render_width,
            config.render_height,
        );
        let plain: Vec<CameraObs> = cameras.iter().map(|(c, _)| c.clone()).collect();
        let specs = camera_specs(&plain);
        let frames = blank_frames(&specs);
        let levels = || cameras.iter().flat_map(|(c, _)| &c.segmentations);
        let instance_ids = if levels().any(|l| *l == Segmentation::Instance) {
            segment_ids(model, groups, false)
        } else {
            Vec::new()
        };
        let class_ids = if levels().any(|l| *l == Segmentation::Class) {
            segment_ids(model, groups, true)
        } else {
            Vec::new()
        };
        #[cfg(feature = "render")]
        {
            let mut width = config.render_width;
            let mut height = config.render_height;
            for (c, _) in &cameras {
                width = width.max(c.width);
                height = height.max(c.height);
            }
            let mut renderer = crate::render::OffscreenRenderer::with_options(
                model,
                width,
                height,
                config.render_quality.supersampling(),
                config.render_gpu_device_id,
            )?;
            renderer.set_reflection(config.render_quality == super::RenderQuality::Robosuite);
            Ok(Some(Self {
                cameras,
                specs,
                frames,
                convention: config.image_convention,
                render_mode: config.render_mode,
                render_camera,
                instance_ids,
                class_ids,
                renderer: Some(renderer),
            }))
        }
        #[cfg(not(feature = "render"))]
        {
            let _ = (
                cameras,
                specs,
                frames,
                render_camera,
                instance_ids,
                class_ids,
            );
            Err(Error::unsupported(
                "camera observations and render modes need a build with the `render` feature \
                 (cargo feature robosuite-env/render)",
            ))
        }
    }

    /// The camera observables, in robosuite's order.
    pub fn specs(&self) -> &[ObsSpec] {
        &self.specs
    }

    /// The frames of the last [`CameraRig::observe`], one per spec.
    pub fn frames(&self) -> &[ArrayValue] {
        &self.frames
    }

    /// Uploads texture `texture` of `model` to the rig's renderer again (see
    /// [`crate::render::OffscreenRenderer::upload_texture`]).
    ///
    /// # Errors
    /// As [`crate::render::OffscreenRenderer::upload_texture`].
    #[cfg(feature = "render")]
    pub fn upload_texture(&mut self, model: &MjModel, texture: usize) -> Result<()> {
        self.renderer()?.upload_texture(model, texture)
    }

    /// The renderer, or [`Error::Closed`] once released.
    #[cfg(feature = "render")]
    fn renderer(&mut self) -> Result<&mut crate::render::OffscreenRenderer> {
        self.renderer.as_mut().ok_or(Error::Closed)
    }

    /// Drops the renderer (its OpenGL contexts go to the next renderer of an identical
    /// model, see [`crate::render`]); the env's `close` calls it. Rendering afterwards is
    /// [`Error::Closed`]; the frames of the last observation stay.
    pub fn release_renderer(&mut self) {
        #[cfg(feature = "render")]
        {
            self.renderer = None;
        }
    }

    /// The render mode chosen at construction.
    pub fn render_mode(&self) -> Option<RenderMode> {
        self.render_mode
    }

    /// Draws every observed camera into its frames.
    ///
    /// # Errors
    /// [`Error::Render`] when the OpenGL context fails.
    pub fn observe(&mut self, data: &mut Data) -> Result<()> {
        if self.cameras.is_empty() {
            return Ok(());
        }
        #[cfg(feature = "render")]
        {
            use crate::render::{Outputs, Request, View};
            let mut frames = self.frames.iter_mut();
            // Requests are made one at a time from the frames: nothing is allocated.
            let requests = self.cameras.iter().map(|(c, id)| {
                let mut out = Outputs::default();
                if let Some(ArrayValue::U8(a)) = frames.next() {
                    out.rgb = a.as_slice_mut();
                }
                if c.depth
                    && let Some(ArrayValue::F32(a)) = frames.next()
                {
                    out.depth = a.as_slice_mut();
                }
                // One element segmentation per camera is drawn (into its first segmentation
                // frame); the others are mapped from it.
                let mut first_seg: Option<&mut ArrayValue> = None;
                for _ in &c.segmentations {
                    let f = frames.next();
                    if first_seg.is_none() {
                        first_seg = f;
                    }
                }
                if let Some(ArrayValue::I32(a)) = first_seg {
                    out.segmentation = a.as_slice_mut();
                }
                Request {
                    camera: View::Fixed(*id),
                    width: c.width,
                    height: c.height,
                    out,
                }
            });
            self.renderer
                .as_mut()
                .ok_or(Error::Closed)?
                .render_each(data, requests)?;
            self.map_segmentations();
            if self.convention == ImageConvention::OpenCv {
                for f in &mut self.frames {
                    gym_core::for_each_array!(f, a => flip_rows(a));
                }
            }
            Ok(())
        }
        #[cfg(not(feature = "render"))]
        {
            let _ = data;
            Err(Error::unsupported("built without the `render` feature"))
        }
    }

    /// Turns each camera's drawn element segmentation (in its first segmentation frame)
    /// into its levels: the other frames first, from the drawn one, then the first in place.
    #[cfg(feature = "render")]
    fn map_segmentations(&mut self) {
        let mut at = 0;
        for (c, _) in &self.cameras {
            at += 1 + usize::from(c.depth);
            let Some((&first, rest)) = c.segmentations.split_first() else {
                continue;
            };
            let (head, tail) = self.frames.split_at_mut(at + 1);
            if let ArrayValue::I32(drawn) = &mut head[at] {
                for (level, frame) in rest.iter().zip(tail.iter_mut()) {
                    if let ArrayValue::I32(out) = frame {
                        out.zip_mut_with(drawn, |o, &d| *o = d);
                        Self::map_with(*level, &self.instance_ids, &self.class_ids, out);
                    }
                }
                Self::map_with(first, &self.instance_ids, &self.class_ids, drawn);
            }
            at += c.segmentations.len();
        }
    }

    /// Maps geom ids (`-1`: background) to `level`'s ids in place.
    #[cfg(feature = "render")]
    fn map_with(
        level: Segmentation,
        instance: &[i32],
        class: &[i32],
        ids: &mut ndarray::ArrayD<i32>,
    ) {
        let table = match level {
            Segmentation::Element => return,
            Segmentation::Instance => instance,
            Segmentation::Class => class,
        };
        ids.mapv_inplace(|g| {
            usize::try_from(g)
                .ok()
                .and_then(|g| table.get(g))
                .copied()
                .unwrap_or(0)
        });
    }

    /// Gymnasium's `render()`: the render camera at the render size, top row first (`u8`
    /// RGB for `rgb_array`, raw `f32` depth for `depth_array`); `None` without a render mode.
    ///
    /// # Errors
    /// [`Error::Render`] when the OpenGL context fails.
    pub fn render(&mut self, data: &mut Data) -> Result<Option<Frame>> {
        let Some(mode) = self.render_mode else {
            return Ok(None);
        };
        #[cfg(feature = "render")]
        {
            use crate::render::{Outputs, Request, View};
            let (camera, width, height) = self.render_camera;
            let frame = match mode {
                RenderMode::DepthArray => {
                    let mut depth = ndarray::Array2::<f32>::zeros((height, width));
                    let mut req = [Request {
                        camera: View::Fixed(camera),
                        width,
                        height,
                        out: Outputs {
                            depth: depth.as_slice_mut(),
                            ..Outputs::default()
                        },
                    }];
                    self.renderer()?.render(data, &mut req)?;
                    flip_rows(&mut depth);
                    Frame::Depth(depth)
                }
                _ => {
                    let mut rgb = ndarray::Array3::<u8>::zeros((height, width, 3));
                    let mut req = [Request {
                        camera: View::Fixed(camera),
                        width,
                        height,
                        out: Outputs {
                            rgb: rgb.as_slice_mut(),
                            ..Outputs::default()
                        },
                    }];
                    self.renderer()?.render(data, &mut req)?;
                    flip_rows(&mut rgb);
                    Frame::Rgb(rgb)
                }
            };
            Ok(Some(frame))
        }
        #[cfg(not(feature = "render"))]
        {
            let _ = (data, mode);
            Err(Error::unsupported("built without the `render` feature"))
        }
    }
}

/// Reverses the row order (axis 0) of a standard-layout array in place.
#[cfg(feature = "render")]
fn flip_rows<T, D: ndarray::Dimension>(a: &mut ndarray::Array<T, D>) {
    let rows = a.shape().first().copied().unwrap_or(0);
    if let Some(flat) = a.as_slice_mut()
        && rows > 1
    {
        let row = flat.len() / rows;
        for i in 0..rows / 2 {
            let (top, bottom) = flat.split_at_mut((rows - 1 - i) * row);
            top[i * row..(i + 1) * row].swap_with_slice(&mut bottom[..row]);
        }
    }
}
