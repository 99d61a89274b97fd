//! [`RepeatAction`]: each action repeated a fixed number of times.

use gym_core::{Env, Error, Result, Step};

/// Gymnasium's `RepeatAction(env, num_repeats)` (v1.3): steps the inner environment with
/// the same action `num_repeats` times, summing the rewards, and stops early when an inner
/// step ends the episode. The last inner observation, flags and info are returned.
#[derive(Debug, Clone)]
pub struct RepeatAction<E> {
    env: E,
    num_repeats: u32,
}

impl<E: Env> RepeatAction<E> {
    /// Wraps `env`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when `num_repeats == 0`.
    pub fn new(env: E, num_repeats: u32) -> Result<Self> {
        if num_repeats == 0 {
            return Err(Error::invalid_argument(
                "num_repeats",
                "must be at least 1, got 0",
            ));
        }
        Ok(Self { env, num_repeats })
    }

    /// How many inner steps each step takes (at most).
    pub fn num_repeats(&self) -> u32 {
        self.num_repeats
    }
}

impl<E: Env> gym_core::StepWrapper for RepeatAction<E> {
    fn step(this: &mut Self, action: &E::Act) -> Result<Step<E::Obs>> {
        let mut total = 0.0;
        let mut last = this.env.step(action)?;
        total += last.reward;
        for _ in 1..this.num_repeats {
            if last.terminated || last.truncated {
                break;
            }
            last = this.env.step(action)?;
            total += last.reward;
        }
        last.reward = total;
        Ok(last)
    }
}

impl<E: Env> gym_core::Wrapper for RepeatAction<E> {
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
    use crate::toy::CountEnv;

    #[test]
    fn sums_rewards_and_stops_early() {
        let mut env = RepeatAction::new(CountEnv::new(Some(5), None), 3).unwrap();
        env.reset(None, None).unwrap();
        let s = env.step(&0).unwrap();
        assert_eq!(
            (s.observation[[0]], s.reward, s.terminated),
            (3.0, 6.0, false)
        );
        let s = env.step(&0).unwrap();
        assert_eq!(
            (s.observation[[0]], s.reward, s.terminated),
            (5.0, 9.0, true)
        );
        assert!(RepeatAction::new(CountEnv::new(None, None), 0).is_err());
    }
}
