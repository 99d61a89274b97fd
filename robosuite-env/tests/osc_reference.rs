//! The OSC_POSE torques against an independent dense computation from MuJoCo's own
//! Jacobian, mass matrix and bias forces (nalgebra `DMatrix`, LU inverse, SVD
//! pseudo-inverse), and hand-derived cases.

use gym_core::{Env, Space};
use nalgebra::{DMatrix, DVector, Matrix3, Rotation3, Vector3};
use robosuite_env::controllers::{ArmBinding, ArmController, OscConfig, OscPose};
use robosuite_env::sim::Sim;
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};

/// robosuite's OSC_POSE law, written out densely from the paper formulas.
fn reference_torques(sim: &Sim, osc: &OscPose) -> Vec<f64> {
    let bind = osc.binding();
    let d = sim.data();
    let nv = sim.model().ffi().nv as usize;
    let (jacp, jacr) = d.jac_site(true, true, bind.site);
    let mut full = vec![0.0; nv * nv];
    d.full_m(&mut full).unwrap();
    let jp_full = DMatrix::from_row_slice(3, nv, &jacp);
    let jr_full = DMatrix::from_row_slice(3, nv, &jacr);
    let qvel = DVector::from_column_slice(d.qvel());
    let v = &jp_full * &qvel;
    let w = &jr_full * &qvel;
    let cols = &bind.dofs;
    let mut j = DMatrix::zeros(6, 7);
    let mut m = DMatrix::zeros(7, 7);
    for c in 0..7 {
        for r in 0..3 {
            j[(r, c)] = jp_full[(r, cols[c])];
            j[(r + 3, c)] = jr_full[(r, cols[c])];
        }
        for r in 0..7 {
            m[(r, c)] = full[cols[r] * nv + cols[c]];
        }
    }
    let q = DVector::from_iterator(7, bind.qpos.iter().map(|&a| d.qpos()[a]));
    let qd = DVector::from_iterator(7, cols.iter().map(|&a| d.qvel()[a]));
    let h = DVector::from_iterator(7, cols.iter().map(|&a| d.qfrc_bias()[a]));

    let pos = |s: usize| Vector3::from(d.site_xpos()[s]);
    let rot = |s: usize| Matrix3::from_row_slice(&d.site_xmat()[s]);
    let (p_b, r_b, x, r) = (
        pos(bind.base_site),
        rot(bind.base_site),
        pos(bind.site),
        rot(bind.site),
    );
    let x_d = p_b + r_b * osc.goal_pos();
    let r_d = r_b * osc.goal_ori();
    let e_p = x_d - x;
    // 0.5 Σ current_i × desired_i
    let e_o = 0.5
        * (0..3)
            .map(|i| r.column(i).cross(&r_d.column(i)))
            .fold(Vector3::zeros(), |a, b| a + b);
    let cfg = osc.config();
    let kd = cfg.kd();
    let f = Vector3::from_fn(|i, _| cfg.kp[i] * e_p[i] - kd[i] * v[i]);
    let t = Vector3::from_fn(|i, _| cfg.kp[3 + i] * e_o[i] - kd[3 + i] * w[i]);

    let m_inv = m.clone().lu().try_inverse().unwrap();
    let pinv = |a: DMatrix<f64>| {
        let s = a.clone().svd(true, true);
        let cutoff = 1e-15 * s.singular_values.max();
        s.pseudo_inverse(cutoff).unwrap()
    };
    let jpos = j.rows(0, 3).into_owned();
    let jori = j.rows(3, 3).into_owned();
    let lambda = pinv(&j * &m_inv * j.transpose());
    let lambda_p = pinv(&jpos * &m_inv * jpos.transpose());
    let lambda_o = pinv(&jori * &m_inv * jori.transpose());
    let fp = &lambda_p * DVector::from_column_slice(f.as_slice());
    let fo = &lambda_o * DVector::from_column_slice(t.as_slice());
    let wrench = DVector::from_iterator(6, fp.iter().chain(fo.iter()).copied());
    let mut tau = j.transpose() * wrench + h;
    let n = DMatrix::identity(7, 7) - &m_inv * j.transpose() * &lambda * &j;
    let q0 = DVector::from_column_slice(osc.initial_joints());
    let kn = cfg.nullspace_kp;
    tau += n.transpose() * (&m * ((q0 - q) * kn - qd * (2.0 * kn.sqrt())));
    tau.iter().copied().collect()
}

/// A fresh `OSC_POSE` controller for robot 0's arm of `env`, based on `sim`'s state.
fn osc_of(env: &RobosuiteEnv, sim: &Sim) -> OscPose {
    let robot = &env.robots()[0];
    let arm = robot.arm();
    let model = env.sim().model();
    let bind = ArmBinding {
        site: arm.eef_site(),
        base_site: robosuite_env::sim::site_id(model, "robot0_right_center").unwrap(),
        qpos: robot.joint_qpos()[arm.joints()].to_vec(),
        dofs: robot.joint_dofs()[arm.joints()].to_vec(),
        nv: model.ffi().nv as usize,
    };
    let mut osc = OscPose::new(OscConfig::default(), bind).unwrap();
    osc.reset(sim);
    osc
}

/// The torques the controller computes for `sim`'s state (before clipping).
fn torques(osc: &mut OscPose, sim: &Sim) -> Vec<f64> {
    let mut tau = vec![0.0; osc.binding().dofs.len()];
    osc.compute(sim, &mut tau);
    tau
}

#[test]
fn osc_torques_match_an_independent_dense_computation() {
    let mut env = make_with("Lift", EnvConfig::default()).unwrap();
    let mut rng = gym_core::rng_from_seed(4);
    let mut checked = 0;
    for seed in 0..3 {
        env.reset(Some(seed), None).unwrap();
        for k in 0..30 {
            let a = env.action_space().sample(&mut rng);
            let _ = env.step(&a).unwrap();
            if k % 6 != 5 {
                continue;
            }
            // A fixed state: the env's, forwarded (what mj_step1 computes for the controller).
            let mut sim = Sim::new(env.sim().model().clone()).unwrap();
            sim.set_state(&env.get_state()).unwrap();
            let mut osc = osc_of(&env, &sim);
            let input: Vec<f64> = env
                .action_space()
                .sample(&mut rng)
                .iter()
                .copied()
                .collect();
            osc.set_goal(&sim, &input[..6]);
            let ours = torques(&mut osc, &sim);
            let reference = reference_torques(&sim, &osc);
            for i in 0..7 {
                let tol = 1e-7 * reference[i].abs().max(1.0);
                assert!(
                    (ours[i] - reference[i]).abs() < tol,
                    "joint {i}: {} vs {} (seed {seed}, step {k})",
                    ours[i],
                    reference[i]
                );
            }
            checked += 1;
        }
    }
    assert_eq!(checked, 15);
}

#[test]
fn osc_goal_is_the_scaled_delta_on_the_achieved_pose() {
    let mut env = make_with("Lift", EnvConfig::default()).unwrap();
    env.reset(Some(1), None).unwrap();
    let mut sim = Sim::new(env.sim().model().clone()).unwrap();
    sim.set_state(&env.get_state()).unwrap();
    let mut osc = osc_of(&env, &sim);
    let b = osc.binding().clone();
    let x = Vector3::from(sim.data().site_xpos()[b.site]);
    let r = Matrix3::from_row_slice(&sim.data().site_xmat()[b.site]);
    // Inputs are clipped to [-1, 1] and scaled by 0.05 m / 0.5 rad; the base frame of a
    // single Panda is the world frame shifted to the base.
    osc.set_goal(&sim, &[2.0, -0.5, 0.25, 0.0, 0.0, -3.0]);
    let p_b = Vector3::from(sim.data().site_xpos()[b.base_site]);
    let goal_world = p_b + osc.goal_pos();
    let expected = x + Vector3::new(0.05, -0.025, 0.0125);
    assert!((goal_world - expected).norm() < 1e-12);
    let expected_r = Rotation3::from_axis_angle(&Vector3::z_axis(), -0.5).matrix() * r;
    // robosuite rounds the delta rotation through float32.
    assert!((osc.goal_ori() - expected_r).abs().max() < 1e-6);
    assert!((osc.goal_ori() - expected_r).abs().max() > 0.0);
}

#[test]
fn at_rest_on_goal_the_torque_is_gravity_compensation() {
    // Zero velocity, goal = current pose, q = q0: every term but h vanishes.
    let mut env = make_with("Lift", EnvConfig::default()).unwrap();
    env.reset(Some(3), None).unwrap();
    let sim = env.sim();
    let mut osc = osc_of(&env, sim);
    let tau = torques(&mut osc, sim);
    let b = osc.binding().clone();
    let ctrlrange = env.robots()[0].arm().ctrlrange().to_vec();
    for (i, t) in tau.iter().enumerate() {
        let h = sim.data().qfrc_bias()[b.dofs[i]];
        assert!((t - h).abs() < 1e-9, "joint {i}: {t} vs {h}");
    }
    // A pure +x position error with no velocity: τ − h = Jpᵀ Λp F (the orientation and
    // nullspace terms vanish), so the arm alone would accelerate the grip site by exactly F.
    let mut sim2 = Sim::new(env.sim().model().clone()).unwrap();
    sim2.set_state(&env.get_state()).unwrap();
    osc.set_goal(&sim2, &[0.05, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let tau = torques(&mut osc, &sim2);
    let reference = reference_torques(&sim2, &osc);
    for i in 0..7 {
        assert!((tau[i] - reference[i]).abs() < 1e-7 * reference[i].abs().max(1.0));
    }
    let nv = sim2.model().ffi().nv as usize;
    let (jacp, _) = sim2.data().jac_site(true, false, b.site);
    let mut full = vec![0.0; nv * nv];
    sim2.data().full_m(&mut full).unwrap();
    let m = DMatrix::from_fn(7, 7, |r, c| full[b.dofs[r] * nv + b.dofs[c]]);
    let jp = DMatrix::from_fn(3, 7, |r, c| jacp[r * nv + b.dofs[c]]);
    let dtau = DVector::from_fn(7, |i, _| tau[i] - sim2.data().qfrc_bias()[b.dofs[i]]);
    let acc = &jp * m.clone().lu().try_inverse().unwrap() * &dtau;
    // Unsaturated, the task-space acceleration is (Jp M⁻¹ Jpᵀ) Λp F = F = kp · 0.0025 m
    // = 0.375 along x.
    assert!(tau.iter().zip(&ctrlrange).all(|(t, r)| t.abs() < r[1]));
    assert!(
        (acc[0] - 0.375).abs() < 1e-9 && acc[1].abs() < 1e-9 && acc[2].abs() < 1e-9,
        "{acc:?}"
    );
}
