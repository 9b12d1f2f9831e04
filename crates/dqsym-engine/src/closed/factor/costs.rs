//! The cost of a candidate of the branching levels without its tree, for sums of plain
//! monomials with integer coefficients (a polynomial such as `(x + y + z)^60`'s expansion).
//!
//! At each branching level [`Search::searched`] tries several factors and keeps the first of
//! least cost; every candidate used to be built in full and all but one thrown away (about
//! ten trees of `(x + y + z)^60`'s size). Here each candidate's exact [`Cost`] is computed by
//! the same steps the tree search takes (sign, content, split, the run of splits on one
//! factor, the splice of the rest), each step producing a [`Shape`] (the cost and the few
//! facts about a node its parent's cost depends on) instead of a node; only the winner is then
//! built. The coefficients are machine integers: a group of the search is always the root's
//! monomials divided by one common divisor `d` (see [`super::Group`]), so a group is its
//! indices and `d`, and a coefficient `coef[i] / d` is never formed. The costs equal the
//! built trees' (checked in debug builds for every winner), so the choice, and the output,
//! is the one building every candidate gave.
//!
//! Taken only when every monomial is a product of symbols without a radical or a
//! trigonometric atom and every coefficient an integer within 126 bits; otherwise the
//! candidates are built as before.
//!
//! A visit of a group passes over its monomials once for its value (the memo's key), the work
//! it charges and the counts of its quotients' symbols (its candidates). For a multilinear
//! root ([`Masks`]) the split that makes the group, which passes over the parent's monomials
//! anyway, makes both parts' passes ([`Pre`]): the value is a sum over the monomials and the
//! work too, so each part's is summed as its monomials are sorted into it, and only the
//! smaller part is counted, the other's counts being the parent's less those. The work
//! charged is the sum the visit's own pass made (the test of `factor.rs` that compares the
//! two routes checks it, with the choices, under budgets that run out); on the symbolic 6R
//! the pass was about a fifth of the cost search (`fk --jacobian`: 81.7 M instructions to
//! 78.1 M).
//!
//! # Branch and bound
//!
//! Here no cost has calls (there is no atom and no radical), so a cost is its count of
//! operations, and a candidate is taken only when it costs strictly less than the best one
//! before it. So each candidate is searched under a bound, the best cost so far (and the
//! bound its own group was searched under): a search that finds its cost will reach the bound
//! stops with `None`, which is exact for the choice, since such a candidate is never taken.
//! A group's bound is handed down to the searches of its parts, reduced by what the parts
//! still to come add at least; this is sound because costs only grow as a node is put
//! together from its parts ([`Shape`]'s arithmetic, `a` the cost standing alone, `s` as a
//! term of a sum, `c` without the negations around it, so `s >= c` and `a <= s + 1`):
//! - a negation around a node adds one to `a`, and so does the product with a content `g != 1`
//!   (two factors; a negation of the part moves out of the product and stays counted);
//! - `f^k` times the group holding `f` (at least two monomials, so not the number one) costs
//!   `a(inner) + k` alone and `s >= a(inner) + k - 1` as a term;
//! - that term beside a rest `r` costs `c(r) + s(factored) + 1 >= a(r) + s(factored)`
//!   (`c(r) >= a(r) - 1`, or `r`'s terms are spliced in and `c(r) = a(r)`);
//! - a sum of `n` distinct monomials costs at least its `n - 1` additions in every shape the
//!   search gives it (a split keeps them: `n1 - 1` inside the factored group, `n2 - 1` among
//!   the rest, one joining them), so a rest of `n` adds at least `n`;
//! - each level of a run ([`Search::c_run`]) is one of these steps, so every level costs at
//!   most the run.
//!
//! So a part whose cost reaches its reduced bound makes the whole reach the group's bound.
//! The memo keeps what a cut search learned (its cost is at least the bound, `AtLeast`), and
//! a search under a looser bound searches the group again. The candidates' costs differ by a
//! few operations and most ties are exact (the symbolic 6R's top levels: 319, 319, 320), so
//! a cut mostly comes late; on the symbolic 6R the bound saved about 2 M instructions of
//! the pass's ~80 M, and on random polynomials it can cost a little (groups searched again).
//! A bound from a group's leaves (its distinct symbols, on [`Masks`]) cut more groups of the
//! 6R but cost more than it saved (its report: 148.5 M instructions to 150.5 M): a group cut
//! under a tight bound is searched again under a looser one.

use super::run::{most_frequent, Buckets};
use super::{
    multiplicity, quotient_syms, Candidates, Factor, Search, BIG_WORD_UNITS, BRANCH, BRANCH_DEPTH,
};
use crate::closed::expr::Cost;
use crate::closed::mon::{FxMap, Mon};
use crate::scalar::q::gcd_u64;
use crate::scalar::{FxHasher, Q};
use num_traits::ToPrimitive;
use smallvec::SmallVec;
use std::hash::{Hash, Hasher};

/// The root's coefficients as machine integers, and the costs found for groups.
pub(super) struct Costs {
    coef: Vec<i128>,
    /// The budget units of a coefficient's words (as [`Q::words`] counts them, for the
    /// root's coefficient: an upper bound of a quotient's).
    words: Vec<u64>,
    memo: FxMap<u64, Vec<Known>>,
    /// Each monomial's symbols as a bit set, when the root is multilinear (see [`Masks`]).
    masks: Option<Masks>,
    /// Whether a candidate is cut once its cost reaches the best so far (see the module's
    /// doc); off only in the tests that compare the two.
    pub(super) bounded: bool,
    /// Whether a multilinear root's parts are handed what their visit needs ([`Pre`]) by the
    /// split that makes them; off only in the tests that compare it with the pass of each
    /// visit over its group.
    pub(super) derived: bool,
}

/// A cost found for a group: its depth class, divisor, the factors pulled out of it and its
/// monomials by index; what is known of its cost, and at a branching level the candidate
/// that won.
struct Known {
    level: usize,
    d: i128,
    div: DivKey,
    group: Vec<u32>,
    found: Bounded,
    winner: Option<Factor>,
}

/// The factors pulled out of a group: [`Masks::div`] for a multilinear root (each factor a
/// symbol to the first power, so the set is the key), [`Search::div_key`] otherwise. The mask
/// is kept with the search, where the list was collected and sorted from the path on every
/// [`Search::c_search`] (and turned back into a mask to compare quotients).
#[derive(PartialEq, Eq)]
enum DivKey {
    Mask(u64),
    List(Vec<(usize, u32)>),
}

/// What a search under a bound knows of a group's cost: its exact shape, or that its cost
/// (standing alone) is at least the bound, found without finishing the search.
#[derive(Clone, Copy, Debug)]
enum Bounded {
    Exact(Shape),
    AtLeast(usize),
}

/// The candidates of a group [`Search::c_search`] is given: the factors themselves, counted
/// already (in [`Search::c_build_at`]'s pass, in [`super::Counts`]), or to be counted.
#[derive(Clone, Copy)]
enum Cands<'f> {
    Given(&'f [Factor]),
    Counted,
    Count,
}

/// A part of a split: monomials by index, on the stack up to a size the 6R's groups keep.
type Part = SmallVec<[u32; 64]>;

/// No bound: every cost counts.
const NO_BOUND: usize = usize::MAX;

/// The cost of a group of `n` distinct monomials is at least `n - 1` operations: its
/// additions. Every step of the search keeps them: a split makes the group holding the factor
/// one term of the sum of the rest's terms (`n1 - 1` additions inside it, `n2 - 1` among the
/// rest, one to join them), and a sign, a content or a power only adds operations.
fn additions(n: usize) -> usize {
    n.saturating_sub(1)
}

/// What a node's parent needs of it: the cost of its core (the node without its leading
/// negations), the kind of the core and the number of negations around it.
#[derive(Clone, Copy, Debug)]
struct Shape {
    core: Cost,
    kind: Kind,
    negs: usize,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Kind {
    /// The number one (`E::Num(1)`), dropped from a product.
    One,
    Add,
    Mul,
    Other,
}

impl Shape {
    const ZERO: Shape = Shape {
        core: Cost { ops: 0, calls: 0 },
        kind: Kind::Other,
        negs: 0,
    };

    /// A leaf costing `ops` operations (a symbol, a power, an integer).
    fn leaf(ops: usize) -> Shape {
        Shape {
            core: Cost { ops, calls: 0 },
            kind: Kind::Other,
            negs: 0,
        }
    }

    /// An integer `E::Num`.
    fn int(n: i128) -> Shape {
        Shape {
            kind: if n == 1 { Kind::One } else { Kind::Other },
            ..Shape::ZERO
        }
    }

    /// [`super::E::cost`]: standing alone, each negation is an operation.
    fn alone(&self) -> Cost {
        Cost {
            ops: self.core.ops + self.negs,
            calls: self.core.calls,
        }
    }

    /// The cost as a term of a sum: the outermost negation is the subtraction's.
    fn in_sum(&self) -> Cost {
        Cost {
            ops: self.core.ops + self.negs.saturating_sub(1),
            calls: self.core.calls,
        }
    }

    fn neg(self) -> Shape {
        Shape {
            negs: self.negs + 1,
            ..self
        }
    }
}

fn add(a: Cost, b: Cost) -> Cost {
    Cost {
        ops: a.ops + b.ops,
        calls: a.calls + b.calls,
    }
}

/// [`super::mul`]'s node: products flattened (each keeps its cost, so it counts as one
/// factor), a leading negation of a factor pulled out of the product, a one dropped.
fn mul(parts: &[Shape]) -> Shape {
    let (mut flat, mut units, mut parity) = (0usize, 0usize, false);
    let mut cost = Cost::default();
    let mut single = Shape::ZERO;
    for p in parts {
        let e = if p.negs > 0 {
            parity = !parity;
            Shape {
                negs: p.negs - 1,
                ..*p
            }
        } else if p.kind == Kind::One {
            continue;
        } else {
            *p
        };
        flat += if e.negs == 0 && e.kind == Kind::Mul {
            2
        } else {
            1
        };
        units += 1;
        cost = add(cost, e.alone());
        single = e;
    }
    let e = match flat {
        0 => Shape::int(1),
        1 => single,
        _ => Shape {
            core: Cost {
                ops: cost.ops + units - 1,
                calls: cost.calls,
            },
            kind: Kind::Mul,
            negs: 0,
        },
    };
    if parity {
        e.neg()
    } else {
        e
    }
}

/// A sum of terms already shaped (`E::sum`).
fn sum(terms: impl Iterator<Item = Shape>) -> Shape {
    let (mut n, mut cost) = (0usize, Cost::default());
    for t in terms {
        n += 1;
        cost = add(cost, t.in_sum());
    }
    Shape {
        core: Cost {
            ops: cost.ops + n.saturating_sub(1),
            calls: cost.calls,
        },
        kind: Kind::Add,
        negs: 0,
    }
}

/// `f^k` (`super::factor_expr` of a symbol).
fn factor_shape(k: u32) -> Shape {
    Shape::leaf(k.saturating_sub(1) as usize)
}

/// The steps a level of a run takes before it splits (`run::Steps`, without a radical).
#[derive(Default, Clone, Copy)]
struct Steps {
    neg: bool,
    content: Option<i128>,
}

/// `e` inside a level's steps (`run::wrap`).
#[inline]
fn wrap(e: Shape, steps: Steps) -> Shape {
    let mut e = e;
    if let Some(g) = steps.content {
        e = mul(&[Shape::int(g), e]);
    }
    if steps.neg {
        e = e.neg();
    }
    e
}

/// What the buckets above a level of a run have in common (`run::Level`).
struct Level {
    size: usize,
    first: u32,
    all_neg: bool,
    all_pos: bool,
    /// The gcd of the root's coefficients (absolute values; 0 for none).
    gcd: u128,
    best: Option<usize>,
}

/// Below this bit size a coefficient, its quotients and products of divisors stay in `i128`.
const MAX_BITS: u64 = 126;

impl Costs {
    /// The costs of a search of `mons`, when every monomial is a plain product of symbols
    /// with an integer coefficient of at most [`MAX_BITS`] bits.
    pub(super) fn for_mons(mons: &[Mon]) -> Option<Costs> {
        let mut coef = Vec::with_capacity(mons.len());
        let mut words = Vec::with_capacity(mons.len());
        for m in mons {
            if m.rad != 1 || !m.atoms.is_empty() || m.q.bits() > MAX_BITS {
                return None;
            }
            let n = match &m.q {
                Q::S(n, 1) => i128::from(*n),
                Q::S(..) => return None,
                Q::B(b) if num_traits::One::is_one(b.denom()) => b.numer().to_i128()?,
                Q::B(_) => return None,
            };
            coef.push(n);
            words.push(m.q.words() * BIG_WORD_UNITS);
        }
        let masks = Masks::for_mons(mons, &coef, &words);
        Some(Costs {
            coef,
            words,
            memo: FxMap::default(),
            masks,
            bounded: true,
            derived: true,
        })
    }

    /// Monomial `i` (`m`) of a group divided by `div`, the root not multilinear: its
    /// coefficient and quotient (its symbols and their powers) hashed into `h`, as
    /// [`Search::c_value`] and [`Search::c_build_at`] hash them, each symbol of the quotient
    /// handed to `each`; the number of symbols. Inlined into their loops, which ask once per
    /// group whether the root is multilinear (asked per monomial, and a call per monomial,
    /// it was 3% of `(x + y + z)^30`'s report).
    #[inline(always)]
    fn hash_listed(
        &self,
        i: u32,
        m: &Mon,
        div: &[u32],
        sym_base: usize,
        h: &mut FxHasher,
        mut each: impl FnMut(u32),
    ) -> u64 {
        h.write_i128(self.coef[i as usize]);
        let mut len = 0u64;
        for (s, e) in quotient_syms(m, div, sym_base) {
            len += 1;
            h.write_u32(s);
            h.write_u32(e);
            each(s);
        }
        h.write_u8(0xff);
        len
    }

    /// Monomial `i` of a multilinear root with quotient `q` hashed into `h`, as
    /// [`Search::c_value`] and [`Search::c_build_at`] hash it.
    fn hash_quotient(&self, i: u32, q: u64, h: &mut FxHasher) {
        hash_quotient(self.coef[i as usize], q, h);
    }

    /// [`Search::c_build_at`]'s pass over a multilinear root's group: the quotients hashed
    /// and their symbols counted in [`Masks::tally`] (read by [`Search::counted_best`]);
    /// the work.
    fn count_masked(&mut self, group: &[u32], h: &mut FxHasher) -> u64 {
        let Costs {
            coef, words, masks, ..
        } = self;
        let Some(masks) = masks else {
            return 0;
        };
        let (mut ones, mut rest) = (0u32, 0u64);
        for &i in group {
            let q = masks.quotient(i);
            hash_quotient(coef[i as usize], q, h);
            masks.tally.add(q);
            ones += q.count_ones();
            rest += words[i as usize];
        }
        group.len() as u64 + u64::from(ones) + rest
    }

    /// Whether the monomials are taken as bit sets ([`Masks`]; the tests).
    #[cfg(test)]
    pub(super) fn masked(&self) -> bool {
        self.masks.is_some()
    }

    /// The common divisor of a group of the tree search: `coef[i] / q` for its first
    /// monomial `(i, q)`.
    pub(super) fn divisor(&self, group: &[(u32, Q)]) -> Option<i128> {
        let (i, q) = group.first()?;
        let q = match q {
            Q::S(n, 1) => i128::from(*n),
            Q::B(b) if num_traits::One::is_one(b.denom()) => b.numer().to_i128()?,
            _ => return None,
        };
        let c = self.coef[*i as usize];
        (q != 0 && c % q == 0).then(|| c / q)
    }
}

/// The monomials of a multilinear root (every symbol to the first power, every symbol's id
/// below 64) as bit sets, bit `s` for symbol `s`: the entries of a chain whose lengths and
/// twists are symbols, in the cosines and sines of its joints, are such sums (a fully symbolic
/// 6R's matrix: 55 to 232 monomials in 36 symbols). A group's divisor is then a mask too (a
/// factor pulled out of a group is in all its monomials, to the first power), so a quotient is
/// `mask & !div`: one word hashed and compared where the symbol list was walked and each
/// power looked up in the divisor (the 6R's cost pass: 72 M instructions to 46 M).
pub(super) struct Masks {
    of: Vec<u64>,
    /// The symbols pulled out of the current group ([`Search::div`]'s symbols), kept with
    /// it by the cost pass ([`Search::c_split_on`]) and set from it where the tree search
    /// hands a group to the pass ([`Search::cost_winner`]).
    div: u64,
    /// The symbols of the current group's quotients counted, where [`super::Counts`] counts
    /// those of a root that is not multilinear.
    tally: Tally,
    /// Each monomial's mask with what [`Search::c_partition_pre`] and [`Search::c_pre`] read
    /// of it, one bounds check for three.
    bits: Vec<Bits>,
}

/// A monomial of a multilinear root, for [`Search::c_partition_pre`].
struct Bits {
    of: u64,
    /// Its coefficient's low word scrambled, for [`mix`].
    seed: u64,
    /// Its work in a visit's pass before the divisor's symbols are taken off: one, its
    /// symbols and its coefficient's words (see [`Search::c_build_at`]).
    unit: u64,
}

/// Monomial `q` with coefficient `coef`, hashed into `h`: the low word of the coefficient
/// is enough for a hash (the memo compares the coefficients in full), and a record of two
/// words needs no end mark.
fn hash_quotient(coef: i128, q: u64, h: &mut FxHasher) {
    h.write_u64(coef as u64);
    h.write_u64(q);
}

/// The odd multiplier of a coefficient's low word in [`Bits::seed`].
const MIX_SEED: u64 = 0x9e37_79b9_7f4a_7c15;

/// Monomial `q` with a coefficient seeded `seed` ([`Bits::seed`]) as one word of a group's
/// value: a multilinear root's group's value is the sum of its monomials' words, so a split
/// makes both parts' values in its one pass over the group (the memo compares the groups a
/// value finds, so a collision costs only that comparison).
#[inline]
fn mix(seed: u64, q: u64) -> u64 {
    let x = (seed ^ q).wrapping_mul(0xd6e8_feb8_6659_fd93);
    x ^ (x >> 29)
}

/// What a visit of a multilinear root's group ([`Search::c_build_at`]) takes from its pass
/// over the group, handed to it by the split that made the group ([`Search::c_split_on`]),
/// which passes over the group's monomials anyway: the group's value (the memo's key, the
/// sum of [`mix`]), the work the pass charges and its quotients' symbols counted. The smaller
/// part is counted and the larger one's counts are the group's less those (either may hold
/// the split's factor): most monomials are counted once per split, not once per part they
/// fall in.
struct Pre {
    value: u64,
    work: u64,
    tally: Tally,
}

impl Pre {
    fn new() -> Pre {
        Pre {
            value: 0,
            work: 0,
            tally: Tally::new(),
        }
    }
}

/// How many symbols each count of a [`Tally`] can reach: `2^PLANES - 1` monomials.
const PLANES: usize = 32;

/// Counts of the symbols of a group's quotients, bit-sliced: plane `p` holds bit `p` of
/// every symbol's count, so a quotient is counted by adding its mask with a carry, a few
/// word operations (each of its symbols was an increment in [`super::Counts`], a fifth of
/// the symbolic 6R's cost pass), and the most frequent symbols are read from the planes,
/// top down.
struct Tally {
    planes: [u64; PLANES],
    /// The planes that may be nonzero.
    used: usize,
    /// The symbols counted at least once.
    union: u64,
}

impl Tally {
    fn new() -> Tally {
        Tally {
            planes: [0; PLANES],
            used: 0,
            union: 0,
        }
    }

    /// Each symbol of `q` counted once more.
    #[inline]
    fn add(&mut self, q: u64) {
        self.union |= q;
        let (mut carry, mut p) = (q, 0);
        while carry != 0 && p < PLANES {
            let plane = &mut self.planes[p];
            let next = *plane & carry;
            *plane ^= carry;
            carry = next;
            p += 1;
        }
        self.used = self.used.max(p);
    }

    /// The count of symbol `s`.
    #[inline]
    fn count(&self, s: u32) -> u32 {
        self.planes[..self.used]
            .iter()
            .enumerate()
            .fold(0, |n, (p, plane)| n | (((plane >> s) & 1) as u32) << p)
    }

    /// [`Tally::ranked`], the counts cleared.
    fn best(&mut self, k: usize) -> Candidates {
        let out = self.ranked(k);
        self.clear();
        out
    }

    /// `self` less `part` (counts of some of `self`'s monomials) in `out` (zero), symbol `f`
    /// left out: the bit-sliced difference, one borrow per plane.
    fn minus_into(&self, part: &Tally, f: u32, out: &mut Tally) {
        let (mut borrow, mut union) = (0u64, 0u64);
        for p in 0..self.used {
            let (a, b) = (self.planes[p], part.planes[p]);
            let diff = a ^ b ^ borrow;
            borrow = (!a & (b | borrow)) | (a & b & borrow);
            out.planes[p] = diff & !(1 << f);
            union |= out.planes[p];
        }
        debug_assert_eq!(borrow, 0, "a part counts no symbol more than its group");
        out.used = self.used;
        out.union = union;
    }

    /// [`super::Counts::best`]: the first `k` symbols counted at least twice, most frequent
    /// first, ties by symbol. The symbols of the highest count among those left are the ones
    /// left at a plane's bit at each plane from the top that has any.
    fn ranked(&self, k: usize) -> Candidates {
        let mut out = Candidates::new();
        let mut left = self.union;
        while out.len() < k && left != 0 {
            let mut top = left;
            for plane in self.planes[..self.used].iter().rev() {
                if top & plane != 0 {
                    top &= plane;
                }
            }
            if self.count(top.trailing_zeros()) < 2 {
                break;
            }
            let room = k - out.len();
            out.extend(bits(top).take(room).map(Factor::Sym));
            left &= !top;
        }
        out
    }

    #[inline]
    fn clear(&mut self) {
        self.planes[..self.used].fill(0);
        self.used = 0;
        self.union = 0;
    }
}

impl Masks {
    fn for_mons(mons: &[Mon], coef: &[i128], words: &[u64]) -> Option<Masks> {
        let of = mons
            .iter()
            .map(|m| {
                m.syms.iter().try_fold(0u64, |mask, &(s, e)| {
                    (e == 1 && s < 64).then(|| mask | 1 << s)
                })
            })
            .collect::<Option<Vec<u64>>>()?;
        let bits = of
            .iter()
            .zip(coef.iter().zip(words))
            .map(|(&of, (&c, w))| Bits {
                of,
                seed: (c as u64).wrapping_mul(MIX_SEED),
                unit: 1 + u64::from(of.count_ones()) + w,
            })
            .collect();
        Some(Masks {
            of,
            div: 0,
            tally: Tally::new(),
            bits,
        })
    }

    /// Monomial `i`'s quotient by the current divisor.
    pub(super) fn quotient(&self, i: u32) -> u64 {
        self.of[i as usize] & !self.div
    }
}

/// The symbols of a mask, in increasing order (the order of a monomial's symbol list).
fn bits(mask: u64) -> impl Iterator<Item = u32> {
    let mut m = mask;
    std::iter::from_fn(move || {
        (m != 0).then(|| {
            let s = m.trailing_zeros();
            m &= m - 1;
            s
        })
    })
}

/// `gcd(g, n)`, `g` the gcd so far (0 for none): `n` enters as its remainder modulo `g`, and
/// once `g` is a machine word the rest is a binary gcd of words.
fn gcd(g: u128, n: u128) -> u128 {
    if g == 0 {
        return n;
    }
    let r = n % g;
    match u64::try_from(g) {
        Ok(w) => u128::from(gcd_u64(w, r as u64)),
        Err(_) => {
            let (mut a, mut b) = (g, r);
            while b != 0 {
                (a, b) = (b, a % b);
            }
            a
        }
    }
}

/// The gcd of `n` over a group whose coefficients `d` divides: it stops at `|d|`, below
/// which it cannot go. Inlined into its callers (called apart it was 2% of
/// `(x + y + z)^30`'s report).
#[inline]
fn gcd_over(d: i128, ns: impl Iterator<Item = i128>, above: u128) -> u128 {
    let floor = d.unsigned_abs();
    let mut g = above;
    for n in ns {
        if g == floor {
            break;
        }
        g = gcd(g, n.unsigned_abs());
    }
    g
}

impl Search<'_> {
    /// The candidate of `fs` (those of `group`, of the tree search at `depth`, a branching
    /// level) the search takes, the first of least cost, with that cost, when the group's
    /// monomials allow costs without trees.
    pub(super) fn cost_winner(
        &mut self,
        group: &[(u32, Q)],
        fs: &[Factor],
        depth: usize,
    ) -> Option<(Factor, Cost)> {
        let d = self.costs.as_ref()?.divisor(group)?;
        debug_assert!(group.iter().all(|(i, q)| {
            let c = self.costs.as_ref().map_or(0, |c| c.coef[*i as usize]);
            c % d == 0 && *q == c_q(c / d)
        }));
        let idx: Vec<u32> = group.iter().map(|(i, _)| *i).collect();
        self.set_div_mask();
        let (shape, winner) = match self.c_pre(&idx) {
            Some(pre) => {
                let cands = Cands::Given(fs);
                self.c_search(&idx, d, pre.value, depth, cands, NO_BOUND, Some(&pre.tally))
            }
            None => {
                let value = self.c_value(&idx);
                self.c_search(&idx, d, value, depth, Cands::Given(fs), NO_BOUND, None)
            }
        };
        Some((winner?, shape?.alone()))
    }

    /// What a visit of `group` takes from its pass ([`Pre`]), made in a pass of its own,
    /// when the root is multilinear and the parts of a split are handed theirs.
    fn c_pre(&self, group: &[u32]) -> Option<Pre> {
        let costs = self.costs.as_ref().filter(|c| c.derived)?;
        let m = costs.masks.as_ref()?;
        let mut pre = Pre::new();
        for &i in group {
            let b = &m.bits[i as usize];
            let q = b.of & !m.div;
            pre.tally.add(q);
            pre.value = pre.value.wrapping_add(mix(b.seed, q));
            pre.work += b.unit;
        }
        pre.work -= group.len() as u64 * u64::from(m.div.count_ones());
        Some(pre)
    }

    fn coef(&self, i: u32) -> i128 {
        self.costs.as_ref().map_or(1, |c| c.coef[i as usize])
    }

    /// The bit sets of a multilinear root ([`Masks`]).
    pub(super) fn masks(&self) -> Option<&Masks> {
        self.costs.as_ref()?.masks.as_ref()
    }

    /// The tally of a multilinear root ([`Masks::tally`]).
    fn tally(&mut self) -> Option<&mut Tally> {
        Some(&mut self.costs.as_mut()?.masks.as_mut()?.tally)
    }

    /// The best `k` factors of the group [`Search::c_build_at`] counted ([`super::Counts::best`]
    /// or [`Tally::best`]); the counts are cleared.
    fn counted_best(&mut self, k: usize) -> Candidates {
        match self.tally() {
            Some(t) => t.best(k),
            None => self.counts.best(k),
        }
    }

    /// The counts of [`Search::c_build_at`] cleared without reading them.
    fn clear_counted(&mut self) {
        match self.tally() {
            Some(t) => t.clear(),
            None => self.counts.clear(),
        }
    }

    /// [`Search::clear_counted`], unless the group's counts are `tally` (handed down by a
    /// split: the visit counted nothing).
    fn clear_counted_unless(&mut self, tally: Option<&Tally>) {
        if tally.is_none() {
            self.clear_counted();
        }
    }

    /// The factors pulled out of the current group, as the memo of costs keys them.
    fn c_div_key(&self) -> DivKey {
        match self.masks() {
            Some(m) => DivKey::Mask(m.div),
            None => DivKey::List(self.div_key()),
        }
    }

    /// The symbols of [`Search::div`] (each to the first power, the root being multilinear)
    /// as a mask.
    fn div_as_mask(&self) -> u64 {
        self.div[self.counts.sym_base..]
            .iter()
            .enumerate()
            .filter(|&(_, &k)| k > 0)
            .fold(0, |mask, (s, _)| mask | 1 << s)
    }

    /// [`Masks::div`] set from [`Search::div`].
    fn set_div_mask(&mut self) {
        let div = self.div_as_mask();
        if let Some(m) = self.costs.as_mut().and_then(|c| c.masks.as_mut()) {
            m.div = div;
        }
    }

    /// `f` put in [`Masks::div`] (`on`) or taken out of it, when the root is multilinear;
    /// whether it was.
    pub(super) fn mask_div(&mut self, f: Factor, on: bool) -> bool {
        let m = self.costs.as_mut().and_then(|c| c.masks.as_mut());
        match (m, f) {
            (Some(m), Factor::Sym(s)) => {
                m.div = if on {
                    m.div | 1 << s
                } else {
                    m.div & !(1 << s)
                };
                true
            }
            _ => false,
        }
    }

    /// The power of `f` in each monomial of `group` above the current divisor's
    /// ([`multiplicity`]; a bit of the mask for a multilinear root, the choice made once per
    /// group: made per monomial it was 2% of the 6R's report).
    pub(super) fn powers<C: FromIterator<u32>>(
        &self,
        group: impl Iterator<Item = u32>,
        f: Factor,
    ) -> C {
        let base = self.div[self.counts.index(f)];
        match (self.masks(), f) {
            (Some(m), Factor::Sym(s)) => group
                .map(|i| ((m.of[i as usize] >> s) as u32 & 1) - base)
                .collect(),
            _ => group
                .map(|i| multiplicity(&self.root[i as usize], f) - base)
                .collect(),
        }
    }

    /// [`Search::candidates`] of a multilinear root's group, counted on its quotients'
    /// bit sets ([`Tally`]); `None` for another root.
    pub(super) fn candidates_masked(
        &mut self,
        group: impl Iterator<Item = u32>,
        k: usize,
    ) -> Option<Candidates> {
        let m = self.costs.as_mut()?.masks.as_mut()?;
        for i in group {
            let q = m.quotient(i);
            m.tally.add(q);
        }
        Some(m.tally.best(k))
    }

    /// Whether candidates are cut at the best cost so far (always, but in the tests that
    /// compare the search with and without the bound).
    fn bounded(&self) -> bool {
        self.costs.as_ref().is_some_and(|c| c.bounded)
    }

    /// Monomial `i` with coefficient `coef[i] / d` ([`Search::mon_expr`]).
    fn c_mon(&self, i: u32, d: i128) -> Shape {
        let q = self.coef(i) / d;
        let m = &self.root[i as usize];
        let mut parts = 0usize;
        let mut ops = 0usize;
        if q.unsigned_abs() != 1 {
            parts += 1;
        }
        if let Some(masks) = self.masks() {
            parts += masks.quotient(i).count_ones() as usize;
        } else {
            for (_, e) in quotient_syms(m, &self.div, self.counts.sym_base) {
                parts += 1;
                ops += (e as usize).saturating_sub(1);
            }
        }
        let e = match parts {
            0 => Shape::int(1),
            1 => Shape::leaf(ops),
            n => Shape {
                core: Cost {
                    ops: ops + n - 1,
                    calls: 0,
                },
                kind: Kind::Mul,
                negs: 0,
            },
        };
        if q < 0 {
            e.neg()
        } else {
            e
        }
    }

    fn c_plain_sum(&self, group: &[u32], d: i128) -> Shape {
        sum(group.iter().map(|&i| self.c_mon(i, d)))
    }

    /// [`Search::build_at`] for the group `coef[i] / d`, `i` in `group`; `None` when its cost
    /// is at least `bound` operations (see the module's doc). `pre` is what the visit's pass
    /// over the group would find, when the split that made the group found it ([`Pre`]).
    fn c_build_at(
        &mut self,
        group: &[u32],
        d: i128,
        depth: usize,
        bound: usize,
        pre: Option<&Pre>,
    ) -> Option<Shape> {
        match pre {
            Some(pre) => self.c_build_pre(group, d, depth, bound, pre),
            None => self.c_build_counting(group, d, depth, bound),
        }
    }

    /// [`Search::c_build_at`] with its pass over the group.
    fn c_build_counting(
        &mut self,
        group: &[u32],
        d: i128,
        depth: usize,
        bound: usize,
    ) -> Option<Shape> {
        match group {
            [] => return Some(Shape::ZERO),
            [i] => return Some(self.c_mon(*i, d)),
            _ => {}
        }
        if additions(group.len()) >= bound {
            return None;
        }
        // The work's pass over the quotients also hashes them (see [`Search::c_search`]) and
        // counts their factors (the candidates), one pass for three.
        let mut work = 0u64;
        let mut h = FxHasher::default();
        let Some(costs) = self.costs.as_mut() else {
            return Some(self.c_plain_sum(group, d));
        };
        let (root, div, counts) = (self.root, &self.div, &mut self.counts);
        let base = counts.sym_base;
        if costs.masks.is_some() {
            work = costs.count_masked(group, &mut h);
        } else {
            for &i in group {
                let len = costs.hash_listed(i, &root[i as usize], div, base, &mut h, |s| {
                    counts.bump(base + s as usize);
                });
                work += 1 + len + costs.words[i as usize];
            }
        }
        let value = h.finish();
        debug_assert!(self.masks().is_none_or(|m| m.div == self.div_as_mask()));
        self.charge_work(work);
        if self.spent.is_some() {
            self.clear_counted();
            return Some(self.c_plain_sum(group, d));
        }
        // The negation and the content each add one operation to the group's cost.
        if group.iter().all(|&i| (self.coef(i) < 0) != (d < 0)) {
            self.clear_counted();
            return self
                .c_build_counting(group, -d, depth, bound.saturating_sub(1))
                .map(Shape::neg);
        }
        let g = gcd_over(d, group.iter().map(|&i| self.coef(i)), 0) / d.unsigned_abs();
        if g != 1 {
            self.clear_counted();
            let d = d * g as i128;
            let inner = self.c_build_counting(group, d, depth, bound.saturating_sub(1))?;
            return Some(mul(&[Shape::int(g as i128), inner]));
        }
        self.c_search(group, d, value, depth, Cands::Counted, bound, None)
            .0
    }

    /// [`Search::c_build_counting`] of a multilinear root's group whose pass its split made
    /// (`pre`): the same steps, the same work charged.
    fn c_build_pre(
        &mut self,
        group: &[u32],
        d: i128,
        depth: usize,
        bound: usize,
        pre: &Pre,
    ) -> Option<Shape> {
        match group {
            [] => return Some(Shape::ZERO),
            [i] => return Some(self.c_mon(*i, d)),
            _ => {}
        }
        if additions(group.len()) >= bound {
            return None;
        }
        debug_assert!(self.c_pre(group).is_some_and(|q| {
            (q.value, q.work, q.tally.planes) == (pre.value, pre.work, pre.tally.planes)
        }));
        self.charge_work(pre.work);
        if self.spent.is_some() {
            return Some(self.c_plain_sum(group, d));
        }
        // The negation and the content each add one operation to the group's cost.
        if group.iter().all(|&i| (self.coef(i) < 0) != (d < 0)) {
            return self
                .c_build_pre(group, -d, depth, bound.saturating_sub(1), pre)
                .map(Shape::neg);
        }
        let g = gcd_over(d, group.iter().map(|&i| self.coef(i)), 0) / d.unsigned_abs();
        if g != 1 {
            let d = d * g as i128;
            let inner = self.c_build_pre(group, d, depth, bound.saturating_sub(1), pre)?;
            return Some(mul(&[Shape::int(g as i128), inner]));
        }
        let tally = Some(&pre.tally);
        self.c_search(group, d, pre.value, depth, Cands::Counted, bound, tally)
            .0
    }

    /// The hash of a group's coefficients and quotients, as [`Search::c_build_at`] makes it.
    fn c_value(&self, group: &[u32]) -> u64 {
        let mut h = FxHasher::default();
        let Some(costs) = &self.costs else {
            return h.finish();
        };
        if let Some(masks) = &costs.masks {
            for &i in group {
                costs.hash_quotient(i, masks.quotient(i), &mut h);
            }
        } else {
            let base = self.counts.sym_base;
            for &i in group {
                let m = &self.root[i as usize];
                costs.hash_listed(i, m, &self.div, base, &mut h, |_| {});
            }
        }
        h.finish()
    }

    /// Whether the group of `k` is `group` as now divided: the same divisor, coefficients and
    /// quotients, monomial by monomial (`key` is [`Search::c_div_key`]).
    fn c_same(&self, k: &Known, d: i128, key: &DivKey, group: &[u32]) -> bool {
        if k.d != d || k.group.len() != group.len() {
            return false;
        }
        if k.div == *key {
            // Divided alike: a quotient determines its monomial of the root.
            return k.group == group;
        }
        let div = match (&k.div, self.masks()) {
            (DivKey::Mask(other), Some(masks)) => {
                return k.group.iter().zip(group).all(|(&i, &j)| {
                    self.coef(i) == self.coef(j)
                        && masks.of[i as usize] & !other == masks.quotient(j)
                });
            }
            (DivKey::List(div), None) => div,
            // A search's root is multilinear or not throughout: its keys are all of one kind.
            _ => return false,
        };
        let base = self.counts.sym_base;
        let mut other = vec![0u32; self.div.len()];
        for &(i, p) in div {
            other[i] = p;
        }
        k.group.iter().zip(group).all(|(&i, &j)| {
            let (m, n) = (&self.root[i as usize], &self.root[j as usize]);
            self.coef(i) == self.coef(j)
                && quotient_syms(m, &other, base).eq(quotient_syms(n, &self.div, base))
        })
    }

    /// [`Search::searched`]: the memo, the candidates (`fs` when counted already), the
    /// splits; the shape (`None` when its cost is at least `bound` operations) and, at a
    /// branching level, the candidate taken.
    ///
    /// The memo is keyed by the group's value (`value`, [`Search::c_value`]): the divisor,
    /// the coefficients and the quotients, which are all the search of a group reads (the
    /// candidates are counted on the quotients, ties broken by factor; the shapes are made
    /// from the quotients and the coefficients divided by `d`). The same quotients come back
    /// under other factors pulled out, in other groups of the root's monomials.
    ///
    /// `tally` is the group's counts when its split handed them down ([`Pre`]): the
    /// candidates are read from them and they are handed on to the group's splits.
    #[allow(clippy::too_many_arguments)]
    fn c_search(
        &mut self,
        group: &[u32],
        d: i128,
        value: u64,
        depth: usize,
        fs: Cands,
        bound: usize,
        tally: Option<&Tally>,
    ) -> (Option<Shape>, Option<Factor>) {
        let level = depth.min(BRANCH_DEPTH);
        let key = self.c_div_key();
        let mut h = FxHasher::default();
        (level, d, value).hash(&mut h);
        let hash = h.finish();
        // An entry that only knows a lower bound below this one is searched again and
        // replaced.
        let mut stale = None;
        if let Some((pos, k)) = self.costs.as_ref().and_then(|c| {
            c.memo
                .get(&hash)?
                .iter()
                .enumerate()
                .find(|(_, k)| k.level == level && self.c_same(k, d, &key, group))
        }) {
            let found = match k.found {
                Bounded::Exact(s) => Some((Some(s), k.winner)),
                Bounded::AtLeast(l) if l >= bound => Some((None, None)),
                Bounded::AtLeast(_) => {
                    stale = Some(pos);
                    None
                }
            };
            if let Some(found) = found {
                if matches!(fs, Cands::Counted) {
                    self.clear_counted_unless(tally);
                }
                return found;
            }
        }
        let tries = if depth < BRANCH_DEPTH { BRANCH } else { 1 };
        let counted;
        let candidates = match fs {
            Cands::Given(fs) => fs,
            Cands::Counted => {
                counted = match tally {
                    Some(t) => t.ranked(tries),
                    None => self.counted_best(tries),
                };
                &counted[..]
            }
            Cands::Count => {
                counted = self.candidates(group.iter().copied(), tries);
                &counted[..]
            }
        };
        if candidates.is_empty() {
            return (Some(self.c_plain_sum(group, d)), None);
        }
        let (shape, winner) = if tries == 1 {
            (
                self.c_run(group, d, candidates[0], depth, bound, tally),
                None,
            )
        } else {
            let bounded = self.bounded();
            let mut best: Option<(Shape, Factor)> = None;
            for &f in candidates {
                // A candidate costing as much as the best so far is not taken (the first of
                // least cost is): it is cut there.
                let b = match best {
                    Some((s, _)) if bounded => s.alone().ops.min(bound),
                    _ => bound,
                };
                let Some(e) = self.c_split_on(group, d, f, depth, b, tally) else {
                    continue;
                };
                if e.alone().ops < b && best.is_none_or(|(s, _)| e.alone() < s.alone()) {
                    best = Some((e, f));
                }
            }
            (best.map(|(s, _)| s), best.map(|(_, f)| f))
        };
        if let Some(c) = self.costs.as_mut() {
            let found = match shape {
                Some(s) => Bounded::Exact(s),
                None => Bounded::AtLeast(bound),
            };
            let k = Known {
                level,
                d,
                div: key,
                group: group.to_vec(),
                found,
                winner,
            };
            let entries = c.memo.entry(hash).or_default();
            match stale {
                Some(pos) => entries[pos] = k,
                None => entries.push(k),
            }
        }
        (shape, winner)
    }

    /// The split of `group` on `f` ([`Search::split_on`]'s): the lowest power `k` of `f`
    /// (above the current divisor's) among the monomials holding it, the monomials holding
    /// `f^k` (pushed on `with`) and the others (on `rest`), each in order.
    fn c_partition(&self, group: &[u32], f: Factor, with: &mut Part, rest: &mut Part) -> u32 {
        if let (Some(m), Factor::Sym(s)) = (self.masks(), f) {
            // A multilinear root's powers are bits, and a candidate is not pulled out yet:
            // `k` is one, and a monomial holds `f` when it has its bit.
            debug_assert_eq!(m.div >> s & 1, 0);
            for &i in group {
                if m.of[i as usize] >> s & 1 != 0 {
                    with.push(i);
                } else {
                    rest.push(i);
                }
            }
            return 1;
        }
        // Each monomial's power of `f` looked up once, for `k` and for the split (twice was a
        // sixth of the symbolic 6R's cost pass).
        let mults: SmallVec<[u32; 32]> = self.powers(group.iter().copied(), f);
        let k = mults.iter().copied().filter(|&n| n > 0).min().unwrap_or(1);
        for (&i, &n) in group.iter().zip(&mults) {
            if n >= k {
                with.push(i);
            } else {
                rest.push(i);
            }
        }
        k
    }

    /// [`Search::c_partition`] of a multilinear root's group whose counts are `tally` on `f`
    /// (symbol `s`), with what each part's visit takes from its pass ([`Pre`], in `w` for
    /// the part holding `f`, as divided by `f`, and `r` for the rest): the smaller part
    /// counted, the other's counts the group's less those (most monomials are counted once
    /// per split, where each part's visit counted all of its own).
    #[allow(clippy::too_many_arguments)]
    fn c_partition_pre(
        &self,
        group: &[u32],
        s: u32,
        tally: &Tally,
        with: &mut Part,
        rest: &mut Part,
        w: &mut Pre,
        r: &mut Pre,
    ) {
        let Some(m) = self.masks() else {
            return;
        };
        let fbit = 1u64 << s;
        debug_assert_eq!(m.div & fbit, 0);
        let n_with = tally.count(s) as usize;
        let count_with = 2 * n_with <= group.len();
        for &i in group {
            let b = &m.bits[i as usize];
            let q = b.of & !m.div;
            if q & fbit != 0 {
                with.push(i);
                let q = q & !fbit;
                if count_with {
                    w.tally.add(q);
                }
                w.value = w.value.wrapping_add(mix(b.seed, q));
                w.work += b.unit;
            } else {
                rest.push(i);
                if !count_with {
                    r.tally.add(q);
                }
                r.value = r.value.wrapping_add(mix(b.seed, q));
                r.work += b.unit;
            }
        }
        debug_assert_eq!(with.len(), n_with);
        if count_with {
            tally.minus_into(&w.tally, s, &mut r.tally);
        } else {
            tally.minus_into(&r.tally, s, &mut w.tally);
        }
        let ones = u64::from(m.div.count_ones());
        w.work -= with.len() as u64 * (ones + 1);
        r.work -= rest.len() as u64 * ones;
    }

    /// [`Search::split_on`]; `None` when its cost is at least `bound` operations. `tally` is
    /// the group's counts when its parts are handed theirs ([`Pre`]).
    fn c_split_on(
        &mut self,
        group: &[u32],
        d: i128,
        f: Factor,
        depth: usize,
        bound: usize,
        tally: Option<&Tally>,
    ) -> Option<Shape> {
        // On the stack: a split's two parts were two allocations per candidate tried.
        let (mut with, mut rest) = (Part::with_capacity(group.len()), Part::new());
        if let (Some(t), Factor::Sym(s), true) = (tally, f, self.masks().is_some()) {
            let (mut w, mut r) = (Pre::new(), Pre::new());
            self.c_partition_pre(group, s, t, &mut with, &mut rest, &mut w, &mut r);
            return self.c_split_parts(&with, &rest, 1, d, f, depth, bound, Some((&w, &r)));
        }
        let k = self.c_partition(group, f, &mut with, &mut rest);
        self.c_split_parts(&with, &rest, k, d, f, depth, bound, None)
    }

    /// [`Search::c_split_on`] past its partition: the part `with` holding `f^k` and the
    /// `rest`, with their [`Pre`]s when handed down.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn c_split_parts(
        &mut self,
        with: &[u32],
        rest: &[u32],
        k: u32,
        d: i128,
        f: Factor,
        depth: usize,
        bound: usize,
        pre: Option<(&Pre, &Pre)>,
    ) -> Option<Shape> {
        let fi = self.counts.index(f);
        // What the split adds to the cost of the group holding `f` (at least two monomials,
        // so not the number one): `k - 1` for the power and one for the product, or with a
        // rest of `n` monomials `k - 1` and `n` (its additions and the one joining it; the
        // product's operation may be the subtraction's negation, see the module's doc).
        let over = (k as usize - 1) + rest.len().max(1);
        self.div[fi] += k;
        self.path.push((fi, k));
        let masked = self.mask_div(f, true);
        let inner = self.c_build_at(
            with,
            d,
            depth.saturating_add(k as usize),
            bound.saturating_sub(over),
            pre.map(|(w, _)| w),
        );
        if masked {
            self.mask_div(f, false);
        }
        self.path.pop();
        self.div[fi] -= k;
        let factored = mul(&[factor_shape(k), inner?]);
        self.c_beside(factored, rest, d, depth, bound, pre.map(|(_, r)| r))
    }

    /// [`Search::beside`]: the rest's terms and the factored group in one sum; `None` when
    /// its cost is at least `bound` operations. `pre` is the rest's [`Pre`], when handed down.
    fn c_beside(
        &mut self,
        factored: Shape,
        rest: &[u32],
        d: i128,
        depth: usize,
        bound: usize,
        pre: Option<&Pre>,
    ) -> Option<Shape> {
        if rest.is_empty() {
            return Some(factored);
        }
        let r = self.c_build_at(
            rest,
            d,
            depth + 1,
            bound.saturating_sub(factored.in_sum().ops),
            pre,
        )?;
        Some(if r.kind == Kind::Add && r.negs == 0 {
            Shape {
                core: add(add(r.core, factored.in_sum()), Cost { ops: 1, calls: 0 }),
                ..r
            }
        } else {
            sum([r, factored].into_iter())
        })
    }

    /// [`Search::run`]: the split of `g0` on `f`, and of the group holding `f` on `f` again
    /// while `f` stays its most frequent factor, from buckets by the power of `f`; `None`
    /// when its cost is at least `bound` operations (each level's cost is at most the run's).
    /// `tally` is `g0`'s counts, when handed down ([`Pre`]).
    fn c_run(
        &mut self,
        g0: &[u32],
        d: i128,
        f: Factor,
        depth: usize,
        bound: usize,
        tally: Option<&Tally>,
    ) -> Option<Shape> {
        if self.masks().is_some() {
            // A multilinear root's powers are 0 and 1: its runs are short.
            return self.c_split_on(g0, d, f, depth, bound, tally);
        }
        let fi = self.counts.index(f);
        let base = self.div[fi];
        let mults: Vec<u32> = self.powers(g0.iter().copied(), f);
        // The distinct powers, 0 among them, in increasing order: marked in a table when the
        // largest is small beside the group (a power's run), sorted otherwise.
        let top = mults.iter().copied().max().unwrap_or(0) as usize;
        let ks: Vec<u32> = if top <= 4 * mults.len() + 64 {
            let mut seen = vec![false; top + 1];
            seen[0] = true;
            for &m in &mults {
                seen[m as usize] = true;
            }
            (0..=top as u32).filter(|&k| seen[k as usize]).collect()
        } else {
            let mut ks = mults.clone();
            ks.push(0);
            ks.sort_unstable();
            ks.dedup();
            ks
        };
        if ks.len() <= super::run::SHORT_RUN {
            return self.c_split_on(g0, d, f, depth, bound, None);
        }
        let buckets = Buckets::sorted(&mults, &ks);
        let levels = self.c_levels(g0, d, f, &ks, &buckets);
        if self.spent.is_some() {
            return Some(self.c_plain_sum(g0, d));
        }
        // A level's coefficients are `g0`'s divided by `divisor` and negated with `neg`:
        // `coef / (d * divisor * sign)`.
        let at = |neg: bool, divisor: i128| if neg { -d * divisor } else { d * divisor };
        let (mut neg, mut divisor) = (false, 1i128);
        let mut states: Vec<(Steps, bool, i128)> = Vec::new();
        let mut b = 1;
        let inner = loop {
            let l = &levels[b];
            self.div[fi] = base + ks[b];
            if l.size == 1 {
                break self.c_mon(g0[l.first as usize], at(neg, divisor));
            }
            let mut steps = Steps::default();
            if (neg && l.all_pos) || (!neg && l.all_neg) {
                steps.neg = true;
                neg = !neg;
            }
            // The level's content relative to `g0`'s coefficients.
            let content = (l.gcd / d.unsigned_abs()) as i128;
            if content != divisor {
                steps.content = Some(content / divisor);
                divisor = content;
            }
            if l.best != Some(fi) {
                let mut group: Vec<u32> = buckets.from(b).to_vec();
                group.sort_unstable();
                for p in &mut group {
                    *p = g0[*p as usize];
                }
                self.path.push((fi, ks[b]));
                let value = self.c_value(&group);
                let e = self
                    .c_search(
                        &group,
                        at(neg, divisor),
                        value,
                        depth,
                        Cands::Count,
                        bound,
                        None,
                    )
                    .0;
                self.path.pop();
                match e {
                    Some(e) => break wrap(e, steps),
                    None => {
                        self.div[fi] = base;
                        return None;
                    }
                }
            }
            states.push((steps, neg, divisor));
            b += 1;
        };
        let mut e = inner;
        for lb in (0..b).rev() {
            let (steps, neg, divisor) = match lb {
                0 => (Steps::default(), false, 1),
                _ => states.pop().unwrap_or((Steps::default(), false, 1)),
            };
            let factored = mul(&[factor_shape(ks[lb + 1] - ks[lb]), e]);
            let rest: SmallVec<[u32; 8]> =
                buckets.get(lb).iter().map(|&p| g0[p as usize]).collect();
            self.div[fi] = base + ks[lb];
            self.path.push((fi, ks[lb]));
            let level_e = self.c_beside(factored, &rest, at(neg, divisor), depth, bound, None);
            self.path.pop();
            match level_e {
                Some(level_e) => e = wrap(level_e, steps),
                None => {
                    self.div[fi] = base;
                    return None;
                }
            }
        }
        self.div[fi] = base;
        Some(e)
    }
    /// Each level's data from the buckets above it ([`Search::levels`]), charged alike.
    fn c_levels(
        &mut self,
        g0: &[u32],
        d: i128,
        f: Factor,
        ks: &[u32],
        buckets: &Buckets,
    ) -> Vec<Level> {
        let fi = self.counts.index(f);
        let n = ks.len();
        let empty = || Level {
            size: 0,
            first: u32::MAX,
            all_neg: true,
            all_pos: true,
            gcd: 0,
            best: None,
        };
        let mut out: Vec<Level> = (0..=n).map(|_| empty()).collect();
        let sym_base = self.counts.sym_base;
        let mut counts = vec![0u32; self.counts.n.len()];
        let mut touched: Vec<usize> = Vec::new();
        let mut work = 0u64;
        for b in (1..n).rev() {
            let mut l = empty();
            for &p in buckets.get(b) {
                let i = g0[p as usize];
                let m = &self.root[i as usize];
                let c = self.coef(i);
                work += 1 + m.syms.len() as u64;
                work += self.costs.as_ref().map_or(0, |c| c.words[i as usize]);
                let negative = (c < 0) != (d < 0);
                l.all_neg &= negative;
                l.all_pos &= !negative;
                for (s, _) in quotient_syms(m, &self.div, sym_base) {
                    let k = sym_base + s as usize;
                    if k != fi {
                        if counts[k] == 0 {
                            touched.push(k);
                        }
                        counts[k] += 1;
                    }
                }
            }
            l.size = buckets.get(b).len();
            l.first = buckets.get(b)[0];
            let above = &out[b + 1];
            // The bucket's coefficients after the gcd of the buckets above (one and the same
            // gcd; it stops at `|d|`).
            l.gcd = gcd_over(
                d,
                buckets.get(b).iter().map(|&p| self.coef(g0[p as usize])),
                above.gcd,
            );
            if above.size > 0 {
                l.size += above.size;
                l.first = l.first.min(above.first);
                l.all_neg &= above.all_neg;
                l.all_pos &= above.all_pos;
            }
            work += 1 + touched.len() as u64;
            l.best = most_frequent(above.size as u32, fi, &touched, &counts);
            out[b] = l;
        }
        self.charge_work(work);
        out
    }
}

/// The integer `n` as a [`Q`] (debug checks only).
fn c_q(n: i128) -> Q {
    match i64::try_from(n) {
        Ok(s) if s != i64::MIN => Q::S(s, 1),
        _ => Q::big(num_rational::BigRational::from_integer(n.into())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bit-sliced counts agree with counts kept one symbol at a time, and the best `k`
    /// with those counts sorted (most frequent first, ties by symbol, at least two), over
    /// random groups of sparse and dense masks, small and past a plane's carry.
    #[test]
    fn a_tally_counts_and_ranks_as_counting_each_symbol() {
        let mut next = crate::testing::xorshift_below(0x9e37_79b9_7f4a_7c15);
        let mut tally = Tally::new();
        for round in 0..200 {
            let n = 1 + next(if round % 10 == 0 { 300 } else { 12 }) as usize;
            let mut counts = [0u32; 64];
            for _ in 0..n {
                let mut q = 0u64;
                for _ in 0..next(if round % 2 == 0 { 4 } else { 40 }) {
                    q |= 1 << next(64);
                }
                tally.add(q);
                for s in bits(q) {
                    counts[s as usize] += 1;
                }
            }
            for s in 0..64 {
                assert_eq!(
                    tally.count(s),
                    counts[s as usize],
                    "round {round}, symbol {s}"
                );
            }
            let mut ranked: Vec<u32> = (0..64).filter(|&s| counts[s as usize] >= 2).collect();
            ranked.sort_by_key(|&s| (std::cmp::Reverse(counts[s as usize]), s));
            let k = next(5) as usize;
            let want: Vec<Factor> = ranked.into_iter().take(k).map(Factor::Sym).collect();
            assert_eq!(tally.best(k).to_vec(), want, "round {round}, k {k}");
            assert_eq!((tally.used, tally.union), (0, 0), "cleared");
        }
    }
}
