//! [`NumericSpace`]: spaces whose elements are arrays of numbers (Box, Discrete,
//! MultiDiscrete, MultiBinary and their dynamic forms), seen uniformly as shaped, bounded
//! arrays. The numeric wrappers of the `adapters` crate (`ClipAction`, `RescaleAction`,
//! `NormalizeObservation`, `DtypeObservation`, the `GymWrapper`'s action conversion) are
//! generic over it, so they work on typed spaces and on the dynamic [`AnySpace`] alike.
//!
//! Each kind implements what it has (bounds, the conversion of its elements); the Box-only
//! operations default to [`Error::Unsupported`], and [`AnySpace`] delegates to the space it
//! holds (Dict and Tuple are not numeric).

use crate::spaces::{
    AnyBox, AnySpace, BoxSpace, DictSpace, Discrete, MultiBinary, MultiDiscrete, TupleSpace,
};
use crate::{ArrayElement, ArrayValue, DType, DynSpace, Error, Result, Space, SpaceError, Value};
use ndarray::{ArrayD, IxDyn, Zip};
use std::any::Any;

/// The numeric view of an array-like space: element shape, dtype and bounds.
#[derive(Debug, Clone, PartialEq)]
pub struct ArraySpec {
    /// Gymnasium's class name of the space (`"Box"`, `"Discrete"`, ...).
    pub kind: &'static str,
    /// The shape of one element (`[]` for Discrete).
    pub shape: Vec<usize>,
    /// The element dtype.
    pub dtype: DType,
    /// Lower bounds as `f64` (`-inf` where unbounded).
    pub low: ArrayD<f64>,
    /// Upper bounds as `f64` (`+inf` where unbounded).
    pub high: ArrayD<f64>,
}

/// A space whose elements are numeric arrays.
///
/// Box-only operations ([`NumericSpace::with_bounds`], [`NumericSpace::clip_element`],
/// [`NumericSpace::element_from_array`]) fail with [`Error::Unsupported`] on the other kinds;
/// wrappers check [`NumericSpace::is_box`] at construction and report a clearer error.
pub trait NumericSpace: DynSpace {
    /// Shape, dtype and bounds.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for spaces whose elements are not arrays (Dict, Tuple).
    fn array_spec(&self) -> Result<ArraySpec>;

    /// Whether this is a Box (the kind action wrappers require).
    fn is_box(&self) -> bool {
        false
    }

    /// The element as an array of `U` (NumPy's `astype`, an unsafe cast with Rust `as`
    /// semantics).
    ///
    /// # Errors
    /// When a dynamic element does not have the space's structure.
    fn element_to_array<U: ArrayElement>(&self, x: &Self::Element) -> Result<ArrayD<U>>;

    /// [`NumericSpace::element_to_array`] into `out`, reusing its storage when it has the
    /// element's shape.
    ///
    /// # Errors
    /// As [`NumericSpace::element_to_array`].
    fn element_to_array_into<U: ArrayElement>(
        &self,
        x: &Self::Element,
        out: &mut ArrayD<U>,
    ) -> Result<()> {
        *out = self.element_to_array(x)?;
        Ok(())
    }

    /// An element of this Box from an array of `U` (cast with Rust `as` semantics).
    ///
    /// # Errors
    /// [`Error::Unsupported`] for non-Box spaces; a shape mismatch.
    fn element_from_array<U: ArrayElement>(&self, _x: &ArrayD<U>) -> Result<Self::Element> {
        Err(not_a_box(self.to_any().kind()))
    }

    /// [`NumericSpace::element_from_array`] into `out`, reusing its storage when it has
    /// the right shape.
    ///
    /// # Errors
    /// As [`NumericSpace::element_from_array`]; `out` is then unchanged.
    fn element_from_array_into<U: ArrayElement>(
        &self,
        x: &ArrayD<U>,
        out: &mut Self::Element,
    ) -> Result<()> {
        *out = self.element_from_array(x)?;
        Ok(())
    }

    /// The same Box (shape, dtype) with other bounds.
    ///
    /// # Errors
    /// [`Error::Unsupported`] for non-Box spaces; invalid bounds.
    fn with_bounds(&self, _low: ArrayD<f64>, _high: ArrayD<f64>) -> Result<Self> {
        Err(not_a_box(self.to_any().kind()))
    }

    /// Clips an element into the Box's bounds (`np.clip(x, low, high)`).
    ///
    /// # Errors
    /// [`Error::Unsupported`] for non-Box spaces; a malformed dynamic element.
    fn clip_element(&self, _x: &Self::Element) -> Result<Self::Element> {
        Err(not_a_box(self.to_any().kind()))
    }
}

/// Converts a borrowed array to another element type (a copy; NumPy's `astype`).
pub fn cast_array_ref<S: ArrayElement, T: ArrayElement>(x: &ArrayD<S>) -> ArrayD<T> {
    if let Some(same) = (x as &dyn Any).downcast_ref::<ArrayD<T>>() {
        return same.clone();
    }
    x.mapv(|v| v.cast_to::<T>())
}

/// Converts any array value to a typed array (unsafe cast, as NumPy's `astype`).
pub fn array_value_to<U: ArrayElement>(x: &ArrayValue) -> ArrayD<U> {
    crate::for_each_array!(x, a => cast_array_ref(a))
}

/// Casts `x` into `out` in place when the shapes agree, else replaces `out`.
fn cast_into<S: ArrayElement, T: ArrayElement>(x: &ArrayD<S>, out: &mut ArrayD<T>) {
    if out.shape() == x.shape() {
        out.zip_mut_with(x, |o, v| *o = v.cast_to::<T>());
    } else {
        *out = cast_array_ref(x);
    }
}

fn not_a_box(kind: &str) -> Error {
    Error::unsupported(format!("this operation needs a Box space, got {kind}"))
}

fn check_shape(expected: &[usize], got: &[usize]) -> Result<()> {
    if expected == got {
        Ok(())
    } else {
        Err(SpaceError::ShapeMismatch {
            expected: expected.to_vec(),
            got: got.to_vec(),
        }
        .into())
    }
}

impl<T: ArrayElement> NumericSpace for BoxSpace<T> {
    fn array_spec(&self) -> Result<ArraySpec> {
        let (low, high) = self.bounds_f64();
        Ok(ArraySpec {
            kind: "Box",
            shape: self.low().shape().to_vec(),
            dtype: T::DTYPE,
            low,
            high,
        })
    }

    fn is_box(&self) -> bool {
        true
    }

    fn element_to_array<U: ArrayElement>(&self, x: &ArrayD<T>) -> Result<ArrayD<U>> {
        Ok(cast_array_ref(x))
    }

    fn element_to_array_into<U: ArrayElement>(
        &self,
        x: &ArrayD<T>,
        out: &mut ArrayD<U>,
    ) -> Result<()> {
        cast_into(x, out);
        Ok(())
    }

    fn element_from_array<U: ArrayElement>(&self, x: &ArrayD<U>) -> Result<ArrayD<T>> {
        check_shape(self.low().shape(), x.shape())?;
        Ok(cast_array_ref(x))
    }

    fn element_from_array_into<U: ArrayElement>(
        &self,
        x: &ArrayD<U>,
        out: &mut ArrayD<T>,
    ) -> Result<()> {
        check_shape(self.low().shape(), x.shape())?;
        cast_into(x, out);
        Ok(())
    }

    fn with_bounds(&self, low: ArrayD<f64>, high: ArrayD<f64>) -> Result<Self> {
        check_shape(self.low().shape(), low.shape())?;
        Ok(BoxSpace::new(low, high)?)
    }

    fn clip_element(&self, x: &ArrayD<T>) -> Result<ArrayD<T>> {
        check_shape(self.low().shape(), x.shape())?;
        Ok(self.clip(x))
    }
}

impl NumericSpace for Discrete {
    fn array_spec(&self) -> Result<ArraySpec> {
        let scalar = |v: i64| ArrayD::from_elem(IxDyn(&[]), v as f64);
        Ok(ArraySpec {
            kind: "Discrete",
            shape: Vec::new(),
            dtype: DType::I64,
            low: scalar(self.start()),
            high: scalar(self.start() + self.n() - 1),
        })
    }

    fn element_to_array<U: ArrayElement>(&self, x: &i64) -> Result<ArrayD<U>> {
        Ok(ArrayD::from_elem(IxDyn(&[]), U::from_f64(*x as f64)))
    }
}

impl NumericSpace for MultiDiscrete {
    fn array_spec(&self) -> Result<ArraySpec> {
        let low = self.start().mapv(|s| s as f64);
        let high = Zip::from(self.start())
            .and(self.nvec())
            .map_collect(|&s, &n| (s + n - 1) as f64);
        Ok(ArraySpec {
            kind: "MultiDiscrete",
            shape: self.nvec().shape().to_vec(),
            dtype: DType::I64,
            low,
            high,
        })
    }

    fn element_to_array<U: ArrayElement>(&self, x: &ArrayD<i64>) -> Result<ArrayD<U>> {
        Ok(cast_array_ref(x))
    }
}

impl NumericSpace for MultiBinary {
    fn array_spec(&self) -> Result<ArraySpec> {
        let shape = self.shape().unwrap_or(&[]).to_vec();
        Ok(ArraySpec {
            kind: "MultiBinary",
            low: ArrayD::zeros(IxDyn(&shape)),
            high: ArrayD::ones(IxDyn(&shape)),
            shape,
            dtype: DType::I8,
        })
    }

    fn element_to_array<U: ArrayElement>(&self, x: &ArrayD<i8>) -> Result<ArrayD<U>> {
        Ok(cast_array_ref(x))
    }
}

impl NumericSpace for AnyBox {
    fn array_spec(&self) -> Result<ArraySpec> {
        let (low, high) = self.bounds_f64();
        Ok(ArraySpec {
            kind: "Box",
            shape: self.shape().unwrap_or(&[]).to_vec(),
            dtype: self.dtype(),
            low,
            high,
        })
    }

    fn is_box(&self) -> bool {
        true
    }

    fn element_to_array<U: ArrayElement>(&self, x: &ArrayValue) -> Result<ArrayD<U>> {
        Ok(array_value_to(x))
    }

    fn element_to_array_into<U: ArrayElement>(
        &self,
        x: &ArrayValue,
        out: &mut ArrayD<U>,
    ) -> Result<()> {
        crate::for_each_array!(x, a => cast_into(a, out));
        Ok(())
    }

    fn element_from_array<U: ArrayElement>(&self, x: &ArrayD<U>) -> Result<ArrayValue> {
        check_shape(self.shape().unwrap_or(&[]), x.shape())?;
        Ok(match self.dtype() {
            DType::I8 => ArrayValue::I8(cast_array_ref(x)),
            DType::I16 => ArrayValue::I16(cast_array_ref(x)),
            DType::I32 => ArrayValue::I32(cast_array_ref(x)),
            DType::I64 => ArrayValue::I64(cast_array_ref(x)),
            DType::U8 => ArrayValue::U8(cast_array_ref(x)),
            DType::F32 => ArrayValue::F32(cast_array_ref(x)),
            DType::F64 => ArrayValue::F64(cast_array_ref(x)),
            DType::Bool => ArrayValue::Bool(cast_array_ref(x)),
        })
    }

    fn with_bounds(&self, low: ArrayD<f64>, high: ArrayD<f64>) -> Result<Self> {
        check_shape(self.shape().unwrap_or(&[]), low.shape())?;
        Ok(AnyBox::new(self.dtype(), low, high)?)
    }

    fn clip_element(&self, x: &ArrayValue) -> Result<ArrayValue> {
        Ok(self.clip(x)?)
    }
}

fn not_numeric(space: &AnySpace) -> Error {
    Error::invalid_argument(
        "space",
        format!("expected a Box, Discrete, MultiDiscrete or MultiBinary space, got {space}"),
    )
}

fn as_array(v: &Value) -> Result<&ArrayValue> {
    v.as_array().ok_or_else(|| {
        SpaceError::WrongKind {
            expected: "array",
            got: v.kind(),
        }
        .into()
    })
}

/// Dict and Tuple spaces are not numeric: every operation fails.
macro_rules! not_numeric_space {
    ($($t:ty),*) => {$(
        impl NumericSpace for $t {
            fn array_spec(&self) -> Result<ArraySpec> {
                Err(not_numeric(&self.to_any()))
            }

            fn element_to_array<U: ArrayElement>(&self, _x: &Self::Element) -> Result<ArrayD<U>> {
                Err(not_numeric(&self.to_any()))
            }
        }
    )*};
}
not_numeric_space!(DictSpace, TupleSpace);

/// The space-level operations delegate to the space inside; an element is converted the
/// way each kind's elements appear as [`Value`]s (arrays cast with `astype`).
impl NumericSpace for AnySpace {
    fn array_spec(&self) -> Result<ArraySpec> {
        each_space!(self, s => s.array_spec())
    }

    fn is_box(&self) -> bool {
        each_space!(self, s => s.is_box())
    }

    fn element_to_array<U: ArrayElement>(&self, x: &Value) -> Result<ArrayD<U>> {
        match (self, x) {
            (AnySpace::Discrete(d), v) => d.element_to_array(&d.from_value(v)?),
            (AnySpace::Box(_) | AnySpace::MultiDiscrete(_) | AnySpace::MultiBinary(_), v) => {
                Ok(array_value_to(as_array(v)?))
            }
            _ => Err(not_numeric(self)),
        }
    }

    fn element_from_array<U: ArrayElement>(&self, x: &ArrayD<U>) -> Result<Value> {
        match self {
            AnySpace::Box(b) => Ok(Value::Array(b.element_from_array(x)?)),
            other => Err(not_a_box(other.kind())),
        }
    }

    fn with_bounds(&self, low: ArrayD<f64>, high: ArrayD<f64>) -> Result<Self> {
        each_space!(self, s => Ok(s.with_bounds(low, high)?.into()))
    }

    fn clip_element(&self, x: &Value) -> Result<Value> {
        match self {
            AnySpace::Box(b) => Ok(Value::Array(b.clip_element(as_array(x)?)?)),
            other => Err(not_a_box(other.kind())),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::arr1;

    #[test]
    fn cast_keeps_same_type_and_converts_otherwise() {
        let a = arr1(&[1.5f64, -2.0]).into_dyn();
        let same: ArrayD<f64> = cast_array_ref(&a);
        assert_eq!(same, a);
        let f: ArrayD<f32> = cast_array_ref(&a);
        assert_eq!(f, arr1(&[1.5f32, -2.0]).into_dyn());
    }

    #[test]
    fn specs_of_each_kind() {
        let d = Discrete::with_start(3, -1).unwrap().array_spec().unwrap();
        assert_eq!((d.low[[]], d.high[[]], d.dtype), (-1.0, 1.0, DType::I64));
        let m = MultiDiscrete::new(arr1(&[2, 5]).into_dyn())
            .unwrap()
            .array_spec()
            .unwrap();
        assert_eq!(m.high, arr1(&[1.0, 4.0]).into_dyn());
        let any: AnySpace = BoxSpace::<f32>::uniform(-1.0, 1.0, &[2]).unwrap().into();
        assert!(any.is_box());
        let clipped = any
            .clip_element(&Value::from(arr1(&[3.0f32, -0.5]).into_dyn()))
            .unwrap();
        assert_eq!(clipped, Value::from(arr1(&[1.0f32, -0.5]).into_dyn()));
        assert!(
            AnySpace::from(Discrete::new(2).unwrap())
                .clip_element(&Value::Discrete(1))
                .is_err()
        );
    }
}
