//! Reliability under bad input and faults (issue #17): MuJoCo's fatal errors, unbounded
//! steps, divergence, bad states and mis-sized sensors give typed errors, and every
//! rejected call leaves the env as it was.

use crate::common::zero;
use gym_core::{Env, Error};
use robosuite_env::config::MAX_SUBSTEPS;
use robosuite_env::sim::MAX_STATE_MAGNITUDE;
use robosuite_env::{
    EnvConfig, InitNoise, NoiseKind, make, make_from_scene_xml, make_with, scene_xml,
};

/// The Lift scene with `extra` inserted as the last child of `<mujoco>`.
fn lift_scene_with(extra: &str) -> String {
    let xml = scene_xml("Lift", &EnvConfig::default()).unwrap();
    let end = xml.rfind("</mujoco>").unwrap();
    format!("{}{extra}{}", &xml[..end], &xml[end..])
}

#[test]
fn a_scene_whose_arena_is_too_small_fails_at_make_not_at_the_first_step() {
    let xml = lift_scene_with(r#"<size memory="16K"/>"#);
    let Err(Error::Model(message)) = make_from_scene_xml("Lift", &xml, EnvConfig::default()) else {
        panic!("expected Error::Model");
    };
    assert!(message.to_string().contains("memory"), "{message}");
    // The process is alive and other envs work.
    let mut env = make("Lift").unwrap();
    env.reset(Some(0), None).unwrap();
    let _ = env.step(&zero()).unwrap();
}

#[test]
fn work_per_step_is_bounded_at_make() {
    for hz in [1e-6, 0.1, 0.0, -1.0, f64::NAN] {
        assert!(
            matches!(
                make_with("Lift", EnvConfig::default().with_control_freq(hz)),
                Err(Error::InvalidArgument { ref name, .. }) if name == "control_freq"
            ),
            "control_freq {hz}"
        );
    }
    // The slowest accepted rate runs exactly MAX_SUBSTEPS substeps.
    let slowest = 1.0 / (MAX_SUBSTEPS as f64 * 0.002);
    let env = make_with("Lift", EnvConfig::default().with_control_freq(slowest)).unwrap();
    assert_eq!(env.substeps(), MAX_SUBSTEPS);
    // A supplied model with a tiny timestep needs too many substeps at 20 Hz.
    let xml = lift_scene_with(r#"<option timestep="1e-9"/>"#);
    assert!(matches!(
        make_from_scene_xml("Lift", &xml, EnvConfig::default()),
        Err(Error::InvalidArgument { ref name, .. }) if name == "control_freq"
    ));
}

#[test]
fn huge_noise_is_rejected() {
    for m in [1e10, f64::INFINITY, -1.0] {
        let noise = InitNoise {
            magnitude: m,
            kind: NoiseKind::Gaussian,
        };
        let config = EnvConfig::default().with_initialization_noise(noise);
        assert!(matches!(
            make_with("Lift", config),
            Err(Error::InvalidArgument { .. })
        ));
    }
}

#[test]
fn bad_states_are_rejected_and_change_nothing() {
    let mut env = make("Lift").unwrap();
    env.reset(Some(1), None).unwrap();
    let _ = env.step(&zero()).unwrap();
    let before = env.get_state();
    let observation = env.observation();
    let n = before.len();
    let mut bad = Vec::new();
    for (i, v) in [
        (1, 1e10),
        (n - 1, 1e10),
        (5, -1e7),
        (2, f64::NAN),
        (0, f64::INFINITY),
    ] {
        let mut s = before.clone();
        s[i] = v;
        bad.push(s);
    }
    bad.push(before[..n - 1].to_vec());
    bad.push([before.clone(), vec![0.0]].concat());
    for s in &bad {
        assert!(matches!(
            env.set_state(s),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            env.reset_to_state(&env.task().save_state(), s),
            Err(Error::InvalidArgument { .. })
        ));
        assert_eq!(env.get_state(), before);
        assert_eq!(env.observation(), observation);
    }
    // The env steps on as if nothing had been tried.
    let _ = env.step(&zero()).unwrap();
}

#[test]
fn a_diverged_simulation_is_an_error_never_a_success() {
    let mut env = make("Lift").unwrap();
    env.reset(Some(2), None).unwrap();
    let mut state = env.get_state();
    let nq = env.sim().model().ffi().nq as usize;
    // Velocities at the accepted bound: the Coriolis forces (~v²) overflow MuJoCo's limit.
    for v in &mut state[1 + nq..] {
        *v = MAX_STATE_MAGNITUDE;
    }
    env.set_state(&state).unwrap();
    let Err(Error::Simulation(message)) = env.step(&zero()) else {
        panic!("a diverged step must be an error");
    };
    assert!(message.to_string().contains("diverged"), "{message}");
    // The episode is over: a reset is needed, and works.
    assert!(matches!(env.step(&zero()), Err(Error::ResetNeeded)));
    env.reset(Some(2), None).unwrap();
    for _ in 0..5 {
        let step = env.step(&zero()).unwrap();
        assert!(step.reward.is_finite());
    }
}

#[test]
fn a_sensor_of_the_wrong_dimension_is_rejected_at_make() {
    let xml = scene_xml("Wipe", &EnvConfig::default()).unwrap();
    let sensor = xml
        .find("<force ")
        .map(|at| &xml[at..at + xml[at..].find("/>").unwrap() + 2])
        .expect("a force sensor");
    assert!(sensor.contains("force_ee"), "{sensor}");
    // A 1-D touch sensor under the force sensor's name.
    let one_d = sensor.replacen("<force ", "<touch ", 1);
    let xml = xml.replacen(sensor, &one_d, 1);
    let Err(Error::Model(message)) = make_from_scene_xml("Wipe", &xml, EnvConfig::default()) else {
        panic!("expected Error::Model");
    };
    assert!(message.to_string().contains("force_ee"), "{message}");
}

#[test]
fn a_saved_state_continues_bit_identically_in_a_new_env() {
    use robosuite_env::saved::SavedEnv;
    let config = EnvConfig::default().with_seed(5);
    let mut env = make_with("Lift", config.clone()).unwrap();
    env.reset(None, None).unwrap();
    let a = crate::common::action([0.3, -0.2, 0.1, 0.0, 0.05, -0.1, 1.0]);
    for _ in 0..3 {
        let _ = env.step(&a).unwrap();
    }
    let text = SavedEnv::of(&env).to_json().unwrap();
    let mut copy = make_with("Lift", config).unwrap();
    SavedEnv::from_json(&text)
        .unwrap()
        .apply(&mut copy)
        .unwrap();
    for round in 0..2 {
        for _ in 0..4 {
            let (x, y) = (env.step(&a).unwrap(), copy.step(&a).unwrap());
            assert_eq!(x, y);
        }
        assert_eq!(env.get_state(), copy.get_state());
        // Unseeded resets draw from the copied RNG: the same episode starts.
        if round == 0 {
            assert_eq!(
                env.reset(None, None).unwrap(),
                copy.reset(None, None).unwrap()
            );
        }
    }
    assert!(matches!(
        SavedEnv::from_json("{\"snapshot\": 1}"),
        Err(Error::InvalidArgument { .. })
    ));
}
