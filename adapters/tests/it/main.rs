//! The adapters' integration tests (`vector_no_alloc` stays a binary of its own: it counts allocations).
//!
//! One test binary per crate: each binary links MuJoCo once, so merging the test files
//! into modules of one binary saves most of the link time of `make test`.

#[path = "../common/mod.rs"]
mod common;

mod cameras;
mod lift;
mod pool;
mod stack;
mod vector;
mod vector_dynamic;
mod vector_reliability;
