//! robosuite's composite controllers (`controllers/composite/composite_controller.py`):
//! what splits a robot's action among its part controllers. One table,
//! [`COMPOSITE_CONTROLLERS`], lists robosuite's composite types; an entry says which robots
//! it drives and builds its [`CompositeController`].
//!
//! Adding a composite type takes a [`CompositeController`] implementation and its entry:
//! `layout` (the action's slices, robosuite's `_action_split_indexes`; the default is
//! `BASIC`'s), `extra_limits` (entries after the slices, such as `HYBRID_MOBILE_BASE`'s
//! base mode) and `set_goal` (how the action reaches the part controllers; the default
//! hands each slice to its part, [`basic_set_goal`]).

use super::robot::{Arm, BodyPart};
use crate::controllers::config::CompositeControllerConfig;
use crate::controllers::whole_body_ik::{WholeBodyIkComposite, WholeBodyIkConfig};
use crate::models::robots::RobotKind;
use crate::sim::Sim;
use gym_core::{Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use serde_json::{Map, Value};
use std::ops::Range;

/// What a slice of a robot's action drives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PartRef {
    /// The controller of arm `i` (in the robot's arm order).
    Arm(usize),
    /// The gripper of arm `i`.
    Gripper(usize),
    /// Body part `i` other than an arm (torso, head, base, legs; see [`BodyPart`]).
    Body(usize),
}

/// One slice of a robot's action: robosuite's `_action_split_indexes` entry.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ActionSlot {
    /// robosuite's part name (`"right"`, `"right_gripper"`, `"torso"`, `"base"`, ...).
    pub name: String,
    /// The part it drives.
    pub part: PartRef,
    /// Its indices in the robot's action.
    pub range: Range<usize>,
}

/// A robot's parts as [`CompositeController::bind`] sees them.
#[derive(Debug, Clone, Copy)]
pub struct CompositeParts<'a> {
    /// The body parts in the config's order (arm sides and other part names).
    pub order: &'a [String],
    /// The arms, with their controllers and grippers.
    pub arms: &'a [Arm],
    /// The other body parts.
    pub bodies: &'a [BodyPart],
    /// The robot's joints (robosuite's `robot_model.joints`), which [`Arm::joints`]
    /// indexes.
    pub joints: &'a [String],
}

/// The parts a composite controller drives.
#[derive(Debug)]
pub struct PartsMut<'a> {
    /// The arms, with their controllers and grippers.
    pub arms: &'a mut [Arm],
    /// The other body parts.
    pub bodies: &'a mut [BodyPart],
}

/// A robosuite composite controller: how a robot's action is split among its part
/// controllers.
pub trait CompositeController: Send + Sync + std::fmt::Debug {
    /// robosuite's composite type, such as `"BASIC"`.
    fn name(&self) -> &'static str;

    /// The action's slices for the parts, given the body parts in the config's order
    /// (`order`, arm sides and other part names); robosuite's `setup_action_split_idx`.
    /// The default is `BASIC`'s: each part in the config's order, then each arm's gripper.
    fn layout(&self, order: &[String], arms: &[Arm], bodies: &[BodyPart]) -> Vec<ActionSlot> {
        basic_layout(order, arms, bodies)
    }

    /// Bounds of the entries after the parts' slices (none by default).
    fn extra_limits(&self) -> (Vec<f64>, Vec<f64>) {
        (Vec::new(), Vec::new())
    }

    /// Binds the controller to the compiled model and the robot's parts, before the
    /// layout is asked for (`WHOLE_BODY_IK` builds its IK solver here). The default does
    /// nothing.
    ///
    /// # Errors
    /// [`Error::Model`] or [`Error::InvalidArgument`] when the config does not fit the
    /// robot or the model.
    fn bind(&mut self, model: &MjModel, parts: &CompositeParts<'_>) -> Result<()> {
        let _ = (model, parts);
        Ok(())
    }

    /// The bounds of the whole action, for a controller whose action is not the parts'
    /// slices (`WHOLE_BODY_IK`: end-effector poses first); `None` (the default) for the
    /// layout's bounds followed by [`CompositeController::extra_limits`].
    fn action_limits(&self) -> Option<(Vec<f64>, Vec<f64>)> {
        None
    }

    /// The whole action's slices by part name when they differ from the layout's
    /// (`WHOLE_BODY_IK`: robosuite's `_whole_body_controller_action_split_indexes`, which
    /// its `create_action_vector` uses); `None` (the default) otherwise.
    fn action_split(&self) -> Option<Vec<(String, Range<usize>)>> {
        None
    }

    /// Sets the parts' goals from the robot's action (first substep of an env step; the
    /// action has the layout's length plus the extra entries, all finite).
    fn set_goal(&mut self, sim: &Sim, parts: PartsMut<'_>, layout: &[ActionSlot], action: &[f64]) {
        basic_set_goal(sim, parts, layout, action);
    }

    /// A boxed copy.
    fn clone_box(&self) -> Box<dyn CompositeController>;
}

impl Clone for Box<dyn CompositeController> {
    fn clone(&self) -> Self {
        self.clone_box()
    }
}

/// `BASIC`'s layout: each part of `order` (arms by side, other parts by name) with its
/// controller's action dimension, then each arm's gripper (in the robot's arm order, none
/// for an arm without a gripper).
pub fn basic_layout(order: &[String], arms: &[Arm], bodies: &[BodyPart]) -> Vec<ActionSlot> {
    let mut out = Vec::new();
    let mut at = 0;
    let mut push = |name: String, part, n: usize, out: &mut Vec<ActionSlot>| {
        out.push(ActionSlot {
            name,
            part,
            range: at..at + n,
        });
        at += n;
    };
    for name in order {
        if let Some(i) = arms.iter().position(|a| a.side() == name) {
            push(
                name.clone(),
                PartRef::Arm(i),
                arms[i].controller().action_dim(),
                &mut out,
            );
        } else if let Some(i) = bodies.iter().position(|b| b.name() == name) {
            push(
                name.clone(),
                PartRef::Body(i),
                bodies[i].controller().action_dim(),
                &mut out,
            );
        }
    }
    for (i, arm) in arms.iter().enumerate() {
        if arm.gripper().has_gripper() {
            push(
                format!("{}_gripper", arm.side()),
                PartRef::Gripper(i),
                arm.gripper().action_dim(),
                &mut out,
            );
        }
    }
    out
}

/// `BASIC`'s goal setting: each slot's slice of `action` to its part's controller.
pub fn basic_set_goal(sim: &Sim, parts: PartsMut<'_>, layout: &[ActionSlot], action: &[f64]) {
    for slot in layout {
        let a = &action[slot.range.clone()];
        match slot.part {
            PartRef::Arm(i) => parts.arms[i].controller_mut().set_goal(sim, a),
            PartRef::Gripper(i) => parts.arms[i].gripper_mut().set_goal(a),
            PartRef::Body(i) => parts.bodies[i].controller_mut().set_goal(sim, a),
        }
    }
}

/// robosuite's `BASIC` composite controller (`CompositeController`).
#[derive(Debug, Clone, Default)]
pub struct Basic;

impl CompositeController for Basic {
    fn name(&self) -> &'static str {
        "BASIC"
    }

    fn clone_box(&self) -> Box<dyn CompositeController> {
        Box::new(self.clone())
    }
}

/// robosuite's `HYBRID_MOBILE_BASE` (`HybridMobileBase`): `BASIC`'s layout plus one last
/// entry, the base mode; with a base mode above 0 the arms' delta goals apply to their
/// last goals ("desired"), else to the achieved poses ("achieved"), so the arms hold
/// their goals while the base moves.
#[derive(Debug, Clone, Default)]
pub struct HybridMobileBase;

impl CompositeController for HybridMobileBase {
    fn name(&self) -> &'static str {
        "HYBRID_MOBILE_BASE"
    }

    fn extra_limits(&self) -> (Vec<f64>, Vec<f64>) {
        (vec![-1.0], vec![1.0])
    }

    fn set_goal(&mut self, sim: &Sim, parts: PartsMut<'_>, layout: &[ActionSlot], action: &[f64]) {
        let desired = action.last().is_some_and(|&m| m > 0.0);
        for arm in parts.arms.iter_mut() {
            arm.controller_mut().set_goal_update_mode(desired);
        }
        basic_set_goal(sim, parts, layout, action);
    }

    fn clone_box(&self) -> Box<dyn CompositeController> {
        Box::new(self.clone())
    }
}

/// Builds a composite controller from its config (`path` names it in errors).
pub type CompositeBuildFn =
    fn(&CompositeControllerConfig, &str) -> Result<Box<dyn CompositeController>>;

/// One composite type of the table.
#[derive(Debug, Clone, Copy)]
pub struct CompositeEntry {
    /// robosuite's type name.
    pub name: &'static str,
    /// The robot classes it drives (robosuite's `FixedBaseRobot`, `WheeledRobot`,
    /// `LeggedRobot`).
    pub robot_kinds: &'static [RobotKind],
    /// Checks `composite_controller_specific_configs` (at the given path).
    pub check_specific: fn(&Map<String, Value>, &str) -> Result<()>,
    /// Builds the controller; `None` for a type robosuite-rs does not serve.
    pub build: Option<CompositeBuildFn>,
    /// Why the type is not served (shown in the [`Error::Unsupported`] error).
    pub unserved: &'static str,
}

const ALL_KINDS: &[RobotKind] = &[RobotKind::FixedBase, RobotKind::Wheeled, RobotKind::Legged];
const MOBILE_KINDS: &[RobotKind] = &[RobotKind::Wheeled, RobotKind::Legged];

/// `BASIC` and `HYBRID_MOBILE_BASE` read only `body_part_ordering`, which robosuite-rs
/// does not offer; the other keys (robosuite's own files carry IK settings there) are
/// ignored, as robosuite ignores them.
fn basic_specific(specific: &Map<String, Value>, path: &str) -> Result<()> {
    if specific.contains_key("body_part_ordering") {
        return Err(Error::invalid_argument(
            format!("{path}.body_part_ordering"),
            "robosuite-rs orders the action as the config's `body_parts` (then the grippers); \
             leave `body_part_ordering` out",
        ));
    }
    Ok(())
}

/// `WHOLE_BODY_IK` reads its IK settings ([`WholeBodyIkConfig`]).
fn whole_body_ik_specific(specific: &Map<String, Value>, path: &str) -> Result<()> {
    WholeBodyIkConfig::from_value(&Value::Object(specific.clone()), path).map(|_| ())
}

fn no_specific(_: &Map<String, Value>, _: &str) -> Result<()> {
    Ok(())
}

/// robosuite's composite controllers, in its registration order.
pub const COMPOSITE_CONTROLLERS: &[CompositeEntry] = &[
    CompositeEntry {
        name: "BASIC",
        robot_kinds: ALL_KINDS,
        check_specific: basic_specific,
        build: Some(|_, _| Ok(Box::new(Basic))),
        unserved: "",
    },
    CompositeEntry {
        name: "HYBRID_MOBILE_BASE",
        robot_kinds: MOBILE_KINDS,
        check_specific: basic_specific,
        build: Some(|_, _| Ok(Box::new(HybridMobileBase))),
        unserved: "",
    },
    CompositeEntry {
        name: "WHOLE_BODY_IK",
        robot_kinds: ALL_KINDS,
        check_specific: whole_body_ik_specific,
        build: Some(|config, path| {
            let at =
                crate::controllers::config::join(path, "composite_controller_specific_configs");
            let specific =
                WholeBodyIkConfig::from_value(&Value::Object(config.specific.clone()), &at)?;
            Ok(Box::new(WholeBodyIkComposite::new(specific)))
        }),
        unserved: "",
    },
    CompositeEntry {
        name: "WHOLE_BODY_MINK_IK",
        robot_kinds: ALL_KINDS,
        check_specific: no_specific,
        build: None,
        unserved: "robosuite's WHOLE_BODY_MINK_IK is an example built on the `mink` \
                   library (its own QP-based IK), which robosuite-rs does not serve; use \
                   WHOLE_BODY_IK or BASIC",
    },
];

/// The names of the composite types robosuite-rs serves.
pub fn served_composite_types() -> Vec<&'static str> {
    COMPOSITE_CONTROLLERS
        .iter()
        .filter(|e| e.build.is_some())
        .map(|e| e.name)
        .collect()
}

/// The table entry of composite type `kind`, which must be served (`path` names the
/// config's `type` in errors).
///
/// # Errors
/// [`Error::Unsupported`] for a robosuite type robosuite-rs does not serve;
/// [`Error::InvalidArgument`] for an unknown type, listing the valid ones.
pub fn composite_entry(kind: &str, path: &str) -> Result<&'static CompositeEntry> {
    match COMPOSITE_CONTROLLERS.iter().find(|e| e.name == kind) {
        Some(e) if e.build.is_some() => Ok(e),
        Some(e) => Err(Error::unsupported(format!(
            "{path}: the composite controller `{kind}`: {}; served: {}",
            e.unserved,
            served_composite_types().join(", ")
        ))),
        None => Err(Error::invalid_argument(
            path,
            format!(
                "unknown composite controller `{kind}`; valid: {}",
                served_composite_types().join(", ")
            ),
        )),
    }
}

/// Builds the composite controller of `config` for a robot of class `kind` (named
/// `robot`).
///
/// # Errors
/// [`Error::InvalidArgument`] naming `path.type` when the type does not drive this class
/// of robot (`HYBRID_MOBILE_BASE` on a fixed-base arm), listing the types that do; as
/// [`composite_entry`] otherwise.
pub fn build_composite(
    config: &CompositeControllerConfig,
    kind: RobotKind,
    robot: &str,
    path: &str,
) -> Result<Box<dyn CompositeController>> {
    let at = crate::controllers::config::join(path, "type");
    let entry = composite_entry(&config.kind, &at)?;
    if !entry.robot_kinds.contains(&kind) {
        let fits: Vec<&str> = COMPOSITE_CONTROLLERS
            .iter()
            .filter(|e| e.build.is_some() && e.robot_kinds.contains(&kind))
            .map(|e| e.name)
            .collect();
        return Err(Error::invalid_argument(
            at,
            format!(
                "`{}` does not drive {robot} (a {}); its composite controllers: {}",
                entry.name,
                kind.class_name(),
                fits.join(", ")
            ),
        ));
    }
    let build = entry
        .build
        .ok_or_else(|| Error::unsupported(entry.unserved))?;
    build(config, path)
}
