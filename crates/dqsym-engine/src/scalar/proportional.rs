//! Scalars compared up to a nonzero rational factor, exactly: the report's entries that are
//! rational multiples of each other (a Jacobian column `1/2 k dq`, two entries in `q2 - q3`
//! and `q3 - q2`) are put in closed form once (see `app/fk.rs`).
//!
//! # Soundness
//! A canonical term vector times a nonzero rational `c` is canonical with the same keys
//! (mode, monomial, radical) and every coefficient times `c`: the terms stay sorted and
//! nonzero, and the canonical bases of the constant groups (`cyclo/`) are linear over the
//! rationals (`arith::mul` relies on the same for a product by a constant). The canonical
//! form is unique, so `x = c y` exactly when `x` and `y` have the same keys in the same order
//! and `x_i = c y_i` for every term `i`. Nothing is evaluated in floating point.

use super::{Scalar, Term, Q, SAMPLED_TERMS};
use std::hash::{Hash, Hasher};

/// A scalar as a hash-map key equal to its nonzero rational multiples: `ProportionalKey(x)
/// == ProportionalKey(y)` iff `x = c y` for a rational `c != 0` (zero and each error value
/// are equal only to themselves). Hashed as [`super::SampledKey`] is, by the number of terms
/// and at most [`SAMPLED_TERMS`] terms spread over the vector, each one's key and its
/// coefficient over the first term's (the same for every multiple); `Eq` compares every
/// term.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ProportionalKey<'a>(pub(crate) &'a Scalar);

impl ProportionalKey<'_> {
    /// The rational `c` with `self = c other` for keys known to be equal (a map's match): the
    /// ratio of the first coefficients, without comparing the other terms again (1 for zero
    /// and for errors).
    pub(crate) fn factor(&self, other: &ProportionalKey) -> Q {
        match (self.0.terms(), other.0.terms()) {
            (Ok([x0, ..]), Ok([y0, ..])) => &x0.coef * &y0.coef.recip(),
            _ => Q::ONE,
        }
    }

    /// The rational `c` with `self = c other`, when there is one (1 for equal scalars,
    /// zero and errors included).
    pub(crate) fn factor_over(&self, other: &ProportionalKey) -> Option<Q> {
        let (x, y) = match (self.0.terms(), other.0.terms()) {
            (Ok(x), Ok(y)) => (x, y),
            (Err(a), Err(b)) => return (a == b).then_some(Q::ONE),
            _ => return None,
        };
        if x.len() != y.len() {
            return None;
        }
        let c = self.factor(other);
        let same = |a: &Term, b: &Term| {
            a.mode == b.mode && a.mono == b.mono && a.rad == b.rad && a.coef == &c * &b.coef
        };
        x.iter().zip(y).all(|(a, b)| same(a, b)).then_some(c)
    }
}

impl PartialEq for ProportionalKey<'_> {
    fn eq(&self, other: &Self) -> bool {
        self.factor_over(other).is_some()
    }
}

impl Eq for ProportionalKey<'_> {}

impl Hash for ProportionalKey<'_> {
    fn hash<H: Hasher>(&self, h: &mut H) {
        match self.0.terms() {
            Ok(t) => {
                h.write_usize(t.len());
                let Some(first) = t.first() else {
                    return;
                };
                let unit = first.coef.recip();
                let step = t.len().div_ceil(SAMPLED_TERMS).max(1);
                for term in t.iter().step_by(step) {
                    term.mode.hash(h);
                    term.mono.hash(h);
                    h.write_u64(term.rad);
                    (&term.coef * &unit).hash_words(h);
                }
            }
            Err(e) => e.hash(h),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{ProportionalKey, Q};
    use crate::Scalar;
    use num_rational::BigRational;
    use std::collections::HashMap;
    use std::hash::{BuildHasher, RandomState};

    fn rat(n: i64, d: i64) -> Scalar {
        Scalar::rational(BigRational::new(n.into(), d.into()))
    }

    /// Multiples by rationals of every size and sign (small and big coefficients, pi
    /// offsets in a cyclotomic basis, radicals) are one key with the factor they were made
    /// with; scalars that differ by a term, by a coefficient the hash does not sample, or by
    /// an irrational factor are other keys.
    #[test]
    fn multiples_are_one_key_with_their_factor() {
        let (a, t, u) = (Scalar::sym("a"), Scalar::sym("t"), Scalar::sym("u"));
        let pi7 = Scalar::pi() * rat(1, 7);
        let x = (a.clone() * t.cos() + (u.clone() + pi7).sin() * Scalar::int(3).sqrt() - rat(5, 3))
            .pow(3);
        let n = x.terms().map(<[_]>::len).unwrap_or(0);
        assert!(n > 2 * super::SAMPLED_TERMS, "{n} terms");
        let state = RandomState::new();
        let big = BigRational::new(
            "123456789012345678901234567890".parse().expect("integer"),
            7.into(),
        );
        for (c, q) in [
            (rat(-1, 1), Q::int(-1)),
            (rat(1, 2), Q::new(1, 2)),
            (rat(-3, 4), Q::new(-3, 4)),
            (Scalar::rational(big.clone()), Q::big(big)),
        ] {
            let y = x.clone() * c;
            let (kx, ky) = (ProportionalKey(&x), ProportionalKey(&y));
            assert_eq!(kx, ky);
            assert_eq!(state.hash_one(kx), state.hash_one(ky));
            assert_eq!(ky.factor_over(&kx), Some(q.clone()));
            assert_eq!(ky.factor(&kx), q);
            // Independently: the factor times x is y.
            assert_eq!(Scalar::rational(q.to_big()) * x.clone(), y);
        }
        // The second term doubled (the sample reads every `ceil(n/4)`-th term from the first,
        // so not that one), another term, one term more, an irrational multiple, a symbolic
        // one: other keys.
        let second = Scalar::from_terms(vec![x.terms().expect("terms")[1].clone()]);
        let others = [
            x.clone() + second,
            x.clone() + a.clone() * u.cos() * rat(1, 9),
            x.clone() + Scalar::int(1),
            x.clone() * Scalar::int(2).sqrt(),
            x.clone() * a.clone(),
        ];
        for y in &others {
            assert_ne!(ProportionalKey(&x), ProportionalKey(y), "{y:?}");
            assert_eq!(ProportionalKey(y).factor_over(&ProportionalKey(&x)), None);
        }
        // Zero is its own class; a map finds a multiple under its class's first entry.
        let zero = Scalar::int(0);
        assert_eq!(ProportionalKey(&zero), ProportionalKey(&zero));
        assert_ne!(ProportionalKey(&zero), ProportionalKey(&x));
        let mut m = HashMap::new();
        m.insert(ProportionalKey(&x), 0);
        m.insert(ProportionalKey(&zero), 1);
        let half = x.clone() * rat(-1, 2);
        assert_eq!(m.get(&ProportionalKey(&half)), Some(&0));
        assert_eq!(m.len(), 2);
    }
}
