//! A property-tested mirror of Gymnasium's `check_env` for any [`gym_core::Env`].
//!
//! * [`check_env`] runs Gymnasium's `check_env` check by check and in order (space
//!   structure and limits, reset return value, reset seed determinism, reset options,
//!   the passive reset and step checks, step determinism, returned data not reused,
//!   render and close), plus Rust additions (invalid actions are typed errors, a step
//!   after the end of an episode is refused) and, optionally, Stable-Baselines3's extra
//!   checks. Failures name the [`Check`] they broke and say what was observed; warnings
//!   are reported apart, with Gymnasium's wording.
//! * [`passive`] holds Gymnasium's passive checks on single values, shared with the
//!   `PassiveEnvChecker` wrapper of the `adapters` crate (with [`check_space`] and
//!   [`check_obs`]), so the wrapper and `check_env` apply one checker. They live in
//!   [`gym_core::check`] and are re-exported here at their old paths.
//! * [`prop`] (feature `prop`, on by default) runs property-based checks with proptest over random seeds and action
//!   sequences, shrinking to a minimal failing sequence: observations stay in their
//!   space, replays are bit-identical, state get/set round-trips, time limits truncate
//!   at exactly N, invalid actions are rejected without side effects, spaces sample and
//!   flatten correctly.
//! * [`toy`] holds small, correct environments and [`broken`] deliberately broken ones,
//!   one per defect, each caught by the check meant for it (both with the `prop` feature).
//!
//! ```
//! use conformance_tests::{check_env, Check, CheckOptions, toy::PointMass};
//!
//! let mut env = PointMass::new();
//! let report = check_env(&mut env, &CheckOptions::default()).expect("PointMass conforms");
//! assert!(report.passed(Check::ResetSeedDeterminism));
//! ```
//!
//! See `examples/check_my_env.rs` for a custom environment checked both ways.
//!
//! # Where this differs from Gymnasium's `check_env`
//!
//! * Stricter, as failures rather than warnings: an observation outside its space in the
//!   passive checks, a NaN or infinite observation (SB3's NaN check) or reward, a `close`
//!   that panics the second time, a render `fps` that is not positive.
//! * The observation comparisons of `check_reset_seed_determinism` run unless
//!   [`CheckOptions::nondeterministic`] is set (Gymnasium runs them only for environments
//!   made from a spec that is not `nondeterministic`).
//! * The environment must expose its RNG ([`gym_core::Env::rng`]), the analogue of
//!   Gymnasium's `_np_random is not None` assertion ([`CheckOptions::require_rng`]).
//! * Additions: [`Check::InvalidAction`], [`Check::StepAfterEnd`], reset option probes
//!   ([`ResetOptionsProbe`]).
//! * `check_returned_data_not_reused` is answered by ownership for gym-core's value types;
//!   the check catches observation types with shared interior mutability instead.
//! * The close check runs on the checked environment (Gymnasium makes a new one from the
//!   spec), which is closed afterwards; alternative render modes cannot be tried without a
//!   way to make the environment in each mode, which gives a warning.
//! * Left out because the Rust types make them moot: the `TypeError` for objects that are
//!   not environments, the `hasattr` checks for spaces, the tuple shapes of `reset` and
//!   `step`, the `bool` type of the flags, the `dict` type of `info`, the deprecation
//!   warnings (`seed()` method, `return_info`, the 4-tuple step API) and the default-seed
//!   warning; and the JAX / PyTorch conversions.

#[cfg(feature = "prop")]
pub mod broken;
pub mod data;
pub mod env_checker;
pub mod invalid;
pub use gym_core::check::{obs, passive, spaces};
pub mod options;
#[cfg(feature = "prop")]
pub mod prop;
pub mod report;
pub mod sb3;
#[cfg(feature = "prop")]
pub mod toy;

pub use data::{Compare, data_equivalence};
pub use env_checker::{
    check_close, check_env, check_invalid_actions, check_reset_options, check_reset_return_type,
    check_reset_seed_determinism, check_returned_data_not_reused, check_step_after_end,
    check_step_determinism, env_render_passive_checker, env_reset_passive_checker,
    env_step_passive_checker,
};
pub use obs::check_obs;
pub use options::{CheckOptions, ResetOptionsProbe};
pub use passive::{check_info_types, check_render_metadata, check_render_return, check_reward};
#[cfg(feature = "prop")]
pub use prop::{
    EpisodeEndSpec, PropConfig, PropFailure, PropReport, Property, StateHook, prop_check_env,
};
pub use report::{Check, ConformanceError, Failure, Report, Skipped, Warning, WarningKind};
pub use spaces::{SpaceType, check_space, check_space_limit};
