//! Angle-sum recombination: `T cos a cos b - T sin a sin b -> T cos(a + b)` and its three
//! siblings, for any cofactor `T` (lengths, other trigonometric factors, numbers), repeated
//! until nothing pairs up, so `c1 c2 c3 - ...` regroups to `c123` at any depth.

use super::mon::{angle_combine, angle_of, atom, is_sin, merge, remap, Atom, Ctx, Mon};
use super::trace::{AngleSum, Recorder};
use std::cmp::Ordering;
use std::collections::HashMap;

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
#[derive(Clone, Copy, Debug)]
struct Entry {
    class: Class,
    a: u32,
    b: u32,
    i: usize,
    /// The first atom is a sine.
    sin: bool,
    p: usize,
    q: usize,
}

/// The atoms of `m` other than those at `p` and `q`.
fn rest(m: &Mon, p: usize, q: usize) -> impl Iterator<Item = &Atom> {
    m.atoms
        .iter()
        .enumerate()
        .filter(move |&(k, _)| k != p && k != q)
        .map(|(_, a)| a)
}

fn key_cmp(mons: &[Mon], x: &Entry, y: &Entry) -> Ordering {
    x.class
        .cmp(&y.class)
        .then(x.a.cmp(&y.a))
        .then(x.b.cmp(&y.b))
        .then_with(|| {
            if x.i == y.i && x.p == y.p && x.q == y.q {
                return Ordering::Equal;
            }
            let (m, n) = (&mons[x.i], &mons[y.i]);
            m.rad
                .cmp(&n.rad)
                .then_with(|| m.syms.cmp(&n.syms))
                .then_with(|| rest(m, x.p, x.q).cmp(rest(n, y.p, y.q)))
        })
}

/// Applies the angle-sum identities until no pair of monomials combines.
pub(crate) fn recombine(ctx: &mut Ctx, mons: Vec<Mon>) -> Vec<Mon> {
    recombine_traced(ctx, mons, &mut None)
}

/// [`recombine`], telling `rec` (when there is one) each round's sum and every identity applied.
pub(crate) fn recombine_traced(
    ctx: &mut Ctx,
    mut mons: Vec<Mon>,
    rec: &mut Option<&mut Recorder>,
) -> Vec<Mon> {
    // Each round strictly lowers the number of monomials or stops, so this terminates.
    loop {
        if let Some(r) = rec.as_deref_mut() {
            r.round(ctx, &mons);
        }
        let (mut next, changed) = round(ctx, &mons, rec);
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

/// The combined atom for angles `a + sign * b`: `None` for the zero angle, else the new angle's
/// id and whether it was negated to normalize it.
type Combined = Option<(u32, bool)>;

fn round(ctx: &mut Ctx, mons: &[Mon], rec: &mut Option<&mut Recorder>) -> (Vec<Mon>, bool) {
    let mut index: Vec<Entry> = Vec::new();
    for (i, m) in mons.iter().enumerate() {
        for p in 0..m.atoms.len() {
            for q in p + 1..m.atoms.len() {
                let (a, b) = (m.atoms[p], m.atoms[q]);
                if angle_of(a) == angle_of(b) {
                    continue;
                }
                let class = if is_sin(a) == is_sin(b) {
                    Class::Cos
                } else {
                    Class::Sin
                };
                index.push(Entry {
                    class,
                    a: angle_of(a),
                    b: angle_of(b),
                    i,
                    sin: is_sin(a),
                    p,
                    q,
                });
            }
        }
    }
    // Stable: within a key, the entries keep the order in which they were found.
    index.sort_by(|x, y| key_cmp(mons, x, y));
    let mut used = vec![false; mons.len()];
    let mut out = Vec::new();
    let mut changed = false;
    let mut combined: HashMap<(u32, u32, i64), Combined> = HashMap::new();
    let mut start = 0;
    while start < index.len() {
        let mut end = start + 1;
        while end < index.len() && key_cmp(mons, &index[start], &index[end]).is_eq() {
            end += 1;
        }
        let entries = &index[start..end];
        start = end;
        let (class, a, b) = (entries[0].class, entries[0].a, entries[0].b);
        for e in entries {
            let (i, i_sin) = (e.i, e.sin);
            if used[i] {
                continue;
            }
            // The partner has both atoms of the other kind (Cos class) or swapped (Sin class).
            let partner = entries.iter().find(|f| {
                !used[f.i] && f.i != i && f.sin != i_sin && {
                    let (qi, qj) = (&mons[i].q, &mons[f.i].q);
                    qi == qj || *qi == -qj
                }
            });
            let Some(&Entry {
                i: j, p: pj, q: qj, ..
            }) = partner
            else {
                continue;
            };
            let Some(&Entry { p: pi, q: qi, .. }) = entries.iter().find(|f| f.i == i) else {
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
    for (i, m) in mons.iter().enumerate() {
        if !used[i] {
            out.push(m.clone());
        }
    }
    (out, changed)
}
