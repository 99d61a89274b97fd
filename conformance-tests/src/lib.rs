//! Conformance checks for gym-core environments.
