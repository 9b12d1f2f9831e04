//! From monomials to a nested display expression: common factors (symbols, trigonometric
//! atoms, numeric content) are pulled out where that lowers the cost.

use super::expr::{Cost, Expr};
use super::mon::{content, Atom, Mon};
use crate::scalar::Sym;

use num_rational::BigRational;
use num_traits::{One, Signed};
use std::collections::BTreeMap;

/// A factor that can be pulled out of several monomials.
#[derive(Clone, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Factor {
    Atom(Atom),
    Sym(Sym),
}

/// How many alternative factors are tried at each of the first levels.
const BRANCH: usize = 3;
/// How many levels branch; below them the most frequent factor is taken.
const BRANCH_DEPTH: usize = 3;

/// The cheapest nested expression this search finds for the sum of `mons`.
pub(crate) fn build(mons: &[Mon]) -> Expr {
    build_at(mons, 0)
}

fn build_at(mons: &[Mon], depth: usize) -> Expr {
    match mons {
        [] => return Expr::zero(),
        [m] => return mon_expr(m),
        _ => {}
    }
    // A sum whose terms are all negative reads better as the negation of a sum.
    if mons.iter().all(|m| m.q.is_negative()) {
        let neg: Vec<Mon> = mons
            .iter()
            .map(|m| Mon {
                q: -m.q.clone(),
                ..m.clone()
            })
            .collect();
        return Expr::Neg(Box::new(build_at(&neg, depth)));
    }
    let g = content(mons);
    if !g.is_one() {
        let inner: Vec<Mon> = mons
            .iter()
            .map(|m| Mon {
                q: &m.q / &g,
                ..m.clone()
            })
            .collect();
        return mul(vec![Expr::Num(g), build_at(&inner, depth)]);
    }
    let r = mons[0].rad;
    if r != 1 && mons.iter().all(|m| m.rad == r) {
        let inner: Vec<Mon> = mons
            .iter()
            .map(|m| Mon {
                rad: 1,
                ..m.clone()
            })
            .collect();
        return mul(vec![Expr::Sqrt(r), build_at(&inner, depth)]);
    }
    let candidates = candidates(mons);
    if candidates.is_empty() {
        return Expr::Add(mons.iter().map(mon_expr).collect());
    }
    let tries = if depth < BRANCH_DEPTH { BRANCH } else { 1 };
    let mut best: Option<(Cost, Expr)> = None;
    for f in candidates.into_iter().take(tries) {
        let e = split_on(mons, &f, depth);
        let c = e.cost();
        if best.as_ref().is_none_or(|(bc, _)| c < *bc) {
            best = Some((c, e));
        }
    }
    best.map(|(_, e)| e).unwrap_or_else(Expr::zero)
}

/// Factors that occur in at least two monomials, most frequent first, ties by factor order.
fn candidates(mons: &[Mon]) -> Vec<Factor> {
    let mut count: BTreeMap<Factor, usize> = BTreeMap::new();
    for m in mons {
        for (s, _) in &m.syms {
            *count.entry(Factor::Sym(s.clone())).or_default() += 1;
        }
        let mut last: Option<&Atom> = None;
        for a in &m.atoms {
            if last != Some(a) {
                *count.entry(Factor::Atom(a.clone())).or_default() += 1;
            }
            last = Some(a);
        }
    }
    let mut v: Vec<(Factor, usize)> = count.into_iter().filter(|(_, n)| *n >= 2).collect();
    v.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    v.into_iter().map(|(f, _)| f).collect()
}

/// `f * (sum of the monomials containing f, divided by f) + (the others)`.
fn split_on(mons: &[Mon], f: &Factor, depth: usize) -> Expr {
    let mut with = Vec::new();
    let mut without = Vec::new();
    let mut first_with = None;
    for (i, m) in mons.iter().enumerate() {
        match divide(m, f) {
            Some(d) => {
                first_with.get_or_insert(i);
                with.push(d)
            }
            None => without.push((i, m.clone())),
        }
    }
    let factored = mul(vec![factor_expr(f), build_at(&with, depth + 1)]);
    let first_with = first_with.unwrap_or(0);
    // Keep the reading order: the factored group stands where its first monomial stood.
    let before: Vec<Mon> = without
        .iter()
        .filter(|(i, _)| *i < first_with)
        .map(|(_, m)| m.clone())
        .collect();
    let after: Vec<Mon> = without
        .iter()
        .filter(|(i, _)| *i > first_with)
        .map(|(_, m)| m.clone())
        .collect();
    let mut terms = Vec::new();
    if !before.is_empty() || !after.is_empty() {
        let rest: Vec<Mon> = before.iter().chain(after.iter()).cloned().collect();
        let rest_expr = build_at(&rest, depth + 1);
        // Splice the rest around the factored group in reading order.
        let rest_terms = match rest_expr {
            Expr::Add(v) => v,
            e => vec![e],
        };
        let n_before = before.len().min(rest_terms.len());
        if rest_terms.len() == rest.len() {
            terms.extend(rest_terms[..n_before].iter().cloned());
            terms.push(factored);
            terms.extend(rest_terms[n_before..].iter().cloned());
        } else {
            terms.push(factored);
            terms.extend(rest_terms);
        }
    } else {
        terms.push(factored);
    }
    if terms.len() == 1 {
        terms.pop().unwrap_or_else(Expr::zero)
    } else {
        Expr::Add(terms)
    }
}

fn divide(m: &Mon, f: &Factor) -> Option<Mon> {
    let mut m = m.clone();
    match f {
        Factor::Sym(s) => {
            let pos = m.syms.iter().position(|(x, _)| x == s)?;
            if m.syms[pos].1 == 1 {
                m.syms.remove(pos);
            } else {
                m.syms[pos].1 -= 1;
            }
        }
        Factor::Atom(a) => {
            let pos = m.atoms.iter().position(|x| x == a)?;
            m.atoms.remove(pos);
        }
    }
    Some(m)
}

fn factor_expr(f: &Factor) -> Expr {
    match f {
        Factor::Sym(s) => Expr::Sym(s.clone()),
        Factor::Atom(a) => Expr::Trig {
            sin: a.sin,
            angle: a.angle.clone(),
        },
    }
}

/// A product, flattened, with a leading negation pulled out of it.
pub(crate) fn mul(parts: Vec<Expr>) -> Expr {
    let mut flat = Vec::new();
    let mut neg = false;
    for p in parts {
        match p {
            Expr::Mul(v) => flat.extend(v),
            Expr::Neg(e) => {
                neg = !neg;
                match *e {
                    Expr::Mul(v) => flat.extend(v),
                    e => flat.push(e),
                }
            }
            Expr::Num(q) if q.is_one() => {}
            e => flat.push(e),
        }
    }
    // Numbers first, then radicals, symbols, sums and trigonometric factors.
    flat.sort_by_key(rank);
    let e = match flat.len() {
        0 => Expr::Num(BigRational::one()),
        1 => flat.pop().unwrap_or_else(Expr::zero),
        _ => Expr::Mul(flat),
    };
    if neg {
        Expr::Neg(Box::new(e))
    } else {
        e
    }
}

fn rank(e: &Expr) -> u8 {
    match e {
        Expr::Num(_) => 0,
        Expr::Sqrt(_) => 1,
        Expr::Sym(_) | Expr::Pow(..) => 2,
        Expr::Trig { .. } => 3,
        _ => 4,
    }
}

/// One monomial as an expression: `-2 sqrt(3) l1^2 c1`.
pub(crate) fn mon_expr(m: &Mon) -> Expr {
    let mut parts = Vec::new();
    let q = m.q.abs();
    if !q.is_one() {
        parts.push(Expr::Num(q));
    }
    if m.rad != 1 {
        parts.push(Expr::Sqrt(m.rad));
    }
    for (s, e) in &m.syms {
        parts.push(if *e == 1 {
            Expr::Sym(s.clone())
        } else {
            Expr::Pow(Box::new(Expr::Sym(s.clone())), *e)
        });
    }
    for a in &m.atoms {
        parts.push(Expr::Trig {
            sin: a.sin,
            angle: a.angle.clone(),
        });
    }
    let e = mul(parts);
    if m.q.is_negative() {
        Expr::Neg(Box::new(e))
    } else {
        e
    }
}
