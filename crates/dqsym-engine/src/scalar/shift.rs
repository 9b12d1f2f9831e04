//! Constant angle offsets put back into a scalar computed without them: `x -> x + o pi` for
//! symbols `x` that occur only inside angles, as a shift of each term's phase.
//!
//! Why: a robot's joint offset (`theta = q2 + 5 pi/9`) carries a pi offset outside the
//! multiples of pi/12 through every product of the chain, and every term product then
//! rewrites its group in a cyclotomic basis. Multiplied with the offset left out and put
//! back once per entry, the entry is the same canonical scalar (substitution is a ring
//! homomorphism and the canonical form is unique), for a fraction of the work.

use super::atoms::{Small, Sym};
use super::{FxHasher, Scalar, Term};
use num_traits::{CheckedAdd, CheckedMul, Zero};
use std::cell::RefCell;
use std::collections::HashMap;
use std::hash::BuildHasherDefault;

/// `p` modulo 2, in `[0, 2)`; `None` when twice its denominator leaves a machine word.
fn modulo_two(p: Small) -> Option<Small> {
    let period = i64::checked_mul(*p.denom(), 2)?;
    Some(Small::new(p.numer().rem_euclid(period), *p.denom()))
}

/// `f . o` over the symbols of `shifts` in the frequency vector `freq`, exactly; `None` when
/// it leaves a machine word.
fn phase(freq: &[(Sym, Small)], shifts: &[(Sym, Small)]) -> Option<Small> {
    let mut d = Small::zero();
    for (s, k) in freq {
        if let Some((_, o)) = shifts.iter().find(|(x, _)| x == s) {
            d = d.checked_add(&k.checked_mul(o)?)?;
        }
    }
    Some(d)
}

/// The phase `f . o` the shifts add to the term `t`'s angle ([`phase`]); `None` when a
/// shifted symbol is in its monomial (the substitution is then not a shift of phases) or
/// the phase leaves a machine word.
fn term_phase(t: &Term, shifts: &[(Sym, Small)]) -> Option<Small> {
    if t.mono
        .iter()
        .any(|(s, _)| shifts.iter().any(|(x, _)| x == s))
    {
        return None;
    }
    phase(&t.mode.freq, shifts)
}

/// (sine, the offset's numerator and denominator) under FxHash: `Ratio`'s own `Hash` walks
/// the continued fraction (a division per step) and std's SipHash was most of a lookup
/// (0.6 M instructions of the Jaco-style arm's `fk --jacobian`). The table is only looked
/// up, never iterated; the offsets come reduced from [`modulo_two`].
type Sizes = HashMap<(bool, i64, i64), usize, BuildHasherDefault<FxHasher>>;

thread_local! {
    /// [`shifted_term_size`] by (sine, offset): the few offsets of a chain's entries come
    /// back for every entry of every partial product.
    static SIZES: RefCell<Sizes> = RefCell::new(Sizes::default());
}

/// The number of terms of the canonical form of one term `c sqrt(r) m trig(f.x + p pi)`
/// (`c` nonzero, `m` a monomial): a function of the sine flag and `p` alone. The canonical
/// form of a group is its coordinates in a basis of `cos`/`sin` of `f.x + theta` (see
/// `cyclo/`), the same for every `f`; a monomial and a nonzero rational factor do not change
/// which coordinates are nonzero, and `sqrt(r)` maps each term `sqrt(s)` of a coordinate to
/// one term `sqrt(r s)` (distinct `s`, square-free, give distinct `r s` up to squares), the
/// result canonical as it stands (`Scalar::from_terms_settled`). `None` when the term's form
/// is an error value.
fn shifted_term_size(sin: bool, pi: Small) -> Option<usize> {
    let key = (sin, *pi.numer(), *pi.denom());
    if let Some(n) = SIZES.with(|c| c.borrow().get(&key).copied()) {
        return Some(n);
    }
    let one = vec![(Sym::new("x"), Small::from_integer(1))];
    let n = Scalar::trig_of_parts(sin, one, pi).check().ok()?.len();
    SIZES.with(|c| c.borrow_mut().insert(key, n));
    Some(n)
}

impl Scalar {
    /// `c` when `self` is `c pi` for a nonzero rational `c` within machine words (a joint's
    /// constant angle offset).
    pub(crate) fn as_pi_multiple(&self) -> Option<Small> {
        let [t] = self.terms().ok()? else {
            return None;
        };
        let pi = matches!(&t.mono[..], [(s, 1)] if s.is_pi());
        (pi && t.mode.is_unit() && t.rad == 1)
            .then(|| t.coef.to_ratio_i64())
            .flatten()
    }

    /// The symbol when `self` is a plain symbol (coefficient 1, exponent 1), not `pi`.
    pub(crate) fn as_plain_symbol(&self) -> Option<Sym> {
        let [t] = self.terms().ok()? else {
            return None;
        };
        match &t.mono[..] {
            [(s, 1)] if !s.is_pi() && t.mode.is_unit() && t.rad == 1 && t.coef.is_one() => {
                Some(s.clone())
            }
            _ => None,
        }
    }

    /// `self` with each symbol `x` of `shifts` replaced by `x + o pi` (`(x, o)`), when those
    /// symbols occur only inside angles: each term `trig(f.x + p pi)` becomes
    /// `trig(f.x + (p + f.o) pi)` (its frequency vector, and so its sign, unchanged), then the
    /// terms are canonicalized once. `None` when a shifted symbol is in a monomial (the
    /// substitution is then not a shift of phases) or a phase leaves a machine word; an
    /// error value stays itself.
    ///
    /// Equal to [`Scalar::subs`] of each `x` by `x + o pi` (tests check it), which multiplies
    /// out every shifted term's trigonometric factor.
    pub(crate) fn shift_angles(&self, shifts: &[(Sym, Small)]) -> Option<Scalar> {
        let Ok(terms) = self.terms() else {
            return Some(self.clone());
        };
        let mut out: Vec<Term> = Vec::with_capacity(terms.len() + terms.len() / 2);
        let mut settled = true;
        for t in terms {
            let d = term_phase(t, shifts)?;
            if d.is_zero() {
                out.push(t.clone());
                continue;
            }
            let pi = modulo_two(t.mode.pi.checked_add(&d)?)?;
            // A group moves as a whole (its terms share `f`, so `f.o`), and one moved onto
            // multiples of pi/12 is written at once without an offset: as in
            // `closed::offsets`' shift, every group is then canonical once merged.
            if !t.push_at_twelfths(pi, &mut out) {
                settled = false;
                let mut t = t.clone();
                t.mode.pi = pi;
                out.push(t);
            }
        }
        Some(if settled {
            Scalar::from_terms_settled(out)
        } else {
            Scalar::from_terms(out)
        })
    }

    /// An upper bound of the number of terms of [`Scalar::shift_angles`] of `self` by
    /// `shifts` (`None` when that is `None` or a term's form is an error value): the sum over
    /// the terms of each one's shifted canonical size. Sound because a canonical form is a
    /// scalar's coordinates in a fixed basis (the cyclotomic groups' and the plain terms'),
    /// so the form of a sum has no term outside the union of its summands' (like terms merge
    /// or cancel, a group's coordinates add).
    pub(crate) fn shifted_size_bound(&self, shifts: &[(Sym, Small)]) -> Option<usize> {
        let terms = self.terms().ok()?;
        let mut n = 0usize;
        for t in terms {
            let d = term_phase(t, shifts)?;
            n += if d.is_zero() {
                1
            } else {
                let pi = modulo_two(t.mode.pi.checked_add(&d)?)?;
                shifted_term_size(t.mode.sin, pi)?
            };
        }
        Some(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::xorshift_below;

    /// A random scalar in the angles `q1`, `q2` (the shifted one), `t` and lengths.
    fn random_scalar(next: &mut impl FnMut(u64) -> u64, den: i64) -> Scalar {
        let sym = |s: &str| Scalar::sym(s);
        let mut x = Scalar::int(0);
        for _ in 0..1 + next(4) {
            let k = |n: u64| Scalar::int(n as i64 - 1);
            let angle = sym("q1") * k(next(3))
                + sym("q2") * k(next(3))
                + sym("t")
                    * Scalar::rational(num_rational::BigRational::new(
                        (next(3) as i64).into(),
                        2.into(),
                    ))
                + Scalar::pi()
                    * Scalar::rational(num_rational::BigRational::new(
                        (next(2 * den as u64) as i64).into(),
                        den.into(),
                    ));
            let trig = if next(2) == 0 {
                angle.cos()
            } else {
                angle.sin()
            };
            let coef = Scalar::int(next(7) as i64 - 3)
                * if next(3) == 0 {
                    Scalar::int(3).sqrt()
                } else {
                    Scalar::int(1)
                };
            let length = if next(2) == 0 {
                sym("a2")
            } else {
                Scalar::int(1)
            };
            x = x + coef * length * trig;
        }
        x
    }

    #[test]
    fn a_shift_of_angles_is_the_substitution_and_within_its_bound() {
        let mut next = xorshift_below(33);
        let mut checked = 0;
        for den in [5i64, 7, 9, 10, 18] {
            for _ in 0..40 {
                let x = random_scalar(&mut next, den);
                let o = Small::new(1 + next(2 * den as u64 - 1) as i64, den);
                let shifts = [(Sym::new("q2"), o)];
                let by_subs = x.subs(
                    "q2",
                    &(Scalar::sym("q2")
                        + Scalar::pi()
                            * Scalar::rational(num_rational::BigRational::new(
                                (*o.numer()).into(),
                                (*o.denom()).into(),
                            ))),
                );
                let shifted = x.shift_angles(&shifts).expect("q2 only in angles");
                assert_eq!(shifted, by_subs, "{x:?} shifted by {o}");
                let bound = x.shifted_size_bound(&shifts).expect("a bound");
                assert!(shifted.len() <= bound, "{} > {bound}", shifted.len());
                checked += 1;
            }
        }
        assert_eq!(checked, 200);
    }

    /// `shifted_term_size`, computed and remembered (keyed by the sine flag and the offset's
    /// numerator and denominator), is the size of the term's canonical form, for cosines and
    /// sines of the same offsets asked in turn.
    #[test]
    fn a_remembered_term_size_is_the_canonical_size() {
        let mut next = xorshift_below(7);
        for _ in 0..3 {
            for den in [5i64, 9, 12, 18] {
                let pi = Small::new(next(2 * den as u64) as i64, den);
                for sin in [true, false, true] {
                    let one = vec![(Sym::new("x"), Small::from_integer(1))];
                    let n = Scalar::trig_of_parts(sin, one, pi).len();
                    assert_eq!(shifted_term_size(sin, pi), Some(n), "{sin} {pi}");
                }
            }
        }
    }

    #[test]
    fn a_shifted_symbol_in_a_monomial_is_no_shift() {
        let x = Scalar::sym("q2") * Scalar::sym("q2").cos();
        let shifts = [(Sym::new("q2"), Small::new(5, 9))];
        assert!(x.shift_angles(&shifts).is_none());
        assert!(x.shifted_size_bound(&shifts).is_none());
    }
}
