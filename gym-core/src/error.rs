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

/// Why an action, a simulation, a model or a feature failed: a message, a typed cause, or
/// the same kind of error in one sub-environment of a vector environment.
///
/// The kind of failure is the [`Error`] variant that holds the reason, so callers match on
/// the variant (`Error::InvalidAction(_)`) whether the error came from a single environment
/// or from sub-environment `i` of a vector one; [`Reason::InEnv`] keeps that sub-environment's
/// error whole (its [`source`](std::error::Error::source)) instead of rewriting its message.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Reason {
    /// What was wrong, in words.
    Message(String),
    /// A value did not fit a space (for an action: it does not convert to the action type).
    Space(SpaceError),
    /// The error of sub-environment `index` of a vector environment; it has the kind of the
    /// [`Error`] variant that holds this reason.
    InEnv {
        /// The sub-environment's index.
        index: usize,
        /// The sub-environment's error.
        source: Box<Error>,
    },
}

impl Reason {
    /// The sub-environment the error happened in, the outermost first, if it came from a
    /// vector environment.
    pub fn sub_environment(&self) -> Option<usize> {
        match self {
            Reason::InEnv { index, .. } => Some(*index),
            _ => None,
        }
    }
}

impl std::fmt::Display for Reason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Reason::Message(m) => f.write_str(m),
            Reason::Space(e) => e.fmt(f),
            // The sub-environment's own reason when it has one, so the kind is said once.
            Reason::InEnv { index, source } => match source.reason() {
                Some(r) => write!(f, "sub-environment {index}: {r}"),
                None => write!(f, "sub-environment {index}: {source}"),
            },
        }
    }
}

impl std::error::Error for Reason {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Reason::Message(_) => None,
            Reason::Space(e) => Some(e),
            Reason::InEnv { source, .. } => Some(source.as_ref()),
        }
    }
}

impl From<String> for Reason {
    fn from(m: String) -> Self {
        Reason::Message(m)
    }
}

impl From<&str> for Reason {
    fn from(m: &str) -> Self {
        Reason::Message(m.to_owned())
    }
}

impl From<SpaceError> for Reason {
    fn from(e: SpaceError) -> Self {
        Reason::Space(e)
    }
}

/// Everything that can go wrong when making, resetting, stepping or wrapping an environment.
///
/// Each variant carries enough to say what was wrong and what would be valid; typed causes
/// (a [`SpaceError`], a sub-environment's error) are kept as
/// [`source`](std::error::Error::source)s.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The action does not fit the action space (wrong length, NaN, ±inf, out of bounds, ...).
    /// The environment is left untouched and stays usable.
    #[error("invalid action: {0}")]
    InvalidAction(#[source] Reason),
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
    Model(#[source] Reason),
    /// The simulator reported a failure (for example a diverged state).
    #[error("simulation error: {0}")]
    Simulation(#[source] Reason),
    /// A feature that this build does not provide.
    #[error("not supported: {0}")]
    Unsupported(#[source] Reason),
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
        #[source]
        message: Reason,
    },
}

impl Error {
    /// Builds an [`Error::InvalidAction`] from a message.
    pub fn invalid_action(message: impl Into<String>) -> Self {
        Self::InvalidAction(Reason::Message(message.into()))
    }

    /// Builds an [`Error::Model`] from a message.
    pub fn model(message: impl Into<String>) -> Self {
        Self::Model(Reason::Message(message.into()))
    }

    /// Builds an [`Error::Simulation`] from a message.
    pub fn simulation(message: impl Into<String>) -> Self {
        Self::Simulation(Reason::Message(message.into()))
    }

    /// Builds an [`Error::Unsupported`] from a message.
    pub fn unsupported(message: impl Into<String>) -> Self {
        Self::Unsupported(Reason::Message(message.into()))
    }

    /// Builds an [`Error::Contract`] from the check's name and a message.
    pub fn contract(check: impl Into<String>, message: impl Into<String>) -> Self {
        Self::Contract {
            check: check.into(),
            message: Reason::Message(message.into()),
        }
    }

    /// The error as it happened in sub-environment `index` of a vector environment: the
    /// same kind, with this error as its source (kinds without a [`Reason`] stay as they are,
    /// as they say nothing specific to one sub-environment).
    pub fn in_env(self, index: usize) -> Self {
        let wrap = |e: Error| Reason::InEnv {
            index,
            source: Box::new(e),
        };
        match self {
            Error::InvalidAction(_) => Error::InvalidAction(wrap(self)),
            Error::Simulation(_) => Error::Simulation(wrap(self)),
            Error::Model(_) => Error::Model(wrap(self)),
            Error::Unsupported(_) => Error::Unsupported(wrap(self)),
            Error::Contract { ref check, .. } => Error::Contract {
                check: check.clone(),
                message: wrap(self),
            },
            other => other,
        }
    }

    /// The error as an invalid action, for a wrapper whose action mapping failed: an
    /// invalid action stays as it is, a space error becomes the typed reason, anything else
    /// becomes its message.
    pub fn into_invalid_action(self) -> Self {
        match self {
            Error::InvalidAction(_) => self,
            Error::Space(e) => Error::InvalidAction(Reason::Space(e)),
            other => Error::invalid_action(other.to_string()),
        }
    }

    /// The reason the error holds, for the kinds that have one.
    pub fn reason(&self) -> Option<&Reason> {
        match self {
            Error::InvalidAction(r)
            | Error::Model(r)
            | Error::Simulation(r)
            | Error::Unsupported(r)
            | Error::Contract { message: r, .. } => Some(r),
            _ => None,
        }
    }

    /// The sub-environment of a vector environment the error happened in, if any.
    pub fn sub_environment(&self) -> Option<usize> {
        self.reason().and_then(Reason::sub_environment)
    }

    /// Builds an [`Error::InvalidArgument`].
    pub fn invalid_argument(name: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::InvalidArgument {
            name: name.into(),
            reason: reason.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::error::Error as _;

    #[test]
    fn sub_environment_errors_keep_kind_message_and_source() {
        let inner = Error::InvalidAction(
            SpaceError::WrongKind {
                expected: "array",
                got: "dict",
            }
            .into(),
        );
        let outer = inner.clone().in_env(3);
        assert!(matches!(
            outer,
            Error::InvalidAction(Reason::InEnv { index: 3, .. })
        ));
        assert_eq!(
            outer.to_string(),
            "invalid action: sub-environment 3: wrong kind of value: expected array, got dict"
        );
        assert_eq!(outer.sub_environment(), Some(3));
        let reason = outer.source().unwrap();
        assert_eq!(reason.source().unwrap().to_string(), inner.to_string());
        let space = reason.source().unwrap().source().unwrap();
        assert!(
            space
                .downcast_ref::<Reason>()
                .is_some_and(|r| matches!(r, Reason::Space(_)))
        );
        assert_eq!(Error::Closed.in_env(1), Error::Closed);
        let c = Error::contract("step", "reward is NaN").in_env(0);
        assert_eq!(
            c.to_string(),
            "contract violation in step: sub-environment 0: reward is NaN"
        );
    }
}
