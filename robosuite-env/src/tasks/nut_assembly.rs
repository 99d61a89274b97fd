//! robosuite's `NutAssembly` family: fit the square nut on the square peg and the round nut
//! on the round peg (`nut_assembly.py`).

use super::common::{
    FreeBody, ObjectMode, PARKED_POS, dist, eef_pos, is_grasped, write_object_pose_obs,
};
use super::placement::{Axis, PlacedObject, Pose, Rotation, UniformRandomSampler};
use super::{ModelSource, RewardConfig, Task};
use crate::models::arenas::TableArena;
use crate::models::objects::{PrimitiveGeom, PrimitiveObject};
use crate::models::scene::SceneBuilder;
use crate::observations::ObsKey;
use crate::robots::Robot;
use crate::sim::{GeomSet, Sim, body_id, site_id};
use gym_core::{EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use rand::RngExt;
use std::f64::consts::FRAC_PI_4;

/// The nuts, in robosuite's order (their ids): square 0 (peg1), round 1 (peg2).
pub const NUTS: [&str; 2] = ["SquareNut", "RoundNut"];

/// The table top of the pegs arena.
pub const PEGS_TABLE_TOP: [f64; 3] = [0.0, 0.0, 0.82];

/// The peg positions (bodies `peg1`, `peg2`).
pub const PEG_POS: [[f64; 3]; 2] = [[0.23, 0.10, 0.85], [0.23, -0.10, 0.85]];

/// The pegs arena: Lift's table with its top at z = 0.82 and the two pegs (`peg1`: box
/// half-extents (0.016, 0.016, 0.1); `peg2`: cylinder radius 0.02, half-length 0.1).
pub fn pegs_arena_xml() -> String {
    let table = TableArena {
        top: PEGS_TABLE_TOP,
        ..TableArena::default()
    }
    .to_xml();
    let [p1, p2] = PEG_POS;
    let pegs = format!(
        r#"<body name="peg1" pos="{} {} {}">
      <geom name="peg1_g0" type="box" size="0.016 0.016 0.1" group="0" rgba="0.5 0.5 0.6 1"/>
    </body>
    <body name="peg2" pos="{} {} {}">
      <geom name="peg2_g0" type="cylinder" size="0.02 0.1" group="0" rgba="0.6 0.5 0.4 1"/>
    </body>
  </worldbody>"#,
        p1[0], p1[1], p1[2], p2[0], p2[1], p2[2]
    );
    table.replacen("</worldbody>", &pegs, 1)
}

/// A nut as robosuite builds it from boxes: square (a square ring of inner half-width
/// 0.02275 with walls 0.021 thick) or round (an octagonal ring of inner radius ≈ 0.031), 2 cm
/// thick, with a handle of 0.0505 × 0.03175 m on +x carrying the site `handle_site`;
/// density 100, friction (0.95, 0.3, 0.1), condim 4, free-joint damping 0.0005.
fn nut_object(i: usize) -> PrimitiveObject {
    let b = |h: [f64; 3], p: [f64; 3]| PrimitiveGeom::new("box", &h, p);
    let handle_x;
    let mut geoms = if i == 0 {
        handle_x = 0.054;
        vec![
            b([0.0105, 0.04375, 0.01], [-0.03325, 0.0, 0.0]),
            b([0.03125, 0.0105, 0.01], [0.0, 0.03325, 0.0]),
            b([0.03125, 0.0105, 0.01], [0.0, -0.03325, 0.0]),
            b([0.0105, 0.04375, 0.01], [0.03325, 0.0, 0.0]),
        ]
    } else {
        handle_x = 0.06;
        let (s, c) = (FRAC_PI_4 / 2.0).sin_cos();
        let rot = [c, 0.0, 0.0, s];
        let side = [0.01125, 0.0225, 0.01];
        let across = [0.0225, 0.01125, 0.01];
        vec![
            b(side, [-0.04245, 0.0, 0.0]),
            b(side, [0.04245, 0.0, 0.0]),
            b(across, [0.0, -0.04245, 0.0]),
            b(across, [0.0, 0.04245, 0.0]),
            b(side, [-0.03, -0.03, 0.0]).rotated(rot),
            b(side, [0.03, 0.03, 0.0]).rotated(rot),
            b(across, [0.03, -0.03, 0.0]).rotated(rot),
            b(across, [-0.03, 0.03, 0.0]).rotated(rot),
        ]
    };
    geoms.push(b([0.02525, 0.015875, 0.01], [handle_x, 0.0, 0.0]));
    let rgba = if i == 0 {
        [0.2, 0.3, 0.8, 1.0]
    } else {
        [0.7, 0.7, 0.7, 1.0]
    };
    let mut obj = PrimitiveObject::new(geoms, 100.0, rgba);
    obj.friction = [0.95, 0.3, 0.1];
    obj.solref = if i == 0 { [0.02, 0.5] } else { [0.02, 1.0] };
    obj.solimp = [0.998, 0.998, 0.001];
    obj.condim = 4;
    obj.joint_damping = 0.0005;
    obj.extra = format!(
        r#"<site name="handle_site" pos="{handle_x} 0 0" size="0.005" rgba="0 0 0 0" group="1"/>"#
    );
    obj
}

/// The sampler's view of nut `i` (robosuite's bottom/top/horizontal-radius sites).
fn nut_extent(i: usize) -> PlacedObject {
    if i == 0 {
        PlacedObject {
            horizontal_radius: 0.11f64.hypot(0.06),
            bottom_offset: -0.05,
            top_offset: 0.01,
        }
    } else {
        PlacedObject {
            horizontal_radius: 0.11f64.hypot(0.05),
            bottom_offset: -0.05,
            top_offset: 0.025,
        }
    }
}

/// The NutAssembly family (`NutAssembly`, `NutAssemblySingle`, `NutAssemblySquare`,
/// `NutAssemblyRound`).
///
/// * Arena: [`pegs_arena_xml`]; robot base at (−0.56, 0, 0.912).
/// * Nuts `SquareNut` and `RoundNut` (bodies `{Nut}_main`, free joints `{Nut}_joint0`,
///   geoms `{Nut}_g*`, sites `{Nut}_handle_site`).
/// * Reset (robosuite's `SequentialCompositeSampler`): square nut x ∈ U(−0.115, −0.11),
///   y ∈ U(0.11, 0.225); round nut x ∈ U(−0.115, −0.11), y ∈ U(−0.225, −0.11); yaw
///   `U(0, 2π)`; 2 cm above the table by robosuite's bottom offsets; no overlap. In single
///   modes the other nut is parked at (10, 10, 10).
/// * `on_peg`: |dx|, |dy| < 0.03 to the peg and z < 0.87; a nut counts once on its peg with
///   the gripper farther than 0.0424 m. Success: all nuts (single modes: one).
/// * Reward: the number of nuts placed plus, shaped, the best staged reward (reach 0.1,
///   grasp 0.35, lift up to 0.5, hover up to 0.7); times `reward_scale` (÷ 2 with both nuts).
#[derive(Debug, Clone)]
pub struct NutAssembly {
    name: String,
    mode: ObjectMode,
    active: usize,
    nuts: Vec<FreeBody>,
    handles: Vec<usize>,
    pegs: Vec<usize>,
    table_z: f64,
}

impl NutAssembly {
    /// The variant registered as `name`.
    ///
    /// # Errors
    /// [`Error::UnknownEnv`] for another name.
    pub fn variant(name: &str) -> Result<Self> {
        let mode = match name {
            "NutAssembly" => ObjectMode::All,
            "NutAssemblySingle" => ObjectMode::RandomSingle,
            "NutAssemblySquare" => ObjectMode::Single(0),
            "NutAssemblyRound" => ObjectMode::Single(1),
            _ => {
                return Err(Error::UnknownEnv {
                    id: name.to_owned(),
                    available: crate::ENV_NAMES.iter().map(|s| (*s).to_owned()).collect(),
                });
            }
        };
        Ok(Self {
            name: name.to_owned(),
            mode,
            active: match mode {
                ObjectMode::Single(i) => i,
                _ => 0,
            },
            nuts: Vec::new(),
            handles: Vec::new(),
            pegs: Vec::new(),
            table_z: PEGS_TABLE_TOP[2] - 0.025,
        })
    }

    /// The single-object mode.
    pub fn mode(&self) -> ObjectMode {
        self.mode
    }

    /// The nut in play (single modes).
    pub fn active_nut(&self) -> usize {
        self.active
    }

    /// robosuite's `on_peg` for nut `i` at `pos`.
    pub fn on_peg(&self, sim: &Sim, pos: [f64; 3], i: usize) -> bool {
        let peg = sim.data().xpos()[self.pegs[i]];
        (pos[0] - peg[0]).abs() < 0.03
            && (pos[1] - peg[1]).abs() < 0.03
            && pos[2] < PEGS_TABLE_TOP[2] + 0.05
    }

    /// robosuite's `objects_on_pegs`.
    pub fn objects_on_pegs(&self, sim: &Sim, robots: &[Robot]) -> [bool; 2] {
        let eef = eef_pos(sim, robots);
        std::array::from_fn(|i| {
            let p = self.nuts[i].pos(sim);
            self.on_peg(sim, p, i) && 1.0 - (10.0 * dist(eef, p)).tanh() < 0.6
        })
    }

    /// robosuite's `staged_rewards`: `(reach, grasp, lift, hover)`.
    pub fn staged_rewards(&self, sim: &Sim, robots: &[Robot], on: &[bool; 2]) -> [f64; 4] {
        let (reach_mult, grasp_mult, lift_mult, hover_mult) = (0.1, 0.35, 0.5, 0.7);
        let active: Vec<usize> = (0..2).filter(|&i| !on[i]).collect();
        if active.is_empty() {
            return [0.0; 4];
        }
        let eef = eef_pos(sim, robots);
        let d = sim.data();
        let min_d = active
            .iter()
            .map(|&i| dist(eef, d.site_xpos()[self.handles[i]]))
            .fold(f64::INFINITY, f64::min);
        let r_reach = (1.0 - (10.0 * min_d).tanh()) * reach_mult;
        let geoms = GeomSet::new(
            active
                .iter()
                .flat_map(|&i| self.nuts[i].geoms.ids().to_vec())
                .map(|g| g as usize),
        );
        let r_grasp = if is_grasped(sim, robots, &geoms) {
            grasp_mult
        } else {
            0.0
        };
        let mut r_lift = 0.0;
        if r_grasp > 0.0 {
            let z_target = self.table_z + 0.2;
            let min_z = active
                .iter()
                .map(|&i| (z_target - self.nuts[i].pos(sim)[2]).max(0.0))
                .fold(f64::INFINITY, f64::min);
            r_lift = grasp_mult + (1.0 - (15.0 * min_z).tanh()) * (lift_mult - grasp_mult);
        }
        let r_hover = active
            .iter()
            .map(|&i| {
                let p = self.nuts[i].pos(sim);
                let peg = d.xpos()[self.pegs[i]];
                r_lift
                    + (1.0 - (10.0 * (peg[0] - p[0]).hypot(peg[1] - p[1])).tanh())
                        * (hover_mult - lift_mult)
            })
            .fold(f64::NEG_INFINITY, f64::max);
        [r_reach, r_grasp, r_lift, r_hover]
    }
}

impl Task for NutAssembly {
    fn name(&self) -> &str {
        &self.name
    }

    fn robot_base_pose(&self, _index: usize) -> ([f64; 3], [f64; 4]) {
        ([-0.16 - 0.8 / 2.0, 0.0, 0.912], [1.0, 0.0, 0.0, 0.0])
    }

    fn arena_xml(&self) -> String {
        pegs_arena_xml()
    }

    fn build_objects(&self, scene: &mut SceneBuilder) -> Result<()> {
        for (i, name) in NUTS.iter().enumerate() {
            scene.add_part(name, &nut_object(i).to_xml(name), &format!("{name}_"))?;
        }
        Ok(())
    }

    fn bind(&mut self, model: &MjModel, _robots: &[Robot], _source: ModelSource) -> Result<()> {
        self.nuts = NUTS
            .iter()
            .enumerate()
            .map(|(i, n)| {
                let count = nut_object(i).geoms.len();
                let geoms: Vec<String> = (0..count).map(|g| format!("{n}_g{g}")).collect();
                FreeBody::bind(model, &format!("{n}_main"), &format!("{n}_joint0"), &geoms)
            })
            .collect::<Result<_>>()?;
        self.handles = NUTS
            .iter()
            .map(|n| site_id(model, &format!("{n}_handle_site")))
            .collect::<Result<_>>()?;
        self.pegs = vec![body_id(model, "peg1")?, body_id(model, "peg2")?];
        self.table_z = model.body_pos()[body_id(model, "table")?][2];
        Ok(())
    }

    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let mut placed: Vec<(Pose, PlacedObject)> = Vec::new();
        for (i, y_range) in [[0.11, 0.225], [-0.225, -0.11]].into_iter().enumerate() {
            let sampler = UniformRandomSampler {
                x_range: [-0.115, -0.11],
                y_range,
                rotation: Rotation::Random,
                rotation_axis: Axis::Z,
                ensure_object_boundary_in_range: false,
                ensure_valid_placement: true,
                reference_pos: PEGS_TABLE_TOP,
                z_offset: 0.02,
            };
            let extent = nut_extent(i);
            let pose = sampler.sample(rng, &[extent], &placed)?[0];
            placed.push((pose, extent));
        }
        for (nut, ((p, q), _)) in self.nuts.iter().zip(&placed) {
            nut.set_pose(sim, *p, *q);
        }
        if self.mode == ObjectMode::RandomSingle {
            self.active = rng.random_range(0..2);
        }
        if self.mode != ObjectMode::All {
            let other = 1 - self.active;
            self.nuts[other].set_pose(sim, PARKED_POS, [1.0, 0.0, 0.0, 0.0]);
        }
        Ok(())
    }

    fn observation_keys(&self) -> Vec<ObsKey> {
        self.mode.pose_keys(&NUTS, "nut")
    }

    fn write_observations(&self, sim: &Sim, robots: &[Robot], out: &mut [f64]) {
        self.mode
            .write_pose_obs(NUTS.len(), self.active, out, |i, out| {
                let o = &self.nuts[i];
                write_object_pose_obs(sim, robots, o.pos(sim), o.quat(sim), out);
            });
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let on = self.objects_on_pegs(sim, robots);
        self.mode
            .reward(&on, || self.staged_rewards(sim, robots, &on), config)
    }

    fn check_success(&self, sim: &Sim, robots: &[Robot]) -> bool {
        self.mode.is_success(&self.objects_on_pegs(sim, robots))
    }

    fn save_state(&self) -> Vec<f64> {
        vec![self.active as f64]
    }

    fn load_state(&mut self, _sim: &mut Sim, state: &[f64]) -> Result<()> {
        match state {
            [a] => {
                self.active = (*a as usize).min(1);
                Ok(())
            }
            _ => Err(Error::invalid_argument(
                "state",
                format!("NutAssembly's state is 1 value, got {}", state.len()),
            )),
        }
    }
}
