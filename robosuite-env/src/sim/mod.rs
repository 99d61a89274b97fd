//! MuJoCo plumbing: the simulator an environment owns, name lookups, contact queries,
//! run-time model edits, safe wrappers of the MuJoCo math the controllers use ([`mju`]), the
//! scene's MJCF with the model's current values ([`scene_xml`]) and the MuJoCo version check.

mod contacts;
mod data;
mod guard;
pub mod mju;
mod names;
mod resize;
mod shared;
mod textures;
mod version;
mod xml;

pub use contacts::{GeomSet, any_contact_between, any_contact_with};
pub use data::{Data, KeepAlive};
pub use names::{actuator_for_joint, actuator_id, body_id, geom_id, joint_id, sensor_adr, site_id};
pub use resize::{
    BoxGeomUpdate, reshape_body_from, resize_box_body, resize_cylinder_body, resized_box_bodies,
};
pub use shared::SharedModel;
pub use version::{MUJOCO_VERSION, check_mujoco_version};
pub use xml::scene_xml;

use guard::Call;
use gym_core::{Error, Result};
use mujoco_rs::mujoco_c::{mjData, mjModel, mjtWarning};
use mujoco_rs::wrappers::mj_model::{MjModel, MjtDisableBit};
use std::sync::Arc;

/// The largest magnitude accepted for a position or velocity in [`Sim::set_state`]: far
/// beyond any posture or speed of robosuite's scenes, and four orders of magnitude below
/// MuJoCo's own divergence threshold (`mjMAXVAL`, 1e10).
pub const MAX_STATE_MAGNITUDE: f64 = 1e6;

/// MuJoCo's warnings that mean the simulation diverged (MuJoCo then resets the data by
/// itself): bad positions, velocities, accelerations, controls.
const DIVERGENCE_WARNINGS: [(mjtWarning, &str); 4] = [
    (mjtWarning::mjWARN_BADQPOS, "a position"),
    (mjtWarning::mjWARN_BADQVEL, "a velocity"),
    (mjtWarning::mjWARN_BADQACC, "an acceleration"),
    (mjtWarning::mjWARN_BADCTRL, "a control"),
];

/// A compiled model with its data: what one environment instance simulates.
///
/// The model is this simulator's own, either a plain copy ([`Sim::new`]) or a copy-on-write
/// view of a [`SharedModel`] ([`Sim::new_shared`]): reads share the compiled model's memory
/// with every other view, and the first write to a page of it (per-episode randomisation
/// such as Lift's cube size, edited in place without recompiling) copies that page for this
/// simulator alone. Either way no write is ever seen by another simulator.
///
/// MuJoCo's fatal errors do not end the process: [`Sim::forward`], [`Sim::step1`],
/// [`Sim::step2`] and [`Sim::step`] return [`Error::Simulation`] (see the `guard` module), and
/// the simulator then refuses every further step until [`Sim::reset_data`].
#[derive(Debug)]
pub struct Sim {
    data: Data,
    failed: Option<String>,
}

impl Sim {
    /// Wraps a compiled model, allocating its data, and checks that MuJoCo can simulate it:
    /// a trial `mj_forward` and `mj_step` from the model's reference state (then
    /// `mj_resetData`), so that a model MuJoCo cannot step (an arena too small, ...) fails here
    /// rather than at the first env step.
    ///
    /// # Errors
    /// [`Error::Model`] when MuJoCo cannot allocate the data or raises an error in the trial.
    pub fn new(model: MjModel) -> Result<Self> {
        // SAFETY: a compiled model; the shim allocates and frees one mjData.
        unsafe { guard::trial_make_data(model.ffi()) }
            .map_err(|e| Error::model(format!("MuJoCo cannot allocate mjData: {e}")))?;
        Self::checked(Data::new(model))
    }

    /// As [`Sim::new`] on a copy-on-write view of `shared` (see [`Sim`]): the compiled
    /// model's memory is shared with every other simulator made from it.
    ///
    /// # Errors
    /// As [`Sim::new`].
    pub fn new_shared(shared: &Arc<SharedModel>) -> Result<Self> {
        // SAFETY: a compiled model; the shim allocates and frees one mjData.
        unsafe { guard::trial_make_data(shared.model().ffi()) }
            .map_err(|e| Error::model(format!("MuJoCo cannot allocate mjData: {e}")))?;
        Self::checked(Data::new_shared(shared))
    }

    /// The trial step of [`Sim::new`] on a fresh data.
    fn checked(data: std::result::Result<Data, String>) -> Result<Self> {
        let data = data.map_err(|e| Error::model(format!("cannot allocate mjData: {e}")))?;
        let mut sim = Self { data, failed: None };
        sim.forward()
            .and_then(|()| sim.step())
            .map_err(|e| Error::model(format!("the trial step failed: {e}")))?;
        sim.reset_data();
        Ok(sim)
    }

    /// Runs a MuJoCo function through the guard; on a fatal error marks the simulator failed.
    fn guarded(&mut self, call: Call) -> Result<()> {
        if let Some(message) = &self.failed {
            return Err(Error::simulation(format!(
                "an earlier MuJoCo error ({message}) left the simulation unusable; reset first"
            )));
        }
        // SAFETY: the model and data are owned by `self.data` and made for each other; this
        // crate installs no MuJoCo callback.
        let result = unsafe {
            let (m, d) = self.data.raw_mut();
            guard::run(call, m, d)
        };
        result.map_err(|message| {
            let error = Error::simulation(format!(
                "MuJoCo error: {message} (the simulation is unusable until reset)"
            ));
            self.failed = Some(message);
            error
        })
    }

    /// Whether a MuJoCo error left the simulator unusable (until [`Sim::reset_data`]).
    pub fn failed(&self) -> bool {
        self.failed.is_some()
    }

    /// Clears MuJoCo's divergence warning counters (bad position, velocity, acceleration and
    /// control); [`Sim::check_diverged`] then reports what happened since.
    pub fn clear_divergence(&mut self) {
        // SAFETY: only warning counters are written, no size or pointer.
        let warnings = unsafe { &mut self.data.ffi_mut().warning };
        for (w, _) in DIVERGENCE_WARNINGS {
            warnings[w as usize].number = 0;
        }
    }

    /// Whether MuJoCo found a non-finite or huge (> 1e10) position, velocity, acceleration or
    /// control since [`Sim::clear_divergence`] (MuJoCo then resets the data silently and
    /// carries on).
    ///
    /// # Errors
    /// [`Error::Simulation`] naming what diverged and in which degree of freedom (or
    /// actuator).
    pub fn check_diverged(&self) -> Result<()> {
        let warnings = &self.data.ffi().warning;
        for (w, what) in DIVERGENCE_WARNINGS {
            let stat = &warnings[w as usize];
            if stat.number > 0 {
                return Err(Error::simulation(format!(
                    "the simulation diverged: {what} became non-finite or larger than 1e10 \
                     (index {}, time {}); MuJoCo reset the physics, so reset the env",
                    stat.lastinfo,
                    self.data.time()
                )));
            }
        }
        Ok(())
    }

    /// The model.
    pub fn model(&self) -> &MjModel {
        self.data.model()
    }

    /// The shared model this simulator's model is a copy-on-write view of (`None` for a
    /// model of its own; see [`Sim`]).
    pub fn shared_model(&self) -> Option<&Arc<SharedModel>> {
        self.data.shared_model()
    }

    /// Replaces the model with `textured` (see [`Data`]'s `replace_with_textured`).
    pub(crate) fn replace_with_textured(&mut self, textured: MjModel) -> Result<()> {
        self.data
            .replace_with_textured(textured)
            .map_err(|e| Error::model(format!("cannot load the scene's textures: {e}")))
    }

    /// A copy of `textured` holding every value of this model except its textures (see
    /// [`Data`]'s `replace_with_textured`).
    pub(crate) fn with_textures_of(&self, mut textured: MjModel) -> Result<MjModel> {
        // SAFETY: a model of the caller's own, changed only in values of arrays of equal
        // lengths.
        textures::copy_all_but_textures(self.model().ffi(), unsafe { textured.ffi_mut() })
            .map_err(|e| Error::model(format!("cannot load the scene's textures: {e}")))?;
        Ok(textured)
    }

    /// The data.
    pub fn data(&self) -> &Data {
        &self.data
    }

    /// The data, mutably.
    pub fn data_mut(&mut self) -> &mut Data {
        &mut self.data
    }

    /// Mutable raw pointers to the model and the data (for `mj_setConst`).
    pub(crate) fn raw_mut(&mut self) -> (*mut mjModel, *mut mjData) {
        self.data.raw_mut()
    }

    /// The model, mutably, for edits that keep every size and address unchanged.
    pub(crate) fn model_mut(&mut self) -> &mut MjModel {
        // SAFETY: callers only change values (sizes of geoms, masses, inertias), never
        // counts, addresses or array lengths.
        unsafe { self.data.model_mut() }
    }

    /// `mj_resetData`: time 0, `qpos = qpos0`, zero velocities, controls and warm start; also
    /// makes a simulator failed by a MuJoCo error usable again.
    pub fn reset_data(&mut self) {
        self.data.reset();
        self.failed = None;
    }

    /// `mj_forward`: recomputes every derived quantity from the state.
    ///
    /// # Errors
    /// [`Error::Simulation`] for a MuJoCo error, now or earlier (see [`Sim`]).
    pub fn forward(&mut self) -> Result<()> {
        self.guarded(Call::Forward)
    }

    /// `mj_step1`: position and velocity stages (kinematics, Jacobian inputs, mass matrix, bias forces).
    ///
    /// # Errors
    /// [`Error::Simulation`] for a MuJoCo error, now or earlier (see [`Sim`]).
    pub fn step1(&mut self) -> Result<()> {
        self.guarded(Call::Step1)
    }

    /// `mj_step2`: actuation, acceleration, constraints and integration.
    ///
    /// # Errors
    /// [`Error::Simulation`] for a MuJoCo error, now or earlier (see [`Sim`]).
    pub fn step2(&mut self) -> Result<()> {
        self.guarded(Call::Step2)
    }

    /// `mj_step2` with sensor computation switched off (`mjDSBL_SENSOR`) for this call only.
    ///
    /// The trajectory is bit-identical to [`Sim::step2`]: sensors feed nothing back into the
    /// dynamics. Only `sensordata` and the quantities MuJoCo computes just for acceleration
    /// sensors (`cacc`, `cfrc_int`, `cfrc_ext`, from `mj_rnePostConstraint`) are left as they
    /// were; the env uses it on every substep but the last of an env step, whose sensors are
    /// read by nobody. That skips a third of the cost of `mj_step2` for the Panda's wrist
    /// force-torque sensor (callgrind: 4.1 % of a Lift env step).
    ///
    /// # Errors
    /// As [`Sim::step2`].
    pub fn step2_without_sensors(&mut self) -> Result<()> {
        let sensor = MjtDisableBit::mjDSBL_SENSOR as i32;
        let flags = self.model().opt().disableflags;
        self.model_mut().opt_mut().disableflags = flags | sensor;
        let result = self.guarded(Call::Step2);
        self.model_mut().opt_mut().disableflags = flags;
        result
    }

    /// `mj_step` (physics only, no split).
    ///
    /// # Errors
    /// [`Error::Simulation`] for a MuJoCo error, now or earlier (see [`Sim`]).
    pub fn step(&mut self) -> Result<()> {
        self.guarded(Call::Step)
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

    /// Checks a flattened state `[time, qpos, qvel]` for this model without applying it.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the length is wrong, a value is not finite, or a
    /// position or velocity exceeds [`MAX_STATE_MAGNITUDE`] in magnitude.
    pub fn check_state(&self, state: &[f64]) -> Result<()> {
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
        if let Some(i) = state[1..]
            .iter()
            .position(|x| x.abs() > MAX_STATE_MAGNITUDE)
        {
            return Err(Error::invalid_argument(
                "state",
                format!(
                    "value {} is {}; positions and velocities must lie within ±{MAX_STATE_MAGNITUDE:e}",
                    i + 1,
                    state[i + 1]
                ),
            ));
        }
        Ok(())
    }

    /// Sets the flattened state `[time, qpos, qvel]` and runs `mj_forward`.
    ///
    /// # Errors
    /// As [`Sim::check_state`] (the simulator is then left unchanged); [`Error::Simulation`]
    /// when `mj_forward` raises a MuJoCo error.
    pub fn set_state(&mut self, state: &[f64]) -> Result<()> {
        self.check_state(state)?;
        let nq = self.model().ffi().nq as usize;
        self.data.set_time(state[0]);
        self.data.qpos_mut().copy_from_slice(&state[1..1 + nq]);
        self.data.qvel_mut().copy_from_slice(&state[1 + nq..]);
        self.forward()
    }

    /// The full integration state (`mjSTATE_INTEGRATION`: time, qpos, qvel, act, warm start,
    /// controls, applied forces, mocap, ...), enough to continue bit-identically.
    pub fn integration_state(&self) -> Vec<f64> {
        self.data
            .state(mujoco_rs::mujoco_c::mjtState::mjSTATE_INTEGRATION as u32)
    }

    /// Restores a state from [`Sim::integration_state`] and runs `mj_forward`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the length does not match this model.
    pub fn set_integration_state(&mut self, state: &[f64]) -> Result<()> {
        if self.failed.is_some() {
            // The whole state is overwritten; the reset restores MuJoCo's stack first.
            self.reset_data();
        }
        self.data
            .set_state(
                state,
                mujoco_rs::mujoco_c::mjtState::mjSTATE_INTEGRATION as u32,
            )
            .map_err(|e| Error::invalid_argument("state", e))?;
        self.forward()
    }

    /// Hands the model's memory to another owner (see [`Data::hand_over_model`]).
    ///
    /// # Errors
    /// `wrap`'s error; nothing changes then.
    ///
    /// # Safety
    /// As [`Data::hand_over_model`].
    pub unsafe fn hand_over_model<E>(
        &mut self,
        wrap: impl FnOnce(*mut mjModel) -> std::result::Result<KeepAlive, E>,
    ) -> std::result::Result<(), E> {
        // SAFETY: as the caller promises.
        unsafe { self.data.hand_over_model(wrap) }
    }

    /// Moves the data into memory of another owner (see [`Data::adopt_data`]); the state is
    /// copied whole, so stepping continues bit-identically.
    ///
    /// # Errors
    /// `make`'s error; nothing changes then.
    ///
    /// # Safety
    /// As [`Data::adopt_data`].
    pub unsafe fn adopt_data<E: From<String>>(
        &mut self,
        make: impl FnOnce(*const mjModel) -> std::result::Result<(*mut mjData, KeepAlive), E>,
    ) -> std::result::Result<(), E> {
        // SAFETY: as the caller promises.
        unsafe { self.data.adopt_data(make) }
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
