//! A sum of Fourier terms as a polynomial in `c_x = cos(u_x x)`, `s_x = sin(u_x x)` and the
//! monomial symbols (`u_x` the largest unit the angles of `x` are whole multiples of), factored
//! over the integers (`zfactor.rs`) in three readings: as it expands, with `s_x^2 = 1 - c_x^2`
//! and with `c_x^2 = 1 - s_x^2` (each reading a polynomial of its own; equal on the circle).
//! The same is done with the modes' directions as the variables in place of the symbols
//! (`c_g = cos(u_g g)` for `g = a + b`), when some mode is a multiple of two or more of its
//! direction's unit: `a2^2 cos(a)^2 - a3^2 cos(a + b)^2` is a polynomial of degree 2 in
//! `cos(a)`, `cos(a + b)`, but of degree 4 in the cosines and sines of `a` and `b`.
//! Each factorization with at least two factors is offered as a closed form, each factor shown
//! as its polynomial or as its own closed form, whichever is cheaper
//! (`cos(a)^2 - cos(b)^2 = (cos a - cos b)(cos a + cos b)`,
//! `(1 + cos x)(1 - cos y)` from its expansion in `x + y` and `x - y`).

use super::alt::{mul, neg, num, shorter, trig};
use super::expr::Expr;
use super::zfactor::{factor, MPoly};
use crate::scalar::atoms::Small;
use crate::scalar::{charge, Sym, Term};
use crate::Scalar;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational as Rat;
use num_traits::{One, Signed, Zero};
use std::collections::BTreeMap;

/// The largest number of terms a sum may have for its factorization to be tried.
const MAX_TERMS: usize = 24;
/// The largest multiple of an angle's unit expanded.
const MAX_MULTIPLE: i64 = 8;
/// The most variables (cosines, sines and monomial symbols) of the polynomial.
const MAX_VARS: usize = 9;
/// The largest number of terms a sum may have to be read by its modes' directions: a
/// polynomial of degree two in two or three angle sums and a few lengths has few Fourier
/// terms, and the entries of a 6-joint chain, which this reading would only slow down, have
/// more.
const MAX_DIRECTION_TERMS: usize = 12;
/// The most angle symbols: sums in more angles (the entries of a 6-joint chain) are left to
/// the regrouping, which this search would only slow down.
const MAX_ANGLES: usize = 3;

/// A variable of the polynomial: the cosine or sine of an angle (its frequency vector), or a
/// monomial symbol.
#[derive(Clone, PartialEq, Eq, PartialOrd, Ord)]
enum Var {
    Cos(Vec<(Sym, Small)>),
    Sin(Vec<(Sym, Small)>),
    Sym(Sym),
}

type CPoly = BTreeMap<Vec<u32>, (Rat, Rat)>;

fn c_add(p: &mut CPoly, e: Vec<u32>, re: Rat, im: Rat) {
    let v = p
        .entry(e.clone())
        .or_insert_with(|| (Rat::zero(), Rat::zero()));
    v.0 += re;
    v.1 += im;
    if v.0.is_zero() && v.1.is_zero() {
        p.remove(&e);
    }
}

/// The factored forms of the sum of `t` (see the module text); empty when none applies, and
/// inside the closed form of one of this file's factors or pairs of factors (see [`nested`]).
pub(super) fn factored_forms(t: &[Term]) -> Vec<Expr> {
    if nested_open() {
        return Vec::new();
    }
    candidates(t).unwrap_or_default()
}

/// Whether a closed form of this file's [`nested`] is open on this thread (the memo of
/// `closed/mod.rs` keeps what it finds apart).
pub(super) fn nested_open() -> bool {
    NESTED.with(|n| n.get())
}

thread_local! {
    /// Whether a closed form of this file's [`nested`] is open on this thread.
    static NESTED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// The closed form of a factor, or of a pair of factors, of a factorization, found without
/// factoring it again: its factors are known (those of the reading it came from), and what its
/// closed form is asked for is a shorter way to write them, an angle sum or a multiple angle
/// (`sin(2)` for `2 cos(1) sin(1)`), which the regrouped and whole-mode shapes and the other
/// candidates find. Factored again, each reading of each factor and pair asked for the
/// closed forms of its own factors and pairs, and those of theirs: `sin(1) sin(2) sin(3)`, a
/// polynomial of degree 6 in `cos(1)`, `sin(1)`, spent 100 million instructions in a hundred
/// nested searches and two hundred factorizations.
fn nested(x: &Scalar) -> Option<Expr> {
    let outer = NESTED.with(|n| n.replace(true));
    let e = super::closed_form(x).ok();
    NESTED.with(|n| n.set(outer));
    e
}

/// How a sum is read as a polynomial: the angles whose cosine and sine are its variables
/// (unit angles, each a pair `c`, `s`), and each term's mode as whole multiples of them.
struct Reading {
    /// The unit angles' frequency vectors.
    units: Vec<Vec<(Sym, Small)>>,
    /// Per term, `(unit, multiple)`: the mode's angle is the sum of the multiples.
    parts: Vec<Vec<(usize, i64)>>,
}

/// Each angle symbol its own unit: one over the common denominator of its coefficients
/// (`cos(2 b)` read as `c_b^2 - s_b^2`, `cos(q/2)` as `c`); `None` past [`MAX_ANGLES`]
/// symbols.
fn by_symbols(t: &[Term]) -> Option<Reading> {
    let mut unit: BTreeMap<Sym, Small> = BTreeMap::new();
    for u in t {
        for (s, k) in u.mode.freq.iter() {
            if unit.len() == MAX_ANGLES && !unit.contains_key(s) {
                return None;
            }
            let e = unit.entry(s.clone()).or_insert(Small::one());
            *e = Small::new(1, e.denom().lcm(k.denom()));
        }
    }
    let index: BTreeMap<&Sym, usize> = unit.keys().enumerate().map(|(i, s)| (s, i)).collect();
    let parts = t
        .iter()
        .map(|u| {
            u.mode
                .freq
                .iter()
                .map(|(s, k)| (index[s], (*k / unit[s]).to_integer()))
                .collect()
        })
        .collect();
    Some(Reading {
        units: unit.iter().map(|(s, k)| vec![(s.clone(), *k)]).collect(),
        parts,
    })
}

/// Each mode's direction its own unit, as the angle sums of a regrouped form read
/// (`a2^2 cos(a)^2 - a3^2 cos(a + b)^2` from its modes `2 a` and `2 a + 2 b`: variables
/// `cos(a)`, `cos(a + b)`): a mode `k g`, `g` with coprime integer coefficients and a positive
/// first one, is the multiple `k / u_g` of the unit `u_g g`, `u_g` one over the common
/// denominator of the `k` of that direction. `None` when it would be the reading by symbols
/// (every direction a single symbol), past [`MAX_ANGLES`] directions, or when no mode is a
/// multiple of two or more of its unit (without a square or a product of equal angles there
/// is nothing for this reading to find that the regrouping does not).
fn by_directions(t: &[Term]) -> Option<Reading> {
    if t.len() > MAX_DIRECTION_TERMS {
        return None;
    }
    // First without arithmetic: modes on different sets of symbols are different directions,
    // and a sum with a mode of two or more symbols is needed.
    let mut supports: Vec<&[(Sym, Small)]> = Vec::with_capacity(MAX_ANGLES);
    let same = |a: &[(Sym, Small)], b: &[(Sym, Small)]| {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.0 == y.0)
    };
    for u in t {
        let f = &u.mode.freq[..];
        if !f.is_empty() && !supports.iter().any(|g| same(g, f)) {
            if supports.len() == MAX_ANGLES {
                return None;
            }
            supports.push(f);
        }
    }
    if supports.iter().all(|g| g.len() < 2) {
        return None;
    }
    // Per term its direction (coprime integers, the first positive) and the scale `num/den`
    // of its mode along it, in integers.
    let mut dirs: Vec<(Vec<(Sym, i64)>, i64)> = Vec::new();
    let mut scaled: Vec<Option<(usize, i64, i64)>> = Vec::with_capacity(t.len());
    for u in t {
        let f = &u.mode.freq;
        if f.is_empty() {
            scaled.push(None);
            continue;
        }
        let mut num = f.iter().fold(0i64, |g, (_, k)| g.gcd(k.numer()));
        let den = f.iter().fold(1i64, |l, (_, k)| l.lcm(k.denom()));
        if *f[0].1.numer() < 0 {
            num = -num;
        }
        let g: Vec<(Sym, i64)> = f
            .iter()
            .map(|(s, k)| (s.clone(), k.numer() * (den / k.denom()) / num))
            .collect();
        let i = match dirs.iter().position(|(h, _)| *h == g) {
            Some(i) => i,
            None => {
                if dirs.len() == MAX_ANGLES {
                    return None;
                }
                dirs.push((g, 1));
                dirs.len() - 1
            }
        };
        dirs[i].1 = dirs[i].1.lcm(&den);
        scaled.push(Some((i, num, den)));
    }
    // The multiple of the unit `g / lcm_den`: `num/den * lcm_den`.
    let parts: Vec<Vec<(usize, i64)>> = scaled
        .iter()
        .map(|p| match *p {
            Some((i, num, den)) => vec![(i, num * (dirs[i].1 / den))],
            None => Vec::new(),
        })
        .collect();
    if dirs.iter().all(|(g, _)| g.len() == 1) || !parts.iter().flatten().any(|(_, m)| m.abs() >= 2)
    {
        return None;
    }
    let units = dirs
        .into_iter()
        .map(|(g, d)| g.into_iter().map(|(s, k)| (s, Small::new(k, d))).collect())
        .collect();
    Some(Reading { units, parts })
}

fn candidates(t: &[Term]) -> Option<Vec<Expr>> {
    if t.len() < 2 || t.len() > MAX_TERMS {
        return None;
    }
    if t.iter().any(|u| u.rad != 1 || *u.mode.pi.denom() > 2) {
        return None;
    }
    let readings: Vec<Reading> = [by_symbols(t), by_directions(t)]
        .into_iter()
        .flatten()
        .collect();
    if readings.is_empty() {
        return None;
    }
    let mut syms: Vec<Sym> = Vec::new();
    for u in t {
        for (s, _) in u.mono.iter() {
            if !syms.contains(s) {
                syms.push(s.clone());
            }
        }
    }
    syms.sort();
    let mut out = Vec::new();
    for reading in &readings {
        if let Some(found) = read(t, reading, &syms) {
            out.extend(found);
        }
    }
    Some(out)
}

/// The candidates of one reading: each of its three polynomials expanded and factored.
fn read(t: &[Term], reading: &Reading, syms: &[Sym]) -> Option<Vec<Expr>> {
    let mut vars: Vec<Var> = Vec::new();
    for g in &reading.units {
        vars.push(Var::Cos(g.clone()));
        vars.push(Var::Sin(g.clone()));
    }
    vars.extend(syms.iter().cloned().map(Var::Sym));
    if vars.len() > MAX_VARS || reading.units.is_empty() || reading.units.len() > MAX_ANGLES {
        return None;
    }
    let n = vars.len();
    let pos = |v: &Var| vars.iter().position(|w| w == v);
    // The expansion: cos and sin of sum m_g u_g + p pi are the real and imaginary parts of
    // i^(2p) prod (c_g + i s_g)^(m_g).
    let mut poly: BTreeMap<Vec<u32>, Rat> = BTreeMap::new();
    for (u, parts) in t.iter().zip(&reading.parts) {
        let mut base = vec![0u32; n];
        for (s, e) in u.mono.iter() {
            base[pos(&Var::Sym(s.clone()))?] += e;
        }
        let mut p: CPoly = BTreeMap::from([(base, (u.coef.to_big(), Rat::zero()))]);
        for &(g, m) in parts {
            if m.abs() > MAX_MULTIPLE {
                return None;
            }
            let (ci, si) = (2 * g, 2 * g + 1);
            let sigma = Rat::from_integer(BigInt::from(m.signum()));
            for _ in 0..m.abs() {
                charge(p.len() as u64).ok()?;
                let mut q = CPoly::new();
                for (e, (a, b)) in &p {
                    let mut ec = e.clone();
                    ec[ci] += 1;
                    c_add(&mut q, ec, a.clone(), b.clone());
                    let mut es = e.clone();
                    es[si] += 1;
                    c_add(&mut q, es, -b * &sigma, a * &sigma);
                }
                p = q;
            }
        }
        // i^(2p): 1, i, -1, -i.
        let quarter = (u.mode.pi * Small::from_integer(2))
            .to_integer()
            .rem_euclid(4);
        for (e, (a, b)) in p {
            let (re, im) = match quarter {
                0 => (a, b),
                1 => (-b, a),
                2 => (-a, -b),
                _ => (b, -a),
            };
            let c = if u.mode.sin { im } else { re };
            if !c.is_zero() {
                let v = poly.entry(e).or_insert_with(Rat::zero);
                *v += c;
            }
        }
    }
    poly.retain(|_, c| !c.is_zero());
    if poly.is_empty() {
        return None;
    }
    let pairs: Vec<(usize, usize)> = (0..reading.units.len())
        .map(|i| (2 * i, 2 * i + 1))
        .collect();
    let mut readings = vec![poly.clone()];
    for sin_reduced in [true, false] {
        let r = reduce(&poly, &pairs, sin_reduced)?;
        if !readings.contains(&r) {
            readings.push(r);
        }
    }
    let mut out = Vec::new();
    for r in readings {
        out.extend(expanded_expr(&r, &vars));
        if let Some(e) = factored_expr(&r, &vars) {
            out.push(e);
        }
    }
    Some(out)
}

/// The polynomial with `s^2 = 1 - c^2` (or `c^2 = 1 - s^2`) applied for every pair of
/// variables `(c, s)` until each term has the reduced one at most to the first power.
fn reduce(
    p: &BTreeMap<Vec<u32>, Rat>,
    pairs: &[(usize, usize)],
    sin_reduced: bool,
) -> Option<BTreeMap<Vec<u32>, Rat>> {
    let mut out: BTreeMap<Vec<u32>, Rat> = BTreeMap::new();
    for (e, c) in p {
        let mut parts: Vec<(Vec<u32>, Rat)> = vec![(e.clone(), c.clone())];
        for &(ci, si) in pairs {
            let (r, o) = if sin_reduced { (si, ci) } else { (ci, si) };
            let k = e[r] / 2;
            if k == 0 {
                continue;
            }
            // (1 - o^2)^k.
            let mut next = Vec::new();
            for (pe, pc) in &parts {
                let mut binom = BigInt::one();
                for j in 0..=k {
                    let mut ne = pe.clone();
                    ne[r] = e[r] % 2;
                    ne[o] += 2 * j;
                    let sign = if j % 2 == 0 { 1 } else { -1 };
                    next.push((ne, pc * Rat::from_integer(&binom * BigInt::from(sign))));
                    binom = binom * BigInt::from(k - j) / BigInt::from(j + 1);
                }
            }
            parts = next;
        }
        charge(parts.len() as u64).ok()?;
        for (pe, pc) in parts {
            *out.entry(pe).or_insert_with(Rat::zero) += pc;
        }
    }
    out.retain(|_, c| !c.is_zero());
    Some(out)
}

/// The polynomial over Z times `1/den`.
fn integral(p: &BTreeMap<Vec<u32>, Rat>, n: usize) -> (MPoly, BigInt) {
    let den = p.values().fold(BigInt::one(), |acc, q| acc.lcm(q.denom()));
    let terms: BTreeMap<Vec<u32>, BigInt> = p
        .iter()
        .map(|(e, q)| (e.clone(), (q * Rat::from_integer(den.clone())).to_integer()))
        .collect();
    (MPoly { n, terms }, den)
}

/// The reading itself, expanded: `l1^2 - l2^2 cos(b)^2`.
fn expanded_expr(p: &BTreeMap<Vec<u32>, Rat>, vars: &[Var]) -> Option<Expr> {
    let (g, den) = integral(p, vars.len());
    let c = g.terms.values().fold(BigInt::zero(), |acc, c| acc.gcd(c));
    let g = MPoly {
        n: g.n,
        terms: g.terms.iter().map(|(e, x)| (e.clone(), x / &c)).collect(),
    };
    let (negated, e) = poly_expr(&g, vars)?;
    let k = Rat::new(if negated { -c } else { c }, den);
    Some(mul(num(k), e))
}

/// Whether `p` has no factorization into two non-constant factors, by a test that costs one
/// pass over its terms (the PUMA 560's `d4 c23 - a2 s2 - a3 s23`, which the factorization
/// would only confirm). When every term holds exactly one monomial symbol, to the first
/// power, and there are two or more such symbols, `p = sum_j x_j T_j` is of degree 1 in them:
/// of two factors, one is free of them and divides every coefficient `T_j`. That factor is a
/// constant when some `T_j` is a single term that is a constant, or a single variable `v`
/// (irreducible) that some term of another `T_k` lacks (so `v` does not divide `T_k`).
fn plainly_irreducible(p: &BTreeMap<Vec<u32>, Rat>, vars: &[Var]) -> bool {
    let is_sym: Vec<bool> = vars.iter().map(|v| matches!(v, Var::Sym(_))).collect();
    // Per monomial symbol, the exponent vectors of its coefficient's terms.
    let mut groups: BTreeMap<usize, Vec<&Vec<u32>>> = BTreeMap::new();
    for e in p.keys() {
        let mut which = None;
        for (i, &x) in e.iter().enumerate() {
            if is_sym[i] && x > 0 {
                if x > 1 || which.is_some() {
                    return false;
                }
                which = Some(i);
            }
        }
        let Some(i) = which else {
            return false;
        };
        groups.entry(i).or_default().push(e);
    }
    if groups.len() < 2 {
        return false;
    }
    groups.iter().any(|(i, g)| {
        let [e] = g[..] else {
            return false;
        };
        let mut trig = e.iter().enumerate().filter(|&(k, &x)| !is_sym[k] && x > 0);
        match (trig.next(), trig.next()) {
            (None, _) => true,
            (Some((v, 1)), None) => groups
                .iter()
                .any(|(j, h)| j != i && h.iter().any(|f| f[v] == 0)),
            _ => false,
        }
    })
}

/// The factored polynomial as an expression, when it has at least two factors; two factors
/// whose product has a cheaper closed form of its own are shown as that
/// (`(cos(2a) - cos(2b)) (1 + cos(c))` for `2 (cos a - cos b) (cos a + cos b) (1 + cos c)`).
fn factored_expr(p: &BTreeMap<Vec<u32>, Rat>, vars: &[Var]) -> Option<Expr> {
    if plainly_irreducible(p, vars) {
        return None;
    }
    let (poly, den) = integral(p, vars.len());
    let f = factor(&poly)?;
    let count: u32 = f.factors.iter().map(|(_, m)| m).sum();
    if count < 2 {
        return None;
    }
    let mut k = Rat::new(f.content, den);
    // A negative number in front is absorbed by a factor of odd multiplicity with as many
    // negative terms as positive ones (`-(c - 1)` read `1 - c`).
    let balanced =
        |g: &MPoly| 2 * g.terms.values().filter(|c| c.is_negative()).count() == g.terms.len();
    let mut absorb = k
        .is_negative()
        .then(|| {
            f.factors
                .iter()
                .position(|(g, m)| m % 2 == 1 && balanced(g))
        })
        .flatten();
    let mut parts: Vec<Expr> = Vec::new();
    for (i, (g, m)) in f.factors.iter().enumerate() {
        let flip = absorb == Some(i);
        if flip {
            absorb = None;
            k = -k;
        }
        let (negated, e) = factor_expr(&if flip { g.neg() } else { g.clone() }, vars)?;
        if negated && m % 2 == 1 {
            k = -k;
        }
        parts.push(if *m == 1 {
            e
        } else {
            Expr::Pow(Box::new(e), *m)
        });
    }
    // Symbols first, then cosines and sines by angle, then sums.
    fn rank(e: &Expr) -> (u8, Option<&super::expr::Angle>) {
        match e {
            Expr::Sym(_) => (0, None),
            Expr::Trig { angle, .. } => (1, Some(angle)),
            Expr::Pow(b, _) => (rank(b).0, rank(b).1),
            _ => (2, None),
        }
    }
    parts.sort_by(|a, b| rank(a).cmp(&rank(b)));
    while parts.len() >= 3 {
        let mut best: Option<(usize, usize, Expr)> = None;
        for i in 0..parts.len() {
            for j in i + 1..parts.len() {
                let pair = mul(num(k.clone()), mul(parts[i].clone(), parts[j].clone()));
                let Some(c) = nested(&pair.to_scalar()) else {
                    continue;
                };
                let bar = best.as_ref().map_or(&pair, |(_, _, b)| b);
                if shorter(&c, &pair) && (best.is_none() || shorter(&c, bar)) {
                    best = Some((i, j, c));
                }
            }
        }
        let Some((i, j, c)) = best else { break };
        parts.remove(j);
        parts[i] = c;
        k = Rat::one();
    }
    let mut e = num(k);
    for part in parts {
        e = mul(e, part);
    }
    Some(e)
}

/// One factor as an expression, and whether it is shown negated (as `-g`, its sign then
/// moved into the number in front): as its polynomial, with no more negative terms than
/// positive ones, or as its closed form when that is cheaper.
fn factor_expr(g: &MPoly, vars: &[Var]) -> Option<(bool, Expr)> {
    let (negated, poly) = poly_expr(g, vars)?;
    if g.terms.len() < 2 {
        return Some((negated, poly));
    }
    // Its own closed form (of the factor shown), when cheaper: `cos(x + y)` for
    // `c_x c_y - s_x s_y`.
    let closed = nested(&poly.to_scalar());
    match closed {
        Some(c) if shorter(&c, &poly) => Some((negated, c)),
        _ => Some((negated, poly)),
    }
}

/// A polynomial as its sum of monomials, with no more negative terms than positive ones, and
/// whether it was negated for that.
fn poly_expr(g: &MPoly, vars: &[Var]) -> Option<(bool, Expr)> {
    let negative = g.terms.values().filter(|c| c.is_negative()).count();
    let negated = 2 * negative > g.terms.len();
    // Leading monomials first among equals (reverse order of the keys).
    let mut mons: Vec<(Vec<u32>, BigInt)> = g
        .terms
        .iter()
        .rev()
        .map(|(e, c)| (e.clone(), if negated { -c } else { c.clone() }))
        .collect();
    // Higher degree first; positive terms first among equals.
    mons.sort_by_key(|(e, c)| (std::cmp::Reverse(e.iter().sum::<u32>()), c.is_negative()));
    let mut sum: Vec<Expr> = Vec::new();
    for (e, c) in &mons {
        let mut m = num(Rat::from_integer(c.abs()));
        // Symbols first, then cosines and sines: `l2 cos(b)`.
        let order = (0..e.len())
            .filter(|&i| matches!(vars[i], Var::Sym(_)))
            .chain((0..e.len()).filter(|&i| !matches!(vars[i], Var::Sym(_))));
        for i in order {
            let x = e[i];
            if x == 0 {
                continue;
            }
            let a = match &vars[i] {
                Var::Cos(g) => trig(false, g.clone(), Small::zero()),
                Var::Sin(g) => trig(true, g.clone(), Small::zero()),
                Var::Sym(s) => Expr::Sym(s.clone()),
            };
            m = mul(m, if x == 1 { a } else { Expr::Pow(Box::new(a), x) });
        }
        sum.push(if c.is_negative() { neg(m) } else { m });
    }
    let poly = if sum.len() == 1 {
        sum.pop()?
    } else {
        // Positive terms first.
        sum.sort_by_key(|e| matches!(e, Expr::Neg(_)));
        Expr::Add(sum)
    };
    Some((negated, poly))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(terms: &[(&[u32], i64)]) -> BTreeMap<Vec<u32>, Rat> {
        terms
            .iter()
            .map(|(e, c)| (e.to_vec(), Rat::from_integer(BigInt::from(*c))))
            .collect()
    }

    /// The test that skips the factorization agrees with it: `d4 (c2 c3 - s2 s3) - a2 s2 -
    /// a3 (s2 c3 + c2 s3)` (the PUMA 560's T[2][3]) is skipped and has no two factors; `a2 s c
    /// plus a3 s` (every coefficient divisible by `s`) and `a2 (c - 1) plus a3 (c - 1)` are
    /// not skipped and factor.
    #[test]
    fn plainly_irreducible_only_where_nothing_factors() {
        let trig = |n: &str| Var::Cos(vec![(Sym::new(n), Small::one())]);
        let sin = |n: &str| Var::Sin(vec![(Sym::new(n), Small::one())]);
        let sym = |n: &str| Var::Sym(Sym::new(n));
        // c2 s2 c3 s3 d4 a2 a3
        let vars = [
            trig("t2"),
            sin("t2"),
            trig("t3"),
            sin("t3"),
            sym("a2"),
            sym("a3"),
            sym("d4"),
        ];
        let puma = poly(&[
            (&[1, 0, 1, 0, 0, 0, 1], 1),
            (&[0, 1, 0, 1, 0, 0, 1], -1),
            (&[0, 1, 0, 0, 1, 0, 0], -1),
            (&[0, 1, 1, 0, 0, 1, 0], -1),
            (&[1, 0, 0, 1, 0, 1, 0], -1),
        ]);
        assert!(plainly_irreducible(&puma, &vars));
        let (p, _) = integral(&puma, vars.len());
        assert!(factor(&p).is_none_or(|f| f.factors.iter().map(|(_, m)| m).sum::<u32>() < 2));
        // l1 = a2, l2 = a3: a2 s2 c2 + a3 s2.
        let common = poly(&[(&[1, 1, 0, 0, 1, 0, 0], 1), (&[0, 1, 0, 0, 0, 1, 0], 1)]);
        assert!(!plainly_irreducible(&common, &vars));
        assert!(factored_expr(&common, &vars).is_some());
        let shared = poly(&[
            (&[1, 0, 0, 0, 1, 0, 0], 1),
            (&[0, 0, 0, 0, 1, 0, 0], -1),
            (&[1, 0, 0, 0, 0, 1, 0], 1),
            (&[0, 0, 0, 0, 0, 1, 0], -1),
        ]);
        assert!(!plainly_irreducible(&shared, &vars));
        assert!(factored_expr(&shared, &vars).is_some());
    }
}
