//! dqsym: exact symbolic algebra of dual quaternions for robot kinematics.

mod algebra;
mod lang;
mod ring;

pub use lang::{
    parse, parse_expr, parse_expr_with, parse_with, AddOp, Expr, ExprKind, Ident, MulOp,
    ParseError, ParseErrorKind, ParseOptions, Program, Span, Stmt, StmtKind, UnaryOp,
};
pub use ring::Ring;
