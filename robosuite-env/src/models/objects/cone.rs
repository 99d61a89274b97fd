//! robosuite's `ConeObject` (`models/objects/composite/cone.py`): a cone approximated by a
//! stack of cylinders or boxes.

use super::ObjectModel;
use super::composite::{CompositeGeom, CompositeObject, GeneratedObject, GeomType, ShellStyle};
use gym_core::{Error, Result};

/// The figures of a cone (robosuite's constructor arguments and defaults).
#[derive(Debug, Clone, PartialEq)]
pub struct Cone {
    /// The object's name.
    pub name: String,
    /// Radius of the base (default 0.0425).
    pub outer_radius: f64,
    /// Radius of the tip (default 0.03).
    pub inner_radius: f64,
    /// Height (default 0.05).
    pub height: f64,
    /// Number of slices (default 8; an even number is raised by one).
    pub ngeoms: usize,
    /// Boxes instead of cylinders (a square pyramid).
    pub use_box: bool,
    /// Colour, material, density, solver figures and friction of the slices.
    pub style: ShellStyle,
}

impl Cone {
    /// A cone with robosuite's defaults.
    pub fn new(name: &str) -> Self {
        Self {
            name: name.to_owned(),
            outer_radius: 0.0425,
            inner_radius: 0.03,
            height: 0.05,
            ngeoms: 8,
            use_box: false,
            style: ShellStyle::default(),
        }
    }

    /// The number of slices robosuite uses (odd).
    pub fn slices(&self) -> usize {
        if self.ngeoms.is_multiple_of(2) {
            self.ngeoms + 1
        } else {
            self.ngeoms
        }
    }

    /// The slices as robosuite's `_get_geom_attrs` lists them: `c_{i}` stacked along z
    /// around the centre, widest first, condim 4.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for fewer than two slices.
    pub fn geoms(&self) -> Result<Vec<CompositeGeom>> {
        let n = self.slices();
        if n < 2 {
            return Err(Error::invalid_argument(
                "ngeoms",
                "a cone needs at least two slices",
            ));
        }
        let unit_height = (self.height / n as f64) / 2.0;
        let unit_r = (self.outer_radius - self.inner_radius) / (n - 1) as f64;
        let side = ((n - 1) / 2) as isize;
        let (geom_type, mut sizes): (GeomType, Vec<Vec<f64>>) = if self.use_box {
            (
                GeomType::Box,
                (0..n)
                    .map(|i| {
                        let r = self.inner_radius + i as f64 * unit_r;
                        vec![r, r, unit_height]
                    })
                    .collect(),
            )
        } else {
            (
                GeomType::Cylinder,
                (0..n)
                    .map(|i| vec![self.inner_radius + i as f64 * unit_r, unit_height])
                    .collect(),
            )
        };
        sizes.reverse();
        Ok((-side..=side)
            .zip(sizes)
            .enumerate()
            .map(|(i, (k, size))| {
                let at = [0.0, 0.0, k as f64 * unit_height * 2.0];
                self.style
                    .geom(CompositeGeom::new(geom_type, &size, at), format!("c_{i}"))
            })
            .collect())
    }

    /// The composite object robosuite generates (site `center`, material appended last).
    ///
    /// # Errors
    /// As [`Cone::geoms`].
    pub fn composite(&self) -> Result<CompositeObject> {
        let half = [self.outer_radius, self.outer_radius, self.height / 2.0];
        Ok(self.style.composite(&self.name, half, self.geoms()?))
    }
}

impl GeneratedObject for Cone {
    fn build(&self) -> Result<ObjectModel> {
        self.composite()?.build()
    }

    fn bounding_box_half_size(&self, _built: &ObjectModel) -> [f64; 3] {
        [self.outer_radius, self.outer_radius, self.height / 2.0]
    }
}
