//! robosuite's `TwoArmPegInHole`: one arm holds a peg, the other a plate with a square hole;
//! put the peg through the hole (`environments/manipulation/two_arm_peg_in_hole.py`).

use super::common::{scale_reward, sub};
use super::options::{self, TaskOptions};
use super::{Bound, RewardConfig, RobotSetup, Task, TaskLogic, TaskScene, TaskSpec};
use crate::assets::Assets;
use crate::math::xyzw;
use crate::mjcf::tree::{self, append, array_to_string, set_attr};
use crate::models::arenas::Arena;
use crate::models::objects::primitive::Primitive;
use crate::models::objects::{CustomMaterial, Joints, ObjType, Shape, xml_object};
use crate::models::robots::{GripperChoice, RobotModel};
use crate::observables::{Modality, Observable};
use crate::robots::Robot;
use crate::sim::{BoxGeomUpdate, Sim, body_id, resize_cylinder_body};
use gym_core::{DType, EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use rand::RngExt;

/// TwoArmPegInHole's settings (robosuite's constructor defaults).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TwoArmPegInHoleSpec {
    /// The range the peg's radius is drawn from at every reset (default 1.5 to 3 cm).
    pub peg_radius: [f64; 2],
    /// The peg's half-length (default 13 cm).
    pub peg_length: f64,
}

impl Default for TwoArmPegInHoleSpec {
    fn default() -> Self {
        Self {
            peg_radius: [0.015, 0.03],
            peg_length: 0.13,
        }
    }
}

impl TwoArmPegInHoleSpec {
    fn validate(&self) -> Result<()> {
        let [lo, hi] = self.peg_radius;
        if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo <= hi) {
            return Err(Error::invalid_argument(
                "peg_radius",
                format!("need 0 < min <= max, got [{lo}, {hi}]"),
            ));
        }
        if !(self.peg_length.is_finite() && self.peg_length > 0.0) {
            return Err(Error::invalid_argument(
                "peg_length",
                format!("must be positive and finite, got {}", self.peg_length),
            ));
        }
        Ok(())
    }
}

/// The density of robosuite's `CylinderObject` (its default).
const PEG_DENSITY: f64 = 1000.0;

impl TaskSpec for TwoArmPegInHoleSpec {
    fn options(&self) -> TaskOptions {
        options::to_options(self)
    }

    fn configure(&mut self, options: &TaskOptions) -> Result<()> {
        *self = options::merged(self.name(), self, options)?;
        Ok(())
    }

    fn name(&self) -> &str {
        "TwoArmPegInHole"
    }

    fn robots(&self) -> RobotSetup {
        RobotSetup::TwoArm {
            opposed_shift: 0.0,
            parallel_shift: 0.25,
        }
    }

    /// robosuite asserts `gripper_types is None`: the arms hold the peg and the plate.
    fn gripper(
        &self,
        _robot: usize,
        _arm: usize,
        configured: &GripperChoice,
    ) -> Result<GripperChoice> {
        match configured {
            GripperChoice::Default | GripperChoice::None => Ok(GripperChoice::None),
            GripperChoice::Named(name) => Err(Error::invalid_argument(
                "gripper_types",
                format!(
                    "TwoArmPegInHole takes no gripper (robosuite asserts gripper_types is None), got `{name}`"
                ),
            )),
        }
    }

    fn build(&self, assets: &Assets, robots: &mut [RobotModel]) -> Result<TaskScene> {
        self.validate()?;
        let mut arena = Arena::empty(assets)?;
        arena.set_origin([0.0; 3])?;
        arena.set_camera(
            "agentview",
            [
                1.0666432116509934,
                1.4903257668114777e-08,
                2.0563394967349096,
            ],
            [
                0.6530979871749878,
                0.27104058861732483,
                0.27104055881500244,
                0.6530978679656982,
            ],
        )?;
        let mut hole = xml_object(
            assets,
            "objects/plate-with-hole.xml",
            "hole",
            &Joints::None,
            ObjType::All,
            true,
        )?;
        let radius = 0.5 * (self.peg_radius[0] + self.peg_radius[1]);
        let mut peg = Primitive::new("peg", Shape::Cylinder([radius, self.peg_length]));
        peg.material = Some(CustomMaterial::new(
            assets,
            "WoodGreen",
            "greenwood",
            "greenwood_mat",
            &[("type", "cube")],
            &[
                ("texrepeat", "1 1"),
                ("specular", "0.4"),
                ("shininess", "0.1"),
            ],
            false,
        )?);
        peg.rgba = [0.0, 1.0, 0.0, 1.0];
        peg.joints = Some(Joints::None);
        let mut peg = peg.build()?;
        set_attr(&mut hole.body, "quat", "0 0 0.707 0.707".to_owned());
        set_attr(&mut hole.body, "pos", array_to_string(&[0.11, 0.0, 0.17]));
        set_attr(
            &mut peg.body,
            "pos",
            array_to_string(&[0.0, 0.0, self.peg_length]),
        );
        // The peg goes into gripper 0's hand, the plate into gripper 1's.
        let hands: [(usize, usize); 2] = if robots.len() == 1 {
            [(0, 0), (0, 1)]
        } else {
            [(0, 0), (1, 0)]
        };
        for ((robot, arm), object) in hands.into_iter().zip([&peg, &hole]) {
            let model = robots.get_mut(robot).ok_or_else(|| {
                Error::invalid_argument("robots", "TwoArmPegInHole needs its robots")
            })?;
            let eef = model.eef_body(arm);
            let body = tree::find_mut(
                model.xml.doc.worldbody_mut(),
                "body",
                &[("name", Some(&eef))],
            )
            .ok_or_else(|| Error::model(format!("no body `{eef}` to attach to")))?;
            append(body, object.body.clone());
        }
        Ok(TaskScene {
            arena,
            objects: Vec::new(),
            attached: vec![hole, peg],
        })
    }

    fn bind(&self, scene: &TaskScene, model: &MjModel, _robots: &[Robot]) -> Result<Box<dyn Task>> {
        let (hole, peg) = (&scene.attached[0], &scene.attached[1]);
        let peg_geoms = [peg.contact_geoms(), peg.visual_geoms()]
            .concat()
            .iter()
            .map(|g| crate::sim::geom_id(model, g))
            .collect::<Result<Vec<_>>>()?;
        let radius = model.geom_size()[peg_geoms[0]][0];
        let task = TwoArmPegInHole {
            spec: self.clone(),
            hole_body: body_id(model, &hole.root_body())?,
            peg_body: body_id(model, &peg.root_body())?,
            peg_geoms,
            radius,
        };
        let observables = vec![
            Observable::vec("hole_pos", Modality::Object, |t: &TwoArmPegInHole, sim| {
                sim.data().xpos()[t.hole_body]
            }),
            Observable::vec("hole_quat", Modality::Object, |t: &TwoArmPegInHole, sim| {
                xyzw(sim.data().xquat()[t.hole_body])
            }),
            Observable::f64(
                "peg_to_hole",
                3,
                Modality::Object,
                |t: &TwoArmPegInHole, sim, out| {
                    let d = sim.data();
                    out.copy_from_slice(&sub(d.xpos()[t.hole_body], d.xpos()[t.peg_body]));
                },
            ),
            Observable::vec("peg_quat", Modality::Object, |t: &TwoArmPegInHole, sim| {
                xyzw(sim.data().xquat()[t.peg_body])
            }),
            Observable::new(
                "angle",
                &[],
                DType::F64,
                Modality::Object,
                |t: &TwoArmPegInHole, sim, out| {
                    out[0] = t.orientation(sim).2;
                },
            ),
            Observable::new(
                "t",
                &[],
                DType::F64,
                Modality::Object,
                |t: &TwoArmPegInHole, sim, out| {
                    out[0] = t.orientation(sim).0;
                },
            ),
            Observable::new(
                "d",
                &[],
                DType::F64,
                Modality::Object,
                |t: &TwoArmPegInHole, sim, out| {
                    out[0] = t.orientation(sim).1;
                },
            ),
        ];
        Ok(Bound::boxed(task, observables))
    }
}

/// The bound TwoArmPegInHole task: a cylinder peg (body `peg_main`) fixed 13 cm out of
/// gripper 0's hand and a plate with a square hole (body `hole_main`) fixed to gripper 1's
/// hand; no grippers, no objects to place.
///
/// * Reset: the peg radius is drawn `U(0.015, 0.03)` (mass and inertia follow, density
///   1000).
/// * Geometry (`_compute_orientation`): `v` the peg's axis, `c` the hole's centre (10 cm
///   along the plate's x axis), `t = (c − peg)·v`, `d = ‖v × (peg − c)‖`,
///   `cos = |plate normal · v|`.
/// * Success: `d < 0.06`, `−0.12 ≤ t ≤ 0.14` and `cos > 0.95`.
/// * Reward: 1 on success; shaped plus `1 − tanh(‖peg − plate‖)`, `1 − tanh(d)`,
///   `1 − tanh(|t|)` and `cos`; sparse × 5; scaled by `reward_scale / 5`.
#[derive(Debug, Clone)]
pub struct TwoArmPegInHole {
    spec: TwoArmPegInHoleSpec,
    hole_body: usize,
    peg_body: usize,
    peg_geoms: Vec<usize>,
    radius: f64,
}

fn column(m: &[f64; 9], j: usize) -> [f64; 3] {
    [m[j], m[3 + j], m[6 + j]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

impl TwoArmPegInHole {
    /// robosuite's `_compute_orientation`: `(t, d, cos)`.
    fn orientation(&self, sim: &Sim) -> (f64, f64, f64) {
        let data = sim.data();
        let peg_pos = data.xpos()[self.peg_body];
        let hole_pos = data.xpos()[self.hole_body];
        let peg_mat = data.xmat()[self.peg_body];
        let hole_mat = data.xmat()[self.hole_body];
        let v = column(&peg_mat, 2);
        let n = norm(v);
        let v = v.map(|x| x / n);
        let x = column(&hole_mat, 0);
        let center = [
            hole_pos[0] + x[0] * 0.1,
            hole_pos[1] + x[1] * 0.1,
            hole_pos[2] + x[2] * 0.1,
        ];
        let nv = norm(v);
        let t = dot(sub(center, peg_pos), v) / (nv * nv);
        let p = sub(peg_pos, center);
        let cross = [
            v[1] * p[2] - v[2] * p[1],
            v[2] * p[0] - v[0] * p[2],
            v[0] * p[1] - v[1] * p[0],
        ];
        let d = norm(cross) / nv;
        let normal = column(&hole_mat, 2);
        let cos = (dot(normal, v) / norm(normal) / nv).abs();
        (t, d, cos)
    }

    fn resize(&mut self, sim: &mut Sim, radius: f64) -> Result<()> {
        resize_cylinder_body(
            sim,
            BoxGeomUpdate {
                body: self.peg_body,
                geoms: &self.peg_geoms,
                density: PEG_DENSITY,
            },
            radius,
            self.spec.peg_length,
        )?;
        self.radius = radius;
        Ok(())
    }
}

impl TaskLogic for TwoArmPegInHole {
    fn randomize_model(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let [lo, hi] = self.spec.peg_radius;
        let radius = lo + (hi - lo) * rng.random::<f64>();
        self.resize(sim, radius)
    }

    fn place_objects(&mut self, _sim: &mut Sim, _rng: &mut EnvRng) -> Result<()> {
        Ok(())
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let mut reward = 0.0;
        if self.check_success(sim, robots) {
            reward = 1.0;
        }
        if config.reward_shaping {
            let (t, d, cos) = self.orientation(sim);
            let data = sim.data();
            let dist = norm(sub(data.xpos()[self.peg_body], data.xpos()[self.hole_body]));
            reward += 1.0 - dist.tanh();
            reward += 1.0 - d.tanh();
            reward += 1.0 - t.abs().tanh();
            reward += cos;
        } else {
            reward *= 5.0;
        }
        scale_reward(reward, config.reward_scale, 5.0)
    }

    fn check_success(&self, sim: &Sim, _robots: &[Robot]) -> bool {
        let (t, d, cos) = self.orientation(sim);
        d < 0.06 && (-0.12..=0.14).contains(&t) && cos > 0.95
    }

    fn save_state(&self) -> Vec<f64> {
        vec![self.radius]
    }

    fn load_state(&mut self, sim: &mut Sim, state: &[f64]) -> Result<()> {
        let [radius] = state else {
            return Err(Error::invalid_argument(
                "task state",
                format!(
                    "TwoArmPegInHole's state is the peg radius, got {} values",
                    state.len()
                ),
            ));
        };
        if *radius != self.radius {
            self.resize(sim, *radius)?;
        }
        Ok(())
    }
}
