//! robosuite's `MujocoXMLObject`: objects read from robosuite's object files.

use super::{Joints, ObjectModel};
use crate::assets::Assets;
use crate::mjcf::tree::{self, append, array_to_string, attr, children, set_attr};
use crate::mjcf::{Element, ElementNames, MjcfDoc};
use crate::models::OBJECT_COLLISION_COLOR;
use gym_core::{Error, Result};
use xmltree::XMLNode;

/// Which geoms of an object file are kept (robosuite's `obj_type`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ObjType {
    /// Group-0 (collision) geoms only.
    Collision,
    /// Group-1 (visual) geoms only.
    Visual,
    /// Both.
    All,
}

impl ObjType {
    fn keeps(self, group: u32) -> bool {
        match self {
            Self::Collision => group == 0,
            Self::Visual => group == 1,
            Self::All => group <= 1,
        }
    }
}

/// robosuite's `MujocoXMLObject(file, name, joints, obj_type, duplicate_collision_geoms)`:
/// the body `object` of the file (renamed `main`), its geoms filtered by `obj_type`
/// (unnamed ones named `g{i}`), each kept collision geom recoloured and, with
/// `duplicate_collision_geoms`, doubled by a visual copy `{geom}_visual`; then its joints and
/// a `default_site`; every name prefixed `{name}_`. The extent comes from the file's
/// `bottom_site`, `top_site` and `horizontal_radius_site`.
///
/// # Errors
/// [`Error::Model`] when the file is missing or does not have robosuite's object layout.
pub fn xml_object(
    assets: &Assets,
    file: &str,
    name: &str,
    joints: &Joints,
    obj_type: ObjType,
    duplicate_collision_geoms: bool,
) -> Result<ObjectModel> {
    let path = assets.file(file)?;
    let mut doc = MjcfDoc::load(&path)?;
    let layout_error = |what: &str| Error::model(format!("{}: {what}", path.display()));
    let outer_idx = doc
        .worldbody()
        .children
        .iter()
        .position(|n| {
            n.as_element().is_some_and(|e| {
                e.name == "body"
                    && children(e).any(|c| c.name == "body" && attr(c, "name") == Some("object"))
            })
        })
        .ok_or_else(|| layout_error("no <body><body name=\"object\"> in the world body"))?;
    let outer = doc.worldbody_mut().children[outer_idx]
        .as_mut_element()
        .expect("found as an element");
    let obj_idx = outer
        .children
        .iter()
        .position(|n| {
            n.as_element()
                .is_some_and(|c| c.name == "body" && attr(c, "name") == Some("object"))
        })
        .expect("found above");
    let XMLNode::Element(mut obj) = outer.children.remove(obj_idx) else {
        unreachable!("found as an element")
    };
    set_attr(&mut obj, "name", "main");
    let mut counter = 0;
    filter_geoms(
        &mut obj,
        obj_type,
        duplicate_collision_geoms,
        &mut counter,
        &path,
    )?;
    for joint in joints.elements() {
        append(&mut obj, joint);
    }
    append(
        &mut obj,
        tree::element(
            "site",
            &[
                ("pos", "0 0 0".to_owned()),
                ("size", "0.002 0.002 0.002".to_owned()),
                ("rgba", "1 0 0 0".to_owned()),
                ("type", "sphere".to_owned()),
                ("group", "0".to_owned()),
                ("name", "default_site".to_owned()),
            ],
        ),
    );
    let names = ElementNames::sort(&mut obj, false, &path.display().to_string())?;
    let prefix = format!("{name}_");
    tree::add_prefix(&mut obj, &prefix, &|_| false);
    tree::add_prefix(doc.root_mut(), &prefix, &|_| false);
    let outer = doc.worldbody().children[outer_idx]
        .as_element()
        .expect("found as an element");
    let site_pos = |site: &str| -> Result<[f64; 3]> {
        let full = format!("{prefix}{site}");
        let s = children(outer)
            .find(|c| c.name == "site" && attr(c, "name") == Some(full.as_str()))
            .ok_or_else(|| layout_error(&format!("no site `{site}` beside the object body")))?;
        tree::attr_array(s, "pos", [0.0; 3])
    };
    let bottom_offset = site_pos("bottom_site")?;
    let top_offset = site_pos("top_site")?;
    let horizontal_radius = site_pos("horizontal_radius_site")?[0];
    Ok(ObjectModel {
        name: name.to_owned(),
        body: obj,
        assets: doc.section("asset").clone(),
        names,
        bottom_offset,
        top_offset,
        horizontal_radius,
        shape: None,
    })
}

/// The geom pass of `_get_object_subtree`: geoms in pre-order get index `i`; a geom outside
/// `obj_type` is removed, a kept one without a name is named `g{i}`, and a kept collision
/// geom is recoloured (material dropped) after its visual copy is appended to its parent.
fn filter_geoms(
    e: &mut Element,
    obj_type: ObjType,
    duplicate: bool,
    counter: &mut usize,
    path: &std::path::Path,
) -> Result<()> {
    let mut kept = Vec::with_capacity(e.children.len());
    let mut copies = Vec::new();
    for node in std::mem::take(&mut e.children) {
        let XMLNode::Element(mut c) = node else {
            kept.push(node);
            continue;
        };
        if c.name != "geom" {
            filter_geoms(&mut c, obj_type, duplicate, counter, path)?;
            kept.push(XMLNode::Element(c));
            continue;
        }
        let i = *counter;
        *counter += 1;
        let group: u32 = attr(&c, "group")
            .and_then(|g| g.parse().ok())
            .ok_or_else(|| {
                Error::model(format!(
                    "{}: object geom {i} has no numeric group (robosuite reads it as an integer)",
                    path.display()
                ))
            })?;
        if !obj_type.keeps(group) {
            continue;
        }
        if attr(&c, "name").is_none() {
            set_attr(&mut c, "name", format!("g{i}"));
        }
        if duplicate && attr(&c, "group") == Some("0") {
            let mut vis = c.clone();
            set_attr(&mut vis, "group", "1");
            set_attr(&mut vis, "conaffinity", "0");
            set_attr(&mut vis, "contype", "0");
            set_attr(&mut vis, "mass", "1e-8");
            let vis_name = format!("{}_visual", attr(&vis, "name").unwrap_or_default());
            set_attr(&mut vis, "name", vis_name);
            copies.push(XMLNode::Element(vis));
            set_attr(&mut c, "rgba", array_to_string(&OBJECT_COLLISION_COLOR));
            tree::remove_attr(&mut c, "material");
        }
        kept.push(XMLNode::Element(c));
    }
    kept.extend(copies);
    e.children = kept;
    Ok(())
}
