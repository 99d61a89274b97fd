//! The MuJoCo version this crate is built for, checked once before the first model load.

use gym_core::{Error, Result};
use std::sync::OnceLock;

/// The MuJoCo version the bindings (mujoco-rs 7.0.0) were generated for: 3.17.0.
pub const MUJOCO_VERSION: u32 = mujoco_rs::mujoco_c::mjVERSION_HEADER;

/// Checks that the loaded MuJoCo library is the one the bindings expect (3.17.0).
///
/// mujoco-rs panics on a mismatch inside its loaders; calling this first turns the mismatch
/// into a typed error. The result is computed once per process.
///
/// # Errors
/// [`Error::Model`] naming both versions when they differ.
pub fn check_mujoco_version() -> Result<()> {
    static CHECK: OnceLock<std::result::Result<(), String>> = OnceLock::new();
    CHECK
        .get_or_init(|| {
            // SAFETY: mj_version is a pure query with no preconditions.
            let linked = unsafe { mujoco_rs::mujoco_c::mj_version() };
            if u32::try_from(linked).ok() == Some(MUJOCO_VERSION) {
                Ok(())
            } else {
                Err(format!(
                    "the loaded MuJoCo library has version {linked}, but robosuite-env is built for {MUJOCO_VERSION} \
                     (MuJoCo 3.17.0); put libmujoco.so.3.17.0 on the library path"
                ))
            }
        })
        .clone()
        .map_err(Error::model)
}
