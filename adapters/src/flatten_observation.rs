//! [`FlattenObservation`]: observations flattened to one dimension (Gymnasium's
//! `flatten` / `flatten_space`).

use gym_core::spaces::AnyBox;
use gym_core::{ArrayValue, Env, Info, ResetOptions, Result, Space, Step};

/// Gymnasium's `FlattenObservation`: the observation space becomes
/// `flatten_space(env.observation_space)` and each observation `flatten(space, obs)`.
///
/// The dtypes follow Gymnasium: a Discrete space flattens to an `int64` one-hot, a Dict
/// concatenates its parts in key order with NumPy's type promotion (so `float32` and
/// `float64` parts give `float64`). Observations are [`ArrayValue`]s of the flat Box's
/// dtype; the space is the dynamic [`AnyBox`].
#[derive(Debug, Clone)]
pub struct FlattenObservation<E> {
    env: E,
    space: AnyBox,
}

impl<E: Env> FlattenObservation<E> {
    /// Wraps `env`.
    pub fn new(env: E) -> Self {
        let space = env.observation_space().flatten_space();
        Self { env, space }
    }
}

impl<E: Env> Env for FlattenObservation<E> {
    type Obs = ArrayValue;
    type Act = E::Act;
    type ObsSpace = AnyBox;
    type ActSpace = E::ActSpace;

    fn observation_space(&self) -> &AnyBox {
        &self.space
    }

    fn action_space(&self) -> &E::ActSpace {
        self.env.action_space()
    }

    fn reset(
        &mut self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(ArrayValue, Info)> {
        let (obs, info) = self.env.reset(seed, options)?;
        Ok((self.env.observation_space().flatten(&obs)?, info))
    }

    fn step(&mut self, action: &E::Act) -> Result<Step<ArrayValue>> {
        let step = self.env.step(action)?;
        let space = self.env.observation_space();
        Ok(step.try_map_observation(|o| space.flatten(&o))?)
    }

    gym_core::forward_env!();
}

impl_wrapper!(FlattenObservation);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{DictEnv, DiscreteEnv, a64};
    use gym_core::DType;

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
