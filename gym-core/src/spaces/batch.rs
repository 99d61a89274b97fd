//! Batched spaces (Gymnasium's `gymnasium.vector.utils`): [`BatchSpace::batch_space`],
//! writing and reading one item of a batch in place (`concatenate` / `iterate`),
//! `create_empty_array` and `create_zero_array`.
//!
//! | single space | batched space |
//! |---|---|
//! | `Box` | `Box` with tiled bounds, shape `(n, *shape)` |
//! | `Discrete(n', start)` | `MultiDiscrete(full(n, n'), start = full(n, start))` |
//! | `MultiDiscrete` | `Box(tile(start), tile(start + nvec - 1), int64)` |
//! | `MultiBinary` | `Box(0, 1, (n, *shape), int8)` |
//! | `Dict` / `Tuple` | a Dict / Tuple of the batched parts, same order |

use crate::row::{RowLeaf, RowLeaves};
use crate::spaces::{
    AnyBox, AnySpace, BoxSpace, DictSpace, Discrete, MultiBinary, MultiDiscrete, TupleSpace,
};
use crate::{
    ArrayElement, ArrayValue, DictValue, DynSpace, Error, Flatten, Result, Space, SpaceError, Value,
};
use ndarray::{ArrayD, Axis, IxDyn, Zip};

/// The element type of a batched space.
pub type BatchOf<S> = <<S as BatchSpace>::Batched as Space>::Element;

/// A space that can be batched, with in-place access to one item of a batch.
pub trait BatchSpace: Flatten + DynSpace {
    /// The space of `n` stacked elements.
    type Batched: Flatten + DynSpace;

    /// Gymnasium's `batch_space(space, n)`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when `n == 0`.
    fn batch_space(&self, n: usize) -> Result<Self::Batched>;

    /// Gymnasium's `create_empty_array(space, n)`: a zero-filled batch of `n` items (not
    /// necessarily inside the batched space).
    fn create_empty_batch(&self, n: usize) -> BatchOf<Self>;

    /// Writes `x` as item `i` of `batch` (Gymnasium's `concatenate` for one item).
    ///
    /// # Errors
    /// When `x` or `batch` does not have the structure of the space, or `i` is out of range.
    fn write_item(&self, batch: &mut BatchOf<Self>, i: usize, x: &Self::Element) -> Result<()>;

    /// Reads item `i` of `batch` (Gymnasium's `iterate`).
    ///
    /// # Errors
    /// When `batch` does not have the structure of the space, or `i` is out of range.
    fn read_item(&self, batch: &BatchOf<Self>, i: usize) -> Result<Self::Element>;

    /// [`BatchSpace::read_item`] into `out`, reusing its storage when it already has the
    /// item's shape (arrays; other elements are replaced), so that reading the rows of a
    /// batch in a loop does not allocate.
    ///
    /// # Errors
    /// As [`BatchSpace::read_item`]; `out` is unchanged then.
    fn read_item_into(
        &self,
        batch: &BatchOf<Self>,
        i: usize,
        out: &mut Self::Element,
    ) -> Result<()> {
        *out = self.read_item(batch, i)?;
        Ok(())
    }

    /// Checks that `batch` holds exactly `n` items of this space's shape and no NaN or
    /// ±inf value (what a vector environment checks before any sub-environment steps).
    /// Array spaces check without allocating.
    ///
    /// # Errors
    /// [`Error::InvalidAction`] naming the first problem.
    fn check_batch(&self, batch: &BatchOf<Self>, n: usize) -> Result<()> {
        check_any_batch(self, batch, n)
    }

    /// The array leaves of item `i` of `batch` (see [`ObsRow`](crate::ObsRow)), appended to
    /// `out`, for an environment to write its observation straight into the batch: one
    /// for an array space, one per entry for a Dict whose entries are array spaces.
    /// `false` (and `out` unspecified) for other spaces (the default), a batch that does
    /// not have the space's structure, or `i` out of range.
    fn row_leaves(&self, batch: &mut BatchOf<Self>, i: usize, out: &mut RowLeaves) -> bool {
        let _ = (batch, i, out);
        false
    }

    /// Gymnasium's `create_zero_array(space)`: the element closest to zero that is still
    /// valid (Box zeros moved into the bounds, Discrete/MultiDiscrete `start`, zeros).
    fn zero_element(&self) -> Self::Element;
}

fn check_n(n: usize) -> Result<()> {
    if n == 0 {
        Err(Error::invalid_argument(
            "n",
            "a batch needs at least one item",
        ))
    } else {
        Ok(())
    }
}

fn batched_shape(n: usize, shape: &[usize]) -> Vec<usize> {
    let mut s = Vec::with_capacity(shape.len() + 1);
    s.push(n);
    s.extend_from_slice(shape);
    s
}

/// `np.tile(a, (n, 1, ...))`: `n` copies stacked along a new first axis.
pub fn tile<T: Clone>(a: &ArrayD<T>, n: usize) -> ArrayD<T> {
    a.broadcast(IxDyn(&batched_shape(n, a.shape())))
        .expect("prepending an axis always broadcasts")
        .to_owned()
}

/// The default [`BatchSpace::check_batch`]: reads every item and flattens the batch.
fn check_any_batch<S: BatchSpace>(space: &S, batch: &BatchOf<S>, n: usize) -> Result<()> {
    for k in 0..n {
        space
            .read_item(batch, k)
            .map_err(|e| Error::invalid_action(format!("actions[{k}]: {e}")))?;
    }
    // Every item exists and has the item's shape; the flat length then pins the number of
    // items to exactly `n`.
    let flat = space.batch_space(n)?.flatten(batch).map_err(|e| {
        Error::invalid_action(format!("expected a batch of exactly {n} actions: {e}"))
    })?;
    if !flat.all_finite() {
        let values = flat.to_f64_vec();
        let at = values.iter().position(|v| !v.is_finite()).unwrap_or(0);
        return Err(not_finite(
            at / (values.len() / n.max(1)).max(1),
            values[at],
        ));
    }
    Ok(())
}

fn not_finite(row: usize, value: f64) -> Error {
    Error::invalid_action(format!(
        "actions[{row}] holds a value that is not finite ({value}); nothing was stepped"
    ))
}

/// [`BatchSpace::check_batch`] for an array batch whose items have shape `item_shape`,
/// without allocating.
fn check_typed<T: ArrayElement>(batch: &ArrayD<T>, n: usize, item_shape: &[usize]) -> Result<()> {
    if batch.ndim() == 0 || &batch.shape()[1..] != item_shape {
        return Err(Error::invalid_action(format!(
            "actions[0]: {}",
            SpaceError::ShapeMismatch {
                expected: batched_shape(n, item_shape),
                got: batch.shape().to_vec(),
            }
        )));
    }
    if batch.shape()[0] != n {
        return Err(Error::invalid_action(format!(
            "expected a batch of exactly {n} actions, got {}",
            batch.shape()[0]
        )));
    }
    let per_row = item_shape.iter().product::<usize>().max(1);
    match batch.iter().position(|x| !x.is_finite()) {
        Some(at) => Err(not_finite(
            at / per_row,
            batch.iter().nth(at).map_or(f64::NAN, |x| x.to_f64()),
        )),
        None => Ok(()),
    }
}

/// Reads row `i` of `batch` into `out`, in place when `out` has the row's shape.
fn read_typed_into<T: ArrayElement>(
    batch: &ArrayD<T>,
    i: usize,
    item_shape: &[usize],
    out: &mut ArrayD<T>,
) -> Result<()> {
    if out.shape() != item_shape {
        *out = read_typed(batch, i, item_shape)?;
        return Ok(());
    }
    let n = batch.shape().first().copied().unwrap_or(0);
    if i >= n {
        return Err(out_of_range(i, n));
    }
    if &batch.shape()[1..] != item_shape {
        return Err(SpaceError::ShapeMismatch {
            expected: batched_shape(n, item_shape),
            got: batch.shape().to_vec(),
        }
        .into());
    }
    out.assign(&batch.index_axis(Axis(0), i));
    Ok(())
}

/// [`read_typed_into`] for dynamic arrays: in place when `out` has the batch's dtype.
fn read_array_value_into(
    batch: &ArrayValue,
    i: usize,
    item_shape: &[usize],
    out: &mut ArrayValue,
) -> Result<()> {
    fn go<T: ArrayElement>(
        batch: &ArrayD<T>,
        i: usize,
        item_shape: &[usize],
        out: &mut ArrayValue,
    ) -> Result<()> {
        // Borrow `out` as the batch's array type when the dtypes agree.
        let typed: Option<&mut ArrayD<T>> = crate::for_each_array!(out, a => {
            (a as &mut dyn std::any::Any).downcast_mut::<ArrayD<T>>()
        });
        match typed {
            Some(a) => read_typed_into(batch, i, item_shape, a),
            None => {
                *out = T::wrap(read_typed(batch, i, item_shape)?);
                Ok(())
            }
        }
    }
    crate::for_each_array!(batch, b => go(b, i, item_shape, out))
}

fn check_array_value(batch: &ArrayValue, n: usize, item_shape: &[usize]) -> Result<()> {
    crate::for_each_array!(batch, b => check_typed(b, n, item_shape))
}

fn out_of_range(i: usize, n: usize) -> Error {
    Error::invalid_argument("index", format!("item {i} is outside a batch of {n}"))
}

fn write_typed<T: ArrayElement>(batch: &mut ArrayD<T>, i: usize, x: &ArrayD<T>) -> Result<()> {
    let n = batch.shape().first().copied().unwrap_or(0);
    if i >= n {
        return Err(out_of_range(i, n));
    }
    if &batch.shape()[1..] != x.shape() {
        return Err(SpaceError::ShapeMismatch {
            expected: batch.shape()[1..].to_vec(),
            got: x.shape().to_vec(),
        }
        .into());
    }
    batch.index_axis_mut(Axis(0), i).assign(x);
    Ok(())
}

fn read_typed<T: ArrayElement>(
    batch: &ArrayD<T>,
    i: usize,
    item_shape: &[usize],
) -> Result<ArrayD<T>> {
    let n = batch.shape().first().copied().unwrap_or(0);
    if i >= n {
        return Err(out_of_range(i, n));
    }
    if &batch.shape()[1..] != item_shape {
        return Err(SpaceError::ShapeMismatch {
            expected: batched_shape(n, item_shape),
            got: batch.shape().to_vec(),
        }
        .into());
    }
    Ok(batch.index_axis(Axis(0), i).to_owned())
}

/// Writes an array item into an array batch, casting the item to the batch's dtype.
fn write_array_value(batch: &mut ArrayValue, i: usize, x: &ArrayValue) -> Result<()> {
    fn go<T: ArrayElement>(batch: &mut ArrayD<T>, i: usize, x: &ArrayValue) -> Result<()> {
        match T::peek(x) {
            Some(typed) => write_typed(batch, i, typed),
            None => write_typed(batch, i, &crate::spaces::numeric::array_value_to::<T>(x)),
        }
    }
    match batch {
        ArrayValue::I8(b) => go(b, i, x),
        ArrayValue::I16(b) => go(b, i, x),
        ArrayValue::I32(b) => go(b, i, x),
        ArrayValue::I64(b) => go(b, i, x),
        ArrayValue::U8(b) => go(b, i, x),
        ArrayValue::F32(b) => go(b, i, x),
        ArrayValue::F64(b) => go(b, i, x),
        ArrayValue::Bool(b) => go(b, i, x),
    }
}

fn read_array_value(batch: &ArrayValue, i: usize, item_shape: &[usize]) -> Result<ArrayValue> {
    crate::for_each_array!(batch, b => Ok(ArrayValue::from(read_typed(b, i, item_shape)?)))
}

fn box_zero<T: ArrayElement>(b: &BoxSpace<T>) -> ArrayD<T> {
    Zip::from(b.low())
        .and(b.high())
        .and(b.bounded_below())
        .and(b.bounded_above())
        .map_collect(|&l, &h, &bl, &bh| {
            if bl && l.to_f64() > 0.0 {
                l
            } else if bh && h.to_f64() < 0.0 {
                h
            } else {
                T::zero()
            }
        })
}

impl<T: ArrayElement> BatchSpace for BoxSpace<T> {
    type Batched = BoxSpace<T>;

    fn batch_space(&self, n: usize) -> Result<BoxSpace<T>> {
        check_n(n)?;
        let (low, high) = self.bounds_f64();
        Ok(BoxSpace::new(tile(&low, n), tile(&high, n))?)
    }

    fn create_empty_batch(&self, n: usize) -> ArrayD<T> {
        ArrayD::from_elem(IxDyn(&batched_shape(n, self.low().shape())), T::zero())
    }

    fn write_item(&self, batch: &mut ArrayD<T>, i: usize, x: &ArrayD<T>) -> Result<()> {
        write_typed(batch, i, x)
    }

    fn read_item(&self, batch: &ArrayD<T>, i: usize) -> Result<ArrayD<T>> {
        read_typed(batch, i, self.low().shape())
    }

    fn read_item_into(&self, batch: &ArrayD<T>, i: usize, out: &mut ArrayD<T>) -> Result<()> {
        read_typed_into(batch, i, self.low().shape(), out)
    }

    fn check_batch(&self, batch: &ArrayD<T>, n: usize) -> Result<()> {
        check_typed(batch, n, self.low().shape())
    }

    fn zero_element(&self) -> ArrayD<T> {
        box_zero(self)
    }

    fn row_leaves(&self, batch: &mut ArrayD<T>, i: usize, out: &mut RowLeaves) -> bool {
        batch.shape().get(1..) == Some(self.low().shape())
            && RowLeaf::of_typed_batch_row(batch, i).is_some_and(|l| out.push(l).is_ok())
    }
}

impl BatchSpace for Discrete {
    type Batched = MultiDiscrete;

    fn batch_space(&self, n: usize) -> Result<MultiDiscrete> {
        check_n(n)?;
        let full = |v: i64| ArrayD::from_elem(IxDyn(&[n]), v);
        Ok(MultiDiscrete::with_start(
            full(self.n()),
            full(self.start()),
        )?)
    }

    fn create_empty_batch(&self, n: usize) -> ArrayD<i64> {
        ArrayD::zeros(IxDyn(&[n]))
    }

    fn write_item(&self, batch: &mut ArrayD<i64>, i: usize, x: &i64) -> Result<()> {
        write_typed(batch, i, &ArrayD::from_elem(IxDyn(&[]), *x))
    }

    fn check_batch(&self, batch: &ArrayD<i64>, n: usize) -> Result<()> {
        check_typed(batch, n, &[])
    }

    fn read_item(&self, batch: &ArrayD<i64>, i: usize) -> Result<i64> {
        Ok(read_typed(batch, i, &[])?
            .iter()
            .next()
            .copied()
            .unwrap_or_default())
    }

    fn zero_element(&self) -> i64 {
        self.start()
    }
}

impl BatchSpace for MultiDiscrete {
    type Batched = BoxSpace<i64>;

    fn batch_space(&self, n: usize) -> Result<BoxSpace<i64>> {
        check_n(n)?;
        let low = self.start().mapv(|s| s as f64);
        let high = Zip::from(self.start())
            .and(self.nvec())
            .map_collect(|&s, &v| (s + v - 1) as f64);
        Ok(BoxSpace::new(tile(&low, n), tile(&high, n))?)
    }

    fn create_empty_batch(&self, n: usize) -> ArrayD<i64> {
        ArrayD::zeros(IxDyn(&batched_shape(n, self.nvec().shape())))
    }

    fn write_item(&self, batch: &mut ArrayD<i64>, i: usize, x: &ArrayD<i64>) -> Result<()> {
        write_typed(batch, i, x)
    }

    fn read_item(&self, batch: &ArrayD<i64>, i: usize) -> Result<ArrayD<i64>> {
        read_typed(batch, i, self.nvec().shape())
    }

    fn read_item_into(&self, batch: &ArrayD<i64>, i: usize, out: &mut ArrayD<i64>) -> Result<()> {
        read_typed_into(batch, i, self.nvec().shape(), out)
    }

    fn check_batch(&self, batch: &ArrayD<i64>, n: usize) -> Result<()> {
        check_typed(batch, n, self.nvec().shape())
    }

    fn zero_element(&self) -> ArrayD<i64> {
        self.start().clone()
    }
}

impl BatchSpace for MultiBinary {
    type Batched = BoxSpace<i8>;

    fn batch_space(&self, n: usize) -> Result<BoxSpace<i8>> {
        check_n(n)?;
        Ok(BoxSpace::uniform(
            0.0,
            1.0,
            &batched_shape(n, self.shape().unwrap_or(&[])),
        )?)
    }

    fn create_empty_batch(&self, n: usize) -> ArrayD<i8> {
        ArrayD::zeros(IxDyn(&batched_shape(n, self.shape().unwrap_or(&[]))))
    }

    fn write_item(&self, batch: &mut ArrayD<i8>, i: usize, x: &ArrayD<i8>) -> Result<()> {
        write_typed(batch, i, x)
    }

    fn read_item(&self, batch: &ArrayD<i8>, i: usize) -> Result<ArrayD<i8>> {
        read_typed(batch, i, self.shape().unwrap_or(&[]))
    }

    fn read_item_into(&self, batch: &ArrayD<i8>, i: usize, out: &mut ArrayD<i8>) -> Result<()> {
        read_typed_into(batch, i, self.shape().unwrap_or(&[]), out)
    }

    fn check_batch(&self, batch: &ArrayD<i8>, n: usize) -> Result<()> {
        check_typed(batch, n, self.shape().unwrap_or(&[]))
    }

    fn zero_element(&self) -> ArrayD<i8> {
        ArrayD::zeros(IxDyn(self.shape().unwrap_or(&[])))
    }
}

impl BatchSpace for AnyBox {
    type Batched = AnyBox;

    fn batch_space(&self, n: usize) -> Result<AnyBox> {
        each_box!(self, b => Ok(b.batch_space(n)?.into()))
    }

    fn create_empty_batch(&self, n: usize) -> ArrayValue {
        each_box!(self, b => ArrayValue::from(b.create_empty_batch(n)))
    }

    fn write_item(&self, batch: &mut ArrayValue, i: usize, x: &ArrayValue) -> Result<()> {
        write_array_value(batch, i, x)
    }

    fn read_item(&self, batch: &ArrayValue, i: usize) -> Result<ArrayValue> {
        read_array_value(batch, i, self.shape().unwrap_or(&[]))
    }

    fn read_item_into(&self, batch: &ArrayValue, i: usize, out: &mut ArrayValue) -> Result<()> {
        read_array_value_into(batch, i, self.shape().unwrap_or(&[]), out)
    }

    fn check_batch(&self, batch: &ArrayValue, n: usize) -> Result<()> {
        check_array_value(batch, n, self.shape().unwrap_or(&[]))
    }

    fn zero_element(&self) -> ArrayValue {
        each_box!(self, b => ArrayValue::from(box_zero(b)))
    }
}

fn wrong_kind(expected: &'static str, got: &Value) -> Error {
    SpaceError::WrongKind {
        expected,
        got: got.kind(),
    }
    .into()
}

fn dict_entry<'a>(d: &'a DictValue, key: &str) -> Result<&'a Value> {
    d.get(key).ok_or_else(|| Error::UnknownKey {
        key: key.to_owned(),
        available: d.keys().cloned().collect(),
    })
}

impl BatchSpace for AnySpace {
    type Batched = AnySpace;

    fn batch_space(&self, n: usize) -> Result<AnySpace> {
        each_space!(self, s => Ok(s.batch_space(n)?.to_any()))
    }

    fn create_empty_batch(&self, n: usize) -> Value {
        each_space!(self, s => s.create_empty_batch(n).into())
    }

    fn write_item(&self, batch: &mut Value, i: usize, x: &Value) -> Result<()> {
        match (self, batch) {
            (AnySpace::Discrete(d), Value::Array(b)) => {
                let v = d.from_value(x)?;
                write_array_value(b, i, &ArrayValue::I64(ArrayD::from_elem(IxDyn(&[]), v)))
            }
            (
                AnySpace::Box(_) | AnySpace::MultiDiscrete(_) | AnySpace::MultiBinary(_),
                Value::Array(b),
            ) => write_array_value(b, i, x.as_array().ok_or_else(|| wrong_kind("array", x))?),
            (AnySpace::Dict(d), Value::Dict(b)) => match x {
                Value::Dict(xd) => d.write_item(b, i, xd),
                other => Err(wrong_kind("dict", other)),
            },
            (AnySpace::Tuple(t), Value::Tuple(b)) => match x {
                Value::Tuple(xt) => t.write_item(b, i, xt),
                other => Err(wrong_kind("tuple", other)),
            },
            (_, b) => Err(wrong_kind("a batch of this space", b)),
        }
    }

    fn row_leaves(&self, batch: &mut Value, i: usize, out: &mut RowLeaves) -> bool {
        match (self, batch) {
            (AnySpace::Dict(d), Value::Dict(b)) => d.row_leaves(b, i, out),
            (space, Value::Array(b)) => array_row_leaf(space, b, i, out),
            _ => false,
        }
    }

    fn read_item(&self, batch: &Value, i: usize) -> Result<Value> {
        match (self, batch) {
            (AnySpace::Discrete(_), Value::Array(b)) => {
                let item = read_array_value(b, i, &[])?;
                Ok(Value::Discrete(
                    item.to_f64_vec().first().copied().unwrap_or_default() as i64,
                ))
            }
            (
                AnySpace::Box(_) | AnySpace::MultiDiscrete(_) | AnySpace::MultiBinary(_),
                Value::Array(b),
            ) => Ok(Value::Array(read_array_value(
                b,
                i,
                self.shape().unwrap_or(&[]),
            )?)),
            (AnySpace::Dict(d), Value::Dict(b)) => Ok(Value::Dict(d.read_item(b, i)?)),
            (AnySpace::Tuple(t), Value::Tuple(b)) => Ok(Value::Tuple(t.read_item(b, i)?)),
            (_, b) => Err(wrong_kind("a batch of this space", b)),
        }
    }

    fn read_item_into(&self, batch: &Value, i: usize, out: &mut Value) -> Result<()> {
        match (self, batch, out) {
            (
                AnySpace::Box(_) | AnySpace::MultiDiscrete(_) | AnySpace::MultiBinary(_),
                Value::Array(b),
                Value::Array(o),
            ) => read_array_value_into(b, i, self.shape().unwrap_or(&[]), o),
            (_, _, out) => {
                *out = self.read_item(batch, i)?;
                Ok(())
            }
        }
    }

    fn check_batch(&self, batch: &Value, n: usize) -> Result<()> {
        match (self, batch) {
            (
                AnySpace::Box(_) | AnySpace::MultiDiscrete(_) | AnySpace::MultiBinary(_),
                Value::Array(b),
            ) => check_array_value(b, n, self.shape().unwrap_or(&[])),
            (AnySpace::Discrete(_), Value::Array(b)) => check_array_value(b, n, &[]),
            _ => check_any_batch(self, batch, n),
        }
    }

    fn zero_element(&self) -> Value {
        each_space!(self, s => s.to_value(&s.zero_element()))
    }
}

impl BatchSpace for DictSpace {
    type Batched = DictSpace;

    fn batch_space(&self, n: usize) -> Result<DictSpace> {
        check_n(n)?;
        let parts = self
            .iter()
            .map(|(k, s)| Ok((k.to_owned(), s.batch_space(n)?)))
            .collect::<Result<Vec<_>>>()?;
        Ok(DictSpace::new(parts)?)
    }

    fn create_empty_batch(&self, n: usize) -> DictValue {
        self.iter()
            .map(|(k, s)| (k.to_owned(), s.create_empty_batch(n)))
            .collect()
    }

    fn write_item(&self, batch: &mut DictValue, i: usize, x: &DictValue) -> Result<()> {
        for (k, s) in self.iter() {
            let item = dict_entry(x, k)?;
            let available: Vec<String> = batch.keys().cloned().collect();
            let slot = batch.get_mut(k).ok_or_else(|| Error::UnknownKey {
                key: k.to_owned(),
                available,
            })?;
            s.write_item(slot, i, item)?;
        }
        Ok(())
    }

    fn row_leaves(&self, batch: &mut DictValue, i: usize, out: &mut RowLeaves) -> bool {
        batch.len() == self.len()
            && self.iter().all(|(k, s)| match batch.get_mut(k) {
                Some(Value::Array(b)) => array_row_leaf(s, b, i, out),
                _ => false,
            })
    }

    fn read_item(&self, batch: &DictValue, i: usize) -> Result<DictValue> {
        self.iter()
            .map(|(k, s)| Ok((k.to_owned(), s.read_item(dict_entry(batch, k)?, i)?)))
            .collect()
    }

    fn zero_element(&self) -> DictValue {
        self.iter()
            .map(|(k, s)| (k.to_owned(), s.zero_element()))
            .collect()
    }
}

/// Row `i` of the batch `b` of an array space (Box, MultiBinary, MultiDiscrete) as one
/// leaf appended to `out`.
fn array_row_leaf(space: &AnySpace, b: &mut ArrayValue, i: usize, out: &mut RowLeaves) -> bool {
    let item_shape = match space {
        AnySpace::Box(_) | AnySpace::MultiBinary(_) | AnySpace::MultiDiscrete(_) => space.shape(),
        _ => return false,
    };
    item_shape.is_some()
        && b.shape().get(1..) == item_shape
        && RowLeaf::of_batch_row(b, i).is_some_and(|l| out.push(l).is_ok())
}

fn tuple_len_error(expected: usize, got: usize) -> Error {
    SpaceError::InvalidArgument(format!("expected {expected} tuple items, got {got}")).into()
}

impl BatchSpace for TupleSpace {
    type Batched = TupleSpace;

    fn batch_space(&self, n: usize) -> Result<TupleSpace> {
        check_n(n)?;
        Ok(TupleSpace::new(
            self.spaces()
                .iter()
                .map(|s| s.batch_space(n))
                .collect::<Result<_>>()?,
        ))
    }

    fn create_empty_batch(&self, n: usize) -> Vec<Value> {
        self.spaces()
            .iter()
            .map(|s| s.create_empty_batch(n))
            .collect()
    }

    fn write_item(&self, batch: &mut Vec<Value>, i: usize, x: &Vec<Value>) -> Result<()> {
        if batch.len() != self.len() || x.len() != self.len() {
            return Err(tuple_len_error(self.len(), x.len().min(batch.len())));
        }
        for ((s, b), v) in self.spaces().iter().zip(batch.iter_mut()).zip(x) {
            s.write_item(b, i, v)?;
        }
        Ok(())
    }

    fn read_item(&self, batch: &Vec<Value>, i: usize) -> Result<Vec<Value>> {
        if batch.len() != self.len() {
            return Err(tuple_len_error(self.len(), batch.len()));
        }
        self.spaces()
            .iter()
            .zip(batch)
            .map(|(s, b)| s.read_item(b, i))
            .collect()
    }

    fn zero_element(&self) -> Vec<Value> {
        self.spaces().iter().map(BatchSpace::zero_element).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::DType;
    use ndarray::{arr1, arr2};

    #[test]
    fn box_batches_tile_bounds_and_write_rows() {
        let b = BoxSpace::<f32>::new(arr1(&[-1.0, 0.0]).into_dyn(), arr1(&[1.0, 2.0]).into_dyn())
            .unwrap();
        let bb = b.batch_space(3).unwrap();
        assert_eq!(bb.shape(), Some(&[3usize, 2][..]));
        assert_eq!(bb.high()[[2, 1]], 2.0);
        let mut batch = b.create_empty_batch(3);
        b.write_item(&mut batch, 1, &arr1(&[0.5f32, 1.5]).into_dyn())
            .unwrap();
        assert_eq!(
            batch,
            arr2(&[[0.0f32, 0.0], [0.5, 1.5], [0.0, 0.0]]).into_dyn()
        );
        assert_eq!(
            b.read_item(&batch, 1).unwrap(),
            arr1(&[0.5f32, 1.5]).into_dyn()
        );
        assert!(
            b.write_item(&mut batch, 3, &arr1(&[0.0f32, 0.0]).into_dyn())
                .is_err()
        );
        assert!(
            b.write_item(&mut batch, 0, &arr1(&[0.0f32]).into_dyn())
                .is_err()
        );
    }

    #[test]
    fn batch_space_table() {
        let d = Discrete::with_start(4, 2).unwrap().batch_space(3).unwrap();
        assert_eq!(d.nvec(), &arr1(&[4i64, 4, 4]).into_dyn());
        assert_eq!(d.start(), &arr1(&[2i64, 2, 2]).into_dyn());
        let md =
            MultiDiscrete::with_start(arr1(&[2, 3]).into_dyn(), arr1(&[0, 1]).into_dyn()).unwrap();
        let mb = md.batch_space(2).unwrap();
        assert_eq!(mb.high(), &arr2(&[[1i64, 3], [1, 3]]).into_dyn());
        assert_eq!(mb.low(), &arr2(&[[0i64, 1], [0, 1]]).into_dyn());
        let bin = MultiBinary::new(&[2]).unwrap().batch_space(2).unwrap();
        assert_eq!(bin.dtype(), DType::I8);
        let dict = DictSpace::new([("a", AnySpace::from(Discrete::new(2).unwrap()))]).unwrap();
        let bd = dict.batch_space(2).unwrap();
        assert_eq!(bd.get("a").unwrap().kind(), "MultiDiscrete");
    }

    #[test]
    fn dynamic_items_round_trip() {
        let space = AnySpace::Dict(
            DictSpace::new([
                ("d", AnySpace::from(Discrete::new(3).unwrap())),
                (
                    "b",
                    AnySpace::from(BoxSpace::<f64>::uniform(-1.0, 1.0, &[2]).unwrap()),
                ),
            ])
            .unwrap(),
        );
        let mut batch = space.create_empty_batch(2);
        let item = Value::Dict(
            [
                ("d".to_owned(), Value::Discrete(2)),
                ("b".to_owned(), Value::from(arr1(&[0.25, -0.5]).into_dyn())),
            ]
            .into_iter()
            .collect(),
        );
        space.write_item(&mut batch, 1, &item).unwrap();
        assert_eq!(space.read_item(&batch, 1).unwrap(), item);
        assert!(space.batch_space(2).unwrap().contains(&batch));
    }

    #[test]
    fn zero_elements_lie_in_the_space() {
        let b = BoxSpace::<f64>::new(
            arr1(&[1.0, -3.0, -1.0]).into_dyn(),
            arr1(&[2.0, -2.0, 1.0]).into_dyn(),
        )
        .unwrap();
        assert_eq!(b.zero_element(), arr1(&[1.0, -2.0, 0.0]).into_dyn());
        assert_eq!(Discrete::with_start(3, 5).unwrap().zero_element(), 5);
    }
}
