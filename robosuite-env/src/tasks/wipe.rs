//! robosuite's `Wipe`: wipe a path of dirt markers off the table with a flat tool
//! (`environments/manipulation/wipe.py`).

use super::common::{TaskArm, robot0_arms, sub};
use super::options::{self, TaskOptions};
use super::{Bound, RewardConfig, Task, TaskLogic, TaskScene, TaskSpec};
use crate::assets::Assets;
use crate::models::robots::{GripperChoice, RobotModel};
use crate::models::wipe_arena::{MarkerWalk, WipeArenaConfig, marker_name, wipe_arena};
use crate::observables::{Modality, Observable};
use crate::robots::Robot;
use crate::sim::{GeomSet, Sim, any_contact_with, body_id, geom_id, sensor_adr, site_id};
use gym_core::{DType, EnvRng, Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;

/// The only gripper Wipe takes (robosuite asserts it).
const WIPING_GRIPPER: &str = "WipingGripper";

/// robosuite's `task_config` for Wipe, defaulting to its `DEFAULT_WIPE_CONFIG`.
///
/// Of `DEFAULT_WIPE_CONFIG`, `print_results` and `get_info` (console output and extra
/// `info` keys) are not offered; `ee_accel_penalty`, `table_height` and `table_height_std`
/// take only their default 0 (see [`WipeConfig::validate`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WipeConfig {
    /// Reward on an arm collision or a joint near its limit (−10; shaped rewards only).
    pub arm_limit_collision_penalty: f64,
    /// Reward for tool contact (0.01).
    pub wipe_contact_reward: f64,
    /// Reward per wiped marker (50).
    pub unit_wiped_reward: f64,
    /// Penalty on the end effector's acceleration (0; only 0 is supported).
    pub ee_accel_penalty: f64,
    /// Penalty per newton of tool force above `pressure_threshold_max` (0.05).
    pub excess_force_penalty_mul: f64,
    /// Weight of the reward for nearing the centroid of the remaining markers (5).
    pub distance_multiplier: f64,
    /// Scale of the distance inside that reward's `tanh` (5).
    pub distance_th_multiplier: f64,
    /// The table's full size (0.5 × 0.8 × 0.05).
    pub table_full_size: [f64; 3],
    /// The table top's centre (0.15, 0, 0.9).
    pub table_offset: [f64; 3],
    /// The table's friction (0.03, 0.005, 0.0001).
    pub table_friction: [f64; 3],
    /// robosuite passes it to `WipeArena`, which never uses it (0).
    pub table_friction_std: f64,
    /// Extra table height (0; only 0 is supported).
    pub table_height: f64,
    /// Spread of the extra table height (0; only 0 is supported).
    pub table_height_std: f64,
    /// The markers' diameter (0.04).
    pub line_width: f64,
    /// Two paths of half the markers each (false).
    pub two_clusters: bool,
    /// The fraction of the table the path may cover (0.6).
    pub coverage_factor: f64,
    /// The number of markers (100).
    pub num_markers: usize,
    /// Tool force (N) beyond its bias that counts as contact (1).
    pub contact_threshold: f64,
    /// Tool force (N) above which pressing is rewarded (0.5).
    pub pressure_threshold: f64,
    /// Tool force (N) above which pressing is penalised (60).
    pub pressure_threshold_max: f64,
    /// Observe `gripper_to_wipe_centroid` (or `gripper_to_marker{i}`) (true).
    pub use_robot_obs: bool,
    /// Observe `robot0_contact` (true).
    pub use_contact_obs: bool,
    /// End the episode on arm contact, a joint near its limit, or success (true).
    pub early_terminations: bool,
    /// Observe the remaining markers' centroid and radius instead of every marker (true).
    pub use_condensed_obj_obs: bool,
}

impl Default for WipeConfig {
    fn default() -> Self {
        Self {
            arm_limit_collision_penalty: -10.0,
            wipe_contact_reward: 0.01,
            unit_wiped_reward: 50.0,
            ee_accel_penalty: 0.0,
            excess_force_penalty_mul: 0.05,
            distance_multiplier: 5.0,
            distance_th_multiplier: 5.0,
            table_full_size: [0.5, 0.8, 0.05],
            table_offset: [0.15, 0.0, 0.9],
            table_friction: [0.03, 0.005, 0.0001],
            table_friction_std: 0.0,
            table_height: 0.0,
            table_height_std: 0.0,
            line_width: 0.04,
            two_clusters: false,
            coverage_factor: 0.6,
            num_markers: 100,
            contact_threshold: 1.0,
            pressure_threshold: 0.5,
            pressure_threshold_max: 60.0,
            use_robot_obs: true,
            use_contact_obs: true,
            early_terminations: true,
            use_condensed_obj_obs: true,
        }
    }
}

impl WipeConfig {
    /// robosuite's `task_complete_reward`: `unit_wiped_reward · (wipe_contact_reward + 0.5)`
    /// (25.5).
    pub fn task_complete_reward(&self) -> f64 {
        self.unit_wiped_reward * (self.wipe_contact_reward + 0.5)
    }

    /// robosuite's `reward_normalization_factor` for an episode length: `horizon /
    /// (num_markers · unit_wiped_reward + horizon · (wipe_contact_reward +
    /// task_complete_reward))` (0.032776 at 1000).
    pub fn reward_normalization_factor(&self, horizon: u64) -> f64 {
        let h = horizon as f64;
        h / (self.num_markers as f64 * self.unit_wiped_reward
            + h * (self.wipe_contact_reward + self.task_complete_reward()))
    }

    /// Checks the configuration.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for no markers, non-finite or non-positive sizes, a
    /// `distance_multiplier` not below `task_complete_reward` (robosuite asserts it), or a
    /// non-zero `ee_accel_penalty`, `table_height` or `table_height_std` (robosuite's
    /// acceleration estimate is not ported; its drawn table height is added to the table
    /// offset again at every hard reset, so the table climbs from episode to episode).
    pub fn validate(&self) -> Result<()> {
        let bad = |name: &str, why: String| Err(Error::invalid_argument(name, why));
        if self.num_markers == 0 {
            return bad("num_markers", "needs at least one marker".into());
        }
        let sizes = [self.line_width, self.coverage_factor]
            .into_iter()
            .chain(self.table_full_size);
        if sizes.clone().any(|v| !(v.is_finite() && v > 0.0)) {
            return bad(
                "task_config",
                format!(
                    "line_width, coverage_factor and table_full_size must be positive and finite, \
                     got {}, {} and {:?}",
                    self.line_width, self.coverage_factor, self.table_full_size
                ),
            );
        }
        let figures = [
            self.arm_limit_collision_penalty,
            self.wipe_contact_reward,
            self.unit_wiped_reward,
            self.excess_force_penalty_mul,
            self.distance_multiplier,
            self.distance_th_multiplier,
            self.contact_threshold,
            self.pressure_threshold,
            self.pressure_threshold_max,
            self.table_friction_std,
        ];
        if figures
            .iter()
            .chain(&self.table_offset)
            .chain(&self.table_friction)
            .any(|v| !v.is_finite())
        {
            return bad(
                "task_config",
                format!("every figure must be finite: {self:?}"),
            );
        }
        if self.task_complete_reward() <= self.distance_multiplier {
            return bad(
                "distance_multiplier",
                format!(
                    "must be below task_complete_reward ({}), got {}",
                    self.task_complete_reward(),
                    self.distance_multiplier
                ),
            );
        }
        for (name, v) in [
            ("ee_accel_penalty", self.ee_accel_penalty),
            ("table_height", self.table_height),
            ("table_height_std", self.table_height_std),
        ] {
            if v != 0.0 {
                return bad(
                    name,
                    format!("only 0 (robosuite's default) is supported, got {v}"),
                );
            }
        }
        Ok(())
    }

    fn arena(&self) -> WipeArenaConfig {
        WipeArenaConfig {
            table_full_size: self.table_full_size,
            table_friction: self.table_friction,
            table_offset: self.table_offset,
            coverage_factor: self.coverage_factor,
            num_markers: self.num_markers,
            line_width: self.line_width,
            two_clusters: self.two_clusters,
        }
    }
}

/// Wipe's settings: robosuite's `task_config`.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct WipeSpec {
    /// The task configuration (default `DEFAULT_WIPE_CONFIG`).
    pub task_config: WipeConfig,
}

impl WipeSpec {
    /// robosuite's constructor arguments (see [`TaskSpec::options`]): `task_config`.
    fn task_options(&self) -> TaskOptions {
        options::to_options(self)
    }

    /// Sets robosuite's constructor arguments (see [`TaskSpec::configure`]): the keys of a
    /// `task_config` dict replace the current ones (robosuite's `DEFAULT_WIPE_CONFIG` as a
    /// whole is accepted, its `print_results` and `get_info` only as `False`: console
    /// printing and the extra `info` keys are not offered); `None` restores the defaults.
    fn set_task_options(&mut self, given: &TaskOptions) -> Result<()> {
        let mut rest = given.clone();
        match rest.get_mut("task_config") {
            Some(serde_json::Value::Null) => {
                rest.insert(
                    "task_config".into(),
                    options::to_options(&WipeConfig::default()).into(),
                );
            }
            Some(serde_json::Value::Object(config)) => {
                for key in ["print_results", "get_info"] {
                    match config.remove(key) {
                        None | Some(serde_json::Value::Bool(false)) => {}
                        Some(other) => {
                            return Err(Error::Unsupported(
                                format!(
                                    "Wipe's task_config[{key:?}] = {other}: only false is \
                                     supported (no console printing or extra info keys)"
                                )
                                .into(),
                            ));
                        }
                    }
                }
                let mut merged = options::to_options(&self.task_config);
                merged.extend(std::mem::take(config));
                *config = merged;
            }
            _ => {}
        }
        *self = options::merged(self.name(), self, &rest)?;
        Ok(())
    }
}

impl TaskSpec for WipeSpec {
    fn options(&self) -> TaskOptions {
        self.task_options()
    }

    fn configure(&mut self, options: &TaskOptions) -> Result<()> {
        self.set_task_options(options)
    }

    fn name(&self) -> &str {
        "Wipe"
    }

    /// robosuite's Wipe asserts `gripper_types == "WipingGripper"` (its default).
    fn gripper(
        &self,
        _robot: usize,
        _arm: usize,
        configured: &GripperChoice,
    ) -> Result<GripperChoice> {
        match configured {
            GripperChoice::Default => Ok(GripperChoice::Named(WIPING_GRIPPER.to_owned())),
            GripperChoice::Named(name) if name == WIPING_GRIPPER => Ok(configured.clone()),
            other => Err(Error::invalid_argument(
                "gripper_types",
                format!(
                    "Wipe takes only robosuite's {WIPING_GRIPPER} (robosuite asserts it), got {other:?}"
                ),
            )),
        }
    }

    fn default_reward_shaping(&self) -> bool {
        true
    }

    fn build(&self, assets: &Assets, _robots: &mut [RobotModel]) -> Result<TaskScene> {
        self.task_config.validate()?;
        let mut arena = wipe_arena(assets, &self.task_config.arena())?;
        arena.set_origin([0.0; 3])?;
        Ok(TaskScene {
            arena,
            objects: Vec::new(),
            attached: Vec::new(),
        })
    }

    fn bind(&self, _scene: &TaskScene, model: &MjModel, robots: &[Robot]) -> Result<Box<dyn Task>> {
        let config = self.task_config.clone();
        let robot = robots
            .first()
            .ok_or_else(|| Error::model("Wipe needs a robot"))?;
        let tools = robot
            .arms()
            .iter()
            .map(|arm| {
                let corners: [usize; 4] = arm.gripper().corners().try_into().map_err(|_| {
                    Error::model(format!(
                        "Wipe needs the wiping tool's four corner geoms, the gripper has {}",
                        arm.gripper().corners().len()
                    ))
                })?;
                Ok(WipeTool {
                    corners,
                    force_adr: sensor_adr(
                        model,
                        &format!("gripper{}_{}_force_ee", robot.index(), arm.side()),
                        3,
                    )?,
                    eef_site: arm.eef_site(),
                    latest_force: [0.0; 3],
                    step_force: [0.0; 3],
                    force_bias: [0.0; 3],
                })
            })
            .collect::<Result<Vec<_>>>()?;
        if tools.len() > MAX_TOOLS {
            return Err(Error::model(format!(
                "Wipe takes a robot of at most {MAX_TOOLS} arms, {} has {}",
                robot.name(),
                tools.len()
            )));
        }
        let n = config.num_markers;
        let mut markers = Vec::with_capacity(n);
        for i in 0..n {
            let name = marker_name(i);
            markers.push(Marker {
                body: body_id(model, &format!("{name}_main"))?,
                geom: geom_id(model, &format!("{name}_g0_vis"))?,
                site: site_id(model, &format!("{name}_default_site"))?,
            });
        }
        let ranges = model.jnt_range();
        let arm_joints = robot
            .joint_qpos()
            .iter()
            .map(|&adr| {
                (0..ranges.len())
                    .find(|&j| model.jnt_qposadr()[j] as usize == adr)
                    .map(|j| (adr, ranges[j]))
                    .ok_or_else(|| Error::model(format!("no joint has qpos address {adr}")))
            })
            .collect::<Result<Vec<_>>>()?;
        let pf = format!("robot{}_", robot.index());
        let task = Wipe {
            walk: MarkerWalk {
                table_half: [
                    config.table_full_size[0] / 2.0,
                    config.table_full_size[1] / 2.0,
                ],
                coverage_factor: config.coverage_factor,
                line_width: config.line_width,
                two_clusters: config.two_clusters,
            },
            marker_z: config.table_full_size[2] / 2.0,
            positions: markers.iter().map(|m| model.body_pos()[m.body]).collect(),
            path: vec![[0.0; 2]; n],
            newly_wiped: Vec::with_capacity(n),
            wiped: vec![false; n],
            wiped_count: 0,
            markers,
            tools,
            arm_geoms: robot.contact_geoms().clone(),
            arm_joints,
            observed: WipeInfo::default(),
            config,
        };
        let observables = task.make_observables(&pf, robot.index(), &robot0_arms(robots));
        Ok(Bound::boxed(task, observables))
    }
}

/// The most arms (wiping tools) a robot has.
const MAX_TOOLS: usize = 2;

/// One arm's wiping tool: its corners, its force sensor and robosuite's force records.
#[derive(Debug, Clone, Copy, PartialEq)]
struct WipeTool {
    corners: [usize; 4],
    force_adr: usize,
    eef_site: usize,
    /// The force sensor as of the last observation pass: what the next step's first
    /// substep reads (only the last substep's `mj_step2` changes it).
    latest_force: [f64; 3],
    /// robosuite's `recent_ee_forcetorques[arm].current[:3]`: the force at this step's
    /// first substep.
    step_force: [f64; 3],
    /// robosuite's `ee_force_bias[arm]`.
    force_bias: [f64; 3],
}

impl WipeTool {
    /// The force sensor (`{gripper}force_ee`) now.
    fn force_now(&self, sim: &Sim) -> [f64; 3] {
        let s = &sim.data().sensordata()[self.force_adr..self.force_adr + 3];
        [s[0], s[1], s[2]]
    }

    /// robosuite's `_get_active_markers` set-up: the plane of the tool's four corners now.
    fn plane(&self, sim: &Sim) -> ToolPlane {
        let d = sim.data();
        let c = self.corners.map(|g| d.geom_xpos()[g]);
        let v1 = unit(sub(c[0], c[1]));
        let v2 = unit(sub(c[3], c[1]));
        let mut plane = ToolPlane {
            origin: c[1],
            v1,
            v2,
            n: unit(cross(v1, v2)),
            corners: [[0.0; 2]; 4],
        };
        plane.corners = [
            plane.project(c[0]),
            plane.project(c[1]),
            plane.project(c[3]),
            plane.project(c[2]),
        ];
        plane
    }
}

/// The plane of a wiping tool's corners (robosuite's `_get_active_markers`).
#[derive(Debug, Clone, Copy, PartialEq)]
struct ToolPlane {
    origin: [f64; 3],
    v1: [f64; 3],
    v2: [f64; 3],
    n: [f64; 3],
    /// The corners in the plane's coordinates, in robosuite's order `[t1, t2, t4, t3]`.
    corners: [[f64; 2]; 4],
}

impl ToolPlane {
    fn project(&self, p: [f64; 3]) -> [f64; 2] {
        let v = sub(p, self.origin);
        [dot(v, self.v1), dot(v, self.v2)]
    }

    /// Whether a marker centred at `m` lies less than 2 cm above the plane, inside the
    /// corners' rectangle.
    fn covers(&self, m: [f64; 3]) -> bool {
        let n = self.n;
        let dist = dot(sub(m, self.origin), n);
        if !(dist > 0.0 && dist < 0.02) {
            return false;
        }
        let p = self.project([m[0] - dist * n[0], m[1] - dist * n[1], m[2] - dist * n[2]]);
        let is_left = |p0: [f64; 2], p1: [f64; 2], p2: [f64; 2]| {
            (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1])
        };
        let pp = self.corners;
        is_left(pp[0], pp[1], p) < 0.0
            && is_left(pp[1], pp[2], p) < 0.0
            && is_left(pp[2], pp[3], p) < 0.0
            && is_left(pp[3], pp[0], p) < 0.0
    }
}

/// One marker's ids.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Marker {
    body: usize,
    geom: usize,
    site: usize,
}

/// robosuite's `_get_wipe_information`: the radius around and the centroid of the markers
/// not wiped, and the centroid relative to the nearest grip site (zeros when every marker
/// is wiped).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct WipeInfo {
    radius: f64,
    centroid: [f64; 3],
    to_centroid: [f64; 3],
}

/// The bound Wipe task: robosuite's `WipeArena` table (0.5 × 0.8 × 0.05, top at
/// (0.15, 0, 0.9), friction (0.03, 0.005, 0.0001)) carrying `num_markers` visual markers
/// `contact{i}_main`, and a robot with the wiping tool on each arm (action: each arm's 6
/// OSC inputs).
///
/// * Reset: the markers are laid out by robosuite's random walk ([`MarkerWalk`]) through
///   the model (`body_pos`, part of [`Task::save_state`]); every marker is visible again
///   and none is wiped; the force bias is cleared.
/// * Wiping (in the reward, as robosuite): unless an arm link touches anything or an arm
///   joint is within 0.1 rad of a limit, each marker whose centre lies less than 2 cm above
///   the plane of a tool's four corner geoms and inside their rectangle, while there is
///   any contact, is wiped (made transparent).
/// * Reward: robosuite's (shaped by default, see [`WipeConfig`]), times `reward_scale ·
///   reward_normalization_factor`. The tool force of the step is the force sensor's value
///   at the step's first substep (robosuite's `recent_ee_forcetorques`; the largest over
///   the arms); tool contact is the current force beyond the bias (any arm's), which is
///   the force after the first step.
/// * Observations are sampled before the step's reward wipes markers, so
///   `proportion_wiped`, `wipe_radius` and `wipe_centroid` lag the wiping by one step, as in
///   robosuite. `robot0_contact` is a bool, as robosuite's.
/// * Success: every marker wiped. Early termination (`terminated`): an arm link touching
///   anything, a joint near its limit, or success.
#[derive(Debug, Clone)]
pub struct Wipe {
    config: WipeConfig,
    walk: MarkerWalk,
    marker_z: f64,
    markers: Vec<Marker>,
    /// The markers' `body_pos` (table frame) as laid out.
    positions: Vec<[f64; 3]>,
    /// Scratch for the walk.
    path: Vec<[f64; 2]>,
    /// Scratch for [`Task::after_reward`]: the markers the step wiped.
    newly_wiped: Vec<bool>,
    wiped: Vec<bool>,
    wiped_count: usize,
    /// The wiping tools, one per arm of the robot (robosuite's `robots[0].arms`).
    tools: Vec<WipeTool>,
    arm_geoms: GeomSet,
    /// `(qpos address, range)` of each arm joint.
    arm_joints: Vec<(usize, [f64; 2])>,
    /// The wipe information of the last observation pass.
    observed: WipeInfo,
}

impl Wipe {
    /// robosuite's observables, in its order: `{robot}contact` (proprio modality, with
    /// `use_contact_obs`), then `proportion_wiped`, `wipe_radius`, `wipe_centroid` and
    /// `{arm}gripper_to_wipe_centroid` per arm (with `use_robot_obs`) — or, without
    /// `use_condensed_obj_obs`, per marker `marker{i}_pos`, `marker{i}_wiped` (int64) and
    /// `{arm}gripper_to_marker{i}` per arm (`arm` empty for a single-arm robot, `right_` /
    /// `left_` for a bimanual one). All exist only with `use_object_obs`, as in robosuite.
    fn make_observables(&self, pf: &str, robot: usize, arms: &[TaskArm]) -> Vec<Observable<Wipe>> {
        let mut obs = Vec::new();
        if self.config.use_contact_obs {
            obs.push(
                Observable::new(
                    format!("{pf}contact"),
                    &[],
                    DType::Bool,
                    Modality::Proprio(robot),
                    |t: &Wipe, sim, out| out[0] = f64::from(u8::from(t.has_gripper_contact(sim))),
                )
                .only_with_object_obs(),
            );
        }
        if self.config.use_condensed_obj_obs {
            obs.push(Observable::new(
                "proportion_wiped",
                &[],
                DType::F64,
                Modality::Object,
                |t: &Wipe, _, out| {
                    out[0] = t.wiped_count as f64 / t.config.num_markers as f64;
                },
            ));
            obs.push(Observable::new(
                "wipe_radius",
                &[],
                DType::F64,
                Modality::Object,
                |t: &Wipe, _, out| {
                    out[0] = t.observed.radius;
                },
            ));
            obs.push(Observable::vec(
                "wipe_centroid",
                Modality::Object,
                |t: &Wipe, _| t.observed.centroid,
            ));
            if self.config.use_robot_obs {
                for arm in arms {
                    let site = arm.eef_site;
                    obs.push(Observable::f64(
                        format!("{}gripper_to_wipe_centroid", arm.prefix),
                        3,
                        Modality::Object,
                        move |t: &Wipe, sim, out| {
                            let eef = sim.data().site_xpos()[site];
                            for k in 0..3 {
                                out[k] = t.observed.centroid[k] - eef[k];
                            }
                        },
                    ));
                }
            }
        } else {
            for i in 0..self.markers.len() {
                obs.push(Observable::vec(
                    format!("marker{i}_pos"),
                    Modality::Object,
                    move |t: &Wipe, sim| sim.data().xpos()[t.markers[i].body],
                ));
                obs.push(Observable::new(
                    format!("marker{i}_wiped"),
                    &[],
                    DType::I64,
                    Modality::Object,
                    move |t: &Wipe, _, out| {
                        out[0] = f64::from(u8::from(t.wiped[i]));
                    },
                ));
                if self.config.use_robot_obs {
                    for arm in arms {
                        let site = arm.eef_site;
                        obs.push(Observable::f64(
                            format!("{}gripper_to_marker{i}", arm.prefix),
                            3,
                            Modality::Object,
                            move |t: &Wipe, sim, out| {
                                let d = sim.data();
                                let (m, eef) = (d.xpos()[t.markers[i].body], d.site_xpos()[site]);
                                for k in 0..3 {
                                    out[k] = m[k] - eef[k];
                                }
                            },
                        ));
                    }
                }
            }
        }
        obs
    }

    /// The task configuration.
    pub fn config(&self) -> &WipeConfig {
        &self.config
    }

    /// The number of wiped markers.
    pub fn wiped_count(&self) -> usize {
        self.wiped_count
    }

    /// Which markers are wiped, in marker order.
    pub fn wiped(&self) -> &[bool] {
        &self.wiped
    }

    /// The markers' positions in the table's frame (`body_pos`), as laid out at the last
    /// reset.
    pub fn marker_positions(&self) -> &[[f64; 3]] {
        &self.positions
    }

    /// robosuite's `_has_gripper_contact`: some arm's force sensor differs from its bias by
    /// more than `contact_threshold`.
    pub fn has_gripper_contact(&self, sim: &Sim) -> bool {
        self.tools
            .iter()
            .any(|t| norm(sub(t.force_now(sim), t.force_bias)) > self.config.contact_threshold)
    }

    /// robosuite's `check_contact(robot_model)`: some arm link geom is in a contact.
    pub fn arm_in_contact(&self, sim: &Sim) -> bool {
        any_contact_with(sim.data(), &self.arm_geoms)
    }

    /// robosuite's `check_q_limits`: an arm joint (of a limited range) within 0.1 rad of a
    /// limit.
    pub fn joint_near_limit(&self, sim: &Sim) -> bool {
        let q = sim.data().qpos();
        self.arm_joints
            .iter()
            .any(|&(a, [lo, hi])| lo != hi && !(lo + 0.1 < q[a] && q[a] < hi - 0.1))
    }

    /// Whether the step is unsafe (no wiping, the penalty): arm contact or a joint limit.
    fn unsafe_state(&self, sim: &Sim) -> bool {
        self.arm_in_contact(sim) || self.joint_near_limit(sim)
    }

    /// robosuite's `_get_active_markers` over the arms: a test of whether marker `i` is
    /// under a tool now (the tools' planes computed once), or `None` when there is no
    /// contact at all (then none is).
    fn active_test<'a>(&'a self, sim: &'a Sim) -> Option<impl Fn(usize) -> bool + 'a> {
        let d = sim.data();
        if d.contact().is_empty() {
            return None;
        }
        let mut planes = [None; MAX_TOOLS];
        for (plane, tool) in planes.iter_mut().zip(&self.tools) {
            *plane = Some(tool.plane(sim));
        }
        Some(move |i: usize| {
            let m = d.xpos()[self.markers[i].body];
            planes.iter().flatten().any(|p| p.covers(m))
        })
    }

    /// robosuite's `_get_wipe_information` over the markers for which `wiped` is false.
    fn wipe_information(&self, sim: &Sim, wiped: impl Fn(usize) -> bool) -> WipeInfo {
        let xpos = sim.data().xpos();
        let remaining = || {
            (0..self.markers.len())
                .filter(|&i| !wiped(i))
                .map(|i| xpos[self.markers[i].body])
        };
        let mut info = WipeInfo::default();
        let mut count = 0usize;
        for p in remaining() {
            for (c, v) in info.centroid.iter_mut().zip(p) {
                *c += v;
            }
            count += 1;
        }
        if count == 0 {
            return info;
        }
        for c in &mut info.centroid {
            *c /= count as f64;
        }
        // The centroid relative to the nearest grip site (the first of equals).
        let sites = sim.data().site_xpos();
        let mut nearest = f64::INFINITY;
        for tool in &self.tools {
            let to = sub(info.centroid, sites[tool.eef_site]);
            if norm(to) < nearest {
                nearest = norm(to);
                info.to_centroid = to;
            }
        }
        info.radius = remaining()
            .map(|p| norm(sub(p, info.centroid)))
            .fold(f64::NEG_INFINITY, f64::max);
        info
    }

    /// Writes marker `i`'s layout into the model: its position, its geom visible unless
    /// wiped, its site hidden (robosuite's `reset_arena`).
    fn show_marker(&mut self, sim: &mut Sim, i: usize) {
        let m = self.markers[i];
        let model = sim.model_mut();
        model.body_pos_mut()[m.body] = self.positions[i];
        model.geom_rgba_mut()[m.geom][3] = if self.wiped[i] { 0.0 } else { 1.0 };
        model.site_rgba_mut()[m.site][3] = 0.0;
    }

    fn state_len(&self) -> usize {
        4 * self.markers.len() + 9 * self.tools.len()
    }
}

impl TaskLogic for Wipe {
    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        self.walk.lay(rng, &mut self.path)?;
        self.wiped.fill(false);
        self.wiped_count = 0;
        for i in 0..self.markers.len() {
            let [x, y] = self.path[i];
            self.positions[i] = [x, y, self.marker_z];
            self.show_marker(sim, i);
        }
        for tool in &mut self.tools {
            tool.step_force = [0.0; 3];
            tool.force_bias = [0.0; 3];
        }
        Ok(())
    }

    fn before_observe(&mut self, sim: &Sim) {
        for tool in &mut self.tools {
            tool.latest_force = tool.force_now(sim);
        }
        self.observed = self.wipe_information(sim, |i| self.wiped[i]);
    }

    fn on_policy_step(&mut self, _sim: &Sim, _robots: &[Robot]) {
        for tool in &mut self.tools {
            tool.step_force = tool.latest_force;
        }
    }

    fn reward(&self, sim: &Sim, _robots: &[Robot], config: &RewardConfig) -> f64 {
        let c = &self.config;
        let shaping = config.reward_shaping;
        let total_force_ee = self
            .tools
            .iter()
            .map(|t| norm(t.step_force))
            .fold(f64::NEG_INFINITY, f64::max);
        let ncon = sim.data().contact().len();
        let mut reward = 0.0;
        if self.unsafe_state(sim) {
            if shaping {
                reward = c.arm_limit_collision_penalty;
            }
        } else {
            let active = self.active_test(sim);
            let is_new = |i: usize| !self.wiped[i] && active.as_ref().is_some_and(|t| t(i));
            let mut wiped = self.wiped_count;
            for _ in (0..self.markers.len()).filter(|&i| is_new(i)) {
                wiped += 1;
                if shaping {
                    reward += c.unit_wiped_reward;
                }
            }
            if shaping {
                if wiped < c.num_markers {
                    let info = self.wipe_information(sim, |i| self.wiped[i] || is_new(i));
                    reward += c.distance_multiplier
                        * (1.0 - (c.distance_th_multiplier * norm(info.to_centroid)).tanh());
                }
                if ncon != 0 && self.has_gripper_contact(sim) {
                    reward += c.wipe_contact_reward;
                }
                if total_force_ee > c.pressure_threshold_max {
                    reward -= c.excess_force_penalty_mul * total_force_ee;
                } else if total_force_ee > c.pressure_threshold && ncon > 1 {
                    reward += c.wipe_contact_reward + 0.01 * total_force_ee;
                    if ncon > 50 {
                        reward += 10.0 * c.wipe_contact_reward;
                    }
                }
            }
            if wiped == c.num_markers {
                reward += c.task_complete_reward();
            }
        }
        match config.reward_scale {
            Some(scale) if scale != 0.0 => {
                reward * (scale * c.reward_normalization_factor(config.horizon))
            }
            _ => reward,
        }
    }

    /// robosuite's reward updates the wiped markers (made transparent) and, after the
    /// reward, `_post_action` takes the force bias at the first step.
    fn after_reward(&mut self, sim: &mut Sim, _robots: &[Robot], _config: &RewardConfig) {
        if !self.unsafe_state(sim) {
            let mut new = std::mem::take(&mut self.newly_wiped);
            new.clear();
            if let Some(active) = self.active_test(sim) {
                new.extend((0..self.markers.len()).map(|i| !self.wiped[i] && active(i)));
            }
            for (i, _) in new.iter().enumerate().filter(|(_, n)| **n) {
                self.wiped[i] = true;
                self.wiped_count += 1;
                sim.model_mut().geom_rgba_mut()[self.markers[i].geom][3] = 0.0;
            }
            self.newly_wiped = new;
        }
        if self.tools.iter().all(|t| norm(t.force_bias) == 0.0) {
            for tool in &mut self.tools {
                tool.force_bias = tool.force_now(sim);
            }
        }
    }

    fn check_success(&self, _sim: &Sim, _robots: &[Robot]) -> bool {
        self.wiped_count == self.config.num_markers
    }

    fn check_terminated(&self, sim: &Sim, robots: &[Robot]) -> bool {
        self.config.early_terminations
            && (self.arm_in_contact(sim)
                || self.check_success(sim, robots)
                || self.joint_near_limit(sim))
    }

    /// The markers' positions (`body_pos`, 3 per marker), their wiped flags (0 or 1), the
    /// force biases, the step's forces and the forces of the last observation pass (3 per
    /// arm each, arms in robosuite's order).
    fn save_state(&self) -> Vec<f64> {
        let mut s = Vec::with_capacity(self.state_len());
        s.extend(self.positions.iter().flatten());
        s.extend(self.wiped.iter().map(|w| f64::from(u8::from(*w))));
        s.extend(self.tools.iter().flat_map(|t| t.force_bias));
        s.extend(self.tools.iter().flat_map(|t| t.step_force));
        s.extend(self.tools.iter().flat_map(|t| t.latest_force));
        s
    }

    fn load_state(&mut self, sim: &mut Sim, state: &[f64]) -> Result<()> {
        let n = self.markers.len();
        let bad = |why: String| Err(Error::invalid_argument("task state", why));
        if state.len() != self.state_len() {
            return bad(format!(
                "Wipe's state is {n} marker positions (3 each), {n} wiped flags and three forces \
                 per arm ({} arm(s), 3 each): {} values, got {}",
                self.tools.len(),
                self.state_len(),
                state.len()
            ));
        }
        if let Some(i) = state.iter().position(|v| !v.is_finite()) {
            return bad(format!("value {i} is not finite ({})", state[i]));
        }
        let flags = &state[3 * n..4 * n];
        if let Some(i) = flags.iter().position(|v| *v != 0.0 && *v != 1.0) {
            return bad(format!("wiped flag {i} must be 0 or 1, got {}", flags[i]));
        }
        for (i, p) in state[..3 * n].chunks_exact(3).enumerate() {
            self.positions[i] = [p[0], p[1], p[2]];
        }
        for (w, f) in self.wiped.iter_mut().zip(flags) {
            *w = *f == 1.0;
        }
        self.wiped_count = self.wiped.iter().filter(|w| **w).count();
        let arms = self.tools.len();
        let force = |k: usize, arm: usize| {
            let at = 4 * n + 3 * (k * arms + arm);
            [state[at], state[at + 1], state[at + 2]]
        };
        for (arm, tool) in self.tools.iter_mut().enumerate() {
            tool.force_bias = force(0, arm);
            tool.step_force = force(1, arm);
            tool.latest_force = force(2, arm);
        }
        for i in 0..n {
            self.show_marker(sim, i);
        }
        Ok(())
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = norm(a);
    [a[0] / n, a[1] / n, a[2] / n]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
