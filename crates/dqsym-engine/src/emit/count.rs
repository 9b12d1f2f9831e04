//! Operation counts of products (Tables 1 and 2 of the paper, with ERRATA items 10 and 11) and
//! of generated code.
//!
//! A product is counted by running it: [`Counted`] is an f64 that implements [`Ring`] and
//! records every `+`, `-`, `*`, negation and sin/cos done on it in thread-local counters, so a
//! count is what the algorithm does, never a number written down.

use super::codegen::{lower, CodegenError, CodegenOptions, OpCount, Output};
use crate::{DualQuat, Matrix4, Quat, Ring};
use num_traits::{One, Zero};
use std::cell::Cell;
use std::ops::{Add, Mul, Neg, Sub};

thread_local! {
    static COUNT: Cell<OpCount> = const { Cell::new(OpCount { mul: 0, add: 0, neg: 0, trig: 0 }) };
}

/// Records one addition or subtraction. (Counting lives outside the operator impls, where
/// clippy would read the counter's `+=` as a suspicious operator.)
fn tick_add() {
    bump(|c| c.add += 1);
}

fn tick_mul() {
    bump(|c| c.mul += 1);
}

fn bump(f: impl FnOnce(&mut OpCount)) {
    COUNT.with(|c| {
        let mut v = c.get();
        f(&mut v);
        c.set(v);
    });
}

/// An f64 that counts the operations done on it (see [`count_ops`]).
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd, Default)]
pub struct Counted(pub f64);

/// Runs `f` and returns its result with the operations it did on [`Counted`] values (on this
/// thread). Constants (`zero`, `one`, `from_ratio`) are free.
pub fn count_ops<R>(f: impl FnOnce() -> R) -> (R, OpCount) {
    let before = COUNT.with(|c| c.replace(OpCount::default()));
    let r = f();
    let n = COUNT.with(|c| c.replace(before));
    (r, n)
}

/// What the code generated for `outputs` costs to evaluate (as `rust_function` would write it:
/// shared subexpressions counted once).
///
/// # Errors
/// As [`rust_function`](crate::emit::rust_function).
pub fn generated_ops(
    outputs: &[Output],
    args: &[String],
    o: &CodegenOptions,
) -> Result<OpCount, CodegenError> {
    Ok(lower(outputs, args, o)?.count())
}

impl Add for Counted {
    type Output = Counted;
    fn add(self, b: Counted) -> Counted {
        tick_add();
        Counted(self.0 + b.0)
    }
}

impl Sub for Counted {
    type Output = Counted;
    fn sub(self, b: Counted) -> Counted {
        tick_add();
        Counted(self.0 - b.0)
    }
}

impl Mul for Counted {
    type Output = Counted;
    fn mul(self, b: Counted) -> Counted {
        tick_mul();
        Counted(self.0 * b.0)
    }
}

impl Neg for Counted {
    type Output = Counted;
    fn neg(self) -> Counted {
        bump(|c| c.neg += 1);
        Counted(-self.0)
    }
}

impl<'a> Add<&'a Counted> for Counted {
    type Output = Counted;
    fn add(self, b: &'a Counted) -> Counted {
        self + *b
    }
}

impl<'a> Sub<&'a Counted> for Counted {
    type Output = Counted;
    fn sub(self, b: &'a Counted) -> Counted {
        self - *b
    }
}

impl<'a> Mul<&'a Counted> for Counted {
    type Output = Counted;
    fn mul(self, b: &'a Counted) -> Counted {
        self * *b
    }
}

impl Zero for Counted {
    fn zero() -> Counted {
        Counted(0.0)
    }
    fn is_zero(&self) -> bool {
        self.0 == 0.0
    }
}

impl One for Counted {
    fn one() -> Counted {
        Counted(1.0)
    }
}

impl Ring for Counted {
    fn from_ratio(num: i64, den: i64) -> Counted {
        Counted(num as f64 / den as f64)
    }
    fn try_recip(&self) -> Option<Counted> {
        (self.0 != 0.0).then(|| Counted(1.0 / self.0))
    }
    fn cos(&self) -> Counted {
        bump(|c| c.trig += 1);
        Counted(self.0.cos())
    }
    fn sin(&self) -> Counted {
        bump(|c| c.trig += 1);
        Counted(self.0.sin())
    }
    fn try_sqrt(&self) -> Option<Counted> {
        (self.0 >= 0.0).then(|| Counted(self.0.sqrt()))
    }
    fn to_f64(&self) -> Option<f64> {
        Some(self.0)
    }
}

fn rand(rng: &mut Lcg) -> Counted {
    Counted(rng.next())
}

fn quat(rng: &mut Lcg) -> Quat<Counted> {
    Quat::new(rand(rng), rand(rng), rand(rng), rand(rng))
}

fn mat3(rng: &mut Lcg) -> [[Counted; 3]; 3] {
    std::array::from_fn(|_| std::array::from_fn(|_| rand(rng)))
}

/// The naive 3x3 product.
fn mul3(a: &[[Counted; 3]; 3], b: &[[Counted; 3]; 3]) -> [[Counted; 3]; 3] {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j])
    })
}

/// The top three rows of a 4x4 product, every entry a sum of four products.
fn mul_top_rows(a: &Matrix4<Counted>, b: &Matrix4<Counted>) -> [[Counted; 4]; 3] {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            (0..4)
                .map(|k| a.rows[i][k] * b.rows[k][j])
                .reduce(|x, y| x + y)
                .unwrap()
        })
    })
}

/// `(R1, t1)(R2, t2) = (R1 R2, R1 t2 + t1)`: the homogeneous product that knows the last row is
/// `(0, 0, 0, 1)`.
fn mul_rigid(
    (r1, t1): &([[Counted; 3]; 3], [Counted; 3]),
    (r2, t2): &([[Counted; 3]; 3], [Counted; 3]),
) -> ([[Counted; 3]; 3], [Counted; 3]) {
    let r = mul3(r1, r2);
    let t = std::array::from_fn(|i| r1[i][0] * t2[0] + r1[i][1] * t2[1] + r1[i][2] * t2[2] + t1[i]);
    (r, t)
}

/// Counts of one product each: 3x3, quaternion, DQ, full 4x4, top three rows, rigid.
/// Tables 1 and 2 of the paper, counted by running each product once on [`Counted`] values:
/// the 3x3 rotation product, the quaternion and dual-quaternion products, and the 4x4
/// homogeneous product in full, for its top three rows, and exploiting the constant last row.
pub fn product_table() -> Vec<(&'static str, OpCount)> {
    let mut rng = Lcg(2);
    let (a3, b3) = (mat3(&mut rng), mat3(&mut rng));
    let (p, q) = (quat(&mut rng), quat(&mut rng));
    let dq = |rng: &mut Lcg| DualQuat::from_real_and_dual(quat(rng), quat(rng));
    let (pd, qd) = (dq(&mut rng), dq(&mut rng));
    let m4 = |rng: &mut Lcg| {
        Matrix4::from_rows(std::array::from_fn(|_| std::array::from_fn(|_| rand(rng))))
    };
    let (a, b) = (m4(&mut rng), m4(&mut rng));
    let rigid = |rng: &mut Lcg| (mat3(rng), [rand(rng), rand(rng), rand(rng)]);
    let (x, y) = (rigid(&mut rng), rigid(&mut rng));
    vec![
        (
            "3x3 rotation matrix product",
            count_ops(|| mul3(&a3, &b3)).1,
        ),
        ("quaternion product", count_ops(|| &p * &q).1),
        ("dual quaternion product", count_ops(|| &pd * &qd).1),
        ("4x4 product, full", count_ops(|| &a * &b).1),
        (
            "4x4 product, top three rows",
            count_ops(|| mul_top_rows(&a, &b)).1,
        ),
        (
            "4x4 product, constant last row exploited",
            count_ops(|| mul_rigid(&x, &y)).1,
        ),
    ]
}

/// What a chain of `n` 3x3 rotation products costs, counted (sec 7 with ERRATA 11).
pub fn rotation_chain_ops(n: usize) -> OpCount {
    let mut rng = Lcg(3);
    let ms: Vec<_> = (0..n.max(1)).map(|_| mat3(&mut rng)).collect();
    count_ops(|| ms[1..].iter().fold(ms[0], |acc, m| mul3(&acc, m))).1
}

/// A tiny deterministic generator: the counted values only need to be nonzero and varied.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }
}
