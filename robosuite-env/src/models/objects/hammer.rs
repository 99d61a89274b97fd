//! robosuite's `HammerObject` (`models/objects/composite/hammer.py`): a box handle with a
//! head, neck, face and claw, every figure drawn at random (TwoArmHandover's hammer and
//! TwoArmTransport's payload).

use super::composite::{CompositeGeom, CompositeObject, GeneratedObject, GeomType};
use super::{CustomMaterial, ObjectModel};
use crate::assets::Assets;
use gym_core::{EnvRng, Error, Result};
use rand::RngExt;

/// The ranges robosuite draws a hammer's figures from (its constructor arguments; a fixed
/// value is a range of one point).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HammerRanges {
    /// Handle half-width (default 1.5 to 2 cm).
    pub handle_radius: [f64; 2],
    /// Handle length (default 10 to 25 cm).
    pub handle_length: [f64; 2],
    /// Handle density (default 100 to 250).
    pub handle_density: [f64; 2],
    /// Handle sliding friction (default 3 to 5).
    pub handle_friction: [f64; 2],
    /// Head density over handle density (default 2).
    pub head_density_ratio: f64,
}

impl Default for HammerRanges {
    fn default() -> Self {
        Self {
            handle_radius: [0.015, 0.02],
            handle_length: [0.1, 0.25],
            handle_density: [100.0, 250.0],
            handle_friction: [3.0, 5.0],
            head_density_ratio: 2.0,
        }
    }
}

impl HammerRanges {
    /// Checks that every range is finite, positive and ordered.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the range.
    pub fn validate(&self) -> Result<()> {
        for (name, [lo, hi]) in [
            ("handle_radius", self.handle_radius),
            ("handle_length", self.handle_length),
            ("handle_density", self.handle_density),
            ("handle_friction", self.handle_friction),
        ] {
            if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo <= hi) {
                return Err(Error::invalid_argument(
                    name,
                    format!("need 0 < min <= max, got [{lo}, {hi}]"),
                ));
            }
        }
        if !(self.head_density_ratio.is_finite() && self.head_density_ratio > 0.0) {
            return Err(Error::invalid_argument(
                "head_density_ratio",
                format!("must be positive, got {}", self.head_density_ratio),
            ));
        }
        Ok(())
    }
}

/// A hammer's drawn figures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HammerFigures {
    /// Handle half-width.
    pub handle_radius: f64,
    /// Handle length.
    pub handle_length: f64,
    /// Handle density.
    pub handle_density: f64,
    /// Handle sliding friction.
    pub handle_friction: f64,
    /// Head half-size, `U(r, 1.2 r)`.
    pub head_halfsize: f64,
}

impl HammerFigures {
    /// robosuite's draws, in its order: radius, length, density, friction, head half-size.
    pub fn draw(ranges: &HammerRanges, rng: &mut EnvRng) -> Self {
        let mut u = |[lo, hi]: [f64; 2]| lo + (hi - lo) * rng.random::<f64>();
        let handle_radius = u(ranges.handle_radius);
        let handle_length = u(ranges.handle_length);
        let handle_density = u(ranges.handle_density);
        let handle_friction = u(ranges.handle_friction);
        let head_halfsize = u([handle_radius, handle_radius * 1.2]);
        Self {
            handle_radius,
            handle_length,
            handle_density,
            handle_friction,
            head_halfsize,
        }
    }

    /// The middle of each range (what the scene is composed with before the first draw).
    pub fn middle(ranges: &HammerRanges) -> Self {
        let mid = |[lo, hi]: [f64; 2]| 0.5 * (lo + hi);
        let handle_radius = mid(ranges.handle_radius);
        Self {
            handle_radius,
            handle_length: mid(ranges.handle_length),
            handle_density: mid(ranges.handle_density),
            handle_friction: mid(ranges.handle_friction),
            head_halfsize: 1.1 * handle_radius,
        }
    }

    /// As five numbers (radius, length, density, friction, head half-size).
    pub fn to_array(self) -> [f64; 5] {
        [
            self.handle_radius,
            self.handle_length,
            self.handle_density,
            self.handle_friction,
            self.head_halfsize,
        ]
    }

    /// From [`HammerFigures::to_array`]'s layout.
    pub fn from_array(v: [f64; 5]) -> Self {
        Self {
            handle_radius: v[0],
            handle_length: v[1],
            handle_density: v[2],
            handle_friction: v[3],
            head_halfsize: v[4],
        }
    }

    /// robosuite's `bottom_offset` / `top_offset` z: `∓handle_radius`.
    pub fn top_offset(&self) -> f64 {
        self.handle_radius
    }
}

/// robosuite's hammer with box handle and textures: name, figures and density ratio.
#[derive(Debug, Clone, PartialEq)]
pub struct Hammer {
    /// The object's name.
    pub name: String,
    /// The drawn figures.
    pub figures: HammerFigures,
    /// Head density over handle density.
    pub head_density_ratio: f64,
    /// robosuite's `metal` / `metal_mat` and `wood` / `wood_mat`.
    pub materials: [CustomMaterial; 2],
}

/// robosuite's hammer materials: cube textures, `texrepeat 3 3`.
fn material(assets: &Assets, texture: &str, name: &str) -> Result<CustomMaterial> {
    CustomMaterial::new(
        assets,
        texture,
        name,
        &format!("{name}_mat"),
        &[("type", "cube")],
        &[
            ("texrepeat", "3 3"),
            ("specular", "0.4"),
            ("shininess", "0.1"),
        ],
        false,
    )
}

/// robosuite's quaternion (wxyz) turning the neck and face cylinders onto x: its literal
/// 0.707106, not 1/√2.
#[allow(clippy::approx_constant)]
const ONTO_X: [f64; 4] = [0.707106, 0.0, 0.707106, 0.0];

/// One head part of the hammer: shape, size, location, orientation (wxyz), name.
struct HeadPart {
    kind: GeomType,
    size: Vec<f64>,
    location: [f64; 3],
    quat: [f64; 4],
    name: &'static str,
}

/// The hammer's geoms, in robosuite's order.
pub const HAMMER_GEOMS: [&str; 5] = ["handle", "head", "neck", "face", "claw"];

impl Hammer {
    /// A hammer `name` with these figures.
    ///
    /// # Errors
    /// [`Error::Model`] when a texture is missing.
    pub fn new(
        assets: &Assets,
        name: &str,
        figures: HammerFigures,
        head_density_ratio: f64,
    ) -> Result<Self> {
        Ok(Self {
            name: name.to_owned(),
            figures,
            head_density_ratio,
            materials: [
                material(assets, "SteelScratched", "metal")?,
                material(assets, "WoodLight", "wood")?,
            ],
        })
    }

    /// robosuite's `init_quat` (xyzw), drawn anew at every placement:
    /// `(0.5, −0.5, 0.5, −0.5)` or `(−0.5, −0.5, −0.5, −0.5)` with even odds.
    pub fn init_quat(rng: &mut EnvRng) -> [f64; 4] {
        if rng.random::<f64>() >= 0.5 {
            [0.5, -0.5, 0.5, -0.5]
        } else {
            [-0.5, -0.5, -0.5, -0.5]
        }
    }

    /// The composite object robosuite generates: geoms `handle` (box), `head` (box), `neck`
    /// and `face` (cylinders turned onto x), `claw` (box turned 45° about y).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for non-positive or non-finite figures.
    pub fn composite(&self) -> Result<CompositeObject> {
        let f = self.figures;
        if f.to_array().iter().any(|v| !v.is_finite() || *v <= 0.0) {
            return Err(Error::invalid_argument(
                "hammer",
                format!("every figure must be positive and finite, got {f:?}"),
            ));
        }
        let (r, len, h) = (f.handle_radius, f.handle_length, f.head_halfsize);
        let head_density = f.handle_density * self.head_density_ratio;
        let [metal, wood] = [0, 1].map(|i| Some(self.materials[i].material_name().to_owned()));
        let head_z = len / 2.0 + h;
        let mut handle = CompositeGeom::new(GeomType::Box, &[r, r, len / 2.0], [0.0; 3])
            .quat([1.0, 0.0, 0.0, 0.0])
            .named("handle");
        handle.material = wood;
        handle.friction = Some([f.handle_friction, 0.005, 0.0001]);
        handle.density = Some(f.handle_density);
        let mut geoms = vec![handle];
        let part = |kind, size: Vec<f64>, location, quat, name| HeadPart {
            kind,
            size,
            location,
            quat,
            name,
        };
        let parts = [
            part(
                GeomType::Box,
                vec![h * 2.0, h, h],
                [0.0, 0.0, head_z],
                [1.0, 0.0, 0.0, 0.0],
                "head",
            ),
            part(
                GeomType::Cylinder,
                vec![h * 0.8, h * 0.2],
                [h * 2.2, 0.0, head_z],
                ONTO_X,
                "neck",
            ),
            part(
                GeomType::Cylinder,
                vec![h, h * 0.4],
                [h * 2.8, 0.0, head_z],
                ONTO_X,
                "face",
            ),
            part(
                GeomType::Box,
                vec![h * 0.7072, h * 0.95, h * 0.7072],
                [-h * 2.0, 0.0, head_z],
                [0.9238795, 0.0, 0.3826834, 0.0],
                "claw",
            ),
        ];
        for p in parts {
            let mut g = CompositeGeom::new(p.kind, &p.size, p.location)
                .quat(p.quat)
                .named(p.name);
            g.material = metal.clone();
            g.density = Some(head_density);
            geoms.push(g);
        }
        let total = [3.2 * h / 2.0, h / 2.0, (len + 2.0 * h) / 2.0];
        let mut c = CompositeObject::centred(
            &self.name,
            total,
            f.handle_density,
            [0.02, 1.0],
            [0.9, 0.95, 0.001],
        );
        c.density = None;
        c.geoms = geoms;
        c.materials = self.materials.to_vec();
        Ok(c)
    }
}

/// The compiler settings of robosuite's `base.xml` that shape a body's inertia.
const DONOR_XML: &str = r#"<mujoco model="donor"><compiler angle="radian" inertiagrouprange="0 0" autolimits="true"/><worldbody/></mujoco>"#;

impl Hammer {
    /// The hammer alone, compiled as robosuite's `base.xml` compiles it (materials left
    /// out): the donor of [`crate::sim::reshape_body_from`], which gives the scene's hammer
    /// these figures without recompiling the scene. Its body is body 1.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for invalid figures; [`Error::Model`] when MuJoCo rejects
    /// the body.
    pub fn donor_model(&self) -> Result<mujoco_rs::wrappers::mj_model::MjModel> {
        let mut body = self.build()?.body;
        crate::mjcf::tree::visit_mut(&mut body, &mut |e| {
            crate::mjcf::tree::remove_attr(e, "material");
        });
        let mut doc = crate::mjcf::MjcfDoc::parse(DONOR_XML, std::path::Path::new("donor.xml"))?;
        crate::mjcf::tree::append(doc.worldbody_mut(), body);
        mujoco_rs::wrappers::mj_model::MjModel::from_xml_string(&doc.to_xml())
            .map_err(|e| Error::model(format!("MuJoCo cannot compile the hammer: {e}")))
    }
}

impl GeneratedObject for Hammer {
    /// The object, with robosuite's overridden extent: bottom and top at `∓handle_radius`,
    /// horizontal radius `head_halfsize + handle_length / 2`.
    fn build(&self) -> Result<ObjectModel> {
        let mut built = self.composite()?.build()?;
        let f = self.figures;
        built.bottom_offset = [0.0, 0.0, -f.handle_radius];
        built.top_offset = [0.0, 0.0, f.handle_radius];
        built.horizontal_radius = f.head_halfsize + 0.5 * f.handle_length;
        Ok(built)
    }

    fn bounding_box_half_size(&self, _built: &ObjectModel) -> [f64; 3] {
        let h = self.figures.head_halfsize;
        [
            3.2 * h / 2.0,
            h / 2.0,
            (self.figures.handle_length + 2.0 * h) / 2.0,
        ]
    }
}
