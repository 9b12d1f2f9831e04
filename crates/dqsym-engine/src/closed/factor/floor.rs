//! A lower bound on the cost of a candidate of a branching level, found before it is built.
//!
//! Where `costs.rs` cannot cost a candidate without its tree (atoms, radicals, fractions: the
//! entries of a chain with 60-degree twists), [`Search::searched`] built every candidate and
//! kept the first of least cost. A candidate whose bound is not below the best cost so far
//! cannot win (it would need a lower cost; a tie keeps the earlier one), so it is not built;
//! nor is its rest where its factored part, built, makes the bound reach the best cost
//! ([`Search::split_below`]).
//!
//! The bound counts leaves. Every node of an [`E`] tree that has `j` children costs `j - 1`
//! operations (a sum, a product), a negation one or none, and a leaf costs what it reads: an
//! integer nothing, a fraction one division, `sqrt`, `cos` and `sin` one operation and one
//! call, `s^n` its `n - 1` multiplications. Over a tree, the children counted by the nodes
//! are every node but the root, so its operations are at least `leaves - 1` plus the leaves'
//! own costs: at least `W - 1` for its *weight* `W`, the sum over its leaves of one plus the
//! leaf's cost. A weight adds up over the parts a candidate joins: `f^k (inner) + rest` has
//! the weight of `f^k`, of the inner group's tree and of the rest's (a product or a sum
//! flattened into its parent keeps its leaves; a one is never a factor of these products:
//! the inner group has two distinct monomials at least). So `W(f^k) + W(inner) + W(rest) - 1`
//! is a lower bound of the candidate's operations, given lower bounds of the two groups'
//! weights ([`Search::floor`]), and the calls add up alike.
//!
//! The bound reads each monomial's quotient once per candidate, as the visit of the group
//! does, and its work is not charged to the budget: a deliberate leak, bounded but not by
//! the visit's charge. The crossing factors' count compares each power-one factor with the
//! groups found so far, quadratic in the distinct factors, and is made only for groups of at
//! most 64 monomials.
//!
//! [`E`]: super::E

use super::{
    lowest_power, quotient_atoms, quotient_syms, split_by, Atom, Factor, Mults, Search, E,
};
use crate::closed::expr::Cost;
use crate::scalar::Q;
use smallvec::SmallVec;

/// A lower bound of the weight (one plus the cost of each leaf, summed over the leaves) and
/// of the calls of a tree the search builds for a group.
#[derive(Clone, Copy, Default, Debug, PartialEq, Eq)]
pub(super) struct Floor {
    pub(super) weight: usize,
    pub(super) calls: usize,
}

impl Floor {
    fn add(self, o: Floor) -> Floor {
        Floor {
            weight: self.weight + o.weight,
            calls: self.calls + o.calls,
        }
    }
}

/// Whether `q` is `1` or `-1`: a unit needs no number leaf.
fn unit(q: &Q) -> bool {
    match q {
        Q::S(n, d) => *d == 1 && n.unsigned_abs() == 1,
        Q::B(b) => {
            num_traits::Signed::abs(&**b) == num_rational::BigRational::from_integer(1.into())
        }
    }
}

/// Whether `q` is an integer: a fraction needs a leaf that is one.
fn integer(q: &Q) -> bool {
    match q {
        Q::S(_, d) => *d == 1,
        Q::B(b) => b.is_integer(),
    }
}

impl Search<'_> {
    /// A lower bound of the weight and calls of the tree built for `group` (monomials of the
    /// current group, divided by the current divisor), from what the tree must hold:
    /// - each monomial is one summand of it (the factoring keeps the monomials apart), and a
    ///   sum of `n` summands has `n - 1` additions, so `n` leaves at least;
    /// - a quotient holding atom `a` to the power `p` is the product of the factors on its
    ///   path from the root, and an atom is a leaf of power one: `p` leaves `a` on one path,
    ///   each of weight two (one operation, one call);
    /// - a quotient holding symbol `s` to the power `p`: leaves `s^e` on its path whose powers
    ///   add up to `p`, so of weight `p` (one leaf at least);
    /// - each radicand (not pulled out above) a leaf `sqrt(r)` of weight two, one call;
    /// - a coefficient other than `1` or `-1`: a number leaf, and a fraction: a fraction leaf
    ///   (a product of integers is an integer), of weight two.
    ///
    /// The leaves of distinct factors are distinct: their weight adds; the leaf count is at
    /// least the larger of the summands and these leaves.
    pub(super) fn floor<'g>(&mut self, group: impl Iterator<Item = &'g (u32, Q)>) -> Floor {
        let (root, div, base) = (self.root, &self.div, self.counts.sym_base);
        let (pow, touched) = (&mut self.floor_pow, &mut self.floor_touched);
        let mut n = 0usize;
        let (mut number, mut fraction) = (false, false);
        let mut rads: SmallVec<[u64; 4]> = SmallVec::new();
        let bits = &mut self.floor_bits;
        for (i, q) in group {
            let bit = if n < 64 { 1u64 << n } else { 0 };
            n += 1;
            let m = &root[*i as usize];
            for (s, e) in quotient_syms(m, div, base) {
                raise(pow, touched, base + s as usize, e);
                bits[base + s as usize] |= bit;
            }
            let mut run: (Option<Atom>, u32) = (None, 0);
            for a in quotient_atoms(m, div) {
                if run.0 == Some(a) {
                    run.1 += 1;
                } else {
                    run = (Some(a), 1);
                }
                raise(pow, touched, a as usize, run.1);
                bits[a as usize] |= bit;
            }
            let r = if self.rad_off { 1 } else { m.rad };
            if r != 1 && !rads.contains(&r) {
                rads.push(r);
            }
            number |= !unit(q);
            fraction |= !integer(q);
        }
        // Leaves required, and their weight beyond one each.
        let (mut leaves, mut extra, mut calls) = (0usize, 0usize, 0usize);
        if n <= 64 {
            let more = crossing_leaves(touched, pow, bits, base, n);
            leaves += more.atoms + more.syms;
            extra += more.atoms;
            calls += more.atoms;
        }
        for &k in touched.iter() {
            let p = pow[k] as usize;
            pow[k] = 0;
            bits[k] = 0;
            if k < base {
                leaves += p;
                extra += p;
                calls += p;
            } else {
                leaves += 1;
                extra += p - 1;
            }
        }
        touched.clear();
        leaves += rads.len() + usize::from(number);
        extra += rads.len() + usize::from(fraction);
        calls += rads.len();
        Floor {
            weight: leaves.max(n) + extra,
            calls,
        }
    }

    /// A lower bound of the cost of [`Search::split_on`]`(group, f, _)`, without building it
    /// (module doc): the weights of `f^k`, of the monomials holding `f^k` divided by it and of
    /// the others, less one; with the powers of `f` and the others' floor.
    pub(super) fn split_floor(&mut self, group: &[(u32, Q)], f: Factor) -> SplitFloor {
        let fi = self.counts.index(f);
        let mults: Mults = self.powers(group.iter().map(|(i, _)| *i), f);
        let k = lowest_power(&mults);
        let rest = self.floor(
            group
                .iter()
                .zip(&mults)
                .filter(|(_, &n)| n < k)
                .map(|(m, _)| m),
        );
        self.div[fi] += k;
        let inner = self.floor(
            group
                .iter()
                .zip(&mults)
                .filter(|(_, &n)| n >= k)
                .map(|(m, _)| m),
        );
        self.div[fi] -= k;
        let fk = match f {
            Factor::Atom(_) => Floor {
                weight: 2 * k as usize,
                calls: k as usize,
            },
            Factor::Sym(_) => Floor {
                weight: k as usize,
                calls: 0,
            },
        };
        let w = fk.add(inner).add(rest);
        SplitFloor {
            cost: Cost {
                ops: w.weight - 1,
                calls: w.calls,
            },
            rest,
            mults,
        }
    }

    /// [`Search::split_on`]`(group, f, depth)` where its cost may be below `best`; `None`,
    /// having built at most its factored part, where it cannot be.
    ///
    /// First the bound of [`Search::split_floor`]. Then, once the factored part `F` is
    /// built, a second one: the split is the sum of `F` and the rest's terms (the rest `R`'s
    /// own terms spliced in where `R` is a sum, else `R` itself), so it costs one addition
    /// joining them more than `F` and `R` cost as terms of a sum: `1 + cost_in_sum(F) +
    /// cost_in_sum(R)` operations (a sum's cost as a term is its cost). A term's cost is at
    /// least its weight less one (module doc: a negation, free as a term, is no leaf and has
    /// one child, so the count holds), and the rest's weight is at least its floor's: the
    /// split costs at least `cost_in_sum(F)` plus the rest's floor weight. Its calls are
    /// `F`'s and `R`'s, at least `F`'s plus the rest's floor calls. Both bounds hold, so their
    /// larger operations and larger calls do; a split at or above `best` is not chosen (the
    /// first of least cost is), so then its rest is not built.
    pub(super) fn split_below(
        &mut self,
        group: &[(u32, Q)],
        f: Factor,
        depth: usize,
        best: Cost,
    ) -> Option<E> {
        let SplitFloor { cost, rest, mults } = self.split_floor(group, f);
        if cost >= best {
            return None;
        }
        let split = split_by(group, &mults);
        let factored = self.factored(&split, f, depth);
        let bound = if split.rest.is_empty() {
            cost
        } else {
            let fc = factored.cost_in_sum();
            Cost {
                ops: cost.ops.max(fc.ops + rest.weight),
                calls: cost.calls.max(fc.calls + rest.calls),
            }
        };
        if bound >= best {
            return None;
        }
        let e = self.beside(factored, &split.rest, split.n_before, depth);
        debug_assert!(
            {
                let c = e.cost();
                c.ops >= bound.ops && c.calls >= bound.calls
            },
            "floor {bound:?} of {:?}",
            e.cost()
        );
        Some(e)
    }
}

/// [`Search::split_floor`]'s bound of a split, with the floor of its rest and each
/// monomial's power of the factor.
pub(super) struct SplitFloor {
    pub(super) cost: Cost,
    rest: Floor,
    mults: Mults,
}

/// Leaves beyond one per factor, of atoms and of symbols.
#[derive(Default)]
struct More {
    atoms: usize,
    syms: usize,
}

/// Leaves a tree needs beyond one per factor, from factors whose monomials cross.
///
/// A factor `a` of power one in every quotient holding it (`pow[a] == 1`) that is a single
/// leaf of the tree covers exactly the monomials holding it (`bits[a]`): those whose path
/// from the root passes through the product it is a factor of (a group's product, or one
/// monomial's own). The sets of monomials whose paths pass through a node are nested or
/// disjoint over the nodes of a tree; so of factors whose sets pairwise cross (meet, neither
/// holding the other), at most one is a single leaf, and each other one is two leaves at
/// least. The factors are partitioned greedily into such groups (each joins the first whose
/// members it all crosses); each group of `t` factors needs `t - 1` more leaves, one for each
/// member but the one excused, taken an atom where the group holds one (an atom weighs two
/// and calls once, a symbol weighs one), so the count is low in weight and in calls both.
///
/// A factor held by all `n` monomials or by one crosses no set (every set lies within the
/// first; a single monomial's set cannot both meet another and leave it): it would only
/// start a group of its own, which needs no leaf more and which no later factor joins, so it
/// is passed over.
fn crossing_leaves(touched: &[usize], pow: &[u32], bits: &[u64], base: usize, n: usize) -> More {
    let crosses = |a: u64, b: u64| a & b != 0 && a & !b != 0 && b & !a != 0;
    let all = if n >= 64 { u64::MAX } else { (1u64 << n) - 1 };
    // Each group: its members' sets, and how many of them are atoms.
    let mut groups: SmallVec<[(SmallVec<[u64; 8]>, usize); 8]> = SmallVec::new();
    for &k in touched {
        if pow[k] != 1 || bits[k] == all || bits[k].count_ones() == 1 {
            continue;
        }
        let atom = usize::from(k < base);
        let b = bits[k];
        match groups
            .iter_mut()
            .find(|(sets, _)| sets.iter().all(|&s| crosses(s, b)))
        {
            Some((sets, atoms)) => {
                sets.push(b);
                *atoms += atom;
            }
            None => groups.push((SmallVec::from_slice(&[b]), atom)),
        }
    }
    let mut more = More::default();
    for (sets, atoms) in &groups {
        let excused_atom = usize::from(*atoms > 0);
        more.atoms += atoms - excused_atom;
        more.syms += sets.len() - atoms - (1 - excused_atom);
    }
    more
}

/// `pow[k]` raised to at least `p`, `k` noted in `touched` when first raised.
fn raise(pow: &mut [u32], touched: &mut Vec<usize>, k: usize, p: u32) {
    if pow[k] == 0 {
        touched.push(k);
    }
    pow[k] = pow[k].max(p);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`crossing_leaves`] counts what the greedy partition of every factor of power one
    /// counts, the factors held by all monomials or by one among them: on 3,000 random
    /// families of sets over 2 to 64 monomials, with such factors mixed in.
    #[test]
    fn passing_over_factors_that_cross_nothing_keeps_the_count() {
        let mut next = crate::testing::xorshift_below(0x5eed_f100);
        let (mut passed_over, mut counted) = (0, 0);
        for _ in 0..3000 {
            let n = 2 + next(63) as usize;
            let all = if n == 64 { u64::MAX } else { (1u64 << n) - 1 };
            let factors = 1 + next(12) as usize;
            let base = next(factors as u64 + 1) as usize;
            let (mut pow, mut bits) = (vec![0u32; factors], vec![0u64; factors]);
            for k in 0..factors {
                pow[k] = 1 + u32::from(next(5) == 0);
                bits[k] = match next(6) {
                    0 => all,
                    1 => 1u64 << next(n as u64),
                    _ => (next(u64::MAX) ^ (next(u64::MAX) << 1)) & all,
                }
                .max(1);
                passed_over +=
                    usize::from(pow[k] == 1 && (bits[k] == all || bits[k].count_ones() == 1));
            }
            let touched: Vec<usize> = (0..factors).collect();
            let got = crossing_leaves(&touched, &pow, &bits, base, n);
            // The greedy partition of every factor of power one.
            let crosses = |a: u64, b: u64| a & b != 0 && a & !b != 0 && b & !a != 0;
            let mut groups: Vec<Vec<usize>> = Vec::new();
            for k in (0..factors).filter(|&k| pow[k] == 1) {
                match groups
                    .iter_mut()
                    .find(|g| g.iter().all(|&j| crosses(bits[j], bits[k])))
                {
                    Some(g) => g.push(k),
                    None => groups.push(vec![k]),
                }
            }
            let (mut atoms, mut syms) = (0, 0);
            for g in &groups {
                let a = g.iter().filter(|&&k| k < base).count();
                let excused = usize::from(a > 0);
                atoms += a - excused;
                syms += g.len() - a - (1 - excused);
            }
            assert_eq!((got.atoms, got.syms), (atoms, syms), "{bits:?} {pow:?}");
            counted += atoms + syms;
        }
        assert!(passed_over >= 3000, "{passed_over} factors passed over");
        assert!(counted >= 1000, "{counted} leaves counted");
    }
}
