//! robosuite's `HookFrame` (`models/objects/composite/hook_frame.py`): an upside-down L
//! (a rod and a bar) with an optional hook, grip and insertion tip (ToolHang's frame).

use super::composite::{CompositeGeom, CompositeObject, GeneratedObject, GeomType, SiteSpec};
use super::cone::Cone;
use super::stand_with_mount::{brass, tool_material};
use super::{CustomMaterial, ObjectModel};
use crate::assets::Assets;
use crate::math::quat_multiply_f32;
use gym_core::{Error, Result};

/// The grip around the rod.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameGrip {
    /// Where the grip sits, from the centre of the rod.
    pub location: f64,
    /// Half-width and half-height of the (box) grip.
    pub size: [f64; 2],
}

/// The insertion tip below the rod: robosuite's `(CH, LR, UR, H)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameTip {
    /// Half-height of the cylinder below the rod.
    pub cylinder_half_height: f64,
    /// Radius at the cone's point.
    pub lower_radius: f64,
    /// Radius of the cylinder and the cone's base.
    pub upper_radius: f64,
    /// Height of the cone.
    pub cone_height: f64,
}

/// The figures of a hook frame (robosuite's constructor arguments; [`HookFrame::tool_hang`]
/// gives ToolHang's).
#[derive(Debug, Clone, PartialEq)]
pub struct HookFrame {
    /// The object's name.
    pub name: String,
    /// Length of the bar.
    pub frame_length: f64,
    /// Height of the rod.
    pub frame_height: f64,
    /// Thickness of rod and bar.
    pub frame_thickness: f64,
    /// Height of the hook at the bar's end, if any.
    pub hook_height: Option<f64>,
    /// The grip, if any.
    pub grip: Option<FrameGrip>,
    /// The tip, if any.
    pub tip: Option<FrameTip>,
    /// Friction (`None`: MuJoCo's default).
    pub friction: Option<[f64; 3]>,
    /// Density.
    pub density: f64,
    /// Solref.
    pub solref: [f64; 2],
    /// Solimp.
    pub solimp: [f64; 3],
    /// Whether the geoms use the materials (else they take `rgba`; the materials are in the
    /// assets either way).
    pub use_texture: bool,
    /// Colour of the geoms without texture.
    pub rgba: [f64; 4],
    /// Brass (rod, bar, hook).
    pub brass: CustomMaterial,
    /// Ceramic (grip).
    pub ceramic: CustomMaterial,
    /// Scratched steel (tip).
    pub steel: CustomMaterial,
}

impl HookFrame {
    /// ToolHang's frame (`tool_hang.py`'s `frame_args`): a 9.5 cm bar, an 18 cm rod,
    /// 0.75 cm thick, a 1.2 cm hook, a 6.35 cm grip of 2.54 cm and a solder tip; density
    /// 500, solimp `(0.998, 0.998, 0.001)`.
    ///
    /// # Errors
    /// [`Error::Model`] when a texture is missing.
    pub fn tool_hang(assets: &Assets) -> Result<Self> {
        Ok(Self {
            name: "frame".to_owned(),
            frame_length: 9.5 / 100.0,
            frame_height: 18.0 / 100.0,
            frame_thickness: 0.75 / 100.0,
            hook_height: Some(1.2 / 100.0),
            grip: Some(FrameGrip {
                location: ((9.0 - 3.0) / 100.0) - (0.75 / 200.0),
                size: [2.54 / 200.0, 6.35 / 200.0],
            }),
            tip: Some(FrameTip {
                cylinder_half_height: 2.54 / 200.0,
                lower_radius: 0.2 / 200.0,
                upper_radius: 0.65 / 200.0,
                cone_height: 1.905 / 100.0,
            }),
            friction: None,
            density: 500.0,
            solref: [0.02, 1.0],
            solimp: [0.998, 0.998, 0.001],
            use_texture: true,
            rgba: [0.2, 0.1, 0.0, 1.0],
            brass: brass(assets)?,
            ceramic: tool_material(assets, "Ceramic", "ceramic", "ceramic_mat")?,
            steel: tool_material(assets, "SteelScratched", "steel", "steel_mat")?,
        })
    }

    /// robosuite's `init_quat` (xyzw, float32): two quarter turns that lay the frame flat,
    /// which its placement sampler multiplies onto the sampled rotation.
    pub fn init_quat(&self) -> [f64; 4] {
        let h = 2f64.sqrt() / 2.0;
        quat_multiply_f32([0.0, 0.0, h, h], [-h, 0.0, 0.0, h])
    }

    /// The full size of the bounding box (the tip lengthens the rod).
    pub fn size(&self) -> [f64; 3] {
        let mut size = [self.frame_length, self.frame_thickness, self.frame_height];
        if let Some(t) = self.tip {
            size[2] += 2.0 * (t.cylinder_half_height + (2.0 * t.cone_height));
        }
        size
    }

    /// The composite object robosuite generates: geoms `vertical_frame`,
    /// `horizontal_frame`, then optionally `hook_frame`, `grip_frame` (a box, default
    /// friction, dark grey), `tip_cylinder` and the 51 boxes `tip_cone_{i}` of a cone (as
    /// robosuite adds them, in reverse size order); sites `hang_site`, `mount_site`,
    /// `intersection_site` and, with a tip, `tip_site`; brass, then ceramic (with a grip)
    /// and steel (with a tip) appended.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for non-positive or non-finite sizes.
    pub fn composite(&self) -> Result<CompositeObject> {
        let (fl, fh, ft) = (self.frame_length, self.frame_height, self.frame_thickness);
        if [fl, fh, ft].iter().any(|v| !v.is_finite() || *v <= 0.0) {
            return Err(Error::invalid_argument(
                "frame_length",
                format!("{}: frame sizes must be positive and finite", self.name),
            ));
        }
        let textured = |mut g: CompositeGeom, material: &CustomMaterial| {
            if self.use_texture {
                g.material = Some(material.material_name().to_owned());
            } else {
                g.rgba = Some(self.rgba);
            }
            g.friction = self.friction;
            g.quat([1.0, 0.0, 0.0, 0.0])
        };
        let mut geoms = vec![
            textured(
                CompositeGeom::new(
                    GeomType::Box,
                    &[ft / 2.0, ft / 2.0, (fh - ft) / 2.0],
                    [(fl - ft) / 2.0, 0.0, -ft / 2.0],
                )
                .named("vertical_frame"),
                &self.brass,
            ),
            textured(
                CompositeGeom::new(
                    GeomType::Box,
                    &[fl / 2.0, ft / 2.0, ft / 2.0],
                    [0.0, 0.0, (fh - ft) / 2.0],
                )
                .named("horizontal_frame"),
                &self.brass,
            ),
        ];
        if let Some(hh) = self.hook_height {
            geoms.push(textured(
                CompositeGeom::new(
                    GeomType::Box,
                    &[ft / 2.0, ft / 2.0, hh / 2.0],
                    [(-fl + ft) / 2.0, 0.0, (fh + hh) / 2.0],
                )
                .named("hook_frame"),
                &self.brass,
            ));
        }
        if let Some(grip) = self.grip {
            let mut g = CompositeGeom::new(
                GeomType::Box,
                &[grip.size[0], grip.size[0], grip.size[1]],
                [(fl - ft) / 2.0, 0.0, (-ft / 2.0) + grip.location],
            )
            .quat([1.0, 0.0, 0.0, 0.0])
            .named("grip_frame");
            g.rgba = Some([0.13, 0.13, 0.13, 1.0]);
            if self.use_texture {
                g.material = Some(self.ceramic.material_name().to_owned());
            }
            g.friction = Some([1.0, 0.005, 0.0001]);
            geoms.push(g);
        }
        if let Some(tip) = self.tip {
            let mut cone = Cone::new("cone");
            cone.outer_radius = tip.upper_radius;
            cone.inner_radius = tip.lower_radius;
            cone.height = tip.cone_height;
            cone.ngeoms = 50;
            cone.use_box = true;
            cone.style.density = self.density;
            cone.style.solref = self.solref;
            cone.style.solimp = self.solimp;
            cone.style.friction = self.friction;
            let slices = cone.geoms()?;
            let cylinder = [(fl - ft) / 2.0, 0.0, -fh / 2.0 - tip.cylinder_half_height];
            let offset = [
                cylinder[0],
                cylinder[1],
                cylinder[2] - tip.cylinder_half_height - tip.cone_height / 2.0,
            ];
            geoms.push(textured(
                CompositeGeom::new(
                    GeomType::Cylinder,
                    &[tip.upper_radius, tip.cylinder_half_height],
                    cylinder,
                )
                .named("tip_cylinder"),
                &self.steel,
            ));
            // robosuite adds the slices' sizes in reverse order (narrowest at the bottom).
            let sizes: Vec<Vec<f64>> = slices.iter().rev().map(|g| g.size.clone()).collect();
            for (i, (slice, size)) in slices.iter().zip(sizes).enumerate() {
                let at = slice.location;
                geoms.push(textured(
                    CompositeGeom::new(
                        slice.geom_type,
                        &size,
                        [at[0] + offset[0], at[1] + offset[1], at[2] + offset[2]],
                    )
                    .named(format!("tip_cone_{i}")),
                    &self.steel,
                ));
            }
        }
        let site = |name: &str, pos: [f64; 3], rgba: &str| {
            SiteSpec::named(name)
                .with_numbers("pos", &pos)
                .with("size", "0.002")
                .with("rgba", rgba)
                .with("type", "sphere")
        };
        let rod = (fl - ft) / 2.0;
        let mut sites = vec![
            site("hang_site", [-fl / 2.0, 0.0, (fh - ft) / 2.0], "1 0 0 1"),
            site("mount_site", [rod, 0.0, -fh / 2.0], "0 1 0 1"),
            site("intersection_site", [rod, 0.0, (fh - ft) / 2.0], "0 0 1 1"),
        ];
        if let Some(t) = self.tip {
            sites.push(site(
                "tip_site",
                [
                    rod,
                    0.0,
                    (-fh / 2.0) - 2.0 * t.cylinder_half_height - t.cone_height,
                ],
                "1 0 0 1",
            ));
        }
        let mut c = CompositeObject::centred(
            &self.name,
            self.size().map(|v| v / 2.0),
            self.density,
            self.solref,
            self.solimp,
        );
        c.geoms = geoms;
        c.sites = sites;
        c.materials = vec![self.brass.clone()];
        if self.grip.is_some() {
            c.materials.push(self.ceramic.clone());
        }
        if self.tip.is_some() {
            c.materials.push(self.steel.clone());
        }
        Ok(c)
    }
}

impl GeneratedObject for HookFrame {
    fn build(&self) -> Result<ObjectModel> {
        self.composite()?.build()
    }

    fn bounding_box_half_size(&self, _built: &ObjectModel) -> [f64; 3] {
        self.size().map(|v| v / 2.0)
    }
}

#[cfg(test)]
mod tests {
    use super::super::robosuite_expected::{assert_matches_robosuite, init_quat};
    use super::*;

    #[test]
    fn tool_hang_frame_matches_robosuite() {
        let frame = HookFrame::tool_hang(&Assets::locate().unwrap()).unwrap();
        let built = frame.build().unwrap();
        assert_matches_robosuite("frame", &built, frame.bounding_box_half_size(&built));
        assert_eq!(init_quat("frame"), Some(frame.init_quat().to_vec()));
    }

    #[test]
    fn bad_size_is_rejected() {
        let mut frame = HookFrame::tool_hang(&Assets::locate().unwrap()).unwrap();
        frame.frame_height = f64::NAN;
        assert!(matches!(frame.build(), Err(Error::InvalidArgument { .. })));
    }
}
