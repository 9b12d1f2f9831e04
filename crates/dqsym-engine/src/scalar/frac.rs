//! Quotients of canonical scalars, for results that divide by an expression: screw axes and
//! moments (divided by sin(theta/2)), centres of planar displacements.
//!
//! A [`Frac`] is not canonical: `a/b` and `(a k)/(b k)` are different representations of one
//! value. Equality is therefore decided by cross-multiplication, which is exact on canonical
//! scalars. Constant denominators are always divided out, and a numerator that is a constant
//! multiple of the denominator collapses to that constant, so the common cases print simply.

use super::{Scalar, ScalarError};
use num_traits::Zero;

/// `num / den` with `den != 0`.
#[derive(Clone, Debug)]
pub struct Frac {
    num: Scalar,
    den: Scalar,
}

impl Frac {
    /// `num / den`, reduced where that is cheap and exact.
    pub fn new(num: Scalar, den: Scalar) -> Result<Frac, ScalarError> {
        let num = num.check()?;
        let den = den.check()?;
        if den.is_zero() {
            return Err(ScalarError::DivisionByZero);
        }
        if den.is_constant() {
            return Ok(Frac::from(num.try_div(&den)?));
        }
        if let Some(k) = constant_ratio(&num, &den) {
            return Ok(Frac::from(k));
        }
        Ok(Frac { num, den })
    }

    /// The numerator.
    pub fn num(&self) -> &Scalar {
        &self.num
    }

    /// The denominator (1 when the value is a plain scalar).
    pub fn den(&self) -> &Scalar {
        &self.den
    }

    /// The value as a scalar, when the denominator is 1.
    pub fn as_scalar(&self) -> Option<&Scalar> {
        (self.den == Scalar::int(1)).then_some(&self.num)
    }

    /// `self + other`. When one denominator is a constant multiple of the other (`s` and
    /// `2 s`), the sum keeps the first one rather than their product.
    pub fn add(&self, other: &Frac) -> Result<Frac, ScalarError> {
        if self.den == other.den {
            return Frac::new(&self.num + &other.num, self.den.clone());
        }
        if let Some(k) = constant_ratio(&other.den, &self.den).filter(Scalar::is_constant) {
            // other = b / (k d) = (b / k) / d.
            return Frac::new(&self.num + other.num.try_div(&k)?, self.den.clone());
        }
        Frac::new(
            &self.num * &other.den + &other.num * &self.den,
            &self.den * &other.den,
        )
    }

    /// `self - other`.
    pub fn sub(&self, other: &Frac) -> Result<Frac, ScalarError> {
        self.add(&other.neg())
    }

    /// `-self`.
    pub fn neg(&self) -> Frac {
        Frac {
            num: -&self.num,
            den: self.den.clone(),
        }
    }

    /// `self * other`.
    pub fn mul(&self, other: &Frac) -> Result<Frac, ScalarError> {
        Frac::new(&self.num * &other.num, &self.den * &other.den)
    }

    /// `self / other`.
    pub fn div(&self, other: &Frac) -> Result<Frac, ScalarError> {
        Frac::new(&self.num * &other.den, &self.den * &other.num)
    }

    /// The derivative by the symbol `x`, by the quotient rule.
    pub fn diff(&self, x: &str) -> Result<Frac, ScalarError> {
        let (dn, dd) = (self.num.diff(x), self.den.diff(x));
        if dd.is_zero() {
            return Frac::new(dn, self.den.clone());
        }
        Frac::new(dn * &self.den - &self.num * dd, &self.den * &self.den)
    }

    /// The value under a binding of symbols.
    pub fn eval(&self, env: &dyn Fn(&str) -> Option<f64>) -> Result<f64, ScalarError> {
        Ok(self.num.eval(env)? / self.den.eval(env)?)
    }
}

impl From<Scalar> for Frac {
    fn from(s: Scalar) -> Frac {
        Frac {
            num: s,
            den: Scalar::int(1),
        }
    }
}

/// Equal values: `a/b == c/d` iff `a d == c b`, exact on canonical scalars.
impl PartialEq for Frac {
    fn eq(&self, other: &Frac) -> bool {
        &self.num * &other.den == &other.num * &self.den
    }
}

/// Cross-multiplication is an equivalence: canonical scalars form an integral domain (polynomials
/// in symbols and in cos, sin of angles modulo cos^2 + sin^2 = 1, over rationals and radicals),
/// and denominators are never zero.
impl Eq for Frac {}

/// `k` when `num == k den` and `k` is read off term by term: for a one-term denominator
/// `c sqrt(r) m M` (monomial `m`, mode `M`), each numerator term with mode `M` divided by it;
/// otherwise a constant ratio of the leading terms. The candidate is always checked by
/// multiplying back, so a wrong guess only means no reduction.
fn constant_ratio(num: &Scalar, den: &Scalar) -> Option<Scalar> {
    let (n, d) = (num.terms().ok()?, den.terms().ok()?);
    if num.is_zero() {
        return Some(Scalar::int(0));
    }
    let unit = |rad: u64, coef: &super::Q, mono: super::MonoRc| {
        Scalar::from_terms_sorted(vec![super::Term {
            mode: super::Mode::unit(),
            mono,
            rad,
            coef: coef.clone(),
        }])
    };
    let candidate = if let [b] = d {
        let inv = unit(b.rad, &b.coef, Vec::new().into()).recip();
        let mut k = Scalar::int(0);
        for t in n.iter().filter(|t| t.mode == b.mode) {
            let mono = mono_div(&t.mono, &b.mono)?;
            k = k + unit(t.rad, &t.coef, mono) * &inv;
        }
        k
    } else {
        let (a, b) = (n.first()?, d.first()?);
        if a.mode != b.mode || a.mono != b.mono {
            return None;
        }
        unit(a.rad, &a.coef, Vec::new().into())
            .try_div(&unit(b.rad, &b.coef, Vec::new().into()))
            .ok()?
    };
    (&candidate * den == *num).then_some(candidate)
}

/// `a / b` for monomials, when `b` divides `a`.
fn mono_div(a: &[(super::Sym, u32)], b: &[(super::Sym, u32)]) -> Option<super::MonoRc> {
    let mut out: Vec<(super::Sym, u32)> = a.to_vec();
    for (s, e) in b {
        let pos = out.iter().position(|(x, _)| x == s)?;
        if out[pos].1 < *e {
            return None;
        }
        out[pos].1 -= e;
        if out[pos].1 == 0 {
            out.remove(pos);
        }
    }
    Some(out.into())
}
