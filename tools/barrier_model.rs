//! The barrier model of a synchronous vector env: from a sample of single-step times, how
//! much of the machine a vector step of `n` envs on `threads` threads can use.
//!
//! A synchronous step ends when its last env has stepped, so `threads` cores are busy for
//! the sum of the step times but held for the step's *makespan*; the efficiency is
//! `sum / (threads × makespan)` (1 when every env takes the same time). The makespan
//! depends on how envs are assigned to threads:
//!
//! * [`Assignment::Static`]: contiguous blocks of `n / threads` envs per thread (the
//!   previous `ThreadVectorEnv`); the makespan is the largest block sum. With one env per
//!   thread it is the expected maximum of `threads` i.i.d. step times, which grows with
//!   `threads` for any spread of step times.
//! * [`Assignment::Dynamic`]: each thread takes its own block's envs first and then any env
//!   still waiting (the current `ThreadVectorEnv`): greedy list scheduling, whose makespan
//!   exceeds the mean load by at most one step time, so the loss shrinks like
//!   `1 / (envs per thread)`.
//!
//! Step times are drawn by resampling the measured sample (bootstrap), so the prediction
//! keeps the real distribution's tail (resets, contact-rich steps). The model leaves out
//! the hand-off cost and the calling thread's serial work (copying observations), and
//! assumes a core of the larger machine steps an env as fast as one here.

use rand::{Rng, RngExt};

/// How envs are assigned to the threads of a synchronous step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Assignment {
    /// Contiguous blocks, each stepped by its own thread.
    Static,
    /// Own block first, then whatever is left (greedy list scheduling).
    Dynamic,
}

/// Mean, standard deviation and quantiles of a sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// The number of values.
    pub count: usize,
    /// The mean.
    pub mean: f64,
    /// The standard deviation (n − 1 in the denominator).
    pub sd: f64,
    /// The minimum.
    pub min: f64,
    /// The median.
    pub p50: f64,
    /// The 90th percentile.
    pub p90: f64,
    /// The 99th percentile.
    pub p99: f64,
    /// The maximum.
    pub max: f64,
}

/// The `q`-quantile (`0 ≤ q ≤ 1`) of sorted values, by linear interpolation (NumPy's
/// default); NaN for no values.
pub fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let pos = q.clamp(0.0, 1.0) * (sorted.len() - 1) as f64;
    let (lo, hi) = (pos.floor() as usize, pos.ceil() as usize);
    sorted[lo] + (sorted[hi] - sorted[lo]) * (pos - lo as f64)
}

/// The [`Summary`] of `values` (NaN entries for an empty sample).
pub fn summarize(values: &[f64]) -> Summary {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    let mean = sorted.iter().sum::<f64>() / n as f64;
    let var = sorted.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n.max(2) - 1) as f64;
    Summary {
        count: n,
        mean,
        sd: var.sqrt(),
        min: sorted.first().copied().unwrap_or(f64::NAN),
        p50: quantile(&sorted, 0.5),
        p90: quantile(&sorted, 0.9),
        p99: quantile(&sorted, 0.99),
        max: sorted.last().copied().unwrap_or(f64::NAN),
    }
}

/// The makespan of one synchronous step whose envs take `times` (env `i` in block
/// `i * threads / n`, as `ThreadVectorEnv` places them).
pub fn makespan(times: &[f64], threads: usize, assignment: Assignment) -> f64 {
    let n = times.len();
    let threads = threads.clamp(1, n.max(1));
    let block = |t: usize| (t * n).div_ceil(threads)..((t + 1) * n).div_ceil(threads);
    match assignment {
        Assignment::Static => (0..threads)
            .map(|t| times[block(t)].iter().sum::<f64>())
            .fold(0.0, f64::max),
        Assignment::Dynamic => {
            // Each free thread claims the next env of its own block, else of the next block
            // with envs left: an event simulation of the team's claim loop.
            let mut next: Vec<usize> = (0..threads).map(|t| block(t).start).collect();
            let mut free_at = vec![0.0f64; threads];
            loop {
                let t = (0..threads)
                    .min_by(|&a, &b| free_at[a].total_cmp(&free_at[b]))
                    .unwrap_or(0);
                let Some(b) = (0..threads)
                    .map(|k| (t + k) % threads)
                    .find(|&b| next[b] < block(b).end)
                else {
                    break;
                };
                free_at[t] += times[next[b]];
                next[b] += 1;
            }
            free_at.into_iter().fold(0.0, f64::max)
        }
    }
}

/// The predicted efficiency of `n` envs on `threads` threads: the mean over `rounds`
/// resampled steps of `sum of step times / (threads × makespan)`, step times drawn from
/// `sample` with replacement.
pub fn predicted_efficiency<R: Rng + ?Sized>(
    sample: &[f64],
    n: usize,
    threads: usize,
    assignment: Assignment,
    rounds: usize,
    rng: &mut R,
) -> f64 {
    if sample.is_empty() || n == 0 {
        return f64::NAN;
    }
    let threads = threads.clamp(1, n);
    let mut times = vec![0.0; n];
    let mut total = 0.0;
    for _ in 0..rounds.max(1) {
        for t in &mut times {
            *t = sample[rng.random_range(0..sample.len())];
        }
        let work: f64 = times.iter().sum();
        total += work / (threads as f64 * makespan(&times, threads, assignment));
    }
    total / rounds.max(1) as f64
}

/// The expected maximum of `k` i.i.d. step times drawn from `sample` (by resampling).
pub fn expected_max<R: Rng + ?Sized>(sample: &[f64], k: usize, rounds: usize, rng: &mut R) -> f64 {
    if sample.is_empty() || k == 0 {
        return f64::NAN;
    }
    let mut total = 0.0;
    for _ in 0..rounds.max(1) {
        total += (0..k)
            .map(|_| sample[rng.random_range(0..sample.len())])
            .fold(f64::MIN, f64::max);
    }
    total / rounds.max(1) as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use gym_core::rng_from_seed;

    #[test]
    fn quantiles_interpolate_like_numpy() {
        let v = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(quantile(&v, 0.5), 2.5);
        assert_eq!(quantile(&v, 0.0), 1.0);
        assert_eq!(quantile(&v, 1.0), 4.0);
        let s = summarize(&[3.0, 1.0, 2.0]);
        assert_eq!((s.mean, s.sd, s.p50, s.max), (2.0, 1.0, 2.0, 3.0));
    }

    #[test]
    fn equal_step_times_waste_nothing() {
        let mut rng = rng_from_seed(0);
        for a in [Assignment::Static, Assignment::Dynamic] {
            assert_eq!(predicted_efficiency(&[2.0], 16, 16, a, 10, &mut rng), 1.0);
            assert_eq!(predicted_efficiency(&[2.0], 32, 16, a, 10, &mut rng), 1.0);
        }
    }

    #[test]
    fn makespans_of_a_known_step() {
        // Block 0 = [5, 1], block 1 = [1, 1]: static waits for block 0 (6); dynamic lets
        // thread 1 take env 1 after its own two (5 vs 1 + 1 + 1 = 3).
        let times = [5.0, 1.0, 1.0, 1.0];
        assert_eq!(makespan(&times, 2, Assignment::Static), 6.0);
        assert_eq!(makespan(&times, 2, Assignment::Dynamic), 5.0);
        // One env per thread: both wait for the slowest env.
        assert_eq!(makespan(&times, 4, Assignment::Static), 5.0);
        assert_eq!(makespan(&times, 4, Assignment::Dynamic), 5.0);
    }

    #[test]
    fn the_expected_maximum_of_a_coin_flip() {
        // Times 1 or 3 with probability 1/2: E[max of 2] = 3 - 2 * 1/4 = 2.5.
        let mut rng = rng_from_seed(3);
        let e = expected_max(&[1.0, 3.0], 2, 200_000, &mut rng);
        assert!((e - 2.5).abs() < 0.01, "{e}");
        // The barrier loses more with more threads, and dynamic assignment of several envs
        // per thread wins it back.
        let sample = [1.0, 1.0, 1.0, 3.0];
        let mut one = |n, t, a| predicted_efficiency(&sample, n, t, a, 20_000, &mut rng);
        let (e2, e16) = (
            one(2, 2, Assignment::Static),
            one(16, 16, Assignment::Static),
        );
        assert!(e16 < e2, "{e16} {e2}");
        let (dynamic, fixed) = (
            one(64, 16, Assignment::Dynamic),
            one(64, 16, Assignment::Static),
        );
        assert!(dynamic > fixed, "{dynamic} {fixed}");
    }
}
