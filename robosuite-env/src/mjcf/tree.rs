//! Small operations on an MJCF element tree, as robosuite's `mjcf_utils` performs them:
//! searching (pre-order, the root included), prefixing names, recolouring collision geoms
//! and reading or writing number lists.

use gym_core::{Error, Result};
use xmltree::{Element, XMLNode};

/// The attributes that name or reference an MJCF element (robosuite's
/// `MUJOCO_NAMED_ATTRIBUTES`); [`add_prefix`] prefixes each of them.
pub const NAMED_ATTRIBUTES: &[&str] = &[
    "class",
    "childclass",
    "name",
    "objname",
    "material",
    "texture",
    "joint",
    "joint1",
    "joint2",
    "jointinparent",
    "geom",
    "geom1",
    "geom2",
    "mesh",
    "fixed",
    "actuator",
    "tendon",
    "tendon1",
    "tendon2",
    "slidesite",
    "cranksite",
    "body",
    "body1",
    "body2",
    "hfield",
    "target",
    "prefix",
    "site",
];

/// The sensor element names (robosuite's `SENSOR_TYPES`).
pub const SENSOR_TYPES: &[&str] = &[
    "touch",
    "accelerometer",
    "velocimeter",
    "gyro",
    "force",
    "torque",
    "magnetometer",
    "rangefinder",
    "jointpos",
    "jointvel",
    "tendonpos",
    "tendonvel",
    "actuatorpos",
    "actuatorvel",
    "actuatorfrc",
    "ballangvel",
    "jointlimitpos",
    "jointlimitvel",
    "jointlimitfrc",
    "tendonlimitpos",
    "tendonlimitvel",
    "tendonlimitfrc",
    "framepos",
    "framequat",
    "framexaxis",
    "frameyaxis",
    "framezaxis",
    "framelinvel",
    "frameangvel",
    "framelinacc",
    "frameangacc",
    "subtreecom",
    "subtreelinvel",
    "subtreeangmom",
    "user",
];

/// A new element with attributes, in the given order.
pub fn element(tag: &str, attributes: &[(&str, String)]) -> Element {
    let mut e = Element::new(tag);
    for (k, v) in attributes {
        e.attributes.insert((*k).to_owned(), v.clone());
    }
    e
}

/// The value of an attribute.
pub fn attr<'a>(e: &'a Element, name: &str) -> Option<&'a str> {
    e.attributes.get(name).map(String::as_str)
}

/// Sets an attribute (keeping its place if it exists, appending it otherwise).
pub fn set_attr(e: &mut Element, name: &str, value: impl Into<String>) {
    e.attributes.insert(name.to_owned(), value.into());
}

/// Removes an attribute, keeping the order of the others.
pub fn remove_attr(e: &mut Element, name: &str) -> Option<String> {
    e.attributes.shift_remove(name)
}

/// The child elements, in order (text and comments skipped).
pub fn children(e: &Element) -> impl Iterator<Item = &Element> {
    e.children.iter().filter_map(XMLNode::as_element)
}

/// The child elements, mutably.
pub fn children_mut(e: &mut Element) -> impl Iterator<Item = &mut Element> {
    e.children.iter_mut().filter_map(XMLNode::as_mut_element)
}

/// The first child element with this tag.
pub fn child<'a>(e: &'a Element, tag: &str) -> Option<&'a Element> {
    children(e).find(|c| c.name == tag)
}

/// The first child element with this tag, mutably.
pub fn child_mut<'a>(e: &'a mut Element, tag: &str) -> Option<&'a mut Element> {
    children_mut(e).find(|c| c.name == tag)
}

/// Appends a child element.
pub fn append(parent: &mut Element, child: Element) {
    parent.children.push(XMLNode::Element(child));
}

/// Removes and returns the child elements for which `remove` is true, keeping the others in
/// order.
pub fn take_children(parent: &mut Element, remove: impl Fn(&Element) -> bool) -> Vec<Element> {
    let mut taken = Vec::new();
    let mut kept = Vec::with_capacity(parent.children.len());
    for node in std::mem::take(&mut parent.children) {
        match node {
            XMLNode::Element(e) if remove(&e) => taken.push(e),
            other => kept.push(other),
        }
    }
    parent.children = kept;
    taken
}

/// Whether `e` has this tag and every given attribute value (`None`: the attribute is absent),
/// as robosuite's `find_elements` compares.
pub fn matches(e: &Element, tag: &str, attrs: &[(&str, Option<&str>)]) -> bool {
    e.name == tag && attrs.iter().all(|(k, v)| attr(e, k) == *v)
}

/// The child-index path (into `children`) of the first element in pre-order, `root`
/// included (the empty path), for which `pred` holds.
pub fn find_path(root: &Element, pred: &dyn Fn(&Element) -> bool) -> Option<Vec<usize>> {
    if pred(root) {
        return Some(Vec::new());
    }
    for (i, node) in root.children.iter().enumerate() {
        if let XMLNode::Element(c) = node
            && let Some(mut rest) = find_path(c, pred)
        {
            rest.insert(0, i);
            return Some(rest);
        }
    }
    None
}

/// The element at a path from [`find_path`].
pub fn at_path<'a>(root: &'a Element, path: &[usize]) -> &'a Element {
    path.iter().fold(root, |e, &i| match &e.children[i] {
        XMLNode::Element(c) => c,
        _ => unreachable!("paths from find_path address elements"),
    })
}

/// The element at a path from [`find_path`], mutably.
pub fn at_path_mut<'a>(root: &'a mut Element, path: &[usize]) -> &'a mut Element {
    path.iter().fold(root, |e, &i| match &mut e.children[i] {
        XMLNode::Element(c) => c,
        _ => unreachable!("paths from find_path address elements"),
    })
}

/// robosuite's `find_elements(root, tags, attribs, return_first=True)`.
pub fn find<'a>(
    root: &'a Element,
    tag: &str,
    attrs: &[(&str, Option<&str>)],
) -> Option<&'a Element> {
    find_path(root, &|e| matches(e, tag, attrs)).map(|p| at_path(root, &p))
}

/// [`find`], mutably.
pub fn find_mut<'a>(
    root: &'a mut Element,
    tag: &str,
    attrs: &[(&str, Option<&str>)],
) -> Option<&'a mut Element> {
    let path = find_path(root, &|e| matches(e, tag, attrs))?;
    Some(at_path_mut(root, &path))
}

/// The body named `name` in pre-order under `root`.
///
/// # Errors
/// [`Error::Model`] when there is none.
pub fn body_mut<'a>(root: &'a mut Element, name: &str) -> Result<&'a mut Element> {
    find_mut(root, "body", &[("name", Some(name))])
        .ok_or_else(|| Error::model(format!("the MJCF has no body named `{name}`")))
}

/// Every element with this tag under `root` (pre-order, `root` included).
pub fn find_all<'a>(root: &'a Element, tag: &str) -> Vec<&'a Element> {
    let mut out = Vec::new();
    visit(root, &mut |e| {
        if e.name == tag {
            out.push(e);
        }
    });
    out
}

/// Calls `f` on every element in pre-order, `root` included.
pub fn visit<'a>(root: &'a Element, f: &mut dyn FnMut(&'a Element)) {
    f(root);
    for c in children(root) {
        visit(c, f);
    }
}

/// Calls `f` on every element in pre-order, `root` included, mutably.
pub fn visit_mut(root: &mut Element, f: &mut dyn FnMut(&mut Element)) {
    f(root);
    for c in children_mut(root) {
        visit_mut(c, f);
    }
}

/// robosuite's `add_prefix`: prefixes every naming attribute of every element under `root`
/// that does not already start with `prefix`, except where `exclude` says so (it sees each
/// attribute value).
pub fn add_prefix(root: &mut Element, prefix: &str, exclude: &dyn Fn(&str) -> bool) {
    visit_mut(root, &mut |e| {
        for name in NAMED_ATTRIBUTES {
            if let Some(v) = e.attributes.get_mut(*name)
                && !v.starts_with(prefix)
                && !exclude(v)
            {
                v.insert_str(0, prefix);
            }
        }
    });
}

/// robosuite's `recolor_collision_geoms`: every geom of group 0 (or without a group) gets
/// `rgba` and loses its material, unless `exclude` holds for it.
pub fn recolor_collision_geoms(
    root: &mut Element,
    rgba: &[f64; 4],
    exclude: &dyn Fn(&Element) -> bool,
) {
    let rgba = array_to_string(rgba);
    visit_mut(root, &mut |e| {
        if e.name == "geom" && matches!(attr(e, "group"), None | Some("0")) && !exclude(e) {
            set_attr(e, "rgba", rgba.clone());
            remove_attr(e, "material");
        }
    });
}

/// robosuite's `array_to_string`: the numbers separated by single spaces, each written in
/// the shortest form that reads back to the same `f64`.
pub fn array_to_string(values: &[f64]) -> String {
    let mut out = String::new();
    for (i, v) in values.iter().enumerate() {
        if i > 0 {
            out.push(' ');
        }
        out.push_str(&format_number(*v));
    }
    out
}

/// One number as robosuite writes it: the shortest form that reads back to the same `f64`
/// (Python writes `1.0` where this writes `1`; both read back to the same value).
pub fn format_number(v: f64) -> String {
    format!("{v}")
}

/// robosuite's `string_to_array`: the numbers of an attribute value.
///
/// # Errors
/// [`Error::Model`] when a part is not a number.
pub fn parse_array(text: &str) -> Result<Vec<f64>> {
    text.split_whitespace()
        .map(|s| {
            s.parse::<f64>()
                .map_err(|_| Error::model(format!("`{text}` is not a list of numbers")))
        })
        .collect()
}

/// The numbers of attribute `name` of `e`, or `default` when it is absent.
///
/// # Errors
/// [`Error::Model`] when the value is not a list of `N` numbers.
pub fn attr_array<const N: usize>(e: &Element, name: &str, default: [f64; N]) -> Result<[f64; N]> {
    match attr(e, name) {
        None => Ok(default),
        Some(text) => {
            let v = parse_array(text)?;
            v.try_into().map_err(|v: Vec<f64>| {
                Error::model(format!(
                    "attribute {name}=\"{text}\" of <{}> has {} numbers, expected {N}",
                    e.name,
                    v.len()
                ))
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(xml: &str) -> Element {
        Element::parse(xml.as_bytes()).unwrap()
    }

    #[test]
    fn numbers_round_trip_exactly() {
        for v in [
            0.0,
            -0.0,
            1.0,
            0.1,
            -0.56,
            0.912,
            1.0 / 3.0,
            1e-8,
            5.0 / 7.0,
            123456.789,
            2.5e-5,
        ] {
            let s = array_to_string(&[v]);
            assert_eq!(
                s.parse::<f64>().unwrap().to_bits(),
                v.to_bits(),
                "{v} -> {s}"
            );
        }
        assert_eq!(array_to_string(&[0.0, 0.5, 1.0]), "0 0.5 1");
        assert_eq!(parse_array(" 1  2 3.5 ").unwrap(), vec![1.0, 2.0, 3.5]);
        assert!(parse_array("1 x").is_err());
    }

    #[test]
    fn prefix_skips_already_prefixed_and_excluded_values() {
        let mut e = parse(
            r#"<body name="a"><geom name="robot0_b" mesh="m" material="shared"/><site name="s"/></body>"#,
        );
        add_prefix(&mut e, "robot0_", &|v| v == "shared");
        let geom = child(&e, "geom").unwrap();
        assert_eq!(attr(&e, "name"), Some("robot0_a"));
        assert_eq!(attr(geom, "name"), Some("robot0_b"));
        assert_eq!(attr(geom, "mesh"), Some("robot0_m"));
        assert_eq!(attr(geom, "material"), Some("shared"));
    }

    #[test]
    fn find_is_preorder_and_paths_address_elements() {
        let mut e = parse(r#"<w><body name="a"><body name="b"/></body><body name="b"/></w>"#);
        let path = find_path(&e, &|x| attr(x, "name") == Some("b")).unwrap();
        assert_eq!(path.len(), 2);
        set_attr(body_mut(&mut e, "b").unwrap(), "pos", "1 2 3");
        assert_eq!(attr(at_path(&e, &path), "pos"), Some("1 2 3"));
        assert!(body_mut(&mut e, "c").is_err());
    }

    #[test]
    fn recolor_touches_group_zero_geoms_only() {
        let mut e = parse(
            r#"<b><geom material="m"/><geom group="1" material="m"/><geom group="0" name="floor"/></b>"#,
        );
        recolor_collision_geoms(&mut e, &[0.5, 0.0, 0.0, 1.0], &|g| {
            attr(g, "name") == Some("floor")
        });
        let geoms: Vec<_> = children(&e).collect();
        assert_eq!(attr(geoms[0], "rgba"), Some("0.5 0 0 1"));
        assert_eq!(attr(geoms[0], "material"), None);
        assert_eq!(attr(geoms[1], "material"), Some("m"));
        assert_eq!(attr(geoms[2], "rgba"), None);
    }
}
