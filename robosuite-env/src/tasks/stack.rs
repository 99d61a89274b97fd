//! robosuite's `Stack`: put the red cube A on the green cube B (`stack.py`).

use super::common::{FreeBody, dist, dist_xy, eef_pos, is_grasped, scale_reward, xyzw};
use super::placement::{Axis, PlacedObject, Rotation, UniformRandomSampler};
use super::{ModelSource, RewardConfig, Task};
use crate::models::arenas::TableArena;
use crate::models::objects::BoxObject;
use crate::models::scene::SceneBuilder;
use crate::observations::ObsKey;
use crate::robots::Robot;
use crate::sim::{Sim, any_contact_between};
use gym_core::{DType, EnvRng, Result};
use mujoco_rs::wrappers::mj_model::MjModel;

/// Half-size of cube A (red, 0.02, 0.064 kg).
pub const CUBE_A_HALF: f64 = 0.02;
/// Half-size of cube B (green, 0.025, 0.125 kg).
pub const CUBE_B_HALF: f64 = 0.025;

/// The Stack task: cubes `cubeA` (bodies `cubeA_main`, joint `cubeA_joint0`, geom
/// `cubeA_g0`) and `cubeB` on Lift's table.
///
/// * Reset: both cubes `U(±0.08)²` around the table centre, yaw `U(0, 2π)`, 1 cm above
///   the table, without overlap (rejection sampling, a typed error after 5000 tries).
/// * Reward (robosuite's `staged_rewards`): reach `0.25·(1 − tanh(10 d(eef, A)))` + 0.25
///   when A is grasped; lift `1 + 0.5·(1 − tanh(‖A_xy − B_xy‖))` when A is 4 cm above
///   the table; stack 2 when A touches B, is lifted and not grasped. Shaped: the maximum;
///   sparse: 2 on stack; scaled by `reward_scale / 2`.
/// * Success: the stack stage.
#[derive(Debug, Clone)]
pub struct Stack {
    table: TableArena,
    sampler: UniformRandomSampler,
    cube_a: FreeBody,
    cube_b: FreeBody,
}

impl Default for Stack {
    fn default() -> Self {
        Self::new()
    }
}

impl Stack {
    /// Stack with robosuite's defaults.
    pub fn new() -> Self {
        let table = TableArena::default();
        Self {
            sampler: UniformRandomSampler {
                x_range: [-0.08, 0.08],
                y_range: [-0.08, 0.08],
                rotation: Rotation::Random,
                rotation_axis: Axis::Z,
                ensure_object_boundary_in_range: false,
                ensure_valid_placement: true,
                reference_pos: table.top,
                z_offset: 0.01,
            },
            table,
            cube_a: FreeBody::default(),
            cube_b: FreeBody::default(),
        }
    }

    /// Cube A's binding.
    pub fn cube_a(&self) -> &FreeBody {
        &self.cube_a
    }

    /// Cube B's binding.
    pub fn cube_b(&self) -> &FreeBody {
        &self.cube_b
    }

    /// `(r_reach, r_lift, r_stack)`, robosuite's `staged_rewards`.
    pub fn staged_rewards(&self, sim: &Sim, robots: &[Robot]) -> (f64, f64, f64) {
        let a = self.cube_a.pos(sim);
        let b = self.cube_b.pos(sim);
        let eef = eef_pos(sim, robots);
        let grasping = is_grasped(sim, robots, &self.cube_a.geoms);
        let r_reach =
            0.25 * (1.0 - (10.0 * dist(eef, a)).tanh()) + if grasping { 0.25 } else { 0.0 };
        let lifted = a[2] > self.table.top[2] + 0.04;
        let r_lift = if lifted {
            1.0 + 0.5 * (1.0 - dist_xy(a, b).tanh())
        } else {
            0.0
        };
        let touching = any_contact_between(sim.data(), &self.cube_a.geoms, &self.cube_b.geoms);
        let r_stack = if !grasping && r_lift > 0.0 && touching {
            2.0
        } else {
            0.0
        };
        (r_reach, r_lift, r_stack)
    }
}

fn placed(half: f64) -> PlacedObject {
    PlacedObject {
        horizontal_radius: half.hypot(half),
        bottom_offset: -half,
        top_offset: half,
    }
}

impl Task for Stack {
    fn name(&self) -> &str {
        "Stack"
    }

    fn robot_base_pose(&self, _index: usize) -> ([f64; 3], [f64; 4]) {
        (
            [-0.16 - self.table.full_size[0] / 2.0, 0.0, 0.912],
            [1.0, 0.0, 0.0, 0.0],
        )
    }

    fn arena_xml(&self) -> String {
        self.table.to_xml()
    }

    fn build_objects(&self, scene: &mut SceneBuilder) -> Result<()> {
        let a = BoxObject::new("cubeA", [CUBE_A_HALF; 3], [1.0, 0.0, 0.0, 1.0]);
        let b = BoxObject::new("cubeB", [CUBE_B_HALF; 3], [0.0, 1.0, 0.0, 1.0]);
        scene.add_part("cubeA", &a.to_xml(), "cubeA_")?;
        scene.add_part("cubeB", &b.to_xml(), "cubeB_")?;
        Ok(())
    }

    fn bind(&mut self, model: &MjModel, _robots: &[Robot], _source: ModelSource) -> Result<()> {
        self.cube_a = FreeBody::bind(model, "cubeA_main", "cubeA_joint0", &["cubeA_g0".into()])?;
        self.cube_b = FreeBody::bind(model, "cubeB_main", "cubeB_joint0", &["cubeB_g0".into()])?;
        Ok(())
    }

    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let poses = self
            .sampler
            .sample(rng, &[placed(CUBE_A_HALF), placed(CUBE_B_HALF)], &[])?;
        self.cube_a.set_pose(sim, poses[0].0, poses[0].1);
        self.cube_b.set_pose(sim, poses[1].0, poses[1].1);
        Ok(())
    }

    fn observation_keys(&self) -> Vec<ObsKey> {
        [
            ("cubeA_pos", 3),
            ("cubeA_quat", 4),
            ("cubeB_pos", 3),
            ("cubeB_quat", 4),
            ("cubeA_to_cubeB", 3),
            ("gripper_to_cubeA", 3),
            ("gripper_to_cubeB", 3),
        ]
        .iter()
        .map(|(n, l)| ObsKey::new(*n, &[*l], DType::F64))
        .collect()
    }

    fn write_observations(&self, sim: &Sim, robots: &[Robot], out: &mut [f64]) {
        let a = self.cube_a.pos(sim);
        let b = self.cube_b.pos(sim);
        let eef = eef_pos(sim, robots);
        out[0..3].copy_from_slice(&a);
        out[3..7].copy_from_slice(&xyzw(self.cube_a.quat(sim)));
        out[7..10].copy_from_slice(&b);
        out[10..14].copy_from_slice(&xyzw(self.cube_b.quat(sim)));
        for i in 0..3 {
            out[14 + i] = b[i] - a[i];
            out[17 + i] = a[i] - eef[i];
            out[20 + i] = b[i] - eef[i];
        }
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let (reach, lift, stack) = self.staged_rewards(sim, robots);
        let r = if config.reward_shaping {
            reach.max(lift).max(stack)
        } else if stack > 0.0 {
            2.0
        } else {
            0.0
        };
        scale_reward(r, config.reward_scale, 2.0)
    }

    fn check_success(&self, sim: &Sim, robots: &[Robot]) -> bool {
        self.staged_rewards(sim, robots).2 > 0.0
    }
}
