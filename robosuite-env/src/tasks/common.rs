//! Helpers shared by the tasks: free-joint objects, distances, grasp checks, reward scaling,
//! robosuite's single-object modes and its object-pose sensors.

use super::RewardConfig;
use crate::assets::Assets;
use crate::math::{conj, mat_from_row_major, mat2quat, pose_inv_of, quat_mul, quat_rotate, xyzw};
use crate::models::objects::{CustomMaterial, ObjectModel};
use crate::observables::{Modality, Observable};
use crate::robots::{Gripper, Robot};
use crate::sim::{GeomSet, Sim, any_contact_between, body_id, geom_id, joint_id};
use gym_core::{DType, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;

/// A free-floating object bound in a compiled model.
#[derive(Debug, Clone, PartialEq)]
pub struct FreeBody {
    /// Body id.
    pub body: usize,
    /// `qpos` address of the free joint.
    pub qpos: usize,
    /// `qvel` address of the free joint.
    pub dof: usize,
    /// Contact geoms.
    pub geoms: GeomSet,
}

impl FreeBody {
    /// Binds `object`: its root body, its first joint (which must be free) and its contact
    /// geoms.
    ///
    /// # Errors
    /// [`Error::Model`] for a missing name or a first joint that is not free.
    pub fn bind(model: &MjModel, object: &ObjectModel) -> Result<Self> {
        let joint = object
            .joints()
            .into_iter()
            .next()
            .ok_or_else(|| Error::model(format!("object `{}` has no joint", object.name)))?;
        let j = joint_id(model, &joint)?;
        if model.jnt_type()[j] != mujoco_rs::mujoco_c::mjtJoint::mjJNT_FREE {
            return Err(Error::model(format!("`{joint}` must be a free joint")));
        }
        Ok(Self {
            body: body_id(model, &object.root_body())?,
            qpos: model.jnt_qposadr()[j] as usize,
            dof: model.jnt_dofadr()[j] as usize,
            geoms: geoms_of(model, &object.contact_geoms())?,
        })
    }

    /// Writes the free joint's position and quaternion (wxyz) and zeroes its velocity.
    pub fn set_pose(&self, sim: &mut Sim, pos: [f64; 3], quat: [f64; 4]) {
        let d = sim.data_mut();
        let qpos = d.qpos_mut();
        qpos[self.qpos..self.qpos + 3].copy_from_slice(&pos);
        qpos[self.qpos + 3..self.qpos + 7].copy_from_slice(&quat);
        d.qvel_mut()[self.dof..self.dof + 6].fill(0.0);
    }

    /// The body position (`body_xpos`, as read without a forward pass).
    pub fn pos(&self, sim: &Sim) -> [f64; 3] {
        sim.data().xpos()[self.body]
    }

    /// The body orientation (`body_xquat`, wxyz).
    pub fn quat(&self, sim: &Sim) -> [f64; 4] {
        sim.data().xquat()[self.body]
    }
}

/// The wood material robosuite gives the cubes of Lift and Stack: `CustomMaterial(texture,
/// tex_name, f"{tex_name}_mat")` with a cube texture, `texrepeat="1 1"`, `specular="0.4"`
/// and `shininess="0.1"` (`"WoodRed"` / `"redwood"`, `"WoodGreen"` / `"greenwood"`).
///
/// # Errors
/// As [`CustomMaterial::new`].
pub fn wood_material(assets: &Assets, texture: &str, tex_name: &str) -> Result<CustomMaterial> {
    CustomMaterial::new(
        assets,
        texture,
        tex_name,
        &format!("{tex_name}_mat"),
        &[("type", "cube")],
        &[
            ("texrepeat", "1 1"),
            ("specular", "0.4"),
            ("shininess", "0.1"),
        ],
        false,
    )
}

/// The geom ids of `names`.
///
/// # Errors
/// [`Error::Model`] for a missing geom.
pub fn geoms_of(model: &MjModel, names: &[String]) -> Result<GeomSet> {
    Ok(GeomSet::new(
        names
            .iter()
            .map(|n| geom_id(model, n))
            .collect::<Result<Vec<_>>>()?,
    ))
}

/// robosuite's `clear_objects` target: unused objects are parked at (10, 10, 10).
pub const PARKED_POS: [f64; 3] = [10.0, 10.0, 10.0];

/// Euclidean distance.
pub fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Horizontal distance.
pub fn dist_xy(a: [f64; 3], b: [f64; 3]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// `a − b`.
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// robosuite's `_check_grasp(gripper, object_geoms)`: some geom of each finger-pad group
/// touches `geoms`.
pub fn is_grasped(sim: &Sim, gripper: &Gripper, geoms: &GeomSet) -> bool {
    let (left, right) = gripper.finger_pads();
    any_contact_between(sim.data(), left, geoms) && any_contact_between(sim.data(), right, geoms)
}

/// robosuite's `_check_grasp(self.robots[0].gripper, geoms)`: whether a gripper of robot 0
/// grasps `geoms` (any arm's, for a bimanual robot, whose `gripper` is a dict per arm).
pub fn robot0_grasps(sim: &Sim, robots: &[Robot], geoms: &GeomSet) -> bool {
    robots
        .first()
        .is_some_and(|r| r.arms().iter().any(|a| is_grasped(sim, a.gripper(), geoms)))
}

/// Robot 0's (first arm's) grip-site position (the origin when there is no robot).
pub fn eef_pos(sim: &Sim, robots: &[Robot]) -> [f64; 3] {
    robots.first().map_or([0.0; 3], |r| r.eef_pos(sim, 0))
}

/// robosuite's `_gripper_to_target(self.robots[0].gripper, target, return_distance=True)`:
/// the distance from robot 0's grip site to `target`, the smallest over its arms for a
/// bimanual robot (infinite when there is no robot).
pub fn robot0_eef_dist(sim: &Sim, robots: &[Robot], target: [f64; 3]) -> f64 {
    robots.first().map_or(f64::INFINITY, |r| {
        (0..r.arms().len())
            .map(|arm| dist(r.eef_pos(sim, arm), target))
            .fold(f64::INFINITY, f64::min)
    })
}

/// One arm of robot 0 as robosuite's single-arm tasks name its observables.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TaskArm {
    /// robosuite's `_get_arm_prefixes(robot, include_robot_name=False)` entry: empty for a
    /// single-arm robot, `"{side}_"` (`"right_"`, `"left_"`) for each arm of a bimanual one.
    pub prefix: String,
    /// The same with the robot's prefix (`"robot0_"`, `"robot0_right_"`).
    pub full_prefix: String,
    /// The arm's index in [`Robot::arms`].
    pub arm: usize,
    /// The arm's grip site.
    pub eef_site: usize,
    /// The body of the arm's end effector (the hand).
    pub eef_body: usize,
}

/// Robot 0's arms in robosuite's order (`robot.arms`: right, then left), with the prefixes
/// its single-arm tasks give their per-arm observables (`{prefix}gripper_to_cube_pos`,
/// `door_to_{full_prefix}eef_pos`).
pub fn robot0_arms(robots: &[Robot]) -> Vec<TaskArm> {
    let Some(robot) = robots.first() else {
        return Vec::new();
    };
    let one = robot.arms().len() == 1;
    robot
        .arms()
        .iter()
        .enumerate()
        .map(|(i, a)| {
            let prefix = if one {
                String::new()
            } else {
                format!("{}_", a.side())
            };
            TaskArm {
                full_prefix: format!("robot{}_{prefix}", robot.index()),
                prefix,
                arm: i,
                eef_site: a.eef_site(),
                eef_body: a.eef_body(),
            }
        })
        .collect()
}

/// Applies `reward_scale` (`None`: unnormalised) with robosuite's normalisation divisor, in
/// robosuite's arithmetic order (`reward *= reward_scale / max`).
pub fn scale_reward(reward: f64, scale: Option<f64>, max: f64) -> f64 {
    match scale {
        Some(s) => reward * (s / max),
        None => reward,
    }
}

/// Where an object's pose is read (robosuite's object sensors read a body, and ToolHang's
/// a geom or a site).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PoseRef {
    /// A body's `xpos` / `xquat`.
    Body(usize),
    /// A geom's `geom_xpos` / `geom_xmat` (quaternion through robosuite's `mat2quat`, which
    /// returns float32).
    Geom(usize),
    /// A site's `site_xpos` / `site_xmat` (quaternion through robosuite's `mat2quat`).
    Site(usize),
    /// A body's `xpos` / `xmat` (quaternion through robosuite's `mat2quat`: ToolHang's
    /// body query).
    BodyFrame(usize),
}

/// robosuite's `mat2quat` of a MuJoCo frame matrix: `xyzw`, `w ≥ 0`, float32 values.
fn frame_quat(xmat: &[f64; 9]) -> [f64; 4] {
    mat2quat(&mat_from_row_major(xmat)).map(|v| f64::from(v as f32))
}

impl PoseRef {
    /// The position and the `xyzw` quaternion, as read without a forward pass.
    pub fn pose(self, sim: &Sim) -> ([f64; 3], [f64; 4]) {
        let d = sim.data();
        match self {
            Self::Body(b) => (d.xpos()[b], xyzw(d.xquat()[b])),
            Self::Geom(g) => (d.geom_xpos()[g], frame_quat(&d.geom_xmat()[g])),
            Self::Site(s) => (d.site_xpos()[s], frame_quat(&d.site_xmat()[s])),
            Self::BodyFrame(b) => (d.xpos()[b], frame_quat(&d.xmat()[b])),
        }
    }
}

/// robosuite's object sensors (`_create_obj_sensors`) for a set of objects, with the
/// observation cache they read.
///
/// robosuite computes `{obj}_to_robot0_eef_pos` / `_quat` (the object's pose in the frame
/// of the grip-site position and the hand-body orientation) before it samples `{obj}_pos`
/// and `{obj}_quat` in the same pass, from its observation cache: so they combine the
/// current gripper pose with the object pose of the *previous* observation, and are zero
/// in the first observation after a reset. This keeps that cache. With a bimanual robot
/// every arm has its own relative pose (`{obj}_to_robot0_right_eef_pos`, ...).
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectSensors {
    poses: Vec<PoseRef>,
    /// Robot 0's arms: (full prefix, arm prefix, grip site, hand body).
    arms: Vec<(String, String, usize, usize)>,
    previous: Option<Vec<([f64; 3], [f64; 4])>>,
}

impl ObjectSensors {
    /// Sensors for objects whose poses `poses` reads, relative to each arm of robot 0.
    pub fn new(poses: Vec<PoseRef>, robots: &[Robot]) -> Self {
        Self {
            poses,
            arms: robot0_arms(robots)
                .into_iter()
                .map(|a| (a.full_prefix, a.prefix, a.eef_site, a.eef_body))
                .collect(),
            previous: None,
        }
    }

    /// Forgets the cached poses (every reset).
    pub fn clear(&mut self) {
        self.previous = None;
    }

    /// Caches the objects' current poses (after every observation pass). Reuses the cache's
    /// buffer: only the first pass after [`ObjectSensors::clear`] allocates.
    pub fn remember(&mut self, sim: &Sim) {
        let previous = self.previous.get_or_insert_with(Vec::new);
        previous.clear();
        previous.extend(self.poses.iter().map(|p| p.pose(sim)));
    }

    /// The cache as flat numbers (for snapshots): empty when cleared.
    pub fn save(&self) -> Vec<f64> {
        self.previous.as_ref().map_or_else(Vec::new, |poses| {
            poses
                .iter()
                .flat_map(|(p, q)| p.iter().chain(q).copied())
                .collect()
        })
    }

    /// Restores a cache from [`ObjectSensors::save`].
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a wrong length.
    pub fn load(&mut self, values: &[f64]) -> Result<()> {
        if values.is_empty() {
            self.previous = None;
            return Ok(());
        }
        if values.len() != 7 * self.poses.len() {
            return Err(Error::invalid_argument(
                "task state",
                format!(
                    "expected {} cached pose values, got {}",
                    7 * self.poses.len(),
                    values.len()
                ),
            ));
        }
        self.previous = Some(
            values
                .chunks_exact(7)
                .map(|c| ([c[0], c[1], c[2]], [c[3], c[4], c[5], c[6]]))
                .collect(),
        );
        Ok(())
    }

    /// The length of [`ObjectSensors::save`] when filled.
    pub fn saved_len(&self) -> usize {
        7 * self.poses.len()
    }

    /// The relative pose of object `i`'s cached pose in the current frame of arm `arm`'s
    /// gripper: position and `xyzw` quaternion (`w ≥ 0`), or zeros before the first pass.
    fn relative(&self, sim: &Sim, i: usize, arm: usize) -> ([f64; 3], [f64; 4]) {
        let Some((pos, quat_xyzw)) = self.previous.as_ref().map(|p| p[i]) else {
            return ([0.0; 3], [0.0; 4]);
        };
        let (_, _, eef_site, eef_body) = self.arms[arm];
        let d = sim.data();
        let eef_p = d.site_xpos()[eef_site];
        let eef_q = d.xquat()[eef_body];
        let q = [quat_xyzw[3], quat_xyzw[0], quat_xyzw[1], quat_xyzw[2]];
        let inv = conj(eef_q);
        let rel_p = quat_rotate(inv, sub(pos, eef_p));
        let mut rel_q = quat_mul(inv, q);
        if rel_q[0] < 0.0 {
            rel_q = rel_q.map(|v| -v);
        }
        (rel_p, xyzw(rel_q))
    }

    /// robosuite's `world_pose_in_gripper`: the world's pose in arm `arm`'s gripper frame
    /// (grip-site position, hand-body orientation), `T.pose_inv(T.pose2mat((eef_pos,
    /// eef_quat)))`.
    fn world_pose(&self, sim: &Sim, arm: usize) -> [f64; 16] {
        let (_, _, eef_site, eef_body) = self.arms[arm];
        let d = sim.data();
        pose_inv_of(d.site_xpos()[eef_site], xyzw(d.xquat()[eef_body]))
    }

    /// robosuite's `world_pose_in_{arm}gripper` observables, one per arm of robot 0
    /// (`world_pose_in_gripper` for a single-arm robot; 4x4 float64 matrices, modality
    /// `object`), enabled and inactive as robosuite makes them: read in every observation
    /// pass (robosuite's relative-pose sensors read them from the observation cache) but
    /// not in the observation dict. `get` finds the sensors in the task.
    pub fn world_pose_observables<T: 'static>(
        &self,
        get: fn(&T) -> &ObjectSensors,
    ) -> Vec<Observable<T>> {
        self.arms
            .iter()
            .enumerate()
            .map(|(arm, (_, prefix, _, _))| {
                Observable::new(
                    format!("world_pose_in_{prefix}gripper"),
                    &[4, 4],
                    DType::F64,
                    Modality::Object,
                    move |t: &T, sim, out| out.copy_from_slice(&get(t).world_pose(sim, arm)),
                )
                .inactive()
            })
            .collect()
    }

    /// The observables of object `i` named `name`, in robosuite's order:
    /// `{name}_to_robot0_eef_pos` per arm (`{name}_to_robot0_right_eef_pos`,
    /// `{name}_to_robot0_left_eef_pos` for a bimanual robot), `{name}_to_robot0_eef_quat`
    /// per arm, `{name}_pos`, `{name}_quat` (modality `object`). `get` finds the sensors in
    /// the task; `quat_dtype` is the dtype robosuite gives `{name}_quat` (float32 where it
    /// reads a frame's matrix, as ToolHang's sensors do); the relative quaternion is always
    /// float64.
    pub fn observables<T: 'static>(
        &self,
        get: fn(&T) -> &ObjectSensors,
        i: usize,
        name: &str,
        quat_dtype: DType,
    ) -> Vec<Observable<T>> {
        let mut out: Vec<Observable<T>> = self
            .arms
            .iter()
            .enumerate()
            .map(|(arm, (full, _, _, _))| {
                Observable::vec(
                    format!("{name}_to_{full}eef_pos"),
                    Modality::Object,
                    move |t: &T, sim| get(t).relative(sim, i, arm).0,
                )
            })
            .collect();
        out.extend(self.arms.iter().enumerate().map(|(arm, (full, _, _, _))| {
            Observable::new(
                format!("{name}_to_{full}eef_quat"),
                &[4],
                DType::F64,
                Modality::Object,
                move |t: &T, sim, out| out.copy_from_slice(&get(t).relative(sim, i, arm).1),
            )
        }));
        out.push(Observable::vec(
            format!("{name}_pos"),
            Modality::Object,
            move |t: &T, sim| get(t).poses[i].pose(sim).0,
        ));
        out.push(Observable::new(
            format!("{name}_quat"),
            &[4],
            quat_dtype,
            Modality::Object,
            move |t: &T, sim, out| out.copy_from_slice(&get(t).poses[i].pose(sim).1),
        ));
        out
    }
}

/// robosuite's `single_object_mode` for PickPlace and NutAssembly.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ObjectMode {
    /// Mode 0: every object is in play.
    #[default]
    All,
    /// Mode 1: one object, drawn from the env RNG at every reset; the others are parked.
    RandomSingle,
    /// Mode 2: always the object with this index; the others are parked.
    Single(usize),
}

impl ObjectMode {
    /// robosuite's mode number.
    pub fn number(self) -> u8 {
        match self {
            Self::All => 0,
            Self::RandomSingle => 1,
            Self::Single(_) => 2,
        }
    }

    /// robosuite's reward for these tasks: one per placed object, plus (when shaping) the
    /// largest staged reward that `staged` computes; `reward_scale` divided by the number
    /// of objects in mode 0.
    pub fn reward(
        self,
        placed: &[bool],
        staged: impl FnOnce() -> [f64; 4],
        config: &RewardConfig,
    ) -> f64 {
        let mut r = placed.iter().filter(|b| **b).count() as f64;
        if config.reward_shaping {
            r += staged().iter().copied().fold(f64::NEG_INFINITY, f64::max);
        }
        if let Some(scale) = config.reward_scale {
            r *= scale;
            if self == Self::All {
                r /= placed.len() as f64;
            }
        }
        r
    }

    /// robosuite's success rule: every object placed in mode 0, at least one otherwise.
    pub fn is_success(self, placed: &[bool]) -> bool {
        let n = placed.iter().filter(|b| **b).count();
        match self {
            Self::All => n == placed.len(),
            _ => n > 0,
        }
    }
}
