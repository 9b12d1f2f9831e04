//! Ring operations on canonical scalars: `+ - *`, powers, reciprocals of constants, exact
//! square roots of rationals, and cos / sin of angles.

use super::atoms::{
    empty_mono, mode_mul, mono_mul_in, rad_mul, small_ok, split_square, trig_mode, Mode, ModeSum,
    MonoRc, Small, Sym,
};
use super::{charge, term_limit, GroupKey, Poll, ProductTrace, Scalar, ScalarError, Term, Q};
use crate::{Ring, SignedProduct};
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use smallvec::SmallVec;
use std::borrow::Borrow;
use std::cell::RefCell;
use std::collections::HashSet;
use std::hash::{BuildHasherDefault, Hash, Hasher};
use std::ops::{Add, Mul, Neg, Sub};
use std::rc::Rc;
use std::sync::Arc;

/// How many term pairs one product may form, as a multiple of the term limit.
const PRODUCT_FACTOR: usize = 2;

/// Propagates error values: the first operand's error wins.
macro_rules! terms_or_return {
    ($a:expr, $b:expr) => {
        match ($a.terms(), $b.terms()) {
            (Ok(x), Ok(y)) => (x, y),
            (Err(e), _) | (_, Err(e)) => return Scalar::error(e.clone()),
        }
    };
}

pub(crate) fn add(a: &Scalar, b: &Scalar, sign: i64) -> Scalar {
    let (x, y) = terms_or_return!(a, b);
    // Adding two coefficients of `a` and `b` words and reducing the sum costs like
    // `(a + b)^2`, at most `2 (a^2 + b^2)`; a big term, [`BIG_PAIR`] more.
    let ((bx, _, qx), (by, _, qy)) = (coefficient_words(x), coefficient_words(y));
    let big = (bx + by)
        .saturating_mul(BIG_PAIR)
        .saturating_add(qx.saturating_add(qy).saturating_mul(2));
    if let Err(e) = charge(((x.len() + y.len()) as u64).saturating_add(big)) {
        return Scalar::error(e);
    }
    let mut out = Vec::with_capacity(x.len() + y.len());
    // Where each term of the sum came from, and the keys of the terms that cancelled: only
    // the groups mixed from both operands are canonicalized again (`Scalar::from_sum`).
    // Without a pi offset in either operand there is nothing to canonicalize or track.
    let offsets = |t: &[Term]| t.iter().any(|t| !t.mode.pi.is_zero());
    let track = offsets(x) || offsets(y);
    let mut origin: Vec<u8> = Vec::with_capacity(if track { x.len() + y.len() } else { 0 });
    let mut cancelled: Vec<GroupKey> = Vec::new();
    let (mut i, mut j) = (0, 0);
    // A long sum notices cancellation as it goes, not only before.
    let mut poll = Poll::default();
    let flip = |t: &Term| {
        let mut t = t.clone();
        if sign < 0 {
            t.coef = -t.coef;
        }
        t
    };
    while i < x.len() && j < y.len() {
        if let Err(e) = poll.step() {
            return Scalar::error(e);
        }
        match x[i].key_cmp(&y[j]) {
            std::cmp::Ordering::Less => {
                out.push(x[i].clone());
                if track {
                    origin.push(1);
                }
                i += 1;
            }
            std::cmp::Ordering::Greater => {
                out.push(flip(&y[j]));
                if track {
                    origin.push(2);
                }
                j += 1;
            }
            std::cmp::Ordering::Equal => {
                let c = if sign < 0 {
                    &x[i].coef - &y[j].coef
                } else {
                    &x[i].coef + &y[j].coef
                };
                if c.is_zero() {
                    // Only terms with a pi offset matter (see `Settled`).
                    if track && !x[i].mode.pi.is_zero() {
                        cancelled.push((&*x[i].mode.freq, &x[i].mono));
                    }
                } else {
                    let mut t = x[i].clone();
                    t.coef = c;
                    out.push(t);
                    if track {
                        origin.push(3);
                    }
                }
                i += 1;
                j += 1;
            }
        }
    }
    out.extend(x[i..].iter().cloned());
    if !track {
        out.extend(y[j..].iter().map(flip));
        return Scalar::from_sum(out, None);
    }
    origin.resize(out.len(), 1);
    out.extend(y[j..].iter().map(flip));
    origin.resize(out.len(), 2);
    Scalar::from_sum(out, Some((&origin, &cancelled)))
}

/// A small, fast, non-cryptographic hasher (FxHash) for the mode-product cache.
#[derive(Default)]
pub(crate) struct FxHasher(u64);

impl FxHasher {
    fn add(&mut self, w: u64) {
        self.0 = (self.0.rotate_left(5) ^ w).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

impl Hasher for FxHasher {
    fn write(&mut self, bytes: &[u8]) {
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            let mut b = [0u8; 8];
            b.copy_from_slice(c);
            self.add(u64::from_le_bytes(b));
        }
        let rest = chunks.remainder();
        if !rest.is_empty() {
            let mut b = [0u8; 8];
            b[..rest.len()].copy_from_slice(rest);
            self.add(u64::from_le_bytes(b) ^ ((rest.len() as u64) << 56));
        }
    }
    fn write_u8(&mut self, i: u8) {
        self.add(u64::from(i));
    }
    fn write_u32(&mut self, i: u32) {
        self.add(u64::from(i));
    }
    fn write_u64(&mut self, i: u64) {
        self.add(i);
    }
    fn write_i64(&mut self, i: i64) {
        self.add(i as u64);
    }
    fn write_usize(&mut self, i: usize) {
        self.add(i as u64);
    }
    fn finish(&self) -> u64 {
        self.0
    }
}

/// A remembered mode product: the two factors (the key) with their product, in one
/// allocation, so that the cache's table holds one pointer a product. (A table of
/// `((Mode, Mode), Rc<ModeSum>)` buckets, 88 bytes each, spent some 180 kB on its growth
/// for the PUMA 560's `fk --jacobian`, 467 products: 38 page faults of the process's 537.)
struct ModeProduct {
    key: (Mode, Mode),
    sum: ModeSum,
}

/// A cache entry, hashed and compared by its factors alone, so the table is searched with a
/// bare `(Mode, Mode)`.
struct Cached(Rc<ModeProduct>);

impl Hash for Cached {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.0.key.hash(state);
    }
}

impl PartialEq for Cached {
    fn eq(&self, other: &Self) -> bool {
        self.0.key == other.0.key
    }
}

impl Eq for Cached {}

impl Borrow<(Mode, Mode)> for Cached {
    fn borrow(&self) -> &(Mode, Mode) {
        &self.0.key
    }
}

type ModeCache = HashSet<Cached, BuildHasherDefault<FxHasher>>;

/// How many mode products the per-thread cache keeps before it starts over.
const MODE_CACHE_LIMIT: usize = 1 << 14;

thread_local! {
    static MODE_CACHE: RefCell<ModeCache> = RefCell::new(ModeCache::default());
}

/// A mode product from [`cached_mode_mul`]: remembered, or made on the spot for a unit mode
/// (a product by 1, cheaper made than looked up).
enum Modes {
    Cached(Rc<ModeProduct>),
    Fresh(ModeSum),
}

impl Modes {
    /// The product's modes with their weights.
    fn sum(&self) -> &ModeSum {
        match self {
            Modes::Cached(p) => &p.sum,
            Modes::Fresh(sum) => sum,
        }
    }
}

/// [`mode_mul`], remembered per thread: kinematic chains multiply the same modes again and
/// again (every quaternion product forms sixteen scalar products of the same factors).
/// `product_terms` forms the pairs with a unit mode itself, so the unit branch (`Modes::Fresh`)
/// is reached only by this function's own tests; kept so that it is `mode_mul` for every mode.
fn cached_mode_mul(a: &Mode, b: &Mode) -> Modes {
    if a.is_unit() || b.is_unit() {
        return Modes::Fresh(mode_mul(a, b));
    }
    MODE_CACHE.with(|c| {
        let mut c = c.borrow_mut();
        let key = (a.clone(), b.clone());
        if let Some(hit) = c.get(&key) {
            return Modes::Cached(hit.0.clone());
        }
        if c.len() >= MODE_CACHE_LIMIT {
            c.clear();
        }
        let sum = mode_mul(a, b);
        let product = Rc::new(ModeProduct { key, sum });
        c.insert(Cached(product.clone()));
        Modes::Cached(product)
    })
}

/// The runs of a sorted term slice that share a mode, in order, found as they are asked for
/// (no vector of them).
struct ModeRuns<'a>(&'a [Term]);

impl<'a> Iterator for ModeRuns<'a> {
    type Item = &'a [Term];

    fn next(&mut self) -> Option<&'a [Term]> {
        let first = &self.0.first()?.mode;
        let n = 1 + self.0[1..]
            .iter()
            .position(|t| t.mode != *first)
            .unwrap_or(self.0.len() - 1);
        let (run, rest) = self.0.split_at(n);
        self.0 = rest;
        Some(run)
    }
}

/// The work of a product, for the budget: one unit per pair of terms plus one per symbol of the
/// pair's monomials, since merging monomials is what a pair costs when symbols are many (a chain
/// of fully symbolic links spends most of its time there).
///
/// Big coefficients add their own work: a pair with a big coefficient costs [`BIG_PAIR`]
/// units (the big rationals' allocation and reduction), and multiplying two rationals of `a`
/// and `b` words and reducing the result (a binary gcd, some 64 steps per word) takes time
/// like `(a + b)^2` word operations, counted one unit each. Summed over all pairs before any
/// is formed: `ny sum(a^2) + nx sum(b^2) + 2 sum(a) sum(b)`, so products of huge numbers
/// (`cos(1) * ... * cos(512)`'s coefficients, repeated squaring) run out of the budget at
/// once instead of after minutes. (Calibrated on the product of 512 constant cosines, whose
/// pairs of three-word coefficients took some eight times a small pair's time.) Their
/// reductions add [`GCD_UNITS_PER_WORD`] a word: `(ny sum(a) + nx sum(b))` words in all.
///
/// Long angles add theirs: a pair's mode is hashed, combined and compared (in the sort of the
/// product's terms) symbol by symbol, so each symbol of a mode past
/// [`MODE_SYMBOLS_IN_A_PAIR`] counts as one of the monomial's. (A chain of 1,000 joints about
/// one axis, its offsets off the axis, has angles of up to 1,000 symbols; uncharged, `fk` spent
/// 77 s and 1.3 GB expanding it at the default budget before its recurrence.)
fn product_work(x: &[Term], y: &[Term]) -> u64 {
    let syms = |t: &[Term]| {
        t.iter()
            .map(|t| {
                let long = (t.mode.freq.len() as u64).saturating_sub(MODE_SYMBOLS_IN_A_PAIR);
                t.mono.len() as u64 + long
            })
            .sum::<u64>()
    };
    let (nx, ny) = (x.len() as u64, y.len() as u64);
    let (bx, sx, qx) = coefficient_words(x);
    let (by, sy, qy) = coefficient_words(y);
    let big_pairs = nx * ny - (nx - bx) * (ny - by);
    let words = ny
        .saturating_mul(qx)
        .saturating_add(nx.saturating_mul(qy))
        .saturating_add(sx.saturating_mul(sy).saturating_mul(2));
    let gcd_steps = ny
        .saturating_mul(sx)
        .saturating_add(nx.saturating_mul(sy))
        .saturating_mul(GCD_UNITS_PER_WORD);
    (nx * ny + ny * syms(x) + nx * syms(y))
        .saturating_add(big_pairs.saturating_mul(BIG_PAIR))
        .saturating_add(words)
        .saturating_add(gcd_steps)
}

/// The units of one word of a big coefficient in a pair, for the reductions of its rationals:
/// the binary gcd takes about one step per bit (64 per word), each a shift into a new
/// allocation, and a pair reduces its coefficient some three times (the cross gcds of the
/// product, the weight of a product-to-sum identity, the merge of like terms). Calibrated on
/// the products of constant cosines (`cos(1) * ... * cos(512)`, one- to eight-word
/// coefficients): without this charge the default budget of 3,000,000 units took 1.8 s of
/// release CPU there (0.6 microseconds a unit, where other work takes 0.2 to 0.4); with 16
/// units a word, 0.57 s.
const GCD_UNITS_PER_WORD: u64 = 16;

/// The symbols of a mode (an angle `q1 + ... + qk`) whose handling fits in the unit a term
/// pair costs: the angles of arms of up to eight joints, so their charges are unchanged.
const MODE_SYMBOLS_IN_A_PAIR: u64 = 8;

/// The work of one term operation with a big coefficient beyond its words (see
/// [`product_work`]).
const BIG_PAIR: u64 = 8;

/// The number of big coefficients of `t`, the sum of their words, and of their squares.
fn coefficient_words(t: &[Term]) -> (u64, u64, u64) {
    t.iter()
        .map(|t| t.coef.words())
        .filter(|&w| w > 0)
        .fold((0, 0, 0), |(n, s, q), w| {
            (
                n + 1,
                s.saturating_add(w),
                q.saturating_add(w.saturating_mul(w)),
            )
        })
}

pub(crate) fn mul(a: &Scalar, b: &Scalar) -> Scalar {
    let (x, y) = terms_or_return!(a, b);
    if let Err(e) = admit_product(x, y) {
        return Scalar::error(e);
    }
    // A canonical scalar times a nonzero constant of the square-root field times a monomial
    // is canonical once like terms merge: each group is carried to one group (the monomial
    // multiplies its key), its value times the constant `k`, which has the same smallest
    // cyclotomic field (`k` is invertible in the field of square roots), and the products of
    // the terms, merged, are its coordinates over `Q` in the same basis (a basis of square
    // roots times the columns). So the product skips the cyclotomic rewrite.
    let settled = scales(x) || scales(y);
    // Otherwise, the groups that are canonical anyway (a group of one factor with pi offsets
    // times an offset-free group of the other, alone in its group of the product): traced
    // term by term, so that only the others are rewritten (see `cyclo::ProductTrace`).
    let mut trace = if settled {
        None
    } else {
        ProductTrace::new(x, y)
    };
    let mut out = Vec::with_capacity(x.len() * y.len());
    if let Err(e) = product_terms(x, y, false, &mut out, trace.as_mut()) {
        return Scalar::error(e);
    }
    if settled {
        return Scalar::from_terms_settled(out);
    }
    match trace {
        Some(trace) => {
            let known = trace.settled(&out);
            Scalar::from_terms_known(out, &known)
        }
        None => Scalar::from_terms(out),
    }
}

/// The limits a product of `x` and `y` must pass before its terms are formed: the number of
/// term pairs, and its work charged to the budget ([`product_work`]).
fn admit_product(x: &[Term], y: &[Term]) -> Result<(), ScalarError> {
    let limit = term_limit();
    if x.len().saturating_mul(y.len()) > limit.saturating_mul(PRODUCT_FACTOR) {
        return Err(ScalarError::TooManyPairs {
            left: x.len(),
            right: y.len(),
            limit,
        });
    }
    charge(product_work(x, y))
}

/// Appends the terms of `x y` (of `-x y` when `minus`) to `out`, neither sorted nor merged,
/// marking each in `trace` when given (its indices are `out`'s).
fn product_terms(
    x: &[Term],
    y: &[Term],
    minus: bool,
    out: &mut Vec<Term>,
    mut trace: Option<&mut ProductTrace>,
) -> Result<(), ScalarError> {
    // A large product notices cancellation as it goes (every few term pairs), not only before.
    let mut poll = Poll::default();
    // The right factor's runs, found once (not again for every run of the left one).
    let runs_y: SmallVec<[&[Term]; 16]> = ModeRuns(y).collect();
    // The scratch vector of the monomials' merges (see `mono_mul_in`).
    let mut buf = Vec::new();
    let mut ia = 0;
    for ra in ModeRuns(x) {
        let mut ib = 0;
        for &rb in &runs_y {
            let (ma, mb) = (&ra[0].mode, &rb[0].mode);
            if ma.is_unit() || mb.is_unit() {
                // A mode times 1 is the other mode, of weight 1 (`mode_mul`): the terms are
                // formed on it directly, without the sum of modes (two allocations) and the
                // coefficients' products by 1 (the same values, as `Q` has one form a value).
                let mode = if ma.is_unit() { mb } else { ma };
                out.reserve(ra.len() * rb.len());
                for (i, s) in (ia..).zip(ra) {
                    for (j, t) in (ib..).zip(rb) {
                        poll.step()?;
                        let (mono, rad, coef) = pair_product(s, t, minus, &mut buf)?;
                        if let Some(trace) = trace.as_deref_mut() {
                            trace.mark(out.len(), (i, &s.mode), (j, &t.mode), mode);
                        }
                        out.push(Term {
                            mode: mode.clone(),
                            mono,
                            rad,
                            coef,
                        });
                    }
                }
                ib += rb.len();
                continue;
            }
            // Mode products are the expensive part; compute each once per pair of mode runs.
            let modes = cached_mode_mul(ma, mb);
            let weights: usize = modes.sum().iter().map(|(_, w)| w.len()).sum();
            out.reserve(ra.len() * rb.len() * weights);
            for (i, s) in (ia..).zip(ra) {
                for (j, t) in (ib..).zip(rb) {
                    poll.step()?;
                    let (mono, rad, coef) = pair_product(s, t, minus, &mut buf)?;
                    for (mode, weights) in modes.sum().iter() {
                        for (r2, w) in weights {
                            let (rad3, g2) = rad_mul(rad, *r2).ok_or_else(|| {
                                ScalarError::OutOfRange("radicand too large".into())
                            })?;
                            let mut c = &coef * w;
                            if g2 != 1 {
                                c = &c * &Q::from_u64(g2);
                            }
                            if let Some(trace) = trace.as_deref_mut() {
                                trace.mark(out.len(), (i, &s.mode), (j, &t.mode), mode);
                            }
                            out.push(Term {
                                mode: mode.clone(),
                                mono: mono.clone(),
                                rad: rad3,
                                coef: c,
                            });
                        }
                    }
                }
            }
            ib += rb.len();
        }
        ia += ra.len();
    }
    Ok(())
}

/// The monomial, radicand and coefficient (negated when `minus`) of the product of the terms
/// `s` and `t`, before their modes multiply; an error when an exponent or the radicand leaves
/// its machine word (the monomial's first).
#[inline]
fn pair_product(
    s: &Term,
    t: &Term,
    minus: bool,
    buf: &mut Vec<(Sym, u32)>,
) -> Result<(MonoRc, u64, Q), ScalarError> {
    let mono = mono_mul_in(&s.mono, &t.mono, buf)
        .ok_or_else(|| ScalarError::OutOfRange("exponent too large".into()))?;
    let (rad, g) = rad_mul(s.rad, t.rad)
        .ok_or_else(|| ScalarError::OutOfRange("radicand too large".into()))?;
    let mut coef = &s.coef * &t.coef;
    if g != 1 {
        coef = &coef * &Q::from_u64(g);
    }
    if minus {
        coef = -coef;
    }
    Ok((mono, rad, coef))
}

/// `Σᵢ Σⱼ ±aᵢⱼ bᵢⱼ` ([`Ring::sums_of_products`]): the terms of every product formed, then
/// sorted, merged and brought to canonical form once.
///
/// The same scalar as the products and sums one by one: the canonical form of a group is a
/// function of its value (see `cyclo`), and the terms formed here, merged, sum to the value
/// of each group of the result, so the rewrite of the merged terms is the group the steps
/// give. Only the intermediate canonical forms are skipped: the rewrites of every product's
/// groups and of every partial sum's mixed groups (and the charges of those additions). An
/// error in a factor is the first one in the order of the products, as in the fold.
pub(crate) fn sums_of_products(sums: &[&[SignedProduct<'_, Scalar>]]) -> Scalar {
    let mut out = Vec::new();
    for &(minus, a, b) in sums.iter().flat_map(|s| s.iter()) {
        let (x, y) = terms_or_return!(a, b);
        if let Err(e) =
            admit_product(x, y).and_then(|()| product_terms(x, y, minus, &mut out, None))
        {
            return Scalar::error(e);
        }
    }
    Scalar::from_terms(out)
}

/// Whether `t` is a nonzero constant of the square-root field times one monomial: every term
/// without a trigonometric mode, all with the same monomial (see [`mul`]).
fn scales(t: &[Term]) -> bool {
    t.first().is_some_and(|first| {
        t.iter().all(|u| {
            u.mode.is_unit() && (Arc::ptr_eq(&u.mono, &first.mono) || u.mono == first.mono)
        })
    })
}

impl Scalar {
    /// `self^n`, by repeated squaring; an error value when the result would be too large.
    pub fn pow(&self, n: u64) -> Scalar {
        if let Err(e) = self.terms() {
            return Scalar::error(e.clone());
        }
        if n == 0 {
            return Scalar::int(1);
        }
        if let Some(q) = self.as_rational() {
            // `q^n` has about `n` times the bits of `q`: refused before it is computed.
            let bits = q.numer().bits().max(q.denom().bits());
            let digits = super::digits_of_bits(bits.saturating_sub(1).saturating_mul(n));
            let limit = super::max_digits();
            if bits > 1 && digits > limit {
                return Scalar::error(ScalarError::TooManyDigits { digits, limit });
            }
        }
        if n > u32::MAX as u64 {
            return Scalar::error(ScalarError::OutOfRange(format!(
                "exponent {n} is too large"
            )));
        }
        // A plain polynomial: each term of the power formed once (see `multinomial.rs`).
        if let Some(p) = self
            .terms()
            .ok()
            .and_then(|t| super::multinomial::pow(t, n as u32))
        {
            return p;
        }
        let mut base = self.clone();
        let mut acc = Scalar::int(1);
        let mut e = n;
        loop {
            if e & 1 == 1 {
                acc = mul(&acc, &base);
                if acc.as_error().is_some() {
                    return acc;
                }
            }
            e >>= 1;
            if e == 0 {
                return acc;
            }
            base = mul(&base, &base);
            if base.as_error().is_some() {
                return base;
            }
        }
    }

    /// `self / other`; `other` must be a nonzero number (rationals and radicals).
    pub fn try_div(&self, other: &Scalar) -> Result<Scalar, ScalarError> {
        let r = other.recip();
        mul(self, &r).check()
    }

    /// `1 / self` for a nonzero constant built from rationals and radicals; an error value
    /// otherwise. Radicals in the denominator are removed by multiplying with conjugates.
    pub fn recip(&self) -> Scalar {
        let t = match self.terms() {
            Ok(t) => t,
            Err(e) => return Scalar::error(e.clone()),
        };
        if t.is_empty() {
            return Scalar::error(ScalarError::DivisionByZero);
        }
        if !t.iter().all(|x| x.mode.is_unit() && x.mono.is_empty()) {
            return Scalar::error(ScalarError::SymbolicDivisor(self.to_string()));
        }
        let mut num = Scalar::int(1);
        let mut den = self.clone();
        loop {
            let dt = match den.terms() {
                Ok(dt) => dt,
                Err(e) => return Scalar::error(e.clone()),
            };
            let Some(r) = dt.iter().map(|x| x.rad).find(|&r| r > 1) else {
                break;
            };
            let p = smallest_prime_factor(r);
            let conj: Vec<Term> = dt
                .iter()
                .map(|x| {
                    let mut x = x.clone();
                    if x.rad % p == 0 {
                        x.coef = -x.coef;
                    }
                    x
                })
                .collect();
            let conj = Scalar::from_terms(conj);
            num = mul(&num, &conj);
            den = mul(&den, &conj);
        }
        match den.as_rational() {
            Some(q) if !q.is_zero() => mul(&num, &Scalar::rational(q.recip())),
            _ => Scalar::error(ScalarError::DivisionByZero),
        }
    }

    /// The exact square root of a non-negative rational, reduced: `sqrt(8) = 2 sqrt(2)`,
    /// `sqrt(1/2) = sqrt(2)/2`.
    pub fn sqrt(&self) -> Scalar {
        let Some(q) = self.as_rational() else {
            return match self.terms() {
                Err(e) => Scalar::error(e.clone()),
                Ok(_) => Scalar::error(ScalarError::BadSqrt(self.to_string())),
            };
        };
        if q.is_negative() {
            return Scalar::error(ScalarError::BadSqrt(q.to_string()));
        }
        if q.is_zero() {
            return Scalar::int(0);
        }
        let prod = q.numer() * q.denom();
        let Some((s, r)) = split_square(&prod) else {
            return Scalar::error(ScalarError::BadSqrt(format!("{q} (too large to factor)")));
        };
        let coef = Q::big(BigRational::new(s, q.denom().clone()));
        Scalar::from_terms_sorted(vec![Term {
            mode: Mode::unit(),
            mono: empty_mono(),
            rad: r,
            coef,
        }])
    }

    /// `cos(self)`, reduced to canonical modes; an error value when `self` is not an angle.
    pub fn cos(&self) -> Scalar {
        self.trig(false)
    }

    /// `sin(self)`, reduced to canonical modes; an error value when `self` is not an angle.
    pub fn sin(&self) -> Scalar {
        self.trig(true)
    }

    fn trig(&self, sin: bool) -> Scalar {
        let func = if sin { "sin" } else { "cos" };
        match self.angle_parts() {
            Ok((freq, pi)) => Scalar::trig_of_parts(sin, freq, pi),
            Err(None) => Scalar::error(ScalarError::NotAnAngle {
                func,
                arg: self.to_string(),
            }),
            Err(Some(e)) => Scalar::error(e),
        }
    }

    /// `cos` or `sin` of the angle `sum k_i x_i + p pi` given by its parts, as
    /// [`Scalar::angle_parts`] reads them (sorted by symbol, the constant part on the symbol
    /// `1`, coefficients within the small bound).
    pub(crate) fn trig_of_parts(sin: bool, freq: Vec<(Sym, Small)>, pi: Small) -> Scalar {
        let mut out = Vec::new();
        for (mode, weights) in trig_mode(sin, freq, pi) {
            for (rad, coef) in weights {
                out.push(Term {
                    mode: mode.clone(),
                    mono: empty_mono(),
                    rad,
                    coef,
                });
            }
        }
        Scalar::from_terms(out)
    }

    /// Reads `self` as `sum k_i x_i + p pi` with small rational `k_i`, `p`.
    pub(crate) fn angle_parts(&self) -> Result<AngleParts, Option<ScalarError>> {
        let t = self.terms().map_err(|e| Some(e.clone()))?;
        let mut freq = Vec::new();
        let mut pi = Small::zero();
        for x in t {
            if !x.mode.is_unit() || x.rad != 1 {
                return Err(None);
            }
            let k = to_small(&x.coef).ok_or_else(|| {
                Some(ScalarError::OutOfRange(format!(
                    "angle coefficient {} is too large",
                    x.coef
                )))
            })?;
            match &x.mono[..] {
                [] => freq.push((Sym::one(), k)),
                [(s, 1)] if s.is_pi() => pi = k,
                [(s, 1)] => freq.push((s.clone(), k)),
                _ => return Err(None),
            }
        }
        freq.sort_by(|a, b| a.0.cmp(&b.0));
        Ok((freq, pi))
    }
}

/// An angle read as `(frequencies, multiple of pi)`.
pub(crate) type AngleParts = (Vec<(Sym, Small)>, Small);

fn to_small(q: &Q) -> Option<Small> {
    let s = q.to_ratio_i64()?;
    small_ok(&s).then_some(s)
}

fn smallest_prime_factor(n: u64) -> u64 {
    let mut p = 2;
    while p * p <= n {
        if n.is_multiple_of(p) {
            return p;
        }
        p += 1;
    }
    n
}

impl Zero for Scalar {
    fn zero() -> Self {
        Scalar::int(0)
    }
    fn is_zero(&self) -> bool {
        self.is_zero_value()
    }
}

impl One for Scalar {
    fn one() -> Self {
        Scalar::int(1)
    }
}

macro_rules! binop {
    ($tr:ident, $m:ident, $body:expr) => {
        impl $tr<Scalar> for Scalar {
            type Output = Scalar;
            fn $m(self, rhs: Scalar) -> Scalar {
                $body(&self, &rhs)
            }
        }
        impl<'a> $tr<&'a Scalar> for Scalar {
            type Output = Scalar;
            fn $m(self, rhs: &'a Scalar) -> Scalar {
                $body(&self, rhs)
            }
        }
        impl<'a> $tr<Scalar> for &'a Scalar {
            type Output = Scalar;
            fn $m(self, rhs: Scalar) -> Scalar {
                $body(self, &rhs)
            }
        }
        impl<'a, 'b> $tr<&'b Scalar> for &'a Scalar {
            type Output = Scalar;
            fn $m(self, rhs: &'b Scalar) -> Scalar {
                $body(self, rhs)
            }
        }
    };
}

binop!(Add, add, |a, b| add(a, b, 1));
binop!(Sub, sub, |a, b| add(a, b, -1));
binop!(Mul, mul, mul);

impl Neg for Scalar {
    type Output = Scalar;
    fn neg(self) -> Scalar {
        -&self
    }
}

impl Neg for &Scalar {
    type Output = Scalar;
    fn neg(self) -> Scalar {
        // A canonical group negated is canonical: its coordinates negated (the terms stay
        // sorted and merged).
        match self.terms() {
            Ok(t) => Scalar::from_sorted_settled(
                t.iter()
                    .map(|x| {
                        let mut x = x.clone();
                        x.coef = -x.coef;
                        x
                    })
                    .collect(),
            ),
            Err(e) => Scalar::error(e.clone()),
        }
    }
}

impl Ring for Scalar {
    fn from_ratio(num: i64, den: i64) -> Self {
        if den == 0 {
            return Scalar::error(ScalarError::DivisionByZero);
        }
        Scalar::from_q(Q::new(num, den))
    }
    fn try_recip(&self) -> Option<Self> {
        self.recip().check().ok()
    }
    fn cos(&self) -> Self {
        Scalar::cos(self)
    }
    fn sin(&self) -> Self {
        Scalar::sin(self)
    }
    fn try_sqrt(&self) -> Option<Self> {
        self.sqrt().check().ok()
    }
    fn to_f64(&self) -> Option<f64> {
        self.eval(&|_| None).ok()
    }
    fn sums_of_products(sums: &[&[SignedProduct<'_, Self>]]) -> Self {
        sums_of_products(sums)
    }
}

impl From<i64> for Scalar {
    fn from(n: i64) -> Scalar {
        Scalar::int(n)
    }
}

#[cfg(test)]
mod mode_cache_tests {
    use super::super::atoms::freq_rc;
    use super::{cached_mode_mul, mode_mul, Mode, Modes, Small};
    use crate::scalar::atoms::Sym;
    use std::rc::Rc;

    /// `cos` (or `sin`) of `k t + pi / 3`.
    fn mode(sin: bool, k: i64, t: &str) -> Mode {
        Mode {
            sin,
            freq: freq_rc(vec![(Sym::new(t), Small::from_integer(k))]),
            pi: Small::new(1, 3),
        }
    }

    /// The cache answers what `mode_mul` computes, first by computing it (a miss), then by
    /// handing back the same product (a hit, found by the factors alone); factors in the other
    /// order, or another pair, are other products; a unit factor is never remembered.
    #[test]
    fn cached_products_are_mode_products_keyed_by_their_factors() {
        let (a, b) = (mode(false, 2, "t"), mode(true, 1, "u"));
        let Modes::Cached(first) = cached_mode_mul(&a, &b) else {
            panic!("a product of two angles is remembered");
        };
        assert_eq!(first.sum, mode_mul(&a, &b));
        let Modes::Cached(again) = cached_mode_mul(&a.clone(), &b.clone()) else {
            panic!("a product of two angles is remembered");
        };
        assert!(Rc::ptr_eq(&first, &again));
        let Modes::Cached(swapped) = cached_mode_mul(&b, &a) else {
            panic!("a product of two angles is remembered");
        };
        assert!(!Rc::ptr_eq(&first, &swapped));
        assert_eq!(swapped.sum, mode_mul(&b, &a));
        let c = mode(true, 2, "t");
        let Modes::Cached(other) = cached_mode_mul(&c, &b) else {
            panic!("a product of two angles is remembered");
        };
        assert_eq!(other.sum, mode_mul(&c, &b));
        assert_ne!(other.sum, first.sum);
        let unit = Mode::unit();
        match cached_mode_mul(&unit, &a) {
            Modes::Fresh(sum) => assert_eq!(sum, vec![(a.clone(), vec![(1, super::Q::ONE)])]),
            Modes::Cached(_) => panic!("a product by a unit mode is made on the spot"),
        }
    }
}

#[cfg(test)]
mod product_tests;
