//! The script language: grammar, syntax tree, parser and printer.
//!
//! Text goes in, a [`Program`] comes out; the language layer never sees a quaternion. Names
//! such as `I`, `eps` and `pi`, built-ins such as `conj` and `dh`, and the half-angle
//! declarations are all plain syntax here; the evaluator gives them meaning.
//!
//! - `grammar/dqsym.pest`: the grammar, one documented rule per construct.
//! - `ast`: the tree, with a [`Span`] on every node.
//! - `parse`: pest, the Pratt table, and one lowering function per rule.
//! - `scan`: the bracket pre-scan and byte-to-line:column mapping.
//! - `error`: [`ParseError`] and its rendering with a caret.
//! - `print`: `Display` back to source, such that parsing the output gives the same tree.

mod ast;
mod error;
mod names;
mod parse;
mod print;
mod scan;

pub use ast::{AddOp, Expr, ExprKind, Ident, MulOp, Program, Span, Stmt, StmtKind, UnaryOp};
pub use error::{ParseError, ParseErrorKind};
pub use parse::{parse, parse_expr, parse_expr_with, parse_with, ParseOptions};
