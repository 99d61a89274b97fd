//! [`FilterObservation`]: keeps some keys of a Dict observation or some items of a Tuple.

use gym_core::spaces::{AnySpace, DictSpace, TupleSpace};
use gym_core::{
    DictValue, Env, Error, ObservationWrapper, Observations, Result, Space, SpaceError, Value,
    Wrapper,
};

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

/// A space that [`FilterObservation`] can filter: Dict, Tuple, or a dynamic space holding
/// one of them.
pub trait FilterableSpace: Space {
    /// The filtered space.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an empty selection, a duplicate, keys of the wrong
    /// kind or a space that is neither a Dict nor a Tuple; [`Error::UnknownKey`] for a
    /// missing Dict key or Tuple index.
    fn filter_space(&self, keys: &FilterKeys) -> Result<Self>;

    /// Keeps the selected parts of an element, in the filtered space's order.
    ///
    /// # Errors
    /// When the element lacks a selected part.
    fn filter_element(&self, keys: &FilterKeys, x: Self::Element) -> Result<Self::Element>;
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
    /// A Dict of the selected keys, **sorted** by key: Gymnasium builds the new space from a
    /// plain `dict`, which `Dict` sorts.
    fn filter_space(&self, keys: &FilterKeys) -> Result<Self> {
        let names = check_names(self, keys)?;
        let parts = names
            .iter()
            .map(|k| (k.clone(), self.get(k).cloned().expect("checked")));
        Ok(DictSpace::sorted(parts)?)
    }

    fn filter_element(&self, keys: &FilterKeys, mut x: DictValue) -> Result<DictValue> {
        let FilterKeys::Names(names) = keys else {
            return Err(empty());
        };
        let mut sorted: Vec<&String> = names.iter().collect();
        sorted.sort();
        let mut out = DictValue::with_capacity(sorted.len());
        for k in sorted {
            let v = x
                .swap_remove(k.as_str())
                .ok_or_else(|| SpaceError::KeyMismatch {
                    expected: names.clone(),
                    got: x.keys().cloned().collect(),
                })?;
            out.insert(k.clone(), v);
        }
        Ok(out)
    }
}

impl FilterableSpace for TupleSpace {
    fn filter_space(&self, keys: &FilterKeys) -> Result<Self> {
        let idx = check_indices(self, keys)?;
        Ok(TupleSpace::new(
            idx.iter().map(|&i| self.spaces()[i].clone()).collect(),
        ))
    }

    fn filter_element(&self, keys: &FilterKeys, x: Vec<Value>) -> Result<Vec<Value>> {
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
}

impl FilterableSpace for AnySpace {
    fn filter_space(&self, keys: &FilterKeys) -> Result<Self> {
        match self {
            AnySpace::Dict(d) => Ok(AnySpace::Dict(d.filter_space(keys)?)),
            AnySpace::Tuple(t) => Ok(AnySpace::Tuple(t.filter_space(keys)?)),
            other => Err(Error::invalid_argument(
                "env",
                format!(
                    "FilterObservation is only usable with Dict and Tuple observations, got {}",
                    other.kind()
                ),
            )),
        }
    }

    fn filter_element(&self, keys: &FilterKeys, x: Value) -> Result<Value> {
        match (self, x) {
            (AnySpace::Dict(d), Value::Dict(v)) => Ok(Value::Dict(d.filter_element(keys, v)?)),
            (AnySpace::Tuple(t), Value::Tuple(v)) => Ok(Value::Tuple(t.filter_element(keys, v)?)),
            (_, v) => Err(SpaceError::WrongKind {
                expected: "dict or tuple",
                got: v.kind(),
            }
            .into()),
        }
    }
}

/// Gymnasium's `FilterObservation(env, filter_keys)`: keeps the listed Dict keys (the new
/// Dict space is sorted by key, as Gymnasium's is) or Tuple indices (in the order listed).
/// Missing keys, duplicates and an empty selection are errors at construction.
#[derive(Debug, Clone)]
pub struct FilterObservation<E: Env> {
    env: E,
    keys: FilterKeys,
    space: E::ObsSpace,
}

impl<E: Env> FilterObservation<E>
where
    E::ObsSpace: FilterableSpace,
{
    /// Wraps `env`, keeping `keys`.
    ///
    /// # Errors
    /// As [`FilterableSpace::filter_space`].
    pub fn new(env: E, keys: impl Into<FilterKeys>) -> Result<Self> {
        let keys = keys.into();
        let space = env.observation_space().filter_space(&keys)?;
        Ok(Self { env, keys, space })
    }

    /// The kept keys or indices.
    pub fn filter_keys(&self) -> &FilterKeys {
        &self.keys
    }
}

impl<E: Env> Wrapper for FilterObservation<E>
where
    E::ObsSpace: FilterableSpace,
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

impl<E: Env> ObservationWrapper for FilterObservation<E>
where
    E::ObsSpace: FilterableSpace,
{
    type Space = E::ObsSpace;

    fn space(&self) -> &E::ObsSpace {
        &self.space
    }

    fn observation(&mut self, observation: E::Obs) -> Result<E::Obs> {
        self.env
            .observation_space()
            .filter_element(&self.keys, observation)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{DictEnv, ScriptEnv, a64, unit_actions};
    use gym_core::spaces::{BoxSpace, Discrete};

    #[test]
    fn dict_keys_are_kept_and_sorted() {
        let mut env = FilterObservation::new(
            DictEnv::new(5, false),
            ["robot0_proprio-state", "object-state"],
        )
        .unwrap();
        let keys: Vec<&str> = env.observation_space().keys().collect();
        assert_eq!(keys, ["object-state", "robot0_proprio-state"]);
        let (obs, _) = env.reset(Some(1), None).unwrap();
        assert_eq!(
            obs.keys().collect::<Vec<_>>(),
            ["object-state", "robot0_proprio-state"]
        );
        assert!(env.observation_space().contains(&obs));
        let step = env.step(&a64(&[0.0, 0.0, 0.0])).unwrap();
        assert_eq!(
            step.observation["robot0_proprio-state"]
                .as_array()
                .unwrap()
                .to_f64_vec()[3],
            1.0
        );
    }

    #[test]
    fn tuple_indices_in_listed_order() {
        let space = TupleSpace::new(vec![
            Discrete::new(3).unwrap().into(),
            BoxSpace::<f64>::unbounded(&[1]).into(),
            Discrete::new(4).unwrap().into(),
        ]);
        let obs = vec![
            Value::Discrete(2),
            Value::from(a64(&[0.5])),
            Value::Discrete(3),
        ];
        let inner = ScriptEnv::new(space, unit_actions(), vec![obs], vec![0.0]);
        let mut env = FilterObservation::new(inner, [2usize, 0]).unwrap();
        assert_eq!(
            env.reset(None, None).unwrap().0,
            vec![Value::Discrete(3), Value::Discrete(2)]
        );
        assert_eq!(env.observation_space().len(), 2);
    }

    #[test]
    fn invalid_selections() {
        let err = FilterObservation::new(DictEnv::new(5, false), ["nope"]).unwrap_err();
        assert!(
            matches!(&err, Error::UnknownKey { key, available } if key == "nope" && available.len() == 4)
        );
        assert!(FilterObservation::new(DictEnv::new(5, false), Vec::<String>::new()).is_err());
        assert!(
            FilterObservation::new(DictEnv::new(5, false), ["object-state", "object-state"])
                .is_err()
        );
        assert!(FilterObservation::new(DictEnv::new(5, false), [0usize]).is_err());
        let any = gym_core::IntoBoxedEnv::boxed(crate::toy::DiscreteEnv::new());
        assert!(FilterObservation::new(any, [0usize]).is_err());
    }
}
