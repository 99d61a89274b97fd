//! ToolHang: model, observations, placement and the success check on a hand-set state.

mod common;

use common::get;
use gym_core::{DType, Env};
use robosuite_env::sim::{body_id, geom_id, site_id};
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};

fn tool_hang() -> RobosuiteEnv {
    make_with("ToolHang", EnvConfig::default().with_horizon(200)).unwrap()
}

#[test]
fn tool_hang_sizes_and_observations_match_robosuite() {
    let mut env = tool_hang();
    let m = env.sim().model().ffi();
    assert_eq!((m.nq, m.nv, m.nu), (30, 27, 9));
    let (obs, _) = env.reset(Some(0), None).unwrap();
    let keys = env.observation_keys();
    let expected: Vec<String> = ["base", "frame", "tool"]
        .iter()
        .flat_map(|n| {
            [
                format!("{n}_to_robot0_eef_pos"),
                format!("{n}_to_robot0_eef_quat"),
                format!("{n}_pos"),
                format!("{n}_quat"),
            ]
        })
        .chain(["frame_is_assembled".to_owned(), "tool_on_frame".to_owned()])
        .collect();
    assert_eq!(&keys[10..24], &expected[..]);
    assert_eq!(get(&obs, "object-state").len(), 44);
    assert_eq!(
        obs.get("tool_quat").unwrap().as_array().unwrap().dtype(),
        DType::F32
    );
    assert_eq!(get(&obs, "frame_is_assembled"), [0.0]);
    assert_eq!(get(&obs, "tool_on_frame"), [0.0]);
}

#[test]
fn objects_are_placed_in_their_ranges_and_settle() {
    let mut env = tool_hang();
    for seed in 0..3 {
        let (obs, _) = env.reset(Some(seed), None).unwrap();
        let base = get(&obs, "base_pos");
        assert!(
            (base[0] + 0.08).abs() < 1e-9 && base[1].abs() < 1e-9,
            "{base:?}"
        );
        let tool = get(&obs, "tool_pos");
        assert!((tool[0] - 0.04).abs() <= 0.02 + 1e-9 && (tool[1] + 0.2).abs() <= 0.02 + 1e-9);
        for _ in 0..20 {
            let step = env.step(&common::zero()).unwrap();
            assert!(!step.terminated);
        }
        let obs = env.observation();
        // Everything rests on the table: the stand base plate, the flat frame, the tool.
        assert!(
            (get(&obs, "base_pos")[2] - 0.805).abs() < 0.003,
            "{:?}",
            get(&obs, "base_pos")
        );
        let frame = get(&obs, "frame_pos");
        assert!(frame[2] > 0.8 && frame[2] < 0.83, "{frame:?}");
        let tool = get(&obs, "tool_pos");
        assert!(tool[2] > 0.8 && tool[2] < 0.83, "{tool:?}");
        assert!(!env.check_success());
    }
}

#[test]
fn frame_in_the_stand_with_the_tool_on_the_hook_is_a_success() {
    let mut env = tool_hang();
    env.reset(Some(0), None).unwrap();
    let model = env.sim().model();
    let (stand_q, frame_q, tool_q) = (1 + 9, 1 + 16, 1 + 23);
    let _ = (
        body_id(model, "stand_main"),
        geom_id(model, "stand_base"),
        site_id(model, "tool_hole1_center"),
    );
    let mut s = env.get_state();
    // The stand upright at (−0.08, 0), its cavity at y + 0.045, its plate top at 0.811.
    let (sx, sy) = (-0.08, 0.0);
    s[stand_q..stand_q + 7].copy_from_slice(&[sx, sy, 0.881, 1.0, 0.0, 0.0, 0.0]);
    // The frame upright with its rod in the cavity, its tip on the plate.
    let rod_x = (0.095 - 0.0075) / 2.0;
    let fz = 0.811 + 0.09 + 0.0508 + 0.0005;
    let (fx, fy) = (sx - rod_x, sy + 0.045);
    s[frame_q..frame_q + 7].copy_from_slice(&[fx, fy, fz, 1.0, 0.0, 0.0, 0.0]);
    // The wrench hanging from the bar by hole 1 (ring axis along the bar, handle down):
    // a quarter turn about y; hole 1's top box rests on the bar.
    let bar_z = fz + (0.18 - 0.0075) / 2.0;
    let hang_x = fx - 0.095 / 2.0;
    let hole_x = hang_x + 0.3 * (rod_x + 0.095 / 2.0);
    let hole_z = bar_z + 0.00375 - 0.0105 * (std::f64::consts::PI / 8.0).cos() - 0.0002;
    // hole 1 sits at x1 along the tool's own x axis, which now points down.
    let unit = (0.0175 - 0.0105) * (std::f64::consts::PI / 8.0).cos() / 2.0;
    let x1 = -0.0825 - 0.0175 + 2.0 * unit;
    let h = std::f64::consts::FRAC_1_SQRT_2;
    s[tool_q..tool_q + 7].copy_from_slice(&[hole_x, fy, hole_z + x1, h, 0.0, h, 0.0]);
    env.set_state(&s).unwrap();
    let obs = env.observation();
    assert_eq!(get(&obs, "frame_is_assembled"), [1.0]);
    assert_eq!(get(&obs, "tool_on_frame"), [1.0]);
    assert!(env.check_success());
    assert_eq!(env.reward(), 1.0);

    // Without the tool touching the bar (lowered by 1 cm) it is not hung.
    let mut low = s.clone();
    low[tool_q + 2] -= 0.01;
    env.set_state(&low).unwrap();
    assert!(!env.check_success());
    // With the frame lifted out of the stand it is not assembled.
    let mut out = s.clone();
    out[frame_q + 2] += 0.1;
    env.set_state(&out).unwrap();
    assert_eq!(get(&env.observation(), "frame_is_assembled"), [0.0]);
}
