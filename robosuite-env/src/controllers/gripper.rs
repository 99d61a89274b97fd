//! robosuite's `GRIP` controller (`SimpleGripController`) with each gripper's action
//! mapping (`format_action`).

use crate::models::grippers::GripAction;

/// A gripper's command state and its mapping to actuator targets.
///
/// Per env step (`set_goal`) the gripper's [`GripAction`] updates one command per actuator
/// in `[-1, 1]` (Panda: `c ← clip(c + [-1, 1]·0.2·sign(a), −1, 1)`; only the sign of the
/// action matters and 0 holds). Per substep (`ctrl`): `ctrl_i = bias_i + weight_i·c_i` with
/// `bias = (hi + lo)/2`, `weight = (hi − lo)/2` of each actuator's ctrlrange, clipped to it.
#[derive(Debug, Clone, PartialEq)]
pub struct GripController {
    action: GripAction,
    ranges: Vec<[f64; 2]>,
    scaling: bool,
    command: Vec<f64>,
}

impl GripController {
    /// A controller for actuators with the given ctrlranges; `scaling` maps commands
    /// onto the ctrlrange (robosuite's `use_action_scaling`, default true), otherwise the
    /// command is the actuator target.
    pub fn new(action: GripAction, ranges: Vec<[f64; 2]>, scaling: bool) -> Self {
        let n = ranges.len();
        Self {
            action,
            ranges,
            scaling,
            command: vec![0.0; n],
        }
    }

    /// The number of action dimensions.
    pub fn action_dim(&self) -> usize {
        self.action.dof()
    }

    /// Zeroes the command (every reset).
    pub fn reset(&mut self) {
        self.command.iter_mut().for_each(|c| *c = 0.0);
    }

    /// Applies one env step's gripper action (`action` has [`GripController::action_dim`]
    /// values).
    pub fn set_goal(&mut self, action: &[f64]) {
        match self.action {
            GripAction::None => {}
            GripAction::SignIntegrator { signs, speed } => {
                let sign = sign_of(action.first().copied().unwrap_or(0.0));
                for (c, s) in self.command.iter_mut().zip(signs) {
                    *c = (*c + s * speed * sign).clamp(-1.0, 1.0);
                }
            }
            GripAction::ValueIntegrator {
                speed,
                shared,
                tail,
            } => {
                let a = action.first().copied().unwrap_or(0.0);
                let c = (self.command.first().copied().unwrap_or(0.0) + speed * a).clamp(-1.0, 1.0);
                for (i, cmd) in self.command.iter_mut().enumerate() {
                    *cmd = if i < shared {
                        c
                    } else {
                        tail.get(i - shared).copied().unwrap_or(0.0)
                    };
                }
            }
            GripAction::PerActuator { sign, speed, .. } => {
                for (c, a) in self.command.iter_mut().zip(action) {
                    *c = (*c + sign * speed * sign_of(*a)).clamp(-1.0, 1.0);
                }
            }
            GripAction::Indexed { indices, .. } => {
                for (c, &i) in self.command.iter_mut().zip(indices) {
                    *c = action.get(i).copied().unwrap_or(0.0);
                }
            }
        }
    }

    /// The command per actuator.
    pub fn command(&self) -> &[f64] {
        &self.command
    }

    /// Sets the command (for snapshots), each entry clipped to `[-1, 1]` (an integrator's
    /// range; an [`GripAction::Indexed`] command, the action itself, is kept as given);
    /// extra or missing entries are ignored.
    pub fn set_command(&mut self, command: &[f64]) {
        let direct = matches!(self.action, GripAction::Indexed { .. });
        for (c, v) in self.command.iter_mut().zip(command) {
            *c = if direct { *v } else { v.clamp(-1.0, 1.0) };
        }
    }

    /// The target of actuator `i` for the current command, clipped to its ctrlrange.
    pub fn ctrl(&self, i: usize) -> f64 {
        let [lo, hi] = self.ranges[i];
        if !self.scaling {
            return self.command[i].clamp(lo, hi);
        }
        let bias = 0.5 * (hi + lo);
        let weight = 0.5 * (hi - lo);
        (bias + weight * self.command[i].clamp(-1.0, 1.0)).clamp(lo, hi)
    }
}

/// NumPy's `sign`: −1, 0 or 1.
fn sign_of(a: f64) -> f64 {
    if a > 0.0 {
        1.0
    } else if a < 0.0 {
        -1.0
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::grippers::{
        JACO_THREE_FINGER_DEXTEROUS_GRIPPER, PANDA_GRIPPER, ROBOTIQ_THREE_FINGER_GRIPPER,
    };

    #[test]
    fn panda_integrator_saturates_after_five_steps() {
        let mut g =
            GripController::new(PANDA_GRIPPER.action, vec![[0.0, 0.04], [-0.04, 0.0]], true);
        assert_eq!(g.action_dim(), 1);
        assert_eq!((g.ctrl(0), g.ctrl(1)), (0.02, -0.02));
        for _ in 0..5 {
            g.set_goal(&[0.3]);
        }
        assert_eq!(g.command(), [-1.0, 1.0]);
        assert_eq!((g.ctrl(0), g.ctrl(1)), (0.0, 0.0));
        g.set_goal(&[0.0]);
        assert_eq!(g.command(), [-1.0, 1.0]);
        for _ in 0..10 {
            g.set_goal(&[-1e-9]);
        }
        assert_eq!(g.command(), [1.0, -1.0]);
        assert_eq!((g.ctrl(0), g.ctrl(1)), (0.04, -0.04));
        g.reset();
        assert_eq!(g.command(), [0.0, 0.0]);
    }

    #[test]
    fn robotiq_three_finger_integrates_the_value_and_holds_the_scissor_open() {
        let r = [0.0, 1.2217];
        let mut g = GripController::new(
            ROBOTIQ_THREE_FINGER_GRIPPER.action,
            vec![r, r, r, [-0.29, 0.29]],
            true,
        );
        g.set_goal(&[0.5]);
        assert_eq!(g.command(), [0.1, 0.1, 0.1, -1.0]);
        g.set_goal(&[-0.25]);
        assert!((g.command()[0] - 0.05).abs() < 1e-15);
        for _ in 0..20 {
            g.set_goal(&[1.0]);
        }
        assert_eq!(g.command(), [1.0, 1.0, 1.0, -1.0]);
        assert_eq!(g.ctrl(3), -0.29);
    }

    #[test]
    fn dexterous_jaco_moves_each_finger_by_its_own_sign() {
        let mut g = GripController::new(
            JACO_THREE_FINGER_DEXTEROUS_GRIPPER.action,
            vec![[0.0, 1.51]; 3],
            true,
        );
        assert_eq!(g.action_dim(), 3);
        g.set_goal(&[1.0, 0.0, -3.0]);
        assert_eq!(g.command(), [-0.01, 0.0, 0.01]);
    }

    #[test]
    fn inspire_hand_copies_its_actions_to_the_actuators() {
        use crate::models::grippers::INSPIRE_RIGHT_HAND;
        let ranges = vec![[0.0, 1.5]; 12];
        let mut g = GripController::new(INSPIRE_RIGHT_HAND.action, ranges.clone(), false);
        assert_eq!(g.action_dim(), 6);
        g.set_goal(&[0.1, 0.2, 0.3, 0.4, 2.0, -0.5]);
        assert_eq!(
            g.command(),
            [0.1, 0.1, 0.2, 0.2, 0.3, 0.3, 0.4, 0.4, 2.0, 2.0, 2.0, -0.5]
        );
        let ctrl: Vec<f64> = (0..12).map(|i| g.ctrl(i)).collect();
        assert_eq!(
            ctrl,
            [0.1, 0.1, 0.2, 0.2, 0.3, 0.3, 0.4, 0.4, 1.5, 1.5, 1.5, 0.0]
        );
        // A snapshot keeps the command as given (no integrator range).
        let copy = g.command().to_vec();
        g.reset();
        g.set_command(&copy);
        assert_eq!(g.command(), copy.as_slice());
        // With action scaling (robosuite's GRIP default), [-1, 1] spans the ctrlrange.
        let mut scaled = GripController::new(INSPIRE_RIGHT_HAND.action, ranges, true);
        scaled.set_goal(&[1.0, 0.0, -1.0, 0.5, 3.0, -3.0]);
        let ctrl: Vec<f64> = (0..12).map(|i| scaled.ctrl(i)).collect();
        assert_eq!(
            ctrl,
            [
                1.5, 1.5, 0.75, 0.75, 0.0, 0.0, 1.125, 1.125, 1.5, 1.5, 1.5, 0.0
            ]
        );
    }
}
