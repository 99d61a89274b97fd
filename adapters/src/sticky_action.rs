//! [`StickyAction`]: with some probability the previous action is repeated (Machado et al.,
//! 2018).

use gym_core::{Env, EnvRng, Error, Info, ResetOptions, Result, Step, entropy_seed, rng_from_seed};
use rand::RngExt;

/// Mixed into the reset seed so the wrapper's stream differs from the environment's own
/// stream for the same seed.
const STREAM: u64 = 0x5354_4943_4b59_4143; // "STICKYAC"

/// Gymnasium's `StickyAction(env, repeat_action_probability, repeat_action_duration)`.
///
/// Before each step, if a repeat series is running, or with probability `p` when there is a
/// previous action, the previous action is used instead of the given one; a new series
/// draws its length uniformly from `repeat_action_duration = (lo, hi)` (inclusive). `reset`
/// clears the state.
///
/// Randomness: Gymnasium draws from the environment's `np_random`. gym-core environments do
/// not lend their RNG, so this wrapper owns an [`EnvRng`] that `reset(Some(seed))` re-seeds
/// from `seed` (mixed with a constant, so it is not the environment's own stream);
/// `reset(None)` continues the stream, which is seeded from entropy if it has never been
/// seeded. The draws per step are those of Gymnasium (one uniform when not already repeating
/// and a previous action exists, one integer when a series starts).
#[derive(Debug, Clone)]
pub struct StickyAction<E: Env> {
    env: E,
    probability: f64,
    duration: (u64, u64),
    rng: Option<EnvRng>,
    last_action: Option<E::Act>,
    is_sticky: bool,
    num_repeats: u64,
    repeats_taken: u64,
}

impl<E: Env> StickyAction<E> {
    /// Wraps `env` with repeat probability `p` and a repeat duration of one step.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when `p` is outside `[0, 1)`.
    pub fn new(env: E, repeat_action_probability: f64) -> Result<Self> {
        Self::with_duration(env, repeat_action_probability, (1, 1))
    }

    /// Wraps `env` with repeat probability `p` and repeat series of `lo..=hi` steps.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when `p` is outside `[0, 1)`, `lo > hi` or `lo < 1`.
    pub fn with_duration(
        env: E,
        repeat_action_probability: f64,
        duration: (u64, u64),
    ) -> Result<Self> {
        let p = repeat_action_probability;
        if !(0.0..1.0).contains(&p) {
            return Err(Error::invalid_argument(
                "repeat_action_probability",
                format!("must be in [0, 1), got {p}"),
            ));
        }
        if duration.0 > duration.1 {
            return Err(Error::invalid_argument(
                "repeat_action_duration",
                format!("{duration:?} is not a valid range"),
            ));
        }
        if duration.0 < 1 {
            return Err(Error::invalid_argument(
                "repeat_action_duration",
                format!("must be at least 1, got {duration:?}"),
            ));
        }
        Ok(Self {
            env,
            probability: p,
            duration,
            rng: None,
            last_action: None,
            is_sticky: false,
            num_repeats: 0,
            repeats_taken: 0,
        })
    }

    /// The action that will be repeated if the next step is sticky.
    pub fn last_action(&self) -> Option<&E::Act> {
        self.last_action.as_ref()
    }

    fn action(&mut self, action: &E::Act) -> E::Act {
        let rng = self
            .rng
            .get_or_insert_with(|| rng_from_seed(entropy_seed()));
        let mut chosen = action.clone();
        let sticky = self.is_sticky
            || (self.last_action.is_some() && rng.random::<f64>() < self.probability);
        if sticky && let Some(last) = &self.last_action {
            if self.num_repeats == 0 {
                self.num_repeats = rng.random_range(self.duration.0..=self.duration.1);
            }
            chosen = last.clone();
            self.is_sticky = true;
            self.repeats_taken += 1;
        }
        if self.is_sticky && self.num_repeats == self.repeats_taken {
            self.is_sticky = false;
            self.num_repeats = 0;
            self.repeats_taken = 0;
        }
        self.last_action = Some(chosen.clone());
        chosen
    }
}

impl<E: Env> gym_core::StepWrapper for StickyAction<E> {
    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(E::Obs, Info)> {
        this.last_action = None;
        this.is_sticky = false;
        this.num_repeats = 0;
        this.repeats_taken = 0;
        if let Some(s) = seed {
            this.rng = Some(rng_from_seed(s ^ STREAM));
        }
        this.env.reset(seed, options)
    }

    fn step(this: &mut Self, action: &E::Act) -> Result<Step<E::Obs>> {
        let chosen = this.action(action);
        this.env.step(&chosen)
    }
}

impl<E: Env> gym_core::Wrapper for StickyAction<E> {
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
    use crate::toy::DiscreteEnv;
    use gym_core::EnvExt;

    /// Records the actions the inner env receives.
    fn run(p: f64, duration: (u64, u64), seed: u64, actions: &[i64]) -> Vec<i64> {
        let mut env = StickyAction::with_duration(DiscreteEnv::new(), p, duration).unwrap();
        env.reset(Some(seed), None).unwrap();
        let mut got = Vec::new();
        for a in actions {
            let before = env.unwrapped_as::<DiscreteEnv>().unwrap().pos;
            let s = env.step(a).unwrap();
            got.push(i64::from(s.observation > before));
            if s.terminated {
                env.unwrapped_as_mut::<DiscreteEnv>().unwrap().pos = 2;
            }
        }
        got
    }

    #[test]
    fn probability_zero_never_sticks_and_seeding_is_reproducible() {
        let actions: Vec<i64> = (0..40).map(|i| i % 2).collect();
        assert_eq!(run(0.0, (1, 1), 0, &actions), actions);
        let a = run(0.9, (1, 1), 7, &actions);
        assert_eq!(a, run(0.9, (1, 1), 7, &actions));
        assert_ne!(a, actions);
        // The first action is never sticky.
        assert_eq!(a[0], actions[0]);
    }

    #[test]
    fn a_series_repeats_for_its_duration() {
        // With p close to 1 and duration exactly 3, every taken action is followed by runs
        // of the same action; alternating inputs must show runs of length >= 3 after the first.
        let actions: Vec<i64> = (0..30).map(|i| i % 2).collect();
        let got = run(0.999, (3, 3), 1, &actions);
        let changes: Vec<usize> = (1..got.len()).filter(|&i| got[i] != got[i - 1]).collect();
        for w in changes.windows(2) {
            assert!(w[1] - w[0] >= 3, "{got:?}");
        }
        assert!(StickyAction::new(DiscreteEnv::new(), 1.0).is_err());
        assert!(StickyAction::with_duration(DiscreteEnv::new(), 0.5, (2, 1)).is_err());
        assert!(StickyAction::with_duration(DiscreteEnv::new(), 0.5, (0, 1)).is_err());
    }
}
