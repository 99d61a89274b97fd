//! The operational-space algebra of [`super::Osc`] (robosuite's
//! `control_utils.opspace_matrices` and `nullspace_torques`), written once over nalgebra's
//! dimension types: on fixed-size matrices (stack arrays, loops of known length) for arms
//! of up to [`MAX_FIXED_JOINTS`] joints, on heap-sized ones for larger arms. Both sizes
//! run the same code, so they perform the same floating-point operations in the same order
//! and give the same bits.

use super::state::ArmState;
use crate::math::PsdPinv;
use nalgebra::allocator::Allocator;
use nalgebra::{
    Cholesky, Const, DMatrix, DVector, DefaultAllocator, Dim, Dyn, Matrix6, OMatrix, OVector, U6,
    Vector3, Vector6,
};

/// The largest arm the fixed-size algebra covers.
pub const MAX_FIXED_JOINTS: usize = 7;

/// robosuite's nullspace stiffness (`nullspace_torques`' `joint_kp`).
const NULLSPACE_KP: f64 = 10.0;

/// The matrices of one arm of `D` joints: inputs copied from the arm state, then the
/// intermediate products.
#[derive(Debug, Clone)]
pub(super) struct OpSpace<D: Dim>
where
    DefaultAllocator: Allocator<D, D> + Allocator<U6, D> + Allocator<D, U6> + Allocator<D>,
{
    jac: OMatrix<f64, U6, D>,
    mass: OMatrix<f64, D, D>,
    m_inv: OMatrix<f64, D, D>,
    chol: Option<OMatrix<f64, D, D>>,
    j_minv: OMatrix<f64, U6, D>,
    jbar: OMatrix<f64, D, U6>,
    null: OMatrix<f64, D, D>,
    posture: OVector<f64, D>,
    posture_m: OVector<f64, D>,
    tau: OVector<f64, D>,
}

impl<D: Dim> OpSpace<D>
where
    DefaultAllocator: Allocator<D, D> + Allocator<U6, D> + Allocator<D, U6> + Allocator<D>,
{
    fn new(n: D) -> Self {
        Self {
            jac: OMatrix::zeros_generic(U6, n),
            mass: OMatrix::zeros_generic(n, n),
            m_inv: OMatrix::zeros_generic(n, n),
            chol: Some(OMatrix::zeros_generic(n, n)),
            j_minv: OMatrix::zeros_generic(U6, n),
            jbar: OMatrix::zeros_generic(n, U6),
            null: OMatrix::zeros_generic(n, n),
            posture: OMatrix::zeros_generic(n, Const::<1>),
            posture_m: OMatrix::zeros_generic(n, Const::<1>),
            tau: OMatrix::zeros_generic(n, Const::<1>),
        }
    }

    /// `M⁻¹` of the arm's mass matrix into `m_inv` (robosuite: `np.linalg.inv`): Cholesky
    /// in place when positive definite, LU otherwise.
    fn invert_mass(&mut self) {
        let (n, _) = self.mass.shape_generic();
        let mut buf = self
            .chol
            .take()
            .unwrap_or_else(|| OMatrix::zeros_generic(n, n));
        buf.copy_from(&self.mass);
        let chol = Cholesky::new_unchecked(buf);
        let l = chol.l_dirty();
        let definite = (0..n.value()).all(|i| l[(i, i)].is_finite() && l[(i, i)] > 0.0);
        self.m_inv.fill_with_identity();
        if definite {
            chol.solve_mut(&mut self.m_inv);
            self.chol = Some(chol.unpack_dirty());
        } else {
            // Not positive definite (a degenerate model): the general inverse, or the
            // pseudo-inverse when singular, on a heap copy whatever the arm's size (one
            // code for both sizes). Rare, so it may allocate.
            self.chol = Some(chol.unpack_dirty());
            let n = n.value();
            let mass = DMatrix::from_column_slice(n, n, self.mass.as_slice());
            match mass.clone().try_inverse() {
                Some(inv) => self.m_inv.as_mut_slice().copy_from_slice(inv.as_slice()),
                None => {
                    let pinv = mass
                        .pseudo_inverse(1e-15)
                        .unwrap_or_else(|_| DMatrix::zeros(n, n));
                    self.m_inv.as_mut_slice().copy_from_slice(pinv.as_slice());
                }
            }
        }
    }

    /// `τ = Jᵀ[Λp·F; Λo·T] + h + Nᵀ·M·(kp(q₀ − q) − kv·q̇)` into `out` (see
    /// [`super::Osc`]); `bias` is MuJoCo's `qfrc_bias`.
    #[allow(clippy::too_many_arguments)]
    fn torques(
        &mut self,
        arm: &ArmState,
        q0: &DVector<f64>,
        bias: &[f64],
        force: &Vector3<f64>,
        torque: &Vector3<f64>,
        uncouple: bool,
        out: &mut [f64],
    ) {
        let n = self.mass.nrows();
        // Both column-major, of the same shape.
        self.jac.as_mut_slice().copy_from_slice(arm.jac.as_slice());
        self.mass
            .as_mut_slice()
            .copy_from_slice(arm.mass.as_slice());
        self.invert_mass();
        let jac = &self.jac;
        // Small products by hand: nalgebra's dynamic matrix products allocate packing
        // buffers.
        for r in 0..6 {
            for c in 0..n {
                let mut s = 0.0;
                for k in 0..n {
                    s += jac[(r, k)] * self.m_inv[(k, c)];
                }
                self.j_minv[(r, c)] = s;
            }
        }
        let lambda_inv = Matrix6::from_fn(|r, c| {
            let mut s = 0.0;
            for k in 0..n {
                s += self.j_minv[(r, k)] * jac[(c, k)];
            }
            s
        });
        let lambda = lambda_inv.pinv_psd();
        let wrench: Vector6<f64> = if uncouple {
            let lambda_p = lambda_inv.fixed_view::<3, 3>(0, 0).into_owned().pinv_psd();
            let lambda_o = lambda_inv.fixed_view::<3, 3>(3, 3).into_owned().pinv_psd();
            let fp = lambda_p * force;
            let fo = lambda_o * torque;
            Vector6::new(fp[0], fp[1], fp[2], fo[0], fo[1], fo[2])
        } else {
            lambda
                * Vector6::new(
                    force[0], force[1], force[2], torque[0], torque[1], torque[2],
                )
        };
        // τ = Jᵀ wrench + h
        let dofs = &arm.binding().dofs;
        for c in 0..n {
            let mut s = 0.0;
            for r in 0..6 {
                s += jac[(r, c)] * wrench[r];
            }
            self.tau[c] = s + bias[dofs[c]];
        }
        // Nullspace posture term (control_utils.nullspace_torques): N = I − M⁻¹Jᵀ Λ J.
        for rr in 0..n {
            for c in 0..6 {
                let mut s = 0.0;
                for k in 0..6 {
                    s += self.j_minv[(k, rr)] * lambda[(k, c)];
                }
                self.jbar[(rr, c)] = s;
            }
        }
        for i in 0..n {
            for j in 0..n {
                let mut s = 0.0;
                for k in 0..6 {
                    s += self.jbar[(i, k)] * jac[(k, j)];
                }
                self.null[(i, j)] = f64::from(u8::from(i == j)) - s;
            }
        }
        let kvn = NULLSPACE_KP.sqrt() * 2.0;
        for i in 0..n {
            self.posture[i] = (q0[i] - arm.q[i]) * NULLSPACE_KP - arm.qd[i] * kvn;
        }
        self.mass.mul_to(&self.posture, &mut self.posture_m);
        self.tau.gemv_tr(1.0, &self.null, &self.posture_m, 1.0);
        out.copy_from_slice(self.tau.as_slice());
    }
}

/// The matrices of the fixed-size algebra of `n` joints (`Fixed`), or the heap-sized one.
macro_rules! algebra {
    ($($variant:ident = $n:literal),*) => {
        /// [`OpSpace`] of the arm's size, chosen at construction.
        #[derive(Debug, Clone)]
        pub(super) enum Algebra {
            $(
                #[doc = concat!("An arm of ", stringify!($n), " joints, on fixed-size matrices.")]
                $variant(Box<OpSpace<Const<$n>>>),
            )*
            /// Any arm, on heap-sized matrices.
            Dynamic(Box<OpSpace<Dyn>>),
        }

        impl Algebra {
            /// The fixed-size algebra for `n` joints when there is one and `fixed`, else
            /// the heap-sized one.
            pub(super) fn new(n: usize, fixed: bool) -> Self {
                match n {
                    $($n if fixed => Self::$variant(Box::new(OpSpace::new(Const::<$n>))),)*
                    _ => Self::Dynamic(Box::new(OpSpace::new(Dyn(n)))),
                }
            }

            /// Whether this is a fixed-size algebra.
            pub(super) fn is_fixed(&self) -> bool {
                !matches!(self, Self::Dynamic(_))
            }

            /// [`OpSpace::torques`] on the algebra of this arm.
            #[allow(clippy::too_many_arguments)]
            pub(super) fn torques(
                &mut self,
                arm: &ArmState,
                q0: &DVector<f64>,
                bias: &[f64],
                force: &Vector3<f64>,
                torque: &Vector3<f64>,
                uncouple: bool,
                out: &mut [f64],
            ) {
                match self {
                    $(Self::$variant(o) => o.torques(arm, q0, bias, force, torque, uncouple, out),)*
                    Self::Dynamic(o) => o.torques(arm, q0, bias, force, torque, uncouple, out),
                }
            }
        }
    };
}

algebra!(
    Fixed1 = 1,
    Fixed2 = 2,
    Fixed3 = 3,
    Fixed4 = 4,
    Fixed5 = 5,
    Fixed6 = 6,
    Fixed7 = 7
);

const _: () = assert!(MAX_FIXED_JOINTS == 7, "algebra! lists the sizes 1 to 7");
