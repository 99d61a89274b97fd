//! [`TransformReward`]: rewards mapped by a closure.

use gym_core::{Env, RewardWrapper, Rewards, Wrapper};

/// Gymnasium's `TransformReward(env, func)`: each reward becomes `func(reward)`.
pub struct TransformReward<E, F> {
    env: E,
    func: F,
}

impl<E: Env, F: FnMut(f64) -> f64 + Send + 'static> TransformReward<E, F> {
    /// Wraps `env`, mapping rewards with `func`.
    pub fn new(env: E, func: F) -> Self {
        Self { env, func }
    }
}

impl<E: std::fmt::Debug, F> std::fmt::Debug for TransformReward<E, F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TransformReward")
            .field("env", &self.env)
            .finish_non_exhaustive()
    }
}

impl<E: Env, F: FnMut(f64) -> f64 + Send + 'static> Wrapper for TransformReward<E, F> {
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

impl<E: Env, F: FnMut(f64) -> f64 + Send + 'static> RewardWrapper for TransformReward<E, F> {
    fn reward(&mut self, reward: f64) -> f64 {
        (self.func)(reward)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::CountEnv;

    #[test]
    fn maps_rewards() {
        let mut env = TransformReward::new(CountEnv::new(None, None), |r| 2.0 * r + 1.0);
        env.reset(None, None).unwrap();
        assert_eq!(env.step(&0).unwrap().reward, 3.0);
        assert_eq!(env.step(&0).unwrap().reward, 5.0);
    }
}
