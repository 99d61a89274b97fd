//! Typed errors shared by every crate of the workspace.

use crate::dtype::DType;

/// The result type of environment, wrapper and registry operations.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Why a space could not be built, or a value did not fit it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SpaceError {
    /// A bound is NaN, `low > high`, or a bound does not fit the dtype.
    #[error("invalid bounds: {0}")]
    InvalidBounds(String),
    /// Two shapes that must agree do not.
    #[error("shape mismatch: expected {expected:?}, got {got:?}")]
    ShapeMismatch {
        /// The shape the space requires.
        expected: Vec<usize>,
        /// The shape that was given.
        got: Vec<usize>,
    },
    /// A value's dtype cannot be cast safely to the space's dtype.
    #[error("dtype mismatch: expected {expected}, got {got}")]
    DtypeMismatch {
        /// The dtype the space requires.
        expected: DType,
        /// The dtype that was given.
        got: DType,
    },
    /// A value of the wrong kind (for example a dict where an array was expected).
    #[error("wrong kind of value: expected {expected}, got {got}")]
    WrongKind {
        /// What the space holds.
        expected: &'static str,
        /// What was given.
        got: &'static str,
    },
    /// A dict value or space argument names keys the space does not have, or lacks some.
    #[error("dict keys differ: expected {expected:?}, got {got:?}")]
    KeyMismatch {
        /// The space's keys, in order.
        expected: Vec<String>,
        /// The keys that were given.
        got: Vec<String>,
    },
    /// A flat vector cannot be unflattened (wrong length, or a one-hot with no set entry).
    #[error("cannot unflatten: {0}")]
    Unflatten(String),
    /// A constructor argument is out of its valid range.
    #[error("invalid space argument: {0}")]
    InvalidArgument(String),
}

/// Everything that can go wrong when making, resetting, stepping or wrapping an environment.
///
/// Each variant carries enough to say what was wrong and what would be valid.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The action does not fit the action space (wrong length, NaN, ±inf, out of bounds, ...).
    /// The environment is left untouched and stays usable.
    #[error("invalid action: {0}")]
    InvalidAction(String),
    /// `step` was called before the first `reset` (Gymnasium's `ResetNeeded`).
    #[error("cannot call step() before calling reset()")]
    ResetNeeded,
    /// `step` was called after the episode ended; call `reset` first.
    #[error(
        "cannot call step() after the episode ended (terminated or truncated); call reset() first"
    )]
    EpisodeEnded,
    /// A constructor or method argument is invalid.
    #[error("invalid argument `{name}`: {reason}")]
    InvalidArgument {
        /// The argument's name.
        name: String,
        /// What is wrong and what would be valid.
        reason: String,
    },
    /// No environment is registered under this id.
    #[error("unknown environment `{id}`; registered: {}", available.join(", "))]
    UnknownEnv {
        /// The id that was asked for.
        id: String,
        /// Every registered id.
        available: Vec<String>,
    },
    /// An observation (or info, or option) key that does not exist.
    #[error("unknown key `{key}`; available: {}", available.join(", "))]
    UnknownKey {
        /// The key that was asked for.
        key: String,
        /// The keys that exist.
        available: Vec<String>,
    },
    /// A space could not be built, or a value did not fit it.
    #[error(transparent)]
    Space(#[from] SpaceError),
    /// A simulation model could not be loaded or compiled.
    #[error("invalid model: {0}")]
    Model(String),
    /// The simulator reported a failure (for example a diverged state).
    #[error("simulation error: {0}")]
    Simulation(String),
    /// A feature that this build does not provide.
    #[error("not supported: {0}")]
    Unsupported(String),
    /// Offscreen rendering failed or is unavailable (for example libEGL is missing); the
    /// message names the missing library or what failed.
    #[error("rendering error: {0}")]
    Render(String),
    /// The environment was closed and cannot be used any more.
    #[error("the environment is closed")]
    Closed,
    /// An environment broke the API contract (reported by checking layers such as
    /// `PassiveEnvChecker`).
    #[error("contract violation in {check}: {message}")]
    Contract {
        /// The check that failed.
        check: String,
        /// What was observed.
        message: String,
    },
}

impl Error {
    /// Builds an [`Error::InvalidArgument`].
    pub fn invalid_argument(name: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::InvalidArgument {
            name: name.into(),
            reason: reason.into(),
        }
    }
}
