//! Lower bounds of what a closed-form search can return, so that a search that cannot beat a
//! form found before is not finished.
//!
//! A scalar whose modes carry pi offsets outside the multiples of pi/12 is searched twice
//! (`offsets.rs`): as given and with the offsets absorbed into its symbols. The shifted form is
//! the one taken on ties, and the unshifted one is taken only when strictly shorter
//! ([`alt::shorter`]); on a Jaco-style arm it never is (its angles keep every offset, `sin(q1/2 -
//! q2/2 + q3/2 - q4/2 - q5/2 - q6/2 + 2*pi/9)`, at about three times the cost) and it was most
//! of the closed-form work. Once the shifted form is known, [`cannot_beat`] says from the
//! regrouped monomials, before they are factored, whether any form the unshifted search can
//! return (the regrouped shape factored, the whole modes factored, a candidate of `alt.rs`)
//! may be strictly shorter; when none may, the factoring and the candidates' checks are never
//! made.

use super::alt;
use super::expr::Angle;
use super::mon::{self, angle_of, Ctx, Mon};
use crate::scalar::Small;
use crate::Scalar;
use num_traits::{One, Zero};

/// The first two parts of [`alt::choice_key`] a form must be strictly below to be taken over
/// another ([`alt::shorter`]).
pub(super) type Cap = (usize, usize);

/// Whether no form the unshifted search (`best_of` on the regrouped monomials `mons` of `x`,
/// with or without the whole modes, and the whole modes alone when its check fails) returns
/// can be strictly below `cap`: both shapes' [`shape_floor`] are above it and no candidate of
/// `alt.rs` is below it.
pub(super) fn cannot_beat(x: &Scalar, ctx: &Ctx, mons: &[Mon], cap: Cap) -> bool {
    if shape_floor(ctx, mons) <= cap.0 {
        return false;
    }
    let (wctx, wmons) = mon::whole_modes_joined(x);
    shape_floor(&wctx, &wmons) > cap.0 && !alt::any_candidate_below(x, cap)
}

/// A lower bound of the first part of [`alt::choice_key`] ([`alt::full_cost`]'s operations
/// with the arithmetic inside the angles) of the expression `factor::build` makes of `mons`,
/// shown (`E::to_expr`, then `Expr::symbols_leading`).
///
/// The factoring only pulls common factors (atoms, symbols, numbers) out of groups of the
/// monomials, so its result is a tree whose sums partition the monomials: each of the `n`
/// distinct monomials is a term of some sum, below which it has a leaf of its own, and each
/// distinct atom and symbol is a leaf at least once. A tree of `L` leaves whose sums and
/// products have `k` parts each costs `k - 1` operations per node, `L - 1` in all (negations
/// and powers have one part and only add; merging equal factors into a power keeps a leaf for
/// each monomial), and every atom is a call (its cosine or sine), with its angle's arithmetic
/// ([`angle_floor`]), at least once.
pub(super) fn shape_floor(ctx: &Ctx, mons: &[Mon]) -> usize {
    let mut atoms: Vec<u32> = mons.iter().flat_map(|m| m.atoms.iter().copied()).collect();
    atoms.sort_unstable();
    atoms.dedup();
    let mut syms: Vec<u32> = mons
        .iter()
        .flat_map(|m| m.syms.iter().map(|&(s, _)| s))
        .collect();
    syms.sort_unstable();
    syms.dedup();
    // The distinct nonzero monomials (a list with equal ones or zeros would have fewer).
    let mut keys: Vec<&Mon> = mons.iter().filter(|m| !m.q.is_zero()).collect();
    keys.sort_unstable_by(|a, b| mon::key_cmp(a, b));
    keys.dedup_by(|a, b| mon::key_cmp(a, b).is_eq());
    let leaves = keys.len().max(atoms.len() + syms.len());
    let angles: usize = atoms
        .iter()
        .map(|&a| angle_floor(&ctx.angles[angle_of(a) as usize]))
        .sum();
    leaves.saturating_sub(1) + atoms.len() + angles
}

/// A lower bound of the arithmetic [`alt::full_cost`] counts inside a call of `angle`, and of
/// the call's angle once `Expr::symbols_leading` has negated it: one operation per part
/// (symbol, rational constant, multiple of pi) after the first. Negation keeps the parts, and
/// the reduction of the multiple of pi into (-1, 1] that follows it keeps a nonzero multiple in
/// that range nonzero.
pub(super) fn angle_floor(angle: &Angle) -> usize {
    let one = Small::one();
    let pi = !angle.pi.is_zero() && angle.pi <= one && angle.pi > -one;
    (angle.terms.len() + usize::from(!angle.constant.is_zero()) + usize::from(pi)).saturating_sub(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (an LCG), so that the points repeat.
    struct Rng(u64);

    impl Rng {
        fn below(&mut self, n: u64) -> u64 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (self.0 >> 33) % n
        }
    }

    fn ratio(n: i64, d: i64) -> Scalar {
        Scalar::rational(num_rational::BigRational::new(n.into(), d.into()))
    }

    /// A random sum of products of lengths and cosines or sines of angles in `x`, `y`, `z`
    /// (half angles too) at offsets of multiples of `pi/9`, `pi/7` or `pi/12` (the Jaco's
    /// kind of scalar, and the kinds around it).
    fn random_scalar(rng: &mut Rng) -> Scalar {
        let syms = ["x", "y", "z"];
        let lengths = ["a", "b", "d"];
        let dens = [9, 7, 12, 18];
        let mut sum = Scalar::int(0);
        for _ in 0..1 + rng.below(4) {
            let mut term = Scalar::int(1 + rng.below(3) as i64);
            if rng.below(2) == 0 {
                term = term * Scalar::sym(lengths[rng.below(3) as usize]);
            }
            for _ in 0..1 + rng.below(3) {
                let mut angle = Scalar::int(0);
                for s in syms {
                    let k = rng.below(5) as i64 - 2;
                    if k != 0 {
                        angle = angle + Scalar::sym(s) * ratio(k, 2);
                    }
                }
                let d = dens[rng.below(4) as usize];
                let off = rng.below(2 * d as u64) as i64;
                angle = angle + Scalar::pi() * ratio(off, d);
                term = term
                    * if rng.below(2) == 0 {
                        angle.cos()
                    } else {
                        angle.sin()
                    };
            }
            sum = sum + term;
        }
        sum
    }

    #[test]
    fn shape_floor_never_exceeds_the_cost_of_the_factored_shapes() {
        let mut rng = Rng(7);
        let mut checked = 0;
        for _ in 0..60 {
            let x = random_scalar(&mut rng);
            if x.terms().map_or(true, |t| t.is_empty()) {
                continue;
            }
            let (mut sctx, smons) = mon::split_modes(&x);
            let smons = super::super::recombine::recombine(&mut sctx, smons);
            let (wctx, wmons) = mon::whole_modes_joined(&x);
            for (ctx, mons) in [(&sctx, &smons), (&wctx, &wmons)] {
                let (e, _) = super::super::factor::build(mons).expect("factored");
                let e = e.to_expr(ctx).symbols_leading();
                let cost = alt::full_cost(&e).0;
                let floor = shape_floor(ctx, mons);
                assert!(floor <= cost, "floor {floor} > cost {cost} of {e:?}");
                checked += 1;
            }
        }
        assert!(checked >= 60, "only {checked} shapes");
    }

    #[test]
    fn a_capped_search_gives_up_only_when_the_full_one_is_not_below_the_cap() {
        // The decision `prepared_unshifted_below` makes from the floors against the search
        // it replaces, at caps around the true cost (below, equal, above).
        let mut rng = Rng(11);
        let (mut skipped, mut kept) = (0, 0);
        for _ in 0..40 {
            let x = random_scalar(&mut rng);
            let (full, _) = super::super::prepared_unshifted(&x);
            let Ok(full) = full else { continue };
            let k = alt::choice_key(&full);
            for cap in [
                (k.0 / 3, k.1 / 3),
                (k.0, k.1),
                (k.0 + 1, k.1 + 1),
                (2 * k.0, 2 * k.1),
            ] {
                match super::super::prepared_unshifted_below(&x, Some(cap)) {
                    None => {
                        assert!((k.0, k.1) >= cap, "gave up below the cap {cap:?}: {full:?}");
                        skipped += 1;
                    }
                    Some((e, _)) => {
                        assert_eq!(e.ok(), Some(full.clone()));
                        kept += 1;
                    }
                }
            }
        }
        assert!(skipped > 0 && kept > 0, "skipped {skipped}, kept {kept}");
    }

    #[test]
    fn substitution_floor_never_exceeds_what_the_constants_add() {
        // Every lifted scalar (`coefs.rs`) of random scalars: the closed form with its
        // constants put back costs at least the lifted form's cost plus the floor.
        let mut rng = Rng(5);
        let mut checked = 0;
        for _ in 0..80 {
            let x = random_scalar(&mut rng);
            let Some(mut lifting) = super::super::coefs::Lifting::new(&x) else {
                continue;
            };
            for phased in [true, false] {
                let Some(l) = lifting.lift(phased) else {
                    continue;
                };
                let Ok(c0) = super::super::prepared_shifted(&l.scalar).0 else {
                    continue;
                };
                let inner = alt::full_cost(&c0).0;
                let c = l.substitute(c0);
                let floor = l.substitution_floor();
                let cost = alt::full_cost(&c).0;
                assert!(
                    inner + floor <= cost,
                    "{inner} + {floor} > {cost} for {c:?}"
                );
                checked += 1;
            }
        }
        assert!(checked >= 5, "only {checked} lifted forms");
    }
}
