//! robosuite's mobile-base controller `MobileBaseJointVelocityController`
//! (`controllers/parts/mobile_base/joint_vel.py`), the `base` part's `JOINT_VELOCITY`.

use super::config::{JointVelocityConfig, join};
use super::interpolator::mat2euler_f32;
use super::{ArmBinding, ArmController, Timing, check_state};
use crate::math::mat_from_row_major;
use crate::sim::Sim;
use gym_core::{Error, Result};

/// Velocity commands for a mobile base's joints (forward, side, yaw), as robosuite runs
/// them:
///
/// * `set_goal`: the forward and side inputs are rotated by the base's yaw since the last
///   reset (read from the base's `center` site, [`ArmBinding::base_site`]); the inputs are
///   used as they are, without robosuite's `input_min`/`input_max` clipping (robosuite
///   scales them and then discards the scaled values).
/// * `compute`: each goal `g` in `[-1, 1]` maps onto its motor's ctrlrange,
///   `mid + half_range·g` (the robot clips the result to the ctrlrange).
/// * `reset`: the goal is the joints' current velocities and the base's orientation is
///   kept as the reference of later rotations.
///
/// The config's `kp`, `velocity_limits` and gains are accepted and unused, as in robosuite;
/// the goal is not interpolated (robosuite's factory builds no interpolator for the base).
#[derive(Debug, Clone)]
pub struct MobileBaseJointVelocity {
    bind: ArmBinding,
    goal: Vec<f64>,
    init_yaw: f32,
}

impl MobileBaseJointVelocity {
    /// The controller for the base joints of `bind` (`config` is checked for its lists'
    /// lengths only, as robosuite reads nothing else of it).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the key for an input/output list of the wrong
    /// length, or when the base does not have its forward and side joints (at least two).
    pub fn new(
        config: &JointVelocityConfig,
        bind: ArmBinding,
        _timing: Timing,
        path: &str,
    ) -> Result<Self> {
        let n = bind.dofs.len();
        if n < 2 {
            return Err(Error::invalid_argument(
                path,
                format!("a mobile base needs its forward and side joints, got {n} joint(s)"),
            ));
        }
        let key = |k: &str| join(path, k);
        config.input_min.resolve(n, &key("input_min"))?;
        config.input_max.resolve(n, &key("input_max"))?;
        config.output_min.resolve(n, &key("output_min"))?;
        config.output_max.resolve(n, &key("output_max"))?;
        Ok(Self {
            goal: vec![0.0; n],
            init_yaw: 0.0,
            bind,
        })
    }

    /// The base's yaw as robosuite's `mat2euler` returns it (float32).
    fn yaw(&self, sim: &Sim) -> f32 {
        let m = mat_from_row_major(&sim.data().site_xmat()[self.bind.base_site]);
        mat2euler_f32(&m)[2] as f32
    }
}

impl ArmController for MobileBaseJointVelocity {
    fn name(&self) -> &'static str {
        "JOINT_VELOCITY"
    }

    fn action_dim(&self) -> usize {
        self.goal.len()
    }

    fn action_limits(&self) -> (Vec<f64>, Vec<f64>) {
        (vec![-1.0; self.goal.len()], vec![1.0; self.goal.len()])
    }

    fn reset(&mut self, sim: &Sim) {
        let qvel = sim.data().qvel();
        for (g, &d) in self.goal.iter_mut().zip(&self.bind.dofs) {
            *g = qvel[d];
        }
        self.init_yaw = self.yaw(sim);
    }

    fn set_goal(&mut self, sim: &Sim, action: &[f64]) {
        // robosuite's angles are float32, and so are their sine and cosine.
        let theta = self.yaw(sim) - self.init_yaw;
        let (x, y) = (action[0], action[1]);
        let (s, c) = (f64::from(theta.sin()), f64::from(theta.cos()));
        self.goal.copy_from_slice(action);
        self.goal[0] = x * c + y * s;
        self.goal[1] = -x * s + y * c;
    }

    fn compute(&mut self, _sim: &Sim, torques: &mut [f64]) {
        for ((t, g), [lo, hi]) in torques.iter_mut().zip(&self.goal).zip(&self.bind.ctrlrange) {
            *t = 0.5 * (hi + lo) + 0.5 * (hi - lo) * g;
        }
    }

    fn state(&self) -> Vec<f64> {
        let mut out = self.goal.clone();
        out.push(f64::from(self.init_yaw));
        out
    }

    fn set_state(&mut self, state: &[f64]) -> Result<()> {
        check_state(state, self.goal.len() + 1, "MobileBaseJointVelocity")?;
        let n = self.goal.len();
        self.goal.copy_from_slice(&state[..n]);
        self.init_yaw = state[n] as f32;
        Ok(())
    }

    fn clone_box(&self) -> Box<dyn ArmController> {
        Box::new(self.clone())
    }
}
