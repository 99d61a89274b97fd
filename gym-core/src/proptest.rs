//! Proptest strategies for every space and its elements (feature `proptest-support`),
//! for this workspace's tests and for users testing their own environments.
//!
//! Strategies are functions, as in nalgebra's `proptest` module: bounds are drawn from
//! ranges that keep arithmetic finite, with infinite bounds mixed in where a space allows
//! them. Elements are drawn with [`sample_of`], which samples the space from a proptest-chosen
//! seed, so every element lies in its space by construction of the space's own sampler.

use crate::dtype::DType;
use crate::rng::rng_from_seed;
use crate::space::Space;
use crate::spaces::{
    AnyBox, AnySpace, DictSpace, Discrete, MultiBinary, MultiDiscrete, TupleSpace,
};
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
/// floating dtypes; integer bounds within `-100..150`, `0..200` for `uint8`).
pub fn box_space(dtype: DType) -> impl Strategy<Value = AnyBox> {
    shape(3, 4).prop_flat_map(move |shape| {
        let n: usize = shape.iter().product();
        proptest::collection::vec(bound_pair(dtype.is_float()), n).prop_map(move |pairs| {
            let (mut low, mut high): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
            if !dtype.is_float() {
                let (lo, hi) = if dtype == DType::U8 {
                    (0.0, 200.0)
                } else {
                    (-100.0, 150.0)
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

/// Elements of `space`, drawn by the space's own sampler from a proptest-chosen seed.
pub fn sample_of<S: Space>(space: S) -> impl Strategy<Value = S::Element> {
    seed().prop_map(move |s| space.sample(&mut rng_from_seed(s)))
}

/// A space together with one of its elements.
pub fn space_and_element(depth: u32) -> impl Strategy<Value = (AnySpace, crate::value::Value)> {
    (any_space(depth), seed()).prop_map(|(space, s)| {
        let x = space.sample(&mut rng_from_seed(s));
        (space, x)
    })
}

/// Sequences of `len` actions from `space` (each drawn from its own seed).
pub fn action_sequence<S: Space>(
    space: S,
    len: std::ops::RangeInclusive<usize>,
) -> impl Strategy<Value = Vec<S::Element>> {
    proptest::collection::vec(sample_of(space), len)
}
