//! Space checks: Gymnasium's `check_space` (passive_env_checker) and `check_space_limit`
//! (env_checker), recursing into Tuple and Dict.
//!
//! gym-core's constructors already reject most malformed spaces (bounds of another shape,
//! `low > high`, `Discrete(0)`, a zero `nvec` entry, a zero MultiBinary dimension), so on
//! spaces built through them only the empty Tuple and Dict assertions can fail; the other
//! assertions are still made, so a space that reached this crate some other way is
//! caught.

use super::report::{Check, Failure, Warning, WarningKind};
use crate::{AnyBox, AnySpace, Space};
use std::fmt;

/// Whether a space is the observation or the action space (Gymnasium's `space_type`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SpaceType {
    /// The observation space.
    Observation,
    /// The action space.
    Action,
}

impl SpaceType {
    /// `"observation"` or `"action"`.
    pub fn as_str(self) -> &'static str {
        match self {
            SpaceType::Observation => "observation",
            SpaceType::Action => "action",
        }
    }

    /// The check that validates this kind of space.
    pub fn check(self) -> Check {
        match self {
            SpaceType::Observation => Check::ObservationSpace,
            SpaceType::Action => Check::ActionSpace,
        }
    }
}

impl fmt::Display for SpaceType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

fn located(path: &str) -> String {
    if path.is_empty() {
        String::new()
    } else {
        format!(" (at {path})")
    }
}

/// Gymnasium's `check_space(space, space_type)`: asserts the structure of the space and
/// warns about degenerate Box bounds.
///
/// * Box: the bound shapes equal the space's shape; a warning when some `low == high`
///   ("A Box {type} space maximum and minimum values are equal."), and for observation
///   spaces otherwise a warning when some `high < low`.
/// * Discrete: `n > 0` and shape `()`. MultiDiscrete: every `nvec > 0`. MultiBinary: every
///   dimension `> 0`.
/// * Tuple and Dict: non-empty ("An empty Dict {type} space is not allowed."), then every
///   subspace.
///
/// # Errors
/// The first violated assertion, as a failure of [`Check::ObservationSpace`] or
/// [`Check::ActionSpace`].
pub fn check_space(space: &AnySpace, space_type: SpaceType) -> Result<Vec<Warning>, Failure> {
    let mut warnings = Vec::new();
    walk_space(space, space_type, "", &mut warnings)?;
    Ok(warnings)
}

fn walk_space(
    space: &AnySpace,
    ty: SpaceType,
    path: &str,
    warnings: &mut Vec<Warning>,
) -> Result<(), Failure> {
    let fail = |m: String| Err(Failure::new(ty.check(), format!("{m}{}", located(path))));
    match space {
        AnySpace::Box(b) => check_box(b, ty, path, warnings),
        AnySpace::Discrete(d) => {
            if d.n() <= 0 {
                return fail(format!(
                    "Discrete {ty} space's number of elements must be positive, actual number of elements: {}",
                    d.n()
                ));
            }
            if d.shape() != Some(&[]) {
                return fail(format!(
                    "Discrete {ty} space's shape should be empty, actual shape: {:?}",
                    d.shape()
                ));
            }
            Ok(())
        }
        AnySpace::MultiDiscrete(m) => {
            if m.shape() != Some(m.nvec().shape()) {
                return fail(format!(
                    "Multi-discrete {ty} space's shape must be equal to the nvec shape, space shape: {:?}, nvec shape: {:?}",
                    m.shape(),
                    m.nvec().shape()
                ));
            }
            if m.nvec().iter().any(|&n| n <= 0) {
                return fail(format!(
                    "Multi-discrete {ty} space's all nvec elements must be greater than 0, actual nvec: {:?}",
                    m.nvec().iter().collect::<Vec<_>>()
                ));
            }
            Ok(())
        }
        AnySpace::MultiBinary(m) => {
            let shape = m.shape().unwrap_or(&[]);
            if shape.is_empty() || shape.contains(&0) {
                return fail(format!(
                    "Multi-binary {ty} space's all shape elements must be greater than 0, actual shape: {shape:?}"
                ));
            }
            Ok(())
        }
        AnySpace::Tuple(t) => {
            if t.is_empty() {
                return fail(format!("An empty Tuple {ty} space is not allowed."));
            }
            for (i, s) in t.spaces().iter().enumerate() {
                walk_space(s, ty, &format!("{path}[{i}]"), warnings)?;
            }
            Ok(())
        }
        AnySpace::Dict(d) => {
            if d.is_empty() {
                return fail(format!("An empty Dict {ty} space is not allowed."));
            }
            for (k, s) in d.iter() {
                walk_space(s, ty, &format!("{path}[{k:?}]"), warnings)?;
            }
            Ok(())
        }
    }
}

fn check_box(
    b: &AnyBox,
    ty: SpaceType,
    path: &str,
    warnings: &mut Vec<Warning>,
) -> Result<(), Failure> {
    let (low, high) = b.bounds_f64();
    let shape = b.shape().unwrap_or(&[]);
    if low.shape() != shape {
        return Err(Failure::new(
            ty.check(),
            format!(
                "The Box {ty} space shape and low shape have different shapes, low shape: {:?}, box shape: {shape:?}{}",
                low.shape(),
                located(path)
            ),
        ));
    }
    if high.shape() != shape {
        return Err(Failure::new(
            ty.check(),
            format!(
                "The Box {ty} space shape and high shape have different shapes, high shape: {:?}, box shape: {shape:?}{}",
                high.shape(),
                located(path)
            ),
        ));
    }
    let equal: Vec<usize> = low
        .iter()
        .zip(high.iter())
        .enumerate()
        .filter(|(_, (l, h))| l == h)
        .map(|(i, _)| i)
        .collect();
    if !equal.is_empty() {
        warnings.push(Warning::new(
            WarningKind::BoxLowEqualsHigh,
            format!(
                "A Box {ty} space maximum and minimum values are equal{}. Actual equal coordinates (flat): {equal:?}",
                located(path)
            ),
        ));
    } else if ty == SpaceType::Observation && low.iter().zip(high.iter()).any(|(l, h)| h < l) {
        // Unreachable through gym-core's constructors, kept for parity with Gymnasium.
        warnings.push(Warning::new(
            WarningKind::BoxHighBelowLow,
            format!(
                "A Box {ty} space low value is greater than a high value{}.",
                located(path)
            ),
        ));
    }
    Ok(())
}

/// Gymnasium's `check_space_limit(space, space_type)`: warnings only, recursing into Tuple
/// and Dict.
///
/// * A floating-point Box with a `-inf` lower bound: "A Box {type} space minimum value is
///   -infinity. This is probably too low." (Gymnasium compares the stored bounds with
///   ±inf, which an integer Box never holds, so integer Boxes never warn.)
/// * The same for `+inf` upper bounds ("... maximum value is infinity. This is probably
///   too high.").
/// * A one-dimensional Box action space with some `low != 0 && |low| != |high|`, some
///   `low < -1` or some `high > 1`: "For Box action spaces, we recommend using a symmetric
///   and normalized space (range=[-1, 1] or [0, 1])."
pub fn check_space_limit(space: &AnySpace, space_type: SpaceType) -> Vec<Warning> {
    let mut warnings = Vec::new();
    walk_limit(space, space_type, "", &mut warnings);
    warnings
}

fn walk_limit(space: &AnySpace, ty: SpaceType, path: &str, warnings: &mut Vec<Warning>) {
    match space {
        AnySpace::Box(b) => {
            let (low, high) = b.bounds_f64();
            if b.dtype().is_float() {
                if low.iter().any(|&l| l == f64::NEG_INFINITY) {
                    warnings.push(Warning::new(
                        WarningKind::BoxUnboundedBelow,
                        format!("A Box {ty} space minimum value is -infinity. This is probably too low.{}", located(path)),
                    ));
                }
                if high.iter().any(|&h| h == f64::INFINITY) {
                    warnings.push(Warning::new(
                        WarningKind::BoxUnboundedAbove,
                        format!("A Box {ty} space maximum value is infinity. This is probably too high.{}", located(path)),
                    ));
                }
            }
            let one_dimensional = b.shape().is_some_and(|s| s.len() == 1);
            if ty == SpaceType::Action && one_dimensional {
                let asymmetric = low
                    .iter()
                    .zip(high.iter())
                    .any(|(&l, &h)| l != 0.0 && l.abs() != h.abs());
                if asymmetric || low.iter().any(|&l| l < -1.0) || high.iter().any(|&h| h > 1.0) {
                    warnings.push(Warning::new(
                        WarningKind::ActionSpaceNotNormalized,
                        format!(
                            "For Box action spaces, we recommend using a symmetric and normalized space (range=[-1, 1] or [0, 1]). \
                             See https://stable-baselines3.readthedocs.io/en/master/guide/rl_tips.html for more information.{}",
                            located(path)
                        ),
                    ));
                }
            }
        }
        AnySpace::Tuple(t) => {
            for (i, s) in t.spaces().iter().enumerate() {
                walk_limit(s, ty, &format!("{path}[{i}]"), warnings);
            }
        }
        AnySpace::Dict(d) => {
            for (k, s) in d.iter() {
                walk_limit(s, ty, &format!("{path}[{k:?}]"), warnings);
            }
        }
        AnySpace::Discrete(_) | AnySpace::MultiDiscrete(_) | AnySpace::MultiBinary(_) => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BoxSpace, DictSpace, Discrete, TupleSpace};

    fn bx(low: f64, high: f64) -> AnySpace {
        BoxSpace::<f32>::uniform(low, high, &[2]).unwrap().into()
    }

    #[test]
    fn empty_composites_fail() {
        let d = AnySpace::Dict(DictSpace::new(Vec::<(String, AnySpace)>::new()).unwrap());
        let f = check_space(&d, SpaceType::Observation).unwrap_err();
        assert_eq!(f.check, Check::ObservationSpace);
        assert_eq!(f.message, "An empty Dict observation space is not allowed.");
        let t = AnySpace::Tuple(TupleSpace::new(vec![
            bx(0.0, 1.0),
            AnySpace::Tuple(TupleSpace::new(vec![])),
        ]));
        let f = check_space(&t, SpaceType::Action).unwrap_err();
        assert_eq!(f.check, Check::ActionSpace);
        assert_eq!(
            f.message,
            "An empty Tuple action space is not allowed. (at [1])"
        );
    }

    #[test]
    fn box_warnings() {
        let w = check_space(&bx(1.0, 1.0), SpaceType::Observation).unwrap();
        assert_eq!(w[0].kind, WarningKind::BoxLowEqualsHigh);
        assert!(
            check_space(&bx(0.0, 1.0), SpaceType::Action)
                .unwrap()
                .is_empty()
        );
        let kinds = |s: &AnySpace, t| {
            check_space_limit(s, t)
                .into_iter()
                .map(|w| w.kind)
                .collect::<Vec<_>>()
        };
        assert_eq!(
            kinds(
                &bx(f64::NEG_INFINITY, f64::INFINITY),
                SpaceType::Observation
            ),
            [
                WarningKind::BoxUnboundedBelow,
                WarningKind::BoxUnboundedAbove
            ]
        );
        assert_eq!(
            kinds(&bx(-2.0, 2.0), SpaceType::Action),
            [WarningKind::ActionSpaceNotNormalized]
        );
        assert!(kinds(&bx(-2.0, 2.0), SpaceType::Observation).is_empty());
        assert!(kinds(&bx(0.0, 1.0), SpaceType::Action).is_empty());
        assert!(kinds(&bx(-0.5, 0.5), SpaceType::Action).is_empty());
        assert_eq!(
            kinds(&bx(-1.0, 0.5), SpaceType::Action),
            [WarningKind::ActionSpaceNotNormalized]
        );
        let int_unbounded: AnySpace = BoxSpace::<i64>::unbounded(&[2]).into();
        assert!(kinds(&int_unbounded, SpaceType::Observation).is_empty());
        assert!(
            check_space(
                &AnySpace::Discrete(Discrete::new(3).unwrap()),
                SpaceType::Action
            )
            .is_ok()
        );
    }
}
