//! robosuite's `LinearInterpolator` (`utils/traj_utils.py`): between two env steps a
//! controller's goal ramps from the previous goal to the new one over
//! `ceil(ramp_ratio · controller_freq / policy_freq)` substeps.

use crate::math::{euler2mat, mat2quat, quat2mat_f32};
use nalgebra::Matrix3;

/// What the interpolated values are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InterpolationKind {
    /// Plain values (positions, joint positions, velocities, torques).
    Values,
    /// xyz Euler angles, interpolated on the sphere (robosuite's `ori="euler"`).
    Euler,
}

/// A linear interpolator as robosuite runs it, allocation-free after construction.
///
/// Each call of [`LinearInterpolator::next`] returns `start + (goal − start) / (T − k)` for
/// the `k`-th substep (`k` stops at `T − 1`, so the goal is reached at the `T`-th call and
/// held), where `start` is the *previous goal*, not the state reached (robosuite's
/// semantics). Euler angles are interpolated by quaternion slerp with fraction
/// `(k + 1) / T`.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearInterpolator {
    kind: InterpolationKind,
    total_steps: f64,
    step: usize,
    start: Vec<f64>,
    goal: Vec<f64>,
}

impl LinearInterpolator {
    /// An interpolator of `dim` values at rest at zero (robosuite's freshly made one).
    /// `timestep` is the physics timestep, `policy_freq` the control frequency.
    pub fn new(
        dim: usize,
        kind: InterpolationKind,
        timestep: f64,
        policy_freq: f64,
        ramp_ratio: f64,
    ) -> Self {
        let controller_freq = 1.0 / timestep;
        Self {
            kind,
            total_steps: (ramp_ratio * controller_freq / policy_freq).ceil(),
            step: 0,
            start: vec![0.0; dim],
            goal: vec![0.0; dim],
        }
    }

    /// The number of substeps a ramp takes.
    pub fn total_steps(&self) -> f64 {
        self.total_steps
    }

    /// Back to a fresh interpolator (robosuite makes its controllers anew at every reset).
    pub fn clear(&mut self) {
        self.start.iter_mut().for_each(|v| *v = 0.0);
        self.goal.iter_mut().for_each(|v| *v = 0.0);
        self.step = 0;
    }

    /// Starts a new ramp from the current goal to `goal`.
    pub fn set_goal(&mut self, goal: &[f64]) {
        self.start.copy_from_slice(&self.goal);
        self.goal.copy_from_slice(goal);
        self.step = 0;
    }

    /// Writes the next interpolated goal into `out` and advances.
    pub fn next(&mut self, out: &mut [f64]) {
        match self.kind {
            InterpolationKind::Values => {
                let remaining = self.total_steps - self.step as f64;
                for ((o, s), g) in out.iter_mut().zip(&self.start).zip(&self.goal) {
                    *o = s + (g - s) / remaining;
                }
            }
            InterpolationKind::Euler => {
                let q0 = mat2quat(&euler2mat([self.start[0], self.start[1], self.start[2]]));
                let q1 = mat2quat(&euler2mat([self.goal[0], self.goal[1], self.goal[2]]));
                let q = quat_slerp(q0, q1, (self.step as f64 + 1.0) / self.total_steps);
                out.copy_from_slice(&mat2euler_f32(&quat2mat_f32(q)));
            }
        }
        if (self.step as f64) < self.total_steps - 1.0 {
            self.step += 1;
        }
    }

    /// `[step, start.., goal..]`.
    pub fn state(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(1 + 2 * self.start.len());
        out.push(self.step as f64);
        out.extend(&self.start);
        out.extend(&self.goal);
        out
    }

    /// The length of [`LinearInterpolator::state`].
    pub fn state_len(&self) -> usize {
        1 + 2 * self.start.len()
    }

    /// Restores a state from [`LinearInterpolator::state`] (of the right length, checked by
    /// the caller).
    pub fn set_state(&mut self, state: &[f64]) {
        let n = self.start.len();
        self.step = state[0].max(0.0) as usize;
        self.start.copy_from_slice(&state[1..1 + n]);
        self.goal.copy_from_slice(&state[1 + n..1 + 2 * n]);
    }
}

/// robosuite's `quat_slerp` (`xyzw`, shortest path).
pub fn quat_slerp(quat0: [f64; 4], quat1: [f64; 4], fraction: f64) -> [f64; 4] {
    const EPS: f64 = f64::EPSILON * 4.0;
    let unit = |q: [f64; 4]| {
        let n = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
        q.map(|v| v / n)
    };
    let q0 = unit(quat0);
    let mut q1 = unit(quat1);
    if fraction == 0.0 {
        return q0;
    }
    if fraction == 1.0 {
        return q1;
    }
    let mut d = q0[0] * q1[0] + q0[1] * q1[1] + q0[2] * q1[2] + q0[3] * q1[3];
    if (d.abs() - 1.0).abs() < EPS {
        return q0;
    }
    if d < 0.0 {
        d = -d;
        q1 = q1.map(|v| -v);
    }
    let angle = d.clamp(-1.0, 1.0).acos();
    if angle.abs() < EPS {
        return q0;
    }
    let isin = 1.0 / angle.sin();
    let a = ((1.0 - fraction) * angle).sin() * isin;
    let b = (fraction * angle).sin() * isin;
    std::array::from_fn(|i| q0[i] * a + q1[i] * b)
}

/// robosuite's `mat2euler` (static xyz axes), which reads the matrix as float32.
pub fn mat2euler_f32(m: &Matrix3<f64>) -> [f64; 3] {
    const EPS: f64 = f64::EPSILON * 4.0;
    let f = |r: usize, c: usize| m[(r, c)] as f32;
    // sxyz: i = 0, j = 1, k = 2, no parity, no repetition, static frame.
    let cy = f64::from(f(0, 0) * f(0, 0) + f(1, 0) * f(1, 0)).sqrt();
    let g = |r: usize, c: usize| f64::from(f(r, c));
    if cy > EPS {
        [
            g(2, 1).atan2(g(2, 2)),
            (-g(2, 0)).atan2(cy),
            g(1, 0).atan2(g(0, 0)),
        ]
    } else {
        [(-g(1, 2)).atan2(g(1, 1)), (-g(2, 0)).atan2(cy), 0.0]
    }
}
