//! Composable Gymnasium wrappers and vector environments over any [`gym_core::Env`].
//!
//! Every wrapper is a typed [`gym_core::Wrapper`] that owns the environment it wraps and is
//! written as Gymnasium writes it: the observation maps are
//! [`gym_core::ObservationWrapper`]s, the action maps [`gym_core::ActionWrapper`]s, the
//! reward maps [`gym_core::RewardWrapper`]s, the rest override only the hooks they change
//! ([`gym_core::StepWrapper`], [`gym_core::CustomWrapper`]); none writes an `Env`
//! implementation of its own. A stack is a plain value (`NormalizeObservation<TimeLimit<GymWrapper<RobosuiteEnv>>>`),
//! `Send` when the innermost environment is, and convertible into the dynamic
//! [`gym_core::BoxedEnv`] with [`IntoBoxedEnv::boxed`](gym_core::IntoBoxedEnv::boxed).
//! [`WrapperExt`] adds one method per wrapper to every environment so stacks read in order:
//!
//! ```no_run
//! use adapters::WrapperExt;
//! use gym_core::{Env, IntoBoxedEnv};
//!
//! let env = robosuite_env::make("Lift")?
//!     .gym_wrapper(None, true)?
//!     .time_limit(500)?
//!     .normalize_observation()?
//!     .record_episode_statistics();
//! let mut boxed = env.boxed();
//! let (obs, _info) = boxed.reset(Some(0), None)?;
//! # Ok::<(), gym_core::Error>(())
//! ```
//!
//! Semantics follow Gymnasium 1.x exactly (the order of operations, which flags are touched,
//! the test vectors of its documentation) unless a wrapper's documentation says otherwise.
//! Gymnasium's assertions and exceptions are typed [`gym_core::Error`]s here, never panics.
//!
//! * robosuite: [`GymWrapper`] / [`FlatGymWrapper`] (robosuite's `GymWrapper`, corrected).
//! * Common: [`TimeLimit`], [`OrderEnforcing`], [`Autoreset`], [`RecordEpisodeStatistics`],
//!   [`PassiveEnvChecker`].
//! * Observation: [`FlattenObservation`], [`FilterObservation`], [`DtypeObservation`],
//!   [`NormalizeObservation`], [`TransformObservation`], [`FrameStackObservation`].
//! * Action: [`ClipAction`], [`RescaleAction`], [`TransformAction`], [`StickyAction`],
//!   [`RepeatAction`].
//! * Reward: [`NormalizeReward`], [`TransformReward`], [`ClipReward`].
//! * Vector environments: [`vector`] ([`SyncVectorEnv`], [`ThreadVectorEnv`], and
//!   EnvPool's asynchronous mode, [`ThreadEnvPool`]).
//! * The space abilities the wrappers are generic over live in gym-core beside the spaces
//!   ([`gym_core::spaces`]) and are re-exported here: [`NumericSpace`], [`BatchSpace`],
//!   [`FilterableSpace`].

pub mod autoreset;
/// Batched spaces (moved to [`gym_core::spaces::batch`]; this path is kept).
pub use gym_core::spaces::batch;
pub mod clip_action;
pub mod clip_reward;
pub mod dtype_observation;
pub mod ext;
pub mod filter_observation;
pub mod flatten_observation;
pub mod frame_stack_observation;
pub mod gym_wrapper;
pub mod normalize_observation;
pub mod normalize_reward;
/// Numeric spaces (moved to [`gym_core::spaces::numeric`]; this path is kept).
pub use gym_core::spaces::numeric;
pub mod order_enforcing;
pub mod passive_env_checker;
pub mod record_episode_statistics;
pub mod repeat_action;
pub mod rescale_action;
pub mod running_mean_std;
pub mod sticky_action;
pub mod time_limit;
pub mod transform_action;
pub mod transform_observation;
pub mod transform_reward;
pub mod vector;

#[cfg(test)]
#[path = "../tests/common/mod.rs"]
#[allow(missing_docs)]
pub(crate) mod toy;

pub use autoreset::Autoreset;
pub use batch::{BatchOf, BatchSpace};
pub use clip_action::ClipAction;
pub use clip_reward::ClipReward;
pub use dtype_observation::DtypeObservation;
pub use ext::WrapperExt;
pub use filter_observation::FilterObservation;
pub use flatten_observation::FlattenObservation;
pub use frame_stack_observation::{FrameStackObservation, Padding};
pub use gym_core::spaces::{FilterKeys, FilterableSpace};
pub use gym_wrapper::{FlatGymWrapper, GymWrapper, default_keys};
pub use normalize_observation::NormalizeObservation;
pub use normalize_reward::NormalizeReward;
pub use numeric::{ArraySpec, NumericSpace};
pub use order_enforcing::OrderEnforcing;
pub use passive_env_checker::PassiveEnvChecker;
pub use record_episode_statistics::RecordEpisodeStatistics;
pub use repeat_action::RepeatAction;
pub use rescale_action::{ActionBound, RescaleAction};
pub use running_mean_std::RunningMeanStd;
pub use sticky_action::StickyAction;
pub use time_limit::TimeLimit;
pub use transform_action::TransformAction;
pub use transform_observation::TransformObservation;
pub use transform_reward::TransformReward;
pub use vector::{
    AutoresetMode, PoolStep, Seeds, SyncVectorEnv, ThreadEnvPool, ThreadOptions, ThreadVectorEnv,
    VectorEnv, VectorInfo, VectorStep,
};
