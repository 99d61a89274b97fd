//! [`FrameStackObservation`]: the last `stack_size` observations, stacked.

use crate::batch::{BatchOf, BatchSpace};
use gym_core::{Env, Error, Info, ResetOptions, Result, Space, Step};
use std::collections::VecDeque;

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
/// the oldest and appends the new one. Each returned stack is a fresh value.
#[derive(Debug, Clone)]
pub struct FrameStackObservation<E: Env>
where
    E::ObsSpace: BatchSpace,
{
    env: E,
    stack_size: usize,
    padding: Padding<E::Obs>,
    padding_value: E::Obs,
    queue: VecDeque<E::Obs>,
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
        let queue = std::iter::repeat_n(padding_value.clone(), stack_size).collect();
        Ok(Self {
            env,
            stack_size,
            padding,
            padding_value,
            queue,
            space,
        })
    }

    /// The number of stacked observations.
    pub fn stack_size(&self) -> usize {
        self.stack_size
    }

    fn stacked(&self) -> Result<BatchOf<E::ObsSpace>> {
        let single = self.env.observation_space();
        let mut batch = single.create_empty_batch(self.stack_size);
        for (i, o) in self.queue.iter().enumerate() {
            single.write_item(&mut batch, i, o)?;
        }
        Ok(batch)
    }
}

impl<E: Env> gym_core::CustomWrapper for FrameStackObservation<E>
where
    E::ObsSpace: BatchSpace,
    BatchOf<E::ObsSpace>: Send,
{
    type Observation = BatchOf<E::ObsSpace>;
    type Action = E::Act;
    type ObservationSpace = <E::ObsSpace as BatchSpace>::Batched;
    type ActionSpace = E::ActSpace;

    fn observation_space(this: &Self) -> &Self::ObservationSpace {
        &this.space
    }

    fn action_space(this: &Self) -> &E::ActSpace {
        this.env.action_space()
    }

    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Self::Observation, Info)> {
        let (obs, info) = this.env.reset(seed, options)?;
        if matches!(this.padding, Padding::Reset) {
            this.padding_value = obs.clone();
        }
        this.queue.clear();
        this.queue.extend(std::iter::repeat_n(
            this.padding_value.clone(),
            this.stack_size - 1,
        ));
        this.queue.push_back(obs);
        Ok((this.stacked()?, info))
    }

    fn step(this: &mut Self, action: &E::Act) -> Result<Step<Self::Observation>> {
        let step = this.env.step(action)?;
        if this.queue.len() == this.stack_size {
            this.queue.pop_front();
        }
        this.queue.push_back(step.observation.clone());
        let stacked = this.stacked()?;
        Ok(step.map_observation(|_| stacked))
    }
}

impl<E: Env> gym_core::Wrapper for FrameStackObservation<E>
where
    E::ObsSpace: BatchSpace,
    BatchOf<E::ObsSpace>: Send,
{
    type Inner = E;
    type Kind = gym_core::Custom;
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
}
