//! A run of splits on one factor, below the branching levels, without a group per level.
//!
//! Below the branching levels the search pulls out the most frequent factor `f`, and in the
//! group of the monomials holding it (divided by it) `f` is often the most frequent factor
//! again: `(x + y + z)^60` nests `x (x (x (...) + ...) + ...)` sixty levels deep. Level by
//! level, [`Search::split_on`] copied, hashed, counted and divided the whole inner group, a
//! cost quadratic in the size of the sum (cubic in the exponent). The groups of such a run
//! are nested: the monomials whose power of `f` is at least the `j`-th distinct power. So
//! [`Search::run`] sorts the monomials once by their power of `f` into buckets and finds each
//! level's sign, content, radical and most frequent factor from the buckets above it (suffix
//! gcds and counts); only the monomials left at each level (one bucket, the rest beside the
//! factored group) are materialized and searched. The result is the expression the level by
//! level search built: every step it took is taken, in the same order, from the same data.

use super::{factor_expr, mul, multiplicity, Factor, Search, E};
use crate::closed::mon::{content_of, div_q};
use crate::scalar::Q;
use smallvec::SmallVec;
use std::rc::Rc;

/// The steps a level of a run takes before it splits (those of [`Search::build_at`]).
#[derive(Default)]
struct Steps {
    /// The group was all negative: the level is a negation.
    neg: bool,
    /// The content pulled out, when not one.
    content: Option<Q>,
    /// The common radical pulled out, when not one.
    rad: Option<u64>,
}

/// What the buckets above a level (its group) have in common.
struct Level {
    /// The number of monomials.
    size: usize,
    /// The first position (in the group the run started from) of a monomial of the group.
    first: u32,
    /// Whether every coefficient is negative, and whether every one is positive.
    all_neg: bool,
    all_pos: bool,
    /// The content of the coefficients (as the run's first group has them).
    content: Q,
    /// The radicand every monomial shares, if they share one.
    rad: Option<u64>,
    /// The most frequent factor of the group, if one occurs twice.
    best: Option<usize>,
}

/// Runs over at most this many distinct powers (0 among them) take the level by level path.
pub(super) const SHORT_RUN: usize = 3;

impl Search<'_> {
    /// The split of `g0` on `f` (at a level that does not branch), and of the group holding
    /// `f` on `f` again while `f` stays its most frequent factor; equal to
    /// [`Search::split_on`] followed by [`Search::build_at`] on each group it makes.
    pub(super) fn run(&mut self, g0: &[(u32, Q)], f: Factor, depth: usize) -> E {
        if self.masks().is_some() {
            // A multilinear root's powers are 0 and 1: its runs are short.
            return self.split_on(g0, f, depth);
        }
        let fi = self.counts.index(f);
        let base = self.div[fi];
        let (ks, buckets) = self.buckets(g0, f, base);
        // A run of at most two levels gains nothing from the buckets, and the level by level
        // search keeps each level's group in the memo (measured: the symbolic 6R's factors,
        // mostly powers 0, 1, 2, cost 8% more through the run).
        if ks.len() <= SHORT_RUN {
            return self.split_on(g0, f, depth);
        }
        let levels = self.levels(g0, f, &ks, &buckets);
        if self.spent.is_some() {
            return self.plain_sum(g0);
        }
        let entry_rad_off = self.rad_off;
        // Down the run: each level's steps from its bucket data, until a level has one
        // monomial or another most frequent factor.
        let (mut neg, mut divisor) = (false, Q::ONE);
        let mut states: Vec<(Steps, bool, Q, bool)> = Vec::new();
        let mut b = 1;
        let inner = loop {
            let l = &levels[b];
            self.div[fi] = base + ks[b];
            if l.size == 1 {
                let (i, q) = &g0[l.first as usize];
                break self.mon_expr(*i, &cur(q, neg, &divisor));
            }
            let mut steps = Steps::default();
            if (neg && l.all_pos) || (!neg && l.all_neg) {
                steps.neg = true;
                neg = !neg;
            }
            if l.content != divisor {
                steps.content = Some(div_q(&l.content, &divisor));
                divisor = l.content.clone();
            }
            if let Some(r) = l.rad.filter(|&r| r != 1 && !self.rad_off) {
                steps.rad = Some(r);
                self.rad_off = true;
            }
            if l.best != Some(fi) {
                // The run ends: the group as the level by level search had it (in the order of
                // the first group), searched.
                let mut at: Vec<u32> = buckets.from(b).to_vec();
                at.sort_unstable();
                let group: Vec<(u32, Q)> = at
                    .iter()
                    .map(|&p| &g0[p as usize])
                    .map(|(i, q)| (*i, cur(q, neg, &divisor)))
                    .collect();
                self.path.push((fi, ks[b]));
                let e = self.searched(&group, depth);
                self.path.pop();
                break wrap(e, steps);
            }
            states.push((steps, neg, divisor.clone(), self.rad_off));
            b += 1;
        };
        // Up the run: each level's factored group beside its bucket (the monomials whose
        // power of `f` is exactly the level's), then the level's steps around it.
        let mut e = inner;
        for lb in (0..b).rev() {
            let (steps, neg, divisor, rad_off) = match lb {
                0 => (Steps::default(), false, Q::ONE, entry_rad_off),
                _ => states
                    .pop()
                    .unwrap_or_else(|| (Steps::default(), false, Q::ONE, entry_rad_off)),
            };
            let factored = mul(factor_expr(f, ks[lb + 1] - ks[lb]), e);
            let rest: SmallVec<[(u32, Q); 4]> = buckets
                .get(lb)
                .iter()
                .map(|&p| &g0[p as usize])
                .map(|(i, q)| (*i, cur(q, neg, &divisor)))
                .collect();
            let n_before = buckets
                .get(lb)
                .partition_point(|&p| p < levels[lb + 1].first);
            self.div[fi] = base + ks[lb];
            self.rad_off = rad_off;
            self.path.push((fi, ks[lb]));
            let level_e = self.beside(factored, &rest, n_before, depth);
            self.path.pop();
            e = wrap(level_e, steps);
        }
        self.div[fi] = base;
        self.rad_off = entry_rad_off;
        e
    }

    /// `factored` among the terms of `rest` searched, where its first monomial stood (the
    /// splice of [`Search::split_on`]).
    pub(super) fn beside(
        &mut self,
        factored: E,
        rest: &[(u32, Q)],
        n_before: usize,
        depth: usize,
    ) -> E {
        if rest.is_empty() {
            return factored;
        }
        let rest_expr = self.build_at(rest, depth + 1);
        // The rest's terms are copied once, into the sum they join.
        let rest_terms: &[E] = match &rest_expr {
            E::Add(v, _) => v,
            e => std::slice::from_ref(e),
        };
        let at = if rest_terms.len() == rest.len() {
            n_before.min(rest_terms.len())
        } else {
            0
        };
        let (before, after) = rest_terms.split_at(at);
        // Collected from an iterator of known length: the node is allocated once.
        let terms: Rc<[E]> = before
            .iter()
            .cloned()
            .chain(std::iter::once(factored))
            .chain(after.iter().cloned())
            .collect();
        E::sum_of(terms)
    }

    /// The distinct powers of `f` in `g0` (divided by `f^base`), 0 first, and the positions of
    /// the monomials of each, in order.
    fn buckets(&self, g0: &[(u32, Q)], f: Factor, base: u32) -> (Vec<u32>, Buckets) {
        let mults: Vec<u32> = g0
            .iter()
            .map(|(i, _)| multiplicity(&self.root[*i as usize], f) - base)
            .collect();
        let mut ks = mults.clone();
        ks.push(0);
        ks.sort_unstable();
        ks.dedup();
        let buckets = Buckets::sorted(&mults, &ks);
        (ks, buckets)
    }

    /// Each level's data from the buckets above it, top down (a last level past the buckets,
    /// empty); charged to the work budget: one unit per monomial and factor read,
    /// [`super::BIG_WORD_UNITS`] per word of a coefficient or content, one per factor compared
    /// at each level.
    fn levels(&mut self, g0: &[(u32, Q)], f: Factor, ks: &[u32], buckets: &Buckets) -> Vec<Level> {
        let fi = self.counts.index(f);
        let n = ks.len();
        let mut out: Vec<Level> = (0..=n).map(|_| Level::empty()).collect();
        let (root, div) = (self.root, &self.div);
        let sym_base = self.counts.sym_base;
        let mut counts = vec![0u32; self.counts.n.len()];
        let mut touched: Vec<usize> = Vec::new();
        let mut work = 0u64;
        for b in (1..n).rev() {
            let mut l = Level::empty();
            let mut rad: Option<Option<u64>> = None;
            for &p in buckets.get(b) {
                let (i, q) = &g0[p as usize];
                let m = &root[*i as usize];
                work += 1 + (m.syms.len() + m.atoms.len()) as u64;
                work += q.words() * super::BIG_WORD_UNITS;
                l.all_neg &= q.is_negative();
                l.all_pos &= !q.is_negative();
                rad = Some(match rad {
                    None => Some(m.rad),
                    Some(r) => r.filter(|&r| r == m.rad),
                });
                for (s, _) in super::quotient_syms(m, div, sym_base) {
                    let k = sym_base + s as usize;
                    if k != fi {
                        bump(&mut counts, &mut touched, k);
                    }
                }
                let mut last = None;
                for a in super::quotient_atoms(m, div) {
                    if last != Some(a) && a as usize != fi {
                        bump(&mut counts, &mut touched, a as usize);
                    }
                    last = Some(a);
                }
            }
            let bucket = buckets.get(b);
            l.size = bucket.len();
            l.first = bucket[0];
            l.rad = rad.flatten();
            l.content = content_of(bucket.iter().map(|&p| &g0[p as usize].1));
            let above = &out[b + 1];
            if above.size > 0 {
                l.size += above.size;
                l.first = l.first.min(above.first);
                l.all_neg &= above.all_neg;
                l.all_pos &= above.all_pos;
                l.rad = l.rad.filter(|r| above.rad == Some(*r));
                l.content = content_of([&l.content, &above.content].into_iter());
                work += l.content.words() * super::BIG_WORD_UNITS;
            }
            // The most frequent factor; `f` itself is in the monomials of the levels above.
            work += 1 + touched.len() as u64;
            l.best = most_frequent(above.size as u32, fi, &touched, &counts);
            out[b] = l;
        }
        self.charge_work(work);
        out
    }
}

/// The factor that occurs in most monomials of a level, at least twice: `f` itself
/// (`f_count` times, in the monomials of the levels above) or a factor `k` of `touched`
/// (`counts[k]` times); on a tie the lower index.
pub(super) fn most_frequent(
    f_count: u32,
    fi: usize,
    touched: &[usize],
    counts: &[u32],
) -> Option<usize> {
    let mut best: Option<(u32, usize)> = (f_count >= 2).then_some((f_count, fi));
    for &k in touched {
        let c = counts[k];
        if c >= 2 && best.is_none_or(|(bc, bk)| c > bc || (c == bc && k < bk)) {
            best = Some((c, k));
        }
    }
    best.map(|(_, k)| k)
}

/// The positions of a run's first group by their power of `f`: bucket `b` (power `ks[b]`) is
/// `order[start[b]..start[b + 1]]`, in increasing order.
pub(super) struct Buckets {
    order: Vec<u32>,
    start: Vec<usize>,
}

impl Buckets {
    /// Positions `0..mults.len()` by the bucket of their power `mults[p]` among `ks` (sorted,
    /// distinct, holding every power): a counting sort, stable (positions stay in order within
    /// each), into one vector: a vector per bucket was an allocation per monomial in a run of
    /// single ones.
    pub(super) fn sorted(mults: &[u32], ks: &[u32]) -> Buckets {
        let of: Vec<usize> = mults
            .iter()
            .map(|m| ks.binary_search(m).unwrap_or(0))
            .collect();
        let mut start = vec![0usize; ks.len() + 1];
        for &b in &of {
            start[b + 1] += 1;
        }
        for b in 0..ks.len() {
            start[b + 1] += start[b];
        }
        let mut next = start.clone();
        let mut order = vec![0u32; of.len()];
        for (p, &b) in of.iter().enumerate() {
            order[next[b]] = p as u32;
            next[b] += 1;
        }
        Buckets { order, start }
    }

    pub(super) fn get(&self, b: usize) -> &[u32] {
        &self.order[self.start[b]..self.start[b + 1]]
    }

    /// Buckets `b` and up, one after another.
    pub(super) fn from(&self, b: usize) -> &[u32] {
        &self.order[self.start[b]..]
    }
}

impl Level {
    /// No monomial: what every level starts from, and the level past the last.
    fn empty() -> Level {
        Level {
            size: 0,
            first: u32::MAX,
            all_neg: true,
            all_pos: true,
            content: Q::ONE,
            rad: None,
            best: None,
        }
    }
}

/// A coefficient of the run's first group as a level has it: divided by the content pulled
/// out above, negated when the levels above negated it an odd number of times.
fn cur(q: &Q, neg: bool, divisor: &Q) -> Q {
    let q = if divisor.is_one() {
        q.clone()
    } else {
        div_q(q, divisor)
    };
    if neg {
        -q
    } else {
        q
    }
}

fn bump(counts: &mut [u32], touched: &mut Vec<usize>, k: usize) {
    if counts[k] == 0 {
        touched.push(k);
    }
    counts[k] += 1;
}

/// `e` inside a level's steps: the radical innermost, then the content, then the sign (the
/// order [`Search::build_at`] takes them in, each around the rest).
fn wrap(e: E, steps: Steps) -> E {
    let mut e = e;
    if let Some(r) = steps.rad {
        e = mul(E::Sqrt(r), e);
    }
    if let Some(g) = steps.content {
        e = mul(E::Num(g), e);
    }
    if steps.neg {
        e = E::Neg(Rc::new(e));
    }
    e
}
