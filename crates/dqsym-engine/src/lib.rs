//! dqsym-engine: the engine of dqsym, exact symbolic algebra of dual quaternions for robot
//! kinematics. The script language, the walkthroughs and the command line are the `dqsym`
//! crate's; this crate has no command-line dependency.
//!
//! Data moves one way through its modules, each a layer (ARCHITECTURE.md's table, which a
//! test enforces):
//!
//! - [`scalar`]: the exact [`Scalar`] (a canonical finite Fourier series over rationals and
//!   square roots) and the execution [`Context`] (limits, work budget, threads, cancel flag);
//! - [`algebra`]: [`Quat`], [`DualQuat`], [`Matrix4`] over any [`Ring`];
//! - [`closed`]: [`closed_form`], the most readable equal display expression [`Expr`];
//! - [`print`](mod@print) and [`emit`]: display expressions to plain text, LaTeX, SymPy and code;
//! - [`kin`]: links, chains, robot files ([`Robot`]), Jacobians, screws;
//! - [`app`] and [`ik`]: the `fk` report, task Jacobians, operation counts, inverse kinematics.
//!
//! The core nouns are re-exported here; everything else is reached through its module.
//!
//! ```
//! use dqsym_engine::{closed_form, plain, DualQuat, PlainOptions, Scalar};
//!
//! // Two rotations about the x axis compose to one rotation by the sum of the angles.
//! let x = [Scalar::int(1), Scalar::int(0), Scalar::int(0)];
//! let q = DualQuat::rotation(&x, &Scalar::sym("theta1"))
//!     * DualQuat::rotation(&x, &Scalar::sym("theta2"));
//! let m = q.to_matrix();
//! let e = closed_form(&m.rows[1][1])?;
//! assert_eq!(plain(&e, &PlainOptions { shorthand: true }), "c12");
//! assert_eq!(plain(&e, &PlainOptions { shorthand: false }), "cos(theta1 + theta2)");
//! # Ok::<(), dqsym_engine::ScalarError>(())
//! ```

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

// The core nouns.
pub use algebra::{DualQuat, Matrix4, Quat};
pub use app::{fk_report, FkOptions, ReportFormat};
pub use closed::{closed_form, Angle, Expr};
pub use emit::{latex, LatexOptions};
pub use kin::{parse_robot, parse_urdf, Chain, Joint, JointKind, Robot};
pub use print::{plain, PlainOptions};
pub use ring::Ring;
pub use scalar::{Context, Frac, Scalar, ScalarError, Sym, Trig};

// Everything else, kept at the top for the callers written before the modules were public;
// its documented home is its module.
#[doc(hidden)]
pub use algebra::dqr;
#[doc(hidden)]
pub use algebra::{DualNumber, UnitConstraints};
#[doc(hidden)]
pub use app::{
    dh_refusal, fk_entries, fk_recurrence, ops_tables, rate_name, robot_toml, task_jacobian,
    task_report, FkEntries, ReportError, TaskJacobian, TaskMatrix,
};
#[doc(hidden)]
pub use closed::{
    closed_form_cos_sin, closed_form_of_derivative, closed_form_prepared, closed_form_traced,
    expanded_form, shorthand_name, Cost, Identity, Prepared, TraceStep, TrigNames,
};
#[doc(hidden)]
pub use emit::{
    arguments, c_function, count_ops, generated_ops, javascript_function, latex_aligned,
    latex_aligned_named, latex_dual_quat, latex_matrix, latex_named, latex_quotient,
    latex_quotient_matrix, latex_symbol, latex_tuple, product_table, python_function,
    rotation_chain_ops, rust_function, sympy, sympy_quotient, CodegenError, CodegenOptions,
    Counted, OpCount, Output,
};
#[doc(hidden)]
pub use kin::dqexp;
#[doc(hidden)]
pub use kin::{
    dh_link, dh_link_matrix, dq_jacobian, geometric_jacobian, mdh_link, mdh_link_matrix,
    screw_parameters, ChainError, Convention, FieldEval, Frame, JointGeometry, RobotError,
    ScrewError, ScrewParams, UrdfError, UrdfOptions, UrdfRobot, SNAP_TOLERANCE,
};
#[doc(hidden)]
pub use print::{legend, plain_named, plain_quotient, plain_quotient_named};
#[doc(hidden)]
pub use scalar::{
    parse_decimal, parse_trig_placeholder, trig_placeholder, Entered,
    DEFAULT_MAX_CYCLOTOMIC_DEGREE, DEFAULT_MAX_EXPONENT,
};
