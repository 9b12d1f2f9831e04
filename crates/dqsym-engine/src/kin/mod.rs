//! Kinematics over any [`Ring`](crate::Ring): Denavit–Hartenberg links, joints and serial
//! chains, each both as a dual quaternion and as a 4×4 matrix.
//!
//! The matrix versions are built from the elementary matrices of
//! [`Matrix4`](crate::Matrix4) and never from a dual quaternion, so the two agree only if
//! both are right: tests compare them.

pub mod angles;
mod chain;
mod dh;
pub mod dqexp;
mod field_error;
mod jacobian;
mod joint;
mod robot;
mod screw;
mod urdf;

pub use chain::{Chain, ChainError};
pub use dh::{dh_link, dh_link_matrix, mdh_link, mdh_link_matrix};
pub use jacobian::{dq_jacobian, geometric_jacobian, geometric_jacobian_body};
pub use joint::{local_frame_dq, local_frame_matrix, Joint, JointGeometry, JointKind, LocalFrame};
pub use robot::{
    parse_robot, parse_robot_with, split_top_level, Convention, ExprError, FieldError, FieldEval,
    Frame, Robot, RobotError, RobotOptions,
};
#[cfg(test)]
pub(crate) use robot::{random_test_chain, symbolic_test_chain, LARGEST_FIRST};
pub(crate) use robot::{JointMatrices, MadeJoints, OffsetFree};
pub use screw::{screw_parameters, ScrewError, ScrewParams};
pub use urdf::{parse_urdf, UrdfError, UrdfOptions, UrdfRobot, SNAP_TOLERANCE};
