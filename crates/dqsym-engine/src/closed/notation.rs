//! Notation for angles, shared by every printer and emitter: the robotics shorthand `c12`,
//! `s123` and the explicit text of an angle (`theta1 + theta2`, `t - pi/7`).

use super::Angle;
use crate::scalar::{Small, Trig};
use num_traits::{One, Signed, Zero};

/// `c12` / `s123` for cos / sin of a plain sum of numbered symbols sharing one prefix
/// (`theta1 + theta2`, `t2 + t3`; prefixes other than theta, q, t and th are kept:
/// `calpha5`); `None` for any other angle.
pub fn shorthand_name(f: Trig, angle: &Angle) -> Option<String> {
    let mut out = String::new();
    write_shorthand(f, angle, &mut out).then_some(out)
}

/// [`shorthand_name`] appended to `out`; whether there is one (`out` is unchanged when not).
/// The plain printer writes each name in place: every printed cosine and sine asks for its
/// name (a fully symbolic 6R's report: 9,616 names, whose `String`s and `str::parse` were
/// 3.4 M instructions, 3.6% of the report).
pub(crate) fn write_shorthand(f: Trig, angle: &Angle, out: &mut String) -> bool {
    if !angle.is_plain_sum() || angle.terms.is_empty() {
        return false;
    }
    let mut prefix: Option<&str> = None;
    // Each index as its digits: without a leading zero they are the decimal of its value, and
    // ordered by length, then as text, they are ordered by value.
    let mut idx: smallvec::SmallVec<[&str; 4]> = smallvec::SmallVec::new();
    for (s, _) in &angle.terms {
        let name = s.name();
        // A digit is one byte, and no byte of a longer character is an ASCII digit: the byte
        // position is the character's.
        let Some(cut) = name.bytes().position(|c| c.is_ascii_digit()) else {
            return false;
        };
        let (p, digits) = name.split_at(cut);
        if p.is_empty()
            || digits.starts_with('0')
            || !digits.bytes().all(|c| c.is_ascii_digit())
            || !fits_u64(digits)
            || prefix.is_some_and(|q| q != p)
        {
            return false;
        }
        prefix = Some(p);
        idx.push(digits);
    }
    if idx.len() > 1 {
        idx.sort_unstable_by(|a, b| a.len().cmp(&b.len()).then_with(|| a.cmp(b)));
    }
    let sep = if idx.iter().any(|d| d.len() > 1) {
        ","
    } else {
        ""
    };
    // The bare `c12` is kept for the usual names of joint variables; any other prefix is
    // written out (`calpha5`), so cos(alpha5) and cos(theta5) never print alike.
    let shown = match prefix {
        Some("theta" | "q" | "t" | "th") | None => "",
        Some(p) => p,
    };
    out.push_str(&f.name()[..1]);
    out.push_str(shown);
    for (k, d) in idx.iter().enumerate() {
        if k > 0 {
            out.push_str(sep);
        }
        out.push_str(d);
    }
    true
}

/// Whether decimal digits without a leading zero are a value of `u64` (the indices
/// `str::parse::<u64>` read when names were parsed: a longer one is no index).
fn fits_u64(digits: &str) -> bool {
    const MAX: &str = "18446744073709551615";
    digits.len() < MAX.len() || (digits.len() == MAX.len() && digits <= MAX)
}

/// The angle in explicit form: `theta1 + theta2`, `theta3/2`, `t - pi/7`, `t/2 - 1/3` (the
/// symbols first, then the rational constant, then the multiple of pi); a sum whose
/// coefficients (the pi part included) all have one denominator `d > 1` is written over it once,
/// `(q1 + q2)/2` for `q1/2 + q2/2` (as the LaTeX printer writes `\frac{q_1 + q_2}{2}`).
pub fn angle_text(angle: &Angle) -> String {
    angle_text_with(angle, &str::to_owned)
}

/// [`angle_text`] with each symbol written as `name` gives it (SymPy's `Symbol('E')`).
pub fn angle_text_with(angle: &Angle, name: &dyn Fn(&str) -> String) -> String {
    angle_text_full(angle, name, false)
}

/// [`angle_text`] with a constant that is a decimal fraction written as its decimal
/// (`cos(0.785)`, `q1 + 0.3`) when `decimals`: a robot whose file wrote its angles as decimals
/// reads them so (exactly; see [`shows_as_decimal`](super::shows_as_decimal)).
pub fn angle_text_decimals(angle: &Angle, decimals: bool) -> String {
    angle_text_full(angle, &str::to_owned, decimals)
}

/// The constant `k` of an angle as a decimal, when `decimals` and it is a decimal fraction.
pub(crate) fn decimal_constant(k: Small, decimals: bool) -> Option<String> {
    // Every angle a printer writes passes here: nothing is built unless decimals are asked
    // for and the denominator could be a decimal's (a factor 5).
    if !decimals || k.denom() % 5 != 0 {
        return None;
    }
    let q = num_rational::BigRational::new((*k.numer()).into(), (*k.denom()).into());
    super::shows_as_decimal(&q)
        .then(|| crate::scalar::decimal_text(&q.abs(), 40))
        .flatten()
}

fn angle_text_full(angle: &Angle, name: &dyn Fn(&str) -> String, decimals: bool) -> String {
    if decimals && !angle.constant.is_zero() && decimal_constant(angle.constant, true).is_some() {
        // The decimal stands alone; the other parts keep their own denominators.
        return sum_text(angle, name, true);
    }
    match common_denominator(angle) {
        Some(d) => {
            // Every nonzero part has the denominator `d`: times `d`, its numerator.
            let whole = Angle::new(
                angle
                    .terms
                    .iter()
                    .map(|(s, k)| (s.clone(), Small::from_integer(*k.numer())))
                    .collect(),
                Small::from_integer(*angle.constant.numer()),
                Small::from_integer(*angle.pi.numer()),
            );
            format!("({})/{d}", sum_text(&whole, name, false))
        }
        None => sum_text(angle, name, false),
    }
}

/// The denominator `d > 1` shared by every coefficient of an angle of two or more parts.
pub(crate) fn common_denominator(angle: &Angle) -> Option<i64> {
    let mut ks = (!angle.constant.is_zero())
        .then_some(angle.constant)
        .into_iter()
        .chain(angle.terms.iter().map(|(_, k)| *k))
        .chain((!angle.pi.is_zero()).then_some(angle.pi));
    let d = *ks.next()?.denom();
    let mut parts = 1;
    for k in ks {
        if *k.denom() != d {
            return None;
        }
        parts += 1;
    }
    (d > 1 && parts > 1).then_some(d)
}

fn sum_text(angle: &Angle, name: &dyn Fn(&str) -> String, decimals: bool) -> String {
    let mut s = String::new();
    let mut first = true;
    let mut push = |k: Small, name: &str, s: &mut String| {
        let neg = k.is_negative();
        let a = k.abs();
        if first {
            if neg {
                s.push('-');
            }
        } else {
            s.push_str(if neg { " - " } else { " + " });
        }
        first = false;
        if name.is_empty() {
            match decimal_constant(a, decimals) {
                Some(d) => s.push_str(&d),
                None => s.push_str(&a.to_string()),
            }
        } else if a.is_one() {
            s.push_str(name);
        } else if a.numer().is_one() {
            s.push_str(&format!("{name}/{}", a.denom()));
        } else if a.denom().is_one() {
            s.push_str(&format!("{}*{name}", a.numer()));
        } else {
            s.push_str(&format!("{}*{name}/{}", a.numer(), a.denom()));
        }
    };
    // Symbols first, then the rational constant and the multiple of pi: `t/2 - 1/3`, as the
    // pi offset reads in `x - pi/7`.
    for (sym, k) in &angle.terms {
        push(*k, &name(sym.name()), &mut s);
    }
    if !angle.constant.is_zero() {
        push(angle.constant, "", &mut s);
    }
    if !angle.pi.is_zero() {
        push(angle.pi, "pi", &mut s);
    }
    if s.is_empty() {
        s.push('0');
    }
    s
}

/// How a printer names the cosine or sine of an angle: `Some(name)` for a shorthand, `None` to
/// write the function out.
pub type TrigNames<'a> = &'a dyn Fn(Trig, &Angle) -> Option<String>;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Sym;

    /// The shorthand as first written (vectors of index strings joined, `format!`): the
    /// reference [`shorthand_name`] must agree with.
    fn reference(f: Trig, angle: &Angle) -> Option<String> {
        if !angle.is_plain_sum() || angle.terms.is_empty() {
            return None;
        }
        let mut prefix: Option<&str> = None;
        let mut idx = Vec::new();
        for (s, _) in &angle.terms {
            let name = s.name();
            let cut = name.find(|c: char| c.is_ascii_digit())?;
            let (p, digits) = name.split_at(cut);
            if p.is_empty()
                || !digits.chars().all(|c| c.is_ascii_digit())
                || digits.starts_with('0')
            {
                return None;
            }
            if prefix.is_some_and(|q| q != p) {
                return None;
            }
            prefix = Some(p);
            idx.push(digits.parse::<u64>().ok()?);
        }
        idx.sort_unstable();
        let sep = if idx.iter().any(|&i| i >= 10) {
            ","
        } else {
            ""
        };
        let body: Vec<String> = idx.iter().map(|i| i.to_string()).collect();
        let shown = match prefix {
            Some("theta" | "q" | "t" | "th") | None => "",
            Some(p) => p,
        };
        Some(format!("{}{shown}{}", &f.name()[..1], body.join(sep)))
    }

    #[test]
    fn shorthand_names_agree_with_the_reference_on_every_kind_of_name() {
        let names = [
            "theta1",
            "theta2",
            "theta10",
            "theta12",
            "q3",
            "q1",
            "q20",
            "t7",
            "th4",
            "alpha5",
            "alpha1",
            "d3",
            "x",
            "q0",
            "q01",
            "q1a",
            "1q",
            "theta3x4",
            "q18446744073709551616",
            "q18446744073709551615",
            "q99999999999999999999",
            "q9999999999999999999",
            "q09",
            "θ2",
            "theta٣",
            "q9",
        ];
        let one = Small::one();
        let mut angles: Vec<Angle> = Vec::new();
        for (i, a) in names.iter().enumerate() {
            angles.push(Angle::of_symbol(Sym::new(a)));
            for b in &names[i + 1..] {
                angles.push(Angle::new(
                    vec![(Sym::new(a), one), (Sym::new(b), one)],
                    Small::zero(),
                    Small::zero(),
                ));
                for c in ["theta3", "q11", "alpha2"] {
                    angles.push(Angle::new(
                        vec![(Sym::new(a), one), (Sym::new(b), one), (Sym::new(c), one)],
                        Small::zero(),
                        Small::zero(),
                    ));
                }
            }
        }
        // Not plain sums: a coefficient, a constant, a multiple of pi.
        let q1 = Sym::new("q1");
        angles.push(Angle::new(
            vec![(q1.clone(), Small::new(1, 2))],
            Small::zero(),
            Small::zero(),
        ));
        angles.push(Angle::new(vec![(q1.clone(), one)], one, Small::zero()));
        angles.push(Angle::new(vec![(q1, one)], Small::zero(), Small::new(1, 7)));
        angles.push(Angle::new(Vec::new(), Small::zero(), Small::zero()));
        let mut named = 0;
        for a in &angles {
            for f in [Trig::Cos, Trig::Sin] {
                let got = shorthand_name(f, a);
                assert_eq!(got, reference(f, a), "{a:?}");
                // In place: appended to what is written, nothing written without a name.
                let mut out = String::from("2 ");
                let written = write_shorthand(f, a, &mut out);
                assert_eq!(written, got.is_some());
                assert_eq!(out, format!("2 {}", got.as_deref().unwrap_or("")));
                named += usize::from(got.is_some());
            }
        }
        // Both kinds occur: names made, and names refused.
        assert!(named > 50 && named < 2 * angles.len(), "{named}");
        assert_eq!(
            shorthand_name(
                Trig::Sin,
                &Angle::new(
                    vec![(Sym::new("theta12"), one), (Sym::new("theta3"), one)],
                    Small::zero(),
                    Small::zero()
                )
            )
            .as_deref(),
            Some("s3,12")
        );
    }
}
