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

/// MuJoCo's renderer on its own headless OpenGL context, drawing a model's fixed cameras.
pub struct OffscreenRenderer {
    // Dropped by `Drop` while the GL context is current; `None` only during the drop.
    context: Option<MjrContext>,
    scene: MjvScene,
    option: MjvOption,
    perturb: MjvPerturb,
    seg_rgb: Vec<u8>,
    seg_ids: Vec<i32>,
    size: (usize, usize),
    gl: GlContext,
}

impl std::fmt::Debug for OffscreenRenderer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OffscreenRenderer")
            .field("device", &self.gl.device())
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
        Self::on_device(model, width, height, None)
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
        check_size("width", width)?;
        check_size("height", height)?;
        let mut gl = GlContext::with_device(device)?;
        let context = {
            let _current = gl.make_current()?;
            // SAFETY: the GL context is current on this thread; the MjrContext is only used
            // (and dropped) while it is current again (see `Send` above).
            let mut context = unsafe { MjrContext::new(model) };
            context.change_font(MjtFontScale::mjFONTSCALE_150);
            context.resize_offscreen(width as u32, height as u32);
            context.offscreen();
            context
        };
        // robosuite's defaults (`render_collision_mesh=False`, `render_visual_mesh=True`):
        // geom group 0 (collision) hidden, group 1 (visual) shown.
        let mut option = MjvOption::default();
        option.geomgroup[0] = 0;
        option.geomgroup[1] = 1;
        Ok(Self {
            context: Some(context),
            scene: MjvScene::new(model, MAX_GEOM),
            option,
            perturb: MjvPerturb::default(),
            seg_rgb: Vec::new(),
            seg_ids: Vec::new(),
            size: (width, height),
            gl,
        })
    }

    /// The EGL device drawing the frames.
    pub fn device(&self) -> &str {
        self.gl.device()
    }

    /// Shows or hides geom group `group` (0..6); robosuite's `render_collision_mesh` is
    /// group 0 and `render_visual_mesh` group 1 (defaults: hidden, shown).
    pub fn set_geom_group(&mut self, group: usize, visible: bool) {
        if let Some(g) = self.option.geomgroup.get_mut(group) {
            *g = u8::from(visible);
        }
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
            size,
            gl,
        } = self;
        let context = context
            .as_ref()
            .ok_or_else(|| Error::Render("the rendering context was freed".into()))?;
        let _current = gl.make_current()?;
        let mut pass = Pass {
            context,
            scene,
            option,
            perturb,
            seg_rgb,
            seg_ids,
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
        } = self;
        let context: &MjrContext = context;
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
        if r.out.rgb.is_some() || r.out.depth.is_some() {
            scene.render(&viewport, context);
            context
                .read_pixels(
                    r.out.rgb.as_deref_mut(),
                    r.out.depth.as_deref_mut(),
                    &viewport,
                )
                .map_err(|e| Error::Render(format!("mjr_readPixels: {e}")))?;
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
                decode_segmentation(scene, seg_rgb, seg_ids, seg, |g| g.objid);
            }
            if let Some(seg) = r.out.segmentation_type.as_deref_mut() {
                decode_segmentation(scene, seg_rgb, seg_ids, seg, |g| g.objtype);
            }
        }
        Ok(())
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
        if let Some(context) = self.context.take() {
            match self.gl.make_current() {
                Ok(_current) => drop(context),
                // Freeing GL objects without their context is undefined: leak them instead.
                Err(_) => std::mem::forget(context),
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
/// (`-1` where no geom was drawn).
fn decode_segmentation(
    scene: &MjvScene,
    rgb: &[u8],
    ids: &mut Vec<i32>,
    out: &mut [i32],
    field: impl Fn(&mujoco_rs::mujoco_c::mjvGeom) -> i32,
) {
    let ffi = scene.ffi();
    let ngeom = ffi.ngeom.max(0) as usize;
    ids.clear();
    ids.resize(ngeom + 1, -1);
    // SAFETY: `geoms` holds `ngeom` initialised entries after `mjv_updateScene`.
    let geoms = unsafe { std::slice::from_raw_parts(ffi.geoms, ngeom) };
    for g in geoms {
        if g.segid >= 0 && (g.segid as usize) < ngeom {
            ids[g.segid as usize + 1] = field(g);
        }
    }
    for (px, o) in rgb.chunks_exact(3).zip(out.iter_mut()) {
        let c = px[0] as usize | (px[1] as usize) << 8 | (px[2] as usize) << 16;
        *o = if c <= ngeom { ids[c] } else { ids[0] };
    }
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
