//! [`OrderEnforcing`]: a `step` (or `render`) before the first `reset` is an error.

use gym_core::{Env, Error, Frame, Info, ResetOptions, Result, Step};

/// Gymnasium's `OrderEnforcing`: `step` before the first `reset` is [`Error::ResetNeeded`],
/// and so is `render` unless render order enforcing is disabled (the same variant; its
/// message names `step()`).
#[derive(Debug, Clone)]
pub struct OrderEnforcing<E> {
    env: E,
    has_reset: bool,
    disable_render_order_enforcing: bool,
}

impl<E: Env> OrderEnforcing<E> {
    /// Wraps `env`, enforcing the order for `step` and `render`.
    pub fn new(env: E) -> Self {
        Self {
            env,
            has_reset: false,
            disable_render_order_enforcing: false,
        }
    }

    /// Wraps `env`; with `disable_render_order_enforcing`, `render` is allowed before `reset`.
    pub fn with_render_order_enforcing(env: E, disable_render_order_enforcing: bool) -> Self {
        Self {
            env,
            has_reset: false,
            disable_render_order_enforcing,
        }
    }

    /// Whether `reset` has been called.
    pub fn has_reset(&self) -> bool {
        self.has_reset
    }
}

impl<E: Env> gym_core::StepWrapper for OrderEnforcing<E> {
    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(E::Obs, Info)> {
        this.has_reset = true;
        this.env.reset(seed, options)
    }

    fn step(this: &mut Self, action: &E::Act) -> Result<Step<E::Obs>> {
        if !this.has_reset {
            return Err(Error::ResetNeeded);
        }
        this.env.step(action)
    }

    /// # Errors
    /// [`Error::ResetNeeded`] before the first `reset` (unless disabled); the inner error.
    fn render(this: &mut Self) -> Result<Option<Frame>> {
        if !this.disable_render_order_enforcing && !this.has_reset {
            return Err(Error::ResetNeeded);
        }
        this.env.render()
    }
}

impl<E: Env> gym_core::Wrapper for OrderEnforcing<E> {
    type Inner = E;
    type Kind = gym_core::Steps;
    fn inner(&self) -> &E {
        &self.env
    }
    fn inner_mut(&mut self) -> &mut E {
        &mut self.env
    }
    fn into_inner(self) -> E {
        self.env
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::DiscreteEnv;

    #[test]
    fn step_and_render_need_a_reset() {
        let mut env = OrderEnforcing::new(DiscreteEnv::new());
        assert_eq!(env.step(&1).unwrap_err(), Error::ResetNeeded);
        assert_eq!(env.render().unwrap_err(), Error::ResetNeeded);
        assert!(!env.has_reset());
        assert_eq!(env.reset(None, None).unwrap().0, 2);
        assert!(env.has_reset());
        assert_eq!(env.step(&1).unwrap().observation, 3);
        assert_eq!(env.render().unwrap(), None);
        let mut lenient = OrderEnforcing::with_render_order_enforcing(DiscreteEnv::new(), true);
        assert_eq!(lenient.render().unwrap(), None);
        assert_eq!(lenient.step(&1).unwrap_err(), Error::ResetNeeded);
    }
}
