//! robosuite's instance and class segmentations: which model part each geom belongs to
//! (`Task.generate_id_mappings`), as the ids the segmentation frames hold.

use crate::models::objects::Shape;
use crate::models::robots::RobotModel;
use crate::tasks::TaskScene;
use mujoco_rs::prelude::{MjModel, MjtObjBase};

/// One model part for robosuite's instance and class segmentations (an entry of its
/// `instances_to_ids`, in order): a robot, mount, gripper or object, whose geoms are the
/// named geoms with its prefix, or a top-level arena body, whose geoms are its subtree's
/// visual (group 1) geoms.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SegmentGroup {
    /// The instance (unique).
    pub instance: String,
    /// The class (shared by instances of one kind, such as two `BoxObject`s).
    pub class: String,
    /// Where its geoms are.
    pub geoms: GroupGeoms,
}

/// How a [`SegmentGroup`] finds its geoms in the model.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum GroupGeoms {
    /// The geoms whose names start with this prefix (`robot0_`, `cube_`, ...).
    Prefix(String),
    /// The visual (group 1) geoms of this body's subtree.
    Body(String),
}

/// Per geom id, the 1-based index of its group (by instance or by class, in order of first
/// appearance), 0 for a geom in none: robosuite's `mapping.get(id, -1) + 1`.
pub(crate) fn segment_ids(model: &MjModel, groups: &[SegmentGroup], by_class: bool) -> Vec<i32> {
    let ngeom = model.ffi().ngeom.max(0) as usize;
    let mut ids = vec![0; ngeom];
    let mut names: Vec<&str> = Vec::new();
    let parents = model.body_parentid();
    let (geom_body, geom_group) = (model.geom_bodyid(), model.geom_group());
    for g in groups {
        let key = if by_class { &g.class } else { &g.instance };
        let id = match names.iter().position(|n| n == key) {
            Some(i) => i,
            None => {
                names.push(key);
                names.len() - 1
            }
        } as i32
            + 1;
        let body = match &g.geoms {
            GroupGeoms::Body(name) => model.name_to_id(MjtObjBase::mjOBJ_BODY, name),
            GroupGeoms::Prefix(_) => None,
        };
        for (geom, slot) in ids.iter_mut().enumerate() {
            let member = match &g.geoms {
                GroupGeoms::Prefix(prefix) => model
                    .id_to_name(MjtObjBase::mjOBJ_GEOM, geom)
                    .is_some_and(|n| n.starts_with(prefix.as_str())),
                GroupGeoms::Body(_) => {
                    body.is_some_and(|b| {
                        let mut at = geom_body[geom] as usize;
                        loop {
                            if at == b {
                                break true;
                            }
                            if at == 0 {
                                break false;
                            }
                            at = parents[at] as usize;
                        }
                    }) && geom_group[geom] == 1
                }
            };
            if member && *slot == 0 {
                *slot = id;
            }
        }
    }
    ids
}

/// robosuite's `Task.generate_id_mappings` order: the objects, then each robot, its mount
/// and its grippers, then the arena's top-level bodies (but the table and the mocap
/// targets).
pub(crate) fn groups(task_scene: &TaskScene, robots: &[RobotModel]) -> Vec<SegmentGroup> {
    let prefixed = |instance: String, class: &str, prefix: &str| SegmentGroup {
        instance,
        class: class.to_owned(),
        geoms: GroupGeoms::Prefix(prefix.to_owned()),
    };
    let mut groups = Vec::new();
    for o in &task_scene.objects {
        // Generated boxes and cylinders share robosuite's classes; other objects each
        // have their own.
        let class = match o.shape {
            Some(Shape::Box(_)) => "BoxObject".to_owned(),
            Some(Shape::Cylinder(_)) => "CylinderObject".to_owned(),
            None => format!("object:{}", o.name),
        };
        groups.push(prefixed(o.name.clone(), &class, &format!("{}_", o.name)));
    }
    for r in robots {
        let name = r.info.name;
        groups.push(prefixed(format!("{name}{}", r.idn), name, &r.xml.prefix));
        if let Some(m) = &r.mount {
            let class = m.info.name;
            groups.push(prefixed(format!("{class}{}", r.idn), class, &m.xml.prefix));
        }
        for arm in &r.arms {
            let class = arm.gripper.info.name;
            let instance = format!("{class}{}_{}", r.idn, arm.side);
            groups.push(prefixed(instance, class, &arm.gripper.xml.prefix));
        }
    }
    let arena = task_scene.arena.doc.worldbody();
    for body in crate::mjcf::tree::children(arena).filter(|e| e.name == "body") {
        if let Some(name) = crate::mjcf::tree::attr(body, "name")
            && !["table", "left_eef_target", "right_eef_target"].contains(&name)
        {
            groups.push(SegmentGroup {
                instance: name.to_owned(),
                class: name.to_owned(),
                geoms: GroupGeoms::Body(name.to_owned()),
            });
        }
    }
    groups
}
