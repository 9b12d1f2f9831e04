//! How a number written for an angle is read, one rule for robot files and URDF files.
//!
//! Datasheets and exporters print angles as decimals (`1.5708`, `3.14159`, `-0.7854`): a
//! decimal within [`snap_tolerance`] of a multiple of pi/12 is read as that multiple, and the
//! reader reports it (`1.5708 read as pi/2`). A decimal with fewer than [`MIN_PLACES`] digits
//! after the point (`1.57`, `3.14`) is not: two digits cannot tell pi/2 from an angle of
//! 1.57 rad, so it stays as written and the note says how to mean the multiple. A robot file
//! also refuses a bare angle past 2 pi (`alpha = 90`: degrees, `"90deg"` is the way to say so);
//! a URDF file is in radians by its specification, so there such an angle stays a parameter.

use crate::scalar::{decimal_places, decimal_text};
use crate::Scalar;
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};

/// The fewest digits after the point for a decimal to be read as a multiple of pi/12: with
/// `d` digits the tolerance is `10^-d` (below), and the multiples of pi/12 are 0.2618 apart,
/// so at `d = 2` a decimal drawn at random would be within the tolerance of one of them 7.6%
/// of the time (`2 * 10^-2 / (pi/12)`): too often to be read as intended. At `d = 3` it is
/// 0.76%, the same tolerance the URDF reader has always used.
pub const MIN_PLACES: u64 = 3;

/// The tolerance never goes below this many radians, however many digits are written: angles
/// computed in single precision (2^-24 relative, up to 4e-7 at 2 pi) and printed with all
/// their digits are still read as the multiple they approximate (`1.570796325`). A chance hit
/// is then 7.6e-6 per angle.
pub const FLOAT_FLOOR: f64 = 1e-6;

/// The largest magnitude tried: beyond it the f64 distance to a multiple of pi/12 has lost the
/// digits the tolerance needs.
const LARGEST: f64 = 1e6;

/// How far (radians) a decimal with `places` digits after the point may be from a multiple of
/// pi/12 to be read as it, or `None` below [`MIN_PLACES`].
///
/// A decimal written to `d` places that is the true value rounded (or truncated) to `d` places
/// is within `10^-d` of it, and only then: so `10^-d`, never below [`FLOAT_FLOOR`]. `1.5708`
/// (3.7e-6 from pi/2, tolerance 1e-4), `3.14159` (2.7e-6, 1e-5), `1.571` (2.0e-4, 1e-3) and
/// `3.1415` (9.3e-5, truncated, 1e-4) are read as multiples; `1.5700` is the value 1.57, two
/// places, and stays.
pub fn snap_tolerance(places: u64) -> Option<f64> {
    if places < MIN_PLACES {
        return None;
    }
    let exp = i32::try_from(places).unwrap_or(i32::MAX);
    Some(10f64.powi(-exp).max(FLOAT_FLOOR))
}

/// How a number written for an angle reads.
#[derive(Clone, Debug, PartialEq)]
pub enum AngleReading {
    /// Zero: nothing to say.
    Zero,
    /// `twelfths * pi/12`, within the tolerance of the decimal.
    Multiple {
        /// The multiple of pi/12.
        twelfths: i64,
    },
    /// Not read as a multiple; `near` is the multiple of pi/12 it is within `10^-d` of when
    /// it has too few digits to be read as it (`1.57`: pi/2).
    Literal {
        /// The multiple of pi/12 it is close to, when it has too few digits.
        near: Option<i64>,
    },
}

/// Reads the decimal `x` as an angle by the rule of this module.
pub fn read_angle(x: &BigRational) -> AngleReading {
    if x.is_zero() {
        return AngleReading::Zero;
    }
    let xf = x.to_f64().unwrap_or(f64::NAN);
    let Some(places) = decimal_places(x) else {
        return AngleReading::Literal { near: None };
    };
    if !xf.is_finite() || xf.abs() > LARGEST {
        return AngleReading::Literal { near: None };
    }
    let step = std::f64::consts::PI / 12.0;
    let k = (xf / step).round();
    let off = (xf - k * step).abs();
    match snap_tolerance(places) {
        Some(tol) if off <= tol => AngleReading::Multiple { twelfths: k as i64 },
        // One digit after the point is within 0.1 of some multiple for 76% of all values:
        // only two digits make a near miss worth a word.
        None if places + 1 == MIN_PLACES && off <= 10f64.powi(-(places as i32)) => {
            AngleReading::Literal {
                near: Some(k as i64),
            }
        }
        _ => AngleReading::Literal { near: None },
    }
}

/// `twelfths * pi/12` exactly.
pub fn pi_twelfths(twelfths: i64) -> Scalar {
    Scalar::rational(BigRational::new(twelfths.into(), 12.into())) * Scalar::pi()
}

/// `k pi/n` as text: `pi/2`, `-pi/4`, `5*pi/12`, `pi`, `0`.
pub fn pi_multiple_text(k: i64, n: i64) -> String {
    let g = num_integer::gcd(k, n);
    let (k, d) = if g == 0 { (0, 1) } else { (k / g, n / g) };
    let num = match k {
        0 => return "0".into(),
        1 => "pi".to_string(),
        -1 => "-pi".to_string(),
        k => format!("{k}*pi"),
    };
    if d == 1 {
        num
    } else {
        format!("{num}/{d}")
    }
}

/// A number as the user wrote it: its exact decimal when it is one (`1.5708`), else its
/// fraction.
pub fn number_text(x: &BigRational) -> String {
    decimal_text(x, 64).unwrap_or_else(|| x.to_string())
}

/// The note for a decimal read as a multiple: `1.5708 read as pi/2`.
pub fn snapped_note(x: &BigRational, twelfths: i64) -> String {
    format!(
        "{} read as {}",
        number_text(x),
        pi_multiple_text(twelfths, 12)
    )
}

/// The advice for a decimal with too few digits near a multiple: `it is within 0.01 of pi/2:
/// write pi/2 (or 1.5708) to mean it`.
pub fn near_note(x: &BigRational, twelfths: i64) -> String {
    let places = decimal_places(x).unwrap_or(0);
    let m = pi_multiple_text(twelfths, 12);
    let closer = twelfths as f64 * std::f64::consts::PI / 12.0;
    format!(
        "it is within {} of {m} but has fewer than {MIN_PLACES} decimals: write {m} (or {closer:.4}) to mean it",
        number_text(&BigRational::new(1.into(), num_bigint::BigInt::from(10u32).pow(places as u32)))
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::parse_decimal;

    fn read(t: &str) -> AngleReading {
        read_angle(&parse_decimal(t, 100).expect("a decimal"))
    }

    #[test]
    fn datasheet_decimals_are_read_as_multiples_of_pi_over_12() {
        for (t, k) in [
            ("1.5708", 6),
            ("-1.5708", -6),
            ("3.14159", 12),
            ("3.1415", 12),
            ("1.571", 6),
            ("0.7854", 3),
            ("0.5236", 2),
            ("6.2832", 24),
            ("1.570796325", 6),
            ("1.5707963267948966", 6),
            ("4.712", 18),
        ] {
            assert_eq!(read(t), AngleReading::Multiple { twelfths: k }, "{t}");
        }
    }

    #[test]
    fn short_or_distant_decimals_stay_as_written() {
        assert_eq!(read("1.57"), AngleReading::Literal { near: Some(6) });
        assert_eq!(read("3.14"), AngleReading::Literal { near: Some(12) });
        assert_eq!(read("1.5700"), AngleReading::Literal { near: Some(6) });
        for t in ["1.5", "1.6", "0.3", "1.5690", "90", "1", "0.17453"] {
            assert_eq!(read(t), AngleReading::Literal { near: None }, "{t}");
        }
        assert_eq!(read("0"), AngleReading::Zero);
        // Each tolerance admits the value rounded or truncated to its places, and no more.
        let pi2 = std::f64::consts::FRAC_PI_2;
        for places in MIN_PLACES..=12 {
            let tol = snap_tolerance(places).expect("enough places");
            let scale = 10f64.powi(places as i32);
            for v in [(pi2 * scale).round() / scale, (pi2 * scale).trunc() / scale] {
                assert!((v - pi2).abs() <= tol, "{v} at {places} places");
            }
        }
    }
}
