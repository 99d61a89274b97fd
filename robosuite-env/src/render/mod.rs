//! Offscreen rendering with MuJoCo's own renderer (`mjv_updateScene`, `mjr_render`,
//! `mjr_readPixels`) on a headless EGL context: the frames behind robosuite's camera
//! observations and Gymnasium's `rgb_array` / `depth_array` render modes.
//!
//! One [`OffscreenRenderer`] per environment holds one OpenGL context, made current on the
//! calling thread for a render pass and released after it, so an environment (and its
//! renderer) can move between threads; each thread that renders uses its own contexts.
//! Frames come out as OpenGL reads them, bottom row first (robosuite's default
//! `IMAGE_CONVENTION = "opengl"`); depth is the raw z-buffer value in `[0, 1]`, as robosuite
//! returns it (see [`real_depth`]).

mod gl;
mod reuse;

pub use gl::{EGL_HINT, GlContext};

use crate::sim::Data;
use gym_core::{Error, Result};
use mujoco_rs::mujoco_c::mjtRndFlag;
use mujoco_rs::prelude::{
    MjModel, MjrContext, MjrRectangle, MjtFontScale, MjvCamera, MjvOption, MjvPerturb, MjvScene,
};

/// The scene capacity robosuite gives its render context (`maxgeom=10000`).
const MAX_GEOM: usize = 10_000;

/// The largest width or height a frame may have ([`crate::cameras::MAX_CAMERA_SIZE`]).
pub use crate::cameras::MAX_CAMERA_SIZE as MAX_SIZE;
use crate::cameras::check_size;

/// What one render of one camera writes; each buffer holds `height × width` pixels (×3 for
/// RGB), bottom row first.
#[derive(Debug, Default)]
pub struct Outputs<'a> {
    /// RGB bytes.
    pub rgb: Option<&'a mut [u8]>,
    /// Raw depth in `[0, 1]`.
    pub depth: Option<&'a mut [f32]>,
    /// Per-pixel id of the drawn object (robosuite's element segmentation: channel 1 of
    /// `sim.render(segmentation=True)`, the geom id for geoms), `-1` for the background.
    pub segmentation: Option<&'a mut [i32]>,
    /// Per-pixel type (`mjtObj`) of the drawn object (channel 0 of robosuite's
    /// `sim.render(segmentation=True)`: 5 for geoms, 6 for sites, ...), `-1` for the
    /// background. Drawn in the same segmentation pass as `segmentation`.
    pub segmentation_type: Option<&'a mut [i32]>,
}

/// Antialiasing without multisampling: frames drawn at `factor` times their size, each block
/// of sub-pixels averaged into one pixel (multisampling's cost on a CPU renderer grows with
/// its samples; supersampling's with the pixels drawn, so large frames skip it).
///
/// A frame whose larger side is at least `full_size_from` pixels is drawn at its own size.
/// With `factor` 4, only the four sub-pixels at the positions of OpenGL's standard 4×
/// multisampling pattern (`(0.375, 0.125)`, `(0.875, 0.375)`, `(0.125, 0.625)`,
/// `(0.625, 0.875)` of the pixel) are averaged; other factors average every sub-pixel.
/// Depth takes, for each pixel, the depth at sample 0 of that pattern (what a multisampled
/// depth buffer resolves to): at factor 4 its sub-pixel, otherwise the bottom-left sub-pixel
/// with the view moved by a fraction of a pixel to put its centre there (the RGB of a frame
/// with depth moves with it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Supersampling {
    /// Sub-pixels per side, 1..=4 (1: none).
    pub factor: usize,
    /// Frames whose width or height is at least this many pixels are drawn at their own size.
    pub full_size_from: usize,
}

impl Supersampling {
    /// No supersampling (frames drawn at their size; depth at the pixel centres).
    pub const NONE: Self = Self {
        factor: 1,
        full_size_from: usize::MAX,
    };

    /// `factor` for frames of every size.
    pub const fn at(factor: usize) -> Self {
        Self {
            factor,
            full_size_from: usize::MAX,
        }
    }

    /// The factor a `width × height` frame is drawn at.
    pub fn factor_for(&self, width: usize, height: usize) -> usize {
        if width.max(height) >= self.full_size_from {
            1
        } else {
            self.factor
        }
    }
}

impl Default for Supersampling {
    fn default() -> Self {
        Self::NONE
    }
}

/// MuJoCo's renderer on its own headless OpenGL context, drawing a model's fixed cameras.
pub struct OffscreenRenderer {
    // Dropped by `Drop` while the GL context is current; `None` only during the drop.
    context: Option<MjrContext>,
    scene: MjvScene,
    option: MjvOption,
    perturb: MjvPerturb,
    seg_rgb: Vec<u8>,
    seg_ids: Vec<i32>,
    fine_depth: Vec<f32>,
    size: (usize, usize),
    supersample: Supersampling,
    // `None` only during the drop.
    gl: Option<GlContext>,
    /// Where the contexts go when the renderer drops (`None`: freed, after a texture upload).
    reuse: Option<reuse::Key>,
}

impl std::fmt::Debug for OffscreenRenderer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OffscreenRenderer")
            .field("device", &self.device())
            .field("size", &self.size)
            .finish()
    }
}

// SAFETY: the MuJoCo rendering context (`MjrContext`, `!Send` because its GL objects belong
// to one GL context) is only touched while `gl` is current on the calling thread: every
// method that uses it makes the context current first and releases it before returning
// (including `Drop`), so the renderer holds no thread-bound state between calls.
unsafe impl Send for OffscreenRenderer {}

impl OffscreenRenderer {
    /// A renderer for `model` whose offscreen buffer holds frames up to `width × height`.
    ///
    /// # Errors
    /// [`Error::Render`] when no EGL context can be opened (the message names the missing
    /// library); [`Error::InvalidArgument`] for a zero size or one above [`MAX_SIZE`].
    pub fn new(model: &MjModel, width: usize, height: usize) -> Result<Self> {
        Self::with_options(model, width, height, Supersampling::NONE, None)
    }

    /// [`OffscreenRenderer::new`] on EGL device `device` (robosuite's
    /// `render_gpu_device_id`; `None`: `MUJOCO_EGL_DEVICE_ID`, else the first device that
    /// opens), see [`GlContext::with_device`].
    ///
    /// # Errors
    /// As [`OffscreenRenderer::new`]; [`Error::InvalidArgument`] for a device index that
    /// does not exist (the message lists the devices found).
    pub fn on_device(
        model: &MjModel,
        width: usize,
        height: usize,
        device: Option<usize>,
    ) -> Result<Self> {
        Self::with_options(model, width, height, Supersampling::NONE, device)
    }

    /// [`OffscreenRenderer::new`] drawing every frame at `factor` times its size and
    /// averaging each block of sub-pixels into one pixel ([`Supersampling::at`]).
    /// Segmentations are drawn at the frame's own size. A factor that would make the buffer
    /// larger than [`MAX_SIZE`] is lowered to 1.
    ///
    /// # Errors
    /// As [`OffscreenRenderer::new`]; [`Error::InvalidArgument`] for a factor of 0 or above 4.
    pub fn with_supersampling(
        model: &MjModel,
        width: usize,
        height: usize,
        factor: usize,
    ) -> Result<Self> {
        Self::with_options(model, width, height, Supersampling::at(factor), None)
    }

    /// [`OffscreenRenderer::new`] with `supersampling` (see [`Supersampling`];
    /// segmentations are drawn at the frame's own size) on EGL device `device` (see
    /// [`OffscreenRenderer::on_device`]). A factor that would make the buffer larger than
    /// [`MAX_SIZE`] is lowered to 1.
    ///
    /// # Errors
    /// As [`OffscreenRenderer::new`] and [`OffscreenRenderer::on_device`];
    /// [`Error::InvalidArgument`] for a factor of 0 or above 4.
    pub fn with_options(
        model: &MjModel,
        width: usize,
        height: usize,
        supersampling: Supersampling,
        device: Option<usize>,
    ) -> Result<Self> {
        Self::with_context_model(model, model, width, height, supersampling, device)
    }

    /// [`OffscreenRenderer::with_options`] drawing `model`'s scenes with a render context
    /// (meshes, textures, materials, visual settings) made from `context_model`: a model of
    /// the same scene that may differ from `model` only in its textures' images, such as
    /// the scene compiled with its images for a model compiled without them. MuJoCo's
    /// scene update (`mjv_updateScene`) reads no texture image, so the frames are those of
    /// `context_model`.
    ///
    /// # Errors
    /// As [`OffscreenRenderer::with_options`]; [`Error::InvalidArgument`] when the two
    /// models differ in their numbers of geoms, meshes, materials, textures, skins or
    /// height fields.
    pub fn with_context_model(
        model: &MjModel,
        context_model: &MjModel,
        width: usize,
        height: usize,
        supersampling: Supersampling,
        device: Option<usize>,
    ) -> Result<Self> {
        let counts = |m: &MjModel| {
            let m = m.ffi();
            [m.ngeom, m.nmesh, m.nmat, m.ntex, m.nskin, m.nhfield]
        };
        if counts(model) != counts(context_model) {
            return Err(Error::invalid_argument(
                "context_model",
                "must be a model of the same scene (its numbers of geoms, meshes, materials, \
                 textures, skins and height fields differ)",
            ));
        }
        check_size("width", width)?;
        check_size("height", height)?;
        let factor = supersampling.factor;
        if !(1..=4).contains(&factor) {
            return Err(Error::invalid_argument(
                "supersample",
                format!("must be in 1..=4, got {factor}"),
            ));
        }
        // The buffer holds every frame that fits `width × height` at the factor it is drawn
        // at: the sides below `full_size_from` at `factor`, the others at 1.
        let buffer = |side: usize, s: Supersampling| {
            side.max(s.factor * side.min(s.full_size_from.saturating_sub(1)))
        };
        let supersampling = if buffer(width, supersampling) <= MAX_SIZE
            && buffer(height, supersampling) <= MAX_SIZE
        {
            supersampling
        } else {
            Supersampling::NONE
        };
        let (buffer_w, buffer_h) = (
            buffer(width, supersampling) as u32,
            buffer(height, supersampling) as u32,
        );
        let key = reuse::Key::of(context_model, device);
        let kept = reuse::take(&key).and_then(|(mut gl, mut context)| {
            match gl.make_current() {
                Ok(_current) => {
                    context.resize_offscreen(buffer_w, buffer_h);
                    context.offscreen();
                }
                // Its GL context is lost: its objects cannot be freed, so they are leaked.
                Err(_) => {
                    std::mem::forget(context);
                    return None;
                }
            }
            Some((gl, context))
        });
        let (gl, context) = match kept {
            Some(kept) => kept,
            None => {
                let mut gl = GlContext::with_device(device)?;
                let context = {
                    let _current = gl.make_current()?;
                    // SAFETY: the GL context is current on this thread; the MjrContext is
                    // only used (and dropped) while it is current again (see `Send` above).
                    let mut context = unsafe { MjrContext::new(context_model) };
                    context.change_font(MjtFontScale::mjFONTSCALE_150);
                    context.resize_offscreen(buffer_w, buffer_h);
                    context.offscreen();
                    context
                };
                (gl, context)
            }
        };
        // robosuite's defaults (`render_collision_mesh=False`, `render_visual_mesh=True`):
        // geom group 0 (collision) hidden, group 1 (visual) shown.
        let mut option = MjvOption::default();
        option.geomgroup[0] = 0;
        option.geomgroup[1] = 1;
        Ok(Self {
            context: Some(context),
            // Made for the context's model: the scene and the context describe one model.
            scene: MjvScene::new(context_model, MAX_GEOM),
            option,
            perturb: MjvPerturb::default(),
            seg_rgb: Vec::new(),
            seg_ids: Vec::new(),
            fine_depth: Vec::new(),
            size: (width, height),
            supersample: supersampling,
            gl: Some(gl),
            reuse: Some(key),
        })
    }

    /// The EGL device drawing the frames.
    pub fn device(&self) -> &str {
        self.gl.as_ref().map_or("", GlContext::device)
    }

    /// Shows or hides geom group `group` (0..6); robosuite's `render_collision_mesh` is
    /// group 0 and `render_visual_mesh` group 1 (defaults: hidden, shown).
    pub fn set_geom_group(&mut self, group: usize, visible: bool) {
        if let Some(g) = self.option.geomgroup.get_mut(group) {
            *g = u8::from(visible);
        }
    }

    /// Uploads texture `texture` of `model` to this renderer's OpenGL context again (MuJoCo's
    /// `mjr_uploadTexture`), so frames show a texture whose bitmap (`tex_data`) was changed
    /// after the renderer was made.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a texture id out of range (nothing is uploaded);
    /// [`Error::Render`] when the context cannot be made current.
    pub fn upload_texture(&mut self, model: &MjModel, texture: usize) -> Result<()> {
        let ntex = model.ffi().ntex.max(0) as usize;
        if texture >= ntex {
            return Err(Error::invalid_argument(
                "texture",
                format!("texture id {texture} out of range (the model has {ntex} textures)"),
            ));
        }
        let gl = self
            .gl
            .as_mut()
            .ok_or_else(|| Error::Render("no OpenGL context".into()))?;
        let _current = gl.make_current()?;
        let context = self
            .context
            .as_ref()
            .ok_or_else(|| Error::Render("no rendering context".into()))?;
        // The context's textures are no longer the model's as compiled: it is not reused.
        self.reuse = None;
        context
            .upload_texture(model, texture)
            .map_err(|e| Error::Render(format!("mjr_uploadTexture: {e}")))
    }

    /// Draws (`true`, MuJoCo's default) or skips the mirrored scene of reflective planes and
    /// boxes (`mjRND_REFLECTION`).
    pub fn set_reflection(&mut self, on: bool) {
        // SAFETY: one render flag changes; no invariant of the wrapper depends on it.
        let ffi = unsafe { self.scene.ffi_mut() };
        ffi.flags[mjtRndFlag::mjRND_REFLECTION as usize] = u8::from(on);
    }

    /// The largest frame (width, height) the offscreen buffer holds.
    pub fn max_size(&self) -> (usize, usize) {
        self.size
    }

    /// Draws fixed camera `camera` of `data`'s model at `width × height` for each request,
    /// with the context current once for all of them.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an unknown camera id, a size beyond
    /// [`OffscreenRenderer::max_size`] or a buffer of the wrong length (nothing is drawn);
    /// [`Error::Render`] when the context cannot be made current.
    pub fn render(&mut self, data: &mut Data, requests: &mut [Request<'_>]) -> Result<()> {
        for r in requests.iter() {
            check(self.size, data, r)?;
        }
        self.render_each(
            data,
            requests.iter_mut().map(|r| Request {
                camera: r.camera,
                width: r.width,
                height: r.height,
                out: Outputs {
                    rgb: r.out.rgb.as_deref_mut(),
                    depth: r.out.depth.as_deref_mut(),
                    segmentation: r.out.segmentation.as_deref_mut(),
                    segmentation_type: r.out.segmentation_type.as_deref_mut(),
                },
            }),
        )
    }

    /// [`OffscreenRenderer::render`] for requests made one at a time (no list of them is
    /// kept, so a render pass allocates nothing); each is checked just before it is drawn.
    ///
    /// # Errors
    /// As [`OffscreenRenderer::render`]; the requests before a bad one are drawn.
    pub fn render_each<'a>(
        &mut self,
        data: &mut Data,
        requests: impl IntoIterator<Item = Request<'a>>,
    ) -> Result<()> {
        let mut requests = requests.into_iter().peekable();
        if requests.peek().is_none() {
            return Ok(());
        }
        let Self {
            context,
            scene,
            option,
            perturb,
            seg_rgb,
            seg_ids,
            fine_depth,
            size,
            supersample,
            gl,
            reuse: _,
        } = self;
        let context = context
            .as_ref()
            .ok_or_else(|| Error::Render("the rendering context was freed".into()))?;
        let _current = gl
            .as_mut()
            .ok_or_else(|| Error::Render("no OpenGL context".into()))?
            .make_current()?;
        let mut pass = Pass {
            context,
            scene,
            option,
            perturb,
            seg_rgb,
            seg_ids,
            fine_depth,
            supersample: *supersample,
        };
        for mut r in requests {
            check(*size, data, &r)?;
            pass.draw(data, &mut r)?;
        }
        Ok(())
    }
}

/// The renderer's parts one render pass uses, borrowed while the context is current.
struct Pass<'p> {
    context: &'p MjrContext,
    scene: &'p mut MjvScene,
    option: &'p MjvOption,
    perturb: &'p MjvPerturb,
    seg_rgb: &'p mut Vec<u8>,
    seg_ids: &'p mut Vec<i32>,
    fine_depth: &'p mut Vec<f32>,
    supersample: Supersampling,
}

/// Checks one request against the model and the offscreen buffer of `size`.
fn check(size: (usize, usize), data: &Data, r: &Request<'_>) -> Result<()> {
    let ncam = data.model().ffi().ncam as usize;
    match r.camera {
        View::Fixed(id) if id >= ncam => {
            return Err(Error::invalid_argument(
                "camera",
                format!("camera id {id} out of range (the model has {ncam})"),
            ));
        }
        View::Free(c)
            if !(c.lookat.iter().all(|v| v.is_finite())
                && c.distance.is_finite()
                && c.distance > 0.0
                && c.azimuth.is_finite()
                && c.elevation.is_finite()) =>
        {
            return Err(Error::invalid_argument(
                "camera",
                format!("the free camera needs finite values and a distance > 0, got {c:?}"),
            ));
        }
        _ => {}
    }
    if r.width == 0 || r.height == 0 || r.width > size.0 || r.height > size.1 {
        return Err(Error::invalid_argument(
            "size",
            format!(
                "{}x{} does not fit the renderer's {}x{} buffer",
                r.width, r.height, size.0, size.1
            ),
        ));
    }
    let n = r.width * r.height;
    let bad = r.out.rgb.as_ref().is_some_and(|b| b.len() != 3 * n)
        || r.out.depth.as_ref().is_some_and(|b| b.len() != n)
        || r.out.segmentation.as_ref().is_some_and(|b| b.len() != n)
        || r.out
            .segmentation_type
            .as_ref()
            .is_some_and(|b| b.len() != n);
    if bad {
        return Err(Error::invalid_argument(
            "outputs",
            format!("buffers must hold {}x{} pixels", r.width, r.height),
        ));
    }
    Ok(())
}

impl Pass<'_> {
    /// Draws one checked request; the context must be current.
    fn draw(&mut self, data: &mut Data, r: &mut Request<'_>) -> Result<()> {
        let Self {
            context,
            scene,
            option,
            perturb,
            seg_rgb,
            seg_ids,
            fine_depth,
            supersample,
        } = self;
        let context: &MjrContext = context;
        let f = supersample.factor_for(r.width, r.height);
        // Depth is read at the multisampling pattern's sample 0: factor 4 has a sub-pixel
        // there; otherwise the view moves to put the bottom-left sub-pixel's centre there.
        let shift = (r.out.depth.is_some() && supersample.factor > 1 && f != 4).then(|| {
            let centre = 0.5 / f as f32;
            (SAMPLE_0.0 - centre, SAMPLE_0.1 - centre)
        });
        let mut camera = match r.camera {
            View::Fixed(id) => MjvCamera::new_fixed(id),
            View::Free(c) => MjvCamera {
                type_: mujoco_rs::mujoco_c::mjtCamera::mjCAMERA_FREE as i32,
                lookat: c.lookat,
                distance: c.distance,
                azimuth: c.azimuth,
                elevation: c.elevation,
                ..MjvCamera::default()
            },
        };
        let (m, d) = data.raw_mut();
        let (opt, pert): (&MjvOption, &MjvPerturb) = (option, perturb);
        // SAFETY: `check` put a fixed camera id in range (a free camera reads no id); the scene was made for this
        // model (`OffscreenRenderer::new`), `perturb.select` is 0 (the world body); MuJoCo
        // writes only the scene and the data's visualisation fields.
        unsafe {
            mujoco_rs::mujoco_c::mjv_updateScene(
                m,
                d,
                opt,
                pert,
                &mut camera,
                mujoco_rs::mujoco_c::mjtCatBit::mjCAT_ALL as i32,
                scene.ffi_mut(),
            );
        }
        let viewport = MjrRectangle::new(0, 0, r.width as i32, r.height as i32);
        // Geoms the camera cannot see are dropped before drawing (identical frames, less
        // geometry); their segment ids stay as `mjv_updateScene` gave them.
        let segments = scene.ffi().ngeom.max(0) as usize;
        // The cameras as `mjv_updateScene` set them (restored after a moved view).
        let cameras = shift.map(|(dx, dy)| {
            let saved = scene.ffi().camera.clone();
            shift_view(scene, r.width, r.height, dx, dy);
            saved
        });
        cull_outside_view(scene, r.width as f32 / r.height as f32);
        if f == 1 && (r.out.rgb.is_some() || r.out.depth.is_some()) {
            scene.render(&viewport, context);
            context
                .read_pixels(
                    r.out.rgb.as_deref_mut(),
                    r.out.depth.as_deref_mut(),
                    &viewport,
                )
                .map_err(|e| Error::Render(format!("mjr_readPixels: {e}")))?;
        } else if r.out.rgb.is_some() || r.out.depth.is_some() {
            let fine = MjrRectangle::new(0, 0, (f * r.width) as i32, (f * r.height) as i32);
            let n = f * f * r.width * r.height;
            scene.render(&fine, context);
            seg_rgb.resize(3 * n, 0);
            fine_depth.resize(if r.out.depth.is_some() { n } else { 0 }, 0.0);
            context
                .read_pixels(
                    r.out.rgb.as_ref().map(|_| seg_rgb.as_mut_slice()),
                    r.out.depth.as_ref().map(|_| fine_depth.as_mut_slice()),
                    &fine,
                )
                .map_err(|e| Error::Render(format!("mjr_readPixels: {e}")))?;
            let samples = sample_pattern(f);
            if let Some(rgb) = r.out.rgb.as_deref_mut() {
                downsample_rgb(seg_rgb, rgb, r.width, f, samples);
            }
            if let Some(depth) = r.out.depth.as_deref_mut() {
                let row = f * r.width;
                let (sx, sy) = if shift.is_some() { (0, 0) } else { samples[0] };
                for (y, out) in depth.chunks_exact_mut(r.width).enumerate() {
                    let fine_row = &fine_depth[(f * y + sy) * row..][..row];
                    for (x, o) in out.iter_mut().enumerate() {
                        *o = fine_row[f * x + sx];
                    }
                }
            }
        }
        if let Some(saved) = cameras {
            // SAFETY: the cameras `mjv_updateScene` set come back unchanged.
            unsafe { scene.ffi_mut() }.camera = saved;
        }
        if r.out.segmentation.is_some() || r.out.segmentation_type.is_some() {
            set_segmentation_flags(scene, true);
            scene.render(&viewport, context);
            set_segmentation_flags(scene, false);
            seg_rgb.resize(3 * r.width * r.height, 0);
            context
                .read_pixels(Some(seg_rgb), None, &viewport)
                .map_err(|e| Error::Render(format!("mjr_readPixels: {e}")))?;
            if let Some(seg) = r.out.segmentation.as_deref_mut() {
                decode_segmentation(scene, segments, seg_rgb, seg_ids, seg, |g| g.objid);
            }
            if let Some(seg) = r.out.segmentation_type.as_deref_mut() {
                decode_segmentation(scene, segments, seg_rgb, seg_ids, seg, |g| g.objtype);
            }
        }
        Ok(())
    }
}

/// Sample 0 of OpenGL's standard 4× multisampling pattern, in pixels from the pixel's bottom
/// left corner: the sample a multisampled depth buffer resolves to.
const SAMPLE_0: (f32, f32) = (0.375, 0.125);

/// The sub-pixels `(x, y)` (from the bottom left) of an `f × f` block that make one pixel:
/// for `f = 4`, the four positions of OpenGL's standard 4× multisampling pattern (`(0.375,
/// 0.125)`, `(0.875, 0.375)`, `(0.125, 0.625)`, `(0.625, 0.875)` of the pixel, sample 0
/// first: the one a multisampled depth buffer resolves to); otherwise every sub-pixel.
fn sample_pattern(f: usize) -> &'static [(usize, usize)] {
    match f {
        4 => &[(1, 0), (3, 1), (0, 2), (2, 3)],
        2 => &[(0, 0), (1, 0), (0, 1), (1, 1)],
        3 => &[
            (0, 0),
            (1, 0),
            (2, 0),
            (0, 1),
            (1, 1),
            (2, 1),
            (0, 2),
            (1, 2),
            (2, 2),
        ],
        _ => &[(0, 0)],
    }
}

/// Averages the `samples` of each `f × f` block of the RGB frame `fine` (`f · width` pixels
/// a row) into one pixel of `out` (`width` pixels a row), rounding to nearest.
fn downsample_rgb(fine: &[u8], out: &mut [u8], width: usize, f: usize, samples: &[(usize, usize)]) {
    let fine_row = 3 * f * width;
    let count = samples.len().max(1) as u32;
    for (y, out_row) in out.chunks_exact_mut(3 * width).enumerate() {
        let block = &fine[f * y * fine_row..][..f * fine_row];
        for (x, px) in out_row.chunks_exact_mut(3).enumerate() {
            for (c, v) in px.iter_mut().enumerate() {
                let sum: u32 = samples
                    .iter()
                    .map(|&(dx, dy)| u32::from(block[dy * fine_row + 3 * (f * x + dx) + c]))
                    .sum();
                *v = ((sum + count / 2) / count) as u8;
            }
        }
    }
}

/// The camera a request draws from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum View {
    /// A fixed camera of the model, by id.
    Fixed(usize),
    /// MuJoCo's free camera (robosuite's camera id `-1`).
    Free(FreeCamera),
}

impl From<usize> for View {
    fn from(id: usize) -> Self {
        Self::Fixed(id)
    }
}

/// MuJoCo's free camera: it looks at `lookat` from `distance` metres, turned by `azimuth`
/// and `elevation` degrees (`mjvCamera`'s fields).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeCamera {
    /// The point looked at.
    pub lookat: [f64; 3],
    /// Distance from the point, metres (> 0).
    pub distance: f64,
    /// Azimuth, degrees.
    pub azimuth: f64,
    /// Elevation, degrees.
    pub elevation: f64,
}

impl Default for FreeCamera {
    /// `mjv_defaultCamera`'s (what robosuite's render context draws for camera id `-1`).
    fn default() -> Self {
        Self {
            lookat: [0.0; 3],
            distance: 2.0,
            azimuth: 90.0,
            elevation: -45.0,
        }
    }
}

/// One camera to draw and where its pixels go.
#[derive(Debug)]
pub struct Request<'a> {
    /// The camera.
    pub camera: View,
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// The buffers to fill.
    pub out: Outputs<'a>,
}

impl Drop for OffscreenRenderer {
    fn drop(&mut self) {
        if let (Some(context), Some(gl)) = (self.context.take(), self.gl.take()) {
            match self.reuse.take() {
                Some(key) => reuse::put(key, gl, context),
                None => reuse::free(gl, context),
            }
        }
    }
}

fn set_segmentation_flags(scene: &mut MjvScene, on: bool) {
    // SAFETY: only two render flags change; no invariant of the wrapper depends on them.
    let ffi = unsafe { scene.ffi_mut() };
    ffi.flags[mjtRndFlag::mjRND_SEGMENT as usize] = u8::from(on);
    ffi.flags[mjtRndFlag::mjRND_IDCOLOR as usize] = u8::from(on);
}

/// robosuite's `read_pixels(segmentation=True)[..., 1]` (or `[..., 0]`, by `field`): the segment colour `r + 256 g +
/// 65536 b` is `segid + 1` of a scene geom (0: background), mapped to that geom's `objid`
/// (`-1` where no geom was drawn). `segments` is the number of segment ids
/// `mjv_updateScene` gave (the scene's geom count before culling).
fn decode_segmentation(
    scene: &MjvScene,
    segments: usize,
    rgb: &[u8],
    ids: &mut Vec<i32>,
    out: &mut [i32],
    field: impl Fn(&mujoco_rs::mujoco_c::mjvGeom) -> i32,
) {
    let ffi = scene.ffi();
    let ngeom = ffi.ngeom.max(0) as usize;
    ids.clear();
    ids.resize(segments + 1, -1);
    // SAFETY: `geoms` holds `ngeom` initialised entries after `mjv_updateScene`.
    let geoms = unsafe { std::slice::from_raw_parts(ffi.geoms, ngeom) };
    for g in geoms {
        if g.segid >= 0 && (g.segid as usize) < segments {
            ids[g.segid as usize + 1] = field(g);
        }
    }
    for (px, o) in rgb.chunks_exact(3).zip(out.iter_mut()) {
        let c = px[0] as usize | (px[1] as usize) << 8 | (px[2] as usize) << 16;
        *o = if c <= segments { ids[c] } else { ids[0] };
    }
}

/// Moves the view window of the scene's cameras by `(dx, dy)` pixels of a `width × height`
/// frame, so that each pixel shows what the point `(dx, dy)` pixels from its centre showed.
fn shift_view(scene: &mut MjvScene, width: usize, height: usize, dx: f32, dy: f32) {
    // SAFETY: only the two scene cameras' frustum values change.
    let ffi = unsafe { scene.ffi_mut() };
    let aspect = width as f32 / height as f32;
    for cam in &mut ffi.camera {
        // `mjr_render`'s half width of the window at the near plane.
        let half = if cam.frustum_width != 0.0 {
            cam.frustum_width
        } else {
            0.5 * aspect * (cam.frustum_top - cam.frustum_bottom)
        };
        let pixel_y = (cam.frustum_top - cam.frustum_bottom) / height as f32;
        cam.frustum_center += dx * 2.0 * half / width as f32;
        cam.frustum_bottom += dy * pixel_y;
        cam.frustum_top += dy * pixel_y;
    }
}

/// Whether MuJoCo draws anything of the scene outside the camera's view volume: a floor or
/// box reflection (the mirrored scene) or a shadow (geoms out of view cast shadows in view).
fn draws_outside_view(ffi: &mujoco_rs::mujoco_c::mjvScene) -> bool {
    use mujoco_rs::mujoco_c::mjtGeom;
    let ngeom = ffi.ngeom.max(0) as usize;
    let nlight = ffi.nlight.clamp(0, ffi.lights.len() as i32) as usize;
    // SAFETY: `geoms` holds `ngeom` initialised entries after `mjv_updateScene`.
    let geoms = unsafe { std::slice::from_raw_parts(ffi.geoms, ngeom) };
    let reflection = ffi.flags[mjtRndFlag::mjRND_REFLECTION as usize] != 0
        && geoms.iter().any(|g| {
            (g.type_ == mjtGeom::mjGEOM_PLANE as i32 || g.type_ == mjtGeom::mjGEOM_BOX as i32)
                && g.reflectance > 0.0
        });
    let shadow = ffi.flags[mjtRndFlag::mjRND_SHADOW as usize] != 0
        && ffi.lights[..nlight].iter().any(|l| l.castshadow != 0);
    reflection || shadow
}

/// Drops from the scene the model geoms whose bounding sphere (`modelrbound` around the
/// geom's position) lies wholly outside the view volume of the scene's camera, for a
/// viewport of `aspect` (width / height), as `mjr_render` sets it up. Nothing it drops
/// could reach a pixel: it does nothing when the scene draws reflections or shadows, or for
/// an orthographic camera; geoms without a model bound (decor, planes) are kept, and the
/// order of the kept ones is unchanged.
fn cull_outside_view(scene: &mut MjvScene, aspect: f32) {
    // SAFETY: geoms are only reordered and `ngeom` lowered; MuJoCo reads nothing else from
    // the culled entries.
    let ffi = unsafe { scene.ffi_mut() };
    if draws_outside_view(ffi) {
        return;
    }
    // SAFETY: both cameras were set by `mjv_updateScene`; `mjr_render` draws their average.
    let cam = unsafe { mujoco_rs::mujoco_c::mjv_averageCamera(&ffi.camera[0], &ffi.camera[1]) };
    if cam.orthographic != 0
        || cam.frustum_near.is_nan()
        || cam.frustum_near <= 0.0
        || !aspect.is_finite()
    {
        return;
    }
    let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let norm = |a: [f32; 3]| {
        let n = dot(a, a).sqrt();
        [a[0] / n, a[1] / n, a[2] / n]
    };
    let fwd = norm(cam.forward);
    let up = norm(cam.up);
    // gluLookAt's x axis: forward × up.
    let right = norm([
        fwd[1] * up[2] - fwd[2] * up[1],
        fwd[2] * up[0] - fwd[0] * up[2],
        fwd[0] * up[1] - fwd[1] * up[0],
    ]);
    let near = cam.frustum_near;
    let half = if cam.frustum_width != 0.0 {
        cam.frustum_width
    } else {
        0.5 * aspect * (cam.frustum_top - cam.frustum_bottom)
    };
    let (left, rightx) = (cam.frustum_center - half, cam.frustum_center + half);
    let (bottom, top) = (cam.frustum_bottom, cam.frustum_top);
    // Inward unit normals (in the (x, z) or (y, z) plane) of the four side planes.
    let side = |a: f32, sign: f32| {
        let l = (near * near + a * a).sqrt();
        (sign * near / l, -sign * a / l)
    };
    let planes = [
        (0, side(left, 1.0)),
        (0, side(rightx, -1.0)),
        (1, side(bottom, 1.0)),
        (1, side(top, -1.0)),
    ];
    let ngeom = ffi.ngeom.max(0) as usize;
    // SAFETY: `geoms` holds `ngeom` initialised entries after `mjv_updateScene`.
    let geoms = unsafe { std::slice::from_raw_parts_mut(ffi.geoms, ngeom) };
    let mut kept = 0;
    for i in 0..ngeom {
        let g = &geoms[i];
        // A margin of 1 % and 1 mm against rounding: culling less is always safe.
        let r = g.modelrbound * 1.01 + 1e-3;
        let outside = g.modelrbound > 0.0 && {
            let v = [
                g.pos[0] - cam.pos[0],
                g.pos[1] - cam.pos[1],
                g.pos[2] - cam.pos[2],
            ];
            let xy = [dot(v, right), dot(v, up)];
            let z = dot(v, fwd);
            z < near - r
                || z > cam.frustum_far + r
                || planes
                    .iter()
                    .any(|&(axis, (nx, nz))| nx * xy[axis] + nz * z < -r)
        };
        if !outside {
            geoms.swap(kept, i);
            kept += 1;
        }
    }
    ffi.ngeom = kept as i32;
}

/// robosuite's `get_real_depth_map`: a raw depth value in `[0, 1]` as a distance in metres,
/// `near / (1 - d (1 - near / far))` with `near = znear · extent`, `far = zfar · extent`.
pub fn real_depth(model: &MjModel, depth: f32) -> f64 {
    let extent = model.stat().extent;
    let map = &model.vis().map;
    let near = f64::from(map.znear) * extent;
    let far = f64::from(map.zfar) * extent;
    near / (1.0 - f64::from(depth) * (1.0 - near / far))
}
