//! A robot bound to a compiled model: its joints, body parts (arms with their grippers or
//! hands, torso, head, base, legs), their part controllers, the composite controller that
//! splits the action among them, reset noise and proprioceptive observables (robosuite's
//! `Robot`, `FixedBaseRobot`, `WheeledRobot`, `LeggedRobot`).

use super::composite::{
    ActionSlot, CompositeController, CompositeParts, PartRef, PartsMut, build_composite,
};
use super::noise::InitNoise;
use crate::controllers::config::ArmControllerConfig;
use crate::controllers::config::join;
use crate::controllers::{
    ArmBinding, ArmController, CompositeControllerConfig, GripController, MobileBaseJointVelocity,
    Timing, build_arm_controller,
};
use crate::math::{mat_from_row_major, mat2quat, xyzw};
use crate::models::grippers::GripperInfo;
use crate::models::robots::{RobotKind, RobotModel, body_part_of};
use crate::observables::{Modality, ObsSpec, Observable, observe_all, specs};
use crate::sim::{GeomSet, Sim, actuator_id, body_id, geom_id, joint_id, site_id};
use gym_core::{DType, EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use std::ops::Range;

/// The controller state of a robot, for snapshots: per arm, the arm controller's state and
/// the gripper command; per other body part, its controller's state.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RobotState {
    /// Per arm: the arm controller's [`ArmController::state`].
    pub arms: Vec<Vec<f64>>,
    /// Per arm: the gripper command.
    pub grippers: Vec<Vec<f64>>,
    /// Per body part other than an arm: its controller's state.
    #[serde(default)]
    pub parts: Vec<Vec<f64>>,
}

/// A gripper in a compiled scene.
#[derive(Debug, Clone)]
pub struct Gripper {
    info: GripperInfo,
    has_gripper: bool,
    qpos: Vec<usize>,
    dofs: Vec<usize>,
    actuators: Vec<usize>,
    controller: GripController,
    left_pads: GeomSet,
    right_pads: GeomSet,
    geoms: GeomSet,
    fingers: GeomSet,
    corners: Vec<usize>,
}

impl Gripper {
    /// The gripper's actuators (ids), empty without a gripper.
    pub fn actuators(&self) -> &[usize] {
        &self.actuators
    }

    /// The `qpos` addresses of the gripper's joints, empty without a gripper.
    pub fn qpos(&self) -> &[usize] {
        &self.qpos
    }

    /// The gripper's figures.
    pub fn info(&self) -> &GripperInfo {
        &self.info
    }

    /// Whether the arm has a gripper (false with `gripper_types=None`, where robosuite
    /// attaches a null gripper).
    pub fn has_gripper(&self) -> bool {
        self.has_gripper
    }

    /// The action dimension.
    pub fn action_dim(&self) -> usize {
        self.controller.action_dim()
    }

    /// The geoms of the left and right finger-pad groups (`_check_grasp`).
    pub fn finger_pads(&self) -> (&GeomSet, &GeomSet) {
        (&self.left_pads, &self.right_pads)
    }

    /// Every contact geom of the gripper.
    pub fn contact_geoms(&self) -> &GeomSet {
        &self.geoms
    }

    /// Every geom of robosuite's `important_geoms` groups: both fingers and both finger
    /// pads (what ToolHang checks the tool against).
    pub fn finger_geoms(&self) -> &GeomSet {
        &self.fingers
    }

    /// The ids of the gripper's named corner geoms (the wiping tool's).
    pub fn corners(&self) -> &[usize] {
        &self.corners
    }

    /// The gripper controller.
    pub fn controller(&self) -> &GripController {
        &self.controller
    }

    /// Applies one env step's gripper action (its slice of the robot's action).
    pub fn set_goal(&mut self, action: &[f64]) {
        self.controller.set_goal(action);
    }
}

/// One arm: its joints (a range of the robot's joints), motors, controller and gripper.
#[derive(Debug, Clone)]
pub struct Arm {
    side: &'static str,
    joints: Range<usize>,
    actuators: Vec<usize>,
    ctrlrange: Vec<[f64; 2]>,
    controller: Box<dyn ArmController>,
    torques: Vec<f64>,
    eef_site: usize,
    eef_body: usize,
    gripper: Gripper,
}

impl Arm {
    /// `"right"` or `"left"`.
    pub fn side(&self) -> &'static str {
        self.side
    }

    /// The arm controller.
    pub fn controller(&self) -> &dyn ArmController {
        self.controller.as_ref()
    }

    /// The arm controller, mutably (for composite controllers).
    pub fn controller_mut(&mut self) -> &mut dyn ArmController {
        self.controller.as_mut()
    }

    /// The gripper.
    pub fn gripper(&self) -> &Gripper {
        &self.gripper
    }

    /// The gripper, mutably (for composite controllers).
    pub fn gripper_mut(&mut self) -> &mut Gripper {
        &mut self.gripper
    }

    /// The arm motors' actuator ids.
    pub fn actuators(&self) -> &[usize] {
        &self.actuators
    }

    /// The arm motors' ctrlranges (torques are clipped to them).
    pub fn ctrlrange(&self) -> &[[f64; 2]] {
        &self.ctrlrange
    }

    /// The arm's joints as a range of the robot's joints.
    pub fn joints(&self) -> Range<usize> {
        self.joints.clone()
    }

    /// The grip site id (`gripper{i}_{arm}_grip_site`: `eef_pos`, the controller's reference).
    pub fn eef_site(&self) -> usize {
        self.eef_site
    }

    /// The eef body id (the hand: `eef_quat`).
    pub fn eef_body(&self) -> usize {
        self.eef_body
    }

    /// The torques of the last substep (clipped to the motors' ctrlrange).
    pub fn torques(&self) -> &[f64] {
        &self.torques
    }

    /// The action dimension: the arm controller's plus the gripper's.
    pub fn action_dim(&self) -> usize {
        self.controller.action_dim() + self.gripper.action_dim()
    }
}

/// A body part other than an arm (robosuite's `torso`, `head`, `base`, `legs`): its
/// joints, actuators and part controller.
#[derive(Debug, Clone)]
pub struct BodyPart {
    name: &'static str,
    joint_names: Vec<String>,
    qpos: Vec<usize>,
    dofs: Vec<usize>,
    actuators: Vec<usize>,
    ctrlrange: Vec<[f64; 2]>,
    gear: Vec<f64>,
    controller: Box<dyn ArmController>,
    torques: Vec<f64>,
}

impl BodyPart {
    /// robosuite's part name: `"torso"`, `"head"`, `"base"` or `"legs"`.
    pub fn name(&self) -> &'static str {
        self.name
    }

    /// The part's joints, prefixed.
    pub fn joint_names(&self) -> &[String] {
        &self.joint_names
    }

    /// The `qpos` addresses of the part's joints.
    pub fn qpos(&self) -> &[usize] {
        &self.qpos
    }

    /// The dof (`qvel`) addresses of the part's joints.
    pub fn dofs(&self) -> &[usize] {
        &self.dofs
    }

    /// The part's actuator ids.
    pub fn actuators(&self) -> &[usize] {
        &self.actuators
    }

    /// The actuators' ctrlranges.
    pub fn ctrlrange(&self) -> &[[f64; 2]] {
        &self.ctrlrange
    }

    /// The part controller.
    pub fn controller(&self) -> &dyn ArmController {
        self.controller.as_ref()
    }

    /// The part controller, mutably (for composite controllers).
    pub fn controller_mut(&mut self) -> &mut dyn ArmController {
        self.controller.as_mut()
    }

    /// The controls of the last substep (after the robot's gear division and clipping).
    pub fn torques(&self) -> &[f64] {
        &self.torques
    }
}

/// One robot in a compiled scene.
#[derive(Debug, Clone)]
pub struct Robot {
    index: usize,
    name: &'static str,
    kind: RobotKind,
    joint_qpos: Vec<usize>,
    joint_dofs: Vec<usize>,
    init_qpos: Vec<f64>,
    init_torso_qpos: Option<Vec<f64>>,
    init_base_qpos: Option<Vec<f64>>,
    /// The leg joints' rest positions (robosuite's leg base `init_qpos`; empty without legs).
    init_legs_qpos: Vec<f64>,
    noise: InitNoise,
    base_body: usize,
    base_site: Option<usize>,
    arms: Vec<Arm>,
    bodies: Vec<BodyPart>,
    composite: Box<dyn CompositeController>,
    layout: Vec<ActionSlot>,
    action_dim: usize,
    divide_by_gear: bool,
    arm_gears: Vec<Vec<f64>>,
    dropped_parts: Vec<String>,
    contact_geoms: GeomSet,
    observables: Vec<Observable<Robot>>,
    qpos_buf: Vec<f64>,
}

fn joint_addresses(model: &MjModel, name: &str) -> Result<(usize, usize)> {
    let j = joint_id(model, name)?;
    Ok((
        model.jnt_qposadr()[j] as usize,
        model.jnt_dofadr()[j] as usize,
    ))
}

fn geom_set(model: &MjModel, names: &[String]) -> Result<GeomSet> {
    Ok(GeomSet::new(
        names
            .iter()
            .map(|n| geom_id(model, n))
            .collect::<Result<Vec<_>>>()?,
    ))
}

impl Robot {
    /// Binds robot `robot` (as composed into the scene) in the compiled `model`, with the
    /// controllers of `controllers` (fitted to the robot: one part config per arm and per
    /// other body part it has, see [`CompositeControllerConfig::fit_to`]) and the reset
    /// noise `noise`; `path` names the controller config in errors.
    ///
    /// The robot's joints (robosuite's `robot_model.joints`) and its base's are sorted
    /// into body parts by name as robosuite sorts them (`torso`, `mobile` for the base,
    /// `head`, `leg`; the rest are the arms', split evenly among the arms). A fixed-base
    /// robot controls its arms alone; a wheeled robot also its base, head and torso; a
    /// legged robot also its legs.
    ///
    /// # Errors
    /// [`Error::Model`] when a joint, body, site, geom or actuator robosuite names is
    /// missing; [`Error::InvalidArgument`] naming the key for a controller configuration
    /// that does not fit the part or is out of range, or a composite controller that does
    /// not drive this class of robot.
    pub fn bind(
        model: &MjModel,
        robot: &RobotModel,
        controllers: &CompositeControllerConfig,
        timing: Timing,
        noise: InitNoise,
        path: &str,
    ) -> Result<Self> {
        noise.validate()?;
        let index = robot.idn;
        let kind = robot.info.kind;
        let nv = model.ffi().nv as usize;
        let joints = robot.joints();
        let mut joint_qpos = Vec::with_capacity(joints.len());
        let mut joint_dofs = Vec::with_capacity(joints.len());
        for j in &joints {
            let (q, d) = joint_addresses(model, j)?;
            joint_qpos.push(q);
            joint_dofs.push(d);
        }
        // robosuite's `arm_joints` / `arm_actuators`: every robot or base element whose
        // name does not place it in another part.
        let all_joints = robot.all_joints();
        let all_actuators = robot.all_actuators();
        let arm_joints: Vec<&String> = all_joints
            .iter()
            .filter(|j| body_part_of(j).is_none())
            .collect();
        let arm_actuators: Vec<&String> = all_actuators
            .iter()
            .filter(|a| body_part_of(a).is_none())
            .collect();
        let narms = robot.arms.len();
        let per_arm = arm_joints.len() / narms.max(1);
        if narms == 0
            || per_arm * narms != arm_joints.len()
            || arm_actuators.len() != arm_joints.len()
        {
            return Err(Error::model(format!(
                "{}: {} arm joints and {} arm motors do not split into {narms} arm(s)",
                robot.info.name,
                arm_joints.len(),
                arm_actuators.len()
            )));
        }
        let divide_by_gear = kind == RobotKind::Legged;
        let gear_of = |id: usize| model.actuator_gear()[id][0];
        let mut arms = Vec::with_capacity(narms);
        let mut arm_gears = Vec::with_capacity(narms);
        for (a, arm) in robot.arms.iter().enumerate() {
            let names = &arm_joints[a * per_arm..(a + 1) * per_arm];
            // The arm's joints as a range of the robot's joints.
            let first = joints.iter().position(|j| j == names[0]).ok_or_else(|| {
                Error::model(format!(
                    "{}: arm joint `{}` is not the robot's",
                    robot.info.name, names[0]
                ))
            })?;
            let range = first..first + per_arm;
            if joints
                .get(range.clone())
                .is_none_or(|js| js.iter().zip(names).any(|(j, n)| j != *n))
            {
                return Err(Error::model(format!(
                    "{}: the {} arm's joints are not consecutive joints of the robot",
                    robot.info.name, arm.side
                )));
            }
            let mut act_ids = Vec::with_capacity(per_arm);
            let mut ctrlrange = Vec::with_capacity(per_arm);
            for name in &arm_actuators[a * per_arm..(a + 1) * per_arm] {
                let id = actuator_id(model, name)?;
                act_ids.push(id);
                ctrlrange.push(model.actuator_ctrlrange()[id]);
            }
            arm_gears.push(act_ids.iter().map(|&id| gear_of(id)).collect());
            let g = &arm.gripper;
            let eef_site = site_id(model, &g.xml.name("grip_site"))?;
            let base_site = site_id(model, &format!("robot{index}_{}_center", arm.side))?;
            let binding = ArmBinding {
                site: eef_site,
                base_site,
                qpos: joint_qpos[range.clone()].to_vec(),
                dofs: joint_dofs[range.clone()].to_vec(),
                nv,
                ctrlrange: ctrlrange.clone(),
                stale_goal_origin: kind == RobotKind::Wheeled,
            };
            let part_path = join(&join(path, "body_parts"), arm.side);
            let part = controllers.arm(arm.side).ok_or_else(|| {
                Error::invalid_argument(
                    join(path, "body_parts"),
                    format!(
                        "no controller for the `{}` arm of {}",
                        arm.side, robot.info.name
                    ),
                )
            })?;
            let controller = build_arm_controller(&part.controller, binding, timing, &part_path)?;
            let (mut gq, mut gd, mut ga, mut granges) = (vec![], vec![], vec![], vec![]);
            for j in g.xml.names_of(&g.xml.names.joints) {
                let (q, d) = joint_addresses(model, &j)?;
                gq.push(q);
                gd.push(d);
            }
            for name in g.xml.names_of(&g.xml.names.actuators) {
                let id = actuator_id(model, &name)?;
                ga.push(id);
                granges.push(model.actuator_ctrlrange()[id]);
            }
            let named =
                |list: &[&str]| -> Vec<String> { list.iter().map(|n| g.xml.name(n)).collect() };
            let gripper = Gripper {
                info: g.info,
                has_gripper: arm.has_gripper,
                qpos: gq,
                dofs: gd,
                actuators: ga,
                controller: GripController::new(
                    g.info.action,
                    granges,
                    part.gripper.use_action_scaling,
                ),
                left_pads: geom_set(model, &named(g.info.left_fingerpad))?,
                right_pads: geom_set(model, &named(g.info.right_fingerpad))?,
                geoms: geom_set(model, &g.xml.names_of(&g.xml.names.contact_geoms))?,
                fingers: geom_set(
                    model,
                    &named(
                        &[
                            g.info.left_finger,
                            g.info.right_finger,
                            g.info.left_fingerpad,
                            g.info.right_fingerpad,
                        ]
                        .concat(),
                    ),
                )?,
                corners: named(g.info.corners)
                    .iter()
                    .map(|n| geom_id(model, n))
                    .collect::<Result<_>>()?,
            };
            arms.push(Arm {
                side: arm.side,
                joints: range,
                actuators: act_ids,
                torques: vec![0.0; per_arm],
                ctrlrange,
                controller,
                eef_site,
                eef_body: body_id(model, &robot.eef_body(a))?,
                gripper,
            });
        }
        let base_site = match robot.base_center_site() {
            Some(name) if kind.is_mobile() => Some(site_id(model, &name)?),
            _ => None,
        };
        let mut bodies = Vec::new();
        for &name in kind.body_parts() {
            let names: Vec<String> = all_joints
                .iter()
                .filter(|j| body_part_of(j) == Some(name))
                .cloned()
                .collect();
            let acts: Vec<&String> = all_actuators
                .iter()
                .filter(|a| body_part_of(a) == Some(name))
                .collect();
            if names.is_empty() || acts.is_empty() {
                continue;
            }
            let part_path = join(&join(path, "body_parts"), name);
            let config = controllers.part(name).ok_or_else(|| {
                Error::invalid_argument(
                    join(path, "body_parts"),
                    format!("no controller for the `{name}` of {}", robot.info.name),
                )
            })?;
            let (mut qpos, mut dofs) = (Vec::new(), Vec::new());
            for j in &names {
                let (q, d) = joint_addresses(model, j)?;
                qpos.push(q);
                dofs.push(d);
            }
            let mut actuators = Vec::with_capacity(acts.len());
            let mut ctrlrange = Vec::with_capacity(acts.len());
            for a in acts {
                let id = actuator_id(model, a)?;
                actuators.push(id);
                ctrlrange.push(model.actuator_ctrlrange()[id]);
            }
            if actuators.len() != qpos.len() {
                return Err(Error::model(format!(
                    "{}: the {name} has {} joints and {} actuators",
                    robot.info.name,
                    qpos.len(),
                    actuators.len()
                )));
            }
            let binding = ArmBinding {
                site: base_site.unwrap_or(0),
                base_site: base_site.unwrap_or(0),
                qpos: qpos.clone(),
                dofs: dofs.clone(),
                nv,
                ctrlrange: ctrlrange.clone(),
                stale_goal_origin: false,
            };
            let controller: Box<dyn ArmController> = match (name, config) {
                ("base", ArmControllerConfig::JointVelocity(c)) => {
                    if base_site.is_none() {
                        return Err(Error::model(format!(
                            "{}: the mobile base has no `center` site",
                            robot.info.name
                        )));
                    }
                    Box::new(MobileBaseJointVelocity::new(
                        c, binding, timing, &part_path,
                    )?)
                }
                _ => build_arm_controller(config, binding, timing, &part_path)?,
            };
            let n = actuators.len();
            bodies.push(BodyPart {
                name,
                gear: actuators.iter().map(|&id| gear_of(id)).collect(),
                joint_names: names,
                qpos,
                dofs,
                actuators,
                ctrlrange,
                controller,
                torques: vec![0.0; n],
            });
        }
        let mut composite = build_composite(controllers, kind, robot.info.name, path)?;
        // The config's order; parts a hand-built config left out of it come after.
        let mut order = controllers.order.clone();
        for name in controllers
            .arms
            .iter()
            .map(|(s, _)| s)
            .chain(controllers.parts.iter().map(|(s, _)| s))
        {
            if !order.contains(name) {
                order.push(name.clone());
            }
        }
        composite.bind(
            model,
            &CompositeParts {
                order: &order,
                arms: &arms,
                bodies: &bodies,
                joints: &joints,
            },
        )?;
        let layout = composite.layout(&order, &arms, &bodies);
        let action_dim = match composite.action_limits() {
            Some((low, _)) => low.len(),
            None => layout.last().map_or(0, |s| s.range.end) + composite.extra_limits().0.len(),
        };
        let arm_names: Vec<&str> = arms.iter().map(|a| a.side).collect();
        let body_names: Vec<&str> = bodies.iter().map(|b| b.name).collect();
        let dropped_parts = controllers.dropped_parts(&arm_names, &body_names);
        let contact_geoms = geom_set(model, &robot.xml.names_of(&robot.xml.names.contact_geoms))?;
        let mut out = Self {
            index,
            name: robot.info.name,
            kind,
            init_qpos: robot.info.init_qpos.to_vec(),
            init_torso_qpos: robot.info.init_torso_qpos.map(<[f64]>::to_vec),
            init_base_qpos: robot.info.init_base_qpos.map(<[f64]>::to_vec),
            init_legs_qpos: robot
                .mount
                .as_ref()
                .map_or(&[][..], |m| m.info.legs_init_qpos())
                .to_vec(),
            qpos_buf: vec![0.0; joint_qpos.len()],
            joint_qpos,
            joint_dofs,
            noise,
            base_body: body_id(model, &robot.xml.root_body())?,
            base_site,
            arms,
            bodies,
            composite,
            layout,
            action_dim,
            divide_by_gear,
            arm_gears,
            dropped_parts,
            contact_geoms,
            observables: Vec::new(),
        };
        out.observables = out.make_observables();
        Ok(out)
    }

    /// robosuite's proprioceptive observables, modality `robot{i}_proprio`: `joint_pos`,
    /// `joint_pos_cos`, `joint_pos_sin`, `joint_vel`, `joint_acc` over every robot joint,
    /// then per arm `eef_pos` (grip site), `eef_quat` (eef body, xyzw), `eef_quat_site`
    /// (grip site, float32) and, with a gripper, `gripper_qpos` and `gripper_qvel` (arm keys
    /// prefixed `right_` / `left_` on a bimanual robot).
    fn make_observables(&self) -> Vec<Observable<Robot>> {
        let pf = format!("robot{}_", self.index);
        let n = self.joint_qpos.len();
        let m = Modality::Proprio(self.index);
        let mut obs = vec![
            Observable::f64(format!("{pf}joint_pos"), n, m, |r: &Robot, sim, out| {
                for (o, &a) in out.iter_mut().zip(&r.joint_qpos) {
                    *o = sim.data().qpos()[a];
                }
            }),
            Observable::f64(format!("{pf}joint_pos_cos"), n, m, |r: &Robot, sim, out| {
                for (o, &a) in out.iter_mut().zip(&r.joint_qpos) {
                    *o = sim.data().qpos()[a].cos();
                }
            }),
            Observable::f64(format!("{pf}joint_pos_sin"), n, m, |r: &Robot, sim, out| {
                for (o, &a) in out.iter_mut().zip(&r.joint_qpos) {
                    *o = sim.data().qpos()[a].sin();
                }
            }),
            Observable::f64(format!("{pf}joint_vel"), n, m, |r: &Robot, sim, out| {
                for (o, &a) in out.iter_mut().zip(&r.joint_dofs) {
                    *o = sim.data().qvel()[a];
                }
            }),
            Observable::f64(format!("{pf}joint_acc"), n, m, |r: &Robot, sim, out| {
                for (o, &a) in out.iter_mut().zip(&r.joint_dofs) {
                    *o = sim.data().qacc()[a];
                }
            }),
        ];
        let bimanual = self.arms.len() > 1;
        for (i, arm) in self.arms.iter().enumerate() {
            let apf = if bimanual {
                format!("{pf}{}_", arm.side)
            } else {
                pf.clone()
            };
            obs.push(Observable::f64(
                format!("{apf}eef_pos"),
                3,
                m,
                move |r: &Robot, sim, out| {
                    out.copy_from_slice(&sim.data().site_xpos()[r.arms[i].eef_site]);
                },
            ));
            obs.push(Observable::f64(
                format!("{apf}eef_quat"),
                4,
                m,
                move |r: &Robot, sim, out| {
                    out.copy_from_slice(&xyzw(sim.data().xquat()[r.arms[i].eef_body]));
                },
            ));
            obs.push(Observable::new(
                format!("{apf}eef_quat_site"),
                &[4],
                DType::F32,
                m,
                move |r: &Robot, sim, out| {
                    let q = mat2quat(&mat_from_row_major(
                        &sim.data().site_xmat()[r.arms[i].eef_site],
                    ));
                    for (o, v) in out.iter_mut().zip(q) {
                        *o = f64::from(v as f32);
                    }
                },
            ));
            if arm.gripper.has_gripper {
                let ng = arm.gripper.qpos.len();
                obs.push(Observable::f64(
                    format!("{apf}gripper_qpos"),
                    ng,
                    m,
                    move |r: &Robot, sim, out| {
                        for (o, &a) in out.iter_mut().zip(&r.arms[i].gripper.qpos) {
                            *o = sim.data().qpos()[a];
                        }
                    },
                ));
                obs.push(Observable::f64(
                    format!("{apf}gripper_qvel"),
                    ng,
                    m,
                    move |r: &Robot, sim, out| {
                        for (o, &a) in out.iter_mut().zip(&r.arms[i].gripper.dofs) {
                            *o = sim.data().qvel()[a];
                        }
                    },
                ));
            }
        }
        if self.base_site.is_some() {
            self.push_base_observables(&mut obs);
        }
        obs
    }

    /// A mobile robot's base observables (robosuite's `MobileRobot._create_base_sensors`):
    /// `base_pos`, `base_quat` (float32) of the base's `center` site, then per arm
    /// `base_to_{arm_}eef_pos`, `base_to_{arm_}eef_quat` (the eef body) and
    /// `base_to_{arm_}eef_quat_site` (the grip site), in the base's frame.
    fn push_base_observables(&self, obs: &mut Vec<Observable<Robot>>) {
        let pf = format!("robot{}_", self.index);
        let m = Modality::Proprio(self.index);
        let base = |r: &Robot, sim: &Sim| {
            let s = r.base_site.unwrap_or(0);
            (
                nalgebra::Vector3::from(sim.data().site_xpos()[s]),
                mat_from_row_major(&sim.data().site_xmat()[s]),
            )
        };
        let f32_quat = |q: [f64; 4], out: &mut [f64]| {
            for (o, v) in out.iter_mut().zip(q) {
                *o = f64::from(v as f32);
            }
        };
        obs.push(Observable::f64(
            format!("{pf}base_pos"),
            3,
            m,
            move |r: &Robot, sim, out| {
                out.copy_from_slice(base(r, sim).0.as_slice());
            },
        ));
        obs.push(Observable::new(
            format!("{pf}base_quat"),
            &[4],
            DType::F32,
            m,
            move |r: &Robot, sim, out| f32_quat(mat2quat(&base(r, sim).1), out),
        ));
        let bimanual = self.arms.len() > 1;
        for (i, arm) in self.arms.iter().enumerate() {
            let apf = if bimanual {
                format!("{}_", arm.side)
            } else {
                String::new()
            };
            obs.push(Observable::f64(
                format!("{pf}base_to_{apf}eef_pos"),
                3,
                m,
                move |r: &Robot, sim, out| {
                    let (p_b, r_b) = base(r, sim);
                    let p = nalgebra::Vector3::from(sim.data().site_xpos()[r.arms[i].eef_site]);
                    out.copy_from_slice((r_b.transpose() * (p - p_b)).as_slice());
                },
            ));
            obs.push(Observable::new(
                format!("{pf}base_to_{apf}eef_quat"),
                &[4],
                DType::F32,
                m,
                move |r: &Robot, sim, out| {
                    let (_, r_b) = base(r, sim);
                    let q = sim.data().xquat()[r.arms[i].eef_body];
                    let r_e = crate::math::quat2mat_f32(xyzw(q));
                    f32_quat(mat2quat(&(r_b.transpose() * r_e)), out);
                },
            ));
            obs.push(Observable::new(
                format!("{pf}base_to_{apf}eef_quat_site"),
                &[4],
                DType::F32,
                m,
                move |r: &Robot, sim, out| {
                    let (_, r_b) = base(r, sim);
                    let r_e = mat_from_row_major(&sim.data().site_xmat()[r.arms[i].eef_site]);
                    f32_quat(mat2quat(&(r_b.transpose() * r_e)), out);
                },
            ));
        }
    }

    /// The robot's index (`robot{index}_`).
    pub fn index(&self) -> usize {
        self.index
    }

    /// robosuite's robot name.
    pub fn name(&self) -> &'static str {
        self.name
    }

    /// robosuite's robot class.
    pub fn kind(&self) -> RobotKind {
        self.kind
    }

    /// The arms.
    pub fn arms(&self) -> &[Arm] {
        &self.arms
    }

    /// The first (right) arm.
    pub fn arm(&self) -> &Arm {
        &self.arms[0]
    }

    /// The body parts other than arms the robot controls (torso, head, base, legs), in
    /// robosuite's order of loading their controllers.
    pub fn body_parts(&self) -> &[BodyPart] {
        &self.bodies
    }

    /// The body part `name` (`"torso"`, `"head"`, `"base"`, `"legs"`), if the robot
    /// controls one.
    pub fn body_part(&self, name: &str) -> Option<&BodyPart> {
        self.bodies.iter().find(|b| b.name == name)
    }

    /// The composite controller (robosuite's `robot.composite_controller`).
    pub fn composite_controller(&self) -> &dyn CompositeController {
        self.composite.as_ref()
    }

    /// The action's slices per part (robosuite's `_action_split_indexes`), in order; a
    /// composite controller's extra entries (`HYBRID_MOBILE_BASE`'s base mode) follow the
    /// last slice.
    pub fn action_layout(&self) -> &[ActionSlot] {
        &self.layout
    }

    /// The action's slices by part name where the composite controller's action is not
    /// its layout's (`WHOLE_BODY_IK`: the end-effector poses as `"right"` / `"left"`, then
    /// the parts outside the IK); `None` when the layout is the action's.
    pub fn action_split(&self) -> Option<Vec<(String, Range<usize>)>> {
        self.composite.action_split()
    }

    /// The body parts the controller config named that the robot does not have: robosuite
    /// drops their configs with a warning.
    pub fn dropped_parts(&self) -> &[String] {
        &self.dropped_parts
    }

    /// The `qpos` addresses of the robot's joints.
    pub fn joint_qpos(&self) -> &[usize] {
        &self.joint_qpos
    }

    /// The `qvel` addresses of the robot's joints.
    pub fn joint_dofs(&self) -> &[usize] {
        &self.joint_dofs
    }

    /// The robot's rest posture (`init_qpos`).
    pub fn init_qpos(&self) -> &[f64] {
        &self.init_qpos
    }

    /// The robot's root body id.
    pub fn base_body(&self) -> usize {
        self.base_body
    }

    /// The id of the mobile base's `center` site (robosuite's base frame of a mobile
    /// robot), `None` for a fixed-base robot.
    pub fn base_site(&self) -> Option<usize> {
        self.base_site
    }

    /// The robot's own contact geoms (arm links, not mount or gripper).
    pub fn contact_geoms(&self) -> &GeomSet {
        &self.contact_geoms
    }

    /// The action dimension (robosuite's `robot.action_dim`).
    pub fn action_dim(&self) -> usize {
        self.action_dim
    }

    /// The action bounds `(low, high)` (robosuite's `action_limits`): per slot of the
    /// layout, an arm controller's own bounds, `[-1, 1]` for a gripper or another body
    /// part; then the composite controller's extra entries.
    pub fn action_limits(&self) -> (Vec<f64>, Vec<f64>) {
        if let Some(limits) = self.composite.action_limits() {
            return limits;
        }
        let (mut lo, mut hi) = (Vec::new(), Vec::new());
        for slot in &self.layout {
            match slot.part {
                PartRef::Arm(i) => {
                    let (l, h) = self.arms[i].controller.action_limits();
                    lo.extend(l);
                    hi.extend(h);
                }
                PartRef::Gripper(_) | PartRef::Body(_) => {
                    let n = slot.range.len();
                    lo.extend(std::iter::repeat_n(-1.0, n));
                    hi.extend(std::iter::repeat_n(1.0, n));
                }
            }
        }
        let (l, h) = self.composite.extra_limits();
        lo.extend(l);
        hi.extend(h);
        (lo, hi)
    }

    /// The grip-site position of arm `arm` (read without a forward pass).
    pub fn eef_pos(&self, sim: &Sim, arm: usize) -> [f64; 3] {
        sim.data().site_xpos()[self.arms[arm].eef_site]
    }

    /// The specs of the robot's observables, in order.
    pub fn observation_specs(&self) -> Vec<ObsSpec> {
        specs(&self.observables)
    }

    /// Writes the robot's observables in order into `out` (their total length), reading
    /// the data as it is (robosuite's one-substep kinematic lag after a step).
    pub fn observe(&self, sim: &Sim, out: &mut [f64]) {
        observe_all(&self.observables, self, sim, out);
    }

    /// The reset posture: `init_qpos` plus noise (one draw per joint from `rng`), the
    /// grippers' initial positions, and zeroed gripper commands. Call after
    /// `mj_resetData`.
    ///
    /// As robosuite, the controllers are reset (see [`ArmController::reset`]) after the
    /// arm's posture is written (with a forward pass) and before the grippers' is.
    ///
    /// # Errors
    /// [`gym_core::Error::Simulation`] when the forward pass raises a MuJoCo error.
    pub fn reset(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> gym_core::Result<()> {
        self.reset_with(sim, Some(rng))
    }

    /// robosuite's deterministic reset (`robot.reset(deterministic=True)`): as
    /// [`Robot::reset`] at `init_qpos` exactly, without noise and drawing nothing, and the
    /// grippers' fingers left where the scene has them (robosuite sets them only in a
    /// random reset).
    ///
    /// # Errors
    /// As [`Robot::reset`].
    pub fn reset_deterministic(&mut self, sim: &mut Sim) -> gym_core::Result<()> {
        self.reset_with(sim, None)
    }

    fn reset_with(&mut self, sim: &mut Sim, rng: Option<&mut EnvRng>) -> gym_core::Result<()> {
        self.qpos_buf.copy_from_slice(&self.init_qpos);
        // robosuite's deterministic reset leaves the fingers where the scene has them.
        let deterministic = rng.is_none();
        if let Some(rng) = rng {
            self.noise.perturb(rng, &mut self.qpos_buf);
        }
        self.start_at_posture(sim)?;
        let qpos = sim.data_mut().qpos_mut();
        for arm in &mut self.arms {
            let g = &mut arm.gripper;
            if g.has_gripper
                && !deterministic
                && let Some(init) = g.info.init_qpos
            {
                for (&a, &v) in g.qpos.iter().zip(init) {
                    qpos[a] = v;
                }
            }
            g.controller.reset();
        }
        Ok(())
    }

    /// Writes `qpos_buf` as the robot's joint positions (then robosuite's
    /// `init_base_qpos` and `init_torso_qpos` over the base's and torso's joints),
    /// forwards, lets the controllers reset (robosuite's controller construction during a
    /// reset), then writes a legged robot's leg rest positions.
    fn start_at_posture(&mut self, sim: &mut Sim) -> gym_core::Result<()> {
        let qpos = sim.data_mut().qpos_mut();
        for (&a, &v) in self.joint_qpos.iter().zip(&self.qpos_buf) {
            qpos[a] = v;
        }
        for (part, init) in [
            ("base", &self.init_base_qpos),
            ("torso", &self.init_torso_qpos),
        ] {
            if let (Some(init), Some(body)) = (init, self.bodies.iter().find(|b| b.name == part)) {
                for (&a, &v) in body.qpos.iter().zip(init) {
                    qpos[a] = v;
                }
            }
        }
        sim.forward()?;
        for arm in &mut self.arms {
            arm.controller.reset(sim);
            arm.torques.iter_mut().for_each(|t| *t = 0.0);
        }
        for body in &mut self.bodies {
            body.controller.reset(sim);
            body.torques.iter_mut().for_each(|t| *t = 0.0);
        }
        // robosuite's `LeggedRobot.reset`: the legs take their rest positions after the
        // controllers are built.
        if let Some(legs) = self.bodies.iter().find(|b| b.name == "legs") {
            let qpos = sim.data_mut().qpos_mut();
            for (&a, &v) in legs.qpos.iter().zip(&self.init_legs_qpos) {
                qpos[a] = v;
            }
        }
        Ok(())
    }

    /// The controller part of a reset to a recorded state: the robot's joints take their
    /// values in `state` (`[time, qpos, qvel]`) on a freshly reset simulator, as robosuite
    /// builds its controllers before the grippers and objects are placed; the caller then
    /// sets the whole state. Gripper commands are zeroed.
    ///
    /// # Errors
    /// [`gym_core::Error::Simulation`] when the forward pass raises a MuJoCo error.
    pub fn reset_to(&mut self, sim: &mut Sim, state: &[f64]) -> gym_core::Result<()> {
        for (v, &a) in self.qpos_buf.iter_mut().zip(&self.joint_qpos) {
            *v = state[1 + a];
        }
        self.start_at_posture(sim)?;
        self.zero_gripper_commands();
        Ok(())
    }

    /// Zeroes every gripper command (robosuite's `current_action` at reset).
    pub fn zero_gripper_commands(&mut self) {
        for arm in &mut self.arms {
            arm.gripper.controller.reset();
        }
    }

    /// Sets the goals from this robot's slice of the action, through the composite
    /// controller (robosuite's part order: [`Robot::action_layout`]); call on the first
    /// substep, after `mj_step1`. The slice length is checked by the environment.
    pub fn set_goal(&mut self, sim: &Sim, action: &[f64]) {
        let parts = PartsMut {
            arms: &mut self.arms,
            bodies: &mut self.bodies,
        };
        self.composite.set_goal(sim, parts, &self.layout, action);
    }

    /// Computes and writes this robot's controls (every substep, after `mj_step1`), each
    /// clipped to its actuator's ctrlrange as robosuite clips them (a legged robot's
    /// divided by the actuator's gear first, as robosuite's `LeggedRobot` does).
    pub fn apply_control(&mut self, sim: &mut Sim) {
        let divide = self.divide_by_gear;
        for (arm, gears) in self.arms.iter_mut().zip(&self.arm_gears) {
            let part = PartDrive {
                torques: &mut arm.torques,
                gear: divide.then_some(gears.as_slice()),
                ctrlrange: &arm.ctrlrange,
                actuators: &arm.actuators,
            };
            part.drive(arm.controller.as_mut(), sim);
            let ctrl = sim.data_mut().ctrl_mut();
            for (i, &a) in arm.gripper.actuators.iter().enumerate() {
                ctrl[a] = arm.gripper.controller.ctrl(i);
            }
        }
        for body in &mut self.bodies {
            let part = PartDrive {
                torques: &mut body.torques,
                gear: divide.then_some(body.gear.as_slice()),
                ctrlrange: &body.ctrlrange,
                actuators: &body.actuators,
            };
            part.drive(body.controller.as_mut(), sim);
        }
    }

    /// The controller state (per arm: controller state, gripper command; per other body
    /// part: controller state).
    pub fn controller_state(&self) -> RobotState {
        RobotState {
            arms: self.arms.iter().map(|a| a.controller.state()).collect(),
            grippers: self
                .arms
                .iter()
                .map(|a| a.gripper.controller.command().to_vec())
                .collect(),
            parts: self.bodies.iter().map(|b| b.controller.state()).collect(),
        }
    }

    /// Restores a state from [`Robot::controller_state`].
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a state of another robot; nothing is changed then.
    pub fn set_controller_state(&mut self, state: &RobotState) -> Result<()> {
        if state.arms.len() != self.arms.len()
            || state.grippers.len() != self.arms.len()
            || state.parts.len() != self.bodies.len()
        {
            return Err(Error::invalid_argument(
                "snapshot",
                "the robot state has another number of arms or body parts",
            ));
        }
        let mut copy: Vec<Box<dyn ArmController>> =
            self.arms.iter().map(|a| a.controller.clone()).collect();
        for (c, s) in copy.iter_mut().zip(&state.arms) {
            c.set_state(s)?;
        }
        let mut parts: Vec<Box<dyn ArmController>> =
            self.bodies.iter().map(|b| b.controller.clone()).collect();
        for (c, s) in parts.iter_mut().zip(&state.parts) {
            c.set_state(s)?;
        }
        for ((arm, c), g) in self.arms.iter_mut().zip(copy).zip(&state.grippers) {
            arm.controller = c;
            arm.gripper.controller.set_command(g);
        }
        for (body, c) in self.bodies.iter_mut().zip(parts) {
            body.controller = c;
        }
        Ok(())
    }
}

/// One part's control path: its controller's torques, divided by the actuators' gear where
/// the robot divides (robosuite's `LeggedRobot`), clipped to the ctrlrange, written to the
/// actuators' controls.
struct PartDrive<'a> {
    torques: &'a mut [f64],
    gear: Option<&'a [f64]>,
    ctrlrange: &'a [[f64; 2]],
    actuators: &'a [usize],
}

impl PartDrive<'_> {
    fn drive(self, controller: &mut dyn ArmController, sim: &mut Sim) {
        controller.compute(sim, self.torques);
        if let Some(gear) = self.gear {
            for (t, g) in self.torques.iter_mut().zip(gear) {
                *t /= g;
            }
        }
        for (t, [lo, hi]) in self.torques.iter_mut().zip(self.ctrlrange) {
            *t = t.clamp(*lo, *hi);
        }
        let ctrl = sim.data_mut().ctrl_mut();
        for (&a, &t) in self.actuators.iter().zip(self.torques.iter()) {
            ctrl[a] = t;
        }
    }
}
