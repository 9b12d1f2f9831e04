//! Angle-sum recombination: `T cos a cos b - T sin a sin b -> T cos(a + b)` and its three
//! siblings, for any cofactor `T` (lengths, other trigonometric factors, numbers), repeated
//! until nothing pairs up, so `c1 c2 c3 - ...` regroups to `c123` at any depth.

use super::mon::{
    angle_combine, angle_of, atom, is_sin, merge, remap, Atom, Atoms, Ctx, FxMap, Mon, Syms,
};
use super::trace::{AngleSum, Recorder};
use crate::scalar::q::Q;
use std::cmp::Ordering;

/// Which identity a pair of atoms can take part in.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Class {
    /// `cos a cos b` with `sin a sin b`.
    Cos,
    /// `sin a cos b` with `cos a sin b`.
    Sin,
}

/// A pair of atoms `p < q` of monomial `i`, with the identity they can take part in. Pairs
/// are grouped by the key `(class, angle a, angle b, rad, syms, the other atoms)`: two
/// monomials combine only when their keys agree.
///
/// 32 bytes (the positions in narrow fields: [`pairs_of`] says how): the PUMA 560's largest
/// rounds make thousands of pairs on each thread, and every fresh page their tables touch is
/// a page fault of the process.
#[derive(Clone, Copy, Debug)]
struct Entry {
    /// A hash of the key.
    hash: u64,
    a: u32,
    b: u32,
    /// The rank of the monomial's `(rad, syms)`.
    cof: u32,
    i: u32,
    p: u16,
    q: u16,
    class: Class,
    /// The first atom is a sine.
    sin: bool,
}

impl Entry {
    /// The monomial `i`, as an index.
    fn mon(&self) -> usize {
        self.i as usize
    }

    /// The positions `(p, q)` of the pair's atoms in its monomial.
    fn atoms(&self) -> (usize, usize) {
        (usize::from(self.p), usize::from(self.q))
    }
}

/// A hash of one atom (splitmix64's finalizer), summed over the other atoms of a pair's
/// monomial for the hash of its key ([`pairs_of`]): the sum is the monomial's less the pair's
/// two, one subtraction per pair instead of a pass over the other atoms (the Jaco-style arm's
/// split shapes have monomials of six to eight atoms, each with up to 28 pairs). Equal keys
/// have equal other atoms (sorted), so equal sums; the hash only groups the entries, which are
/// compared by their keys within a group.
pub(super) fn atom_hash(a: Atom) -> u64 {
    let mut z = u64::from(a).wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A pair of atoms as [`pairs_of`] lists them all: the hash of its key and its place `(i, p, q)`
/// (so pairs order by hash, then as they were found). 16 bytes: of the PUMA 560's thousands
/// of pairs a round, only those whose hash can pair become an [`Entry`], twice the size.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
struct Pair {
    hash: u64,
    i: u32,
    p: u16,
    /// `q` (below 2^15) and, in bit 15, whether atom `p` is a sine: the same for every pair
    /// of one `(i, p)`, so pairs still order as `(hash, i, p, q)` do.
    q_sin: u16,
}

impl Pair {
    /// The pair `p < q < 2^15` of monomial `i`, atom `p` a sine or not.
    fn new(i: u32, p: u16, q: u16, sin: bool) -> Pair {
        Pair {
            hash: 0,
            i,
            p,
            q_sin: q | u16::from(sin) << 15,
        }
    }

    /// Whether the pair's first atom is a sine.
    fn sin(self) -> bool {
        self.q_sin >> 15 == 1
    }

    /// This pair's entry; `cof` ranks the cofactors of `mons`.
    fn entry(self, mons: &[Mon], cof: &[u32]) -> Entry {
        let i = self.i as usize;
        entry(&mons[i].atoms, cof[i], self)
    }
}

/// The entry of `pair`, whose monomial has the atoms `atoms` (of two angles at the pair's
/// positions) and the cofactor ranked `cof`.
fn entry(atoms: &[Atom], cof: u32, pair: Pair) -> Entry {
    let (p, q) = (pair.p, pair.q_sin & 0x7fff);
    let (a, b) = (atoms[usize::from(p)], atoms[usize::from(q)]);
    Entry {
        class: if is_sin(a) == is_sin(b) {
            Class::Cos
        } else {
            Class::Sin
        },
        a: angle_of(a),
        b: angle_of(b),
        cof,
        i: pair.i,
        sin: pair.sin(),
        p,
        q,
        hash: pair.hash,
    }
}

/// Which pairs of atoms of each monomial a round of [`recombine`] tries.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Pass {
    /// Only the two lowest atoms (`p = 0`, `q = 1`).
    Low,
    /// Every pair.
    All,
}

impl Pass {
    /// The atoms of each monomial (its first ones) whose pairs the pass tries.
    fn atoms(self) -> usize {
        match self {
            Pass::Low => 2,
            Pass::All => 1 << 15,
        }
    }

    /// The number of pairs the pass tries in `mons` (at most).
    fn pairs(self, mons: &[Mon]) -> usize {
        mons.iter()
            .map(|m| {
                let k = m.atoms.len().min(self.atoms());
                k * k.saturating_sub(1) / 2
            })
            .sum()
    }
}

/// The pairs of `mons` that `pass` tries: every pair of atoms of two different angles among
/// the first [`Pass::atoms`] of each monomial, in the order `(i, p, q)`; `cof` ranks the
/// monomials' cofactors, `pairs` is the capacity. The narrow fields of a [`Pair`] hold the
/// first `u32::MAX` monomials and the first 2^15 atoms of each: a pair past them (never met:
/// its round would charge billions of pairs) is left out, so it is not recombined, which
/// leaves its terms as they were.
fn pairs_of(mons: &[Mon], cof: &[u32], pairs: usize, pass: Pass) -> Vec<Pair> {
    // The hash of a pair's key `(class, a, b, cof, the other atoms)` is a sum: the other
    // atoms' [`atom_hash`]es, a hash of each of the pair's two angles (of the atom with its
    // sine bit cleared, turned, so that it is not that atom's own hash), a hash of the
    // cofactor's rank and a constant for the sine class. It is a function of the key, so
    // equal keys hash alike, as [`groups`] needs (it compares the keys within each hash, and
    // orders the groups by key, not by hash: another hash gives the same groups in the same
    // order). Each atom's two hashes enter as one difference, `d = angle's - atom's`, so that
    // a pair's hash is the monomial's sum plus two differences and no entry is built for it.
    // Against an `FxHasher` over the entry's fields, callgrind, one thread: `fk --jacobian
    // tests/data/jaco_style.toml` (22,420 pairs in 247 rounds) 124.50 M -> 124.31 M
    // instructions, the PUMA 560's 21.80 M -> 21.67 M.
    const SIN_CLASS: u64 = 0x6a09_e667_f3bc_c909;
    let mut found: Vec<Pair> = Vec::with_capacity(pairs);
    let mut diffs: Vec<u64> = Vec::new();
    for ((i, m), &cof) in mons.iter().enumerate().zip(cof).take(u32::MAX as usize) {
        let atoms: &[Atom] = &m.atoms;
        let atoms = &atoms[..atoms.len().min(pass.atoms())];
        let mut base = atom_hash(cof).rotate_left(41);
        diffs.clear();
        for &a in m.atoms.iter() {
            let h = atom_hash(a);
            base = base.wrapping_add(h);
            diffs.push(atom_hash(a & !1).rotate_left(23).wrapping_sub(h));
        }
        for (p, &a) in atoms.iter().enumerate() {
            for (q, &b) in atoms.iter().enumerate().skip(p + 1) {
                if angle_of(a) == angle_of(b) {
                    continue;
                }
                // In range: `i < u32::MAX` and `p < q < 2^15` (above).
                let pair = Pair::new(i as u32, p as u16, q as u16, is_sin(a));
                let class = if is_sin(a) == is_sin(b) { 0 } else { SIN_CLASS };
                let hash = base
                    .wrapping_add(diffs[p])
                    .wrapping_add(diffs[q])
                    .wrapping_add(class);
                found.push(Pair { hash, ..pair });
            }
        }
    }
    found
}

/// The entries grouped by key, the groups in key order, each group's entries in the order in
/// which they were found (`(i, p, q)`). Only groups that can pair (two entries, one with a
/// first atom that is a sine and one without) are kept: the others change nothing.
fn groups(mons: &[Mon], cof: &[u32], mut all: Vec<Pair>) -> Groups {
    // A group lies within the entries of one hash, so only a hash with entries of both kinds
    // can hold one that pairs; the others are dropped below anyway. Sorting every entry was
    // the largest cost of the PUMA 560's recombinations (1.26 M instructions of its 37.8 M
    // for 8,340 entries): the kinds are marked in two bit sets, one for the entries whose
    // first atom is a sine and one for the others, by a few bits of the hash, and only the
    // entries whose bit is set in both are sorted. A hash that shares its bit with one of the
    // other kind is sorted in vain (at most about one in eight at eight bits an entry), never
    // left out, so the groups are the same. The PUMA's run on one thread: 37.80 M -> 37.25 M
    // instructions, page faults as before (about 595); a hash map of the kinds instead cost
    // 0.05 M instructions and some 30 page faults (its tables) more.
    let bits = (8 * all.len()).max(64).next_power_of_two();
    let shift = 64 - bits.trailing_zeros();
    // Fibonacci hashing: the top bits of the product depend on every bit of the hash.
    let bit = |hash: u64| (hash.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> shift) as usize;
    let mut seen = [vec![0u64; bits / 64], vec![0u64; bits / 64]];
    for x in &all {
        let k = bit(x.hash);
        seen[usize::from(x.sin())][k / 64] |= 1 << (k % 64);
    }
    let both = |hash: u64| {
        let k = bit(hash);
        (seen[0][k / 64] & seen[1][k / 64]) >> (k % 64) & 1 == 1
    };
    // Equal hashes together, in the order in which the pairs were found (`by_hash`).
    all.retain(|x| both(x.hash));
    drop(seen);
    by_hash(&mut all);
    // The entries that can pair, in that order; the pairs freed at once, for the tables that
    // follow to reuse their memory instead of touching fresh pages.
    let mut index: Vec<Entry> = all.iter().map(|x| x.entry(mons, cof)).collect();
    drop(all);
    // Each group is a range of `index`, not a copy of its entries.
    let mut groups: Vec<(u128, usize, usize)> = Vec::new();
    let pairs = |g: &[Entry]| g.iter().any(|e| e.sin) && g.iter().any(|e| !e.sin);
    let mut start = 0;
    while start < index.len() {
        let mut end = start + 1;
        while end < index.len() && index[end].hash == index[start].hash {
            end += 1;
        }
        let (from, run) = (start, &mut index[start..end]);
        start = end;
        if run.len() < 2 {
            continue;
        }
        // One key (almost always): the run is the group, its keys compared once.
        if run[1..].iter().all(|e| key_cmp(mons, &run[0], e).is_eq()) {
            if pairs(run) {
                groups.push((head(&run[0]), from, end));
            }
            continue;
        }
        // Different keys with one hash: order by key, stably.
        run.sort_by(|x, y| key_cmp(mons, x, y));
        let mut s = 0;
        while s < run.len() {
            let mut t = s + 1;
            while t < run.len() && key_cmp(mons, &run[s], &run[t]).is_eq() {
                t += 1;
            }
            if pairs(&run[s..t]) {
                groups.push((head(&run[s]), from + s, from + t));
            }
            s = t;
        }
    }
    // In key order. The keys of the groups differ (one group per key), so an unstable sort
    // gives the order of a stable one; the fixed part of the key, packed in one integer, is
    // compared first, and the other atoms only when it ties (rarely: a few ties in thousands
    // of groups on the Jaco-style arm). `fk --jacobian tests/data/jaco_style.toml` on one
    // thread: 565.6 M -> 563.4 M instructions against a stable sort of the groups by `key_cmp`.
    let rest = |&(_, k, _): &(u128, usize, usize), &(_, l, _): &(u128, usize, usize)| {
        let (e, f) = (&index[k], &index[l]);
        let ((ep, eq), (fp, fq)) = (e.atoms(), f.atoms());
        rest_cmp(&mons[e.mon()].atoms, ep, eq, &mons[f.mon()].atoms, fp, fq)
    };
    match (groups.len() >= RADIX_MIN)
        .then(|| Packing::of(&groups))
        .flatten()
    {
        // Many groups: by their heads packed in one word, in a few counting passes (the
        // Jaco-style arm's split shapes: thousands of groups a round, and this sort was 6% of
        // its `fk --jacobian`), then each run of equal heads by the other atoms.
        Some(p) => {
            radix_sort(&mut groups, p.bits(), |g| p.pack(g.0));
            for run in groups.chunk_by_mut(|x, y| x.0 == y.0) {
                if run.len() > 1 {
                    run.sort_unstable_by(rest);
                }
            }
        }
        _ => groups.sort_unstable_by(|x, y| x.0.cmp(&y.0).then_with(|| rest(x, y))),
    }
    Groups {
        ranges: groups.iter().map(|&(_, from, to)| from..to).collect(),
        entries: index,
    }
}

/// The fewest groups that [`groups`] orders by counting passes ([`radix_sort`]): below it a
/// comparison sort costs less than the passes' tables.
const RADIX_MIN: usize = 128;

/// The bits of one counting pass of [`radix_sort`].
const DIGIT: u32 = 8;

/// Sorts `v` stably by the low `bits` bits of `key`, in passes of [`DIGIT`] bits from the
/// lowest (a pass that would leave every item in one bucket is skipped).
fn radix_sort<T: Copy>(v: &mut Vec<T>, bits: u32, key: impl Fn(&T) -> u64) {
    // Two buffers, `v`'s own and one copy, written in turn.
    let mut from = std::mem::take(v);
    let mut to = from.clone();
    for shift in (0..bits).step_by(DIGIT as usize) {
        let digit = |x: &T| ((key(x) >> shift) & ((1 << DIGIT) - 1)) as usize;
        let mut start = [0usize; 1 << DIGIT];
        for x in &from {
            start[digit(x)] += 1;
        }
        if start.contains(&from.len()) {
            continue;
        }
        let mut sum = 0;
        for c in &mut start {
            sum += std::mem::replace(c, sum);
        }
        for x in &from {
            let d = digit(x);
            to[start[d]] = *x;
            start[d] += 1;
        }
        std::mem::swap(&mut from, &mut to);
    }
    *v = from;
}

/// Sorts `order` (pairs in the order in which they were found) so that equal hashes stand
/// together, in the order in which they were found: what sorting the pairs gives, except for
/// the order of the runs, which [`groups`] does not use (its groups are sorted by key
/// afterwards).
///
/// The pairs of each hash are chained through an open-addressing table of the hashes (linear
/// probing, at most half full), each new pair appended to its hash's chain, so that each
/// chain keeps the order in which its pairs were found; the chains are then written out one
/// after the other, in the order of their slots: a few steps a pair, where the counting
/// passes over the top bits of the hashes and a sort of each bucket (every bucket holds at
/// least the two pairs of a group, so each was a sort of its own) cost about 100. Callgrind,
/// `fk --jacobian tests/data/jaco_style.toml` on one thread (9,702 pairs kept in 247 rounds):
/// 0.96 M -> about 0.6 M instructions here; with the moves of [`round`] and the one pass of
/// [`cofactor_ranks`], 125.21 M -> 124.50 M in all (the PUMA 560's 21.95 M -> 21.81 M).
fn by_hash(order: &mut Vec<Pair>) {
    let n = order.len();
    // Chains are numbered by `u32` below `u32::MAX` (never more: a round of that many pairs
    // would charge billions).
    if n < 2 || n >= u32::MAX as usize {
        order.sort_unstable();
        return;
    }
    let bits = (2 * n).next_power_of_two().trailing_zeros();
    let mask = (1usize << bits) - 1;
    let slot = |h: u64| (h.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - bits)) as usize;
    // Each slot: one hash's first and last pair, numbered from 1 (0: an empty slot).
    let mut table = vec![(0u32, 0u32); mask + 1];
    // The pair after each in its hash's chain (`END`: the last).
    const END: u32 = u32::MAX;
    let mut next = vec![END; n];
    for (k, x) in order.iter().enumerate() {
        // In range: `k < n < u32::MAX`.
        let id = k as u32 + 1;
        let mut s = slot(x.hash);
        loop {
            let (first, last) = table[s];
            if first == 0 {
                table[s] = (id, id);
                break;
            }
            if order[first as usize - 1].hash == x.hash {
                next[last as usize - 1] = k as u32;
                table[s].1 = id;
                break;
            }
            s = (s + 1) & mask;
        }
    }
    let mut chained = Vec::with_capacity(n);
    for &(first, _) in &table {
        if first == 0 {
            continue;
        }
        let mut k = first as usize - 1;
        loop {
            chained.push(order[k]);
            match next[k] {
                END => break,
                j => k = j as usize,
            }
        }
    }
    *order = chained;
}

/// How the heads of some groups ([`head`]) pack into one word: each part as wide as its
/// largest value among them needs, the class bit above `a`, above `b`, above `cof`, so that
/// the words compare as the heads do.
#[derive(Clone, Copy)]
struct Packing {
    a: u32,
    b: u32,
    cof: u32,
}

impl Packing {
    /// The packing of the heads of `groups`; `None` when they need more than 64 bits.
    fn of(groups: &[(u128, usize, usize)]) -> Option<Packing> {
        let width = |shift: u32| {
            let max = groups
                .iter()
                .map(|g| (g.0 >> shift) as u32)
                .max()
                .unwrap_or(0);
            u32::BITS - max.leading_zeros()
        };
        let p = Packing {
            a: width(64),
            b: width(32),
            cof: width(0),
        };
        (p.bits() <= 64).then_some(p)
    }

    /// The bits of a packed head.
    fn bits(self) -> u32 {
        1 + self.a + self.b + self.cof
    }

    /// The head `h` packed.
    fn pack(self, h: u128) -> u64 {
        let part = |shift: u32| u64::from((h >> shift) as u32);
        let class = (h >> 96) as u64;
        class << (self.a + self.b + self.cof)
            | part(64) << (self.b + self.cof)
            | part(32) << self.cof
            | part(0)
    }
}

/// The groups of pairs that can combine: `entries[range]` for each range, in key order.
struct Groups {
    entries: Vec<Entry>,
    ranges: Vec<std::ops::Range<usize>>,
}

/// The part `(class, a, b, cof)` of the key of `e`, packed so that integers compare as
/// [`key_cmp`] compares that part.
fn head(e: &Entry) -> u128 {
    u128::from(e.class == Class::Sin) << 96
        | u128::from(e.a) << 64
        | u128::from(e.b) << 32
        | u128::from(e.cof)
}

/// Compares the atoms of `x` other than those at `xp < xq` with those of `y` other than those
/// at `yp < yq`, lexicographically.
fn rest_cmp(x: &[Atom], xp: usize, xq: usize, y: &[Atom], yp: usize, yq: usize) -> Ordering {
    let skip = |mut k: usize, p: usize, q: usize| {
        if k == p {
            k += 1;
        }
        if k == q {
            k += 1;
        }
        k
    };
    let (mut i, mut j) = (skip(0, xp, xq), skip(0, yp, yq));
    loop {
        match (x.get(i), y.get(j)) {
            (None, None) => return Ordering::Equal,
            (None, Some(_)) => return Ordering::Less,
            (Some(_), None) => return Ordering::Greater,
            (Some(a), Some(b)) => {
                if a != b {
                    return a.cmp(b);
                }
            }
        }
        i = skip(i + 1, xp, xq);
        j = skip(j + 1, yp, yq);
    }
}

/// The key order; `cof` ranks `(rad, syms)`, so it stands for comparing them.
fn key_cmp(mons: &[Mon], x: &Entry, y: &Entry) -> Ordering {
    x.class
        .cmp(&y.class)
        .then(x.a.cmp(&y.a))
        .then(x.b.cmp(&y.b))
        .then(x.cof.cmp(&y.cof))
        .then_with(|| {
            if x.i == y.i && x.p == y.p && x.q == y.q {
                return Ordering::Equal;
            }
            let ((xp, xq), (yp, yq)) = (x.atoms(), y.atoms());
            rest_cmp(&mons[x.mon()].atoms, xp, xq, &mons[y.mon()].atoms, yp, yq)
        })
}

/// The order of the cofactors `(rad, syms)` of two monomials.
fn cof_cmp(a: &Mon, b: &Mon) -> Ordering {
    a.rad.cmp(&b.rad).then_with(|| a.syms.cmp(&b.syms))
}

/// The rank of each monomial's cofactor `(rad, syms)` among those of `mons`.
///
/// The monomials come sorted from `merge`: each is compared once with the one before it, its
/// rank the number of rises so far, which is what ranking them in their own order gives.
/// Out of order (a fall), they are ranked by [`sorted_cofactor_ranks`] instead, as they
/// always were: the check that they were sorted was a pass of its own over the same
/// comparisons.
fn cofactor_ranks(mons: &[Mon]) -> Vec<u32> {
    let mut rank = vec![0u32; mons.len()];
    let mut r = 0u32;
    for k in 1..mons.len() {
        match cof_cmp(&mons[k - 1], &mons[k]) {
            Ordering::Less => r += 1,
            Ordering::Equal => {}
            Ordering::Greater => return sorted_cofactor_ranks(mons),
        }
        rank[k] = r;
    }
    rank
}

/// [`cofactor_ranks`] of monomials in any order: their indices sorted by cofactor, then
/// ranked in that order.
fn sorted_cofactor_ranks(mons: &[Mon]) -> Vec<u32> {
    let mut order: Vec<usize> = (0..mons.len()).collect();
    order.sort_by(|&a, &b| cof_cmp(&mons[a], &mons[b]));
    let mut rank = vec![0u32; mons.len()];
    let mut r = 0u32;
    for k in 1..order.len() {
        if cof_cmp(&mons[order[k - 1]], &mons[order[k]]).is_ne() {
            r += 1;
        }
        rank[order[k]] = r;
    }
    rank
}

/// Applies the angle-sum identities until no pair of monomials combines.
pub(crate) fn recombine(ctx: &mut Ctx, mons: Vec<Mon>) -> Vec<Mon> {
    recombine_traced(ctx, mons, &mut None)
}

/// [`recombine`], telling `rec` (when there is one) each round's sum and every identity applied.
pub(crate) fn recombine_traced(
    ctx: &mut Ctx,
    mons: Vec<Mon>,
    rec: &mut Option<&mut Recorder>,
) -> Vec<Mon> {
    let pass = first_pass(&mons);
    rounds(ctx, mons, rec, pass)
}

/// The rounds of [`recombine_traced`], beginning with `pass` (with [`Pass::Low`], its rounds
/// until nothing joins, then the all-pairs rounds).
///
/// Incremental rounds were tried and do not pay. Two monomials that a round leaves unused and
/// that `merge` leaves unchanged cannot join in the next round: the round goes through every
/// group that pairs, and when it comes to one, each still unused monomial looks for an unused
/// partner of the other kind with `q` equal or opposite (monomials only ever become used), so
/// two such monomials sharing a group would not both have been left; their keys agree in the
/// next round exactly when they did (the renumbering is one to one, the cofactor ranks rank
/// the same `(rad, syms)`), their kinds stay different and their `q` the same. (The low pass
/// is the exception: a renumbering can change which two atoms come first.) So only groups
/// with a new or merged monomial need forming; but on `fk --jacobian
/// tests/data/jaco_style.toml` 4,790 of the 4,892 monomials of the 247 rounds are new or
/// merged (nearly every monomial joins in each round), 22,024 of the 22,420 pairs theirs,
/// and the groups that only old monomials form were 54 of 9,702 entries kept: marking the
/// new monomials through `merge` and a third bit set in [`groups`] cost 125.21 M instructions
/// against 124.51 M.
fn rounds(
    ctx: &mut Ctx,
    mut mons: Vec<Mon>,
    rec: &mut Option<&mut Recorder>,
    mut pass: Pass,
) -> Vec<Mon> {
    // Each round strictly lowers the number of monomials or stops (the low pass once, then
    // the usual rounds), so this terminates.
    let mut fresh = true;
    loop {
        if fresh {
            if let Some(r) = rec.as_deref_mut() {
                r.round(ctx, &mons);
            }
        }
        let (mut next, changed) = round(ctx, std::mem::take(&mut mons), rec, pass);
        // Nothing joined in the low pass: the same sum again with every pair tried, its round
        // not told twice.
        if !changed && pass == Pass::Low {
            mons = next;
            pass = Pass::All;
            fresh = false;
            continue;
        }
        fresh = true;
        if let Some(map) = ctx.renumber() {
            for m in &mut next {
                remap(m, &map);
            }
        } else {
            for m in &mut next {
                m.atoms.sort_unstable();
            }
        }
        mons = merge(next);
        if !changed {
            return mons;
        }
    }
}

/// The fewest pairs a monomial, on average, for which the rounds begin with the low pass:
/// 15, monomials of six atoms.
///
/// The greedy rounds over every pair join each monomial by whichever of its pairs comes first
/// in key order, so the monomials of a long split product (the Jaco-style arm's 96-term
/// components: 1,152 monomials of six atoms) join along different angles and meet no partner
/// afterwards: 180 left where 72 can be. Joining first by each monomial's two lowest atoms
/// joins them all alike: 1,152 -> 144 -> 72, and the later all-pairs rounds are on 144
/// monomials, not 1,152. The low pass costs a round of one pair a monomial, a fifteenth of an
/// all-pairs round or less, when nothing joins; below the bound the monomials are short,
/// their all-pairs rounds cheap, and the pass seldom joins much. Callgrind, one thread, fast
/// builds: `fk --jacobian tests/data/jaco_style.toml` 481.4 M -> 430.3 M instructions (430.6 M
/// at 10 pairs, 430.7 M at 1); the PUMA 560's 37.54 M -> 37.73 M (eight calls of 15 pairs a
/// monomial, where it joins nothing; 38.0 M at 1). At 10 pairs one expression of 300 of
/// `scripts/offsets_same.py` (products of sines of sums of angles plus `k pi/9`) ran out of
/// its default work budget at a longer form; none at 15.
const LOW_PASS_PAIRS: usize = 15;

/// The fewest monomials for which the rounds begin with the low pass (with
/// [`LOW_PASS_PAIRS`]): below it an all-pairs round tries fewer than ~2,000 pairs, and the
/// low pass saves little while it changes which of two forms of equal cost the search meets
/// first. With no such bound the UR3, UR5 and UR10 reports (`fk --jacobian`, sums of 32
/// monomials of six atoms) printed 9 entries each with the same summands in another order
/// (a leading minus); from 128 they print as before, and the gain is kept: the Jaco-style
/// arm's sums of 1,152 and 192 monomials (318.3 M instructions; 324.3 M from 256), the UR5's
/// long DQ entries 13% shorter in text (their regrouped shapes win now).
const LOW_PASS_MONOMIALS: usize = 128;

/// The pass the rounds of `mons` begin with: [`Pass::Low`] when there are at least
/// [`LOW_PASS_MONOMIALS`] and the all-pairs rounds try at least [`LOW_PASS_PAIRS`] pairs a
/// monomial.
fn first_pass(mons: &[Mon]) -> Pass {
    if mons.len() >= LOW_PASS_MONOMIALS && Pass::All.pairs(mons) >= LOW_PASS_PAIRS * mons.len() {
        Pass::Low
    } else {
        Pass::All
    }
}

/// The combined atom for angles `a + sign * b`: `None` for the zero angle, else the new angle's
/// id and whether it was negated to normalize it.
type Combined = Option<(u32, bool)>;

/// One round of `pass` on `mons`: the monomials, each pair that joins replaced by its
/// combination (unordered, unmerged), and whether any pair joined (when none did, `mons` as
/// they were).
///
/// The round owns `mons`, so that a monomial is moved, not copied, to where it goes: the first
/// of each pair that joins (its atoms then changed) is taken out of `mons` and a placeholder
/// ([`taken`]) left, and the monomials that join nothing are moved in their order after the
/// combinations, where each was cloned. A monomial that has joined is never read again:
/// `used` marks it, the partner search skips it, and the signs compared are those of
/// monomials not yet used. So the monomials and their order are those of the clones
/// (`tests::moved_round_is_the_cloning_round`).
fn round(
    ctx: &mut Ctx,
    mut mons: Vec<Mon>,
    rec: &mut Option<&mut Recorder>,
    pass: Pass,
) -> (Vec<Mon>, bool) {
    let cof = cofactor_ranks(&mons);
    let pairs = pass.pairs(&mons);
    // The round's work, charged before it is done; out of budget or cancelled, the round
    // changes nothing and the error comes from the closed form's next charge.
    if crate::scalar::charge((mons.len() + pairs) as u64).is_err() {
        return (mons, false);
    }
    let groups = groups(&mons, &cof, pairs_of(&mons, &cof, pairs, pass));
    if groups.ranges.is_empty() {
        return (mons, false);
    }
    let mut used = vec![false; mons.len()];
    let mut out = Vec::with_capacity(mons.len());
    let mut changed = false;
    let mut combined: FxMap<(u32, u32, i64), Combined> = FxMap::default();
    for range in &groups.ranges {
        let entries = &groups.entries[range.clone()];
        let (class, a, b) = (entries[0].class, entries[0].a, entries[0].b);
        for e in entries {
            let (i, i_sin) = (e.mon(), e.sin);
            if used[i] {
                continue;
            }
            // The partner has both atoms of the other kind (Cos class) or swapped (Sin class).
            let partner = entries.iter().find(|f| {
                !used[f.mon()] && f.mon() != i && f.sin != i_sin && {
                    let (qi, qj) = (&mons[i].q, &mons[f.mon()].q);
                    qi == qj || *qi == -qj
                }
            });
            let Some(partner) = partner else {
                continue;
            };
            let (j, (pj, qj)) = (partner.mon(), partner.atoms());
            let Some((pi, qi)) = entries.iter().find(|f| f.mon() == i).map(Entry::atoms) else {
                continue;
            };
            // Orient: `first` is cos a cos b (Cos) or sin a cos b (Sin).
            let (first, second) = if i_sin == (class == Class::Sin) {
                ((i, pi, qi), (j, pj, qj))
            } else {
                ((j, pj, qj), (i, pi, qi))
            };
            let same_sign = mons[first.0].q == mons[second.0].q;
            // cc + ss = cos(a - b); cc - ss = cos(a + b); sc + cs = sin(a + b); sc - cs = sin(a - b).
            let sign = match (class, same_sign) {
                (Class::Cos, true) | (Class::Sin, false) => -1,
                _ => 1,
            };
            let c = *combined.entry((a, b, sign)).or_insert_with(|| {
                let (x, y) = (&ctx.angles[a as usize], &ctx.angles[b as usize]);
                angle_combine(x, y, sign).map(|(angle, flipped)| (ctx.intern(angle), flipped))
            });
            let sin = class == Class::Sin;
            let mut base = std::mem::replace(&mut mons[first.0], taken());
            base.atoms.remove(first.2);
            base.atoms.remove(first.1);
            if let Some(r) = rec.as_deref_mut() {
                r.apply(
                    ctx,
                    &AngleSum {
                        sin,
                        sign,
                        a,
                        b,
                        terms: [first.0, second.0],
                        cofactor: &base,
                        combined: c,
                    },
                );
            }
            used[i] = true;
            used[j] = true;
            changed = true;
            match c {
                // cos 0 = 1, sin 0 = 0.
                None => {
                    if !sin {
                        out.push(base);
                    }
                }
                Some((id, flipped)) => {
                    // The atoms are put in order after the renumbering.
                    base.atoms.push(atom(id, sin));
                    if sin && flipped {
                        base.q = -&base.q;
                    }
                    out.push(base);
                }
            }
        }
    }
    if !changed {
        return (mons, false);
    }
    out.extend(
        mons.into_iter()
            .zip(used)
            .filter_map(|(m, used)| (!used).then_some(m)),
    );
    (out, true)
}

/// What [`round`] leaves in place of a monomial it has moved out: never read (a monomial
/// that has joined is marked used), only dropped.
fn taken() -> Mon {
    Mon {
        q: Q::default(),
        rad: 0,
        syms: Syms::new(),
        atoms: Atoms::new(),
    }
}

#[cfg(test)]
mod tests;
