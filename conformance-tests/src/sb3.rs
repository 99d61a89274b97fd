//! Stable-Baselines3's additions to the checks (`stable_baselines3.common.env_checker`,
//! SB3 2.x), enabled by [`CheckOptions::sb3`](crate::CheckOptions::sb3).
//!
//! Left out: the goal-environment checks (`compute_reward`, which the Rust `Env` trait does
//! not have) and the Python type assertions (`bool` terminated, `float` reward) that the
//! Rust types guarantee.

use crate::report::{Check, Failure, Warning, WarningKind};
use gym_core::{AnyBox, AnySpace, DType, Space};

/// SB3's space checks: `_check_unsupported_spaces`, `_check_box_obs` for the observation
/// (or each Box entry of a Dict observation) and the Box action checks.
///
/// Warnings: a Dict inside a Dict observation, a multi-dimensional MultiDiscrete, a Tuple
/// observation, a Dict or Tuple action, a (Multi)Discrete with a non-zero start; a
/// 3-dimensional Box observation that is not `uint8`, not in `[0, 255]` or smaller than
/// 36x36; a Box observation of neither 1 nor 3 dimensions; a Box action other than
/// exactly `[-1, 1]` ("We recommend you to use a symmetric and normalized Box action space
/// (range=[-1, 1])"); a Box action whose dtype is not `float32`.
///
/// # Errors
/// [`Check::Sb3ActionBounds`] when a Box action space has an infinite bound ("Continuous
/// action space must have a finite lower and upper bound").
pub fn sb3_check_spaces(
    observation_space: &AnySpace,
    action_space: &AnySpace,
) -> Result<Vec<Warning>, Failure> {
    let mut w = Vec::new();
    let unsupported = |m: &str| Warning::new(WarningKind::Sb3UnsupportedSpace, m);
    if let AnySpace::Dict(d) = observation_space
        && d.iter().any(|(_, s)| matches!(s, AnySpace::Dict(_)))
    {
        w.push(unsupported(
            "Nested observation spaces are not supported by Stable Baselines3 (Dict spaces inside Dict space). \
             You should flatten it to have only one level of keys.",
        ));
    }
    let multi_dim_md =
        |s: &AnySpace| matches!(s, AnySpace::MultiDiscrete(m) if m.nvec().ndim() > 1);
    let obs_leaves: Vec<&AnySpace> = match observation_space {
        AnySpace::Dict(d) => d.iter().map(|(_, s)| s).collect(),
        other => vec![other],
    };
    if obs_leaves.iter().any(|s| multi_dim_md(s)) {
        w.push(unsupported(
            "Multi-dimensional MultiDiscrete observation space is not supported. You can flatten it instead.",
        ));
    }
    if matches!(observation_space, AnySpace::Tuple(_)) {
        w.push(unsupported(
            "The observation space is a Tuple, this is currently not supported by Stable Baselines3. \
             However, you can convert it to a Dict observation space which is supported by SB3.",
        ));
    }
    for (name, leaves) in [
        ("observation", obs_leaves.clone()),
        ("action", vec![action_space]),
    ] {
        for s in leaves {
            let nonzero_start = match s {
                AnySpace::Discrete(d) => d.start() != 0,
                AnySpace::MultiDiscrete(m) => m.start().iter().any(|&x| x != 0),
                _ => false,
            };
            if nonzero_start {
                w.push(unsupported(&format!(
                    "Discrete {name} space with a non-zero start is not supported by Stable-Baselines3. \
                     You can use a wrapper or update your {name} space."
                )));
            }
        }
    }
    if multi_dim_md(action_space) {
        w.push(unsupported("Multi-dimensional MultiDiscrete action space is not supported. You can flatten it instead."));
    }
    if matches!(action_space, AnySpace::Dict(_) | AnySpace::Tuple(_)) {
        w.push(unsupported(
            "The action space is not based off a numpy array. Typically this means it's either a Dict or Tuple space. \
             This type of action space is currently not supported by Stable Baselines 3. You should try to flatten the \
             action using a wrapper.",
        ));
    }
    let named_boxes: Vec<(String, &AnyBox)> = match observation_space {
        AnySpace::Dict(d) => d
            .iter()
            .filter_map(|(k, s)| match s {
                AnySpace::Box(b) => Some((k.to_owned(), b)),
                _ => None,
            })
            .collect(),
        AnySpace::Box(b) => vec![(String::new(), b)],
        _ => Vec::new(),
    };
    for (key, b) in named_boxes {
        check_box_obs(b, &key, &mut w);
    }
    if let AnySpace::Box(b) = action_space {
        let (low, high) = b.bounds_f64();
        if low
            .iter()
            .zip(high.iter())
            .any(|(l, h)| l.abs() != h.abs() || *l != -1.0 || *h != 1.0)
        {
            w.push(Warning::new(
                WarningKind::Sb3ActionNotNormalized,
                "We recommend you to use a symmetric and normalized Box action space (range=[-1, 1]) \
                 cf. https://stable-baselines3.readthedocs.io/en/master/guide/rl_tips.html",
            ));
        }
        if !b.is_bounded() || low.iter().chain(high.iter()).any(|v| !v.is_finite()) {
            return Err(Failure::new(
                Check::Sb3ActionBounds,
                format!(
                    "Continuous action space must have a finite lower and upper bound; the action space is {b}"
                ),
            ));
        }
        if b.dtype() != DType::F32 {
            w.push(Warning::new(
                WarningKind::Sb3ActionDtype,
                format!("Your action space has dtype {}, we recommend using np.float32 to avoid cast errors.", b.dtype()),
            ));
        }
    }
    Ok(w)
}

fn check_box_obs(b: &AnyBox, key: &str, w: &mut Vec<Warning>) {
    let shape = b.shape().unwrap_or(&[]).to_vec();
    if shape.len() == 3 {
        let image = |m: String| Warning::new(WarningKind::Sb3ImageSpace, m);
        if b.dtype() != DType::U8 {
            w.push(image(format!(
                "It seems that your observation {key} is an image but its `dtype` is ({}) whereas it has to be `np.uint8`. \
                 If your observation is not an image, we recommend you to flatten the observation to have only a 1D vector",
                b.dtype()
            )));
        }
        let (low, high) = b.bounds_f64();
        if low.iter().any(|&l| l != 0.0) || high.iter().any(|&h| h != 255.0) {
            w.push(image(format!(
                "It seems that your observation space {key} is an image but the upper and lower bounds are not in [0, 255]. \
                 Because the CNN policy normalize automatically the observation you may encounter issue if the values are not in that range."
            )));
        }
        // SB3's channels-first heuristic: the smallest axis first means CHW.
        let channels_first = shape[0] <= shape[2];
        let (height, width) = if channels_first {
            (shape[1], shape[2])
        } else {
            (shape[0], shape[1])
        };
        if height < 36 || width < 36 {
            w.push(image(
                "The minimal resolution for an image is 36x36 for the default `CnnPolicy`. \
                 You might need to use a custom feature extractor cf. https://stable-baselines3.readthedocs.io/en/master/guide/custom_policy.html"
                    .to_owned(),
            ));
        }
    }
    if shape.len() != 1 && shape.len() != 3 {
        w.push(Warning::new(
            WarningKind::Sb3UnconventionalShape,
            format!(
                "Your observation {key} has an unconventional shape (neither an image, nor a 1D vector). \
                 We recommend you to flatten the observation to have only a 1D vector or use a custom policy to properly process the data. \
                 Actual observation shape: {shape:?}"
            ),
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gym_core::{BoxSpace, DictSpace, TupleSpace};

    #[test]
    fn action_bounds_and_recommendations() {
        let obs: AnySpace = BoxSpace::<f32>::uniform(-1.0, 1.0, &[3]).unwrap().into();
        let ok: AnySpace = BoxSpace::<f32>::uniform(-1.0, 1.0, &[2]).unwrap().into();
        assert!(sb3_check_spaces(&obs, &ok).unwrap().is_empty());
        let unbounded: AnySpace = BoxSpace::<f32>::unbounded(&[2]).into();
        assert_eq!(
            sb3_check_spaces(&obs, &unbounded).unwrap_err().check,
            Check::Sb3ActionBounds
        );
        let f64_01: AnySpace = BoxSpace::<f64>::uniform(0.0, 1.0, &[2]).unwrap().into();
        let kinds: Vec<_> = sb3_check_spaces(&obs, &f64_01)
            .unwrap()
            .into_iter()
            .map(|w| w.kind)
            .collect();
        assert_eq!(
            kinds,
            [
                WarningKind::Sb3ActionNotNormalized,
                WarningKind::Sb3ActionDtype
            ]
        );
    }

    #[test]
    fn observation_shapes() {
        let act: AnySpace = BoxSpace::<f32>::uniform(-1.0, 1.0, &[2]).unwrap().into();
        let img: AnySpace = BoxSpace::<u8>::uniform(0.0, 255.0, &[84, 84, 3])
            .unwrap()
            .into();
        assert!(sb3_check_spaces(&img, &act).unwrap().is_empty());
        let small: AnySpace = BoxSpace::<f32>::uniform(0.0, 1.0, &[3, 8, 8])
            .unwrap()
            .into();
        let kinds: Vec<_> = sb3_check_spaces(&small, &act)
            .unwrap()
            .into_iter()
            .map(|w| w.kind)
            .collect();
        assert_eq!(kinds, [WarningKind::Sb3ImageSpace; 3]);
        let square: AnySpace = BoxSpace::<f32>::uniform(0.0, 1.0, &[2, 2]).unwrap().into();
        let tuple = AnySpace::Tuple(TupleSpace::new(vec![square.clone()]));
        let nested = AnySpace::Dict(
            DictSpace::new([(
                "a",
                AnySpace::Dict(DictSpace::new([("b", square.clone())]).unwrap()),
            )])
            .unwrap(),
        );
        let kinds = |o: &AnySpace, a: &AnySpace| {
            sb3_check_spaces(o, a)
                .unwrap()
                .into_iter()
                .map(|w| w.kind)
                .collect::<Vec<_>>()
        };
        assert_eq!(kinds(&square, &act), [WarningKind::Sb3UnconventionalShape]);
        assert_eq!(kinds(&tuple, &act), [WarningKind::Sb3UnsupportedSpace]);
        assert_eq!(kinds(&nested, &act), [WarningKind::Sb3UnsupportedSpace]);
        assert!(kinds(&square, &tuple).contains(&WarningKind::Sb3UnsupportedSpace));
    }
}
