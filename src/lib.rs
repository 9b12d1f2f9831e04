//! dqsym: exact symbolic algebra of dual quaternions for robot kinematics.

mod algebra;
mod ring;

pub use ring::Ring;
