//! robosuite's `JOINT_TORQUE` controller (`controllers/parts/generic/joint_tor.py`).

use super::config::{Interpolation, JointTorqueConfig, join};
use super::interpolator::{InterpolationKind, LinearInterpolator};
use super::state::{ArmState, Needs};
use super::{ActionScale, ArmBinding, ArmController, Timing, check_ramp_ratio, check_state};
use crate::sim::Sim;
use gym_core::Result;

/// Joint torques from the action.
///
/// * `set_goal`: the input is clipped, scaled (±0.05 N·m by default) and clipped to
///   `torque_limits` (default the motors' ctrlrange).
/// * `compute`: `τ = goal + h` (gravity and Coriolis compensation unless
///   `use_torque_compensation` is off).
///
/// With robosuite's `joint_torque.json` (output ±0.1 N·m) the torques stay below the
/// joints' friction loss (0.1 N·m on the Panda), so the arm holds still, as in robosuite.
#[derive(Debug, Clone)]
pub struct JointTorque {
    arm: ArmState,
    scale: ActionScale,
    limits: (Vec<f64>, Vec<f64>),
    compensate: bool,
    goal: Vec<f64>,
    current: Vec<f64>,
    interp: Option<LinearInterpolator>,
}

impl JointTorque {
    /// The controller for `config` on the arm of `bind`.
    ///
    /// # Errors
    /// [`gym_core::Error::InvalidArgument`] naming the key (under `path`) for a list of the
    /// wrong length or a value out of range.
    pub fn new(
        config: &JointTorqueConfig,
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
        let limits = match &config.torque_limits {
            Some(b) => b.resolve(n, &key("torque_limits"))?,
            None => (
                bind.ctrlrange.iter().map(|r| r[0]).collect(),
                bind.ctrlrange.iter().map(|r| r[1]).collect(),
            ),
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
            limits,
            compensate: config.use_torque_compensation,
            goal: vec![0.0; n],
            current: vec![0.0; n],
            interp,
        })
    }

    /// The torque goal (before compensation).
    pub fn goal(&self) -> &[f64] {
        &self.goal
    }

    fn state_len(&self) -> usize {
        2 * self.arm.joints()
            + self
                .interp
                .as_ref()
                .map_or(0, LinearInterpolator::state_len)
            + self.arm.state_len()
    }
}

impl ArmController for JointTorque {
    fn name(&self) -> &'static str {
        "JOINT_TORQUE"
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
        self.goal.iter_mut().for_each(|g| *g = 0.0);
        self.current.iter_mut().for_each(|g| *g = 0.0);
        if let Some(i) = &mut self.interp {
            i.clear();
            i.set_goal(&self.goal);
        }
    }

    fn set_goal(&mut self, sim: &Sim, action: &[f64]) {
        self.arm.update(sim, false);
        for (i, g) in self.goal.iter_mut().enumerate() {
            *g = self
                .scale
                .apply(i, action[i])
                .clamp(self.limits.0[i], self.limits.1[i]);
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
        let bias = sim.data().qfrc_bias();
        let dofs = &self.arm.binding().dofs;
        for (i, t) in torques.iter_mut().enumerate() {
            *t = if self.compensate {
                self.current[i] + bias[dofs[i]]
            } else {
                self.current[i]
            };
        }
        self.arm.finish();
    }

    /// `[goal (n), current (n), interpolator, cached arm state]`.
    fn state(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.state_len());
        out.extend(&self.goal);
        out.extend(&self.current);
        if let Some(i) = &self.interp {
            out.extend(i.state());
        }
        self.arm.state(&mut out);
        out
    }

    fn set_state(&mut self, state: &[f64]) -> Result<()> {
        check_state(state, self.state_len(), self.name())?;
        let n = self.arm.joints();
        self.goal.copy_from_slice(&state[..n]);
        self.current.copy_from_slice(&state[n..2 * n]);
        let mut rest = &state[2 * n..];
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
