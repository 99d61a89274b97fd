//! The [`Wrapper`] trait: an environment that owns another and changes part of its
//! behaviour, as Gymnasium's `gymnasium.Wrapper`.

use crate::env::Env;

/// An environment layered over an inner one it owns. A stack of wrappers is a plain owned
/// value (`TimeLimit<FlattenObservation<Lift>>`), `Send` when the innermost env is.
pub trait Wrapper: Env {
    /// The wrapped environment's type.
    type Inner: Env;

    /// The wrapped environment.
    fn inner(&self) -> &Self::Inner;

    /// The wrapped environment, mutably.
    fn inner_mut(&mut self) -> &mut Self::Inner;

    /// Takes the wrapper apart, returning the wrapped environment.
    fn into_inner(self) -> Self::Inner
    where
        Self: Sized;

    /// The innermost environment, if it has type `T` (Gymnasium's `env.unwrapped`).
    fn unwrapped<T: 'static>(&self) -> Option<&T>
    where
        Self: Sized,
    {
        self.unwrapped_any().downcast_ref()
    }
}

/// Forwards the parts of [`Env`] a wrapper usually leaves alone (metadata, rendering,
/// close, RNG, `unwrapped`) to `self.inner()`. Use it inside `impl Env for MyWrapper`.
///
/// The wrapper must implement [`Wrapper`].
#[macro_export]
macro_rules! forward_env {
    () => {
        fn metadata(&self) -> &$crate::Metadata {
            $crate::Wrapper::inner(self).metadata()
        }
        fn render_mode(&self) -> Option<$crate::RenderMode> {
            $crate::Wrapper::inner(self).render_mode()
        }
        fn render(&mut self) -> $crate::Result<Option<$crate::Frame>> {
            $crate::Wrapper::inner_mut(self).render()
        }
        fn close(&mut self) {
            $crate::Wrapper::inner_mut(self).close()
        }
        fn rng(&self) -> Option<&$crate::EnvRng> {
            $crate::Wrapper::inner(self).rng()
        }
        fn unwrapped_any(&self) -> &dyn ::std::any::Any {
            $crate::Wrapper::inner(self).unwrapped_any()
        }
        fn unwrapped_any_mut(&mut self) -> &mut dyn ::std::any::Any {
            $crate::Wrapper::inner_mut(self).unwrapped_any_mut()
        }
    };
}
