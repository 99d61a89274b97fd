//! `BoxSpace`: Gymnasium's `Box`, a (possibly unbounded) n-dimensional box of numbers.

use crate::dtype::{DType, Scalar};
use crate::error::SpaceError;
use crate::space::{DynSpace, Flatten, Space};
use crate::spaces::{AnyBox, AnySpace};
use crate::value::{ArrayElement, ArrayValue, Value};
use ndarray::{ArrayD, IxDyn, Zip};
use rand::RngExt;
use rand_distr::{Exp1, StandardNormal};

/// Gymnasium's `Box(low, high, shape, dtype)`: arrays of `T` with per-element bounds.
///
/// Bounds may be ±inf. For integer dtypes an infinite bound is stored as the dtype's
/// minimum or maximum but still counts as unbounded, as in Gymnasium.
#[derive(Debug, Clone, PartialEq)]
pub struct BoxSpace<T: ArrayElement> {
    low: ArrayD<T>,
    high: ArrayD<T>,
    bounded_below: ArrayD<bool>,
    bounded_above: ArrayD<bool>,
}

impl<T: ArrayElement> BoxSpace<T> {
    /// A box with per-element bounds given as `f64` (so ±inf can be said for any dtype).
    ///
    /// # Errors
    /// [`SpaceError::ShapeMismatch`] when the shapes differ; [`SpaceError::InvalidBounds`]
    /// for NaN, `low > high`, infinite bounds on an unsigned dtype, or finite bounds outside
    /// the dtype's range.
    pub fn new(low: ArrayD<f64>, high: ArrayD<f64>) -> Result<Self, SpaceError> {
        if low.shape() != high.shape() {
            return Err(SpaceError::ShapeMismatch {
                expected: low.shape().to_vec(),
                got: high.shape().to_vec(),
            });
        }
        let mut problems = Vec::new();
        Zip::from(&low).and(&high).for_each(|&l, &h| {
            if l.is_nan() || h.is_nan() {
                problems.push("NaN bound".to_owned());
            } else if l > h {
                problems.push(format!("low {l} > high {h}"));
            } else if !T::DTYPE.is_float() {
                for b in [l, h] {
                    if b.is_infinite() && T::DTYPE.is_unsigned() {
                        problems.push(format!("infinite bound for {}", T::DTYPE));
                    } else if b.is_finite() && (b < T::MIN || b > T::MAX) {
                        problems.push(format!("bound {b} outside the range of {}", T::DTYPE));
                    }
                }
            }
        });
        if let Some(p) = problems.first() {
            return Err(SpaceError::InvalidBounds(p.clone()));
        }
        let bounded_below = low.mapv(|l| l > f64::NEG_INFINITY);
        let bounded_above = high.mapv(|h| h < f64::INFINITY);
        let cast = |v: f64| {
            if T::DTYPE.is_float() {
                T::from_f64(v)
            } else {
                T::from_f64(v.clamp(T::MIN, T::MAX))
            }
        };
        Ok(Self {
            low: low.mapv(cast),
            high: high.mapv(cast),
            bounded_below,
            bounded_above,
        })
    }

    /// A box whose elements all share the bounds `low` and `high`.
    ///
    /// # Errors
    /// As [`BoxSpace::new`].
    pub fn uniform(low: f64, high: f64, shape: &[usize]) -> Result<Self, SpaceError> {
        Self::new(
            ArrayD::from_elem(IxDyn(shape), low),
            ArrayD::from_elem(IxDyn(shape), high),
        )
    }

    /// The unbounded box `(-inf, inf)` of this shape (floating dtypes; signed integer
    /// dtypes get their full range, marked unbounded). An unsigned dtype cannot be unbounded
    /// (Gymnasium refuses infinite bounds for it): it gets its full range `[0, MAX]`
    /// (`[false, true]` for `bool`).
    pub fn unbounded(shape: &[usize]) -> Self {
        let full = |v: T| ArrayD::from_elem(IxDyn(shape), v);
        let flag = |b: bool| ArrayD::from_elem(IxDyn(shape), b);
        if T::DTYPE.is_unsigned() {
            Self {
                low: full(T::zero()),
                high: full(T::from_f64(T::MAX)),
                bounded_below: flag(true),
                bounded_above: flag(true),
            }
        } else {
            let (low, high) = if T::DTYPE.is_float() {
                (f64::NEG_INFINITY, f64::INFINITY)
            } else {
                (T::MIN, T::MAX)
            };
            Self {
                low: full(T::from_f64(low)),
                high: full(T::from_f64(high)),
                bounded_below: flag(false),
                bounded_above: flag(false),
            }
        }
    }

    /// A box from typed bounds.
    ///
    /// # Errors
    /// As [`BoxSpace::new`].
    pub fn from_bounds(low: ArrayD<T>, high: ArrayD<T>) -> Result<Self, SpaceError> {
        Self::new(low.mapv(Scalar::to_f64), high.mapv(Scalar::to_f64))
    }

    /// The lower bounds.
    pub fn low(&self) -> &ArrayD<T> {
        &self.low
    }

    /// The upper bounds.
    pub fn high(&self) -> &ArrayD<T> {
        &self.high
    }

    /// Which elements have a finite lower bound.
    pub fn bounded_below(&self) -> &ArrayD<bool> {
        &self.bounded_below
    }

    /// Which elements have a finite upper bound.
    pub fn bounded_above(&self) -> &ArrayD<bool> {
        &self.bounded_above
    }

    /// Whether every element is bounded on both sides (`is_bounded("both")`).
    pub fn is_bounded(&self) -> bool {
        self.bounded_below.iter().all(|&b| b) && self.bounded_above.iter().all(|&b| b)
    }

    /// The dtype of the elements.
    pub fn dtype(&self) -> DType {
        T::DTYPE
    }

    /// Clips every element of `x` into the bounds (`np.clip(x, low, high)`).
    pub fn clip(&self, x: &ArrayD<T>) -> ArrayD<T> {
        let mut out = x.clone();
        Zip::from(&mut out)
            .and(&self.low)
            .and(&self.high)
            .for_each(|v, &l, &h| {
                if *v < l {
                    *v = l;
                } else if *v > h {
                    *v = h;
                }
            });
        out
    }

    /// Converts the bounds to another element type, keeping boundedness.
    ///
    /// # Errors
    /// When a finite bound does not fit the new dtype.
    pub fn cast<U: ArrayElement>(&self) -> Result<BoxSpace<U>, SpaceError> {
        let low = Zip::from(&self.low)
            .and(&self.bounded_below)
            .map_collect(|l, &b| if b { l.to_f64() } else { f64::NEG_INFINITY });
        let high = Zip::from(&self.high)
            .and(&self.bounded_above)
            .map_collect(|h, &b| if b { h.to_f64() } else { f64::INFINITY });
        BoxSpace::<U>::new(low, high)
    }

    /// The bounds as `f64`, with ±inf for unbounded elements.
    pub fn bounds_f64(&self) -> (ArrayD<f64>, ArrayD<f64>) {
        let low = Zip::from(&self.low)
            .and(&self.bounded_below)
            .map_collect(|l, &b| if b { l.to_f64() } else { f64::NEG_INFINITY });
        let high = Zip::from(&self.high)
            .and(&self.bounded_above)
            .map_collect(|h, &b| if b { h.to_f64() } else { f64::INFINITY });
        (low, high)
    }

    fn sample_one<R: rand::Rng + ?Sized>(
        &self,
        rng: &mut R,
        low: f64,
        high: f64,
        below: bool,
        above: bool,
    ) -> T {
        let int = !T::DTYPE.is_float();
        let high = if int && above { high + 1.0 } else { high };
        let v = match (below, above) {
            (false, false) => rng.sample::<f64, _>(StandardNormal),
            (true, false) => low + rng.sample::<f64, _>(Exp1),
            (false, true) => high - rng.sample::<f64, _>(Exp1),
            (true, true) => {
                let u: f64 = rng.random();
                let v = low + (high - low) * u;
                if v.is_finite() {
                    v
                } else {
                    low * (1.0 - u) + high * u
                }
            }
        };
        if int {
            T::from_f64(v.floor().clamp(T::MIN, T::MAX))
        } else {
            T::from_f64(v)
        }
    }
}

impl<T: ArrayElement> Space for BoxSpace<T> {
    type Element = ArrayD<T>;

    /// Per element, as Gymnasium: uniform on `[low, high)` when bounded on both sides
    /// (`[low, high]` for integers), `low + Exp(1)` or `high - Exp(1)` when bounded on one
    /// side, `N(0, 1)` when unbounded; the result is clipped into the bounds.
    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> ArrayD<T> {
        let mut out = ArrayD::from_elem(self.low.raw_dim(), T::zero());
        Zip::from(&mut out)
            .and(&self.low)
            .and(&self.high)
            .and(&self.bounded_below)
            .and(&self.bounded_above)
            .for_each(|o, &l, &h, &b, &a| {
                let v = self.sample_one(rng, l.to_f64(), h.to_f64(), b, a);
                *o = if v < l {
                    l
                } else if v > h {
                    h
                } else {
                    v
                };
            });
        out
    }

    fn contains(&self, x: &ArrayD<T>) -> bool {
        x.shape() == self.low.shape()
            && Zip::from(x)
                .and(&self.low)
                .and(&self.high)
                .all(|v, l, h| *v >= *l && *v <= *h)
    }

    fn shape(&self) -> Option<&[usize]> {
        Some(self.low.shape())
    }
}

impl<T: ArrayElement> Flatten for BoxSpace<T> {
    fn flatdim(&self) -> usize {
        self.low.len()
    }

    fn flat_dtype(&self) -> DType {
        T::DTYPE
    }

    fn flatten(&self, x: &ArrayD<T>) -> Result<ArrayValue, SpaceError> {
        if x.len() != self.low.len() {
            return Err(SpaceError::ShapeMismatch {
                expected: self.low.shape().to_vec(),
                got: x.shape().to_vec(),
            });
        }
        Ok(T::wrap(
            x.to_shape(IxDyn(&[x.len()]))
                .expect("contiguous reshape")
                .to_owned(),
        ))
    }

    fn unflatten(&self, flat: &ArrayValue) -> Result<ArrayD<T>, SpaceError> {
        if flat.len() != self.low.len() {
            return Err(SpaceError::Unflatten(format!(
                "expected {} elements, got {}",
                self.low.len(),
                flat.len()
            )));
        }
        let typed: ArrayD<T> = match T::peek(flat) {
            Some(a) => a.clone(),
            None => T::peek(&flat.cast(T::DTYPE))
                .expect("cast gives this dtype")
                .clone(),
        };
        let data: Vec<T> = typed.iter().copied().collect();
        Ok(ArrayD::from_shape_vec(self.low.raw_dim(), data).expect("length checked"))
    }

    fn flatten_space(&self) -> AnyBox {
        let n = self.low.len();
        let flat = |a: &ArrayD<bool>| a.to_shape(IxDyn(&[n])).expect("reshape").to_owned();
        T::any_box(BoxSpace {
            low: self.low.to_shape(IxDyn(&[n])).expect("reshape").to_owned(),
            high: self.high.to_shape(IxDyn(&[n])).expect("reshape").to_owned(),
            bounded_below: flat(&self.bounded_below),
            bounded_above: flat(&self.bounded_above),
        })
    }
}

impl<T: ArrayElement> DynSpace for BoxSpace<T> {
    fn to_any(&self) -> AnySpace {
        AnySpace::Box(T::any_box(self.clone()))
    }

    fn to_value(&self, x: &ArrayD<T>) -> Value {
        Value::Array(T::wrap(x.clone()))
    }

    fn from_value(&self, v: &Value) -> Result<ArrayD<T>, SpaceError> {
        match v {
            Value::Array(a) => {
                let typed = a.to_typed::<T>()?;
                if typed.shape() != self.low.shape() {
                    return Err(SpaceError::ShapeMismatch {
                        expected: self.low.shape().to_vec(),
                        got: typed.shape().to_vec(),
                    });
                }
                Ok(typed)
            }
            other => Err(SpaceError::WrongKind {
                expected: "array",
                got: other.kind(),
            }),
        }
    }
}

impl<T: ArrayElement> std::fmt::Display for BoxSpace<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (low, high) = self.bounds_f64();
        let show = |a: &ArrayD<f64>| match a.iter().next() {
            Some(first) if a.iter().all(|v| v == first) => format!("{first}"),
            _ => format!("{:?}", a.iter().collect::<Vec<_>>()),
        };
        write!(
            f,
            "Box({}, {}, {:?}, {})",
            show(&low),
            show(&high),
            self.low.shape(),
            T::DTYPE
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng_from_seed;
    use ndarray::arr1;

    #[test]
    fn rejects_bad_bounds() {
        assert!(BoxSpace::<f32>::uniform(1.0, 0.0, &[2]).is_err());
        assert!(BoxSpace::<f32>::uniform(f64::NAN, 0.0, &[2]).is_err());
        assert!(BoxSpace::<u8>::uniform(0.0, f64::INFINITY, &[2]).is_err());
        assert!(BoxSpace::<i8>::uniform(0.0, 300.0, &[2]).is_err());
        assert!(
            BoxSpace::<f32>::new(arr1(&[0.0]).into_dyn(), arr1(&[1.0, 2.0]).into_dyn()).is_err()
        );
    }

    #[test]
    fn unbounded_never_panics() {
        let u = BoxSpace::<u8>::unbounded(&[2]);
        assert_eq!((u.low()[[0]], u.high()[[1]]), (0, 255));
        assert!(u.is_bounded());
        let i = BoxSpace::<i16>::unbounded(&[1]);
        assert!(!i.is_bounded());
        assert_eq!((i.low()[[0]], i.high()[[0]]), (i16::MIN, i16::MAX));
        let f = BoxSpace::<f32>::unbounded(&[3]);
        assert!(f.low().iter().all(|v| *v == f32::NEG_INFINITY) && !f.is_bounded());
        assert_eq!(
            f,
            BoxSpace::<f32>::uniform(f64::NEG_INFINITY, f64::INFINITY, &[3]).unwrap()
        );
        assert_eq!(
            i,
            BoxSpace::<i16>::uniform(f64::NEG_INFINITY, f64::INFINITY, &[1]).unwrap()
        );
    }

    #[test]
    fn contains_checks_shape_bounds_and_nan() {
        let b = BoxSpace::<f32>::uniform(-1.0, 1.0, &[2]).unwrap();
        assert!(b.contains(&arr1(&[0.0f32, 1.0]).into_dyn()));
        assert!(!b.contains(&arr1(&[0.0f32, 1.5]).into_dyn()));
        assert!(!b.contains(&arr1(&[f32::NAN, 0.0]).into_dyn()));
        assert!(!b.contains(&arr1(&[0.0f32]).into_dyn()));
        let u = BoxSpace::<f64>::unbounded(&[1]);
        assert!(u.contains(&arr1(&[f64::INFINITY]).into_dyn()));
        assert!(!u.is_bounded());
    }

    #[test]
    fn int_samples_include_high() {
        let b = BoxSpace::<i64>::uniform(0.0, 2.0, &[200]).unwrap();
        let s = b.sample(&mut rng_from_seed(1));
        assert!(s.iter().any(|&v| v == 2) && s.iter().any(|&v| v == 0));
        assert!(b.contains(&s));
    }

    #[test]
    fn half_bounded_samples_respect_side() {
        let low = arr1(&[0.0, f64::NEG_INFINITY]).into_dyn();
        let high = arr1(&[f64::INFINITY, 5.0]).into_dyn();
        let b = BoxSpace::<f64>::new(low, high).unwrap();
        let mut rng = rng_from_seed(3);
        for _ in 0..100 {
            let s = b.sample(&mut rng);
            assert!(s[[0]] >= 0.0 && s[[1]] <= 5.0);
        }
    }

    #[test]
    fn bool_boxes_sample_contain_and_flatten() {
        assert!(BoxSpace::<bool>::uniform(0.0, f64::INFINITY, &[1]).is_err());
        assert!(BoxSpace::<bool>::uniform(0.0, 2.0, &[1]).is_err());
        let b = BoxSpace::<bool>::unbounded(&[64]);
        assert!(b.is_bounded() && b.high().iter().all(|&h| h));
        assert_eq!(b.to_string(), "Box(0, 1, [64], bool)");
        let s = b.sample(&mut rng_from_seed(4));
        assert!(b.contains(&s) && s.iter().any(|&v| v) && s.iter().any(|&v| !v));
        let only_false = BoxSpace::<bool>::uniform(0.0, 0.0, &[2]).unwrap();
        assert!(!only_false.contains(&arr1(&[false, true]).into_dyn()));
        assert_eq!(
            only_false.sample(&mut rng_from_seed(0)),
            arr1(&[false, false]).into_dyn()
        );
        let flat = b.flatten(&s).unwrap();
        assert_eq!(flat.dtype(), DType::Bool);
        assert_eq!(b.unflatten(&flat).unwrap(), s);
        assert_eq!(b.flatten_space().dtype(), DType::Bool);
        let v = b.to_value(&s);
        assert_eq!(b.from_value(&v).unwrap(), s);
        assert_eq!(
            v.as_array().unwrap().cast(DType::F32).to_f64_vec(),
            flat.to_f64_vec()
        );
    }

    #[test]
    fn cast_keeps_unboundedness() {
        let b = BoxSpace::<f64>::unbounded(&[3]).cast::<f32>().unwrap();
        assert!(b.bounded_below().iter().all(|&x| !x));
        assert_eq!(b.to_string(), "Box(-inf, inf, [3], float32)");
    }
}
