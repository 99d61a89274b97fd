//! [`TransformObservation`]: observations mapped by a closure.

use gym_core::{DynSpace, Env, Flatten, ObservationWrapper, Observations, Result, Space, Wrapper};

/// Gymnasium's `TransformObservation(env, func, observation_space)`: each observation (from
/// `reset` and `step`) becomes `func(obs)`, which must lie in the new observation space.
/// [`TransformObservation::keep_space`] keeps the inner space (Gymnasium's
/// `observation_space=None`).
pub struct TransformObservation<E, F, S> {
    env: E,
    func: F,
    space: S,
}

impl<E: Env, F, S: Space> TransformObservation<E, F, S>
where
    F: FnMut(E::Obs) -> S::Element + Send + 'static,
{
    /// Wraps `env`, mapping observations with `func` into `observation_space`.
    pub fn new(env: E, func: F, observation_space: S) -> Self {
        Self {
            env,
            func,
            space: observation_space,
        }
    }
}

impl<E: Env, F> TransformObservation<E, F, E::ObsSpace>
where
    F: FnMut(E::Obs) -> E::Obs + Send + 'static,
{
    /// Wraps `env`, mapping observations with `func` and keeping the observation space.
    pub fn keep_space(env: E, func: F) -> Self {
        let space = env.observation_space().clone();
        Self { env, func, space }
    }
}

impl<E: std::fmt::Debug, F, S: std::fmt::Debug> std::fmt::Debug for TransformObservation<E, F, S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TransformObservation")
            .field("env", &self.env)
            .field("space", &self.space)
            .finish_non_exhaustive()
    }
}

impl<E: Env, F, S: Space> Wrapper for TransformObservation<E, F, S>
where
    F: FnMut(E::Obs) -> S::Element + Send + 'static,
    S: Flatten + DynSpace,
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

impl<E: Env, F, S: Space> ObservationWrapper for TransformObservation<E, F, S>
where
    F: FnMut(E::Obs) -> S::Element + Send + 'static,
    S: Flatten + DynSpace,
{
    type Space = S;

    fn space(&self) -> &S {
        &self.space
    }

    fn observation(&mut self, observation: E::Obs) -> Result<S::Element> {
        Ok((self.func)(observation))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{CountEnv, DiscreteEnv};
    use gym_core::spaces::{BoxSpace, Discrete};
    use ndarray::ArrayD;

    #[test]
    fn maps_observations_into_a_new_space() {
        let space = BoxSpace::<f32>::uniform(0.0, 2000.0, &[1]).unwrap();
        let mut env = TransformObservation::new(
            CountEnv::new(None, None),
            |o: ArrayD<f64>| o.mapv(|v| (2.0 * v) as f32),
            space,
        );
        assert_eq!(env.reset(None, None).unwrap().0[[0]], 0.0);
        assert_eq!(env.step(&0).unwrap().observation[[0]], 2.0);
        assert_eq!(env.step(&0).unwrap().observation[[0]], 4.0);
        assert_eq!(env.observation_space().dtype(), gym_core::DType::F32);
    }

    #[test]
    fn keep_space() {
        let mut env = TransformObservation::keep_space(DiscreteEnv::new(), |o| 4 - o);
        assert_eq!(env.observation_space(), &Discrete::new(5).unwrap());
        assert_eq!(env.reset(None, None).unwrap().0, 2);
        assert_eq!(env.step(&1).unwrap().observation, 1);
    }
}
