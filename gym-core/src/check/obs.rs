//! Gymnasium's `check_obs(obs, observation_space, method_name)`, on dynamic values, with
//! the reason an observation is not in its space spelled out.

use super::report::{Check, Failure, Warning, WarningKind};
use super::unravel;
use crate::{AnyBox, AnySpace, ArrayValue, Space, Value};

/// Checks an observation returned by `method` (`"reset"` or `"step"`) against its space.
///
/// In order, recursively through Dict and Tuple:
/// 1. structure ([`Check::ObservationStructure`]): an array for Box, MultiBinary and
///    MultiDiscrete, an integer for Discrete (a 0-d integer array is accepted with
///    Gymnasium's "should be an int or np.int64" warning), a dict with exactly the space's
///    keys, a tuple of the space's length;
/// 2. dtype ([`Check::ObservationDtype`]): a Box observation (of non-empty shape, as in
///    Gymnasium) whose dtype differs from the space's fails when it cannot be cast safely
///    (it is then not in the space: Gymnasium's `np.can_cast` rule, e.g. `float64` for a
///    `float32` Box) and warns otherwise, with Gymnasium's wording; MultiDiscrete
///    observations must have an integer dtype;
/// 3. finiteness ([`Check::ObservationFinite`]): no NaN or ±inf anywhere (an infinite
///    value in an unbounded Box is in the space, but is refused here, as SB3's NaN check
///    does);
/// 4. bounds and shape ([`Check::ObservationContained`]): `space.contains(obs)`, naming
///    the first element out of its bounds.
///
/// # Errors
/// The first violated rule, with the path of the offending element.
pub fn check_obs(obs: &Value, space: &AnySpace, method: &str) -> Result<Vec<Warning>, Failure> {
    let pre = format!("The obs returned by the `{method}()` method");
    let mut warnings = Vec::new();
    walk(obs, space, &pre, "", &mut warnings)?;
    if !space.contains(obs) {
        return Err(Failure::new(
            Check::ObservationContained,
            format!("{pre} is not within the observation space."),
        ));
    }
    Ok(warnings)
}

fn place(path: &str) -> String {
    if path.is_empty() {
        String::new()
    } else {
        format!(" at {path}")
    }
}

fn walk(
    obs: &Value,
    space: &AnySpace,
    pre: &str,
    path: &str,
    warnings: &mut Vec<Warning>,
) -> Result<(), Failure> {
    let structure = |m: String| {
        Err(Failure::new(
            Check::ObservationStructure,
            format!("{pre}{} {m}", place(path)),
        ))
    };
    match (space, obs) {
        (AnySpace::Box(b), Value::Array(a)) => check_box_obs(a, b, pre, path, warnings),
        (AnySpace::Box(_), other) => structure(format!(
            "was expecting a numpy array, actual type: {}",
            other.kind()
        )),
        (AnySpace::Discrete(d), Value::Discrete(x)) => {
            if d.contains(x) {
                Ok(())
            } else {
                Err(Failure::new(
                    Check::ObservationContained,
                    format!(
                        "{pre}{} is not within the observation space: {x} is not in Discrete({}, start={})",
                        place(path),
                        d.n(),
                        d.start()
                    ),
                ))
            }
        }
        (AnySpace::Discrete(_), Value::Array(a))
            if a.shape().is_empty() && !a.dtype().is_float() =>
        {
            warnings.push(Warning::new(
                WarningKind::DiscreteObservationType,
                format!(
                    "{pre}{} should be an int or np.int64, actual type: 0-d {} array",
                    place(path),
                    a.dtype()
                ),
            ));
            contained(obs, space, pre, path)
        }
        (AnySpace::Discrete(_), other) => structure(format!(
            "should be an int or np.int64, actual type: {}",
            describe(other)
        )),
        (AnySpace::MultiDiscrete(_), Value::Array(a)) => {
            if a.dtype().is_float() {
                return Err(Failure::new(
                    Check::ObservationDtype,
                    format!(
                        "{pre}{} was expecting an integer array (MultiDiscrete is int64), actual type: {}",
                        place(path),
                        a.dtype()
                    ),
                ));
            }
            contained(obs, space, pre, path)
        }
        (AnySpace::MultiBinary(_), Value::Array(a)) => {
            if !a.all_finite() {
                return Err(Failure::new(
                    Check::ObservationFinite,
                    format!("{pre}{} contains NaN or inf", place(path)),
                ));
            }
            contained(obs, space, pre, path)
        }
        (AnySpace::MultiDiscrete(_) | AnySpace::MultiBinary(_), other) => structure(format!(
            "was expecting a numpy array, actual type: {}",
            other.kind()
        )),
        (AnySpace::Tuple(t), Value::Tuple(items)) => {
            if items.len() != t.len() {
                return structure(format!(
                    "length is not same as the observation space length, obs length: {}, space length: {}",
                    items.len(),
                    t.len()
                ));
            }
            for (i, (s, x)) in t.spaces().iter().zip(items).enumerate() {
                walk(x, s, pre, &format!("{path}[{i}]"), warnings)?;
            }
            Ok(())
        }
        (AnySpace::Tuple(_), other) => structure(format!(
            "was expecting a tuple, actual type: {}",
            other.kind()
        )),
        (AnySpace::Dict(d), Value::Dict(items)) => {
            if items.len() != d.len() || !d.keys().all(|k| items.contains_key(k)) {
                return structure(format!(
                    "observation keys is not same as the observation space keys, obs keys: {:?}, space keys: {:?}",
                    items.keys().collect::<Vec<_>>(),
                    d.keys().collect::<Vec<_>>()
                ));
            }
            for (k, s) in d.iter() {
                walk(&items[k], s, pre, &format!("{path}[{k:?}]"), warnings)?;
            }
            Ok(())
        }
        (AnySpace::Dict(_), other) => {
            structure(format!("must be a dict, actual type: {}", other.kind()))
        }
    }
}

fn describe(v: &Value) -> String {
    match v {
        Value::Array(a) => format!("{} array of shape {:?}", a.dtype(), a.shape()),
        other => other.kind().to_owned(),
    }
}

fn contained(obs: &Value, space: &AnySpace, pre: &str, path: &str) -> Result<(), Failure> {
    if space.contains(obs) {
        Ok(())
    } else {
        Err(Failure::new(
            Check::ObservationContained,
            format!(
                "{pre}{} is not within the observation space {space}: {}",
                place(path),
                describe(obs)
            ),
        ))
    }
}

fn check_box_obs(
    a: &ArrayValue,
    b: &AnyBox,
    pre: &str,
    path: &str,
    warnings: &mut Vec<Warning>,
) -> Result<(), Failure> {
    let shape = b.shape().unwrap_or(&[]);
    if !shape.is_empty() && a.dtype() != b.dtype() {
        let msg = format!(
            "{pre}{} was expecting numpy array dtype to be {}, actual type: {}",
            place(path),
            b.dtype(),
            a.dtype()
        );
        if a.dtype().can_cast_to(b.dtype()) {
            warnings.push(Warning::new(WarningKind::ObservationDtype, msg));
        } else {
            return Err(Failure::new(
                Check::ObservationDtype,
                format!(
                    "{msg} ({} cannot be cast safely to {}, so the observation is not in the space)",
                    a.dtype(),
                    b.dtype()
                ),
            ));
        }
    }
    if !a.all_finite() {
        let values = a.to_f64_vec();
        let i = values.iter().position(|v| !v.is_finite()).unwrap_or(0);
        return Err(Failure::new(
            Check::ObservationFinite,
            format!(
                "{pre}{} contains a non-finite value: element {:?} is {}",
                place(path),
                unravel(i, a.shape()),
                values.get(i).copied().unwrap_or(f64::NAN)
            ),
        ));
    }
    if b.contains(a) {
        return Ok(());
    }
    let why = if a.shape() != shape {
        format!("its shape {:?} is not the space's {shape:?}", a.shape())
    } else if !a.dtype().can_cast_to(b.dtype()) {
        format!(
            "its dtype {} cannot be cast safely to {}",
            a.dtype(),
            b.dtype()
        )
    } else {
        let (low, high) = b.bounds_f64();
        let values = a.to_f64_vec();
        match values
            .iter()
            .zip(low.iter().zip(high.iter()))
            .position(|(v, (l, h))| !(v >= l && v <= h))
        {
            Some(i) => format!(
                "element {:?} = {} is outside [{}, {}]",
                unravel(i, a.shape()),
                values[i],
                low.iter().nth(i).copied().unwrap_or(f64::NAN),
                high.iter().nth(i).copied().unwrap_or(f64::NAN)
            ),
            None => "it is not contained".to_owned(),
        }
    };
    Err(Failure::new(
        Check::ObservationContained,
        format!(
            "{pre}{} is not within the observation space {b}: {why}",
            place(path)
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BoxSpace, DictSpace, Discrete};
    use ndarray::arr1;

    fn space() -> AnySpace {
        BoxSpace::<f32>::uniform(-1.0, 1.0, &[2]).unwrap().into()
    }

    #[test]
    fn diagnoses() {
        let ok = Value::from(arr1(&[0.5f32, -0.5]).into_dyn());
        assert!(check_obs(&ok, &space(), "reset").unwrap().is_empty());
        let f64s = Value::from(arr1(&[0.5f64, -0.5]).into_dyn());
        let f = check_obs(&f64s, &space(), "reset").unwrap_err();
        assert_eq!(f.check, Check::ObservationDtype);
        assert!(f.message.starts_with(
            "The obs returned by the `reset()` method was expecting numpy array dtype to be float32, actual type: float64"
        ));
        let i8s = Value::from(arr1(&[0i8, 1]).into_dyn());
        assert_eq!(
            check_obs(&i8s, &space(), "step").unwrap()[0].kind,
            WarningKind::ObservationDtype
        );
        let out = Value::from(arr1(&[0.5f32, 2.0]).into_dyn());
        let f = check_obs(&out, &space(), "step").unwrap_err();
        assert_eq!(f.check, Check::ObservationContained);
        assert!(
            f.message.ends_with("element [1] = 2 is outside [-1, 1]"),
            "{}",
            f.message
        );
        let nan = Value::from(arr1(&[f32::NAN, 0.0]).into_dyn());
        assert_eq!(
            check_obs(&nan, &space(), "step").unwrap_err().check,
            Check::ObservationFinite
        );
        let short = Value::from(arr1(&[0.5f32]).into_dyn());
        assert!(
            check_obs(&short, &space(), "step")
                .unwrap_err()
                .message
                .contains("shape [1]")
        );
    }

    #[test]
    fn structure() {
        let d = AnySpace::Dict(
            DictSpace::new([
                ("a", space()),
                ("b", AnySpace::Discrete(Discrete::new(2).unwrap())),
            ])
            .unwrap(),
        );
        let mut v = crate::DictValue::new();
        v.insert("a".into(), Value::from(arr1(&[0.0f32, 0.0]).into_dyn()));
        assert_eq!(
            check_obs(&Value::Dict(v.clone()), &d, "reset")
                .unwrap_err()
                .check,
            Check::ObservationStructure
        );
        v.insert("b".into(), Value::Discrete(2));
        let f = check_obs(&Value::Dict(v.clone()), &d, "reset").unwrap_err();
        assert_eq!(f.check, Check::ObservationContained);
        assert!(f.message.contains("at [\"b\"]"));
        v.insert("b".into(), Value::Discrete(1));
        assert!(check_obs(&Value::Dict(v), &d, "reset").is_ok());
    }
}
