//! Proptest strategies for every space and its elements (feature `proptest-support`),
//! for this workspace's tests and for users testing their own environments.
//!
//! Strategies are functions, as in nalgebra's `proptest` module: bounds are drawn from
//! ranges that keep arithmetic finite, with infinite bounds mixed in where a space allows
//! them. Elements ([`element_of`], [`value_of`]) are drawn value by value — every array
//! entry, discrete index and Dict / Tuple member by its own strategy within its bounds — so
//! a failing case shrinks its values (toward each entry's lower bound or zero), not a seed.

use crate::dtype::DType;
use crate::rng::rng_from_seed;
use crate::space::{DynSpace, Space};
use crate::spaces::{
    AnyBox, AnySpace, DictSpace, Discrete, MultiBinary, MultiDiscrete, TupleSpace,
};
use crate::value::{ArrayValue, Value};
use ndarray::{ArrayD, IxDyn};
use proptest::prelude::*;

/// Shapes of rank 1 to `max_rank`, each dimension 1 to `max_dim`.
pub fn shape(max_rank: usize, max_dim: usize) -> impl Strategy<Value = Vec<usize>> {
    proptest::collection::vec(1..=max_dim.max(1), 1..=max_rank.max(1))
}

/// One bound pair: finite, half-open or unbounded, as `f64`.
fn bound_pair(allow_inf: bool) -> impl Strategy<Value = (f64, f64)> {
    let finite = (-100.0f64..100.0, 0.0f64..50.0).prop_map(|(l, w)| (l, l + w));
    if allow_inf {
        prop_oneof![
            4 => finite,
            1 => (-100.0f64..100.0).prop_map(|l| (l, f64::INFINITY)),
            1 => (-100.0f64..100.0).prop_map(|h| (f64::NEG_INFINITY, h)),
            1 => Just((f64::NEG_INFINITY, f64::INFINITY)),
        ]
        .boxed()
    } else {
        finite.boxed()
    }
}

/// A Box of `dtype` with a random shape and per-element bounds (infinite bounds for
/// floating dtypes; integer bounds within `-100..150`, `0..200` for `uint8`, `0..=1` for
/// `bool`).
pub fn box_space(dtype: DType) -> impl Strategy<Value = AnyBox> {
    shape(3, 4).prop_flat_map(move |shape| {
        let n: usize = shape.iter().product();
        proptest::collection::vec(bound_pair(dtype.is_float()), n).prop_map(move |pairs| {
            let (mut low, mut high): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
            if !dtype.is_float() {
                let (lo, hi) = match dtype {
                    DType::U8 => (0.0, 200.0),
                    DType::Bool => (0.0, 1.0),
                    _ => (-100.0, 150.0),
                };
                for (l, h) in low.iter_mut().zip(high.iter_mut()) {
                    *l = l.clamp(lo, hi).floor();
                    *h = h.clamp(*l, hi).floor();
                }
                if dtype == DType::I8 {
                    low.iter_mut().for_each(|l| *l = l.min(100.0));
                    high.iter_mut().for_each(|h| *h = h.min(120.0));
                }
            }
            let arr = |v: Vec<f64>| ArrayD::from_shape_vec(IxDyn(&shape), v).expect("length");
            AnyBox::new(dtype, arr(low), arr(high)).expect("strategy builds valid bounds")
        })
    })
}

/// A Box of any supported dtype.
pub fn any_box() -> impl Strategy<Value = AnyBox> {
    proptest::sample::select(DType::ALL.to_vec()).prop_flat_map(box_space)
}

/// A Discrete with `n` in `1..=20` and `start` in `-10..=10`.
pub fn discrete() -> impl Strategy<Value = Discrete> {
    (1i64..=20, -10i64..=10).prop_map(|(n, s)| Discrete::with_start(n, s).expect("valid"))
}

/// A MultiDiscrete of rank 1 or 2 with `nvec` entries in `1..=6`.
pub fn multi_discrete() -> impl Strategy<Value = MultiDiscrete> {
    shape(2, 4).prop_flat_map(|shape| {
        let n: usize = shape.iter().product();
        (
            proptest::collection::vec(1i64..=6, n),
            proptest::collection::vec(-3i64..=3, n),
        )
            .prop_map(move |(nv, st)| {
                let arr = |v: Vec<i64>| ArrayD::from_shape_vec(IxDyn(&shape), v).expect("length");
                MultiDiscrete::with_start(arr(nv), arr(st)).expect("valid")
            })
    })
}

/// A MultiBinary of rank 1 or 2.
pub fn multi_binary() -> impl Strategy<Value = MultiBinary> {
    shape(2, 5).prop_map(|s| MultiBinary::new(&s).expect("valid"))
}

/// A non-composite space of any kind.
pub fn leaf_space() -> impl Strategy<Value = AnySpace> {
    prop_oneof![
        3 => any_box().prop_map(AnySpace::Box),
        1 => discrete().prop_map(AnySpace::Discrete),
        1 => multi_discrete().prop_map(AnySpace::MultiDiscrete),
        1 => multi_binary().prop_map(AnySpace::MultiBinary),
    ]
}

/// Any space, with Dict and Tuple nested up to `depth` levels (each non-empty, at most 4
/// children, Dict keys in random order).
pub fn any_space(depth: u32) -> impl Strategy<Value = AnySpace> {
    leaf_space().prop_recursive(depth, 24, 4, |inner| {
        prop_oneof![
            proptest::collection::vec(inner.clone(), 1..=4)
                .prop_map(|v| AnySpace::Tuple(TupleSpace::new(v))),
            proptest::collection::btree_map("[a-z][a-z0-9_-]{0,8}", inner, 1..=4).prop_map(|m| {
                AnySpace::Dict(DictSpace::new(m.into_iter().rev()).expect("unique keys"))
            }),
        ]
    })
}

/// Seeds for samplers and environments.
pub fn seed() -> impl Strategy<Value = u64> {
    any::<u64>()
}

/// One floating entry within `[low, high]` (either may be infinite): the finite side's
/// neighbourhood when half-bounded, mostly moderate magnitudes when unbounded.
fn float_entry(low: f64, high: f64) -> BoxedStrategy<f64> {
    match (low.is_finite(), high.is_finite()) {
        (true, true) if low == high => Just(low).boxed(),
        (true, true) => (low..=high).boxed(),
        (true, false) => prop_oneof![4 => low..low + 100.0, 1 => low..low + 1e6].boxed(),
        (false, true) => prop_oneof![4 => high - 100.0..=high, 1 => high - 1e6..=high].boxed(),
        (false, false) => prop_oneof![4 => -100.0..100.0f64, 1 => -1e6..1e6f64].boxed(),
    }
}

/// The array of `dtype` and `shape` from row-major entries given as `i64`.
fn int_array(dtype: DType, shape: &[usize], entries: Vec<i64>) -> ArrayValue {
    fn typed<T: crate::value::ArrayElement>(shape: &[usize], entries: Vec<i64>) -> ArrayValue {
        let values = entries.into_iter().map(T::from_i64).collect();
        T::wrap(ArrayD::from_shape_vec(IxDyn(shape), values).expect("one entry per element"))
    }
    match dtype {
        DType::I8 => typed::<i8>(shape, entries),
        DType::I16 => typed::<i16>(shape, entries),
        DType::I32 => typed::<i32>(shape, entries),
        DType::U8 => typed::<u8>(shape, entries),
        DType::Bool => typed::<bool>(shape, entries),
        _ => typed::<i64>(shape, entries),
    }
}

/// Elements of a Box, entry by entry within each entry's bounds.
fn box_value(b: &AnyBox) -> BoxedStrategy<ArrayValue> {
    let (low, high) = b.bounds_f64();
    let shape = low.shape().to_vec();
    let dtype = b.dtype();
    if dtype.is_float() {
        let entries: Vec<_> = low
            .iter()
            .zip(high.iter())
            .map(|(l, h)| float_entry(*l, *h))
            .collect();
        entries
            .prop_map(move |v| {
                let a = ArrayD::from_shape_vec(IxDyn(&shape), v).expect("one entry per element");
                if dtype == DType::F32 {
                    ArrayValue::F32(a.mapv(|x| x as f32))
                } else {
                    ArrayValue::F64(a)
                }
            })
            .boxed()
    } else {
        // An unbounded side of an integer Box is the dtype's range.
        let (min, max) = match dtype {
            DType::I8 => (i8::MIN.into(), i8::MAX.into()),
            DType::I16 => (i16::MIN.into(), i16::MAX.into()),
            DType::I32 => (i32::MIN.into(), i32::MAX.into()),
            DType::U8 => (0, u8::MAX.into()),
            DType::Bool => (0, 1),
            _ => (i64::MIN, i64::MAX),
        };
        let entries: Vec<_> = low
            .iter()
            .zip(high.iter())
            .map(|(l, h)| (*l as i64).max(min)..=(*h as i64).min(max))
            .collect();
        entries
            .prop_map(move |v| int_array(dtype, &shape, v))
            .boxed()
    }
}

/// Elements of `space` as dynamic [`Value`]s, value by value, so they shrink: Box entries
/// within their bounds, Discrete indices from `start`, MultiDiscrete and MultiBinary entries
/// within their ranges, Dict and Tuple members each by their own strategy.
pub fn value_of(space: &AnySpace) -> BoxedStrategy<Value> {
    match space {
        AnySpace::Box(b) => box_value(b).prop_map(Value::Array).boxed(),
        AnySpace::Discrete(d) => (d.start()..d.start() + d.n())
            .prop_map(Value::Discrete)
            .boxed(),
        AnySpace::MultiDiscrete(m) => {
            let shape = m.nvec().shape().to_vec();
            let entries: Vec<_> = m
                .start()
                .iter()
                .zip(m.nvec().iter())
                .map(|(s, n)| *s..*s + *n)
                .collect();
            entries
                .prop_map(move |v| Value::Array(int_array(DType::I64, &shape, v)))
                .boxed()
        }
        AnySpace::MultiBinary(m) => {
            let shape = m.shape().map(<[usize]>::to_vec).unwrap_or_default();
            let n: usize = shape.iter().product();
            proptest::collection::vec(0i64..=1, n)
                .prop_map(move |v| Value::Array(int_array(DType::I8, &shape, v)))
                .boxed()
        }
        AnySpace::Tuple(t) => {
            let members: Vec<_> = t.spaces().iter().map(value_of).collect();
            members.prop_map(Value::Tuple).boxed()
        }
        AnySpace::Dict(d) => {
            let keys: Vec<String> = d.keys().map(str::to_owned).collect();
            let members: Vec<_> = d.iter().map(|(_, s)| value_of(s)).collect();
            members
                .prop_map(move |values| Value::Dict(keys.iter().cloned().zip(values).collect()))
                .boxed()
        }
    }
}

/// Elements of `space`, drawn value by value (see [`value_of`]), so that shrinking shrinks
/// the values themselves.
pub fn element_of<S: DynSpace>(space: S) -> impl Strategy<Value = S::Element> {
    value_of(&space.to_any()).prop_filter_map(
        "the space's from_value refuses a value of its own to_any structure",
        move |v| space.from_value(&v).ok(),
    )
}

/// Elements of `space`, drawn by the space's own sampler (Gymnasium's sampling law) from a
/// proptest-chosen seed. They shrink only by their seed; prefer [`element_of`] unless the
/// sampling law itself is under test.
pub fn sample_of<S: Space>(space: S) -> impl Strategy<Value = S::Element> {
    seed().prop_map(move |s| space.sample(&mut rng_from_seed(s)))
}

/// A space together with one of its elements (drawn value by value).
pub fn space_and_element(depth: u32) -> impl Strategy<Value = (AnySpace, Value)> {
    any_space(depth).prop_flat_map(|space| {
        let values = value_of(&space);
        (Just(space), values)
    })
}

/// Sequences of `len` actions from `space`, each drawn value by value.
pub fn action_sequence<S: DynSpace>(
    space: S,
    len: std::ops::RangeInclusive<usize>,
) -> impl Strategy<Value = Vec<S::Element>> {
    proptest::collection::vec(element_of(space), len)
}
