//! Composes a scene from parts with MuJoCo's model editing (`mjs_attach`), giving every
//! element robosuite's name.

use crate::robots::RobotSpec;
use crate::sim::check_mujoco_version;
use gym_core::{Error, Result};
use mujoco_rs::wrappers::mj_editing::{Attach, MjSpec};
use mujoco_rs::wrappers::mj_model::MjModel;

fn parse(part: &str, xml: &str) -> Result<MjSpec> {
    if xml.contains('\0') {
        return Err(Error::Model(format!(
            "the MJCF of `{part}` contains a NUL byte"
        )));
    }
    MjSpec::from_xml_string(xml)
        .map_err(|e| Error::Model(format!("cannot parse the MJCF of `{part}`: {e:?}")))
}

fn attach_error(part: &str) -> impl FnOnce(mujoco_rs::error::MjEditError) -> Error + '_ {
    move |e| Error::Model(format!("cannot attach `{part}`: {e:?}"))
}

/// Builds a scene: the world, then an arena, robots and objects, compiled to one model.
///
/// Body order (and so joint, qpos and actuator order) follows the order of the calls, so
/// tasks add robots before objects, as robosuite does.
#[derive(Debug)]
pub struct SceneBuilder {
    spec: MjSpec,
}

impl SceneBuilder {
    /// Starts from the empty world (physics options of robosuite).
    ///
    /// # Errors
    /// [`Error::Model`] when the MuJoCo library is not 3.17.0 or the world cannot be parsed.
    pub fn new() -> Result<Self> {
        check_mujoco_version()?;
        Ok(Self {
            spec: parse("world", super::WORLD_XML)?,
        })
    }

    /// Starts from the world with an arena: the content of the arena MJCF's `<worldbody>`
    /// becomes the world's, keeping the arena's names unprefixed (`floor`, `table`,
    /// `table_top`, ...) as robosuite's arenas are.
    ///
    /// # Errors
    /// [`Error::Model`] when the MuJoCo library is not 3.17.0, the arena has no
    /// `<worldbody>`, or the result cannot be parsed.
    pub fn with_arena(arena_xml: &str) -> Result<Self> {
        check_mujoco_version()?;
        let inner = arena_xml
            .find("<worldbody>")
            .and_then(|start| {
                let from = start + "<worldbody>".len();
                arena_xml[from..]
                    .rfind("</worldbody>")
                    .map(|end| &arena_xml[from..from + end])
            })
            .ok_or_else(|| {
                Error::Model("the arena MJCF has no <worldbody>...</worldbody>".into())
            })?;
        let world = super::WORLD_XML.replacen(
            "<worldbody/>",
            &format!("<worldbody>{inner}</worldbody>"),
            1,
        );
        Ok(Self {
            spec: parse("arena", &world)?,
        })
    }

    /// Attaches a part's world-body content at the world origin with a name prefix.
    ///
    /// # Errors
    /// [`Error::Model`] when the part does not parse or attach.
    pub fn add_part(&mut self, part: &str, xml: &str, prefix: &str) -> Result<&mut Self> {
        self.add_part_at(part, xml, prefix, [0.0; 3], [1.0, 0.0, 0.0, 0.0])
    }

    /// Attaches a part's world-body content in a frame at `pos` / `quat` (wxyz).
    ///
    /// # Errors
    /// [`Error::Model`] when the part does not parse or attach.
    pub fn add_part_at(
        &mut self,
        part: &str,
        xml: &str,
        prefix: &str,
        pos: [f64; 3],
        quat: [f64; 4],
    ) -> Result<&mut Self> {
        let mut child = parse(part, xml)?;
        self.spec
            .world_body_mut()
            .add_frame()
            .with_pos(pos)
            .with_quat(quat)
            .attach_by_deep_copy(&mut child, prefix, "")
            .map_err(attach_error(part))?;
        Ok(self)
    }

    /// Attaches a part to the body `parent` (a full, prefixed name) with a name prefix.
    ///
    /// # Errors
    /// [`Error::Model`] when the body does not exist or the part does not parse or attach.
    pub fn add_part_to_body(
        &mut self,
        part: &str,
        xml: &str,
        parent: &str,
        prefix: &str,
    ) -> Result<&mut Self> {
        let mut child = parse(part, xml)?;
        let body = self.spec.body_mut(parent).ok_or_else(|| {
            Error::Model(format!(
                "cannot attach `{part}`: the scene has no body `{parent}`"
            ))
        })?;
        body.attach_by_deep_copy(&mut child, prefix, "")
            .map_err(attach_error(part))?;
        Ok(self)
    }

    /// Adds robot `index` with its base at `pos` / `quat` (wxyz): the arm (prefix
    /// `robot{index}_`), its mount under the base (prefix `fixed_mount{index}_`) and its
    /// gripper on the hand (prefix `gripper{index}_right_`).
    ///
    /// # Errors
    /// [`Error::Model`] when a part does not parse or attach.
    pub fn add_robot(
        &mut self,
        index: usize,
        robot: &RobotSpec,
        pos: [f64; 3],
        quat: [f64; 4],
    ) -> Result<&mut Self> {
        let prefix = format!("robot{index}_");
        self.add_part_at(robot.arm.name, robot.arm.xml, &prefix, pos, quat)?;
        if let Some(gripper) = &robot.gripper {
            let hand = format!("{prefix}{}", robot.arm.hand_body);
            self.add_part_to_body(
                gripper.name,
                gripper.xml,
                &hand,
                &format!("gripper{index}_right_"),
            )?;
        }
        if let Some(mount) = robot.arm.mount_xml {
            let base = format!("{prefix}{}", robot.arm.base_body);
            self.add_part_to_body("mount", mount, &base, &format!("fixed_mount{index}_"))?;
        }
        Ok(self)
    }

    /// Sets the bytes MuJoCo reserves per `mjData` for contacts, constraints and its stack
    /// (the world's default is 2 MiB); tasks with many contacts may need more.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for less than 64 KiB.
    pub fn set_memory(&mut self, bytes: usize) -> Result<&mut Self> {
        if bytes < 1 << 16 {
            return Err(Error::invalid_argument(
                "memory",
                format!("need at least 64 KiB, got {bytes} bytes"),
            ));
        }
        self.spec.set_memory(bytes as _);
        Ok(self)
    }

    /// Compiles the scene.
    ///
    /// # Errors
    /// [`Error::Model`] with MuJoCo's message when compilation fails.
    pub fn compile(mut self) -> Result<MjModel> {
        self.spec
            .compile()
            .map_err(|e| Error::Model(format!("cannot compile the scene: {e:?}")))
    }

    /// The scene as MJCF text (for inspection or to load elsewhere).
    ///
    /// # Errors
    /// [`Error::Model`] when MuJoCo cannot write the XML.
    pub fn to_xml(&mut self) -> Result<String> {
        // Compiling first resolves defaults, so the saved XML is complete.
        self.spec
            .compile()
            .map_err(|e| Error::Model(format!("cannot compile the scene: {e:?}")))?;
        self.spec
            .save_xml_string(1 << 20)
            .map_err(|e| Error::Model(format!("cannot write the scene XML: {e:?}")))
    }
}
