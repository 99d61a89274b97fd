//! Helpers shared by the example programs in this folder.

use gym_core::Info;

/// Formats an [`Info`] on one line, `key=value` pairs in order.
pub fn format_info(info: &Info) -> String {
    info.iter()
        .map(|(k, v)| match v {
            gym_core::InfoValue::Bool(b) => format!("{k}={b}"),
            gym_core::InfoValue::Int(i) => format!("{k}={i}"),
            gym_core::InfoValue::Float(f) => format!("{k}={f:.4}"),
            gym_core::InfoValue::Str(s) => format!("{k}={s}"),
            gym_core::InfoValue::Array(a) => format!("{k}=array{:?}", a.shape()),
            gym_core::InfoValue::Map(m) => format!("{k}={{{}}}", format_info(m)),
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The scripted Lift grasp of `lift_demo` and `view`: above the cube, down, close, up, with
/// OSC_POSE delta actions `[dx, dy, dz, ax, ay, az, grip]` in [-1, 1] (±1 = ±5 cm per step),
/// read from robosuite's observation keys `cube_pos` and `robot0_eef_pos`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LiftScript {
    /// The phase of the grasp.
    pub phase: LiftPhase,
    /// Where the cube started (the lift goes above it).
    cube0: [f64; 3],
}

/// The phases of [`LiftScript`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LiftPhase {
    /// Moving above the cube.
    Approach,
    /// Going down around it.
    Descend,
    /// Closing the gripper (steps so far).
    Grasp(u32),
    /// Lifting.
    Lift,
}

/// A 3-vector observation of `obs` (its first three values).
///
/// # Panics
/// When `key` is missing or holds fewer than three values (a programming error here).
pub fn vec3(obs: &gym_core::DictValue, key: &str) -> [f64; 3] {
    let v = obs[key].as_array().expect("array observation").to_f64_vec();
    [v[0], v[1], v[2]]
}

impl LiftScript {
    /// The script for the episode that starts with observation `obs`.
    pub fn new(obs: &gym_core::DictValue) -> Self {
        Self {
            phase: LiftPhase::Approach,
            cube0: vec3(obs, "cube_pos"),
        }
    }

    /// The action for observation `obs`; moves to the next phase when this one is done.
    pub fn act(&mut self, obs: &gym_core::DictValue) -> ndarray::ArrayD<f64> {
        let (eef, cube) = (vec3(obs, "robot0_eef_pos"), vec3(obs, "cube_pos"));
        let toward = |target: [f64; 3], grip: f64| {
            let mut a = ndarray::ArrayD::zeros(ndarray::IxDyn(&[7]));
            for i in 0..3 {
                a[[i]] = ((target[i] - eef[i]) / 0.05).clamp(-1.0, 1.0);
            }
            a[[6]] = grip;
            a
        };
        let action = match self.phase {
            LiftPhase::Approach => toward([cube[0], cube[1], cube[2] + 0.1], -1.0),
            LiftPhase::Descend => toward([cube[0], cube[1], cube[2] - 0.005], -1.0),
            LiftPhase::Grasp(_) => toward(eef, 1.0),
            LiftPhase::Lift => toward([self.cube0[0], self.cube0[1], 1.05], 1.0),
        };
        self.phase = match self.phase {
            LiftPhase::Approach
                if (eef[0] - cube[0]).hypot(eef[1] - cube[1]) < 0.01
                    && (eef[2] - cube[2] - 0.1).abs() < 0.02 =>
            {
                LiftPhase::Descend
            }
            LiftPhase::Descend if (eef[2] - cube[2]).abs() < 0.01 => LiftPhase::Grasp(0),
            LiftPhase::Grasp(n) if n >= 12 => LiftPhase::Lift,
            LiftPhase::Grasp(n) => LiftPhase::Grasp(n + 1),
            p => p,
        };
        action
    }
}
