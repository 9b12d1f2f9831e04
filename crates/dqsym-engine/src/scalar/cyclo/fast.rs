//! The fast path: the canonical basis found modulo a prime and checked exactly, the
//! coordinates of every unit (a term without its rational coefficient) remembered, and a
//! group's coordinates summed from its units'.

use super::super::atoms::Small;
use super::super::modp::{self, ModSpan};
use super::super::par::{this_fork, PerFork};
use super::super::{FxHasher, ScalarError, Term, Q};
use super::candidates::{candidates, Candidate, Col};
use super::field::{field, ints_mul, Field, Ints};
use super::level::{level_of, level_primes, pi_exponent};
use super::{poisoned, terms_in_basis};
use std::cell::RefCell;
use std::collections::HashMap;
use std::hash::BuildHasherDefault;
use std::sync::{Arc, Mutex, OnceLock};

/// A term's value without its rational coefficient: `sqrt(h)` times `1`, `cos`, `sin` (real
/// groups) or `e^{ia}`, `-i e^{ia}` (complex groups) at `zeta_W^a`.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(super) struct Unit {
    pub(super) h: u64,
    pub(super) a: u64,
    pub(super) kind: u8,
}

pub(super) const UNIT_ONE: u8 = 0;
pub(super) const UNIT_COS: u8 = 1;
pub(super) const UNIT_SIN: u8 = 2;

impl Unit {
    /// The value, doubled: `sqrt(h)` (`roots`, [`Field::roots`]) times a trigonometric part of
    /// at most two terms, doubled coefficients `+-1`, `+-2` (`None` never: see
    /// [`ints_mul`]).
    fn value(&self, f: &Field, roots: &[super::field::Integral], real: bool) -> Option<Ints> {
        let (w, a) = (f.w, self.a);
        // Doubled coefficients, but not an `Ints`: unsorted for a sine, and one exponent twice
        // for `a = 0` (`ints_mul` sums them into its sorted product).
        let trig: Vec<(u64, i64)> = match (real, self.kind) {
            (true, UNIT_ONE) => vec![(0, 2)],
            // cos = (zeta^a + zeta^-a) / 2 (the two the same exponent for `a = 0`).
            (true, UNIT_COS) => vec![(a, 1), ((w - a) % w, 1)],
            // sin = -i (zeta^a - zeta^-a) / 2.
            (true, _) => {
                let q4 = 3 * w / 4;
                vec![((a + q4) % w, 1), ((w - a + q4) % w, -1)]
            }
            (false, UNIT_COS) => vec![(a, 2)],
            (false, _) => vec![((a + 3 * w / 4) % w, 2)],
        };
        let h = f.sqrts.binary_search_by_key(&self.h, |(x, _)| *x).ok()?;
        ints_mul(&roots[h], &trig, w)
    }
}

/// The exact coordinates of a vector over the columns of a [`FastBasis`] span: `(n, d)` for
/// `n / d` reduced, `d > 0` (small: read back from residues by [`modp::reconstruct`]).
pub(super) type Coords = Vec<(usize, (i64, i64))>;

/// The same as machine-word rationals where they fit (the form a group's sum is taken in).
pub(super) type QCoords = Vec<(usize, Q)>;

/// The most units a [`FastBasis`] keeps in its table by position (three kinds for every
/// square root and power of `zeta_W`); bigger fields keep them in a map.
pub(super) const DENSE_UNITS: usize = 1 << 16;

/// The basis of [`Basis`] (the same columns, in the same order) found modulo a prime and
/// checked exactly: every column taken is independent of the ones before modulo `P`, hence
/// over `Q`; every candidate left out was shown to depend on the ones before by exact
/// coordinates (small rationals read back from their residues, the combination checked in
/// `Q(zeta_W)`). The span is completed to the whole field (to its real subfield for real
/// bases, whose values are real), so every value has coordinates; a value is in the basis'
/// field when those past `cols` are zero.
pub(super) struct FastBasis {
    pub(super) cols: Vec<Col>,
    pub(super) span: ModSpan,
    /// The exact value of every span column (basis columns, then the completion).
    pub(super) vecs: Vec<Ints>,
    /// The units' coordinates by position ([`FastBasis::slot`]), each found once: one
    /// lookup per unit of every group, without a lock.
    pub(super) dense: Vec<OnceLock<Option<Arc<QCoords>>>>,
    /// The same for fields with more units than [`DENSE_UNITS`]. Keyed by three words:
    /// hashed by FxHash (SipHash's rounds were 2% of the Jaco-style arm's `fk --jacobian`).
    pub(super) units: Mutex<HashMap<Unit, Option<Arc<QCoords>>, BuildHasherDefault<FxHasher>>>,
}

impl FastBasis {
    /// `Ok(None)` when a check fails (the caller takes the exact path).
    fn new(f: &Field, m: u64, real: bool) -> Result<Option<FastBasis>, ScalarError> {
        let w = f.w;
        // Never `None` ([`Field::roots`]); the exact path would decide then.
        let Some(roots) = &f.roots else {
            return Ok(None);
        };
        let positions = f.sqrts.len() * w as usize * 3;
        let mut fb = FastBasis {
            cols: Vec::new(),
            span: ModSpan::new(),
            vecs: Vec::new(),
            dense: if positions <= DENSE_UNITS {
                (0..positions).map(|_| OnceLock::new()).collect()
            } else {
                Vec::new()
            },
            units: Mutex::new(HashMap::default()),
        };
        for Candidate { k, l, parts } in candidates(m, w, real) {
            let c = &parts[0];
            super::super::charge((fb.span.rank() * f.phi) as u64 / 256 + 1)?;
            if let Some(xs) = fb.span.solve(f.reduce_mod_ints(c)) {
                // Dependent modulo P: shown over Q, or the exact path decides.
                let Some(xs) = xs
                    .iter()
                    .enumerate()
                    .filter(|(_, x)| **x != 0)
                    .map(|(j, x)| modp::reconstruct(*x).map(|r| (j, r)))
                    .collect::<Option<Coords>>()
                else {
                    return Ok(None);
                };
                if f.combination_is_ints(&xs, &fb.vecs, c) != Some(true) {
                    return Ok(None);
                }
                continue;
            }
            for ((h, _), r) in f.sqrts.iter().zip(roots) {
                for (imag, x) in parts.iter().enumerate() {
                    let Some(n) = ints_mul(r, x, w) else {
                        return Ok(None);
                    };
                    if !fb.span.push(f.reduce_mod_ints(&n)) {
                        return Ok(None);
                    }
                    fb.vecs.push(n);
                    fb.cols.push(Col {
                        h: *h,
                        angle: Small::new(2 * k, l),
                        imag: imag == 1,
                    });
                }
            }
        }
        // Completed to the real subfield (real groups hold real values only) with
        // cos(2 pi j / W), or to the whole field with the coordinate vectors.
        let full = if real { f.phi / 2 } else { f.phi };
        let mut j = 0;
        while fb.span.rank() < full {
            if j >= f.phi.max(w as usize) {
                return Ok(None);
            }
            super::super::charge((fb.span.rank() * f.phi) as u64 / 256 + 1)?;
            let (v, val) = if real {
                // (zeta^e + zeta^-e) / 2, doubled, by increasing exponent.
                let (e, e2) = (j as u64, (w - j as u64) % w);
                let c = match e.cmp(&e2) {
                    std::cmp::Ordering::Equal => vec![(e, 2)],
                    std::cmp::Ordering::Less => vec![(e, 1), (e2, 1)],
                    std::cmp::Ordering::Greater => vec![(e2, 1), (e, 1)],
                };
                (f.reduce_mod_ints(&c), c)
            } else {
                let mut v = vec![0u64; f.phi];
                v[j] = 1;
                // The coordinate vector j is zeta_W^e for the exponent e in its slot.
                let pos = f.kept[j];
                let e = f.slot.iter().position(|s| *s == pos).expect("a slot") as u64;
                (v, vec![(e, 2)])
            };
            if fb.span.push(v) {
                fb.vecs.push(val);
            }
            j += 1;
        }
        Ok(Some(fb))
    }

    /// The position of a unit in [`FastBasis::dense`], when the table is kept.
    fn slot(&self, f: &Field, u: Unit) -> Option<usize> {
        if self.dense.is_empty() {
            return None;
        }
        let h = f.sqrts.binary_search_by_key(&u.h, |(x, _)| *x).ok()?;
        Some((h * f.w as usize + u.a as usize) * 3 + usize::from(u.kind))
    }

    /// The exact coordinates of a unit over the span (`None` when they cannot be shown).
    fn unit(&self, f: &Field, u: Unit, real: bool) -> Result<Option<Arc<QCoords>>, ScalarError> {
        let slot = self.slot(f, u);
        if let Some(c) = slot.and_then(|i| self.dense[i].get()) {
            return Ok(c.clone());
        }
        if slot.is_none() {
            if let Some(c) = self.units.lock().map_err(poisoned)?.get(&u) {
                return Ok(c.clone());
            }
        }
        let xs = self.unit_coords(f, u, real)?;
        match slot {
            // Another thread may have set it meanwhile, to the same value.
            Some(i) => Ok(self.dense[i].get_or_init(|| xs).clone()),
            None => {
                self.units.lock().map_err(poisoned)?.insert(u, xs.clone());
                Ok(xs)
            }
        }
    }

    /// [`FastBasis::unit`] computed: residues solved modulo `P`, read back as rationals and
    /// checked exactly.
    fn unit_coords(
        &self,
        f: &Field,
        u: Unit,
        real: bool,
    ) -> Result<Option<Arc<QCoords>>, ScalarError> {
        super::super::charge((f.phi * f.phi) as u64 / 256 + 1)?;
        // Never `None`: a basis was made, so the roots are there ([`FastBasis::new`]), and
        // the value fits ([`Unit::value`]).
        let Some(t) = f.roots.as_ref().and_then(|roots| u.value(f, roots, real)) else {
            return Ok(None);
        };
        let xs = self
            .span
            .solve(f.reduce_mod_ints(&t))
            .and_then(|xs| {
                xs.iter()
                    .enumerate()
                    .filter(|(_, x)| **x != 0)
                    .map(|(j, x)| modp::reconstruct(*x).map(|r| (j, r)))
                    .collect::<Option<Coords>>()
            })
            .filter(|xs| f.combination_is_ints(xs, &self.vecs, &t) == Some(true))
            .map(|xs| Arc::new(xs.iter().map(|(j, (n, d))| (*j, Q::new(*n, *d))).collect()));
        Ok(xs)
    }
}

/// The [`FastBasis`] of `(W, M, real)`, computed once per process; `None` when its checks
/// failed (the exact [`Basis`] is used then). The ones a thread used are kept by the thread,
/// looked up without a lock.
pub(super) fn fast_basis(
    f: &Field,
    m: u64,
    real: bool,
) -> Result<Option<Arc<FastBasis>>, ScalarError> {
    type Local = HashMap<(u64, u64, bool), Option<Arc<FastBasis>>, BuildHasherDefault<FxHasher>>;
    thread_local! {
        // With the fork count it was filled at: a forked child empties it ([`PerFork`]).
        static LOCAL: RefCell<(u64, Local)> = RefCell::new((0, Local::default()));
    }
    let key = (f.w, m, real);
    if let Some(b) = LOCAL.with(|c| this_fork(&mut c.borrow_mut()).get(&key).cloned()) {
        return Ok(b);
    }
    let b = shared_fast_basis(f, m, real)?;
    LOCAL.with(|c| this_fork(&mut c.borrow_mut()).insert(key, b.clone()));
    Ok(b)
}

/// [`fast_basis`] from the process-wide cache.
pub(super) fn shared_fast_basis(
    f: &Field,
    m: u64,
    real: bool,
) -> Result<Option<Arc<FastBasis>>, ScalarError> {
    type FastCache = PerFork<Mutex<HashMap<(u64, u64, bool), Option<Arc<FastBasis>>>>>;
    static CACHE: FastCache = PerFork::new();
    let cache = CACHE.get_or(Default::default);
    let key = (f.w, m, real);
    if let Some(b) = cache.lock().map_err(poisoned)?.get(&key) {
        return Ok(b.clone());
    }
    let b = FastBasis::new(f, m, real)?.map(Arc::new);
    cache.lock().map_err(poisoned)?.insert(key, b.clone());
    Ok(b)
}

/// The work a group of `terms` terms in a field of degree `phi` is charged on the fast path,
/// besides the making of its bases and units (also a group found rewritten before:
/// `rewritten_before`).
pub(super) fn charge_group(terms: usize, phi: u64) -> Result<(), ScalarError> {
    super::super::charge(terms as u64 * phi / 128 + 1)
}

/// [`canonical_group_exact`] through the [`FastBasis`]es; `None` when one of their checks
/// failed.
pub(super) fn canonical_group_fast(g: &[&Term]) -> Result<Option<Vec<Term>>, ScalarError> {
    canonical_group_fast_at(g, level_of(g.iter().copied())?)
}

/// [`canonical_group_fast`] of a group whose level `w` (`level_of`, within the limit) the
/// caller found.
pub(super) fn canonical_group_fast_at(
    g: &[&Term],
    w: u64,
) -> Result<Option<Vec<Term>>, ScalarError> {
    let Some(first) = g.first() else {
        return Ok(Some(Vec::new()));
    };
    let real = first.mode.freq.is_empty();
    let (phi, primes) = level_primes(w);
    charge_group(g.len(), phi)?;
    let f = field(w)?;
    // Coefficients as `Q` (machine-word rationals until they overflow): the coordinates
    // are small rationals, and `BigRational`'s products and sums reduced by big-integer gcds
    // at every step (56% of the Jaco-style arm's `fk --jacobian` was spent in this function).
    // Each term is a unit (its value without the rational coefficient) of a class `s` of
    // square roots outside the field; a class's value is the sum of its units' coordinates
    // times their coefficients (units met twice are simply added twice).
    let mut units: Vec<(u64, Unit, &Q)> = g
        .iter()
        .map(|t| {
            let (s, h) = f.split(t.rad);
            let (a, kind) = if real && t.mode.is_unit() {
                (0, UNIT_ONE)
            } else {
                let kind = if t.mode.sin { UNIT_SIN } else { UNIT_COS };
                (pi_exponent(&t.mode.pi, w), kind)
            };
            (s, Unit { h, a, kind }, &t.coef)
        })
        .collect();
    units.sort_by_key(|(s, _, _)| *s);
    let classes: Vec<&[(u64, Unit, &Q)]> = units.chunk_by(|x, y| x.0 == y.0).collect();
    enum Fit {
        In(Vec<Vec<Q>>),
        Out,
        Unsure,
    }
    let fits = |m: u64| -> Result<Fit, ScalarError> {
        let Some(b) = fast_basis(&f, m, real)? else {
            return Ok(Fit::Unsure);
        };
        let mut sol = Vec::with_capacity(classes.len());
        for class in &classes {
            let mut x = vec![Q::ZERO; b.span.cols];
            for (_, u, q) in *class {
                let Some(cs) = b.unit(&f, *u, real)? else {
                    return Ok(Fit::Unsure);
                };
                for (j, c) in cs.iter() {
                    x[*j] += &(*q * c);
                }
            }
            if x[b.cols.len()..].iter().any(|v| !v.is_zero()) {
                return Ok(Fit::Out);
            }
            x.truncate(b.cols.len());
            sol.push(x);
        }
        Ok(Fit::In(sol))
    };
    let mut m = w;
    let mut sol = match fits(m)? {
        Fit::In(sol) => sol,
        Fit::Out | Fit::Unsure => return Ok(None),
    };
    'descend: loop {
        let Some(bm) = fast_basis(&f, m, real)? else {
            return Ok(None);
        };
        for &p in primes.iter().filter(|p| m.is_multiple_of(**p)) {
            let n = m / p;
            if !n.is_multiple_of(24) {
                continue;
            }
            // When the basis of level `n` is the first columns of level `m`'s (ninths: the
            // level-24 columns come first in the level-72 order), the coordinates at `m`
            // decide without a second solve: coordinates over a basis are unique, so the value
            // is in the span of those columns, `n`'s field, exactly when its coordinates past
            // them are zero, and they are then its coordinates at `n`.
            if let Some(bn) = fast_basis(&f, n, real)? {
                let k = bn.cols.len();
                if bm.cols.get(..k) == Some(&bn.cols[..]) {
                    if sol.iter().all(|x| x[k..].iter().all(Q::is_zero)) {
                        for x in &mut sol {
                            x.truncate(k);
                        }
                        m = n;
                        continue 'descend;
                    }
                    continue;
                }
            }
            match fits(n)? {
                Fit::In(s) => {
                    m = n;
                    sol = s;
                    continue 'descend;
                }
                Fit::Out => {}
                Fit::Unsure => return Ok(None),
            }
        }
        break;
    }
    let Some(b) = fast_basis(&f, m, real)? else {
        return Ok(None);
    };
    let classes: Vec<u64> = classes.iter().map(|c| c[0].0).collect();
    terms_in_basis(first, real, &classes, sol, &b.cols).map(Some)
}

#[cfg(test)]
mod tests {
    use super::super::exact::Basis;
    use super::super::field::{ints, mono, sparse_mul, Sparse};
    use super::super::level::totient;
    use super::*;
    use num_rational::BigRational as Rat;
    use num_traits::{One, Zero};

    /// The route as it was, in `BigRational`, kept as the reference of the machine-word one:
    /// candidates and units as sparse sums with rational coefficients, reduced by
    /// `modp::from_rat`, coordinates read back as `BigRational`s and checked by the
    /// big-integer `combination_is`.
    mod big {
        use super::*;

        /// The old reconstruction (`modp::reconstruct` returned a `BigRational`).
        fn reconstruct(a: u64) -> Option<Rat> {
            modp::reconstruct_big(a)
        }

        /// The candidates' parts as they were built (the angles and their order are the
        /// shared `candidates`').
        fn parts(k: i64, l: i64, w: u64, real: bool) -> Vec<Sparse> {
            if real {
                let a = k as u64 * (w / l as u64);
                let c = if a == 0 {
                    mono(0, Rat::one())
                } else {
                    let half = Rat::new(1.into(), 2.into());
                    let mut s = mono(a, half.clone());
                    s.insert(w - a, half);
                    s
                };
                vec![c]
            } else {
                let a = (k.rem_euclid(l) as u64) * (w / l as u64);
                let c = mono(a, Rat::one());
                let ic = sparse_mul(&mono(w / 4, Rat::one()), &c, w);
                vec![c, ic]
            }
        }

        pub(super) struct Old {
            pub(super) cols: Vec<Col>,
            pub(super) span: ModSpan,
            pub(super) vecs: Vec<Ints>,
        }

        /// `FastBasis::new` as it was.
        pub(super) fn basis(f: &Field, m: u64, real: bool) -> Option<Old> {
            let w = f.w;
            let mut fb = Old {
                cols: Vec::new(),
                span: ModSpan::new(),
                vecs: Vec::new(),
            };
            for Candidate { k, l, .. } in candidates(m, w, real) {
                let parts = parts(k, l, w, real);
                let c = &parts[0];
                let v = f.reduce_mod(c)?;
                if let Some(xs) = fb.span.solve(v) {
                    let xs = xs
                        .iter()
                        .enumerate()
                        .filter(|(_, x)| **x != 0)
                        .map(|(j, x)| reconstruct(*x).map(|r| (j, r)))
                        .collect::<Option<Vec<(usize, Rat)>>>()?;
                    if f.combination_is(&xs, &fb.vecs, c) != Some(true) {
                        return None;
                    }
                    continue;
                }
                for (h, r) in &f.sqrts {
                    for (imag, x) in parts.iter().enumerate() {
                        let val = sparse_mul(r, x, w);
                        let (Some(v), Some(n)) = (f.reduce_mod(&val), ints(&val)) else {
                            return None;
                        };
                        if !fb.span.push(v) {
                            return None;
                        }
                        fb.vecs.push(n);
                        fb.cols.push(Col {
                            h: *h,
                            angle: Small::new(2 * k, l),
                            imag: imag == 1,
                        });
                    }
                }
            }
            let full = if real { f.phi / 2 } else { f.phi };
            let mut j = 0;
            while fb.span.rank() < full {
                if j >= f.phi.max(w as usize) {
                    return None;
                }
                let (v, val) = if real {
                    let e = j as u64;
                    let mut c = mono(e, Rat::new(1.into(), 2.into()));
                    *c.entry((w - e) % w).or_insert_with(Rat::zero) += Rat::new(1.into(), 2.into());
                    (f.reduce_mod(&c)?, ints(&c)?)
                } else {
                    let mut v = vec![0u64; f.phi];
                    v[j] = 1;
                    let pos = f.kept[j];
                    let e = f.slot.iter().position(|s| *s == pos).expect("a slot") as u64;
                    (v, vec![(e, 2)])
                };
                if fb.span.push(v) {
                    fb.vecs.push(val);
                }
                j += 1;
            }
            Some(fb)
        }

        /// `Unit::value` as it was.
        fn value(u: &Unit, f: &Field, real: bool) -> Sparse {
            let (w, a) = (f.w, u.a);
            let half = Rat::new(1.into(), 2.into());
            let trig = match (real, u.kind) {
                (true, UNIT_ONE) => mono(0, Rat::one()),
                (true, UNIT_COS) => {
                    let mut s = mono(a, half.clone());
                    *s.entry((w - a) % w).or_insert_with(Rat::zero) += half;
                    s
                }
                (true, _) => {
                    let q4 = 3 * w / 4;
                    let mut s = mono((a + q4) % w, half.clone());
                    *s.entry((w - a + q4) % w).or_insert_with(Rat::zero) -= half;
                    s
                }
                (false, UNIT_COS) => mono(a, Rat::one()),
                (false, _) => mono((a + 3 * w / 4) % w, Rat::one()),
            };
            let mut out = sparse_mul(f.sqrt(u.h), &trig, w);
            out.retain(|_, c| !c.is_zero());
            out
        }

        /// `FastBasis::unit_coords` as it was.
        pub(super) fn unit(b: &Old, f: &Field, u: Unit, real: bool) -> Option<QCoords> {
            let t = value(&u, f, real);
            f.reduce_mod(&t)
                .and_then(|v| b.span.solve(v))
                .and_then(|xs| {
                    xs.iter()
                        .enumerate()
                        .filter(|(_, x)| **x != 0)
                        .map(|(j, x)| reconstruct(*x).map(|r| (j, r)))
                        .collect::<Option<Vec<(usize, Rat)>>>()
                })
                .filter(|xs| f.combination_is(xs, &b.vecs, &t) == Some(true))
                .map(|xs| xs.iter().map(|(j, c)| (*j, Q::from(c))).collect())
        }
    }

    /// The machine-word basis is the `BigRational` one (columns, their exact values, the
    /// span's rank), and so are the coordinates of units (every unit of the smaller fields,
    /// a sample of the larger ones'), for every field of degree up to 96 and every subfield
    /// level, real and complex.
    #[test]
    fn machine_word_bases_and_units_are_the_big_ones() {
        let (mut bases, mut units, mut shown) = (0, 0, 0);
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for w in (24..=24 * 30).step_by(24) {
            if totient(w) > 96 {
                continue;
            }
            let f = Field::new(w).expect("field");
            for m in (24..=w).step_by(24).filter(|m| w.is_multiple_of(*m)) {
                for real in [true, false] {
                    let fast = FastBasis::new(&f, m, real)
                        .expect("budget")
                        .expect("checked");
                    let old = big::basis(&f, m, real).expect("checked");
                    assert_eq!(key(&fast.cols), key(&old.cols), "W = {w}, M = {m}, {real}");
                    assert_eq!(fast.vecs, old.vecs, "W = {w}, M = {m}, {real}");
                    assert_eq!(fast.span.rank(), old.span.rank());
                    bases += 1;
                    let all = f.sqrts.len() * w as usize * 3;
                    for i in 0..all.min(600) {
                        let i = if all <= 600 { i } else { next() as usize % all };
                        let (h, a, kind) = (
                            f.sqrts[i / (3 * w as usize)].0,
                            (i / 3) as u64 % w,
                            (i % 3) as u8,
                        );
                        let u = Unit { h, a, kind };
                        let new = fast.unit_coords(&f, u, real).expect("budget");
                        let new = new.map(|c| c.as_ref().clone());
                        let reference = big::unit(&old, &f, u, real);
                        assert_eq!(new, reference, "W = {w}, M = {m}, {real}, {h} {a} {kind}");
                        units += 1;
                        shown += usize::from(new.is_some_and(|c| !c.is_empty()));
                    }
                }
            }
        }
        assert!(
            bases > 40 && units > 20_000 && shown > 10_000,
            "{bases} {units} {shown}"
        );
    }

    fn key(cols: &[Col]) -> Vec<(u64, Small, bool)> {
        cols.iter().map(|c| (c.h, c.angle, c.imag)).collect()
    }

    /// The basis found modulo a prime and checked is the exact dense one, column for column,
    /// for every field of degree up to 96 and every subfield level, real and complex.
    #[test]
    fn fast_bases_are_the_exact_bases() {
        let mut checked = 0;
        for w in (24..=24 * 30).step_by(24) {
            if totient(w) > 96 {
                continue;
            }
            let f = Field::new(w).expect("field");
            for m in (24..=w).step_by(24).filter(|m| w.is_multiple_of(*m)) {
                for real in [true, false] {
                    let fast = FastBasis::new(&f, m, real)
                        .expect("budget")
                        .expect("checked");
                    let exact = Basis::new(&f, m, real).expect("budget");
                    assert_eq!(
                        key(&fast.cols),
                        key(&exact.cols),
                        "W = {w}, M = {m}, {real}"
                    );
                    assert_eq!(fast.span.rank(), if real { f.phi / 2 } else { f.phi });
                    checked += 1;
                }
            }
        }
        assert!(checked > 40, "{checked}");
    }
}
