//! [`MjcfDoc`]: one MJCF document as robosuite's `MujocoXML` holds it.

use super::tree::{self, append, attr, child, children, children_mut, set_attr};
use crate::assets::read_file;
use gym_core::{Error, Result};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use xmltree::{Element, EmitterConfig, ParserConfig};

/// The sections every document gets (created empty at the end when missing), in
/// robosuite's order.
const SECTIONS: [&str; 7] = [
    "worldbody",
    "actuator",
    "sensor",
    "asset",
    "tendon",
    "equality",
    "contact",
];

/// Where [`MjcfDoc::merge`] puts the other document's top-level bodies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MergeBody<'a> {
    /// Into this document's `<worldbody>` (robosuite's `merge_body="default"`).
    World,
    /// Into the first body with this (full) name.
    Body(&'a str),
    /// Nowhere: only assets, actuators, sensors, tendons, equalities and contacts merge.
    None,
}

/// An MJCF document processed as robosuite's `MujocoXML.__init__` does:
/// * the sections `worldbody`, `actuator`, `sensor`, `asset`, `tendon`, `equality` and
///   `contact` exist (created empty at the end when missing);
/// * default classes are written into the elements that use them (an attribute the element
///   sets itself wins) and `<default>` is removed; as in robosuite, only the top-level
///   `<default class="...">` entries count, and defaults outside a class are dropped;
/// * asset `file` paths are absolute (joined to the document's folder).
#[derive(Debug, Clone)]
pub struct MjcfDoc {
    root: Element,
    file: PathBuf,
}

impl MjcfDoc {
    /// Loads and processes the MJCF file at `path`.
    ///
    /// # Errors
    /// [`Error::Model`] when the file is missing, unreadable or malformed, or uses a default
    /// class it does not define.
    pub fn load(path: &Path) -> Result<Self> {
        let text = read_file(path)?;
        Self::parse(&text, path)
    }

    /// Processes MJCF text as if read from `path` (relative asset paths resolve against its
    /// folder).
    ///
    /// # Errors
    /// As [`MjcfDoc::load`].
    pub fn parse(text: &str, path: &Path) -> Result<Self> {
        let config = ParserConfig::new()
            .ignore_comments(true)
            .trim_whitespace(true);
        let mut root = Element::parse_with_config(text.as_bytes(), config)
            .map_err(|e| Error::model(format!("{} is not valid XML: {e}", path.display())))?;
        if root.name != "mujoco" {
            return Err(Error::model(format!(
                "{} is not an MJCF file (its root element is <{}>, not <mujoco>)",
                path.display(),
                root.name
            )));
        }
        for name in SECTIONS {
            if child(&root, name).is_none() {
                append(&mut root, Element::new(name));
            }
        }
        inline_defaults(&mut root, path)?;
        let folder = path.parent().map(Path::to_path_buf).unwrap_or_default();
        let folder = std::path::absolute(&folder).unwrap_or(folder);
        if let Some(asset) = tree::child_mut(&mut root, "asset") {
            for node in children_mut(asset) {
                if let Some(file) = attr(node, "file") {
                    let full = folder.join(file);
                    set_attr(node, "file", full.to_string_lossy().into_owned());
                }
            }
        }
        Ok(Self {
            root,
            file: path.to_path_buf(),
        })
    }

    /// The file the document was read from.
    pub fn file(&self) -> &Path {
        &self.file
    }

    /// The `<mujoco>` element.
    pub fn root(&self) -> &Element {
        &self.root
    }

    /// The `<mujoco>` element, mutably.
    pub fn root_mut(&mut self) -> &mut Element {
        &mut self.root
    }

    /// One of the sections every document has (`worldbody`, `asset`, ...).
    ///
    /// # Panics
    /// If `name` is not one of those sections (a programming error).
    pub fn section(&self, name: &str) -> &Element {
        assert!(SECTIONS.contains(&name), "`{name}` is not an MJCF section");
        child(&self.root, name).expect("sections are created at load")
    }

    /// A section, mutably.
    ///
    /// # Panics
    /// As [`MjcfDoc::section`].
    pub fn section_mut(&mut self, name: &str) -> &mut Element {
        assert!(SECTIONS.contains(&name), "`{name}` is not an MJCF section");
        tree::child_mut(&mut self.root, name).expect("sections are created at load")
    }

    /// `<worldbody>`.
    pub fn worldbody(&self) -> &Element {
        self.section("worldbody")
    }

    /// `<worldbody>`, mutably.
    pub fn worldbody_mut(&mut self) -> &mut Element {
        self.section_mut("worldbody")
    }

    /// robosuite's `MujocoXML.merge(other, merge_body)`: appends `other`'s world-body
    /// children to `merge_body`, merges its assets ([`MjcfDoc::merge_assets`]) and appends
    /// its actuators, sensors, tendons, equalities and contacts.
    ///
    /// # Errors
    /// [`Error::Model`] when `merge_body` names a body this document does not have.
    pub fn merge(&mut self, mut other: MjcfDoc, merge_body: MergeBody<'_>) -> Result<()> {
        let bodies = std::mem::take(&mut other.worldbody_mut().children);
        match merge_body {
            MergeBody::World => self.worldbody_mut().children.extend(bodies),
            MergeBody::Body(name) => {
                tree::body_mut(self.worldbody_mut(), name)?
                    .children
                    .extend(bodies);
            }
            MergeBody::None => {}
        }
        let assets = std::mem::take(&mut other.section_mut("asset").children);
        self.merge_asset_nodes(assets);
        for name in ["actuator", "sensor", "tendon", "equality", "contact"] {
            let items = std::mem::take(&mut other.section_mut(name).children);
            self.section_mut(name).children.extend(items);
        }
        Ok(())
    }

    /// robosuite's `merge_assets`: appends each asset of `assets` unless an element with the
    /// same tag and the same name (or both unnamed) is already among this document's assets.
    pub fn merge_assets(&mut self, assets: &Element) {
        self.merge_asset_nodes(assets.children.clone());
    }

    fn merge_asset_nodes(&mut self, nodes: Vec<xmltree::XMLNode>) {
        for node in nodes {
            let xmltree::XMLNode::Element(asset) = node else {
                continue;
            };
            let name = attr(&asset, "name");
            let present =
                tree::find(self.section("asset"), &asset.name, &[("name", name)]).is_some();
            if !present {
                append(self.section_mut("asset"), asset);
            }
        }
    }

    /// The document as MJCF text.
    pub fn to_xml(&self) -> String {
        let mut out = Vec::new();
        let config = EmitterConfig::new()
            .perform_indent(true)
            .write_document_declaration(false);
        self.root
            .write_with_config(&mut out, config)
            .expect("writing XML to memory does not fail");
        String::from_utf8(out).expect("xmltree writes UTF-8")
    }
}

/// robosuite's `_get_default_classes` + `_replace_defaults_inline`, then removes `<default>`.
fn inline_defaults(root: &mut Element, path: &Path) -> Result<()> {
    // class → tag → the attributes of the last such child (a dict comprehension in robosuite).
    let mut classes: HashMap<String, HashMap<String, indexmap::IndexMap<String, String>>> =
        HashMap::new();
    let defaults = child(root, "default").into_iter().flat_map(children);
    for class in defaults {
        let Some(name) = attr(class, "class") else {
            continue; // defaults outside a class never apply in robosuite
        };
        let entry = classes.entry(name.to_owned()).or_default();
        for c in children(class) {
            entry.insert(c.name.clone(), c.attributes.clone().into_iter().collect());
        }
    }
    fn apply(
        e: &mut Element,
        classes: &HashMap<String, HashMap<String, indexmap::IndexMap<String, String>>>,
        path: &Path,
    ) -> Result<()> {
        if let Some(class) = tree::remove_attr(e, "class") {
            let tags = classes.get(&class).ok_or_else(|| {
                Error::model(format!(
                    "{}: <{}> uses the default class `{class}`, which the file does not define",
                    path.display(),
                    e.name
                ))
            })?;
            if let Some(defaults) = tags.get(&e.name) {
                for (k, v) in defaults {
                    if !e.attributes.contains_key(k) {
                        e.attributes.insert(k.clone(), v.clone());
                    }
                }
            }
        }
        for c in children_mut(e) {
            if c.name != "default" {
                apply(c, classes, path)?;
            }
        }
        Ok(())
    }
    apply(root, &classes, path)?;
    tree::take_children(root, |e| e.name == "default");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc(xml: &str) -> Result<MjcfDoc> {
        MjcfDoc::parse(xml, Path::new("/models/part.xml"))
    }

    #[test]
    fn defaults_are_inlined_sections_created_and_paths_resolved() {
        let d = doc(r#"<mujoco model="m">
            <default><geom rgba="1 1 1 1"/><default class="c"><geom friction="2" group="1"/></default></default>
            <asset><mesh name="a" file="meshes/a.stl"/></asset>
            <worldbody><body name="b"><geom class="c" group="0"/><geom/></body></worldbody>
        </mujoco>"#)
        .unwrap();
        assert!(child(d.root(), "default").is_none());
        let body = child(d.worldbody(), "body").unwrap();
        let geoms: Vec<_> = children(body).collect();
        assert_eq!(attr(geoms[0], "friction"), Some("2"));
        assert_eq!(attr(geoms[0], "group"), Some("0"));
        assert_eq!(attr(geoms[0], "class"), None);
        // A default outside any class is dropped, as robosuite drops it.
        assert_eq!(attr(geoms[1], "rgba"), None);
        let mesh = child(d.section("asset"), "mesh").unwrap();
        assert_eq!(attr(mesh, "file"), Some("/models/meshes/a.stl"));
        for s in SECTIONS {
            let _ = d.section(s);
        }
    }

    #[test]
    fn merge_appends_bodies_and_deduplicates_assets() {
        let mut a = doc(
            r#"<mujoco><asset><texture type="skybox"/><mesh name="x" file="/x"/></asset>
            <worldbody><body name="hand"/></worldbody></mujoco>"#,
        )
        .unwrap();
        let b = doc(r#"<mujoco><asset><texture type="2d"/><mesh name="x" file="/y"/><mesh name="z" file="/z"/></asset>
            <worldbody><body name="finger"/></worldbody><actuator><position joint="j"/></actuator></mujoco>"#)
        .unwrap();
        a.merge(b, MergeBody::Body("hand")).unwrap();
        let hand = child(a.worldbody(), "body").unwrap();
        assert_eq!(attr(child(hand, "body").unwrap(), "name"), Some("finger"));
        let assets: Vec<_> = children(a.section("asset")).collect();
        // The unnamed texture and the mesh `x` were present already.
        assert_eq!(assets.len(), 3);
        assert_eq!(attr(assets[1], "file"), Some("/x"));
        assert_eq!(children(a.section("actuator")).count(), 1);
        let c = doc("<mujoco/>").unwrap();
        assert!(a.merge(c, MergeBody::Body("nope")).is_err());
    }

    #[test]
    fn malformed_input_is_an_error() {
        assert!(doc("<mujoco>").is_err());
        assert!(doc("").is_err());
        assert!(doc("<robot/>").is_err());
        assert!(doc(r#"<mujoco><worldbody><geom class="missing"/></worldbody></mujoco>"#).is_err());
        let missing = MjcfDoc::load(Path::new("/no/such/file.xml")).unwrap_err();
        assert!(missing.to_string().contains("/no/such/file.xml"));
    }
}
