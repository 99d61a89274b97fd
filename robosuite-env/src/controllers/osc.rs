//! robosuite's `OSC_POSE` operational-space controller (`controllers/parts/arm/osc.py`) for
//! an arm of any number of joints.

use super::config::OscConfig;
use super::{ArmBinding, ArmController};
use crate::math::{PsdPinv, axisangle2quat, mat_from_row_major, orientation_error, quat2mat_f32};
use crate::sim::Sim;
use gym_core::{Error, Result};
use mujoco_rs::mujoco_c::{mj_fullM, mj_jacSite};
use nalgebra::{Cholesky, DMatrix, DVector, Matrix3, Matrix6, Vector3, Vector6};

/// The `OSC_POSE` controller of one arm.
///
/// * `set_goal` (first substep of each env step): the input is clipped to
///   `[input_min, input_max]`, scaled to a delta (±0.05 m, ±0.5 rad by default) in the base
///   frame (the `{robot}{arm}_center` site) and applied to the *achieved* pose:
///   `goal_p = R_bᵀ(x − p_b) + δp`, `goal_R = Rot(δr)·R_bᵀR` (with robosuite's float32
///   `quat2mat`).
/// * `compute` (every substep, from the state after `mj_step1`):
///   `τ = Jᵀ[Λp·F; Λo·T] + h + Nᵀ·M·(k_n(q₀ − q) − 2√k_n·q̇)` with
///   `F = kp∘e_p − kd∘(v − v_b)`, `T = kp∘e_o − kd∘(ω − ω_b)` (`v_b`, `ω_b`: the velocity of
///   the base-frame site, which moves on robots whose `{arm}_center` site sits on a moving
///   link, such as the IIWA's), `Λ = pinv(J M⁻¹ Jᵀ)` (and its position and orientation
///   blocks), `N = I − M⁻¹JᵀΛJ`.
///
/// Every matrix lives in a buffer allocated at construction: the substep loop does not
/// allocate.
#[derive(Debug, Clone)]
pub struct OscPose {
    config: OscConfig,
    kd: [f64; 6],
    scale: [f64; 6],
    out_offset: [f64; 6],
    in_offset: f64,
    bind: ArmBinding,
    jacp: Vec<f64>,
    jacr: Vec<f64>,
    base_jacp: Vec<f64>,
    base_jacr: Vec<f64>,
    full_m: Vec<f64>,
    /// The arm's mass matrix as robosuite's controller cached it at creation.
    reset_mass: DMatrix<f64>,
    /// Whether the next torque computation is robosuite's first after a reset.
    first_after_reset: bool,
    work: Work,
    goal_pos: Vector3<f64>,
    goal_ori: Matrix3<f64>,
    q0: DVector<f64>,
}

/// The controller's n-sized buffers.
#[derive(Debug, Clone)]
struct Work {
    jac: DMatrix<f64>,
    mass: DMatrix<f64>,
    m_inv: DMatrix<f64>,
    chol: Option<DMatrix<f64>>,
    j_minv: DMatrix<f64>,
    jbar: DMatrix<f64>,
    null: DMatrix<f64>,
    q: DVector<f64>,
    qd: DVector<f64>,
    posture: DVector<f64>,
    posture_m: DVector<f64>,
    tau: DVector<f64>,
}

impl Work {
    fn new(n: usize) -> Self {
        Self {
            jac: DMatrix::zeros(6, n),
            mass: DMatrix::zeros(n, n),
            m_inv: DMatrix::zeros(n, n),
            chol: Some(DMatrix::zeros(n, n)),
            j_minv: DMatrix::zeros(6, n),
            jbar: DMatrix::zeros(n, 6),
            null: DMatrix::zeros(n, n),
            q: DVector::zeros(n),
            qd: DVector::zeros(n),
            posture: DVector::zeros(n),
            posture_m: DVector::zeros(n),
            tau: DVector::zeros(n),
        }
    }
}

impl OscPose {
    /// A controller for the arm described by `bind`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the configuration is invalid
    /// ([`OscConfig::validate`]).
    pub fn new(config: OscConfig, bind: ArmBinding) -> Result<Self> {
        config.validate()?;
        let n = bind.dofs.len();
        let nv = bind.nv;
        let kd = config.kd();
        let scale = std::array::from_fn(|i| {
            (config.output_max[i] - config.output_min[i]).abs()
                / (config.input_max - config.input_min).abs()
        });
        let out_offset =
            std::array::from_fn(|i| (config.output_max[i] + config.output_min[i]) / 2.0);
        let in_offset = (config.input_max + config.input_min) / 2.0;
        Ok(Self {
            config,
            kd,
            scale,
            out_offset,
            in_offset,
            jacp: vec![0.0; 3 * nv],
            jacr: vec![0.0; 3 * nv],
            base_jacp: vec![0.0; 3 * nv],
            base_jacr: vec![0.0; 3 * nv],
            full_m: vec![0.0; nv * nv],
            reset_mass: DMatrix::zeros(n, n),
            first_after_reset: false,
            work: Work::new(n),
            goal_pos: Vector3::zeros(),
            goal_ori: Matrix3::identity(),
            q0: DVector::zeros(n),
            bind,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &OscConfig {
        &self.config
    }

    /// The model binding.
    pub fn binding(&self) -> &ArmBinding {
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
    pub fn initial_joints(&self) -> &[f64] {
        self.q0.as_slice()
    }

    fn site_pose(sim: &Sim, site: usize) -> (Vector3<f64>, Matrix3<f64>) {
        let d = sim.data();
        (
            Vector3::from(d.site_xpos()[site]),
            mat_from_row_major(&d.site_xmat()[site]),
        )
    }

    /// Scales a raw input to the delta robosuite applies (`scale_action`).
    pub fn scale_action(&self, action: &[f64]) -> [f64; 6] {
        std::array::from_fn(|i| {
            let a = action[i].clamp(self.config.input_min, self.config.input_max);
            (a - self.in_offset) * self.scale[i] + self.out_offset[i]
        })
    }

    /// `M⁻¹` of the arm's mass matrix into `work.m_inv` (robosuite: `np.linalg.inv`):
    /// Cholesky in place when positive definite, LU otherwise.
    fn invert_mass(work: &mut Work) {
        let n = work.mass.nrows();
        let mut buf = work.chol.take().unwrap_or_else(|| DMatrix::zeros(n, n));
        buf.copy_from(&work.mass);
        let chol = Cholesky::new_unchecked(buf);
        let l = chol.l_dirty();
        let definite = (0..n).all(|i| l[(i, i)].is_finite() && l[(i, i)] > 0.0);
        work.m_inv.fill_with_identity();
        if definite {
            chol.solve_mut(&mut work.m_inv);
            work.chol = Some(chol.unpack_dirty());
        } else {
            // Not positive definite (a degenerate model): the general inverse, or the
            // pseudo-inverse when singular. Rare, so it may allocate.
            work.chol = Some(chol.unpack_dirty());
            match work.mass.clone().try_inverse() {
                Some(inv) => work.m_inv.copy_from(&inv),
                None => {
                    let pinv = work
                        .mass
                        .clone()
                        .pseudo_inverse(1e-15)
                        .unwrap_or_else(|_| DMatrix::zeros(n, n));
                    work.m_inv.copy_from(&pinv);
                }
            }
        }
    }
}

impl ArmController for OscPose {
    fn name(&self) -> &'static str {
        "OSC_POSE"
    }

    fn action_dim(&self) -> usize {
        6
    }

    fn action_limits(&self) -> (Vec<f64>, Vec<f64>) {
        (
            vec![self.config.input_min; 6],
            vec![self.config.input_max; 6],
        )
    }

    fn capture_reset(&mut self, sim: &Sim) {
        let nv = self.bind.nv;
        let (m_ptr, d_ptr) = sim.raw();
        // SAFETY: m/d are live; full_m holds nv·nv values.
        unsafe { mj_fullM(m_ptr, d_ptr, self.full_m.as_mut_ptr()) };
        let dofs = &self.bind.dofs;
        for (r, &dr) in dofs.iter().enumerate() {
            for (c, &dc) in dofs.iter().enumerate() {
                self.reset_mass[(r, c)] = self.full_m[dr * nv + dc];
            }
        }
        self.first_after_reset = true;
    }

    fn reset(&mut self, sim: &Sim) {
        let qpos = sim.data().qpos();
        for (i, &a) in self.bind.qpos.iter().enumerate() {
            self.q0[i] = qpos[a];
        }
        let (p_b, r_b) = Self::site_pose(sim, self.bind.base_site);
        let (x, r) = Self::site_pose(sim, self.bind.site);
        self.goal_pos = r_b.transpose() * (x - p_b);
        self.goal_ori = r_b.transpose() * r;
    }

    fn set_goal(&mut self, sim: &Sim, action: &[f64]) {
        let delta = self.scale_action(action);
        let (p_b, r_b) = Self::site_pose(sim, self.bind.base_site);
        let (x, r) = Self::site_pose(sim, self.bind.site);
        let dp = Vector3::new(delta[0], delta[1], delta[2]);
        let dr = Vector3::new(delta[3], delta[4], delta[5]);
        self.goal_pos = r_b.transpose() * (x - p_b) + dp;
        let rot = quat2mat_f32(axisangle2quat(&dr));
        self.goal_ori = rot * (r_b.transpose() * r);
    }

    fn compute(&mut self, sim: &Sim, torques: &mut [f64]) {
        let nv = self.bind.nv;
        let n = self.bind.dofs.len();
        let (m_ptr, d_ptr) = sim.raw();
        let site = i32::try_from(self.bind.site).unwrap_or(i32::MAX);
        let base_site = i32::try_from(self.bind.base_site).unwrap_or(i32::MAX);
        // SAFETY: m/d are live; the Jacobian buffers hold 3·nv and full_m nv·nv values.
        unsafe {
            mj_jacSite(
                m_ptr,
                d_ptr,
                self.jacp.as_mut_ptr(),
                self.jacr.as_mut_ptr(),
                site,
            );
            mj_jacSite(
                m_ptr,
                d_ptr,
                self.base_jacp.as_mut_ptr(),
                self.base_jacr.as_mut_ptr(),
                base_site,
            );
            mj_fullM(m_ptr, d_ptr, self.full_m.as_mut_ptr());
        }
        let d = sim.data();
        let (qpos, qvel, bias) = (d.qpos(), d.qvel(), d.qfrc_bias());
        let dofs = &self.bind.dofs;
        let w = &mut self.work;

        // Task Jacobian on the arm dofs; end-effector velocity over all dofs (robosuite's
        // get_site_xvelp / xvelr = Jacobian × full qvel).
        for c in 0..n {
            for r in 0..3 {
                w.jac[(r, c)] = self.jacp[r * nv + dofs[c]];
                w.jac[(r + 3, c)] = self.jacr[r * nv + dofs[c]];
            }
            for r in 0..n {
                w.mass[(r, c)] = if self.first_after_reset {
                    self.reset_mass[(r, c)]
                } else {
                    self.full_m[dofs[r] * nv + dofs[c]]
                };
            }
            w.q[c] = qpos[self.bind.qpos[c]];
            w.qd[c] = qvel[dofs[c]];
        }
        // v − v_b and ω − ω_b: the grip site's velocity relative to the base-frame site's.
        self.first_after_reset = false;
        let mut v = Vector3::zeros();
        let mut om = Vector3::zeros();
        for r in 0..3 {
            let (mut sv, mut sw, mut bv, mut bw) = (0.0, 0.0, 0.0, 0.0);
            for (k, qd) in qvel.iter().enumerate() {
                sv += self.jacp[r * nv + k] * qd;
                sw += self.jacr[r * nv + k] * qd;
                bv += self.base_jacp[r * nv + k] * qd;
                bw += self.base_jacr[r * nv + k] * qd;
            }
            v[r] = sv - bv;
            om[r] = sw - bw;
        }

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
        let torque = Vector3::from_fn(|i, _| e_o[i] * kp[3 + i] + (-om[i]) * kd[3 + i]);

        // Operational-space matrices (control_utils.opspace_matrices).
        Self::invert_mass(w);
        // Small products by hand: nalgebra's dynamic matrix products allocate packing
        // buffers.
        for r in 0..6 {
            for c in 0..n {
                let mut s = 0.0;
                for k in 0..n {
                    s += w.jac[(r, k)] * w.m_inv[(k, c)];
                }
                w.j_minv[(r, c)] = s;
            }
        }
        let lambda_inv = Matrix6::from_fn(|r, c| {
            let mut s = 0.0;
            for k in 0..n {
                s += w.j_minv[(r, k)] * w.jac[(c, k)];
            }
            s
        });
        let lambda = lambda_inv.pinv_psd();
        let wrench: Vector6<f64> = if self.config.uncouple_pos_ori {
            let lambda_p = lambda_inv.fixed_view::<3, 3>(0, 0).into_owned().pinv_psd();
            let lambda_o = lambda_inv.fixed_view::<3, 3>(3, 3).into_owned().pinv_psd();
            let fp = lambda_p * force;
            let fo = lambda_o * torque;
            Vector6::new(fp[0], fp[1], fp[2], fo[0], fo[1], fo[2])
        } else {
            lambda
                * Vector6::new(
                    force[0], force[1], force[2], torque[0], torque[1], torque[2],
                )
        };
        // τ = Jᵀ wrench + h
        for c in 0..n {
            let mut s = 0.0;
            for r in 0..6 {
                s += w.jac[(r, c)] * wrench[r];
            }
            w.tau[c] = s + bias[dofs[c]];
        }

        // Nullspace posture term (control_utils.nullspace_torques): N = I − M⁻¹Jᵀ Λ J.
        for rr in 0..n {
            for c in 0..6 {
                let mut s = 0.0;
                for k in 0..6 {
                    s += w.j_minv[(k, rr)] * lambda[(k, c)];
                }
                w.jbar[(rr, c)] = s;
            }
        }
        for i in 0..n {
            for j in 0..n {
                let mut s = 0.0;
                for k in 0..6 {
                    s += w.jbar[(i, k)] * w.jac[(k, j)];
                }
                w.null[(i, j)] = f64::from(u8::from(i == j)) - s;
            }
        }
        let kn = self.config.nullspace_kp;
        let kvn = kn.sqrt() * 2.0;
        for i in 0..n {
            w.posture[i] = (self.q0[i] - w.q[i]) * kn - w.qd[i] * kvn;
        }
        w.mass.mul_to(&w.posture, &mut w.posture_m);
        w.tau.gemv_tr(1.0, &w.null, &w.posture_m, 1.0);
        torques.copy_from_slice(w.tau.as_slice());
    }

    /// `[goal_pos (3), goal_ori (9, column-major), q₀ (n), first-after-reset flag (1),
    /// creation-time mass matrix (n·n)]`.
    fn state(&self) -> Vec<f64> {
        let n = self.q0.len();
        let mut out = Vec::with_capacity(13 + n + n * n);
        out.extend(self.goal_pos.iter());
        out.extend(self.goal_ori.iter());
        out.extend(self.q0.iter());
        out.push(f64::from(u8::from(self.first_after_reset)));
        out.extend(self.reset_mass.iter());
        out
    }

    fn set_state(&mut self, state: &[f64]) -> Result<()> {
        let n = self.q0.len();
        let len = 13 + n + n * n;
        if state.len() != len || state.iter().any(|v| !v.is_finite()) {
            return Err(Error::invalid_argument(
                "controller state",
                format!(
                    "expected {len} finite values for OSC_POSE, got {}",
                    state.len()
                ),
            ));
        }
        self.goal_pos = Vector3::from_column_slice(&state[..3]);
        self.goal_ori = Matrix3::from_column_slice(&state[3..12]);
        self.q0.copy_from_slice(&state[12..12 + n]);
        self.first_after_reset = state[12 + n] != 0.0;
        self.reset_mass.copy_from_slice(&state[13 + n..]);
        Ok(())
    }

    fn clone_box(&self) -> Box<dyn ArmController> {
        Box::new(self.clone())
    }
}
