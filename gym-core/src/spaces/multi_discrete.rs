//! `MultiDiscrete`: an array of independent discrete choices.

use crate::dtype::DType;
use crate::error::SpaceError;
use crate::space::{DynSpace, Flatten, Space};
use crate::spaces::{AnyBox, AnySpace, BoxSpace};
use crate::value::{ArrayValue, Value};
use ndarray::{ArrayD, IxDyn, Zip};
use rand::RngExt;

/// Gymnasium's `MultiDiscrete(nvec, start)`; elements are `int64` arrays of `nvec`'s shape.
#[derive(Debug, Clone, PartialEq)]
pub struct MultiDiscrete {
    nvec: ArrayD<i64>,
    start: ArrayD<i64>,
}

impl MultiDiscrete {
    /// `MultiDiscrete(nvec)` with every `start` 0.
    ///
    /// # Errors
    /// [`SpaceError::InvalidArgument`] when an entry of `nvec` is not positive.
    pub fn new(nvec: ArrayD<i64>) -> Result<Self, SpaceError> {
        let start = ArrayD::zeros(nvec.raw_dim());
        Self::with_start(nvec, start)
    }

    /// `MultiDiscrete(nvec, start)`.
    ///
    /// # Errors
    /// [`SpaceError::InvalidArgument`] when an entry of `nvec` is not positive;
    /// [`SpaceError::ShapeMismatch`] when `start` has another shape.
    pub fn with_start(nvec: ArrayD<i64>, start: ArrayD<i64>) -> Result<Self, SpaceError> {
        if nvec.iter().any(|&n| n <= 0) {
            return Err(SpaceError::InvalidArgument(
                "MultiDiscrete needs every nvec entry > 0".into(),
            ));
        }
        if start.shape() != nvec.shape() {
            return Err(SpaceError::ShapeMismatch {
                expected: nvec.shape().to_vec(),
                got: start.shape().to_vec(),
            });
        }
        Ok(Self { nvec, start })
    }

    /// The number of choices of each entry.
    pub fn nvec(&self) -> &ArrayD<i64> {
        &self.nvec
    }

    /// The smallest value of each entry.
    pub fn start(&self) -> &ArrayD<i64> {
        &self.start
    }
}

impl Space for MultiDiscrete {
    type Element = ArrayD<i64>;

    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> ArrayD<i64> {
        Zip::from(&self.nvec)
            .and(&self.start)
            .map_collect(|&n, &s| s + rng.random_range(0..n))
    }

    fn contains(&self, x: &ArrayD<i64>) -> bool {
        x.shape() == self.nvec.shape()
            && Zip::from(x)
                .and(&self.nvec)
                .and(&self.start)
                .all(|&v, &n, &s| v >= s && i128::from(v) - i128::from(s) < i128::from(n))
    }

    fn shape(&self) -> Option<&[usize]> {
        Some(self.nvec.shape())
    }
}

impl Flatten for MultiDiscrete {
    fn flatdim(&self) -> usize {
        self.nvec.iter().map(|&n| n as usize).sum()
    }

    fn flat_dtype(&self) -> DType {
        DType::I64
    }

    /// Concatenated one-hot vectors, one per entry in row-major order.
    fn flatten(&self, x: &ArrayD<i64>) -> Result<ArrayValue, SpaceError> {
        if !self.contains(x) {
            return Err(SpaceError::InvalidArgument(
                "value is not in the MultiDiscrete space".into(),
            ));
        }
        let mut out = vec![0i64; self.flatdim()];
        let mut offset = 0usize;
        for ((&v, &n), &s) in x.iter().zip(&self.nvec).zip(&self.start) {
            out[offset + (v - s) as usize] = 1;
            offset += n as usize;
        }
        Ok(ArrayValue::I64(
            ArrayD::from_shape_vec(IxDyn(&[out.len()]), out).expect("length"),
        ))
    }

    fn unflatten(&self, flat: &ArrayValue) -> Result<ArrayD<i64>, SpaceError> {
        if flat.len() != self.flatdim() {
            return Err(SpaceError::Unflatten(format!(
                "expected {} entries, got {}",
                self.flatdim(),
                flat.len()
            )));
        }
        let values = flat.to_f64_vec();
        let mut out = Vec::with_capacity(self.nvec.len());
        let mut offset = 0usize;
        for (&n, &s) in self.nvec.iter().zip(&self.start) {
            let part = &values[offset..offset + n as usize];
            let i = part.iter().position(|&v| v != 0.0).ok_or_else(|| {
                SpaceError::Unflatten("one-hot part has no non-zero entry".into())
            })?;
            out.push(s + i as i64);
            offset += n as usize;
        }
        Ok(ArrayD::from_shape_vec(self.nvec.raw_dim(), out).expect("length"))
    }

    fn flatten_space(&self) -> AnyBox {
        AnyBox::from(BoxSpace::<i64>::uniform(0.0, 1.0, &[self.flatdim()]).expect("0..1 is valid"))
    }
}

impl DynSpace for MultiDiscrete {
    fn to_any(&self) -> AnySpace {
        AnySpace::MultiDiscrete(self.clone())
    }

    fn to_value(&self, x: &ArrayD<i64>) -> Value {
        Value::Array(ArrayValue::I64(x.clone()))
    }

    fn from_value(&self, v: &Value) -> Result<ArrayD<i64>, SpaceError> {
        match v {
            Value::Array(a) => {
                let typed = a.to_typed::<i64>()?;
                if typed.shape() != self.nvec.shape() {
                    return Err(SpaceError::ShapeMismatch {
                        expected: self.nvec.shape().to_vec(),
                        got: typed.shape().to_vec(),
                    });
                }
                Ok(typed)
            }
            other => Err(SpaceError::WrongKind {
                expected: "array",
                got: other.kind(),
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::arr1;

    #[test]
    fn one_hot_parts() {
        let md =
            MultiDiscrete::with_start(arr1(&[2, 3]).into_dyn(), arr1(&[0, 1]).into_dyn()).unwrap();
        let x = arr1(&[1, 3]).into_dyn();
        let flat = md.flatten(&x).unwrap();
        assert_eq!(flat.to_f64_vec(), vec![0.0, 1.0, 0.0, 0.0, 1.0]);
        assert_eq!(md.unflatten(&flat).unwrap(), x);
        assert!(!md.contains(&arr1(&[1, 0]).into_dyn()));
    }
}
