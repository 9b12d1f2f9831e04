//! Two candidates for sums whose short form is a product of sinusoids of mixed angles, or a sum
//! of a few such products (issue 33: what SymPy's `trigsimp` finds and the other candidates of
//! `alt.rs` miss):
//! - a sinusoid `cos(d.x + phi)` peeled off when its angle mixes symbols
//!   (`-sin(u1) cos(u1 + 2*u2 - pi/6)`, whose expansion is `cos(2*u1 + 2*u2 + pi/3)/2 +
//!   cos(2*u2 - 2*pi/3)/2`): in the exponential form `f = sum a_m e^{i m.x}` the factor is the
//!   binomial `e^{i(d.x + phi)} + e^{-i(d.x + phi)}`, so `d` is half the difference of the top
//!   exponent (for a generic direction) and another exponent of the support; `phi` a multiple of
//!   pi/24, tried in floats on the hyperplane where the factor vanishes; the factor then divided
//!   out exactly ([`divide`], a long division along `d`) and the cofactor given its own closed
//!   form, which peels the next factor;
//! - a sum split into parts that share no length monomial or no symbol, each part given its
//!   own closed form (`sin(p) sin(r/2 + u1) - k1 cos(u1) cos(2*u1 + w)`).
//!
//! Both are gated on the shape of the scalar (no term with a constant angle, at most
//! [`MAX_TERMS`] terms) and charge their work to the Context's budget; like every candidate of
//! `alt.rs` they are checked exactly and kept only when shorter.

use super::alt::{full_cost, mul, neg, trig};
use super::expr::Expr;
use crate::scalar::atoms::freq_combine;
use crate::scalar::{charge, Small, Sym, Term};
use crate::{Context, Scalar};
use num_traits::{One, Signed, ToPrimitive, Zero};

mod lines;

/// The most terms a scalar may have for these candidates: a product of four sinusoids at
/// offsets has up to 16, a sum of two products of three 8 (with radicals twice as many); the
/// long sums of a chain with 60-degree twists (the Jaco-style arm) are past it.
const MAX_TERMS: usize = 24;

/// The most sinusoid factors (directions and phases) divided out and recursed on per scalar.
const MAX_FACTORS: usize = 3;

/// The phases tried: multiples of pi/PHASES in `[0, pi)` (a factor is defined up to sign,
/// `cos(A + pi) = -cos(A)`).
const PHASES: i64 = 24;

/// The most parts a sum is split into.
const MAX_PARTS: usize = 6;

/// The candidates of this file for the canonical terms `t`, not yet checked against them;
/// only those whose cost (as [`full_cost`] counts it) may be below `bound`: each is made only
/// when a lower bound of its cost ([`least_cost`]) is.
pub(super) fn candidates(t: &[Term], bound: usize) -> Vec<Expr> {
    let mut out = Vec::new();
    // Optional candidates: made only while most of the budget is left, so that they never
    // turn a closed form the other candidates find into a budget error.
    if !may_nest()
        || t.len() < 2
        || t.len() > MAX_TERMS
        || t.iter().all(|u| u.mode.freq.is_empty())
        || t.iter()
            .any(|u| u.mode.freq.iter().any(|(s, _)| s.is_one()))
        || !small_modes(t)
        || unit_modes(t)
    {
        return out;
    }
    out.extend(split_sum(t, bound));
    out.extend(sinusoid_factors(t, bound));
    out
}

/// How many of this file's closed forms of a part or a cofactor are open on this thread: each
/// cofactor's closed form may peel the next factor (up to [`MAX_FACTORS`] deep), and the search
/// it starts reaches these candidates again through every other candidate (`cspoly`'s factors'
/// closed forms); past this depth they are not made, so the nesting stays bounded.
const MAX_NESTED: u32 = MAX_FACTORS as u32;

thread_local! {
    static NESTED: std::cell::Cell<u32> = const { std::cell::Cell::new(0) };
}

/// Whether a candidate that searches closed forms of parts (through [`nested_closed_form`])
/// may be made: below [`MAX_NESTED`]. What such a candidate spends is bounded by the nested
/// searches' own budgets ([`NESTED_SHARE`]), not by the budget left here: this test also
/// compared the work left with half of `Context::current().work_budget()`, which is the work
/// left itself (`current` gives the entered budget less the work used), so it never failed
/// (found in session 29; removed, no output changes). Making it a real half-budget test
/// (against `Context::entered`) would change forms once half the budget is used: not done
/// without measuring that.
pub(super) fn may_nest() -> bool {
    NESTED.with(|n| n.get()) < MAX_NESTED
}

/// The share of the budget left that one nested closed form may spend.
const NESTED_SHARE: u64 = 16;

/// `closed_form(x)` one level deeper in [`NESTED`], in a context of its own whose budget is
/// [`NESTED_SHARE`]-th of the work left, its work then charged to the caller's: a part's or a
/// cofactor's search starts every candidate again (measured: a 5-term sum of products at
/// `sqrt(5)` coefficients spent the whole default budget of 3,000,000 units in them), so a
/// candidate of this file spends about a sixteenth of what is left at most (`charge` counts a
/// unit before it checks the limit, so a nested search can pass its share by its last charge,
/// all of it charged to the caller's).
///
/// Its results are not remembered beyond the memo of one outermost search (`closed/mod.rs`'s
/// `Memo`, which serves a part asked for again within that search): measured on the `fk --jacobian`
/// reports of the 16 robots in examples/robots/, the Jaco-style arm and the symbolic 6R and 4R (one
/// thread), the same part seldom comes back in another outermost search. The Jaco-style arm's 38
/// nested searches are of 38 distinct scalars; of its 73 closed forms searched inside an outermost
/// search and not in its memo (8,809 of the report's 95,052 work units), 11 repeat one of another
/// search exactly (14 units) and 26 up to a rational factor (209 units, and `closed_form(c x)` need
/// not be `c closed_form(x)`); none is a pose entry. Over the 19 reports: 146 such searches (35,500
/// units), 36 repeating another's scalar exactly (39 units). A memo across the report (whose hits
/// would have to replay the work charged and the entries the per-search memo gained) would save at
/// most about 0.2% of the arm's work. Nor does the part of a scalar as given, shifted by its own
/// offsets, come back as a part of the shifted scalar's search: `prepared_unshifted` of offset-free
/// scalars inside nested closed forms remembered per outermost search (keyed by the scalar, the
/// nesting depth and `cspoly::nested_open`) saved 0.13 M of the arm's 119.02 M instructions.
pub(super) fn nested_closed_form(x: &Scalar) -> Result<Expr, crate::scalar::ScalarError> {
    let left = crate::scalar::work_left();
    NESTED.with(|n| n.set(n.get() + 1));
    let (e, used) = if left == u64::MAX {
        (super::closed_form(x), 0)
    } else {
        let sub = Context::current().with_work_budget(left / NESTED_SHARE);
        let entered = sub.enter();
        let e = super::closed_form(x);
        let used = entered.work_used();
        (e, used)
    };
    NESTED.with(|n| n.set(n.get() - 1));
    crate::scalar::charge(used)?;
    e
}

/// The bound on the numerators and denominators of the modes' coefficients these candidates
/// take: the long division multiplies and adds them in `i64` rationals (products of two, sums of
/// a few: far below `2^63` from `2^16`).
const SMALL_FREQ: i64 = 1 << 16;

/// Whether every mode's coefficients are within [`SMALL_FREQ`].
fn small_modes(t: &[Term]) -> bool {
    t.iter().all(|u| {
        u.mode
            .freq
            .iter()
            .all(|(_, k)| k.numer().abs() <= SMALL_FREQ && *k.denom() <= SMALL_FREQ)
    })
}

/// Whether every mode is a sum or difference of symbols at one common multiple `c` without a pi
/// offset, and no term has a radical (`q1/2 + q2/2 - q3/2`, the half-angle series of a chain
/// whose twists are multiples of pi/2: the PUMA's scalars): in `y = c x` the split shape's
/// single-angle atoms, regrouped by the angle-sum identities and factored, already find the
/// products of sinusoids (`c1 c23`), and these candidates are not made.
pub(super) fn unit_modes(t: &[Term]) -> bool {
    let mut step: Option<Small> = None;
    t.iter().all(|u| {
        u.mode.pi.is_zero()
            && u.rad == 1
            && u.mode.freq.iter().all(|(_, k)| {
                let k = k.abs();
                *step.get_or_insert(k) == k
            })
    })
}

/// A lower bound of the operations of any closed form of the terms `t`: the multiplications
/// by the symbols of the shortest monomial, and one call when some term has a mode, or two
/// calls and an operation when the modes have two or more frequencies (a single sinusoid
/// `R cos(F + phi)`, `cos(F)^2 = (1 + cos 2F)/2`, has one).
pub(super) fn least_cost(t: &[Term]) -> usize {
    let mono = t.iter().map(|u| u.mono.len()).min().unwrap_or(0);
    let mut freqs = t
        .iter()
        .filter(|u| !u.mode.freq.is_empty())
        .map(|u| &u.mode.freq);
    let calls = match freqs.next() {
        None => 0,
        Some(f) if freqs.all(|g| g == f) => 1,
        Some(_) => 3,
    };
    mono + calls
}

/// A term's coefficient, radical and monomial as a scalar (its mode dropped).
fn weight(t: &Term) -> Scalar {
    Scalar::from_terms_sorted(vec![Term {
        mode: crate::scalar::Mode::unit(),
        ..t.clone()
    }])
}

/// The scalar of some of the terms (a subsequence of canonical terms is canonical).
fn scalar_of(t: &[Term], pick: impl Fn(usize) -> bool) -> Scalar {
    Scalar::from_terms_sorted(
        t.iter()
            .enumerate()
            .filter(|(i, _)| pick(*i))
            .map(|(_, u)| u.clone())
            .collect(),
    )
}

/// The sum split into parts with distinct monomials, and within one monomial into parts whose
/// angles share no symbol (the constant terms of a monomial kept with its first part), each
/// part's closed form found on its own.
fn split_sum(t: &[Term], bound: usize) -> Option<Expr> {
    let part = parts(t);
    let n = part.iter().copied().max()? + 1;
    if !(2..=MAX_PARTS).contains(&n) {
        return None;
    }
    // The additions between the parts and each part's least cost.
    let least: usize = (n - 1)
        + (0..n)
            .map(|p| {
                let terms: Vec<Term> = (0..t.len())
                    .filter(|&i| part[i] == p)
                    .map(|i| t[i].clone())
                    .collect();
                least_cost(&terms)
            })
            .sum::<usize>();
    if least >= bound {
        return None;
    }
    charge(t.len() as u64).ok()?;
    // The parts in the order of their monomials (`l1 ... + l2 ... + l3 ...`), then of their terms.
    let mut order: Vec<usize> = (0..n).collect();
    let first = |p: usize| (0..t.len()).find(|&i| part[i] == p).unwrap_or(0);
    order.sort_by(|&a, &b| {
        t[first(a)]
            .mono
            .iter()
            .cmp(t[first(b)].mono.iter())
            .then(first(a).cmp(&first(b)))
    });
    let mut sum = Vec::with_capacity(n);
    for p in order {
        let x = scalar_of(t, |i| part[i] == p);
        let e = nested_closed_form(&x).ok()?;
        match e {
            Expr::Add(v) => sum.extend(v),
            e => sum.push(e),
        }
    }
    Some(Expr::Add(sum))
}

/// The part of each term: terms of one monomial whose symbols connect (union-find over the
/// terms: two join when they share a monomial and a symbol; a radical does not part them,
/// `sqrt(3) cos(x) + sin(x)` is one sinusoid), the constant terms with the monomial's first
/// part.
fn parts(t: &[Term]) -> Vec<usize> {
    let mut up: Vec<usize> = (0..t.len()).collect();
    fn root(up: &mut [usize], mut i: usize) -> usize {
        while up[i] != i {
            up[i] = up[up[i]];
            i = up[i];
        }
        i
    }
    let shares = |a: &Term, b: &Term| {
        a.mode
            .freq
            .iter()
            .any(|(s, _)| b.mode.freq.iter().any(|(r, _)| r == s))
    };
    for i in 0..t.len() {
        for j in 0..i {
            if t[i].mono == t[j].mono && shares(&t[i], &t[j]) {
                let (a, b) = (root(&mut up, i), root(&mut up, j));
                up[a.max(b)] = a.min(b);
            }
        }
    }
    // A constant term joins the first term of its monomial with a mode (joining every part
    // would join the parts).
    for i in 0..t.len() {
        if t[i].mode.freq.is_empty() {
            if let Some(j) =
                (0..t.len()).find(|&j| !t[j].mode.freq.is_empty() && t[j].mono == t[i].mono)
            {
                let (a, b) = (root(&mut up, i), root(&mut up, j));
                up[a.max(b)] = a.min(b);
            }
        }
    }
    let mut ids: Vec<usize> = Vec::new();
    (0..t.len())
        .map(|i| {
            let r = root(&mut up, i);
            match ids.iter().position(|&x| x == r) {
                Some(p) => p,
                None => {
                    ids.push(r);
                    ids.len() - 1
                }
            }
        })
        .collect()
}

/// One term in floats over the symbols of the modes: `amp cos(f.x + phase)`.
struct Wave {
    f: Vec<f64>,
    phase: f64,
    amp: f64,
}

fn value(ws: &[Wave], x: &[f64]) -> f64 {
    ws.iter()
        .map(|w| {
            let a: f64 = w.f.iter().zip(x).map(|(f, x)| f * x).sum();
            w.amp * (a + w.phase).cos()
        })
        .sum()
}

/// A small pseudo-random generator of points (the search is deterministic).
struct Points(u64);

impl Points {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        0.3 + 1.4 * (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn point(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.next()).collect()
    }
}

/// The sinusoid factors `cos(d.x + phi)` of the sum (see the module doc), each divided out and
/// its cofactor given its closed form.
fn sinusoid_factors(t: &[Term], bound: usize) -> Vec<Expr> {
    // A factor of mixed angle costs a call and an operation in its angle, one multiplication
    // joins it to its cofactor, which has a call at least.
    if 4 + t.iter().map(|u| u.mono.len()).min().unwrap_or(0) >= bound {
        return Vec::new();
    }
    let (syms, exps) = exponents(t);
    let n = syms.len();
    if n == 0 {
        return Vec::new();
    }
    let Some(ws) = waves(t, &exps) else {
        return Vec::new();
    };
    let found = find_factors(&exps, &ws, n);
    let mut out = Vec::new();
    let x = Scalar::from_terms_sorted(t.to_vec());
    for (d, k) in found.into_iter().take(MAX_FACTORS) {
        let freq: Vec<(Sym, Small)> = syms
            .iter()
            .cloned()
            .zip(d)
            .filter(|(_, k)| !k.is_zero())
            .collect();
        let phi = Small::new(k, PHASES);
        let shown = shown_factor(&freq, phi);
        let Some(q) = divide(&x, &freq, phi) else {
            continue;
        };
        let Ok(qt) = q.terms() else {
            continue;
        };
        if full_cost(&shown).0 + 1 + least_cost(qt) >= bound {
            continue;
        }
        let Ok(qe) = nested_closed_form(&q) else {
            continue;
        };
        out.push(mul(shown, qe));
    }
    out
}

/// The symbols of the terms' modes, sorted, and each term's exponent: its mode's coefficient
/// of each symbol.
fn exponents(t: &[Term]) -> (Vec<Sym>, Vec<Vec<Small>>) {
    let mut syms: Vec<Sym> = Vec::new();
    for u in t {
        for (s, _) in u.mode.freq.iter() {
            if !syms.contains(s) {
                syms.push(s.clone());
            }
        }
    }
    syms.sort();
    let exps: Vec<Vec<Small>> = t
        .iter()
        .map(|u| {
            syms.iter()
                .map(|s| {
                    u.mode
                        .freq
                        .iter()
                        .find(|(r, _)| r == s)
                        .map_or(Small::zero(), |(_, k)| *k)
                })
                .collect()
        })
        .collect();
    (syms, exps)
}

/// The terms as waves at a fixed point of the length symbols; `None` past `f64`.
fn waves(t: &[Term], exps: &[Vec<Small>]) -> Option<Vec<Wave>> {
    let pi = std::f64::consts::PI;
    t.iter()
        .zip(exps)
        .map(|(u, e)| {
            let mut amp = u.coef.to_f64()? * (u.rad as f64).sqrt();
            for (s, p) in u.mono.iter() {
                amp *= super::point_value(s, 0x5851_f42d_4c95_7f2d).powi(i32::try_from(*p).ok()?);
            }
            let off = *u.mode.pi.numer() as f64 / *u.mode.pi.denom() as f64;
            Some(Wave {
                f: e.iter().map(|k| k.to_f64().unwrap_or(0.0)).collect(),
                phase: pi * off - if u.mode.sin { pi / 2.0 } else { 0.0 },
                amp,
            })
        })
        .collect()
}

/// Each exponent's position along a generic direction (tilted by `tilt`), from the exponents
/// in f64 ([`floats`]): the top one is a vertex of the Newton polytope of the exponents `+-m`.
fn along(floats: &[Vec<f64>], n: usize, tilt: f64) -> Vec<f64> {
    let generic: Vec<f64> = (0..n)
        .map(|i| 1.0 + tilt * (i as f64 + 1.0).sqrt())
        .collect();
    floats
        .iter()
        .map(|e| e.iter().zip(&generic).map(|(k, g)| k * g).sum())
        .collect()
}

/// The exponents in f64 (0 where one does not fit), converted once for both tilts of
/// [`along`].
fn floats(signed: &[Vec<Small>]) -> Vec<Vec<f64>> {
    signed
        .iter()
        .map(|e| e.iter().map(|k| k.to_f64().unwrap_or(0.0)).collect())
        .collect()
}

/// The differences between the top exponent by `along` (the last of equal ones) and every
/// other exponent, first nonzero entry positive, sorted and without repeats: twice the
/// directions. Generic so that the exponents may be integers over one common denominator
/// (the order and the equality of such vectors are those of the rationals they stand for,
/// compared without the gcds and divisions of rationals).
fn differences<T>(signed: &[Vec<T>], along: &[f64]) -> Vec<Vec<T>>
where
    T: Ord + Clone + Zero + std::ops::Sub<Output = T> + std::ops::Neg<Output = T>,
{
    let Some(top) = (0..signed.len()).max_by(|&a, &b| along[a].total_cmp(&along[b])) else {
        return Vec::new();
    };
    let top = &signed[top];
    let mut dirs: Vec<Vec<T>> = Vec::new();
    for e in signed {
        let mut d: Vec<T> = top
            .iter()
            .zip(e)
            .map(|(a, b)| a.clone() - b.clone())
            .collect();
        let Some(first) = d.iter().find(|k| !k.is_zero()) else {
            continue;
        };
        if *first < T::zero() {
            d.iter_mut().for_each(|k| *k = -k.clone());
        }
        dirs.push(d);
    }
    dirs.sort_unstable();
    dirs.dedup();
    dirs
}

/// Twice the directions tried (see [`find_factors`]): those seen from the vertices `first`
/// and `second` (each by [`along`]), mixing two or more symbols, in sorted order.
fn twice_the_directions<T>(signed: &[Vec<T>], first: &[f64], second: &[f64]) -> Vec<Vec<T>>
where
    T: Ord + Clone + Zero + std::ops::Sub<Output = T> + std::ops::Neg<Output = T>,
{
    let first = differences(signed, first);
    differences(signed, second)
        .into_iter()
        .filter(|d| {
            d.iter().filter(|k| !k.is_zero()).count() >= 2 && first.binary_search(d).is_ok()
        })
        .collect()
}

/// The exponents as integers over one common denominator `L`, each within `2^61` in absolute
/// value (so that their differences fit an `i64`), `L` within `2^46` (so that `2 L` does);
/// `None` past those bounds.
fn integer_exponents(signed: &[Vec<Small>]) -> Option<(Vec<Vec<i64>>, i64)> {
    let l = super::offsets::common_denominator(signed.iter().flatten())?;
    if l > 1 << 46 {
        return None;
    }
    let ints = signed
        .iter()
        .map(|e| {
            e.iter()
                .map(|k| {
                    let v = k.numer().checked_mul(l / k.denom())?;
                    (v.unsigned_abs() <= 1 << 61).then_some(v)
                })
                .collect::<Option<Vec<i64>>>()
        })
        .collect::<Option<Vec<_>>>()?;
    Some((ints, l))
}

/// The directions tried (see [`find_factors`]), halves of [`twice_the_directions`]: in
/// integers over a common denominator `L` when they fit (each `D / (2 L)` is then the
/// rational `(a - b) / 2` itself, and the order the same), in rationals otherwise.
#[cfg(test)]
fn directions(signed: &[Vec<Small>], n: usize) -> Vec<Vec<Small>> {
    directions_in(signed, n, integer_exponents(signed).as_ref())
}

/// [`directions`] with the exponents' [`integer_exponents`], computed once for it and the
/// screen of [`lines`].
fn directions_in(
    signed: &[Vec<Small>],
    n: usize,
    ints: Option<&(Vec<Vec<i64>>, i64)>,
) -> Vec<Vec<Small>> {
    let f = floats(signed);
    let (first, second) = (along(&f, n, 0.313_7), along(&f, n, -0.561_3));
    match ints {
        Some((ints, l)) => twice_the_directions(ints, &first, &second)
            .into_iter()
            .map(|d| d.into_iter().map(|k| Small::new(k, 2 * l)).collect())
            .collect(),
        None => {
            let two = Small::from_integer(2);
            twice_the_directions(signed, &first, &second)
                .into_iter()
                .map(|d| d.into_iter().map(|k| k / two).collect())
                .collect()
        }
    }
}

/// The directions `d` (first nonzero entry positive) and phases `k` (`phi = k pi/PHASES`) at
/// which the sum vanishes on the hyperplane `d.x + phi = pi/2` at three points; a direction
/// along which no phase's plane can be a zero set of the sum ([`lines`]) is not evaluated.
fn find_factors(exps: &[Vec<Small>], ws: &[Wave], n: usize) -> Vec<(Vec<Small>, i64)> {
    let signed: Vec<Vec<Small>> = exps
        .iter()
        .flat_map(|e| [e.clone(), e.iter().map(|k| -*k).collect()])
        .collect();
    // A factor's direction shows from every vertex of the Newton polytope (unless terms
    // cancel there): only directions seen from two vertices are tried, and only those mixing
    // two or more symbols (one symbol's factors are `roots.rs`'s).
    let ints = integer_exponents(&signed);
    let dirs = directions_in(&signed, n, ints.as_ref());
    let lines = lines::Lines::new(ints.as_ref(), ws);
    // The sum is evaluated to a relative error of about (terms) * 1e-16 times the largest
    // angle (below 100 here: coefficients of a few units at points below 2); a factor's zero
    // shows as well below 1e-9 of the sum of the magnitudes, a nonzero value at a generic point
    // as far above it (a false zero is then caught by the exact division).
    let scale: f64 = ws.iter().map(|w| w.amp.abs()).sum();
    let tol = 1e-9 * scale;
    let mut pts = Points(0x2545_f491_4f6c_dd1d);
    let bases: Vec<Vec<f64>> = (0..3).map(|_| pts.point(n)).collect();
    let mut found = Vec::new();
    for d in dirs {
        if charge((ws.len() as u64 * PHASES as u64) / 8 + 1).is_err() {
            break;
        }
        // No phase of a direction along which an exponent is alone on its line can carry a
        // factor (proof in `lines.rs`); its charge above is kept, so that the budget is spent
        // as before. Only a false zero of the float test there (see `lines.rs`) was listed
        // before and is not now: its division's charge and its place among the first
        // `MAX_FACTORS` entries go with it.
        if lines.as_ref().is_some_and(|l| l.lonely_along(&d)) {
            continue;
        }
        let df: Vec<f64> = d.iter().map(|k| k.to_f64().unwrap_or(0.0)).collect();
        let dd: f64 = df.iter().map(|k| k * k).sum();
        let surely = surely_above(ws, &bases[0], &df, dd, tol);
        for (k, surely) in (0..PHASES).zip(surely) {
            if !surely
                && bases
                    .iter()
                    .all(|b| value(ws, &on_plane(b, &df, dd, k)).abs() <= tol)
            {
                found.push((d.clone(), k));
            }
        }
    }
    found
}

/// The point `base + s d` on the plane `d.x + k pi/PHASES = pi/2` (`dd = d.d`).
fn on_plane(base: &[f64], df: &[f64], dd: f64, k: i64) -> Vec<f64> {
    let c = std::f64::consts::FRAC_PI_2 - k as f64 * std::f64::consts::PI / PHASES as f64;
    let s = (c - df.iter().zip(base).map(|(a, b)| a * b).sum::<f64>()) / dd;
    base.iter().zip(df).map(|(b, a)| b + s * a).collect()
}

/// For each phase `k`, whether the sum's value at the point of `base` on the plane of `k`
/// (`value(ws, on_plane(base, d, dd, k))` as [`find_factors`] computes it) is surely above
/// `tol` in absolute value: then that phase fails at its first point, and its cosine per wave
/// is not taken (most directions and phases fail there; those cosines were two fifths of
/// `sinusoid_factors` on the Jaco-style arm). Decided from the same values in another way: on
/// the plane of `k` the point is `base + s_k d` with `s_k = s_0 - k step`, so a wave's angle
/// is `theta_0 + k delta`, and `e^{i theta_k}` is rotated from phase to phase (a complex
/// product, no cosine).
///
/// Why sound: both ways compute each wave's angle from sums of at most `n + 3` products
/// whose magnitudes add up to at most `m` (the bound computed below: the products
/// `f_i b_i`, `s f_i d_i` with `|s| <= s_max`, the phase), so each angle is within about
/// `(n + 3) 2^-53 m` of the exact one; the rotation adds at most about `5 2^-53 (1 + |delta|)`
/// (`|delta| <= m`) per phase, 24 phases; the cosine and the sums over the waves a few units
/// in the last place of `scale` (the sum of the amplitudes), and cos is 1-Lipschitz. The two
/// values then differ by less than `scale (1e-9 + 1e-12 (n + 2 PHASES) (1 + m))`, which is
/// above that by a factor of 10^3 at least; a value above `tol` by more than it is one
/// [`value`] finds above `tol`. Anything not finite fails the comparison and the phase is
/// evaluated as before.
fn surely_above(ws: &[Wave], base: &[f64], df: &[f64], dd: f64, tol: f64) -> Vec<bool> {
    use std::f64::consts::{FRAC_PI_2, PI};
    let n = base.len() as f64;
    let scale: f64 = ws.iter().map(|w| w.amp.abs()).sum();
    let db: f64 = df.iter().zip(base).map(|(a, b)| a * b).sum();
    let db_abs: f64 = df.iter().zip(base).map(|(a, b)| (a * b).abs()).sum();
    let s0 = (FRAC_PI_2 - db) / dd;
    let step = PI / PHASES as f64 / dd;
    // |c_k| <= pi/2 for c_k = pi/2 - k pi/PHASES, k < PHASES: a bound of |s_k| and of the
    // magnitudes its sum adds.
    let s_max = (FRAC_PI_2 + db_abs) / dd;
    let mut m: f64 = 0.0;
    // Each wave's amp e^{i theta_k} and its rotation e^{i delta} from one phase to the next.
    let mut z: Vec<(f64, f64, f64, f64)> = Vec::with_capacity(ws.len());
    for w in ws {
        let fb: f64 = w.f.iter().zip(base).map(|(f, b)| f * b).sum();
        let fd: f64 = w.f.iter().zip(df).map(|(f, a)| f * a).sum();
        let fb_abs: f64 = w.f.iter().zip(base).map(|(f, b)| (f * b).abs()).sum();
        let fd_abs: f64 = w.f.iter().zip(df).map(|(f, a)| (f * a).abs()).sum();
        m = m.max(fb_abs + s_max * fd_abs + w.phase.abs());
        let (sin, cos) = (fb + w.phase + s0 * fd).sin_cos();
        let (rot_sin, rot_cos) = (-step * fd).sin_cos();
        z.push((w.amp * cos, w.amp * sin, rot_cos, rot_sin));
    }
    let margin = scale * (1e-9 + 1e-12 * (n + 2.0 * PHASES as f64) * (1.0 + m));
    (0..PHASES)
        .map(|_| {
            let v: f64 = z.iter().map(|z| z.0).sum();
            for (re, im, c, s) in z.iter_mut() {
                (*re, *im) = (*re * *c - *im * *s, *re * *s + *im * *c);
            }
            v.abs() > tol + margin
        })
        .collect()
}

/// `x / cos(d.x + phi)` when exact: a long division along `d`, each step taking the term
/// whose mode reaches furthest along `d` (`|m.d|` largest) as the product of the factor and a
/// term of the quotient; `None` when a remainder is left or the budget runs out.
fn divide(x: &Scalar, d: &[(Sym, Small)], phi: Small) -> Option<Scalar> {
    let factor = trig(false, d.to_vec(), phi).to_scalar();
    let dd: Small = d.iter().map(|(_, k)| *k * *k).sum();
    let dot = |f: &[(Sym, Small)]| -> Small {
        f.iter()
            .filter_map(|(s, k)| d.iter().find(|(r, _)| r == s).map(|(_, j)| *k * *j))
            .sum()
    };
    let mut rem = x.clone();
    let mut quot = Scalar::zero();
    let limit = 4 * x.len() + 8;
    for _ in 0..limit {
        let t = rem.terms().ok()?;
        if t.is_empty() {
            return Some(quot);
        }
        charge(t.len() as u64).ok()?;
        let (u, p) = t
            .iter()
            .map(|u| (u, dot(&u.mode.freq)))
            .max_by(|a, b| a.1.abs().cmp(&b.1.abs()))?;
        if p.abs() < dd {
            return None;
        }
        // Oriented so that the mode reaches along +d: cos(-A) = cos(A), sin(-A) = -sin(A).
        let (flip, sign) = if p.is_negative() {
            (-Small::one(), if u.mode.sin { -1 } else { 1 })
        } else {
            (Small::one(), 1)
        };
        let m: Vec<(Sym, Small)> = u
            .mode
            .freq
            .iter()
            .map(|(s, k)| (s.clone(), *k * flip))
            .collect();
        let rest: Vec<(Sym, Small)> = freq_combine(&m, d, -1);
        let h = weight(u)
            * Scalar::int(2 * sign)
            * trig(u.mode.sin, rest, u.mode.pi * flip - phi).to_scalar();
        rem = (&rem - &(&factor * &h)).check().ok()?;
        quot = (&quot + &h).check().ok()?;
    }
    None
}

/// `cos(d.x + phi)` shown the cheapest way: as a cosine or a sine, with either sign, the
/// offset reduced.
fn shown_factor(d: &[(Sym, Small)], phi: Small) -> Expr {
    let half = Small::new(1, 2);
    let centred = |p: Small| {
        let two = Small::from_integer(2);
        let mut p = p - (p / two).floor() * two;
        if p > Small::one() {
            p -= two;
        }
        p
    };
    // cos(A) = sin(A + pi/2) = -cos(A + pi) = -sin(A - pi/2).
    let options = [
        trig(false, d.to_vec(), centred(phi)),
        trig(true, d.to_vec(), centred(phi + half)),
        neg(trig(false, d.to_vec(), centred(phi + Small::one()))),
        neg(trig(true, d.to_vec(), centred(phi - half))),
    ];
    options
        .into_iter()
        .min_by_key(full_cost)
        .expect("four options")
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::BigRational;

    /// `surely_above` never says a phase is above the tolerance where `value` at its point is
    /// not: on seeded random sums of waves (whole and half frequencies, amplitudes of either
    /// sign) and sums with a factor `cos(d.x + k pi/24)` (the product's two waves), for every
    /// direction and phase; and it decides most phases (what it is for).
    #[test]
    fn a_phase_surely_above_the_tolerance_is_above_it() {
        let mut next = crate::testing::xorshift_below(0x50e1_ab0e_7010_0004);
        let mut unit = move || next(1 << 20) as f64 / (1u64 << 20) as f64;
        let (mut decided, mut phases, mut zeros) = (0usize, 0usize, 0usize);
        for round in 0..300 {
            let n = 2 + (unit() * 3.0) as usize;
            let freq = |u: f64| ((u * 9.0) as i64 - 4) as f64 / if u > 0.5 { 2.0 } else { 1.0 };
            let draw = |unit: &mut dyn FnMut() -> f64| -> Vec<f64> {
                (0..n).map(|_| freq(unit())).collect()
            };
            let d = draw(&mut unit);
            let mut ws: Vec<Wave> = Vec::new();
            if round % 2 == 0 {
                for _ in 0..2 + (unit() * 8.0) as usize {
                    ws.push(Wave {
                        f: draw(&mut unit),
                        phase: std::f64::consts::PI * unit() * 2.0,
                        amp: unit() * 4.0 - 2.0,
                    });
                }
            } else {
                // cos(d.x + phi) cos(g.x + psi) = (cos((d + g).x + phi + psi)
                // + cos((d - g).x + phi - psi)) / 2, phi = k pi/24.
                let g = draw(&mut unit);
                let phi = std::f64::consts::PI * (unit() * 24.0).floor() / 24.0;
                let (psi, amp) = (unit() * 6.0, unit() * 4.0 - 2.0);
                let sum: Vec<f64> = d.iter().zip(&g).map(|(a, b)| a + b).collect();
                let diff: Vec<f64> = d.iter().zip(&g).map(|(a, b)| a - b).collect();
                ws.push(Wave {
                    f: sum,
                    phase: phi + psi,
                    amp: amp / 2.0,
                });
                ws.push(Wave {
                    f: diff,
                    phase: phi - psi,
                    amp: amp / 2.0,
                });
            }
            let dd: f64 = d.iter().map(|k| k * k).sum();
            if dd == 0.0 {
                continue;
            }
            let scale: f64 = ws.iter().map(|w| w.amp.abs()).sum();
            let tol = 1e-9 * scale;
            let base: Vec<f64> = (0..n).map(|_| 0.3 + 1.4 * unit()).collect();
            for (k, surely) in (0..PHASES).zip(surely_above(&ws, &base, &d, dd, tol)) {
                let v = value(&ws, &on_plane(&base, &d, dd, k)).abs();
                phases += 1;
                zeros += usize::from(v <= tol);
                if surely {
                    decided += 1;
                    assert!(v > tol, "round {round}, phase {k}: {v} <= {tol}");
                }
            }
        }
        assert!(zeros > 50, "phases at a factor's zero were met ({zeros})");
        assert!(
            decided * 10 > phases * 8,
            "most phases decided ({decided} of {phases})"
        );
    }

    /// The directions as first written, the independent computation the test below compares
    /// with: halves of the differences in rationals from each vertex, sorted, those of the
    /// second vertex kept when they mix two symbols and are seen from the first.
    fn halved_directions(signed: &[Vec<Small>], n: usize) -> Vec<Vec<Small>> {
        let from = |tilt: f64| -> Vec<Vec<Small>> {
            let generic: Vec<f64> = (0..n)
                .map(|i| 1.0 + tilt * (i as f64 + 1.0).sqrt())
                .collect();
            let along = |e: &[Small]| -> f64 {
                e.iter()
                    .zip(&generic)
                    .map(|(k, g)| k.to_f64().unwrap_or(0.0) * g)
                    .sum()
            };
            let top = signed
                .iter()
                .max_by(|a, b| along(a).total_cmp(&along(b)))
                .expect("exponents");
            let two = Small::from_integer(2);
            let mut dirs: Vec<Vec<Small>> = Vec::new();
            for e in signed {
                let mut d: Vec<Small> = top.iter().zip(e).map(|(a, b)| (*a - *b) / two).collect();
                let Some(first) = d.iter().find(|k| !k.is_zero()) else {
                    continue;
                };
                if first.is_negative() {
                    d.iter_mut().for_each(|k| *k = -*k);
                }
                dirs.push(d);
            }
            dirs.sort();
            dirs.dedup();
            dirs
        };
        let first = from(0.313_7);
        from(-0.561_3)
            .into_iter()
            .filter(|d| {
                d.iter().filter(|k| !k.is_zero()).count() >= 2 && first.binary_search(d).is_ok()
            })
            .collect()
    }

    /// The directions in integers over a common denominator (`directions`' first way) are the
    /// halves of the differences in rationals (its second way), in the same order, on seeded
    /// random exponents of half, third and whole coefficients (some of them repeated, so that
    /// directions repeat and ties are met).
    #[test]
    fn directions_in_integers_are_the_directions_in_rationals() {
        let mut next = crate::testing::xorshift_below(0x7f1c_0dd5_d1ec_0003);
        let mut found = 0;
        for _ in 0..400 {
            let n = 2 + next(3) as usize;
            let mut exps: Vec<Vec<Small>> = Vec::new();
            for _ in 0..2 + next(8) {
                let e: Vec<Small> = (0..n)
                    .map(|_| Small::new(next(9) as i64 - 4, [1, 2, 3][next(3) as usize]))
                    .collect();
                if next(4) == 0 {
                    if let Some(p) = exps.last().cloned() {
                        exps.push(p);
                    }
                }
                exps.push(e);
            }
            let signed: Vec<Vec<Small>> = exps
                .iter()
                .flat_map(|e| [e.clone(), e.iter().map(|k| -*k).collect()])
                .collect();
            assert!(integer_exponents(&signed).is_some());
            let f = floats(&signed);
            let (first, second) = (along(&f, n, 0.313_7), along(&f, n, -0.561_3));
            let two = Small::from_integer(2);
            let rational: Vec<Vec<Small>> = twice_the_directions(&signed, &first, &second)
                .into_iter()
                .map(|d| d.into_iter().map(|k| k / two).collect())
                .collect();
            let want = halved_directions(&signed, n);
            found += want.len();
            assert_eq!(rational, want, "{exps:?}");
            assert_eq!(directions(&signed, n), want, "{exps:?}");
        }
        assert!(found > 200, "directions were found ({found})");
    }

    fn q(n: i64, d: i64) -> Scalar {
        Scalar::rational(BigRational::new(n.into(), d.into()))
    }

    /// An angle `sum k_s s + pi_k pi` as a scalar.
    fn angle(terms: &[(&str, i64, i64)], pi: (i64, i64)) -> Scalar {
        let mut a = q(pi.0, pi.1) * Scalar::pi();
        for (s, n, d) in terms {
            a = a + q(*n, *d) * Scalar::sym(s);
        }
        a
    }

    /// The same angle in floats at a point.
    fn angle_f64(terms: &[(&str, i64, i64)], pi: (i64, i64), at: &dyn Fn(&str) -> f64) -> f64 {
        let mut a = std::f64::consts::PI * pi.0 as f64 / pi.1 as f64;
        for (s, n, d) in terms {
            a += *n as f64 / *d as f64 * at(s);
        }
        a
    }

    type Factor = (bool, &'static [(&'static str, i64, i64)], (i64, i64));

    /// The product `c * prod f_i(angle_i)` as a canonical (expanded) scalar.
    fn product(c: &Scalar, fs: &[Factor]) -> Scalar {
        fs.iter().fold(c.clone(), |acc, (sin, t, pi)| {
            let a = angle(t, *pi);
            acc * if *sin { a.sin() } else { a.cos() }
        })
    }

    /// The same product in floats (an independent evaluation: `f64::cos`, `f64::sin`).
    fn product_f64(c: f64, fs: &[Factor], at: &dyn Fn(&str) -> f64) -> f64 {
        fs.iter().fold(c, |acc, (sin, t, pi)| {
            let a = angle_f64(t, *pi, at);
            acc * if *sin { a.sin() } else { a.cos() }
        })
    }

    /// The number of cos/sin factors of a product (under a sign), 0 for other shapes.
    fn trig_factors(e: &Expr) -> usize {
        match e {
            Expr::Neg(e) => trig_factors(e),
            Expr::Mul(v) => v
                .iter()
                .map(|f| match f {
                    Expr::Trig { .. } => 1,
                    Expr::Pow(b, n) if matches!(**b, Expr::Trig { .. }) => *n as usize,
                    _ => 0,
                })
                .sum(),
            _ => 0,
        }
    }

    /// Compares the closed form with the float value of the sum of products at random points.
    fn agrees(e: &Expr, parts: &[(f64, &[Factor], Option<&str>)]) {
        let mut seed = 0x1234_5678_9abc_def1u64;
        for _ in 0..5 {
            let mut vals: Vec<(String, f64)> = Vec::new();
            for s in ["a", "b", "c", "k"] {
                seed = seed
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                vals.push((
                    s.into(),
                    4.0 * (seed >> 11) as f64 / (1u64 << 53) as f64 - 2.0,
                ));
            }
            let at = |s: &str| vals.iter().find(|(n, _)| n == s).expect("symbol").1;
            let want: f64 = parts
                .iter()
                .map(|(c, fs, m)| product_f64(*c, fs, &at) * m.map_or(1.0, &at))
                .sum();
            let (got, scale) = e.eval_f64(&|s: &Sym| at(s.name()));
            // Both sides are a few dozen f64 operations on values of size ~1.
            assert!(
                (got - want).abs() <= 1e-12 * scale.max(1.0),
                "{got} vs {want}"
            );
        }
    }

    #[test]
    fn a_sinusoid_of_mixed_angle_with_an_offset_is_peeled_off() {
        // sin(a) cos(a + 2 b + pi/4): expanded, cos(2a + 2b + pi/4)/2 ... over sqrt(2).
        let fs: &[Factor] = &[
            (true, &[("a", 1, 1)], (0, 1)),
            (false, &[("a", 1, 1), ("b", 2, 1)], (1, 4)),
        ];
        let x = product(&Scalar::int(1), fs);
        assert!(x.len() >= 2);
        let e = super::super::closed_form(&x).expect("closed form");
        assert_eq!(e.to_scalar(), x);
        assert_eq!(trig_factors(&e), 2, "{e:?}");
        agrees(&e, &[(1.0, fs, None)]);
    }

    #[test]
    fn three_sinusoids_of_mixed_angles_are_found_one_by_one() {
        let fs: &[Factor] = &[
            (false, &[("a", 2, 1)], (0, 1)),
            (true, &[("a", -1, 2), ("b", 1, 1)], (0, 1)),
            (false, &[("a", 1, 1), ("c", 1, 1)], (1, 3)),
        ];
        let x = product(&q(-3, 2), fs);
        let e = super::super::closed_form(&x).expect("closed form");
        assert_eq!(e.to_scalar(), x);
        assert_eq!(trig_factors(&e), 3, "{e:?}");
        agrees(&e, &[(-1.5, fs, None)]);
    }

    #[test]
    fn a_sum_of_products_in_distinct_monomials_is_split() {
        let f1: &[Factor] = &[
            (false, &[("a", 1, 1)], (0, 1)),
            (false, &[("a", 2, 1), ("b", 1, 1)], (0, 1)),
        ];
        let f2: &[Factor] = &[
            (true, &[("c", 1, 1)], (0, 1)),
            (true, &[("c", 1, 2), ("a", 1, 1)], (1, 6)),
        ];
        let x = product(&Scalar::sym("k"), f1) + product(&Scalar::int(1), f2);
        let e = super::super::closed_form(&x).expect("closed form");
        assert_eq!(e.to_scalar(), x);
        let Expr::Add(v) = &e else {
            panic!("not a sum: {e:?}")
        };
        assert_eq!(v.len(), 2, "{e:?}");
        assert_eq!(v.iter().map(trig_factors).sum::<usize>(), 4, "{e:?}");
        agrees(&e, &[(1.0, f1, Some("k")), (1.0, f2, None)]);
    }
}
