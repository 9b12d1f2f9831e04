//! Hamilton quaternions `w + x i + y j + z k` over a ring.

use super::mul;
use crate::{Ring, SignedProduct};
use std::ops::{Add, Mul, Neg, Sub};

/// A quaternion `w + x i + y j + z k` (the paper's `(s, m)` with `s = w`, `m = (x, y, z)`).
///
/// Arguments and fields are in the order `w, x, y, z`, scalar first, as the paper writes
/// them; there is no hidden storage order to trip over.
///
/// # Laws
/// - `*` is associative and distributes over `+`, [`Quat::identity`] is neutral; it is not
///   commutative (`i j = k = −j i`).
/// - `(p q)* = q* p*` and `q q* = q* q = |q|²` ([`Quat::norm_squared`], a scalar).
/// - `|p q|² = |p|² |q|²`.
/// - `q · q.try_inverse().unwrap() = 1` whenever `try_inverse` returns `Some`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Quat<T> {
    /// The scalar part `s`.
    pub w: T,
    /// The `i` coefficient.
    pub x: T,
    /// The `j` coefficient.
    pub y: T,
    /// The `k` coefficient.
    pub z: T,
}

impl<T: Ring> Quat<T> {
    /// The quaternion `w + x i + y j + z k`.
    pub fn new(w: T, x: T, y: T, z: T) -> Self {
        Quat { w, x, y, z }
    }

    /// The pure quaternion `x i + y j + z k` (scalar part zero), the paper's `(0, v)`.
    pub fn vector(x: T, y: T, z: T) -> Self {
        Quat::new(T::zero(), x, y, z)
    }

    /// The pure quaternion of a 3-vector.
    pub fn from_vector(v: &[T; 3]) -> Self {
        Quat::vector(v[0].clone(), v[1].clone(), v[2].clone())
    }

    /// The real quaternion `w` (vector part zero).
    pub fn from_scalar(w: T) -> Self {
        Quat::new(w, T::zero(), T::zero(), T::zero())
    }

    /// The multiplicative identity `1`.
    pub fn identity() -> Self {
        Quat::from_scalar(T::one())
    }

    /// The zero quaternion.
    pub fn zero() -> Self {
        Quat::from_scalar(T::zero())
    }

    /// Whether all four components are zero.
    pub fn is_zero(&self) -> bool {
        self.w.is_zero() && self.x.is_zero() && self.y.is_zero() && self.z.is_zero()
    }

    /// The vector part `(x, y, z)`.
    pub fn vector_part(&self) -> [T; 3] {
        [self.x.clone(), self.y.clone(), self.z.clone()]
    }

    /// The components in the order `(w, x, y, z)`.
    pub fn components(&self) -> [T; 4] {
        [
            self.w.clone(),
            self.x.clone(),
            self.y.clone(),
            self.z.clone(),
        ]
    }

    /// The quaternion with components `(w, x, y, z)`.
    pub fn from_components([w, x, y, z]: [T; 4]) -> Self {
        Quat::new(w, x, y, z)
    }

    /// The product `k q` by a scalar (scalars commute with quaternions).
    pub fn scale(&self, k: &T) -> Self {
        Quat::new(
            mul(k, &self.w),
            mul(k, &self.x),
            mul(k, &self.y),
            mul(k, &self.z),
        )
    }

    /// The conjugate `q* = (s, −m)` (eq 2).
    pub fn conjugate(&self) -> Self {
        Quat::new(
            self.w.clone(),
            -self.x.clone(),
            -self.y.clone(),
            -self.z.clone(),
        )
    }

    /// Conjugates in place.
    pub fn conjugate_mut(&mut self) {
        *self = self.conjugate();
    }

    /// The inner product `s₁ s₂ + m₁ · m₂` of the components.
    pub fn dot(&self, other: &Self) -> T {
        mul(&self.w, &other.w)
            + mul(&self.x, &other.x)
            + mul(&self.y, &other.y)
            + mul(&self.z, &other.z)
    }

    /// `|q|² = s² + x² + y² + z² = q q*`.
    pub fn norm_squared(&self) -> T {
        self.dot(self)
    }

    /// The inverse `q* / |q|²`, or `None` when the ring cannot invert `|q|²` (zero, or a
    /// symbolic expression the scalar refuses to divide by).
    pub fn try_inverse(&self) -> Option<Self> {
        let r = self.norm_squared().try_recip()?;
        Some(self.conjugate().scale(&r))
    }

    /// The Hamilton product (eq 1): `(s₁ s₂ − m₁·m₂, s₁ m₂ + s₂ m₁ + m₁ × m₂)`.
    ///
    /// 16 multiplications and 12 additions, as Table 1 counts them; each component is one
    /// [`Ring::sums_of_products`] of its signed products.
    pub fn mul_ref(&self, b: &Self) -> Self {
        let [w, x, y, z] = self.product_terms(b).map(|c| T::sums_of_products(&[&c]));
        Quat { w, x, y, z }
    }

    /// The vector part `(x, y, z)` of `self * b`, computed exactly as [`Quat::mul_ref`]
    /// computes it, without the scalar part.
    pub(crate) fn mul_vector_part(&self, b: &Self) -> [T; 3] {
        let [_, x, y, z] = self.product_terms(b);
        [x, y, z].map(|c| T::sums_of_products(&[&c]))
    }

    /// The signed products whose sums are the components `w, x, y, z` of `self * b` (eq 1),
    /// each in the order the Hamilton product adds them.
    pub(crate) fn product_terms<'a>(&'a self, b: &'a Self) -> [[SignedProduct<'a, T>; 4]; 4] {
        let a = self;
        [
            [
                (false, &a.w, &b.w),
                (true, &a.x, &b.x),
                (true, &a.y, &b.y),
                (true, &a.z, &b.z),
            ],
            [
                (false, &a.w, &b.x),
                (false, &a.x, &b.w),
                (false, &a.y, &b.z),
                (true, &a.z, &b.y),
            ],
            [
                (false, &a.w, &b.y),
                (true, &a.x, &b.z),
                (false, &a.y, &b.w),
                (false, &a.z, &b.x),
            ],
            [
                (false, &a.w, &b.z),
                (false, &a.x, &b.y),
                (true, &a.y, &b.x),
                (false, &a.z, &b.w),
            ],
        ]
    }

    fn add_ref(&self, b: &Self) -> Self {
        Quat {
            w: self.w.clone() + &b.w,
            x: self.x.clone() + &b.x,
            y: self.y.clone() + &b.y,
            z: self.z.clone() + &b.z,
        }
    }

    fn sub_ref(&self, b: &Self) -> Self {
        Quat {
            w: self.w.clone() - &b.w,
            x: self.x.clone() - &b.x,
            y: self.y.clone() - &b.y,
            z: self.z.clone() - &b.z,
        }
    }
}

/// Implements a binary operator for the four owned/borrowed combinations by delegating to a
/// `fn(&Self, &Self) -> Self` method.
macro_rules! forward_binop {
    ($ty:ident, $trait:ident, $method:ident, $by_ref:ident) => {
        impl<'a, 'b, T: Ring> $trait<&'b $ty<T>> for &'a $ty<T> {
            type Output = $ty<T>;
            fn $method(self, rhs: &'b $ty<T>) -> $ty<T> {
                self.$by_ref(rhs)
            }
        }
        impl<'b, T: Ring> $trait<&'b $ty<T>> for $ty<T> {
            type Output = $ty<T>;
            fn $method(self, rhs: &'b $ty<T>) -> $ty<T> {
                self.$by_ref(rhs)
            }
        }
        impl<'a, T: Ring> $trait<$ty<T>> for &'a $ty<T> {
            type Output = $ty<T>;
            fn $method(self, rhs: $ty<T>) -> $ty<T> {
                self.$by_ref(&rhs)
            }
        }
        impl<T: Ring> $trait<$ty<T>> for $ty<T> {
            type Output = $ty<T>;
            fn $method(self, rhs: $ty<T>) -> $ty<T> {
                self.$by_ref(&rhs)
            }
        }
    };
}
pub(crate) use forward_binop;

forward_binop!(Quat, Mul, mul, mul_ref);
forward_binop!(Quat, Add, add, add_ref);
forward_binop!(Quat, Sub, sub, sub_ref);

impl<T: Ring> Neg for Quat<T> {
    type Output = Quat<T>;
    fn neg(self) -> Quat<T> {
        Quat::new(-self.w, -self.x, -self.y, -self.z)
    }
}

impl<T: Ring> Neg for &Quat<T> {
    type Output = Quat<T>;
    fn neg(self) -> Quat<T> {
        -self.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(w: f64, x: f64, y: f64, z: f64) -> Quat<f64> {
        Quat::new(w, x, y, z)
    }

    #[test]
    fn units_multiply_like_hamilton() {
        let (i, j, k) = (q(0., 1., 0., 0.), q(0., 0., 1., 0.), q(0., 0., 0., 1.));
        assert_eq!(&i * &j, k);
        assert_eq!(&j * &k, i);
        assert_eq!(&k * &i, j);
        assert_eq!(&j * &i, -k.clone());
        assert_eq!(&i * &i, q(-1., 0., 0., 0.));
    }

    #[test]
    fn inverse_of_zero_is_none() {
        assert_eq!(Quat::<f64>::zero().try_inverse(), None);
    }
}
