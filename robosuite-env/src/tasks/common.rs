//! Helpers shared by the tasks: free-joint objects, distances, grasp checks and the
//! object-in-gripper-frame observations of robosuite's `_create_obj_sensors`.

use super::RewardConfig;
use crate::observations::ObsKey;
use crate::robots::Robot;
use crate::sim::{GeomSet, Sim, any_contact_between, body_id, geom_id, joint_id};
use gym_core::{DType, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;

/// A free-floating object bound in a compiled model.
#[derive(Debug, Clone, Default, PartialEq)]
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
    /// Binds body `body`, free joint `joint` and the contact geoms `geoms`.
    ///
    /// # Errors
    /// [`Error::Model`] for a missing name or a joint that is not free.
    pub fn bind(model: &MjModel, body: &str, joint: &str, geoms: &[String]) -> Result<Self> {
        let b = body_id(model, body)?;
        let j = joint_id(model, joint)?;
        if model.jnt_type()[j] != mujoco_rs::mujoco_c::mjtJoint::mjJNT_FREE {
            return Err(Error::Model(format!("`{joint}` must be a free joint")));
        }
        let ids = geoms
            .iter()
            .map(|g| geom_id(model, g))
            .collect::<Result<Vec<_>>>()?;
        Ok(Self {
            body: b,
            qpos: model.jnt_qposadr()[j] as usize,
            dof: model.jnt_dofadr()[j] as usize,
            geoms: GeomSet::new(ids),
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

/// robosuite's `_check_grasp` for robot 0: both finger-pad groups touch `geoms`.
pub fn is_grasped(sim: &Sim, robots: &[Robot], geoms: &GeomSet) -> bool {
    robots
        .first()
        .and_then(Robot::finger_pads)
        .is_some_and(|(left, right)| {
            any_contact_between(sim.data(), left, geoms)
                && any_contact_between(sim.data(), right, geoms)
        })
}

/// Robot 0's grip-site position (the origin when there is no robot).
pub fn eef_pos(sim: &Sim, robots: &[Robot]) -> [f64; 3] {
    robots.first().map_or([0.0; 3], |r| r.eef_pos(sim))
}

/// wxyz → xyzw.
pub fn xyzw(q: [f64; 4]) -> [f64; 4] {
    [q[1], q[2], q[3], q[0]]
}

/// Quaternion (wxyz) product.
pub fn quat_mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// Rotates `v` by the unit quaternion `q` (wxyz).
pub fn quat_rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let p = quat_mul(quat_mul(q, [0.0, v[0], v[1], v[2]]), conj(q));
    [p[1], p[2], p[3]]
}

/// Conjugate (inverse of a unit quaternion).
pub fn conj(q: [f64; 4]) -> [f64; 4] {
    [q[0], -q[1], -q[2], -q[3]]
}

/// Yaw rotation (wxyz) by `angle` about z.
pub fn yaw_quat(angle: f64) -> [f64; 4] {
    let (s, c) = (angle / 2.0).sin_cos();
    [c, 0.0, 0.0, s]
}

/// Writes robosuite's four object sensors in the order of its observation dict:
/// `{obj}_to_robot0_eef_pos` (3), `{obj}_to_robot0_eef_quat` (4, xyzw), `{obj}_pos` (3),
/// `{obj}_quat` (4, xyzw). The relative pose is the object's pose in the frame of the
/// end effector (grip-site position, hand-body orientation, as robosuite's
/// `world_pose_in_gripper`).
pub fn write_object_pose_obs(
    sim: &Sim,
    robots: &[Robot],
    pos: [f64; 3],
    quat: [f64; 4],
    out: &mut [f64],
) {
    let (eef_p, eef_q) = robots
        .first()
        .map_or(([0.0; 3], [1.0, 0.0, 0.0, 0.0]), |r| {
            (r.eef_pos(sim), sim.data().xquat()[r.hand_body()])
        });
    let inv = conj(eef_q);
    let rel_p = quat_rotate(
        inv,
        [pos[0] - eef_p[0], pos[1] - eef_p[1], pos[2] - eef_p[2]],
    );
    let mut rel_q = quat_mul(inv, quat);
    if rel_q[0] < 0.0 {
        rel_q = rel_q.map(|v| -v);
    }
    out[0..3].copy_from_slice(&rel_p);
    out[3..7].copy_from_slice(&xyzw(rel_q));
    out[7..10].copy_from_slice(&pos);
    out[10..14].copy_from_slice(&xyzw(quat));
}

/// The four observation keys of [`write_object_pose_obs`] for `name`.
pub fn object_pose_keys(name: &str) -> Vec<ObsKey> {
    vec![
        ObsKey::new(format!("{name}_to_robot0_eef_pos"), &[3], DType::F64),
        ObsKey::new(format!("{name}_to_robot0_eef_quat"), &[4], DType::F64),
        ObsKey::new(format!("{name}_pos"), &[3], DType::F64),
        ObsKey::new(format!("{name}_quat"), &[4], DType::F64),
    ]
}

/// Applies `reward_scale` (`None`: unnormalised) with robosuite's normalisation divisor.
pub fn scale_reward(reward: f64, scale: Option<f64>, max: f64) -> f64 {
    match scale {
        Some(s) => reward * s / max,
        None => reward,
    }
}

/// robosuite's `single_object_mode` for PickPlace and NutAssembly.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ObjectMode {
    /// Mode 0: every object is in play.
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

    /// The pose observation keys of the objects in play (14 per object). In
    /// [`ObjectMode::RandomSingle`] robosuite renames them after each reset's object; a fixed
    /// observation space cannot, so they are named `{single}_*` followed by `{single}_id`.
    pub fn pose_keys(self, names: &[&str], single: &str) -> Vec<ObsKey> {
        match self {
            Self::All => names.iter().flat_map(|n| object_pose_keys(n)).collect(),
            Self::Single(i) => object_pose_keys(names[i]),
            Self::RandomSingle => {
                let mut k = object_pose_keys(single);
                k.push(ObsKey::new(format!("{single}_id"), &[], DType::I64));
                k
            }
        }
    }

    /// Writes the pose observations of the objects in play, laid out as
    /// [`ObjectMode::pose_keys`]: `write(i, out)` fills object `i`'s 14 values; `active` is the
    /// object drawn for [`ObjectMode::RandomSingle`].
    pub fn write_pose_obs(
        self,
        count: usize,
        active: usize,
        out: &mut [f64],
        mut write: impl FnMut(usize, &mut [f64]),
    ) {
        match self {
            Self::All => {
                for i in 0..count {
                    write(i, &mut out[14 * i..14 * (i + 1)]);
                }
            }
            Self::Single(i) => write(i, &mut out[..14]),
            Self::RandomSingle => {
                write(active, &mut out[..14]);
                out[14] = active as f64;
            }
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
