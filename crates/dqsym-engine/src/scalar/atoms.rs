//! The atoms of the canonical form: symbols, monomials, radicals and trigonometric modes.
//!
//! A canonical scalar is a finite sum of terms `q * sqrt(r) * m * t` where `q` is a rational,
//! `r` a square-free integer, `m` a monomial in plain symbols and `t` a *mode*: `1`,
//! `cos(phi)` or `sin(phi)` with `phi` a rational linear combination of symbols (plus a rational
//! multiple of pi that has no exact value). This is a finite Fourier series whose coefficients
//! are polynomials: products of modes are turned back into single modes by the product-to-sum
//! identities, so `cos(t)^2 + sin(t)^2` and `1` are the same vector of terms.

use super::q::Q;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::Ratio;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::fmt;
use std::hash::{Hash, Hasher};
use std::sync::{Arc, OnceLock};

/// A symbol of the canonical form: a named symbol, or the constant 1 that carries the
/// rational constant of a trigonometric argument (`cos(t + 1)`, which is not a multiple of pi)
/// inside a frequency vector. Ordered by the text it prints as (the constant as `1`, so before
/// every name), so the canonical order never depends on the order in which symbols were first
/// seen (no interning-order leaks into the output).
///
/// The constant is one allocation of its own, told apart by identity ([`Sym::is_one`]), never
/// by its text: a named symbol `1` would be a different symbol. Symbols stay one pointer to
/// their name, so frequency vectors and monomials copy, compare and hash as cheaply as names.
///
/// The name is interned for the process (allocated once per distinct name), not
/// reference-counted: a count shared by every term of every thread (`q1` is in most terms of a
/// chain) was one cache line written by both threads of a parallel stage at each copy and drop
/// of a symbol. PUMA 560 and Jaco-style `fk --jacobian`, two threads, SCHED_FIFO, 3 x 30 runs
/// each on a loaded machine: processor time 5.6-6.2 -> 4.9-5.6 ms and 25-28 -> 22-24 ms, wall
/// 3.9-4.1 -> 3.4-3.7 ms and 15-17 -> 13-15 ms; one thread (callgrind) -0.7% instructions on
/// both, the same output.
///
/// A symbol points to its interned `Name`, which holds the name's first eight bytes as one
/// word beside the text, so that two symbols are ordered by one comparison of words unless
/// their names share those bytes (see [`Sym::cmp`]).
#[derive(Clone)]
pub struct Sym(&'static Name);

/// An interned name: its text, and its first eight bytes as a big-endian word (zeros past the
/// end of a shorter name), whose order is the texts' wherever two words differ.
struct Name {
    key: u64,
    text: &'static str,
}

impl Name {
    /// A name for the process: never freed (see [`interned`]).
    fn leak(text: &str) -> &'static Name {
        let mut w = [0u8; 8];
        let n = text.len().min(8);
        w[..n].copy_from_slice(&text.as_bytes()[..n]);
        Box::leak(Box::new(Name {
            key: u64::from_be_bytes(w),
            text: Box::leak(Box::from(text)),
        }))
    }
}

/// The constant's name: its own allocation, never the interned name `1`.
fn one_name() -> &'static Name {
    static ONE: OnceLock<&'static Name> = OnceLock::new();
    ONE.get_or_init(|| Name::leak("1"))
}

/// The interned `Name` of `name` (and its text), made once for the whole process at its first use. A name
/// is never freed: the process holds one copy of each distinct name its symbols ever had, the
/// user's and the project's generated ones (`closed/coefs.rs`'s constants, as many as the
/// largest expression needs), in exchange for symbols copied without a shared count.
///
/// Each thread remembers the names it has interned ([`SEEN`]) and finds them again without the
/// process's lock: a symbolic chain's recurrence makes a symbol from its name for every
/// placeholder and renamed symbol of its closed forms (a fully symbolic 6R's `fk --jacobian`:
/// 10,963 calls, 3.3 M instructions, 3% of the report, in the lock and std's SipHash of the
/// shared set). What a thread remembers is what the shared set returned, so a name has one
/// allocation whichever thread asks. A thread whose locals are being destroyed (a symbol made
/// in another thread-local's destructor) asks the shared set alone.
fn interned(name: &str) -> &'static Name {
    if let Ok(Some(n)) = SEEN.try_with(|seen| seen.borrow().get(name).copied()) {
        return n;
    }
    let n = interned_shared(name);
    let _ = SEEN.try_with(|seen| seen.borrow_mut().insert(n.text, n));
    n
}

/// Interned names by their text, hashed by FxHash (only looked up and added to, never
/// iterated).
type Names = std::collections::HashMap<
    &'static str,
    &'static Name,
    std::hash::BuildHasherDefault<super::FxHasher>,
>;

thread_local! {
    /// The names this thread has interned (see [`interned`]).
    static SEEN: std::cell::RefCell<Names> = std::cell::RefCell::new(Names::default());
}

/// [`interned`] in the process's set of names, under its lock.
fn interned_shared(name: &str) -> &'static Name {
    static NAMES: OnceLock<std::sync::Mutex<Names>> = OnceLock::new();
    let mut names = NAMES
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    if let Some(&n) = names.get(name) {
        return n;
    }
    let n = Name::leak(name);
    names.insert(n.text, n);
    n
}

impl Sym {
    /// The symbol called `name`.
    pub fn new(name: &str) -> Sym {
        Sym(interned(name))
    }

    /// The name as written; the constant of a frequency vector prints as `1`.
    pub fn name(&self) -> &str {
        self.0.text
    }

    /// The constant 1 as an entry of a frequency vector: it carries the rational constant of a
    /// trigonometric argument (`cos(t + 1)`), which is not a multiple of pi.
    pub(crate) fn one() -> Sym {
        Sym(one_name())
    }

    /// The address of the name's allocation: equal exactly for equal symbols (names are
    /// interned; the constant's differs from a named `1`'s).
    pub(crate) fn addr(&self) -> usize {
        std::ptr::from_ref(self.0) as usize
    }

    /// Whether this is the symbol `pi`.
    pub fn is_pi(&self) -> bool {
        self.0.text == "pi"
    }

    /// Whether this is the constant 1 of a frequency vector, which carries the rational
    /// constant of an angle (`cos(t + 1)`); a display [`Angle`](crate::Angle) holds it as its
    /// `constant` field instead.
    pub fn is_one(&self) -> bool {
        std::ptr::eq(self.0, one_name())
    }
}

/// Equal names, and both the constant or neither: one allocation, as names are interned (the
/// constant's is its own).
impl PartialEq for Sym {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self.0, other.0)
    }
}

impl Eq for Sym {}

/// By the name (agrees with `Eq`: the constant and a symbol named `1` only share a hash).
impl Hash for Sym {
    fn hash<H: Hasher>(&self, h: &mut H) {
        self.0.text.hash(h);
    }
}

impl Ord for Sym {
    /// By text (`str`'s order: byte by byte, a prefix first), and the constant before a symbol
    /// printing like it. The first eight bytes decide by one comparison of the names' words
    /// when they differ (a byte that differs decides both orders alike; a name that ends first
    /// has a zero where the other has a byte, nonzero since the words differ, and is a prefix
    /// of it). Names sharing them (`theta1`, `theta2`: the angles of a chain) are compared as
    /// texts. The merges of monomials and the sorts of terms compare symbols by the million,
    /// where `str::cmp` called `memcmp` (the symbolic 6R's `fk --jacobian`: 79,000 of its
    /// 138,000 calls of `memcmp` are gone, 1.7 M instructions).
    #[inline]
    fn cmp(&self, other: &Self) -> Ordering {
        if std::ptr::eq(self.0, other.0) {
            return Ordering::Equal;
        }
        match self.0.key.cmp(&other.0.key) {
            Ordering::Equal => self.cmp_texts(other),
            o => o,
        }
    }
}

impl Sym {
    /// [`Sym::cmp`] of two symbols whose names share their first eight bytes: out of line, so
    /// that the comparison inlined into the sorts of terms (through [`Mode::cmp`]) stays two
    /// word comparisons.
    #[inline(never)]
    fn cmp_texts(&self, other: &Self) -> Ordering {
        self.0
            .text
            .cmp(other.0.text)
            .then_with(|| other.is_one().cmp(&self.is_one()))
    }
}

impl PartialOrd for Sym {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl fmt::Debug for Sym {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0.text)
    }
}

impl fmt::Display for Sym {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0.text)
    }
}

/// The two trigonometric functions of the canonical form and of display expressions.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub enum Trig {
    /// The cosine.
    Cos,
    /// The sine.
    Sin,
}

impl Trig {
    /// `Sin` when `sin` is true, else `Cos`.
    pub fn of(sin: bool) -> Trig {
        if sin {
            Trig::Sin
        } else {
            Trig::Cos
        }
    }

    /// Whether this is the sine.
    pub fn is_sin(self) -> bool {
        self == Trig::Sin
    }

    /// The function's name: `cos` or `sin`.
    pub fn name(self) -> &'static str {
        match self {
            Trig::Cos => "cos",
            Trig::Sin => "sin",
        }
    }

    /// The function's value at `x` in f64.
    pub fn f64(self, x: f64) -> f64 {
        match self {
            Trig::Cos => x.cos(),
            Trig::Sin => x.sin(),
        }
    }
}

/// A small exact rational for frequencies and pi offsets; bounded so sums never overflow.
pub type Small = Ratio<i64>;

/// The largest numerator or denominator a frequency may have.
pub(crate) const SMALL_BOUND: i64 = 1 << 40;

pub(crate) fn small_ok(q: &Small) -> bool {
    q.numer().abs() < SMALL_BOUND && *q.denom() < SMALL_BOUND
}

/// A monomial as a term stores it: shared, so copying a term never copies its factors.
pub(crate) type MonoRc = Arc<[(Sym, u32)]>;

/// The frequency vector of a mode, shared like [`MonoRc`].
pub(crate) type Freq = Arc<[(Sym, Small)]>;

/// The empty monomial (one shared allocation).
pub(crate) fn empty_mono() -> MonoRc {
    static EMPTY: OnceLock<MonoRc> = OnceLock::new();
    EMPTY.get_or_init(|| Arc::from(Vec::new())).clone()
}

fn empty_freq() -> Freq {
    static EMPTY: OnceLock<Freq> = OnceLock::new();
    EMPTY.get_or_init(|| Arc::from(Vec::new())).clone()
}

/// A frequency vector as shared storage (the empty one is not allocated again).
pub(crate) fn freq_rc(v: Vec<(Sym, Small)>) -> Freq {
    if v.is_empty() {
        empty_freq()
    } else {
        Arc::from(v)
    }
}

/// The product of two monomials, or `None` when an exponent would overflow.
pub(crate) fn mono_mul(a: &MonoRc, b: &MonoRc) -> Option<MonoRc> {
    if a.is_empty() {
        return Some(b.clone());
    }
    if b.is_empty() {
        return Some(a.clone());
    }
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].0.cmp(&b[j].0) {
            Ordering::Less => {
                out.push(a[i].clone());
                i += 1;
            }
            Ordering::Greater => {
                out.push(b[j].clone());
                j += 1;
            }
            Ordering::Equal => {
                out.push((a[i].0.clone(), a[i].1.checked_add(b[j].1)?));
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
    Some(Arc::from(out))
}

/// [`mono_mul`] merged in `buf` (cleared first), a scratch vector the caller keeps across
/// products: the monomial's one allocation is its shared storage, where [`mono_mul`] also
/// allocates (and frees) the vector it merges in. (A product of scalars forms a monomial for
/// every pair of terms: 7,624 in the symbolic 6R's `fk --jacobian`.)
pub(crate) fn mono_mul_in(a: &MonoRc, b: &MonoRc, buf: &mut Vec<(Sym, u32)>) -> Option<MonoRc> {
    if a.is_empty() {
        return Some(b.clone());
    }
    if b.is_empty() {
        return Some(a.clone());
    }
    buf.clear();
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].0.cmp(&b[j].0) {
            Ordering::Less => {
                buf.push(a[i].clone());
                i += 1;
            }
            Ordering::Greater => {
                buf.push(b[j].clone());
                j += 1;
            }
            Ordering::Equal => {
                buf.push((a[i].0.clone(), a[i].1.checked_add(b[j].1)?));
                i += 1;
                j += 1;
            }
        }
    }
    buf.extend_from_slice(&a[i..]);
    buf.extend_from_slice(&b[j..]);
    Some(Arc::from(&buf[..]))
}

/// Numeric order of two small rationals (denominators are positive): the order `Ratio`
/// gives, without its divisions.
pub(crate) fn small_cmp(a: &Small, b: &Small) -> Ordering {
    if a.denom() == b.denom() {
        return a.numer().cmp(b.numer());
    }
    (*a.numer() as i128 * *b.denom() as i128).cmp(&(*b.numer() as i128 * *a.denom() as i128))
}

/// A trigonometric mode: `1` (empty frequency, no pi offset, cosine), `cos(phi)` or `sin(phi)`.
///
/// Invariants, kept by [`trig_mode`] and `cyclo/`: `freq` is sorted by symbol with nonzero
/// entries and a positive first entry; `pi` lies in `[0, 2)` and is never a multiple of 1/12
/// (those are expanded exactly); a mode with empty `freq` has `pi` in `(0, 1)`, or is the unit
/// mode. Within the degree bound of `cyclo/` the modes with a pi offset are those of the
/// canonical bases: `cos(k pi/n)` at angles in `(0, pi/2)` for constants, `cos`/`sin` of
/// `phi + theta` with `theta` in `(-pi/4, pi/4]` for symbolic angles.
#[derive(Clone, PartialEq, Eq, Debug)]
pub struct Mode {
    pub(crate) sin: bool,
    pub(crate) freq: Freq,
    pub(crate) pi: Small,
}

/// Lexicographic by `(sin, freq, pi)`, the frequencies compared entry by entry (symbol by
/// name, then coefficient by value), shorter first on a common prefix.
impl Ord for Mode {
    // Inlined into `Term::key_cmp`, the comparator of every sort of terms.
    #[inline]
    fn cmp(&self, other: &Self) -> Ordering {
        self.sin
            .cmp(&other.sin)
            .then_with(|| freq_cmp(&self.freq, &other.freq))
            .then_with(|| small_cmp(&self.pi, &other.pi))
    }
}

/// The derived order of frequency vectors (entry by entry, symbol by name, then coefficient
/// by value, shorter first on a common prefix), without its costs: one shared vector is
/// equal to itself at once, and coefficients compare by [`small_cmp`] instead of `Ratio`'s
/// divisions (the group keys of `cyclo::canonicalize`, sorted and searched for every term
/// of every canonical scalar, spent 10 M of the Jaco-style arm's 318 M instructions in
/// `Ratio::cmp` and the slice comparison around it). Always inlined: called out of line
/// from [`Mode::cmp`] (every sort of terms) it cost the symbolic 4R chain's report 1.5%.
#[inline(always)]
pub(crate) fn freq_cmp(a: &[(Sym, Small)], b: &[(Sym, Small)]) -> Ordering {
    if std::ptr::eq(a, b) {
        return Ordering::Equal;
    }
    for (x, y) in a.iter().zip(b) {
        let o = x.0.cmp(&y.0).then_with(|| small_cmp(&x.1, &y.1));
        if o.is_ne() {
            return o;
        }
    }
    a.len().cmp(&b.len())
}

/// Hashes the symbol names and the coefficients' numerators and denominators directly: the
/// generic `Ratio` hash (a continued-fraction expansion) dominated the mode-product cache.
/// Agrees with `Eq` because every `Small` is kept reduced (all of them come from `Ratio`
/// arithmetic or `Ratio::new`).
impl Hash for Mode {
    fn hash<H: Hasher>(&self, h: &mut H) {
        h.write_u8(u8::from(self.sin));
        h.write_usize(self.freq.len());
        for (s, k) in self.freq.iter() {
            // The name's length and last (up to) eight bytes: content only, so still
            // consistent with `Eq`, and one word instead of a byte-string hash.
            let b = s.name().as_bytes();
            let tail = &b[b.len().saturating_sub(8)..];
            let mut w = [0u8; 8];
            w[..tail.len()].copy_from_slice(tail);
            h.write_u64(u64::from_le_bytes(w));
            h.write_usize(b.len());
            h.write_i64(*k.numer());
            h.write_i64(*k.denom());
        }
        h.write_i64(*self.pi.numer());
        h.write_i64(*self.pi.denom());
    }
}

impl PartialOrd for Mode {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Mode {
    /// The mode `1`.
    pub(crate) fn unit() -> Mode {
        Mode {
            sin: false,
            freq: empty_freq(),
            pi: Small::zero(),
        }
    }

    pub(crate) fn is_unit(&self) -> bool {
        !self.sin && self.freq.is_empty() && self.pi.is_zero()
    }
}

/// A mode together with the exact coefficient it was multiplied by while being normalized:
/// `cos(-x) = cos x`, `sin(-x) = -sin x`, `cos(x + pi/4) = sqrt(2)/2 (cos x - sin x)`.
pub(crate) type ModeSum = Vec<(Mode, Vec<(u64, Q)>)>;

/// `cos(phi)` or `sin(phi)` with `phi = freq . symbols + pi_mult * pi`, as a sum of
/// normalized modes times exact constants (radical, rational).
pub(crate) fn trig_mode(sin: bool, mut freq: Vec<(Sym, Small)>, pi_mult: Small) -> ModeSum {
    freq.retain(|(_, k)| !k.is_zero());
    let mut pi = pi_mult;
    let mut sign = 1i64;
    if freq.first().is_some_and(|(_, k)| k.is_negative()) {
        for (_, k) in freq.iter_mut() {
            *k = -*k;
        }
        pi = -pi;
        if sin {
            sign = -1;
        }
    }
    if pi.is_zero() {
        // cos(x) or sign * sin(x): the common case, without the reduction below.
        if freq.is_empty() {
            return if sin {
                Vec::new()
            } else {
                vec![(Mode::unit(), vec![(1, Q::ONE)])]
            };
        }
        return vec![(
            Mode {
                sin,
                freq: freq_rc(freq),
                pi,
            },
            vec![(1, Q::int(sign))],
        )];
    }
    // Reduce pi into [0, 2).
    let two = Small::from_integer(2);
    pi = pi - (pi / two).floor() * two;
    let twelfths = pi * Small::from_integer(12);
    if twelfths.is_integer() {
        let n = twelfths.to_integer();
        if freq.is_empty() {
            // A pure constant: cos a or sin a.
            let v = exact_cos_twelfth(if sin { n - 6 } else { n });
            return if v.is_empty() {
                Vec::new()
            } else {
                vec![(Mode::unit(), scaled_weights(v, sign))]
            };
        }
        return twelfth_modes(sin, freq_rc(freq), n, sign);
    }
    if freq.is_empty() && pi > Small::one() {
        // cos(a) = cos(2 pi - a), sin(a) = -sin(2 pi - a).
        pi = two - pi;
        if sin {
            sign = -sign;
        }
    }
    let one = vec![(1u64, Q::int(sign))];
    vec![(
        Mode {
            sin,
            freq: freq_rc(freq),
            pi,
        },
        one,
    )]
}

/// Weights each times the integer `f`.
fn scaled_weights(v: Vec<(u64, Q)>, f: i64) -> Vec<(u64, Q)> {
    v.into_iter().map(|(r, q)| (r, q.mul_int(f))).collect()
}

/// `cos(phi + n pi/12)` (or `sin`) for the symbolic angle `phi` of the normalized frequency
/// vector `freq`, times `sign`, as the modes `cos(phi)`, `sin(phi)` without an offset times
/// exact constants: `cos(x + a) = cos a cos x - sin a sin x`, `sin(x + a) = cos a sin x + sin
/// a cos x`, with `cos a`, `sin a` radicals (`exact_cos_twelfth`).
pub(crate) fn twelfth_modes(sin: bool, freq: Freq, n: i64, sign: i64) -> ModeSum {
    let (ca, sa) = (exact_cos_twelfth(n), exact_cos_twelfth(n - 6));
    let base = |s: bool| Mode {
        sin: s,
        freq: freq.clone(),
        pi: Small::zero(),
    };
    let mut out: ModeSum = Vec::new();
    if sin {
        if !ca.is_empty() {
            out.push((base(true), scaled_weights(ca, sign)));
        }
        if !sa.is_empty() {
            out.push((base(false), scaled_weights(sa, sign)));
        }
    } else {
        if !ca.is_empty() {
            out.push((base(false), ca));
        }
        if !sa.is_empty() {
            out.push((base(true), scaled_weights(sa, -1)));
        }
    }
    out
}

/// `cos(n pi / 12)` exactly, as a sum of (square-free radicand, rational) pairs; empty for 0.
pub(crate) fn exact_cos_twelfth(n: i64) -> Vec<(u64, Q)> {
    let n = n.rem_euclid(24);
    // cos(pi - x) = -cos x and cos(2 pi - x) = cos x fold everything into [0, 6].
    let (m, sign) = match n {
        0..=6 => (n, 1),
        7..=12 => (12 - n, -1),
        13..=18 => (n - 12, -1),
        _ => (24 - n, 1),
    };
    let q = |a: i64, b: i64| Q::new(a * sign, b);
    match m {
        0 => vec![(1, q(1, 1))],
        1 => vec![(2, q(1, 4)), (6, q(1, 4))],
        2 => vec![(3, q(1, 2))],
        3 => vec![(2, q(1, 2))],
        4 => vec![(1, q(1, 2))],
        5 => vec![(2, q(-1, 4)), (6, q(1, 4))],
        _ => vec![],
    }
}

/// The product of two modes as a sum of modes with exact weights (product-to-sum identities).
pub(crate) fn mode_mul(a: &Mode, b: &Mode) -> ModeSum {
    let one = || vec![(1u64, Q::ONE)];
    if a.is_unit() {
        return vec![(b.clone(), one())];
    }
    if b.is_unit() {
        return vec![(a.clone(), one())];
    }
    let sum = freq_combine(&a.freq, &b.freq, 1);
    let diff = freq_combine(&a.freq, &b.freq, -1);
    let (ps, pd) = (a.pi + b.pi, a.pi - b.pi);
    // cos a cos b = (cos(a-b) + cos(a+b))/2, sin a sin b = (cos(a-b) - cos(a+b))/2,
    // sin a cos b = (sin(a+b) + sin(a-b))/2, cos a sin b = (sin(a+b) - sin(a-b))/2.
    let (kind, w_diff) = match (a.sin, b.sin) {
        (false, false) => (false, 1),
        (true, true) => (false, 1),
        (true, false) => (true, 1),
        (false, true) => (true, -1),
    };
    let w_sum = if a.sin && b.sin { -1 } else { 1 };
    // Two modes, cos or sin of `a - b` and of `a + b`, unless a multiple of pi splits one:
    // sized for the usual two (products are cached for the whole run, and a growing `Vec`
    // starts at four: 128 bytes of each product's 256 unused).
    let mut out = Vec::with_capacity(2);
    for (f, p, w) in [(diff, pd, w_diff), (sum, ps, w_sum)] {
        for (m, v) in trig_mode(kind, f, p) {
            let v = v
                .into_iter()
                .map(|(r, q)| (r, &q * &Q::new(w, 2)))
                .collect();
            out.push((m, v));
        }
    }
    out
}

/// `a + b`, reduced like `Ratio`'s sum; a shortcut for a common denominator (the usual case:
/// half angles), which `Ratio` reduces through its generic gcd.
fn small_add(a: &Small, b: &Small) -> Small {
    let d = *a.denom();
    if d == *b.denom() {
        if let Some(n) = a.numer().checked_add(*b.numer()) {
            if n == 0 {
                return Small::zero();
            }
            let g = n.unsigned_abs().gcd(&d.unsigned_abs());
            // `g` divides both, and `d > 0`, so the quotients fit and the sign stays on top.
            return Small::new_raw(n / g as i64, d / g as i64);
        }
    }
    a + b
}

/// `a + sign * b` on sorted frequency vectors.
pub(crate) fn freq_combine(a: &[(Sym, Small)], b: &[(Sym, Small)], sign: i64) -> Vec<(Sym, Small)> {
    let signed = |k: Small| match sign {
        1 => k,
        -1 => -k,
        _ => k * Small::from_integer(sign),
    };
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].0.cmp(&b[j].0) {
            Ordering::Less => {
                out.push(a[i].clone());
                i += 1;
            }
            Ordering::Greater => {
                out.push((b[j].0.clone(), signed(b[j].1)));
                j += 1;
            }
            Ordering::Equal => {
                let k = small_add(&a[i].1, &signed(b[j].1));
                if !k.is_zero() {
                    out.push((a[i].0.clone(), k));
                }
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend(b[j..].iter().map(|(x, k)| (x.clone(), signed(*k))));
    out
}

/// `sqrt(a) sqrt(b) = g sqrt(ab / g^2)` with `g = gcd(a, b)`, for square-free `a`, `b`;
/// `None` when the radicand leaves `u64`.
pub(crate) fn rad_mul(a: u64, b: u64) -> Option<(u64, u64)> {
    if a == 1 {
        return Some((b, 1));
    }
    if b == 1 {
        return Some((a, 1));
    }
    let g = a.gcd(&b);
    let r = (a / g).checked_mul(b / g)?;
    Some((r, g))
}

/// The largest square dividing a positive integer: `n = s^2 * r` with `r` square-free.
/// `None` when `n` is too large to factor quickly.
pub(crate) fn split_square(n: &BigInt) -> Option<(BigInt, u64)> {
    let mut n = n.clone();
    let mut s = BigInt::one();
    let mut r: u64 = 1;
    let mut p: u64 = 2;
    while p <= 1_000_000 {
        let pb = BigInt::from(p);
        if &pb * &pb > n {
            break;
        }
        let mut e = 0u32;
        while (&n % &pb).is_zero() {
            n /= &pb;
            e += 1;
        }
        for _ in 0..e / 2 {
            s *= &pb;
        }
        if e % 2 == 1 {
            r = r.checked_mul(p)?;
        }
        p += if p == 2 { 1 } else { 2 };
    }
    if n.is_one() {
        return Some((s, r));
    }
    let root = n.sqrt();
    if &root * &root == n {
        return Some((s * root, r));
    }
    // No factor up to 10^6: below 10^12 the rest is prime, hence square-free.
    let rest = n.to_u64().filter(|&v| v < 1_000_000_000_000)?;
    Some((s, r.checked_mul(rest)?))
}

#[cfg(test)]
mod tests {
    use super::Sym;

    /// Symbols made apart (here on four threads) from equal names are one symbol: equal, the
    /// same address, the same order; different names, and the constant beside a named `1`,
    /// are not, and the order is the names' (the constant first).
    #[test]
    fn interned_names_are_one_symbol_and_the_constant_stays_apart() {
        let names = ["q1", "q2", "1", "pi", "", "theta12", "q1"];
        let made: Vec<Vec<Sym>> = std::thread::scope(|s| {
            let hs: Vec<_> = (0..4)
                .map(|_| s.spawn(|| names.iter().map(|n| Sym::new(n)).collect::<Vec<_>>()))
                .collect();
            hs.into_iter()
                .map(|h| h.join().expect("no panic"))
                .collect()
        });
        for syms in &made {
            for (i, a) in syms.iter().enumerate() {
                let b = &made[0][i];
                assert_eq!(a, b);
                assert_eq!(a.addr(), b.addr());
                assert_eq!(a.name(), names[i]);
                for (j, c) in made[0].iter().enumerate() {
                    assert_eq!(a == c, names[i] == names[j]);
                    assert_eq!(a.addr() == c.addr(), names[i] == names[j]);
                    assert_eq!(a.cmp(c), names[i].cmp(names[j]));
                }
            }
        }
        let one = Sym::one();
        let named = Sym::new("1");
        assert!(one.is_one() && !named.is_one());
        assert_ne!(one, named);
        assert_ne!(one.addr(), named.addr());
        assert_eq!(one.name(), named.name());
        assert!(one < named && one < Sym::new("a") && Sym::new("0") < one);
        assert!(Sym::new("pi").is_pi() && !Sym::new("q1").is_pi());
    }

    /// Symbols compared by their first eight bytes' words are in `str`'s order (the replaced
    /// comparison), and the constant comes just before a named `1`: random names over a small
    /// alphabet (so that many share prefixes, are prefixes of each other or are equal), with
    /// and without a common prefix of eight bytes (`theta_12`) or seven, multi-byte characters,
    /// zero bytes (a word's padding) and the empty name among them.
    #[test]
    fn symbols_are_in_the_order_of_their_names() {
        let mut next = crate::testing::xorshift_below(4021);
        let alphabet = ["a", "b", "1", "_", "\0", "é", "z", "\u{10348}"];
        // Half of them after a common prefix of eight bytes and more (their words equal).
        let names: Vec<String> = (0..400)
            .map(|i| {
                let tail: String = (0..next(11))
                    .map(|_| alphabet[next(alphabet.len() as u64) as usize])
                    .collect();
                match i % 4 {
                    0 => format!("theta_12{tail}"),
                    1 => format!("theta_1{tail}"),
                    _ => tail,
                }
            })
            .collect();
        let syms: Vec<Sym> = names.iter().map(|n| Sym::new(n)).collect();
        let (mut less, mut equal) = (0, 0);
        for (a, x) in names.iter().zip(&syms) {
            for (b, y) in names.iter().zip(&syms) {
                let o = x.cmp(y);
                assert_eq!(o, a.as_str().cmp(b.as_str()), "{a:?} {b:?}");
                less += usize::from(o.is_lt());
                equal += usize::from(o.is_eq());
            }
            let one = Sym::one();
            let expected = "1".cmp(a.as_str()).then(std::cmp::Ordering::Less);
            assert_eq!(one.cmp(x), expected, "{a:?}");
            assert_eq!(x.cmp(&one), expected.reverse(), "{a:?}");
        }
        assert!(less > 50_000 && equal > 400, "{less} {equal}");
    }
}
