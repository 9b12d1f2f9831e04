//! From monomials to a nested display expression: common factors (symbols, trigonometric
//! atoms, numeric content) are pulled out where that lowers the cost.
//!
//! The search works on [`E`], a display expression over the interned atoms and symbols of a
//! [`Ctx`]; only the chosen one becomes an [`Expr`].

use super::expr::{Cost, Expr};
use super::mon::{angle_of, content, div_q, is_sin, Atom, Ctx, FxMap, Mon};
use crate::scalar::{charge, FxHasher, Q};
use crate::ScalarError;
use num_traits::One;
use std::hash::{Hash, Hasher};
use std::rc::Rc;

/// A factor that can be pulled out of several monomials.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug)]
enum Factor {
    Atom(Atom),
    Sym(u32),
}

/// How many alternative factors are tried at each of the first levels.
const BRANCH: usize = 3;
/// How many levels branch; below them the most frequent factor is taken.
const BRANCH_DEPTH: usize = 3;

/// [`Expr`] over interned atoms and symbols.
#[derive(Clone, Debug)]
pub(crate) enum E {
    Num(Q),
    Sqrt(u64),
    Sym(u32),
    /// `sym^n`.
    Pow(u32, u32),
    Trig(Atom),
    /// Children are shared: the search copies and memoizes subtrees without copying them.
    /// The cost of the node is kept beside them (see [`E::sum`]).
    Add(Rc<[E]>, Cost),
    Mul(Rc<[E]>, Cost),
    Neg(Rc<E>),
}

impl E {
    fn zero() -> E {
        E::Num(Q::ZERO)
    }

    /// The sum of `v`, its cost computed once from the children's (each of which is kept
    /// in its node or is a leaf): the search compares the costs of many candidates whose
    /// subtrees it shares, and a walk of each candidate's whole tree was quadratic.
    fn sum(v: Vec<E>) -> E {
        let c = Self::node_cost(&v, true);
        E::Add(v.into(), c)
    }

    /// The product of `v`, its cost computed as [`E::sum`]'s.
    fn product(v: Vec<E>) -> E {
        let c = Self::node_cost(&v, false);
        E::Mul(v.into(), c)
    }

    fn node_cost(v: &[E], in_sum: bool) -> Cost {
        let mut c = Cost {
            ops: v.len().saturating_sub(1),
            calls: 0,
        };
        for e in v {
            e.add_cost(&mut c, in_sum);
        }
        c
    }

    /// The cost of the [`Expr`] this becomes (see [`Expr::cost`]).
    pub(crate) fn cost(&self) -> Cost {
        let mut c = Cost::default();
        self.add_cost(&mut c, false);
        c
    }

    fn add_cost(&self, c: &mut Cost, in_sum: bool) {
        match self {
            E::Num(q) => {
                let integer = match q {
                    Q::S(_, d) => *d == 1,
                    Q::B(b) => b.denom().is_one(),
                };
                if !integer {
                    c.ops += 1;
                }
            }
            E::Sqrt(_) | E::Trig(_) => {
                c.ops += 1;
                c.calls += 1;
            }
            E::Sym(_) => {}
            E::Add(_, k) | E::Mul(_, k) => {
                c.ops += k.ops;
                c.calls += k.calls;
            }
            E::Neg(e) => {
                if !in_sum {
                    c.ops += 1;
                }
                e.add_cost(c, false);
            }
            E::Pow(_, n) => {
                c.ops += (*n as usize).saturating_sub(1);
            }
        }
    }

    /// The display expression.
    pub(crate) fn to_expr(&self, ctx: &Ctx) -> Expr {
        match self {
            E::Num(q) => Expr::Num(q.to_big()),
            E::Sqrt(n) => Expr::Sqrt(*n),
            E::Sym(s) => Expr::Sym(ctx.syms[*s as usize].clone()),
            E::Pow(s, n) => Expr::Pow(Box::new(Expr::Sym(ctx.syms[*s as usize].clone())), *n),
            E::Trig(a) => Expr::Trig {
                f: crate::scalar::Trig::of(is_sin(*a)),
                angle: ctx.angles[angle_of(*a) as usize].clone(),
            },
            E::Add(v, _) => Expr::Add(v.iter().map(|e| e.to_expr(ctx)).collect()),
            E::Mul(v, _) => product_expr(v, ctx),
            E::Neg(e) => Expr::Neg(Box::new(e.to_expr(ctx))),
        }
    }
}

/// A product as a display expression, with equal symbols and equal atoms merged into one
/// power: a factor pulled out of a sum meets its own power inside it (`a2 (a2 x + ..)` where
/// the sum had one term, `a2 a2 x`), and `a2^2` is what a reader expects. The merged power
/// stands where the first of its factors stood; the cost is the same or lower (`cos(a)^2`
/// calls cos once).
fn product_expr(v: &[E], ctx: &Ctx) -> Expr {
    #[derive(PartialEq)]
    enum Key {
        Sym(u32),
        Atom(Atom),
    }
    let key = |e: &E| match e {
        E::Sym(s) => Some((Key::Sym(*s), 1)),
        E::Pow(s, n) => Some((Key::Sym(*s), *n)),
        E::Trig(a) => Some((Key::Atom(*a), 1)),
        _ => None,
    };
    // A first pass on 64-bit masks (every product is converted, so this stays cheap): only
    // when two factors share a bit are they compared.
    let (mut syms, mut atoms, mut clash) = (0u64, 0u64, false);
    for e in v {
        let (mask, bit) = match e {
            E::Sym(s) | E::Pow(s, _) => (&mut syms, 1u64 << (s % 64)),
            E::Trig(a) => (&mut atoms, 1u64 << (*a as u64 % 64)),
            _ => continue,
        };
        clash |= *mask & bit != 0;
        *mask |= bit;
    }
    let repeated = clash
        && v.iter().enumerate().any(|(i, e)| {
            key(e).is_some_and(|(k, _)| v[..i].iter().any(|f| key(f).is_some_and(|(j, _)| j == k)))
        });
    if !repeated {
        return Expr::Mul(v.iter().map(|e| e.to_expr(ctx)).collect());
    }
    let mut merged: Vec<(Option<Key>, u32, &E)> = Vec::with_capacity(v.len());
    for e in v {
        match key(e) {
            Some((k, n)) => match merged.iter_mut().find(|(m, _, _)| m.as_ref() == Some(&k)) {
                Some((_, m, _)) => *m += n,
                None => merged.push((Some(k), n, e)),
            },
            None => merged.push((None, 1, e)),
        }
    }
    let parts: Vec<Expr> = merged
        .into_iter()
        .map(|(k, n, e)| match (k, e) {
            (Some(Key::Sym(s)), _) => E::Pow(s, n).to_expr(ctx),
            (_, e) if n == 1 => e.to_expr(ctx),
            (_, e) => Expr::Pow(Box::new(e.to_expr(ctx)), n),
        })
        .map(|e| match e {
            Expr::Pow(b, 1) => *b,
            e => e,
        })
        .collect();
    match parts.len() {
        1 => parts.into_iter().next().unwrap_or_else(Expr::zero),
        _ => Expr::Mul(parts),
    }
}

/// The search state: results already found for a monomial list at a depth class, by hash, and
/// the budget error once the search has used up the work budget.
#[derive(Default)]
struct Search {
    memo: FxMap<u64, Vec<(usize, Vec<Mon>, E)>>,
    spent: Option<ScalarError>,
    counts: Counts,
}

/// The cheapest nested expression this search finds for the sum of `mons`, with its cost.
///
/// The search counts against the work budget like scalar arithmetic (one unit per monomial
/// and per factor of it looked at); when the budget runs out it stops with the budget error.
/// A lower bound of the cost [`build`] finds for `mons`, without the search: the factoring
/// only pulls common factors out of the given monomials, so every distinct atom and symbol
/// of them is a leaf of its result at least once; each atom is a call, and `n` leaves take
/// at least `n - 1` additions and multiplications to combine (a sum or product of `k` parts
/// costs `k - 1`; negations and powers only add).
pub(crate) fn cost_lower_bound(mons: &[Mon]) -> Cost {
    let mut atoms: Vec<Atom> = mons.iter().flat_map(|m| m.atoms.iter().copied()).collect();
    atoms.sort_unstable();
    atoms.dedup();
    let mut syms: Vec<u32> = mons
        .iter()
        .flat_map(|m| m.syms.iter().map(|&(s, _)| s))
        .collect();
    syms.sort_unstable();
    syms.dedup();
    Cost {
        ops: (atoms.len() + syms.len()).saturating_sub(1) + atoms.len(),
        calls: atoms.len(),
    }
}

pub(crate) fn build(mons: &[Mon]) -> Result<(E, Cost), ScalarError> {
    let mut s = Search {
        counts: Counts::for_mons(mons),
        ..Search::default()
    };
    let e = s.build_at(mons, 0);
    if let Some(err) = s.spent {
        return Err(err);
    }
    let c = e.cost();
    Ok((e, c))
}

impl Search {
    fn build_at(&mut self, mons: &[Mon], depth: usize) -> E {
        match mons {
            [] => return E::zero(),
            [m] => return mon_expr(m),
            _ => {}
        }
        let work: usize = mons.iter().map(|m| 1 + m.syms.len() + m.atoms.len()).sum();
        if self.spent.is_none() {
            self.spent = charge(work as u64).err();
        }
        if self.spent.is_some() {
            // Out of budget: the result is discarded, so stop at once.
            return E::sum(mons.iter().map(mon_expr).collect());
        }
        // A sum whose terms are all negative reads better as the negation of a sum.
        if mons.iter().all(|m| m.q.is_negative()) {
            let neg: Vec<Mon> = mons
                .iter()
                .map(|m| Mon {
                    q: -&m.q,
                    ..m.clone()
                })
                .collect();
            return E::Neg(Rc::new(self.build_at(&neg, depth)));
        }
        let g = content(mons);
        if !g.is_one() {
            let inner: Vec<Mon> = mons
                .iter()
                .map(|m| Mon {
                    q: div_q(&m.q, &g),
                    ..m.clone()
                })
                .collect();
            return mul(vec![E::Num(g), self.build_at(&inner, depth)]);
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
            return mul(vec![E::Sqrt(r), self.build_at(&inner, depth)]);
        }
        let tries = if depth < BRANCH_DEPTH { BRANCH } else { 1 };
        let candidates = self.counts.candidates(mons, tries);
        if candidates.is_empty() {
            return E::sum(mons.iter().map(mon_expr).collect());
        }
        // The result depends on the depth only through the branching, so below the branching
        // levels all depths share one entry.
        let level = depth.min(BRANCH_DEPTH);
        let hash = {
            let mut h = FxHasher::default();
            level.hash(&mut h);
            mons.hash(&mut h);
            h.finish()
        };
        if let Some((_, _, e)) = self
            .memo
            .get(&hash)
            .and_then(|v| v.iter().find(|(l, m, _)| *l == level && m == mons))
        {
            return e.clone();
        }
        let mut best: Option<(Cost, E)> = None;
        for f in candidates {
            let e = self.split_on(mons, f, depth);
            let c = e.cost();
            if best.as_ref().is_none_or(|(bc, _)| c < *bc) {
                best = Some((c, e));
            }
        }
        let e = best.map(|(_, e)| e).unwrap_or_else(E::zero);
        self.memo
            .entry(hash)
            .or_default()
            .push((level, mons.to_vec(), e.clone()));
        e
    }

    /// `f^k * (sum of the monomials containing f, divided by f^k) + (the others)`, `k` the
    /// lowest power of `f` among the monomials containing it. Pulling out `f` once per level
    /// would give the same expression (while `f` is in every monomial of the group it stays
    /// the most frequent factor), but at a cost quadratic in `k`: `x^10000 - x^9999` took ten
    /// thousand levels, each copying the product of the levels above.
    fn split_on(&mut self, mons: &[Mon], f: Factor, depth: usize) -> E {
        let k = mons
            .iter()
            .map(|m| multiplicity(m, f))
            .filter(|&n| n > 0)
            .min()
            .unwrap_or(1);
        let mut with = Vec::with_capacity(mons.len());
        let mut without = Vec::with_capacity(mons.len());
        let mut first_with = None;
        for (i, m) in mons.iter().enumerate() {
            match divide(m, f, k) {
                Some(d) => {
                    first_with.get_or_insert(i);
                    with.push(d)
                }
                None => without.push(i),
            }
        }
        // The depth as if `f` had been pulled out `k` times, one level each (the branching
        // stops at the same place).
        let inner = self.build_at(&with, depth.saturating_add(k as usize));
        let factored = mul(vec![factor_expr(f, k), inner]);
        let first_with = first_with.unwrap_or(0);
        // Keep the reading order: the factored group stands where its first monomial stood.
        let n_before = without.iter().filter(|&&i| i < first_with).count();
        let rest: Vec<Mon> = without
            .iter()
            .filter(|&&i| i != first_with)
            .map(|&i| mons[i].clone())
            .collect();
        if rest.is_empty() {
            return factored;
        }
        let rest_expr = self.build_at(&rest, depth + 1);
        // Splice the rest around the factored group in reading order.
        let mut rest_terms = match rest_expr {
            E::Add(v, _) => v.to_vec(),
            e => vec![e],
        };
        let mut terms = Vec::with_capacity(rest_terms.len() + 1);
        if rest_terms.len() == rest.len() {
            let n_before = n_before.min(rest_terms.len());
            let after = rest_terms.split_off(n_before);
            terms.extend(rest_terms);
            terms.push(factored);
            terms.extend(after);
        } else {
            terms.push(factored);
            terms.extend(rest_terms);
        }
        if terms.len() == 1 {
            terms.pop().unwrap_or_else(E::zero)
        } else {
            E::sum(terms)
        }
    }
}

/// Counts of the factors of a group of monomials, by a dense index (atoms first, then
/// symbols: the order of [`Factor`]), reused across the search.
#[derive(Default)]
struct Counts {
    /// The index of symbol 0 (one past the largest atom).
    sym_base: usize,
    n: Vec<u32>,
    touched: Vec<usize>,
}

impl Counts {
    fn for_mons(mons: &[Mon]) -> Counts {
        let atoms = mons.iter().flat_map(|m| m.atoms.iter().map(|&a| a as usize + 1));
        let syms = mons.iter().flat_map(|m| m.syms.iter().map(|&(s, _)| s as usize + 1));
        let sym_base = atoms.max().unwrap_or(0);
        Counts {
            sym_base,
            n: vec![0; sym_base + syms.max().unwrap_or(0)],
            touched: Vec::new(),
        }
    }

    fn factor(&self, i: usize) -> Factor {
        if i < self.sym_base {
            Factor::Atom(i as Atom)
        } else {
            Factor::Sym((i - self.sym_base) as u32)
        }
    }

    /// The first `k` factors that occur in at least two monomials, most frequent first, ties
    /// by factor order (the order a full sort of the counts gave, without the sort: only the
    /// first few are ever tried).
    fn candidates(&mut self, mons: &[Mon], k: usize) -> Vec<Factor> {
        for m in mons {
            for &(s, _) in &m.syms {
                self.bump(self.sym_base + s as usize);
            }
            let mut last: Option<Atom> = None;
            for &a in &m.atoms {
                if last != Some(a) {
                    self.bump(a as usize);
                }
                last = Some(a);
            }
        }
        // The best `k` as (count, index), best first: a higher count, then a lower index.
        let mut best: Vec<(u32, usize)> = Vec::with_capacity(k + 1);
        for &i in &self.touched {
            let c = self.n[i];
            if c < 2 {
                continue;
            }
            let pos = best.partition_point(|&(bc, bi)| bc > c || (bc == c && bi < i));
            if pos < k {
                best.insert(pos, (c, i));
                best.truncate(k);
            }
        }
        for &i in &self.touched {
            self.n[i] = 0;
        }
        self.touched.clear();
        best.into_iter().map(|(_, i)| self.factor(i)).collect()
    }

    fn bump(&mut self, i: usize) {
        if self.n[i] == 0 {
            self.touched.push(i);
        }
        self.n[i] += 1;
    }
}

/// The power of `f` in `m` (0 when `m` lacks it).
fn multiplicity(m: &Mon, f: Factor) -> u32 {
    match f {
        Factor::Sym(s) => m.syms.iter().find(|&&(x, _)| x == s).map_or(0, |&(_, e)| e),
        Factor::Atom(a) => m.atoms.iter().filter(|&&x| x == a).count() as u32,
    }
}

/// `m / f^k`, when `f^k` divides `m`.
fn divide(m: &Mon, f: Factor, k: u32) -> Option<Mon> {
    match f {
        Factor::Sym(s) => {
            let pos = m.syms.iter().position(|&(x, e)| x == s && e >= k)?;
            let mut m = m.clone();
            if m.syms[pos].1 == k {
                m.syms.remove(pos);
            } else {
                m.syms[pos].1 -= k;
            }
            Some(m)
        }
        Factor::Atom(a) => {
            if multiplicity(m, f) < k {
                return None;
            }
            let mut m = m.clone();
            // The atoms are sorted: the `k` copies of `a` stand together.
            let pos = m.atoms.iter().position(|&x| x == a)?;
            m.atoms.drain(pos..pos + k as usize);
            Some(m)
        }
    }
}

/// `f^k` as a product.
fn factor_expr(f: Factor, k: u32) -> E {
    match (f, k) {
        (Factor::Sym(s), 1) => E::Sym(s),
        (Factor::Sym(s), k) => E::Pow(s, k),
        (Factor::Atom(a), 1) => E::Trig(a),
        (Factor::Atom(a), k) => E::product(vec![E::Trig(a); k as usize]),
    }
}

/// A product, flattened, with a leading negation pulled out of it.
fn mul(parts: Vec<E>) -> E {
    let mut flat = Vec::new();
    let mut neg = false;
    for p in parts {
        match p {
            E::Mul(v, _) => flat.extend(v.iter().cloned()),
            E::Neg(e) => {
                neg = !neg;
                match Rc::unwrap_or_clone(e) {
                    E::Mul(v, _) => flat.extend(v.iter().cloned()),
                    e => flat.push(e),
                }
            }
            E::Num(q) if q.is_one() => {}
            e => flat.push(e),
        }
    }
    // Numbers first, then radicals, symbols, sums and trigonometric factors.
    flat.sort_by_key(rank);
    let e = match flat.len() {
        0 => E::Num(Q::ONE),
        1 => flat.pop().unwrap_or_else(E::zero),
        _ => E::product(flat),
    };
    if neg {
        E::Neg(Rc::new(e))
    } else {
        e
    }
}

fn rank(e: &E) -> u8 {
    match e {
        E::Num(_) => 0,
        E::Sqrt(_) => 1,
        E::Sym(_) | E::Pow(..) => 2,
        E::Trig(_) => 3,
        _ => 4,
    }
}

/// One monomial as an expression: `-2 sqrt(3) l1^2 c1`.
pub(crate) fn mon_expr(m: &Mon) -> E {
    let mut parts = Vec::with_capacity(2 + m.syms.len() + m.atoms.len());
    let neg = m.q.is_negative();
    let q = if neg { -&m.q } else { m.q.clone() };
    if !q.is_one() {
        parts.push(E::Num(q));
    }
    if m.rad != 1 {
        parts.push(E::Sqrt(m.rad));
    }
    for &(s, e) in &m.syms {
        parts.push(if e == 1 { E::Sym(s) } else { E::Pow(s, e) });
    }
    for &a in &m.atoms {
        parts.push(E::Trig(a));
    }
    let e = mul(parts);
    if neg {
        E::Neg(Rc::new(e))
    } else {
        e
    }
}
