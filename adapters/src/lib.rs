//! Composable Gymnasium wrappers and vector environments.
