//! robosuite's `WipeArena` (`models/arenas/wipe_arena.py`): a table carrying a path of
//! visual dirt markers, and the random walk that lays the path out anew at every reset
//! (`reset_arena`).

use super::arenas::Arena;
use super::objects::primitive::Primitive;
use super::objects::{CustomMaterial, Joints, ObjType, Shape};
use crate::assets::Assets;
use crate::mjcf::tree::append;
use gym_core::{EnvRng, Error, Result};
use rand::RngExt;
use rand_distr::StandardNormal;
use std::f64::consts::PI;

/// The name of marker `i` (robosuite's `f"contact{i}"`): its body is `contact{i}_main`, its
/// visual geom `contact{i}_g0_vis`, its site `contact{i}_default_site`.
pub fn marker_name(i: usize) -> String {
    format!("contact{i}")
}

/// The figures of a `WipeArena` (robosuite's constructor arguments, as `Wipe` passes them).
#[derive(Debug, Clone, PartialEq)]
pub struct WipeArenaConfig {
    /// The table's full size.
    pub table_full_size: [f64; 3],
    /// The table's friction.
    pub table_friction: [f64; 3],
    /// The table top's centre.
    pub table_offset: [f64; 3],
    /// The fraction of the table the path may cover.
    pub coverage_factor: f64,
    /// The number of markers.
    pub num_markers: usize,
    /// The markers' diameter.
    pub line_width: f64,
    /// Two paths of half the markers each instead of one.
    pub two_clusters: bool,
}

/// robosuite's `WipeArena`: a `TableArena` (`arenas/table_arena.xml`) whose table body gets
/// `num_markers` visual `CylinderObject`s `contact{i}` (radius `line_width / 2`, half
/// height 0.001, no joints, the shared `dirt` material; their assets merged into the
/// arena's), appended in order after the table's own elements. The markers sit at the
/// table body's origin until [`MarkerWalk::lay`] places them.
///
/// # Errors
/// [`Error::Model`] when a model file is missing; [`Error::InvalidArgument`] for an invalid
/// table or marker size.
pub fn wipe_arena(assets: &Assets, config: &WipeArenaConfig) -> Result<Arena> {
    let mut arena = Arena::table(
        assets,
        "arenas/table_arena.xml",
        config.table_full_size,
        config.table_friction,
        config.table_offset,
    )?;
    let dirt = CustomMaterial::new(
        assets,
        "Dirt",
        "dirt",
        "dirt_mat",
        &[("type", "cube")],
        &[
            ("texrepeat", "1 1"),
            ("specular", "0.0"),
            ("shininess", "0.0"),
        ],
        true,
    )?;
    for i in 0..config.num_markers {
        let mut marker = Primitive::new(
            &marker_name(i),
            Shape::Cylinder([config.line_width / 2.0, 0.001]),
        );
        marker.rgba = [1.0, 1.0, 1.0, 1.0];
        marker.material = Some(dirt.clone());
        marker.obj_type = ObjType::Visual;
        marker.joints = Some(Joints::None);
        let marker = marker.build()?;
        arena.doc.merge_assets(&marker.assets);
        append(arena.table_body_mut()?, marker.body);
    }
    Ok(arena)
}

/// The most direction re-draws per marker before a walk counts as stuck (robosuite redraws
/// without bound; a walk that cannot continue would hang there).
pub const MAX_REDRAWS: usize = 10_000;

/// robosuite's marker path (`sample_start_pos` / `sample_path_pos`): a random walk of 5 mm
/// steps inside the central `coverage_factor` of the table.
#[derive(Debug, Clone, PartialEq)]
pub struct MarkerWalk {
    /// Half the table's length and width.
    pub table_half: [f64; 2],
    /// The fraction of the table the path may cover.
    pub coverage_factor: f64,
    /// The markers' diameter.
    pub line_width: f64,
    /// Restart the walk halfway (robosuite's `two_clusters`).
    pub two_clusters: bool,
}

impl MarkerWalk {
    /// The walk's bound on each axis: `|x|` and `|y|` stay below
    /// `table_half · coverage_factor − line_width / 2`.
    pub fn limits(&self) -> [f64; 2] {
        self.table_half
            .map(|h| h * self.coverage_factor - self.line_width / 2.0)
    }

    /// robosuite's `reset_arena` path: fills `out` with the markers' positions (table
    /// frame) in robosuite's draw order. A start is a direction `U(−π, π)`, then `x` and `y`
    /// uniform within the limits; each next point is 5 mm along the direction (`x += 0.005
    /// sin`, `y += 0.005 cos`), the direction first turned by `N(0, 0.5)` with probability 0.3
    /// (a uniform draw above 0.7) and again until the point is inside the limits. A next
    /// point is drawn after the last marker too, as robosuite does.
    ///
    /// # Errors
    /// [`Error::Simulation`] when the walk finds no way on within [`MAX_REDRAWS`] direction
    /// draws (a path area too small for a 5 mm step); `out` is then partly written.
    pub fn lay(&self, rng: &mut EnvRng, out: &mut [[f64; 2]]) -> Result<()> {
        let n = out.len();
        let mut direction = 0.0;
        let mut pos = self.start(rng, &mut direction);
        for (i, slot) in out.iter_mut().enumerate() {
            if self.two_clusters && i == n / 2 {
                pos = self.start(rng, &mut direction);
            }
            *slot = pos;
            pos = self.next(rng, pos, &mut direction)?;
        }
        Ok(())
    }

    fn start(&self, rng: &mut EnvRng, direction: &mut f64) -> [f64; 2] {
        *direction = uniform(rng, -PI, PI);
        let [lx, ly] = self.limits();
        let x = uniform(rng, -lx, lx);
        let y = uniform(rng, -ly, ly);
        [x, y]
    }

    fn next(&self, rng: &mut EnvRng, pos: [f64; 2], direction: &mut f64) -> Result<[f64; 2]> {
        if uniform(rng, 0.0, 1.0) > 0.7 {
            *direction += normal(rng, 0.5);
        }
        let step = |d: f64| [pos[0] + 0.005 * d.sin(), pos[1] + 0.005 * d.cos()];
        let [lx, ly] = self.limits();
        let mut new = step(*direction);
        let mut redraws = 0;
        while new[0].abs() >= lx || new[1].abs() >= ly {
            if redraws == MAX_REDRAWS {
                return Err(Error::simulation(format!(
                    "the Wipe marker walk is stuck at ({}, {}) after {MAX_REDRAWS} direction draws \
                     (path limits ±{lx} × ±{ly} m)",
                    pos[0], pos[1]
                )));
            }
            redraws += 1;
            *direction += normal(rng, 0.5);
            new = step(*direction);
        }
        Ok(new)
    }
}

/// NumPy's `uniform(lo, hi)`: `lo + (hi − lo)·U[0, 1)`.
fn uniform(rng: &mut EnvRng, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * rng.random::<f64>()
}

/// NumPy's `normal(0, scale)`.
fn normal(rng: &mut EnvRng, scale: f64) -> f64 {
    scale * rng.sample::<f64, _>(StandardNormal)
}

#[cfg(test)]
mod tests {
    use super::*;
    use gym_core::rng_from_seed;

    fn walk() -> MarkerWalk {
        MarkerWalk {
            table_half: [0.25, 0.4],
            coverage_factor: 0.6,
            line_width: 0.04,
            two_clusters: false,
        }
    }

    #[test]
    fn the_walk_takes_five_millimetre_steps_inside_its_limits() {
        let mut rng = rng_from_seed(4);
        let w = walk();
        let [lx, ly] = w.limits();
        assert!((lx - 0.13).abs() < 1e-12 && (ly - 0.22).abs() < 1e-12);
        for _ in 0..20 {
            let mut pts = vec![[0.0; 2]; 100];
            w.lay(&mut rng, &mut pts).unwrap();
            for p in &pts {
                assert!(p[0].abs() < lx && p[1].abs() < ly, "{p:?}");
            }
            for s in pts.windows(2) {
                let d = (s[1][0] - s[0][0]).hypot(s[1][1] - s[0][1]);
                assert!((d - 0.005).abs() < 1e-12, "{d}");
            }
        }
        // Two clusters restart the walk halfway.
        let two = MarkerWalk {
            two_clusters: true,
            ..w
        };
        let mut pts = vec![[0.0; 2]; 100];
        two.lay(&mut rng_from_seed(1), &mut pts).unwrap();
        let jump = (pts[50][0] - pts[49][0]).hypot(pts[50][1] - pts[49][1]);
        assert!((jump - 0.005).abs() > 1e-6, "{jump}");
    }

    #[test]
    fn a_walk_with_no_room_is_a_typed_error_not_a_hang() {
        // The markers are wider than the covered part of the table: no point is inside.
        let tight = MarkerWalk {
            coverage_factor: 0.04,
            ..walk()
        };
        let [lx, ly] = tight.limits();
        assert!(lx <= 0.0 && ly <= 0.0);
        let mut pts = vec![[0.0; 2]; 10];
        let err = tight.lay(&mut rng_from_seed(0), &mut pts);
        assert!(matches!(err, Err(Error::Simulation(_))), "{err:?}");
    }
}
