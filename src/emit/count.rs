//! Operation counts of products (Tables 1 and 2 of the paper, with ERRATA items 10 and 11) and
//! of generated code.
//!
//! A product is counted by running it: [`Counted`] is an f64 that implements [`Ring`] and
//! records every `+`, `-`, `*`, negation and sin/cos done on it in thread-local counters, so a
//! count is what the algorithm does, never a number written down.

use super::codegen::{lower, CodegenError, CodegenOptions, OpCount, Output};
use crate::Ring;
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
/// As [`rust_function`](crate::rust_function).
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
