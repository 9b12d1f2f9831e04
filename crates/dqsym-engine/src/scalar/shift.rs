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

/// [`term_phase`] of the terms of one scalar, one after another, and the offset each term
/// moves to. With one shifted symbol `x` (a chain's one offset joint), the phase of a term
/// is `k o` for the coefficient `k` of `x` in its frequency vector, and so is kept by `k`:
/// the few coefficients of a chain's entries come back at every term, and the checked
/// products and sums of `Ratio` (a gcd each) were a third of the Jaco-style arm's
/// offset-free size checks. A phase kept is the exact rational [`phase`] gives (it reads
/// nothing else of the term), and so is the offset `modulo_two(d)` of a term without one
/// (`0 + d` is `d`).
struct TermPhases<'a> {
    shifts: &'a [(Sym, Small)],
    /// By the coefficient `k` (its reduced numerator and denominator, `(0, 1)` for a
    /// vector without `x`): the phase, and the offset of a term without one moved by it.
    known: Vec<((i64, i64), Small, Option<Small>)>,
}

impl<'a> TermPhases<'a> {
    fn new(shifts: &'a [(Sym, Small)]) -> TermPhases<'a> {
        TermPhases {
            shifts,
            known: Vec::new(),
        }
    }

    /// [`term_phase`] of `t`, `d`, and the offset `t` moves to, `modulo_two(p + d)` for its
    /// offset `p` (`None` when that leaves a machine word; not made when `d` is zero).
    fn moved(&mut self, t: &Term) -> Option<(Small, Option<Small>)> {
        if t.mono
            .iter()
            .any(|(s, _)| self.shifts.iter().any(|(x, _)| x == s))
        {
            return None;
        }
        let moved = |d: Small| -> Option<(Small, Option<Small>)> {
            if d.is_zero() {
                return Some((d, None));
            }
            Some((d, t.mode.pi.checked_add(&d).and_then(modulo_two)))
        };
        let [(x, _)] = self.shifts else {
            return moved(phase(&t.mode.freq, self.shifts)?);
        };
        let mut of_x = t.mode.freq.iter().filter(|(s, _)| s == x);
        let k = match (of_x.next(), of_x.next()) {
            (None, _) => (0, 1),
            (Some((_, k)), None) => (*k.numer(), *k.denom()),
            _ => return moved(phase(&t.mode.freq, self.shifts)?),
        };
        let (d, at_zero) = match self.known.iter().find(|(c, _, _)| *c == k) {
            Some(&(_, d, at_zero)) => (d, at_zero),
            None => {
                let d = phase(&t.mode.freq, self.shifts)?;
                let at_zero = if d.is_zero() { None } else { modulo_two(d) };
                self.known.push((k, d, at_zero));
                (d, at_zero)
            }
        };
        if d.is_zero() || !t.mode.pi.is_zero() {
            return moved(d);
        }
        Some((d, at_zero))
    }
}

/// [`shifted_term_size`] by sine flag and offset (numerator, denominator).
type Sizes = HashMap<(bool, i64, i64), usize, BuildHasherDefault<FxHasher>>;

thread_local! {
    /// [`shifted_term_size`] by (sine, offset's numerator and denominator): the few offsets
    /// of a chain's entries come back for every entry of every partial product. The offset
    /// is reduced, so equal offsets have equal words; hashed by `FxHasher`, where the
    /// default SipHash of a `Ratio` (its continued fraction) cost as much as the rest of the
    /// size checks.
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
    /// `trig(f.x + (p + f.o) pi)` (its frequency vector, and so its sign, unchanged). `None`
    /// when a shifted symbol is in a monomial (the substitution is then not a shift of
    /// phases) or a phase leaves a machine word; an error value stays itself.
    ///
    /// A term without an offset moved off the multiples of pi/12 is written at once in its
    /// canonical form (`cyclo::canonical_term`), and the terms are then only merged, when no
    /// term with an offset is so moved; otherwise the shifted terms are canonicalized as a
    /// whole ([`Scalar::shift_angles_rewritten`]). Why the merge is canonical: a group's
    /// canonical form is its value's expansion in the basis of its smallest level `M`, whose
    /// first column is `1`, and a group is canonical exactly when its terms with an offset are
    /// canonical on their own (`cyclo::Settled`). The terms of a group share `f`, so its phase
    /// `d = f.o`: its terms without an offset, `Z = sum q sqrt(r) z` (`z` `1` or `-i`, `Z` a
    /// nonzero value of `K(i)`, `K` the square-root field), become `Z e^{i d pi}`, whose
    /// smallest level is that of `e^{i d pi}` (`K(i)` is in every field), and so is each
    /// term's: all are expanded in the one basis, over `K(i)`, where the expansion is linear,
    /// so the merged expansions are the expansion of the sum. Its terms with an offset moved
    /// onto multiples of pi/12 are offset-free, values of `K(i)` (the column `1`), and those
    /// not moved (`d = 0`) are the group as it was. So every group is canonical once merged.
    /// The same terms as the rewrite (a canonical form is unique; tests compare both; where
    /// a term's form is an error value the rewrite itself is returned), for less work
    /// charged: each term is charged as one rewritten alone, where the rewrite charged each
    /// group by its size. An offset-free product's entry shifted back so spends less of the
    /// report's budget: it may now be kept at the budget's very edge (see `OffsetFree`), and
    /// the closed forms searched after it find more of the budget left, so where a nested
    /// search of their optional candidates (`trigfac::nested_closed_form`: a share of the
    /// budget left) ran out before, it may now end and be taken (a different form of the
    /// same value, at that edge only).
    ///
    /// Equal to [`Scalar::subs`] of each `x` by `x + o pi` (tests check it), which multiplies
    /// out every shifted term's trigonometric factor.
    pub(crate) fn shift_angles(&self, shifts: &[(Sym, Small)]) -> Option<Scalar> {
        let Ok(terms) = self.terms() else {
            return Some(self.clone());
        };
        let mut out: Vec<Term> = Vec::with_capacity(terms.len() + terms.len() / 2);
        let mut phases = TermPhases::new(shifts);
        for t in terms {
            let (d, pi) = phases.moved(t)?;
            if d.is_zero() {
                out.push(t.clone());
                continue;
            }
            let pi = pi?;
            // A reduced offset is a multiple of 1/12 exactly when its denominator divides
            // 12: others are not looked at again. One not written so (a radicand past a
            // machine word), or a term with an offset moved elsewhere: the rewrite.
            if 12 % *pi.denom() == 0 {
                if t.push_at_twelfths(pi, &mut out) {
                    continue;
                }
                return self.shift_angles_rewritten(shifts);
            }
            if !t.mode.pi.is_zero() {
                return self.shift_angles_rewritten(shifts);
            }
            let mut t = t.clone();
            t.mode.pi = pi;
            match super::cyclo::canonical_term(&t) {
                Ok(c) => out.extend(c),
                // Past the degree limit (or another limit): the rewrite, whose error value
                // (or `None`, for a later term it cannot shift) is the one given before.
                Err(_) => return self.shift_angles_rewritten(shifts),
            }
        }
        Some(Scalar::from_terms_settled(out))
    }

    /// [`Scalar::shift_angles`] with every group rewritten in its canonical basis unless all
    /// of them moved onto multiples of pi/12: the route for terms with an offset moved
    /// elsewhere, and the reference the tests compare the other with.
    pub(crate) fn shift_angles_rewritten(&self, shifts: &[(Sym, Small)]) -> Option<Scalar> {
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
        let mut phases = TermPhases::new(shifts);
        for t in terms {
            let (d, pi) = phases.moved(t)?;
            n += if d.is_zero() {
                1
            } else {
                shifted_term_size(t.mode.sin, pi?)?
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

    /// `x` with each symbol `s` of `shifts` replaced by `s + o pi` ([`Scalar::subs`], one
    /// symbol after another: no replacement holds another shifted symbol), the reference the
    /// shift is compared with.
    fn substituted(x: &Scalar, shifts: &[(Sym, Small)]) -> Scalar {
        shifts.iter().fold(x.clone(), |x, (s, o)| {
            let o = num_rational::BigRational::new((*o.numer()).into(), (*o.denom()).into());
            x.subs(
                s.name(),
                &(Scalar::sym(s.name()) + Scalar::pi() * Scalar::rational(o)),
            )
        })
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
                let by_subs = substituted(&x, &shifts);
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

    /// A random offset-free scalar (offsets on the pi/12 grid are written without one) with
    /// groups of several terms: a product of two random scalars at sixths of pi.
    fn offset_free_scalar(next: &mut impl FnMut(u64) -> u64) -> Scalar {
        random_scalar(next, 6) * random_scalar(next, 6)
    }

    /// The shift that writes the terms without an offset in their canonical form at once and
    /// only merges them gives the terms the rewrite of every group from scratch gives (the
    /// route it replaced), on offset-free scalars shifted off the pi/12 grid (the route
    /// taken) and on scalars with offsets (the rewrite taken).
    #[test]
    fn a_shift_merged_is_the_shift_rewritten() {
        let mut next = xorshift_below(91);
        let (mut merged, mut checked) = (0, 0);
        for den in [5i64, 7, 9, 10, 18, 36] {
            for i in 0..40 {
                let x = if i % 4 == 3 {
                    random_scalar(&mut next, den)
                } else {
                    offset_free_scalar(&mut next)
                };
                let o1 = Small::new(1 + next(2 * den as u64 - 1) as i64, den);
                let o2 = Small::new(next(2 * den as u64) as i64, den);
                let shifts = [(Sym::new("q2"), o1), (Sym::new("t"), o2)];
                let shifted = x.shift_angles(&shifts).expect("q2, t only in angles");
                let rewritten = x.shift_angles_rewritten(&shifts).expect("as the other");
                assert_eq!(shifted, rewritten, "{x:?} shifted by {o1}, {o2}");
                let offset_free = x
                    .terms()
                    .is_ok_and(|t| t.iter().all(|t| t.mode.pi.is_zero()));
                let off_grid = |o: Small| !(o * Small::from_integer(12)).is_integer();
                merged += usize::from(offset_free && off_grid(o1) && shifted != x);
                checked += 1;
            }
        }
        assert_eq!(checked, 240);
        assert!(merged >= 120, "{merged} merged");
    }

    /// As [`a_shift_merged_is_the_shift_rewritten`], in the fields where a square root lies
    /// inside the cyclotomic field of the shift (`sqrt(2)` at eighths, `sqrt(5)` at fifths and
    /// twentieths, `sqrt(6)`, `sqrt(10)`), with one shifted symbol (the phases kept by its
    /// coefficient, `TermPhases`) and with two, and with terms at offsets of the shift's
    /// denominator or of fifths, sevenths, ninths (the moved terms with an offset, which take
    /// the rewrite): the same scalar both ways, and both the substitution.
    #[test]
    fn a_shift_merged_is_the_shift_rewritten_in_other_fields() {
        let mut next = xorshift_below(57);
        let (mut merged, mut checked) = (0, 0);
        for den in [8i64, 16, 20, 24, 40, 60] {
            for i in 0..24 {
                // Offsets of other denominators than the shift's: a moved term with an
                // offset may then need another level than the terms moved without one.
                let x = if i % 4 == 3 {
                    random_scalar(&mut next, [den, 5, 7, 9][i / 4 % 4])
                } else {
                    offset_free_scalar(&mut next)
                };
                let r = [1, 2, 5, 6, 10][next(5) as usize];
                let x = x * Scalar::int(r).sqrt() + Scalar::int(2).sqrt() * Scalar::sym("q2").sin();
                let o1 = Small::new(1 + next(2 * den as u64 - 1) as i64, den);
                let o2 = Small::new(next(2 * den as u64) as i64, den);
                let two = [(Sym::new("q2"), o1), (Sym::new("t"), o2)];
                let shifts = if i % 2 == 0 { &two[..1] } else { &two[..] };
                let shifted = x.shift_angles(shifts).expect("q2, t only in angles");
                let rewritten = x.shift_angles_rewritten(shifts).expect("as the other");
                assert_eq!(shifted, rewritten, "{x:?} shifted by {shifts:?}");
                assert_eq!(
                    shifted,
                    substituted(&x, shifts),
                    "{x:?} shifted by {shifts:?}"
                );
                let off_grid = |o: Small| !(o * Small::from_integer(12)).is_integer();
                merged += usize::from(off_grid(o1) && shifted != x);
                checked += 1;
            }
        }
        assert_eq!(checked, 144);
        assert!(merged >= 60, "{merged} merged");
    }

    #[test]
    fn a_shifted_symbol_in_a_monomial_is_no_shift() {
        let x = Scalar::sym("q2") * Scalar::sym("q2").cos();
        let shifts = [(Sym::new("q2"), Small::new(5, 9))];
        assert!(x.shift_angles(&shifts).is_none());
        assert!(x.shifted_size_bound(&shifts).is_none());
    }
}
