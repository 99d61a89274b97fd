//! [`VectorInfo`]: the infos of `n` sub-environments batched key by key, with `_key` masks
//! (Gymnasium's `VectorEnv._add_info`).

use gym_core::{ArrayElement, ArrayValue, Info, InfoValue, Value};
use indexmap::IndexMap;
use ndarray::{ArrayD, Axis, IxDyn};

/// One batched info entry: a column of `n` values (one per sub-environment).
#[derive(Debug, Clone, PartialEq)]
pub enum VectorInfoValue {
    /// Flags (also the `_key` masks); absent entries are `false`.
    Bool(Vec<bool>),
    /// Integers; absent entries are 0.
    Int(Vec<i64>),
    /// Numbers; absent entries are 0.0.
    Float(Vec<f64>),
    /// Arrays stacked along a new first axis (`(n, *shape)`); absent rows are zeros.
    Array(ArrayValue),
    /// Anything else (text, or values whose kinds differ between sub-environments); NumPy's
    /// object arrays. Absent entries are `None`.
    Objects(Vec<Option<InfoValue>>),
    /// Observations (`final_obs` under `AutoresetMode::SameStep`); absent entries are `None`.
    Observations(Vec<Option<Value>>),
    /// A nested info (a map value), with its own `_key` masks.
    Map(VectorInfo),
}

impl VectorInfoValue {
    /// Entry `i` as an [`InfoValue`] (`None` for absent objects; observations are not
    /// representable and give `None`).
    pub fn get(&self, i: usize) -> Option<InfoValue> {
        match self {
            VectorInfoValue::Bool(v) => v.get(i).map(|&b| InfoValue::Bool(b)),
            VectorInfoValue::Int(v) => v.get(i).map(|&x| InfoValue::Int(x)),
            VectorInfoValue::Float(v) => v.get(i).map(|&x| InfoValue::Float(x)),
            VectorInfoValue::Array(a) => {
                (i < a.shape().first().copied().unwrap_or(0)).then(|| InfoValue::Array(row(a, i)))
            }
            VectorInfoValue::Objects(v) => v.get(i).cloned().flatten(),
            VectorInfoValue::Observations(_) => None,
            VectorInfoValue::Map(m) => Some(InfoValue::Map(m.env_info(i))),
        }
    }

    /// The flags, if this is a Bool column.
    pub fn as_bools(&self) -> Option<&[bool]> {
        match self {
            VectorInfoValue::Bool(v) => Some(v),
            _ => None,
        }
    }

    /// The integers, if this is an Int column.
    pub fn as_ints(&self) -> Option<&[i64]> {
        match self {
            VectorInfoValue::Int(v) => Some(v),
            _ => None,
        }
    }

    /// The numbers, if this is a Float column.
    pub fn as_floats(&self) -> Option<&[f64]> {
        match self {
            VectorInfoValue::Float(v) => Some(v),
            _ => None,
        }
    }

    /// The nested info, if this is a Map.
    pub fn as_map(&self) -> Option<&VectorInfo> {
        match self {
            VectorInfoValue::Map(m) => Some(m),
            _ => None,
        }
    }
}

fn row(a: &ArrayValue, i: usize) -> ArrayValue {
    gym_core::for_each_array!(a, arr => ArrayValue::from(arr.index_axis(Axis(0), i).to_owned()))
}

fn stacked_zeros(like: &ArrayValue, n: usize) -> ArrayValue {
    let mut shape = vec![n];
    shape.extend_from_slice(like.shape());
    fn z<T: ArrayElement>(shape: &[usize]) -> ArrayValue {
        T::wrap(ArrayD::from_elem(IxDyn(shape), T::zero()))
    }
    use gym_core::DType::*;
    match like.dtype() {
        I8 => z::<i8>(&shape),
        I16 => z::<i16>(&shape),
        I32 => z::<i32>(&shape),
        I64 => z::<i64>(&shape),
        U8 => z::<u8>(&shape),
        F32 => z::<f32>(&shape),
        F64 => z::<f64>(&shape),
        Bool => z::<bool>(&shape),
    }
}

/// Writes `x` as row `i` of `batch` if it has the batch's dtype and row shape.
fn write_row(batch: &mut ArrayValue, i: usize, x: &ArrayValue) -> bool {
    if batch.dtype() != x.dtype() || &batch.shape()[1..] != x.shape() {
        return false;
    }
    fn go<T: ArrayElement>(b: &mut ArrayD<T>, i: usize, x: &ArrayValue) {
        if let Some(x) = T::peek(x) {
            b.index_axis_mut(Axis(0), i).assign(x);
        }
    }
    match batch {
        ArrayValue::I8(b) => go(b, i, x),
        ArrayValue::I16(b) => go(b, i, x),
        ArrayValue::I32(b) => go(b, i, x),
        ArrayValue::I64(b) => go(b, i, x),
        ArrayValue::U8(b) => go(b, i, x),
        ArrayValue::F32(b) => go(b, i, x),
        ArrayValue::F64(b) => go(b, i, x),
        ArrayValue::Bool(b) => go(b, i, x),
    }
    true
}

/// The infos of a vector step or reset, batched as Gymnasium does: for every key some
/// sub-environment reported, a column of `num_envs` values under `key` and a flag column
/// under `"_" + key` saying which sub-environments reported it. Nested maps are batched
/// recursively (with their own masks). Keys keep first-seen order, each followed by its mask.
///
/// A vector environment keeps one `VectorInfo` and refills it at every call: the columns of
/// earlier calls are kept (hidden) and reused, so a step that reports the same keys as an
/// earlier one does not allocate.
///
/// Deviation: when sub-environments report different kinds for one key, Gymnasium lets
/// NumPy cast into the first kind's array (truncating floats into an int array); here a
/// Bool/Int column is promoted to Int/Float, and other mixes become an `Objects` column.
#[derive(Clone)]
pub struct VectorInfo {
    num_envs: usize,
    /// Entries `..live` are this call's, in order; the others are kept for reuse.
    entries: IndexMap<String, VectorInfoValue>,
    live: usize,
    /// Where `"_" + key` is built without allocating.
    scratch: String,
}

impl PartialEq for VectorInfo {
    fn eq(&self, other: &Self) -> bool {
        self.num_envs == other.num_envs
            && self.len() == other.len()
            && self.iter().zip(other.iter()).all(|(a, b)| a == b)
    }
}

impl std::fmt::Debug for VectorInfo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VectorInfo")
            .field("num_envs", &self.num_envs)
            .field("entries", &DebugEntries(self))
            .finish()
    }
}

struct DebugEntries<'a>(&'a VectorInfo);

impl std::fmt::Debug for DebugEntries<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_map().entries(self.0.iter()).finish()
    }
}

/// Resets `col` to an absent column of the same kind (keeping its storage) when it can
/// hold `v`; `false` when a fresh column is needed.
fn reset_for(col: &mut VectorInfoValue, v: &InfoValue) -> bool {
    match (col, v) {
        (VectorInfoValue::Bool(c), InfoValue::Bool(_)) => c.fill(false),
        (VectorInfoValue::Int(c), InfoValue::Int(_)) => c.fill(0),
        (VectorInfoValue::Float(c), InfoValue::Float(_)) => c.fill(0.0),
        (VectorInfoValue::Array(b), InfoValue::Array(a))
            if b.dtype() == a.dtype() && &b.shape()[1..] == a.shape() =>
        {
            gym_core::for_each_array!(b, x => fill_zero(x));
        }
        (VectorInfoValue::Objects(c), InfoValue::Str(_)) => c.fill(None),
        (VectorInfoValue::Map(m), InfoValue::Map(_)) => m.clear(),
        _ => return false,
    }
    true
}

/// Sets every element of `a` to zero.
fn fill_zero<T: ArrayElement>(a: &mut ArrayD<T>) {
    a.fill(T::zero());
}

/// A column for `v` where no sub-environment has reported yet.
fn fresh(v: &InfoValue, n: usize) -> VectorInfoValue {
    match v {
        InfoValue::Bool(_) => VectorInfoValue::Bool(vec![false; n]),
        InfoValue::Int(_) => VectorInfoValue::Int(vec![0; n]),
        InfoValue::Float(_) => VectorInfoValue::Float(vec![0.0; n]),
        InfoValue::Array(a) => VectorInfoValue::Array(stacked_zeros(a, n)),
        InfoValue::Str(_) => VectorInfoValue::Objects(vec![None; n]),
        InfoValue::Map(_) => VectorInfoValue::Map(VectorInfo::new(n)),
    }
}

impl VectorInfo {
    /// An empty info for `num_envs` sub-environments.
    pub fn new(num_envs: usize) -> Self {
        Self {
            num_envs,
            entries: IndexMap::new(),
            live: 0,
            scratch: String::new(),
        }
    }

    /// Empties the info for the next call, keeping its columns' storage for reuse.
    pub(crate) fn clear(&mut self) {
        self.live = 0;
    }

    /// The number of sub-environments.
    pub fn num_envs(&self) -> usize {
        self.num_envs
    }

    /// The column under `key` (masks are under `"_" + key`).
    pub fn get(&self, key: &str) -> Option<&VectorInfoValue> {
        match self.entries.get_full(key) {
            Some((j, _, v)) if j < self.live => Some(v),
            _ => None,
        }
    }

    /// The mask of `key`: which sub-environments reported it.
    pub fn mask(&self, key: &str) -> Option<&[bool]> {
        self.get(&format!("_{key}"))?.as_bools()
    }

    /// Whether `key` is present.
    pub fn contains_key(&self, key: &str) -> bool {
        self.get(key).is_some()
    }

    /// Every key, masks included, in order.
    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.iter().map(|(k, _)| k)
    }

    /// Every entry, masks included, in order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &VectorInfoValue)> {
        self.entries
            .iter()
            .take(self.live)
            .map(|(k, v)| (k.as_str(), v))
    }

    /// The number of entries, masks included.
    pub fn len(&self) -> usize {
        self.live
    }

    /// Whether no sub-environment reported anything.
    pub fn is_empty(&self) -> bool {
        self.live == 0
    }

    /// The info sub-environment `i` reported (the keys whose mask is set at `i`, without
    /// masks and without `final_obs`): Gymnasium's `DictInfoToList` for one environment.
    pub fn env_info(&self, i: usize) -> Info {
        let mut out = Info::new();
        for (k, v) in self.iter() {
            if k.starts_with('_') && v.as_bools().is_some() && self.contains_key(&k[1..]) {
                continue;
            }
            if matches!(v, VectorInfoValue::Observations(_)) {
                continue;
            }
            if self
                .mask(k)
                .is_some_and(|m| m.get(i).copied().unwrap_or(false))
                && let Some(x) = v.get(i)
            {
                out.insert(k.to_owned(), x);
            }
        }
        out
    }

    /// The final observation of sub-environment `i` under `AutoresetMode::SameStep`.
    pub fn final_observation(&self, i: usize) -> Option<&Value> {
        match self.get("final_obs")? {
            VectorInfoValue::Observations(v) => v.get(i)?.as_ref(),
            _ => None,
        }
    }

    /// The final info of sub-environment `i` under `AutoresetMode::SameStep`.
    pub fn final_info(&self, i: usize) -> Option<Info> {
        let m = self.get("final_info")?.as_map()?;
        self.mask("final_info")?
            .get(i)
            .copied()
            .unwrap_or(false)
            .then(|| m.env_info(i))
    }

    /// The index of `key`'s column for this call, making it live (appended after this
    /// call's columns) if it is not yet: a kept column is reset by `reuse` when that
    /// returns `true`, else replaced by `make()`.
    fn column(
        &mut self,
        key: &str,
        reuse: impl FnOnce(&mut VectorInfoValue) -> bool,
        make: impl FnOnce() -> VectorInfoValue,
    ) -> usize {
        match self.entries.get_index_of(key) {
            Some(j) if j < self.live => return j,
            Some(j) => {
                let col = &mut self.entries[j];
                if !reuse(col) {
                    *col = make();
                }
                self.entries.move_index(j, self.live);
            }
            None => {
                self.entries.insert(key.to_owned(), make());
                self.entries.move_index(self.entries.len() - 1, self.live);
            }
        }
        self.live += 1;
        self.live - 1
    }

    fn set_mask(&mut self, key: &str, i: usize) {
        let n = self.num_envs;
        let mut name = std::mem::take(&mut self.scratch);
        name.clear();
        name.push('_');
        name.push_str(key);
        let j = self.column(
            &name,
            |c| match c {
                VectorInfoValue::Bool(m) => {
                    m.fill(false);
                    true
                }
                _ => false,
            },
            || VectorInfoValue::Bool(vec![false; n]),
        );
        self.scratch = name;
        if let VectorInfoValue::Bool(m) = &mut self.entries[j] {
            m[i] = true;
        }
    }

    fn objects_of(&self, key: &str) -> Vec<Option<InfoValue>> {
        let mask = self
            .mask(key)
            .map(<[bool]>::to_vec)
            .unwrap_or_else(|| vec![false; self.num_envs]);
        let col = self.get(key).expect("a live column");
        (0..self.num_envs)
            .map(|j| if mask[j] { col.get(j) } else { None })
            .collect()
    }

    /// Adds sub-environment `i`'s info (Gymnasium's `_add_info`).
    pub(crate) fn add(&mut self, info: &Info, i: usize) {
        for (k, v) in info.iter() {
            self.add_value(k, v, i);
        }
    }

    fn add_value(&mut self, key: &str, v: &InfoValue, i: usize) {
        let n = self.num_envs;
        let j = self.column(key, |c| reset_for(c, v), || fresh(v, n));
        // Promote the column where the kinds differ.
        let promoted = match (&self.entries[j], v) {
            (VectorInfoValue::Bool(b), InfoValue::Int(_)) => Some(VectorInfoValue::Int(
                b.iter().map(|&x| i64::from(x)).collect(),
            )),
            (VectorInfoValue::Bool(b), InfoValue::Float(_)) => Some(VectorInfoValue::Float(
                b.iter().map(|&x| f64::from(u8::from(x))).collect(),
            )),
            (VectorInfoValue::Int(c), InfoValue::Float(_)) => Some(VectorInfoValue::Float(
                c.iter().map(|&x| x as f64).collect(),
            )),
            (VectorInfoValue::Bool(_), InfoValue::Bool(_))
            | (VectorInfoValue::Int(_), InfoValue::Int(_) | InfoValue::Bool(_))
            | (
                VectorInfoValue::Float(_),
                InfoValue::Float(_) | InfoValue::Int(_) | InfoValue::Bool(_),
            )
            | (VectorInfoValue::Objects(_), _)
            | (VectorInfoValue::Map(_), InfoValue::Map(_)) => None,
            (VectorInfoValue::Array(b), InfoValue::Array(a))
                if b.dtype() == a.dtype() && &b.shape()[1..] == a.shape() =>
            {
                None
            }
            _ => Some(VectorInfoValue::Objects(self.objects_of(key))),
        };
        if let Some(p) = promoted {
            self.entries[j] = p;
        }
        match (&mut self.entries[j], v) {
            (VectorInfoValue::Bool(c), InfoValue::Bool(x)) => c[i] = *x,
            (VectorInfoValue::Int(c), InfoValue::Int(x)) => c[i] = *x,
            (VectorInfoValue::Int(c), InfoValue::Bool(x)) => c[i] = i64::from(*x),
            (VectorInfoValue::Float(c), InfoValue::Float(x)) => c[i] = *x,
            (VectorInfoValue::Float(c), InfoValue::Int(x)) => c[i] = *x as f64,
            (VectorInfoValue::Float(c), InfoValue::Bool(x)) => c[i] = f64::from(u8::from(*x)),
            (VectorInfoValue::Array(b), InfoValue::Array(a)) => {
                write_row(b, i, a);
            }
            (VectorInfoValue::Map(m), InfoValue::Map(x)) => m.add(x, i),
            (VectorInfoValue::Objects(c), x) => c[i] = Some(x.clone()),
            _ => {}
        }
        self.set_mask(key, i);
    }

    /// Adds `final_obs` and `final_info` for sub-environment `i` (`AutoresetMode::SameStep`).
    pub(crate) fn add_final(&mut self, i: usize, observation: Value, info: &Info) {
        let n = self.num_envs;
        let j = self.column(
            "final_obs",
            |c| match c {
                VectorInfoValue::Observations(v) => {
                    v.fill(None);
                    true
                }
                _ => false,
            },
            || VectorInfoValue::Observations(vec![None; n]),
        );
        if let VectorInfoValue::Observations(v) = &mut self.entries[j] {
            v[i] = Some(observation);
        }
        self.set_mask("final_obs", i);
        let j = self.column(
            "final_info",
            |c| match c {
                VectorInfoValue::Map(m) => {
                    m.clear();
                    true
                }
                _ => false,
            },
            || VectorInfoValue::Map(VectorInfo::new(n)),
        );
        if let VectorInfoValue::Map(m) = &mut self.entries[j] {
            m.add(info, i);
        }
        self.set_mask("final_info", i);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gymnasium_example() {
        // {'step': [0, 3], '_step': [F, T], 'reset': [T, F], '_reset': [T, F]}
        let mut infos = VectorInfo::new(2);
        infos.add(&Info::new().with("reset", true), 0);
        infos.add(&Info::new().with("step", 3i64), 1);
        assert_eq!(
            infos.keys().collect::<Vec<_>>(),
            ["reset", "_reset", "step", "_step"]
        );
        assert_eq!(infos.get("step").unwrap().as_ints(), Some(&[0i64, 3][..]));
        assert_eq!(infos.mask("step"), Some(&[false, true][..]));
        assert_eq!(
            infos.get("reset").unwrap().as_bools(),
            Some(&[true, false][..])
        );
        assert_eq!(infos.env_info(1), Info::new().with("step", 3i64));
    }

    #[test]
    fn nested_maps_arrays_and_promotion() {
        let mut infos = VectorInfo::new(3);
        let a = ArrayValue::from(ndarray::arr1(&[1.0f32, 2.0]).into_dyn());
        infos.add(
            &Info::new()
                .with("episode", Info::new().with("r", 1.5).with("l", 3i64))
                .with("v", a.clone()),
            2,
        );
        infos.add(&Info::new().with("x", 1i64), 0);
        infos.add(&Info::new().with("x", 2.5), 1);
        infos.add(&Info::new().with("name", "a"), 1);
        let ep = infos.get("episode").unwrap().as_map().unwrap();
        assert_eq!(ep.get("r").unwrap().as_floats(), Some(&[0.0, 0.0, 1.5][..]));
        assert_eq!(ep.mask("l"), Some(&[false, false, true][..]));
        assert_eq!(infos.mask("episode"), Some(&[false, false, true][..]));
        assert_eq!(
            infos.get("x").unwrap().as_floats(),
            Some(&[1.0, 2.5, 0.0][..])
        );
        assert_eq!(infos.get("v").unwrap().get(2), Some(InfoValue::Array(a)));
        assert_eq!(
            infos.get("name").unwrap().get(1),
            Some(InfoValue::Str("a".into()))
        );
        assert_eq!(
            infos.env_info(2).get_map("episode").unwrap().get_f64("r"),
            Some(1.5)
        );
        // A second kind for an array key falls back to objects, keeping the first value.
        infos.add(&Info::new().with("v", 1i64), 0);
        assert_eq!(infos.get("v").unwrap().get(0), Some(InfoValue::Int(1)));
        assert!(matches!(
            infos.get("v").unwrap().get(2),
            Some(InfoValue::Array(_))
        ));
    }
}
