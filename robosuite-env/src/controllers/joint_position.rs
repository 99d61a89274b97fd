//! robosuite's `JOINT_POSITION` controller (`controllers/parts/generic/joint_pos.py`).

use super::config::{ImpedanceMode, InputType, Interpolation, JointPositionConfig, join};
use super::interpolator::{InterpolationKind, LinearInterpolator};
use super::state::{ArmState, Needs};
use super::{
    ActionScale, ArmBinding, ArmController, Timing, check_gains, check_ramp_ratio, check_state,
};
use crate::sim::Sim;
use gym_core::{Error, Result};
use nalgebra::DVector;

/// Joint-position impedance control of one arm.
///
/// * `set_goal`: in the `variable` mode the action starts with n damping ratios and n
///   stiffnesses, in `variable_kp` with n stiffnesses (clipped to their limits). A `delta`
///   input is clipped, scaled (±0.05 rad by default) and added to the joint positions; an
///   `absolute` input is the target itself. `qpos_limits` clip the target.
/// * `compute`: `τ = M·(kp∘(q* − q) − kd∘q̇) + h` (without `M` and `h` when
///   `use_torque_compensation` is off), `kd = 2·sqrt(kp)·damping_ratio` unless `kd` is
///   given.
#[derive(Debug, Clone)]
pub struct JointPosition {
    core: JointTracker,
    impedance: ImpedanceMode,
    input_type: InputType,
    scale: ActionScale,
    kp_limits: (Vec<f64>, Vec<f64>),
    damping_limits: (Vec<f64>, Vec<f64>),
    qpos_limits: Option<(Vec<f64>, Vec<f64>)>,
}

/// The joint-position tracking part `JOINT_POSITION` and `IK_POSE` share: gains, the joint
/// target (possibly interpolated) and the torque law.
#[derive(Debug, Clone)]
pub(crate) struct JointTracker {
    pub(crate) arm: ArmState,
    config_kp: Vec<f64>,
    config_kd: Vec<f64>,
    pub(crate) kp: Vec<f64>,
    pub(crate) kd: Vec<f64>,
    compensate: bool,
    pub(crate) goal: DVector<f64>,
    interp: Option<LinearInterpolator>,
    desired: Vec<f64>,
    raw: Vec<f64>,
}

impl JointTracker {
    /// A tracker with gains `kp`, `kd` (checked) on the arm of `bind`; `site` when the
    /// owner also needs the reference site's Jacobian.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        site: bool,
        kp: Vec<f64>,
        kd: Vec<f64>,
        compensate: bool,
        interpolation: Interpolation,
        ramp_ratio: f64,
        bind: ArmBinding,
        timing: Timing,
        path: &str,
    ) -> Result<Self> {
        check_gains(&kp, &join(path, "kp"))?;
        check_gains(&kd, &join(path, "kd"))?;
        let n = bind.dofs.len();
        let interp = match interpolation {
            Interpolation::Linear => {
                check_ramp_ratio(ramp_ratio, &join(path, "ramp_ratio"))?;
                Some(LinearInterpolator::new(
                    n,
                    InterpolationKind::Values,
                    timing.timestep,
                    timing.control_freq,
                    ramp_ratio,
                ))
            }
            Interpolation::None => None,
        };
        Ok(Self {
            arm: ArmState::new(bind, Needs { site, mass: true }),
            config_kp: kp.clone(),
            config_kd: kd.clone(),
            kp,
            kd,
            compensate,
            goal: DVector::zeros(n),
            interp,
            desired: vec![0.0; n],
            raw: vec![0.0; n],
        })
    }

    /// Creation at a reset: reads the state, restores the configured gains, targets the
    /// current joints.
    pub(crate) fn reset(&mut self, sim: &Sim) {
        self.arm.restart(sim);
        self.kp.copy_from_slice(&self.config_kp);
        self.kd.copy_from_slice(&self.config_kd);
        self.goal.copy_from(&self.arm.q);
        if let Some(i) = &mut self.interp {
            i.clear();
            i.set_goal(self.goal.as_slice());
        }
    }

    /// A new joint target.
    pub(crate) fn set_target(&mut self) {
        if let Some(i) = &mut self.interp {
            i.set_goal(self.goal.as_slice());
        }
    }

    /// The torque law on the current (cached) state.
    pub(crate) fn compute(&mut self, sim: &Sim, torques: &mut [f64]) {
        self.arm.update(sim, false);
        match &mut self.interp {
            Some(i) => i.next(&mut self.desired),
            None => self.desired.copy_from_slice(self.goal.as_slice()),
        }
        let n = self.arm.joints();
        for i in 0..n {
            self.raw[i] =
                (self.desired[i] - self.arm.q[i]) * self.kp[i] + (-self.arm.qd[i]) * self.kd[i];
        }
        if self.compensate {
            let bias = sim.data().qfrc_bias();
            let dofs = &self.arm.binding().dofs;
            for (r, t) in torques.iter_mut().enumerate().take(n) {
                let mut s = 0.0;
                for c in 0..n {
                    s += self.arm.mass[(r, c)] * self.raw[c];
                }
                *t = s + bias[dofs[r]];
            }
        } else {
            torques[..n].copy_from_slice(&self.raw);
        }
        self.arm.finish();
    }

    /// The length of [`JointTracker::state`].
    pub(crate) fn state_len(&self) -> usize {
        let n = self.arm.joints();
        3 * n
            + self
                .interp
                .as_ref()
                .map_or(0, LinearInterpolator::state_len)
            + self.arm.state_len()
    }

    /// `[kp (n), kd (n), target (n), interpolator, cached arm state]`.
    pub(crate) fn state(&self, out: &mut Vec<f64>) {
        out.extend(&self.kp);
        out.extend(&self.kd);
        out.extend(self.goal.iter());
        if let Some(i) = &self.interp {
            out.extend(i.state());
        }
        self.arm.state(out);
    }

    /// Restores [`JointTracker::state`] from the front of `state` (length checked by the
    /// caller); returns the rest.
    pub(crate) fn set_state<'a>(&mut self, state: &'a [f64]) -> &'a [f64] {
        let n = self.arm.joints();
        self.kp.copy_from_slice(&state[..n]);
        self.kd.copy_from_slice(&state[n..2 * n]);
        self.goal.copy_from_slice(&state[2 * n..3 * n]);
        let mut rest = &state[3 * n..];
        if let Some(i) = &mut self.interp {
            let k = i.state_len();
            i.set_state(&rest[..k]);
            rest = &rest[k..];
        }
        self.arm.set_state(rest)
    }
}

impl JointPosition {
    /// The controller for `config` on the arm of `bind`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the key (under `path`) for a list of the wrong
    /// length (not one value per joint), a value out of range, or absolute inputs with
    /// variable impedance (robosuite asserts the same).
    pub fn new(
        config: &JointPositionConfig,
        bind: ArmBinding,
        timing: Timing,
        path: &str,
    ) -> Result<Self> {
        let n = bind.dofs.len();
        let key = |k: &str| join(path, k);
        if config.input_type == InputType::Absolute && config.impedance_mode != ImpedanceMode::Fixed
        {
            return Err(Error::invalid_argument(
                key("input_type"),
                "absolute inputs need impedance_mode \"fixed\" (robosuite asserts the same)",
            ));
        }
        let scale = ActionScale::new(
            (
                config.input_min.resolve(n, &key("input_min"))?,
                config.input_max.resolve(n, &key("input_max"))?,
            ),
            (
                config.output_min.resolve(n, &key("output_min"))?,
                config.output_max.resolve(n, &key("output_max"))?,
            ),
            path,
        )?;
        let kp = config.kp.resolve(n, &key("kp"))?;
        let damping = config.damping_ratio.resolve(n, &key("damping_ratio"))?;
        check_gains(&damping, &key("damping_ratio"))?;
        let kd = match &config.kd {
            Some(kd) => kd.resolve(n, &key("kd"))?,
            None => (0..n)
                .map(|i| 2.0 * kp[i].max(0.0).sqrt() * damping[i])
                .collect(),
        };
        let kp_limits = config.kp_limits.resolve(n, &key("kp_limits"))?;
        check_gains(&kp_limits.0, &key("kp_limits"))?;
        let damping_limits = config
            .damping_ratio_limits
            .resolve(n, &key("damping_ratio_limits"))?;
        check_gains(&damping_limits.0, &key("damping_ratio_limits"))?;
        let qpos_limits = match &config.qpos_limits {
            Some(b) => Some(b.resolve(n, &key("qpos_limits"))?),
            None => None,
        };
        Ok(Self {
            core: JointTracker::new(
                false,
                kp,
                kd,
                config.use_torque_compensation,
                config.interpolation,
                config.ramp_ratio,
                bind,
                timing,
                path,
            )?,
            impedance: config.impedance_mode,
            input_type: config.input_type,
            scale,
            kp_limits,
            damping_limits,
            qpos_limits,
        })
    }

    /// The joint target.
    pub fn goal(&self) -> &[f64] {
        self.core.goal.as_slice()
    }

    /// The current stiffness per joint.
    pub fn kp(&self) -> &[f64] {
        &self.core.kp
    }
}

impl ArmController for JointPosition {
    fn name(&self) -> &'static str {
        "JOINT_POSITION"
    }

    fn action_dim(&self) -> usize {
        self.scale.dim() * (1 + self.impedance.gain_vectors())
    }

    fn action_limits(&self) -> (Vec<f64>, Vec<f64>) {
        let (mut lo, mut hi) = (Vec::new(), Vec::new());
        if self.impedance == ImpedanceMode::Variable {
            lo.extend(&self.damping_limits.0);
            hi.extend(&self.damping_limits.1);
        }
        if self.impedance != ImpedanceMode::Fixed {
            lo.extend(&self.kp_limits.0);
            hi.extend(&self.kp_limits.1);
        }
        let (l, h) = self.scale.input_limits();
        lo.extend(l);
        hi.extend(h);
        (lo, hi)
    }

    fn reset(&mut self, sim: &Sim) {
        self.core.reset(sim);
    }

    // The gains come from parallel slices of the action and the limits: indices read best.
    #[allow(clippy::needless_range_loop)]
    fn set_goal(&mut self, sim: &Sim, action: &[f64]) {
        let c = &mut self.core;
        c.arm.update(sim, false);
        let n = c.arm.joints();
        let input = match self.impedance {
            ImpedanceMode::Variable => {
                for i in 0..n {
                    let kp = action[n + i].clamp(self.kp_limits.0[i], self.kp_limits.1[i]);
                    let dr = action[i].clamp(self.damping_limits.0[i], self.damping_limits.1[i]);
                    c.kp[i] = kp;
                    c.kd[i] = 2.0 * kp.sqrt() * dr;
                }
                &action[2 * n..]
            }
            ImpedanceMode::VariableKp => {
                for i in 0..n {
                    let kp = action[i].clamp(self.kp_limits.0[i], self.kp_limits.1[i]);
                    c.kp[i] = kp;
                    c.kd[i] = 2.0 * kp.sqrt();
                }
                &action[n..]
            }
            ImpedanceMode::Fixed => action,
        };
        for i in 0..n {
            let target = match self.input_type {
                InputType::Delta => c.arm.q[i] + self.scale.apply(i, input[i]),
                InputType::Absolute => input[i],
            };
            c.goal[i] = match &self.qpos_limits {
                Some((lo, hi)) => target.clamp(lo[i], hi[i]),
                None => target,
            };
        }
        c.set_target();
    }

    fn compute(&mut self, sim: &Sim, torques: &mut [f64]) {
        self.core.compute(sim, torques);
    }

    fn state(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.core.state_len());
        self.core.state(&mut out);
        out
    }

    fn set_state(&mut self, state: &[f64]) -> Result<()> {
        check_state(state, self.core.state_len(), self.name())?;
        self.core.set_state(state);
        Ok(())
    }

    fn clone_box(&self) -> Box<dyn ArmController> {
        Box::new(self.clone())
    }
}
