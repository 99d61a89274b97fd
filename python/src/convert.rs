//! Conversions between the dynamic values of gym-core and Python objects.

use gym_core::{
    AnySpace, ArrayValue, DictValue, Info, InfoValue, Scalar, Space, Value, for_each_array,
};
use ndarray::{ArrayD, Zip};
use numpy::{
    PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// A fresh NumPy array owning a copy of the values, of the value's dtype.
pub fn array_into_py(py: Python<'_>, a: ArrayValue) -> Bound<'_, PyAny> {
    for_each_array!(a, x => PyArrayDyn::from_owned_array(py, x).into_any())
}

/// A fresh NumPy array holding a copy of `a`, made in one pass (no intermediate copy).
pub fn array_to_py<'py>(py: Python<'py>, a: &ArrayValue) -> Bound<'py, PyAny> {
    for_each_array!(a, x => PyArrayDyn::from_array(py, x).into_any())
}

/// `v` with every array a read-only NumPy view of `v`'s memory (no copy), kept alive by
/// `owner`, the Python object that owns `v`.
///
/// # Safety
/// `v`'s arrays must stay allocated (never reallocated or dropped) for as long as `owner`
/// lives; their contents may change (the views show the change).
///
/// # Errors
/// Only when Python itself fails.
pub unsafe fn value_view_to_py<'py>(
    py: Python<'py>,
    v: &Value,
    owner: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Array(a) => {
            // SAFETY: the caller keeps the array's memory alive for `owner`'s life, and
            // `owner` is the view's base object.
            let view = for_each_array!(a, x => unsafe {
                PyArrayDyn::borrow_from_array(x, owner.clone()).into_any()
            });
            view.getattr("flags")?.setattr("writeable", false)?;
            view
        }
        Value::Discrete(i) => i.into_pyobject(py)?.into_any(),
        Value::Dict(d) => {
            let out = PyDict::new(py);
            for (k, x) in d {
                // SAFETY: the caller's contract covers every part of `v`.
                out.set_item(k, unsafe { value_view_to_py(py, x, owner)? })?;
            }
            out.into_any()
        }
        Value::Tuple(t) => {
            let items = t
                .iter()
                // SAFETY: as above.
                .map(|x| unsafe { value_view_to_py(py, x, owner) })
                .collect::<PyResult<Vec<_>>>()?;
            PyTuple::new(py, items)?.into_any()
        }
    })
}

/// [`value_into_py`] for a borrowed value: every array is copied once, straight into its
/// NumPy array.
///
/// # Errors
/// Only when Python itself fails.
pub fn value_to_py<'py>(py: Python<'py>, v: &Value, ordered: bool) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Array(a) => array_to_py(py, a),
        Value::Discrete(i) => i.into_pyobject(py)?.into_any(),
        Value::Dict(d) => {
            let out = if ordered {
                py.import("collections")?.getattr("OrderedDict")?.call0()?
            } else {
                PyDict::new(py).into_any()
            };
            for (k, x) in d {
                out.set_item(k, value_to_py(py, x, ordered)?)?;
            }
            out
        }
        Value::Tuple(t) => {
            let items = t
                .iter()
                .map(|x| value_to_py(py, x, ordered))
                .collect::<PyResult<Vec<_>>>()?;
            PyTuple::new(py, items)?.into_any()
        }
    })
}

/// Writes the Python object `obj` as an element of `space` into `out`. When `space` is a
/// Box, `out` already holds an array of the Box's dtype and `obj` is a NumPy array of
/// `out`'s shape with the same dtype (or, for a float Box, any float dtype, cast as
/// `np.asarray(obj, dtype=space.dtype)` does), the values are copied into `out` in one
/// pass without allocating; anything else goes through [`py_to_value`].
///
/// # Errors
/// As [`py_to_value`].
pub fn py_into_value(obj: &Bound<'_, PyAny>, space: &AnySpace, out: &mut Value) -> PyResult<()> {
    if let (AnySpace::Box(b), Value::Array(dst)) = (space, &mut *out)
        && dst.dtype() == b.dtype()
        && copy_into(obj, dst, b.dtype().is_float())
    {
        return Ok(());
    }
    *out = py_to_value(obj, space)?;
    Ok(())
}

/// Copies the NumPy array `obj` into `dst` when it has `dst`'s shape and dtype (or a float
/// dtype, with `float_cast`); `false` when it does not.
fn copy_into(obj: &Bound<'_, PyAny>, dst: &mut ArrayValue, float_cast: bool) -> bool {
    fn copy<S: numpy::Element + Scalar, T: Scalar>(
        obj: &Bound<'_, PyAny>,
        dst: &mut ArrayD<T>,
    ) -> Option<bool> {
        let src = obj.cast::<PyArrayDyn<S>>().ok()?.try_readonly().ok()?;
        let src = src.as_array();
        if src.shape() != dst.shape() {
            return Some(false);
        }
        Zip::from(dst)
            .and(&src)
            .for_each(|d, &s| *d = s.cast_to::<T>());
        Some(true)
    }
    macro_rules! exact_or_float {
        ($a:expr, $t:ty) => {
            copy::<$t, $t>(obj, $a)
                .or_else(|| {
                    float_cast
                        .then(|| copy::<f64, $t>(obj, $a).or_else(|| copy::<f32, $t>(obj, $a)))
                        .flatten()
                })
                .unwrap_or(false)
        };
    }
    match dst {
        ArrayValue::I8(a) => exact_or_float!(a, i8),
        ArrayValue::I16(a) => exact_or_float!(a, i16),
        ArrayValue::I32(a) => exact_or_float!(a, i32),
        ArrayValue::I64(a) => exact_or_float!(a, i64),
        ArrayValue::U8(a) => exact_or_float!(a, u8),
        ArrayValue::F32(a) => exact_or_float!(a, f32),
        ArrayValue::F64(a) => exact_or_float!(a, f64),
        // Bool Boxes go through `py_to_value`, which checks NumPy's bool dtype.
        ArrayValue::Bool(_) => false,
    }
}

/// An observation (or any space element) as Python objects: arrays become fresh NumPy
/// arrays, Discrete elements Python ints, Dicts `dict`s (an `OrderedDict` when `ordered`),
/// Tuples `tuple`s.
///
/// # Errors
/// Only when Python itself fails (out of memory, `collections` missing).
pub fn value_into_py(py: Python<'_>, v: Value, ordered: bool) -> PyResult<Bound<'_, PyAny>> {
    Ok(match v {
        Value::Array(a) => array_into_py(py, a),
        Value::Discrete(i) => i.into_pyobject(py)?.into_any(),
        Value::Dict(d) => dict_into_py(py, d, ordered)?,
        Value::Tuple(t) => {
            let items = t
                .into_iter()
                .map(|x| value_into_py(py, x, ordered))
                .collect::<PyResult<Vec<_>>>()?;
            PyTuple::new(py, items)?.into_any()
        }
    })
}

fn dict_into_py(py: Python<'_>, d: DictValue, ordered: bool) -> PyResult<Bound<'_, PyAny>> {
    let out = if ordered {
        py.import("collections")?.getattr("OrderedDict")?.call0()?
    } else {
        PyDict::new(py).into_any()
    };
    for (k, v) in d {
        out.set_item(k, value_into_py(py, v, ordered)?)?;
    }
    Ok(out)
}

/// An [`Info`] as a Python `dict` (bools, ints, floats, strs, arrays copied into fresh
/// NumPy arrays, nested dicts).
///
/// # Errors
/// Only when Python itself fails.
pub fn info_into_py<'py>(py: Python<'py>, info: &Info) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    for (k, v) in info.iter() {
        let v = match v {
            InfoValue::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
            InfoValue::Int(i) => i.into_pyobject(py)?.into_any(),
            InfoValue::Float(f) => PyFloat::new(py, *f).into_any(),
            InfoValue::Str(s) => PyString::new(py, s).into_any(),
            InfoValue::Array(a) => array_to_py(py, a),
            InfoValue::Map(m) => info_into_py(py, m)?.into_any(),
        };
        out.set_item(k, v)?;
    }
    Ok(out)
}

/// A Python object (usually a dict of keyword arguments or reset options) as an [`Info`]:
/// `bool`, `int`, `float`, `str`, `None` (as the string `"None"`), a list or tuple of
/// strings (joined with commas, for `robots=["Panda"]`), arrays and nested dicts.
///
/// # Errors
/// `ValueError` naming the key whose value has an unsupported type.
pub fn py_to_info(d: &Bound<'_, PyDict>) -> PyResult<Info> {
    let mut info = Info::new();
    for (k, v) in d.iter() {
        let key: String = k
            .extract()
            .map_err(|_| PyValueError::new_err("keyword names must be strings"))?;
        let value = py_to_info_value(&key, &v)?;
        info.insert(key, value);
    }
    Ok(info)
}

fn py_to_info_value(key: &str, v: &Bound<'_, PyAny>) -> PyResult<InfoValue> {
    if v.is_none() {
        return Ok(InfoValue::Str("None".into()));
    }
    if v.is_instance_of::<PyBool>() {
        return Ok(InfoValue::Bool(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return Ok(InfoValue::Int(v.extract()?));
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(InfoValue::Float(v.extract()?));
    }
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(InfoValue::Str(s.to_str()?.to_owned()));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        return Ok(InfoValue::Map(py_to_info(d)?));
    }
    if (v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>())
        && let Ok(items) = v.extract::<Vec<String>>()
    {
        return Ok(InfoValue::Str(items.join(",")));
    }
    if v.is_instance_of::<PyUntypedArray>() {
        return Ok(InfoValue::Array(array_from_py(v)?));
    }
    // NumPy scalars and other numbers.
    if let Ok(b) = v.extract::<bool>()
        && v.get_type().name()?.to_str()? == "bool"
    {
        return Ok(InfoValue::Bool(b));
    }
    if let Ok(i) = v.extract::<i64>() {
        return Ok(InfoValue::Int(i));
    }
    if let Ok(f) = v.extract::<f64>() {
        return Ok(InfoValue::Float(f));
    }
    Err(PyValueError::new_err(format!(
        "argument `{key}`: unsupported value of type {}",
        v.get_type()
            .name()
            .map(|n| n.to_string())
            .unwrap_or_else(|_| "?".into())
    )))
}

/// A Python value as JSON, for keyword arguments (robosuite's `make(**kwargs)`): `None`,
/// bools, ints, floats, strs, lists, tuples, dicts with str keys, and NumPy arrays and
/// scalars (through their `tolist()`).
///
/// # Errors
/// `ValueError` naming the argument (`path`, e.g. `camera_heights[1]`) that holds a
/// non-finite float, a dict key that is not a str, or a value of another type.
pub fn py_to_json(obj: &Bound<'_, PyAny>, path: &str) -> PyResult<serde_json::Value> {
    use serde_json::Value as J;
    if obj.is_none() {
        return Ok(J::Null);
    }
    if obj.is_instance_of::<PyBool>() {
        return Ok(J::Bool(obj.extract()?));
    }
    if obj.is_instance_of::<PyInt>() {
        if let Ok(i) = obj.extract::<i64>() {
            return Ok(J::from(i));
        }
        return Ok(J::from(obj.extract::<u64>().map_err(|_| {
            PyValueError::new_err(format!("invalid argument `{path}`: integer out of range"))
        })?));
    }
    if obj.is_instance_of::<PyFloat>() {
        let f: f64 = obj.extract()?;
        return serde_json::Number::from_f64(f)
            .map(J::Number)
            .ok_or_else(|| {
                PyValueError::new_err(format!(
                    "invalid argument `{path}`: must be a finite number, got {f}"
                ))
            });
    }
    if let Ok(s) = obj.cast::<PyString>() {
        return Ok(J::String(s.to_str()?.to_owned()));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut map = serde_json::Map::new();
        for (k, v) in d.iter() {
            let key: String = k.extract().map_err(|_| {
                PyValueError::new_err(format!("invalid argument `{path}`: dict keys must be strs"))
            })?;
            let value = py_to_json(&v, &format!("{path}.{key}"))?;
            map.insert(key, value);
        }
        return Ok(J::Object(map));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        return obj
            .try_iter()?
            .enumerate()
            .map(|(i, v)| py_to_json(&v?, &format!("{path}[{i}]")))
            .collect::<PyResult<Vec<_>>>()
            .map(J::Array);
    }
    // NumPy arrays and scalars: their plain Python values.
    let module = obj.get_type().module()?;
    if module.to_str()? == "numpy" && obj.hasattr("tolist")? {
        return py_to_json(&obj.call_method0("tolist")?, path);
    }
    Err(PyValueError::new_err(format!(
        "invalid argument `{path}`: unsupported value of type {}",
        obj.get_type().name()?
    )))
}

/// Any array-like (NumPy array, list, scalar) as an [`ArrayValue`] of its NumPy dtype
/// (`bool` becomes `int8`, other integer types `int64` by value, other float types
/// `float64`).
///
/// # Errors
/// `ValueError` for objects NumPy cannot turn into a numeric array, and for unsigned values
/// above `i64::MAX`.
pub fn array_from_py(obj: &Bound<'_, PyAny>) -> PyResult<ArrayValue> {
    let py = obj.py();
    let np = py.import("numpy")?;
    let arr = np.call_method1("asarray", (obj,))?;
    if let Some(a) = typed_array(&arr) {
        return Ok(a);
    }
    let kind = arr
        .cast::<PyUntypedArray>()
        .map(|a| a.dtype().kind())
        .unwrap_or(b'O');
    let target = match kind {
        b'b' => "int8",
        b'i' => "int64",
        // By value: an unsigned value above int64's range is rejected, never wrapped.
        b'u' => {
            if arr.getattr("size")?.extract::<usize>()? > 0 {
                let max: u64 = arr.call_method0("max")?.extract()?;
                if max > i64::MAX as u64 {
                    return Err(PyValueError::new_err(format!(
                        "invalid value: the unsigned value {max} does not fit int64"
                    )));
                }
            }
            "int64"
        }
        b'f' => "float64",
        _ => {
            return Err(PyValueError::new_err(format!(
                "expected a numeric array, got {}",
                obj.repr().map(|r| r.to_string()).unwrap_or_default()
            )));
        }
    };
    typed_array(&arr.call_method1("astype", (target,))?)
        .ok_or_else(|| PyValueError::new_err("cannot convert the array to a supported dtype"))
}

/// The array as an [`ArrayValue`] if its dtype is one gym-core supports.
fn typed_array(arr: &Bound<'_, PyAny>) -> Option<ArrayValue> {
    macro_rules! try_dtype {
        ($($t:ty),*) => {$(
            if let Ok(a) = arr.cast::<PyArrayDyn<$t>>() {
                return Some(ArrayValue::from(a.readonly().as_array().to_owned()));
            }
        )*};
    }
    try_dtype!(f64, f32, i64, i32, i16, i8, u8, bool);
    None
}

/// A Python object as an element of `space` (structure from the space, dtype from the
/// object; bounds are the environment's to check).
///
/// # Errors
/// `ValueError` when the object does not have the space's structure.
pub fn py_to_value(obj: &Bound<'_, PyAny>, space: &AnySpace) -> PyResult<Value> {
    match space {
        // As `np.asarray(action, dtype=space.dtype)` for float boxes: a float64 policy
        // output (or a list) is accepted by a float32 action space.
        AnySpace::Box(b) => {
            let a = array_from_py(obj)?;
            Ok(Value::Array(
                if b.dtype().is_float() && a.dtype() != b.dtype() {
                    a.cast(b.dtype())
                } else {
                    a
                },
            ))
        }
        AnySpace::MultiDiscrete(_) | AnySpace::MultiBinary(_) => {
            Ok(Value::Array(array_from_py(obj)?))
        }
        AnySpace::Discrete(_) => {
            if let Ok(i) = obj.extract::<i64>() {
                return Ok(Value::Discrete(i));
            }
            let a = array_from_py(obj)?;
            match (a.len(), a.dtype().is_float()) {
                (1, false) => Ok(Value::Discrete(a.to_f64_vec()[0] as i64)),
                _ => Err(PyValueError::new_err(format!(
                    "invalid action: expected an integer for {space}"
                ))),
            }
        }
        AnySpace::Dict(d) => {
            let mut out = DictValue::with_capacity(d.len());
            for (k, s) in d.iter() {
                let item = obj.get_item(k).map_err(|_| {
                    PyValueError::new_err(format!("invalid action: missing key `{k}` for {space}"))
                })?;
                out.insert(k.to_owned(), py_to_value(&item, s)?);
            }
            Ok(Value::Dict(out))
        }
        AnySpace::Tuple(t) => {
            let n = obj.len().map_err(|_| {
                PyValueError::new_err(format!("invalid action: expected a tuple for {space}"))
            })?;
            if n != t.len() {
                return Err(PyValueError::new_err(format!(
                    "invalid action: expected a tuple of {} elements, got {n}",
                    t.len()
                )));
            }
            let items = t
                .spaces()
                .iter()
                .enumerate()
                .map(|(i, s)| py_to_value(&obj.get_item(i)?, s))
                .collect::<PyResult<Vec<_>>>()?;
            Ok(Value::Tuple(items))
        }
    }
}

/// A description of `space` that `robosuite_rs.spaces.from_spec` turns into a
/// `gymnasium.spaces.Space`: `("Box", low, high, dtype)`, `("Discrete", n, start)`,
/// `("MultiDiscrete", nvec, start)`, `("MultiBinary", shape)`, `("Dict", [(key, spec)])`,
/// `("Tuple", [spec])`. Box bounds are `float64` arrays with ±inf where unbounded.
///
/// # Errors
/// Only when Python itself fails.
pub fn space_spec<'py>(py: Python<'py>, space: &AnySpace) -> PyResult<Bound<'py, PyAny>> {
    Ok(match space {
        AnySpace::Box(b) => {
            let (low, high) = b.bounds_f64();
            (
                "Box",
                PyArrayDyn::from_owned_array(py, low),
                PyArrayDyn::from_owned_array(py, high),
                b.dtype().name(),
            )
                .into_pyobject(py)?
                .into_any()
        }
        AnySpace::Discrete(d) => ("Discrete", d.n(), d.start()).into_pyobject(py)?.into_any(),
        AnySpace::MultiDiscrete(m) => (
            "MultiDiscrete",
            PyArrayDyn::from_owned_array(py, m.nvec().clone()),
            PyArrayDyn::from_owned_array(py, m.start().clone()),
        )
            .into_pyobject(py)?
            .into_any(),
        AnySpace::MultiBinary(m) => ("MultiBinary", m.shape().unwrap_or(&[]).to_vec())
            .into_pyobject(py)?
            .into_any(),
        AnySpace::Dict(d) => {
            let items = d
                .iter()
                .map(|(k, s)| {
                    Ok((k.to_owned(), space_spec(py, s)?)
                        .into_pyobject(py)?
                        .into_any())
                })
                .collect::<PyResult<Vec<_>>>()?;
            ("Dict", PyList::new(py, items)?)
                .into_pyobject(py)?
                .into_any()
        }
        AnySpace::Tuple(t) => {
            let items = t
                .spaces()
                .iter()
                .map(|s| space_spec(py, s))
                .collect::<PyResult<Vec<_>>>()?;
            ("Tuple", PyList::new(py, items)?)
                .into_pyobject(py)?
                .into_any()
        }
    })
}
