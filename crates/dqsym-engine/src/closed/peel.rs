//! A product of cosines and sines of multiples of one angle, peeled off a Fourier sum by
//! exact division (`cos(1) cos(2) ... cos(512)`, Morrie's `cos x cos 2x cos 4x`): a candidate
//! of `alt.rs`.
//!
//! The sum is a Laurent polynomial in `z = e^{i theta}` with Gaussian rational coefficients.
//! They are kept as Gaussian integers over one common denominator: dividing by
//! `(z^a + z^-a)/2` or `(z^a - z^-a)/(2i)` then only adds, subtracts and doubles integers.
//! With reduced rationals each of those steps took a gcd of the coefficients (a binary gcd, a
//! shift and a subtraction per bit): the products of many constant cosines, whose
//! coefficients have hundreds of digits, spent seconds in them, and each step was charged far
//! less than it cost.

use super::alt::{mul, trig};
use super::expr::Expr;
use crate::scalar::atoms::Small;
use crate::scalar::{charge, Sym, Term};
use crate::Scalar;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational as Rat;
use num_traits::{One, Zero};
use std::collections::BTreeMap;

/// A Gaussian integer `(re, im)`.
type C = (BigInt, BigInt);

/// A Laurent polynomial in `z`: exponent to coefficient, over the common denominator kept
/// beside it.
type Laurent = BTreeMap<i64, C>;

/// The units of a step per word of its coefficients: an addition, a subtraction or a
/// doubling goes over each word once, and the first two take a copy (as
/// `scalar::arith::add` charges a word).
const UNITS_PER_WORD: u64 = 2;

/// The units per word of a reduction of a rational (a binary gcd: about one shift and one
/// subtraction per bit), as `scalar::arith` charges one (`GCD_UNITS_PER_WORD` there).
const GCD_UNITS_PER_WORD: u64 = 16;

/// The words of a coefficient.
fn words(c: &C) -> u64 {
    (c.0.bits() + c.1.bits()).div_ceil(64)
}

fn c_add(p: &mut Laurent, e: i64, c: &C) {
    let v = p
        .entry(e)
        .or_insert_with(|| (BigInt::zero(), BigInt::zero()));
    v.0 += &c.0;
    v.1 += &c.1;
    if v.0.is_zero() && v.1.is_zero() {
        p.remove(&e);
    }
}

/// `p / ((z^a + z^-a)/2)` (cosine) or `p / ((z^a - z^-a)/(2i))` (sine) when exact, over the
/// same denominator.
///
/// Each step charges its work ([`UNITS_PER_WORD`] a word of the coefficient it reads); out of
/// budget or cancelled, the division gives up (`None`), and the error comes from the next
/// charge of the closed form.
fn divide_trig(p: &Laurent, a: i64, sin: bool) -> Option<Laurent> {
    let lo = *p.keys().next()?;
    charge(p.values().map(|c| 1 + words(c)).sum()).ok()?;
    let mut r = p.clone();
    let mut q = Laurent::new();
    while let Some((&t, c)) = r.iter().next_back() {
        charge(1 + UNITS_PER_WORD * words(c)).ok()?;
        let c = c.clone();
        let e = t - a;
        if e - a < lo {
            return None;
        }
        // cos: (z^a + z^-a)/2 * (2c z^e) = c z^t + c z^(t-2a);
        // sin: (z^a - z^-a)/(2i) * (2ic z^e) = c z^t - c z^(t-2a).
        let qc = if sin {
            (-(&c.1 << 1u32), &c.0 << 1u32)
        } else {
            (&c.0 << 1u32, &c.1 << 1u32)
        };
        c_add(&mut q, e, &qc);
        c_add(&mut r, t, &(-&c.0, -&c.1));
        let low = if sin { c.clone() } else { (-&c.0, -&c.1) };
        c_add(&mut r, t - 2 * a, &low);
    }
    Some(q)
}

/// The angle symbol of `t` and the denominator of its multiples, when `t` is a sum of
/// cosines and sines of multiples of one symbol (constants included) over one monomial.
fn one_angle(t: &[Term]) -> Option<(Sym, i64)> {
    let (m, rad) = (&t[0].mono, t[0].rad);
    let mut var: Option<&Sym> = None;
    let mut den: i64 = 1;
    for u in t {
        if u.mono != *m || u.rad != rad || !u.mode.pi.is_zero() {
            return None;
        }
        match &*u.mode.freq {
            [] => {}
            [(s, k)] => {
                if var.is_some_and(|v| v != s) {
                    return None;
                }
                var = Some(s);
                den = den.lcm(k.denom());
            }
            _ => return None,
        }
    }
    Some((var?.clone(), den))
}

/// `t` as a Laurent polynomial in `z^(1/unit)` and its common denominator.
fn laurent(t: &[Term], unit: i64) -> Option<(Laurent, BigInt)> {
    // The denominator: twice the lcm of the coefficients' (a cosine is half of `z^e + z^-e`).
    let mut lcm = BigInt::one();
    let mut work = 0u64;
    for u in t {
        let q = u.coef.to_big();
        work += 1 + GCD_UNITS_PER_WORD * (q.denom().bits().div_ceil(64) + lcm.bits() / 64);
        lcm = lcm.lcm(q.denom());
    }
    charge(work).ok()?;
    let mut p = Laurent::new();
    let mut work = 0u64;
    for u in t {
        let q = u.coef.to_big();
        // The coefficient times `lcm`: half of it times the denominator `2 lcm`.
        let n = q.numer() * (&lcm / q.denom());
        work += 1 + UNITS_PER_WORD * (n.bits().div_ceil(64) + lcm.bits().div_ceil(64));
        let e = match &*u.mode.freq {
            [] => 0,
            [(_, k)] => (*k * Small::from_integer(unit)).to_integer(),
            _ => return None,
        };
        let zero = BigInt::zero();
        if e == 0 {
            c_add(&mut p, 0, &(n << 1u32, zero));
        } else if u.mode.sin {
            c_add(&mut p, e, &(zero.clone(), -&n));
            c_add(&mut p, -e, &(zero, n));
        } else {
            c_add(&mut p, e, &(n.clone(), zero.clone()));
            c_add(&mut p, -e, &(n, zero));
        }
    }
    charge(work).ok()?;
    Some((p, lcm << 1u32))
}

/// A sum of cosines and sines of multiples of one angle symbol (constants included) over one
/// monomial, as a product of cosines and sines peeled off one at a time by exact division:
/// `cos(1) cos(2) cos(4) ... cos(512)` stays a product.
pub(super) fn product(t: &[Term]) -> Option<Expr> {
    let (m, rad) = (&t[0].mono, t[0].rad);
    let (var, den) = one_angle(t)?;
    // Exponents in units of var / (2 den), so that half differences are whole.
    let unit = 2 * den;
    let (mut p, denom) = laurent(t, unit)?;
    let mut factors: Vec<Expr> = Vec::new();
    loop {
        if p.len() < 2 || factors.len() > 64 {
            break;
        }
        let mut top = p.keys().rev();
        let (t1, t2) = (*top.next()?, *top.next()?);
        let a = (t1 - t2) / 2;
        if a <= 0 || (t1 - t2) % 2 != 0 {
            break;
        }
        let found = [false, true]
            .into_iter()
            .find_map(|sin| divide_trig(&p, a, sin).map(|q| (sin, q)));
        let Some((sin, q)) = found else { break };
        factors.push(trig(
            sin,
            vec![(var.clone(), Small::new(a, unit))],
            Small::zero(),
        ));
        p = q;
    }
    if factors.len() < 2 {
        return None;
    }
    let rest = quotient_terms(&p, &denom, &var, unit, m, rad)?;
    let rest = super::closed_form(&Scalar::from_terms(rest)).ok()?;
    let mut e = rest;
    for f in factors.into_iter().rev() {
        e = mul(f, e);
    }
    Some(e)
}

/// The quotient back as cosines and sines: `c_e z^e + c_-e z^-e = A cos + B sin` with
/// `A = c_e + c_-e`, `B = i (c_e - c_-e)`, over `denom`; `None` when it is not real. Each
/// coefficient is reduced once (charged as a gcd).
fn quotient_terms(
    p: &Laurent,
    denom: &BigInt,
    var: &Sym,
    unit: i64,
    m: &crate::scalar::MonoRc,
    rad: u64,
) -> Option<Vec<Term>> {
    let mut rest: Vec<Term> = Vec::new();
    let zero = (BigInt::zero(), BigInt::zero());
    let mut work = 0u64;
    for (&e, c) in p.iter().filter(|(e, _)| **e >= 0) {
        let d = p.get(&-e).unwrap_or(&zero);
        let (a, b) = if e == 0 {
            if !c.1.is_zero() {
                return None;
            }
            (c.0.clone(), BigInt::zero())
        } else {
            // A real function: c_-e is the conjugate of c_e.
            if c.0 != d.0 || c.1 != -&d.1 {
                return None;
            }
            (&c.0 + &d.0, -(&c.1 - &d.1))
        };
        let freq = if e == 0 {
            Vec::new()
        } else {
            vec![(var.clone(), Small::new(e, unit))]
        };
        for (sin, w) in [(false, a), (true, b)] {
            if w.is_zero() || (e == 0 && sin) {
                continue;
            }
            work += 1 + GCD_UNITS_PER_WORD * (w.bits() + denom.bits()).div_ceil(64);
            rest.push(Term {
                mode: crate::scalar::Mode {
                    sin,
                    freq: crate::scalar::atoms::freq_rc(freq.clone()),
                    pi: Small::zero(),
                },
                mono: m.clone(),
                rad,
                coef: crate::scalar::Q::big(Rat::new(w, denom.clone())),
            });
        }
    }
    if p.iter().any(|(e, _)| *e < 0 && !p.contains_key(&-e)) {
        return None;
    }
    charge(work).ok()?;
    Some(rest)
}
