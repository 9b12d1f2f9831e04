//! `Q(zeta_W)`: its elements as sparse sums of powers of `zeta_W`, their reduction to the
//! power basis and to the tensor basis (exactly, and modulo a prime), the square roots the
//! field contains, and the per-process cache of fields.

use super::super::modp;
use super::super::par::{this_fork, PerFork};
use super::super::{FxHasher, ScalarError};
use super::level::{moebius, primes_of, totient};
use super::{poisoned, Cache};
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational as Rat;
use num_traits::{One, ToPrimitive, Zero};
use std::cell::RefCell;
use std::collections::{BTreeMap, HashMap};
use std::hash::BuildHasherDefault;
#[cfg(all(test, unix))]
use std::sync::Mutex;
use std::sync::{Arc, OnceLock};

/// An element of `Q(zeta_W)` as a sum of powers of `zeta_W` (exponents mod `W`).
pub(super) type Sparse = BTreeMap<u64, Rat>;

/// The same with integer coefficients, doubled (every basis vector is in `Z[zeta_W] / 2`): by
/// increasing exponent, no zero coefficient. The fast path computes in this form (machine
/// words: a `BigRational` per coefficient made the bases cost 2.4 M instructions of the
/// Jaco-style arm's `fk --jacobian`).
pub(super) type Ints = Vec<(u64, i64)>;

/// The same with integer coefficients, not doubled (the square roots of [`Field::roots`]).
pub(super) type Integral = Vec<(u64, i64)>;

/// The most a coefficient of [`Field::roots`] may be in size: a product by a value of at most
/// two terms with doubled coefficients of size at most 2 (a candidate, a unit's trigonometric
/// part) then has doubled coefficients of at most `2^62` in size, in `i64` (each exponent of the product
/// is met once per term of that value).
const ROOT_BOUND: i64 = 1 << 60;

/// `a b` for `a` with integer coefficients and `b` doubled: the product, doubled. `None` when a
/// coefficient leaves `i64` (never for `a` a root of [`Field::roots`] and `b` of at most two
/// terms of size at most 2: see [`ROOT_BOUND`]). `b` may be in any order and repeat an
/// exponent (a unit's trigonometric part at angle 0, or a sine's): the product sums every
/// pair's term, and is an [`Ints`] (sorted, no zero coefficient) whatever `b`'s order.
pub(super) fn ints_mul(a: &[(u64, i64)], b: &[(u64, i64)], w: u64) -> Option<Ints> {
    let mut acc = vec![0i128; w as usize];
    for (i, x) in a {
        for (j, y) in b {
            let t = &mut acc[((i + j) % w) as usize];
            *t = t.checked_add(i128::from(*x) * i128::from(*y))?;
        }
    }
    acc.iter()
        .enumerate()
        .filter(|(_, c)| **c != 0)
        .map(|(e, c)| i64::try_from(*c).ok().map(|c| (e as u64, c)))
        .collect()
}

/// The value of doubled coefficients (the exact path's form).
pub(super) fn halves(s: &Ints) -> Sparse {
    s.iter()
        .map(|(e, c2)| (*e, Rat::new((*c2).into(), 2.into())))
        .collect()
}

pub(super) fn sparse_mul(a: &Sparse, b: &Sparse, w: u64) -> Sparse {
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

pub(super) fn mono(e: u64, c: Rat) -> Sparse {
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
pub(super) struct Field {
    pub(super) w: u64,
    pub(super) phi: usize,
    /// The cyclotomic polynomial, coefficients from the constant term.
    pub(super) poly: Vec<i64>,
    /// `red[k]`: `x^k` modulo the cyclotomic polynomial, `k < W` (the exact path only).
    pub(super) red: OnceLock<Option<Vec<Vec<i64>>>>,
    /// The prime powers `(q, p)` of `W`; axis `i` has stride `q_0 ... q_{i-1}`.
    pub(super) axes: Vec<(u64, u64)>,
    /// The position of `zeta_W^e` in the tensor layout, for each exponent `e`.
    pub(super) slot: Vec<u32>,
    /// The reduced positions (every digit below `phi(q)`), in order: the coordinates.
    pub(super) kept: Vec<u32>,
    /// The primes `p` with `sqrt(p)` in the field (odd divisors of `W`, 2 when 8 divides `W`).
    pub(super) allowed: Vec<u64>,
    /// Every square-free product `h` of allowed primes with `sqrt(h)`.
    pub(super) sqrts: Vec<(u64, Sparse)>,
    /// The same square roots (in the same order) in machine words, for the fast path. Their
    /// coefficients are `0` and `+-1` (a product of Gauss sums of coprime orders, the `i` of a
    /// prime `3 mod 4` a shift: every exponent of the product is met once), so this is never
    /// `None`; were a coefficient past [`ROOT_BOUND`], the fast path would leave the field to
    /// the exact one.
    pub(super) roots: Option<Vec<Integral>>,
}

pub(super) fn legendre(a: u64, p: u64) -> i64 {
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
    pub(super) fn new(w: u64) -> Option<Field> {
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
        let roots = sqrts
            .iter()
            .map(|(_, s)| {
                s.iter()
                    .map(|(e, c)| {
                        let c = c.is_integer().then(|| c.to_integer().to_i64()).flatten()?;
                        (c.abs() <= ROOT_BOUND).then_some((*e, c))
                    })
                    .collect::<Option<Integral>>()
            })
            .collect();
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
            roots,
        })
    }

    /// The power-basis reduction of every power of `zeta_W` (charged on first use).
    pub(super) fn red(&self) -> Result<&Vec<Vec<i64>>, ScalarError> {
        if self.red.get().is_none() {
            super::super::charge(self.w.saturating_mul(self.phi as u64))?;
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

    pub(super) fn reduce(&self, s: &Sparse) -> Result<Vec<Rat>, ScalarError> {
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
    pub(super) fn crt_reduce<T: Copy + PartialEq>(
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

    /// `s` (doubled) in the tensor basis modulo [`modp::P`]: the residues
    /// `Field::reduce_mod` (the tests' reference) gives its value.
    pub(super) fn reduce_mod_ints(&self, s: &Ints) -> Vec<u64> {
        let mut a = vec![0u64; self.w as usize];
        for (e, c2) in s {
            let t = &mut a[self.slot[*e as usize] as usize];
            *t = modp::add(*t, modp::from_doubled(*c2));
        }
        // Subtraction modulo `P` never fails.
        let _ = self.crt_reduce(&mut a, 0, |x, y| Some(modp::sub(x, y)));
        self.kept.iter().map(|&k| a[k as usize]).collect()
    }

    /// `s` in the tensor basis modulo [`modp::P`]; `None` when `P` divides a denominator.
    #[cfg(test)]
    pub(super) fn reduce_mod(&self, s: &Sparse) -> Option<Vec<u64>> {
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
    pub(super) fn combination_is(
        &self,
        xs: &[(usize, Rat)],
        vs: &[Ints],
        t: &Sparse,
    ) -> Option<bool> {
        let mut d = BigInt::from(2);
        for (_, x) in xs {
            d = d.lcm(x.denom());
        }
        for c in t.values() {
            d = d.lcm(c.denom());
        }
        let mut acc = vec![0i128; self.w as usize];
        for (j, x) in xs {
            // (d x) (2 v) = 2 d (x v); `d x` read off the numerator, `d` a multiple of the
            // denominator (a product of rationals reduced its result by big-integer gcds).
            let k = x.numer() * (&d / x.denom());
            let k = k.to_i128()?;
            for (e, c2) in &vs[*j] {
                let a = &mut acc[self.slot[*e as usize] as usize];
                *a = a.checked_add(k.checked_mul(i128::from(*c2))?)?;
            }
        }
        let d2 = BigInt::from(2) * &d;
        for (e, c) in t {
            let k = c.numer() * (&d2 / c.denom());
            let a = &mut acc[self.slot[*e as usize] as usize];
            *a = a.checked_sub(k.to_i128()?)?;
        }
        self.crt_reduce(&mut acc, 0, |x, y| x.checked_sub(y))?;
        Some(acc.iter().all(|a| *a == 0))
    }

    /// [`Field::combination_is`] for coordinates `x_j = n / d` in machine words (reduced,
    /// `d > 0`) and a doubled `t`, in 128 bits: the same products and sums, each overflowing
    /// exactly when the big-integer ones leave `i128` there. Only the common denominator `d`
    /// is formed differently (past `i128` the big-integer route decides).
    pub(super) fn combination_is_ints(
        &self,
        xs: &[(usize, (i64, i64))],
        vs: &[Ints],
        t: &Ints,
    ) -> Option<bool> {
        // `t`'s denominators (1 and 2) divide the 2 `d` starts at.
        let mut d: i128 = 2;
        for (_, (_, den)) in xs {
            let den = i128::from(*den);
            let g = super::super::q::gcd_u64(den as u64, (d % den) as u64);
            match (d / i128::from(g)).checked_mul(den) {
                Some(l) => d = l,
                None => {
                    let xs: Vec<(usize, Rat)> = xs
                        .iter()
                        .map(|(j, (n, den))| (*j, Rat::new((*n).into(), (*den).into())))
                        .collect();
                    return self.combination_is(&xs, vs, &halves(t));
                }
            }
        }
        let mut acc = vec![0i128; self.w as usize];
        for (j, (n, den)) in xs {
            // `n (d / den)`: the big-integer route's `d x`, `None` where its `to_i128` was.
            let k = i128::from(*n).checked_mul(d / i128::from(*den))?;
            for (e, c2) in &vs[*j] {
                let a = &mut acc[self.slot[*e as usize] as usize];
                *a = a.checked_add(k.checked_mul(i128::from(*c2))?)?;
            }
        }
        for (e, c2) in t {
            // `(2 d) c = d c2` for `c = c2 / 2`.
            let k = i128::from(*c2).checked_mul(d)?;
            let a = &mut acc[self.slot[*e as usize] as usize];
            *a = a.checked_sub(k)?;
        }
        self.crt_reduce(&mut acc, 0, |x, y| x.checked_sub(y))?;
        Some(acc.iter().all(|a| *a == 0))
    }

    pub(super) fn sqrt(&self, h: u64) -> &Sparse {
        let i = self
            .sqrts
            .binary_search_by_key(&h, |(x, _)| *x)
            .expect("h is a product of allowed primes");
        &self.sqrts[i].1
    }

    /// `d = s h`: `h` the part of the square-free `d` whose square root is in the field.
    pub(super) fn split(&self, d: u64) -> (u64, u64) {
        let h: u64 = self
            .allowed
            .iter()
            .filter(|&&p| d.is_multiple_of(p))
            .product();
        (d / h, h)
    }
}

/// The exact value of a column, doubled into integers (`None` past `i64`).
#[cfg(test)]
pub(super) fn ints(s: &Sparse) -> Option<Ints> {
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

/// `Q(zeta_W)`, computed once per process (its work charged to the context that builds it);
/// the ones a thread used are kept by the thread, looked up without a lock.
pub(super) fn field(w: u64) -> Result<Arc<Field>, ScalarError> {
    type Fields = HashMap<u64, Arc<Field>, BuildHasherDefault<FxHasher>>;
    thread_local! {
        // With the fork count it was filled at: a forked child empties it ([`PerFork`]).
        static FIELDS: RefCell<(u64, Fields)> = RefCell::new((0, Fields::default()));
    }
    if let Some(f) = FIELDS.with(|c| this_fork(&mut c.borrow_mut()).get(&w).cloned()) {
        return Ok(f);
    }
    let f = shared_field(w)?;
    FIELDS.with(|c| this_fork(&mut c.borrow_mut()).insert(w, f.clone()));
    Ok(f)
}

/// The fields made in this process (made again in a forked child).
static SHARED_FIELDS: Cache<u64, Field> = PerFork::new();

/// [`field`] from the process-wide cache.
pub(super) fn shared_field(w: u64) -> Result<Arc<Field>, ScalarError> {
    let cache = SHARED_FIELDS.get_or(Default::default);
    if let Some(f) = cache.lock().map_err(poisoned)?.get(&w) {
        return Ok(f.clone());
    }
    super::super::charge(w)?;
    let f = Arc::new(Field::new(w).ok_or_else(|| {
        ScalarError::OutOfRange(format!("the cyclotomic polynomial of order {w}"))
    })?);
    cache.lock().map_err(poisoned)?.insert(w, f.clone());
    Ok(f)
}

#[cfg(all(test, unix))]
mod fork_tests {
    use super::*;
    use crate::Scalar;

    /// `cos(k pi / n)`.
    fn cos_pi(k: i64, n: i64) -> Scalar {
        (&Scalar::pi() * &Scalar::rational(Rat::new(k.into(), n.into()))).cos()
    }

    /// `cos(a pi / n) cos(b pi / n)`, as a product and as half the sum of
    /// `cos((a - b) pi / n)` and `cos((a + b) pi / n)`.
    fn both_ways(a: i64, b: i64, n: i64) -> (Scalar, Scalar) {
        let sum = &cos_pi(a - b, n) + &cos_pi(a + b, n);
        (
            &cos_pi(a, n) * &cos_pi(b, n),
            &sum * &Scalar::rational(Rat::new(1.into(), 2.into())),
        )
    }

    /// A child forked while another thread of the parent holds the process-wide field cache
    /// (here: this thread, through the fork) makes fields of its own: before, it waited
    /// forever on the lock. Its per-thread cache, filled in the parent, is emptied too.
    #[test]
    fn a_forked_child_makes_its_own_fields() {
        let (product, sum) = both_ways(1, 2, 7);
        assert_eq!(product, sum);
        let held = SHARED_FIELDS.get_or(Default::default).lock().unwrap();
        let parents: *const Mutex<_> = SHARED_FIELDS.get_or(Default::default);
        super::super::super::par::in_forked_child(
            || {
                let own: *const Mutex<_> = SHARED_FIELDS.get_or(Default::default);
                // Q(zeta_7) again, and Q(zeta_11), which this process has not made before.
                let (p7, s7) = both_ways(1, 2, 7);
                let (p11, s11) = both_ways(1, 2, 11);
                !std::ptr::eq(own, parents) && p7 == product && p7 == s7 && p11 == s11
            },
            move || drop(held),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rng(seed: u64) -> impl FnMut() -> u64 {
        let mut x = seed;
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        }
    }

    /// The machine-word product is the `BigRational` one doubled, for random sparse values
    /// of every size of coefficient up to the end of `i64` (`None` exactly when a doubled
    /// coefficient of the product leaves it).
    #[test]
    fn machine_word_products_are_the_big_ones() {
        let mut next = rng(0x1234_5678_9abc_def1);
        let (mut some, mut none) = (0, 0);
        for i in 0..4000 {
            let w = 24 * (1 + next() % 6);
            let bits = [2, 20, 40, 62][i % 4];
            let coef = |n: &mut dyn FnMut() -> u64| (n() % (1 << bits)) as i64 - (1 << (bits - 1));
            let a: Integral = (0..1 + next() % 12)
                .map(|_| (next() % w, coef(&mut next)))
                .collect::<BTreeMap<_, _>>()
                .into_iter()
                .collect();
            let b: Ints = (0..1 + next() % 3)
                .map(|_| (next() % w, coef(&mut next)))
                .collect::<BTreeMap<_, _>>()
                .into_iter()
                .collect();
            let ra: Sparse = a
                .iter()
                .map(|(e, c)| (*e, Rat::from_integer((*c).into())))
                .collect();
            let reference = ints(&sparse_mul(&ra, &halves(&b), w));
            let product = ints_mul(&a, &b, w);
            assert_eq!(product, reference, "{a:?} {b:?}");
            if product.is_some() {
                some += 1;
            } else {
                none += 1;
            }
        }
        assert!(some > 1500 && none > 200, "{some} {none}");
    }

    /// The machine-word check of a combination is the big-integer one, for random
    /// coordinates (small and large denominators: their common multiple past `i128` too),
    /// random doubled vectors and targets that are the combination or are not.
    #[test]
    fn machine_word_combinations_are_the_big_ones() {
        let mut next = rng(0x0ddb_a11c_afe0_0042);
        let f = Field::new(72).expect("field");
        let primes = [
            1_000_003i64,
            998_244_353,
            1_000_000_007,
            1_073_741_789,
            999_999_937,
        ];
        let mut seen = BTreeMap::new();
        for i in 0..3000 {
            let n = 1 + next() as usize % 6;
            let vs: Vec<Ints> = (0..n)
                .map(|_| {
                    (0..1 + next() % 5)
                        .map(|_| (next() % 72, (next() % 9) as i64 - 4))
                        .collect::<BTreeMap<_, _>>()
                        .into_iter()
                        .filter(|(_, c)| *c != 0)
                        .collect()
                })
                .collect();
            let xs: Vec<(usize, (i64, i64))> = (0..n)
                .map(|j| {
                    let d = match i % 3 {
                        0 => 1 + (next() % 4) as i64,
                        1 => primes[next() as usize % primes.len()],
                        _ => 1 + (next() % (1 << 29)) as i64,
                    };
                    let q = Rat::new(((next() % (1 << 20)) as i64 - (1 << 19)).into(), d.into());
                    let (n, d) = (
                        q.numer().to_i64().expect("small"),
                        q.denom().to_i64().expect("small"),
                    );
                    (j, (n, d))
                })
                .filter(|(_, (n, _))| *n != 0)
                .collect();
            // The combination's value, doubled where it is in Z / 2; perturbed every other time.
            let mut sum: Sparse = Sparse::new();
            for (j, (n, d)) in &xs {
                for (e, c2) in &vs[*j] {
                    *sum.entry(*e).or_insert_with(Rat::zero) +=
                        Rat::new((*n).into(), (*d).into()) * Rat::new((*c2).into(), 2.into());
                }
            }
            let mut t: Ints = sum
                .iter()
                .filter(|(_, c)| !c.is_zero())
                .map(|(e, c)| {
                    (
                        *e,
                        (c * Rat::from_integer(2.into()))
                            .round()
                            .to_integer()
                            .to_i64()
                            .unwrap_or(1),
                    )
                })
                .filter(|(_, c)| *c != 0)
                .collect();
            if i % 2 == 1 {
                t.push((71, 1 + (next() % 3) as i64));
                t = t
                    .into_iter()
                    .collect::<BTreeMap<_, _>>()
                    .into_iter()
                    .collect();
            }
            let big: Vec<(usize, Rat)> = xs
                .iter()
                .map(|(j, (n, d))| (*j, Rat::new((*n).into(), (*d).into())))
                .collect();
            let reference = f.combination_is(&big, &vs, &halves(&t));
            let small = f.combination_is_ints(&xs, &vs, &t);
            assert_eq!(small, reference, "{xs:?} {vs:?} {t:?}");
            *seen.entry(format!("{small:?}")).or_insert(0) += 1;
        }
        // Some answers of every kind: shown, refuted, and overflowing (undecided).
        assert!(
            seen.len() == 3 && seen.values().all(|n| *n > 50),
            "{seen:?}"
        );
    }
}
