//! The `OSC_POSE` controller configuration (robosuite's `default_panda.json`).

use gym_core::{Error, Result};

/// `OSC_POSE` settings: fixed impedance, delta input in the robot base frame, goal updated
/// from the achieved pose, decoupled position / orientation (robosuite 1.5.2 defaults).
#[derive(Debug, Clone, PartialEq)]
pub struct OscConfig {
    /// Stiffness per axis (x, y, z, ax, ay, az); robosuite's `kp` (default 150).
    pub kp: [f64; 6],
    /// Damping ratio per axis (default 1); `kd = 2·sqrt(kp)·damping_ratio`.
    pub damping_ratio: [f64; 6],
    /// Largest input; inputs are clipped to `[input_min, input_max]` (default 1).
    pub input_max: f64,
    /// Smallest input (default −1).
    pub input_min: f64,
    /// Output at `input_max` (default `[0.05, 0.05, 0.05, 0.5, 0.5, 0.5]`: metres, radians).
    pub output_max: [f64; 6],
    /// Output at `input_min` (default `[-0.05, -0.05, -0.05, -0.5, -0.5, -0.5]`).
    pub output_min: [f64; 6],
    /// Use separate position and orientation task-space inertias (default true).
    pub uncouple_pos_ori: bool,
    /// Nullspace stiffness pulling the arm toward its reset posture (robosuite: 10).
    pub nullspace_kp: f64,
}

impl Default for OscConfig {
    fn default() -> Self {
        Self {
            kp: [150.0; 6],
            damping_ratio: [1.0; 6],
            input_max: 1.0,
            input_min: -1.0,
            output_max: [0.05, 0.05, 0.05, 0.5, 0.5, 0.5],
            output_min: [-0.05, -0.05, -0.05, -0.5, -0.5, -0.5],
            uncouple_pos_ori: true,
            nullspace_kp: 10.0,
        }
    }
}

impl OscConfig {
    /// The same stiffness on every axis.
    #[must_use]
    pub fn with_kp(mut self, kp: f64) -> Self {
        self.kp = [kp; 6];
        self
    }

    /// The same damping ratio on every axis.
    #[must_use]
    pub fn with_damping_ratio(mut self, ratio: f64) -> Self {
        self.damping_ratio = [ratio; 6];
        self
    }

    /// Symmetric output limits: ±`pos` metres and ±`ori` radians per env step.
    #[must_use]
    pub fn with_output_limits(mut self, pos: f64, ori: f64) -> Self {
        self.output_max = [pos, pos, pos, ori, ori, ori];
        self.output_min = self.output_max.map(|v| -v);
        self
    }

    /// The damping gains `kd = 2·sqrt(kp)·damping_ratio`.
    pub fn kd(&self) -> [f64; 6] {
        std::array::from_fn(|i| 2.0 * self.kp[i].sqrt() * self.damping_ratio[i])
    }

    /// Checks every value.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the field and the valid range.
    pub fn validate(&self) -> Result<()> {
        let bad = |name: &str, reason: String| {
            Err(Error::invalid_argument(
                format!("controller.{name}"),
                reason,
            ))
        };
        if let Some(k) = self.kp.iter().find(|k| !k.is_finite() || **k < 0.0) {
            return bad(
                "kp",
                format!("must be finite and >= 0 (robosuite's kp_limits are [0, 300]), got {k}"),
            );
        }
        if let Some(d) = self
            .damping_ratio
            .iter()
            .find(|d| !d.is_finite() || **d < 0.0)
        {
            return bad(
                "damping_ratio",
                format!("must be finite and >= 0 (robosuite's limits are [0, 10]), got {d}"),
            );
        }
        if !(self.input_min.is_finite()
            && self.input_max.is_finite()
            && self.input_min < self.input_max)
        {
            return bad(
                "input_min/input_max",
                format!(
                    "need finite input_min < input_max, got [{}, {}]",
                    self.input_min, self.input_max
                ),
            );
        }
        for i in 0..6 {
            let (lo, hi) = (self.output_min[i], self.output_max[i]);
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return bad(
                    "output_min/output_max",
                    format!("need finite output_min < output_max on axis {i}, got [{lo}, {hi}]"),
                );
            }
        }
        if !self.nullspace_kp.is_finite() || self.nullspace_kp < 0.0 {
            return bad(
                "nullspace_kp",
                format!("must be finite and >= 0, got {}", self.nullspace_kp),
            );
        }
        Ok(())
    }
}
