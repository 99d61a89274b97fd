//! `Discrete`: the integers `start, start + 1, ..., start + n - 1`.

use crate::dtype::DType;
use crate::error::SpaceError;
use crate::space::{DynSpace, Flatten, Space};
use crate::spaces::{AnyBox, AnySpace, BoxSpace};
use crate::value::{ArrayValue, Value};
use ndarray::{ArrayD, IxDyn};
use rand::RngExt;

/// Gymnasium's `Discrete(n, start=0)`; elements are `i64` (NumPy's default `int64`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Discrete {
    n: i64,
    start: i64,
}

impl Discrete {
    /// `Discrete(n)`, the integers `0..n`.
    ///
    /// # Errors
    /// [`SpaceError::InvalidArgument`] when `n <= 0`.
    pub fn new(n: i64) -> Result<Self, SpaceError> {
        Self::with_start(n, 0)
    }

    /// `Discrete(n, start)`, the integers `start..start + n`.
    ///
    /// # Errors
    /// [`SpaceError::InvalidArgument`] when `n <= 0` or `start + n` overflows.
    pub fn with_start(n: i64, start: i64) -> Result<Self, SpaceError> {
        if n <= 0 {
            return Err(SpaceError::InvalidArgument(format!(
                "Discrete needs n > 0, got {n}"
            )));
        }
        if start.checked_add(n).is_none() {
            return Err(SpaceError::InvalidArgument(format!(
                "start {start} + n {n} overflows int64"
            )));
        }
        Ok(Self { n, start })
    }

    /// The number of elements.
    pub fn n(&self) -> i64 {
        self.n
    }

    /// The smallest element.
    pub fn start(&self) -> i64 {
        self.start
    }
}

impl Space for Discrete {
    type Element = i64;

    /// Uniform over the `n` integers.
    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> i64 {
        self.start + rng.random_range(0..self.n)
    }

    fn contains(&self, x: &i64) -> bool {
        *x >= self.start && i128::from(*x) - i128::from(self.start) < i128::from(self.n)
    }

    fn shape(&self) -> Option<&[usize]> {
        Some(&[])
    }
}

impl Flatten for Discrete {
    fn flatdim(&self) -> usize {
        self.n as usize
    }

    fn flat_dtype(&self) -> DType {
        DType::I64
    }

    /// A one-hot `int64` vector of length `n`.
    fn flatten(&self, x: &i64) -> Result<ArrayValue, SpaceError> {
        if !self.contains(x) {
            return Err(SpaceError::InvalidArgument(format!(
                "{x} is not in Discrete({}, start={})",
                self.n, self.start
            )));
        }
        let mut v = ArrayD::zeros(IxDyn(&[self.n as usize]));
        v[[(x - self.start) as usize]] = 1i64;
        Ok(ArrayValue::I64(v))
    }

    /// `start` + the index of the first non-zero entry.
    fn unflatten(&self, flat: &ArrayValue) -> Result<i64, SpaceError> {
        if flat.len() != self.n as usize {
            return Err(SpaceError::Unflatten(format!(
                "expected {} entries, got {}",
                self.n,
                flat.len()
            )));
        }
        flat.to_f64_vec()
            .iter()
            .position(|&v| v != 0.0)
            .map(|i| self.start + i as i64)
            .ok_or_else(|| SpaceError::Unflatten("one-hot vector has no non-zero entry".into()))
    }

    fn flatten_space(&self) -> AnyBox {
        AnyBox::from(BoxSpace::<i64>::uniform(0.0, 1.0, &[self.n as usize]).expect("0..1 is valid"))
    }
}

impl DynSpace for Discrete {
    fn to_any(&self) -> AnySpace {
        AnySpace::Discrete(*self)
    }

    fn to_value(&self, x: &i64) -> Value {
        Value::Discrete(*x)
    }

    fn from_value(&self, v: &Value) -> Result<i64, SpaceError> {
        match v {
            Value::Discrete(i) => Ok(*i),
            Value::Array(a) if a.shape().is_empty() && !a.dtype().is_float() => {
                Ok(a.to_f64_vec()[0] as i64)
            }
            other => Err(SpaceError::WrongKind {
                expected: "integer",
                got: other.kind(),
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng_from_seed;

    #[test]
    fn one_hot_round_trip_with_start() {
        let d = Discrete::with_start(4, -2).unwrap();
        let flat = d.flatten(&0).unwrap();
        assert_eq!(flat.to_f64_vec(), vec![0.0, 0.0, 1.0, 0.0]);
        assert_eq!(d.unflatten(&flat).unwrap(), 0);
        assert!(d.flatten(&2).is_err());
        assert!(Discrete::new(0).is_err());
    }

    #[test]
    fn samples_cover_range() {
        let d = Discrete::with_start(3, 5).unwrap();
        let mut rng = rng_from_seed(0);
        let s: Vec<i64> = (0..100).map(|_| d.sample(&mut rng)).collect();
        assert!(s.iter().all(|x| d.contains(x)));
        for v in 5..8 {
            assert!(s.contains(&v));
        }
    }
}
