//! robosuite's `initialization_noise`: the random offsets added to a robot's rest posture
//! on every reset.

use gym_core::{EnvRng, Error, Result};
use rand::RngExt;
use rand_distr::StandardNormal;

/// The largest noise magnitude accepted (radians): beyond it a reset posture is arbitrary
/// and the simulation can diverge.
pub const MAX_NOISE_MAGNITUDE: f64 = 10.0;

/// The law of the reset noise on the robot joints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoiseKind {
    /// `magnitude · N(0, 1)` per joint (robosuite's `"gaussian"`).
    Gaussian,
    /// `magnitude · U(−1, 1)` per joint (robosuite's `"uniform"`).
    Uniform,
}

/// robosuite's `initialization_noise`: added to `init_qpos` on every reset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InitNoise {
    /// Scale of the noise in radians.
    pub magnitude: f64,
    /// Its law.
    pub kind: NoiseKind,
}

impl Default for InitNoise {
    /// robosuite's `"default"`: Gaussian with magnitude 0.02.
    fn default() -> Self {
        Self {
            magnitude: 0.02,
            kind: NoiseKind::Gaussian,
        }
    }
}

impl InitNoise {
    /// No noise (robosuite's `None`: magnitude 0; the draws still happen, so the RNG stream
    /// stays aligned with the noisy setting).
    pub fn none() -> Self {
        Self {
            magnitude: 0.0,
            kind: NoiseKind::Gaussian,
        }
    }

    /// Checks the magnitude.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a negative, non-finite or too large magnitude.
    pub fn validate(&self) -> Result<()> {
        let m = self.magnitude;
        if !(m.is_finite() && (0.0..=MAX_NOISE_MAGNITUDE).contains(&m)) {
            return Err(Error::invalid_argument(
                "initialization_noise",
                format!("magnitude must be in [0, {MAX_NOISE_MAGNITUDE}] rad, got {m}"),
            ));
        }
        Ok(())
    }

    /// Adds one draw per joint to `qpos` (robosuite draws them all at once, in joint order).
    pub fn perturb(&self, rng: &mut EnvRng, qpos: &mut [f64]) {
        for q in qpos {
            let z: f64 = match self.kind {
                NoiseKind::Gaussian => rng.sample(StandardNormal),
                NoiseKind::Uniform => -1.0 + 2.0 * rng.random::<f64>(),
            };
            *q += z * self.magnitude;
        }
    }
}
