//! dqsym-engine: the engine of dqsym, exact symbolic algebra of dual quaternions for robot
//! kinematics: scalars, algebra, kinematics, closed forms, printers, emitters and reports.
//! The script language, the walkthroughs and the command line live in the `dqsym` crate.

#![warn(missing_docs)]

pub mod algebra;
pub mod app;
pub mod closed;
pub mod emit;
pub mod ik;
pub mod kin;
pub mod print;
mod ring;
pub mod scalar;

pub use algebra::dqr;
pub use algebra::{DualNumber, DualQuat, Matrix4, Quat, UnitConstraints};
pub use app::{
    fk_entries, fk_recurrence, fk_report, ops_tables, rate_name, robot_toml, task_jacobian,
    task_report, FkEntries, FkOptions, ReportError, ReportFormat, TaskJacobian,
};
pub use closed::{
    closed_form, closed_form_cos_sin, closed_form_of_derivative, closed_form_prepared,
    closed_form_traced, expanded_form, shorthand_name, Angle, Cost, Expr, Identity, Prepared,
    TraceStep, TrigNames,
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
pub use print::{legend, plain, plain_named, plain_quotient, plain_quotient_named, PlainOptions};
pub use ring::Ring;
pub use scalar::{
    parse_decimal, parse_trig_placeholder, trig_placeholder, Context, Entered, Frac, Scalar,
    ScalarError, Sym, DEFAULT_MAX_EXPONENT,
};
