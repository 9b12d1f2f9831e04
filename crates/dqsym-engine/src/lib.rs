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
//! assert_eq!(plain(&e, &PlainOptions { shorthand: true, decimals: false }), "c12");
//! assert_eq!(plain(&e, &PlainOptions { shorthand: false, decimals: false }), "cos(theta1 + theta2)");
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
#[cfg(test)]
mod testing;

// The core nouns.
pub use algebra::{DualQuat, Matrix4, Quat};
pub use app::{fk_report, FkOptions};
pub use closed::{closed_form, Angle, Expr};
pub use emit::{latex, LatexOptions};
pub use kin::{parse_robot, parse_urdf, Chain, Joint, JointKind, Robot};
pub use print::{plain, Format, PlainOptions};
pub use ring::{Ring, SignedProduct};
pub use scalar::{Context, Frac, Preset, Scalar, ScalarError, Sym, Trig};
