use super::*;
use crate::closed::mon::{Atoms, Syms};
use crate::scalar::q::Q;
use crate::scalar::Scalar;
use crate::testing::xorshift_below;

/// `groups` as it was before it left out the hashes without entries of both kinds: every
/// entry sorted, then the same runs.
fn all_sorted(mons: &[Mon], index: Vec<Entry>) -> Vec<Vec<Entry>> {
    let mut order: Vec<(u64, usize)> = index.iter().enumerate().map(|(k, e)| (e.hash, k)).collect();
    order.sort_unstable();
    let mut index: Vec<Entry> = order.iter().map(|&(_, k)| index[k]).collect();
    let mut groups: Vec<Vec<Entry>> = Vec::new();
    for run in index.chunk_by_mut(|x, y| x.hash == y.hash) {
        run.sort_by(|x, y| key_cmp(mons, x, y));
        for g in run.chunk_by(|x, y| key_cmp(mons, x, y).is_eq()) {
            if g.iter().any(|e| e.sin) && g.iter().any(|e| !e.sin) {
                groups.push(g.to_vec());
            }
        }
    }
    groups.sort_by(|x, y| key_cmp(mons, &x[0], &y[0]));
    groups
}

/// The groups of `mons` by [`groups`] and by [`all_sorted`], as `(i, p, q)` lists.
fn both_ways(mons: &[Mon]) -> [Vec<Vec<(usize, usize, usize)>>; 2] {
    let cof = cofactor_ranks(mons);
    let all = pairs_of(mons, &cof, 0, Pass::All);
    let index = all.iter().map(|x| x.entry(mons, &cof)).collect();
    let ids = |gs: Vec<Vec<Entry>>| -> Vec<Vec<(usize, usize, usize)>> {
        gs.iter()
            .map(|g| {
                g.iter()
                    .map(|e| (e.mon(), e.atoms().0, e.atoms().1))
                    .collect()
            })
            .collect()
    };
    let expected = ids(all_sorted(mons, index));
    let found = groups(mons, &cof, all);
    let found = found
        .ranges
        .iter()
        .map(|r| found.entries[r.clone()].to_vec())
        .collect();
    [ids(found), expected]
}

/// `count` random monomials of 2 to `2 + extra - 1` atoms over `angles` angles.
fn random_mons(
    below: &mut impl FnMut(u64) -> u64,
    count: u64,
    extra: u64,
    angles: u64,
) -> Vec<Mon> {
    (0..count)
        .map(|_| {
            let mut atoms: Atoms = (0..2 + below(extra))
                .map(|_| atom(below(angles) as u32, below(2) == 1))
                .collect();
            atoms.sort_unstable();
            Mon {
                q: Q::int(if below(2) == 0 { -1 } else { 1 }),
                rad: 1 + below(2),
                syms: Syms::new(),
                atoms,
            }
        })
        .collect()
}

/// The groups of `mons` by [`groups`] and formed by their keys alone, with no hash: every
/// entry sorted by key, stably (so each key's entries in the order found), the groups that
/// pair kept, in key order; as `(i, p, q)` lists. Also checks that entries with equal keys
/// have equal hashes, as [`groups`] needs.
fn by_keys(mons: &[Mon]) -> [Vec<Vec<(usize, usize, usize)>>; 2] {
    let cof = cofactor_ranks(mons);
    let all = pairs_of(mons, &cof, 0, Pass::All);
    let mut index: Vec<Entry> = all.iter().map(|x| x.entry(mons, &cof)).collect();
    for e in &index {
        for f in &index {
            if key_cmp(mons, e, f).is_eq() {
                assert_eq!(e.hash, f.hash);
            }
        }
    }
    index.sort_by(|x, y| key_cmp(mons, x, y));
    let ids = |g: &[Entry]| -> Vec<(usize, usize, usize)> {
        g.iter()
            .map(|e| (e.mon(), e.atoms().0, e.atoms().1))
            .collect()
    };
    let expected = index
        .chunk_by(|x, y| key_cmp(mons, x, y).is_eq())
        .filter(|g| g.iter().any(|e| e.sin) && g.iter().any(|e| !e.sin))
        .map(ids)
        .collect();
    let found = groups(mons, &cof, all);
    let found = found
        .ranges
        .iter()
        .map(|r| ids(&found.entries[r.clone()]))
        .collect();
    [found, expected]
}

/// The groups (hashed by the sums of [`pairs_of`]) are those formed by the keys alone, on
/// random monomials, few and many, with two cofactors.
#[test]
fn groups_are_those_of_the_keys_alone() {
    let mut below = xorshift_below(0x4a5d_c0f1);
    let mut pairing = 0;
    for case in 0..200 {
        let count = 1 + below(if case % 8 == 0 { 400 } else { 30 });
        let angles = 3 + below(3);
        let mut mons = random_mons(&mut below, count, 4, angles);
        for m in &mut mons {
            m.rad = 1 + below(2);
        }
        let mons = merge(mons);
        let [found, expected] = by_keys(&mons);
        pairing += usize::from(!expected.is_empty());
        assert_eq!(found, expected, "case {case}");
    }
    assert!(pairing > 30 && pairing < 200, "{pairing} of 200 pair");
}

#[test]
fn groups_are_those_of_sorting_every_entry() {
    let mut below = xorshift_below(0x5eed_9a1f);
    let mut pairing = 0;
    for _ in 0..300 {
        // Few angles, cofactors and coefficients, so that many pairs share a key.
        let count = 1 + below(24);
        let mons = random_mons(&mut below, count, 3, 3);
        let [found, expected] = both_ways(&mons);
        pairing += usize::from(!expected.is_empty());
        assert_eq!(found, expected);
    }
    // Both outcomes occur: monomials that pair and monomials that do not.
    assert!(pairing > 60 && pairing < 300, "{pairing} of 300 pair");
}

#[test]
fn many_groups_sorted_by_counting_passes_are_those_of_sorting_every_entry() {
    let mut below = xorshift_below(0x0ddb_a11e);
    for angles in [10, 14, 20] {
        // Enough entries and groups for `by_hash` and the counting passes of `radix_sort`.
        let mons = random_mons(&mut below, 5000, 3, angles);
        let [found, expected] = both_ways(&mons);
        assert!(found.len() >= RADIX_MIN, "{} groups", found.len());
        assert_eq!(found, expected);
    }
}

/// Every pair of atoms of two angles is listed once, each with its first atom's sine bit,
/// and the bit stored above `q` leaves pairs in the order of `(hash, i, p, q)`.
#[test]
fn pairs_are_listed_once_and_order_by_their_places() {
    let mut below = xorshift_below(0x9a1e_5eed);
    // Few angles: many pairs of one monomial share a hash.
    let mons = random_mons(&mut below, 400, 6, 4);
    let cof = cofactor_ranks(&mons);
    let mut pairs = pairs_of(&mons, &cof, 0, Pass::All);
    let mut expected = Vec::new();
    for (i, m) in mons.iter().enumerate() {
        for p in 0..m.atoms.len() {
            for q in p + 1..m.atoms.len() {
                if angle_of(m.atoms[p]) != angle_of(m.atoms[q]) {
                    expected.push((i, p, q, is_sin(m.atoms[p])));
                }
            }
        }
    }
    let found: Vec<(usize, usize, usize, bool)> = pairs
        .iter()
        .map(|x| {
            let e = x.entry(&mons, &cof);
            (e.mon(), e.atoms().0, e.atoms().1, e.sin)
        })
        .collect();
    assert_eq!(found, expected);
    let place = |x: &Pair| {
        let e = x.entry(&mons, &cof);
        (x.hash, e.i, e.p, e.q)
    };
    let mut by_place = pairs.clone();
    by_place.sort_by_key(place);
    pairs.sort_unstable();
    assert_eq!(pairs, by_place);
}

/// The sum of `mons` as a scalar.
fn sum_of(ctx: &Ctx, mons: &[Mon]) -> Scalar {
    mons.iter().fold(Scalar::int(0), |s, m| {
        s + crate::closed::factor::mon_expr(m).to_expr(ctx).to_scalar()
    })
}

/// `cos` (or `sin`) of `q1 + ... + qn`, plus `k pi / 7` when `k` is not 0.
fn long_angle(n: usize, k: i64, sin: bool) -> Scalar {
    let mut a = (1..=n).fold(Scalar::int(0), |s, j| s + Scalar::sym(&format!("q{j}")));
    if k != 0 {
        a = a + Scalar::pi() * Scalar::from_q(Q::new(k, 7));
    }
    if sin {
        a.sin()
    } else {
        a.cos()
    }
}

/// The split shape of `x` recombined beginning with the low pass and with the all-pairs
/// rounds only, each with its context.
fn both_passes(x: &Scalar) -> [(Ctx, Vec<Mon>); 2] {
    [Pass::Low, Pass::All].map(|pass| {
        let (mut ctx, mons) = crate::closed::mon::split_modes(x);
        let mons = rounds(&mut ctx, mons, &mut None, pass);
        (ctx, mons)
    })
}

/// On long sums of angles, split into products of single angles, the low pass's result
/// is the same scalar, exactly, and has no more monomials than the all-pairs rounds'.
#[test]
fn low_pass_keeps_the_scalar_and_leaves_no_more_monomials() {
    let l = Scalar::sym("a2");
    for n in 3..=7 {
        for k in [0, 1, 3] {
            let shapes = [
                long_angle(n, k, false),
                long_angle(n, k, true),
                l.clone() * long_angle(n, k, false) + long_angle(n, -k, true),
                long_angle(n, k, false) * long_angle(3, 0, true),
            ];
            for x in &shapes {
                let [(lctx, low), (actx, all)] = both_passes(x);
                assert_eq!(sum_of(&lctx, &low), *x, "n {n}, k {k}");
                assert_eq!(sum_of(&actx, &all), *x, "n {n}, k {k}");
                assert!(low.len() <= all.len(), "{} > {}", low.len(), all.len());
            }
        }
    }
}

/// Where the all-pairs rounds join the monomials of a long split product along different
/// angles and leave them apart, the low pass joins them all: `cos(q1 + ... + q6)` split
/// into 32 monomials comes back whole (the all-pairs rounds leave 4), and
/// `cos(q1 + q2 + q3 + pi/7) sin(q4 + q5 + q6)` (64) to fewer monomials than the all-pairs
/// rounds leave (12). The rule takes the low pass on `cos(q1 + ... + q8)` (128 monomials
/// of eight atoms), not on those two (fewer than [`LOW_PASS_MONOMIALS`]).
#[test]
fn low_pass_joins_long_split_products_that_the_all_pairs_rounds_leave_apart() {
    let whole = long_angle(6, 0, false);
    let shifted = long_angle(3, 1, false)
        * (4..=6)
            .fold(Scalar::int(0), |s, j| s + Scalar::sym(&format!("q{j}")))
            .sin();
    let rule = |x: &Scalar| first_pass(&crate::closed::mon::split_modes(x).1);
    let eight = long_angle(8, 0, false);
    assert_eq!(crate::closed::mon::split_modes(&eight).1.len(), 128);
    assert_eq!(rule(&eight), Pass::Low);
    assert_eq!(rule(&whole), Pass::All);
    assert_eq!(rule(&shifted), Pass::All);
    for x in [&whole, &shifted, &eight] {
        let [(lctx, low), (actx, all)] = both_passes(x);
        assert_eq!(sum_of(&lctx, &low), *x);
        assert_eq!(sum_of(&actx, &all), *x);
        assert!(low.len() < all.len(), "{} >= {}", low.len(), all.len());
    }
    let [(_, low), _] = both_passes(&whole);
    assert_eq!(low.len(), 1);
}

/// [`round`] as it was before it moved the monomials: each one that goes out cloned from
/// `mons`, `None` when nothing joins.
fn cloning_round(
    ctx: &mut Ctx,
    mons: &[Mon],
    rec: &mut Option<&mut Recorder>,
    pass: Pass,
) -> Option<Vec<Mon>> {
    let cof = cofactor_ranks(mons);
    let pairs = pass.pairs(mons);
    if crate::scalar::charge((mons.len() + pairs) as u64).is_err() {
        return None;
    }
    let groups = groups(mons, &cof, pairs_of(mons, &cof, pairs, pass));
    if groups.ranges.is_empty() {
        return None;
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
            let (first, second) = if i_sin == (class == Class::Sin) {
                ((i, pi, qi), (j, pj, qj))
            } else {
                ((j, pj, qj), (i, pi, qi))
            };
            let same_sign = mons[first.0].q == mons[second.0].q;
            let sign = match (class, same_sign) {
                (Class::Cos, true) | (Class::Sin, false) => -1,
                _ => 1,
            };
            let c = *combined.entry((a, b, sign)).or_insert_with(|| {
                let (x, y) = (&ctx.angles[a as usize], &ctx.angles[b as usize]);
                angle_combine(x, y, sign).map(|(angle, flipped)| (ctx.intern(angle), flipped))
            });
            let sin = class == Class::Sin;
            let mut base = mons[first.0].clone();
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
                None => {
                    if !sin {
                        out.push(base);
                    }
                }
                Some((id, flipped)) => {
                    base.atoms.push(atom(id, sin));
                    if sin && flipped {
                        base.q = -&base.q;
                    }
                    out.push(base);
                }
            }
        }
    }
    for (i, m) in mons.iter().enumerate() {
        if !used[i] {
            out.push(m.clone());
        }
    }
    changed.then_some(out)
}

/// The round that moves the monomials gives the cloning round's monomials in its order,
/// and interns the same angles, on random monomials over the angles of a real context
/// (`q1` to `q6` and their sums), both passes; the signs `+-1` and `+-2`, so that some
/// pairs of equal atoms do not join.
#[test]
fn moved_round_is_the_cloning_round() {
    let mut below = xorshift_below(0x3071_5eed);
    let x = long_angle(6, 1, false) * long_angle(2, 0, true) + long_angle(3, 2, true);
    let (ctx, _) = crate::closed::mon::split_modes(&x);
    let angles = ctx.angles.len() as u64;
    assert!(angles >= 6, "{angles} angles");
    let mut joined = 0;
    for case in 0..400 {
        let count = 1 + below(if case % 10 == 0 { 300 } else { 30 });
        let some = angles.min(4 + below(4));
        let mut mons = random_mons(&mut below, count, 4, some);
        for m in &mut mons {
            m.q = Q::int([-2, -1, 1, 2][below(4) as usize]);
        }
        let mons = crate::closed::mon::merge(mons);
        for pass in [Pass::Low, Pass::All] {
            let (mut moved_ctx, mut cloned_ctx) = (ctx.clone(), ctx.clone());
            let (moved, changed) = round(&mut moved_ctx, mons.clone(), &mut None, pass);
            let cloned = cloning_round(&mut cloned_ctx, &mons, &mut None, pass);
            assert_eq!(changed, cloned.is_some(), "case {case}");
            assert_eq!(moved, cloned.unwrap_or_else(|| mons.clone()), "case {case}");
            assert!(moved_ctx.angles == cloned_ctx.angles, "case {case}");
            joined += usize::from(changed);
        }
    }
    // Both outcomes occur: rounds that join and rounds that do not.
    assert!(joined > 100 && joined < 800, "{joined} of 800 join");
}

/// [`cofactor_ranks`] as it was: the indices sorted by cofactor (when the monomials are
/// not in order), then ranked in that order.
fn ranks_by_sorting(mons: &[Mon]) -> Vec<u32> {
    let mut order: Vec<usize> = (0..mons.len()).collect();
    if !mons.is_sorted_by(|a, b| cof_cmp(a, b).is_le()) {
        order.sort_by(|&a, &b| cof_cmp(&mons[a], &mons[b]));
    }
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

/// The ranks of one pass over sorted monomials, and of the fallback over others, are
/// those of sorting the indices, on monomials of few cofactors, sorted and not.
#[test]
fn cofactor_ranks_are_those_of_sorting() {
    let mut below = xorshift_below(0xc0fa_5eed);
    let mut sorted = 0;
    for case in 0..400 {
        let count = below(40);
        let mut mons = random_mons(&mut below, count, 2, 3);
        for m in &mut mons {
            m.rad = 1 + below(2);
            m.syms = (0..below(3)).map(|_| (below(2) as u32, 1)).collect();
        }
        if case % 2 == 0 {
            mons.sort_by(cof_cmp);
        }
        sorted += usize::from(mons.is_sorted_by(|a, b| cof_cmp(a, b).is_le()));
        assert_eq!(
            cofactor_ranks(&mons),
            ranks_by_sorting(&mons),
            "case {case}"
        );
    }
    assert!(sorted > 150 && sorted < 400, "{sorted} of 400 sorted");
}

/// [`by_hash`] leaves each hash's pairs together, in the order in which they were found:
/// ordered stably by hash, its result is the pairs sorted. Hashes from a few values (long
/// chains) and from values that share their table slots (long probes), and the sizes
/// around the table's.
#[test]
fn by_hash_keeps_each_hash_together_in_found_order() {
    let mut below = xorshift_below(0xb1_a5ed);
    for case in 0..300 {
        let n = match case % 3 {
            0 => below(8),
            1 => below(200),
            _ => 500 + below(3000),
        };
        let values = 1 + below(n.max(1) * 2);
        // Multiples of 2^58 share the top bits of their products, so their slots.
        let spread = if case % 5 == 0 { 1 << 58 } else { 0x9e37_79b9 };
        let pairs: Vec<Pair> = (0..n)
            .map(|k| Pair {
                hash: below(values).wrapping_mul(spread),
                ..Pair::new(
                    k as u32,
                    below(7) as u16,
                    7 + below(7) as u16,
                    below(2) == 1,
                )
            })
            .collect();
        let mut found = pairs.clone();
        by_hash(&mut found);
        let runs: Vec<u64> = found
            .chunk_by(|x, y| x.hash == y.hash)
            .map(|r| r[0].hash)
            .collect();
        let mut distinct = runs.clone();
        distinct.sort_unstable();
        distinct.dedup();
        assert_eq!(
            runs.len(),
            distinct.len(),
            "case {case}: a hash in two runs"
        );
        found.sort_by_key(|x| x.hash);
        let mut expected = pairs;
        expected.sort_unstable();
        assert_eq!(found, expected, "case {case}");
    }
}

#[test]
fn radix_sort_is_a_stable_sort_by_the_key() {
    let mut below = xorshift_below(0xface_5eed);
    for bits in [1, 8, 13, 29, 64] {
        let mask = if bits == 64 {
            u64::MAX
        } else {
            (1u64 << bits) - 1
        };
        let mut v: Vec<(u64, usize)> = (0..2000)
            .map(|k| (below(1 << 20).wrapping_mul(0x9e37_79b9_7f4a_7c15) & mask, k))
            .collect();
        let mut expected = v.clone();
        expected.sort_by_key(|&(key, _)| key);
        radix_sort(&mut v, bits, |&(key, _)| key);
        assert_eq!(v, expected);
    }
}

#[test]
fn packed_heads_compare_as_the_heads() {
    let mut below = xorshift_below(0x0004_ead5);
    let groups: Vec<(u128, usize, usize)> = (0..1000)
        .map(|k| {
            let e = Entry {
                class: if below(2) == 0 {
                    Class::Cos
                } else {
                    Class::Sin
                },
                a: below(700) as u32,
                b: below(90) as u32,
                cof: below(5000) as u32,
                i: 0,
                sin: false,
                p: 0,
                q: 1,
                hash: 0,
            };
            (head(&e), k, k)
        })
        .collect();
    let p = Packing::of(&groups).expect("fits one word");
    for x in &groups[..100] {
        for y in &groups {
            assert_eq!(p.pack(x.0).cmp(&p.pack(y.0)), x.0.cmp(&y.0));
        }
    }
}
