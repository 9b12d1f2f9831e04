//! Exact decimals where the user wrote decimals: a closed form of a robot whose lengths were
//! typed as decimals (`a2 = -0.425`) pulls their common denominator out of its sums
//! (`1/10000 (4250 c2 + 3922 c23)`); [`decimal_form`] puts it back into the sums, so that with
//! the printers' `decimals` option the entry reads `0.425 c2 + 0.3922 c23`. The value is the
//! same (each number multiplied exactly), and nothing else moves.

use super::Expr;
use crate::scalar::decimal_places;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed};

/// `e` with every leading factor that is a decimal fraction (its denominator has the factor
/// 5, which only decimals make; halves and quarters come from half angles and `sqrt(2)/2`)
/// multiplied into the sum it stands before: `1/10000 (c1 (4250 c2 + ...) + s1 (...))` becomes
/// `c1 (0.425 c2 + ...) + s1 (...)`, `1/80000 sqrt(2) (3922 cos(x) ...)` becomes `1/8 sqrt(2)
/// (0.3922 cos(x) ...)` (the power of 2 beyond the decimal's stays in front).
///
/// `typed` are the numbers the user wrote (their magnitudes): where a power of 1/2 may stay in
/// front or go in, the choice shows the most of them as typed.
pub fn decimal_form(e: &Expr, typed: &[BigRational]) -> Expr {
    let rec = |x: &Expr| decimal_form(x, typed);
    match e {
        Expr::Add(v) => Expr::Add(v.iter().map(rec).collect()),
        Expr::Neg(x) => Expr::Neg(Box::new(rec(x))),
        Expr::Pow(b, n) => Expr::Pow(Box::new(rec(b)), *n),
        Expr::Mul(v) => {
            let v: Vec<Expr> = v.iter().map(rec).collect();
            if let Some(Expr::Num(q)) = v.first() {
                let rest = &v[1..];
                if let (Some(k), Some(splits)) = (
                    rest.iter().position(|x| matches!(x, Expr::Add(_))),
                    splits(q),
                ) {
                    // Of the ways to leave a power of 1/2 in front, the one that shows the
                    // most numbers as typed, then the fewest significant digits:
                    // `1/8 sqrt(2) (0.3922 ...)` (the half angles' 1/8 kept, the lengths as
                    // typed), `0.0825` rather than `1/2 (0.165 ...)`; the most distributed
                    // among equals.
                    let mut best: Option<((usize, std::cmp::Reverse<usize>), Expr)> = None;
                    for (outer, inner) in splits {
                        let mut r = rest.to_vec();
                        r[k] = scale(&r[k], &inner);
                        let score = (
                            r.iter().map(|x| as_typed(x, typed)).sum::<usize>(),
                            std::cmp::Reverse(r.iter().map(significant_digits).sum::<usize>()),
                        );
                        if best.as_ref().is_none_or(|(b, _)| score > *b) {
                            best = Some((score, product(outer, r)));
                        }
                    }
                    if let Some((_, e)) = best {
                        return e;
                    }
                }
            }
            Expr::Mul(v)
        }
        other => other.clone(),
    }
}

/// Whether `q` is shown as a decimal by a printer with `decimals` set: a terminating decimal
/// that is not an integer and whose denominator has the factor 5.
pub fn shows_as_decimal(q: &BigRational) -> bool {
    !q.is_integer()
        && decimal_places(q).is_some()
        && (q.denom() % BigInt::from(5)) == BigInt::from(0)
}

/// The ways to write `q = outer * inner` with `inner > 0` a decimal and `outer` plus or minus
/// a power of 1/2 (`1/80000 = 1/8 * 1/10000`, `= 1/4 * 1/20000`, ...), the whole of `q`
/// distributed first; `None` when `q` is not a decimal fraction.
fn splits(q: &BigRational) -> Option<Vec<(BigRational, BigRational)>> {
    if !shows_as_decimal(q) {
        return None;
    }
    let (mut d, mut twos, mut fives) = (q.denom().clone(), 0u32, 0u32);
    while (&d % 2) == BigInt::from(0) {
        d /= 2;
        twos += 1;
    }
    while (&d % 5) == BigInt::from(0) {
        d /= 5;
        fives += 1;
    }
    let sign = if q.is_negative() { -1 } else { 1 };
    Some(
        (0..=twos.saturating_sub(fives))
            .map(|extra| {
                let outer = BigRational::new(BigInt::from(sign), BigInt::from(2).pow(extra));
                let inner = q / &outer;
                (outer, inner)
            })
            .collect(),
    )
}

/// How many numbers of `e` are (in magnitude) among `typed`.
fn as_typed(e: &Expr, typed: &[BigRational]) -> usize {
    match e {
        Expr::Num(q) => usize::from(typed.contains(&q.abs())),
        Expr::Add(v) | Expr::Mul(v) => v.iter().map(|x| as_typed(x, typed)).sum(),
        Expr::Neg(x) | Expr::Pow(x, _) => as_typed(x, typed),
        _ => 0,
    }
}

/// The significant digits of the numbers of `e` as a printer with `decimals` shows them.
fn significant_digits(e: &Expr) -> usize {
    match e {
        Expr::Num(q) => {
            let t = crate::scalar::decimal_text(q, 1_000).unwrap_or_else(|| q.to_string());
            t.trim_start_matches(['-', '0', '.'])
                .chars()
                .filter(char::is_ascii_digit)
                .count()
        }
        Expr::Add(v) | Expr::Mul(v) => v.iter().map(significant_digits).sum(),
        Expr::Neg(x) | Expr::Pow(x, _) => significant_digits(x),
        _ => 0,
    }
}

/// `e` times the positive rational `q`, pushed into its sums and leading numbers.
fn scale(e: &Expr, q: &BigRational) -> Expr {
    match e {
        Expr::Num(r) => Expr::Num(r * q),
        Expr::Add(v) => Expr::Add(v.iter().map(|x| scale(x, q)).collect()),
        Expr::Neg(x) => Expr::Neg(Box::new(scale(x, q))),
        Expr::Mul(v) => {
            let (k, mut rest) = match v.first() {
                Some(Expr::Num(r)) => (r * q, v[1..].to_vec()),
                _ => (q.clone(), v.clone()),
            };
            // A fraction goes on into the product's sum: `c5 (0.176 c6 + 0.214 s6)`, not
            // `0.002 c5 (88 c6 + 107 s6)`.
            match rest.iter().position(|x| matches!(x, Expr::Add(_))) {
                Some(i) if !k.is_integer() => {
                    rest[i] = scale(&rest[i], &k);
                    product(BigRational::one(), rest)
                }
                _ => product(k, rest),
            }
        }
        other => product(q.clone(), vec![other.clone()]),
    }
}

/// `k` times the product of `rest`: the factor left out when 1, a negation for -1.
pub(super) fn product(k: BigRational, rest: Vec<Expr>) -> Expr {
    let body = |rest: Vec<Expr>| match rest.len() {
        0 => Expr::Num(BigRational::one()),
        1 => rest.into_iter().next().expect("one factor"),
        _ => Expr::Mul(rest),
    };
    if k.is_one() {
        body(rest)
    } else if (-&k).is_one() {
        Expr::Neg(Box::new(body(rest)))
    } else if rest.is_empty() {
        Expr::Num(k)
    } else {
        let mut v = vec![Expr::Num(k)];
        v.extend(rest);
        Expr::Mul(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{closed_form, Scalar};

    #[test]
    fn decimal_form_keeps_the_value_and_distributes_tenths() {
        let q = |n: i64, d: i64| Scalar::rational(BigRational::new(n.into(), d.into()));
        let (c2, c23) = (
            Scalar::sym("q2").cos(),
            (Scalar::sym("q2") + Scalar::sym("q3")).cos(),
        );
        let x = Scalar::sym("q1").cos() * (q(-17, 40) * c2.clone() - q(1961, 5000) * c23.clone())
            + q(1333, 10000);
        let y = (q(-17, 40) * c2 + q(1961, 5000) * c23) * Scalar::int(2).sqrt() * q(1, 8);
        for s in [x, y] {
            let e = closed_form(&s).expect("closed form");
            let d = decimal_form(&e, &[]);
            assert_eq!(d.to_scalar(), s);
            // No decimal fraction is left in front of a sum.
            fn no_pulled(e: &Expr) -> bool {
                match e {
                    Expr::Mul(v) => {
                        !(matches!(v.first(), Some(Expr::Num(q)) if shows_as_decimal(q))
                            && v.iter().any(|x| matches!(x, Expr::Add(_))))
                            && v.iter().all(no_pulled)
                    }
                    Expr::Add(v) => v.iter().all(no_pulled),
                    Expr::Neg(x) | Expr::Pow(x, _) => no_pulled(x),
                    _ => true,
                }
            }
            assert!(no_pulled(&d), "{d:?}");
        }
    }
}
