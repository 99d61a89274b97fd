//! robosuite's `ToolHang`: insert the hook frame into the stand, then hang the ratcheting
//! wrench on the hook (`tool_hang.py`).

use super::common::{FreeBody, is_grasped, quat_mul};
use super::placement::{Axis, PlacedObject, Pose, Rotation, UniformRandomSampler};
use super::{ModelSource, RewardConfig, Task};
use crate::controllers::math::{mat_from_row_major, mat2quat};
use crate::models::arenas::TableArena;
use crate::models::scene::SceneBuilder;
use crate::observations::ObsKey;
use crate::robots::Robot;
use crate::sim::{GeomSet, Sim, any_contact_between, geom_id, site_id};
use gym_core::{DType, EnvRng, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// The stand's full size (0.12 × 0.14 × 0.16 m).
pub const STAND_SIZE: [f64; 3] = [0.12, 0.14, 0.16];
/// Where the rod cavity sits on the stand (x, y from its centre).
pub const STAND_MOUNT: [f64; 2] = [0.0, 0.045];
/// Width of the rod cavity.
pub const STAND_MOUNT_WIDTH: f64 = 0.012;
/// Thickness of the cavity walls.
pub const STAND_WALL: f64 = 0.001;
/// Thickness of the stand's base plate.
pub const STAND_BASE: f64 = 0.01;
/// Frame length (the hook bar), height (the rod) and thickness.
pub const FRAME: [f64; 3] = [0.095, 0.18, 0.0075];
/// Height of the hook at the bar's end.
pub const HOOK_HEIGHT: f64 = 0.012;
/// The frame's grip: radius, half-length, and its centre up the rod.
pub const FRAME_GRIP: [f64; 3] = [0.0127, 0.03175, 0.05625];
/// The frame's insertion tip: radius and length below the rod.
pub const FRAME_TIP: [f64; 2] = [0.00325, 0.0508];
/// The wrench's inner radius of hole 1 (0.0105) and the frame thickness set the hanging
/// tolerance.
pub const TOOL_INNER_RADIUS_1: f64 = 0.0105;

/// Our stand (prefix `stand_`): base plate `base` and the four cavity walls `wall0..3`,
/// density 50000, site `mount_site` on top of the centre line.
pub fn stand_xml() -> String {
    let [sx, sy, sz] = STAND_SIZE;
    let w = (STAND_MOUNT_WIDTH - STAND_WALL) / 2.0;
    let xs = [0.0, -w, 0.0, w];
    let ys = [-w, 0.0, w, 0.0];
    let rs = [PI / 2.0, 0.0, -PI / 2.0, PI];
    let contact = r#"density="50000" solref="0.02 1" solimp="0.998 0.998 0.001" friction="1 0.005 0.0001" group="0" rgba="0.7 0.55 0.2 1""#;
    let walls: String = (0..4)
        .map(|i| {
            let (s, c) = (rs[i] / 2.0).sin_cos();
            format!(
                r#"<geom name="wall{i}" type="box" pos="{} {} {}" quat="{c} 0 0 {s}" size="{} {} {}" {contact}/>"#,
                xs[i] + STAND_MOUNT[0],
                ys[i] + STAND_MOUNT[1],
                STAND_BASE / 2.0,
                STAND_WALL / 2.0,
                STAND_MOUNT_WIDTH / 2.0,
                (sz - STAND_BASE) / 2.0
            )
        })
        .collect::<Vec<_>>()
        .join("\n      ");
    format!(
        r#"<mujoco model="stand">
  <compiler angle="radian" autolimits="true" inertiagrouprange="0 0"/>
  <worldbody>
    <body name="main" pos="0 0 1">
      <joint name="joint0" type="free"/>
      <geom name="base" type="box" pos="0 0 {}" size="{} {} {}" {contact}/>
      {walls}
      <site name="mount_site" pos="0 0 {}" size="0.002" rgba="1 0 0 1" type="sphere" group="1"/>
    </body>
  </worldbody>
</mujoco>
"#,
        -(sz - STAND_BASE) / 2.0,
        sx / 2.0,
        sy / 2.0,
        STAND_BASE / 2.0,
        sz / 2.0
    )
}

/// Our hook frame (prefix `frame_`): an L of a rod `vertical_frame` and a bar
/// `horizontal_frame` (0.0075 thick), the hook `hook_frame` at the bar's end, the grip
/// `grip_frame` on the rod and the insertion tip `tip_frame` below it; density 500; sites
/// `hang_site`, `mount_site`, `intersection_site`, `tip_site`.
pub fn frame_xml() -> String {
    let [l, h, t] = FRAME;
    let rod_x = (l - t) / 2.0;
    let contact = r#"density="500" solref="0.02 1" solimp="0.998 0.998 0.001" friction="1 0.005 0.0001" group="0" rgba="0.7 0.55 0.2 1""#;
    let tip_center = -h / 2.0 - FRAME_TIP[1] / 2.0;
    format!(
        r#"<mujoco model="frame">
  <compiler angle="radian" autolimits="true" inertiagrouprange="0 0"/>
  <worldbody>
    <body name="main" pos="0 0 1">
      <joint name="joint0" type="free"/>
      <geom name="vertical_frame" type="box" pos="{rod_x} 0 {}" size="{} {} {}" {contact}/>
      <geom name="horizontal_frame" type="box" pos="0 0 {}" size="{} {} {}" {contact}/>
      <geom name="hook_frame" type="box" pos="{} 0 {}" size="{} {} {}" {contact}/>
      <geom name="grip_frame" type="cylinder" pos="{rod_x} 0 {}" size="{} {}" {contact}/>
      <geom name="tip_frame" type="cylinder" pos="{rod_x} 0 {tip_center}" size="{} {}" {contact}/>
      <site name="hang_site" pos="{} 0 {}" size="0.002" rgba="1 0 0 1" type="sphere" group="1"/>
      <site name="mount_site" pos="{rod_x} 0 {}" size="0.002" rgba="0 1 0 1" type="sphere" group="1"/>
      <site name="intersection_site" pos="{rod_x} 0 {}" size="0.002" rgba="0 0 1 1" type="sphere" group="1"/>
      <site name="tip_site" pos="{rod_x} 0 {}" size="0.002" rgba="1 1 0 1" type="sphere" group="1"/>
    </body>
  </worldbody>
</mujoco>
"#,
        -t / 2.0,
        t / 2.0,
        t / 2.0,
        (h - t) / 2.0,
        (h - t) / 2.0,
        l / 2.0,
        t / 2.0,
        t / 2.0,
        (-l + t) / 2.0,
        (h + HOOK_HEIGHT) / 2.0,
        t / 2.0,
        t / 2.0,
        HOOK_HEIGHT / 2.0,
        -t / 2.0 + FRAME_GRIP[2],
        FRAME_GRIP[0],
        FRAME_GRIP[1],
        FRAME_TIP[0],
        FRAME_TIP[1] / 2.0,
        -l / 2.0,
        (h - t) / 2.0,
        -h / 2.0,
        (h - t) / 2.0,
        -h / 2.0 - FRAME_TIP[1],
    )
}

/// A ring of `n` boxes (robosuite's `HollowCylinderObject`) named `{name}_hc_{i}`, centred
/// at `x` along the body's x axis, axis along z.
fn ring(
    name: &str,
    x: f64,
    outer: f64,
    inner: f64,
    half_height: f64,
    n: usize,
    contact: &str,
) -> String {
    let nf = n as f64;
    let w = outer * (PI / nf).sin();
    let hh = (outer - inner) * (PI / nf).cos() / 2.0;
    let r = inner * (PI / nf).cos() + hh;
    (0..n)
        .map(|i| {
            let a = PI - i as f64 * 2.0 * PI / nf;
            let (s, c) = (a / 2.0).sin_cos();
            format!(
                r#"<geom name="{name}_hc_{i}" type="box" pos="{} {} 0" quat="{c} 0 0 {s}" size="{hh} {w} {half_height}" condim="4" {contact}/>"#,
                x + r * a.cos(),
                r * a.sin()
            )
        })
        .collect::<Vec<_>>()
        .join("\n      ")
}

/// Our ratcheting wrench (prefix `tool_`): a 0.165 m handle `handle` between two rings
/// (`hole1`: radii 0.0175 / 0.0105, `hole2`: 0.015 / 0.01, 8 boxes each, 7 mm tall) and a
/// grip around the handle (`grip`, r 0.015, 8 cm; a solid cylinder of matched mass in place
/// of robosuite's 50-box shell); density 2000, friction (0.95, 0.3, 0.1), free-joint
/// damping 0.0005; sites `hole1_center`, `hole2_center`.
pub fn tool_xml() -> String {
    let contact = r#"density="2000" solref="0.02 1" solimp="0.998 0.998 0.001" friction="0.95 0.3 0.1" group="0" rgba="0.6 0.6 0.65 1""#;
    let hx = 0.165 / 2.0;
    let unit = |outer: f64, inner: f64| (outer - inner) * (PI / 8.0).cos() / 2.0;
    let x1 = -hx - 0.0175 + 2.0 * unit(0.0175, 0.0105);
    let x2 = hx + 0.015 - 2.0 * unit(0.015, 0.01);
    // A solid grip with the hollow one's mass: density 2000 · (1 − (r_in/r_out)²).
    let grip_density = 2000.0 * (1.0 - (0.00875f64 / 0.015).powi(2));
    format!(
        r#"<mujoco model="tool">
  <compiler angle="radian" autolimits="true" inertiagrouprange="0 0"/>
  <worldbody>
    <body name="main" pos="0 0 1">
      <joint name="joint0" type="free" damping="0.0005"/>
      {}
      {}
      <geom name="handle" type="box" pos="0 0 0" size="{hx} 0.00875 0.0016" {contact}/>
      <geom name="grip" type="cylinder" pos="0 0 0" quat="{FRAC_1_SQRT_2} 0 {FRAC_1_SQRT_2} 0" size="0.015 0.04" density="{grip_density}" solref="0.02 1" solimp="0.998 0.998 0.001" friction="0.95 0.3 0.1" group="0" rgba="0.6 0.2 0.1 1"/>
      <site name="hole1_center" pos="{x1} 0 0" size="0.002" rgba="1 0 0 1" type="sphere" group="1"/>
      <site name="hole2_center" pos="{x2} 0 0" size="0.002" rgba="1 0 0 1" type="sphere" group="1"/>
    </body>
  </worldbody>
</mujoco>
"#,
        ring("hole1", x1, 0.0175, 0.0105, 0.0035, 8, contact),
        ring("hole2", x2, 0.015, 0.01, 0.0035, 8, contact),
    )
}

/// The hook frame's `init_quat` (xyzw), which robosuite's sampler multiplies onto its
/// sampled rotation (lays the frame flat).
const FRAME_INIT_QUAT_XYZW: [f64; 4] = [-0.5, -0.5, 0.5, 0.5];

/// robosuite's `quat_multiply(sampled, init_quat)` as its sampler calls it: the sampled
/// quaternion is wxyz but is multiplied as if it were xyzw, and the product is used as wxyz.
fn robosuite_init_quat(sampled_wxyz: [f64; 4], init_xyzw: [f64; 4]) -> [f64; 4] {
    // quat_multiply(q1, q0) in xyzw is the Hamilton product q1·q0.
    let to_wxyz = |q: [f64; 4]| [q[3], q[0], q[1], q[2]];
    let p = quat_mul(to_wxyz(sampled_wxyz), to_wxyz(init_xyzw));
    let out = [p[1], p[2], p[3], p[0]];
    let n = out.iter().map(|v| v * v).sum::<f64>().sqrt();
    out.map(|v| v / n)
}

/// The ToolHang task.
///
/// * Lift's table and robot base; objects `stand`, `frame` and `tool` (free joints).
/// * Reset (no overlap checks): stand at (−0.08, 0) upright; frame at (−0.04, −0.24) ± 0.02
///   lying flat, rotated about y by (−π/2 + π/6) ± π/18 (times the frame's initial
///   rotation, as robosuite's sampler composes them); tool at (0.04, −0.2) ± 0.02 with yaw
///   (−π/2 − π/9) ± π/18.
/// * Success: `frame_is_assembled` (stand upright within 10°, the frame tip within 5 cm of
///   the stand base, the rod between the cavity walls) and `tool_on_frame` (no finger-pad
///   contact with the tool, hole 1 touching the bar, its centre within 0.00675 m of the
///   bar's line, two opposite ring boxes on either side, inserted 5–100 % along the bar).
/// * Reward: `reward_scale` on success, else 0 (shaping is ignored, as in robosuite).
#[derive(Debug, Clone, Default)]
pub struct ToolHang {
    table: TableArena,
    stand: FreeBody,
    frame: FreeBody,
    tool: FreeBody,
    stand_base: usize,
    stand_walls: [usize; 4],
    stand_mount_site: usize,
    frame_hang_site: usize,
    frame_mount_site: usize,
    frame_intersection_site: usize,
    frame_tip_site: usize,
    frame_bar: GeomSet,
    tool_hole1: Vec<usize>,
    tool_hole1_geoms: GeomSet,
    tool_hole1_center: usize,
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
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

impl ToolHang {
    /// A new ToolHang with robosuite's settings.
    pub fn new() -> Self {
        Self::default()
    }

    /// robosuite's `_check_frame_assembled`.
    pub fn frame_is_assembled(&self, sim: &Sim) -> bool {
        let d = sim.data();
        let base = d.geom_xpos()[self.stand_base];
        let shaft = sub(d.site_xpos()[self.stand_mount_site], base);
        let vertical = (shaft[2] / norm(shaft)).clamp(-1.0, 1.0).acos().abs() < PI / 18.0;
        let tip = d.site_xpos()[self.frame_tip_site];
        let close = norm(sub(tip, base)) < 0.05;
        let end = d.site_xpos()[self.frame_mount_site];
        let hook = sub(d.site_xpos()[self.frame_intersection_site], end);
        let hook = hook.map(|v| v / norm(hook));
        let w = self.stand_walls.map(|g| sub(d.geom_xpos()[g], end));
        let between = dot(cross(w[0], hook), cross(w[2], hook)) < 0.0
            && dot(cross(w[1], hook), cross(w[3], hook)) < 0.0;
        vertical && close && between
    }

    /// robosuite's `_check_tool_on_frame`.
    pub fn tool_on_frame(&self, sim: &Sim, robots: &[Robot]) -> bool {
        let d = sim.data();
        let touched_by_robot =
            robots
                .first()
                .and_then(Robot::finger_pads)
                .is_some_and(|(left, right)| {
                    any_contact_between(d, left, &self.tool.geoms)
                        || any_contact_between(d, right, &self.tool.geoms)
                });
        let on_bar = any_contact_between(d, &self.tool_hole1_geoms, &self.frame_bar);
        let end = d.site_xpos()[self.frame_hang_site];
        let hook = sub(d.site_xpos()[self.frame_intersection_site], end);
        let length = norm(hook);
        let hook = hook.map(|v| v / length);
        let hole = sub(d.site_xpos()[self.tool_hole1_center], end);
        let along = dot(hole, hook);
        let ortho = sub(hole, hook.map(|v| v * along));
        let close = norm(ortho) < TOOL_INNER_RADIUS_1 - FRAME[2] / 2.0;
        let g1 = sub(d.geom_xpos()[self.tool_hole1[0]], end);
        let g2 = sub(
            d.geom_xpos()[self.tool_hole1[self.tool_hole1.len() / 2]],
            end,
        );
        let around = dot(cross(g1, hook), cross(g2, hook)) < 0.0;
        let fraction = along / length;
        let inserted = fraction > 0.05 && fraction < 1.0;
        !touched_by_robot && on_bar && close && around && inserted
    }

    /// Whether the robot grasps the tool (both finger pads touch it).
    pub fn tool_grasped(&self, sim: &Sim, robots: &[Robot]) -> bool {
        is_grasped(sim, robots, &self.tool.geoms)
    }
}

fn quat_from_xmat(m: &[f64; 9]) -> [f64; 4] {
    // robosuite's T.mat2quat (xyzw), computed in float32 there.
    mat2quat(&mat_from_row_major(m)).map(|v| f64::from(v as f32))
}

impl Task for ToolHang {
    fn name(&self) -> &str {
        "ToolHang"
    }

    fn robot_base_pose(&self, _index: usize) -> ([f64; 3], [f64; 4]) {
        (
            [-0.16 - self.table.full_size[0] / 2.0, 0.0, 0.912],
            [1.0, 0.0, 0.0, 0.0],
        )
    }

    fn arena_xml(&self) -> String {
        self.table.to_xml()
    }

    fn build_objects(&self, scene: &mut SceneBuilder) -> Result<()> {
        scene.add_part("stand", &stand_xml(), "stand_")?;
        scene.add_part("frame", &frame_xml(), "frame_")?;
        scene.add_part("tool", &tool_xml(), "tool_")?;
        Ok(())
    }

    fn bind(&mut self, model: &MjModel, _robots: &[Robot], _source: ModelSource) -> Result<()> {
        let names = |prefix: &str, list: &[&str]| -> Vec<String> {
            list.iter().map(|n| format!("{prefix}{n}")).collect()
        };
        self.stand = FreeBody::bind(
            model,
            "stand_main",
            "stand_joint0",
            &names("stand_", &["base", "wall0", "wall1", "wall2", "wall3"]),
        )?;
        self.frame = FreeBody::bind(
            model,
            "frame_main",
            "frame_joint0",
            &names(
                "frame_",
                &[
                    "vertical_frame",
                    "horizontal_frame",
                    "hook_frame",
                    "grip_frame",
                    "tip_frame",
                ],
            ),
        )?;
        let mut tool_geoms: Vec<String> = (0..8).map(|i| format!("tool_hole1_hc_{i}")).collect();
        tool_geoms.extend((0..8).map(|i| format!("tool_hole2_hc_{i}")));
        tool_geoms.push("tool_handle".into());
        tool_geoms.push("tool_grip".into());
        self.tool = FreeBody::bind(model, "tool_main", "tool_joint0", &tool_geoms)?;
        self.stand_base = geom_id(model, "stand_base")?;
        for (i, w) in self.stand_walls.iter_mut().enumerate() {
            *w = geom_id(model, &format!("stand_wall{i}"))?;
        }
        self.stand_mount_site = site_id(model, "stand_mount_site")?;
        self.frame_hang_site = site_id(model, "frame_hang_site")?;
        self.frame_mount_site = site_id(model, "frame_mount_site")?;
        self.frame_intersection_site = site_id(model, "frame_intersection_site")?;
        self.frame_tip_site = site_id(model, "frame_tip_site")?;
        self.frame_bar = GeomSet::new([geom_id(model, "frame_horizontal_frame")?]);
        self.tool_hole1 = (0..8)
            .map(|i| geom_id(model, &format!("tool_hole1_hc_{i}")))
            .collect::<Result<_>>()?;
        self.tool_hole1_geoms = GeomSet::new(self.tool_hole1.iter().copied());
        self.tool_hole1_center = site_id(model, "tool_hole1_center")?;
        Ok(())
    }

    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        let [tx, ty, _] = self.table.full_size;
        let sampler =
            |x: f64, xt: f64, y: f64, yt: f64, r: f64, rt: f64, axis: Axis| UniformRandomSampler {
                x_range: [x - xt, x + xt],
                y_range: [y - yt, y + yt],
                rotation: Rotation::Range(r - rt, r + rt),
                rotation_axis: axis,
                ensure_object_boundary_in_range: false,
                ensure_valid_placement: false,
                reference_pos: self.table.top,
                z_offset: 0.001,
            };
        let extent = |bottom: f64, top: f64, r: f64| PlacedObject {
            horizontal_radius: r,
            bottom_offset: bottom,
            top_offset: top,
        };
        let stand: Pose = sampler(-tx * 0.1, 0.0, 0.0, 0.0, 0.0, 0.0, Axis::Z).sample(
            rng,
            &[extent(-STAND_SIZE[2] / 2.0, STAND_SIZE[2] / 2.0, 0.092)],
            &[],
        )?[0];
        // The frame lies flat on its grip (our geometry; robosuite tunes its z offset to its
        // own bounding box).
        let (fpos, fq) = sampler(
            -tx * 0.05,
            0.02,
            -ty * 0.3,
            0.02,
            -PI / 2.0 + PI / 6.0,
            PI / 18.0,
            Axis::Y,
        )
        .sample(rng, &[extent(-FRAME_GRIP[0], FRAME_GRIP[0], 0.1)], &[])?[0];
        let tool: Pose = sampler(
            tx * 0.05,
            0.02,
            -ty * 0.25,
            0.02,
            -PI / 2.0 - PI / 9.0,
            PI / 18.0,
            Axis::Z,
        )
        .sample(rng, &[extent(-0.015, 0.015, 0.2)], &[])?[0];
        self.stand.set_pose(sim, stand.0, stand.1);
        self.frame
            .set_pose(sim, fpos, robosuite_init_quat(fq, FRAME_INIT_QUAT_XYZW));
        self.tool.set_pose(sim, tool.0, tool.1);
        Ok(())
    }

    fn observation_keys(&self) -> Vec<ObsKey> {
        let mut k = Vec::new();
        for n in ["base", "frame", "tool"] {
            k.push(ObsKey::new(
                format!("{n}_to_robot0_eef_pos"),
                &[3],
                DType::F64,
            ));
            k.push(ObsKey::new(
                format!("{n}_to_robot0_eef_quat"),
                &[4],
                DType::F64,
            ));
            k.push(ObsKey::new(format!("{n}_pos"), &[3], DType::F64));
            k.push(ObsKey::new(format!("{n}_quat"), &[4], DType::F32));
        }
        k.push(ObsKey::new("frame_is_assembled", &[], DType::F64));
        k.push(ObsKey::new("tool_on_frame", &[], DType::F64));
        k
    }

    fn write_observations(&self, sim: &Sim, robots: &[Robot], out: &mut [f64]) {
        let d = sim.data();
        let poses = [
            (
                d.geom_xpos()[self.stand_base],
                quat_from_xmat(&d.geom_xmat()[self.stand_base]),
            ),
            (
                d.site_xpos()[self.frame_intersection_site],
                quat_from_xmat(&d.site_xmat()[self.frame_intersection_site]),
            ),
            (
                d.xpos()[self.tool.body],
                quat_from_xmat(&d.xmat()[self.tool.body]),
            ),
        ];
        for (i, (p, q_xyzw)) in poses.iter().enumerate() {
            let q_wxyz = [q_xyzw[3], q_xyzw[0], q_xyzw[1], q_xyzw[2]];
            super::common::write_object_pose_obs(
                sim,
                robots,
                *p,
                q_wxyz,
                &mut out[14 * i..14 * (i + 1)],
            );
            // The absolute quaternion keeps robosuite's float32 values.
            out[14 * i + 10..14 * i + 14].copy_from_slice(q_xyzw);
        }
        out[42] = f64::from(u8::from(self.frame_is_assembled(sim)));
        out[43] = f64::from(u8::from(self.tool_on_frame(sim, robots)));
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let r = if self.check_success(sim, robots) {
            1.0
        } else {
            0.0
        };
        match config.reward_scale {
            Some(s) => r * s,
            None => r,
        }
    }

    fn check_success(&self, sim: &Sim, robots: &[Robot]) -> bool {
        self.frame_is_assembled(sim) && self.tool_on_frame(sim, robots)
    }
}
