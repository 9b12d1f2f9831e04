//! Squares of sums (issue 33): `k2^2 cos(u2)^2 - 2 k2 sin(w) cos(u2) + sin(w)^2` is
//! `(k2 cos(u2) - sin(w))^2`, which neither the regrouping (it expands the square) nor the
//! factorization of `cspoly.rs` (whose readings reduce `s^2 = 1 - c^2` for every angle at
//! once, and which takes no radicals) finds.
//!
//! The sum is read in its exponential form, a Laurent polynomial `f = sum c_e z^e` in
//! `z_s = e^{i s}` for the angle symbols and an ordinary polynomial in the length symbols
//! (one exponent vector per term: the lengths' powers, then the frequencies over a common
//! denominator), and its square root taken by the schoolbook algorithm in a total order of
//! the exponents compatible with their addition (lexicographic): the top term of `g` is the
//! square root of the top term of `f`, and each next term of `g` is the top term of the
//! remainder `f - g^2` divided by twice the top term of `g`, until the remainder vanishes or
//! its top falls below what a square root can reach (half the bottom exponent of `f`). This
//! runs in complex `f64`; a common monomial of every term is divided out first
//! (`k1 (cos p + sin r)^2`). The root found is read back as a real sum of cosines and sines
//! (the terms at `e` and at `e` with the frequencies negated are conjugate; when they are
//! conjugate up to a sign, `f` is minus a square), scaled so that its top sinusoid has
//! amplitude 1, each coefficient snapped to a rational times a square root, and the square
//! checked exactly (`k h^2 == f`, `k` rational) before the closed form of `h` is found; the
//! candidate is then checked against `f` like every other (`alt::best_alternative`).

use super::alt::{mul, neg, num, trig};
use super::expr::Expr;
use crate::scalar::{charge, Small, Sym, Term};
use crate::Scalar;
use num_integer::Integer;
use num_rational::BigRational as Rat;
use num_traits::{Signed, Zero};
use std::collections::BTreeMap;

/// The most terms a sum may have: the square of a sum of four sinusoids of distinct angles
/// has up to 4 + 4 * 3 * 2 = 28 Fourier terms (with radicals from offsets at pi/6, fewer
/// than twice as many distinct modes).
const MAX_TERMS: usize = 40;

/// The most terms of the root in exponential form (each real sinusoid is two).
const MAX_ROOT_TERMS: usize = 16;

/// The largest denominator of a snapped coefficient's square.
const MAX_DENOM: i64 = 10_000;

type Exps = Vec<i64>;

use super::roots::C;

/// The sum as exponent vectors over `lengths` then `angles` (frequencies times `den`).
struct Laurent {
    lengths: Vec<Sym>,
    angles: Vec<Sym>,
    den: i64,
    terms: BTreeMap<Exps, C>,
}

/// The candidate of this file for the canonical terms `t`, not yet checked against them; only
/// when `bound` (the cost of the form found before) leaves room for a square of a sum of two
/// terms: a power, an addition and two calls at least.
pub(super) fn candidates(t: &[Term], bound: usize) -> Vec<Expr> {
    if bound <= 4
        || t.len() < 3
        || t.len() > MAX_TERMS
        || t.iter()
            .any(|u| u.mode.freq.iter().any(|(s, _)| s.is_one()))
        || t.iter().all(|u| u.mode.freq.is_empty())
        || !super::trigfac::may_nest()
        || charge(t.len() as u64).is_err()
    {
        return Vec::new();
    }
    // The mean of `m k g^2` over the angles is `m k` times the sum of the squares of the
    // root's coefficients: never zero, so a square has a term without an angle (the PUMA's
    // rotation entries have none).
    if !t.iter().any(|u| u.mode.freq.is_empty()) || !even_spans(t) || !one_signed(t) {
        return Vec::new();
    }
    square(t).into_iter().collect()
}

/// Whether every length symbol's largest and smallest powers over the terms differ by an even
/// number: in `m g^2` (`m` a monomial) a symbol's top and bottom powers are those of `m`
/// plus twice those of `g`. One pass over the terms; rejects most sums at once (the PUMA's
/// entries, linear in their lengths).
fn even_spans(t: &[Term]) -> bool {
    let mut span: Vec<(&Sym, u32, u32)> = Vec::new();
    for u in t {
        for (s, p) in u.mono.iter() {
            match span.iter_mut().find(|(r, _, _)| *r == s) {
                Some((_, lo, hi)) => {
                    *lo = (*lo).min(*p);
                    *hi = (*hi).max(*p);
                }
                None => span.push((s, *p, *p)),
            }
        }
    }
    // A symbol missing from some term has power 0 there.
    span.iter().all(|(s, lo, hi)| {
        let lo = if t.iter().all(|u| u.mono.iter().any(|(r, _)| r == *s)) {
            *lo
        } else {
            0
        };
        (hi - lo) % 2 == 0
    })
}

/// A term for [`one_signed`]: amplitude, phase, sine or cosine, the lengths' indices and
/// powers, the angle symbols' indices and frequencies.
type SignTerm = (f64, f64, bool, Vec<(usize, i32)>, Vec<(usize, f64)>);

/// The points at which [`one_signed`] evaluates the sum.
const SIGN_POINTS: usize = 8;

/// Whether the sum takes one sign at a few pseudo-random points (lengths and angles in
/// `[-2, 2]`): a monomial `m` times `k g^2` is of one sign wherever `m` is, so the sign of
/// the monomial common to the terms is divided out. The sum is
/// evaluated to a relative error of about (terms) * 1e-16 of the magnitudes; a value below
/// 1e-9 of them counts as either sign.
fn one_signed(t: &[Term]) -> bool {
    let pi = std::f64::consts::PI;
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        -2.0 + 4.0 * (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut syms: Vec<&Sym> = Vec::new();
    for u in t {
        let names = u.mono.iter().map(|(s, _)| s);
        for s in names.chain(u.mode.freq.iter().map(|(s, _)| s)) {
            if !syms.contains(&s) {
                syms.push(s);
            }
        }
    }
    // The common monomial: each symbol at its smallest power over the terms.
    let common: Vec<(&Sym, i32)> = syms
        .iter()
        .map(|s| {
            let p = t
                .iter()
                .map(|u| u.mono.iter().find(|(r, _)| r == *s).map_or(0, |(_, p)| *p))
                .min()
                .unwrap_or(0);
            (*s, p as i32)
        })
        .collect();
    // Each term with its symbols as indices into `syms`: the points then take only floats.
    let index = |s: &Sym| syms.iter().position(|r| *r == s).unwrap_or(0);
    let mut terms: Vec<SignTerm> = Vec::with_capacity(t.len());
    for u in t {
        let Some(c) = u.coef.to_f64() else {
            return true;
        };
        terms.push((
            c * (u.rad as f64).sqrt(),
            pi * (*u.mode.pi.numer() as f64 / *u.mode.pi.denom() as f64),
            u.mode.sin,
            u.mono.iter().map(|(s, p)| (index(s), *p as i32)).collect(),
            u.mode
                .freq
                .iter()
                .map(|(s, k)| (index(s), *k.numer() as f64 / *k.denom() as f64))
                .collect(),
        ));
    }
    let common: Vec<(usize, i32)> = common.iter().map(|(s, p)| (index(s), *p)).collect();
    let (mut pos, mut negs) = (false, false);
    for _ in 0..SIGN_POINTS {
        let at: Vec<f64> = syms.iter().map(|_| next()).collect();
        let (mut v, mut scale) = (0.0f64, 0.0f64);
        for (amp, phase, sin, mono, freq) in &terms {
            let a = mono.iter().fold(*amp, |a, (i, p)| a * at[*i].powi(*p));
            let angle = freq.iter().fold(*phase, |x, (i, k)| x + at[*i] * k);
            v += a * if *sin { angle.sin() } else { angle.cos() };
            scale += a.abs();
        }
        let m: f64 = common.iter().map(|(i, p)| at[*i].powi(*p)).product();
        let v = v * m.signum();
        if v > 1e-9 * scale {
            pos = true;
        } else if v < -1e-9 * scale {
            negs = true;
        }
        if pos && negs {
            return false;
        }
    }
    !(pos && negs)
}

fn square(t: &[Term]) -> Option<Expr> {
    let mut f = laurent(t)?;
    let common = f.common_monomial();
    let root = f.root()?;
    let (k, h) = f.real_root(&root)?;
    // Checked exactly before the closed form of `h` is searched for.
    let x = Scalar::from_terms_sorted(t.to_vec());
    let hh = &h * &h;
    let ks = Scalar::rational(k.clone()) * f.monomial(&common);
    if (&ks * &hh).check().ok()? != x {
        return None;
    }
    let he = super::trigfac::nested_closed_form(&h).ok()?;
    // An even power: the base shown with no more negative terms than positive ones, the
    // positive ones first.
    let he = match he {
        Expr::Neg(e) => *e,
        Expr::Add(v) => {
            let negative = v.iter().filter(|e| matches!(e, Expr::Neg(_))).count();
            let mut v: Vec<Expr> = if 2 * negative > v.len() {
                v.into_iter().map(neg).collect()
            } else {
                v
            };
            v.sort_by_key(|e| matches!(e, Expr::Neg(_)));
            Expr::Add(v)
        }
        e => e,
    };
    // A rational factor of the base's closed form goes to `k` (the root of `sin(x)^10` is
    // found as `16 sin(x)^5`), and a power's exponent doubles: `sin(x)^10`, never
    // `1/256 (16 sin(x)^5)^2`.
    let (he, k) = match he {
        Expr::Mul(v) if v.iter().any(|e| matches!(e, Expr::Num(_))) => {
            let mut k = k;
            let mut rest = Vec::new();
            for e in v {
                match e {
                    Expr::Num(c) => k = k * &c * &c,
                    e => rest.push(e),
                }
            }
            if rest.is_empty() {
                return None;
            }
            let he = if rest.len() == 1 {
                rest.pop()?
            } else {
                Expr::Mul(rest)
            };
            (he, k)
        }
        he => (he, k),
    };
    let power = match he {
        Expr::Pow(b, p) => Expr::Pow(b, 2 * p),
        he => Expr::Pow(Box::new(he), 2),
    };
    let kf = if k.is_negative() {
        neg(num(-k))
    } else {
        num(k)
    };
    let mono = monomial_expr(&f.lengths, &common);
    Some(mul(kf, mul(mono, power)))
}

fn monomial_expr(lengths: &[Sym], e: &[i64]) -> Expr {
    let mut m = num(Rat::from_integer(1.into()));
    for (s, &p) in lengths.iter().zip(e) {
        let a = Expr::Sym(s.clone());
        match p {
            0 => {}
            1 => m = mul(m, a),
            p => m = mul(m, Expr::Pow(Box::new(a), p as u32)),
        }
    }
    m
}

/// The terms in exponential form; `None` past `f64` or `i64`.
fn laurent(t: &[Term]) -> Option<Laurent> {
    let mut lengths: Vec<Sym> = Vec::new();
    let mut angles: Vec<Sym> = Vec::new();
    let mut den = 1i64;
    for u in t {
        for (s, _) in u.mono.iter() {
            if !lengths.contains(s) {
                lengths.push(s.clone());
            }
        }
        for (s, k) in u.mode.freq.iter() {
            if !angles.contains(s) {
                angles.push(s.clone());
            }
            den = den.lcm(k.denom());
        }
    }
    lengths.sort();
    angles.sort();
    // Twice the common denominator: the root's frequencies are half of the sum's.
    let den = den.checked_mul(2)?;
    let pi = std::f64::consts::PI;
    let mut terms: BTreeMap<Exps, C> = BTreeMap::new();
    for u in t {
        let mut e = vec![0i64; lengths.len() + angles.len()];
        for (s, p) in u.mono.iter() {
            let i = lengths.binary_search(s).ok()?;
            e[i] = i64::from(*p);
        }
        for (s, k) in u.mode.freq.iter() {
            let i = angles.binary_search(s).ok()?;
            e[lengths.len() + i] = k.numer().checked_mul(den / k.denom())?;
        }
        let amp = u.coef.to_f64()? * (u.rad as f64).sqrt();
        // cos(m.x + phase) with the sine a quarter turn behind.
        let off = *u.mode.pi.numer() as f64 / *u.mode.pi.denom() as f64;
        let phase = pi * off - if u.mode.sin { pi / 2.0 } else { 0.0 };
        if u.mode.freq.is_empty() {
            let v = terms.entry(e).or_insert(C(0.0, 0.0));
            *v = v.add(C(amp * phase.cos(), 0.0));
            continue;
        }
        let half = amp / 2.0;
        let up = C(half * phase.cos(), half * phase.sin());
        let down = C(up.0, -up.1);
        let v = terms.entry(e.clone()).or_insert(C(0.0, 0.0));
        *v = v.add(up);
        let n = lengths.len();
        let mut d = e;
        d[n..].iter_mut().for_each(|k| *k = -*k);
        let v = terms.entry(d).or_insert(C(0.0, 0.0));
        *v = v.add(down);
    }
    if !terms.values().all(|c| c.0.is_finite() && c.1.is_finite()) {
        return None;
    }
    Some(Laurent {
        lengths,
        angles,
        den,
        terms,
    })
}

impl Laurent {
    /// The terms' values below which a coefficient is taken as zero: the sum is built from
    /// its terms to a relative error of a few units of `f64` (1e-16) each, and the root's
    /// recurrence divides by the top coefficient, of the size of the others for the sums of a
    /// few unit sinusoids looked for here; 1e-9 of the total magnitude is far above that
    /// error and far below any coefficient of a sum with rationals of small denominators.
    fn tol(&self) -> f64 {
        1e-9 * self.terms.values().map(|c| c.abs()).sum::<f64>().max(1.0)
    }

    /// Divides out the lengths' monomial common to every term and returns it.
    fn common_monomial(&mut self) -> Exps {
        let n = self.lengths.len();
        let mut common: Exps = vec![i64::MAX; n];
        for e in self.terms.keys() {
            for (c, x) in common.iter_mut().zip(e) {
                *c = (*c).min(*x);
            }
        }
        if common.iter().any(|&c| c > 0) {
            self.terms = std::mem::take(&mut self.terms)
                .into_iter()
                .map(|(mut e, c)| {
                    e.iter_mut().zip(&common).for_each(|(x, c)| *x -= c);
                    (e, c)
                })
                .collect();
        }
        common
    }

    /// The lengths' monomial of exponents `e` as a scalar.
    fn monomial(&self, e: &[i64]) -> Scalar {
        let mut m = Scalar::int(1);
        for (s, &p) in self.lengths.iter().zip(e) {
            for _ in 0..p {
                m = m * Scalar::sym(s.name());
            }
        }
        m
    }

    /// The square root in exponential form (see the module doc), `None` when the sum is no
    /// square (a remainder left).
    fn root(&self) -> Option<Vec<(Exps, C)>> {
        let tol = self.tol();
        let mut rem = self.terms.clone();
        rem.retain(|_, c| c.abs() > tol);
        let (top, ftop) = rem.iter().next_back().map(|(e, c)| (e.clone(), *c))?;
        let bottom = rem.keys().next()?.clone();
        if top.iter().any(|x| x % 2 != 0) {
            return None;
        }
        let half: Exps = top.iter().map(|x| x / 2).collect();
        let g0 = ftop.sqrt();
        let mut g: Vec<(Exps, C)> = vec![(half.clone(), g0)];
        rem.remove(&top);
        let add = |a: &[i64], b: &[i64]| -> Exps { a.iter().zip(b).map(|(x, y)| x + y).collect() };
        loop {
            rem.retain(|_, c| c.abs() > tol);
            let Some((e, r)) = rem.iter().next_back().map(|(e, c)| (e.clone(), *c)) else {
                return Some(g);
            };
            // The next exponent of the root; below half the bottom of `f` no root reaches.
            let n: Exps = e.iter().zip(&half).map(|(x, y)| x - y).collect();
            let twice: Exps = n.iter().map(|x| 2 * x).collect();
            if twice < bottom
                || n[..self.lengths.len()].iter().any(|&x| x < 0)
                || g.len() >= MAX_ROOT_TERMS
            {
                return None;
            }
            charge((g.len() + 1) as u64).ok()?;
            let c = r.div(g0.scale(2.0));
            // rem -= (2 g + c z^n) c z^n.
            for (ge, gc) in &g {
                let v = rem.entry(add(ge, &n)).or_insert(C(0.0, 0.0));
                *v = v.sub(gc.mul(c).scale(2.0));
            }
            let v = rem.entry(twice).or_insert(C(0.0, 0.0));
            *v = v.sub(c.mul(c));
            g.push((n, c));
        }
    }

    /// The root as a real sum `h` with `f = k h^2` (`k` rational, the top sinusoid of `h` of
    /// amplitude 1), each coefficient snapped; `None` when it is not real (up to a factor `i`)
    /// or a coefficient is not a rational times a square root.
    fn real_root(&self, g: &[(Exps, C)]) -> Option<(Rat, Scalar)> {
        let n = self.lengths.len();
        let conj = |e: &Exps| -> Exps {
            let mut d = e.clone();
            d[n..].iter_mut().for_each(|k| *k = -*k);
            d
        };
        let map: BTreeMap<&Exps, C> = g.iter().map(|(e, c)| (e, *c)).collect();
        let scale: f64 = g.iter().map(|(_, c)| c.abs()).sum();
        // Relative to the root's magnitude, as the remainder's tolerance.
        let tol = 1e-7 * scale;
        // Real (`c(e*) = conj c(e)`) or imaginary (`c(e*) = -conj c(e)`: `f = -h^2`).
        let mut sign: Option<f64> = None;
        for (e, c) in g {
            let d = map.get(&conj(e)).copied()?;
            let s = if (d.0 - c.0).abs() + (d.1 + c.1).abs() <= tol {
                1.0
            } else if (d.0 + c.0).abs() + (d.1 - c.1).abs() <= tol {
                -1.0
            } else {
                return None;
            };
            if *sign.get_or_insert(s) != s {
                return None;
            }
        }
        let sign = sign?;
        // `h = g` or `-i g`.
        let turn = |c: C| if sign > 0.0 { c } else { C(c.1, -c.0) };
        // Real terms: `a cos(m.x) + b sin(m.x)` per conjugate pair (`2 Re c`, `-2 Im c`),
        // `Re c` alone at a zero frequency.
        let mut real: Vec<(&Exps, f64, f64)> = Vec::new();
        for (e, c) in g {
            let c = turn(*c);
            let m = &e[n..];
            match m.iter().find(|k| **k != 0) {
                None => real.push((e, c.0, 0.0)),
                Some(k) if *k > 0 => real.push((e, 2.0 * c.0, -2.0 * c.1)),
                Some(_) => {}
            }
        }
        let top = real.iter().max_by(|a, b| a.0.cmp(b.0))?;
        let amp = top.1.hypot(top.2);
        let k = super::alt::small_rational(sign * amp * amp)?;
        if k.is_zero() || *k.denom() > MAX_DENOM.into() {
            return None;
        }
        let mut h = Scalar::zero();
        for (e, a, b) in real {
            let freq: Vec<(Sym, Small)> = self
                .angles
                .iter()
                .zip(&e[n..])
                .filter(|(_, k)| **k != 0)
                .map(|(s, k)| (s.clone(), Small::new(*k, self.den)))
                .collect();
            let mono = self.monomial(&e[..n]);
            for (x, sin) in [(a / amp, false), (b / amp, true)] {
                if x.abs() <= 1e-9 {
                    continue;
                }
                if freq.is_empty() && sin {
                    return None;
                }
                let c = snapped(x)?;
                let tr = if freq.is_empty() {
                    Scalar::int(1)
                } else {
                    trig(sin, freq.clone(), Small::zero()).to_scalar()
                };
                h = (&h + &(&(&c * &mono) * &tr)).check().ok()?;
            }
        }
        Some((k, h))
    }
}

/// `x` as a rational times a square root, `sign(x) sqrt(p/q)` with `x^2 = p/q` of a small
/// denominator; `None` otherwise.
fn snapped(x: f64) -> Option<Scalar> {
    let q = super::alt::small_rational(x * x)?;
    if !q.is_positive() || *q.denom() > MAX_DENOM.into() || q.numer().bits() > 40 {
        return None;
    }
    let r = Scalar::rational(q).sqrt().check().ok()?;
    Some(if x < 0.0 { -r } else { r })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_root_of_a_square_in_exponential_form_squares_back() {
        let (k, p, r) = (Scalar::sym("k"), Scalar::sym("p"), Scalar::sym("r"));
        let g = &(&k * &p.cos()) + &r.sin();
        let f = &g * &g;
        let t = f.terms().expect("terms");
        let l = laurent(t).expect("laurent");
        assert_eq!(l.angles.len(), 2);
        let root = l.root().expect("a square");
        let (q, h) = l.real_root(&root).expect("real");
        assert_eq!(&(Scalar::rational(q) * &h) * &h, f);
    }
}
