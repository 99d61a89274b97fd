//! The physics-only baseline the benchmarks compare an env with: the env's own model
//! stepped by `mj_step` alone.

use gym_core::Result;
use robosuite_env::{RobosuiteEnv, sim::Sim};

/// The physics of an env's model alone: `mj_step` × substeps with the arms held by gravity
/// compensation and the other body parts (torso, head, legs, base) held where they start
/// (no controller, observations or reward), restarted every 200 env steps.
pub struct PhysicsOnly {
    sim: Sim,
    start: Vec<f64>,
    /// Each arm motor with the dof it drives.
    motors: Vec<(usize, usize)>,
    /// Each actuator of the other body parts with how it is held.
    holds: Vec<Hold>,
    substeps: usize,
    steps: u64,
}

impl PhysicsOnly {
    /// The physics of `env`'s model, starting from `env`'s current state.
    ///
    /// # Errors
    /// When MuJoCo cannot allocate the data or the state does not fit.
    pub fn new(env: &RobosuiteEnv) -> Result<Self> {
        let start = env.get_state();
        let mut sim = Sim::new(env.sim().model().clone())?;
        sim.set_state(&start)?;
        let motors = env
            .robots()
            .iter()
            .flat_map(|r| {
                r.arms().iter().flat_map(move |arm| {
                    let dofs = &r.joint_dofs()[arm.joints()];
                    arm.actuators().iter().copied().zip(dofs.iter().copied())
                })
            })
            .collect();
        let holds = env
            .robots()
            .iter()
            .flat_map(|r| r.body_parts().iter().flat_map(|p| p.actuators().iter()))
            .map(|&a| Hold::of(&sim, a))
            .collect();
        Ok(Self {
            sim,
            start,
            motors,
            holds,
            substeps: env.substeps(),
            steps: 0,
        })
    }

    /// One env step's worth of physics.
    ///
    /// # Errors
    /// When restoring the start state fails.
    pub fn step(&mut self) -> Result<()> {
        for _ in 0..self.substeps {
            for &(actuator, dof) in &self.motors {
                let bias = self.sim.data().qfrc_bias()[dof];
                self.sim.data_mut().ctrl_mut()[actuator] = bias;
            }
            for hold in &self.holds {
                let ctrl = hold.ctrl(&self.sim);
                self.sim.data_mut().ctrl_mut()[hold.actuator] = ctrl;
            }
            self.sim.step()?;
        }
        self.steps += 1;
        if self.steps.is_multiple_of(200) {
            self.sim.set_state(&self.start)?;
        }
        Ok(())
    }
}

impl PhysicsOnly {
    /// The current simulator state `[time, qpos, qvel]`.
    pub fn state(&self) -> Vec<f64> {
        self.sim.state()
    }
}

/// Proportional and derivative gains of the hold on a torque-driven body-part joint.
const HOLD_KP: f64 = 150.0;
const HOLD_KD: f64 = 25.0;

/// How the baseline holds one actuator of a body part other than an arm: a position servo
/// at its joint's starting position, a motor by gravity compensation plus a stiff PD on
/// that position (divided by the gear), anything else (a velocity servo, a tendon) at 0.
struct Hold {
    actuator: usize,
    kind: HoldKind,
}

enum HoldKind {
    Position {
        target: f64,
    },
    Motor {
        qpos: usize,
        dof: usize,
        target: f64,
        gear: f64,
    },
    Zero,
}

impl Hold {
    fn of(sim: &Sim, actuator: usize) -> Self {
        use mujoco_rs::mujoco_c::{mjtBias, mjtTrn};
        let m = sim.model();
        let [joint, _] = m.actuator_trnid()[actuator];
        let kind = if m.actuator_trntype()[actuator] != mjtTrn::mjTRN_JOINT || joint < 0 {
            HoldKind::Zero
        } else {
            let j = joint as usize;
            let qpos = m.jnt_qposadr()[j] as usize;
            let dof = m.jnt_dofadr()[j] as usize;
            let target = sim.data().qpos()[qpos];
            let bias = m.actuator_biastype()[actuator];
            let gain = m.actuator_gainprm()[actuator][0];
            let bias_q = m.actuator_biasprm()[actuator][1];
            let bias_v = m.actuator_biasprm()[actuator][2];
            match bias {
                mjtBias::mjBIAS_NONE => HoldKind::Motor {
                    qpos,
                    dof,
                    target,
                    gear: m.actuator_gear()[actuator][0],
                },
                // `biasprm = [0, -kp, -kv]` with `gainprm = [kp]`: a position servo.
                mjtBias::mjBIAS_AFFINE if bias_q != 0.0 && gain == -bias_q => {
                    HoldKind::Position { target }
                }
                // A velocity servo (`biasprm = [0, 0, -kv]`) holds at 0.
                _ if bias_q == 0.0 && bias_v != 0.0 => HoldKind::Zero,
                _ => HoldKind::Position { target },
            }
        };
        Self { actuator, kind }
    }

    fn ctrl(&self, sim: &Sim) -> f64 {
        match self.kind {
            HoldKind::Position { target } => target,
            HoldKind::Motor {
                qpos,
                dof,
                target,
                gear,
            } => {
                let d = sim.data();
                let torque = d.qfrc_bias()[dof] + HOLD_KP * (target - d.qpos()[qpos])
                    - HOLD_KD * d.qvel()[dof];
                if gear != 0.0 { torque / gear } else { 0.0 }
            }
            HoldKind::Zero => 0.0,
        }
    }
}
