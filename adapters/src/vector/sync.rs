//! [`SyncVectorEnv`]: sub-environments stepped in turn on the calling thread.

use super::core::{VectorCore, run_op};
use super::delegate_to_core;
use super::{AutoresetMode, Seeds, VectorEnv, VectorInfo, VectorStep};
use crate::batch::{BatchOf, BatchSpace};
use gym_core::{Env, Metadata, ResetOptions, Result};

/// Gymnasium's `SyncVectorEnv`: `n` environments with identical spaces, stepped one after
/// the other (see the [module documentation](super) for the semantics).
#[derive(Debug)]
pub struct SyncVectorEnv<E: Env>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    envs: Vec<E>,
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
        let core = VectorCore::new(&envs)?;
        Ok(Self { envs, core })
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
    ) -> Result<VectorInfo> {
        let ops = self.core.plan_reset(seeds, options, mask)?;
        let outcomes = ops
            .into_iter()
            .zip(&mut self.envs)
            .map(|(op, env)| op.map(|op| run_op(env, op)))
            .collect();
        self.core.finish_reset(outcomes)
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
        let ops = self.core.plan_step(actions)?;
        let outcomes = ops
            .into_iter()
            .zip(&mut self.envs)
            .map(|(op, env)| run_op(env, op))
            .collect();
        let infos = self.core.finish_step(outcomes)?;
        Ok(self.core.view(infos))
    }

    fn close(&mut self) {
        if !self.core.closed {
            self.core.closed = true;
            for e in &mut self.envs {
                e.close();
            }
        }
    }
}
