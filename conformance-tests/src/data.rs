//! Comparing observations, infos and steps: Gymnasium's `data_equivalence` (approximate or
//! exact) and a bit-for-bit comparison for replays.
//!
//! Each `*_difference` function returns `None` when the two sides are equivalent and
//! otherwise a description of the first difference, with its path (`["key"][2]`).

use gym_core::{ArrayValue, Info, InfoValue, Step, Value};

/// How two numbers are compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Compare {
    /// `np.allclose(a, b, rtol=1e-5, atol=1e-5)` for arrays; NaN never equals NaN.
    Approx,
    /// `a == b` (so NaN never equals NaN, and `-0.0 == 0.0`).
    Exact,
    /// The same bits (so NaN equals the same NaN, and `-0.0 != 0.0`).
    Bits,
}

/// Gymnasium's `data_equivalence(d1, d2, exact)` on dynamic values: the same kind, the same
/// dict keys (in any order), the same tuple length, and arrays of the same shape and dtype
/// that are `allclose` (rtol = atol = 1e-5), or equal when `exact`.
pub fn data_equivalence(a: &Value, b: &Value, exact: bool) -> bool {
    value_difference(
        a,
        b,
        if exact {
            Compare::Exact
        } else {
            Compare::Approx
        },
    )
    .is_none()
}

/// The first difference between two values, or `None` when they are equivalent under `cmp`.
pub fn value_difference(a: &Value, b: &Value, cmp: Compare) -> Option<String> {
    diff_value(a, b, cmp, "")
}

/// The first difference between two infos, or `None` when they are equivalent under `cmp`.
///
/// As Gymnasium's `data_equivalence` on dicts: the key sets must be equal (order does not
/// matter), floats compare with `==` (Python floats are not arrays), arrays as in
/// [`value_difference`], nested maps recursively. A bool and an int are different kinds.
pub fn info_difference(a: &Info, b: &Info, cmp: Compare) -> Option<String> {
    diff_info(a, b, cmp, "")
}

/// The first difference between two steps (observation, reward, terminated, truncated,
/// info), or `None` when they are equivalent under `cmp`. Rewards compare exactly (or by
/// bits), as Gymnasium compares Python floats.
pub fn step_difference(a: &Step<Value>, b: &Step<Value>, cmp: Compare) -> Option<String> {
    if let Some(d) = value_difference(&a.observation, &b.observation, cmp) {
        return Some(format!("observation: {d}"));
    }
    let reward_differs = match cmp {
        Compare::Bits => a.reward.to_bits() != b.reward.to_bits(),
        _ => a.reward != b.reward,
    };
    if reward_differs {
        return Some(format!("reward: {} vs {}", a.reward, b.reward));
    }
    if a.terminated != b.terminated {
        return Some(format!("terminated: {} vs {}", a.terminated, b.terminated));
    }
    if a.truncated != b.truncated {
        return Some(format!("truncated: {} vs {}", a.truncated, b.truncated));
    }
    info_difference(&a.info, &b.info, cmp).map(|d| format!("info: {d}"))
}

/// A short rendering of a value for messages: arrays as `[0.5, -1]` (with their dtype and
/// shape when not one-dimensional), dicts as `{"k": ...}`, tuples as `(..., ...)`; cut to
/// about `max` characters.
pub fn compact(v: &Value, max: usize) -> String {
    let s = match v {
        Value::Array(a) => {
            let items: Vec<String> = a.to_f64_vec().iter().map(|x| format!("{x}")).collect();
            if a.shape().len() == 1 {
                format!("[{}]", items.join(", "))
            } else {
                format!("{} array {:?} [{}]", a.dtype(), a.shape(), items.join(", "))
            }
        }
        Value::Discrete(i) => i.to_string(),
        Value::Dict(d) => {
            let items: Vec<String> = d
                .iter()
                .map(|(k, x)| format!("{k:?}: {}", compact(x, max)))
                .collect();
            format!("{{{}}}", items.join(", "))
        }
        Value::Tuple(t) => {
            let items: Vec<String> = t.iter().map(|x| compact(x, max)).collect();
            format!("({})", items.join(", "))
        }
    };
    if s.chars().count() <= max {
        s
    } else {
        format!("{}...", s.chars().take(max).collect::<String>())
    }
}

fn at(path: &str) -> String {
    if path.is_empty() {
        "the top level".to_owned()
    } else {
        path.to_owned()
    }
}

fn diff_value(a: &Value, b: &Value, cmp: Compare, path: &str) -> Option<String> {
    match (a, b) {
        (Value::Array(x), Value::Array(y)) => diff_array(x, y, cmp, path),
        (Value::Discrete(x), Value::Discrete(y)) => {
            (x != y).then(|| format!("{} differs: {x} vs {y}", at(path)))
        }
        (Value::Dict(x), Value::Dict(y)) => {
            if x.len() != y.len() || !x.keys().all(|k| y.contains_key(k)) {
                return Some(format!(
                    "keys differ at {}: {:?} vs {:?}",
                    at(path),
                    x.keys().collect::<Vec<_>>(),
                    y.keys().collect::<Vec<_>>()
                ));
            }
            x.iter()
                .find_map(|(k, v)| diff_value(v, &y[k], cmp, &format!("{path}[{k:?}]")))
        }
        (Value::Tuple(x), Value::Tuple(y)) => {
            if x.len() != y.len() {
                return Some(format!(
                    "tuple lengths differ at {}: {} vs {}",
                    at(path),
                    x.len(),
                    y.len()
                ));
            }
            x.iter()
                .zip(y)
                .enumerate()
                .find_map(|(i, (u, v))| diff_value(u, v, cmp, &format!("{path}[{i}]")))
        }
        _ => Some(format!(
            "kinds differ at {}: {} vs {}",
            at(path),
            a.kind(),
            b.kind()
        )),
    }
}

/// Whether two numbers are equal under `cmp` (`np.isclose` semantics for `Approx`).
fn close(x: f64, y: f64, cmp: Compare) -> bool {
    match cmp {
        Compare::Bits => x.to_bits() == y.to_bits(),
        Compare::Exact => x == y,
        Compare::Approx => {
            x == y || (x.is_finite() && y.is_finite() && (x - y).abs() <= 1e-5 + 1e-5 * y.abs())
        }
    }
}

pub(crate) use gym_core::check::unravel;

macro_rules! same_variant {
    ($a:expr, $b:expr, |$x:ident, $y:ident| $body:expr, $otherwise:expr) => {
        match ($a, $b) {
            (ArrayValue::I8($x), ArrayValue::I8($y)) => $body,
            (ArrayValue::I16($x), ArrayValue::I16($y)) => $body,
            (ArrayValue::I32($x), ArrayValue::I32($y)) => $body,
            (ArrayValue::I64($x), ArrayValue::I64($y)) => $body,
            (ArrayValue::U8($x), ArrayValue::U8($y)) => $body,
            (ArrayValue::F32($x), ArrayValue::F32($y)) => $body,
            (ArrayValue::F64($x), ArrayValue::F64($y)) => $body,
            (ArrayValue::Bool($x), ArrayValue::Bool($y)) => $body,
            _ => $otherwise,
        }
    };
}

fn diff_array(a: &ArrayValue, b: &ArrayValue, cmp: Compare, path: &str) -> Option<String> {
    if a.dtype() != b.dtype() {
        return Some(format!(
            "dtypes differ at {}: {} vs {}",
            at(path),
            a.dtype(),
            b.dtype()
        ));
    }
    if a.shape() != b.shape() {
        return Some(format!(
            "shapes differ at {}: {:?} vs {:?}",
            at(path),
            a.shape(),
            b.shape()
        ));
    }
    let shape = a.shape().to_vec();
    let is_float = a.dtype().is_float();
    let first = same_variant!(
        a,
        b,
        |x, y| x.iter().zip(y.iter()).position(|(u, v)| {
            use gym_core::Scalar;
            if is_float {
                !close(u.to_f64(), v.to_f64(), cmp)
            } else {
                u != v
            }
        }),
        None
    );
    first.map(|i| {
        let (x, y) = (a.to_f64_vec()[i], b.to_f64_vec()[i]);
        format!("{path}{:?} differs: {x:?} vs {y:?}", unravel(i, &shape))
    })
}

fn diff_info(a: &Info, b: &Info, cmp: Compare, path: &str) -> Option<String> {
    if a.len() != b.len() || !a.keys().all(|k| b.contains_key(k)) {
        return Some(format!(
            "keys differ at {}: {:?} vs {:?}",
            at(path),
            a.keys().collect::<Vec<_>>(),
            b.keys().collect::<Vec<_>>()
        ));
    }
    a.iter().find_map(|(k, x)| {
        let p = format!("{path}[{k:?}]");
        let y = b.get(k)?;
        match (x, y) {
            (InfoValue::Bool(u), InfoValue::Bool(v)) => {
                (u != v).then(|| format!("{p} differs: {u} vs {v}"))
            }
            (InfoValue::Int(u), InfoValue::Int(v)) => {
                (u != v).then(|| format!("{p} differs: {u} vs {v}"))
            }
            (InfoValue::Str(u), InfoValue::Str(v)) => {
                (u != v).then(|| format!("{p} differs: {u:?} vs {v:?}"))
            }
            (InfoValue::Float(u), InfoValue::Float(v)) => {
                let same = if cmp == Compare::Bits {
                    u.to_bits() == v.to_bits()
                } else {
                    u == v
                };
                (!same).then(|| format!("{p} differs: {u:?} vs {v:?}"))
            }
            (InfoValue::Array(u), InfoValue::Array(v)) => diff_array(u, v, cmp, &p),
            (InfoValue::Map(u), InfoValue::Map(v)) => diff_info(u, v, cmp, &p),
            _ => Some(format!("kinds differ at {p}: {} vs {}", x.kind(), y.kind())),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::arr1;

    fn f32s(v: &[f32]) -> Value {
        Value::from(arr1(v).into_dyn())
    }

    #[test]
    fn approx_exact_and_bits() {
        let a = f32s(&[1.0, 2.0]);
        let b = f32s(&[1.0, 2.000_001]);
        assert!(data_equivalence(&a, &b, false));
        assert!(!data_equivalence(&a, &b, true));
        let nan = f32s(&[f32::NAN]);
        assert!(!data_equivalence(&nan, &nan, true));
        assert!(value_difference(&nan, &nan, Compare::Bits).is_none());
        let z = f32s(&[0.0]);
        let nz = f32s(&[-0.0]);
        assert!(data_equivalence(&z, &nz, true));
        assert!(value_difference(&z, &nz, Compare::Bits).is_some());
        let inf = f32s(&[f32::INFINITY]);
        assert!(data_equivalence(&inf, &inf, false));
    }

    #[test]
    fn dtype_and_kind_matter() {
        let a = f32s(&[1.0]);
        let b = Value::from(arr1(&[1.0f64]).into_dyn());
        assert!(
            value_difference(&a, &b, Compare::Approx)
                .unwrap()
                .contains("dtypes differ")
        );
        assert!(!data_equivalence(&Value::Discrete(1), &a, false));
    }

    #[test]
    fn info_keys_in_any_order() {
        let a = Info::new().with("x", 1.0).with("y", true);
        let b = Info::new().with("y", true).with("x", 1.0);
        assert!(info_difference(&a, &b, Compare::Exact).is_none());
        let c = Info::new().with("y", true).with("x", 1);
        assert!(
            info_difference(&a, &c, Compare::Exact)
                .unwrap()
                .contains("kinds differ")
        );
    }

    #[test]
    fn paths_name_the_element() {
        let mut d = gym_core::DictValue::new();
        d.insert("pos".into(), f32s(&[0.0, 1.0, 2.0]));
        let mut e = d.clone();
        e.insert("pos".into(), f32s(&[0.0, 1.0, 3.0]));
        let msg = value_difference(&Value::Dict(d), &Value::Dict(e), Compare::Exact).unwrap();
        assert_eq!(msg, "[\"pos\"][2] differs: 2.0 vs 3.0");
    }
}
