//! robosuite's MJCF processing (`robosuite/models/base.py`, `utils/mjcf_utils.py`) in Rust:
//! the same documents, the same default-class inlining, naming prefixes, recolouring and
//! merges, so that a scene composed here is, element for element, the scene robosuite
//! composes from the same files.
//!
//! * [`tree`]: searching, prefixing and number lists on an element tree;
//! * [`MjcfDoc`]: one document (`MujocoXML`);
//! * [`XmlModel`]: a prefixed robot, gripper or mount file (`MujocoXMLModel`).

mod doc;
mod model;
pub mod tree;

pub use doc::{MergeBody, MjcfDoc};
pub use model::{ElementNames, XmlModel};
pub use xmltree::Element;
