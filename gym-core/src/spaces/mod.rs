//! The spaces: Box, Discrete, MultiDiscrete, MultiBinary, Dict and Tuple, and their
//! dynamic forms; and what wrappers and vector environments ask of them beyond [`Space`],
//! [`Flatten`] and [`DynSpace`]: [`numeric`] (bounded arrays), [`batch`] (stacking
//! elements, as `gymnasium.vector.utils`) and [`filter`] (selecting Dict keys or Tuple
//! items). Each is implemented once per typed space; [`AnySpace`] delegates to the space it
//! holds.
//!
//! [`Space`]: crate::Space
//! [`Flatten`]: crate::Flatten
//! [`DynSpace`]: crate::DynSpace

#[macro_use]
mod any;
pub mod batch;
mod box_space;
mod dict;
mod discrete;
pub mod filter;
mod multi_binary;
mod multi_discrete;
pub mod numeric;
mod tuple;

pub use any::{AnyBox, AnySpace};
pub(crate) use any::{concat_flat_spaces, split_flat};
pub use batch::{BatchOf, BatchSpace};
pub use box_space::BoxSpace;
pub use dict::DictSpace;
pub use discrete::Discrete;
pub use filter::{FilterKeys, FilterableSpace};
pub use multi_binary::MultiBinary;
pub use multi_discrete::MultiDiscrete;
pub use numeric::{ArraySpec, NumericSpace};
pub use tuple::TupleSpace;
