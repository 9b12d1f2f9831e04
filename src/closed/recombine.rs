//! Angle-sum recombination: `T cos a cos b - T sin a sin b -> T cos(a + b)` and its three
//! siblings, for any cofactor `T` (lengths, other trigonometric factors, numbers), repeated
//! until nothing pairs up, so `c1 c2 c3 - ...` regroups to `c123` at any depth.

use super::expr::Angle;
use super::mon::{angle_combine, merge, with_atom, Atom, Mon};
use crate::scalar::Mono;
use std::collections::BTreeMap;

/// Which identity a pair of atoms can take part in.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Class {
    /// `cos a cos b` with `sin a sin b`.
    Cos,
    /// `sin a cos b` with `cos a sin b`.
    Sin,
}

/// The cofactor and the two angles that must agree for two monomials to combine.
type Key = (Class, Angle, Angle, u64, Mono, Vec<Atom>);

/// `(monomial index, first atom is sine, atom positions)`.
type Entry = (usize, bool, usize, usize);

/// Applies the angle-sum identities until no pair of monomials combines.
pub(crate) fn recombine(mut mons: Vec<Mon>) -> Vec<Mon> {
    // Each round strictly lowers the number of monomials or stops, so this terminates.
    loop {
        let (next, changed) = round(&mons);
        mons = merge(next);
        if !changed {
            return mons;
        }
    }
}

fn round(mons: &[Mon]) -> (Vec<Mon>, bool) {
    let mut index: BTreeMap<Key, Vec<Entry>> = BTreeMap::new();
    for (i, m) in mons.iter().enumerate() {
        for p in 0..m.atoms.len() {
            for q in p + 1..m.atoms.len() {
                let (a, b) = (&m.atoms[p], &m.atoms[q]);
                if a.angle == b.angle {
                    continue;
                }
                let class = if a.sin == b.sin {
                    Class::Cos
                } else {
                    Class::Sin
                };
                let mut rest = m.atoms.clone();
                rest.remove(q);
                rest.remove(p);
                let key = (
                    class,
                    a.angle.clone(),
                    b.angle.clone(),
                    m.rad,
                    m.syms.clone(),
                    rest,
                );
                index.entry(key).or_default().push((i, a.sin, p, q));
            }
        }
    }
    let mut used = vec![false; mons.len()];
    let mut out = Vec::new();
    let mut changed = false;
    for ((class, a, b, _, _, _), entries) in &index {
        for &(i, i_sin, _, _) in entries {
            if used[i] {
                continue;
            }
            // The partner has both atoms of the other kind (Cos class) or swapped (Sin class).
            let partner = entries.iter().find(|&&(j, j_sin, _, _)| {
                !used[j] && j != i && j_sin != i_sin && {
                    let (qi, qj) = (&mons[i].q, &mons[j].q);
                    qi == qj || *qi == -qj.clone()
                }
            });
            let Some(&(j, _, pj, qj)) = partner else {
                continue;
            };
            let (_, _, pi, qi) = *entries.iter().find(|e| e.0 == i).expect("entry present");
            // Orient: `first` is cos a cos b (Cos) or sin a cos b (Sin).
            let (first, second) = if i_sin == (*class == Class::Sin) {
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
            let (angle, flipped) = angle_combine(a, b, sign);
            let sin = *class == Class::Sin;
            let mut base = mons[first.0].clone();
            base.atoms.remove(first.2);
            base.atoms.remove(first.1);
            let coef_sign = if sin && flipped { -1 } else { 1 };
            used[i] = true;
            used[j] = true;
            changed = true;
            if angle.terms.is_empty() && angle.pi.numer() == &0 {
                // cos 0 = 1, sin 0 = 0.
                if !sin {
                    out.push(base);
                }
                continue;
            }
            out.push(with_atom(base, Atom { angle, sin }, coef_sign));
        }
    }
    for (i, m) in mons.iter().enumerate() {
        if !used[i] {
            out.push(m.clone());
        }
    }
    (out, changed)
}
