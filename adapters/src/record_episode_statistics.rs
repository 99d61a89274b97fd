//! [`RecordEpisodeStatistics`]: episode return, length and duration in `info["episode"]`.

use gym_core::{Env, Error, Info, ResetOptions, Result, Step};
use std::collections::VecDeque;
use std::time::Instant;

/// Gymnasium's `RecordEpisodeStatistics`.
///
/// On the step that ends an episode (`terminated || truncated`) it adds
/// `info[stats_key] = {"r": return (float), "l": length (int), "t": seconds since the reset
/// rounded to 6 decimals (float)}` and appends to the return, length and time buffers (each
/// keeping the last `buffer_length` episodes). An inner info that already holds `stats_key`
/// is an [`Error::Contract`] (Gymnasium asserts).
#[derive(Debug, Clone)]
pub struct RecordEpisodeStatistics<E> {
    env: E,
    stats_key: String,
    buffer_length: usize,
    episode_count: u64,
    episode_start: Instant,
    episode_return: f64,
    episode_length: u64,
    return_queue: VecDeque<f64>,
    length_queue: VecDeque<u64>,
    time_queue: VecDeque<f64>,
}

impl<E: Env> RecordEpisodeStatistics<E> {
    /// Wraps `env` with `buffer_length = 100` and `stats_key = "episode"`.
    pub fn new(env: E) -> Self {
        Self::with_options(env, 100, "episode")
    }

    /// Wraps `env` with buffers of `buffer_length` episodes and the info key `stats_key`.
    pub fn with_options(env: E, buffer_length: usize, stats_key: impl Into<String>) -> Self {
        Self {
            env,
            stats_key: stats_key.into(),
            buffer_length,
            episode_count: 0,
            episode_start: Instant::now(),
            episode_return: 0.0,
            episode_length: 0,
            return_queue: VecDeque::with_capacity(buffer_length),
            length_queue: VecDeque::with_capacity(buffer_length),
            time_queue: VecDeque::with_capacity(buffer_length),
        }
    }

    /// Episodes finished so far.
    pub fn episode_count(&self) -> u64 {
        self.episode_count
    }

    /// Returns of the last `buffer_length` episodes, oldest first.
    pub fn return_queue(&self) -> &VecDeque<f64> {
        &self.return_queue
    }

    /// Lengths of the last `buffer_length` episodes, oldest first.
    pub fn length_queue(&self) -> &VecDeque<u64> {
        &self.length_queue
    }

    /// Durations in seconds (rounded to 6 decimals) of the last `buffer_length` episodes.
    pub fn time_queue(&self) -> &VecDeque<f64> {
        &self.time_queue
    }

    /// The return and length of the episode in progress.
    pub fn current_episode(&self) -> (f64, u64) {
        (self.episode_return, self.episode_length)
    }

    fn push<T>(queue: &mut VecDeque<T>, cap: usize, x: T) {
        if cap == 0 {
            return;
        }
        if queue.len() == cap {
            queue.pop_front();
        }
        queue.push_back(x);
    }
}

impl<E: Env> gym_core::StepWrapper for RecordEpisodeStatistics<E> {
    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(E::Obs, Info)> {
        let out = this.env.reset(seed, options)?;
        this.episode_start = Instant::now();
        this.episode_return = 0.0;
        this.episode_length = 0;
        Ok(out)
    }

    fn step(this: &mut Self, action: &E::Act) -> Result<Step<E::Obs>> {
        let mut step = this.env.step(action)?;
        this.episode_return += step.reward;
        this.episode_length += 1;
        if step.terminated || step.truncated {
            if step.info.contains_key(&this.stats_key) {
                return Err(Error::Contract {
                    check: "RecordEpisodeStatistics".into(),
                    message: format!(
                        "the inner info already contains the key `{}`",
                        this.stats_key
                    )
                    .into(),
                });
            }
            let t = (this.episode_start.elapsed().as_secs_f64() * 1e6).round() / 1e6;
            let stats = Info::new()
                .with("r", this.episode_return)
                .with("l", this.episode_length)
                .with("t", t);
            step.info.insert(this.stats_key.clone(), stats);
            let cap = this.buffer_length;
            Self::push(&mut this.time_queue, cap, t);
            Self::push(&mut this.return_queue, cap, this.episode_return);
            Self::push(&mut this.length_queue, cap, this.episode_length);
            this.episode_count += 1;
            this.episode_start = Instant::now();
        }
        Ok(step)
    }
}

impl<E: Env> gym_core::Wrapper for RecordEpisodeStatistics<E> {
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
    use crate::toy::{CountEnv, a32, script_f32};
    use gym_core::InfoValue;

    #[test]
    fn records_return_length_and_time() {
        // Rewards 1, 2 (terminated), then 1, 2 again: r = 3, l = 2 each episode.
        let mut env =
            RecordEpisodeStatistics::with_options(CountEnv::new(Some(2), None), 1, "episode");
        for episode in 1..=2u64 {
            env.reset(None, None).unwrap();
            let s1 = env.step(&0).unwrap();
            assert!(!s1.info.contains_key("episode"));
            let s2 = env.step(&0).unwrap();
            let stats = s2.info.get_map("episode").unwrap();
            assert_eq!(stats.get("r"), Some(&InfoValue::Float(3.0)));
            assert_eq!(stats.get("l"), Some(&InfoValue::Int(2)));
            let t = stats.get_f64("t").unwrap();
            assert!((0.0..1.0).contains(&t) && (t * 1e6 - (t * 1e6).round()).abs() < 1e-6);
            assert_eq!(env.episode_count(), episode);
        }
        // buffer_length 1 keeps only the last episode.
        assert_eq!(
            env.return_queue().iter().copied().collect::<Vec<_>>(),
            vec![3.0]
        );
        assert_eq!(env.length_queue().len(), 1);
        assert_eq!(env.time_queue().len(), 1);
    }

    #[test]
    fn existing_key_is_a_contract_error() {
        let inner = script_f32(&[&[0.0]], &[1.0])
            .with_terminated(vec![true])
            .with_step_info(Info::new().with("episode", 1));
        let mut env = RecordEpisodeStatistics::new(inner);
        env.reset(None, None).unwrap();
        assert!(matches!(
            env.step(&a32(&[0.0, 0.0])),
            Err(Error::Contract { .. })
        ));
    }
}
