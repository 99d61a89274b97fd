//! robosuite's `JOINT_VELOCITY` controller (`controllers/parts/generic/joint_vel.py`), as
//! robosuite documents it.
//!
//! robosuite 1.5.2 cannot build this controller: its constructor assigns
//! `self.torque_compensation = kwargs.get("use_torque_compensation", True)`, which collides
//! with the read-only `torque_compensation` property and raises `AttributeError`. Here the
//! flag is `use_torque_compensation`, as its other controllers name it; everything else is
//! robosuite's code path (the recorded rollouts run robosuite with that one name fixed).

use super::config::Interpolation;
use super::config::{JointVelocityConfig, join};
use super::interpolator::{InterpolationKind, LinearInterpolator};
use super::state::{ArmState, Needs};
use super::{
    ActionScale, ArmBinding, ArmController, Timing, check_gains, check_ramp_ratio, check_state,
};
use crate::sim::Sim;
use gym_core::Result;

/// The length of robosuite's error-derivative ring buffer.
const DERIVATIVE_WINDOW: usize = 5;

/// A PID on joint velocities.
///
/// * `set_goal`: the input is clipped, scaled (±1 rad/s by default) and clipped to
///   `velocity_limits`.
/// * `compute`: `e = q̇* − q̇`, `τ = kp∘e + ki∘Σe + kd∘mean(Δe over the last 5 substeps) + h`,
///   clipped to the motors' ctrlrange; the sum stops growing while the output saturates.
///   A scalar `kp` is multiplied by each motor's torque range (`ki = 0.005·kp`,
///   `kd = 0.001·kp`).
#[derive(Debug, Clone)]
pub struct JointVelocity {
    arm: ArmState,
    scale: ActionScale,
    kp: Vec<f64>,
    ki: Vec<f64>,
    kd: Vec<f64>,
    velocity_limits: Option<(Vec<f64>, Vec<f64>)>,
    compensate: bool,
    low: Vec<f64>,
    high: Vec<f64>,
    goal: Vec<f64>,
    current: Vec<f64>,
    last_err: Vec<f64>,
    summed_err: Vec<f64>,
    derr: Vec<f64>,
    derr_ptr: usize,
    derr_size: usize,
    saturated: bool,
    interp: Option<LinearInterpolator>,
}

impl JointVelocity {
    /// The controller for `config` on the arm of `bind`.
    ///
    /// # Errors
    /// [`gym_core::Error::InvalidArgument`] naming the key (under `path`) for a list of the
    /// wrong length or a value out of range.
    pub fn new(
        config: &JointVelocityConfig,
        bind: ArmBinding,
        timing: Timing,
        path: &str,
    ) -> Result<Self> {
        let n = bind.dofs.len();
        let key = |k: &str| join(path, k);
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
        let low: Vec<f64> = bind.ctrlrange.iter().map(|r| r[0]).collect();
        let high: Vec<f64> = bind.ctrlrange.iter().map(|r| r[1]).collect();
        let kp: Vec<f64> = if config.kp.is_scalar() {
            let k = config.kp.values()[0];
            (0..n).map(|i| k * (high[i] - low[i])).collect()
        } else {
            config.kp.resolve(n, &key("kp"))?
        };
        check_gains(&kp, &key("kp"))?;
        let velocity_limits = match &config.velocity_limits {
            Some(b) => Some(b.resolve(n, &key("velocity_limits"))?),
            None => None,
        };
        let interp = match config.interpolation {
            Interpolation::Linear => {
                check_ramp_ratio(config.ramp_ratio, &key("ramp_ratio"))?;
                Some(LinearInterpolator::new(
                    n,
                    InterpolationKind::Values,
                    timing.timestep,
                    timing.control_freq,
                    config.ramp_ratio,
                ))
            }
            Interpolation::None => None,
        };
        Ok(Self {
            arm: ArmState::new(
                bind,
                Needs {
                    site: false,
                    mass: false,
                },
            ),
            scale,
            ki: kp.iter().map(|k| k * 0.005).collect(),
            kd: kp.iter().map(|k| k * 0.001).collect(),
            kp,
            velocity_limits,
            compensate: config.use_torque_compensation,
            low,
            high,
            goal: vec![0.0; n],
            current: vec![0.0; n],
            last_err: vec![0.0; n],
            summed_err: vec![0.0; n],
            derr: vec![0.0; DERIVATIVE_WINDOW * n],
            derr_ptr: DERIVATIVE_WINDOW - 1,
            derr_size: 0,
            saturated: false,
            interp,
        })
    }

    /// The goal joint velocities.
    pub fn goal(&self) -> &[f64] {
        &self.goal
    }

    /// The proportional gains per joint.
    pub fn kp(&self) -> &[f64] {
        &self.kp
    }

    fn state_len(&self) -> usize {
        let n = self.arm.joints();
        4 * n
            + DERIVATIVE_WINDOW * n
            + 3
            + self
                .interp
                .as_ref()
                .map_or(0, LinearInterpolator::state_len)
            + self.arm.state_len()
    }
}

impl ArmController for JointVelocity {
    fn name(&self) -> &'static str {
        "JOINT_VELOCITY"
    }

    fn action_dim(&self) -> usize {
        self.scale.dim()
    }

    fn action_limits(&self) -> (Vec<f64>, Vec<f64>) {
        let (l, h) = self.scale.input_limits();
        (l.to_vec(), h.to_vec())
    }

    fn reset(&mut self, sim: &Sim) {
        self.arm.restart(sim);
        for v in [
            &mut self.goal,
            &mut self.current,
            &mut self.last_err,
            &mut self.summed_err,
            &mut self.derr,
        ] {
            v.iter_mut().for_each(|x| *x = 0.0);
        }
        self.derr_ptr = DERIVATIVE_WINDOW - 1;
        self.derr_size = 0;
        self.saturated = false;
        if let Some(i) = &mut self.interp {
            i.clear();
            i.set_goal(&self.goal);
        }
    }

    fn set_goal(&mut self, sim: &Sim, action: &[f64]) {
        self.arm.update(sim, false);
        for (i, g) in self.goal.iter_mut().enumerate() {
            let v = self.scale.apply(i, action[i]);
            *g = match &self.velocity_limits {
                Some((lo, hi)) => v.clamp(lo[i], hi[i]),
                None => v,
            };
        }
        if let Some(i) = &mut self.interp {
            i.set_goal(&self.goal);
        }
    }

    fn compute(&mut self, sim: &Sim, torques: &mut [f64]) {
        self.arm.update(sim, false);
        match &mut self.interp {
            Some(i) => i.next(&mut self.current),
            None => self.current.copy_from_slice(&self.goal),
        }
        let n = self.arm.joints();
        self.derr_ptr = (self.derr_ptr + 1) % DERIVATIVE_WINDOW;
        self.derr_size = (self.derr_size + 1).min(DERIVATIVE_WINDOW);
        let bias = sim.data().qfrc_bias();
        let dofs = &self.arm.binding().dofs;
        let mut clipped_any = false;
        for i in 0..n {
            let err = self.current[i] - self.arm.qd[i];
            let derr = err - self.last_err[i];
            self.last_err[i] = err;
            self.derr[self.derr_ptr * n + i] = derr;
            if !self.saturated {
                self.summed_err[i] += err;
            }
            // NumPy's mean over the filled rows: their sum in row order, over the count.
            let mut sum = 0.0;
            for row in 0..self.derr_size {
                sum += self.derr[row * n + i];
            }
            let avg = sum / self.derr_size as f64;
            let mut t = self.kp[i] * err + self.ki[i] * self.summed_err[i] + self.kd[i] * avg;
            if self.compensate {
                t += bias[dofs[i]];
            }
            let c = t.clamp(self.low[i], self.high[i]);
            if c != t {
                clipped_any = true;
            }
            torques[i] = c;
        }
        self.saturated = clipped_any;
        self.arm.finish();
    }

    /// `[goal (n), current (n), last error (n), summed error (n), derivative buffer (5n),
    /// buffer pointer, buffer size, saturated, interpolator, cached arm state]`.
    fn state(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.state_len());
        out.extend(&self.goal);
        out.extend(&self.current);
        out.extend(&self.last_err);
        out.extend(&self.summed_err);
        out.extend(&self.derr);
        out.push(self.derr_ptr as f64);
        out.push(self.derr_size as f64);
        out.push(f64::from(u8::from(self.saturated)));
        if let Some(i) = &self.interp {
            out.extend(i.state());
        }
        self.arm.state(&mut out);
        out
    }

    fn set_state(&mut self, state: &[f64]) -> Result<()> {
        check_state(state, self.state_len(), self.name())?;
        let n = self.arm.joints();
        let mut at = 0;
        let mut take = |k: usize| {
            let s = &state[at..at + k];
            at += k;
            s
        };
        self.goal.copy_from_slice(take(n));
        self.current.copy_from_slice(take(n));
        self.last_err.copy_from_slice(take(n));
        self.summed_err.copy_from_slice(take(n));
        self.derr.copy_from_slice(take(DERIVATIVE_WINDOW * n));
        self.derr_ptr = (take(1)[0].max(0.0) as usize).min(DERIVATIVE_WINDOW - 1);
        self.derr_size = (take(1)[0].max(0.0) as usize).min(DERIVATIVE_WINDOW);
        self.saturated = take(1)[0] != 0.0;
        let mut rest = &state[at..];
        if let Some(i) = &mut self.interp {
            let k = i.state_len();
            i.set_state(&rest[..k]);
            rest = &rest[k..];
        }
        self.arm.set_state(rest);
        Ok(())
    }

    fn clone_box(&self) -> Box<dyn ArmController> {
        Box::new(self.clone())
    }
}
