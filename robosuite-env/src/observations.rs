//! Observation layouts: robosuite's ordered observation dict (each sensor key, then the
//! `robotN_proprio-state` and `object-state` concatenations), filled from one flat buffer.

use gym_core::{
    AnySpace, ArrayValue, BoxSpace, DType, DictSpace, DictValue, Result, Scalar, Value,
};
use ndarray::{ArrayD, IxDyn};
use std::ops::Range;

/// One observation key: name, shape and dtype.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObsKey {
    /// The key, such as `"robot0_eef_pos"`.
    pub name: String,
    /// The shape (`[]` for a scalar).
    pub shape: Vec<usize>,
    /// The dtype robosuite returns.
    pub dtype: DType,
}

impl ObsKey {
    /// A key.
    pub fn new(name: impl Into<String>, shape: &[usize], dtype: DType) -> Self {
        Self {
            name: name.into(),
            shape: shape.to_vec(),
            dtype,
        }
    }

    /// The number of values.
    pub fn len(&self) -> usize {
        self.shape.iter().product()
    }

    /// Whether the key holds no values.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The layout of an observation dict over a flat `f64` buffer.
///
/// Keys are laid out one after the other in insertion order; a group (a robosuite
/// modality such as `robot0_proprio-state`) is a contiguous run of keys whose values are
/// also returned concatenated as one `float64` array after all keys.
#[derive(Debug, Clone, PartialEq)]
pub struct ObsLayout {
    keys: Vec<(ObsKey, Range<usize>)>,
    groups: Vec<(String, Range<usize>)>,
    len: usize,
}

impl ObsLayout {
    /// An empty layout.
    pub fn new() -> Self {
        Self {
            keys: Vec::new(),
            groups: Vec::new(),
            len: 0,
        }
    }

    /// Appends the keys of a group and the group itself (if `group` is given); returns the
    /// buffer range the group's values occupy.
    pub fn push_group(&mut self, group: Option<&str>, keys: Vec<ObsKey>) -> Range<usize> {
        let start = self.len;
        for k in keys {
            let r = self.len..self.len + k.len();
            self.len = r.end;
            self.keys.push((k, r));
        }
        let range = start..self.len;
        if let Some(g) = group {
            self.groups.push((g.to_owned(), range.clone()));
        }
        range
    }

    /// Adds a group (a concatenation returned after all keys) over an existing range.
    pub fn add_group(&mut self, name: &str, range: Range<usize>) {
        self.groups.push((name.to_owned(), range));
    }

    /// The length of the flat buffer.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the layout has no values.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Every key of the observation dict, in order (sensor keys, then groups).
    pub fn key_names(&self) -> Vec<String> {
        self.keys
            .iter()
            .map(|(k, _)| k.name.clone())
            .chain(self.groups.iter().map(|(g, _)| g.clone()))
            .collect()
    }

    /// The buffer range of a key or group.
    pub fn range_of(&self, name: &str) -> Option<Range<usize>> {
        self.keys
            .iter()
            .find(|(k, _)| k.name == name)
            .map(|(_, r)| r.clone())
            .or_else(|| {
                self.groups
                    .iter()
                    .find(|(g, _)| g == name)
                    .map(|(_, r)| r.clone())
            })
    }

    /// The observation space: a Dict of unbounded Boxes with each key's shape and dtype,
    /// then one `float64` Box per group.
    ///
    /// # Errors
    /// A [`gym_core::Error::Space`] for duplicate keys.
    pub fn space(&self) -> Result<DictSpace> {
        let boxes = self
            .keys
            .iter()
            .map(|(k, _)| (k.name.clone(), unbounded(&k.shape, k.dtype)));
        let groups = self
            .groups
            .iter()
            .map(|(g, r)| (g.clone(), unbounded(&[r.len()], DType::F64)));
        Ok(DictSpace::new(boxes.chain(groups))?)
    }

    /// The observation dict for a filled buffer.
    pub fn to_dict(&self, buf: &[f64]) -> DictValue {
        let mut out = DictValue::with_capacity(self.keys.len() + self.groups.len());
        for (k, r) in &self.keys {
            out.insert(
                k.name.clone(),
                Value::Array(array(&k.shape, k.dtype, &buf[r.clone()])),
            );
        }
        for (g, r) in &self.groups {
            out.insert(
                g.clone(),
                Value::Array(array(&[r.len()], DType::F64, &buf[r.clone()])),
            );
        }
        out
    }
}

impl ObsLayout {
    /// Writes a filled buffer into `out` in place when `out` has this layout's keys (in
    /// order), shapes and dtypes, as the previous observation does; otherwise replaces it
    /// with [`ObsLayout::to_dict`].
    pub fn write_dict(&self, buf: &[f64], out: &mut DictValue) {
        if !self.matches(out) {
            *out = self.to_dict(buf);
            return;
        }
        let ranges = self
            .keys
            .iter()
            .map(|(_, r)| r)
            .chain(self.groups.iter().map(|(_, r)| r));
        for (value, r) in out.values_mut().zip(ranges) {
            if let Value::Array(a) = value {
                let src = &buf[r.clone()];
                gym_core::for_each_array!(a, arr => arr
                    .iter_mut()
                    .zip(src)
                    .for_each(|(d, s)| *d = Scalar::from_f64(*s)));
            }
        }
    }

    /// Whether `dict` has this layout's keys in order with the same shapes and dtypes.
    fn matches(&self, dict: &DictValue) -> bool {
        if dict.len() != self.keys.len() + self.groups.len() {
            return false;
        }
        let mut entries = dict.iter();
        let keys_match = self.keys.iter().all(|(k, _)| {
            matches!(entries.next(), Some((name, Value::Array(a)))
                if *name == k.name && a.dtype() == k.dtype && a.shape() == k.shape.as_slice())
        });
        keys_match
            && self.groups.iter().all(|(g, r)| {
                matches!(entries.next(), Some((name, Value::Array(a)))
                    if name == g && a.dtype() == DType::F64 && a.shape() == [r.len()])
            })
    }
}

impl Default for ObsLayout {
    fn default() -> Self {
        Self::new()
    }
}

fn unbounded(shape: &[usize], dtype: DType) -> AnySpace {
    match dtype {
        DType::I8 => BoxSpace::<i8>::unbounded(shape).into(),
        DType::I16 => BoxSpace::<i16>::unbounded(shape).into(),
        DType::I32 => BoxSpace::<i32>::unbounded(shape).into(),
        DType::I64 => BoxSpace::<i64>::unbounded(shape).into(),
        DType::U8 => BoxSpace::<u8>::uniform(0.0, 255.0, shape)
            .map_or_else(|_| BoxSpace::<f64>::unbounded(shape).into(), Into::into),
        DType::F32 => BoxSpace::<f32>::unbounded(shape).into(),
        DType::F64 => BoxSpace::<f64>::unbounded(shape).into(),
    }
}

fn array(shape: &[usize], dtype: DType, values: &[f64]) -> ArrayValue {
    let shape = IxDyn(shape);
    let mk =
        |v: Vec<f64>| ArrayD::from_shape_vec(shape.clone(), v).expect("layout ranges match shapes");
    let f64s = mk(values.to_vec());
    match dtype {
        DType::F64 => ArrayValue::F64(f64s),
        other => ArrayValue::F64(f64s).cast(other),
    }
}
