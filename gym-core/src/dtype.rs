//! Element types of array spaces and values, with NumPy's casting and promotion rules.

use std::fmt;

/// The element type of an array, named as NumPy names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum DType {
    /// `int8` (the dtype of `MultiBinary`).
    I8,
    /// `int16`.
    I16,
    /// `int32`.
    I32,
    /// `int64` (the dtype of `Discrete` and `MultiDiscrete`).
    I64,
    /// `uint8` (images).
    U8,
    /// `float32`.
    F32,
    /// `float64`.
    F64,
    /// `bool` (NumPy's `bool_`: flags such as robosuite's contact observations).
    Bool,
}

impl DType {
    /// Every dtype, in declaration order.
    pub const ALL: [DType; 8] = [
        DType::I8,
        DType::I16,
        DType::I32,
        DType::I64,
        DType::U8,
        DType::F32,
        DType::F64,
        DType::Bool,
    ];

    /// NumPy's name for the dtype (`"float32"`, ...).
    pub fn name(self) -> &'static str {
        match self {
            DType::I8 => "int8",
            DType::I16 => "int16",
            DType::I32 => "int32",
            DType::I64 => "int64",
            DType::U8 => "uint8",
            DType::F32 => "float32",
            DType::F64 => "float64",
            DType::Bool => "bool",
        }
    }

    /// The size of one element in bytes (NumPy's `itemsize`).
    pub fn size(self) -> usize {
        match self {
            DType::I8 | DType::U8 | DType::Bool => 1,
            DType::I16 => 2,
            DType::I32 | DType::F32 => 4,
            DType::I64 | DType::F64 => 8,
        }
    }

    /// Parses NumPy's name of a dtype.
    pub fn from_name(name: &str) -> Option<DType> {
        DType::ALL.into_iter().find(|d| d.name() == name)
    }

    /// Whether the dtype cannot hold negative values (`uint8`, `bool`), so a Box of it
    /// cannot be unbounded.
    pub fn is_unsigned(self) -> bool {
        matches!(self, DType::U8 | DType::Bool)
    }

    /// Whether this is a floating-point dtype.
    pub fn is_float(self) -> bool {
        matches!(self, DType::F32 | DType::F64)
    }

    /// NumPy's `can_cast(self, to)` under the default "safe" rule: every value of `self`
    /// is represented exactly (integers to floats follow NumPy: int64 → float64 is safe).
    pub fn can_cast_to(self, to: DType) -> bool {
        use DType::*;
        if self == to {
            return true;
        }
        match self {
            I8 => matches!(to, I16 | I32 | I64 | F32 | F64),
            I16 => matches!(to, I32 | I64 | F32 | F64),
            I32 => matches!(to, I64 | F64),
            I64 => matches!(to, F64),
            U8 => matches!(to, I16 | I32 | I64 | F32 | F64),
            F32 => matches!(to, F64),
            F64 => false,
            Bool => true,
        }
    }

    /// NumPy's `result_type(self, other)`: the smallest dtype both cast to safely.
    pub fn promote(self, other: DType) -> DType {
        use DType::*;
        if self.can_cast_to(other) {
            return other;
        }
        if other.can_cast_to(self) {
            return self;
        }
        // Neither casts to the other: the first common dtype, smallest first.
        [I16, I32, I64, F32, F64]
            .into_iter()
            .find(|d| self.can_cast_to(*d) && other.can_cast_to(*d))
            .unwrap_or(F64)
    }
}

impl fmt::Display for DType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

mod sealed {
    pub trait Sealed {}
}

/// A Rust element type that array spaces hold: `i8`, `i16`, `i32`, `i64`, `u8`, `f32`, `f64`,
/// `bool`.
pub trait Scalar:
    Copy
    + fmt::Debug
    + fmt::Display
    + PartialOrd
    + PartialEq
    + Default
    + Send
    + Sync
    + 'static
    + sealed::Sealed
{
    /// The dtype of this element type.
    const DTYPE: DType;
    /// The smallest finite value, as `f64`.
    const MIN: f64;
    /// The largest finite value, as `f64`.
    const MAX: f64;
    /// Converts to `f64` (exact for every type but large `i64`).
    fn to_f64(self) -> f64;
    /// Converts from `f64` with Rust's `as` semantics (saturating, NaN becomes 0 for ints).
    fn from_f64(v: f64) -> Self;
    /// Zero.
    fn zero() -> Self {
        Self::default()
    }
    /// One.
    fn one() -> Self {
        Self::from_f64(1.0)
    }
    /// Whether the value is finite (always true for integers).
    fn is_finite(self) -> bool;
    /// Converts to `i64` with Rust's `as` semantics (exact for every integer type).
    fn to_i64(self) -> i64;
    /// Converts from `i64` with Rust's `as` semantics (wrapping for narrower integers).
    fn from_i64(v: i64) -> Self;
    /// Converts to another element type as NumPy's `astype` does: integers to integers
    /// exactly (wrapping when narrowing), anything involving a float through `f64`.
    #[inline]
    fn cast_to<U: Scalar>(self) -> U {
        if Self::DTYPE.is_float() || U::DTYPE.is_float() {
            U::from_f64(self.to_f64())
        } else {
            U::from_i64(self.to_i64())
        }
    }
}

macro_rules! scalar {
    ($t:ty, $d:ident, $float:expr) => {
        impl sealed::Sealed for $t {}
        impl Scalar for $t {
            const DTYPE: DType = DType::$d;
            const MIN: f64 = <$t>::MIN as f64;
            const MAX: f64 = <$t>::MAX as f64;
            #[inline]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn from_f64(v: f64) -> Self {
                v as $t
            }
            #[inline]
            #[allow(clippy::unnecessary_cast)]
            fn is_finite(self) -> bool {
                !$float || (self as f64).is_finite()
            }
            #[inline]
            #[allow(clippy::unnecessary_cast)]
            fn to_i64(self) -> i64 {
                self as i64
            }
            #[inline]
            #[allow(clippy::unnecessary_cast)]
            fn from_i64(v: i64) -> Self {
                v as $t
            }
        }
    };
}
scalar!(i8, I8, false);
scalar!(i16, I16, false);
scalar!(i32, I32, false);
scalar!(i64, I64, false);
scalar!(u8, U8, false);
scalar!(f32, F32, true);
scalar!(f64, F64, true);

/// NumPy's `bool_`: `False < True`, numerically 0 and 1; casting a number to it tests for
/// non-zero (NaN is `True`, as in NumPy).
impl sealed::Sealed for bool {}
impl Scalar for bool {
    const DTYPE: DType = DType::Bool;
    const MIN: f64 = 0.0;
    const MAX: f64 = 1.0;
    #[inline]
    fn to_f64(self) -> f64 {
        f64::from(u8::from(self))
    }
    #[inline]
    fn from_f64(v: f64) -> Self {
        v != 0.0
    }
    #[inline]
    fn is_finite(self) -> bool {
        true
    }
    #[inline]
    fn to_i64(self) -> i64 {
        i64::from(self)
    }
    #[inline]
    fn from_i64(v: i64) -> Self {
        v != 0
    }
}

#[cfg(test)]
mod tests {
    use super::DType::*;

    #[test]
    fn casting_follows_numpy() {
        assert!(F32.can_cast_to(F64));
        assert!(!F64.can_cast_to(F32));
        assert!(!I64.can_cast_to(F32));
        assert!(I64.can_cast_to(F64));
        assert!(I32.can_cast_to(I64));
        assert!(!U8.can_cast_to(I8));
        assert!(Bool.can_cast_to(I8) && Bool.can_cast_to(F32));
        assert!(!I8.can_cast_to(Bool) && !F64.can_cast_to(Bool));
    }

    #[test]
    fn bool_scalars_follow_numpy() {
        use super::Scalar;
        assert_eq!(true.cast_to::<f32>(), 1.0);
        assert_eq!(false.cast_to::<i64>(), 0);
        assert!(f64::NAN.cast_to::<bool>() && (-2i8).cast_to::<bool>());
        assert!(!0.0f32.cast_to::<bool>());
        assert_eq!(Bool.promote(F32), F32);
        assert_eq!(Bool.promote(Bool), Bool);
    }

    #[test]
    fn promotion_follows_numpy() {
        assert_eq!(I64.promote(F32), F64);
        assert_eq!(I8.promote(F32), F32);
        assert_eq!(I8.promote(U8), I16);
        assert_eq!(F32.promote(F32), F32);
        assert_eq!(U8.promote(I64), I64);
        assert_eq!(I32.promote(F32), F64);
    }
}
