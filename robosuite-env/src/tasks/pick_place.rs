//! robosuite's `PickPlace` family: move grocery objects from one bin into their quadrant
//! of the other (`environments/manipulation/pick_place.py`).

use super::common::{ObjectMode, robot0_eef_dist};
use super::mode_objects::ModeArgs;
use super::mode_objects::{HOVER_MULT, LIFT_MULT, ModeObjects};
use super::options::TaskOptions;
use super::{Bound, RewardConfig, Task, TaskLogic, TaskScene, TaskSpec};
use crate::assets::Assets;
use crate::models::arenas::Arena;
use crate::models::objects::{Joints, ObjType, ObjectModel, xml_object};
use crate::models::robots::RobotModel;
use crate::placement::{Axis, PlacedObject, Pose, Rotation, UniformRandomSampler};
use crate::robots::Robot;
use crate::sim::{Sim, body_id};
use gym_core::{EnvRng, Error, Result, rng_from_seed};
use mujoco_rs::wrappers::mj_model::MjModel;

/// The objects, in robosuite's order (their ids): milk 0, bread 1, cereal 2, can 3.
pub const PICK_PLACE_OBJECTS: [&str; 4] = ["Milk", "Bread", "Cereal", "Can"];

/// The object files (`objects/{file}.xml`, and `objects/{file}-visual.xml` for the targets).
const OBJECT_FILES: [&str; 4] = ["milk", "bread", "cereal", "can"];

/// The single-object variants (mode 2), by object id.
const SINGLE_VARIANTS: [&str; 4] = [
    "PickPlaceMilk",
    "PickPlaceBread",
    "PickPlaceCereal",
    "PickPlaceCan",
];

/// PickPlace's settings (robosuite's constructor defaults).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PickPlaceSpec {
    #[serde(skip)]
    mode: ObjectMode,
    /// A registered variant (robosuite's subclasses) fixes the mode.
    #[serde(skip)]
    fixed_mode: bool,
    /// The bins' inner size (robosuite's `table_full_size`, default 0.39 × 0.49 × 0.82; the
    /// arena's `bin_size`).
    #[serde(rename = "table_full_size")]
    pub bin_size: [f64; 3],
    /// robosuite's `table_friction` (default (1, 0.005, 0.0001)): robosuite's `BinsArena`
    /// keeps it and uses it nowhere, and neither does this task.
    pub table_friction: [f64; 3],
    /// Centre of the bin the objects start in (default (0.1, −0.25, 0.8)).
    pub bin1_pos: [f64; 3],
    /// Centre of the goal bin (default (0.1, 0.28, 0.8)).
    pub bin2_pos: [f64; 3],
    /// Height above bin 1 at which objects are placed (default 0).
    pub z_offset: f64,
    /// The objects' yaw at placement (robosuite's `z_rotation`; default uniform).
    pub z_rotation: Rotation,
}

impl Default for PickPlaceSpec {
    fn default() -> Self {
        Self {
            mode: ObjectMode::All,
            fixed_mode: false,
            bin_size: [0.39, 0.49, 0.82],
            table_friction: [1.0, 5e-3, 1e-4],
            bin1_pos: [0.1, -0.25, 0.8],
            bin2_pos: [0.1, 0.28, 0.8],
            z_offset: 0.0,
            z_rotation: Rotation::Random,
        }
    }
}

impl PickPlaceSpec {
    /// robosuite's `single_object_mode` and `object_type`.
    const MODE_ARGS: ModeArgs = ModeArgs {
        type_key: "object_type",
        types: &["milk", "bread", "cereal", "can"],
    };

    /// robosuite's constructor arguments (see [`TaskSpec::options`]); the base task also
    /// lists `single_object_mode` and `object_type`.
    fn task_options(&self) -> TaskOptions {
        Self::MODE_ARGS.options(self, self.mode, self.fixed_mode)
    }

    /// Sets robosuite's constructor arguments (see [`TaskSpec::configure`]).
    fn set_task_options(&mut self, given: &TaskOptions) -> Result<()> {
        let (mut next, mode) =
            Self::MODE_ARGS.configure(self.name(), self, self.mode, self.fixed_mode, given)?;
        Self::new(mode)?;
        next.mode = mode;
        next.fixed_mode = self.fixed_mode;
        *self = next;
        Ok(())
    }

    /// robosuite's defaults in `mode` (robosuite's `single_object_mode` and `object_type`:
    /// [`ObjectMode::Single`] takes the object id, milk 0, bread 1, cereal 2, can 3).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an object id above 3.
    pub fn new(mode: ObjectMode) -> Result<Self> {
        if let ObjectMode::Single(i) = mode
            && i >= PICK_PLACE_OBJECTS.len()
        {
            return Err(Error::invalid_argument(
                "object_type",
                format!("object id {i} is not one of 0 (milk), 1 (bread), 2 (cereal), 3 (can)"),
            ));
        }
        Ok(Self {
            mode,
            ..Self::default()
        })
    }

    /// The registered variant `name` (`PickPlace`, `PickPlaceSingle`, `PickPlaceMilk`,
    /// `PickPlaceBread`, `PickPlaceCereal`, `PickPlaceCan`), if it is one.
    pub fn variant(name: &str) -> Option<Self> {
        let mode = match name {
            "PickPlace" => ObjectMode::All,
            "PickPlaceSingle" => ObjectMode::RandomSingle,
            _ => ObjectMode::Single(SINGLE_VARIANTS.iter().position(|v| *v == name)?),
        };
        Some(Self {
            fixed_mode: name != "PickPlace",
            ..Self::new(mode).ok()?
        })
    }

    /// The single-object mode.
    pub fn mode(&self) -> ObjectMode {
        self.mode
    }

    /// The low corner of object `i`'s quadrant of the goal bin (robosuite's `not_in_bin`).
    fn quadrant_low(&self, i: usize) -> [f64; 2] {
        let mut x = self.bin2_pos[0];
        let mut y = self.bin2_pos[1];
        if i == 0 || i == 2 {
            x -= self.bin_size[0] / 2.0;
        }
        if i < 2 {
            y -= self.bin_size[1] / 2.0;
        }
        [x, y]
    }

    /// Whether `pos` lies in object `i`'s quadrant of the goal bin, less than 10 cm above
    /// the bin's centre height (robosuite's `not not_in_bin(pos, i)`).
    pub fn in_target_bin(&self, pos: [f64; 3], i: usize) -> bool {
        let [x_low, y_low] = self.quadrant_low(i);
        let x_high = x_low + self.bin_size[0] / 2.0;
        let y_high = y_low + self.bin_size[1] / 2.0;
        x_low < pos[0]
            && pos[0] < x_high
            && y_low < pos[1]
            && pos[1] < y_high
            && self.bin2_pos[2] < pos[2]
            && pos[2] < self.bin2_pos[2] + 0.1
    }

    /// The centre of object `i`'s quadrant at the goal bin's height (robosuite's
    /// `target_bin_placements[i]`).
    pub fn target_bin_placement(&self, i: usize) -> [f64; 3] {
        let [x, y] = self.quadrant_low(i);
        [
            x + self.bin_size[0] / 4.0,
            y + self.bin_size[1] / 4.0,
            self.bin2_pos[2],
        ]
    }

    fn validate(&self) -> Result<()> {
        let finite = self
            .bin1_pos
            .iter()
            .chain(&self.bin2_pos)
            .chain(&[self.z_offset])
            .all(|v| v.is_finite());
        if !finite {
            return Err(Error::invalid_argument(
                "bin1_pos",
                format!(
                    "bin positions and z_offset must be finite, got {:?}, {:?}, {}",
                    self.bin1_pos, self.bin2_pos, self.z_offset
                ),
            ));
        }
        let x_half = self.bin_size[0] / 2.0 - 0.05;
        let y_half = self.bin_size[1] / 2.0 - 0.05;
        if !(x_half > 0.0 && y_half > 0.0) {
            return Err(Error::invalid_argument(
                "table_full_size",
                format!(
                    "the bins must be larger than 0.1 × 0.1, got {:?}",
                    self.bin_size
                ),
            ));
        }
        Self::new(self.mode).map(|_| ())
    }

    /// robosuite's sampler for the objects: uniform in bin 1 less 5 cm at each wall, kept
    /// inside by each object's radius, non-overlapping, yawed by `z_rotation`.
    fn object_sampler(&self) -> UniformRandomSampler {
        let x_half = self.bin_size[0] / 2.0 - 0.05;
        let y_half = self.bin_size[1] / 2.0 - 0.05;
        UniformRandomSampler {
            x_range: [-x_half, x_half],
            y_range: [-y_half, y_half],
            rotation: self.z_rotation,
            rotation_axis: Axis::Z,
            ensure_object_boundary_in_range: true,
            ensure_valid_placement: true,
            reference_pos: self.bin1_pos,
            z_offset: self.z_offset,
        }
    }

    /// robosuite's sampler for visual object `i`: the centre of its quadrant, relative to
    /// bin 1, unrotated, at the goal bin's height.
    fn visual_sampler(&self, i: usize) -> UniformRandomSampler {
        let [x_low, y_low] = self.quadrant_low(i);
        let center = [
            (x_low + (x_low + self.bin_size[0] / 2.0)) / 2.0,
            (y_low + (y_low + self.bin_size[1] / 2.0)) / 2.0,
        ];
        let rel = [center[0] - self.bin1_pos[0], center[1] - self.bin1_pos[1]];
        UniformRandomSampler {
            x_range: [rel[0], rel[0]],
            y_range: [rel[1], rel[1]],
            rotation: Rotation::Fixed(0.0),
            rotation_axis: Axis::Z,
            ensure_object_boundary_in_range: false,
            ensure_valid_placement: false,
            reference_pos: self.bin1_pos,
            z_offset: self.bin2_pos[2] - self.bin1_pos[2],
        }
    }
}

impl TaskSpec for PickPlaceSpec {
    fn options(&self) -> TaskOptions {
        self.task_options()
    }

    fn configure(&mut self, options: &TaskOptions) -> Result<()> {
        self.set_task_options(options)
    }

    fn name(&self) -> &str {
        match self.mode {
            ObjectMode::All => "PickPlace",
            ObjectMode::RandomSingle => "PickPlaceSingle",
            ObjectMode::Single(i) => SINGLE_VARIANTS.get(i).copied().unwrap_or("PickPlace"),
        }
    }

    /// robosuite's `_load_model`: the robot at the bins' base offset, the bins arena at the
    /// origin, then the visual objects (`VisualMilk`, ...: visual geoms only, no joint) and
    /// the objects (`Milk`, ...: a free joint with damping 0.0005, collision geoms doubled
    /// by visual copies), robosuite's `visual_objects + objects`.
    fn build(&self, assets: &Assets, _robots: &mut [RobotModel]) -> Result<TaskScene> {
        self.validate()?;
        let mut arena = Arena::bins(assets, self.bin1_pos, self.bin_size)?;
        arena.set_origin([0.0; 3])?;
        let mut objects = Vec::with_capacity(2 * PICK_PLACE_OBJECTS.len());
        for (name, file) in PICK_PLACE_OBJECTS.iter().zip(OBJECT_FILES) {
            objects.push(xml_object(
                assets,
                &format!("objects/{file}-visual.xml"),
                &format!("Visual{name}"),
                &Joints::None,
                ObjType::Visual,
                true,
            )?);
        }
        for (name, file) in PICK_PLACE_OBJECTS.iter().zip(OBJECT_FILES) {
            objects.push(xml_object(
                assets,
                &format!("objects/{file}.xml"),
                name,
                &Joints::free_with_damping("0.0005"),
                ObjType::All,
                true,
            )?);
        }
        Ok(TaskScene {
            arena,
            objects,
            attached: Vec::new(),
        })
    }

    fn bind(&self, scene: &TaskScene, model: &MjModel, robots: &[Robot]) -> Result<Box<dyn Task>> {
        let n = PICK_PLACE_OBJECTS.len();
        let (visuals, objects) = scene.objects.split_at(n);
        let objects = ModeObjects::bind(model, objects, self.mode, robots)?;
        let visual_bodies = visuals
            .iter()
            .map(|v| body_id(model, &v.root_body()))
            .collect::<Result<Vec<_>>>()?;
        // The visual samplers' ranges are single points and their rotation fixed: their
        // placement is the same at every reset (whatever the RNG), so it is drawn once here.
        let mut fixed_rng = rng_from_seed(0);
        let visual_poses = visuals
            .iter()
            .enumerate()
            .map(|(i, v)| {
                Ok(self
                    .visual_sampler(i)
                    .sample(&mut fixed_rng, &[v.placement()], &[])?[0])
            })
            .collect::<Result<Vec<Pose>>>()?;
        let task = PickPlace {
            spec: self.clone(),
            name: self.name().to_owned(),
            sampler: self.object_sampler(),
            extents: scene.objects[n..]
                .iter()
                .map(ObjectModel::placement)
                .collect(),
            objects,
            visual_bodies,
            visual_poses,
            bins: [body_id(model, "bin1")?, body_id(model, "bin2")?],
        };
        // robosuite's order: the inactive world pose first, then the objects'.
        let observables = task
            .objects
            .sensors()
            .world_pose_observables(|t: &PickPlace| t.objects.sensors())
            .into_iter()
            .chain(task.objects.observables(
                |t: &PickPlace| t.objects.sensors(),
                |t: &PickPlace| t.objects.active(),
                &PICK_PLACE_OBJECTS,
                "obj",
            ))
            .collect();
        Ok(Bound::boxed(task, observables))
    }
}

/// The bound PickPlace task.
///
/// * Scene: robosuite's `BinsArena`; the robot at the bins' base offset; the visual targets
///   `VisualMilk`, `VisualBread`, `VisualCereal`, `VisualCan` (no joint, no collision), then
///   the objects `Milk`, `Bread`, `Cereal`, `Can` (meshes from robosuite's files, free
///   joints `{Obj}_joint0`).
/// * Reset: the objects uniform in bin 1 (x ±0.145, y ±0.195 around its centre, kept
///   inside by each object's radius), yaw `U(0, 2π)`, no overlap, the bottom site at bin
///   1's centre height (as robosuite: 2 cm below the floor's top, whose contacts push the
///   objects out in the first step); the visual targets at the centres of their quadrants of bin 2 (written
///   into the model's `body_pos` / `body_quat`, the same at every reset); the bins at
///   `bin1_pos` / `bin2_pos`; then the single modes' choice and parking (see
///   [`ModeObjects`]).
/// * Success: every object (single modes: one) in its quadrant of bin 2 (at most 10 cm
///   above the bin's centre height) with the grip site more than 0.0424 m away
///   (`1 − tanh(10·d) < 0.6`).
/// * Reward: the number of objects in place plus, shaped, the largest staged reward (reach
///   0.1, grasp 0.35, lift up to 0.5, hover up to 0.7), times `reward_scale` (÷ 4 in mode 0).
/// * Task state: the object in play (single modes), then the object sensors' cache.
#[derive(Debug, Clone)]
pub struct PickPlace {
    spec: PickPlaceSpec,
    name: String,
    sampler: UniformRandomSampler,
    extents: Vec<PlacedObject>,
    objects: ModeObjects,
    visual_bodies: Vec<usize>,
    visual_poses: Vec<Pose>,
    bins: [usize; 2],
}

impl PickPlace {
    /// The objects (in robosuite's order) and the single-object mode.
    pub fn objects(&self) -> &ModeObjects {
        &self.objects
    }

    /// The settings.
    pub fn spec(&self) -> &PickPlaceSpec {
        &self.spec
    }

    /// robosuite's `objects_in_bins` (as `_check_success` updates it): each object in its
    /// quadrant with the (nearest) grip site more than 0.0424 m away.
    pub fn objects_in_bins(&self, sim: &Sim, robots: &[Robot]) -> [bool; 4] {
        std::array::from_fn(|i| {
            let p = self.objects.pos(sim, i);
            let r_reach = 1.0 - (10.0 * robot0_eef_dist(sim, robots, p)).tanh();
            self.spec.in_target_bin(p, i) && r_reach < 0.6
        })
    }

    /// robosuite's `staged_rewards`: `[reach, grasp, lift, hover]` over the objects not in
    /// their quadrant (parked ones included).
    pub fn staged_rewards(&self, sim: &Sim, robots: &[Robot], in_bins: &[bool; 4]) -> [f64; 4] {
        let mask = ModeObjects::unplaced(in_bins);
        let z_target = self.spec.bin2_pos[2] + 0.25;
        let [r_reach, r_grasp, r_lift] = self.objects.reach_grasp_lift(
            sim,
            robots,
            mask,
            |i| self.objects.pos(sim, i),
            z_target,
        );
        let mut r_hover = 0.0;
        if mask != 0 {
            let (qx, qy) = (self.spec.bin_size[0] / 4.0, self.spec.bin_size[1] / 4.0);
            r_hover = (0..PICK_PLACE_OBJECTS.len())
                .filter(|i| mask & (1 << i) != 0)
                .map(|i| {
                    let p = self.objects.pos(sim, i);
                    let t = self.spec.target_bin_placement(i);
                    let above = (p[1] - t[1]).abs() < qy && (p[0] - t[0]).abs() < qx;
                    let d = ((t[0] - p[0]).powi(2) + (t[1] - p[1]).powi(2)).sqrt();
                    let base = if above { LIFT_MULT } else { r_lift };
                    base + (1.0 - (10.0 * d).tanh()) * (HOVER_MULT - LIFT_MULT)
                })
                .fold(f64::NEG_INFINITY, f64::max);
        }
        [r_reach, r_grasp, r_lift, r_hover]
    }

    /// Writes what robosuite places through the model: the visual targets and the bins.
    fn place_fixed(&self, sim: &mut Sim) {
        let model = sim.model_mut();
        for (&body, (pos, quat)) in self.visual_bodies.iter().zip(&self.visual_poses) {
            model.body_pos_mut()[body] = *pos;
            model.body_quat_mut()[body] = *quat;
        }
        model.body_pos_mut()[self.bins[0]] = self.spec.bin1_pos;
        model.body_pos_mut()[self.bins[1]] = self.spec.bin2_pos;
    }
}

impl TaskLogic for PickPlace {
    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let poses = self.sampler.sample(rng, &self.extents, &[])?;
        for (body, (pos, quat)) in self.objects.bodies().iter().zip(poses) {
            body.set_pose(sim, pos, quat);
        }
        self.place_fixed(sim);
        self.objects.choose_and_park(sim, rng);
        Ok(())
    }

    fn clear_observation_cache(&mut self) {
        self.objects.clear_cache();
    }

    fn after_observe(&mut self, sim: &Sim) {
        self.objects.remember(sim);
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let in_bins = self.objects_in_bins(sim, robots);
        self.objects.mode().reward(
            &in_bins,
            || self.staged_rewards(sim, robots, &in_bins),
            config,
        )
    }

    fn check_success(&self, sim: &Sim, robots: &[Robot]) -> bool {
        self.objects
            .mode()
            .is_success(&self.objects_in_bins(sim, robots))
    }

    fn save_state(&self) -> Vec<f64> {
        self.objects.save()
    }

    fn load_state(&mut self, sim: &mut Sim, state: &[f64]) -> Result<()> {
        self.objects.load(&self.name, state)?;
        self.place_fixed(sim);
        Ok(())
    }
}
