//! [`ClipReward`]: rewards clipped into `[min_reward, max_reward]`.

use gym_core::{Env, Error, Info, ResetOptions, Result, Step};

/// Gymnasium's `ClipReward(env, min_reward=None, max_reward=None)`: `np.clip(reward, min,
/// max)` with an open side where a bound is `None`.
#[derive(Debug, Clone)]
pub struct ClipReward<E> {
    env: E,
    min_reward: Option<f64>,
    max_reward: Option<f64>,
}

impl<E: Env> ClipReward<E> {
    /// Wraps `env`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when both bounds are `None`, a bound is NaN, or
    /// `max_reward < min_reward` (Gymnasium's `InvalidBound`).
    pub fn new(env: E, min_reward: Option<f64>, max_reward: Option<f64>) -> Result<Self> {
        if min_reward.is_none() && max_reward.is_none() {
            return Err(Error::invalid_argument(
                "min_reward/max_reward",
                "both bounds are None",
            ));
        }
        if min_reward.is_some_and(f64::is_nan) || max_reward.is_some_and(f64::is_nan) {
            return Err(Error::invalid_argument(
                "min_reward/max_reward",
                "NaN bound",
            ));
        }
        if let (Some(lo), Some(hi)) = (min_reward, max_reward)
            && hi < lo
        {
            return Err(Error::invalid_argument(
                "max_reward",
                format!("{hi} is below min_reward {lo}"),
            ));
        }
        Ok(Self {
            env,
            min_reward,
            max_reward,
        })
    }
}

impl<E: Env> Env for ClipReward<E> {
    type Obs = E::Obs;
    type Act = E::Act;
    type ObsSpace = E::ObsSpace;
    type ActSpace = E::ActSpace;

    fn observation_space(&self) -> &E::ObsSpace {
        self.env.observation_space()
    }

    fn action_space(&self) -> &E::ActSpace {
        self.env.action_space()
    }

    fn reset(
        &mut self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(E::Obs, Info)> {
        self.env.reset(seed, options)
    }

    fn step(&mut self, action: &E::Act) -> Result<Step<E::Obs>> {
        let mut step = self.env.step(action)?;
        if let Some(lo) = self.min_reward
            && step.reward < lo
        {
            step.reward = lo;
        }
        if let Some(hi) = self.max_reward
            && step.reward > hi
        {
            step.reward = hi;
        }
        Ok(step)
    }

    gym_core::forward_env!();
}

impl_wrapper!(ClipReward);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{a32, script_f32};

    #[test]
    fn clips_each_side() {
        let mut env = ClipReward::new(
            script_f32(&[&[0.0]], &[-3.0, 0.5, 7.0]),
            Some(-1.0),
            Some(1.0),
        )
        .unwrap();
        env.reset(None, None).unwrap();
        let r: Vec<f64> = (0..3)
            .map(|_| env.step(&a32(&[0.0, 0.0])).unwrap().reward)
            .collect();
        assert_eq!(r, vec![-1.0, 0.5, 1.0]);
        let mut upper =
            ClipReward::new(script_f32(&[&[0.0]], &[-3.0, 7.0]), None, Some(1.0)).unwrap();
        upper.reset(None, None).unwrap();
        assert_eq!(upper.step(&a32(&[0.0, 0.0])).unwrap().reward, -3.0);
        assert_eq!(upper.step(&a32(&[0.0, 0.0])).unwrap().reward, 1.0);
        assert!(ClipReward::new(script_f32(&[&[0.0]], &[0.0]), None, None).is_err());
        assert!(ClipReward::new(script_f32(&[&[0.0]], &[0.0]), Some(1.0), Some(0.0)).is_err());
    }
}
