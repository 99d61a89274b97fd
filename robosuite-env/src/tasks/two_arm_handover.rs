//! robosuite's `TwoArmHandover`: one arm picks a hammer up and hands it to the other
//! (`environments/manipulation/two_arm_handover.py`, prehensile).

use super::common::{FreeBody, dist, is_grasped, scale_reward, sub};
use super::options::{self, TaskOptions};
use super::two_arm::{ArmRef, task_arms};
use super::{Bound, RewardConfig, RobotSetup, Task, TaskLogic, TaskScene, TaskSpec};
use crate::assets::Assets;
use crate::math::{quat2mat_f32, xyzw};
use crate::models::arenas::Arena;
use crate::models::objects::composite::GeneratedObject;
use crate::models::objects::hammer::{Hammer, HammerFigures, HammerRanges};
use crate::models::robots::RobotModel;
use crate::observables::{Modality, Observable};
use crate::placement::{Axis, PlacedObject, Rotation, UniformRandomSampler, with_init_quat};
use crate::robots::Robot;
use crate::sim::{GeomSet, Sim, geom_id, reshape_body_from, site_id};
use gym_core::{EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use std::f64::consts::PI;

/// TwoArmHandover's settings (robosuite's constructor defaults).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TwoArmHandoverSpec {
    /// The table's nominal full size (default 0.8 × 1.2 × 0.05); the table itself is a
    /// quarter as wide, centred 3/8 of the width towards robot 0.
    pub table_full_size: [f64; 3],
    /// The table's friction (default `(1, 0.005, 0.0001)`).
    pub table_friction: [f64; 3],
    /// The ranges the hammer's figures are drawn from at every reset.
    #[serde(skip)]
    pub hammer: HammerRanges,
    /// robosuite's `placement_initializer`: a sampler that replaces the task's own (it
    /// places every object of the task); `None` (the default) keeps robosuite's.
    #[serde(default)]
    pub placement_initializer: Option<UniformRandomSampler>,
}

impl Default for TwoArmHandoverSpec {
    fn default() -> Self {
        Self {
            table_full_size: [0.8, 1.2, 0.05],
            table_friction: [1.0, 5e-3, 1e-4],
            hammer: HammerRanges::default(),
            placement_initializer: None,
        }
    }
}

/// How high (m) above the table the hammer counts as lifted.
const HEIGHT_THRESHOLD: f64 = 0.1;

impl TwoArmHandoverSpec {
    /// robosuite's constructor arguments (see [`TaskSpec::options`]), `prehensile` (true)
    /// included.
    fn task_options(&self) -> TaskOptions {
        let mut out = options::to_options(self);
        out.insert("prehensile".into(), true.into());
        out
    }

    /// Sets robosuite's constructor arguments (see [`TaskSpec::configure`]).
    /// `prehensile=False` (the hammer starting in the first arm's gripper) is refused: in
    /// robosuite 1.5.2 that start calls the robots' removed `controller` attribute and fails.
    fn set_task_options(&mut self, given: &TaskOptions) -> Result<()> {
        let mut rest = given.clone();
        if options::take::<bool>(&mut rest, "prehensile")? == Some(false) {
            return Err(Error::Unsupported(
                "TwoArmHandover's prehensile=False: robosuite 1.5.2's own start for it \
                 fails (it calls the robots' `controller`, removed in 1.5)"
                    .into(),
            ));
        }
        let mut next: Self = options::merged(self.name(), self, &rest)?;
        next.hammer = self.hammer;
        *self = next;
        Ok(())
    }

    /// robosuite's `table_true_size` and `table_offset`.
    fn table(&self) -> ([f64; 3], [f64; 3]) {
        let mut true_size = self.table_full_size;
        true_size[1] *= 0.25;
        (
            true_size,
            [0.0, self.table_full_size[1] * (-3.0 / 8.0), 0.8],
        )
    }
}

impl TaskSpec for TwoArmHandoverSpec {
    fn options(&self) -> TaskOptions {
        self.task_options()
    }

    fn configure(&mut self, options: &TaskOptions) -> Result<()> {
        self.set_task_options(options)
    }

    fn name(&self) -> &str {
        "TwoArmHandover"
    }

    fn robots(&self) -> RobotSetup {
        RobotSetup::TwoArm {
            opposed_shift: 0.25,
            parallel_shift: 0.6,
        }
    }

    fn build(&self, assets: &Assets, _robots: &mut [RobotModel]) -> Result<TaskScene> {
        self.hammer.validate()?;
        let (true_size, offset) = self.table();
        let mut arena = Arena::table(
            assets,
            "arenas/table_arena.xml",
            true_size,
            self.table_friction,
            offset,
        )?;
        arena.set_origin([0.0; 3])?;
        arena.set_camera(
            "agentview",
            [
                0.8894354364730311,
                -3.481824231498976e-08,
                1.7383813133506494,
            ],
            [
                0.6530981063842773,
                0.2710406184196472,
                0.27104079723358154,
                0.6530979871749878,
            ],
        )?;
        let hammer = Hammer::new(
            assets,
            "hammer",
            HammerFigures::middle(&self.hammer),
            self.hammer.head_density_ratio,
        )?;
        Ok(TaskScene {
            arena,
            objects: vec![hammer.build()?],
            attached: Vec::new(),
        })
    }

    fn bind(&self, scene: &TaskScene, model: &MjModel, robots: &[Robot]) -> Result<Box<dyn Task>> {
        let object = &scene.objects[0];
        let (_, offset) = self.table();
        // The scene's hammer, rebuilt without textures (its materials only colour it).
        let assets = Assets::locate()?;
        let hammer = Hammer::new(
            &assets,
            "hammer",
            HammerFigures::middle(&self.hammer),
            self.hammer.head_density_ratio,
        )?;
        let donor = hammer.donor_model()?;
        let arms = task_arms(robots);
        let task = TwoArmHandover {
            spec: self.clone(),
            sampler: self
                .placement_initializer
                .clone()
                .unwrap_or_else(|| UniformRandomSampler {
                    x_range: [-0.1, 0.1],
                    y_range: [-0.05, 0.05],
                    rotation: Rotation::Random,
                    rotation_axis: Axis::Y,
                    ensure_object_boundary_in_range: false,
                    ensure_valid_placement: true,
                    reference_pos: offset,
                    z_offset: 0.0,
                }),
            body: FreeBody::bind(model, object)?,
            handle_geom: geom_id(model, &object.name_of("handle"))?,
            handle: GeomSet::new([geom_id(model, &object.name_of("handle"))?]),
            table_top: site_id(model, "table_top")?,
            donor_size: donor.stat().meansize,
            hammer,
            arms,
            eef_sites: arms.map(|a| robots[a.robot].arms()[a.arm].eef_site()),
        };
        let observables = vec![
            Observable::vec("hammer_pos", Modality::Object, |t: &TwoArmHandover, sim| {
                t.body.pos(sim)
            }),
            Observable::vec(
                "hammer_quat",
                Modality::Object,
                |t: &TwoArmHandover, sim| xyzw(t.body.quat(sim)),
            ),
            Observable::vec(
                "handle_xpos",
                Modality::Object,
                |t: &TwoArmHandover, sim| t.handle_pos(sim),
            ),
            Observable::vec(
                "gripper0_to_handle",
                Modality::Object,
                |t: &TwoArmHandover, sim| t.gripper_to_handle(sim, 0),
            ),
            Observable::vec(
                "gripper1_to_handle",
                Modality::Object,
                |t: &TwoArmHandover, sim| t.gripper_to_handle(sim, 1),
            ),
        ];
        Ok(Bound::boxed(task, observables))
    }
}

/// The bound TwoArmHandover task: a hammer (body `hammer_root`, joint `hammer_joint0`,
/// geoms `hammer_handle`, `_head`, `_neck`, `_face`, `_claw`) on a narrow table in front of
/// gripper 0.
///
/// * Reset: the hammer's figures are drawn (handle half-width `U(0.015, 0.02)`, length
///   `U(0.1, 0.25)`, density `U(100, 250)`, friction `U(3, 5)`, head half-size
///   `U(r, 1.2 r)`; the scene's hammer takes them without recompiling), then it is placed
///   `U(±0.1) × U(±0.05)` around the table centre, lying on its side (robosuite's random
///   `init_quat`) turned `U(0, 2π)` about y.
/// * Lifted: the handle's height, less the handle half-width and the tilt's share
///   `(length / 2 + 2 · head) · sin(angle)`, more than 10 cm above the table.
/// * Success: gripper 1 grasps the handle, gripper 0 touches no part with both pads, and
///   the hammer is lifted.
/// * Reward: sparse 2 on success; shaped: lifted → 1.5 (both grasp) / 2 (only gripper 1
///   grasps the handle) / `1 + 0.25 · (1 − tanh(d(gripper 1, handle)))`; not lifted → 0.5
///   when gripper 0 grasps, else `0.25 · (1 − tanh(d(gripper 0, handle)))`; scaled by
///   `reward_scale / 2`.
#[derive(Debug, Clone)]
pub struct TwoArmHandover {
    spec: TwoArmHandoverSpec,
    sampler: UniformRandomSampler,
    body: FreeBody,
    handle_geom: usize,
    handle: GeomSet,
    table_top: usize,
    hammer: Hammer,
    donor_size: f64,
    arms: [ArmRef; 2],
    eef_sites: [usize; 2],
}

/// `_get_task_info`: whether gripper 0 grasps any part, whether gripper 1 grasps the
/// handle, and the hammer's and the table's heights.
struct TaskInfo {
    arm0_grasps_any: bool,
    arm1_grasps_handle: bool,
    hammer_height: f64,
    table_height: f64,
}

impl TaskInfo {
    fn lifted(&self) -> bool {
        self.hammer_height - self.table_height > HEIGHT_THRESHOLD
    }
}

impl TwoArmHandover {
    fn handle_pos(&self, sim: &Sim) -> [f64; 3] {
        sim.data().geom_xpos()[self.handle_geom]
    }

    fn gripper_to_handle(&self, sim: &Sim, i: usize) -> [f64; 3] {
        sub(
            self.handle_pos(sim),
            sim.data().site_xpos()[self.eef_sites[i]],
        )
    }

    fn info(&self, sim: &Sim, robots: &[Robot]) -> TaskInfo {
        let f = self.hammer.figures;
        let m = quat2mat_f32(xyzw(self.body.quat(sim)));
        let angle = PI / 2.0 - m[(2, 2)].acos();
        let offset = (f.handle_length / 2.0 + 2.0 * f.head_halfsize) * angle.sin();
        let hammer_height = self.handle_pos(sim)[2] - f.top_offset() - offset;
        let gripper = |i: usize| {
            let a = self.arms[i];
            robots[a.robot].arms()[a.arm].gripper()
        };
        TaskInfo {
            arm0_grasps_any: is_grasped(sim, gripper(0), &self.body.geoms),
            arm1_grasps_handle: is_grasped(sim, gripper(1), &self.handle),
            hammer_height,
            table_height: sim.data().site_xpos()[self.table_top][2],
        }
    }

    /// Gives the scene's hammer `figures` (see [`reshape_body_from`]).
    fn reshape(&mut self, sim: &mut Sim, figures: HammerFigures) -> Result<()> {
        let mut hammer = self.hammer.clone();
        hammer.figures = figures;
        let donor = hammer.donor_model()?;
        let size = donor.stat().meansize;
        reshape_body_from(sim, self.body.body, &donor, 1, size - self.donor_size)?;
        self.hammer = hammer;
        self.donor_size = size;
        Ok(())
    }
}

impl TaskLogic for TwoArmHandover {
    fn randomize_model(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let figures = HammerFigures::draw(&self.spec.hammer, rng);
        self.reshape(sim, figures)
    }

    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let f = self.hammer.figures;
        let extent = PlacedObject {
            horizontal_radius: f.head_halfsize + 0.5 * f.handle_length,
            bottom_offset: -f.handle_radius,
            top_offset: f.handle_radius,
        };
        let (pos, quat) = self.sampler.sample(rng, &[extent], &[])?[0];
        let quat = with_init_quat(quat, Hammer::init_quat(rng));
        self.body.set_pose(sim, pos, quat);
        Ok(())
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let mut reward = 0.0;
        if config.reward_shaping {
            let info = self.info(sim, robots);
            if info.lifted() {
                if info.arm1_grasps_handle {
                    reward = if info.arm0_grasps_any { 1.5 } else { 2.0 };
                } else {
                    let d = dist(self.handle_pos(sim), self.arms[1].eef_pos(sim, robots));
                    reward = 1.0 + 0.25 * (1.0 - d.tanh());
                }
            } else if info.arm0_grasps_any {
                reward = 0.5;
            } else {
                let d = dist(self.handle_pos(sim), self.arms[0].eef_pos(sim, robots));
                reward = 0.25 * (1.0 - d.tanh());
            }
        } else if self.check_success(sim, robots) {
            reward = 2.0;
        }
        scale_reward(reward, config.reward_scale, 2.0)
    }

    fn check_success(&self, sim: &Sim, robots: &[Robot]) -> bool {
        let info = self.info(sim, robots);
        info.arm1_grasps_handle && !info.arm0_grasps_any && info.lifted()
    }

    fn save_state(&self) -> Vec<f64> {
        self.hammer.figures.to_array().to_vec()
    }

    fn load_state(&mut self, sim: &mut Sim, state: &[f64]) -> Result<()> {
        let values: [f64; 5] = state.try_into().map_err(|_| {
            Error::invalid_argument(
                "task state",
                format!(
                    "TwoArmHandover's state is the hammer's 5 figures (radius, length, density, \
                     friction, head half-size), got {} values",
                    state.len()
                ),
            )
        })?;
        let figures = HammerFigures::from_array(values);
        if figures != self.hammer.figures {
            self.reshape(sim, figures)?;
        }
        Ok(())
    }
}
