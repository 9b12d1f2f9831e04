//! Plain text in the field's notation: robotics shorthand (`l1 c1 + l2 c12`) or explicit
//! (`l1*cos(theta1) + l2*cos(theta1 + theta2)`).

use crate::closed::{angle_text, shorthand_name, Angle, Expr, Trig, TrigNames};
use num_traits::One;
use std::collections::BTreeSet;

/// How plain text is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlainOptions {
    /// `c12` for `cos(theta1 + theta2)` where the angle allows it (see [`shorthand_name`]).
    pub shorthand: bool,
}

impl Default for PlainOptions {
    fn default() -> Self {
        PlainOptions { shorthand: true }
    }
}

/// The expression as plain text.
pub fn plain(e: &Expr, opts: &PlainOptions) -> String {
    let names = |f: Trig, a: &Angle| opts.shorthand.then(|| shorthand_name(f, a)).flatten();
    plain_named(e, opts, &names)
}

/// The expression as plain text, cos and sin named by `names` (a walkthrough's notation)
/// instead of [`shorthand_name`]; `opts.shorthand` still chooses `l1 c1` over `l1*c1`.
pub fn plain_named(e: &Expr, opts: &PlainOptions, names: TrigNames) -> String {
    let mut out = String::new();
    write(e, opts, names, 0, &mut out);
    out
}

/// The quotient `num / den` as plain text, `num` alone when `den` is 1. A part that is a sum or
/// a product is bracketed, so the quotient reads one way: `(d1 s - d2 c)/(2 s)`, `-l/sin(t)`.
pub fn plain_quotient(num: &Expr, den: &Expr, opts: &PlainOptions) -> String {
    if matches!(den, Expr::Num(q) if q.is_one()) {
        return plain(num, opts);
    }
    let names = |f: Trig, a: &Angle| opts.shorthand.then(|| shorthand_name(f, a)).flatten();
    plain_quotient_named(num, den, opts, &names)
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
    let mut out = String::new();
    match num {
        Expr::Neg(inner) => {
            out.push('-');
            write(inner, opts, names, 3, &mut out);
        }
        _ => write(num, opts, names, 3, &mut out),
    }
    out.push('/');
    write(den, opts, names, 3, &mut out);
    out
}

/// Precedence levels: 0 top, 1 sum, 2 product, 3 power base.
fn write(e: &Expr, o: &PlainOptions, names: TrigNames, prec: u8, out: &mut String) {
    let times = if o.shorthand { " " } else { "*" };
    match e {
        Expr::Num(q) => {
            if q.denom().is_one() || prec < 2 {
                out.push_str(&q.to_string());
            } else {
                out.push('(');
                out.push_str(&q.to_string());
                out.push(')');
            }
        }
        Expr::Sqrt(n) => out.push_str(&format!("sqrt({n})")),
        Expr::Sym(s) => out.push_str(s.name()),
        Expr::Trig { f, angle } => match names(*f, angle) {
            Some(name) => out.push_str(&name),
            None => {
                out.push_str(f.name());
                out.push('(');
                out.push_str(&angle_text(angle));
                out.push(')');
            }
        },
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
                if q.numer().is_one() && !q.denom().is_one() && prec <= 2 {
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
                        out.push_str(&q.to_string());
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

/// The shorthand names used in `exprs`, with their meaning, sorted:
/// `c12 = cos(theta1 + theta2)`.
pub fn legend(exprs: &[&Expr]) -> Vec<String> {
    let mut seen = BTreeSet::new();
    for e in exprs {
        collect(e, &mut seen);
    }
    seen.into_iter()
        .map(|(name, f, text)| format!("{name} = {}({text})", f.name()))
        .collect()
}

fn collect(e: &Expr, seen: &mut BTreeSet<(String, Trig, String)>) {
    match e {
        Expr::Trig { f, angle } => {
            if let Some(n) = shorthand_name(*f, angle) {
                seen.insert((n, *f, angle_text(angle)));
            }
        }
        Expr::Add(v) | Expr::Mul(v) => v.iter().for_each(|x| collect(x, seen)),
        Expr::Neg(x) | Expr::Pow(x, _) => collect(x, seen),
        _ => {}
    }
}
