//! Dynamically typed elements: what any space's element becomes in the dynamic layer
//! (registries, boxed envs, the Python export).

use crate::dtype::{DType, Scalar};
use crate::error::SpaceError;
use indexmap::IndexMap;
use ndarray::{ArrayD, IxDyn};

/// An n-dimensional array of any supported dtype.
#[derive(Debug, Clone, PartialEq)]
#[allow(missing_docs)]
pub enum ArrayValue {
    I8(ArrayD<i8>),
    I16(ArrayD<i16>),
    I32(ArrayD<i32>),
    I64(ArrayD<i64>),
    U8(ArrayD<u8>),
    F32(ArrayD<f32>),
    F64(ArrayD<f64>),
    Bool(ArrayD<bool>),
}

/// Applies `$body` to the array inside any variant, bound as `$a`.
#[macro_export]
#[doc(hidden)]
macro_rules! for_each_array {
    ($value:expr, $a:ident => $body:expr) => {
        match $value {
            $crate::ArrayValue::I8($a) => $body,
            $crate::ArrayValue::I16($a) => $body,
            $crate::ArrayValue::I32($a) => $body,
            $crate::ArrayValue::I64($a) => $body,
            $crate::ArrayValue::U8($a) => $body,
            $crate::ArrayValue::F32($a) => $body,
            $crate::ArrayValue::F64($a) => $body,
            $crate::ArrayValue::Bool($a) => $body,
        }
    };
}

/// Conversion between a typed array and [`ArrayValue`].
pub trait ArrayElement: Scalar {
    /// Wraps a typed array.
    fn wrap(array: ArrayD<Self>) -> ArrayValue;
    /// Borrows the typed array if the value has exactly this dtype.
    fn peek(value: &ArrayValue) -> Option<&ArrayD<Self>>;
    /// Wraps a typed Box space into the dynamic [`AnyBox`](crate::spaces::AnyBox).
    fn any_box(space: crate::spaces::BoxSpace<Self>) -> crate::spaces::AnyBox;
}

macro_rules! array_element {
    ($t:ty, $v:ident) => {
        impl ArrayElement for $t {
            fn wrap(array: ArrayD<Self>) -> ArrayValue {
                ArrayValue::$v(array)
            }
            fn peek(value: &ArrayValue) -> Option<&ArrayD<Self>> {
                match value {
                    ArrayValue::$v(a) => Some(a),
                    _ => None,
                }
            }
            fn any_box(space: crate::spaces::BoxSpace<Self>) -> crate::spaces::AnyBox {
                crate::spaces::AnyBox::$v(space)
            }
        }
        impl From<ArrayD<$t>> for ArrayValue {
            fn from(a: ArrayD<$t>) -> Self {
                ArrayValue::$v(a)
            }
        }
    };
}
array_element!(i8, I8);
array_element!(i16, I16);
array_element!(i32, I32);
array_element!(i64, I64);
array_element!(u8, U8);
array_element!(f32, F32);
array_element!(f64, F64);
array_element!(bool, Bool);

impl ArrayValue {
    /// The dtype of the elements.
    pub fn dtype(&self) -> DType {
        match self {
            ArrayValue::I8(_) => DType::I8,
            ArrayValue::I16(_) => DType::I16,
            ArrayValue::I32(_) => DType::I32,
            ArrayValue::I64(_) => DType::I64,
            ArrayValue::U8(_) => DType::U8,
            ArrayValue::F32(_) => DType::F32,
            ArrayValue::F64(_) => DType::F64,
            ArrayValue::Bool(_) => DType::Bool,
        }
    }

    /// The shape of the array.
    pub fn shape(&self) -> &[usize] {
        for_each_array!(self, a => a.shape())
    }

    /// The number of elements.
    pub fn len(&self) -> usize {
        for_each_array!(self, a => a.len())
    }

    /// Whether the array has no elements.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The elements as `f64`, in logical (row-major) order.
    pub fn to_f64_vec(&self) -> Vec<f64> {
        for_each_array!(self, a => a.iter().map(|x| x.to_f64()).collect())
    }

    /// Whether every element is finite (NaN and ±inf are not).
    pub fn all_finite(&self) -> bool {
        for_each_array!(self, a => a.iter().all(|x| x.is_finite()))
    }

    /// Converts to another dtype with Rust `as` semantics, as NumPy's `astype` (unsafe cast).
    pub fn cast(&self, to: DType) -> ArrayValue {
        if self.dtype() == to {
            return self.clone();
        }
        fn conv<T: ArrayElement>(v: &ArrayValue) -> ArrayValue {
            T::wrap(for_each_array!(v, a => a.mapv(|x| x.cast_to::<T>())))
        }
        match to {
            DType::I8 => conv::<i8>(self),
            DType::I16 => conv::<i16>(self),
            DType::I32 => conv::<i32>(self),
            DType::I64 => conv::<i64>(self),
            DType::U8 => conv::<u8>(self),
            DType::F32 => conv::<f32>(self),
            DType::F64 => conv::<f64>(self),
            DType::Bool => conv::<bool>(self),
        }
    }

    /// Converts to `T` if NumPy would cast safely, else a [`SpaceError::DtypeMismatch`].
    ///
    /// # Errors
    /// When the dtype cannot be cast safely to `T`.
    pub fn to_typed<T: ArrayElement>(&self) -> Result<ArrayD<T>, SpaceError> {
        if let Some(a) = T::peek(self) {
            return Ok(a.clone());
        }
        if !self.dtype().can_cast_to(T::DTYPE) {
            return Err(SpaceError::DtypeMismatch {
                expected: T::DTYPE,
                got: self.dtype(),
            });
        }
        Ok(for_each_array!(self, a => a.mapv(|x| x.cast_to::<T>())))
    }

    /// The array reshaped to one dimension (a copy).
    pub fn flattened(&self) -> ArrayValue {
        for_each_array!(self, a => {
            let flat: Vec<_> = a.iter().copied().collect();
            ArrayValue::from(ArrayD::from_shape_vec(IxDyn(&[flat.len()]), flat).expect("length matches"))
        })
    }

    /// Concatenates one-dimensional arrays into one, promoting dtypes as NumPy does.
    /// An empty list gives an empty `float64` array.
    pub fn concatenate(parts: &[ArrayValue]) -> ArrayValue {
        let dtype = parts
            .iter()
            .map(ArrayValue::dtype)
            .reduce(DType::promote)
            .unwrap_or(DType::F64);
        fn join<T: ArrayElement>(parts: &[ArrayValue]) -> ArrayValue {
            let mut out: Vec<T> = Vec::with_capacity(parts.iter().map(ArrayValue::len).sum());
            for p in parts {
                for_each_array!(p, a => out.extend(a.iter().map(|x| x.cast_to::<T>())));
            }
            let n = out.len();
            T::wrap(ArrayD::from_shape_vec(IxDyn(&[n]), out).expect("length matches"))
        }
        match dtype {
            DType::I8 => join::<i8>(parts),
            DType::I16 => join::<i16>(parts),
            DType::I32 => join::<i32>(parts),
            DType::I64 => join::<i64>(parts),
            DType::U8 => join::<u8>(parts),
            DType::F32 => join::<f32>(parts),
            DType::F64 => join::<f64>(parts),
            DType::Bool => join::<bool>(parts),
        }
    }

    /// Copies `src` into `self`, reusing `self`'s storage when the dtypes agree (nothing is
    /// allocated when the shapes agree too), else replacing `self` by a copy.
    pub fn assign_from(&mut self, src: &ArrayValue) {
        use ArrayValue as A;
        match (self, src) {
            (A::I8(d), A::I8(s)) => d.clone_from(s),
            (A::I16(d), A::I16(s)) => d.clone_from(s),
            (A::I32(d), A::I32(s)) => d.clone_from(s),
            (A::I64(d), A::I64(s)) => d.clone_from(s),
            (A::U8(d), A::U8(s)) => d.clone_from(s),
            (A::F32(d), A::F32(s)) => d.clone_from(s),
            (A::F64(d), A::F64(s)) => d.clone_from(s),
            (A::Bool(d), A::Bool(s)) => d.clone_from(s),
            (d, s) => *d = s.clone(),
        }
    }

    /// Whether the array is contiguous in row-major order.
    pub fn is_standard_layout(&self) -> bool {
        for_each_array!(self, a => a.is_standard_layout())
    }

    /// Writes `src`'s elements (row-major, cast with `as`) into this contiguous array from
    /// element `at` on; `false`, with nothing written, when this is not contiguous or has
    /// no room for them.
    pub fn write_at(&mut self, at: usize, src: &ArrayValue) -> bool {
        fn go<T: ArrayElement>(dst: &mut ArrayD<T>, at: usize, src: &ArrayValue) -> bool {
            let Some(part) = dst
                .as_slice_mut()
                .and_then(|d| d.get_mut(at..at + src.len()))
            else {
                return false;
            };
            for_each_array!(src, a => part
                .iter_mut()
                .zip(a.iter())
                .for_each(|(d, v)| *d = v.cast_to::<T>()));
            true
        }
        for_each_array!(self, d => go(d, at, src))
    }

    /// The elements `start..end` of a one-dimensional array.
    pub fn slice_1d(&self, start: usize, end: usize) -> ArrayValue {
        for_each_array!(self, a => {
            let v: Vec<_> = a.iter().skip(start).take(end.saturating_sub(start)).copied().collect();
            let n = v.len();
            ArrayValue::from(ArrayD::from_shape_vec(IxDyn(&[n]), v).expect("length matches"))
        })
    }
}

/// An ordered dict element (the element of a [`DictSpace`](crate::spaces::DictSpace)).
pub type DictValue = IndexMap<String, Value>;

/// An element of any space.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// An element of a Box, MultiBinary or MultiDiscrete space.
    Array(ArrayValue),
    /// An element of a Discrete space.
    Discrete(i64),
    /// An element of a Dict space, in the space's key order.
    Dict(DictValue),
    /// An element of a Tuple space.
    Tuple(Vec<Value>),
}

impl Value {
    /// A short name of the kind of value, for messages.
    pub fn kind(&self) -> &'static str {
        match self {
            Value::Array(_) => "array",
            Value::Discrete(_) => "integer",
            Value::Dict(_) => "dict",
            Value::Tuple(_) => "tuple",
        }
    }

    /// The array inside, if this is an array.
    pub fn as_array(&self) -> Option<&ArrayValue> {
        match self {
            Value::Array(a) => Some(a),
            _ => None,
        }
    }

    /// The dict inside, if this is a dict.
    pub fn as_dict(&self) -> Option<&DictValue> {
        match self {
            Value::Dict(d) => Some(d),
            _ => None,
        }
    }

    /// Copies `src` into `self` in place where the two have the same structure (dict keys
    /// in the same order, tuples of the same length, arrays of the same dtype and shape:
    /// then nothing is allocated), else replacing the differing part by a copy.
    pub fn assign_from(&mut self, src: &Value) {
        match (self, src) {
            (Value::Array(d), Value::Array(s)) => d.assign_from(s),
            (Value::Discrete(d), Value::Discrete(s)) => *d = *s,
            (Value::Dict(d), Value::Dict(s)) => assign_dict(d, s),
            (Value::Tuple(d), Value::Tuple(s)) if d.len() == s.len() => {
                d.iter_mut().zip(s).for_each(|(d, s)| d.assign_from(s));
            }
            (d, s) => *d = s.clone(),
        }
    }

    /// Whether every number inside is finite.
    pub fn all_finite(&self) -> bool {
        match self {
            Value::Array(a) => a.all_finite(),
            Value::Discrete(_) => true,
            Value::Dict(d) => d.values().all(Value::all_finite),
            Value::Tuple(t) => t.iter().all(Value::all_finite),
        }
    }
}

/// [`Value::assign_from`] for dicts: in place when the keys agree in order.
pub fn assign_dict(dst: &mut DictValue, src: &DictValue) {
    if dst.len() == src.len() && dst.keys().eq(src.keys()) {
        dst.values_mut()
            .zip(src.values())
            .for_each(|(d, s)| d.assign_from(s));
    } else {
        dst.clone_from(src);
    }
}

impl From<DictValue> for Value {
    fn from(d: DictValue) -> Self {
        Value::Dict(d)
    }
}

impl From<Vec<Value>> for Value {
    fn from(t: Vec<Value>) -> Self {
        Value::Tuple(t)
    }
}

impl From<i64> for Value {
    fn from(i: i64) -> Self {
        Value::Discrete(i)
    }
}

impl TryFrom<Value> for DictValue {
    type Error = SpaceError;

    /// The dict inside a [`Value::Dict`] (moved), else [`SpaceError::WrongKind`].
    fn try_from(v: Value) -> Result<Self, SpaceError> {
        match v {
            Value::Dict(d) => Ok(d),
            other => Err(SpaceError::WrongKind {
                expected: "dict",
                got: other.kind(),
            }),
        }
    }
}

impl<T: ArrayElement> From<ArrayD<T>> for Value {
    fn from(a: ArrayD<T>) -> Self {
        Value::Array(T::wrap(a))
    }
}

impl From<ArrayValue> for Value {
    fn from(a: ArrayValue) -> Self {
        Value::Array(a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::arr1;

    #[test]
    fn concatenate_promotes() {
        let a = ArrayValue::from(arr1(&[1i64, 0]).into_dyn());
        let b = ArrayValue::from(arr1(&[0.5f32]).into_dyn());
        let c = ArrayValue::concatenate(&[a, b]);
        assert_eq!(c.dtype(), DType::F64);
        assert_eq!(c.to_f64_vec(), vec![1.0, 0.0, 0.5]);
    }

    #[test]
    fn concatenate_keeps_integers_exact() {
        // 2^53 + 1 is not an f64; routed through f64 it came back as 2^53.
        let big = (1i64 << 53) + 1;
        let a = ArrayValue::from(arr1(&[big]).into_dyn());
        let b = ArrayValue::from(arr1(&[-big, 7]).into_dyn());
        let c = ArrayValue::concatenate(&[a, b]);
        assert_eq!(c.dtype(), DType::I64);
        assert_eq!(
            c.to_typed::<i64>().unwrap().into_raw_vec_and_offset().0,
            vec![big, -big, 7]
        );
        let small = ArrayValue::from(arr1(&[-3i8]).into_dyn());
        let c = ArrayValue::concatenate(&[small, ArrayValue::from(arr1(&[big]).into_dyn())]);
        assert_eq!(
            c.to_typed::<i64>().unwrap().into_raw_vec_and_offset().0,
            vec![-3, big]
        );
        assert_eq!(
            ArrayValue::from(arr1(&[big]).into_dyn())
                .cast(DType::I32)
                .to_typed::<i32>()
                .unwrap()[[0]],
            big as i32
        );
    }

    #[test]
    fn bools_concatenate_as_numpy() {
        let flags = ArrayValue::from(arr1(&[true, false]).into_dyn());
        let both = ArrayValue::concatenate(&[flags.clone(), flags.clone()]);
        assert_eq!(both.dtype(), DType::Bool);
        let mixed = ArrayValue::concatenate(&[ArrayValue::from(arr1(&[0.5f64]).into_dyn()), flags]);
        assert_eq!(mixed.dtype(), DType::F64);
        assert_eq!(mixed.to_f64_vec(), vec![0.5, 1.0, 0.0]);
        let back = ArrayValue::from(arr1(&[2i64, 0]).into_dyn()).cast(DType::Bool);
        assert_eq!(back, ArrayValue::from(arr1(&[true, false]).into_dyn()));
        assert!(back.to_typed::<f32>().is_ok());
        assert!(mixed.to_typed::<bool>().is_err());
    }

    #[test]
    fn assign_from_reuses_matching_storage() {
        let mut dst = Value::Dict(
            [("a".to_owned(), Value::from(arr1(&[1.0f64, 2.0]).into_dyn()))]
                .into_iter()
                .collect(),
        );
        let src = Value::Dict(
            [("a".to_owned(), Value::from(arr1(&[3.0f64, 4.0]).into_dyn()))]
                .into_iter()
                .collect(),
        );
        let ptr = |v: &Value| match v {
            Value::Dict(d) => match &d["a"] {
                Value::Array(ArrayValue::F64(a)) => a.as_ptr(),
                _ => unreachable!(),
            },
            _ => unreachable!(),
        };
        let before = ptr(&dst);
        dst.assign_from(&src);
        assert_eq!(dst, src);
        assert_eq!(ptr(&dst), before);
        let other = Value::Tuple(vec![Value::Discrete(1)]);
        dst.assign_from(&other);
        assert_eq!(dst, other);
        let mut a = ArrayValue::from(arr1(&[1i8]).into_dyn());
        a.assign_from(&ArrayValue::from(arr1(&[0.5f32, 1.0]).into_dyn()));
        assert_eq!(a.dtype(), DType::F32);
    }

    #[test]
    fn to_typed_is_safe_only() {
        let f64s = ArrayValue::from(arr1(&[1.5f64]).into_dyn());
        assert!(f64s.to_typed::<f32>().is_err());
        let f32s = ArrayValue::from(arr1(&[1.5f32]).into_dyn());
        assert_eq!(f32s.to_typed::<f64>().unwrap()[[0]], 1.5);
    }
}
