//! A scripted policy (reach above the cube, descend, close, lift) solves Lift.

use gym_core::Env;
use robosuite_env::{EnvConfig, make_with};

#[test]
fn scripted_policy_lifts_the_cube_on_most_seeds() {
    let mut env = make_with("Lift", EnvConfig::default().with_horizon(300)).unwrap();
    let mut successes = 0;
    let mut report = Vec::new();
    for seed in 0..5 {
        let (ok, steps) = crate::common::scripted_lift(&mut env, seed, 250).unwrap();
        report.push((seed, ok, steps));
        successes += usize::from(ok);
    }
    assert!(
        successes >= 4,
        "scripted policy succeeded on {successes}/5 seeds: {report:?}"
    );
    // The env is reusable after the scripted episodes.
    env.reset(Some(99), None).unwrap();
}

#[test]
fn grasp_adds_the_shaped_bonus() {
    // Unnormalised shaped reward: 1 - tanh(10 d) + 0.25 while both finger pads touch the cube.
    let config = EnvConfig::default()
        .with_horizon(300)
        .with_reward_shaping(true)
        .with_reward_scale(None);
    let mut env = make_with("Lift", config).unwrap();
    let (mut obs, _) = env.reset(Some(1), None).unwrap();
    let mut saw_grasp = false;
    let mut phase = 0;
    let mut n = 0;
    for _ in 0..200 {
        let eef = crate::common::get(&obs, "robot0_eef_pos");
        let cube = crate::common::get(&obs, "cube_pos");
        let (target, grip) = match phase {
            0 => ([cube[0], cube[1], cube[2] + 0.08], -1.0),
            1 => ([cube[0], cube[1], cube[2] - 0.005], -1.0),
            _ => ([eef[0], eef[1], eef[2] + 0.004], 1.0),
        };
        let err: Vec<f64> = (0..3).map(|i| target[i] - eef[i]).collect();
        let a = crate::common::action([
            (err[0] * 10.0).clamp(-1.0, 1.0),
            (err[1] * 10.0).clamp(-1.0, 1.0),
            (err[2] * 10.0).clamp(-1.0, 1.0),
            0.0,
            0.0,
            0.0,
            grip,
        ]);
        let step = env.step(&a).unwrap();
        obs = step.observation;
        let g2c = crate::common::get(&obs, "gripper_to_cube_pos");
        let d = g2c.iter().map(|v| v * v).sum::<f64>().sqrt();
        let bonus = step.reward - (1.0 - (10.0 * d).tanh());
        if step.info.get_bool("success") != Some(true) {
            assert!(
                bonus.abs() < 1e-9 || (bonus - 0.25).abs() < 1e-9,
                "bonus {bonus}"
            );
            saw_grasp |= (bonus - 0.25).abs() < 1e-9;
        }
        n += 1;
        let dist = err.iter().map(|e| e * e).sum::<f64>().sqrt();
        if (phase == 0 && (dist < 0.01 || n > 60)) || (phase == 1 && (dist < 0.006 || n > 40)) {
            phase += 1;
            n = 0;
        }
        if saw_grasp && phase == 2 && n > 20 {
            break;
        }
    }
    assert!(saw_grasp, "the closed fingers never registered a grasp");
}
