//! Closed forms: the display layer between canonical scalars and printed text.
//!
//! The canonical form is a Fourier series; a kinematician reads products of cosines and sines
//! of grouped angles. [`closed_form`] tries two shapes and keeps the cheaper by [`Cost`]:
//! (a) every mode split into single-symbol atoms, then regrouped by the angle-sum identities
//! (`recombine.rs`) and factored (`factor.rs`); (b) the Fourier modes kept whole and factored;
//! then (c) the candidates of `alt.rs` (harmonic form, sum to product, a polynomial in one
//! cosine or sine factored by its rational roots, products of one angle's cosines and sines
//! found from the roots on the unit circle, `roots.rs`) when one is cheaper still; (d) for a scalar
//! whose symbolic modes carry pi offsets outside the multiples of pi/12, the same with the
//! offsets absorbed into the symbols (`offsets.rs`) when that is shorter; (e) for such a scalar,
//! also the same with its constant coefficients lifted out of the angles into symbols of
//! their own (`coefs.rs`: `sin(pi/7) cos(pi/9) cos(q)`), and with angles at multiples of pi/12
//! that the canonical form holds as radicals made angles again (`l1 cos(x - pi/3)`). The result
//! is re-canonicalized and compared with the input before it is returned.
//!
//! # The heuristics, file by file
//!
//! `mon.rs` turns the canonical Fourier form into monomials over trigonometric atoms (modes whole,
//! or split per symbol; for the whole-modes shape each group of one monomial and one angle at
//! offsets outside pi/12 joined into `R cos(F + phi)` when it is one angle, checked exactly: `l1
//! cos(t + 5*pi/9) + l2 cos(2*t + 5*pi/9)`); `recombine.rs` applies the four angle-sum identities
//! to any depth (greedy rounds over every pair of atoms; on sums of at least 128 monomials of six
//! atoms or more, first on each monomial's two lowest atoms); `factor.rs` nests common factors,
//! choosing by `Cost` (below its branching levels a run of splits on one factor from one sort of
//! the terms by its power, `factor/run.rs`; at the branching levels of a plain integer polynomial
//! each candidate's exact cost found without its tree, in machine integers, `factor/costs.rs`);
//! `expr.rs` is the display expression `Expr` with its cost and exact value (and f64 value);
//! `decimals.rs` `decimal_form`, a robot's decimal denominators put back into their sums (`0.425
//! c2`, the printers' `decimals` option prints the decimal fractions); `alt.rs` the further
//! candidates taken when strictly shorter counting the arithmetic inside angles (harmonic form `R
//! cos(x + phi)`, sum to product, a polynomial in one cosine or sine factored by its rational roots
//! (the roots 1 and -1 paired as `-sin^2`), a sum of such polynomials in distinct angles with the
//! constants merged, products of cosines peeled off by exact division (`peel.rs`, Gaussian integer
//! coefficients over one denominator), a single `cos(k pi/n)`; `cprod.rs`: products of one to three
//! constant cosines and sines at the field's angles times a rational polynomial, `cos(pi/7)
//! cos(pi/9)`, found numerically, with a radical cofactor (each radicand's terms apart, `1/4 (1 +
//! sqrt(5)) sin(pi/11)^2`, or the square root of a radicand of the terms beside the product,
//! `sqrt(2) sin(pi/7)^2 cos(pi/9)`) and beside the terms without a mode split off as a constant
//! (`1 - cos(pi/7) cos(pi/9)`); `roots.rs`: for a scalar over one monomial with a pi offset or a
//! square root whose modes are multiples of one angle `theta`, products of cosines and sines of
//! multiples of `theta/2` with different offsets (`l cos(x) cos(x - pi/14)`, `(cos(x) - cos(pi/7))
//! (sin(x) + 1)`), found from the roots of the sum as a polynomial in `e^{i theta}` (Aberth's
//! iteration in f64, each cluster snapped to a rational multiple of pi within a denominator bound
//! from the field's conductor and the degree, the factorization checked in floats), the roots
//! grouped into `sin(k (phi - a))`, `cos(k phi) - cos(k b)`, `sin(k phi) - sin(k b)` (every order
//! of the kinds, the largest `k` first or `theta` before `theta/2`), each shown with the cheapest
//! offset, the constant exact from the scalar's top coefficient; and, for 2 to 4 symbols, products
//! `f(x) g(y)` of such one-angle parts (`cos(x - pi/8) sin(y - pi/8)`, whose expansion has the
//! modes `x - y`, `x + y`): the symbols split where the scalar is numerically of rank one, each
//! part's roots from its restriction to a point of the others, the constant exact from the
//! coefficient of the parts' top modes combined; and the factorization over the integers of the sum
//! read as a polynomial in `c_x = cos x`, `s_x = sin x` and the length symbols, and, when some mode
//! is a multiple of two or more of its direction's unit, in the cosines and sines of the modes'
//! directions (`cos(a + b)` a variable of its own: `a2^2 cos(a)^2 - a3^2 cos(a + b)^2`)
//! (`cspoly.rs`: as expanded, with `s^2 = 1 - c^2`, with `c^2 = 1 - s^2`; not factored when linear
//! in distinct length symbols with one coefficient a constant or a variable another coefficient
//! lacks; the closed forms of its factors and pairs of factors found without factoring them again;
//! `zfactor.rs`: content and monomial factor, Kronecker's substitution onto one variable,
//! square-free part by a modular gcd, factors modulo a small prime (distinct-degree and
//! Cantor-Zassenhaus), Hensel lifting past a Gelfond bound, subsets recombined by exact
//! multivariate division, a subset whose constant term cannot divide skipped before its product is
//! formed; image degree <= 64, charged to the work budget)); `trigfac.rs` (made in
//! `best_alternative` only when a lower bound of their cost is below the form found, for at most 24
//! terms, not for modes at one step without offsets or radicals such as the PUMA's): sinusoids
//! `cos(d.x + phi)` whose angle mixes symbols (`-sin(u1) cos(u1 + 2*u2 - pi/6)`), `d` from
//! half-differences of the exponents seen from two vertices of the Newton polytope, `phi` a
//! multiple of pi/24 found in floats on the factor's zero set, divided out exactly by a long
//! division along `d`, the cofactor given its own closed form; and a sum split into parts of
//! distinct monomials or disjoint symbols, each part's closed form found alone; `extra.rs` (the one
//! place of the candidates below, for issue 33's held-out corpus): squares of sums `k (g)^2`
//! (`square.rs`: the square root of the sum's exponential form taken in `f64` by the schoolbook
//! algorithm in a lexicographic order of the exponents, read back as a real sum with coefficients
//! snapped to rationals times square roots, the square checked exactly before the root's closed
//! form is found), every candidate with a factor shared by all or some of its summands taken out
//! (`k2 (a - b)` for `k2 a - k2 b`), a sum split by the symbols of its terms' angles (not for the
//! PUMA's unit-step modes), each part's closed form found alone, and pairs of summands with equal
//! numbers and factors but one call joined (sum to product, `cos A + cos B = 2 cos((A + B)/2)
//! cos((A - B)/2)`; a number beside its cosine as a square, `1 - cos(2 w) = 2 sin(w)^2`), greedily
//! while no longer, also on the form shown (`extra::joined_form`: the angles made again from
//! radicals by `coefs.rs` are first seen there), there also the sums inside its products (`sin(c)
//! (sin(2 a + b) + sin(b))` as `2 sin(c) sin(a + b) cos(a)`), and a cosine and a sine of one angle
//! with the same other factors as one sinusoid when its offset is a multiple of pi/12 (`cos(a) +
//! sqrt(3) sin(a) = 2 sin(a + pi/6)`); each checked exactly; constant angles are shown with a
//! positive sign; an angle's symbols print first, then its rational constant and its multiple of pi
//! (`t/2 - 1/3`, `x - pi/7`), and an angle with a rational constant is shown with its first
//! symbol's coefficient positive (`Expr::symbols_leading`: `sin(1/3 - t/2)` prints `-sin(t/2 -
//! 1/3)`); equal symbols and atoms of a product print as one power (`a2^2`, never `a2 a2`); an
//! angle whose coefficients share one denominator prints over it (`cos((q1 + q2)/2)`,
//! `notation::angle_text`, as in LaTeX) and is costed so; the split shape is skipped (`skip_split`)
//! when it would multiply the terms by more than 256, or by more than 32 with no two terms able to
//! meet in it (`disjoint_parts`: the cumulative angles of a planar chain), and a scalar without
//! trigonometric terms is factored once; `offsets.rs` absorbs pi offsets outside the multiples of
//! pi/12 into the symbols: for a scalar whose symbolic modes carry such offsets (the gate an
//! offset-free scalar such as the PUMA's fails at once), one rational multiple of pi `o_s` per
//! symbol such that the scalar in `y_s = x_s + o_s` has none left (each group's phase class modulo
//! pi/12 tried exactly, the congruences `f . o = d_f` solved by a bounded search), its closed form
//! found on the offset-free path and every angle shifted back (`cos(q2 + 5*pi/9)`, `cos(x - pi/7)
//! cos(y + pi/7)`, `sin(x - 2*pi/7)^2`; the candidates of `alt.rs` for the shifted scalar compared
//! again shifted back, since a shift changes what an angle costs: `cos(x) cos(x + 2*pi/7)`), kept
//! unless the form as given is strictly shorter (found first, so that the search as given checks
//! its candidates of `alt.rs` only below it: `prepared_shifted`, the same choice; the search as
//! given not made for a scalar of 32 terms or more whose shifted form, each sinusoid read as the
//! cheapest of its four equal forms (`Expr::cheapest_offsets`: `sin(a + pi/18)` for `cos(a -
//! 4*pi/9)`), has fewer than 2 operations a term, a measured rule: `as_given_may_win`) and checked
//! like every other; the offset shown among equal classes is the one with the fewest cosine and
//! sine parts in `y`, then the smallest
//! denominator, the fewest nonzero offsets, the fewest negative parts (`cos(t + 5*pi/9)`, not
//! `-cos(t - 4*pi/9)`), the smallest `|o|`, the positive one; derivatives of a prepared scalar are
//! shifted alike; the congruences are scaled to integer residues modulo one common modulus and
//! solved in echelon form (`congruence.rs`: each unknown a residue class given the earlier ones,
//! the solutions listed in lexicographic order without a search, every value charged to the
//! Context); an `fk` report's entry that is a rational multiple of another with a joint angle
//! (or the twist ending a DH chain) turned by a quarter or half turn (`turn.rs`: the second half
//! of a dual quaternion whose first joint turns about z, `Rz(q1) M`'s second row, `M Rx(alpha)`'s
//! third column) takes the other's form turned, checked, not a search of its own, a form that
//! can differ from its own search's; a recurrence's entry that is another with its symbols
//! permuted and signed (`rename.rs`: the components of a quaternion product) takes the other's
//! form renamed, alike; across an `fk` report one
//! offset per angle direction (`common.rs`, `CommonOffsets`):
//! each angle `l (g . x + t pi)` (`g` primitive) votes for `t` once per pose entry, directions of
//! fewer symbols first and then by votes fix one offset vector `o` (ties: non-negative, then
//! smallest), and every entry's angle whose offset differs from `l (g . o)` by a multiple of pi/2
//! is shown at it, call and sign adjusted, unless that entry gets costlier (`cos(q2 - q3 + 5*pi/9)`
//! and `sin(q2/2 + q3/2 + 5*pi/18)` in one report, never `-4*pi/9`); `coefs.rs` lifts constant
//! coefficients out of the angles: for a non-constant scalar with pi offsets outside the multiples
//! of pi/12, each mode written back in `cos F`, `sin F` of its offset-free angle (`cos(F + a) = cos
//! F cos a - sin F sin a`), the two coefficients of one angle joined into `R cos(F - phi)` when
//! `phi` is a rational multiple of pi (found from `atan2`, checked exactly), and each constant
//! outside pi/12 (up to a rational factor) a fresh symbol; that scalar's closed form, with each
//! symbol replaced by its constant's closed form (`sin(pi/7) cos(pi/9) cos(q)`, `cos(pi/9) sin(q +
//! pi/7)`, was a sum over pi/63), kept when shorter and checked like every other (a derivative's
//! closed form then starts afresh); the unlifted coefficients of `cos F` and `sin F` lifted only
//! when joining them into phases left some constant outside pi/12, and neither when the terms show
//! that it cannot (one sinusoid per monomial and angle, or two at right angles with `tan^2` 1/3, 1
//! or 3: the Jaco-style arm's entries); `coefs::phase_angles` does the same for angles at offsets
//! that are multiples of pi/12, which the canonical form holds as radicals (`l1 sin(x + pi/6)` is
//! `l1 (cos x + sqrt(3) sin x)/2`): the two coefficients of one monomial's `cos F` and `sin F`, `R
//! cos(phi)` and `R sin(phi)` with `phi` a multiple of pi/24 off the multiples of pi/2, make `R
//! cos(W)` with a fresh angle symbol `W = F - phi`, and each `W` is replaced back in the closed
//! form, shown as the cosine or sine with the cheaper angle (`l1 cos(x - pi/3) + l2 cos(x + y -
//! 2*pi/3)`); the whole-modes shape is not factored when a lower bound of its cost
//! (`factor::cost_lower_bound`: each distinct atom and symbol a leaf, each atom a call, each
//! monomial a summand) is not below the regrouped shape's, and is factored first when that bound is
//! below the regrouped shape's own lower bound (`m` monomials, `m - 1` additions:
//! `factor::summands_lower_bound`), the regrouped shape then not factored when the whole one costs
//! less than that (the Jaco-style arm's entries as given), and `alt::best_alternative` checks only
//! candidates shorter than the form found before; `closed_form_prepared` keeps the regrouped
//! monomials of a scalar so that `closed_form_of_derivative` starts a derivative's closed form from
//! them (the Jacobian of a chain: no second expansion into single angles); `closed_form_cos_sin`
//! factors a cos/sin polynomial and shows its placeholders as cos/sin; `trace.rs` records, for
//! `closed_form_traced`, each round's sum (the first is the expanded sum) and every identity
//! applied (`TraceStep`, `Identity`), observing the recombination without steering it.
//! `notation.rs` names angles the way every printer and emitter does: `shorthand_name` (`c12`,
//! `s123`), `angle_text` (`theta1 + theta2`), `TrigNames`.

mod alt;
mod coefs;
mod common;
pub mod congruence;
mod cprod;
mod cspoly;
mod decimals;
mod expr;
mod extra;
mod factor;
mod mon;
mod notation;
mod offsets;
mod peel;
mod recombine;
pub(crate) mod rename;
mod roots;
mod square;
mod trace;
mod trigfac;
pub(crate) mod turn;
mod zfactor;

pub use crate::scalar::Trig;
pub use common::CommonOffsets;
pub use decimals::{decimal_form, shows_as_decimal};
pub use expr::{Angle, Cost, Expr};
pub use notation::{angle_text, angle_text_decimals, angle_text_with, shorthand_name, TrigNames};
pub(crate) use notation::{decimal_constant, write_shorthand};
pub(crate) use offsets::Hint;
pub use trace::{Identity, TraceStep};

use crate::scalar::FxHasher;
use crate::{Scalar, ScalarError, Sym};
use std::collections::hash_map::Entry;
use std::hash::{BuildHasherDefault, Hasher};

/// The largest number of monomials the split shape may have before it is skipped.
const SPLIT_LIMIT: usize = 100_000;

/// The most readable equivalent form of `x`: fewest operations, then fewest calls.
///
/// # Errors
/// When `x` is an error value, and when the search or the check of its result against `x`
/// runs out of the work budget or over the term limit (see [`crate::Context::with_work_budget`]).
pub fn closed_form(x: &Scalar) -> Result<Expr, ScalarError> {
    if let Some(e) = Memo::get(x) {
        return Ok(e);
    }
    let r = closed_form_prepared(x).0;
    if let Ok(e) = &r {
        Memo::put(x, e);
    }
    r
}

/// The closed forms found during one outermost search, by scalar: the searches call
/// [`closed_form`] on their pieces (the factors of `cspoly.rs` and every pair of them, the
/// rest beside a constant product, ...), and the same pieces come back in each reading and
/// at every level of that recursion (`sin(1)*sin(2)*sin(3)` asked for the same scalars'
/// closed forms again and again). A memo lives only while the outermost
/// [`closed_form_prepared`] of its thread runs, so it never outlives the context (limits,
/// budget) its entries were found in; errors are never remembered. The closed forms found
/// inside `cspoly.rs`'s search of a factor's or a pair's closed form (without factoring them
/// again: `cspoly::nested_open`) are kept apart, so that a search outside it never takes a
/// closed form made without its factorizations.
struct Memo;

/// The most closed forms one outermost search remembers.
const MEMO_LIMIT: usize = 4096;

/// The memo's tables: the searches outside `cspoly.rs`'s nested ones, and those inside.
type MemoTables = [FxMap<Scalar, Expr>; 2];

thread_local! {
    static MEMO: std::cell::RefCell<Option<MemoTables>> =
        const { std::cell::RefCell::new(None) };
}

impl Memo {
    /// Opens the memo when none is open on this thread; the guard closes the memo it opened.
    fn open() -> MemoGuard {
        MemoGuard(MEMO.with(|m| {
            let mut m = m.borrow_mut();
            let opened = m.is_none();
            if opened {
                *m = Some(Default::default());
            }
            opened
        }))
    }

    /// The table of the searches of this kind (see [`Memo`]).
    fn table() -> usize {
        usize::from(cspoly::nested_open())
    }

    fn get(x: &Scalar) -> Option<Expr> {
        let t = Self::table();
        MEMO.with(|m| m.borrow().as_ref().and_then(|m| m[t].get(x).cloned()))
    }

    fn put(x: &Scalar, e: &Expr) {
        let t = Self::table();
        MEMO.with(|m| {
            if let Some(m) = m.borrow_mut().as_mut() {
                if m[t].len() < MEMO_LIMIT {
                    m[t].insert(x.clone(), e.clone());
                }
            }
        });
    }
}

/// Closes the memo of [`Memo::open`] when it opened it.
struct MemoGuard(bool);

impl Drop for MemoGuard {
    fn drop(&mut self) {
        if self.0 {
            MEMO.with(|m| *m.borrow_mut() = None);
        }
    }
}

type FxMap<K, V> = std::collections::HashMap<K, V, BuildHasherDefault<FxHasher>>;

/// The regrouped monomials [`closed_form`] found for a scalar, kept so that the closed forms of
/// its derivatives start from them ([`closed_form_of_derivative`]) instead of from the
/// expanded Fourier series, and whether that regrouped shape won over the whole modes. `None`
/// when the split shape was skipped (too large) or failed.
pub struct Prepared(
    Option<(mon::Ctx, Vec<mon::Mon>, bool)>,
    Option<(offsets::Shift, Scalar)>,
);

/// [`closed_form`], and what it found on the way (see [`Prepared`]).
///
/// A scalar whose symbolic modes carry offsets outside the multiples of pi/12 is also tried
/// with the offsets absorbed into its symbols (`offsets.rs`: `cos(q2 + 5*pi/9)` regrouped
/// and factored like `cos(q2)`), the shorter of the two kept (`alt::shorter`; the shifted
/// one on ties).
pub fn closed_form_prepared(x: &Scalar) -> (Result<Expr, ScalarError>, Prepared) {
    closed_form_prepared_as(x, AsGiven::Searched, None)
}

/// [`closed_form_prepared`] as an `fk` report shows a pose entry: with its offsets absorbed
/// into the joint angles when they can be (`offsets.rs`), without the search of the form as
/// given beside it ([`AsGiven::Skipped`]).
///
/// Why: a report's entries carry the joints' offsets (`theta2 = q2 + 5*pi/9`), and the shifted
/// form is written in the angles the robot file wrote. The search as given only wins by
/// another grouping of the offsets' phases, by a few operations (the Jaco-style arm's `dq[1]`:
/// 41 against 44), and costs twice the shifted search (its phases split every mode in two):
/// on the Jaco-style arm's `fk --jacobian` it was 19 M of 78 M instructions (callgrind, one
/// thread, session 31). Measured on the `fk --jacobian` reports of every robot file in the
/// repository (61): 22 rows of 2 robots change (the Jaco-style arm and
/// `datasheet_base_yaw.toml`), 16 of them printed longer (134 characters in all, the few
/// operations the search as given won by), 6 shorter (154 characters). Expressions
/// (`closed_form`, the REPL, `-e`) and the searches nested in a report's search both ways
/// as before.
///
/// With `hint` (`offsets::Hint`: `x` is the hint's `y` with its symbols shifted, as an
/// offset-free product's entry is shifted back), the shifted scalar is the hint's `y` when the
/// shift that `x`'s offsets are absorbed into is the hint's, and is not made again
/// (`offsets::Shift::apply_hinted`): the same scalar, so the same result. Only `x` itself takes
/// the hint, not the scalars derived from it (constants lifted, phases as angles).
pub(crate) fn report_form_prepared(
    x: &Scalar,
    hint: Option<Hint>,
) -> (Result<Expr, ScalarError>, Prepared) {
    closed_form_prepared_as(x, AsGiven::Skipped, hint)
}

/// [`report_form_prepared`]'s closed form.
pub(crate) fn report_form(x: &Scalar, hint: Option<Hint>) -> Result<Expr, ScalarError> {
    report_form_prepared(x, hint).0
}

/// Whether a scalar with offsets absorbed ([`prepared_shifted`]) is also searched as given.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum AsGiven {
    /// Searched (where [`as_given_may_win`] says it may win), the shorter kept.
    Searched,
    /// Not searched: the shifted form is kept (an `fk` report's entries).
    Skipped,
}

/// [`closed_form_prepared`], the form as given searched or not (`as_given`), with `hint` (see
/// [`report_form_prepared`]).
fn closed_form_prepared_as(
    x: &Scalar,
    as_given: AsGiven,
    hint: Option<Hint>,
) -> (Result<Expr, ScalarError>, Prepared) {
    let memo = Memo::open();
    let (e, prepared) = prepared_shifted(x, as_given, hint);
    let Ok(found) = e else {
        return (e, prepared);
    };
    // Constants lifted out of the angles, when shorter still (`coefs.rs`); derivatives then
    // start from the expanded series.
    let mut best: Option<Expr> = None;
    let mut lifting = coefs::Lifting::new(x);
    for phased in [true, false] {
        let Some(l) = lifting.as_mut().and_then(|l| l.lift(phased)) else {
            continue;
        };
        let Ok(c) = prepared_shifted(&l.scalar, as_given, None)
            .0
            .map(|c| l.substitute(c))
        else {
            continue;
        };
        let c = joined(c, x, memo.0);
        if alt::shorter(&c, best.as_ref().unwrap_or(&found)) && verified(&c, x) {
            best = Some(c);
        }
    }
    // Angles at offsets that are multiples of pi/12, hidden in radicals, as angles again
    // (`l1 sin(x + pi/6)`, canonically `l1 (cos(x) + sqrt(3) sin(x))/2`).
    if let Some(a) = coefs::phase_angles(x) {
        if let Some(c) = prepared_shifted(&a.scalar, as_given, None)
            .0
            .ok()
            .and_then(|c| a.substitute(c))
            .map(|c| joined(c, x, memo.0))
        {
            if alt::shorter(&c, best.as_ref().unwrap_or(&found)) && verified(&c, x) {
                best = Some(c);
            }
        }
    }
    // Pairs of summands joined in the angles shown (`extra::joined_form`).
    if best.is_none() {
        best = extra::joined_form(&found, memo.0, |c| verified(c, x));
    }
    match best {
        Some(c) => (Ok(c.symbols_leading()), Prepared(None, None)),
        None => (Ok(found), prepared),
    }
}

/// `e` (a form of `x`) with pairs of its summands joined when that is shorter
/// (`extra::joined_form`): the angles that constants lifted out or radicals made angles again
/// (`coefs.rs`) are first seen in the form shown (`cos(r - u2/2 + pi/3) + cos(r + 3*u2/2 +
/// pi/3)` is `2 cos(r + u2/2 + pi/3) cos(u2)`).
fn joined(e: Expr, x: &Scalar, outermost: bool) -> Expr {
    extra::joined_form(&e, outermost, |c| verified(c, x)).unwrap_or(e)
}

/// [`closed_form_prepared`] without the constants lifted; with `hint`, the shifted scalar
/// may be the hint's (see [`report_form_prepared`]).
///
/// With offsets absorbed (`offsets.rs`), the shifted form `e` is found first and, with
/// [`AsGiven::Searched`], the form as given is searched with `e`'s key as its cap ([`best_of`]'s
/// `cap`): the form as given is taken only when [`alt::shorter`] than `e`, so a search of it
/// that gives up on forms not below `e` changes nothing. Where [`as_given_may_win`] (a
/// measured rule, not a proven one) says it cannot win, it is not made. Otherwise the choice is the same as searching both in
/// full:
/// - the capped search gives the uncapped search's form whenever either is strictly below
///   the cap (`alt::best_alternative_below`; every other step is the same), so when the form
///   as given is shorter than `e`, it is taken either way;
/// - otherwise neither is shorter, and `e` is taken when it passes its check, as before; when
///   it does not (a defect the check guards against), the form as given is searched again
///   without the cap and taken, as before.
///
/// The work budget sees the same: the form as given used to be searched first, so it is the
/// fallback when the shifted search fails (runs out of the budget, say). Found after that
/// failed search, it would find the budget spent (`stress::heavy_factorizations_stay_exact_
/// within_the_budget`: the shifted search of `cos(3*q + 2*pi/9)*cos(-2*y)` spends all of its
/// 3,000,000 units factoring `cos(3 q) cos(2 y)` in `cspoly.rs`, and the form as given, 40
/// units, then failed too: the first reordering's 588 units over). So a fallback search of
/// the form as given runs in the budget left before the shifted search ([`as_first`]), its
/// work charged after it. `e` is checked (exactly, in debug builds) only once the form as
/// given has lost, as before. At the budget's edge the order still tells: where the form as
/// given used to spend the budget the shifted search needed, the shifted form is now found.
/// A search as given that [`as_given_may_win`] skips leaves its work in the budget: 2 of 120
/// random 5-joint chains whose `fk --jacobian` ran out of the default budget (and printed the
/// recurrence) now print the expanded report, the one both ways print with a raised budget.
fn prepared_shifted(
    x: &Scalar,
    as_given: AsGiven,
    hint: Option<Hint>,
) -> (Result<Expr, ScalarError>, Prepared) {
    let shifted = offsets::find(x).and_then(|s| s.apply_hinted(x, hint).map(|y| (s, y)));
    let Some((shift, y)) = shifted else {
        return prepared_unshifted(x, None);
    };
    // No context entered: nothing is charged, and none is entered for the fallback.
    let before = (crate::scalar::work_left() != u64::MAX).then(crate::Context::current);
    let (shifted, yprep) = prepared_unshifted(&y, None);
    let Ok(mut e) = shifted.map(|e| shift.unshift(e)) else {
        return as_first(&before, x);
    };
    // The shift changes what an angle costs (`cos(y - pi/7) cos(y + pi/7)` ties with the sum in
    // `y`, `cos(x) cos(x + 2*pi/7)` beats it in `x`): the candidates of `alt.rs` for the
    // shifted scalar are compared again once shifted back.
    for a in alt::candidates(&y).into_iter().map(|a| shift.unshift(a)) {
        if alt::shorter(&a, &e) && a.to_scalar() == *x {
            e = a;
            break;
        }
    }
    if as_given == AsGiven::Searched && as_given_may_win(x, &e) {
        let (plain, prepared) = match prepared_unshifted(x, cap_of(x, &e)) {
            // Out of the budget (or another limit) after the shifted search: as when first.
            (Err(_), _) => as_first(&before, x),
            found => found,
        };
        // On equal cost the shifted form: its angles are the ones the user wrote.
        if plain.as_ref().is_ok_and(|p| alt::shorter(p, &e)) {
            return (plain, prepared);
        }
    }
    if !verified(&e, x) {
        return as_first(&before, x);
    }
    (Ok(e.symbols_leading()), Prepared(yprep.0, Some((shift, y))))
}

/// The fewest terms a scalar with offsets must have for [`as_given_may_win`] to skip its search as
/// given. A measured threshold (with [`AS_GIVEN_OPS_PER_TERM`]), not a proven one: the search as
/// given beats the shifted form on small scalars by another grouping of its phases (`cos(a +
/// 5*pi/18)` beside `cos(a - 2*pi/9)`, 41 operations against 44), so no argument from the shape
/// alone rules it out. Its wins by a printed offset alone (`sin(q2 - q3 + pi/18)` against `cos(q2 -
/// q3 - 4*pi/9)`) are left out by reading the shifted form at its cheapest offsets
/// (`Expr::cheapest_offsets`; the form shown is not changed): against that form, the wins on the
/// corpus below fall from 6,161 to 1,457. Measured on the `fk --jacobian` reports of every robot in
/// the repository and of 120 random DH chains of 3 to 6 joints (offsets `k pi/n` on two joints in
/// five, n in 5, 7, 9, 10, 18; twists pi/3, pi/4, pi/6, pi/2, 0, pi) and on
/// `scripts/offsets_same.py`'s expressions (seeds 1, 2, 3, 7, 2211; 1,500), split in two halves
/// (even and odd chains and expressions): 14,402 searches as given made, 1,457 won. The largest
/// winner against a shifted form of fewer than [`AS_GIVEN_OPS_PER_TERM`] operations a term had 30
/// terms in the half the threshold was read off (a 3-joint chain's entry, 0.8 operations a term)
/// and 27 in the other; none of 32 terms or more under the ratio won (214 searches, now skipped).
/// Before the cheapest offsets, a 44-term scalar won under the ratio, hence the earlier threshold
/// of 64. The Jaco-style arm's 36- and 42-term entries (1.25 and 1.07 operations a term) are above
/// it; its 29-term one (1.59) is not.
const AS_GIVEN_MIN_TERMS: usize = 32;

/// The most operations a term (of the scalar as given) the shifted form may have for
/// [`as_given_may_win`] to skip the search as given (with [`AS_GIVEN_MIN_TERMS`]; measured
/// on the same corpora): every form as given that won on a scalar of 32 terms or more did so
/// against a shifted form of 2.08 operations a term or more (2.19 and 2.08 in the two
/// halves).
const AS_GIVEN_OPS_PER_TERM: usize = 2;

/// Whether the search of `x` as given may be shorter than its shifted form `e`: `false`
/// when `x` is large ([`AS_GIVEN_MIN_TERMS`]) and `e` short for its size
/// ([`AS_GIVEN_OPS_PER_TERM`]), a measured rule: there the shifted search has regrouped
/// what the search as given sees as twice as many phases (the Jaco-style arm's 96-term
/// entries, 48 terms once shifted, 143 operations; 835 as given; its 42-term ones, 45
/// operations; 124 as given), and that search is skipped.
fn as_given_may_win(x: &Scalar, e: &Expr) -> bool {
    let terms = x.len();
    // The rule is read against `e` at its cheapest offsets (`sin(a + pi/18)` for `cos(a -
    // 4*pi/9)`, the value unchanged), which the form as given does not beat by a printed offset
    // alone; `e` is shown as found (a report's common offsets are chosen from its angles). Made
    // only for scalars large enough for the rule to apply.
    let may = terms < AS_GIVEN_MIN_TERMS || {
        let cheapest = e.clone().cheapest_offsets(&|t| alt::full_cost(t).0);
        alt::choice_key(&cheapest).0 >= AS_GIVEN_OPS_PER_TERM * terms
    };
    #[cfg(test)]
    if !may {
        tests::AS_GIVEN_SKIPS.with(|n| n.set(n.get() + 1));
        if tests::AS_GIVEN_ALWAYS.with(std::cell::Cell::get) {
            return true;
        }
    }
    may
}

/// The uncapped search of `x` as given, in `before` (the context as it was before the
/// shifted search of [`prepared_shifted`]; `None` when none was entered), its work then
/// charged to the context entered now (an error of that charge is left to the next one: the
/// result was found within `before`).
fn as_first(before: &Option<crate::Context>, x: &Scalar) -> (Result<Expr, ScalarError>, Prepared) {
    let Some(before) = before else {
        return prepared_unshifted(x, None);
    };
    let entered = before.enter();
    let found = prepared_unshifted(x, None);
    let used = entered.work_used();
    drop(entered);
    let _ = crate::scalar::charge(used);
    found
}

/// The cap of a search of `x` whose result is taken only when [`alt::shorter`] than `e`: the
/// first two parts of `e`'s [`alt::choice_key`]. `None` (no cap) when some mode of `x` holds a
/// rational constant: its forms' angles may then be turned by `Expr::symbols_leading`, which
/// can drop a negation after the search, so a form not below the cap inside the search could
/// be below it once shown.
fn cap_of(x: &Scalar, e: &Expr) -> Option<(usize, usize)> {
    #[cfg(test)]
    if tests::UNCAPPED.with(std::cell::Cell::get) {
        return None;
    }
    let constant = x.terms().map_or(true, |t| {
        t.iter()
            .any(|u| u.mode.freq.iter().any(|(s, _)| s.is_one()))
    });
    let k = alt::choice_key(e);
    (!constant).then_some((k.0, k.1))
}

/// Whether `e` equals `x`: exactly in debug builds, numerically first in release builds (as
/// [`best_of`] checks).
fn verified(e: &Expr, x: &Scalar) -> bool {
    (!cfg!(debug_assertions) && agrees_numerically(e, x)) || e.to_scalar() == *x
}

/// [`closed_form_prepared`] without the offsets absorbed; with `cap`, as [`best_of`] with it.
fn prepared_unshifted(
    x: &Scalar,
    cap: Option<(usize, usize)>,
) -> (Result<Expr, ScalarError>, Prepared) {
    if let Err(e) = x.terms() {
        return (Err(e.clone()), Prepared(None, None));
    }
    let split_size: usize = x
        .terms()
        .map(|t| t.iter().map(|t| 1usize << t.mode.freq.len().min(30)).sum())
        .unwrap_or(0);
    if split_size > SPLIT_LIMIT {
        return (
            whole_form(x).map(|(e, _)| e.symbols_leading()),
            Prepared(None, None),
        );
    }
    if skip_split(x, split_size) {
        return (
            best_whole(x).map(Expr::symbols_leading),
            Prepared(None, None),
        );
    }
    let (mut sctx, smons) = mon::split_modes(x);
    let smons = recombine::recombine(&mut sctx, smons);
    let result = best_of(x, &sctx, &smons, true, cap);
    let split_won = result.as_ref().is_ok_and(|(_, split)| *split);
    (
        result.map(|(e, _)| e.symbols_leading()),
        Prepared(Some((sctx, smons, split_won)), None),
    )
}

/// The most a scalar's split shape may multiply its number of terms by, on average, before
/// the split shape is skipped: modes of 8 or more symbols each (the half-angle series of a
/// planar chain of 10 joints, `cos(q1/2 - q2/2 + ... - q10/2)`: 1,024 single-angle products
/// per term, which the recombination only puts back together).
const WIDE_SPLIT: usize = 256;

/// The least a scalar's split shape multiplies its number of terms by, on average, for the
/// test of [`disjoint_parts`] to be worth making (modes of 5 or more symbols).
const DISJOINT_SPLIT: usize = 32;

/// Whether the split shape of `x` (of `split_size` single-angle products) is skipped for the
/// whole modes: when it is very large for the number of terms ([`WIDE_SPLIT`]), or large
/// and unable to regroup anything the whole modes do not ([`disjoint_parts`]).
fn skip_split(x: &Scalar, split_size: usize) -> bool {
    split_size > WIDE_SPLIT * x.len()
        || (split_size > DISJOINT_SPLIT * x.len() && disjoint_parts(x))
}

/// Whether no two terms of `x` expand, split into single angles, into a common product of
/// atoms: each term's expansion is the products of `cos` or `sin` of `c s` over its mode's
/// symbols `s` with coefficients `c`, times its cofactor (radicand and monomial), so two terms
/// can meet only if their cofactors and their sets of `(s, |c|)` agree (a pi offset is left
/// out of the comparison, which only makes it stricter). When no two can meet, the
/// recombination only reassembles each term, and the split shape is the whole modes again
/// (the sum of cumulative angles `c1 + c12 + ... + c1..10` of a planar chain, say).
fn disjoint_parts(x: &Scalar) -> bool {
    let Ok(terms) = x.terms() else {
        return false;
    };
    // The keys are hashed, not built (one word per term), and compared when their hashes
    // meet: the first two terms with equal keys end the search. A collision of different
    // keys leaves the answer to `disjoint_by_sorting`, which compares every pair of equal
    // hashes.
    let mut seen: std::collections::HashMap<u64, usize, BuildHasherDefault<FxHasher>> =
        std::collections::HashMap::with_capacity_and_hasher(terms.len(), Default::default());
    let mut collided = false;
    for (i, t) in terms.iter().enumerate() {
        match seen.entry(key_hash(t)) {
            Entry::Occupied(o) => {
                if same_key(&terms[*o.get()], t) {
                    return false;
                }
                collided = true;
            }
            Entry::Vacant(v) => {
                v.insert(i);
            }
        }
    }
    !collided || disjoint_by_sorting(terms)
}

/// [`disjoint_parts`] by sorting the hashes of the keys and comparing every pair within a run
/// of equal hashes.
fn disjoint_by_sorting(terms: &[crate::scalar::Term]) -> bool {
    let mut hashed: Vec<(u64, usize)> = terms
        .iter()
        .enumerate()
        .map(|(i, t)| (key_hash(t), i))
        .collect();
    hashed.sort_unstable();
    let mut run = 0;
    while run < hashed.len() {
        let end = run + hashed[run..].partition_point(|&(h, _)| h == hashed[run].0);
        for i in run..end {
            for j in i + 1..end {
                if same_key(&terms[hashed[i].1], &terms[hashed[j].1]) {
                    return false;
                }
            }
        }
        run = end;
    }
    true
}

/// A hash of a term's key for [`disjoint_parts`]: its radicand, monomial and frequencies
/// without their signs. A symbol counts by the length and last eight bytes of its name: a
/// function of the name, so equal keys hash alike, in one word.
fn key_hash(t: &crate::scalar::Term) -> u64 {
    let name = |s: &Sym| {
        let b = s.name().as_bytes();
        let tail = &b[b.len().saturating_sub(8)..];
        let mut w = [0u8; 8];
        w[..tail.len()].copy_from_slice(tail);
        u64::from_le_bytes(w) ^ (b.len() as u64).rotate_right(8)
    };
    let mut h = FxHasher::default();
    h.write_u64(t.rad);
    for (s, e) in t.mono.iter() {
        h.write_u64(name(s));
        h.write_u32(*e);
    }
    h.write_usize(t.mono.len());
    for (s, c) in t.mode.freq.iter() {
        h.write_u64(name(s));
        h.write_i64(c.numer().abs());
        h.write_i64(*c.denom());
    }
    h.finish()
}

/// Whether two terms have the same key for [`disjoint_parts`].
fn same_key(a: &crate::scalar::Term, b: &crate::scalar::Term) -> bool {
    a.rad == b.rad
        && a.mono == b.mono
        && a.mode.freq.len() == b.mode.freq.len()
        && a.mode
            .freq
            .iter()
            .zip(b.mode.freq.iter())
            .all(|((s, c), (r, d))| {
                s == r && c.numer().abs() == d.numer().abs() && c.denom() == d.denom()
            })
}

/// The whole-modes shape or, when strictly shorter, a candidate of `alt.rs`, checked against
/// `x` like [`best_of`]'s result.
fn best_whole(x: &Scalar) -> Result<Expr, ScalarError> {
    let (w, _) = whole_form(x)?;
    let best = alt::best_alternative(x, &w).unwrap_or(w);
    if !cfg!(debug_assertions) && agrees_numerically(&best, x) {
        return Ok(best);
    }
    let value = best.to_scalar();
    if let Some(e) = value.as_error() {
        return Err(e.clone());
    }
    if value == *x {
        Ok(best)
    } else {
        debug_assert!(!x.is_canonical(), "closed form does not equal its input");
        whole_form(x).map(|(e, _)| e)
    }
}

/// The whole-modes shape: each Fourier mode one factor, factored.
fn whole_form(x: &Scalar) -> Result<(Expr, Cost), ScalarError> {
    let (wctx, wmons) = mon::whole_modes_joined(x);
    let (whole, wc) = factor::build(&wmons)?;
    Ok((whole.to_expr(&wctx), wc))
}

/// The cheaper of the regrouped monomials `smons` (factored) and, with `try_whole`, the
/// whole-modes shape of `x`, checked against `x`; and whether the regrouped shape was taken.
///
/// With `cap` (see [`prepared_shifted`]) the result is taken by the caller only when strictly
/// below it ([`alt::shorter`] than a form whose key starts with `cap`): the candidates of
/// `alt.rs` are checked only below it (`alt::best_alternative_below`: the same candidate
/// whenever one below `cap` is found either way, none below it otherwise), and a form not
/// below it is returned unchecked (the caller discards it; the check fails only on a defect,
/// `x` being canonical). The result is the uncapped one whenever either is below `cap`: both
/// ways take the same shape; the same alternative, or none below `cap`; and when `best` is
/// below `cap` (so `cap` does not narrow the candidates), the same check and fallback.
fn best_of(
    x: &Scalar,
    sctx: &mon::Ctx,
    smons: &[mon::Mon],
    try_whole: bool,
    cap: Option<(usize, usize)>,
) -> Result<(Expr, bool), ScalarError> {
    // Without trigonometric terms both shapes are the same monomials (a polynomial in cos/sin
    // placeholders, say): the whole shape would be factored again to the same cost.
    let try_whole = try_whole && !same_monomials(x, smons);
    // The same monomials as `whole_form`'s (modes joined into one angle where they are one),
    // with a lower bound of their factored cost.
    let wholes = try_whole.then(|| {
        let (wctx, wmons) = mon::whole_modes_joined(x);
        let bound = factor::cost_lower_bound(&wmons);
        (wctx, wmons, bound)
    });
    // The whole shape is taken only when strictly cheaper. Factored first when even its lower
    // bound is below the regrouped shape's: when its cost is below that bound too, the
    // regrouped shape cannot be taken and is not factored (the Jaco-style arm's entries as
    // given, whose regrouped shapes were the larger part of their search); otherwise it is
    // factored as below, which would have factored the whole shape too.
    let split_bound = factor::summands_lower_bound(smons);
    let early = match &wholes {
        Some((wctx, wmons, bound)) if *bound < split_bound => {
            let (w, wc) = factor::build(wmons)?;
            Some((w.to_expr(wctx), wc))
        }
        _ => None,
    };
    let (best, split_won, whole) = match early {
        Some((w, wc)) if wc < split_bound => {
            debug_assert!(factor::build(smons).map_or(true, |(_, sc)| sc >= split_bound));
            (w.clone(), false, Some((w, wc)))
        }
        early => {
            let (split, sc) = factor::build(smons)?;
            // Not searched when even a lower bound of its cost is not below `sc` (the common
            // case: many more distinct modes than the regrouped shape has calls).
            let whole = match (early, &wholes) {
                (Some(w), _) => Some(w),
                (None, Some((wctx, wmons, bound))) if *bound < sc => {
                    let (w, wc) = factor::build(wmons)?;
                    Some((w.to_expr(wctx), wc))
                }
                (None, Some((_, wmons, bound))) => {
                    debug_assert!(factor::build(wmons).map_or(true, |(_, wc)| wc >= *bound));
                    None
                }
                (None, None) => None,
            };
            // Prefer the regrouped shape on ties: it is the one textbooks print.
            match &whole {
                Some((w, wc)) if *wc < sc => (w.clone(), false, whole),
                _ => (split.to_expr(sctx), true, whole),
            }
        }
    };
    // A shorter form of another kind (checked exactly by `best_alternative`).
    // An alternative is returned only once it equals `x` exactly: not checked again (in debug
    // builds that second expansion could run the budget out on a form already verified).
    let (best, verified) = match alt::best_alternative_below(x, &best, cap) {
        Some(e) => (e, true),
        None => (best, false),
    };
    // A form not below `cap` is discarded by the caller: its check (an expansion in debug
    // builds) is not made. It could fail only on a defect (`x`, an error-free value, is
    // canonical: see the `debug_assert` below).
    if verified
        || cap.is_some_and(|c| !below(&best, c))
        || (!cfg!(debug_assertions) && agrees_numerically(&best, x))
    {
        return Ok((best, split_won));
    }
    let value = best.to_scalar();
    if let Some(e) = value.as_error() {
        // The check ran out of the budget or the term limit: no verified form to give.
        return Err(e.clone());
    }
    if value == *x {
        Ok((best, split_won))
    } else {
        // Past the degree bound of exact constants, equal values may differ in form.
        debug_assert!(!x.is_canonical(), "closed form does not equal its input");
        let (w, _) = match whole {
            Some(w) => w,
            None => whole_form(x)?,
        };
        Ok((w, false))
    }
}

/// Whether `e` is chosen over a form whose [`alt::choice_key`] starts with `cap`.
fn below(e: &Expr, cap: (usize, usize)) -> bool {
    let k = alt::choice_key(e);
    (k.0, k.1) < cap
}

/// Whether `x` has no trigonometric term and its whole-modes monomials are `smons`.
fn same_monomials(x: &Scalar, smons: &[mon::Mon]) -> bool {
    let trig_free = x.terms().is_ok_and(|t| t.iter().all(|t| t.mode.is_unit()));
    trig_free && mon::whole_modes(x).1 == smons
}

/// The closed form of `dx`, the derivative of the scalar `p` was prepared from with respect to
/// the symbol `var`: the prepared monomials are differentiated (each cosine or sine of an
/// angle holding `var` turns into the other, each power of `var` drops by one), regrouped
/// and factored, compared with the whole-modes shape of `dx` when that shape won for the
/// prepared scalar, and checked against `dx`. Much cheaper than [`closed_form`] on `dx` for the
/// Jacobian of a chain, whose entries are long half-angle series: the expansion into single
/// angles is not redone. The form may differ from `closed_form(dx)`; it equals `dx`. Where it
/// starts over, it searches as an `fk` report does (`report_form`: the form in the joints'
/// angles, not also as given).
///
/// # Errors
/// As [`closed_form`].
pub fn closed_form_of_derivative(
    p: &Prepared,
    var: &str,
    dx: &Scalar,
) -> Result<Expr, ScalarError> {
    if let Err(e) = dx.terms() {
        return Err(e.clone());
    }
    // Prepared with its offsets absorbed: the derivative (with respect to the same symbol,
    // d/dx = d/dy) is shifted alike, its closed form shifted back.
    if let Some((shift, y)) = &p.1 {
        // The shifted derivative is the derivative of the shifted scalar: made from it, in
        // radicals, not by shifting `dx` back out of its cyclotomic basis (the Jaco-style
        // arm's Jacobian: 20 M instructions).
        let dy = y.diff(var);
        let dy = match dy.terms() {
            Ok(_) => dy,
            Err(_) => match shift.apply(dx) {
                Some(dy) => dy,
                None => return report_form(dx, None),
            },
        };
        debug_assert!(shift.apply(dx).is_none_or(|d| d == dy), "d/d{var} shifted");
        let e = shift.unshift(derivative_unshifted(p, var, &dy)?);
        return if verified(&e, dx) {
            Ok(e)
        } else {
            report_form(dx, None)
        };
    }
    derivative_unshifted(p, var, dx)
}

/// [`closed_form_of_derivative`] for a scalar and monomials in the same symbols.
///
/// What it costs, measured on the Jaco-style arm's `fk --jacobian` (callgrind, one thread,
/// session 30): 23.8 M instructions for the 36 derivatives searched of the 48 rows (the
/// other 12 are rational multiples of a searched one, shared by `app/fk.rs`). The 20 of the
/// dual part (96 terms, 48 shifted; the regrouped shape won for the component and wins
/// again, no candidate of `alt.rs` is made) cost 0.60-0.62 M each, four fifths of it the
/// factor search of the differentiated monomials; the 8 of `dq[1]` and `dq[2]` (16 terms;
/// the whole modes won for the component, so both shapes are factored here) 1.22-1.32 M
/// each, where a form of `extra.rs` (pairs joined, common factors) wins, 139 operations down
/// to 41-52, and `trigfac.rs`'s sinusoid factors spend 0.25 M finding none; the 8 of `dq[0]`
/// and `dq[3]` (16 terms, 8 shifted) 0.18-0.19 M each. Left, with the reasons: the 8 of the `q1` column (the base
/// joint's derivative is a signed permutation of the components) are rational multiples of
/// pose entries, 5.4 M, but the pose's search is another route and its forms change rows
/// (see `expanded_sections`); and the component's factored tree cannot stand in for this
/// search: the differentiated monomials are the component's with each atom in `var` turned
/// (cosine and sine swapped) and scaled by its own signed coefficient, which changes the
/// coefficients the search's costs count (a common factor's sign, the rational content), so
/// its choice is not provably the renamed tree.
fn derivative_unshifted(p: &Prepared, var: &str, dx: &Scalar) -> Result<Expr, ScalarError> {
    let Some((ctx, mons, split_won)) = &p.0 else {
        return report_form(dx, None);
    };
    let mut ctx = ctx.clone();
    let dmons = mon::differentiate(&ctx, mons, var);
    let dmons = recombine::recombine(&mut ctx, mon::merge(dmons));
    // Where the regrouped shape won for the scalar, it is kept for its derivatives (which have
    // the same modes) without factoring the whole modes again.
    best_of(dx, &ctx, &dmons, !split_won, None).map(|(e, _)| e.symbols_leading())
}

/// The closed form of a polynomial in cosine and sine placeholders (see
/// [`Scalar::to_cos_sin_polynomial`]), factored as a polynomial and shown with each
/// placeholder as the cosine or sine of its angle: `c1 (a2 c2 + a3 c23)` style for chains
/// whose Fourier form is too large. Checked exactly against `x` as a polynomial.
///
/// # Errors
/// As [`closed_form`].
pub fn closed_form_cos_sin(x: &Scalar) -> Result<Expr, ScalarError> {
    Ok(closed_form(x)?.with_placeholders_as_trig())
}

/// `x` as its plain sum of monomials, each Fourier mode one trigonometric factor: what an
/// expanding CAS prints, for comparing sizes (see `bench/compare`).
pub fn expanded_form(x: &Scalar) -> Result<Expr, ScalarError> {
    if let Err(e) = x.terms() {
        return Err(e.clone());
    }
    let (ctx, mons) = mon::whole_modes(x);
    Ok(match mons.len() {
        0 => Expr::zero(),
        1 => factor::mon_expr(&mons[0]).to_expr(&ctx),
        _ => Expr::Add(
            mons.iter()
                .map(|m| factor::mon_expr(m).to_expr(&ctx))
                .collect(),
        ),
    })
}

/// Whether `e` and `x` have the same value at a fixed pseudo-random point, to a relative
/// 1e-9 of the magnitudes involved. Every step from `x` to `e` is an exact identity; this check
/// guards against a defect in them. Release builds use it in place of the exact check
/// (re-canonicalizing `e`, which costs about a sixth of the closed-form search) and fall back
/// to the exact check when it does not pass; debug builds, and so every test, always check
/// exactly.
fn agrees_numerically(e: &Expr, x: &Scalar) -> bool {
    [0x9e37_79b9_7f4a_7c15u64].iter().all(|&seed| {
        let value = |s: &Sym| point_value(s, seed);
        let (a, scale_a) = e.eval_f64(&value);
        let Ok(b) = x.eval_symbols(&|s| Some(point_value(s, seed))) else {
            return false;
        };
        let scale = scale_a.max(b.abs()).max(1.0);
        a.is_finite() && b.is_finite() && (a - b).abs() <= 1e-9 * scale
    })
}

/// A value in [0.3, 1.7) for the symbol `s`, a fixed function of its name and the seed (`pi`
/// and the constant 1 have their values, and are never asked for).
fn point_value(s: &Sym, seed: u64) -> f64 {
    let mut h = seed;
    for b in s.name().bytes() {
        h = (h ^ u64::from(b))
            .wrapping_mul(0x0100_0000_01b3)
            .rotate_left(17);
    }
    h ^= h >> 29;
    h = h.wrapping_mul(0xbf58_476d_1ce4_e5b9);
    h ^= h >> 32;
    0.3 + 1.4 * (h >> 11) as f64 / (1u64 << 53) as f64
}

/// [`closed_form`] with a record of how it was reached: the expanded sum, every angle-sum
/// identity applied (with the numbers of the terms it combined), each regrouped sum, and the
/// factored result. The expression is the one [`closed_form`] returns.
///
/// # Errors
/// When `x` is an error value, or the work budget runs out.
pub fn closed_form_traced(x: &Scalar) -> Result<(Expr, Vec<TraceStep>), ScalarError> {
    let (e, mut steps) = traced(x)?;
    // The last step is the closed form; it is shown as `closed_form` shows it.
    if let Some(TraceStep::Factored(last) | TraceStep::KeptWhole(last) | TraceStep::Shorter(last)) =
        steps.last_mut()
    {
        *last = std::mem::replace(last, Expr::zero()).symbols_leading();
    }
    Ok((e.symbols_leading(), steps))
}

fn traced(x: &Scalar) -> Result<(Expr, Vec<TraceStep>), ScalarError> {
    if let Err(e) = x.terms() {
        return Err(e.clone());
    }
    // With offsets absorbed into the symbols the form is found in other symbols: it is
    // recorded as one step when it is not the traced one.
    if offsets::find(x).is_some() {
        let e = closed_form(x)?;
        let (t, steps) = traced_unshifted(x)?;
        return Ok(if t == e {
            (t, steps)
        } else {
            (e.clone(), vec![TraceStep::Shorter(e)])
        });
    }
    traced_unshifted(x)
}

/// [`closed_form_traced`] without the offsets absorbed.
fn traced_unshifted(x: &Scalar) -> Result<(Expr, Vec<TraceStep>), ScalarError> {
    let (wctx, wmons) = mon::whole_modes_joined(x);
    let (whole, wc) = factor::build(&wmons)?;
    let split_size: usize = x
        .terms()
        .map(|t| t.iter().map(|t| 1usize << t.mode.freq.len().min(30)).sum())
        .unwrap_or(0);
    if split_size > SPLIT_LIMIT {
        let e = whole.to_expr(&wctx);
        return Ok((e.clone(), vec![TraceStep::KeptWhole(e)]));
    }
    if skip_split(x, split_size) {
        let e = best_whole(x)?;
        let kept = whole.to_expr(&wctx);
        let step = if e == kept {
            TraceStep::KeptWhole(e.clone())
        } else {
            TraceStep::Shorter(e.clone())
        };
        return Ok((e, vec![step]));
    }
    let (mut sctx, smons) = mon::split_modes(x);
    let mut rec = trace::Recorder::default();
    let smons = recombine::recombine_traced(&mut sctx, smons, &mut Some(&mut rec));
    let (split, sc) = factor::build(&smons)?;
    let (best, last) = if sc <= wc {
        let e = split.to_expr(&sctx);
        (e.clone(), TraceStep::Factored(e))
    } else {
        let e = whole.to_expr(&wctx);
        (e.clone(), TraceStep::KeptWhole(e))
    };
    let (best, last) = match alt::best_alternative(x, &best) {
        Some(a) => (a.clone(), TraceStep::Shorter(a)),
        None => (best, last),
    };
    if best.to_scalar() == *x {
        Ok((best, rec.finish(last)))
    } else {
        // Past the degree bound of exact constants, equal values may differ in form.
        debug_assert!(!x.is_canonical(), "closed form does not equal its input");
        let e = whole.to_expr(&wctx);
        Ok((e.clone(), vec![TraceStep::KeptWhole(e)]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Q;

    thread_local! {
        /// Set by a test to search the form as given without the shifted form's cap.
        pub(super) static UNCAPPED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
        /// Set by a test to search every scalar as given after its shifted form (no
        /// [`as_given_may_win`] skip).
        pub(super) static AS_GIVEN_ALWAYS: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
        /// How many searches as given [`as_given_may_win`] ruled out.
        pub(super) static AS_GIVEN_SKIPS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
    }

    fn s(x: &str) -> Scalar {
        Scalar::sym(x)
    }

    /// A pseudo-random scalar with pi offsets outside the multiples of pi/12 (the shape of the
    /// Jaco-style arm's entries, smaller): 2 to 4 terms, each a signed small integer, maybe a
    /// length, times one or two cosines or sines of one or two joint angles plus `k pi/n`
    /// (`n` one of 5, 7, 9 for the whole scalar).
    fn offset_scalar(seed: u64) -> Scalar {
        let mut next = crate::testing::xorshift_below(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
        let (angles, lengths) = (["q1", "q2", "q3"], ["a2", "d3"]);
        let n = [5u64, 7, 9][next(3) as usize];
        let mut x = Scalar::int(0);
        for _ in 0..2 + next(3) {
            let sign = if next(2) == 0 { -1 } else { 1 };
            let mut t = Scalar::int(sign * (next(4) as i64 + 1));
            if next(2) == 0 {
                t = t * s(lengths[next(2) as usize]);
            }
            for _ in 0..1 + next(2) {
                let mut a = s(angles[next(3) as usize]);
                if next(3) == 0 {
                    a = a + s(angles[next(3) as usize]);
                }
                let k = next(2 * n) as i64;
                a = a + Scalar::pi() * Scalar::from_q(Q::new(k, n as i64));
                t = t * if next(2) == 0 { a.cos() } else { a.sin() };
            }
            x = x + t;
        }
        x
    }

    /// The search as given with a cap gives the uncapped form whenever either is below the
    /// cap, and neither is below it otherwise (`best_of`, `alt::best_alternative_below`): caps
    /// around, at and below the uncapped form's key.
    #[test]
    fn a_capped_search_gives_the_uncapped_form_below_its_cap() {
        let mut compared = 0;
        for seed in 0..40 {
            let x = offset_scalar(seed);
            if x.terms().map_or(true, <[_]>::is_empty) {
                continue;
            }
            let e = prepared_unshifted(&x, None).0.expect("a closed form");
            let k = alt::choice_key(&e);
            let caps = [
                (k.0, k.1),
                (k.0, k.1 + 1),
                (k.0 + 1, 0),
                (k.0.saturating_sub(1), k.1),
                (k.0 / 2, 0),
                (k.0 + 8, 0),
            ];
            for cap in caps {
                let c = prepared_unshifted(&x, Some(cap)).0.expect("a closed form");
                if below(&e, cap) || below(&c, cap) {
                    assert_eq!(c, e, "seed {seed}, cap {cap:?}");
                    assert_eq!(c.to_scalar(), x, "seed {seed}");
                    compared += 1;
                }
            }
        }
        assert!(compared >= 40, "{compared} capped forms below their caps");
    }

    /// The closed form chosen with the shifted form's cap on the search as given is the one
    /// chosen without it, on random scalars with offsets; it equals the scalar exactly and at
    /// a random point in floats.
    #[test]
    fn the_shifted_forms_cap_does_not_change_the_chosen_form() {
        let (mut shifted, mut plain) = (0, 0);
        for seed in 100..260 {
            let x = offset_scalar(seed);
            let capped = closed_form_prepared(&x).0;
            UNCAPPED.with(|u| u.set(true));
            let uncapped = closed_form_prepared(&x).0;
            UNCAPPED.with(|u| u.set(false));
            let (Ok(c), Ok(u)) = (capped, uncapped) else {
                panic!("seed {seed}: no closed form");
            };
            assert_eq!(c, u, "seed {seed}");
            assert_eq!(c.to_scalar(), x, "seed {seed}");
            let point = |sym: &Sym| point_value(sym, seed);
            let want = x.eval_symbols(&|sym| Some(point(sym))).expect("a value");
            let (got, scale) = c.eval_f64(&point);
            assert!((got - want).abs() <= 1e-9 * scale.max(1.0), "seed {seed}");
            if offsets::find(&x).is_some() {
                let (p, _) = prepared_unshifted(&x, None);
                if p.is_ok_and(|p| alt::shorter(&p, &c) || p == c) {
                    plain += 1;
                } else {
                    shifted += 1;
                }
            }
        }
        assert!(
            shifted >= 5 && plain >= 10,
            "shifted {shifted}, as given {plain}"
        );
    }

    /// The entries of the rotation of a pseudo-random DH chain of `joints` revolute joints (the
    /// Jaco-style arm's shape): twists pi/3, pi/6 or pi/2, and each joint angle offset by
    /// `k pi/9` one time in two (`Rz(theta) Rx(alpha)` multiplied out, expanded).
    fn chain_rotation(seed: u64, joints: usize) -> Vec<Scalar> {
        chain_matrix(seed, joints, 3)
            .into_iter()
            .flatten()
            .collect()
    }

    /// The top-left `size` x `size` block (3: the rotation; 4: the homogeneous matrix, lengths
    /// `a{j}`, `d{j}` symbolic) of the product of the links of a pseudo-random DH chain of
    /// `joints` revolute joints in the Jaco-style arm's shape, as [`chain_rotation`] draws it:
    /// the block of each link multiplied out, expanded (the rotation block of a product of
    /// homogeneous matrices is the product of their rotation blocks).
    pub(super) fn chain_matrix(seed: u64, joints: usize, size: usize) -> Vec<Vec<Scalar>> {
        let mut next = crate::testing::xorshift_below(seed.wrapping_mul(0x2545_f491_4f6c_dd1d) | 1);
        let pi = |p: i64, q: i64| Scalar::pi() * Scalar::from_q(Q::new(p, q));
        let mut m: Vec<Vec<Scalar>> = (0..size)
            .map(|i| (0..size).map(|j| Scalar::int(i64::from(i == j))).collect())
            .collect();
        for j in 1..=joints {
            let mut theta = s(&format!("q{j}"));
            if next(2) == 0 {
                theta = theta + pi(1 + next(17) as i64, 9);
            }
            let alpha = pi(1, [3, 6, 2][next(3) as usize]);
            let (a, d) = (s(&format!("a{j}")), s(&format!("d{j}")));
            let (ct, st, ca, sa) = (
                theta.clone().cos(),
                theta.sin(),
                alpha.clone().cos(),
                alpha.sin(),
            );
            let z = Scalar::int(0);
            let t = [
                [
                    ct.clone(),
                    -(st.clone() * ca.clone()),
                    st.clone() * sa.clone(),
                    a.clone() * ct.clone(),
                ],
                [
                    st.clone(),
                    ct.clone() * ca.clone(),
                    -(ct * sa.clone()),
                    a * st,
                ],
                [z.clone(), sa, ca, d],
                [z.clone(), z.clone(), z, Scalar::int(1)],
            ];
            m = (0..size)
                .map(|i| {
                    (0..size)
                        .map(|k| {
                            (0..size).fold(Scalar::int(0), |acc, l| {
                                acc + m[i][l].clone() * t[l][k].clone()
                            })
                        })
                        .collect()
                })
                .collect();
        }
        m
    }

    /// The measured rule of [`as_given_may_win`] changes no chosen form where it skips the
    /// search as given: the rotation entries of pseudo-random Jaco-style chains of 5 joints
    /// get the same closed form with every search as given run (`AS_GIVEN_ALWAYS`), equal to
    /// the entry exactly; and the rule does skip there.
    #[test]
    fn skipping_the_search_as_given_keeps_the_chosen_form() {
        let (mut large, mut skipped) = (0, 0);
        for seed in 0..10 {
            for (i, x) in chain_rotation(seed, 5).into_iter().enumerate() {
                if x.len() < AS_GIVEN_MIN_TERMS {
                    continue;
                }
                large += 1;
                AS_GIVEN_SKIPS.with(|n| n.set(0));
                let ruled = closed_form_prepared(&x).0.expect("a closed form");
                skipped += AS_GIVEN_SKIPS.with(std::cell::Cell::get);
                AS_GIVEN_ALWAYS.with(|a| a.set(true));
                let full = closed_form_prepared(&x).0.expect("a closed form");
                AS_GIVEN_ALWAYS.with(|a| a.set(false));
                assert_eq!(ruled, full, "seed {seed}, entry {i}");
                assert_eq!(ruled.to_scalar(), x, "seed {seed}, entry {i}");
            }
        }
        assert!(
            large >= 40 && skipped >= 20,
            "{large} large entries, {skipped} skipped"
        );
    }

    /// The two values the numeric check compares: the form's by the same `eval_f64` the
    /// check calls (not changed here), and the scalar's as it was computed before each
    /// mode's cosine or sine was reused: `point_value` at every occurrence, and every term
    /// of the scalar evaluated on its own (the value this test checks independently).
    fn numeric_values_reference(e: &Expr, x: &Scalar) -> ((f64, f64), f64) {
        let seed = 0x9e37_79b9_7f4a_7c15u64;
        let a = e.eval_f64(&|s: &Sym| point_value(s, seed));
        let mut b = 0.0;
        for term in x.terms().expect("a value") {
            let mut v = term.coef.to_f64().unwrap_or(f64::NAN) * (term.rad as f64).sqrt();
            for (s, e) in term.mono.iter() {
                let sv = if s.is_pi() {
                    std::f64::consts::PI
                } else {
                    point_value(s, seed)
                };
                v *= sv.powi(*e as i32);
            }
            if !term.mode.is_unit() {
                let mut phi = (*term.mode.pi.numer() as f64 / *term.mode.pi.denom() as f64)
                    * std::f64::consts::PI;
                for (s, k) in term.mode.freq.iter() {
                    let sv = if s.is_one() {
                        1.0
                    } else {
                        point_value(s, seed)
                    };
                    phi += (*k.numer() as f64 / *k.denom() as f64) * sv;
                }
                v *= if term.mode.sin { phi.sin() } else { phi.cos() };
            }
            b += v;
        }
        (a, b)
    }

    /// The numeric check computes the same floats as before (the old computation above, bit
    /// for bit), so it decides alike: on closed forms of random scalars with offsets and
    /// lengths (modes repeated over monomials), and on scalars off by a term.
    #[test]
    fn the_numeric_check_computes_the_floats_it_computed() {
        let seed = 0x9e37_79b9_7f4a_7c15u64;
        let (mut compared, mut agreed, mut repeated) = (0, 0, 0);
        for k in 0..60 {
            let x = offset_scalar(k) * (s("d3") + offset_scalar(k + 1000));
            let Ok(e) = closed_form(&x) else {
                continue;
            };
            let y = if k % 3 == 0 {
                x.clone() + Scalar::from_q(Q::new(1, 1000)) * s("q1").cos()
            } else {
                x.clone()
            };
            let ((a, scale), b) = numeric_values_reference(&e, &y);
            let (a2, scale2) = e.eval_f64(&|s: &Sym| point_value(s, seed));
            let b2 = y
                .eval_symbols(&|s| Some(point_value(s, seed)))
                .expect("a value");
            assert_eq!(
                (a.to_bits(), scale.to_bits(), b.to_bits()),
                (a2.to_bits(), scale2.to_bits(), b2.to_bits()),
                "{y:?}"
            );
            let scale = scale.max(b.abs()).max(1.0);
            let old = a.is_finite() && b.is_finite() && (a - b).abs() <= 1e-9 * scale;
            assert_eq!(agrees_numerically(&e, &y), old, "{y:?}");
            let t = y.terms().expect("a value");
            repeated += t
                .windows(2)
                .filter(|w| !w[0].mode.is_unit() && w[0].mode == w[1].mode)
                .count();
            agreed += usize::from(old);
            compared += 1;
        }
        assert!(compared >= 50, "{compared} compared");
        assert!(
            agreed >= 30 && compared - agreed >= 15,
            "{agreed} of {compared} agreed"
        );
        assert!(repeated >= 100, "{repeated} repeated modes");
    }

    #[test]
    fn the_numeric_check_accepts_closed_forms_and_rejects_other_values() {
        let (t1, t2, l1) = (s("theta1"), s("theta2"), s("l1"));
        let x = l1.clone() * t1.clone().cos() + l1.clone() * (t1.clone() + t2.clone()).cos()
            - (t1.clone() * Scalar::from_q(Q::new(1, 2))).sin().pow(2);
        let e = closed_form(&x).expect("closed form");
        assert!(agrees_numerically(&e, &x));
        // Off by a small multiple of a term: rejected.
        let y = x.clone() + Scalar::from_q(Q::new(1, 1000)) * t2.cos();
        assert!(!agrees_numerically(&e, &y));
        // A value with cancellation well below the magnitudes of its terms still agrees.
        let z = Scalar::sym("a").pow(3) * Scalar::int(1_000_000) + Scalar::int(1);
        assert!(agrees_numerically(
            &closed_form(&z).expect("closed form"),
            &z
        ));
    }
}
