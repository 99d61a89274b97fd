//! `Info`: the typed, ordered map that `reset` and `step` return (and that `reset` takes as
//! options and `make` takes as keyword arguments).

use crate::value::ArrayValue;
use indexmap::IndexMap;

/// One entry of an [`Info`].
#[derive(Debug, Clone, PartialEq)]
pub enum InfoValue {
    /// A flag, such as `success`.
    Bool(bool),
    /// An integer, such as an episode length.
    Int(i64),
    /// A number, such as an episode return.
    Float(f64),
    /// Text.
    Str(String),
    /// An array, such as a final observation.
    Array(ArrayValue),
    /// A nested map, such as `episode` from `RecordEpisodeStatistics`.
    Map(Info),
}

impl InfoValue {
    /// A short name of the kind of value, for messages.
    pub fn kind(&self) -> &'static str {
        match self {
            InfoValue::Bool(_) => "bool",
            InfoValue::Int(_) => "int",
            InfoValue::Float(_) => "float",
            InfoValue::Str(_) => "str",
            InfoValue::Array(_) => "array",
            InfoValue::Map(_) => "map",
        }
    }
}

macro_rules! from_for_info_value {
    ($($t:ty => $v:ident($conv:expr)),* $(,)?) => {
        $(impl From<$t> for InfoValue {
            fn from(x: $t) -> Self {
                #[allow(clippy::redundant_closure_call)]
                InfoValue::$v(($conv)(x))
            }
        })*
    };
}
from_for_info_value!(
    bool => Bool(|x| x),
    i64 => Int(|x| x),
    i32 => Int(i64::from),
    u32 => Int(i64::from),
    usize => Int(|x: usize| i64::try_from(x).unwrap_or(i64::MAX)),
    u64 => Int(|x: u64| i64::try_from(x).unwrap_or(i64::MAX)),
    f64 => Float(|x| x),
    f32 => Float(f64::from),
    String => Str(|x| x),
    &str => Str(str::to_owned),
    ArrayValue => Array(|x| x),
    Info => Map(|x| x),
);

/// An ordered map from string keys to typed values (Gymnasium's `info` dict).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Info(IndexMap<String, InfoValue>);

/// Options passed to `reset` (Gymnasium's `options` dict).
pub type ResetOptions = Info;

impl Info {
    /// An empty map.
    pub fn new() -> Self {
        Self::default()
    }

    /// Inserts or replaces a value; returns the previous one.
    pub fn insert(
        &mut self,
        key: impl Into<String>,
        value: impl Into<InfoValue>,
    ) -> Option<InfoValue> {
        self.0.insert(key.into(), value.into())
    }

    /// Sets `key` to `value`: in place when the key is present (no allocation), else
    /// inserted at the end.
    pub fn set(&mut self, key: &str, value: impl Into<InfoValue>) {
        match self.0.get_mut(key) {
            Some(slot) => *slot = value.into(),
            None => {
                self.0.insert(key.to_owned(), value.into());
            }
        }
    }

    /// Builder form of [`Info::insert`].
    #[must_use]
    pub fn with(mut self, key: impl Into<String>, value: impl Into<InfoValue>) -> Self {
        self.insert(key, value);
        self
    }

    /// The value under `key`.
    pub fn get(&self, key: &str) -> Option<&InfoValue> {
        self.0.get(key)
    }

    /// The value under `key`, mutably.
    pub fn get_mut(&mut self, key: &str) -> Option<&mut InfoValue> {
        self.0.get_mut(key)
    }

    /// The flag under `key`, if it is a bool.
    pub fn get_bool(&self, key: &str) -> Option<bool> {
        match self.get(key)? {
            InfoValue::Bool(b) => Some(*b),
            _ => None,
        }
    }

    /// The integer under `key`, if it is an integer.
    pub fn get_i64(&self, key: &str) -> Option<i64> {
        match self.get(key)? {
            InfoValue::Int(i) => Some(*i),
            _ => None,
        }
    }

    /// The number under `key`, if it is a float or an integer.
    pub fn get_f64(&self, key: &str) -> Option<f64> {
        match self.get(key)? {
            InfoValue::Float(f) => Some(*f),
            InfoValue::Int(i) => Some(*i as f64),
            _ => None,
        }
    }

    /// The nested map under `key`, if it is a map.
    pub fn get_map(&self, key: &str) -> Option<&Info> {
        match self.get(key)? {
            InfoValue::Map(m) => Some(m),
            _ => None,
        }
    }

    /// Removes and returns the value under `key`, keeping the order of the rest.
    pub fn remove(&mut self, key: &str) -> Option<InfoValue> {
        self.0.shift_remove(key)
    }

    /// Whether `key` is present.
    pub fn contains_key(&self, key: &str) -> bool {
        self.0.contains_key(key)
    }

    /// The keys, in insertion order.
    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.0.keys().map(String::as_str)
    }

    /// The entries, in insertion order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &InfoValue)> {
        self.0.iter().map(|(k, v)| (k.as_str(), v))
    }

    /// The number of entries.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether there are no entries.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Removes every entry.
    pub fn clear(&mut self) {
        self.0.clear();
    }
}

impl<K: Into<String>, V: Into<InfoValue>> FromIterator<(K, V)> for Info {
    fn from_iter<I: IntoIterator<Item = (K, V)>>(iter: I) -> Self {
        Info(
            iter.into_iter()
                .map(|(k, v)| (k.into(), v.into()))
                .collect(),
        )
    }
}

impl IntoIterator for Info {
    type Item = (String, InfoValue);
    type IntoIter = indexmap::map::IntoIter<String, InfoValue>;
    fn into_iter(self) -> Self::IntoIter {
        self.0.into_iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_replaces_in_place_and_appends_new_keys() {
        let mut info = Info::new().with("a", 1i64).with("b", true);
        info.set("a", 2.5);
        info.set("c", false);
        assert_eq!(info.keys().collect::<Vec<_>>(), ["a", "b", "c"]);
        assert_eq!(info.get_f64("a"), Some(2.5));
        assert_eq!(info.get_bool("c"), Some(false));
    }

    #[test]
    fn typed_getters() {
        let info = Info::new()
            .with("success", true)
            .with("l", 3usize)
            .with("r", 1.5);
        assert_eq!(info.get_bool("success"), Some(true));
        assert_eq!(info.get_i64("l"), Some(3));
        assert_eq!(info.get_f64("r"), Some(1.5));
        assert_eq!(info.get_f64("l"), Some(3.0));
        assert_eq!(info.get_bool("r"), None);
        assert_eq!(info.keys().collect::<Vec<_>>(), ["success", "l", "r"]);
    }
}
