//! robosuite's generated composite objects (`models/objects/generated_objects.py`):
//! [`CompositeObject`], one body of primitive geoms (robosuite's `CompositeObject`), and
//! [`CompositeBodyObject`], other objects' bodies nested into one object (robosuite's
//! `CompositeBodyObject`). Both generate, element for element, the MJCF robosuite's Python
//! generates: the same elements in the same order with the same names and attributes
//! (collision geom plus `_vis` copy, joints, sites, `default_site`, materials, prefixes), and
//! the same extents for the placement samplers.

use super::{CustomMaterial, Joints, ObjType, ObjectModel, Shape};
use crate::mjcf::tree::{self, append, array_to_string, attr, element, format_number};
use crate::mjcf::{Element, ElementNames};
use crate::models::OBJECT_COLLISION_COLOR;
use gym_core::{Error, Result};
use std::collections::HashMap;

/// Something robosuite generates in code (a `MujocoGeneratedObject`): it builds into an
/// [`ObjectModel`] and knows its bounding box, which a [`CompositeBodyObject`] with
/// corner-relative locations needs.
pub trait GeneratedObject {
    /// Generates the object.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for figures robosuite would reject;
    /// [`Error::Model`] for an inconsistent element tree.
    fn build(&self) -> Result<ObjectModel>;

    /// robosuite's `get_bounding_box_half_size()` of the generated object `built`.
    fn bounding_box_half_size(&self, built: &ObjectModel) -> [f64; 3];
}

/// The MuJoCo geom primitives a [`CompositeObject`] can use.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GeomType {
    /// `box`: half-extents.
    Box,
    /// `sphere`: radius.
    Sphere,
    /// `capsule`: radius and half-length of the cylinder part.
    Capsule,
    /// `cylinder`: radius and half-height.
    Cylinder,
    /// `ellipsoid`: semi-axes.
    Ellipsoid,
}

impl GeomType {
    /// The MJCF type name.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Box => "box",
            Self::Sphere => "sphere",
            Self::Capsule => "capsule",
            Self::Cylinder => "cylinder",
            Self::Ellipsoid => "ellipsoid",
        }
    }

    /// The number of size values the type takes.
    fn size_len(self) -> usize {
        match self {
            Self::Box | Self::Ellipsoid => 3,
            Self::Sphere => 1,
            Self::Capsule | Self::Cylinder => 2,
        }
    }

    /// robosuite's `_size_to_cartesian_half_lengths`: the half-extents of the geom's box.
    fn cartesian_half_lengths(self, size: &[f64]) -> [f64; 3] {
        match self {
            Self::Box | Self::Ellipsoid => [size[0], size[1], size[2]],
            Self::Sphere => [size[0]; 3],
            Self::Capsule => [size[0], size[0], size[0] + size[1]],
            Self::Cylinder => [size[0], size[0], size[1]],
        }
    }
}

/// One geom of a [`CompositeObject`]: one entry of robosuite's per-geom lists.
#[derive(Debug, Clone, PartialEq)]
pub struct CompositeGeom {
    /// `geom_types`.
    pub geom_type: GeomType,
    /// `geom_sizes`.
    pub size: Vec<f64>,
    /// `geom_locations`: from the corner of the bounding box, or from its centre with
    /// [`CompositeObject::locations_relative_to_center`].
    pub location: [f64; 3],
    /// `geom_quats` (wxyz); `None` writes no `quat`.
    pub quat: Option<[f64; 4]>,
    /// `geom_names`; `None` names the geom `g{i}`.
    pub name: Option<String>,
    /// `geom_rgbas`: the visual geom's colour; `None` takes the object's `rgba`.
    pub rgba: Option<[f64; 4]>,
    /// `geom_materials`: the visual geom's material name (prefixed with the object's).
    pub material: Option<String>,
    /// `geom_frictions`; `None` writes MuJoCo's default `1.0 0.005 0.0001`.
    pub friction: Option<[f64; 3]>,
    /// `geom_condims`; `None` writes none.
    pub condim: Option<u32>,
    /// `obj_types`: which of the collision geom and its visual copy to generate.
    pub obj_type: ObjType,
    /// Per-geom density; `None` takes the object's [`CompositeObject::density`].
    pub density: Option<f64>,
    /// Per-geom solref; `None` takes the object's.
    pub solref: Option<[f64; 2]>,
    /// Per-geom solimp; `None` takes the object's.
    pub solimp: Option<[f64; 3]>,
}

impl CompositeGeom {
    /// A geom of `geom_type` and `size` at `location`, every other entry robosuite's `None`
    /// (and `obj_type` `all`).
    pub fn new(geom_type: GeomType, size: &[f64], location: [f64; 3]) -> Self {
        Self {
            geom_type,
            size: size.to_vec(),
            location,
            quat: None,
            name: None,
            rgba: None,
            material: None,
            friction: None,
            condim: None,
            obj_type: ObjType::All,
            density: None,
            solref: None,
            solimp: None,
        }
    }

    /// With a name.
    pub fn named(mut self, name: impl Into<String>) -> Self {
        self.name = Some(name.into());
        self
    }

    /// With a quaternion (wxyz).
    pub fn quat(mut self, quat: [f64; 4]) -> Self {
        self.quat = Some(quat);
        self
    }
}

/// A site of a generated object: robosuite's site dictionary, its attributes in the
/// dictionary's order. A key given with `None` is robosuite's `None` value: no attribute.
/// robosuite's `new_site` writes the other attributes, then `pos`, `size` and `rgba`
/// (defaults `0 0 0`, `0.005` and red when the key is absent), then `name`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SiteSpec {
    attrs: Vec<(&'static str, Option<String>)>,
}

impl SiteSpec {
    /// An unnamed site (named `site{n}` by the object).
    pub fn new() -> Self {
        Self::default()
    }

    /// A site named `name`.
    pub fn named(name: &str) -> Self {
        Self::new().with("name", name)
    }

    /// Sets an attribute.
    pub fn with(mut self, key: &'static str, value: impl Into<String>) -> Self {
        self.set(key, Some(value.into()));
        self
    }

    /// Sets an attribute to numbers (robosuite's `array_to_string`).
    pub fn with_numbers(self, key: &'static str, values: &[f64]) -> Self {
        self.with(key, array_to_string(values))
    }

    /// Gives `key` as robosuite's `None`: the site gets no such attribute.
    pub fn without(mut self, key: &'static str) -> Self {
        self.set(key, None);
        self
    }

    fn set(&mut self, key: &'static str, value: Option<String>) {
        match self.attrs.iter_mut().find(|(k, _)| *k == key) {
            Some(entry) => entry.1 = value,
            None => self.attrs.push((key, value)),
        }
    }

    fn has(&self, key: &str) -> bool {
        self.attrs.iter().any(|(k, _)| *k == key)
    }

    /// robosuite's `MujocoObject.get_site_attrib_template()` named `default_site`, with the
    /// generated objects' transparent red.
    fn default_site() -> Self {
        Self::new()
            .with("pos", "0 0 0")
            .with("size", "0.002 0.002 0.002")
            .with("rgba", "1 0 0 0")
            .with("type", "sphere")
            .with("group", "0")
            .with("name", "default_site")
    }

    /// robosuite's `new_site(**spec)`.
    fn element(&self) -> Element {
        let value = |key: &str, default: &str| -> Option<String> {
            match self.attrs.iter().find(|(k, _)| *k == key) {
                Some((_, v)) => v.clone(),
                None => Some(default.to_owned()),
            }
        };
        let mut attrs: Vec<(&str, String)> = self
            .attrs
            .iter()
            .filter(|(k, _)| !matches!(*k, "name" | "pos" | "size" | "rgba"))
            .filter_map(|(k, v)| v.clone().map(|v| (*k, v)))
            .collect();
        for (key, default) in [("pos", "0 0 0"), ("size", "0.005"), ("rgba", "1 0 0 1")] {
            if let Some(v) = value(key, default) {
                attrs.push((key, v));
            }
        }
        if let Some(Some(name)) = self
            .attrs
            .iter()
            .find(|(k, _)| *k == "name")
            .map(|(_, v)| v)
        {
            attrs.push(("name", name.clone()));
        }
        element("site", &attrs)
    }
}

/// The sites of a generated object: the given ones, then `default_site`; unnamed ones named
/// `site{n}` in order.
fn site_elements(sites: &[SiteSpec]) -> Vec<Element> {
    let mut n = 0;
    sites
        .iter()
        .cloned()
        .chain([SiteSpec::default_site()])
        .map(|mut s| {
            if !s.has("name") {
                s.set("name", Some(format!("site{n}")));
                n += 1;
            }
            s.element()
        })
        .collect()
}

/// The attribute lists of `joints` (robosuite's `"default"`: one free joint).
fn joint_specs(joints: &Joints) -> Vec<Vec<(&'static str, String)>> {
    match joints {
        Joints::Default => vec![vec![("type", "free".to_owned())]],
        Joints::None => Vec::new(),
        Joints::Specs(s) => s.clone(),
    }
}

/// A joint element: the spec's attributes, then `name` (robosuite's `new_joint`).
fn joint_element(spec: &[(&'static str, String)], name: String) -> Element {
    let mut attrs: Vec<(&str, String)> = spec
        .iter()
        .filter(|(k, _)| *k != "name")
        .map(|(k, v)| (*k, v.clone()))
        .collect();
    attrs.push(("name", name));
    element("joint", &attrs)
}

/// The top-level joints of a generated object: unnamed ones named `joint{n}`, counting only
/// the unnamed ones (robosuite's composite objects count so).
fn joint_elements(joints: &Joints) -> Vec<Element> {
    let mut n = 0;
    joint_specs(joints)
        .iter()
        .map(|spec| {
            let name = match spec.iter().find(|(k, _)| *k == "name") {
                Some((_, v)) => v.clone(),
                None => {
                    n += 1;
                    format!("joint{}", n - 1)
                }
            };
            joint_element(spec, name)
        })
        .collect()
}

/// robosuite's `MujocoGeneratedObject.append_material` over `materials` in order: each
/// texture and material is added unless a shared material of that name was added before,
/// and the assets are prefixed except for shared names.
fn material_assets(materials: &[CustomMaterial], prefix: &str) -> Element {
    let mut assets = Element::new("asset");
    let mut shared: Vec<String> = Vec::new();
    for m in materials {
        if !shared.iter().any(|s| s == m.material_name()) {
            for e in m.elements() {
                append(&mut assets, e);
            }
        }
        if m.shared {
            shared.push(m.material_name().to_owned());
            shared.push(m.texture_name().to_owned());
        }
        tree::add_prefix(&mut assets, prefix, &|v| shared.iter().any(|s| s == v));
    }
    assets
}

/// The end of `MujocoObject._get_object_properties` for a generated object: its element
/// names sorted, then every name under the body prefixed `{name}_`. The body is prefixed
/// before any material is appended, so shared material names are prefixed there too (as
/// robosuite does).
fn finish_body(body: &mut Element, name: &str) -> Result<ElementNames> {
    let names = ElementNames::sort(body, false, name)?;
    tree::add_prefix(body, &format!("{name}_"), &|_| false);
    Ok(names)
}

fn check_name(name: &str) -> Result<()> {
    if name.is_empty() {
        return Err(Error::invalid_argument(
            "name",
            "a generated object needs a name",
        ));
    }
    Ok(())
}

fn check_finite(what: &str, values: &[f64]) -> Result<()> {
    if values.iter().any(|v| !v.is_finite()) {
        return Err(Error::invalid_argument(
            what,
            format!("must be finite, got {values:?}"),
        ));
    }
    Ok(())
}

/// robosuite's `CompositeObject`: one body `root` holding the object's joints, its sites and
/// `default_site`, then per geom a collision geom (group 0, the object collision colour) and
/// a visual copy `{geom}_vis` (group 1, massless, no contacts, the geom's material and
/// colour), as its `obj_type` asks; every name prefixed `{name}_`, then the materials
/// appended to the assets (robosuite's subclasses append them after construction).
///
/// Extent: `bottom_offset = -total_size[2]`, `top_offset = total_size[2]`,
/// `horizontal_radius = ‖total_size[:2]‖`.
#[derive(Debug, Clone, PartialEq)]
pub struct CompositeObject {
    /// The object's name (its naming prefix is `{name}_`).
    pub name: String,
    /// Half-size of the bounding box.
    pub total_size: [f64; 3],
    /// The geoms, in order.
    pub geoms: Vec<CompositeGeom>,
    /// Colour of visual geoms without their own (`None`: no `rgba`).
    pub rgba: Option<[f64; 4]>,
    /// Density of collision geoms without their own (default 100; `None`: no `density`).
    pub density: Option<f64>,
    /// Solref of geoms without their own (default `(0.02, 1.0)`).
    pub solref: [f64; 2],
    /// Solimp of geoms without their own (default `(0.9, 0.95, 0.001)`).
    pub solimp: [f64; 3],
    /// Geom locations from the centre of the bounding box instead of its lower corner.
    pub locations_relative_to_center: bool,
    /// The joints (default: one free joint).
    pub joints: Joints,
    /// Sites besides `default_site`.
    pub sites: Vec<SiteSpec>,
    /// Materials appended after construction, in order.
    pub materials: Vec<CustomMaterial>,
}

impl CompositeObject {
    /// A composite object with robosuite's defaults and no geoms yet.
    pub fn new(name: &str, total_size: [f64; 3]) -> Self {
        Self {
            name: name.to_owned(),
            total_size,
            geoms: Vec::new(),
            rgba: None,
            density: Some(100.0),
            solref: [0.02, 1.0],
            solimp: [0.9, 0.95, 0.001],
            locations_relative_to_center: false,
            joints: Joints::Default,
            sites: Vec::new(),
            materials: Vec::new(),
        }
    }

    /// A composite object whose geom locations are from the centre of its bounding box,
    /// with this density and these solver figures (how robosuite's composite classes call
    /// their base class).
    pub fn centred(
        name: &str,
        total_size: [f64; 3],
        density: f64,
        solref: [f64; 2],
        solimp: [f64; 3],
    ) -> Self {
        Self {
            density: Some(density),
            solref,
            solimp,
            locations_relative_to_center: true,
            ..Self::new(name, total_size)
        }
    }

    fn validate(&self) -> Result<()> {
        check_name(&self.name)?;
        check_finite("total_size", &self.total_size)?;
        for (i, g) in self.geoms.iter().enumerate() {
            if g.size.len() != g.geom_type.size_len() {
                return Err(Error::invalid_argument(
                    "geom_sizes",
                    format!(
                        "{}: geom {i} ({}) needs {} size values, got {}",
                        self.name,
                        g.geom_type.as_str(),
                        g.geom_type.size_len(),
                        g.size.len()
                    ),
                ));
            }
            check_finite("geom_sizes", &g.size)?;
            check_finite("geom_locations", &g.location)?;
        }
        Ok(())
    }

    /// The geom elements of geom `i` (collision, then visual, as its `obj_type` asks).
    fn geom_elements(&self, i: usize, g: &CompositeGeom) -> Vec<Element> {
        let half = g.geom_type.cartesian_half_lengths(&g.size);
        let pos = if self.locations_relative_to_center {
            g.location
        } else {
            std::array::from_fn(|k| (-self.total_size[k] + half[k]) + g.location[k])
        };
        let name = g.name.clone().unwrap_or_else(|| format!("g{i}"));
        let quat = g.quat.map(|q| ("quat", array_to_string(&q)));
        // robosuite's `new_geom` writes the remaining attributes, then type, size, pos,
        // group and name.
        let tail = |group: &str, name: String| {
            [
                ("type", g.geom_type.as_str().to_owned()),
                ("size", array_to_string(&g.size)),
                ("pos", array_to_string(&pos)),
                ("group", group.to_owned()),
                ("name", name),
            ]
        };
        let mut out = Vec::with_capacity(2);
        if matches!(g.obj_type, ObjType::Collision | ObjType::All) {
            let mut attrs: Vec<(&str, String)> = quat.iter().cloned().collect();
            attrs.push(("rgba", array_to_string(&OBJECT_COLLISION_COLOR)));
            if let Some(d) = g.density.or(self.density) {
                attrs.push(("density", format_number(d)));
            }
            let friction = g.friction.unwrap_or([1.0, 0.005, 0.0001]);
            attrs.push(("friction", array_to_string(&friction)));
            attrs.push(("solref", array_to_string(&g.solref.unwrap_or(self.solref))));
            attrs.push(("solimp", array_to_string(&g.solimp.unwrap_or(self.solimp))));
            if let Some(c) = g.condim {
                attrs.push(("condim", c.to_string()));
            }
            attrs.extend(tail("0", name.clone()));
            out.push(element("geom", &attrs));
        }
        if matches!(g.obj_type, ObjType::Visual | ObjType::All) {
            let mut attrs: Vec<(&str, String)> = quat.iter().cloned().collect();
            attrs.push(("conaffinity", "0".to_owned()));
            attrs.push(("contype", "0".to_owned()));
            attrs.push(("mass", "1e-8".to_owned()));
            if let Some(m) = &g.material {
                attrs.push(("material", m.clone()));
            }
            if let Some(rgba) = g.rgba.or(self.rgba) {
                attrs.push(("rgba", array_to_string(&rgba)));
            }
            attrs.extend(tail("1", format!("{name}_vis")));
            out.push(element("geom", &attrs));
        }
        out
    }
}

impl GeneratedObject for CompositeObject {
    fn build(&self) -> Result<ObjectModel> {
        self.validate()?;
        let mut body = element(
            "body",
            &[("pos", "0 0 0".to_owned()), ("name", "root".to_owned())],
        );
        for e in joint_elements(&self.joints) {
            append(&mut body, e);
        }
        for e in site_elements(&self.sites) {
            append(&mut body, e);
        }
        for (i, g) in self.geoms.iter().enumerate() {
            for e in self.geom_elements(i, g) {
                append(&mut body, e);
            }
        }
        let names = finish_body(&mut body, &self.name)?;
        let [x, y, z] = self.total_size;
        Ok(ObjectModel {
            name: self.name.clone(),
            body,
            assets: material_assets(&self.materials, &format!("{}_", self.name)),
            names,
            bottom_offset: [0.0, 0.0, -z],
            top_offset: [0.0, 0.0, z],
            horizontal_radius: (x * x + y * y).sqrt(),
            shape: None,
        })
    }

    fn bounding_box_half_size(&self, _built: &ObjectModel) -> [f64; 3] {
        self.total_size
    }
}

impl GeneratedObject for super::primitive::Primitive {
    fn build(&self) -> Result<ObjectModel> {
        super::primitive::Primitive::build(self)
    }

    fn bounding_box_half_size(&self, _built: &ObjectModel) -> [f64; 3] {
        match self.shape {
            Shape::Box(s) => s,
            Shape::Cylinder([r, h]) => [r, r, h],
        }
    }
}

/// The figures robosuite's shell-like composites (`HollowCylinderObject`, `ConeObject`)
/// give each of their geoms, with those classes' defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct ShellStyle {
    /// Colour of the visual geoms (`None`: none).
    pub rgba: Option<[f64; 4]>,
    /// Material of the visual geoms (appended to the assets).
    pub material: Option<CustomMaterial>,
    /// Density (default 1000).
    pub density: f64,
    /// Solref (default `(0.02, 1.0)`).
    pub solref: [f64; 2],
    /// Solimp (default `(0.9, 0.95, 0.001)`).
    pub solimp: [f64; 3],
    /// Friction (`None`: MuJoCo's default).
    pub friction: Option<[f64; 3]>,
}

impl Default for ShellStyle {
    fn default() -> Self {
        Self {
            rgba: None,
            material: None,
            density: 1000.0,
            solref: [0.02, 1.0],
            solimp: [0.9, 0.95, 0.001],
            friction: None,
        }
    }
}

impl ShellStyle {
    /// A geom named `name` as these classes add it: the style's colour, material and
    /// friction, condim 4.
    pub fn geom(&self, geom: CompositeGeom, name: String) -> CompositeGeom {
        let mut g = geom.named(name);
        g.rgba = self.rgba;
        g.material = self.material.as_ref().map(|m| m.material_name().to_owned());
        g.friction = self.friction;
        g.condim = Some(4);
        g
    }

    /// The composite object these classes make of `geoms`: locations from the centre, the
    /// style's density and solver figures, the red site `center` at the origin, the material
    /// appended.
    pub fn composite(
        &self,
        name: &str,
        total_size: [f64; 3],
        geoms: Vec<CompositeGeom>,
    ) -> CompositeObject {
        let mut c =
            CompositeObject::centred(name, total_size, self.density, self.solref, self.solimp);
        c.geoms = geoms;
        c.sites = vec![
            SiteSpec::named("center")
                .with("pos", "0 0 0")
                .with("size", "0.002")
                .with("rgba", "1 0 0 1")
                .with("type", "sphere"),
        ];
        c.materials = self.material.iter().cloned().collect();
        c
    }
}

/// One object of a [`CompositeBodyObject`] (one entry of robosuite's `objects`,
/// `object_locations`, `object_quats` and `object_parents`).
#[derive(Debug, Clone)]
pub struct BodyPart {
    /// The generated object.
    pub object: ObjectModel,
    /// Its bounding box half size (robosuite's `get_bounding_box_half_size()`).
    pub half_size: [f64; 3],
    /// Its location in its parent body (from the lower corner of the composite's
    /// `total_size` box with [`CompositeBodyObject::locations_relative_to_corner`]).
    pub location: [f64; 3],
    /// Its orientation in its parent body (wxyz; `None`: identity).
    pub quat: Option<[f64; 4]>,
    /// The body it is appended to, by its name inside the composite before the composite's
    /// prefix (such as `hole1_root`); `None`: the composite's `root`.
    pub parent: Option<String>,
}

impl BodyPart {
    /// Generates `object` as a part at `location`, in the root body, unrotated.
    ///
    /// # Errors
    /// As [`GeneratedObject::build`].
    pub fn of(object: &dyn GeneratedObject, location: [f64; 3]) -> Result<Self> {
        let built = object.build()?;
        let half_size = object.bounding_box_half_size(&built);
        Ok(Self {
            object: built,
            half_size,
            location,
            quat: None,
            parent: None,
        })
    }

    /// With an orientation (wxyz).
    pub fn rotated(mut self, quat: [f64; 4]) -> Self {
        self.quat = Some(quat);
        self
    }

    /// Appended to the body `parent` instead of the root.
    pub fn under(mut self, parent: &str) -> Self {
        self.parent = Some(parent.to_owned());
        self
    }
}

/// robosuite's `CompositeBodyObject`: a body `root` holding the object's joints, its sites
/// and `default_site`, then each part's body (its own top-level joints removed, `pos` and
/// `quat` set) appended to its parent, then the extra joints of `body_joints`; the parts'
/// assets merged (first of each tag and name kept); every name prefixed `{name}_`.
///
/// Extent, accumulated over the parts as robosuite's `_append_object` does from each part's
/// position relative to the root: `top_offset` the highest part top (at least 0),
/// `bottom_offset` the lowest part bottom (at most 0), `horizontal_radius` the largest
/// `max(x, y) + part radius` (at least 0).
#[derive(Debug, Clone)]
pub struct CompositeBodyObject {
    /// The object's name.
    pub name: String,
    /// The parts, in order (a part nested in another comes after it).
    pub parts: Vec<BodyPart>,
    /// The root body's joints (robosuite's default: one free joint).
    pub joints: Joints,
    /// Extra joints per body (by name inside the composite, such as `hole1_root`); unnamed
    /// ones are named `{body}_joint{i}`.
    pub body_joints: Vec<(String, Joints)>,
    /// Sites of the root body besides `default_site`.
    pub sites: Vec<SiteSpec>,
    /// The bounding box half size, if given.
    pub total_size: Option<[f64; 3]>,
    /// Part locations from the lower corner of `total_size` instead of the parent's origin.
    pub locations_relative_to_corner: bool,
}

impl CompositeBodyObject {
    /// A composite body of `parts` with robosuite's defaults (a free joint, no extra sites,
    /// no bounding box).
    pub fn new(name: &str, parts: Vec<BodyPart>) -> Self {
        Self {
            name: name.to_owned(),
            parts,
            joints: Joints::Default,
            body_joints: Vec::new(),
            sites: Vec::new(),
            total_size: None,
            locations_relative_to_corner: false,
        }
    }

    /// Generates the object.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a parent or body that is not in the object, corner
    /// locations without `total_size`, or non-finite figures.
    pub fn generate(&self) -> Result<ObjectModel> {
        check_name(&self.name)?;
        let corner = match (self.locations_relative_to_corner, self.total_size) {
            (false, _) => None,
            (true, Some(t)) => Some(t),
            (true, None) => {
                return Err(Error::invalid_argument(
                    "locations_relative_to_corner",
                    format!("{}: corner-relative locations need total_size", self.name),
                ));
            }
        };
        let mut root = element(
            "body",
            &[("pos", "0 0 0".to_owned()), ("name", "root".to_owned())],
        );
        for e in joint_elements(&self.joints) {
            append(&mut root, e);
        }
        for e in site_elements(&self.sites) {
            append(&mut root, e);
        }
        let mut assets = Element::new("asset");
        let mut absolute: HashMap<String, [f64; 3]> =
            HashMap::from([("root".to_owned(), [0.0; 3])]);
        let (mut top, mut bottom, mut horizontal) = (0.0f64, 0.0f64, 0.0f64);
        for part in &self.parts {
            check_finite("object_locations", &part.location)?;
            let parent_name = part.parent.as_deref().unwrap_or("root");
            let missing = || {
                Error::invalid_argument(
                    "object_parents",
                    format!(
                        "{}: no body `{parent_name}` to append `{}` to",
                        self.name, part.object.name
                    ),
                )
            };
            let parent_pos = *absolute.get(parent_name).ok_or_else(missing)?;
            let mut child = part.object.body.clone();
            tree::take_children(&mut child, |e| e.name == "joint");
            let pos: [f64; 3] = match corner {
                Some(t) => std::array::from_fn(|k| (-t[k] + part.half_size[k]) + part.location[k]),
                None => part.location,
            };
            tree::set_attr(&mut child, "pos", array_to_string(&pos));
            tree::set_attr(
                &mut child,
                "quat",
                array_to_string(&part.quat.unwrap_or([1.0, 0.0, 0.0, 0.0])),
            );
            merge_assets(&mut assets, &part.object.assets);
            tree::find_mut(&mut root, "body", &[("name", Some(parent_name))])
                .ok_or_else(missing)?
                .children
                .push(xmltree::XMLNode::Element(child));
            let abs: [f64; 3] = std::array::from_fn(|k| parent_pos[k] + pos[k]);
            absolute.insert(part.object.root_body(), abs);
            top = top.max(abs[2] + part.object.top_offset[2]);
            bottom = bottom.min(abs[2] + part.object.bottom_offset[2]);
            horizontal = horizontal.max(abs[0].max(abs[1]) + part.object.horizontal_radius);
        }
        for (body_name, joints) in &self.body_joints {
            let body = tree::find_mut(&mut root, "body", &[("name", Some(body_name))]).ok_or_else(
                || {
                    Error::invalid_argument(
                        "body_joints",
                        format!("{}: no body `{body_name}` for joints", self.name),
                    )
                },
            )?;
            for (i, spec) in joint_specs(joints).iter().enumerate() {
                let name = spec
                    .iter()
                    .find(|(k, _)| *k == "name")
                    .map_or_else(|| format!("{body_name}_joint{i}"), |(_, v)| v.clone());
                append(body, joint_element(spec, name));
            }
        }
        let names = finish_body(&mut root, &self.name)?;
        tree::add_prefix(&mut assets, &format!("{}_", self.name), &|_| false);
        Ok(ObjectModel {
            name: self.name.clone(),
            body: root,
            assets,
            names,
            bottom_offset: [0.0, 0.0, bottom],
            top_offset: [0.0, 0.0, top],
            horizontal_radius: horizontal,
            shape: None,
        })
    }
}

impl GeneratedObject for CompositeBodyObject {
    fn build(&self) -> Result<ObjectModel> {
        self.generate()
    }

    /// `total_size` if given, else `MujocoGeneratedObject`'s `[r, r, 0] − bottom_offset`.
    fn bounding_box_half_size(&self, built: &ObjectModel) -> [f64; 3] {
        self.total_size.unwrap_or([
            built.horizontal_radius,
            built.horizontal_radius,
            0.0 - built.bottom_offset[2],
        ])
    }
}

/// robosuite's `MujocoObject.merge_assets`: appends each asset of `from` unless `into`
/// already holds an element of that tag and name.
fn merge_assets(into: &mut Element, from: &Element) {
    for asset in tree::children(from) {
        if tree::find(into, &asset.name, &[("name", attr(asset, "name"))]).is_none() {
            append(into, asset.clone());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::cone::Cone;
    use super::super::hollow_cylinder::HollowCylinder;
    use super::super::primitive::Primitive;
    use super::super::robosuite_expected::assert_matches_robosuite;
    use super::*;
    use crate::assets::Assets;

    fn wood(assets: &Assets) -> CustomMaterial {
        CustomMaterial::new(
            assets,
            "WoodRed",
            "wood",
            "wood_mat",
            &[("type", "cube")],
            &[("texrepeat", "1 1")],
            false,
        )
        .unwrap()
    }

    fn check(key: &str, object: &dyn GeneratedObject) {
        let built = object.build().unwrap();
        let half = object.bounding_box_half_size(&built);
        assert_matches_robosuite(key, &built, half);
    }

    /// Every per-geom option: corner-relative locations, each geom type, collision-only and
    /// visual-only geoms, unnamed geoms and sites, per-geom densities, a site given
    /// without colour, unnamed joints among named ones, and a shared material appended
    /// twice (robosuite prefixes its name in the body but not in the assets).
    #[test]
    fn composite_object_matches_robosuite() {
        let assets = Assets::locate().unwrap();
        let metal = CustomMaterial::new(
            &assets,
            "Metal",
            "metal",
            "metal_mat",
            &[("type", "cube")],
            &[],
            true,
        )
        .unwrap();
        let mut c = CompositeObject::new("small", [0.05, 0.04, 0.03]);
        let geom = |t, size: &[f64], loc| CompositeGeom::new(t, size, loc);
        let mut a = geom(GeomType::Box, &[0.01, 0.02, 0.005], [0.0; 3])
            .quat([1.0, 0.0, 0.0, 0.0])
            .named("a");
        a.material = Some("wood_mat".into());
        a.density = Some(500.0);
        let mut b = geom(GeomType::Cylinder, &[0.01, 0.004], [0.02, 0.01, 0.0]);
        b.rgba = Some([0.1, 0.2, 0.3, 1.0]);
        b.friction = Some([0.5, 0.01, 0.001]);
        b.obj_type = ObjType::Collision;
        b.density = Some(600.0);
        let mut g = geom(GeomType::Sphere, &[0.007], [0.03, 0.003, 0.01])
            .quat([0.5; 4])
            .named("c");
        g.material = Some("metal_mat".into());
        g.condim = Some(4);
        g.obj_type = ObjType::Visual;
        let mut d = geom(GeomType::Capsule, &[0.003, 0.01], [0.0, 0.05, 0.02]);
        d.condim = Some(3);
        d.density = Some(700.0);
        let mut e = geom(GeomType::Ellipsoid, &[0.01, 0.011, 0.012], [0.1, 0.0, 0.0]).named("e");
        e.rgba = Some([1.0, 1.0, 0.0, 0.5]);
        e.density = Some(800.0);
        c.geoms = vec![a, b, g, d, e];
        c.rgba = Some([0.9, 0.8, 0.7, 1.0]);
        c.density = None;
        c.solref = [0.01, 0.5];
        c.solimp = [0.95, 0.99, 0.002];
        c.joints = Joints::Specs(vec![
            vec![("type", "slide".into()), ("axis", "1 0 0".into())],
            vec![("name", "spin".into()), ("type", "hinge".into())],
            vec![("type", "hinge".into()), ("axis", "0 1 0".into())],
        ]);
        c.sites = vec![
            SiteSpec::named("top")
                .with("pos", "0 0 0.03")
                .with("size", "0.002")
                .with("type", "sphere"),
            SiteSpec::new().with("pos", "0.01 0 0").without("rgba"),
            SiteSpec::new().with("size", "0.1 0.2").with("group", "2"),
        ];
        c.materials = vec![wood(&assets), metal.clone(), metal];
        check("small", &c);
    }

    #[test]
    fn hollow_cylinder_and_cone_match_robosuite() {
        let assets = Assets::locate().unwrap();
        let mut hc = HollowCylinder::new("hc");
        hc.outer_radius = 0.03;
        hc.inner_radius = 0.02;
        hc.height = 0.01;
        hc.ngeoms = 6;
        hc.make_half = true;
        hc.style.material = Some(wood(&assets));
        hc.style.friction = Some([0.9, 0.1, 0.01]);
        hc.style.rgba = Some([0.2, 0.2, 0.2, 1.0]);
        check("hollow", &hc);
        let mut cone = Cone::new("cone");
        cone.outer_radius = 0.02;
        cone.inner_radius = 0.005;
        cone.height = 0.03;
        cone.ngeoms = 4;
        cone.style.rgba = Some([0.5, 0.5, 0.5, 1.0]);
        check("cone", &cone);
    }

    fn parts(assets: &Assets) -> (Primitive, HollowCylinder) {
        let mut b = Primitive::new("box", Shape::Box([0.02, 0.03, 0.01]));
        b.material = Some(wood(assets));
        b.density = 300.0;
        let mut ring = HollowCylinder::new("ring");
        ring.outer_radius = 0.02;
        ring.inner_radius = 0.015;
        ring.height = 0.005;
        ring.ngeoms = 4;
        ring.style.material = Some(wood(assets));
        (b, ring)
    }

    /// Nested parts, corner-relative locations, a rotated part, extra body joints (one
    /// named by robosuite's rule, one default free joint), no root joint and a root site.
    #[test]
    fn composite_body_object_matches_robosuite() {
        let assets = Assets::locate().unwrap();
        let (b, ring) = parts(&assets);
        let mut lid = Primitive::new("lid", Shape::Box([0.01, 0.01, 0.002]));
        lid.rgba = [0.0, 1.0, 0.0, 1.0];
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let mut c = CompositeBodyObject::new(
            "group",
            vec![
                BodyPart::of(&b, [0.0; 3]).unwrap(),
                BodyPart::of(&ring, [0.01, -0.02, 0.03])
                    .unwrap()
                    .rotated([h, 0.0, h, 0.0])
                    .under("box_main"),
                BodyPart::of(&lid, [0.005, 0.0, 0.001]).unwrap(),
            ],
        );
        c.joints = Joints::None;
        c.body_joints = vec![
            (
                "ring_root".into(),
                Joints::Specs(vec![vec![
                    ("type", "hinge".into()),
                    ("axis", "0 0 1".into()),
                ]]),
            ),
            ("box_main".into(), Joints::Default),
        ];
        c.sites = vec![SiteSpec::named("mark").with_numbers("pos", &[0.0, 0.0, 0.05])];
        c.total_size = Some([0.06, 0.05, 0.04]);
        c.locations_relative_to_corner = true;
        check("body", &c);

        let (b, ring) = parts(&assets);
        let pair = CompositeBodyObject::new(
            "pair",
            vec![
                BodyPart::of(&b, [0.0, 0.01, -0.02]).unwrap(),
                BodyPart::of(&ring, [-0.05, 0.0, 0.01]).unwrap(),
            ],
        );
        check("body_default", &pair);
    }

    #[test]
    fn invalid_figures_are_rejected() {
        let mut c = CompositeObject::new("bad", [0.1; 3]);
        c.geoms = vec![CompositeGeom::new(GeomType::Box, &[0.1, 0.1], [0.0; 3])];
        assert!(matches!(c.build(), Err(Error::InvalidArgument { .. })));
        c.geoms = vec![CompositeGeom::new(GeomType::Sphere, &[f64::NAN], [0.0; 3])];
        assert!(matches!(c.build(), Err(Error::InvalidArgument { .. })));
        let b = Primitive::new("b", Shape::Box([0.01; 3]));
        let part = BodyPart::of(&b, [0.0; 3]).unwrap();
        let mut body = CompositeBodyObject::new("g", vec![part.clone().under("nowhere")]);
        assert!(matches!(
            body.generate(),
            Err(Error::InvalidArgument { .. })
        ));
        body.parts = vec![part];
        body.locations_relative_to_corner = true;
        assert!(matches!(
            body.generate(),
            Err(Error::InvalidArgument { .. })
        ));
        body.locations_relative_to_corner = false;
        body.body_joints = vec![("missing".into(), Joints::Default)];
        assert!(matches!(
            body.generate(),
            Err(Error::InvalidArgument { .. })
        ));
    }
}
