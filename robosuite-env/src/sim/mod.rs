//! MuJoCo plumbing: the simulator an environment owns, name lookups, contact queries,
//! run-time model edits and the MuJoCo version check.

mod contacts;
mod names;
mod resize;
mod version;

pub use contacts::{GeomSet, any_contact_between, any_contact_with};
pub use names::{actuator_for_joint, actuator_id, body_id, geom_id, joint_id, sensor_adr, site_id};
pub use resize::{BoxGeomUpdate, reshape_body_from, resize_box_body, resize_cylinder_body};
pub use version::{MUJOCO_VERSION, check_mujoco_version};

use gym_core::{Error, Result};
use mujoco_rs::mujoco_c::{mjData, mjModel};
use mujoco_rs::wrappers::mj_data::MjData;
use mujoco_rs::wrappers::mj_model::{MjModel, MjtDisableBit};

/// The simulator data of one environment, owning its (private, editable) copy of the model.
pub type Data = MjData<Box<MjModel>>;

/// A compiled model with its data: what one environment instance simulates.
///
/// The model is owned (not shared) so that per-episode randomisation, such as Lift's cube
/// size, can edit it in place without recompiling.
#[derive(Debug)]
pub struct Sim {
    data: Data,
}

impl Sim {
    /// Wraps a compiled model, allocating its data.
    ///
    /// # Errors
    /// [`Error::Model`] when MuJoCo cannot allocate the data.
    pub fn new(model: MjModel) -> Result<Self> {
        let data = MjData::try_new(Box::new(model))
            .map_err(|e| Error::Model(format!("cannot allocate mjData: {e}")))?;
        Ok(Self { data })
    }

    /// The model.
    pub fn model(&self) -> &MjModel {
        self.data.model()
    }

    /// The data.
    pub fn data(&self) -> &Data {
        &self.data
    }

    /// The data, mutably.
    pub fn data_mut(&mut self) -> &mut Data {
        &mut self.data
    }

    /// Raw pointers to the model and the data, for MuJoCo functions that the safe wrapper
    /// does not expose without allocating.
    pub(crate) fn raw(&self) -> (*const mjModel, *const mjData) {
        (
            self.data.model().ffi() as *const mjModel,
            self.data.ffi() as *const mjData,
        )
    }

    /// Mutable raw pointers to the model and the data (for `mj_setConst`).
    pub(crate) fn raw_mut(&mut self) -> (*mut mjModel, *mut mjData) {
        // SAFETY: the pointers address the heap objects owned by `self.data`; the caller uses
        // them only while `self` is mutably borrowed and keeps every size of the model.
        unsafe {
            let d = self.data.ffi_mut() as *mut mjData;
            let m = self.data.model_mut().ffi_mut() as *mut mjModel;
            (m, d)
        }
    }

    /// The model, mutably, for edits that keep every size and address unchanged.
    pub(crate) fn model_mut(&mut self) -> &mut MjModel {
        // SAFETY: callers only change values (sizes of geoms, masses, inertias), never
        // counts, addresses or array lengths.
        unsafe { self.data.model_mut() }
    }

    /// `mj_resetData`: time 0, `qpos = qpos0`, zero velocities, controls and warm start.
    pub fn reset_data(&mut self) {
        self.data.reset();
    }

    /// `mj_forward`: recomputes every derived quantity from the state.
    pub fn forward(&mut self) {
        self.data.forward();
    }

    /// `mj_step1`: position and velocity stages (kinematics, Jacobian inputs, mass matrix, bias forces).
    pub fn step1(&mut self) {
        self.data.step1();
    }

    /// `mj_step2`: actuation, acceleration, constraints and integration.
    pub fn step2(&mut self) {
        self.data.step2();
    }

    /// `mj_step2` with sensor computation switched off (`mjDSBL_SENSOR`) for this call only.
    ///
    /// The trajectory is bit-identical to [`Sim::step2`]: sensors feed nothing back into the
    /// dynamics. Only `sensordata` and the quantities MuJoCo computes just for acceleration
    /// sensors (`cacc`, `cfrc_int`, `cfrc_ext`, from `mj_rnePostConstraint`) are left as they
    /// were; the env uses it on every substep but the last of an env step, whose sensors are
    /// read by nobody. That skips a third of the cost of `mj_step2` for the Panda's wrist
    /// force-torque sensor (callgrind: 4.1 % of a Lift env step).
    pub fn step2_without_sensors(&mut self) {
        let sensor = MjtDisableBit::mjDSBL_SENSOR as i32;
        let flags = self.model().opt().disableflags;
        self.model_mut().opt_mut().disableflags = flags | sensor;
        self.data.step2();
        self.model_mut().opt_mut().disableflags = flags;
    }

    /// `mj_step` (physics only, no split).
    pub fn step(&mut self) {
        self.data.step();
    }

    /// The length of the flattened state `[time, qpos, qvel]`.
    pub fn state_len(&self) -> usize {
        let m = self.model().ffi();
        1 + m.nq as usize + m.nv as usize
    }

    /// The flattened state `[time, qpos, qvel]` (robosuite's `sim.get_state().flatten()`).
    pub fn state(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.state_len());
        out.push(self.data.time());
        out.extend_from_slice(self.data.qpos());
        out.extend_from_slice(self.data.qvel());
        out
    }

    /// Sets the flattened state `[time, qpos, qvel]` and runs `mj_forward`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the length is wrong or a value is not finite; the
    /// simulator is then left unchanged.
    pub fn set_state(&mut self, state: &[f64]) -> Result<()> {
        let expected = self.state_len();
        if state.len() != expected {
            return Err(Error::invalid_argument(
                "state",
                format!(
                    "expected {expected} values [time, qpos, qvel], got {}",
                    state.len()
                ),
            ));
        }
        if let Some(i) = state.iter().position(|x| !x.is_finite()) {
            return Err(Error::invalid_argument(
                "state",
                format!("value {i} is not finite ({})", state[i]),
            ));
        }
        let nq = self.model().ffi().nq as usize;
        self.data.set_time(state[0]);
        self.data.qpos_mut().copy_from_slice(&state[1..1 + nq]);
        self.data.qvel_mut().copy_from_slice(&state[1 + nq..]);
        self.data.forward();
        Ok(())
    }

    /// The full integration state (`mjSTATE_INTEGRATION`: time, qpos, qvel, act, warm start,
    /// controls, applied forces, mocap, ...), enough to continue bit-identically.
    pub fn integration_state(&self) -> Vec<f64> {
        self.data
            .state(mujoco_rs::mujoco_c::mjtState::mjSTATE_INTEGRATION as u32)
            .into_vec()
    }

    /// Restores a state from [`Sim::integration_state`] and runs `mj_forward`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the length does not match this model.
    pub fn set_integration_state(&mut self, state: &[f64]) -> Result<()> {
        self.data
            .set_state(
                state,
                mujoco_rs::mujoco_c::mjtState::mjSTATE_INTEGRATION as u32,
            )
            .map_err(|e| Error::invalid_argument("state", format!("{e:?}")))?;
        self.data.forward();
        Ok(())
    }

    /// Bytes MuJoCo reserved for this data's arena and stack.
    pub fn arena_bytes(&self) -> usize {
        self.data.ffi().narena as usize
    }

    /// The most arena bytes used so far.
    pub fn arena_max_use(&self) -> usize {
        self.data.ffi().maxuse_arena as usize
    }
}
