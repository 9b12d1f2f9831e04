//! dqsym: exact symbolic algebra of dual quaternions for robot kinematics.

mod ring;
mod scalar;

pub use ring::Ring;
pub use scalar::{set_term_limit, term_limit, Scalar, ScalarError, Sym};
