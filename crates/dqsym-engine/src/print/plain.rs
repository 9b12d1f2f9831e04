//! Plain text in the field's notation: robotics shorthand (`l1 c1 + l2 c12`) or explicit
//! (`l1*cos(theta1) + l2*cos(theta1 + theta2)`).

use crate::closed::{
    angle_text, angle_text_decimals, shorthand_name, shows_as_decimal, write_shorthand, Angle,
    Expr, Trig, TrigNames,
};
use num_traits::{One, Zero};
use std::collections::BTreeSet;

/// How plain text is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlainOptions {
    /// `c12` for `cos(theta1 + theta2)` where the angle allows it (see [`shorthand_name`]).
    pub shorthand: bool,
    /// Numbers that are decimal fractions (a factor 5 in the denominator) as exact decimals:
    /// `0.425`, not `17/40` (for robots whose file wrote decimals; see
    /// [`decimal_form`](crate::closed::decimal_form)).
    pub decimals: bool,
}

impl Default for PlainOptions {
    fn default() -> Self {
        PlainOptions {
            shorthand: true,
            decimals: false,
        }
    }
}

/// `q` as an exact decimal when `o.decimals` and it is a decimal fraction.
fn decimal(q: &num_rational::BigRational, o: &PlainOptions) -> Option<String> {
    if o.decimals && shows_as_decimal(q) {
        crate::scalar::decimal_text(q, 1_000)
    } else {
        None
    }
}

/// The expression as plain text.
pub fn plain(e: &Expr, opts: &PlainOptions) -> String {
    let mut out = String::new();
    write(e, opts, &mut Naming::shorthand(), 0, &mut out);
    out
}

/// The expression as plain text, cos and sin named by `names` (a walkthrough's notation)
/// instead of [`shorthand_name`]; `opts.shorthand` still chooses `l1 c1` over `l1*c1`.
pub fn plain_named(e: &Expr, opts: &PlainOptions, names: TrigNames) -> String {
    let mut out = String::new();
    write(e, opts, &mut Naming::Given(names), 0, &mut out);
    out
}

/// The quotient `num / den` as plain text, `num` alone when `den` is 1. A part that is a sum or
/// a product is bracketed, so the quotient reads one way: `(d1 s - d2 c)/(2 s)`, `-l/sin(t)`.
pub fn plain_quotient(num: &Expr, den: &Expr, opts: &PlainOptions) -> String {
    if matches!(den, Expr::Num(q) if q.is_one()) {
        return plain(num, opts);
    }
    quotient(num, den, opts, Naming::shorthand())
}

/// [`plain_quotient`] with cos and sin named by `names`, as [`plain_named`].
pub fn plain_quotient_named(
    num: &Expr,
    den: &Expr,
    opts: &PlainOptions,
    names: TrigNames,
) -> String {
    if matches!(den, Expr::Num(q) if q.is_one()) {
        return plain_named(num, opts, names);
    }
    quotient(num, den, opts, Naming::Given(names))
}

/// [`plain_quotient_named`] with `den` not 1, named as [`write`] names.
fn quotient(num: &Expr, den: &Expr, opts: &PlainOptions, mut names: Naming) -> String {
    let mut out = String::new();
    match num {
        Expr::Neg(inner) => {
            out.push('-');
            write(inner, opts, &mut names, 3, &mut out);
        }
        _ => write(num, opts, &mut names, 3, &mut out),
    }
    out.push('/');
    write(den, opts, &mut names, 3, &mut out);
    out
}

/// How [`write`] names cos and sin: by the caller's names, or by [`shorthand_name`] (when
/// `o.shorthand`) written in place ([`write_shorthand`]: no `String` per call), each call of
/// one symbol's angle named once per text and its name copied after (a fully symbolic 6R's
/// matrix: 4,712 names of 24 calls, each written twice, 3.4 M instructions of its report
/// when each was a `String`).
enum Naming<'a> {
    Given(TrigNames<'a>),
    /// The calls of one symbol named so far: the function, the symbol's interned address
    /// and the name, if any.
    Shorthand(Vec<(Trig, usize, Option<Box<str>>)>),
}

impl Naming<'_> {
    fn shorthand() -> Self {
        Naming::Shorthand(Vec::new())
    }

    /// The name of `f(angle)` appended to `out`; whether there is one.
    fn write(&mut self, f: Trig, angle: &Angle, o: &PlainOptions, out: &mut String) -> bool {
        let seen = match self {
            Naming::Given(names) => return names(f, angle).map(|n| out.push_str(&n)).is_some(),
            Naming::Shorthand(_) if !o.shorthand => return false,
            Naming::Shorthand(seen) => seen,
        };
        // Of one symbol (coefficient one, no offset) the name is a function of the symbol's
        // name, so of its interned address.
        let [(x, k)] = angle.terms.as_slice() else {
            return write_shorthand(f, angle, out);
        };
        if !(k.is_one() && angle.constant.is_zero() && angle.pi.is_zero()) {
            return write_shorthand(f, angle, out);
        }
        let addr = x.addr();
        if let Some((_, _, name)) = seen.iter().find(|(g, a, _)| *g == f && *a == addr) {
            return name.as_deref().map(|n| out.push_str(n)).is_some();
        }
        let start = out.len();
        let named = write_shorthand(f, angle, out);
        seen.push((f, addr, named.then(|| out[start..].into())));
        named
    }
}

/// Precedence levels: 0 top, 1 sum, 2 product, 3 power base.
fn write(e: &Expr, o: &PlainOptions, names: &mut Naming, prec: u8, out: &mut String) {
    let times = if o.shorthand { " " } else { "*" };
    match e {
        Expr::Num(q) => {
            if let Some(t) = decimal(q, o) {
                out.push_str(&t);
            } else if q.denom().is_one() || prec < 2 {
                out.push_str(&q.to_string());
            } else {
                out.push('(');
                out.push_str(&q.to_string());
                out.push(')');
            }
        }
        Expr::Sqrt(n) => out.push_str(&format!("sqrt({n})")),
        Expr::Sym(s) => out.push_str(s.name()),
        Expr::Trig { f, angle } => {
            if !names.write(*f, angle, o, out) {
                out.push_str(f.name());
                out.push('(');
                out.push_str(&angle_text_decimals(angle, o.decimals));
                out.push(')');
            }
        }
        Expr::Add(v) => {
            if prec > 1 {
                out.push('(');
            }
            for (i, t) in v.iter().enumerate() {
                match t {
                    Expr::Neg(inner) => {
                        out.push_str(if i == 0 { "-" } else { " - " });
                        // A fraction after the minus reads without brackets: `x - 3/4`.
                        let p = if matches!(**inner, Expr::Num(_)) {
                            1
                        } else {
                            2
                        };
                        write(inner, o, names, p, out);
                    }
                    t => {
                        if i > 0 {
                            out.push_str(" + ");
                        }
                        write(t, o, names, 1, out);
                    }
                }
            }
            if prec > 1 {
                out.push(')');
            }
        }
        Expr::Mul(v) => {
            // `pi/2`, `l/3`: a unit fraction times one symbol reads as a quotient.
            if let [Expr::Num(q), Expr::Sym(s)] = v.as_slice() {
                if q.numer().is_one() && !q.denom().is_one() && prec <= 2 && decimal(q, o).is_none()
                {
                    out.push_str(&format!("{}/{}", s.name(), q.denom()));
                    return;
                }
            }
            if prec > 2 {
                out.push('(');
            }
            for (i, t) in v.iter().enumerate() {
                if i > 0 {
                    out.push_str(times);
                }
                // A leading fraction reads as a coefficient: `3/8 cos(t)`.
                if i == 0 && matches!(t, Expr::Num(_)) {
                    if let Expr::Num(q) = t {
                        out.push_str(&decimal(q, o).unwrap_or_else(|| q.to_string()));
                    }
                    continue;
                }
                write(t, o, names, 2, out);
            }
            if prec > 2 {
                out.push(')');
            }
        }
        Expr::Neg(inner) => {
            if prec > 1 {
                out.push('(');
            }
            out.push('-');
            write(inner, o, names, 2, out);
            if prec > 1 {
                out.push(')');
            }
        }
        Expr::Pow(b, n) => {
            write(b, o, names, 3, out);
            out.push_str(&format!("^{n}"));
        }
    }
}

/// An upper bound of the length of [`plain`]`(e, opts)` for either setting of
/// `opts.shorthand`, found without writing the text: every number counted with as many
/// digits as its bits allow, every coefficient of an angle with its sign, `*`, `/` and
/// denominator, every bracket a precedence could add. For deciding that a report is short
/// (`app::fk::text_exceeds`) without printing it twice.
pub(crate) fn plain_len_bound(e: &Expr) -> usize {
    // Decimal digits of an integer of `bits` bits: at most bits * log10(2) + 1 <= bits/3 + 1.
    fn big_digits(bits: u64) -> usize {
        usize::try_from(bits / 3).unwrap_or(usize::MAX) + 1
    }
    fn digits(n: i64) -> usize {
        n.unsigned_abs()
            .checked_ilog10()
            .map_or(1, |d| d as usize + 1)
    }
    fn part(k: &crate::scalar::Small, name: &str) -> usize {
        // ` - 3*name/4`, or the number alone for the constant.
        3 + digits(*k.numer()) + 1 + name.len() + 1 + digits(*k.denom())
    }
    match e {
        // The sign, `(`, numerator, `/`, denominator, `)`.
        Expr::Num(q) => 4 + big_digits(q.numer().bits()) + big_digits(q.denom().bits()),
        Expr::Sqrt(_) => "sqrt()".len() + digits(i64::MAX) + 1,
        Expr::Sym(s) => s.name().len(),
        Expr::Trig { f, angle } => {
            // The shorthand: a letter, the symbols' names (their prefix and digits) and
            // separators.
            let short = 1 + angle
                .terms
                .iter()
                .map(|(s, _)| s.name().len() + 1)
                .sum::<usize>();
            // `cos(`, `(`, the parts, `)/d`, `)`, or `0`.
            let d = angle
                .terms
                .iter()
                .map(|(s, k)| part(k, s.name()))
                .sum::<usize>()
                + part(&angle.constant, "")
                + part(&angle.pi, "pi");
            let explicit = f.name().len() + 2 + 3 + digits(i64::MAX) + d + 1;
            short.max(explicit)
        }
        Expr::Add(v) | Expr::Mul(v) => 2 + v.iter().map(|x| 3 + plain_len_bound(x)).sum::<usize>(),
        Expr::Neg(x) => 3 + plain_len_bound(x),
        Expr::Pow(x, n) => plain_len_bound(x) + 1 + digits(i64::from(*n)),
    }
}

/// The shorthand names used in `exprs`, with their meaning, sorted:
/// `c12 = cos(theta1 + theta2)`.
pub fn legend(exprs: &[&Expr]) -> Vec<String> {
    // Each distinct call is named and written once: a name and its text are functions of the
    // call (its function and angle), so the set of entries is the same as naming every call
    // (a fully symbolic 6R's report: 4,904 calls of a few dozen distinct ones, whose names,
    // texts and ordered-set insertions were 6 M instructions, 6% of the report).
    let mut calls: CallSet = CallSet::default();
    for e in exprs {
        collect(e, &mut calls);
    }
    let seen: BTreeSet<(String, Trig, String)> = calls
        .into_iter()
        .filter_map(|Call(f, angle)| shorthand_name(f, angle).map(|n| (n, f, angle_text(angle))))
        .collect();
    seen.into_iter()
        .map(|(name, f, text)| format!("{name} = {}({text})", f.name()))
        .collect()
}

/// The distinct calls of a report (only collected, then sorted by their entries' text).
type CallSet<'a> =
    std::collections::HashSet<Call<'a>, std::hash::BuildHasherDefault<crate::scalar::FxHasher>>;

/// A call as a set key: equal as its function and angle are, hashed by the words of its
/// angle (each symbol's interned address, each coefficient's numerator and denominator), not
/// by `Angle`'s derived hash, which hashes each name's text and each rational by its
/// continued fraction. Equality is `Angle`'s (rationals by value), so the hash agrees with it
/// because every `Small` is kept in lowest terms (the invariant `atoms.rs`'s frequency hashes
/// rely on too): equal values, equal words.
#[derive(PartialEq, Eq)]
struct Call<'a>(Trig, &'a Angle);

impl std::hash::Hash for Call<'_> {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        let word = |h: &mut H, q: &crate::scalar::Small| {
            h.write_i64(*q.numer());
            h.write_i64(*q.denom());
        };
        self.0.hash(h);
        for (s, k) in &self.1.terms {
            h.write_usize(s.addr());
            word(h, k);
        }
        word(h, &self.1.constant);
        word(h, &self.1.pi);
    }
}

fn collect<'a>(e: &'a Expr, calls: &mut CallSet<'a>) {
    match e {
        Expr::Trig { f, angle } => {
            calls.insert(Call(*f, angle));
        }
        Expr::Add(v) | Expr::Mul(v) => v.iter().for_each(|x| collect(x, calls)),
        Expr::Neg(x) | Expr::Pow(x, _) => collect(x, calls),
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Small;
    use crate::{closed_form, Scalar, Sym};
    use num_rational::BigRational;
    use num_traits::Signed;

    #[test]
    fn the_length_bound_is_never_below_the_text() {
        let s = Scalar::sym;
        let q =
            |n: i64, d: i64| Scalar::rational(num_rational::BigRational::new(n.into(), d.into()));
        let (t1, t2, alpha5) = (s("theta1"), s("theta2"), s("alpha5"));
        let xs = [
            t1.cos() * s("l1") + (t1.clone() + t2.clone()).cos() * s("l2"),
            (t1.clone() * q(1, 2) + t2.clone() * q(1, 2)).sin().pow(3) * q(-123_456_789, 7),
            (t1.clone() + Scalar::pi() * q(2, 7)).cos() * Scalar::int(2).sqrt()
                - (t2.clone() * q(3, 4) + Scalar::int(5)).sin(),
            (alpha5.clone() - t1.clone() * q(5, 3) + Scalar::pi() * q(1, 5)).cos()
                * s("a").pow(4)
                * q(1, 1 << 40),
            (s("q12") + s("q3")).sin() * alpha5.cos() - Scalar::int(10).pow(30),
        ];
        for x in &xs {
            let e = closed_form(x).expect("closed form");
            // The bound is checked, and the closed form is the value it shows.
            assert_eq!(e.to_scalar(), *x);
            for shorthand in [true, false] {
                let text = plain(
                    &e,
                    &PlainOptions {
                        shorthand,
                        decimals: false,
                    },
                );
                assert!(
                    text.len() <= plain_len_bound(&e),
                    "{text}: {} over the bound {}",
                    text.len(),
                    plain_len_bound(&e)
                );
            }
        }
    }

    /// The legend names each distinct call once; its entries are those of naming every call
    /// (the route before, kept here): random sums and products of calls of angles over names
    /// with and without shorthand (`q1`, `q12`, `theta3`, `alpha5`, `x`, `q01`), coefficients
    /// and offsets, many calls repeated, some equal in text from different angles.
    #[test]
    fn the_legend_is_every_call_named() {
        fn every_call(exprs: &[&Expr]) -> Vec<String> {
            fn go(e: &Expr, seen: &mut BTreeSet<(String, Trig, String)>) {
                match e {
                    Expr::Trig { f, angle } => {
                        if let Some(n) = shorthand_name(*f, angle) {
                            seen.insert((n, *f, angle_text(angle)));
                        }
                    }
                    Expr::Add(v) | Expr::Mul(v) => v.iter().for_each(|x| go(x, seen)),
                    Expr::Neg(x) | Expr::Pow(x, _) => go(x, seen),
                    _ => {}
                }
            }
            let mut seen = BTreeSet::new();
            exprs.iter().for_each(|e| go(e, &mut seen));
            seen.into_iter()
                .map(|(name, f, text)| format!("{name} = {}({text})", f.name()))
                .collect()
        }
        let names = [
            "q1", "q2", "q3", "q12", "theta3", "alpha5", "x", "q01", "th2",
        ];
        let mut g = 0x2545_f491_4f6c_dd1d_u64;
        let mut named = 0;
        for _ in 0..300 {
            let mut exprs = Vec::new();
            for _ in 0..1 + below(&mut g, 4) {
                let mut terms = Vec::new();
                for _ in 0..1 + below(&mut g, 6) {
                    let mut factors = Vec::new();
                    for _ in 0..1 + below(&mut g, 3) {
                        let mut coefs: std::collections::BTreeMap<&str, i64> = Default::default();
                        for _ in 0..1 + below(&mut g, 3) {
                            let s = names[below(&mut g, names.len() as u64) as usize];
                            *coefs.entry(s).or_default() += [1, -1, 2][below(&mut g, 3) as usize];
                        }
                        let terms: Vec<(Sym, Small)> = coefs
                            .into_iter()
                            .filter(|(_, k)| *k != 0)
                            .map(|(s, k)| (Sym::new(s), Small::from_integer(k)))
                            .collect();
                        let pi = Small::new(i64::from(below(&mut g, 4) == 0), 3);
                        let f = if below(&mut g, 2) == 0 {
                            Trig::Cos
                        } else {
                            Trig::Sin
                        };
                        let angle = Angle::new(terms, Small::zero(), pi);
                        factors.push(Expr::Trig { f, angle });
                    }
                    terms.push(Expr::Mul(factors));
                }
                exprs.push(Expr::Add(terms));
            }
            let refs: Vec<&Expr> = exprs.iter().collect();
            let l = legend(&refs);
            assert_eq!(l, every_call(&refs));
            named += l.len();
        }
        assert!(named > 300, "{named}");
    }

    /// `plain` writes each shorthand in place ([`write_shorthand`]), a call of one symbol's
    /// angle named once per text ([`Naming`]); the route before, kept here, asked
    /// [`shorthand_name`] for a `String` per call through `plain_named`: both write the same
    /// text, with and without the shorthand, on random sums and products (quotients too)
    /// of calls whose angles have a name, have none, or fail only at a later symbol (a prefix
    /// that differs, a leading zero, a coefficient, an offset), nested in powers and
    /// negations.
    #[test]
    fn shorthand_written_in_place_is_the_named_text() {
        let names = [
            "q1", "q2", "q12", "theta3", "alpha5", "x", "q01", "th2", "t10", "θ4", "q7b",
        ];
        let mut g = 0x9e37_79b9_7f4a_7c15_u64;
        let call = |g: &mut u64| {
            let mut terms: Vec<(Sym, Small)> = Vec::new();
            for _ in 0..1 + below(g, 3) {
                let s = Sym::new(names[below(g, names.len() as u64) as usize]);
                if terms.iter().all(|(t, _)| *t != s) {
                    let k = [1, 1, 1, -1, 2][below(g, 5) as usize];
                    terms.push((s, Small::from_integer(k)));
                }
            }
            terms.sort();
            let constant = Small::from_integer(i64::from(below(g, 6) == 0));
            let pi = Small::new(i64::from(below(g, 6) == 0), 3);
            let f = [Trig::Cos, Trig::Sin][below(g, 2) as usize];
            Expr::Trig {
                f,
                angle: Angle::new(terms, constant, pi),
            }
        };
        let (mut short, mut long) = (0, 0);
        for _ in 0..400 {
            let mut sum = Vec::new();
            for _ in 0..1 + below(&mut g, 4) {
                let mut factors = vec![Expr::Num(BigRational::new(
                    (1 + below(&mut g, 3) as i64).into(),
                    (1 + below(&mut g, 2) as i64).into(),
                ))];
                for _ in 0..1 + below(&mut g, 3) {
                    let c = call(&mut g);
                    factors.push(match below(&mut g, 4) {
                        0 => Expr::Pow(Box::new(c), 2),
                        1 => Expr::Neg(Box::new(c)),
                        _ => c,
                    });
                }
                let m = Expr::Mul(factors);
                sum.push(if below(&mut g, 3) == 0 {
                    Expr::Neg(Box::new(m))
                } else {
                    m
                });
            }
            let e = Expr::Add(sum);
            let den = call(&mut g);
            for shorthand in [true, false] {
                let o = PlainOptions {
                    shorthand,
                    decimals: false,
                };
                let names =
                    |f: Trig, a: &Angle| o.shorthand.then(|| shorthand_name(f, a)).flatten();
                let text = plain(&e, &o);
                assert_eq!(text, plain_named(&e, &o, &names));
                assert_eq!(
                    plain_quotient(&e, &den, &o),
                    plain_quotient_named(&e, &den, &o, &names)
                );
                if shorthand {
                    short += usize::from(text.contains(" c") || text.contains(" s"));
                    long += usize::from(text.contains("cos(") || text.contains("sin("));
                }
            }
        }
        // Both kinds of call were written, in many of the sums.
        assert!(short > 100 && long > 100, "{short} {long}");
    }

    /// The next of xorshift state `g`, below `n`.
    fn below(g: &mut u64, n: u64) -> u64 {
        *g ^= *g << 13;
        *g ^= *g >> 7;
        *g ^= *g << 17;
        *g % n
    }

    /// A random display expression as the closed-form search writes one (numbers positive,
    /// a product's number first, negations only on the terms of sums), drawn from `g`, of
    /// nesting at most `depth`.
    fn random_form(g: &mut u64, depth: u32) -> Expr {
        let sym = |name: &str| Expr::Sym(Sym::new(name));
        let trig = |f: Trig, name: &str| Expr::Trig {
            f,
            angle: Angle::of_symbol(Sym::new(name)),
        };
        if depth == 0 || below(g, 4) == 0 {
            return match below(g, 5) {
                0 => sym("a"),
                1 => sym("b"),
                2 => trig(Trig::Cos, "t"),
                3 => trig(Trig::Sin, "u"),
                _ => Expr::Pow(Box::new(sym("a")), 2),
            };
        }
        let n = 2 + below(g, 2);
        if below(g, 2) == 0 {
            let mut terms = Vec::new();
            for _ in 0..n {
                let t = match random_form(g, depth - 1) {
                    Expr::Add(v) => Expr::Mul(vec![sym("b"), Expr::Add(v)]),
                    t => t,
                };
                terms.push(if below(g, 2) == 0 {
                    Expr::Neg(Box::new(t))
                } else {
                    t
                });
            }
            Expr::Add(terms)
        } else {
            let mut factors = Vec::new();
            if below(g, 3) == 0 {
                let d = 1 + below(g, 4) as i64;
                factors.push(Expr::Num(BigRational::new(1.into(), d.into())));
            }
            for _ in 0..n {
                match random_form(g, depth - 1) {
                    Expr::Mul(v) => {
                        factors.extend(v.into_iter().filter(|f| !matches!(f, Expr::Num(_))))
                    }
                    f => factors.push(f),
                }
            }
            Expr::Mul(factors)
        }
    }

    /// On many random forms (sums of products of sums, three levels), a form times -1, 1/2 or
    /// -3 is that multiple of its value exactly, holds no `-(-x)`, and a negative multiple
    /// prints no longer than the sign left in front of the positive one: the sign placement
    /// `Expr::scaled` finds from the texts of the terms and factors (checked against the texts
    /// of the products it builds in debug builds).
    #[test]
    fn random_forms_scaled_are_their_multiples_and_no_longer() {
        let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
        let po = PlainOptions {
            shorthand: false,
            decimals: false,
        };
        let mut g = 0x9e37_79b9_7f4a_7c15_u64;
        let (mut shorter, mut cases) = (0, 0);
        for _ in 0..400 {
            let e = match random_form(&mut g, 3) {
                Expr::Neg(x) => *x,
                e => e,
            };
            let x = e.to_scalar();
            for c in [q(-1, 1), q(1, 2), q(-3, 1)] {
                let s = scaled_exactly(&e, &x, &c);
                if c.is_negative() {
                    shorter += usize::from(no_longer_than_in_front(&e, &s, &c, &po));
                    cases += 1;
                }
            }
        }
        assert_eq!(cases, 800);
        assert!(shorter > 100, "{shorter}");
    }

    /// `e` (whose value is `x`) times `c`, asserted to be `c x` exactly and to hold no
    /// `-(-x)`.
    fn scaled_exactly(e: &Expr, x: &Scalar, c: &BigRational) -> Expr {
        let s = e.clone().scaled(c);
        assert_eq!(
            s.to_scalar(),
            x.clone() * Scalar::rational(c.clone()),
            "{e:?} {c}"
        );
        assert!(!badly_signed(&s), "{s:?}");
        s
    }

    /// Asserts that `s` (`e` times `c`) prints no longer than the sign left in front of `e`
    /// times `-c`; whether it prints strictly shorter.
    fn no_longer_than_in_front(e: &Expr, s: &Expr, c: &BigRational, po: &PlainOptions) -> bool {
        let front = Expr::Neg(Box::new(e.clone().scaled(&-c.clone())));
        let (new, old) = (plain(s, po), plain(&front, po));
        assert!(new.len() <= old.len(), "{new} vs {old}");
        new.len() < old.len()
    }

    /// Whether `e` holds a `-(-x)`, a negation as a product's factor or a negative number.
    fn badly_signed(e: &Expr) -> bool {
        match e {
            Expr::Neg(x) => matches!(**x, Expr::Neg(_)) || badly_signed(x),
            Expr::Mul(v) => v
                .iter()
                .any(|f| matches!(f, Expr::Neg(_)) || badly_signed(f)),
            Expr::Add(v) => v.iter().any(badly_signed),
            Expr::Pow(x, _) => badly_signed(x),
            Expr::Num(q) => q < &BigRational::zero(),
            _ => false,
        }
    }

    /// A closed form times a rational is that rational times its value, exactly, on the
    /// closed forms of many computed scalars (sums, products with sums as factors, radicals,
    /// constant angles) and factors of every sign; the sign is placed without `-(-x)` and the
    /// plain text is never longer than the form with the sign left in front.
    #[test]
    fn a_scaled_closed_form_is_the_multiple_of_its_value() {
        let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
        let (t, u, a) = (Scalar::sym("t"), Scalar::sym("u"), Scalar::sym("a"));
        let half = Scalar::rational(q(1, 2));
        let scalars = [
            t.cos() - u.sin(),
            u.sin() - t.cos(),
            (t.cos() + u.sin()) * half.clone(),
            (t.cos() - u.sin() * Scalar::int(3)) * (t.clone() + u.clone()).cos() * half.clone(),
            a.clone() * (t.clone() - u.clone()).sin() * Scalar::int(2).sqrt() - u.cos(),
            ((t.clone() * half.clone()).cos() * (u.clone() * half).sin() - a.clone())
                * Scalar::rational(q(-3, 8)),
            (t.clone() + Scalar::pi() * Scalar::rational(q(5, 18))).cos() * a.clone() + u.sin(),
            a.pow(2) - Scalar::int(1),
            Scalar::int(0),
            Scalar::rational(q(-5, 7)),
        ];
        let po = PlainOptions {
            shorthand: false,
            decimals: false,
        };
        let mut placed = 0;
        for x in &scalars {
            let e = crate::closed_form(x).expect("closed form");
            assert_eq!(e.to_scalar(), *x);
            for c in [
                q(1, 1),
                q(-1, 1),
                q(1, 2),
                q(-1, 2),
                q(-3, 4),
                q(2, 1),
                q(-7, 3),
            ] {
                let s = scaled_exactly(&e, x, &c);
                if c.is_one() {
                    assert_eq!(s, e);
                }
                placed += usize::from(no_longer_than_in_front(&e, &s, &c, &po));
            }
        }
        assert!(placed > 5, "{placed}");
        // The search's style: `-(1/4 (a - b))` is `1/4 (b - a)`; `-1/4 (a + b)` stays.
        let sum = |neg: bool| {
            let b = Expr::Trig {
                f: Trig::Sin,
                angle: Angle::of_symbol(Sym::new("u")),
            };
            Expr::Mul(vec![
                Expr::Num(q(1, 4)),
                Expr::Add(vec![
                    Expr::Sym(Sym::new("a")),
                    if neg { Expr::Neg(Box::new(b)) } else { b },
                ]),
            ])
        };
        let text = |e: Expr| plain(&e.scaled(&q(-1, 1)), &po);
        assert_eq!(text(sum(true)), "1/4*(sin(u) - a)");
        assert_eq!(text(sum(false)), "-1/4*(a + sin(u))");
    }
}
