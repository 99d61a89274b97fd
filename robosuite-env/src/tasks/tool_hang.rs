//! robosuite's `ToolHang`: insert the hook frame into the stand, then hang the ratcheting
//! wrench on the frame's hook (`environments/manipulation/tool_hang.py`).

use super::common::{FreeBody, ObjectSensors, PoseRef, scale_reward, sub};
use super::options::{self, TaskOptions};
use super::table::TABLE_OFFSET;
use super::{Bound, RewardConfig, Task, TaskLogic, TaskScene, TaskSpec};
use crate::assets::Assets;
use crate::models::arenas::Arena;
use crate::models::objects::composite::GeneratedObject;
use crate::models::objects::hook_frame::HookFrame;
use crate::models::objects::ratcheting_wrench::RatchetingWrench;
use crate::models::objects::stand_with_mount::StandWithMount;
use crate::models::robots::RobotModel;
use crate::observables::{Modality, Observable};
use crate::placement::{Axis, PlacedObject, Rotation, UniformRandomSampler, with_init_quat};
use crate::robots::Robot;
use crate::sim::{GeomSet, Sim, any_contact_between, body_id, geom_id, site_id};
use gym_core::{DType, EnvRng, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use std::f64::consts::PI;

/// robosuite's `agentview` camera for ToolHang: position.
const AGENTVIEW_POS: [f64; 3] = [0.4837275266036987, 0.2505579098815722, 1.2639379055124524];
/// robosuite's `sideview` camera for ToolHang: position (agentview's, 5 cm lower).
const SIDEVIEW_POS: [f64; 3] = [0.4837275266036987, 0.2505579098815722, 1.2139379055124524];
/// The orientation of both cameras (wxyz).
const CAMERA_QUAT: [f64; 4] = [
    0.39713290333747864,
    0.27807527780532837,
    0.5016612410545349,
    0.7164464592933655,
];

/// ToolHang's settings (robosuite's constructor defaults).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ToolHangSpec {
    /// The table's full size (default 0.8 × 0.8 × 0.05).
    pub table_full_size: [f64; 3],
    /// The table's friction (default `(1, 0.005, 0.0001)`).
    pub table_friction: [f64; 3],
}

impl Default for ToolHangSpec {
    fn default() -> Self {
        Self {
            table_full_size: [0.8, 0.8, 0.05],
            table_friction: [1.0, 5e-3, 1e-4],
        }
    }
}

/// The objects as ToolHang builds them (its `stand_args`, `frame_args`, `real_tool_args`).
struct Objects {
    stand: StandWithMount,
    frame: HookFrame,
    tool: RatchetingWrench,
}

impl Objects {
    fn new(assets: &Assets) -> Result<Self> {
        Ok(Self {
            stand: StandWithMount::tool_hang(assets)?,
            frame: HookFrame::tool_hang(assets)?,
            tool: RatchetingWrench::tool_hang(assets)?,
        })
    }
}

/// One object's sampler (robosuite's `_get_placement_initializer`), the object's extent and
/// its `init_quat` (xyzw), if it has one.
#[derive(Debug, Clone, PartialEq)]
struct Placement {
    sampler: UniformRandomSampler,
    extent: PlacedObject,
    init_quat: Option<[f64; 4]>,
}

impl ToolHangSpec {
    /// robosuite's three samplers, in its order (stand, frame, tool): centres
    /// `(−0.1·L, 0)`, `(−0.05·L, −0.3·W)`, `(0.05·L, −0.25·W)` with tolerances 0, 2 cm,
    /// 2 cm; rotations `0`, `−π/2 + π/6 ± π/18` about y, `−π/2 − π/9 ± π/18` about z; no
    /// boundary or overlap checks; the frame's height offset tuned to its figures as
    /// robosuite tunes it.
    fn placements(
        &self,
        stand: &StandWithMount,
        frame: &HookFrame,
        extents: [PlacedObject; 3],
    ) -> [Placement; 3] {
        let [l, w, _] = self.table_full_size;
        let x = [-l * 0.1, -l * 0.05, l * 0.05];
        let y = [0.0, -w * 0.3, -w * 0.25];
        let tol = [0.0, 0.02, 0.02];
        let rot = [0.0, (-PI / 2.0) + (PI / 6.0), (-PI / 2.0) - (PI / 9.0)];
        let rot_tol = [0.0, PI / 18.0, PI / 18.0];
        let axes = [Axis::Z, Axis::Y, Axis::Z];
        let grip_half_height = frame.grip.map_or(0.0, |g| g.size[1]);
        let mut frame_z = (frame.frame_thickness - frame.frame_height) / 2.0
            + 0.001
            + (stand.base_thickness / 2.0)
            + grip_half_height;
        if let Some(t) = frame.tip {
            frame_z -= t.cylinder_half_height + 2.0 * t.cone_height;
        }
        let z = [0.001, frame_z, 0.001];
        let init = [Some(stand.init_quat()), Some(frame.init_quat()), None];
        std::array::from_fn(|i| Placement {
            sampler: UniformRandomSampler {
                x_range: [x[i] - tol[i], x[i] + tol[i]],
                y_range: [y[i] - tol[i], y[i] + tol[i]],
                rotation: Rotation::Range(rot[i] - rot_tol[i], rot[i] + rot_tol[i]),
                rotation_axis: axes[i],
                ensure_object_boundary_in_range: false,
                ensure_valid_placement: false,
                reference_pos: TABLE_OFFSET,
                z_offset: z[i],
            },
            extent: extents[i],
            init_quat: init[i],
        })
    }
}

impl TaskSpec for ToolHangSpec {
    fn options(&self) -> TaskOptions {
        options::to_options(self)
    }

    fn configure(&mut self, options: &TaskOptions) -> Result<()> {
        *self = options::merged(self.name(), self, options)?;
        Ok(())
    }

    fn name(&self) -> &str {
        "ToolHang"
    }

    fn build(&self, assets: &Assets, _robots: &mut [RobotModel]) -> Result<TaskScene> {
        let mut arena = Arena::table(
            assets,
            "arenas/table_arena.xml",
            self.table_full_size,
            self.table_friction,
            TABLE_OFFSET,
        )?;
        arena.set_origin([0.0; 3])?;
        arena.set_camera("agentview", AGENTVIEW_POS, CAMERA_QUAT)?;
        arena.set_camera("sideview", SIDEVIEW_POS, CAMERA_QUAT)?;
        let o = Objects::new(assets)?;
        Ok(TaskScene {
            arena,
            objects: vec![o.stand.build()?, o.frame.build()?, o.tool.build()?],
            attached: Vec::new(),
        })
    }

    fn bind(&self, scene: &TaskScene, model: &MjModel, robots: &[Robot]) -> Result<Box<dyn Task>> {
        let [stand, frame, tool] = &scene.objects[..] else {
            return Err(gym_core::Error::model(format!(
                "ToolHang's scene holds 3 objects, got {}",
                scene.objects.len()
            )));
        };
        // The figures the checks and the placement read (robosuite keeps its `*_args`).
        let assets = Assets::locate()?;
        let o = Objects::new(&assets)?;
        let hole1: Vec<usize> = (0..o.tool.ngeoms)
            .map(|i| geom_id(model, &format!("tool_hole1_hc_{i}")))
            .collect::<Result<_>>()?;
        let walls = [0, 1, 2, 3].map(|i| geom_id(model, &format!("stand_wall{i}")));
        let [w0, w1, w2, w3] = walls;
        let stand_base = geom_id(model, "stand_base")?;
        let frame_intersection = site_id(model, "frame_intersection_site")?;
        let tool_body = body_id(model, &tool.root_body())?;
        let mut fingers: Vec<i32> = Vec::new();
        for robot in robots.iter().take(1) {
            for arm in robot.arms() {
                fingers.extend_from_slice(arm.gripper().finger_geoms().ids());
            }
        }
        let task = ToolHang {
            placements: self.placements(
                &o.stand,
                &o.frame,
                [stand.placement(), frame.placement(), tool.placement()],
            ),
            stand: FreeBody::bind(model, stand)?,
            frame: FreeBody::bind(model, frame)?,
            tool: FreeBody::bind(model, tool)?,
            stand_base,
            stand_walls: [w0?, w1?, w2?, w3?],
            stand_mount_site: site_id(model, "stand_mount_site")?,
            frame_hang_site: site_id(model, "frame_hang_site")?,
            frame_mount_site: site_id(model, "frame_mount_site")?,
            frame_intersection_site: frame_intersection,
            frame_tip_site: match o.frame.tip {
                Some(_) => Some(site_id(model, "frame_tip_site")?),
                None => None,
            },
            frame_bar: GeomSet::new([geom_id(model, "frame_horizontal_frame")?]),
            tool_hole1_geoms: GeomSet::new(hole1.iter().copied()),
            tool_hole1_first: hole1[0],
            tool_hole1_opposite: hole1[o.tool.ngeoms / 2],
            tool_hole1_center: site_id(model, "tool_hole1_center")?,
            robot_fingers: GeomSet::new(fingers.iter().map(|&g| g as usize)),
            hanging_tolerance: o.tool.inner_radii[0] - (o.frame.frame_thickness / 2.0),
            sensors: ObjectSensors::new(
                vec![
                    PoseRef::Geom(stand_base),
                    PoseRef::Site(frame_intersection),
                    PoseRef::BodyFrame(tool_body),
                ],
                robots,
            ),
        };
        // robosuite's order: the inactive world pose first, then the objects'.
        let mut observables = task
            .sensors
            .world_pose_observables(|t: &ToolHang| &t.sensors);
        for (i, name) in ["base", "frame", "tool"].iter().enumerate() {
            observables.extend(task.sensors.observables(
                |t: &ToolHang| &t.sensors,
                i,
                name,
                DType::F32,
            ));
        }
        observables.push(Observable::new(
            "frame_is_assembled",
            &[],
            DType::F64,
            Modality::Object,
            |t: &ToolHang, sim, out| out[0] = f64::from(u8::from(t.frame_is_assembled(sim))),
        ));
        observables.push(Observable::new(
            "tool_on_frame",
            &[],
            DType::F64,
            Modality::Object,
            |t: &ToolHang, sim, out| out[0] = f64::from(u8::from(t.tool_on_frame(sim))),
        ));
        Ok(Bound::boxed(task, observables))
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// `a` on opposite sides of the line along `dir` from `b`: `(a × dir)·(b × dir) < 0`.
fn opposite_sides(a: [f64; 3], b: [f64; 3], dir: [f64; 3]) -> bool {
    dot(cross(a, dir), cross(b, dir)) < 0.0
}

/// The bound ToolHang task: a stand (`stand_root`), a hook frame (`frame_root`) and a
/// ratcheting wrench (`tool_root`), free bodies on Lift's table.
///
/// * Reset (no overlap checks, robosuite's sampler order): stand at `(−0.08, 0)` upright;
///   frame at `(−0.04, −0.24) ± 0.02` lying flat, turned about y by `−π/3 ± π/18` composed
///   with its `init_quat` as robosuite's sampler composes them (float32); tool at
///   `(0.04, −0.2) ± 0.02`, yawed `−11π/18 ± π/18`.
/// * `frame_is_assembled`: the stand's shaft within 10° of vertical, the frame's tip within
///   5 cm of the stand's base, and the rod between both pairs of opposite mount walls.
/// * `tool_on_frame`: no finger or finger-pad geom touches the tool, a box of hole 1 touches
///   the frame's bar, the hole's centre is within `r_in − thickness / 2` of the bar's line,
///   boxes 0 and 4 of the hole are on opposite sides of it, and the hole is 5–100 % along
///   the bar from the hook.
/// * Success: both. Reward: `reward_scale` (1 when unscaled) on success, else 0; reward
///   shaping changes nothing (as in robosuite).
/// * Observations (44 values): per object (`base`: geom `stand_base`, `frame`: site
///   `frame_intersection_site`, `tool`: body `tool_root`) the pose relative to the gripper
///   (from the previous observation's object pose, see [`ObjectSensors`]), position and
///   float32 quaternion; then `frame_is_assembled` and `tool_on_frame` as 0 / 1.
#[derive(Debug, Clone)]
pub struct ToolHang {
    placements: [Placement; 3],
    stand: FreeBody,
    frame: FreeBody,
    tool: FreeBody,
    stand_base: usize,
    stand_walls: [usize; 4],
    stand_mount_site: usize,
    frame_hang_site: usize,
    frame_mount_site: usize,
    frame_intersection_site: usize,
    frame_tip_site: Option<usize>,
    frame_bar: GeomSet,
    tool_hole1_geoms: GeomSet,
    tool_hole1_first: usize,
    tool_hole1_opposite: usize,
    tool_hole1_center: usize,
    robot_fingers: GeomSet,
    hanging_tolerance: f64,
    sensors: ObjectSensors,
}

impl ToolHang {
    /// robosuite's `_check_frame_assembled`: the stand upright (its shaft within 10° of
    /// the z axis), the frame's tip (or mount end) within 5 cm of the stand's base, and the
    /// rod between the stand's opposite walls.
    pub fn frame_is_assembled(&self, sim: &Sim) -> bool {
        let d = sim.data();
        let base = d.geom_xpos()[self.stand_base];
        let shaft = sub(d.site_xpos()[self.stand_mount_site], base);
        let n = norm(shaft);
        let shaft = shaft.map(|v| v / n);
        // As robosuite: no clamping, so a rounding past 1 gives NaN and fails the check.
        let vertical = shaft[2].acos().abs() < PI / 18.0;
        let bottom = d.site_xpos()[self.frame_tip_site.unwrap_or(self.frame_mount_site)];
        let close = norm(sub(bottom, base)) < 0.05;
        let end = d.site_xpos()[self.frame_mount_site];
        let hook = sub(d.site_xpos()[self.frame_intersection_site], end);
        let length = norm(hook);
        let hook = hook.map(|v| v / length);
        let w = self.stand_walls.map(|g| sub(d.geom_xpos()[g], end));
        let between = opposite_sides(w[0], w[2], hook) && opposite_sides(w[1], w[3], hook);
        vertical && (close && between)
    }

    /// robosuite's `_check_tool_on_frame`: the robot's fingers do not touch the tool, hole
    /// 1 touches the frame's bar, its centre is close to the bar's line with two opposite
    /// boxes on either side, and it is 5–100 % along the bar.
    pub fn tool_on_frame(&self, sim: &Sim) -> bool {
        let d = sim.data();
        let touched = any_contact_between(d, &self.robot_fingers, &self.tool.geoms);
        let on_bar = any_contact_between(d, &self.tool_hole1_geoms, &self.frame_bar);
        let end = d.site_xpos()[self.frame_hang_site];
        let hook = sub(d.site_xpos()[self.frame_intersection_site], end);
        let length = norm(hook);
        let hook = hook.map(|v| v / length);
        let hole = sub(d.site_xpos()[self.tool_hole1_center], end);
        let along = dot(hole, hook);
        let ortho = sub(hole, hook.map(|v| along * v));
        let close = norm(ortho) < self.hanging_tolerance;
        let g1 = sub(d.geom_xpos()[self.tool_hole1_first], end);
        let g2 = sub(d.geom_xpos()[self.tool_hole1_opposite], end);
        let around = opposite_sides(g1, g2, hook);
        let fraction = along / length;
        let inserted = fraction > 0.05 && fraction < 1.0;
        !touched && on_bar && close && around && inserted
    }

    /// The stand, frame and tool as free bodies (in that order).
    pub fn bodies(&self) -> [&FreeBody; 3] {
        [&self.stand, &self.frame, &self.tool]
    }
}

impl TaskLogic for ToolHang {
    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let bodies = [&self.stand, &self.frame, &self.tool];
        for (p, body) in self.placements.iter().zip(bodies) {
            let (pos, mut quat) = p.sampler.sample(rng, &[p.extent], &[])?[0];
            if let Some(init) = p.init_quat {
                quat = with_init_quat(quat, init);
            }
            body.set_pose(sim, pos, quat);
        }
        Ok(())
    }

    fn clear_observation_cache(&mut self) {
        self.sensors.clear();
    }

    fn after_observe(&mut self, sim: &Sim) {
        self.sensors.remember(sim);
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let reward = if self.check_success(sim, robots) {
            1.0
        } else {
            0.0
        };
        scale_reward(reward, config.reward_scale, 1.0)
    }

    fn check_success(&self, sim: &Sim, _robots: &[Robot]) -> bool {
        self.frame_is_assembled(sim) && self.tool_on_frame(sim)
    }

    /// The observation cache (empty right after a reset, else the three objects' cached
    /// poses, 21 values): ToolHang draws no model parameters.
    fn save_state(&self) -> Vec<f64> {
        self.sensors.save()
    }

    fn load_state(&mut self, _sim: &mut Sim, state: &[f64]) -> Result<()> {
        self.sensors.load(state)
    }
}
