//! [`NormalizeReward`]: rewards scaled by the running standard deviation of the discounted
//! return.

use crate::running_mean_std::RunningMeanStd;
use gym_core::{Env, Error, Result, Step};
use ndarray::{ArrayD, IxDyn};

/// Gymnasium's `NormalizeReward(env, gamma=0.99, epsilon=1e-8)`.
///
/// Each step: `discounted = discounted * gamma * (1 - terminated) + reward`; the running
/// statistics are updated with `discounted` (unless frozen); the returned reward is
/// `reward / sqrt(var + epsilon)` (the mean is not subtracted). As in Gymnasium the
/// discounted return is **not** reset by `reset` and not zeroed on truncation.
#[derive(Debug, Clone)]
pub struct NormalizeReward<E> {
    env: E,
    gamma: f64,
    epsilon: f64,
    discounted_reward: f64,
    return_rms: RunningMeanStd<f64>,
    update_running_mean: bool,
}

impl<E: Env> NormalizeReward<E> {
    /// Wraps `env` with `gamma = 0.99` and `epsilon = 1e-8`.
    pub fn new(env: E) -> Self {
        Self {
            env,
            gamma: 0.99,
            epsilon: 1e-8,
            discounted_reward: 0.0,
            return_rms: RunningMeanStd::new(&[]),
            update_running_mean: true,
        }
    }

    /// Wraps `env` with the given discount and epsilon.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when `gamma` is outside `[0, 1]` or `epsilon` is not
    /// positive and finite.
    pub fn with_options(env: E, gamma: f64, epsilon: f64) -> Result<Self> {
        if !(0.0..=1.0).contains(&gamma) {
            return Err(Error::invalid_argument(
                "gamma",
                format!("must be in [0, 1], got {gamma}"),
            ));
        }
        if !(epsilon > 0.0 && epsilon.is_finite()) {
            return Err(Error::invalid_argument(
                "epsilon",
                format!("must be positive and finite, got {epsilon}"),
            ));
        }
        let mut w = Self::new(env);
        w.gamma = gamma;
        w.epsilon = epsilon;
        Ok(w)
    }

    /// The discount factor.
    pub fn gamma(&self) -> f64 {
        self.gamma
    }

    /// The current discounted return.
    pub fn discounted_reward(&self) -> f64 {
        self.discounted_reward
    }

    /// The running statistics of the discounted return.
    pub fn return_rms(&self) -> &RunningMeanStd<f64> {
        &self.return_rms
    }

    /// Whether steps update the statistics.
    pub fn update_running_mean(&self) -> bool {
        self.update_running_mean
    }

    /// Freezes (`false`) or resumes (`true`) the statistics.
    pub fn set_update_running_mean(&mut self, on: bool) {
        self.update_running_mean = on;
    }
}

impl<E: Env> gym_core::StepWrapper for NormalizeReward<E> {
    fn step(this: &mut Self, action: &E::Act) -> Result<Step<E::Obs>> {
        let mut step = this.env.step(action)?;
        let not_terminated = if step.terminated { 0.0 } else { 1.0 };
        this.discounted_reward = this.discounted_reward * this.gamma * not_terminated + step.reward;
        if this.update_running_mean {
            let x = ArrayD::from_elem(IxDyn(&[]), this.discounted_reward);
            this.return_rms
                .update_from_moments(&x, &ArrayD::zeros(IxDyn(&[])), 1.0);
        }
        step.reward /= (this.return_rms.var()[[]] + this.epsilon).sqrt();
        Ok(step)
    }
}

impl<E: Env> gym_core::Wrapper for NormalizeReward<E> {
    type Inner = E;
    type Kind = gym_core::Steps;
    fn inner(&self) -> &E {
        &self.env
    }
    fn inner_mut(&mut self) -> &mut E {
        &mut self.env
    }
    fn into_inner(self) -> E {
        self.env
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{a32, script_f32};

    #[test]
    fn gymnasium_test_vector() {
        // The reference run's env reports terminated from the 3rd step on (it is not reset),
        // so the return restarts at the 3rd and at the 4th step: 1, 2.99, 3, 4.
        let inner = script_f32(&[&[0.0]], &[1.0, 2.0, 3.0, 4.0])
            .with_terminated(vec![false, false, true, true]);
        let mut env = NormalizeReward::new(inner);
        env.reset(None, None).unwrap();
        let want = [70.714213, 2.0098478, 3.1895921, 3.6722713];
        for w in want {
            let r = env.step(&a32(&[0.0, 0.0])).unwrap().reward;
            assert!((r - w).abs() < 1e-5 * w, "got {r}, want {w}");
        }
        assert_eq!(env.discounted_reward(), 4.0);
        // Terminated only at the 3rd step: the 4th return is 3 * 0.99 + 4.
        let inner = script_f32(&[&[0.0]], &[1.0, 2.0, 3.0, 4.0])
            .with_terminated(vec![false, false, true, false]);
        let mut env = NormalizeReward::new(inner);
        env.reset(None, None).unwrap();
        let last = (0..4)
            .map(|_| env.step(&a32(&[0.0, 0.0])).unwrap().reward)
            .last()
            .unwrap();
        assert!((env.discounted_reward() - 6.97).abs() < 1e-12);
        assert!((last - 1.844991366447538).abs() < 1e-9);
    }

    #[test]
    fn reset_keeps_the_discounted_return_and_options_are_checked() {
        let inner = script_f32(&[&[0.0]], &[1.0]);
        let mut env = NormalizeReward::new(inner);
        env.reset(None, None).unwrap();
        let _ = env.step(&a32(&[0.0, 0.0])).unwrap();
        env.reset(None, None).unwrap();
        let _ = env.step(&a32(&[0.0, 0.0])).unwrap();
        assert!((env.discounted_reward() - 1.99).abs() < 1e-12);
        assert!(NormalizeReward::with_options(script_f32(&[&[0.0]], &[1.0]), 1.5, 1e-8).is_err());
        assert!(NormalizeReward::with_options(script_f32(&[&[0.0]], &[1.0]), 0.9, 0.0).is_err());
    }
}
