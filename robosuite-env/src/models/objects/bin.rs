//! robosuite's `Bin` and `Lid` (`models/objects/composite/bin.py`, `lid.py`): an open box
//! with four walls, and a flat lid with a handle (TwoArmTransport's bins and lid).

use super::CustomMaterial;
use super::composite::{CompositeGeom, CompositeObject, GeomType};
use crate::assets::Assets;
use crate::math::axisangle2quat;
use gym_core::{Error, Result};
use nalgebra::Vector3;
use std::f64::consts::PI;

/// robosuite's `dark_wood_mat` of bins and lids: `WoodDark`, cube, `texrepeat 3 3`.
fn dark_wood(assets: &Assets) -> Result<CustomMaterial> {
    CustomMaterial::new(
        assets,
        "WoodDark",
        "dark_wood",
        "dark_wood_mat",
        &[("type", "cube")],
        &[
            ("texrepeat", "3 3"),
            ("specular", "0.4"),
            ("shininess", "0.1"),
        ],
        false,
    )
}

fn check(name: &str, what: &str, values: &[f64]) -> Result<()> {
    if values.iter().any(|v| !v.is_finite() || *v <= 0.0) {
        return Err(Error::invalid_argument(
            what,
            format!("{name}: must be positive and finite, got {values:?}"),
        ));
    }
    Ok(())
}

/// robosuite's `Bin(name, bin_size, wall_thickness=0.01, transparent_walls=True,
/// density)` with texture: geom `base` (dark wood) and the transparent walls `wall0`..
/// `wall3` (turned π/2, 0, −π/2, π about z).
///
/// # Errors
/// [`Error::InvalidArgument`] for non-positive or non-finite figures; [`Error::Model`]
/// when the texture is missing.
pub fn bin(
    assets: &Assets,
    name: &str,
    bin_size: [f64; 3],
    density: f64,
) -> Result<CompositeObject> {
    check(name, "bin_size", &bin_size)?;
    check(name, "density", &[density])?;
    let t = 0.01;
    let material = dark_wood(assets)?;
    let base_size = [
        (bin_size[0] - t) / 2.0,
        (bin_size[1] - t) / 2.0,
        (t - 0.0) / 2.0,
    ];
    let mut base = CompositeGeom::new(
        GeomType::Box,
        &base_size,
        [0.0, 0.0, -(bin_size[2] - t) / 2.0],
    )
    .quat([1.0, 0.0, 0.0, 0.0])
    .named("base");
    base.material = Some(material.material_name().to_owned());
    let mut geoms = vec![base];
    let xs = [0.0, -(bin_size[0] - t) / 2.0, 0.0, (bin_size[0] - t) / 2.0];
    let ys = [-(bin_size[1] - t) / 2.0, 0.0, (bin_size[1] - t) / 2.0, 0.0];
    let ws = [bin_size[0], bin_size[1], bin_size[0], bin_size[1]];
    let rs = [PI / 2.0, 0.0, -PI / 2.0, PI];
    for i in 0..4 {
        let q = axisangle2quat(&Vector3::new(0.0, 0.0, rs[i]));
        let mut wall = CompositeGeom::new(
            GeomType::Box,
            &[t / 2.0, ws[i] / 2.0, bin_size[2] / 2.0],
            [xs[i], ys[i], 0.0],
        )
        .quat([q[3], q[0], q[1], q[2]])
        .named(format!("wall{i}"));
        wall.rgba = Some([1.0, 1.0, 1.0, 0.3]);
        geoms.push(wall);
    }
    let mut c = CompositeObject::centred(
        name,
        bin_size.map(|v| v / 2.0),
        density,
        [0.02, 1.0],
        [0.9, 0.95, 0.001],
    );
    c.geoms = geoms;
    c.materials = vec![material];
    Ok(c)
}

/// robosuite's `Lid(name, lid_size)` with its defaults (handle 2 × 8 × 3 cm, transparent,
/// density 250, the handle twice as dense): geoms `top` and `handle`.
///
/// # Errors
/// As [`bin`].
pub fn lid(assets: &Assets, name: &str, lid_size: [f64; 3]) -> Result<CompositeObject> {
    check(name, "lid_size", &lid_size)?;
    let handle = [0.02, 0.08, 0.03];
    let density = 250.0;
    let material = dark_wood(assets)?;
    let full = [lid_size[0], lid_size[1], lid_size[2] + handle[2]];
    let mut top = CompositeGeom::new(
        GeomType::Box,
        &[full[0] / 2.0, full[1] / 2.0, lid_size[2] / 2.0],
        [0.0, 0.0, (-full[2] + lid_size[2]) / 2.0],
    )
    .quat([1.0, 0.0, 0.0, 0.0])
    .named("top");
    top.rgba = Some([1.0, 1.0, 1.0, 0.3]);
    top.density = Some(density);
    let mut grip = CompositeGeom::new(
        GeomType::Box,
        &handle.map(|v| v / 2.0),
        [0.0, 0.0, (full[2] - handle[2]) / 2.0],
    )
    .quat([1.0, 0.0, 0.0, 0.0])
    .named("handle");
    grip.material = Some(material.material_name().to_owned());
    grip.density = Some(density * 2.0);
    let mut c = CompositeObject::new(name, full.map(|v| v / 2.0));
    c.locations_relative_to_center = true;
    c.geoms = vec![top, grip];
    c.materials = vec![material];
    Ok(c)
}
