//! Dual quaternions `q + ε q_ε` with `ε² = 0`, and the dual numbers their norm lives in.

use super::quat::forward_binop;
use super::{mul, Quat};
use crate::Ring;
use std::ops::{Add, Mul, Neg, Sub};

/// A dual number `re + ε du` with `ε² = 0`: the value of [`DualQuat::norm_squared`].
///
/// # Laws
/// `(a + ε b)(c + ε d) = a c + ε (a d + b c)`; a unit dual quaternion has norm `1 + ε 0`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct DualNumber<T> {
    /// The real part.
    pub re: T,
    /// The coefficient of ε.
    pub du: T,
}

impl<T: Ring> DualNumber<T> {
    /// The dual number `re + ε du`.
    pub fn new(re: T, du: T) -> Self {
        DualNumber { re, du }
    }

    /// The product of two dual numbers.
    pub fn mul_ref(&self, other: &Self) -> Self {
        DualNumber {
            re: mul(&self.re, &other.re),
            du: mul(&self.re, &other.du) + mul(&self.du, &other.re),
        }
    }
}

/// The two values that vanish exactly when a dual quaternion is a unit one (sec 2):
/// `|q|² − 1` and `q · q_ε`.
///
/// The algebra does not decide what "zero" means: an exact scalar tests it exactly, an f64
/// caller compares against a tolerance.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct UnitConstraints<T> {
    /// `q₁² + q₂² + q₃² + q₄² − 1`, zero when the rotation part is a unit quaternion.
    pub norm_minus_one: T,
    /// `q · q_ε`, zero when the dual part is orthogonal to the real part.
    pub real_dot_dual: T,
}

impl<T: Ring> UnitConstraints<T> {
    /// Whether both constraints are exactly zero (meaningful for an exact scalar).
    pub fn hold_exactly(&self) -> bool {
        self.norm_minus_one.is_zero() && self.real_dot_dual.is_zero()
    }
}

/// A dual quaternion `q + ε q_ε` (eq 6), with `real = q` and `dual = q_ε`, the whole
/// coefficient of ε.
///
/// The paper's sec 3-B and Appendix I write `(q1..q4) + (ε/2)(q5..q8)`; in this type
/// `dual = (q5..q8) / 2`.
///
/// # Laws
/// - `*` (eq 7) is associative and distributes over `+`; [`DualQuat::identity`] is neutral.
/// - All three conjugates are anti-automorphisms: `conj(p q) = conj(q) conj(p)` for
///   [`conjugate`](DualQuat::conjugate) and [`combined_conjugate`](DualQuat::combined_conjugate);
///   [`dual_conjugate`](DualQuat::dual_conjugate) is an automorphism, `(p q)‾ = p‾ q‾`.
/// - `|p q|² = |p|² |q|²` as dual numbers ([`DualQuat::norm_squared`]).
/// - `q · q.try_inverse().unwrap() = 1`; for a unit DQ the inverse is `q* + ε q_ε*`.
/// - `q` and `−q` are the same rigid motion.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct DualQuat<T> {
    /// The real (rotation) part `q`.
    pub real: Quat<T>,
    /// The dual part `q_ε`.
    pub dual: Quat<T>,
}

impl<T: Ring> DualQuat<T> {
    /// The dual quaternion `real + ε dual`.
    pub fn from_real_and_dual(real: Quat<T>, dual: Quat<T>) -> Self {
        DualQuat { real, dual }
    }

    /// The dual quaternion `q + ε 0`.
    pub fn from_real(real: Quat<T>) -> Self {
        DualQuat::from_real_and_dual(real, Quat::zero())
    }

    /// The eight components `(w, x, y, z, w_ε, x_ε, y_ε, z_ε)` (eq 6, `q + ε q_ε` convention).
    pub fn components(&self) -> [T; 8] {
        let [a, b, c, d] = self.real.components();
        let [e, f, g, h] = self.dual.components();
        [a, b, c, d, e, f, g, h]
    }

    /// The dual quaternion with components `(w, x, y, z, w_ε, x_ε, y_ε, z_ε)`.
    pub fn from_components([a, b, c, d, e, f, g, h]: [T; 8]) -> Self {
        DualQuat::from_real_and_dual(Quat::new(a, b, c, d), Quat::new(e, f, g, h))
    }

    /// The product `k q̂` by a scalar.
    pub fn scale(&self, k: &T) -> Self {
        DualQuat::from_real_and_dual(self.real.scale(k), self.dual.scale(k))
    }

    /// The quaternion conjugate of both parts, `q* + ε q_ε*`.
    pub fn conjugate(&self) -> Self {
        DualQuat::from_real_and_dual(self.real.conjugate(), self.dual.conjugate())
    }

    /// Applies [`DualQuat::conjugate`] in place.
    pub fn conjugate_mut(&mut self) {
        self.real.conjugate_mut();
        self.dual.conjugate_mut();
    }

    /// The dual conjugate `q − ε q_ε` (eq 8).
    pub fn dual_conjugate(&self) -> Self {
        DualQuat::from_real_and_dual(self.real.clone(), -&self.dual)
    }

    /// The combined conjugate `q* − ε q_ε*` (eq 9):
    /// `(s, −x, −y, −z, −s_ε, x_ε, y_ε, z_ε)`. Points are transformed with it (eq 10).
    pub fn combined_conjugate(&self) -> Self {
        let d = &self.dual;
        DualQuat::from_real_and_dual(
            self.real.conjugate(),
            Quat::new(-d.w.clone(), d.x.clone(), d.y.clone(), d.z.clone()),
        )
    }

    /// The dual-number norm `q̂ q̂* = |q|² + ε 2 (q · q_ε)`.
    pub fn norm_squared(&self) -> DualNumber<T> {
        let d = self.real.dot(&self.dual);
        DualNumber::new(self.real.norm_squared(), d.clone() + &d)
    }

    /// The two unit constraints of sec 2, `|q|² − 1` and `q · q_ε`; both vanish exactly for
    /// a unit dual quaternion (a rigid motion).
    pub fn unit_constraints(&self) -> UnitConstraints<T> {
        UnitConstraints {
            norm_minus_one: self.real.norm_squared() - T::one(),
            real_dot_dual: self.real.dot(&self.dual),
        }
    }

    /// The inverse `q⁻¹ − ε q⁻¹ q_ε q⁻¹`, or `None` when `q` has no inverse.
    ///
    /// The paper's `1/q − ε q_ε/q²` (sec 2) is wrong because quaternions do not commute
    /// (ERRATA item 2); this is the corrected form. For a unit DQ it equals `q* + ε q_ε*`.
    pub fn try_inverse(&self) -> Option<Self> {
        let inv = self.real.try_inverse()?;
        let dual = -(&inv * &self.dual * &inv);
        Some(DualQuat::from_real_and_dual(inv, dual))
    }

    /// The product (eq 7): `p q + ε (p q_ε + p_ε q)`.
    ///
    /// The dual part's components are each one [`Ring::sums_of_products`] of the eight
    /// products of `real₁ dual₂ + dual₁ real₂`: the value the two quaternion products and
    /// their sum give (bit for bit in `f64`), in one step for an exact ring.
    pub fn mul_ref(&self, b: &Self) -> Self {
        let (rd, dr) = (
            self.real.product_terms(&b.dual),
            self.dual.product_terms(&b.real),
        );
        let [w, x, y, z] = [0, 1, 2, 3].map(|k| T::sums_of_products(&[&rd[k], &dr[k]]));
        DualQuat {
            real: &self.real * &b.real,
            dual: Quat { w, x, y, z },
        }
    }

    fn add_ref(&self, b: &Self) -> Self {
        DualQuat::from_real_and_dual(&self.real + &b.real, &self.dual + &b.dual)
    }

    fn sub_ref(&self, b: &Self) -> Self {
        DualQuat::from_real_and_dual(&self.real - &b.real, &self.dual - &b.dual)
    }
}

forward_binop!(DualQuat, Mul, mul, mul_ref);
forward_binop!(DualQuat, Add, add, add_ref);
forward_binop!(DualQuat, Sub, sub, sub_ref);

impl<T: Ring> Neg for DualQuat<T> {
    type Output = DualQuat<T>;
    fn neg(self) -> DualQuat<T> {
        DualQuat::from_real_and_dual(-self.real, -self.dual)
    }
}

impl<T: Ring> Neg for &DualQuat<T> {
    type Output = DualQuat<T>;
    fn neg(self) -> DualQuat<T> {
        -self.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn combined_conjugate_flips_the_signs_of_eq_9() {
        let q = DualQuat::from_components([1., 2., 3., 4., 5., 6., 7., 8.]);
        assert_eq!(
            q.combined_conjugate().components(),
            [1., -2., -3., -4., -5., 6., 7., 8.]
        );
    }

    #[test]
    fn pure_dual_quaternion_has_no_inverse() {
        let q = DualQuat::<f64>::from_real_and_dual(Quat::zero(), Quat::identity());
        assert_eq!(q.try_inverse(), None);
    }

    #[test]
    fn epsilon_squares_to_zero() {
        let eps = DualQuat::<f64>::from_real_and_dual(Quat::zero(), Quat::identity());
        assert_eq!(&eps * &eps, DualQuat::from_components([0.; 8]));
    }
}
