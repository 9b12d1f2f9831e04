//! dqsym: exact symbolic algebra of dual quaternions for robot kinematics.

mod algebra;
mod closed;
mod kin;
mod lang;
mod print;
mod ring;
mod scalar;

pub use algebra::{DualNumber, DualQuat, Matrix4, Quat, UnitConstraints};
pub use closed::{closed_form, Angle, Cost, Expr};
pub use kin::{
    dh_link, dh_link_matrix, mdh_link, mdh_link_matrix, Chain, ChainError, Joint, JointGeometry,
    JointKind,
};
pub use lang::{
    builtin, parse, parse_expr, parse_expr_with, parse_with, show, show_value, AddOp, Binding,
    BindingKind, Builtin, Displayed, EvalError, EvalErrorKind, Expr as AstExpr, ExprKind, Format,
    Ident, MulOp, ParseError, ParseErrorKind, ParseOptions, Program, Session, ShowOptions, Span,
    Stmt, StmtKind, UnaryOp, Value, BUILTINS, CONSTANTS, MAX_EXPONENT,
};
pub use print::{legend, plain, shorthand_name, PlainOptions};
pub use ring::Ring;
pub use scalar::{set_term_limit, term_limit, Scalar, ScalarError, Sym};
