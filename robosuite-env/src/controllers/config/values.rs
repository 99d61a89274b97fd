//! The value kinds of robosuite's controller configs: a number or a list of numbers
//! ([`PerAxis`], robosuite's `nums2array`), a `[low, high]` pair of them ([`Bounds`]) and the
//! named options (impedance mode, input type and frame, interpolation).

use gym_core::{Error, Result};
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::{Deserialize, Serialize, Serializer};
use std::fmt;

/// A number or a list of numbers, one per axis (robosuite's `nums2array`): a number stands
/// for the same value on every axis.
#[derive(Debug, Clone, PartialEq)]
pub enum PerAxis {
    /// One value for every axis.
    Scalar(f64),
    /// One value per axis.
    List(Vec<f64>),
}

impl PerAxis {
    /// The values on `dim` axes.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming `key` when a list does not have `dim` values.
    pub fn resolve(&self, dim: usize, key: &str) -> Result<Vec<f64>> {
        match self {
            Self::Scalar(v) => Ok(vec![*v; dim]),
            Self::List(v) if v.len() == dim => Ok(v.clone()),
            Self::List(v) => Err(Error::invalid_argument(
                key,
                format!(
                    "expected a number or a list of {dim} numbers, got a list of {}",
                    v.len()
                ),
            )),
        }
    }

    /// Whether this is a single number (robosuite treats a scalar `kp` of `JOINT_VELOCITY`
    /// differently from a list).
    pub fn is_scalar(&self) -> bool {
        matches!(self, Self::Scalar(_))
    }

    /// Every value given.
    pub fn values(&self) -> &[f64] {
        match self {
            Self::Scalar(v) => std::slice::from_ref(v),
            Self::List(v) => v,
        }
    }
}

impl From<f64> for PerAxis {
    fn from(v: f64) -> Self {
        Self::Scalar(v)
    }
}

impl From<Vec<f64>> for PerAxis {
    fn from(v: Vec<f64>) -> Self {
        Self::List(v)
    }
}

impl<const N: usize> From<[f64; N]> for PerAxis {
    fn from(v: [f64; N]) -> Self {
        Self::List(v.to_vec())
    }
}

impl Serialize for PerAxis {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self {
            Self::Scalar(v) => s.serialize_f64(*v),
            Self::List(v) => v.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for PerAxis {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct PerAxisVisitor;
        impl<'de> Visitor<'de> for PerAxisVisitor {
            type Value = PerAxis;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a number or a list of numbers")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> std::result::Result<PerAxis, E> {
                Ok(PerAxis::Scalar(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> std::result::Result<PerAxis, E> {
                Ok(PerAxis::Scalar(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> std::result::Result<PerAxis, E> {
                Ok(PerAxis::Scalar(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> std::result::Result<PerAxis, A::Error> {
                let mut out = Vec::with_capacity(seq.size_hint().unwrap_or(0));
                while let Some(v) = seq.next_element::<f64>()? {
                    out.push(v);
                }
                Ok(PerAxis::List(out))
            }
        }
        d.deserialize_any(PerAxisVisitor)
    }
}

/// A `[low, high]` pair (robosuite's `kp_limits`, `qpos_limits`, ...), each a number or a
/// list of numbers per axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Bounds(pub PerAxis, pub PerAxis);

impl Bounds {
    /// The same `[low, high]` on every axis.
    pub fn uniform(low: f64, high: f64) -> Self {
        Self(PerAxis::Scalar(low), PerAxis::Scalar(high))
    }

    /// The lows and highs on `dim` axes.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming `key` for lists of the wrong length, NaN, or a low
    /// above its high.
    pub fn resolve(&self, dim: usize, key: &str) -> Result<(Vec<f64>, Vec<f64>)> {
        let lo = self.0.resolve(dim, key)?;
        let hi = self.1.resolve(dim, key)?;
        for (i, (l, h)) in lo.iter().zip(&hi).enumerate() {
            if l.is_nan() || h.is_nan() || l > h {
                return Err(Error::invalid_argument(
                    key,
                    format!("needs low <= high on every axis, got [{l}, {h}] on axis {i}"),
                ));
            }
        }
        Ok((lo, hi))
    }
}

/// How the impedance gains are set (robosuite's `impedance_mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ImpedanceMode {
    /// `kp` and `damping_ratio` come from the configuration.
    #[default]
    Fixed,
    /// Each action starts with the damping ratios, then the stiffnesses.
    Variable,
    /// Each action starts with the stiffnesses; critically damped.
    VariableKp,
}

impl ImpedanceMode {
    /// How many gain vectors (of the controller's gain dimension) each action starts with.
    pub fn gain_vectors(self) -> usize {
        match self {
            Self::Fixed => 0,
            Self::VariableKp => 1,
            Self::Variable => 2,
        }
    }
}

/// Whether actions are changes of the goal or the goal itself (robosuite's `input_type`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InputType {
    /// Actions are scaled and added to the current (achieved) state.
    #[default]
    Delta,
    /// Actions are the goal, unscaled.
    Absolute,
}

/// The frame in which end-effector actions are expressed (robosuite's `input_ref_frame`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InputRefFrame {
    /// The arm's base frame (the `{robot}{arm}_center` site).
    #[default]
    Base,
    /// The world frame.
    World,
}

/// Goal interpolation between env steps (robosuite's `interpolation`: `null` or
/// `"linear"`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Interpolation {
    /// The goal applies from the first substep.
    #[default]
    None,
    /// The goal ramps over `ceil(ramp_ratio · substeps)` substeps (robosuite's
    /// `LinearInterpolator`).
    Linear,
}

impl Serialize for Interpolation {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self {
            Self::None => s.serialize_none(),
            Self::Linear => s.serialize_str("linear"),
        }
    }
}

impl<'de> Deserialize<'de> for Interpolation {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        // robosuite's own files write `null`, and once the string "null" (its factory only
        // tests for "linear").
        match Option::<String>::deserialize(d)?.as_deref() {
            None | Some("null") => Ok(Self::None),
            Some("linear") => Ok(Self::Linear),
            Some(other) => Err(de::Error::custom(format!(
                "unknown interpolation `{other}`, expected null or \"linear\""
            ))),
        }
    }
}
