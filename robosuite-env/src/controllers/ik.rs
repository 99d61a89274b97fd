//! robosuite's `IK_POSE` controller (`controllers/parts/arm/ik.py`) as robosuite documents
//! it: each env step, one damped least-squares differential-IK step toward the commanded
//! end-effector change gives a joint target that a joint-position controller tracks.
//!
//! robosuite 1.5.2 computes that target as an *absolute* joint position and then hands it
//! to its joint-position controller in delta mode, so the arm moves to `q + clip(q_des)`:
//! a zero action moves the end effector by about 35 cm in 20 steps. Here the target is
//! used as the absolute joint position it is, which is what robosuite itself does when its
//! config adds `"input_type": "absolute"` (the recorded rollouts run it so). robosuite also
//! accepts only the Panda, Sawyer and Baxter, with nullspace gains sized for 7 joints;
//! here any arm works, with gains 10 on all but the last three joints and 5 on those (for
//! 7 joints: robosuite's `[10, 10, 10, 10, 5, 5, 5]`).

use super::config::{IkConfig, join};
use super::joint_position::JointTracker;
use super::{ArmBinding, ArmController, Timing, check_gains, check_state};
use crate::math::{PsdPinv, axisangle2quat, clip_rotation, clip_translation, quat2mat_f32};
use crate::sim::{Sim, mju};
use gym_core::{Error, Result};
use nalgebra::{DMatrix, DVector, Matrix6, Vector3, Vector6};

/// robosuite's gains on the position and orientation error (`Kpos`, `Kori`).
const K_TWIST: f64 = 0.95;
/// robosuite's damping of the least-squares solve (`damping_pseudo_inv`), squared.
const DAMPING_SQ: f64 = 0.05 * 0.05;
/// robosuite's largest joint speed of the IK step (`velocity_limits[1]`), rad/s.
const MAX_JOINT_SPEED: f64 = 1.0;

/// Differential IK toward an end-effector change, tracked in joint space.
///
/// * `set_goal`: the position change (world frame) is scaled down to at most
///   `ik_pos_limit` metres, the rotation vector's angle clipped to `ik_ori_limit` radians
///   (robosuite's `clip_translation` / `clip_rotation`); the twist
///   `[0.95·δp/dt, 0.95·ω(δR)/dt]` (`dt = ik_integration_dt`) gives
///   `q̇ = Jᵀ(JJᵀ + 0.05²I)⁻¹ twist + (I − J⁺J)·Kn∘(q₀ − q)`, scaled so that no joint exceeds
///   1 rad/s; the joint target is `q + q̇·dt`.
/// * `compute`: `τ = M·(kp∘(q* − q) − kd∘q̇) + h` (kp 100, critically damped).
#[derive(Debug, Clone)]
pub struct InverseKinematics {
    tracker: JointTracker,
    pos_limit: f64,
    ori_limit: f64,
    dt: f64,
    kn: DVector<f64>,
    initial_joint: DVector<f64>,
    dq: DVector<f64>,
    null_in: DVector<f64>,
    proj: DMatrix<f64>,
}

impl InverseKinematics {
    /// The controller for `config` on the arm of `bind`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the key (under `path`) for a limit or time step
    /// that is not positive and finite, or gains out of range.
    pub fn new(config: &IkConfig, bind: ArmBinding, timing: Timing, path: &str) -> Result<Self> {
        let n = bind.dofs.len();
        let key = |k: &str| join(path, k);
        for (k, v) in [
            ("ik_pos_limit", config.ik_pos_limit),
            ("ik_ori_limit", config.ik_ori_limit),
            ("ik_integration_dt", config.ik_integration_dt),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid_argument(
                    key(k),
                    format!("must be finite and > 0, got {v}"),
                ));
            }
        }
        let kp = config.kp.resolve(n, &key("kp"))?;
        let damping = config.damping_ratio.resolve(n, &key("damping_ratio"))?;
        check_gains(&damping, &key("damping_ratio"))?;
        let kd = (0..n)
            .map(|i| 2.0 * kp[i].max(0.0).sqrt() * damping[i])
            .collect();
        let wrist = n.saturating_sub(3);
        Ok(Self {
            tracker: JointTracker::new(
                true,
                kp,
                kd,
                true,
                config.interpolation,
                config.ramp_ratio,
                bind,
                timing,
                path,
            )?,
            pos_limit: config.ik_pos_limit,
            ori_limit: config.ik_ori_limit,
            dt: config.ik_integration_dt,
            kn: DVector::from_fn(n, |i, _| if i < wrist { 10.0 } else { 5.0 }),
            initial_joint: DVector::zeros(n),
            dq: DVector::zeros(n),
            null_in: DVector::zeros(n),
            proj: DMatrix::zeros(n, n),
        })
    }

    /// The joint target of the last step.
    pub fn goal(&self) -> &[f64] {
        self.tracker.goal.as_slice()
    }

    /// The nullspace gains per joint.
    pub fn nullspace_gains(&self) -> &[f64] {
        self.kn.as_slice()
    }

    fn state_len(&self) -> usize {
        self.tracker.arm.joints() + self.tracker.state_len()
    }
}

impl ArmController for InverseKinematics {
    fn name(&self) -> &'static str {
        "IK_POSE"
    }

    fn action_dim(&self) -> usize {
        6
    }

    fn action_limits(&self) -> (Vec<f64>, Vec<f64>) {
        let (p, o) = (self.pos_limit, self.ori_limit);
        (vec![-p, -p, -p, -o, -o, -o], vec![p, p, p, o, o, o])
    }

    fn reset(&mut self, sim: &Sim) {
        self.tracker.reset(sim);
        self.initial_joint.copy_from(&self.tracker.arm.q);
    }

    fn set_goal(&mut self, sim: &Sim, action: &[f64]) {
        // robosuite forces a fresh read here (`update(force=True)`).
        self.tracker.arm.update(sim, true);
        let mut dpos = Vector3::new(action[0], action[1], action[2]);
        if dpos.iter().any(|v| *v != 0.0) {
            dpos = clip_translation(&dpos, self.pos_limit);
        }
        let rot = clip_rotation(
            axisangle2quat(&Vector3::new(action[3], action[4], action[5])),
            self.ori_limit,
        );
        let drot = quat2mat_f32(rot);
        // The twist: mju_mat2Quat of the (row-major) rotation, then mju_quat2Vel.
        let mat: [f64; 9] = std::array::from_fn(|i| drot[(i / 3, i % 3)]);
        let vel = mju::quat2vel(&mju::mat2quat(&mat), 1.0);
        let twist = Vector6::new(
            K_TWIST * dpos[0] / self.dt,
            K_TWIST * dpos[1] / self.dt,
            K_TWIST * dpos[2] / self.dt,
            vel[0] * (K_TWIST / self.dt),
            vel[1] * (K_TWIST / self.dt),
            vel[2] * (K_TWIST / self.dt),
        );
        let arm = &self.tracker.arm;
        let (jac, q) = (&arm.jac, &arm.q);
        let n = arm.joints();
        let jjt = Matrix6::from_fn(|r, c| {
            let mut s = 0.0;
            for k in 0..n {
                s += jac[(r, k)] * jac[(c, k)];
            }
            s
        });
        let damped = jjt + Matrix6::identity() * DAMPING_SQ;
        let y = damped
            .cholesky()
            .map_or_else(|| damped.pinv_svd() * twist, |c| c.solve(&twist));
        // J⁺J = Jᵀ(JJᵀ)⁺J.
        let jjt_pinv = jjt.pinv_psd();
        for i in 0..n {
            let mut s = 0.0;
            for r in 0..6 {
                s += jac[(r, i)] * y[r];
            }
            self.dq[i] = s;
            self.null_in[i] = self.kn[i] * (self.initial_joint[i] - q[i]);
        }
        for i in 0..n {
            for j in 0..n {
                let mut s = 0.0;
                for r in 0..6 {
                    let mut t = 0.0;
                    for c in 0..6 {
                        t += jjt_pinv[(r, c)] * jac[(c, j)];
                    }
                    s += jac[(r, i)] * t;
                }
                self.proj[(i, j)] = f64::from(u8::from(i == j)) - s;
            }
        }
        self.dq.gemv(1.0, &self.proj, &self.null_in, 1.0);
        let peak = self.dq.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if peak > MAX_JOINT_SPEED {
            self.dq *= MAX_JOINT_SPEED / peak;
        }
        for i in 0..n {
            self.tracker.goal[i] = q[i] + self.dq[i] * self.dt;
        }
        self.tracker.set_target();
    }

    fn compute(&mut self, sim: &Sim, torques: &mut [f64]) {
        self.tracker.compute(sim, torques);
    }

    /// `[q₀ (n), joint tracker state]`.
    fn state(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.state_len());
        out.extend(self.initial_joint.iter());
        self.tracker.state(&mut out);
        out
    }

    fn set_state(&mut self, state: &[f64]) -> Result<()> {
        check_state(state, self.state_len(), self.name())?;
        let n = self.tracker.arm.joints();
        self.initial_joint.copy_from_slice(&state[..n]);
        self.tracker.set_state(&state[n..]);
        Ok(())
    }

    fn clone_box(&self) -> Box<dyn ArmController> {
        Box::new(self.clone())
    }
}
