//! A headless OpenGL context on EGL: the first EGL device that opens one (a GPU through its
//! vendor's EGL, or Mesa's software device on a CPU-only machine), with no display or window.

use glutin::api::egl::context::{NotCurrentContext, PossiblyCurrentContext};
use glutin::api::egl::device::Device;
use glutin::api::egl::display::Display;
use glutin::api::egl::surface::Surface;
use glutin::config::{ConfigSurfaceTypes, ConfigTemplateBuilder};
use glutin::context::{ContextApi, ContextAttributesBuilder, GlProfile, Version};
use glutin::prelude::{GlDisplay, NotCurrentGlContext, PossiblyCurrentGlContext};
use glutin::surface::{PbufferSurface, SurfaceAttributesBuilder};
use gym_core::{Error, Result};
use std::num::NonZero;

/// What to install when EGL cannot be loaded or opens no device.
pub const EGL_HINT: &str = "install libEGL (Debian/Ubuntu: apt-get install libegl1 libegl-mesa0 \
                            libgl1-mesa-dri; `make test` does this when run as root)";

/// An offscreen OpenGL context that is current on no thread between uses, so the value can
/// move between threads: [`GlContext::make_current`] makes it current on the calling thread
/// and the returned guard releases it again.
#[derive(Debug)]
pub struct GlContext {
    // `Option` only so that the guard can move the context in and out of the current state.
    context: Option<NotCurrentContext>,
    surface: Surface<PbufferSurface>,
    device: String,
}

/// The context made current on this thread; dropping it releases the context.
#[derive(Debug)]
pub struct CurrentGuard<'a> {
    owner: &'a mut GlContext,
    context: Option<PossiblyCurrentContext>,
}

impl Drop for CurrentGuard<'_> {
    fn drop(&mut self) {
        if let Some(c) = self.context.take() {
            // A failed release leaves the context current on this thread, where the next
            // `make_current` on this thread still succeeds.
            match c.make_not_current() {
                Ok(nc) => self.owner.context = Some(nc),
                Err(_) => self.owner.context = None,
            }
        }
    }
}

/// An EGL device by what identifies it: its DRM node, `"Mesa software"`, or its name.
fn describe(device: &Device) -> String {
    if let Some(path) = device.drm_device_node_path() {
        path.display().to_string()
    } else if device.extensions().contains("EGL_MESA_device_software") {
        "Mesa software".to_owned()
    } else {
        device.name().unwrap_or("unnamed").to_owned()
    }
}

impl GlContext {
    /// Opens a context on the first EGL device that gives one.
    ///
    /// # Errors
    /// [`Error::Render`] naming the missing library when libEGL cannot be loaded, or saying
    /// why no device opened a context.
    pub fn new() -> Result<Self> {
        Self::with_device(None)
    }

    /// Opens a context on EGL device `index` (in EGL's `EGL_EXT_device_enumeration`
    /// order), or with `None` on the device `MUJOCO_EGL_DEVICE_ID` names (as MuJoCo's own
    /// Python bindings do) or else the first that gives one.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] (naming `render_gpu_device_id`, or `MUJOCO_EGL_DEVICE_ID`
    /// for a value from the environment) for an index that does not exist, listing the
    /// devices found; [`Error::Render`] as [`GlContext::new`], or when the chosen device
    /// gives no context.
    pub fn with_device(index: Option<usize>) -> Result<Self> {
        let devices: Vec<Device> = Device::query_devices()
            .map_err(|e| Error::Render(format!("cannot load libEGL.so.1 ({e}); {EGL_HINT}")))?
            .collect();
        let chosen = match index {
            Some(i) => Some((i, "render_gpu_device_id")),
            None => match std::env::var("MUJOCO_EGL_DEVICE_ID") {
                Ok(v) => Some((
                    v.trim().parse::<usize>().map_err(|_| {
                        Error::invalid_argument(
                            "MUJOCO_EGL_DEVICE_ID",
                            format!("must be a device index (an int >= 0), got {v:?}"),
                        )
                    })?,
                    "MUJOCO_EGL_DEVICE_ID",
                )),
                Err(_) => None,
            },
        };
        if let Some((i, name)) = chosen {
            let found = devices
                .iter()
                .enumerate()
                .map(|(j, d)| format!("{j}: {}", describe(d)))
                .collect::<Vec<_>>();
            let device = devices.get(i).ok_or_else(|| {
                Error::invalid_argument(
                    name,
                    format!(
                        "EGL device {i} does not exist; EGL lists {} device(s): [{}]",
                        found.len(),
                        found.join(", ")
                    ),
                )
            })?;
            return Self::on_device(device).map_err(|e| {
                Error::Render(format!(
                    "EGL device {i} ({}) opened no OpenGL context ({e}); {EGL_HINT}",
                    describe(device)
                ))
            });
        }
        let mut last = None;
        for device in devices {
            match Self::on_device(&device) {
                Ok(c) => return Ok(c),
                Err(e) => last = Some(e),
            }
        }
        Err(Error::Render(match last {
            Some(e) => format!("no EGL device opened an OpenGL context ({e}); {EGL_HINT}"),
            None => format!("EGL lists no device (no GPU and no Mesa software device); {EGL_HINT}"),
        }))
    }

    fn on_device(device: &Device) -> glutin::error::Result<Self> {
        // SAFETY: `device` comes from `query_devices` and outlives the call.
        let display = unsafe { Display::with_device(device, None)? };
        let template = ConfigTemplateBuilder::new()
            .with_surface_type(ConfigSurfaceTypes::PBUFFER)
            .with_alpha_size(0)
            .with_depth_size(24)
            .with_stencil_size(8)
            .build();
        // SAFETY: the display is initialised and the template asks for standard attributes.
        let config = unsafe { display.find_configs(template)? }
            .next()
            .ok_or(glutin::error::ErrorKind::NotSupported("no pbuffer config"))?;
        let attrs = ContextAttributesBuilder::new()
            .with_profile(GlProfile::Compatibility)
            .with_context_api(ContextApi::OpenGl(Some(Version::new(2, 0))))
            .build(None);
        // SAFETY: display and config are valid.
        let context = unsafe { display.create_context(&config, &attrs)? };
        // MuJoCo draws into its own framebuffer object: the surface only has to exist.
        let one = NonZero::new(1).expect("1 is not zero");
        let surface_attrs = SurfaceAttributesBuilder::<PbufferSurface>::new().build(one, one);
        // SAFETY: display and config are valid and the size is positive.
        let surface = unsafe { display.create_pbuffer_surface(&config, &surface_attrs)? };
        Ok(Self {
            context: Some(context),
            surface,
            device: describe(device),
        })
    }

    /// The EGL device the context runs on (a DRM node, or `"Mesa software"`).
    pub fn device(&self) -> &str {
        &self.device
    }

    /// Makes the context current on the calling thread until the guard drops.
    ///
    /// # Errors
    /// [`Error::Render`] when EGL refuses (the context is lost).
    pub fn make_current(&mut self) -> Result<CurrentGuard<'_>> {
        let context = self
            .context
            .take()
            .ok_or_else(|| Error::Render("the OpenGL context was lost".into()))?;
        let current = context
            .make_current(&self.surface)
            .map_err(|e| Error::Render(format!("eglMakeCurrent failed: {e}")))?;
        Ok(CurrentGuard {
            owner: self,
            context: Some(current),
        })
    }
}
