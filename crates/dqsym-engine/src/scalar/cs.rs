//! The other exact form of a kinematic expression: a polynomial in the cosines and sines of the
//! angle symbols, each `cos(x)` and `sin(x)` a plain placeholder symbol.
//!
//! The canonical Fourier form is compact for products that share angles (a planar arm, the
//! PUMA) but a product of `n` factors in distinct angles has `2^(n-1)` Fourier modes where the
//! polynomial has one monomial: the 4x4 pose of a 6R chain with every DH parameter symbolic has
//! about 300,000 Fourier terms and 1,595 monomials. Link matrices hold only `cos x`, `sin x` of
//! their own angles, so their product is multilinear in the placeholders and needs no
//! `cos^2 + sin^2 = 1` reduction: equal polynomials are equal values, and two polynomials that
//! differ may still be equal values only through that identity (which this form does not
//! apply). The placeholder names (`cos(theta1)`) cannot be written in the language, so they
//! never meet a user's symbol.

use super::{Mode, Scalar, Term, Trig};

/// The placeholder symbol standing for `cos(x)` (or `sin(x)`).
pub fn trig_placeholder(x: &str, f: Trig) -> Scalar {
    Scalar::sym(&trig_placeholder_name(x, f))
}

/// The name of [`trig_placeholder`]'s symbol: `cos(x)`.
pub(crate) fn trig_placeholder_name(x: &str, f: Trig) -> String {
    format!("{}({x})", f.name())
}

/// The angle symbol and function of a placeholder name: `("theta1", Trig::Cos)` for
/// `cos(theta1)`.
pub fn parse_trig_placeholder(name: &str) -> Option<(&str, Trig)> {
    let (kind, rest) = name.split_once('(')?;
    let x = rest.strip_suffix(')')?;
    match kind {
        "cos" => Some((x, Trig::Cos)),
        "sin" => Some((x, Trig::Sin)),
        _ => None,
    }
}

impl Scalar {
    /// The same value as a polynomial in placeholders `cos(x)`, `sin(x)` (see
    /// [`trig_placeholder`]): every mode `cos(k1 x1 + ... + c pi)` is expanded with the
    /// angle-sum formulas, the pi part exactly. `None` when a frequency is not an integer (a half
    /// angle) or is above 8 in magnitude, or for an error value.
    pub fn to_cos_sin_polynomial(&self) -> Option<Scalar> {
        let terms = self.terms().ok()?;
        // Terms are sorted by mode first: one expansion per mode, times the sum of its
        // coefficients (still sorted with the mode made the unit), and the products summed
        // pairwise, so that no sum grows one term at a time.
        let mut parts = Vec::new();
        let mut cache = TrigCache::new();
        for run in terms.chunk_by(|a, b| a.mode == b.mode) {
            let trig = mode_polynomial(&run[0].mode, &mut cache)?;
            let rest = Scalar::from_terms_sorted(
                run.iter()
                    .map(|t| Term {
                        mode: Mode::unit(),
                        ..t.clone()
                    })
                    .collect(),
            );
            parts.push(rest * trig);
        }
        while parts.len() > 1 {
            let mut next = Vec::with_capacity(parts.len().div_ceil(2));
            let mut it = parts.into_iter();
            while let Some(a) = it.next() {
                next.push(match it.next() {
                    Some(b) => a + b,
                    None => a,
                });
            }
            parts = next;
        }
        parts.pop().unwrap_or_else(|| Scalar::int(0)).check().ok()
    }
}

/// The largest multiple `k` of an angle symbol `cos(k x)` may hold.
const MAX_MULTIPLE: i64 = 8;

/// `(cos, sin)` of the sums `k1 x1 + ... + kj xj` already expanded, by their terms.
type TrigCache = std::collections::HashMap<Vec<(String, i64)>, (Scalar, Scalar)>;

/// `cos` or `sin` of a mode's angle as a placeholder polynomial; the expansions of the
/// angle's leading sums are shared through `cache` (`theta1 + theta2` serves `theta1 +
/// theta2 - theta4`, and `cos` and `sin` of one angle are one expansion).
fn mode_polynomial(m: &Mode, cache: &mut TrigCache) -> Option<Scalar> {
    if m.is_unit() {
        return Some(Scalar::int(1));
    }
    // (C, S) = (cos, sin) of the part so far.
    let (mut c, mut s) = (Scalar::int(1), Scalar::int(0));
    let mut key = Vec::new();
    for (x, k) in m.freq.iter() {
        // Integer multiples only, and small ones: k x is |k| angle additions of +-x.
        if *k.denom() != 1 || k.numer().abs() > MAX_MULTIPLE || x.is_one() {
            return None;
        }
        key.push((x.name().to_string(), *k.numer()));
        if let Some((kc, ks)) = cache.get(&key) {
            (c, s) = (kc.clone(), ks.clone());
            continue;
        }
        let cx = trig_placeholder(x.name(), Trig::Cos);
        let sx = trig_placeholder(x.name(), Trig::Sin);
        // sin(-x) = -sin(x).
        let sx = if *k.numer() < 0 { -sx } else { sx };
        for _ in 0..k.numer().abs() {
            let c2 = c.clone() * &cx - s.clone() * &sx;
            s = s * &cx + c * &sx;
            c = c2;
        }
        cache.insert(key.clone(), (c.clone(), s.clone()));
    }
    // The exact pi multiple last.
    if *m.pi.numer() != 0 {
        let offset = Scalar::pi()
            * Scalar::rational(super::BigRational::new(
                (*m.pi.numer()).into(),
                (*m.pi.denom()).into(),
            ));
        let (co, so) = (offset.cos(), offset.sin());
        let c2 = c.clone() * &co - s.clone() * &so;
        s = s * &co + c * &so;
        c = c2;
    }
    Some(if m.sin { s } else { c })
}
