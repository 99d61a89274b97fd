//! The crate's linear algebra and rotations, written to follow robosuite's
//! `transform_utils` / `control_utils` (including their float32 steps): quaternions
//! (MuJoCo's `wxyz` and robosuite's `xyzw`), rotation matrices, Euler angles and the
//! pseudo-inverses of the operational-space controller.

use nalgebra::{Matrix3, SMatrix, Vector3};

/// `numpy.linalg.pinv`'s default relative cutoff.
const PINV_RCOND: f64 = 1e-15;

/// Pseudo-inverses of symmetric positive semi-definite matrices (the operational-space
/// inertias), implemented for the 3×3 and 6×6 sizes the controller needs.
pub trait PsdPinv: Sized {
    /// The pseudo-inverse. For a well-conditioned matrix (Cholesky succeeds and its pivots
    /// span less than 10 orders of magnitude) this is the inverse, which is what
    /// `numpy.linalg.pinv` returns there; otherwise [`PsdPinv::pinv_svd`]. No heap allocation.
    fn pinv_psd(&self) -> Self;
    /// The SVD pseudo-inverse with NumPy's cutoff `1e-15·σ_max`.
    fn pinv_svd(&self) -> Self;
}

macro_rules! impl_psd_pinv {
    ($($n:literal),*) => {$(
        impl PsdPinv for SMatrix<f64, $n, $n> {
            fn pinv_psd(&self) -> Self {
                if let Some(chol) = self.cholesky() {
                    let l = chol.l_dirty();
                    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
                    for i in 0..$n {
                        let d = l[(i, i)] * l[(i, i)];
                        lo = lo.min(d);
                        hi = hi.max(d);
                    }
                    if lo.is_finite() && lo > 1e-10 * hi {
                        return chol.inverse();
                    }
                }
                self.pinv_svd()
            }

            fn pinv_svd(&self) -> Self {
                let svd = self.svd(true, true);
                let (Some(u), Some(v_t)) = (svd.u, svd.v_t) else {
                    return Self::zeros();
                };
                let cutoff = PINV_RCOND * svd.singular_values.max();
                let mut out = Self::zeros();
                for k in 0..$n {
                    let s = svd.singular_values[k];
                    if s > cutoff {
                        out += (v_t.row(k).transpose() / s) * u.column(k).transpose();
                    }
                }
                out
            }
        }
    )*};
}
impl_psd_pinv!(3, 6);

/// A row-major MuJoCo 3×3 matrix (`xmat`) as a matrix.
pub fn mat_from_row_major(m: &[f64; 9]) -> Matrix3<f64> {
    Matrix3::from_row_slice(m)
}

/// robosuite's `orientation_error(desired, current)`:
/// `0.5·Σ_i current[:, i] × desired[:, i]`.
pub fn orientation_error(desired: &Matrix3<f64>, current: &Matrix3<f64>) -> Vector3<f64> {
    let rc1: Vector3<f64> = current.column(0).into();
    let rc2: Vector3<f64> = current.column(1).into();
    let rc3: Vector3<f64> = current.column(2).into();
    let rd1: Vector3<f64> = desired.column(0).into();
    let rd2: Vector3<f64> = desired.column(1).into();
    let rd3: Vector3<f64> = desired.column(2).into();
    0.5 * (rc1.cross(&rd1) + rc2.cross(&rd2) + rc3.cross(&rd3))
}

/// robosuite's `axisangle2quat`: a rotation vector to an `xyzw` quaternion (identity for
/// an exactly zero vector).
pub fn axisangle2quat(v: &Vector3<f64>) -> [f64; 4] {
    // NumPy's norm sums the squares in order; the result feeds a float32 rounding, so even
    // one ulp here can change robosuite's goal orientation.
    let angle = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if angle == 0.0 {
        return [0.0, 0.0, 0.0, 1.0];
    }
    let axis = [v[0] / angle, v[1] / angle, v[2] / angle];
    let s = (angle / 2.0).sin();
    [axis[0] * s, axis[1] * s, axis[2] * s, (angle / 2.0).cos()]
}

/// robosuite's `quat2mat` (numba-compiled) for an `xyzw` quaternion, to the bit: the
/// quaternion is rounded to float32; its squared norm is BLAS `sdot`'s (float32 products
/// summed in float64, rounded to float32); each component is scaled by `sqrt(2 / n)` in
/// float64 and stored back as float32; the products are formed in float32, the off-diagonal
/// sums in float32 and the diagonal `1 − a − b` in float64.
pub fn quat2mat_f32(q_xyzw: [f64; 4]) -> Matrix3<f64> {
    let q = [
        q_xyzw[3] as f32,
        q_xyzw[0] as f32,
        q_xyzw[1] as f32,
        q_xyzw[2] as f32,
    ];
    let n = q.iter().fold(0.0f64, |acc, v| acc + f64::from(v * v)) as f32;
    if f64::from(n) < 4.0 * f64::EPSILON {
        return Matrix3::identity();
    }
    let s = (2.0 / f64::from(n)).sqrt();
    let q = q.map(|v| (f64::from(v) * s) as f32);
    let o = |i: usize, j: usize| q[i] * q[j];
    let d = |i: usize, j: usize| 1.0 - f64::from(o(i, i)) - f64::from(o(j, j));
    let f = |x: f32| f64::from(x);
    Matrix3::new(
        d(2, 3),
        f(o(1, 2) - o(3, 0)),
        f(o(1, 3) + o(2, 0)),
        f(o(1, 2) + o(3, 0)),
        d(1, 3),
        f(o(2, 3) - o(1, 0)),
        f(o(1, 3) - o(2, 0)),
        f(o(2, 3) + o(1, 0)),
        d(1, 2),
    )
}

/// robosuite's `T.pose_inv(T.pose2mat((pos, quat)))` for an `xyzw` quaternion: the inverse
/// of the pose, as a row-major 4x4 float64 matrix. As robosuite: `pose2mat` rounds the
/// rotation ([`quat2mat_f32`]) and the position to float32; `pose_inv` transposes the
/// rotation and computes `-Rᵀ p` in float64.
pub fn pose_inv_of(pos: [f64; 3], q_xyzw: [f64; 4]) -> [f64; 16] {
    let r = quat2mat_f32(q_xyzw);
    let p = pos.map(|v| f64::from(v as f32));
    let mut out = [0.0; 16];
    for i in 0..3 {
        // Row i of Rᵀ: column i of the float32 rotation.
        let row = [0, 1, 2].map(|k| f64::from(r[(k, i)] as f32));
        out[4 * i..4 * i + 3].copy_from_slice(&row);
        out[4 * i + 3] = -(row[0] * p[0] + row[1] * p[1] + row[2] * p[2]);
    }
    out[15] = 1.0;
    out
}

/// A rotation matrix to an `xyzw` unit quaternion with `w >= 0` (robosuite's `mat2quat`
/// convention), computed in float64.
pub fn mat2quat(m: &Matrix3<f64>) -> [f64; 4] {
    let (m00, m11, m22) = (m[(0, 0)], m[(1, 1)], m[(2, 2)]);
    let trace = m00 + m11 + m22;
    let (w, x, y, z);
    if trace > 0.0 {
        let s = (trace + 1.0).sqrt() * 2.0;
        w = 0.25 * s;
        x = (m[(2, 1)] - m[(1, 2)]) / s;
        y = (m[(0, 2)] - m[(2, 0)]) / s;
        z = (m[(1, 0)] - m[(0, 1)]) / s;
    } else if m00 > m11 && m00 > m22 {
        let s = (1.0 + m00 - m11 - m22).sqrt() * 2.0;
        w = (m[(2, 1)] - m[(1, 2)]) / s;
        x = 0.25 * s;
        y = (m[(0, 1)] + m[(1, 0)]) / s;
        z = (m[(0, 2)] + m[(2, 0)]) / s;
    } else if m11 > m22 {
        let s = (1.0 + m11 - m00 - m22).sqrt() * 2.0;
        w = (m[(0, 2)] - m[(2, 0)]) / s;
        x = (m[(0, 1)] + m[(1, 0)]) / s;
        y = 0.25 * s;
        z = (m[(1, 2)] + m[(2, 1)]) / s;
    } else {
        let s = (1.0 + m22 - m00 - m11).sqrt() * 2.0;
        w = (m[(1, 0)] - m[(0, 1)]) / s;
        x = (m[(0, 2)] + m[(2, 0)]) / s;
        y = (m[(1, 2)] + m[(2, 1)]) / s;
        z = 0.25 * s;
    }
    let n = (w * w + x * x + y * y + z * z).sqrt();
    let sign = if w < 0.0 { -1.0 } else { 1.0 };
    [sign * x / n, sign * y / n, sign * z / n, sign * w / n]
}

/// SciPy's `Rotation.from_rotvec(v).as_matrix()` (robosuite's absolute `OSC_POSE` goal):
/// the quaternion with SciPy's small-angle series below 1e-3 rad, then its matrix.
pub fn rotvec_to_matrix(v: &Vector3<f64>) -> Matrix3<f64> {
    let angle = v.norm();
    let scale = if angle <= 1e-3 {
        let a2 = angle * angle;
        0.5 - a2 / 48.0 + a2 * a2 / 3840.0
    } else {
        (angle / 2.0).sin() / angle
    };
    let (x, y, z, w) = (
        v[0] * scale,
        v[1] * scale,
        v[2] * scale,
        (angle / 2.0).cos(),
    );
    let (x2, y2, z2, w2) = (x * x, y * y, z * z, w * w);
    let (xy, zw, xz, yw, yz, xw) = (x * y, z * w, x * z, y * w, y * z, x * w);
    Matrix3::new(
        x2 - y2 - z2 + w2,
        2.0 * (xy - zw),
        2.0 * (xz + yw),
        2.0 * (xy + zw),
        -x2 + y2 - z2 + w2,
        2.0 * (yz - xw),
        2.0 * (xz - yw),
        2.0 * (yz + xw),
        -x2 - y2 + z2 + w2,
    )
}

/// robosuite's `clip_translation`: scales `dpos` down to norm `limit` when longer.
pub fn clip_translation(dpos: &Vector3<f64>, limit: f64) -> Vector3<f64> {
    let norm = dpos.norm();
    if norm > limit {
        dpos * (limit / norm)
    } else {
        *dpos
    }
}

/// robosuite's `clip_rotation`: limits the angle of an `xyzw` rotation to `limit` radians.
pub fn clip_rotation(quat: [f64; 4], limit: f64) -> [f64; 4] {
    let n = (quat[0] * quat[0] + quat[1] * quat[1] + quat[2] * quat[2] + quat[3] * quat[3]).sqrt();
    let q = quat.map(|v| v / n);
    let den = (1.0 - q[3] * q[3]).max(0.0).sqrt();
    if den == 0.0 {
        return q;
    }
    let (x, y, z) = (q[0] / den, q[1] / den, q[2] / den);
    let a = 2.0 * q[3].clamp(-1.0, 1.0).acos();
    if a.abs() > limit {
        let half = limit * a.signum() / 2.0;
        let (sa, ca) = half.sin_cos();
        [x * sa, y * sa, z * sa, ca]
    } else {
        q
    }
}

/// `wxyz` → `xyzw` (MuJoCo's order to robosuite's observation order).
pub fn xyzw(q: [f64; 4]) -> [f64; 4] {
    [q[1], q[2], q[3], q[0]]
}

/// Quaternion (`wxyz`) product.
pub fn quat_mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// robosuite's `quat_multiply(q1, q0)` on `xyzw` quaternions: the product `q1·q0` formed
/// in float64 in robosuite's term order and returned rounded to float32 (robosuite returns
/// a float32 array).
pub fn quat_multiply_f32(q1: [f64; 4], q0: [f64; 4]) -> [f64; 4] {
    let [x0, y0, z0, w0] = q0;
    let [x1, y1, z1, w1] = q1;
    [
        x1 * w0 + y1 * z0 - z1 * y0 + w1 * x0,
        -x1 * z0 + y1 * w0 + z1 * x0 + w1 * y0,
        x1 * y0 - y1 * x0 + z1 * w0 + w1 * z0,
        -x1 * x0 - y1 * y0 - z1 * z0 + w1 * w0,
    ]
    .map(|v| f64::from(v as f32))
}

/// Conjugate of a quaternion (`wxyz`; the inverse of a unit quaternion).
pub fn conj(q: [f64; 4]) -> [f64; 4] {
    [q[0], -q[1], -q[2], -q[3]]
}

/// Rotates `v` by the unit quaternion `q` (`wxyz`).
pub fn quat_rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let p = quat_mul(quat_mul(q, [0.0, v[0], v[1], v[2]]), conj(q));
    [p[1], p[2], p[3]]
}

/// The rotation by `angle` about the x, y or z axis (`axis` 0, 1 or 2) as a `wxyz`
/// quaternion (robosuite's placement samplers).
pub fn axis_quat(axis: usize, angle: f64) -> [f64; 4] {
    let (s, c) = (angle / 2.0).sin_cos();
    let mut q = [c, 0.0, 0.0, 0.0];
    q[1 + axis] = s;
    q
}

/// robosuite's `euler2mat` (static x-y-z Euler angles, `(r, p, y)`).
pub fn euler2mat(euler: [f64; 3]) -> Matrix3<f64> {
    let (ai, aj, ak) = (-euler[2], -euler[1], -euler[0]);
    let (si, sj, sk) = (ai.sin(), aj.sin(), ak.sin());
    let (ci, cj, ck) = (ai.cos(), aj.cos(), ak.cos());
    let (cc, cs) = (ci * ck, ci * sk);
    let (sc, ss) = (si * ck, si * sk);
    Matrix3::new(
        cj * ci,
        cj * si,
        -sj,
        sj * cs - sc,
        sj * ss + cc,
        cj * sk,
        sj * cc + ss,
        sj * sc - cs,
        cj * ck,
    )
}

/// robosuite's `mat2quat(euler2mat(rot))` reordered to `wxyz`, as `set_base_ori` writes a
/// robot's base orientation: robosuite computes the quaternion in float32, so each
/// component is rounded to float32.
pub fn euler_xyz_to_quat_wxyz(rot: [f64; 3]) -> [f64; 4] {
    let q = mat2quat(&euler2mat(rot));
    [q[3], q[0], q[1], q[2]].map(|v| f64::from(v as f32))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix6, Rotation3, Unit};

    #[test]
    fn pinv_matches_inverse_and_handles_singular() {
        let a = Matrix6::<f64>::from_fn(|i, j| if i == j { 2.0 + i as f64 } else { 0.1 });
        let p = a.pinv_psd();
        assert!((p * a - Matrix6::identity()).abs().max() < 1e-12);
        // Rank 1: pinv(v vᵀ) = v vᵀ / |v|⁴.
        let v = nalgebra::Vector3::new(1.0, 2.0, 2.0);
        let s = v * v.transpose();
        let p = s.pinv_psd();
        assert!((p - s / 81.0).abs().max() < 1e-12);
    }

    #[test]
    fn quaternions_round_trip() {
        for (axis, angle) in [
            ((0.0, 0.0, 1.0), 0.3),
            ((1.0, 2.0, -0.5), 2.9),
            ((0.0, 1.0, 0.0), 3.1),
        ] {
            let r = Rotation3::from_axis_angle(
                &Unit::new_normalize(Vector3::new(axis.0, axis.1, axis.2)),
                angle,
            );
            let q = mat2quat(r.matrix());
            let back = quat2mat_f32(q);
            assert!((back - r.matrix()).abs().max() < 1e-6);
            assert!(q[3] >= 0.0);
            let aa = axisangle2quat(&(Vector3::new(axis.0, axis.1, axis.2).normalize() * angle));
            assert!((quat2mat_f32(aa) - r.matrix()).abs().max() < 1e-6);
        }
        assert_eq!(axisangle2quat(&Vector3::zeros()), [0.0, 0.0, 0.0, 1.0]);
    }

    #[test]
    fn euler_and_quaternion_helpers_agree() {
        // A yaw of +90° (robosuite's "opposed" robot0) turns x into y.
        let q = euler_xyz_to_quat_wxyz([0.0, 0.0, std::f64::consts::FRAC_PI_2]);
        let v = quat_rotate(q, [1.0, 0.0, 0.0]);
        assert!((v[0]).abs() < 1e-7 && (v[1] - 1.0).abs() < 1e-7, "{v:?}");
        let r = euler2mat([0.3, -0.2, 1.1]);
        assert!((r * r.transpose() - Matrix3::identity()).abs().max() < 1e-12);
        let a = axis_quat(2, 0.7);
        let b = axis_quat(2, -0.7);
        let p = quat_mul(a, b);
        assert!((p[0] - 1.0).abs() < 1e-15 && p[3].abs() < 1e-15);
        assert_eq!(xyzw([1.0, 2.0, 3.0, 4.0]), [2.0, 3.0, 4.0, 1.0]);
    }

    #[test]
    fn orientation_error_is_small_angle_axis() {
        let r = Rotation3::from_axis_angle(&Vector3::z_axis(), 0.01);
        let e = orientation_error(r.matrix(), &Matrix3::identity());
        assert!((e - Vector3::new(0.0, 0.0, 0.01)).norm() < 1e-5);
    }
}
