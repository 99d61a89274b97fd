//! Arenas generated from their parameters (robosuite's `TableArena`).

/// A table arena: floor, a table box whose top face is at `top_z`, visual legs, the
/// `table_top` site and fixed cameras.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableArena {
    /// Full size of the table box (x, y, z) in metres.
    pub full_size: [f64; 3],
    /// Sliding, torsional and rolling friction of the table top.
    pub friction: [f64; 3],
    /// Position of the centre of the table top (robosuite's `table_offset`).
    pub top: [f64; 3],
}

impl Default for TableArena {
    /// robosuite's default: 0.8 × 0.8 × 0.05, friction (1, 0.005, 0.0001), top at z = 0.8.
    fn default() -> Self {
        Self {
            full_size: [0.8, 0.8, 0.05],
            friction: [1.0, 0.005, 0.0001],
            top: [0.0, 0.0, 0.8],
        }
    }
}

impl TableArena {
    /// The arena's MJCF (attach it to the world with an empty prefix).
    pub fn to_xml(&self) -> String {
        let [sx, sy, sz] = self.full_size.map(|v| v / 2.0);
        let [tx, ty, tz] = self.top;
        let body_z = tz - sz;
        let [f0, f1, f2] = self.friction;
        // Legs reach from under the table to the floor; they are visual only.
        let leg_half = ((body_z - sz) / 2.0).max(0.001);
        let leg_z = -sz - leg_half;
        let (lx, ly) = ((sx - 0.1).max(0.0), (sy - 0.1).max(0.0));
        let legs: String = [(lx, ly), (-lx, ly), (-lx, -ly), (lx, -ly)]
            .iter()
            .enumerate()
            .map(|(i, (x, y))| {
                format!(
                    r#"<geom name="table_leg{}_visual" type="cylinder" pos="{x} {y} {leg_z}" size="0.025 {leg_half}" group="1" contype="0" conaffinity="0" rgba="0.3 0.3 0.3 1"/>"#,
                    i + 1
                )
            })
            .collect::<Vec<_>>()
            .join("\n      ");
        format!(
            r#"<mujoco model="table_arena">
  <compiler angle="radian" autolimits="true" inertiagrouprange="0 0"/>
  <worldbody>
    <light name="key_light" pos="1.0 1.0 4.0" dir="-0.19 -0.19 -0.96" directional="true" diffuse="0.8 0.8 0.8" specular="0.3 0.3 0.3" castshadow="false"/>
    <light name="fill_light" pos="-3.0 -3.0 4.0" dir="0.5 0.5 -0.7" directional="true" diffuse="0.4 0.4 0.4" specular="0.1 0.1 0.1" castshadow="false"/>
    <geom name="floor" type="plane" pos="0 0 0" size="3 3 0.125" condim="3" group="1" contype="1" conaffinity="1" rgba="0.55 0.55 0.55 1"/>
    <body name="table" pos="{tx} {ty} {body_z}">
      <geom name="table_collision" type="box" pos="0 0 0" size="{sx} {sy} {sz}" group="0" contype="1" conaffinity="1" condim="3" friction="{f0} {f1} {f2}" rgba="0.5 0.5 0.5 1"/>
      {legs}
      <site name="table_top" pos="0 0 {sz}" size="0.001" rgba="0 0 0 0" group="2"/>
    </body>
    <camera name="frontview" mode="fixed" pos="1.6 0 1.45" quat="0.56 0.43 0.43 0.56"/>
    <camera name="birdview" mode="fixed" pos="-0.2 0 3.0" quat="0.7071 0 0 0.7071"/>
    <camera name="agentview" mode="fixed" pos="0.5 0 1.35" quat="0.653 0.271 0.271 0.653"/>
    <camera name="sideview" mode="fixed" pos="-0.0565 1.2761 1.4880" quat="0.0099 0.0069 0.5912 0.8064"/>
  </worldbody>
</mujoco>
"#
        )
    }
}
