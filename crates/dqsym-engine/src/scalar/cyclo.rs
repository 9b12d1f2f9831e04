//! The canonical form of cos and sin at rational multiples of pi: exact arithmetic in
//! cyclotomic fields.
//!
//! Every term of a scalar is `q sqrt(d) m t` (see `atoms.rs`). For the terms that share a
//! monomial `m` and a frequency vector `f` (a *group*), the sum of the `q sqrt(d) t` is:
//! - for an empty `f`, a real number `c` in `K(zeta_W)`, where `K` is the field of all square
//!   roots of rationals and `W` a multiple of 4 read from the pi offsets;
//! - otherwise `Re(z e^{i phi})` with `phi` the symbolic angle and `z` in `K(zeta_W)`
//!   (`cos(phi + a)` stands for `z = e^{ia}`, `sin(phi + a)` for `z = -i e^{ia}`).
//!
//! When a group holds a mode with a pi offset (a constant `cos(3 pi/7)`, a symbolic
//! `cos(x + pi/5)`; multiples of pi/12 never stay as offsets), [`canonicalize`] rewrites it as
//! the unique expansion of its value in a fixed basis:
//! - `M`, the smallest multiple of 24 dividing `W` with `c` (or `z`) in `K(zeta_M)`, found by
//!   removing one prime of `W` at a time. `K(zeta_M)` contains `i` and `zeta_3` through the
//!   square roots (`i = sqrt(-3)/sqrt(3)`), so fields are only told apart at multiples of 24:
//!   there `K(zeta_M) = K(zeta_N)` only for `M = N`, and the fields holding a value are the
//!   multiples of one smallest;
//! - for real `c`, the basis `R_M` of `K(zeta_M)^+` over `K`: cosines `cos(2 pi k / M)` at
//!   angles in `[0, pi/2)`, taken greedily when independent of the ones before (over `K`), in
//!   the order (the field they need, the denominator of the angle over pi, the angle):
//!   `cos(pi/7)`, `cos(2 pi/7)` for sevenths, with `cos(3 pi/7) = 1/2 - cos(pi/7) + cos(2 pi/7)`; `{1}` for `M = 24` (and
//!   fifths, eighths, tenths and twelfths, whose constants are square roots);
//! - for complex `z`, the basis `C_M` of `K(zeta_M)` over `K(i)`: `e^{i theta}`,
//!   `theta` a multiple of `2 pi / M` in `(-pi/4, pi/4]`, taken greedily in the same order
//!   (`|theta|` then positive first for the angle). A coefficient `a + b i` of `e^{i theta}`
//!   prints as `a cos(phi + theta) - b sin(phi + theta)`.
//!
//! `{q sqrt(d) b}` (`d` square-free, `b` in the basis) is a basis of the field over `Q`, so two
//! equal values give the same terms. The computation is in `Q(zeta_W)` (vectors over `Q` in the
//! power basis modulo the cyclotomic polynomial) for the square roots that live there (Gauss
//! sums); the others are carried along as independent factors. The degree `phi(W)` is bounded
//! by the context's limit ([`Context::with_max_cyclotomic_degree`](super::Context), 192 by
//! default): past it, or when the work budget runs out on the way, the result is an error
//! value, never a group left in a non-canonical form.
//!
//! The canonical form of a group is a function of its value, so a canonical group is its own
//! canonical form: a sum of two canonical scalars rewrites only the groups that hold terms of
//! both ([`Settled::Sum`]), and a product by a nonzero constant of the square-root field
//! times a monomial rewrites none (`arith::mul`). Debug builds check every group passed
//! through this way against the rewrite from scratch.

use super::atoms::{rad_mul, Mode, MonoRc, Small};
use super::modp::{self, ModSpan};
use super::{FxHasher, ScalarError, Term, Q};
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational as Rat;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::cell::RefCell;
use std::collections::{BTreeMap, HashMap};
use std::hash::BuildHasherDefault;
use std::rc::Rc;
use std::sync::{Arc, Mutex, OnceLock};

fn lcm(a: u64, b: u64) -> u64 {
    a / a.gcd(&b) * b
}

/// `W = lcm(24, 2 q1, 2 q2, ...)` for the denominators `q` of the pi offsets of `terms`, when
/// `phi(W)` is within the context's limit; the error otherwise. `phi(n) >= sqrt(n / 2)`, so a
/// `W` above `2 limit^2` is refused without building anything; its degree is computed by
/// trial division up to `W = 10^12`, and past that (or past `u128`) stated as a lower bound
/// (such a `W` is refused whatever the limit).
fn level_of<'a>(terms: impl Iterator<Item = &'a Term>) -> Result<u64, ScalarError> {
    let limit = super::ctx::max_cyclotomic_degree();
    let cap = 2u128.saturating_mul(u128::from(limit).saturating_mul(u128::from(limit)));
    let mut w: Option<u128> = Some(24);
    // The terms of a group share a few denominators: one lcm per change of denominator, none
    // when the level already holds it.
    let mut last = 0;
    for t in terms {
        let den = t.mode.pi.denom().unsigned_abs();
        if den == last {
            continue;
        }
        last = den;
        let d = 2 * u128::from(den);
        w = w.and_then(|w| {
            if w.is_multiple_of(d) {
                Some(w)
            } else {
                (w / w.gcd(&d)).checked_mul(d)
            }
        });
    }
    let refuse = |w: u128, degree: u64, exact: bool| ScalarError::CyclotomicDegree {
        level: u64::try_from(w / 2).unwrap_or(u64::MAX),
        degree,
        exact,
        limit,
    };
    const FACTORED: u128 = 1_000_000_000_000;
    let w = match w {
        Some(w) if w <= cap && w <= FACTORED => w as u64,
        Some(w) if w <= FACTORED => return Err(refuse(w, totient(w as u64), true)),
        Some(w) => {
            let bound = u64::try_from((w / 2).isqrt()).unwrap_or(u64::MAX);
            return Err(refuse(w, bound, false));
        }
        None => return Err(refuse(u128::MAX, u64::MAX, false)),
    };
    let degree = level_primes(w).0;
    if degree > limit {
        return Err(refuse(u128::from(w), degree, true));
    }
    Ok(w)
}

/// `phi(W)` and the primes of `W`, remembered per thread (every group asks for its level's).
fn level_primes(w: u64) -> (u64, Rc<[u64]>) {
    type Levels = HashMap<u64, (u64, Rc<[u64]>), BuildHasherDefault<FxHasher>>;
    thread_local! {
        static LEVELS: RefCell<Levels> = RefCell::new(Levels::default());
    }
    LEVELS.with(|l| {
        l.borrow_mut()
            .entry(w)
            .or_insert_with(|| (totient(w), primes_of(w).into()))
            .clone()
    })
}

fn primes_of(mut n: u64) -> Vec<u64> {
    let mut out = Vec::new();
    let mut p = 2;
    while p * p <= n {
        if n.is_multiple_of(p) {
            out.push(p);
            while n.is_multiple_of(p) {
                n /= p;
            }
        }
        p += 1;
    }
    if n > 1 {
        out.push(n);
    }
    out
}

fn totient(n: u64) -> u64 {
    primes_of(n).iter().fold(n, |acc, p| acc / p * (p - 1))
}

fn moebius(n: u64) -> i64 {
    let mut m = n;
    let mut k = 0;
    for p in primes_of(n) {
        m /= p;
        if m.is_multiple_of(p) {
            return 0;
        }
        k += 1;
    }
    if k % 2 == 0 {
        1
    } else {
        -1
    }
}

/// An element of `Q(zeta_W)` as a sum of powers of `zeta_W` (exponents mod `W`).
type Sparse = BTreeMap<u64, Rat>;

/// The same with integer coefficients, doubled (every basis vector is in `Z[zeta_W] / 2`).
type Ints = Vec<(u64, i64)>;

fn sparse_mul(a: &Sparse, b: &Sparse, w: u64) -> Sparse {
    let mut out = Sparse::new();
    for (i, x) in a {
        for (j, y) in b {
            let e = (i + j) % w;
            let v = out.entry(e).or_insert_with(Rat::zero);
            *v += x * y;
        }
    }
    out.retain(|_, v| !v.is_zero());
    out
}

fn mono(e: u64, c: Rat) -> Sparse {
    let mut s = Sparse::new();
    s.insert(e, c);
    s
}

/// `Q(zeta_W)` for a multiple `W` of 4: the reduction of every power of `zeta_W` to the power
/// basis, and the square roots it contains.
///
/// Two coordinate systems: the power basis modulo the cyclotomic polynomial (the exact dense
/// path, built on first use) and, for the fast path, the tensor basis of
/// `Q(zeta_W) = Q(zeta_q1) (x) ... (x) Q(zeta_qk)` for the prime powers `q` of `W`: an
/// exponent `e` is the tuple `(e mod q)`, and each axis is reduced modulo
/// `Phi_q(x) = sum_{j < p} x^{j q / p}` in one pass (`O(W)` per axis, no table).
struct Field {
    w: u64,
    phi: usize,
    /// The cyclotomic polynomial, coefficients from the constant term.
    poly: Vec<i64>,
    /// `red[k]`: `x^k` modulo the cyclotomic polynomial, `k < W` (the exact path only).
    red: OnceLock<Option<Vec<Vec<i64>>>>,
    /// The prime powers `(q, p)` of `W`; axis `i` has stride `q_0 ... q_{i-1}`.
    axes: Vec<(u64, u64)>,
    /// The position of `zeta_W^e` in the tensor layout, for each exponent `e`.
    slot: Vec<u32>,
    /// The reduced positions (every digit below `phi(q)`), in order: the coordinates.
    kept: Vec<u32>,
    /// The primes `p` with `sqrt(p)` in the field (odd divisors of `W`, 2 when 8 divides `W`).
    allowed: Vec<u64>,
    /// Every square-free product `h` of allowed primes with `sqrt(h)`.
    sqrts: Vec<(u64, Sparse)>,
}

fn legendre(a: u64, p: u64) -> i64 {
    // Euler's criterion.
    let mut r: u128 = 1;
    let (mut b, mut e, m) = (a as u128 % p as u128, (p - 1) / 2, p as u128);
    while e > 0 {
        if e & 1 == 1 {
            r = r * b % m;
        }
        b = b * b % m;
        e >>= 1;
    }
    if r == 1 {
        1
    } else {
        -1
    }
}

impl Field {
    fn new(w: u64) -> Option<Field> {
        let phi = totient(w) as usize;
        // Phi_W = prod_{d | W} (x^d - 1)^mu(W/d): the multiplications first, so that every
        // division is exact.
        let divisors: Vec<u64> = (1..=w).filter(|d| w.is_multiple_of(*d)).collect();
        let mut poly: Vec<i64> = vec![1];
        for &d in &divisors {
            if moebius(w / d) == 1 {
                let d = d as usize;
                let mut next = vec![0i64; poly.len() + d];
                for (i, c) in poly.iter().enumerate() {
                    next[i + d] = next[i + d].checked_add(*c)?;
                    next[i] = next[i].checked_sub(*c)?;
                }
                poly = next;
            }
        }
        for &d in &divisors {
            if moebius(w / d) == -1 {
                // q (x^d - 1) = p: p[i] = q[i - d] - q[i].
                let d = d as usize;
                let n = poly.len() - d;
                let mut q = vec![0i64; n];
                for i in 0..n {
                    let prev = if i >= d { q[i - d] } else { 0 };
                    q[i] = prev.checked_sub(poly[i])?;
                }
                poly = q;
            }
        }
        if poly.len() != phi + 1 || poly[phi] != 1 {
            return None;
        }
        let mut axes = Vec::new();
        for p in primes_of(w) {
            let mut q = 1;
            while w.is_multiple_of(q * p) {
                q *= p;
            }
            axes.push((q, p));
        }
        let slot: Vec<u32> = (0..w)
            .map(|e| {
                let (mut pos, mut stride) = (0, 1);
                for (q, _) in &axes {
                    pos += (e % q) * stride;
                    stride *= q;
                }
                pos as u32
            })
            .collect();
        let kept: Vec<u32> = (0..w)
            .filter(|&pos| {
                let mut r = pos;
                axes.iter().all(|(q, p)| {
                    let d = r % q;
                    r /= q;
                    d < q / p * (p - 1)
                })
            })
            .map(|pos| pos as u32)
            .collect();
        if kept.len() != phi {
            return None;
        }
        let allowed: Vec<u64> = primes_of(w)
            .into_iter()
            .filter(|&p| p != 2 || w.is_multiple_of(8))
            .collect();
        let mut prime_roots: Vec<(u64, Sparse)> = Vec::new();
        for &p in &allowed {
            let s = if p == 2 {
                let mut s = mono(w / 8, Rat::one());
                s.insert(7 * w / 8, Rat::one());
                s
            } else {
                // The Gauss sum g = sum (a/p) zeta_p^a is sqrt(p) for p = 1 mod 4 and
                // i sqrt(p) for p = 3 mod 4.
                let mut g = Sparse::new();
                for a in 1..p {
                    g.insert(a * (w / p), Rat::from_integer(legendre(a, p).into()));
                }
                if p % 4 == 1 {
                    g
                } else {
                    sparse_mul(&g, &mono(3 * w / 4, Rat::one()), w)
                }
            };
            prime_roots.push((p, s));
        }
        let mut sqrts: Vec<(u64, Sparse)> = vec![(1, mono(0, Rat::one()))];
        for (p, s) in &prime_roots {
            let more: Vec<(u64, Sparse)> = sqrts
                .iter()
                .map(|(h, x)| (h * p, sparse_mul(x, s, w)))
                .collect();
            sqrts.extend(more);
        }
        sqrts.sort_by_key(|(h, _)| *h);
        Some(Field {
            w,
            phi,
            poly,
            red: OnceLock::new(),
            axes,
            slot,
            kept,
            allowed,
            sqrts,
        })
    }

    /// The power-basis reduction of every power of `zeta_W` (charged on first use).
    fn red(&self) -> Result<&Vec<Vec<i64>>, ScalarError> {
        if self.red.get().is_none() {
            super::charge(self.w.saturating_mul(self.phi as u64))?;
        }
        let (w, phi, poly) = (self.w as usize, self.phi, &self.poly);
        self.red
            .get_or_init(|| {
                let mut red: Vec<Vec<i64>> = Vec::with_capacity(w);
                for k in 0..w {
                    let mut v = vec![0i64; phi];
                    if k < phi {
                        v[k] = 1;
                    } else {
                        let prev = &red[k - 1];
                        let lead = prev[phi - 1];
                        for j in 0..phi {
                            let shifted = if j > 0 { prev[j - 1] } else { 0 };
                            v[j] = shifted.checked_sub(lead.checked_mul(poly[j])?)?;
                        }
                    }
                    red.push(v);
                }
                Some(red)
            })
            .as_ref()
            .ok_or_else(|| {
                ScalarError::OutOfRange(format!("the cyclotomic polynomial of order {w}"))
            })
    }

    fn reduce(&self, s: &Sparse) -> Result<Vec<Rat>, ScalarError> {
        let red = self.red()?;
        let mut out = vec![Rat::zero(); self.phi];
        for (e, c) in s {
            for (o, r) in out.iter_mut().zip(&red[*e as usize]) {
                if *r != 0 {
                    *o += c * Rat::from_integer(BigInt::from(*r));
                }
            }
        }
        Ok(out)
    }

    /// Reduces a vector in the tensor layout along every axis (see the type's docs), with
    /// `sub(a, b) = a - b` (`None` stops).
    fn crt_reduce<T: Copy + PartialEq>(
        &self,
        a: &mut [T],
        zero: T,
        sub: impl Fn(T, T) -> Option<T>,
    ) -> Option<()> {
        let mut stride = 1usize;
        for &(q, p) in &self.axes {
            let (q, p) = (q as usize, p as usize);
            let m = q / p;
            let block = q * stride;
            for hi in (0..a.len()).step_by(block) {
                for d in (p - 1) * m..q {
                    let r = d - (p - 1) * m;
                    for lo in 0..stride {
                        let v = a[hi + d * stride + lo];
                        if v == zero {
                            continue;
                        }
                        a[hi + d * stride + lo] = zero;
                        for j in 0..p - 1 {
                            let t = &mut a[hi + (r + j * m) * stride + lo];
                            *t = sub(*t, v)?;
                        }
                    }
                }
            }
            stride = block;
        }
        Some(())
    }

    /// `s` in the tensor basis modulo [`modp::P`]; `None` when `P` divides a denominator.
    fn reduce_mod(&self, s: &Sparse) -> Option<Vec<u64>> {
        let mut a = vec![0u64; self.w as usize];
        for (e, c) in s {
            let t = &mut a[self.slot[*e as usize] as usize];
            *t = modp::add(*t, modp::from_rat(c)?);
        }
        self.crt_reduce(&mut a, 0, |x, y| Some(modp::sub(x, y)))?;
        Some(self.kept.iter().map(|&k| a[k as usize]).collect())
    }

    /// Whether `sum x_j v_j = t` exactly, for `v_j` given by their doubled integer
    /// coefficients; `None` when an integer overflows on the way (nothing is decided then).
    fn combination_is(&self, xs: &[(usize, Rat)], vs: &[Ints], t: &Sparse) -> Option<bool> {
        let mut d = BigInt::from(2);
        for (_, x) in xs {
            d = d.lcm(x.denom());
        }
        for c in t.values() {
            d = d.lcm(c.denom());
        }
        let mut acc = vec![0i128; self.w as usize];
        for (j, x) in xs {
            // (d x) (2 v) = 2 d (x v).
            let k = (x * Rat::from_integer(d.clone())).to_integer();
            let k = k.to_i128()?;
            for (e, c2) in &vs[*j] {
                let a = &mut acc[self.slot[*e as usize] as usize];
                *a = a.checked_add(k.checked_mul(i128::from(*c2))?)?;
            }
        }
        for (e, c) in t {
            let k = (c * Rat::from_integer(BigInt::from(2) * &d)).to_integer();
            let a = &mut acc[self.slot[*e as usize] as usize];
            *a = a.checked_sub(k.to_i128()?)?;
        }
        self.crt_reduce(&mut acc, 0, |x, y| x.checked_sub(y))?;
        Some(acc.iter().all(|a| *a == 0))
    }

    fn sqrt(&self, h: u64) -> &Sparse {
        let i = self
            .sqrts
            .binary_search_by_key(&h, |(x, _)| *x)
            .expect("h is a product of allowed primes");
        &self.sqrts[i].1
    }

    /// `d = s h`: `h` the part of the square-free `d` whose square root is in the field.
    fn split(&self, d: u64) -> (u64, u64) {
        let h: u64 = self
            .allowed
            .iter()
            .filter(|&&p| d.is_multiple_of(p))
            .product();
        (d / h, h)
    }
}

/// A pivot row: its pivot index, the reduced vector, and the combination of columns it is.
type PivotRow = (usize, Vec<Rat>, Vec<(usize, Rat)>);

/// A subspace of `Q^phi` spanned by columns added one at a time, in echelon form, with the
/// combination of columns each pivot row stands for.
struct Span {
    cols: usize,
    rows: Vec<PivotRow>,
}

impl Span {
    fn new() -> Span {
        Span {
            cols: 0,
            rows: Vec::new(),
        }
    }

    /// Reduces `v` against the pivots: the remainder, and the multiples of each pivot row
    /// taken away.
    fn reduce(&self, mut v: Vec<Rat>) -> (Vec<Rat>, Vec<Rat>) {
        let mut lambdas = Vec::with_capacity(self.rows.len());
        for (p, row, _) in &self.rows {
            if v[*p].is_zero() {
                lambdas.push(Rat::zero());
                continue;
            }
            let l = &v[*p] / &row[*p];
            for (x, r) in v.iter_mut().zip(row) {
                if !r.is_zero() {
                    *x -= &l * r;
                }
            }
            lambdas.push(l);
        }
        (v, lambdas)
    }

    fn independent(&self, v: &[Rat]) -> bool {
        self.reduce(v.to_vec()).0.iter().any(|x| !x.is_zero())
    }

    /// Adds a column; false when it depends on the others (it is then not recorded).
    fn push(&mut self, v: Vec<Rat>) -> bool {
        let col = self.cols;
        let (rest, lambdas) = self.reduce(v);
        let Some(p) = rest.iter().position(|x| !x.is_zero()) else {
            return false;
        };
        let mut comb: BTreeMap<usize, Rat> = BTreeMap::new();
        comb.insert(col, Rat::one());
        for (l, (_, _, c)) in lambdas.iter().zip(&self.rows) {
            if l.is_zero() {
                continue;
            }
            for (j, x) in c {
                *comb.entry(*j).or_insert_with(Rat::zero) -= l * x;
            }
        }
        comb.retain(|_, x| !x.is_zero());
        self.rows.push((p, rest, comb.into_iter().collect()));
        self.cols += 1;
        true
    }

    /// The coefficients of `v` on the columns, or `None` when `v` is not in the span.
    fn solve(&self, v: Vec<Rat>) -> Option<Vec<Rat>> {
        let (rest, lambdas) = self.reduce(v);
        if rest.iter().any(|x| !x.is_zero()) {
            return None;
        }
        let mut out = vec![Rat::zero(); self.cols];
        for (l, (_, _, c)) in lambdas.iter().zip(&self.rows) {
            if l.is_zero() {
                continue;
            }
            for (j, x) in c {
                out[*j] += l * x;
            }
        }
        Some(out)
    }
}

/// One column of a basis: `sqrt(h) b` with `b = cos(theta)` (real) or `e^{i theta}` (times
/// `i` when `imag`), `theta = pi * angle`.
#[derive(Clone)]
struct Col {
    h: u64,
    angle: Small,
    imag: bool,
}

struct Basis {
    span: Span,
    cols: Vec<Col>,
}

/// The order of `e^{2 pi i k / n}`.
fn order(k: i64, n: u64) -> u64 {
    n / (k.unsigned_abs().gcd(&n))
}

/// What `zeta_o` adds to the field of all square roots and `i`: `o` without its factor 3 when
/// 9 does not divide it, and without its power of 2 when 16 does not (`zeta_3`, `zeta_8` are
/// in `K(i)`). Candidates are taken by this first.
fn reduced(o: u64) -> u64 {
    let mut r = o;
    let mut two = 1;
    while r.is_multiple_of(2) {
        r /= 2;
        two *= 2;
    }
    if two >= 16 {
        r *= two;
    }
    if r.is_multiple_of(3) && !r.is_multiple_of(9) {
        r /= 3;
    }
    r
}

/// The order in which basis candidates are taken: the field they need first, then the
/// denominator of the angle as a multiple of pi (`pi/10` before `2 pi/15`), then the angle.
fn rank(k: i64, n: u64) -> (u64, u64) {
    let o = order(k, n);
    (reduced(o), if o.is_multiple_of(2) { o / 2 } else { o })
}

/// A candidate column of a level-`m` basis: the angle `2 pi k / l` and the candidate's parts
/// in `Q(zeta_w)` (for a real basis `cos(2 pi k / l)`; for a complex one `e^{2 pi i k / l}` and
/// `i e^{2 pi i k / l}`).
struct Candidate {
    k: i64,
    l: i64,
    parts: Vec<Sparse>,
}

/// The candidates of `R_M` (real) or `C_M` (complex), in the order the greedy basis takes
/// them ([`rank`]): real angles `2 pi k / l` in `[0, pi/2)` with `l = lcm(2, m)`, complex ones
/// `2 pi k / m` in `(-pi/4, pi/4]`. The exact and the fast basis both walk this list, so they
/// choose from the same columns in the same order.
fn candidates(m: u64, w: u64, real: bool) -> Vec<Candidate> {
    if real {
        let l = lcm(2, m);
        // theta = 2 pi k / l in [0, pi/2): 4k < l.
        let mut ks: Vec<i64> = (0..).take_while(|k| 4 * k < l as i64).collect();
        ks.sort_by_key(|&k| (rank(k, l), k));
        ks.into_iter()
            .map(|k| {
                let a = k as u64 * (w / l);
                let c = if a == 0 {
                    mono(0, Rat::one())
                } else {
                    let half = Rat::new(1.into(), 2.into());
                    let mut s = mono(a, half.clone());
                    s.insert(w - a, half);
                    s
                };
                Candidate {
                    k,
                    l: l as i64,
                    parts: vec![c],
                }
            })
            .collect()
    } else {
        let bound = m as i64;
        // theta = 2 pi k / m in (-pi/4, pi/4]: -m < 8k <= m.
        let mut ks: Vec<i64> = (-(bound / 8)..=bound / 8)
            .filter(|k| 8 * k > -bound)
            .collect();
        ks.sort_by_key(|&k| (rank(k, m), k.abs(), k < 0));
        let i = mono(w / 4, Rat::one());
        ks.into_iter()
            .map(|k| {
                let a = (k.rem_euclid(bound) as u64) * (w / m);
                let c = mono(a, Rat::one());
                let ic = sparse_mul(&i, &c, w);
                Candidate {
                    k,
                    l: bound,
                    parts: vec![c, ic],
                }
            })
            .collect()
    }
}

impl Basis {
    /// `R_M` (real) or `C_M` (complex, `4 | M`) inside `Q(zeta_W)`, with `sqrt(h)` (and
    /// `i sqrt(h)`) multiples for every square root of the field.
    /// `None` when the work budget runs out on the way (nothing is cached then).
    fn new(f: &Field, m: u64, real: bool) -> Result<Basis, ScalarError> {
        let w = f.w;
        let mut span = Span::new();
        let mut cols = Vec::new();
        for Candidate { k, l, parts } in candidates(m, w, real) {
            super::charge((span.rows.len() * f.phi) as u64 + 1)?;
            if !span.independent(&f.reduce(&parts[0])?) {
                continue;
            }
            for (h, r) in &f.sqrts {
                for (imag, x) in parts.iter().enumerate() {
                    span.push(f.reduce(&sparse_mul(r, x, w))?);
                    cols.push(Col {
                        h: *h,
                        angle: Small::new(2 * k, l),
                        imag: imag == 1,
                    });
                }
            }
        }
        Ok(Basis { span, cols })
    }
}

/// The exact value of a column, doubled into integers (`None` past `i64`).
fn ints(s: &Sparse) -> Option<Ints> {
    s.iter()
        .map(|(e, c)| {
            let c2 = c * Rat::from_integer(2.into());
            c2.is_integer()
                .then(|| c2.to_integer().to_i64())
                .flatten()
                .map(|c| (*e, c))
        })
        .collect()
}

/// A term's value without its rational coefficient: `sqrt(h)` times `1`, `cos`, `sin` (real
/// groups) or `e^{ia}`, `-i e^{ia}` (complex groups) at `zeta_W^a`.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
struct Unit {
    h: u64,
    a: u64,
    kind: u8,
}

const UNIT_ONE: u8 = 0;
const UNIT_COS: u8 = 1;
const UNIT_SIN: u8 = 2;

impl Unit {
    fn value(&self, f: &Field, real: bool) -> Sparse {
        let (w, a) = (f.w, self.a);
        let half = Rat::new(1.into(), 2.into());
        let trig = match (real, self.kind) {
            (true, UNIT_ONE) => mono(0, Rat::one()),
            (true, UNIT_COS) => {
                let mut s = mono(a, half.clone());
                *s.entry((w - a) % w).or_insert_with(Rat::zero) += half;
                s
            }
            (true, _) => {
                // sin = -i (zeta^a - zeta^-a) / 2.
                let q4 = 3 * w / 4;
                let mut s = mono((a + q4) % w, half.clone());
                *s.entry((w - a + q4) % w).or_insert_with(Rat::zero) -= half;
                s
            }
            (false, UNIT_COS) => mono(a, Rat::one()),
            (false, _) => mono((a + 3 * w / 4) % w, Rat::one()),
        };
        let mut out = sparse_mul(f.sqrt(self.h), &trig, w);
        out.retain(|_, c| !c.is_zero());
        out
    }
}

/// The exact coordinates of a vector over the columns of a [`FastBasis`] span.
type Coords = Vec<(usize, Rat)>;

/// The same as machine-word rationals where they fit (the form a group's sum is taken in).
type QCoords = Vec<(usize, Q)>;

/// The most units a [`FastBasis`] keeps in its table by position (three kinds for every
/// square root and power of `zeta_W`); bigger fields keep them in a map.
const DENSE_UNITS: usize = 1 << 16;

/// The basis of [`Basis`] (the same columns, in the same order) found modulo a prime and
/// checked exactly: every column taken is independent of the ones before modulo `P`, hence
/// over `Q`; every candidate left out was shown to depend on the ones before by exact
/// coordinates (small rationals read back from their residues, the combination checked in
/// `Q(zeta_W)`). The span is completed to the whole field (to its real subfield for real
/// bases, whose values are real), so every value has coordinates; a value is in the basis'
/// field when those past `cols` are zero.
struct FastBasis {
    cols: Vec<Col>,
    span: ModSpan,
    /// The exact value of every span column (basis columns, then the completion).
    vecs: Vec<Ints>,
    /// The units' coordinates by position ([`FastBasis::slot`]), each found once: one
    /// lookup per unit of every group, without a lock.
    dense: Vec<OnceLock<Option<Arc<QCoords>>>>,
    /// The same for fields with more units than [`DENSE_UNITS`]. Keyed by three words:
    /// hashed by FxHash (SipHash's rounds were 2% of the Jaco-style arm's `fk --jacobian`).
    units: Mutex<HashMap<Unit, Option<Arc<QCoords>>, BuildHasherDefault<FxHasher>>>,
}

impl FastBasis {
    /// `Ok(None)` when a check fails (the caller takes the exact path).
    fn new(f: &Field, m: u64, real: bool) -> Result<Option<FastBasis>, ScalarError> {
        let w = f.w;
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
            super::charge((fb.span.rank() * f.phi) as u64 / 256 + 1)?;
            let Some(v) = f.reduce_mod(c) else {
                return Ok(None);
            };
            if let Some(xs) = fb.span.solve(v) {
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
                if f.combination_is(&xs, &fb.vecs, c) != Some(true) {
                    return Ok(None);
                }
                continue;
            }
            for (h, r) in &f.sqrts {
                for (imag, x) in parts.iter().enumerate() {
                    let val = sparse_mul(r, x, w);
                    let (Some(v), Some(n)) = (f.reduce_mod(&val), ints(&val)) else {
                        return Ok(None);
                    };
                    if !fb.span.push(v) {
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
            super::charge((fb.span.rank() * f.phi) as u64 / 256 + 1)?;
            let (v, val) = if real {
                let e = j as u64;
                let mut c = mono(e, Rat::new(1.into(), 2.into()));
                *c.entry((w - e) % w).or_insert_with(Rat::zero) += Rat::new(1.into(), 2.into());
                let Some(v) = f.reduce_mod(&c) else {
                    return Ok(None);
                };
                let Some(n) = ints(&c) else {
                    return Ok(None);
                };
                (v, n)
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
        super::charge((f.phi * f.phi) as u64 / 256 + 1)?;
        let t = u.value(f, real);
        let xs = f
            .reduce_mod(&t)
            .and_then(|v| self.span.solve(v))
            .and_then(|xs| {
                xs.iter()
                    .enumerate()
                    .filter(|(_, x)| **x != 0)
                    .map(|(j, x)| modp::reconstruct(*x).map(|r| (j, r)))
                    .collect::<Option<Coords>>()
            })
            .filter(|xs| f.combination_is(xs, &self.vecs, &t) == Some(true))
            .map(|xs| Arc::new(xs.iter().map(|(j, c)| (*j, Q::from(c))).collect()));
        Ok(xs)
    }
}

type Cache<K, V> = OnceLock<Mutex<HashMap<K, Arc<V>>>>;

fn poisoned<T>(_: T) -> ScalarError {
    ScalarError::OutOfRange("cyclotomic cache poisoned".into())
}

/// `Q(zeta_W)`, computed once per process (its work charged to the context that builds it);
/// the ones a thread used are kept by the thread, looked up without a lock.
fn field(w: u64) -> Result<Arc<Field>, ScalarError> {
    type Fields = HashMap<u64, Arc<Field>, BuildHasherDefault<FxHasher>>;
    thread_local! {
        static FIELDS: RefCell<Fields> = RefCell::new(Fields::default());
    }
    if let Some(f) = FIELDS.with(|c| c.borrow().get(&w).cloned()) {
        return Ok(f);
    }
    let f = shared_field(w)?;
    FIELDS.with(|c| c.borrow_mut().insert(w, f.clone()));
    Ok(f)
}

/// [`field`] from the process-wide cache.
fn shared_field(w: u64) -> Result<Arc<Field>, ScalarError> {
    static CACHE: Cache<u64, Field> = OnceLock::new();
    let cache = CACHE.get_or_init(Default::default);
    if let Some(f) = cache.lock().map_err(poisoned)?.get(&w) {
        return Ok(f.clone());
    }
    super::charge(w)?;
    let f = Arc::new(Field::new(w).ok_or_else(|| {
        ScalarError::OutOfRange(format!("the cyclotomic polynomial of order {w}"))
    })?);
    cache.lock().map_err(poisoned)?.insert(w, f.clone());
    Ok(f)
}

fn basis(f: &Field, m: u64, real: bool) -> Result<Arc<Basis>, ScalarError> {
    static CACHE: Cache<(u64, u64, bool), Basis> = OnceLock::new();
    let cache = CACHE.get_or_init(Default::default);
    let key = (f.w, m, real);
    if let Some(b) = cache.lock().map_err(poisoned)?.get(&key) {
        return Ok(b.clone());
    }
    let b = Arc::new(Basis::new(f, m, real)?);
    cache.lock().map_err(poisoned)?.insert(key, b.clone());
    Ok(b)
}

/// The [`FastBasis`] of `(W, M, real)`, computed once per process; `None` when its checks
/// failed (the exact [`Basis`] is used then). The ones a thread used are kept by the thread,
/// looked up without a lock.
fn fast_basis(f: &Field, m: u64, real: bool) -> Result<Option<Arc<FastBasis>>, ScalarError> {
    type Local = HashMap<(u64, u64, bool), Option<Arc<FastBasis>>, BuildHasherDefault<FxHasher>>;
    thread_local! {
        static LOCAL: RefCell<Local> = RefCell::new(Local::default());
    }
    let key = (f.w, m, real);
    if let Some(b) = LOCAL.with(|c| c.borrow().get(&key).cloned()) {
        return Ok(b);
    }
    let b = shared_fast_basis(f, m, real)?;
    LOCAL.with(|c| c.borrow_mut().insert(key, b.clone()));
    Ok(b)
}

/// [`fast_basis`] from the process-wide cache.
fn shared_fast_basis(f: &Field, m: u64, real: bool) -> Result<Option<Arc<FastBasis>>, ScalarError> {
    type FastCache = OnceLock<Mutex<HashMap<(u64, u64, bool), Option<Arc<FastBasis>>>>>;
    static CACHE: FastCache = OnceLock::new();
    let cache = CACHE.get_or_init(Default::default);
    let key = (f.w, m, real);
    if let Some(b) = cache.lock().map_err(poisoned)?.get(&key) {
        return Ok(b.clone());
    }
    let b = FastBasis::new(f, m, real)?.map(Arc::new);
    cache.lock().map_err(poisoned)?.insert(key, b.clone());
    Ok(b)
}

/// `e^{i pi p}` as a power of `zeta_W`.
fn pi_exponent(p: &Small, w: u64) -> u64 {
    // p = n/d, 2d | W: exponent n W / (2d) mod W.
    let (n, d) = (*p.numer() as i128, *p.denom() as i128);
    let e = n * (w as i128) / (2 * d);
    e.rem_euclid(w as i128) as u64
}

/// The key of a group: the frequency vector and the monomial its terms share.
pub(crate) type GroupKey<'a> = (&'a [(super::Sym, Small)], &'a MonoRc);

/// Which groups of a term vector are known to be canonical already, so that
/// [`canonicalize`] passes them through.
pub(crate) enum Settled<'a> {
    /// None: every group holding a pi offset is rewritten.
    Nothing,
    /// The terms of the sum of two canonical scalars, `origin[i]` telling where term `i`
    /// came from (bit 1 the left operand, bit 2 the right one), with the keys of the terms
    /// that cancelled. A group whose terms all come from one operand, none cancelled, is
    /// that operand's group, canonical: the canonical form is a function of the group's
    /// value alone, and canonicalizing a canonical group gives it back.
    Sum {
        /// Where each term came from.
        origin: &'a [u8],
        /// The keys of the terms of both operands that cancelled.
        cancelled: &'a [GroupKey<'a>],
    },
}

/// Rewrites the groups of terms holding a pi offset in their canonical basis (see the module
/// docs); a field past the context's degree limit, or the work budget running out, is an
/// error. `None` when every such group is [`Settled`] (the terms are canonical as they are).
pub(crate) fn canonicalize(
    terms: &[Term],
    settled: &Settled,
) -> Result<Option<Vec<Term>>, ScalarError> {
    let mut keys: Vec<GroupKey> = terms
        .iter()
        .filter(|t| !t.mode.pi.is_zero())
        .map(|t| (&*t.mode.freq, &t.mono))
        .collect();
    keys.sort_unstable();
    keys.dedup();
    // For each group, the operands its terms came from (see `Settled::Sum`).
    let mut from = vec![0u8; keys.len()];
    let mut at: Vec<Option<usize>> = Vec::with_capacity(terms.len());
    for (i, t) in terms.iter().enumerate() {
        let k = keys.binary_search(&(&*t.mode.freq, &t.mono)).ok();
        if let (Some(k), Settled::Sum { origin, .. }) = (k, settled) {
            from[k] |= origin[i];
        }
        at.push(k);
    }
    let redo: Vec<bool> = match settled {
        Settled::Nothing => vec![true; keys.len()],
        Settled::Sum { cancelled, .. } => keys
            .iter()
            .zip(&from)
            .map(|(k, f)| *f == 3 || cancelled.contains(k))
            .collect(),
    };
    if cfg!(debug_assertions) {
        debug_check_settled(terms, &at, &redo);
    }
    if !redo.contains(&true) {
        return Ok(None);
    }
    let mut groups: Vec<Vec<&Term>> = vec![Vec::new(); keys.len()];
    let mut out: Vec<Term> = Vec::with_capacity(terms.len());
    for (t, k) in terms.iter().zip(&at) {
        match k {
            Some(k) if redo[*k] => groups[*k].push(t),
            _ => out.push(t.clone()),
        }
    }
    for g in groups {
        if !g.is_empty() {
            out.extend(canonical_group(&g)?);
        }
    }
    Ok(Some(out))
}

/// Debug builds: every group passed through as settled is its own canonical form (checked
/// on a budget of its own, so the check neither fails for lack of the caller's budget nor
/// spends it).
fn debug_check_settled(terms: &[Term], at: &[Option<usize>], redo: &[bool]) {
    for (k, _) in redo.iter().enumerate().filter(|(_, r)| !**r) {
        let g: Vec<&Term> = terms
            .iter()
            .zip(at)
            .filter(|(_, a)| **a == Some(k))
            .map(|(t, _)| t)
            .collect();
        let again = super::with_own_budget(u64::MAX / 4, || canonical_group(&g));
        if let Ok(mut again) = again {
            again.sort_by(Term::key_cmp);
            let mut g: Vec<Term> = g.into_iter().cloned().collect();
            g.sort_by(Term::key_cmp);
            assert_eq!(again, g, "a settled group is not canonical");
        }
    }
}

/// Debug builds: `terms` (sorted, merged) are canonical as they are.
pub(crate) fn debug_check_canonical(terms: &[Term]) {
    let again = super::with_own_budget(u64::MAX / 4, || {
        canonicalize(terms, &Settled::Nothing)
            .and_then(|t| t.map(super::canonical_terms).transpose())
    });
    if let Ok(Some(again)) = again {
        assert_eq!(again, terms, "terms taken as canonical are not");
    }
}

fn canonical_group(g: &[&Term]) -> Result<Vec<Term>, ScalarError> {
    match canonical_group_fast(g)? {
        Some(out) => Ok(out),
        None => canonical_group_exact(g),
    }
}

/// [`canonical_group_exact`] through the [`FastBasis`]es; `None` when one of their checks
/// failed.
fn canonical_group_fast(g: &[&Term]) -> Result<Option<Vec<Term>>, ScalarError> {
    let Some(first) = g.first() else {
        return Ok(Some(Vec::new()));
    };
    let real = first.mode.freq.is_empty();
    let w = level_of(g.iter().copied())?;
    let (phi, primes) = level_primes(w);
    super::charge(g.len() as u64 * phi / 128 + 1)?;
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
        for &p in primes.iter().filter(|p| m.is_multiple_of(**p)) {
            let n = m / p;
            if !n.is_multiple_of(24) {
                continue;
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

/// The terms of a group from its coordinates: for each class `s` of square roots outside the
/// field, `x_j sqrt(s) b_j` over the basis columns `b_j`.
fn terms_in_basis(
    first: &Term,
    real: bool,
    classes: &[u64],
    sol: Vec<Vec<Q>>,
    cols: &[Col],
) -> Result<Vec<Term>, ScalarError> {
    let mut out = Vec::new();
    for (s, xs) in classes.iter().zip(sol) {
        for (col, x) in cols.iter().zip(xs) {
            if x.is_zero() {
                continue;
            }
            let (rad, k) = rad_mul(*s, col.h)
                .ok_or_else(|| ScalarError::OutOfRange("radicand too large".into()))?;
            // The common case multiplies by one: skipped, since a product of big rationals
            // reduces its result by gcds (11% of the Jaco-style arm's `fk --jacobian`).
            let mut coef = if k == 1 { x } else { &x * &Q::from_u64(k) };
            let mode = if col.angle.is_zero() && real {
                Mode::unit()
            } else {
                let two = Small::from_integer(2);
                let pi = if col.angle.is_negative() {
                    col.angle + two
                } else {
                    col.angle
                };
                if col.imag {
                    coef = -coef;
                }
                Mode {
                    sin: col.imag,
                    freq: first.mode.freq.clone(),
                    pi,
                }
            };
            out.push(Term {
                mode,
                mono: first.mono.clone(),
                rad,
                coef,
            });
        }
    }
    Ok(out)
}

/// The canonical terms of a group by exact dense linear algebra over `Q` (the reference the
/// fast path is checked against, and its fallback).
fn canonical_group_exact(g: &[&Term]) -> Result<Vec<Term>, ScalarError> {
    let Some(first) = g.first() else {
        return Ok(Vec::new());
    };
    let real = first.mode.freq.is_empty();
    // Multiples of 24 only: K(zeta_M) for 24 | M are distinct fields, one for each smallest
    // field holding a value (K(zeta_15) = K(zeta_20) = K(zeta_120) since sqrt(-3) and i are
    // there), so the descent below ends at one M.
    let w = level_of(g.iter().copied())?;
    super::charge(g.len() as u64 * totient(w))?;
    let f = field(w)?;
    // y_s for each class s of square roots outside the field.
    let mut ys: BTreeMap<u64, Sparse> = BTreeMap::new();
    for t in g {
        let (s, h) = f.split(t.rad);
        let a = pi_exponent(&t.mode.pi, w);
        let q = t.coef.to_big();
        let half = &q / Rat::from_integer(2.into());
        let trig: Sparse = if real {
            if t.mode.is_unit() {
                mono(0, q)
            } else if !t.mode.sin {
                let mut s = mono(a, half.clone());
                *s.entry((w - a) % w).or_insert_with(Rat::zero) += half;
                s
            } else {
                // sin = -i (zeta^a - zeta^-a) / 2.
                let q4 = 3 * w / 4;
                let mut s = mono((a + q4) % w, half.clone());
                *s.entry((w - a + q4) % w).or_insert_with(Rat::zero) -= half;
                s
            }
        } else if !t.mode.sin {
            mono(a, q)
        } else {
            mono((a + 3 * w / 4) % w, q)
        };
        let x = sparse_mul(f.sqrt(h), &trig, w);
        let y = ys.entry(s).or_default();
        for (e, c) in x {
            *y.entry(e).or_insert_with(Rat::zero) += c;
        }
    }
    let ys: Vec<(u64, Vec<Rat>)> = ys
        .into_iter()
        .map(|(s, y)| Ok((s, f.reduce(&y)?)))
        .collect::<Result<_, ScalarError>>()?;
    let fits = |m: u64| -> Result<Option<Vec<Vec<Rat>>>, ScalarError> {
        let b = basis(&f, m, real)?;
        Ok(ys.iter().map(|(_, y)| b.span.solve(y.clone())).collect())
    };
    let mut m = w;
    let mut sol = fits(m)?.ok_or_else(|| {
        ScalarError::OutOfRange(format!("a value outside its cyclotomic field of order {w}"))
    })?;
    'descend: loop {
        for p in primes_of(m) {
            let n = m / p;
            if !n.is_multiple_of(24) {
                continue;
            }
            if let Some(s) = fits(n)? {
                m = n;
                sol = s;
                continue 'descend;
            }
        }
        break;
    }
    let b = basis(&f, m, real)?;
    let classes: Vec<u64> = ys.iter().map(|(s, _)| *s).collect();
    let sol = sol
        .into_iter()
        .map(|xs| xs.into_iter().map(Q::big).collect())
        .collect();
    terms_in_basis(first, real, &classes, sol, &b.cols)
}

#[cfg(test)]
mod tests {
    use super::*;

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
