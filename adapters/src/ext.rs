//! [`WrapperExt`]: one method per wrapper on every environment, so stacks read in order.

use crate::batch::BatchSpace;
use crate::frame_stack_observation::Padding;
use crate::numeric::NumericSpace;
use crate::rescale_action::ActionBound;
use crate::{
    Autoreset, ClipAction, ClipReward, DtypeObservation, FilterObservation, FlatGymWrapper,
    FlattenObservation, FrameStackObservation, GymWrapper, NormalizeObservation, NormalizeReward,
    OrderEnforcing, PassiveEnvChecker, RecordEpisodeStatistics, RepeatAction, RescaleAction,
    StickyAction, TimeLimit, TransformAction, TransformObservation, TransformReward,
};
use gym_core::spaces::{FilterKeys, FilterableSpace};
use gym_core::{ArrayElement, Env, Result, Space};

/// Builder methods for every wrapper of this crate, implemented for every [`Env`]:
///
/// ```no_run
/// use adapters::WrapperExt;
///
/// let env = robosuite_env::make("Lift")?
///     .gym_wrapper(None, true)?
///     .time_limit(500)?
///     .normalize_observation()?;
/// # Ok::<(), gym_core::Error>(())
/// ```
///
/// Each method is the wrapper's constructor with the same arguments and errors.
pub trait WrapperExt: Env + Sized {
    /// [`GymWrapper::new`].
    ///
    /// # Errors
    /// As [`GymWrapper::new`].
    fn gym_wrapper(self, keys: Option<Vec<String>>, flatten_obs: bool) -> Result<GymWrapper<Self>>
    where
        Self::ObsSpace: FilterableSpace,
        Self::ActSpace: NumericSpace,
    {
        GymWrapper::new(self, keys, flatten_obs)
    }

    /// [`FlatGymWrapper::new`].
    ///
    /// # Errors
    /// As [`FlatGymWrapper::new`].
    fn flat_gym_wrapper(self, keys: Option<Vec<String>>) -> Result<FlatGymWrapper<Self>>
    where
        Self::ObsSpace: FilterableSpace,
        Self::ActSpace: NumericSpace,
    {
        FlatGymWrapper::new(self, keys)
    }

    /// [`TimeLimit::new`].
    ///
    /// # Errors
    /// As [`TimeLimit::new`].
    fn time_limit(self, max_episode_steps: u64) -> Result<TimeLimit<Self>> {
        TimeLimit::new(self, max_episode_steps)
    }

    /// [`OrderEnforcing::new`].
    fn order_enforcing(self) -> OrderEnforcing<Self> {
        OrderEnforcing::new(self)
    }

    /// [`Autoreset::new`].
    fn autoreset(self) -> Autoreset<Self> {
        Autoreset::new(self)
    }

    /// [`RecordEpisodeStatistics::new`].
    fn record_episode_statistics(self) -> RecordEpisodeStatistics<Self> {
        RecordEpisodeStatistics::new(self)
    }

    /// [`PassiveEnvChecker::new`].
    ///
    /// # Errors
    /// As [`PassiveEnvChecker::new`].
    fn passive_env_checker(self) -> Result<PassiveEnvChecker<Self>> {
        PassiveEnvChecker::new(self)
    }

    /// [`FlattenObservation::new`].
    fn flatten_observation(self) -> FlattenObservation<Self> {
        FlattenObservation::new(self)
    }

    /// [`FilterObservation::new`].
    ///
    /// # Errors
    /// As [`FilterObservation::new`].
    fn filter_observation(self, keys: impl Into<FilterKeys>) -> Result<FilterObservation<Self>>
    where
        Self::ObsSpace: FilterableSpace,
    {
        FilterObservation::new(self, keys)
    }

    /// [`DtypeObservation::new`] (`env.dtype_observation::<f32>()`).
    ///
    /// # Errors
    /// As [`DtypeObservation::new`].
    fn dtype_observation<U: ArrayElement>(self) -> Result<DtypeObservation<Self, U>>
    where
        Self::ObsSpace: NumericSpace,
    {
        DtypeObservation::new(self)
    }

    /// [`NormalizeObservation::new`].
    ///
    /// # Errors
    /// As [`NormalizeObservation::new`].
    fn normalize_observation(self) -> Result<NormalizeObservation<Self>>
    where
        Self::ObsSpace: NumericSpace,
    {
        NormalizeObservation::new(self)
    }

    /// [`TransformObservation::new`].
    fn transform_observation<F, S>(
        self,
        func: F,
        observation_space: S,
    ) -> TransformObservation<Self, F, S>
    where
        S: Space,
        F: FnMut(Self::Obs) -> S::Element + Send + 'static,
    {
        TransformObservation::new(self, func, observation_space)
    }

    /// [`FrameStackObservation::new`].
    ///
    /// # Errors
    /// As [`FrameStackObservation::new`].
    fn frame_stack_observation(
        self,
        stack_size: usize,
        padding: Padding<Self::Obs>,
    ) -> Result<FrameStackObservation<Self>>
    where
        Self::ObsSpace: BatchSpace,
    {
        FrameStackObservation::new(self, stack_size, padding)
    }

    /// [`ClipAction::new`].
    ///
    /// # Errors
    /// As [`ClipAction::new`].
    fn clip_action(self) -> Result<ClipAction<Self>>
    where
        Self::ActSpace: NumericSpace,
    {
        ClipAction::new(self)
    }

    /// [`RescaleAction::new`].
    ///
    /// # Errors
    /// As [`RescaleAction::new`].
    fn rescale_action(
        self,
        min_action: impl Into<ActionBound>,
        max_action: impl Into<ActionBound>,
    ) -> Result<RescaleAction<Self>>
    where
        Self::ActSpace: NumericSpace,
    {
        RescaleAction::new(self, min_action, max_action)
    }

    /// [`TransformAction::new`].
    fn transform_action<F, S>(self, func: F, action_space: S) -> TransformAction<Self, F, S>
    where
        S: Space,
        F: FnMut(&S::Element) -> Self::Act + Send + 'static,
    {
        TransformAction::new(self, func, action_space)
    }

    /// [`StickyAction::new`].
    ///
    /// # Errors
    /// As [`StickyAction::new`].
    fn sticky_action(self, repeat_action_probability: f64) -> Result<StickyAction<Self>> {
        StickyAction::new(self, repeat_action_probability)
    }

    /// [`RepeatAction::new`].
    ///
    /// # Errors
    /// As [`RepeatAction::new`].
    fn repeat_action(self, num_repeats: u32) -> Result<RepeatAction<Self>> {
        RepeatAction::new(self, num_repeats)
    }

    /// [`NormalizeReward::new`].
    fn normalize_reward(self) -> NormalizeReward<Self> {
        NormalizeReward::new(self)
    }

    /// [`TransformReward::new`].
    fn transform_reward<F: FnMut(f64) -> f64 + Send + 'static>(
        self,
        func: F,
    ) -> TransformReward<Self, F> {
        TransformReward::new(self, func)
    }

    /// [`ClipReward::new`].
    ///
    /// # Errors
    /// As [`ClipReward::new`].
    fn clip_reward(
        self,
        min_reward: Option<f64>,
        max_reward: Option<f64>,
    ) -> Result<ClipReward<Self>> {
        ClipReward::new(self, min_reward, max_reward)
    }
}

impl<E: Env> WrapperExt for E {}
