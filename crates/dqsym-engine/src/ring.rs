//! The scalar ring the quaternion algebra is written over.
//!
//! `Quat<T>` and `DualQuat<T>` need only what this trait gives: a commutative ring with exact
//! small rationals, a partial reciprocal, and the half-angle trigonometry rotations are built
//! from. It is implemented for `f64` (the numeric oracle) and for [`crate::Scalar`] (exact).
//!
//! # Laws
//! `+` and `*` are associative and commutative, `*` distributes over `+`, `zero()` and `one()`
//! are neutral; `x * x.try_recip().unwrap() == one()` whenever `try_recip` returns `Some`.

use num_traits::{One, Zero};
use std::fmt::Debug;
use std::ops::{Add, Mul, Neg, Sub};

/// A commutative ring with exact rationals, as the algebra layer needs it.
pub trait Ring:
    Clone
    + Debug
    + PartialEq
    + Zero
    + One
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Neg<Output = Self>
    + for<'a> Add<&'a Self, Output = Self>
    + for<'a> Sub<&'a Self, Output = Self>
    + for<'a> Mul<&'a Self, Output = Self>
{
    /// The exact rational `num / den` (`den != 0`).
    fn from_ratio(num: i64, den: i64) -> Self;

    /// The multiplicative inverse, or `None` when `self` is zero or has no inverse in this ring
    /// (a symbolic scalar refuses division by a non-constant expression).
    fn try_recip(&self) -> Option<Self>;

    /// `cos(self)`; for the symbolic scalar `self` must be an angle (linear in symbols plus a
    /// rational multiple of pi), otherwise the result is an error value (see `Scalar::check`).
    fn cos(&self) -> Self;

    /// `sin(self)`, under the same conditions as [`Ring::cos`].
    fn sin(&self) -> Self;

    /// The square root of `self`, when `self` is a non-negative rational (exact for the
    /// symbolic scalar: `sqrt(8) = 2 sqrt(2)`); `None` otherwise.
    fn try_sqrt(&self) -> Option<Self>;

    /// `self / 2`, used everywhere for half angles and the `eps t / 2` translation convention.
    fn half(&self) -> Self {
        self.clone() * Self::from_ratio(1, 2)
    }

    /// An f64 approximation, when `self` has no free symbols.
    fn to_f64(&self) -> Option<f64>;

    /// `Σᵢ Σⱼ ±aᵢⱼ bᵢⱼ`: each inner slice a signed sum of products (`true` subtracts the
    /// product), the sums then added. Defined as the left fold the quaternion products write
    /// out, `((p₁ ± p₂) ± p₃) ...` for each sum (its first product taken with its sign), then
    /// `(s₁ + s₂) + ...`, so an `f64` result is the one those operators give bit for bit; an
    /// exact ring may compute the same value in fewer steps (the symbolic scalar forms every
    /// product's terms and brings them to canonical form once, see
    /// `scalar::arith::sums_of_products`).
    fn sums_of_products(sums: &[&[SignedProduct<'_, Self>]]) -> Self {
        let signed = |&(minus, a, b): &SignedProduct<'_, Self>| {
            let p = a.clone() * b;
            if minus {
                -p
            } else {
                p
            }
        };
        let sum = |s: &[SignedProduct<'_, Self>]| {
            let mut it = s.iter();
            let first = it.next().map_or_else(Self::zero, signed);
            it.fold(first, |acc, &(minus, a, b)| {
                let p = a.clone() * b;
                if minus {
                    acc - p
                } else {
                    acc + p
                }
            })
        };
        let mut it = sums.iter();
        let first = it.next().map_or_else(Self::zero, |s| sum(s));
        it.fold(first, |acc, s| acc + sum(s))
    }
}

/// One product of [`Ring::sums_of_products`]: `(subtract, a, b)` stands for `-a b` when
/// `subtract`, `a b` otherwise.
pub type SignedProduct<'a, T> = (bool, &'a T, &'a T);

impl Ring for f64 {
    fn from_ratio(num: i64, den: i64) -> Self {
        num as f64 / den as f64
    }
    fn try_recip(&self) -> Option<Self> {
        (*self != 0.0).then(|| 1.0 / *self)
    }
    fn cos(&self) -> Self {
        f64::cos(*self)
    }
    fn sin(&self) -> Self {
        f64::sin(*self)
    }
    fn try_sqrt(&self) -> Option<Self> {
        (*self >= 0.0).then(|| f64::sqrt(*self))
    }
    fn to_f64(&self) -> Option<f64> {
        Some(*self)
    }
}
