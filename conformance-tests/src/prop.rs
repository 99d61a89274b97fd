//! Property-based checks with proptest: random seeds and random action sequences (drawn by
//! the action space's own sampler, plus actions outside the space), shrinking a failure to
//! a minimal seed and action sequence.
//!
//! Each `prop_*` function builds its own proptest runner from a [`PropConfig`] (a fixed
//! runner seed by default, so a failure reproduces) and returns a [`PropFailure`] naming
//! the [`Property`] with the minimal failing input. [`prop_check_env`] runs them all.
//!
//! The environment is made once per property with `make_env` and reused across cases (each
//! case starts from a seeded reset); after a panic it is made again.
//!
//! ```
//! use conformance_tests::{prop::{prop_check_env, EpisodeEndSpec, PropConfig}, toy::PointMass};
//!
//! let config = PropConfig { cases: 8, ..PropConfig::default() }
//!     .episode_end(EpisodeEndSpec { truncate_at: Some(10), can_terminate: false });
//! prop_check_env(|| PointMass::new().with_horizon(10), &config).expect("PointMass conforms");
//! ```

use crate::data::{Compare, compact, info_difference, step_difference, value_difference};
use crate::env_checker::{panic_message, reset_call, short_debug};
use crate::invalid::invalid_actions;
use crate::obs::check_obs;
use gym_core::proptest::{action_sequence, any_space, seed};
use gym_core::{AnySpace, DynSpace, Env, Flatten, Info, Space, Step, Value, rng_from_seed};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestCaseError, TestError, TestRunner};
use std::cell::RefCell;
use std::fmt;
use std::marker::PhantomData;
use std::panic::{AssertUnwindSafe, catch_unwind};

/// A property the suite checks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Property {
    /// `make_env` panicked.
    EnvConstruction,
    /// Samples of a space lie in it, and the same sampler seed gives the same sample.
    SpaceSamples,
    /// `flatten(x)` lies in `flatten_space`, has `flatdim` entries, and
    /// `unflatten(flatten(x)) == x` bit for bit.
    FlattenRoundTrip,
    /// Along any seed and action sequence (resetting when an episode ends), every
    /// observation passes [`check_obs`] and every reward is finite.
    ObservationsInSpace,
    /// Replaying a seed and action sequence gives a bit-identical trajectory (observations,
    /// rewards, flags, infos), on the same environment and on a fresh one.
    ReplayIdentical,
    /// An action outside the space gives `Error::InvalidAction` at any point of an episode,
    /// and the rest of the episode is bit-identical to a replay without it.
    InvalidActionRecovery,
    /// `truncated` is first reported at exactly step N of every episode (a `TimeLimit`, or
    /// an environment's own horizon), never before.
    TruncationAtLimit,
    /// The time limit and termination are different causes: an environment that declares
    /// no terminal states never reports `terminated` (a horizon is `truncated` only).
    TerminationCause,
    /// Restoring a state taken with [`StateHook::get_state`] gives back the same state, and
    /// replaying the same actions from it is bit-identical.
    StateRoundTrip,
}

impl Property {
    /// A short name, such as `"replay_identical"`.
    pub fn name(self) -> &'static str {
        match self {
            Property::EnvConstruction => "env_construction",
            Property::SpaceSamples => "space_samples",
            Property::FlattenRoundTrip => "flatten_round_trip",
            Property::ObservationsInSpace => "observations_in_space",
            Property::ReplayIdentical => "replay_identical",
            Property::InvalidActionRecovery => "invalid_action_recovery",
            Property::TruncationAtLimit => "truncation_at_limit",
            Property::TerminationCause => "termination_cause",
            Property::StateRoundTrip => "state_round_trip",
        }
    }

    fn tag(self) -> String {
        format!("[{}] ", self.name())
    }
}

impl fmt::Display for Property {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A property that failed, with the minimal input proptest shrank the failure to.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("property {property} failed: {message}\nminimal failing input: {minimal_input}")]
pub struct PropFailure {
    /// The property.
    pub property: Property,
    /// What was observed on the minimal input.
    pub message: String,
    /// The minimal failing input (`Debug`, cut to 2000 characters): the seed and actions.
    pub minimal_input: String,
    /// The number of actions in the minimal failing input, where the input is a sequence.
    pub minimal_actions: Option<usize>,
}

/// The episode-end rules an environment promises, for [`Property::TruncationAtLimit`] and
/// [`Property::TerminationCause`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EpisodeEndSpec {
    /// Every episode that does not terminate earlier is truncated at exactly this step
    /// (a `TimeLimit`'s `max_episode_steps`, or a base environment's horizon).
    pub truncate_at: Option<u64>,
    /// Whether the environment has terminal states. When `false`, `terminated` must never
    /// be reported, so the end of the horizon is `truncated` only (robosuite tasks other
    /// than Wipe: Gymnasium's robosuite wrapper wrongly reports the horizon as
    /// `terminated`).
    pub can_terminate: bool,
}

/// How the property suite runs.
#[derive(Debug, Clone, PartialEq)]
pub struct PropConfig {
    /// Successful cases per property. Default 32.
    pub cases: u32,
    /// The longest action sequence. Default 24.
    pub max_actions: usize,
    /// At most this many shrinking steps. Default 512.
    pub max_shrink_iters: u32,
    /// The proptest runner's seed (fixed, so failures reproduce). Default 0.
    pub rng_seed: u64,
    /// Also replay on a freshly made environment in [`Property::ReplayIdentical`].
    /// Default `true`.
    pub fresh_env_replay: bool,
    /// Run [`Property::InvalidActionRecovery`]. Default `true`.
    pub invalid_actions: bool,
    /// Count finite out-of-bounds Box values as invalid actions. Default `false`.
    pub out_of_bounds_actions_invalid: bool,
    /// The episode-end rules to check; `None` skips [`Property::TruncationAtLimit`] and
    /// [`Property::TerminationCause`]. Default `None`.
    pub episode_end: Option<EpisodeEndSpec>,
    /// The environment may give different results for the same seed and actions: skips the
    /// replay comparisons. Default `false`.
    pub nondeterministic: bool,
    /// Info entries left out of replay comparisons, as dotted paths (`"episode.t"`, the
    /// wall-clock time `RecordEpisodeStatistics` reports). Default none.
    pub ignored_info_keys: Vec<String>,
}

impl Default for PropConfig {
    fn default() -> Self {
        Self {
            cases: 32,
            max_actions: 24,
            max_shrink_iters: 512,
            rng_seed: 0,
            fresh_env_replay: true,
            invalid_actions: true,
            out_of_bounds_actions_invalid: false,
            episode_end: None,
            nondeterministic: false,
            ignored_info_keys: Vec::new(),
        }
    }
}

impl PropConfig {
    /// A small configuration for expensive environments (simulators): 8 cases, sequences of
    /// at most 6 actions, 32 shrinking steps.
    pub fn cheap() -> Self {
        Self {
            cases: 8,
            max_actions: 6,
            max_shrink_iters: 32,
            ..Self::default()
        }
    }

    /// Adds an info entry (a dotted path) to [`PropConfig::ignored_info_keys`].
    #[must_use]
    pub fn ignore_info_key(mut self, path: impl Into<String>) -> Self {
        self.ignored_info_keys.push(path.into());
        self
    }

    /// Sets [`PropConfig::episode_end`].
    #[must_use]
    pub fn episode_end(mut self, spec: EpisodeEndSpec) -> Self {
        self.episode_end = Some(spec);
        self
    }

    fn runner(&self) -> TestRunner {
        TestRunner::new(Config {
            cases: self.cases,
            max_shrink_iters: self.max_shrink_iters,
            failure_persistence: None,
            rng_seed: RngSeed::Fixed(self.rng_seed),
            ..Config::default()
        })
    }
}

/// The properties that ran and passed.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PropReport {
    /// The properties that passed, in order.
    pub passed: Vec<Property>,
    /// The properties that were skipped, with the reason.
    pub skipped: Vec<(Property, String)>,
}

/// Access to an environment's full state (robosuite's `get_state` / `set_state`), for
/// [`Property::StateRoundTrip`]. Implement it for a hook type, or use [`FnStateHook`].
pub trait StateHook<E: Env> {
    /// The state.
    type State: Clone + fmt::Debug + PartialEq;

    /// Takes the state.
    ///
    /// # Errors
    /// Whatever the environment reports.
    fn get_state(&self, env: &E) -> gym_core::Result<Self::State>;

    /// Restores a state taken with [`StateHook::get_state`].
    ///
    /// # Errors
    /// Whatever the environment reports.
    fn set_state(&self, env: &mut E, state: &Self::State) -> gym_core::Result<()>;
}

/// A [`StateHook`] from two closures.
pub struct FnStateHook<S, G, P> {
    get: G,
    set: P,
    _state: PhantomData<fn() -> S>,
}

impl<S, G, P> FnStateHook<S, G, P> {
    /// A hook whose `get_state` is `get` and `set_state` is `set`.
    pub fn new(get: G, set: P) -> Self {
        Self {
            get,
            set,
            _state: PhantomData,
        }
    }
}

impl<E, S, G, P> StateHook<E> for FnStateHook<S, G, P>
where
    E: Env,
    S: Clone + fmt::Debug + PartialEq,
    G: Fn(&E) -> gym_core::Result<S>,
    P: Fn(&mut E, &S) -> gym_core::Result<()>,
{
    type State = S;

    fn get_state(&self, env: &E) -> gym_core::Result<S> {
        (self.get)(env)
    }

    fn set_state(&self, env: &mut E, state: &S) -> gym_core::Result<()> {
        (self.set)(env, state)
    }
}

/// Runs one proptest property; `Err` strings of the test start with a property tag.
fn run_property<S: Strategy>(
    default: Property,
    config: &PropConfig,
    strategy: S,
    test: impl Fn(S::Value) -> Result<(), String>,
    actions_of: impl Fn(&S::Value) -> Option<usize>,
) -> Result<(), PropFailure> {
    let mut runner = config.runner();
    let result = runner.run(&strategy, |v| {
        catch_unwind(AssertUnwindSafe(|| test(v)))
            .unwrap_or_else(|p| {
                Err(format!(
                    "the property panicked: {}",
                    panic_message(p.as_ref())
                ))
            })
            .map_err(TestCaseError::fail)
    });
    let (message, input) = match result {
        Ok(()) => return Ok(()),
        Err(TestError::Fail(reason, v)) => (reason.message().to_owned(), Some(v)),
        Err(TestError::Abort(reason)) => (format!("proptest aborted: {}", reason.message()), None),
    };
    let all = [
        Property::EnvConstruction,
        Property::SpaceSamples,
        Property::FlattenRoundTrip,
        Property::ObservationsInSpace,
        Property::ReplayIdentical,
        Property::InvalidActionRecovery,
        Property::TruncationAtLimit,
        Property::TerminationCause,
        Property::StateRoundTrip,
    ];
    let (property, message) = all
        .into_iter()
        .find_map(|p| message.strip_prefix(&p.tag()).map(|m| (p, m.to_owned())))
        .unwrap_or((default, message));
    Err(PropFailure {
        property,
        message,
        minimal_input: input
            .as_ref()
            .map_or_else(|| "none".to_owned(), |v| short_debug(v, 2000)),
        minimal_actions: input.as_ref().and_then(actions_of),
    })
}

/// The environment under test, made on first use and again after a panic.
struct Slot<E, F> {
    make: F,
    env: RefCell<Option<E>>,
}

impl<E: Env, F: Fn() -> E> Slot<E, F> {
    fn new(make: F) -> Self {
        Self {
            make,
            env: RefCell::new(None),
        }
    }

    fn fresh(&self) -> Result<E, String> {
        catch_unwind(AssertUnwindSafe(|| (self.make)())).map_err(|p| {
            format!(
                "{}make_env panicked: {}",
                Property::EnvConstruction.tag(),
                panic_message(p.as_ref())
            )
        })
    }

    fn with<R>(&self, f: impl FnOnce(&mut E) -> Result<R, String>) -> Result<R, String> {
        let mut slot = self.env.borrow_mut();
        let env = match slot.take() {
            Some(env) => env,
            None => self.fresh()?,
        };
        let env = slot.insert(env);
        match catch_unwind(AssertUnwindSafe(|| f(env))) {
            Ok(r) => r,
            Err(p) => {
                *slot = None;
                Err(format!(
                    "the environment panicked: {}",
                    panic_message(p.as_ref())
                ))
            }
        }
    }

    /// The spaces of the environment.
    fn spaces(&self) -> Result<(E::ObsSpace, E::ActSpace), PropFailure> {
        self.with(|env| Ok((env.observation_space().clone(), env.action_space().clone())))
            .map_err(|m| PropFailure {
                property: Property::EnvConstruction,
                message: m
                    .trim_start_matches(&Property::EnvConstruction.tag())
                    .to_owned(),
                minimal_input: "none".into(),
                minimal_actions: None,
            })
    }
}

/// One event of a trajectory.
#[derive(Debug, Clone)]
enum Event {
    Reset(Value, Info),
    Step(Step<Value>),
}

/// `info` without the entries at the dotted `paths`.
fn strip_info(info: &Info, paths: &[String]) -> Info {
    let mut out = info.clone();
    for path in paths {
        let mut parts: Vec<&str> = path.split('.').collect();
        let Some(last) = parts.pop() else { continue };
        let mut node = Some(&mut out);
        for p in parts {
            node = match node.and_then(|n| n.get_mut(p)) {
                Some(gym_core::InfoValue::Map(m)) => Some(m),
                _ => None,
            };
        }
        if let Some(n) = node {
            n.remove(last);
        }
    }
    out
}

fn event_difference(a: &Event, b: &Event, ignored: &[String]) -> Option<String> {
    match (a, b) {
        (Event::Reset(x, i), Event::Reset(y, j)) => value_difference(x, y, Compare::Bits)
            .map(|d| format!("reset observation: {d}"))
            .or_else(|| {
                info_difference(
                    &strip_info(i, ignored),
                    &strip_info(j, ignored),
                    Compare::Bits,
                )
                .map(|d| format!("reset info: {d}"))
            }),
        (Event::Step(x), Event::Step(y)) => {
            let strip = |s: &Step<Value>| Step {
                info: strip_info(&s.info, ignored),
                ..s.clone()
            };
            step_difference(&strip(x), &strip(y), Compare::Bits)
        }
        _ => Some("one run reset where the other stepped".to_owned()),
    }
}

fn trajectory_difference(a: &[Event], b: &[Event], ignored: &[String]) -> Option<String> {
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        if let Some(d) = event_difference(x, y, ignored) {
            return Some(format!("at event {i} ({}): {d}", describe_event(x)));
        }
    }
    (a.len() != b.len()).then(|| format!("the runs have {} and {} events", a.len(), b.len()))
}

fn describe_event(e: &Event) -> &'static str {
    match e {
        Event::Reset(..) => "a reset",
        Event::Step(_) => "a step",
    }
}

fn do_reset<E: Env>(env: &mut E, seed: Option<u64>) -> Result<Event, String> {
    let what = reset_call(seed, None);
    let (obs, info) = env
        .reset(seed, None)
        .map_err(|e| format!("`{what}` returned an error: {e}"))?;
    let value = env.observation_space().to_value(&obs);
    check_obs(&value, &env.observation_space().to_any(), "reset").map_err(|f| {
        format!(
            "{}{} (after `{what}`)",
            Property::ObservationsInSpace.tag(),
            f
        )
    })?;
    Ok(Event::Reset(value, info))
}

fn do_step<E: Env>(env: &mut E, action: &E::Act, label: &str) -> Result<Step<Value>, String> {
    let step = env
        .step(action)
        .map_err(|e| format!("{label}: `step` returned an error: {e}"))?;
    let value = env.observation_space().to_value(&step.observation);
    check_obs(&value, &env.observation_space().to_any(), "step")
        .map_err(|f| format!("{}{label}: {f}", Property::ObservationsInSpace.tag()))?;
    if !step.reward.is_finite() {
        return Err(format!(
            "{}{label}: the reward is {}",
            Property::ObservationsInSpace.tag(),
            step.reward
        ));
    }
    Ok(step.map_observation(|_| value))
}

/// `reset(seed)` then every action; at the end of an episode, `reset()` and go on.
fn rollout<E: Env>(env: &mut E, seed: u64, actions: &[E::Act]) -> Result<Vec<Event>, String> {
    let mut events = vec![do_reset(env, Some(seed))?];
    let mut t = 0;
    for (i, a) in actions.iter().enumerate() {
        t += 1;
        let shown = compact(&env.action_space().to_value(a), 100);
        let label = format!(
            "action {} of {} (episode step {t}, action {shown})",
            i + 1,
            actions.len()
        );
        let step = do_step(env, a, &label)?;
        let done = step.done();
        events.push(Event::Step(step));
        if done && i + 1 < actions.len() {
            events.push(do_reset(env, None)?);
            t = 0;
        }
    }
    Ok(events)
}

/// Steps `actions` from the current state, stopping after the step that ends the episode.
fn run_until_done<E: Env>(
    env: &mut E,
    actions: &[E::Act],
    what: &str,
) -> Result<(Vec<Event>, bool), String> {
    let mut events = Vec::new();
    for (i, a) in actions.iter().enumerate() {
        let step = do_step(env, a, &format!("{what} action {}", i + 1))?;
        let done = step.done();
        events.push(Event::Step(step));
        if done {
            return Ok((events, true));
        }
    }
    Ok((events, false))
}

/// [`Property::SpaceSamples`] and [`Property::FlattenRoundTrip`] for one space: for random
/// sampler seeds, the sample lies in the space, the same seed gives the same sample,
/// `flatten(x)` has `flatdim` entries and lies in `flatten_space()` (whose `flatdim` is the
/// same), and `unflatten(flatten(x))` is `x` bit for bit.
///
/// # Errors
/// The property that failed, with the minimal sampler seed.
pub fn prop_space<S: DynSpace>(space: &S, config: &PropConfig) -> Result<(), PropFailure> {
    let space = space.to_any();
    run_property(
        Property::SpaceSamples,
        config,
        seed(),
        |s| space_case(&space, s),
        |_| None,
    )
}

fn space_case(space: &AnySpace, s: u64) -> Result<(), String> {
    let samples = Property::SpaceSamples.tag();
    let flat = Property::FlattenRoundTrip.tag();
    let x = space.sample(&mut rng_from_seed(s));
    if !space.contains(&x) {
        return Err(format!(
            "{samples}the sample {} (sampler seed {s}) is not in {space}",
            short_debug(&x, 300)
        ));
    }
    let again = space.sample(&mut rng_from_seed(s));
    if let Some(d) = value_difference(&x, &again, Compare::Bits) {
        return Err(format!(
            "{samples}the same sampler seed {s} gave different samples: {d}"
        ));
    }
    let f = space
        .flatten(&x)
        .map_err(|e| format!("{flat}flatten failed on a sample of {space}: {e}"))?;
    let fs = space.flatten_space();
    if f.shape() != [space.flatdim()] {
        return Err(format!(
            "{flat}flatten gave shape {:?}, expected [{}] (flatdim)",
            f.shape(),
            space.flatdim()
        ));
    }
    if fs.flatdim() != space.flatdim() {
        return Err(format!(
            "{flat}flatten_space has flatdim {}, the space {}",
            fs.flatdim(),
            space.flatdim()
        ));
    }
    if !fs.contains(&f) {
        return Err(format!(
            "{flat}flatten(x) = {} is not in flatten_space {fs}",
            short_debug(&f, 300)
        ));
    }
    let back = space
        .unflatten(&f)
        .map_err(|e| format!("{flat}unflatten(flatten(x)) failed: {e}"))?;
    if let Some(d) = value_difference(&back, &x, Compare::Bits) {
        return Err(format!("{flat}unflatten(flatten(x)) differs from x: {d}"));
    }
    Ok(())
}

/// [`Property::SpaceSamples`] and [`Property::FlattenRoundTrip`] over random gym-core spaces
/// (`gym_core::proptest::any_space`, Dict and Tuple nested up to `depth`).
///
/// # Errors
/// The property that failed, with the minimal space and sampler seed.
pub fn prop_gym_core_spaces(depth: u32, config: &PropConfig) -> Result<(), PropFailure> {
    run_property(
        Property::SpaceSamples,
        config,
        (any_space(depth), seed()),
        |(space, s)| space_case(&space, s),
        |_| None,
    )
}

/// [`Property::ObservationsInSpace`]: for a random seed and action sequence (from the
/// action space's sampler), `reset(seed)` and every action, resetting without a seed when
/// an episode ends; every observation passes [`check_obs`] and every reward is finite.
///
/// # Errors
/// The minimal seed and action sequence that gives an observation outside its space.
pub fn prop_observations_in_space<E: Env>(
    make_env: impl Fn() -> E,
    config: &PropConfig,
) -> Result<(), PropFailure> {
    let slot = Slot::new(make_env);
    let (_, act) = slot.spaces()?;
    let strategy = (seed(), action_sequence(act, 1..=config.max_actions.max(1)));
    run_property(
        Property::ObservationsInSpace,
        config,
        strategy,
        |(s, actions)| slot.with(|env| rollout(env, s, &actions).map(|_| ())),
        |(_, a)| Some(a.len()),
    )
}

/// [`Property::ReplayIdentical`]: the trajectory of a random seed and action sequence
/// (observations, rewards, flags and infos, resets included) replays bit for bit on the
/// same environment, and with [`PropConfig::fresh_env_replay`] on a fresh one.
///
/// # Errors
/// The minimal seed and action sequence whose replay diverges, with the first difference.
pub fn prop_replay_identical<E: Env>(
    make_env: impl Fn() -> E,
    config: &PropConfig,
) -> Result<(), PropFailure> {
    let slot = Slot::new(make_env);
    let (_, act) = slot.spaces()?;
    let strategy = (seed(), action_sequence(act, 1..=config.max_actions.max(1)));
    let tag = Property::ReplayIdentical.tag();
    run_property(
        Property::ReplayIdentical,
        config,
        strategy,
        |(s, actions)| {
            let (first, second) =
                slot.with(|env| Ok((rollout(env, s, &actions)?, rollout(env, s, &actions)?)))?;
            if let Some(d) = trajectory_difference(&first, &second, &config.ignored_info_keys) {
                return Err(format!(
                    "{tag}replaying seed {s} on the same environment diverged {d}"
                ));
            }
            if config.fresh_env_replay {
                let mut fresh = slot.fresh()?;
                let third = catch_unwind(AssertUnwindSafe(|| rollout(&mut fresh, s, &actions)))
                    .unwrap_or_else(|p| {
                        Err(format!(
                            "the fresh environment panicked: {}",
                            panic_message(p.as_ref())
                        ))
                    })?;
                if let Some(d) = trajectory_difference(&first, &third, &config.ignored_info_keys) {
                    return Err(format!(
                        "{tag}replaying seed {s} on a fresh environment diverged {d}"
                    ));
                }
            }
            Ok(())
        },
        |(_, a)| Some(a.len()),
    )
}

/// [`Property::InvalidActionRecovery`]: for a random seed, a random valid prefix, one
/// action outside the space (derived from the first suffix action by
/// [`invalid_actions`]) and a random valid suffix: the invalid action gives
/// `Error::InvalidAction`, and the suffix is bit-identical to a replay of prefix + suffix
/// without it. Cases whose prefix ends the episode are vacuous.
///
/// # Errors
/// The minimal seed, prefix, invalid action and suffix that break the property.
pub fn prop_invalid_action_recovery<E: Env>(
    make_env: impl Fn() -> E,
    config: &PropConfig,
) -> Result<(), PropFailure> {
    let slot = Slot::new(make_env);
    let (_, act) = slot.spaces()?;
    let half = (config.max_actions / 2).max(1);
    let strategy = (
        seed(),
        action_sequence(act.clone(), 0..=half),
        any::<u8>(),
        action_sequence(act.clone(), 1..=half),
    );
    let tag = Property::InvalidActionRecovery.tag();
    run_property(
        Property::InvalidActionRecovery,
        config,
        strategy,
        |(s, prefix, pick, suffix)| {
            slot.with(|env| {
                let Some(first) = suffix.first() else { return Ok(()) };
                let candidates = invalid_actions(env.action_space(), first, config.out_of_bounds_actions_invalid, 16);
                if candidates.is_empty() {
                    return Ok(());
                }
                let bad = &candidates[usize::from(pick) % candidates.len()];
                do_reset(env, Some(s))?;
                if run_until_done(env, &prefix, "prefix")?.1 {
                    return Ok(());
                }
                match catch_unwind(AssertUnwindSafe(|| env.step(&bad.action))) {
                    Ok(Err(gym_core::Error::InvalidAction(_))) => {}
                    Ok(Err(e)) => {
                        return Err(format!("{tag}the action outside the space ({}) returned `{e}`, not InvalidAction", bad.label));
                    }
                    Ok(Ok(_)) => return Err(format!("{tag}the action outside the space ({}) was accepted", bad.label)),
                    Err(p) => {
                        return Err(format!(
                            "{tag}the action outside the space ({}) panicked: {}",
                            bad.label,
                            panic_message(p.as_ref())
                        ));
                    }
                }
                let (after, _) = run_until_done(env, &suffix, "suffix")?;
                if config.nondeterministic {
                    return Ok(());
                }
                do_reset(env, Some(s))?;
                run_until_done(env, &prefix, "prefix")?;
                let (replay, _) = run_until_done(env, &suffix, "suffix")?;
                match trajectory_difference(&after, &replay, &config.ignored_info_keys) {
                    Some(d) => Err(format!(
                        "{tag}after rejecting the action ({}), the episode differs from a replay without it {d}",
                        bad.label
                    )),
                    None => Ok(()),
                }
            })
        },
        |(_, p, _, s)| Some(p.len() + 1 + s.len()),
    )
}

/// [`Property::TruncationAtLimit`] and [`Property::TerminationCause`]: for a random seed
/// and two episodes' worth of actions, every episode that does not terminate earlier is
/// truncated at exactly [`EpisodeEndSpec::truncate_at`] (never before), and, unless
/// [`EpisodeEndSpec::can_terminate`], `terminated` is never reported.
///
/// # Errors
/// The minimal seed and action sequence that break a rule.
pub fn prop_episode_end<E: Env>(
    make_env: impl Fn() -> E,
    spec: EpisodeEndSpec,
    config: &PropConfig,
) -> Result<(), PropFailure> {
    let slot = Slot::new(make_env);
    let (_, act) = slot.spaces()?;
    let per_episode = spec.truncate_at.map_or(config.max_actions.max(1), |n| {
        usize::try_from(n).unwrap_or(usize::MAX).max(1)
    });
    let len = per_episode.saturating_mul(2).min(100_000);
    let strategy = (seed(), action_sequence(act, len..=len));
    let (trunc, term) = (
        Property::TruncationAtLimit.tag(),
        Property::TerminationCause.tag(),
    );
    run_property(
        Property::TruncationAtLimit,
        config,
        strategy,
        |(s, actions)| {
            slot.with(|env| {
                do_reset(env, Some(s))?;
                let mut t: u64 = 0;
                for (i, a) in actions.iter().enumerate() {
                    t += 1;
                    let step = do_step(env, a, &format!("action {} (episode step {t})", i + 1))?;
                    if let Some(n) = spec.truncate_at {
                        if step.truncated && t < n {
                            return Err(format!("{trunc}truncated at episode step {t}, before the limit {n}"));
                        }
                        if t == n && !step.truncated {
                            return Err(format!(
                                "{trunc}not truncated at episode step {t}, the limit (terminated={})",
                                step.terminated
                            ));
                        }
                    }
                    if step.terminated && !spec.can_terminate {
                        return Err(format!(
                            "{term}terminated at episode step {t} (truncated={}) although the environment declares no \
                             terminal states: the end of a horizon must be reported as truncated only, not as \
                             terminated",
                            step.truncated
                        ));
                    }
                    if step.done() {
                        do_reset(env, None)?;
                        t = 0;
                    }
                }
                Ok(())
            })
        },
        |(_, a)| Some(a.len()),
    )
}

/// [`Property::TruncationAtLimit`] for a `TimeLimit(max_episode_steps = n)` (or any
/// environment that promises to truncate at step `n`, and may terminate earlier).
///
/// # Errors
/// As [`prop_episode_end`].
pub fn prop_time_limit<E: Env>(
    make_env: impl Fn() -> E,
    n: u64,
    config: &PropConfig,
) -> Result<(), PropFailure> {
    prop_episode_end(
        make_env,
        EpisodeEndSpec {
            truncate_at: Some(n),
            can_terminate: true,
        },
        config,
    )
}

/// [`Property::StateRoundTrip`]: for a random seed, prefix and suffix: after the prefix,
/// take the state; run the suffix; restore the state, which must read back equal; run the
/// suffix again, which must be bit-identical. Cases whose prefix ends the episode are
/// vacuous.
///
/// # Errors
/// The minimal seed, prefix and suffix that break the round trip.
pub fn prop_state_round_trip<E: Env, H: StateHook<E>>(
    make_env: impl Fn() -> E,
    hook: &H,
    config: &PropConfig,
) -> Result<(), PropFailure> {
    let slot = Slot::new(make_env);
    let (_, act) = slot.spaces()?;
    let half = (config.max_actions / 2).max(1);
    let strategy = (
        seed(),
        action_sequence(act.clone(), 0..=half),
        action_sequence(act, 1..=half),
    );
    let tag = Property::StateRoundTrip.tag();
    run_property(
        Property::StateRoundTrip,
        config,
        strategy,
        |(s, prefix, suffix)| {
            slot.with(|env| {
                do_reset(env, Some(s))?;
                if run_until_done(env, &prefix, "prefix")?.1 {
                    return Ok(());
                }
                let state = hook
                    .get_state(env)
                    .map_err(|e| format!("{tag}get_state failed: {e}"))?;
                let (first, _) = run_until_done(env, &suffix, "suffix")?;
                hook.set_state(env, &state)
                    .map_err(|e| format!("{tag}set_state failed: {e}"))?;
                let back = hook
                    .get_state(env)
                    .map_err(|e| format!("{tag}get_state after set_state failed: {e}"))?;
                if back != state {
                    return Err(format!(
                        "{tag}get_state after set_state differs from the state set: {} vs {}",
                        short_debug(&back, 400),
                        short_debug(&state, 400)
                    ));
                }
                let (second, _) = run_until_done(env, &suffix, "replayed suffix")?;
                match trajectory_difference(&first, &second, &config.ignored_info_keys) {
                    Some(d) => Err(format!(
                        "{tag}the suffix replayed from the restored state diverged {d}"
                    )),
                    None => Ok(()),
                }
            })
        },
        |(_, p, s)| Some(p.len() + s.len()),
    )
}

/// Runs the whole property suite on environments made by `make_env`:
/// [`prop_space`] on the observation and action spaces, [`prop_observations_in_space`],
/// [`prop_replay_identical`] (unless [`PropConfig::nondeterministic`]),
/// [`prop_invalid_action_recovery`] (if [`PropConfig::invalid_actions`]) and
/// [`prop_episode_end`] (if [`PropConfig::episode_end`] is set).
///
/// # Errors
/// The first property that fails.
pub fn prop_check_env<E: Env, F: Fn() -> E>(
    make_env: F,
    config: &PropConfig,
) -> Result<PropReport, PropFailure> {
    let mut report = PropReport::default();
    let (obs, act) = Slot::new(&make_env).spaces()?;
    prop_space(&obs, config)?;
    prop_space(&act, config)?;
    report
        .passed
        .extend([Property::SpaceSamples, Property::FlattenRoundTrip]);
    prop_observations_in_space(&make_env, config)?;
    report.passed.push(Property::ObservationsInSpace);
    if config.nondeterministic {
        report.skipped.push((
            Property::ReplayIdentical,
            "the environment is declared nondeterministic".into(),
        ));
    } else {
        prop_replay_identical(&make_env, config)?;
        report.passed.push(Property::ReplayIdentical);
    }
    if config.invalid_actions {
        prop_invalid_action_recovery(&make_env, config)?;
        report.passed.push(Property::InvalidActionRecovery);
    } else {
        report.skipped.push((
            Property::InvalidActionRecovery,
            "disabled by PropConfig::invalid_actions".into(),
        ));
    }
    match config.episode_end {
        Some(spec) => {
            prop_episode_end(&make_env, spec, config)?;
            report
                .passed
                .extend([Property::TruncationAtLimit, Property::TerminationCause]);
        }
        None => {
            for p in [Property::TruncationAtLimit, Property::TerminationCause] {
                report.skipped.push((p, "no EpisodeEndSpec given".into()));
            }
        }
    }
    Ok(report)
}

/// [`prop_check_env`] plus [`prop_state_round_trip`] with `hook`.
///
/// # Errors
/// The first property that fails.
pub fn prop_check_env_with_state<E: Env, F: Fn() -> E, H: StateHook<E>>(
    make_env: F,
    hook: &H,
    config: &PropConfig,
) -> Result<PropReport, PropFailure> {
    let mut report = prop_check_env(&make_env, config)?;
    prop_state_round_trip(&make_env, hook, config)?;
    report.passed.push(Property::StateRoundTrip);
    Ok(report)
}
