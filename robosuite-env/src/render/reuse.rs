//! Render contexts of dropped renderers, kept for the next renderer of an identical model on
//! the same EGL device. Making one costs most of a second of CPU on a software renderer
//! (MuJoCo uploads every texture, with its mipmaps, and every mesh, and Mesa compiles the
//! shaders of a new context); envs made one after another in a process (tests, evaluation
//! loops, dataset tools) reuse one instead.
//!
//! A context is kept only while its GPU data is what MuJoCo made from the model (no
//! texture was uploaded again), and only [`KEEP`] of them (the most recently dropped): each
//! holds its textures and meshes.

use super::GlContext;
use mujoco_rs::prelude::{MjModel, MjrContext};
use std::hash::{BuildHasher, Hasher};
use std::sync::Mutex;

/// How many dropped contexts are kept.
pub(super) const KEEP: usize = 2;

/// What a render context was made from: the process, the EGL device asked for and a
/// fingerprint of everything `mjr_makeContext` reads from the model (sizes, visual settings,
/// statistics and the whole model buffer: textures, meshes, materials, plane geoms).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Key {
    // A forked child never takes its parent's contexts.
    process: u32,
    device: Option<usize>,
    env_device: Option<String>,
    fingerprint: u64,
}

impl Key {
    /// The key of a context made for `model` on `device`.
    pub(super) fn of(model: &MjModel, device: Option<usize>) -> Self {
        let m = model.ffi();
        let mut h = foldhash::quality::FixedState::with_seed(0x6d6a_725f_6374_7831).build_hasher();
        for n in [
            m.nq,
            m.nv,
            m.nu,
            m.nbody,
            m.ngeom,
            m.nsite,
            m.ncam,
            m.nlight,
            m.nmesh,
            m.nmeshvert,
            m.nmeshnormal,
            m.nmeshtexcoord,
            m.nmeshface,
            m.nmeshgraph,
            m.nhfield,
            m.nhfielddata,
            m.ntex,
            m.ntexdata,
            m.nmat,
            m.nskin,
            m.nskinvert,
            m.nskinface,
            m.nflex,
        ] {
            h.write_i64(n);
        }
        h.write_i64(m.nbuffer);
        // SAFETY: `mjVisual` (floats and ints) and `mjStatistic` (doubles) have no padding;
        // the buffer holds `nbuffer` bytes.
        unsafe {
            h.write(std::slice::from_raw_parts(
                std::ptr::from_ref(&m.vis).cast::<u8>(),
                std::mem::size_of_val(&m.vis),
            ));
            h.write(std::slice::from_raw_parts(
                std::ptr::from_ref(&m.stat).cast::<u8>(),
                std::mem::size_of_val(&m.stat),
            ));
            if !m.buffer.is_null() && m.nbuffer > 0 {
                h.write(std::slice::from_raw_parts(
                    m.buffer.cast::<u8>(),
                    m.nbuffer as usize,
                ));
            }
        }
        Self {
            process: std::process::id(),
            device,
            env_device: std::env::var("MUJOCO_EGL_DEVICE_ID").ok(),
            fingerprint: h.finish(),
        }
    }
}

/// A kept context, current on no thread.
struct Kept {
    key: Key,
    gl: GlContext,
    context: MjrContext,
}

// SAFETY: as `OffscreenRenderer`: the MjrContext is only touched while `gl` is current on
// the calling thread, and `gl` is current on no thread while kept.
unsafe impl Send for Kept {}

static KEPT: Mutex<Vec<Kept>> = Mutex::new(Vec::new());

fn kept() -> std::sync::MutexGuard<'static, Vec<Kept>> {
    KEPT.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// A kept context made with `key`, removed from the kept ones.
pub(super) fn take(key: &Key) -> Option<(GlContext, MjrContext)> {
    let mut kept = kept();
    let i = kept.iter().rposition(|k| k.key == *key)?;
    let k = kept.remove(i);
    Some((k.gl, k.context))
}

/// Keeps a context made with `key`; the oldest kept beyond [`KEEP`] is freed.
pub(super) fn put(key: Key, gl: GlContext, context: MjrContext) {
    let evicted = {
        let mut kept = kept();
        kept.push(Kept { key, gl, context });
        if kept.len() > KEEP {
            Some(kept.remove(0))
        } else {
            None
        }
    };
    if let Some(k) = evicted {
        free(k.gl, k.context);
    }
}

/// Frees a context's GL objects with its GL context current (leaked when it cannot be made
/// current: freeing them without it is undefined).
pub(super) fn free(mut gl: GlContext, context: MjrContext) {
    match gl.make_current() {
        Ok(_current) => drop(context),
        Err(_) => std::mem::forget(context),
    }
}
