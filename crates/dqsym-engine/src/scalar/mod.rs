//! Exact scalars in one canonical form.
//!
//! [`Scalar`] is a finite Fourier series in angle symbols whose coefficients are polynomials in
//! plain symbols over the rationals extended by square roots (see `atoms.rs` for the shape of a
//! term). Only the functions of this module build the term vector, always sorted, merged and
//! free of zero coefficients, so two equal scalars have the same representation and `==` is
//! exact: `cos(t)^2 + sin(t)^2 == 1`, `2 sin(t/2) cos(t/2) == sin(t)`, `sqrt(2) sqrt(3) == sqrt(6)`.
//!
//! Exact values: cos and sin at multiples of pi/12 become radicals in Q(sqrt 2, sqrt 3) at once
//! (the fast path). Other rational multiples of pi (pi/8, pi/7) are constant modes, and
//! symbolic angles may carry them as offsets (`cos(x + pi/7)`); every group of terms holding
//! such a mode is rewritten in a canonical basis of the cyclotomic field it lives in
//! (`cyclo/`), so `cos(3 pi/8) = sin(pi/8)`, `cos(pi/5) = (1 + sqrt 5)/4` and
//! `cos(x + 6 pi/5) = -cos(x + pi/5)` hold as equal term vectors. The boundary is the field's
//! degree: past the [`Context`]'s `max_cyclotomic_degree` (768 by default: any one denominator
//! up to 100, whole degrees, sevenths with ninths or fifths) the result is the error
//! [`ScalarError::CyclotomicDegree`], never a value left in a non-canonical form.
//!
//! Arithmetic goes through `std::ops` so the generic quaternion algebra can use it. An
//! operation that cannot be done exactly (a result over the size limit, `cos` of a non-angle)
//! yields an *error value* that propagates like a NaN; [`Scalar::check`] turns it into a
//! `Result`. Building or combining scalars never panics.

mod arith;
pub(crate) mod atoms;
mod calculus;
pub(crate) use calculus::mode_angle;
mod cs;
mod ctx;
mod cyclo;
mod decimal;
mod frac;
mod modp;
mod multinomial;
mod par;
mod proportional;
pub(crate) mod q;
mod shift;

pub(crate) use arith::FxHasher;
pub(crate) use atoms::{Mode, MonoRc, Small};
pub use atoms::{Sym, Trig};
pub(crate) use cs::trig_placeholder_name;
pub use cs::{parse_trig_placeholder, trig_placeholder};
pub(crate) use ctx::{
    charge, check_cancelled, max_angle_symbols, max_digits, term_limit, work_left, work_used, Poll,
};
pub use ctx::{
    Context, Entered, Preset, DEFAULT_MAX_ANGLE_SYMBOLS, DEFAULT_MAX_CYCLOTOMIC_DEGREE,
    DEFAULT_MAX_DIGITS, DEFAULT_MAX_EXPONENT,
};
pub(crate) use cyclo::levels_within_limit;
use cyclo::{GroupKey, OwnedKey, ProductTrace, Settled};
pub use decimal::{decimal_places, decimal_text, parse_decimal, short_numbers};
pub use frac::Frac;
pub(crate) use par::{join, par_map, with_own_budget};
pub use par::{on_helper_start, start_helpers};
pub(crate) use proportional::ProportionalKey;
pub(crate) use q::Q;

use num_rational::BigRational;
use num_traits::Zero;
use thiserror::Error;

/// Why an exact operation on scalars could not be done.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Error)]
#[non_exhaustive]
pub enum ScalarError {
    /// A result has more terms than the context's term limit.
    #[error(
        "expression too large: {terms} terms, over the term limit of {limit} (--term-limit \
         raises it)"
    )]
    TooLarge {
        /// The terms of the result.
        terms: usize,
        /// The term limit.
        limit: usize,
    },
    /// A product would form more term pairs than twice the term limit (refused before any
    /// of them is formed).
    #[error(
        "expression too large: a product of {left} by {right} terms forms {} term pairs, over \
         the limit of {} (twice the term limit of {limit}; --term-limit raises it)",
        *left as u128 * *right as u128,
        2 * *limit as u128
    )]
    TooManyPairs {
        /// The terms of the left factor.
        left: usize,
        /// The terms of the right factor.
        right: usize,
        /// The term limit.
        limit: usize,
    },
    /// Division by zero.
    #[error("division by zero")]
    DivisionByZero,
    /// Division by an expression with symbols (rational functions are not supported yet).
    #[error(
        "cannot divide by a symbolic expression ({0}); only numbers and radicals can be divisors"
    )]
    SymbolicDivisor(String),
    /// A trigonometric argument that is not an angle.
    #[error("the argument of {func} must be a rational combination of symbols plus a rational multiple of pi, got {arg}")]
    NotAnAngle {
        /// The function (`cos`, `sin`).
        func: &'static str,
        /// The argument, as text.
        arg: String,
    },
    /// A square root that has no exact reduced form here.
    #[error("cannot take an exact square root of {0}")]
    BadSqrt(String),
    /// An exponent or coefficient outside the supported range.
    #[error("number out of range: {}", decimal::short_numbers(.0))]
    OutOfRange(String),
    /// A symbol without a value during numeric evaluation.
    #[error("no value for symbol {0}")]
    Unbound(String),
    /// The evaluation used up its work budget (see [`Context::with_work_budget`]).
    #[error(
        "work budget exceeded: at least {used} term operations in one evaluation, over the \
         budget of {limit} (--work-budget raises it)"
    )]
    Budget {
        /// The work charged when the budget ran out.
        used: u64,
        /// The budget.
        limit: u64,
    },
    /// Constants at rational multiples of pi that meet in one sum need a cyclotomic field of
    /// a degree above the context's limit (see [`Context::with_max_cyclotomic_degree`]).
    #[error(
        "exact constants at multiples of pi/{level} need a cyclotomic field of degree {}{degree}, \
         over the limit of {limit} (--max-cyclotomic-degree raises it)",
        if *exact { "" } else { "at least " }
    )]
    CyclotomicDegree {
        /// `lcm(12, q1, q2, ...)` for the denominators `q` of the pi offsets (saturated).
        level: u64,
        /// The degree of the field, or a lower bound of it.
        degree: u64,
        /// Whether `degree` is the degree itself (it is a lower bound for huge levels).
        exact: bool,
        /// The limit.
        limit: u64,
    },
    /// A computed number would have more decimal digits than the context allows (see
    /// [`Context::with_max_digits`]).
    #[error(
        "number too large: a computed number of about {digits} digits, over the limit of \
         {limit} digits (--max-digits raises it)"
    )]
    TooManyDigits {
        /// Its decimal digits (of the numerator or the denominator, whichever is longer;
        /// from its size in bits, so within one of the exact count).
        digits: u64,
        /// The limit.
        limit: u64,
    },
    /// A result would hold an angle with more symbols than the context allows (see
    /// [`Context::with_max_angle_symbols`]).
    #[error(
        "expression too large: an angle of {symbols} symbols, over the limit of {limit} \
         symbols in one angle (--max-angle-symbols raises it)"
    )]
    AngleSymbols {
        /// The symbols of the angle.
        symbols: usize,
        /// The limit.
        limit: usize,
    },
    /// The computation was cancelled through its context's cancel flag (Ctrl-C).
    #[error("interrupted")]
    Cancelled,
}

/// One term `coef * sqrt(rad) * mono * mode` of the canonical form.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub(crate) struct Term {
    pub(crate) mode: Mode,
    pub(crate) mono: MonoRc,
    pub(crate) rad: u64,
    pub(crate) coef: Q,
}

/// `12 p` when it is an integer. By one 128-bit division for a positive denominator (the
/// canonical one), where `Ratio`'s product reduces by two gcds first (0.3 M instructions of
/// the Jaco-style arm's `fk --jacobian`, through every shift of angles); `Ratio`'s own
/// arithmetic otherwise and when the integer leaves a machine word.
pub(crate) fn twelfths_of(p: Small) -> Option<i64> {
    let (n, d) = (i128::from(*p.numer()) * 12, i128::from(*p.denom()));
    if d > 0 {
        if n % d != 0 {
            return None;
        }
        if let Ok(k) = i64::try_from(n / d) {
            return Some(k);
        }
    }
    let twelfths = p * Small::from_integer(12);
    twelfths.is_integer().then(|| twelfths.to_integer())
}

impl Term {
    // Inlined: the comparator of every sort of a term vector.
    #[inline]
    pub(crate) fn key_cmp(&self, other: &Term) -> std::cmp::Ordering {
        self.mode
            .cmp(&other.mode)
            .then_with(|| self.mono.cmp(&other.mono))
            .then_with(|| self.rad.cmp(&other.rad))
    }

    /// This term with its pi offset set to `pi`, a multiple of 1/12, pushed onto `out` as
    /// terms without an offset (`cos(x + pi/4) = sqrt(2)/2 (cos x - sin x)`, as
    /// [`atoms::trig_mode`] writes it); false, with nothing pushed, when `pi` is not such a
    /// multiple or the term's angle has no symbol (a constant's offset is kept). The terms
    /// pushed are offset-free, so a group made only of them is canonical once merged (see
    /// `cyclo::Settled`): a shift (`closed::offsets`) that moves every term of a group onto
    /// multiples of 1/12 needs no rewrite in a cyclotomic basis.
    pub(crate) fn push_at_twelfths(&self, pi: Small, out: &mut Vec<Term>) -> bool {
        let Some(n) = twelfths_of(pi) else {
            return false;
        };
        if self.mode.freq.is_empty() {
            return false;
        }
        if n.rem_euclid(24) == 0 {
            let mut t = self.clone();
            t.mode.pi = Small::zero();
            out.push(t);
            return true;
        }
        let modes = atoms::twelfth_modes(self.mode.sin, self.mode.freq.clone(), n, 1);
        let start = out.len();
        for (mode, weights) in modes {
            for (r, q) in weights {
                let Some(t) = self.times_root(mode.clone(), r, &q) else {
                    out.truncate(start);
                    return false;
                };
                out.push(t);
            }
        }
        true
    }

    /// This term's monomial and `coef sqrt(rad)` times `q sqrt(r)`, on `mode`; `None` when
    /// the radicand leaves a machine word.
    pub(crate) fn times_root(&self, mode: Mode, r: u64, q: &Q) -> Option<Term> {
        let (rad, k) = atoms::rad_mul(self.rad, r)?;
        let coef = &self.coef * q;
        Some(Term {
            mode,
            mono: self.mono.clone(),
            rad,
            // The common case multiplies by one, without a product's gcds.
            coef: if k == 1 {
                coef
            } else {
                &coef * &Q::from_u64(k)
            },
        })
    }
}

/// Every scalar built from terms passes here: a coefficient past the context's digit limit
/// makes it [`ScalarError::TooManyDigits`] (repeated squaring grew numbers until the
/// allocator failed). Only big coefficients are looked at.
fn check_digits(terms: &[Term]) -> Result<(), ScalarError> {
    let Some(bits) = terms
        .iter()
        .map(|t| t.coef.bits())
        .filter(|&b| b > 63)
        .max()
    else {
        return Ok(());
    };
    let limit = max_digits();
    let digits = digits_of_bits(bits);
    if digits > limit {
        return Err(ScalarError::TooManyDigits { digits, limit });
    }
    Ok(())
}

/// A scalar with an angle of more symbols than the context allows is an error (a chain of
/// thousands of collinear joints grew memory quadratically with no limit reached).
fn check_angles(terms: &[Term]) -> Result<(), ScalarError> {
    let Some(symbols) = terms.iter().map(|t| t.mode.freq.len()).max() else {
        return Ok(());
    };
    let limit = max_angle_symbols();
    if symbols > limit {
        return Err(ScalarError::AngleSymbols { symbols, limit });
    }
    Ok(())
}

/// The decimal digits of a positive integer of `bits` bits, within one (from above: the
/// count of the largest such integer, `2^bits - 1`).
pub(crate) fn digits_of_bits(bits: u64) -> u64 {
    (bits as f64 * std::f64::consts::LOG10_2).ceil() as u64
}

/// The terms of one sorted run.
const RUN: usize = 1 << 13;

/// `terms` sorted by key, equal keys merged, zero coefficients dropped. Up to [`RUN`] terms
/// are sorted at once; more (a large product forms millions of term pairs) are sorted in runs
/// of [`RUN`] that are merged pairwise, equal keys summed at every merge, with a look at the
/// cancel flag before each run and every few terms of a merge ([`Poll`]): sorting a huge
/// product stops within milliseconds of a cancel. (The order of equal keys does not matter: their
/// coefficients are summed exactly.) The sort of up to [`RUN`] terms is stable: it finds the
/// runs already in order (the groups a cyclotomic rewrite passed through, before the ones it
/// rewrote) and merges them.
fn canonical_terms(mut terms: Vec<Term>) -> Result<Vec<Term>, ScalarError> {
    if terms.len() <= RUN {
        terms.sort_by(Term::key_cmp);
        return merge_sorted(terms);
    }
    let mut runs = Vec::with_capacity(terms.len().div_ceil(RUN));
    let mut rest = terms.into_iter();
    loop {
        check_cancelled()?;
        let mut run: Vec<Term> = rest.by_ref().take(RUN).collect();
        if run.is_empty() {
            break;
        }
        run.sort_unstable_by(Term::key_cmp);
        runs.push(merge_sorted(run)?);
    }
    drop(rest);
    while runs.len() > 1 {
        let mut next = Vec::with_capacity(runs.len().div_ceil(2));
        let mut level = runs.into_iter();
        while let Some(a) = level.next() {
            next.push(match level.next() {
                Some(b) => merge_runs(a, b)?,
                None => a,
            });
        }
        runs = next;
    }
    Ok(runs.pop().unwrap_or_default())
}

/// Sorted terms with equal keys merged and zero coefficients dropped (looking at the cancel
/// flag every few terms).
fn merge_sorted(terms: Vec<Term>) -> Result<Vec<Term>, ScalarError> {
    merge_sorted_counting(terms).map(|(t, _)| t)
}

/// [`merge_sorted`], and how many of the merged terms have a pi offset (counted as they are
/// kept, so that [`Scalar::from_terms`] need not scan them again).
fn merge_sorted_counting(terms: Vec<Term>) -> Result<(Vec<Term>, usize), ScalarError> {
    let mut out: Vec<Term> = Vec::with_capacity(terms.len());
    let mut offsets = 0;
    let mut poll = Poll::default();
    for t in terms {
        poll.step()?;
        match out.last_mut() {
            Some(last) if last.key_cmp(&t).is_eq() => last.coef += &t.coef,
            _ => {
                if out.last().is_some_and(|l| l.coef.is_zero()) {
                    offsets -= out.pop().map_or(0, |l| usize::from(!l.mode.pi.is_zero()));
                }
                offsets += usize::from(!t.mode.pi.is_zero());
                out.push(t)
            }
        }
    }
    if out.last().is_some_and(|l| l.coef.is_zero()) {
        offsets -= out.pop().map_or(0, |l| usize::from(!l.mode.pi.is_zero()));
    }
    Ok((out, offsets))
}

/// Two runs of [`merge_sorted`] as one, looking at the cancel flag every few terms.
fn merge_runs(a: Vec<Term>, b: Vec<Term>) -> Result<Vec<Term>, ScalarError> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut a, mut b) = (a.into_iter().peekable(), b.into_iter().peekable());
    let mut poll = Poll::default();
    loop {
        poll.step()?;
        let next = match (a.peek(), b.peek()) {
            (Some(x), Some(y)) => match x.key_cmp(y) {
                std::cmp::Ordering::Less => a.next(),
                std::cmp::Ordering::Greater => b.next(),
                std::cmp::Ordering::Equal => {
                    let (mut x, y) = (a.next(), b.next());
                    if let (Some(x), Some(y)) = (&mut x, &y) {
                        x.coef += &y.coef;
                    }
                    match x {
                        Some(x) if x.coef.is_zero() => continue,
                        x => x,
                    }
                }
            },
            _ => break,
        };
        out.extend(next);
    }
    out.extend(a);
    out.extend(b);
    Ok(out)
}

#[derive(Clone, PartialEq, Eq, Hash, Debug)]
enum Repr {
    Terms(Vec<Term>),
    Error(ScalarError),
}

/// An exact scalar in canonical form (or an error value; see the module docs).
///
/// # Laws
/// Equal values have equal representations: `a == b` iff `a - b` is the zero scalar, for all
/// scalars built from rationals, radicals of rationals, symbols, `+ - *`, division by nonzero
/// constants, and cos/sin of angles. `Hash` agrees with `Eq` because both read the canonical
/// term vector.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub struct Scalar(Repr);

impl Scalar {
    pub(crate) fn from_terms_sorted(terms: Vec<Term>) -> Scalar {
        let offsets = terms.iter().any(|t| !t.mode.pi.is_zero());
        Scalar::from_canonical(terms, offsets, &Settled::Nothing)
    }

    /// The sum of two canonical scalars from its sorted, merged terms: `origin[i]` says
    /// which operand term `i` came from (bit 1 the left, bit 2 the right), `cancelled` holds
    /// the keys of the terms that cancelled. Only the groups mixed from both operands are
    /// canonicalized again (see [`Settled::Sum`]). `None` when neither operand has a pi
    /// offset.
    pub(crate) fn from_sum(terms: Vec<Term>, origins: Option<(&[u8], &[GroupKey])>) -> Scalar {
        match origins {
            None => Scalar::from_canonical(terms, false, &Settled::Nothing),
            Some((origin, cancelled)) => {
                let offsets = terms.iter().any(|t| !t.mode.pi.is_zero());
                Scalar::from_canonical(terms, offsets, &Settled::Sum { origin, cancelled })
            }
        }
    }

    /// [`Scalar::from_terms_sorted`] told whether a term has a pi offset and which groups
    /// are canonical already.
    fn from_canonical(terms: Vec<Term>, offsets: bool, settled: &Settled) -> Scalar {
        // Constants at rational multiples of pi other than pi/12 (and symbolic angles offset
        // by them) take their canonical basis; the common case only pays for a scan.
        let terms = if offsets {
            match cyclo::canonicalize(&terms, settled) {
                Ok(None) => terms,
                Ok(Some(t)) => match canonical_terms(t) {
                    Ok(t) => t,
                    Err(e) => return Scalar::error(e),
                },
                Err(e) => return Scalar::error(e),
            }
        } else {
            terms
        };
        Scalar::checked(terms)
    }

    /// A scalar of canonical terms, or the error of the first limit they pass.
    fn checked(terms: Vec<Term>) -> Scalar {
        let limit = term_limit();
        if terms.len() > limit {
            return Scalar::error(ScalarError::TooLarge {
                terms: terms.len(),
                limit,
            });
        }
        if let Err(e) = check_digits(&terms).and_then(|()| check_angles(&terms)) {
            return Scalar::error(e);
        }
        Scalar(Repr::Terms(terms))
    }

    /// Sorts, merges equal keys and drops zero coefficients; an error value when the context
    /// is cancelled meanwhile (see [`canonical_terms`]).
    pub(crate) fn from_terms(mut terms: Vec<Term>) -> Scalar {
        if terms.len() <= RUN {
            // As `canonical_terms`, counting the pi offsets on the way. The stable sort finds
            // the runs already in order (a product's terms for one term of a factor, a
            // derivative's terms) and merges them, where the unstable one compared every
            // term again; equal keys are summed, so their order does not matter.
            terms.sort_by(Term::key_cmp);
            return match merge_sorted_counting(terms) {
                Ok((t, offsets)) => Scalar::from_canonical(t, offsets > 0, &Settled::Nothing),
                Err(e) => Scalar::error(e),
            };
        }
        match canonical_terms(terms) {
            Ok(t) => Scalar::from_terms_sorted(t),
            Err(e) => Scalar::error(e),
        }
    }

    /// [`Scalar::from_terms`] for terms whose groups are canonical already once like terms
    /// are merged: a canonical scalar negated, or times a nonzero constant of the square-root
    /// field times a monomial (see `arith::mul`), or with some groups written without an
    /// offset (see [`Term::push_at_twelfths`]). Sorted and merged, never rewritten in a
    /// cyclotomic basis; only the degree limit is checked (see [`Settled::All`]).
    pub(crate) fn from_terms_settled(terms: Vec<Term>) -> Scalar {
        Scalar::from_terms_in(terms, &Settled::All)
    }

    /// [`Scalar::from_terms_settled`] for terms sorted and merged already (a canonical
    /// scalar negated).
    pub(crate) fn from_sorted_settled(terms: Vec<Term>) -> Scalar {
        let offsets = terms.iter().any(|t| !t.mode.pi.is_zero());
        Scalar::from_canonical(terms, offsets, &Settled::All)
    }

    /// [`Scalar::from_terms`] for a product whose groups `known` (sorted) are canonical
    /// already once like terms are merged (see `arith::mul`); the others are rewritten.
    pub(crate) fn from_terms_known(terms: Vec<Term>, known: &[OwnedKey]) -> Scalar {
        Scalar::from_terms_in(terms, &Settled::Groups(known))
    }

    /// Sorted, merged, and the groups `settled` does not name rewritten.
    fn from_terms_in(mut terms: Vec<Term>, settled: &Settled) -> Scalar {
        let merged = if terms.len() <= RUN {
            // Stable, as in `from_terms`: a product's runs are in order already.
            terms.sort_by(Term::key_cmp);
            merge_sorted(terms)
        } else {
            canonical_terms(terms)
        };
        match merged {
            Ok(t) => {
                if cfg!(debug_assertions) && matches!(settled, Settled::All) {
                    cyclo::debug_check_canonical(&t);
                }
                let offsets = t.iter().any(|t| !t.mode.pi.is_zero());
                Scalar::from_canonical(t, offsets, settled)
            }
            Err(e) => Scalar::error(e),
        }
    }

    /// An error value.
    pub fn error(e: ScalarError) -> Scalar {
        Scalar(Repr::Error(e))
    }

    /// The terms, or the error this value carries.
    pub(crate) fn terms(&self) -> Result<&[Term], &ScalarError> {
        match &self.0 {
            Repr::Terms(t) => Ok(t),
            Repr::Error(e) => Err(e),
        }
    }

    /// `Ok(self)` unless this is an error value.
    pub fn check(self) -> Result<Scalar, ScalarError> {
        match self.0 {
            Repr::Error(e) => Err(e),
            t => Ok(Scalar(t)),
        }
    }

    /// The error this value carries, if any.
    pub fn as_error(&self) -> Option<&ScalarError> {
        self.terms().err()
    }

    /// The integer `n`.
    pub fn int(n: i64) -> Scalar {
        Scalar::from_q(Q::int(n))
    }

    /// The exact rational `q`, small-form coefficient.
    pub(crate) fn from_q(q: Q) -> Scalar {
        if q.is_zero() {
            return Scalar::from_terms_sorted(Vec::new());
        }
        Scalar::from_terms_sorted(vec![Term {
            mode: Mode::unit(),
            mono: atoms::empty_mono(),
            rad: 1,
            coef: q,
        }])
    }

    /// The exact rational `q`.
    pub fn rational(q: BigRational) -> Scalar {
        Scalar::from_q(Q::big(q))
    }

    /// The symbol `name` (`pi` is the constant pi).
    pub fn sym(name: &str) -> Scalar {
        Scalar::from_terms_sorted(vec![Term {
            mode: Mode::unit(),
            mono: std::sync::Arc::from(vec![(Sym::new(name), 1)]),
            rad: 1,
            coef: Q::ONE,
        }])
    }

    /// The constant pi.
    pub fn pi() -> Scalar {
        Scalar::sym("pi")
    }

    /// Number of terms of the canonical form (0 for zero and for error values).
    pub fn len(&self) -> usize {
        self.terms().map_or(0, |t| t.len())
    }

    /// True for the zero scalar (no terms).
    pub fn is_empty(&self) -> bool {
        self.is_zero_value()
    }

    /// Whether the scalar is zero, or the error it holds: a check whose own arithmetic
    /// reached a limit has no answer, and must not read as "not zero".
    pub fn try_is_zero(&self) -> Result<bool, ScalarError> {
        match &self.0 {
            Repr::Terms(t) => Ok(t.is_empty()),
            Repr::Error(e) => Err(e.clone()),
        }
    }

    /// True for the zero scalar.
    pub fn is_zero_value(&self) -> bool {
        matches!(&self.0, Repr::Terms(t) if t.is_empty())
    }

    /// The rational term of the value, without symbols, radicals or angles (`-3927/2500` of
    /// `q2 - 3927/2500`, `0` of `pi/2`); zero for an error value.
    pub fn rational_term(&self) -> BigRational {
        self.terms()
            .unwrap_or(&[])
            .iter()
            .find(|x| x.mode.is_unit() && x.mono.is_empty() && x.rad == 1)
            .map_or_else(BigRational::zero, |x| x.coef.to_big())
    }

    /// The value as a rational, when it is one.
    pub fn as_rational(&self) -> Option<BigRational> {
        let t = self.terms().ok()?;
        match t {
            [] => Some(BigRational::zero()),
            [x] if x.mode.is_unit() && x.mono.is_empty() && x.rad == 1 => Some(x.coef.to_big()),
            _ => None,
        }
    }

    /// The names of the angle symbols that occur at a fractional frequency (a half angle,
    /// `cos(t/2)`) in the canonical form, sorted, the constant of an angle as `1` (`cos(t/2 +
    /// 1/2)` gives `1` and `t`); none for an error value.
    pub fn fractional_angle_symbols(&self) -> std::collections::BTreeSet<String> {
        let mut out = std::collections::BTreeSet::new();
        for t in self.terms().unwrap_or(&[]) {
            for (s, k) in t.mode.freq.iter() {
                if !k.is_integer() {
                    out.insert(s.name().to_owned());
                }
            }
        }
        out
    }

    /// True when the value contains no symbol (it is a number: rationals, radicals, and exact
    /// trigonometric constants).
    pub fn is_constant(&self) -> bool {
        self.terms().is_ok_and(|t| {
            t.iter()
                .all(|x| x.mono.is_empty() && x.mode.freq.is_empty())
        })
    }

    /// True when the representation is the canonical one for its value: every value that is
    /// not an error (constants at rational multiples of pi past the context's cyclotomic
    /// degree limit are a [`ScalarError::CyclotomicDegree`], never a non-canonical value).
    pub fn is_canonical(&self) -> bool {
        self.terms().is_ok()
    }

    /// Every symbol the value mentions, sorted by name (`pi` included when present).
    ///
    /// The distinct symbols are kept as they are met (a comparison of pointers each, names
    /// being interned), and only those sorted: a scalar names a few symbols many times over,
    /// and sorting every occurrence was 1.6 M instructions of a fully symbolic 6R's report.
    /// Past `FEW_SYMBOLS` distinct ones the rest are pushed as met and sorted and
    /// deduplicated with them, as before (the scan would be quadratic). Two symbols compare
    /// equal exactly when they are the same (`Sym`'s `Ord` and `Eq`), so either route gives
    /// the one sorted list.
    pub fn symbols(&self) -> Vec<Sym> {
        let mut out: Vec<Sym> = Vec::new();
        let Ok(t) = self.terms() else {
            return out;
        };
        let mut distinct = true;
        for x in t {
            let syms = x.mono.iter().map(|(s, _)| s);
            for s in syms.chain(x.mode.freq.iter().map(|(s, _)| s)) {
                if !distinct {
                    out.push(s.clone());
                } else if !s.is_one() && !out.contains(s) {
                    out.push(s.clone());
                    distinct = out.len() <= FEW_SYMBOLS;
                }
            }
        }
        if distinct {
            out.sort_unstable();
        } else {
            out.retain(|s| !s.is_one());
            out.sort();
            out.dedup();
        }
        out
    }
}

/// The most distinct symbols [`Scalar::symbols`] keeps by scanning those it has (see there).
const FEW_SYMBOLS: usize = 32;

impl Default for Scalar {
    fn default() -> Self {
        Scalar::int(0)
    }
}

/// A scalar as a hash-map key hashed by its number of terms and at most [`SAMPLED_TERMS`] of
/// them, spread over its term vector: for maps of long scalars looked up a few times each,
/// where the derived `Hash` reads every term (the deduplication of the PUMA 560's Jacobian
/// entries hashed 191 scalars of up to a few hundred terms each, 4% of its `fk --jacobian`
/// instructions). Equal scalars have equal term vectors, so they hash alike; `Eq` compares
/// in full.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) struct SampledKey<'a>(pub(crate) &'a Scalar);

/// How many terms a [`SampledKey`] (and a [`ProportionalKey`]) hashes.
const SAMPLED_TERMS: usize = 4;

impl std::hash::Hash for SampledKey<'_> {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        match self.0.terms() {
            Ok(t) => {
                h.write_usize(t.len());
                let step = t.len().div_ceil(SAMPLED_TERMS).max(1);
                for term in t.iter().step_by(step) {
                    std::hash::Hash::hash(term, h);
                }
            }
            Err(e) => std::hash::Hash::hash(e, h),
        }
    }
}

#[cfg(test)]
mod sampled_key_tests {
    use super::{SampledKey, Scalar};
    use std::collections::HashMap;
    use std::hash::{BuildHasher, RandomState};

    /// Equal scalars reached by different arithmetic are one key (the hash agrees with `Eq`),
    /// and scalars that differ only in terms the hash does not sample are still two keys.
    #[test]
    fn sampled_keys_agree_with_equality() {
        let (a, b, c) = (Scalar::sym("a"), Scalar::sym("b"), Scalar::sym("c"));
        let (t, u) = (Scalar::sym("t"), Scalar::sym("u"));
        // (a cos t + b sin u + c)^3 expanded two ways: dozens of terms.
        let s = a * t.cos() + b * u.sin() + c;
        let x = s.pow(3);
        let y = s.clone() * s.clone() * s;
        assert_eq!(x, y);
        let n = x.terms().map(<[_]>::len).unwrap_or(0);
        assert!(n > 2 * super::SAMPLED_TERMS, "{n} terms");
        let state = RandomState::new();
        assert_eq!(
            state.hash_one(SampledKey(&x)),
            state.hash_one(SampledKey(&y))
        );
        // One more term than x, then x with one coefficient changed in a term the sample skips
        // (the second term; the sample reads every `ceil(n/4)`-th from the first).
        let z = x.clone() + Scalar::int(7);
        let w = {
            let terms = x.terms().expect("terms");
            let second = Scalar::from_terms(vec![terms[1].clone()]);
            x.clone() + second
        };
        let mut map: HashMap<SampledKey, usize> = HashMap::new();
        for (k, s) in [&x, &y, &z, &w, &x].into_iter().enumerate() {
            map.entry(SampledKey(s)).or_insert(k);
        }
        assert_eq!(map.len(), 3);
        assert_eq!(map[&SampledKey(&y)], 0);
        assert_eq!(map[&SampledKey(&z)], 2);
        assert_eq!(map[&SampledKey(&w)], 3);
        assert_ne!(w, x);
    }
}

#[cfg(test)]
mod twelfths_tests {
    use super::{twelfths_of, Small};

    /// `twelfths_of` by one division is `Ratio`'s `12 p` when that is an integer, and `None`
    /// when it is not: offsets of many denominators, both signs, reduced and unreduced (the
    /// division needs no reduction), and a negative denominator (the `Ratio` route).
    #[test]
    fn twelfths_by_division_are_ratio_arithmetic() {
        let mut next = crate::testing::xorshift_below(12);
        let (mut some, mut none) = (0, 0);
        for _ in 0..20_000 {
            let d = 1 + next(72) as i64;
            let n = next(8 * d as u64) as i64 - 4 * d;
            let scale = 1 + next(3) as i64;
            for p in [
                Small::new(n, d),
                Small::new_raw(n * scale, d * scale),
                Small::new_raw(-n, -d),
            ] {
                let twelfths = p * Small::from_integer(12);
                let expected = twelfths.is_integer().then(|| twelfths.to_integer());
                assert_eq!(twelfths_of(p), expected, "{p:?}");
                if expected.is_some() {
                    some += 1;
                } else {
                    none += 1;
                }
            }
        }
        assert!(some > 1000 && none > 1000, "{some} {none}");
    }

    /// The 128-bit division near the end of a machine word: numerators about `i64::MAX / 12`
    /// (`12 n` past an `i64`) and up to `i64::MAX`, over denominators 1 to 24, both signs, the
    /// answer against the exact `12 n / d` in 128 bits, for every `12 n / d` that fits a
    /// word or is not an integer (past a word, `twelfths_of` leaves it to `Ratio`, as before).
    #[test]
    fn twelfths_by_division_near_the_word_limit() {
        let (mut some, mut none) = (0, 0);
        for base in [i64::MAX / 12, i64::MAX / 6, i64::MAX / 2, i64::MAX - 40] {
            for k in 0..40i64 {
                for d in 1..=24i64 {
                    for n in [base - k, -(base - k)] {
                        let p = Small::new(n, d);
                        let (num, den) = (i128::from(*p.numer()) * 12, i128::from(*p.denom()));
                        let expected = if num % den != 0 {
                            None
                        } else {
                            match i64::try_from(num / den) {
                                Ok(q) => Some(q),
                                Err(_) => continue,
                            }
                        };
                        assert_eq!(twelfths_of(p), expected, "{p:?}");
                        if expected.is_some() {
                            some += 1;
                        } else {
                            none += 1;
                        }
                    }
                }
            }
        }
        assert!(some > 300 && none > 1000, "{some} {none}");
    }
}

#[cfg(test)]
mod symbols_tests {
    use super::*;
    use crate::ring::Ring;

    /// `Scalar::symbols` as first written (kept as the reference): every occurrence
    /// collected, the constant left out, sorted, deduplicated.
    fn symbols_before(x: &Scalar) -> Vec<Sym> {
        let mut out: Vec<Sym> = Vec::new();
        if let Ok(t) = x.terms() {
            for x in t {
                out.extend(x.mono.iter().map(|(s, _)| s.clone()));
                out.extend(x.mode.freq.iter().map(|(s, _)| s.clone()));
            }
        }
        out.retain(|s| !s.is_one());
        out.sort();
        out.dedup();
        out
    }

    /// On random sums of products of symbols (a symbol named `1`, `pi`, names sharing their
    /// first eight bytes, and past `FEW_SYMBOLS` distinct ones), cosines and sines of their
    /// sums, and numbers: the same sorted symbols as the route before, and both routes taken.
    #[test]
    fn symbols_are_those_of_the_route_before() {
        let mut next = crate::testing::xorshift_below(3030);
        let names: Vec<String> = (0..60)
            .map(|k| match k % 4 {
                0 => format!("theta{k}"),
                1 => format!("a{k}"),
                2 => format!("alpha_long_{k}"),
                _ => format!("x{}", k * 7 % 13),
            })
            .chain(["1".to_string(), "pi".to_string()])
            .collect();
        let (mut few, mut many) = (0, 0);
        for _ in 0..300 {
            let spread = [4, 12, 40, 62][next(4) as usize] as u64;
            let pick = |k: u64| Scalar::sym(&names[k as usize]);
            let mut x = Scalar::from_ratio(next(7) as i64 - 3, 2);
            for _ in 0..next(24) {
                let mut t = pick(next(spread)) * pick(next(spread));
                if next(2) == 0 {
                    t = t * (pick(next(spread)) + pick(next(spread))).cos();
                }
                if next(3) == 0 {
                    t = t * Scalar::pi() + (pick(next(spread)) - pick(next(spread))).sin();
                }
                x = x + t;
            }
            let new = x.symbols();
            assert_eq!(new, symbols_before(&x), "{x}");
            if new.len() > FEW_SYMBOLS {
                many += 1;
            } else if !new.is_empty() {
                few += 1;
            }
        }
        assert!(few > 100 && many > 5, "{few} {many}");
    }
}
