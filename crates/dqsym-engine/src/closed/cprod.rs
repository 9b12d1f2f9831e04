//! A closed-form candidate for scalars whose constants are products of constant cosines and
//! sines: `cos(pi/7) cos(pi/9)` is canonically a sum over `pi/63` (its field's basis), but
//! reads shorter as the product. The scalar stays canonical; this is display only.
//!
//! For a scalar without symbolic angles, `sum_m c_m m` over monomials `m` with constant
//! coefficients `c_m`, the candidates are `P sum_m r_m m` with `r_m` rational and `P` a product
//! of one to three factors `cos(k pi/n)` or `sin(k pi/n)` (repeats are powers) at the angles of
//! the scalar's field that are not multiples of `pi/12` (three only at the terms' own
//! denominators). They are found numerically (every
//! `c_m / P` a small rational) and then, like every candidate, checked exactly by the caller.

use super::alt::{mul, num, trig};
use super::expr::Expr;
use crate::scalar::{MonoRc, Small, Term, Q};
use crate::Scalar;
use num_integer::Integer;
use num_rational::BigRational as Rat;
use std::collections::BTreeMap;

/// The most candidate factors for products of two, and of three (those at the terms' own
/// denominators).
const MAX_PAIRS: usize = 700;
const MAX_TRIPLES: usize = 96;

/// The most square roots tried as a product's cofactor (1 included).
const MAX_ROOTS: usize = 6;

/// The most products returned (the caller keeps the cheapest one that checks).
const MAX_FOUND: usize = 12;

/// The rational `c_m / P` of each monomial and radicand.
type Ratios = Vec<((MonoRc, u64), Rat)>;

/// The value of a term without its monomial (and without its radical, with `split`).
fn value(t: &Term, split: bool) -> Option<f64> {
    let a = std::f64::consts::PI * (*t.mode.pi.numer() as f64) / (*t.mode.pi.denom() as f64);
    let f = if t.mode.is_unit() {
        1.0
    } else if t.mode.sin {
        a.sin()
    } else {
        a.cos()
    };
    let r = if split { 1.0 } else { (t.rad as f64).sqrt() };
    Some(t.coef.to_f64()? * r * f)
}

/// A rational with a denominator up to 1000 within `1e-13` (relative) of `v`: the
/// continued-fraction convergents, in floats until one fits.
fn rational(v: f64) -> Option<Rat> {
    if !v.is_finite() || v.abs() > 1e9 {
        return None;
    }
    let (mut h0, mut h1, mut k0, mut k1) = (0f64, 1f64, 1f64, 0f64);
    let mut x = v;
    loop {
        let a = x.floor();
        (h0, h1) = (h1, a * h1 + h0);
        (k0, k1) = (k1, a * k1 + k0);
        if k1 > 1000.0 {
            return None;
        }
        if (v - h1 / k1).abs() < 1e-13 * (1.0 + v.abs()) {
            return Some(Rat::new((h1 as i64).into(), (k1 as i64).into()));
        }
        let frac = x - a;
        if frac.abs() < 1e-15 {
            return None;
        }
        x = 1.0 / frac;
    }
}

/// Candidates `P sum_m r_m m` (see the module docs); empty when the scalar has symbolic
/// angles or no constant outside the multiples of `pi/12`. With terms of no mode (rationals
/// and radicals, times monomials) beside the others, also `C + P sum_m r_m m` with `C` those
/// terms: `1 - cos(pi/7) cos(pi/9)`.
pub(super) fn constant_products(t: &[Term]) -> Vec<Expr> {
    if t.iter().any(|u| !u.mode.freq.is_empty()) {
        return Vec::new();
    }
    let mut out = products(t, false, false);
    if t.iter().any(|u| u.rad != 1) {
        out.extend(products(t, true, false));
    }
    // The constant is every term without a mode, or only the rational number (the radicals
    // may belong to the product: `sqrt(2) sin(pi/7)^2 - 1/2` holds `sqrt(2)/2 - 1/2`).
    let splits: [fn(&Term) -> bool; 2] = [
        |u| u.mode.is_unit(),
        |u| u.mode.is_unit() && u.rad == 1 && u.mono.is_empty(),
    ];
    let mut seen = 0;
    for split in splits {
        let (plain, rest): (Vec<Term>, Vec<Term>) = t.iter().cloned().partition(split);
        if plain.is_empty() || rest.is_empty() || plain.len() == seen {
            continue;
        }
        seen = plain.len();
        let Ok(c) = super::closed_form(&Scalar::from_terms(plain)) else {
            continue;
        };
        // A negative constant after the product: `P - 3/4`.
        out.extend(
            products(&rest, false, false)
                .into_iter()
                .map(|p| match (&c, p) {
                    (Expr::Neg(_), p) => Expr::Add(vec![p, c.clone()]),
                    (_, p) => Expr::Add(vec![c.clone(), p]),
                }),
        );
    }
    out
}

/// `cos(k pi/n)` for `0 < k < n/2` off the multiples of pi/12, each with its value, named by
/// the smallest denominator (`cos(k pi/n) = sin((n/2 - k) pi/n)`, cosine first).
fn factor_angles(n: i64) -> Vec<(f64, bool, Small)> {
    let mut factors: Vec<(f64, bool, Small)> = (1..n / 2)
        .filter(|k| (12 * k) % n != 0)
        .map(|k| {
            let c = Small::new(k, n);
            let s = Small::new(n / 2 - k, n);
            let v = (std::f64::consts::PI * k as f64 / n as f64).cos();
            if s.denom() < c.denom() {
                (v, true, s)
            } else {
                (v, false, c)
            }
        })
        .collect();
    factors.sort_by_key(|(_, sin, a)| (*a.denom(), *a.numer(), *sin));
    factors
}

/// Whether some value of `values` may be a rational times a square root of 1, 2, 3 or 6
/// times one or two cosines or sines at angles whose denominators divide `l` (a multiple of
/// `pi/n`): the numeric test `coefs.rs` makes before computing its constants exactly.
pub(super) fn may_be_small_product(values: &[f64], n: i64, l: i64) -> bool {
    let factors: Vec<f64> = factor_angles(n)
        .into_iter()
        .filter(|(_, _, a)| l % a.denom() == 0)
        .map(|(v, _, _)| v)
        .collect();
    let fits = |v: f64, p: f64| {
        [1.0f64, 2.0, 3.0, 6.0]
            .iter()
            .any(|r| rational(v / (p * r.sqrt())).is_some())
    };
    values.iter().filter(|v| v.abs() > 1e-12).any(|&v| {
        factors
            .iter()
            .enumerate()
            .any(|(i, &p)| fits(v, p) || factors[i..].iter().any(|&q| fits(v, p * q)))
    })
}

/// The constant of canonical terms `t` as a rational (and radical) multiple of one or two
/// cosines and sines at its own denominators, checked exactly: the quick search `coefs.rs`
/// makes for each constant it lifts.
pub(super) fn small_product(t: &[Term]) -> Option<Expr> {
    if t.iter()
        .any(|u| !u.mode.freq.is_empty() || !u.mono.is_empty())
    {
        return None;
    }
    let x = Scalar::from_terms(t.to_vec());
    let mut cands = products(t, false, true);
    if t.iter().any(|u| u.rad != 1) {
        cands.extend(products(t, true, true));
    }
    cands.into_iter().find(|e| e.to_scalar() == x)
}

/// [`constant_products`] without the split-off constant; with `split`, the terms of each
/// radicand apart, each a rational multiple of the product (`sin(pi/11)^2 cos(pi/5)` is
/// `sin(pi/11)^2 (1 + sqrt(5))/4`), else each monomial's whole coefficient (`cos(pi/7)
/// cos(pi/9)`, whose terms over `pi/63` carry `sqrt(21)`). With `quick`, pairs only among
/// the angles at the terms' own denominators, and no triples.
fn products(t: &[Term], split: bool, quick: bool) -> Vec<Expr> {
    let n = t
        .iter()
        .fold(24i64, |acc, u| acc.lcm(&(2 * u.mode.pi.denom())));
    if n == 24 || n > 20_000 {
        return Vec::new();
    }
    let mut coefs: BTreeMap<(&MonoRc, u64), f64> = BTreeMap::new();
    for u in t {
        let Some(v) = value(u, split) else {
            return Vec::new();
        };
        let rad = if split { u.rad } else { 1 };
        *coefs.entry((&u.mono, rad)).or_insert(0.0) += v;
    }
    if coefs.values().any(|c| c.abs() < 1e-12) {
        return Vec::new();
    }
    let factors = factor_angles(n);
    let f = factors.len();
    // Radical cofactors: with the coefficients whole, the product may stand beside the square
    // root of one of the terms' radicands (`sqrt(2) sin(pi/7)^2 cos(pi/9)`, whose terms over
    // `pi/63` carry `sqrt(2)` and `sqrt(42)`); a few at most.
    // Their common divisors too: `sqrt(3) cos(pi/7) sin(pi/11)` carries `sqrt(21)`, `sqrt(33)`.
    let mut roots: Vec<u64> = vec![1];
    if !split {
        let mut rads: Vec<u64> = t.iter().map(|u| u.rad).filter(|&r| r != 1).collect();
        rads.sort_unstable();
        rads.dedup();
        let pairs = rads
            .iter()
            .enumerate()
            .flat_map(|(i, a)| rads[i + 1..].iter().map(move |b| a.gcd(b)));
        for r in rads.iter().copied().chain(pairs) {
            if roots.len() < MAX_ROOTS && !roots.contains(&r) {
                roots.push(r);
            }
        }
    }
    let fits = |p: f64| -> Option<Ratios> {
        roots.iter().find_map(|&root| {
            let q = p * (root as f64).sqrt();
            coefs
                .iter()
                .map(|((m, d), c)| rational(c / q).map(|r| (((*m).clone(), *d * root), r)))
                .collect()
        })
    };
    let mut found: Vec<(Vec<usize>, Ratios)> = Vec::new();
    let search = |idx: &[usize], found: &mut Vec<_>| {
        let p: f64 = idx.iter().map(|&i| factors[i].0).product();
        if let Some(r) = fits(p) {
            found.push((idx.to_vec(), r));
        }
    };
    for i in 0..f {
        search(&[i], &mut found);
    }
    // Pairs among all the angles or, for large fields, among those whose denominator divides
    // the terms' (triples only among those: pi/7 and pi/9 for a sum over pi/63).
    let l = t.iter().fold(1i64, |acc, u| acc.lcm(u.mode.pi.denom()));
    let near: Vec<usize> = (0..f).filter(|&i| l % factors[i].2.denom() == 0).collect();
    let all: Vec<usize> = (0..f).collect();
    let pairs = if f <= MAX_PAIRS && !quick {
        &all
    } else {
        &near
    };
    if pairs.len() <= MAX_PAIRS {
        for (a, &i) in pairs.iter().enumerate() {
            for &j in &pairs[a..] {
                search(&[i, j], &mut found);
            }
        }
    }
    if near.len() <= MAX_TRIPLES && !quick {
        for (a, &i) in near.iter().enumerate() {
            for (b, &j) in near.iter().enumerate().skip(a) {
                for &k in &near[b..] {
                    search(&[i, j, k], &mut found);
                }
            }
        }
    }
    // Fewest factors first (the numeric search also finds chance matches, checked later).
    found.sort_by_key(|(idx, _)| idx.len());
    found.truncate(MAX_FOUND);
    found
        .into_iter()
        .filter_map(|(idx, r)| {
            let rest = Scalar::from_terms(
                r.into_iter()
                    .map(|((mono, rad), q)| Term {
                        mode: crate::scalar::Mode::unit(),
                        mono,
                        rad,
                        coef: Q::big(q),
                    })
                    .collect(),
            );
            let mut p: Option<Expr> = None;
            let mut k = 0;
            while k < idx.len() {
                let run = idx[k..].iter().take_while(|&&i| i == idx[k]).count();
                let (_, sin, a) = &factors[idx[k]];
                let mut x = trig(*sin, Vec::new(), *a);
                if run > 1 {
                    x = Expr::Pow(Box::new(x), run as u32);
                }
                p = Some(match p {
                    Some(p) => mul(p, x),
                    None => x,
                });
                k += run;
            }
            let p = p?;
            let e = match rest.terms().ok()? {
                [] => return None,
                [u] if u.mode.is_unit() && u.mono.is_empty() && u.rad == 1 => {
                    mul(num(u.coef.to_big()), p)
                }
                _ => mul(super::closed_form(&rest).ok()?, p),
            };
            Some(e)
        })
        .collect()
}
