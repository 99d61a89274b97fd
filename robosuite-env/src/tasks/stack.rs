//! robosuite's `Stack`: put the red cube A on the green cube B
//! (`environments/manipulation/stack.py`).

use super::common::{
    FreeBody, dist_xy, robot0_arms, robot0_eef_dist, robot0_grasps, scale_reward, sub,
    wood_material,
};
use super::options::{self, TaskOptions};
use super::table::{TABLE_OFFSET, table_arena};
use super::{Bound, RewardConfig, Task, TaskLogic, TaskScene, TaskSpec};
use crate::assets::Assets;
use crate::math::xyzw;
use crate::models::objects::Shape;
use crate::models::objects::primitive::Primitive;
use crate::models::robots::RobotModel;
use crate::observables::{Modality, Observable};
use crate::placement::{Axis, PlacedObject, Rotation, UniformRandomSampler};
use crate::robots::Robot;
use crate::sim::{Sim, any_contact_between};
use gym_core::{EnvRng, Result};
use mujoco_rs::wrappers::mj_model::MjModel;

/// Stack's settings (robosuite's constructor defaults).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StackSpec {
    /// The table's full size (default 0.8 × 0.8 × 0.05).
    pub table_full_size: [f64; 3],
    /// The table's friction (default `(1, 0.005, 0.0001)`).
    pub table_friction: [f64; 3],
    /// robosuite's `placement_initializer`: a sampler that replaces the task's own (it
    /// places every object of the task); `None` (the default) keeps robosuite's.
    #[serde(default)]
    pub placement_initializer: Option<UniformRandomSampler>,
}

impl Default for StackSpec {
    fn default() -> Self {
        Self {
            table_full_size: [0.8, 0.8, 0.05],
            table_friction: [1.0, 5e-3, 1e-4],
            placement_initializer: None,
        }
    }
}

/// Half-extents of cube A (robosuite's `size_min = size_max = 0.02`).
pub const CUBE_A_HALF: f64 = 0.02;
/// Half-extents of cube B (`0.025`).
pub const CUBE_B_HALF: f64 = 0.025;

impl TaskSpec for StackSpec {
    fn options(&self) -> TaskOptions {
        options::to_options(self)
    }

    fn configure(&mut self, options: &TaskOptions) -> Result<()> {
        *self = options::merged(self.name(), self, options)?;
        Ok(())
    }

    fn name(&self) -> &str {
        "Stack"
    }

    fn build(&self, assets: &Assets, _robots: &mut [RobotModel]) -> Result<TaskScene> {
        let arena = table_arena(
            assets,
            self.table_full_size,
            self.table_friction,
            TABLE_OFFSET,
        )?;
        let mut cube_a = Primitive::new("cubeA", Shape::Box([CUBE_A_HALF; 3]));
        cube_a.rgba = [1.0, 0.0, 0.0, 1.0];
        cube_a.material = Some(wood_material(assets, "WoodRed", "redwood")?);
        let mut cube_b = Primitive::new("cubeB", Shape::Box([CUBE_B_HALF; 3]));
        cube_b.rgba = [0.0, 1.0, 0.0, 1.0];
        cube_b.material = Some(wood_material(assets, "WoodGreen", "greenwood")?);
        Ok(TaskScene {
            arena,
            objects: vec![cube_a.build()?, cube_b.build()?],
            attached: Vec::new(),
        })
    }

    fn bind(&self, scene: &TaskScene, model: &MjModel, robots: &[Robot]) -> Result<Box<dyn Task>> {
        let [a, b] = [&scene.objects[0], &scene.objects[1]];
        let task = Stack {
            sampler: self
                .placement_initializer
                .clone()
                .unwrap_or_else(|| UniformRandomSampler {
                    x_range: [-0.08, 0.08],
                    y_range: [-0.08, 0.08],
                    rotation: Rotation::Random,
                    rotation_axis: Axis::Z,
                    ensure_object_boundary_in_range: false,
                    ensure_valid_placement: true,
                    reference_pos: TABLE_OFFSET,
                    z_offset: 0.01,
                }),
            extents: [a.placement(), b.placement()],
            cube_a: FreeBody::bind(model, a)?,
            cube_b: FreeBody::bind(model, b)?,
        };
        let observables = Stack::make_observables(robots);
        Ok(Bound::boxed(task, observables))
    }
}

/// The bound Stack task: cube A (`cubeA_main`, joint `cubeA_joint0`, geom `cubeA_g0`, half
/// size 0.02) and cube B (`cubeB_*`, half size 0.025) on Lift's table.
///
/// * Reset: both cubes `U(±0.08)²` around the table centre with a yaw `U(0, 2π)`, resting
///   1 cm above the table, without overlap (robosuite's rejection sampling; a typed error
///   after 5000 tries).
/// * Reward (robosuite's `staged_rewards`): reach `0.25·(1 − tanh(10·d(grip site, A)))`
///   (the nearest grip site of a bimanual robot) plus 0.25 while A is grasped (by any
///   gripper); lift `1 + 0.5·(1 − tanh(‖A_xy − B_xy‖))` once A is 4 cm
///   above the table; stack 2 when A is lifted, not grasped and touches B. Shaped: the
///   largest stage; sparse: 2 on stack; scaled by `reward_scale / 2`.
/// * Success: the stack stage.
#[derive(Debug, Clone)]
pub struct Stack {
    sampler: UniformRandomSampler,
    extents: [PlacedObject; 2],
    cube_a: FreeBody,
    cube_b: FreeBody,
}

impl Stack {
    /// robosuite's object observables, in its order: `cubeA_pos`, `cubeA_quat`, `cubeB_pos`,
    /// `cubeB_quat`, `cubeA_to_cubeB` (B − A), then per arm of robot 0
    /// `{arm}gripper_to_cubeA` and `{arm}gripper_to_cubeB` (cube − grip site; `arm` empty
    /// for a single-arm robot, `right_` / `left_` for a bimanual one), each computed from
    /// values of the same observation pass.
    fn make_observables(robots: &[Robot]) -> Vec<Observable<Stack>> {
        let mut observables = vec![
            Observable::vec("cubeA_pos", Modality::Object, |t: &Stack, sim| {
                t.cube_a.pos(sim)
            }),
            Observable::vec("cubeA_quat", Modality::Object, |t: &Stack, sim| {
                xyzw(t.cube_a.quat(sim))
            }),
            Observable::vec("cubeB_pos", Modality::Object, |t: &Stack, sim| {
                t.cube_b.pos(sim)
            }),
            Observable::vec("cubeB_quat", Modality::Object, |t: &Stack, sim| {
                xyzw(t.cube_b.quat(sim))
            }),
            Observable::vec("cubeA_to_cubeB", Modality::Object, |t: &Stack, sim| {
                sub(t.cube_b.pos(sim), t.cube_a.pos(sim))
            }),
        ];
        for arm in robot0_arms(robots) {
            let site = arm.eef_site;
            observables.push(Observable::vec(
                format!("{}gripper_to_cubeA", arm.prefix),
                Modality::Object,
                move |t: &Stack, sim| sub(t.cube_a.pos(sim), sim.data().site_xpos()[site]),
            ));
            observables.push(Observable::vec(
                format!("{}gripper_to_cubeB", arm.prefix),
                Modality::Object,
                move |t: &Stack, sim| sub(t.cube_b.pos(sim), sim.data().site_xpos()[site]),
            ));
        }
        observables
    }

    /// Cube A's binding.
    pub fn cube_a(&self) -> &FreeBody {
        &self.cube_a
    }

    /// Cube B's binding.
    pub fn cube_b(&self) -> &FreeBody {
        &self.cube_b
    }

    /// robosuite's `staged_rewards`: `(r_reach, r_lift, r_stack)`.
    pub fn staged_rewards(&self, sim: &Sim, robots: &[Robot]) -> (f64, f64, f64) {
        let (a, b) = (self.cube_a.pos(sim), self.cube_b.pos(sim));
        let mut r_reach = (1.0 - (10.0 * robot0_eef_dist(sim, robots, a)).tanh()) * 0.25;
        let grasping = robot0_grasps(sim, robots, &self.cube_a.geoms);
        if grasping {
            r_reach += 0.25;
        }
        let lifted = a[2] > TABLE_OFFSET[2] + 0.04;
        let mut r_lift = if lifted { 1.0 } else { 0.0 };
        if lifted {
            r_lift += 0.5 * (1.0 - dist_xy(a, b).tanh());
        }
        let touching = any_contact_between(sim.data(), &self.cube_a.geoms, &self.cube_b.geoms);
        let r_stack = if !grasping && r_lift > 0.0 && touching {
            2.0
        } else {
            0.0
        };
        (r_reach, r_lift, r_stack)
    }
}

impl TaskLogic for Stack {
    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let poses = self.sampler.sample(rng, &self.extents, &[])?;
        self.cube_a.set_pose(sim, poses[0].0, poses[0].1);
        self.cube_b.set_pose(sim, poses[1].0, poses[1].1);
        Ok(())
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let (r_reach, r_lift, r_stack) = self.staged_rewards(sim, robots);
        let reward = if config.reward_shaping {
            r_reach.max(r_lift).max(r_stack)
        } else if r_stack > 0.0 {
            2.0
        } else {
            0.0
        };
        scale_reward(reward, config.reward_scale, 2.0)
    }

    fn check_success(&self, sim: &Sim, robots: &[Robot]) -> bool {
        self.staged_rewards(sim, robots).2 > 0.0
    }
}
