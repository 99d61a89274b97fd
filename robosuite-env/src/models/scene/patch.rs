//! Compiling a scene that differs from one compiled before only in the sizes of generated
//! box objects (robosuite saves each episode's scene with the cube sizes its reset drew), by
//! copying the compiled model and resizing the boxes in place instead of a full MJCF compile
//! (a third of a second with robosuite's meshes).
//!
//! Only a narrow case is patched; everything else is compiled in full:
//!
//! * the two texts are equal but for the `size` values of named `<geom>` elements;
//! * each changed geom is `type="box"` with no attribute that places it, shapes it or gives it
//!   another mass (no `class`, `pos`, orientation, `fromto`, `mesh`, `density`; `mass` only
//!   as `"0"`), and its body's geoms are exactly the changed ones, all of one new size, the
//!   first without `mass`;
//! * the body's compiled mass and inertia are those of a solid box of density 1000 at its
//!   origin (no explicit `<inertial>`, no default class changing the density).
//!
//! The patch is [`crate::sim::resize_box_body`] (what Lift's resets do), so the model equals
//! a full compile's to rounding (checked field by field by the Python tests on the recorded
//! demonstrations).

use crate::sim::{BoxGeomUpdate, resized_box_bodies};
use gym_core::Result;
use mujoco_rs::wrappers::mj_model::MjModel;
use std::collections::HashMap;
use std::ops::Range;

/// The attributes a patched geom may have.
const ALLOWED: [&str; 14] = [
    "name",
    "size",
    "type",
    "rgba",
    "contype",
    "conaffinity",
    "group",
    "mass",
    "material",
    "friction",
    "solref",
    "solimp",
    "condim",
    "priority",
];

/// The density MuJoCo's compiler gives a geom without one.
const DEFAULT_DENSITY: f64 = 1000.0;

/// One `<geom ... size="...">` of a scene text.
#[derive(Debug, Clone)]
pub(super) struct SizeAttr {
    /// The byte range of the `size` value.
    value: Range<usize>,
    /// The geom's attributes (name, value).
    attrs: Vec<(String, String)>,
}

/// The scene text with every geom `size` value cut out, and those values' places.
#[derive(Debug, Clone)]
pub(super) struct Skeleton {
    /// The text with each geom `size` value replaced by a NUL byte (absent from scenes).
    pub(super) key: String,
    /// The geoms with a `size`, in text order.
    pub(super) sizes: Vec<SizeAttr>,
}

/// An attribute of a tag: its name, its value and the value's byte range.
type Attribute = (String, String, Range<usize>);

/// The box geoms of one body to resize: their ids, their new half-extents and the geom that
/// carries the mass.
type BodyBoxes = (Vec<usize>, [f64; 3], Option<usize>);

/// The attributes of the tag whose attribute text starts at `from`, and the index of its
/// closing `>`; `None` for text that is not a well-formed tag.
fn attributes(xml: &str, from: usize) -> Option<(Vec<Attribute>, usize)> {
    let b = xml.as_bytes();
    let mut i = from;
    let mut out = Vec::new();
    loop {
        while i < b.len() && b[i].is_ascii_whitespace() {
            i += 1;
        }
        match b.get(i)? {
            b'>' => return Some((out, i)),
            b'/' if b.get(i + 1) == Some(&b'>') => return Some((out, i + 1)),
            _ => {}
        }
        let start = i;
        while i < b.len() && !b[i].is_ascii_whitespace() && b[i] != b'=' && b[i] != b'>' {
            i += 1;
        }
        let name = &xml[start..i];
        while i < b.len() && b[i].is_ascii_whitespace() {
            i += 1;
        }
        if b.get(i)? != &b'=' || name.is_empty() {
            return None;
        }
        i += 1;
        while i < b.len() && b[i].is_ascii_whitespace() {
            i += 1;
        }
        let quote = *b.get(i)?;
        if quote != b'"' && quote != b'\'' {
            return None;
        }
        let v0 = i + 1;
        let v1 = v0 + xml[v0..].find(quote as char)?;
        out.push((name.to_owned(), xml[v0..v1].to_owned(), v0..v1));
        i = v1 + 1;
    }
}

/// The skeleton of `xml`; `None` when a `<geom` tag cannot be read.
pub(super) fn skeleton(xml: &str) -> Option<Skeleton> {
    let mut sizes = Vec::new();
    let mut key = String::with_capacity(xml.len());
    let mut copied = 0;
    let mut search = 0;
    while let Some(off) = xml[search..].find("<geom") {
        let at = search + off + "<geom".len();
        search = at;
        if !xml[at..].starts_with(|c: char| c.is_ascii_whitespace()) {
            continue;
        }
        let (attrs, end) = attributes(xml, at)?;
        search = end;
        if let Some((_, _, range)) = attrs.iter().find(|(n, _, _)| n == "size") {
            key.push_str(&xml[copied..range.start]);
            key.push('\0');
            copied = range.end;
            sizes.push(SizeAttr {
                value: range.clone(),
                attrs: attrs.into_iter().map(|(n, v, _)| (n, v)).collect(),
            });
        }
    }
    key.push_str(&xml[copied..]);
    Some(Skeleton { key, sizes })
}

fn attr<'a>(s: &'a SizeAttr, name: &str) -> Option<&'a str> {
    s.attrs
        .iter()
        .find(|(n, _)| n == name)
        .map(|(_, v)| v.as_str())
}

fn half_extents(text: &str) -> Option<[f64; 3]> {
    let v = text
        .split_ascii_whitespace()
        .map(|t| t.parse::<f64>().ok())
        .collect::<Option<Vec<f64>>>()?;
    let h: [f64; 3] = v.try_into().ok()?;
    h.iter().all(|x| x.is_finite() && *x > 0.0).then_some(h)
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300)
}

/// One body of boxes to resize: the body, its box geoms (the first carries the mass) and
/// their new half-extents (positive and finite).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BoxResize {
    /// The body.
    pub(crate) body: usize,
    /// Its box geoms, in id order.
    pub(crate) geoms: Vec<usize>,
    /// The new half-extents.
    pub(crate) half: [f64; 3],
}

impl BoxResize {
    /// The update [`crate::sim::resize_box_body`] applies.
    pub(crate) fn update(&self) -> BoxGeomUpdate<'_> {
        BoxGeomUpdate {
            body: self.body,
            geoms: &self.geoms,
            density: DEFAULT_DENSITY,
        }
    }
}

/// `base` (compiled from `base_xml`, whose skeleton is `base_sk`) turned into the model of
/// `xml` (skeleton `sk`, the same key), or `None` when the difference is not one this module
/// patches (the caller then compiles `xml` in full).
///
/// # Errors
/// Errors of MuJoCo while resizing (the caller falls back to a full compile).
pub(super) fn patched(
    base: &MjModel,
    base_xml: &str,
    base_sk: &Skeleton,
    xml: &str,
    sk: &Skeleton,
) -> Result<Option<MjModel>> {
    let Some(plan) = plan(base, base_xml, base_sk, xml, sk) else {
        return Ok(None);
    };
    if plan.is_empty() {
        return Ok(None);
    }
    let targets: Vec<_> = plan.iter().map(|r| (r.update(), r.half)).collect();
    resized_box_bodies(base, &targets).map(Some)
}

/// The box resizes that turn `base` (compiled from `base_xml`, skeleton `base_sk`) into the
/// model of `xml` (skeleton `sk`), in body order: empty when the texts' sizes are equal,
/// `None` when the difference is not one this module patches.
pub(crate) fn plan(
    base: &MjModel,
    base_xml: &str,
    base_sk: &Skeleton,
    xml: &str,
    sk: &Skeleton,
) -> Option<Vec<BoxResize>> {
    if base_sk.key != sk.key || base_sk.sizes.len() != sk.sizes.len() {
        return None;
    }
    let mut bodies: HashMap<usize, BodyBoxes> = HashMap::new();
    for (old, new) in base_sk.sizes.iter().zip(&sk.sizes) {
        let (old_text, new_text) = (&base_xml[old.value.clone()], &xml[new.value.clone()]);
        if old_text == new_text {
            continue;
        }
        if new
            .attrs
            .iter()
            .any(|(n, _)| !ALLOWED.contains(&n.as_str()))
            || attr(new, "type") != Some("box")
        {
            return None;
        }
        let massless = match attr(new, "mass") {
            None => false,
            Some(m) if m.trim().parse::<f64>() == Ok(0.0) => true,
            Some(_) => return None,
        };
        let (Some(name), Some(half), Some(_)) = (
            attr(new, "name"),
            half_extents(new_text),
            half_extents(old_text),
        ) else {
            return None;
        };
        let Ok(geom) = crate::sim::geom_id(base, name) else {
            return None;
        };
        let body = base.geom_bodyid()[geom] as usize;
        let entry = bodies.entry(body).or_insert((Vec::new(), half, None));
        if entry.1 != half {
            return None;
        }
        entry.0.push(geom);
        if !massless {
            if entry.2.is_some() {
                return None;
            }
            entry.2 = Some(geom);
        }
    }

    let identity = [1.0, 0.0, 0.0, 0.0];
    for (&body, (geoms, _, main)) in bodies.iter_mut() {
        geoms.sort_unstable();
        let adr = base.body_geomadr()[body];
        let num = base.body_geomnum()[body] as usize;
        let expected: Vec<usize> = (0..num).map(|k| adr as usize + k).collect();
        if adr < 0 || *geoms != expected || *main != Some(geoms[0]) {
            return None;
        }
        // The body's mass and inertia must be the box's at density 1000, at the origin.
        let [x, y, z] = base.geom_size()[geoms[0]];
        let mass = DEFAULT_DENSITY * 8.0 * x * y * z;
        let inertia = [
            mass * (y * y + z * z) / 3.0,
            mass * (x * x + z * z) / 3.0,
            mass * (x * x + y * y) / 3.0,
        ];
        let ok = close(base.body_mass()[body], mass)
            && (0..3).all(|i| close(base.body_inertia()[body][i], inertia[i]))
            && base.body_ipos()[body] == [0.0; 3]
            && base.body_iquat()[body] == identity
            && geoms.iter().all(|&g| {
                base.geom_type()[g] == mujoco_rs::wrappers::mj_model::MjtGeomBase::mjGEOM_BOX
                    && base.geom_pos()[g] == [0.0; 3]
                    && base.geom_quat()[g] == identity
            });
        if !ok {
            return None;
        }
    }
    let mut order: Vec<BoxResize> = bodies
        .into_iter()
        .map(|(body, (geoms, half, _))| BoxResize { body, geoms, half })
        .collect();
    order.sort_unstable_by_key(|r| r.body);
    Some(order)
}
