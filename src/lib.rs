//! dqsym: exact symbolic algebra of dual quaternions for robot kinematics.

mod algebra;
mod kin;
mod ring;

pub use algebra::{DualNumber, DualQuat, Matrix4, Quat, UnitConstraints};
pub use kin::{
    dh_link, dh_link_matrix, mdh_link, mdh_link_matrix, Chain, ChainError, Joint, JointGeometry,
    JointKind,
};
pub use ring::Ring;
