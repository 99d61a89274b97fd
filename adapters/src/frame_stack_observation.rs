//! [`FrameStackObservation`]: the last `stack_size` observations, stacked.

use crate::batch::{BatchOf, BatchSpace};
use gym_core::{Env, Error, ObservationWrapper, Observations, Result, Space, Wrapper};

/// How the stack is filled after a reset (Gymnasium's `padding_type`).
#[derive(Debug, Clone, PartialEq)]
pub enum Padding<O> {
    /// Copies of the reset observation (`"reset"`, the default).
    Reset,
    /// The observation closest to zero (`"zero"`, `create_zero_array`).
    Zero,
    /// A given observation, which must lie in the observation space.
    Custom(O),
}

/// Gymnasium's `FrameStackObservation(env, stack_size, padding_type)`.
///
/// The observation space is `batch_space(env.observation_space, stack_size)` (a Box gains
/// a leading axis, a Discrete becomes a MultiDiscrete, ...). `reset` fills the stack with
/// `stack_size - 1` padding observations followed by the reset observation; each step drops
/// the oldest and appends the new one.
///
/// An observation wrapper ([`ObservationWrapper`], with
/// [`ObservationWrapper::reset_observation`] refilling the stack): the frames live in one
/// batch used as a ring, and [`Env::step_into`] keeps the inner
/// observation between steps and writes the stack into the caller's observation in place,
/// so a loop of `step_into` over array observations allocates nothing after its first
/// step. `step` and `reset` return a fresh stack.
#[derive(Debug, Clone)]
pub struct FrameStackObservation<E: Env>
where
    E::ObsSpace: BatchSpace,
{
    env: E,
    stack_size: usize,
    padding: Padding<E::Obs>,
    padding_value: E::Obs,
    /// The last `stack_size` observations, item `(head + i) % stack_size` the `i`-th oldest.
    frames: BatchOf<E::ObsSpace>,
    head: usize,
    /// One frame read out of `frames` on its way to the caller's stack.
    scratch: E::Obs,
    kept: Option<E::Obs>,
    space: <E::ObsSpace as BatchSpace>::Batched,
}

impl<E: Env> FrameStackObservation<E>
where
    E::ObsSpace: BatchSpace,
{
    /// Wraps `env`, stacking `stack_size` observations with the given padding.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when `stack_size == 0` or a custom padding observation is
    /// not in the observation space.
    pub fn new(env: E, stack_size: usize, padding: Padding<E::Obs>) -> Result<Self> {
        if stack_size == 0 {
            return Err(Error::invalid_argument(
                "stack_size",
                "must be greater than 0, got 0",
            ));
        }
        let single = env.observation_space();
        let padding_value = match &padding {
            Padding::Custom(o) if !single.contains(o) => {
                return Err(Error::invalid_argument(
                    "padding",
                    "the custom padding observation is not in the observation space",
                ));
            }
            Padding::Custom(o) => o.clone(),
            Padding::Reset | Padding::Zero => single.zero_element(),
        };
        let space = single.batch_space(stack_size)?;
        let mut frames = single.create_empty_batch(stack_size);
        for i in 0..stack_size {
            single.write_item(&mut frames, i, &padding_value)?;
        }
        Ok(Self {
            scratch: padding_value.clone(),
            env,
            stack_size,
            padding,
            padding_value,
            frames,
            head: 0,
            kept: None,
            space,
        })
    }

    /// The number of stacked observations.
    pub fn stack_size(&self) -> usize {
        self.stack_size
    }

    /// Drops the oldest frame and appends `obs`, in place.
    fn push(&mut self, obs: &E::Obs) -> Result<()> {
        let single = self.env.observation_space();
        single.write_item(&mut self.frames, self.head, obs)?;
        self.head = (self.head + 1) % self.stack_size;
        Ok(())
    }

    /// Writes the frames, oldest first, into `out`.
    fn write_stack(&mut self, out: &mut BatchOf<E::ObsSpace>) -> Result<()> {
        let single = self.env.observation_space();
        for i in 0..self.stack_size {
            let j = (self.head + i) % self.stack_size;
            single.read_item_into(&self.frames, j, &mut self.scratch)?;
            single.write_item(out, i, &self.scratch)?;
        }
        Ok(())
    }

    /// The frames, oldest first, as a new batch.
    fn stacked(&mut self) -> Result<BatchOf<E::ObsSpace>> {
        let mut batch = self
            .env
            .observation_space()
            .create_empty_batch(self.stack_size);
        self.write_stack(&mut batch)?;
        Ok(batch)
    }
}

impl<E: Env> Wrapper for FrameStackObservation<E>
where
    E::ObsSpace: BatchSpace,
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

impl<E: Env> ObservationWrapper for FrameStackObservation<E>
where
    E::ObsSpace: BatchSpace,
{
    type Space = <E::ObsSpace as BatchSpace>::Batched;

    fn space(&self) -> &Self::Space {
        &self.space
    }

    fn reset_observation(&mut self, observation: E::Obs) -> Result<BatchOf<E::ObsSpace>> {
        if matches!(self.padding, Padding::Reset) {
            self.padding_value = observation.clone();
        }
        let single = self.env.observation_space();
        for i in 0..self.stack_size - 1 {
            single.write_item(&mut self.frames, i, &self.padding_value)?;
        }
        single.write_item(&mut self.frames, self.stack_size - 1, &observation)?;
        self.head = 0;
        self.stacked()
    }

    fn observation(&mut self, observation: E::Obs) -> Result<BatchOf<E::ObsSpace>> {
        self.push(&observation)?;
        self.stacked()
    }

    fn observation_into(
        &mut self,
        observation: &E::Obs,
        out: &mut BatchOf<E::ObsSpace>,
    ) -> Result<()> {
        self.push(observation)?;
        if self.write_stack(out).is_err() {
            // `out` is not a stack of this space's layout (a caller's fresh buffer).
            *out = self.stacked()?;
        }
        Ok(())
    }

    fn inner_buffer(&mut self) -> Option<&mut Option<E::Obs>> {
        Some(&mut self.kept)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{CountEnv, DiscreteEnv, a64};
    use ndarray::{arr1, arr2};

    #[test]
    fn reset_padding_then_rolls() {
        let mut env =
            FrameStackObservation::new(CountEnv::new(None, None), 3, Padding::Reset).unwrap();
        assert_eq!(env.observation_space().shape(), Some(&[3usize, 1][..]));
        let (obs, _) = env.reset(None, None).unwrap();
        assert_eq!(obs, arr2(&[[0.0], [0.0], [0.0]]).into_dyn());
        let _ = env.step(&0).unwrap();
        let s = env.step(&0).unwrap();
        assert_eq!(s.observation, arr2(&[[0.0], [1.0], [2.0]]).into_dyn());
        let s = env.step(&0).unwrap();
        assert_eq!(s.observation, arr2(&[[1.0], [2.0], [3.0]]).into_dyn());
        assert!(env.observation_space().contains(&s.observation));
    }

    #[test]
    fn zero_and_custom_padding() {
        // CountEnv's Box is [0, 1000]: zero padding is 0. Custom padding 7.
        let mut env =
            FrameStackObservation::new(CountEnv::new(None, None), 2, Padding::Custom(a64(&[7.0])))
                .unwrap();
        env.reset(None, None).unwrap();
        assert_eq!(
            env.reset(None, None).unwrap().0,
            arr2(&[[7.0], [0.0]]).into_dyn()
        );
        let mut d = FrameStackObservation::new(DiscreteEnv::new(), 3, Padding::Zero).unwrap();
        assert_eq!(
            d.observation_space().nvec(),
            &arr1(&[5i64, 5, 5]).into_dyn()
        );
        assert_eq!(
            d.reset(None, None).unwrap().0,
            arr1(&[0i64, 0, 2]).into_dyn()
        );
        assert_eq!(
            d.step(&1).unwrap().observation,
            arr1(&[0i64, 2, 3]).into_dyn()
        );
        assert!(FrameStackObservation::new(CountEnv::new(None, None), 0, Padding::Reset).is_err());
        assert!(
            FrameStackObservation::new(CountEnv::new(None, None), 2, Padding::Custom(a64(&[-1.0])))
                .is_err()
        );
    }

    #[test]
    fn step_into_equals_step_and_reset_refills() {
        use crate::toy::a32;
        let make =
            || FrameStackObservation::new(crate::toy::WalkEnv::new(6), 3, Padding::Reset).unwrap();
        let (mut by_step, mut by_into) = (make(), make());
        for seed in [1, 2] {
            let (first, _) = by_step.reset(Some(seed), None).unwrap();
            let (mut obs, mut info) = by_into.reset(Some(seed), None).unwrap();
            assert_eq!(first, obs);
            assert_eq!(
                first.index_axis(ndarray::Axis(0), 0),
                first.index_axis(ndarray::Axis(0), 2)
            );
            for k in 0..4 {
                let a = a32(&[0.5, -0.25 * k as f32]);
                let step = by_step.step(&a).unwrap();
                let t = by_into.step_into(&a, &mut obs, &mut info).unwrap();
                assert_eq!(step.observation, obs, "seed {seed}, step {k}");
                assert_eq!(step.info, info);
                assert_eq!(
                    (step.reward, step.terminated, step.truncated),
                    (t.reward, t.terminated, t.truncated)
                );
                assert!(by_into.observation_space().contains(&obs));
            }
        }
        // A buffer of another layout is replaced by the stack.
        let mut odd = ndarray::ArrayD::zeros(ndarray::IxDyn(&[1]));
        let mut info = gym_core::Info::new();
        let _ = by_into
            .step_into(&a32(&[0.0, 0.0]), &mut odd, &mut info)
            .unwrap();
        assert_eq!(odd.shape(), [3, 2]);
    }
}
