//! robosuite's `RatchetingWrenchObject` (`models/objects/composite_body/ratcheting_wrench.py`):
//! a handle between two rings, with an optional grip, as a composite body (ToolHang's tool).

use super::composite::{BodyPart, CompositeBodyObject, GeneratedObject, ShellStyle};
use super::hollow_cylinder::HollowCylinder;
use super::primitive::Primitive;
use super::stand_with_mount::tool_material;
use super::{CustomMaterial, Joints, ObjectModel, Shape};
use crate::assets::Assets;
use gym_core::Result;

/// The figures of a ratcheting wrench (robosuite's constructor arguments;
/// [`RatchetingWrench::tool_hang`] gives ToolHang's).
#[derive(Debug, Clone, PartialEq)]
pub struct RatchetingWrench {
    /// The object's name.
    pub name: String,
    /// Half-sizes of the handle (length, width, height).
    pub handle_size: [f64; 3],
    /// Outer radii of the two rings.
    pub outer_radii: [f64; 2],
    /// Inner radii of the two rings.
    pub inner_radii: [f64; 2],
    /// Half-heights of the two rings.
    pub heights: [f64; 2],
    /// Boxes per ring.
    pub ngeoms: usize,
    /// Radius and half-height of the (box) grip, if any.
    pub grip_size: Option<[f64; 2]>,
    /// Density.
    pub density: f64,
    /// Solref.
    pub solref: [f64; 2],
    /// Solimp.
    pub solimp: [f64; 3],
    /// Friction of rings and handle (`None`: MuJoCo's default).
    pub friction: Option<[f64; 3]>,
    /// Scratched steel (rings and handle).
    pub steel: CustomMaterial,
}

impl RatchetingWrench {
    /// ToolHang's tool (`tool_hang.py`'s `real_tool_args`): a 16.5 × 1.75 × 0.32 cm handle,
    /// rings of 3.5 / 2.1 cm and 3.0 / 2.0 cm diameter, 0.7 cm tall, 8 boxes each, an
    /// 8 cm grip of 3 cm; density 2000, solimp `(0.998, 0.998, 0.001)`, friction
    /// `(0.95, 0.3, 0.1)`.
    ///
    /// # Errors
    /// [`gym_core::Error::Model`] when the texture is missing.
    pub fn tool_hang(assets: &Assets) -> Result<Self> {
        Ok(Self {
            name: "tool".to_owned(),
            handle_size: [16.5 / 200.0, 1.75 / 200.0, 0.32 / 200.0],
            outer_radii: [3.5 / 200.0, 3.0 / 200.0],
            inner_radii: [2.1 / 200.0, 2.0 / 200.0],
            heights: [0.7 / 200.0, 0.7 / 200.0],
            ngeoms: 8,
            grip_size: Some([3.0 / 200.0, 8.0 / 200.0]),
            density: 2000.0,
            solref: [0.02, 1.0],
            solimp: [0.998, 0.998, 0.001],
            friction: Some([0.95, 0.3, 0.1]),
            steel: tool_material(assets, "SteelScratched", "steel", "steel_mat")?,
        })
    }

    /// Ring `i` (0 or 1): robosuite's `HollowCylinderObject` `hole{i+1}`.
    pub fn ring(&self, i: usize) -> HollowCylinder {
        let mut ring = HollowCylinder::new(&format!("hole{}", i + 1));
        ring.outer_radius = self.outer_radii[i];
        ring.inner_radius = self.inner_radii[i];
        ring.height = self.heights[i];
        ring.ngeoms = self.ngeoms;
        ring.style = ShellStyle {
            rgba: None,
            material: Some(self.steel.clone()),
            density: self.density,
            solref: self.solref,
            solimp: self.solimp,
            friction: self.friction,
        };
        ring
    }

    /// The composite body robosuite generates: rings `hole1` and `hole2` at the handle's
    /// ends (touching it), the `handle` box, and the `grip` box turned a quarter about y;
    /// one free joint with damping 0.0005.
    ///
    /// # Errors
    /// [`gym_core::Error::InvalidArgument`] for invalid figures.
    pub fn composite(&self) -> Result<CompositeBodyObject> {
        let hs = self.handle_size;
        let rings = [self.ring(0), self.ring(1)];
        let mut handle = Primitive::new("handle", Shape::Box(hs));
        handle.material = Some(self.steel.clone());
        handle.density = self.density;
        handle.solref = Some(self.solref);
        handle.solimp = self.solimp;
        handle.friction = self.friction;
        let mut parts = vec![
            BodyPart::of(
                &rings[0],
                [
                    -hs[0] - self.outer_radii[0] + 2.0 * rings[0].unit_box_height(),
                    0.0,
                    0.0,
                ],
            )?,
            BodyPart::of(
                &rings[1],
                [
                    hs[0] + self.outer_radii[1] - 2.0 * rings[1].unit_box_height(),
                    0.0,
                    0.0,
                ],
            )?,
            BodyPart::of(&handle, [0.0; 3])?,
        ];
        if let Some([r, h]) = self.grip_size {
            let mut grip = Primitive::new("grip", Shape::Box([r, r, h]));
            grip.rgba = [0.13, 0.13, 0.13, 1.0];
            grip.density = self.density;
            grip.solref = Some(self.solref);
            grip.solimp = self.solimp;
            grip.friction = Some([1.0, 0.005, 0.0001]);
            let h = 2f64.sqrt() / 2.0;
            parts.push(BodyPart::of(&grip, [0.0; 3])?.rotated([h, 0.0, h, 0.0]));
        }
        let mut c = CompositeBodyObject::new(&self.name, parts);
        c.joints = Joints::free_with_damping("0.0005");
        Ok(c)
    }
}

impl GeneratedObject for RatchetingWrench {
    fn build(&self) -> Result<ObjectModel> {
        self.composite()?.generate()
    }

    fn bounding_box_half_size(&self, built: &ObjectModel) -> [f64; 3] {
        [
            built.horizontal_radius,
            built.horizontal_radius,
            0.0 - built.bottom_offset[2],
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::super::robosuite_expected::assert_matches_robosuite;
    use super::*;

    #[test]
    fn tool_hang_tool_matches_robosuite() {
        let tool = RatchetingWrench::tool_hang(&Assets::locate().unwrap()).unwrap();
        let built = tool.build().unwrap();
        assert_matches_robosuite("tool", &built, tool.bounding_box_half_size(&built));
    }
}
