//! robosuite's `GymWrapper`, corrected: [`GymWrapper`] (robosuite's signature, dynamic
//! observations) and [`FlatGymWrapper`] (typed flat `f32` observations).
//!
//! Both select observation keys of a Dict-observation environment (robosuite's
//! `RobosuiteEnv`, any env whose observation space is a [`DictSpace`], or a boxed env from
//! the registry whose [`AnySpace`] is a Dict), and expose the environment's action bounds as
//! an `f32` Box. Compared with robosuite 1.5.2's wrapper:
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
//! `Value`.
//!
//! Both are compositions of wrappers: the selection is [`FilterObservation::keeping_order`]
//! (the keys in the order given, as robosuite concatenates them) under an `f32` action
//! cast, and the flat observation a concatenation layer over it: robosuite's
//! `np.concatenate([np.array(obs[k]).flatten() for k in keys])` cast to `f32`, so each key
//! contributes its values row-major (a Discrete key its scalar value, a MultiDiscrete or
//! MultiBinary key its entries; not Gymnasium's one-hot [`FlattenObservation`]). Each layer
//! keeps its inner observation between steps, so `step_into` allocates nothing after its
//! first step.

use crate::FilterObservation;
#[cfg(doc)]
use crate::FlattenObservation;
use gym_core::spaces::{AnySpace, BoxSpace, DictSpace, FilterKeys, FilterableSpace, NumericSpace};
use gym_core::{
    ActionWrapper, Actions, ArrayValue, DynSpace, Env, Error, Flatten, Info, ObsRow,
    ObservationWrapper, Observations, Pick, ResetOptions, Result, Scalar, Space, Step, Transition,
    Value, Wrapper,
};
use ndarray::{ArrayD, IxDyn};

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

/// The environment with `f32` actions in the environment's bounds (rounded inwards), each
/// cast to an inner action kept between steps.
#[derive(Debug, Clone)]
struct F32Actions<E: Env> {
    env: E,
    space: BoxSpace<f32>,
    kept: Option<E::Act>,
}

impl<E: Env> Wrapper for F32Actions<E>
where
    E::ActSpace: NumericSpace,
{
    type Inner = E;
    type Kind = Actions;
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

impl<E: Env> ActionWrapper for F32Actions<E>
where
    E::ActSpace: NumericSpace,
{
    type Space = BoxSpace<f32>;

    fn space(&self) -> &BoxSpace<f32> {
        &self.space
    }

    fn action(&mut self, action: &ArrayD<f32>) -> Result<E::Act> {
        self.env
            .action_space()
            .element_from_array(action)
            .map_err(Error::into_invalid_action)
    }

    fn action_into(&mut self, action: &ArrayD<f32>, out: &mut E::Act) -> Result<()> {
        self.env
            .action_space()
            .element_from_array_into(action, out)
            .map_err(Error::into_invalid_action)
    }

    fn action_buffer(&mut self) -> Option<&mut Option<E::Act>> {
        Some(&mut self.kept)
    }
}

/// The selected keys, in the order given, over `f32` actions.
type Selected<E> = FilterObservation<F32Actions<E>>;

/// The selected keys concatenated as `f32`, as robosuite's wrapper flattens them: each
/// key's values row-major, a Discrete key its scalar value. The inner (selected)
/// observation is kept between steps and written into the caller's vector in place.
#[derive(Debug, Clone)]
struct Concat<E: Env> {
    env: E,
    /// Each key's number of values, in order.
    sizes: Vec<usize>,
    space: BoxSpace<f32>,
    kept: Option<E::Obs>,
    /// Each key's segment of the flat vector, when every key is an array.
    plan: Option<Vec<Pick>>,
}

impl<E: Env> Concat<E> {
    fn new(env: E, sizes: Vec<usize>) -> Self {
        let space = BoxSpace::unbounded(&[sizes.iter().sum()]);
        let any = env.observation_space().to_any();
        let arrays = any.as_dict().is_some_and(|d| {
            d.len() == sizes.len()
                && d.iter().all(|(_, s)| {
                    matches!(
                        s,
                        AnySpace::Box(_) | AnySpace::MultiBinary(_) | AnySpace::MultiDiscrete(_)
                    )
                })
        });
        let plan = arrays.then(|| {
            let mut start = 0;
            sizes
                .iter()
                .map(|&len| {
                    let pick = Pick::Segment {
                        leaf: 0,
                        start,
                        len,
                    };
                    start += len;
                    pick
                })
                .collect()
        });
        Self {
            env,
            sizes,
            space,
            kept: None,
            plan,
        }
    }
}

impl<E: Env> Wrapper for Concat<E>
where
    E::ObsSpace: FilterableSpace,
{
    type Inner = E;
    type Kind = Observations;
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

impl<E: Env> ObservationWrapper for Concat<E>
where
    E::ObsSpace: FilterableSpace,
{
    type Space = BoxSpace<f32>;

    fn space(&self) -> &BoxSpace<f32> {
        &self.space
    }

    fn observation(&mut self, observation: E::Obs) -> Result<ArrayD<f32>> {
        let mut out = ArrayD::zeros(IxDyn(&[self.space.flatdim()]));
        self.observation_into(&observation, &mut out)?;
        Ok(out)
    }

    fn observation_into(&mut self, observation: &E::Obs, out: &mut ArrayD<f32>) -> Result<()> {
        let total = self.space.flatdim();
        if out.shape() != [total] || !out.is_standard_layout() {
            *out = ArrayD::zeros(IxDyn(&[total]));
        }
        let flat = out.as_slice_mut().expect("a standard-layout vector");
        let space = self.env.observation_space();
        let mut at = 0;
        for (j, &size) in self.sizes.iter().enumerate() {
            let value = space.element_part(observation, j).ok_or_else(|| {
                Error::from(gym_core::SpaceError::InvalidArgument(format!(
                    "the observation has no part {j} of the selected keys"
                )))
            })?;
            let n = match value {
                Value::Array(a) => {
                    let n = a.len();
                    if n == size {
                        let dst = &mut flat[at..at + n];
                        gym_core::for_each_array!(a, arr => dst
                            .iter_mut()
                            .zip(arr.iter())
                            .for_each(|(d, v)| *d = v.to_f64() as f32));
                    }
                    n
                }
                Value::Discrete(d) => {
                    if size == 1 {
                        flat[at] = *d as f32;
                    }
                    1
                }
                other => {
                    return Err(gym_core::SpaceError::WrongKind {
                        expected: "array",
                        got: other.kind(),
                    }
                    .into());
                }
            };
            if n != size {
                return Err(Error::Contract {
                    check: "GymWrapper".into(),
                    message: format!("observation part {j} has {n} elements, its space {size}")
                        .into(),
                });
            }
            at += n;
        }
        Ok(())
    }

    fn inner_buffer(&mut self) -> Option<&mut Option<E::Obs>> {
        Some(&mut self.kept)
    }

    fn row_plan(&self) -> Option<&[Pick]> {
        self.plan.as_deref()
    }
}

/// The selected keys concatenated as `f32`.
type Flat<E> = Concat<Selected<E>>;

/// Checks the environment and keys as robosuite's wrapper needs them and selects the keys:
/// the selection, the keys and each key's flat size.
fn select<E>(
    env: E,
    keys: Option<Vec<String>>,
    flat: bool,
) -> Result<(Selected<E>, Vec<String>, Vec<usize>)>
where
    E: Env,
    E::ObsSpace: FilterableSpace,
    E::ActSpace: NumericSpace,
{
    let any = env.observation_space().to_any();
    let dict = any.as_dict().ok_or_else(|| {
        Error::invalid_argument(
            "env",
            format!("GymWrapper needs a Dict observation space, got {any}"),
        )
    })?;
    let keys = keys.unwrap_or_else(|| default_keys(dict));
    if keys.is_empty() {
        let available: Vec<&str> = dict.keys().collect();
        return Err(Error::invalid_argument(
            "keys",
            format!(
                "no observation keys selected (available: {})",
                available.join(", ")
            ),
        ));
    }
    let selected = dict.select_space(&FilterKeys::Names(keys.clone()))?;
    if flat
        && let Some((k, sub)) = selected
            .iter()
            .find(|(_, s)| matches!(s, AnySpace::Dict(_) | AnySpace::Tuple(_)))
    {
        return Err(Error::invalid_argument(
            "keys",
            format!(
                "`{k}` is a {} space; only array observations can be flattened",
                sub.kind()
            ),
        ));
    }
    // robosuite's `np.array(obs[k]).flatten()`: each key's number of values (1 for a
    // Discrete scalar), not Gymnasium's flat dimension (a Discrete one-hot).
    let sizes = selected
        .iter()
        .map(|(_, s)| s.shape().map_or(1, |s| s.iter().product()))
        .collect();
    let actions = F32Actions {
        space: f32_action_space(env.action_space())?,
        env,
        kept: None,
    };
    let stack = FilterObservation::keeping_order(actions, keys.clone())?;
    Ok((stack, keys, sizes))
}

/// The flat stack over a selection whose keys have `sizes` values.
fn flat<E>(selected: Selected<E>, sizes: Vec<usize>) -> Flat<E>
where
    E: Env,
    E::ObsSpace: FilterableSpace,
    E::ActSpace: NumericSpace,
{
    Concat::new(selected, sizes)
}

/// [`Env::step`] of a flat stack through its `step_into` (one new array).
fn flat_step<E>(stack: &mut Flat<E>, action: &ArrayD<f32>, n: usize) -> Result<Step<ArrayD<f32>>>
where
    E: Env,
    E::ObsSpace: FilterableSpace,
    E::ActSpace: NumericSpace,
{
    let mut observation = ArrayD::zeros(IxDyn(&[n]));
    let mut info = Info::new();
    let t = stack.step_into(action, &mut observation, &mut info)?;
    Ok(Step {
        observation,
        reward: t.reward,
        terminated: t.terminated,
        truncated: t.truncated,
        info,
    })
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
pub struct GymWrapper<E: Env>
where
    E::ObsSpace: FilterableSpace,
    E::ActSpace: NumericSpace,
{
    stack: Stack<E>,
    keys: Vec<String>,
    observation_space: AnySpace,
    action_space: BoxSpace<f32>,
}

/// The layers of a [`GymWrapper`]: the selection alone (with its last observation), or
/// the flat stack.
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)]
enum Stack<E: Env>
where
    E::ObsSpace: FilterableSpace,
    E::ActSpace: NumericSpace,
{
    Dict(Selected<E>, Option<E::Obs>),
    Flat(Flat<E>),
}

impl<E> GymWrapper<E>
where
    E: Env,
    E::ObsSpace: FilterableSpace,
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
        let (selected, keys, sizes) = select(env, keys, flatten_obs)?;
        let action_space = selected.action_space().clone();
        let (stack, observation_space) = if flatten_obs {
            let n = sizes.iter().sum();
            let space = BoxSpace::<f32>::unbounded(&[n]).into();
            (Stack::Flat(flat(selected, sizes)), space)
        } else {
            let space = selected.observation_space().to_any();
            (Stack::Dict(selected, None), space)
        };
        Ok(Self {
            stack,
            keys,
            observation_space,
            action_space,
        })
    }

    /// The selected keys, in observation order.
    pub fn keys(&self) -> &[String] {
        &self.keys
    }

    /// Whether observations are flattened.
    pub fn flatten_obs(&self) -> bool {
        matches!(self.stack, Stack::Flat(_))
    }
}

impl<E> gym_core::CustomWrapper for GymWrapper<E>
where
    E: Env,
    E::ObsSpace: FilterableSpace,
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
        match &mut this.stack {
            Stack::Dict(s, _) => {
                let (obs, info) = s.reset(seed, options)?;
                Ok((s.observation_space().into_value(obs), info))
            }
            Stack::Flat(s) => {
                let (obs, info) = s.reset(seed, options)?;
                Ok((obs.into(), info))
            }
        }
    }

    fn step(this: &mut Self, action: &ArrayD<f32>) -> Result<Step<Value>> {
        match &mut this.stack {
            Stack::Dict(s, _) => {
                let step = s.step(action)?;
                let space = s.observation_space();
                Ok(step.map_observation(|o| space.into_value(o)))
            }
            Stack::Flat(s) => {
                let n = this.observation_space.flatdim();
                Ok(flat_step(s, action, n)?.map_observation(Value::from))
            }
        }
    }

    fn step_into(
        this: &mut Self,
        action: &ArrayD<f32>,
        observation: &mut Value,
        info: &mut Info,
    ) -> Result<Transition> {
        match (&mut this.stack, observation) {
            (Stack::Flat(s), Value::Array(ArrayValue::F32(out))) => s.step_into(action, out, info),
            (Stack::Dict(s, kept), out) => match kept {
                Some(obs) => {
                    let t = s.step_into(action, obs, info)?;
                    s.observation_space().to_value_into(obs, out);
                    Ok(t)
                }
                None => {
                    let step = s.step(action)?;
                    s.observation_space().to_value_into(&step.observation, out);
                    *info = step.info;
                    *kept = Some(step.observation);
                    Ok(Transition {
                        reward: step.reward,
                        terminated: step.terminated,
                        truncated: step.truncated,
                    })
                }
            },
            (Stack::Flat(_), out) => {
                let step = <Self as gym_core::CustomWrapper>::step(this, action)?;
                *out = step.observation;
                *info = step.info;
                Ok(Transition {
                    reward: step.reward,
                    terminated: step.terminated,
                    truncated: step.truncated,
                })
            }
        }
    }

    fn writes_rows(this: &Self) -> bool {
        match &this.stack {
            Stack::Dict(s, _) => s.writes_rows(),
            Stack::Flat(s) => s.writes_rows(),
        }
    }

    fn step_for_row(this: &mut Self, action: &ArrayD<f32>, info: &mut Info) -> Result<Transition> {
        match &mut this.stack {
            Stack::Dict(s, _) => s.step_for_row(action, info),
            Stack::Flat(s) => s.step_for_row(action, info),
        }
    }

    fn write_observation_row(this: &Self, row: &mut ObsRow<'_>) -> Result<()> {
        match &this.stack {
            Stack::Dict(s, _) => s.write_observation_row(row),
            Stack::Flat(s) => s.write_observation_row(row),
        }
    }
}

/// The innermost environment of a selection.
fn env_of<E: Env>(selected: &Selected<E>) -> &E
where
    E::ObsSpace: FilterableSpace,
    E::ActSpace: NumericSpace,
{
    selected.inner().inner()
}

impl<E> Wrapper for GymWrapper<E>
where
    E: Env,
    E::ObsSpace: FilterableSpace,
    E::ActSpace: NumericSpace,
{
    type Inner = E;
    type Kind = gym_core::Custom;
    fn inner(&self) -> &E {
        match &self.stack {
            Stack::Dict(s, _) => env_of(s),
            Stack::Flat(s) => env_of(s.inner()),
        }
    }
    fn inner_mut(&mut self) -> &mut E {
        match &mut self.stack {
            Stack::Dict(s, _) => s.inner_mut().inner_mut(),
            Stack::Flat(s) => s.inner_mut().inner_mut().inner_mut(),
        }
    }
    fn into_inner(self) -> E {
        match self.stack {
            Stack::Dict(s, _) => s.into_inner().into_inner(),
            Stack::Flat(s) => s.into_inner().into_inner().into_inner(),
        }
    }
}

/// [`GymWrapper`] with `flatten_obs = true` and typed observations: `ArrayD<f32>` in
/// `Box(-inf, inf, (n,), float32)`.
///
/// [`Env::step_into`] reuses the caller's buffers and keeps the inner environment's
/// observation and action between steps, so a loop of `step_into` over a robosuite env does
/// not allocate.
#[derive(Debug, Clone)]
pub struct FlatGymWrapper<E: Env>
where
    E::ObsSpace: FilterableSpace,
    E::ActSpace: NumericSpace,
{
    stack: Flat<E>,
    keys: Vec<String>,
    sizes: Vec<usize>,
    observation_space: BoxSpace<f32>,
}

impl<E> FlatGymWrapper<E>
where
    E: Env,
    E::ObsSpace: FilterableSpace,
    E::ActSpace: NumericSpace,
{
    /// Wraps `env`, selecting and flattening `keys` (robosuite's defaults when `None`).
    ///
    /// # Errors
    /// As [`GymWrapper::new`].
    pub fn new(env: E, keys: Option<Vec<String>>) -> Result<Self> {
        let (selected, keys, sizes) = select(env, keys, true)?;
        let observation_space = BoxSpace::unbounded(&[sizes.iter().sum()]);
        Ok(Self {
            stack: flat(selected, sizes.clone()),
            keys,
            sizes,
            observation_space,
        })
    }

    /// The selected keys, in concatenation order.
    pub fn keys(&self) -> &[String] {
        &self.keys
    }

    /// Where each key's values lie in the flat observation (`start..end`), in key order.
    pub fn key_slices(&self) -> Vec<(String, std::ops::Range<usize>)> {
        let mut start = 0;
        self.keys
            .iter()
            .zip(&self.sizes)
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
    E::ObsSpace: FilterableSpace,
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
        this.stack.action_space()
    }

    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(ArrayD<f32>, Info)> {
        this.stack.reset(seed, options)
    }

    fn step(this: &mut Self, action: &ArrayD<f32>) -> Result<Step<ArrayD<f32>>> {
        flat_step(&mut this.stack, action, this.observation_space.flatdim())
    }

    fn step_into(
        this: &mut Self,
        action: &ArrayD<f32>,
        observation: &mut ArrayD<f32>,
        info: &mut Info,
    ) -> Result<Transition> {
        this.stack.step_into(action, observation, info)
    }

    fn writes_rows(this: &Self) -> bool {
        this.stack.writes_rows()
    }

    fn step_for_row(this: &mut Self, action: &ArrayD<f32>, info: &mut Info) -> Result<Transition> {
        this.stack.step_for_row(action, info)
    }

    fn write_observation_row(this: &Self, row: &mut ObsRow<'_>) -> Result<()> {
        this.stack.write_observation_row(row)
    }
}

impl<E> Wrapper for FlatGymWrapper<E>
where
    E: Env,
    E::ObsSpace: FilterableSpace,
    E::ActSpace: NumericSpace,
{
    type Inner = E;
    type Kind = gym_core::Custom;
    fn inner(&self) -> &E {
        env_of(self.stack.inner())
    }
    fn inner_mut(&mut self) -> &mut E {
        self.stack.inner_mut().inner_mut().inner_mut()
    }
    fn into_inner(self) -> E {
        self.stack.into_inner().into_inner().into_inner()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{DictEnv, a32};
    use gym_core::{DType, EnvExt, Space};

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

    #[test]
    fn discrete_keys_flatten_to_their_values_as_robosuite() {
        use crate::toy::{ScriptEnv, unit_actions};
        use gym_core::spaces::{Discrete, MultiBinary, MultiDiscrete};
        let space = DictSpace::new([
            ("pos", AnySpace::from(BoxSpace::<f64>::unbounded(&[2]))),
            ("mode", Discrete::new(4).unwrap().into()),
            (
                "gears",
                MultiDiscrete::new(ndarray::arr1(&[3i64, 5]).into_dyn())
                    .unwrap()
                    .into(),
            ),
            ("flags", MultiBinary::new(&[3]).unwrap().into()),
        ])
        .unwrap();
        let obs = |t: f64, mode: i64| -> gym_core::DictValue {
            [
                ("pos".to_owned(), Value::from(crate::toy::a64(&[t, -t]))),
                ("mode".to_owned(), Value::Discrete(mode)),
                (
                    "gears".to_owned(),
                    Value::from(ndarray::arr1(&[2i64, 4]).into_dyn()),
                ),
                (
                    "flags".to_owned(),
                    Value::from(ndarray::arr1(&[1i8, 0, 1]).into_dyn()),
                ),
            ]
            .into_iter()
            .collect()
        };
        let script = ScriptEnv::new(
            space,
            unit_actions(),
            vec![obs(0.5, 3), obs(1.5, 1)],
            vec![0.0],
        );
        let keys: Vec<String> = ["mode", "pos", "gears", "flags"]
            .map(str::to_owned)
            .to_vec();
        // robosuite's `np.concatenate([np.array(obs[k]).flatten() for k in keys])`: the
        // Discrete key is its scalar, MultiDiscrete and MultiBinary their entries.
        let want_reset = [3.0f32, 0.5, -0.5, 2.0, 4.0, 1.0, 0.0, 1.0];
        let want_step = [1.0f32, 1.5, -1.5, 2.0, 4.0, 1.0, 0.0, 1.0];
        let mut dynamic = GymWrapper::new(script.clone(), Some(keys.clone()), true).unwrap();
        assert_eq!(
            dynamic.observation_space().to_string(),
            "Box(-inf, inf, [8], float32)"
        );
        let (first, _) = dynamic.reset(None, None).unwrap();
        assert_eq!(first, Value::from(a32(&want_reset)));
        let (mut o, mut info) = dynamic.reset(None, None).unwrap();
        let a = a32(&[0.0, 0.0]);
        let _ = dynamic.step_into(&a, &mut o, &mut info).unwrap();
        assert_eq!(o, Value::from(a32(&want_step)));
        let mut typed = FlatGymWrapper::new(script, Some(keys)).unwrap();
        assert_eq!(typed.observation_space().shape(), Some(&[8usize][..]));
        assert_eq!(typed.reset(None, None).unwrap().0, a32(&want_reset));
        assert_eq!(typed.step(&a).unwrap().observation, a32(&want_step));
        assert_eq!(
            typed
                .key_slices()
                .into_iter()
                .map(|(_, r)| r)
                .collect::<Vec<_>>(),
            [0..1, 1..3, 3..5, 5..8]
        );
    }
}
