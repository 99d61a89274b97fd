//! robosuite's `WHOLE_BODY_IK` composite controller (`controllers/composite/composite_controller.py`:
//! `WholeBody`, `WholeBodyIK`) and the IK solver it builds (`utils/ik_utils.py`: `IKSolver`).
//!
//! The env's action starts with one end-effector pose per reference site (`ref_name`: a
//! position and a rotation each); the solver turns those poses into joint targets for the
//! joints of the body parts it actuates (`actuation_part_names`), and those targets become
//! the actions of the parts' own controllers (`JOINT_POSITION` in robosuite's configs). The
//! rest of the action (grippers, parts outside the IK) goes to those parts as it is.
//!
//! [`IkSolver::solve`] is one damped least-squares step, as robosuite computes it:
//!
//! * the targets: `axis_angle` (robosuite's default) or `quat_wxyz` rotations, in the world
//!   frame, robosuite's `"base"` frame (the body `robot0_base`) or the frame of any other body
//!   (`ik_input_ref_frame`). As robosuite, a frame's pose is the body's pose relative to its
//!   parent (`body_pos` / `body_quat`), which is its world pose when the parent is the world,
//!   and the transformed rotation goes through robosuite's float32 `mat2quat`;
//! * the twist per site: `0.95·(p* − p)/dt` and `0.95·ω(q*·q̄)/dt` (`mju_quat2Vel`), with
//!   `dt = ik_integration_dt`;
//! * `q̇ = Jᵀ(JJᵀ + λ²I)⁻¹·twist + (I − J⁺J)·Kn∘(0 − q)` over the IK joints (`λ =
//!   ik_pseudo_inverse_damping`, `Kn` from `nullspace_joint_weights`, 1 for joints not named),
//!   scaled so that no entry exceeds `ik_max_dq`; then the entries at the *model ids* of the
//!   joints whose name contains `torso` are scaled to at most `ik_max_dq_torso` (robosuite
//!   indexes its step by model id there, not by place among the IK joints: the same entries
//!   when the torso joints come first in both, as in GR1);
//! * the joint targets `q + q̇·dt`, clipped to the joints' ranges (`[0, 0]` for a joint without
//!   limits, as robosuite's `np.clip` over `jnt_range`).
//!
//! An unreachable target gets robosuite's best effort: that one step toward it, limited by
//! `ik_max_dq` and the joint ranges. A target given in a non-world frame is clipped by nothing
//! else either.
//!
//! Deviations, each where robosuite would fail or compute garbage: a non-finite action is
//! refused ([`Error::InvalidAction`], nothing changed); a config whose ref sites are all
//! missing, whose torso joint ids fall outside the IK step, or whose IK joints' ids differ from
//! their `qpos` / dof addresses (robosuite indexes `qpos` and the Jacobian by joint id) is
//! refused when the controller is built. `J⁺` is the pseudo-inverse of `J` through `JJᵀ`
//! (robosuite: SVD of `J`), equal to rounding for a Jacobian of full row rank; where its rows
//! are dependent the cutoff applies to `JJᵀ`'s singular values. No step allocates.

use super::config::{join, typed};
use crate::math::{axisangle2quat, mat2quat, quat_multiply_f32, quat2mat_f32};
use crate::robots::composite::{
    ActionSlot, CompositeController, CompositeParts, PartRef, PartsMut, basic_set_goal,
};
use crate::robots::{Arm, BodyPart};
use crate::sim::{Sim, mju};
use gym_core::{Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use mujoco_rs::wrappers::mj_model::MjtObjBase as mjtObj;
use nalgebra::{DMatrix, Matrix3, Matrix4, SMatrix, SVector, Vector3};
use serde::Deserialize;
use serde_json::Value;
use std::collections::BTreeMap;
use std::ops::Range;

/// The most reference sites one solver takes (robosuite's configs name one or two).
pub const MAX_IK_SITES: usize = 4;

/// The rows of the padded task-space matrices: 6 per site.
const MAX_ROWS: usize = 6 * MAX_IK_SITES;
type Square = SMatrix<f64, MAX_ROWS, MAX_ROWS>;
type Column = SVector<f64, MAX_ROWS>;

/// robosuite's gains on the position and orientation errors (`Kpos`, `Kori`).
const K_TWIST: f64 = 0.95;

/// `numpy.linalg.pinv`'s default relative cutoff.
const PINV_RCOND: f64 = 1e-15;

/// The keys robosuite's `WholeBodyIK` reads from `composite_controller_specific_configs`
/// (and those its shipped configs write and it ignores: `max_dq`, `interpolation`,
/// `ik_verbose`). Other keys are ignored, as robosuite ignores them
/// ([`WholeBodyIkConfig::ignored_keys`]).
pub const WHOLE_BODY_IK_KEYS: &[&str] = &[
    "ref_name",
    "actuation_part_names",
    "nullspace_joint_weights",
    "ik_pseudo_inverse_damping",
    "ik_integration_dt",
    "ik_max_dq",
    "ik_max_dq_torso",
    "ik_input_type",
    "ik_input_ref_frame",
    "ik_input_rotation_repr",
    "skip_wbc_action",
    "body_part_ordering",
    "verbose",
    "ik_verbose",
    "max_dq",
    "interpolation",
];

/// How a target's rotation is written (`ik_input_rotation_repr`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum IkRotationRepr {
    /// A rotation vector, 3 values (robosuite's `"axis_angle"`, the default).
    #[default]
    AxisAngle,
    /// A quaternion `w, x, y, z`, 4 values (`"quat_wxyz"`).
    QuatWxyz,
}

impl IkRotationRepr {
    /// The values per rotation.
    pub fn dim(self) -> usize {
        match self {
            Self::AxisAngle => 3,
            Self::QuatWxyz => 4,
        }
    }
}

/// What a target pose means (robosuite's `IKSolver.input_action_repr`).
///
/// robosuite's `WHOLE_BODY_IK` always uses [`IkActionRepr::Absolute`]; the relative modes
/// are its `IKSolver`'s, set from Rust only ([`WholeBodyIkConfig::input_action_repr`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum IkActionRepr {
    /// The pose itself (`"absolute"`).
    #[default]
    Absolute,
    /// A position change added to the site's position and a rotation applied after the
    /// site's (`"relative"`: robosuite's `quat_multiply(mat2quat(R), q)`, in float32).
    Relative,
    /// A pose in the site's frame (`"relative_pose"`: `X_site · X_action`). As robosuite, the
    /// action's `w, x, y, z` quaternion is read by `quat2mat` as `x, y, z, w`.
    RelativePose,
}

/// The frame targets are given in (`ik_input_ref_frame`).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum IkRefFrame {
    /// The world frame (`"world"`, robosuite's default).
    #[default]
    World,
    /// robosuite's `"base"`: the body `robot0_base` (robosuite names it so for every robot).
    Base,
    /// The body of this name (such as `"mobilebase0_base"`).
    Body(String),
}

impl IkRefFrame {
    /// The body whose frame this is, `None` for the world.
    pub fn body(&self) -> Option<&str> {
        match self {
            Self::World => None,
            Self::Base => Some("robot0_base"),
            Self::Body(name) => Some(name),
        }
    }
}

/// robosuite's `WHOLE_BODY_IK` settings (its `composite_controller_specific_configs`).
#[derive(Debug, Clone, PartialEq)]
pub struct WholeBodyIkConfig {
    /// The sites whose poses the action sets, in the action's order (`ref_name`).
    pub ref_name: Vec<String>,
    /// The body parts whose joints the IK moves, in this order (`actuation_part_names`).
    pub actuation_part_names: Vec<String>,
    /// The nullspace gain of each named joint; 1 for the others
    /// (`nullspace_joint_weights`).
    pub nullspace_joint_weights: BTreeMap<String, f64>,
    /// The damping `λ` of the least-squares solve (`ik_pseudo_inverse_damping`, 0.05).
    pub damping: f64,
    /// The time over which the twist is integrated (`ik_integration_dt`, 0.1 s).
    pub integration_dt: f64,
    /// The largest entry of the joint step `q̇`; `<= 0` for none (`ik_max_dq`, 4).
    pub max_dq: f64,
    /// The largest entry of the torso joints' step; `<= 0` for none (`ik_max_dq_torso`,
    /// 0.2).
    pub max_dq_torso: f64,
    /// The frame of the targets (`ik_input_ref_frame`, world).
    pub input_ref_frame: IkRefFrame,
    /// How rotations are written (`ik_input_rotation_repr`, axis-angle).
    pub input_rotation_repr: IkRotationRepr,
    /// What the poses mean: absolute as robosuite's `WHOLE_BODY_IK` (no config key sets it).
    pub input_action_repr: IkActionRepr,
    /// The parts' own actions instead of poses, IK unused (`skip_wbc_action`).
    pub skip_wbc_action: bool,
    /// The order of the body parts, when given (`body_part_ordering`).
    pub body_part_ordering: Option<Vec<String>>,
    /// Keys of the config that robosuite ignores (and so does this crate), as paths.
    pub ignored_keys: Vec<String>,
}

impl Default for WholeBodyIkConfig {
    /// robosuite's defaults, with no sites and no parts.
    fn default() -> Self {
        Self {
            ref_name: Vec::new(),
            actuation_part_names: Vec::new(),
            nullspace_joint_weights: BTreeMap::new(),
            damping: 5e-2,
            integration_dt: 0.1,
            max_dq: 4.0,
            max_dq_torso: 0.2,
            input_ref_frame: IkRefFrame::World,
            input_rotation_repr: IkRotationRepr::AxisAngle,
            input_action_repr: IkActionRepr::Absolute,
            skip_wbc_action: false,
            body_part_ordering: None,
            ignored_keys: Vec::new(),
        }
    }
}

#[derive(Deserialize)]
struct RawConfig {
    ref_name: Option<Vec<String>>,
    actuation_part_names: Option<Vec<String>>,
    nullspace_joint_weights: Option<BTreeMap<String, f64>>,
    ik_pseudo_inverse_damping: Option<f64>,
    ik_integration_dt: Option<f64>,
    ik_max_dq: Option<f64>,
    ik_max_dq_torso: Option<f64>,
    ik_input_type: Option<String>,
    ik_input_ref_frame: Option<String>,
    ik_input_rotation_repr: Option<String>,
    skip_wbc_action: Option<bool>,
    body_part_ordering: Option<Vec<String>>,
    verbose: Option<bool>,
    ik_verbose: Option<bool>,
    max_dq: Option<f64>,
    interpolation: Option<Value>,
}

impl WholeBodyIkConfig {
    /// Parses robosuite's `composite_controller_specific_configs` dict at `path` (the name
    /// errors give it, such as `controller_configs.composite_controller_specific_configs`).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the key for a missing `ref_name`,
    /// `actuation_part_names` or `nullspace_joint_weights` (robosuite fails on them too), an
    /// ill-typed value, a damping or time step that is not finite and `> 0`, a non-finite
    /// step limit or weight, an unknown rotation representation, or an `ik_input_type` asking
    /// for relative input (robosuite hands that key to its solver's teleoperation source, so
    /// its `WHOLE_BODY_IK` always takes absolute poses).
    pub fn from_value(value: &Value, path: &str) -> Result<Self> {
        let obj = value.as_object().ok_or_else(|| {
            Error::invalid_argument(path, "expected a dict of WHOLE_BODY_IK settings")
        })?;
        let ignored_keys = obj
            .keys()
            .filter(|k| !WHOLE_BODY_IK_KEYS.contains(&k.as_str()))
            .map(|k| join(path, k))
            .collect();
        let known: serde_json::Map<String, Value> = obj
            .iter()
            .filter(|(k, _)| WHOLE_BODY_IK_KEYS.contains(&k.as_str()))
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect();
        let raw: RawConfig = typed(Value::Object(known), path)?;
        let _ = (raw.verbose, raw.ik_verbose, raw.max_dq, raw.interpolation);
        let missing = |key: &str| {
            Error::invalid_argument(
                join(path, key),
                "missing (robosuite's WHOLE_BODY_IK requires ref_name, actuation_part_names \
                 and nullspace_joint_weights)",
            )
        };
        let defaults = Self::default();
        let config = Self {
            ref_name: raw.ref_name.ok_or_else(|| missing("ref_name"))?,
            actuation_part_names: raw
                .actuation_part_names
                .ok_or_else(|| missing("actuation_part_names"))?,
            nullspace_joint_weights: raw
                .nullspace_joint_weights
                .ok_or_else(|| missing("nullspace_joint_weights"))?,
            damping: raw.ik_pseudo_inverse_damping.unwrap_or(defaults.damping),
            integration_dt: raw.ik_integration_dt.unwrap_or(defaults.integration_dt),
            max_dq: raw.ik_max_dq.unwrap_or(defaults.max_dq),
            max_dq_torso: raw.ik_max_dq_torso.unwrap_or(defaults.max_dq_torso),
            input_ref_frame: match raw.ik_input_ref_frame.as_deref() {
                None | Some("world") => IkRefFrame::World,
                Some("base") => IkRefFrame::Base,
                Some(body) => IkRefFrame::Body(body.to_owned()),
            },
            input_rotation_repr: match raw.ik_input_rotation_repr.as_deref() {
                None | Some("axis_angle") => IkRotationRepr::AxisAngle,
                Some("quat_wxyz") => IkRotationRepr::QuatWxyz,
                Some(other) => {
                    return Err(Error::invalid_argument(
                        join(path, "ik_input_rotation_repr"),
                        format!(
                            "unknown rotation representation `{other}`; valid: axis_angle, quat_wxyz"
                        ),
                    ));
                }
            },
            input_action_repr: IkActionRepr::Absolute,
            skip_wbc_action: raw.skip_wbc_action.unwrap_or(false),
            body_part_ordering: raw.body_part_ordering,
            ignored_keys,
        };
        if let Some(kind @ ("relative" | "relative_pose" | "delta")) = raw.ik_input_type.as_deref()
        {
            return Err(Error::invalid_argument(
                join(path, "ik_input_type"),
                format!(
                    "`{kind}` is not served: robosuite's WHOLE_BODY_IK passes ik_input_type to its \
                     IK solver's teleoperation source, so its poses are always absolute; use \
                     \"absolute\" or leave the key out"
                ),
            ));
        }
        config.check(path)?;
        Ok(config)
    }

    /// Checks the values (what [`WholeBodyIkConfig::from_value`] checks after parsing).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the key (under `path`) for a damping or time step
    /// that is not finite and `> 0`, or a non-finite step limit or nullspace weight.
    pub fn check(&self, path: &str) -> Result<()> {
        for (key, v) in [
            ("ik_pseudo_inverse_damping", self.damping),
            ("ik_integration_dt", self.integration_dt),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid_argument(
                    join(path, key),
                    format!("must be finite and > 0, got {v}"),
                ));
            }
        }
        for (key, v) in [
            ("ik_max_dq", self.max_dq),
            ("ik_max_dq_torso", self.max_dq_torso),
        ] {
            if !v.is_finite() {
                return Err(Error::invalid_argument(
                    join(path, key),
                    format!("must be finite (<= 0 for no limit), got {v}"),
                ));
            }
        }
        if let Some((joint, w)) = self
            .nullspace_joint_weights
            .iter()
            .find(|(_, w)| !w.is_finite())
        {
            return Err(Error::invalid_argument(
                join(&join(path, "nullspace_joint_weights"), joint),
                format!("must be finite, got {w}"),
            ));
        }
        Ok(())
    }
}

/// The solver's settings besides its sites and joints.
#[derive(Debug, Clone, PartialEq)]
pub struct IkSettings {
    /// The damping `λ` (`> 0`).
    pub damping: f64,
    /// The integration time step (`> 0`).
    pub integration_dt: f64,
    /// The largest step entry (`<= 0`: none).
    pub max_dq: f64,
    /// The largest torso step entry (`<= 0`: none).
    pub max_dq_torso: f64,
    /// The targets' frame.
    pub input_ref_frame: IkRefFrame,
    /// The rotations' representation.
    pub input_rotation_repr: IkRotationRepr,
    /// What the poses mean.
    pub input_action_repr: IkActionRepr,
}

impl From<&WholeBodyIkConfig> for IkSettings {
    fn from(c: &WholeBodyIkConfig) -> Self {
        Self {
            damping: c.damping,
            integration_dt: c.integration_dt,
            max_dq: c.max_dq,
            max_dq_torso: c.max_dq_torso,
            input_ref_frame: c.input_ref_frame.clone(),
            input_rotation_repr: c.input_rotation_repr,
            input_action_repr: c.input_action_repr,
        }
    }
}

/// robosuite's `IKSolver`: one damped least-squares step from end-effector targets to joint
/// targets (see the [module docs](self)). Buffers are sized at construction; a solve does
/// not allocate.
#[derive(Debug, Clone)]
pub struct IkSolver {
    settings: IkSettings,
    site_names: Vec<String>,
    sites: Vec<usize>,
    joint_names: Vec<String>,
    /// Model joint ids, which robosuite uses as `qpos` and dof indices (checked equal).
    joints: Vec<usize>,
    kn: Vec<f64>,
    ranges: Vec<[f64; 2]>,
    /// The entries of the step robosuite limits to `max_dq_torso` (the torso joints' ids).
    torso: Vec<usize>,
    frame_body: Option<usize>,
    jacp: Vec<f64>,
    jacr: Vec<f64>,
    jac: DMatrix<f64>,
    target_pos: Vec<[f64; 3]>,
    target_quat: Vec<[f64; 4]>,
    null_in: Vec<f64>,
    dq: Vec<f64>,
    q_des: Vec<f64>,
}

impl IkSolver {
    /// A solver moving `joints` (model joint names, in the step's order) to bring `sites`
    /// to their targets, with nullspace gains `nullspace_gains` (one per joint).
    ///
    /// # Errors
    /// [`Error::Model`] for a site, joint or frame body the model lacks;
    /// [`Error::InvalidArgument`] for no site or more than [`MAX_IK_SITES`], no joint, gains
    /// of the wrong length or not finite, settings out of range, a joint that is not a hinge
    /// or slide whose model id equals its `qpos` and dof addresses (robosuite indexes both by
    /// joint id), or a torso joint whose model id is not an index into the step (robosuite
    /// indexes the step by it).
    pub fn new(
        model: &MjModel,
        sites: &[&str],
        joints: &[&str],
        nullspace_gains: &[f64],
        settings: IkSettings,
    ) -> Result<Self> {
        let check = WholeBodyIkConfig {
            damping: settings.damping,
            integration_dt: settings.integration_dt,
            max_dq: settings.max_dq,
            max_dq_torso: settings.max_dq_torso,
            ..WholeBodyIkConfig::default()
        };
        check.check("whole_body_ik")?;
        if sites.is_empty() || sites.len() > MAX_IK_SITES {
            return Err(Error::invalid_argument(
                "ref_name",
                format!(
                    "the IK takes 1 to {MAX_IK_SITES} reference sites, got {}",
                    sites.len()
                ),
            ));
        }
        if joints.is_empty() {
            return Err(Error::invalid_argument(
                "actuation_part_names",
                "the IK needs at least one joint to move",
            ));
        }
        if nullspace_gains.len() != joints.len() || nullspace_gains.iter().any(|k| !k.is_finite()) {
            return Err(Error::invalid_argument(
                "nullspace_joint_weights",
                format!(
                    "need {} finite nullspace gains, got {:?}",
                    joints.len(),
                    nullspace_gains
                ),
            ));
        }
        let site_ids = sites
            .iter()
            .map(|s| crate::sim::site_id(model, s))
            .collect::<Result<Vec<_>>>()?;
        let joint_ids = joints
            .iter()
            .map(|j| crate::sim::joint_id(model, j))
            .collect::<Result<Vec<_>>>()?;
        let (nq, nv) = (model.ffi().nq as usize, model.ffi().nv as usize);
        for (name, &id) in joints.iter().zip(&joint_ids) {
            let one_dof = matches!(
                model.jnt_type()[id],
                mujoco_rs::wrappers::mj_model::MjtJoint::mjJNT_HINGE
                    | mujoco_rs::wrappers::mj_model::MjtJoint::mjJNT_SLIDE
            );
            let (qadr, dadr) = (
                model.jnt_qposadr()[id] as usize,
                model.jnt_dofadr()[id] as usize,
            );
            if !one_dof || qadr != id || dadr != id || id >= nq || id >= nv {
                return Err(Error::invalid_argument(
                    "actuation_part_names",
                    format!(
                        "the IK joint `{name}` (id {id}, qpos address {qadr}, dof address {dadr}) \
                         cannot be served: robosuite's IK indexes qpos and the Jacobian by joint \
                         id, which needs hinge or slide joints whose id equals both addresses \
                         (every joint before them with one dof)"
                    ),
                ));
            }
        }
        let n = joints.len();
        let torso: Vec<usize> = joints
            .iter()
            .zip(&joint_ids)
            .filter(|(name, _)| name.contains("torso"))
            .map(|(_, &id)| id)
            .collect();
        if let Some(&bad) = torso.iter().find(|&&id| id >= n) {
            return Err(Error::invalid_argument(
                "actuation_part_names",
                format!(
                    "robosuite limits the IK step's entries at the torso joints' model ids \
                     (here {torso:?}), which must be below the number of IK joints ({n}); \
                     id {bad} is not (robosuite fails with an IndexError)"
                ),
            ));
        }
        let frame_body = match settings.input_ref_frame.body() {
            None => None,
            Some(body) => Some(crate::sim::body_id(model, body)?),
        };
        let ranges = joint_ids.iter().map(|&j| model.jnt_range()[j]).collect();
        let k = site_ids.len();
        Ok(Self {
            site_names: sites.iter().map(|s| (*s).to_owned()).collect(),
            sites: site_ids,
            joint_names: joints.iter().map(|s| (*s).to_owned()).collect(),
            joints: joint_ids,
            kn: nullspace_gains.to_vec(),
            ranges,
            torso,
            frame_body,
            jacp: vec![0.0; 3 * nv],
            jacr: vec![0.0; 3 * nv],
            jac: DMatrix::zeros(6 * k, n),
            target_pos: vec![[0.0; 3]; k],
            target_quat: vec![[0.0; 4]; k],
            null_in: vec![0.0; n],
            dq: vec![0.0; n],
            q_des: vec![0.0; n],
            settings,
        })
    }

    /// The length of the solver's action: per site 3 position values and 3 (axis-angle) or
    /// 4 (quaternion) rotation values (robosuite's `control_dim`).
    pub fn control_dim(&self) -> usize {
        self.sites.len() * (3 + self.settings.input_rotation_repr.dim())
    }

    /// The reference sites.
    pub fn site_names(&self) -> &[String] {
        &self.site_names
    }

    /// The IK joints, in the step's order.
    pub fn joint_names(&self) -> &[String] {
        &self.joint_names
    }

    /// The nullspace gains, one per IK joint.
    pub fn nullspace_gains(&self) -> &[f64] {
        &self.kn
    }

    /// The settings.
    pub fn settings(&self) -> &IkSettings {
        &self.settings
    }

    /// robosuite's `action_split_indexes`: each site's slice of the action, named `"left"`
    /// when the site's name contains `left` and `"right"` otherwise (a later site of the
    /// same name replaces the earlier one's slice, as in robosuite's dict).
    pub fn action_split_indexes(&self) -> Vec<(String, Range<usize>)> {
        let per = 3 + self.settings.input_rotation_repr.dim();
        let mut out: Vec<(String, Range<usize>)> = Vec::new();
        for (i, site) in self.site_names.iter().enumerate() {
            let name = if site.contains("left") {
                "left"
            } else {
                "right"
            };
            let range = i * per..(i + 1) * per;
            match out.iter_mut().find(|(n, _)| n == name) {
                Some((_, r)) => *r = range,
                None => out.push((name.to_owned(), range)),
            }
        }
        out
    }

    /// The joint step `q̇` of the last solve.
    pub fn dq(&self) -> &[f64] {
        &self.dq
    }

    /// The joint targets of the last solve.
    pub fn q_des(&self) -> &[f64] {
        &self.q_des
    }

    /// One IK step toward the targets in `action` ([`IkSolver::control_dim`] values) from the
    /// simulator's current (forwarded) state; returns the joint targets. Nothing in the
    /// simulator changes.
    ///
    /// # Errors
    /// [`Error::InvalidAction`] for an action of the wrong length or with a non-finite value,
    /// or a target so far that the step overflows; the solver's last result is then kept.
    pub fn solve(&mut self, sim: &Sim, action: &[f64]) -> Result<&[f64]> {
        let dim = self.control_dim();
        if action.len() != dim {
            return Err(Error::invalid_action(format!(
                "the IK takes {dim} values ({} sites × position and {:?} rotation), got {}",
                self.sites.len(),
                self.settings.input_rotation_repr,
                action.len()
            )));
        }
        if let Some(i) = action.iter().position(|v| !v.is_finite()) {
            return Err(Error::invalid_action(format!(
                "IK target value {i} is {} (targets must be finite)",
                action[i]
            )));
        }
        let d = sim.data();
        let model = sim.model();
        let per = 3 + self.settings.input_rotation_repr.dim();
        for (i, &site) in self.sites.iter().enumerate() {
            let a = &action[i * per..(i + 1) * per];
            let mut pos = [a[0], a[1], a[2]];
            let mut quat = match self.settings.input_rotation_repr {
                IkRotationRepr::AxisAngle => {
                    let q = axisangle2quat(&Vector3::new(a[3], a[4], a[5]));
                    [q[3], q[0], q[1], q[2]]
                }
                IkRotationRepr::QuatWxyz => [a[3], a[4], a[5], a[6]],
            };
            let cur_pos = d.site_xpos()[site];
            let cur_mat = d.site_xmat()[site];
            match self.settings.input_action_repr {
                IkActionRepr::Absolute => {}
                IkActionRepr::Relative => {
                    for k in 0..3 {
                        pos[k] += cur_pos[k];
                    }
                    let cur = robosuite_mat2quat(&Matrix3::from_row_slice(&cur_mat));
                    let q = quat_multiply_f32(cur, [quat[1], quat[2], quat[3], quat[0]]);
                    quat = [q[3], q[0], q[1], q[2]];
                }
                IkActionRepr::RelativePose => {
                    let cur = pose(cur_pos, &Matrix3::from_row_slice(&cur_mat));
                    // robosuite hands the wxyz quaternion to quat2mat, which reads xyzw.
                    let rel = pose(pos, &quat2mat_f32(quat));
                    let new = cur * rel;
                    pos = [new[(0, 3)], new[(1, 3)], new[(2, 3)]];
                    let q = robosuite_mat2quat(&new.fixed_view::<3, 3>(0, 0).into_owned());
                    quat = [q[3], q[0], q[1], q[2]];
                }
            }
            if let Some(body) = self.frame_body {
                let frame = pose(
                    model.body_pos()[body],
                    &quat2mat_f32(xyzw(model.body_quat()[body])),
                );
                let goal = frame * pose(pos, &quat2mat_f32(xyzw(quat)));
                pos = [goal[(0, 3)], goal[(1, 3)], goal[(2, 3)]];
                let q = robosuite_mat2quat(&goal.fixed_view::<3, 3>(0, 0).into_owned());
                quat = [q[3], q[0], q[1], q[2]];
            }
            self.target_pos[i] = pos;
            self.target_quat[i] = quat;
        }

        // The task Jacobian over the IK joints (robosuite: `jac[:, dof_ids]`).
        let k = self.sites.len();
        let m = 6 * k;
        let n = self.joints.len();
        for (i, &site) in self.sites.iter().enumerate() {
            d.jac_site_into(site, Some(&mut self.jacp), Some(&mut self.jacr));
            let nv = self.jacp.len() / 3;
            for r in 0..3 {
                for (c, &j) in self.joints.iter().enumerate() {
                    self.jac[(6 * i + r, c)] = self.jacp[r * nv + j];
                    self.jac[(6 * i + 3 + r, c)] = self.jacr[r * nv + j];
                }
            }
        }
        let dt = self.settings.integration_dt;
        let mut twist = Column::zeros();
        for (i, &site) in self.sites.iter().enumerate() {
            let p = d.site_xpos()[site];
            for r in 0..3 {
                twist[6 * i + r] = K_TWIST * (self.target_pos[i][r] - p[r]) / dt;
            }
            let site_quat = mju::mat2quat(&d.site_xmat()[site]);
            let err = mju::mul_quat(&self.target_quat[i], &mju::neg_quat(&site_quat));
            let vel = mju::quat2vel(&err, 1.0);
            let gain = K_TWIST / dt;
            for r in 0..3 {
                twist[6 * i + 3 + r] = vel[r] * gain;
            }
        }
        // JJᵀ, zero outside its m × m block.
        let mut jjt = Square::zeros();
        for r in 0..m {
            for c in 0..=r {
                let mut s = 0.0;
                for j in 0..n {
                    s += self.jac[(r, j)] * self.jac[(c, j)];
                }
                jjt[(r, c)] = s;
                jjt[(c, r)] = s;
            }
        }
        // (JJᵀ + λ²I)⁻¹ twist, the padding an identity block.
        let lambda_sq = self.settings.damping * self.settings.damping;
        let mut damped = jjt;
        for r in 0..MAX_ROWS {
            damped[(r, r)] += if r < m { lambda_sq } else { 1.0 };
        }
        let y = damped.lu().solve(&twist).unwrap_or_else(Column::zeros);
        // The nullspace term: x − J⁺(J x) = x − Jᵀ(JJᵀ)⁺(J x), x = Kn∘(0 − q).
        let qpos = d.qpos();
        let mut jx = Column::zeros();
        for (c, &j) in self.joints.iter().enumerate() {
            self.null_in[c] = self.kn[c] * (0.0 - qpos[j]);
        }
        for r in 0..m {
            let mut s = 0.0;
            for c in 0..n {
                s += self.jac[(r, c)] * self.null_in[c];
            }
            jx[r] = s;
        }
        let z = psd_pinv_apply(&jjt, m, &jx);
        for c in 0..n {
            let mut task = 0.0;
            let mut back = 0.0;
            for r in 0..m {
                task += self.jac[(r, c)] * y[r];
                back += self.jac[(r, c)] * z[r];
            }
            self.dq[c] = task + (self.null_in[c] - back);
        }
        // Step limits, then the torso's (at the torso joints' ids, as robosuite).
        let max_dq = self.settings.max_dq;
        if max_dq > 0.0 {
            let peak = self.dq.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if peak > max_dq {
                let s = max_dq / peak;
                self.dq.iter_mut().for_each(|v| *v *= s);
            }
        }
        let max_torso = self.settings.max_dq_torso;
        if !self.torso.is_empty() && max_torso > 0.0 {
            let peak = self
                .torso
                .iter()
                .fold(0.0f64, |a, &i| a.max(self.dq[i].abs()));
            if peak > max_torso {
                let s = max_torso / peak;
                for &i in &self.torso {
                    self.dq[i] *= s;
                }
            }
        }
        if let Some(i) = self.dq.iter().position(|v| !v.is_finite()) {
            return Err(Error::invalid_action(format!(
                "the IK step of joint `{}` is not finite: a target too far to compute with",
                self.joint_names[i]
            )));
        }
        for (c, &j) in self.joints.iter().enumerate() {
            let [lo, hi] = self.ranges[c];
            self.q_des[c] = (qpos[j] + self.dq[c] * dt).max(lo).min(hi);
        }
        Ok(&self.q_des)
    }
}

/// `w, x, y, z` → `x, y, z, w`.
fn xyzw(q: [f64; 4]) -> [f64; 4] {
    [q[1], q[2], q[3], q[0]]
}

/// robosuite's `T.make_pose(p, R)` (float64).
fn pose(p: [f64; 3], r: &Matrix3<f64>) -> Matrix4<f64> {
    let mut out = Matrix4::identity();
    out.fixed_view_mut::<3, 3>(0, 0).copy_from(r);
    for k in 0..3 {
        out[(k, 3)] = p[k];
    }
    out
}

/// robosuite's `T.mat2quat` (`x, y, z, w`): float32, `w >= 0`. robosuite takes the
/// eigenvector of a float32 matrix (`numpy.linalg.eigh`); this is the float64 quaternion
/// rounded to float32, equal to it within float32 rounding.
fn robosuite_mat2quat(m: &Matrix3<f64>) -> [f64; 4] {
    let m32 = m.map(|v| f64::from(v as f32));
    mat2quat(&m32).map(|v| f64::from(v as f32))
}

/// `A⁺ b` for a symmetric positive semi-definite `A` stored in the top-left `m × m` block
/// (zero elsewhere), `b` zero past `m`: a Cholesky solve when the block is well conditioned
/// (pivots within 10 orders of magnitude), else its SVD pseudo-inverse with NumPy's cutoff.
/// No heap allocation.
fn psd_pinv_apply(a: &Square, m: usize, b: &Column) -> Column {
    let mut padded = *a;
    for r in m..MAX_ROWS {
        padded[(r, r)] = 1.0;
    }
    if let Some(chol) = padded.cholesky() {
        let l = chol.l_dirty();
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for i in 0..m {
            let d = l[(i, i)] * l[(i, i)];
            lo = lo.min(d);
            hi = hi.max(d);
        }
        if lo.is_finite() && lo > 1e-10 * hi {
            return chol.solve(b);
        }
    }
    let svd = a.svd(true, true);
    let (Some(u), Some(v_t)) = (svd.u, svd.v_t) else {
        return Column::zeros();
    };
    let cutoff = PINV_RCOND * svd.singular_values.max();
    let mut out = Column::zeros();
    for k in 0..MAX_ROWS {
        let s = svd.singular_values[k];
        if s > cutoff {
            let coef = u.column(k).dot(b) / s;
            out += v_t.row(k).transpose() * coef;
        }
    }
    out
}

/// How a body part enters `WHOLE_BODY_IK`'s action.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PartKind {
    /// An arm: outside the IK its slice is bounded by its controller's limits.
    Arm,
    /// A gripper or hand: `dof` values in `[-1, 1]`.
    Gripper,
    /// Torso, head, legs, base: outside the IK its slice is in `[-1, 1]`.
    Other,
}

/// A body part and its controller as `WHOLE_BODY_IK` sees them (robosuite's part
/// controller: `joint_names`, `control_dim`, `control_limits`; a gripper's `dof`).
#[derive(Debug, Clone, PartialEq)]
pub struct WholeBodyPart {
    /// robosuite's part name (`"right"`, `"torso"`, `"right_gripper"`, ...).
    pub name: String,
    /// Its controller's joints (model joint names).
    pub joints: Vec<String>,
    /// Its controller's action length (a gripper's: its `dof`).
    pub action_dim: usize,
    /// What kind of part it is.
    pub kind: PartKind,
    /// Its controller's action bounds (`control_limits`), `action_dim` values each.
    pub limits: (Vec<f64>, Vec<f64>),
}

/// robosuite's `WHOLE_BODY_IK` composite controller: the action layout and limits, and
/// the conversion of an env action into the parts' actions (robosuite's `set_goal` before
/// each part controller's own `set_goal`).
///
/// The parts' actions are laid out as robosuite's `_action_split_indexes`
/// ([`WholeBodyIk::part_split`]): the actuated parts first, in `actuation_part_names`'
/// order, each taking its joints' targets, then the other parts in the parts' order.
#[derive(Debug, Clone)]
pub struct WholeBodyIk {
    config: WholeBodyIkConfig,
    solver: IkSolver,
    parts: Vec<WholeBodyPart>,
    part_split: Vec<(String, Range<usize>)>,
    action_split: Vec<(String, Range<usize>)>,
    low: Vec<f64>,
    high: Vec<f64>,
    dropped_parts: Vec<String>,
    dropped_ref_names: Vec<String>,
    ik_joints: usize,
}

impl WholeBodyIk {
    /// The controller for `config` over `parts` (in the robot's part order; reordered by
    /// `body_part_ordering` when the config has one) on `model`.
    ///
    /// As robosuite: an actuated part the robot lacks and a reference site the model lacks
    /// are dropped ([`WholeBodyIk::dropped_parts`], [`WholeBodyIk::dropped_ref_names`]).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the key for a `body_part_ordering` that is not an
    /// order of the parts, no reference site left (robosuite fails on it), an actuated part
    /// whose action length differs from its number of joints, or parts of the same name;
    /// otherwise as [`IkSolver::new`].
    pub fn new(
        model: &MjModel,
        config: &WholeBodyIkConfig,
        parts: &[WholeBodyPart],
    ) -> Result<Self> {
        let path = "composite_controller_specific_configs";
        config.check(path)?;
        for (i, p) in parts.iter().enumerate() {
            if parts[..i].iter().any(|q| q.name == p.name) {
                return Err(Error::invalid_argument(
                    "body_parts",
                    format!("the part `{}` is given twice", p.name),
                ));
            }
            if p.limits.0.len() != p.action_dim || p.limits.1.len() != p.action_dim {
                return Err(Error::invalid_argument(
                    join("body_parts", &p.name),
                    format!("needs {} action bounds each side", p.action_dim),
                ));
            }
        }
        let names: Vec<&str> = parts.iter().map(|p| p.name.as_str()).collect();
        let parts: Vec<WholeBodyPart> = match &config.body_part_ordering {
            None => parts.to_vec(),
            Some(order) => {
                let mut sorted = order.clone();
                sorted.sort();
                let mut have: Vec<String> = names.iter().map(|s| (*s).to_owned()).collect();
                have.sort();
                if sorted != have {
                    return Err(Error::invalid_argument(
                        join(path, "body_part_ordering"),
                        format!(
                            "must order exactly the robot's parts: {}; got {}",
                            names.join(", "),
                            order.join(", ")
                        ),
                    ));
                }
                order
                    .iter()
                    .map(|n| parts.iter().find(|p| &p.name == n).cloned())
                    .collect::<Option<Vec<_>>>()
                    .unwrap_or_default()
            }
        };
        let (actuated, dropped_parts): (Vec<String>, Vec<String>) = config
            .actuation_part_names
            .iter()
            .cloned()
            .partition(|n| parts.iter().any(|p| &p.name == n));
        let (ref_names, dropped_ref_names): (Vec<String>, Vec<String>) =
            config.ref_name.iter().cloned().partition(|s| {
                !s.contains('\0') && model.name_to_id(mjtObj::mjOBJ_SITE, s).is_some()
            });
        if ref_names.is_empty() {
            return Err(Error::invalid_argument(
                join(path, "ref_name"),
                format!(
                    "none of the reference sites {:?} is in the model; the robot's grip sites: {}",
                    config.ref_name,
                    grip_sites(model).join(", ")
                ),
            ));
        }
        let mut joints: Vec<&str> = Vec::new();
        for name in &actuated {
            let part = parts.iter().find(|p| &p.name == name).expect("kept above");
            if part.action_dim != part.joints.len() {
                return Err(Error::invalid_argument(
                    join(path, "actuation_part_names"),
                    format!(
                        "the part `{name}` takes {} action values for {} joints; the IK gives \
                         one target per joint",
                        part.action_dim,
                        part.joints.len()
                    ),
                ));
            }
            joints.extend(part.joints.iter().map(String::as_str));
        }
        let gains: Vec<f64> = joints
            .iter()
            .map(|j| {
                config
                    .nullspace_joint_weights
                    .get(*j)
                    .copied()
                    .unwrap_or(1.0)
            })
            .collect();
        let sites: Vec<&str> = ref_names.iter().map(String::as_str).collect();
        let solver = IkSolver::new(model, &sites, &joints, &gains, IkSettings::from(config))?;

        // robosuite's `_action_split_indexes`: actuated parts, then the others.
        let mut part_split = Vec::new();
        let mut at = 0;
        for name in &actuated {
            let part = parts.iter().find(|p| &p.name == name).expect("kept above");
            part_split.push((name.clone(), at..at + part.action_dim));
            at += part.action_dim;
        }
        for p in parts.iter().filter(|p| !actuated.contains(&p.name)) {
            part_split.push((p.name.clone(), at..at + p.action_dim));
            at += p.action_dim;
        }
        let ik_joints = joints.len();
        let mut config = config.clone();
        config.ref_name = ref_names;
        config.actuation_part_names = actuated;
        let (action_split, low, high) = if config.skip_wbc_action {
            // BASIC's limits, in the parts' order (robosuite's, though its split puts the
            // actuated parts first).
            let (mut low, mut high) = (Vec::new(), Vec::new());
            for p in &parts {
                push_limits(p, &mut low, &mut high);
            }
            (part_split.clone(), low, high)
        } else {
            let mut split = solver.action_split_indexes();
            let dim = solver.control_dim();
            let mut low = vec![f64::NEG_INFINITY; dim];
            let mut high = vec![f64::INFINITY; dim];
            let mut at = dim;
            for p in parts
                .iter()
                .filter(|p| !config.actuation_part_names.contains(&p.name))
            {
                match split.iter_mut().find(|(n, _)| n == &p.name) {
                    Some((_, r)) => *r = at..at + p.action_dim,
                    None => split.push((p.name.clone(), at..at + p.action_dim)),
                }
                at += p.action_dim;
                push_limits(p, &mut low, &mut high);
            }
            (split, low, high)
        };
        Ok(Self {
            config,
            solver,
            parts,
            part_split,
            action_split,
            low,
            high,
            dropped_parts,
            dropped_ref_names,
            ik_joints,
        })
    }

    /// The config in use: reference sites and actuated parts as robosuite keeps them.
    pub fn config(&self) -> &WholeBodyIkConfig {
        &self.config
    }

    /// The IK solver.
    pub fn solver(&self) -> &IkSolver {
        &self.solver
    }

    /// The body parts, in their order.
    pub fn parts(&self) -> &[WholeBodyPart] {
        &self.parts
    }

    /// The env action's length.
    pub fn action_dim(&self) -> usize {
        self.low.len()
    }

    /// The env action's bounds (robosuite's `action_limits`): unbounded for the poses, a
    /// gripper's `[-1, 1]`, an arm outside the IK its controller's limits, other parts
    /// `[-1, 1]`.
    pub fn action_limits(&self) -> (&[f64], &[f64]) {
        (&self.low, &self.high)
    }

    /// The env action's slices by name (robosuite's
    /// `_whole_body_controller_action_split_indexes`): `"right"` / `"left"` for the poses,
    /// then the parts outside the IK.
    pub fn action_split(&self) -> &[(String, Range<usize>)] {
        &self.action_split
    }

    /// The parts' actions' slices (robosuite's `_action_split_indexes`).
    pub fn part_split(&self) -> &[(String, Range<usize>)] {
        &self.part_split
    }

    /// The length of the parts' actions.
    pub fn part_actions_dim(&self) -> usize {
        self.part_split.last().map_or(0, |(_, r)| r.end)
    }

    /// The actuated parts the config names that the robot lacks (robosuite drops them with
    /// a warning).
    pub fn dropped_parts(&self) -> &[String] {
        &self.dropped_parts
    }

    /// The reference sites the config names that the model lacks (robosuite drops them with
    /// a warning).
    pub fn dropped_ref_names(&self) -> &[String] {
        &self.dropped_ref_names
    }

    /// robosuite's `set_goal` up to the parts: writes the parts' actions for env action
    /// `action` into `part_actions` (laid out as [`WholeBodyIk::part_split`]): the IK's joint
    /// targets for the actuated parts, the rest of the action as it is. With
    /// `skip_wbc_action` the action is the parts' actions. Does not allocate.
    ///
    /// # Errors
    /// [`Error::InvalidAction`] for an action of the wrong length or with a non-finite value
    /// (as [`IkSolver::solve`]); `part_actions` is then unchanged.
    ///
    /// # Panics
    /// When `part_actions` does not hold [`WholeBodyIk::part_actions_dim`] values.
    pub fn set_goal(&mut self, sim: &Sim, action: &[f64], part_actions: &mut [f64]) -> Result<()> {
        assert_eq!(part_actions.len(), self.part_actions_dim());
        if action.len() != self.action_dim() {
            return Err(Error::invalid_action(format!(
                "WHOLE_BODY_IK takes {} action values, got {}",
                self.action_dim(),
                action.len()
            )));
        }
        if let Some(i) = action.iter().position(|v| !v.is_finite()) {
            return Err(Error::invalid_action(format!(
                "action value {i} is {} (actions must be finite)",
                action[i]
            )));
        }
        if self.config.skip_wbc_action {
            part_actions.copy_from_slice(action);
            return Ok(());
        }
        let dim = self.solver.control_dim();
        let q_des = self.solver.solve(sim, &action[..dim])?;
        part_actions[..self.ik_joints].copy_from_slice(q_des);
        part_actions[self.ik_joints..].copy_from_slice(&action[dim..]);
        Ok(())
    }
}

impl WholeBodyIk {
    /// The parts' actions that hold the IK joints where they are (their positions, clipped
    /// to their ranges), the rest of `action` as [`WholeBodyIk::set_goal`] passes it on
    /// (finite values only; others become 0).
    ///
    /// # Panics
    /// When `part_actions` does not hold [`WholeBodyIk::part_actions_dim`] values.
    pub fn hold(&self, sim: &Sim, action: &[f64], part_actions: &mut [f64]) {
        assert_eq!(part_actions.len(), self.part_actions_dim());
        let qpos = sim.data().qpos();
        let n = self.ik_joints;
        for (c, &j) in self.solver.joints.iter().enumerate() {
            let [lo, hi] = self.solver.ranges[c];
            part_actions[c] = qpos[j].max(lo).min(hi);
        }
        let start = if self.config.skip_wbc_action {
            0
        } else {
            self.solver.control_dim()
        };
        let rest = if self.config.skip_wbc_action { 0 } else { n };
        for (out, a) in part_actions[rest..]
            .iter_mut()
            .zip(action.iter().skip(start))
        {
            *out = if a.is_finite() { *a } else { 0.0 };
        }
    }
}

fn push_limits(p: &WholeBodyPart, low: &mut Vec<f64>, high: &mut Vec<f64>) {
    match p.kind {
        PartKind::Arm => {
            low.extend_from_slice(&p.limits.0);
            high.extend_from_slice(&p.limits.1);
        }
        PartKind::Gripper | PartKind::Other => {
            low.extend(std::iter::repeat_n(-1.0, p.action_dim));
            high.extend(std::iter::repeat_n(1.0, p.action_dim));
        }
    }
}

/// The model's sites whose name ends in `grip_site` (for error messages).
fn grip_sites(model: &MjModel) -> Vec<String> {
    (0..model.ffi().nsite as usize)
        .filter_map(|i| model.id_to_name(mjtObj::mjOBJ_SITE, i))
        .filter(|n| n.ends_with("grip_site"))
        .map(str::to_owned)
        .collect()
}

/// robosuite's `WHOLE_BODY_IK` as a robot's composite controller (the table entry of
/// [`COMPOSITE_CONTROLLERS`](crate::robots::composite::COMPOSITE_CONTROLLERS)): the robot's
/// action is [`WholeBodyIk`]'s, its layout ([`CompositeController::layout`], robosuite's
/// `_action_split_indexes`) the parts' actions. The parts are the config's body parts in
/// its order, then the arms' grippers.
///
/// Should a target be so far (beyond about 1e307) that the IK step overflows, the IK
/// joints hold their positions for that step.
#[derive(Debug, Clone)]
pub struct WholeBodyIkComposite {
    config: WholeBodyIkConfig,
    inner: Option<WholeBodyIk>,
    part_actions: Vec<f64>,
}

impl WholeBodyIkComposite {
    /// The controller for `config`, to be bound to a robot
    /// ([`CompositeController::bind`]).
    pub fn new(config: WholeBodyIkConfig) -> Self {
        Self {
            config,
            inner: None,
            part_actions: Vec::new(),
        }
    }

    /// The bound controller (`None` before [`CompositeController::bind`]).
    pub fn whole_body_ik(&self) -> Option<&WholeBodyIk> {
        self.inner.as_ref()
    }
}

impl CompositeController for WholeBodyIkComposite {
    fn name(&self) -> &'static str {
        "WHOLE_BODY_IK"
    }

    fn bind(&mut self, model: &MjModel, parts: &CompositeParts<'_>) -> Result<()> {
        let mut list = Vec::new();
        for name in parts.order {
            if let Some(arm) = parts.arms.iter().find(|a| a.side() == name) {
                let (low, high) = arm.controller().action_limits();
                list.push(WholeBodyPart {
                    name: name.clone(),
                    joints: parts.joints[arm.joints()].to_vec(),
                    action_dim: arm.controller().action_dim(),
                    kind: PartKind::Arm,
                    limits: (low, high),
                });
            } else if let Some(body) = parts.bodies.iter().find(|b| b.name() == name) {
                let (low, high) = body.controller().action_limits();
                list.push(WholeBodyPart {
                    name: name.clone(),
                    joints: body.joint_names().to_vec(),
                    action_dim: body.controller().action_dim(),
                    kind: PartKind::Other,
                    limits: (low, high),
                });
            }
        }
        for arm in parts.arms.iter().filter(|a| a.gripper().has_gripper()) {
            let n = arm.gripper().action_dim();
            list.push(WholeBodyPart {
                name: format!("{}_gripper", arm.side()),
                joints: Vec::new(),
                action_dim: n,
                kind: PartKind::Gripper,
                limits: (vec![-1.0; n], vec![1.0; n]),
            });
        }
        let inner = WholeBodyIk::new(model, &self.config, &list)?;
        self.part_actions = vec![0.0; inner.part_actions_dim()];
        self.inner = Some(inner);
        Ok(())
    }

    fn layout(&self, _order: &[String], arms: &[Arm], bodies: &[BodyPart]) -> Vec<ActionSlot> {
        let Some(inner) = &self.inner else {
            return Vec::new();
        };
        inner
            .part_split()
            .iter()
            .filter_map(|(name, range)| {
                let part = if let Some(i) = arms.iter().position(|a| a.side() == name) {
                    PartRef::Arm(i)
                } else if let Some(i) = bodies.iter().position(|b| b.name() == name) {
                    PartRef::Body(i)
                } else {
                    let side = name.strip_suffix("_gripper")?;
                    PartRef::Gripper(arms.iter().position(|a| a.side() == side)?)
                };
                Some(ActionSlot {
                    name: name.clone(),
                    part,
                    range: range.clone(),
                })
            })
            .collect()
    }

    fn action_limits(&self) -> Option<(Vec<f64>, Vec<f64>)> {
        self.inner.as_ref().map(|w| {
            let (low, high) = w.action_limits();
            (low.to_vec(), high.to_vec())
        })
    }

    fn action_split(&self) -> Option<Vec<(String, Range<usize>)>> {
        self.inner.as_ref().map(|w| w.action_split().to_vec())
    }

    fn set_goal(&mut self, sim: &Sim, parts: PartsMut<'_>, layout: &[ActionSlot], action: &[f64]) {
        let Some(inner) = &mut self.inner else {
            return;
        };
        if inner.set_goal(sim, action, &mut self.part_actions).is_err() {
            inner.hold(sim, action, &mut self.part_actions);
        }
        basic_set_goal(sim, parts, layout, &self.part_actions);
    }

    fn clone_box(&self) -> Box<dyn CompositeController> {
        Box::new(self.clone())
    }
}
