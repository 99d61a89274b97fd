//! Test support: what robosuite 1.5.2's Python generates for a set of generated objects
//! (`testdata/generated_objects.json`: the body and asset XML, extents and element names of
//! small composite objects and of ToolHang's stand, frame and tool, texture paths cut to
//! their file names, numbers as Python's `repr`), and the element-for-element comparison of our objects with it.

use super::ObjectModel;
use crate::mjcf::Element;
use crate::mjcf::tree::{attr, children};

const EXPECTED: &str = include_str!("testdata/generated_objects.json");

/// robosuite's output for one object.
struct Expected {
    body: Element,
    asset: Element,
    json: serde_json::Value,
}

fn expected(key: &str) -> Expected {
    let all: serde_json::Value = serde_json::from_str(EXPECTED).expect("the test data is JSON");
    let json = all
        .get(key)
        .unwrap_or_else(|| panic!("no expected object `{key}`"))
        .clone();
    let parse = |field: &str| {
        Element::parse(json[field].as_str().expect("XML text").as_bytes())
            .expect("robosuite's XML parses")
    };
    Expected {
        body: parse("body"),
        asset: parse("asset"),
        json,
    }
}

/// Whether two attribute values are equal: the same numbers (bit for bit) where both are
/// number lists, the same file name for `file`, else the same text.
fn same_value(key: &str, ours: &str, theirs: &str) -> bool {
    if key == "file" {
        return std::path::Path::new(ours)
            .file_name()
            .and_then(|f| f.to_str())
            == Some(theirs);
    }
    let numbers = |s: &str| -> Option<Vec<u64>> {
        s.split_whitespace()
            .map(|p| p.parse::<f64>().ok().map(f64::to_bits))
            .collect()
    };
    match (numbers(ours), numbers(theirs)) {
        (Some(a), Some(b)) => a == b,
        _ => ours == theirs,
    }
}

/// Asserts that `ours` and `theirs` are the same element tree: the same tags in the same
/// order, each with the same attributes and equal values (attribute order does not change
/// what MuJoCo compiles, and this crate's primitives write theirs in another order).
fn assert_same_tree(ours: &Element, theirs: &Element, path: &str) {
    let here = format!(
        "{path}/{}[{}]",
        theirs.name,
        attr(theirs, "name").unwrap_or("")
    );
    assert_eq!(ours.name, theirs.name, "{here}: tag");
    let keys = |e: &Element| {
        let mut k = e.attributes.keys().cloned().collect::<Vec<_>>();
        k.sort();
        k
    };
    assert_eq!(keys(ours), keys(theirs), "{here}: attributes");
    for (k, v) in &theirs.attributes {
        let mine = &ours.attributes[k];
        assert!(
            same_value(k, mine, v),
            "{here}: {k}=\"{mine}\", robosuite \"{v}\""
        );
    }
    let (a, b): (Vec<_>, Vec<_>) = (children(ours).collect(), children(theirs).collect());
    let tags = |l: &[&Element]| {
        l.iter()
            .map(|e| format!("{}:{}", e.name, attr(e, "name").unwrap_or("")))
            .collect::<Vec<_>>()
    };
    assert_eq!(tags(&a), tags(&b), "{here}: children");
    for (x, y) in a.iter().zip(&b) {
        assert_same_tree(x, y, &here);
    }
}

/// A number written as Python's `repr` (serde_json's own float parsing may be off by an
/// ulp).
fn float(v: &serde_json::Value) -> f64 {
    v.as_str()
        .and_then(|s| s.parse().ok())
        .expect("a number as text")
}

fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array().expect("a list").iter().map(float).collect()
}

fn strings(v: &serde_json::Value) -> Vec<String> {
    v.as_array()
        .expect("a list")
        .iter()
        .map(|x| x.as_str().expect("a name").to_owned())
        .collect()
}

/// Asserts that `ours` is what robosuite generates for `key`, element for element (body and
/// assets; see `assert_same_tree`), with the same extents (`top_offset`, `bottom_offset`,
/// `horizontal_radius`, bounding box `half_size`, bit for bit) and the same element names.
pub(crate) fn assert_matches_robosuite(key: &str, ours: &ObjectModel, half_size: [f64; 3]) {
    let e = expected(key);
    assert_same_tree(&ours.body, &e.body, key);
    assert_same_tree(&ours.assets, &e.asset, key);
    let j = &e.json;
    assert_eq!(
        floats(&j["top"]),
        ours.top_offset.to_vec(),
        "{key}: top_offset"
    );
    assert_eq!(
        floats(&j["bottom"]),
        ours.bottom_offset.to_vec(),
        "{key}: bottom_offset"
    );
    assert_eq!(
        float(&j["hr"]),
        ours.horizontal_radius,
        "{key}: horizontal_radius"
    );
    assert_eq!(
        floats(&j["bbox"]),
        half_size.to_vec(),
        "{key}: bounding box"
    );
    assert_eq!(
        strings(&j["contact"]),
        ours.contact_geoms(),
        "{key}: contact geoms"
    );
    assert_eq!(
        strings(&j["visual"]),
        ours.visual_geoms(),
        "{key}: visual geoms"
    );
    assert_eq!(strings(&j["sites"]), ours.sites(), "{key}: sites");
    assert_eq!(strings(&j["joints"]), ours.joints(), "{key}: joints");
    let bodies: Vec<String> = ours.names.bodies.iter().map(|b| ours.name_of(b)).collect();
    assert_eq!(strings(&j["bodies"]), bodies, "{key}: bodies");
    assert_eq!(
        j["root"].as_str(),
        Some(ours.root_body().as_str()),
        "{key}: root body"
    );
}

/// robosuite's `init_quat` of `key` (xyzw), if the object has one.
pub(crate) fn init_quat(key: &str) -> Option<Vec<f64>> {
    expected(key).json.get("init_quat").map(floats)
}
