//! Helpers of the measurement programs in this folder (`benchmark`, `step_count`).

pub mod barrier_model;
pub mod case;
pub mod physics_only;
