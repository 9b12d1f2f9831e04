//! Monomials over trigonometric atoms: the working form between the canonical Fourier series
//! and a display expression.
//!
//! Within one closed-form computation the angles and symbols are interned in a [`Ctx`]: an
//! angle is a small integer whose order is the order of the angles themselves (the table is
//! kept sorted, see [`Ctx::renumber`]), so monomials compare, sort and hash as plain integer
//! vectors and the result depends on nothing but the input.

use super::expr::Angle;
use crate::scalar::atoms::freq_combine;
use crate::scalar::{FxHasher, Small, Sym, Q};
use crate::Scalar;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use smallvec::SmallVec;
use std::cmp::Ordering;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hash, Hasher};

/// A map with the crate's fast deterministic hasher (only looked up, never iterated for output).
pub(crate) type FxMap<K, V> = HashMap<K, V, BuildHasherDefault<FxHasher>>;

/// An angle as a hash key: hashes the symbol names and the (always reduced) coefficients
/// directly, which is much cheaper than the generic `Ratio` hash.
#[derive(PartialEq, Eq, Clone)]
struct AngleKey(Angle);

impl Hash for AngleKey {
    fn hash<H: Hasher>(&self, h: &mut H) {
        h.write_usize(self.0.terms.len());
        for (s, k) in &self.0.terms {
            s.name().hash(h);
            h.write_i64(*k.numer());
            h.write_i64(*k.denom());
        }
        h.write_i64(*self.0.constant.numer());
        h.write_i64(*self.0.constant.denom());
        h.write_i64(*self.0.pi.numer());
        h.write_i64(*self.0.pi.denom());
    }
}

/// `cos(angle)` or `sin(angle)` as a factor of a monomial: `2 * angle id + sin`, so the order of
/// the codes is the order `(angle, sin)`.
pub(crate) type Atom = u32;

/// The atom `cos(angle)` or `sin(angle)`.
pub(crate) fn atom(angle: u32, sin: bool) -> Atom {
    angle * 2 + u32::from(sin)
}

/// The angle of an atom.
pub(crate) fn angle_of(a: Atom) -> u32 {
    a >> 1
}

/// Whether an atom is a sine.
pub(crate) fn is_sin(a: Atom) -> bool {
    a & 1 == 1
}

/// The interned angles and symbols of one closed-form computation.
#[derive(Default, Clone)]
pub(crate) struct Ctx {
    /// The angles; after [`Ctx::renumber`] sorted, so an id is its angle's rank.
    pub(crate) angles: Vec<Angle>,
    ids: FxMap<AngleKey, u32>,
    /// Angles were added since the last renumbering.
    dirty: bool,
    /// The plain symbols of the input, sorted; a symbol's id is its rank.
    pub(crate) syms: Vec<Sym>,
    /// The id of each symbol of the input, by [`Sym::addr`] (one address per name: names are
    /// interned for the process).
    by_addr: FxMap<usize, (u32, Sym)>,
}

impl Ctx {
    fn new(x: &Scalar) -> Ctx {
        // The symbols' addresses first (one per symbol, met thousands of times in the entries
        // of a symbolic chain's matrix), so that only those are sorted by name: a sort of
        // every occurrence by name spent 6% of a symbolic 6R's report comparing names.
        let mut by_addr: FxMap<usize, (u32, Sym)> = FxMap::default();
        if let Ok(terms) = x.terms() {
            for t in terms {
                for (s, _) in t.mono.iter() {
                    by_addr.entry(s.addr()).or_insert_with(|| (0, s.clone()));
                }
            }
        }
        let mut syms: Vec<Sym> = by_addr.values().map(|(_, s)| s.clone()).collect();
        syms.sort();
        syms.dedup();
        for (id, s) in by_addr.values_mut() {
            *id = syms.binary_search(s).unwrap_or(0) as u32;
        }
        Ctx {
            syms,
            by_addr,
            ..Ctx::default()
        }
    }

    /// The id of `a` (a new angle gets the next free id until the next renumbering).
    pub(crate) fn intern(&mut self, a: Angle) -> u32 {
        let key = AngleKey(a);
        if let Some(&i) = self.ids.get(&key) {
            return i;
        }
        let a = key.0.clone();
        let i = self.angles.len() as u32;
        self.ids.insert(key, i);
        self.angles.push(a);
        self.dirty = true;
        i
    }

    /// Sorts the angle table; returns the map from old to new ids when anything was added.
    /// The map is monotonic on the ids that were already sorted.
    pub(crate) fn renumber(&mut self) -> Option<Vec<u32>> {
        if !self.dirty {
            return None;
        }
        self.dirty = false;
        let mut order: Vec<u32> = (0..self.angles.len() as u32).collect();
        order.sort_by(|&a, &b| self.angles[a as usize].cmp(&self.angles[b as usize]));
        let mut map = vec![0u32; order.len()];
        for (new, &old) in order.iter().enumerate() {
            map[old as usize] = new as u32;
        }
        let mut old: Vec<Option<Angle>> = std::mem::take(&mut self.angles)
            .into_iter()
            .map(Some)
            .collect();
        self.angles = order
            .iter()
            .filter_map(|&o| old[o as usize].take())
            .collect();
        for v in self.ids.values_mut() {
            *v = map[*v as usize];
        }
        Some(map)
    }

    fn sym_id(&self, s: &Sym) -> u32 {
        if let Some((id, _)) = self.by_addr.get(&s.addr()) {
            return *id;
        }
        self.sym_id_searched(s)
    }

    /// [`Ctx::sym_id`] past the table: out of line, so that the lookup stays small enough
    /// to be inlined into the loops over monomials ([`base_mon`]'s).
    #[cold]
    #[inline(never)]
    fn sym_id_searched(&self, s: &Sym) -> u32 {
        // Every symbol of the input is in the table.
        self.syms.binary_search(s).unwrap_or(0) as u32
    }
}

/// The derivative of the sum of `mons` with respect to the symbol `var`, unmerged: for each
/// factor holding `var`, the monomial with that factor differentiated (product rule).
pub(crate) fn differentiate(ctx: &Ctx, mons: &[Mon], var: &str) -> Vec<Mon> {
    let sym = ctx
        .syms
        .iter()
        .position(|s| s.name() == var)
        .map(|i| i as u32);
    // The coefficient of `var` in each angle.
    let k: Vec<Option<Q>> = ctx
        .angles
        .iter()
        .map(|a| {
            a.terms
                .iter()
                .find(|(s, _)| s.name() == var)
                .map(|(_, k)| Q::new(*k.numer(), *k.denom()))
        })
        .collect();
    let mut out = Vec::new();
    for m in mons {
        if let Some(s) = sym {
            if let Some(pos) = m.syms.iter().position(|&(x, _)| x == s) {
                let e = m.syms[pos].1;
                let mut d = m.clone();
                d.q = d.q.mul_int(i64::from(e));
                if e == 1 {
                    d.syms.remove(pos);
                } else {
                    d.syms[pos].1 -= 1;
                }
                out.push(d);
            }
        }
        for (pos, &a) in m.atoms.iter().enumerate() {
            let Some(kq) = &k[angle_of(a) as usize] else {
                continue;
            };
            // cos(phi)' = -k sin(phi), sin(phi)' = k cos(phi).
            let mut d = m.clone();
            d.q = &d.q * kq;
            if !is_sin(a) {
                d.q = -&d.q;
            }
            d.atoms[pos] = atom(angle_of(a), !is_sin(a));
            d.atoms.sort_unstable();
            out.push(d);
        }
    }
    out
}

/// Renames the atoms of `m` after a renumbering and restores their order.
pub(crate) fn remap(m: &mut Mon, map: &[u32]) {
    for a in m.atoms.iter_mut() {
        *a = atom(map[angle_of(*a) as usize], is_sin(*a));
    }
    m.atoms.sort_unstable();
}

/// The atoms of a monomial, inline up to eight (one per symbol of a mode, at most).
pub(crate) type Atoms = SmallVec<[Atom; 8]>;

/// The symbols `(id, exponent)` of a monomial, inline up to four.
pub(crate) type Syms = SmallVec<[(u32, u32); 4]>;

/// `q * sqrt(rad) * syms * atoms`, symbols `(id, exponent)` and atoms sorted.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub(crate) struct Mon {
    pub(crate) q: Q,
    pub(crate) rad: u64,
    pub(crate) syms: Syms,
    pub(crate) atoms: Atoms,
}

/// The order of the factors `(rad, syms, atoms)`.
pub(crate) fn key_cmp(a: &Mon, b: &Mon) -> Ordering {
    a.rad
        .cmp(&b.rad)
        .then_with(|| a.syms.cmp(&b.syms))
        .then_with(|| a.atoms.cmp(&b.atoms))
}

/// Sums monomials with equal factors and drops zeros; output sorted by factors.
pub(crate) fn merge(mut mons: Vec<Mon>) -> Vec<Mon> {
    mons.sort_unstable_by(key_cmp);
    let mut out: Vec<Mon> = Vec::with_capacity(mons.len());
    for m in mons {
        match out.last_mut() {
            Some(l) if key_cmp(l, &m).is_eq() => l.q += &m.q,
            _ => {
                if out.last().is_some_and(|l| l.q.is_zero()) {
                    out.pop();
                }
                out.push(m);
            }
        }
    }
    if out.last().is_some_and(|l| l.q.is_zero()) {
        out.pop();
    }
    out
}

fn base_mon(ctx: &Ctx, t: &crate::scalar::Term) -> Mon {
    Mon {
        q: t.coef.clone(),
        rad: t.rad,
        syms: t.mono.iter().map(|(s, e)| (ctx.sym_id(s), *e)).collect(),
        atoms: Atoms::new(),
    }
}

/// The canonical form as monomials, each mode kept whole (`cos(t1 + t2)` is one atom).
pub(crate) fn whole_modes(x: &Scalar) -> (Ctx, Vec<Mon>) {
    whole_modes_of(x, false)
}

/// [`whole_modes`] with each group of terms that share a monomial and a symbolic frequency
/// vector `F` and hold a pi offset outside the multiples of pi/12 joined into one angle when
/// it is one: `R cos(F + phi)` (`-1/2 cos(t - pi/9) - sqrt(3)/2 sin(t - pi/9) = cos(t +
/// 5*pi/9)`), `R` a rational times a square root, found numerically and checked exactly
/// (see [`single_angle`]).
pub(crate) fn whole_modes_joined(x: &Scalar) -> (Ctx, Vec<Mon>) {
    whole_modes_of(x, true)
}

/// The group `g` (all the terms of a canonical scalar of one monomial and one frequency
/// vector, in order) as one term `R cos(F + phi)` (or `R sin(F + phi')`, whichever offset has
/// the smaller denominator, cos on ties), `R > 0` a rational times the square root of a
/// square-free integer and `phi` a rational multiple of pi; `None` when the group is not one
/// angle (or the exact check fails).
fn single_angle(g: &[&crate::scalar::Term]) -> Option<crate::scalar::Term> {
    use num_traits::ToPrimitive;
    let (re, im) = super::offsets::amplitude(g.iter().copied())?;
    let den = g.iter().fold(12i64, |d, t| d.lcm(t.mode.pi.denom()));
    let r2 = re * re + im * im;
    // R^2 = n / d with a small d: R = sqrt(n d) / d.
    let (n, d) = square_as_fraction(r2)?;
    let nd = u64::try_from(n.checked_mul(d)?).ok()?;
    let (square, free) = crate::scalar::atoms::split_square(&BigInt::from(nd))?;
    let square = square.to_i64()?;
    let phi = im.atan2(re) / std::f64::consts::PI * den as f64;
    let k = phi.round();
    if (phi - k).abs() > 1e-7 {
        return None;
    }
    let p = Small::new(k as i64, den);
    // cos(F + p) or sin(F + p + 1/2), each offset in [0, 2).
    let two = Small::from_integer(2);
    let wrap = |v: Small| v - (v / two).floor() * two;
    let (c, s) = (wrap(p), wrap(p + Small::new(1, 2)));
    let (sin, pi) = if c.denom() <= s.denom() {
        (false, c)
    } else {
        (true, s)
    };
    let term = crate::scalar::Term {
        mode: crate::scalar::Mode {
            sin,
            freq: g[0].mode.freq.clone(),
            pi,
        },
        mono: g[0].mono.clone(),
        rad: free,
        coef: Q::new(square, d),
    };
    // `g` is a whole group of a canonical scalar (all its terms of one monomial and one
    // frequency vector, in order: the cyclotomic layer's group), so it is canonical on its
    // own and is not rewritten again.
    let group = Scalar::from_sorted_settled(g.iter().map(|t| (*t).clone()).collect());
    (Scalar::from_terms(vec![term.clone()]) == group).then_some(term)
}

/// The largest denominator [`square_as_fraction`] tries.
const MAX_SQUARE_DEN: i64 = 4096;

/// `(n, d)` for the least `d <= MAX_SQUARE_DEN` whose multiple `r2 * d` is within a relative
/// `1e-9` of a whole `n >= 1` (`R^2 = n / d` for [`single_angle`]), or `None`. The scan
/// begins at [`first_candidate`]: the same answer, without the thousands of multiples
/// before it (the Jaco-style arm's `fk --jacobian`: 1,216 squares, most of them found at
/// denominators near 4,096, 14 M instructions in the scan from 1).
fn square_as_fraction(r2: f64) -> Option<(i64, i64)> {
    scan_from(r2, first_candidate(r2)?)
}

/// The scan of [`square_as_fraction`] from the denominator `start` on.
fn scan_from(r2: f64, start: i64) -> Option<(i64, i64)> {
    // Every multiple below 2^52 and not negative: rounded without the library call.
    let small = (0.0..1e11).contains(&r2) && r2.is_sign_positive();
    (start..=MAX_SQUARE_DEN).find_map(|d| {
        let x = r2 * d as f64;
        let n = if small { round_small(x) } else { x.round() };
        ((r2 * d as f64 - n).abs() < 1e-9 * (1.0 + r2 * d as f64) && n >= 1.0)
            .then_some((n as i64, d))
    })
}

/// The least denominator from which [`scan_from`] may succeed on `r2`: every smaller one
/// surely fails its test; `None` when every one up to `MAX_SQUARE_DEN` does, `Some(1)` when
/// unsure.
///
/// Why it is sound. The float `r2` is exactly `num / 2^k`. A `d` the scan takes has
/// `|x - n| < tol` with `x = fl(r2 d)`, `n` a whole number and `tol = fl(1e-9 fl(1 + x))`;
/// `x - n` is exact there (`|x - n| <= 1/2` and `x < 2^52`: a multiple of the ulp of `x`,
/// or Sterbenz below 1), `tol <= 1e-9 (1 + x)(1 + 2^-53)^3` and `|x - r2 d| <= 2^-53 x`, so
/// `||r2 d||`, the distance of the exact `r2 d` to the nearest integer, is below `T =
/// 1.02e-9 (1 + X) + 2.3e-16 X` with `X = r2 (MAX_SQUARE_DEN + 1) > x` (a margin over every
/// rounding, also of `T` itself and of the float compared with it). Let `q_0 = 1 < q_1 <
/// ...` be the denominators of the convergents of `r2`'s continued fraction, computed here
/// in exact integer arithmetic. Lagrange's theorem on best approximations (Khinchin,
/// *Continued Fractions*, Theorems 16 and 17): every `d < q_(j+1)` has `||r2 d|| >= ||r2
/// q_j||`. So when `q_j` is the first convergent with `||r2 q_j|| < T`, every `d < q_j`
/// has `||r2 d|| >= ||r2 q_(j-1)|| >= T` and fails; when no convergent up to
/// `MAX_SQUARE_DEN` has it, every `d` up to there fails (the last one's successor is past
/// `MAX_SQUARE_DEN`, or `r2` is the last convergent itself, at distance 0).
fn first_candidate(r2: f64) -> Option<i64> {
    let Some((num, den)) = dyadic(r2) else {
        return Some(1);
    };
    let big_x = r2 * (MAX_SQUARE_DEN + 1) as f64;
    let t = 1.02e-9 * (1.0 + big_x) + 2.3e-16 * big_x;
    // `||r2 q|| < T` may hold (the float distance, exact but for one rounding, not above `t`).
    let near = |q: u128| {
        let r = q * num % den;
        r.min(den - r) as f64 / den as f64 <= t
    };
    let max_q = MAX_SQUARE_DEN as u128;
    // The fractional part x / y of r2 and the convergents' denominators q_(j-1), q_j.
    let (mut x, mut y) = (num % den, den);
    let (mut q0, mut q1) = (0u128, 1u128);
    loop {
        if near(q1) {
            return i64::try_from(q1).ok();
        }
        if x == 0 {
            return None;
        }
        let a = y / x;
        (x, y) = (y % x, x);
        let q2 = a * q1 + q0;
        if q2 > max_q {
            return None;
        }
        (q0, q1) = (q1, q2);
    }
}

/// `r2` as `(num, 2^k)` exactly, in lowest terms, for `0 < r2 < 1e11` with `1 <= k <= 64`
/// (so that `q num` and the partial quotients stay within 128 bits for `q <= 2^12`);
/// `None` otherwise (also for a whole `r2`).
fn dyadic(r2: f64) -> Option<(u128, u128)> {
    if !(r2 > 0.0 && r2 < 1e11) {
        return None;
    }
    let bits = r2.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i64;
    if exp == 0 {
        return None;
    }
    let mut m = (bits & ((1 << 52) - 1)) | (1 << 52);
    let mut k = 1075 - exp;
    if k <= 0 {
        return None;
    }
    let tz = i64::from(m.trailing_zeros()).min(k);
    m >>= tz;
    k -= tz;
    (1..=64).contains(&k).then(|| (u128::from(m), 1u128 << k))
}

/// `x.round()` (half away from zero) for `0 <= x < 2^52` (not `-0.0`), without the library
/// call: there the integer part is `x as i64` exactly, and `x` minus it is exact (Sterbenz),
/// so the result is the same float. [`single_angle`] rounds up to 4,096 multiples of a
/// squared amplitude per group, and a group that is not one angle tries them all (the
/// Jaco-style arm's `fk --jacobian`: 470,000 calls, 11 M instructions in the library's
/// `round`).
fn round_small(x: f64) -> f64 {
    let t = x as i64 as f64;
    if x - t >= 0.5 {
        t + 1.0
    } else {
        t
    }
}

fn whole_modes_of(x: &Scalar, join: bool) -> (Ctx, Vec<Mon>) {
    let mut ctx = Ctx::new(x);
    let Ok(terms) = x.terms() else {
        return (ctx, Vec::new());
    };
    let symbolic = |t: &crate::scalar::Term| t.mode.freq.iter().any(|(s, _)| !s.is_one());
    let joined: Vec<crate::scalar::Term>;
    let terms: &[crate::scalar::Term] =
        if join && terms.iter().any(|t| !t.mode.pi.is_zero() && symbolic(t)) {
            let mut groups: std::collections::BTreeMap<_, Vec<&crate::scalar::Term>> =
                std::collections::BTreeMap::new();
            for t in terms {
                groups.entry((&*t.mode.freq, &t.mono)).or_default().push(t);
            }
            let mut out = Vec::with_capacity(terms.len());
            for g in groups.values() {
                let one = (g.len() > 1 && g.iter().any(|t| !t.mode.pi.is_zero()) && symbolic(g[0]))
                    .then(|| single_angle(g))
                    .flatten();
                match one {
                    Some(t) => out.push(t),
                    None => out.extend(g.iter().map(|t| (*t).clone())),
                }
            }
            joined = out;
            &joined
        } else {
            terms
        };
    let mut mons: Vec<Mon> = terms
        .iter()
        .map(|t| {
            let mut m = base_mon(&ctx, t);
            if !t.mode.is_unit() {
                let id = ctx.intern(Angle::from_freq(&t.mode.freq, t.mode.pi).offset_reduced());
                m.atoms.push(atom(id, t.mode.sin));
            }
            m
        })
        .collect();
    if let Some(map) = ctx.renumber() {
        for m in &mut mons {
            remap(m, &map);
        }
    }
    (ctx, mons)
}

/// Flips an angle to a positive leading coefficient (`cos(-x) = cos x`, `sin(-x) = -sin x`);
/// true when it was flipped.
fn normalize(a: &mut Angle) -> bool {
    let flipped = if a.leading().map_or(a.pi.is_negative(), |k| k.is_negative()) {
        a.negate();
        true
    } else {
        false
    };
    a.reduce_offset();
    flipped
}

/// A part `coef * sym + pi * pi` (no symbol: a pure multiple of pi) with its interned,
/// normalized angle: `(id, negated)`.
type PartKey = (Option<Sym>, Small, Small, (u32, bool));

/// The id of the angle `coef * sym + pi * pi`, normalized, and whether normalizing negated it.
fn part_id(
    ctx: &mut Ctx,
    seen: &mut Vec<PartKey>,
    sym: Option<&Sym>,
    coef: Small,
    pi: Small,
) -> (u32, bool) {
    // The coefficients (reduced) by their words first, then the symbol: `Ratio`'s `==` is a
    // comparison by divisions, and unequal names cost a `memcmp`.
    let same = |a: &Small, b: &Small| a.numer() == b.numer() && a.denom() == b.denom();
    if let Some((_, _, _, r)) = seen
        .iter()
        .find(|(s, c, p, _)| same(c, &coef) && same(p, &pi) && s.as_ref() == sym)
    {
        return *r;
    }
    let mut a = match sym {
        Some(s) => Angle::from_freq(&[(s.clone(), coef)], pi),
        None => Angle::new(Vec::new(), Small::zero(), pi),
    };
    let flipped = normalize(&mut a);
    let r = (ctx.intern(a), flipped);
    // A short list: beyond it, parts are interned directly (the scan stays cheap).
    if seen.len() < 64 {
        seen.push((sym.cloned(), coef, pi, r));
    }
    r
}

/// The canonical form as monomials in single-symbol atoms: every mode is split with the
/// angle-sum formulas, `cos(a + b) = cos a cos b - sin a sin b`, so that recombination can
/// regroup the angles the way the expression is best read.
pub(crate) fn split_modes(x: &Scalar) -> (Ctx, Vec<Mon>) {
    split_modes_over(x, common_denominator)
}

/// [`split_modes`] with the coefficients summed as numerators over the denominator that `den`
/// gives for the terms, or as rationals when it gives none (the same monomials either way).
fn split_modes_over(
    x: &Scalar,
    den: fn(&[crate::scalar::Term]) -> Option<OverCommon>,
) -> (Ctx, Vec<Mon>) {
    let mut ctx = Ctx::new(x);
    let Ok(terms) = x.terms() else {
        return (ctx, Vec::new());
    };
    if terms.iter().all(|t| t.mode.is_unit()) {
        // Nothing to split (a polynomial in cos/sin placeholders, say): each term is its own
        // monomial, summed per cofactor and sorted as below, without the sums by atoms (a
        // hash map, its key and a copy of the cofactor per term).
        let mons = merge(terms.iter().map(|t| base_mon(&ctx, t)).collect());
        return (ctx, mons);
    }
    // First the parts of every mode, so the angle ids are final before expanding. The few
    // distinct parts are remembered by value, sparing an angle and a hash per repeat.
    let mut seen: Vec<PartKey> = Vec::new();
    let mut parts_of: Vec<Vec<(u32, bool)>> = Vec::with_capacity(terms.len());
    for t in terms {
        if t.mode.is_unit() {
            parts_of.push(Vec::new());
            continue;
        }
        // Each symbol's part is its own angle; a leftover pi part rides on the last one.
        let n = t.mode.freq.len();
        let mut parts: Vec<(u32, bool)> = Vec::with_capacity(n + 1);
        for (k, (s, c)) in t.mode.freq.iter().enumerate() {
            let pi = if k + 1 == n { t.mode.pi } else { Small::zero() };
            parts.push(part_id(&mut ctx, &mut seen, Some(s), *c, pi));
        }
        if n == 0 && !t.mode.pi.is_zero() {
            parts.push(part_id(&mut ctx, &mut seen, None, Small::zero(), t.mode.pi));
        }
        parts_of.push(parts);
    }
    if let Some(map) = ctx.renumber() {
        for parts in &mut parts_of {
            for (id, _) in parts.iter_mut() {
                *id = map[*id as usize];
            }
        }
    }
    let out = match den(terms) {
        Some((den, nums)) => {
            let sums = expansions(&ctx, terms, &parts_of, |k| nums[k]);
            sorted_monomials(sums, |n| fraction(n, den))
        }
        None => sorted_monomials(
            expansions(&ctx, terms, &parts_of, |k| terms[k].coef.clone()),
            |q| q,
        ),
    };
    (ctx, out)
}

/// [`monomials`] sorted by [`key_cmp`] (the keys are distinct: the order `merge` gives).
///
/// The cofactors of the groups are distinct, so the groups are sorted by them and each
/// group's monomials by their atoms, as packed keys ([`lex_key`]: integers that compare as
/// the atom lists do) when every product of the group was packed; a group with a product
/// that was not (more than eight atoms, or an id past 16 bits) is sorted by [`key_cmp`]. A
/// sort of every monomial by `key_cmp`, comparing cofactors and atom lists, was a tenth of
/// `split_modes` on the Jaco-style arm (1,152 monomials of six atoms a component).
fn sorted_monomials<V: Coef>(
    mut groups: Vec<(Cofactor, Sum<V>)>,
    value: impl Fn(V) -> Q,
) -> Vec<Mon> {
    groups.sort_unstable_by(|(a, _), (b, _)| a.0.cmp(&b.0).then_with(|| a.1.cmp(&b.1)));
    let mut out: Vec<Mon> = Vec::new();
    let mut keyed: Vec<(u128, V)> = Vec::new();
    for ((rad, syms), sum) in groups {
        if !sum.other.is_empty() {
            let from = out.len();
            out.extend(sum.into_terms().map(|(atoms, q)| Mon {
                q: value(q),
                rad,
                syms: syms.clone(),
                atoms,
            }));
            out[from..].sort_unstable_by(key_cmp);
            continue;
        }
        keyed.clear();
        keyed.extend(
            sum.packed
                .into_iter()
                .filter(|(_, q)| !q.is_zero())
                .map(|(k, q)| (lex_key(k), q)),
        );
        keyed.sort_unstable_by_key(|(k, _)| *k);
        out.extend(keyed.drain(..).map(|(k, q)| Mon {
            q: value(q),
            rad,
            syms: syms.clone(),
            atoms: unpack(lex_key(k)),
        }));
    }
    out
}

/// A packed key ([`pack`]: atom `k` in the 16 bits from `16 k`) with its eight 16-bit fields
/// in the reverse order, and back (its own inverse): the first atom in the top field, so
/// that these keys compare as the atom lists do (the first differing atom decides, each
/// stored as `atom + 1`; a list that ends first has a 0 there, so a prefix comes first).
fn lex_key(key: u128) -> u128 {
    // The bytes reversed (fields reversed, each field's two bytes swapped), then the bytes of
    // each field swapped back.
    let r = key.swap_bytes();
    const LOW: u128 = 0x00ff_00ff_00ff_00ff_00ff_00ff_00ff_00ff;
    (r >> 8) & LOW | (r & LOW) << 8
}

/// A monomial's cofactor `(rad, syms)`.
type Cofactor = (u64, Syms);

/// A denominator common to some coefficients and their numerators over it
/// ([`common_denominator`]).
type OverCommon = (i64, Vec<i128>);

/// The expansions of the terms of a split shape ([`split_modes`]; `parts_of` the parts of each
/// term's mode), summed per cofactor and keyed by the atoms, with the coefficient of term `k`
/// as `coef(k)`.
fn expansions<V: Coef>(
    ctx: &Ctx,
    terms: &[crate::scalar::Term],
    parts_of: &[Vec<(u32, bool)>],
    coef: impl Fn(usize) -> V,
) -> Vec<(Cofactor, Sum<V>)> {
    let mut group_of: FxMap<Cofactor, usize> = FxMap::default();
    let mut groups: Vec<(Cofactor, Sum<V>)> = Vec::new();
    let mut atoms = Vec::new();
    for (k, (t, parts)) in terms.iter().zip(parts_of).enumerate() {
        let base = base_mon(ctx, t);
        let cof = (base.rad, base.syms);
        let g = match group_of.get(&cof) {
            Some(&g) => g,
            None => {
                group_of.insert(cof.clone(), groups.len());
                groups.push((cof, Sum::default()));
                groups.len() - 1
            }
        };
        let sum = &mut groups[g].1;
        let q = coef(k);
        if t.mode.is_unit() {
            add_to(sum, &[], Some(0), &q, false);
            continue;
        }
        expand(parts, t.mode.sin, false, &mut atoms, Some(0), &q, sum);
    }
    groups
}

/// The nonzero sums of [`expansions`] as monomials (unordered), each coefficient made a
/// rational by `value`: the route [`sorted_monomials`] sorts as it goes, kept for its test.
#[cfg(test)]
fn monomials<V: Coef>(groups: Vec<(Cofactor, Sum<V>)>, value: impl Fn(V) -> Q) -> Vec<Mon> {
    let mut out: Vec<Mon> = Vec::new();
    for ((rad, syms), sum) in groups {
        out.extend(sum.into_terms().map(|(atoms, q)| Mon {
            q: value(q),
            rad,
            syms: syms.clone(),
            atoms,
        }));
    }
    out
}

/// A coefficient as a [`Sum`] adds it up: a rational ([`Q`]), or the numerator of a rational
/// over a denominator common to every coefficient of the sum (`i128`, see
/// [`common_denominator`]).
trait Coef: Clone {
    /// `self + (-1)^neg o`.
    fn add_signed(&mut self, o: &Self, neg: bool);
    /// `(-1)^neg self`.
    fn signed(&self, neg: bool) -> Self;
    fn is_zero(&self) -> bool;
}

impl Coef for Q {
    fn add_signed(&mut self, o: &Q, neg: bool) {
        *self += &o.signed(neg);
    }

    fn signed(&self, neg: bool) -> Q {
        if neg {
            -self
        } else {
            self.clone()
        }
    }

    fn is_zero(&self) -> bool {
        Q::is_zero(self)
    }
}

/// Exact: the numerators are those of [`common_denominator`], below 2^63 in size, and a sum adds
/// at most one per product of the expansion, far fewer than 2^63, so no sum leaves `i128`.
impl Coef for i128 {
    fn add_signed(&mut self, o: &i128, neg: bool) {
        *self += if neg { -*o } else { *o };
    }

    fn signed(&self, neg: bool) -> i128 {
        if neg {
            -*self
        } else {
            *self
        }
    }

    fn is_zero(&self) -> bool {
        *self == 0
    }
}

/// The least common denominator `D` of the coefficients of `terms` with their numerators over
/// it, when they are all small rationals and `D` and every numerator are machine words;
/// `None` otherwise.
///
/// Over it the sums of [`split_modes`] add machine integers, where adding rationals took a
/// gcd for each of the products that meet (the Jaco-style arm's `fk --jacobian`: 11,300
/// additions, 1.75 M instructions): the sum of `n_k / D` is `(sum n_k) / D`, made a reduced
/// rational once per monomial by [`fraction`], the same value in the same canonical form.
fn common_denominator(terms: &[crate::scalar::Term]) -> Option<OverCommon> {
    let mut den: i64 = 1;
    for t in terms {
        let Q::S(_, d) = t.coef else {
            return None;
        };
        let g = crate::scalar::q::gcd_u64(den as u64, d as u64) as i64;
        den = (den / g).checked_mul(d)?;
    }
    let nums = terms
        .iter()
        .map(|t| match t.coef {
            Q::S(n, d) => n.checked_mul(den / d).map(i128::from),
            Q::B(_) => None,
        })
        .collect::<Option<Vec<i128>>>()?;
    Some((den, nums))
}

/// The rational `n / den` (`den > 0`), reduced: the canonical form any rational arithmetic
/// gives.
fn fraction(n: i128, den: i64) -> Q {
    match i64::try_from(n) {
        Ok(n) => Q::new(n, den),
        Err(_) => Q::big(BigRational::new(BigInt::from(n), BigInt::from(den))),
    }
}

/// A sum of atom products with coefficients [`Coef`], keyed by the sorted atoms; short
/// products of small ids are keyed by one packed integer (16 bits an atom) to spare the
/// hashing and allocation of a vector key.
struct Sum<V> {
    packed: FxMap<u128, V>,
    other: FxMap<Atoms, V>,
}

impl<V> Default for Sum<V> {
    fn default() -> Sum<V> {
        Sum {
            packed: FxMap::default(),
            other: FxMap::default(),
        }
    }
}

/// `atoms` (sorted) packed 16 bits each as `atom + 1`, when there are at most 8, all below
/// `0xffff`; distinct lists give distinct keys.
fn pack(atoms: &[Atom]) -> Option<u128> {
    if atoms.len() > 8 {
        return None;
    }
    let mut key = 0u128;
    for (k, &a) in atoms.iter().enumerate() {
        if a >= 0xffff {
            return None;
        }
        key |= u128::from(a + 1) << (16 * k);
    }
    Some(key)
}

fn unpack(mut key: u128) -> Atoms {
    let mut atoms = Atoms::new();
    while key != 0 {
        atoms.push((key & 0xffff) as u32 - 1);
        key >>= 16;
    }
    atoms
}

impl<V: Coef> Sum<V> {
    /// The nonzero terms, in no particular order.
    fn into_terms(self) -> impl Iterator<Item = (Atoms, V)> {
        self.packed
            .into_iter()
            .map(|(k, q)| (unpack(k), q))
            .chain(self.other)
            .filter(|(_, q)| !q.is_zero())
    }
}

/// Adds `(-1)^neg q` to the coefficient of `atoms`; `key` is their packed key when it was
/// made as they came ([`pushed`]), else they are sorted and packed here when they can be.
fn add_to<V: Coef>(sum: &mut Sum<V>, atoms: &[Atom], key: Option<u128>, q: &V, neg: bool) {
    // Sorted in place on the stack (up to eight atoms), not in a new vector.
    let sorted;
    let (atoms, key) = match key {
        Some(key) => (atoms, Some(key)),
        None if atoms.is_sorted() => (atoms, pack(atoms)),
        None => {
            sorted = {
                let mut v = Atoms::from_slice(atoms);
                v.sort_unstable();
                v
            };
            (&sorted[..], pack(&sorted))
        }
    };
    if let Some(key) = key {
        match sum.packed.get_mut(&key) {
            Some(s) => s.add_signed(q, neg),
            None => {
                sum.packed.insert(key, q.signed(neg));
            }
        }
        return;
    }
    match sum.other.get_mut(atoms) {
        Some(s) => s.add_signed(q, neg),
        None => {
            sum.other.insert(Atoms::from_slice(atoms), q.signed(neg));
        }
    }
}

/// The packed key ([`pack`]) of `atoms` followed by `a`, from `key`, that of `atoms`, when
/// `a` comes after the last of them and fits: then the atoms are in order, and this is the
/// key [`pack`] gives them. `None` otherwise ([`add_to`] sorts and packs them itself). Made
/// one atom at a time as [`expand`] goes down, instead of a pass over every product's atoms
/// to check their order and another to pack them (the Jaco-style arm's `fk --jacobian`:
/// 15,000 products of six atoms).
fn pushed(key: Option<u128>, atoms: &[Atom], a: Atom) -> Option<u128> {
    let k = atoms.len();
    let in_order = atoms.last().is_none_or(|&last| last < a);
    key.filter(|_| k < 8 && a < 0xffff && in_order)
        .map(|key| key | u128::from(a + 1) << (16 * k))
}

/// Adds `(-1)^neg * q * atoms * trig(sum of parts)` expanded into products of single-part
/// atoms; a part is `(angle id, the angle was negated to normalize it)`. `key` is the packed
/// key of `atoms` as [`pushed`] makes it.
fn expand<V: Coef>(
    parts: &[(u32, bool)],
    sin: bool,
    neg: bool,
    atoms: &mut Vec<Atom>,
    key: Option<u128>,
    q: &V,
    out: &mut Sum<V>,
) {
    let Some((&(id, flipped), rest)) = parts.split_first() else {
        // trig(0): cos 0 = 1, sin 0 = 0.
        if !sin {
            add_to(out, atoms, key, q, neg);
        }
        return;
    };
    // An atom of this part with the sign it brings: sin(-x) = -sin x.
    let part = |s: bool, minus: bool| (atom(id, s), minus ^ (flipped && s));
    if rest.is_empty() {
        let (a, n) = part(sin, false);
        let key = pushed(key, atoms, a);
        atoms.push(a);
        add_to(out, atoms, key, q, neg ^ n);
        atoms.pop();
        return;
    }
    // cos(a + r) = cos a cos r - sin a sin r;  sin(a + r) = sin a cos r + cos a sin r.
    // Each branch: (atom is a sine, the branch is subtracted, trig of the rest is a sine).
    let branches = if sin {
        [(true, false, false), (false, false, true)]
    } else {
        [(false, false, false), (true, true, true)]
    };
    for (s, minus, rest_sin) in branches {
        let (a, n) = part(s, minus);
        let key = pushed(key, atoms, a);
        atoms.push(a);
        expand(rest, rest_sin, neg ^ n, atoms, key, q, out);
        atoms.pop();
    }
}

/// `a + sign * b` as a normalized angle (positive leading coefficient, and a pure multiple of
/// pi non-negative), with whether the normalization negated it; `None` for the zero angle.
pub(crate) fn angle_combine(a: &Angle, b: &Angle, sign: i64) -> Option<(Angle, bool)> {
    let terms = freq_combine(&a.terms, &b.terms, sign);
    let constant = a.constant + b.constant * Small::from_integer(sign);
    let pi = a.pi + b.pi * Small::from_integer(sign);
    if terms.is_empty() && constant.is_zero() && pi.is_zero() {
        return None;
    }
    let mut angle = Angle::new(terms, constant, pi);
    let flipped = normalize(&mut angle);
    Some((angle, flipped))
}

/// The rational gcd of the coefficients `qs` (positive), e.g. `1/4` for `3/4 x + 1/2 y`.
pub(crate) fn content_of<'a, I>(qs: I) -> Q
where
    I: Iterator<Item = &'a Q> + Clone,
{
    let (mut num, mut den) = (0u64, 1u64);
    for q in qs.clone() {
        let Q::S(n, d) = *q else {
            return content_i128(qs.clone()).unwrap_or_else(|| content_big(qs));
        };
        if num != 1 {
            num = num.gcd(&n.unsigned_abs());
        }
        if d != 1 {
            let Some(l) = (den / den.gcd(&(d as u64))).checked_mul(d as u64) else {
                return content_big(qs);
            };
            den = l;
        }
    }
    if num == 0 {
        return Q::ONE;
    }
    match (i64::try_from(num), i64::try_from(den)) {
        // In lowest terms already: a prime of every numerator divides no denominator (each
        // coefficient is in lowest terms), so none of their lcm.
        (Ok(n), Ok(d)) => Q::S(n, d),
        _ => content_big(qs),
    }
}

/// [`content_of`] of integers that fit in 128 bits (the coefficients of `(x + y + z)^80`
/// do), in machine arithmetic: each numerator enters as its remainder modulo the gcd so far
/// (`gcd(g, n) = gcd(g, n mod g)`), without a big integer built. `None` for a fraction or a
/// wider integer.
fn content_i128<'a>(qs: impl Iterator<Item = &'a Q>) -> Option<Q> {
    let mut g = 0u128;
    for q in qs {
        let n = int_i128(q)?.unsigned_abs();
        g = match g {
            0 => n,
            1 => 1,
            g => g.gcd(&(n % g)),
        };
    }
    Some(match g {
        0 => Q::ONE,
        g => q_of_i128(i128::try_from(g).ok()?),
    })
}

/// `q` as a 128-bit integer, when it is an integer that fits.
fn int_i128(q: &Q) -> Option<i128> {
    match q {
        Q::S(n, 1) => Some(i128::from(*n)),
        Q::S(..) => None,
        Q::B(b) if num_traits::One::is_one(b.denom()) => {
            num_traits::ToPrimitive::to_i128(b.numer())
        }
        Q::B(_) => None,
    }
}

/// The integer `n` (a machine word when it fits, as [`Q::big`] keeps it).
fn q_of_i128(n: i128) -> Q {
    match i64::try_from(n) {
        Ok(0) => Q::ZERO,
        Ok(s) if s != i64::MIN => Q::S(s, 1),
        _ => Q::big(BigRational::from_integer(BigInt::from(n))),
    }
}

/// [`content_of`] past machine words. The gcd of the numerators is kept in a machine word as
/// soon as it fits, and each further numerator `n` enters as `n mod g` (one pass over its
/// words): `gcd(g, n) = gcd(g, n mod g)`. A big-integer gcd per coefficient was 56% of the
/// instructions of the closed form of `(x + y + z)^60`.
fn content_big<'a>(qs: impl Iterator<Item = &'a Q>) -> Q {
    let mut small: Option<u64> = None;
    let mut num = BigInt::zero();
    let mut den = BigInt::from(1);
    for q in qs {
        // No allocation for a coefficient once the gcd is a machine word (the common case:
        // a power's coefficients share small factors): its numerator is read modulo the gcd
        // word by word, and a denominator of one (integer coefficients) is skipped.
        match q {
            Q::S(n, d) => {
                if *d != 1 {
                    den = den.lcm(&BigInt::from(*d));
                }
                match small {
                    Some(1) => {}
                    Some(g) => small = Some(g.gcd(&(n.unsigned_abs() % g))),
                    None => {
                        num = num.gcd(&BigInt::from(*n));
                        small =
                            num_traits::ToPrimitive::to_u64(num.magnitude()).filter(|g| *g != 0);
                    }
                }
            }
            Q::B(b) => {
                let d = b.denom();
                if !num_traits::One::is_one(d) && *d != den {
                    den = den.lcm(d);
                }
                match small {
                    Some(1) => {}
                    Some(g) => small = Some(g.gcd(&mod_word(b.numer().magnitude(), g))),
                    None => {
                        num = num.gcd(b.numer());
                        small =
                            num_traits::ToPrimitive::to_u64(num.magnitude()).filter(|g| *g != 0);
                    }
                }
            }
        }
    }
    let num = small.map_or(num, BigInt::from);
    if num.is_zero() {
        return Q::ONE;
    }
    Q::big(BigRational::new(num, den))
}

/// `n mod g` for `g > 0`, from the most significant word down, without allocating.
fn mod_word(n: &num_bigint::BigUint, g: u64) -> u64 {
    n.iter_u64_digits().rev().fold(0u64, |r, w| {
        ((u128::from(r) << 64 | u128::from(w)) % u128::from(g)) as u64
    })
}

/// `q / g` for a positive `g`.
pub(crate) fn div_q(q: &Q, g: &Q) -> Q {
    // Integers (a content divides each of its coefficients exactly) in machine arithmetic:
    // through the rational product each quotient took a 128-bit gcd, and past 64 bits two
    // big integers built for the divisor alone.
    if let (Some(a), Some(b)) = (int_i128(q), int_i128(g)) {
        if b != 0 && a % b == 0 {
            if let Some(z) = a.checked_div(b) {
                return q_of_i128(z);
            }
        }
    }
    if let Some(z) = div_exact(q, g) {
        return z;
    }
    match g {
        Q::S(n, d) => q * &Q::new(*d, *n),
        Q::B(b) => Q::big(q.to_big() / &**b),
    }
}

/// `q / g` by exact integer divisions when it is an integer: `g`'s numerator divides `q`'s and
/// `q`'s denominator divides `g`'s, always so for `g` the content of a list holding `q` (the
/// gcd of the numerators over the lcm of the denominators, [`content_of`]). `None` otherwise,
/// and for a small `q` (the machine-word path is cheap). Through a product of big rationals
/// each quotient took two big-integer gcds: 28% of the instructions of the closed form of
/// `(x + y + z)^60`.
fn div_exact(q: &Q, g: &Q) -> Option<Q> {
    let Q::B(b) = q else {
        return None;
    };
    let (gn, gd) = match g {
        Q::S(n, d) => (BigInt::from(*n), BigInt::from(*d)),
        Q::B(c) => (c.numer().clone(), c.denom().clone()),
    };
    if gn.is_zero() {
        return None;
    }
    let (a, r) = b.numer().div_rem(&gn);
    if !r.is_zero() {
        return None;
    }
    let (c, r) = gd.div_rem(b.denom());
    if !r.is_zero() {
        return None;
    }
    Some(Q::big(BigRational::from_integer(a * c)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigUint;

    /// A random coefficient: a small fraction, or (one in 16 each) one over a large power of
    /// two or of five (two of them have no common denominator within 64 bits), or a big
    /// integer.
    fn random_coefficient(below: &mut impl FnMut(u64) -> u64) -> Q {
        let sign = if below(2) == 0 { 1 } else { -1 };
        match below(16) {
            0 => Q::new(sign * (1 + below(9) as i64), 1 << (30 + below(30))),
            1 => Q::new(sign, 5i64.pow(20 + below(7) as u32)),
            2 => Q::big(BigRational::from_integer(
                BigInt::from(sign) << (64 + below(20) as usize),
            )),
            _ => Q::new(sign * (1 + below(12) as i64), 1 + below(12) as i64),
        }
    }

    /// `count` random sums of `c * l * trig(a . (q1, q2, q3, q4) + k pi / 5)`: `l` 1 or a
    /// length, the angle of up to four symbols with coefficients -1 to 2.
    fn random_sums(seed: u64, count: usize) -> Vec<Scalar> {
        let mut below = crate::testing::xorshift_below(seed);
        (0..count)
            .map(|_| {
                (0..1 + below(6)).fold(Scalar::int(0), |sum, _| {
                    let mut angle = Scalar::pi() * Scalar::from_q(Q::new(below(10) as i64, 5));
                    for j in 1..=4 {
                        let a = below(4) as i64 - 1;
                        angle = angle + Scalar::int(a) * Scalar::sym(&format!("q{j}"));
                    }
                    let trig = if below(2) == 0 {
                        angle.cos()
                    } else {
                        angle.sin()
                    };
                    let length = match below(3) {
                        0 => Scalar::int(1),
                        k => Scalar::sym(&format!("l{k}")),
                    };
                    sum + Scalar::from_q(random_coefficient(&mut below)) * length * trig
                })
            })
            .collect()
    }

    /// The split shape summed over a common denominator is the one summed as rationals
    /// (the same monomials, coefficients in the same canonical form), and its sum is the
    /// input exactly; both routes are taken (products of two random sums, so that the
    /// expansions meet).
    #[test]
    fn split_sums_over_a_common_denominator_are_the_rational_sums() {
        let sums = random_sums(0x5b11_7de0, 240);
        let (mut common, mut rational, mut met) = (0, 0, 0);
        for pair in sums.chunks(2) {
            let x = &pair[0] * &pair[1];
            let terms = x.terms().expect("a value");
            match common_denominator(terms) {
                Some(_) => common += 1,
                None => rational += 1,
            }
            let (ctx, mons) = split_modes(&x);
            let (_, by_rationals) = split_modes_over(&x, |_| None);
            assert_eq!(mons, by_rationals, "{x}");
            let products: usize = terms.iter().map(|t| 1 << t.mode.freq.len()).sum();
            met += usize::from(mons.len() < products / 2);
            let sum = mons.iter().fold(Scalar::int(0), |s, m| {
                s + crate::closed::factor::mon_expr(m).to_expr(&ctx).to_scalar()
            });
            assert_eq!(sum, x);
        }
        assert!(common > 20 && rational > 20, "{common} / {rational}");
        assert!(met > 10, "{met}");
    }

    /// `sorted_monomials` (groups by cofactor, each group's atoms by packed keys) against the
    /// route it replaced (kept here): `monomials`, then a sort of all by `key_cmp`. On the
    /// expansions of products of random sums, and on random sums of atom lists of up to ten
    /// atoms, some ids past 16 bits (unpacked products, sorted by `key_cmp`), some of them
    /// cancelling, over a few cofactors.
    #[test]
    fn monomials_sorted_by_group_and_packed_key_are_the_sorted_monomials() {
        let old = |groups: Vec<(Cofactor, Sum<Q>)>| {
            let mut out = monomials(groups, |q| q);
            out.sort_unstable_by(key_cmp);
            out
        };
        let sums = random_sums(0x0501_7ed0, 120);
        let mut compared = 0;
        for pair in sums.chunks(2) {
            let x = &pair[0] * &pair[1];
            let (_, mons) = split_modes(&x);
            let (_, by_rationals) = split_modes_over(&x, |_| None);
            assert_eq!(mons, by_rationals, "{x}");
            // The split shape as the old route sorted it, from the same expansions.
            let mut ctx = Ctx::new(&x);
            let terms = x.terms().expect("a value");
            let mut seen: Vec<PartKey> = Vec::new();
            let parts_of: Vec<Vec<(u32, bool)>> = terms
                .iter()
                .map(|t| {
                    let n = t.mode.freq.len();
                    let mut parts: Vec<(u32, bool)> = t
                        .mode
                        .freq
                        .iter()
                        .enumerate()
                        .map(|(k, (s, c))| {
                            let pi = if k + 1 == n { t.mode.pi } else { Small::zero() };
                            part_id(&mut ctx, &mut seen, Some(s), *c, pi)
                        })
                        .collect();
                    if n == 0 && !t.mode.pi.is_zero() {
                        parts.push(part_id(&mut ctx, &mut seen, None, Small::zero(), t.mode.pi));
                    }
                    parts
                })
                .collect();
            if let Some(map) = ctx.renumber() {
                let parts_of: Vec<Vec<(u32, bool)>> = parts_of
                    .iter()
                    .map(|p| p.iter().map(|(id, f)| (map[*id as usize], *f)).collect())
                    .collect();
                let want = old(expansions(&ctx, terms, &parts_of, |k| {
                    terms[k].coef.clone()
                }));
                assert_eq!(mons, want, "{x}");
                compared += 1;
            }
        }
        assert!(compared > 50, "{compared}");
        let mut below = crate::testing::xorshift_below(0x1e55_0e7e_0001);
        let (mut packed, mut other) = (0, 0);
        for _ in 0..400 {
            let make = |below: &mut dyn FnMut(u64) -> u64| {
                let mut groups: Vec<(Cofactor, Sum<Q>)> = Vec::new();
                for g in 0..1 + below(4) {
                    let syms: Syms = (0..below(3))
                        .map(|k| (k as u32, 1 + below(2) as u32))
                        .collect();
                    let mut sum = Sum::default();
                    let wide = below(4) == 0;
                    for _ in 0..1 + below(40) {
                        let len = below(if wide { 11 } else { 7 }) as usize;
                        let mut atoms: Vec<Atom> = (0..len)
                            .map(|_| {
                                if wide && below(8) == 0 {
                                    0xfff0 + below(40) as u32
                                } else {
                                    below(12) as u32
                                }
                            })
                            .collect();
                        atoms.sort_unstable();
                        let q = Q::new(below(5) as i64 - 2, 1 + below(3) as i64);
                        add_to(&mut sum, &atoms, None, &q, below(2) == 0);
                    }
                    groups.push(((1 + g % 2, syms), sum));
                }
                // Distinct cofactors, as `expansions` makes them.
                let mut seen: Vec<Cofactor> = Vec::new();
                groups.retain(|(c, _)| {
                    let new = !seen.contains(c);
                    seen.push(c.clone());
                    new
                });
                groups
            };
            let seed = below(u64::MAX);
            let mut a = crate::testing::xorshift_below(seed);
            let mut b = crate::testing::xorshift_below(seed);
            let (x, y) = (make(&mut a), make(&mut b));
            packed += x.iter().filter(|(_, s)| s.other.is_empty()).count();
            other += x.iter().filter(|(_, s)| !s.other.is_empty()).count();
            assert_eq!(sorted_monomials(x, |q| q), old(y));
        }
        assert!(packed > 300 && other > 50, "{packed} packed, {other} other");
    }

    /// `round_small` is `f64::round` bit for bit below 2^52: on integers and halves, next to
    /// them, and on random multiples like those `single_angle` rounds.
    #[test]
    fn rounding_without_the_library_call_is_f64_round() {
        let mut below = crate::testing::xorshift_below(0x000b_0a7d);
        let mut xs: Vec<f64> = vec![0.0, 0.5, 1.5, 2.5, 0.49999999999999994, 4.4e15];
        for k in 0..2000u64 {
            let h = k as f64 / 2.0;
            xs.extend([
                h,
                f64::from_bits(h.to_bits() + 1),
                f64::from_bits(h.to_bits().max(1) - 1),
            ]);
            let r2 = below(1 << 40) as f64 / (1 + below(1 << 20)) as f64;
            xs.push(r2 * (1 + below(4096)) as f64);
        }
        for x in xs {
            assert_eq!(round_small(x).to_bits(), x.round().to_bits(), "{x:e}");
        }
    }

    /// The scan from [`first_candidate`] finds what the scan from 1 finds, on squared
    /// amplitudes like [`single_angle`]'s (sums of rational multiples of square roots at
    /// multiples of pi/36, pi/5 and pi/9), on random floats, on small fractions (found at
    /// their denominator) and on near-misses of them; and it begins past 1 on most of them.
    #[test]
    fn the_square_scan_from_its_first_candidate_finds_what_the_full_scan_finds() {
        let mut below = crate::testing::xorshift_below(0x5eed_0f2d);
        let mut r2s: Vec<f64> = vec![0.0, -1.0, 1e-30, 1e12, f64::NAN, 4.0, 0.25, 1.0 / 4096.0];
        for _ in 0..3000 {
            let mut wave = || {
                let root = [1.0f64, 2.0, 3.0, 5.0, 6.0][below(5) as usize].sqrt();
                let q = (below(8) as f64 + 1.0) / (below(64) as f64 + 1.0);
                let angle =
                    below(72) as f64 * std::f64::consts::PI / [36.0, 5.0, 9.0][below(3) as usize];
                (q * root * angle.cos(), q * root * angle.sin())
            };
            let ((a, b), (e, f)) = (wave(), wave());
            let (re, im) = (a + e, b + f);
            r2s.push(re * re + im * im);
            r2s.push(below(1 << 40) as f64 / (1 + below(1 << 30)) as f64);
            let (n, d) = (1 + below(5000) as i64, 1 + below(4096) as i64);
            let exact = n as f64 / d as f64;
            r2s.push(exact);
            r2s.push(exact * (1.0 + 1e-8 * (below(200) as f64 - 100.0)));
        }
        let mut later = 0;
        for &r2 in &r2s {
            let full = scan_from(r2, 1);
            assert_eq!(square_as_fraction(r2), full, "{r2:e}");
            later += usize::from(first_candidate(r2) != Some(1));
        }
        assert!(later > r2s.len() / 2, "{later} of {}", r2s.len());
    }

    /// Seeded random rationals of one to four words, some small, some integers.
    fn rationals(seed: u64, n: usize) -> Vec<BigRational> {
        let mut s = seed;
        let mut word = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        let common = BigInt::from(word() % 1000 + 1);
        (0..n)
            .map(|_| {
                let words = (word() % 4 + 1) as usize;
                let mut num = BigInt::from(word() % 97 + 1);
                for _ in 1..words {
                    num = (num << 64) + BigInt::from(word());
                }
                num *= &common;
                if word() % 3 == 0 {
                    num = -num;
                }
                let den = if word() % 2 == 0 {
                    BigInt::from(1)
                } else {
                    BigInt::from(word() % 50 + 1)
                };
                BigRational::new(num, den)
            })
            .collect()
    }

    #[test]
    fn content_and_exact_division_agree_with_big_rational_arithmetic() {
        for seed in 1..40u64 {
            let qs = rationals(seed * 0x9e37_79b9, 12);
            let list: Vec<Q> = qs.iter().cloned().map(Q::big).collect();
            // The content computed independently: gcd of the numerators over the lcm of the
            // denominators.
            let num = qs.iter().fold(BigInt::zero(), |g, q| g.gcd(q.numer()));
            let den = qs.iter().fold(BigInt::from(1), |l, q| l.lcm(q.denom()));
            let want = BigRational::new(num, den);
            let g = content_of(list.iter());
            assert_eq!(g.to_big(), want, "seed {seed}");
            for (q, big) in list.iter().zip(&qs) {
                // Each quotient an integer, equal to the big rationals' own division.
                let z = div_q(q, &g);
                assert_eq!(z.to_big(), big / &want, "seed {seed}");
                assert!(z.to_big().is_integer());
            }
            // Division by a value that is not the content: the general path, same values.
            let other = Q::big(BigRational::new(BigInt::from(7), BigInt::from(3)));
            for (q, big) in list.iter().zip(&qs) {
                assert_eq!(
                    div_q(q, &other).to_big(),
                    big * BigRational::new(3.into(), 7.into())
                );
            }
        }
    }

    /// Integers within 128 bits (the machine path of [`content_of`] and [`div_q`]), one in
    /// five lists with a wider one (the big path), against big-integer arithmetic; results in
    /// the canonical form [`Q::big`] gives (the derived `Eq` compares forms).
    #[test]
    fn content_and_division_of_128_bit_integers_agree_with_big_integers() {
        let mut s = 0x2545_f491_4f6c_dd1du64;
        let mut word = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        for case in 0..200u64 {
            let common = match case % 4 {
                0 => BigInt::from(1),
                1 => BigInt::from(word() % 1000 + 2),
                2 => BigInt::from(word() >> 1),
                _ => BigInt::from(u128::from(word()) << 40 | 3),
            };
            let qs: Vec<BigInt> = (0..9)
                .map(|k| {
                    let bits = word() % 120 + 1;
                    let mut n = BigInt::from(u128::from(word()) << 64 | u128::from(word()));
                    n >>= 128 - bits;
                    if n.is_zero() {
                        n = BigInt::from(1);
                    }
                    n *= &common;
                    if case % 5 == 4 && k == 3 {
                        n <<= 140;
                    }
                    if word() % 3 == 0 {
                        n = -n;
                    }
                    if case % 7 == 6 && k == 0 {
                        n = BigInt::from(i64::MIN);
                    }
                    n
                })
                .collect();
            let list: Vec<Q> = qs
                .iter()
                .cloned()
                .map(BigRational::from_integer)
                .map(Q::big)
                .collect();
            let want = qs.iter().fold(BigInt::zero(), |g, n| g.gcd(n));
            let g = content_of(list.iter());
            assert_eq!(
                g,
                Q::big(BigRational::from_integer(want.clone())),
                "case {case}"
            );
            for (q, n) in list.iter().zip(&qs) {
                let z = div_q(q, &g);
                assert_eq!(
                    z,
                    Q::big(BigRational::from_integer(n / &want)),
                    "case {case}"
                );
            }
        }
    }

    #[test]
    fn a_numerator_modulo_a_word_agrees_with_big_integer_remainder() {
        for (i, q) in rationals(7, 60).iter().enumerate() {
            let n: &BigUint = q.numer().magnitude();
            for g in [
                1u64,
                2,
                3,
                97,
                1 << 40,
                u64::MAX,
                0x1234_5678_9abc_def1 + i as u64,
            ] {
                let want = n % BigUint::from(g);
                assert_eq!(BigUint::from(mod_word(n, g)), want, "{n} mod {g}");
            }
        }
    }
}
