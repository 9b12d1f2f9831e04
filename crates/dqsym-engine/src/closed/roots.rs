//! Products of cosines and sines of one angle, found from the roots of the scalar read as a
//! polynomial in `z = e^{i theta}`: `cos(x) sin(x + 3*pi/7)` is canonically a sum over
//! `2*x` and constants in `Q(zeta_28)`, which no angle-sum regrouping puts back together, and
//! whose offsets differ, so `offsets.rs` cannot absorb them.
//!
//! When every symbolic mode of a scalar over one monomial is an integer multiple `k` of one
//! angle `theta` (`0 <= k <= N`), the scalar is `z^-N p(z)` with `p` of degree `2N`, and a
//! root `e^{i a pi}` of `p` is the factor `sin((theta - a pi)/2)` up to a unit: the scalar is
//! `c prod_j sin((theta - a_j pi)/2)` with `c` real when every root lies on the unit circle.
//! The roots are found in f64 (Aberth's iteration), clustered (a root of multiplicity `m` is
//! `m` nearby approximations whose mean is accurate), and each cluster's angle must be a
//! rational multiple of pi of bounded denominator: a root of unity `zeta` of order `M` that
//! is a root of `p`, whose coefficients lie in `Q(zeta_W)`, has `[Q(zeta_W, zeta) : Q(zeta_W)]
//! = phi(lcm(W, M))/phi(W) <= 2N`, and that degree is at least `phi(M')` for `M' = lcm(W,
//! M)/W`; so `M` divides `W M'` with `phi(M') <= 2N`, and the denominator of `a` is at most
//! `W n(2N)`, `n(d)` the largest `n` with `phi(n) <= d` ([`max_denominator`]).
//!
//! The roots are grouped into real factors, each in the cheaper of its shapes: a pair `{a,
//! a + 1}` is `sin(theta - a pi)` (shown as the cosine or sine with the offset of the display
//! rule: smallest denominator, no offset before one, smallest `|offset|`, positive), a pair
//! `{a, -a}` is `cos(theta) - cos(a pi)`, a pair `{a, 1 - a}` is `sin(theta) - sin(a pi)`, a
//! root left alone the half-angle factor `sin((theta - a pi)/2)`; equal factors are powers.
//! Every order of the three pairings is tried, and the halves alone; the caller keeps the
//! cheapest that checks. The constant `c` is exact: the coefficient of `z^N` divided by the
//! product of the factors' leading coefficients, each a power of 2 times a root of unity,
//! so `c = 2^E Re(A_N e^{-i B pi})` is built from the scalar's own top terms. Floats only find
//! the roots: the caller checks every candidate exactly against the scalar.
//!
//! A scalar whose modes hold several symbols may still be a product `f(x) g(y)` of one-angle
//! parts (`sin(x - 5*pi/8) cos(y + 3*pi/8)` expands to the modes `x - y` and `x + y`):
//! [`separable`] splits the symbols where the scalar is numerically of rank one, finds each
//! part's roots from its restriction to a point of the other symbols, and takes the constant
//! exactly from the coefficient of the product of the parts' top modes.

use super::alt::{mul, neg, trig};
use super::expr::Expr;
use crate::scalar::{charge, Small, Sym, Term};
use crate::Scalar;
use num_integer::Integer;
use num_traits::{One, Signed, Zero};
use std::collections::BTreeMap;

/// The most terms a scalar may have for its roots to be looked for.
const MAX_TERMS: usize = 4096;

/// The largest multiple `N` of the base angle (the polynomial has degree `2N`).
const MAX_DEGREE: i64 = 24;

/// The most sweeps of Aberth's iteration.
const MAX_SWEEPS: usize = 500;

/// The largest denominator a root's multiple of pi may have.
const MAX_DENOMINATOR: i64 = 1_000_000;

/// A complex number in f64 (also `square.rs`'s).
#[derive(Clone, Copy, Debug)]
pub(super) struct C(pub(super) f64, pub(super) f64);

impl C {
    fn polar(r: f64, a: f64) -> C {
        C(r * a.cos(), r * a.sin())
    }
    pub(super) fn add(self, o: C) -> C {
        C(self.0 + o.0, self.1 + o.1)
    }
    pub(super) fn sub(self, o: C) -> C {
        C(self.0 - o.0, self.1 - o.1)
    }
    pub(super) fn mul(self, o: C) -> C {
        C(self.0 * o.0 - self.1 * o.1, self.0 * o.1 + self.1 * o.0)
    }
    pub(super) fn div(self, o: C) -> C {
        let d = o.0 * o.0 + o.1 * o.1;
        C(
            (self.0 * o.0 + self.1 * o.1) / d,
            (self.1 * o.0 - self.0 * o.1) / d,
        )
    }
    pub(super) fn abs(self) -> f64 {
        self.0.hypot(self.1)
    }
    /// The principal square root.
    pub(super) fn sqrt(self) -> C {
        let r = self.abs();
        let re = ((r + self.0) / 2.0).max(0.0).sqrt();
        let im = ((r - self.0) / 2.0).max(0.0).sqrt();
        C(re, if self.1 < 0.0 { -im } else { im })
    }
    pub(super) fn scale(self, k: f64) -> C {
        C(self.0 * k, self.1 * k)
    }
    fn finite(self) -> bool {
        self.0.is_finite() && self.1.is_finite()
    }
}

/// `p(z)` and `p'(z)` (coefficients from the constant up).
fn horner(p: &[C], z: C) -> (C, C) {
    let (mut v, mut d) = (C(0.0, 0.0), C(0.0, 0.0));
    for &c in p.iter().rev() {
        d = d.mul(z).add(v);
        v = v.mul(z).add(c);
    }
    (v, d)
}

/// The roots of `p` (degree >= 1, nonzero leading and constant coefficients) by Aberth's
/// simultaneous iteration; `None` when the work budget runs out or it does not settle.
fn aberth(p: &[C]) -> Option<Vec<C>> {
    let n = p.len() - 1;
    let lead = p[n];
    let a: Vec<C> = p.iter().map(|c| c.div(lead)).collect();
    // Start on the circle of the geometric mean of the roots' moduli, off the real axis.
    let r = a[0].abs().powf(1.0 / n as f64);
    let mut z: Vec<C> = (0..n)
        .map(|k| C::polar(r, std::f64::consts::TAU * k as f64 / n as f64 + 0.4))
        .collect();
    for _ in 0..MAX_SWEEPS {
        charge((n * n / 16 + 1) as u64).ok()?;
        let mut largest: f64 = 0.0;
        for i in 0..n {
            let (v, d) = horner(&a, z[i]);
            if v.abs() == 0.0 {
                continue;
            }
            let ratio = v.div(d);
            let mut sum = C(0.0, 0.0);
            for (j, zj) in z.iter().enumerate() {
                if j != i {
                    sum = sum.add(C(1.0, 0.0).div(z[i].sub(*zj)));
                }
            }
            let w = ratio.div(C(1.0, 0.0).sub(ratio.mul(sum)));
            if !w.finite() {
                continue;
            }
            z[i] = z[i].sub(w);
            largest = largest.max(w.abs() / z[i].abs().max(1e-300));
        }
        if largest < 1e-14 {
            break;
        }
    }
    z.iter().all(|z| z.finite()).then_some(z)
}

/// Euler's totient.
fn totient(mut n: i64) -> i64 {
    let mut out = n;
    let mut p = 2;
    while p * p <= n {
        if n % p == 0 {
            while n % p == 0 {
                n /= p;
            }
            out -= out / p;
        }
        p += 1;
    }
    if n > 1 {
        out -= out / n;
    }
    out
}

/// The largest denominator of a root's multiple of pi for a polynomial of degree `d` over
/// `Q(zeta_w)` (see the module docs): `w` times the largest `n` with `phi(n) <= d` (`phi(n) >=
/// sqrt(n/2)`, so the search stops at `2 d^2`).
fn max_denominator(w: i64, d: i64) -> i64 {
    let n = (1..=2 * d * d + 2)
        .filter(|&n| totient(n) <= d)
        .max()
        .unwrap_or(1);
    (2 * w).saturating_mul(n).min(MAX_DENOMINATOR)
}

/// A rational within `tol` of `v` with denominator at most `dmax` (the first continued-fraction
/// convergent that close).
fn snap(v: f64, tol: f64, dmax: i64) -> Option<Small> {
    let (mut h0, mut h1, mut k0, mut k1) = (0i64, 1i64, 1i64, 0i64);
    let mut x = v;
    for _ in 0..64 {
        let a = x.floor();
        let ai = a as i64;
        (h0, h1) = (h1, ai.checked_mul(h1)?.checked_add(h0)?);
        (k0, k1) = (k1, ai.checked_mul(k1)?.checked_add(k0)?);
        if k1 > dmax {
            return None;
        }
        if (v - h1 as f64 / k1 as f64).abs() < tol {
            return Some(Small::new(h1, k1));
        }
        let frac = x - a;
        if frac.abs() < 1e-15 {
            return None;
        }
        x = 1.0 / frac;
    }
    None
}

/// `p` in `[0, 2)`.
fn mod2(p: Small) -> Small {
    let two = Small::from_integer(2);
    p - (p / two).floor() * two
}

/// A frequency vector.
type Freq = Vec<(Sym, Small)>;

/// The base angle (a frequency vector) of which every symbolic mode is a whole multiple, and
/// each term's multiple (0 for a constant term).
fn base(t: &[Term]) -> Option<(Freq, Vec<i64>)> {
    let fs: Vec<&[(Sym, Small)]> = t.iter().map(|u| &u.mode.freq[..]).collect();
    base_of(&fs)
}

/// [`base`] of the frequencies `fs` (the multiples may be negative when the first nonzero
/// frequency is not the largest's direction).
fn base_of(fs: &[&[(Sym, Small)]]) -> Option<(Freq, Vec<i64>)> {
    let v = *fs.iter().find(|f| !f.is_empty())?;
    let mut ratios = Vec::with_capacity(fs.len());
    for f in fs {
        if f.is_empty() {
            ratios.push(Small::zero());
            continue;
        }
        if f.len() != v.len() {
            return None;
        }
        let r = f[0].1 / v[0].1;
        if !f
            .iter()
            .zip(v.iter())
            .all(|((s, k), (s2, k2))| s == s2 && *k == r * *k2)
        {
            return None;
        }
        ratios.push(r);
    }
    let (mut gn, mut gd) = (0i64, 1i64);
    for r in ratios.iter().filter(|r| !r.is_zero()) {
        gn = gn.gcd(r.numer());
        gd = gd.lcm(r.denom());
    }
    let g = Small::new(gn, gd);
    let ks: Vec<i64> = ratios.iter().map(|r| (r / g).to_integer()).collect();
    let theta = v.iter().map(|(s, k)| (s.clone(), *k * g)).collect();
    Some((theta, ks))
}

/// A real factor of the product, by the roots it holds, in the half angle `phi = theta/2`
/// (multiples of pi in `[0, 2)`).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Factor {
    /// `sin(k (phi - a pi))`, `0 <= a < 1/k`: the roots `a + j/k`, `0 <= j < 2k`.
    Full(i64, Small),
    /// `cos(k phi) - cos(k b pi)`, `0 <= k b <= 1`: the roots `+-b + 2j/k`, `0 <= j < k`.
    CosDiff(i64, Small),
    /// `sin(k phi) - sin(k b pi)`, `-1/2 <= k b <= 1/2`: the roots `b + 2j/k` and `1/k - b +
    /// 2j/k`.
    SinDiff(i64, Small),
}

impl Factor {
    /// The factor of kind `kind` (0 full, 1 cosine difference, 2 sine difference) with
    /// multiplier `k` that has the root `r`.
    fn through(kind: u8, k: i64, r: Small) -> Factor {
        let kk = Small::from_integer(k);
        match kind {
            0 => {
                let step = Small::new(1, k);
                Factor::Full(k, r - (r / step).floor() * step)
            }
            1 => Factor::CosDiff(k, centred(r * kk).abs() / kk),
            _ => {
                let c = centred(r * kk);
                let half = Small::new(1, 2);
                let c = if c.abs() <= half {
                    c
                } else {
                    centred(Small::one() - c)
                };
                Factor::SinDiff(k, c / kk)
            }
        }
    }

    /// The factor's roots, with multiplicities.
    fn roots(&self) -> BTreeMap<Small, u32> {
        let mut out = BTreeMap::new();
        let mut add = |r: Small| *out.entry(mod2(r)).or_insert(0u32) += 1;
        match *self {
            Factor::Full(k, a) => (0..2 * k).for_each(|j| add(a + Small::new(j, k))),
            Factor::CosDiff(k, b) => (0..k).for_each(|j| {
                add(b + Small::new(2 * j, k));
                add(-b + Small::new(2 * j, k));
            }),
            Factor::SinDiff(k, b) => (0..k).for_each(|j| {
                add(b + Small::new(2 * j, k));
                add(Small::new(1 + 2 * j, k) - b);
            }),
        }
        out
    }
}

/// The factors [`group`] tries, made once per [`groupings`] (every grouping tries the same
/// factors, each a few rational operations and a map of up to `2k` roots): the roots in
/// order, and for each kind, multiplier and root the factor through it, by its index in
/// `factors` with its roots' indices and multiplicities; `None` when one of its roots is not
/// a root at all (it is never taken).
struct Table {
    roots: Vec<Small>,
    kmax: usize,
    cells: Vec<Option<Option<usize>>>,
    factors: Vec<(Factor, Vec<(usize, u32)>)>,
}

impl Table {
    fn new(half: &BTreeMap<Small, u32>, kmax: usize) -> Table {
        let roots: Vec<Small> = half.keys().copied().collect();
        Table {
            cells: vec![None; 3 * (kmax + 1) * roots.len()],
            roots,
            kmax,
            factors: Vec::new(),
        }
    }

    /// The index of [`Factor::through`] the `i`-th root, with its roots (see [`Table`]).
    fn through(&mut self, kind: u8, k: i64, i: usize) -> Option<usize> {
        let cell = (usize::from(kind) * (self.kmax + 1) + k as usize) * self.roots.len() + i;
        if let Some(id) = self.cells[cell] {
            return id;
        }
        let f = Factor::through(kind, k, self.roots[i]);
        let need: Option<Vec<(usize, u32)>> = f
            .roots()
            .into_iter()
            .map(|(r, n)| self.roots.binary_search(&r).ok().map(|j| (j, n)))
            .collect();
        let id = need.map(
            |need| match self.factors.iter().position(|(g, _)| *g == f) {
                Some(id) => id,
                None => {
                    self.factors.push((f, need));
                    self.factors.len() - 1
                }
            },
        );
        self.cells[cell] = Some(id);
        id
    }
}

/// The roots (multiples of pi in `[0, 2)` of the half angle, with multiplicities) grouped
/// into factors: for each multiplier `k` in `ks`, in turn, the kinds in `kinds` (see
/// [`Factor::through`]) in turn, each factor taken as often as its roots are left. `None`
/// when some root is left over.
///
/// Two skips that change nothing: a factor of multiplier `k` holds `2k` roots counted with
/// their multiplicities, so while fewer are left it is taken no time; and a factor already
/// tried is taken no time again, as roots are only ever removed: after it is taken `m`
/// times, one of its roots of multiplicity `n` in it has fewer than `n` copies left (else
/// it would have been taken `m + 1` times), and a factor taken no time keeps a root short.
fn group(
    half: &BTreeMap<Small, u32>,
    ks: &[i64],
    kinds: &[u8],
    table: &mut Table,
) -> Option<BTreeMap<Factor, u32>> {
    let mut left: Vec<u32> = half.values().copied().collect();
    let mut count: u64 = left.iter().map(|&n| u64::from(n)).sum();
    let mut out: BTreeMap<Factor, u32> = BTreeMap::new();
    let mut tried: Vec<bool> = Vec::new();
    for &k in ks {
        for &kind in kinds {
            if count < 2 * k.unsigned_abs() {
                break;
            }
            for i in 0..left.len() {
                if left[i] == 0 {
                    continue;
                }
                let Some(id) = table.through(kind, k, i) else {
                    continue;
                };
                if tried.len() <= id {
                    tried.resize(id + 1, false);
                }
                if std::mem::replace(&mut tried[id], true) {
                    continue;
                }
                let (f, need) = &table.factors[id];
                let times = need.iter().map(|&(j, n)| left[j] / n).min().unwrap_or(0);
                if times == 0 {
                    continue;
                }
                *out.entry(*f).or_insert(0) += times;
                for &(j, n) in need {
                    left[j] -= n * times;
                    count -= u64::from(n * times);
                }
            }
        }
    }
    (count == 0).then_some(out)
}

/// One way to show a factor `+-f(angle + phi pi)`: whether it is a sine, and `phi` in `(-1,
/// 1]`.
#[derive(Clone, Copy)]
struct Shape {
    sin: bool,
    phi: Small,
}

impl Shape {
    /// The display rule's key: fewest operations in the offset (`pi/10` before `2*pi/5`),
    /// smallest denominator, no offset before one, smallest `|phi|`, positive, cosine first.
    fn key(&self) -> (usize, i64, bool, Small, bool, bool) {
        let ops = if self.phi.is_zero() {
            0
        } else {
            1 + usize::from(self.phi.numer().abs() != 1) + usize::from(*self.phi.denom() != 1)
        };
        (
            ops,
            *self.phi.denom(),
            !self.phi.is_zero(),
            self.phi.abs(),
            self.phi.is_negative(),
            self.sin,
        )
    }

    /// The multiple of pi of the leading coefficient `2^-1 e^{i beta pi}` of the shape in
    /// `e^{i angle}`.
    fn beta(&self) -> Small {
        if self.sin {
            self.phi - Small::new(1, 2)
        } else {
            self.phi
        }
    }

    /// The same function with the offset moved by pi: its negative.
    fn flipped(&self) -> Shape {
        let one = Small::one();
        Shape {
            sin: self.sin,
            phi: if self.phi.is_positive() {
                self.phi - one
            } else {
                self.phi + one
            },
        }
    }
}

/// `phi` reduced into `(-1, 1]`.
fn centred(p: Small) -> Small {
    let p = mod2(p);
    if p > Small::one() {
        p - Small::from_integer(2)
    } else {
        p
    }
}

/// The best shape (by [`Shape::key`]) of the function with the zeros of `sin(angle - a pi)`,
/// up to sign: `sin(angle + phi)` with `phi = -a (mod 1)` or `cos(angle + phi)` with
/// `phi = 1/2 - a (mod 1)`.
fn best_shape(a: Small) -> Shape {
    let mut shapes = Vec::with_capacity(4);
    for (sin, base) in [(false, Small::new(1, 2) - a), (true, -a)] {
        for k in [0, 1] {
            shapes.push(Shape {
                sin,
                phi: centred(base + Small::from_integer(k)),
            });
        }
    }
    shapes
        .into_iter()
        .min_by_key(Shape::key)
        .expect("four shapes")
}

/// The term's coefficient, radical and monomial as a scalar (its mode dropped).
fn weight(t: &Term) -> Scalar {
    Scalar::from_terms_sorted(vec![Term {
        mode: crate::scalar::Mode::unit(),
        ..t.clone()
    }])
}

/// A scalar's top coefficient `re + i im` (the coefficient of the product of the factors' top
/// modes) and the constants `c = 2^E Re((re + i im) e^{-i B pi})` made from it so far, one per
/// `(E, B)` ([`Top::constant`]).
///
/// Why: every grouping of one scalar's roots, and every choice of [`separable`]'s parts, needs
/// its constant, and they share few `(E, B)` pairs (the factors' leading coefficients are
/// powers of 2 times a few roots of unity); each constant costs two exact cosines of `B pi`
/// (cyclotomic canonical forms) and three products. The constant is a function of `(E, B)`
/// alone for one `re + i im`, so a constant made once is the constant made again.
struct Top {
    re: Scalar,
    im: Scalar,
    made: Vec<((u64, Small), Scalar)>,
}

impl Top {
    fn new((re, im): (Scalar, Scalar)) -> Top {
        Top {
            re,
            im,
            made: Vec::new(),
        }
    }

    /// `2^exps Re((re + i im) e^{-i b pi})`, made once per `(exps, b)` ([`constant_of`]).
    fn constant(&mut self, exps: u64, b: Small) -> Scalar {
        if let Some((_, c)) = self.made.iter().find(|(k, _)| *k == (exps, b)) {
            return c.clone();
        }
        let c = constant_of(&self.re, &self.im, exps, b);
        self.made.push(((exps, b), c.clone()));
        c
    }
}

/// `2^exps Re((re + i im) e^{-i b pi}) = 2^exps (re cos(b pi) + im sin(b pi))`.
fn constant_of(re: &Scalar, im: &Scalar, exps: u64, b: Small) -> Scalar {
    let two = Scalar::int(2).pow(exps);
    let c = re * &Scalar::trig_of_parts(false, Vec::new(), b)
        + im * &Scalar::trig_of_parts(true, Vec::new(), b);
    &two * &c
}

/// The scalar's coefficient of `z^N` as `(Re, Im)` exact scalars (times its monomial).
fn top_coefficient(t: &[Term], ks: &[i64], n: i64) -> (Scalar, Scalar) {
    top_of(
        t.iter()
            .zip(ks)
            .filter(|(_, &k)| k == n)
            .map(|(u, _)| (u, false)),
    )
}

/// The coefficient of `e^{i T}` of the terms whose mode is `T` (`false`) or `-T` (`true`), as
/// `(Re, Im)` exact scalars (times their monomial).
fn top_of<'a>(terms: impl Iterator<Item = (&'a Term, bool)>) -> (Scalar, Scalar) {
    let (mut re, mut im) = (Scalar::zero(), Scalar::zero());
    for (u, negated) in terms {
        // (w/2) e^{i psi pi}, psi the offset (less 1/2 for a sine), negated for -T.
        let psi = if u.mode.sin {
            u.mode.pi - Small::new(1, 2)
        } else {
            u.mode.pi
        };
        let psi = if negated { -psi } else { psi };
        let w = weight(u) * Scalar::rational(num_rational::BigRational::new(1.into(), 2.into()));
        re = re + &w * &Scalar::trig_of_parts(false, Vec::new(), psi);
        im = im + &w * &Scalar::trig_of_parts(true, Vec::new(), psi);
    }
    (re, im)
}

/// Candidates for `t` as products of cosines and sines of one angle (see the module docs);
/// empty unless the scalar has a constant outside the rationals (a pi offset or a square root),
/// one monomial, at most [`MAX_TERMS`] terms and its modes multiples of one angle.
pub(super) fn root_products(t: &[Term]) -> Vec<Expr> {
    match found(t) {
        Some(out) => out,
        None => separable(t).unwrap_or_default(),
    }
}

/// The gate both searches share: 2 to `max_terms` terms over one monomial, with a pi offset
/// or a square root (an offset-free rational scalar, the PUMA's entries, is left to the
/// rational roots of `alt.rs`).
fn gate(t: &[Term], max_terms: usize) -> bool {
    (2..=max_terms).contains(&t.len())
        && !t.iter().all(|u| u.mode.pi.is_zero() && u.rad == 1)
        && t.iter().all(|u| u.mono == t[0].mono)
}

fn found(t: &[Term]) -> Option<Vec<Expr>> {
    if !gate(t, MAX_TERMS) {
        return None;
    }
    let (theta, ks) = base(t)?;
    let n = *ks.iter().max()?;
    if !(1..=MAX_DEGREE).contains(&n) {
        return None;
    }
    // p(z) = z^N (the scalar), from the constant coefficient up; W the conductor of its field.
    let mut p = vec![C(0.0, 0.0); 2 * n as usize + 1];
    let mut w: i64 = 24;
    for (u, &k) in t.iter().zip(&ks) {
        w = w.lcm(&(2 * u.mode.pi.denom()));
        if u.rad != 1 {
            w = w.lcm(&(4 * i64::try_from(u.rad).ok()?));
        }
        let psi = if u.mode.sin {
            u.mode.pi - Small::new(1, 2)
        } else {
            u.mode.pi
        };
        let a = std::f64::consts::PI * (*psi.numer() as f64 / *psi.denom() as f64);
        let v = u.coef.to_f64()? * (u.rad as f64).sqrt();
        let (k, n) = (k as usize, n as usize);
        if k == 0 {
            p[n] = p[n].add(C(v * a.cos(), 0.0));
        } else {
            p[n + k] = p[n + k].add(C::polar(v / 2.0, a));
            p[n - k] = p[n - k].add(C::polar(v / 2.0, -a));
        }
    }
    let half = half_roots(&p, w)?;
    let mut top = Top::new(top_coefficient(t, &ks, n));
    let mut out = Vec::new();
    for g in groupings(&half) {
        out.extend(product_expr(&g, &theta, &mut top).unwrap_or_default());
    }
    Some(out)
}

/// The orders in which [`groupings`] tries the three kinds of factor.
const KIND_ORDERS: [[u8; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

/// The distinct groupings of the half-angle roots into factors: the largest multipliers
/// first, or the angle theta itself (k = 2) before the half angle, or the half angle alone;
/// each with the kinds in every order.
fn groupings(half: &BTreeMap<Small, u32>) -> Vec<BTreeMap<Factor, u32>> {
    let kmax = i64::from(half.values().sum::<u32>() / 2);
    let descending: Vec<i64> = (1..=kmax).rev().collect();
    let multipliers: [&[i64]; 3] = [&descending, &[2, 1], &[1]];
    let mut seen: Vec<BTreeMap<Factor, u32>> = Vec::new();
    let mut table = Table::new(half, kmax.max(2) as usize);
    for ks in multipliers {
        for order in &KIND_ORDERS {
            if let Some(g) = group(half, ks, order, &mut table) {
                if !seen.contains(&g) {
                    seen.push(g);
                }
            }
        }
    }
    seen
}

/// The roots of `p` (a polynomial in `e^{i theta}` over `Q(zeta_w)`, from the constant up) as
/// multiples of pi of the half angle `theta/2`, with multiplicities; `None` unless every root
/// is a checked root of unity and their product is `p` numerically.
fn half_roots(p: &[C], w: i64) -> Option<BTreeMap<Small, u32>> {
    let n = (p.len() as i64 - 1) / 2;
    let scale: f64 = p.iter().map(|c| c.abs()).sum();
    if p[0].abs() <= 1e-12 * scale {
        return None;
    }
    let zs = aberth(p)?;
    let roots = unit_roots(p, &zs, max_denominator(w, 2 * n))?;
    // The factorization numerically, before any exact work.
    if !factorization_agrees(p, &roots) {
        return None;
    }
    // The roots in the half angle phi = theta/2: each root a of theta is a/2 and a/2 + 1.
    let mut half: BTreeMap<Small, u32> = BTreeMap::new();
    for (a, m) in &roots {
        for r in [
            *a / Small::from_integer(2),
            *a / Small::from_integer(2) + Small::one(),
        ] {
            *half.entry(r).or_insert(0) += m;
        }
    }
    Some(half)
}

/// The clusters of the approximations `zs` of the roots of `p`, each snapped to `e^{i a pi}`
/// with `a` rational of denominator at most `dmax` and checked to be a root: `a` in `[0, 2)`
/// with its multiplicity. `None` when a root is off the unit circle or not such a root.
fn unit_roots(p: &[C], zs: &[C], dmax: i64) -> Option<BTreeMap<Small, u32>> {
    let mut clusters: Vec<(C, u32)> = Vec::new();
    for &z in zs {
        if (z.abs() - 1.0).abs() > 1e-3 {
            return None;
        }
        match clusters
            .iter_mut()
            .find(|(c, m)| c.div(C(*m as f64, 0.0)).sub(z).abs() < 2e-3)
        {
            Some((c, m)) => {
                *c = c.add(z);
                *m += 1;
            }
            None => clusters.push((z, 1)),
        }
    }
    let scale: f64 = p.iter().map(|c| c.abs()).sum();
    let mut roots = BTreeMap::new();
    for (c, m) in clusters {
        let mean = refined(p, c.div(C(m as f64, 0.0)), m);
        let angle = mean.1.atan2(mean.0) / std::f64::consts::PI;
        let a = mod2(snap(angle, 1e-10, dmax)?);
        let af = *a.numer() as f64 / *a.denom() as f64;
        let (v, _) = horner(p, C::polar(1.0, std::f64::consts::PI * af));
        if v.abs() > 1e-9 * scale {
            return None;
        }
        *roots.entry(a).or_insert(0) += m;
    }
    Some(roots)
}

/// `z` refined as a root of multiplicity `m` of `p`: Newton's iteration on `p^(m-1)`, of which
/// it is a simple root (the mean of a cluster is accurate to about the square of its spread).
fn refined(p: &[C], z: C, m: u32) -> C {
    let mut d = p.to_vec();
    for _ in 1..m {
        d = (1..d.len()).map(|i| d[i].mul(C(i as f64, 0.0))).collect();
    }
    let mut z = z;
    for _ in 0..4 {
        let (v, dv) = horner(&d, z);
        let step = v.div(dv);
        if !step.finite() || step.abs() > 1e-4 {
            break;
        }
        z = z.sub(step);
    }
    z
}

/// Whether `p` is its leading coefficient times the product of `(z - e^{i a pi})^m` at a few
/// points, to a relative `1e-8`.
fn factorization_agrees(p: &[C], roots: &BTreeMap<Small, u32>) -> bool {
    let lead = p[p.len() - 1];
    let scale: f64 = p.iter().map(|c| c.abs()).sum();
    [C::polar(1.0, 0.7), C::polar(1.0, 2.3), C::polar(1.3, -1.9)]
        .into_iter()
        .all(|z| {
            let (v, _) = horner(p, z);
            let mut w = lead;
            for (a, &m) in roots {
                let r = C::polar(
                    1.0,
                    std::f64::consts::PI * (*a.numer() as f64 / *a.denom() as f64),
                );
                for _ in 0..m {
                    w = w.mul(z.sub(r));
                }
            }
            let zs = z.abs().powi(p.len() as i32 - 1).max(1.0);
            v.sub(w).abs() <= 1e-8 * scale * zs
        })
}

/// A factor of a candidate: its expression, the multiple of pi of its leading coefficient's
/// phase, the flipped (negated) form when it has one, and its power.
#[derive(Clone)]
struct Built {
    expr: Expr,
    beta: Small,
    flip: Option<(Expr, Small, Small)>,
    power: u32,
}

/// The candidates `c prod f^m` for one grouping: each factor in its best shape, the constant
/// exact from the top coefficient of the scalar.
fn product_expr(
    g: &BTreeMap<Factor, u32>,
    theta: &[(Sym, Small)],
    top: &mut Top,
) -> Option<Vec<Expr>> {
    finish(built_factors(g, theta)?, top)
}

/// The factors of one grouping, each in its best shape, in the angle `theta`.
fn built_factors(g: &BTreeMap<Factor, u32>, theta: &[(Sym, Small)]) -> Option<Vec<Built>> {
    // The angle k phi = k theta / 2.
    let scaled = |k: Small| -> Vec<(Sym, Small)> {
        theta
            .iter()
            .map(|(s, c)| (s.clone(), *c * k / Small::from_integer(2)))
            .collect()
    };
    let mut built: Vec<Built> = Vec::new();
    for (&f, &power) in g {
        let b = match f {
            Factor::Full(k, a) => {
                let kk = Small::from_integer(k);
                let angle = scaled(kk);
                let a = a * kk;
                let s = best_shape(a);
                let make = |s: Shape| trig(s.sin, angle.clone(), s.phi);
                let flip = (!s.phi.is_zero()).then(|| {
                    let t = s.flipped();
                    (make(t), t.beta(), t.phi.abs())
                });
                Built {
                    expr: make(s),
                    beta: s.beta(),
                    flip,
                    power,
                }
            }
            Factor::CosDiff(k, b) | Factor::SinDiff(k, b) => {
                let sin = matches!(f, Factor::SinDiff(..));
                let kk = Small::from_integer(k);
                let v = trig(sin, scaled(kk), Small::zero());
                let k = Scalar::trig_of_parts(sin, Vec::new(), b * kk);
                let kv = k.eval(&|_| None).ok()?;
                // |k| as its closed form or as the cosine or sine itself, the cheaper
                // (`cos(pi/5)`, not `1/4 (1 + sqrt(5))`).
                let kb = b * kk;
                let direct = if sin {
                    trig(true, Vec::new(), kb.abs())
                } else if kb > Small::new(1, 2) {
                    trig(false, Vec::new(), Small::one() - kb)
                } else {
                    trig(false, Vec::new(), kb)
                };
                let kexpr = super::closed_form(&if kv < 0.0 { -k } else { k }).ok()?;
                let kexpr = if direct.cost() < kexpr.cost() {
                    direct
                } else {
                    kexpr
                };
                let lin = |neg_v: bool| {
                    // v - k (or k - v); the constant's sign folded into the operation.
                    let (vv, kk) = if neg_v {
                        (neg(v.clone()), kexpr.clone())
                    } else {
                        (v.clone(), neg(kexpr.clone()))
                    };
                    let kk = if kv < 0.0 { neg(kk) } else { kk };
                    if kv == 0.0 {
                        vv
                    } else if neg_v {
                        Expr::Add(vec![kk, vv])
                    } else {
                        Expr::Add(vec![vv, kk])
                    }
                };
                // Leading coefficient 1/2 (cosine) or 1/(2i) (sine); negated, plus pi.
                let beta = if sin {
                    Small::new(-1, 2)
                } else {
                    Small::zero()
                };
                Built {
                    expr: lin(false),
                    beta,
                    flip: Some((lin(true), beta + Small::one(), Small::zero())),
                    power,
                }
            }
        };
        built.push(b);
    }
    Some(built)
}

/// The candidates `c prod f^m` for the factors `built`, the constant exact from the top
/// coefficient of the scalar ([`Top`]).
fn finish(mut built: Vec<Built>, top: &mut Top) -> Option<Vec<Expr>> {
    let exps: u64 = built.iter().map(|b| u64::from(b.power)).sum();
    let beta_sum = |bs: &[Built]| -> Small {
        bs.iter()
            .map(|b| b.beta * Small::from(b.power as i64))
            .sum()
    };
    let mut c = top.constant(exps, beta_sum(&built));
    let point = |s: &Sym| if s.is_pi() { std::f64::consts::PI } else { 0.7 };
    let cv = c.eval_symbols(&|s| Some(point(s))).ok()?;
    let mut out = vec![assemble(&c, &built)?];
    if cv < 0.0 {
        // A negative constant: also with an odd power negated instead, the one whose offset
        // moves least (a difference of a cosine before any offset); the cheaper is kept.
        let pick = built
            .iter()
            .enumerate()
            .filter(|(_, b)| b.power % 2 == 1)
            .filter_map(|(i, b)| b.flip.as_ref().map(|(_, _, cost)| (*cost, i)))
            .min();
        if let Some((_, i)) = pick {
            let (e, beta, _) = built[i].flip.take().expect("a flip");
            built[i].expr = e;
            built[i].beta = beta;
            c = top.constant(exps, beta_sum(&built));
            out.extend(assemble(&c, &built));
        }
    }
    Some(out)
}

/// The constant `c` times the factors' powers.
fn assemble(c: &Scalar, built: &[Built]) -> Option<Expr> {
    let c = c.clone().check().ok()?;
    if c.is_zero_value() {
        return None;
    }
    let mut e = super::closed_form(&c).ok()?;
    for b in built {
        let f = if b.power == 1 {
            b.expr.clone()
        } else {
            Expr::Pow(Box::new(b.expr.clone()), b.power)
        };
        e = mul(e, f);
    }
    Some(e)
}

/// The most terms a scalar may have to be tried as a product of one-angle parts.
const MAX_SEPARABLE_TERMS: usize = 1024;

/// The most symbols the modes of a scalar may hold to be tried as a product of one-angle parts.
const MAX_SEPARABLE_SYMBOLS: usize = 4;

/// The groupings kept per part (the cheapest), so that at most `2^4` products are built.
const KEPT_PER_PART: usize = 2;

/// A term in f64: `v cos(k . X + a)`.
struct Wave {
    v: f64,
    k: Vec<f64>,
    a: f64,
}

/// The value of the waves at `x`.
fn wave_value(ws: &[Wave], x: &[f64]) -> f64 {
    ws.iter()
        .map(|w| w.v * (w.k.iter().zip(x).map(|(k, x)| k * x).sum::<f64>() + w.a).cos())
        .sum()
}

/// Points in `[-3, 3)^n` from a fixed xorshift sequence (only candidates depend on them).
struct Points(u64);

impl Points {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 6.0 - 3.0
    }
    fn point(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.next()).collect()
    }
}

/// Whether the waves are numerically `f(S) g(rest)`, `S` the symbols in `mask`: `p(a1, b1)
/// p(a2, b2) = p(a1, b2) p(a2, b1)` at three sets of points (rank one in the split).
fn splits(ws: &[Wave], n: usize, mask: u32, pts: &mut Points, scale: f64) -> Option<bool> {
    for _ in 0..3 {
        charge((ws.len() / 4 + 1) as u64).ok()?;
        let (a1, a2, b1, b2) = (pts.point(n), pts.point(n), pts.point(n), pts.point(n));
        let at = |a: &[f64], b: &[f64]| -> f64 {
            let x: Vec<f64> = (0..n)
                .map(|i| if mask >> i & 1 == 1 { a[i] } else { b[i] })
                .collect();
            wave_value(ws, &x)
        };
        let d = at(&a1, &b1) * at(&a2, &b2) - at(&a1, &b2) * at(&a2, &b1);
        if d.abs() > 1e-9 * scale * scale {
            return Some(false);
        }
    }
    Some(true)
}

/// Candidates for `t` as a product `f(x) g(y) ...` of one-angle products in disjoint sets of
/// symbols (`sin(x - 5*pi/8) cos(y + 3*pi/8)`, whose expansion has the modes `x - y` and `x +
/// y`, so no look at the modes sees it): the symbols are split where the scalar is numerically
/// of rank one across the split; each part's roots are found as [`found`] finds them, from its
/// restriction to a point of the other symbols (which only moves the constant); the constant
/// is exact, from the scalar's coefficient of the product of the parts' top modes. Empty unless
/// the scalar has a pi offset or a square root, one monomial, at most [`MAX_SEPARABLE_TERMS`]
/// terms and 2 to [`MAX_SEPARABLE_SYMBOLS`] symbols in its modes. The caller checks every
/// candidate exactly.
fn separable(t: &[Term]) -> Option<Vec<Expr>> {
    if !gate(t, MAX_SEPARABLE_TERMS) {
        return None;
    }
    let mut syms: Vec<Sym> = Vec::new();
    for u in t {
        for (s, _) in u.mode.freq.iter() {
            if !syms.contains(s) {
                if syms.len() == MAX_SEPARABLE_SYMBOLS {
                    return None;
                }
                syms.push(s.clone());
            }
        }
    }
    let n = syms.len();
    if n < 2 {
        return None;
    }
    charge(t.len() as u64).ok()?;
    let (ws, w) = waves(t, &syms)?;
    let scale: f64 = ws.iter().map(|w| w.v.abs()).sum();
    let mut pts = Points(0x9E37_79B9_7F4A_7C15);
    let parts = split_parts(&ws, n, &mut pts, scale)?;
    // A point where the scalar is far from 0 (the other parts' values there scale each part).
    let x = (0..4).map(|_| pts.point(n)).max_by(|a, b| {
        wave_value(&ws, a)
            .abs()
            .total_cmp(&wave_value(&ws, b).abs())
    })?;
    if wave_value(&ws, &x).abs() < 1e-3 * scale {
        return None;
    }
    let mut options: Vec<Vec<Vec<Built>>> = Vec::with_capacity(parts.len());
    let mut top: BTreeMap<Sym, Small> = BTreeMap::new();
    for &part in &parts {
        let (found, theta, m) = part_options(t, &syms, &ws, part, &x, w)?;
        options.push(found);
        for (s, c) in theta.iter() {
            top.insert(s.clone(), *c * Small::from_integer(m));
        }
    }
    // The coefficient of e^{i T}, T the sum of the parts' top modes: from the terms of mode T
    // or -T.
    let sign = |u: &Term| -> Option<bool> {
        let f = &u.mode.freq;
        if f.len() != top.len() {
            return None;
        }
        if f.iter().all(|(s, c)| top.get(s) == Some(c)) {
            Some(false)
        } else if f.iter().all(|(s, c)| top.get(s) == Some(&-*c)) {
            Some(true)
        } else {
            None
        }
    };
    let mut top = Top::new(top_of(t.iter().filter_map(|u| sign(u).map(|neg| (u, neg)))));
    let mut out = Vec::new();
    for built in every_choice(&options) {
        charge(1).ok()?;
        out.extend(finish(built, &mut top).unwrap_or_default());
    }
    Some(out)
}

/// The terms as waves over `syms`, and the order `w` of the roots of unity their angles and
/// square roots need.
fn waves(t: &[Term], syms: &[Sym]) -> Option<(Vec<Wave>, i64)> {
    let n = syms.len();
    let mut w: i64 = 24;
    let mut ws = Vec::with_capacity(t.len());
    for u in t {
        w = w.lcm(&(2 * u.mode.pi.denom()));
        if u.rad != 1 {
            w = w.lcm(&(4 * i64::try_from(u.rad).ok()?));
        }
        let psi = if u.mode.sin {
            u.mode.pi - Small::new(1, 2)
        } else {
            u.mode.pi
        };
        let mut k = vec![0.0; n];
        for (s, c) in u.mode.freq.iter() {
            let i = syms.iter().position(|x| x == s)?;
            k[i] = *c.numer() as f64 / *c.denom() as f64;
        }
        ws.push(Wave {
            v: u.coef.to_f64()? * (u.rad as f64).sqrt(),
            k,
            a: std::f64::consts::PI * (*psi.numer() as f64 / *psi.denom() as f64),
        });
    }
    Some((ws, w))
}

/// The finest split of the `n` symbols (as bit masks) across which the waves are of rank one:
/// each symbol's part is the intersection of the sets that split. `None` past the budget.
fn split_parts(ws: &[Wave], n: usize, pts: &mut Points, scale: f64) -> Option<Vec<u32>> {
    let full: u32 = (1 << n) - 1;
    let mut passing = vec![full];
    for mask in (1..full).filter(|m| m & 1 == 1) {
        if splits(ws, n, mask, pts, scale)? {
            passing.extend([mask, full ^ mask]);
        }
    }
    let mut parts: Vec<u32> = Vec::new();
    for i in 0..n {
        let b = passing
            .iter()
            .filter(|m| *m >> i & 1 == 1)
            .fold(full, |acc, m| acc & m);
        if !parts.contains(&b) {
            parts.push(b);
        }
    }
    if parts.len() < 2 {
        return None;
    }
    Some(parts)
}

/// The cheapest groupings of one part's roots (its symbols the bits of `part`), found from the
/// part's polynomial in `z = e^{i theta}` at the point `x` of the other symbols; with the
/// part's angle `theta` and top mode `m`.
#[allow(clippy::type_complexity)]
fn part_options(
    t: &[Term],
    syms: &[Sym],
    ws: &[Wave],
    part: u32,
    x: &[f64],
    w: i64,
) -> Option<(Vec<Vec<Built>>, Vec<(Sym, Small)>, i64)> {
    let n = syms.len();
    charge((t.len() / 4 + 1) as u64).ok()?;
    let inside = |s: &Sym| {
        syms.iter()
            .position(|x| x == s)
            .is_some_and(|i| part >> i & 1 == 1)
    };
    let fs: Vec<Vec<(Sym, Small)>> = t
        .iter()
        .map(|u| {
            u.mode
                .freq
                .iter()
                .filter(|(s, _)| inside(s))
                .cloned()
                .collect()
        })
        .collect();
    let refs: Vec<&[(Sym, Small)]> = fs.iter().map(|f| &f[..]).collect();
    let (theta, ks) = base_of(&refs)?;
    // The angle with a positive first coefficient (`cos(y + pi/9)`, not `cos(-y - pi/9)`).
    let (theta, ks): (Vec<(Sym, Small)>, Vec<i64>) = if theta.first()?.1.is_negative() {
        (
            theta.iter().map(|(s, c)| (s.clone(), -*c)).collect(),
            ks.iter().map(|k| -k).collect(),
        )
    } else {
        (theta.to_vec(), ks)
    };
    let m = ks.iter().map(|k| k.abs()).max()?;
    if !(1..=MAX_DEGREE).contains(&m) {
        return None;
    }
    // The part's polynomial in z = e^{i theta} at the point x of the other symbols.
    let mut p = vec![C(0.0, 0.0); 2 * m as usize + 1];
    for (wave, &k) in ws.iter().zip(&ks) {
        let rest: f64 = (0..n)
            .filter(|i| part >> i & 1 == 0)
            .map(|i| wave.k[i] * x[i])
            .sum::<f64>()
            + wave.a;
        p[(m + k) as usize] = p[(m + k) as usize].add(C::polar(wave.v / 2.0, rest));
        p[(m - k) as usize] = p[(m - k) as usize].add(C::polar(wave.v / 2.0, -rest));
    }
    let half = half_roots(&p, w)?;
    let mut found: Vec<(usize, Vec<Built>)> = groupings(&half)
        .iter()
        .filter_map(|g| built_factors(g, &theta))
        .map(|b| (b.iter().map(|f| f.expr.cost().ops).sum(), b))
        .collect();
    found.sort_by_key(|(c, _)| *c);
    found.truncate(KEPT_PER_PART);
    if found.is_empty() {
        return None;
    }
    Some((found.into_iter().map(|(_, b)| b).collect(), theta, m))
}

/// Every choice of one grouping per part, the parts' factors concatenated.
fn every_choice(options: &[Vec<Vec<Built>>]) -> Vec<Vec<Built>> {
    let mut combos: Vec<Vec<Built>> = vec![Vec::new()];
    for opts in options {
        combos = combos
            .iter()
            .flat_map(|c| {
                opts.iter().map(move |o| {
                    let mut c = c.clone();
                    c.extend(o.iter().cloned());
                    c
                })
            })
            .collect();
    }
    combos
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_denominator_bound_covers_the_degree() {
        assert_eq!(totient(210), 48);
        // phi(n) <= 2 only for n in 1, 2, 3, 4, 6.
        assert_eq!(max_denominator(24, 2), 2 * 24 * 6);
        assert!(max_denominator(168, 48) >= 2 * 168 * 210);
    }

    /// [`group`] as it was before its table: each factor made from its root at each try,
    /// every root looked up in a map, no skip.
    fn group_by_maps(
        roots: &BTreeMap<Small, u32>,
        ks: &[i64],
        kinds: &[u8],
    ) -> Option<BTreeMap<Factor, u32>> {
        let mut left = roots.clone();
        let mut out: BTreeMap<Factor, u32> = BTreeMap::new();
        for &k in ks {
            for &kind in kinds {
                let keys: Vec<Small> = left.keys().copied().collect();
                for r in keys {
                    if !left.contains_key(&r) {
                        continue;
                    }
                    let f = Factor::through(kind, k, r);
                    let need = f.roots();
                    let times = need
                        .iter()
                        .map(|(r, n)| left.get(r).copied().unwrap_or(0) / n)
                        .min()
                        .unwrap_or(0);
                    if times == 0 {
                        continue;
                    }
                    *out.entry(f).or_insert(0) += times;
                    for (r, n) in need {
                        let e = left.get_mut(&r).expect("a root");
                        *e -= n * times;
                        if *e == 0 {
                            left.remove(&r);
                        }
                    }
                }
            }
        }
        left.is_empty().then_some(out)
    }

    #[test]
    fn the_table_groups_as_the_maps_do() {
        // Root sets made of 1 to 4 random factors (shared roots give multiplicities), and the
        // same sets with one root dropped (no grouping then): every multiplier list and
        // order of kinds of `groupings`, against the grouping by maps.
        let mut pts = Points(0x2545_F491_4F6C_DD1D);
        let mut pick = |n: i64| ((pts.next() + 3.0) / 6.0 * n as f64) as i64 % n;
        let (mut grouped, mut cases) = (0, 0);
        for case in 0..300 {
            let mut half: BTreeMap<Small, u32> = BTreeMap::new();
            for _ in 0..1 + pick(4) {
                let k = 1 + pick(3);
                let d = [1, 2, 3, 4, 5, 6, 8, 10, 12][pick(9) as usize];
                let f = Factor::through(pick(3) as u8, k, Small::new(pick(2 * d), d));
                for (r, n) in f.roots() {
                    *half.entry(r).or_insert(0) += n;
                }
            }
            if case % 5 == 4 {
                let r = *half.keys().next().expect("a root");
                half.remove(&r);
            }
            let kmax = i64::from(half.values().sum::<u32>() / 2);
            let descending: Vec<i64> = (1..=kmax).rev().collect();
            let mut table = Table::new(&half, kmax.max(2) as usize);
            for ks in [&descending[..], &[2, 1], &[1]] {
                for order in KIND_ORDERS {
                    let want = group_by_maps(&half, ks, &order);
                    assert_eq!(group(&half, ks, &order, &mut table), want, "{half:?}");
                    cases += 1;
                    grouped += usize::from(want.is_some());
                }
            }
        }
        // Both answers occur: most sets group, the ones short of a root do not.
        assert_eq!(cases, 300 * 18);
        assert!(
            grouped > cases / 2 && grouped < cases,
            "{grouped} of {cases}"
        );
    }

    #[test]
    fn a_constant_made_once_is_the_constant_made_again() {
        // Top coefficients `re + i im` with parts in Q(zeta_24) (a rational plus a rational
        // times a cosine or sine of a multiple of pi/12), the constants asked for at random
        // (E, B) pairs, repeats included: each equals the constant made afresh and its value
        // 2^E (re cos(B pi) + im sin(B pi)) in floats; each pair is made once.
        let mut pts = Points(0x9E37_79B9_7F4A_7C15);
        let mut pick = |n: i64| ((pts.next() + 3.0) / 6.0 * n as f64) as i64 % n;
        let part = |pick: &mut dyn FnMut(i64) -> i64| {
            let q = |a: i64, b: i64| {
                Scalar::rational(num_rational::BigRational::new(a.into(), b.into()))
            };
            q(pick(9) - 4, 1 + pick(4))
                + q(pick(9) - 4, 1 + pick(4))
                    * Scalar::trig_of_parts(pick(2) == 1, Vec::new(), Small::new(pick(24), 12))
        };
        let (mut asked, mut hits) = (0, 0);
        for _ in 0..40 {
            let (re, im) = (part(&mut pick), part(&mut pick));
            let value = |x: &Scalar| x.eval(&|_| None).expect("a constant");
            let (rv, iv) = (value(&re), value(&im));
            let mut top = Top::new((re.clone(), im.clone()));
            let mut pairs: Vec<(u64, Small)> = Vec::new();
            for _ in 0..12 {
                let (exps, b) = (pick(3) as u64, Small::new(pick(12) - 6, 12));
                let c = top.constant(exps, b);
                assert_eq!(c, constant_of(&re, &im, exps, b), "{exps} {b}");
                let pi = std::f64::consts::PI * (*b.numer() as f64 / *b.denom() as f64);
                let want = 2f64.powi(exps as i32) * (rv * pi.cos() + iv * pi.sin());
                assert!(
                    (value(&c) - want).abs() < 1e-9 * (1.0 + want.abs()),
                    "{c:?} {want}"
                );
                hits += usize::from(pairs.contains(&(exps, b)));
                if !pairs.contains(&(exps, b)) {
                    pairs.push((exps, b));
                }
                asked += 1;
            }
            assert_eq!(top.made.len(), pairs.len());
        }
        // Repeats were asked for (the memo was read), and new pairs too.
        assert_eq!(asked, 480);
        assert!(hits > 10 && hits < asked / 2, "{hits} of {asked}");
    }

    #[test]
    fn aberth_finds_a_double_root_on_the_unit_circle() {
        // (z - i)^2 (z + 1) = z^3 + (1 - 2i) z^2 + (-1 - 2i) z - 1.
        let p = [C(-1.0, 0.0), C(-1.0, -2.0), C(1.0, -2.0), C(1.0, 0.0)];
        let zs = aberth(&p).expect("roots");
        let roots = unit_roots(&p, &zs, 100).expect("on the circle");
        assert_eq!(roots.get(&Small::new(1, 2)), Some(&2));
        assert_eq!(roots.get(&Small::one()), Some(&1));
        assert!(factorization_agrees(&p, &roots));
    }
}
