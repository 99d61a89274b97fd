//! Skipping sensor computation on the substeps whose sensors nobody reads leaves the
//! trajectory and the sensors read after each env step bit-identical.

use gym_core::Env;
use robosuite_env::sim::Sim;
use robosuite_env::{EnvConfig, make_with};

/// Runs `blocks` env steps' worth of substeps on two copies of `task`'s model, one with
/// sensors on every substep and one with sensors only on each block's last substep, and
/// compares them bit for bit after every block.
fn compare(task: &str, blocks: usize) {
    let mut env = make_with(task, EnvConfig::default()).unwrap();
    env.reset(Some(3), None).unwrap();
    let substeps = env.substeps();
    let mut always = Sim::new(env.sim().model().clone()).unwrap();
    let mut skipping = Sim::new(env.sim().model().clone()).unwrap();
    for sim in [&mut always, &mut skipping] {
        sim.set_state(&env.get_state()).unwrap();
        sim.forward().unwrap();
    }
    let mut robot_a = env.robots()[0].clone();
    let mut robot_b = env.robots()[0].clone();
    let flags = skipping.model().opt().disableflags;
    let mut sensors_changed = false;
    let mut skipped = false;
    for block in 0..blocks {
        // Pushes down and sideways so that the gripper meets the table and objects.
        let action = [
            0.6 * (block as f64 * 0.7).sin(),
            0.5 * (block as f64 * 0.3).cos(),
            -0.8,
            0.0,
            0.1,
            -0.2,
            if block % 10 < 5 { 1.0 } else { -1.0 },
        ];
        let before = skipping.data().sensordata().to_vec();
        for sub in 0..substeps {
            for (sim, robot) in [(&mut always, &mut robot_a), (&mut skipping, &mut robot_b)] {
                sim.step1().unwrap();
                if sub == 0 {
                    robot.set_goal(sim, &action);
                }
                robot.apply_control(sim);
            }
            always.step2().unwrap();
            if sub + 1 == substeps {
                skipping.step2().unwrap();
            } else {
                skipping.step2_without_sensors().unwrap();
                assert_eq!(skipping.model().opt().disableflags, flags);
                // The skipped substeps really skip: their sensors are stale.
                skipped |= always.data().sensordata() != skipping.data().sensordata();
            }
        }
        assert_eq!(
            always.state(),
            skipping.state(),
            "{task}: trajectories differ after env step {block}"
        );
        assert_eq!(
            always.data().sensordata(),
            skipping.data().sensordata(),
            "{task}: sensors differ after env step {block}"
        );
        assert_eq!(
            always.data().qacc_warmstart(),
            skipping.data().qacc_warmstart()
        );
        sensors_changed |= before != skipping.data().sensordata();
    }
    assert!(sensors_changed, "{task}: the sensors never changed");
    assert!(skipped, "{task}: no substep skipped its sensors");
}

#[test]
fn lift_is_bit_identical() {
    compare("Lift", 40);
}

#[test]
fn wipe_is_bit_identical() {
    compare("Wipe", 40);
}
