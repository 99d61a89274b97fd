//! robosuite's `Lift`: lift a small box off the table (`environments/manipulation/lift.py`).

use super::placement::{Axis, PlacedObject, Rotation, UniformRandomSampler};
use super::{ModelSource, RewardConfig, Task};
use crate::models::arenas::TableArena;
use crate::models::objects::BoxObject;
use crate::models::scene::SceneBuilder;
use crate::observations::ObsKey;
use crate::robots::Robot;
use crate::sim::{
    BoxGeomUpdate, GeomSet, Sim, any_contact_between, body_id, geom_id, joint_id, resize_box_body,
};
use gym_core::{DType, EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use rand::RngExt;

/// Lift's settings (robosuite's constructor defaults).
#[derive(Debug, Clone, PartialEq)]
pub struct LiftConfig {
    /// The table arena (0.8 × 0.8 × 0.05, top at z = 0.8).
    pub table: TableArena,
    /// Smallest cube half-extents (0.020 each).
    pub cube_size_min: [f64; 3],
    /// Largest cube half-extents (0.022 each); each is drawn uniformly per reset.
    pub cube_size_max: [f64; 3],
}

impl Default for LiftConfig {
    fn default() -> Self {
        Self {
            table: TableArena::default(),
            cube_size_min: [0.020; 3],
            cube_size_max: [0.022; 3],
        }
    }
}

impl LiftConfig {
    /// Checks the sizes.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for non-positive sizes or min > max.
    pub fn validate(&self) -> Result<()> {
        for i in 0..3 {
            let (lo, hi) = (self.cube_size_min[i], self.cube_size_max[i]);
            if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo <= hi) {
                return Err(Error::invalid_argument(
                    "cube_size",
                    format!("need 0 < min <= max on axis {i}, got [{lo}, {hi}]"),
                ));
            }
        }
        if self
            .table
            .full_size
            .iter()
            .any(|v| !v.is_finite() || *v <= 0.0)
        {
            return Err(Error::invalid_argument(
                "table_full_size",
                format!("must be positive, got {:?}", self.table.full_size),
            ));
        }
        Ok(())
    }
}

/// The Lift task: a cube (body `cube_main`, joint `cube_joint0`, geom `cube_g0`) on a table.
///
/// * Reset: half-extents each `U(0.020, 0.022)` (mass and inertia follow, density 1000),
///   then — after the robot's noise — position `U(±0.03)²` around the table centre with a
///   yaw `U(0, 2π)`, resting 1 cm above the table.
/// * Success: cube height above the table top by more than 4 cm.
/// * Reward: sparse 2.25 on success; shaped `1 − tanh(10·d(grip site, cube))` plus 0.25
///   when both finger-pad groups touch the cube; scaled by `reward_scale / 2.25`.
#[derive(Debug, Clone)]
pub struct Lift {
    config: LiftConfig,
    sampler: UniformRandomSampler,
    half: [f64; 3],
    source: ModelSource,
    cube_body: usize,
    cube_geom: usize,
    cube_qpos: usize,
    cube_geoms: GeomSet,
}

impl Lift {
    /// Lift with the given settings.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for invalid settings.
    pub fn new(config: LiftConfig) -> Result<Self> {
        config.validate()?;
        let sampler = UniformRandomSampler {
            x_range: [-0.03, 0.03],
            y_range: [-0.03, 0.03],
            rotation: Rotation::Random,
            rotation_axis: Axis::Z,
            ensure_object_boundary_in_range: false,
            ensure_valid_placement: true,
            reference_pos: config.table.top,
            z_offset: 0.01,
        };
        let half =
            std::array::from_fn(|i| 0.5 * (config.cube_size_min[i] + config.cube_size_max[i]));
        Ok(Self {
            config,
            sampler,
            half,
            source: ModelSource::Generated,
            cube_body: 0,
            cube_geom: 0,
            cube_qpos: 0,
            cube_geoms: GeomSet::default(),
        })
    }

    /// The cube's current half-extents.
    pub fn cube_half_size(&self) -> [f64; 3] {
        self.half
    }

    /// The cube body id (`cube_main`).
    pub fn cube_body(&self) -> usize {
        self.cube_body
    }

    /// The cube's free-joint `qpos` address.
    pub fn cube_qpos(&self) -> usize {
        self.cube_qpos
    }

    /// Whether both finger-pad groups of robot 0 touch the cube (robosuite's `_check_grasp`).
    pub fn is_grasped(&self, sim: &Sim, robots: &[Robot]) -> bool {
        robots
            .first()
            .and_then(Robot::finger_pads)
            .is_some_and(|(left, right)| {
                any_contact_between(sim.data(), left, &self.cube_geoms)
                    && any_contact_between(sim.data(), right, &self.cube_geoms)
            })
    }

    fn cube_pos(&self, sim: &Sim) -> [f64; 3] {
        sim.data().xpos()[self.cube_body]
    }
}

impl Task for Lift {
    fn name(&self) -> &str {
        "Lift"
    }

    fn robot_base_pose(&self, _index: usize) -> ([f64; 3], [f64; 4]) {
        // Panda's base_xpos_offset["table"](table length) on its mount: (-0.16 - L/2, 0, 0.912).
        (
            [-0.16 - self.config.table.full_size[0] / 2.0, 0.0, 0.912],
            [1.0, 0.0, 0.0, 0.0],
        )
    }

    fn arena_xml(&self) -> String {
        self.config.table.to_xml()
    }

    fn build_objects(&self, scene: &mut SceneBuilder) -> Result<()> {
        let cube = BoxObject::new("cube", self.half, [1.0, 0.0, 0.0, 1.0]);
        scene.add_part("cube", &cube.to_xml(), "cube_")?;
        Ok(())
    }

    fn bind(&mut self, model: &MjModel, _robots: &[Robot], source: ModelSource) -> Result<()> {
        self.source = source;
        self.cube_body = body_id(model, "cube_main")?;
        self.cube_geom = geom_id(model, "cube_g0")?;
        let joint = joint_id(model, "cube_joint0")?;
        if model.jnt_type()[joint] != mujoco_rs::mujoco_c::mjtJoint::mjJNT_FREE {
            return Err(Error::Model("`cube_joint0` must be a free joint".into()));
        }
        self.cube_qpos = model.jnt_qposadr()[joint] as usize;
        self.cube_geoms = GeomSet::new([self.cube_geom]);
        self.half = model.geom_size()[self.cube_geom];
        Ok(())
    }

    fn randomize_model(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        if self.source != ModelSource::Generated {
            return Ok(());
        }
        let (lo, hi) = (self.config.cube_size_min, self.config.cube_size_max);
        let half: [f64; 3] = std::array::from_fn(|i| lo[i] + (hi[i] - lo[i]) * rng.random::<f64>());
        resize_box_body(
            sim,
            BoxGeomUpdate {
                body: self.cube_body,
                geom: self.cube_geom,
                density: 1000.0,
            },
            half,
        )?;
        self.half = half;
        Ok(())
    }

    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let obj = PlacedObject {
            horizontal_radius: self.half[0].hypot(self.half[1]),
            bottom_offset: -self.half[2],
            top_offset: self.half[2],
        };
        let poses = self.sampler.sample(rng, &[obj], &[])?;
        let (pos, quat) = poses[0];
        let qpos = sim.data_mut().qpos_mut();
        qpos[self.cube_qpos..self.cube_qpos + 3].copy_from_slice(&pos);
        qpos[self.cube_qpos + 3..self.cube_qpos + 7].copy_from_slice(&quat);
        Ok(())
    }

    fn observation_keys(&self) -> Vec<ObsKey> {
        vec![
            ObsKey::new("cube_pos", &[3], DType::F64),
            ObsKey::new("cube_quat", &[4], DType::F64),
            ObsKey::new("gripper_to_cube_pos", &[3], DType::F64),
        ]
    }

    fn write_observations(&self, sim: &Sim, robots: &[Robot], out: &mut [f64]) {
        let d = sim.data();
        let p = d.xpos()[self.cube_body];
        let q = d.xquat()[self.cube_body];
        let eef = robots.first().map_or([0.0; 3], |r| r.eef_pos(sim));
        out[0..3].copy_from_slice(&p);
        out[3..7].copy_from_slice(&[q[1], q[2], q[3], q[0]]);
        for i in 0..3 {
            out[7 + i] = p[i] - eef[i];
        }
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let mut reward = 0.0;
        if self.check_success(sim, robots) {
            reward = 2.25;
        } else if config.reward_shaping {
            let cube = self.cube_pos(sim);
            let eef = robots.first().map_or(cube, |r| r.eef_pos(sim));
            let dist = ((cube[0] - eef[0]).powi(2)
                + (cube[1] - eef[1]).powi(2)
                + (cube[2] - eef[2]).powi(2))
            .sqrt();
            reward = 1.0 - (10.0 * dist).tanh();
            if self.is_grasped(sim, robots) {
                reward += 0.25;
            }
        }
        match config.reward_scale {
            Some(scale) => reward * (scale / 2.25),
            None => reward,
        }
    }

    fn save_state(&self) -> Vec<f64> {
        self.half.to_vec()
    }

    fn load_state(&mut self, sim: &mut Sim, state: &[f64]) -> Result<()> {
        let half: [f64; 3] = state.try_into().map_err(|_| {
            Error::invalid_argument(
                "state",
                format!(
                    "Lift's state is the 3 cube half-extents, got {} values",
                    state.len()
                ),
            )
        })?;
        if half != self.half {
            resize_box_body(
                sim,
                BoxGeomUpdate {
                    body: self.cube_body,
                    geom: self.cube_geom,
                    density: 1000.0,
                },
                half,
            )?;
            self.half = half;
        }
        Ok(())
    }

    fn check_success(&self, sim: &Sim, _robots: &[Robot]) -> bool {
        self.cube_pos(sim)[2] > self.config.table.top[2] + 0.04
    }
}
