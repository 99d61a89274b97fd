//! Gymnasium's passive checks (`gymnasium.utils.passive_env_checker`) on single values: the
//! pieces that both conformance-tests' `check_env` and the `PassiveEnvChecker` wrapper of
//! the `adapters` crate run, so that the two never disagree. The space and observation
//! checks are [`check_space`](super::check_space) and [`check_obs`](super::check_obs).

use super::report::{Check, Failure, Warning, WarningKind};
use crate::{Frame, Info, InfoValue, Metadata, RenderMode};

/// Info keys with a conventional type: `(key, kind)` with the kind as
/// [`InfoValue::kind`] names it.
pub const TYPED_INFO_KEYS: [(&str, &str); 3] = [
    ("success", "bool"),
    ("is_success", "bool"),
    ("TimeLimit.truncated", "bool"),
];

/// The reward must be finite (`env_step_passive_checker`; Gymnasium warns, this fails).
///
/// # Errors
/// [`Check::RewardFinite`], saying "The reward is a NaN value" or "... an inf value".
pub fn check_reward(reward: f64) -> Result<(), Failure> {
    if reward.is_finite() {
        return Ok(());
    }
    let kind = if reward.is_nan() {
        "a NaN value"
    } else {
        "an inf value"
    };
    Err(Failure::new(
        Check::RewardFinite,
        format!("The reward is {kind} ({reward})"),
    ))
}

/// Conventional info entries have their type: `success`, `is_success` and
/// `TimeLimit.truncated` are bools; `episode` (RecordEpisodeStatistics) is a map of numeric
/// `r`, `l` (an int) and `t`. `method` (`"reset"` or `"step"`) names the call.
///
/// # Errors
/// [`Check::ResetPassive`] (for `"reset"`) or [`Check::StepPassive`], naming the key.
pub fn check_info_types(info: &Info, method: &str) -> Result<(), Failure> {
    let check = if method == "reset" {
        Check::ResetPassive
    } else {
        Check::StepPassive
    };
    let fail = |m: String| Err(Failure::new(check, m));
    for (key, kind) in TYPED_INFO_KEYS {
        if let Some(v) = info.get(key)
            && v.kind() != kind
        {
            return fail(format!(
                "`{method}()` info[\"{key}\"] must be a {kind}, got a {}",
                v.kind()
            ));
        }
    }
    if let Some(v) = info.get("episode") {
        let InfoValue::Map(m) = v else {
            return fail(format!(
                "`{method}()` info[\"episode\"] must be a map, got a {}",
                v.kind()
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
                    return fail(format!(
                        "info[\"episode\"][\"{key}\"] must be numeric, got a {}",
                        x.kind()
                    ));
                }
                None => return fail(format!("info[\"episode\"] lacks \"{key}\"")),
            }
        }
    }
    Ok(())
}

/// The render metadata and mode (`env_render_passive_checker`): with render modes
/// declared, a warning without `render_fps` and a failure for one that is not positive;
/// without modes, the render mode must be `None`; otherwise `None` or a declared mode.
///
/// # Errors
/// [`Check::Render`].
pub fn check_render_metadata(
    metadata: &Metadata,
    mode: Option<RenderMode>,
) -> Result<Vec<Warning>, Failure> {
    const C: Check = Check::Render;
    let modes = &metadata.render_modes;
    let mut warnings = Vec::new();
    if !modes.is_empty() {
        match metadata.render_fps {
            None => warnings.push(Warning::new(
                WarningKind::RenderFpsMissing,
                "No render fps was declared in the environment (env.metadata['render_fps'] is None or not defined), \
                 rendering may occur at inconsistent fps.",
            )),
            Some(fps) if fps.is_nan() || fps <= 0.0 => {
                return Err(Failure::new(
                    C,
                    format!(
                        "Expects the `env.metadata['render_fps']` to be greater than zero, actual value: {fps}"
                    ),
                ));
            }
            Some(_) => {}
        }
    }
    match mode {
        Some(m) if modes.is_empty() => Err(Failure::new(
            C,
            format!(
                "With no render_modes, expects the Env.render_mode to be None, actual value: {}",
                m.as_str()
            ),
        )),
        Some(m) if !modes.contains(&m) => {
            let names: Vec<&str> = modes.iter().map(|m| m.as_str()).collect();
            Err(Failure::new(
                C,
                format!(
                    "The environment was initialized successfully however with an unsupported render mode. Render mode: {}, \
                     modes: {names:?}",
                    m.as_str()
                ),
            ))
        }
        _ => Ok(warnings),
    }
}

/// What `render()` returned against its mode (`_check_render_return`): `human` returns
/// nothing, `rgb_array` an RGB frame with 3 channels, `depth_array` a depth frame, `ansi`
/// text. `None` when it fits.
pub fn check_render_return(mode: RenderMode, frame: Option<&Frame>) -> Option<Warning> {
    let problem = match (mode, frame) {
        (RenderMode::Human, None) => None,
        (RenderMode::Human, Some(_)) => {
            Some("Human rendering should return `None`, got a frame".to_owned())
        }
        (RenderMode::RgbArray, Some(Frame::Rgb(a))) if a.shape()[2] == 3 => None,
        (RenderMode::RgbArray, Some(Frame::Rgb(a))) => Some(format!(
            "RGB-array rendering should return a numpy array in which the last axis has three dimensions, got {}",
            a.shape()[2]
        )),
        (RenderMode::RgbArray, _) => {
            Some("RGB-array rendering should return an RGB frame".to_owned())
        }
        (RenderMode::DepthArray, Some(Frame::Depth(_))) => None,
        (RenderMode::DepthArray, _) => {
            Some("Depth-array rendering should return a depth frame".to_owned())
        }
        (RenderMode::Ansi, Some(Frame::Ansi(_))) => None,
        (RenderMode::Ansi, _) => Some("ANSI/ASCII rendering should produce a string".to_owned()),
    };
    problem.map(|p| Warning::new(WarningKind::RenderReturn, p))
}
