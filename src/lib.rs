//! dqsym: exact symbolic algebra of dual quaternions for robot kinematics.

mod algebra;
mod closed;
mod emit;
mod kin;
mod lang;
mod print;
mod ring;
mod scalar;

pub use algebra::{DualNumber, DualQuat, Matrix4, Quat, UnitConstraints};
pub use closed::{closed_form, Angle, Cost, Expr};
pub use emit::{
    arguments, c_function, count_ops, generated_ops, latex, latex_aligned, latex_dual_quat,
    latex_matrix, latex_symbol, latex_tuple, python_function, rust_function, sympy, CodegenError,
    CodegenOptions, Counted, LatexOptions, OpCount, Output,
};
pub use kin::{
    dh_link, dh_link_matrix, mdh_link, mdh_link_matrix, Chain, ChainError, Joint, JointGeometry,
    JointKind,
};
pub use lang::{
    parse, parse_expr, parse_expr_with, parse_with, AddOp, Expr as AstExpr, ExprKind, Ident, MulOp,
    ParseError, ParseErrorKind, ParseOptions, Program, Span, Stmt, StmtKind, UnaryOp,
};
pub use print::{legend, plain, shorthand_name, PlainOptions};
pub use ring::Ring;
pub use scalar::{set_term_limit, term_limit, Scalar, ScalarError, Sym};
