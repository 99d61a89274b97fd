//! Gymnasium's passive environment checks (`gymnasium.utils.passive_env_checker`), on
//! single spaces and values: what the `PassiveEnvChecker` wrapper (adapters) applies to
//! every `reset` and `step`, and what conformance-tests' `check_env` runs among its checks.
//!
//! * [`check_space`] and [`check_space_limit`] ([`spaces`]): Gymnasium's `check_space` and
//!   `check_space_limit`.
//! * [`check_obs`] ([`obs`]): Gymnasium's `check_obs`, with the reason an observation is not
//!   in its space spelled out.
//! * [`passive`]: the reward, info, render-metadata and render-return checks.
//! * [`report`]: the [`Check`] each belongs to, its [`Failure`], and [`Warning`]s.

pub mod obs;
pub mod passive;
pub mod report;
pub mod spaces;

pub use obs::check_obs;
pub use passive::{check_info_types, check_render_metadata, check_render_return, check_reward};
pub use report::{Check, Failure, Warning, WarningKind};
pub use spaces::{SpaceType, check_space, check_space_limit};

/// Index `flat` of a row-major array of `shape`, as `[i, j, k]` (for messages naming an
/// element).
pub fn unravel(flat: usize, shape: &[usize]) -> Vec<usize> {
    let mut idx = vec![0; shape.len()];
    let mut rest = flat;
    for (i, &d) in shape.iter().enumerate().rev() {
        if d > 0 {
            idx[i] = rest % d;
            rest /= d;
        }
    }
    idx
}
