//! `DictSpace`: Gymnasium's `Dict`, named subspaces in a fixed order.

use crate::dtype::DType;
use crate::error::SpaceError;
use crate::space::{DynSpace, Flatten, Space};
use crate::spaces::{AnyBox, AnySpace, concat_flat_spaces, split_flat};
use crate::value::{ArrayValue, DictValue, Value};
use indexmap::IndexMap;

/// Gymnasium's `Dict`: an ordered map of subspaces. Its elements are [`DictValue`]s.
///
/// The order is the one given to [`DictSpace::new`] (Gymnasium's `OrderedDict` behaviour,
/// which robosuite's observation dicts need); [`DictSpace::sorted`] sorts the keys, as
/// Gymnasium does for a plain `dict`. Flattening and sampling follow this order.
#[derive(Debug, Clone, PartialEq)]
pub struct DictSpace {
    spaces: IndexMap<String, AnySpace>,
}

impl DictSpace {
    /// A Dict keeping the given order.
    ///
    /// # Errors
    /// [`SpaceError::InvalidArgument`] for a duplicate key.
    pub fn new<K: Into<String>>(
        spaces: impl IntoIterator<Item = (K, AnySpace)>,
    ) -> Result<Self, SpaceError> {
        let mut map = IndexMap::new();
        for (k, s) in spaces {
            let k = k.into();
            if map.contains_key(&k) {
                return Err(SpaceError::InvalidArgument(format!(
                    "duplicate Dict key `{k}`"
                )));
            }
            map.insert(k, s);
        }
        Ok(Self { spaces: map })
    }

    /// A Dict with its keys sorted (Gymnasium's default for a plain `dict`).
    ///
    /// # Errors
    /// [`SpaceError::InvalidArgument`] for a duplicate key.
    pub fn sorted<K: Into<String>>(
        spaces: impl IntoIterator<Item = (K, AnySpace)>,
    ) -> Result<Self, SpaceError> {
        let mut d = Self::new(spaces)?;
        d.spaces.sort_keys();
        Ok(d)
    }

    /// The subspace under `key`.
    pub fn get(&self, key: &str) -> Option<&AnySpace> {
        self.spaces.get(key)
    }

    /// The keys, in order.
    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.spaces.keys().map(String::as_str)
    }

    /// The subspaces, in order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &AnySpace)> {
        self.spaces.iter().map(|(k, v)| (k.as_str(), v))
    }

    /// The number of subspaces.
    pub fn len(&self) -> usize {
        self.spaces.len()
    }

    /// Whether there are no subspaces.
    pub fn is_empty(&self) -> bool {
        self.spaces.is_empty()
    }

    /// A Dict of the listed keys, in the order listed (Gymnasium's `FilterObservation`).
    ///
    /// # Errors
    /// [`SpaceError::KeyMismatch`] when a key is missing.
    pub fn select(&self, keys: &[String]) -> Result<DictSpace, SpaceError> {
        let mut out = IndexMap::new();
        for k in keys {
            let s = self.spaces.get(k).ok_or_else(|| SpaceError::KeyMismatch {
                expected: self.spaces.keys().cloned().collect(),
                got: keys.to_vec(),
            })?;
            out.insert(k.clone(), s.clone());
        }
        Ok(DictSpace { spaces: out })
    }

    fn value_of<'a>(&self, x: &'a DictValue, key: &str) -> Result<&'a Value, SpaceError> {
        x.get(key).ok_or_else(|| SpaceError::KeyMismatch {
            expected: self.spaces.keys().cloned().collect(),
            got: x.keys().cloned().collect(),
        })
    }
}

impl Space for DictSpace {
    type Element = DictValue;

    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> DictValue {
        self.spaces
            .iter()
            .map(|(k, s)| (k.clone(), s.sample(rng)))
            .collect()
    }

    /// The same key set (in any order) and every value in its subspace.
    fn contains(&self, x: &DictValue) -> bool {
        x.len() == self.spaces.len()
            && self
                .spaces
                .iter()
                .all(|(k, s)| x.get(k).is_some_and(|v| s.contains(v)))
    }

    fn shape(&self) -> Option<&[usize]> {
        None
    }
}

impl Flatten for DictSpace {
    fn flatdim(&self) -> usize {
        self.spaces.values().map(Flatten::flatdim).sum()
    }

    fn flat_dtype(&self) -> DType {
        self.spaces
            .values()
            .map(Flatten::flat_dtype)
            .reduce(DType::promote)
            .unwrap_or(DType::F64)
    }

    fn flatten(&self, x: &DictValue) -> Result<ArrayValue, SpaceError> {
        let parts = self
            .spaces
            .iter()
            .map(|(k, s)| s.flatten(self.value_of(x, k)?))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(ArrayValue::concatenate(&parts))
    }

    /// In place when `out` is a vector of the flat dtype and length: each Box part is cast
    /// straight into its range (other parts are flattened first).
    fn flatten_into(&self, x: &DictValue, out: &mut ArrayValue) -> Result<(), SpaceError> {
        let n = self.flatdim();
        if out.dtype() != self.flat_dtype() || out.shape() != [n] || !out.is_standard_layout() {
            *out = self.flatten(x)?;
            return Ok(());
        }
        let mut at = 0;
        for (k, s) in &self.spaces {
            let v = self.value_of(x, k)?;
            let written = match (s, v) {
                (AnySpace::Box(b), Value::Array(a))
                    if a.shape() == b.shape().unwrap_or(&[])
                        && a.dtype().can_cast_to(b.dtype()) =>
                {
                    out.write_at(at, a)
                }
                _ => out.write_at(at, &s.flatten(v)?),
            };
            if !written {
                *out = self.flatten(x)?;
                return Ok(());
            }
            at += s.flatdim();
        }
        Ok(())
    }

    fn unflatten(&self, flat: &ArrayValue) -> Result<DictValue, SpaceError> {
        let parts = split_flat(flat, self.spaces.values())?;
        self.spaces
            .iter()
            .zip(parts)
            .map(|((k, s), p)| Ok((k.clone(), s.unflatten(&p)?)))
            .collect()
    }

    fn flatten_space(&self) -> AnyBox {
        concat_flat_spaces(self.spaces.values())
    }
}

impl DynSpace for DictSpace {
    fn to_any(&self) -> AnySpace {
        AnySpace::Dict(self.clone())
    }

    fn to_value(&self, x: &DictValue) -> Value {
        Value::Dict(x.clone())
    }

    fn into_value(&self, x: DictValue) -> Value {
        Value::Dict(x)
    }

    fn to_value_into(&self, x: &DictValue, out: &mut Value) {
        match out {
            Value::Dict(d) => crate::value::assign_dict(d, x),
            other => *other = Value::Dict(x.clone()),
        }
    }

    fn from_value(&self, v: &Value) -> Result<DictValue, SpaceError> {
        match v {
            Value::Dict(d) => {
                if d.len() != self.spaces.len() || !self.spaces.keys().all(|k| d.contains_key(k)) {
                    return Err(SpaceError::KeyMismatch {
                        expected: self.spaces.keys().cloned().collect(),
                        got: d.keys().cloned().collect(),
                    });
                }
                self.spaces
                    .iter()
                    .map(|(k, s)| Ok((k.clone(), s.from_value(&d[k])?)))
                    .collect()
            }
            other => Err(SpaceError::WrongKind {
                expected: "dict",
                got: other.kind(),
            }),
        }
    }
}
