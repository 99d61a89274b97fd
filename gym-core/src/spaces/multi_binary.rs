//! `MultiBinary`: arrays of zeros and ones.

use crate::dtype::DType;
use crate::error::SpaceError;
use crate::space::{DynSpace, Flatten, Space};
use crate::spaces::{AnyBox, AnySpace, BoxSpace};
use crate::value::{ArrayElement, ArrayValue, Value};
use ndarray::{ArrayD, IxDyn};
use rand::RngExt;

/// Gymnasium's `MultiBinary(n)`; elements are `int8` arrays of 0 and 1.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MultiBinary {
    shape: Vec<usize>,
}

impl MultiBinary {
    /// `MultiBinary(shape)`.
    ///
    /// # Errors
    /// [`SpaceError::InvalidArgument`] when the shape is empty or has a zero entry.
    pub fn new(shape: &[usize]) -> Result<Self, SpaceError> {
        if shape.is_empty() || shape.contains(&0) {
            return Err(SpaceError::InvalidArgument(format!(
                "MultiBinary needs positive dimensions, got {shape:?}"
            )));
        }
        Ok(Self {
            shape: shape.to_vec(),
        })
    }
}

impl Space for MultiBinary {
    type Element = ArrayD<i8>;

    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> ArrayD<i8> {
        ArrayD::from_shape_simple_fn(IxDyn(&self.shape), || i8::from(rng.random_bool(0.5)))
    }

    fn contains(&self, x: &ArrayD<i8>) -> bool {
        x.shape() == self.shape.as_slice() && x.iter().all(|&v| v == 0 || v == 1)
    }

    fn shape(&self) -> Option<&[usize]> {
        Some(&self.shape)
    }
}

impl Flatten for MultiBinary {
    fn flatdim(&self) -> usize {
        self.shape.iter().product()
    }

    fn flat_dtype(&self) -> DType {
        DType::I8
    }

    fn flatten(&self, x: &ArrayD<i8>) -> Result<ArrayValue, SpaceError> {
        if x.shape() != self.shape.as_slice() {
            return Err(SpaceError::ShapeMismatch {
                expected: self.shape.clone(),
                got: x.shape().to_vec(),
            });
        }
        Ok(ArrayValue::I8(x.clone()).flattened())
    }

    fn unflatten(&self, flat: &ArrayValue) -> Result<ArrayD<i8>, SpaceError> {
        if flat.len() != self.flatdim() {
            return Err(SpaceError::Unflatten(format!(
                "expected {} entries, got {}",
                self.flatdim(),
                flat.len()
            )));
        }
        let v: Vec<i8> = flat.to_f64_vec().into_iter().map(|x| x as i8).collect();
        Ok(ArrayD::from_shape_vec(IxDyn(&self.shape), v).expect("length"))
    }

    fn flatten_space(&self) -> AnyBox {
        AnyBox::from(BoxSpace::<i8>::uniform(0.0, 1.0, &[self.flatdim()]).expect("0..1 is valid"))
    }
}

impl DynSpace for MultiBinary {
    fn to_any(&self) -> AnySpace {
        AnySpace::MultiBinary(self.clone())
    }

    fn to_value(&self, x: &ArrayD<i8>) -> Value {
        Value::Array(ArrayValue::I8(x.clone()))
    }

    /// Accepts any integer or float array of the right shape (Gymnasium checks no dtype
    /// here); values are converted to `int8`.
    fn from_value(&self, v: &Value) -> Result<ArrayD<i8>, SpaceError> {
        match v {
            Value::Array(a) if a.shape() == self.shape.as_slice() => {
                if a.to_f64_vec()
                    .iter()
                    .any(|v| v.fract() != 0.0 || v.abs() > 127.0)
                {
                    return Err(SpaceError::InvalidArgument(
                        "MultiBinary values must be integers".into(),
                    ));
                }
                Ok(<i8 as ArrayElement>::peek(&a.cast(DType::I8))
                    .cloned()
                    .expect("cast to int8"))
            }
            Value::Array(a) => Err(SpaceError::ShapeMismatch {
                expected: self.shape.clone(),
                got: a.shape().to_vec(),
            }),
            other => Err(SpaceError::WrongKind {
                expected: "array",
                got: other.kind(),
            }),
        }
    }
}
