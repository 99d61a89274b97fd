//! A robot bound to a compiled model: ids, controllers, reset noise and proprioception.

use super::spec::RobotSpec;
use crate::controllers::math::{mat_from_row_major, mat2quat};
use crate::controllers::{GripController, OscBinding, OscConfig, OscPose, OscState};
use crate::observations::ObsKey;
use crate::sim::{GeomSet, Sim, actuator_for_joint, body_id, geom_id, joint_id, site_id};
use gym_core::{DType, EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use rand::RngExt;
use rand_distr::StandardNormal;

/// The number of arm joints the controllers handle.
pub const ARM_DOF: usize = 7;

/// The law of the reset noise on the arm joints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoiseKind {
    /// `magnitude · N(0, 1)` per joint (robosuite's `"gaussian"`).
    Gaussian,
    /// `magnitude · U(−1, 1)` per joint (robosuite's `"uniform"`).
    Uniform,
}

/// robosuite's `initialization_noise`: added to `init_qpos` on every reset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InitNoise {
    /// Scale of the noise in radians.
    pub magnitude: f64,
    /// Its law.
    pub kind: NoiseKind,
}

impl Default for InitNoise {
    /// robosuite's `"default"`: Gaussian with magnitude 0.02.
    fn default() -> Self {
        Self {
            magnitude: 0.02,
            kind: NoiseKind::Gaussian,
        }
    }
}

impl InitNoise {
    /// No noise (robosuite's `None`: magnitude 0; the seven draws still happen, so the RNG
    /// stream stays aligned with the noisy setting).
    pub fn none() -> Self {
        Self {
            magnitude: 0.0,
            kind: NoiseKind::Gaussian,
        }
    }

    /// Draws the seven offsets.
    pub fn sample(&self, rng: &mut EnvRng) -> [f64; ARM_DOF] {
        std::array::from_fn(|_| {
            let z: f64 = match self.kind {
                NoiseKind::Gaussian => rng.sample(StandardNormal),
                NoiseKind::Uniform => -1.0 + 2.0 * rng.random::<f64>(),
            };
            z * self.magnitude
        })
    }
}

/// The controller state of a robot, for snapshots.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotState {
    /// The arm controller's goal and nullspace target.
    pub arm: OscState,
    /// The gripper integrator.
    pub gripper: Vec<f64>,
}

#[derive(Debug, Clone)]
struct GripperRuntime {
    qpos: Vec<usize>,
    dofs: Vec<usize>,
    actuators: Vec<usize>,
    init_qpos: Vec<f64>,
    left_pads: GeomSet,
    right_pads: GeomSet,
    controller: GripController,
}

/// One robot in a compiled scene: an arm with the `OSC_POSE` controller and, optionally, a
/// gripper with the `GRIP` controller.
#[derive(Debug, Clone)]
pub struct Robot {
    index: usize,
    spec: RobotSpec,
    noise: InitNoise,
    arm_qpos: [usize; ARM_DOF],
    arm_dofs: [usize; ARM_DOF],
    arm_actuators: [usize; ARM_DOF],
    hand_body: usize,
    eef_site: usize,
    osc: OscPose,
    gripper: Option<GripperRuntime>,
}

fn joint_addresses(model: &MjModel, name: &str) -> Result<(usize, usize)> {
    let j = joint_id(model, name)?;
    Ok((
        model.jnt_qposadr()[j] as usize,
        model.jnt_dofadr()[j] as usize,
    ))
}

impl Robot {
    /// Binds robot `index` (names prefixed `robot{index}_` / `gripper{index}_right_`) in
    /// `model`.
    ///
    /// # Errors
    /// [`Error::Model`] when a joint, body, site, geom or actuator is missing;
    /// [`Error::Unsupported`] for a robot without a gripper.
    pub fn bind(
        model: &MjModel,
        index: usize,
        spec: RobotSpec,
        osc: OscConfig,
        noise: InitNoise,
    ) -> Result<Self> {
        let rp = format!("robot{index}_");
        let gp = format!("gripper{index}_right_");
        let mut arm_qpos = [0; ARM_DOF];
        let mut arm_dofs = [0; ARM_DOF];
        let mut arm_actuators = [0; ARM_DOF];
        let mut ctrlrange = [[0.0; 2]; ARM_DOF];
        for (i, joint) in spec.arm.joints.iter().enumerate() {
            let name = format!("{rp}{joint}");
            let (q, d) = joint_addresses(model, &name)?;
            arm_qpos[i] = q;
            arm_dofs[i] = d;
            let a = actuator_for_joint(model, joint_id(model, &name)?, &name)?;
            arm_actuators[i] = a;
            ctrlrange[i] = model.actuator_ctrlrange()[a];
        }
        let hand_body = body_id(model, &format!("{rp}{}", spec.arm.hand_body))?;
        let base_site = site_id(model, &format!("{rp}{}", spec.arm.center_site))?;
        let Some(gspec) = spec.gripper.clone() else {
            return Err(Error::Unsupported("robots without a gripper".into()));
        };
        let eef_site = site_id(model, &format!("{gp}{}", gspec.grip_site))?;
        let mut gq = Vec::new();
        let mut gd = Vec::new();
        let mut ga = Vec::new();
        let mut ranges = Vec::new();
        for joint in gspec.joints {
            let name = format!("{gp}{joint}");
            let (q, d) = joint_addresses(model, &name)?;
            gq.push(q);
            gd.push(d);
            let a = actuator_for_joint(model, joint_id(model, &name)?, &name)?;
            ga.push(a);
            ranges.push(model.actuator_ctrlrange()[a]);
        }
        let pads = |names: &[&str]| -> Result<GeomSet> {
            Ok(GeomSet::new(
                names
                    .iter()
                    .map(|n| geom_id(model, &format!("{gp}{n}")))
                    .collect::<Result<Vec<_>>>()?,
            ))
        };
        let gripper = GripperRuntime {
            qpos: gq,
            dofs: gd,
            actuators: ga,
            init_qpos: gspec.init_qpos.to_vec(),
            left_pads: pads(gspec.left_pads)?,
            right_pads: pads(gspec.right_pads)?,
            controller: GripController::new(gspec.command_signs.to_vec(), gspec.speed, ranges),
        };
        let nv = model.ffi().nv as usize;
        let osc = OscPose::new(
            osc,
            OscBinding {
                site: eef_site,
                base_site,
                qpos: arm_qpos,
                dofs: arm_dofs,
                ctrlrange,
            },
            nv,
        );
        Ok(Self {
            index,
            spec,
            noise,
            arm_qpos,
            arm_dofs,
            arm_actuators,
            hand_body,
            eef_site,
            osc,
            gripper: Some(gripper),
        })
    }

    /// The robot's index (`robot{index}_`).
    pub fn index(&self) -> usize {
        self.index
    }

    /// Its description.
    pub fn spec(&self) -> &RobotSpec {
        &self.spec
    }

    /// The action dimension: 6 for the arm plus 1 for a gripper with fingers (a wiping
    /// tool has none).
    pub fn action_dim(&self) -> usize {
        6 + usize::from(self.gripper.as_ref().is_some_and(|g| !g.qpos.is_empty()))
    }

    /// The arm controller.
    pub fn controller(&self) -> &OscPose {
        &self.osc
    }

    /// The gripper controller, if the robot has a gripper.
    pub fn gripper_controller(&self) -> Option<&GripController> {
        self.gripper.as_ref().map(|g| &g.controller)
    }

    /// The grip site id (`gripperN_right_grip_site`).
    pub fn eef_site(&self) -> usize {
        self.eef_site
    }

    /// The hand body id (`robotN_right_hand`).
    pub fn hand_body(&self) -> usize {
        self.hand_body
    }

    /// The `qpos` addresses of the arm joints.
    pub fn arm_qpos(&self) -> &[usize; ARM_DOF] {
        &self.arm_qpos
    }

    /// The grip site position (`robotN_eef_pos`, read without a forward pass).
    pub fn eef_pos(&self, sim: &Sim) -> [f64; 3] {
        sim.data().site_xpos()[self.eef_site]
    }

    /// The geoms of the left and right finger-pad groups.
    pub fn finger_pads(&self) -> Option<(&GeomSet, &GeomSet)> {
        self.gripper.as_ref().map(|g| (&g.left_pads, &g.right_pads))
    }

    /// Writes the reset configuration: `init_qpos` plus noise on the arm (seven draws from
    /// `rng`), the gripper's initial opening, and zeroes the gripper integrator. Call after
    /// `mj_resetData`; [`Robot::rebase`] after the next `mj_forward`.
    pub fn reset(&mut self, sim: &mut Sim, rng: &mut EnvRng) {
        let noise = self.noise.sample(rng);
        let qpos = sim.data_mut().qpos_mut();
        for i in 0..ARM_DOF {
            qpos[self.arm_qpos[i]] = self.spec.arm.init_qpos[i] + noise[i];
        }
        if let Some(g) = &mut self.gripper {
            for (adr, v) in g.qpos.iter().zip(&g.init_qpos) {
                qpos[*adr] = *v;
            }
            g.controller.reset();
        }
    }

    /// The controller state (arm goal, nullspace target, gripper integrator).
    pub fn controller_state(&self) -> RobotState {
        RobotState {
            arm: self.osc.state(),
            gripper: self
                .gripper
                .as_ref()
                .map_or_else(Vec::new, |g| g.controller.command().to_vec()),
        }
    }

    /// Restores a state from [`Robot::controller_state`].
    pub fn set_controller_state(&mut self, state: &RobotState) {
        self.osc.set_state(&state.arm);
        if let Some(g) = &mut self.gripper {
            g.controller.set_command(&state.gripper);
        }
    }

    /// Re-bases the arm controller on the current (forwarded) state.
    pub fn rebase(&mut self, sim: &Sim) {
        self.osc.reset(sim);
    }

    /// Sets the goals from this robot's slice of the action (`[6 arm, 1 gripper]`); call on
    /// the first substep, after `mj_step1`. The slice length is checked by the environment.
    pub fn set_goal(&mut self, sim: &Sim, action: &[f64]) {
        let arm: [f64; 6] = std::array::from_fn(|i| action[i]);
        self.osc.set_goal(sim, &arm);
        if let (Some(g), Some(a)) = (&mut self.gripper, action.get(6)) {
            g.controller.set_goal(*a);
        }
    }

    /// Computes and writes this robot's controls (every substep, after `mj_step1`).
    pub fn apply_control(&mut self, sim: &mut Sim) {
        let tau = self.osc.compute_torques(sim);
        let ctrl = sim.data_mut().ctrl_mut();
        for i in 0..ARM_DOF {
            ctrl[self.arm_actuators[i]] = tau[i];
        }
        if let Some(g) = &self.gripper {
            for (i, a) in g.actuators.iter().enumerate() {
                ctrl[*a] = g.controller.ctrl(i);
            }
        }
    }

    /// The proprioceptive observation keys, in robosuite's order.
    pub fn observation_keys(&self) -> Vec<ObsKey> {
        let p = format!("robot{}_", self.index);
        let ng = self.gripper.as_ref().map_or(0, |g| g.qpos.len());
        let f64k = |n: &str, len: usize| ObsKey::new(format!("{p}{n}"), &[len], DType::F64);
        vec![
            f64k("joint_pos", ARM_DOF),
            f64k("joint_pos_cos", ARM_DOF),
            f64k("joint_pos_sin", ARM_DOF),
            f64k("joint_vel", ARM_DOF),
            f64k("joint_acc", ARM_DOF),
            f64k("eef_pos", 3),
            f64k("eef_quat", 4),
            ObsKey::new(format!("{p}eef_quat_site"), &[4], DType::F32),
            f64k("gripper_qpos", ng),
            f64k("gripper_qvel", ng),
        ]
    }

    /// Writes the proprioception (in the order of [`Robot::observation_keys`]) into `out`,
    /// reading the data as it is (robosuite's one-substep kinematic lag after a step).
    pub fn write_observations(&self, sim: &Sim, out: &mut [f64]) {
        let d = sim.data();
        let (qpos, qvel, qacc) = (d.qpos(), d.qvel(), d.qacc());
        let mut k = 0;
        let mut put = |v: f64| {
            out[k] = v;
            k += 1;
        };
        for &a in &self.arm_qpos {
            put(qpos[a]);
        }
        for &a in &self.arm_qpos {
            put(qpos[a].cos());
        }
        for &a in &self.arm_qpos {
            put(qpos[a].sin());
        }
        for &a in &self.arm_dofs {
            put(qvel[a]);
        }
        for &a in &self.arm_dofs {
            put(qacc[a]);
        }
        for v in d.site_xpos()[self.eef_site] {
            put(v);
        }
        let hq = d.xquat()[self.hand_body];
        for v in [hq[1], hq[2], hq[3], hq[0]] {
            put(v);
        }
        let sq = mat2quat(&mat_from_row_major(&d.site_xmat()[self.eef_site]));
        for v in sq {
            put(f64::from(v as f32));
        }
        if let Some(g) = &self.gripper {
            for &a in &g.qpos {
                put(qpos[a]);
            }
            for &a in &g.dofs {
                put(qvel[a]);
            }
        }
    }
}
