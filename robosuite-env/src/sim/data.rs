//! [`Data`]: one environment's `mjData` with its model, owned by this crate or shared with
//! another owner.
//!
//! By default the model and the data are this crate's (freed on drop). [`Data::hand_over_model`]
//! and [`Data::adopt_data`] let another owner hold the memory instead — MuJoCo's own Python
//! objects (`mujoco.MjModel` / `mujoco.MjData`), so that Python code reads and writes the very
//! arrays the environment steps. The other owner is represented by a keep-alive handle
//! ([`KeepAlive`]): while this `Data` lives it holds the handle, so the memory cannot be freed
//! under it; when it is dropped it releases the handle instead of freeing the memory, and the
//! memory lives on for as long as the other owner keeps it (a NumPy view included).

use super::shared::{Mapping, SharedModel, View};
use mujoco_rs::mujoco_c::{
    mj_copyData, mj_deleteData, mj_fullM, mj_getState, mj_makeData, mj_resetData, mj_setState,
    mj_stateSize, mjContact, mjData, mjModel,
};
use mujoco_rs::wrappers::mj_model::MjModel;
use std::any::Any;
use std::mem::ManuallyDrop;
use std::ptr::NonNull;
use std::sync::Arc;

/// A handle that keeps memory owned elsewhere alive until it is dropped (for instance a
/// reference to a Python object).
pub type KeepAlive = Box<dyn Any + Send + Sync>;

/// The simulator data of one environment with the model it was made for.
pub struct Data {
    data: NonNull<mjData>,
    model: ManuallyDrop<Box<MjModel>>,
    /// `Some`: the model's memory belongs to this owner (never freed here).
    model_owner: Option<KeepAlive>,
    /// `Some`: the data's memory belongs to this owner (never freed here).
    data_owner: Option<KeepAlive>,
    /// `Some`: the model is a view of a shared model, its arrays in this mapping (see
    /// [`SharedModel`]); only the header is MuJoCo's.
    view: Option<(Mapping, Arc<SharedModel>)>,
}

// SAFETY: `Data` is the only handle through which this crate touches the mjData and mjModel
// (the other owner's handles are opaque keep-alives); `&self` methods only read, `&mut self`
// methods write, exactly as mujoco-rs's `MjData<Box<MjModel>>`, which is Send and Sync.
unsafe impl Send for Data {}
// SAFETY: as above.
unsafe impl Sync for Data {}

impl std::fmt::Debug for Data {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Data")
            .field("nq", &self.model.ffi().nq)
            .field("nv", &self.model.ffi().nv)
            .field("time", &self.time())
            .field("model_shared", &self.model_owner.is_some())
            .field("data_shared", &self.data_owner.is_some())
            .field("model_view", &self.view.is_some())
            .finish()
    }
}

/// `n` values of type `T` starting at `ptr`; an empty slice for `n == 0` (MuJoCo leaves the
/// pointers of empty arrays null).
///
/// # Safety
/// `ptr` must address `n` initialised `T`s that live as long as `'a` and are not written
/// meanwhile.
unsafe fn slice<'a, T>(ptr: *const T, n: usize) -> &'a [T] {
    if n == 0 || ptr.is_null() {
        &[]
    } else {
        // SAFETY: as the caller promises.
        unsafe { std::slice::from_raw_parts(ptr, n) }
    }
}

/// As [`slice`], mutable.
///
/// # Safety
/// As [`slice`], and nothing else may read or write the values during `'a`.
unsafe fn slice_mut<'a, T>(ptr: *mut T, n: usize) -> &'a mut [T] {
    if n == 0 || ptr.is_null() {
        &mut []
    } else {
        // SAFETY: as the caller promises.
        unsafe { std::slice::from_raw_parts_mut(ptr, n) }
    }
}

/// Read-only views of `mjData` arrays: `name: element type, count field of mjModel`.
macro_rules! views {
    ($($(#[$doc:meta])* $name:ident: $ty:ty, $len:ident;)*) => {
        $(
            $(#[$doc])*
            pub fn $name(&self) -> &[$ty] {
                let n = self.model.ffi().$len as usize;
                // SAFETY: MuJoCo lays out `$name` as `n` consecutive `$ty` in the data's
                // buffer, which lives as long as `self`.
                unsafe { slice(self.ffi().$name.cast::<$ty>(), n) }
            }
        )*
    };
}

/// Mutable views of `mjData` arrays.
macro_rules! views_mut {
    ($($(#[$doc:meta])* $name:ident => $field:ident: $ty:ty, $len:ident;)*) => {
        $(
            $(#[$doc])*
            pub fn $name(&mut self) -> &mut [$ty] {
                let n = self.model.ffi().$len as usize;
                // SAFETY: as the read-only view; `&mut self` makes the access exclusive.
                unsafe { slice_mut(self.data.as_ref().$field.cast::<$ty>(), n) }
            }
        )*
    };
}

impl Data {
    /// Allocates the data of `model` (`mj_makeData`), owning both.
    ///
    /// # Errors
    /// A message when MuJoCo cannot allocate the data.
    pub fn new(model: MjModel) -> Result<Self, String> {
        Self::with_view(View {
            model,
            mapping: None,
        })
    }

    /// Allocates the data of a view of `shared` (see [`SharedModel`]): the model's arrays
    /// are shared page by page until this environment writes them, the data is its own.
    ///
    /// # Errors
    /// A message when MuJoCo cannot allocate the data.
    pub fn new_shared(shared: &Arc<SharedModel>) -> Result<Self, String> {
        Self::with_view(shared.view())
    }

    fn with_view(view: View) -> Result<Self, String> {
        let View { model, mapping } = view;
        let model = Box::new(model);
        // SAFETY: a compiled model; a null result is handled.
        let ptr = unsafe { mj_makeData(model.ffi()) };
        let Some(data) = NonNull::new(ptr) else {
            if mapping.is_some() {
                // SAFETY: a view's header, freed before its mapping.
                unsafe { View::free_header(*model) };
            }
            return Err("mj_makeData returned null".to_owned());
        };
        Ok(Self {
            data,
            model: ManuallyDrop::new(model),
            model_owner: None,
            data_owner: None,
            view: mapping,
        })
    }

    /// The shared model this data's model is a copy-on-write view of (`None` for a model of
    /// its own).
    pub fn shared_model(&self) -> Option<&Arc<SharedModel>> {
        self.view.as_ref().map(|(_, shared)| shared)
    }

    /// Replaces a view of a shared model by a model of this crate's own (`mj_copyModel` of
    /// the view's current values); nothing to do for a model already private.
    pub fn make_model_private(&mut self) {
        if self.view.is_none() {
            return;
        }
        let copy = Box::new(MjModel::clone(&self.model));
        let old = std::mem::replace(&mut self.model, ManuallyDrop::new(copy));
        // SAFETY: the view's header (its buffer is the mapping), freed before the mapping.
        unsafe { View::free_header(*ManuallyDrop::into_inner(old)) };
        self.view = None;
    }

    /// Replaces the model with `textured`, a compilation of the same scene with its texture
    /// images, after copying every other value of the current model into it (see
    /// `copy_all_but_textures`); the data is kept, so stepping continues bit-identically.
    ///
    /// # Errors
    /// A message, with nothing changed, when the model was handed over to another owner
    /// or the two models differ in more than their textures.
    pub(crate) fn replace_with_textured(&mut self, mut textured: MjModel) -> Result<(), String> {
        if self.model_owner.is_some() {
            return Err("the model was handed over to another owner".into());
        }
        // SAFETY: `textured` is a model of this crate's own, changed only in values of
        // arrays of equal lengths.
        super::textures::copy_all_but_textures(self.model.ffi(), unsafe { textured.ffi_mut() })?;
        let old = std::mem::replace(&mut self.model, ManuallyDrop::new(Box::new(textured)));
        if self.view.is_some() {
            // SAFETY: the view's header (its buffer is the mapping), freed before the mapping.
            unsafe { View::free_header(*ManuallyDrop::into_inner(old)) };
            self.view = None;
        } else {
            drop(ManuallyDrop::into_inner(old));
        }
        Ok(())
    }

    /// The raw `mjData`.
    pub fn ffi(&self) -> &mjData {
        // SAFETY: a live mjData for as long as `self`.
        unsafe { self.data.as_ref() }
    }

    /// The raw `mjData`, mutably.
    ///
    /// # Safety
    /// The caller must keep every pointer and size of the data unchanged.
    pub unsafe fn ffi_mut(&mut self) -> &mut mjData {
        // SAFETY: exclusive through `&mut self`.
        unsafe { self.data.as_mut() }
    }

    /// The model.
    pub fn model(&self) -> &MjModel {
        &self.model
    }

    /// The model, mutably.
    ///
    /// # Safety
    /// The caller must keep every count, address and array length of the model unchanged
    /// (values only: sizes, masses, ...).
    pub unsafe fn model_mut(&mut self) -> &mut MjModel {
        &mut self.model
    }

    /// Raw pointers to the model and the data.
    pub(crate) fn raw(&self) -> (*const mjModel, *const mjData) {
        (self.model.ffi() as *const mjModel, self.data.as_ptr())
    }

    /// Mutable raw pointers to the model and the data.
    pub(crate) fn raw_mut(&mut self) -> (*mut mjModel, *mut mjData) {
        // SAFETY: the model is exclusively borrowed through `&mut self`; callers keep sizes.
        let m = unsafe { self.model.ffi_mut() } as *mut mjModel;
        (m, self.data.as_ptr())
    }

    /// Whether the model's memory belongs to another owner (see [`Data::hand_over_model`]).
    pub fn model_shared(&self) -> bool {
        self.model_owner.is_some()
    }

    /// Whether the data's memory belongs to another owner (see [`Data::adopt_data`]).
    pub fn data_shared(&self) -> bool {
        self.data_owner.is_some()
    }

    /// Hands the model's memory to another owner: `wrap` receives the `mjModel` pointer and
    /// returns the owner's handle (for instance the `mujoco.MjModel` that took the pointer).
    /// From then on this `Data` never frees the model; it keeps the handle until dropped.
    /// Does nothing (and returns `Ok`) when the model was handed over already.
    ///
    /// # Errors
    /// `wrap`'s error; the model stays this crate's.
    ///
    /// # Safety
    /// When `wrap` returns `Ok`, the handle must own the pointer it was given (free it with
    /// `mj_deleteModel` once dropped, not earlier) and must not touch its sizes; when it
    /// returns `Err`, it must not have kept or freed the pointer.
    pub unsafe fn hand_over_model<E>(
        &mut self,
        wrap: impl FnOnce(*mut mjModel) -> Result<KeepAlive, E>,
    ) -> Result<(), E> {
        if self.model_owner.is_some() {
            return Ok(());
        }
        self.make_model_private();
        let (m, _) = self.raw_mut();
        self.model_owner = Some(wrap(m)?);
        Ok(())
    }

    /// Moves this data into memory allocated by another owner: `make` allocates an `mjData`
    /// for the model (for instance `mujoco.MjData(model)`) and returns its pointer with the
    /// owner's handle; the whole state (`mj_copyData`: time, qpos, qvel, warm start,
    /// controls, derived quantities) is copied into it, so stepping continues bit-identically,
    /// and the previous data is freed if it was this crate's.
    ///
    /// # Errors
    /// `make`'s error, or a message when the pointer it returned is null; the data is then
    /// unchanged.
    ///
    /// # Safety
    /// On `Ok`, the pointer must address an `mjData` made by `mj_makeData` for this data's
    /// model, owned by the handle (which frees it only once dropped) and not used by anybody
    /// else while this `Data` steps it.
    pub unsafe fn adopt_data<E: From<String>>(
        &mut self,
        make: impl FnOnce(*const mjModel) -> Result<(*mut mjData, KeepAlive), E>,
    ) -> Result<(), E> {
        let (m, _) = self.raw();
        let (ptr, owner) = make(m)?;
        let new = NonNull::new(ptr).ok_or_else(|| E::from("the new mjData is null".to_owned()))?;
        // SAFETY: both are datas of this model; the copy includes the arena and stack.
        unsafe { mj_copyData(new.as_ptr(), m, self.data.as_ptr()) };
        let old = std::mem::replace(&mut self.data, new);
        if let Some(previous) = self.data_owner.replace(owner) {
            drop(previous);
        } else {
            // SAFETY: the old data was made by `mj_makeData` here and nothing refers to it.
            unsafe { mj_deleteData(old.as_ptr()) };
        }
        Ok(())
    }

    /// `mj_resetData`: time 0, `qpos = qpos0`, zero velocities, controls and warm start.
    pub fn reset(&mut self) {
        let (m, d) = self.raw_mut();
        // SAFETY: the model and data of `self`.
        unsafe { mj_resetData(m, d) };
    }

    /// `mj_kinematics`, `mj_comPos` and `mj_makeM`: the mass matrix at the current
    /// positions (what [`Data::full_m`] reads), without the rest of a forward pass.
    pub fn mass_matrix_stages(&mut self) {
        let (m, d) = self.raw_mut();
        // SAFETY: the model and data of `self`; these stages only write derived fields.
        unsafe {
            mujoco_rs::mujoco_c::mj_kinematics(m, d);
            mujoco_rs::mujoco_c::mj_comPos(m, d);
            mujoco_rs::mujoco_c::mj_makeM(m, d);
        }
    }

    /// The `3 × nv` translational and rotational Jacobians of site `site` (`mj_jacSite`),
    /// row-major; an empty vector for a part not asked for.
    ///
    /// # Panics
    /// When `site` is not a site id of the model.
    pub fn jac_site(&self, jacp: bool, jacr: bool, site: usize) -> (Vec<f64>, Vec<f64>) {
        let nv = self.model.ffi().nv.max(0) as usize;
        let mut p = if jacp { vec![0.0; 3 * nv] } else { Vec::new() };
        let mut r = if jacr { vec![0.0; 3 * nv] } else { Vec::new() };
        self.jac_site_into(site, jacp.then_some(&mut p[..]), jacr.then_some(&mut r[..]));
        (p, r)
    }

    /// The `3 × nv` translational (`jacp`) and rotational (`jacr`) Jacobians of site
    /// `site` (`mj_jacSite`), row-major, into the buffers given (a part given as `None` is
    /// not computed), without allocating.
    ///
    /// # Panics
    /// When `site` is not a site id of the model, or a buffer holds fewer than `3·nv`
    /// values.
    pub fn jac_site_into(&self, site: usize, jacp: Option<&mut [f64]>, jacr: Option<&mut [f64]>) {
        let nsite = self.model.ffi().nsite.max(0) as usize;
        assert!(
            site < nsite,
            "site id {site} out of range (the model has {nsite})"
        );
        let nv = self.model.ffi().nv.max(0) as usize;
        let out = |v: Option<&mut [f64]>| match v {
            None => std::ptr::null_mut(),
            Some(v) => {
                assert!(
                    v.len() >= 3 * nv,
                    "a Jacobian buffer holds {} values, needs 3·nv = {}",
                    v.len(),
                    3 * nv
                );
                v.as_mut_ptr()
            }
        };
        let (p, r) = (out(jacp), out(jacr));
        let (m, d) = self.raw();
        // SAFETY: the model and data of `self`; each buffer holds at least 3·nv values or
        // is null (which `mj_jacSite` skips); the site id is in range (so it fits an i32,
        // as MuJoCo's sizes do).
        unsafe { mujoco_rs::mujoco_c::mj_jacSite(m, d, p, r, site as i32) };
    }

    /// The simulation time.
    pub fn time(&self) -> f64 {
        self.ffi().time
    }

    /// Sets the simulation time.
    pub fn set_time(&mut self, time: f64) {
        // SAFETY: a scalar field.
        unsafe { self.data.as_mut() }.time = time;
    }

    views! {
        /// Joint positions (`nq`).
        qpos: f64, nq;
        /// Joint velocities (`nv`).
        qvel: f64, nv;
        /// Joint accelerations (`nv`).
        qacc: f64, nv;
        /// The acceleration warm start (`nv`).
        qacc_warmstart: f64, nv;
        /// Controls (`nu`).
        ctrl: f64, nu;
        /// Bias forces: Coriolis, centrifugal, gravity (`nv`).
        qfrc_bias: f64, nv;
        /// Sensor values (`nsensordata`).
        sensordata: f64, nsensordata;
        /// Body frame positions (`nbody`).
        xpos: [f64; 3], nbody;
        /// Body frame orientations, `w, x, y, z` (`nbody`).
        xquat: [f64; 4], nbody;
        /// Body frame orientations, row-major (`nbody`).
        xmat: [f64; 9], nbody;
        /// Geom positions (`ngeom`).
        geom_xpos: [f64; 3], ngeom;
        /// Geom orientations, row-major (`ngeom`).
        geom_xmat: [f64; 9], ngeom;
        /// Site positions (`nsite`).
        site_xpos: [f64; 3], nsite;
        /// Site orientations, row-major (`nsite`).
        site_xmat: [f64; 9], nsite;
        /// Camera positions (`ncam`).
        cam_xpos: [f64; 3], ncam;
        /// Camera orientations, row-major (`ncam`).
        cam_xmat: [f64; 9], ncam;
    }

    views_mut! {
        /// Joint positions, mutably.
        qpos_mut => qpos: f64, nq;
        /// Joint velocities, mutably.
        qvel_mut => qvel: f64, nv;
        /// Controls, mutably.
        ctrl_mut => ctrl: f64, nu;
    }

    /// The active contacts (`ncon`).
    pub fn contact(&self) -> &[mjContact] {
        let d = self.ffi();
        // SAFETY: `ncon` contacts at `contact` in the arena, live as long as `self`.
        unsafe { slice(d.contact.cast_const(), d.ncon.max(0) as usize) }
    }

    /// The state selected by `spec` (`mjtState` bits), `mj_getState`.
    pub fn state(&self, spec: u32) -> Vec<f64> {
        let (m, d) = self.raw();
        // SAFETY: the model and data of `self`; the buffer has `mj_stateSize` values.
        unsafe {
            let n = mj_stateSize(m, spec as i32).max(0) as usize;
            let mut out = vec![0.0; n];
            mj_getState(m, d, out.as_mut_ptr(), spec as i32);
            out
        }
    }

    /// Sets the state selected by `spec` (`mj_setState`).
    ///
    /// # Errors
    /// A message when `state` does not have `mj_stateSize` values.
    pub fn set_state(&mut self, state: &[f64], spec: u32) -> Result<(), String> {
        let (m, d) = self.raw_mut();
        // SAFETY: the model and data of `self`; the length is checked first.
        unsafe {
            let n = mj_stateSize(m, spec as i32).max(0) as usize;
            if state.len() != n {
                return Err(format!("expected {n} values, got {}", state.len()));
            }
            mj_setState(m, d, state.as_ptr(), spec as i32);
        }
        Ok(())
    }

    /// The dense `nv × nv` mass matrix (`mj_fullM`) into `dst`.
    ///
    /// # Errors
    /// A message when `dst` holds fewer than `nv²` values.
    pub fn full_m(&self, dst: &mut [f64]) -> Result<(), String> {
        let nv = self.model.ffi().nv.max(0) as usize;
        if dst.len() < nv * nv {
            return Err(format!("dst holds {} values, needs {}", dst.len(), nv * nv));
        }
        let (m, d) = self.raw();
        // SAFETY: the model and data of `self`; `dst` holds nv² values.
        unsafe { mj_fullM(m, d, dst.as_mut_ptr()) };
        Ok(())
    }
}

impl Data {
    /// Frees the data and gives the model back; `None` (both freed as on drop) when either
    /// belongs to another owner.
    pub(crate) fn into_model(mut self) -> Option<MjModel> {
        if self.model_owner.is_some() || self.data_owner.is_some() {
            return None;
        }
        self.make_model_private();
        let mut this = ManuallyDrop::new(self);
        // SAFETY: the data was made by `mj_makeData` here and is freed once; the model is
        // taken out of its `ManuallyDrop` once, and `this` is never dropped (its owners and
        // view are `None`, so nothing else is left to free).
        unsafe {
            mj_deleteData(this.data.as_ptr());
            Some(*ManuallyDrop::take(&mut this.model))
        }
    }
}

impl Drop for Data {
    fn drop(&mut self) {
        if self.data_owner.is_none() {
            // SAFETY: made by `mj_makeData` here, freed once.
            unsafe { mj_deleteData(self.data.as_ptr()) };
        }
        if self.model_owner.is_none() {
            if self.view.is_some() {
                // SAFETY: a view's header, taken once; its mapping is dropped after it.
                unsafe { View::free_header(*ManuallyDrop::take(&mut self.model)) };
                drop(self.view.take());
            } else {
                // SAFETY: dropped once; the model is this crate's.
                unsafe { ManuallyDrop::drop(&mut self.model) };
            }
        }
        // A handed-over model's memory is the other owner's; only mujoco-rs's small handle
        // (its `Box`) is left unfreed, since dropping it would free that memory.
        // The other owners' handles are dropped after this: data first, then the model.
        drop(self.data_owner.take());
        drop(self.model_owner.take());
    }
}
