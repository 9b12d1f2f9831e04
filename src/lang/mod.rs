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
//! - `value`: the [`Value`]s a script computes and the typing rules of their arithmetic.
//! - `eval`: the [`Session`] that runs statements and keeps bindings; [`EvalError`].
//! - `builtins`: the table of built-in functions and their implementations.
//! - `show`: displayed results as text (closed form, then a printer).

mod ast;
mod builtins;
mod dqr;
mod error;
mod eval;
mod field;
mod names;
mod parse;
mod print;
mod scan;
mod show;
mod value;

pub use ast::{AddOp, Expr, ExprKind, Ident, MulOp, Program, Span, Stmt, StmtKind, UnaryOp};
pub use builtins::{lookup as builtin, Builtin, BUILTINS};
pub use error::{ParseError, ParseErrorKind};
pub use eval::{
    Binding, BindingKind, Displayed, EvalError, EvalErrorKind, Session, CONSTANTS, KEYWORDS,
};
pub(crate) use eval::{Event, Observer};
pub use field::{eval_point_text, eval_scalar_text};
pub use parse::{parse, parse_expr, parse_expr_with, parse_with, ParseOptions, DEFAULT_MAX_DEPTH};
pub use scan::continues;
pub use show::{show, show_value, ShowError, ShowOptions};
pub use value::{Value, MAX_EXPONENT};
