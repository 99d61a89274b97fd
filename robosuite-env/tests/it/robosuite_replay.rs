//! robosuite-rs against robosuite 1.5.2 itself: the recorded scenes, rollouts and
//! placements of `tests/fixtures/robosuite` (see `scripts/record_robosuite.py`).
//!
//! Tolerances (MuJoCo 3.17.0 here, 3.3.7 in the recording): robot joints and grip site in
//! free motion within 1e-5 (rad / m); every position within 2 mm over the rollout once the
//! robot touches something, and objects (which rest and slide on tables) within 2 mm
//! throughout; success equal at every step but where the recorded success changes, whose
//! crossing may come one step earlier or later (at most one differing step per change, its
//! reward left out); rewards within 1e-3. Where robosuite itself,
//! run on MuJoCo 3.17.0, already differs from its 3.3.7 recording by more (the rollout's
//! `floor`, `scripts/mujoco_floor.py`), the tolerance is that floor plus 10 %: the part of
//! the difference MuJoCo's version causes is not robosuite-rs's to remove.

use crate::common::fixtures::{env_for, load, recorded_tasks, replay};
use gym_core::Env;
use mujoco_rs::wrappers::mj_model::MjtObjBase as Obj;

const FREE_ARM_TOL: f64 = 1e-5;
const CONTACT_TOL: f64 = 2e-3;
const REWARD_TOL: f64 = 1e-3;

#[test]
fn every_registered_task_has_a_fixture() {
    let recorded = recorded_tasks();
    for name in robosuite_env::ENV_NAMES {
        assert!(
            recorded.iter().any(|r| r == name),
            "{name} has no recording"
        );
    }
}

#[test]
fn scene_names_and_counts_equal_robosuites() {
    for task in recorded_tasks() {
        let fixture = load(&task);
        let env = env_for(&fixture);
        let m = env.sim().model();
        let f = m.ffi();
        let ours = [
            ("nq", f.nq),
            ("nv", f.nv),
            ("nu", f.nu),
            ("nbody", f.nbody),
            ("njnt", f.njnt),
            ("ngeom", f.ngeom),
            ("nsite", f.nsite),
            ("nmesh", f.nmesh),
            ("nsensor", f.nsensor),
            ("ncam", f.ncam),
        ];
        for (k, v) in ours {
            assert_eq!(v, fixture.counts[k], "{task}: {k}");
        }
        for (kind, obj) in [
            ("body", Obj::mjOBJ_BODY),
            ("joint", Obj::mjOBJ_JOINT),
            ("geom", Obj::mjOBJ_GEOM),
            ("site", Obj::mjOBJ_SITE),
            ("actuator", Obj::mjOBJ_ACTUATOR),
            ("sensor", Obj::mjOBJ_SENSOR),
            ("camera", Obj::mjOBJ_CAMERA),
            ("mesh", Obj::mjOBJ_MESH),
        ] {
            let want = &fixture.names[kind];
            let got: Vec<String> = (0..want.len())
                .map(|i| m.id_to_name(obj, i).unwrap_or("").to_owned())
                .collect();
            assert_eq!(&got, want, "{task}: {kind} names");
        }
    }
}

#[test]
fn rollouts_replay_within_tolerance() {
    for task in recorded_tasks() {
        let fixture = load(&task);
        let mut env = env_for(&fixture);
        for rollout in &fixture.rollouts {
            let e = replay(&mut env, rollout);
            let what = format!("{task} {} rollout: {e:?}", rollout.kind);
            println!("{what}");
            if std::env::var_os("REPLAY_REPORT").is_some() {
                continue;
            }
            let floor = rollout.floor.unwrap_or_default();
            let tol = |base: f64, floor: f64| base.max(1.1 * floor);
            assert_eq!(e.steps, rollout.steps.len(), "{what}");
            assert!(e.free_arm <= tol(FREE_ARM_TOL, floor.free_arm), "{what}");
            assert!(
                e.contact_arm <= tol(CONTACT_TOL, floor.contact_arm),
                "{what}"
            );
            assert!(e.objects <= tol(CONTACT_TOL, floor.objects), "{what}");
            assert!(e.success_mismatches <= floor.success_mismatches, "{what}");
            assert!(e.success_shifts <= e.success_changes, "{what}");
            assert!(e.reward <= tol(REWARD_TOL, floor.reward), "{what}");
        }
    }
}

#[test]
fn placement_ranges_equal_robosuites() {
    for task in recorded_tasks() {
        let fixture = load(&task);
        let mut env = env_for(&fixture);
        let n = fixture.placement.resets;
        // One pass over the seeds, every body's extent drawn from the same resets.
        let bodies: Vec<(&String, usize)> = fixture
            .placement
            .bodies
            .keys()
            .map(|object| {
                let body = robosuite_env::sim::body_id(env.sim().model(), object)
                    .unwrap_or_else(|e| panic!("{task}: {e}"));
                (object, body)
            })
            .collect();
        let mut seen = vec![([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]); bodies.len()];
        for seed in 0..n as u64 {
            env.reset(Some(seed), None).unwrap();
            for ((_, body), (lo, hi)) in bodies.iter().zip(&mut seen) {
                let p = env.sim().data().xpos()[*body];
                for i in 0..3 {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
        }
        for ((object, _), (lo, hi)) in bodies.iter().zip(&seen) {
            let want = &fixture.placement.bodies[*object];
            for i in 0..3 {
                // n uniform draws fall short of a bound by about range / n; allow 5 %.
                let range = want.max[i] - want.min[i];
                let tol = 0.05 * range + 1e-9;
                assert!(
                    (lo[i] - want.min[i]).abs() <= tol && (hi[i] - want.max[i]).abs() <= tol,
                    "{task} {object} axis {i}: ours [{}, {}], robosuite [{}, {}]",
                    lo[i],
                    hi[i],
                    want.min[i],
                    want.max[i]
                );
            }
        }
    }
}
