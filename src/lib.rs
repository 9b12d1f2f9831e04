//! dqsym: exact symbolic algebra of dual quaternions for robot kinematics.

#![warn(missing_docs)]

pub use dqsym_engine::*;

mod lang;
mod paper;
mod walk;

pub use lang::{
    builtin, continues, eval_point_text, eval_scalar_text, parse, parse_expr, parse_expr_with,
    parse_with, show, show_value, AddOp, Binding, BindingKind, Builtin, Displayed, EvalError,
    EvalErrorKind, Expr as AstExpr, ExprKind, Format, Ident, MulOp, ParseError, ParseErrorKind,
    ParseOptions, Program, Session, ShowError, ShowOptions, Span, Stmt, StmtKind, UnaryOp, Value,
    BUILTINS, CONSTANTS, MAX_EXPONENT,
};
pub use paper::paper;
pub use walk::{
    mechanism_svg, walk_html, walk_markdown, walk_robot, walk_robot_chain, walk_script, walk_text,
    ComponentTrace, Config, HalfAngle, KatexAssets, Mechanism, Motion, Step, SvgOptions, WalkError,
    Walkthrough, Word, Words,
};
