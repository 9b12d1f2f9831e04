//! Powers of plain polynomials by the multinomial theorem.
//!
//! `(c1 m1 + ... + ck mk)^n` is the sum over the exponent vectors `a` with `a1 + ... + ak = n`
//! of `n! / (a1! ... ak!) c1^a1 ... ck^ak m1^a1 ... mk^ak`: one term per vector, each formed
//! once. Repeated squaring formed every pair of terms of its last two factors and sorted them
//! (`(x + y + z)^60`: some 280,000 pairs of big coefficients, each reduced by a gcd, for 1,891
//! terms). The coefficients are integers over one common denominator `D^n` (`D` the least
//! common denominator of the `ci`), so no gcd is taken on the way; each result is reduced once.
//!
//! Only for sums of plain monomials (no trigonometric mode, no radical), whose products are
//! single terms; everything else, and powers whose number of exponent vectors passes the term
//! limit or whose coefficients would pass the digit limit, takes repeated squaring (which
//! refuses them as it always did).

use super::atoms::MonoRc;
use super::{charge, digits_of_bits, max_digits, term_limit, Mode, Scalar, ScalarError, Term, Q};
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Zero};
use std::sync::Arc;

/// How many terms are formed between two charges to the work budget (each charge also looks
/// at the cancel flag).
const CHARGE_EVERY: u64 = 64;

/// `base^n` by the multinomial theorem, or `None` when this path does not apply (see the
/// module docs); `n >= 2`.
pub(crate) fn pow(base: &[Term], n: u32) -> Option<Scalar> {
    if base.len() < 2 || n < 2 || !base.iter().all(|t| t.mode.is_unit() && t.rad == 1) {
        return None;
    }
    let count = vectors(base.len() as u64, u64::from(n))?;
    if count > term_limit() as u64 {
        return None;
    }
    let den = base.iter().fold(BigInt::one(), |l, t| {
        l.lcm(&t.coef.to_big().denom().clone())
    });
    let nums: Vec<BigInt> = base
        .iter()
        .map(|t| {
            let c = t.coef.to_big();
            c.numer() * (&den / c.denom())
        })
        .collect();
    // The coefficients' size, bounded before any is formed: `ci^ai` has at most `ai` times
    // the bits of `ci`, the multinomial coefficient at most `n log2 k` bits, `D^n` `n` times
    // those of `D`.
    let widest = nums
        .iter()
        .map(BigInt::bits)
        .max()
        .unwrap_or(0)
        .max(den.bits());
    let log_k = u64::from(64 - (base.len() as u64).leading_zeros());
    let bits = u64::from(n).saturating_mul(widest.saturating_add(log_k));
    if digits_of_bits(bits) > max_digits() {
        return None;
    }
    let mut e = Expansion {
        mode: base[0].mode.clone(),
        den_n: num_traits::pow(den, n as usize),
        powers: nums.iter().map(|c| powers_of(c, n)).collect(),
        monos: base.iter().map(|t| mono_powers(&t.mono, n)).collect(),
        out: Vec::with_capacity(count as usize),
        pending: 0,
        formed: 0,
    };
    if let Err(err) = e.expand(0, n, BigInt::one(), empty()) {
        return Some(Scalar::error(err));
    }
    if let Err(err) = charge(e.pending) {
        return Some(Scalar::error(err));
    }
    Some(Scalar::from_terms(e.out))
}

/// The number of exponent vectors `a` of `k` entries summing to `n`: `C(n + k - 1, k - 1)`;
/// `None` past `u64`.
fn vectors(k: u64, n: u64) -> Option<u64> {
    let mut c: u128 = 1;
    for i in 1..k {
        // C(n + i, i) = C(n + i - 1, i - 1) (n + i) / i, exact at every step.
        c = c.checked_mul(u128::from(n + i))? / u128::from(i);
        if c > u128::from(u64::MAX) {
            return None;
        }
    }
    u64::try_from(c).ok()
}

/// `c^0, ..., c^n`.
fn powers_of(c: &BigInt, n: u32) -> Vec<BigInt> {
    let mut v = Vec::with_capacity(n as usize + 1);
    v.push(BigInt::one());
    for j in 1..=n as usize {
        let next = &v[j - 1] * c;
        v.push(next);
    }
    v
}

/// `m^0, ..., m^n`; `None` for a power whose exponent overflows.
fn mono_powers(m: &MonoRc, n: u32) -> Vec<Option<MonoRc>> {
    (0..=n)
        .map(|j| {
            let v: Option<Vec<_>> = m
                .iter()
                .map(|(s, e)| e.checked_mul(j).map(|e| (s.clone(), e)))
                .collect();
            v.map(|v| if j == 0 { empty() } else { Arc::from(v) })
        })
        .collect()
}

fn empty() -> MonoRc {
    super::atoms::empty_mono()
}

/// The state of one expansion: the powers of each term's numerator and monomial, and the
/// terms formed so far.
struct Expansion {
    /// The unit mode, shared by every term.
    mode: Mode,
    den_n: BigInt,
    powers: Vec<Vec<BigInt>>,
    monos: Vec<Vec<Option<MonoRc>>>,
    out: Vec<Term>,
    /// Work not charged yet.
    pending: u64,
    /// Terms formed, for charging every [`CHARGE_EVERY`].
    formed: u64,
}

impl Expansion {
    /// Every term whose exponents of the base's terms before `i` are fixed (their product so
    /// far `coef mono`, `rest` of the exponent left to give out), term `i` given `j` of it.
    fn expand(
        &mut self,
        i: usize,
        rest: u32,
        coef: BigInt,
        mono: MonoRc,
    ) -> Result<(), ScalarError> {
        if i + 1 == self.powers.len() {
            self.pending += mul_units(&coef, &self.powers[i][rest as usize]);
            return self.push(
                &coef * &self.powers[i][rest as usize],
                mul(&mono, &self.monos[i][rest as usize])?,
            );
        }
        // C(rest, j), from C(rest, j - 1) exactly.
        let mut binom = BigInt::one();
        for j in 0..=rest {
            if j > 0 {
                binom = binom * (rest - j + 1) / j;
            }
            self.pending += mul_units(&coef, &self.powers[i][j as usize]);
            let c = &coef * &binom * &self.powers[i][j as usize];
            let m = mul(&mono, &self.monos[i][j as usize])?;
            self.expand(i + 1, rest - j, c, m)?;
        }
        Ok(())
    }

    fn push(&mut self, num: BigInt, mono: MonoRc) -> Result<(), ScalarError> {
        // A term's work: one unit, one per symbol of its monomial, one per word of its
        // coefficient (its product and reduction).
        self.pending += 1 + mono.len() as u64 + num.bits() / 64;
        self.formed += 1;
        if self.formed.is_multiple_of(CHARGE_EVERY) {
            charge(std::mem::take(&mut self.pending))?;
        }
        if num.is_zero() {
            return Ok(());
        }
        let coef = if self.den_n.is_one() {
            Q::big(BigRational::from_integer(num))
        } else {
            Q::big(BigRational::new(num, self.den_n.clone()))
        };
        self.out.push(Term {
            mode: self.mode.clone(),
            mono,
            rad: 1,
            coef,
        });
        Ok(())
    }
}

/// The work of multiplying two big integers: the product of their word counts (schoolbook),
/// nothing for machine words. With the digit limit's thousand-word coefficients a product
/// takes some fifty microseconds: a term limit's worth of them is charged, not free.
fn mul_units(a: &BigInt, b: &BigInt) -> u64 {
    (a.bits() / 64).saturating_mul(b.bits() / 64)
}

/// `a * b` for a monomial `b` that may have overflowed.
fn mul(a: &MonoRc, b: &Option<MonoRc>) -> Result<MonoRc, ScalarError> {
    b.as_ref()
        .and_then(|b| super::atoms::mono_mul(a, b))
        .ok_or_else(|| ScalarError::OutOfRange("exponent too large".into()))
}

#[cfg(test)]
mod tests {
    use super::super::Context;
    use crate::Scalar;
    use num_bigint::BigInt;
    use num_rational::BigRational;

    fn q(n: i64, d: i64) -> Scalar {
        Scalar::rational(BigRational::new(BigInt::from(n), BigInt::from(d)))
    }

    /// Sums of plain monomials with rational coefficients: ones whose products never meet,
    /// and ones whose products do (`x^2 * y^2 = (x y)^2`), with a constant term.
    fn bases() -> Vec<Scalar> {
        let (x, y, z) = (Scalar::sym("x"), Scalar::sym("y"), Scalar::sym("z"));
        vec![
            &x + &y,
            &(&x + &(&q(2, 1) * &y)) - &(&q(3, 5) * &z),
            &(&(&x * &x) + &(&x * &y)) + &(&y * &y),
            &(&(&(&q(1, 2) * &x) - &(&y * &z)) + &(&q(4, 7) * &(&z * &z))) - &q(1, 3),
        ]
    }

    /// `x^n` as `n - 1` general products (the path repeated squaring takes term by term).
    fn product_power(x: &Scalar, n: u32) -> Scalar {
        let mut acc = x.clone();
        for _ in 1..n {
            acc = &acc * x;
        }
        acc
    }

    #[test]
    fn powers_of_plain_polynomials_equal_repeated_products_and_evaluate_as_the_base_raised() {
        let _ctx = Context::new().enter();
        // A small seeded generator: points in [-1.5, 1.5].
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % 3001) as f64 / 1000.0 - 1.5
        };
        for base in bases() {
            let t = base.terms().unwrap();
            let abs_base = |p: &[(&str, f64)]| -> f64 {
                t.iter()
                    .map(|t| {
                        let one = Scalar::from_terms(vec![t.clone()]);
                        one.eval_at(p).unwrap().abs()
                    })
                    .sum()
            };
            for n in 2..=9u32 {
                let fast = super::pow(t, n).expect("a plain polynomial takes this path");
                // Exactly the general product's value.
                assert_eq!(fast, product_power(&base, n), "({base})^{n}");
                // And numerically the base's value raised to n, at random points. Each term
                // of the expansion is formed with at most n + 3 roundings and the sum adds one
                // per term (at most 55 here), so the error is below (n + 58) eps times the sum
                // of the terms' magnitudes, itself at most (sum |c_i m_i|)^n: 1e-12 of that
                // leaves a margin of some 50.
                for _ in 0..5 {
                    let p = [("x", next()), ("y", next()), ("z", next())];
                    let want = base.eval_at(&p).unwrap().powi(n as i32);
                    let got = fast.eval_at(&p).unwrap();
                    let scale = abs_base(&p).powi(n as i32).max(1.0);
                    assert!(
                        (got - want).abs() <= 1e-12 * scale,
                        "({base})^{n} at {p:?}: {got} vs {want}"
                    );
                }
            }
        }
    }

    #[test]
    fn powers_this_path_does_not_take() {
        let _ctx = Context::new().with_term_limit(100).enter();
        let (x, y) = (Scalar::sym("x"), Scalar::sym("y"));
        // Past the term limit (C(20 + 2, 2) = 231 exponent vectors): left to repeated squaring.
        let three = &(&x + &y) + &Scalar::sym("z");
        assert!(super::pow(three.terms().unwrap(), 20).is_none());
        // A radical or a trigonometric term: products that are not single terms.
        let rad = &x + &Scalar::int(2).sqrt();
        assert!(super::pow(rad.terms().unwrap(), 3).is_none());
        let trig = &y + &Scalar::sym("t").cos();
        assert!(super::pow(trig.terms().unwrap(), 3).is_none());
        // And through `pow` the same values as products.
        assert_eq!(rad.pow(3), product_power(&rad, 3));
        assert_eq!(trig.pow(3), product_power(&trig, 3));
    }
}
