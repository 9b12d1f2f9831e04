//! Exact rationals with a machine-word fast path, for the coefficients of canonical terms.
//!
//! Almost every coefficient of a kinematic expression is a small fraction (`1/2`, `-3/4`,
//! `sqrt(2)/4` has rational part `1/4`), so [`Q`] keeps `numerator / denominator` in two
//! `i64` words and does checked arithmetic on them, switching to a [`BigRational`] only when a
//! result leaves that range. A value has exactly one representation: it is [`Q::S`] whenever
//! it fits (reduced, positive denominator, numerator not `i64::MIN`), so the derived `Eq` and
//! `Hash` agree with the numeric value.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive};
use std::cmp::Ordering;
use std::fmt;
use std::hash::{Hash, Hasher};
use std::ops::{Add, AddAssign, Mul, Neg, Sub};
use std::sync::Arc;

/// An exact rational: small (`S(numerator, denominator)`, reduced, denominator positive,
/// numerator never `i64::MIN`) whenever it fits, big otherwise.
///
/// A big value is shared: cloning a coefficient (every term copied into a sum, a product, a
/// group of the factoring search) counts a reference instead of copying its digits.
#[derive(Clone, PartialEq, Eq, Debug)]
pub(crate) enum Q {
    S(i64, i64),
    B(Arc<BigRational>),
}

/// By numerator and denominator, which are reduced (so this agrees with `Eq`). `Ratio`'s own
/// `Hash` walks the continued fraction of the value (it must agree with unreduced ratios),
/// a division per step: 7% of the instructions of the closed form of `(x + y + z)^60`.
impl Hash for Q {
    fn hash<H: Hasher>(&self, h: &mut H) {
        match self {
            Q::S(n, d) => {
                h.write_u8(0);
                h.write_i64(*n);
                h.write_i64(*d);
            }
            Q::B(b) => {
                h.write_u8(1);
                b.numer().hash(h);
                b.denom().hash(h);
            }
        }
    }
}

/// Binary gcd of machine words (also the closed-form cost pass's, `closed/factor/costs.rs`).
pub(crate) fn gcd_u64(mut a: u64, mut b: u64) -> u64 {
    if a == 0 {
        return b;
    }
    if b == 0 {
        return a;
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    loop {
        b >>= b.trailing_zeros();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b -= a;
        if b == 0 {
            return a << shift;
        }
    }
}

fn gcd_u128(mut a: u128, mut b: u128) -> u128 {
    if a <= u64::MAX as u128 && b <= u64::MAX as u128 {
        return gcd_u64(a as u64, b as u64) as u128;
    }
    if a == 0 {
        return b;
    }
    if b == 0 {
        return a;
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    loop {
        b >>= b.trailing_zeros();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b -= a;
        if b == 0 {
            return a << shift;
        }
    }
}

impl Q {
    pub(crate) const ZERO: Q = Q::S(0, 1);
    pub(crate) const ONE: Q = Q::S(1, 1);

    /// The integer `n`.
    pub(crate) fn int(n: i64) -> Q {
        if n == i64::MIN {
            return Q::big(BigRational::from_integer(BigInt::from(n)));
        }
        Q::S(n, 1)
    }

    /// The integer `n`.
    pub(crate) fn from_u64(n: u64) -> Q {
        match i64::try_from(n) {
            Ok(v) => Q::S(v, 1),
            Err(_) => Q::B(Arc::new(BigRational::from_integer(BigInt::from(n)))),
        }
    }

    /// `n / d` for `d != 0` (a zero denominator gives zero; callers never pass one).
    pub(crate) fn new(n: i64, d: i64) -> Q {
        if d == 0 {
            return Q::ZERO;
        }
        if d > 0 && n != i64::MIN {
            // In machine words (the common case: a `Small` frequency or offset, a
            // twelfth's coordinate), with [`Q::from_i64`]'s shortcuts for the denominator
            // 1 and powers of two: the same reduced value as `from_i128`, without its
            // 128-bit gcd (0.7 M instructions of the Jaco-style arm's `fk --jacobian`).
            return Q::from_i64(n, d);
        }
        Q::from_i128(n as i128, d as i128)
    }

    /// `n / d` reduced, for `d > 0`.
    fn from_i64(n: i64, d: i64) -> Q {
        if n == 0 {
            return Q::ZERO;
        }
        if n == i64::MIN {
            return Q::from_i128(n as i128, d as i128);
        }
        if d == 1 {
            return Q::S(n, 1);
        }
        if d & (d - 1) == 0 {
            // A power-of-two denominator (the common case: half angles): the gcd is a power
            // of two too, read off the trailing zeros.
            let shift = n.trailing_zeros().min(d.trailing_zeros());
            return Q::S(n >> shift, d >> shift);
        }
        let g = gcd_u64(n.unsigned_abs(), d as u64) as i64;
        Q::S(n / g, d / g)
    }

    /// `n / d` reduced, for `d != 0`.
    fn from_i128(mut n: i128, mut d: i128) -> Q {
        if n == 0 {
            return Q::ZERO;
        }
        if d < 0 {
            n = -n;
            d = -d;
        }
        let g = gcd_u128(n.unsigned_abs(), d as u128) as i128;
        if g > 1 {
            n /= g;
            d /= g;
        }
        match (i64::try_from(n), i64::try_from(d)) {
            (Ok(a), Ok(b)) if a != i64::MIN => Q::S(a, b),
            _ => Q::B(Arc::new(BigRational::new_raw(
                BigInt::from(n),
                BigInt::from(d),
            ))),
        }
    }

    /// The value of a big rational, demoted to the small form when it fits.
    pub(crate) fn big(q: BigRational) -> Q {
        if let (Some(n), Some(d)) = (q.numer().to_i64(), q.denom().to_i64()) {
            if n != i64::MIN {
                return if n == 0 { Q::ZERO } else { Q::S(n, d) };
            }
        }
        Q::B(Arc::new(q))
    }

    /// Feeds a few words of the value to `h`: a small value whole, a big one by the sizes of
    /// its numerator and denominator and the numerator's lowest word. Equal values feed equal
    /// words; for hash keys compared in full afterwards, where hashing every word of a big
    /// coefficient was the cost (the factoring search's memo).
    pub(crate) fn hash_words<H: Hasher>(&self, h: &mut H) {
        match self {
            Q::S(n, d) => {
                h.write_i64(*n);
                h.write_i64(*d);
            }
            Q::B(b) => {
                h.write_u64(b.numer().bits());
                h.write_u64(b.numer().iter_u64_digits().next().unwrap_or(0));
                h.write_u8(u8::from(b.numer().is_negative()));
                h.write_u64(b.denom().bits());
            }
        }
    }

    /// The size in bits of the longer of the numerator and the denominator.
    pub(crate) fn bits(&self) -> u64 {
        match self {
            Q::S(n, d) => u64::from(64 - n.unsigned_abs().max(d.unsigned_abs()).leading_zeros()),
            Q::B(b) => b.numer().bits().max(b.denom().bits()),
        }
    }

    /// The 64-bit words of a big value's numerator and denominator together (0 for a small
    /// one): what the work of an operation on it grows with.
    pub(crate) fn words(&self) -> u64 {
        match self {
            Q::S(..) => 0,
            Q::B(b) => (b.numer().bits() + b.denom().bits()).div_ceil(64),
        }
    }

    /// `1 / self`, for `self != 0` (zero gives zero; callers never pass it).
    pub(crate) fn recip(&self) -> Q {
        match self {
            Q::S(0, _) => Q::ZERO,
            Q::S(n, d) => Q::from_i128(*d as i128, *n as i128),
            Q::B(b) => Q::big(b.recip()),
        }
    }

    /// The value as a big rational.
    pub(crate) fn to_big(&self) -> BigRational {
        match self {
            Q::S(n, d) => BigRational::new_raw(BigInt::from(*n), BigInt::from(*d)),
            Q::B(b) => (**b).clone(),
        }
    }

    pub(crate) fn is_zero(&self) -> bool {
        matches!(self, Q::S(0, _))
    }

    pub(crate) fn is_one(&self) -> bool {
        matches!(self, Q::S(1, 1))
    }

    pub(crate) fn is_negative(&self) -> bool {
        match self {
            Q::S(n, _) => *n < 0,
            Q::B(b) => b.is_negative(),
        }
    }

    /// The value as a small `Ratio<i64>`, when it is one.
    pub(crate) fn to_ratio_i64(&self) -> Option<num_rational::Ratio<i64>> {
        match self {
            Q::S(n, d) => Some(num_rational::Ratio::new_raw(*n, *d)),
            Q::B(_) => None,
        }
    }

    pub(crate) fn to_f64(&self) -> Option<f64> {
        match self {
            // Exact operands and one IEEE division: correctly rounded, like BigRational's.
            Q::S(n, d) if n.unsigned_abs() <= 1 << 53 && *d <= 1 << 53 => {
                Some(*n as f64 / *d as f64)
            }
            _ => self.to_big().to_f64(),
        }
    }

    /// `self * k` for a small integer `k`.
    pub(crate) fn mul_int(&self, k: i64) -> Q {
        if k == 1 {
            return self.clone();
        }
        self * &Q::int(k)
    }

    fn add_signed(&self, o: &Q, negate: bool) -> Q {
        if let (Q::S(a, b), Q::S(c, d)) = (self, o) {
            // Same denominator and no overflow: one reduction (the numerator is never
            // i64::MIN, so the negation cannot overflow).
            if b == d {
                let c = if negate { -*c } else { *c };
                if let Some(n) = a.checked_add(c) {
                    return Q::from_i64(n, *b);
                }
            }
        }
        match (self, o) {
            (Q::S(a, b), Q::S(c, d)) => {
                let c = if negate { -(*c as i128) } else { *c as i128 };
                let (a, b, d) = (*a as i128, *b as i128, *d as i128);
                if b == d {
                    // Same denominator (the common case): one gcd with the denominator.
                    if let Ok(c) = i64::try_from(c) {
                        if let Some(n) = (a as i64).checked_add(c) {
                            return Q::from_i64(n, b as i64);
                        }
                    }
                    return Q::from_i128(a + c, b);
                }
                // a/b + c/d with g = gcd(b, d): (a (d/g) + c (b/g)) / (b/g * d).
                let g = gcd_u128(b as u128, d as u128) as i128;
                Q::from_i128(a * (d / g) + c * (b / g), (b / g) * d)
            }
            _ => {
                // Integers (the coefficients of an expansion such as `(x + y + z)^60`): no
                // gcd with the denominator 1, which `BigRational`'s `+` would compute for
                // every sum (44% of that expansion's instructions).
                if let (Some(x), Some(y)) = (self.big_integer(), o.big_integer()) {
                    let n = if negate { &*x - &*y } else { &*x + &*y };
                    return Q::big(BigRational::from_integer(n));
                }
                let (x, y) = (self.to_big(), o.to_big());
                Q::big(if negate { x - y } else { x + y })
            }
        }
    }

    /// The value as a big integer when it is an integer (denominator 1).
    fn big_integer(&self) -> Option<std::borrow::Cow<'_, BigInt>> {
        match self {
            Q::S(n, 1) => Some(std::borrow::Cow::Owned(BigInt::from(*n))),
            Q::S(..) => None,
            Q::B(q) => q
                .denom()
                .is_one()
                .then(|| std::borrow::Cow::Borrowed(q.numer())),
        }
    }
}

impl Default for Q {
    fn default() -> Self {
        Q::ZERO
    }
}

impl From<&BigRational> for Q {
    /// Without copying the digits when the value fits in machine words (the common case: the
    /// cyclotomic coordinates, read once per unit of every group).
    fn from(q: &BigRational) -> Q {
        if let (Some(n), Some(d)) = (q.numer().to_i64(), q.denom().to_i64()) {
            if n != i64::MIN {
                return if n == 0 { Q::ZERO } else { Q::S(n, d) };
            }
        }
        Q::B(Arc::new(q.clone()))
    }
}

impl Add<&Q> for &Q {
    type Output = Q;
    fn add(self, o: &Q) -> Q {
        self.add_signed(o, false)
    }
}

impl Sub<&Q> for &Q {
    type Output = Q;
    fn sub(self, o: &Q) -> Q {
        self.add_signed(o, true)
    }
}

impl AddAssign<&Q> for Q {
    fn add_assign(&mut self, o: &Q) {
        *self = &*self + o;
    }
}

impl Mul<&Q> for &Q {
    type Output = Q;
    fn mul(self, o: &Q) -> Q {
        match (self, o) {
            (Q::S(a, b), Q::S(c, d)) => {
                if *b == 1 && *d == 1 {
                    return match a.checked_mul(*c) {
                        Some(n) if n != i64::MIN => Q::S(n, 1),
                        _ => Q::from_i128(*a as i128 * *c as i128, 1),
                    };
                }
                if b & (b - 1) == 0 && d & (d - 1) == 0 {
                    // Power-of-two denominators (halves and quarters: the coefficients of
                    // the arms' entries, `sqrt(3)/4`): each cross gcd is a power of two,
                    // read off the trailing zeros instead of a binary gcd's loop. A zero
                    // numerator's 64 trailing zeros take the denominator's shift, which
                    // leaves the numerator zero (caught below).
                    let s1 = a.trailing_zeros().min(d.trailing_zeros());
                    let s2 = c.trailing_zeros().min(b.trailing_zeros());
                    if let (Some(n), Some(m)) = (
                        (a >> s1).checked_mul(c >> s2),
                        (b >> s2).checked_mul(d >> s1),
                    ) {
                        if n == 0 {
                            return Q::ZERO;
                        }
                        if n != i64::MIN {
                            return Q::S(n, m);
                        }
                    }
                }
                // Cross-reduce so the product is already in lowest terms.
                let g1 = gcd_u64(a.unsigned_abs(), *d as u64) as i64;
                let g2 = gcd_u64(c.unsigned_abs(), *b as u64) as i64;
                if let (Some(n), Some(m)) =
                    ((a / g1).checked_mul(c / g2), (b / g2).checked_mul(d / g1))
                {
                    if n == 0 {
                        return Q::ZERO;
                    }
                    if n != i64::MIN {
                        return Q::S(n, m);
                    }
                }
                let g1 = gcd_u64(a.unsigned_abs(), d.unsigned_abs()) as i128;
                let g2 = gcd_u64(c.unsigned_abs(), b.unsigned_abs()) as i128;
                let (a, b, c, d) = (*a as i128, *b as i128, *c as i128, *d as i128);
                let n = (a / g1) * (c / g2);
                let m = (b / g2) * (d / g1);
                if n == 0 {
                    return Q::ZERO;
                }
                match (i64::try_from(n), i64::try_from(m)) {
                    (Ok(x), Ok(y)) if x != i64::MIN => Q::S(x, y),
                    _ => Q::B(Arc::new(BigRational::new_raw(
                        BigInt::from(n),
                        BigInt::from(m),
                    ))),
                }
            }
            _ => {
                // Integers: the product is already in lowest terms.
                if let (Some(x), Some(y)) = (self.big_integer(), o.big_integer()) {
                    return Q::big(BigRational::from_integer(&*x * &*y));
                }
                Q::big(self.to_big() * o.to_big())
            }
        }
    }
}

impl Mul<Q> for Q {
    type Output = Q;
    fn mul(self, o: Q) -> Q {
        &self * &o
    }
}

impl Add<Q> for Q {
    type Output = Q;
    fn add(self, o: Q) -> Q {
        &self + &o
    }
}

impl Neg for Q {
    type Output = Q;
    fn neg(self) -> Q {
        -&self
    }
}

impl Neg for &Q {
    type Output = Q;
    fn neg(self) -> Q {
        match self {
            // The numerator is never i64::MIN, so this cannot overflow.
            Q::S(n, d) => Q::S(-n, *d),
            Q::B(b) => Q::big(-(**b).clone()),
        }
    }
}

impl Ord for Q {
    fn cmp(&self, o: &Q) -> Ordering {
        match (self, o) {
            (Q::S(a, b), Q::S(c, d)) => (*a as i128 * *d as i128).cmp(&(*c as i128 * *b as i128)),
            _ => self.to_big().cmp(&o.to_big()),
        }
    }
}

impl PartialOrd for Q {
    fn partial_cmp(&self, o: &Q) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// Prints like [`BigRational`]: `n` for integers, `n/d` otherwise.
impl fmt::Display for Q {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Q::S(n, 1) => write!(f, "{n}"),
            Q::S(n, d) => write!(f, "{n}/{d}"),
            Q::B(b) => write!(f, "{b}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn big(n: i128, d: i128) -> BigRational {
        BigRational::new(BigInt::from(n), BigInt::from(d))
    }

    #[test]
    fn small_arithmetic_agrees_with_big() {
        let vals = [
            (0i64, 1i64),
            (1, 2),
            (-3, 4),
            (7, 1),
            (i64::MAX, 1),
            (-i64::MAX, 3),
            (1, i64::MAX),
            (i64::MAX - 1, i64::MAX),
            (5, 6),
        ];
        for &(a, b) in &vals {
            for &(c, d) in &vals {
                let (x, y) = (Q::new(a, b), Q::new(c, d));
                let (bx, by) = (big(a.into(), b.into()), big(c.into(), d.into()));
                assert_eq!(&x + &y, Q::big(&bx + &by));
                assert_eq!(&x - &y, Q::big(&bx - &by));
                assert_eq!(&x * &y, Q::big(&bx * &by));
                assert_eq!(x.cmp(&y), bx.cmp(&by));
                assert_eq!((&x * &y).to_big(), &bx * &by);
                assert_eq!(x.to_string(), bx.to_string());
            }
        }
    }

    /// A random `i64` of a random size (a few bits up to the word's extremes, `i64::MIN`
    /// included), and a random positive denominator, a power of two half the time.
    fn random_parts(next: &mut impl FnMut(u64) -> u64) -> (i64, i64) {
        let word = |next: &mut dyn FnMut(u64) -> u64| -> i64 {
            let bits = 1 + next(63) as u32;
            let v = (next(u64::MAX) >> (64 - bits)) as i64;
            match next(16) {
                0 => i64::MIN,
                1 => i64::MAX,
                2 => 0,
                k if k % 2 == 0 => -v,
                _ => v,
            }
        };
        let n = word(next);
        let d = if next(2) == 0 {
            1i64 << next(63)
        } else {
            word(next).unsigned_abs().clamp(1, i64::MAX as u64) as i64
        };
        (n, d)
    }

    /// `Q::new` through `from_i64` and the power-of-two product against the 128-bit and big
    /// routes they shortcut: the same value and the same (canonical) representation.
    #[test]
    fn word_shortcuts_agree_with_the_general_routes() {
        let mut next = crate::testing::xorshift_below(0x9e37_79b9_7f4a_7c15);
        for _ in 0..20_000 {
            let (a, b) = random_parts(&mut next);
            let (c, d) = random_parts(&mut next);
            // Half the time a negative denominator (`b` is positive, never `i64::MIN`).
            let b = if next(2) == 0 { b } else { -b };
            let x = Q::new(a, b);
            assert_eq!(x, Q::from_i128(a.into(), b.into()), "new({a}, {b})");
            let y = Q::new(c, d);
            let product = &x * &y;
            assert_eq!(product, Q::big(x.to_big() * y.to_big()), "{x} * {y}");
            if let (Q::S(..), Q::S(n, m)) = (&x, &product) {
                assert!(*m > 0 && *n != i64::MIN);
            }
        }
    }

    #[test]
    fn big_values_demote_when_they_fit() {
        let x = Q::int(i64::MAX);
        let y = &x + &Q::ONE;
        assert!(matches!(y, Q::B(_)));
        let z = &y - &Q::ONE;
        assert_eq!(z, Q::S(i64::MAX, 1));
        assert!(matches!(Q::int(i64::MIN), Q::B(_)));
        assert_eq!(-&Q::int(i64::MIN), Q::big(big(-(i64::MIN as i128), 1)));
    }
}

#[cfg(test)]
mod hash_tests {
    use super::*;
    use std::hash::{DefaultHasher, Hash, Hasher};

    fn hashes(q: &Q) -> (u64, u64) {
        let mut a = DefaultHasher::new();
        q.hash(&mut a);
        let mut b = DefaultHasher::new();
        q.hash_words(&mut b);
        (a.finish(), b.finish())
    }

    /// Equal values reached by different arithmetic hash alike (both hashes), as `Eq` needs;
    /// and different big values of one size are told apart by the full hash.
    #[test]
    fn hashes_agree_with_equality() {
        let two64 = BigInt::from(1u128 << 64);
        let a = Q::big(BigRational::new(two64.clone() * 3, BigInt::from(7)));
        // 3 * 2^64 / 7 as (2^64 / 7) * 3 and as (6 * 2^64 / 14).
        let b = &Q::big(BigRational::new(two64.clone(), BigInt::from(7))) * &Q::int(3);
        let c = Q::big(BigRational::new(two64.clone() * 6, BigInt::from(14)));
        assert_eq!(a, b);
        assert_eq!(a, c);
        assert_eq!(hashes(&a), hashes(&b));
        assert_eq!(hashes(&a), hashes(&c));
        // A big product that comes back to a small value is small, and hashes as one.
        let d = &Q::big(BigRational::new(two64.clone(), BigInt::from(1)))
            * &Q::big(BigRational::new(BigInt::from(5), two64.clone()));
        assert_eq!(d, Q::int(5));
        assert_eq!(hashes(&d), hashes(&Q::int(5)));
        let e = Q::big(BigRational::new(two64.clone() * 3 + 1, BigInt::from(7)));
        assert_ne!(a, e);
        assert_ne!(hashes(&a).0, hashes(&e).0);
    }
}
