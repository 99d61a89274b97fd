//! robosuite's arenas (`robosuite/models/arenas/`): the workspace a task happens in, built
//! from robosuite's arena files and configured as its arena classes configure them.

use super::ENVIRONMENT_COLLISION_COLOR;
use crate::assets::Assets;
use crate::mjcf::tree::{self, array_to_string, attr, element, set_attr};
use crate::mjcf::{MjcfDoc, tree::append};
use gym_core::{Error, Result};

/// Which of robosuite's robot base offsets (`base_xpos_offset`) an arena uses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ArenaKind {
    /// A table of this length (x): robots stand at `(-0.16 - length / 2, 0, 0)` (Panda).
    Table {
        /// The table's full length along x.
        length: f64,
    },
    /// The two bins of PickPlace.
    Bins,
    /// No table (TwoArmPegInHole).
    Empty,
}

/// An arena: its processed MJCF and the figures tasks read from it.
#[derive(Debug, Clone)]
pub struct Arena {
    /// The arena's document (its world body, assets, lights and cameras).
    pub doc: MjcfDoc,
    /// Which base offsets robots take in it.
    pub kind: ArenaKind,
    /// Full size of the table (or of the bin area), if the arena has one.
    pub table_full_size: [f64; 3],
    /// Where the table surface is (robosuite's `table_offset`, or `bin1_pos` for bins).
    pub table_offset: [f64; 3],
}

/// robosuite's `Arena.__init__`: loads the file and adds the two mocap target bodies
/// (`left_eef_target`, `right_eef_target`). Collision geoms are recoloured by [`finish`].
fn load(assets: &Assets, file: &str) -> Result<MjcfDoc> {
    let mut doc = MjcfDoc::load(&assets.file(file)?)?;
    for (side, rgb) in [
        ("left", "0.898 0.420 0.435"),
        ("right", "0.208 0.314 0.439"),
    ] {
        let mut body = element(
            "body",
            &[
                ("name", format!("{side}_eef_target")),
                ("pos", "0 0 -1".to_owned()),
                ("mocap", "true".to_owned()),
            ],
        );
        for (shape, size, alpha) in [("box", "0.05 0.05 0.05", "0.5"), ("sphere", "0.01", "0.8")] {
            append(
                &mut body,
                element(
                    "geom",
                    &[
                        ("name", format!("{side}_eef_target_{shape}")),
                        ("type", shape.to_owned()),
                        ("size", size.to_owned()),
                        ("pos", "0 0 0".to_owned()),
                        ("group", "2".to_owned()),
                        ("rgba", format!("{rgb} {alpha}")),
                        ("conaffinity", "0".to_owned()),
                        ("contype", "0".to_owned()),
                    ],
                ),
            );
        }
        append(doc.worldbody_mut(), body);
    }
    Ok(doc)
}

/// The end of robosuite's `Arena.__init__`: every collision geom but the floor takes the
/// environment collision colour.
fn finish(doc: &mut MjcfDoc) {
    tree::recolor_collision_geoms(doc.worldbody_mut(), &ENVIRONMENT_COLLISION_COLOR, &|e| {
        attr(e, "name") == Some("floor")
    });
}

fn floor_at_origin(doc: &mut MjcfDoc) -> Result<()> {
    let floor = tree::children_mut(doc.worldbody_mut())
        .find(|e| e.name == "geom" && attr(e, "name") == Some("floor"))
        .ok_or_else(|| Error::model("the arena has no geom named `floor`"))?;
    set_attr(floor, "pos", array_to_string(&[0.0; 3]));
    Ok(())
}

fn direct_child_mut<'a>(
    parent: &'a mut crate::mjcf::Element,
    tag: &str,
    name: &str,
) -> Result<&'a mut crate::mjcf::Element> {
    tree::children_mut(parent)
        .find(|e| e.name == tag && attr(e, "name") == Some(name))
        .ok_or_else(|| Error::model(format!("the arena has no <{tag} name=\"{name}\">")))
}

impl Arena {
    /// robosuite's `TableArena(table_full_size, table_friction, table_offset)` from
    /// `arenas/table_arena.xml` (or another table file such as `arenas/pegs_arena.xml`):
    /// table body centred below `table_offset`, its collision and visual boxes and top site
    /// sized to the table, the four visual legs placed near the corners.
    ///
    /// # Errors
    /// [`Error::Model`] when the file is missing or lacks the table elements;
    /// [`Error::InvalidArgument`] for non-positive or non-finite sizes.
    pub fn table(
        assets: &Assets,
        file: &str,
        full_size: [f64; 3],
        friction: [f64; 3],
        offset: [f64; 3],
    ) -> Result<Self> {
        check_size("table_full_size", &full_size)?;
        if offset.iter().chain(&friction).any(|v| !v.is_finite()) {
            return Err(Error::invalid_argument(
                "table_offset",
                format!("must be finite, got offset {offset:?}, friction {friction:?}"),
            ));
        }
        let mut doc = load(assets, file)?;
        let half = full_size.map(|v| v / 2.0);
        let center = [offset[0], offset[1], -half[2] + offset[2]];
        floor_at_origin(&mut doc)?;
        let table = direct_child_mut(doc.worldbody_mut(), "body", "table")?;
        set_attr(table, "pos", array_to_string(&center));
        let collision = direct_child_mut(table, "geom", "table_collision")?;
        set_attr(collision, "size", array_to_string(&half));
        set_attr(collision, "friction", array_to_string(&friction));
        set_attr(
            direct_child_mut(table, "geom", "table_visual")?,
            "size",
            array_to_string(&half),
        );
        set_attr(
            direct_child_mut(table, "site", "table_top")?,
            "pos",
            array_to_string(&[0.0, 0.0, half[2]]),
        );
        let dx = [0.1, -0.1, -0.1, 0.1];
        let dy = [0.1, 0.1, -0.1, -0.1];
        for (i, (dx, dy)) in dx.iter().zip(dy).enumerate() {
            let leg = direct_child_mut(table, "geom", &format!("table_leg{}_visual", i + 1))?;
            let mut x = 0.0;
            if half[0] > (dx * 2.0f64).abs() {
                x += dx.signum() * half[0] - dx;
            }
            let mut y = 0.0;
            if half[1] > (dy * 2.0f64).abs() {
                y += dy.signum() * half[1] - dy;
            }
            let z = (offset[2] - half[2]) / 2.0;
            set_attr(leg, "pos", array_to_string(&[x, y, -z]));
            set_attr(leg, "size", array_to_string(&[0.025, z]));
        }
        finish(&mut doc);
        Ok(Self {
            doc,
            kind: ArenaKind::Table {
                length: full_size[0],
            },
            table_full_size: full_size,
            table_offset: offset,
        })
    }

    /// robosuite's `MultiTableArena(table_offsets, table_rots=0, table_full_sizes,
    /// table_frictions, has_legs=True)` from `arenas/multi_table_arena.xml`: after the
    /// mocap targets, per offset a body `table{i}` (top at the offset) with the collision
    /// box `table{i}_collision`, the visual box `table{i}_visual`, the site `table{i}_top`
    /// and four visual legs `table{i}_leg{k}_visual`.
    ///
    /// # Errors
    /// [`Error::Model`] when the file is missing or malformed;
    /// [`Error::InvalidArgument`] for non-positive or non-finite figures.
    pub fn multi_table(
        assets: &Assets,
        offsets: &[[f64; 3]],
        full_size: [f64; 3],
        friction: [f64; 3],
    ) -> Result<Self> {
        check_size("table_full_sizes", &full_size)?;
        if offsets
            .iter()
            .flatten()
            .chain(&friction)
            .any(|v| !v.is_finite())
        {
            return Err(Error::invalid_argument(
                "table_offsets",
                format!("must be finite, got {offsets:?}, friction {friction:?}"),
            ));
        }
        let mut doc = load(assets, "arenas/multi_table_arena.xml")?;
        let half = full_size.map(|v| v / 2.0);
        for (i, offset) in offsets.iter().enumerate() {
            let name = format!("table{i}");
            let mut body = element(
                "body",
                &[
                    ("name", name.clone()),
                    (
                        "pos",
                        array_to_string(&[offset[0], offset[1], offset[2] - half[2]]),
                    ),
                ],
            );
            let shape = |extra: Vec<(&str, String)>| {
                let mut attrs = extra;
                attrs.extend([
                    ("pos", "0 0 0".to_owned()),
                    ("quat", "1 0 0 0".to_owned()),
                    ("size", array_to_string(&half)),
                    ("type", "box".to_owned()),
                ]);
                element("geom", &attrs)
            };
            append(
                &mut body,
                shape(vec![
                    ("name", format!("{name}_collision")),
                    ("group", "0".to_owned()),
                    ("friction", array_to_string(&friction)),
                ]),
            );
            append(
                &mut body,
                shape(vec![
                    ("name", format!("{name}_visual")),
                    ("group", "1".to_owned()),
                    ("conaffinity", "0".to_owned()),
                    ("contype", "0".to_owned()),
                    ("material", "table_ceramic".to_owned()),
                ]),
            );
            append(
                &mut body,
                element(
                    "site",
                    &[
                        ("name", format!("{name}_top")),
                        ("pos", array_to_string(&[0.0, 0.0, half[2]])),
                        ("size", "0.001 0.001 0.001".to_owned()),
                        ("rgba", "0 0 0 0".to_owned()),
                    ],
                ),
            );
            let dx = [0.1, -0.1, -0.1, 0.1];
            let dy = [0.1, 0.1, -0.1, -0.1];
            for (k, (dx, dy)) in dx.iter().zip(dy).enumerate() {
                let mut x = 0.0;
                if half[0] > (dx * 2.0f64).abs() {
                    x += dx.signum() * half[0] - dx;
                }
                let mut y = 0.0;
                if half[1] > (dy * 2.0f64).abs() {
                    y += dy.signum() * half[1] - dy;
                }
                let z = (offset[2] - half[2]) / 2.0;
                append(
                    &mut body,
                    element(
                        "geom",
                        &[
                            ("name", format!("{name}_leg{k}_visual")),
                            ("pos", array_to_string(&[x, y, -z])),
                            ("type", "cylinder".to_owned()),
                            ("size", array_to_string(&[0.025, z])),
                            ("group", "1".to_owned()),
                            ("conaffinity", "0".to_owned()),
                            ("contype", "0".to_owned()),
                            ("material", "table_legs_metal".to_owned()),
                        ],
                    ),
                );
            }
            append(doc.worldbody_mut(), body);
        }
        finish(&mut doc);
        floor_at_origin(&mut doc)?;
        Ok(Self {
            doc,
            kind: ArenaKind::Table {
                length: full_size[0],
            },
            table_full_size: full_size,
            table_offset: offsets.first().copied().unwrap_or_default(),
        })
    }

    /// robosuite's `BinsArena(bin1_pos, table_full_size, table_friction)` from
    /// `arenas/bins_arena.xml` (the bins are fixed in the file; only the floor is placed).
    ///
    /// # Errors
    /// [`Error::Model`] when the file is missing or malformed.
    pub fn bins(assets: &Assets, bin1_pos: [f64; 3], full_size: [f64; 3]) -> Result<Self> {
        check_size("table_full_size", &full_size)?;
        let mut doc = load(assets, "arenas/bins_arena.xml")?;
        floor_at_origin(&mut doc)?;
        finish(&mut doc);
        Ok(Self {
            doc,
            kind: ArenaKind::Bins,
            table_full_size: full_size,
            table_offset: bin1_pos,
        })
    }

    /// robosuite's `EmptyArena` (`arenas/empty_arena.xml`): floor, walls, cameras.
    ///
    /// # Errors
    /// [`Error::Model`] when the file is missing or malformed.
    pub fn empty(assets: &Assets) -> Result<Self> {
        let mut doc = load(assets, "arenas/empty_arena.xml")?;
        finish(&mut doc);
        Ok(Self {
            doc,
            kind: ArenaKind::Empty,
            table_full_size: [0.0; 3],
            table_offset: [0.0; 3],
        })
    }

    /// robosuite's `Arena.set_origin`: adds `offset` to the position of every element
    /// directly in the world body that has one.
    ///
    /// # Errors
    /// [`Error::Model`] when a position is not three numbers.
    pub fn set_origin(&mut self, offset: [f64; 3]) -> Result<()> {
        for node in tree::children_mut(self.doc.worldbody_mut()) {
            if attr(node, "pos").is_some() {
                let p = tree::attr_array(node, "pos", [0.0; 3])?;
                set_attr(
                    node,
                    "pos",
                    array_to_string(&[p[0] + offset[0], p[1] + offset[1], p[2] + offset[2]]),
                );
            }
        }
        Ok(())
    }

    /// robosuite's `Arena.set_camera(camera_name, pos, quat)`: the first camera named
    /// `name` in the world body gets this `pos` and `quat` (wxyz); when there is none, a
    /// camera with them is appended to the world body.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a non-finite value.
    pub fn set_camera(&mut self, name: &str, pos: [f64; 3], quat: [f64; 4]) -> Result<()> {
        if pos.iter().chain(&quat).any(|v| !v.is_finite()) {
            return Err(Error::invalid_argument(
                "camera",
                format!("`{name}` needs a finite pose, got pos {pos:?}, quat {quat:?}"),
            ));
        }
        let (pos, quat) = (array_to_string(&pos), array_to_string(&quat));
        match tree::find_mut(self.doc.worldbody_mut(), "camera", &[("name", Some(name))]) {
            Some(camera) => {
                set_attr(camera, "pos", pos);
                set_attr(camera, "quat", quat);
            }
            None => append(
                self.doc.worldbody_mut(),
                element(
                    "camera",
                    &[("name", name.to_owned()), ("pos", pos), ("quat", quat)],
                ),
            ),
        }
        Ok(())
    }

    /// The table's body, for tasks that put things on it (Wipe's markers).
    ///
    /// # Errors
    /// [`Error::Model`] when the arena has no body `table`.
    pub fn table_body_mut(&mut self) -> Result<&mut crate::mjcf::Element> {
        direct_child_mut(self.doc.worldbody_mut(), "body", "table")
    }

    /// The table's half size.
    pub fn table_half_size(&self) -> [f64; 3] {
        self.table_full_size.map(|v| v / 2.0)
    }
}

fn check_size(name: &str, size: &[f64; 3]) -> Result<()> {
    if size.iter().any(|v| !v.is_finite() || *v <= 0.0) {
        return Err(Error::invalid_argument(
            name,
            format!("must be positive and finite, got {size:?}"),
        ));
    }
    Ok(())
}
