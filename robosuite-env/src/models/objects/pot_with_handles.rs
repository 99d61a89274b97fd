//! robosuite's `PotWithHandlesObject` (`models/objects/composite/pot_with_handles.py`): an
//! open box with a handle on each side (TwoArmLift's pot).

use super::composite::{CompositeGeom, CompositeObject, GeneratedObject, GeomType, SiteSpec};
use super::{CustomMaterial, ObjectModel};
use crate::assets::Assets;
use crate::math::axisangle2quat;
use gym_core::{Error, Result};
use nalgebra::Vector3;
use std::f64::consts::PI;

/// The figures of a pot (robosuite's constructor arguments; [`PotWithHandles::two_arm_lift`]
/// gives TwoArmLift's, which are robosuite's defaults).
#[derive(Debug, Clone, PartialEq)]
pub struct PotWithHandles {
    /// The object's name.
    pub name: String,
    /// Half-size of the pot body.
    pub body_half_size: [f64; 3],
    /// Radius (half thickness) of the handle bars.
    pub handle_radius: f64,
    /// How far each handle reaches out from the body.
    pub handle_length: f64,
    /// Width of each handle.
    pub handle_width: f64,
    /// Sliding friction of the handles.
    pub handle_friction: f64,
    /// Density of every geom.
    pub density: f64,
    /// Thickness of the walls and the bottom.
    pub thickness: f64,
    /// The body's, handle 0's and handle 1's materials (robosuite's `redwood` /
    /// `pot_mat`, `greenwood` / `handle0_mat`, `bluewood` / `handle1_mat`).
    pub materials: [CustomMaterial; 3],
}

/// robosuite's `GREEN` and `BLUE`: the handle sites' colours.
const HANDLE_RGBA: [[f64; 4]; 2] = [[0.0, 1.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0]];

fn wood(assets: &Assets, texture: &str, tex_name: &str, mat_name: &str) -> Result<CustomMaterial> {
    CustomMaterial::new(
        assets,
        texture,
        tex_name,
        mat_name,
        &[("type", "cube")],
        &[
            ("texrepeat", "1 1"),
            ("specular", "0.4"),
            ("shininess", "0.1"),
        ],
        false,
    )
}

impl PotWithHandles {
    /// TwoArmLift's pot `pot` with robosuite's defaults: body 14 cm cube, handles 9 cm long
    /// and wide with 1 cm bars, handle friction 1, density 1000, 1 cm walls, textured.
    ///
    /// # Errors
    /// [`Error::Model`] when a wood texture is missing.
    pub fn two_arm_lift(assets: &Assets) -> Result<Self> {
        Ok(Self {
            name: "pot".to_owned(),
            body_half_size: [0.07; 3],
            handle_radius: 0.01,
            handle_length: 0.09,
            handle_width: 0.09,
            handle_friction: 1.0,
            density: 1000.0,
            thickness: 0.01,
            materials: [
                wood(assets, "WoodRed", "redwood", "pot_mat")?,
                wood(assets, "WoodGreen", "greenwood", "handle0_mat")?,
                wood(assets, "WoodBlue", "bluewood", "handle1_mat")?,
            ],
        })
    }

    /// The geom names of handle `i` (0 or 1), unprefixed: the cross bar `handle{i}_c`,
    /// then the side bars `handle{i}_-` and `handle{i}_+`.
    pub fn handle_geoms(i: usize) -> [String; 3] {
        [
            format!("handle{i}_c"),
            format!("handle{i}_-"),
            format!("handle{i}_+"),
        ]
    }

    /// The composite object robosuite generates: geoms `base`, `body0`..`body3` (walls
    /// rotated by π/2, 0, −π/2, π about z), then per handle its three bars; sites `handle0`,
    /// `handle1` (5 mm inside each cross bar) and `center`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for non-positive or non-finite sizes.
    pub fn composite(&self) -> Result<CompositeObject> {
        let h = self.body_half_size;
        let figures = [
            h[0],
            h[1],
            h[2],
            self.handle_radius,
            self.handle_length,
            self.handle_width,
            self.thickness,
            self.density,
        ];
        if figures.iter().any(|v| !v.is_finite() || *v <= 0.0) {
            return Err(Error::invalid_argument(
                "pot",
                format!("every size must be positive and finite, got {self:?}"),
            ));
        }
        let t = self.thickness;
        let mat = |i: usize| Some(self.materials[i].material_name().to_owned());
        let mut base = CompositeGeom::new(
            GeomType::Box,
            &[h[0], h[1], t / 2.0],
            [0.0, 0.0, -h[2] + t / 2.0],
        )
        .quat([1.0, 0.0, 0.0, 0.0])
        .named("base");
        base.material = mat(0);
        let mut geoms = vec![base];
        let xs = [0.0, -(h[0] - t / 2.0), 0.0, h[0] - t / 2.0];
        let ys = [-(h[1] - t / 2.0), 0.0, h[1] - t / 2.0, 0.0];
        let ws = [h[0], h[1], h[0], h[1]];
        let rs = [PI / 2.0, 0.0, -PI / 2.0, PI];
        for i in 0..4 {
            let q = axisangle2quat(&Vector3::new(0.0, 0.0, rs[i]));
            let mut wall =
                CompositeGeom::new(GeomType::Box, &[t / 2.0, ws[i], h[2]], [xs[i], ys[i], 0.0])
                    .quat([q[3], q[0], q[1], q[2]])
                    .named(format!("body{i}"));
            wall.material = mat(0);
            geoms.push(wall);
        }
        let (r, len, width) = (self.handle_radius, self.handle_length, self.handle_width);
        let main_bar = [width / 2.0 + r, r, r];
        let side_bar = [r, len / 2.0, r];
        let handle_z = h[2] - r;
        let friction = Some([self.handle_friction, 0.005, 0.0001]);
        let mut sites = Vec::new();
        for (i, side) in [1.0, -1.0].into_iter().enumerate() {
            let center = [0.0, side * (h[1] + len), handle_z];
            let names = Self::handle_geoms(i);
            let mut bars = vec![
                CompositeGeom::new(GeomType::Box, &main_bar, center)
                    .quat([1.0, 0.0, 0.0, 0.0])
                    .named(names[0].clone()),
            ];
            for (k, bar_side) in [-1.0, 1.0].into_iter().enumerate() {
                bars.push(
                    CompositeGeom::new(
                        GeomType::Box,
                        &side_bar,
                        [bar_side * width / 2.0, side * (h[1] + len / 2.0), handle_z],
                    )
                    .quat([1.0, 0.0, 0.0, 0.0])
                    .named(names[k + 1].clone()),
                );
            }
            for mut bar in bars {
                bar.material = mat(i + 1);
                bar.friction = friction;
                geoms.push(bar);
            }
            sites.push(
                SiteSpec::named(&format!("handle{i}"))
                    .with("type", "sphere")
                    .with("group", "0")
                    .with_numbers("pos", &[center[0], center[1] - side * 0.005, center[2]])
                    .with("size", "0.005")
                    .with_numbers("rgba", &HANDLE_RGBA[i]),
            );
        }
        sites.push(
            SiteSpec::named("center")
                .with("type", "sphere")
                .with("group", "0")
                .with("pos", "0 0 0")
                .with("size", "0.005")
                .with("rgba", "1 0 0 1"),
        );
        let total = [h[0] / 2.0, (h[1] + 2.0 * len) / 2.0, h[2] / 2.0];
        let mut c = CompositeObject::centred(
            &self.name,
            total,
            self.density,
            [0.02, 1.0],
            [0.9, 0.95, 0.001],
        );
        c.geoms = geoms;
        c.sites = sites;
        c.materials = self.materials.to_vec();
        Ok(c)
    }
}

impl GeneratedObject for PotWithHandles {
    /// The object, with robosuite's overridden extent: bottom and top at `∓body_half_size
    /// z`, horizontal radius `√2 · (max(body_half_size) + handle_length)`.
    fn build(&self) -> Result<ObjectModel> {
        let mut built = self.composite()?.build()?;
        let h = self.body_half_size;
        built.bottom_offset = [0.0, 0.0, -h[2]];
        built.top_offset = [0.0, 0.0, h[2]];
        built.horizontal_radius = 2f64.sqrt() * (h[0].max(h[1]).max(h[2]) + self.handle_length);
        Ok(built)
    }

    fn bounding_box_half_size(&self, _built: &ObjectModel) -> [f64; 3] {
        let h = self.body_half_size;
        [
            h[0] / 2.0,
            (h[1] + 2.0 * self.handle_length) / 2.0,
            h[2] / 2.0,
        ]
    }
}
