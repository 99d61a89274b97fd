//! [`RescaleAction`]: an affine map from a new Box action range to the environment's.

use crate::numeric::NumericSpace;
use gym_core::{ActionWrapper, Actions, DType, Env, Error, Result, Wrapper};
use ndarray::{ArrayD, IxDyn, Zip};

/// A bound for [`RescaleAction`]: one value for every component, or one per component.
#[derive(Debug, Clone, PartialEq)]
pub enum ActionBound {
    /// The same bound for every component.
    Scalar(f64),
    /// A bound per component (the action's shape).
    Array(ArrayD<f64>),
}

impl From<f64> for ActionBound {
    fn from(v: f64) -> Self {
        ActionBound::Scalar(v)
    }
}

impl From<ArrayD<f64>> for ActionBound {
    fn from(v: ArrayD<f64>) -> Self {
        ActionBound::Array(v)
    }
}

impl From<&[f64]> for ActionBound {
    fn from(v: &[f64]) -> Self {
        ActionBound::Array(ArrayD::from_shape_vec(IxDyn(&[v.len()]), v.to_vec()).expect("1-D"))
    }
}

impl ActionBound {
    fn to_array(&self, shape: &[usize], name: &str) -> Result<ArrayD<f64>> {
        match self {
            ActionBound::Scalar(v) => Ok(ArrayD::from_elem(IxDyn(shape), *v)),
            ActionBound::Array(a) if a.shape() == shape => Ok(a.clone()),
            ActionBound::Array(a) => Err(Error::invalid_argument(
                name,
                format!(
                    "expected shape {shape:?} (the action space's), got {:?}",
                    a.shape()
                ),
            )),
        }
    }
}

/// Gymnasium's `RescaleAction(env, min_action, max_action)` (`rescale_box`).
///
/// The action space becomes `Box(min_action, max_action)` with the inner Box's dtype; an
/// action `a` is mapped back with `(a - intercept) / gradient`, where per component
/// `gradient = (max - min) / (high - low)` when both new bounds are finite (else 1) and
/// `intercept = gradient * -low + min` (or `max - high` when only the upper bound is finite).
/// Gradient, intercept and the map are computed in the Box's dtype, as NumPy does, so the
/// results match Gymnasium bit for bit. Infinite components must stay infinite on the same
/// side; `min == max` for a component is invalid (Gymnasium's `InvalidBound`). Only
/// floating-point Boxes are accepted.
#[derive(Debug, Clone)]
pub struct RescaleAction<E: Env> {
    env: E,
    space: E::ActSpace,
    gradient: ArrayD<f64>,
    intercept: ArrayD<f64>,
    single: bool,
}

impl<E: Env> RescaleAction<E>
where
    E::ActSpace: NumericSpace,
{
    /// Wraps `env`, exposing actions in `[min_action, max_action]`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a non-Box or integer action space, a bound of the
    /// wrong shape, NaN, `min > max`, `min == max`, or an infinite component that is not
    /// infinite on the same side of the inner Box.
    pub fn new(
        env: E,
        min_action: impl Into<ActionBound>,
        max_action: impl Into<ActionBound>,
    ) -> Result<Self> {
        let inner = env.action_space();
        if !inner.is_box() {
            return Err(Error::invalid_argument(
                "env",
                format!("RescaleAction needs a Box action space, got {inner:?}"),
            ));
        }
        let spec = inner.array_spec()?;
        if !spec.dtype.is_float() {
            return Err(Error::invalid_argument(
                "env",
                format!(
                    "RescaleAction needs a floating-point Box, got dtype {}",
                    spec.dtype
                ),
            ));
        }
        let single = spec.dtype == DType::F32;
        let r = move |v: f64| if single { f64::from(v as f32) } else { v };
        let new_min = min_action.into().to_array(&spec.shape, "min_action")?;
        let new_max = max_action.into().to_array(&spec.shape, "max_action")?;
        let mut problems = Vec::new();
        Zip::from(&new_min)
            .and(&new_max)
            .and(&spec.low)
            .and(&spec.high)
            .for_each(|&mn, &mx, &lo, &hi| {
                if mn.is_nan() || mx.is_nan() {
                    problems.push("NaN bound".to_owned());
                } else if (mn.is_infinite() || lo.is_infinite()) && mn != lo {
                    problems.push(format!(
                        "min_action {mn} must equal the inner low {lo} where either is infinite"
                    ));
                } else if (mx.is_infinite() || hi.is_infinite()) && mx != hi {
                    problems.push(format!(
                        "max_action {mx} must equal the inner high {hi} where either is infinite"
                    ));
                } else if mn > mx {
                    problems.push(format!("min_action {mn} > max_action {mx}"));
                } else if mn == mx {
                    problems.push(format!("min_action == max_action == {mn}"));
                }
            });
        if let Some(p) = problems.into_iter().next() {
            return Err(Error::invalid_argument("min_action/max_action", p));
        }
        let mut gradient = ArrayD::from_elem(IxDyn(&spec.shape), 1.0);
        let mut intercept = ArrayD::from_elem(IxDyn(&spec.shape), 0.0);
        Zip::from(&mut gradient)
            .and(&mut intercept)
            .and(&new_min)
            .and(&new_max)
            .and(&spec.low)
            .and(&spec.high)
            .for_each(|g, c, &mn, &mx, &lo, &hi| {
                let (min_finite, max_finite) = (mn.is_finite(), mx.is_finite());
                if min_finite && max_finite {
                    *g = r((mx - mn) / (hi - lo));
                }
                if max_finite {
                    *c = r(mx - hi);
                }
                if min_finite {
                    *c = r(r(*g * -lo) + mn);
                }
            });
        let space = inner.with_bounds(new_min, new_max)?;
        Ok(Self {
            env,
            space,
            gradient,
            intercept,
            single,
        })
    }

    fn backward(&self, action: &E::Act) -> Result<E::Act> {
        let single = self.single;
        let r = move |v: f64| if single { f64::from(v as f32) } else { v };
        let a = self.space.element_to_array::<f64>(action)?;
        if a.shape() != self.gradient.shape() {
            return Err(Error::invalid_action(format!(
                "expected an action of shape {:?}, got {:?}",
                self.gradient.shape(),
                a.shape()
            )));
        }
        let mapped = Zip::from(&a)
            .and(&self.intercept)
            .and(&self.gradient)
            .map_collect(|&a, &c, &g| r(r(a - c) / g));
        self.env.action_space().element_from_array(&mapped)
    }
}

impl<E: Env> Wrapper for RescaleAction<E>
where
    E::ActSpace: NumericSpace,
{
    type Inner = E;
    type Kind = Actions;
    fn inner(&self) -> &E {
        &self.env
    }
    fn inner_mut(&mut self) -> &mut E {
        &mut self.env
    }
    fn into_inner(self) -> E {
        self.env
    }
}

impl<E: Env> ActionWrapper for RescaleAction<E>
where
    E::ActSpace: NumericSpace,
{
    type Space = E::ActSpace;

    fn space(&self) -> &E::ActSpace {
        &self.space
    }

    fn action(&mut self, action: &E::Act) -> Result<E::Act> {
        self.backward(action).map_err(Error::into_invalid_action)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toy::{DiscreteEnv, ScriptEnv, a32, a64, unit_actions};
    use gym_core::spaces::BoxSpace;
    use gym_core::{EnvExt, Space};

    type Script = ScriptEnv<BoxSpace<f32>, BoxSpace<f32>>;

    fn received(env: &RescaleAction<Script>) -> Vec<Vec<f32>> {
        env.unwrapped_as::<Script>()
            .unwrap()
            .actions
            .iter()
            .map(|a| a.iter().copied().collect())
            .collect()
    }

    #[test]
    fn gymnasium_example_unit_to_zero_one() {
        let inner = crate::toy::script_f32(&[&[0.0]], &[0.0]);
        let mut env = RescaleAction::new(inner, 0.0, 1.0).unwrap();
        assert_eq!(env.action_space().to_string(), "Box(0, 1, [2], float32)");
        env.reset(None, None).unwrap();
        for a in [[0.5f32, 0.0], [1.0, 0.25]] {
            let _ = env.step(&a32(&a)).unwrap();
        }
        assert_eq!(received(&env), vec![vec![0.0, -1.0], vec![1.0, -0.5]]);
    }

    #[test]
    fn float32_results_match_gymnasium_bit_for_bit() {
        // Reference: gymnasium 1.4.0 RescaleAction(Box([-1, -2, 0.1], [1, 3, 0.7], float32), -0.3, 0.7).
        let low = a32(&[-1.0, -2.0, 0.1]).mapv(f64::from);
        let high = a32(&[1.0, 3.0, 0.7]).mapv(f64::from);
        let inner = ScriptEnv::new(
            BoxSpace::<f32>::unbounded(&[1]),
            BoxSpace::<f32>::new(low, high).unwrap(),
            vec![a32(&[0.0])],
            vec![0.0],
        );
        let mut env = RescaleAction::new(inner, -0.3, 0.7).unwrap();
        env.reset(None, None).unwrap();
        let inputs: [[f32; 3]; 4] = [[-0.3; 3], [0.7; 3], [0.1, 0.2, 0.3], [0.123, -0.25, 0.69]];
        for a in inputs {
            let _ = env.step(&a32(&a)).unwrap();
        }
        let want: Vec<Vec<f32>> = vec![
            vec![-1.0, -2.0000002, 0.09999999],
            vec![1.0, 2.9999998, 0.6999999],
            vec![-0.2, 0.49999997, 0.45999998],
            vec![-0.154, -1.7500001, 0.69399995],
        ];
        assert_eq!(received(&env), want);
    }

    #[test]
    fn infinite_components_stay_infinite_and_shift() {
        let space = BoxSpace::<f64>::new(
            a64(&[f64::NEG_INFINITY, 0.0]),
            a64(&[f64::INFINITY, f64::INFINITY]),
        )
        .unwrap();
        let inner = ScriptEnv::new(
            BoxSpace::<f32>::unbounded(&[1]),
            space,
            vec![a32(&[0.0])],
            vec![0.0],
        );
        let mut env = RescaleAction::new(
            inner,
            ActionBound::from(&[f64::NEG_INFINITY, 2.0][..]),
            ActionBound::from(&[f64::INFINITY, f64::INFINITY][..]),
        )
        .unwrap();
        env.reset(None, None).unwrap();
        let _ = env.step(&a64(&[7.0, 5.0])).unwrap();
        let inner = env
            .unwrapped_as::<ScriptEnv<BoxSpace<f32>, BoxSpace<f64>>>()
            .unwrap();
        assert_eq!(inner.actions, vec![a64(&[7.0, 3.0])]);
    }

    #[test]
    fn invalid_bounds() {
        let mk = || crate::toy::script_f32(&[&[0.0]], &[0.0]);
        assert!(RescaleAction::new(mk(), 1.0, 1.0).is_err());
        assert!(RescaleAction::new(mk(), 1.0, 0.0).is_err());
        assert!(RescaleAction::new(mk(), f64::NEG_INFINITY, 1.0).is_err());
        assert!(RescaleAction::new(mk(), f64::NAN, 1.0).is_err());
        assert!(RescaleAction::new(mk(), ActionBound::from(&[0.0][..]), 1.0).is_err());
        assert!(RescaleAction::new(DiscreteEnv::new(), 0.0, 1.0).is_err());
        let ints = ScriptEnv::new(
            unit_actions(),
            BoxSpace::<i64>::uniform(0.0, 4.0, &[1]).unwrap(),
            vec![a32(&[0.0, 0.0])],
            vec![0.0],
        );
        assert!(RescaleAction::new(ints, 0.0, 1.0).is_err());
        // The rescaled space contains its bounds.
        let env = RescaleAction::new(mk(), -0.3, 0.7).unwrap();
        assert!(env.action_space().contains(&a32(&[-0.3, 0.7])));
    }
}
