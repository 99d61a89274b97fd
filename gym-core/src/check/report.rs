//! What a check produces: the [`Check`]s, their [`Failure`]s and the [`Warning`]s kept
//! apart from failures (conformance-tests adds the `Report` of a `check_env` run).

use std::fmt;

/// One check of conformance-tests' `check_env`, in the order `check_env` runs them.
///
/// The names ([`Check::name`]) are Gymnasium's function names (`gymnasium.utils.env_checker`
/// and `passive_env_checker`), so a failure can be looked up in Gymnasium's source. The
/// observation checks of Gymnasium's `check_obs` are split by what went wrong (structure,
/// dtype, finiteness, bounds) so a failure says exactly which rule was broken; they apply
/// to every observation any check receives, as Gymnasium asserts `obs in observation_space`
/// after every `reset` it makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Check {
    /// `check_action_space` (passive_env_checker `check_space`): Box bound shapes, Discrete
    /// `n > 0`, MultiDiscrete `nvec > 0`, MultiBinary dimensions `> 0`, non-empty Tuple and
    /// Dict, recursively.
    ActionSpace,
    /// `check_observation_space`: the same rules for the observation space.
    ObservationSpace,
    /// SB3's `check_env`: a Box action space must have finite bounds (only with
    /// `CheckOptions::sb3`).
    Sb3ActionBounds,
    /// `check_reset_return_type`: `reset()` (no seed) succeeds and returns an observation
    /// in the observation space.
    ResetReturnType,
    /// `check_reset_seed_determinism`: `reset(123)`, `reset()`, `reset(123)`, `reset()`,
    /// `reset(456)`; the same seed gives the same observation and the same RNG state, a
    /// different seed a different RNG state, and the environment exposes its RNG.
    ResetSeedDeterminism,
    /// `check_reset_options`: `reset` accepts empty options (and honours the user's
    /// `ResetOptionsProbe`s).
    ResetOptions,
    /// `env_reset_passive_checker`: a plain `reset()` succeeds.
    ResetPassive,
    /// `env_step_passive_checker`: a `step` with a sampled action succeeds.
    StepPassive,
    /// `check_obs` (structure): an observation has the kind of its space (array, integer,
    /// dict with the space's keys, tuple of the space's length).
    ObservationStructure,
    /// `check_obs` (dtype): an array observation of a Box has a dtype that casts safely to
    /// the space's (a safe but different dtype is a warning, as in Gymnasium).
    ObservationDtype,
    /// No NaN or infinite value in an observation.
    ObservationFinite,
    /// `obs in observation_space` (Gymnasium's `Space.contains`): shape and bounds.
    ObservationContained,
    /// `env_step_passive_checker` (reward): the reward is finite (Gymnasium warns on NaN and
    /// inf rewards; here it is a failure, as in SB3's NaN check).
    RewardFinite,
    /// `check_step_determinism`: the same seed and action give the same observation,
    /// reward, termination, info and RNG state after one step.
    StepDeterminism,
    /// `check_step_determinism` (truncation): `truncated` is false after one step
    /// ("Environment truncates after 1 step, something has gone very wrong.").
    TruncatedAfterOneStep,
    /// `check_returned_data_not_reused`: observations returned by different calls are
    /// distinct data that later calls do not change.
    ReturnedDataNotReused,
    /// Rust addition: an action outside the action space (wrong length, NaN, ±inf,
    /// out-of-range discrete value) gives [`crate::Error::InvalidAction`], not a panic or
    /// a step, and leaves the environment as it was.
    InvalidAction,
    /// Rust addition: once an episode has ended (`terminated || truncated`), `step` answers
    /// `Error::EpisodeEnded` (or `Error::ResetNeeded`) until `reset`, or at least keeps
    /// reporting the episode as ended (Gymnasium's `TimeLimit` past its limit); it must not
    /// silently carry on.
    StepAfterEnd,
    /// `env_render_passive_checker`: the render mode is declared in `metadata.render_modes`,
    /// `render_fps > 0`, and `render()` works in the chosen mode.
    Render,
    /// `check_env`'s close check: `close()` twice neither panics nor errors.
    CloseTwice,
}

impl Check {
    /// Every check, in the order conformance-tests' `check_env` runs them.
    pub const ALL: [Check; 20] = [
        Check::ActionSpace,
        Check::ObservationSpace,
        Check::Sb3ActionBounds,
        Check::ResetReturnType,
        Check::ResetSeedDeterminism,
        Check::ResetOptions,
        Check::ResetPassive,
        Check::StepPassive,
        Check::ObservationStructure,
        Check::ObservationDtype,
        Check::ObservationFinite,
        Check::ObservationContained,
        Check::RewardFinite,
        Check::StepDeterminism,
        Check::TruncatedAfterOneStep,
        Check::ReturnedDataNotReused,
        Check::InvalidAction,
        Check::StepAfterEnd,
        Check::Render,
        Check::CloseTwice,
    ];

    /// The name of the Gymnasium (or SB3) function this check mirrors, with the assertion
    /// in parentheses where one function holds several checks.
    pub fn name(self) -> &'static str {
        match self {
            Check::ActionSpace => "check_action_space",
            Check::ObservationSpace => "check_observation_space",
            Check::Sb3ActionBounds => "sb3_check_env (action bounds)",
            Check::ResetReturnType => "check_reset_return_type",
            Check::ResetSeedDeterminism => "check_reset_seed_determinism",
            Check::ResetOptions => "check_reset_options",
            Check::ResetPassive => "env_reset_passive_checker",
            Check::StepPassive => "env_step_passive_checker",
            Check::ObservationStructure => "check_obs (structure)",
            Check::ObservationDtype => "check_obs (dtype)",
            Check::ObservationFinite => "check_obs (finite)",
            Check::ObservationContained => "check_obs (contains)",
            Check::RewardFinite => "env_step_passive_checker (reward)",
            Check::StepDeterminism => "check_step_determinism",
            Check::TruncatedAfterOneStep => "check_step_determinism (truncation)",
            Check::ReturnedDataNotReused => "check_returned_data_not_reused",
            Check::InvalidAction => "check_invalid_actions",
            Check::StepAfterEnd => "check_step_after_end",
            Check::Render => "env_render_passive_checker",
            Check::CloseTwice => "check_close",
        }
    }
}

impl fmt::Display for Check {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A check that failed: which one and what was observed.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// The check that failed.
    pub check: Check,
    /// What was observed, in Gymnasium's wording where Gymnasium has one, followed by the
    /// Rust specifics (the call that was made, the first differing element, ...).
    pub message: String,
}

impl Failure {
    /// A failure of `check` saying `message`.
    pub fn new(check: Check, message: impl Into<String>) -> Self {
        Self {
            check,
            message: message.into(),
        }
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{}] {}", self.check.name(), self.message)
    }
}

/// What a [`Warning`] is about. Warnings never fail a check; they mirror Gymnasium's
/// `logger.warn` calls (and SB3's `warnings.warn`) and keep their meaning.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum WarningKind {
    /// The checked environment is a wrapper, not the unwrapped environment ("The
    /// environment (...) is different from the unwrapped version").
    NotUnwrapped,
    /// A Box space has an element whose low and high bounds are equal.
    BoxLowEqualsHigh,
    /// A Box observation space has an element whose high bound is below its low bound
    /// (unreachable through gym-core's constructors).
    BoxHighBelowLow,
    /// A floating-point Box space has a `-inf` lower bound ("This is probably too low.").
    BoxUnboundedBelow,
    /// A floating-point Box space has a `+inf` upper bound ("This is probably too high.").
    BoxUnboundedAbove,
    /// A one-dimensional Box action space is not symmetric and normalised (`[-1, 1]` or
    /// `[0, 1]`).
    ActionSpaceNotNormalized,
    /// An observation's dtype differs from its Box's but casts safely to it.
    ObservationDtype,
    /// A Discrete observation came as a 0-d array rather than an integer.
    DiscreteObservationType,
    /// Two results that must be equal are equal within `rtol = atol = 1e-5` but not exactly
    /// ("... are not equal although similar").
    NotExactlyEqual,
    /// The environment exposes no RNG (`Env::rng()` is `None`) and
    /// `CheckOptions::require_rng` is off, so the RNG
    /// state checks were skipped.
    NoRng,
    /// Render modes are declared but no `render_fps`.
    RenderFpsMissing,
    /// `render()` returned something that does not fit the render mode.
    RenderReturn,
    /// Other declared render modes could not be tried (no factory to make the
    /// environment in another mode; Gymnasium: "the environment not having a spec").
    AlternativeRenderModesNotTested,
    /// SB3: a space SB3 does not support (nested Dict, Tuple observation, Dict/Tuple
    /// action, multi-dimensional MultiDiscrete, non-zero Discrete start).
    Sb3UnsupportedSpace,
    /// SB3: a 3-dimensional Box observation (an image) that is not `uint8` in `[0, 255]` of
    /// at least 36x36.
    Sb3ImageSpace,
    /// SB3: a Box observation of neither 1 nor 3 dimensions.
    Sb3UnconventionalShape,
    /// SB3: a Box action space other than exactly `[-1, 1]`.
    Sb3ActionNotNormalized,
    /// SB3: a Box action space whose dtype is not `float32`.
    Sb3ActionDtype,
}

/// A warning: something Gymnasium (or SB3) reports without failing.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Warning {
    /// What the warning is about.
    pub kind: WarningKind,
    /// Gymnasium's message, with the space path or call where it applies.
    pub message: String,
}

impl Warning {
    /// A warning of `kind` saying `message`.
    pub fn new(kind: WarningKind, message: impl Into<String>) -> Self {
        Self {
            kind,
            message: message.into(),
        }
    }
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "WARN: {}", self.message)
    }
}
