//! Actions outside the action space, built from a valid one: NaN, ±inf, a wrong length, an
//! out-of-range discrete value, a missing dict key. Used by
//! [`Check::InvalidAction`](crate::Check::InvalidAction) and the property suite.

use gym_core::{AnySpace, ArrayValue, DictValue, DynSpace, Scalar, Value};
use ndarray::{ArrayD, IxDyn};
use std::any::Any;

/// An action outside the action space, with what was done to make it so.
#[derive(Debug, Clone, PartialEq)]
pub struct InvalidAction<A> {
    /// What makes it invalid, such as `"NaN at [0]"` or `"wrong length 8 (expected 7)"`.
    pub label: String,
    /// The action.
    pub action: A,
}

/// The invalid actions derived from `base` (an element of `space`) that the environment's
/// action type can express, each verified to lie outside `space`.
///
/// For every leaf of the space (recursing into Dict and Tuple):
/// * floating Box: NaN at the first element; `+inf` at the first element with a finite
///   upper bound and `-inf` at the first with a finite lower bound; an array one longer
///   (and one shorter) along the first axis;
/// * integer Box: the wrong lengths;
/// * Discrete: `start + n` and `start - 1`; MultiDiscrete: `start + nvec` in the first
///   entry, and the wrong lengths; MultiBinary: a 2, and the wrong lengths;
/// * Dict: a missing key; Tuple: one item fewer.
///
/// With `out_of_bounds`, a finite value beyond a finite Box bound is added too.
///
/// A typed action (for example `ArrayD<f32>`) can express NaN and wrong lengths but not a
/// missing dict key; such candidates are left out. At most `limit` actions are returned.
pub fn invalid_actions<S: DynSpace>(
    space: &S,
    base: &S::Element,
    out_of_bounds: bool,
    limit: usize,
) -> Vec<InvalidAction<S::Element>> {
    let any = space.to_any();
    let base = space.to_value(base);
    let mut candidates = Vec::new();
    corrupt(&any, &base, "", out_of_bounds, &mut candidates);
    let mut out: Vec<InvalidAction<S::Element>> = Vec::new();
    for (label, value) in candidates {
        if out.len() >= limit {
            break;
        }
        if let Some(action) = element_from_value(space, &value)
            && !space.contains(&action)
            && !out.iter().any(|o| o.action == action)
        {
            out.push(InvalidAction { label, action });
        }
    }
    out
}

fn downcast<T: 'static, U: 'static>(x: T) -> Option<U> {
    let b: Box<dyn Any> = Box::new(x);
    b.downcast::<U>().ok().map(|b| *b)
}

/// Converts a dynamic value to the space's element type *without* the structure checks of
/// [`DynSpace::from_value`] when the element type is one of gym-core's own (`Value`,
/// `ArrayValue`, `ArrayD<T>`, `i64`, `Vec<Value>`, `DictValue`), so a wrong length or a
/// missing key survives; otherwise falls back to `from_value`.
pub fn element_from_value<S: DynSpace>(space: &S, v: &Value) -> Option<S::Element> {
    if let Some(e) = downcast::<Value, S::Element>(v.clone()) {
        return Some(e);
    }
    let direct = match v {
        Value::Array(a) => downcast::<ArrayValue, S::Element>(a.clone())
            .or_else(|| gym_core::for_each_array!(a, arr => downcast(arr.clone()))),
        Value::Discrete(i) => downcast(*i),
        Value::Tuple(t) => downcast(t.clone()),
        Value::Dict(d) => downcast(d.clone()),
    };
    direct.or_else(|| space.from_value(v).ok())
}

fn set_flat(a: &ArrayValue, index: usize, value: f64) -> ArrayValue {
    let mut out = a.clone();
    gym_core::for_each_array!(&mut out, arr => {
        if let Some(x) = arr.iter_mut().nth(index) {
            *x = Scalar::from_f64(value);
        }
    });
    out
}

fn resized(a: &ArrayValue, delta: isize) -> Option<ArrayValue> {
    let mut shape = a.shape().to_vec();
    let first = shape.first_mut()?;
    *first = first.checked_add_signed(delta)?;
    Some(gym_core::for_each_array!(a, arr => {
        let fill = arr.iter().next().copied().unwrap_or_default();
        ArrayValue::from(ArrayD::from_elem(IxDyn(&shape), fill))
    }))
}

fn wrong_lengths(a: &ArrayValue, path: &str, out: &mut Vec<(String, Value)>) {
    let expected = a.shape().first().copied().unwrap_or(0);
    for delta in [1isize, -1] {
        if let Some(r) = resized(a, delta) {
            let got = r.shape().first().copied().unwrap_or(0);
            out.push((
                format!("wrong length {got} (expected {expected}){}", at(path)),
                Value::Array(r),
            ));
        }
    }
}

fn at(path: &str) -> String {
    if path.is_empty() {
        String::new()
    } else {
        format!(" at {path}")
    }
}

fn corrupt(
    space: &AnySpace,
    value: &Value,
    path: &str,
    out_of_bounds: bool,
    out: &mut Vec<(String, Value)>,
) {
    match (space, value) {
        (AnySpace::Box(b), Value::Array(a)) => {
            let (low, high) = b.bounds_f64();
            if b.dtype().is_float() && !a.is_empty() {
                out.push((
                    format!("NaN at {path}[0]"),
                    Value::Array(set_flat(a, 0, f64::NAN)),
                ));
                if let Some(i) = high.iter().position(|h| h.is_finite()) {
                    out.push((
                        format!("+inf at {path}{:?}", crate::data::unravel(i, a.shape())),
                        Value::Array(set_flat(a, i, f64::INFINITY)),
                    ));
                }
                if let Some(i) = low.iter().position(|l| l.is_finite()) {
                    out.push((
                        format!("-inf at {path}{:?}", crate::data::unravel(i, a.shape())),
                        Value::Array(set_flat(a, i, f64::NEG_INFINITY)),
                    ));
                }
            }
            wrong_lengths(a, path, out);
            if out_of_bounds && let Some(i) = high.iter().position(|h| h.is_finite()) {
                let h = high.iter().nth(i).copied().unwrap_or(0.0);
                let beyond = if b.dtype().is_float() {
                    h + h.abs().max(1.0)
                } else {
                    h + 1.0
                };
                if beyond <= dtype_max(b.dtype()) {
                    out.push((
                        format!(
                            "{beyond} above the bound {h} at {path}{:?}",
                            crate::data::unravel(i, a.shape())
                        ),
                        Value::Array(set_flat(a, i, beyond)),
                    ));
                }
            }
        }
        (AnySpace::Discrete(d), _) => {
            if let Some(v) = d.start().checked_add(d.n()) {
                out.push((
                    format!("{v} (start + n) out of range{}", at(path)),
                    Value::Discrete(v),
                ));
            }
            if let Some(v) = d.start().checked_sub(1) {
                out.push((
                    format!("{v} (start - 1) out of range{}", at(path)),
                    Value::Discrete(v),
                ));
            }
        }
        (AnySpace::MultiDiscrete(m), Value::Array(a)) => {
            if let (Some(n), Some(s)) = (m.nvec().iter().next(), m.start().iter().next())
                && let Some(v) = s.checked_add(*n)
            {
                out.push((
                    format!("{v} out of range at {path}[0]"),
                    Value::Array(set_flat(a, 0, v as f64)),
                ));
            }
            wrong_lengths(a, path, out);
        }
        (AnySpace::MultiBinary(_), Value::Array(a)) => {
            if !a.is_empty() {
                out.push((format!("2 at {path}[0]"), Value::Array(set_flat(a, 0, 2.0))));
            }
            wrong_lengths(a, path, out);
        }
        (AnySpace::Tuple(t), Value::Tuple(items)) => {
            for (i, (s, x)) in t.spaces().iter().zip(items).enumerate() {
                let mut inner = Vec::new();
                corrupt(s, x, &format!("{path}[{i}]"), out_of_bounds, &mut inner);
                for (label, bad) in inner {
                    let mut whole = items.clone();
                    whole[i] = bad;
                    out.push((label, Value::Tuple(whole)));
                }
            }
            if !items.is_empty() {
                let mut fewer = items.clone();
                fewer.pop();
                out.push((
                    format!(
                        "a tuple of {} items (expected {}){}",
                        fewer.len(),
                        items.len(),
                        at(path)
                    ),
                    Value::Tuple(fewer),
                ));
            }
        }
        (AnySpace::Dict(d), Value::Dict(items)) => {
            for (k, s) in d.iter() {
                let Some(x) = items.get(k) else { continue };
                let mut inner = Vec::new();
                corrupt(s, x, &format!("{path}[{k:?}]"), out_of_bounds, &mut inner);
                for (label, bad) in inner {
                    let mut whole = items.clone();
                    whole.insert(k.to_owned(), bad);
                    out.push((label, Value::Dict(whole)));
                }
            }
            if let Some(k) = d.keys().next() {
                let mut missing: DictValue = items.clone();
                missing.shift_remove(k);
                out.push((
                    format!("missing key {k:?}{}", at(path)),
                    Value::Dict(missing),
                ));
            }
        }
        _ => {}
    }
}

fn dtype_max(d: gym_core::DType) -> f64 {
    use gym_core::DType::*;
    match d {
        I8 => <i8 as Scalar>::MAX,
        I16 => <i16 as Scalar>::MAX,
        I32 => <i32 as Scalar>::MAX,
        I64 => <i64 as Scalar>::MAX,
        U8 => <u8 as Scalar>::MAX,
        F32 => <f32 as Scalar>::MAX,
        F64 => <f64 as Scalar>::MAX,
        Bool => <bool as Scalar>::MAX,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gym_core::{BoxSpace, DictSpace, Discrete, Space, rng_from_seed};

    #[test]
    fn typed_box_actions() {
        let space = BoxSpace::<f32>::uniform(-1.0, 1.0, &[3]).unwrap();
        let base = space.sample(&mut rng_from_seed(0));
        let bad = invalid_actions(&space, &base, false, 16);
        let labels: Vec<_> = bad.iter().map(|b| b.label.as_str()).collect();
        assert_eq!(
            labels,
            [
                "NaN at [0]",
                "+inf at [0]",
                "-inf at [0]",
                "wrong length 4 (expected 3)",
                "wrong length 2 (expected 3)"
            ]
        );
        assert!(bad.iter().all(|b| !space.contains(&b.action)));
        assert_eq!(invalid_actions(&space, &base, true, 16).len(), 6);
    }

    #[test]
    fn discrete_and_dict_actions() {
        let d = Discrete::with_start(3, 1).unwrap();
        let bad = invalid_actions(&d, &2, false, 16);
        assert_eq!(bad.iter().map(|b| b.action).collect::<Vec<_>>(), [4, 0]);
        let space = AnySpace::Dict(
            DictSpace::new([
                ("a", AnySpace::Discrete(d)),
                ("b", BoxSpace::<f64>::unbounded(&[2]).into()),
            ])
            .unwrap(),
        );
        let base = space.sample(&mut rng_from_seed(1));
        let bad = invalid_actions(&space, &base, false, 16);
        let labels: Vec<_> = bad.iter().map(|b| b.label.as_str()).collect();
        assert!(labels.contains(&"NaN at [\"b\"][0]"), "{labels:?}");
        assert!(labels.contains(&"missing key \"a\""), "{labels:?}");
        assert!(
            !labels.iter().any(|l| l.contains("inf")),
            "unbounded Box elements accept ±inf: {labels:?}"
        );
    }
}
