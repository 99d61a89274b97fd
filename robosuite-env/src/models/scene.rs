//! A task's scene as robosuite's `ManipulationTask` composes it — the world of `base.xml`,
//! then the arena, the robots and the objects merged in that order — and its compilation.
//!
//! Compiling robosuite's meshes takes a tenth of a second or more, so compiled models are
//! kept in a process-wide cache keyed by the scene's MJCF, as [`SharedModel`]s: every
//! environment built from the same text gets a copy-on-write view of the one compiled model
//! ([`Scene::compile_shared`]).

use super::arenas::Arena;
use super::objects::ObjectModel;
use super::robots::RobotModel;
use crate::assets::Assets;
use crate::mjcf::tree::{self, append, set_attr};
use crate::mjcf::{MergeBody, MjcfDoc};
use crate::sim::{SharedModel, check_mujoco_version};
use gym_core::{Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};

mod patch;

/// robosuite's simulation timestep (`macros.SIMULATION_TIMESTEP`).
pub const SIMULATION_TIMESTEP: f64 = 0.002;

/// The bytes MuJoCo reserves per `mjData` for contacts, constraints and its stack unless a
/// task asks for more (robosuite's `njmax`/`nconmax` of 5000 reserve 1.2 GiB instead).
pub const DEFAULT_MEMORY: usize = 2 << 20;

/// The most compiled scenes the cache keeps.
const CACHE_CAPACITY: usize = 64;

/// A composed scene: one MJCF document, element for element the one robosuite composes.
#[derive(Debug, Clone)]
pub struct Scene {
    doc: MjcfDoc,
}

impl Scene {
    /// robosuite's `ManipulationTask(arena, robots, objects)` on `MujocoWorldBase`:
    /// `base.xml` with the timestep set, then the arena, each robot and each object (its
    /// assets merged, its body appended to the world body).
    ///
    /// # Errors
    /// [`Error::Model`] when `base.xml` is missing or malformed.
    pub fn compose(
        assets: &Assets,
        arena: &Arena,
        robots: &[RobotModel],
        objects: &[ObjectModel],
    ) -> Result<Self> {
        let mut doc = MjcfDoc::load(&assets.file("base.xml")?)?;
        let option = tree::find_mut(doc.root_mut(), "option", &[])
            .ok_or_else(|| Error::model("base.xml has no <option>"))?;
        set_attr(option, "timestep", tree::format_number(SIMULATION_TIMESTEP));
        doc.merge(arena.doc.clone(), MergeBody::World)?;
        for robot in robots {
            doc.merge(robot.doc().clone(), MergeBody::World)?;
        }
        for object in objects {
            doc.merge_assets(&object.assets);
            append(doc.worldbody_mut(), object.body.clone());
        }
        Ok(Self { doc })
    }

    /// The scene's document.
    pub fn doc(&self) -> &MjcfDoc {
        &self.doc
    }

    /// The scene's document, mutably (for tasks that edit it after the merge).
    pub fn doc_mut(&mut self) -> &mut MjcfDoc {
        &mut self.doc
    }

    /// The MJCF robosuite would compile (`env.model.get_xml()`).
    pub fn to_xml(&self) -> String {
        self.doc.to_xml()
    }

    /// The MJCF this crate compiles: [`Scene::to_xml`] with robosuite's `njmax`/`nconmax`
    /// replaced by an arena of `memory` bytes.
    pub fn to_mujoco_xml(&self, memory: usize) -> String {
        let mut doc = self.doc.clone();
        let root = doc.root_mut();
        if tree::child(root, "size").is_none() {
            append(root, crate::mjcf::Element::new("size"));
        }
        let size = tree::child_mut(root, "size").expect("just ensured");
        for attr_name in ["nconmax", "njmax"] {
            tree::remove_attr(size, attr_name);
        }
        set_attr(size, "memory", memory.to_string());
        doc.to_xml()
    }

    /// The scene with every texture (read from an image file or generated) replaced by a
    /// 1×1 flat grey texture of the same name and type: for environments that never render,
    /// whose physics textures do not touch, it saves the texture images (Lift: 20 MiB of its
    /// 61 MiB per environment). Names, counts and every physical quantity stay as they are.
    pub fn without_texture_images(&self) -> Self {
        const IMAGE_ATTRIBUTES: [&str; 16] = [
            "file",
            "fileright",
            "fileleft",
            "fileup",
            "filedown",
            "filefront",
            "fileback",
            "gridsize",
            "gridlayout",
            "content_type",
            "builtin",
            "rgb2",
            "mark",
            "markrgb",
            "random",
            "nchannel",
        ];
        let mut doc = self.doc.clone();
        let asset = doc.section_mut("asset");
        for texture in tree::children_mut(asset).filter(|e| e.name == "texture") {
            for a in IMAGE_ATTRIBUTES {
                tree::remove_attr(texture, a);
            }
            set_attr(texture, "builtin", "flat");
            set_attr(texture, "width", "1");
            set_attr(texture, "height", "1");
            set_attr(texture, "rgb1", "0.5 0.5 0.5");
        }
        Self { doc }
    }

    /// Compiles the scene with an arena of `memory` bytes (cached: a scene compiled before is
    /// copied).
    ///
    /// # Errors
    /// [`Error::Model`] when MuJoCo is not 3.17.0 or rejects the scene.
    pub fn compile(&self, memory: usize) -> Result<MjModel> {
        compile_cached(&self.to_mujoco_xml(memory))
    }

    /// As [`Scene::compile`], also returning the MJCF text compiled (shared with every
    /// compilation of the same text).
    ///
    /// # Errors
    /// As [`Scene::compile`].
    pub fn compile_with_source(&self, memory: usize) -> Result<(MjModel, Arc<str>)> {
        compile_cached_with_source(&self.to_mujoco_xml(memory))
    }

    /// As [`Scene::compile_with_source`], sharing the cached model instead of copying it
    /// (see [`compile_shared_with_source`]).
    ///
    /// # Errors
    /// As [`Scene::compile`].
    pub fn compile_shared(&self, memory: usize) -> Result<(Compiled, Arc<str>)> {
        compile_shared_with_source(&self.to_mujoco_xml(memory))
    }

    /// As [`Scene::compile_shared`] on [`Scene::without_texture_images`], for environments
    /// that never render: the compiled model has every name, count and physical value of
    /// this scene's, with 1×1 textures. Also returns this scene's own MJCF text (with its
    /// textures), from which the textured model is compiled when it is needed after all.
    ///
    /// # Errors
    /// As [`Scene::compile`].
    pub fn compile_shared_without_textures(&self, memory: usize) -> Result<(Compiled, Arc<str>)> {
        let textured = self.to_mujoco_xml(memory);
        let lock = || cache().lock().unwrap_or_else(PoisonError::into_inner);
        let known = lock()
            .bare
            .get_key_value(textured.as_str())
            .map(|(k, v)| (Arc::clone(k), Arc::clone(v)));
        let (source, bare) = match known {
            Some(pair) => pair,
            None => {
                let bare: Arc<str> = Arc::from(self.without_texture_images().to_mujoco_xml(memory));
                let source: Arc<str> = Arc::from(textured);
                let mut cache = lock();
                if cache.bare.len() >= CACHE_CAPACITY {
                    cache.bare.clear();
                }
                cache.bare.insert(Arc::clone(&source), Arc::clone(&bare));
                (source, bare)
            }
        };
        let (compiled, _) = compile_shared_with_source(&bare)?;
        Ok((compiled, source))
    }
}

/// A compiled scene: the cache's shared model, or a model of its own (a scene made by
/// patching a cached one, which is not cached).
#[derive(Debug)]
pub enum Compiled {
    /// The cached model, shared copy-on-write by every simulator made from it.
    Shared(Arc<SharedModel>),
    /// A model of its own.
    Own(MjModel),
}

impl Compiled {
    /// The compiled model (read only).
    pub fn model(&self) -> &MjModel {
        match self {
            Self::Shared(shared) => shared.model(),
            Self::Own(model) => model,
        }
    }

    /// A model of the caller's own (a copy of a shared one).
    pub fn into_model(self) -> MjModel {
        match self {
            Self::Shared(shared) => MjModel::clone(shared.model()),
            Self::Own(model) => model,
        }
    }
}

/// Turns off what MuJoCo enabled by default after robosuite 1.5.2's MuJoCo 3.3.7:
/// multi-point convex collisions (`multiccd`, opt-in in 3.3.7, on by default since). With it
/// on, mesh-mesh contacts inside robosuite's Robotiq grippers come out in different numbers
/// and the IIWA's Lift diverges from robosuite by 0.2 rad within a step; with it off, the
/// same scene file agrees between the two versions to 3e-9.
fn use_robosuites_collision_defaults(model: &mut MjModel) {
    let multiccd = mujoco_rs::wrappers::mj_model::MjtDisableBit::mjDSBL_MULTICCD as i32;
    model.opt_mut().disableflags |= multiccd;
}

/// Whether [`compile_cached`] may patch a cached model instead of compiling (see
/// [`set_scene_patching`]).
static PATCHING: AtomicBool = AtomicBool::new(true);

/// How many scenes were made by patching a cached model since the process started.
static PATCHED: AtomicUsize = AtomicUsize::new(0);

/// Turns on (the default) or off the patching of cached scenes: with it on, a text that
/// differs from one compiled before only in the sizes of generated box objects (the cube
/// sizes robosuite's resets draw, saved in each episode's scene) is made by copying that
/// model and resizing the boxes in place, as the tasks' resets do, rather than by a full
/// compile. Either way also empties the cache, so that the next compilations follow the new
/// setting (for comparisons).
pub fn set_scene_patching(enabled: bool) {
    PATCHING.store(enabled, Ordering::SeqCst);
    let mut cache = cache().lock().unwrap_or_else(PoisonError::into_inner);
    cache.exact.clear();
    cache.near.clear();
    cache.bare.clear();
}

/// How many scenes [`compile_cached`] made by patching a cached model (see
/// [`set_scene_patching`]) since the process started.
pub fn scenes_patched() -> usize {
    PATCHED.load(Ordering::SeqCst)
}

/// A scene compiled in full: its text, its skeleton and its model.
type NearEntry = (Arc<str>, Arc<patch::Skeleton>, Arc<SharedModel>);

/// The compiled scenes: by full text, and by skeleton (the text without its geom sizes).
#[derive(Default)]
struct Cache {
    exact: HashMap<Arc<str>, Arc<SharedModel>>,
    near: HashMap<String, NearEntry>,
    /// A scene's text with textures → its text without texture images.
    bare: HashMap<Arc<str>, Arc<str>>,
}

fn cache() -> &'static Mutex<Cache> {
    static CACHE: OnceLock<Mutex<Cache>> = OnceLock::new();
    CACHE.get_or_init(Default::default)
}

/// How a live env whose model was compiled from one text becomes the model of another
/// text of the same skeleton without a compile or a new model: copy `base` into its model
/// (`mj_copyModel` into the existing buffer), then apply `resizes` (see
/// [`in_place`]).
#[derive(Debug)]
pub(crate) struct InPlace {
    /// A model compiled from a text of the same skeleton (the cached full compile).
    pub(crate) base: Arc<SharedModel>,
    /// The box resizes that turn `base` into the new text's model (empty for the text
    /// `base` was compiled from).
    pub(crate) resizes: Vec<patch::BoxResize>,
}

/// How a model compiled from `current` becomes the model of `xml` in place (see
/// [`InPlace`]): `Some` when scene patching is on (see [`set_scene_patching`]), the two
/// texts differ at most in geom sizes, a model of that skeleton is cached and the
/// difference to it is one the patching handles; `None` otherwise (compile `xml` instead).
pub(crate) fn in_place(current: &str, xml: &str) -> Option<InPlace> {
    if !PATCHING.load(Ordering::SeqCst) {
        return None;
    }
    let sk = patch::skeleton(xml)?;
    if patch::skeleton(current)?.key != sk.key {
        return None;
    }
    let near = {
        let cache = cache().lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(model) = cache.exact.get(xml) {
            return Some(InPlace {
                base: Arc::clone(model),
                resizes: Vec::new(),
            });
        }
        cache.near.get(&sk.key).cloned()
    };
    let (base_xml, base_sk, base) = near?;
    let resizes = patch::plan(base.model(), &base_xml, &base_sk, xml, &sk)?;
    if !resizes.is_empty() {
        PATCHED.fetch_add(1, Ordering::SeqCst);
    }
    Some(InPlace { base, resizes })
}

/// Compiles MJCF text, or copies the model compiled from the same text before.
///
/// # Errors
/// [`Error::Model`] with MuJoCo's message when it rejects the text, or when the MuJoCo
/// library is not 3.17.0.
pub fn compile_cached(xml: &str) -> Result<MjModel> {
    compile_cached_with_source(xml).map(|(model, _)| model)
}

/// As [`compile_cached`], also returning the text compiled, shared (one allocation) with
/// every other compilation of the same text that is still cached. A text that differs from
/// a cached one only in the sizes of generated boxes is made by patching (see
/// [`set_scene_patching`]).
///
/// # Errors
/// As [`compile_cached`].
pub fn compile_cached_with_source(xml: &str) -> Result<(MjModel, Arc<str>)> {
    compile_shared_with_source(xml).map(|(compiled, key)| (compiled.into_model(), key))
}

/// As [`compile_cached_with_source`], giving the cached model itself
/// ([`Compiled::Shared`]) rather than a copy: [`crate::sim::Sim::new_shared`] makes a
/// copy-on-write view of it, so every environment of one scene shares its memory. A scene
/// made by patching (see [`set_scene_patching`]) is a model of its own ([`Compiled::Own`]).
///
/// # Errors
/// As [`compile_cached`].
pub fn compile_shared_with_source(xml: &str) -> Result<(Compiled, Arc<str>)> {
    check_mujoco_version()?;
    let skeleton = if PATCHING.load(Ordering::SeqCst) {
        patch::skeleton(xml)
    } else {
        None
    };
    // Patches run outside the lock (several threads load scenes at once); only full
    // compilations hold it.
    let lock = || cache().lock().unwrap_or_else(PoisonError::into_inner);
    let base = {
        let cache = lock();
        if let Some((key, model)) = cache.exact.get_key_value(xml) {
            return Ok((Compiled::Shared(Arc::clone(model)), Arc::clone(key)));
        }
        skeleton
            .as_ref()
            .and_then(|sk| cache.near.get(&sk.key).cloned())
    };
    if let (Some(sk), Some((base_xml, base_sk, base))) = (&skeleton, base)
        && let Ok(Some(model)) = patch::patched(base.model(), &base_xml, &base_sk, xml, sk)
    {
        // Not cached: patching again costs no more than copying a cached model.
        PATCHED.fetch_add(1, Ordering::SeqCst);
        return Ok((Compiled::Own(model), Arc::from(xml)));
    }
    // One compilation at a time: MuJoCo's XML loader keeps global state.
    let mut cache = lock();
    if let Some((key, model)) = cache.exact.get_key_value(xml) {
        // compiled by another thread meanwhile
        return Ok((Compiled::Shared(Arc::clone(model)), Arc::clone(key)));
    }
    let mut model = MjModel::from_xml_string(xml)
        .map_err(|e| Error::model(format!("MuJoCo cannot compile the scene: {e}")))?;
    use_robosuites_collision_defaults(&mut model);
    if cache.exact.len() >= CACHE_CAPACITY {
        cache.exact.clear();
    }
    if cache.near.len() >= CACHE_CAPACITY {
        cache.near.clear();
    }
    // Under the lock: the first call compiles a tiny template model.
    let model = SharedModel::new(model);
    let key: Arc<str> = Arc::from(xml);
    cache.exact.insert(Arc::clone(&key), Arc::clone(&model));
    if let Some(sk) = skeleton {
        // The first compile of a skeleton stays its base (a full compile, unless evicted).
        if !cache.near.contains_key(&sk.key) {
            let k = sk.key.clone();
            cache
                .near
                .insert(k, (Arc::clone(&key), Arc::new(sk), Arc::clone(&model)));
        }
    }
    drop(cache);
    Ok((Compiled::Shared(model), key))
}
