//! [`CheckOptions`]: how [`check_env`](crate::check_env) runs.

use gym_core::{Info, ResetOptions, Value};
use std::fmt;
use std::sync::Arc;

/// The test a [`ResetOptionsProbe`] applies to what `reset` returned.
pub type ProbeFn = Arc<dyn Fn(&Value, &Info) -> Result<(), String> + Send + Sync>;

/// A reset option the environment documents, and how to see that it was honoured.
///
/// Gymnasium's `check_reset_options` only checks that `reset(options={})` works; an
/// environment that silently ignores an option it documents passes it. A probe closes the
/// gap for options whose effect is visible: `check_env` resets with
/// [`ResetOptionsProbe::options`] and hands the observation (as a [`Value`]) and the info to
/// [`ResetOptionsProbe::expect`].
#[derive(Clone)]
pub struct ResetOptionsProbe {
    /// A name for messages, such as `"position"`.
    pub name: String,
    /// The options to reset with.
    pub options: ResetOptions,
    /// `Ok(())` when the observation and info show the options were applied; otherwise
    /// what was seen instead.
    pub expect: ProbeFn,
}

impl ResetOptionsProbe {
    /// A probe named `name` resetting with `options` and testing the result with `expect`.
    pub fn new(
        name: impl Into<String>,
        options: ResetOptions,
        expect: impl Fn(&Value, &Info) -> Result<(), String> + Send + Sync + 'static,
    ) -> Self {
        Self {
            name: name.into(),
            options,
            expect: Arc::new(expect),
        }
    }
}

impl fmt::Debug for ResetOptionsProbe {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("ResetOptionsProbe")
            .field("name", &self.name)
            .field("options", &self.options)
            .finish_non_exhaustive()
    }
}

/// How [`check_env`](crate::check_env) runs. `CheckOptions::default()` mirrors Gymnasium's
/// `check_env(env)` plus the Rust additions ([`Check::InvalidAction`](crate::Check::InvalidAction),
/// [`Check::StepAfterEnd`](crate::Check::StepAfterEnd)).
#[derive(Debug, Clone)]
pub struct CheckOptions {
    /// A name for the environment in the report (default: its Rust type name, which for a
    /// `BoxedEnv` says little; the registry id is a good name).
    pub name: Option<String>,
    /// Skip the render checks (Gymnasium's `skip_render_check`). Default `false`.
    pub skip_render_check: bool,
    /// Skip closing the environment twice at the end (Gymnasium's `skip_close_check`).
    /// Default `false`. When the check runs, the environment is closed afterwards.
    pub skip_close_check: bool,
    /// The environment may give different results for the same seed and actions
    /// (Gymnasium's `EnvSpec.nondeterministic`): skips the observation comparisons of
    /// [`Check::ResetSeedDeterminism`](crate::Check::ResetSeedDeterminism) and all of
    /// [`Check::StepDeterminism`](crate::Check::StepDeterminism). Default `false`.
    ///
    /// Gymnasium skips the observation comparison for an environment without a spec; here
    /// it runs unless this is set, as a directly constructed Rust environment is expected
    /// to be deterministic.
    pub nondeterministic: bool,
    /// The environment must expose its RNG through `Env::rng()` (Gymnasium asserts
    /// `env.unwrapped._np_random is not None`). Default `true`. With `false`, an
    /// environment without an RNG gets a [`WarningKind::NoRng`](crate::WarningKind::NoRng)
    /// warning and the RNG-state comparisons are skipped.
    pub require_rng: bool,
    /// The seed of the determinism checks and of the action sampler (Gymnasium: 123).
    pub seed: u64,
    /// The different seed of `check_reset_seed_determinism` (Gymnasium: 456).
    pub other_seed: u64,
    /// Run Stable-Baselines3's additional checks (`stable_baselines3.common.env_checker`):
    /// action Box finite bounds (a failure), unsupported spaces, image and unconventional
    /// observation shapes, `[-1, 1]` and `float32` action recommendations (warnings), and
    /// ten extra steps checked for NaN and inf. Default `false`.
    pub sb3: bool,
    /// Run [`Check::InvalidAction`](crate::Check::InvalidAction). Default `true`.
    pub check_invalid_actions: bool,
    /// Also count finite out-of-bounds Box values as invalid actions (many environments
    /// clip them instead, and Gymnasium's checker never steps with them). Default `false`.
    pub out_of_bounds_actions_invalid: bool,
    /// Run [`Check::StepAfterEnd`](crate::Check::StepAfterEnd). Default `true`.
    pub check_step_after_end: bool,
    /// Require [`Check::StepAfterEnd`](crate::Check::StepAfterEnd) to see an error: without
    /// it (the default), a step after the end may also succeed if it still reports the
    /// episode as ended (`terminated || truncated`), as Gymnasium's `TimeLimit` does when
    /// stepped past its limit.
    pub strict_step_after_end: bool,
    /// How many steps [`Check::StepAfterEnd`](crate::Check::StepAfterEnd) takes at most to
    /// reach the end of an episode; when the episode is longer the check is skipped.
    /// Default 1000.
    pub max_episode_steps: usize,
    /// Keep checking after a failure and report every failure (each check starts from its
    /// own `reset`). Default `false`: stop at the first failure, as Gymnasium's asserts do.
    pub keep_going: bool,
    /// Reset options to try in [`Check::ResetOptions`](crate::Check::ResetOptions).
    pub reset_options_probes: Vec<ResetOptionsProbe>,
}

impl Default for CheckOptions {
    fn default() -> Self {
        Self {
            name: None,
            skip_render_check: false,
            skip_close_check: false,
            nondeterministic: false,
            require_rng: true,
            seed: 123,
            other_seed: 456,
            sb3: false,
            check_invalid_actions: true,
            out_of_bounds_actions_invalid: false,
            check_step_after_end: true,
            strict_step_after_end: false,
            max_episode_steps: 1000,
            keep_going: false,
            reset_options_probes: Vec::new(),
        }
    }
}

impl CheckOptions {
    /// The default options (see the field docs).
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets [`CheckOptions::name`].
    #[must_use]
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.name = Some(name.into());
        self
    }

    /// Sets [`CheckOptions::skip_render_check`].
    #[must_use]
    pub fn skip_render_check(mut self, skip: bool) -> Self {
        self.skip_render_check = skip;
        self
    }

    /// Sets [`CheckOptions::skip_close_check`].
    #[must_use]
    pub fn skip_close_check(mut self, skip: bool) -> Self {
        self.skip_close_check = skip;
        self
    }

    /// Sets [`CheckOptions::nondeterministic`].
    #[must_use]
    pub fn nondeterministic(mut self, nondeterministic: bool) -> Self {
        self.nondeterministic = nondeterministic;
        self
    }

    /// Sets [`CheckOptions::require_rng`].
    #[must_use]
    pub fn require_rng(mut self, require: bool) -> Self {
        self.require_rng = require;
        self
    }

    /// Sets [`CheckOptions::seed`] and [`CheckOptions::other_seed`].
    #[must_use]
    pub fn seeds(mut self, seed: u64, other_seed: u64) -> Self {
        self.seed = seed;
        self.other_seed = other_seed;
        self
    }

    /// Sets [`CheckOptions::sb3`].
    #[must_use]
    pub fn sb3(mut self, sb3: bool) -> Self {
        self.sb3 = sb3;
        self
    }

    /// Sets [`CheckOptions::check_invalid_actions`].
    #[must_use]
    pub fn check_invalid_actions(mut self, check: bool) -> Self {
        self.check_invalid_actions = check;
        self
    }

    /// Sets [`CheckOptions::out_of_bounds_actions_invalid`].
    #[must_use]
    pub fn out_of_bounds_actions_invalid(mut self, invalid: bool) -> Self {
        self.out_of_bounds_actions_invalid = invalid;
        self
    }

    /// Sets [`CheckOptions::check_step_after_end`].
    #[must_use]
    pub fn check_step_after_end(mut self, check: bool) -> Self {
        self.check_step_after_end = check;
        self
    }

    /// Sets [`CheckOptions::strict_step_after_end`].
    #[must_use]
    pub fn strict_step_after_end(mut self, strict: bool) -> Self {
        self.strict_step_after_end = strict;
        self
    }

    /// Sets [`CheckOptions::max_episode_steps`].
    #[must_use]
    pub fn max_episode_steps(mut self, steps: usize) -> Self {
        self.max_episode_steps = steps;
        self
    }

    /// Sets [`CheckOptions::keep_going`].
    #[must_use]
    pub fn keep_going(mut self, keep_going: bool) -> Self {
        self.keep_going = keep_going;
        self
    }

    /// Adds a [`ResetOptionsProbe`].
    #[must_use]
    pub fn reset_options_probe(mut self, probe: ResetOptionsProbe) -> Self {
        self.reset_options_probes.push(probe);
        self
    }
}
