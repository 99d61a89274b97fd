//! [`FilterableSpace`]: selecting keys of a Dict space or items of a Tuple space (what
//! Gymnasium's `FilterObservation` does), for typed and dynamic spaces.

use crate::error::{Error, Result};
use crate::spaces::{AnySpace, DictSpace, TupleSpace};
use crate::value::{DictValue, Value};
use crate::{Space, SpaceError};

/// The keys to keep: names for a Dict space, indices for a Tuple space.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum FilterKeys {
    /// Dict keys.
    Names(Vec<String>),
    /// Tuple indices.
    Indices(Vec<usize>),
}

impl From<Vec<String>> for FilterKeys {
    fn from(v: Vec<String>) -> Self {
        FilterKeys::Names(v)
    }
}

impl From<Vec<&str>> for FilterKeys {
    fn from(v: Vec<&str>) -> Self {
        FilterKeys::Names(v.into_iter().map(str::to_owned).collect())
    }
}

impl From<&[&str]> for FilterKeys {
    fn from(v: &[&str]) -> Self {
        FilterKeys::Names(v.iter().map(|s| (*s).to_owned()).collect())
    }
}

impl<const N: usize> From<[&str; N]> for FilterKeys {
    fn from(v: [&str; N]) -> Self {
        FilterKeys::Names(v.iter().map(|s| (*s).to_owned()).collect())
    }
}

impl From<Vec<usize>> for FilterKeys {
    fn from(v: Vec<usize>) -> Self {
        FilterKeys::Indices(v)
    }
}

impl<const N: usize> From<[usize; N]> for FilterKeys {
    fn from(v: [usize; N]) -> Self {
        FilterKeys::Indices(v.to_vec())
    }
}

/// A space whose elements can be filtered: Dict, Tuple, or a dynamic space holding one of
/// them.
pub trait FilterableSpace: Space {
    /// The filtered space, a Dict **sorted** by key as Gymnasium's `FilterObservation` makes
    /// it (its new space is built from a plain `dict`, which `Dict` sorts).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an empty selection, a duplicate, keys of the wrong
    /// kind or a space that is neither a Dict nor a Tuple; [`Error::UnknownKey`] for a
    /// missing Dict key or Tuple index.
    fn filter_space(&self, keys: &FilterKeys) -> Result<Self>;

    /// The filtered space with the keys in the listed order (robosuite's `GymWrapper`).
    ///
    /// # Errors
    /// As [`FilterableSpace::filter_space`].
    fn select_space(&self, keys: &FilterKeys) -> Result<Self>;

    /// Keeps the selected parts of an element, in the order of `filtered` (what
    /// [`FilterableSpace::filter_space`] or [`FilterableSpace::select_space`] made of
    /// `keys`). Dict entries are found by name.
    ///
    /// # Errors
    /// When the element lacks a selected part.
    fn filter_element(
        &self,
        keys: &FilterKeys,
        filtered: &Self,
        x: Self::Element,
    ) -> Result<Self::Element>;

    /// [`FilterableSpace::filter_element`] of a borrowed element into `out`, reusing its
    /// storage (see [`Value::assign_from`]) when it has the filtered structure.
    ///
    /// # Errors
    /// As [`FilterableSpace::filter_element`].
    fn filter_element_into(
        &self,
        keys: &FilterKeys,
        filtered: &Self,
        x: &Self::Element,
        out: &mut Self::Element,
    ) -> Result<()> {
        *out = self.filter_element(keys, filtered, x.clone())?;
        Ok(())
    }

    /// Part `i` of an element of this space, borrowed: the `i`-th Dict entry in the space's
    /// key order (found by name when the element's keys are in another order) or the
    /// `i`-th Tuple item; `None` past the end or for an element of another structure.
    fn element_part<'a>(&self, x: &'a Self::Element, i: usize) -> Option<&'a Value>;
}

fn empty() -> Error {
    Error::invalid_argument(
        "filter_keys",
        "the observation space is empty due to filtering all keys",
    )
}

fn check_names(space: &DictSpace, keys: &FilterKeys) -> Result<Vec<String>> {
    let FilterKeys::Names(names) = keys else {
        return Err(Error::invalid_argument(
            "filter_keys",
            "a Dict observation space is filtered by key names",
        ));
    };
    if names.is_empty() {
        return Err(empty());
    }
    for (i, k) in names.iter().enumerate() {
        if space.get(k).is_none() {
            return Err(Error::UnknownKey {
                key: k.clone(),
                available: space.keys().map(str::to_owned).collect(),
            });
        }
        if names[..i].contains(k) {
            return Err(Error::invalid_argument(
                "filter_keys",
                format!("duplicate key `{k}`"),
            ));
        }
    }
    Ok(names.clone())
}

fn check_indices(space: &TupleSpace, keys: &FilterKeys) -> Result<Vec<usize>> {
    let FilterKeys::Indices(idx) = keys else {
        return Err(Error::invalid_argument(
            "filter_keys",
            "a Tuple observation space is filtered by indices",
        ));
    };
    if idx.is_empty() {
        return Err(empty());
    }
    for (i, &k) in idx.iter().enumerate() {
        if k >= space.len() {
            return Err(Error::UnknownKey {
                key: k.to_string(),
                available: (0..space.len()).map(|i| i.to_string()).collect(),
            });
        }
        if idx[..i].contains(&k) {
            return Err(Error::invalid_argument(
                "filter_keys",
                format!("duplicate index {k}"),
            ));
        }
    }
    Ok(idx.clone())
}

impl FilterableSpace for DictSpace {
    fn filter_space(&self, keys: &FilterKeys) -> Result<Self> {
        let names = check_names(self, keys)?;
        let parts = names
            .iter()
            .map(|k| (k.clone(), self.get(k).cloned().expect("checked")));
        Ok(DictSpace::sorted(parts)?)
    }

    fn select_space(&self, keys: &FilterKeys) -> Result<Self> {
        Ok(self.select(&check_names(self, keys)?)?)
    }

    fn filter_element(
        &self,
        keys: &FilterKeys,
        filtered: &Self,
        mut x: DictValue,
    ) -> Result<DictValue> {
        let mut out = DictValue::with_capacity(filtered.len());
        for k in filtered.keys() {
            let v = x.swap_remove(k).ok_or_else(|| missing(keys, &x))?;
            out.insert(k.to_owned(), v);
        }
        Ok(out)
    }

    fn filter_element_into(
        &self,
        keys: &FilterKeys,
        filtered: &Self,
        x: &DictValue,
        out: &mut DictValue,
    ) -> Result<()> {
        if out.len() != filtered.len() || !out.keys().eq(filtered.keys()) {
            *out = filtered
                .keys()
                .map(|k| {
                    Ok((
                        k.to_owned(),
                        x.get(k).ok_or_else(|| missing(keys, x))?.clone(),
                    ))
                })
                .collect::<Result<_>>()?;
            return Ok(());
        }
        for (k, v) in out.iter_mut() {
            v.assign_from(x.get(k).ok_or_else(|| missing(keys, x))?);
        }
        Ok(())
    }

    fn element_part<'a>(&self, x: &'a DictValue, i: usize) -> Option<&'a Value> {
        let key = self.keys().nth(i)?;
        match x.get_index(i) {
            Some((k, v)) if k == key => Some(v),
            _ => x.get(key),
        }
    }
}

/// A dict observation that lacks a selected key.
fn missing(keys: &FilterKeys, x: &DictValue) -> Error {
    let expected = match keys {
        FilterKeys::Names(names) => names.clone(),
        FilterKeys::Indices(_) => Vec::new(),
    };
    SpaceError::KeyMismatch {
        expected,
        got: x.keys().cloned().collect(),
    }
    .into()
}

impl FilterableSpace for TupleSpace {
    fn filter_space(&self, keys: &FilterKeys) -> Result<Self> {
        let idx = check_indices(self, keys)?;
        Ok(TupleSpace::new(
            idx.iter().map(|&i| self.spaces()[i].clone()).collect(),
        ))
    }

    fn select_space(&self, keys: &FilterKeys) -> Result<Self> {
        self.filter_space(keys)
    }

    fn filter_element(
        &self,
        keys: &FilterKeys,
        _filtered: &Self,
        x: Vec<Value>,
    ) -> Result<Vec<Value>> {
        let FilterKeys::Indices(idx) = keys else {
            return Err(empty());
        };
        let n = x.len();
        let mut slots: Vec<Option<Value>> = x.into_iter().map(Some).collect();
        idx.iter()
            .map(|&i| {
                slots.get_mut(i).and_then(Option::take).ok_or_else(|| {
                    SpaceError::InvalidArgument(format!(
                        "tuple observation of {n} items has no item {i}"
                    ))
                    .into()
                })
            })
            .collect()
    }

    fn element_part<'a>(&self, x: &'a Vec<Value>, i: usize) -> Option<&'a Value> {
        x.get(i)
    }
}

fn not_filterable(space: &AnySpace) -> Error {
    Error::invalid_argument(
        "env",
        format!(
            "FilterObservation is only usable with Dict and Tuple observations, got {}",
            space.kind()
        ),
    )
}

/// Delegates to the Dict or Tuple inside.
impl FilterableSpace for AnySpace {
    fn filter_space(&self, keys: &FilterKeys) -> Result<Self> {
        match self {
            AnySpace::Dict(d) => Ok(d.filter_space(keys)?.into()),
            AnySpace::Tuple(t) => Ok(t.filter_space(keys)?.into()),
            other => Err(not_filterable(other)),
        }
    }

    fn select_space(&self, keys: &FilterKeys) -> Result<Self> {
        match self {
            AnySpace::Dict(d) => Ok(d.select_space(keys)?.into()),
            AnySpace::Tuple(t) => Ok(t.select_space(keys)?.into()),
            other => Err(not_filterable(other)),
        }
    }

    fn filter_element(&self, keys: &FilterKeys, filtered: &Self, x: Value) -> Result<Value> {
        match (self, filtered, x) {
            (AnySpace::Dict(d), AnySpace::Dict(f), Value::Dict(v)) => {
                Ok(Value::Dict(d.filter_element(keys, f, v)?))
            }
            (AnySpace::Tuple(t), AnySpace::Tuple(f), Value::Tuple(v)) => {
                Ok(Value::Tuple(t.filter_element(keys, f, v)?))
            }
            (_, _, v) => Err(SpaceError::WrongKind {
                expected: "dict or tuple",
                got: v.kind(),
            }
            .into()),
        }
    }

    fn filter_element_into(
        &self,
        keys: &FilterKeys,
        filtered: &Self,
        x: &Value,
        out: &mut Value,
    ) -> Result<()> {
        match (self, filtered, x, out) {
            (AnySpace::Dict(d), AnySpace::Dict(f), Value::Dict(v), Value::Dict(o)) => {
                d.filter_element_into(keys, f, v, o)
            }
            (_, _, x, out) => {
                *out = self.filter_element(keys, filtered, x.clone())?;
                Ok(())
            }
        }
    }

    fn element_part<'a>(&self, x: &'a Value, i: usize) -> Option<&'a Value> {
        match (self, x) {
            (AnySpace::Dict(d), Value::Dict(v)) => d.element_part(v, i),
            (AnySpace::Tuple(t), Value::Tuple(v)) => t.element_part(v, i),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spaces::{BoxSpace, Discrete};

    #[test]
    fn element_part_by_position_with_name_fallback() {
        let space = DictSpace::new([
            ("b", AnySpace::from(BoxSpace::<f32>::unbounded(&[1]))),
            ("a", Discrete::new(3).unwrap().into()),
        ])
        .unwrap();
        let b = Value::from(ndarray::arr1(&[1.0f32]).into_dyn());
        let ordered: DictValue = [
            ("b".to_owned(), b.clone()),
            ("a".to_owned(), Value::Discrete(2)),
        ]
        .into_iter()
        .collect();
        let shuffled: DictValue = [
            ("a".to_owned(), Value::Discrete(2)),
            ("b".to_owned(), b.clone()),
        ]
        .into_iter()
        .collect();
        for x in [&ordered, &shuffled] {
            assert_eq!(space.element_part(x, 0), Some(&b));
            assert_eq!(space.element_part(x, 1), Some(&Value::Discrete(2)));
            assert_eq!(space.element_part(x, 2), None);
        }
        let any = AnySpace::from(space);
        assert_eq!(
            any.element_part(&Value::Dict(shuffled), 1),
            Some(&Value::Discrete(2))
        );
        assert_eq!(any.element_part(&Value::Discrete(0), 0), None);
        let tuple = TupleSpace::new(vec![Discrete::new(2).unwrap().into()]);
        let items = vec![Value::Discrete(1)];
        assert_eq!(tuple.element_part(&items, 0), Some(&Value::Discrete(1)));
        assert_eq!(
            AnySpace::from(tuple).element_part(&Value::Tuple(items), 0),
            Some(&Value::Discrete(1))
        );
    }
}
