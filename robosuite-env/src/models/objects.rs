//! Objects generated from their parameters (robosuite's `BoxObject`).

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
