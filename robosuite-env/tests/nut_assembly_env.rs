//! The NutAssembly family: variants, observations, hand-set states and a scripted policy.

mod common;

use common::{dist3, finger_yaw, get, move_to, wrap_half, yaw_of};
use gym_core::{DType, Env};
use robosuite_env::tasks::PEG_POS;
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};

fn env(name: &str, config: EnvConfig) -> RobosuiteEnv {
    make_with(name, config).unwrap_or_else(|e| panic!("{name} builds: {e}"))
}

#[test]
fn variants_have_robosuites_sizes_and_keys() {
    for (name, obj_dim) in [
        ("NutAssembly", 28),
        ("NutAssemblySingle", 15),
        ("NutAssemblySquare", 14),
        ("NutAssemblyRound", 14),
    ] {
        let mut e = env(name, EnvConfig::default());
        let m = e.sim().model().ffi();
        assert_eq!((m.nq, m.nv, m.nu), (23, 21, 9), "{name}");
        let (obs, _) = e.reset(Some(1), None).unwrap();
        assert_eq!(get(&obs, "object-state").len(), obj_dim, "{name}");
    }
    let e = env("NutAssemblyRound", EnvConfig::default());
    assert_eq!(
        &e.observation_keys()[10..14],
        &[
            "RoundNut_to_robot0_eef_pos",
            "RoundNut_to_robot0_eef_quat",
            "RoundNut_pos",
            "RoundNut_quat"
        ]
    );
    let mut both = env("NutAssembly", EnvConfig::default());
    let (obs, _) = both.reset(Some(3), None).unwrap();
    let sq = get(&obs, "SquareNut_pos");
    let rd = get(&obs, "RoundNut_pos");
    assert!(
        (-0.115..=-0.11).contains(&sq[0]) && (0.11..=0.225).contains(&sq[1]),
        "{sq:?}"
    );
    assert!(
        (-0.115..=-0.11).contains(&rd[0]) && (-0.225..=-0.11).contains(&rd[1]),
        "{rd:?}"
    );
    assert!((sq[2] - 0.89).abs() < 1e-9);
    // The relative pose: the nut position in the end-effector frame has the same length
    // as the world offset.
    let rel = get(&obs, "SquareNut_to_robot0_eef_pos");
    let eef = get(&obs, "robot0_eef_pos");
    let n1: f64 = rel.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!((n1 - dist3([sq[0], sq[1], sq[2]], &eef)).abs() < 1e-9);

    let mut single = env("NutAssemblySingle", EnvConfig::default());
    let (obs, _) = single.reset(Some(0), None).unwrap();
    assert_eq!(
        obs.get("nut_id").unwrap().as_array().unwrap().dtype(),
        DType::I64
    );
    let mut seen = [false; 2];
    for seed in 0..8 {
        let (obs, _) = single.reset(Some(seed), None).unwrap();
        seen[get(&obs, "nut_id")[0] as usize] = true;
        assert!(get(&obs, "nut_pos")[2] < 1.0);
    }
    assert_eq!(seen, [true, true]);
}

/// Puts nut `i` (0 square at qpos 9, 1 round at qpos 16) at `pos`, flat.
fn set_nut(e: &mut RobosuiteEnv, i: usize, pos: [f64; 3]) {
    let mut s = e.get_state();
    let a = 1 + 9 + 7 * i;
    s[a..a + 3].copy_from_slice(&pos);
    s[a + 3..a + 7].copy_from_slice(&[1.0, 0.0, 0.0, 0.0]);
    e.set_state(&s).unwrap();
}

#[test]
fn round_nut_on_its_peg_with_the_gripper_away_is_a_success() {
    let mut e = env("NutAssemblyRound", EnvConfig::default());
    e.reset(Some(0), None).unwrap();
    let p = PEG_POS[1];
    set_nut(&mut e, 1, [p[0], p[1], 0.83]);
    assert!(e.check_success());
    assert_eq!(e.reward(), 1.0);
    // On the wrong peg, or still high on the peg: no.
    let q = PEG_POS[0];
    set_nut(&mut e, 1, [q[0], q[1], 0.83]);
    assert!(!e.check_success());
    set_nut(&mut e, 1, [p[0], p[1], 0.9]);
    assert!(!e.check_success());

    // Both nuts: one placed is half the normalised reward.
    let mut both = env("NutAssembly", EnvConfig::default());
    both.reset(Some(0), None).unwrap();
    set_nut(&mut both, 1, [p[0], p[1], 0.83]);
    assert!(!both.check_success());
    assert_eq!(both.reward(), 0.5);
    set_nut(&mut both, 0, [q[0], q[1], 0.83]);
    assert!(both.check_success());
    assert_eq!(both.reward(), 1.0);
}

/// Grasp the round nut's handle, lift, bring the ring over peg 2, lower, release.
fn scripted_round(e: &mut RobosuiteEnv, seed: u64, verbose: bool) -> (bool, usize) {
    let (mut obs, _) = e.reset(Some(seed), None).unwrap();
    let peg = PEG_POS[1];
    let mut phase = 0;
    let mut n = 0;
    for t in 0..360 {
        let eef = get(&obs, "robot0_eef_pos");
        let nut = get(&obs, "RoundNut_pos");
        let yaw = yaw_of(&get(&obs, "RoundNut_quat"));
        // The handle site: 6 cm along the nut's x axis.
        let h = [nut[0] + 0.06 * yaw.cos(), nut[1] + 0.06 * yaw.sin(), nut[2]];
        let (target, grip, align) = match phase {
            0 => ([h[0], h[1], h[2] + 0.08], -1.0, true),
            1 => ([h[0], h[1], h[2] + 0.002], -1.0, true),
            2 => ([eef[0], eef[1], eef[2]], 1.0, false),
            3 => ([eef[0], eef[1], 1.02], 1.0, false),
            4 => (
                [peg[0] + eef[0] - nut[0], peg[1] + eef[1] - nut[1], 1.02],
                1.0,
                false,
            ),
            5 => (
                [
                    peg[0] + eef[0] - nut[0],
                    peg[1] + eef[1] - nut[1],
                    eef[2] - nut[2] + 0.84,
                ],
                1.0,
                false,
            ),
            6 => ([eef[0], eef[1], eef[2]], -1.0, false),
            _ => ([eef[0], eef[1], 1.0], -1.0, false),
        };
        // Fingers close across the handle (perpendicular to the nut's x axis).
        let yaw_err = if align {
            wrap_half(yaw + std::f64::consts::FRAC_PI_2 - finger_yaw(&obs))
        } else {
            0.0
        };
        let step = e.step(&move_to(&eef, target, 10.0, yaw_err, grip)).unwrap();
        obs = step.observation;
        if verbose {
            eprintln!("t {t} ph {phase} eef {eef:.3?} nut {nut:.3?} yaw_err {yaw_err:.3}");
        }
        if step.info.get_bool("success") == Some(true) {
            return (true, t + 1);
        }
        n += 1;
        let d = dist3(target, &eef);
        let next = match phase {
            0 => (d < 0.01 && yaw_err.abs() < 0.05) || n > 60,
            1 => d < 0.005 || n > 40,
            2 | 6 => n >= 12,
            3 => d < 0.02 || n > 40,
            4 => d < 0.004 || n > 80,
            5 => d < 0.01 || n > 50,
            _ => false,
        };
        if next {
            phase += 1;
            n = 0;
        }
    }
    (false, 360)
}

#[test]
fn scripted_policy_solves_nut_assembly_round() {
    let mut e = env("NutAssemblyRound", EnvConfig::default().with_horizon(400));
    let verbose = std::env::var_os("NUT_VERBOSE").is_some();
    let mut ok = 0;
    let mut report = Vec::new();
    for seed in 0..3 {
        let r = scripted_round(&mut e, seed, verbose);
        ok += usize::from(r.0);
        report.push(r);
    }
    assert!(
        ok >= 2,
        "scripted NutAssemblyRound succeeded on {ok}/3 seeds: {report:?}"
    );
}
