//! Exact values of decimal literals: `0.4318` is 2159/5000, `1e-3` is 1/1000. Datasheets, robot
//! files and URDF give lengths as decimals; reading them through binary floating point would
//! change them (0.4318 is not a binary fraction), so they are read from their text.

use num_bigint::{BigInt, BigUint};
use num_rational::BigRational;
use num_traits::{One, Zero};

/// The exact value of a decimal literal: an optional sign, digits with an optional point
/// (`12`, `0.5`, `.5`, `3.`), then an optional exponent (`e-3`, `E+2`). `None` when the text is
/// not such a literal, or when its value would need more than `max_digits` decimal digits
/// (`1e999999999`): a bound, so that no literal costs more than its length in work.
pub fn parse_decimal(text: &str, max_digits: usize) -> Option<BigRational> {
    let (negative, body) = match text.as_bytes().first()? {
        b'-' => (true, &text[1..]),
        b'+' => (false, &text[1..]),
        _ => (false, text),
    };
    let (mantissa, exponent) = match body.find(['e', 'E']) {
        Some(i) => {
            let e = &body[i + 1..];
            let digits = e.strip_prefix(['+', '-']).unwrap_or(e);
            if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
                return None;
            }
            (&body[..i], e.parse::<i64>().ok()?)
        }
        None => (body, 0),
    };
    let (whole, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    if whole.is_empty() && frac.is_empty()
        || !whole
            .bytes()
            .chain(frac.bytes())
            .all(|b| b.is_ascii_digit())
    {
        return None;
    }
    let digits = format!("{whole}{frac}");
    let digits = digits.trim_start_matches('0');
    let scale = exponent.checked_sub(i64::try_from(frac.len()).ok()?)?;
    if digits.is_empty() {
        return Some(BigRational::zero());
    }
    if digits.len() as u64 + scale.unsigned_abs() > max_digits as u64 {
        return None;
    }
    let num = BigUint::parse_bytes(digits.as_bytes(), 10)?;
    let ten_pow = BigUint::from(10u32).pow(u32::try_from(scale.unsigned_abs()).ok()?);
    let (num, den) = if scale >= 0 {
        (num * ten_pow, BigUint::one())
    } else {
        (num, ten_pow)
    };
    let num = BigInt::from(num);
    let num = if negative { -num } else { num };
    Some(BigRational::new(num, BigInt::from(den)))
}

/// `text` with every run of more than 40 digits abbreviated to its first 12 and last 6 digits
/// and its length, `199506311688...709376 (3011 digits)`: a message about a huge number stays
/// a line long.
pub fn short_numbers(text: &str) -> String {
    const LONG: usize = 40;
    let mut out = String::with_capacity(text.len().min(1024));
    let mut digits = String::new();
    let flush = |digits: &mut String, out: &mut String| {
        if digits.len() > LONG {
            let n = digits.len();
            out.push_str(&format!(
                "{}...{} ({n} digits)",
                &digits[..12],
                &digits[n - 6..]
            ));
        } else {
            out.push_str(digits);
        }
        digits.clear();
    };
    for c in text.chars() {
        if c.is_ascii_digit() {
            digits.push(c);
        } else {
            flush(&mut digits, &mut out);
            out.push(c);
        }
    }
    flush(&mut digits, &mut out);
    out
}

/// The number of digits after the point of `x` written as a terminating decimal (0 for an
/// integer, 4 for 2159/5000 = 0.4318), or `None` when `x` is not one (its reduced denominator
/// has a prime factor other than 2 and 5, as 1/3 has).
pub fn decimal_places(x: &BigRational) -> Option<u64> {
    let mut d = x.denom().magnitude().clone();
    let (two, five) = (BigUint::from(2u32), BigUint::from(5u32));
    let (mut a, mut b) = (0u64, 0u64);
    while !d.is_zero() && (&d % &two).is_zero() {
        d /= &two;
        a += 1;
    }
    while !d.is_zero() && (&d % &five).is_zero() {
        d /= &five;
        b += 1;
    }
    d.is_one().then_some(a.max(b))
}

/// `x` as an exact decimal (`0.4318`, `-0.0996`, `12`), the inverse of [`parse_decimal`];
/// `None` when `x` is not a terminating decimal or needs more than `max_digits` digits.
pub fn decimal_text(x: &BigRational, max_digits: usize) -> Option<String> {
    let places = decimal_places(x)?;
    let places = usize::try_from(places).ok()?;
    if places > max_digits {
        return None;
    }
    let scaled = x * BigRational::from_integer(BigInt::from(10u32).pow(places as u32));
    let n = scaled.to_integer();
    let digits = n.magnitude().to_string();
    if digits.len() > max_digits + 1 {
        return None;
    }
    let sign = if n < BigInt::zero() { "-" } else { "" };
    if places == 0 {
        return Some(format!("{sign}{digits}"));
    }
    let padded = format!("{digits:0>width$}", width = places + 1);
    let (whole, frac) = padded.split_at(padded.len() - places);
    Some(format!("{sign}{whole}.{frac}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }

    #[test]
    fn decimals_are_read_exactly() {
        assert_eq!(parse_decimal("0.4318", 100), Some(q(2159, 5000)));
        assert_eq!(parse_decimal("-0.39225", 100), Some(q(-1569, 4000)));
        assert_eq!(parse_decimal("1e-3", 100), Some(q(1, 1000)));
        assert_eq!(parse_decimal("1.5E2", 100), Some(q(150, 1)));
        assert_eq!(parse_decimal(".25", 100), Some(q(1, 4)));
        assert_eq!(parse_decimal("3.", 100), Some(q(3, 1)));
        assert_eq!(parse_decimal("+0.0", 100), Some(q(0, 1)));
        assert_eq!(parse_decimal("0e999999999999", 100), Some(q(0, 1)));
    }

    #[test]
    fn decimals_are_written_exactly_and_read_back() {
        for (x, text) in [
            (q(2159, 5000), "0.4318"),
            (q(-1569, 4000), "-0.39225"),
            (q(-249, 2500), "-0.0996"),
            (q(1, 1000), "0.001"),
            (q(150, 1), "150"),
            (q(-1, 4), "-0.25"),
            (q(0, 1), "0"),
        ] {
            assert_eq!(decimal_text(&x, 100).as_deref(), Some(text));
            assert_eq!(parse_decimal(text, 100), Some(x));
        }
        assert_eq!(decimal_places(&q(3927, 2500)), Some(4));
        assert_eq!(decimal_places(&q(1, 3)), None);
        assert_eq!(decimal_text(&q(1, 3), 100), None);
        assert_eq!(decimal_text(&q(1, 1 << 40), 10), None);
    }

    #[test]
    fn malformed_or_huge_literals_are_refused() {
        for bad in [
            "", ".", "e3", "1e", "1e+", "1.2.3", "inf", "nan", "0x10", "1_0", "--1",
        ] {
            assert_eq!(parse_decimal(bad, 100), None, "{bad}");
        }
        assert_eq!(parse_decimal("1e999999999", 10_000), None);
        assert_eq!(parse_decimal("1e-99999999999999999999", 10_000), None);
    }

    #[test]
    fn short_numbers_abbreviates_long_digit_runs_only() {
        let big = num_bigint::BigInt::from(7).pow(100u32).to_string();
        let text = format!("power 3 of {big} is 12345 and x{big}y");
        let short = super::short_numbers(&text);
        let n = big.len();
        let abbr = format!("{}...{} ({n} digits)", &big[..12], &big[n - 6..]);
        assert_eq!(short, format!("power 3 of {abbr} is 12345 and x{abbr}y"));
        assert_eq!(super::short_numbers("1/3 of 40 digits"), "1/3 of 40 digits");
    }
}
