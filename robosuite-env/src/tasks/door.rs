//! robosuite's `Door`: open a hinged door, unlatching its handle first (`door.py`).

use super::common::{dist, eef_pos, scale_reward};
use super::placement::{Axis, PlacedObject, Rotation, UniformRandomSampler};
use super::{ModelSource, RewardConfig, Task};
use crate::models::arenas::TableArena;
use crate::models::scene::SceneBuilder;
use crate::observations::ObsKey;
use crate::robots::Robot;
use crate::sim::{Sim, body_id, joint_id, site_id};
use gym_core::{DType, EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use std::f64::consts::FRAC_PI_2;

/// Door's settings.
#[derive(Debug, Clone, PartialEq)]
pub struct DoorConfig {
    /// Whether the handle latches the door (robosuite's `use_latch`, default true).
    pub use_latch: bool,
}

impl Default for DoorConfig {
    fn default() -> Self {
        Self { use_latch: true }
    }
}

/// The door object's MJCF (our own model, attached with the prefix `Door_`): a static
/// frame (`frame`: hinge and latch posts, the latch stopper) and the door (`door`, 0.44 ×
/// 0.04 × 0.58 m, 2.45 kg) on the hinge `hinge` (axis z, range [0, 0.4], damping 0.1),
/// carrying the handle (`latch`: base, lever, the latch tongue and the site `handle`) on
/// the joint `latch_joint` (axis y, range ±π/2, stiffness 1, frictionloss 0.1). Pressing
/// the lever down by about 0.3 rad lifts the tongue over the stopper; until then the door
/// opens only ≈0.03 rad. The root sits on the table top; in the root frame the door faces
/// −y (towards the robot once yawed by −π/2).
pub fn door_xml(use_latch: bool) -> String {
    // Without the latch robosuite drops the lock; here the tongue loses its collisions.
    let tongue_contact = if use_latch {
        r#"contype="1" conaffinity="1""#
    } else {
        r#"contype="0" conaffinity="0""#
    };
    format!(
        r#"<mujoco model="door">
  <compiler angle="radian" autolimits="true" inertiagrouprange="0 0"/>
  <worldbody>
    <body name="main" pos="0 0 0">
      <body name="frame" pos="0 0 0">
        <geom name="hinge_post" type="cylinder" pos="0.25 0.22 0.31" size="0.025 0.31" density="500" group="0" rgba="0.6 0.45 0.3 1"/>
        <geom name="latch_post" type="cylinder" pos="-0.255 0.22 0.31" size="0.025 0.31" density="500" group="0" rgba="0.6 0.45 0.3 1"/>
        <geom name="stopper" type="box" pos="-0.2475 0.155 0.28" size="0.0225 0.01 0.015" density="500" group="0" rgba="0.3 0.3 0.3 1"/>
        <body name="door" pos="0 0.22 0.31">
          <joint name="hinge" type="hinge" pos="0.22 0 0" axis="0 0 1" range="0 0.4" damping="0.1" frictionloss="0"/>
          <geom name="panel" type="box" pos="0 0 0" size="0.22 0.02 0.29" density="240" friction="1 1 1" group="0" rgba="0.75 0.6 0.4 1"/>
          <body name="latch" pos="-0.15 -0.02 -0.03">
            <joint name="latch_joint" type="hinge" pos="0 0 0" axis="0 1 0" range="-1.57 1.57" stiffness="1" springref="0" frictionloss="0.1"/>
            <geom name="handle_base" type="cylinder" fromto="0 0 0 0 -0.1 0" size="0.012" density="1000" group="0" rgba="0.8 0.8 0.8 1"/>
            <geom name="handle" type="box" pos="0.06 -0.1 0" size="0.075 0.015 0.02" density="1000" group="0" rgba="0.8 0.8 0.8 1"/>
            <geom name="tongue" type="box" pos="-0.085 -0.02 0" size="0.025 0.01 0.008" density="1000" group="0" {tongue_contact} rgba="0.3 0.3 0.3 1"/>
            <site name="handle" pos="0.09 -0.1 0" size="0.02" rgba="0 0 1 0" group="1"/>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
"#
    )
}

/// The Door task: a door on a narrow table to the robot's right.
///
/// * Arena: table 0.8 × 0.3 × 0.05 with its top centre at (−0.2, −0.35, 0.8); robot base
///   at (−0.56, 0, 0.912).
/// * Reset: the door root (no free joint) is placed by writing the model's body pose:
///   x ∈ U(0.07, 0.09), y ∈ U(−0.01, 0.01) around the table top, yaw ∈ U(−π/2 − 0.25, −π/2).
/// * Reward: 1 on success; shaped `0.25·(1 − tanh(10 d(eef, handle)))` +
///   `clip(0.25·|latch/(π/2)|, −0.25, 0.25)` (with the latch); times `reward_scale`.
/// * Success: hinge angle > 0.3 rad.
#[derive(Debug, Clone)]
pub struct Door {
    config: DoorConfig,
    table: TableArena,
    sampler: UniformRandomSampler,
    root: usize,
    door_body: usize,
    handle_site: usize,
    hinge_qpos: usize,
    latch_qpos: usize,
    pose: ([f64; 3], [f64; 4]),
}

impl Door {
    /// Door with the given settings.
    pub fn new(config: DoorConfig) -> Self {
        let table = TableArena {
            full_size: [0.8, 0.3, 0.05],
            friction: [1.0, 0.005, 0.0001],
            top: [-0.2, -0.35, 0.8],
        };
        Self {
            config,
            sampler: UniformRandomSampler {
                x_range: [0.07, 0.09],
                y_range: [-0.01, 0.01],
                rotation: Rotation::Range(-FRAC_PI_2 - 0.25, -FRAC_PI_2),
                rotation_axis: Axis::Z,
                ensure_object_boundary_in_range: false,
                ensure_valid_placement: true,
                reference_pos: table.top,
                z_offset: 0.0,
            },
            table,
            root: 0,
            door_body: 0,
            handle_site: 0,
            hinge_qpos: 0,
            latch_qpos: 0,
            pose: ([0.0; 3], [1.0, 0.0, 0.0, 0.0]),
        }
    }

    /// The hinge angle.
    pub fn hinge_angle(&self, sim: &Sim) -> f64 {
        sim.data().qpos()[self.hinge_qpos]
    }

    /// The latch (handle) angle.
    pub fn latch_angle(&self, sim: &Sim) -> f64 {
        sim.data().qpos()[self.latch_qpos]
    }

    /// The handle site position.
    pub fn handle_pos(&self, sim: &Sim) -> [f64; 3] {
        sim.data().site_xpos()[self.handle_site]
    }

    /// The door root's pose (position, wxyz) as placed at the last reset.
    pub fn root_pose(&self) -> ([f64; 3], [f64; 4]) {
        self.pose
    }

    fn write_pose(&mut self, sim: &mut Sim, pos: [f64; 3], quat: [f64; 4]) {
        let model = sim.model_mut();
        model.body_pos_mut()[self.root] = pos;
        model.body_quat_mut()[self.root] = quat;
        self.pose = (pos, quat);
    }
}

impl Default for Door {
    fn default() -> Self {
        Self::new(DoorConfig::default())
    }
}

impl Task for Door {
    fn name(&self) -> &str {
        "Door"
    }

    fn robot_base_pose(&self, _index: usize) -> ([f64; 3], [f64; 4]) {
        ([-0.16 - 0.8 / 2.0, 0.0, 0.912], [1.0, 0.0, 0.0, 0.0])
    }

    fn arena_xml(&self) -> String {
        self.table.to_xml()
    }

    fn build_objects(&self, scene: &mut SceneBuilder) -> Result<()> {
        scene.add_part("Door", &door_xml(self.config.use_latch), "Door_")?;
        Ok(())
    }

    fn bind(&mut self, model: &MjModel, _robots: &[Robot], _source: ModelSource) -> Result<()> {
        self.root = body_id(model, "Door_main")?;
        self.door_body = body_id(model, "Door_door")?;
        self.handle_site = site_id(model, "Door_handle")?;
        let hinge = joint_id(model, "Door_hinge")?;
        let latch = joint_id(model, "Door_latch_joint")?;
        self.hinge_qpos = model.jnt_qposadr()[hinge] as usize;
        self.latch_qpos = model.jnt_qposadr()[latch] as usize;
        if self.root >= model.body_pos().len() {
            return Err(Error::Model("bad door body".into()));
        }
        self.pose = (model.body_pos()[self.root], model.body_quat()[self.root]);
        Ok(())
    }

    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let obj = PlacedObject {
            horizontal_radius: 0.3,
            bottom_offset: 0.0,
            top_offset: 0.62,
        };
        let (pos, quat) = self.sampler.sample(rng, &[obj], &[])?[0];
        self.write_pose(sim, pos, quat);
        Ok(())
    }

    fn observation_keys(&self) -> Vec<ObsKey> {
        vec![
            ObsKey::new("door_pos", &[3], DType::F64),
            ObsKey::new("handle_pos", &[3], DType::F64),
            ObsKey::new("hinge_qpos", &[], DType::F64),
            ObsKey::new("door_to_eef_pos", &[3], DType::F64),
            ObsKey::new("handle_to_eef_pos", &[3], DType::F64),
            ObsKey::new("handle_qpos", &[], DType::F64),
        ]
    }

    fn write_observations(&self, sim: &Sim, robots: &[Robot], out: &mut [f64]) {
        let door = sim.data().xpos()[self.door_body];
        let handle = self.handle_pos(sim);
        let eef = eef_pos(sim, robots);
        out[0..3].copy_from_slice(&door);
        out[3..6].copy_from_slice(&handle);
        out[6] = self.hinge_angle(sim);
        for i in 0..3 {
            out[7 + i] = door[i] - eef[i];
            out[10 + i] = handle[i] - eef[i];
        }
        out[13] = self.latch_angle(sim);
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let mut r = 0.0;
        if self.check_success(sim, robots) {
            r = 1.0;
        } else if config.reward_shaping {
            let d = dist(eef_pos(sim, robots), self.handle_pos(sim));
            r = 0.25 * (1.0 - (10.0 * d).tanh());
            if self.config.use_latch {
                r += (0.25 * (self.latch_angle(sim) / FRAC_PI_2).abs()).clamp(-0.25, 0.25);
            }
        }
        scale_reward(r, config.reward_scale, 1.0)
    }

    fn check_success(&self, sim: &Sim, _robots: &[Robot]) -> bool {
        self.hinge_angle(sim) > 0.3
    }

    fn save_state(&self) -> Vec<f64> {
        let (p, q) = self.pose;
        p.iter().chain(q.iter()).copied().collect()
    }

    fn load_state(&mut self, sim: &mut Sim, state: &[f64]) -> Result<()> {
        if state.len() != 7 {
            return Err(Error::invalid_argument(
                "state",
                format!(
                    "Door's state is the door pose (7 values), got {}",
                    state.len()
                ),
            ));
        }
        let pos = [state[0], state[1], state[2]];
        let quat = [state[3], state[4], state[5], state[6]];
        self.write_pose(sim, pos, quat);
        Ok(())
    }
}
