//! robosuite's `OSC_POSE` operational-space controller (`controllers/parts/arm/osc.py`).

use super::config::OscConfig;
use super::math::{
    PsdPinv, axisangle2quat, inv_spd, mat_from_row_major, orientation_error, quat2mat_f32,
};
use crate::sim::Sim;
use mujoco_rs::mujoco_c::{mj_fullM, mj_jacSite};
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

type Vec6 = SVector<f64, 6>;
type Vec7 = SVector<f64, 7>;
type Mat7 = SMatrix<f64, 7, 7>;
type Jac = SMatrix<f64, 6, 7>;

/// Where the controller reads and writes in the model.
#[derive(Debug, Clone, PartialEq)]
pub struct OscBinding {
    /// The controlled site (the gripper's grip site).
    pub site: usize,
    /// The site whose frame is the base frame of the input (`robotN_right_center`).
    pub base_site: usize,
    /// The `qpos` addresses of the 7 arm joints.
    pub qpos: [usize; 7],
    /// The dof (`qvel`) addresses of the 7 arm joints.
    pub dofs: [usize; 7],
    /// The ctrlrange of each arm joint's motor (torques are clipped to it).
    pub ctrlrange: [[f64; 2]; 7],
}

/// The internal state of an [`OscPose`]: its goal and nullspace target.
#[derive(Debug, Clone, PartialEq)]
pub struct OscState {
    /// Goal position in the base frame.
    pub goal_pos: [f64; 3],
    /// Goal orientation in the base frame (column-major).
    pub goal_ori: [f64; 9],
    /// Nullspace target posture.
    pub q0: [f64; 7],
}

/// The `OSC_POSE` controller of one 7-dof arm.
///
/// * `set_goal` (first substep of each env step): the input is clipped to
///   `[input_min, input_max]`, scaled to a delta (±0.05 m, ±0.5 rad by default) in the base
///   frame and applied to the *achieved* pose: `goal_p = R_bᵀ(x − p_b) + δp`,
///   `goal_R = Rot(δr)·R_bᵀR` (with robosuite's float32 `quat2mat`).
/// * `compute_torques` (every substep, from the state after `mj_step1`):
///   `τ = Jᵀ[Λp·F; Λo·T] + h + Nᵀ·M·(k_n(q₀ − q) − 2√k_n·q̇)` with
///   `F = kp∘e_p − kd∘v`, `T = kp∘e_o − kd∘ω`, `Λ = pinv(J M⁻¹ Jᵀ)` (and its position and
///   orientation blocks), `N = I − M⁻¹JᵀΛJ`, clipped to the motors' ctrlrange.
///
/// Jacobians and the mass matrix go into buffers allocated once; the substep loop does not
/// allocate.
#[derive(Debug, Clone)]
pub struct OscPose {
    config: OscConfig,
    kd: [f64; 6],
    scale: [f64; 6],
    out_offset: [f64; 6],
    in_offset: f64,
    bind: OscBinding,
    nv: usize,
    jacp: Vec<f64>,
    jacr: Vec<f64>,
    full_m: Vec<f64>,
    goal_pos: Vector3<f64>,
    goal_ori: Matrix3<f64>,
    q0: Vec7,
    torques: Vec7,
}

impl OscPose {
    /// A controller for the arm described by `bind` in a model with `nv` dofs.
    ///
    /// The configuration must have been validated ([`OscConfig::validate`]).
    pub fn new(config: OscConfig, bind: OscBinding, nv: usize) -> Self {
        let kd = config.kd();
        let scale = std::array::from_fn(|i| {
            (config.output_max[i] - config.output_min[i]).abs()
                / (config.input_max - config.input_min).abs()
        });
        let out_offset =
            std::array::from_fn(|i| (config.output_max[i] + config.output_min[i]) / 2.0);
        let in_offset = (config.input_max + config.input_min) / 2.0;
        Self {
            config,
            kd,
            scale,
            out_offset,
            in_offset,
            bind,
            nv,
            jacp: vec![0.0; 3 * nv],
            jacr: vec![0.0; 3 * nv],
            full_m: vec![0.0; nv * nv],
            goal_pos: Vector3::zeros(),
            goal_ori: Matrix3::identity(),
            q0: Vec7::zeros(),
            torques: Vec7::zeros(),
        }
    }

    /// The configuration.
    pub fn config(&self) -> &OscConfig {
        &self.config
    }

    /// The model binding.
    pub fn binding(&self) -> &OscBinding {
        &self.bind
    }

    /// The goal position in the base frame.
    pub fn goal_pos(&self) -> Vector3<f64> {
        self.goal_pos
    }

    /// The goal orientation in the base frame.
    pub fn goal_ori(&self) -> Matrix3<f64> {
        self.goal_ori
    }

    /// The nullspace target `q₀` (the arm posture at the last reset).
    pub fn initial_joints(&self) -> [f64; 7] {
        self.q0.into()
    }

    /// The torques of the last [`OscPose::compute_torques`] (after clipping).
    pub fn torques(&self) -> [f64; 7] {
        self.torques.into()
    }

    fn site_pose(sim: &Sim, site: usize) -> (Vector3<f64>, Matrix3<f64>) {
        let d = sim.data();
        (
            Vector3::from(d.site_xpos()[site]),
            mat_from_row_major(&d.site_xmat()[site]),
        )
    }

    /// The goal and nullspace target, for snapshots.
    pub fn state(&self) -> OscState {
        let mut goal_ori = [0.0; 9];
        goal_ori.copy_from_slice(self.goal_ori.as_slice());
        OscState {
            goal_pos: self.goal_pos.into(),
            goal_ori,
            q0: self.q0.into(),
        }
    }

    /// Restores a state from [`OscPose::state`].
    pub fn set_state(&mut self, state: &OscState) {
        self.goal_pos = Vector3::from(state.goal_pos);
        self.goal_ori = Matrix3::from_column_slice(&state.goal_ori);
        self.q0 = Vec7::from(state.q0);
    }

    /// Re-bases the controller on the current state (after `mj_forward`): `q₀` = current
    /// arm posture, goal = current pose. robosuite re-creates its controllers at each reset.
    pub fn reset(&mut self, sim: &Sim) {
        let qpos = sim.data().qpos();
        self.q0 = Vec7::from_fn(|i, _| qpos[self.bind.qpos[i]]);
        let (p_b, r_b) = Self::site_pose(sim, self.bind.base_site);
        let (x, r) = Self::site_pose(sim, self.bind.site);
        self.goal_pos = r_b.transpose() * (x - p_b);
        self.goal_ori = r_b.transpose() * r;
        self.torques = Vec7::zeros();
    }

    /// Scales a raw input to the delta robosuite applies (`scale_action`).
    pub fn scale_action(&self, action: &[f64; 6]) -> [f64; 6] {
        std::array::from_fn(|i| {
            let a = action[i].clamp(self.config.input_min, self.config.input_max);
            (a - self.in_offset) * self.scale[i] + self.out_offset[i]
        })
    }

    /// Sets the goal from a 6-dim input `[dx, dy, dz, ax, ay, az]` (delta in the base frame,
    /// applied to the achieved pose). Call once per env step, after `mj_step1`.
    pub fn set_goal(&mut self, sim: &Sim, action: &[f64; 6]) {
        let delta = self.scale_action(action);
        let (p_b, r_b) = Self::site_pose(sim, self.bind.base_site);
        let (x, r) = Self::site_pose(sim, self.bind.site);
        let dp = Vector3::new(delta[0], delta[1], delta[2]);
        let dr = Vector3::new(delta[3], delta[4], delta[5]);
        self.goal_pos = r_b.transpose() * (x - p_b) + dp;
        let rot = quat2mat_f32(axisangle2quat(&dr));
        self.goal_ori = rot * (r_b.transpose() * r);
    }

    /// Computes the arm torques for the current state (after `mj_step1`), clipped to the
    /// motors' ctrlrange. Does not allocate.
    pub fn compute_torques(&mut self, sim: &Sim) -> [f64; 7] {
        let nv = self.nv;
        let (m_ptr, d_ptr) = sim.raw();
        let site = i32::try_from(self.bind.site).unwrap_or(i32::MAX);
        // SAFETY: m/d are live; jacp/jacr hold 3·nv and full_m nv·nv values.
        unsafe {
            mj_jacSite(
                m_ptr,
                d_ptr,
                self.jacp.as_mut_ptr(),
                self.jacr.as_mut_ptr(),
                site,
            );
            mj_fullM(m_ptr, d_ptr, self.full_m.as_mut_ptr());
        }
        let d = sim.data();
        let (qpos, qvel, bias) = (d.qpos(), d.qvel(), d.qfrc_bias());
        let dofs = &self.bind.dofs;

        // Task Jacobian on the arm dofs, end-effector velocity over all dofs (robosuite's
        // get_site_xvelp / xvelr = Jacobian × full qvel).
        let jac = Jac::from_fn(|r, c| {
            if r < 3 {
                self.jacp[r * nv + dofs[c]]
            } else {
                self.jacr[(r - 3) * nv + dofs[c]]
            }
        });
        let mut v = Vector3::zeros();
        let mut w = Vector3::zeros();
        for r in 0..3 {
            let (mut sv, mut sw) = (0.0, 0.0);
            for (k, qd) in qvel.iter().enumerate() {
                sv += self.jacp[r * nv + k] * qd;
                sw += self.jacr[r * nv + k] * qd;
            }
            v[r] = sv;
            w[r] = sw;
        }
        let mass = Mat7::from_fn(|r, c| self.full_m[dofs[r] * nv + dofs[c]]);
        let q = Vec7::from_fn(|i, _| qpos[self.bind.qpos[i]]);
        let qd = Vec7::from_fn(|i, _| qvel[dofs[i]]);
        let h = Vec7::from_fn(|i, _| bias[dofs[i]]);

        // Pose error in the world frame.
        let (p_b, r_b) = Self::site_pose(sim, self.bind.base_site);
        let (x, r) = Self::site_pose(sim, self.bind.site);
        let x_d = p_b + r_b * self.goal_pos;
        let r_d = r_b * self.goal_ori;
        let e_p = x_d - x;
        let e_o = orientation_error(&r_d, &r);
        let kp = &self.config.kp;
        let kd = &self.kd;
        let force = Vector3::from_fn(|i, _| e_p[i] * kp[i] + (-v[i]) * kd[i]);
        let torque = Vector3::from_fn(|i, _| e_o[i] * kp[3 + i] + (-w[i]) * kd[3 + i]);

        // Operational-space matrices (control_utils.opspace_matrices).
        let m_inv = inv_spd(&mass);
        let jp = jac.fixed_rows::<3>(0).into_owned();
        let jr = jac.fixed_rows::<3>(3).into_owned();
        let lambda = (jac * m_inv * jac.transpose()).pinv_psd();
        let wrench: Vec6 = if self.config.uncouple_pos_ori {
            let lambda_p = (jp * m_inv * jp.transpose()).pinv_psd();
            let lambda_o = (jr * m_inv * jr.transpose()).pinv_psd();
            let fp = lambda_p * force;
            let fo = lambda_o * torque;
            Vec6::new(fp[0], fp[1], fp[2], fo[0], fo[1], fo[2])
        } else {
            lambda
                * Vec6::new(
                    force[0], force[1], force[2], torque[0], torque[1], torque[2],
                )
        };
        let mut tau = jac.transpose() * wrench + h;

        // Nullspace posture term (control_utils.nullspace_torques).
        let jbar = m_inv * jac.transpose() * lambda;
        let nullspace = Mat7::identity() - jbar * jac;
        let kn = self.config.nullspace_kp;
        let kvn = kn.sqrt() * 2.0;
        let pose_torques = mass * ((self.q0 - q) * kn - qd * kvn);
        tau += nullspace.transpose() * pose_torques;

        for i in 0..7 {
            let [lo, hi] = self.bind.ctrlrange[i];
            tau[i] = tau[i].clamp(lo, hi);
        }
        self.torques = tau;
        tau.into()
    }
}
