//! [`ClipAction`]: actions clipped into the environment's Box before stepping.

use crate::numeric::NumericSpace;
use gym_core::{ActionWrapper, Actions, Env, Error, Result, Wrapper};
use ndarray::{ArrayD, IxDyn};

/// Gymnasium's `ClipAction`: the action space becomes `Box(-inf, inf, shape, dtype)` and
/// each action is `np.clip(action, low, high)` of the inner Box before it is passed on.
///
/// For unsigned dtypes, which cannot hold `-inf`, the wrapper's space keeps the dtype's
/// full range.
#[derive(Debug, Clone)]
pub struct ClipAction<E: Env> {
    env: E,
    space: E::ActSpace,
}

impl<E: Env> ClipAction<E>
where
    E::ActSpace: NumericSpace,
{
    /// Wraps `env`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the action space is not a Box.
    pub fn new(env: E) -> Result<Self> {
        let inner = env.action_space();
        if !inner.is_box() {
            return Err(Error::invalid_argument(
                "env",
                format!("ClipAction needs a Box action space, got {inner:?}"),
            ));
        }
        let spec = inner.array_spec()?;
        let unbounded = |v: f64| ArrayD::from_elem(IxDyn(&spec.shape), v);
        let space = if spec.dtype == gym_core::DType::U8 {
            inner.with_bounds(unbounded(0.0), unbounded(255.0))?
        } else {
            inner.with_bounds(unbounded(f64::NEG_INFINITY), unbounded(f64::INFINITY))?
        };
        Ok(Self { env, space })
    }
}

impl<E: Env> Wrapper for ClipAction<E>
where
    E::ActSpace: NumericSpace,
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

impl<E: Env> ActionWrapper for ClipAction<E>
where
    E::ActSpace: NumericSpace,
{
    type Space = E::ActSpace;

    fn space(&self) -> &E::ActSpace {
        &self.space
    }

    fn action(&mut self, action: &E::Act) -> Result<E::Act> {
        self.env
            .action_space()
            .clip_element(action)
            .map_err(Error::into_invalid_action)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{DiscreteEnv, ScriptEnv, WalkEnv, a32, script_f32};
    use gym_core::{BoxSpace, EnvExt, IntoBoxedEnv, Space, Value};

    #[test]
    fn clips_into_the_inner_bounds() {
        let mut env = ClipAction::new(script_f32(&[&[0.0]], &[0.0])).unwrap();
        assert_eq!(
            env.action_space().to_string(),
            "Box(-inf, inf, [2], float32)"
        );
        env.reset(None, None).unwrap();
        let _ = env.step(&a32(&[5.0, -2.0])).unwrap();
        let _ = env.step(&a32(&[0.25, -0.5])).unwrap();
        let inner = env
            .unwrapped_as::<ScriptEnv<BoxSpace<f32>, BoxSpace<f32>>>()
            .unwrap();
        assert_eq!(inner.actions, vec![a32(&[1.0, -1.0]), a32(&[0.25, -0.5])]);
    }

    #[test]
    fn works_on_boxed_envs_and_rejects_non_boxes() {
        let mut env = ClipAction::new(WalkEnv::new(3).boxed()).unwrap();
        env.reset(Some(0), None).unwrap();
        assert!(env.step(&Value::from(a32(&[9.0, 9.0]))).is_ok());
        assert!(env.action_space().contains(&Value::from(a32(&[9.0, 9.0]))));
        assert!(matches!(
            ClipAction::new(DiscreteEnv::new()),
            Err(Error::InvalidArgument { .. })
        ));
    }
}
