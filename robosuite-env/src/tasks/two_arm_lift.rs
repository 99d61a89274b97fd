//! robosuite's `TwoArmLift`: two arms lift a pot by its handles
//! (`environments/manipulation/two_arm_lift.py`).

use super::common::{FreeBody, dist, geoms_of, is_grasped, scale_reward, sub};
use super::options::{self, TaskOptions};
use super::table::TABLE_OFFSET;
use super::two_arm::{ArmRef, task_arms};
use super::{Bound, RewardConfig, RobotSetup, Task, TaskLogic, TaskScene, TaskSpec};
use crate::assets::Assets;
use crate::math::{quat2mat_f32, xyzw};
use crate::models::arenas::Arena;
use crate::models::objects::composite::GeneratedObject;
use crate::models::objects::pot_with_handles::PotWithHandles;
use crate::models::robots::RobotModel;
use crate::observables::{Modality, Observable};
use crate::placement::{Axis, Rotation, UniformRandomSampler};
use crate::robots::Robot;
use crate::sim::{GeomSet, Sim, site_id};
use gym_core::{EnvRng, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use std::f64::consts::PI;

/// TwoArmLift's settings (robosuite's constructor defaults).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TwoArmLiftSpec {
    /// The table's full size (default 0.8 × 0.8 × 0.05).
    pub table_full_size: [f64; 3],
    /// The table's friction (default `(1, 0.005, 0.0001)`).
    pub table_friction: [f64; 3],
    /// robosuite's `placement_initializer`: a sampler that replaces the task's own (it
    /// places every object of the task); `None` (the default) keeps robosuite's.
    #[serde(default)]
    pub placement_initializer: Option<UniformRandomSampler>,
}

impl Default for TwoArmLiftSpec {
    fn default() -> Self {
        Self {
            table_full_size: [0.8, 0.8, 0.05],
            table_friction: [1.0, 5e-3, 1e-4],
            placement_initializer: None,
        }
    }
}

impl TaskSpec for TwoArmLiftSpec {
    fn options(&self) -> TaskOptions {
        options::to_options(self)
    }

    fn configure(&mut self, options: &TaskOptions) -> Result<()> {
        *self = options::merged(self.name(), self, options)?;
        Ok(())
    }

    fn name(&self) -> &str {
        "TwoArmLift"
    }

    fn robots(&self) -> RobotSetup {
        RobotSetup::TwoArm {
            opposed_shift: 0.0,
            parallel_shift: 0.25,
        }
    }

    fn build(&self, assets: &Assets, _robots: &mut [RobotModel]) -> Result<TaskScene> {
        let mut arena = Arena::table(
            assets,
            "arenas/table_arena.xml",
            self.table_full_size,
            self.table_friction,
            TABLE_OFFSET,
        )?;
        arena.set_origin([0.0; 3])?;
        let pot = PotWithHandles::two_arm_lift(assets)?.build()?;
        Ok(TaskScene {
            arena,
            objects: vec![pot],
            attached: Vec::new(),
        })
    }

    fn bind(&self, scene: &TaskScene, model: &MjModel, robots: &[Robot]) -> Result<Box<dyn Task>> {
        let pot = &scene.objects[0];
        let handle = |i: usize| -> Result<GeomSet> {
            geoms_of(
                model,
                &PotWithHandles::handle_geoms(i).map(|g| pot.name_of(&g)),
            )
        };
        let mut task = TwoArmLift {
            sampler: self
                .placement_initializer
                .clone()
                .unwrap_or_else(|| UniformRandomSampler {
                    x_range: [-0.03, 0.03],
                    y_range: [-0.03, 0.03],
                    rotation: Rotation::Range(PI + -PI / 3.0, PI + PI / 3.0),
                    rotation_axis: Axis::Z,
                    ensure_object_boundary_in_range: false,
                    ensure_valid_placement: true,
                    reference_pos: TABLE_OFFSET,
                    z_offset: 0.0,
                }),
            extent: pot.placement(),
            pot: FreeBody::bind(model, pot)?,
            pot_top_offset: pot.top_offset[2],
            handle_geoms: [handle(0)?, handle(1)?],
            handle_sites: [
                site_id(model, &pot.name_of("handle0"))?,
                site_id(model, &pot.name_of("handle1"))?,
            ],
            center_site: site_id(model, &pot.name_of("center"))?,
            table_top: site_id(model, "table_top")?,
            arms: task_arms(robots),
            eef_sites: [0; 2],
        };
        for (site, arm) in task.eef_sites.iter_mut().zip(task.arms) {
            *site = robots[arm.robot].arms()[arm.arm].eef_site();
        }
        let observables = vec![
            Observable::vec("pot_pos", Modality::Object, |t: &TwoArmLift, sim| {
                t.pot.pos(sim)
            }),
            Observable::vec("pot_quat", Modality::Object, |t: &TwoArmLift, sim| {
                xyzw(t.pot.quat(sim))
            }),
            Observable::vec("handle0_xpos", Modality::Object, |t: &TwoArmLift, sim| {
                t.handle_pos(sim, 0)
            }),
            Observable::vec("handle1_xpos", Modality::Object, |t: &TwoArmLift, sim| {
                t.handle_pos(sim, 1)
            }),
            Observable::vec(
                "gripper0_to_handle0",
                Modality::Object,
                |t: &TwoArmLift, sim| t.gripper_to_handle(sim, 0),
            ),
            Observable::vec(
                "gripper1_to_handle1",
                Modality::Object,
                |t: &TwoArmLift, sim| t.gripper_to_handle(sim, 1),
            ),
        ];
        Ok(Bound::boxed(task, observables))
    }
}

/// The bound TwoArmLift task: a pot (body `pot_root`, joint `pot_joint0`) with handle 0
/// (green, +y) and handle 1 (blue, −y) on a table; gripper 0 (robot 0's arm, or a bimanual
/// robot's right arm) goes for handle 0, gripper 1 for handle 1.
///
/// * Reset: the pot `U(±0.03)²` around the table centre, yaw `U(2π/3, 4π/3)`, resting on
///   the table.
/// * Success: the pot's bottom more than 10 cm above the table top.
/// * Reward: `direction = 1` while the pot's z axis is within 30° of vertical, else 0;
///   sparse `3 · direction` on success; shaped (not successful)
///   `10 · direction · clip(elevation − 0.05, 0, 0.15)` plus per gripper `0.25` when it
///   grasps its handle and `0.5 · (1 − tanh(10 · d(grip site, handle site)))`; scaled by
///   `reward_scale / 3`.
#[derive(Debug, Clone)]
pub struct TwoArmLift {
    sampler: UniformRandomSampler,
    extent: crate::placement::PlacedObject,
    pot: FreeBody,
    pot_top_offset: f64,
    handle_geoms: [GeomSet; 2],
    handle_sites: [usize; 2],
    center_site: usize,
    table_top: usize,
    arms: [ArmRef; 2],
    eef_sites: [usize; 2],
}

impl TwoArmLift {
    fn handle_pos(&self, sim: &Sim, i: usize) -> [f64; 3] {
        sim.data().site_xpos()[self.handle_sites[i]]
    }

    fn gripper_to_handle(&self, sim: &Sim, i: usize) -> [f64; 3] {
        sub(
            self.handle_pos(sim, i),
            sim.data().site_xpos()[self.eef_sites[i]],
        )
    }

    /// The heights of the pot's bottom and of the table top.
    fn heights(&self, sim: &Sim) -> (f64, f64) {
        let d = sim.data();
        let bottom = d.site_xpos()[self.center_site][2] - self.pot_top_offset;
        (bottom, d.site_xpos()[self.table_top][2])
    }

    /// 1 while the pot is tilted by at most 30°, else 0.
    fn direction_coef(&self, sim: &Sim) -> f64 {
        let m = quat2mat_f32(xyzw(self.pot.quat(sim)));
        if m[(2, 2)] >= (PI / 6.0).cos() {
            1.0
        } else {
            0.0
        }
    }
}

impl TaskLogic for TwoArmLift {
    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let (pos, quat) = self.sampler.sample(rng, &[self.extent], &[])?[0];
        self.pot.set_pose(sim, pos, quat);
        Ok(())
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let direction = self.direction_coef(sim);
        let mut reward = 0.0;
        if self.check_success(sim, robots) {
            reward = 3.0 * direction;
        } else if config.reward_shaping {
            let (bottom, table) = self.heights(sim);
            let lift = (bottom - table - 0.05).clamp(0.0, 0.15);
            reward += 10.0 * direction * lift;
            for i in 0..2 {
                let arm = self.arms[i];
                let gripper = robots[arm.robot].arms()[arm.arm].gripper();
                let d = dist(self.handle_pos(sim, i), arm.eef_pos(sim, robots));
                if is_grasped(sim, gripper, &self.handle_geoms[i]) {
                    reward += 0.25;
                }
                reward += 0.5 * (1.0 - (10.0 * d).tanh());
            }
        }
        scale_reward(reward, config.reward_scale, 3.0)
    }

    fn check_success(&self, sim: &Sim, _robots: &[Robot]) -> bool {
        let (bottom, table) = self.heights(sim);
        bottom > table + 0.10
    }
}
