//! Entries that are turns of each other: `x = c f(y)`, where `f` adds a multiple of pi to one
//! symbol (`q1 -> q1 + pi`) and `c` is a rational. A robot whose first joint turns about the
//! base's z axis has such pairs in its pose: the dual quaternion is `r(q1) R` with `r(q1) =
//! cos(q1/2) + k sin(q1/2)`, and `r(q1 + pi) = r(q1) k`, so its `z` component is `-f(w)`, `y`
//! is `f(x)` (and the dual part alike), and the matrix `Rz(q1) M` has its second row `-f` of
//! its first with `q1 -> q1 + pi/2`. The closed form of `x` is then `c` times the form of
//! `y` with each call turned (`cos(q1/2 + pi/2) = -sin(q1/2)`: [`turned`]), found without a
//! search of its own, and checked against `x` like every closed form.
//!
//! What is exact and what is not: the pairs are found exactly (the turned scalar made term by
//! term, [`turned_scalar`], compared up to a rational factor by [`ProportionalKey`]), and
//! every turned form is checked against its entry (exactly in debug builds, numerically first
//! in release builds). The form is the turn of the other's, not necessarily the one a search
//! of `x` would give: the search's costs see signs and its ties the order of the atoms, which
//! a turn changes (see `app/fk.rs` for what that changes in the reports).

use super::expr::{quarter_turned, Expr};
use super::rename::SignedRenaming;
use crate::scalar::{trig_placeholder_name, FxHasher, ProportionalKey, Small, Sym, Term, Trig, Q};
use crate::Scalar;
use num_traits::CheckedMul;
use std::collections::HashMap;
use std::hash::BuildHasherDefault;

/// One turn: a symbol and the multiple of pi added to it.
pub(crate) type Turn = (Sym, Small);

/// An entry found to be a turn of an earlier one: `entries[to] = factor * turns[turn]
/// (entries[from])`.
#[derive(Clone, Debug)]
pub(crate) struct Turned {
    /// The entry it is a turn of (earlier in the list; itself a turn of another or not).
    pub(crate) from: usize,
    /// The turn, as given.
    pub(crate) turn: Turn,
    /// The rational factor.
    pub(crate) factor: Q,
}

/// For each of `entries`, the earlier entry it is a turn of (by one of `turns`, up to a
/// rational factor), if any. Each entry `a` is turned by each of `turns` in order while a
/// later entry not yet taken could be its turn ([`turn_invariant`]: the same number of terms
/// and the same frequency vectors and monomials), and the turn is looked up among the
/// entries: a multiple of a later one not yet taken makes that one a turn of `a` (`a` may
/// itself be a turn of an earlier one: its form is found first). Only entries of at least
/// `min_terms` terms are looked at (a small entry's search costs about what its turn does).
pub(crate) fn turned_entries(
    entries: &[&Scalar],
    turns: &[Turn],
    min_terms: usize,
) -> Vec<Option<Turned>> {
    turned_entries_with(
        entries,
        turns,
        min_terms,
        &turned_scalar,
        &Invariants::Same(&turn_invariant),
    )
}

/// [`turned_entries`] of polynomials in cosine and sine placeholders
/// ([`Scalar::to_cos_sin_polynomial`]: a recurrence's matrix), by quarter turns of the angles of
/// `turns` ([`quarter_turned_placeholders`]; other turns are not tried). Each turn has its own
/// invariant (its angle's two placeholders counted as one), so an entry is turned only where
/// a later one may be its turn in that angle (the symbolic 6R: 6 polynomials turned for its
/// 6 pairs, where one invariant for all the turns had 9 turned).
pub(crate) fn turned_placeholder_entries(
    entries: &[&Scalar],
    turns: &[Turn],
    min_terms: usize,
) -> Vec<Option<Turned>> {
    let quarter = |x: &Scalar, (s, t): &Turn| {
        (*t == Small::new(1, 2))
            .then(|| quarter_turned_placeholders(x, s))
            .flatten()
    };
    let syms: Vec<[Sym; 2]> = turns.iter().map(|(s, _)| placeholders(s)).collect();
    let invariants = |x: &Scalar| syms.iter().map(|p| placeholder_invariant(x, p)).collect();
    turned_entries_with(
        entries,
        turns,
        min_terms,
        &quarter,
        &Invariants::PerTurn(&invariants),
    )
}

/// What the turns keep of an entry: one hash for every turn, or one for each (in the order
/// of the turns).
enum Invariants<'a> {
    Same(&'a dyn Fn(&Scalar) -> Option<u64>),
    PerTurn(&'a dyn Fn(&Scalar) -> Vec<Option<u64>>),
}

/// [`turned_entries`] with the turn of a scalar `turned` and what the turns keep.
fn turned_entries_with(
    entries: &[&Scalar],
    turns: &[Turn],
    min_terms: usize,
    turned: &dyn Fn(&Scalar, &Turn) -> Option<Scalar>,
    invariant: &Invariants,
) -> Vec<Option<Turned>> {
    let mut out: Vec<Option<Turned>> = vec![None; entries.len()];
    if turns.is_empty() {
        return out;
    }
    // By entry, by turn.
    let invariant: Vec<Vec<Option<u64>>> = entries
        .iter()
        .map(|x| {
            if x.len() < min_terms {
                return vec![None; turns.len()];
            }
            match invariant {
                Invariants::PerTurn(f) => f(x),
                Invariants::Same(f) => vec![f(x); turns.len()],
            }
        })
        .collect();
    let mut index: HashMap<ProportionalKey, usize, BuildHasherDefault<FxHasher>> =
        HashMap::with_capacity_and_hasher(entries.len(), Default::default());
    for (k, x) in entries.iter().enumerate() {
        if invariant[k].iter().any(Option::is_some) {
            index.entry(ProportionalKey(x)).or_insert(k);
        }
    }
    for (a, x) in entries.iter().enumerate() {
        for (t, turn) in turns.iter().enumerate() {
            let Some(inv) = invariant[a][t] else {
                continue;
            };
            let open =
                (a + 1..entries.len()).any(|b| out[b].is_none() && invariant[b][t] == Some(inv));
            if !open {
                continue;
            }
            let Some(y) = turned(x, turn) else {
                continue;
            };
            let key = ProportionalKey(&y);
            let Some((found, &b)) = index.get_key_value(&key) else {
                continue;
            };
            if b <= a || out[b].is_some() {
                continue;
            }
            // `entries[b] = c y`.
            let Some(c) = found.factor_over(&key) else {
                continue;
            };
            out[b] = Some(Turned {
                from: a,
                turn: turn.clone(),
                factor: c,
            });
        }
    }
    out
}

/// A phase `d` (a multiple of pi) in quarter turns modulo 4, when it is a multiple of 1/2.
pub(crate) fn quarters(d: Small) -> Option<i64> {
    let q = d.checked_mul(&Small::from_integer(2))?;
    q.is_integer().then(|| q.numer().rem_euclid(4))
}

/// The term `t` with its angle turned by `q` quarter turns (`trig(a + q pi/2)`, written as
/// [`quarter_turned`] writes it: `cos` into `-sin` for one, the term negated for two): the
/// same angle and offset, its cosine and sine swapped for odd `q`, its sign turned.
pub(crate) fn quarter_turned_term(t: &Term, q: i64) -> Term {
    let f = if t.mode.sin { Trig::Sin } else { Trig::Cos };
    let (g, neg) = quarter_turned(f, q);
    let mut moved = t.clone();
    moved.mode.sin = g.is_sin();
    if neg {
        moved.coef = -moved.coef;
    }
    moved
}

/// `x` with `turn` applied, term by term, when the turn moves every term it moves by
/// quarter turns: `c cos(a + p pi)` with the symbol's coefficient `k` in `a` is `c cos(a + p
/// pi + k t pi)`, and for `k t` a multiple of 1/2 that is `+-c cos` or `+-c sin` of the same
/// angle and offset ([`quarter_turned`]). Each term so is an identity, so the sum is the
/// turned value whether or not its terms are canonical; [`turned_entries`] compares it with
/// canonical entries term by term, so a form that is not canonical only misses a pair. The
/// scalar shift of every angle ([`Scalar::shift_angles`]) writes the same value canonically
/// but rewrites every group with an offset (`cos(q2 + 5*pi/9)`), ten times the work on the
/// Jaco-style arm's entries. `None` when a turn is not by quarter turns, or the symbol is in
/// a monomial (then it is no angle).
pub(crate) fn turned_scalar(x: &Scalar, turn: &Turn) -> Option<Scalar> {
    let (sym, t) = turn;
    let terms = x.terms().ok()?;
    let mut out = Vec::with_capacity(terms.len());
    for term in terms {
        if term.mono.iter().any(|(s, _)| s == sym) {
            return None;
        }
        let Some(k) = term
            .mode
            .freq
            .iter()
            .find(|(s, _)| s == sym)
            .map(|(_, k)| *k)
        else {
            out.push(term.clone());
            continue;
        };
        out.push(quarter_turned_term(term, quarters(k.checked_mul(t)?)?));
    }
    Some(Scalar::from_terms_settled(out))
}

/// The placeholders of `cos(x)` and `sin(x)` ([`crate::scalar::trig_placeholder`]).
fn placeholders(x: &Sym) -> [Sym; 2] {
    [Trig::Cos, Trig::Sin].map(|f| Sym::new(&trig_placeholder_name(x.name(), f)))
}

/// The quarter turn of the angle `x` on its placeholders, as a signed renaming: `cos(x)`
/// becomes `-sin(x)` and `sin(x)` becomes `cos(x)`.
fn quarter_renaming(x: &Sym) -> SignedRenaming {
    let [c, s] = placeholders(x);
    SignedRenaming::new(vec![(c.clone(), s.clone(), true), (s, c, false)])
        .expect("two placeholders swapped are a permutation")
}

/// A polynomial in cosine and sine placeholders turned by a quarter turn of the angle `x`
/// ([`quarter_renaming`]): each term's exponents of the two are swapped and its sign turned
/// when the cosine's is odd. `None` when a term has a trigonometric mode (no polynomial) or
/// `x`'s angle appears in one.
pub(crate) fn quarter_turned_placeholders(p: &Scalar, x: &Sym) -> Option<Scalar> {
    let terms = p.terms().ok()?;
    if terms
        .iter()
        .any(|t| !t.mode.is_unit() || t.mono.iter().any(|(y, _)| y == x))
    {
        return None;
    }
    quarter_renaming(x).scalar(p)
}

/// A closed form in placeholders ([`Expr::with_placeholders_as_trig`] not applied yet) turned
/// as [`quarter_turned_placeholders`] turns its value: the renaming's form with the signs of
/// products tidied and their symbols sorted, the sums and negations as the form wrote them
/// ([`SignedRenaming::form_as_turned`]), in one walk that leaves the subtrees without the two
/// placeholders as they are (the fully symbolic 6R's matrix entries are deep products).
pub(crate) fn quarter_turned_placeholder_form(e: Expr, x: &Sym) -> Option<Expr> {
    quarter_renaming(x).form_as_turned(e)
}

/// A product whose factors were renamed or turned: the sign of each factor (a negation, or a
/// sum whose terms are all negative) taken out ([`flip_sign`]), its symbols sorted
/// ([`sort_leaves`]), the sign placed as [`signed`] places it.
pub(super) fn signed_product(mut v: Vec<Expr>) -> Expr {
    let mut neg = false;
    for f in &mut v {
        *f = flip_sign(&mut neg, std::mem::replace(f, Expr::zero()));
    }
    sort_leaves(&mut v);
    signed(neg, Expr::Mul(v))
}

/// `t^n` for a base renamed or turned: its sign taken out, kept for an odd `n`.
pub(super) fn signed_power(t: Expr, n: u32) -> Expr {
    let mut neg = false;
    let base = flip_sign(&mut neg, t);
    signed(neg && n % 2 == 1, Expr::Pow(Box::new(base), n))
}

/// The terms of a sum of monomials (each a product of symbols, their powers and a number,
/// negated or not) sorted as a search writes them, by their monomials (the symbols by name,
/// then the exponents); a sum with another term keeps its order.
pub(super) fn sort_monomial_terms(v: &mut [Expr]) {
    fn leaves<'a>(e: &'a Expr, out: &mut Vec<(&'a Sym, u32)>) -> bool {
        match e {
            Expr::Sym(s) => {
                out.push((s, 1));
                true
            }
            Expr::Pow(b, n) => match &**b {
                Expr::Sym(s) => {
                    out.push((s, *n));
                    true
                }
                _ => false,
            },
            Expr::Num(_) => true,
            Expr::Neg(x) => leaves(x, out),
            Expr::Mul(f) => f.iter().all(|x| leaves(x, out)),
            _ => false,
        }
    }
    let mut keys: Vec<Vec<(&Sym, u32)>> = Vec::with_capacity(v.len());
    for t in v.iter() {
        let mut k = Vec::new();
        if !leaves(t, &mut k) {
            return;
        }
        k.sort();
        keys.push(k);
    }
    let mut order: Vec<usize> = (0..v.len()).collect();
    order.sort_by(|&a, &b| keys[a].cmp(&keys[b]));
    if order.iter().enumerate().all(|(i, &k)| i == k) {
        return;
    }
    let mut taken: Vec<Option<Expr>> = v
        .iter_mut()
        .map(|t| Some(std::mem::replace(t, Expr::zero())))
        .collect();
    for (slot, k) in v.iter_mut().zip(order) {
        *slot = taken[k].take().expect("each term is placed once");
    }
}

/// The symbols of a product (a symbol or its power, signed or not) sorted by name in the
/// places they hold among its other factors, as the search orders them (`c1 c2`, where a
/// turned `s1 c2` would print `c2 c1`).
fn sort_leaves(v: &mut [Expr]) {
    fn leaf(e: &Expr) -> Option<&Sym> {
        match e {
            Expr::Sym(s) => Some(s),
            Expr::Pow(x, _) | Expr::Neg(x) => leaf(x),
            _ => None,
        }
    }
    let mut last: Option<&Sym> = None;
    let mut sorted = true;
    for l in v.iter().filter_map(leaf) {
        sorted &= last.is_none_or(|p| p <= l);
        last = Some(l);
    }
    if sorted {
        return;
    }
    let places: Vec<usize> = (0..v.len()).filter(|&i| leaf(&v[i]).is_some()).collect();
    let mut leaves: Vec<Expr> = places.iter().map(|&i| v[i].clone()).collect();
    leaves.sort_by(|a, b| leaf(a).cmp(&leaf(b)));
    for (i, e) in places.into_iter().zip(leaves) {
        v[i] = e;
    }
}

/// A hash of what a quarter turn of the angle whose placeholders are `syms` keeps in a
/// polynomial: its number of terms and the multiset of its monomials with the two
/// placeholders counted as one; `None` when neither placeholder appears (the turn leaves it
/// as it is).
fn placeholder_invariant(x: &Scalar, syms: &[Sym; 2]) -> Option<u64> {
    use std::hash::{Hash, Hasher};
    let terms = x.terms().ok()?;
    let mut sum = terms.len() as u64;
    let mut seen = false;
    for t in terms {
        let mut h = FxHasher::default();
        let mut degree = 0u32;
        for (y, e) in t.mono.iter() {
            if syms.contains(y) {
                degree += e;
            } else {
                h.write_usize(y.addr());
                e.hash(&mut h);
            }
        }
        seen |= degree > 0;
        degree.hash(&mut h);
        sum = sum.wrapping_add(h.finish());
    }
    seen.then_some(sum)
}

/// A hash of what every turn of `x` keeps: its number of terms and the multiset of its
/// terms' frequency vectors and monomials (a turn changes a term's cosine into a sine and
/// its coefficient, not its angle's symbols or its monomial); `None` for an error value.
/// A group whose canonical terms carry an offset may change its number of terms when
/// turned: such a pair is only missed (searched as before).
fn turn_invariant(x: &Scalar) -> Option<u64> {
    use std::hash::{Hash, Hasher};
    let terms = x.terms().ok()?;
    let mut sum = terms.len() as u64;
    for t in terms {
        let mut h = FxHasher::default();
        for (s, k) in t.mode.freq.iter() {
            h.write_usize(s.addr());
            k.hash(&mut h);
        }
        t.mono.hash(&mut h);
        sum = sum.wrapping_add(h.finish());
    }
    Some(sum)
}

/// `e` with `turn` applied to its symbol: each call `f(a)` whose angle holds the symbol with
/// coefficient `k` is `f(a + k t pi)`, written as `g(a)` with a sign ([`quarter_turned`]);
/// `None` when some `k t` is not a multiple of 1/2 (a call that does not turn into another) or
/// the symbol appears outside an angle.
pub(crate) fn turned(e: Expr, turn: &Turn) -> Option<Expr> {
    let (sym, t) = turn;
    if reads_outside_angles(&e, sym) {
        return None;
    }
    let mut whole = true;
    let out = e.map_trig_signed(&mut |f, angle| {
        let k = angle
            .terms
            .iter()
            .find(|(s, _)| s == sym)
            .map(|(_, k)| *k)?;
        let Some(q) = k.checked_mul(t).and_then(quarters) else {
            whole = false;
            return None;
        };
        if q == 0 {
            return None;
        }
        let (g, neg) = quarter_turned(f, q);
        Some((g, angle.clone(), neg))
    });
    whole.then_some(tidy_signs(out))
}

/// A factor of a product with its sign taken out into `neg`: a negation's, or that of a sum
/// whose terms are all negative (its terms turned).
fn flip_sign(neg: &mut bool, e: Expr) -> Expr {
    match e {
        Expr::Neg(x) => {
            *neg = !*neg;
            *x
        }
        Expr::Add(v) if !v.is_empty() && v.iter().all(|t| matches!(t, Expr::Neg(_))) => {
            *neg = !*neg;
            Expr::Add(
                v.into_iter()
                    .map(|t| match t {
                        Expr::Neg(x) => *x,
                        t => t,
                    })
                    .collect(),
            )
        }
        e => e,
    }
}

/// `e`, negated when `neg`: a product's sign placed where it prints shortest
/// (`super::expr::minus`: into one of its sums when that is shorter, `-s1 (-c2 + s3)` as `s1
/// (c2 - s3)`), another's in front.
pub(super) fn signed(neg: bool, e: Expr) -> Expr {
    match (neg, e) {
        (false, e) => e,
        (true, e @ Expr::Mul(_)) => super::expr::minus(e),
        (true, e) => Expr::Neg(Box::new(e)),
    }
}

/// `e` with the sign of each sum inside a product whose terms are all negative taken out of it
/// and out of the product (`s23 (-c4 s6 - s4 c6)` is `-s23 (c4 s6 + s4 c6)`): as long, one
/// minus sign, where a turn left one on every term ([`Expr::map_trig_signed`] keeps the signs
/// on the terms of sums). The value is unchanged.
fn tidy_signs(e: Expr) -> Expr {
    match e {
        Expr::Add(v) => Expr::Add(v.into_iter().map(tidy_signs).collect()),
        Expr::Mul(v) => {
            let mut neg = false;
            let parts = v
                .into_iter()
                .map(|f| flip_sign(&mut neg, tidy_signs(f)))
                .collect();
            signed(neg, Expr::Mul(parts))
        }
        Expr::Neg(x) => match tidy_signs(*x) {
            Expr::Neg(y) => *y,
            y => Expr::Neg(Box::new(y)),
        },
        Expr::Pow(x, n) => {
            let mut neg = false;
            let base = flip_sign(&mut neg, tidy_signs(*x));
            signed(neg && n % 2 == 1, Expr::Pow(Box::new(base), n))
        }
        e => e,
    }
}

/// `e` with the sign of each negated product placed again as [`signed`] places a product's
/// (`-cos(u) (-a + d)` is `cos(u) (a - d)`), and a sum that begins with a negative term begun
/// with its first positive one (`-a s + d c` is `d c - a s`): a turn leaves the negations of
/// the form it turned where they were. The value is unchanged.
pub(crate) fn signs_placed(e: Expr) -> Expr {
    match e {
        Expr::Add(v) => {
            let mut v: Vec<Expr> = v.into_iter().map(signs_placed).collect();
            let negative = |t: &Expr| matches!(t, Expr::Neg(_));
            if v.first().is_some_and(negative) {
                if let Some(j) = v.iter().position(|t| !negative(t)) {
                    let t = v.remove(j);
                    v.insert(0, t);
                }
            }
            Expr::Add(v)
        }
        Expr::Mul(v) => Expr::Mul(v.into_iter().map(signs_placed).collect()),
        Expr::Pow(x, n) => Expr::Pow(Box::new(signs_placed(*x)), n),
        Expr::Neg(x) => match signs_placed(*x) {
            m @ Expr::Mul(_) => signed(true, m),
            y => Expr::Neg(Box::new(y)),
        },
        e => e,
    }
}

/// Whether `sym` appears in `e` other than in an angle (a monomial's symbol).
fn reads_outside_angles(e: &Expr, sym: &Sym) -> bool {
    match e {
        Expr::Sym(s) => s == sym,
        Expr::Add(v) | Expr::Mul(v) => v.iter().any(|x| reads_outside_angles(x, sym)),
        Expr::Neg(x) | Expr::Pow(x, _) => reads_outside_angles(x, sym),
        Expr::Num(_) | Expr::Sqrt(_) | Expr::Trig { .. } => false,
    }
}

/// The closed form of `x`, an entry that is `t.factor` times `t.turn` of an entry whose
/// closed form is `from`: `from` turned and scaled; `None` when it cannot be turned or its
/// check fails. Checked exactly against `x` in debug builds (so in every test); in release
/// builds numerically against `from` at a turned point ([`agrees_turned`]): `x` is that
/// multiple of the turned entry exactly ([`turned_entries`]) and `from` was checked against
/// that entry, so only the turn itself is left to check, without evaluating `x`.
pub(crate) fn turned_form(from: &Expr, t: &Turned, x: &Scalar) -> Option<Expr> {
    let e = turned(from.clone(), &t.turn)?.scaled(&t.factor.to_big());
    let good = if cfg!(debug_assertions) {
        e.to_scalar() == *x
    } else {
        agrees_turned(&e, from, t)
    };
    #[cfg(test)]
    counts::count(good);
    good.then_some(e)
}

/// Whether `e` and `t.factor` times `from` with `t.turn`'s symbol turned agree at a fixed
/// pseudo-random point, to a relative 1e-9 of the magnitudes involved (as
/// `agrees_numerically` compares a form with its scalar).
fn agrees_turned(e: &Expr, from: &Expr, t: &Turned) -> bool {
    let seed = 0x9e37_79b9_7f4a_7c15u64;
    let (sym, turn) = &t.turn;
    let shift = *turn.numer() as f64 / *turn.denom() as f64 * std::f64::consts::PI;
    let (a, scale_a) = e.eval_f64(&|s| super::point_value(s, seed));
    let (b, scale_b) = from.eval_f64(&|s| {
        let v = super::point_value(s, seed);
        if s == sym {
            v + shift
        } else {
            v
        }
    });
    let c = t.factor.to_f64().unwrap_or(f64::NAN);
    let scale = scale_a.max(scale_b * c.abs()).max(1.0);
    a.is_finite() && b.is_finite() && (a - c * b).abs() <= 1e-9 * scale
}

/// The closed form of `x`, a polynomial in placeholders that is `t.factor` times the quarter
/// turn of `t.turn`'s angle of one whose closed form (in placeholders) is `from`: `from`
/// turned ([`quarter_turned_placeholder_form`]) and scaled, checked exactly against `x` in
/// debug builds (so in every test); in release builds numerically against `from` with the
/// two placeholders' values turned (the quarter turn is the signed renaming `cos -> -sin`,
/// `sin -> cos`: [`SignedRenaming::agrees_times`]), as [`turned_form`] checks a turned form
/// without evaluating `x` (whose numeric check was 1.5 M instructions of the symbolic 6R's
/// six turned entries). `None` when the check fails.
pub(crate) fn turned_placeholder_form(from: &Expr, t: &Turned, x: &Scalar) -> Option<Expr> {
    let e = quarter_turned_placeholder_form(from.clone(), &t.turn.0)?.scaled(&t.factor.to_big());
    let good = if cfg!(debug_assertions) {
        e.to_scalar() == *x
    } else {
        let factor = t.factor.to_f64().unwrap_or(f64::NAN);
        quarter_renaming(&t.turn.0).agrees_times(&e, from, factor)
    };
    #[cfg(test)]
    counts::count(good);
    good.then_some(e)
}

/// The turned forms made and those whose check failed, on this thread (for tests).
#[cfg(test)]
pub(crate) mod counts {
    thread_local! {
        pub(crate) static COUNTS: std::cell::Cell<(u64, u64)> =
            const { std::cell::Cell::new((0, 0)) };
    }

    /// One turned form counted, made (`good`) or failed.
    pub(crate) fn count(good: bool) {
        COUNTS.with(|c| {
            let (made, failed) = c.get();
            c.set(if good {
                (made + 1, failed)
            } else {
                (made, failed + 1)
            });
        });
    }
}
