//! robosuite's `TwoArmTransport`: carry a hammer from a lidded bin on one table into a bin
//! on the other, and throw the cube of trash in that bin into the trash bin
//! (`environments/manipulation/two_arm_transport.py`, `models/objects/group/transport.py`).

use super::common::{FreeBody, PoseRef, scale_reward, sub};
use super::options::{self, TaskOptions};
use super::two_arm::task_arms;
use super::{Bound, RewardConfig, RobotSetup, Task, TaskLogic, TaskScene, TaskSpec};
use crate::assets::Assets;
use crate::models::arenas::Arena;
use crate::models::objects::bin::{bin, lid};
use crate::models::objects::composite::GeneratedObject;
use crate::models::objects::hammer::{Hammer, HammerFigures, HammerRanges};
use crate::models::objects::primitive::Primitive;
use crate::models::objects::{CustomMaterial, ObjectModel, Shape};
use crate::models::robots::RobotModel;
use crate::observables::{Modality, Observable};
use crate::placement::{Axis, Rotation, UniformRandomSampler, with_init_quat};
use crate::robots::Robot;
use crate::sim::{GeomSet, Sim, any_contact_between, geom_id, reshape_body_from};
use gym_core::{DType, EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use std::cell::Cell;
use std::f64::consts::PI;

/// TwoArmTransport's settings (robosuite's constructor defaults).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TwoArmTransportSpec {
    /// The area both tables span (default 0.8 × 1.2 × 0.05); each table is a quarter as
    /// wide, 3/8 of the width to either side.
    pub tables_boundary: [f64; 3],
    /// The tables' friction (default `(1, 0.005, 0.0001)`).
    pub table_friction: [f64; 3],
    /// Every bin's full size (default 0.3 × 0.3 × 0.15).
    pub bin_size: [f64; 3],
}

impl Default for TwoArmTransportSpec {
    fn default() -> Self {
        Self {
            tables_boundary: [0.8, 1.2, 0.05],
            table_friction: [1.0, 5e-3, 1e-4],
            bin_size: [0.3, 0.3, 0.15],
        }
    }
}

/// The payload: robosuite's hammer with fixed figures but its random head.
const PAYLOAD: HammerRanges = HammerRanges {
    handle_radius: [0.015, 0.015],
    handle_length: [0.20, 0.20],
    handle_density: [150.0, 150.0],
    handle_friction: [4.0, 4.0],
    head_density_ratio: 1.5,
};

/// The bins' wall thickness (robosuite's `Bin` default).
const WALL: f64 = 0.01;

impl TwoArmTransportSpec {
    fn table_full_size(&self) -> [f64; 3] {
        let mut s = self.tables_boundary;
        s[1] *= 0.25;
        s
    }

    fn table_offsets(&self) -> [[f64; 3]; 2] {
        let y = self.tables_boundary[1];
        [[0.0, y * -3.0 / 8.0, 0.8], [0.0, y * 3.0 / 8.0, 0.8]]
    }
}

/// The objects in robosuite's order (`TransportGroup._generate_objects`).
const PAYLOAD_I: usize = 0;
const TRASH_I: usize = 1;
const START_BIN_I: usize = 2;
const TARGET_BIN_I: usize = 3;
const TRASH_BIN_I: usize = 4;
const LID_I: usize = 5;

impl TaskSpec for TwoArmTransportSpec {
    fn options(&self) -> TaskOptions {
        options::to_options(self)
    }

    fn configure(&mut self, options: &TaskOptions) -> Result<()> {
        *self = options::merged(self.name(), self, options)?;
        Ok(())
    }

    fn name(&self) -> &str {
        "TwoArmTransport"
    }

    fn robots(&self) -> RobotSetup {
        RobotSetup::TwoArm {
            opposed_shift: 0.25,
            parallel_shift: 0.6,
        }
    }

    fn build(&self, assets: &Assets, _robots: &mut [RobotModel]) -> Result<TaskScene> {
        let table = self.table_full_size();
        let mut arena =
            Arena::multi_table(assets, &self.table_offsets(), table, self.table_friction)?;
        arena.set_origin([0.0; 3])?;
        for (name, pos, quat) in [
            (
                "agentview",
                [
                    0.8894354364730311,
                    -3.481824231498976e-08,
                    1.7383813133506494,
                ],
                [
                    0.6530981063842773,
                    0.2710406184196472,
                    0.27104079723358154,
                    0.6530979871749878,
                ],
            ),
            (
                "shouldercamera0",
                [0.4430096057365183, -1.0697399743660143, 1.3639950119362048],
                [
                    0.804057240486145,
                    0.5531665086746216,
                    0.11286306381225586,
                    0.18644218146800995,
                ],
            ),
            (
                "shouldercamera1",
                [-0.40900713993039983, 0.9613722572245062, 1.3084072951772754],
                [
                    0.15484197437763214,
                    0.12077208608388901,
                    -0.5476858019828796,
                    -0.8133130073547363,
                ],
            ),
        ] {
            arena.set_camera(name, pos, quat)?;
        }
        let payload = Hammer::new(
            assets,
            "payload",
            HammerFigures::middle(&PAYLOAD),
            PAYLOAD.head_density_ratio,
        )?;
        let mut trash = Primitive::new("trash", Shape::Box([0.02; 3]));
        trash.material = Some(CustomMaterial::new(
            assets,
            "WoodRed",
            "redwood",
            "redwood_mat",
            &[("type", "cube")],
            &[
                ("texrepeat", "3 3"),
                ("specular", "0.4"),
                ("shininess", "0.1"),
            ],
            false,
        )?);
        let bin_of = |name: &str| bin(assets, &format!("transport_{name}"), self.bin_size, 10000.0);
        let lid_size = [self.bin_size[0], self.bin_size[1], 0.01];
        Ok(TaskScene {
            arena,
            objects: vec![
                payload.build()?,
                trash.build()?,
                bin_of("start_bin")?.build()?,
                bin_of("target_bin")?.build()?,
                bin_of("trash_bin")?.build()?,
                lid(assets, "transport_start_bin_lid", lid_size)?.build()?,
            ],
            attached: Vec::new(),
        })
    }

    fn bind(&self, scene: &TaskScene, model: &MjModel, robots: &[Robot]) -> Result<Box<dyn Task>> {
        let o: &[ObjectModel] = &scene.objects;
        let bodies = o
            .iter()
            .map(|obj| FreeBody::bind(model, obj))
            .collect::<Result<Vec<_>>>()?;
        let base = |i: usize| geom_id(model, &o[i].name_of("base"));
        let assets = Assets::locate()?;
        let payload = Hammer::new(
            &assets,
            "payload",
            HammerFigures::middle(&PAYLOAD),
            PAYLOAD.head_density_ratio,
        )?;
        let donor_size = payload.donor_model()?.stat().meansize;
        let offsets = self.table_offsets();
        let table = self.table_full_size();
        // robosuite's per-object samplers: (x centre, table, rotation centre, tolerance,
        // axis), in its sampling order start bin, lid, payload, target bin, trash, trash bin.
        let sampler = |x: f64, t: usize, r: f64, tol: f64, axis: Axis| UniformRandomSampler {
            x_range: [x - 0.005, x + 0.005],
            y_range: [-0.005, 0.005],
            rotation: Rotation::Range(r - tol, r + tol),
            rotation_axis: axis,
            ensure_object_boundary_in_range: false,
            ensure_valid_placement: false,
            reference_pos: offsets[t],
            z_offset: 0.001,
        };
        let samplers = vec![
            (START_BIN_I, sampler(table[0] * 0.25, 0, 0.0, 0.0, Axis::Z)),
            (LID_I, sampler(0.0, 0, 0.0, 0.0, Axis::Z)),
            (PAYLOAD_I, sampler(0.0, 0, PI / 2.0, PI / 6.0, Axis::Y)),
            (
                TARGET_BIN_I,
                sampler(-table[0] * 0.25, 1, 0.0, 0.0, Axis::Z),
            ),
            (TRASH_I, sampler(0.0, 1, 0.0, 0.3 * PI, Axis::Z)),
            (TRASH_BIN_I, sampler(table[0] * 0.25, 1, 0.0, 0.0, Axis::Z)),
        ];
        let arms = task_arms(robots);
        let task = TwoArmTransport {
            samplers,
            extents: o.iter().map(ObjectModel::placement).collect(),
            payload_geoms: bodies[PAYLOAD_I].geoms.clone(),
            trash_geoms: bodies[TRASH_I].geoms.clone(),
            target_base: GeomSet::new([base(TARGET_BIN_I)?]),
            trash_base: GeomSet::new([base(TRASH_BIN_I)?]),
            target_base_id: base(TARGET_BIN_I)?,
            trash_base_id: base(TRASH_BIN_I)?,
            lid_handle: geom_id(model, &o[LID_I].name_of("handle"))?,
            bodies,
            payload,
            donor_size,
            eef_sites: arms.map(|a| robots[a.robot].arms()[a.arm].eef_site()),
            shaping_off: Cell::new(false),
        };
        let pos = |f: fn(&TwoArmTransport, &Sim) -> [f64; 3]| {
            move |t: &TwoArmTransport, sim: &Sim, out: &mut [f64]| {
                out.copy_from_slice(&f(t, sim));
            }
        };
        let quat = |name: &'static str, f: fn(&TwoArmTransport) -> PoseRef| {
            Observable::new(
                name,
                &[4],
                DType::F32,
                Modality::Object,
                move |t: &TwoArmTransport, sim: &Sim, out: &mut [f64]| {
                    out.copy_from_slice(&f(t).pose(sim).1);
                },
            )
        };
        let flag = |name: &'static str, f: fn(&TwoArmTransport, &Sim) -> bool| {
            Observable::new(
                name,
                &[],
                DType::Bool,
                Modality::Object,
                move |t: &TwoArmTransport, sim: &Sim, out: &mut [f64]| {
                    out[0] = f64::from(u8::from(f(t, sim)));
                },
            )
        };
        let to = |name: &'static str, arm: usize, f: fn(&TwoArmTransport, &Sim) -> [f64; 3]| {
            Observable::f64(
                name,
                3,
                Modality::Object,
                move |t: &TwoArmTransport, sim: &Sim, out: &mut [f64]| {
                    let e = sim.data().site_xpos()[t.eef_sites[arm]];
                    out.copy_from_slice(&sub(f(t, sim), e));
                },
            )
        };
        let mut observables = vec![
            Observable::f64(
                "payload_pos",
                3,
                Modality::Object,
                pos(|t, s| t.bodies[PAYLOAD_I].pos(s)),
            ),
            quat("payload_quat", |t| {
                PoseRef::BodyFrame(t.bodies[PAYLOAD_I].body)
            }),
            Observable::f64(
                "trash_pos",
                3,
                Modality::Object,
                pos(|t, s| t.bodies[TRASH_I].pos(s)),
            ),
            quat("trash_quat", |t| PoseRef::BodyFrame(t.bodies[TRASH_I].body)),
            Observable::f64(
                "lid_handle_pos",
                3,
                Modality::Object,
                pos(TwoArmTransport::lid_handle_pos),
            ),
            quat("lid_handle_quat", |t| PoseRef::Geom(t.lid_handle)),
            Observable::f64(
                "target_bin_pos",
                3,
                Modality::Object,
                pos(|t, s| s.data().geom_xpos()[t.target_base_id]),
            ),
            Observable::f64(
                "trash_bin_pos",
                3,
                Modality::Object,
                pos(|t, s| s.data().geom_xpos()[t.trash_base_id]),
            ),
            flag(
                "payload_in_target_bin",
                TwoArmTransport::payload_in_target_bin,
            ),
            flag("trash_in_trash_bin", TwoArmTransport::trash_in_trash_bin),
        ];
        // robosuite's order: per robot (its payload, then lid handle or trash sensor); one
        // bimanual robot alone ("single-robot") lists both payload sensors first.
        let payload0 = to("gripper0_to_payload", 0, |t, s| t.bodies[PAYLOAD_I].pos(s));
        let lid0 = to("gripper0_to_lid_handle", 0, TwoArmTransport::lid_handle_pos);
        let payload1 = to("gripper1_to_payload", 1, |t, s| t.bodies[PAYLOAD_I].pos(s));
        let trash1 = to("gripper1_to_trash", 1, |t, s| t.bodies[TRASH_I].pos(s));
        if robots.len() == 1 {
            observables.extend([payload0, payload1, lid0, trash1]);
        } else {
            observables.extend([payload0, lid0, payload1, trash1]);
        }
        Ok(Bound::boxed(task, observables))
    }
}

/// The bound TwoArmTransport task: robosuite's `TransportGroup` on two tables. Objects
/// (robosuite's order): the hammer `payload`, the cube `trash`, the bins
/// `transport_start_bin`, `transport_target_bin`, `transport_trash_bin` and the lid
/// `transport_start_bin_lid`.
///
/// * Reset: the payload's head half-size is drawn `U(0.015, 0.018)` (the scene's hammer
///   takes it without recompiling); start bin at x = 0.2 on table 0, target bin at −0.2
///   and trash bin at 0.2 on table 1 (±5 mm); the lid on the start bin, the payload in it
///   (turned `π/2 ± π/6` about y, with the hammer's random `init_quat`), the trash in the
///   target bin (yaw `±0.3π`).
/// * Success: the payload touches the target bin's base and the trash the trash bin's.
/// * Reward: sparse only, `reward_scale` on success. With `reward_shaping` robosuite warns,
///   turns shaping off for good and returns 0 for that step; so does this task.
#[derive(Debug)]
pub struct TwoArmTransport {
    samplers: Vec<(usize, UniformRandomSampler)>,
    extents: Vec<crate::placement::PlacedObject>,
    bodies: Vec<FreeBody>,
    payload_geoms: GeomSet,
    trash_geoms: GeomSet,
    target_base: GeomSet,
    trash_base: GeomSet,
    target_base_id: usize,
    trash_base_id: usize,
    lid_handle: usize,
    payload: Hammer,
    donor_size: f64,
    eef_sites: [usize; 2],
    shaping_off: Cell<bool>,
}

impl TwoArmTransport {
    fn lid_handle_pos(&self, sim: &Sim) -> [f64; 3] {
        sim.data().geom_xpos()[self.lid_handle]
    }

    fn payload_in_target_bin(&self, sim: &Sim) -> bool {
        any_contact_between(sim.data(), &self.target_base, &self.payload_geoms)
    }

    fn trash_in_trash_bin(&self, sim: &Sim) -> bool {
        any_contact_between(sim.data(), &self.trash_base, &self.trash_geoms)
    }

    fn reshape(&mut self, sim: &mut Sim, figures: HammerFigures) -> Result<()> {
        let mut payload = self.payload.clone();
        payload.figures = figures;
        let donor = payload.donor_model()?;
        let size = donor.stat().meansize;
        let body = self.bodies[PAYLOAD_I].body;
        reshape_body_from(sim, body, &donor, 1, size - self.donor_size)?;
        self.extents[PAYLOAD_I] = payload.build()?.placement();
        self.payload = payload;
        self.donor_size = size;
        Ok(())
    }
}

impl TaskLogic for TwoArmTransport {
    fn randomize_model(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let figures = HammerFigures::draw(&PAYLOAD, rng);
        self.reshape(sim, figures)
    }

    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let mut start_bin = [0.0; 3];
        let mut target_bin = [0.0; 3];
        for (i, sampler) in &self.samplers {
            let (mut pos, mut quat) = sampler.sample(rng, &[self.extents[*i]], &[])?[0];
            match *i {
                START_BIN_I => start_bin = pos,
                TARGET_BIN_I => target_bin = pos,
                LID_I => pos = [start_bin[0], start_bin[1], pos[2] + 0.15],
                PAYLOAD_I => {
                    quat = with_init_quat(quat, Hammer::init_quat(rng));
                    pos = [start_bin[0], start_bin[1], pos[2] + WALL];
                }
                TRASH_I => pos = [target_bin[0], target_bin[1], pos[2] + WALL],
                _ => {}
            }
            self.bodies[*i].set_pose(sim, pos, quat);
        }
        Ok(())
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let mut reward = 0.0;
        if config.reward_shaping && !self.shaping_off.get() {
            self.shaping_off.set(true);
        } else if self.check_success(sim, robots) {
            reward = 1.0;
        }
        scale_reward(reward, config.reward_scale, 1.0)
    }

    fn check_success(&self, sim: &Sim, _robots: &[Robot]) -> bool {
        self.payload_in_target_bin(sim) && self.trash_in_trash_bin(sim)
    }

    fn save_state(&self) -> Vec<f64> {
        self.payload.figures.to_array().to_vec()
    }

    fn load_state(&mut self, sim: &mut Sim, state: &[f64]) -> Result<()> {
        let values: [f64; 5] = state.try_into().map_err(|_| {
            Error::invalid_argument(
                "task state",
                format!(
                    "TwoArmTransport's state is the payload's 5 figures, got {} values",
                    state.len()
                ),
            )
        })?;
        let figures = HammerFigures::from_array(values);
        if figures != self.payload.figures {
            self.reshape(sim, figures)?;
        }
        Ok(())
    }
}
