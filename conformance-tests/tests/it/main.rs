//! The conformance suite's integration tests.
//!
//! One test binary per crate: each binary links MuJoCo once, so merging the test files
//! into modules of one binary saves most of the link time of `make test`.

mod broken_envs;
mod registered_envs;
mod toy_envs;
mod wrapper_stacks;
