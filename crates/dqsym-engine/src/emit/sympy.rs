//! Text that SymPy's `sympify` parses back to the same value: integers, rationals, `+ - * / **`,
//! parentheses, `sqrt`, `sin`, `cos`, `pi` and the user's symbols.
//!
//! Symbol names are written as they are, but a name `sympify` reads as something else (the
//! constants `E`, `I`, `oo`, `nan`, `zoo`, the functions `beta`, `gamma`, `S`, `N`, `O`, `Q`, a
//! Python keyword `lambda`: the table of [`super::names`]) is written `Symbol('E')`, so that
//! plain `sympify(text)` reads every symbol back as the symbol.

use super::names::sympy_symbol;
use crate::closed::{angle_text_with, Expr};
use num_traits::One;

/// The expression as SymPy input: `l1*cos(theta1) + l2*cos(theta1 + theta2)`, `(3/8)*x`,
/// `sqrt(2)*sin(theta/2)`, `Symbol('E')*x`; the canonical 1 is `1`.
pub fn sympy(e: &Expr) -> String {
    let mut out = String::new();
    write(e, 0, &sympy_symbol, &mut out);
    out
}

/// The same text with every symbol written by its name alone: what dqsym's own language
/// reads (robot files written by `convert`).
pub(crate) fn dqsym_text(e: &Expr) -> String {
    let mut out = String::new();
    write(e, 0, &str::to_owned, &mut out);
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
fn write(e: &Expr, prec: u8, sym: &dyn Fn(&str) -> String, out: &mut String) {
    match e {
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
                        write(inner, 2, sym, out);
                    }
                    t => {
                        if i > 0 {
                            out.push_str(" + ");
                        }
                        write(t, 1, sym, out);
                    }
                }
            }
            if prec > 1 {
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
                write(t, 2, sym, out);
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
            write(inner, 2, sym, out);
            if prec > 1 {
                out.push(')');
            }
        }
        Expr::Pow(b, n) => {
            write(b, 3, sym, out);
            out.push_str(&format!("**{n}"));
        }
    }
}
