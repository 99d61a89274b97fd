//! [`TimeLimit`]: truncates episodes after a number of steps (Gymnasium's `TimeLimit`).

use gym_core::{Env, Error, Info, ResetOptions, Result, Step, Transition};

/// Sets `truncated = true` once `max_episode_steps` steps have been taken since the last
/// reset.
///
/// As in Gymnasium: the inner `terminated` is never inspected or changed, so an episode that
/// terminates on its last allowed step returns `terminated = truncated = true`; stepping past
/// the end keeps counting and keeps forcing `truncated`. Unlike Gymnasium (which fails with a
/// `TypeError`), a `step` before the first `reset` is [`Error::ResetNeeded`].
#[derive(Debug, Clone)]
pub struct TimeLimit<E> {
    env: E,
    max_episode_steps: u64,
    elapsed_steps: Option<u64>,
}

impl<E: Env> TimeLimit<E> {
    /// Wraps `env` with a limit of `max_episode_steps` steps per episode.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when `max_episode_steps == 0`.
    pub fn new(env: E, max_episode_steps: u64) -> Result<Self> {
        if max_episode_steps == 0 {
            return Err(Error::invalid_argument(
                "max_episode_steps",
                "must be greater than 0, got 0",
            ));
        }
        Ok(Self {
            env,
            max_episode_steps,
            elapsed_steps: None,
        })
    }

    /// The episode length limit.
    pub fn max_episode_steps(&self) -> u64 {
        self.max_episode_steps
    }

    /// Steps taken since the last reset (`None` before the first reset).
    pub fn elapsed_steps(&self) -> Option<u64> {
        self.elapsed_steps
    }
}

impl<E: Env> gym_core::StepWrapper for TimeLimit<E> {
    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(E::Obs, Info)> {
        this.elapsed_steps = Some(0);
        this.env.reset(seed, options)
    }

    fn step(this: &mut Self, action: &E::Act) -> Result<Step<E::Obs>> {
        let elapsed = this.elapsed_steps.ok_or(Error::ResetNeeded)?;
        let mut step = this.env.step(action)?;
        let elapsed = elapsed + 1;
        this.elapsed_steps = Some(elapsed);
        if elapsed >= this.max_episode_steps {
            step.truncated = true;
        }
        Ok(step)
    }

    fn step_into(
        this: &mut Self,
        action: &E::Act,
        observation: &mut E::Obs,
        info: &mut Info,
    ) -> Result<Transition> {
        let elapsed = this.elapsed_steps.ok_or(Error::ResetNeeded)?;
        let mut transition = this.env.step_into(action, observation, info)?;
        let elapsed = elapsed + 1;
        this.elapsed_steps = Some(elapsed);
        if elapsed >= this.max_episode_steps {
            transition.truncated = true;
        }
        Ok(transition)
    }

    fn writes_rows(this: &Self) -> bool {
        this.env.writes_rows()
    }

    fn step_for_row(this: &mut Self, action: &E::Act, info: &mut Info) -> Result<Transition> {
        let elapsed = this.elapsed_steps.ok_or(Error::ResetNeeded)?;
        let mut transition = this.env.step_for_row(action, info)?;
        let elapsed = elapsed + 1;
        this.elapsed_steps = Some(elapsed);
        if elapsed >= this.max_episode_steps {
            transition.truncated = true;
        }
        Ok(transition)
    }
}

impl<E: Env> gym_core::Wrapper for TimeLimit<E> {
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
    use crate::toy::{CountEnv, a64};

    fn flags(env: &mut TimeLimit<CountEnv>, n: usize) -> Vec<(f64, bool, bool)> {
        (0..n)
            .map(|_| {
                let s = env.step(&0).unwrap();
                (s.observation[[0]], s.terminated, s.truncated)
            })
            .collect()
    }

    #[test]
    fn truncates_exactly_at_the_limit_and_keeps_counting() {
        let mut env = TimeLimit::new(CountEnv::new(None, None), 3).unwrap();
        assert_eq!(env.reset(None, None).unwrap().0, a64(&[0.0]));
        let f = flags(&mut env, 5);
        assert_eq!(
            f,
            vec![
                (1.0, false, false),
                (2.0, false, false),
                (3.0, false, true),
                (4.0, false, true),
                (5.0, false, true)
            ]
        );
        assert_eq!(env.elapsed_steps(), Some(5));
    }

    #[test]
    fn terminated_on_the_last_allowed_step_gives_both_flags() {
        let mut env = TimeLimit::new(CountEnv::new(Some(3), None), 3).unwrap();
        env.reset(None, None).unwrap();
        assert_eq!(flags(&mut env, 3)[2], (3.0, true, true));
        // Terminated before the limit: truncated untouched.
        let mut env = TimeLimit::new(CountEnv::new(Some(2), None), 3).unwrap();
        env.reset(None, None).unwrap();
        assert_eq!(
            flags(&mut env, 3),
            vec![(1.0, false, false), (2.0, true, false), (3.0, false, true)]
        );
    }

    #[test]
    fn reset_mid_episode_restarts_the_count() {
        let mut env = TimeLimit::new(CountEnv::new(None, None), 2).unwrap();
        env.reset(None, None).unwrap();
        let _ = env.step(&0).unwrap();
        env.reset(None, None).unwrap();
        assert_eq!(
            flags(&mut env, 2),
            vec![(1.0, false, false), (2.0, false, true)]
        );
    }

    #[test]
    fn errors() {
        assert!(matches!(
            TimeLimit::new(CountEnv::new(None, None), 0),
            Err(Error::InvalidArgument { .. })
        ));
        let mut env = TimeLimit::new(CountEnv::new(None, None), 2).unwrap();
        assert_eq!(env.step(&0).unwrap_err(), Error::ResetNeeded);
        env.reset(None, None).unwrap();
        // An invalid action leaves the count untouched.
        assert!(matches!(env.step(&7), Err(Error::InvalidAction(_))));
        assert_eq!(env.elapsed_steps(), Some(0));
    }
}
