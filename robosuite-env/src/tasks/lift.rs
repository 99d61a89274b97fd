//! robosuite's `Lift`: lift a small box off the table (`environments/manipulation/lift.py`).

use super::common::{
    FreeBody, robot0_arms, robot0_eef_dist, robot0_grasps, scale_reward, sub, wood_material,
};
use super::options::{self, TaskOptions};
use super::table::{TABLE_OFFSET, table_arena};
use super::{Bound, RewardConfig, Task, TaskLogic, TaskScene, TaskSpec};
use crate::assets::Assets;
use crate::math::xyzw;
use crate::models::objects::primitive::Primitive;
use crate::models::objects::{ObjectModel, Shape};
use crate::models::robots::RobotModel;
use crate::observables::{Modality, Observable};
use crate::placement::{Axis, PlacedObject, Rotation, UniformRandomSampler};
use crate::robots::Robot;
use crate::sim::{BoxGeomUpdate, Sim, geom_id, resize_box_body};
use gym_core::{EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use rand::RngExt;

/// Lift's settings (robosuite's constructor defaults).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LiftSpec {
    /// The table's full size (default 0.8 × 0.8 × 0.05).
    pub table_full_size: [f64; 3],
    /// The table's friction (default `(1, 0.005, 0.0001)`).
    pub table_friction: [f64; 3],
    /// Smallest cube half-extents (0.020 each).
    pub cube_size_min: [f64; 3],
    /// Largest cube half-extents (0.022 each); each is drawn uniformly per reset.
    pub cube_size_max: [f64; 3],
    /// robosuite's `placement_initializer`: a sampler that replaces the task's own (it
    /// places every object of the task); `None` (the default) keeps robosuite's.
    #[serde(default)]
    pub placement_initializer: Option<UniformRandomSampler>,
}

impl Default for LiftSpec {
    fn default() -> Self {
        Self {
            table_full_size: [0.8, 0.8, 0.05],
            table_friction: [1.0, 5e-3, 1e-4],
            cube_size_min: [0.020; 3],
            cube_size_max: [0.022; 3],
            placement_initializer: None,
        }
    }
}

impl LiftSpec {
    fn validate(&self) -> Result<()> {
        for i in 0..3 {
            let (lo, hi) = (self.cube_size_min[i], self.cube_size_max[i]);
            if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo <= hi) {
                return Err(Error::invalid_argument(
                    "cube_size",
                    format!("need 0 < min <= max on axis {i}, got [{lo}, {hi}]"),
                ));
            }
        }
        Ok(())
    }
}

impl TaskSpec for LiftSpec {
    fn options(&self) -> TaskOptions {
        options::to_options(self)
    }

    fn configure(&mut self, options: &TaskOptions) -> Result<()> {
        *self = options::merged(self.name(), self, options)?;
        Ok(())
    }

    fn name(&self) -> &str {
        "Lift"
    }

    fn build(&self, assets: &Assets, _robots: &mut [RobotModel]) -> Result<TaskScene> {
        self.validate()?;
        let arena = table_arena(
            assets,
            self.table_full_size,
            self.table_friction,
            TABLE_OFFSET,
        )?;
        let half = std::array::from_fn(|i| 0.5 * (self.cube_size_min[i] + self.cube_size_max[i]));
        let mut cube = Primitive::new("cube", Shape::Box(half));
        cube.material = Some(wood_material(assets, "WoodRed", "redwood")?);
        Ok(TaskScene {
            arena,
            objects: vec![cube.build()?],
            attached: Vec::new(),
        })
    }

    fn bind(&self, scene: &TaskScene, model: &MjModel, robots: &[Robot]) -> Result<Box<dyn Task>> {
        let cube: &ObjectModel = &scene.objects[0];
        let body = FreeBody::bind(model, cube)?;
        let geoms = [cube.contact_geoms(), cube.visual_geoms()]
            .concat()
            .iter()
            .map(|g| geom_id(model, g))
            .collect::<Result<Vec<_>>>()?;
        let half = model.geom_size()[geoms[0]];
        let task = Lift {
            spec: self.clone(),
            sampler: self
                .placement_initializer
                .clone()
                .unwrap_or_else(|| UniformRandomSampler {
                    x_range: [-0.03, 0.03],
                    y_range: [-0.03, 0.03],
                    rotation: Rotation::Random,
                    rotation_axis: Axis::Z,
                    ensure_object_boundary_in_range: false,
                    ensure_valid_placement: true,
                    reference_pos: TABLE_OFFSET,
                    z_offset: 0.01,
                }),
            half,
            cube: body,
            cube_geoms: geoms,
        };
        let object = Modality::Object;
        let mut observables = vec![
            Observable::vec("cube_pos", object, |t: &Lift, sim| t.cube.pos(sim)),
            Observable::vec("cube_quat", object, |t: &Lift, sim| xyzw(t.cube.quat(sim))),
        ];
        observables.extend(robot0_arms(robots).into_iter().map(|arm| {
            Observable::vec(
                format!("{}gripper_to_cube_pos", arm.prefix),
                object,
                move |t: &Lift, sim| sub(t.cube.pos(sim), sim.data().site_xpos()[arm.eef_site]),
            )
        }));
        Ok(Bound::boxed(task, observables))
    }
}

/// The bound Lift task: a cube (body `cube_main`, joint `cube_joint0`, geoms `cube_g0` and
/// `cube_g0_vis`) on a table.
///
/// * Reset: half-extents each `U(0.020, 0.022)` (mass and inertia follow, density 1000),
///   then — after the robot's noise — position `U(±0.03)²` around the table centre with a
///   yaw `U(0, 2π)`, resting 1 cm above the table.
/// * Success: cube height above the table top by more than 4 cm.
/// * Reward: sparse 2.25 on success; shaped `1 − tanh(10·d(grip site, cube))` plus 0.25
///   when both finger-pad groups of a gripper touch the cube (for a bimanual robot: the
///   nearest grip site, any gripper); scaled by `reward_scale / 2.25`.
#[derive(Debug, Clone)]
pub struct Lift {
    spec: LiftSpec,
    sampler: UniformRandomSampler,
    half: [f64; 3],
    cube: FreeBody,
    cube_geoms: Vec<usize>,
}

impl Lift {
    fn resize(&mut self, sim: &mut Sim, half: [f64; 3]) -> Result<()> {
        resize_box_body(
            sim,
            BoxGeomUpdate {
                body: self.cube.body,
                geoms: &self.cube_geoms,
                density: 1000.0,
            },
            half,
        )?;
        self.half = half;
        Ok(())
    }
}

impl TaskLogic for Lift {
    fn randomize_model(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let (lo, hi) = (self.spec.cube_size_min, self.spec.cube_size_max);
        let half: [f64; 3] = std::array::from_fn(|i| lo[i] + (hi[i] - lo[i]) * rng.random::<f64>());
        self.resize(sim, half)
    }

    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let extent = PlacedObject {
            horizontal_radius: (self.half[0] * self.half[0] + self.half[1] * self.half[1]).sqrt(),
            bottom_offset: -self.half[2],
            top_offset: self.half[2],
        };
        let (pos, quat) = self.sampler.sample(rng, &[extent], &[])?[0];
        self.cube.set_pose(sim, pos, quat);
        Ok(())
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let mut reward = 0.0;
        if self.check_success(sim, robots) {
            reward = 2.25;
        } else if config.reward_shaping {
            reward = 1.0 - (10.0 * robot0_eef_dist(sim, robots, self.cube.pos(sim))).tanh();
            if robot0_grasps(sim, robots, &self.cube.geoms) {
                reward += 0.25;
            }
        }
        scale_reward(reward, config.reward_scale, 2.25)
    }

    fn check_success(&self, sim: &Sim, _robots: &[Robot]) -> bool {
        self.cube.pos(sim)[2] > TABLE_OFFSET[2] + 0.04
    }

    fn save_state(&self) -> Vec<f64> {
        self.half.to_vec()
    }

    fn load_state(&mut self, sim: &mut Sim, state: &[f64]) -> Result<()> {
        let half: [f64; 3] = state.try_into().map_err(|_| {
            Error::invalid_argument(
                "task state",
                format!(
                    "Lift's state is the 3 cube half-extents, got {} values",
                    state.len()
                ),
            )
        })?;
        if half != self.half {
            self.resize(sim, half)?;
        }
        Ok(())
    }
}
