//! robosuite's `Wipe`: wipe a path of 100 markers off the table with a flat tool
//! (`wipe.py`, `WipeArena`).

use super::common::eef_pos;
use super::{ModelSource, RewardConfig, Task};
use crate::models::arenas::TableArena;
use crate::models::scene::SceneBuilder;
use crate::observations::ObsKey;
use crate::robots::{ARM_DOF, Robot, RobotSpec, WIPING_GRIPPER};
use crate::sim::{GeomSet, Sim, any_contact_between, body_id, geom_id, joint_id, sensor_adr};
use gym_core::{DType, EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use rand::RngExt;
use rand_distr::StandardNormal;
use std::f64::consts::PI;

/// robosuite's `DEFAULT_WIPE_CONFIG` (the values this port uses).
#[derive(Debug, Clone, PartialEq)]
pub struct WipeConfig {
    /// Reward for an arm collision or a joint near its limit (−10).
    pub arm_limit_collision_penalty: f64,
    /// Reward for keeping contact (0.01).
    pub wipe_contact_reward: f64,
    /// Reward per wiped marker (50).
    pub unit_wiped_reward: f64,
    /// Force penalty factor above `pressure_threshold_max` (0.05).
    pub excess_force_penalty_mul: f64,
    /// Weight of the distance-to-centroid term (5).
    pub distance_multiplier: f64,
    /// Scale inside its tanh (5).
    pub distance_th_multiplier: f64,
    /// Table full size (0.5, 0.8, 0.05).
    pub table_full_size: [f64; 3],
    /// Table top centre (0.15, 0, 0.9).
    pub table_offset: [f64; 3],
    /// Table friction (0.03, 0.005, 0.0001).
    pub table_friction: [f64; 3],
    /// Marker diameter (0.04).
    pub line_width: f64,
    /// Fraction of the table the path may cover (0.6).
    pub coverage_factor: f64,
    /// Number of markers (100).
    pub num_markers: usize,
    /// Force (N) above the bias that counts as tool contact (1.0).
    pub contact_threshold: f64,
    /// Force (N) above which pressing is rewarded (0.5).
    pub pressure_threshold: f64,
    /// Force (N) above which pressing is penalised (60).
    pub pressure_threshold_max: f64,
    /// End the episode on arm contact, joint limit or success (true).
    pub early_terminations: bool,
}

impl Default for WipeConfig {
    fn default() -> Self {
        Self {
            arm_limit_collision_penalty: -10.0,
            wipe_contact_reward: 0.01,
            unit_wiped_reward: 50.0,
            excess_force_penalty_mul: 0.05,
            distance_multiplier: 5.0,
            distance_th_multiplier: 5.0,
            table_full_size: [0.5, 0.8, 0.05],
            table_offset: [0.15, 0.0, 0.9],
            table_friction: [0.03, 0.005, 0.0001],
            line_width: 0.04,
            coverage_factor: 0.6,
            num_markers: 100,
            contact_threshold: 1.0,
            pressure_threshold: 0.5,
            pressure_threshold_max: 60.0,
            early_terminations: true,
        }
    }
}

impl WipeConfig {
    /// robosuite's `task_complete_reward` = unit · (contact + 0.5) (25.5).
    pub fn task_complete_reward(&self) -> f64 {
        self.unit_wiped_reward * (self.wipe_contact_reward + 0.5)
    }

    /// robosuite's `reward_normalization_factor` for a horizon (0.032776 at 1000).
    pub fn normalization(&self, horizon: u64) -> f64 {
        let h = horizon as f64;
        h / (self.num_markers as f64 * self.unit_wiped_reward
            + h * (self.wipe_contact_reward + self.task_complete_reward()))
    }
}

/// The most direction re-draws per marker before the random walk is declared stuck.
const MAX_WALK_TRIES: usize = 10_000;

/// The Wipe task.
///
/// * Robot: the Panda with the wiping tool ([`WIPING_GRIPPER`]); action `[6 OSC]`;
///   proprioception gains `robot0_contact` (47 values).
/// * Arena: table 0.5 × 0.8 × 0.05 with its top centre at (0.15, 0, 0.9), friction
///   (0.03, 0.005, 0.0001); robot base (−0.41, 0, 0.912); 100 visual markers
///   (`contact{i}_main`, cylinders r 0.02) laid out by robosuite's random walk at every
///   reset (start uniform in ±(half size · 0.6 − 0.02), direction U(−π, π), 5 mm steps, the
///   direction perturbed by N(0, 0.5) with probability 0.3 or when leaving the area).
/// * A marker is wiped when it lies less than 2 cm above the plane of the tool's four
///   corner geoms and inside their rectangle (while there is any contact).
/// * Reward (shaped by default): −10 on arm contact or a joint within 0.1 rad of a limit;
///   else +50 per newly wiped marker, `5·(1 − tanh(5·d(centroid, eef)))`, +0.01 for
///   tool contact, the pressure terms, +25.5 when all are wiped; times
///   `reward_scale · horizon / (5000 + 25.51 · horizon)`.
/// * Success: all markers wiped. Early termination (`terminated`): arm contact, joint
///   limit or success.
#[derive(Debug, Clone)]
pub struct Wipe {
    config: WipeConfig,
    table: TableArena,
    markers: Vec<usize>,
    marker_geoms: Vec<usize>,
    marker_pos: Vec<[f64; 3]>,
    wiped: Vec<bool>,
    corners: [usize; 4],
    arm_geoms: GeomSet,
    all_geoms: GeomSet,
    arm_joints: Vec<(usize, [f64; 2])>,
    force_adr: usize,
    /// `recent_ee_forcetorques.current[:3]`: the force sensor at the step's first substep.
    step_force: [f64; 3],
    force_bias: [f64; 3],
    /// Scratch for `after_reward`: which markers the step wiped (capacity kept).
    newly_wiped: Vec<bool>,
}

impl Wipe {
    /// Wipe with the given settings.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for no markers or a non-positive table.
    pub fn new(config: WipeConfig) -> Result<Self> {
        if config.num_markers == 0 {
            return Err(Error::invalid_argument("num_markers", "must be at least 1"));
        }
        if config
            .table_full_size
            .iter()
            .any(|v| !(v.is_finite() && *v > 0.0))
        {
            return Err(Error::invalid_argument(
                "table_full_size",
                format!("must be positive, got {:?}", config.table_full_size),
            ));
        }
        let table = TableArena {
            full_size: config.table_full_size,
            friction: config.table_friction,
            top: config.table_offset,
        };
        Ok(Self {
            table,
            markers: Vec::new(),
            marker_geoms: Vec::new(),
            marker_pos: vec![[0.0; 3]; config.num_markers],
            wiped: vec![false; config.num_markers],
            corners: [0; 4],
            arm_geoms: GeomSet::default(),
            all_geoms: GeomSet::default(),
            arm_joints: Vec::new(),
            force_adr: 0,
            step_force: [0.0; 3],
            force_bias: [0.0; 3],
            newly_wiped: Vec::with_capacity(config.num_markers),
            config,
        })
    }

    /// The number of wiped markers.
    pub fn wiped_count(&self) -> usize {
        self.wiped.iter().filter(|w| **w).count()
    }

    /// Marker positions (world) as laid out at the last reset.
    pub fn marker_positions(&self, sim: &Sim) -> Vec<[f64; 3]> {
        self.markers.iter().map(|&b| sim.data().xpos()[b]).collect()
    }

    fn half(&self) -> [f64; 3] {
        self.config.table_full_size.map(|v| v / 2.0)
    }

    fn ee_force(&self, sim: &Sim) -> [f64; 3] {
        let s = sim.data().sensordata();
        [
            s[self.force_adr],
            s[self.force_adr + 1],
            s[self.force_adr + 2],
        ]
    }

    /// robosuite's `_has_gripper_contact`: the force sensor deviates from its bias by more
    /// than `contact_threshold`.
    pub fn has_gripper_contact(&self, sim: &Sim) -> bool {
        let f = self.ee_force(sim);
        let d = (0..3)
            .map(|i| (f[i] - self.force_bias[i]).powi(2))
            .sum::<f64>();
        d.sqrt() > self.config.contact_threshold
    }

    /// Whether any arm link touches anything (robosuite's `check_contact(robot_model)`).
    pub fn arm_in_contact(&self, sim: &Sim) -> bool {
        any_contact_between(sim.data(), &self.arm_geoms, &self.all_geoms)
    }

    /// robosuite's `check_q_limits`: an arm joint within 0.1 rad of a limit.
    pub fn joint_near_limit(&self, sim: &Sim) -> bool {
        let q = sim.data().qpos();
        self.arm_joints
            .iter()
            .any(|&(a, [lo, hi])| lo != hi && !(lo + 0.1 < q[a] && q[a] < hi - 0.1))
    }

    /// The markers under the tool now (robosuite's `_get_active_markers`).
    pub fn active_markers(&self, sim: &Sim) -> Vec<usize> {
        match self.active_test(sim) {
            Some(active) => (0..self.markers.len()).filter(|&i| active(i)).collect(),
            None => Vec::new(),
        }
    }

    /// Whether marker `i` is under the tool now (the tool's plane is computed once), or
    /// `None` when there are no contacts at all (then no marker is).
    fn active_test<'a>(&'a self, sim: &'a Sim) -> Option<impl Fn(usize) -> bool + 'a> {
        let d = sim.data();
        if d.contact().is_empty() {
            return None;
        }
        let c: [[f64; 3]; 4] = self.corners.map(|g| d.geom_xpos()[g]);
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let unit = |a: [f64; 3]| {
            let n = dot(a, a).sqrt();
            [a[0] / n, a[1] / n, a[2] / n]
        };
        let v1 = unit(sub(c[0], c[1]));
        let v2 = unit(sub(c[3], c[1]));
        let plane = move |p: [f64; 3]| [dot(sub(p, c[1]), v1), dot(sub(p, c[1]), v2)];
        let (t1, t2, t3, t4) = (plane(c[0]), plane(c[1]), plane(c[2]), plane(c[3]));
        let pp = [t1, t2, t4, t3];
        let n = unit([
            v1[1] * v2[2] - v1[2] * v2[1],
            v1[2] * v2[0] - v1[0] * v2[2],
            v1[0] * v2[1] - v1[1] * v2[0],
        ]);
        let is_left = |p0: [f64; 2], p1: [f64; 2], p2: [f64; 2]| {
            (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1])
        };
        let inside = move |p: [f64; 2]| {
            is_left(pp[0], pp[1], p) < 0.0
                && is_left(pp[1], pp[2], p) < 0.0
                && is_left(pp[2], pp[3], p) < 0.0
                && is_left(pp[3], pp[0], p) < 0.0
        };
        Some(move |i: usize| {
            let m = d.xpos()[self.markers[i]];
            let dist = dot(sub(m, c[1]), n);
            dist > 0.0 && dist < 0.02 && {
                let proj = [m[0] - dist * n[0], m[1] - dist * n[1], m[2] - dist * n[2]];
                inside(plane(proj))
            }
        })
    }

    /// robosuite's `_get_wipe_information` over the markers `i` with `!wiped(i)`:
    /// `(radius, centroid, centroid − eef)`.
    fn wipe_information(
        &self,
        sim: &Sim,
        robots: &[Robot],
        wiped: impl Fn(usize) -> bool,
    ) -> (f64, [f64; 3], [f64; 3]) {
        let d = sim.data();
        let remaining = || {
            self.markers
                .iter()
                .enumerate()
                .filter(|&(i, _)| !wiped(i))
                .map(|(_, &b)| d.xpos()[b])
        };
        let len = remaining().count();
        if len == 0 {
            return (0.0, [0.0; 3], [0.0; 3]);
        }
        let mut c = [0.0; 3];
        for p in remaining() {
            for k in 0..3 {
                c[k] += p[k] / len as f64;
            }
        }
        let eef = eef_pos(sim, robots);
        let radius = remaining()
            .map(|p| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)).sqrt())
            .fold(0.0, f64::max);
        (radius, c, [c[0] - eef[0], c[1] - eef[1], c[2] - eef[2]])
    }

    /// Whether marker `i` is newly wiped by this step (active and not yet wiped), or `None`
    /// when none is: the arm is colliding or at a joint limit, or nothing touches.
    fn newly_wiped_test<'a>(&'a self, sim: &'a Sim) -> Option<impl Fn(usize) -> bool + 'a> {
        if self.arm_in_contact(sim) || self.joint_near_limit(sim) {
            return None;
        }
        let active = self.active_test(sim)?;
        Some(move |i: usize| !self.wiped[i] && active(i))
    }

    fn place_marker(&mut self, sim: &mut Sim, i: usize, p: [f64; 3]) {
        let model = sim.model_mut();
        model.body_pos_mut()[self.markers[i]] = p;
        model.geom_rgba_mut()[self.marker_geoms[i]][3] = if self.wiped[i] { 0.0 } else { 1.0 };
        self.marker_pos[i] = p;
    }

    fn arena(&self) -> String {
        let [_, _, hz] = self.half();
        let markers: String = (0..self.config.num_markers)
            .map(|i| {
                format!(
                    r#"<body name="contact{i}_main" pos="0 0 {hz}"><geom name="contact{i}_g0_vis" type="cylinder" size="{} 0.001" contype="0" conaffinity="0" group="1" rgba="0 0.6 0.2 1"/></body>"#,
                    self.config.line_width / 2.0
                )
            })
            .collect::<Vec<_>>()
            .join("\n      ");
        self.table.to_xml().replacen(
            r#"<site name="table_top""#,
            &format!("{markers}\n      <site name=\"table_top\""),
            1,
        )
    }
}

impl Default for Wipe {
    fn default() -> Self {
        Self::new(WipeConfig::default()).expect("the default Wipe settings are valid")
    }
}

impl Task for Wipe {
    fn name(&self) -> &str {
        "Wipe"
    }

    fn robot_base_pose(&self, _index: usize) -> ([f64; 3], [f64; 4]) {
        (
            [-0.16 - self.config.table_full_size[0] / 2.0, 0.0, 0.912],
            [1.0, 0.0, 0.0, 0.0],
        )
    }

    fn robot_spec(&self, _index: usize, mut spec: RobotSpec) -> Result<RobotSpec> {
        spec.gripper = Some(WIPING_GRIPPER);
        Ok(spec)
    }

    fn arena_xml(&self) -> String {
        self.arena()
    }

    fn build_objects(&self, _scene: &mut SceneBuilder) -> Result<()> {
        Ok(())
    }

    fn bind(&mut self, model: &MjModel, robots: &[Robot], _source: ModelSource) -> Result<()> {
        let n = self.config.num_markers;
        self.markers = (0..n)
            .map(|i| body_id(model, &format!("contact{i}_main")))
            .collect::<Result<_>>()?;
        self.marker_geoms = (0..n)
            .map(|i| geom_id(model, &format!("contact{i}_g0_vis")))
            .collect::<Result<_>>()?;
        self.marker_pos = self.markers.iter().map(|&b| model.body_pos()[b]).collect();
        for (k, c) in self.corners.iter_mut().enumerate() {
            *c = geom_id(model, &format!("gripper0_right_wiping_corner{}", k + 1))?;
        }
        self.force_adr = sensor_adr(model, "gripper0_right_force_ee")?;
        let ngeom = model.ffi().ngeom as usize;
        let names: Vec<usize> = (0..ngeom)
            .filter(|&g| {
                let colliding = model.geom_contype()[g] != 0 || model.geom_conaffinity()[g] != 0;
                colliding
                    && model
                        .id_to_name(mujoco_rs::wrappers::mj_model::MjtObjBase::mjOBJ_GEOM, g)
                        .is_some_and(|n| n.starts_with("robot0_"))
            })
            .collect();
        self.arm_geoms = GeomSet::new(names);
        self.all_geoms = GeomSet::new(0..ngeom);
        let robot = robots
            .first()
            .ok_or_else(|| Error::Model("Wipe needs a robot".into()))?;
        self.arm_joints = (0..ARM_DOF)
            .map(|i| {
                let name = format!("robot0_{}", robot.spec().arm.joints[i]);
                let j = joint_id(model, &name)?;
                Ok((robot.arm_qpos()[i], model.jnt_range()[j]))
            })
            .collect::<Result<_>>()?;
        Ok(())
    }

    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        self.wiped.iter_mut().for_each(|w| *w = false);
        self.step_force = [0.0; 3];
        self.force_bias = [0.0; 3];
        let [hx, hy, hz] = self.half();
        let lim_x = hx * self.config.coverage_factor - self.config.line_width / 2.0;
        let lim_y = hy * self.config.coverage_factor - self.config.line_width / 2.0;
        let uniform = |rng: &mut EnvRng, lo: f64, hi: f64| lo + (hi - lo) * rng.random::<f64>();
        let mut pos = [uniform(rng, -lim_x, lim_x), uniform(rng, -lim_y, lim_y)];
        let mut direction = uniform(rng, -PI, PI);
        for i in 0..self.config.num_markers {
            self.place_marker(sim, i, [pos[0], pos[1], hz]);
            // The next point of the walk.
            if rng.random::<f64>() > 0.7 {
                direction += 0.5 * rng.sample::<f64, _>(StandardNormal);
            }
            let mut next = [
                pos[0] + 0.005 * direction.sin(),
                pos[1] + 0.005 * direction.cos(),
            ];
            let mut tries = 0;
            while next[0].abs() >= lim_x || next[1].abs() >= lim_y {
                tries += 1;
                if tries > MAX_WALK_TRIES {
                    return Err(Error::Simulation(format!(
                        "the marker walk is stuck after {MAX_WALK_TRIES} direction draws"
                    )));
                }
                direction += 0.5 * rng.sample::<f64, _>(StandardNormal);
                next = [
                    pos[0] + 0.005 * direction.sin(),
                    pos[1] + 0.005 * direction.cos(),
                ];
            }
            pos = next;
        }
        Ok(())
    }

    fn robot_observation_keys(&self, index: usize) -> Vec<ObsKey> {
        // robosuite's bool; the closest dtype here is int8.
        vec![ObsKey::new(format!("robot{index}_contact"), &[], DType::I8)]
    }

    fn write_robot_observations(
        &self,
        sim: &Sim,
        _robots: &[Robot],
        _index: usize,
        out: &mut [f64],
    ) {
        out[0] = f64::from(u8::from(self.has_gripper_contact(sim)));
    }

    fn observation_keys(&self) -> Vec<ObsKey> {
        vec![
            ObsKey::new("proportion_wiped", &[], DType::F64),
            ObsKey::new("wipe_radius", &[], DType::F64),
            ObsKey::new("wipe_centroid", &[3], DType::F64),
            ObsKey::new("gripper_to_wipe_centroid", &[3], DType::F64),
        ]
    }

    fn write_observations(&self, sim: &Sim, robots: &[Robot], out: &mut [f64]) {
        let (radius, centroid, _) = self.wipe_information(sim, robots, |i| self.wiped[i]);
        let eef = eef_pos(sim, robots);
        out[0] = self.wiped_count() as f64 / self.config.num_markers as f64;
        out[1] = radius;
        out[2..5].copy_from_slice(&centroid);
        for k in 0..3 {
            out[5 + k] = centroid[k] - eef[k];
        }
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        let c = &self.config;
        let shaping = config.reward_shaping;
        let force = self.step_force.iter().map(|v| v * v).sum::<f64>().sqrt();
        let ncon = sim.data().contact().len();
        let mut reward = 0.0;
        if self.arm_in_contact(sim) || self.joint_near_limit(sim) {
            if shaping {
                reward = c.arm_limit_collision_penalty;
            }
        } else {
            let newly = self.newly_wiped_test(sim);
            let is_new = |i: usize| newly.as_ref().is_some_and(|t| t(i));
            let wiped = |i: usize| self.wiped[i] || is_new(i);
            let new_count = (0..self.markers.len()).filter(|&i| is_new(i)).count();
            let count = (0..self.markers.len()).filter(|&i| wiped(i)).count();
            if shaping {
                reward += c.unit_wiped_reward * new_count as f64;
                if count < c.num_markers {
                    let (_, _, to) = self.wipe_information(sim, robots, wiped);
                    let d = to.iter().map(|v| v * v).sum::<f64>().sqrt();
                    reward += c.distance_multiplier * (1.0 - (c.distance_th_multiplier * d).tanh());
                }
                if ncon != 0 && self.has_gripper_contact(sim) {
                    reward += c.wipe_contact_reward;
                }
                if force > c.pressure_threshold_max {
                    reward -= c.excess_force_penalty_mul * force;
                } else if force > c.pressure_threshold && ncon > 1 {
                    reward += c.wipe_contact_reward + 0.01 * force;
                    if ncon > 50 {
                        reward += 10.0 * c.wipe_contact_reward;
                    }
                }
            }
            if count == c.num_markers {
                reward += c.task_complete_reward();
            }
        }
        match config.reward_scale {
            Some(s) if s != 0.0 => reward * s * c.normalization(config.horizon),
            _ => reward,
        }
    }

    fn check_success(&self, _sim: &Sim, _robots: &[Robot]) -> bool {
        self.wiped.iter().all(|w| *w)
    }

    fn check_terminated(&self, sim: &Sim, robots: &[Robot]) -> bool {
        self.config.early_terminations
            && (self.arm_in_contact(sim)
                || self.check_success(sim, robots)
                || self.joint_near_limit(sim))
    }

    fn on_policy_step(&mut self, sim: &Sim, _robots: &[Robot]) {
        self.step_force = self.ee_force(sim);
    }

    fn after_reward(&mut self, sim: &mut Sim, _robots: &[Robot], _config: &RewardConfig) {
        let mut new = std::mem::take(&mut self.newly_wiped);
        new.clear();
        match self.newly_wiped_test(sim) {
            Some(test) => new.extend((0..self.markers.len()).map(test)),
            None => new.resize(self.markers.len(), false),
        }
        for (i, _) in new.iter().enumerate().filter(|(_, n)| **n) {
            self.wiped[i] = true;
            sim.model_mut().geom_rgba_mut()[self.marker_geoms[i]][3] = 0.0;
        }
        self.newly_wiped = new;
        if self.force_bias.iter().all(|v| *v == 0.0) {
            self.force_bias = self.ee_force(sim);
        }
    }

    fn save_state(&self) -> Vec<f64> {
        let mut s = Vec::with_capacity(6 + 4 * self.markers.len());
        s.extend_from_slice(&self.step_force);
        s.extend_from_slice(&self.force_bias);
        for (p, w) in self.marker_pos.iter().zip(&self.wiped) {
            s.extend_from_slice(p);
            s.push(f64::from(u8::from(*w)));
        }
        s
    }

    fn load_state(&mut self, sim: &mut Sim, state: &[f64]) -> Result<()> {
        let n = self.markers.len();
        if state.len() != 6 + 4 * n {
            return Err(Error::invalid_argument(
                "state",
                format!("Wipe's state has {} values, got {}", 6 + 4 * n, state.len()),
            ));
        }
        self.step_force.copy_from_slice(&state[0..3]);
        self.force_bias.copy_from_slice(&state[3..6]);
        for i in 0..n {
            let r = &state[6 + 4 * i..10 + 4 * i];
            self.wiped[i] = r[3] != 0.0;
            self.place_marker(sim, i, [r[0], r[1], r[2]]);
        }
        Ok(())
    }
}
