//! [`XmlModel`]: a model file with a naming prefix, as robosuite's `MujocoXMLModel` (the
//! base of its robots, grippers and mounts) prepares it.

use super::doc::MjcfDoc;
use super::tree::{self, SENSOR_TYPES, attr, children_mut};
use gym_core::{Error, Result};
use std::path::Path;
use xmltree::Element;

/// The names of a model's elements, without its prefix, in document order (robosuite's
/// `sort_elements` with the default element filter).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ElementNames {
    /// The one top-level body.
    pub root_body: String,
    /// Every body, the root body first.
    pub bodies: Vec<String>,
    /// Every joint (not tendon or equality joint references).
    pub joints: Vec<String>,
    /// Every actuator.
    pub actuators: Vec<String>,
    /// Every site.
    pub sites: Vec<String>,
    /// Every sensor.
    pub sensors: Vec<String>,
    /// Geoms of group 0 (or without a group): contact geoms.
    pub contact_geoms: Vec<String>,
    /// Geoms of group 1: visual geoms.
    pub visual_geoms: Vec<String>,
}

impl ElementNames {
    /// Sorts the elements under `root` (pre-order). With `name_geoms`, unnamed geoms are first
    /// named `g{n}_col` (group 0) or `g{n}_vis` (group 1), as `MujocoXMLModel` does.
    ///
    /// # Errors
    /// [`Error::Model`] for an unnamed top-level body, joint, site, actuator or sensor, an unnamed geom
    /// of another group, or not exactly one top-level body.
    pub fn sort(root: &mut Element, name_geoms: bool, what: &str) -> Result<Self> {
        let mut names = Self::default();
        let mut roots = Vec::new();
        let mut counters = [0usize; 2];
        sort(
            root,
            None,
            name_geoms,
            &mut counters,
            &mut names,
            &mut roots,
            what,
        )?;
        match roots.as_slice() {
            [one] => names.root_body = one.clone(),
            other => {
                return Err(Error::model(format!(
                    "{what}: expected one top-level body, found {}",
                    other.len()
                )));
            }
        }
        names.bodies.insert(0, names.root_body.clone());
        Ok(names)
    }
}

fn sort(
    e: &mut Element,
    parent: Option<&str>,
    name_geoms: bool,
    counters: &mut [usize; 2],
    out: &mut ElementNames,
    roots: &mut Vec<String>,
    what: &str,
) -> Result<()> {
    let named = |e: &Element| {
        attr(e, "name")
            .map(str::to_owned)
            .ok_or_else(|| Error::model(format!("{what}: a <{}> has no name", e.name)))
    };
    if parent == Some("actuator") {
        out.actuators.push(named(e)?);
    } else if e.name == "joint" {
        if attr(e, "joint").is_none() && attr(e, "joint1").is_none() {
            out.joints.push(named(e)?);
        }
    } else if e.name == "body" {
        // robosuite keeps an unnamed inner body (a Fourier hand's frame) without a name.
        if parent == Some("body") {
            out.bodies.extend(attr(e, "name").map(str::to_owned));
        } else {
            roots.push(named(e)?);
        }
    } else if e.name == "site" {
        out.sites.push(named(e)?);
    } else if SENSOR_TYPES.contains(&e.name.as_str()) {
        out.sensors.push(named(e)?);
    } else if e.name == "geom" {
        let group = attr(e, "group").map(str::to_owned);
        let visual = match group.as_deref() {
            None | Some("0") => Some(false),
            Some("1") => Some(true),
            Some(_) => None,
        };
        if name_geoms && attr(e, "name").is_none() {
            let Some(visual) = visual else {
                return Err(Error::model(format!(
                    "{what}: an unnamed geom of group {} (robosuite names only groups 0 and 1)",
                    group.unwrap_or_default()
                )));
            };
            let k = usize::from(visual);
            let name = format!("g{}_{}", counters[k], if visual { "vis" } else { "col" });
            counters[k] += 1;
            tree::set_attr(e, "name", name);
        }
        match visual {
            Some(true) => out.visual_geoms.push(named(e)?),
            Some(false) => out.contact_geoms.push(named(e)?),
            None => {}
        }
    }
    let tag = e.name.clone();
    for c in children_mut(e) {
        sort(c, Some(&tag), name_geoms, counters, out, roots, what)?;
    }
    Ok(())
}

/// A robosuite model file (robot, gripper or mount) prepared as `MujocoXMLModel.__init__`
/// prepares it: loaded as an [`MjcfDoc`], unnamed geoms named, its elements sorted
/// ([`ElementNames`]), every name prefixed with `prefix`, and its collision geoms
/// recoloured.
#[derive(Debug, Clone)]
pub struct XmlModel {
    /// The processed document.
    pub doc: MjcfDoc,
    /// The naming prefix (`robot0_`, `gripper0_right_`, `fixed_mount0_`, ...).
    pub prefix: String,
    /// The element names without the prefix.
    pub names: ElementNames,
    /// The root body's `pos` in the file (robosuite's `base_offset`).
    pub base_offset: [f64; 3],
}

impl XmlModel {
    /// Loads and prepares the model file at `path`.
    ///
    /// # Errors
    /// [`Error::Model`] when the file cannot be read or parsed, or breaks robosuite's naming
    /// rules (see [`ElementNames::sort`]).
    pub fn load(path: &Path, prefix: &str, collision_rgba: [f64; 4]) -> Result<Self> {
        let mut doc = MjcfDoc::load(path)?;
        let what = path.display().to_string();
        let names = ElementNames::sort(doc.root_mut(), true, &what)?;
        let root_body = tree::find(doc.worldbody(), "body", &[("name", Some(&names.root_body))])
            .expect("the root body was just found");
        let base_offset = tree::attr_array(root_body, "pos", [0.0; 3])?;
        tree::add_prefix(doc.root_mut(), prefix, &|_| false);
        tree::recolor_collision_geoms(doc.worldbody_mut(), &collision_rgba, &|_| false);
        Ok(Self {
            doc,
            prefix: prefix.to_owned(),
            names,
            base_offset,
        })
    }

    /// `raw` with the prefix (robosuite's `correct_naming`).
    pub fn name(&self, raw: &str) -> String {
        format!("{}{raw}", self.prefix)
    }

    /// Every name of a list with the prefix.
    pub fn names_of(&self, raw: &[String]) -> Vec<String> {
        raw.iter().map(|n| self.name(n)).collect()
    }

    /// The root body's full name.
    pub fn root_body(&self) -> String {
        self.name(&self.names.root_body)
    }

    /// The root body element.
    pub fn root_body_element_mut(&mut self) -> &mut Element {
        let name = self.root_body();
        tree::body_mut(self.doc.worldbody_mut(), &name).expect("the root body exists")
    }
}
