//! What a check run produces: the [`Check`]s, their [`Failure`]s, the [`Warning`]s kept
//! apart from failures (gym-core's [`gym_core::check::report`], re-exported here), the
//! [`Report`] and the [`ConformanceError`].

pub use gym_core::check::report::{Check, Failure, Warning, WarningKind};
use std::fmt;

/// A check that was not run, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Skipped {
    /// The check.
    pub check: Check,
    /// Why it was skipped.
    pub reason: String,
}

/// The result of a [`check_env`](crate::check_env) run: the checks that passed, those that
/// were skipped and every warning.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Report {
    /// The Rust type of the checked environment.
    pub env: String,
    /// The checks that ran and passed, in order.
    pub passed: Vec<Check>,
    /// The checks that were skipped, with the reason.
    pub skipped: Vec<Skipped>,
    /// Every warning, in the order they were raised (duplicates removed).
    pub warnings: Vec<Warning>,
}

impl Report {
    /// An empty report for an environment of type `env`.
    pub fn new(env: impl Into<String>) -> Self {
        Self {
            env: env.into(),
            ..Self::default()
        }
    }

    /// Whether a warning of `kind` was raised.
    pub fn has_warning(&self, kind: WarningKind) -> bool {
        self.warnings.iter().any(|w| w.kind == kind)
    }

    /// The warnings of `kind`.
    pub fn warnings_of(&self, kind: WarningKind) -> impl Iterator<Item = &Warning> {
        self.warnings.iter().filter(move |w| w.kind == kind)
    }

    /// Whether `check` ran and passed.
    pub fn passed(&self, check: Check) -> bool {
        self.passed.contains(&check)
    }

    /// Adds warnings, skipping exact duplicates (as Python's warning filter does for a
    /// repeated message).
    pub fn extend_warnings(&mut self, warnings: impl IntoIterator<Item = Warning>) {
        for w in warnings {
            if !self.warnings.contains(&w) {
                self.warnings.push(w);
            }
        }
    }
}

impl fmt::Display for Report {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "check_env report for {}", self.env)?;
        for c in &self.passed {
            writeln!(f, "  ok      {c}")?;
        }
        for s in &self.skipped {
            writeln!(f, "  skipped {}: {}", s.check, s.reason)?;
        }
        for w in &self.warnings {
            writeln!(f, "  {w}")?;
        }
        Ok(())
    }
}

/// `check_env` found at least one failure.
///
/// Holds every failure found (one, unless
/// [`CheckOptions::keep_going`](crate::CheckOptions::keep_going) is set) and the report of
/// what ran before (passed checks and warnings).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}", self.describe())]
pub struct ConformanceError {
    first: Failure,
    more: Vec<Failure>,
    report: Box<Report>,
}

impl ConformanceError {
    /// An error holding `first` and any further failures.
    pub fn new(first: Failure, more: Vec<Failure>, report: Report) -> Self {
        Self {
            first,
            more,
            report: Box::new(report),
        }
    }

    /// What ran and passed, was skipped, or warned before (and, with
    /// [`CheckOptions::keep_going`](crate::CheckOptions::keep_going), after) the failures.
    pub fn report(&self) -> &Report {
        &self.report
    }

    /// The first failure (the one Gymnasium's `check_env` would have raised).
    pub fn first(&self) -> &Failure {
        &self.first
    }

    /// The check of the first failure.
    pub fn check(&self) -> Check {
        self.first.check
    }

    /// Every failure, first to last.
    pub fn failures(&self) -> impl Iterator<Item = &Failure> {
        std::iter::once(&self.first).chain(&self.more)
    }

    /// Whether `check` failed.
    pub fn failed(&self, check: Check) -> bool {
        self.failures().any(|f| f.check == check)
    }

    fn describe(&self) -> String {
        let n = 1 + self.more.len();
        let mut s = format!(
            "{n} conformance check{} failed for {}:",
            if n == 1 { "" } else { "s" },
            self.report.env
        );
        for f in self.failures() {
            s.push_str("\n  - ");
            s.push_str(&f.to_string());
        }
        s
    }
}
