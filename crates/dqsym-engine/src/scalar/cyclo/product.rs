//! Which groups of a product of two canonical scalars are canonical once like terms merge,
//! so that only the others are rewritten.
//!
//! # Why
//! Write a group of frequency `f` as `Re(z e^{i phi})` (`z` in `K(zeta_M)`, `phi = f . x`),
//! or as a real `c` when `f` is empty (module docs of `cyclo`). The product of a group `A`
//! of `x` and a group `B` of `y` is, by the product-to-sum rules `arith::mul` applies term by
//! term,
//!
//! ```text
//! Re(z_A e^{i phi_A}) Re(z_B e^{i phi_B}) = 1/2 Re(z_A z_B e^{i (phi_A + phi_B)})
//!                                         + 1/2 Re(z_A conj(z_B) e^{i (phi_A - phi_B)}),
//! ```
//!
//! a frequency with a negative leading coefficient being turned round by conjugating
//! (`Re(w e^{-i psi}) = Re(conj(w) e^{i psi})`). Call `B` *offset-free* when none of its
//! terms has a pi offset: its value `c` is then in `K(i)` (in `K` for a real group). When `A`
//! has offsets and `B` is offset-free, a branch whose terms keep the pi offset `theta` of the
//! term of `A` they come from (rather than `-theta`, which is what a conjugation does) and stay
//! complex when `A` is complex (real when `A` is real) has the value `z_A c'` with `c'` one of
//! `c/2`, `conj(c)/2` (or `c` for a real `B` times any `A`, the product being `A`'s terms
//! times constants): a nonzero element of `K(i)` times `z_A`. Its smallest level is `A`'s
//! (every `K(zeta_M)`, `24 | M`, holds `K(i)`), and its expansion in `A`'s basis is `A`'s
//! coordinates times `c'`: each product term is a rational times `sqrt(r)` times a mode at a
//! column of `A`'s basis, so once like terms merge they are that expansion, the unique one.
//! (The other cases are not canonical in general: `conj(z_A)` has the conjugate columns, a
//! real `A` times a complex `B` mixes `theta` and `-theta`, and `z_A z_B` lives in a larger
//! field.)
//!
//! A group of the product is therefore canonical when all its terms with a pi offset come
//! from one such pair `(A, B)` (its terms without one do not matter: `Settled`); a term with a
//! pi offset from any other pair, or from a pair of the other kind, makes it rewritten. The
//! origins are recorded before like terms merge, so a cancellation between two origins is
//! seen as two origins. Debug builds check every group passed through this way against a
//! rewrite from scratch.

use super::super::atoms::Mode;
use super::super::Term;
use super::{group_ids, key_cmp, GroupKey, OwnedKey};
use num_traits::Zero;

/// The origins of the terms with a pi offset of one product (see the module docs).
pub(crate) struct ProductTrace {
    /// The group of each term of the left factor, and of the right one.
    gx: Vec<u32>,
    gy: Vec<u32>,
    /// Whether each group of the left factor, and of the right one, is offset-free.
    free_x: Vec<bool>,
    free_y: Vec<bool>,
    /// The origin of every product term with a pi offset: its index and the pair of groups
    /// it came from, `0` for a pair of the other kind.
    marks: Vec<(usize, u64)>,
}

/// The group of each term, and for each group whether it is offset-free. The groups are
/// numbered as [`group_ids`] finds them, not in key order: a trace only tells groups apart
/// (its origins are compared for equality, in [`settled_groups`]).
fn groups(t: &[Term]) -> (Vec<u32>, Vec<bool>) {
    let (_, ids, offset) = group_ids(t);
    (ids, offset.iter().map(|o| !o).collect())
}

impl ProductTrace {
    /// A trace for the product of `x` and `y`; `None` when no group of the product can be
    /// canonical this way (no group with a pi offset on one side and an offset-free one on
    /// the other).
    pub(crate) fn new(x: &[Term], y: &[Term]) -> Option<ProductTrace> {
        let offsets = |t: &[Term]| t.iter().any(|t| !t.mode.pi.is_zero());
        let (ox, oy) = (offsets(x), offsets(y));
        if !ox && !oy {
            return None;
        }
        let (gx, free_x) = groups(x);
        let (gy, free_y) = groups(y);
        let any = |f: &[bool]| f.iter().any(|f| *f);
        if !(ox && any(&free_y) || oy && any(&free_x)) {
            return None;
        }
        Some(ProductTrace {
            gx,
            gy,
            free_x,
            free_y,
            marks: Vec::new(),
        })
    }

    /// Records the product term `k`, of mode `mode`, formed from the terms `i` of `x` (mode
    /// `s`) and `j` of `y` (mode `t`).
    pub(crate) fn mark(
        &mut self,
        k: usize,
        (i, s): (usize, &Mode),
        (j, t): (usize, &Mode),
        mode: &Mode,
    ) {
        if mode.pi.is_zero() {
            return;
        }
        let (gi, gj) = (self.gx[i], self.gy[j]);
        // The term with the offset, and whether the other's group is offset-free.
        let source = match (s.pi.is_zero(), t.pi.is_zero()) {
            (false, true) => Some((s, self.free_y[gj as usize])),
            (true, false) => Some((t, self.free_x[gi as usize])),
            _ => None,
        };
        let kept = source.is_some_and(|(src, free)| {
            free && mode.pi == src.pi && mode.freq.is_empty() == src.freq.is_empty()
        });
        let origin = if kept {
            u64::from(gi) * self.free_y.len() as u64 + u64::from(gj) + 1
        } else {
            0
        };
        self.marks.push((k, origin));
    }

    /// The marks recorded so far (for the tests of `arith::product_terms`).
    #[cfg(test)]
    pub(crate) fn marks(&self) -> &[(usize, u64)] {
        &self.marks
    }

    /// The keys of the groups of the product terms `out` (before they are sorted) that are
    /// canonical once like terms merge, sorted.
    pub(crate) fn settled(self, out: &[Term]) -> Vec<OwnedKey> {
        settled_groups(out, &self.marks)
    }
}

/// The keys of the groups of `out` (terms not yet sorted or merged) whose terms with a pi
/// offset all have one origin, none of them `0`, sorted: `marks` holds the index and the
/// origin of every term of `out` with a pi offset, `0` for one that may not be passed
/// through. The caller shows that a group of one origin is canonical once like terms merge
/// (a product's: see the module docs; a derivative's: `Scalar::diff`).
pub(crate) fn settled_groups(out: &[Term], marks: &[(usize, u64)]) -> Vec<OwnedKey> {
    let mut m: Vec<(GroupKey, u64, usize)> = marks
        .iter()
        .map(|&(k, origin)| {
            let t = &out[k];
            ((&*t.mode.freq, &t.mono), origin, k)
        })
        .collect();
    m.sort_unstable_by(|a, b| key_cmp(&a.0, &b.0).then(a.1.cmp(&b.1)));
    m.chunk_by(|a, b| key_cmp(&a.0, &b.0).is_eq())
        .filter(|run| run[0].1 != 0 && run[0].1 == run[run.len() - 1].1)
        .map(|run| {
            let t = &out[run[0].2];
            (t.mode.freq.clone(), t.mono.clone())
        })
        .collect()
}
