//! [`PassiveEnvChecker`]: validates every `reset` and `step` against the environment's
//! spaces and reports violations as typed errors. The checks themselves are gym-core's
//! ([`gym_core::check`]: [`check_space`], [`check_obs`] and the [`gym_core::check::passive`]
//! checks), the same ones conformance-tests' `check_env` runs.

use gym_core::check::{
    Failure, SpaceType, Warning, check_info_types, check_obs, check_render_metadata,
    check_render_return, check_reward, check_space,
};
use gym_core::{DynSpace, Env, Error, Frame, Info, RenderMode, ResetOptions, Result, Step};

/// A failed check as an [`Error::Contract`] naming `check`.
fn contract(check: &str, failure: Failure) -> Error {
    Error::Contract {
        check: check.to_owned(),
        message: failure.message.into(),
    }
}

fn messages(warnings: Vec<Warning>) -> impl Iterator<Item = String> {
    warnings.into_iter().map(|w| w.message)
}

/// A checking layer in the spirit of Gymnasium's `PassiveEnvChecker`, strict where
/// Gymnasium only warns.
///
/// * Construction: both spaces pass Gymnasium's `check_space` (non-empty Dict and Tuple
///   spaces, recursively; [`Error::Contract`] naming `check_space`); degenerate Box bounds
///   are recorded as warnings.
/// * Every `reset` and `step`: the observation passes `check_obs` (structure, dtype that
///   casts safely, finite values, within the space; [`Error::Contract`] naming `reset` or
///   `step`), the reward is finite (`step`), and conventional info keys have their type
///   (`success`, `is_success`, `TimeLimit.truncated` bools; `episode` a map of numeric `r`,
///   `l`, `t`; [`Error::Contract`] naming `info`).
/// * First `reset` and first `step`: `check_obs`'s warnings are recorded (a dtype that
///   differs from the space's but casts safely, as in Gymnasium).
/// * `render`: the render mode must be one of `metadata.render_modes` (none without modes),
///   `render_fps` must be positive when given; a frame of the wrong kind for the mode is an
///   error, a missing frame a warning.
///
/// Warnings are collected in [`PassiveEnvChecker::warnings`]. Actions are not checked,
/// as in Gymnasium.
#[derive(Debug, Clone)]
pub struct PassiveEnvChecker<E> {
    env: E,
    checked_reset: bool,
    checked_step: bool,
    checked_render: bool,
    warnings: Vec<String>,
}

impl<E: Env> PassiveEnvChecker<E> {
    /// Wraps `env` after checking its spaces.
    ///
    /// # Errors
    /// [`Error::Contract`] when a space fails `check_space`.
    pub fn new(env: E) -> Result<Self> {
        let mut warnings = Vec::new();
        for (space, kind) in [
            (env.action_space().to_any(), SpaceType::Action),
            (env.observation_space().to_any(), SpaceType::Observation),
        ] {
            let found = check_space(&space, kind).map_err(|f| contract("check_space", f))?;
            warnings.extend(messages(found));
        }
        Ok(Self {
            env,
            checked_reset: false,
            checked_step: false,
            checked_render: false,
            warnings,
        })
    }

    /// The warnings recorded so far.
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    fn check_obs(&mut self, obs: &E::Obs, method: &str, first: bool) -> Result<()> {
        let space = self.env.observation_space();
        let found = check_obs(&space.to_value(obs), &space.to_any(), method)
            .map_err(|f| contract(method, f))?;
        if first {
            self.warnings.extend(messages(found));
        }
        Ok(())
    }

    fn check_render(&mut self, frame: &Option<Frame>) -> Result<()> {
        let mode = self.env.render_mode();
        let meta = self.env.metadata();
        let found = check_render_metadata(meta, mode).map_err(|f| contract("render", f))?;
        if !self.checked_render {
            self.checked_render = true;
            if meta.render_modes.is_empty() {
                self.warnings.push("No render modes was declared in the environment (env.metadata['render_modes'] is empty)".into());
            }
            self.warnings.extend(messages(found));
        }
        match (mode, frame) {
            (None, None) => Ok(()),
            (None, Some(_)) => {
                self.warnings
                    .push("render() returned a frame but the render mode is None".into());
                Ok(())
            }
            (Some(m), frame) => match check_render_return(m, frame.as_ref()) {
                None => Ok(()),
                // Strict where Gymnasium warns: a frame of the wrong kind is an error.
                Some(w) if frame.is_some() && m != RenderMode::Human => Err(Error::Contract {
                    check: "render".to_owned(),
                    message: w.message.into(),
                }),
                Some(w) => {
                    self.warnings.push(w.message);
                    Ok(())
                }
            },
        }
    }
}

impl<E: Env> gym_core::StepWrapper for PassiveEnvChecker<E> {
    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(E::Obs, Info)> {
        let (obs, info) = this.env.reset(seed, options)?;
        let first = !this.checked_reset;
        this.checked_reset = true;
        this.check_obs(&obs, "reset", first)?;
        check_info_types(&info, "reset").map_err(|f| contract("info", f))?;
        Ok((obs, info))
    }

    fn step(this: &mut Self, action: &E::Act) -> Result<Step<E::Obs>> {
        let step = this.env.step(action)?;
        let first = !this.checked_step;
        this.checked_step = true;
        this.check_obs(&step.observation, "step", first)?;
        check_reward(step.reward).map_err(|f| contract("step", f))?;
        check_info_types(&step.info, "step").map_err(|f| contract("info", f))?;
        Ok(step)
    }

    fn render(this: &mut Self) -> Result<Option<Frame>> {
        let frame = this.env.render()?;
        this.check_render(&frame)?;
        Ok(frame)
    }
}

impl<E: Env> gym_core::Wrapper for PassiveEnvChecker<E> {
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
    use crate::toy::{CountEnv, ScriptEnv, a32, script_f32, unit_actions};
    use gym_core::Value;
    use gym_core::spaces::{AnySpace, BoxSpace, DictSpace, TupleSpace};
    use gym_core::{ArrayValue, IntoBoxedEnv};

    #[test]
    fn a_well_behaved_env_passes() {
        let mut env = PassiveEnvChecker::new(CountEnv::new(Some(3), None)).unwrap();
        env.reset(Some(0), None).unwrap();
        for _ in 0..3 {
            let _ = env.step(&0).unwrap();
        }
        assert!(env.warnings().is_empty());
        assert_eq!(env.render().unwrap(), None);
        assert_eq!(env.warnings().len(), 1); // no render modes declared
    }

    #[test]
    fn observations_outside_the_space_are_errors_on_every_call() {
        // CountEnv's Box is [0, 1000]; a script with an out-of-space third observation.
        let inner = ScriptEnv::new(
            BoxSpace::<f32>::uniform(0.0, 1.0, &[1]).unwrap(),
            unit_actions(),
            vec![a32(&[0.5]), a32(&[0.2]), a32(&[2.0])],
            vec![0.0],
        );
        let mut env = PassiveEnvChecker::new(inner).unwrap();
        env.reset(None, None).unwrap();
        assert!(env.step(&a32(&[0.0, 0.0])).is_ok());
        let err = env.step(&a32(&[0.0, 0.0])).unwrap_err();
        assert!(
            matches!(&err, Error::Contract { check, .. } if check == "step"),
            "{err}"
        );
    }

    #[test]
    fn rewards_and_info_types() {
        let nan = script_f32(&[&[0.0]], &[f64::NAN]);
        let mut env = PassiveEnvChecker::new(nan).unwrap();
        env.reset(None, None).unwrap();
        assert!(matches!(
            env.step(&a32(&[0.0, 0.0])),
            Err(Error::Contract { .. })
        ));
        let bad_info =
            script_f32(&[&[0.0]], &[1.0]).with_step_info(Info::new().with("success", 1.0));
        let mut env = PassiveEnvChecker::new(bad_info).unwrap();
        env.reset(None, None).unwrap();
        assert!(
            matches!(env.step(&a32(&[0.0, 0.0])), Err(Error::Contract { check, .. }) if check == "info")
        );
    }

    #[test]
    fn space_checks_and_dtype_warnings() {
        let empty = ScriptEnv::new(
            DictSpace::new(Vec::<(String, AnySpace)>::new()).unwrap(),
            unit_actions(),
            vec![Default::default()],
            vec![0.0],
        );
        assert!(matches!(
            PassiveEnvChecker::new(empty),
            Err(Error::Contract { .. })
        ));
        let empty_tuple = ScriptEnv::new(
            TupleSpace::new(vec![]),
            unit_actions(),
            vec![vec![]],
            vec![0.0],
        );
        assert!(PassiveEnvChecker::new(empty_tuple).is_err());
        // A boxed env returning float32 for a float64 Box: contained, but warned about.
        let inner = ScriptEnv::new(
            AnySpace::from(BoxSpace::<f64>::unbounded(&[1])),
            unit_actions(),
            vec![Value::Array(ArrayValue::F32(a32(&[1.0])))],
            vec![0.0],
        );
        let mut env = PassiveEnvChecker::new(inner.boxed()).unwrap();
        env.reset(None, None).unwrap();
        assert_eq!(env.warnings().len(), 1, "{:?}", env.warnings());
    }
}
