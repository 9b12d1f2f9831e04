//! Linear algebra modulo the prime `P = 2^61 - 1`, and rational reconstruction: the fast
//! path of the cyclotomic bases (`cyclo/`). Nothing computed here is trusted on its own:
//! - columns independent modulo `P` are independent over `Q` (a nonzero minor modulo `P` is
//!   nonzero), so a set found independent here is independent;
//! - a dependence, or coordinates, found here are read back as small rationals and then
//!   checked exactly by the caller; when that fails the caller takes the exact dense path.

#[cfg(test)]
use num_bigint::BigInt;
#[cfg(test)]
use num_rational::BigRational as Rat;
#[cfg(test)]
use num_traits::ToPrimitive;

pub(crate) const P: u64 = (1 << 61) - 1;

fn fold(r: u128) -> u64 {
    let s = (r as u64 & P) + (r >> 61) as u64;
    let s = if s >= P { s - P } else { s };
    if s >= P {
        s - P
    } else {
        s
    }
}

pub(crate) fn mul(a: u64, b: u64) -> u64 {
    fold(a as u128 * b as u128)
}

pub(crate) fn add(a: u64, b: u64) -> u64 {
    let s = a + b;
    if s >= P {
        s - P
    } else {
        s
    }
}

pub(crate) fn sub(a: u64, b: u64) -> u64 {
    if a >= b {
        a - b
    } else {
        a + P - b
    }
}

fn pow(mut b: u64, mut e: u64) -> u64 {
    let mut r = 1;
    while e > 0 {
        if e & 1 == 1 {
            r = mul(r, b);
        }
        b = mul(b, b);
        e >>= 1;
    }
    r
}

pub(crate) fn inv(a: u64) -> u64 {
    pow(a, P - 2)
}

fn from_i64(x: i64) -> u64 {
    if x >= 0 {
        x as u64 % P
    } else {
        sub(0, x.unsigned_abs() % P)
    }
}

#[cfg(test)]
fn from_big(x: &BigInt) -> u64 {
    let m = BigInt::from(P);
    let r = ((x % &m) + &m) % &m;
    r.to_u64().unwrap_or(0)
}

/// A rational modulo `P`; `None` when `P` divides its denominator (the reference of the
/// fast path's tests: it computes in machine words).
#[cfg(test)]
pub(crate) fn from_rat(x: &Rat) -> Option<u64> {
    if let (Some(n), Some(d)) = (x.numer().to_i64(), x.denom().to_i64()) {
        let n = from_i64(n);
        return match d {
            1 => Some(n),
            // 1/2 = (P + 1)/2.
            2 => Some(mul(n, P.div_ceil(2))),
            _ => {
                let d = from_i64(d);
                (d != 0).then(|| mul(n, inv(d)))
            }
        };
    }
    let d = from_big(x.denom());
    (d != 0).then(|| mul(from_big(x.numer()), inv(d)))
}

/// Half of a doubled integer `c2` modulo `P` (a coefficient of `Z[zeta_W] / 2` kept doubled):
/// the residue `from_rat` gives `c2 / 2`, whose reduced form is `(c2 / 2) / 1` or `c2 / 2`.
pub(crate) fn from_doubled(c2: i64) -> u64 {
    if c2 % 2 == 0 {
        from_i64(c2 / 2)
    } else {
        mul(from_i64(c2), P.div_ceil(2))
    }
}

/// The rational `n/d` with `|n|, d < 2^30` that is `a` modulo `P`, when there is one: reduced,
/// `d > 0` (`(0, 1)` for zero), in machine words.
pub(crate) fn reconstruct(a: u64) -> Option<(i64, i64)> {
    if a == 0 {
        return Some((0, 1));
    }
    const B: i64 = 1 << 30;
    // In `i64`: the remainders are below `P < 2^61`, and `|t_k| <= P / r_{k-1}` (so is
    // `q t1` less the previous `t0`, both below `2^61`).
    let (mut r0, mut r1) = (P as i64, a as i64);
    let (mut t0, mut t1) = (0i64, 1i64);
    while r1 >= B {
        let q = r0 / r1;
        (r0, r1) = (r1, r0 - q * r1);
        (t0, t1) = (t1, t0 - q * t1);
    }
    if t1 == 0 || t1.abs() >= B {
        return None;
    }
    // Both below 2^30 in size: `r1 / t1` reduced with its denominator made positive, the
    // value `Ratio::new` gave (this built a `BigRational` per coordinate before).
    let g = super::q::gcd_u64(r1.unsigned_abs(), t1.unsigned_abs()) as i64;
    let (mut n, mut d) = (r1 / g, t1 / g);
    if d < 0 {
        (n, d) = (-n, -d);
    }
    // `n / d = a` exactly when `n = a d` (`d` is invertible modulo `P`): the check
    // `from_rat(n / d) == Some(a)` without its inverse (a power by `P - 2`).
    (from_i64(n) == mul(a, from_i64(d))).then_some((n, d))
}

/// A pivot row: its pivot, the row scaled to 1 at the pivot, and the combination of the
/// columns it is (dense over the columns pushed before it and itself).
type Row = (usize, Vec<u64>, Vec<u64>);

/// A subspace of `F_P^n` spanned by columns added one at a time, in echelon form.
pub(crate) struct ModSpan {
    pub(crate) cols: usize,
    rows: Vec<Row>,
}

impl ModSpan {
    pub(crate) fn new() -> ModSpan {
        ModSpan {
            cols: 0,
            rows: Vec::new(),
        }
    }

    pub(crate) fn rank(&self) -> usize {
        self.rows.len()
    }

    /// Reduces `v` in place; the multiple of each pivot row taken away.
    fn reduce(&self, v: &mut [u64]) -> Vec<u64> {
        let mut lambdas = Vec::with_capacity(self.rows.len());
        for (p, row, _) in &self.rows {
            let l = v[*p];
            lambdas.push(l);
            if l == 0 {
                continue;
            }
            for (x, r) in v.iter_mut().zip(row).skip(*p) {
                if *r != 0 {
                    *x = sub(*x, mul(l, *r));
                }
            }
        }
        lambdas
    }

    /// The combination of columns that the pivot rows times `lambdas` are.
    fn combine(&self, lambdas: &[u64], cols: usize) -> Vec<u64> {
        let mut out = vec![0u64; cols];
        for (l, (_, _, c)) in lambdas.iter().zip(&self.rows) {
            if *l == 0 {
                continue;
            }
            for (o, x) in out.iter_mut().zip(c) {
                if *x != 0 {
                    *o = add(*o, mul(*l, *x));
                }
            }
        }
        out
    }

    /// Adds a column; false when it depends on the others (it is then not recorded).
    pub(crate) fn push(&mut self, mut v: Vec<u64>) -> bool {
        let lambdas = self.reduce(&mut v);
        let Some(p) = v.iter().position(|x| *x != 0) else {
            return false;
        };
        let col = self.cols;
        let mut comb = self.combine(&lambdas, col + 1);
        for x in comb.iter_mut() {
            *x = sub(0, *x);
        }
        comb[col] = 1;
        let s = inv(v[p]);
        for x in v.iter_mut().chain(comb.iter_mut()) {
            *x = mul(*x, s);
        }
        self.rows.push((p, v, comb));
        self.cols += 1;
        true
    }

    /// The coordinates of `v` on the columns, or `None` when `v` is not in the span.
    pub(crate) fn solve(&self, mut v: Vec<u64>) -> Option<Vec<u64>> {
        let lambdas = self.reduce(&mut v);
        if v.iter().any(|x| *x != 0) {
            return None;
        }
        Some(self.combine(&lambdas, self.cols))
    }
}

/// The reconstruction as it was, in `BigRational`: the reference of the tests of the
/// machine-word [`reconstruct`] (here and in `cyclo/fast.rs`).
#[cfg(test)]
pub(crate) fn reconstruct_big(a: u64) -> Option<Rat> {
    if a == 0 {
        return Some(Rat::from_integer(0.into()));
    }
    const B: i128 = 1 << 30;
    let (mut r0, mut r1) = (P as i128, a as i128);
    let (mut t0, mut t1) = (0i128, 1i128);
    while r1 >= B {
        let q = r0 / r1;
        (r0, r1) = (r1, r0 - q * r1);
        (t0, t1) = (t1, t0 - q * t1);
    }
    if t1 == 0 || t1.abs() >= B {
        return None;
    }
    let x = Rat::new(BigInt::from(r1), BigInt::from(t1));
    (from_rat(&x) == Some(a)).then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reconstruction_reads_small_rationals_back() {
        for (n, d) in [
            (1, 2),
            (-3, 7),
            (123456, 789),
            (-1, 1),
            (0, 1),
            (1 << 29, 3),
        ] {
            let x = Rat::new(n.into(), d.into());
            let a = from_rat(&x).expect("denominator prime to P");
            let back = reconstruct(a).map(|(n, d)| Rat::new_raw(n.into(), d.into()));
            assert_eq!(back, Some(x));
        }
        assert_eq!(from_rat(&Rat::new(1.into(), BigInt::from(P))), None);
    }

    /// The machine-word reconstruction is the `BigRational` one, numerator and denominator,
    /// for random residues (about half of them are small fractions), the residues of random
    /// small fractions and the ends of the range.
    #[test]
    fn reconstruction_in_machine_words_is_the_big_one() {
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let (mut found, mut none) = (0, 0);
        for i in 0..60_000u64 {
            let a = match i % 3 {
                0 => next() % P,
                1 => {
                    let (n, d) = ((next() % (1 << 31)) as i64 - (1 << 30), next() % (1 << 30));
                    from_rat(&Rat::new(n.into(), (d.max(1) as i64).into())).expect("d < P")
                }
                _ => [
                    0,
                    1,
                    2,
                    P - 1,
                    P - 2,
                    (1 << 30) - 1,
                    1 << 30,
                    P / 2,
                    P / 2 + 1,
                ][(i % 9) as usize],
            };
            let small = reconstruct(a);
            let big = reconstruct_big(a).map(|x| {
                let (n, d) = (x.numer().to_i64(), x.denom().to_i64());
                (n.expect("small"), d.expect("small"))
            });
            assert_eq!(small, big, "{a}");
            if small.is_some() {
                found += 1;
            } else {
                none += 1;
            }
        }
        assert!(found > 30_000 && none > 5_000, "{found} {none}");
    }

    #[test]
    fn span_solves_what_it_spans() {
        let mut s = ModSpan::new();
        assert!(s.push(vec![1, 2, 0]));
        assert!(s.push(vec![0, 1, 1]));
        assert!(!s.push(vec![2, 5, 1]));
        // 3 (1, 2, 0) - (0, 1, 1) = (3, 5, -1).
        let v = vec![3, 5, sub(0, 1)];
        assert_eq!(s.solve(v), Some(vec![3, sub(0, 1)]));
        assert_eq!(s.solve(vec![0, 0, 1]), None);
    }
}
