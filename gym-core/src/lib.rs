//! Gymnasium's environment API in Rust.
//!
//! * [`Space`] and the spaces in [`spaces`] (Box, Discrete, MultiDiscrete, MultiBinary,
//!   Dict, Tuple) with seeded sampling and `contains`; Gymnasium's flatten / unflatten
//!   ([`Flatten`], [`flatten`], [`unflatten`]) and the conversion to dynamic values
//!   ([`DynSpace`]) beside it.
//! * [`Env`] and [`Wrapper`]: typed environments and owned wrapper stacks with Gymnasium
//!   1.x semantics (`reset(seed, options)`, `step` → [`Step`] with `terminated` and
//!   `truncated` apart, a typed [`Info`]). Wrappers are observation, action, reward or step
//!   wrappers ([`ObservationWrapper`], ...) as in Gymnasium and get `Env` from their kind.
//! * The dynamic layer ([`DynEnv`], [`BoxedEnv`], [`Value`], [`AnySpace`]) and the
//!   [`registry`], so any typed env can be boxed, made by id, and exported to Python.
//! * Typed errors ([`Error`], [`SpaceError`]).
//! * Gymnasium's passive environment checks on spaces and values ([`check`]), which the
//!   `PassiveEnvChecker` wrapper and conformance-tests' `check_env` apply.
//! * With the `proptest-support` feature, proptest strategies for every space and its
//!   elements (values that shrink) in the `proptest` module.
//!
//! ```
//! use gym_core::{flatten, rng_from_seed, spaces::{BoxSpace, Discrete}, Space};
//!
//! let b = BoxSpace::<f32>::uniform(-1.0, 1.0, &[3])?;
//! let x = b.sample(&mut rng_from_seed(42));
//! assert!(b.contains(&x));
//! let d = Discrete::new(4)?;
//! assert_eq!(flatten(&d, &2)?.to_f64_vec(), [0.0, 0.0, 1.0, 0.0]);
//! # Ok::<(), gym_core::SpaceError>(())
//! ```

pub mod check;
pub mod dtype;
pub mod dynamic;
pub mod env;
pub mod error;
pub mod info;
#[cfg(feature = "proptest-support")]
pub mod proptest;
pub mod registry;
pub mod rng;
pub mod row;
pub mod space;
pub mod spaces;
pub mod value;
pub mod wrapper;

pub use dtype::{DType, Scalar};
pub use dynamic::{BoxedEnv, DynAdapter, DynEnv, IntoBoxedEnv};
pub use env::{AsAny, Env, EnvExt, Frame, Metadata, RenderMode, Step, Transition};
pub use error::{Error, Result, SpaceError};
pub use info::{Info, InfoValue, ResetOptions};
pub use rng::{EnvRng, entropy_seed, rng_from_seed};
pub use row::{MAX_ROW_LEAVES, ObsRow, Pick, RowLeaf, RowLeaves};
pub use space::{DynSpace, Flatten, Space, flatdim, flatten, flatten_space, unflatten};
pub use spaces::{
    AnyBox, AnySpace, BoxSpace, DictSpace, Discrete, MultiBinary, MultiDiscrete, TupleSpace,
};
pub use value::{ArrayElement, ArrayValue, DictValue, Value};
pub use wrapper::{
    ActionWrapper, Actions, Custom, CustomWrapper, ObservationWrapper, Observations, RewardWrapper,
    Rewards, StepWrapper, Steps, Wrapper, WrapperKind,
};
