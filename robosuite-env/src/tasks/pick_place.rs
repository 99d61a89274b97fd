//! robosuite's `PickPlace` family: move grocery objects from one bin to their quadrant of
//! the other (`pick_place.py`).

use super::common::{
    FreeBody, ObjectMode, PARKED_POS, dist, eef_pos, is_grasped, write_object_pose_obs,
};
use super::placement::{Axis, PlacedObject, Rotation, UniformRandomSampler};
use super::{ModelSource, RewardConfig, Task};
use crate::models::objects::{PrimitiveGeom, PrimitiveObject};
use crate::models::scene::SceneBuilder;
use crate::observations::ObsKey;
use crate::robots::Robot;
use crate::sim::{GeomSet, Sim, body_id};
use gym_core::{EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use rand::RngExt;

/// The objects, in robosuite's order (their ids): milk 0, bread 1, cereal 2, can 3.
pub const PICK_PLACE_OBJECTS: [&str; 4] = ["Milk", "Bread", "Cereal", "Can"];

/// Centre of the source bin (robosuite's `bin1_pos`).
pub const BIN1_POS: [f64; 3] = [0.1, -0.25, 0.8];
/// Centre of the target bin (`bin2_pos`).
pub const BIN2_POS: [f64; 3] = [0.1, 0.28, 0.8];
/// Inner size of a bin (`bin_size` = the arena's `table_full_size`).
pub const BIN_SIZE: [f64; 3] = [0.39, 0.49, 0.82];

/// The shape of one grocery object: our primitives standing in for robosuite's meshes.
#[derive(Debug, Clone, PartialEq)]
struct Shape {
    geom: PrimitiveGeom,
    density: f64,
    rgba: [f64; 4],
    radius: f64,
    half_height: f64,
}

fn shape(i: usize) -> Shape {
    let b = |h: [f64; 3]| PrimitiveGeom::new("box", &h, [0.0; 3]);
    match i {
        // Milk carton 0.05 × 0.05 × 0.14 m, density 100.
        0 => Shape {
            geom: b([0.025, 0.025, 0.07]),
            density: 100.0,
            rgba: [0.95, 0.95, 0.95, 1.0],
            radius: 0.025f64.hypot(0.025),
            half_height: 0.07,
        },
        // Bread loaf 0.07 × 0.044 × 0.075 m, density 50.
        1 => Shape {
            geom: b([0.035, 0.022, 0.0375]),
            density: 50.0,
            rgba: [0.8, 0.55, 0.25, 1.0],
            radius: 0.03f64.hypot(0.03),
            half_height: 0.0375,
        },
        // Cereal box 0.08 × 0.05 × 0.12 m, density 150.
        2 => Shape {
            geom: b([0.04, 0.025, 0.06]),
            density: 150.0,
            rgba: [0.9, 0.8, 0.2, 1.0],
            radius: 0.04f64.hypot(0.03),
            half_height: 0.06,
        },
        // Can: cylinder radius 0.032, height 0.1, density 100.
        _ => Shape {
            geom: PrimitiveGeom::new("cylinder", &[0.032, 0.05], [0.0; 3]),
            density: 100.0,
            rgba: [0.8, 0.1, 0.1, 1.0],
            radius: 0.025f64.hypot(0.025),
            half_height: 0.05,
        },
    }
}

/// The bins arena: floor, the source bin `bin1` and the target bin `bin2` (floor top at
/// z = 0.82, walls 0.1 high; the target bin divided into four quadrants).
pub fn bins_arena_xml() -> String {
    let wall = |name: &str, pos: [f64; 3], size: [f64; 3]| {
        format!(
            r#"<geom name="{name}" type="box" pos="{} {} {}" size="{} {} {}" group="0" friction="1 0.005 0.0001" rgba="0.6 0.45 0.3 1"/>"#,
            pos[0], pos[1], pos[2], size[0], size[1], size[2]
        )
    };
    let bin = |name: &str, pos: [f64; 3], dividers: bool| {
        let mut g = vec![
            wall(&format!("{name}_floor"), [0.0; 3], [0.2, 0.25, 0.02]),
            wall(
                &format!("{name}_wall_left"),
                [0.0, 0.25, 0.05],
                [0.21, 0.01, 0.05],
            ),
            wall(
                &format!("{name}_wall_right"),
                [0.0, -0.25, 0.05],
                [0.21, 0.01, 0.05],
            ),
            wall(
                &format!("{name}_wall_front"),
                [0.2, 0.0, 0.05],
                [0.01, 0.25, 0.05],
            ),
            wall(
                &format!("{name}_wall_back"),
                [-0.2, 0.0, 0.05],
                [0.01, 0.25, 0.05],
            ),
        ];
        if dividers {
            g.push(wall(
                &format!("{name}_divider_x"),
                [0.0, 0.0, 0.05],
                [0.2, 0.01, 0.05],
            ));
            g.push(wall(
                &format!("{name}_divider_y"),
                [0.0, 0.0, 0.05],
                [0.01, 0.25, 0.05],
            ));
        }
        for (k, (x, y)) in [(0.15, 0.2), (-0.15, 0.2), (-0.15, -0.2), (0.15, -0.2)]
            .iter()
            .enumerate()
        {
            g.push(format!(
                r#"<geom name="{name}_leg{}_visual" type="cylinder" pos="{x} {y} -0.4" size="0.01 0.4" contype="0" conaffinity="0" group="1" rgba="0.3 0.3 0.3 1"/>"#,
                k + 1
            ));
        }
        format!(
            r#"<body name="{name}" pos="{} {} {}">
      {}
    </body>"#,
            pos[0],
            pos[1],
            pos[2],
            g.join("\n      ")
        )
    };
    format!(
        r#"<mujoco model="bins_arena">
  <worldbody>
    <light name="key_light" pos="1.0 1.0 1.5" dir="-0.2 -0.2 -1" directional="true" diffuse="0.8 0.8 0.8" specular="0.3 0.3 0.3" castshadow="false"/>
    <geom name="floor" type="plane" pos="0 0 0" size="3 3 0.125" condim="3" group="1" contype="1" conaffinity="1" rgba="0.55 0.55 0.55 1"/>
    {}
    {}
    <camera name="frontview" mode="fixed" pos="1.6 0 1.45" quat="0.56 0.43 0.43 0.56"/>
    <camera name="birdview" mode="fixed" pos="-0.2 0 3.0" quat="0.7071 0 0 0.7071"/>
    <camera name="agentview" mode="fixed" pos="1.0 0 1.75" quat="0.653 0.271 0.271 0.653"/>
  </worldbody>
</mujoco>
"#,
        bin("bin1", BIN1_POS, false),
        bin("bin2", BIN2_POS, true)
    )
}

/// The low corner of object `i`'s target quadrant (robosuite's `not_in_bin` box).
pub fn quadrant_low(i: usize) -> [f64; 2] {
    let mut x = BIN2_POS[0];
    let mut y = BIN2_POS[1];
    if i == 0 || i == 2 {
        x -= BIN_SIZE[0] / 2.0;
    }
    if i < 2 {
        y -= BIN_SIZE[1] / 2.0;
    }
    [x, y]
}

/// The centre of object `i`'s target quadrant (`target_bin_placements`).
pub fn target_placement(i: usize) -> [f64; 3] {
    let [x, y] = quadrant_low(i);
    [x + BIN_SIZE[0] / 4.0, y + BIN_SIZE[1] / 4.0, BIN2_POS[2]]
}

/// Whether `pos` lies in object `i`'s target quadrant (0.8 < z < 0.9).
pub fn in_quadrant(pos: [f64; 3], i: usize) -> bool {
    let [x, y] = quadrant_low(i);
    x < pos[0]
        && pos[0] < x + BIN_SIZE[0] / 2.0
        && y < pos[1]
        && pos[1] < y + BIN_SIZE[1] / 2.0
        && BIN2_POS[2] < pos[2]
        && pos[2] < BIN2_POS[2] + 0.1
}

/// The PickPlace family (`PickPlace`, `PickPlaceSingle`, `PickPlaceMilk`, `PickPlaceBread`,
/// `PickPlaceCereal`, `PickPlaceCan`).
///
/// * Arena: [`bins_arena_xml`]; robot base at (−0.5, −0.1, 0.912).
/// * Objects `Milk`, `Bread`, `Cereal`, `Can` (bodies `{Obj}_main`, free joints
///   `{Obj}_joint0` with damping 0.0005, geom `{Obj}_g0`; friction (0.95, 0.3, 0.1),
///   solref (0.001, 1), solimp (0.998, 0.998, 0.001), condim 4) and the joint-less,
///   non-colliding markers `Visual{Obj}_main` at the quadrant centres.
/// * Reset: objects uniform in bin 1 (x ±0.145, y ±0.195, shrunk by their radius), yaw
///   `U(0, 2π)`, no overlap; markers at their quadrant centres (two RNG draws each); in
///   single-object modes the unused objects are parked at (10, 10, 10).
/// * Success: every object (single modes: one) in its quadrant with the gripper more than
///   0.0424 m away. Reward: the number of objects in place plus, shaped, the best staged
///   reward (reach 0.1, grasp 0.35, lift up to 0.5, hover up to 0.7); times
///   `reward_scale` (÷ 4 with all objects).
#[derive(Debug, Clone)]
pub struct PickPlace {
    name: String,
    mode: ObjectMode,
    active: usize,
    objects: Vec<FreeBody>,
    visuals: Vec<usize>,
    all_geoms: GeomSet,
    visual_pose: Vec<[f64; 3]>,
}

impl PickPlace {
    /// The variant registered as `name` (`PickPlace`, `PickPlaceSingle`, `PickPlaceMilk`,
    /// ...).
    ///
    /// # Errors
    /// [`Error::UnknownEnv`] for another name.
    pub fn variant(name: &str) -> Result<Self> {
        let mode = match name {
            "PickPlace" => ObjectMode::All,
            "PickPlaceSingle" => ObjectMode::RandomSingle,
            _ => {
                let obj = name.strip_prefix("PickPlace").unwrap_or("");
                match PICK_PLACE_OBJECTS.iter().position(|o| *o == obj) {
                    Some(i) => ObjectMode::Single(i),
                    None => {
                        return Err(Error::UnknownEnv {
                            id: name.to_owned(),
                            available: crate::ENV_NAMES.iter().map(|s| (*s).to_owned()).collect(),
                        });
                    }
                }
            }
        };
        Ok(Self {
            name: name.to_owned(),
            mode,
            active: match mode {
                ObjectMode::Single(i) => i,
                _ => 0,
            },
            objects: Vec::new(),
            visuals: Vec::new(),
            all_geoms: GeomSet::default(),
            visual_pose: Vec::new(),
        })
    }

    /// The single-object mode.
    pub fn mode(&self) -> ObjectMode {
        self.mode
    }

    /// The object in play (single modes), by robosuite's id.
    pub fn active_object(&self) -> usize {
        self.active
    }

    /// The object bindings, in robosuite's order.
    pub fn objects(&self) -> &[FreeBody] {
        &self.objects
    }

    /// robosuite's `objects_in_bins`: in the quadrant and the gripper farther than 0.0424 m.
    pub fn objects_in_bins(&self, sim: &Sim, robots: &[Robot]) -> [bool; 4] {
        let eef = eef_pos(sim, robots);
        std::array::from_fn(|i| {
            let p = self.objects[i].pos(sim);
            in_quadrant(p, i) && 1.0 - (10.0 * dist(eef, p)).tanh() < 0.6
        })
    }

    /// robosuite's `staged_rewards`: `(reach, grasp, lift, hover)`.
    pub fn staged_rewards(&self, sim: &Sim, robots: &[Robot], in_bins: &[bool; 4]) -> [f64; 4] {
        let (reach_mult, grasp_mult, lift_mult, hover_mult) = (0.1, 0.35, 0.5, 0.7);
        let active: Vec<usize> = (0..4).filter(|&i| !in_bins[i]).collect();
        if active.is_empty() {
            return [0.0; 4];
        }
        let eef = eef_pos(sim, robots);
        let pos: Vec<[f64; 3]> = active.iter().map(|&i| self.objects[i].pos(sim)).collect();
        let min_d = pos
            .iter()
            .map(|p| dist(eef, *p))
            .fold(f64::INFINITY, f64::min);
        let r_reach = (1.0 - (10.0 * min_d).tanh()) * reach_mult;
        let geoms = GeomSet::new(
            active
                .iter()
                .flat_map(|&i| self.objects[i].geoms.ids().to_vec())
                .map(|g| g as usize),
        );
        let r_grasp = if is_grasped(sim, robots, &geoms) {
            grasp_mult
        } else {
            0.0
        };
        let mut r_lift = 0.0;
        if r_grasp > 0.0 {
            let z_target = BIN2_POS[2] + 0.25;
            let min_z = pos
                .iter()
                .map(|p| (z_target - p[2]).max(0.0))
                .fold(f64::INFINITY, f64::min);
            r_lift = grasp_mult + (1.0 - (15.0 * min_z).tanh()) * (lift_mult - grasp_mult);
        }
        let mut r_hover = f64::NEG_INFINITY;
        for (k, &i) in active.iter().enumerate() {
            let t = target_placement(i);
            let p = pos[k];
            let above =
                (p[1] - t[1]).abs() < BIN_SIZE[1] / 4.0 && (p[0] - t[0]).abs() < BIN_SIZE[0] / 4.0;
            let d = (t[0] - p[0]).hypot(t[1] - p[1]);
            let base = if above { lift_mult } else { r_lift };
            r_hover = r_hover.max(base + (1.0 - (10.0 * d).tanh()) * (hover_mult - lift_mult));
        }
        [r_reach, r_grasp, r_lift, r_hover]
    }
}

impl Task for PickPlace {
    fn name(&self) -> &str {
        &self.name
    }

    fn robot_base_pose(&self, _index: usize) -> ([f64; 3], [f64; 4]) {
        ([-0.5, -0.1, 0.912], [1.0, 0.0, 0.0, 0.0])
    }

    fn arena_xml(&self) -> String {
        bins_arena_xml()
    }

    fn build_objects(&self, scene: &mut SceneBuilder) -> Result<()> {
        for (i, name) in PICK_PLACE_OBJECTS.iter().enumerate() {
            let s = shape(i);
            let mut obj = PrimitiveObject::new(vec![s.geom.clone()], s.density, s.rgba);
            obj.friction = [0.95, 0.3, 0.1];
            obj.solref = [0.001, 1.0];
            obj.solimp = [0.998, 0.998, 0.001];
            obj.condim = 4;
            obj.joint_damping = 0.0005;
            scene.add_part(name, &obj.to_xml(name), &format!("{name}_"))?;
        }
        for (i, name) in PICK_PLACE_OBJECTS.iter().enumerate() {
            let s = shape(i);
            let mut obj =
                PrimitiveObject::new(vec![s.geom], 1.0, [s.rgba[0], s.rgba[1], s.rgba[2], 0.3]);
            obj.visual_only = true;
            let vname = format!("Visual{name}");
            scene.add_part(&vname, &obj.to_xml(&vname), &format!("{vname}_"))?;
        }
        Ok(())
    }

    fn bind(&mut self, model: &MjModel, _robots: &[Robot], _source: ModelSource) -> Result<()> {
        self.objects = PICK_PLACE_OBJECTS
            .iter()
            .map(|n| {
                FreeBody::bind(
                    model,
                    &format!("{n}_main"),
                    &format!("{n}_joint0"),
                    &[format!("{n}_g0")],
                )
            })
            .collect::<Result<_>>()?;
        self.visuals = PICK_PLACE_OBJECTS
            .iter()
            .map(|n| body_id(model, &format!("Visual{n}_main")))
            .collect::<Result<_>>()?;
        self.all_geoms = GeomSet::new(
            self.objects
                .iter()
                .flat_map(|o| o.geoms.ids().to_vec())
                .map(|g| g as usize),
        );
        self.visual_pose = self.visuals.iter().map(|&b| model.body_pos()[b]).collect();
        Ok(())
    }

    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let placed: Vec<PlacedObject> = (0..4)
            .map(|i| {
                let s = shape(i);
                PlacedObject {
                    horizontal_radius: s.radius,
                    bottom_offset: -s.half_height,
                    top_offset: s.half_height,
                }
            })
            .collect();
        // Our bin floors' tops are at 0.82 (robosuite's spawn 2 cm into the floor, which
        // its stiff contacts push out); objects start resting on the floor.
        let sampler = UniformRandomSampler {
            x_range: [-(BIN_SIZE[0] / 2.0 - 0.05), BIN_SIZE[0] / 2.0 - 0.05],
            y_range: [-(BIN_SIZE[1] / 2.0 - 0.05), BIN_SIZE[1] / 2.0 - 0.05],
            rotation: Rotation::Random,
            rotation_axis: Axis::Z,
            ensure_object_boundary_in_range: true,
            ensure_valid_placement: true,
            reference_pos: [BIN1_POS[0], BIN1_POS[1], BIN1_POS[2] + 0.02],
            z_offset: 0.0,
        };
        let poses = sampler.sample(rng, &placed, &[])?;
        for (obj, (p, q)) in self.objects.iter().zip(&poses) {
            obj.set_pose(sim, *p, *q);
        }
        for i in 0..4 {
            let t = target_placement(i);
            let marker = UniformRandomSampler {
                x_range: [t[0] - BIN1_POS[0]; 2],
                y_range: [t[1] - BIN1_POS[1]; 2],
                rotation: Rotation::Fixed(0.0),
                rotation_axis: Axis::Z,
                ensure_object_boundary_in_range: false,
                ensure_valid_placement: false,
                reference_pos: [BIN1_POS[0], BIN1_POS[1], BIN2_POS[2] + 0.02],
                z_offset: 0.0,
            };
            let (p, _) = marker.sample(rng, &placed[i..=i], &[])?[0];
            sim.model_mut().body_pos_mut()[self.visuals[i]] = p;
            self.visual_pose[i] = p;
        }
        if self.mode == ObjectMode::RandomSingle {
            self.active = rng.random_range(0..4);
        }
        if self.mode != ObjectMode::All {
            for i in (0..4).filter(|&i| i != self.active) {
                self.objects[i].set_pose(sim, PARKED_POS, [1.0, 0.0, 0.0, 0.0]);
            }
        }
        Ok(())
    }

    fn observation_keys(&self) -> Vec<ObsKey> {
        self.mode.pose_keys(&PICK_PLACE_OBJECTS, "obj")
    }

    fn write_observations(&self, sim: &Sim, robots: &[Robot], out: &mut [f64]) {
        self.mode
            .write_pose_obs(PICK_PLACE_OBJECTS.len(), self.active, out, |i, out| {
                let o = &self.objects[i];
                write_object_pose_obs(sim, robots, o.pos(sim), o.quat(sim), out);
            });
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let in_bins = self.objects_in_bins(sim, robots);
        self.mode.reward(
            &in_bins,
            || self.staged_rewards(sim, robots, &in_bins),
            config,
        )
    }

    fn check_success(&self, sim: &Sim, robots: &[Robot]) -> bool {
        self.mode.is_success(&self.objects_in_bins(sim, robots))
    }

    fn save_state(&self) -> Vec<f64> {
        let mut s = vec![self.active as f64];
        for p in &self.visual_pose {
            s.extend_from_slice(p);
        }
        s
    }

    fn load_state(&mut self, sim: &mut Sim, state: &[f64]) -> Result<()> {
        if state.len() != 1 + 3 * self.visuals.len() {
            return Err(Error::invalid_argument(
                "state",
                format!(
                    "PickPlace's state has {} values, got {}",
                    1 + 3 * self.visuals.len(),
                    state.len()
                ),
            ));
        }
        self.active = (state[0] as usize).min(3);
        for (i, &b) in self.visuals.iter().enumerate() {
            let p = [state[1 + 3 * i], state[2 + 3 * i], state[3 + 3 * i]];
            sim.model_mut().body_pos_mut()[b] = p;
            self.visual_pose[i] = p;
        }
        Ok(())
    }
}
