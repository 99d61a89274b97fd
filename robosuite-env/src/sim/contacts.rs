//! Contact queries by geom ids (robosuite's name-based `check_contact`, resolved once).

use super::Data;

/// A small set of geom ids (an object's contact geoms, or a finger pad group).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct GeomSet(Vec<i32>);

impl GeomSet {
    /// A set of geom ids.
    pub fn new(ids: impl IntoIterator<Item = usize>) -> Self {
        Self(
            ids.into_iter()
                .map(|i| i32::try_from(i).unwrap_or(i32::MAX))
                .collect(),
        )
    }

    /// Whether `geom` is in the set.
    pub fn contains(&self, geom: i32) -> bool {
        self.0.contains(&geom)
    }

    /// The ids.
    pub fn ids(&self) -> &[i32] {
        &self.0
    }
}

/// Whether any active contact pairs a geom of `a` with a geom of `b` (in either order), as
/// robosuite's `check_contact`: every contact in `d.contact[:ncon]`, no force threshold.
pub fn any_contact_between(data: &Data, a: &GeomSet, b: &GeomSet) -> bool {
    data.contact().iter().any(|c| {
        let (g1, g2) = (c.geom[0], c.geom[1]);
        (a.contains(g1) && b.contains(g2)) || (a.contains(g2) && b.contains(g1))
    })
}

/// Whether any active contact involves a geom of `a` (with any other geom), as robosuite's
/// `check_contact(geoms_1)` without a second group (Wipe's arm-collision test).
pub fn any_contact_with(data: &Data, a: &GeomSet) -> bool {
    data.contact()
        .iter()
        .any(|c| a.contains(c.geom[0]) || a.contains(c.geom[1]))
}
