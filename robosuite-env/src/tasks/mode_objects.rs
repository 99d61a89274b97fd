//! The free objects of robosuite's tasks with a `single_object_mode` (PickPlace's groceries,
//! NutAssembly's nuts): which of them are in play, their observables, parking the unused
//! ones, the staged-reward terms the two tasks share, and their part of the task state.

use super::common::{
    FreeBody, ObjectMode, ObjectSensors, PARKED_POS, PoseRef, robot0_eef_dist, robot0_grasps,
};
use super::options::{self, TaskOptions};
use crate::models::objects::ObjectModel;
use crate::observables::{Modality, Observable};
use crate::robots::Robot;
use crate::sim::{GeomSet, Sim};
use gym_core::{DType, EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use rand::RngExt;
use serde::Serialize;
use serde::de::DeserializeOwned;

/// robosuite's `reach_mult`: the largest reaching reward.
pub const REACH_MULT: f64 = 0.1;
/// robosuite's `grasp_mult`: the grasping reward.
pub const GRASP_MULT: f64 = 0.35;
/// robosuite's `lift_mult`: the largest lifting reward.
pub const LIFT_MULT: f64 = 0.5;
/// robosuite's `hover_mult`: the largest hovering reward.
pub const HOVER_MULT: f64 = 0.7;

/// robosuite's `single_object_mode` and `type_key` (`object_type`, `nut_type`) arguments
/// of a task whose objects are named `types` (robosuite's lower-case names, by id). Only
/// the base task (`PickPlace`, `NutAssembly`) takes them; its registered variants fix them,
/// as robosuite's subclasses do.
pub(crate) struct ModeArgs {
    /// `object_type` or `nut_type`.
    pub type_key: &'static str,
    /// robosuite's names of the objects, by id.
    pub types: &'static [&'static str],
}

impl ModeArgs {
    /// `spec`'s options (see [`TaskSpec::options`](super::TaskSpec::options)) with the mode
    /// arguments when the mode is not `fixed`.
    pub(crate) fn options<T: Serialize>(
        &self,
        spec: &T,
        mode: ObjectMode,
        fixed: bool,
    ) -> TaskOptions {
        let mut out = options::to_options(spec);
        if !fixed {
            out.insert("single_object_mode".into(), mode.number().into());
            let kind = match mode {
                ObjectMode::Single(i) => self.types.get(i).map(|t| (*t).into()),
                _ => None,
            };
            out.insert(
                self.type_key.into(),
                kind.unwrap_or(serde_json::Value::Null),
            );
        }
        out
    }

    /// `spec` with `given` applied and the mode they select (see
    /// [`TaskSpec::configure`](super::TaskSpec::configure)).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a mode other than 0, 1, 2, an unknown type, mode 2
    /// without a type, these arguments given to a variant, or another argument the task
    /// does not take or of the wrong type.
    pub(crate) fn configure<T: Serialize + DeserializeOwned>(
        &self,
        task: &str,
        spec: &T,
        current: ObjectMode,
        fixed: bool,
        given: &TaskOptions,
    ) -> Result<(T, ObjectMode)> {
        let mut rest = given.clone();
        let number: Option<u8> = options::take(&mut rest, "single_object_mode")?;
        let kind: Option<Option<String>> = options::take(&mut rest, self.type_key)?;
        let mode = if fixed {
            if number.is_some() || kind.is_some() {
                return Err(Error::invalid_argument(
                    "single_object_mode",
                    format!("{task} fixes single_object_mode and {}", self.type_key),
                ));
            }
            current
        } else {
            self.mode(number, kind.flatten(), current)?
        };
        let next = options::merged(task, spec, &rest).map_err(|e| match &e {
            // An unknown name lists the mode arguments too.
            Error::InvalidArgument { name, .. } if !fixed => {
                let all = self.options(spec, current, fixed);
                if all.contains_key(name) {
                    e
                } else {
                    options::unknown(task, name, all.keys().map(String::as_str))
                }
            }
            _ => e,
        })?;
        Ok((next, mode))
    }

    fn mode(
        &self,
        number: Option<u8>,
        kind: Option<String>,
        current: ObjectMode,
    ) -> Result<ObjectMode> {
        let key = self.type_key;
        let id = match kind {
            None => None,
            Some(name) => Some(self.types.iter().position(|t| *t == name).ok_or_else(|| {
                Error::invalid_argument(
                    key,
                    format!("unknown {key} `{name}`; valid: {}", self.types.join(", ")),
                )
            })?),
        };
        Ok(match (number.unwrap_or(current.number()), id) {
            (0, _) => ObjectMode::All,
            (1, _) => ObjectMode::RandomSingle,
            (2, Some(i)) => ObjectMode::Single(i),
            (2, None) => match current {
                ObjectMode::Single(i) => ObjectMode::Single(i),
                _ => {
                    return Err(Error::invalid_argument(
                        key,
                        format!(
                            "single_object_mode=2 needs {key}: one of {}",
                            self.types.join(", ")
                        ),
                    ));
                }
            },
            (other, _) => {
                return Err(Error::invalid_argument(
                    "single_object_mode",
                    format!(
                        "must be 0 (all objects), 1 (one drawn per reset) or 2 (one fixed), got {other}"
                    ),
                ));
            }
        })
    }
}

/// The objects of a task with robosuite's `single_object_mode`.
///
/// * Mode 0 ([`ObjectMode::All`]): every object is in play and observed.
/// * Mode 2 ([`ObjectMode::Single`]): one fixed object is in play; the others are parked at
///   (10, 10, 10) after placement (robosuite's `clear_objects`), and only its observables
///   are in the observation.
/// * Mode 1 ([`ObjectMode::RandomSingle`]): as mode 2 with the object drawn at every reset
///   (after placement, as robosuite's `rng.choice`). robosuite renames the observation keys
///   after each reset's object; a fixed observation space cannot, so its observables are
///   named after the task's single-object prefix (`obj_*`, `nut_*`) and followed by the
///   object's id (`obj_id`, `nut_id`, int64), as robosuite's.
///
/// Every object is placed by the task's sampler in every mode (robosuite places them all,
/// then parks the unused ones), and every object not yet placed at its goal takes part in
/// the staged rewards, parked ones included, as in robosuite.
#[derive(Debug, Clone)]
pub struct ModeObjects {
    mode: ObjectMode,
    active: usize,
    bodies: Vec<FreeBody>,
    /// The contact geoms of each subset of the objects, indexed by its bit mask.
    grasp_sets: Vec<GeomSet>,
    /// The sensors of the observed objects (mode 1: the active one's, swapped at reset).
    sensors: ObjectSensors,
    /// One object's sensors per object.
    single_sensors: Vec<ObjectSensors>,
}

impl ModeObjects {
    /// The most objects a task may have (grasp checks keep one geom set per subset).
    pub const MAX_OBJECTS: usize = 8;

    /// Binds `objects` (each with a free joint first) in `mode`; the sensors are relative to
    /// robot 0's first arm.
    ///
    /// # Errors
    /// [`Error::Model`] for a missing name or a first joint that is not free;
    /// [`Error::InvalidArgument`] for a mode naming no object or too many objects.
    pub fn bind(
        model: &MjModel,
        objects: &[ObjectModel],
        mode: ObjectMode,
        robots: &[Robot],
    ) -> Result<Self> {
        let n = objects.len();
        if n == 0 || n > Self::MAX_OBJECTS {
            return Err(Error::invalid_argument(
                "objects",
                format!("need 1 to {} objects, got {n}", Self::MAX_OBJECTS),
            ));
        }
        if let ObjectMode::Single(i) = mode
            && i >= n
        {
            return Err(Error::invalid_argument(
                "single_object_mode",
                format!("object {i} does not exist; there are {n}"),
            ));
        }
        let bodies = objects
            .iter()
            .map(|o| FreeBody::bind(model, o))
            .collect::<Result<Vec<_>>>()?;
        let single_sensors: Vec<ObjectSensors> = bodies
            .iter()
            .map(|b| ObjectSensors::new(vec![PoseRef::Body(b.body)], robots))
            .collect();
        let active = match mode {
            ObjectMode::Single(i) => i,
            _ => 0,
        };
        let sensors = match mode {
            ObjectMode::All => ObjectSensors::new(
                bodies.iter().map(|b| PoseRef::Body(b.body)).collect(),
                robots,
            ),
            _ => single_sensors[active].clone(),
        };
        let grasp_sets = (0..1usize << n)
            .map(|mask| {
                GeomSet::new(
                    bodies
                        .iter()
                        .enumerate()
                        .filter(|(i, _)| mask & (1 << i) != 0)
                        .flat_map(|(_, b)| b.geoms.ids().iter().map(|&g| g as usize)),
                )
            })
            .collect();
        Ok(Self {
            mode,
            active,
            bodies,
            grasp_sets,
            sensors,
            single_sensors,
        })
    }

    /// The mode.
    pub fn mode(&self) -> ObjectMode {
        self.mode
    }

    /// The object in play in the single modes (robosuite's `object_id` / `nut_id`); 0 in
    /// mode 0.
    pub fn active(&self) -> usize {
        self.active
    }

    /// The objects, in robosuite's order.
    pub fn bodies(&self) -> &[FreeBody] {
        &self.bodies
    }

    /// The sensors of the observed objects.
    pub fn sensors(&self) -> &ObjectSensors {
        &self.sensors
    }

    /// Object `i`'s position.
    pub fn pos(&self, sim: &Sim, i: usize) -> [f64; 3] {
        self.bodies[i].pos(sim)
    }

    /// The observables of the observed objects, robosuite's four per object (see
    /// [`ObjectSensors::observables`]) named after `names` (mode 0: all, mode 2: the fixed
    /// one), or in mode 1 the active object's named after `single` followed by
    /// `{single}_id`. `sensors` and `active` find [`ModeObjects::sensors`] and
    /// [`ModeObjects::active`] in the task.
    pub fn observables<T: 'static>(
        &self,
        sensors: fn(&T) -> &ObjectSensors,
        active: fn(&T) -> usize,
        names: &[&str],
        single: &str,
    ) -> Vec<Observable<T>> {
        match self.mode {
            ObjectMode::All => names
                .iter()
                .enumerate()
                .flat_map(|(i, name)| self.sensors.observables(sensors, i, name, DType::F64))
                .collect(),
            ObjectMode::Single(i) => self.sensors.observables(sensors, 0, names[i], DType::F64),
            ObjectMode::RandomSingle => {
                let mut obs = self.sensors.observables(sensors, 0, single, DType::F64);
                obs.push(Observable::new(
                    format!("{single}_id"),
                    &[],
                    DType::I64,
                    Modality::Object,
                    move |t: &T, _sim, out| out[0] = active(t) as f64,
                ));
                obs
            }
        }
    }

    /// Forgets the sensors' cached poses (every reset).
    pub fn clear_cache(&mut self) {
        self.sensors.clear();
    }

    /// Caches the observed objects' poses (after every observation pass).
    pub fn remember(&mut self, sim: &Sim) {
        self.sensors.remember(sim);
    }

    /// The end of robosuite's `_reset_internal` after placement: in mode 1 draws the object
    /// in play (uniformly); in the single modes parks the others at (10, 10, 10).
    pub fn choose_and_park(&mut self, sim: &mut Sim, rng: &mut EnvRng) {
        if self.mode == ObjectMode::RandomSingle {
            self.set_active(rng.random_range(0..self.bodies.len()));
        }
        if self.mode != ObjectMode::All {
            for (i, body) in self.bodies.iter().enumerate() {
                if i != self.active {
                    body.set_pose(sim, PARKED_POS, [1.0, 0.0, 0.0, 0.0]);
                }
            }
        }
    }

    /// Puts object `i` in play (single modes), with fresh sensors.
    fn set_active(&mut self, i: usize) {
        self.active = i;
        self.sensors = self.single_sensors[i].clone();
    }

    /// The bit mask of the objects not yet placed at their goal.
    pub fn unplaced(placed: &[bool]) -> usize {
        placed
            .iter()
            .enumerate()
            .filter(|(_, p)| !**p)
            .fold(0, |mask, (i, _)| mask | 1 << i)
    }

    /// Whether a gripper of robot 0 grasps the objects of `mask` (robosuite's `_check_grasp`
    /// on all their contact geoms together: one finger pad may touch one object and the
    /// other another); never for an empty mask.
    pub fn grasps(&self, sim: &Sim, robots: &[Robot], mask: usize) -> bool {
        mask != 0 && robot0_grasps(sim, robots, &self.grasp_sets[mask])
    }

    /// robosuite's reaching, grasping and lifting stages over the objects of `mask`:
    /// reaching `0.1·(1 − tanh(10·min d(grip site, reach_point(i))))` (the nearest of robot
    /// 0's grip sites); grasping 0.35 (any of its grippers); lifting,
    /// when grasping, `0.35 + 0.15·(1 − tanh(15·min max(z_target − z_i, 0)))`. Each is 0
    /// for an empty mask.
    pub fn reach_grasp_lift(
        &self,
        sim: &Sim,
        robots: &[Robot],
        mask: usize,
        reach_point: impl Fn(usize) -> [f64; 3],
        z_target: f64,
    ) -> [f64; 3] {
        let in_mask = |i: &usize| mask & (1 << i) != 0;
        let indices = || (0..self.bodies.len()).filter(in_mask);
        let mut r_reach = 0.0;
        if mask != 0 {
            let d = indices()
                .map(|i| robot0_eef_dist(sim, robots, reach_point(i)))
                .fold(f64::INFINITY, f64::min);
            r_reach = (1.0 - (10.0 * d).tanh()) * REACH_MULT;
        }
        let r_grasp = f64::from(u8::from(self.grasps(sim, robots, mask))) * GRASP_MULT;
        let mut r_lift = 0.0;
        if mask != 0 && r_grasp > 0.0 {
            let z = indices()
                .map(|i| (z_target - self.pos(sim, i)[2]).max(0.0))
                .fold(f64::INFINITY, f64::min);
            r_lift = GRASP_MULT + (1.0 - (15.0 * z).tanh()) * (LIFT_MULT - GRASP_MULT);
        }
        [r_reach, r_grasp, r_lift]
    }

    /// The state: the object in play in the single modes, then the sensors' cache (empty
    /// when cleared).
    pub fn save(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(1 + self.sensors.saved_len());
        if self.mode != ObjectMode::All {
            out.push(self.active as f64);
        }
        out.extend(self.sensors.save());
        out
    }

    /// Restores a state from [`ModeObjects::save`]; `task` names the task in errors.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a wrong length, an object id that is not an object's
    /// (or, in mode 2, not the fixed one), or non-finite cached values; nothing is changed
    /// then.
    pub fn load(&mut self, task: &str, state: &[f64]) -> Result<()> {
        let bad = |why: String| Error::invalid_argument("task state", format!("{task}: {why}"));
        let (id, cache) = match self.mode {
            ObjectMode::All => (None, state),
            _ => {
                let Some((&id, cache)) = state.split_first() else {
                    return Err(bad(
                        "the state starts with the id of the object in play; got none".into(),
                    ));
                };
                let i = self.bodies.len();
                let valid = id.fract() == 0.0 && (0.0..i as f64).contains(&id);
                if !valid {
                    return Err(bad(format!("object id {id} is not one of 0..{i}")));
                }
                if let ObjectMode::Single(k) = self.mode
                    && id as usize != k
                {
                    return Err(bad(format!("the object in play is always {k}, got {id}")));
                }
                (Some(id as usize), cache)
            }
        };
        let per_object = self.single_sensors[0].saved_len();
        let observed = self.sensors.saved_len() / per_object;
        if !(cache.is_empty() || cache.len() == observed * per_object) {
            let id_first = if id.is_some() {
                "the object id, then "
            } else {
                ""
            };
            return Err(bad(format!(
                "expected {id_first}0 or {} cached pose values, got {} values in all",
                observed * per_object,
                state.len()
            )));
        }
        if cache.iter().any(|v| !v.is_finite()) {
            return Err(bad("cached poses must be finite".into()));
        }
        if let Some(i) = id {
            self.set_active(i);
        }
        self.sensors.load(cache)
    }
}
