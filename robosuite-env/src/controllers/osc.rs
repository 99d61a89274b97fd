//! robosuite's operational-space controller (`controllers/parts/arm/osc.py`): `OSC_POSE`
//! and `OSC_POSITION` for an arm of any number of joints.

use super::config::{ImpedanceMode, InputRefFrame, InputType, Interpolation, OscConfig, join};
use super::interpolator::{InterpolationKind, LinearInterpolator};
use super::opspace::Algebra;
use super::state::{ArmState, Needs};
use super::{
    ActionScale, ArmBinding, ArmController, Timing, check_gains, check_ramp_ratio, check_state,
};
use crate::controllers::interpolator::mat2euler_f32;
use crate::math::{
    axisangle2quat, euler2mat, mat_from_row_major, orientation_error, quat2mat_f32,
    rotvec_to_matrix,
};
use crate::sim::Sim;
use gym_core::{Error, Result};
use nalgebra::{DVector, Matrix3, Vector3};
use std::f64::consts::PI;

/// The operational-space controller of one arm (`OSC_POSE`, or `OSC_POSITION` which holds
/// the orientation).
///
/// * `set_goal`: in the `variable` impedance mode the action starts with 6 damping ratios
///   and 6 stiffnesses (clipped to their limits), in `variable_kp` with 6 stiffnesses
///   (critically damped). A `delta` input is clipped to `[input_min, input_max]`, scaled
///   (±0.05 m, ±0.5 rad by default) and applied to the *achieved* pose in the input frame
///   (`base`: the `{robot}{arm}_center` site; `world`):
///   `goal_p = R_bᵀ(x − p_b) + δp`, `goal_R = Rot(δr)·R_bᵀR` (robosuite's float32 `quat2mat`).
///   An `absolute` input is the goal itself (position, then rotation vector), unclipped.
///   `position_limits` / `orientation_limits` clip the goal (robosuite raises
///   `NotImplementedError` for them).
/// * `compute`: `τ = Jᵀ[Λp·F; Λo·T] + h + Nᵀ·M·(10(q₀ − q) − 2√10·q̇)` with
///   `F = kp∘e_p − kd∘(v − v_b)`, `T = kp∘e_o − kd∘(ω − ω_b)` (`v_b`, `ω_b`: the base-frame
///   site's velocity), `Λ = pinv(J M⁻¹ Jᵀ)` (or its position and orientation blocks when
///   `uncouple_pos_ori`), `N = I − M⁻¹JᵀΛJ`, `q₀` the posture at the reset.
/// * `interpolation: "linear"` ramps the goal position and the orientation error as
///   robosuite's `LinearInterpolator`s do. robosuite feeds a base-frame goal to the position
///   interpolator and uses its output as a world position (with the default base frame a
///   zero action then moves the hand about 40 cm); here the interpolated goal is mapped
///   from the input frame to the world, so both frames behave as robosuite's world frame.
///
/// The matrices of an arm of up to 7 joints are fixed-size (on the stack, loops of known
/// length); a larger arm's are heap-sized, allocated once. Both give the same bits.
#[derive(Debug, Clone)]
pub struct Osc {
    use_ori: bool,
    impedance: ImpedanceMode,
    input_type: InputType,
    frame: InputRefFrame,
    uncouple: bool,
    scale: ActionScale,
    config_kp: [f64; 6],
    config_kd: [f64; 6],
    kp: [f64; 6],
    kd: [f64; 6],
    kp_limits: ([f64; 6], [f64; 6]),
    damping_limits: ([f64; 6], [f64; 6]),
    position_limits: Option<([f64; 3], [f64; 3])>,
    orientation_limits: Option<([f64; 3], [f64; 3])>,
    interp_pos: Option<LinearInterpolator>,
    interp_ori: Option<LinearInterpolator>,
    ori_ref: Matrix3<f64>,
    arm: ArmState,
    base_jacp: Vec<f64>,
    base_jacr: Vec<f64>,
    goal_pos: Vector3<f64>,
    goal_ori: Matrix3<f64>,
    initial_joint: DVector<f64>,
    algebra: Algebra,
    /// robosuite's `goal_update_mode == "desired"`: deltas apply to the last goal.
    update_desired: bool,
    /// No goal was set since the reset (robosuite's reset goal is the world pose).
    fresh: bool,
    /// The grip site's world pose at the reset (robosuite's `reset_goal`).
    reset_pos: Vector3<f64>,
    reset_ori: Matrix3<f64>,
    /// The base frame read at the reset, for robots whose origin robosuite updates only
    /// then ([`ArmBinding::origin_at_reset`]).
    origin_pos: Vector3<f64>,
    origin_ori: Matrix3<f64>,
}

fn six(v: Vec<f64>) -> [f64; 6] {
    std::array::from_fn(|i| v[i])
}

fn three(v: Vec<f64>) -> [f64; 3] {
    std::array::from_fn(|i| v[i])
}

impl Osc {
    /// The controller for `config` (`OSC_POSE` when `use_ori`, else `OSC_POSITION`) on the
    /// arm of `bind`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the key (under `path`) for a list of the wrong
    /// length or a value out of range.
    pub fn new(
        config: &OscConfig,
        use_ori: bool,
        bind: ArmBinding,
        timing: Timing,
        path: &str,
    ) -> Result<Self> {
        let dim = if use_ori { 6 } else { 3 };
        let key = |k: &str| join(path, k);
        let default_out = [0.05, 0.05, 0.05, 0.5, 0.5, 0.5];
        let output_max = match &config.output_max {
            Some(v) => v.resolve(dim, &key("output_max"))?,
            None => default_out[..dim].to_vec(),
        };
        let output_min = match &config.output_min {
            Some(v) => v.resolve(dim, &key("output_min"))?,
            None => default_out[..dim].iter().map(|v| -v).collect(),
        };
        let scale = ActionScale::new(
            (
                config.input_min.resolve(dim, &key("input_min"))?,
                config.input_max.resolve(dim, &key("input_max"))?,
            ),
            (output_min, output_max),
            path,
        )?;
        let kp = config.kp.resolve(6, &key("kp"))?;
        check_gains(&kp, &key("kp"))?;
        let damping = config.damping_ratio.resolve(6, &key("damping_ratio"))?;
        check_gains(&damping, &key("damping_ratio"))?;
        let (kp_lo, kp_hi) = config.kp_limits.resolve(6, &key("kp_limits"))?;
        check_gains(&kp_lo, &key("kp_limits"))?;
        let (dr_lo, dr_hi) = config
            .damping_ratio_limits
            .resolve(6, &key("damping_ratio_limits"))?;
        check_gains(&dr_lo, &key("damping_ratio_limits"))?;
        let position_limits = match &config.position_limits {
            Some(b) => {
                let (lo, hi) = b.resolve(3, &key("position_limits"))?;
                Some((three(lo), three(hi)))
            }
            None => None,
        };
        let orientation_limits = match &config.orientation_limits {
            Some(b) => {
                let at = key("orientation_limits");
                let lo = b.0.resolve(3, &at)?;
                let hi = b.1.resolve(3, &at)?;
                if let Some(v) = lo.iter().chain(&hi).find(|v| !v.is_finite()) {
                    return Err(Error::invalid_argument(
                        at,
                        format!("must be finite Euler angles, got {v}"),
                    ));
                }
                Some((three(lo), three(hi)))
            }
            None => None,
        };
        let interp = config.interpolation == Interpolation::Linear;
        if interp {
            check_ramp_ratio(config.ramp_ratio, &key("ramp_ratio"))?;
        }
        let make = |kind| {
            LinearInterpolator::new(
                3,
                kind,
                timing.timestep,
                timing.control_freq,
                config.ramp_ratio,
            )
        };
        let kp = six(kp);
        let kd: [f64; 6] = std::array::from_fn(|i| 2.0 * kp[i].sqrt() * damping[i]);
        let n = bind.dofs.len();
        let nv = bind.nv;
        Ok(Self {
            use_ori,
            impedance: config.impedance_mode,
            input_type: config.input_type,
            frame: config.input_ref_frame,
            uncouple: config.uncouple_pos_ori,
            scale,
            config_kp: kp,
            config_kd: kd,
            kp,
            kd,
            kp_limits: (six(kp_lo), six(kp_hi)),
            damping_limits: (six(dr_lo), six(dr_hi)),
            position_limits,
            orientation_limits,
            interp_pos: interp.then(|| make(InterpolationKind::Values)),
            interp_ori: (interp && use_ori).then(|| make(InterpolationKind::Euler)),
            ori_ref: Matrix3::identity(),
            arm: ArmState::new(
                bind,
                Needs {
                    site: true,
                    mass: true,
                },
            ),
            base_jacp: vec![0.0; 3 * nv],
            base_jacr: vec![0.0; 3 * nv],
            goal_pos: Vector3::zeros(),
            goal_ori: Matrix3::identity(),
            initial_joint: DVector::zeros(n),
            algebra: Algebra::new(n, true),
            update_desired: false,
            fresh: true,
            reset_pos: Vector3::zeros(),
            reset_ori: Matrix3::identity(),
            origin_pos: Vector3::zeros(),
            origin_ori: Matrix3::identity(),
        })
    }

    /// The same controller computing on heap-sized matrices, the algebra of arms of more
    /// than 7 joints, whatever the arm's size. Arms of up to 7 joints compute on fixed-size
    /// matrices, bit for bit the same torques at less cost; this is for comparing the two.
    #[must_use]
    pub fn with_dynamic_matrices(mut self) -> Self {
        self.algebra = Algebra::new(self.arm.joints(), false);
        self
    }

    /// Whether the controller computes on fixed-size matrices (an arm of up to 7 joints,
    /// unless [`Osc::with_dynamic_matrices`]).
    pub fn uses_fixed_size(&self) -> bool {
        self.algebra.is_fixed()
    }

    /// The model binding.
    pub fn binding(&self) -> &ArmBinding {
        self.arm.binding()
    }

    /// The goal position in the input frame.
    pub fn goal_pos(&self) -> Vector3<f64> {
        self.goal_pos
    }

    /// The goal orientation in the input frame.
    pub fn goal_ori(&self) -> Matrix3<f64> {
        self.goal_ori
    }

    /// The current stiffness per task axis.
    pub fn kp(&self) -> [f64; 6] {
        self.kp
    }

    /// The current damping gains per task axis.
    pub fn kd(&self) -> [f64; 6] {
        self.kd
    }

    /// The nullspace target `q₀` (the arm posture at the last reset).
    pub fn initial_joints(&self) -> &[f64] {
        self.initial_joint.as_slice()
    }

    /// The base-frame site's pose (robosuite's `origin_pos`, `origin_ori`), read live, or
    /// as read at the reset when [`ArmBinding::origin_at_reset`].
    fn origin(&self, sim: &Sim) -> (Vector3<f64>, Matrix3<f64>) {
        if self.arm.binding().origin_at_reset {
            return (self.origin_pos, self.origin_ori);
        }
        self.live_origin(sim)
    }

    fn live_origin(&self, sim: &Sim) -> (Vector3<f64>, Matrix3<f64>) {
        let d = sim.data();
        let s = self.arm.binding().base_site;
        (
            Vector3::from(d.site_xpos()[s]),
            mat_from_row_major(&d.site_xmat()[s]),
        )
    }

    /// The achieved position and orientation in the input frame.
    fn achieved(&self, sim: &Sim) -> (Vector3<f64>, Matrix3<f64>) {
        match self.frame {
            InputRefFrame::World => (self.arm.pos, self.arm.ori),
            InputRefFrame::Base => {
                let (p_b, r_b) = self.origin(sim);
                (
                    r_b.transpose() * (self.arm.pos - p_b),
                    r_b.transpose() * self.arm.ori,
                )
            }
        }
    }

    /// The goal orientation in the world.
    fn world_goal_ori(&self, r_b: &Matrix3<f64>) -> Matrix3<f64> {
        match self.frame {
            InputRefFrame::World => self.goal_ori,
            InputRefFrame::Base => r_b * self.goal_ori,
        }
    }

    fn clip_goal(&mut self) {
        if let Some((lo, hi)) = &self.position_limits {
            for i in 0..3 {
                self.goal_pos[i] = self.goal_pos[i].clamp(lo[i], hi[i]);
            }
        }
        if let Some((lo, hi)) = &self.orientation_limits {
            let mut euler = mat2euler_f32(&self.goal_ori);
            let mut limited = false;
            for i in 0..3 {
                if clip_angle(&mut euler[i], lo[i], hi[i]) {
                    limited = true;
                }
            }
            if limited {
                self.goal_ori = euler2mat(euler);
            }
        }
    }

    /// The base-frame site's linear and angular velocity (robosuite's
    /// `get_site_xvelp/xvelr` of `{robot}{arm}_center`), read live.
    fn base_velocity(&mut self, sim: &Sim) -> (Vector3<f64>, Vector3<f64>) {
        let nv = self.arm.binding().nv;
        sim.data().jac_site_into(
            self.arm.binding().base_site,
            Some(&mut self.base_jacp),
            Some(&mut self.base_jacr),
        );
        let qvel = sim.data().qvel();
        let (mut v, mut w) = (Vector3::zeros(), Vector3::zeros());
        for r in 0..3 {
            for (k, qd) in qvel.iter().enumerate() {
                v[r] += self.base_jacp[r * nv + k] * qd;
                w[r] += self.base_jacr[r * nv + k] * qd;
            }
        }
        (v, w)
    }
}

/// Clips an Euler angle to `[lo, hi]` (an inverted sector when `lo > hi`), to the nearer
/// bound by wrapped angular distance; returns whether it was clipped.
fn clip_angle(angle: &mut f64, lo: f64, hi: f64) -> bool {
    let inside = if lo < hi {
        lo < *angle && *angle < hi
    } else {
        lo < *angle || *angle < hi
    };
    if inside {
        return false;
    }
    let wrap = |d: f64| {
        if d > PI {
            d - 2.0 * PI
        } else if d < -PI {
            d + 2.0 * PI
        } else {
            d
        }
    };
    *angle = if wrap(*angle - lo).abs() <= wrap(*angle - hi).abs() {
        lo
    } else {
        hi
    };
    true
}

impl ArmController for Osc {
    fn name(&self) -> &'static str {
        if self.use_ori {
            "OSC_POSE"
        } else {
            "OSC_POSITION"
        }
    }

    fn action_dim(&self) -> usize {
        self.scale.dim() + 6 * self.impedance.gain_vectors()
    }

    fn action_limits(&self) -> (Vec<f64>, Vec<f64>) {
        let (mut lo, mut hi) = (Vec::new(), Vec::new());
        if self.impedance == ImpedanceMode::Variable {
            lo.extend(self.damping_limits.0);
            hi.extend(self.damping_limits.1);
        }
        if self.impedance != ImpedanceMode::Fixed {
            lo.extend(self.kp_limits.0);
            hi.extend(self.kp_limits.1);
        }
        let (l, h) = self.scale.input_limits();
        lo.extend(l);
        hi.extend(h);
        (lo, hi)
    }

    fn reset(&mut self, sim: &Sim) {
        self.arm.restart(sim);
        (self.origin_pos, self.origin_ori) = self.live_origin(sim);
        self.update_desired = false;
        self.fresh = true;
        self.reset_pos = self.arm.pos;
        self.reset_ori = self.arm.ori;
        self.initial_joint.copy_from(&self.arm.q);
        self.kp = self.config_kp;
        self.kd = self.config_kd;
        let (p, r) = self.achieved(sim);
        self.goal_pos = p;
        self.goal_ori = r;
        if let Some(ip) = &mut self.interp_pos {
            ip.clear();
            ip.set_goal(self.goal_pos.as_slice());
        }
        self.ori_ref = self.arm.ori;
        if let Some(io) = &mut self.interp_ori {
            io.clear();
            io.set_goal(&[0.0; 3]);
        }
    }

    // The gains come from parallel slices of the action and the limits: indices read best.
    #[allow(clippy::needless_range_loop)]
    fn set_goal(&mut self, sim: &Sim, action: &[f64]) {
        self.arm.update(sim, false);
        let gains = 6 * self.impedance.gain_vectors();
        match self.impedance {
            ImpedanceMode::Variable => {
                for i in 0..6 {
                    let kp = action[6 + i].clamp(self.kp_limits.0[i], self.kp_limits.1[i]);
                    let dr = action[i].clamp(self.damping_limits.0[i], self.damping_limits.1[i]);
                    self.kp[i] = kp;
                    self.kd[i] = 2.0 * kp.sqrt() * dr;
                }
            }
            ImpedanceMode::VariableKp => {
                for i in 0..6 {
                    let kp = action[i].clamp(self.kp_limits.0[i], self.kp_limits.1[i]);
                    self.kp[i] = kp;
                    self.kd[i] = 2.0 * kp.sqrt();
                }
            }
            ImpedanceMode::Fixed => {}
        }
        let input = &action[gains..];
        match self.input_type {
            InputType::Delta => {
                // robosuite's "desired" mode adds the delta to the last goal, which after a
                // reset is the world pose (whatever the input frame).
                let (pos, ori) = match (self.update_desired, self.fresh) {
                    (false, _) => self.achieved(sim),
                    (true, true) => (self.reset_pos, self.reset_ori),
                    (true, false) => (self.goal_pos, self.goal_ori),
                };
                let d = |i: usize| self.scale.apply(i, input[i]);
                self.goal_pos = pos + Vector3::new(d(0), d(1), d(2));
                self.goal_ori = if self.use_ori {
                    quat2mat_f32(axisangle2quat(&Vector3::new(d(3), d(4), d(5)))) * ori
                } else {
                    ori
                };
            }
            InputType::Absolute => {
                self.goal_pos = Vector3::new(input[0], input[1], input[2]);
                self.goal_ori = if self.use_ori {
                    rotvec_to_matrix(&Vector3::new(input[3], input[4], input[5]))
                } else {
                    self.achieved(sim).1
                };
            }
        }
        self.fresh = false;
        self.clip_goal();
        if let Some(ip) = &mut self.interp_pos {
            ip.set_goal(self.goal_pos.as_slice());
        }
        if self.interp_ori.is_some() {
            let (_, r_b) = self.origin(sim);
            self.ori_ref = self.arm.ori;
            let err = orientation_error(&self.world_goal_ori(&r_b), &self.ori_ref);
            if let Some(io) = &mut self.interp_ori {
                io.set_goal(err.as_slice());
            }
        }
    }

    fn compute(&mut self, sim: &Sim, torques: &mut [f64]) {
        self.arm.update(sim, false);
        let (p_b, r_b) = self.origin(sim);
        let goal_pos = match &mut self.interp_pos {
            Some(ip) => {
                let mut g = [0.0; 3];
                ip.next(&mut g);
                Vector3::from(g)
            }
            None => self.goal_pos,
        };
        let desired_pos = match self.frame {
            InputRefFrame::World => goal_pos,
            InputRefFrame::Base => p_b + r_b * goal_pos,
        };
        let e_o = match &mut self.interp_ori {
            Some(io) => {
                let mut e = [0.0; 3];
                io.next(&mut e);
                Vector3::from(e)
            }
            None => orientation_error(&self.world_goal_ori(&r_b), &self.arm.ori),
        };
        let e_p = desired_pos - self.arm.pos;
        let (bv, bw) = self.base_velocity(sim);
        let v = self.arm.vel - bv;
        let om = self.arm.angvel - bw;
        let (kp, kd) = (&self.kp, &self.kd);
        let force = Vector3::from_fn(|i, _| e_p[i] * kp[i] + (-v[i]) * kd[i]);
        let torque = Vector3::from_fn(|i, _| e_o[i] * kp[3 + i] + (-om[i]) * kd[3 + i]);

        // Operational-space matrices (control_utils.opspace_matrices) and the nullspace
        // posture term (control_utils.nullspace_torques).
        self.algebra.torques(
            &self.arm,
            &self.initial_joint,
            sim.data().qfrc_bias(),
            &force,
            &torque,
            self.uncouple,
            torques,
        );
        self.arm.finish();
    }

    /// `[kp (6), kd (6), goal_pos (3), goal_ori (9), ori_ref (9), q₀ (n), interpolators,
    /// cached arm state]`.
    fn state(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.state_len());
        out.extend(self.kp);
        out.extend(self.kd);
        out.extend(self.goal_pos.iter());
        out.extend(self.goal_ori.iter());
        out.extend(self.ori_ref.iter());
        out.extend(self.initial_joint.iter());
        for i in self.interp_pos.iter().chain(&self.interp_ori) {
            out.extend(i.state());
        }
        self.arm.state(&mut out);
        out.push(f64::from(u8::from(self.update_desired)));
        out.push(f64::from(u8::from(self.fresh)));
        out.extend(self.reset_pos.iter());
        out.extend(self.reset_ori.iter());
        out.extend(self.origin_pos.iter());
        out.extend(self.origin_ori.iter());
        out
    }

    fn set_goal_update_mode(&mut self, desired: bool) {
        self.update_desired = desired;
    }

    fn set_state(&mut self, state: &[f64]) -> Result<()> {
        check_state(state, self.state_len(), self.name())?;
        let n = self.arm.joints();
        self.kp.copy_from_slice(&state[..6]);
        self.kd.copy_from_slice(&state[6..12]);
        self.goal_pos.copy_from_slice(&state[12..15]);
        self.goal_ori.copy_from_slice(&state[15..24]);
        self.ori_ref.copy_from_slice(&state[24..33]);
        self.initial_joint.copy_from_slice(&state[33..33 + n]);
        let mut rest = &state[33 + n..];
        for i in self.interp_pos.iter_mut().chain(self.interp_ori.iter_mut()) {
            let k = i.state_len();
            i.set_state(&rest[..k]);
            rest = &rest[k..];
        }
        let rest = self.arm.set_state(rest);
        self.update_desired = rest[0] != 0.0;
        self.fresh = rest[1] != 0.0;
        self.reset_pos.copy_from_slice(&rest[2..5]);
        self.reset_ori.copy_from_slice(&rest[5..14]);
        self.origin_pos.copy_from_slice(&rest[14..17]);
        self.origin_ori.copy_from_slice(&rest[17..26]);
        Ok(())
    }

    fn clone_box(&self) -> Box<dyn ArmController> {
        Box::new(self.clone())
    }
}

impl Osc {
    fn state_len(&self) -> usize {
        33 + self.arm.joints()
            + self
                .interp_pos
                .iter()
                .chain(&self.interp_ori)
                .map(LinearInterpolator::state_len)
                .sum::<usize>()
            + self.arm.state_len()
            + OSC_MODE_STATE
    }
}

/// The goal-update mode, the reset pose and the reset origin in [`Osc`]'s state.
const OSC_MODE_STATE: usize = 2 + 12 + 12;
