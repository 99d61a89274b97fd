//! [`NormalizeObservation`]: observations normalised by running statistics.

use crate::numeric::NumericSpace;
use crate::running_mean_std::RunningMeanStd;
use gym_core::spaces::BoxSpace;
use gym_core::{DType, Env, Error, ObservationWrapper, Observations, Result, Wrapper};
use ndarray::ArrayD;

/// The statistics, kept in `f32` for `float32` observations and in `f64` otherwise, as
/// NumPy's type promotion does in Gymnasium.
#[derive(Debug, Clone, PartialEq)]
enum Stats {
    F32(RunningMeanStd<f32>),
    F64(RunningMeanStd<f64>),
}

/// Gymnasium's `NormalizeObservation(env, epsilon=1e-8)`.
///
/// The observation space becomes `Box(-inf, inf, shape, float32)`. Each observation (from
/// `reset` and `step`) first updates the running mean and variance (unless
/// [`set_update_running_mean(false)`](Self::set_update_running_mean)), then is returned as
/// `float32((obs - mean) / sqrt(var + epsilon))`. The statistics start at `mean = 0`,
/// `var = 1`, `count = 1e-4`, and are computed in `float32` for `float32` observations and in
/// `float64` otherwise, reproducing Gymnasium's numbers.
#[derive(Debug, Clone)]
pub struct NormalizeObservation<E> {
    env: E,
    space: BoxSpace<f32>,
    stats: Stats,
    epsilon: f64,
    update_running_mean: bool,
}

impl<E: Env> NormalizeObservation<E>
where
    E::ObsSpace: NumericSpace,
{
    /// Wraps `env` with `epsilon = 1e-8`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the observation space is not an array space.
    pub fn new(env: E) -> Result<Self> {
        Self::with_epsilon(env, 1e-8)
    }

    /// Wraps `env` with the given `epsilon`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when `epsilon` is not positive and finite, or the
    /// observation space is not an array space (Dict, Tuple).
    pub fn with_epsilon(env: E, epsilon: f64) -> Result<Self> {
        if !(epsilon > 0.0 && epsilon.is_finite()) {
            return Err(Error::invalid_argument(
                "epsilon",
                format!("must be positive and finite, got {epsilon}"),
            ));
        }
        let spec = env.observation_space().array_spec()?;
        let stats = if spec.dtype == DType::F32 {
            Stats::F32(RunningMeanStd::new(&spec.shape))
        } else {
            Stats::F64(RunningMeanStd::new(&spec.shape))
        };
        Ok(Self {
            space: BoxSpace::unbounded(&spec.shape),
            env,
            stats,
            epsilon,
            update_running_mean: true,
        })
    }

    fn normalize(&mut self, obs: &E::Obs) -> Result<ArrayD<f32>> {
        let space = self.env.observation_space();
        let update = self.update_running_mean;
        match &mut self.stats {
            Stats::F32(rms) => {
                let x = space.element_to_array::<f32>(obs)?;
                if update {
                    rms.update_one(&x)?;
                } else if x.shape() != rms.mean().shape() {
                    return Err(shape_error(rms.mean().shape(), x.shape()));
                }
                Ok(rms.normalize(&x, self.epsilon))
            }
            Stats::F64(rms) => {
                let x = space.element_to_array::<f64>(obs)?;
                if update {
                    rms.update_one(&x)?;
                } else if x.shape() != rms.mean().shape() {
                    return Err(shape_error(rms.mean().shape(), x.shape()));
                }
                Ok(rms.normalize(&x, self.epsilon).mapv(|v| v as f32))
            }
        }
    }
}

fn shape_error(expected: &[usize], got: &[usize]) -> Error {
    gym_core::SpaceError::ShapeMismatch {
        expected: expected.to_vec(),
        got: got.to_vec(),
    }
    .into()
}

impl<E> NormalizeObservation<E> {
    /// Whether observations update the statistics.
    pub fn update_running_mean(&self) -> bool {
        self.update_running_mean
    }

    /// Freezes (`false`) or resumes (`true`) the statistics, e.g. for evaluation.
    pub fn set_update_running_mean(&mut self, on: bool) {
        self.update_running_mean = on;
    }

    /// The `epsilon` added to the variance.
    pub fn epsilon(&self) -> f64 {
        self.epsilon
    }

    /// The running mean, as `f64`.
    pub fn mean(&self) -> ArrayD<f64> {
        match &self.stats {
            Stats::F32(r) => r.mean().mapv(f64::from),
            Stats::F64(r) => r.mean().clone(),
        }
    }

    /// The running variance, as `f64`.
    pub fn var(&self) -> ArrayD<f64> {
        match &self.stats {
            Stats::F32(r) => r.var().mapv(f64::from),
            Stats::F64(r) => r.var().clone(),
        }
    }

    /// The sample count (plus the initial `1e-4`).
    pub fn count(&self) -> f64 {
        match &self.stats {
            Stats::F32(r) => r.count(),
            Stats::F64(r) => r.count(),
        }
    }

    /// Replaces the statistics (rounded to `f32` for `float32` observations), e.g. to
    /// evaluate with the statistics of a training environment.
    ///
    /// # Errors
    /// As [`RunningMeanStd::set`].
    pub fn set_statistics(
        &mut self,
        mean: ArrayD<f64>,
        var: ArrayD<f64>,
        count: f64,
    ) -> Result<()> {
        match &mut self.stats {
            Stats::F32(r) => r.set(mean.mapv(|v| v as f32), var.mapv(|v| v as f32), count),
            Stats::F64(r) => r.set(mean, var, count),
        }
    }
}

impl<E: Env> Wrapper for NormalizeObservation<E>
where
    E::ObsSpace: NumericSpace,
{
    type Inner = E;
    type Kind = Observations;
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

impl<E: Env> ObservationWrapper for NormalizeObservation<E>
where
    E::ObsSpace: NumericSpace,
{
    type Space = BoxSpace<f32>;

    fn space(&self) -> &BoxSpace<f32> {
        &self.space
    }

    fn observation(&mut self, observation: E::Obs) -> Result<ArrayD<f32>> {
        self.normalize(&observation)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{DiscreteEnv, ScriptEnv, a32, script_f32, unit_actions};

    fn close(got: &ArrayD<f32>, want: &[f32], tol: f32) {
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g - w).abs() <= tol * w.abs().max(1e-3),
                "got {got}, want {want:?}"
            );
        }
    }

    #[test]
    fn gymnasium_test_vector() {
        let inner = script_f32(
            &[&[1.0, -2.0], &[2.0, -2.0], &[3.0, -4.0], &[4.0, -6.0]],
            &[0.0],
        );
        let mut env = NormalizeObservation::new(inner).unwrap();
        let (obs, _) = env.reset(None, None).unwrap();
        close(&obs, &[0.0070726, -0.0089465], 1e-4);
        let m = env.mean();
        assert!((m[[0]] - 0.9999).abs() < 1e-6 && (m[[1]] + 1.9998).abs() < 1e-6);
        assert!(
            (env.var()[[0]] - 1.9997e-4).abs() < 1e-8 && (env.var()[[1]] - 4.9991e-4).abs() < 1e-8
        );
        assert!((env.count() - 1.0001).abs() < 1e-12);
        let a = a32(&[0.0, 0.0]);
        close(
            &env.step(&a).unwrap().observation,
            &[0.99985, -0.0063258],
            1e-4,
        );
        close(
            &env.step(&a).unwrap().observation,
            &[1.2246939, -1.4141163],
            1e-5,
        );
        close(
            &env.step(&a).unwrap().observation,
            &[1.3416163, -1.5075377],
            1e-5,
        );
        assert_eq!(
            env.observation_space().to_string(),
            "Box(-inf, inf, [2], float32)"
        );
    }

    #[test]
    fn bit_exact_against_gymnasium_in_both_precisions() {
        // Reference: gymnasium 1.4.0 / NumPy 2 with float32 and float64 observation Boxes.
        let seq: [[f64; 2]; 4] = [[1.0, -2.0], [2.0, -2.0], [3.0, -4.0], [4.0, -6.0]];
        let want32: [[f32; 2]; 4] = [
            [0.007072595, -0.008946472],
            [0.99985, -0.0063257623],
            [1.2246939, -1.4141163],
            [1.3416163, -1.5075377],
        ];
        let want64: [[f32; 2]; 4] = [
            [0.007070714, -0.008944093],
            [0.9998501, -0.0063243974],
            [1.2246939, -1.4141164],
            [1.3416162, -1.5075375],
        ];
        let obs32: Vec<ArrayD<f32>> = seq
            .iter()
            .map(|o| a32(&[o[0] as f32, o[1] as f32]))
            .collect();
        let inner = ScriptEnv::new(
            BoxSpace::<f32>::unbounded(&[2]),
            unit_actions(),
            obs32,
            vec![0.0],
        );
        let mut env = NormalizeObservation::new(inner).unwrap();
        let mut got = vec![env.reset(None, None).unwrap().0];
        got.extend((0..3).map(|_| env.step(&a32(&[0.0, 0.0])).unwrap().observation));
        assert_eq!(got, want32.iter().map(|w| a32(w)).collect::<Vec<_>>());
        let obs64: Vec<ArrayD<f64>> = seq.iter().map(|o| crate::toy::a64(o)).collect();
        let inner = ScriptEnv::new(
            BoxSpace::<f64>::unbounded(&[2]),
            unit_actions(),
            obs64,
            vec![0.0],
        );
        let mut env = NormalizeObservation::new(inner).unwrap();
        let mut got = vec![env.reset(None, None).unwrap().0];
        got.extend((0..3).map(|_| env.step(&a32(&[0.0, 0.0])).unwrap().observation));
        assert_eq!(got, want64.iter().map(|w| a32(w)).collect::<Vec<_>>());
    }

    #[test]
    fn frozen_statistics_do_not_move() {
        let inner = script_f32(&[&[1.0, -2.0], &[2.0, -2.0]], &[0.0]);
        let mut env = NormalizeObservation::new(inner).unwrap();
        env.reset(None, None).unwrap();
        env.set_update_running_mean(false);
        let before = (env.mean(), env.var(), env.count());
        let _ = env.step(&a32(&[0.0, 0.0])).unwrap();
        assert_eq!(before, (env.mean(), env.var(), env.count()));
        env.set_statistics(
            crate::toy::a64(&[0.0, 0.0]),
            crate::toy::a64(&[4.0, 4.0]),
            10.0,
        )
        .unwrap();
        let obs = env.step(&a32(&[0.0, 0.0])).unwrap().observation;
        close(&obs, &[0.5, -1.0], 1e-6);
    }

    #[test]
    fn discrete_observations_use_f64_statistics() {
        let mut env = NormalizeObservation::new(DiscreteEnv::new()).unwrap();
        let (obs, _) = env.reset(None, None).unwrap();
        assert_eq!(obs.shape(), &[] as &[usize]);
        // (2 - 2/1.0001) / sqrt(var + eps) with var = 4e-4/1.0001
        let mean = 2.0 / 1.0001;
        let var = (1e-4 + 4.0 * 1e-4 / 1.0001) / 1.0001;
        let want = ((2.0 - mean) / (var + 1e-8f64).sqrt()) as f32;
        assert!((obs[[]] - want).abs() < 1e-6);
        assert!(NormalizeObservation::with_epsilon(DiscreteEnv::new(), 0.0).is_err());
    }
}
