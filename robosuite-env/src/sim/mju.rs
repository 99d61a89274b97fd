//! Safe wrappers of the MuJoCo utility functions (`mju_*`) the controllers use: pure math
//! on fixed-size arrays, so the sizes MuJoCo reads and writes are checked by the types.

use mujoco_rs::mujoco_c::{mju_mat2Quat, mju_quat2Vel};

/// The unit quaternion (`w, x, y, z`) of a row-major rotation matrix (`mju_mat2Quat`).
pub fn mat2quat(mat: &[f64; 9]) -> [f64; 4] {
    let mut quat = [0.0; 4];
    // SAFETY: `mju_mat2Quat` reads 9 values from `mat` and writes 4 to `quat`, the sizes
    // of the arrays.
    unsafe { mju_mat2Quat(&mut quat, mat) };
    quat
}

/// The angular velocity that rotates by `quat` in time `dt` (`mju_quat2Vel`).
pub fn quat2vel(quat: &[f64; 4], dt: f64) -> [f64; 3] {
    let mut vel = [0.0; 3];
    // SAFETY: `mju_quat2Vel` reads 4 values from `quat` and writes 3 to `vel`, the sizes
    // of the arrays.
    unsafe { mju_quat2Vel(&mut vel, quat, dt) };
    vel
}

/// The conjugate of a quaternion (`w, x, y, z`; `mju_negQuat`).
pub fn neg_quat(quat: &[f64; 4]) -> [f64; 4] {
    let mut out = [0.0; 4];
    // SAFETY: `mju_negQuat` reads 4 values from `quat` and writes 4 to `out`.
    unsafe { mujoco_rs::mujoco_c::mju_negQuat(&mut out, quat) };
    out
}

/// The quaternion product `a·b` (`w, x, y, z`; `mju_mulQuat`).
pub fn mul_quat(a: &[f64; 4], b: &[f64; 4]) -> [f64; 4] {
    let mut out = [0.0; 4];
    // SAFETY: `mju_mulQuat` reads 4 values from each input and writes 4 to `out`.
    unsafe { mujoco_rs::mujoco_c::mju_mulQuat(&mut out, a, b) };
    out
}
