//! robosuite's `Door`: open a hinged door, turning its latched handle first
//! (`environments/manipulation/door.py`, `DoorObject`).

use super::common::{TaskArm, robot0_arms, robot0_eef_dist, scale_reward, sub};
use super::options::{self, TaskOptions};
use super::table::table_arena;
use super::{Bound, RewardConfig, Task, TaskLogic, TaskScene, TaskSpec};
use crate::assets::Assets;
use crate::mjcf::tree::{self, format_number, set_attr};
use crate::models::objects::{Joints, ObjType, ObjectModel, xml_object};
use crate::models::robots::RobotModel;
use crate::observables::{Modality, Observable};
use crate::placement::{Axis, PlacedObject, Rotation, UniformRandomSampler};
use crate::robots::Robot;
use crate::sim::{Sim, body_id, joint_id, site_id};
use gym_core::{DType, EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use std::f64::consts::PI;

/// Door's settings (robosuite's constructor defaults).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DoorSpec {
    /// Whether the handle latches the door (robosuite's `use_latch`, default true): the
    /// door comes from `objects/door_lock.xml` instead of `objects/door.xml`, the reward
    /// pays for turning the handle and `handle_qpos` is observed.
    pub use_latch: bool,
    /// robosuite's `placement_initializer`: a sampler that replaces the task's own (it
    /// places every object of the task); `None` (the default) keeps robosuite's.
    #[serde(default)]
    pub placement_initializer: Option<UniformRandomSampler>,
}

impl Default for DoorSpec {
    fn default() -> Self {
        Self {
            use_latch: true,
            placement_initializer: None,
        }
    }
}

/// Door's table (hard-coded in robosuite): full size.
const TABLE_FULL_SIZE: [f64; 3] = [0.8, 0.3, 0.05];
/// Door's table top.
const TABLE_OFFSET: [f64; 3] = [-0.2, -0.35, 0.8];
/// `TableArena`'s default friction (Door passes none).
const TABLE_FRICTION: [f64; 3] = [1.0, 0.005, 0.0001];
/// Door's `agentview` camera (`set_camera`): position.
const AGENTVIEW_POS: [f64; 3] = [
    0.598_613_174_683_477_1,
    -4.392_035_683_362_857e-9,
    1.590_350_024_037_242_3,
];
/// Door's `agentview` camera: quaternion (wxyz).
const AGENTVIEW_QUAT: [f64; 4] = [
    0.638_017_773_628_234_9,
    0.304_849_743_843_078_6,
    0.304_849_863_052_368_16,
    0.638_017_773_628_234_9,
];

/// robosuite's `DoorObject(name="Door", friction=0.0, damping=0.1, lock=use_latch)`: the door
/// file as an XML object with no joints of its own added, its hinge's `frictionloss` and
/// `damping` overridden in the XML.
fn door_object(assets: &Assets, use_latch: bool) -> Result<ObjectModel> {
    let file = if use_latch {
        "objects/door_lock.xml"
    } else {
        "objects/door.xml"
    };
    let mut door = xml_object(assets, file, "Door", &Joints::None, ObjType::All, true)?;
    let hinge = door.name_of("hinge");
    let joint = tree::find_mut(&mut door.body, "joint", &[("name", Some(hinge.as_str()))])
        .ok_or_else(|| Error::model(format!("{file} has no joint `hinge`")))?;
    set_attr(joint, "frictionloss", format_number(0.0));
    set_attr(joint, "damping", format_number(0.1));
    Ok(door)
}

impl TaskSpec for DoorSpec {
    fn options(&self) -> TaskOptions {
        options::to_options(self)
    }

    fn configure(&mut self, options: &TaskOptions) -> Result<()> {
        *self = options::merged(self.name(), self, options)?;
        Ok(())
    }

    fn name(&self) -> &str {
        "Door"
    }

    fn build(&self, assets: &Assets, _robots: &mut [RobotModel]) -> Result<TaskScene> {
        let mut arena = table_arena(assets, TABLE_FULL_SIZE, TABLE_FRICTION, TABLE_OFFSET)?;
        arena.set_camera("agentview", AGENTVIEW_POS, AGENTVIEW_QUAT)?;
        Ok(TaskScene {
            arena,
            objects: vec![door_object(assets, self.use_latch)?],
            attached: Vec::new(),
        })
    }

    fn bind(&self, scene: &TaskScene, model: &MjModel, robots: &[Robot]) -> Result<Box<dyn Task>> {
        let door = &scene.objects[0];
        let qpos_of = |joint: &str| -> Result<usize> {
            Ok(model.jnt_qposadr()[joint_id(model, &door.name_of(joint))?] as usize)
        };
        let root = body_id(model, &door.root_body())?;
        let task = Door {
            use_latch: self.use_latch,
            sampler: self
                .placement_initializer
                .clone()
                .unwrap_or_else(|| UniformRandomSampler {
                    x_range: [0.07, 0.09],
                    y_range: [-0.01, 0.01],
                    rotation: Rotation::Range(-PI / 2.0 - 0.25, -PI / 2.0),
                    rotation_axis: Axis::Z,
                    ensure_object_boundary_in_range: false,
                    ensure_valid_placement: true,
                    reference_pos: TABLE_OFFSET,
                    z_offset: 0.0,
                }),
            extent: door.placement(),
            root,
            pose: (model.body_pos()[root], model.body_quat()[root]),
            door_body: body_id(model, &door.name_of("door"))?,
            handle_site: site_id(model, &door.name_of("handle"))?,
            hinge_qpos: qpos_of("hinge")?,
            latch_qpos: if self.use_latch {
                Some(qpos_of("latch_joint")?)
            } else {
                None
            },
        };
        let observables = task.make_observables(&robot0_arms(robots));
        Ok(Bound::boxed(task, observables))
    }
}

/// The bound Door task: the door (root body `Door_main`, no free joint) with the door panel
/// `Door_door` on the hinge `Door_hinge` (range [0, 0.4], damping 0.1, no friction) and,
/// with the latch, the handle on `Door_latch_joint`; table 0.8 × 0.3 × 0.05 with its top at
/// (−0.2, −0.35, 0.8).
///
/// * Reset: the door's root is placed through the model (`body_pos` / `body_quat`, part of
///   [`Task::save_state`]): `x ∈ U(0.07, 0.09)`, `y ∈ U(−0.01, 0.01)` around the table top,
///   its bottom on the table, yaw `U(−π/2 − 0.25, −π/2)`.
/// * Reward: 1 on success; shaped `0.25·(1 − tanh(10·d(grip site, handle)))` (the nearest
///   grip site of a bimanual robot) plus, with
///   the latch, `clip(0.25·|handle angle / (π/2)|, −0.25, 0.25)`; times `reward_scale`.
/// * Success: hinge angle above 0.3 rad.
#[derive(Debug, Clone)]
pub struct Door {
    use_latch: bool,
    sampler: UniformRandomSampler,
    extent: PlacedObject,
    root: usize,
    pose: ([f64; 3], [f64; 4]),
    door_body: usize,
    handle_site: usize,
    hinge_qpos: usize,
    latch_qpos: Option<usize>,
}

impl Door {
    /// robosuite's object observables, in its order: `door_pos` (door panel body),
    /// `handle_pos` (handle site), `hinge_qpos`, `door_to_{arm}eef_pos` per arm, then
    /// `handle_to_{arm}eef_pos` per arm (door / handle − grip site, despite the names; `arm`
    /// empty for a single-arm robot, `right_` / `left_` for a bimanual one), and with the
    /// latch `handle_qpos`.
    fn make_observables(&self, arms: &[TaskArm]) -> Vec<Observable<Door>> {
        let mut obs = vec![
            Observable::vec("door_pos", Modality::Object, |t: &Door, sim| {
                t.door_pos(sim)
            }),
            Observable::vec("handle_pos", Modality::Object, |t: &Door, sim| {
                t.handle_pos(sim)
            }),
            Observable::new(
                "hinge_qpos",
                &[],
                DType::F64,
                Modality::Object,
                |t: &Door, sim, out| {
                    out[0] = t.hinge_angle(sim);
                },
            ),
        ];
        obs.extend(arms.iter().map(|arm| {
            let site = arm.eef_site;
            Observable::vec(
                format!("door_to_{}eef_pos", arm.prefix),
                Modality::Object,
                move |t: &Door, sim| sub(t.door_pos(sim), sim.data().site_xpos()[site]),
            )
        }));
        obs.extend(arms.iter().map(|arm| {
            let site = arm.eef_site;
            Observable::vec(
                format!("handle_to_{}eef_pos", arm.prefix),
                Modality::Object,
                move |t: &Door, sim| sub(t.handle_pos(sim), sim.data().site_xpos()[site]),
            )
        }));
        if self.use_latch {
            obs.push(Observable::new(
                "handle_qpos",
                &[],
                DType::F64,
                Modality::Object,
                |t: &Door, sim, out| out[0] = t.handle_angle(sim).unwrap_or(0.0),
            ));
        }
        obs
    }

    /// The door panel's position (`door_pos`).
    pub fn door_pos(&self, sim: &Sim) -> [f64; 3] {
        sim.data().xpos()[self.door_body]
    }

    /// The handle site's position (`handle_pos`).
    pub fn handle_pos(&self, sim: &Sim) -> [f64; 3] {
        sim.data().site_xpos()[self.handle_site]
    }

    /// The hinge angle (`hinge_qpos`).
    pub fn hinge_angle(&self, sim: &Sim) -> f64 {
        sim.data().qpos()[self.hinge_qpos]
    }

    /// The handle (latch) angle, when the door has the latch (`handle_qpos`).
    pub fn handle_angle(&self, sim: &Sim) -> Option<f64> {
        self.latch_qpos.map(|a| sim.data().qpos()[a])
    }

    /// The door root's pose (position, wxyz quaternion) as placed in the model.
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

impl TaskLogic for Door {
    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let (pos, quat) = self.sampler.sample(rng, &[self.extent], &[])?[0];
        self.write_pose(sim, pos, quat);
        Ok(())
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let mut reward = 0.0;
        if self.check_success(sim, robots) {
            reward = 1.0;
        } else if config.reward_shaping {
            let d = robot0_eef_dist(sim, robots, self.handle_pos(sim));
            reward += 0.25 * (1.0 - (10.0 * d).tanh());
            if let Some(q) = self.handle_angle(sim) {
                reward += (0.25 * (q / (0.5 * PI)).abs()).clamp(-0.25, 0.25);
            }
        }
        scale_reward(reward, config.reward_scale, 1.0)
    }

    fn check_success(&self, sim: &Sim, _robots: &[Robot]) -> bool {
        self.hinge_angle(sim) > 0.3
    }

    /// The door root's pose in the model: position, then quaternion (wxyz).
    fn save_state(&self) -> Vec<f64> {
        let (p, q) = self.pose;
        p.iter().chain(&q).copied().collect()
    }

    fn load_state(&mut self, sim: &mut Sim, state: &[f64]) -> Result<()> {
        let bad = |why: String| Error::invalid_argument("task state", why);
        if state.len() != 7 {
            return Err(bad(format!(
                "Door's state is the door's root pose (position and wxyz quaternion, 7 values), got {} values",
                state.len()
            )));
        }
        if state.iter().any(|v| !v.is_finite()) || state[3..].iter().all(|v| *v == 0.0) {
            return Err(bad(format!(
                "the door's pose must be finite with a non-zero quaternion, got {state:?}"
            )));
        }
        let pos = [state[0], state[1], state[2]];
        let quat = [state[3], state[4], state[5], state[6]];
        self.write_pose(sim, pos, quat);
        Ok(())
    }
}
