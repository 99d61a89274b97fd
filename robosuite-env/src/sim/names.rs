//! Name → id lookups that fail with a typed error naming what is missing.

use gym_core::{Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use mujoco_rs::wrappers::mj_model::MjtObjBase as mjtObj;

fn lookup(model: &MjModel, kind: mjtObj, what: &str, name: &str) -> Result<usize> {
    if name.contains('\0') {
        return Err(Error::model(format!(
            "{what} name `{name:?}` contains a NUL byte"
        )));
    }
    model.name_to_id(kind, name).ok_or_else(|| {
        Error::model(format!(
            "the model has no {what} named `{name}` (robosuite's naming is expected)"
        ))
    })
}

/// The id of the body `name`.
///
/// # Errors
/// [`Error::Model`] when there is no such body.
pub fn body_id(model: &MjModel, name: &str) -> Result<usize> {
    lookup(model, mjtObj::mjOBJ_BODY, "body", name)
}

/// The id of the joint `name`.
///
/// # Errors
/// [`Error::Model`] when there is no such joint.
pub fn joint_id(model: &MjModel, name: &str) -> Result<usize> {
    lookup(model, mjtObj::mjOBJ_JOINT, "joint", name)
}

/// The id of the geom `name`.
///
/// # Errors
/// [`Error::Model`] when there is no such geom.
pub fn geom_id(model: &MjModel, name: &str) -> Result<usize> {
    lookup(model, mjtObj::mjOBJ_GEOM, "geom", name)
}

/// The id of the site `name`.
///
/// # Errors
/// [`Error::Model`] when there is no such site.
pub fn site_id(model: &MjModel, name: &str) -> Result<usize> {
    lookup(model, mjtObj::mjOBJ_SITE, "site", name)
}

/// The id of the actuator `name`.
///
/// # Errors
/// [`Error::Model`] when there is no such actuator.
pub fn actuator_id(model: &MjModel, name: &str) -> Result<usize> {
    lookup(model, mjtObj::mjOBJ_ACTUATOR, "actuator", name)
}

/// The id of the (first) actuator whose transmission is the joint `joint`.
///
/// Binding actuators by joint rather than by name accepts robosuite's exported models as
/// well as ours.
///
/// # Errors
/// [`Error::Model`] when no actuator drives the joint.
pub fn actuator_for_joint(model: &MjModel, joint: usize, joint_name: &str) -> Result<usize> {
    let m = model.ffi();
    let nu = m.nu as usize;
    // SAFETY: actuator_trntype / actuator_trnid have nu and 2*nu entries in a compiled model.
    let (trntype, trnid) = unsafe {
        (
            std::slice::from_raw_parts(m.actuator_trntype, nu),
            std::slice::from_raw_parts(m.actuator_trnid, 2 * nu),
        )
    };
    (0..nu)
        .find(|&a| {
            trntype[a] == mujoco_rs::mujoco_c::mjtTrn::mjTRN_JOINT as i32
                && trnid[2 * a] as usize == joint
        })
        .ok_or_else(|| Error::model(format!("no actuator drives the joint `{joint_name}`")))
}

/// The address in `sensordata` of the sensor `name`, which must have `dim` values (so that
/// reading `dim` values from the address reads this sensor and no other).
///
/// # Errors
/// [`Error::Model`] when there is no such sensor or it has another dimension.
pub fn sensor_adr(model: &MjModel, name: &str, dim: usize) -> Result<usize> {
    let id = lookup(model, mjtObj::mjOBJ_SENSOR, "sensor", name)?;
    let got = model.sensor_dim()[id];
    if usize::try_from(got).ok() != Some(dim) {
        return Err(Error::model(format!(
            "the sensor `{name}` has {got} value(s); {dim} expected"
        )));
    }
    Ok(model.sensor_adr()[id] as usize)
}
