//! [`ClipReward`]: rewards clipped into `[min_reward, max_reward]`.

use gym_core::{Env, Error, Result, RewardWrapper, Rewards, Wrapper};

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

impl<E: Env> Wrapper for ClipReward<E> {
    type Inner = E;
    type Kind = Rewards;
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

impl<E: Env> RewardWrapper for ClipReward<E> {
    fn reward(&mut self, reward: f64) -> f64 {
        match (self.min_reward, self.max_reward) {
            (Some(lo), _) if reward < lo => lo,
            (_, Some(hi)) if reward > hi => hi,
            _ => reward,
        }
    }
}

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
