//! A task written outside the crate, from public items only: "LiftHigh", robosuite's Lift
//! with a fixed-size cube that must rise 10 cm above the table.
//!
//! `cargo run -p robosuite-env --example custom_task` makes it, resets it and steps it;
//! `cargo test` runs the same through the test below.

use ndarray::{ArrayD, IxDyn};
use robosuite_env::prelude::*;

/// The configuration: what `_load_model` needs (here only the cube's size).
#[derive(Debug, Clone)]
struct LiftHighSpec {
    half: f64,
}

impl TaskSpec for LiftHighSpec {
    fn name(&self) -> &str {
        "LiftHigh"
    }

    fn build(&self, assets: &Assets, _robots: &mut [RobotModel]) -> Result<TaskScene> {
        let arena = table_arena(assets, [0.8, 0.8, 0.05], [1.0, 5e-3, 1e-4], TABLE_OFFSET)?;
        let mut cube = Primitive::new("cube", Shape::Box([self.half; 3]));
        cube.rgba = [0.9, 0.5, 0.1, 1.0];
        Ok(TaskScene {
            arena,
            objects: vec![cube.build()?],
            attached: Vec::new(),
        })
    }

    fn bind(&self, scene: &TaskScene, model: &MjModel, _robots: &[Robot]) -> Result<Box<dyn Task>> {
        let cube = &scene.objects[0];
        let task = LiftHigh {
            cube: FreeBody::bind(model, cube)?,
            extent: cube.placement(),
        };
        let observables = vec![
            Observable::vec("cube_pos", Modality::Object, |t: &LiftHigh, sim| {
                t.cube.pos(sim)
            }),
            Observable::vec("cube_height", Modality::Object, |t: &LiftHigh, sim| {
                [t.cube.pos(sim)[2] - TABLE_OFFSET[2]]
            }),
        ];
        Ok(Bound::boxed(task, observables))
    }
}

/// The run-time task: the ids it reads.
#[derive(Debug)]
struct LiftHigh {
    cube: FreeBody,
    extent: PlacedObject,
}

impl TaskLogic for LiftHigh {
    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let sampler = UniformRandomSampler {
            x_range: [-0.05, 0.05],
            y_range: [-0.05, 0.05],
            rotation: Rotation::Random,
            rotation_axis: Axis::Z,
            ensure_object_boundary_in_range: false,
            ensure_valid_placement: true,
            reference_pos: TABLE_OFFSET,
            z_offset: 0.01,
        };
        let (pos, quat) = sampler.sample(rng, &[self.extent], &[])?[0];
        self.cube.set_pose(sim, pos, quat);
        Ok(())
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let reward = if self.check_success(sim, robots) {
            1.0
        } else if config.reward_shaping {
            0.5 * (1.0 - (10.0 * dist(eef_pos(sim, robots), self.cube.pos(sim))).tanh())
        } else {
            0.0
        };
        scale_reward(reward, config.reward_scale, 1.0)
    }

    fn check_success(&self, sim: &Sim, _robots: &[Robot]) -> bool {
        self.cube.pos(sim)[2] > TABLE_OFFSET[2] + 0.10
    }
}

/// Makes LiftHigh, resets it and takes `steps` steps; returns the observation keys
/// and the rewards.
fn run(steps: usize) -> Result<(Vec<String>, Vec<f64>)> {
    let mut env = RobosuiteEnv::new(&LiftHighSpec { half: 0.02 }, EnvConfig::default())?;
    let (obs, _info) = env.reset(Some(0), None)?;
    let keys = obs.keys().cloned().collect();
    let mut rewards = Vec::with_capacity(steps);
    for k in 0..steps {
        // A fixed wiggle of every action dimension.
        let action = ArrayD::from_shape_fn(IxDyn(&[env.action_dim()]), |i| {
            (0.7 * (k + i[0]) as f64).sin()
        });
        rewards.push(env.step(&action)?.reward);
    }
    Ok((keys, rewards))
}

fn main() -> Result<()> {
    let (keys, rewards) = run(20)?;
    println!("LiftHigh observation keys: {}", keys.join(", "));
    println!("rewards of 20 steps: {rewards:.3?}");
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn lift_high_runs() {
        let (keys, rewards) = super::run(5).unwrap();
        let task_keys: Vec<&str> = keys
            .iter()
            .map(String::as_str)
            .filter(|k| !k.starts_with("robot0_"))
            .collect();
        assert_eq!(task_keys, ["cube_pos", "cube_height", "object-state"]);
        assert_eq!(rewards.len(), 5);
        assert!(rewards.iter().all(|r| r.is_finite()));
    }
}
