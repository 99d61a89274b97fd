//! The physics-only baseline the benchmarks compare an env with: the env's own model
//! stepped by `mj_step` alone.

use gym_core::Result;
use robosuite_env::{RobosuiteEnv, sim::Sim};

/// The physics of an env's model alone: `mj_step` × substeps with the arm held by gravity
/// compensation (no controller, observations or reward), restarted every 200 env steps.
pub struct PhysicsOnly {
    sim: Sim,
    start: Vec<f64>,
    /// Each arm motor with the dof it drives.
    motors: Vec<(usize, usize)>,
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
        Ok(Self {
            sim,
            start,
            motors,
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
