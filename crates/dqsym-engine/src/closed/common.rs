//! One offset per symbol across the entries of a report. Each closed form chooses the offsets
//! it absorbs on its own (`offsets.rs`: fewest cosine and sine parts, then fewest negative
//! ones, ...), so sibling entries may show one class differently: `cos(q2 - q3 + 5*pi/9)`
//! beside `cos(q2 - q3 - 4*pi/9)`, `sin(q2/2 - q3/2 + 5*pi/18)` beside `sin(q2/2 - q3/2 -
//! 2*pi/9)`.
//!
//! The rule ([`CommonOffsets`]): every angle `f . x + c pi` whose offset `c` is not a multiple
//! of 1/12 is read as `l (g . x + t pi)`, `g` the primitive integer direction of `f` (first
//! coefficient positive) and `t = c / l` modulo 2. Each direction's offset `t` is voted for
//! by the entries (one vote per entry and offset); the directions are taken by their
//! number of symbols (a symbol alone first), then their largest vote, each fixing `g . o = t` for one offset vector `o` of the symbols when
//! independent of the directions fixed before, and taking the value they imply otherwise
//! (on a tie the non-negative `t`, then the smallest). An angle is then shown at `l (g . o)`
//! when that differs from its offset by a multiple of pi/2, the call and sign adjusted
//! (`cos(a - pi/2) = sin(a)`), in every entry that gets no longer by it. So the Jaco-style
//! arm's `q2 + 5*pi/9` shows as `q2 - q3 + 5*pi/9` and `q2/2 + q3/2 + 5*pi/18` alike.

use super::{Angle, Expr};
use crate::scalar::{Small, Sym};
use num_integer::Integer;
use num_traits::{One, Signed, Zero};
use std::collections::BTreeMap;

/// The offset each angle direction of a report is shown at; see the module docs.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CommonOffsets(BTreeMap<Direction, Small>);

/// A primitive integer direction of symbols.
type Direction = Vec<(Sym, i64)>;

/// `t` reduced into `(-1, 1]` (modulo 2).
fn centred(t: Small) -> Small {
    let two = Small::from_integer(2);
    let v = t - (t / two).floor() * two;
    if v > Small::one() {
        v - two
    } else {
        v
    }
}

/// `(g, l, t)` for an angle with symbols whose offset is not a multiple of 1/12: `f = l g`,
/// `g` primitive with integer coefficients, the first positive, `t = c / l` modulo 2.
fn direction(a: &Angle) -> Option<(Direction, Small, Small)> {
    // Offsets at multiples of pi/12 (zero included: every angle of the PUMA's) first, cheaply.
    if 12 % a.pi.denom() == 0 || a.terms.is_empty() {
        return None;
    }
    let den = a.terms.iter().fold(1i64, |d, (_, k)| d.lcm(k.denom()));
    let ints: Vec<i64> = a
        .terms
        .iter()
        .map(|(_, k)| (*k * Small::from_integer(den)).to_integer())
        .collect();
    let mut g = ints.iter().fold(0i64, |g, v| g.gcd(v));
    if ints[0] < 0 {
        g = -g;
    }
    let dir = a
        .terms
        .iter()
        .zip(&ints)
        .map(|((s, _), v)| (s.clone(), v / g))
        .collect();
    let l = Small::new(g, den);
    Some((dir, l, centred(a.pi / l)))
}

fn walk(e: &Expr, out: &mut dyn FnMut(&Angle)) {
    match e {
        Expr::Trig { angle, .. } => out(angle),
        Expr::Add(v) | Expr::Mul(v) => v.iter().for_each(|x| walk(x, out)),
        Expr::Neg(x) | Expr::Pow(x, _) => walk(x, out),
        _ => {}
    }
}

/// Rows `(g, t)` in echelon form over the rationals: each with a pivot symbol no later row
/// holds.
type Basis = Vec<(Vec<(Sym, Small)>, Small)>;

/// `g` reduced by the basis: what is left, and the offset the basis implies for the part it
/// spans.
fn reduce(basis: &Basis, g: &[(Sym, i64)]) -> (BTreeMap<Sym, Small>, Small) {
    let mut left: BTreeMap<Sym, Small> = g
        .iter()
        .map(|(s, k)| (s.clone(), Small::from_integer(*k)))
        .collect();
    let mut implied = Small::zero();
    for (row, t) in basis {
        let (p, kp) = &row[0];
        let Some(c) = left.get(p).map(|v| *v / *kp) else {
            continue;
        };
        for (s, k) in row {
            let v = left.entry(s.clone()).or_insert_with(Small::zero);
            *v -= c * *k;
        }
        left.retain(|_, v| !v.is_zero());
        implied += c * *t;
    }
    (left, implied)
}

impl CommonOffsets {
    /// The offsets chosen from the closed forms `forms` (a report's pose entries).
    pub fn from_forms<'a>(forms: impl IntoIterator<Item = &'a Expr>) -> CommonOffsets {
        let mut votes: BTreeMap<Direction, BTreeMap<Small, usize>> = BTreeMap::new();
        for e in forms {
            let mut seen: Vec<(Direction, Small)> = Vec::new();
            walk(e, &mut |a| {
                if let Some((g, _, t)) = direction(a) {
                    if !seen.iter().any(|(h, u)| *h == g && *u == t) {
                        seen.push((g, t));
                    }
                }
            });
            for (g, t) in seen {
                *votes.entry(g).or_default().entry(t).or_default() += 1;
            }
        }
        // Each direction's winner; the directions of fewer symbols first (a symbol alone fixes
        // its own offset), then by their winners' votes.
        let mut winners: Vec<(usize, Direction, Small)> = votes
            .into_iter()
            .filter_map(|(g, v)| {
                let (t, n) = v
                    .into_iter()
                    .min_by_key(|(t, n)| (std::cmp::Reverse(*n), t.is_negative(), t.abs(), *t))?;
                Some((n, g, t))
            })
            .collect();
        winners.sort_by(|a, b| {
            (a.1.len(), b.0)
                .cmp(&(b.1.len(), a.0))
                .then_with(|| a.1.cmp(&b.1))
        });
        let mut basis: Basis = Vec::new();
        let mut chosen = BTreeMap::new();
        for (_, g, t) in winners {
            let (left, implied) = reduce(&basis, &g);
            if left.is_empty() {
                chosen.insert(g, centred(implied));
            } else {
                basis.push((left.into_iter().collect(), t - implied));
                chosen.insert(g, t);
            }
        }
        CommonOffsets(chosen)
    }

    /// Whether [`CommonOffsets::apply`] leaves `e` as it is whatever offsets were chosen:
    /// no angle of `e` has symbols and an offset outside the multiples of pi/12 (the PUMA's
    /// entries, every entry of a chain without offsets). The text of such an entry is final
    /// before the report's offsets are known.
    pub fn fixes(e: &Expr) -> bool {
        let mut fixed = true;
        walk(e, &mut |a| fixed &= direction(a).is_none());
        fixed
    }

    /// `e` with every angle whose offset differs from its direction's common one by a multiple
    /// of `pi/2` shown at the common one (see the module docs), when that costs no more than
    /// `e`; else `e`.
    pub fn apply(&self, e: Expr) -> Expr {
        if self.0.is_empty() {
            return e;
        }
        let mut changed = false;
        let new = e.clone().map_trig_signed(&mut |f, angle| {
            let (g, l, _) = direction(angle)?;
            let target = *self.0.get(&g)? * l;
            // The number of quarter turns from the common offset to the angle's.
            let quarters = (angle.pi - target) * Small::from_integer(2);
            if !quarters.is_integer() {
                return None;
            }
            let mut b = angle.clone();
            b.pi = target;
            b.reduce_offset();
            if b == *angle {
                return None;
            }
            changed = true;
            // cos(a + q pi/2) and sin(a + q pi/2) in cos(a) and sin(a).
            let (g, neg) = super::expr::quarter_turned(f, quarters.to_integer());
            Some((g, b, neg))
        });
        if changed && new.cost() <= e.cost() {
            new
        } else {
            e
        }
    }
}
