//! robosuite's `NutAssembly` family: fit the square nut on the square peg and the round nut
//! on the round peg (`environments/manipulation/nut_assembly.py`).

use super::common::{ObjectMode, robot0_eef_dist};
use super::mode_objects::ModeArgs;
use super::mode_objects::{HOVER_MULT, LIFT_MULT, ModeObjects};
use super::options::TaskOptions;
use super::{Bound, RewardConfig, Task, TaskLogic, TaskScene, TaskSpec};
use crate::assets::Assets;
use crate::models::arenas::Arena;
use crate::models::objects::{Joints, ObjType, ObjectModel, xml_object};
use crate::models::robots::RobotModel;
use crate::placement::{
    Axis, PlacedObject, Rotation, SequentialCompositeSampler, UniformRandomSampler,
};
use crate::robots::Robot;
use crate::sim::{Sim, body_id, site_id};
use gym_core::{EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;

/// The nuts, in robosuite's order (their ids): square 0 (goes on `peg1`), round 1 (`peg2`).
pub const NUTS: [&str; 2] = ["SquareNut", "RoundNut"];

/// The nut files.
const NUT_FILES: [&str; 2] = ["objects/square-nut.xml", "objects/round-nut.xml"];

/// The single-nut variants (mode 2), by nut id.
const SINGLE_VARIANTS: [&str; 2] = ["NutAssemblySquare", "NutAssemblyRound"];

/// The y range of each nut's sampler, relative to the table centre.
const NUT_Y_RANGES: [[f64; 2]; 2] = [[0.11, 0.225], [-0.225, -0.11]];

/// NutAssembly's settings (robosuite's constructor defaults).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct NutAssemblySpec {
    #[serde(skip)]
    mode: ObjectMode,
    /// A registered variant (robosuite's subclasses) fixes the mode.
    #[serde(skip)]
    fixed_mode: bool,
    /// The table's full size (default 0.8 × 0.8 × 0.05).
    pub table_full_size: [f64; 3],
    /// The table's friction (default `(1, 0.005, 0.0001)`).
    pub table_friction: [f64; 3],
    /// The table top's centre (default (0, 0, 0.82)).
    pub table_offset: [f64; 3],
    /// robosuite's `placement_initializer`: a sampler that replaces the task's own (it
    /// places every object of the task); `None` (the default) keeps robosuite's.
    #[serde(default)]
    pub placement_initializer: Option<UniformRandomSampler>,
}

impl Default for NutAssemblySpec {
    fn default() -> Self {
        Self {
            mode: ObjectMode::All,
            fixed_mode: false,
            table_full_size: [0.8, 0.8, 0.05],
            table_friction: [1.0, 5e-3, 1e-4],
            table_offset: [0.0, 0.0, 0.82],
            placement_initializer: None,
        }
    }
}

impl NutAssemblySpec {
    /// robosuite's `single_object_mode` and `nut_type`.
    const MODE_ARGS: ModeArgs = ModeArgs {
        type_key: "nut_type",
        types: &["square", "round"],
    };

    /// robosuite's constructor arguments (see [`TaskSpec::options`]); the base task also
    /// lists `single_object_mode` and `nut_type`.
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

    /// robosuite's defaults in `mode` (robosuite's `single_object_mode` and `nut_type`:
    /// [`ObjectMode::Single`] takes the nut id, square 0, round 1).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a nut id above 1.
    pub fn new(mode: ObjectMode) -> Result<Self> {
        if let ObjectMode::Single(i) = mode
            && i >= NUTS.len()
        {
            return Err(Error::invalid_argument(
                "nut_type",
                format!("nut id {i} is not one of 0 (square), 1 (round)"),
            ));
        }
        Ok(Self {
            mode,
            ..Self::default()
        })
    }

    /// The registered variant `name` (`NutAssembly`, `NutAssemblySingle`,
    /// `NutAssemblySquare`, `NutAssemblyRound`), if it is one.
    pub fn variant(name: &str) -> Option<Self> {
        let mode = match name {
            "NutAssembly" => ObjectMode::All,
            "NutAssemblySingle" => ObjectMode::RandomSingle,
            _ => ObjectMode::Single(SINGLE_VARIANTS.iter().position(|v| *v == name)?),
        };
        Some(Self {
            fixed_mode: name != "NutAssembly",
            ..Self::new(mode).ok()?
        })
    }

    /// The single-object mode.
    pub fn mode(&self) -> ObjectMode {
        self.mode
    }

    /// robosuite's default placement: a `SequentialCompositeSampler` with one sampler per
    /// nut (`SquareNutSampler`, `RoundNutSampler`): x in [−0.115, −0.11], y in
    /// [0.11, 0.225] (square) or [−0.225, −0.11] (round) around the table top, yaw
    /// `U(0, 2π)`, 2 cm above the table, the round nut clear of the square one.
    fn sampler(&self) -> SequentialCompositeSampler {
        if let Some(user) = &self.placement_initializer {
            // robosuite adds every nut to the given sampler.
            return SequentialCompositeSampler {
                samplers: vec![(user.clone(), (0..NUTS.len()).collect())],
            };
        }
        SequentialCompositeSampler {
            samplers: NUT_Y_RANGES
                .iter()
                .enumerate()
                .map(|(i, y_range)| {
                    let sampler = UniformRandomSampler {
                        x_range: [-0.115, -0.11],
                        y_range: *y_range,
                        rotation: Rotation::Random,
                        rotation_axis: Axis::Z,
                        ensure_object_boundary_in_range: false,
                        ensure_valid_placement: true,
                        reference_pos: self.table_offset,
                        z_offset: 0.02,
                    };
                    (sampler, vec![i])
                })
                .collect(),
        }
    }
}

impl TaskSpec for NutAssemblySpec {
    fn options(&self) -> TaskOptions {
        self.task_options()
    }

    fn configure(&mut self, options: &TaskOptions) -> Result<()> {
        self.set_task_options(options)
    }

    fn name(&self) -> &str {
        match self.mode {
            ObjectMode::All => "NutAssembly",
            ObjectMode::RandomSingle => "NutAssemblySingle",
            ObjectMode::Single(i) => SINGLE_VARIANTS.get(i).copied().unwrap_or("NutAssembly"),
        }
    }

    /// robosuite's `_load_model`: the robot at the table's base offset, `PegsArena` at the
    /// origin, then the nuts `SquareNut` and `RoundNut` (free joints with damping 0.0005,
    /// collision geoms doubled by visual copies).
    fn build(&self, assets: &Assets, _robots: &mut [RobotModel]) -> Result<TaskScene> {
        Self::new(self.mode)?;
        let mut arena = Arena::table(
            assets,
            "arenas/pegs_arena.xml",
            self.table_full_size,
            self.table_friction,
            self.table_offset,
        )?;
        arena.set_origin([0.0; 3])?;
        let objects = NUTS
            .iter()
            .zip(NUT_FILES)
            .map(|(name, file)| {
                xml_object(
                    assets,
                    file,
                    name,
                    &Joints::free_with_damping("0.0005"),
                    ObjType::All,
                    true,
                )
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(TaskScene {
            arena,
            objects,
            attached: Vec::new(),
        })
    }

    fn bind(&self, scene: &TaskScene, model: &MjModel, robots: &[Robot]) -> Result<Box<dyn Task>> {
        let handles = scene
            .objects
            .iter()
            .map(|nut| site_id(model, &nut.name_of("handle_site")))
            .collect::<Result<Vec<_>>>()?;
        let task = NutAssembly {
            spec: self.clone(),
            name: self.name().to_owned(),
            sampler: self.sampler(),
            extents: scene.objects.iter().map(ObjectModel::placement).collect(),
            nuts: ModeObjects::bind(model, &scene.objects, self.mode, robots)?,
            handles,
            pegs: [body_id(model, "peg1")?, body_id(model, "peg2")?],
            table: body_id(model, "table")?,
        };
        // robosuite's order: the inactive world pose first, then the nuts'.
        let observables = task
            .nuts
            .sensors()
            .world_pose_observables(|t: &NutAssembly| t.nuts.sensors())
            .into_iter()
            .chain(task.nuts.observables(
                |t: &NutAssembly| t.nuts.sensors(),
                |t: &NutAssembly| t.nuts.active(),
                &NUTS,
                "nut",
            ))
            .collect();
        Ok(Bound::boxed(task, observables))
    }
}

/// The bound NutAssembly task.
///
/// * Scene: robosuite's `PegsArena` (a 0.8 × 0.8 table with its top at z = 0.82, the square
///   peg `peg1` at (0.23, 0.1) and the round peg `peg2` at (0.23, −0.1)); the robot at the
///   table's base offset; the nuts `SquareNut` and `RoundNut` (boxes from robosuite's files,
///   free joints `{Nut}_joint0`, handle sites `{Nut}_handle_site`).
/// * Reset: robosuite's sequential sampler (see [`NutAssemblySpec`]), then the single
///   modes' choice and parking (see [`ModeObjects`]).
/// * `on_peg`: |dx|, |dy| < 0.03 between the nut's and its peg's bodies, the nut lower
///   than the table top + 0.05. Success: every nut (single modes: one) on its peg with the
///   grip site more than 0.0424 m from the nut (`1 − tanh(10·d) < 0.6`).
/// * Reward: the number of nuts on their pegs plus, shaped, the largest staged reward
///   (reach 0.1 to the handle site, grasp 0.35, lift up to 0.5 towards 0.2 above the
///   table body, hover `r_lift + 0.2·(1 − tanh(10·d_xy(nut, peg)))`), times
///   `reward_scale` (÷ 2 in mode 0).
/// * Task state: the nut in play (single modes), then the nut sensors' cache.
#[derive(Debug, Clone)]
pub struct NutAssembly {
    spec: NutAssemblySpec,
    name: String,
    sampler: SequentialCompositeSampler,
    extents: Vec<PlacedObject>,
    nuts: ModeObjects,
    handles: Vec<usize>,
    pegs: [usize; 2],
    table: usize,
}

impl NutAssembly {
    /// The nuts (in robosuite's order) and the single-object mode.
    pub fn nuts(&self) -> &ModeObjects {
        &self.nuts
    }

    /// robosuite's `on_peg(pos, i)`: `pos` within 3 cm of peg `i` in x and y, and below
    /// the table top + 0.05.
    pub fn on_peg(&self, sim: &Sim, pos: [f64; 3], i: usize) -> bool {
        let peg = sim.data().xpos()[self.pegs[i]];
        (pos[0] - peg[0]).abs() < 0.03
            && (pos[1] - peg[1]).abs() < 0.03
            && pos[2] < self.spec.table_offset[2] + 0.05
    }

    /// robosuite's `objects_on_pegs` (as `_check_success` updates it): each nut on its peg
    /// with the grip site more than 0.0424 m away.
    pub fn objects_on_pegs(&self, sim: &Sim, robots: &[Robot]) -> [bool; 2] {
        std::array::from_fn(|i| {
            let p = self.nuts.pos(sim, i);
            let r_reach = 1.0 - (10.0 * robot0_eef_dist(sim, robots, p)).tanh();
            self.on_peg(sim, p, i) && r_reach < 0.6
        })
    }

    /// robosuite's `staged_rewards`: `[reach, grasp, lift, hover]` over the nuts not on
    /// their pegs (a parked one included).
    pub fn staged_rewards(&self, sim: &Sim, robots: &[Robot], on_pegs: &[bool; 2]) -> [f64; 4] {
        let mask = ModeObjects::unplaced(on_pegs);
        let d = sim.data();
        let z_target = d.xpos()[self.table][2] + 0.2;
        let [r_reach, r_grasp, r_lift] = self.nuts.reach_grasp_lift(
            sim,
            robots,
            mask,
            |i| d.site_xpos()[self.handles[i]],
            z_target,
        );
        let mut r_hover = 0.0;
        if mask != 0 {
            r_hover = (0..NUTS.len())
                .filter(|i| mask & (1 << i) != 0)
                .map(|i| {
                    let peg = d.xpos()[self.pegs[i]];
                    let p = self.nuts.pos(sim, i);
                    let dist = ((peg[0] - p[0]).powi(2) + (peg[1] - p[1]).powi(2)).sqrt();
                    r_lift + (1.0 - (10.0 * dist).tanh()) * (HOVER_MULT - LIFT_MULT)
                })
                .fold(f64::NEG_INFINITY, f64::max);
        }
        [r_reach, r_grasp, r_lift, r_hover]
    }
}

impl TaskLogic for NutAssembly {
    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let poses = self.sampler.sample(rng, &self.extents)?;
        for (body, (pos, quat)) in self.nuts.bodies().iter().zip(poses) {
            body.set_pose(sim, pos, quat);
        }
        self.nuts.choose_and_park(sim, rng);
        Ok(())
    }

    fn clear_observation_cache(&mut self) {
        self.nuts.clear_cache();
    }

    fn after_observe(&mut self, sim: &Sim) {
        self.nuts.remember(sim);
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let on_pegs = self.objects_on_pegs(sim, robots);
        self.nuts.mode().reward(
            &on_pegs,
            || self.staged_rewards(sim, robots, &on_pegs),
            config,
        )
    }

    fn check_success(&self, sim: &Sim, robots: &[Robot]) -> bool {
        self.nuts
            .mode()
            .is_success(&self.objects_on_pegs(sim, robots))
    }

    fn save_state(&self) -> Vec<f64> {
        self.nuts.save()
    }

    fn load_state(&mut self, _sim: &mut Sim, state: &[f64]) -> Result<()> {
        self.nuts.load(&self.name, state)
    }
}
