//! From monomials to a nested display expression: common factors (symbols, trigonometric
//! atoms, numeric content) are pulled out where that lowers the cost.
//!
//! The search works on [`E`], a display expression over the interned atoms and symbols of a
//! [`Ctx`]; only the chosen one becomes an [`Expr`].

use super::expr::{Cost, Expr};
use super::mon::{angle_of, content_of, div_q, is_sin, Atom, Ctx, FxMap, Mon};
use super::recombine::atom_hash;
use crate::scalar::{charge, FxHasher, Q};
use crate::ScalarError;
use num_traits::One;
use smallvec::SmallVec;
use std::hash::{Hash, Hasher};
use std::rc::Rc;

mod costs;
mod floor;
mod run;

/// A factor that can be pulled out of several monomials.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug)]
enum Factor {
    Atom(Atom),
    Sym(u32),
}

/// The units one word of a big coefficient adds to a group's visit: its remainder modulo the
/// content (one 128-bit division a word), its exact division and its copy each go over it
/// once.
const BIG_WORD_UNITS: u64 = 3;

/// How many alternative factors are tried at each of the first levels.
///
/// The choice is the first of least cost, and the costs of the alternatives differ by a few
/// operations even where the sum is symmetric in them (measured on `(x + y + z)^60`: 37,760
/// and 37,759 operations for `x` and `y` pulled out of the same group, through ties broken by
/// symbol order further down), so neither a symmetry nor an estimate picks the same one: each
/// cost is exact. For a plain integer polynomial `costs.rs` finds it without the tree and only
/// the winner is built (`(x + y + z)^60`: 159 M instructions to 94 M); otherwise each
/// candidate is built in full (about ten trees of a big power's size) unless its lower bound
/// (`factor/floor.rs`) is not below the best built so far.
const BRANCH: usize = 3;
/// The candidates of a group, at most [`BRANCH`]: on the stack (a `Vec` was an allocation per
/// group searched).
type Candidates = SmallVec<[Factor; BRANCH]>;
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

    /// [`E::product`] of a slice, copied into the node (one allocation).
    fn product_of(v: &[E]) -> E {
        let c = Self::node_cost(v, false);
        E::Mul(Rc::from(v), c)
    }

    /// [`E::sum`] of terms already in their node.
    fn sum_of(v: Rc<[E]>) -> E {
        let c = Self::node_cost(&v, true);
        E::Add(v, c)
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

    /// The cost of this as a term of a sum: a negation there is a subtraction, no operation
    /// of its own.
    fn cost_in_sum(&self) -> Cost {
        let mut c = Cost::default();
        self.add_cost(&mut c, true);
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

/// A group of the search: monomials of the root list by index, each with its coefficient,
/// divided by the factors pulled out above it ([`Search::div`]). The monomials themselves are
/// never copied: a group of the search is always the root's monomials divided by one common
/// monomial, with coefficients scaled alike, so an index, a coefficient and that common
/// divisor (kept once, in the search) describe each one.
type Group = Vec<(u32, Q)>;

/// A result found for a group: its depth class, the group, the factors pulled out of it
/// (sorted counts indices with their powers) and whether its radical was, and the result.
struct Found {
    level: usize,
    group: Group,
    div: Vec<(usize, u32)>,
    rad_off: bool,
    e: E,
}

/// A split of a group on a factor `f` ([`Search::split`]): the lowest power `k` of `f` among
/// the monomials holding it, those monomials (`with`) and the others (`rest`), each in the
/// group's order, and how many of the others stand before the first of `with`.
struct Split {
    k: u32,
    with: Group,
    rest: Group,
    n_before: usize,
}

/// The search state: the root monomials; the common divisor of the current group and whether
/// its common radical was pulled out; results already found for a group at a depth class, by
/// the hash of its monomials; the budget error once the search has used up the work budget.
struct Search<'a> {
    root: &'a [Mon],
    counts: Counts,
    /// The power of each factor (by [`Counts`] index) pulled out of the current group.
    div: Vec<u32>,
    /// The factors of `div`, as pulled out (an index may repeat).
    path: Vec<(usize, u32)>,
    rad_off: bool,
    memo: FxMap<u64, Vec<Found>>,
    /// Each root monomial's [`linear_hash`]: a quotient's is this less the divisor's.
    mon_hash: Vec<u64>,
    /// The costs of candidates found without their trees, for plain integer polynomials.
    costs: Option<costs::Costs>,
    spent: Option<ScalarError>,
    /// Above zero while the winner of a cost pass is built: its work was charged by the pass
    /// (which repeats every step of the build), so charging it again would count it twice.
    prepaid: u32,
    /// Scratch of [`Search::floor`]: the highest power of each factor (by [`Counts`] index)
    /// in a group's quotients, zero between calls, and the indices raised.
    floor_pow: Vec<u32>,
    floor_touched: Vec<usize>,
    /// Scratch of [`Search::floor`]: the monomials (of up to 64) holding each factor, as bits.
    floor_bits: Vec<u64>,
    /// Whether a built candidate is skipped where its lower bound is not below the best cost
    /// so far (always, but in the tests that compare the search with and without it).
    floored: bool,
}

/// The cheapest nested expression this search finds for the sum of `mons`, with its cost.
///
/// The search counts against the work budget like scalar arithmetic (one unit per monomial
/// and per factor of it looked at, [`BIG_WORD_UNITS`] per word of a big coefficient); when
/// the budget runs out it stops with the budget error.
pub(crate) fn build(mons: &[Mon]) -> Result<(E, Cost), ScalarError> {
    build_with(mons, Pass::Bounded)
}

/// How [`build_with`] compares the candidates of its branching levels.
///
/// Only [`Pass::Bounded`] runs outside the tests, which compare the three.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
#[cfg_attr(not(test), allow(dead_code))]
enum Pass {
    /// Every candidate built.
    Trees,
    /// Each candidate's cost found without its tree (`costs.rs`) where the monomials allow it;
    /// elsewhere a candidate built only where its lower bound (`floor.rs`) is below the best
    /// cost so far.
    Costs,
    /// [`Pass::Costs`], each candidate cut once its cost reaches the best so far ([`build`]).
    Bounded,
}

/// [`build`], the candidates compared as `pass` says (the tests compare the three).
fn build_with(mons: &[Mon], pass: Pass) -> Result<(E, Cost), ScalarError> {
    let mut s = search(mons, pass);
    let group = root_group(mons);
    let e = s.build_at(&group, 0);
    if let Some(err) = s.spent {
        return Err(err);
    }
    let c = e.cost();
    Ok((e, c))
}

/// A search of `mons` in its start state, comparing candidates as `pass` says.
fn search(mons: &[Mon], pass: Pass) -> Search<'_> {
    let counts = Counts::for_mons(mons);
    let factors = counts.n.len();
    let mon_hash = mons.iter().map(|m| linear_hash(m, &counts)).collect();
    Search {
        root: mons,
        div: vec![0; factors],
        counts,
        path: Vec::new(),
        rad_off: false,
        memo: FxMap::default(),
        mon_hash,
        costs: match pass {
            Pass::Trees => None,
            Pass::Costs | Pass::Bounded => costs::Costs::for_mons(mons).map(|mut c| {
                c.bounded = pass == Pass::Bounded;
                c
            }),
        },
        spent: None,
        prepaid: 0,
        floor_pow: vec![0; factors],
        floor_touched: Vec::new(),
        floor_bits: vec![0; factors],
        floored: pass != Pass::Trees,
    }
}

/// The group of all of `mons`, with their coefficients.
fn root_group(mons: &[Mon]) -> Group {
    mons.iter()
        .enumerate()
        .map(|(i, m)| (i as u32, m.q.clone()))
        .collect()
}

/// A lower bound of the cost [`build`] finds for `mons`, without the search: the factoring
/// only pulls common factors out of the given monomials, so every distinct atom and symbol
/// of them is a leaf of its result at least once; each atom is a call, and `n` leaves take
/// at least `n - 1` additions and multiplications to combine (a sum or product of `k` parts
/// costs `k - 1`; negations and powers only add); and at least [`summands_lower_bound`].
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
    let leaves = (atoms.len() + syms.len()).saturating_sub(1);
    Cost {
        ops: leaves.max(summands_lower_bound(mons).ops) + atoms.len(),
        calls: atoms.len(),
    }
}

/// A lower bound of the cost [`build`] finds for `mons`, in constant time: each monomial stays
/// one summand of the result (a factor pulled out of some monomials divides each of them
/// exactly, and distinct monomials stay distinct), so `m` monomials take at least `m - 1`
/// additions or subtractions (a regrouped shape of 180 monomials at least 179 operations, more
/// than its whole modes' form of 163: the Jaco-style arm's entries as given).
pub(crate) fn summands_lower_bound(mons: &[Mon]) -> Cost {
    Cost {
        ops: mons.len().saturating_sub(1),
        calls: 0,
    }
}

/// A hash of `f^k`, `f` by its [`Counts`] index: `k` times the factor's.
fn factor_hash(f: usize, k: u32) -> u64 {
    u64::from(k).wrapping_mul(atom_hash(f as u32))
}

/// A hash of monomial `m`'s symbols and atoms (not its coefficient or radical): the sum of
/// [`factor_hash`] over its factors. Being a sum, the hash of a quotient `m / d` is `m`'s
/// less `d`'s, found without the quotient ([`Search::hash`]: the walk of each quotient was
/// most of the hash of a group). Equal quotients hash alike; the memo compares the groups
/// a hash finds ([`Search::same_monomials`]), so a collision costs only that comparison.
fn linear_hash(m: &Mon, counts: &Counts) -> u64 {
    factors_hash(
        m.syms.iter().copied(),
        m.atoms.iter().copied(),
        counts.sym_base,
    )
}

/// The sum of [`factor_hash`] over symbols `syms` (indexed from `sym_base`) and `atoms`:
/// [`linear_hash`] of the monomial they make.
fn factors_hash(
    syms: impl Iterator<Item = (u32, u32)>,
    atoms: impl Iterator<Item = Atom>,
    sym_base: usize,
) -> u64 {
    let syms = syms.map(|(s, e)| factor_hash(sym_base + s as usize, e));
    let atoms = atoms.map(|a| factor_hash(a as usize, 1));
    syms.chain(atoms).fold(0u64, u64::wrapping_add)
}

/// The symbols of `m` divided by `div` (indexed as [`Counts`]), those left.
fn quotient_syms<'m>(
    m: &'m Mon,
    div: &'m [u32],
    sym_base: usize,
) -> impl Iterator<Item = (u32, u32)> + 'm {
    m.syms.iter().filter_map(move |&(s, e)| {
        let e = e - div[sym_base + s as usize];
        (e > 0).then_some((s, e))
    })
}

/// The atoms of `m` divided by `div`: the first `div[a]` copies of each atom `a` left out
/// (the atoms are sorted, so the copies stand together).
fn quotient_atoms<'m>(m: &'m Mon, div: &'m [u32]) -> impl Iterator<Item = Atom> + 'm {
    let mut run: (Option<Atom>, u32) = (None, 0);
    m.atoms.iter().copied().filter(move |&a| {
        if run.0 != Some(a) {
            run = (Some(a), 0);
        }
        run.1 += 1;
        run.1 > div[a as usize]
    })
}

impl Search<'_> {
    /// Charges `work` to the budget, unless it is out already or the work was prepaid.
    fn charge_work(&mut self, work: u64) {
        if self.spent.is_none() && self.prepaid == 0 {
            self.spent = charge(work).err();
        }
    }

    fn build_at(&mut self, group: &[(u32, Q)], depth: usize) -> E {
        match group {
            [] => return E::zero(),
            [(i, q)] => return self.mon_expr(*i, q),
            _ => {}
        }
        // A big coefficient adds its words: each visit reads it a few times (content,
        // division, hash). Uncharged, a power whose expansion is cheap (`(x + y)^2000`, a
        // thousand-digit coefficient per term, formed term by term) spent a minute here
        // before the budget stopped it.
        let work: usize = self.quotient_lens(group)
            + group
                .iter()
                .map(|(_, q)| 1 + (q.words() * BIG_WORD_UNITS) as usize)
                .sum::<usize>();
        self.charge_work(work as u64);
        if self.spent.is_some() {
            // Out of budget: the result is discarded, so stop at once.
            return self.plain_sum(group);
        }
        // A sum whose terms are all negative reads better as the negation of a sum.
        if group.iter().all(|(_, q)| q.is_negative()) {
            let neg: Group = group.iter().map(|(i, q)| (*i, -q)).collect();
            return E::Neg(Rc::new(self.build_at(&neg, depth)));
        }
        let g = content_of(group.iter().map(|(_, q)| q));
        if !g.is_one() {
            let inner: Group = group.iter().map(|(i, q)| (*i, div_q(q, &g))).collect();
            return mul(E::Num(g), self.build_at(&inner, depth));
        }
        let r = self.rad(group[0].0);
        if r != 1 && group.iter().all(|(i, _)| self.rad(*i) == r) {
            self.rad_off = true;
            let e = self.build_at(group, depth);
            self.rad_off = false;
            return mul(E::Sqrt(r), e);
        }
        self.searched(group, depth)
    }

    /// [`Search::build_at`] past its first steps (sign, content, radical): the memo, the
    /// candidates, the splits.
    fn searched(&mut self, group: &[(u32, Q)], depth: usize) -> E {
        // The result depends on the depth only through the branching, so below the branching
        // levels all depths share one entry. Looked up before the candidates are counted: a
        // group found before needs no count. A group without candidates (its plain sum) is
        // stored too: the rests of the candidates of a branching level meet the same small
        // groups again.
        let level = depth.min(BRANCH_DEPTH);
        let hash = self.hash(level, group);
        let key = self.div_key();
        if let Some(e) = self.remembered(hash, level, &key, group) {
            return e;
        }
        let tries = if depth < BRANCH_DEPTH { BRANCH } else { 1 };
        let candidates = self.candidates(group.iter().map(|(i, _)| *i), tries);
        let e = if candidates.is_empty() {
            self.plain_sum(group)
        } else if tries == 1 {
            // Below the branching levels: the run of splits on the most frequent factor.
            self.run(group, candidates[0], depth)
        } else if let Some((f, c)) = self.cost_winner(group, &candidates, depth) {
            // Only the first candidate of least cost is built (`costs.rs`).
            self.prepaid += 1;
            let e = self.split_on(group, f, depth);
            self.prepaid -= 1;
            debug_assert!(
                self.spent.is_some() || e.cost() == c,
                "cost without the tree"
            );
            e
        } else {
            let mut best: Option<(Cost, E)> = None;
            for f in candidates {
                // A candidate whose lower bound is not below the best cost so far cannot be
                // chosen (the first of least cost is): it is not built, or only its factored
                // part is (`floor.rs`).
                let e = match best.as_ref().filter(|_| self.floored) {
                    Some((bc, _)) => match self.split_below(group, f, depth, *bc) {
                        Some(e) => e,
                        None => continue,
                    },
                    None => self.split_on(group, f, depth),
                };
                let c = e.cost();
                if best.as_ref().is_none_or(|(bc, _)| c < *bc) {
                    best = Some((c, e));
                }
            }
            best.map(|(_, e)| e).unwrap_or_else(E::zero)
        };
        let found = Found {
            level,
            group: group.to_vec(),
            div: key,
            rad_off: self.rad_off,
            e: e.clone(),
        };
        self.memo.entry(hash).or_default().push(found);
        e
    }

    /// `f^k * (sum of the monomials containing f, divided by f^k) + (the others)`, `k` the
    /// lowest power of `f` among the monomials containing it. Pulling out `f` once per level
    /// would give the same expression (while `f` is in every monomial of the group it stays
    /// the most frequent factor), but at a cost quadratic in `k`: `x^10000 - x^9999` took ten
    /// thousand levels, each copying the product of the levels above.
    fn split_on(&mut self, group: &[(u32, Q)], f: Factor, depth: usize) -> E {
        let split = self.split(group, f);
        let factored = self.factored(&split, f, depth);
        // The rest spliced around the factored group in reading order: the factored group
        // stands where its first monomial stood.
        self.beside(factored, &split.rest, split.n_before, depth)
    }

    /// The parts of [`Search::split_on`]`(group, f, _)`, not yet searched.
    fn split(&self, group: &[(u32, Q)], f: Factor) -> Split {
        // Each monomial's power of `f` looked up once, for `k` and for the split.
        let mults: Mults = self.powers(group.iter().map(|(i, _)| *i), f);
        split_by(group, &mults)
    }
}

/// Each monomial's power of the factor a group is split on.
type Mults = SmallVec<[u32; 32]>;

/// The lowest power above zero among `mults` (one where there is none).
fn lowest_power(mults: &[u32]) -> u32 {
    mults.iter().copied().filter(|&n| n > 0).min().unwrap_or(1)
}

/// The split of `group` whose monomials hold the factor to the powers `mults`.
fn split_by(group: &[(u32, Q)], mults: &[u32]) -> Split {
    let k = lowest_power(mults);
    let mut with = Vec::with_capacity(group.len());
    let mut rest = Vec::with_capacity(group.len());
    let mut first_with = None;
    let mut n_before = 0;
    for ((pos, m), &n) in group.iter().enumerate().zip(mults) {
        if n >= k {
            first_with.get_or_insert(pos);
            with.push(m.clone());
        } else {
            if first_with.is_none() {
                n_before += 1;
            }
            rest.push(m.clone());
        }
    }
    Split {
        k,
        with,
        rest,
        n_before,
    }
}

impl Search<'_> {
    /// `f^k` times the search of the monomials holding it, divided by it.
    fn factored(&mut self, split: &Split, f: Factor, depth: usize) -> E {
        let (fi, k) = (self.counts.index(f), split.k);
        // The depth as if `f` had been pulled out `k` times, one level each (the branching
        // stops at the same place).
        self.div[fi] += k;
        self.path.push((fi, k));
        let masked = self.mask_div(f, true);
        let inner = self.build_at(&split.with, depth.saturating_add(k as usize));
        if masked {
            self.mask_div(f, false);
        }
        self.path.pop();
        self.div[fi] -= k;
        mul(factor_expr(f, k), inner)
    }

    /// The radicand of monomial `i` of the current group.
    fn rad(&self, i: u32) -> u64 {
        if self.rad_off {
            1
        } else {
            self.root[i as usize].rad
        }
    }

    /// The number of symbols and atoms of the monomials of the current group: on a
    /// multilinear root's bit sets ([`Search::masks`]), or counted from each monomial's
    /// lengths. Every monomial of a group holds the divisor (a split keeps in the group only
    /// the monomials holding the factor pulled out), so its quotient has `div[a]` copies less
    /// of each atom `a` of the divisor, and lacks a symbol of the divisor exactly where its
    /// power is the divisor's: the count [`quotient_syms`] and [`quotient_atoms`] give, without
    /// walking them (walked, it was 5 M instructions of the Jaco-style arm's report). Not
    /// inlined: [`Search::build_at`] stays small enough for its content's gcd to be inlined
    /// (`(x + y + z)^30`: 0.5% of the report).
    #[inline(never)]
    fn quotient_lens(&self, group: &[(u32, Q)]) -> usize {
        if let Some(masks) = self.masks() {
            return group
                .iter()
                .map(|(i, _)| masks.quotient(*i).count_ones() as usize)
                .sum();
        }
        let pulled = self.pulled();
        let base = self.counts.sym_base;
        let atoms_pulled: usize = pulled
            .iter()
            .filter(|&&(j, _)| j < base)
            .map(|&(_, k)| k as usize)
            .sum();
        let lens = group.iter().map(|(i, _)| {
            let m = &self.root[*i as usize];
            let gone = pulled
                .iter()
                .filter(|&&(j, k)| j >= base && multiplicity(m, self.counts.factor(j)) == k)
                .count();
            (m.syms.len() + m.atoms.len()).saturating_sub(atoms_pulled + gone)
        });
        let n = lens.sum();
        debug_assert_eq!(
            n,
            group
                .iter()
                .map(|(i, _)| {
                    let m = &self.root[*i as usize];
                    quotient_syms(m, &self.div, base).count() + quotient_atoms(m, &self.div).count()
                })
                .sum::<usize>()
        );
        n
    }

    /// The factors of the divisor, each once, with their powers in it: every power `div`
    /// holds above zero was pulled out on the path (a split or a run pushes its factor
    /// there), so the path names them all.
    fn pulled(&self) -> SmallVec<[(usize, u32); 8]> {
        let mut pulled: SmallVec<[(usize, u32); 8]> = SmallVec::new();
        for &(j, _) in &self.path {
            let k = self.div[j];
            if k > 0 && !pulled.iter().any(|&(i, _)| i == j) {
                pulled.push((j, k));
            }
        }
        pulled
    }

    /// Monomial `i` of the current group, with coefficient `q`, as an expression.
    fn mon_expr(&self, i: u32, q: &Q) -> E {
        let m = &self.root[i as usize];
        mon_parts_expr(
            q,
            self.rad(i),
            quotient_syms(m, &self.div, self.counts.sym_base),
            quotient_atoms(m, &self.div),
        )
    }

    /// The group as a plain sum of its monomials.
    fn plain_sum(&self, group: &[(u32, Q)]) -> E {
        E::sum(group.iter().map(|(i, q)| self.mon_expr(*i, q)).collect())
    }

    /// The first `k` factors that occur in at least two monomials of the group.
    fn candidates(&mut self, group: impl Iterator<Item = u32> + Clone, k: usize) -> Candidates {
        if let Some(best) = self.candidates_masked(group.clone(), k) {
            return best;
        }
        let (root, div, c) = (self.root, &self.div, &mut self.counts);
        for i in group {
            let m = &root[i as usize];
            for (s, _) in quotient_syms(m, div, c.sym_base) {
                c.bump(c.sym_base + s as usize);
            }
            let mut last: Option<Atom> = None;
            for a in quotient_atoms(m, div) {
                if last != Some(a) {
                    c.bump(a as usize);
                }
                last = Some(a);
            }
        }
        c.best(k)
    }

    /// The factors pulled out of the current group, sorted by index, equal ones merged.
    fn div_key(&self) -> Vec<(usize, u32)> {
        let mut v = self.path.clone();
        v.sort_unstable();
        v.dedup_by(|b, a| {
            let same = a.0 == b.0;
            if same {
                a.1 += b.1;
            }
            same
        });
        v
    }

    /// A hash of the group's monomials (as divided) at a depth class.
    fn hash(&self, level: usize, group: &[(u32, Q)]) -> u64 {
        let mut h = FxHasher::default();
        level.hash(&mut h);
        group.len().hash(&mut h);
        if let Some(masks) = self.masks() {
            // A multilinear root: a quotient is one word, and there is no radical.
            for (i, q) in group {
                q.hash_words(&mut h);
                h.write_u64(masks.quotient(*i));
            }
            return h.finish();
        }
        // A quotient's [`linear_hash`] is its monomial's less the divisor's (every monomial
        // of the group holds the divisor): one subtraction where its factors were walked.
        let div = self
            .pulled()
            .iter()
            .fold(0u64, |d, &(j, k)| d.wrapping_add(factor_hash(j, k)));
        for (i, q) in group {
            q.hash_words(&mut h);
            self.rad(*i).hash(&mut h);
            let quotient = self.mon_hash[*i as usize].wrapping_sub(div);
            debug_assert_eq!(quotient, {
                let m = &self.root[*i as usize];
                let base = self.counts.sym_base;
                factors_hash(
                    quotient_syms(m, &self.div, base),
                    quotient_atoms(m, &self.div),
                    base,
                )
            });
            h.write_u64(quotient);
        }
        h.finish()
    }

    /// The result found before for a group of the same monomials at the same depth class.
    fn remembered(
        &self,
        hash: u64,
        level: usize,
        key: &[(usize, u32)],
        group: &[(u32, Q)],
    ) -> Option<E> {
        let entries = self.memo.get(&hash)?;
        entries
            .iter()
            .find(|f| f.level == level && self.same_monomials(f, key, group))
            .map(|f| f.e.clone())
    }

    /// Whether `found`'s group holds the same monomials as `group` does in the current state
    /// (`key` its [`Search::div_key`]).
    fn same_monomials(&self, found: &Found, key: &[(usize, u32)], group: &[(u32, Q)]) -> bool {
        if found.group.len() != group.len() {
            return false;
        }
        if found.div == key && found.rad_off == self.rad_off {
            // Divided alike: a quotient determines its monomial of the root, which are
            // distinct.
            return found.group == group;
        }
        // Divided differently: compared monomial by monomial.
        let mut other = vec![0u32; self.div.len()];
        for &(i, k) in &found.div {
            other[i] = k;
        }
        let base = self.counts.sym_base;
        found.group.iter().zip(group).all(|((i, q), (j, r))| {
            let (m, n) = (&self.root[*i as usize], &self.root[*j as usize]);
            let rad_m = if found.rad_off { 1 } else { m.rad };
            q == r
                && rad_m == self.rad(*j)
                && quotient_syms(m, &other, base).eq(quotient_syms(n, &self.div, base))
                && quotient_atoms(m, &other).eq(quotient_atoms(n, &self.div))
        })
    }
}

/// Counts of the factors of a group of monomials, by a dense index (atoms first, then
/// symbols: the order of [`Factor`]), reused across the search.
struct Counts {
    /// The index of symbol 0 (one past the largest atom).
    sym_base: usize,
    n: Vec<u32>,
    touched: Vec<usize>,
}

impl Counts {
    fn for_mons(mons: &[Mon]) -> Counts {
        let atoms = mons
            .iter()
            .flat_map(|m| m.atoms.iter().map(|&a| a as usize + 1));
        let syms = mons
            .iter()
            .flat_map(|m| m.syms.iter().map(|&(s, _)| s as usize + 1));
        let sym_base = atoms.max().unwrap_or(0);
        Counts {
            sym_base,
            n: vec![0; sym_base + syms.max().unwrap_or(0)],
            touched: Vec::new(),
        }
    }

    fn index(&self, f: Factor) -> usize {
        match f {
            Factor::Atom(a) => a as usize,
            Factor::Sym(s) => self.sym_base + s as usize,
        }
    }

    fn factor(&self, i: usize) -> Factor {
        if i < self.sym_base {
            Factor::Atom(i as Atom)
        } else {
            Factor::Sym((i - self.sym_base) as u32)
        }
    }

    /// The counts cleared without reading them.
    fn clear(&mut self) {
        for &i in &self.touched {
            self.n[i] = 0;
        }
        self.touched.clear();
    }

    fn bump(&mut self, i: usize) {
        if self.n[i] == 0 {
            self.touched.push(i);
        }
        self.n[i] += 1;
    }

    /// The first `k` factors counted at least twice, most frequent first, ties by factor
    /// order (the order a full sort of the counts gave, without the sort: only the first few
    /// are ever tried); the counts are cleared.
    fn best(&mut self, k: usize) -> Candidates {
        // The best `k` as (count, index), best first: a higher count, then a lower index. A
        // count no better than the last kept is passed over at once (most are).
        let mut best: SmallVec<[(u32, usize); 4]> = SmallVec::new();
        for &i in &self.touched {
            let c = self.n[i];
            self.n[i] = 0;
            if c < 2 || k == 0 {
                continue;
            }
            if best.len() == k {
                let (lc, li) = best[k - 1];
                if c < lc || (c == lc && i > li) {
                    continue;
                }
            }
            let pos = best.partition_point(|&(bc, bi)| bc > c || (bc == c && bi < i));
            best.insert(pos, (c, i));
            best.truncate(k);
        }
        self.touched.clear();
        best.into_iter().map(|(_, i)| self.factor(i)).collect()
    }
}

/// The power of `f` in `m` (0 when `m` lacks it).
fn multiplicity(m: &Mon, f: Factor) -> u32 {
    match f {
        // The symbols are sorted by id (`Mon`'s invariant, checked in debug builds).
        Factor::Sym(s) => {
            debug_assert!(m.syms.windows(2).all(|w| w[0].0 < w[1].0));
            m.syms
                .binary_search_by_key(&s, |&(x, _)| x)
                .map_or(0, |k| m.syms[k].1)
        }
        Factor::Atom(a) => m.atoms.iter().filter(|&&x| x == a).count() as u32,
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

/// The product `a b`, flattened, with a leading negation pulled out of it.
///
/// The factors are gathered on the stack and the node is allocated once, at its size: a
/// vector per product, copied into the node and freed, was one allocation in three of the
/// search. Two factors neither of which is a product, a negation or the number one (a
/// factor and a sum: most products of the search) are that node at once, in [`rank`] order,
/// as the general path would sort them (its sort is stable).
fn mul(a: E, b: E) -> E {
    let plain = |e: &E| match e {
        E::Mul(..) | E::Neg(_) => false,
        E::Num(q) => !q.is_one(),
        _ => true,
    };
    if plain(&a) && plain(&b) {
        return if rank(&b) < rank(&a) {
            E::product_of(&[b, a])
        } else {
            E::product_of(&[a, b])
        };
    }
    mul_flat(a, b)
}

/// [`mul`]'s general path: the factors of products flattened, negations pulled out, ones
/// left out, the rest stably sorted by [`rank`].
fn mul_flat(a: E, b: E) -> E {
    let mut flat: SmallVec<[E; 8]> = SmallVec::new();
    let mut neg = false;
    for p in [a, b] {
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
    product_node(flat, neg)
}

/// The product of `parts` (in [`rank`] order, none a product, a negation or the number one)
/// as one node: one, the single part, or their product; negated when `neg`.
fn product_node(mut parts: SmallVec<[E; 8]>, neg: bool) -> E {
    let e = match parts.len() {
        0 => E::Num(Q::ONE),
        1 => parts.pop().unwrap_or_else(E::zero),
        _ => E::product_of(&parts),
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
    mon_parts_expr(&m.q, m.rad, m.syms.iter().copied(), m.atoms.iter().copied())
}

/// The monomial `q sqrt(rad) syms atoms` as an expression.
fn mon_parts_expr(
    q: &Q,
    rad: u64,
    syms: impl Iterator<Item = (u32, u32)>,
    atoms: impl Iterator<Item = Atom>,
) -> E {
    let mut parts: SmallVec<[E; 8]> = SmallVec::new();
    let neg = q.is_negative();
    let q = if neg { -q } else { q.clone() };
    if !q.is_one() {
        parts.push(E::Num(q));
    }
    if rad != 1 {
        parts.push(E::Sqrt(rad));
    }
    for (s, e) in syms {
        parts.push(if e == 1 { E::Sym(s) } else { E::Pow(s, e) });
    }
    for a in atoms {
        parts.push(E::Trig(a));
    }
    // The parts are pushed in [`rank`] order, none a product, a negation or the number one,
    // so this is the product [`mul`]'s flattening and stable sort would make of them, without
    // them (they were two thirds of a monomial's cost: 8 M instructions of the Jaco-style
    // arm's report).
    debug_assert!(parts.windows(2).all(|w| rank(&w[0]) <= rank(&w[1])));
    product_node(parts, neg)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::closed::mon::whole_modes;
    use crate::Scalar;

    /// A pseudo-random integer polynomial in up to four symbols: a power of a sum with
    /// coefficients of either sign, times another, plus a few monomials.
    fn poly(seed: u64) -> Scalar {
        let mut next = crate::testing::xorshift_below(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
        let names = ["x", "y", "z", "w"];
        let sum = |next: &mut dyn FnMut(u64) -> u64| {
            let mut s = Scalar::int(next(3) as i64);
            for name in names.iter().take(2 + next(3) as usize) {
                let c = next(7) as i64 - 3;
                s = s + Scalar::int(if c == 0 { 1 } else { c }) * Scalar::sym(name);
            }
            s
        };
        let a = sum(&mut next).pow(2 + next(9));
        let b = sum(&mut next).pow(1 + next(3));
        let mut p = a * b;
        for _ in 0..next(4) {
            let c = next(41) as i64 - 20;
            let e = next(5);
            p = p + Scalar::int(c) * Scalar::sym(names[next(4) as usize]).pow(e);
        }
        p
    }

    /// The draws of a seeded random test generator (`testing::xorshift_below`'s).
    type Draw<'a> = &'a mut dyn FnMut(u64) -> u64;

    /// A product of two to four sums of two to four of `term`'s terms, drawn with `next`: the
    /// shape of the random polynomials the tests below factor.
    fn product_of_sums(next: &mut dyn FnMut(u64) -> u64, term: &dyn Fn(Draw) -> Scalar) -> Scalar {
        let mut p = Scalar::int(1);
        for _ in 0..2 + next(3) {
            let mut s = Scalar::int(0);
            for _ in 0..2 + next(3) {
                s = s + term(next);
            }
            p = p * s;
        }
        p
    }

    /// A pseudo-random polynomial in many symbols of low degree each, as the entries of a
    /// chain whose lengths and twists are symbols are: a product of two to four short sums of
    /// products of one or two symbols out of ten, plus a few monomials.
    fn poly_many(seed: u64) -> Scalar {
        let mut next = crate::testing::xorshift_below(seed.wrapping_mul(0x2545_f491_4f6c_dd1d) | 1);
        let names = ["a", "b", "c", "d", "e", "f", "g", "h", "u", "v"];
        let term = |next: &mut dyn FnMut(u64) -> u64| {
            let c = [1, -1, 1, -1, 2, -2, 3][next(7) as usize];
            let mut t = Scalar::int(c) * Scalar::sym(names[next(10) as usize]);
            if next(2) == 0 {
                t = t * Scalar::sym(names[next(10) as usize]);
            }
            t
        };
        let mut p = product_of_sums(&mut next, &term);
        for _ in 0..next(4) {
            p = p + term(&mut next) * term(&mut next);
        }
        p
    }

    /// The three passes on `p`: the same expression (and so the same cost), equal to `p`;
    /// whether the cost path was taken, and the work the costs and the bounded costs charged.
    fn three_passes(p: &Scalar, what: &str) -> Option<(bool, u64, u64)> {
        let (ctx, mons) = whole_modes(p);
        if mons.len() < 2 {
            return None;
        }
        let taken = costs::Costs::for_mons(&mons).is_some();
        let _entered = crate::Context::default().enter();
        let w0 = crate::Context::work_done();
        let (costed, cc) = build_with(&mons, Pass::Costs).expect("factored");
        let w1 = crate::Context::work_done();
        let (bounded, bc) = build_with(&mons, Pass::Bounded).expect("factored");
        let w2 = crate::Context::work_done();
        let (full, uc) = build_with(&mons, Pass::Trees).expect("factored");
        assert_eq!(cc, uc, "{what}");
        assert_eq!(bc, uc, "{what}");
        let (costed, bounded, full) = (
            costed.to_expr(&ctx),
            bounded.to_expr(&ctx),
            full.to_expr(&ctx),
        );
        assert_eq!(costed, full, "{what}");
        assert_eq!(bounded, full, "{what}");
        assert_eq!(bounded.to_scalar(), *p, "{what}");
        Some((taken, w1 - w0, w2 - w1))
    }

    /// The costs found without the trees, with and without the bound, choose what building
    /// every candidate chose: the same expression (and so the same cost), equal to the
    /// polynomial. The bound changes only the work: it saves some on many inputs (on others a
    /// group cut under a tight bound is searched again under a looser one).
    #[test]
    fn candidate_costs_without_trees_choose_as_the_built_candidates() {
        let (mut taken, mut tried, mut saved) = (0, 0, 0);
        let polys = (0..60)
            .map(|seed| (poly(seed), format!("seed {seed}")))
            .chain((0..60).map(|seed| (poly_many(seed), format!("many, seed {seed}"))));
        for (p, what) in polys {
            let Some((t, costed, bounded)) = three_passes(&p, &what) else {
                continue;
            };
            tried += 1;
            taken += usize::from(t);
            saved += usize::from(bounded < costed);
        }
        assert!(
            taken >= 100,
            "the cost path was taken {taken} times of {tried}"
        );
        assert!(saved >= 10, "the bound saved work {saved} times of {tried}");
    }

    /// A pseudo-random multilinear polynomial, as a chain's entries are in the cosines and
    /// sines of its joints: a product of two to four sums, each over symbols of its own (one
    /// or two of them a term), plus a few products of two symbols of different sums.
    fn poly_multilinear(seed: u64) -> Scalar {
        let mut next = crate::testing::xorshift_below(seed.wrapping_mul(0x5851_f42d_4c95_7f2d) | 1);
        let sym = |link: u64, k: u64| Scalar::sym(&format!("s{link}_{k}"));
        let mut p = Scalar::int(1);
        let links = 2 + next(3);
        for link in 0..links {
            let mut s = Scalar::int(0);
            for _ in 0..2 + next(3) {
                let c = [1, -1, 1, -1, 2, -3][next(6) as usize];
                let (a, b) = (next(5), next(5));
                let mut t = Scalar::int(c) * sym(link, a);
                if next(2) == 0 && b != a {
                    t = t * sym(link, b);
                }
                s = s + t;
            }
            p = p * s;
        }
        for _ in 0..next(4) {
            let c = next(9) as i64 - 4;
            p = p + Scalar::int(c) * sym(0, next(5)) * sym(1, next(5));
        }
        p
    }

    /// A multilinear root takes its monomials as bit sets (`costs.rs`'s `Masks`), in the
    /// cost pass and in building the winner's tree (its hash, candidates and splits), and
    /// the result is the one of the symbol lists: the same expression as building every
    /// candidate on the lists ([`Pass::Trees`] has no bit sets).
    #[test]
    fn multilinear_roots_choose_on_bit_sets_as_the_built_candidates() {
        let mut masked = 0;
        for seed in 0..60 {
            let p = poly_multilinear(seed);
            let (_, mons) = whole_modes(&p);
            masked += usize::from(costs::Costs::for_mons(&mons).is_some_and(|c| c.masked()));
            three_passes(&p, &format!("multilinear, seed {seed}"));
        }
        assert!(masked >= 50, "bit sets taken {masked} times of 60");
    }

    /// The additions and subtractions of `e`: `k - 1` for each sum of `k` terms.
    fn additions(e: &Expr) -> usize {
        match e {
            Expr::Add(v) => v.len() - 1 + v.iter().map(additions).sum::<usize>(),
            Expr::Mul(v) => v.iter().map(additions).sum(),
            Expr::Neg(x) | Expr::Pow(x, _) => additions(x),
            _ => 0,
        }
    }

    /// Factoring keeps each monomial one summand: the form built for `m` monomials (integer
    /// polynomials; trigonometric ones split into single angles) has exactly `m - 1` additions
    /// and subtractions, counted on its tree, so [`summands_lower_bound`] holds, and
    /// [`cost_lower_bound`] with it; on polynomials of many monomials in a few symbols it is
    /// the larger part of that bound.
    #[test]
    fn each_monomial_stays_one_summand() {
        let (a, b, l) = (Scalar::sym("a"), Scalar::sym("b"), Scalar::sym("l"));
        let trig = (1..5).map(|k| {
            let s = a.clone().cos() + l.clone() * b.clone().sin() + Scalar::int(1);
            let t = (a.clone() + b.clone()).cos() * Scalar::sym("d") - Scalar::int(2);
            s.pow(k) * t
        });
        let (mut scalars, mut by_summands) = (0, 0);
        for p in (0..30)
            .map(poly)
            .chain((0..30).map(poly_many))
            .chain((0..30).map(poly_multilinear))
            .chain(trig)
        {
            let (ctx, mons) = crate::closed::mon::split_modes(&p);
            if mons.is_empty() {
                continue;
            }
            let (e, c) = build(&mons).expect("factored");
            let e = e.to_expr(&ctx);
            assert_eq!(e.to_scalar(), p);
            assert_eq!(additions(&e), mons.len() - 1, "{p}");
            let (lower, summands) = (cost_lower_bound(&mons), summands_lower_bound(&mons));
            assert!(
                c >= lower && lower >= summands,
                "{p}: {c:?} {lower:?} {summands:?}"
            );
            scalars += 1;
            // More monomials than distinct atoms and symbols (`lower.calls` counts the atoms).
            let mut syms: Vec<u32> = mons
                .iter()
                .flat_map(|m| m.syms.iter().map(|s| s.0))
                .collect();
            syms.sort_unstable();
            syms.dedup();
            by_summands += usize::from(mons.len() > lower.calls + syms.len());
        }
        assert!(scalars >= 90, "{scalars} scalars");
        assert!(
            by_summands >= 30,
            "the summands bound the larger {by_summands} times"
        );
    }

    /// [`mul`]'s shortcut for two factors that are neither products, negations nor one makes
    /// the product its general path makes, on every pair of such leaves and sums (both
    /// orders): the same expression and cost.
    #[test]
    fn two_plain_factors_multiply_as_the_general_path() {
        let p = Scalar::sym("x") * Scalar::sym("y").cos() + Scalar::sym("z").sin();
        let (ctx, mons) = whole_modes(&p);
        let (sum, _) = build(&mons).expect("factored");
        let trig = mons
            .iter()
            .find_map(|m| m.atoms.first().copied())
            .expect("an atom");
        let plain = [
            E::Num(Q::new(-3, 1)),
            E::Num(Q::ZERO),
            E::Sqrt(3),
            E::Sym(0),
            E::Pow(0, 2),
            E::Trig(trig),
            sum,
        ];
        let mut pairs = 0;
        for a in &plain {
            for b in &plain {
                let (fast, general) = (mul(a.clone(), b.clone()), mul_flat(a.clone(), b.clone()));
                assert_eq!(fast.cost(), general.cost());
                assert_eq!(fast.to_expr(&ctx), general.to_expr(&ctx));
                pairs += 1;
            }
        }
        assert_eq!(pairs, 49);
    }

    /// Sums of products of cosines and sines with radicals and fractions (a chain with 60
    /// degree twists has such entries) factor back to themselves: the path the cost pass
    /// does not take (candidates built unless their floor rules them out, plain sums met again taken from the memo, the
    /// quotients' lengths counted from the divisor, checked against the walk in debug builds).
    #[test]
    fn trigonometric_sums_with_radicals_factor_back_to_themselves() {
        let (a, b, c) = (Scalar::sym("a"), Scalar::sym("b"), Scalar::sym("c"));
        let half = || Scalar::rational(num_rational::BigRational::new(1.into(), 2.into()));
        let half_root3 = Scalar::int(3).sqrt() * half();
        let mut checked = 0;
        for k in 1..4u64 {
            let s = a.clone().cos() * half_root3.clone() + b.clone().sin() * half();
            let t = c.clone().cos() * Scalar::sym("d") - a.clone().sin() * half_root3.clone();
            let p = s.pow(k) * t.clone() + b.clone().cos() * t.pow(2);
            let (ctx, mons) = crate::closed::mon::split_modes(&p);
            assert!(costs::Costs::for_mons(&mons).is_none(), "{p}");
            let (e, c) = build(&mons).expect("factored");
            assert_eq!(e.to_expr(&ctx).to_scalar(), p);
            assert!(c >= cost_lower_bound(&mons));
            checked += 1;
        }
        assert_eq!(checked, 3);
    }

    /// A pseudo-random sum of products of cosines and sines with radicals and fractions, as
    /// the entries of a chain with 60-degree twists are: a product of two to four sums, each
    /// of two to four terms `c cos(x)` or `c sin(x)` (`c` one of `1`, `-1`, `1/2`, `-1/2`,
    /// `sqrt(3)/2`, `-sqrt(3)/2`, `3/4`; `x` one of four angles), some times a length, plus a
    /// few such terms.
    fn poly_trig(seed: u64) -> Scalar {
        let mut next = crate::testing::xorshift_below(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
        let q =
            |n: i64, d: i64| Scalar::rational(num_rational::BigRational::new(n.into(), d.into()));
        let root3 = Scalar::int(3).sqrt();
        let angles = ["a", "b", "c", "d"];
        let term = |next: &mut dyn FnMut(u64) -> u64| {
            let c = match next(7) {
                0 => Scalar::int(1),
                1 => Scalar::int(-1),
                2 => q(1, 2),
                3 => q(-1, 2),
                4 => root3.clone() * q(1, 2),
                5 => root3.clone() * q(-1, 2),
                _ => q(3, 4),
            };
            let x = Scalar::sym(angles[next(4) as usize]);
            let t = c * if next(2) == 0 { x.cos() } else { x.sin() };
            match next(4) {
                0 => t * Scalar::sym("l1"),
                1 => t * Scalar::sym("l2"),
                _ => t,
            }
        };
        let mut p = product_of_sums(&mut next, &term);
        for _ in 0..next(3) {
            p = p + term(&mut next);
        }
        p
    }

    /// Where candidates are built (trigonometric sums with radicals and fractions), the search
    /// that skips a candidate whose lower bound is not below the best so far chooses what the
    /// search building every candidate chooses: the same expression and cost, equal to the
    /// sum; at the root every candidate's bound is at most its built cost; and the skips save
    /// work on many sums.
    #[test]
    fn candidates_skipped_by_their_floor_choose_as_the_built_candidates() {
        let (mut tried, mut saved, mut floors) = (0, 0, 0);
        for seed in 0..80 {
            let p = poly_trig(seed);
            let (ctx, mons) = crate::closed::mon::split_modes(&p);
            if mons.len() < 2 {
                continue;
            }
            assert!(costs::Costs::for_mons(&mons).is_none(), "{p}");
            let _entered = crate::Context::default().enter();
            let w0 = crate::Context::work_done();
            let (all, ac) = build_with(&mons, Pass::Trees).expect("factored");
            let w1 = crate::Context::work_done();
            let (floored, fc) = build_with(&mons, Pass::Bounded).expect("factored");
            let w2 = crate::Context::work_done();
            assert_eq!(fc, ac, "seed {seed}");
            let floored = floored.to_expr(&ctx);
            assert_eq!(floored, all.to_expr(&ctx), "seed {seed}");
            assert_eq!(floored.to_scalar(), p, "seed {seed}");
            tried += 1;
            saved += usize::from(w2 - w1 < w1 - w0);
            // Each candidate of the root: its bound against its tree.
            let mut s = search(&mons, Pass::Trees);
            let group = root_group(&mons);
            for f in s.candidates(group.iter().map(|(i, _)| *i), BRANCH) {
                let floor = s.split_floor(&group, f).cost;
                let c = s.split_on(&group, f, 0).cost();
                assert!(
                    floor.ops <= c.ops && floor.calls <= c.calls,
                    "seed {seed}: {floor:?} {c:?}"
                );
                floors += 1;
            }
        }
        assert!(tried >= 75, "{tried} sums");
        assert!(floors >= 200, "{floors} bounds checked");
        assert!(
            saved >= 10,
            "the floors saved work {saved} times of {tried}"
        );
    }

    /// A split searched under a best cost so far ([`Search::split_below`]) is the split
    /// [`Search::split_on`] builds where it returns one, and returns none only where that
    /// split costs at least the best: checked for every candidate of the root of 80 random
    /// sums against bests around its built cost; the bound after the factored part skips
    /// splits the first bound let through.
    #[test]
    fn splits_below_a_best_cost_are_the_built_splits() {
        let (mut checked, mut second) = (0, 0);
        for seed in 0..80 {
            let p = poly_trig(seed);
            let (ctx, mons) = crate::closed::mon::split_modes(&p);
            if mons.len() < 2 {
                continue;
            }
            let _entered = crate::Context::default().enter();
            let mut s = search(&mons, Pass::Bounded);
            let group = root_group(&mons);
            for f in s.candidates(group.iter().map(|(i, _)| *i), BRANCH) {
                let built = s.split_on(&group, f, 0);
                let c = built.cost();
                let first = s.split_floor(&group, f).cost;
                for ops in c.ops.saturating_sub(4)..=c.ops + 1 {
                    for calls in c.calls.saturating_sub(1)..=c.calls + 1 {
                        let best = Cost { ops, calls };
                        match s.split_below(&group, f, 0, best) {
                            Some(e) => {
                                assert_eq!(e.to_expr(&ctx), built.to_expr(&ctx), "seed {seed}")
                            }
                            None => {
                                assert!(c >= best, "seed {seed}: {c:?} skipped under {best:?}");
                                second += usize::from(first < best);
                            }
                        }
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked >= 2000, "{checked} splits checked");
        assert!(second >= 50, "the second bound skipped {second} splits");
    }

    /// The entries of random chains of two to four joints in the shape of a DH transform, in
    /// plain symbols (`c1`, `s1` for a joint's cosine and sine, `ca1`, `sa1` for its twist's,
    /// `a1`, `d1`): multilinear sums like the symbolic 6R's recurrence entries, some
    /// parameters zero or a right angle.
    fn chain_entries(seed: u64) -> Vec<Scalar> {
        let mut next = crate::testing::xorshift_below(seed.wrapping_mul(0x2545_f491_4f6c_dd1d) | 1);
        let z = || Scalar::int(0);
        let mut m: Vec<Vec<Scalar>> = (0..4)
            .map(|r| (0..4).map(|c| Scalar::int(i64::from(r == c))).collect())
            .collect();
        for j in 1..=2 + next(3) {
            let v = |n: &str| Scalar::sym(&format!("{n}{j}"));
            let (c, s) = (v("c"), v("s"));
            let (ca, sa) = match next(4) {
                0 => (Scalar::int(1), z()),
                1 => (z(), Scalar::int(1)),
                _ => (v("ca"), v("sa")),
            };
            let a = if next(3) == 0 { z() } else { v("a") };
            let d = if next(3) == 0 { z() } else { v("d") };
            let t = [
                [
                    c.clone(),
                    -(s.clone() * ca.clone()),
                    s.clone() * sa.clone(),
                    a.clone() * c.clone(),
                ],
                [
                    s.clone(),
                    c.clone() * ca.clone(),
                    -(c.clone() * sa.clone()),
                    a * s,
                ],
                [z(), sa, ca, d],
                [z(), z(), z(), Scalar::int(1)],
            ];
            m = (0..4)
                .map(|r| {
                    (0..4)
                        .map(|k| (0..4).fold(z(), |acc, i| acc + m[r][i].clone() * t[i][k].clone()))
                        .collect()
                })
                .collect();
        }
        m.into_iter().take(3).flatten().collect()
    }

    /// The bounded search of `mons` (as [`build`]), a multilinear root's parts handed their
    /// visit's pass by their split (`derived`, `costs.rs`'s `Pre`) or each visit passing over
    /// its group (the route before it), under `budget`: the expression or the budget error,
    /// with the work charged.
    fn derived_or_counted(
        mons: &[Mon],
        ctx: &Ctx,
        derived: bool,
        budget: Option<u64>,
    ) -> (Result<Expr, String>, u64) {
        let mut c = crate::Context::default();
        if let Some(b) = budget {
            c = c.with_work_budget(b);
        }
        let _entered = c.enter();
        let w0 = crate::Context::work_done();
        let mut s = search(mons, Pass::Bounded);
        if let Some(c) = s.costs.as_mut() {
            c.derived = derived;
        }
        let e = s.build_at(&root_group(mons), 0);
        let out = match s.spent {
            Some(err) => Err(format!("{err:?}")),
            None => Ok(e.to_expr(ctx)),
        };
        (out, crate::Context::work_done() - w0)
    }

    /// A multilinear root's parts take their value, work and counts from the split that made
    /// them (`costs.rs`'s `Pre`): the same expressions and the same work charged as each
    /// visit's own pass over its group, on random multilinear sums and the entries of random
    /// chains, and at budgets that run out in the search the same budget errors after the
    /// same work.
    #[test]
    fn parts_handed_their_pass_choose_and_charge_as_each_visit_counting() {
        let (mut masked, mut compared, mut ran_out, mut wide) = (0, 0, 0, 0);
        // Coefficients past a machine word (a monomial's work counts its coefficient's
        // words; low words shared, so that memo values collide), negations and contents
        // (found by the reviewer's scratch test).
        let two64 = Scalar::int(1 << 32) * Scalar::int(1 << 32);
        let words = (0..6).flat_map(|i| {
            let (p, q) = (poly_multilinear(100 + i), poly_multilinear(200 + i));
            [
                p.clone() * &two64 + &q,
                p.clone() * (two64.clone() * Scalar::int(3) + Scalar::int(5))
                    + q.clone() * &two64 * Scalar::int(7),
                p * Scalar::int(-6) - q * Scalar::int(12),
            ]
        });
        let polys = (0..40)
            .map(poly_multilinear)
            .chain((0..12).flat_map(chain_entries))
            .chain(words);
        for (k, p) in polys.enumerate() {
            let (ctx, mons) = whole_modes(&p);
            if mons.len() < 2 || !costs::Costs::for_mons(&mons).is_some_and(|c| c.masked()) {
                continue;
            }
            masked += 1;
            wide += usize::from(mons.iter().any(|m| m.q.words() > 0));
            let (old, work) = derived_or_counted(&mons, &ctx, false, None);
            let new = derived_or_counted(&mons, &ctx, true, None);
            assert_eq!(new, (old.clone(), work), "{k}: {p}");
            assert_eq!(old.expect("factored").to_scalar(), p, "{k}");
            compared += 1;
            if k % 4 == 0 {
                for budget in [work / 3, work / 2, work - work / 8, work - 1] {
                    let old = derived_or_counted(&mons, &ctx, false, Some(budget));
                    let new = derived_or_counted(&mons, &ctx, true, Some(budget));
                    ran_out += usize::from(old.0.is_err());
                    assert_eq!(new, old, "{k} at {budget}: {p}");
                }
            }
        }
        assert!(
            masked >= 120 && wide >= 8,
            "{masked} multilinear roots, {wide} wide"
        );
        assert!(
            compared >= 120 && ran_out >= 40,
            "{compared} compared, {ran_out} ran out"
        );
    }

    /// Past 126 bits a coefficient is not a machine integer: the candidates are built, not
    /// costed without their trees.
    #[test]
    fn wide_coefficients_take_the_built_candidates() {
        let p = (Scalar::sym("x") + Scalar::sym("y") + Scalar::sym("z")).pow(90);
        let (_, mons) = whole_modes(&p);
        assert!(costs::Costs::for_mons(&mons).is_none());
        let p = (Scalar::sym("x") + Scalar::sym("y") + Scalar::sym("z")).pow(80);
        let (_, mons) = whole_modes(&p);
        assert!(costs::Costs::for_mons(&mons).is_some());
    }
}
