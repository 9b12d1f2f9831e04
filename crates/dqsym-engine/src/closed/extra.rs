//! The candidates added for issue 33's held-out corpus, made in one place for
//! `alt::best_alternative`: squares of sums (`square.rs`); a sum split into the parts whose
//! angles have one set of symbols, each part's closed form found alone (`2 sin(u1/2)
//! sin(u1 - u2) - cos(p) cos(u1) sin(w)`, whose parts share `u1`, which `trigfac.rs` keeps
//! together); and any candidate that is a sum of
//! products sharing a factor with that factor taken out (`k2 cos(w/2 - pi/3) sin(w) -
//! k2 sin(p/2 + u2) cos(r)` is `k2 (cos(w/2 - pi/3) sin(w) - sin(p/2 + u2) cos(r))`: the parts
//! of `trigfac.rs`'s split sums and the constant products of `cprod.rs` are found apart and
//! joined by an addition, never factored); pairs of summands joined (sum to product, `1 -
//! cos(2 w)` as a square, a cosine and a sine of one angle as one sinusoid), also in the sums
//! inside the products of the form shown (`joined_form`), where a sinusoid's square root may
//! merge with the product's (`sqrt(2) k (cos(a) - sin(a))` is `2 k cos(a + pi/4)`); sums among
//! a summand's factors that differ only in sign are made equal first (`x (a - b) + y (b - a)`
//! shares `a - b`).

use super::alt::{choice_key, full_cost, mul, neg, num};
use super::expr::{Angle, Expr};
use crate::scalar::atoms::{freq_combine, Small};
use crate::scalar::{charge, Sym, Term, Trig};
use crate::Scalar;
use num_integer::Integer;
use num_rational::BigRational as Rat;
use num_traits::One;

/// The candidates of the files listed above for the canonical terms `t`, not yet checked
/// against them; `than` is the form found before, `bound` its cost (`alt::full_cost`; any
/// value for a sum without a trigonometric term, which `candidates_up_to` never reads) and
/// `others` the other candidates (only shorter ones can be taken).
pub(super) fn candidates(t: &[Term], than: &Expr, others: &[Expr], bound: usize) -> Vec<Expr> {
    let mut out = candidates_up_to(t, bound, others);
    if !out.is_empty() || super::trigfac::may_nest() {
        out.extend(common_factor(than));
        for e in pairs_joined(than, false) {
            out.extend(common_factor(&e));
            out.push(e);
        }
    }
    out
}

/// The candidates of [`candidates`] made without a form found before, for costs below
/// `bound`: what a search capped at `bound` (`floor.rs`) must count as possible winners.
pub(super) fn candidates_up_to(t: &[Term], bound: usize, others: &[Expr]) -> Vec<Expr> {
    // Each candidate costs an exact check; made under the nesting bound of `trigfac.rs`'s
    // (`may_nest`), their nested searches each on a share of the budget left.
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
    // `x (a - b) + y (b - a)` read as `x (a - b) - y (a - b)`, so that `a - b` is shared.
    let unified = same_signed_sums(sum);
    let sum = unified.as_deref().unwrap_or(sum);
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

/// Whether the sums `f` and `g` are negations of each other, term by term in any order
/// (`a - 2 b` and `-a + 2 b`), read without copying either.
fn negated_sums(f: &[Expr], g: &[Expr]) -> bool {
    // `x` is `-y`: one of them is the other's negation.
    let opposite = |x: &Expr, y: &Expr| match (x, y) {
        (Expr::Neg(a), b) | (b, Expr::Neg(a)) => **a == *b,
        _ => false,
    };
    if f.len() != g.len() {
        return false;
    }
    let mut used = vec![false; g.len()];
    f.iter().all(|x| {
        (0..g.len())
            .find(|&j| !used[j] && opposite(x, &g[j]))
            .map(|j| used[j] = true)
            .is_some()
    })
}

/// The summands with every sum among a summand's factors that is the negation of a sum met
/// before (in that summand or an earlier one) written as that sum, the summand's sign changed
/// once for each: `sin(A) (a - 2 b) + sin(B) (-a + 2 b)` is `sin(A) (a - 2 b) - sin(B) (a - 2
/// b)`, whose summands share a factor and can join; `None` (nothing copied) when no factor
/// changes. Sums in powers are left (an even power hides the sign).
fn same_signed_sums(sum: &[Expr]) -> Option<Vec<Expr>> {
    let is_sum = |f: &Expr| matches!(f, Expr::Add(_));
    // Most sums have no two summands with a sum among their factors.
    if sum
        .iter()
        .filter(|e| summand_factors(e).iter().any(is_sum))
        .count()
        < 2
    {
        return None;
    }
    let mut seen: Vec<&Expr> = Vec::new();
    let mut out: Option<Vec<Expr>> = None;
    for (i, e) in sum.iter().enumerate() {
        let fs = summand_factors(e);
        let mut swaps: Vec<(usize, &Expr)> = Vec::new();
        for (k, f) in fs.iter().enumerate() {
            let Expr::Add(terms) = f else {
                continue;
            };
            if seen.contains(&f) {
                continue;
            }
            match seen
                .iter()
                .find(|g| matches!(g, Expr::Add(v) if negated_sums(terms, v)))
            {
                Some(g) => swaps.push((k, *g)),
                None => seen.push(f),
            }
        }
        if swaps.is_empty() {
            continue;
        }
        let mut new: Vec<Expr> = fs.to_vec();
        for (k, g) in &swaps {
            new[*k] = (*g).clone();
        }
        let body = match new.len() {
            1 => new.pop().expect("one factor"),
            _ => Expr::Mul(new),
        };
        let negated = matches!(e, Expr::Neg(_)) ^ (swaps.len() % 2 == 1);
        out.get_or_insert_with(|| sum.to_vec())[i] = if negated { neg(body) } else { body };
    }
    out
}

/// The most summands [`pairs_joined`] looks at (its pairs are quadratic in them).
const MAX_PAIR_SUMMANDS: usize = 16;

/// A call among a summand's factors: the other factors, the function and its angle.
type Call = (Vec<Expr>, Trig, Angle);

/// A summand read for [`pairs_joined`]: its sign, its number (positive), its other factors,
/// and the position among them of the call it is written in (a call outside a power).
#[derive(Clone)]
struct Summand {
    negated: bool,
    q: Rat,
    factors: Vec<Expr>,
}

impl Summand {
    fn of(e: &Expr) -> Summand {
        let (negated, e) = match e {
            Expr::Neg(x) => (true, &**x),
            e => (false, e),
        };
        let mut q = Rat::one();
        let mut factors = Vec::new();
        let fs: Vec<&Expr> = match e {
            Expr::Mul(v) => v.iter().collect(),
            e => vec![e],
        };
        for f in fs {
            match f {
                Expr::Num(n) => q *= n,
                f => factors.push(f.clone()),
            }
        }
        Summand {
            negated,
            q,
            factors,
        }
    }

    /// The summand as an expression: the number first, equal factors as one power.
    fn expr(&self) -> Expr {
        let mut fs: Vec<Expr> = Vec::new();
        for f in &self.factors {
            match f {
                Expr::Pow(x, n) => fs.extend(std::iter::repeat_n((**x).clone(), *n as usize)),
                f => fs.push(f.clone()),
            }
        }
        let mut v: Vec<Expr> = Vec::new();
        if !self.q.is_one() {
            v.push(Expr::Num(self.q.clone()));
        }
        let mut used = vec![false; fs.len()];
        for i in 0..fs.len() {
            if used[i] {
                continue;
            }
            let mut n = 0u32;
            for j in i..fs.len() {
                if !used[j] && fs[j] == fs[i] {
                    used[j] = true;
                    n += 1;
                }
            }
            v.push(if n == 1 {
                fs[i].clone()
            } else {
                Expr::Pow(Box::new(fs[i].clone()), n)
            });
        }
        let e = match v.len() {
            0 => num(Rat::one()),
            1 => v.pop().expect("one factor"),
            _ => Expr::Mul(v),
        };
        if self.negated {
            neg(e)
        } else {
            e
        }
    }

    /// The other factors and the call, for each call among the factors.
    fn calls(&self) -> Vec<Call> {
        let mut out = Vec::new();
        for (i, f) in self.factors.iter().enumerate() {
            if let Expr::Trig { f, angle } = f {
                let mut rest = self.factors.clone();
                rest.remove(i);
                out.push((rest, *f, angle.clone()));
            }
        }
        out
    }
}

/// The sinusoid `f(angle)` with the angle's leading coefficient made positive, an offset that
/// is a multiple of `pi/2` taken into the call (`cos(x/2 + pi/2)` is `-sin(x/2)`) and the
/// offset reduced: `(negated, call)`.
fn sinusoid(mut f: Trig, mut angle: Angle) -> (bool, Expr) {
    let mut negated = false;
    if angle.leading().is_some_and(|k| k < Small::from_integer(0)) {
        angle.negate();
        negated = f.is_sin();
    }
    let quarters = angle.pi * Small::from_integer(2);
    if quarters.is_integer() {
        // cos(y + pi/2) = -sin(y), sin(y + pi/2) = cos(y), once per quarter turn.
        for _ in 0..quarters.numer().rem_euclid(4) {
            negated ^= !f.is_sin();
            f = Trig::of(!f.is_sin());
        }
        angle.pi = Small::from_integer(0);
    }
    angle.reduce_offset();
    (negated, Expr::Trig { f, angle })
}

/// `(a + sign b) / 2` of two angles.
fn half_sum(a: &Angle, b: &Angle, sign: i64) -> Angle {
    let two = Small::from_integer(2);
    let f: Vec<(Sym, Small)> = freq_combine(&a.freq(), &b.freq(), sign)
        .into_iter()
        .map(|(s, k)| (s, k / two))
        .collect();
    let pi = (a.pi + b.pi * Small::from_integer(sign)) / two;
    Angle::from_freq(&f, pi)
}

/// Two summands joined into one, when they have the same factors but one call and numbers
/// of equal size: sum to product (`cos A + cos B = 2 cos((A + B)/2) cos((A - B)/2)`, and the
/// three others), and a number beside the cosine or sine of one angle as a square
/// (`1 - cos(2 w) = 2 sin(w)^2`, `k + k cos(x) = 2 k cos(x/2)^2`). Not checked.
fn joined(a: &Summand, ca: &[Call], b: &Summand, cb: &[Call]) -> Vec<Summand> {
    if a.q != b.q {
        return Vec::new();
    }
    let mut out = Vec::new();
    let same_sign = a.negated == b.negated;
    // A call beside a summand without it: `s (1 + sign f(phi))`, `f(phi)` as a cosine.
    // The calls are read in place and copied only where the rests match: most pairs of a long
    // sum match nowhere (copying every call first cost the Jaco-style arm ~0.9 M instructions).
    for (x, y) in [(a, cb), (b, ca)] {
        for (rest, f, angle) in y {
            if *rest != x.factors {
                continue;
            }
            let angle = if f.is_sin() {
                Angle::new(
                    angle.terms.clone(),
                    angle.constant,
                    angle.pi - Small::new(1, 2),
                )
            } else {
                angle.clone()
            };
            if angle.is_pi_multiple() {
                continue;
            }
            // 1 + cos(phi) = 2 cos(phi/2)^2, 1 - cos(phi) = 2 sin(phi/2)^2.
            let (_, e) = sinusoid(Trig::of(!same_sign), angle.scaled(Small::new(1, 2)));
            let mut factors = rest.clone();
            factors.push(e.clone());
            factors.push(e);
            out.push(Summand {
                negated: x.negated,
                q: &x.q * Rat::from_integer(2.into()),
                factors,
            });
        }
    }
    for (ra, fa, aa) in ca {
        for (rb, fb, ab) in cb {
            if ra != rb {
                continue;
            }
            // `b`'s call as the kind of `a`'s: cos B = sin(B + pi/2), sin B = cos(B - pi/2).
            let ab = match (fa.is_sin(), fb.is_sin()) {
                (true, false) => {
                    Angle::new(ab.terms.clone(), ab.constant, ab.pi + Small::new(1, 2))
                }
                (false, true) => {
                    Angle::new(ab.terms.clone(), ab.constant, ab.pi - Small::new(1, 2))
                }
                _ => ab.clone(),
            };
            let (s, d) = (half_sum(aa, &ab, 1), half_sum(aa, &ab, -1));
            if s.is_pi_multiple() || d.is_pi_multiple() {
                continue;
            }
            // cos A + cos B = 2 cos S cos D, cos A - cos B = -2 sin S sin D,
            // sin A + sin B = 2 sin S cos D, sin A - sin B = 2 cos S sin D.
            let (k1, k2, negate) = match (fa.is_sin(), same_sign) {
                (false, true) => (false, false, false),
                (false, false) => (true, true, true),
                (true, true) => (true, false, false),
                (true, false) => (false, true, false),
            };
            let (n1, e1) = sinusoid(Trig::of(k1), s);
            let (n2, e2) = sinusoid(Trig::of(k2), d);
            let mut factors = ra.clone();
            factors.push(e1);
            factors.push(e2);
            out.push(Summand {
                negated: a.negated ^ negate ^ n1 ^ n2,
                q: &a.q * Rat::from_integer(2.into()),
                factors,
            });
        }
    }
    out
}

/// The factors of a summand, its sign aside: `-2 cos(a) b` is `[2, cos(a), b]`, a summand
/// that is no product is its own one factor.
fn summand_factors(e: &Expr) -> &[Expr] {
    let e = match e {
        Expr::Neg(x) => &**x,
        e => e,
    };
    match e {
        Expr::Mul(v) => v.as_slice(),
        e => std::slice::from_ref(e),
    }
}

/// Whether two of the summands have the same numbers and the same factors but a call in one
/// or each (what [`joined`] needs), read without copying them: most sums have no such pair.
fn any_pair_may_join(sum: &[Expr]) -> bool {
    fn read(e: &Expr) -> (Rat, Vec<&Expr>) {
        let fs = summand_factors(e);
        let mut q = Rat::one();
        let mut rest = Vec::with_capacity(fs.len());
        for f in fs {
            match f {
                Expr::Num(n) => q *= n,
                f => rest.push(f),
            }
        }
        (q, rest)
    }
    let read: Vec<(Rat, Vec<&Expr>)> = sum.iter().map(read).collect();
    // The factors of `a` missing from `b` (with multiplicity), when at most one.
    let missing = |a: &[&Expr], b: &[&Expr]| -> Option<Option<usize>> {
        let mut used = vec![false; b.len()];
        let mut miss = None;
        for (i, f) in a.iter().enumerate() {
            match (0..b.len()).find(|&j| !used[j] && b[j] == *f) {
                Some(j) => used[j] = true,
                None if miss.is_none() => miss = Some(i),
                None => return None,
            }
        }
        Some(miss)
    };
    let call = |f: &Expr| matches!(f, Expr::Trig { .. });
    for i in 0..read.len() {
        for j in 0..read.len() {
            let ((qa, a), (qb, b)) = (&read[i], &read[j]);
            if i == j || qa != qb {
                continue;
            }
            let ok = if a.len() == b.len() {
                // Sum to product: one call of each differs (or none: equal summands).
                i < j && missing(a, b).is_some_and(|m| m.is_none_or(|k| call(a[k])))
            } else if a.len() == b.len() + 1 {
                // A call beside the summand without it.
                missing(a, b).is_some_and(|m| m.is_some_and(|k| call(a[k])))
            } else {
                false
            };
            if ok {
                return true;
            }
        }
    }
    false
}

/// Whether two of the summands have the same factors but a cosine in one and a sine of the
/// same angle in the other, numbers and square roots aside (what [`harmonic_joined`] needs).
fn any_harmonic_pair(sum: &[Expr]) -> bool {
    fn read(e: &Expr) -> Vec<&Expr> {
        summand_factors(e)
            .iter()
            .filter(|f| !matches!(f, Expr::Num(_) | Expr::Sqrt(_)))
            .collect()
    }
    // First only the calls: most sums have no cosine and sine of one angle in two summands.
    let mut calls: Vec<(usize, &Trig, &Angle)> = Vec::new();
    for (i, e) in sum.iter().enumerate() {
        for f in summand_factors(e) {
            if let Expr::Trig { f, angle } = f {
                calls.push((i, f, angle));
            }
        }
    }
    let paired = calls.iter().enumerate().any(|(k, (i, f, a))| {
        calls[k + 1..]
            .iter()
            .any(|(j, g, b)| i != j && f != g && a == b)
    });
    if !paired {
        return false;
    }
    let read: Vec<Vec<&Expr>> = sum.iter().map(read).collect();
    for i in 0..read.len() {
        for j in i + 1..read.len() {
            let (a, b) = (&read[i], &read[j]);
            if a.len() != b.len() {
                continue;
            }
            for (k, f) in a.iter().enumerate() {
                let Expr::Trig { f: fa, angle: aa } = f else {
                    continue;
                };
                for (l, g) in b.iter().enumerate() {
                    let Expr::Trig { f: fb, angle: ab } = g else {
                        continue;
                    };
                    if fa == fb || aa != ab {
                        continue;
                    }
                    let (mut ra, mut rb) = (a.clone(), b.clone());
                    ra.remove(k);
                    rb.remove(l);
                    if ra == rb {
                        return true;
                    }
                }
            }
        }
    }
    false
}

/// `sqrt(r)` as `g sqrt(m)`, `g` rational and `m` square-free; `None` when `r` is negative,
/// zero or too large to factor by trial division.
fn sqrt_parts(r: &Rat) -> Option<(Rat, u64)> {
    use num_traits::ToPrimitive;
    let (n, d) = (r.numer().to_u64()?, r.denom().to_u64()?);
    let mut x = n.checked_mul(d)?;
    if x == 0 || x > 1 << 40 {
        return None;
    }
    let (mut g, mut m, mut p) = (1u64, 1u64, 2u64);
    while p * p <= x {
        let mut e = 0;
        while x.is_multiple_of(p) {
            x /= p;
            e += 1;
        }
        g *= p.pow(e / 2);
        if e % 2 == 1 {
            m *= p;
        }
        p += 1;
    }
    Some((Rat::new(g.into(), d.into()), m * x))
}

/// Two summands with the same factors, numbers and square roots aside, but `cos A` in one and
/// `sin A` in the other joined as one sinusoid (the harmonic form, `c cos A + s sin A =
/// R cos(A - phi)`), when `phi` is a multiple of pi/12 (found in floats; the result is
/// checked exactly by the caller): `cos(u1) + sqrt(3) sin(u1) = 2 cos(u1 - pi/3)`. Each of
/// the four ways to write the sinusoid (`cos`, `sin`, either negated) is offered.
fn harmonic_joined(a: &Summand, ca: &[Call], b: &Summand, cb: &[Call]) -> Vec<Summand> {
    use num_traits::ToPrimitive;
    let split = |rest: &[Expr]| -> Option<(Vec<Expr>, u64)> {
        let mut m = 1u64;
        let mut v = Vec::with_capacity(rest.len());
        for f in rest {
            match f {
                Expr::Sqrt(n) => m = m.checked_mul(*n)?,
                f => v.push(f.clone()),
            }
        }
        Some((v, m))
    };
    let value = |s: &Summand, m: u64| {
        let v = s.q.to_f64().unwrap_or(f64::NAN) * (m as f64).sqrt();
        if s.negated {
            -v
        } else {
            v
        }
    };
    let square = |s: &Summand, m: u64| &s.q * &s.q * Rat::from_integer(m.into());
    let mut out = Vec::new();
    for (ra, fa, aa) in ca {
        for (rb, fb, ab) in cb {
            if fa == fb || aa != ab || aa.is_pi_multiple() {
                continue;
            }
            let (Some((ra, ma)), Some((rb, mb))) = (split(ra), split(rb)) else {
                continue;
            };
            if ra != rb {
                continue;
            }
            let (va, vb) = (value(a, ma), value(b, mb));
            let (c, s) = if fa.is_sin() { (vb, va) } else { (va, vb) };
            // c cos A + s sin A = R cos(A - phi), phi = atan2(s, c).
            let k = s.atan2(c) * 12.0 / std::f64::consts::PI;
            let kr = k.round();
            if (k - kr).abs() >= 1e-9 {
                continue;
            }
            let Some((g, m)) = sqrt_parts(&(square(a, ma) + square(b, mb))) else {
                continue;
            };
            let o = aa.pi - Small::new(kr as i64, 12);
            // cos y = sin(y + pi/2) = -cos(y + pi) = -sin(y + 3 pi/2).
            for (sin, quarters, negated) in [
                (false, 0, false),
                (true, 1, false),
                (false, 2, true),
                (true, 3, true),
            ] {
                let angle = Angle::new(aa.terms.clone(), aa.constant, o + Small::new(quarters, 2));
                let (n, e) = sinusoid(Trig::of(sin), angle);
                let mut factors = ra.clone();
                if m > 1 {
                    factors.push(Expr::Sqrt(m));
                }
                factors.push(e);
                out.push(Summand {
                    negated: negated ^ n,
                    q: g.clone(),
                    factors,
                });
            }
        }
    }
    out
}

/// A product's factors flattened: products in it spread, signs taken out, numbers multiplied
/// into one number first, square roots into one.
fn tidy_product(kids: Vec<Expr>) -> Expr {
    fn push(e: Expr, q: &mut Rat, negated: &mut bool, fs: &mut Vec<Expr>) {
        match e {
            Expr::Neg(x) => {
                *negated ^= true;
                push(*x, q, negated, fs);
            }
            Expr::Mul(v) => v.into_iter().for_each(|f| push(f, q, negated, fs)),
            Expr::Num(n) => *q *= n,
            f => fs.push(f),
        }
    }
    let (mut q, mut negated, mut fs) = (Rat::one(), false, Vec::new());
    kids.into_iter()
        .for_each(|f| push(f, &mut q, &mut negated, &mut fs));
    // Square roots multiplied into one (`sqrt(2) sqrt(2)` is 2), first among the factors.
    if fs.iter().filter(|f| matches!(f, Expr::Sqrt(_))).count() >= 2 {
        let mut n = 1u64;
        let mut overflow = false;
        for f in &fs {
            if let Expr::Sqrt(m) = f {
                n = n.checked_mul(*m).unwrap_or_else(|| {
                    overflow = true;
                    1
                });
            }
        }
        if let Some((g, m)) = (!overflow)
            .then(|| sqrt_parts(&Rat::from_integer(n.into())))
            .flatten()
        {
            fs.retain(|f| !matches!(f, Expr::Sqrt(_)));
            q *= g;
            if m > 1 {
                fs.insert(0, Expr::Sqrt(m));
            }
        }
    }
    let mut v = Vec::with_capacity(fs.len() + 1);
    if !q.is_one() {
        v.push(Expr::Num(q));
    }
    v.extend(fs);
    let e = match v.len() {
        0 => Expr::Num(Rat::one()),
        1 => v.pop().expect("one factor"),
        _ => Expr::Mul(v),
    };
    if negated {
        neg(e)
    } else {
        e
    }
}

/// The numbers' common factor of a sum's summands taken out (`2 a + 4 b` is `2 (a + 2 b)`).
fn gcd_out(v: Vec<Expr>) -> Expr {
    let parts: Vec<Summand> = v.iter().map(Summand::of).collect();
    let (n, d) = parts.iter().fold(
        (parts[0].q.numer().clone(), parts[0].q.denom().clone()),
        |(n, d), s| (n.gcd(s.q.numer()), d.lcm(s.q.denom())),
    );
    let g = Rat::new(n, d);
    if g.is_one() {
        return Expr::Add(v);
    }
    let terms: Vec<Expr> = parts
        .into_iter()
        .map(|mut s| {
            s.q = &s.q / &g;
            s.expr()
        })
        .collect();
    Expr::Mul(vec![Expr::Num(g), Expr::Add(terms)])
}

/// The most summands a sum inside a product may have to be joined by [`nested_joined`]: the
/// pairs of a short factor such as `sin(2 r + w) + sin(w)`; an fk entry's long sums inside
/// products (whose pairs rarely join) are left as they are.
const MAX_NESTED_SUMMANDS: usize = 4;

/// `e` with the sums inside it (below the top: factors of products) joined as
/// [`pairs_joined`] joins a sum (also a cosine and a sine of one angle as one sinusoid), the
/// products holding them flattened and the numbers' common factor of a sum taken out
/// (`sin(p) (sin(2 r + w) + sin(w))` is `2 sin(p) sin(r + w) cos(r)`); `None` when nothing
/// changes. Not checked.
fn nested_joined(e: &Expr) -> Option<Expr> {
    /// The terms or factors `v` with those that change replaced; `None` (and nothing copied)
    /// when none does.
    fn kids(v: &[Expr]) -> Option<Vec<Expr>> {
        let (i, y) = v
            .iter()
            .enumerate()
            .find_map(|(i, x)| go(x, false).map(|y| (i, y)))?;
        let mut out = Vec::with_capacity(v.len());
        out.extend_from_slice(&v[..i]);
        out.push(y);
        out.extend(
            v[i + 1..]
                .iter()
                .map(|x| go(x, false).unwrap_or_else(|| x.clone())),
        );
        Some(out)
    }
    /// Whether a summand has a call among its factors (what every join needs).
    fn has_call(v: &[Expr]) -> bool {
        let call = |f: &Expr| matches!(f, Expr::Trig { .. });
        v.iter().any(|t| {
            let t = match t {
                Expr::Neg(x) => &**x,
                t => t,
            };
            match t {
                Expr::Mul(fs) => fs.iter().any(call),
                t => call(t),
            }
        })
    }
    fn go(e: &Expr, top: bool) -> Option<Expr> {
        match e {
            Expr::Add(v) => {
                let kids = kids(v);
                if top || v.len() < 2 {
                    return kids.map(Expr::Add);
                }
                match kids {
                    None if v.len() > MAX_NESTED_SUMMANDS || !has_call(v) => None,
                    None => pairs_joined(e, true).pop(),
                    Some(k) => {
                        let sum = gcd_out(k);
                        if v.len() > MAX_NESTED_SUMMANDS {
                            return Some(sum);
                        }
                        pairs_joined(&sum, true).pop().or(Some(sum))
                    }
                }
            }
            Expr::Mul(v) => {
                let k = kids(v);
                let fs = k.as_deref().unwrap_or(v);
                match sinusoid_in_product(fs) {
                    Some(e) => Some(e),
                    None => k.map(tidy_product),
                }
            }
            Expr::Neg(x) => go(x, top).map(neg),
            Expr::Pow(x, n) => go(x, false).map(|y| match y {
                Expr::Neg(y) if (*n).is_multiple_of(2) => Expr::Pow(y, *n),
                Expr::Neg(y) => neg(Expr::Pow(y, *n)),
                y => Expr::Pow(Box::new(y), *n),
            }),
            _ => None,
        }
    }
    /// Whether a call's angle has a symbol (the constant products of `cprod.rs` are found as
    /// products already, and are left alone).
    fn symbolic_call(e: &Expr) -> bool {
        match e {
            Expr::Trig { angle, .. } => !angle.terms.is_empty(),
            Expr::Add(v) | Expr::Mul(v) => v.iter().any(symbolic_call),
            Expr::Neg(x) | Expr::Pow(x, _) => symbolic_call(x),
            _ => false,
        }
    }
    if !symbolic_call(e) {
        return None;
    }
    go(e, true)
}

/// The product `fs` with a two-summand sum among its factors that is a cosine and a sine of
/// one angle written as one sinusoid ([`harmonic_joined`]) and the product tidied, when that
/// is shorter than the product tidied as it is: the sinusoid's number or square root then
/// merges with the product's (`sqrt(2) k (cos(a) - sin(a))` is `2 k cos(a + pi/4)`, though
/// `sqrt(2) cos(a + pi/4)` alone is no shorter than `cos(a) - sin(a)`, so [`pairs_joined`]
/// leaves the sum). Only for products with a number or a square root to merge with.
fn sinusoid_in_product(fs: &[Expr]) -> Option<Expr> {
    if !fs.iter().any(|f| matches!(f, Expr::Num(_) | Expr::Sqrt(_))) {
        return None;
    }
    let mut best: Option<(usize, usize, Expr)> = None;
    for (k, f) in fs.iter().enumerate() {
        let Expr::Add(sum) = f else {
            continue;
        };
        if sum.len() != 2 || !any_harmonic_pair(sum) {
            continue;
        }
        let (a, b) = (Summand::of(&sum[0]), Summand::of(&sum[1]));
        for s in harmonic_joined(&a, &a.calls(), &b, &b.calls()) {
            let mut v = fs.to_vec();
            v[k] = s.expr();
            let e = tidy_product(v);
            let key = choice_key(&e);
            if best
                .as_ref()
                .is_none_or(|(c, d, _)| (key.0, key.1) < (*c, *d))
            {
                best = Some((key.0, key.1, e));
            }
        }
    }
    let (c, d, e) = best?;
    let now = choice_key(&tidy_product(fs.to_vec()));
    ((c, d) < (now.0, now.1)).then_some(e)
}

/// The first of the sums of [`pairs_joined`] for `e` (each also with its common factors
/// taken out; for the `outermost` search also with a cosine and a sine of one angle joined
/// and the sums inside its products joined, [`nested_joined`]) shorter than `e` by
/// `alt::shorter` for which `equal` holds: for the final form of a scalar, whose angles at
/// multiples of pi/12 (`coefs::phase_angles`) the candidates never see (`cos(r - u2/2 + pi/3) + cos(r + 3*u2/2 + pi/3)` is `2 cos(r + u2/2 + pi/3)
/// cos(u2)`).
pub(super) fn joined_form(
    e: &Expr,
    outermost: bool,
    equal: impl Fn(&Expr) -> bool,
) -> Option<Expr> {
    let mut cands: Vec<Expr> = Vec::new();
    for j in pairs_joined(e, outermost) {
        cands.extend(common_factor(&j));
        cands.push(j);
    }
    // The sums inside products joined too, and cosines and sines of one angle (once, for the
    // form of the outermost search, whose tree holds every sum of the nested ones).
    if let Some(n) = outermost.then(|| nested_joined(e)).flatten() {
        for j in pairs_joined(&n, true) {
            cands.extend(common_factor(&j));
            cands.push(j);
        }
        cands.extend(common_factor(&n));
        cands.push(n);
    }
    cands.retain(|c| super::alt::shorter(c, e));
    cands.sort_by_cached_key(choice_key);
    cands.into_iter().find(|c| equal(c))
}

/// The items of `v` whose index `keep` keeps, in their order.
fn without<T>(v: Vec<T>, keep: impl Fn(&usize) -> bool) -> Vec<T> {
    v.into_iter()
        .enumerate()
        .filter(|(k, _)| keep(k))
        .map(|(_, x)| x)
        .collect()
}

/// A join of two summands for [`pairs_joined`]: what it saves, the summand it makes and its
/// cost in a sum.
type Join = (usize, Summand, usize);

/// The cost of a summand in a sum (its sign the sum's subtraction).
fn summand_cost(s: &Summand) -> usize {
    let mut s = s.clone();
    s.negated = false;
    full_cost(&s.expr()).0
}

/// The join of two summands (each with its calls and its cost in a sum) that saves the most
/// ([`joined`], and with `harmonic` [`harmonic_joined`]): what the two summands and the
/// addition between them cost, less the join's cost; the first of the greatest saving (which
/// may be nothing), none when every join costs more.
fn pair_join(
    (a, ca, ka): (&Summand, &[Call], usize),
    (b, cb, kb): (&Summand, &[Call], usize),
    harmonic: bool,
) -> Option<Join> {
    let mut joins = if a.q == b.q {
        joined(a, ca, b, cb)
    } else {
        Vec::new()
    };
    if harmonic {
        joins.extend(harmonic_joined(a, ca, b, cb));
    }
    let mut best: Option<Join> = None;
    for s in joins {
        let c = summand_cost(&s);
        let Some(d) = (ka + kb + 1).checked_sub(c) else {
            continue;
        };
        if best.as_ref().is_none_or(|(b, _, _)| d > *b) {
            best = Some((d, s, c));
        }
    }
    best
}

/// The sum `e` (or a number times it) with pairs of its summands joined ([`joined`]) while
/// that makes it no longer by [`choice_key`], the cheapest join first; each sum reached, not
/// yet checked (`alt::best_alternative` checks them exactly). Empty when no pair joins.
fn pairs_joined(e: &Expr, harmonic: bool) -> Vec<Expr> {
    let (front, sum) = match e {
        Expr::Add(v) => (None, v),
        Expr::Mul(v) if v.len() == 2 => match (&v[0], &v[1]) {
            (Expr::Num(q), Expr::Add(s)) => (Some(q.clone()), s),
            _ => return Vec::new(),
        },
        _ => return Vec::new(),
    };
    if sum.len() < 2 || sum.len() > MAX_PAIR_SUMMANDS {
        return Vec::new();
    }
    // Factors that differ only in sign made equal (`sin(A) (a - 2 b) + sin(B) (-a + 2 b)` as
    // `sin(A) (a - 2 b) - sin(B) (a - 2 b)`), so that the pair can join.
    let unified = same_signed_sums(sum);
    let sum = unified.as_deref().unwrap_or(sum);
    // Harmonic pairs looked for only when asked and the sum has one to begin with.
    let harmonic = harmonic && any_harmonic_pair(sum);
    if !(harmonic || any_pair_may_join(sum)) || charge((sum.len() * sum.len()) as u64).is_err() {
        return Vec::new();
    }
    let whole = |v: &[Summand]| -> Expr {
        // The numbers' common factor taken out (`2 (a b + c^2)`; `1/4 (2 a + 4 b)` is
        // `1/2 (a + 2 b)`): the gcd of the numerators over the lcm of the denominators.
        let mut front = front.clone();
        let mut v = v.to_vec();
        if v.len() >= 2 {
            let (n, d) = v.iter().fold(
                (v[0].q.numer().clone(), v[0].q.denom().clone()),
                |(n, d), s| (n.gcd(s.q.numer()), d.lcm(s.q.denom())),
            );
            let g = Rat::new(n, d);
            if !g.is_one() {
                v.iter_mut().for_each(|s| s.q = &s.q / &g);
                front = Some(front.map_or(g.clone(), |f| f * g));
            }
        }
        let mut terms: Vec<Expr> = v.iter().map(Summand::expr).collect();
        terms.sort_by_key(|e| matches!(e, Expr::Neg(_)));
        let (inner, q) = match (terms.len(), &front) {
            (1, Some(q)) => {
                let mut s = v[0].clone();
                s.q *= q;
                (s.expr(), None)
            }
            (1, None) => (terms.pop().expect("one"), None),
            _ => (Expr::Add(terms), front.clone()),
        };
        match q {
            Some(q) => mul(Expr::Num(q), inner),
            None => inner,
        }
    };
    join_rounds(
        sum.iter().map(Summand::of).collect(),
        choice_key(e),
        harmonic,
        whole,
    )
}

/// The rounds of [`pairs_joined`] on its summands `cur` (of a sum whose key is `key`), the sum
/// of summands made by `whole`: each round joins the pair that saves the most, while the
/// sum's key does not grow; the sum after each round.
fn join_rounds(
    mut cur: Vec<Summand>,
    mut key: (usize, usize, usize, usize),
    harmonic: bool,
    whole: impl Fn(&[Summand]) -> Expr,
) -> Vec<Expr> {
    let mut out = Vec::new();
    // Each summand's calls and cost, kept beside `cur`: a join replaces two summands by one,
    // whose calls and cost are the only new ones.
    let mut calls: Vec<Vec<Call>> = cur.iter().map(Summand::calls).collect();
    let mut costs: Vec<usize> = cur.iter().map(summand_cost).collect();
    // Each pair's best join, `pairs[i][j]` for `i < j`, kept beside `cur` likewise: a pair's
    // join depends on its two summands alone, so each pair is read once, and a round reads only
    // the pairs of the summand it made.
    let best_join = |cur: &[Summand], calls: &[Vec<Call>], costs: &[usize], i: usize, j: usize| {
        pair_join(
            (&cur[i], &calls[i][..], costs[i]),
            (&cur[j], &calls[j][..], costs[j]),
            harmonic,
        )
    };
    let mut pairs: Vec<Vec<Option<Join>>> = (0..cur.len())
        .map(|i| {
            (0..cur.len())
                .map(|j| {
                    (i < j)
                        .then(|| best_join(&cur, &calls, &costs, i, j))
                        .flatten()
                })
                .collect()
        })
        .collect();
    while cur.len() >= 2 {
        // The pair whose join saves the most locally (the addition between them included; the
        // first such pair, and within it the first such join), then the whole sum built once
        // and compared.
        let mut pick: Option<(usize, usize, &Join)> = None;
        for (i, row) in pairs.iter().enumerate() {
            for (j, join) in row.iter().enumerate().skip(i + 1) {
                if let Some(join) = join {
                    if pick.is_none_or(|(_, _, b)| join.0 > b.0) {
                        pick = Some((i, j, join));
                    }
                }
            }
        }
        let best = pick.and_then(|(i, j, (_, s, c))| {
            let mut v = without(cur.clone(), |k| *k != i && *k != j);
            let s_calls = s.calls();
            v.push(s.clone());
            let e = whole(&v);
            let k = choice_key(&e);
            ((k.0, k.1) <= (key.0, key.1)).then_some((k, v, e, (i, j, s_calls, *c)))
        });
        let Some((k, v, e, (i, j, s_calls, c))) = best else {
            break;
        };
        let kept = |k: &usize| *k != i && *k != j;
        calls = without(calls, kept);
        calls.push(s_calls);
        costs = without(costs, kept);
        costs.push(c);
        key = k;
        cur = v;
        pairs = without(pairs, kept)
            .into_iter()
            .map(|row| without(row, kept))
            .collect();
        let n = cur.len();
        for (k, row) in pairs.iter_mut().enumerate() {
            row.push(best_join(&cur, &calls, &costs, k, n - 1));
        }
        pairs.push(vec![None; n]);
        out.push(e);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Sym;

    /// [`join_rounds`] as it was before each pair's join was kept from round to round: every
    /// pair read again in every round (the old route).
    fn join_rounds_rescanned(
        mut cur: Vec<Summand>,
        mut key: (usize, usize, usize, usize),
        harmonic: bool,
        whole: impl Fn(&[Summand]) -> Expr,
    ) -> Vec<Expr> {
        let mut out = Vec::new();
        while cur.len() >= 2 {
            let calls: Vec<Vec<Call>> = cur.iter().map(Summand::calls).collect();
            let costs: Vec<usize> = cur.iter().map(summand_cost).collect();
            let mut pick: Option<(usize, usize, usize, Summand)> = None;
            for i in 0..cur.len() {
                for j in i + 1..cur.len() {
                    let mut joins = if cur[i].q == cur[j].q {
                        joined(&cur[i], &calls[i], &cur[j], &calls[j])
                    } else {
                        Vec::new()
                    };
                    if harmonic {
                        joins.extend(harmonic_joined(&cur[i], &calls[i], &cur[j], &calls[j]));
                    }
                    for s in joins {
                        let Some(d) = (costs[i] + costs[j] + 1).checked_sub(summand_cost(&s))
                        else {
                            continue;
                        };
                        if pick.as_ref().is_none_or(|(_, _, b, _)| d > *b) {
                            pick = Some((i, j, d, s));
                        }
                    }
                }
            }
            let Some((i, j, _, s)) = pick else {
                break;
            };
            let mut v = without(cur.clone(), |k| *k != i && *k != j);
            v.push(s);
            let e = whole(&v);
            let k = choice_key(&e);
            if (k.0, k.1) > (key.0, key.1) {
                break;
            }
            key = k;
            cur = v;
            out.push(e);
        }
        out
    }

    /// The rounds of [`join_rounds`], each pair's join kept from round to round, are the old
    /// route's, where every pair was read again each round, on random sums of products of
    /// cosines and sines (a few angles, so that pairs join, some several times over); every sum
    /// reached equals the sum it started from.
    #[test]
    fn kept_pair_joins_give_the_rounds_of_pairs_read_again() {
        use crate::scalar::atoms::Small;
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = |n: u64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed % n
        };
        let syms = [Sym::new("a"), Sym::new("b"), Sym::new("l")];
        let offsets = [(0, 1), (1, 3), (1, 6), (1, 4), (-1, 3), (1, 2)];
        let whole = |v: &[Summand]| match v {
            [s] => s.expr(),
            v => Expr::Add(v.iter().map(Summand::expr).collect()),
        };
        let (mut compared, mut several) = (0, 0);
        for case in 0..600 {
            let n = 2 + next(9) as usize;
            // Every other case plain sums of single calls, which join again and again.
            let plain = case % 2 == 0;
            let mut sum = Vec::with_capacity(n);
            for _ in 0..n {
                let mut fs: Vec<Expr> = Vec::new();
                match if plain { 3 } else { next(4) } {
                    0 => fs.push(Expr::Num(Rat::new(1.into(), 2.into()))),
                    1 => fs.push(Expr::Num(Rat::from_integer(2.into()))),
                    _ => {}
                }
                if !plain && next(3) == 0 {
                    fs.push(Expr::Sym(syms[2].clone()));
                }
                if !plain && next(6) == 0 {
                    fs.push(Expr::Sqrt(3));
                }
                for _ in 0..1 + usize::from(!plain) * next(2) as usize {
                    let mut freq = vec![(syms[next(2) as usize].clone(), Small::one())];
                    if next(3) == 0 {
                        let other = syms[1 - usize::from(freq[0].0 == syms[1])].clone();
                        freq.push((other, Small::new(1 + next(2) as i64, 1)));
                        freq.sort();
                    }
                    let (p, q) = offsets[next(offsets.len() as u64) as usize];
                    fs.push(super::super::alt::trig(
                        next(2) == 0,
                        freq,
                        Small::new(p, q),
                    ));
                }
                let e = if fs.len() == 1 {
                    fs.pop().expect("one factor")
                } else {
                    Expr::Mul(fs)
                };
                sum.push(if next(3) == 0 { neg(e) } else { e });
            }
            let input = Expr::Add(sum);
            let Expr::Add(terms) = &input else {
                unreachable!()
            };
            let cur: Vec<Summand> = terms.iter().map(Summand::of).collect();
            let value = input.to_scalar();
            for harmonic in [false, true] {
                let key = choice_key(&whole(&cur));
                let kept = join_rounds(cur.clone(), key, harmonic, whole);
                let again = join_rounds_rescanned(cur.clone(), key, harmonic, whole);
                assert_eq!(kept, again, "case {case}, harmonic {harmonic}");
                for e in &kept {
                    assert_eq!(e.to_scalar(), value, "case {case}: {e:?}");
                }
                compared += usize::from(!kept.is_empty());
                several += usize::from(kept.len() >= 2);
            }
        }
        assert!(
            compared >= 150,
            "{compared} sums joined ({several} more than once)"
        );
        assert!(several >= 80, "{several} sums joined more than once");
    }

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

    #[test]
    fn sums_that_differ_only_in_sign_are_made_equal_with_the_summand_negated() {
        let sym = |n: &str| Expr::Sym(Sym::new(n));
        let two_b = Expr::Mul(vec![num(Rat::from_integer(2.into())), sym("b")]);
        // a - 2 b and -2 b + a (another order): negations of -a + 2 b.
        let f = Expr::Add(vec![sym("a"), neg(two_b.clone())]);
        let g = Expr::Add(vec![neg(sym("a")), two_b.clone()]);
        let h = Expr::Add(vec![neg(two_b.clone()), sym("a")]);
        let terms = |e: &Expr| match e {
            Expr::Add(v) => v.clone(),
            _ => unreachable!(),
        };
        assert!(negated_sums(&terms(&f), &terms(&g)));
        assert!(negated_sums(&terms(&h), &terms(&g)));
        assert!(!negated_sums(&terms(&f), &terms(&h)));
        // x (a - 2 b) + y (-a + 2 b) is x (a - 2 b) - y (a - 2 b): equal value, one factor.
        let sum = vec![
            Expr::Mul(vec![sym("x"), f.clone()]),
            Expr::Mul(vec![sym("y"), g.clone()]),
        ];
        let same = same_signed_sums(&sum).expect("a factor changes");
        assert_eq!(same[1], neg(Expr::Mul(vec![sym("y"), f.clone()])));
        assert_eq!(
            Expr::Add(same).to_scalar(),
            Expr::Add(sum.clone()).to_scalar()
        );
        // Nothing to change: no copy.
        assert!(same_signed_sums(&sum[..1]).is_none());
        let c = common_factor(&Expr::Add(sum.clone())).expect("a shared sum");
        assert_eq!(c.to_scalar(), Expr::Add(sum).to_scalar());
    }

    #[test]
    fn a_square_root_of_a_rational_is_split_into_a_rational_and_a_square_free_root() {
        let r = |n: i64, d: i64| Rat::new(n.into(), d.into());
        // sqrt(8/3) = sqrt(24)/3 = 2 sqrt(6)/3; sqrt(4) = 2; sqrt(1/2) = sqrt(2)/2.
        assert_eq!(sqrt_parts(&r(8, 3)), Some((r(2, 3), 6)));
        assert_eq!(sqrt_parts(&r(4, 1)), Some((r(2, 1), 1)));
        assert_eq!(sqrt_parts(&r(1, 2)), Some((r(1, 2), 2)));
        assert_eq!(sqrt_parts(&r(0, 1)), None);
        assert_eq!(sqrt_parts(&r(-2, 1)), None);
    }
}
