//! robosuite's `GymWrapper`, corrected: [`GymWrapper`] (robosuite's signature, dynamic
//! observations) and [`FlatGymWrapper`] (typed flat `f32` observations).
//!
//! Both select observation keys of a Dict-observation environment (robosuite's
//! `RobosuiteEnv`, any env whose observation space is a [`DictSpace`], or a boxed env from
//! the registry whose [`AnySpace`] is a Dict; see [`DictObservationSpace`]), and expose the
//! environment's action bounds as an `f32` Box. Compared with robosuite 1.5.2's wrapper:
//!
//! * flat observations are `float32`, matching their `Box(-inf, inf, (n,), float32)` space
//!   (robosuite returns `float64` inside a `float32` space, which fails `check_env`);
//! * `reset(seed)` forwards the seed to the environment, so the same seed gives the same
//!   initial observation (robosuite seeds NumPy's global RNG, which it never reads);
//! * `terminated` and `truncated` are forwarded untouched (the environment reports its
//!   horizon as `truncated`; robosuite's wrapper reports it as `terminated`), and so is
//!   `info` (with `success`);
//! * the observation space comes from the environment's Dict space: no extra reset at
//!   construction;
//! * an unknown key is an [`Error::UnknownKey`] at construction listing the available keys.
//!
//! Typing: `flatten_obs` changes the observation type, so [`GymWrapper`] (the constructor
//! robosuite users know, `GymWrapper::new(env, keys, flatten_obs)`) yields dynamic
//! [`Value`] observations in an [`AnySpace`] (a `float32` Box when flat, a Dict of the
//! selected keys otherwise), and [`FlatGymWrapper`] yields typed `ArrayD<f32>` observations
//! in a [`BoxSpace<f32>`], for code that wants the flat vector without matching on a
//! `Value`. Both precompute each key's position in the observation dict (a lookup by name is
//! only the fallback when an observation's keys are not in the space's order); `step`
//! allocates one array per flat observation and [`FlatGymWrapper`]'s `step_into` none.

use crate::numeric::NumericSpace;
use gym_core::spaces::{AnySpace, BoxSpace, DictSpace};
use gym_core::{
    DictValue, DynSpace, Env, Error, Info, ResetOptions, Result, Scalar, Space, SpaceError, Step,
    Transition, Value,
};
use ndarray::{ArrayD, IxDyn};

/// An observation space whose elements are ordered dicts: [`DictSpace`], or an
/// [`AnySpace`] holding one (the observation space of a boxed, registry-made env).
pub trait DictObservationSpace: DynSpace {
    /// The Dict space, if this is one.
    fn dict_space(&self) -> Option<&DictSpace>;

    /// The element as a dict (moved, not copied).
    ///
    /// # Errors
    /// When a dynamic element is not a dict.
    fn into_dict(x: Self::Element) -> Result<DictValue>;

    /// The element as a borrowed dict.
    ///
    /// # Errors
    /// When a dynamic element is not a dict.
    fn as_dict(x: &Self::Element) -> Result<&DictValue>;
}

impl DictObservationSpace for DictSpace {
    fn dict_space(&self) -> Option<&DictSpace> {
        Some(self)
    }

    fn into_dict(x: DictValue) -> Result<DictValue> {
        Ok(x)
    }

    fn as_dict(x: &DictValue) -> Result<&DictValue> {
        Ok(x)
    }
}

impl DictObservationSpace for AnySpace {
    fn dict_space(&self) -> Option<&DictSpace> {
        self.as_dict()
    }

    fn into_dict(x: Value) -> Result<DictValue> {
        match x {
            Value::Dict(d) => Ok(d),
            other => Err(not_a_dict(&other)),
        }
    }

    fn as_dict(x: &Value) -> Result<&DictValue> {
        match x {
            Value::Dict(d) => Ok(d),
            other => Err(not_a_dict(other)),
        }
    }
}

fn not_a_dict(x: &Value) -> Error {
    SpaceError::WrongKind {
        expected: "dict",
        got: x.kind(),
    }
    .into()
}

fn dict_space_of<S: DictObservationSpace>(space: &S) -> Result<&DictSpace> {
    space.dict_space().ok_or_else(|| {
        Error::invalid_argument(
            "env",
            format!(
                "GymWrapper needs a Dict observation space, got {}",
                space.to_any()
            ),
        )
    })
}

/// robosuite 1.5's default keys for an observation space: `object-state` (when present),
/// the camera images (keys ending in `_image`, in space order), then
/// `robot{i}_proprio-state` for `i = 0, 1, ...` while present.
pub fn default_keys(space: &DictSpace) -> Vec<String> {
    let mut keys = Vec::new();
    if space.get("object-state").is_some() {
        keys.push("object-state".to_owned());
    }
    keys.extend(
        space
            .keys()
            .filter(|k| k.ends_with("_image"))
            .map(str::to_owned),
    );
    for i in 0.. {
        let k = format!("robot{i}_proprio-state");
        if space.get(&k).is_none() {
            break;
        }
        keys.push(k);
    }
    keys
}

/// The selected keys with their positions and flat sizes, computed once.
#[derive(Debug, Clone, PartialEq)]
struct KeyPlan {
    keys: Vec<String>,
    positions: Vec<usize>,
    sizes: Vec<usize>,
    total: usize,
}

impl KeyPlan {
    fn new(space: &DictSpace, keys: Option<Vec<String>>, flat: bool) -> Result<Self> {
        let available = || space.keys().map(str::to_owned).collect::<Vec<_>>();
        let keys = match keys {
            Some(k) => k,
            None => default_keys(space),
        };
        if keys.is_empty() {
            return Err(Error::invalid_argument(
                "keys",
                format!(
                    "no observation keys selected (available: {})",
                    available().join(", ")
                ),
            ));
        }
        let mut positions = Vec::with_capacity(keys.len());
        let mut sizes = Vec::with_capacity(keys.len());
        for (i, k) in keys.iter().enumerate() {
            let pos = space
                .keys()
                .position(|s| s == k)
                .ok_or_else(|| Error::UnknownKey {
                    key: k.clone(),
                    available: available(),
                })?;
            if keys[..i].contains(k) {
                return Err(Error::invalid_argument(
                    "keys",
                    format!("duplicate key `{k}`"),
                ));
            }
            let sub = space.get(k).expect("found above");
            if flat && matches!(sub, AnySpace::Dict(_) | AnySpace::Tuple(_)) {
                return Err(Error::invalid_argument(
                    "keys",
                    format!(
                        "`{k}` is a {} space; only array observations can be flattened",
                        sub.kind()
                    ),
                ));
            }
            positions.push(pos);
            sizes.push(sub.shape().map_or(1, |s| s.iter().product()));
        }
        let total = sizes.iter().sum();
        Ok(Self {
            keys,
            positions,
            sizes,
            total,
        })
    }

    /// The value of selected key `j`: by position when the dict is in the space's order,
    /// else by name.
    fn value<'a>(&self, obs: &'a DictValue, j: usize) -> Result<&'a Value> {
        let key = &self.keys[j];
        if let Some((k, v)) = obs.get_index(self.positions[j])
            && k == key
        {
            return Ok(v);
        }
        obs.get(key).ok_or_else(|| Error::UnknownKey {
            key: key.clone(),
            available: obs.keys().cloned().collect(),
        })
    }

    /// The selected keys concatenated (each flattened, row-major) as `f32`.
    fn flatten(&self, obs: &DictValue) -> Result<ArrayD<f32>> {
        let mut out = ArrayD::zeros(IxDyn(&[self.total]));
        self.flatten_into(obs, &mut out)?;
        Ok(out)
    }

    /// Flattens into `out`, reusing its storage when it is a standard-layout vector of the
    /// flat length.
    fn flatten_into(&self, obs: &DictValue, out: &mut ArrayD<f32>) -> Result<()> {
        if out.shape() != [self.total] || !out.is_standard_layout() {
            *out = ArrayD::zeros(IxDyn(&[self.total]));
        }
        let flat = out.as_slice_mut().expect("a standard-layout vector");
        let mut at = 0;
        for j in 0..self.keys.len() {
            let n = match self.value(obs, j)? {
                Value::Array(a) => {
                    let n = a.len();
                    if n == self.sizes[j] {
                        let dst = &mut flat[at..at + n];
                        gym_core::for_each_array!(a, arr => dst
                            .iter_mut()
                            .zip(arr.iter())
                            .for_each(|(d, v)| *d = v.to_f64() as f32));
                    }
                    n
                }
                Value::Discrete(d) => {
                    if self.sizes[j] == 1 {
                        flat[at] = *d as f32;
                    }
                    1
                }
                other => {
                    return Err(SpaceError::WrongKind {
                        expected: "array",
                        got: other.kind(),
                    }
                    .into());
                }
            };
            if n != self.sizes[j] {
                return Err(Error::Contract {
                    check: "GymWrapper".into(),
                    message: format!(
                        "observation `{}` has {n} elements, its space {}",
                        self.keys[j], self.sizes[j]
                    )
                    .into(),
                });
            }
            at += n;
        }
        Ok(())
    }

    /// The selected entries of `obs` copied into `out`, in key order: in place when `out`
    /// already holds such a dict (the previous step's), else as a new dict.
    fn select_into(&self, obs: &DictValue, out: &mut Value) -> Result<()> {
        let same_keys = matches!(out, Value::Dict(d) if d.keys().eq(self.keys.iter()));
        if !same_keys {
            let mut dict = DictValue::with_capacity(self.keys.len());
            for j in 0..self.keys.len() {
                dict.insert(self.keys[j].clone(), self.value(obs, j)?.clone());
            }
            *out = Value::Dict(dict);
            return Ok(());
        }
        if let Value::Dict(dict) = out {
            for (j, dst) in dict.values_mut().enumerate() {
                assign_value(dst, self.value(obs, j)?);
            }
        }
        Ok(())
    }

    /// The selected entries moved out of `obs`, in key order.
    fn select(&self, mut obs: DictValue) -> Result<DictValue> {
        let mut out = DictValue::with_capacity(self.keys.len());
        for (j, key) in self.keys.iter().enumerate() {
            let in_place = obs
                .get_index(self.positions[j])
                .is_some_and(|(k, _)| k == key);
            let v = if in_place {
                std::mem::replace(&mut obs[self.positions[j]], Value::Discrete(0))
            } else {
                obs.swap_remove(key.as_str())
                    .ok_or_else(|| Error::UnknownKey {
                        key: key.clone(),
                        available: obs.keys().cloned().collect(),
                    })?
            };
            out.insert(key.clone(), v);
        }
        Ok(out)
    }
}

/// The environment's action bounds as an `f32` Box. Bounds that `f32` cannot represent are
/// rounded inwards, so every `f32` action in the Box converts to an action in the inner Box.
fn f32_action_space<S: NumericSpace>(inner: &S) -> Result<BoxSpace<f32>> {
    if !inner.is_box() {
        return Err(Error::invalid_argument(
            "env",
            format!("GymWrapper needs a Box action space, got {inner:?}"),
        ));
    }
    let spec = inner.array_spec()?;
    let inward = |v: f64, up: bool| {
        let r = v as f32;
        if !v.is_finite() || f64::from(r) == v {
            f64::from(r)
        } else if up == (f64::from(r) < v) {
            f64::from(if up { r.next_up() } else { r.next_down() })
        } else {
            f64::from(r)
        }
    };
    Ok(BoxSpace::new(
        spec.low.mapv(|v| inward(v, true)),
        spec.high.mapv(|v| inward(v, false)),
    )?)
}

fn convert_action<S: NumericSpace>(inner: &S, action: &ArrayD<f32>) -> Result<S::Element> {
    inner
        .element_from_array(action)
        .map_err(Error::into_invalid_action)
}

/// The inner environment's last action and observation, kept between `step_into` calls so
/// that a loop of them converts the action and receives the observation in place.
#[derive(Debug, Clone)]
struct InnerBuffers<E: Env> {
    action: Option<E::Act>,
    obs: Option<E::Obs>,
}

impl<E> InnerBuffers<E>
where
    E: Env,
    E::ActSpace: NumericSpace,
{
    fn new() -> Self {
        Self {
            action: None,
            obs: None,
        }
    }

    /// Converts `action` into the kept inner action, steps `env` into the kept inner
    /// observation (allocating only on the first call) and returns the transition with that
    /// observation.
    fn step_into(
        &mut self,
        env: &mut E,
        action: &ArrayD<f32>,
        info: &mut Info,
    ) -> Result<(Transition, &E::Obs)> {
        let space = env.action_space();
        let inner_action = match &mut self.action {
            Some(a) => {
                space
                    .element_from_array_into(action, a)
                    .map_err(Error::into_invalid_action)?;
                a
            }
            None => self.action.insert(convert_action(space, action)?),
        };
        let transition = match &mut self.obs {
            Some(obs) => env.step_into(inner_action, obs, info)?,
            None => {
                let step = env.step(inner_action)?;
                *info = step.info;
                self.obs = Some(step.observation);
                Transition {
                    reward: step.reward,
                    terminated: step.terminated,
                    truncated: step.truncated,
                }
            }
        };
        let obs = self
            .obs
            .as_ref()
            .ok_or_else(|| Error::simulation("the inner observation was not kept"))?;
        Ok((transition, obs))
    }
}

/// Copies `src` into `dst`, reusing `dst`'s arrays where the two have the same structure,
/// dtypes and shapes (a kept observation buffer), else replacing `dst` by a copy.
fn assign_value(dst: &mut Value, src: &Value) {
    use gym_core::ArrayValue as A;
    match (dst, src) {
        (Value::Array(d), Value::Array(s)) => match (d, s) {
            (A::F32(d), A::F32(s)) => d.clone_from(s),
            (A::F64(d), A::F64(s)) => d.clone_from(s),
            (A::I8(d), A::I8(s)) => d.clone_from(s),
            (A::I16(d), A::I16(s)) => d.clone_from(s),
            (A::I32(d), A::I32(s)) => d.clone_from(s),
            (A::I64(d), A::I64(s)) => d.clone_from(s),
            (A::U8(d), A::U8(s)) => d.clone_from(s),
            (A::Bool(d), A::Bool(s)) => d.clone_from(s),
            (d, s) => *d = s.clone(),
        },
        (Value::Dict(d), Value::Dict(s)) if d.keys().eq(s.keys()) => {
            for (dv, sv) in d.values_mut().zip(s.values()) {
                assign_value(dv, sv);
            }
        }
        (Value::Tuple(d), Value::Tuple(s)) if d.len() == s.len() => {
            for (dv, sv) in d.iter_mut().zip(s) {
                assign_value(dv, sv);
            }
        }
        (d, s) => *d = s.clone(),
    }
}

/// robosuite's `GymWrapper(env, keys=None, flatten_obs=True)`, corrected (see the
/// [module documentation](self)). Observations are dynamic [`Value`]s: with `flatten_obs`
/// a `float32` array in `Box(-inf, inf, (n,), float32)`, else a Dict of the selected keys
/// (in the order given) whose subspaces are the environment's, dtypes included.
///
/// [`Env::step_into`] keeps the inner environment's action and observation between steps
/// and writes into the caller's observation in place (the flat array, or each array of the
/// Dict), so a loop of `step_into` allocates nothing after its first step.
#[derive(Debug, Clone)]
pub struct GymWrapper<E: Env> {
    env: E,
    plan: KeyPlan,
    flatten_obs: bool,
    observation_space: AnySpace,
    action_space: BoxSpace<f32>,
    buffers: InnerBuffers<E>,
}

impl<E> GymWrapper<E>
where
    E: Env,
    E::ObsSpace: DictObservationSpace,
    E::ActSpace: NumericSpace,
{
    /// Wraps `env`, selecting `keys` (robosuite's defaults when `None`, see
    /// [`default_keys`]) and flattening them when `flatten_obs`.
    ///
    /// # Errors
    /// [`Error::UnknownKey`] for a key the observation space lacks (listing the available
    /// keys); [`Error::InvalidArgument`] for no keys, a duplicate key, a nested Dict/Tuple
    /// key when flattening, a non-Dict observation space or a non-Box action space.
    pub fn new(env: E, keys: Option<Vec<String>>, flatten_obs: bool) -> Result<Self> {
        let dict = dict_space_of(env.observation_space())?;
        let plan = KeyPlan::new(dict, keys, flatten_obs)?;
        let observation_space = if flatten_obs {
            AnySpace::from(BoxSpace::<f32>::unbounded(&[plan.total]))
        } else {
            AnySpace::Dict(dict.select(&plan.keys)?)
        };
        let action_space = f32_action_space(env.action_space())?;
        Ok(Self {
            env,
            plan,
            flatten_obs,
            observation_space,
            action_space,
            buffers: InnerBuffers::new(),
        })
    }

    /// The selected keys, in observation order.
    pub fn keys(&self) -> &[String] {
        &self.plan.keys
    }

    /// Whether observations are flattened.
    pub fn flatten_obs(&self) -> bool {
        self.flatten_obs
    }

    fn observation(&self, obs: E::Obs) -> Result<Value> {
        let obs = E::ObsSpace::into_dict(obs)?;
        if self.flatten_obs {
            Ok(Value::from(self.plan.flatten(&obs)?))
        } else {
            Ok(Value::Dict(self.plan.select(obs)?))
        }
    }
}

impl<E> gym_core::CustomWrapper for GymWrapper<E>
where
    E: Env,
    E::ObsSpace: DictObservationSpace,
    E::ActSpace: NumericSpace,
{
    type Observation = Value;
    type Action = ArrayD<f32>;
    type ObservationSpace = AnySpace;
    type ActionSpace = BoxSpace<f32>;

    fn observation_space(this: &Self) -> &AnySpace {
        &this.observation_space
    }

    fn action_space(this: &Self) -> &BoxSpace<f32> {
        &this.action_space
    }

    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Value, Info)> {
        let (obs, info) = this.env.reset(seed, options)?;
        Ok((this.observation(obs)?, info))
    }

    fn step(this: &mut Self, action: &ArrayD<f32>) -> Result<Step<Value>> {
        let action = convert_action(this.env.action_space(), action)?;
        let step = this.env.step(&action)?;
        step.try_map_observation(|o| this.observation(o))
    }

    fn step_into(
        this: &mut Self,
        action: &ArrayD<f32>,
        observation: &mut Value,
        info: &mut Info,
    ) -> Result<Transition> {
        let (transition, inner_obs) = this.buffers.step_into(&mut this.env, action, info)?;
        let dict = E::ObsSpace::as_dict(inner_obs)?;
        if !this.flatten_obs {
            this.plan.select_into(dict, observation)?;
        } else if let Value::Array(gym_core::ArrayValue::F32(out)) = observation
            && out.shape() == [this.plan.total]
        {
            this.plan.flatten_into(dict, out)?;
        } else {
            *observation = Value::from(this.plan.flatten(dict)?);
        }
        Ok(transition)
    }
}

impl<E> gym_core::Wrapper for GymWrapper<E>
where
    E: Env,
    E::ObsSpace: DictObservationSpace,
    E::ActSpace: NumericSpace,
{
    type Inner = E;
    type Kind = gym_core::Custom;
    fn inner(&self) -> &E {
        &self.env
    }
    fn inner_mut(&mut self) -> &mut E {
        &mut self.env
    }
    fn into_inner(self) -> E {
        self.env
    }
}

/// [`GymWrapper`] with `flatten_obs = true` and typed observations: `ArrayD<f32>` in
/// `Box(-inf, inf, (n,), float32)`.
///
/// [`Env::step_into`] reuses the caller's buffers and keeps the inner environment's
/// observation and action between steps, so a loop of `step_into` over a robosuite env does
/// not allocate.
#[derive(Debug, Clone)]
pub struct FlatGymWrapper<E: Env> {
    env: E,
    plan: KeyPlan,
    observation_space: BoxSpace<f32>,
    action_space: BoxSpace<f32>,
    buffers: InnerBuffers<E>,
}

impl<E> FlatGymWrapper<E>
where
    E: Env,
    E::ObsSpace: DictObservationSpace,
    E::ActSpace: NumericSpace,
{
    /// Wraps `env`, selecting and flattening `keys` (robosuite's defaults when `None`).
    ///
    /// # Errors
    /// As [`GymWrapper::new`].
    pub fn new(env: E, keys: Option<Vec<String>>) -> Result<Self> {
        let plan = KeyPlan::new(dict_space_of(env.observation_space())?, keys, true)?;
        let observation_space = BoxSpace::unbounded(&[plan.total]);
        let action_space = f32_action_space(env.action_space())?;
        Ok(Self {
            env,
            plan,
            observation_space,
            action_space,
            buffers: InnerBuffers::new(),
        })
    }

    /// The selected keys, in concatenation order.
    pub fn keys(&self) -> &[String] {
        &self.plan.keys
    }

    /// Where each key's values lie in the flat observation (`start..end`), in key order.
    pub fn key_slices(&self) -> Vec<(String, std::ops::Range<usize>)> {
        let mut start = 0;
        self.plan
            .keys
            .iter()
            .zip(&self.plan.sizes)
            .map(|(k, &n)| {
                let r = start..start + n;
                start += n;
                (k.clone(), r)
            })
            .collect()
    }
}

impl<E> gym_core::CustomWrapper for FlatGymWrapper<E>
where
    E: Env,
    E::ObsSpace: DictObservationSpace,
    E::ActSpace: NumericSpace,
{
    type Observation = ArrayD<f32>;
    type Action = ArrayD<f32>;
    type ObservationSpace = BoxSpace<f32>;
    type ActionSpace = BoxSpace<f32>;

    fn observation_space(this: &Self) -> &BoxSpace<f32> {
        &this.observation_space
    }

    fn action_space(this: &Self) -> &BoxSpace<f32> {
        &this.action_space
    }

    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(ArrayD<f32>, Info)> {
        let (obs, info) = this.env.reset(seed, options)?;
        Ok((this.plan.flatten(&E::ObsSpace::into_dict(obs)?)?, info))
    }

    fn step(this: &mut Self, action: &ArrayD<f32>) -> Result<Step<ArrayD<f32>>> {
        let mut observation = ArrayD::zeros(IxDyn(&[this.plan.total]));
        let mut info = Info::new();
        let t = this.step_into(action, &mut observation, &mut info)?;
        Ok(Step {
            observation,
            reward: t.reward,
            terminated: t.terminated,
            truncated: t.truncated,
            info,
        })
    }

    fn step_into(
        this: &mut Self,
        action: &ArrayD<f32>,
        observation: &mut ArrayD<f32>,
        info: &mut Info,
    ) -> Result<Transition> {
        let (transition, inner_obs) = this.buffers.step_into(&mut this.env, action, info)?;
        this.plan
            .flatten_into(E::ObsSpace::as_dict(inner_obs)?, observation)?;
        Ok(transition)
    }
}

impl<E> gym_core::Wrapper for FlatGymWrapper<E>
where
    E: Env,
    E::ObsSpace: DictObservationSpace,
    E::ActSpace: NumericSpace,
{
    type Inner = E;
    type Kind = gym_core::Custom;
    fn inner(&self) -> &E {
        &self.env
    }
    fn inner_mut(&mut self) -> &mut E {
        &mut self.env
    }
    fn into_inner(self) -> E {
        self.env
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{DictEnv, a32};
    use gym_core::{DType, EnvExt};

    #[test]
    fn default_keys_follow_robosuite() {
        assert_eq!(
            default_keys(&DictEnv::new(5, false).observation_space),
            ["object-state", "robot0_proprio-state"]
        );
        assert_eq!(
            default_keys(&DictEnv::new(5, true).observation_space),
            ["object-state", "frontview_image", "robot0_proprio-state"]
        );
    }

    #[test]
    fn flat_observations_are_f32_and_object_state_first() {
        let mut env = GymWrapper::new(DictEnv::new(5, false), None, true).unwrap();
        assert_eq!(
            env.observation_space().to_string(),
            "Box(-inf, inf, [7], float32)"
        );
        let (obs, _) = env.reset(Some(4), None).unwrap();
        assert!(env.observation_space().contains(&obs));
        let flat = obs.as_array().unwrap();
        assert_eq!(flat.dtype(), DType::F32);
        let s = env.unwrapped_as::<DictEnv>().unwrap().state;
        let want: Vec<f64> = [s[0] + s[1], s[1], s[2], s[0], s[1], s[2], 0.0]
            .iter()
            .map(|v| f64::from(*v as f32))
            .collect();
        assert_eq!(flat.to_f64_vec(), want);
    }

    #[test]
    fn dict_mode_keeps_dtypes_and_order() {
        let keys = vec![
            "robot0_eef_quat_site".to_owned(),
            "frontview_image".to_owned(),
        ];
        let mut env = GymWrapper::new(DictEnv::new(5, true), Some(keys), false).unwrap();
        let space = env.observation_space().as_dict().unwrap().clone();
        assert_eq!(
            space.keys().collect::<Vec<_>>(),
            ["robot0_eef_quat_site", "frontview_image"]
        );
        assert_eq!(
            space
                .get("frontview_image")
                .unwrap()
                .as_box()
                .unwrap()
                .dtype(),
            DType::U8
        );
        let (obs, _) = env.reset(Some(0), None).unwrap();
        assert!(env.observation_space().contains(&obs));
        let step = env.step(&a32(&[0.0, 0.0, 0.0])).unwrap();
        assert!(env.observation_space().contains(&step.observation));
    }

    #[test]
    fn step_into_equals_step_in_both_modes() {
        let keys = vec![
            "robot0_eef_quat_site".to_owned(),
            "frontview_image".to_owned(),
        ];
        for (keys, flatten) in [(None, true), (Some(keys), false)] {
            let mut by_step =
                GymWrapper::new(DictEnv::new(5, !flatten), keys.clone(), flatten).unwrap();
            let mut by_into = GymWrapper::new(DictEnv::new(5, !flatten), keys, flatten).unwrap();
            let (first, _) = by_step.reset(Some(3), None).unwrap();
            let (mut obs, mut info) = by_into.reset(Some(3), None).unwrap();
            assert_eq!(first, obs);
            for k in 0..4 {
                let a = a32(&[0.1 * k as f32, -0.05, 0.02]);
                let step = by_step.step(&a).unwrap();
                let t = by_into.step_into(&a, &mut obs, &mut info).unwrap();
                assert_eq!(step.observation, obs, "step {k}, flatten_obs {flatten}");
                assert_eq!(step.info, info);
                assert_eq!(
                    (step.reward, step.terminated, step.truncated),
                    (t.reward, t.terminated, t.truncated)
                );
            }
            // A bad action is rejected by both and leaves the kept observation alone.
            let before = obs.clone();
            assert!(
                by_into
                    .step_into(&a32(&[0.0]), &mut obs, &mut info)
                    .is_err()
            );
            assert!(by_step.step(&a32(&[0.0])).is_err());
            assert_eq!(obs, before);
        }
    }

    #[test]
    fn seeded_resets_are_deterministic_and_flags_forwarded() {
        let run = |seed| {
            let mut env = FlatGymWrapper::new(DictEnv::new(3, false), None).unwrap();
            let (o, _) = env.reset(Some(seed), None).unwrap();
            let steps: Vec<_> = (0..3)
                .map(|_| env.step(&a32(&[0.1, 0.05, -0.1])).unwrap())
                .collect();
            (o, steps)
        };
        let (a, sa) = run(11);
        let (b, sb) = run(11);
        assert_eq!(a, b);
        assert_eq!(sa, sb);
        assert_ne!(a, run(12).0);
        assert_eq!(
            sa.iter()
                .map(|s| (s.terminated, s.truncated))
                .collect::<Vec<_>>(),
            [(false, false), (false, false), (false, true)]
        );
        assert!(sa.iter().all(|s| s.info.get_bool("success").is_some()));
    }

    #[test]
    fn action_space_is_f32_rounded_inwards() {
        let mut env = FlatGymWrapper::new(DictEnv::new(3, false), None).unwrap();
        let space = env.action_space().clone();
        assert_eq!(space.dtype(), DType::F32);
        // 0.1 is not an f32: the f32 bound lies inside [-0.1, 0.1].
        assert!(f64::from(space.high()[[1]]) <= 0.1 && f64::from(space.low()[[1]]) >= -0.1);
        assert_eq!(space.high()[[0]], 1.0);
        env.reset(Some(0), None).unwrap();
        let edge = a32(&[1.0, space.high()[[1]], space.low()[[2]]]);
        assert!(env.step(&edge).is_ok());
        assert!(matches!(
            env.step(&a32(&[0.0, 0.0])),
            Err(Error::InvalidAction(_))
        ));
    }

    #[test]
    fn unknown_and_duplicate_keys() {
        let err = GymWrapper::new(DictEnv::new(3, false), Some(vec!["cube_pos".into()]), true)
            .unwrap_err();
        match err {
            Error::UnknownKey { key, available } => {
                assert_eq!(key, "cube_pos");
                assert!(available.contains(&"object-state".to_owned()));
            }
            other => panic!("{other}"),
        }
        assert!(
            GymWrapper::new(
                DictEnv::new(3, false),
                Some(vec!["object-state".into(), "object-state".into()]),
                true
            )
            .is_err()
        );
        assert!(GymWrapper::new(DictEnv::new(3, false), Some(vec![]), true).is_err());
    }

    #[test]
    fn boxed_dict_envs_are_accepted() {
        use gym_core::IntoBoxedEnv;
        let mut boxed = FlatGymWrapper::new(DictEnv::new(3, false).boxed(), None).unwrap();
        let mut typed = FlatGymWrapper::new(DictEnv::new(3, false), None).unwrap();
        assert_eq!(
            boxed.reset(Some(9), None).unwrap().0,
            typed.reset(Some(9), None).unwrap().0
        );
        let a = a32(&[0.2, 0.0, 0.1]);
        assert_eq!(boxed.step(&a).unwrap(), typed.step(&a).unwrap());
        let not_dict = crate::toy::WalkEnv::new(3).boxed();
        assert!(matches!(
            GymWrapper::new(not_dict, None, true),
            Err(Error::InvalidArgument { .. })
        ));
    }

    #[test]
    fn out_of_order_dicts_use_the_name_fallback() {
        let mut inner = DictEnv::new(3, false);
        inner.shuffle_keys = true;
        let mut shuffled = FlatGymWrapper::new(inner, None).unwrap();
        let mut plain = FlatGymWrapper::new(DictEnv::new(3, false), None).unwrap();
        assert_eq!(
            shuffled.reset(Some(5), None).unwrap().0,
            plain.reset(Some(5), None).unwrap().0
        );
        let mut dict = GymWrapper::new(
            {
                let mut e = DictEnv::new(3, false);
                e.shuffle_keys = true;
                e
            },
            None,
            false,
        )
        .unwrap();
        let (obs, _) = dict.reset(Some(5), None).unwrap();
        assert_eq!(
            obs.as_dict().unwrap().keys().collect::<Vec<_>>(),
            ["object-state", "robot0_proprio-state"]
        );
        assert_eq!(
            shuffled.key_slices()[1],
            ("robot0_proprio-state".to_owned(), 3..7)
        );
    }
}
