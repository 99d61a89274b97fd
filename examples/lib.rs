//! Helpers shared by the example programs in this folder.

use gym_core::Info;

/// Formats an [`Info`] on one line, `key=value` pairs in order.
pub fn format_info(info: &Info) -> String {
    info.iter()
        .map(|(k, v)| match v {
            gym_core::InfoValue::Bool(b) => format!("{k}={b}"),
            gym_core::InfoValue::Int(i) => format!("{k}={i}"),
            gym_core::InfoValue::Float(f) => format!("{k}={f:.4}"),
            gym_core::InfoValue::Str(s) => format!("{k}={s}"),
            gym_core::InfoValue::Array(a) => format!("{k}=array{:?}", a.shape()),
            gym_core::InfoValue::Map(m) => format!("{k}={{{}}}", format_info(m)),
        })
        .collect::<Vec<_>>()
        .join(" ")
}
