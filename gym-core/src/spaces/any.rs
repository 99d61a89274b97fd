//! `AnySpace` and `AnyBox`: the dynamic forms of every space, whose elements are
//! [`Value`]s and [`ArrayValue`]s.

use crate::dtype::DType;
use crate::error::SpaceError;
use crate::space::{DynSpace, Flatten, Space};
use crate::spaces::{BoxSpace, DictSpace, Discrete, MultiBinary, MultiDiscrete, TupleSpace};
use crate::value::{ArrayElement, ArrayValue, Value};
use ndarray::{ArrayD, IxDyn};

/// A Box space of any dtype; its elements are [`ArrayValue`]s.
#[derive(Debug, Clone, PartialEq)]
#[allow(missing_docs)]
pub enum AnyBox {
    I8(BoxSpace<i8>),
    I16(BoxSpace<i16>),
    I32(BoxSpace<i32>),
    I64(BoxSpace<i64>),
    U8(BoxSpace<u8>),
    F32(BoxSpace<f32>),
    F64(BoxSpace<f64>),
    Bool(BoxSpace<bool>),
}

macro_rules! each_box {
    ($value:expr, $b:ident => $body:expr) => {
        match $value {
            AnyBox::I8($b) => $body,
            AnyBox::I16($b) => $body,
            AnyBox::I32($b) => $body,
            AnyBox::I64($b) => $body,
            AnyBox::U8($b) => $body,
            AnyBox::F32($b) => $body,
            AnyBox::F64($b) => $body,
            AnyBox::Bool($b) => $body,
        }
    };
}

macro_rules! any_box_from {
    ($($t:ty => $v:ident),*) => {$(
        impl From<BoxSpace<$t>> for AnyBox {
            fn from(b: BoxSpace<$t>) -> Self { AnyBox::$v(b) }
        }
        impl From<BoxSpace<$t>> for AnySpace {
            fn from(b: BoxSpace<$t>) -> Self { AnySpace::Box(AnyBox::$v(b)) }
        }
    )*};
}
any_box_from!(i8 => I8, i16 => I16, i32 => I32, i64 => I64, u8 => U8, f32 => F32, f64 => F64, bool => Bool);

impl AnyBox {
    /// A Box of `dtype` with `f64` bounds (±inf allowed).
    ///
    /// # Errors
    /// As [`BoxSpace::new`].
    pub fn new(dtype: DType, low: ArrayD<f64>, high: ArrayD<f64>) -> Result<Self, SpaceError> {
        Ok(match dtype {
            DType::I8 => AnyBox::I8(BoxSpace::new(low, high)?),
            DType::I16 => AnyBox::I16(BoxSpace::new(low, high)?),
            DType::I32 => AnyBox::I32(BoxSpace::new(low, high)?),
            DType::I64 => AnyBox::I64(BoxSpace::new(low, high)?),
            DType::U8 => AnyBox::U8(BoxSpace::new(low, high)?),
            DType::F32 => AnyBox::F32(BoxSpace::new(low, high)?),
            DType::F64 => AnyBox::F64(BoxSpace::new(low, high)?),
            DType::Bool => AnyBox::Bool(BoxSpace::new(low, high)?),
        })
    }

    /// The dtype of the elements.
    pub fn dtype(&self) -> DType {
        each_box!(self, b => b.dtype())
    }

    /// The bounds as `f64`, with ±inf for unbounded elements.
    pub fn bounds_f64(&self) -> (ArrayD<f64>, ArrayD<f64>) {
        each_box!(self, b => b.bounds_f64())
    }

    /// Whether every element is bounded on both sides.
    pub fn is_bounded(&self) -> bool {
        each_box!(self, b => b.is_bounded())
    }

    /// The same bounds with another dtype.
    ///
    /// # Errors
    /// When a finite bound does not fit the new dtype.
    pub fn cast(&self, dtype: DType) -> Result<AnyBox, SpaceError> {
        let (low, high) = self.bounds_f64();
        AnyBox::new(dtype, low, high)
    }

    /// Clips an array of this box's dtype and shape into its bounds.
    ///
    /// # Errors
    /// When the array's dtype cannot be cast safely or its shape differs.
    pub fn clip(&self, x: &ArrayValue) -> Result<ArrayValue, SpaceError> {
        fn clip_typed<T: ArrayElement>(
            b: &BoxSpace<T>,
            x: &ArrayValue,
        ) -> Result<ArrayValue, SpaceError> {
            let typed = b.from_value(&Value::Array(x.clone()))?;
            Ok(T::wrap(b.clip(&typed)))
        }
        each_box!(self, b => clip_typed(b, x))
    }
}

impl std::fmt::Display for AnyBox {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        each_box!(self, b => b.fmt(f))
    }
}

/// Casts a value to `T`'s box if that is safe, then asks the box.
fn box_contains<T: ArrayElement>(b: &BoxSpace<T>, x: &ArrayValue) -> bool {
    match T::peek(x) {
        Some(a) => b.contains(a),
        None => x.dtype().can_cast_to(T::DTYPE) && x.to_typed::<T>().is_ok_and(|a| b.contains(&a)),
    }
}

impl Space for AnyBox {
    type Element = ArrayValue;

    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> ArrayValue {
        each_box!(self, b => ArrayValue::from(b.sample(rng)))
    }

    /// Gymnasium's rule: the dtype casts safely to the box's, the shape matches and every
    /// element lies in its bounds.
    fn contains(&self, x: &ArrayValue) -> bool {
        each_box!(self, b => box_contains(b, x))
    }

    fn shape(&self) -> Option<&[usize]> {
        each_box!(self, b => b.shape())
    }
}

impl Flatten for AnyBox {
    fn flatdim(&self) -> usize {
        each_box!(self, b => b.flatdim())
    }

    fn flat_dtype(&self) -> DType {
        self.dtype()
    }

    fn flatten(&self, x: &ArrayValue) -> Result<ArrayValue, SpaceError> {
        each_box!(self, b => b.flatten(&b.from_value(&Value::Array(x.clone()))?))
    }

    /// In place when `x` casts safely to the Box's dtype, has its shape, and `out` is a
    /// vector of the Box's dtype and size.
    fn flatten_into(&self, x: &ArrayValue, out: &mut ArrayValue) -> Result<(), SpaceError> {
        let fits = x.dtype().can_cast_to(self.dtype())
            && self.shape() == Some(x.shape())
            && out.dtype() == self.dtype()
            && out.shape() == [x.len()];
        if !(fits && out.write_at(0, x)) {
            *out = self.flatten(x)?;
        }
        Ok(())
    }

    fn unflatten(&self, flat: &ArrayValue) -> Result<ArrayValue, SpaceError> {
        each_box!(self, b => Ok(ArrayValue::from(b.unflatten(flat)?)))
    }

    fn flatten_space(&self) -> AnyBox {
        each_box!(self, b => b.flatten_space())
    }
}

impl DynSpace for AnyBox {
    fn to_any(&self) -> AnySpace {
        AnySpace::Box(self.clone())
    }

    fn to_value(&self, x: &ArrayValue) -> Value {
        Value::Array(x.clone())
    }

    fn into_value(&self, x: ArrayValue) -> Value {
        Value::Array(x)
    }

    fn from_value(&self, v: &Value) -> Result<ArrayValue, SpaceError> {
        each_box!(self, b => Ok(ArrayValue::from(b.from_value(v)?)))
    }
}

/// Any space; its elements are [`Value`]s. This is what the dynamic layer and the Python
/// export see.
#[derive(Debug, Clone, PartialEq)]
#[allow(clippy::large_enum_variant)]
pub enum AnySpace {
    /// A Box of any dtype.
    Box(AnyBox),
    /// A Discrete space.
    Discrete(Discrete),
    /// A MultiDiscrete space.
    MultiDiscrete(MultiDiscrete),
    /// A MultiBinary space.
    MultiBinary(MultiBinary),
    /// A Dict space.
    Dict(DictSpace),
    /// A Tuple space.
    Tuple(TupleSpace),
}

macro_rules! each_space {
    ($value:expr, $s:ident => $body:expr) => {
        match $value {
            AnySpace::Box($s) => $body,
            AnySpace::Discrete($s) => $body,
            AnySpace::MultiDiscrete($s) => $body,
            AnySpace::MultiBinary($s) => $body,
            AnySpace::Dict($s) => $body,
            AnySpace::Tuple($s) => $body,
        }
    };
}

impl AnySpace {
    /// Gymnasium's class name of the space (`"Box"`, `"Dict"`, ...).
    pub fn kind(&self) -> &'static str {
        match self {
            AnySpace::Box(_) => "Box",
            AnySpace::Discrete(_) => "Discrete",
            AnySpace::MultiDiscrete(_) => "MultiDiscrete",
            AnySpace::MultiBinary(_) => "MultiBinary",
            AnySpace::Dict(_) => "Dict",
            AnySpace::Tuple(_) => "Tuple",
        }
    }

    /// The Box inside, if this is a Box.
    pub fn as_box(&self) -> Option<&AnyBox> {
        match self {
            AnySpace::Box(b) => Some(b),
            _ => None,
        }
    }

    /// The Dict inside, if this is a Dict.
    pub fn as_dict(&self) -> Option<&DictSpace> {
        match self {
            AnySpace::Dict(d) => Some(d),
            _ => None,
        }
    }
}

impl From<AnyBox> for AnySpace {
    fn from(b: AnyBox) -> Self {
        AnySpace::Box(b)
    }
}
impl From<Discrete> for AnySpace {
    fn from(s: Discrete) -> Self {
        AnySpace::Discrete(s)
    }
}
impl From<MultiDiscrete> for AnySpace {
    fn from(s: MultiDiscrete) -> Self {
        AnySpace::MultiDiscrete(s)
    }
}
impl From<MultiBinary> for AnySpace {
    fn from(s: MultiBinary) -> Self {
        AnySpace::MultiBinary(s)
    }
}
impl From<DictSpace> for AnySpace {
    fn from(s: DictSpace) -> Self {
        AnySpace::Dict(s)
    }
}
impl From<TupleSpace> for AnySpace {
    fn from(s: TupleSpace) -> Self {
        AnySpace::Tuple(s)
    }
}

impl Space for AnySpace {
    type Element = Value;

    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> Value {
        each_space!(self, s => s.to_value(&s.sample(rng)))
    }

    fn contains(&self, x: &Value) -> bool {
        match (self, x) {
            (AnySpace::Box(b), Value::Array(a)) => b.contains(a),
            (AnySpace::Discrete(d), v) => d.from_value(v).is_ok_and(|i| d.contains(&i)),
            (AnySpace::MultiDiscrete(m), Value::Array(a)) => {
                !a.dtype().is_float() && a.to_typed::<i64>().is_ok_and(|a| m.contains(&a))
            }
            (AnySpace::MultiBinary(m), v) => {
                v.as_array()
                    .is_some_and(|a| a.to_f64_vec().iter().all(|&x| x == 0.0 || x == 1.0))
                    && m.from_value(v).is_ok_and(|a| m.contains(&a))
            }
            (AnySpace::Dict(d), Value::Dict(v)) => d.contains(v),
            (AnySpace::Tuple(t), Value::Tuple(v)) => t.contains(v),
            _ => false,
        }
    }

    fn shape(&self) -> Option<&[usize]> {
        each_space!(self, s => s.shape())
    }
}

impl Flatten for AnySpace {
    fn flatdim(&self) -> usize {
        each_space!(self, s => s.flatdim())
    }

    fn flat_dtype(&self) -> DType {
        each_space!(self, s => s.flat_dtype())
    }

    fn flatten(&self, x: &Value) -> Result<ArrayValue, SpaceError> {
        each_space!(self, s => s.flatten(&s.from_value(x)?))
    }

    fn flatten_into(&self, x: &Value, out: &mut ArrayValue) -> Result<(), SpaceError> {
        match (self, x) {
            (AnySpace::Box(b), Value::Array(a)) => b.flatten_into(a, out),
            (AnySpace::Dict(d), Value::Dict(v)) => d.flatten_into(v, out),
            _ => {
                *out = self.flatten(x)?;
                Ok(())
            }
        }
    }

    fn unflatten(&self, flat: &ArrayValue) -> Result<Value, SpaceError> {
        each_space!(self, s => Ok(s.to_value(&s.unflatten(flat)?)))
    }

    fn flatten_space(&self) -> AnyBox {
        each_space!(self, s => s.flatten_space())
    }
}

impl DynSpace for AnySpace {
    fn to_any(&self) -> AnySpace {
        self.clone()
    }

    fn to_value(&self, x: &Value) -> Value {
        x.clone()
    }

    fn into_value(&self, x: Value) -> Value {
        x
    }

    fn to_value_into(&self, x: &Value, out: &mut Value) {
        out.assign_from(x);
    }

    fn from_value(&self, v: &Value) -> Result<Value, SpaceError> {
        each_space!(self, s => Ok(s.to_value(&s.from_value(v)?)))
    }
}

impl std::fmt::Display for AnySpace {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            AnySpace::Box(b) => b.fmt(f),
            AnySpace::Discrete(d) if d.start() == 0 => write!(f, "Discrete({})", d.n()),
            AnySpace::Discrete(d) => write!(f, "Discrete({}, start={})", d.n(), d.start()),
            AnySpace::MultiDiscrete(m) => write!(
                f,
                "MultiDiscrete({:?})",
                m.nvec().iter().collect::<Vec<_>>()
            ),
            AnySpace::MultiBinary(m) => write!(f, "MultiBinary({:?})", m.shape().unwrap_or(&[])),
            AnySpace::Dict(d) => {
                f.write_str("Dict(")?;
                for (i, (k, s)) in d.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "'{k}': {s}")?;
                }
                f.write_str(")")
            }
            AnySpace::Tuple(t) => {
                f.write_str("Tuple(")?;
                for (i, s) in t.spaces().iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "{s}")?;
                }
                f.write_str(")")
            }
        }
    }
}

/// The flattened Box of a Dict or Tuple: concatenated bounds, promoted dtype.
pub(crate) fn concat_flat_spaces<'a>(spaces: impl Iterator<Item = &'a AnySpace>) -> AnyBox {
    let (mut low, mut high, mut dtype) = (Vec::new(), Vec::new(), None::<DType>);
    for s in spaces {
        let flat = s.flatten_space();
        let (l, h) = flat.bounds_f64();
        low.extend(l.iter());
        high.extend(h.iter());
        dtype = Some(dtype.map_or(flat.dtype(), |d| d.promote(flat.dtype())));
    }
    let n = low.len();
    let arr = |v: Vec<f64>| ArrayD::from_shape_vec(IxDyn(&[n]), v).expect("length");
    AnyBox::new(dtype.unwrap_or(DType::F64), arr(low), arr(high))
        .expect("bounds of valid spaces stay valid")
}

/// Splits a flat vector into the flat parts of `spaces`.
pub(crate) fn split_flat<'a>(
    flat: &ArrayValue,
    spaces: impl Iterator<Item = &'a AnySpace> + Clone,
) -> Result<Vec<ArrayValue>, SpaceError> {
    let total: usize = spaces.clone().map(Flatten::flatdim).sum();
    if flat.len() != total || flat.shape().len() != 1 {
        return Err(SpaceError::Unflatten(format!(
            "expected a flat vector of {total} entries, got shape {:?}",
            flat.shape()
        )));
    }
    let mut start = 0;
    Ok(spaces
        .map(|s| {
            let end = start + s.flatdim();
            let part = flat.slice_1d(start, end).cast(s.flat_dtype());
            start = end;
            part
        })
        .collect())
}
