//! Printing the tree back to source.
//!
//! The printer adds only the parentheses that precedence requires, so its output reads like
//! hand-written source (`(c3, s3, 0, 0) + I*(0, 0, -(l1 + l2)*s3)`).
//!
//! # Laws
//! For every tree the parser can produce, `parse_expr(&e.to_string())` gives `e` back, up to
//! spans ([`Expr::erase_spans`]); the same holds for statements and programs. This is why a
//! sum or product that is the *first* operand of a chain of its own level is parenthesized:
//! `(a + b) + c` is a different tree from `a + b + c`.

use super::ast::{AddOp, Expr, ExprKind, Ident, MulOp, Program, Stmt, StmtKind, UnaryOp};
use std::fmt::{self, Display, Formatter};

/// How tightly an expression binds when printed; an operand printed in a slot that needs a
/// tighter level is parenthesized.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Level {
    Sum,
    Product,
    Neg,
    Pow,
    Postfix,
    Atom,
}

fn level(e: &Expr) -> Level {
    match &e.kind {
        ExprKind::Sum { .. } => Level::Sum,
        ExprKind::Product { .. } => Level::Product,
        ExprKind::Unary {
            op: UnaryOp::Neg, ..
        } => Level::Neg,
        ExprKind::Pow { .. } => Level::Pow,
        ExprKind::Unary {
            op: UnaryOp::Conj, ..
        } => Level::Postfix,
        _ => Level::Atom,
    }
}

/// Writes `e`, parenthesized unless it binds at least as tightly as `min`.
fn operand(f: &mut Formatter<'_>, e: &Expr, min: Level) -> fmt::Result {
    if level(e) < min {
        write!(f, "({e})")
    } else {
        write!(f, "{e}")
    }
}

/// Writes `items` separated by `, `.
fn list(f: &mut Formatter<'_>, items: &[Expr]) -> fmt::Result {
    for (i, item) in items.iter().enumerate() {
        if i > 0 {
            f.write_str(", ")?;
        }
        write!(f, "{item}")?;
    }
    Ok(())
}

impl Display for Expr {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match &self.kind {
            ExprKind::Int(n) => write!(f, "{n}"),
            ExprKind::Decimal { text, .. } => f.write_str(text),
            ExprKind::Degrees { text, .. } => write!(f, "{text}deg"),
            ExprKind::Name(name) => f.write_str(name),
            ExprKind::Unary {
                op: UnaryOp::Neg,
                operand: x,
            } => {
                f.write_str("-")?;
                operand(f, x, Level::Neg)
            }
            ExprKind::Unary {
                op: UnaryOp::Conj,
                operand: x,
            } => {
                operand(f, x, Level::Atom)?;
                f.write_str("'")
            }
            ExprKind::Sum { first, rest } => {
                operand(f, first, Level::Product)?;
                for (op, term) in rest {
                    f.write_str(match op {
                        AddOp::Add => " + ",
                        AddOp::Sub => " - ",
                    })?;
                    operand(f, term, Level::Product)?;
                }
                Ok(())
            }
            ExprKind::Product { first, rest } => {
                operand(f, first, Level::Neg)?;
                for (op, factor) in rest {
                    f.write_str(match op {
                        MulOp::Mul => "*",
                        MulOp::Div => "/",
                    })?;
                    operand(f, factor, Level::Neg)?;
                }
                Ok(())
            }
            ExprKind::Pow { base, exponent } => {
                operand(f, base, Level::Postfix)?;
                f.write_str("^")?;
                operand(f, exponent, Level::Neg)
            }
            ExprKind::Call { func, args } => {
                write!(f, "{func}(")?;
                list(f, args)?;
                f.write_str(")")
            }
            ExprKind::Tuple(items) => {
                f.write_str("(")?;
                list(f, items)?;
                f.write_str(")")
            }
            ExprKind::Matrix(rows) => {
                f.write_str("[")?;
                for (i, row) in rows.iter().enumerate() {
                    if i > 0 {
                        f.write_str("; ")?;
                    }
                    list(f, row)?;
                }
                f.write_str("]")
            }
        }
    }
}

impl Display for Ident {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name)
    }
}

impl Display for Stmt {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match &self.kind {
            StmtKind::Assign { name, value } => write!(f, "{name} = {value}"),
            StmtKind::Expr(e) => write!(f, "{e}"),
            StmtKind::Syms(names) => {
                f.write_str("syms")?;
                names.iter().try_for_each(|n| write!(f, " {n}"))
            }
            StmtKind::HalfAngle { cos, sin, angle } => {
                write!(f, "halfangle {cos}, {sin} = {angle}")
            }
        }
    }
}

/// One statement per line, with `;` after the quiet ones.
impl Display for Program {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        self.statements.iter().try_for_each(|s| {
            let end = if s.quiet { ";" } else { "" };
            writeln!(f, "{s}{end}")
        })
    }
}
