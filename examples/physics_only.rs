//! The physics-only baseline the benchmarks compare an env with: the env's own model
//! stepped by `mj_step` alone.

use gym_core::Result;
use robosuite_env::{RobosuiteEnv, sim::Sim};

/// The physics of an env's model alone: `mj_step` × substeps with the arm held by gravity
/// compensation (no controller, observations or reward), restarted every 200 env steps.
pub struct PhysicsOnly {
    sim: Sim,
    start: Vec<f64>,
    dofs: Vec<usize>,
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
        let dofs = env
            .robots()
            .iter()
            .flat_map(|r| r.controller().binding().dofs.to_vec())
            .collect();
        Ok(Self {
            sim,
            start,
            dofs,
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
            for (col, &d) in self.dofs.iter().enumerate() {
                let bias = self.sim.data().qfrc_bias()[d];
                self.sim.data_mut().ctrl_mut()[col] = bias;
            }
            self.sim.step();
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
