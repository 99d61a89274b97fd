//! Property tests of every space kind: samples lie in their space, sampling is
//! reproducible, flatten/unflatten round-trips, and `contains` rejects what it must.

use gym_core::proptest::{
    any_space, box_space, discrete, element_of, multi_binary, multi_discrete, seed,
    space_and_element,
};
use gym_core::{AnyBox, AnySpace, ArrayValue, DType, Flatten, Space, Value, rng_from_seed};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn samples_lie_in_their_space(space in any_space(3), s in seed()) {
        let mut rng = rng_from_seed(s);
        for _ in 0..4 {
            let x = space.sample(&mut rng);
            prop_assert!(space.contains(&x), "{space} does not contain its sample {x:?}");
        }
    }

    #[test]
    fn value_strategies_stay_in_their_space((space, x) in space_and_element(3)) {
        prop_assert!(space.contains(&x), "{space} does not contain the drawn value {x:?}");
    }

    #[test]
    fn same_seed_same_samples(space in any_space(3), s in seed()) {
        let (mut a, mut b) = (rng_from_seed(s), rng_from_seed(s));
        for _ in 0..3 {
            prop_assert_eq!(space.sample(&mut a), space.sample(&mut b));
        }
    }

    #[test]
    fn flatten_round_trips(space in any_space(3), s in seed()) {
        let x = space.sample(&mut rng_from_seed(s));
        let flat = space.flatten(&x).unwrap();
        prop_assert_eq!(flat.shape(), &[space.flatdim()][..]);
        prop_assert_eq!(flat.dtype(), space.flat_dtype());
        prop_assert!(space.flatten_space().contains(&flat), "flat sample outside flatten_space");
        prop_assert_eq!(space.flatten_space().dtype(), space.flat_dtype());
        let back = space.unflatten(&flat).unwrap();
        prop_assert!(values_equal(&back, &x), "{back:?} != {x:?}");
    }

    #[test]
    fn box_rejects_wrong_shape_nan_and_out_of_bounds(b in box_space(DType::F32), s in seed()) {
        let x = b.sample(&mut rng_from_seed(s));
        let ArrayValue::F32(arr) = &x else { unreachable!() };
        // A wrong shape.
        let longer = ArrayValue::F32(ndarray::ArrayD::zeros(ndarray::IxDyn(&[arr.len() + 1])));
        prop_assert!(!b.contains(&longer));
        // NaN anywhere.
        let mut nan = arr.clone();
        if let Some(v) = nan.iter_mut().next() {
            *v = f32::NAN;
        }
        prop_assert!(!b.contains(&ArrayValue::F32(nan)));
        // A dtype that does not cast safely (float64 into float32).
        prop_assert!(!b.contains(&x.cast(DType::F64)));
        // Out of bounds where the box is bounded.
        let (low, high) = b.bounds_f64();
        if let Some(i) = high.iter().position(|h| h.is_finite()) {
            let mut over = arr.clone();
            let h = high.iter().nth(i).copied().unwrap();
            *over.iter_mut().nth(i).unwrap() = (h as f32 + 1.0).max(h as f32 * 1.01 + 1.0);
            prop_assert!(!b.contains(&ArrayValue::F32(over)));
        }
        if let Some(i) = low.iter().position(|l| l.is_finite()) {
            let mut under = arr.clone();
            let l = low.iter().nth(i).copied().unwrap();
            *under.iter_mut().nth(i).unwrap() = (l as f32 - 1.0).min(l as f32 * 1.01 - 1.0);
            prop_assert!(!b.contains(&ArrayValue::F32(under)));
        }
    }

    #[test]
    fn float32_values_fit_float64_boxes(b in box_space(DType::F64), s in seed()) {
        let x = b.sample(&mut rng_from_seed(s));
        // Gymnasium: np.can_cast(float32, float64) holds, so a float32 array may be in a
        // float64 Box when its values are in bounds.
        let as_f32 = x.cast(DType::F32);
        let back = as_f32.cast(DType::F64);
        prop_assert_eq!(b.contains(&as_f32), b.contains(&back));
    }

    #[test]
    fn discrete_like_spaces_reject_outsiders(d in discrete(), md in multi_discrete(), mb in multi_binary()) {
        prop_assert!(!d.contains(&(d.start() - 1)));
        prop_assert!(!d.contains(&(d.start() + d.n())));
        let mut x = md.sample(&mut rng_from_seed(1));
        if let Some(v) = x.iter_mut().next() {
            *v = i64::MAX;
        }
        prop_assert!(!md.contains(&x));
        let mut y = mb.sample(&mut rng_from_seed(2));
        if let Some(v) = y.iter_mut().next() {
            *v = 2;
        }
        prop_assert!(!mb.contains(&y));
        // Floats are not integers: a float array is not a MultiDiscrete element.
        let floats = Value::Array(ArrayValue::F64(md.sample(&mut rng_from_seed(3)).mapv(|v| v as f64)));
        prop_assert!(!AnySpace::MultiDiscrete(md.clone()).contains(&floats));
    }

    #[test]
    fn any_box_contains_agrees_with_typed_box(b in box_space(DType::I32), s in seed()) {
        let x = b.sample(&mut rng_from_seed(s));
        let AnyBox::I32(typed) = &b else { unreachable!() };
        let ArrayValue::I32(arr) = &x else { unreachable!() };
        prop_assert!(typed.contains(arr));
        prop_assert!(b.contains(&x));
        // int32 casts safely to int64 and float64, but not to float32.
        prop_assert!(!b.cast(DType::F32).unwrap().contains(&x));
    }
}

/// Exact equality, except that unflatten returns arrays in the flat dtype's promotion of
/// the original, so compare values after casting back.
fn values_equal(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Array(x), Value::Array(y)) => x.shape() == y.shape() && x.cast(y.dtype()) == *y,
        (Value::Discrete(x), Value::Discrete(y)) => x == y,
        (Value::Dict(x), Value::Dict(y)) => {
            x.len() == y.len()
                && x.iter()
                    .all(|(k, v)| y.get(k).is_some_and(|w| values_equal(v, w)))
        }
        (Value::Tuple(x), Value::Tuple(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(v, w)| values_equal(v, w))
        }
        _ => false,
    }
}

#[test]
fn dict_flatten_follows_key_order_and_promotes() {
    use gym_core::{BoxSpace, DictSpace, Discrete};
    let space = DictSpace::new([
        ("b", AnySpace::from(Discrete::new(3).unwrap())),
        (
            "a",
            AnySpace::from(BoxSpace::<f32>::uniform(-1.0, 1.0, &[2]).unwrap()),
        ),
    ])
    .unwrap();
    let x: gym_core::DictValue = [
        (
            "a".to_owned(),
            Value::from(ndarray::arr1(&[0.5f32, -0.25]).into_dyn()),
        ),
        ("b".to_owned(), Value::Discrete(1)),
    ]
    .into_iter()
    .collect();
    let flat = space.flatten(&x).unwrap();
    // int64 one-hot + float32 promotes to float64, in the space's key order (b, a).
    assert_eq!(flat.dtype(), DType::F64);
    assert_eq!(flat.to_f64_vec(), vec![0.0, 1.0, 0.0, 0.5, -0.25]);
    let sorted = DictSpace::sorted(space.iter().map(|(k, s)| (k.to_owned(), s.clone()))).unwrap();
    assert_eq!(
        sorted.flatten(&x).unwrap().to_f64_vec(),
        vec![0.5, -0.25, 0.0, 1.0, 0.0]
    );
    assert!(
        space.contains(&x),
        "key order of the value does not matter for contains"
    );
}

#[test]
fn flatten_space_of_discrete_is_an_int64_box() {
    let d = AnySpace::from(gym_core::Discrete::new(4).unwrap());
    let fs = d.flatten_space();
    assert_eq!(fs.dtype(), DType::I64);
    assert_eq!(fs.shape(), Some(&[4usize][..]));
    assert_eq!(fs.to_string(), "Box(0, 1, [4], int64)");
}

/// A failing property over Box elements shrinks value by value (every entry not needed for
/// the failure goes to its lower bound), not to another random sample.
#[test]
fn element_strategies_shrink_values() {
    use proptest::test_runner::{Config, TestError, TestRunner};
    let space = gym_core::BoxSpace::<f64>::uniform(0.0, 100.0, &[4]).unwrap();
    let mut runner = TestRunner::new(Config {
        cases: 256,
        failure_persistence: None,
        ..Config::default()
    });
    let result = runner.run(&element_of(space), |x| {
        prop_assert!(x.iter().all(|v| *v < 50.0));
        Ok(())
    });
    let Err(TestError::Fail(_, minimal)) = result else {
        panic!("the property must fail: {result:?}");
    };
    let above: Vec<f64> = minimal.iter().copied().filter(|v| *v >= 50.0).collect();
    let below: Vec<f64> = minimal.iter().copied().filter(|v| *v < 50.0).collect();
    assert_eq!(above.len(), 1, "one entry left failing: {minimal:?}");
    assert!(
        below.iter().all(|v| *v == 0.0),
        "the others shrink to the bound: {minimal:?}"
    );

    let discrete = gym_core::Discrete::with_start(1000, 5).unwrap();
    let result = runner.run(&element_of(discrete), |x| {
        prop_assert!(x < 300);
        Ok(())
    });
    let Err(TestError::Fail(_, minimal)) = result else {
        panic!("the property must fail: {result:?}");
    };
    assert_eq!(
        minimal, 300,
        "a discrete index shrinks to the smallest failing one"
    );
}
