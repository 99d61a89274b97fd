//! [`TransformReward`]: rewards mapped by a closure.

use gym_core::{Env, Info, ResetOptions, Result, Step};

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

impl<E: Env, F: FnMut(f64) -> f64 + Send + 'static> Env for TransformReward<E, F> {
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
        step.reward = (self.func)(step.reward);
        Ok(step)
    }

    gym_core::forward_env!();
}

impl_wrapper!(TransformReward, F);

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
