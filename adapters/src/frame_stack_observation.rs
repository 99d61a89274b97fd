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

impl<E: Env> Env for FrameStackObservation<E>
where
    E::ObsSpace: BatchSpace,
    BatchOf<E::ObsSpace>: Send,
{
    type Obs = BatchOf<E::ObsSpace>;
    type Act = E::Act;
    type ObsSpace = <E::ObsSpace as BatchSpace>::Batched;
    type ActSpace = E::ActSpace;

    fn observation_space(&self) -> &Self::ObsSpace {
        &self.space
    }

    fn action_space(&self) -> &E::ActSpace {
        self.env.action_space()
    }

    fn reset(
        &mut self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Self::Obs, Info)> {
        let (obs, info) = self.env.reset(seed, options)?;
        if matches!(self.padding, Padding::Reset) {
            self.padding_value = obs.clone();
        }
        self.queue.clear();
        self.queue.extend(std::iter::repeat_n(
            self.padding_value.clone(),
            self.stack_size - 1,
        ));
        self.queue.push_back(obs);
        Ok((self.stacked()?, info))
    }

    fn step(&mut self, action: &E::Act) -> Result<Step<Self::Obs>> {
        let step = self.env.step(action)?;
        if self.queue.len() == self.stack_size {
            self.queue.pop_front();
        }
        self.queue.push_back(step.observation.clone());
        let stacked = self.stacked()?;
        Ok(step.map_observation(|_| stacked))
    }

    gym_core::forward_env!();
}

impl_wrapper!(FrameStackObservation; where E::ObsSpace: BatchSpace);

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
