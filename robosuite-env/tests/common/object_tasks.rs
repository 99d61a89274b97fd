//! Helpers for the tasks with free objects and single-object modes (PickPlace,
//! NutAssembly): robosuite's observation layout, hand-set object poses, a scripted
//! pick-and-place and the MuJoCo arena check.

use super::{assert_observation_layout, dist3, get, move_to};
use gym_core::{DType, DictValue, Env, Space};
use ndarray::ArrayD;
use robosuite_env::RobosuiteEnv;
use robosuite_env::sim::{body_id, joint_id};

/// robosuite 1.5.2's Panda observables, in order (`robosuite-1.5.2-observations.json`).
pub const ROBOT_OBS: [(&str, usize, DType); 10] = [
    ("robot0_joint_pos", 7, DType::F64),
    ("robot0_joint_pos_cos", 7, DType::F64),
    ("robot0_joint_pos_sin", 7, DType::F64),
    ("robot0_joint_vel", 7, DType::F64),
    ("robot0_joint_acc", 7, DType::F64),
    ("robot0_eef_pos", 3, DType::F64),
    ("robot0_eef_quat", 4, DType::F64),
    ("robot0_eef_quat_site", 4, DType::F32),
    ("robot0_gripper_qpos", 2, DType::F64),
    ("robot0_gripper_qvel", 2, DType::F64),
];

/// robosuite's observation keys, shapes and dtypes for a task whose observed objects are
/// `objects` (four float64 keys each), followed by the object id `id_key` (an int64
/// scalar) in single-object mode 1, then the two concatenations.
pub fn expected_obs(objects: &[&str], id_key: Option<&str>) -> Vec<(String, Vec<usize>, DType)> {
    let mut out: Vec<(String, Vec<usize>, DType)> = ROBOT_OBS
        .iter()
        .map(|(k, n, d)| ((*k).to_owned(), vec![*n], *d))
        .collect();
    for name in objects {
        for (suffix, n) in [
            ("_to_robot0_eef_pos", 3),
            ("_to_robot0_eef_quat", 4),
            ("_pos", 3),
            ("_quat", 4),
        ] {
            out.push((format!("{name}{suffix}"), vec![n], DType::F64));
        }
    }
    if let Some(id) = id_key {
        out.push((id.to_owned(), vec![], DType::I64));
    }
    let object_len = 14 * objects.len() + usize::from(id_key.is_some());
    out.push(("robot0_proprio-state".to_owned(), vec![50], DType::F64));
    out.push(("object-state".to_owned(), vec![object_len], DType::F64));
    out
}

/// Checks the observation space and a reset's observation against
/// [`expected_obs`]: keys in order, shapes, dtypes, and the concatenations.
pub fn assert_obs_layout(env: &mut RobosuiteEnv, objects: &[&str], id_key: Option<&str>) {
    let expected = expected_obs(objects, id_key);
    let (obs, _) = env.reset(Some(0), None).unwrap();
    assert_observation_layout(env, &obs, &expected);
    let concat = |range: std::ops::Range<usize>| -> Vec<f64> {
        expected[range]
            .iter()
            .flat_map(|(k, _, _)| get(&obs, k))
            .collect()
    };
    assert_eq!(get(&obs, "robot0_proprio-state"), concat(0..10));
    assert_eq!(get(&obs, "object-state"), concat(10..expected.len() - 2));
}

/// Checks each variant's model sizes `(nq, nv, nu, nbody, ngeom)` and observation layout
/// (its observed objects), and the mode-1 variant `single`, whose object keys are named
/// after `prefix` and followed by `{prefix}_id`.
pub fn assert_variant_layouts(
    variants: &[(&str, &[&str])],
    sizes: [i64; 5],
    single: &str,
    prefix: &str,
) {
    let make = |name: &str| {
        robosuite_env::make_with(name, robosuite_env::EnvConfig::default())
            .unwrap_or_else(|e| panic!("{name} builds: {e}"))
    };
    for (name, objects) in variants {
        let mut env = make(name);
        let m = env.sim().model().ffi();
        assert_eq!([m.nq, m.nv, m.nu, m.nbody, m.ngeom], sizes, "{name}");
        assert_obs_layout(&mut env, objects, None);
    }
    assert_obs_layout(&mut make(single), &[prefix], Some(&format!("{prefix}_id")));
}

/// A few actions for snapshot checks.
pub fn probe_actions() -> Vec<ArrayD<f64>> {
    [0.3, -0.2, 0.1, 0.4]
        .iter()
        .map(|v| super::action([*v, 0.1, -0.2, 0.0, 0.1, 0.0, -v]))
        .collect()
}

/// The world position of body `name`.
pub fn body_pos(env: &RobosuiteEnv, name: &str) -> [f64; 3] {
    env.sim().data().xpos()[body_id(env.sim().model(), name).unwrap()]
}

/// Puts the free joint `joint` at `pos` with orientation `quat` (wxyz), at rest, and takes
/// a fresh observation.
pub fn set_free_joint(env: &mut RobosuiteEnv, joint: &str, pos: [f64; 3], quat: [f64; 4]) {
    let m = env.sim().model();
    let j = joint_id(m, joint).unwrap();
    let (qadr, dadr) = (m.jnt_qposadr()[j] as usize, m.jnt_dofadr()[j] as usize);
    let nq = m.ffi().nq as usize;
    let mut s = env.get_state();
    s[1 + qadr..1 + qadr + 3].copy_from_slice(&pos);
    s[1 + qadr + 3..1 + qadr + 7].copy_from_slice(&quat);
    s[1 + nq + dadr..1 + nq + dadr + 6].fill(0.0);
    env.set_state(&s).unwrap();
}

/// The MuJoCo arena and stack bytes used at most so far, and the bytes reserved.
pub fn arena_use(env: &RobosuiteEnv) -> (usize, usize) {
    let f = env.sim().data().ffi();
    (
        f.maxuse_arena as usize + f.maxuse_stack as usize,
        env.sim().arena_bytes(),
    )
}

/// A scripted pick-and-place, as the recorded robosuite rollouts: above the grasp point,
/// descend (turning the fingers by the yaw error `grab` returns), close, lift to `carry_z`,
/// carry the object over `goal`, lower it until its origin is at `release_z`, open, rise.
pub struct PlacePolicy<G> {
    /// The grasp point and the fingers' yaw error, from the observation.
    pub grab: G,
    /// The object position key.
    pub object_key: &'static str,
    /// Where the object goes (x, y).
    pub goal: [f64; 2],
    /// The carrying height of the grip site.
    pub carry_z: f64,
    /// The object's height at release.
    pub release_z: f64,
}

impl<G: Fn(&DictValue) -> ([f64; 3], f64)> PlacePolicy<G> {
    /// Runs the policy from a reset with `seed` for at most `steps` steps; returns the step
    /// at which `info["success"]` first held, if it did.
    pub fn run(&self, env: &mut RobosuiteEnv, seed: u64, steps: usize) -> Option<usize> {
        let (mut obs, _) = env.reset(Some(seed), None).unwrap();
        let (mut phase, mut n) = (0, 0);
        for t in 0..steps {
            let eef = get(&obs, "robot0_eef_pos");
            let o = get(&obs, self.object_key);
            let (point, yaw_err) = (self.grab)(&obs);
            let over_goal = |z: f64| {
                [
                    self.goal[0] + eef[0] - o[0],
                    self.goal[1] + eef[1] - o[1],
                    z,
                ]
            };
            let here = [eef[0], eef[1], eef[2]];
            let (target, grip, align) = match phase {
                0 => ([point[0], point[1], point[2] + 0.08], -1.0, true),
                1 => (point, -1.0, true),
                2 => (here, 1.0, false),
                3 => ([eef[0], eef[1], self.carry_z], 1.0, false),
                4 => (over_goal(self.carry_z), 1.0, false),
                5 => (over_goal(eef[2] - o[2] + self.release_z), 1.0, false),
                6 => (here, -1.0, false),
                _ => ([eef[0], eef[1], self.carry_z], -1.0, false),
            };
            let yaw = if align { yaw_err } else { 0.0 };
            let step = env.step(&move_to(&eef, target, 10.0, yaw, grip)).unwrap();
            if step.info.get_bool("success") == Some(true) {
                return Some(t + 1);
            }
            if step.done() {
                return None;
            }
            obs = step.observation;
            n += 1;
            let d = dist3(target, &eef);
            let next = match phase {
                0 => (d < 0.01 && yaw.abs() < 0.05) || n > 60,
                1 => d < 0.005 || n > 40,
                2 | 6 => n >= 12,
                3 => d < 0.02 || n > 40,
                4 => d < 0.005 || n > 80,
                5 => d < 0.01 || n > 50,
                _ => false,
            };
            if next {
                phase += 1;
                n = 0;
            }
        }
        None
    }
}

/// Asserts that drawn angles spread over more than one radian (random yaw).
pub fn assert_spread(angles: &[f64]) {
    let hi = angles.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let lo = angles.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(hi - lo > 1.0, "the angles are drawn: {angles:?}");
}

/// Asserts that each of `bad` is refused as a task state by `reset_to_state` (with the
/// valid simulator state `state`) and leaves the task state as it was.
pub fn assert_task_states_rejected(env: &mut RobosuiteEnv, bad: &[Vec<f64>], state: &[f64]) {
    for task_state in bad {
        let before = env.task().save_state();
        assert!(
            matches!(
                env.reset_to_state(task_state, state),
                Err(gym_core::Error::InvalidArgument { .. })
            ),
            "{task_state:?}"
        );
        assert_eq!(
            env.task().save_state(),
            before,
            "{task_state:?} changed the task"
        );
    }
}

/// Runs `episodes` episodes of uniformly random actions to their end.
pub fn random_episodes(env: &mut RobosuiteEnv, episodes: u64) {
    let mut rng = gym_core::rng_from_seed(8);
    for seed in 0..episodes {
        env.reset(Some(seed), None).unwrap();
        loop {
            let a = env.action_space().sample(&mut rng);
            if env.step(&a).unwrap().done() {
                break;
            }
        }
    }
}
