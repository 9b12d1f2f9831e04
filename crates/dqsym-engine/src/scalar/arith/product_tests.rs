//! [`product_terms`] and [`mul`] against the route they replaced, kept here as the reference:
//! the same terms in the same order, the same trace marks, the same errors, on random scalars.

use super::super::atoms::{mode_mul, mono_mul, rad_mul, trig_mode, Mode, Small, Sym};
use super::super::ctx::test_hook;
use super::super::{Context, Poll, ProductTrace, Scalar, ScalarError, Term, Q};
use super::{admit_product, mul, product_terms, product_work, scales};
use crate::testing::xorshift_below;
use num_bigint::BigInt;
use num_rational::BigRational;
use std::sync::Arc;

/// Splits a sorted term slice into runs that share a mode (the replaced route's, a vector a
/// call).
fn mode_runs(t: &[Term]) -> Vec<&[Term]> {
    let mut runs = Vec::with_capacity(t.len());
    let mut start = 0;
    for i in 1..=t.len() {
        if i == t.len() || t[i].mode != t[start].mode {
            runs.push(&t[start..i]);
            start = i;
        }
    }
    runs
}

/// The replaced `product_terms`: the right factor's runs found again for every run of the
/// left one, every mode product by [`mode_mul`] (here not even cached), a unit mode's too,
/// every monomial by [`mono_mul`], every coefficient times its weight (1 included).
fn product_terms_reference(
    x: &[Term],
    y: &[Term],
    minus: bool,
    out: &mut Vec<Term>,
    mut trace: Option<&mut ProductTrace>,
) -> Result<(), ScalarError> {
    let mut poll = Poll::default();
    let mut ia = 0;
    for ra in mode_runs(x) {
        let mut ib = 0;
        for rb in mode_runs(y) {
            let modes = mode_mul(&ra[0].mode, &rb[0].mode);
            for (i, s) in (ia..).zip(ra) {
                for (j, t) in (ib..).zip(rb) {
                    poll.step()?;
                    let mono = mono_mul(&s.mono, &t.mono)
                        .ok_or_else(|| ScalarError::OutOfRange("exponent too large".into()))?;
                    let (rad, g) = rad_mul(s.rad, t.rad)
                        .ok_or_else(|| ScalarError::OutOfRange("radicand too large".into()))?;
                    let mut coef = &s.coef * &t.coef;
                    if g != 1 {
                        coef = &coef * &Q::from_u64(g);
                    }
                    if minus {
                        coef = -coef;
                    }
                    for (mode, weights) in modes.iter() {
                        for (r2, w) in weights {
                            let (rad3, g2) = rad_mul(rad, *r2).ok_or_else(|| {
                                ScalarError::OutOfRange("radicand too large".into())
                            })?;
                            let mut c = &coef * w;
                            if g2 != 1 {
                                c = &c * &Q::from_u64(g2);
                            }
                            if let Some(trace) = trace.as_deref_mut() {
                                trace.mark(out.len(), (i, &s.mode), (j, &t.mode), mode);
                            }
                            out.push(Term {
                                mode: mode.clone(),
                                mono: mono.clone(),
                                rad: rad3,
                                coef: c,
                            });
                        }
                    }
                }
            }
            ib += rb.len();
        }
        ia += ra.len();
    }
    Ok(())
}

/// [`mul`] through [`product_terms_reference`].
fn mul_reference(a: &Scalar, b: &Scalar) -> Scalar {
    let (x, y) = terms_or_return!(a, b);
    if let Err(e) = admit_product(x, y) {
        return Scalar::error(e);
    }
    let settled = scales(x) || scales(y);
    let mut trace = if settled {
        None
    } else {
        ProductTrace::new(x, y)
    };
    let mut out = Vec::new();
    if let Err(e) = product_terms_reference(x, y, false, &mut out, trace.as_mut()) {
        return Scalar::error(e);
    }
    if settled {
        return Scalar::from_terms_settled(out);
    }
    match trace {
        Some(trace) => {
            let known = trace.settled(&out);
            Scalar::from_terms_known(out, &known)
        }
        None => Scalar::from_terms(out),
    }
}

/// A random canonical scalar: up to `max` terms (none at times) with small or big rational
/// coefficients, radicals (huge coprime radicands at times, whose products leave a machine
/// word), monomials in a few symbols (an exponent near `u32::MAX` at times, whose square
/// overflows), and modes: `1`, cos or sin of angles in `q1`, `q2`, `t` and the constant `1`,
/// with offsets at twelfths of pi (expanded) and at fifths, sevenths, eighths (cyclotomic
/// constants and offsets), constant modes among them; or an error value.
fn random_scalar(next: &mut impl FnMut(u64) -> u64, max: u64) -> Scalar {
    if next(40) == 0 {
        return Scalar::error(ScalarError::DivisionByZero);
    }
    let angle_syms = [Sym::one(), Sym::new("q1"), Sym::new("q2"), Sym::new("t")];
    let mono_syms = ["a1", "a2", "d1", "d3", "l"].map(Sym::new);
    let unit_share = next(3);
    let mut terms = Vec::new();
    for _ in 0..next(max + 1) {
        let coef = match next(8) {
            0 => Q::big(BigRational::new(
                (BigInt::from(1u64 << 60) * BigInt::from(1 + next(1 << 20)))
                    * if next(2) == 0 { 1 } else { -1 },
                BigInt::from(3 + 2 * next(40)),
            )),
            _ => Q::new(next(19) as i64 - 9, 1 + next(6) as i64),
        };
        if coef == Q::ZERO {
            continue;
        }
        let rad = match next(12) {
            0 => [10_000_000_019u64, 10_000_000_033][next(2) as usize],
            1..=5 => [2, 3, 5, 6, 7, 10][next(6) as usize],
            _ => 1,
        };
        let mut mono: Vec<(Sym, u32)> = Vec::new();
        for s in &mono_syms {
            if next(3) == 0 {
                let e = if next(60) == 0 {
                    u32::MAX - 1
                } else {
                    1 + next(3) as u32
                };
                mono.push((s.clone(), e));
            }
        }
        let modes = if next(3) < unit_share {
            vec![(Mode::unit(), vec![(1, Q::ONE)])]
        } else {
            let mut freq = Vec::new();
            for s in &angle_syms {
                if next(2) == 0 {
                    freq.push((
                        s.clone(),
                        Small::new(next(7) as i64 - 3, 1 + next(2) as i64),
                    ));
                }
            }
            let den = [1, 12, 12, 5, 7, 8][next(6) as usize];
            let pi = Small::new(next(2 * den as u64) as i64, den);
            trig_mode(next(2) == 0, freq, pi)
        };
        for (mode, weights) in modes {
            for (r, w) in weights {
                let Some((r, g)) = rad_mul(rad, r) else {
                    continue;
                };
                terms.push(Term {
                    mode: mode.clone(),
                    mono: Arc::from(mono.clone()),
                    rad: r,
                    coef: &(&coef * &w) * &Q::from_u64(g),
                });
            }
        }
    }
    Scalar::from_terms(terms)
}

/// The terms of `x y` (of `-x y` when `minus`), traced when a trace applies: the terms (or
/// error) with the marks, and how often the cancel flag was looked at.
type Formed = (
    Result<Vec<Term>, ScalarError>,
    Option<Vec<(usize, u64)>>,
    u64,
);

/// A route forming the terms of a product: [`product_terms`] or its reference.
type Route = fn(
    &[Term],
    &[Term],
    bool,
    &mut Vec<Term>,
    Option<&mut ProductTrace>,
) -> Result<(), ScalarError>;

fn formed(route: Route, x: &[Term], y: &[Term], minus: bool) -> Formed {
    test_hook::reset(None);
    let mut trace = ProductTrace::new(x, y);
    // A term already in `out`, as `sums_of_products` leaves them: indices count on from it.
    let mut out = x.first().cloned().into_iter().collect::<Vec<_>>();
    let r = route(x, y, minus, &mut out, trace.as_mut()).map(|()| out);
    (r, trace.map(|t| t.marks().to_vec()), test_hook::looks())
}

/// The terms formed, in their order, the trace's marks and the error (or none) of each
/// product: the same both ways, on products of random scalars of all kinds (unit modes on
/// either side or both, angles with and without offsets, big coefficients, overflowing
/// exponents and radicands); and the scalar `mul` makes, the reference route's.
#[test]
fn products_are_the_replaced_route() {
    let mut next = xorshift_below(2029);
    let (mut checked, mut traced, mut failed, mut units, mut long) = (0, 0, 0, 0, 0);
    for i in 0..3000 {
        let max = if i % 10 == 9 { 40 } else { 8 };
        let (a, b) = (random_scalar(&mut next, max), random_scalar(&mut next, max));
        let (Ok(x), Ok(y)) = (a.terms(), b.terms()) else {
            assert_eq!(mul(&a, &b), mul_reference(&a, &b));
            continue;
        };
        for minus in [false, true] {
            let new = formed(product_terms, x, y, minus);
            let old = formed(product_terms_reference, x, y, minus);
            assert_eq!(new, old, "{a:?} * {b:?}");
            traced += usize::from(new.1.as_ref().is_some_and(|m| !m.is_empty()));
            failed += usize::from(new.0.is_err());
        }
        let (p, q) = (mul(&a, &b), mul_reference(&a, &b));
        assert_eq!(p, q, "{a:?} * {b:?}");
        let has_unit = |t: &[Term]| t.iter().any(|t| t.mode.is_unit());
        units += usize::from(has_unit(x) && has_unit(y));
        long += usize::from(x.len() * y.len() > 256);
        checked += 1;
    }
    assert!(checked > 2500, "{checked} products");
    assert!(traced > 100, "{traced} traced");
    assert!(failed > 50, "{failed} errors");
    assert!(units > 500, "{units} with unit modes on both sides");
    assert!(long > 50, "{long} long");
}

/// At the edges of the term limit (pairs refused, results too large) and of the work budget
/// (the product's charge exactly within it, one unit over), and with the context cancelled at
/// a look of the product's loop: the same value or error both ways, and the same work charged
/// (the per-thread caches warmed first, as a miss charges its work).
#[test]
fn products_at_the_limits_are_the_replaced_route() {
    let mut next = xorshift_below(77);
    let (mut edges, mut errors) = (0, 0);
    for _ in 0..300 {
        let (a, b) = (random_scalar(&mut next, 24), random_scalar(&mut next, 24));
        let (Ok(x), Ok(y)) = (a.terms(), b.terms()) else {
            continue;
        };
        let (pairs, work) = (x.len() * y.len(), product_work(x, y));
        if pairs == 0 {
            continue;
        }
        let contexts = [
            Context::new().with_term_limit(pairs / 2),
            Context::new().with_term_limit(pairs.div_ceil(2)),
            Context::new().with_term_limit((pairs / 3).max(1)),
            Context::new().with_work_budget(work),
            Context::new().with_work_budget(work - 1),
        ];
        for ctx in contexts {
            let run = |f: fn(&Scalar, &Scalar) -> Scalar| {
                let guard = ctx.enter();
                let p = f(&a, &b);
                (p, guard.work_used())
            };
            // Once before, so that both find the per-thread caches (of cyclotomic bases,
            // whose misses charge their work) as the other did.
            run(mul);
            let (p, q) = (run(mul), run(mul_reference));
            assert_eq!(p, q, "{a:?} * {b:?}");
            errors += usize::from(p.0.as_error().is_some());
            edges += 1;
        }
        for at in [1, 2, 3] {
            let run = |f: fn(&Scalar, &Scalar) -> Scalar| {
                test_hook::reset(Some(at));
                let p = f(&a, &b);
                test_hook::reset(None);
                p
            };
            assert_eq!(run(mul), run(mul_reference), "{a:?} * {b:?}");
        }
    }
    assert!(edges > 1000, "{edges}");
    assert!(errors > 300, "{errors}");
}
