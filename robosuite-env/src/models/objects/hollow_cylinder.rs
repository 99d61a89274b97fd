//! robosuite's `HollowCylinderObject` (`models/objects/composite/hollow_cylinder.py`): a
//! cylindrical shell approximated by a ring of boxes.

use super::ObjectModel;
use super::composite::{CompositeGeom, CompositeObject, GeneratedObject, GeomType, ShellStyle};
use gym_core::{Error, Result};
use std::f64::consts::PI;

/// The figures of a hollow cylinder (robosuite's constructor arguments and defaults).
#[derive(Debug, Clone, PartialEq)]
pub struct HollowCylinder {
    /// The object's name.
    pub name: String,
    /// Outer radius (default 0.0425).
    pub outer_radius: f64,
    /// Inner radius (default 0.03).
    pub inner_radius: f64,
    /// Half-height (default 0.05).
    pub height: f64,
    /// Boxes around the full ring (default 8).
    pub ngeoms: usize,
    /// Only the first `ngeoms / 2 + 1` boxes (half a shell).
    pub make_half: bool,
    /// Colour, material, density, solver figures and friction of the boxes.
    pub style: ShellStyle,
}

impl HollowCylinder {
    /// A hollow cylinder with robosuite's defaults.
    pub fn new(name: &str) -> Self {
        Self {
            name: name.to_owned(),
            outer_radius: 0.0425,
            inner_radius: 0.03,
            height: 0.05,
            ngeoms: 8,
            make_half: false,
            style: ShellStyle::default(),
        }
    }

    /// Half-width of each box (`r_out · sin(π / n)`).
    pub fn unit_box_width(&self) -> f64 {
        self.outer_radius * (PI / self.ngeoms as f64).sin()
    }

    /// Half-thickness of each box (`(r_out − r_in) · cos(π / n) / 2`).
    pub fn unit_box_height(&self) -> f64 {
        (self.outer_radius - self.inner_radius) * (PI / self.ngeoms as f64).cos() / 2.0
    }

    /// The composite object robosuite generates: boxes `hc_{i}` from the top-most one
    /// clockwise, condim 4, site `center`, material appended last.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for no boxes.
    pub fn composite(&self) -> Result<CompositeObject> {
        if self.ngeoms == 0 {
            return Err(Error::invalid_argument(
                "ngeoms",
                "a hollow cylinder needs boxes",
            ));
        }
        let n = self.ngeoms as f64;
        let (r1, r2) = (self.inner_radius, self.outer_radius);
        let height = self.unit_box_height();
        let width = self.unit_box_width();
        let int_r = (r1 * (PI / n).cos()) + height;
        let n_make = if self.make_half {
            self.ngeoms / 2 + 1
        } else {
            self.ngeoms
        };
        let step = 2.0 * PI / n;
        let geoms = (0..n_make)
            .map(|i| {
                let angle = PI - i as f64 * step;
                let g = CompositeGeom::new(
                    GeomType::Box,
                    &[height, width, self.height],
                    [int_r * angle.cos(), int_r * angle.sin(), 0.0],
                )
                .quat([(angle / 2.0).cos(), 0.0, 0.0, (angle / 2.0).sin()]);
                self.style.geom(g, format!("hc_{i}"))
            })
            .collect();
        Ok(self
            .style
            .composite(&self.name, [r2, r2, self.height], geoms))
    }
}

impl GeneratedObject for HollowCylinder {
    fn build(&self) -> Result<ObjectModel> {
        self.composite()?.build()
    }

    fn bounding_box_half_size(&self, _built: &ObjectModel) -> [f64; 3] {
        [self.outer_radius, self.outer_radius, self.height]
    }
}
