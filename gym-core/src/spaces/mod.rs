//! The spaces: Box, Discrete, MultiDiscrete, MultiBinary, Dict and Tuple, and their
//! dynamic forms.

mod any;
mod box_space;
mod dict;
mod discrete;
mod multi_binary;
mod multi_discrete;
mod tuple;

pub use any::{AnyBox, AnySpace};
pub(crate) use any::{concat_flat_spaces, split_flat};
pub use box_space::BoxSpace;
pub use dict::DictSpace;
pub use discrete::Discrete;
pub use multi_binary::MultiBinary;
pub use multi_discrete::MultiDiscrete;
pub use tuple::TupleSpace;
