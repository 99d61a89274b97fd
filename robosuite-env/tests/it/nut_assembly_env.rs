//! The NutAssembly family: observation layouts, placement, single-object modes, hand-set
//! reward / success, a scripted policy, task states and the MuJoCo arena.

use crate::common::object_tasks::{
    PlacePolicy, arena_use, assert_spread, assert_task_states_rejected, assert_variant_layouts,
    body_pos, probe_actions, random_episodes, set_free_joint,
};
use crate::common::{
    action, assert_scripted_successes, assert_snapshot_replays, finger_yaw, get, wrap_half, yaw_of,
};
use gym_core::{DictValue, Env, Error};
use robosuite_env::sim::site_id;
use robosuite_env::tasks::common::ObjectMode;
use robosuite_env::tasks::{NUTS, NutAssemblySpec};
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};

fn env(name: &str, config: EnvConfig) -> RobosuiteEnv {
    make_with(name, config).unwrap_or_else(|e| panic!("{name} builds: {e}"))
}

/// The pegs (bodies `peg1`, `peg2`) of robosuite's `PegsArena`.
const PEGS: [[f64; 2]; 2] = [[0.23, 0.1], [0.23, -0.1]];

const FLAT: [f64; 4] = [1.0, 0.0, 0.0, 0.0];

/// Puts nut `i` (0 square, 1 round) flat at `pos`.
fn put_nut(env: &mut RobosuiteEnv, i: usize, pos: [f64; 3]) {
    set_free_joint(env, &format!("{}_joint0", NUTS[i]), pos, FLAT);
}

#[test]
fn variants_have_robosuites_observation_layouts() {
    // Mode 1: robosuite names the keys after each reset's nut; here they are `nut_*`,
    // followed by robosuite's `nut_id`.
    assert_variant_layouts(
        &[
            ("NutAssembly", &NUTS[..]),
            ("NutAssemblySquare", &["SquareNut"][..]),
            ("NutAssemblyRound", &["RoundNut"][..]),
        ],
        [23, 21, 9, 29, 120],
        "NutAssemblySingle",
        "nut",
    );
    // The relative pose, as robosuite computes it from its observation cache: the nut
    // position of the previous observation in the current grip frame (zero at reset).
    let mut both = env("NutAssembly", EnvConfig::default());
    let (first, _) = both.reset(Some(3), None).unwrap();
    assert_eq!(get(&first, "SquareNut_to_robot0_eef_pos"), vec![0.0; 3]);
    let obs = both.step(&action([0.0; 7])).unwrap().observation;
    let rel = get(&obs, "SquareNut_to_robot0_eef_pos");
    let (nut, eef) = (get(&first, "SquareNut_pos"), get(&obs, "robot0_eef_pos"));
    let world: f64 = (0..3)
        .map(|i| (nut[i] - eef[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    let local: f64 = rel.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!((local - world).abs() < 1e-12, "{local} vs {world}");
}

#[test]
fn placement_follows_robosuites_samplers() {
    let mut e = env("NutAssembly", EnvConfig::default());
    let mut yaws = Vec::new();
    for seed in 0..20 {
        let (obs, _) = e.reset(Some(seed), None).unwrap();
        let sq = get(&obs, "SquareNut_pos");
        let rd = get(&obs, "RoundNut_pos");
        for (p, y_range) in [(&sq, (0.11, 0.225)), (&rd, (-0.225, -0.11))] {
            assert!((-0.115..=-0.11).contains(&p[0]), "{p:?}");
            assert!((y_range.0..=y_range.1).contains(&p[1]), "{p:?}");
            // 2 cm above the table top, the bottom 5 cm below the origin.
            assert!((p[2] - 0.89).abs() < 1e-12, "{p:?}");
        }
        yaws.push(yaw_of(&get(&obs, "RoundNut_quat")));
    }
    assert_spread(&yaws);
}

#[test]
fn single_modes_keep_one_nut_and_park_the_other() {
    let mut single = env("NutAssemblySingle", EnvConfig::default());
    let mut seen = [false; 2];
    for seed in 0..10 {
        let (obs, _) = single.reset(Some(seed), None).unwrap();
        let id = get(&obs, "nut_id")[0] as usize;
        seen[id] = true;
        assert_eq!(
            get(&obs, "nut_pos"),
            body_pos(&single, &format!("{}_main", NUTS[id])).to_vec()
        );
        assert_eq!(
            body_pos(&single, &format!("{}_main", NUTS[1 - id])),
            [10.0; 3]
        );
    }
    assert_eq!(seen, [true, true]);
    let mut square = env("NutAssemblySquare", EnvConfig::default());
    square.reset(Some(1), None).unwrap();
    assert!(body_pos(&square, "SquareNut_main")[2] < 1.0);
    assert_eq!(body_pos(&square, "RoundNut_main"), [10.0; 3]);
}

#[test]
fn reward_and_success_on_hand_set_states() {
    let [sq_peg, rd_peg] = PEGS;
    let mut round = env("NutAssemblyRound", EnvConfig::default());
    round.reset(Some(0), None).unwrap();
    put_nut(&mut round, 1, [rd_peg[0], rd_peg[1], 0.83]);
    assert!(round.check_success());
    assert_eq!(round.reward(), 1.0);
    // On the wrong peg, or at the table top + 0.05: not on its peg.
    put_nut(&mut round, 1, [sq_peg[0], sq_peg[1], 0.83]);
    assert!(!round.check_success());
    put_nut(&mut round, 1, [rd_peg[0], rd_peg[1], 0.87]);
    assert!(!round.check_success());
    // Within 3 cm of the peg in x and y counts.
    put_nut(&mut round, 1, [rd_peg[0] + 0.029, rd_peg[1] - 0.029, 0.83]);
    assert!(round.check_success());

    // Both nuts: one placed is half the normalised reward.
    let mut both = env("NutAssembly", EnvConfig::default());
    both.reset(Some(0), None).unwrap();
    put_nut(&mut both, 1, [rd_peg[0], rd_peg[1], 0.83]);
    assert!(!both.check_success());
    assert_eq!(both.reward(), 0.5);
    put_nut(&mut both, 0, [sq_peg[0], sq_peg[1], 0.83]);
    assert!(both.check_success());
    assert_eq!(both.reward(), 1.0);

    // Shaped, unnormalised: the nut 1 cm beside its peg and too high is worth the hover
    // term; far from its peg, the reaching term towards its handle site.
    let mut shaped = env(
        "NutAssemblyRound",
        EnvConfig::default()
            .with_reward_shaping(true)
            .with_reward_scale(None),
    );
    shaped.reset(Some(0), None).unwrap();
    put_nut(&mut shaped, 1, [rd_peg[0] + 0.01, rd_peg[1], 1.0]);
    let hover = (1.0 - 0.1f64.tanh()) * (0.7 - 0.5);
    assert!(
        (shaped.reward() - hover).abs() < 1e-12,
        "{}",
        shaped.reward()
    );
    let (obs, _) = shaped.reset(Some(0), None).unwrap();
    let nut = get(&obs, "RoundNut_pos");
    let eef = get(&obs, "robot0_eef_pos");
    let handle = shaped.sim().data().site_xpos()
        [site_id(shaped.sim().model(), "RoundNut_handle_site").unwrap()];
    let d_handle = (0..3)
        .map(|i| (handle[i] - eef[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    let d_peg = ((nut[0] - rd_peg[0]).powi(2) + (nut[1] - rd_peg[1]).powi(2)).sqrt();
    let reach = (1.0 - (10.0 * d_handle).tanh()) * 0.1;
    let hover = (1.0 - (10.0 * d_peg).tanh()) * (0.7 - 0.5);
    assert!(
        (shaped.reward() - reach.max(hover)).abs() < 1e-12,
        "{}",
        shaped.reward()
    );
}

#[test]
fn scripted_policy_solves_nut_assembly_round() {
    let mut e = env("NutAssemblyRound", EnvConfig::default().with_horizon(300));
    let policy = PlacePolicy {
        // The handle, 6 cm along the nut's x axis, with the fingers across it.
        grab: |obs: &DictValue| {
            let nut = get(obs, "RoundNut_pos");
            let yaw = yaw_of(&get(obs, "RoundNut_quat"));
            let point = [
                nut[0] + 0.06 * yaw.cos(),
                nut[1] + 0.06 * yaw.sin(),
                nut[2] + 0.002,
            ];
            (
                point,
                wrap_half(yaw + std::f64::consts::FRAC_PI_2 - finger_yaw(obs)),
            )
        },
        object_key: "RoundNut_pos",
        goal: PEGS[1],
        carry_z: 1.02,
        release_z: 0.84,
    };
    assert_scripted_successes("NutAssemblyRound", &mut e, 3, 2, |env, seed| {
        policy
            .run(env, seed, 300)
            .map_or((false, 300), |t| (true, t))
    });
}

#[test]
fn task_state_round_trips_and_bad_states_are_rejected() {
    let mut e = env("NutAssemblySingle", EnvConfig::default());
    e.reset(Some(2), None).unwrap();
    let state = e.get_state();
    let task = e.task().save_state();
    assert_eq!(task.len(), 1 + 7);
    let id = task[0];
    let _ = e
        .step(&action([0.3, 0.1, -0.2, 0.0, 0.0, 0.1, 1.0]))
        .unwrap();
    assert_snapshot_replays(&mut e, &probe_actions(), 1);

    // The other nut can be put in play by a recorded start.
    let other = 1.0 - id;
    let (obs, _) = e.reset_to_state(&[other], &state).unwrap();
    assert_eq!(get(&obs, "nut_id"), vec![other]);
    let nut = NUTS[other as usize];
    assert_eq!(
        get(&obs, "nut_pos"),
        body_pos(&e, &format!("{nut}_main")).to_vec()
    );
    let bad = [
        vec![],
        vec![2.0],
        vec![0.5],
        vec![f64::INFINITY],
        vec![id, 1.0],
    ];
    assert_task_states_rejected(&mut e, &bad, &state);
    let mut round = env("NutAssemblyRound", EnvConfig::default());
    round.reset(Some(0), None).unwrap();
    let s = round.get_state();
    assert!(round.reset_to_state(&[1.0], &s).is_ok());
    assert!(round.reset_to_state(&[0.0], &s).is_err());
    let mut both = env("NutAssembly", EnvConfig::default());
    both.reset(Some(0), None).unwrap();
    assert_eq!(both.task().save_state().len(), 2 * 7);
    assert!(both.reset_to_state(&[0.0], &both.get_state()).is_err());
}

#[test]
fn invalid_nut_ids_are_rejected() {
    assert!(matches!(
        NutAssemblySpec::new(ObjectMode::Single(2)),
        Err(Error::InvalidArgument { .. })
    ));
    let spec = NutAssemblySpec::new(ObjectMode::Single(0)).unwrap();
    assert_eq!(
        robosuite_env::tasks::TaskSpec::name(&spec),
        "NutAssemblySquare"
    );
    assert!(NutAssemblySpec::variant("NutAssemblyHex").is_none());
}

#[test]
fn the_mujoco_arena_suffices_for_stacked_nuts_and_long_random_rollouts() {
    // The most contacts: the round nut lying on the square one, both on the table (box
    // pairs give up to 8 contacts each).
    let mut e = env("NutAssembly", EnvConfig::default().with_horizon(500));
    e.reset(Some(0), None).unwrap();
    put_nut(&mut e, 0, [0.0, 0.0, 0.8299]);
    let turned = [0.92388, 0.0, 0.0, 0.38268];
    set_free_joint(&mut e, "RoundNut_joint0", [0.0, 0.0, 0.8499], turned);
    let mut most = 0;
    for _ in 0..40 {
        let _ = e.step(&action([0.0; 7])).unwrap();
        most = most.max(e.sim().data().contact().len());
    }
    assert!(
        most >= 60,
        "the nuts touch each other and the table: {most} contacts"
    );
    random_episodes(&mut e, 2);
    let (used, reserved) = arena_use(&e);
    // Measured: about 390 KB of the default 2 MiB.
    assert!(used < reserved / 4, "{used} of {reserved} bytes");
}
