//! The level `W` of a group (the cyclotomic field its pi offsets need) and the arithmetic of
//! the integers it is made of.

use super::super::atoms::Small;
use super::super::FxHasher;
use super::super::{ScalarError, Term};
use num_integer::Integer;
use std::cell::RefCell;
use std::collections::HashMap;
use std::hash::BuildHasherDefault;
use std::rc::Rc;

pub(super) fn lcm(a: u64, b: u64) -> u64 {
    a / a.gcd(&b) * b
}

/// `W = lcm(24, 2 q1, 2 q2, ...)` for the denominators `q` of the pi offsets of `terms`, when
/// `phi(W)` is within the context's limit; the error otherwise. `phi(n) >= sqrt(n / 2)`, so a
/// `W` above `2 limit^2` is refused without building anything; its degree is computed by
/// trial division up to `W = 10^12`, and past that (or past `u128`) stated as a lower bound
/// (such a `W` is refused whatever the limit).
pub(super) fn level_of<'a>(terms: impl Iterator<Item = &'a Term>) -> Result<u64, ScalarError> {
    let limit = super::super::ctx::max_cyclotomic_degree();
    let cap = 2u128.saturating_mul(u128::from(limit).saturating_mul(u128::from(limit)));
    let mut w: Option<u128> = Some(24);
    // The terms of a group share a few denominators: one lcm per change of denominator, none
    // when the level already holds it.
    let mut last = 0;
    for t in terms {
        let den = t.mode.pi.denom().unsigned_abs();
        if den == last {
            continue;
        }
        last = den;
        let d = 2 * u128::from(den);
        w = w.and_then(|w| {
            if w.is_multiple_of(d) {
                Some(w)
            } else {
                (w / w.gcd(&d)).checked_mul(d)
            }
        });
    }
    let refuse = |w: u128, degree: u64, exact: bool| ScalarError::CyclotomicDegree {
        level: u64::try_from(w / 2).unwrap_or(u64::MAX),
        degree,
        exact,
        limit,
    };
    const FACTORED: u128 = 1_000_000_000_000;
    let w = match w {
        Some(w) if w <= cap && w <= FACTORED => w as u64,
        Some(w) if w <= FACTORED => return Err(refuse(w, totient(w as u64), true)),
        Some(w) => {
            let bound = u64::try_from((w / 2).isqrt()).unwrap_or(u64::MAX);
            return Err(refuse(w, bound, false));
        }
        None => return Err(refuse(u128::MAX, u64::MAX, false)),
    };
    let degree = level_primes(w).0;
    if degree > limit {
        return Err(refuse(u128::from(w), degree, true));
    }
    Ok(w)
}

/// Whether a group whose pi offsets all have denominators dividing `den` is within the
/// context's degree limit whatever its offsets: its level divides `lcm(24, 2 den)` (see
/// [`level_of`]), and a level dividing another has a degree (`phi`) dividing the other's.
/// Products and canonical forms of such groups stay among them: a sum of offsets has a
/// denominator dividing `den`, and a group's basis at level `W` has offsets with
/// denominators dividing `W / 2 = lcm(12, den)`.
pub(crate) fn levels_within_limit(den: u64) -> bool {
    let limit = super::super::ctx::max_cyclotomic_degree();
    let d = 2 * u128::from(den);
    let w = 24 / 24u128.gcd(&d) * d;
    let cap = 2u128.saturating_mul(u128::from(limit).saturating_mul(u128::from(limit)));
    w <= cap && w <= 1_000_000_000_000 && level_primes(w as u64).0 <= limit
}

/// `phi(W)` and the primes of `W`, remembered per thread (every group asks for its level's).
pub(super) fn level_primes(w: u64) -> (u64, Rc<[u64]>) {
    type Levels = HashMap<u64, (u64, Rc<[u64]>), BuildHasherDefault<FxHasher>>;
    thread_local! {
        static LEVELS: RefCell<Levels> = RefCell::new(Levels::default());
    }
    LEVELS.with(|l| {
        l.borrow_mut()
            .entry(w)
            .or_insert_with(|| (totient(w), primes_of(w).into()))
            .clone()
    })
}

pub(super) fn primes_of(mut n: u64) -> Vec<u64> {
    let mut out = Vec::new();
    let mut p = 2;
    while p * p <= n {
        if n.is_multiple_of(p) {
            out.push(p);
            while n.is_multiple_of(p) {
                n /= p;
            }
        }
        p += 1;
    }
    if n > 1 {
        out.push(n);
    }
    out
}

pub(super) fn totient(n: u64) -> u64 {
    primes_of(n).iter().fold(n, |acc, p| acc / p * (p - 1))
}

pub(super) fn moebius(n: u64) -> i64 {
    let mut m = n;
    let mut k = 0;
    for p in primes_of(n) {
        m /= p;
        if m.is_multiple_of(p) {
            return 0;
        }
        k += 1;
    }
    if k % 2 == 0 {
        1
    } else {
        -1
    }
}

/// `e^{i pi p}` as a power of `zeta_W`.
pub(super) fn pi_exponent(p: &Small, w: u64) -> u64 {
    // p = n/d, 2d | W: exponent n W / (2d) mod W.
    let (n, d) = (*p.numer() as i128, *p.denom() as i128);
    let e = n * (w as i128) / (2 * d);
    e.rem_euclid(w as i128) as u64
}
