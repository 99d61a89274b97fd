//! The scene as MJCF with a compiled model's current values (robosuite's `get_xml`).

use gym_core::{Error, Result};
use mujoco_rs::wrappers::mj_editing::MjSpec;
use mujoco_rs::wrappers::mj_model::MjModel;

/// `source` (the MJCF `model` was compiled from) with every real-valued model array as
/// `model` has it now (MuJoCo's `mj_copyBack`: sizes re-drawn at reset, masses, positions,
/// run-time edits), saved by MuJoCo's XML writer.
///
/// # Errors
/// [`Error::Model`] when MuJoCo cannot parse, compile or save the scene, or when `source`
/// does not compile to a model of `model`'s sizes.
pub fn scene_xml(source: &str, model: &MjModel) -> Result<String> {
    let mut spec = MjSpec::from_xml_string(source)
        .map_err(|e| Error::model(format!("cannot parse the scene: {e}")))?;
    let compiled = spec
        .compile()
        .map_err(|e| Error::model(format!("cannot compile the scene: {e}")))?;
    let (a, b) = (compiled.ffi(), model.ffi());
    let same_sizes = (
        a.nq, a.nv, a.nu, a.nbody, a.njnt, a.ngeom, a.nsite, a.nmesh, a.ntex,
    ) == (
        b.nq, b.nv, b.nu, b.nbody, b.njnt, b.ngeom, b.nsite, b.nmesh, b.ntex,
    );
    if !same_sizes {
        return Err(Error::model(
            "the scene's text does not compile to a model of this model's sizes",
        ));
    }
    // SAFETY: the spec was just compiled, and its model has `model`'s sizes (checked above:
    // `model` was compiled from the same text, and run-time edits keep every size), which is
    // what `mj_copyBack` requires; both pointers are valid for the call.
    let copied = unsafe { mujoco_rs::mujoco_c::mj_copyBack(spec.ffi_mut(), model.ffi()) };
    if copied == 0 {
        return Err(Error::model(
            "MuJoCo could not copy the model back into the scene",
        ));
    }
    let mut size = 4 * source.len() + (1 << 16);
    loop {
        match spec.save_xml_string(size) {
            Ok(text) => return Ok(text),
            Err(mujoco_rs::error::MjEditError::XmlBufferTooSmall { required_size })
                if required_size > size =>
            {
                size = required_size + 1;
            }
            Err(e) => return Err(Error::model(format!("cannot save the scene: {e}"))),
        }
    }
}
