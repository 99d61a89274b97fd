#![allow(dead_code)]

//! Small deterministic environments for the adapters' tests (no MuJoCo).
//!
//! * [`ScriptEnv`]: replays scripted observations, rewards and flags and records the
//!   actions and seeds it receives.
//! * [`CountEnv`]: observation `[t]`, reward `t`, terminates at a given step; the env of
//!   Gymnasium's vector autoreset traces.
//! * [`WalkEnv`]: a seeded random walk with Box observations and actions and a horizon.
//! * [`DictEnv`]: a robosuite-like env with an ordered Dict observation, a Box action,
//!   seeded resets, `info["success"]`, and the horizon reported as truncated.
//! * [`DiscreteEnv`]: Discrete observations and actions.

use gym_core::spaces::{AnySpace, BoxSpace, DictSpace, Discrete};
use gym_core::{
    DictValue, DynSpace, Env, EnvRng, Error, Flatten, Info, ResetOptions, Result, Space, Step,
    Value, rng_from_seed,
};
use ndarray::{ArrayD, IxDyn, arr1};
use rand::RngExt;

/// A 1-D `f64` array.
pub fn a64(v: &[f64]) -> ArrayD<f64> {
    arr1(v).into_dyn()
}

/// A 1-D `f32` array.
pub fn a32(v: &[f32]) -> ArrayD<f32> {
    arr1(v).into_dyn()
}

/// Replays a script: `reset` returns `observations[0]`; step `k` (1-based since the reset)
/// returns `observations[k % len]`, `rewards[(k-1) % len]`, and the flags at `k-1`.
#[derive(Debug, Clone)]
pub struct ScriptEnv<S: Space, A: Space> {
    pub observation_space: S,
    pub action_space: A,
    pub observations: Vec<S::Element>,
    pub rewards: Vec<f64>,
    pub terminated: Vec<bool>,
    pub truncated: Vec<bool>,
    /// Extra info returned by every step.
    pub step_info: Info,
    pub t: usize,
    pub actions: Vec<A::Element>,
    pub seeds: Vec<Option<u64>>,
    pub closed: usize,
}

impl<S: Space, A: Space> ScriptEnv<S, A> {
    pub fn new(
        observation_space: S,
        action_space: A,
        observations: Vec<S::Element>,
        rewards: Vec<f64>,
    ) -> Self {
        let n = rewards.len().max(1);
        Self {
            observation_space,
            action_space,
            observations,
            rewards,
            terminated: vec![false; n],
            truncated: vec![false; n],
            step_info: Info::new(),
            t: 0,
            actions: Vec::new(),
            seeds: Vec::new(),
            closed: 0,
        }
    }

    pub fn with_terminated(mut self, terminated: Vec<bool>) -> Self {
        self.terminated = terminated;
        self
    }

    pub fn with_truncated(mut self, truncated: Vec<bool>) -> Self {
        self.truncated = truncated;
        self
    }

    pub fn with_step_info(mut self, info: Info) -> Self {
        self.step_info = info;
        self
    }
}

fn at<T: Clone>(v: &[T], i: usize, default: T) -> T {
    if v.is_empty() {
        default
    } else {
        v[i % v.len()].clone()
    }
}

impl<S: Flatten + DynSpace, A: Flatten + DynSpace> Env for ScriptEnv<S, A>
where
    S::Element: Send,
    A::Element: Send,
{
    type Obs = S::Element;
    type Act = A::Element;
    type ObsSpace = S;
    type ActSpace = A;

    fn observation_space(&self) -> &S {
        &self.observation_space
    }
    fn action_space(&self) -> &A {
        &self.action_space
    }
    fn reset(
        &mut self,
        seed: Option<u64>,
        _options: Option<&ResetOptions>,
    ) -> Result<(S::Element, Info)> {
        self.t = 0;
        self.seeds.push(seed);
        Ok((
            self.observations[0].clone(),
            Info::new().with("reset", true),
        ))
    }
    fn step(&mut self, action: &A::Element) -> Result<Step<S::Element>> {
        self.actions.push(action.clone());
        self.t += 1;
        let k = self.t - 1;
        let mut info = self.step_info.clone();
        info.insert("t", self.t);
        Ok(Step {
            observation: at(&self.observations, self.t, self.observations[0].clone()),
            reward: at(&self.rewards, k, 0.0),
            terminated: at(&self.terminated, k, false),
            truncated: at(&self.truncated, k, false),
            info,
        })
    }
    fn close(&mut self) {
        self.closed += 1;
    }
}

/// A Box `(2,)` f32 action space in `[-1, 1]`.
pub fn unit_actions() -> BoxSpace<f32> {
    BoxSpace::uniform(-1.0, 1.0, &[2]).expect("valid")
}

/// A [`ScriptEnv`] with unbounded `f32` Box observations of shape `(n,)`.
pub fn script_f32(
    observations: &[&[f32]],
    rewards: &[f64],
) -> ScriptEnv<BoxSpace<f32>, BoxSpace<f32>> {
    let n = observations[0].len();
    ScriptEnv::new(
        BoxSpace::unbounded(&[n]),
        unit_actions(),
        observations.iter().map(|o| a32(o)).collect(),
        rewards.to_vec(),
    )
}

/// Observation `[t]` (`f64`), reward `t`, info `{"step": t}`; terminates at step
/// `terminate_at` (if any) and truncates at `truncate_at` (if any). Reset info is
/// `{"reset": true}`. Action: Discrete(2), ignored.
#[derive(Debug, Clone)]
pub struct CountEnv {
    pub terminate_at: Option<u64>,
    pub truncate_at: Option<u64>,
    pub t: u64,
    pub observation_space: BoxSpace<f64>,
    pub action_space: Discrete,
    pub resets: usize,
}

impl CountEnv {
    pub fn new(terminate_at: Option<u64>, truncate_at: Option<u64>) -> Self {
        Self {
            terminate_at,
            truncate_at,
            t: 0,
            observation_space: BoxSpace::uniform(0.0, 1000.0, &[1]).expect("valid"),
            action_space: Discrete::new(2).expect("valid"),
            resets: 0,
        }
    }
}

impl Env for CountEnv {
    type Obs = ArrayD<f64>;
    type Act = i64;
    type ObsSpace = BoxSpace<f64>;
    type ActSpace = Discrete;

    fn observation_space(&self) -> &BoxSpace<f64> {
        &self.observation_space
    }
    fn action_space(&self) -> &Discrete {
        &self.action_space
    }
    fn reset(
        &mut self,
        _seed: Option<u64>,
        _options: Option<&ResetOptions>,
    ) -> Result<(ArrayD<f64>, Info)> {
        self.t = 0;
        self.resets += 1;
        Ok((a64(&[0.0]), Info::new().with("reset", true)))
    }
    fn step(&mut self, action: &i64) -> Result<Step<ArrayD<f64>>> {
        if !self.action_space.contains(action) {
            return Err(Error::invalid_action(format!(
                "{action} not in Discrete(2)"
            )));
        }
        self.t += 1;
        Ok(Step {
            observation: a64(&[self.t as f64]),
            reward: self.t as f64,
            terminated: self.terminate_at == Some(self.t),
            truncated: self.truncate_at == Some(self.t),
            info: Info::new().with("step", self.t),
        })
    }
}

/// A seeded random walk: observation `pos` (f32, `(2,)`), action in `[-1, 1]^2`,
/// `pos += 0.1 * action + N(0, 0.01)`, reward `-|pos|`, terminated when `|pos| > 2`,
/// truncated after `horizon` steps. Info: `success` (|pos| < 0.1) and `dist`.
#[derive(Debug, Clone)]
pub struct WalkEnv {
    pub horizon: u64,
    pub t: u64,
    pub pos: [f64; 2],
    pub rng: Option<EnvRng>,
    pub observation_space: BoxSpace<f32>,
    pub action_space: BoxSpace<f32>,
    /// Panics on step number `panic_at` (to test worker-thread failures).
    pub panic_at: Option<u64>,
    /// CPU busy-work per step, in loop iterations (to measure threading).
    pub work_iters: u64,
}

impl WalkEnv {
    pub fn new(horizon: u64) -> Self {
        Self {
            horizon,
            t: 0,
            pos: [0.0; 2],
            rng: None,
            observation_space: BoxSpace::unbounded(&[2]),
            action_space: unit_actions(),
            panic_at: None,
            work_iters: 0,
        }
    }

    fn obs(&self) -> ArrayD<f32> {
        a32(&[self.pos[0] as f32, self.pos[1] as f32])
    }

    fn dist(&self) -> f64 {
        (self.pos[0] * self.pos[0] + self.pos[1] * self.pos[1]).sqrt()
    }
}

impl Env for WalkEnv {
    type Obs = ArrayD<f32>;
    type Act = ArrayD<f32>;
    type ObsSpace = BoxSpace<f32>;
    type ActSpace = BoxSpace<f32>;

    fn observation_space(&self) -> &BoxSpace<f32> {
        &self.observation_space
    }
    fn action_space(&self) -> &BoxSpace<f32> {
        &self.action_space
    }
    fn reset(
        &mut self,
        seed: Option<u64>,
        _options: Option<&ResetOptions>,
    ) -> Result<(ArrayD<f32>, Info)> {
        if let Some(s) = seed {
            self.rng = Some(rng_from_seed(s));
        }
        let rng = self
            .rng
            .get_or_insert_with(|| rng_from_seed(gym_core::entropy_seed()));
        self.pos = [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
        self.t = 0;
        Ok((self.obs(), Info::new()))
    }
    fn step(&mut self, action: &ArrayD<f32>) -> Result<Step<ArrayD<f32>>> {
        if !self.action_space.contains(action) {
            return Err(Error::invalid_action(format!(
                "{action} is outside [-1, 1]^2"
            )));
        }
        self.t += 1;
        if self.panic_at == Some(self.t) {
            panic!("WalkEnv asked to panic at step {}", self.t);
        }
        let mut acc = 0u64;
        for i in 0..self.work_iters {
            acc = std::hint::black_box(acc.wrapping_mul(6364136223846793005).wrapping_add(i));
        }
        std::hint::black_box(acc);
        let rng = self.rng.as_mut().ok_or(Error::ResetNeeded)?;
        for (p, a) in self.pos.iter_mut().zip(action.iter()) {
            *p += 0.1 * f64::from(*a) + 0.01 * rng.sample::<f64, _>(rand_distr::StandardNormal);
        }
        let dist = self.dist();
        Ok(Step {
            observation: self.obs(),
            reward: -dist,
            terminated: dist > 2.0,
            truncated: self.t >= self.horizon,
            info: Info::new().with("success", dist < 0.1).with("dist", dist),
        })
    }
    fn rng(&self) -> Option<&EnvRng> {
        self.rng.as_ref()
    }
}

/// A robosuite-like env. Observation keys, in order: `robot0_joint_pos` (f64, 2),
/// `object-state` (f64, 3), [`frontview_image` (u8, 2x2x1) when `camera`],
/// `robot0_proprio-state` (f64, 4), `robot0_eef_quat_site` (f32, 2). Action: Box f64 `(3,)`
/// with bounds `[-1, -0.1, -1]..[1, 0.1, 1]`; out-of-bounds actions are rejected. The
/// horizon is reported as truncated; `info["success"]` is `object-state[0] > 1`.
#[derive(Debug, Clone)]
pub struct DictEnv {
    pub observation_space: DictSpace,
    pub action_space: BoxSpace<f64>,
    pub horizon: u64,
    pub t: u64,
    pub state: [f64; 3],
    pub rng: Option<EnvRng>,
    pub camera: bool,
    /// Return the observation dict with its keys in reverse order (tests the fallback).
    pub shuffle_keys: bool,
}

impl DictEnv {
    pub fn new(horizon: u64, camera: bool) -> Self {
        let f64box = |n: usize| AnySpace::from(BoxSpace::<f64>::unbounded(&[n]));
        let mut parts = vec![("robot0_joint_pos", f64box(2)), ("object-state", f64box(3))];
        if camera {
            parts.push((
                "frontview_image",
                AnySpace::from(BoxSpace::<u8>::uniform(0.0, 255.0, &[2, 2, 1]).expect("valid")),
            ));
        }
        parts.push(("robot0_proprio-state", f64box(4)));
        parts.push((
            "robot0_eef_quat_site",
            AnySpace::from(BoxSpace::<f32>::unbounded(&[2])),
        ));
        let low = a64(&[-1.0, -0.1, -1.0]);
        let high = a64(&[1.0, 0.1, 1.0]);
        Self {
            observation_space: DictSpace::new(parts).expect("unique keys"),
            action_space: BoxSpace::new(low, high).expect("valid"),
            horizon,
            t: 0,
            state: [0.0; 3],
            rng: None,
            camera,
            shuffle_keys: false,
        }
    }

    pub fn observation(&self) -> DictValue {
        let s = self.state;
        let t = self.t as f64;
        let mut d = DictValue::new();
        d.insert("robot0_joint_pos".into(), Value::from(a64(&[s[0], t])));
        d.insert(
            "object-state".into(),
            Value::from(a64(&[s[0] + s[1], s[1], s[2]])),
        );
        if self.camera {
            let img =
                ArrayD::from_shape_vec(IxDyn(&[2, 2, 1]), vec![0u8, 64, 128, (self.t % 256) as u8])
                    .expect("shape");
            d.insert("frontview_image".into(), Value::from(img));
        }
        d.insert(
            "robot0_proprio-state".into(),
            Value::from(a64(&[s[0], s[1], s[2], t])),
        );
        d.insert(
            "robot0_eef_quat_site".into(),
            Value::from(a32(&[0.5, -0.25])),
        );
        if self.shuffle_keys {
            d.reverse();
        }
        d
    }
}

impl Env for DictEnv {
    type Obs = DictValue;
    type Act = ArrayD<f64>;
    type ObsSpace = DictSpace;
    type ActSpace = BoxSpace<f64>;

    fn observation_space(&self) -> &DictSpace {
        &self.observation_space
    }
    fn action_space(&self) -> &BoxSpace<f64> {
        &self.action_space
    }
    fn reset(
        &mut self,
        seed: Option<u64>,
        _options: Option<&ResetOptions>,
    ) -> Result<(DictValue, Info)> {
        if let Some(s) = seed {
            self.rng = Some(rng_from_seed(s));
        }
        let rng = self
            .rng
            .get_or_insert_with(|| rng_from_seed(gym_core::entropy_seed()));
        self.state = [
            rng.random_range(-0.5..0.5),
            rng.random_range(-0.5..0.5),
            rng.random_range(-0.5..0.5),
        ];
        self.t = 0;
        Ok((self.observation(), Info::new()))
    }
    fn step(&mut self, action: &ArrayD<f64>) -> Result<Step<DictValue>> {
        if !self.action_space.contains(action) {
            return Err(Error::invalid_action(format!(
                "{action} is outside the action space"
            )));
        }
        if self.t >= self.horizon {
            return Err(Error::EpisodeEnded);
        }
        self.t += 1;
        for (s, a) in self.state.iter_mut().zip(action.iter()) {
            *s += a;
        }
        let success = self.state[0] + self.state[1] > 1.0;
        Ok(Step {
            observation: self.observation(),
            reward: if success { 1.0 } else { 0.0 },
            terminated: false,
            truncated: self.t >= self.horizon,
            info: Info::new().with("success", success),
        })
    }
    fn rng(&self) -> Option<&EnvRng> {
        self.rng.as_ref()
    }
}

/// Discrete(5) observation (a position starting at 2), Discrete(2) action (0 left, 1
/// right); terminated at either end with reward 1 at the right end.
#[derive(Debug, Clone)]
pub struct DiscreteEnv {
    pub pos: i64,
    pub observation_space: Discrete,
    pub action_space: Discrete,
}

impl DiscreteEnv {
    pub fn new() -> Self {
        Self {
            pos: 2,
            observation_space: Discrete::new(5).expect("valid"),
            action_space: Discrete::new(2).expect("valid"),
        }
    }
}

impl Default for DiscreteEnv {
    fn default() -> Self {
        Self::new()
    }
}

impl Env for DiscreteEnv {
    type Obs = i64;
    type Act = i64;
    type ObsSpace = Discrete;
    type ActSpace = Discrete;

    fn observation_space(&self) -> &Discrete {
        &self.observation_space
    }
    fn action_space(&self) -> &Discrete {
        &self.action_space
    }
    fn reset(
        &mut self,
        _seed: Option<u64>,
        _options: Option<&ResetOptions>,
    ) -> Result<(i64, Info)> {
        self.pos = 2;
        Ok((self.pos, Info::new()))
    }
    fn step(&mut self, action: &i64) -> Result<Step<i64>> {
        if !self.action_space.contains(action) {
            return Err(Error::invalid_action(format!(
                "{action} not in Discrete(2)"
            )));
        }
        self.pos += if *action == 1 { 1 } else { -1 };
        let end = self.pos == 0 || self.pos == 4;
        Ok(Step {
            observation: self.pos,
            reward: if self.pos == 4 { 1.0 } else { 0.0 },
            terminated: end,
            truncated: false,
            info: Info::new(),
        })
    }
}
