//! [`Autoreset`]: resets the environment on the step after an episode ends (Gymnasium 1.x
//! order).

use gym_core::{Env, Info, ResetOptions, Result, Step};

/// Gymnasium 1.x's `Autoreset`: when the previous step ended the episode
/// (`terminated || truncated`), the next `step` ignores its action, calls `reset()` (no seed,
/// no options) and returns `(reset_obs, 0.0, false, false, reset_info)`. An explicit `reset`
/// clears the pending autoreset. There is no `final_observation`.
#[derive(Debug, Clone)]
pub struct Autoreset<E> {
    env: E,
    autoreset: bool,
}

impl<E: Env> Autoreset<E> {
    /// Wraps `env`.
    pub fn new(env: E) -> Self {
        Self {
            env,
            autoreset: false,
        }
    }

    /// Whether the next `step` will reset instead of stepping.
    pub fn pending_reset(&self) -> bool {
        self.autoreset
    }
}

impl<E: Env> gym_core::StepWrapper for Autoreset<E> {
    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(E::Obs, Info)> {
        this.autoreset = false;
        this.env.reset(seed, options)
    }

    fn step(this: &mut Self, action: &E::Act) -> Result<Step<E::Obs>> {
        let step = if this.autoreset {
            let (observation, info) = this.env.reset(None, None)?;
            Step {
                observation,
                reward: 0.0,
                terminated: false,
                truncated: false,
                info,
            }
        } else {
            this.env.step(action)?
        };
        this.autoreset = step.terminated || step.truncated;
        Ok(step)
    }
}

impl<E: Env> gym_core::Wrapper for Autoreset<E> {
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
    use crate::TimeLimit;
    use crate::toy::CountEnv;

    fn trace(
        env: &mut impl Env<Act = i64, Obs = ndarray::ArrayD<f64>>,
        n: usize,
    ) -> Vec<(f64, f64, bool, bool, bool)> {
        (0..n)
            .map(|_| {
                let s = env.step(&0).unwrap();
                (
                    s.observation[[0]],
                    s.reward,
                    s.terminated,
                    s.truncated,
                    s.info.contains_key("reset"),
                )
            })
            .collect()
    }

    #[test]
    fn resets_on_the_step_after_done() {
        let mut env = Autoreset::new(CountEnv::new(Some(2), None));
        env.reset(None, None).unwrap();
        assert_eq!(
            trace(&mut env, 5),
            vec![
                (1.0, 1.0, false, false, false),
                (2.0, 2.0, true, false, false),
                (0.0, 0.0, false, false, true),
                (1.0, 1.0, false, false, false),
                (2.0, 2.0, true, false, false),
            ]
        );
        assert!(env.pending_reset());
    }

    #[test]
    fn truncation_also_triggers_and_explicit_reset_clears() {
        let mut env = Autoreset::new(TimeLimit::new(CountEnv::new(None, None), 2).unwrap());
        env.reset(None, None).unwrap();
        assert_eq!(
            trace(&mut env, 3)[1..],
            [
                (2.0, 2.0, false, true, false),
                (0.0, 0.0, false, false, true)
            ]
        );
        let _ = env.step(&0).unwrap();
        let _ = env.step(&0).unwrap(); // truncated again
        assert!(env.pending_reset());
        env.reset(None, None).unwrap();
        assert!(!env.pending_reset());
        assert_eq!(trace(&mut env, 1), vec![(1.0, 1.0, false, false, false)]);
        // Both flags at once (terminated on the last allowed step) also autoresets.
        let mut env = Autoreset::new(TimeLimit::new(CountEnv::new(Some(2), None), 2).unwrap());
        env.reset(None, None).unwrap();
        assert_eq!(
            trace(&mut env, 3)[1..],
            [
                (2.0, 2.0, true, true, false),
                (0.0, 0.0, false, false, true)
            ]
        );
    }
}
