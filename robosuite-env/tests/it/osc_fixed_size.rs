//! `OSC_POSE` and `OSC_POSITION` on fixed-size matrices (arms of up to 7 joints) against
//! the same controllers on heap-sized matrices: bit-identical torques at every substep (so
//! bit-identical trajectories) and controller states, for every arm of every robot, under
//! random actions: on the Panda (7 joints) and the UR5e (6) in every input type, frame,
//! impedance mode and coupling, with and without interpolation and goal limits; on the
//! other robots in three of these.

use gym_core::rng_from_seed;
use nalgebra::Rotation3;
use rand::RngExt;
use robosuite_env::controllers::config::{
    Bounds, ImpedanceMode, InputRefFrame, InputType, Interpolation, OscConfig, PerAxis,
};
use robosuite_env::controllers::{ArmBinding, ArmController, Osc, Timing};
use robosuite_env::models::robots::ROBOTS;
use robosuite_env::sim::{Sim, site_id};
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};

/// robosuite's substeps per env step at 20 Hz control and a 2 ms timestep.
const SUBSTEPS: usize = 25;

const TIMING: Timing = Timing {
    timestep: 0.002,
    control_freq: 20.0,
};

/// The controller variants compared: `(label, use_ori, config)`.
fn cases() -> Vec<(&'static str, bool, OscConfig)> {
    let base = OscConfig::default();
    vec![
        ("OSC_POSE delta", true, base.clone()),
        (
            "OSC_POSE delta world coupled",
            true,
            OscConfig {
                input_ref_frame: InputRefFrame::World,
                uncouple_pos_ori: false,
                ..base.clone()
            },
        ),
        (
            "OSC_POSE absolute",
            true,
            OscConfig {
                input_type: InputType::Absolute,
                ..base.clone()
            },
        ),
        (
            "OSC_POSE variable",
            true,
            OscConfig {
                impedance_mode: ImpedanceMode::Variable,
                damping_ratio_limits: Bounds::uniform(0.5, 2.0),
                ..base.clone()
            },
        ),
        (
            "OSC_POSE variable_kp linear limits",
            true,
            OscConfig {
                impedance_mode: ImpedanceMode::VariableKp,
                interpolation: Interpolation::Linear,
                orientation_limits: Some(Bounds::uniform(-2.5, 2.5)),
                ..base.clone()
            },
        ),
        ("OSC_POSITION delta", false, base.clone()),
        (
            "OSC_POSITION absolute coupled variable_kp",
            false,
            OscConfig {
                input_type: InputType::Absolute,
                uncouple_pos_ori: false,
                impedance_mode: ImpedanceMode::VariableKp,
                ..base
            },
        ),
    ]
}

/// Arm `arm` of the env's robot, as the robot binds it.
fn binding(env: &RobosuiteEnv, arm: usize) -> (ArmBinding, Vec<usize>) {
    let robot = &env.robots()[0];
    let a = &robot.arms()[arm];
    let model = env.sim().model();
    let bind = ArmBinding {
        site: a.eef_site(),
        base_site: site_id(model, &format!("robot0_{}_center", a.side())).unwrap(),
        qpos: robot.joint_qpos()[a.joints()].to_vec(),
        dofs: robot.joint_dofs()[a.joints()].to_vec(),
        nv: model.ffi().nv as usize,
        ctrlrange: a.ctrlrange().to_vec(),
        stale_goal_origin: false,
    };
    (bind, a.actuators().to_vec())
}

fn snapshot_sim(env: &RobosuiteEnv) -> Sim {
    let mut sim = Sim::new(env.sim().model().clone()).unwrap();
    sim.set_state(&env.get_state()).unwrap();
    sim
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Runs [`STEPS`] env steps of random actions on a copy of the env's state, both
/// controllers computing at every substep and the fixed-size one driving the arm; asserts
/// equal torque bits at every substep (so the dynamic controller would drive the arm along
/// the same trajectory, bit for bit) and equal controller state bits after every env step.
/// Returns the largest torque applied (to show the arm was driven).
fn compare(
    env: &RobosuiteEnv,
    arm: usize,
    label: &str,
    use_ori: bool,
    mut config: OscConfig,
) -> f64 {
    let (bind, actuators) = binding(env, arm);
    let what = format!("{} arm {arm}: {label}", env.robots()[0].name());
    let mut sim = snapshot_sim(env);
    let n = bind.dofs.len();
    // Goal limits around the reset pose, narrow enough that random deltas reach them.
    let mut probe = Osc::new(&config, use_ori, bind.clone(), TIMING, "c").unwrap();
    probe.reset(&sim);
    let home = probe.goal_pos();
    let home_rotvec = Rotation3::from_matrix(&probe.goal_ori()).scaled_axis();
    if label.contains("limits") {
        config.position_limits = Some(Bounds(
            PerAxis::List(home.iter().map(|v| v - 0.08).collect()),
            PerAxis::List(home.iter().map(|v| v + 0.08).collect()),
        ));
    }
    let mut fixed = Osc::new(&config, use_ori, bind.clone(), TIMING, "c").unwrap();
    let mut dynamic = Osc::new(&config, use_ori, bind, TIMING, "c")
        .unwrap()
        .with_dynamic_matrices();
    assert!(fixed.uses_fixed_size(), "{what}");
    assert!(!dynamic.uses_fixed_size(), "{what}");
    fixed.reset(&sim);
    dynamic.reset(&sim);
    let (lo, hi) = fixed.action_limits();
    let gains = lo.len() - if use_ori { 6 } else { 3 };
    let mut rng = rng_from_seed(3);
    let (mut tf, mut td) = (vec![0.0; n], vec![0.0; n]);
    let mut peak = 0.0f64;
    for step in 0..STEPS {
        let mut action: Vec<f64> = (0..lo.len())
            .map(|i| rng.random_range(lo[i]..=hi[i]))
            .collect();
        if config.input_type == InputType::Absolute {
            // A goal near the reset pose (a random absolute pose is out of reach).
            for i in 0..3 {
                action[gains + i] = home[i] + rng.random_range(-0.1..=0.1);
                if use_ori {
                    action[gains + 3 + i] = home_rotvec[i] + rng.random_range(-0.3..=0.3);
                }
            }
        }
        for sub in 0..SUBSTEPS {
            sim.step1().unwrap();
            if sub == 0 {
                fixed.set_goal(&sim, &action);
                dynamic.set_goal(&sim, &action);
            }
            fixed.compute(&sim, &mut tf);
            dynamic.compute(&sim, &mut td);
            assert_eq!(bits(&tf), bits(&td), "{what}: step {step} substep {sub}");
            let ranges = fixed.binding().ctrlrange.iter();
            for ((&a, t), [lo, hi]) in actuators.iter().zip(&tf).zip(ranges) {
                let t = t.clamp(*lo, *hi);
                peak = peak.max(t.abs());
                sim.data_mut().ctrl_mut()[a] = t;
            }
            sim.step2().unwrap();
        }
        assert_eq!(
            bits(&fixed.state()),
            bits(&dynamic.state()),
            "{what}: step {step}"
        );
    }
    peak
}

/// Env steps per case (500 substeps, 500 torque computations).
const STEPS: usize = 20;

/// Every case of [`cases`] whose label is in `only` (all when empty), on every arm of
/// `robot`.
fn check_robot(robot: &str, only: &[&str]) {
    let info = ROBOTS.iter().find(|r| r.name == robot).unwrap();
    let task = if info.arms.len() == 1 {
        "Lift"
    } else {
        "TwoArmLift"
    };
    let mut env = make_with(task, EnvConfig::default().with_robots([robot])).unwrap();
    gym_core::Env::reset(&mut env, Some(1), None).unwrap();
    let mut checked = 0;
    for arm in 0..info.arms.len() {
        for (label, use_ori, config) in cases() {
            if only.is_empty() || only.contains(&label) {
                let peak = compare(&env, arm, label, use_ori, config);
                assert!(peak > 1e-3, "{robot} {label}: the arm was not driven");
                checked += 1;
            }
        }
    }
    assert!(
        checked >= info.arms.len() * only.len().max(1),
        "{robot}: {checked} cases"
    );
}

/// The cases run on the robots whose arm size another robot already covers in full.
const SOME: &[&str] = &[
    "OSC_POSE delta",
    "OSC_POSE variable",
    "OSC_POSITION absolute coupled variable_kp",
];

#[test]
fn every_case_on_the_panda_is_bit_identical() {
    check_robot("Panda", &[]);
}

#[test]
fn every_case_on_the_six_joint_ur5e_is_bit_identical() {
    check_robot("UR5e", &[]);
}

#[test]
fn the_other_robots_and_both_baxter_arms_are_bit_identical() {
    let mut covered = vec!["Panda", "UR5e"];
    for robot in [
        "Sawyer",
        "IIWA",
        "Jaco",
        "Kinova3",
        "XArm7",
        "Baxter",
        "PandaOmron",
        "Tiago",
        "SpotWithArm",
        "SpotWithArmFloating",
        "PandaDexRH",
        "PandaDexLH",
        "GR1",
        "GR1ArmsOnly",
        "GR1FloatingBody",
    ] {
        check_robot(robot, SOME);
        covered.push(robot);
    }
    // GR1FixedLowerBody's arms are GR1's (its default composite controller is not served).
    covered.push("GR1FixedLowerBody");
    // Every robot of the table is covered.
    for r in ROBOTS {
        assert!(covered.contains(&r.name), "{} is not covered", r.name);
    }
}

#[test]
fn arms_of_more_than_seven_joints_are_not_fixed_size_and_small_ones_are() {
    let env = make_with("Lift", EnvConfig::default()).unwrap();
    let (bind, _) = binding(&env, 0);
    let config = OscConfig::default();
    for n in 1..=9 {
        let mut b = bind.clone();
        b.dofs = (0..n).map(|i| bind.dofs[i % bind.dofs.len()]).collect();
        b.qpos = (0..n).map(|i| bind.qpos[i % bind.qpos.len()]).collect();
        b.ctrlrange = vec![[-1.0, 1.0]; n];
        let osc = Osc::new(&config, true, b, TIMING, "c").unwrap();
        assert_eq!(osc.uses_fixed_size(), n <= 7, "{n} joints");
        assert!(!osc.with_dynamic_matrices().uses_fixed_size());
    }
}
