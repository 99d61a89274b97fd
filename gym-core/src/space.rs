//! What spaces are, in three parts as Gymnasium has them: the [`Space`] trait (sampling,
//! membership, shape), flattening ([`Flatten`] and the free functions [`flatten`],
//! [`unflatten`], [`flatdim`], [`flatten_space`], as `gymnasium.spaces.flatten` and friends)
//! and the conversion to the dynamic layer ([`DynSpace`]).

use crate::dtype::DType;
use crate::error::SpaceError;
use crate::spaces::{AnyBox, AnySpace};
use crate::value::{ArrayValue, Value};
use std::fmt::Debug;

/// A set of valid observations or actions, as Gymnasium's `gymnasium.spaces.Space`.
///
/// Sampling takes the RNG explicitly (use [`EnvRng`](crate::EnvRng) from
/// [`rng_from_seed`](crate::rng_from_seed) for reproducible samples); a space holds no RNG of
/// its own, so sampling never mutates it and the same seed always gives the same samples.
pub trait Space: Clone + Debug + PartialEq + Send + Sync + 'static {
    /// The Rust type of one element.
    type Element: Clone + Debug + PartialEq + Send + Sync + 'static;

    /// Draws one element, as Gymnasium's `sample()` does (see each space for the law).
    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> Self::Element;

    /// Whether `x` is an element (`x in space`).
    fn contains(&self, x: &Self::Element) -> bool;

    /// The shape of an element, for spaces whose elements are arrays or scalars.
    fn shape(&self) -> Option<&[usize]>;
}

/// Flattening a space's elements to one-dimensional arrays, as Gymnasium's
/// `gymnasium.spaces.utils` functions (which [`flatten`], [`unflatten`], [`flatdim`] and
/// [`flatten_space`] name).
pub trait Flatten: Space {
    /// The length of the flattened element (`gymnasium.spaces.flatdim`).
    fn flatdim(&self) -> usize;

    /// The dtype of the flattened element.
    fn flat_dtype(&self) -> DType;

    /// Flattens an element to one dimension (`gymnasium.spaces.flatten`): Discrete becomes a
    /// one-hot, Dict concatenates in its key order.
    ///
    /// # Errors
    /// When `x` does not have the structure of the space.
    fn flatten(&self, x: &Self::Element) -> Result<ArrayValue, SpaceError>;

    /// [`Flatten::flatten`] into `out`, reusing its storage when it already is a vector of
    /// the flat dtype and length (Box and Dict spaces of arrays then allocate nothing); the
    /// default allocates.
    ///
    /// # Errors
    /// As [`Flatten::flatten`].
    fn flatten_into(&self, x: &Self::Element, out: &mut ArrayValue) -> Result<(), SpaceError> {
        *out = self.flatten(x)?;
        Ok(())
    }

    /// Inverts [`Flatten::flatten`] (`gymnasium.spaces.unflatten`).
    ///
    /// # Errors
    /// When `flat` has the wrong length, or a one-hot part has no set entry.
    fn unflatten(&self, flat: &ArrayValue) -> Result<Self::Element, SpaceError>;

    /// The Box that flattened elements lie in (`gymnasium.spaces.flatten_space`).
    fn flatten_space(&self) -> AnyBox;
}

/// A space seen through the dynamic layer: itself as an [`AnySpace`], its elements as
/// [`Value`]s (what registries, boxed environments and the Python export use).
pub trait DynSpace: Space {
    /// This space as the dynamic [`AnySpace`].
    fn to_any(&self) -> AnySpace;

    /// Converts an element to a dynamic [`Value`].
    fn to_value(&self, x: &Self::Element) -> Value;

    /// Converts an owned element to a dynamic [`Value`], moving it where the element already
    /// is one (Dict, Tuple and dynamic spaces); the default copies it.
    #[allow(clippy::wrong_self_convention)]
    fn into_value(&self, x: Self::Element) -> Value {
        self.to_value(&x)
    }

    /// [`DynSpace::to_value`] into `out`, reusing its storage where it has the same
    /// structure (see [`Value::assign_from`]); the default allocates.
    fn to_value_into(&self, x: &Self::Element, out: &mut Value) {
        *out = self.to_value(x);
    }

    /// Converts a dynamic [`Value`] to an element, checking structure and dtype (safe casts
    /// only) but not bounds; use [`Space::contains`] for that.
    ///
    /// # Errors
    /// When the value has another kind, shape or an unsafe dtype.
    #[allow(clippy::wrong_self_convention)]
    fn from_value(&self, v: &Value) -> Result<Self::Element, SpaceError>;
}

/// `gymnasium.spaces.flatten(space, x)`: see [`Flatten::flatten`].
///
/// # Errors
/// When `x` does not have the structure of the space.
pub fn flatten<S: Flatten>(space: &S, x: &S::Element) -> Result<ArrayValue, SpaceError> {
    space.flatten(x)
}

/// `gymnasium.spaces.unflatten(space, flat)`: see [`Flatten::unflatten`].
///
/// # Errors
/// When `flat` has the wrong length, or a one-hot part has no set entry.
pub fn unflatten<S: Flatten>(space: &S, flat: &ArrayValue) -> Result<S::Element, SpaceError> {
    space.unflatten(flat)
}

/// `gymnasium.spaces.flatdim(space)`: see [`Flatten::flatdim`].
pub fn flatdim<S: Flatten>(space: &S) -> usize {
    space.flatdim()
}

/// `gymnasium.spaces.flatten_space(space)`: see [`Flatten::flatten_space`].
pub fn flatten_space<S: Flatten>(space: &S) -> AnyBox {
    space.flatten_space()
}
