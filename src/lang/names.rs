//! Spelling helpers for lowering: Greek letters in names, and the exact fraction a decimal
//! literal stands for.

use num_bigint::BigUint;
use num_integer::Integer;
use num_traits::{One, Zero};

/// The name a Greek letter is spelled as, so that `θ1` and `theta1` are one symbol. ε is
/// spelled `eps`, Matlab's name, so that `ε` and `eps` both denote the dual unit.
fn greek_name(c: char) -> Option<&'static str> {
    Some(match c {
        'α' => "alpha",
        'β' => "beta",
        'γ' => "gamma",
        'δ' => "delta",
        'ε' | 'ϵ' => "eps",
        'ζ' => "zeta",
        'η' => "eta",
        'θ' | 'ϑ' => "theta",
        'ι' => "iota",
        'κ' => "kappa",
        'λ' => "lambda",
        'μ' => "mu",
        'ν' => "nu",
        'ξ' => "xi",
        'ο' => "omicron",
        'π' => "pi",
        'ρ' => "rho",
        'σ' | 'ς' => "sigma",
        'τ' => "tau",
        'υ' => "upsilon",
        'φ' | 'ϕ' => "phi",
        'χ' => "chi",
        'ψ' => "psi",
        'ω' => "omega",
        'Α' => "Alpha",
        'Β' => "Beta",
        'Γ' => "Gamma",
        'Δ' => "Delta",
        'Ε' => "Epsilon",
        'Ζ' => "Zeta",
        'Η' => "Eta",
        'Θ' => "Theta",
        'Ι' => "Iota",
        'Κ' => "Kappa",
        'Λ' => "Lambda",
        'Μ' => "Mu",
        'Ν' => "Nu",
        'Ξ' => "Xi",
        'Ο' => "Omicron",
        'Π' => "Pi",
        'Ρ' => "Rho",
        'Σ' => "Sigma",
        'Τ' => "Tau",
        'Υ' => "Upsilon",
        'Φ' => "Phi",
        'Χ' => "Chi",
        'Ψ' => "Psi",
        'Ω' => "Omega",
        _ => return None,
    })
}

/// `name` with every Greek letter spelled out: `θ1` becomes `theta1`, `ε` becomes `eps`.
pub(crate) fn normalize_name(name: &str) -> String {
    if name.is_ascii() {
        return name.to_owned();
    }
    let mut out = String::with_capacity(name.len() * 2);
    for c in name.chars() {
        match greek_name(c) {
            Some(spelled) => out.push_str(spelled),
            None => out.push(c),
        }
    }
    out
}

/// Literals whose exact value would need more digits than this get a generic hint instead.
const MAX_SHOWN_DIGITS: usize = 40;

/// The exact value of a decimal literal (`1.5`, `.25`, `2e-3`) as dqsym source: `3/2`, `1/4`,
/// `1/500`. Literals too long to show usefully get `p/q` as a hint.
pub(crate) fn decimal_as_fraction(literal: &str) -> String {
    exact(literal).unwrap_or_else(|| "p/q".to_owned())
}

fn exact(literal: &str) -> Option<String> {
    let (mantissa, exponent) = match literal.find(['e', 'E']) {
        Some(i) => (&literal[..i], literal[i + 1..].parse::<i64>().ok()?),
        None => (literal, 0),
    };
    let (whole, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let digits = format!("{whole}{frac}");
    let scale = exponent.checked_sub(i64::try_from(frac.len()).ok()?)?;
    let digits = digits.trim_start_matches('0');
    if digits.len() + scale.unsigned_abs() as usize > MAX_SHOWN_DIGITS {
        return None;
    }
    let mut num = if digits.is_empty() {
        BigUint::zero()
    } else {
        BigUint::parse_bytes(digits.as_bytes(), 10)?
    };
    let ten_pow = BigUint::from(10u32).pow(u32::try_from(scale.unsigned_abs()).ok()?);
    let mut den = BigUint::one();
    if scale >= 0 {
        num *= ten_pow;
    } else {
        den = ten_pow;
    }
    let g = num.gcd(&den);
    if !g.is_zero() {
        num /= &g;
        den /= &g;
    }
    Some(if den.is_one() {
        num.to_string()
    } else {
        format!("{num}/{den}")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn greek_letters_are_spelled_out() {
        assert_eq!(normalize_name("θ1"), "theta1");
        assert_eq!(normalize_name("ϑ_2"), "theta_2");
        assert_eq!(normalize_name("ε"), "eps");
        assert_eq!(normalize_name("Δx"), "Deltax");
        assert_eq!(normalize_name("l1"), "l1");
    }

    #[test]
    fn decimals_become_reduced_fractions() {
        assert_eq!(decimal_as_fraction("1.5"), "3/2");
        assert_eq!(decimal_as_fraction(".25"), "1/4");
        assert_eq!(decimal_as_fraction("2e-3"), "1/500");
        assert_eq!(decimal_as_fraction("1.5E2"), "150");
        assert_eq!(decimal_as_fraction("3."), "3");
        assert_eq!(decimal_as_fraction("0.0"), "0");
        assert_eq!(decimal_as_fraction("1e99999999999999999999"), "p/q");
        assert_eq!(decimal_as_fraction("1e-100"), "p/q");
    }
}
