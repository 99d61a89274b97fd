//! `TupleSpace`: Gymnasium's `Tuple`, a fixed sequence of subspaces.

use crate::dtype::DType;
use crate::error::SpaceError;
use crate::space::{DynSpace, Flatten, Space};
use crate::spaces::{AnyBox, AnySpace, concat_flat_spaces, split_flat};
use crate::value::{ArrayValue, Value};

/// Gymnasium's `Tuple(spaces)`; elements are `Vec<Value>` of the same length.
#[derive(Debug, Clone, PartialEq)]
pub struct TupleSpace {
    spaces: Vec<AnySpace>,
}

impl TupleSpace {
    /// A Tuple of these subspaces (an empty Tuple is allowed, as in Gymnasium; the checker
    /// rejects it).
    pub fn new(spaces: Vec<AnySpace>) -> Self {
        Self { spaces }
    }

    /// The subspaces.
    pub fn spaces(&self) -> &[AnySpace] {
        &self.spaces
    }

    /// The number of subspaces.
    pub fn len(&self) -> usize {
        self.spaces.len()
    }

    /// Whether there are no subspaces.
    pub fn is_empty(&self) -> bool {
        self.spaces.is_empty()
    }
}

impl Space for TupleSpace {
    type Element = Vec<Value>;

    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> Vec<Value> {
        self.spaces.iter().map(|s| s.sample(rng)).collect()
    }

    fn contains(&self, x: &Vec<Value>) -> bool {
        x.len() == self.spaces.len() && self.spaces.iter().zip(x).all(|(s, v)| s.contains(v))
    }

    fn shape(&self) -> Option<&[usize]> {
        None
    }
}

impl Flatten for TupleSpace {
    fn flatdim(&self) -> usize {
        self.spaces.iter().map(Flatten::flatdim).sum()
    }

    fn flat_dtype(&self) -> DType {
        self.spaces
            .iter()
            .map(Flatten::flat_dtype)
            .reduce(DType::promote)
            .unwrap_or(DType::F64)
    }

    fn flatten(&self, x: &Vec<Value>) -> Result<ArrayValue, SpaceError> {
        if x.len() != self.spaces.len() {
            return Err(SpaceError::InvalidArgument(format!(
                "expected {} items, got {}",
                self.spaces.len(),
                x.len()
            )));
        }
        let parts = self
            .spaces
            .iter()
            .zip(x)
            .map(|(s, v)| s.flatten(v))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(ArrayValue::concatenate(&parts))
    }

    fn unflatten(&self, flat: &ArrayValue) -> Result<Vec<Value>, SpaceError> {
        let parts = split_flat(flat, self.spaces.iter())?;
        self.spaces
            .iter()
            .zip(parts)
            .map(|(s, p)| s.unflatten(&p))
            .collect()
    }

    fn flatten_space(&self) -> AnyBox {
        concat_flat_spaces(self.spaces.iter())
    }
}

impl DynSpace for TupleSpace {
    fn to_any(&self) -> AnySpace {
        AnySpace::Tuple(self.clone())
    }

    fn to_value(&self, x: &Vec<Value>) -> Value {
        Value::Tuple(x.clone())
    }

    fn from_value(&self, v: &Value) -> Result<Vec<Value>, SpaceError> {
        match v {
            Value::Tuple(items) if items.len() == self.spaces.len() => self
                .spaces
                .iter()
                .zip(items)
                .map(|(s, i)| s.from_value(i))
                .collect(),
            Value::Tuple(items) => Err(SpaceError::InvalidArgument(format!(
                "expected {} items, got {}",
                self.spaces.len(),
                items.len()
            ))),
            other => Err(SpaceError::WrongKind {
                expected: "tuple",
                got: other.kind(),
            }),
        }
    }
}
