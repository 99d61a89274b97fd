//! [`FlattenObservation`]: observations flattened to one dimension (Gymnasium's
//! `flatten` / `flatten_space`).

use gym_core::spaces::AnyBox;
use gym_core::{ArrayValue, Env, Flatten, ObservationWrapper, Observations, Result, Wrapper};

/// Gymnasium's `FlattenObservation`: the observation space becomes
/// `flatten_space(env.observation_space)` and each observation `flatten(space, obs)`.
///
/// The dtypes follow Gymnasium: a Discrete space flattens to an `int64` one-hot, a Dict
/// concatenates its parts in key order with NumPy's type promotion (so `float32` and
/// `float64` parts give `float64`). Observations are [`ArrayValue`]s of the flat Box's
/// dtype; the space is the dynamic [`AnyBox`].
///
/// [`Env::step_into`] keeps the inner observation between steps and flattens it into the
/// caller's array ([`gym_core::Flatten::flatten_into`]: Box and Dict-of-Box observations
/// then allocate nothing).
#[derive(Debug, Clone)]
pub struct FlattenObservation<E: Env> {
    env: E,
    space: AnyBox,
    kept: Option<E::Obs>,
}

impl<E: Env> FlattenObservation<E> {
    /// Wraps `env`.
    pub fn new(env: E) -> Self {
        let space = gym_core::flatten_space(env.observation_space());
        Self {
            env,
            space,
            kept: None,
        }
    }
}

impl<E: Env> Wrapper for FlattenObservation<E> {
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

impl<E: Env> ObservationWrapper for FlattenObservation<E> {
    type Space = AnyBox;

    fn space(&self) -> &AnyBox {
        &self.space
    }

    fn observation(&mut self, observation: E::Obs) -> Result<ArrayValue> {
        Ok(gym_core::flatten(
            self.env.observation_space(),
            &observation,
        )?)
    }

    fn observation_into(&mut self, observation: &E::Obs, out: &mut ArrayValue) -> Result<()> {
        Ok(self
            .env
            .observation_space()
            .flatten_into(observation, out)?)
    }

    fn inner_buffer(&mut self) -> Option<&mut Option<E::Obs>> {
        Some(&mut self.kept)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{DictEnv, DiscreteEnv, a64};
    use gym_core::{DType, Space};

    #[test]
    fn discrete_becomes_int64_one_hot() {
        let mut env = FlattenObservation::new(DiscreteEnv::new());
        assert_eq!(env.observation_space().to_string(), "Box(0, 1, [5], int64)");
        let (obs, _) = env.reset(None, None).unwrap();
        assert_eq!(obs.dtype(), DType::I64);
        assert_eq!(obs.to_f64_vec(), vec![0.0, 0.0, 1.0, 0.0, 0.0]);
        assert_eq!(
            env.step(&1).unwrap().observation.to_f64_vec(),
            vec![0.0, 0.0, 0.0, 1.0, 0.0]
        );
    }

    #[test]
    fn dict_concatenates_in_key_order_with_promotion() {
        let mut env = FlattenObservation::new(DictEnv::new(10, false));
        assert_eq!(env.observation_space().dtype(), DType::F64);
        assert_eq!(env.observation_space().shape(), Some(&[11usize][..]));
        let (obs, _) = env.reset(Some(3), None).unwrap();
        let step = env.step(&a64(&[0.5, 0.0, 0.0])).unwrap();
        let v = step.observation.to_f64_vec();
        // robot0_joint_pos[1] is t; the f32 quat part comes last.
        assert_eq!(v[1], 1.0);
        assert_eq!(&v[9..], &[0.5, -0.25]);
        assert!(env.observation_space().contains(&obs));
    }
}
