//! Every arm controller's torques against an independent dense computation from MuJoCo's
//! own Jacobians, mass matrix and bias forces (nalgebra `DMatrix`, LU inverses, SVD
//! pseudo-inverses, written from robosuite's formulas), at states reached by random
//! actions, on a 7-joint (Panda) and a 6-joint (UR5e) arm.
//!
//! Each controller is created (reset) at one state A and given an action at a later state
//! B, so the posture target `q₀` and the PID history are not trivial.

use gym_core::{Env, Space};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use robosuite_env::controllers::config::{
    IkConfig, ImpedanceMode, InputRefFrame, JointPositionConfig, JointTorqueConfig,
    JointVelocityConfig, OscConfig, PerAxis,
};
use robosuite_env::controllers::{ArmBinding, ArmControllerConfig, Timing, build_arm_controller};
use robosuite_env::sim::Sim;
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};

/// MuJoCo's quantities at one (forwarded) state, dense.
struct Dense {
    j: DMatrix<f64>,
    m: DMatrix<f64>,
    q: DVector<f64>,
    qd: DVector<f64>,
    h: DVector<f64>,
    x: Vector3<f64>,
    r: Matrix3<f64>,
    v: Vector3<f64>,
    w: Vector3<f64>,
    p_b: Vector3<f64>,
    r_b: Matrix3<f64>,
    v_b: Vector3<f64>,
    w_b: Vector3<f64>,
}

fn dense(sim: &Sim, b: &ArmBinding) -> Dense {
    let d = sim.data();
    let nv = b.nv;
    let n = b.dofs.len();
    let qvel = DVector::from_column_slice(d.qvel());
    let jac = |site| {
        let (p, r) = d.jac_site(true, true, site);
        (
            DMatrix::from_row_slice(3, nv, &p),
            DMatrix::from_row_slice(3, nv, &r),
        )
    };
    let (jp, jr) = jac(b.site);
    let (bp, br) = jac(b.base_site);
    let mut full = vec![0.0; nv * nv];
    d.full_m(&mut full).unwrap();
    let v3 = |m: DVector<f64>| Vector3::new(m[0], m[1], m[2]);
    Dense {
        j: DMatrix::from_fn(6, n, |r, c| {
            if r < 3 {
                jp[(r, b.dofs[c])]
            } else {
                jr[(r - 3, b.dofs[c])]
            }
        }),
        m: DMatrix::from_fn(n, n, |r, c| full[b.dofs[r] * nv + b.dofs[c]]),
        q: DVector::from_iterator(n, b.qpos.iter().map(|&a| d.qpos()[a])),
        qd: DVector::from_iterator(n, b.dofs.iter().map(|&a| d.qvel()[a])),
        h: DVector::from_iterator(n, b.dofs.iter().map(|&a| d.qfrc_bias()[a])),
        x: Vector3::from(d.site_xpos()[b.site]),
        r: Matrix3::from_row_slice(&d.site_xmat()[b.site]),
        v: v3(&jp * &qvel),
        w: v3(&jr * &qvel),
        p_b: Vector3::from(d.site_xpos()[b.base_site]),
        r_b: Matrix3::from_row_slice(&d.site_xmat()[b.base_site]),
        v_b: v3(&bp * &qvel),
        w_b: v3(&br * &qvel),
    }
}

fn pinv(a: DMatrix<f64>) -> DMatrix<f64> {
    let s = a.svd(true, true);
    let cutoff = 1e-15 * s.singular_values.max();
    s.pseudo_inverse(cutoff).unwrap()
}

fn inv(a: &DMatrix<f64>) -> DMatrix<f64> {
    a.clone().lu().try_inverse().unwrap()
}

/// `Rot(axis · angle)` by Rodrigues' formula.
fn rotation(v: Vector3<f64>) -> Matrix3<f64> {
    nalgebra::Rotation3::from_scaled_axis(v).into_inner()
}

fn ori_error(desired: &Matrix3<f64>, current: &Matrix3<f64>) -> Vector3<f64> {
    0.5 * (0..3)
        .map(|i| current.column(i).cross(&desired.column(i)))
        .fold(Vector3::zeros(), |a, b| a + b)
}

/// robosuite's OSC law for a delta input in the base frame with fixed gains.
fn osc_reference(
    s: &Dense,
    q0: &DVector<f64>,
    input: &[f64],
    use_ori: bool,
    kp: [f64; 6],
    kd: [f64; 6],
) -> DVector<f64> {
    let scale = [0.05, 0.05, 0.05, 0.5, 0.5, 0.5];
    let d = |i: usize| input[i].clamp(-1.0, 1.0) * scale[i];
    let goal_p = s.r_b.transpose() * (s.x - s.p_b) + Vector3::new(d(0), d(1), d(2));
    let rot = if use_ori {
        rotation(Vector3::new(d(3), d(4), d(5)))
    } else {
        Matrix3::identity()
    };
    let goal_r = rot * s.r_b.transpose() * s.r;
    let e_p = s.p_b + s.r_b * goal_p - s.x;
    let e_o = ori_error(&(s.r_b * goal_r), &s.r);
    let (v, w) = (s.v - s.v_b, s.w - s.w_b);
    let f = DVector::from_fn(3, |i, _| kp[i] * e_p[i] - kd[i] * v[i]);
    let t = DVector::from_fn(3, |i, _| kp[3 + i] * e_o[i] - kd[3 + i] * w[i]);
    let m_inv = inv(&s.m);
    let n = s.q.len();
    let jp = s.j.rows(0, 3).into_owned();
    let jo = s.j.rows(3, 3).into_owned();
    let lambda = pinv(&s.j * &m_inv * s.j.transpose());
    let wrench = DVector::from_iterator(
        6,
        (pinv(&jp * &m_inv * jp.transpose()) * f)
            .iter()
            .chain((pinv(&jo * &m_inv * jo.transpose()) * t).iter())
            .copied()
            .collect::<Vec<_>>(),
    );
    let null = DMatrix::identity(n, n) - &m_inv * s.j.transpose() * &lambda * &s.j;
    let posture = (q0 - &s.q) * 10.0 - &s.qd * (2.0 * 10f64.sqrt());
    s.j.transpose() * wrench + &s.h + null.transpose() * (&s.m * posture)
}

/// `M·(kp∘(goal − q) − kd∘q̇) + h`.
fn joint_pd(s: &Dense, goal: &DVector<f64>, kp: &[f64], kd: &[f64]) -> DVector<f64> {
    let n = s.q.len();
    let raw = DVector::from_fn(n, |i, _| kp[i] * (goal[i] - s.q[i]) - kd[i] * s.qd[i]);
    &s.m * raw + &s.h
}

/// robosuite's IK step (damped least squares, nullspace pull, speed cap) and its tracking.
fn ik_reference(s: &Dense, q0: &DVector<f64>, input: &[f64]) -> DVector<f64> {
    let n = s.q.len();
    let mut dp = Vector3::new(input[0], input[1], input[2]);
    if dp.norm() > 0.02 {
        dp *= 0.02 / dp.norm();
    }
    let mut dr = Vector3::new(input[3], input[4], input[5]);
    if dr.norm() > 0.05 {
        dr *= 0.05 / dr.norm();
    }
    let twist = DVector::from_iterator(6, (dp * 9.5).iter().chain((dr * 9.5).iter()).copied());
    let damped = &s.j * s.j.transpose() + DMatrix::identity(6, 6) * 0.0025;
    let mut dq = s.j.transpose() * inv(&damped) * twist;
    let kn = DVector::from_fn(n, |i, _| if i + 3 < n { 10.0 } else { 5.0 });
    let pull = DVector::from_fn(n, |i, _| kn[i] * (q0[i] - s.q[i]));
    dq += (DMatrix::identity(n, n) - pinv(s.j.clone()) * &s.j) * pull;
    let peak = dq.amax();
    if peak > 1.0 {
        dq /= peak;
    }
    let goal = &s.q + dq * 0.1;
    joint_pd(s, &goal, &vec![100.0; n], &vec![20.0; n])
}

/// The env's arm binding and timing.
fn binding(env: &RobosuiteEnv) -> (ArmBinding, Timing) {
    let robot = &env.robots()[0];
    let arm = robot.arm();
    let model = env.sim().model();
    (
        ArmBinding {
            site: arm.eef_site(),
            base_site: robosuite_env::sim::site_id(model, "robot0_right_center").unwrap(),
            qpos: robot.joint_qpos()[arm.joints()].to_vec(),
            dofs: robot.joint_dofs()[arm.joints()].to_vec(),
            nv: model.ffi().nv as usize,
            ctrlrange: arm.ctrlrange().to_vec(),
            origin_at_reset: false,
        },
        Timing {
            timestep: 0.002,
            control_freq: 20.0,
        },
    )
}

/// The env's state in a fresh simulator, forwarded (what `mj_step1` gives the controller).
fn snapshot_sim(env: &RobosuiteEnv) -> Sim {
    let mut sim = Sim::new(env.sim().model().clone()).unwrap();
    sim.set_state(&env.get_state()).unwrap();
    sim
}

/// For each controller config: reset at state A, act at state B, compare with `reference`
/// (given the dense state at B, `q` at A, the input and the controller's dimension).
fn check(
    robot: &str,
    config: ArmControllerConfig,
    reference: impl Fn(&Dense, &Dense, &[f64]) -> DVector<f64>,
) {
    let mut env = make_with("Lift", EnvConfig::default().with_robots([robot])).unwrap();
    let mut rng = gym_core::rng_from_seed(11);
    let mut checked = 0;
    for seed in 0..3 {
        env.reset(Some(seed), None).unwrap();
        let sim_a = snapshot_sim(&env);
        for _ in 0..(4 + 3 * seed) {
            let a = env.action_space().sample(&mut rng);
            let _ = env.step(&a).unwrap();
        }
        let sim_b = snapshot_sim(&env);
        let (bind, timing) = binding(&env);
        let mut ctrl = build_arm_controller(&config, bind.clone(), timing, "c").unwrap();
        let n = bind.dofs.len();
        let mut tau = vec![0.0; n];
        ctrl.reset(&sim_a);
        ctrl.compute(&sim_a, &mut tau);
        let (lo, hi) = ctrl.action_limits();
        let input: Vec<f64> = (0..ctrl.action_dim())
            .map(|i| {
                let u = (seed as f64 + 1.0) * 0.37 * (i as f64 + 1.0);
                lo[i] + (hi[i] - lo[i]) * (0.5 + 0.45 * u.sin())
            })
            .collect();
        ctrl.set_goal(&sim_b, &input);
        ctrl.compute(&sim_b, &mut tau);
        let expected = reference(&dense(&sim_a, &bind), &dense(&sim_b, &bind), &input);
        for i in 0..n {
            // robosuite rounds the delta rotation through float32 (1e-7 relative).
            let tol = 1e-5 * expected[i].abs().max(1.0);
            assert!(
                (tau[i] - expected[i]).abs() < tol,
                "{robot} {}: joint {i}: {} vs {} (seed {seed})",
                config.controller_type(),
                tau[i],
                expected[i]
            );
        }
        checked += 1;
    }
    assert_eq!(checked, 3);
}

const ROBOTS: [&str; 2] = ["Panda", "UR5e"];

#[test]
fn osc_pose_and_position_match_the_dense_law() {
    for robot in ROBOTS {
        check(
            robot,
            ArmControllerConfig::OscPose(OscConfig::default()),
            |a, b, x| osc_reference(b, &a.q, x, true, [150.0; 6], [2.0 * 150f64.sqrt(); 6]),
        );
        check(
            robot,
            ArmControllerConfig::OscPosition(OscConfig::default()),
            |a, b, x| osc_reference(b, &a.q, x, false, [150.0; 6], [2.0 * 150f64.sqrt(); 6]),
        );
        // variable_kp: the first six inputs are the stiffnesses, critically damped.
        check(
            robot,
            ArmControllerConfig::OscPose(
                OscConfig::default().with_impedance_mode(ImpedanceMode::VariableKp),
            ),
            |a, b, x| {
                let kp: [f64; 6] = std::array::from_fn(|i| x[i]);
                let kd = kp.map(|k| 2.0 * k.sqrt());
                osc_reference(b, &a.q, &x[6..], true, kp, kd)
            },
        );
    }
}

#[test]
fn osc_world_frame_absolute_goal_is_the_input() {
    // In the world frame an absolute input is the world pose itself.
    let mut env = make_with("Lift", EnvConfig::default()).unwrap();
    env.reset(Some(2), None).unwrap();
    let sim = snapshot_sim(&env);
    let (bind, timing) = binding(&env);
    let config = ArmControllerConfig::OscPose(
        OscConfig::default()
            .with_input_ref_frame(InputRefFrame::World)
            .with_input_type(robosuite_env::controllers::config::InputType::Absolute),
    );
    let mut ctrl = build_arm_controller(&config, bind.clone(), timing, "c").unwrap();
    ctrl.reset(&sim);
    let mut tau = vec![0.0; 7];
    ctrl.compute(&sim, &mut tau);
    let s = dense(&sim, &bind);
    let target = s.x + Vector3::new(0.02, -0.01, 0.03);
    let turned = rotation(Vector3::new(0.0, 0.0, 0.1)) * s.r;
    let rotvec = nalgebra::Rotation3::from_matrix(&turned).scaled_axis();
    let input = [
        target[0], target[1], target[2], rotvec[0], rotvec[1], rotvec[2],
    ];
    ctrl.set_goal(&sim, &input);
    ctrl.compute(&sim, &mut tau);
    // The same torques as a base-frame delta input that asks for the same pose.
    let delta_in = [0.4, -0.2, 0.6, 0.0, 0.0, 0.2];
    let expected = osc_reference(
        &s,
        &s.q,
        &delta_in,
        true,
        [150.0; 6],
        [2.0 * 150f64.sqrt(); 6],
    );
    for i in 0..7 {
        assert!(
            (tau[i] - expected[i]).abs() < 1e-5 * expected[i].abs().max(1.0),
            "joint {i}: {} vs {}",
            tau[i],
            expected[i]
        );
    }
}

#[test]
fn joint_position_matches_the_dense_law() {
    for robot in ROBOTS {
        check(
            robot,
            ArmControllerConfig::JointPosition(JointPositionConfig::default()),
            |_, b, x| {
                let n = b.q.len();
                let goal = DVector::from_fn(n, |i, _| b.q[i] + x[i].clamp(-1.0, 1.0) * 0.05);
                joint_pd(b, &goal, &vec![50.0; n], &vec![2.0 * 50f64.sqrt(); n])
            },
        );
        check(
            robot,
            ArmControllerConfig::JointPosition(JointPositionConfig {
                impedance_mode: ImpedanceMode::Variable,
                ..JointPositionConfig::default()
            }),
            |_, b, x| {
                let n = b.q.len();
                let (damping, kp, delta) = (&x[..n], &x[n..2 * n], &x[2 * n..]);
                let kd: Vec<f64> = (0..n).map(|i| 2.0 * kp[i].sqrt() * damping[i]).collect();
                let goal = DVector::from_fn(n, |i, _| b.q[i] + delta[i] * 0.05);
                joint_pd(b, &goal, kp, &kd)
            },
        );
    }
}

#[test]
fn joint_velocity_matches_the_dense_pid() {
    for robot in ROBOTS {
        let config = JointVelocityConfig {
            kp: PerAxis::Scalar(3.0),
            output_max: PerAxis::Scalar(0.5),
            output_min: PerAxis::Scalar(-0.5),
            ..JointVelocityConfig::default()
        };
        let env = make_with("Lift", EnvConfig::default().with_robots([robot])).unwrap();
        let ranges = env.robots()[0].arm().ctrlrange().to_vec();
        check(
            robot,
            ArmControllerConfig::JointVelocity(config),
            move |a, b, x| {
                let n = b.q.len();
                DVector::from_fn(n, |i, _| {
                    let kp = 3.0 * (ranges[i][1] - ranges[i][0]);
                    // One earlier substep at A with a zero goal, then the new goal at B.
                    let e_a = -a.qd[i];
                    let e_b = x[i].clamp(-1.0, 1.0) * 0.5 - b.qd[i];
                    let tau_a = kp * e_a + 0.005 * kp * e_a + 0.001 * kp * e_a + a.h[i];
                    let saturated_a = tau_a < ranges[i][0] || tau_a > ranges[i][1];
                    let summed = if saturated_a { e_a } else { e_a + e_b };
                    let derr_mean = (e_a + (e_b - e_a)) / 2.0;
                    let t = kp * e_b + 0.005 * kp * summed + 0.001 * kp * derr_mean + b.h[i];
                    t.clamp(ranges[i][0], ranges[i][1])
                })
            },
        );
    }
}

#[test]
fn joint_torque_matches_the_dense_law() {
    for robot in ROBOTS {
        check(
            robot,
            ArmControllerConfig::JointTorque(JointTorqueConfig {
                output_max: PerAxis::Scalar(5.0),
                output_min: PerAxis::Scalar(-5.0),
                ..JointTorqueConfig::default()
            }),
            |_, b, x| DVector::from_fn(b.q.len(), |i, _| x[i] * 5.0 + b.h[i]),
        );
    }
}

#[test]
fn ik_pose_matches_the_dense_step() {
    for robot in ROBOTS {
        check(
            robot,
            ArmControllerConfig::IkPose(IkConfig::default()),
            |a, b, x| ik_reference(b, &a.q, x),
        );
    }
}
