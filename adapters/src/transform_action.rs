//! [`TransformAction`]: actions mapped by a closure before stepping.

use gym_core::{ActionWrapper, Actions, DynSpace, Env, Flatten, Result, Space, Wrapper};

/// Gymnasium's `TransformAction(env, func, action_space)`: the wrapper accepts actions of
/// `action_space` and steps the inner environment with `func(action)`.
/// [`TransformAction::keep_space`] keeps the inner space (Gymnasium's `action_space=None`).
pub struct TransformAction<E, F, S> {
    env: E,
    func: F,
    space: S,
}

impl<E: Env, F, S: Space> TransformAction<E, F, S>
where
    F: FnMut(&S::Element) -> E::Act + Send + 'static,
{
    /// Wraps `env`: actions from `action_space` are mapped by `func`.
    pub fn new(env: E, func: F, action_space: S) -> Self {
        Self {
            env,
            func,
            space: action_space,
        }
    }
}

impl<E: Env, F> TransformAction<E, F, E::ActSpace>
where
    F: FnMut(&E::Act) -> E::Act + Send + 'static,
{
    /// Wraps `env`, mapping actions by `func` and keeping the action space.
    pub fn keep_space(env: E, func: F) -> Self {
        let space = env.action_space().clone();
        Self { env, func, space }
    }
}

impl<E: std::fmt::Debug, F, S: std::fmt::Debug> std::fmt::Debug for TransformAction<E, F, S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TransformAction")
            .field("env", &self.env)
            .field("space", &self.space)
            .finish_non_exhaustive()
    }
}

impl<E: Env, F, S: Space> Wrapper for TransformAction<E, F, S>
where
    F: FnMut(&S::Element) -> E::Act + Send + 'static,
    S: Flatten + DynSpace,
{
    type Inner = E;
    type Kind = Actions;
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

impl<E: Env, F, S: Space> ActionWrapper for TransformAction<E, F, S>
where
    F: FnMut(&S::Element) -> E::Act + Send + 'static,
    S: Flatten + DynSpace,
{
    type Space = S;

    fn space(&self) -> &S {
        &self.space
    }

    fn action(&mut self, action: &S::Element) -> Result<E::Act> {
        Ok((self.func)(action))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{DiscreteEnv, a32};
    use gym_core::spaces::BoxSpace;
    use ndarray::ArrayD;

    #[test]
    fn continuous_to_discrete() {
        let space = BoxSpace::<f32>::uniform(-1.0, 1.0, &[1]).unwrap();
        let mut env = TransformAction::new(
            DiscreteEnv::new(),
            |a: &ArrayD<f32>| i64::from(a[[0]] > 0.0),
            space,
        );
        env.reset(None, None).unwrap();
        assert_eq!(env.step(&a32(&[0.7])).unwrap().observation, 3);
        assert_eq!(env.step(&a32(&[-0.2])).unwrap().observation, 2);
        let mut flipped = TransformAction::keep_space(DiscreteEnv::new(), |a| 1 - a);
        flipped.reset(None, None).unwrap();
        assert_eq!(flipped.step(&1).unwrap().observation, 1);
    }
}
