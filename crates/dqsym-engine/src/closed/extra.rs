//! The candidates added for issue 33's held-out corpus, made in one place for
//! `alt::best_alternative`: squares of sums (`square.rs`); a sum split into the parts whose
//! angles have one set of symbols, each part's closed form found alone (`2 sin(u1/2)
//! sin(u1 - u2) - cos(p) cos(u1) sin(w)`, whose parts share `u1`, which `trigfac.rs` keeps
//! together); and any candidate that is a sum of
//! products sharing a factor with that factor taken out (`k2 cos(w/2 - pi/3) sin(w) -
//! k2 sin(p/2 + u2) cos(r)` is `k2 (cos(w/2 - pi/3) sin(w) - sin(p/2 + u2) cos(r))`: the parts
//! of `trigfac.rs`'s split sums and the constant products of `cprod.rs` are found apart and
//! joined by an addition, never factored).

use super::alt::{full_cost, mul, neg};
use super::expr::Expr;
use crate::scalar::{charge, Sym, Term};
use crate::Scalar;

/// The candidates of the files listed above for the canonical terms `t`, not yet checked
/// against them; `than` is the form found before and `others` the other candidates (only
/// shorter ones can be taken).
pub(super) fn candidates(t: &[Term], than: &Expr, others: &[Expr]) -> Vec<Expr> {
    let mut out = candidates_up_to(t, full_cost(than).0, others);
    if !out.is_empty() || super::trigfac::may_nest() {
        out.extend(common_factor(than));
    }
    out
}

/// The candidates of [`candidates`] made without a form found before, for costs below
/// `bound`: what a search capped at `bound` (`floor.rs`) must count as possible winners.
pub(super) fn candidates_up_to(t: &[Term], bound: usize, others: &[Expr]) -> Vec<Expr> {
    // Each candidate costs an exact check: made only while half the budget is left (as
    // `trigfac.rs`'s), so that they never turn a form found within the budget into an error.
    if !super::trigfac::may_nest() {
        return Vec::new();
    }
    let mut out: Vec<Expr> = others.iter().filter_map(common_factor).collect();
    out.extend(super::square::candidates(t, bound));
    if let Some(e) = by_support(t, bound) {
        out.extend(common_factor(&e));
        out.push(e);
    }
    out
}

/// The most parts [`by_support`] makes.
const MAX_PARTS: usize = 4;

/// The most terms [`by_support`] splits (as `trigfac.rs`'s candidates).
const MAX_TERMS: usize = 24;

/// The sum split by the set of symbols of each term's angle (a term without an angle joins
/// the first part of its monomial), each part's closed form found alone; `None` for one part,
/// or when a lower bound of the cost is not below `bound`. Not made for modes at one step
/// without offsets or radicals (`trigfac::unit_modes`, the PUMA's scalars), whose products
/// the regrouping of single-angle atoms already finds, part by part.
fn by_support(t: &[Term], bound: usize) -> Option<Expr> {
    if t.len() < 3
        || t.len() > MAX_TERMS
        || super::trigfac::unit_modes(t)
        || !super::trigfac::may_nest()
    {
        return None;
    }
    if t.iter()
        .any(|u| u.mode.freq.iter().any(|(s, _)| s.is_one()))
    {
        return None;
    }
    let support = |u: &Term| -> Vec<Sym> { u.mode.freq.iter().map(|(s, _)| s.clone()).collect() };
    let mut keys: Vec<Vec<Sym>> = Vec::new();
    let mut part: Vec<usize> = Vec::with_capacity(t.len());
    for u in t.iter().filter(|u| !u.mode.freq.is_empty()) {
        let k = support(u);
        if !keys.contains(&k) {
            keys.push(k);
        }
    }
    if !(2..=MAX_PARTS).contains(&keys.len()) {
        return None;
    }
    for u in t {
        let p = if u.mode.freq.is_empty() {
            t.iter()
                .filter(|v| !v.mode.freq.is_empty() && v.mono == u.mono)
                .map(|v| keys.iter().position(|k| *k == support(v)))
                .next()
                .flatten()
                .unwrap_or(0)
        } else {
            keys.iter().position(|k| *k == support(u))?
        };
        part.push(p);
    }
    let group = |p: usize| -> Vec<Term> {
        t.iter()
            .zip(&part)
            .filter(|(_, q)| **q == p)
            .map(|(u, _)| u.clone())
            .collect()
    };
    let least: usize = (keys.len() - 1)
        + (0..keys.len())
            .map(|p| super::trigfac::least_cost(&group(p)))
            .sum::<usize>();
    if least >= bound {
        return None;
    }
    charge(t.len() as u64).ok()?;
    let mut sum = Vec::with_capacity(keys.len());
    for p in 0..keys.len() {
        let x = Scalar::from_terms_sorted(group(p));
        match super::trigfac::nested_closed_form(&x).ok()? {
            Expr::Add(v) => sum.extend(v),
            e => sum.push(e),
        }
    }
    sum.sort_by_key(|e| matches!(e, Expr::Neg(_)));
    Some(Expr::Add(sum))
}

/// A summand as its sign and its factors, a power `x^n` as `n` factors `x` (numbers kept).
fn factors(e: &Expr) -> (bool, Vec<&Expr>) {
    let (negated, e) = match e {
        Expr::Neg(x) => (true, &**x),
        e => (false, e),
    };
    let mut out = Vec::new();
    fn push<'a>(f: &'a Expr, out: &mut Vec<&'a Expr>) {
        match f {
            Expr::Pow(x, n) => out.extend(std::iter::repeat_n(&**x, *n as usize)),
            f => out.push(f),
        }
    }
    match e {
        Expr::Mul(v) => v.iter().for_each(|f| push(f, &mut out)),
        f => push(f, &mut out),
    }
    (negated, out)
}

/// Factors back into a product, equal factors as a power.
fn product(fs: &[&Expr]) -> Expr {
    let mut v: Vec<Expr> = Vec::new();
    let mut i = 0;
    while i < fs.len() {
        let n = fs[i..].iter().take_while(|f| **f == fs[i]).count();
        v.push(if n == 1 {
            (*fs[i]).clone()
        } else {
            Expr::Pow(Box::new((*fs[i]).clone()), n as u32)
        });
        i += n;
    }
    match v.len() {
        0 => Expr::Num(num_rational::BigRational::from_integer(1.into())),
        1 => v.pop().expect("one factor"),
        _ => Expr::Mul(v),
    }
}

/// The sum `e` (or a number times it) with the factors common to all its summands (other
/// than numbers) taken out: `c (a + b)` for `c a + c b`; `None` when they share none.
fn common_factor(e: &Expr) -> Option<Expr> {
    let (front, sum) = match e {
        Expr::Add(v) => (None, v),
        Expr::Mul(v) if v.len() == 2 => match (&v[0], &v[1]) {
            (Expr::Num(_), Expr::Add(s)) => (Some(v[0].clone()), s),
            _ => return None,
        },
        _ => return None,
    };
    if sum.len() < 2 {
        return None;
    }
    let parts: Vec<(bool, Vec<&Expr>)> = sum.iter().map(factors).collect();
    // The common factors with their multiplicities: those of the first summand kept while
    // every other summand has one left.
    let mut rests: Vec<Vec<&Expr>> = parts.iter().map(|(_, f)| f.clone()).collect();
    let mut common: Vec<&Expr> = Vec::new();
    for &f in &parts[0].1 {
        if matches!(f, Expr::Num(_)) {
            continue;
        }
        if rests.iter().all(|r| r.contains(&f)) {
            for r in rests.iter_mut() {
                let i = r.iter().position(|g| *g == f).expect("present");
                r.remove(i);
            }
            common.push(f);
        }
    }
    if common.is_empty() {
        return partial_factor(front, sum, &parts);
    }
    let inner: Vec<Expr> = parts
        .iter()
        .zip(&rests)
        .map(|((negated, _), r)| {
            let p = product(r);
            if *negated {
                neg(p)
            } else {
                p
            }
        })
        .collect();
    let out = match signed_sum(inner) {
        Expr::Neg(sum) => neg(mul(product(&common), *sum)),
        sum => mul(product(&common), sum),
    };
    Some(match front {
        Some(n) => mul(n, out),
        None => out,
    })
}

/// The terms as a sum, positive terms first as the printers order a sum; when every term is
/// negative, minus the sum of their negations (`-(a + b)`, one negation: a sum whose terms
/// are all negative needs one, which the cost of a sum does not count).
fn signed_sum(mut terms: Vec<Expr>) -> Expr {
    if terms.iter().all(|e| matches!(e, Expr::Neg(_))) {
        return neg(Expr::Add(terms.into_iter().map(neg).collect()));
    }
    terms.sort_by_key(|e| matches!(e, Expr::Neg(_)));
    Expr::Add(terms)
}

/// The factor (other than a number) in the most summands, two or more but not all, taken
/// out of those: `c a + c b + d` as `c (a + b) + d`; then again in the sum left.
fn partial_factor(front: Option<Expr>, sum: &[Expr], parts: &[(bool, Vec<&Expr>)]) -> Option<Expr> {
    let mut best: Option<(&Expr, usize)> = None;
    for (_, fs) in parts {
        for &f in fs {
            if matches!(f, Expr::Num(_)) || best.is_some_and(|(b, _)| b == f) {
                continue;
            }
            let n = parts.iter().filter(|(_, g)| g.contains(&f)).count();
            if n >= 2 && best.is_none_or(|(_, m)| n > m) {
                best = Some((f, n));
            }
        }
    }
    let (f, _) = best?;
    let mut with: Vec<Expr> = Vec::new();
    let mut rest: Vec<Expr> = Vec::new();
    for (e, (_, g)) in sum.iter().zip(parts) {
        if g.contains(&f) {
            with.push(e.clone());
        } else {
            rest.push(e.clone());
        }
    }
    let grouped = common_factor(&Expr::Add(with))?;
    let rest = if rest.len() >= 2 {
        match common_factor(&Expr::Add(rest.clone())) {
            Some(e) => vec![e],
            None => rest,
        }
    } else {
        rest.pop().into_iter().collect()
    };
    let mut v = vec![grouped];
    v.extend(rest);
    v.sort_by_key(|e| matches!(e, Expr::Neg(_)));
    let out = Expr::Add(v);
    Some(match front {
        Some(n) => mul(n, out),
        None => out,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Sym;

    #[test]
    fn a_factor_shared_by_every_summand_is_taken_out() {
        let (a, b, k) = (
            Expr::Sym(Sym::new("a")),
            Expr::Sym(Sym::new("b")),
            Expr::Sym(Sym::new("k")),
        );
        let e = Expr::Add(vec![
            Expr::Mul(vec![k.clone(), a.clone()]),
            neg(Expr::Mul(vec![
                k.clone(),
                Expr::Pow(Box::new(b.clone()), 2),
            ])),
        ]);
        let c = common_factor(&e).expect("a common factor");
        assert_eq!(c.to_scalar(), e.to_scalar());
        assert!(full_cost(&c) < full_cost(&e));
        assert!(common_factor(&Expr::Add(vec![a, b])).is_none());
    }
}
