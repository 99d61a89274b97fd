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

impl<E: Env> Env for Autoreset<E> {
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
        self.autoreset = false;
        self.env.reset(seed, options)
    }

    fn step(&mut self, action: &E::Act) -> Result<Step<E::Obs>> {
        let step = if self.autoreset {
            let (observation, info) = self.env.reset(None, None)?;
            Step {
                observation,
                reward: 0.0,
                terminated: false,
                truncated: false,
                info,
            }
        } else {
            self.env.step(action)?
        };
        self.autoreset = step.terminated || step.truncated;
        Ok(step)
    }

    gym_core::forward_env!();
}

impl_wrapper!(Autoreset);

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
