//! [`PassiveEnvChecker`]: validates every `reset` and `step` against the environment's
//! spaces and reports violations as typed errors.

use gym_core::spaces::AnySpace;
use gym_core::{
    Env, Error, Frame, Info, InfoValue, RenderMode, ResetOptions, Result, Space, Step, Value,
};

/// Info keys with a conventional type, checked on every `reset` and `step`.
const TYPED_INFO_KEYS: [(&str, &str); 3] = [
    ("success", "bool"),
    ("is_success", "bool"),
    ("TimeLimit.truncated", "bool"),
];

fn contract(check: &str, message: impl Into<String>) -> Error {
    Error::Contract {
        check: check.to_owned(),
        message: message.into(),
    }
}

/// Gymnasium's `check_space` (construction-time assertions): Dict and Tuple spaces must be
/// non-empty, recursively. Equal Box bounds are a warning.
fn check_space(space: &AnySpace, kind: &str, warnings: &mut Vec<String>) -> Result<()> {
    match space {
        AnySpace::Box(b) => {
            let (low, high) = b.bounds_f64();
            if low.iter().zip(high.iter()).any(|(l, h)| l == h) {
                warnings.push(format!("A Box {kind} space maximum and minimum values are equal. Actual equal coordinates: {b}"));
            }
            Ok(())
        }
        AnySpace::Dict(d) => {
            if d.is_empty() {
                return Err(contract(
                    "check_space",
                    format!("An empty Dict {kind} space is not allowed."),
                ));
            }
            d.iter()
                .try_for_each(|(_, s)| check_space(s, kind, warnings))
        }
        AnySpace::Tuple(t) => {
            if t.is_empty() {
                return Err(contract(
                    "check_space",
                    format!("An empty Tuple {kind} space is not allowed."),
                ));
            }
            t.spaces()
                .iter()
                .try_for_each(|s| check_space(s, kind, warnings))
        }
        AnySpace::Discrete(_) | AnySpace::MultiDiscrete(_) | AnySpace::MultiBinary(_) => Ok(()),
    }
}

/// Gymnasium's `check_obs` dtype warnings: an array whose dtype differs from its Box's.
fn check_obs_dtypes(space: &AnySpace, obs: &Value, method: &str, warnings: &mut Vec<String>) {
    match (space, obs) {
        (AnySpace::Box(b), Value::Array(a))
            if !b.shape().unwrap_or(&[]).is_empty() && a.dtype() != b.dtype() =>
        {
            warnings.push(format!(
                "The obs returned by the `{method}()` method was expecting numpy array dtype to be {}, actual type: {}",
                b.dtype(),
                a.dtype()
            ));
        }
        (AnySpace::Dict(d), Value::Dict(v)) => {
            for (k, s) in d.iter() {
                if let Some(x) = v.get(k) {
                    check_obs_dtypes(s, x, method, warnings);
                }
            }
        }
        (AnySpace::Tuple(t), Value::Tuple(v)) => {
            for (s, x) in t.spaces().iter().zip(v) {
                check_obs_dtypes(s, x, method, warnings);
            }
        }
        _ => {}
    }
}

fn check_info(info: &Info, method: &str) -> Result<()> {
    for (key, kind) in TYPED_INFO_KEYS {
        if let Some(v) = info.get(key)
            && v.kind() != kind
        {
            return Err(contract(
                "info",
                format!(
                    "`{method}()` info[\"{key}\"] must be a {kind}, got a {}",
                    v.kind()
                ),
            ));
        }
    }
    if let Some(v) = info.get("episode") {
        let InfoValue::Map(m) = v else {
            return Err(contract(
                "info",
                format!(
                    "`{method}()` info[\"episode\"] must be a map, got a {}",
                    v.kind()
                ),
            ));
        };
        for (key, ok) in [
            ("r", &["float", "int"][..]),
            ("l", &["int"][..]),
            ("t", &["float", "int"][..]),
        ] {
            match m.get(key) {
                Some(x) if ok.contains(&x.kind()) => {}
                Some(x) => {
                    return Err(contract(
                        "info",
                        format!(
                            "info[\"episode\"][\"{key}\"] must be numeric, got a {}",
                            x.kind()
                        ),
                    ));
                }
                None => {
                    return Err(contract(
                        "info",
                        format!("info[\"episode\"] lacks \"{key}\""),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// A checking layer in the spirit of Gymnasium's `PassiveEnvChecker`, strict where
/// Gymnasium only warns.
///
/// * Construction: both spaces pass Gymnasium's `check_space` (non-empty Dict and Tuple
///   spaces, recursively); equal Box bounds are recorded as warnings.
/// * Every `reset` and `step`: the observation lies in the observation space, the reward is
///   finite, and conventional info keys have their type (`success`, `is_success`,
///   `TimeLimit.truncated` bools; `episode` a map of numeric `r`, `l`, `t`). A violation is
///   an [`Error::Contract`] naming the check.
/// * First `reset` and first `step`: the observation's dtypes are compared with the space's
///   (a mismatch that `contains` still accepts is a warning, as in Gymnasium).
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
        check_space(&env.action_space().to_any(), "action", &mut warnings)?;
        check_space(
            &env.observation_space().to_any(),
            "observation",
            &mut warnings,
        )?;
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
        if first {
            check_obs_dtypes(
                &space.to_any(),
                &space.to_value(obs),
                method,
                &mut self.warnings,
            );
        }
        if !space.contains(obs) {
            return Err(contract(
                method,
                format!(
                    "The obs returned by the `{method}()` method is not within the observation space"
                ),
            ));
        }
        Ok(())
    }

    fn check_render(&mut self, frame: &Option<Frame>) -> Result<()> {
        let mode = self.env.render_mode();
        let meta = self.env.metadata();
        if !self.checked_render {
            self.checked_render = true;
            if meta.render_modes.is_empty() {
                self.warnings.push("No render modes was declared in the environment (env.metadata['render_modes'] is empty)".into());
            } else {
                match meta.render_fps {
                    None => self.warnings.push("No render fps was declared in the environment (env.metadata['render_fps'] is None)".into()),
                    Some(fps) if fps.is_nan() || fps <= 0.0 => {
                        return Err(contract("render", format!("render_fps must be positive, got {fps}")));
                    }
                    Some(_) => {}
                }
            }
        }
        if let Some(m) = mode
            && !meta.render_modes.contains(&m)
        {
            return Err(contract(
                "render",
                format!(
                    "render mode `{}` is not in metadata.render_modes",
                    m.as_str()
                ),
            ));
        }
        match (mode, frame) {
            (None | Some(RenderMode::Human), None) => Ok(()),
            (None | Some(RenderMode::Human), Some(_)) => {
                self.warnings
                    .push("render() returned a frame but the render mode is None or human".into());
                Ok(())
            }
            (Some(m), None) => {
                self.warnings.push(format!(
                    "render() returned no frame in render mode `{}`",
                    m.as_str()
                ));
                Ok(())
            }
            (Some(RenderMode::RgbArray), Some(Frame::Rgb(a))) if a.shape()[2] == 3 => Ok(()),
            (Some(RenderMode::DepthArray), Some(Frame::Depth(_)))
            | (Some(RenderMode::Ansi), Some(Frame::Ansi(_))) => Ok(()),
            (Some(m), Some(_)) => Err(contract(
                "render",
                format!(
                    "render() returned a frame of the wrong kind for `{}`",
                    m.as_str()
                ),
            )),
        }
    }
}

impl<E: Env> Env for PassiveEnvChecker<E> {
    type Obs = E::Obs;
    type Act = E::Act;
    type ObsSpace = E::ObsSpace;
    type ActSpace = E::ActSpace;

    fn observation_space(&self) -> &E::ObsSpace {
        self.env.observation_space()
    }

    fn action_space(&self) -> &E::ActSpace {
        self.env.action_space()
    }

    fn reset(
        &mut self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(E::Obs, Info)> {
        let (obs, info) = self.env.reset(seed, options)?;
        let first = !self.checked_reset;
        self.checked_reset = true;
        self.check_obs(&obs, "reset", first)?;
        check_info(&info, "reset")?;
        Ok((obs, info))
    }

    fn step(&mut self, action: &E::Act) -> Result<Step<E::Obs>> {
        let step = self.env.step(action)?;
        let first = !self.checked_step;
        self.checked_step = true;
        self.check_obs(&step.observation, "step", first)?;
        if step.reward.is_nan() {
            return Err(contract("step", "The reward is a NaN value."));
        }
        if step.reward.is_infinite() {
            return Err(contract("step", "The reward is an inf value."));
        }
        check_info(&step.info, "step")?;
        Ok(step)
    }

    fn render(&mut self) -> Result<Option<Frame>> {
        let frame = self.env.render()?;
        self.check_render(&frame)?;
        Ok(frame)
    }

    forward_env_except_render!();
}

impl_wrapper!(PassiveEnvChecker);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{CountEnv, ScriptEnv, a32, script_f32, unit_actions};
    use gym_core::spaces::{BoxSpace, DictSpace, TupleSpace};
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
