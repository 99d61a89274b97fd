//! A robot bound to a compiled model: its joints, arms, controllers, grippers, reset noise
//! and proprioceptive observables (robosuite's `Robot` / `FixedBaseRobot`).

use super::noise::InitNoise;
use crate::controllers::config::join;
use crate::controllers::{
    ArmBinding, ArmController, CompositeControllerConfig, GripController, Timing,
    build_arm_controller,
};
use crate::math::{mat_from_row_major, mat2quat, xyzw};
use crate::models::grippers::GripperInfo;
use crate::models::robots::RobotModel;
use crate::observables::{Modality, ObsSpec, Observable, observe_all, specs};
use crate::sim::{GeomSet, Sim, actuator_id, body_id, geom_id, joint_id, site_id};
use gym_core::{DType, EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use std::ops::Range;

/// The controller state of a robot, for snapshots: per arm, the arm controller's state and
/// the gripper command.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RobotState {
    /// Per arm: the arm controller's [`ArmController::state`].
    pub arms: Vec<Vec<f64>>,
    /// Per arm: the gripper command.
    pub grippers: Vec<Vec<f64>>,
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

    /// The gripper.
    pub fn gripper(&self) -> &Gripper {
        &self.gripper
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

/// One robot in a compiled scene.
#[derive(Debug, Clone)]
pub struct Robot {
    index: usize,
    name: &'static str,
    joint_qpos: Vec<usize>,
    joint_dofs: Vec<usize>,
    init_qpos: Vec<f64>,
    noise: InitNoise,
    base_body: usize,
    arms: Vec<Arm>,
    part_order: Vec<usize>,
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
    /// controllers of `controllers` (fitted to the robot: one part per arm, see
    /// [`CompositeControllerConfig::fit_to`]) and the reset noise `noise`; `path` names the
    /// controller config in errors.
    ///
    /// # Errors
    /// [`Error::Model`] when a joint, body, site, geom or actuator robosuite names is
    /// missing; [`Error::InvalidArgument`] naming the key for a controller configuration
    /// that does not fit the arm or is out of range.
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
        let nv = model.ffi().nv as usize;
        let joints = robot.joints();
        let mut joint_qpos = Vec::with_capacity(joints.len());
        let mut joint_dofs = Vec::with_capacity(joints.len());
        for j in &joints {
            let (q, d) = joint_addresses(model, j)?;
            joint_qpos.push(q);
            joint_dofs.push(d);
        }
        let actuators = robot.actuators();
        let narms = robot.arms.len();
        let per_arm = joints.len() / narms;
        if per_arm * narms != joints.len() || actuators.len() != joints.len() {
            return Err(Error::model(format!(
                "{}: {} joints and {} motors do not split into {narms} arm(s)",
                robot.info.name,
                joints.len(),
                actuators.len()
            )));
        }
        let mut arms = Vec::with_capacity(narms);
        for (a, arm) in robot.arms.iter().enumerate() {
            let range = a * per_arm..(a + 1) * per_arm;
            let mut act_ids = Vec::with_capacity(per_arm);
            let mut ctrlrange = Vec::with_capacity(per_arm);
            for name in &actuators[range.clone()] {
                let id = actuator_id(model, name)?;
                act_ids.push(id);
                ctrlrange.push(model.actuator_ctrlrange()[id]);
            }
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
        let part_order = controllers
            .arms
            .iter()
            .filter_map(|(side, _)| arms.iter().position(|a| a.side == side))
            .collect();
        let contact_geoms = geom_set(model, &robot.xml.names_of(&robot.xml.names.contact_geoms))?;
        let mut out = Self {
            index,
            name: robot.info.name,
            init_qpos: robot.info.init_qpos.to_vec(),
            qpos_buf: vec![0.0; joint_qpos.len()],
            joint_qpos,
            joint_dofs,
            noise,
            base_body: body_id(model, &robot.xml.root_body())?,
            arms,
            part_order,
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
        obs
    }

    /// The robot's index (`robot{index}_`).
    pub fn index(&self) -> usize {
        self.index
    }

    /// robosuite's robot name.
    pub fn name(&self) -> &'static str {
        self.name
    }

    /// The arms.
    pub fn arms(&self) -> &[Arm] {
        &self.arms
    }

    /// The first (right) arm.
    pub fn arm(&self) -> &Arm {
        &self.arms[0]
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

    /// The robot's own contact geoms (arm links, not mount or gripper).
    pub fn contact_geoms(&self) -> &GeomSet {
        &self.contact_geoms
    }

    /// The action dimension (every arm's controller and gripper).
    pub fn action_dim(&self) -> usize {
        self.arms.iter().map(Arm::action_dim).sum()
    }

    /// The action bounds `(low, high)`: per arm (in the controller config's order) the
    /// controller's, then per arm the gripper's `[-1, 1]`.
    pub fn action_limits(&self) -> (Vec<f64>, Vec<f64>) {
        let (mut lo, mut hi) = (Vec::new(), Vec::new());
        for arm in self.part_order.iter().map(|&i| &self.arms[i]) {
            let (l, h) = arm.controller.action_limits();
            lo.extend(l);
            hi.extend(h);
        }
        for arm in &self.arms {
            let n = arm.gripper.action_dim();
            lo.extend(std::iter::repeat_n(-1.0, n));
            hi.extend(std::iter::repeat_n(1.0, n));
        }
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

    /// Writes `qpos_buf` as the robot's joint positions, forwards, and lets the controllers
    /// reset (robosuite's controller construction during a reset).
    fn start_at_posture(&mut self, sim: &mut Sim) -> gym_core::Result<()> {
        let qpos = sim.data_mut().qpos_mut();
        for (&a, &v) in self.joint_qpos.iter().zip(&self.qpos_buf) {
            qpos[a] = v;
        }
        sim.forward()?;
        for arm in &mut self.arms {
            arm.controller.reset(sim);
            arm.torques.iter_mut().for_each(|t| *t = 0.0);
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

    /// Sets the goals from this robot's slice of the action (robosuite's part order: the
    /// arms' controllers in the controller config's order, then the grippers in arm order);
    /// call on the first substep, after `mj_step1`. The slice length is checked by the
    /// environment.
    pub fn set_goal(&mut self, sim: &Sim, action: &[f64]) {
        let mut at = 0;
        for &i in &self.part_order {
            let arm = &mut self.arms[i];
            let n = arm.controller.action_dim();
            arm.controller.set_goal(sim, &action[at..at + n]);
            at += n;
        }
        for arm in &mut self.arms {
            let n = arm.gripper.action_dim();
            arm.gripper.controller.set_goal(&action[at..at + n]);
            at += n;
        }
    }

    /// Computes and writes this robot's controls (every substep, after `mj_step1`), each
    /// clipped to its actuator's ctrlrange as robosuite clips them.
    pub fn apply_control(&mut self, sim: &mut Sim) {
        for arm in &mut self.arms {
            arm.controller.compute(sim, &mut arm.torques);
            for (t, [lo, hi]) in arm.torques.iter_mut().zip(&arm.ctrlrange) {
                *t = t.clamp(*lo, *hi);
            }
            let ctrl = sim.data_mut().ctrl_mut();
            for (&a, &t) in arm.actuators.iter().zip(&arm.torques) {
                ctrl[a] = t;
            }
            for (i, &a) in arm.gripper.actuators.iter().enumerate() {
                ctrl[a] = arm.gripper.controller.ctrl(i);
            }
        }
    }

    /// The controller state (per arm: controller state, gripper command).
    pub fn controller_state(&self) -> RobotState {
        RobotState {
            arms: self.arms.iter().map(|a| a.controller.state()).collect(),
            grippers: self
                .arms
                .iter()
                .map(|a| a.gripper.controller.command().to_vec())
                .collect(),
        }
    }

    /// Restores a state from [`Robot::controller_state`].
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a state of another robot; nothing is changed then.
    pub fn set_controller_state(&mut self, state: &RobotState) -> Result<()> {
        if state.arms.len() != self.arms.len() || state.grippers.len() != self.arms.len() {
            return Err(Error::invalid_argument(
                "snapshot",
                "the robot state has another number of arms",
            ));
        }
        let mut copy: Vec<Box<dyn ArmController>> =
            self.arms.iter().map(|a| a.controller.clone()).collect();
        for (c, s) in copy.iter_mut().zip(&state.arms) {
            c.set_state(s)?;
        }
        for ((arm, c), g) in self.arms.iter_mut().zip(copy).zip(&state.grippers) {
            arm.controller = c;
            arm.gripper.controller.set_command(g);
        }
        Ok(())
    }
}
