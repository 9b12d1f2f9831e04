//! Quaternions, dual quaternions and 4×4 homogeneous matrices over any [`Ring`].
//!
//! Non-commutativity and ε² = 0 live only in this module; the scalar stays commutative.
//! The files follow nalgebra's split: the types and their operators (`quat.rs`,
//! `dual_quat.rs`), the constructors of rigid motions (`construct.rs`) and the conversion
//! to and from homogeneous matrices (`matrix.rs`).
//!
//! Convention: a dual quaternion is `q + ε q_ε`, the whole coefficient of ε is stored in
//! [`DualQuat::dual`]. Paper formulas that write `(ε/2)(q5..q8)` (sec 3-B, Appendix I) are
//! converted where they are used (ERRATA, "Two dual-part conventions").

mod construct;
pub mod dqr;
mod dual_quat;
mod matrix;
mod quat;

pub use dual_quat::{DualNumber, DualQuat, UnitConstraints};
pub use matrix::Matrix4;
pub use quat::Quat;

use crate::Ring;

/// `a · b` for two borrowed scalars, cloning only the left factor.
///
/// The ring gives `T * &T`; this keeps hot products at one clone per multiplication.
#[inline]
pub(crate) fn mul<T: Ring>(a: &T, b: &T) -> T {
    a.clone() * b
}

/// The cross product `a × b` of two 3-vectors.
pub fn cross<T: Ring>(a: &[T; 3], b: &[T; 3]) -> [T; 3] {
    [
        mul(&a[1], &b[2]) - mul(&a[2], &b[1]),
        mul(&a[2], &b[0]) - mul(&a[0], &b[2]),
        mul(&a[0], &b[1]) - mul(&a[1], &b[0]),
    ]
}

/// `k · v` for a scalar `k` and a 3-vector `v`.
pub(crate) fn scale3<T: Ring>(k: &T, v: &[T; 3]) -> [T; 3] {
    [mul(k, &v[0]), mul(k, &v[1]), mul(k, &v[2])]
}

/// The componentwise negation of a 3-vector.
pub(crate) fn neg3<T: Ring>(v: &[T; 3]) -> [T; 3] {
    [-v[0].clone(), -v[1].clone(), -v[2].clone()]
}
