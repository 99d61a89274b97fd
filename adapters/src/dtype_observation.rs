//! [`DtypeObservation`]: observations cast to another dtype.

use crate::numeric::NumericSpace;
use gym_core::spaces::BoxSpace;
use gym_core::{ArrayElement, Env, ObservationWrapper, Observations, Result, Wrapper};
use ndarray::ArrayD;
use std::marker::PhantomData;

/// Gymnasium's `DtypeObservation(env, dtype)` for a Box, Discrete, MultiDiscrete or
/// MultiBinary observation space; `U` is the new element type.
///
/// | inner space | new space |
/// |---|---|
/// | `Box` | the same bounds with dtype `U` |
/// | `Discrete(n, start)` | `Box(start, start + n - 1, shape = (), U)` |
/// | `MultiDiscrete(nvec, start)` | `Box(start, start + nvec - 1, U)` (Gymnasium keeps a `MultiDiscrete` with dtype `U`; gym-core's MultiDiscrete is `int64`-only, so the same set is described by a Box) |
/// | `MultiBinary` | `Box(0, 1, shape, U)` |
///
/// Observations are cast with Rust `as` semantics (NumPy's `astype`, saturating instead of
/// wrapping for out-of-range integers). [`Env::step_into`] keeps the inner observation
/// between steps and casts it into the caller's array, allocating nothing.
#[derive(Debug, Clone)]
pub struct DtypeObservation<E: Env, U: ArrayElement> {
    env: E,
    space: BoxSpace<U>,
    kept: Option<E::Obs>,
    _dtype: PhantomData<fn() -> U>,
}

impl<E: Env, U: ArrayElement> DtypeObservation<E, U>
where
    E::ObsSpace: NumericSpace,
{
    /// Wraps `env`.
    ///
    /// # Errors
    /// [`gym_core::Error::InvalidArgument`] for a Dict or Tuple space; a space error when a
    /// finite bound does not fit `U`.
    pub fn new(env: E) -> Result<Self> {
        let spec = env.observation_space().array_spec()?;
        let space = BoxSpace::<U>::new(spec.low, spec.high)?;
        Ok(Self {
            env,
            space,
            kept: None,
            _dtype: PhantomData,
        })
    }
}

impl<E: Env, U: ArrayElement> Wrapper for DtypeObservation<E, U>
where
    E::ObsSpace: NumericSpace,
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

impl<E: Env, U: ArrayElement> ObservationWrapper for DtypeObservation<E, U>
where
    E::ObsSpace: NumericSpace,
{
    type Space = BoxSpace<U>;

    fn space(&self) -> &BoxSpace<U> {
        &self.space
    }

    fn observation(&mut self, observation: E::Obs) -> Result<ArrayD<U>> {
        self.env.observation_space().element_to_array(&observation)
    }

    fn observation_into(&mut self, observation: &E::Obs, out: &mut ArrayD<U>) -> Result<()> {
        self.env
            .observation_space()
            .element_to_array_into(observation, out)
    }

    fn inner_buffer(&mut self) -> Option<&mut Option<E::Obs>> {
        Some(&mut self.kept)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{DiscreteEnv, ScriptEnv, WalkEnv, a32, unit_actions};
    use gym_core::spaces::{MultiBinary, MultiDiscrete};
    use gym_core::{DType, Space};
    use ndarray::arr1;

    #[test]
    fn box_changes_dtype_keeping_bounds() {
        let mut env = DtypeObservation::<_, f64>::new(WalkEnv::new(5)).unwrap();
        assert_eq!(
            env.observation_space().to_string(),
            "Box(-inf, inf, [2], float64)"
        );
        let (obs, _) = env.reset(Some(0), None).unwrap();
        let s = env.step(&a32(&[1.0, 1.0])).unwrap();
        assert!(env.observation_space().contains(&obs) && s.observation.len() == 2);
    }

    #[test]
    fn discrete_becomes_scalar_box() {
        let mut env = DtypeObservation::<_, f32>::new(DiscreteEnv::new()).unwrap();
        assert_eq!(
            env.observation_space().to_string(),
            "Box(0, 4, [], float32)"
        );
        assert_eq!(env.reset(None, None).unwrap().0[[]], 2.0f32);
        assert_eq!(env.step(&0).unwrap().observation[[]], 1.0f32);
    }

    #[test]
    fn multi_discrete_and_multi_binary() {
        let md =
            MultiDiscrete::with_start(arr1(&[3, 2]).into_dyn(), arr1(&[1, 0]).into_dyn()).unwrap();
        let inner = ScriptEnv::new(
            md,
            unit_actions(),
            vec![arr1(&[3i64, 1]).into_dyn()],
            vec![0.0],
        );
        let mut env = DtypeObservation::<_, u8>::new(inner).unwrap();
        assert_eq!(env.observation_space().high(), &arr1(&[3u8, 1]).into_dyn());
        assert_eq!(env.reset(None, None).unwrap().0, arr1(&[3u8, 1]).into_dyn());
        let mb = MultiBinary::new(&[2]).unwrap();
        let inner = ScriptEnv::new(
            mb,
            unit_actions(),
            vec![arr1(&[1i8, 0]).into_dyn()],
            vec![0.0],
        );
        let env = DtypeObservation::<_, f64>::new(inner).unwrap();
        assert_eq!(env.observation_space().dtype(), DType::F64);
        assert_eq!(
            env.observation_space().to_string(),
            "Box(0, 1, [2], float64)"
        );
    }
}
