//! [`FilterObservation`]: keeps some keys of a Dict observation or some items of a Tuple.

use gym_core::spaces::AnySpace;
use gym_core::spaces::{FilterKeys, FilterableSpace};
use gym_core::{DynSpace, Env, ObservationWrapper, Observations, Pick, Result, Wrapper};

/// Gymnasium's `FilterObservation(env, filter_keys)`: keeps the listed Dict keys (the new
/// Dict space is sorted by key, as Gymnasium's is; [`FilterObservation::keeping_order`]
/// keeps the listed order) or Tuple indices (in the order listed). Missing keys, duplicates
/// and an empty selection are errors at construction.
///
/// [`Env::step_into`] keeps the inner observation between steps and copies the kept
/// entries into the caller's observation, so a loop of `step_into` allocates nothing.
#[derive(Debug, Clone)]
pub struct FilterObservation<E: Env> {
    env: E,
    keys: FilterKeys,
    space: E::ObsSpace,
    kept: Option<E::Obs>,
    /// Where each inner Dict entry goes in a row of the filtered observations (a Dict of
    /// arrays only).
    plan: Option<Vec<Pick>>,
}

/// The row plan of a Dict of arrays filtered to `outer`: each inner entry's position among
/// the kept entries, or [`Pick::Absent`].
fn filter_plan(inner: &AnySpace, outer: &AnySpace) -> Option<Vec<Pick>> {
    let (inner, outer) = (inner.as_dict()?, outer.as_dict()?);
    inner
        .iter()
        .map(|(k, s)| {
            matches!(
                s,
                AnySpace::Box(_) | AnySpace::MultiBinary(_) | AnySpace::MultiDiscrete(_)
            )
            .then(|| {
                outer
                    .keys()
                    .position(|o| o == k)
                    .map_or(Pick::Absent, Pick::Leaf)
            })
        })
        .collect()
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
        let plan = filter_plan(&env.observation_space().to_any(), &space.to_any());
        Ok(Self {
            env,
            keys,
            space,
            kept: None,
            plan,
        })
    }

    /// Wraps `env`, keeping `keys` in the listed order (Dict keys are not sorted).
    ///
    /// # Errors
    /// As [`FilterableSpace::select_space`].
    pub fn keeping_order(env: E, keys: impl Into<FilterKeys>) -> Result<Self> {
        let keys = keys.into();
        let space = env.observation_space().select_space(&keys)?;
        let plan = filter_plan(&env.observation_space().to_any(), &space.to_any());
        Ok(Self {
            env,
            keys,
            space,
            kept: None,
            plan,
        })
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
            .filter_element(&self.keys, &self.space, observation)
    }

    fn observation_into(&mut self, observation: &E::Obs, out: &mut E::Obs) -> Result<()> {
        self.env
            .observation_space()
            .filter_element_into(&self.keys, &self.space, observation, out)
    }

    fn inner_buffer(&mut self) -> Option<&mut Option<E::Obs>> {
        Some(&mut self.kept)
    }

    fn row_plan(&self) -> Option<&[Pick]> {
        self.plan.as_deref()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{DictEnv, ScriptEnv, a64, unit_actions};
    use gym_core::spaces::{BoxSpace, Discrete, TupleSpace};
    use gym_core::{Error, Space, Value};

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
