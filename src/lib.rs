//! dqsym: exact symbolic algebra of dual quaternions for robot kinematics.

mod algebra;
mod closed;
mod emit;
pub mod ik;
mod kin;
mod lang;
mod print;
mod ring;
mod scalar;
mod walk;

pub use algebra::dqr;
pub use algebra::{DualNumber, DualQuat, Matrix4, Quat, UnitConstraints};
pub use closed::{
    closed_form, closed_form_cos_sin, closed_form_of_derivative, closed_form_prepared,
    closed_form_traced, expanded_form, Angle, Cost, Expr, Identity, Prepared, TraceStep,
};
pub use emit::{
    arguments, c_function, count_ops, generated_ops, javascript_function, latex, latex_aligned,
    latex_aligned_named, latex_dual_quat, latex_matrix, latex_named, latex_quotient,
    latex_quotient_matrix, latex_symbol, latex_tuple, product_table, python_function,
    rotation_chain_ops, rust_function, sympy, sympy_quotient, CodegenError, CodegenOptions,
    Counted, LatexOptions, OpCount, Output,
};
pub use kin::dqexp;
pub use kin::{
    dh_link, dh_link_matrix, dq_jacobian, geometric_jacobian, mdh_link, mdh_link_matrix,
    parse_robot, parse_urdf, screw_parameters, Chain, ChainError, Convention, FieldEval, Frame,
    Joint, JointGeometry, JointKind, Robot, RobotError, ScrewError, ScrewParams, UrdfError,
    UrdfOptions, UrdfRobot, SNAP_TOLERANCE,
};
pub use lang::{
    builtin, continues, eval_point_text, eval_scalar_text, parse, parse_expr, parse_expr_with,
    parse_with, show, show_value, AddOp, Binding, BindingKind, Builtin, Displayed, EvalError,
    EvalErrorKind, Expr as AstExpr, ExprKind, Format, Ident, MulOp, ParseError, ParseErrorKind,
    ParseOptions, Program, Session, ShowError, ShowOptions, Span, Stmt, StmtKind, UnaryOp, Value,
    BUILTINS, CONSTANTS, MAX_EXPONENT,
};
pub use print::{
    dh_refusal, fk_entries, fk_recurrence, fk_report, legend, ops_tables, plain, plain_named,
    plain_quotient, plain_quotient_named, rate_name, robot_toml, shorthand_name, task_jacobian,
    task_report, FkEntries, FkOptions, PlainOptions, ReportError, ReportFormat, TaskJacobian,
    TaskMatrix, TrigNames,
};
pub use ring::Ring;
pub use scalar::{
    parse_decimal, parse_trig_placeholder, trig_placeholder, Context, Entered, Frac, Scalar,
    ScalarError, Sym, DEFAULT_MAX_EXPONENT,
};
pub use walk::{
    ik_walk_html, mechanism_svg, walk_html, walk_markdown, walk_robot, walk_robot_chain,
    walk_script, walk_text, ComponentTrace, Config, HalfAngle, KatexAssets, Mechanism, Motion,
    Step, SvgOptions, WalkError, Walkthrough, Word, Words,
};
