//! robosuite's placement samplers: `UniformRandomSampler` (object positions uniform in a
//! rectangle around a reference point, a rotation about one axis, and rejection of
//! overlapping placements) and `SequentialCompositeSampler` (samplers run one after another,
//! each keeping clear of what the earlier ones placed).

use gym_core::{EnvRng, Error, Result};
use rand::RngExt;
use std::f64::consts::PI;

/// How the sampler rotates objects. Its serde form is robosuite's argument: `null`
/// (random), a number (fixed) or `[lo, hi]` (a range).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(from = "RotationArg", into = "RotationArg")]
pub enum Rotation {
    /// Uniform in `[0, 2π)` (robosuite's `rotation=None`).
    Random,
    /// Uniform in `[lo, hi)`.
    Range(f64, f64),
    /// Always this angle.
    Fixed(f64),
}

/// robosuite's `rotation` / `z_rotation` argument as it is written.
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(
    untagged,
    expecting = "None, an angle (radians) or a [low, high] range"
)]
enum RotationArg {
    Random(()),
    Fixed(f64),
    Range([f64; 2]),
}

impl From<RotationArg> for Rotation {
    fn from(arg: RotationArg) -> Self {
        match arg {
            RotationArg::Random(()) => Self::Random,
            RotationArg::Fixed(angle) => Self::Fixed(angle),
            RotationArg::Range([lo, hi]) => Self::Range(lo, hi),
        }
    }
}

impl From<Rotation> for RotationArg {
    fn from(rotation: Rotation) -> Self {
        match rotation {
            Rotation::Random => Self::Random(()),
            Rotation::Fixed(angle) => Self::Fixed(angle),
            Rotation::Range(lo, hi) => Self::Range([lo, hi]),
        }
    }
}

/// The axis of the sampled rotation (serde: robosuite's `"x"`, `"y"`, `"z"`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// About x.
    X,
    /// About y.
    Y,
    /// About z.
    Z,
}

/// The extent of an object as the sampler sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlacedObject {
    /// Radius of the object's footprint.
    pub horizontal_radius: f64,
    /// Height of the bottom below the object's origin (negative: robosuite's `bottom_offset[2]`).
    pub bottom_offset: f64,
    /// Height of the top above the object's origin (robosuite's `top_offset[2]`).
    pub top_offset: f64,
}

/// A sampled pose: position and quaternion (wxyz).
pub type Pose = ([f64; 3], [f64; 4]);

/// What robosuite's `UniformRandomSampler` makes of a sampled quaternion for an object with
/// an `init_quat` (xyzw; ToolHang's stand and frame, the hammer):
/// `quat_multiply(sampled, init_quat)`, which takes the sampled `wxyz` quaternion as if it
/// were `xyzw`, returns float32, and whose result is used as `wxyz`.
pub fn with_init_quat(sampled: [f64; 4], init_quat: [f64; 4]) -> [f64; 4] {
    crate::math::quat_multiply_f32(sampled, init_quat)
}

/// robosuite's `UniformRandomSampler` (serde: its constructor arguments by name, as a
/// task's `placement_initializer` option).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UniformRandomSampler {
    /// Range of x around the reference.
    pub x_range: [f64; 2],
    /// Range of y around the reference.
    pub y_range: [f64; 2],
    /// Rotation law.
    pub rotation: Rotation,
    /// Rotation axis.
    pub rotation_axis: Axis,
    /// Shrink the ranges by each object's horizontal radius.
    pub ensure_object_boundary_in_range: bool,
    /// Reject overlapping placements (up to 5000 tries per object).
    pub ensure_valid_placement: bool,
    /// Reference position (the table top, for instance).
    pub reference_pos: [f64; 3],
    /// Extra height above the reference.
    pub z_offset: f64,
}

fn uniform(rng: &mut EnvRng, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * rng.random::<f64>()
}

impl UniformRandomSampler {
    /// The number of tries per object before giving up (robosuite's 5000).
    pub const MAX_TRIES: usize = 5000;

    /// Samples poses for `objects` in order, avoiding `fixed` ones already placed; the
    /// object's bottom rests at `reference z + z_offset`. RNG use per try: x, y; then the
    /// rotation once the position is valid (robosuite's order).
    ///
    /// # Errors
    /// [`Error::Simulation`] when an object finds no valid placement in 5000 tries.
    pub fn sample(
        &self,
        rng: &mut EnvRng,
        objects: &[PlacedObject],
        fixed: &[(Pose, PlacedObject)],
    ) -> Result<Vec<Pose>> {
        let mut placed: Vec<(Pose, PlacedObject)> = fixed.to_vec();
        let mut out = Vec::with_capacity(objects.len());
        for (n, obj) in objects.iter().enumerate() {
            let r = obj.horizontal_radius;
            let shrink = if self.ensure_object_boundary_in_range {
                r
            } else {
                0.0
            };
            let mut found = None;
            for _ in 0..Self::MAX_TRIES {
                let x = uniform(rng, self.x_range[0] + shrink, self.x_range[1] - shrink)
                    + self.reference_pos[0];
                let y = uniform(rng, self.y_range[0] + shrink, self.y_range[1] - shrink)
                    + self.reference_pos[1];
                let z = self.z_offset + self.reference_pos[2] - obj.bottom_offset;
                let valid = !self.ensure_valid_placement
                    || placed.iter().all(|((p, _), other)| {
                        let overlap_xy = (x - p[0]).hypot(y - p[1]) <= other.horizontal_radius + r;
                        let overlap_z = z - p[2] <= other.top_offset - obj.bottom_offset;
                        !(overlap_xy && overlap_z)
                    });
                if valid {
                    let quat = self.sample_quat(rng);
                    found = Some(([x, y, z], quat));
                    break;
                }
            }
            let Some(pose) = found else {
                return Err(Error::simulation(format!(
                    "cannot place object {n} without overlap in {} tries",
                    Self::MAX_TRIES
                )));
            };
            placed.push((pose, *obj));
            out.push(pose);
        }
        Ok(out)
    }

    fn sample_quat(&self, rng: &mut EnvRng) -> [f64; 4] {
        let angle = match self.rotation {
            Rotation::Random => uniform(rng, 0.0, 2.0 * PI),
            Rotation::Range(a, b) => uniform(rng, a.min(b), a.max(b)),
            Rotation::Fixed(a) => a,
        };
        let (s, c) = (angle / 2.0).sin_cos();
        match self.rotation_axis {
            Axis::X => [c, s, 0.0, 0.0],
            Axis::Y => [c, 0.0, s, 0.0],
            Axis::Z => [c, 0.0, 0.0, s],
        }
    }
}

/// robosuite's `SequentialCompositeSampler`: its samplers run in order, each placing its own
/// objects clear of every object placed before it (robosuite passes the placements made so
/// far on as fixtures).
#[derive(Debug, Clone, PartialEq)]
pub struct SequentialCompositeSampler {
    /// Each sampler with the indices (into the objects given to
    /// [`SequentialCompositeSampler::sample`]) of the objects it places, in its order.
    pub samplers: Vec<(UniformRandomSampler, Vec<usize>)>,
}

impl SequentialCompositeSampler {
    /// Samples a pose for every object of `objects`, sampler after sampler; the result is
    /// indexed like `objects`. RNG use: each sampler's, in order.
    ///
    /// # Errors
    /// [`Error::Simulation`] when an object finds no valid placement, or
    /// [`Error::InvalidArgument`] when the samplers do not place every object exactly once.
    pub fn sample(&self, rng: &mut EnvRng, objects: &[PlacedObject]) -> Result<Vec<Pose>> {
        let mut assigned: Vec<usize> = self
            .samplers
            .iter()
            .flat_map(|(_, o)| o.iter().copied())
            .collect();
        assigned.sort_unstable();
        if assigned != (0..objects.len()).collect::<Vec<_>>() {
            return Err(Error::invalid_argument(
                "samplers",
                format!(
                    "must place each of the {} objects once, got {assigned:?}",
                    objects.len()
                ),
            ));
        }
        let mut placed: Vec<(Pose, PlacedObject)> = Vec::with_capacity(objects.len());
        let mut out = vec![([0.0; 3], [1.0, 0.0, 0.0, 0.0]); objects.len()];
        for (sampler, indices) in &self.samplers {
            let extents: Vec<PlacedObject> = indices.iter().map(|&i| objects[i]).collect();
            let poses = sampler.sample(rng, &extents, &placed)?;
            for ((&i, pose), extent) in indices.iter().zip(poses).zip(extents) {
                out[i] = pose;
                placed.push((pose, extent));
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gym_core::rng_from_seed;

    #[test]
    fn samples_in_range_without_overlap() {
        let s = UniformRandomSampler {
            x_range: [-0.08, 0.08],
            y_range: [-0.08, 0.08],
            rotation: Rotation::Random,
            rotation_axis: Axis::Z,
            ensure_object_boundary_in_range: false,
            ensure_valid_placement: true,
            reference_pos: [0.0, 0.0, 0.8],
            z_offset: 0.01,
        };
        let obj = PlacedObject {
            horizontal_radius: 0.03,
            bottom_offset: -0.02,
            top_offset: 0.02,
        };
        let mut rng = rng_from_seed(3);
        for _ in 0..50 {
            let poses = s.sample(&mut rng, &[obj, obj], &[]).unwrap();
            let (a, b) = (poses[0].0, poses[1].0);
            assert!((a[0] - b[0]).hypot(a[1] - b[1]) > 0.06);
            assert!((a[2] - 0.83).abs() < 1e-12);
            assert!(a[0].abs() <= 0.08 && a[1].abs() <= 0.08);
        }
        let big = PlacedObject {
            horizontal_radius: 1.0,
            ..obj
        };
        assert!(matches!(
            s.sample(&mut rng, &[big, big], &[]),
            Err(Error::Simulation(_))
        ));
    }
}
