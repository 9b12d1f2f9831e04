//! dqsym: exact symbolic algebra of dual quaternions for robot kinematics.

mod closed;
mod print;
mod ring;
mod scalar;

pub use closed::{closed_form, Angle, Cost, Expr};
pub use print::{legend, plain, shorthand_name, PlainOptions};
pub use ring::Ring;
pub use scalar::{set_term_limit, term_limit, Scalar, ScalarError, Sym};
