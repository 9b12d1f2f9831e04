//! Text that SymPy's `sympify` parses back to the same value: integers, rationals, `+ - * / **`,
//! parentheses, `sqrt`, `sin`, `cos`, `pi` and the user's symbols.
//!
//! Symbol names are written as they are, but a name `sympify` reads as something else (the
//! constants `E`, `I`, `oo`, `nan`, `zoo`, the functions `beta`, `gamma`, `S`, `N`, `O`, `Q`, a
//! Python keyword `lambda`: the table of [`super::names`]) is written `Symbol('E')`, so that
//! plain `sympify(text)` reads every symbol back as the symbol.

use super::names::sympy_symbol;
use crate::closed::{angle_text_with, shows_as_decimal, Expr};
use num_traits::One;

/// The expression as SymPy input: `l1*cos(theta1) + l2*cos(theta1 + theta2)`, `(3/8)*x`,
/// `sqrt(2)*sin(theta/2)`, `Symbol('E')*x`; the canonical 1 is `1`.
pub fn sympy(e: &Expr) -> String {
    let mut out = String::new();
    write(e, 0, &sympy_symbol, false, &mut out);
    out
}

/// The same text with every symbol written by its name alone: what dqsym's own language
/// reads (robot files written by `convert`).
pub(crate) fn dqsym_text(e: &Expr) -> String {
    let mut out = String::new();
    write(e, 0, &str::to_owned, false, &mut out);
    out
}

/// [`sympy`] with decimal fractions (a factor 5 in the denominator) written as their digits
/// over a power of ten, `(425/1000)` for 0.425 (exact; a bare `0.425` would be a float to
/// `sympify`), for robots whose file wrote decimals (see
/// [`decimal_form`](crate::closed::decimal_form)).
pub fn sympy_decimals(e: &Expr) -> String {
    let mut out = String::new();
    write(e, 0, &sympy_symbol, true, &mut out);
    out
}

/// The quotient `num / den` as SymPy input, `(num)/(den)`; `num` alone when `den` is 1.
pub fn sympy_quotient(num: &Expr, den: &Expr) -> String {
    if matches!(den, Expr::Num(q) if q.is_one()) {
        return sympy(num);
    }
    format!("({})/({})", sympy(num), sympy(den))
}

/// Precedence levels: 0 top, 1 sum term, 2 product factor, 3 power base.
fn write(e: &Expr, prec: u8, sym: &dyn Fn(&str) -> String, dec: bool, out: &mut String) {
    let write = |e: &Expr, prec: u8, out: &mut String| write(e, prec, sym, dec, out);
    match e {
        Expr::Num(q) if dec && shows_as_decimal(q) => {
            // The decimal's digits over its power of ten, `(425/1000)` for 0.425: exact for
            // `sympify` with no name to bind (a bare `0.425` would be a float).
            let places = crate::scalar::decimal_places(q).unwrap_or(0);
            let scale = num_bigint::BigInt::from(10u32).pow(u32::try_from(places).unwrap_or(0));
            let digits = (q * num_rational::BigRational::from_integer(scale.clone())).to_integer();
            out.push_str(&format!("({digits}/{scale})"));
        }
        Expr::Num(q) => {
            // `(3/8)` keeps the division from binding to a neighbour in `x*(3/8)`.
            if q.denom().is_one() || prec == 0 {
                out.push_str(&q.to_string());
            } else {
                out.push_str(&format!("({q})"));
            }
        }
        Expr::Sqrt(n) => out.push_str(&format!("sqrt({n})")),
        Expr::Sym(s) if s.is_pi() => out.push_str("pi"),
        Expr::Sym(s) => out.push_str(&sym(s.name())),
        Expr::Trig { f, angle } => {
            out.push_str(f.name());
            out.push('(');
            out.push_str(&angle_text_with(angle, sym));
            out.push(')');
        }
        Expr::Add(v) => {
            if prec > 1 {
                out.push('(');
            }
            for (i, t) in v.iter().enumerate() {
                match t {
                    Expr::Neg(inner) => {
                        out.push_str(if i == 0 { "-" } else { " - " });
                        write(inner, 2, out);
                    }
                    t => {
                        if i > 0 {
                            out.push_str(" + ");
                        }
                        write(t, 1, out);
                    }
                }
            }
            if prec > 1 {
                out.push(')');
            }
        }
        // `2*(a + b)*c` would be read `(2*a + 2*b)*c`: Python multiplies left to right, and
        // SymPy distributes a number over a sum it multiplies alone. `2*((a + b)*c)` is the
        // tree `Mul(2, a + b, c)`, which the Python package builds from the same expression.
        Expr::Mul(v)
            if v.len() > 2 && matches!(v[0], Expr::Num(_)) && matches!(v[1], Expr::Add(_)) =>
        {
            if prec > 2 {
                out.push('(');
            }
            write(&v[0], 2, out);
            out.push_str("*(");
            write(&Expr::Mul(v[1..].to_vec()), 0, out);
            out.push(')');
            if prec > 2 {
                out.push(')');
            }
        }
        Expr::Mul(v) => {
            if prec > 2 {
                out.push('(');
            }
            for (i, t) in v.iter().enumerate() {
                if i > 0 {
                    out.push('*');
                }
                write(t, 2, out);
            }
            if prec > 2 {
                out.push(')');
            }
        }
        Expr::Neg(inner) => {
            // `-x**2` is `-(x**2)` in Python, so a power needs no parentheses here.
            if prec > 1 {
                out.push('(');
            }
            out.push('-');
            write(inner, 2, out);
            if prec > 1 {
                out.push(')');
            }
        }
        Expr::Pow(b, n) => {
            write(b, 3, out);
            out.push_str(&format!("**{n}"));
        }
    }
}
