//! The arm state a controller works from, cached as robosuite's `Controller.update` caches
//! it: read from the simulator when a new update is due (or forced), then reused until the
//! controller's torque computation ends.
//!
//! robosuite reads the state in `set_goal` and then skips the read in the same substep's
//! `run_controller`; right after a reset, the state read when the controller was created
//! (arm posture written, grippers not yet) is what the first env step's goal and torques
//! use. Reproducing the cache, not just its effect, keeps every controller exact.

use super::ArmBinding;
use crate::math::mat_from_row_major;
use crate::sim::Sim;
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

/// What a controller reads besides the joint positions and velocities.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Needs {
    /// The reference site's pose, velocity and Jacobian.
    pub site: bool,
    /// The arm's mass matrix.
    pub mass: bool,
}

/// The cached arm state of one controller.
#[derive(Debug, Clone)]
pub struct ArmState {
    bind: ArmBinding,
    needs: Needs,
    new_update: bool,
    /// Joint positions.
    pub q: DVector<f64>,
    /// Joint velocities.
    pub qd: DVector<f64>,
    /// The reference (grip) site's position.
    pub pos: Vector3<f64>,
    /// Its orientation.
    pub ori: Matrix3<f64>,
    /// Its linear velocity (over every dof of the model).
    pub vel: Vector3<f64>,
    /// Its angular velocity.
    pub angvel: Vector3<f64>,
    /// Its Jacobian on the arm's dofs (rows: position, then rotation).
    pub jac: DMatrix<f64>,
    /// The arm's block of the mass matrix.
    pub mass: DMatrix<f64>,
    jacp: Vec<f64>,
    jacr: Vec<f64>,
    full_m: Vec<f64>,
}

impl ArmState {
    /// An empty cache for the arm of `bind`.
    pub fn new(bind: ArmBinding, needs: Needs) -> Self {
        let n = bind.dofs.len();
        let nv = bind.nv;
        Self {
            needs,
            new_update: true,
            q: DVector::zeros(n),
            qd: DVector::zeros(n),
            pos: Vector3::zeros(),
            ori: Matrix3::identity(),
            vel: Vector3::zeros(),
            angvel: Vector3::zeros(),
            jac: DMatrix::zeros(6, n),
            mass: DMatrix::zeros(n, n),
            jacp: vec![0.0; if needs.site { 3 * nv } else { 0 }],
            jacr: vec![0.0; if needs.site { 3 * nv } else { 0 }],
            full_m: vec![0.0; if needs.mass { nv * nv } else { 0 }],
            bind,
        }
    }

    /// The arm binding.
    pub fn binding(&self) -> &ArmBinding {
        &self.bind
    }

    /// The number of arm joints.
    pub fn joints(&self) -> usize {
        self.bind.dofs.len()
    }

    /// robosuite's `update(force)`: reads the state when an update is due or forced.
    pub fn update(&mut self, sim: &Sim, force: bool) {
        if !(self.new_update || force) {
            return;
        }
        let d = sim.data();
        let (qpos, qvel) = (d.qpos(), d.qvel());
        for (i, (&a, &v)) in self.bind.qpos.iter().zip(&self.bind.dofs).enumerate() {
            self.q[i] = qpos[a];
            self.qd[i] = qvel[v];
        }
        let nv = self.bind.nv;
        if self.needs.site {
            d.jac_site_into(self.bind.site, Some(&mut self.jacp), Some(&mut self.jacr));
            self.pos = Vector3::from(d.site_xpos()[self.bind.site]);
            self.ori = mat_from_row_major(&d.site_xmat()[self.bind.site]);
            for r in 0..3 {
                let (mut v, mut w) = (0.0, 0.0);
                for (k, qd) in qvel.iter().enumerate() {
                    v += self.jacp[r * nv + k] * qd;
                    w += self.jacr[r * nv + k] * qd;
                }
                self.vel[r] = v;
                self.angvel[r] = w;
                for (c, &dof) in self.bind.dofs.iter().enumerate() {
                    self.jac[(r, c)] = self.jacp[r * nv + dof];
                    self.jac[(r + 3, c)] = self.jacr[r * nv + dof];
                }
            }
        }
        if self.needs.mass {
            d.full_m(&mut self.full_m)
                .expect("the buffer is sized for the model's nv");
            for (r, &dr) in self.bind.dofs.iter().enumerate() {
                for (c, &dc) in self.bind.dofs.iter().enumerate() {
                    self.mass[(r, c)] = self.full_m[dr * nv + dc];
                }
            }
        }
        self.new_update = false;
    }

    /// The end of a torque computation: the next [`ArmState::update`] reads again.
    pub fn finish(&mut self) {
        self.new_update = true;
    }

    /// A fresh cache, read now (robosuite's controller construction).
    pub fn restart(&mut self, sim: &Sim) {
        self.new_update = true;
        self.update(sim, false);
    }

    /// The length of [`ArmState::state`].
    pub fn state_len(&self) -> usize {
        let n = self.joints();
        1 + 2 * n + 18 + 6 * n + n * n
    }

    /// `[new-update flag, q, q̇, pos, ori (column-major), vel, angvel, J (column-major),
    /// M (column-major)]`.
    pub fn state(&self, out: &mut Vec<f64>) {
        out.push(f64::from(u8::from(self.new_update)));
        out.extend(self.q.iter());
        out.extend(self.qd.iter());
        out.extend(self.pos.iter());
        out.extend(self.ori.iter());
        out.extend(self.vel.iter());
        out.extend(self.angvel.iter());
        out.extend(self.jac.iter());
        out.extend(self.mass.iter());
    }

    /// Restores [`ArmState::state`] from the front of `state` (at least
    /// [`ArmState::state_len`] values, checked by the caller); returns the rest.
    pub fn set_state<'a>(&mut self, state: &'a [f64]) -> &'a [f64] {
        let n = self.joints();
        let mut at = 0;
        let mut take = |k: usize| {
            let s = &state[at..at + k];
            at += k;
            s
        };
        self.new_update = take(1)[0] != 0.0;
        self.q.copy_from_slice(take(n));
        self.qd.copy_from_slice(take(n));
        self.pos.copy_from_slice(take(3));
        self.ori.copy_from_slice(take(9));
        self.vel.copy_from_slice(take(3));
        self.angvel.copy_from_slice(take(3));
        self.jac.copy_from_slice(take(6 * n));
        self.mass.copy_from_slice(take(n * n));
        &state[at..]
    }
}
