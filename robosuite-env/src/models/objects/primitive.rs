//! robosuite's `PrimitiveObject`s: `BoxObject` and `CylinderObject`, generated from their
//! figures as robosuite generates them.

use super::{CustomMaterial, Joints, ObjType, ObjectModel, Shape};
use crate::mjcf::tree::{self, append, array_to_string, element};
use crate::mjcf::{Element, ElementNames};
use crate::models::OBJECT_COLLISION_COLOR;
use gym_core::{Error, Result};

/// The figures of a primitive object (robosuite's `PrimitiveObject` arguments; `None` takes
/// robosuite's default for the shape).
#[derive(Debug, Clone, PartialEq)]
pub struct Primitive {
    /// The object's name.
    pub name: String,
    /// The shape and its size.
    pub shape: Shape,
    /// Colour of the visual geom when there is no material (default red).
    pub rgba: [f64; 4],
    /// Density (default 1000).
    pub density: f64,
    /// Friction (box default `(1, 0.005, 0.0001)`, cylinder `(1, 0.01, 0.001)`).
    pub friction: Option<[f64; 3]>,
    /// Contact solref (box default `(0.02, 1)`, cylinder `(0.01, 0.5)`).
    pub solref: Option<[f64; 2]>,
    /// Contact solimp (default `(0.9, 0.95, 0.001)`).
    pub solimp: [f64; 3],
    /// The visual material.
    pub material: Option<CustomMaterial>,
    /// Joints (box default: one free joint; cylinder: a free joint with damping 0.0001).
    pub joints: Option<Joints>,
    /// Which geoms to generate.
    pub obj_type: ObjType,
}

impl Primitive {
    /// A primitive with robosuite's defaults.
    pub fn new(name: &str, shape: Shape) -> Self {
        Self {
            name: name.to_owned(),
            shape,
            rgba: [1.0, 0.0, 0.0, 1.0],
            density: 1000.0,
            friction: None,
            solref: None,
            solimp: [0.9, 0.95, 0.001],
            material: None,
            joints: None,
            obj_type: ObjType::All,
        }
    }

    /// Builds the object: body `main` with the collision geom `g0` (group 0) and the visual
    /// geom `g0_vis` (group 1), its joints and `default_site`, names prefixed `{name}_`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a non-positive or non-finite size.
    pub fn build(&self) -> Result<ObjectModel> {
        let (kind, size): (&str, Vec<f64>) = match self.shape {
            Shape::Box(s) => ("box", s.to_vec()),
            Shape::Cylinder(s) => ("cylinder", s.to_vec()),
        };
        if size.iter().any(|v| !v.is_finite() || *v <= 0.0) {
            return Err(Error::invalid_argument(
                "size",
                format!(
                    "{} size must be positive and finite, got {size:?}",
                    self.name
                ),
            ));
        }
        let cylinder = matches!(self.shape, Shape::Cylinder(_));
        let friction = self.friction.unwrap_or(if cylinder {
            [1.0, 0.01, 0.001]
        } else {
            [1.0, 0.005, 0.0001]
        });
        let solref = self
            .solref
            .unwrap_or(if cylinder { [0.01, 0.5] } else { [0.02, 1.0] });
        let joints = self.joints.clone().unwrap_or(if cylinder {
            Joints::free_with_damping("0.0001")
        } else {
            Joints::Default
        });
        let prefix = format!("{}_", self.name);
        let shared: Vec<String> = self
            .material
            .iter()
            .filter(|m| m.shared)
            .flat_map(|m| [m.material_name().to_owned(), m.texture_name().to_owned()])
            .collect();
        let exclude = |v: &str| shared.iter().any(|s| s == v);

        let mut assets = Element::new("asset");
        if let Some(m) = &self.material {
            for e in m.elements() {
                append(&mut assets, e);
            }
            tree::add_prefix(&mut assets, &prefix, &exclude);
        }

        let mut body = element(
            "body",
            &[("name", "main".to_owned()), ("pos", "0 0 0".to_owned())],
        );
        let size = array_to_string(&size);
        if matches!(self.obj_type, ObjType::Collision | ObjType::All) {
            let mut attrs = vec![
                ("name", "g0".to_owned()),
                ("type", kind.to_owned()),
                ("size", size.clone()),
                ("pos", "0 0 0".to_owned()),
                ("group", "0".to_owned()),
                ("rgba", array_to_string(&OBJECT_COLLISION_COLOR)),
            ];
            if cylinder {
                attrs.push(("margin", "0.001".to_owned()));
            }
            attrs.extend([
                ("density", tree::format_number(self.density)),
                ("friction", array_to_string(&friction)),
                ("solref", array_to_string(&solref)),
                ("solimp", array_to_string(&self.solimp)),
            ]);
            append(&mut body, element("geom", &attrs));
        }
        if matches!(self.obj_type, ObjType::Visual | ObjType::All) {
            let mut attrs = vec![
                ("name", "g0_vis".to_owned()),
                ("type", kind.to_owned()),
                ("size", size),
                ("pos", "0 0 0".to_owned()),
                ("conaffinity", "0".to_owned()),
                ("contype", "0".to_owned()),
                ("mass", "1e-8".to_owned()),
                ("group", "1".to_owned()),
            ];
            match &self.material {
                Some(m) => attrs.push(("material", m.material_name().to_owned())),
                None => attrs.push(("rgba", array_to_string(&self.rgba))),
            }
            append(&mut body, element("geom", &attrs));
        }
        for joint in joints.elements() {
            append(&mut body, joint);
        }
        append(
            &mut body,
            element(
                "site",
                &[
                    ("name", "default_site".to_owned()),
                    ("rgba", "1 0 0 1".to_owned()),
                    ("pos", "0 0 0".to_owned()),
                    ("size", "0.002 0.002 0.002".to_owned()),
                    ("type", "sphere".to_owned()),
                    ("group", "0".to_owned()),
                ],
            ),
        );
        let names = ElementNames::sort(&mut body, false, &self.name)?;
        tree::add_prefix(&mut body, &prefix, &exclude);
        let (bottom, top, radius) = match self.shape {
            Shape::Box(s) => (-s[2], s[2], (s[0] * s[0] + s[1] * s[1]).sqrt()),
            Shape::Cylinder(s) => (-s[1], s[1], s[0]),
        };
        Ok(ObjectModel {
            name: self.name.clone(),
            body,
            assets,
            names,
            bottom_offset: [0.0, 0.0, bottom],
            top_offset: [0.0, 0.0, top],
            horizontal_radius: radius,
            shape: Some(self.shape),
        })
    }
}
