//! robosuite's `make` arguments beyond the RL loop. The tasks' constructor arguments as
//! task options: every argument robosuite 1.5.2 declares is one here with robosuite's
//! default (recorded by `scripts/record_task_args.py`), options reach the scene, and bad
//! ones are typed errors. `placement_initializer`, `lite_physics`, `base_types` (scenes
//! recorded by `scripts/record_bases.py`) and the env step taken one substep at a time.

use crate::common::get;
use gym_core::{Env, Error};
use ndarray::ArrayD;
use robosuite_env::sim::{body_id, geom_id, joint_id};
use robosuite_env::{ENV_NAMES, EnvConfig, make_task, make_with};
use serde_json::{Value, json};

fn recorded() -> Value {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/task_args.json");
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// JSON values equal as robosuite's (integers and floats compared as numbers).
fn same(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => x.as_f64() == y.as_f64(),
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(x, y)| same(x, y))
        }
        _ => a == b,
    }
}

#[test]
fn every_robosuite_task_argument_is_an_option_with_robosuite_default() {
    let recorded = recorded();
    let wipe_default = &recorded["wipe_default_config"];
    let mut checked = 0;
    for &name in ENV_NAMES {
        let options = make_task(name).unwrap().options();
        let args = recorded["tasks"][name]
            .as_object()
            .unwrap_or_else(|| panic!("{name} not recorded"));
        for (arg, default) in args {
            let ours = options
                .get(arg)
                .unwrap_or_else(|| panic!("{name}: robosuite's `{arg}` is not an option"));
            if name == "Wipe" && arg == "task_config" {
                // robosuite's default None means DEFAULT_WIPE_CONFIG.
                for (key, value) in wipe_default.as_object().unwrap() {
                    if key == "print_results" || key == "get_info" {
                        assert_eq!(value, &json!(false));
                        continue;
                    }
                    assert!(
                        same(&ours[key], value),
                        "Wipe {key}: {} vs {value}",
                        ours[key]
                    );
                }
            } else {
                assert!(
                    same(ours, default),
                    "{name} {arg}: ours {ours}, robosuite {default}"
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 30, "{checked}");
}

#[test]
fn options_reach_the_scene() {
    // Lift's table: the collision box is half the full size.
    let config = EnvConfig::default().with_task_option("table_full_size", json!([1.0, 0.6, 0.05]));
    let env = make_with("Lift", config).unwrap();
    let m = env.sim().model();
    assert_eq!(
        m.geom_size()[geom_id(m, "table_collision").unwrap()],
        [0.5, 0.3, 0.025]
    );
    assert_eq!(
        env.task_options()["table_full_size"],
        json!([1.0, 0.6, 0.05])
    );

    // Door without the latch: no latch joint and no handle observation, as robosuite.
    let with = make_with("Door", EnvConfig::default()).unwrap();
    let without = make_with(
        "Door",
        EnvConfig::default().with_task_option("use_latch", false),
    )
    .unwrap();
    assert!(joint_id(with.sim().model(), "Door_latch_joint").is_ok());
    assert!(joint_id(without.sim().model(), "Door_latch_joint").is_err());
    assert!(with.observation_keys().contains(&"handle_qpos".to_owned()));
    assert!(
        !without
            .observation_keys()
            .contains(&"handle_qpos".to_owned())
    );

    // PickPlace's modes equal the registered variants.
    let config = EnvConfig::default()
        .with_task_option("single_object_mode", 2)
        .with_task_option("object_type", "can");
    let base = make_with("PickPlace", config).unwrap();
    let can = make_with("PickPlaceCan", EnvConfig::default()).unwrap();
    assert_eq!(base.observation_keys(), can.observation_keys());
    let nut = EnvConfig::default().with_task_option("single_object_mode", 1);
    let single = make_with("NutAssembly", nut).unwrap();
    let variant = make_with("NutAssemblySingle", EnvConfig::default()).unwrap();
    assert_eq!(single.observation_keys(), variant.observation_keys());

    // Wipe's task_config: a partial dict changes those keys.
    let config = EnvConfig::default().with_task_option("task_config", json!({"num_markers": 30}));
    let env = make_with("Wipe", config).unwrap();
    let m = env.sim().model();
    assert!(body_id(m, "contact29_main").is_ok());
    assert!(body_id(m, "contact30_main").is_err());
    assert_eq!(env.task_options()["task_config"]["num_markers"], 30);
}

#[test]
fn a_placement_initializer_replaces_the_tasks_sampler() {
    // robosuite's UniformRandomSampler arguments: a fixed spot 10 cm ahead, 20 cm left.
    let sampler = json!({
        "x_range": [0.1, 0.1], "y_range": [0.2, 0.2], "rotation": 0.0, "rotation_axis": "z",
        "ensure_object_boundary_in_range": false, "ensure_valid_placement": true,
        "reference_pos": [0.0, 0.0, 0.8], "z_offset": 0.01,
    });
    let config = EnvConfig::default().with_task_option("placement_initializer", sampler.clone());
    let mut env = make_with("Lift", config).unwrap();
    for seed in 0..3 {
        let (obs, _) = env.reset(Some(seed), None).unwrap();
        let pos = get(&obs, "cube_pos");
        assert!(
            (pos[0] - 0.1).abs() < 1e-12 && (pos[1] - 0.2).abs() < 1e-12,
            "{pos:?}"
        );
        assert_eq!(get(&obs, "cube_quat"), [0.0, 0.0, 0.0, 1.0]);
    }
    // NutAssembly gives both nuts to it, as robosuite's add_objects: both in its range
    // (robosuite's own samplers put them at x ≈ -0.11).
    let wide = json!({
        "x_range": [0.1, 0.3], "y_range": [-0.3, 0.3], "rotation": null, "rotation_axis": "z",
        "ensure_object_boundary_in_range": false, "ensure_valid_placement": true,
        "reference_pos": [0.0, 0.0, 0.82], "z_offset": 0.02,
    });
    let config = EnvConfig::default().with_task_option("placement_initializer", wide);
    let mut env = make_with("NutAssembly", config).unwrap();
    let (obs, _) = env.reset(Some(0), None).unwrap();
    for nut in ["SquareNut_pos", "RoundNut_pos"] {
        let p = get(&obs, nut);
        assert!(
            (0.1..=0.3).contains(&p[0]) && p[1].abs() <= 0.3,
            "{nut} {p:?}"
        );
    }
    // A sampler missing an argument or with an unknown axis names it.
    let mut bad = sampler.clone();
    bad["rotation_axis"] = json!("w");
    let config = EnvConfig::default().with_task_option("placement_initializer", bad);
    match make_with("Door", config).unwrap_err() {
        Error::InvalidArgument { name, .. } => assert!(name.contains("rotation_axis"), "{name}"),
        other => panic!("{other:?}"),
    }
    // Tasks robosuite gives no placement_initializer take none here either.
    let config = EnvConfig::default().with_task_option("placement_initializer", sampler);
    assert!(matches!(
        make_with("ToolHang", config),
        Err(Error::InvalidArgument { .. })
    ));
}

#[test]
fn bad_options_are_typed_errors_naming_the_argument() {
    let err = |name: &str, key: &str, value: Value| {
        make_with(name, EnvConfig::default().with_task_option(key, value)).unwrap_err()
    };
    match err("Door", "table_full_size", json!([1, 1, 1])) {
        Error::InvalidArgument { name, reason } => {
            assert_eq!(name, "table_full_size");
            assert!(reason.contains("use_latch"), "{reason}");
        }
        other => panic!("{other:?}"),
    }
    match err("Door", "use_latch", json!("yes")) {
        Error::InvalidArgument { name, .. } => assert_eq!(name, "use_latch"),
        other => panic!("{other:?}"),
    }
    match err("Lift", "table_full_size", json!([1.0, 1.0])) {
        Error::InvalidArgument { name, .. } => assert_eq!(name, "table_full_size"),
        other => panic!("{other:?}"),
    }
    match err("PickPlaceMilk", "single_object_mode", json!(0)) {
        Error::InvalidArgument { name, .. } => assert_eq!(name, "single_object_mode"),
        other => panic!("{other:?}"),
    }
    match err("PickPlace", "object_type", json!("pizza")) {
        Error::InvalidArgument { name, reason } => {
            assert_eq!(name, "object_type");
            assert!(reason.contains("milk"), "{reason}");
        }
        other => panic!("{other:?}"),
    }
    match err("NutAssembly", "single_object_mode", json!(3)) {
        Error::InvalidArgument { name, .. } => assert_eq!(name, "single_object_mode"),
        other => panic!("{other:?}"),
    }
    match err("Wipe", "task_config", json!({"num_markers": 0})) {
        Error::InvalidArgument { name, .. } => assert_eq!(name, "num_markers"),
        other => panic!("{other:?}"),
    }
    match err("Wipe", "task_config", json!({"no_such_key": 1})) {
        Error::InvalidArgument { name, reason } => {
            assert!(name.contains("task_config"), "{name}");
            assert!(reason.contains("no_such_key"), "{reason}");
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        err("Wipe", "task_config", json!({"print_results": true})),
        Error::Unsupported(_)
    ));
    assert!(matches!(
        err("TwoArmHandover", "prehensile", json!(false)),
        Error::Unsupported(_)
    ));
    assert!(matches!(
        err("PickPlace", "z_rotation", json!("x")),
        Error::InvalidArgument { .. }
    ));
    assert!(matches!(
        err("Lift", "table_full_size", json!([f64::MAX, 1.0, -1.0])),
        Error::InvalidArgument { .. }
    ));

    // A failed configure leaves the task as it was.
    let mut spec = make_task("Lift").unwrap();
    let before = spec.options();
    let mut bad = robosuite_env::tasks::TaskOptions::new();
    bad.insert("table_friction".into(), json!([1.0, 0.1, 0.1]));
    bad.insert("table_full_size".into(), json!("wide"));
    assert!(spec.configure(&bad).is_err());
    assert_eq!(spec.options(), before);
}

#[test]
fn lite_physics_off_runs_robosuites_older_substep_with_the_same_trajectory() {
    // robosuite 1.5.2 gives bit-identical trajectories with and without lite physics on
    // Lift (mj_forward + mj_step repeats what mj_step1 + mj_step2 computes); so does this.
    let run = |lite: bool| {
        let config = EnvConfig::default().with_seed(4).with_lite_physics(lite);
        let mut env = make_with("Lift", config).unwrap();
        env.reset(None, None).unwrap();
        let mut states = Vec::new();
        for i in 0..15 {
            let a = ArrayD::from_shape_vec(
                vec![7],
                (0..7).map(|j| ((i * 7 + j) as f64 * 0.37).sin()).collect(),
            )
            .unwrap();
            let _ = env.step(&a).unwrap();
            states.push(env.get_state());
        }
        states
    };
    assert_eq!(run(true), run(false));
}

#[test]
fn a_step_taken_one_substep_at_a_time_is_the_same_step() {
    let mut whole = make_with("Lift", EnvConfig::default().with_seed(2)).unwrap();
    let mut split = make_with("Lift", EnvConfig::default().with_seed(2)).unwrap();
    whole.reset(None, None).unwrap();
    split.reset(None, None).unwrap();
    let a = ArrayD::from_shape_vec(vec![7], vec![0.3, -0.2, 0.1, 0.0, 0.2, -0.1, 1.0]).unwrap();
    // Out of order: no step under way.
    assert!(matches!(
        split.substep(true),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        split.finish_step(),
        Err(Error::InvalidArgument { .. })
    ));
    for _ in 0..5 {
        let step = whole.step(&a).unwrap();
        split.begin_step(&a).unwrap();
        assert!(matches!(
            split.begin_step(&a),
            Err(Error::InvalidArgument { .. })
        ));
        let mut n = 0;
        loop {
            n += 1;
            if split.substep(n % 5 == 0).unwrap() {
                break;
            }
            if n == 3 {
                assert!(matches!(
                    split.finish_step(),
                    Err(Error::InvalidArgument { .. })
                ));
            }
        }
        assert_eq!(n, split.substeps());
        let (transition, _) = split.finish_step().unwrap();
        assert_eq!(transition.reward, step.reward);
        assert_eq!(split.get_state(), whole.get_state());
        assert_eq!(split.observation(), step.observation);
    }
    // A reset abandons a step under way.
    split.begin_step(&a).unwrap();
    split.substep(false).unwrap();
    split.reset(None, None).unwrap();
    split.begin_step(&a).unwrap();
}

#[test]
fn base_types_build_robosuites_scenes() {
    // Recorded from robosuite 1.5.2 by scripts/record_bases.py.
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/bases.json");
    let recorded: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    for scene in recorded["scenes"].as_array().unwrap() {
        let (task, base) = (
            scene["task"].as_str().unwrap(),
            scene["base"].as_str().unwrap(),
        );
        let config = EnvConfig::default().with_base_types([Some(base)]);
        let mut env = make_with(task, config).unwrap();
        env.reset(Some(0), None).unwrap();
        let m = env.sim().model();
        let want: Vec<String> = serde_json::from_value(scene["bodies"].clone()).unwrap();
        assert_eq!(m.ffi().nbody as usize, want.len(), "{task} {base}");
        for (i, name) in want.iter().enumerate().skip(1) {
            assert_eq!(body_id(m, name).ok(), Some(i), "{task} {base} {name}");
        }
        assert_eq!(
            m.ffi().ngeom as u64,
            scene["ngeom"].as_u64().unwrap(),
            "{task} {base}"
        );
        let b = body_id(m, "robot0_base").unwrap();
        let pos = env.sim().data().xpos()[b];
        for (k, want) in scene["base_pos"].as_array().unwrap().iter().enumerate() {
            assert!(
                (pos[k] - want.as_f64().unwrap()).abs() < 1e-9,
                "{task} {base} {pos:?}"
            );
        }
        let mass: f64 = m.body_mass().iter().sum();
        assert!(
            (mass - scene["total_mass"].as_f64().unwrap()).abs() < 1e-6,
            "{task} {base} {mass}"
        );
    }
    let bad = EnvConfig::default().with_base_types([Some("Pedestal")]);
    match make_with("Lift", bad).unwrap_err() {
        Error::InvalidArgument { name, reason } => {
            assert_eq!(name, "base_types");
            assert!(reason.contains("NullMount"), "{reason}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn an_unknown_argument_of_a_task_with_object_modes_lists_the_mode_arguments() {
    let config = EnvConfig::default().with_task_option("bin3_pos", json!([0, 0, 0]));
    match make_with("PickPlace", config).unwrap_err() {
        Error::InvalidArgument { name, reason } => {
            assert_eq!(name, "bin3_pos");
            assert!(
                reason.contains("single_object_mode") && reason.contains("object_type"),
                "{reason}"
            );
        }
        other => panic!("{other:?}"),
    }
    // A variant fixes them, so its list does not offer them.
    let config = EnvConfig::default().with_task_option("bin3_pos", json!([0, 0, 0]));
    match make_with("PickPlaceCan", config).unwrap_err() {
        Error::InvalidArgument { reason, .. } => {
            assert!(
                !reason.contains("single_object_mode") && reason.contains("bin1_pos"),
                "{reason}"
            );
        }
        other => panic!("{other:?}"),
    }
}
