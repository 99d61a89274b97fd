//! robosuite's `StandWithMount` (`models/objects/composite/stand_with_mount.py`): a flat
//! stand with a four-walled mount rising from it (ToolHang's stand).

use super::composite::{CompositeGeom, CompositeObject, GeneratedObject, GeomType, SiteSpec};
use super::{CustomMaterial, ObjType, ObjectModel};
use crate::assets::Assets;
use crate::math::axisangle2quat;
use gym_core::{Error, Result};
use nalgebra::Vector3;
use std::f64::consts::PI;

/// The brass material of robosuite's stand and frame (`mat_name` `brass_mat`).
pub(crate) fn brass(assets: &Assets) -> Result<CustomMaterial> {
    tool_material(assets, "Brass", "brass", "brass_mat")
}

/// A material as robosuite's ToolHang objects define theirs: cube texture, `texrepeat 3 3`,
/// specular 0.4, shininess 0.1.
pub(crate) fn tool_material(
    assets: &Assets,
    texture: &str,
    tex_name: &str,
    mat_name: &str,
) -> Result<CustomMaterial> {
    CustomMaterial::new(
        assets,
        texture,
        tex_name,
        mat_name,
        &[("type", "cube")],
        &[
            ("texrepeat", "3 3"),
            ("specular", "0.4"),
            ("shininess", "0.1"),
        ],
        false,
    )
}

/// The figures of a stand (robosuite's constructor arguments; [`StandWithMount::tool_hang`]
/// gives ToolHang's).
#[derive(Debug, Clone, PartialEq)]
pub struct StandWithMount {
    /// The object's name.
    pub name: String,
    /// Full size (x, y, z).
    pub size: [f64; 3],
    /// Where the mount is, from the stand's centre (x, y).
    pub mount_location: [f64; 2],
    /// Width of the mount, measured outside the walls.
    pub mount_width: f64,
    /// Thickness of the mount's walls.
    pub wall_thickness: f64,
    /// Thickness of the base plate.
    pub base_thickness: f64,
    /// Start tipped over on its side (the init quaternion).
    pub initialize_on_side: bool,
    /// Add a purely visual rim marking the hole.
    pub add_hole_vis: bool,
    /// Friction (`None`: MuJoCo's default).
    pub friction: Option<[f64; 3]>,
    /// Density.
    pub density: f64,
    /// Solref.
    pub solref: [f64; 2],
    /// Solimp.
    pub solimp: [f64; 3],
    /// Whether the geoms use the brass material (else they take `rgba`; the material is in
    /// the assets either way, as in robosuite).
    pub use_texture: bool,
    /// The brass material.
    pub material: CustomMaterial,
    /// Colour of the geoms without texture.
    pub rgba: [f64; 4],
}

impl StandWithMount {
    /// ToolHang's stand (`tool_hang.py`'s `stand_args`): 12 × 14 × 16 cm, the mount 4.5 cm
    /// off centre in y, 1.2 cm wide with 1 mm walls, a 1 cm base, upright, with the hole
    /// rim, density 50000, solimp `(0.998, 0.998, 0.001)`, brass.
    ///
    /// # Errors
    /// [`Error::Model`] when the brass texture is missing.
    pub fn tool_hang(assets: &Assets) -> Result<Self> {
        Ok(Self {
            name: "stand".to_owned(),
            size: [12.0 / 100.0, 14.0 / 100.0, 16.0 / 100.0],
            mount_location: [0.0, 4.5 / 100.0],
            mount_width: 1.2 / 100.0,
            wall_thickness: 0.1 / 100.0,
            base_thickness: 1.0 / 100.0,
            initialize_on_side: false,
            add_hole_vis: true,
            friction: None,
            density: 50000.0,
            solref: [0.02, 1.0],
            solimp: [0.998, 0.998, 0.001],
            use_texture: true,
            material: brass(assets)?,
            rgba: [0.2, 0.1, 0.0, 1.0],
        })
    }

    /// robosuite's `init_quat` (xyzw), which its placement sampler multiplies onto the
    /// sampled rotation: a quarter turn about y when on its side, else the identity.
    // robosuite's literal 0.707107, not 1/√2.
    #[allow(clippy::approx_constant)]
    pub fn init_quat(&self) -> [f64; 4] {
        if self.initialize_on_side {
            [0.0, 0.707107, 0.0, 0.707107]
        } else {
            [0.0, 0.0, 0.0, 1.0]
        }
    }

    /// The composite object robosuite generates: geoms `base`, `wall0`..`wall3` (walls at
    /// the mount, rotated by π/2, 0, −π/2, π about z), optionally the visual `hole_vis`;
    /// site `mount_site` on top; brass appended.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for non-positive or non-finite sizes.
    pub fn composite(&self) -> Result<CompositeObject> {
        if self.size.iter().any(|v| !v.is_finite() || *v <= 0.0) {
            return Err(Error::invalid_argument(
                "size",
                format!(
                    "{}: must be positive and finite, got {:?}",
                    self.name, self.size
                ),
            ));
        }
        let s = self.size;
        let (mw, wt, bt) = (self.mount_width, self.wall_thickness, self.base_thickness);
        let styled = |mut g: CompositeGeom| {
            if self.use_texture {
                g.material = Some(self.material.material_name().to_owned());
            } else {
                g.rgba = Some(self.rgba);
            }
            g.friction = self.friction;
            g
        };
        let mut geoms = vec![styled(
            CompositeGeom::new(
                GeomType::Box,
                &[s[0] / 2.0, s[1] / 2.0, bt / 2.0],
                [0.0, 0.0, -(s[2] - bt) / 2.0],
            )
            .quat([1.0, 0.0, 0.0, 0.0])
            .named("base"),
        )];
        let off = (mw - wt) / 2.0;
        let xs = [0.0, -off, 0.0, off].map(|x| x + self.mount_location[0]);
        let ys = [-off, 0.0, off, 0.0].map(|y| y + self.mount_location[1]);
        let rs = [PI / 2.0, 0.0, -PI / 2.0, PI];
        for i in 0..4 {
            let q = axisangle2quat(&Vector3::new(0.0, 0.0, rs[i]));
            geoms.push(styled(
                CompositeGeom::new(
                    GeomType::Box,
                    &[wt / 2.0, mw / 2.0, (s[2] - bt) / 2.0],
                    [xs[i], ys[i], bt / 2.0],
                )
                .quat([q[3], q[0], q[1], q[2]])
                .named(format!("wall{i}")),
            ));
        }
        if self.add_hole_vis {
            let side = 0.7 * ((mw - wt) / 2.0);
            let half = [side, side, wt / 2.0];
            let mut rim = CompositeGeom::new(
                GeomType::Box,
                &half,
                [
                    self.mount_location[0],
                    self.mount_location[1],
                    (s[2] / 2.0) - half[2],
                ],
            )
            .quat([1.0, 0.0, 0.0, 0.0])
            .named("hole_vis");
            rim.rgba = Some([0.0, 1.0, 0.0, 0.5]);
            rim.friction = self.friction;
            rim.obj_type = ObjType::Visual;
            geoms.push(rim);
        }
        let mut c = CompositeObject::centred(
            &self.name,
            s.map(|v| v / 2.0),
            self.density,
            self.solref,
            self.solimp,
        );
        c.geoms = geoms;
        c.sites = vec![
            SiteSpec::named("mount_site")
                .with_numbers("pos", &[0.0, 0.0, s[2] / 2.0])
                .with("size", "0.002")
                .with("rgba", "1 0 0 1")
                .with("type", "sphere"),
        ];
        c.materials = vec![self.material.clone()];
        Ok(c)
    }
}

impl GeneratedObject for StandWithMount {
    fn build(&self) -> Result<ObjectModel> {
        self.composite()?.build()
    }

    fn bounding_box_half_size(&self, _built: &ObjectModel) -> [f64; 3] {
        self.size.map(|v| v / 2.0)
    }
}

#[cfg(test)]
mod tests {
    use super::super::robosuite_expected::{assert_matches_robosuite, init_quat};
    use super::*;

    #[test]
    fn tool_hang_stand_matches_robosuite() {
        let stand = StandWithMount::tool_hang(&Assets::locate().unwrap()).unwrap();
        let built = stand.build().unwrap();
        assert_matches_robosuite("stand", &built, stand.bounding_box_half_size(&built));
        assert_eq!(init_quat("stand"), Some(stand.init_quat().to_vec()));
    }

    #[test]
    fn bad_size_is_rejected() {
        let mut stand = StandWithMount::tool_hang(&Assets::locate().unwrap()).unwrap();
        stand.size[1] = -1.0;
        assert!(matches!(stand.build(), Err(Error::InvalidArgument { .. })));
    }
}
