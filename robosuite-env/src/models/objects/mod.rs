//! robosuite's objects (`robosuite/models/objects/`): what a task puts into the scene.
//!
//! Every object becomes an [`ObjectModel`]: a prefixed body subtree with its assets, its
//! element names and the extent the placement samplers use. They are made from robosuite's
//! object files ([`xml_object`]: can, milk, bread, cereal, nuts, door, ...) or generated
//! from figures as robosuite generates them ([`primitive`]: boxes and cylinders;
//! [`composite`]: robosuite's composite objects and composite bodies, with ToolHang's
//! [`stand_with_mount`], [`hook_frame`] and [`ratcheting_wrench`] built on them).

pub mod bin;
pub mod composite;
pub mod cone;
pub mod hammer;
pub mod hollow_cylinder;
pub mod hook_frame;
mod material;
pub mod pot_with_handles;
pub mod primitive;
pub mod ratcheting_wrench;
#[cfg(test)]
mod robosuite_expected;
pub mod stand_with_mount;
mod xml;

pub use material::CustomMaterial;
pub use xml::{ObjType, xml_object};

use crate::mjcf::{Element, ElementNames};
use crate::placement::PlacedObject;

/// The joints an object gets (robosuite's `joints` argument).
#[derive(Debug, Clone, PartialEq)]
pub enum Joints {
    /// One free joint `joint0` (robosuite's `"default"`).
    Default,
    /// None.
    None,
    /// These joints, each a list of attributes (a joint without `name` is named `joint{i}`).
    Specs(Vec<Vec<(&'static str, String)>>),
}

impl Joints {
    /// One free joint with damping (robosuite's `[dict(type="free", damping=...)]`).
    pub fn free_with_damping(damping: &str) -> Self {
        Self::Specs(vec![vec![
            ("type", "free".to_owned()),
            ("damping", damping.to_owned()),
        ]])
    }

    /// The joint elements, named as robosuite names them.
    pub(crate) fn elements(&self) -> Vec<Element> {
        let specs = match self {
            Self::Default => vec![vec![("type", "free".to_owned())]],
            Self::None => Vec::new(),
            Self::Specs(s) => s.clone(),
        };
        specs
            .into_iter()
            .enumerate()
            .map(|(i, mut spec)| {
                if !spec.iter().any(|(k, _)| *k == "name") {
                    spec.push(("name", format!("joint{i}")));
                }
                crate::mjcf::tree::element("joint", &spec)
            })
            .collect()
    }
}

/// A primitive shape, for objects whose size a task changes at reset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A box with these half-extents.
    Box([f64; 3]),
    /// A cylinder: radius and half-height.
    Cylinder([f64; 2]),
}

/// An object ready to be merged into a scene.
#[derive(Debug, Clone)]
pub struct ObjectModel {
    /// The object's name (its naming prefix is `{name}_`).
    pub name: String,
    /// The object's body subtree, every name prefixed.
    pub body: Element,
    /// The assets it needs (`<asset>` element), names prefixed.
    pub assets: Element,
    /// Its element names without the prefix.
    pub names: ElementNames,
    /// From the root body to the object's bottom (robosuite's `bottom_offset`).
    pub bottom_offset: [f64; 3],
    /// From the root body to the object's top.
    pub top_offset: [f64; 3],
    /// The largest horizontal distance from the root body to the object's outline.
    pub horizontal_radius: f64,
    /// The primitive shape, for generated boxes and cylinders.
    pub shape: Option<Shape>,
}

impl ObjectModel {
    /// `raw` with the object's prefix.
    pub fn name_of(&self, raw: &str) -> String {
        format!("{}_{raw}", self.name)
    }

    /// The root body's full name (`{name}_main` for most objects).
    pub fn root_body(&self) -> String {
        self.name_of(&self.names.root_body)
    }

    /// The joints' full names.
    pub fn joints(&self) -> Vec<String> {
        self.names.joints.iter().map(|j| self.name_of(j)).collect()
    }

    /// The contact geoms' full names.
    pub fn contact_geoms(&self) -> Vec<String> {
        self.names
            .contact_geoms
            .iter()
            .map(|g| self.name_of(g))
            .collect()
    }

    /// The visual geoms' full names.
    pub fn visual_geoms(&self) -> Vec<String> {
        self.names
            .visual_geoms
            .iter()
            .map(|g| self.name_of(g))
            .collect()
    }

    /// The sites' full names.
    pub fn sites(&self) -> Vec<String> {
        self.names.sites.iter().map(|s| self.name_of(s)).collect()
    }

    /// The extent the placement samplers use.
    pub fn placement(&self) -> PlacedObject {
        PlacedObject {
            horizontal_radius: self.horizontal_radius,
            bottom_offset: self.bottom_offset[2],
            top_offset: self.top_offset[2],
        }
    }
}
