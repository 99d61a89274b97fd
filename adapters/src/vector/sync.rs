//! [`SyncVectorEnv`]: sub-environments stepped in turn on the calling thread.

use super::core::VectorCore;
use super::delegate_to_core;
use super::slot::Slot;
use super::{AutoresetMode, Seeds, VectorEnv, VectorInfo, VectorStep};
use crate::batch::{BatchOf, BatchSpace};
use gym_core::{Env, Metadata, ResetOptions, Result};

/// Gymnasium's `SyncVectorEnv`: `n` environments with identical spaces, stepped one after
/// the other (see the [module documentation](super) for the semantics). Steps go through
/// [`Env::step_into`] into per-environment buffers, so with environments whose `step_into`
/// reuses them a step does not allocate.
#[derive(Debug)]
pub struct SyncVectorEnv<E: Env>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    envs: Vec<E>,
    slots: Vec<Slot<E>>,
    core: VectorCore<E::ObsSpace, E::ActSpace>,
}

impl<E: Env> SyncVectorEnv<E>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    /// A vector of `envs` with [`AutoresetMode::NextStep`].
    ///
    /// # Errors
    /// [`gym_core::Error::InvalidArgument`] for no environments or differing spaces.
    pub fn new(envs: Vec<E>) -> Result<Self> {
        let mut core = VectorCore::new(&envs)?;
        let slots = envs
            .iter()
            .enumerate()
            .map(|(i, e)| {
                let mut slot = Slot::new(i, e);
                core.attach_row(&mut slot, e);
                slot
            })
            .collect();
        Ok(Self { envs, slots, core })
    }

    /// `n` environments made by `make(i)`.
    ///
    /// # Errors
    /// The first error of `make`; as [`SyncVectorEnv::new`].
    pub fn from_fn(n: usize, make: impl FnMut(usize) -> Result<E>) -> Result<Self> {
        Self::new((0..n).map(make).collect::<Result<Vec<_>>>()?)
    }

    /// The same vector with another autoreset mode (set it before the first step).
    #[must_use]
    pub fn with_autoreset_mode(mut self, mode: AutoresetMode) -> Self {
        self.core.mode = mode;
        self
    }

    /// The sub-environments.
    pub fn envs(&self) -> &[E] {
        &self.envs
    }

    /// The sub-environments, mutably (changing their state bypasses the autoreset flags).
    pub fn envs_mut(&mut self) -> &mut [E] {
        &mut self.envs
    }

    fn run_reset(
        &mut self,
        seeds: Seeds,
        options: Option<&ResetOptions>,
        mask: Option<&[bool]>,
    ) -> Result<()> {
        let tasks = self.core.plan_reset(seeds, options, mask)?;
        for ((slot, env), task) in self.slots.iter_mut().zip(&mut self.envs).zip(tasks) {
            slot.task = task;
            slot.run(env);
        }
        self.core.begin();
        let mut first_err = Ok(());
        for slot in &mut self.slots {
            let r = self.core.finish_reset(slot);
            first_err = first_err.and(r);
        }
        first_err
    }
}

impl<E: Env> VectorEnv for SyncVectorEnv<E>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    type ObsSpace = E::ObsSpace;
    type ActSpace = E::ActSpace;

    delegate_to_core!(E::ObsSpace, E::ActSpace);

    fn step(
        &mut self,
        actions: &BatchOf<E::ActSpace>,
    ) -> Result<VectorStep<'_, BatchOf<E::ObsSpace>>> {
        self.core.check_step(actions)?;
        for slot in &mut self.slots {
            self.core.plan_step(slot, actions)?;
        }
        for (slot, env) in self.slots.iter_mut().zip(&mut self.envs) {
            slot.run(env);
        }
        self.core.begin();
        let mut first_err = Ok(());
        for slot in &mut self.slots {
            let r = self.core.finish_step(slot);
            first_err = first_err.and(r);
        }
        first_err?;
        Ok(self.core.view())
    }

    fn close(&mut self) {
        if !self.core.closed {
            self.core.closed = true;
            for (slot, env) in self.slots.iter().zip(&mut self.envs) {
                slot.close(env);
            }
        }
    }
}
