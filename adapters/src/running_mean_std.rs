//! [`RunningMeanStd`]: Gymnasium's running mean and variance (Chan et al.'s parallel
//! update), used by [`NormalizeObservation`](crate::NormalizeObservation) and
//! [`NormalizeReward`](crate::NormalizeReward).

use gym_core::{ArrayElement, Error, Result};
use ndarray::{ArrayD, ArrayViewD, Axis, IxDyn, Zip};
use std::ops::{Add, Div, Mul, Sub};

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// The floating types statistics are kept in (`f32` or `f64`). The arithmetic happens in
/// this type, with scalar operands (`count`, `epsilon`) rounded to it first, exactly as
/// NumPy does for a `float32` or `float64` array and a Python float.
pub trait RmsFloat:
    ArrayElement
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + sealed::Sealed
{
    /// The square root.
    fn sqrt(self) -> Self;
}

impl RmsFloat for f32 {
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
}

impl RmsFloat for f64 {
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
}

/// Gymnasium's `RunningMeanStd(epsilon=1e-4, shape)`: `mean = 0`, `var = 1`,
/// `count = 1e-4` initially.
#[derive(Debug, Clone, PartialEq)]
pub struct RunningMeanStd<F: RmsFloat = f64> {
    mean: ArrayD<F>,
    var: ArrayD<F>,
    count: f64,
}

impl<F: RmsFloat> RunningMeanStd<F> {
    /// Fresh statistics for elements of `shape` with the initial count `1e-4`.
    pub fn new(shape: &[usize]) -> Self {
        Self::with_count(shape, 1e-4)
    }

    /// Fresh statistics with the initial count `epsilon`.
    pub fn with_count(shape: &[usize], epsilon: f64) -> Self {
        Self {
            mean: ArrayD::from_elem(IxDyn(shape), F::zero()),
            var: ArrayD::from_elem(IxDyn(shape), F::one()),
            count: epsilon,
        }
    }

    /// The running mean.
    pub fn mean(&self) -> &ArrayD<F> {
        &self.mean
    }

    /// The running (population) variance.
    pub fn var(&self) -> &ArrayD<F> {
        &self.var
    }

    /// The number of samples seen, plus the initial epsilon.
    pub fn count(&self) -> f64 {
        self.count
    }

    /// Replaces the statistics (for example to evaluate with frozen training statistics).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the shapes differ from the current ones or `count`
    /// is not positive.
    pub fn set(&mut self, mean: ArrayD<F>, var: ArrayD<F>, count: f64) -> Result<()> {
        if mean.shape() != self.mean.shape() || var.shape() != self.var.shape() {
            return Err(Error::invalid_argument(
                "mean/var",
                format!(
                    "expected shape {:?}, got {:?} and {:?}",
                    self.mean.shape(),
                    mean.shape(),
                    var.shape()
                ),
            ));
        }
        if count.is_nan() || count <= 0.0 {
            return Err(Error::invalid_argument(
                "count",
                format!("must be > 0, got {count}"),
            ));
        }
        self.mean = mean;
        self.var = var;
        self.count = count;
        Ok(())
    }

    /// Updates from a batch whose first axis indexes samples (`update(x)`): the batch mean
    /// and population variance are computed in `f64` and rounded to `F`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when a sample's shape differs from the statistics' shape.
    pub fn update(&mut self, batch: ArrayViewD<'_, F>) -> Result<()> {
        if batch.ndim() == 0 || &batch.shape()[1..] != self.mean.shape() {
            return Err(Error::invalid_argument(
                "batch",
                format!(
                    "expected samples of shape {:?}, got a batch of shape {:?}",
                    self.mean.shape(),
                    batch.shape()
                ),
            ));
        }
        let n = batch.shape()[0];
        if n == 0 {
            return Ok(());
        }
        let as64 = batch.mapv(|v| v.to_f64());
        let mean = as64.mean_axis(Axis(0)).expect("non-empty batch");
        let var = as64.var_axis(Axis(0), 0.0);
        self.update_from_moments(&mean.mapv(F::from_f64), &var.mapv(F::from_f64), n as f64);
        Ok(())
    }

    /// Updates from one sample (a batch of one: its mean is the sample, its variance 0).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the sample's shape differs from the statistics' shape.
    pub fn update_one(&mut self, x: &ArrayD<F>) -> Result<()> {
        if x.shape() != self.mean.shape() {
            return Err(Error::invalid_argument(
                "x",
                format!(
                    "expected a sample of shape {:?}, got {:?}",
                    self.mean.shape(),
                    x.shape()
                ),
            ));
        }
        let zeros = ArrayD::from_elem(x.raw_dim(), F::zero());
        self.update_from_moments(x, &zeros, 1.0);
        Ok(())
    }

    /// Gymnasium's `update_mean_var_count_from_moments`, operation for operation.
    pub fn update_from_moments(
        &mut self,
        batch_mean: &ArrayD<F>,
        batch_var: &ArrayD<F>,
        batch_count: f64,
    ) {
        let tot_count = self.count + batch_count;
        let (count, bc, tot) = (
            F::from_f64(self.count),
            F::from_f64(batch_count),
            F::from_f64(tot_count),
        );
        let mut new_var = self.var.clone();
        Zip::from(&mut self.mean)
            .and(&mut new_var)
            .and(batch_mean)
            .and(batch_var)
            .for_each(|mean, var, &bm, &bv| {
                let delta = bm - *mean;
                let m_a = *var * count;
                let m_b = bv * bc;
                let m2 = m_a + m_b + delta * delta * count * bc / tot;
                *mean = *mean + delta * bc / tot;
                *var = m2 / tot;
            });
        self.var = new_var;
        self.count = tot_count;
    }

    /// `(x - mean) / sqrt(var + epsilon)`, elementwise in `F`.
    pub fn normalize(&self, x: &ArrayD<F>, epsilon: f64) -> ArrayD<F> {
        let eps = F::from_f64(epsilon);
        Zip::from(x)
            .and(&self.mean)
            .and(&self.var)
            .map_collect(|&x, &m, &v| (x - m) / (v + eps).sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::arr2;

    #[test]
    fn first_update_matches_gymnasium() {
        let mut rms = RunningMeanStd::<f64>::new(&[2]);
        rms.update_one(&crate::toy::a64(&[1.0, -2.0])).unwrap();
        assert!((rms.mean()[[0]] - 0.99990001).abs() < 1e-8);
        assert!((rms.mean()[[1]] + 1.99980002).abs() < 1e-8);
        assert!((rms.var()[[0]] - 1.9997e-4).abs() < 1e-8);
        assert!((rms.var()[[1]] - 4.9991e-4).abs() < 1e-8);
        assert!((rms.count() - 1.0001).abs() < 1e-12);
    }

    #[test]
    fn batch_update_equals_sequential_moments() {
        let mut a = RunningMeanStd::<f64>::new(&[2]);
        a.update(arr2(&[[1.0, 2.0], [3.0, 6.0]]).into_dyn().view())
            .unwrap();
        assert!((a.mean()[[1]] - 4.0 * 2.0 / 2.0001).abs() < 1e-9);
        assert!(
            a.update(arr2(&[[1.0, 2.0, 3.0]]).into_dyn().view())
                .is_err()
        );
        assert!(a.set(a.mean().clone(), a.var().clone(), 0.0).is_err());
    }
}
