//! robosuite's `GRIP` controller (`SimpleGripController`) with the Panda gripper's
//! command integrator.

/// The gripper command integrator and its mapping to position-actuator targets.
///
/// Per env step (`set_goal`): `c ← clip(c + signs·speed·sign(a), −1, 1)`; only the sign of
/// the action matters and 0 holds. Per substep (`ctrl`): `ctrl_i = bias_i + weight_i·c_i`
/// with `bias = (hi + lo)/2`, `weight = (hi − lo)/2` of each actuator's ctrlrange, clipped
/// to the ctrlrange. For the Panda, `a > 0` closes and `a < 0` opens.
#[derive(Debug, Clone, PartialEq)]
pub struct GripController {
    signs: Vec<f64>,
    speed: f64,
    ranges: Vec<[f64; 2]>,
    command: Vec<f64>,
}

impl GripController {
    /// A controller for actuators with the given ctrlranges; `signs` says which way each
    /// finger's command moves for a positive action (Panda: `[-1, 1]`).
    pub fn new(signs: Vec<f64>, speed: f64, ranges: Vec<[f64; 2]>) -> Self {
        let n = ranges.len();
        Self {
            signs,
            speed,
            ranges,
            command: vec![0.0; n],
        }
    }

    /// Zeroes the integrator (every reset).
    pub fn reset(&mut self) {
        self.command.iter_mut().for_each(|c| *c = 0.0);
    }

    /// Integrates one env-step action (`a` is the gripper entry of the action).
    pub fn set_goal(&mut self, a: f64) {
        let sign = if a > 0.0 {
            1.0
        } else if a < 0.0 {
            -1.0
        } else {
            0.0
        };
        for (c, s) in self.command.iter_mut().zip(&self.signs) {
            *c = (*c + s * self.speed * sign).clamp(-1.0, 1.0);
        }
    }

    /// The integrator state `c` (one entry per actuator).
    pub fn command(&self) -> &[f64] {
        &self.command
    }

    /// Sets the integrator state (for snapshots); extra or missing entries are ignored.
    pub fn set_command(&mut self, command: &[f64]) {
        for (c, v) in self.command.iter_mut().zip(command) {
            *c = v.clamp(-1.0, 1.0);
        }
    }

    /// The actuator target of actuator `i` for the current command.
    pub fn ctrl(&self, i: usize) -> f64 {
        let [lo, hi] = self.ranges[i];
        let bias = 0.5 * (hi + lo);
        let weight = 0.5 * (hi - lo);
        (bias + weight * self.command[i].clamp(-1.0, 1.0)).clamp(lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn panda_integrator_saturates_after_five_steps() {
        let mut g = GripController::new(vec![-1.0, 1.0], 0.2, vec![[0.0, 0.04], [-0.04, 0.0]]);
        assert_eq!((g.ctrl(0), g.ctrl(1)), (0.02, -0.02));
        for _ in 0..5 {
            g.set_goal(0.3);
        }
        assert_eq!(g.command(), [-1.0, 1.0]);
        assert_eq!((g.ctrl(0), g.ctrl(1)), (0.0, 0.0));
        g.set_goal(0.0);
        assert_eq!(g.command(), [-1.0, 1.0]);
        for _ in 0..10 {
            g.set_goal(-1e-9);
        }
        assert_eq!(g.command(), [1.0, -1.0]);
        assert_eq!((g.ctrl(0), g.ctrl(1)), (0.04, -0.04));
        g.reset();
        assert_eq!(g.command(), [0.0, 0.0]);
    }
}
