//! robosuite's `HollowCylinderObject` (`models/objects/composite/hollow_cylinder.py`): a
//! cylindrical shell approximated by a ring of boxes.

use super::composite::{CompositeGeom, CompositeObject, GeneratedObject, GeomType, SiteSpec};
use super::{CustomMaterial, ObjectModel};
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
    /// Colour of the visual geoms (`None`: none).
    pub rgba: Option<[f64; 4]>,
    /// Material of the visual geoms.
    pub material: Option<CustomMaterial>,
    /// Density (default 1000).
    pub density: f64,
    /// Solref (default `(0.02, 1.0)`).
    pub solref: [f64; 2],
    /// Solimp (default `(0.9, 0.95, 0.001)`).
    pub solimp: [f64; 3],
    /// Friction (`None`: MuJoCo's default).
    pub friction: Option<[f64; 3]>,
    /// Only the first `ngeoms / 2 + 1` boxes (half a shell).
    pub make_half: bool,
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
            rgba: None,
            material: None,
            density: 1000.0,
            solref: [0.02, 1.0],
            solimp: [0.9, 0.95, 0.001],
            friction: None,
            make_half: false,
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
        let mut c = CompositeObject::new(&self.name, [r2, r2, self.height]);
        c.locations_relative_to_center = true;
        c.density = Some(self.density);
        c.solref = self.solref;
        c.solimp = self.solimp;
        c.geoms = (0..n_make)
            .map(|i| {
                let angle = PI - i as f64 * step;
                let mut g = CompositeGeom::new(
                    GeomType::Box,
                    &[height, width, self.height],
                    [int_r * angle.cos(), int_r * angle.sin(), 0.0],
                )
                .quat([(angle / 2.0).cos(), 0.0, 0.0, (angle / 2.0).sin()])
                .named(format!("hc_{i}"));
                g.rgba = self.rgba;
                g.material = self.material.as_ref().map(|m| m.material_name().to_owned());
                g.friction = self.friction;
                g.condim = Some(4);
                g
            })
            .collect();
        c.sites = vec![
            SiteSpec::named("center")
                .with("pos", "0 0 0")
                .with("size", "0.002")
                .with("rgba", "1 0 0 1")
                .with("type", "sphere"),
        ];
        c.materials = self.material.iter().cloned().collect();
        Ok(c)
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
