//! The reference environments pass every check and property, typed and boxed; warnings
//! are reported apart from failures with Gymnasium's meaning.

use conformance_tests::prop::{
    EpisodeEndSpec, PropConfig, prop_check_env, prop_check_env_with_state, prop_gym_core_spaces,
    prop_time_limit,
};
use conformance_tests::toy::{GridWorld, PointMass, PointMassStateHook, position_probe};
use conformance_tests::{Check, CheckOptions, WarningKind, check_env};
use gym_core::{
    BoxSpace, BoxedEnv, Env, EnvRng, Info, IntoBoxedEnv, RenderMode, ResetOptions, Result, Step,
    StepWrapper, Steps, Wrapper, rng_from_seed,
};
use ndarray::ArrayD;

#[test]
fn point_mass_passes_check_env() {
    let options = CheckOptions::default().reset_options_probe(position_probe(-3.0));
    let report = check_env(&mut PointMass::new(), &options).unwrap();
    assert!(report.skipped.is_empty(), "{report}");
    assert_eq!(
        report.warnings.iter().map(|w| w.kind).collect::<Vec<_>>(),
        [WarningKind::AlternativeRenderModesNotTested],
        "{report}"
    );
    let boxed = check_env(&mut PointMass::new().boxed(), &options).unwrap();
    assert_eq!(boxed.passed, report.passed);
    let rendered = check_env(
        &mut PointMass::new().with_render_mode(RenderMode::Ansi),
        &options,
    )
    .unwrap();
    assert!(rendered.warnings.is_empty(), "{rendered}");
}

#[test]
fn point_mass_passes_sb3() {
    let report = check_env(&mut PointMass::new(), &CheckOptions::default().sb3(true)).unwrap();
    assert!(
        !report
            .warnings
            .iter()
            .any(|w| format!("{:?}", w.kind).starts_with("Sb3")),
        "{report}"
    );
}

#[test]
fn grid_world_passes_check_env() {
    let report = check_env(&mut GridWorld::default(), &CheckOptions::default()).unwrap();
    assert!(report.passed(Check::InvalidAction), "{report}");
    assert!(report.passed(Check::StepAfterEnd), "{report}");
    check_env(&mut GridWorld::default().boxed(), &CheckOptions::default()).unwrap();
    let sb3 = check_env(
        &mut GridWorld::default(),
        &CheckOptions::default().sb3(true),
    )
    .unwrap();
    assert!(
        !sb3.warnings
            .iter()
            .any(|w| format!("{:?}", w.kind).starts_with("Sb3")),
        "{sb3}"
    );
}

#[test]
fn point_mass_passes_the_property_suite() {
    let config = PropConfig::default().episode_end(EpisodeEndSpec {
        truncate_at: Some(10),
        can_terminate: false,
    });
    let make = || PointMass::new().with_horizon(10);
    let report = prop_check_env_with_state(make, &PointMassStateHook, &config).unwrap();
    assert_eq!(report.passed.len(), 8);
    let boxed = || -> BoxedEnv { PointMass::new().with_horizon(10).boxed() };
    prop_check_env_with_state(boxed, &PointMassStateHook, &config).unwrap();
}

#[test]
fn grid_world_passes_the_property_suite() {
    let config = PropConfig::default().episode_end(EpisodeEndSpec {
        truncate_at: Some(6),
        can_terminate: true,
    });
    prop_check_env(|| GridWorld::new(4).with_horizon(6), &config).unwrap();
    prop_check_env(|| GridWorld::new(4).with_horizon(6).boxed(), &config).unwrap();
    // A horizon is a time limit: the time-limit property holds for it.
    prop_time_limit(|| GridWorld::new(4).with_horizon(6), 6, &config).unwrap();
    // Claiming another limit is caught.
    let f = prop_time_limit(|| GridWorld::new(9).with_horizon(6), 5, &config).unwrap_err();
    assert_eq!(f.property, conformance_tests::Property::TruncationAtLimit);
}

#[test]
fn gym_core_spaces_sample_and_flatten() {
    prop_gym_core_spaces(
        3,
        &PropConfig {
            cases: 256,
            ..PropConfig::default()
        },
    )
    .unwrap();
}

/// An environment with an unbounded observation Box and a `[-2, 2]` action Box: it works,
/// and Gymnasium only warns about it.
#[derive(Debug)]
struct Loose {
    obs: BoxSpace<f64>,
    act: BoxSpace<f32>,
    rng: Option<EnvRng>,
    done: bool,
}

impl Loose {
    fn new(act: BoxSpace<f32>) -> Self {
        Self {
            obs: BoxSpace::unbounded(&[3]),
            act,
            rng: None,
            done: false,
        }
    }
}

impl Env for Loose {
    type Obs = ArrayD<f64>;
    type Act = ArrayD<f32>;
    type ObsSpace = BoxSpace<f64>;
    type ActSpace = BoxSpace<f32>;

    fn observation_space(&self) -> &BoxSpace<f64> {
        &self.obs
    }
    fn action_space(&self) -> &BoxSpace<f32> {
        &self.act
    }
    fn reset(
        &mut self,
        seed: Option<u64>,
        _: Option<&ResetOptions>,
    ) -> Result<(ArrayD<f64>, Info)> {
        self.rng = Some(rng_from_seed(seed.unwrap_or(7)));
        self.done = false;
        Ok((ArrayD::zeros(ndarray::IxDyn(&[3])), Info::new()))
    }
    fn step(&mut self, a: &ArrayD<f32>) -> Result<Step<ArrayD<f64>>> {
        if self.done {
            return Err(gym_core::Error::EpisodeEnded);
        }
        if a.shape() != [2] || a.iter().any(|x| !x.is_finite()) {
            return Err(gym_core::Error::invalid_action(format!("{a:?}")));
        }
        self.done = true;
        let obs = ArrayD::from_elem(ndarray::IxDyn(&[3]), f64::from(a[[0]]));
        Ok(Step {
            observation: obs,
            reward: 0.0,
            terminated: true,
            truncated: false,
            info: Info::new(),
        })
    }
    fn rng(&self) -> Option<&EnvRng> {
        self.rng.as_ref()
    }
}

#[test]
fn space_limit_warnings_are_apart_from_failures() {
    let mut env = Loose::new(BoxSpace::uniform(-2.0, 2.0, &[2]).unwrap());
    let report = check_env(&mut env, &CheckOptions::default()).unwrap();
    for kind in [
        WarningKind::BoxUnboundedBelow,
        WarningKind::BoxUnboundedAbove,
        WarningKind::ActionSpaceNotNormalized,
    ] {
        assert!(report.has_warning(kind), "{kind:?} missing:\n{report}");
    }
    let w = report
        .warnings_of(WarningKind::BoxUnboundedBelow)
        .next()
        .unwrap();
    assert_eq!(
        w.message,
        "A Box observation space minimum value is -infinity. This is probably too low."
    );
    let sb3 = check_env(
        &mut Loose::new(BoxSpace::uniform(-2.0, 2.0, &[2]).unwrap()),
        &CheckOptions::default().sb3(true),
    )
    .unwrap();
    assert!(sb3.has_warning(WarningKind::Sb3ActionNotNormalized));
    // [0, 1] is normalised for Gymnasium but not for SB3.
    let unit = check_env(
        &mut Loose::new(BoxSpace::uniform(0.0, 1.0, &[2]).unwrap()),
        &CheckOptions::default().sb3(true),
    )
    .unwrap();
    assert!(!unit.has_warning(WarningKind::ActionSpaceNotNormalized));
    assert!(unit.has_warning(WarningKind::Sb3ActionNotNormalized));
}

#[test]
fn sb3_requires_finite_action_bounds() {
    let mut env = Loose::new(BoxSpace::unbounded(&[2]));
    assert!(check_env(&mut env, &CheckOptions::default()).is_ok());
    let err = check_env(
        &mut Loose::new(BoxSpace::unbounded(&[2])),
        &CheckOptions::default().sb3(true),
    )
    .unwrap_err();
    assert_eq!(err.check(), Check::Sb3ActionBounds);
    assert!(
        err.first()
            .message
            .starts_with("Continuous action space must have a finite lower and upper bound")
    );
}

/// A wrapper that changes nothing.
struct Identity<E: Env>(E);

impl<E: Env> Wrapper for Identity<E> {
    type Inner = E;
    type Kind = Steps;
    fn inner(&self) -> &E {
        &self.0
    }
    fn inner_mut(&mut self) -> &mut E {
        &mut self.0
    }
    fn into_inner(self) -> E {
        self.0
    }
}

/// Every hook forwards.
impl<E: Env> StepWrapper for Identity<E> {}

#[test]
fn wrapped_envs_get_the_unwrapped_warning() {
    let report = check_env(&mut Identity(PointMass::new()), &CheckOptions::default()).unwrap();
    let w = report
        .warnings_of(WarningKind::NotUnwrapped)
        .next()
        .expect("NotUnwrapped warning");
    assert!(
        w.message
            .contains("is different from the unwrapped version")
    );
    assert!(
        !check_env(&mut PointMass::new(), &CheckOptions::default())
            .unwrap()
            .has_warning(WarningKind::NotUnwrapped)
    );
}
