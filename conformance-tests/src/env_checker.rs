//! [`check_env`] and the checks it runs, mirroring `gymnasium.utils.env_checker.check_env`
//! check by check.
//!
//! Every call into the environment goes through a guard that turns an `Err` and a panic
//! into a [`Failure`] of the running check, and every observation the checks receive is
//! validated with [`check_obs`] (Gymnasium asserts `obs in observation_space` after each of
//! its resets) and every reward with a finiteness check.

use crate::data::{Compare, compact, info_difference, step_difference, value_difference};
use crate::invalid::invalid_actions;
use crate::obs::check_obs;
use crate::options::CheckOptions;
use crate::passive::{check_render_metadata, check_render_return, check_reward};
use crate::report::{Check, ConformanceError, Failure, Report, Skipped, Warning, WarningKind};
use crate::sb3::sb3_check_spaces;
use crate::spaces::{SpaceType, check_space, check_space_limit};
use gym_core::{
    AnySpace, BoxedEnv, DynSpace, Env, EnvRng, Info, ResetOptions, Space, Step, Value,
    rng_from_seed,
};
use std::any::{Any, TypeId};
use std::panic::{AssertUnwindSafe, catch_unwind};

/// The text of a panic payload.
pub(crate) fn panic_message(payload: &(dyn Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_owned()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "a non-string panic payload".to_owned()
    }
}

/// A `Debug` rendering cut to `max` characters.
#[cfg_attr(not(feature = "prop"), allow(dead_code))]
pub(crate) fn short_debug(x: &impl std::fmt::Debug, max: usize) -> String {
    let s = format!("{x:?}");
    if s.chars().count() <= max {
        s
    } else {
        format!("{}...", s.chars().take(max).collect::<String>())
    }
}

/// How a `reset` call is written in messages: `reset(seed=123)`, `reset()`, ...
pub(crate) fn reset_call(seed: Option<u64>, options: Option<&ResetOptions>) -> String {
    let mut args = Vec::new();
    if let Some(s) = seed {
        args.push(format!("seed={s}"));
    }
    if let Some(o) = options {
        let items: Vec<String> = o.iter().map(|(k, v)| format!("{k:?}: {v:?}")).collect();
        args.push(format!("options={{{}}}", items.join(", ")));
    }
    format!("reset({})", args.join(", "))
}

/// One check as run by [`check_env`].
type CheckFn<E> =
    for<'h, 'a, 'o> fn(&'h mut Harness<'a, E>, &'o CheckOptions) -> Result<Outcome, Failure>;

/// What a check produced when it did not fail.
enum Outcome {
    Passed,
    Skipped(String),
}

/// The environment under test, with the calls the checks make guarded.
struct Harness<'a, E: Env> {
    env: &'a mut E,
    obs_space: AnySpace,
    act_space: AnySpace,
    warnings: Vec<Warning>,
}

impl<'a, E: Env> Harness<'a, E> {
    fn new(env: &'a mut E) -> Self {
        let obs_space = env.observation_space().to_any();
        let act_space = env.action_space().to_any();
        Self {
            env,
            obs_space,
            act_space,
            warnings: Vec::new(),
        }
    }

    fn warn(&mut self, w: Warning) {
        if !self.warnings.contains(&w) {
            self.warnings.push(w);
        }
    }

    /// Runs `f` on the environment; an `Err` or a panic becomes a failure of `check`.
    fn call<R>(
        &mut self,
        check: Check,
        what: &str,
        f: impl FnOnce(&mut E) -> gym_core::Result<R>,
    ) -> Result<R, Failure> {
        let env = &mut *self.env;
        match catch_unwind(AssertUnwindSafe(|| f(env))) {
            Ok(Ok(r)) => Ok(r),
            Ok(Err(e)) => Err(Failure::new(
                check,
                format!("`{what}` returned an error: {e}"),
            )),
            Err(p) => Err(Failure::new(
                check,
                format!("`{what}` panicked: {}", panic_message(p.as_ref())),
            )),
        }
    }

    fn validate_obs(
        &mut self,
        check: Check,
        what: &str,
        method: &str,
        obs: &Value,
    ) -> Result<(), Failure> {
        match check_obs(obs, &self.obs_space, method) {
            Ok(ws) => {
                for w in ws {
                    self.warn(w);
                }
                Ok(())
            }
            Err(f) => Err(Failure::new(
                f.check,
                format!("{} (in {check}, after `{what}`)", f.message),
            )),
        }
    }

    /// `reset`, returning the typed observation, the info and the observation as a value.
    fn reset_raw(
        &mut self,
        check: Check,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(E::Obs, Info, Value), Failure> {
        let what = reset_call(seed, options);
        let (obs, info) = self.call(check, &what, |env| env.reset(seed, options))?;
        let value = self.env.observation_space().to_value(&obs);
        self.validate_obs(check, &what, "reset", &value)?;
        Ok((obs, info, value))
    }

    fn reset(
        &mut self,
        check: Check,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Value, Info), Failure> {
        self.reset_raw(check, seed, options)
            .map(|(_, info, value)| (value, info))
    }

    /// `step`, returning the typed observation and the step with the observation as a value.
    fn step_raw(
        &mut self,
        check: Check,
        action: &E::Act,
    ) -> Result<(E::Obs, Step<Value>), Failure> {
        let what = format!(
            "step({})",
            compact(&self.env.action_space().to_value(action), 120)
        );
        let step = self.call(check, &what, |env| env.step(action))?;
        let value = self.env.observation_space().to_value(&step.observation);
        self.validate_obs(check, &what, "step", &value)?;
        check_reward(step.reward).map_err(|f| {
            Failure::new(
                f.check,
                format!("{} (in {check}, after `{what}`)", f.message),
            )
        })?;
        let Step {
            observation,
            reward,
            terminated,
            truncated,
            info,
        } = step;
        Ok((
            observation,
            Step {
                observation: value,
                reward,
                terminated,
                truncated,
                info,
            },
        ))
    }

    fn step(&mut self, check: Check, action: &E::Act) -> Result<Step<Value>, Failure> {
        self.step_raw(check, action).map(|(_, s)| s)
    }

    fn rng(&self) -> Option<EnvRng> {
        self.env.rng().cloned()
    }

    fn sample_action(&self, rng: &mut EnvRng) -> E::Act {
        self.env.action_space().sample(rng)
    }
}

/// Checks that an environment follows Gymnasium's API, as `gymnasium.utils.env_checker.check_env`
/// does, check by check and in the same order (see [`Check`] for each check):
///
/// 1. a warning when `env` is a wrapper rather than the unwrapped environment;
/// 2. [`check_space`] and [`check_space_limit`] on the action space, then on the
///    observation space (with [`CheckOptions::sb3`], SB3's space checks);
/// 3. [`Check::ResetReturnType`], [`Check::ResetSeedDeterminism`], [`Check::ResetOptions`];
/// 4. the passive checks: [`Check::ResetPassive`], [`Check::StepPassive`];
/// 5. [`Check::StepDeterminism`] (and [`Check::TruncatedAfterOneStep`]),
///    [`Check::ReturnedDataNotReused`];
/// 6. the Rust additions [`Check::InvalidAction`] and [`Check::StepAfterEnd`] (and, with
///    [`CheckOptions::sb3`], ten more steps checked for NaN and inf);
/// 7. [`Check::Render`] and [`Check::CloseTwice`] (which leaves the environment closed).
///
/// Every observation received along the way is checked ([`Check::ObservationStructure`],
/// [`Check::ObservationDtype`], [`Check::ObservationFinite`],
/// [`Check::ObservationContained`]) and every reward must be finite
/// ([`Check::RewardFinite`]). Works on any [`Env`], including [`BoxedEnv`]; on a
/// `BoxedEnv` the observation dtype is the one the environment actually returned.
///
/// # Errors
/// A [`ConformanceError`] with the first failure (all of them with
/// [`CheckOptions::keep_going`]) and the report of what ran before.
pub fn check_env<E: Env>(env: &mut E, options: &CheckOptions) -> Result<Report, ConformanceError> {
    let mut report = Report::new(
        options
            .name
            .clone()
            .unwrap_or_else(|| std::any::type_name::<E>().to_owned()),
    );
    let mut failures: Vec<Failure> = Vec::new();
    let mut h = Harness::new(env);

    if TypeId::of::<E>() != TypeId::of::<BoxedEnv>()
        && <dyn Any>::type_id(h.env.unwrapped_any()) != TypeId::of::<E>()
    {
        h.warn(Warning::new(
            WarningKind::NotUnwrapped,
            format!(
                "The environment ({}) is different from the unwrapped version. This could effect the environment checker \
                 as the environment most likely has a wrapper applied to it. We recommend using the raw environment for \
                 `check_env` using `env.unwrapped`.",
                std::any::type_name::<E>()
            ),
        ));
    }

    let mut plan: Vec<(Check, CheckFn<E>)> = vec![
        (Check::ActionSpace, run_action_space),
        (Check::ObservationSpace, run_observation_space),
    ];
    if options.sb3 {
        plan.push((Check::Sb3ActionBounds, run_sb3_spaces));
    }
    plan.extend([
        (Check::ResetReturnType, run_reset_return_type as CheckFn<E>),
        (Check::ResetSeedDeterminism, run_reset_seed_determinism),
        (Check::ResetOptions, run_reset_options),
        (Check::ResetPassive, run_reset_passive),
        (Check::StepPassive, run_step_passive),
        (Check::StepDeterminism, run_step_determinism),
        (Check::ReturnedDataNotReused, run_returned_data_not_reused),
        (Check::InvalidAction, run_invalid_actions),
        (Check::StepAfterEnd, run_step_after_end),
    ]);
    if options.sb3 {
        plan.push((Check::StepPassive, run_sb3_nan));
    }
    plan.extend([
        (Check::Render, run_render as CheckFn<E>),
        (Check::CloseTwice, run_close),
    ]);

    for (check, run) in plan {
        match run(&mut h, options) {
            Ok(Outcome::Passed) => {
                if !report.passed.contains(&check) {
                    report.passed.push(check);
                }
            }
            Ok(Outcome::Skipped(reason)) => report.skipped.push(Skipped { check, reason }),
            Err(f) => {
                failures.push(f);
                if !options.keep_going {
                    break;
                }
            }
        }
    }
    report.extend_warnings(h.warnings);
    let any_failed = |c: Check| failures.iter().any(|f| f.check == c);
    if report.passed.contains(&Check::StepPassive) {
        for c in [
            Check::ObservationStructure,
            Check::ObservationDtype,
            Check::ObservationFinite,
            Check::ObservationContained,
            Check::RewardFinite,
        ] {
            if !any_failed(c) {
                report.passed.push(c);
            }
        }
    }
    let mut failures = failures.into_iter();
    match failures.next() {
        None => Ok(report),
        Some(first) => Err(ConformanceError::new(first, failures.collect(), report)),
    }
}

/// Runs one check on its own, with its warnings. Used by the public single-check functions.
fn single<E: Env>(
    env: &mut E,
    options: &CheckOptions,
    run: CheckFn<E>,
) -> Result<Vec<Warning>, Failure> {
    let mut h = Harness::new(env);
    run(&mut h, options)?;
    Ok(h.warnings)
}

fn run_action_space<E: Env>(h: &mut Harness<'_, E>, _: &CheckOptions) -> Result<Outcome, Failure> {
    let ws = check_space(&h.act_space, SpaceType::Action)?;
    for w in ws
        .into_iter()
        .chain(check_space_limit(&h.act_space, SpaceType::Action))
    {
        h.warn(w);
    }
    Ok(Outcome::Passed)
}

fn run_observation_space<E: Env>(
    h: &mut Harness<'_, E>,
    _: &CheckOptions,
) -> Result<Outcome, Failure> {
    let ws = check_space(&h.obs_space, SpaceType::Observation)?;
    for w in ws
        .into_iter()
        .chain(check_space_limit(&h.obs_space, SpaceType::Observation))
    {
        h.warn(w);
    }
    Ok(Outcome::Passed)
}

fn run_sb3_spaces<E: Env>(h: &mut Harness<'_, E>, _: &CheckOptions) -> Result<Outcome, Failure> {
    for w in sb3_check_spaces(&h.obs_space, &h.act_space)? {
        h.warn(w);
    }
    Ok(Outcome::Passed)
}

/// Gymnasium's `check_reset_return_type`: `reset()` (no seed) returns `(obs, info)` with
/// `obs` in the observation space. In Rust the tuple and the info map are guaranteed by
/// the types, so what remains is that the call succeeds and the observation fits.
///
/// # Errors
/// [`Check::ResetReturnType`] when `reset` errors or panics; an observation check when the
/// observation does not fit its space.
pub fn check_reset_return_type<E: Env>(
    env: &mut E,
    options: &CheckOptions,
) -> Result<Vec<Warning>, Failure> {
    single(env, options, run_reset_return_type)
}

fn run_reset_return_type<E: Env>(
    h: &mut Harness<'_, E>,
    _: &CheckOptions,
) -> Result<Outcome, Failure> {
    h.reset(Check::ResetReturnType, None, None)?;
    Ok(Outcome::Passed)
}

/// Gymnasium's `check_reset_seed_determinism`: `reset(seed)`, `reset()`, `reset(seed)`,
/// `reset()`, `reset(other_seed)`.
///
/// * The environment exposes its RNG after a seeded reset (Gymnasium's assertion that
///   `env.unwrapped._np_random is not None`); see [`CheckOptions::require_rng`].
/// * Unless [`CheckOptions::nondeterministic`]: the two seeded observations are equivalent
///   (`data_equivalence`, rtol = atol = 1e-5), and so are the two unseeded ones that
///   follow them; a warning when they are only similar.
/// * The RNG state after the two seeded resets is equal.
/// * The RNG state after `reset(other_seed)` differs from that after `reset(seed)`.
///
/// # Errors
/// [`Check::ResetSeedDeterminism`], with Gymnasium's message and what differed.
pub fn check_reset_seed_determinism<E: Env>(
    env: &mut E,
    options: &CheckOptions,
) -> Result<Vec<Warning>, Failure> {
    single(env, options, run_reset_seed_determinism)
}

fn run_reset_seed_determinism<E: Env>(
    h: &mut Harness<'_, E>,
    o: &CheckOptions,
) -> Result<Outcome, Failure> {
    const C: Check = Check::ResetSeedDeterminism;
    let (seed, other) = (o.seed, o.other_seed);
    let (obs_1, _) = h.reset(C, Some(seed), None)?;
    let rng_1 = h.rng();
    if rng_1.is_none() {
        if o.require_rng {
            return Err(Failure::new(
                C,
                format!(
                    "Expects the random number generator to have been generated given a seed was passed to reset. \
                     Most likely the environment reset function does not call `super().reset(seed=seed)`. \
                     (`Env::rng()` returned None after `reset(seed={seed})`: return the environment's RNG from `rng()` so \
                     seeding can be checked, or use `CheckOptions::require_rng(false)` for an environment without randomness.)"
                ),
            ));
        }
        h.warn(Warning::new(
            WarningKind::NoRng,
            "`Env::rng()` returned None after a seeded reset; the RNG state checks of check_reset_seed_determinism \
             and check_step_determinism were skipped.",
        ));
    }
    let (obs_2, _) = h.reset(C, None, None)?;
    let (obs_3, _) = h.reset(C, Some(seed), None)?;
    let rng_3 = h.rng();
    let (obs_4, _) = h.reset(C, None, None)?;

    if !o.nondeterministic {
        if let Some(d) = value_difference(&obs_1, &obs_3, Compare::Approx) {
            return Err(Failure::new(
                C,
                format!(
                    "Using `env.reset(seed={seed})` is non-deterministic as the observations are not equivalent. \
                     First difference: {d}"
                ),
            ));
        }
        if let Some(d) = value_difference(&obs_2, &obs_4, Compare::Approx) {
            return Err(Failure::new(
                C,
                format!(
                    "Using `env.reset(seed={seed})` then `env.reset()` is non-deterministic as the observations are not \
                     equivalent. First difference: {d}"
                ),
            ));
        }
        if let Some(d) = value_difference(&obs_1, &obs_3, Compare::Exact) {
            h.warn(Warning::new(
                WarningKind::NotExactlyEqual,
                format!("Using `env.reset(seed={seed})` observations are not equal although similar. ({d})"),
            ));
        }
        if let Some(d) = value_difference(&obs_2, &obs_4, Compare::Exact) {
            h.warn(Warning::new(
                WarningKind::NotExactlyEqual,
                format!("Using `env.reset(seed={seed})` then `env.reset()` observations are not equal although similar. ({d})"),
            ));
        }
    }
    if let Some(rng_1) = &rng_1
        && rng_3.as_ref() != Some(rng_1)
    {
        let detail = if rng_3.is_none() {
            ": `rng()` returned None"
        } else {
            ""
        };
        return Err(Failure::new(
            C,
            format!(
                "Most likely the environment reset function does not call `super().reset(seed=seed)` as the random \
                 generates are not same when the same seeds are passed to `env.reset`. (The RNG state after the second \
                 `reset(seed={seed})` differs from the state after the first{detail}.)"
            ),
        ));
    }
    h.reset(C, Some(other), None)?;
    if let Some(rng_1) = &rng_1
        && h.rng().as_ref() == Some(rng_1)
    {
        return Err(Failure::new(
            C,
            format!(
                "Most likely the environment reset function does not call `super().reset(seed=seed)` as the random number \
                 generators are not different when different seeds are passed to `env.reset`. (`reset(seed={other})` left \
                 the RNG in the state `reset(seed={seed})` did.)"
            ),
        ));
    }
    Ok(Outcome::Passed)
}

/// Gymnasium's `check_reset_options`: `reset(options={})` succeeds; then each of
/// [`CheckOptions::reset_options_probes`] resets with its options (and the check seed) and
/// must see them honoured.
///
/// # Errors
/// [`Check::ResetOptions`] when a reset with options errors or panics, or a probe sees its
/// option ignored.
pub fn check_reset_options<E: Env>(
    env: &mut E,
    options: &CheckOptions,
) -> Result<Vec<Warning>, Failure> {
    single(env, options, run_reset_options)
}

fn run_reset_options<E: Env>(h: &mut Harness<'_, E>, o: &CheckOptions) -> Result<Outcome, Failure> {
    const C: Check = Check::ResetOptions;
    h.reset(C, None, Some(&ResetOptions::new())).map_err(|f| {
        if f.check == C {
            Failure::new(
                C,
                format!("The environment cannot be reset with options, even though `reset` takes `options`. {}", f.message),
            )
        } else {
            f
        }
    })?;
    for probe in &o.reset_options_probes {
        let (obs, info) = h.reset(C, Some(o.seed), Some(&probe.options))?;
        let call = reset_call(Some(o.seed), Some(&probe.options));
        let verdict = catch_unwind(AssertUnwindSafe(|| (probe.expect)(&obs, &info)))
            .unwrap_or_else(|p| Err(format!("the probe panicked: {}", panic_message(p.as_ref()))));
        if let Err(m) = verdict {
            return Err(Failure::new(
                C,
                format!(
                    "The reset option `{}` was not honoured by `{call}`: {m}",
                    probe.name
                ),
            ));
        }
    }
    Ok(Outcome::Passed)
}

/// Gymnasium's `env_reset_passive_checker`: a plain `reset()`, whose observation is checked
/// by [`check_obs`] (Gymnasium only warns about an observation outside the space here; the
/// observation checks of this crate fail).
///
/// # Errors
/// [`Check::ResetPassive`] when `reset` errors or panics; an observation check otherwise.
pub fn env_reset_passive_checker<E: Env>(
    env: &mut E,
    options: &CheckOptions,
) -> Result<Vec<Warning>, Failure> {
    single(env, options, run_reset_passive)
}

fn run_reset_passive<E: Env>(h: &mut Harness<'_, E>, _: &CheckOptions) -> Result<Outcome, Failure> {
    h.reset(Check::ResetPassive, None, None)?;
    Ok(Outcome::Passed)
}

/// Gymnasium's `env_step_passive_checker`: one `step` with a sampled action (the action
/// sampler is seeded with [`CheckOptions::seed`] so a failure replays); the observation is
/// checked and the reward must be finite. Call it after a reset.
///
/// # Errors
/// [`Check::StepPassive`] when `step` errors or panics; [`Check::RewardFinite`] for a NaN or
/// infinite reward; an observation check otherwise.
pub fn env_step_passive_checker<E: Env>(
    env: &mut E,
    options: &CheckOptions,
) -> Result<Vec<Warning>, Failure> {
    single(env, options, run_step_passive)
}

fn run_step_passive<E: Env>(h: &mut Harness<'_, E>, o: &CheckOptions) -> Result<Outcome, Failure> {
    let action = h.sample_action(&mut rng_from_seed(o.seed.wrapping_add(1)));
    let _ = h.step(Check::StepPassive, &action)?;
    Ok(Outcome::Passed)
}

/// Gymnasium's `check_step_determinism`: the action sampler seeded with
/// [`CheckOptions::seed`] gives one action; `reset(seed)` then `step(action)`, twice.
///
/// * The RNG state after the two steps is equal ("The `.np_random` is not properly been
///   updated after step.").
/// * The observations are equivalent (a warning when only similar), the rewards equal,
///   `terminated` equal, the infos equivalent (a warning when only similar).
/// * `truncated` is false after one step ([`Check::TruncatedAfterOneStep`]).
///
/// Skipped with [`CheckOptions::nondeterministic`].
///
/// # Errors
/// [`Check::StepDeterminism`] or [`Check::TruncatedAfterOneStep`].
pub fn check_step_determinism<E: Env>(
    env: &mut E,
    options: &CheckOptions,
) -> Result<Vec<Warning>, Failure> {
    single(env, options, run_step_determinism)
}

fn run_step_determinism<E: Env>(
    h: &mut Harness<'_, E>,
    o: &CheckOptions,
) -> Result<Outcome, Failure> {
    const C: Check = Check::StepDeterminism;
    if o.nondeterministic {
        return Ok(Outcome::Skipped(
            "the environment is declared nondeterministic".into(),
        ));
    }
    let action = h.sample_action(&mut rng_from_seed(o.seed));
    h.reset(C, Some(o.seed), None)?;
    let s0 = h.step(C, &action)?;
    let rng_0 = h.rng();
    h.reset(C, Some(o.seed), None)?;
    let s1 = h.step(C, &action)?;
    if rng_0.is_some() && h.rng() != rng_0 {
        return Err(Failure::new(
            C,
            format!(
                "The `.np_random` is not properly been updated after step. (After `reset(seed={})` and the same action, \
                 the RNG state differs between the two runs.)",
                o.seed
            ),
        ));
    }
    let same = |what: &str, d: Option<String>| match d {
        Some(d) => Err(Failure::new(
            C,
            format!(
                "Deterministic step {what} are not equivalent for the same seed and action. First difference: {d}"
            ),
        )),
        None => Ok(()),
    };
    same(
        "observations",
        value_difference(&s0.observation, &s1.observation, Compare::Approx),
    )?;
    if let Some(d) = value_difference(&s0.observation, &s1.observation, Compare::Exact) {
        h.warn(Warning::new(
            WarningKind::NotExactlyEqual,
            format!("Step observations are not equal although similar given the same seed and action ({d})"),
        ));
    }
    same(
        "rewards",
        (s0.reward != s1.reward).then(|| format!("{} vs {}", s0.reward, s1.reward)),
    )?;
    same(
        "termination",
        (s0.terminated != s1.terminated).then(|| format!("{} vs {}", s0.terminated, s1.terminated)),
    )?;
    if s0.truncated || s1.truncated {
        return Err(Failure::new(
            Check::TruncatedAfterOneStep,
            format!(
                "Environment truncates after 1 step, something has gone very wrong. (`truncated` was {} and {} after \
                 `reset(seed={})` and one step.)",
                s0.truncated, s1.truncated, o.seed
            ),
        ));
    }
    same("info", info_difference(&s0.info, &s1.info, Compare::Approx))?;
    if let Some(d) = info_difference(&s0.info, &s1.info, Compare::Exact) {
        h.warn(Warning::new(
            WarningKind::NotExactlyEqual,
            format!(
                "Step info are not equal although similar given the same seed and action ({d})"
            ),
        ));
    }
    Ok(Outcome::Passed)
}

/// Gymnasium's `check_returned_data_not_reused`: `reset(seed)`, up to two steps with sampled
/// actions (stopping at the end of the episode), `reset(seed)`; no two returned
/// observations may share data.
///
/// In Rust an observation is an owned value, and `gym_core::Value`, `ArrayD` and `Info`
/// cannot alias the environment's buffers, so Gymnasium's `np.shares_memory` question is
/// answered by the types for them. What remains possible is an observation type with
/// shared interior mutability (an `Arc<Mutex<_>>` the environment keeps writing into).
/// The check catches that: each observation is copied into a [`Value`] when it is
/// returned, and after all calls every observation still held must be bit-identical to
/// its copy.
///
/// # Errors
/// [`Check::ReturnedDataNotReused`] naming the observation that changed.
pub fn check_returned_data_not_reused<E: Env>(
    env: &mut E,
    options: &CheckOptions,
) -> Result<Vec<Warning>, Failure> {
    single(env, options, run_returned_data_not_reused)
}

fn run_returned_data_not_reused<E: Env>(
    h: &mut Harness<'_, E>,
    o: &CheckOptions,
) -> Result<Outcome, Failure> {
    const C: Check = Check::ReturnedDataNotReused;
    let mut rng = rng_from_seed(o.seed);
    let mut held: Vec<(String, E::Obs, Value)> = Vec::new();
    let (obs, _, value) = h.reset_raw(C, Some(o.seed), None)?;
    held.push((format!("reset(seed={})", o.seed), obs, value));
    for i in 1..=2 {
        let action = h.sample_action(&mut rng);
        let (obs, step) = h.step_raw(C, &action)?;
        let done = step.done();
        held.push((format!("step {i}"), obs, step.observation));
        if done {
            break;
        }
    }
    let (obs, _, value) = h.reset_raw(C, Some(o.seed), None)?;
    held.push((format!("the second reset(seed={})", o.seed), obs, value));
    let space = h.env.observation_space();
    for (label, obs, snapshot) in &held {
        if let Some(d) = value_difference(&space.to_value(obs), snapshot, Compare::Bits) {
            return Err(Failure::new(
                C,
                format!(
                    "The observation returned by {label} changed after later calls to the environment ({d}): it shares \
                     data with the environment or with other observations. Each call must return new observation data."
                ),
            ));
        }
    }
    Ok(Outcome::Passed)
}

/// Rust addition: actions outside the action space give a typed error and leave the
/// environment usable and unchanged.
///
/// With the action sampler seeded by [`CheckOptions::seed`], a valid action `a` is drawn
/// and `reset(seed)`, `step(a)` recorded. For each invalid action derived from `a` (see
/// [`invalid_actions`]: NaN, ±inf, wrong lengths, out-of-range discrete values): `reset(seed)`,
/// `step(invalid)` must return `gym_core::Error::InvalidAction` (not succeed, not panic, not
/// another error), then `step(a)` must succeed and, unless
/// [`CheckOptions::nondeterministic`], be bit-identical to the recorded step.
///
/// Skipped when the action type cannot express any action outside the space.
///
/// # Errors
/// [`Check::InvalidAction`] naming the invalid action and what happened.
pub fn check_invalid_actions<E: Env>(
    env: &mut E,
    options: &CheckOptions,
) -> Result<Vec<Warning>, Failure> {
    single(env, options, run_invalid_actions)
}

fn run_invalid_actions<E: Env>(
    h: &mut Harness<'_, E>,
    o: &CheckOptions,
) -> Result<Outcome, Failure> {
    const C: Check = Check::InvalidAction;
    if !o.check_invalid_actions {
        return Ok(Outcome::Skipped(
            "disabled by CheckOptions::check_invalid_actions".into(),
        ));
    }
    let base = h.sample_action(&mut rng_from_seed(o.seed));
    let candidates = invalid_actions(
        h.env.action_space(),
        &base,
        o.out_of_bounds_actions_invalid,
        8,
    );
    if candidates.is_empty() {
        return Ok(Outcome::Skipped(
            "the action type cannot express an action outside the action space".into(),
        ));
    }
    h.reset(C, Some(o.seed), None)?;
    let reference = h.step(C, &base)?;
    for bad in candidates {
        h.reset(C, Some(o.seed), None)?;
        let env = &mut *h.env;
        let result = catch_unwind(AssertUnwindSafe(|| env.step(&bad.action)));
        let label = &bad.label;
        match result {
            Ok(Err(gym_core::Error::InvalidAction(_))) => {}
            Ok(Err(e)) => {
                return Err(Failure::new(
                    C,
                    format!(
                        "`step` with an action outside the action space ({label}) returned `{e}`; expected \
                         gym_core::Error::InvalidAction"
                    ),
                ));
            }
            Ok(Ok(_)) => {
                return Err(Failure::new(
                    C,
                    format!(
                        "`step` accepted an action outside the action space ({label}): {}; it must return \
                         gym_core::Error::InvalidAction",
                        compact(&h.env.action_space().to_value(&bad.action), 160)
                    ),
                ));
            }
            Err(p) => {
                return Err(Failure::new(
                    C,
                    format!(
                        "`step` panicked on an action outside the action space ({label}): {}; invalid actions must be a \
                         typed error (gym_core::Error::InvalidAction), never a panic",
                        panic_message(p.as_ref())
                    ),
                ));
            }
        }
        let after = h.step(C, &base).map_err(|f| {
            Failure::new(
                f.check,
                format!(
                    "the environment is not usable after rejecting an invalid action ({label}): {}",
                    f.message
                ),
            )
        })?;
        if !o.nondeterministic
            && let Some(d) = step_difference(&reference, &after, Compare::Bits)
        {
            return Err(Failure::new(
                C,
                format!(
                    "after rejecting the action ({label}), the next valid step differs from a replay without it: {d}. A \
                     rejected action must leave the environment untouched."
                ),
            ));
        }
    }
    Ok(Outcome::Passed)
}

/// Rust addition: after an episode ends, `step` is refused until `reset`.
///
/// `reset(seed)`, then steps with sampled actions until `terminated || truncated` (at most
/// [`CheckOptions::max_episode_steps`]; skipped if the episode is longer); one more `step`
/// must return `gym_core::Error::EpisodeEnded` (or `Error::ResetNeeded`), or succeed while
/// still reporting the episode as ended (Gymnasium's `TimeLimit` keeps forcing `truncated`
/// past its limit; [`CheckOptions::strict_step_after_end`] refuses this); then `reset` and
/// `step` must work again. What is caught is an environment that silently carries on (or
/// starts a new episode) without a reset.
///
/// # Errors
/// [`Check::StepAfterEnd`] when the extra step is accepted as a running episode, panics or
/// returns another error.
pub fn check_step_after_end<E: Env>(
    env: &mut E,
    options: &CheckOptions,
) -> Result<Vec<Warning>, Failure> {
    single(env, options, run_step_after_end)
}

fn run_step_after_end<E: Env>(
    h: &mut Harness<'_, E>,
    o: &CheckOptions,
) -> Result<Outcome, Failure> {
    const C: Check = Check::StepAfterEnd;
    if !o.check_step_after_end {
        return Ok(Outcome::Skipped(
            "disabled by CheckOptions::check_step_after_end".into(),
        ));
    }
    let mut rng = rng_from_seed(o.seed);
    h.reset(C, Some(o.seed), None)?;
    let mut end = None;
    for t in 1..=o.max_episode_steps {
        let action = h.sample_action(&mut rng);
        let s = h.step(C, &action)?;
        if s.done() {
            end = Some((t, s.terminated, s.truncated));
            break;
        }
    }
    let Some((t, terminated, truncated)) = end else {
        return Ok(Outcome::Skipped(format!(
            "the episode did not end within {} steps",
            o.max_episode_steps
        )));
    };
    let action = h.sample_action(&mut rng);
    let env = &mut *h.env;
    let ended =
        format!("the episode ended at step {t} (terminated={terminated}, truncated={truncated})");
    match catch_unwind(AssertUnwindSafe(|| env.step(&action))) {
        Ok(Err(gym_core::Error::EpisodeEnded | gym_core::Error::ResetNeeded)) => {}
        Ok(Err(e)) => {
            return Err(Failure::new(
                C,
                format!(
                    "`step` after {ended} returned `{e}`; expected gym_core::Error::EpisodeEnded"
                ),
            ));
        }
        Ok(Ok(s)) if s.done() && !o.strict_step_after_end => {}
        Ok(Ok(s)) => {
            let how = if s.done() {
                "was accepted (CheckOptions::strict_step_after_end requires an error)".to_owned()
            } else {
                format!(
                    "was accepted and reported the episode as running (terminated={}, truncated={})",
                    s.terminated, s.truncated
                )
            };
            return Err(Failure::new(
                C,
                format!(
                    "`step` after {ended} {how}; it must return gym_core::Error::EpisodeEnded until `reset()` (or, as \
                     Gymnasium's TimeLimit does past its limit, keep reporting the episode as ended)"
                ),
            ));
        }
        Err(p) => {
            return Err(Failure::new(
                C,
                format!(
                    "`step` after {ended} panicked: {}; it must return gym_core::Error::EpisodeEnded",
                    panic_message(p.as_ref())
                ),
            ));
        }
    }
    h.reset(C, Some(o.seed), None)?;
    let action = h.sample_action(&mut rng);
    let _ = h.step(C, &action)?;
    Ok(Outcome::Passed)
}

/// SB3's `_check_nan`: `reset()` then ten steps with sampled actions, every observation and
/// reward checked (NaN and inf are failures here, warnings in SB3).
fn run_sb3_nan<E: Env>(h: &mut Harness<'_, E>, o: &CheckOptions) -> Result<Outcome, Failure> {
    let mut rng = rng_from_seed(o.seed.wrapping_add(2));
    h.reset(Check::StepPassive, None, None)?;
    for _ in 0..10 {
        let action = h.sample_action(&mut rng);
        if h.step(Check::StepPassive, &action)?.done() {
            h.reset(Check::StepPassive, None, None)?;
        }
    }
    Ok(Outcome::Passed)
}

/// Gymnasium's `env_render_passive_checker` (and `check_env`'s render part).
///
/// * With render modes declared: a warning without `render_fps`; `render_fps` must be
///   `> 0`.
/// * Without render modes, `render_mode()` must be `None` ("With no render_modes, expects
///   the Env.render_mode to be None"); otherwise it must be `None` or a declared mode.
/// * With a render mode: after `reset(seed)`, `render()` must succeed; a warning when its
///   result does not fit the mode (`human`: nothing; `rgb_array`: an RGB frame with 3
///   channels; `depth_array`: a depth frame; `ansi`: text).
/// * A warning that the other declared modes were not tried (making the environment in
///   another mode needs a factory; Gymnasium uses the spec).
///
/// Gymnasium runs the metadata checks only when a render mode is set; here they always run.
///
/// # Errors
/// [`Check::Render`].
pub fn env_render_passive_checker<E: Env>(
    env: &mut E,
    options: &CheckOptions,
) -> Result<Vec<Warning>, Failure> {
    single(env, options, run_render)
}

fn run_render<E: Env>(h: &mut Harness<'_, E>, o: &CheckOptions) -> Result<Outcome, Failure> {
    const C: Check = Check::Render;
    if o.skip_render_check {
        return Ok(Outcome::Skipped("skip_render_check".into()));
    }
    let metadata = h.env.metadata().clone();
    let mode = h.env.render_mode();
    let modes = &metadata.render_modes;
    let names: Vec<&str> = modes.iter().map(|m| m.as_str()).collect();
    for w in check_render_metadata(&metadata, mode)? {
        h.warn(w);
    }
    if let Some(m) = mode {
        h.reset(C, Some(o.seed), None)?;
        let frame = h.call(C, "render()", |env| env.render())?;
        if let Some(w) = check_render_return(m, frame.as_ref()) {
            h.warn(w);
        }
    }
    if modes.iter().any(|m| Some(*m) != mode) {
        h.warn(Warning::new(
            WarningKind::AlternativeRenderModesNotTested,
            format!(
                "Not able to test alternative render modes ({names:?}) due to the environment not having a spec: \
                 check an environment made in each render mode to cover them."
            ),
        ));
    }
    Ok(Outcome::Passed)
}

/// `check_env`'s close check: `close()` twice. Gymnasium warns when the second close raises;
/// here a panic in either is a failure, as `Env::close` is documented idempotent. The
/// environment is closed afterwards.
///
/// # Errors
/// [`Check::CloseTwice`].
pub fn check_close<E: Env>(env: &mut E, options: &CheckOptions) -> Result<Vec<Warning>, Failure> {
    single(env, options, run_close)
}

fn run_close<E: Env>(h: &mut Harness<'_, E>, o: &CheckOptions) -> Result<Outcome, Failure> {
    const C: Check = Check::CloseTwice;
    if o.skip_close_check {
        return Ok(Outcome::Skipped("skip_close_check".into()));
    }
    for (i, what) in [
        "Calling `env.close()`",
        "Calling `env.close()` on the closed environment",
    ]
    .iter()
    .enumerate()
    {
        let env = &mut *h.env;
        if let Err(p) = catch_unwind(AssertUnwindSafe(|| env.close())) {
            let tail = if i == 1 {
                " should be allowed, but it panicked"
            } else {
                " panicked"
            };
            return Err(Failure::new(
                C,
                format!("{what}{tail}: {}", panic_message(p.as_ref())),
            ));
        }
    }
    Ok(Outcome::Passed)
}
