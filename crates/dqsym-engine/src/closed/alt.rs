//! Closed-form candidates beside the regrouped and whole-mode shapes, taken when cheaper:
//! - the harmonic form `a cos x + b sin x = R cos(x - phi)`, `R` a square root of a rational
//!   and `phi` a rational multiple of pi (`sin(x)/2 + sqrt(3) cos(x)/2 = cos(x - pi/6)`,
//!   `sqrt(2)/2 (cos t - sin t) = cos(t + pi/4)`);
//! - sum to product for two terms of equal weight (`sin(x - y) + sin(x + y) = 2 sin(x) cos(y)`);
//! - a polynomial in `cos x` alone or `sin x` alone (`sin^2 = 1 - cos^2` applied one way or
//!   the other), factored over the rationals by its rational roots (`1 - sin(x)^2 = cos(x)^2`,
//!   `(cos x - 1)^2 (cos x + 1)^3`);
//!   a pair of the roots 1 and -1 also as `-sin(x)^2` (`sin(x)^4 (cos x + 1)`);
//! - a sum of such polynomials in distinct angles, each in cos or sin, constants merged
//!   (`cos(a + b) cos(a - b) = cos(a)^2 - sin(b)^2`);
//! - a product of cosines and sines of multiples of one angle, peeled off by exact division
//!   of the Fourier sum (`cos(1) cos(2) ... cos(512)`, Morrie's `cos x cos 2x cos 4x`);
//! - products of cosines and sines of one angle with different offsets, from the roots of the
//!   sum as a polynomial in `e^{i x}` (`roots.rs`: `cos(x) cos(x - pi/14)`).
//!
//! Every candidate is checked exactly against its input before it is offered.

use super::expr::{Angle, Expr};
use crate::scalar::atoms::{freq_combine, Small};
use crate::scalar::{Sym, Term};
use crate::Scalar;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational as Rat;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::collections::BTreeMap;

/// The largest multiple `k` of `cos(k x)` expanded as a polynomial in `cos x`, `sin x`.
const MAX_MULTIPLE: i64 = 24;

/// The largest number of terms a scalar may have for these candidates to be tried.
const MAX_TERMS: usize = 48;

/// The largest number of terms a sum may have to be tried as a product of cosines and sines.
const MAX_PRODUCT_TERMS: usize = 4096;

/// The cheapest candidate that equals `x`, if it is [`shorter`] than `than` (the form found
/// before).
///
/// Candidates are taken in the order of [`choice_key`], the first that equals `x` wins; only
/// those shorter than `than` are checked against `x`: the keys are sorted, so when the first
/// candidate equal to `x` is not shorter than `than`, no candidate shorter than `than` equals
/// `x`, and both ways give `than`.
pub(super) fn best_alternative(x: &Scalar, than: &Expr) -> Option<Expr> {
    best_alternative_below(x, than, None)
}

/// [`best_alternative`] for a search whose result is taken only when [`shorter`] than a form
/// found elsewhere, whose [`choice_key`]'s first two parts are `cap`: only the candidates
/// strictly below both `than` and `cap` are checked against `x`.
///
/// The result is the same as [`best_alternative`]'s whenever either is strictly below `cap`,
/// and neither is otherwise. The candidates are made exactly as without `cap` (every one of
/// them, whatever its cost: a candidate above `cap` may still yield one below it, `extra.rs`
/// taking a common factor out of it), and sorted by their keys; the keys strictly below
/// `min(than, cap)` are a prefix of that order (keys are compared by their first two parts
/// first). So when the first candidate equal to `x` below `than` (the answer without `cap`)
/// is below `cap`, it lies in that prefix and is its first candidate equal to `x`; when it
/// is not below `cap` (or there is none), no candidate of the prefix equals `x`, and both
/// answers are `None` or not below `cap`. Only the exact checks of the candidates between
/// `cap` and `than` are saved (each expands a candidate: the Jaco-style arm's form as given
/// checked several candidates of a few hundred operations that its shifted form of about a
/// hundred beats).
pub(super) fn best_alternative_below(
    x: &Scalar,
    than: &Expr,
    cap: Option<(usize, usize)>,
) -> Option<Expr> {
    let mut cands = unsorted_candidates(x);
    // Products of sinusoids of mixed angles, sums split into parts (`trigfac.rs`): made only
    // when a lower bound of their cost is below the form found before.
    if let Ok(t) = x.terms() {
        // The cost the candidates must be below, counted once for both. Only candidates of
        // sums with a trigonometric term use it (`trigfac.rs`, `square.rs` and `extra.rs`'s
        // split by angles make none of a polynomial): a polynomial's is not counted (the
        // symbolic 6R's matrix in cosine and sine placeholders: 0.7 M instructions counting
        // the costs of forms of thousands of operations, twice each).
        let bound = if t.iter().all(|u| u.mode.freq.is_empty()) {
            0
        } else {
            full_cost(than).0
        };
        cands.extend(super::trigfac::candidates(t, bound));
        // Squares of sums, common factors, sums split by their angles' symbols (`extra.rs`).
        let more = super::extra::candidates(t, than, &cands, bound);
        cands.extend(more);
    }
    if cands.is_empty() {
        return None;
    }
    let bound = choice_key(than);
    let bound = (bound.0, bound.1);
    let bound = cap.map_or(bound, |c| c.min(bound));
    let mut cands: Vec<_> = cands
        .into_iter()
        .map(|e| (choice_key(&e), e))
        .filter(|(k, _)| (k.0, k.1) < bound)
        .collect();
    // Stable: on equal keys the earlier candidate is taken.
    cands.sort_by_key(|(k, _)| *k);
    cands
        .into_iter()
        .map(|(_, e)| e)
        .find(|e| e.to_scalar() == *x)
}

/// Every candidate for `x`, cheapest first ([`choice_key`]), not yet checked against it.
pub(super) fn candidates(x: &Scalar) -> Vec<Expr> {
    let mut cands = unsorted_candidates(x);
    cands.sort_by_cached_key(choice_key);
    cands
}

/// Every candidate for `x` in the order they are made (on equal keys the earlier is taken).
fn unsorted_candidates(x: &Scalar) -> Vec<Expr> {
    let Ok(t) = x.terms() else {
        return Vec::new();
    };
    if t.is_empty() || t.len() > MAX_PRODUCT_TERMS || t.iter().all(|t| t.mode.is_unit()) {
        return Vec::new();
    }
    // First: on equal cost, constant factors in the order of their angles win.
    let mut cands = super::cprod::constant_products(t);
    if t.len() <= MAX_TERMS {
        cands.extend(harmonic(t));
        cands.extend(sum_to_product(t));
        cands.extend(single_angle(t));
        cands.extend(separable(t));
    }
    cands.extend(super::roots::root_products(t));
    cands.extend(super::peel::product(t));
    cands.extend(constant_trig(x, t));
    // Last, so that on ties the candidates above are kept.
    if t.len() <= MAX_TERMS {
        cands.extend(super::cspoly::factored_forms(t));
    }
    cands
}

/// Operations counted as a CAS counts them (SymPy's `count_ops`): [`Expr::cost`] plus the
/// arithmetic inside the angles (`sin(x - y)` is two operations, `cos(2*x)` two); then the
/// plain cost. Candidates are compared with the shape found before by this.
pub(super) fn full_cost(e: &Expr) -> (usize, usize, usize) {
    fn angle_ops(e: &Expr) -> usize {
        match e {
            Expr::Trig { angle, .. } => {
                let terms = angle.terms.len()
                    + usize::from(!angle.constant.is_zero())
                    + usize::from(!angle.pi.is_zero());
                // Over a common denominator `(q1 + q2)/2` (see `angle_text`): one division,
                // and a multiplication per numerator other than 1.
                let d = super::notation::common_denominator(angle).unwrap_or(1);
                let coefs = angle.terms.iter().filter(|(_, k)| !unit_over(k, d)).count()
                    + usize::from(!unit_over(&angle.pi, d) && !angle.pi.is_zero())
                    + usize::from(d > 1);
                // Without a common denominator a fraction other than `1/n` is a multiplication
                // and a division (`3*u1/2`, `5*pi/12`), as SymPy counts it.
                let fractions = if d > 1 {
                    0
                } else {
                    let two_ops = |k: &Small| *k.denom() > 1 && k.numer().abs() > 1;
                    angle.terms.iter().filter(|(_, k)| two_ops(k)).count()
                        + usize::from(two_ops(&angle.pi))
                };
                terms.saturating_sub(1) + coefs + fractions
            }
            Expr::Add(v) | Expr::Mul(v) => v.iter().map(angle_ops).sum(),
            Expr::Neg(x) | Expr::Pow(x, _) => angle_ops(x),
            _ => 0,
        }
    }
    let c = e.cost();
    (c.ops + angle_ops(e), c.ops, c.calls)
}

/// Whether `|k d| = 1`, for `k` in lowest terms and `d > 0`, without the product (which
/// reduces by a gcd, once per angle term of every cost evaluated): `k = p/q` with
/// `|p| d = q` and `gcd(p, q) = 1` makes `p` divide `q`, so `|p| = 1` and `q = d`; the
/// converse is immediate.
fn unit_over(k: &Small, d: i64) -> bool {
    k.numer().unsigned_abs() == 1 && *k.denom() == d
}

/// The order candidates are chosen in: [`full_cost`]'s operations, then the operations with
/// a power counted once as SymPy's `count_ops` counts it (`sin(x)^4` one operation, not three),
/// then the rest of [`full_cost`].
pub(super) fn choice_key(e: &Expr) -> (usize, usize, usize, usize) {
    fn extra_pow(e: &Expr) -> usize {
        match e {
            Expr::Pow(x, n) => (*n as usize).saturating_sub(2) + extra_pow(x),
            Expr::Add(v) | Expr::Mul(v) => v.iter().map(extra_pow).sum(),
            Expr::Neg(x) => extra_pow(x),
            _ => 0,
        }
    }
    let (all, ops, calls) = full_cost(e);
    (all, all - extra_pow(e), ops, calls)
}

/// Whether `a` is chosen over `b` ([`choice_key`]).
pub(super) fn shorter(a: &Expr, b: &Expr) -> bool {
    let (ka, kb) = (choice_key(a), choice_key(b));
    (ka.0, ka.1) < (kb.0, kb.1)
}

pub(super) fn mul(a: Expr, b: Expr) -> Expr {
    let parts = |e: Expr| match e {
        Expr::Mul(v) => v,
        Expr::Num(q) if q.is_one() => Vec::new(),
        e => vec![e],
    };
    match (a, b) {
        (Expr::Neg(a), b) | (b, Expr::Neg(a)) => neg(mul(*a, b)),
        (a, b) => {
            let mut v = parts(a);
            v.extend(parts(b));
            match v.len() {
                0 => Expr::Num(Rat::one()),
                1 => v.pop().expect("one factor"),
                _ => Expr::Mul(v),
            }
        }
    }
}

pub(super) fn neg(e: Expr) -> Expr {
    match e {
        Expr::Neg(e) => *e,
        e => Expr::Neg(Box::new(e)),
    }
}

pub(super) fn num(q: Rat) -> Expr {
    if q.is_negative() {
        neg(Expr::Num(-q))
    } else {
        Expr::Num(q)
    }
}

/// `cos` or `sin` of the angle of a frequency vector (see [`Angle::from_freq`]) and a multiple
/// of pi; a constant negative angle is shown positive (`cos` is even, `sin` odd).
pub(super) fn trig(sin: bool, freq: Vec<(Sym, Small)>, pi: Small) -> Expr {
    if freq.is_empty() && pi.is_negative() {
        let e = trig(sin, freq, -pi);
        return if sin { neg(e) } else { e };
    }
    Expr::Trig {
        f: crate::scalar::Trig::of(sin),
        angle: Angle::from_freq(&freq, pi).offset_reduced(),
    }
}

/// The closed form of a scalar without modes (a coefficient times a monomial).
fn plain(x: &Scalar) -> Option<Expr> {
    super::closed_form(x).ok()
}

/// The term's coefficient, radical and monomial as a scalar (its mode dropped).
fn weight(t: &Term) -> Scalar {
    Scalar::from_terms_sorted(vec![Term {
        mode: crate::scalar::Mode::unit(),
        ..t.clone()
    }])
}

/// `pi` reduced into `(-1, 1]`.
fn centred(p: Small) -> Small {
    let two = Small::from_integer(2);
    let mut p = p - (p / two).floor() * two;
    if p > Small::one() {
        p -= two;
    }
    p
}

/// A rational with a small denominator within `1e-9` of `v` (continued fractions).
pub(super) fn small_rational(v: f64) -> Option<Rat> {
    if !v.is_finite() || v.abs() > 1e9 {
        return None;
    }
    let (mut h0, mut h1, mut k0, mut k1) = (0i64, 1i64, 1i64, 0i64);
    let mut x = v;
    for _ in 0..40 {
        let a = x.floor();
        let ai = a as i64;
        let h2 = ai.checked_mul(h1)?.checked_add(h0)?;
        let k2 = ai.checked_mul(k1)?.checked_add(k0)?;
        (h0, h1, k0, k1) = (h1, h2, k1, k2);
        if k1 > 100_000 {
            return None;
        }
        if (v - h1 as f64 / k1 as f64).abs() < 1e-10 * (1.0 + v.abs()) {
            return Some(Rat::new(h1.into(), k1.into()));
        }
        let frac = x - a;
        if frac.abs() < 1e-12 {
            return None;
        }
        x = 1.0 / frac;
    }
    None
}

/// A sum over one monomial of cosines and sines of one angle `F` with any offsets:
/// `R m cos(F + theta)` with `R^2` rational and `theta` a rational multiple of pi
/// (`a cos F + b sin F = R cos(F - phi)`, `sqrt(2)/2 (cos t - sin t) = cos(t + pi/4)`).
fn harmonic(t: &[Term]) -> Option<Expr> {
    let f = &t[0].mode.freq;
    if f.is_empty() {
        return None;
    }
    let m = &t[0].mono;
    if !t.iter().all(|x| x.mode.freq == *f && x.mono == *m) {
        return None;
    }
    // The value as a function of F: A cos F - B sin F; at F = 0 it is A, at F = pi/2, -B.
    let at = |phi: f64| -> Option<f64> {
        let mut v = 0.0;
        for x in t {
            let a = phi
                + std::f64::consts::PI * (*x.mode.pi.numer() as f64 / *x.mode.pi.denom() as f64);
            let tr = if x.mode.sin { a.sin() } else { a.cos() };
            v += x.coef.to_f64()? * (x.rad as f64).sqrt() * tr;
        }
        Some(v)
    };
    let (a, b) = (at(0.0)?, -at(std::f64::consts::FRAC_PI_2)?);
    let r2 = small_rational(a * a + b * b)?;
    if !r2.is_positive() {
        return None;
    }
    let theta = b.atan2(a) / std::f64::consts::PI;
    let p = (1..=120i64).find_map(|d| {
        let n = (theta * d as f64).round();
        ((theta - n / d as f64).abs() < 1e-9).then(|| Small::new(n as i64, d))
    })?;
    let r = Scalar::rational(r2).sqrt().check().ok()?;
    let mono_scalar = weight(&Term {
        coef: crate::scalar::Q::ONE,
        rad: 1,
        mode: crate::scalar::Mode::unit(),
        ..t[0].clone()
    });
    let coef = plain(&(&r * &mono_scalar))?;
    // cos(F + theta) or sin(F + theta + 1/2), the smaller denominator (cos on ties).
    let (c, s) = (centred(p), centred(p + Small::new(1, 2)));
    let (sin, off) = if c.denom() <= s.denom() {
        (false, c)
    } else {
        (true, s)
    };
    // An offset of pi is a sign.
    let tr = if off.is_one() {
        neg(trig(sin, f.to_vec(), Small::zero()))
    } else {
        trig(sin, f.to_vec(), off)
    };
    Some(mul(coef, tr))
}

/// `w (trig A +- trig B)` as a product of two trigonometric factors.
fn sum_to_product(t: &[Term]) -> Option<Expr> {
    let [u, v] = t else { return None };
    if u.mono != v.mono || u.rad != v.rad || u.mode.is_unit() || v.mode.is_unit() {
        return None;
    }
    let sign = if u.coef == v.coef {
        1
    } else if u.coef == -v.coef.clone() {
        -1
    } else {
        return None;
    };
    // Both as the kind of `u`: cos B = sin(B + 1/2), sin B = cos(B - 1/2).
    let sin = u.mode.sin;
    let vpi = match (sin, v.mode.sin) {
        (true, false) => v.mode.pi + Small::new(1, 2),
        (false, true) => v.mode.pi - Small::new(1, 2),
        _ => v.mode.pi,
    };
    let half = |sign: i64| {
        let f: Vec<(Sym, Small)> = freq_combine(&u.mode.freq, &v.mode.freq, sign)
            .into_iter()
            .map(|(s, k)| (s, k / Small::from_integer(2)))
            .collect();
        let pi = (u.mode.pi + vpi * Small::from_integer(sign)) / Small::from_integer(2);
        (f, pi)
    };
    let (sf, spi) = half(1);
    let (df, dpi) = half(-1);
    // A function of an angle with the first coefficient made positive: (negated?, expr).
    let make = |sin: bool, f: Vec<(Sym, Small)>, pi: Small| -> (bool, Expr) {
        if f.first().is_some_and(|(_, k)| k.is_negative()) {
            let f = f.into_iter().map(|(s, k)| (s, -k)).collect();
            (sin, trig(sin, f, centred(-pi)))
        } else {
            (false, trig(sin, f, centred(pi)))
        }
    };
    // cos A + cos B = 2 cos S cos D, cos A - cos B = -2 sin S sin D,
    // sin A + sin B = 2 sin S cos D, sin A - sin B = 2 cos S sin D.
    let (k1, k2, negate) = match (sin, sign) {
        (false, 1) => (false, false, false),
        (false, _) => (true, true, true),
        (true, 1) => (true, false, false),
        (true, _) => (false, true, false),
    };
    let (n1, e1) = make(k1, sf, spi);
    let (n2, e2) = make(k2, df, dpi);
    let w = weight(u) * Scalar::int(2);
    let mut e = mul(plain(&w)?, mul(e1, e2));
    if negate ^ n1 ^ n2 {
        e = neg(e);
    }
    Some(e)
}

/// A polynomial in `cos x` alone (or `sin x` alone, or one of them times such a polynomial)
/// with rational coefficients, factored by its rational roots.
fn single_angle(t: &[Term]) -> Vec<Expr> {
    let Some((var, poly)) = cos_sin_poly(t) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for sin_var in [false, true] {
        let (even, odd) = in_one_function(&poly, sin_var);
        let v = trig(sin_var, vec![(var.clone(), Small::one())], Small::zero());
        let o = trig(!sin_var, vec![(var.clone(), Small::one())], Small::zero());
        match (even.is_empty(), odd.is_empty()) {
            (false, true) => out.extend(factored_forms(&even, &v, &o)),
            (true, false) => out.extend(
                factored_forms(&odd, &v, &o)
                    .into_iter()
                    .map(|e| mul(o.clone(), e)),
            ),
            _ => {}
        }
    }
    out
}

/// `(x, p)` when the terms are a polynomial in `cos x` and `sin x` with rational coefficients:
/// `p` maps `(i, j)` to the coefficient of `cos^i sin^j`.
#[allow(clippy::type_complexity)]
fn cos_sin_poly(t: &[Term]) -> Option<(Sym, BTreeMap<(u32, u32), Rat>)> {
    let mut var: Option<&Sym> = None;
    for u in t {
        if !u.mono.is_empty() || u.rad != 1 || !u.mode.pi.is_zero() {
            return None;
        }
        match &*u.mode.freq {
            [] => {}
            [(s, k)] if k.is_integer() => {
                if var.is_some_and(|v| v != s) {
                    return None;
                }
                var = Some(s);
            }
            _ => return None,
        }
    }
    let var = var?;
    // (i, j) -> coefficient of cos^i sin^j: cos(k x) and sin(k x) are the real and imaginary
    // parts of (c + i s)^k. Summed as integers over the coefficients' common denominator and
    // reduced once each at the end (a rational sum reduces at every step: most of the cost).
    let coefs: Vec<Rat> = t.iter().map(|u| u.coef.to_big()).collect();
    let den = coefs.iter().fold(BigInt::one(), |d, q| d.lcm(q.denom()));
    let mut poly: BTreeMap<(u32, u32), BigInt> = BTreeMap::new();
    for (u, q) in t.iter().zip(&coefs) {
        let n = q.numer() * (&den / q.denom());
        let k = match &*u.mode.freq {
            [] => {
                *poly.entry((0, 0)).or_default() += n;
                continue;
            }
            [(_, k)] => k.to_integer(),
            _ => return None,
        };
        if !(1..=MAX_MULTIPLE).contains(&k) {
            return None;
        }
        let k = k as u32;
        // C(k, j) for k <= MAX_MULTIPLE (at most C(24, 12) = 2,704,156) fits an i64.
        let mut binom = 1i64;
        for j in 0..=k {
            // i^j: real for even j (sign (-1)^(j/2)), imaginary for odd j (sign (-1)^((j-1)/2)).
            let real = j % 2 == 0;
            if real != u.mode.sin {
                let c = &n * BigInt::from(binom);
                let e = poly.entry((k - j, j)).or_default();
                if (j / 2) % 2 == 0 {
                    *e += c;
                } else {
                    *e -= c;
                }
            }
            binom = binom * i64::from(k - j) / i64::from(j + 1);
        }
    }
    Some((var.clone(), over(poly, &den)))
}

/// The nonzero integers of `m` over `den`, each reduced once.
fn over<K: Ord>(m: BTreeMap<K, BigInt>, den: &BigInt) -> BTreeMap<K, Rat> {
    m.into_iter()
        .filter(|(_, n)| !n.is_zero())
        .map(|(k, n)| (k, Rat::new(n, den.clone())))
        .collect()
}

/// The polynomial in `v = sin x` (or `cos x`) that `p` is, with `o^2 = 1 - v^2` for the other
/// function `o`: the part even in `o` and the part odd in `o` (divided by `o`).
fn in_one_function(
    poly: &BTreeMap<(u32, u32), Rat>,
    sin_var: bool,
) -> (BTreeMap<u32, Rat>, BTreeMap<u32, Rat>) {
    // Integers over the coefficients' common denominator, each result reduced once (as in
    // `cos_sin_poly`).
    let den = poly.values().fold(BigInt::one(), |d, q| d.lcm(q.denom()));
    let mut even: BTreeMap<u32, BigInt> = BTreeMap::new();
    let mut odd: BTreeMap<u32, BigInt> = BTreeMap::new();
    for (&(i, j), q) in poly {
        let (dv, d_o) = if sin_var { (j, i) } else { (i, j) };
        let target = if d_o % 2 == 0 { &mut even } else { &mut odd };
        let num = q.numer() * (&den / q.denom());
        // (1 - v^2)^(d_o / 2) v^dv; C(n, k) for n <= MAX_MULTIPLE / 2 fits an i64.
        let n = d_o / 2;
        let mut binom = 1i64;
        for k in 0..=n {
            let c = &num * BigInt::from(binom);
            let e = target.entry(dv + 2 * k).or_default();
            if k % 2 == 0 {
                *e += c;
            } else {
                *e -= c;
            }
            binom = binom * i64::from(n - k) / i64::from(k + 1);
        }
    }
    (over(even, &den), over(odd, &den))
}

/// `p(v)` factored by its rational roots, and also with the pairs `(v - 1)(v + 1)` of the
/// roots 1 and -1 written `-o^2` (`(cos x - 1)^2 (cos x + 1)^3 = sin(x)^4 (cos x + 1)`).
fn factored_forms(p: &BTreeMap<u32, Rat>, v: &Expr, o: &Expr) -> Vec<Expr> {
    let mut out: Vec<Expr> = factored(p, v).into_iter().collect();
    // Divide out (v^2 - 1)^k, k as large as it goes, and factor the rest.
    let mut rest = p.clone();
    let mut k = 0u32;
    while let Some(q) = divide_by_v2_minus_1(&rest) {
        rest = q;
        k += 1;
    }
    if k > 0 {
        if let Some(f) = factored(&rest, v) {
            let pw = Expr::Pow(Box::new(o.clone()), 2 * k);
            // A number first (`-3/4 sin(x)^2`), as every product prints.
            let number = match &f {
                Expr::Neg(x) => matches!(**x, Expr::Num(_)),
                f => matches!(f, Expr::Num(_)),
            };
            let e = if number { mul(f, pw) } else { mul(pw, f) };
            out.push(if k % 2 == 1 { neg(e) } else { e });
        }
    }
    out
}

/// `p / (v^2 - 1)` when exact.
fn divide_by_v2_minus_1(p: &BTreeMap<u32, Rat>) -> Option<BTreeMap<u32, Rat>> {
    let deg = *p.keys().max()? as usize;
    if deg < 2 {
        return None;
    }
    let mut r: Vec<Rat> = vec![Rat::zero(); deg + 1];
    for (i, q) in p {
        r[*i as usize] = q.clone();
    }
    let mut quot = vec![Rat::zero(); deg - 1];
    for i in (2..=deg).rev() {
        let c = r[i].clone();
        if c.is_zero() {
            continue;
        }
        r[i] = Rat::zero();
        r[i - 2] += &c;
        quot[i - 2] = c;
    }
    if r.iter().any(|x| !x.is_zero()) {
        return None;
    }
    Some(
        quot.into_iter()
            .enumerate()
            .filter(|(_, q)| !q.is_zero())
            .map(|(i, q)| (i as u32, q))
            .collect(),
    )
}

/// A sum of polynomials in one cosine or sine each, of distinct angle symbols (and a
/// constant): each part written in the function that makes it shortest, the constants merged
/// (`cos(a + b) cos(a - b) = (cos 2a + cos 2b)/2 = cos(a)^2 - sin(b)^2`).
fn separable(t: &[Term]) -> Option<Expr> {
    let mut parts: BTreeMap<&Sym, Vec<Term>> = BTreeMap::new();
    let mut constant = Rat::zero();
    for u in t {
        if !u.mono.is_empty() || u.rad != 1 || !u.mode.pi.is_zero() {
            return None;
        }
        match &*u.mode.freq {
            [] => constant += u.coef.to_big(),
            [(s, _)] => parts.entry(s).or_default().push(u.clone()),
            _ => return None,
        }
    }
    if parts.len() < 2 || parts.len() > 4 {
        return None;
    }
    // Each part in cos alone and in sin alone (without its constant); every combination is
    // built with the constants merged, the cheapest kept.
    let mut options: Vec<Vec<(Vec<Expr>, Rat)>> = Vec::new();
    for ts in parts.values() {
        let (var, poly) = cos_sin_poly(ts)?;
        let mut opts = Vec::new();
        for sin_var in [false, true] {
            let (even, odd) = in_one_function(&poly, sin_var);
            if !odd.is_empty() || even.len() > 4 {
                continue;
            }
            let v = trig(sin_var, vec![(var.clone(), Small::one())], Small::zero());
            let c0 = even.get(&0).cloned().unwrap_or_else(Rat::zero);
            let terms: Vec<Expr> = even
                .iter()
                .rev()
                .filter(|(i, _)| **i > 0)
                .map(|(i, q)| {
                    let pw = if *i == 1 {
                        v.clone()
                    } else {
                        Expr::Pow(Box::new(v.clone()), *i)
                    };
                    if q.is_one() {
                        pw
                    } else if (-q).is_one() {
                        neg(pw)
                    } else {
                        mul(num(q.clone()), pw)
                    }
                })
                .collect();
            opts.push((terms, c0));
        }
        if opts.is_empty() {
            return None;
        }
        options.push(opts);
    }
    let mut best: Option<Expr> = None;
    for mut pick in 0..(1usize << options.len()) {
        let mut sum: Vec<Expr> = Vec::new();
        let mut c = constant.clone();
        for opts in &options {
            let (terms, c0) = &opts[pick % 2 % opts.len()];
            pick /= 2;
            sum.extend(terms.iter().cloned());
            c += c0;
        }
        if !c.is_zero() {
            sum.push(num(c));
        }
        let e = match sum.len() {
            0 => continue,
            1 => sum.pop().expect("one term"),
            _ => Expr::Add(sum),
        };
        if best.as_ref().is_none_or(|b| full_cost(&e) < full_cost(b)) {
            best = Some(e);
        }
    }
    best
}

/// `sum q_i v^i` factored by its rational roots (with multiplicity); the rest expanded.
fn factored(p: &BTreeMap<u32, Rat>, v: &Expr) -> Option<Expr> {
    let deg = *p.keys().max()? as usize;
    if deg > 24 {
        return None;
    }
    let mut coefs: Vec<Rat> = vec![Rat::zero(); deg + 1];
    for (i, q) in p {
        coefs[*i as usize] = q.clone();
    }
    // Primitive integer polynomial with a positive leading coefficient, and the constant.
    let l = coefs
        .iter()
        .fold(BigInt::one(), |acc, q| acc.lcm(q.denom()));
    let mut ints: Vec<BigInt> = coefs
        .iter()
        .map(|q| (q * Rat::from_integer(l.clone())).to_integer())
        .collect();
    let mut g = ints.iter().fold(BigInt::zero(), |acc, x| acc.gcd(x));
    if ints[deg].is_negative() {
        g = -g;
    }
    for x in ints.iter_mut() {
        *x /= &g;
    }
    let mut k = Rat::new(g, l);
    let mut factors: Vec<(Expr, u32)> = Vec::new();
    let zeros = ints.iter().take_while(|x| x.is_zero()).count();
    ints.drain(..zeros);
    if zeros > 0 {
        factors.push((v.clone(), zeros as u32));
    }
    // Rational roots p/q: p divides the constant term, q the leading one.
    let divisors = |n: &BigInt| -> Option<Vec<i64>> {
        let n = n.abs().to_i64()?;
        (n <= 1_000_000).then(|| (1..=n).filter(|d| n % d == 0).collect())
    };
    if ints.len() > 1 {
        let ps = divisors(&ints[0])?;
        let qs = divisors(ints.last()?)?;
        let mut roots: Vec<(i64, i64)> = Vec::new();
        for &q in &qs {
            for &pp in &ps {
                for s in [1, -1] {
                    if pp.gcd(&q) == 1 {
                        roots.push((s * pp, q));
                    }
                }
            }
        }
        for (rp, rq) in roots {
            let mut mult = 0u32;
            while ints.len() > 1 {
                // Divide by (rq v - rp) when it divides exactly.
                let n = ints.len() - 1;
                let mut quot = vec![BigInt::zero(); n];
                let mut rem = ints[n].clone();
                let mut ok = true;
                for i in (0..n).rev() {
                    if !(&rem % rq).is_zero() {
                        ok = false;
                        break;
                    }
                    quot[i] = &rem / rq;
                    rem = &ints[i] + &quot[i] * rp;
                }
                if !ok || !rem.is_zero() {
                    break;
                }
                ints = quot;
                mult += 1;
            }
            if mult > 0 {
                let lin = if rq == 1 {
                    v.clone()
                } else {
                    mul(Expr::Num(Rat::from_integer(rq.into())), v.clone())
                };
                let f = if rp > 0 {
                    Expr::Add(vec![lin, neg(Expr::Num(Rat::from_integer(rp.into())))])
                } else {
                    Expr::Add(vec![lin, Expr::Num(Rat::from_integer((-rp).into()))])
                };
                factors.push((f, mult));
            }
        }
    }
    // What is left: a constant or a polynomial without rational roots.
    if ints.len() == 1 {
        k *= Rat::from_integer(ints[0].clone());
    } else {
        let mut terms = Vec::new();
        for (i, c) in ints.iter().enumerate().rev() {
            if c.is_zero() {
                continue;
            }
            let pw = match i {
                0 => Expr::Num(Rat::one()),
                1 => v.clone(),
                _ => Expr::Pow(Box::new(v.clone()), i as u32),
            };
            let c = Rat::from_integer(c.clone());
            terms.push(mul(num(c), pw));
        }
        factors.push((Expr::Add(terms), 1));
    }
    let mut e = num(k);
    for (f, m) in factors {
        let f = if m == 1 { f } else { Expr::Pow(Box::new(f), m) };
        e = mul(e, f);
    }
    Some(e)
}

/// A constant equal to `cos(k pi / n)` or `sin(k pi / n)` or their negatives, `n` from the
/// offsets it holds:
/// `cos(3 pi/7)` prints as itself, not as its expansion in the basis.
fn constant_trig(x: &Scalar, t: &[Term]) -> Option<Expr> {
    if !t
        .iter()
        .all(|u| u.mode.freq.is_empty() && u.mono.is_empty())
    {
        return None;
    }
    // The value's field holds zeta_24 through the square roots: look at multiples of pi/12 too.
    let n = t
        .iter()
        .fold(24i64, |acc, u| acc.lcm(&(2 * u.mode.pi.denom())));
    if n > 20_000 {
        return None;
    }
    let v = x.eval(&|_| None).ok()?;
    // An angle in [0, pi/2] whose cosine or sine is |v|: the smallest denominator, then the
    // smallest numerator, cosine first.
    let (_, _, sin, k) = (0..=n / 2)
        .flat_map(|k| [(k, false), (k, true)])
        .filter(|&(k, sin)| {
            let a = std::f64::consts::PI * k as f64 / n as f64;
            let f = if sin { a.sin() } else { a.cos() };
            (f - v.abs()).abs() < 1e-12
        })
        .map(|(k, sin)| {
            let r = Small::new(k, n);
            (*r.denom(), *r.numer(), sin, k)
        })
        .min()?;
    let e = trig(sin, Vec::new(), Small::new(k, n));
    Some(if v < 0.0 { neg(e) } else { e })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `unit_over` (no product) against `|k d| = 1` computed as a rational product, on seeded
    /// random fractions and denominators, with `k = +-1/d` and `+-1` among them.
    #[test]
    fn a_unit_over_a_denominator_is_the_product_of_one() {
        let mut next = crate::testing::xorshift_below(0x5eed_0a17_c057_0001);
        let mut units = 0;
        for _ in 0..20_000 {
            let d = 1 + next(24) as i64;
            let k = match next(4) {
                0 => Small::new(1 - 2 * next(2) as i64, d),
                1 => Small::new(1 - 2 * next(2) as i64, 1),
                _ => Small::new(next(49) as i64 - 24, 1 + next(36) as i64),
            };
            let want = (k * Small::from_integer(d)).abs().is_one();
            units += usize::from(want);
            assert_eq!(unit_over(&k, d), want, "{k} over {d}");
        }
        assert!(units > 1000, "the units were tried ({units})");
    }

    /// `in_one_function` (integers over a common denominator) against the polynomial itself,
    /// exactly, at the rational point (cos, sin) = (3/5, 4/5) of the unit circle, for both
    /// choices of the variable and random polynomials with rational coefficients.
    #[test]
    fn a_polynomial_in_cos_and_sin_rewritten_in_one_of_them_keeps_its_value_on_the_circle() {
        let r = |n: i64, d: i64| Rat::new(n.into(), d.into());
        let pow = |x: &Rat, n: u32| (0..n).fold(Rat::one(), |acc, _| acc * x);
        let (c, s) = (r(3, 5), r(4, 5));
        let mut next = crate::testing::xorshift_below(0x2545_f491_4f6c_dd1du64);
        for _ in 0..40 {
            let mut poly: BTreeMap<(u32, u32), Rat> = BTreeMap::new();
            for _ in 0..1 + next(6) {
                let (i, j) = (next(9) as u32, next(9) as u32);
                let q = r(next(41) as i64 - 20, 1 + next(12) as i64);
                if !q.is_zero() {
                    poly.insert((i, j), q);
                }
            }
            let want: Rat = poly
                .iter()
                .map(|(&(i, j), q)| q * pow(&c, i) * pow(&s, j))
                .fold(Rat::zero(), |a, b| a + b);
            for sin_var in [false, true] {
                let (even, odd) = in_one_function(&poly, sin_var);
                let (v, o) = if sin_var { (&s, &c) } else { (&c, &s) };
                let at = |p: &BTreeMap<u32, Rat>| {
                    p.iter()
                        .map(|(&k, q)| q * pow(v, k))
                        .fold(Rat::zero(), |a, b| a + b)
                };
                assert!(even.values().chain(odd.values()).all(|q| !q.is_zero()));
                assert_eq!(at(&even) + o * at(&odd), want, "{poly:?}");
            }
        }
    }
}
