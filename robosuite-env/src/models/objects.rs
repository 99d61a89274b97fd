//! Objects generated from their parameters (robosuite's `BoxObject`, and composites of
//! primitives standing in for robosuite's mesh and XML objects).

/// A free-floating box with robosuite's object naming: body `{name}_main`, free joint
/// `{name}_joint0`, collision geom `{name}_g0` (attach with the prefix `{name}_`).
#[derive(Debug, Clone, PartialEq)]
pub struct BoxObject {
    /// The object's name (the prefix of its body, joint and geom names).
    pub name: String,
    /// Half-extents (x, y, z) in metres at compile time.
    pub half_size: [f64; 3],
    /// Density in kg/m³ (robosuite's default 1000).
    pub density: f64,
    /// Sliding, torsional and rolling friction.
    pub friction: [f64; 3],
    /// Contact solref (time constant, damping ratio).
    pub solref: [f64; 2],
    /// Contact solimp (dmin, dmax, width).
    pub solimp: [f64; 3],
    /// Colour.
    pub rgba: [f64; 4],
}

impl BoxObject {
    /// A box with robosuite's `BoxObject` defaults: density 1000, friction (1, 0.005, 0.0001),
    /// solref (0.02, 1), solimp (0.9, 0.95, 0.001).
    pub fn new(name: impl Into<String>, half_size: [f64; 3], rgba: [f64; 4]) -> Self {
        Self {
            name: name.into(),
            half_size,
            density: 1000.0,
            friction: [1.0, 0.005, 0.0001],
            solref: [0.02, 1.0],
            solimp: [0.9, 0.95, 0.001],
            rgba,
        }
    }

    /// The object's MJCF, with unprefixed names (`main`, `joint0`, `g0`).
    pub fn to_xml(&self) -> String {
        let [x, y, z] = self.half_size;
        let [f0, f1, f2] = self.friction;
        let [r0, r1] = self.solref;
        let [i0, i1, i2] = self.solimp;
        let [c0, c1, c2, c3] = self.rgba;
        let density = self.density;
        format!(
            r#"<mujoco model="{name}">
  <compiler angle="radian" autolimits="true" inertiagrouprange="0 0"/>
  <worldbody>
    <body name="main" pos="0 0 {pz}">
      <freejoint name="joint0"/>
      <geom name="g0" type="box" pos="0 0 0" size="{x} {y} {z}" density="{density}" group="0" contype="1" conaffinity="1" condim="3" friction="{f0} {f1} {f2}" solref="{r0} {r1}" solimp="{i0} {i1} {i2}" rgba="{c0} {c1} {c2} {c3}"/>
    </body>
  </worldbody>
</mujoco>
"#,
            name = self.name,
            pz = 1.0 + z,
        )
    }

    /// The horizontal radius used by placement samplers (`‖(x, y)‖`).
    pub fn horizontal_radius(&self) -> f64 {
        self.half_size[0].hypot(self.half_size[1])
    }
}

/// One geom of a [`PrimitiveObject`]: MuJoCo type (`"box"`, `"cylinder"`, `"capsule"`),
/// size, position and orientation (wxyz) in the body frame.
#[derive(Debug, Clone, PartialEq)]
pub struct PrimitiveGeom {
    /// MuJoCo geom type.
    pub kind: &'static str,
    /// MuJoCo size (half-extents / radius and half-length).
    pub size: Vec<f64>,
    /// Position in the body frame.
    pub pos: [f64; 3],
    /// Orientation (wxyz) in the body frame.
    pub quat: [f64; 4],
}

impl PrimitiveGeom {
    /// A geom at `pos`, unrotated.
    pub fn new(kind: &'static str, size: &[f64], pos: [f64; 3]) -> Self {
        Self {
            kind,
            size: size.to_vec(),
            pos,
            quat: [1.0, 0.0, 0.0, 0.0],
        }
    }

    /// Rotated by `quat` (wxyz).
    #[must_use]
    pub fn rotated(mut self, quat: [f64; 4]) -> Self {
        self.quat = quat;
        self
    }
}

/// An object built from primitive geoms with robosuite's naming: body `main`, free joint
/// `joint0` (unless `fixed`), geoms `g0`, `g1`, ... and sites added by the caller.
#[derive(Debug, Clone, PartialEq)]
pub struct PrimitiveObject {
    /// Geoms, named `g{i}` in order.
    pub geoms: Vec<PrimitiveGeom>,
    /// Density (kg/m³).
    pub density: f64,
    /// Friction.
    pub friction: [f64; 3],
    /// solref.
    pub solref: [f64; 2],
    /// solimp.
    pub solimp: [f64; 3],
    /// Contact dimensionality.
    pub condim: u8,
    /// Colour.
    pub rgba: [f64; 4],
    /// Free-joint damping.
    pub joint_damping: f64,
    /// `false`: a colliding body on a free joint; `true`: a joint-less, non-colliding
    /// marker (robosuite's visual objects), placed through the model's body pose.
    pub visual_only: bool,
    /// Extra MJCF inside the body (sites).
    pub extra: String,
}

impl PrimitiveObject {
    /// A colliding free object with robosuite's default contact parameters.
    pub fn new(geoms: Vec<PrimitiveGeom>, density: f64, rgba: [f64; 4]) -> Self {
        Self {
            geoms,
            density,
            friction: [1.0, 0.005, 0.0001],
            solref: [0.02, 1.0],
            solimp: [0.9, 0.95, 0.001],
            condim: 3,
            rgba,
            joint_damping: 0.0,
            visual_only: false,
            extra: String::new(),
        }
    }

    /// The object's MJCF (attach with the prefix `{name}_`).
    pub fn to_xml(&self, model: &str) -> String {
        let [f0, f1, f2] = self.friction;
        let [r0, r1] = self.solref;
        let [i0, i1, i2] = self.solimp;
        let [c0, c1, c2, c3] = self.rgba;
        let contact = if self.visual_only {
            r#"contype="0" conaffinity="0" group="1""#.to_owned()
        } else {
            format!(
                r#"contype="1" conaffinity="1" group="0" condim="{}" friction="{f0} {f1} {f2}" solref="{r0} {r1}" solimp="{i0} {i1} {i2}" density="{}""#,
                self.condim, self.density
            )
        };
        let geoms: String = self
            .geoms
            .iter()
            .enumerate()
            .map(|(i, g)| {
                let size = g
                    .size
                    .iter()
                    .map(f64::to_string)
                    .collect::<Vec<_>>()
                    .join(" ");
                let [px, py, pz] = g.pos;
                let [qw, qx, qy, qz] = g.quat;
                format!(
                    r#"<geom name="g{i}" type="{}" size="{size}" pos="{px} {py} {pz}" quat="{qw} {qx} {qy} {qz}" {contact} rgba="{c0} {c1} {c2} {c3}"/>"#,
                    g.kind
                )
            })
            .collect::<Vec<_>>()
            .join("\n      ");
        let joint = if self.visual_only {
            String::new()
        } else {
            format!(
                r#"<joint name="joint0" type="free" damping="{}"/>"#,
                self.joint_damping
            )
        };
        format!(
            r#"<mujoco model="{model}">
  <compiler angle="radian" autolimits="true" inertiagrouprange="0 0"/>
  <worldbody>
    <body name="main" pos="0 0 1">
      {joint}
      {geoms}
      {extra}
    </body>
  </worldbody>
</mujoco>
"#,
            extra = self.extra
        )
    }
}
