//! robosuite's observables (`robosuite/utils/observables.py`): each is one value — its key,
//! shape, dtype, modality and reader — and [`ObsLayout`] lays them out as robosuite's
//! observation dict: every observable in order, then one `{modality}-state` concatenation per
//! modality in the order modalities first appear.
//!
//! Readers are closures over the observable's owner (a robot or a task) and the simulator;
//! they write the values into a slice of one `f64` buffer (exact for every numeric dtype
//! robosuite uses), cast to the key's dtype when the dict is built.

use crate::sim::Sim;
use gym_core::{
    AnySpace, ArrayValue, BoxSpace, DType, DictSpace, DictValue, Error, ObsRow, Result, Scalar,
    Value,
};
use ndarray::{ArrayD, IxDyn};
use std::sync::Arc;

/// An observable's modality: observables of one modality are also returned concatenated
/// as `{modality}-state` (images are not concatenated).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Modality {
    /// robosuite's `object`: task observables, present only with `use_object_obs`.
    Object,
    /// robosuite's `image`: camera frames (outside the flat observation buffer).
    Image,
    /// robosuite's `robot{i}_proprio`: robot `i`'s proprioception.
    Proprio(usize),
}

impl std::fmt::Display for Modality {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Object => f.write_str("object"),
            Self::Image => f.write_str("image"),
            Self::Proprio(i) => write!(f, "robot{i}_proprio"),
        }
    }
}

impl Modality {
    /// robosuite's name of the modality (`"object"`, `"image"`, `"robot0_proprio"`).
    pub fn name(self) -> String {
        self.to_string()
    }
}

/// What an observable is, without its reader.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObsSpec {
    /// The key, such as `"robot0_eef_pos"`.
    pub key: String,
    /// The shape (`[]` for a scalar).
    pub shape: Vec<usize>,
    /// The dtype robosuite returns.
    pub dtype: DType,
    /// The modality: observables of one modality are also returned concatenated as
    /// `{modality}-state`.
    pub modality: Modality,
    /// Whether the observable exists only with `use_object_obs` (every `object` observable,
    /// and task observables robosuite creates inside its `use_object_obs` branch, such as
    /// Wipe's `robot0_contact`).
    pub needs_object_obs: bool,
    /// Whether the env returns it in observations as made (robosuite's `active`; `false`
    /// for robosuite's `Observable(..., active=False)`, such as `world_pose_in_gripper`,
    /// which is computed and cached but left out of the observation dict).
    pub active: bool,
}

impl ObsSpec {
    /// The number of values.
    pub fn len(&self) -> usize {
        self.shape.iter().product()
    }

    /// Whether the observable holds no values.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Reads an observable's values from its owner `C` and the simulator.
pub type Reader<C> = Arc<dyn Fn(&C, &Sim, &mut [f64]) + Send + Sync>;

/// One robosuite observable (a "sensor" with its key): spec and reader.
pub struct Observable<C> {
    /// Key, shape, dtype and modality.
    pub spec: ObsSpec,
    read: Reader<C>,
}

impl<C> Clone for Observable<C> {
    fn clone(&self) -> Self {
        Self {
            spec: self.spec.clone(),
            read: Arc::clone(&self.read),
        }
    }
}

impl<C> std::fmt::Debug for Observable<C> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Observable")
            .field("spec", &self.spec)
            .finish()
    }
}

impl<C> Observable<C> {
    /// An observable of `shape` and `dtype` in `modality` whose values `read` writes.
    pub fn new(
        key: impl Into<String>,
        shape: &[usize],
        dtype: DType,
        modality: Modality,
        read: impl Fn(&C, &Sim, &mut [f64]) + Send + Sync + 'static,
    ) -> Self {
        Self {
            spec: ObsSpec {
                key: key.into(),
                shape: shape.to_vec(),
                dtype,
                modality,
                needs_object_obs: modality == Modality::Object,
                active: true,
            },
            read: Arc::new(read),
        }
    }

    /// The observable, existing only with `use_object_obs` whatever its modality (robosuite
    /// creates it inside the task's `use_object_obs` branch).
    #[must_use]
    pub fn only_with_object_obs(mut self) -> Self {
        self.spec.needs_object_obs = true;
        self
    }

    /// The observable, inactive as made (robosuite's `active=False`): enabled and read in
    /// every observation pass, but not in the observation dict until activated.
    #[must_use]
    pub fn inactive(mut self) -> Self {
        self.spec.active = false;
        self
    }

    /// A float64 vector observable of `len` values that `read` writes.
    pub fn f64(
        key: impl Into<String>,
        len: usize,
        modality: Modality,
        read: impl Fn(&C, &Sim, &mut [f64]) + Send + Sync + 'static,
    ) -> Self {
        Self::new(key, &[len], DType::F64, modality, read)
    }

    /// A float64 vector observable of the `N` values `value` returns:
    /// `Observable::vec("cube_pos", Modality::Object, |t: &Lift, sim| t.cube.pos(sim))`.
    pub fn vec<const N: usize>(
        key: impl Into<String>,
        modality: Modality,
        value: impl Fn(&C, &Sim) -> [f64; N] + Send + Sync + 'static,
    ) -> Self {
        Self::new(key, &[N], DType::F64, modality, move |c, sim, out| {
            out.copy_from_slice(&value(c, sim));
        })
    }

    /// [`Observable::vec`] with robosuite's `dtype` for the values (float32 quaternions read
    /// from a frame matrix, booleans, ...).
    pub fn vec_as<const N: usize>(
        key: impl Into<String>,
        dtype: DType,
        modality: Modality,
        value: impl Fn(&C, &Sim) -> [f64; N] + Send + Sync + 'static,
    ) -> Self {
        Self::new(key, &[N], dtype, modality, move |c, sim, out| {
            out.copy_from_slice(&value(c, sim));
        })
    }
}

/// Reads each observable of `set` in order into consecutive slices of `out`.
pub fn observe_all<C>(set: &[Observable<C>], owner: &C, sim: &Sim, out: &mut [f64]) {
    let mut at = 0;
    for o in set {
        let n = o.spec.len();
        (o.read)(owner, sim, &mut out[at..at + n]);
        at += n;
    }
}

/// The specs of a set of observables.
pub fn specs<C>(set: &[Observable<C>]) -> Vec<ObsSpec> {
    set.iter().map(|o| o.spec.clone()).collect()
}

/// The total number of values of a set of specs.
pub fn total_len(specs: &[ObsSpec]) -> usize {
    specs.iter().map(ObsSpec::len).sum()
}

/// A modality concatenation: its key and the observables it joins.
#[derive(Debug, Clone, PartialEq)]
struct Group {
    key: String,
    modality: Modality,
    members: Vec<usize>,
    len: usize,
}

/// The layout of robosuite's observation dict over one flat `f64` buffer: each observable's
/// values at its offset, in order; then the `{modality}-state` concatenations (float64).
/// Observables of modality `image` (camera frames) take no buffer space: their values come
/// from a list of frames (`images`), the `n`-th image observable from the `n`-th frame.
/// Inactive observables (robosuite's `active=False`, such as object observables with
/// `use_object_obs=False`) keep their place in the buffer but are not in the dict.
#[derive(Debug, Clone, PartialEq)]
pub struct ObsLayout {
    keys: Vec<(ObsSpec, usize)>,
    groups: Vec<Group>,
    len: usize,
}

impl ObsLayout {
    /// Lays out `specs` in order; those for which `active` is false take buffer space only.
    /// Each modality gets a concatenation of its active observables (in the order
    /// modalities first appear; `image` modalities are not concatenated, as in robosuite).
    pub fn new(specs: Vec<ObsSpec>, active: impl Fn(&ObsSpec) -> bool) -> Self {
        let mut keys = Vec::with_capacity(specs.len());
        let mut groups: Vec<Group> = Vec::new();
        let mut at = 0;
        let mut image = 0;
        for spec in specs {
            if spec.modality == Modality::Image {
                if active(&spec) {
                    keys.push((spec, image));
                }
                image += 1;
                continue;
            }
            let n = spec.len();
            if !active(&spec) {
                at += n;
                continue;
            }
            let i = keys.len();
            match groups.iter_mut().find(|g| g.modality == spec.modality) {
                Some(g) => {
                    g.members.push(i);
                    g.len += spec.len();
                }
                None => groups.push(Group {
                    key: format!("{}-state", spec.modality),
                    modality: spec.modality,
                    members: vec![i],
                    len: spec.len(),
                }),
            }
            keys.push((spec, at));
            at += n;
        }
        Self {
            keys,
            groups,
            len: at,
        }
    }

    /// The length of the flat buffer (inactive observables included).
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the layout has no values.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Every key of the dict, in order (observables, then concatenations).
    pub fn key_names(&self) -> Vec<String> {
        self.keys
            .iter()
            .map(|(k, _)| k.key.clone())
            .chain(self.groups.iter().map(|g| g.key.clone()))
            .collect()
    }

    /// The offset and length of an observable's values in the buffer (`None` for images).
    pub fn range_of(&self, key: &str) -> Option<std::ops::Range<usize>> {
        self.keys
            .iter()
            .find(|(k, _)| k.key == key && k.modality != Modality::Image)
            .map(|(k, at)| *at..*at + k.len())
    }

    /// The observation space: a Dict of unbounded Boxes with each key's shape and dtype,
    /// then one `float64` Box per concatenation.
    ///
    /// # Errors
    /// A [`gym_core::Error::Space`] for duplicate keys.
    pub fn space(&self) -> Result<DictSpace> {
        let boxes = self
            .keys
            .iter()
            .map(|(k, _)| (k.key.clone(), unbounded(&k.shape, k.dtype)));
        let groups = self
            .groups
            .iter()
            .map(|g| (g.key.clone(), unbounded(&[g.len], DType::F64)));
        Ok(DictSpace::new(boxes.chain(groups))?)
    }

    fn group_values<'a>(&'a self, g: &'a Group, buf: &'a [f64]) -> impl Iterator<Item = f64> + 'a {
        g.members.iter().flat_map(move |&m| {
            let (k, at) = &self.keys[m];
            buf[*at..*at + k.len()].iter().copied()
        })
    }

    /// The observation dict for a filled buffer (and no camera frames).
    pub fn to_dict(&self, buf: &[f64]) -> DictValue {
        self.to_dict_with(buf, &[])
    }

    /// The observation dict for a filled buffer and the camera frames (a missing frame
    /// reads as zeros).
    pub fn to_dict_with(&self, buf: &[f64], images: &[ArrayValue]) -> DictValue {
        let mut out = DictValue::with_capacity(self.keys.len() + self.groups.len());
        for (k, at) in &self.keys {
            if k.modality == Modality::Image {
                let frame = images
                    .get(*at)
                    .cloned()
                    .unwrap_or_else(|| array(&k.shape, k.dtype, vec![0.0; k.len()]));
                out.insert(k.key.clone(), Value::Array(frame));
                continue;
            }
            let values = buf[*at..*at + k.len()].to_vec();
            out.insert(
                k.key.clone(),
                Value::Array(array(&k.shape, k.dtype, values)),
            );
        }
        for g in &self.groups {
            let values: Vec<f64> = self.group_values(g, buf).collect();
            out.insert(
                g.key.clone(),
                Value::Array(array(&[g.len], DType::F64, values)),
            );
        }
        out
    }

    /// Writes a filled buffer into `out` in place when `out` has this layout's keys (in
    /// order), shapes and dtypes, as the previous observation does; otherwise replaces it
    /// with [`ObsLayout::to_dict`]. In place, nothing is allocated.
    pub fn write_dict(&self, buf: &[f64], out: &mut DictValue) {
        self.write_dict_with(buf, &[], out);
    }

    /// [`ObsLayout::write_dict`] with the camera frames (copied into `out`'s arrays).
    pub fn write_dict_with(&self, buf: &[f64], images: &[ArrayValue], out: &mut DictValue) {
        if !self.matches(out) {
            *out = self.to_dict_with(buf, images);
            return;
        }
        let mut values = out.values_mut();
        for (k, at) in &self.keys {
            if k.modality == Modality::Image {
                if let (Some(Value::Array(a)), Some(frame)) = (values.next(), images.get(*at)) {
                    a.assign_from(frame);
                }
                continue;
            }
            if let Some(Value::Array(a)) = values.next() {
                let src = &buf[*at..*at + k.len()];
                gym_core::for_each_array!(a, arr => arr
                    .iter_mut()
                    .zip(src)
                    .for_each(|(d, s)| *d = Scalar::from_f64(*s)));
            }
        }
        for g in &self.groups {
            if let Some(Value::Array(a)) = values.next() {
                let src = self.group_values(g, buf);
                gym_core::for_each_array!(a, arr => arr
                    .iter_mut()
                    .zip(src)
                    .for_each(|(d, s)| *d = Scalar::from_f64(s)));
            }
        }
    }

    /// [`ObsLayout::write_dict_with`] into a row of a batch (one leaf per key, in order;
    /// converted to the leaves' dtypes): the camera frames are copied once, straight into
    /// the batch. Every leaf is checked before anything is written.
    ///
    /// # Errors
    /// [`Error::Contract`] when the row does not have this layout's leaves.
    pub fn write_row(
        &self,
        buf: &[f64],
        images: &[ArrayValue],
        row: &mut ObsRow<'_>,
    ) -> Result<()> {
        let n = self.keys.len() + self.groups.len();
        if row.len() != n {
            return Err(Error::Contract {
                check: "observation row".into(),
                message: format!("the row has {} leaves, the observation {n}", row.len()).into(),
            });
        }
        for (j, (k, _)) in self.keys.iter().enumerate() {
            row.check_leaf(j, k.len())?;
        }
        for (j, g) in self.groups.iter().enumerate() {
            row.check_leaf(self.keys.len() + j, g.len)?;
        }
        for (j, (k, at)) in self.keys.iter().enumerate() {
            if k.modality == Modality::Image {
                if let Some(frame) = images.get(*at) {
                    row.write_array(j, frame)?;
                }
                continue;
            }
            let src = &buf[*at..*at + k.len()];
            let value = |i: usize| src[i];
            match k.dtype {
                DType::I8 => row.write_f64_as::<i8>(j, src.len(), value),
                DType::I16 => row.write_f64_as::<i16>(j, src.len(), value),
                DType::I32 => row.write_f64_as::<i32>(j, src.len(), value),
                DType::I64 => row.write_f64_as::<i64>(j, src.len(), value),
                DType::U8 => row.write_f64_as::<u8>(j, src.len(), value),
                DType::F32 => row.write_f64_as::<f32>(j, src.len(), value),
                DType::F64 => row.write_f64_as::<f64>(j, src.len(), value),
                DType::Bool => row.write_f64_as::<bool>(j, src.len(), value),
            }?;
        }
        for (j, g) in self.groups.iter().enumerate() {
            let mut values = self.group_values(g, buf);
            row.write_f64_as::<f64>(self.keys.len() + j, g.len, |_| values.next().unwrap_or(0.0))?;
        }
        Ok(())
    }

    /// Whether `dict` has this layout's keys in order with the same shapes and dtypes.
    fn matches(&self, dict: &DictValue) -> bool {
        if dict.len() != self.keys.len() + self.groups.len() {
            return false;
        }
        let mut entries = dict.iter();
        let keys_match = self.keys.iter().all(|(k, _)| {
            matches!(entries.next(), Some((name, Value::Array(a)))
                if *name == k.key && a.dtype() == k.dtype && a.shape() == k.shape.as_slice())
        });
        keys_match
            && self.groups.iter().all(|g| {
                matches!(entries.next(), Some((name, Value::Array(a)))
                    if *name == g.key && a.dtype() == DType::F64 && a.shape() == [g.len])
            })
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
        DType::Bool => BoxSpace::<bool>::unbounded(shape).into(),
    }
}

fn array(shape: &[usize], dtype: DType, values: Vec<f64>) -> ArrayValue {
    let f64s = ArrayD::from_shape_vec(IxDyn(shape), values).expect("layout lengths match shapes");
    match dtype {
        DType::F64 => ArrayValue::F64(f64s),
        other => ArrayValue::F64(f64s).cast(other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(key: &str, len: usize, dtype: DType, modality: Modality) -> ObsSpec {
        ObsSpec {
            key: key.into(),
            shape: vec![len],
            dtype,
            modality,
            needs_object_obs: modality == Modality::Object,
            active: true,
        }
    }

    #[test]
    fn modalities_concatenate_in_first_appearance_order() {
        let layout = ObsLayout::new(
            vec![
                spec("robot0_a", 2, DType::F64, Modality::Proprio(0)),
                spec("cube_pos", 3, DType::F64, Modality::Object),
                spec("hidden", 2, DType::F64, Modality::Object),
                spec("robot0_contact", 1, DType::Bool, Modality::Proprio(0)),
            ],
            |s| s.key != "hidden",
        );
        assert_eq!(
            layout.key_names(),
            [
                "robot0_a",
                "cube_pos",
                "robot0_contact",
                "robot0_proprio-state",
                "object-state"
            ]
        );
        let buf = [1.0, 2.0, 3.0, 4.0, 5.0, -1.0, -1.0, 1.0];
        let d = layout.to_dict(&buf);
        let proprio = d
            .get("robot0_proprio-state")
            .unwrap()
            .as_array()
            .unwrap()
            .to_f64_vec();
        assert_eq!(proprio, [1.0, 2.0, 1.0]);
        assert_eq!(
            d.get("robot0_contact").unwrap().as_array().unwrap().dtype(),
            DType::Bool
        );
        let mut out = d.clone();
        let buf2 = [9.0, 8.0, 7.0, 6.0, 5.0, -1.0, -1.0, 0.0];
        layout.write_dict(&buf2, &mut out);
        assert_eq!(out, layout.to_dict(&buf2));
        assert_eq!(layout.range_of("cube_pos"), Some(2..5));
        assert_eq!(layout.space().unwrap().len(), 5);
    }
}
