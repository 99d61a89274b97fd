//! robosuite's `CustomMaterial`: a texture file from robosuite's `textures/` folder and the
//! material that uses it.

use crate::assets::Assets;
use crate::mjcf::Element;
use crate::mjcf::tree::element;
use gym_core::{Error, Result};

/// robosuite's named textures (`mjcf_utils.TEXTURE_FILES`).
const TEXTURE_FILES: &[(&str, &str)] = &[
    ("WoodRed", "red-wood.png"),
    ("WoodGreen", "green-wood.png"),
    ("WoodBlue", "blue-wood.png"),
    ("WoodLight", "light-wood.png"),
    ("WoodDark", "dark-wood.png"),
    ("WoodTiles", "wood-tiles.png"),
    ("WoodPanels", "wood-varnished-panels.png"),
    ("WoodgrainGray", "gray-woodgrain.png"),
    ("PlasterCream", "cream-plaster.png"),
    ("PlasterPink", "pink-plaster.png"),
    ("PlasterYellow", "yellow-plaster.png"),
    ("PlasterGray", "gray-plaster.png"),
    ("PlasterWhite", "white-plaster.png"),
    ("BricksWhite", "white-bricks.png"),
    ("Metal", "metal.png"),
    ("SteelBrushed", "steel-brushed.png"),
    ("SteelScratched", "steel-scratched.png"),
    ("Brass", "brass-ambra.png"),
    ("Bread", "bread.png"),
    ("Can", "can.png"),
    ("Ceramic", "ceramic.png"),
    ("Cereal", "cereal.png"),
    ("Clay", "clay.png"),
    ("Dirt", "dirt.png"),
    ("Glass", "glass.png"),
    ("FeltGray", "gray-felt.png"),
    ("Lemon", "lemon.png"),
];

/// A texture and a material robosuite adds to a generated object's assets.
#[derive(Debug, Clone, PartialEq)]
pub struct CustomMaterial {
    /// The `<texture>` attributes (`name`, `file`, and the given ones).
    pub texture: Vec<(&'static str, String)>,
    /// The `<material>` attributes (`name`, `texture`, and the given ones).
    pub material: Vec<(&'static str, String)>,
    /// Shared materials keep their names unprefixed (robosuite's `shared=True`).
    pub shared: bool,
}

impl CustomMaterial {
    /// robosuite's `CustomMaterial(texture, tex_name, mat_name, tex_attrib, mat_attrib,
    /// shared)` for a named texture (`"WoodRed"`, ...).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an unknown texture; [`Error::Model`] when the texture
    /// file is missing.
    pub fn new(
        assets: &Assets,
        texture: &str,
        tex_name: &str,
        mat_name: &str,
        tex_attrib: &[(&'static str, &str)],
        mat_attrib: &[(&'static str, &str)],
        shared: bool,
    ) -> Result<Self> {
        let file = TEXTURE_FILES
            .iter()
            .find(|(k, _)| *k == texture)
            .map(|(_, f)| *f)
            .ok_or_else(|| {
                Error::invalid_argument(
                    "texture",
                    format!(
                        "unknown texture `{texture}`; valid: {}",
                        TEXTURE_FILES
                            .iter()
                            .map(|(k, _)| *k)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                )
            })?;
        let path = assets.file(&format!("textures/{file}"))?;
        let mut tex: Vec<_> = tex_attrib
            .iter()
            .map(|(k, v)| (*k, (*v).to_owned()))
            .collect();
        tex.push(("name", tex_name.to_owned()));
        tex.push(("file", path.to_string_lossy().into_owned()));
        let mut mat: Vec<_> = mat_attrib
            .iter()
            .map(|(k, v)| (*k, (*v).to_owned()))
            .collect();
        mat.push(("name", mat_name.to_owned()));
        mat.push(("texture", tex_name.to_owned()));
        Ok(Self {
            texture: tex,
            material: mat,
            shared,
        })
    }

    /// The material's name.
    pub fn material_name(&self) -> &str {
        attr_of(&self.material, "name")
    }

    /// The texture's name.
    pub fn texture_name(&self) -> &str {
        attr_of(&self.texture, "name")
    }

    /// The `<texture>` and `<material>` elements.
    pub fn elements(&self) -> [Element; 2] {
        [
            element("texture", &self.texture),
            element("material", &self.material),
        ]
    }
}

fn attr_of<'a>(attrs: &'a [(&'static str, String)], key: &str) -> &'a str {
    attrs
        .iter()
        .find(|(k, _)| *k == key)
        .map(|(_, v)| v.as_str())
        .unwrap_or_default()
}
