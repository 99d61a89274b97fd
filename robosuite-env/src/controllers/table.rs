//! The arm controller table: one entry per robosuite arm controller type, from which the
//! list of types ([`ARM_CONTROLLER_TYPES`]), the parsing of a part config (its keys come
//! from the config's serde struct) and the building of the controller all derive.
//!
//! Adding an arm controller takes its config struct, its [`ArmControllerConfig`] variant
//! and one entry in [`ARM_CONTROLLERS`].

use super::config::{
    ArmControllerConfig, IkConfig, JointPositionConfig, JointTorqueConfig, JointVelocityConfig,
    OscConfig, typed,
};
use super::{
    ArmBinding, ArmController, InverseKinematics, JointPosition, JointTorque, JointVelocity, Osc,
    Timing,
};
use gym_core::{Error, Result};
use serde_aux::serde_introspection::serde_introspect;
use serde_json::Value;

/// Builds a controller from a config of its type (arguments as
/// [`super::build_arm_controller`]'s).
pub type BuildFn =
    fn(&ArmControllerConfig, ArmBinding, Timing, &str) -> Result<Box<dyn ArmController>>;

/// One arm controller type of the table.
#[derive(Debug, Clone, Copy)]
pub struct ArmControllerEntry {
    /// robosuite's config `type`, such as `"OSC_POSE"`.
    pub name: &'static str,
    /// Whether a config is of this type.
    pub is: fn(&ArmControllerConfig) -> bool,
    /// The keys a config of this type may hold besides `type` and `gripper`: the fields
    /// of its serde struct.
    pub keys: fn() -> &'static [&'static str],
    /// Keys robosuite's own configs of this type carry that its controller ignores.
    pub ignored: &'static [&'static str],
    /// Parses this type's settings (a dict of its keys only) at `path`.
    pub parse: fn(Value, &str) -> Result<ArmControllerConfig>,
    /// Builds the controller of a config of this type.
    pub build: BuildFn,
}

/// An entry: `variant` of [`ArmControllerConfig`] holds a `config`, `new` builds the
/// controller from it.
macro_rules! entry {
    ($name:literal, $variant:ident($config:ty), ignored: $ignored:expr, new: $new:expr $(,)?) => {
        ArmControllerEntry {
            name: $name,
            is: |c| matches!(c, ArmControllerConfig::$variant(_)),
            keys: serde_introspect::<$config>,
            ignored: $ignored,
            parse: |fields, path| Ok(ArmControllerConfig::$variant(typed(fields, path)?)),
            build: |config, bind, timing, path| match config {
                ArmControllerConfig::$variant(c) => Ok(Box::new(($new)(c, bind, timing, path)?)),
                other => Err(Error::invalid_argument(
                    path,
                    format!(
                        "a {} config given to the {} builder",
                        other.controller_type(),
                        $name
                    ),
                )),
            },
        }
    };
}

/// The arm controllers robosuite 1.5.2 offers, in robosuite's order.
pub const ARM_CONTROLLERS: &[ArmControllerEntry] = &[
    entry!("OSC_POSE", OscPose(OscConfig), ignored: &[],
        new: |c, bind, timing, path| Osc::new(c, true, bind, timing, path)),
    entry!("OSC_POSITION", OscPosition(OscConfig), ignored: &[],
        new: |c, bind, timing, path| Osc::new(c, false, bind, timing, path)),
    entry!("IK_POSE", IkPose(IkConfig), ignored: &[], new: InverseKinematics::new),
    entry!("JOINT_POSITION", JointPosition(JointPositionConfig),
        ignored: &["kv", "velocity_limits"], new: JointPosition::new),
    entry!("JOINT_VELOCITY", JointVelocity(JointVelocityConfig), ignored: &[],
        new: JointVelocity::new),
    entry!("JOINT_TORQUE", JointTorque(JointTorqueConfig), ignored: &[], new: JointTorque::new),
];

/// The arm controllers robosuite 1.5.2 offers, by their config `type` (the names of
/// [`ARM_CONTROLLERS`]).
pub const ARM_CONTROLLER_TYPES: &[&str] = &type_names::<{ ARM_CONTROLLERS.len() }>();

const fn type_names<const N: usize>() -> [&'static str; N] {
    let mut out = [""; N];
    let mut i = 0;
    while i < N {
        out[i] = ARM_CONTROLLERS[i].name;
        i += 1;
    }
    out
}

/// The entry of controller type `name`, if there is one.
pub fn arm_controller(name: &str) -> Option<&'static ArmControllerEntry> {
    ARM_CONTROLLERS.iter().find(|e| e.name == name)
}

/// The entry of the type of `config`.
pub(crate) fn entry_of(config: &ArmControllerConfig) -> &'static ArmControllerEntry {
    ARM_CONTROLLERS
        .iter()
        .find(|e| (e.is)(config))
        .unwrap_or_else(|| unreachable!("every ArmControllerConfig variant has an entry"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_entry_parses_and_names_its_own_type() {
        for (i, entry) in ARM_CONTROLLERS.iter().enumerate() {
            assert_eq!(ARM_CONTROLLER_TYPES[i], entry.name);
            let config = (entry.parse)(Value::Object(Default::default()), "c").unwrap();
            assert_eq!(config.controller_type(), entry.name);
            for other in ARM_CONTROLLERS {
                assert_eq!((other.is)(&config), other.name == entry.name);
            }
            assert!(!(entry.keys)().is_empty());
        }
        assert_eq!(ARM_CONTROLLER_TYPES.len(), ARM_CONTROLLERS.len());
    }
}
